"""Batched runs (issue 16) equal single runs of the exact simulator (paper eq. 4-5), bit for bit.

The grids mix rest, chatter, oscillation, divergence, delay, β = 0 and σ = 0.
"""

import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

from dfa import DFAValueError
from dfa.maps import stability_map
from dfa.simulation import OUTCOMES, simulate, simulate_batch


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
    b = simulate_batch(mu, beta, sigma, v0, 4000, x0, delay, quantize, bound=1e4)
    for i in range(len(b)):
        r = simulate(mu[i], beta[i], sigma[i], v0[i], 4000, x0[i], delay, quantize, record=False, bound=1e4)
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
    d = short.as_dict()
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
    kw = dict(grid=6, samples=3000, progress=False, delay=1)
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
        r = simulate(mu, beta, sigma, v0, 20000, delay=delay, record=False)
        done, x, v = plain_kernel(mu, beta, sigma, 0.0, v0, 20000, delay, True, 1e6)
        assert r.outcome == "rest" and done == r.rest_sample
        assert x == pytest.approx(r.final_xi, rel=1e-12) and v == r.final_xi_dot == 0.0
    for mu, beta, sigma, v0, delay in [(5.0, 0.2, 0.6, 1.5, 1), (30.0, 0.0, 0.7, 1.0, 2)]:  # past the bound
        r = simulate(mu, beta, sigma, v0, 20000, delay=delay, record=False)
        done, x, v = plain_kernel(mu, beta, sigma, 0.0, v0, 20000, delay, True, 1e6)
        assert r.outcome == "unstable" and done == r.samples_run and x == pytest.approx(r.final_xi, rel=1e-12)
