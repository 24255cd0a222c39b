"""Exact linear bound of the sampled spring (spec section 8; issue 12 item 2): dfa.analysis.linear and k_gil.

Checked against: the reproducer of the issue (m = 0.01 kg, b = 5 N·s/m, T = 10 ms:
Gil et al.'s closed form 2587.8 N/m, true bound 1652 N/m) in the package's own
linear simulation; an independent discrete state-space loop built with
scipy.linalg.expm; Gil et al. (2004)'s closed form where it binds; the z = −1
Jury condition β > ½ − tanh(a/2)/a where it binds; the small-a limit
b/(T(½ + d)) (eq. 8 for d = 0, Diolaiti et al. 2006 with delay); the CLI row
and the JSON key ``k_gil``.
"""

import json
import math

import numpy as np
import pytest
import scipy.linalg
from hypothesis import example, given, settings
from hypothesis import strategies as st
from result_json import written
from scipy.optimize import brentq

import dfa
from dfa.analysis import linear
from dfa.analysis.limits.closed_form import gil_factor
from dfa.analysis.linear import (
    characteristic_polynomial,
    critical_beta,
    critical_stiffness,
    linear_stable,
    spectral_radius,
)
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.model.wall import Wall, WallParams

A_STAR = 3.720753996  # Gil's condition and the z = −1 condition give the same K here (d = 0)
REPRO = dict(mass=0.01, damping=5.0, period=0.01)  # bT/m = 5


# ---------------------------------------------------------------- independent model: expm of the continuous device
def _ss_loop(mu, beta, d):
    """Closed-loop matrix of μξ'' + βξ' = −ξ(h − d) under a ZOH, built from scipy.linalg.expm (state ξ, ξ', delay line)."""
    m = np.zeros((3, 3))
    m[0, 1] = 1.0
    m[1, 1] = -beta / mu
    m[1, 2] = 1.0 / mu
    e = scipy.linalg.expm(m)
    ad, bd = e[:2, :2], e[:2, 2]
    n = 2 + d
    f = np.zeros((n, n))
    f[:2, :2] = ad
    if d == 0:
        f[:2, 0] -= bd
    else:
        f[:2, n - 1] -= bd  # the oldest delayed reading ξ(h − d)
        f[2, 0] = 1.0
        for i in range(1, d):
            f[2 + i, 1 + i] = 1.0
    return f


def _ss_rho(mu, beta, d):
    return float(max(abs(np.linalg.eigvals(_ss_loop(mu, beta, d)))))


def _ss_rho_physical(k, a, d):
    """Spectral radius at stiffness K for m = T = 1, b = a (so μ = 1/K, β = a/K)."""
    return _ss_rho(1.0 / k, a / k, d)


def _gil_closed_form(a):
    """Gil et al. (2004): K T²/m = γ² (1 − δ)/(1 − δ − γδ), γ = a, δ = e^{−a} (direct formula, a not small)."""
    dl = math.exp(-a)
    return a * a * (1 - dl) / (1 - dl - a * dl)


def _z_minus_one_form(a):
    """The z = −1 condition: K T²/m = 2a²/(a − 2 tanh(a/2)), i.e. β = ½ − tanh(a/2)/a."""
    return 2 * a * a / (a - 2 * math.tanh(a / 2))


# ---------------------------------------------------------------- the reproducer
def test_gil_reproducer_bound_is_1652_not_2588():
    k = critical_stiffness(**REPRO)
    assert k == pytest.approx(1652.0, rel=1e-3)
    dev = dfa.Device(coulomb=0.1, resolution=1e-5, **REPRO)
    assert dfa.k_gil(dev) == k
    assert 5.0 / 0.01 * gil_factor(5.0) == pytest.approx(2587.8, abs=0.05)  # the old, unsafe answer
    assert dfa.stiffness_limits(dev, 0.1).k_gil == k


