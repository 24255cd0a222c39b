"""Outcome-only runs (issue 43): the searches' runs stop once their outcome is proven, with the every-sample outcome.

:func:`dfa.core.wall_kernel.outcome_wall_kernel` skips the periods of a loop whose state returns with ξ drifted by
rounding alone (a passivity controller held at its limit while the device chatters below a tick), once the rest of
the run is proven (paper eq. 4-5: ξ' and the forces do not depend on ξ beyond its reading; "Outcome-only runs" in
:mod:`dfa.core.wall_kernel`). Checked here against the every-sample run (``run_wall_kernel(..., skip=False)``): the
outcome of :func:`dfa.core.kernel.classify`, the samples done and the rest sample, on the runs of the slow search
of issue 43 (``dfa stiffness --device phantom --velocity 0.1 --passivity-controller --pc-force-limit 0.38``) and
on the borders of their outcomes (undecided, rest, unstable), on seeded and random walls; the rule
:func:`dfa.core.wall_kernel._robust` on statistics near each threshold; and a whole design search against the same
search with every run integrated in full.
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import dfa
import dfa.core.batch as batch_module
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.simulation import GROWTH, OUTCOMES, SETTLE, STABLE_AMPLITUDE, _tail_length
from dfa.core import kernel, wall_kernel
from dfa.model.elements import PassivityController
from dfa.model.loop import Loop
from dfa.model.wall import Wall, WallParams

RULES = (STABLE_AMPLITUDE, GROWTH, SETTLE)
EMPTY = np.empty(0)


def _pc(limit, window=0, **groups):
    """The wall's groups with a passivity controller (window W samples, 0: unbounded; force limit in KΔ)."""
    return WallParams(((PassivityController, (window, limit)), *WallParams.of(**groups).groups))


def _every_sample(mu, beta, sigma, x0, v0, n, wall, tail, bound):
    stats = np.empty(kernel.NSTATS)
    run = (n, tail, bound, True)
    done, rest, _ = wall_kernel.run_wall_kernel((mu, beta, sigma), (x0, v0), run, wall.kernel_table(), EMPTY, EMPTY,
                                                stats, False)  # fmt: skip
    return kernel.classify(n, done, rest, stats, *RULES, True, mu)[0], done, rest


def _same_outcome(mu, beta, sigma, x0, v0, n, wall, tail=None, bound=1e6):
    """The outcome-only run's outcome, samples done and rest sample are the every-sample run's; return the samples
    it integrated."""
    tail = _tail_length(n, mu) if tail is None else tail
    stats = np.empty(kernel.NSTATS)
    run = (n, tail, bound, True)
    done, rest, integrated = wall_kernel.outcome_wall_kernel((mu, beta, sigma), (x0, v0), run, wall.kernel_table(),
                                                              stats, RULES)  # fmt: skip
    code = kernel.classify(n, done, rest, stats, *RULES, True, mu)[0]
    assert (code, done, rest) == _every_sample(mu, beta, sigma, x0, v0, n, wall, tail, bound)
    return integrated


# (μ, β, σ, ξ0, ξ'0, n, outcome): runs of the search of issue 43 (its controller's limit 0.38 N is 10 σ, as the
# Phantom's c is 0.038 N), each outcome and its borders (undecided at 5·10⁴ samples, and extended to 2·10⁵, 8·10⁵)
SEARCH_RUNS = [
    (13.879126865252152, 0.0009638282545313996, 0.3644325738526685, 15.43759500149229, 0.0, 200_000, "chatter"),
    (26.905818059244385, 0.0018684595874475269, 0.7064822320697116, 8.588033406156287, 0.0, 50000, "chatter"),
    (19.8698023820806, 0.0013798473876444862, 0.5217333406018952, 0.0, 2.4875621890547266, 1_000_000, "chatter"),
    (224.602597402822, 0.015597402597418195, 5.897525360217824, 12.417036250555459, 0.0, 50000, "rest"),
    (66.80426052952073, 0.004639184758994496, 1.7541196103660779, 0.0, 4.975124378109453, 1_000_000, "rest"),
    (8.002682516471479, 0.0005557418414216305, 0.21013124352260654, 11.719845951097103, 0.0, 1_000_000, "unstable"),
    (34.627788003886664, 0.002404707500269907, 0.9092426369179748, 0.0, 1.658374792703151, 200_000, "undecided"),
    (14.844373260535864, 0.0010308592542038794, 0.38977762845519814, 0.0, 0.8291873963515755, 50000, "undecided"),
    (13.5265384553172, 0.0009393429482859167, 0.35517444810810783, 0.0, 0.8291873963515755, 800_000, "undecided"),
    (12.845647724843664, 0.0008920588697808099, 0.3372958910614008, 2.966409484479711, 0.0, 800_000, "undecided"),
    (14.300981512549306, 0.0009932, 0.37549, 15.67166806084978, 0.0, 100_000, "undecided"),  # held, no period
]  # fmt: skip


