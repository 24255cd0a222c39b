"""The simulator kernel's inlined steps (dfa.core.kernel; paper eq. 4-5, 18-23), each against the pure-Python reference.

``reference.step_python`` is the per-sample map written out in plain Python; the compiled
steps must reproduce it bit for bit, and running a simulation in arbitrary ranges of samples
(:func:`dfa.core.kernel.advance`) must equal the single call.
"""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import step_python
from scipy.integrate import quad

from dfa.analysis.criterion import spring_energy
from dfa.core import exprel, kernel

finite = dict(allow_nan=False, allow_infinity=False)
MU = st.floats(0.05, 1e4, **finite)
BETA = st.one_of(st.just(0.0), st.floats(0.0, 5.0, **finite))
SIGMA = st.one_of(st.just(0.0), st.floats(0.0, 3.0, **finite))
X = st.floats(-50.0, 50.0, **finite)
V = st.one_of(st.just(0.0), st.floats(-5.0, 5.0, **finite))


def _consts(mu, beta):
    return (kernel.sample_constants(mu, beta),)


@given(X, V, X, MU, BETA, SIGMA)
def test_eq4_step_equals_python_reference_step(x, v, phi, mu, beta, sigma):
    got = kernel.step(x, v, phi, mu, sigma, *_consts(mu, beta))
    assert got[:2] == step_python(x, v, phi, mu, beta, sigma)


@pytest.mark.parametrize(
    "x, v, phi, mu, beta, sigma, stopped",
    [
        (0.3, 0.0, 0.4, 2.0, 0.1, 0.5, False),  # stuck: |φ| <= σ
        (0.3, 0.01, -1.5, 2.0, 0.4, 0.1, True),  # stops, restarts backwards
        (0.3, 0.01, -0.05, 2.0, 0.4, 0.1, True),  # stops and sticks
        (0.3, 2.0, -0.5, 2.0, 0.0, 0.0, False),  # β = σ = 0: polynomial motion
    ],
)
def test_eq4_step_stick_slip_cases(x, v, phi, mu, beta, sigma, stopped):
    got = kernel.step(x, v, phi, mu, sigma, *_consts(mu, beta))
    assert got[:2] == step_python(x, v, phi, mu, beta, sigma)
    assert got[-1] is stopped
    if stopped:
        assert 0.0 < got[3] <= 1.0  # t*


def test_eq4_force_and_delay_ring_match_shifted_history():
    rng = np.random.default_rng(3)
    for delay in range(5):
        xs = rng.uniform(-5, 5, 40)
        hist = np.full(delay + 1, kernel.force(xs[0], True))
        shifted = [hist[0]] * (delay + 1)
        pos = 0
        for x in xs:
            f = kernel.force(x, True)
            assert f == -(math.floor(x) + 0.5) and kernel.force(x, False) == -x
            shifted = shifted[1:] + [f]
            phi, pos = kernel.delayed_force(f, hist, pos, delay)
            assert phi == shifted[0]
            assert sorted(hist.tolist()) == sorted(shifted) or delay == 0
            assert kernel.at_rest(0.0, phi, abs(phi), hist, delay) == all(h == phi for h in shifted)


def test_eq4_at_rest_needs_zero_speed_and_friction_above_force():
    hist = np.array([-0.5])
    assert kernel.at_rest(0.0, -0.5, 0.5, hist, 0)
    assert not kernel.at_rest(1e-300, -0.5, 0.5, hist, 0)
    assert not kernel.at_rest(0.0, -0.5, 0.4999, hist, 0)


def test_eq4_segment_bounds_match_per_sample_division():
    for n in [1, 2, 7, 8, 9, 15, 16, 17, 1000, 50_001]:
        seg = np.arange(n) * kernel.NSEG // n
        for k in range(kernel.NSEG):
            lo, hi = kernel.segment_bounds(k, n)
            assert np.array_equal(np.flatnonzero(seg == k), np.arange(lo, hi))