@pytest.mark.parametrize("delay, samples", [(0, 2000), (1, 8000), (2, 20000)])
def test_gil_reproducer_linear_simulation_grows_above_and_decays_below(delay, samples):
    """dfa.simulate(quantize=False): |ξ| grows by > 1e3 at 1.01 K_crit and falls by > 1e3 at 0.99 K_crit."""
    m, b, t = REPRO["mass"], REPRO["damping"], REPRO["period"]
    k_crit = critical_stiffness(m, b, t, wall=Wall.of(1.0, delay=delay))
    ratios = []
    for f in (0.99, 1.01):
        k = f * k_crit
        r = simulate(
            m / (k * t * t),
            b / (k * t),
            0.0,
            1e-3,
            samples,
            quantize=False,
            bound=1e300,
            wall=WallParams.of(delay=delay),
        )
        tenth = samples // 10
        ratios.append(np.max(np.abs(r.xi[-tenth:])) / np.max(np.abs(r.xi[:tenth])))
    assert ratios[0] < 1e-3 < 1e3 < ratios[1]


def test_gil_old_closed_form_is_unstable_in_the_packages_own_simulation():
    """At 0.99 × Gil's 2587.8 N/m (the old k_gil) the linear loop diverges: the old answer was a counterexample."""
    m, b, t = REPRO["mass"], REPRO["damping"], REPRO["period"]
    k = 0.99 * b / t * gil_factor(b * t / m)
    r = simulate(m / (k * t * t), b / (k * t), 0.0, 1e-3, 500, quantize=False, bound=1e300)
    assert np.max(np.abs(r.xi[-50:])) > 1e6 * np.max(np.abs(r.xi[:50]))
    assert critical_stiffness(m, b, t) < 0.65 * k


# ---------------------------------------------------------------- independent state-space model
@pytest.mark.parametrize("mu, beta, d", [(2.0, 0.3, 0), (0.05, 4.0, 0), (50.0, 1e-3, 1), (1.0, 0.0, 2), (0.3, 7.0, 3)])
def test_characteristic_polynomial_equals_that_of_the_expm_state_space_loop(mu, beta, d):
    chi = characteristic_polynomial(mu, beta, wall=WallParams.of(delay=d))
    assert chi.shape == (d + 3,) and chi[0] == mu
    np.testing.assert_allclose(chi / mu, np.poly(_ss_loop(mu, beta, d)), rtol=1e-9, atol=1e-12)
    assert spectral_radius(mu, beta, wall=WallParams.of(delay=d)) == pytest.approx(_ss_rho(mu, beta, d), rel=1e-9)


_A_GRID = sorted(set(np.geomspace(1e-4, 50.0, 24).tolist() + [A_STAR - 1e-3, A_STAR, A_STAR + 1e-3, 3.72]))


@pytest.mark.parametrize("d", [0, 1, 2, 3])
def test_critical_stiffness_is_where_the_expm_loop_crosses_the_unit_circle(d):
    k = critical_stiffness(1.0, np.array(_A_GRID), 1.0, wall=Wall.of(1.0, delay=d))  # m = T = 1, b = a: K = κ
    for a, kc in zip(_A_GRID, k, strict=False):
        assert _ss_rho_physical(kc * (1 - 1e-6), a, d) < 1.0 < _ss_rho_physical(kc * (1 + 1e-6), a, d), (a, d)


@settings(max_examples=30)
@given(st.floats(-4.0, math.log10(50.0)), st.integers(0, 3))
@example(math.log10(A_STAR), 0)
@example(math.log10(A_STAR - 1e-4), 0)
@example(math.log10(A_STAR + 1e-4), 0)
@example(-4.0, 3)
@example(math.log10(50.0), 2)
def test_critical_stiffness_matches_expm_loop_property(log_a, d):
    a = 10.0**log_a
    m, t = 0.3, 2e-3
    b = a * m / t
    k = critical_stiffness(m, b, t, wall=Wall.of(1.0, delay=d))
    for step in (1e-6, 1e-4):
        lo, hi = k * (1 - step), k * (1 + step)
        assert _ss_rho(m / (lo * t * t), b / (lo * t), d) < 1.0 < _ss_rho(m / (hi * t * t), b / (hi * t), d)