@pytest.mark.parametrize("mu, beta, sigma, x0, v0, n, outcome", SEARCH_RUNS)
def test_eq4_outcome_only_runs_of_the_slow_search_keep_their_outcome(mu, beta, sigma, x0, v0, n, outcome):
    wall = _pc(10.0 * sigma)
    _same_outcome(mu, beta, sigma, x0, v0, n, wall)
    tail = _tail_length(n, mu)
    assert OUTCOMES[_every_sample(mu, beta, sigma, x0, v0, n, wall, tail, 1e6)[0]] == outcome


def test_eq4_outcome_only_held_chatter_stops_early():
    """The controller held at its limit, the device chattering below a tick: ξ' returns bit for bit every 4 samples
    while ξ drifts by an ulp; the rest of the run is proven after a few hundred samples (the hook: a count)."""
    mu, beta, sigma, x0, v0, n, _ = SEARCH_RUNS[0]
    assert _exact_skip_integrates(mu, beta, sigma, x0, v0, n, _pc(10.0 * sigma)) == n
    assert _same_outcome(mu, beta, sigma, x0, v0, n, _pc(10.0 * sigma)) < 2000
    assert _same_outcome(mu, beta, sigma, x0, v0, 1_000_001, _pc(10.0 * sigma)) < 2000


def test_eq4_outcome_only_run_is_exact_where_the_state_returns_bit_for_bit():
    """A loop whose whole state returns (no drift) skips as run_wall_kernel does, and a record-free spring-only
    wall's outcome is the every-sample one."""
    wall = WallParams.of(damping=0.5, cutoff=0.1, delay=1)
    _same_outcome(2.0, 2.0, 0.1, 0.0, 2.0, 50_001, wall)
    _same_outcome(100.0, 0.3, 0.3, 0.0, 1.0, 50_001, _pc(0.2, damping=0.5))


def _exact_skip_integrates(mu, beta, sigma, x0, v0, n, wall):
    """Samples run_wall_kernel integrates with the exact skip alone."""
    run = (n, _tail_length(n, mu), 1e6, True)
    stats = np.empty(kernel.NSTATS)
    return wall_kernel.run_wall_kernel((mu, beta, sigma), (x0, v0), run, wall.kernel_table(), EMPTY, EMPTY, stats,
                                       True)[2]  # fmt: skip


def test_eq4_outcome_only_runs_on_a_seeded_sweep():
    """300 seeded random walls with a controller (damper, filter, delay, lag), many chattering at its limit: every
    outcome is the every-sample one, and the approximate return proves the rest of many runs (the hook: runs that
    integrate fewer samples than with the exact skip alone)."""
    rng = np.random.default_rng(4343)
    proven = 0
    for _ in range(300):
        wall = _pc(
            float(rng.choice([0.2, 1.0, 3.6, rng.uniform(0.05, 6.0)])),
            damping=float(rng.choice([0.0, rng.uniform(0, 1.5)])),
            cutoff=None if rng.integers(2) else float(rng.uniform(0.01, 0.45)),
            delay=int(rng.integers(0, 3)),
            lag=float(rng.choice([0.0, 0.0, rng.uniform(0.05, 0.5)])),
        )
        mu = float(rng.choice([2.0, 13.9, 100.0, rng.uniform(1.0, 300.0)]))
        beta, sigma = float(rng.choice([0.001, rng.uniform(0, 2)])), float(rng.uniform(0.1, 0.9))
        x0, v0 = (float(rng.uniform(-20, 20)), 0.0) if rng.integers(2) else (0.0, float(rng.uniform(0.3, 5)))
        n = int(rng.choice([12_001, 50_000]))
        integrated = _same_outcome(mu, beta, sigma, x0, v0, n, wall)
        proven += integrated < _exact_skip_integrates(mu, beta, sigma, x0, v0, n, wall)
    assert proven >= 20


