"""Exact linear stability of the sampled wall with a controller (issue 15 item 1): dfa.analysis.linear_wall, dfa.analysis.linear.

Checked against: 50-digit mpmath (divided differences of e^{−u}); ``control.c2d`` (the ZOH
pulse transfer with amplifier lag) and ``control.c2d`` + ``control.feedback`` (the closed
loop, built independently here from the controller's sample-level definition); the
spring-only functions of dfa.analysis.linear (same numbers, bit for bit, for a spring controller;
the same K_crit to 1e-9 by the general ray algorithm); the linear rule
K < (b + B)/(T(d + ½)) as bT/m → 0 (issue 15: within 1 % for bT/m <= 0.005 at m = 1 kg,
T = 1 ms; Diolaiti et al. 2006 for B = 0); the amplifier lag acting as an extra delay,
K ≈ b/(T(d + ½) + τ_a); the Colgate–Schenkel line b = KT/2 + |B| (Colgate & Schenkel 1997)
lying inside the linear bound; a dense spectral-radius scan where the stable set has
several intervals.
"""

import json
import math

import control
import mpmath
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from result_json import assert_json_from_fields, written

import dfa
from dfa import Wall, WallParams
from dfa.analysis.colgate_schenkel import colgate_schenkel_damping
from dfa.analysis.linear import characteristic_polynomial, critical_stiffness, linear_stable, spectral_radius
from dfa.analysis.linear_wall import (
    LinearStatus,
    _Ray,
    _ray_intervals,
    amplifier_zoh_coefficients,
    stable_region,
    stable_stiffness,
)
from dfa.core.divdiff import exp_divided_difference
from dfa.errors import DFATypeError, DFAValueError
from dfa.jsonable import dumps

M, T = 1.0, 1e-3  # the anchor device: m = 1 kg, T = 1 ms


# ---------------------------------------------------------------- independent loop: python-control


def _control_loop(mu: float, beta: float, p: WallParams):
    """Closed loop of μξ'' + βξ' = φ_A, α φ_A' = φ_cmd − φ_A, φ_cmd = −H ξ, from control.c2d and control.feedback."""
    den = np.polymul([p.lag, 1.0], [mu, beta, 0.0]) if p.lag > 0.0 else np.array([mu, beta, 0.0])
    gd = control.c2d(control.tf([1.0], den), 1.0, method="zoh")
    zinv = control.tf([1.0], [1.0, 0.0], 1.0)
    filt = control.tf([1.0], [1.0], 1.0)
    if p.cutoff is not None:
        a = p.filter_pole
        filt = control.tf([1.0 - a], [1.0, -a], 1.0)  # (1 − a) z^{−1}/(1 − a z^{−1})
    h = 1 + p.damping * (1 - zinv) * filt
    for _ in range(p.delay):
        h = h * zinv
    return control.feedback(gd, h)


def _control_rho(mu: float, beta: float, p: WallParams) -> float:
    return float(np.max(np.abs(control.poles(_control_loop(mu, beta, p)))))


controllers = st.builds(
    WallParams.of,
    damping=st.one_of(st.just(0.0), st.floats(0.0, 5.0)),
    delay=st.integers(0, 3),
    cutoff=st.one_of(st.none(), st.floats(0.005, 0.45)),
    lag=st.one_of(st.just(0.0), st.floats(1e-3, 10.0)),
)


# ---------------------------------------------------------------- divided differences and the plant
@pytest.mark.parametrize(
    "nodes",
    [
        (0.0, 0.0, 0.0, 0.0),
        (0.0, 1e-7, 2e-7, 0.3),
        (0.0, 0.0, 2.0, 2.0000001),
        (0.4, 0.9, 1.3, 1.3),
        (3.0, 50.0, 53.0, 53.0),
    ],
)
def test_exp_divided_difference_mpmath(nodes):
    """f[x₀..x_n] of e^{−u} to 1e-14 relative of its value, against the mean of f^{(n)}/n! over the simplex (mpmath)."""
    n = len(nodes) - 1

    def dd(v):
        return mpmath.e ** (-v[0]) if len(v) == 1 else (dd(v[1:]) - dd(v[:-1])) / (v[-1] - v[0])

    with mpmath.workdps(250):  # the recursion on nodes made distinct by 1e-50: error ~1e-50, cancellation < 200 digits
        ref = dd([mpmath.mpf(v) + mpmath.mpf(10) ** -50 * (i + 1) for i, v in enumerate(nodes)])
    got = exp_divided_difference(*nodes)
    assert got == pytest.approx(float(ref), rel=1e-14, abs=0.0)
    assert (-1) ** n * got > 0.0