@pytest.mark.parametrize("a, d", [(0.01, 0), (1.0, 0), (5.0, 0), (20.0, 0), (0.5, 1), (8.0, 2), (2.0, 3)])
def test_stable_set_in_k_is_the_interval_below_the_bound(a, d):
    k = critical_stiffness(1.0, a, 1.0, wall=Wall.of(1.0, delay=d))
    below = k * np.geomspace(1e-4, 1 - 1e-5, 60)
    above = k * np.geomspace(1 + 1e-5, 1e3, 60)
    assert all(_ss_rho_physical(x, a, d) < 1.0 for x in below)
    assert all(_ss_rho_physical(x, a, d) > 1.0 for x in above)


def test_critical_kappa_increases_with_bt_over_m_so_beta_stable_set_is_an_interval():
    """The documented reason β > β_crit(μ, d) is the whole stable set at fixed μ."""
    a = np.geomspace(1e-4, 1e3, 150)
    for d in range(7):
        k = critical_stiffness(1.0, a, 1.0, wall=Wall.of(1.0, delay=d))
        assert np.all(np.diff(k) > 0), d


@pytest.mark.parametrize("mu, d", [(1.0, 0), (0.05, 0), (5.0, 1), (100.0, 2), (0.2, 3)])
def test_linear_stable_over_beta_is_exactly_beta_above_critical_beta(mu, d):
    bc = critical_beta(mu, d)
    betas = np.concatenate([bc * np.geomspace(1e-3, 1 - 1e-5, 40), bc * np.geomspace(1 + 1e-5, 1e3, 40)])
    stable = linear_stable(np.full_like(betas, mu), betas, wall=WallParams.of(delay=d))
    np.testing.assert_array_equal(stable, betas > bc)
    assert [_ss_rho(mu, b, d) < 1.0 for b in betas] == (betas > bc).tolist()


# ---------------------------------------------------------------- closed-form anchors
def test_gil_closed_form_is_the_bound_where_it_binds():
    a = np.concatenate([np.geomspace(1e-3, 3.7, 30), [A_STAR - 1e-6]])
    k = critical_stiffness(1.0, a, 1.0)
    np.testing.assert_allclose(k, a * gil_factor(a), rtol=1e-9)  # (b/T) f(bT/m) with m = T = 1
    assert dfa.k_gil(dfa.Device(mass=0.01, damping=5.0, coulomb=0.0, resolution=1e-5, period=2e-3)) == pytest.approx(
        5.0 / 2e-3 * gil_factor(1.0), rel=1e-9
    )


def test_z_minus_one_condition_is_the_bound_beyond_a_star():
    a = np.concatenate([[A_STAR + 1e-6], np.geomspace(3.75, 50.0, 30)])
    k = critical_stiffness(1.0, a, 1.0)
    np.testing.assert_allclose(k, [_z_minus_one_form(x) for x in a], rtol=1e-9)
    assert np.all(k < a * gil_factor(a))
    # in (μ, β): β_crit = ½ − tanh(a/2)/a
    for x, kc in zip(a, k, strict=False):
        assert x / kc == pytest.approx(0.5 - math.tanh(x / 2) / x, rel=1e-9)  # β = b/(KT) = a/κ


def test_a_star_is_where_the_two_jury_conditions_meet():
    a_star = brentq(lambda x: _gil_closed_form(x) - _z_minus_one_form(x), 3.0, 4.5, xtol=1e-13)
    assert a_star == pytest.approx(A_STAR, abs=1e-8)
    assert critical_stiffness(1.0, a_star, 1.0) == pytest.approx(_gil_closed_form(a_star), rel=1e-9)


def test_z_minus_one_crossing_needs_an_even_delay():
    """(−1)^d flips the sign of −D(−1)/N(−1): odd delays never lose stability through z = −1."""
    a = 20.0
    k = {d: critical_stiffness(1.0, a, 1.0, wall=Wall.of(1.0, delay=d)) for d in (1, 3)}
    for d, kc in k.items():
        z = np.roots(characteristic_polynomial(1.0 / (kc * 1.0001), a / (kc * 1.0001), wall=WallParams.of(delay=d)))
        outside = z[np.abs(z) > 1]
        assert outside.size and np.all(np.abs(outside.imag) > 1e-3)  # a complex pair, not z = −1