@given(
    mu=st.sampled_from([2.0, 13.9, 70.0]) | st.floats(0.5, 300.0),
    beta=st.just(0.001) | st.floats(0.0, 2.0),
    sigma=st.floats(0.0, 1.0),
    x0=st.just(0.0) | st.floats(-20.0, 20.0),
    v0=st.floats(-5.0, 5.0),
    limit=st.sampled_from([0.2, 1.0, 3.6]) | st.floats(0.01, 10.0),
    damping=st.just(0.0) | st.floats(0.0, 2.0),
    cutoff=st.none() | st.floats(0.01, 0.45),
    delay=st.integers(0, 3),
    n=st.sampled_from([777, 6001, 20_000]),
    tail_frac=st.sampled_from([0.05, 0.25, 1.0]),
    bound=st.sampled_from([1e6, 30.0]),
)
def test_eq4_outcome_only_runs_keep_the_outcome_on_random_walls(
    mu, beta, sigma, x0, v0, limit, damping, cutoff, delay, n, tail_frac, bound
):
    wall = _pc(limit, damping=damping, cutoff=cutoff, delay=delay)
    _same_outcome(mu, beta, sigma, x0, v0, n, wall, tail=max(2, math.ceil(tail_frac * n)), bound=bound)


CHATTER_TAIL = np.tile([-0.1, 0.05, 0.1, -0.05], 50)


def _robust(peaks, tmin, tmax, err, tail=CHATTER_TAIL, n=400_000, mu=14.0):
    """:func:`_robust` on stats with these segment peaks and tail (its crossings counted as the kernel does)."""
    tail = np.asarray(tail, float)
    stats = np.zeros(kernel.NSTATS)
    stats[: kernel.NSEG] = peaks
    kernel.tail_stats(tail, tail.size, tmin, tmax, stats)
    return wall_kernel._robust(n, n, -1, stats, tail, tail.size, RULES, mu, err)


def test_eq4_outcome_only_robust_rule_decides_each_threshold_with_its_margin():
    """Chatter below one tick, a settled envelope, two crossings of the centre: decided when each holds with the
    margin, not when the margin reaches a threshold (the run is then integrated in full)."""
    chatter = ([16.0] + [0.12] * 7, -0.1, 0.12)
    assert _robust(*chatter, 1e-9)
    assert not _robust(*chatter, 0.03)  # the crossings of the centre (0.01) are no longer certain
    assert not _robust(*chatter, math.nan)
    assert not _robust([16.0] + [0.9999] * 7, -0.9999, 0.9999, 1e-3, tail=np.tile([-0.99, 0.99], 50))
    assert _robust([16.0] + [1.5] * 7, -1.5, 1.5, 1e-6, tail=np.tile([-1.4, 1.4], 50))  # oscillating
    assert not _robust(
        [16.0] + [1.5] * 7, -1.5, 1.5, 1e-3, tail=np.tile([-1.4, 1.4], 50)
    )  # settled within 2e-3: not certain
    unsettled = ([16.0] + [0.12] * 5 + [0.1201, 0.12], -0.1, 0.12)  # spread 1e-4 < 1e-3 of 0.12
    assert not _robust(*unsettled, 1e-4)
    assert _robust(*unsettled, 1e-9)
    assert _robust([16.0] + [0.12] * 5 + [0.13, 0.12], -0.1, 0.12, 1e-6)  # certainly undecided
    growing = ([1.0, 1.0, 1.0, 1.0, 2.0, 2.2, 2.4, 2.6], -2.6, 2.6)
    assert _robust(*growing, 1e-6, tail=np.tile([-2.5, 2.5], 50))  # certainly unstable
    border = [1.0, 1.0, 1.0, 1.0, 2.0, 2.2, 2.4, 2.5]  # P_7 = 1.25 P_4: growth or not within the margin
    assert not _robust(border, -2.5, 2.5, 0.01, tail=np.tile([-2.5, 2.5], 50))


def test_eq11_controller_search_with_outcome_only_runs_is_the_every_sample_search(monkeypatch):
    """A whole design search of the Phantom with the controller of issue 43 (a coarse one): the same answer, to the
    last number, as the search whose every run is integrated in full."""
    dev = dfa.get_device("Phantom").device
    wall = Wall(1015.0, (PassivityController(force_limit=0.38),))
    fast = design_answer(Loop(dev, wall), 0.1, speeds=2, grid=6, max_samples=200_000).to_dict()

    def every_sample(devices, initials, runs, tables, rules, stats, done, rest):
        batch_module.batch_wall_kernel(devices, initials, runs, tables, stats, done, rest)

    monkeypatch.setattr(batch_module, "batch_wall_outcomes", every_sample)
    assert design_answer(Loop(dev, wall), 0.1, speeds=2, grid=6, max_samples=200_000).to_dict() == fast
