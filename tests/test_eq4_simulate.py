"""Exact simulator of the sampled loop (paper eq. 4-5), checked against independent integrators,
the energy identity of section 6.1 (eq. 18-23) and the criterion's claim (eq. 6)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import linear_zoh_recursion, simulate_control, simulate_ivp

import dfa
from dfa.analysis.simulation import preload_position, simulate, stored_energy
from dfa.model.wall import WallParams

CASES = [  # (μ, β, σ, ξ0, ξ'0): stick-slip, β = 0, σ = 0, offsets
    (100.0, 0.1, 0.9, 0.0, 2.0),
    (5.0, 0.0, 0.3, 0.2, 1.3),
    (2.0, 0.6, 0.45, -0.3, 0.7),
    (1.0, 0.05, 0.0, 0.0, 0.5),
    (30.0, 0.2, 1.1, 3.7, 0.0),
    (20.3, 0.0, 0.0, 0.4137, 0.1093),  # non-dyadic: exact arithmetic must not land on a quantizer edge
]


@pytest.mark.parametrize("mu, beta, sigma, x0, v0", CASES)
def test_eq4_simulator_matches_solve_ivp_with_events(mu, beta, sigma, x0, v0):
    r = simulate(mu, beta, sigma, v0, 250, xi0=x0)
    xs, vs = simulate_ivp(mu, beta, sigma, x0, v0, 250)
    # Past ~1e3 ticks a 1e-13 relative difference can move ξ across an integer, the quantizer
    # then reads another level and any two integrators part: compare up to there.
    big = np.nonzero(np.abs(xs) > 1e3)[0]
    ok = np.isfinite(r.xi) & (np.arange(xs.size) < (big[0] if big.size else xs.size))
    assert ok.sum() > 20
    scale = np.maximum(1.0, np.abs(xs[ok]))
    assert np.max(np.abs(r.xi[ok] - xs[ok]) / scale) <= 1e-8
    assert np.max(np.abs(r.xi_dot[ok] - vs[ok]) / np.maximum(1.0, np.abs(vs[ok]))) <= 1e-8


def test_eq4_stick_slip_really_happens_in_the_checked_cases():
    r = simulate(100.0, 0.1, 0.9, 2.0, 250)
    assert r.rest_sample is None or r.rest_sample > 10
    # velocity reversals inside samples: sign changes of ξ' between samples
    v = r.xi_dot[np.isfinite(r.xi_dot)]
    assert np.sum(np.sign(v[:-1]) * np.sign(v[1:]) < 0) >= 3
    # with d = 0 a stop at a sample instant is final: the run sticks once, at its rest
    r = simulate(30.0, 0.2, 1.1, 0.0, 250, xi0=3.7)
    assert r.rest_sample is not None and r.xi_dot[r.rest_sample] == 0.0 and np.all(r.xi_dot[1 : r.rest_sample] != 0.0)


@pytest.mark.parametrize("delay", [1, 3])
def test_eq4_delay_matches_solve_ivp(delay):
    r = simulate(5.0, 0.2, 0.6, 1.5, 150, wall=WallParams.of(delay=delay))
    xs, _ = simulate_ivp(5.0, 0.2, 0.6, 0.0, 1.5, 150, delay=delay)
    ok = np.isfinite(r.xi)
    assert np.max(np.abs(r.xi[ok] - xs[ok]) / np.maximum(1, np.abs(xs[ok]))) <= 1e-8


def test_eq4_python_control_io_simulation_agrees():
    r = simulate(2.0, 0.4, 0.1, 2.0, 400)
    xc, vc = simulate_control(2.0, 0.4, 0.1, 0.0, 2.0, 400)
    assert np.max(np.abs(xc - r.xi)) <= 1e-9


@pytest.mark.parametrize(
    "mu, beta, delay", [(5.0, 0.6, 0), (1.0, 0.55, 0), (50.0, 1.2, 1), (3.0, 2.0, 3), (5.0, 0.0, 0)]
)
def test_linear_variant_matches_exact_zoh_recursion_from_c2d(mu, beta, delay):
    n = 10_000 if beta > 0 else 2_000
    r = simulate(mu, beta, 0.0, 1.0, n, xi0=0.5, quantize=False, bound=1e300, wall=WallParams.of(delay=delay))
    xl, vl = linear_zoh_recursion(mu, beta, 0.5, 1.0, n, delay=delay)
    scale = max(1.0, np.max(np.abs(xl)))
    assert np.max(np.abs(r.xi - xl)) <= 1e-10 * scale
    assert np.max(np.abs(r.xi_dot - vl)) <= 1e-10 * max(1.0, np.max(np.abs(vl)))


@pytest.mark.parametrize("mu", [1.0, 5.0, 100.0])
def test_gil_bound_flips_growth_of_the_linear_loop(mu):
    b = dfa.gil_beta_critical(mu)
    n = 40_000
    peaks = []
    for beta in (b * 0.98, b * 1.02):
        r = simulate(mu, beta, 0.0, 1.0, n, quantize=False, bound=1e300)
        peaks.append((np.max(np.abs(r.xi[: n // 10])), np.max(np.abs(r.xi[-n // 10 :]))))
    (first_lo, last_lo), (first_hi, last_hi) = peaks
    assert last_lo > first_lo  # below the bound: grows
    assert last_hi < first_hi  # above: decays


def _energy_cases():
    return st.tuples(
        st.floats(0.2, 200.0),
        st.floats(0.0, 1.0),
        st.floats(0.0, 1.5),
        st.floats(-3, 3),
        st.floats(-4, 4),
        st.booleans(),
    )


@given(_energy_cases())
def test_eq20_energy_identity_holds_every_sample(case):
    mu, beta, sigma, x0, v0, quantize = case
    r = simulate(mu, beta, sigma, v0, 400, xi0=x0, quantize=quantize, energy=True, bound=1e8)
    e = r.energy
    n = r.samples_run
    res = e.balance_residual()[:n]
    scale = max(1.0, float(np.max(np.abs(e.stored[:n]))) if n else 1.0, e.initial_stored)
    assert np.all(np.abs(res) <= 1e-9 * scale)
    # the stored energy agrees with the trajectory
    np.testing.assert_allclose(
        e.stored[:n], stored_energy(r.xi[1 : n + 1], r.xi_dot[1 : n + 1], mu, quantize), rtol=1e-12, atol=1e-12
    )
    assert np.all(e.dissipated_viscous[:n] >= 0) and np.all(e.dissipated_coulomb[:n] >= 0)


def test_eq32_viscous_dissipation_matches_quadrature_of_the_velocity():
    from scipy.integrate import quad

    mu, beta, sigma = 3.0, 0.7, 0.2
    r = simulate(mu, beta, sigma, 1.2, 30, energy=True)
    # rebuild ξ'(t) inside sample 0 from the closed form and integrate β ξ'² numerically
    x, v = r.xi[0], r.xi_dot[0]
    phi = -(math.floor(x) + 0.5)
    a = (phi - sigma) / mu

    def vel(t):
        return v * math.exp(-beta * t / mu) + a * mu / beta * (1 - math.exp(-beta * t / mu))

    assert r.xi_dot[1] > 0
    num, _ = quad(lambda t: beta * vel(t) ** 2, 0, 1, epsabs=1e-14)
    assert r.energy.dissipated_viscous[0] == pytest.approx(num, rel=1e-12)


@given(st.floats(1.0, 200.0), st.floats(0.0, 0.8), st.floats(0.5, 2.5), st.floats(0.05, 6.0))
def test_eq6_criterion_claim_holds_on_simulated_paths(mu, beta, sigma, v0):
    """Where eq. 6 says passive, the path is never unstable and never gains energy beyond the 1/8 tick² of eq. 18."""
    crit = dfa.passivity_criterion(beta, sigma, v0)
    r = simulate(mu, beta, sigma, v0, 3000, energy=True)
    if crit.passive:
        assert r.outcome != "unstable"
        n = r.samples_run
        assert np.max(r.energy.stored[:n], initial=0.0) <= r.energy.initial_stored + 0.125 + 1e-9


def test_rest_at_origin_is_exact():
    lin = simulate(5.0, 0.2, 0.0, 0.0, 100, xi0=0.0, quantize=False)
    assert lin.rest_sample == 0 and lin.outcome == "rest" and np.all(lin.xi == 0.0) and np.all(lin.xi_dot == 0.0)
    stuck = simulate(5.0, 0.2, 0.5, 0.0, 100)  # |φ| = ½ <= σ: stiction holds at ξ = 0
    assert stuck.rest_sample == 0 and np.all(stuck.xi == 0.0)
    # σ < ½: the ½-tick offset pushes the device off ξ = 0 into a sub-tick chatter (region b/c behaviour)
    chat = simulate(5.0, 0.8, 0.2, 0.0, 20000)
    assert chat.rest_sample is None and 0 < chat.amplitude < 1 and chat.outcome == "chatter" and chat.frequency > 0


def test_outcome_classes():
    assert simulate(100.0, 0.3, 1.5, 2.0, 20000).outcome == "rest"
    unstable = simulate(100.0, 0.0, 0.2, 2.0, 20000)
    assert unstable.outcome == "unstable" and unstable.samples_run < 20000 and math.isinf(unstable.amplitude)
    osc = simulate(2.0, 0.4, 0.1, 2.0, 20000)
    assert osc.outcome == "oscillating" and osc.amplitude > 1.0
    # the measured cycle is the one in the recorded tail
    tail = osc.xi[-4000:]
    assert osc.amplitude == pytest.approx((tail.max() - tail.min()) / 2, rel=0.05)
    assert osc.period == pytest.approx(2 * math.pi / osc.frequency)


def test_growing_envelope_below_the_bound_is_unstable():
    # slow growth that never reaches the bound within the run
    r = simulate(100.0, 0.45, 0.0, 1.0, 30000, quantize=False, bound=1e300)
    peaks = [np.max(np.abs(r.xi[i : i + 3000])) for i in (0, 27000)]
    assert peaks[1] > 2 * peaks[0]
    assert r.outcome == "unstable"


def test_record_off_gives_same_outcome_and_final_state():
    a = simulate(2.0, 0.4, 0.1, 2.0, 5000)
    b = simulate(2.0, 0.4, 0.1, 2.0, 5000, record=False)
    assert b.xi is None and (a.outcome, a.amplitude, a.frequency) == (b.outcome, b.amplitude, b.frequency)
    assert (a.final_xi, a.final_xi_dot) == (b.final_xi, b.final_xi_dot) == (a.xi[-1], a.xi_dot[-1])


@given(st.floats(0.1, 500.0), st.floats(0.0, 20.0))
def test_section5_preload_stores_the_kinetic_energy(mu, v):
    x0 = preload_position(mu, v)
    assert x0 >= 0
    assert stored_energy(x0, 0.0, mu) == pytest.approx(0.5 * mu * v * v, rel=1e-12, abs=1e-15)


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(samples=0), "samples"),
        (dict(samples=2.5), "samples"),
        (dict(wall=WallParams.of(damping=0.1), energy=True), "energy"),
        (dict(mu=0.0), "mu"),
        (dict(beta=-0.1), "beta"),
        (dict(sigma=math.nan), "sigma"),
        (dict(xi_dot0=math.inf), "xi_dot0"),
        (dict(samples=10**9), "record=False"),
        (dict(growth=1.0), "growth"),
    ],
)
def test_simulate_bad_input(kwargs, needle):
    args = dict(mu=1.0, beta=0.1, sigma=0.1, xi_dot0=1.0, samples=10)
    args.update(kwargs)
    with pytest.raises(dfa.DFAValueError, match=needle):
        simulate(**args)


@pytest.mark.parametrize(
    "mu, beta, sigma, x0, v0",
    [
        (2.0, 5e-324, 1.0, 0.0, 1.0),  # β/μ underflows to 0: the stop time must not divide by it
        (0.001, 0.5, 0.5, -1.0, 1.0),  # force exactly balanced by friction: ξ' decays and underflows to 0
    ],
)
def test_eq4_edge_cases_found_by_hypothesis(mu, beta, sigma, x0, v0):
    r = simulate(mu, beta, sigma, v0, 300, xi0=x0, energy=True)
    assert r.outcome == "rest"
    res = r.energy.balance_residual()[: r.samples_run]
    assert np.all(np.abs(res) <= 1e-9 * max(1.0, r.energy.initial_stored))