@pytest.mark.parametrize("d", [0, 1, 2, 3])
def test_small_bt_over_m_limit_is_b_over_t_half_plus_d(d):
    for a in (1e-4, 1e-3, 5e-3):
        k = critical_stiffness(0.5, a * 0.5 / 1e-3, 1e-3, wall=Wall.of(1.0, delay=d))
        limit = (a * 0.5 / 1e-3) / (1e-3 * (0.5 + d))
        assert k == pytest.approx(limit, rel=1e-2)
        assert 0 < k / limit - 1 < a  # approached from above, O(bT/m)


@pytest.mark.parametrize("mu, beta_crit", [(1.0, 0.4617), (5.0, 0.4918), (100.0, 0.49958)])
def test_gil_critical_beta_matches_spec_section8(mu, beta_crit):
    b = critical_beta(mu)
    assert b == pytest.approx(beta_crit, abs=6e-5)
    assert dfa.gil_beta_critical(mu) == b
    gil = brentq(lambda x: x * gil_factor(x / mu) - 1.0, 1e-9, 0.5, xtol=1e-15, rtol=1e-15)  # Gil's condition alone
    assert b == pytest.approx(gil, rel=1e-10)


def test_critical_beta_where_z_minus_one_binds():
    """Small μ (a = β/μ > 3.72): β_crit = ½ − tanh(a/2)/a, below Gil's condition's β."""
    mu = 0.02
    b = critical_beta(mu)
    a = b / mu
    assert a > A_STAR
    assert b == pytest.approx(0.5 - math.tanh(a / 2) / a, rel=1e-9)
    gil = brentq(lambda x: x * gil_factor(x / mu) - 1.0, 1e-9, 0.5, xtol=1e-15)
    assert b > gil  # Gil's condition alone would call (μ, gil) stable: it is not
    assert not linear_stable(mu, 0.5 * (gil + b))


@pytest.mark.parametrize("d", [0, 1, 2, 3])
def test_critical_beta_tends_to_half_plus_delay(d):
    assert critical_beta(1e6, delay=d) == pytest.approx(0.5 + d, abs=1e-3)
    assert dfa.gil_beta_critical(1e6, delay=d) == critical_beta(1e6, delay=d)


# ---------------------------------------------------------------- edges, vectorisation, errors
def test_undamped_loop_has_no_stable_stiffness():
    assert critical_stiffness(1.0, 0.0, 1e-3) == 0.0
    assert dfa.k_gil(dfa.Device(mass=1.0, damping=0.0, coulomb=0.1, resolution=1e-5, period=1e-3)) == 0.0
    assert characteristic_polynomial(2.0, 0.0).tolist() == [2.0, -3.5, 2.5]  # β → 0 limit: c₁ = c₀ = ½, p = 1
    for mu in (1e-2, 1.0, 1e4):
        assert spectral_radius(mu, 0.0) > 1.0 and spectral_radius(mu, 0.0, wall=WallParams.of(delay=2)) > 1.0


def test_characteristic_polynomial_is_continuous_at_small_beta():
    c_small = characteristic_polynomial(3.0, 3.0 * 1e-12)
    np.testing.assert_allclose(c_small, characteristic_polynomial(3.0, 0.0), rtol=1e-11)
    # across the series/closed-form switch at a = ½
    np.testing.assert_allclose(
        characteristic_polynomial(1.0, 0.5 - 1e-12), characteristic_polynomial(1.0, 0.5 + 1e-12), rtol=1e-10
    )


