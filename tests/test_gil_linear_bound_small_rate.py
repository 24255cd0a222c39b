"""The exact linear bound K_crit (dfa.analysis.linear.critical_stiffness, spec section 8) at very small a = bT/m, with and
without delay, checked against the spectral radius of the same characteristic polynomial in high-precision arithmetic
(mpmath).

Formerly a known bug: below about a = 1e-9 (d = 30) or 1e-10 (d = 3) the float spectral radius that verified each
crossing could not resolve the boundary (the roots cluster at z = 1, |z| − 1 = O(a)), K_crit came out up to 4e-4 above
the true limit, 10⁶ times too small at a = 1e-12, d = 3, and not at all at a <= 1e-16. Below r_d·a = 1e-6 the bound is
now the small-a expansion κ = a/(½ + d)(1 + r_d a), r_d = (2d² + 2d + 1)/(6(2d + 1)) (``_small_rate_kappa``).
"""

from __future__ import annotations

import json
import math

import mpmath
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dfa.analysis import linear
from dfa.analysis.linear import _critical_kappa, _small_rate_kappa, critical_stiffness
from dfa.cli import main
from dfa.model.wall import Wall


def _char_poly_mp(a, kappa, d, a_b=0.0, cutoff=None, lag=0.0):
    """Coefficients (highest first, mpmath) of κχ = P₀ + κQ of the loop of dfa.analysis.linear_wall (the spring:
    a_b = 0, no lag): plant c₁ = (a − 1 + p)/a², c₀ = (1 − p − ap)/a² (a = 0: ½, ½), or with amplifier lag α the
    residue numerator of ``test_controlled_linear._zoh_numerator_mpmath``; controller z^{−d}[1 + β_B(1 − z^{−1})F].
    Call inside ``mpmath.workdps``."""
    from test_controlled_linear import _zoh_numerator_mpmath

    def pmul(x, y):
        out = [mpmath.mpf(0)] * (len(x) + len(y) - 1)
        for i, u in enumerate(x):
            for j, v in enumerate(y):
                out[i + j] += u * v
        return out

    def padd(x, y):
        n = max(len(x), len(y))
        x, y = [0] * (n - len(x)) + list(x), [0] * (n - len(y)) + list(y)
        return [u + v for u, v in zip(x, y, strict=True)]

    a_, k = mpmath.mpf(a), mpmath.mpf(kappa)
    p = mpmath.e ** (-a_)
    if lag:
        ng = _zoh_numerator_mpmath(a, lag, dps=mpmath.mp.dps, as_float=False)
        dg = pmul(pmul([1, -1], [1, -p]), [1, -(mpmath.e ** (-1 / mpmath.mpf(lag)))])
    else:
        ng = [(a_ - 1 + p) / a_**2, (1 - p - a_ * p) / a_**2] if a else [mpmath.mpf(0.5)] * 2
        dg = pmul([1, -1], [1, -p])
    shift = [mpmath.mpf(1)] + [mpmath.mpf(0)] * (d + 1)  # z^{d+1}
    if a_b and cutoff is not None:
        af = mpmath.e ** (-2 * mpmath.pi * mpmath.mpf(cutoff))
        n1, n2, dh = [1, -af, 0], [1 - af, af - 1], pmul(shift, [1, -af])
    else:
        n1, n2, dh = [1, 0], [1, -1], shift
    p0 = padd(pmul(dg, dh), [mpmath.mpf(a_b) * c for c in pmul(ng, n2)])
    return padd(p0, [k * c for c in pmul(ng, n1)])


def _rho_mp(a: float, kappa: float, d: int, **controller) -> float:
    """ρ − 1, ρ the largest root modulus of z^d (z − 1)(z − p) + κ(c₁z + c₀) (p = e^{−a}: ZOH of 1/(s(s + a))), or
    with ``controller`` (a_b, cutoff, lag) of the loop of dfa.analysis.linear_wall (:func:`_char_poly_mp`).

    60 significant digits after the cancellation in c₁ = (a − 1 + p)/a², c₀ = (1 − p − ap)/a² (which costs
    2·log10(1/a) digits, so the working precision grows as a shrinks).
    """
    dps = 60 + max(0, int(-2 * math.log10(a or controller.get("a_b") or 1.0)))
    with mpmath.workdps(dps):
        coef = _char_poly_mp(a, kappa, d, **controller)
        lead = coef[0]
        coef = [c / lead for c in coef]
        while coef[-1] == 0:  # roots at z = 0 (the controller's z^{d+1}): no bearing on ρ, slow for polyroots
            coef.pop()
        return float(max(abs(r) for r in mpmath.polyroots(coef, maxsteps=400, extraprec=2 * dps)) - 1)