@pytest.mark.parametrize(
    ("a", "lag"),
    [(0.0, 1.0), (1e-3, 0.3), (2.0, 0.5), (2.0, 0.5000001), (1e-6, 1e3), (0.7, 1.0 / 0.7), (10.0, 0.05)],
)
def test_zoh_with_amplifier_lag_vs_control_c2d(a, lag):
    """n₂, n₁, n₀, p, q equal control.c2d of 1/((αs + 1)(s² + as)) (μ = 1) to 1e-9 (coincident poles included)."""
    den = np.polymul([lag, 1.0], [1.0, a, 0.0])
    d = control.c2d(control.tf([1.0], den), 1.0, method="zoh")
    num, dd_ = np.asarray(d.num[0][0], dtype=float), np.asarray(d.den[0][0], dtype=float)
    n2, n1, n0, p, q = amplifier_zoh_coefficients(a, lag)
    np.testing.assert_allclose([n2, n1, n0], num / dd_[0], rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(np.poly([1.0, p, q]), dd_ / dd_[0], rtol=1e-12, atol=1e-15)


def test_zoh_with_amplifier_lag_limits():
    """α → 0: the device alone (c₁, c₀, n₀ ≈ pα²); α → ∞ at a = 0: (1, 4, 1)/(6α), the ZOH of 1/(α s³).

    No cancellation at either end: n₀ ≈ pα² = 1.35e-25 is resolved to 1e-6 next to c₁ ≈ 0.28.
    """
    c1 = (math.expm1(-2.0) + 2.0) / 4.0
    c0 = (1.0 - math.exp(-2.0) - 2.0 * math.exp(-2.0)) / 4.0
    n2, n1, n0, _, q = amplifier_zoh_coefficients(2.0, 1e-12)
    assert (n2, n1, q) == pytest.approx((c1, c0, 0.0), rel=1e-10, abs=1e-300)
    assert n0 == pytest.approx(math.exp(-2.0) * 1e-24, rel=1e-6)
    n2, n1, n0, p, q = amplifier_zoh_coefficients(0.0, 1e12)
    np.testing.assert_allclose(np.array([n2, n1, n0]) * 6e12, [1.0, 4.0, 1.0], rtol=1e-10)
    assert p == 1.0 and q == math.exp(-1e-12)


# ---------------------------------------------------------------- the closed loop vs python-control
@settings(max_examples=40)
@given(mu=st.floats(0.01, 1e4), beta=st.floats(0.0, 10.0), p=controllers)
def test_closed_loop_roots_vs_control_feedback(mu, beta, p):
    """Spectral radius of the closed loop equals that of control.c2d + control.feedback (built here) to 1e-6."""
    ours = spectral_radius(mu, beta, wall=p)
    theirs = _control_rho(mu, beta, p)
    assert ours == pytest.approx(theirs, abs=1e-6)
    if abs(theirs - 1.0) > 1e-6:
        assert linear_stable(mu, beta, wall=p) == (theirs < 1.0)


@settings(max_examples=30)
@given(
    b=st.floats(0.05, 50.0),
    big_b=st.floats(0.0, 20.0),
    d=st.integers(0, 3),
    fc=st.one_of(st.none(), st.floats(5.0, 450.0)),
    fbw=st.one_of(st.none(), st.floats(50.0, 5000.0)),
)
def test_critical_stiffness_boundary_vs_control_feedback(b, big_b, d, fc, fbw):
    """At K_crit(1 ∓ 1e-5) the independent python-control loop is stable / unstable (B, f_c, τ_a fixed as K varies)."""
    c = Wall.of(1.0, big_b, d, fc, fbw)
    r = stable_stiffness(M, b, T, c)
    assert r.status in (LinearStatus.INTERVAL, LinearStatus.NEVER)  # what this family shows (no gaps seen)
    if r.status is LinearStatus.NEVER:
        k = 1.0 / T  # unstable at small and large K: spot checks
        for kk in (1e-3 * k, k, 1e3 * k):
            assert _control_rho(M / (kk * T * T), b / (kk * T), Wall.of(kk, big_b, d, fc, fbw).params(T)) >= 1.0
        return
    assert r.k_crit == pytest.approx(critical_stiffness(M, b, T, wall=c), rel=1e-9)
    for f, stable in ((1.0 - 1e-5, True), (1.0 + 1e-5, False)):
        k = r.k_crit * f
        rho = _control_rho(M / (k * T * T), b / (k * T), Wall.of(k, big_b, d, fc, fbw).params(T))
        assert (rho < 1.0) == stable, (k, rho)


# ---------------------------------------------------------------- the spring: unchanged
@pytest.mark.parametrize("d", [0, 1, 3])
def test_spring_controller_gives_spring_results_bit_identical(d):
    """Wall.of(K, delay=d) / WallParams.of(delay=d): the same numbers as the spring-only functions, bit for bit."""
    p = WallParams.of(delay=d)
    mus, betas = np.array([0.5, 3.0, 200.0]), np.array([0.1, 0.6, 2.0])
    assert np.array_equal(spectral_radius(mus, betas, wall=WallParams.of(delay=d)), spectral_radius(mus, betas, wall=p))
    assert np.array_equal(
        characteristic_polynomial(2.0, 0.3, wall=WallParams.of(delay=d)), characteristic_polynomial(2.0, 0.3, wall=p)
    )
    for m, b, t in ((1.0, 2.0, 1e-3), (0.01, 5.0, 0.01), (0.1, 1e-4, 1e-3)):
        assert critical_stiffness(m, b, t, wall=Wall.of(1.0, delay=d)) == critical_stiffness(
            m, b, t, wall=Wall.of(123.0, delay=d)
        )


@pytest.mark.parametrize("d", [0, 1, 2, 4])
@pytest.mark.parametrize("a", [1e-4, 0.01, 1.0, 3.0, 5.0, 100.0])
def test_ray_algorithm_reproduces_spring_bound(a, d):
    """The general ray algorithm (stable_stiffness) finds the spring's K_crit of dfa.analysis.linear to 1e-9: one interval."""
    r = stable_stiffness(1.0, a, 1.0, Wall.of(1.0, delay=d))
    assert r.status is LinearStatus.INTERVAL
    assert r.k_crit == pytest.approx(critical_stiffness(1.0, a, 1.0, wall=Wall.of(1.0, delay=d)), rel=1e-9)


# ---------------------------------------------------------------- anchors of issue 15
@pytest.mark.parametrize("d", [0, 1, 2, 3])
@pytest.mark.parametrize("b", [0.1, 1.0, 5.0])
@pytest.mark.parametrize("big_b", [0.0, 0.5, 2.0, 5.0])
def test_eq8_linear_rule_with_virtual_damper(b, big_b, d):
    """K_crit → (b + B)/(T(d + ½)) as bT/m → 0: within 1 % for bT/m <= 0.005 (and BT/m <= 0.005), m = 1 kg, T = 1 ms."""
    k = critical_stiffness(M, b, T, wall=Wall.of(1.0, big_b, d))
    assert k == pytest.approx((b + big_b) / (T * (d + 0.5)), rel=0.01)


@pytest.mark.parametrize("d", [0, 1, 2])
@pytest.mark.parametrize("b", [1.0, 5.0])
@pytest.mark.parametrize("tau_over_t", [0.01, 0.03, 0.1, 0.3])
def test_amplifier_lag_acts_as_extra_delay(b, tau_over_t, d):
    """K_crit ≈ b/(T(d + ½) + τ_a) for τ_a <= 0.3 T: within 0.5 %, while ignoring the lag errs by up to 37 %.

    Why 0.5 %: 1/(τ_a s + 1) = e^{−τ_a s}(1 + O((ωτ_a)²)) at the crossing frequency ω ≈ √(K/m)
    (ωτ_a <= 0.03 here, so below 0.1 %), plus the linear rule's own O(bT/m) error (at most
    0.22 % for bT/m <= 0.005, d <= 2, measured in the test above). Measured: at most 0.25 %.
    The ratio K_crit(τ_a)/K_crit(0) cancels the rule's own error: it equals
    T(d + ½)/(T(d + ½) + τ_a) to 0.1 % (measured 0.042 %).
    """
    tau = tau_over_t * T
    k = critical_stiffness(M, b, T, wall=Wall.of(1.0, 0.0, d, amplifier_bandwidth=1.0 / (2 * math.pi * tau)))
    assert k == pytest.approx(b / (T * (d + 0.5) + tau), rel=0.005)
    k0 = critical_stiffness(M, b, T, wall=Wall.of(1.0, 0.0, d))
    assert k / k0 == pytest.approx(T * (d + 0.5) / (T * (d + 0.5) + tau), rel=1e-3)  # the lag's own effect


@pytest.mark.parametrize("b", [0.5, 2.0, 5.0])
@pytest.mark.parametrize("frac", [0.0, 0.3, 0.8])
def test_colgate_schenkel_line_inside_linear_bound(b, frac):
    """Passivity (b > KT/2 + B, Colgate & Schenkel 1997, d = 0, no filter) is stricter than stability: they differ.

    The passivity line K_CS = 2(b − B)/T lies below the exact linear bound, which grows with B
    (≈ 2(b + B)/T as bT/m → 0) where the passivity line falls.
    """
    big_b = frac * b
    k_cs = 2.0 * (b - big_b) / T
    assert colgate_schenkel_damping(Wall.of(k_cs, big_b), T).damping_min == pytest.approx(b, rel=1e-12)
    k_lin = critical_stiffness(M, b, T, wall=Wall.of(1.0, big_b))
    assert k_lin > k_cs
    if big_b > 0.0:
        assert k_lin == pytest.approx(2.0 * (b + big_b) / T, rel=0.01)  # not 2(b − B)/T


def test_amplifier_lag_lowers_the_bound():
    """A slower amplifier never raises K_crit (the lag adds phase lag), for b = 2, B = 0.5, d = 1."""
    ks = [critical_stiffness(M, 2.0, T, wall=Wall.of(1.0, 0.5, 1, amplifier_bandwidth=f)) for f in (1e5, 1e4, 1e3, 1e2)]
    assert ks == sorted(ks, reverse=True)


# ---------------------------------------------------------------- several intervals, none, the K–B region
def _in_w(pz):
    """The coefficients in w = z − 1 of a polynomial in z (substitute z = w + 1, Horner)."""
    out = np.zeros(1)
    for c in pz:
        out = np.polyadd(np.polymul(out, [1.0, 1.0]), [c])
    return out[-len(pz) :]


def test_ray_with_several_intervals_vs_dense_scan():
    """A pair (P₀, Q) whose stable set has two intervals: its edges agree with a dense np.roots scan."""
    p0 = np.array([1.0, 1.069237163630643, -0.6243535942878822, -0.9539866170654505, 0.01508063820712044,
                   0.3891335795425942, 0.1831520815358585, 0.02654394356156959])  # fmt: skip
    q = np.array([2.2110571623347774, 0.011622013918882693, -0.7581270719825384, -1.0256240581930005,
                  -0.2011986994848956, -0.629343213365391])  # fmt: skip
    iv = _ray_intervals(_Ray(_in_w(p0), np.zeros(1), _in_w(q), 0), ())  # P₀ = z^0 A + 0 and Q, in w = z − 1
    assert len(iv) == 2 and iv[0][0] == 0.0
    ks = np.linspace(1e-4, 0.7, 7001)
    rho = np.array([max(abs(np.roots(np.polyadd(p0, k * q)))) for k in ks])
    inside = np.array([any(lo < k < hi for lo, hi in iv) for k in ks])
    edge = np.min(np.abs(ks[:, None] - np.array(iv).ravel()[None, :]), axis=1) < 2e-4
    assert np.array_equal((rho < 1.0)[~edge], inside[~edge])


def test_no_friction_no_damper_never_stable_but_virtual_damper_stabilises():
    """b = B = 0: unstable for every K (status 'never', K_crit 0); B > 0 alone gives a stable interval."""
    r = stable_stiffness(M, 0.0, T, Wall.of(1.0))
    assert r.status is LinearStatus.NEVER and r.k_crit == 0.0 and r.intervals.shape == (0, 2)
    r = stable_stiffness(M, 0.0, T, Wall.of(1.0, damping=2.0))
    assert r.status is LinearStatus.INTERVAL and r.k_crit == pytest.approx(2.0 / (T / 2), rel=0.01)


def test_stable_region_matches_stable_stiffness_and_is_json():
    """K_max(B) of stable_region is stable_stiffness's k_crit at each B; JSON strict (no NaN), statuses per B."""
    grid = [0.0, 0.5, 2.0, 10.0]
    reg = stable_region(M, 1.0, T, grid, wall=Wall.of(1.0, delay=1, filter_cutoff=100.0, amplifier_bandwidth=2000.0))
    for bb, k in zip(grid, reg.k_crit, strict=True):
        c = Wall.of(1.0, bb, 1, filter_cutoff=100.0, amplifier_bandwidth=2000.0)
        assert k == stable_stiffness(M, 1.0, T, c).k_crit
    data = json.loads(dumps(reg.to_dict()))
    assert (
        data["k_crit"] == written(reg.k_crit.tolist())
        and len(data["intervals"]) == 4
        and data["status"] == reg.status.value
    )
    assert data["device"] == {"mass": M, "damping": 1.0, "period": T}
    one = json.loads(dumps(reg.rows[1].to_dict()))
    assert one["wall"]["filter_cutoff"] == 100.0 and "stiffness" not in one["wall"]


# ---------------------------------------------------------------- bad input
def test_bad_input_names_the_parameter():
    with pytest.raises(TypeError, match="delay"):
        critical_stiffness(M, 1.0, T, delay=2, wall=Wall.of(1.0, delay=1))  # the delay lives in the wall
    with pytest.raises(DFATypeError, match="wall"):
        critical_stiffness(M, 1.0, T, wall=WallParams.of())  # dimensionless groups: the physical wall is needed
    with pytest.raises(DFAValueError, match="filter_cutoff"):
        stable_stiffness(M, 1.0, T, Wall.of(1.0, filter_cutoff=600.0))  # above Nyquist 500 Hz
    with pytest.raises(DFAValueError, match="virtual_damping"):
        stable_region(M, 1.0, T, [])
    with pytest.raises(DFAValueError, match="damping"):
        stable_region(M, 1.0, T, [-1.0])


def test_public_names():
    for name in ("stable_stiffness", "stable_region", "StiffnessIntervals", "StableRegion", "colgate_schenkel_damping"):
        assert name in dfa.__all__ and getattr(dfa, name) is not None


def _zoh_numerator_mpmath(a, lag, dps=60, as_float=True):
    """(n₂, n₁, n₀) of the ZOH of 1/((αs + 1)s(s + a)) from its step response by residues, ``dps`` digits (a > 0,
    a ≠ 1/α; the residues cancel to ~2·log10(1/a) digits); mpmath numbers unless ``as_float``."""
    with mpmath.workdps(dps):
        a, b = mpmath.mpf(a), 1 / mpmath.mpf(lag)

        def y(t):  # step response of b/(s(s + a)(s + b)): residues at 0 (double), −a, −b
            return (
                b * t / (a * b)
                - b * (a + b) / (a * b) ** 2
                + b * mpmath.e ** (-a * t) / (a**2 * (b - a))
                + (b * mpmath.e ** (-b * t) / (b**2 * (a - b)))
            )

        g = [y(k) - y(k - 1) if k else y(0) for k in range(4)]
        p, q = mpmath.e ** (-a), mpmath.e ** (-b)
        d1, d2 = -(1 + p + q), p + q + p * q
        out = (g[1], g[2] + d1 * g[1], g[3] + d1 * g[2] + d2 * g[1])
        return [float(x) for x in out] if as_float else list(out)


@pytest.mark.parametrize(
    ("a", "lag"),
    [
        (1e-3, 0.3),
        (2.0, 0.5000001),
        (0.7, 1.0 / 0.7 * (1 + 1e-9)),
        (10.0, 0.05),
        (1e-6, 1e3),
        (30.0, 1e-3),
        (0.05, 40.0),
    ],
)
def test_zoh_with_amplifier_lag_vs_mpmath(a, lag):
    """The one implementation (dfa.core.zohlag.amplifier_zoh, used by the DF and the linear bound) to 1e-13 relative."""
    got = amplifier_zoh_coefficients(a, lag)[:3]
    np.testing.assert_allclose(got, _zoh_numerator_mpmath(a, lag), rtol=1e-13, atol=0.0)


def test_stiffness_intervals_and_stable_region_json_from_their_fields():
    """StiffnessIntervals and StableRegion write the Result base's JSON: fields, json_properties, message."""
    r = stable_stiffness(0.1, 0.5, 1e-3, Wall.of(1.0, damping=1.0, delay=1, filter_cutoff=100.0))
    d = assert_json_from_fields(r)
    assert d["intervals"] == r.intervals.tolist() and d["wall"]["filter_cutoff"] == 100.0
    region = stable_region(1.0, 2.0, 1e-3, [0.0, 1.0])
    d = assert_json_from_fields(region)
    assert "rows" not in d and d["row_status"] == ["interval", "interval"]
    assert d["device"] == {"mass": 1.0, "damping": 2.0, "period": 1e-3}


# ---------------------------------------------------------------- accuracy where the poles cluster at z = 1
def _mp_divided_difference(nodes, mp):
    """f[x₀ … x₃] of f(u) = e^{−u}, repeated nodes by a 1e-60 spread at 200 digits (independent of dfa.core)."""
    with mp.workdps(200):
        x = [mp.mpf(v) + mp.mpf(10) ** -60 * i * (i + 1) for i, v in enumerate(nodes)]
        t = [mp.e ** (-v) for v in x]
        for k in range(1, len(x)):
            t = [(t[i + 1] - t[i]) / (x[i + k] - x[i]) for i in range(len(t) - 1)]
        return +t[0]


def _mp_rho(m, b, t, big_b, fc, fbw, d, k, mp):
    """Spectral radius of the loop at stiffness k in 60 digits, the polynomials built from the module docstring's
    formulas (plant by divided differences, filter, delay), not from dfa's elements."""
    m, b, t, big_b, k = (mp.mpf(v) for v in (m, b, t, big_b, k))
    mul = lambda x, y: [
        sum(x[i] * y[j - i] for i in range(len(x)) if 0 <= j - i < len(y)) for j in range(len(x) + len(y) - 1)
    ]
    a, p = b * t / m, mp.e ** (-b * t / m)
    if fbw is None:  # the device alone: (c₁z + c₀)/((z − 1)(z − p)), c₁ = (a − 1 + p)/a², c₀ = (1 − p − ap)/a²
        ng, dg = [(a - 1 + p) / a**2, (1 - p - a * p) / a**2], mul([1, -1], [1, -p])
    else:
        ba = 2 * mp.pi * mp.mpf(fbw) * t  # 1/α = 2π f_bw T
        dd = lambda *n: _mp_divided_difference(n, mp)
        ng = [-ba * dd(0, 0, a, ba), -ba * (dd(0, a, a, ba) + dd(a, a, ba, a + ba) + dd(0, a, ba, ba)
              + dd(a, ba, ba, a + ba)), -ba * dd(a, ba, a + ba, a + ba)]  # fmt: skip
        dg = mul(mul([1, -1], [1, -p]), [1, -(mp.e ** (-ba))])
    af = mp.e ** (-2 * mp.pi * mp.mpf(fc) * t)
    dh = mul([1] + [0] * (d + 1), [1, -af])
    h = [x + big_b / (k * t) * y for x, y in zip([1, -af, 0], [0, 1 - af, -(1 - af)], strict=True)]
    mu = m / (k * t * t)
    left, right = [mu * c for c in mul(dg, dh)], mul(ng, h)
    chi = [x + y for x, y in zip(left, [0] * (len(left) - len(right)) + right, strict=True)]
    return max(abs(r) for r in mp.polyroots(chi, maxsteps=400, extraprec=400))


@pytest.mark.parametrize(
    ("m", "b", "t", "big_b", "fc", "fbw", "d"),
    [
        (0.04322, 0.04703, 2.7729e-3, 0.23376, 0.528, 0.0804, 2),  # issue 27: 1.5e-6 high before (slow filter, amp)
        (1.0, 0.0, 1e-3, 0.023, 1.0001, 25.67015211159602, 5),  # b = 0, filter at its floor, α = 6.2, d = 5
        (1.0, 5e-4, 1e-3, 5e-4, 1.0, None, 2),  # crossing at θ = 6e-4 inside the first scan cell: was 'never'
        (1.0, 1.5e-4, 1e-3, 1.5e-4, 1.0, None, 0),  # (b + B)T/m = 3e-7, filter at its floor, no delay
    ],
)
def test_exact_linear_bound_within_1e_12_of_a_60_digit_check_where_poles_cluster_at_one(m, b, t, big_b, fc, fbw, d):
    """K_crit is computed in w = z − 1 (dfa.model.elements.CommandPolynomials): 1e-12 below it the 60-digit loop is
    stable, 1e-12 above it unstable (the expanded powers of z were 6e-7 high at the first point)."""
    mp = pytest.importorskip("mpmath")
    with mp.workdps(60):
        k = stable_stiffness(
            m, b, t, Wall.of(1.0, damping=big_b, delay=d, filter_cutoff=fc, amplifier_bandwidth=fbw)
        ).k_crit
        assert _mp_rho(m, b, t, big_b, fc, fbw, d, k * (1 - 1e-12), mp) < 1
        assert _mp_rho(m, b, t, big_b, fc, fbw, d, k * (1 + 1e-12), mp) > 1


@settings(max_examples=60, deadline=None)
@example(rate=1e-6, share=0.5, cutoff=1e-3, delay=2)  # found by review: 'never' for a loop stable up to 0.398 N/m
@given(
    rate=st.floats(1e-7, 1e-2),
    share=st.floats(0.0, 1.0),
    cutoff=st.one_of(st.none(), st.floats(1e-3, 0.4)),
    delay=st.integers(0, 4),
)
def test_slow_poles_status_agrees_with_the_spectral_radius_on_both_sides_of_k_crit(rate, share, cutoff, delay):
    """Slow filters and tiny rates (the crossing deep inside the first scan cell): 'interval' is stable at K/2 and
    unstable at 2K; 'never' is unstable at every K of a wide grid (it was reported for a stable loop)."""
    from dfa.analysis.linear_wall import controlled_spectral_radius

    m, t = 1.0, 1e-3
    b, big_b = share * rate * m / t, (1 - share) * rate * m / t
    wall = Wall.of(1.0, damping=big_b, delay=delay, filter_cutoff=None if cutoff is None else cutoff / t)
    r = stable_stiffness(m, b, t, wall)

    def rho(k):
        return controlled_spectral_radius(m / (k * t * t), b / (k * t), wall.with_stiffness(k).params(t))

    if r.status is LinearStatus.INTERVAL:
        assert rho(0.5 * r.k_crit) < 1.0 < rho(2.0 * r.k_crit)
    elif r.status is LinearStatus.NEVER:
        assert all(rho(k) >= 1.0 for k in np.geomspace(1e-12, 1e6, 73) * m / t**2)


def test_linear_crossing_cell_whose_ends_agree_in_sign_gives_the_end_nearer_zero():
    """The exact linear bound's crossing angles (linear_wall._candidate_angles, _roots_in_cells): a grid cell
    whose ends agree in sign (Im(P0 conj Q) within rounding of 0 at an end) is
    that end, not a brentq ValueError ('f(a) and f(b) must have different signs', found by `dfa require` with a
    damper, filter and delay, issue 41); a cell with a sign change gives a root where Im(P0 conj Q) vanishes."""
    from dfa.analysis.linear_wall import _im_part, _roots_in_cells

    ray = _Ray(np.array([1.0, -0.4, 0.3]), np.zeros(1), np.array([1.0, 0.2]), 0)  # P₀ = A, Q in w
    thetas = np.linspace(0.01, 3.1, 2000)
    g = _im_part(ray, thetas)
    i = int(np.nonzero(g[:-1] * g[1:] < 0.0)[0][0])
    a, b = thetas[[i, i + 5]], thetas[[i + 1, i + 6]]  # a sign change; then one sign at both ends
    fa, fb = _im_part(ray, a), _im_part(ray, b)
    root, end = _roots_in_cells(ray, a, b, fa, fb)
    assert thetas[i] <= root <= thetas[i + 1] and abs(float(_im_part(ray, root))) < 1e-12
    assert fa[1] * fb[1] > 0 and end == (a[1] if abs(fa[1]) <= abs(fb[1]) else b[1])


@pytest.mark.parametrize(
    ("b", "big_b", "fc", "fbw", "d"),
    [(0.01, 1.0, 200.0, None, 1), (0.5, 2.0, 50.0, 300.0, 3), (0.01, 1.0, 200.0, None, 12), (2.0, 0.0, None, 80.0, 5)],
)
def test_linear_crossing_angles_match_a_dense_scan_and_k_crit_the_spectral_radius(b, big_b, fc, fbw, d):
    """The crossing angles of the exact linear bound (linear_wall._candidate_angles: sign changes of Im(P0 conj Q)
    on its grid, bisected to neighbouring floats all at once) against an independent scan 16 times denser: every
    sign change of the dense scan lies within one of its cells of a candidate; and K_crit against a bisection of
    the spectral radius of the closed loop (rho(K) = 1 to 1e-12 relative), which uses no crossing at all: the
    same to 1e-9 relative."""
    from dfa.analysis.linear_wall import _candidate_angles, _im_part, _ray, controlled_spectral_radius

    m, t = 0.25, 1.0 / 3000.0
    wall = Wall.of(1.0, damping=big_b, delay=d, filter_cutoff=fc, amplifier_bandwidth=fbw)
    p = wall.params(t)
    ray = _ray(b * t / m, big_b * t / m, p)
    cand = np.sort(_candidate_angles(ray))
    dense = np.linspace(0.0, math.pi, 16 * 512 * (len(ray.a) + d))[1:]  # deg P₀ + 1 = deg A + d + 1
    g = _im_part(ray, dense)
    for i in np.nonzero(g[:-1] * g[1:] < 0.0)[0]:
        assert np.any((cand >= dense[i] - 1e-12) & (cand <= dense[i + 1] + 1e-12)), dense[i]
    r = stable_stiffness(m, b, t, wall)

    def rho(k):
        return controlled_spectral_radius(m / (k * t * t), b / (k * t), wall.with_stiffness(k).params(t))

    lo, hi = 0.5 * r.k_crit, 2.0 * r.k_crit
    assert rho(lo) < 1.0 < rho(hi)
    while hi - lo > 1e-12 * hi:
        lo, hi = (0.5 * (lo + hi), hi) if rho(0.5 * (lo + hi)) < 1.0 else (lo, 0.5 * (lo + hi))
    assert r.k_crit == pytest.approx(lo, rel=1e-9)
