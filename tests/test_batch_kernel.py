"""Batched runs (issue 16) equal single runs of the exact simulator (paper eq. 4-5), bit for bit.

The grids mix rest, chatter, oscillation, divergence, delay, β = 0 and σ = 0.
"""

import re
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dfa import DFAValueError
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import OUTCOMES, simulate, simulate_batch
from dfa.model.wall import WallParams


def _grid(seed: int, size: int):
    rng = np.random.default_rng(seed)
    mu = 10 ** rng.uniform(0, 2.5, size)
    beta = np.where(rng.random(size) < 0.25, 0.0, rng.uniform(0, 1.2, size))
    sigma = np.where(rng.random(size) < 0.25, 0.0, rng.uniform(0, 2, size))
    v0 = rng.uniform(-4, 4, size)
    x0 = np.where(rng.random(size) < 0.5, 0.0, rng.uniform(-2, 2, size))
    return mu, beta, sigma, v0, x0


def _same(r, b, i) -> bool:
    freq = np.nan if r.frequency is None else r.frequency
    return (
        OUTCOMES.index(r.outcome) == b.outcome[i]
        and r.samples_run == b.samples_run[i]
        and (r.rest_sample if r.rest_sample is not None else -1) == b.rest_sample[i]
        and np.array_equal([r.final_xi, r.final_xi_dot], [b.final_xi[i], b.final_xi_dot[i]], equal_nan=True)
        and np.array_equal(r.envelope, b.envelope[i], equal_nan=True)
        and np.array_equal(
            [r.amplitude, freq, r.centre, r.force_peak_to_peak],
            [b.amplitude[i], b.frequency[i], b.centre[i], b.force_peak_to_peak[i]],
            equal_nan=True,
        )
    )


@pytest.mark.parametrize("delay, quantize", [(0, True), (0, False), (2, True)])
def test_eq4_batched_runs_equal_single_runs(delay, quantize):
    mu, beta, sigma, v0, x0 = _grid(7 + delay, 60)
    wall = WallParams.of(delay=delay)
    b = simulate_batch(mu, beta, sigma, v0, 4000, x0, quantize, bound=1e4, wall=wall)
    for i in range(len(b)):
        r = simulate(mu[i], beta[i], sigma[i], v0[i], 4000, x0[i], quantize, record=False, bound=1e4, wall=wall)
        assert _same(r, b, i), i
    seen = Counter(b.outcomes())
    assert seen["rest"] and seen["unstable"] and (seen["chatter"] or not quantize or delay)


def test_eq4_batch_covers_every_outcome_class():
    """A hand-picked batch with one run per class (rest, oscillating, unstable, chatter, undecided)."""
    cases = [(100.0, 0.3, 1.5, 2.0), (2.0, 0.4, 0.1, 2.0), (100.0, 0.0, 0.2, 2.0), (100.0, 0.3, 0.3, 1.0)]
    mu, beta, sigma, v0 = (np.array(c) for c in zip(*cases, strict=True))
    b = simulate_batch(mu, beta, sigma, v0, 20000)
    for i in range(len(b)):
        assert _same(simulate(mu[i], beta[i], sigma[i], v0[i], 20000, record=False), b, i)
    assert b.outcomes() == ["rest", "oscillating", "unstable", "chatter"]
    short = simulate_batch(156250.0, 0.125, 0.9554, 0.637, 50_000)
    assert short.outcomes() == ["undecided"]
    d = short.to_dict()
    assert d["outcome"] == ["undecided"] and d["rest_sample"] == [None]
    with pytest.raises(ValueError):
        short.amplitude[0] = 1.0  # read-only arrays


def test_eq4_batch_rejects_bad_runs_naming_them():
    with pytest.raises(DFAValueError, match="mu"):
        simulate_batch([1.0, -1.0], 0.1, 0.1, 1.0, 100)
    with pytest.raises(DFAValueError, match="xi_dot0"):
        simulate_batch(1.0, 0.1, 0.1, [1.0, np.nan], 100)
    with pytest.raises(DFAValueError, match="broadcast"):
        simulate_batch([1.0, 2.0], [0.1, 0.2, 0.3], 0.1, 1.0, 100)
    with pytest.raises(DFAValueError, match="bound"):
        simulate_batch(1.0, 0.1, 0.1, 1.0, 100, xi0=[0.0, 5.0], bound=2.0)


def test_fig4_map_same_for_threads_and_processes():
    kw = dict(grid=6, samples=3000, progress=False, wall=WallParams.of(delay=1))
    a = stability_map(30.0, [1.0, 4.0], n_jobs=1, **kw)
    for jobs, backend in ((2, "threads"), (2, "processes")):
        b = stability_map(30.0, [1.0, 4.0], n_jobs=jobs, backend=backend, **kw)
        for f in ("outcome", "amplitude", "frequency"):
            np.testing.assert_array_equal(getattr(a, f), getattr(b, f))
    with pytest.raises(DFAValueError, match="backend"):
        stability_map(30.0, [1.0], grid=2, samples=10, progress=False, backend="gpu")


