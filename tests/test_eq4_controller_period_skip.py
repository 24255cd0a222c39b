"""The controller kernel's skip of repeated periods (issue 16) changes no result, bit for bit (paper eq. 4-5).

:func:`dfa.core.wall_kernel.run_wall_kernel` with ``skip=True`` (what :func:`~dfa.core.wall_kernel.simulate_wall_kernel` runs
unrecorded) against the same kernel with ``skip=False``, which integrates every sample (one
implementation of the sample; the switch only turns the cycle check off), and against recorded runs
(records switch skipping off). Compared bit for bit: samples done, rest sample, every stats entry
(segment peaks, tail extremes with the turning points, crossings, bound flag, final state, tail
readings' extremes). The number of samples integrated is the hook that shows skipping happened.
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import recorded_period

from dfa.analysis.simulation import simulate, simulate_batch
from dfa.core import kernel, wall_kernel
from dfa.model.wall import WallParams

EMPTY = np.empty(0)


def _run(mu, beta, sigma, x0, v0, n, ctl, *, quantize=True, bound=1e6, tail_len=None, skip=True):
    """(done, rest, samples integrated, stats) of one unrecorded run of the controller kernel."""
    stats = np.empty(kernel.NSTATS)
    tail = n // 4 if tail_len is None else tail_len
    run = (n, tail, bound, quantize)
    done, rest, integrated = wall_kernel.run_wall_kernel(
        (mu, beta, sigma), (x0, v0), run, ctl.kernel_table(), EMPTY, EMPTY, stats, skip
    )
    return done, rest, integrated, stats


def _recorded(mu, beta, sigma, x0, v0, n, ctl, *, quantize=True, bound=1e6, tail_len=None):
    """(done, rest, stats, ξ record, ξ' record) of :func:`dfa.core.wall_kernel.simulate_wall_kernel` with records."""
    stats, rx, rv = np.empty(kernel.NSTATS), np.empty(n + 1), np.empty(n + 1)
    tail = n // 4 if tail_len is None else tail_len
    run = (n, tail, bound, quantize)
    done, rest = wall_kernel.simulate_wall_kernel((mu, beta, sigma), (x0, v0), run, ctl.kernel_table(), rx, rv, stats)
    return done, rest, stats, rx, rv


def _same_as_every_sample(*args, **kw):
    """Skipping and integrating every sample agree bit for bit; return the skipping run's outputs."""
    fast = _run(*args, **kw, skip=True)
    full = _run(*args, **kw, skip=False)
    assert fast[:2] == full[:2]
    assert fast[3].tobytes() == full[3].tobytes()  # bit for bit: ±0 and NaN payloads included
    assert full[2] == full[0]  # without skipping every sample done is integrated
    assert fast[2] <= full[2]
    return fast


def _boundaries(n, tail_len):
    """Samples at which a range of the run starts: the segments' starts and the tail's."""
    return sorted({kernel.segment_bounds(k, n)[0] for k in range(kernel.NSEG)} | {n - tail_len})


CHATTER = [  # (μ, β, σ, ξ'0, controller): runs that settle on an exact cycle after a transient
    (100.0, 0.5, 0.3, 2.0, WallParams.of()),
    (100.0, 0.1, 0.1, 2.0, WallParams.of(damping=0.5)),
    (10.0, 0.5, 0.6, 1.0, WallParams.of(damping=0.5, cutoff=0.1, delay=1)),
    (10.0, 0.5, 0.3, 2.0, WallParams.of(lag=0.2)),
    (100.0, 2.0, 0.1, 2.0, WallParams.of(damping=0.5, cutoff=0.1, delay=1, lag=0.2)),
    (2.0, 2.0, 0.3, 2.0, WallParams.of(delay=3)),
    (100.0, 2.0, 0.3, 1.0, WallParams.of(damping=0.2, cutoff=0.05, delay=2)),
    (10.0, 2.0, 0.3, 2.0, WallParams.of(damping=0.3, delay=2, lag=0.1)),
]


@pytest.mark.parametrize("mu, beta, sigma, v0, ctl", CHATTER)
def test_eq4_controller_chatter_skips_to_the_same_result(mu, beta, sigma, v0, ctl):
    """Chatter on an exact cycle: most samples are skipped, and the result is the every-sample one."""
    n = 50_001
    done, rest, integrated, stats = _same_as_every_sample(mu, beta, sigma, 0.0, v0, n, ctl, tail_len=n // 3 + 1)
    assert rest == -1 and done == n
    assert integrated < n // 4  # the test hook: skipping happened (a count, not a time)
    rec = _recorded(mu, beta, sigma, 0.0, v0, n, ctl, tail_len=n // 3 + 1)
    assert rec[:2] == (done, rest) and rec[2].tobytes() == stats.tobytes()  # records: every sample integrated


@pytest.mark.parametrize("mu, beta, sigma, v0, ctl", CHATTER)
def test_eq4_controller_periods_cross_tail_start_and_segment_boundaries(mu, beta, sigma, v0, ctl):
    """Periods cut by a segment boundary and by the tail's start: each range's peaks and tail still exact."""
    n = 20_003
    tail_len = n // 3 + 1
    _same_as_every_sample(mu, beta, sigma, 0.0, v0, n, ctl, tail_len=tail_len)
    _, _, _, xs, vs = _recorded(mu, beta, sigma, 0.0, v0, n, ctl, tail_len=tail_len)
    start, period = recorded_period(xs, vs)
    assert period >= 2 and np.array_equal(xs[start + period :], xs[start:-period])  # ξ is periodic from start
    cut = [b for b in _boundaries(n, tail_len) if b > start and (b - start) % period]
    assert len(cut) >= 2  # boundaries (segments, tail start) fall inside periods of ξ, not between them


STICK_THEN_SLIP = [  # (μ, β, σ, ξ0, ξ'0, controller): stuck for whole samples, then the device breaks away
    (2.0, 1.7160778623960347, 0.4229591319394351, -1.440842805829135, 0.16263885934249522, 1.3342762280112466, 0.023959929243382735, 0.0),
    (1.0, 1.82621961532622, 0.3150908367056482, 1.7125720048512894, 1.502176715619857, 2.1871859632878716, 0.04647447859240245, 0.0),
    (1.0, 1.1982915611965106, 0.4211516839603168, -0.6431026405202109, 2.686488345800301, 0.0, None, 11.864601300880501),
    (2.0, 1.5771033044919958, 0.21838005244683278, 1.2916755568543596, -2.745009353983316, 0.0, None, 9.476737867463589),
]  # fmt: skip


@pytest.mark.parametrize("mu, beta, sigma, x0, v0, damping, cutoff, lag", STICK_THEN_SLIP)
def test_eq4_controller_stuck_samples_are_no_period(mu, beta, sigma, x0, v0, damping, cutoff, lag):
    """While stuck, (ξ, ξ', r) repeat after one sample but the filtered y or φ_A still moves toward breakaway.

    Only the whole state (module docstring) tells these samples apart; a check on (ξ, ξ', r) alone would
    take them for a period of 1 and skip the breakaway.
    """
    ctl = WallParams.of(damping=damping, cutoff=cutoff, lag=lag)
    _same_as_every_sample(mu, beta, sigma, x0, v0, 3000, ctl, tail_len=750)
    done, rest, _, xs, vs = _recorded(mu, beta, sigma, x0, v0, 3000, ctl, tail_len=750)
    held = (xs[1:] == xs[:-1]) & (vs[1:] == 0.0) & (vs[:-1] == 0.0)  # sample h left (ξ, ξ' = 0) unchanged
    assert rest == -1 and any(held[h - 1] and held[h] and not held[h + 1] for h in range(1, done - 1))


def test_eq4_controller_rest_and_divergence_are_unchanged():
    """A run that rests and one that diverges end where integrating every sample ends them."""
    rest = _same_as_every_sample(100.0, 0.3, 1.5, 0.0, 2.0, 20_000, WallParams.of(damping=0.5, lag=0.3))
    assert rest[1] >= 0 and rest[0] == rest[1]
    grow = _same_as_every_sample(100.0, 0.0, 0.0, 0.0, 2.0, 20_000, WallParams.of(delay=3), bound=50.0)
    assert grow[1] == -1 and grow[0] < 20_000 and grow[3][kernel.NSEG + 5] == 1.0


def test_eq4_controller_without_repetition_integrates_every_sample():
    """The linear loop (no encoder) decaying geometrically never repeats bit for bit: nothing is skipped."""
    ctl = WallParams.of(damping=0.5, cutoff=0.2, delay=1, lag=0.2)
    done, rest, integrated, _ = _same_as_every_sample(100.0, 2.0, 0.0, 0.3, 1.0, 5000, ctl, quantize=False)
    assert done == integrated == 5000 and rest == -1


@given(
    mu=st.sampled_from([1.0, 2.0, 10.0, 100.0]) | st.floats(0.5, 300.0),
    beta=st.just(0.0) | st.floats(0.0, 2.0),
    sigma=st.just(0.0) | st.floats(0.0, 1.5),
    x0=st.just(0.0) | st.floats(-3.0, 3.0),
    v0=st.floats(-5.0, 5.0),
    damping=st.just(0.0) | st.floats(0.0, 3.0),
    cutoff=st.none() | st.floats(0.01, 0.45),
    delay=st.integers(0, 3),
    lag=st.just(0.0) | st.floats(0.01, 1.0) | st.floats(1.0, 20.0),
    quantize=st.booleans(),
    n=st.sampled_from([7, 777, 4001]),
    tail_frac=st.sampled_from([0.0, 0.25, 0.34, 1.0]),
    bound=st.sampled_from([30.0, 1e6]),
)
def test_eq4_controller_skip_is_exact_on_random_controllers(
    mu, beta, sigma, x0, v0, damping, cutoff, delay, lag, quantize, n, tail_frac, bound
):
    ctl = WallParams.of(damping=damping, cutoff=cutoff, delay=delay, lag=lag)
    tail_len = math.ceil(tail_frac * n)
    fast = _same_as_every_sample(mu, beta, sigma, x0, v0, n, ctl, quantize=quantize, bound=bound, tail_len=tail_len)
    rec = _recorded(mu, beta, sigma, x0, v0, n, ctl, quantize=quantize, bound=bound, tail_len=tail_len)
    assert rec[:2] == fast[:2] and rec[2].tobytes() == fast[3].tobytes()


def test_eq4_controller_skip_is_exact_on_a_seeded_sweep():
    """600 seeded random runs (all four controller parts, d = 0 … 3, both spring laws), many chattering."""
    rng = np.random.default_rng(16)
    skipped = 0
    for _ in range(600):
        ctl = WallParams.of(
            damping=float(rng.choice([0.0, rng.uniform(0, 1.5), rng.uniform(1.0, 3.0)])),
            cutoff=None if rng.integers(2) else float(rng.uniform(0.01, 0.45)),
            delay=int(rng.integers(0, 4)),
            lag=float(rng.choice([0.0, 0.0, rng.uniform(0.01, 1.0), rng.uniform(1.0, 20.0)])),
        )
        mu = float(rng.choice([1.0, 2.0, 10.0, 100.0]))
        beta, sigma = (
            float(rng.choice([0.0, rng.uniform(0, 2)])),
            float(rng.choice([0.0, rng.uniform(0, 0.5), rng.uniform(0, 1.5)])),
        )
        n = int(rng.choice([777, 6001, 20001]))
        out = _same_as_every_sample(
            mu, beta, sigma, float(rng.uniform(-3, 3)), float(rng.uniform(-5, 5)), n, ctl,
            quantize=bool(rng.integers(2)), tail_len=int(rng.choice([0, 1, n // 3 + 1, n])),
        )  # fmt: skip
        skipped += out[0] > out[2]
    assert skipped >= 20  # the sweep exercises the skip (24 of the 600 runs skip periods)


def test_eq4_controller_users_numbers_equal_recorded_runs():
    """dfa.simulate and simulate_batch (skipping) report what recorded runs (every sample) report."""
    ctl = WallParams.of(damping=0.5, cutoff=0.1, delay=1, lag=0.2)
    for beta, sigma in [(2.0, 0.1), (0.3, 1.5), (0.0, 0.2)]:
        fast = simulate(2.0, beta, sigma, 2.0, samples=30_000, record=False, wall=ctl).to_dict()
        full = simulate(2.0, beta, sigma, 2.0, samples=30_000, record=True, wall=ctl).to_dict()
        for key in ("xi", "xi_dot", "record"):
            full.pop(key, None)
            fast.pop(key, None)
        assert fast == full
    b = simulate_batch(2.0, [2.0, 0.3, 0.0], [0.1, 1.5, 0.2], 2.0, samples=30_000, wall=ctl)
    for i, (beta, sigma) in enumerate([(2.0, 0.1), (0.3, 1.5), (0.0, 0.2)]):
        r = simulate(2.0, beta, sigma, 2.0, samples=30_000, record=True, wall=ctl)
        assert (r.samples_run, r.outcome.value) == (b.samples_run[i], b.outcomes()[i])
        assert np.array_equal([r.amplitude, r.centre, r.final_xi], [b.amplitude[i], b.centre[i], b.final_xi[i]])


def test_eq4_serial_controller_kernel_equals_single_every_sample_runs():
    """serial_wall_kernel (skipping, the batch entry point) against single runs that integrate every sample."""
    ctl = WallParams.of(damping=0.3, delay=2, lag=0.1)
    mus, betas, sigmas = np.full(4, 2.0), np.array([2.0, 0.5, 0.0, 1.0]), np.array([0.1, 0.3, 0.2, 0.6])
    x0s, v0s = np.zeros(4), np.array([2.0, 1.0, 3.0, 0.5])
    stats, done, rest = np.empty((4, kernel.NSTATS)), np.empty(4, np.int64), np.empty(4, np.int64)
    run = (10_000, 2500, 1e6, True)
    wall_kernel.serial_wall_kernel((mus, betas, sigmas), (x0s, v0s), run, ctl.kernel_table(), stats, done, rest)
    for i in range(4):
        d, r, _, s = _run(mus[i], betas[i], sigmas[i], 0.0, v0s[i], 10_000, ctl, tail_len=2500, skip=False)
        assert (done[i], rest[i]) == (d, r) and stats[i].tobytes() == s.tobytes()
