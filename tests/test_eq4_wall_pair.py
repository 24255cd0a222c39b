"""Two outcome-only wall runs in flight (issue 43): :func:`dfa.core.wall_pair.pair_wall_outcomes`, what the searches
run, gives every run the outcome of :func:`dfa.core.wall_kernel.outcome_wall_kernel` alone, the every-sample run's
(paper eq. 4-5 with the wall's command).

Each lane runs :func:`dfa.core.wall_kernel._advance`'s loop on its own run; only where a period is skipped may change.
Checked here: the outcome, the samples done and the rest sample of runs in batches against each run alone (and
against the every-sample run), on the runs of the slow search of issue 43, on seeded batches that mix the walls the
lanes take with those they leave to the kernel alone, and on random batches (hypothesis); a chatter that integrates
every sample gives the single run's statistics bit for bit; and which walls the lanes take.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_eq4_outcome_only_runs import RULES, SEARCH_RUNS, _every_sample, _pc

from dfa.analysis.simulation import _tail_length
from dfa.core import kernel, wall_kernel
from dfa.core.table import FILTER, HAND, ONE_SIDED, stack_tables
from dfa.core.wall_pair import LANE_CODES, pair_wall_outcomes, pairable
from dfa.model.elements import OneSided, Push
from dfa.model.wall import WallParams


def _runs(cases):
    """Arrays of the batch kernels for ``cases`` = [(μ, β, σ, ξ0, ξ'0, n, wall, bound)], simulate()'s tails."""
    mu, beta, sigma, x0, v0 = (np.array([c[j] for c in cases], dtype=float) for j in range(5))
    ns = np.array([c[5] for c in cases], dtype=np.int64)
    tails = np.array([_tail_length(int(n), float(m)) for n, m in zip(ns, mu, strict=True)], dtype=np.int64)
    bounds = np.array([c[7] for c in cases], dtype=float)
    tables = stack_tables([c[6].kernel_table() for c in cases]) if cases else np.zeros((0, 1))
    return (mu, beta, sigma), (x0, v0), (ns, tails, bounds, True), tables


def _codes(devices, runs, stats, done, rest):
    k = done.size
    out = (np.empty(k, np.int64), np.empty(k), np.empty(k), np.empty(k), np.empty(k))
    kernel.classify_batch(devices[0], runs[0], done, rest, stats, RULES, True, out)
    return out[0]


def _paired_and_alone(cases):
    """(codes, done, rest, stats) of the batch in flight two at a time, then of each run alone."""
    devices, starts, runs, tables = _runs(cases)
    k = len(cases)
    results = []
    for paired in (True, False):
        stats, done, rest = np.empty((k, kernel.NSTATS)), np.empty(k, np.int64), np.empty(k, np.int64)
        if paired:
            pair_wall_outcomes(devices, starts, runs, tables, RULES, stats, done, rest)
        for i in range(k) if not paired else ():
            run = (runs[0][i], runs[1][i], runs[2][i], True)
            device, start = (devices[0][i], devices[1][i], devices[2][i]), (starts[0][i], starts[1][i])
            done[i], rest[i], _ = wall_kernel.outcome_wall_kernel(device, start, run, tables[i], stats[i], RULES)
        results.append((_codes(devices, runs, stats, done, rest), done, rest, stats))
    return results


def _assert_same_outcomes(cases):
    (codes, done, rest, stats), (codes1, done1, rest1, stats1) = _paired_and_alone(cases)
    assert codes.tolist() == codes1.tolist()
    assert done.tolist() == done1.tolist()
    assert rest.tolist() == rest1.tolist()
    return stats, stats1


def _pairs(wall):
    return pairable(wall.kernel_table(), True)


def test_eq4_wall_pair_takes_the_walls_of_its_lanes_alone():
    """The encoder, no delay, filter, lag or hand, bilateral, an unbounded observer: in a lane; a damper, the force
    limit, the travel and a push may be there; every other wall runs alone."""
    assert _pairs(WallParams.of()) and _pairs(_pc(3.6)) and _pairs(_pc(3.6, damping=0.5, force_limit=20.0))
    assert _pairs(WallParams(((Push, 0.3), *WallParams.of(travel=50.0).groups)))
    for wall in (_pc(3.6, delay=1), _pc(3.6, cutoff=0.1), _pc(3.6, lag=0.2), _pc(3.6, window=8),
                 WallParams.of(hand_stiffness=0.1), WallParams(((OneSided, 0.0),))):  # fmt: skip
        assert not _pairs(wall)
    assert not pairable(_pc(3.6).kernel_table(), False)  # without the encoder
    assert pairable(np.array([0.0]), True)  # the paper's spring
    # a block the lanes do not list runs alone, even where it would change nothing (a hand of stiffness 0)
    assert not pairable(np.array([1.0, HAND, 1.0, 0.0, 0.0]), True)
    assert HAND not in LANE_CODES and ONE_SIDED not in LANE_CODES and FILTER not in LANE_CODES


def test_eq4_wall_pair_keeps_the_outcomes_of_the_slow_search():
    """The runs of issue 43's search (chatter held at the limit, rest, unstable, undecided), in one batch: each run's
    outcome is its own alone, and the every-sample run's."""
    cases = [(mu, beta, sigma, x0, v0, n, _pc(10.0 * sigma), 1e6) for mu, beta, sigma, x0, v0, n, _ in SEARCH_RUNS]
    _assert_same_outcomes(cases)
    codes = _paired_and_alone(cases)[0][0]
    for (mu, beta, sigma, x0, v0, n, wall, bound), code in zip(cases, codes, strict=True):
        assert code == _every_sample(mu, beta, sigma, x0, v0, n, wall, _tail_length(n, mu), bound)[0]


def test_eq4_wall_pair_chatter_is_the_single_run_bit_for_bit():
    """Four runs of the search that never return (each alone integrates every sample: the hook) in flight two at a
    time: every statistic equals the single run's exactly (the lanes run _advance's operations in its order)."""
    cases = [(*SEARCH_RUNS[i][:5], 60_000, _pc(10.0 * SEARCH_RUNS[i][2]), 1e6) for i in (6, 8, 9, 10)]
    for mu, beta, sigma, x0, v0, n, wall, bound in cases:
        run = (n, _tail_length(n, mu), bound, True)
        stats = np.empty(kernel.NSTATS)
        assert (
            wall_kernel.outcome_wall_kernel((mu, beta, sigma), (x0, v0), run, wall.kernel_table(), stats, RULES)[2] == n
        )
    stats, stats1 = _assert_same_outcomes(cases)
    np.testing.assert_array_equal(stats, stats1)


def _seeded_case(rng):
    """A random run: a wall the lanes take or not, a start, a length and a bound (some runs diverge or end stop)."""
    groups = {
        "damping": float(rng.choice([0.0, rng.uniform(0, 1.5)])),
        "delay": int(rng.choice([0, 0, 0, 1])),
        "cutoff": None if rng.integers(4) else float(rng.uniform(0.01, 0.45)),
        "force_limit": None if rng.integers(3) else float(rng.uniform(0.5, 20.0)),
        "travel": None if rng.integers(3) else float(rng.uniform(5.0, 60.0)),
    }
    wall = _pc(float(rng.choice([0.2, 1.0, 3.6, rng.uniform(0.05, 6.0)])), **groups) if rng.integers(4) else None
    wall = WallParams.of(**groups) if wall is None else wall
    if rng.integers(5) == 0:
        wall = WallParams(((Push, float(rng.uniform(0.0, 0.5))), *wall.groups))
    mu = float(rng.choice([2.0, 13.9, 100.0, rng.uniform(1.0, 300.0)]))
    beta, sigma = float(rng.choice([0.001, rng.uniform(0, 2)])), float(rng.uniform(0.0, 0.9))
    x0, v0 = (float(rng.uniform(-20, 20)), 0.0) if rng.integers(2) else (0.0, float(rng.uniform(0.3, 5)))
    return mu, beta, sigma, x0, v0, int(rng.choice([777, 12_001, 30_000])), wall, float(rng.choice([1e6, 30.0]))


def test_eq4_wall_pair_seeded_batches_keep_every_outcome():
    """240 seeded runs in batches of 1 to 17, the walls the lanes take mixed with the others (delay, filter): each
    outcome, samples done and rest sample is the run's alone (the hook: most runs run in a lane)."""
    rng = np.random.default_rng(4344)
    cases = [_seeded_case(rng) for _ in range(240)]
    assert sum(_pairs(c[6]) for c in cases) >= 120
    i = 0
    while i < len(cases):
        size = int(rng.integers(1, 18))
        _assert_same_outcomes(cases[i : i + size])
        i += size


def test_eq4_wall_pair_empty_and_single_batches():
    """No run, and one run alone in a lane, as the kernel alone."""
    assert _paired_and_alone([])[0][0].size == 0
    mu, beta, sigma, x0, v0, n, _ = SEARCH_RUNS[3]
    _assert_same_outcomes([(mu, beta, sigma, x0, v0, n, _pc(10.0 * sigma), 1e6)])


@settings(max_examples=25, deadline=None)
@given(
    batch=st.lists(
        st.tuples(
            st.sampled_from([2.0, 13.9, 70.0]) | st.floats(0.5, 300.0),
            st.just(0.001) | st.floats(0.0, 2.0),
            st.floats(0.0, 1.0),
            st.just(0.0) | st.floats(-20.0, 20.0),
            st.floats(-5.0, 5.0),
            st.sampled_from([0.2, 1.0, 3.6]) | st.floats(0.01, 10.0),
            st.just(0.0) | st.floats(0.0, 2.0),
            st.booleans(),
            st.sampled_from([777, 6001]),
        ),
        min_size=1,
        max_size=6,
    )
)
def test_eq4_wall_pair_random_batches_keep_every_outcome(batch):
    cases = [
        (mu, beta, sigma, x0, v0, n, _pc(limit, damping=damping) if pc else WallParams.of(damping=damping), 1e6)
        for mu, beta, sigma, x0, v0, limit, damping, pc, n in batch
    ]
    _assert_same_outcomes(cases)


@pytest.mark.parametrize("bound", [3.0, math.inf])
def test_eq4_wall_pair_ends_as_the_kernel_alone(bound):
    """Runs that pass the bound, come to rest or reach the end stop in a lane end where they end alone."""
    cases = [
        (2.0, 0.0, 0.0, 0.0, 3.0, 5000, WallParams.of(travel=4.0), bound),
        (2.0, 0.5, 0.6, 5.2, 0.0, 5000, _pc(1.0), bound),
        (0.3, 0.0, 0.0, 0.0, 2.0, 5000, WallParams.of(), bound),
        (13.9, 0.001, 0.36, 0.0, 2.5, 5000, _pc(3.6), bound),
    ]
    _assert_same_outcomes(cases)


def test_eq4_wall_pair_lanes_walk_the_ranges_of_the_spring_lanes():
    """The lanes take their next range with dfa.core.pair's walk, on the same first columns of their state."""
    from dfa.core import pair, wall_pair

    spring = (pair.PT, pair.SEG, pair.PART, pair.H, pair.END, pair.N, pair.TAIL)
    assert spring == (wall_pair.PT, wall_pair.SEG, wall_pair.PART, wall_pair.H, wall_pair.END, wall_pair.N,
                      wall_pair.TAIL)  # fmt: skip
