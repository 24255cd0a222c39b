"""Period skipping with a passivity controller (issue 43) changes no result, bit for bit (paper eq. 4-5).

An unbounded observer's energy E accumulates, so the loop's state with it never repeats; the controller's force
repeats when it is held at its limit (or idle) and E cannot come back over the rest of the run
(:func:`dfa.core.wall_kernel._pc_repeats`). :func:`dfa.core.wall_kernel.run_wall_kernel` with ``skip=True`` is
compared with ``skip=False`` (every sample integrated) and with recorded runs: samples done, rest sample and every
stats entry, bit for bit; the number of samples integrated shows where skipping happened.
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dfa.core import kernel, wall_kernel
from dfa.core.wall_kernel import DEPENDS, HELD, IDLE, PBK, PE
from dfa.model.elements import PassivityController
from dfa.model.wall import WallParams

EMPTY = np.empty(0)


def _pc(limit, window=0, **groups):
    """The wall's groups with a passivity controller (window W samples, 0: unbounded; force limit in KΔ)."""
    return WallParams(((PassivityController, (window, limit)), *WallParams.of(**groups).groups))


def _run(mu, beta, sigma, x0, v0, n, wall, skip, tail_len=None, quantize=True):
    stats = np.empty(kernel.NSTATS)
    run = (n, n // 3 + 1 if tail_len is None else tail_len, 1e6, quantize)
    out = wall_kernel.run_wall_kernel((mu, beta, sigma), (x0, v0), run, wall.kernel_table(), EMPTY, EMPTY, stats, skip)
    return out, stats


def _same_as_every_sample(mu, beta, sigma, x0, v0, n, wall, **kw):
    """Skipping and integrating every sample agree bit for bit, and so does the recorded run; return the samples
    integrated with skipping."""
    (done, rest, integrated), fast = _run(mu, beta, sigma, x0, v0, n, wall, True, **kw)
    (done2, rest2, every), full = _run(mu, beta, sigma, x0, v0, n, wall, False, **kw)
    assert (done, rest) == (done2, rest2) and every == done
    assert fast.tobytes() == full.tobytes()  # ±0 and NaN payloads included
    tail = n // 3 + 1 if kw.get("tail_len") is None else kw["tail_len"]
    rec, rx, rv = np.empty(kernel.NSTATS), np.empty(n + 1), np.empty(n + 1)
    run = (n, tail, 1e6, kw.get("quantize", True))
    assert wall_kernel.simulate_wall_kernel((mu, beta, sigma), (x0, v0), run, wall.kernel_table(), rx, rv, rec) == (
        done,
        rest,
    )
    assert rec.tobytes() == fast.tobytes()
    return integrated


HELD_CASES = [  # (μ, β, σ, ξ'0, wall): chatter with the controller held at its limit (found by a scan)
    (2.0, 2.0, 0.1, 1.0, _pc(1.0, damping=0.5)),
    (100.0, 0.5, 0.3, 2.0, _pc(0.2, damping=0.5)),
    (2.0, 2.0, 0.3, 2.0, _pc(1.0, delay=1)),
    (100.0, 2.0, 0.3, 2.0, _pc(0.2, delay=1)),
    (10.0, 2.0, 0.3, 2.0, _pc(1.0)),
    (100.0, 2.0, 0.3, 2.0, _pc(0.2, damping=0.3, cutoff=0.1, delay=2)),
    (10.0, 2.0, 0.1, 1.0, _pc(1.0, damping=0.3, cutoff=0.1, delay=2)),
]


@pytest.mark.parametrize("mu, beta, sigma, v0, wall", HELD_CASES)
def test_eq4_passivity_controller_held_at_its_limit_skips_to_the_same_result(mu, beta, sigma, v0, wall):
    """The controller's force repeats at ± its limit once E is far enough below: the chatter is skipped, and every
    number is the every-sample one."""
    n = 50_001
    integrated = _same_as_every_sample(mu, beta, sigma, 0.0, v0, n, wall)
    assert integrated < n // 4  # the hook: skipping happened (a count, not a time)


@pytest.mark.parametrize("mu, beta, sigma, v0, wall", HELD_CASES[:3])
def test_eq4_passivity_controller_windowed_observer_is_never_skipped(mu, beta, sigma, v0, wall):
    """A windowed observer's energy is not bounded by the rule: every sample is integrated."""
    others = tuple(g for g in wall.groups if g[0] is not PassivityController)
    windowed = WallParams(((PassivityController, (50, wall.group(PassivityController)[1])), *others))
    assert _same_as_every_sample(mu, beta, sigma, 0.0, v0, 20_001, windowed) == 20_001


@given(
    mu=st.sampled_from([2.0, 10.0, 100.0]) | st.floats(0.5, 300.0),
    beta=st.just(0.0) | st.floats(0.0, 2.0),
    sigma=st.just(0.0) | st.floats(0.0, 1.0),
    x0=st.just(0.0) | st.floats(-3.0, 3.0),
    v0=st.floats(-4.0, 4.0),
    limit=st.none() | st.sampled_from([0.2, 1.0]) | st.floats(0.01, 5.0),
    damping=st.just(0.0) | st.floats(0.0, 2.0),
    cutoff=st.none() | st.floats(0.01, 0.45),
    delay=st.integers(0, 3),
    lag=st.just(0.0) | st.floats(0.01, 1.0),
    n=st.sampled_from([7, 777, 6001]),
    tail_frac=st.sampled_from([0.0, 0.25, 1.0]),
    quantize=st.booleans(),
)
def test_eq4_passivity_controller_skip_is_exact_on_random_controllers(
    mu, beta, sigma, x0, v0, limit, damping, cutoff, delay, lag, n, tail_frac, quantize
):
    wall = _pc(limit, damping=damping, cutoff=cutoff, delay=delay, lag=lag)
    _same_as_every_sample(mu, beta, sigma, x0, v0, n, wall, tail_len=math.ceil(tail_frac * n), quantize=quantize)


def test_eq4_passivity_controller_skip_is_exact_on_a_seeded_sweep():
    """300 seeded random controller walls, many of them chattering with the controller at its limit."""
    rng = np.random.default_rng(43)
    skipped = 0
    for _ in range(300):
        wall = _pc(
            float(rng.choice([0.2, 1.0, rng.uniform(0.05, 3.0)])),
            damping=float(rng.choice([0.0, rng.uniform(0, 1.5)])),
            cutoff=None if rng.integers(2) else float(rng.uniform(0.01, 0.45)),
            delay=int(rng.integers(0, 3)),
        )
        mu = float(rng.choice([2.0, 10.0, 100.0]))
        beta, sigma, v0 = float(rng.uniform(0, 2)), float(rng.uniform(0, 0.6)), float(rng.uniform(0.3, 3))
        n = 12_001
        skipped += _same_as_every_sample(mu, beta, sigma, 0.0, v0, n, wall) < n // 2
    assert skipped >= 30  # the sweep exercises the skip


def _observer(mode, e, terms, vmax=0.0, bookings=(0.0,)):
    """An observer at energy ``e`` after one period of ``terms`` with the modes ``mode`` (bits), and what
    :func:`_pc_track` kept over it (E at its start, E's range, modes, max |v_h|), for :func:`_pc_repeats`."""
    pcs = np.zeros(PBK + len(bookings))
    pcs[PE], pcs[PBK:] = e, bookings
    es = e - np.sum(terms) + np.concatenate(([0.0], np.cumsum(terms)))
    return pcs, (float(es[0]), float(es.min()), float(es.max()), mode, vmax)


def _repeats(observer, limit=1.0, period=2, remaining=10**6):
    pcs, track = observer
    return wall_kernel._pc_repeats(pcs, len(pcs) - PBK - 1, limit, period, remaining, track)


def test_eq4_passivity_controller_held_needs_energy_below_its_reach():
    """HELD: E + (its rise within a period) + bookings + limit·max|v_h| must stay below 0 with the rounding of 10⁶
    more readings."""
    terms = [0.25, -0.75]  # ΔE = −0.5 a period, rising by 0.25 within one
    assert _repeats(_observer(HELD, -100.0, terms, vmax=1.0))
    assert _repeats(_observer(HELD, -1.26, terms, vmax=1.0))
    assert not _repeats(_observer(HELD, -1.25, terms, vmax=1.0))  # exactly at the limit: not with the rounding
    assert not _repeats(_observer(HELD, -1.0, terms, vmax=1.0))  # |L/v_h| could fall below the limit
    assert not _repeats(_observer(HELD, -100.0, [0.75, -0.25], vmax=1.0))  # E rising: it comes back
    assert not _repeats(_observer(HELD, -2.0, terms, vmax=1.0, bookings=(0.0, 1.0)))  # pending bookings count
    assert not _repeats(_observer(HELD, -1e12, terms, vmax=1.0), remaining=2**52)  # E's rounding over 2⁵² terms


def test_eq4_passivity_controller_idle_needs_energy_above_its_reach():
    """IDLE: ΔE >= 0 and E − (its fall within a period) − bookings above 0 with the rounding."""
    terms = [-0.25, 0.75]
    assert _repeats(_observer(IDLE, 1.0, terms))
    assert not _repeats(_observer(IDLE, 0.25, terms))
    assert not _repeats(_observer(IDLE, 100.0, [-0.75, 0.25]))  # E falling: the controller fires some day
    assert not _repeats(_observer(IDLE, 1.0, terms, bookings=(0.0, -2.0)))


def test_eq4_passivity_controller_mixed_or_dependent_modes_never_repeat():
    terms = [-0.75, 0.25]
    assert not _repeats(_observer(DEPENDS, -100.0, terms, vmax=1.0))
    assert not _repeats(_observer(HELD | IDLE, -100.0, terms, vmax=1.0))
    assert not _repeats(_observer(HELD, math.nan, terms, vmax=1.0))
    assert not _repeats(_observer(HELD, -100.0, terms, vmax=1.0), limit=math.inf)  # the textbook controller
    assert _repeats(_observer(0, 5.0, [0.0, 0.0]))  # v_h = 0 throughout: the force is 0 whatever E
