"""The exact simulator's skip of repeated periods (issue 16) changes no result, bit for bit (paper eq. 4-5).

Without delay the loop's state is (ξ, ξ') alone; :func:`dfa.core.kernel.advance_free` skips whole periods
once that state repeats bit for bit. The unskipped reference is the same kernel with records on
(``record=True`` integrates every sample), and the batched runs of a stability map.
"""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import recorded_period

from dfa import simulate
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import OUTCOMES, divergence_bound, simulate_batch


def _outputs(r):
    freq = np.nan if r.frequency is None else r.frequency
    rest = -1 if r.rest_sample is None else r.rest_sample
    return [OUTCOMES.index(r.outcome), r.samples_run, rest, r.final_xi, r.final_xi_dot, *r.envelope] + [
        r.amplitude,
        freq,
        r.centre,
        r.force_peak_to_peak,
    ]


def _same_as_recorded(mu, beta, sigma, v0, n, x0=0.0, quantize=True):
    fast = simulate(mu, beta, sigma, v0, n, x0, quantize=quantize, record=False)
    full = simulate(mu, beta, sigma, v0, n, x0, quantize=quantize, record=True)
    assert np.array_equal(_outputs(fast), _outputs(full), equal_nan=True)
    return full


@pytest.mark.parametrize(
    "mu, beta, sigma, v0",
    [(2.0, 0.4, 0.1, 2.0), (100.0, 0.3, 0.3, 1.0), (100.0, 0.1, 0.6, 2.0), (100.0, 0.05, 0.2, 5.0)],
)
def test_eq4_periodic_runs_skip_to_the_same_result(mu, beta, sigma, v0):
    """Cycles that repeat bit for bit (the skip is exercised) end exactly as when every sample is integrated."""
    full = _same_as_recorded(mu, beta, sigma, v0, 50_000)
    found = recorded_period(np.asarray(full.xi), np.asarray(full.xi_dot))
    assert found is not None and found[0] < 40_000  # periods skipped before the tail


@given(
    st.floats(1.0, 300.0),
    st.floats(0.0, 1.0) | st.just(0.0),
    st.floats(0.0, 2.0) | st.just(0.0),
    st.floats(-6.0, 6.0),
    st.floats(-2.0, 2.0) | st.just(0.0),
    st.booleans(),
)
def test_eq4_skip_is_exact_on_random_runs(mu, beta, sigma, v0, x0, quantize):
    _same_as_recorded(mu, beta, sigma, v0, 6000, x0, quantize)


def test_fig4_map_points_equal_single_recorded_runs():
    """Points of a Fig. 4 map (batched, skipping) equal single runs integrating every sample."""
    m = stability_map(100.0, [2.0], grid=6, samples=20_000, n_jobs=1, progress=False)
    for i, sigma in enumerate(m.sigma):
        for j, beta in enumerate(m.beta):
            r = simulate(100.0, beta, sigma, 2.0, 20_000, record=True, bound=divergence_bound(0.0, 2.0, 100.0))
            assert OUTCOMES.index(r.outcome) == m.outcome[0, i, j]
            assert np.array_equal([r.amplitude], [m.amplitude[0, i, j]], equal_nan=True)
            f = np.nan if r.frequency is None else r.frequency
            assert np.array_equal([f], [m.frequency[0, i, j]], equal_nan=True)


def test_eq4_batch_with_skips_equals_recorded_runs():
    rng = np.random.default_rng(3)
    mu, beta, sigma, v0 = 100.0, rng.uniform(0, 0.5, 30), rng.uniform(0, 1.0, 30), rng.uniform(0.5, 5, 30)
    b = simulate_batch(mu, beta, sigma, v0, 20_000, bound=1e4)
    for i in range(len(b)):
        r = simulate(mu, beta[i], sigma[i], v0[i], 20_000, record=True, bound=1e4)
        assert r.samples_run == b.samples_run[i] and OUTCOMES.index(r.outcome) == b.outcome[i]
        assert np.array_equal(r.envelope, b.envelope[i]) and r.final_xi == b.final_xi[i]
        assert np.array_equal([r.amplitude, r.centre], [b.amplitude[i], b.centre[i]], equal_nan=True)