def test_eq4_plain_benchmark_kernel_agrees_with_simulate():
    """benchmarks/plain_kernel.py (the speed baseline) is the same model: same rest sample, same state to rounding."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from plain_kernel import plain_kernel

    cases = [(100.0, 0.3, 1.5, 2.0, 0), (5.0, 1.8, 0.8, 1.5, 1), (30.0, 2.8, 1.2, 1.0, 2), (10.0, 0.0, 1.0, 1.0, 0)]
    for mu, beta, sigma, v0, delay in cases:
        r = simulate(mu, beta, sigma, v0, 20000, record=False, wall=WallParams.of(delay=delay))
        done, x, v = plain_kernel(mu, beta, sigma, 0.0, v0, 20000, delay, True, 1e6)
        assert r.outcome == "rest" and done == r.rest_sample
        assert x == pytest.approx(r.final_xi, rel=1e-12) and v == r.final_xi_dot == 0.0
    for mu, beta, sigma, v0, delay in [(5.0, 0.2, 0.6, 1.5, 1), (30.0, 0.0, 0.7, 1.0, 2)]:  # past the bound
        r = simulate(mu, beta, sigma, v0, 20000, record=False, wall=WallParams.of(delay=delay))
        done, x, v = plain_kernel(mu, beta, sigma, 0.0, v0, 20000, delay, True, 1e6)
        assert r.outcome == "unstable" and done == r.samples_run and x == pytest.approx(r.final_xi, rel=1e-12)


def _kernels_agree(pts, n, delay, tail_len, bound=1e4):
    """dfa.core.batch.batch_kernel (two runs in flight, dfa.core.pair) against dfa.core.kernel.serial_kernel (one run after
    the other): every output, bit for bit."""
    from dfa.core import batch, kernel

    k = pts[0].size
    ref = (np.zeros((k, kernel.NSTATS)), np.zeros(k, np.int64), np.zeros(k, np.int64))
    devices, initials = pts[:3], pts[3:]
    kernel.serial_kernel(devices, initials, (n, tail_len, bound, True), delay, *ref)
    runs = (np.full(k, n, np.int64), np.full(k, tail_len, np.int64), np.full(k, bound), True)
    got = (np.full((k, kernel.NSTATS), 7.0), np.full(k, 7, np.int64), np.full(k, 7, np.int64))
    batch.batch_kernel(devices, initials, runs, delay, *got)
    assert np.array_equal(ref[0].view(np.int64), got[0].view(np.int64))  # bits: ±0 and NaN payloads too
    assert np.array_equal(ref[1], got[1]) and np.array_equal(ref[2], got[2])
    return ref


def test_eq4_batch_runs_each_with_its_own_length_bound_and_tail():
    """Runs of different lengths, bounds and tails in one batch (two in flight): each equals simulate_kernel alone."""
    from dfa.core import batch, kernel

    run_batch = batch.batch_kernel

    mu, beta, sigma, v0, x0 = _grid(11, 40)
    rng = np.random.default_rng(11)
    ns = rng.integers(1, 8000, mu.size)
    bounds = np.where(rng.random(mu.size) < 0.3, 50.0, 1e5)
    tails = (rng.random(mu.size) * ns).astype(np.int64)
    for delay in (0, 1):
        st, dn, rs = np.zeros((mu.size, kernel.NSTATS)), np.zeros(mu.size, np.int64), np.zeros(mu.size, np.int64)
        run_batch((mu, beta, sigma), (x0, v0), (ns, tails, bounds, True), delay, st, dn, rs)
        for i in range(mu.size):
            one = np.empty(kernel.NSTATS)
            e = np.empty(0)
            args = ((mu[i], beta[i], sigma[i]), (x0[i], v0[i]), (ns[i], tails[i], bounds[i], True), delay)
            d, r = kernel.simulate_kernel(*args, e, e, np.empty((0, 4)), one)
            assert (d, r) == (dn[i], rs[i]) and np.array_equal(one.view(np.int64), st[i].view(np.int64)), i
        assert (st[:, 8 + 5] > 0).any() and (rs >= 0).any()  # some runs pass their bound, some rest


@pytest.mark.parametrize("size", [0, 1, 2, 3, 61])
@pytest.mark.parametrize("seed", [1, 2])
def test_eq4_two_runs_in_flight_equal_serial_kernel_bit_for_bit(size, seed):
    """Lanes drop out and refill (odd sizes, a single run, none); every tail length from none to the whole run."""
    mu, beta, sigma, v0, x0 = _grid(seed, size)
    for n in (1, 7, 3000):
        for tail_len in {0, 1, n // 3, n}:
            ref = _kernels_agree((mu, beta, sigma, x0, v0), n, 0, tail_len)
    if size > 20:  # the grid reaches rest, the bound and full-length runs
        assert (ref[2] >= 0).any() and (ref[0][:, 8 + 5] > 0).any() and (ref[1] == 3000).any()


@given(st.integers(0, 2**32 - 1), st.integers(1, 9), st.integers(1, 6000), st.floats(0.0, 1.0))
def test_eq4_two_runs_in_flight_property(seed, size, n, tail_frac):
    """Random grids (rest, chatter, oscillation, divergence, β = 0, σ = 0): identical to one run at a time."""
    mu, beta, sigma, v0, x0 = _grid(seed, size)
    _kernels_agree((mu, beta, sigma, x0, v0), n, 0, int(tail_frac * n))


def test_eq4_two_runs_in_flight_skip_repeated_periods_alike():
    """A repeating chatter run (its periods skipped) beside a never-repeating one, both orders, both lengths."""
    rep, steady = (100.0, 0.3, 0.3, 0.0, 1.0), (20.0, 0.47, 0.02, 0.0, 3.0)
    for pair in ((rep, steady), (steady, rep), (rep, rep)):
        pts = tuple(np.array(c) for c in zip(*pair, strict=True))
        for n in (20_000, 50_001):
            _kernels_agree(pts, n, 0, n // 4, bound=1e6)


def test_eq4_two_runs_in_flight_hand_delay_to_serial_kernel():
    mu, beta, sigma, v0, x0 = _grid(5, 9)
    _kernels_agree((mu, beta, sigma, x0, v0), 2000, 2, 500)


@pytest.mark.parametrize("delay", [0, 1])
def test_eq4_design_searches_batch_equals_simulate_per_point(delay):
    """dfa.analysis.limits.runs.simulate_points (the K_max searches) batches its spring runs: outcomes and lengths are simulate()'s."""
    from dfa.analysis.limits.runs import DIVERGENCE_BOUND, simulate_points
    from dfa.analysis.simulation import default_samples, divergence_bound, preload_position

    mu, beta, sigma, v0, _ = _grid(21 + delay, 30)
    v0 = np.abs(v0) + 0.1
    pts = [(m, b, s, 0.0, v) for m, b, s, v in zip(mu, beta, sigma, v0, strict=True)]
    pts += [(m, b, s, preload_position(m, v), 0.0) for m, b, s, v in zip(mu, beta, sigma, v0, strict=True)]
    wall = WallParams.of(delay=delay)
    outs, lengths = simulate_points(pts, [wall] * len(pts), 40_000)
    for (m, b, s, x0, v), o, n in zip(pts, outs, lengths, strict=True):
        assert n == min(default_samples(m, b, s, v, x0, wall=wall), 40_000)
        bound = divergence_bound(x0, v, m, DIVERGENCE_BOUND)
        assert o == simulate(m, b, s, v, n, xi0=x0, record=False, bound=bound, wall=wall).outcome
    assert {"rest", "unstable"} <= set(outs)  # not one trivial class