def _check(a: float, d: int, rel: float = 1e-4) -> None:
    k = _critical_kappa(a, d)
    assert _rho_mp(a, k * (1 - rel), d) < 0.0, (a, d, k)  # stable just below K_crit
    assert _rho_mp(a, k * (1 + rel), d) > 0.0, (a, d, k)  # unstable just above


@pytest.mark.parametrize("a, d", [(1e-6, 30), (1e-6, 3), (1e-4, 0), (1e-3, 1), (0.3, 2)])
def test_gil_linear_bound_is_the_stability_limit_mpmath(a, d):
    _check(a, d)


@pytest.mark.parametrize("a, d", [(1e-9, 30), (1e-10, 3), (1e-12, 3), (1e-12, 0), (1e-16, 1), (1e-30, 0)])
def test_gil_linear_bound_small_rate_former_counterexamples(a, d):
    _check(a, d)


@pytest.mark.parametrize(
    "a, d",
    [
        (1e-16, 0),
        (1e-13, 2),
        (1e-11, 30),
        (1e-8, 7),
        (3e-7, 30),
        (5e-7, 1),
        (1e-5, 4),
        (0.01, 30),
        (1.0, 3),
        (10.0, 0),
        (10.0, 5),
    ],
)
def test_gil_linear_bound_grid_of_rates_and_delays_mpmath(a, d):
    """A representative grid a = 1e-16 … 10, d = 0 … 30, both sides of the small-a switch (r_d·a = 1e-6)."""
    _check(a, d)


@pytest.mark.parametrize("d", [0, 1, 3, 30])
def test_gil_small_rate_expansion_matches_the_verified_crossings_at_the_switch(d):
    """Near the switch both methods are valid: the expansion agrees with the verified crossing to ~(r_d a)² <= 1e-11."""
    r = (2 * d * d + 2 * d + 1) / (6 * (2 * d + 1))
    for ra in (1.01e-6, 3e-6, 1e-5):
        a = ra / r
        assert ra > linear._ASYMPTOTIC_LIMIT  # the verified crossings, not the expansion
        assert _small_rate_kappa(a, d) == pytest.approx(linear._critical_kappa(a, d), rel=3 * ra * ra)


def test_gil_small_rate_expansion_d0_is_the_critical_beta_asymptote():
    """d = 0: κ = 2a(1 + a/6) ⇔ β_crit = ½ − 1/(24μ) + O(μ⁻²) (module docstring of dfa.analysis.linear, c_0 = 1/24)."""
    a = 1e-7
    kappa = _small_rate_kappa(a, 0)
    assert a / kappa == pytest.approx(0.5 - kappa / 24, rel=1e-13)


@settings(max_examples=8, deadline=None)
@given(st.floats(-16.0, 1.0), st.integers(0, 12))
def test_gil_linear_bound_property_stable_below_unstable_above_mpmath(log_a, d):
    _check(10.0**log_a, d)


def test_gil_critical_stiffness_huge_mass_is_b_over_t_half_plus_d():
    """m = 1e30 kg: a = bT/m = 1e-33, K_crit = b/(T(½ + d)) to double precision (formerly: 'please report')."""
    assert critical_stiffness(1e30, 1.0, 1e-3) == pytest.approx(2000.0, rel=1e-15)
    assert critical_stiffness(1e30, 1.0, 1e-3, wall=Wall.of(1.0, delay=3)) == pytest.approx(1000.0 / 3.5, rel=1e-15)


def test_gil_cli_stiffness_huge_mass_prints_a_finite_k_linear(capsys):
    """The exact linear bound is a closed form: at speed 0 `dfa stiffness` states it without the simulated search
    (which took 20 s of this test at 0.1 m/s and is not what it checks)."""
    argv = ["stiffness", "--mass", "1e30", "--damping", "1", "--coulomb", "0", "--resolution", "1e-6"]
    argv += ["--period", "1e-3", "--delay", "3", "--velocity", "0", "--json"]
    assert main(argv) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["k_linear"]["value"] == pytest.approx(1000.0 / 3.5, rel=1e-12)
    assert "k_gil" not in rec  # one key per concept: the exact linear bound is k_linear