def test_vectorised_calls_equal_scalar_calls():
    m = np.array([0.01, 0.2, 1.0])
    k = critical_stiffness(m, 5.0, 0.01, wall=Wall.of(1.0, delay=1))
    assert k.shape == (3,) and k.tolist() == [
        critical_stiffness(float(x), 5.0, 0.01, wall=Wall.of(1.0, delay=1)) for x in m
    ]
    mu = np.array([[0.5], [5.0]])
    beta = np.array([0.1, 0.6, 3.0])
    r = spectral_radius(mu, beta, wall=WallParams.of(delay=2))
    assert r.shape == (2, 3)
    assert r[1, 2] == spectral_radius(5.0, 3.0, wall=WallParams.of(delay=2))
    np.testing.assert_array_equal(linear_stable(mu, beta), spectral_radius(mu, beta) < 1.0)


def test_fallback_scan_agrees_with_the_crossings(monkeypatch):
    """If the crossing search missed a root, the spectral-radius scan still finds the first instability."""
    expected = [linear._critical_kappa(a, d) for a, d in [(0.3, 0), (5.0, 0), (2.0, 1), (0.01, 3)]]
    monkeypatch.setattr(linear, "_crossings", lambda a, d: [])
    got = [linear._critical_kappa(a, d) for a, d in [(0.3, 0), (5.0, 0), (2.0, 1), (0.01, 3)]]
    np.testing.assert_allclose(got, expected, rtol=1e-9)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: critical_stiffness(-1.0, 5.0, 0.01), "mass"),
        (lambda: critical_stiffness(0.01, -5.0, 0.01), "damping"),
        (lambda: critical_stiffness(0.01, 5.0, [0.01, 0.0]), "period"),
        (lambda: critical_stiffness(0.01, 5.0, 0.01, wall=Wall.of(1.0, delay=-1)), "delay"),
        (lambda: critical_beta(0.0), "mu"),
        (lambda: critical_beta(1.0, delay=1.5), "delay"),
        (lambda: spectral_radius([1.0, np.nan], 0.1), "mu"),
        (lambda: spectral_radius(1.0, -0.1), "beta"),
        (lambda: characteristic_polynomial(1.0, 0.1, wall=WallParams.of(delay=-2)), "delay"),
        (lambda: dfa.k_gil(dfa.get_device("Delta").device, delay=-1), "delay"),
    ],
)
def test_invalid_inputs_name_the_parameter(call, name):
    with pytest.raises(dfa.DFAValueError, match=rf"^{name} = "):
        call()


def test_type_errors_are_dfa_type_errors():
    with pytest.raises(dfa.DFATypeError, match="^mu = "):
        spectral_radius("1", 0.1)
    with pytest.raises(dfa.DFATypeError, match="^delay = "):
        critical_stiffness(0.01, 5.0, 0.01, wall=Wall.of(1.0, delay="1"))


# ---------------------------------------------------------------- what users read
_CLI = [
    "stiffness",
    "--mass",
    "0.01",
    "--damping",
    "5",
    "--period",
    "0.01",
    "--coulomb",
    "0.1",
    "--resolution",
    "1e-5",
    "--velocity",
    "0.1",
    "--stiffness",
    "1000",
]


def test_gil_cli_row_prints_the_exact_linear_bound(capsys):
    assert main([*_CLI, "--explain"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("exact linear bound"))
    assert row.split()[-2:] == ["1651.9", "N/m"]


def test_gil_cli_json_k_gil(capsys):
    assert main(_CLI + ["--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["k_linear"]["value"] == pytest.approx(1652.0, rel=1e-3)
    assert rec["k_linear"]["value"] == written(critical_stiffness(**REPRO))


def test_gil_cli_row_follows_the_delay(capsys):
    """`dfa stiffness --delay 1` prints the exact linear bound of the delayed loop (smaller than without delay)."""
    from dfa.analysis.linear import critical_stiffness

    assert main(_CLI + ["--delay", "1", "--explain"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("exact linear bound"))
    assert "delay 1" in row
    assert float(row.split()[-2]) == pytest.approx(
        critical_stiffness(0.01, 5.0, 0.01, wall=Wall.of(1.0, delay=1)), rel=1e-4
    )
    assert float(row.split()[-2]) < 1651.9