@pytest.mark.parametrize(
    ("bad", "named"),
    [((-1.0, 0.1, 0.5, 0.0, 1.0), "mu"), ((1e-320, 0.1, 0.5, 0.0, 1.0), "1/μ overflows"),
     ((100.0, -0.1, 0.5, 0.0, 1.0), "beta"),
     ((100.0, 0.1, 0.5, 0.0, float("nan")), "nan"), ((100.0, 1e308, 0.5, 0.0, 1.0), "β/μ = bT/m")],
)  # fmt: skip
def test_eq4_design_searches_refuse_a_point_simulate_refuses(bad, named):
    """simulate_points checks its points in one pass (not point by point): a bad one is still refused, named."""
    from dfa.analysis.limits.runs import simulate_points
    from dfa.errors import DFAValueError

    good = (100.0, 0.1, 0.5, 0.0, 1.0)
    with pytest.raises(DFAValueError, match=re.escape(named)):
        simulate_points([good, bad], [WallParams.of()] * 2, 1000)


def test_eq4_tail_length_of_a_huge_mass_is_a_quarter_run_without_overflow():
    """The tail cap 4·2π√μ passes int64 for μ beyond 10³⁷ (a 1e30 kg device): no cast warning, a quarter of the run."""
    import warnings

    from dfa.analysis.simulation import _tail_length, _tail_lengths

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _tail_length(50_000, 1e40) == 12_500 and _tail_length(50_000, 100.0) == 8192
        got = _tail_lengths(np.array([50_000, 7, 10**6]), np.array([1e300, 1.0, 1e12]))
    assert got.tolist() == [12_500, 2, 10**6 // 4]