@pytest.mark.parametrize(
    "x, v, phi, mu, beta, sigma",
    [(0.2, 1.5, -0.5, 3.0, 0.6, 0.2), (0.2, 0.02, -2.5, 3.0, 0.6, 0.2), (0.0, 0.0, 1.5, 0.5, 2.0, 0.3)],
)
def test_eq21_energy_terms_match_quadrature(x, v, phi, mu, beta, sigma):
    """Viscous loss β∫ξ'² and Coulomb loss σ∫|ξ'| of one sample against numerical quadrature of the motion."""
    x1, v1, xr, tstar, a, a2, tr, _stopped = kernel.step(x, v, phi, mu, sigma, *_consts(mu, beta))
    gen, dvisc, dcoul, stored = kernel.energy_terms(x, v, x1, v1, phi, (xr, tstar, a, a2, tr), (mu, beta, sigma), True)
    r = beta / mu

    def speed(t):  # ξ'(t) on the two phases (closed form)
        if t <= tstar:
            return v * math.exp(-r * t) + a * t * exprel.phi1(r * t)
        s = t - tstar
        return a2 * s * exprel.phi1(r * s)

    brk = [tstar] if 0.0 < tstar < 1.0 else None
    assert dvisc == pytest.approx(beta * quad(lambda t: speed(t) ** 2, 0, 1, points=brk, epsabs=1e-14)[0], rel=1e-9)
    assert dcoul == pytest.approx(sigma * quad(lambda t: abs(speed(t)), 0, 1, points=brk, epsabs=1e-14)[0], rel=1e-9)
    assert stored == 0.5 * mu * v1 * v1 + float(spring_energy(x1))
    assert gen == pytest.approx(phi * (x1 - x) + float(spring_energy(x1) - spring_energy(x)), rel=1e-12, abs=1e-15)


@pytest.mark.parametrize("delay", [0, 2])
@pytest.mark.parametrize("case", [(2.0, 0.4, 0.1, 0.0, 2.0), (100.0, 0.3, 1.5, 0.0, 2.0), (100.0, 0.0, 0.2, 0.3, 2.0)])
def test_eq4_run_in_ranges_equals_one_call(case, delay):
    """start + advance over arbitrary ranges + finish (how a caller may chunk a run) equals simulate_kernel."""
    mu, beta, sigma, x0, v0 = case
    n, tail_len, bound = 5000, 1200, 1e3
    whole = np.empty(kernel.NSTATS)
    e, e2 = np.empty(0), np.empty((0, 4))
    run = (n, tail_len, bound, True)
    keep = (False, False)  # no records
    done, rest = kernel.simulate_kernel((mu, beta, sigma), (x0, v0), run, delay, e, e, e2, whole)
    stats, state, hist, tail = (
        np.empty(kernel.NSTATS),
        np.empty(kernel.NSTATE),
        np.empty(delay + 1),
        np.empty(tail_len),
    )
    kernel.start(x0, v0, delay, True, state, hist, stats)
    seams = [kernel.segment_bounds(k, n)[0] for k in range(kernel.NSEG)]  # a range's peak belongs to one segment
    cuts = sorted({0, n, n - tail_len, *seams, *np.random.default_rng(5).integers(0, n, 12).tolist()})
    done2, rest2 = n, -1
    for lo, hi in zip(cuts[:-1], cuts[1:], strict=True):
        end, why, peak = kernel.advance(state, hist, lo, hi, (mu, beta, sigma), run, delay, tail, (e, e, e2), keep)
        k = lo * kernel.NSEG // n
        stats[k] = max(stats[k], peak)
        if why:
            done2, rest2 = end, (end if why == 1 else -1)
            stats[kernel.NSEG + 5] = float(why == 2)
            break
    kernel.finish(state, done2, rest2, mu, run, tail, stats, (e, e, e2), keep)
    assert (done2, rest2) == (done, rest)
    np.testing.assert_array_equal(stats, whole)


def test_eq4_step_stays_finite_when_speed_and_force_underflow():
    """Denormal ξ' and φ of the same sign (a stop 'found' by underflow, w < 0): finite, as the kernel always was.

    Found by the soundness check of random walls (dfa.studies.soundness, seed 2024): a linear run decaying through the denormals reached
    ξ' = φ = −5e-324, where log1p(y)/y at y < −1 would have been NaN.
    """
    mu, beta = 1.010500446509884, 1.8047083379647524
    for phi in (-5e-324, -1e-323, 5e-324):
        got = kernel.step(1e-323, -5e-324, phi, mu, 0.0, *_consts(mu, beta))
        assert all(math.isfinite(g) for g in got[:5])
        assert got[:2] == step_python(1e-323, -5e-324, phi, mu, beta, 0.0)
