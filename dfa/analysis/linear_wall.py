"""Exact linear stability of the sampled wall with a controller: damper, filter, delay, amplifier lag (issue 15).

The device without encoder and Coulomb friction, μ ξ'' + β ξ' = φ_A (paper
eq. 4-5 with σ = 0 and no quantizer; time in samples, Table 1 groups), driven
through the amplifier lag α φ_A' = φ_cmd − φ_A by the held command of the
controller of :mod:`dfa.model.wall` (dimensionless groups β_B, d, ν_c, α)::

    φ_cmd = −H(z) ξ,   H(z) = z^{−d} [1 + β_B (1 − z^{−1}) F(z)],
    F(z) = (1 − a_f) z^{−1}/(1 − a_f z^{−1}),  a_f = e^{−2π ν_c}   (F = 1 without filter).

Plant. With a = β/μ = bT/m, p = e^{−a}, and for α > 0 also b_α = 1/α, q = e^{−b_α},
the exact ZOH pulse transfer of 1/((αs + 1)(μs² + βs)) is (derivation:
1/(αs + 1) = 1 − αs/(αs + 1) splits the plant into the device alone, whose pulse
transfer is (c₁z + c₀)/(μ(z − 1)(z − p)) of :mod:`dfa.analysis.linear`, minus
1/(μ(s + a)(s + b_α)); collecting the residues, every coefficient is a
divided difference of f(u) = e^{−u}, :mod:`dfa.core.divdiff`)::

    G(z) = (n₂z² + n₁z + n₀)/(μ (z − 1)(z − p)(z − q)),
    n₂ = −b_α f[0, 0, a, b_α],       n₀ = −b_α f[a, b_α, a + b_α, a + b_α],
    n₁ = −b_α (f[0, a, a, b_α] + f[a, a, b_α, a + b_α] + f[0, a, b_α, b_α] + f[a, b_α, b_α, a + b_α]).

Every third divided difference of e^{−u} is negative, so n₂, n₁, n₀ > 0 are sums
of positive terms: no cancellation for any α (tiny α: n₂ → c₁, n₁ → c₀, n₀ → 0;
huge α: (n₂, n₁, n₀) → (1, 4, 1)/(6α) at a = 0, the ZOH of 1/(αμs³)).
``tests/test_controlled_linear.py`` compares them with ``control.c2d``. For α so
small that 1/α overflows (α < 1e-308) the lag is dropped: its effect is below rounding.

Loop. With N_H = N₁ + β_B N₂ over D_H (no filter: N₁ = z, N₂ = z − 1,
D_H = z^{d+1}; filter: N₁ = z(z − a_f), N₂ = (1 − a_f)(z − 1), D_H = z^{d+1}(z − a_f))
the closed-loop characteristic polynomial is χ(z) = μ D_G D_H + N_G (N₁ + β_B N₂).
A filter without a damper (β_B = 0) filters nothing and is left out: its own decaying
mode a_f is not a pole of the loop, and the spring's polynomial is unchanged.

The stiffness ray at fixed physical damper. With the device, period, B, f_c and
τ_a fixed, K enters only through κ = KT²/m = 1/μ, because β_B κ = BT/m =: a_B
is fixed: κχ = P₀(z) + κ Q(z), P₀ = D_G D_H + a_B N_G N₂, Q = N_G N₁, with
deg Q < deg P₀, so every root moves continuously with κ and the roots go to
infinity as κ → ∞ (unstable for large K). Stability can change only at a κ > 0
where a root lies on the unit circle, i.e. κ = −P₀(z)/Q(z) real and positive on
|z| = 1: at z = −1, and at z = e^{jθ} where Im(P₀ Q̄) = 0 — the unit-circle roots
of R(z) = P₀(z) z^n Q(1/z) − Q(z) z^n P₀(1/z) (n = deg P₀), joined with the sign
changes of Im(P₀ Q̄) on a dense θ grid (512(n + 1) cells, the first refined geometrically to θ = 1e-10),
each polished by bracketing: every cell of the grid whose ends differ in sign holds a root and is bisected,
all cells at once as arrays, until its ends are neighbouring floats (no crossing between grid cells is
missed, and none is found less tightly than to the last bit at which Im(P₀ Q̄) changes sign). Between
consecutive candidates the stability is constant; it is decided by the spectral
radius at the geometric mean, and the resulting stable set (one interval, several,
or none) is checked against the spectral radius on an independent geometric grid
of κ. z = 1 is a root of P₀ (the free mass): it moves inside for small κ when
a + a_B > 0.

Accuracy. Every polynomial is built and evaluated in w = z − 1 (the elements' own basis,
:class:`dfa.model.elements.CommandPolynomials`): each factor z − r is w + (1 − r) with 1 − r from
``expm1``, products of such factors have positive coefficients, and on the circle w = e^{jθ} − 1 is
formed without cancellation, so P₀, Q and the spectral radius keep full relative accuracy where the
device's, filter's and amplifier's poles cluster near z = 1. Expanded in powers of z they lost up to
six digits there (K_crit 6e-7 high with a 0.5 Hz filter and a 0.08 Hz amplifier at T = 2.8 ms);
``tests/test_controlled_linear.py`` checks K_crit to 1e-12 against a 60-digit construction.

Long delays. The delay's z^d is never expanded in w: P₀ = z^d A + B with A = D_G D_H/z^d, B = a_B N_G N₂ and Q
of low degree in w, and on the circle z^d = e^{jdθ} multiplies A(w) (exact at θ = 0 and π). Expanded as
(w + 1)^d its terms reach 3^d at z = −1 (all digits lost from d ≈ 32: a false 'never', K_crit = 0). The
spectral radius is that of a state matrix: (B + κQ)/A in controllable canonical form in w closed through a
d-sample shift register (exact zeros and ones), its eigenvalues taken as w = z − 1 as before; the angle grid
keeps 512(n + 1) cells, n = d + deg A, for the d oscillations of e^{jdθ}. For every accepted delay (<= 100
samples) the bound agrees with an independent shift-register loop to 1e-8
(``tests/test_linear_wall_long_delay.py``); for small d the numbers are those of the full expansion to rounding.

Tiny rates. For (b + B)T/m <= :data:`SERIES_RATE` = 1e-4 the roots cluster at z = 1
(|z| − 1 = O((b + B)T/m)) and the crossing lies at θ = O(√rate), deep inside the first
cell of the angle scan (which is refined geometrically down to θ = 1e-10 for it); in
powers of z the float crossings lost digits there (1e-11 relative at 1e-4, 1e-8 at 1e-7,
all below), in w they agree with the series where both are found. There κ_crit comes from the Taylor series of
Φ(s) = P₀/Q at z = e^s (:func:`series_kappa`; every factor expanded in w = z − 1
without cancellation): Im Φ(jθ) = 0, κ = −Re Φ(jθ) is solved as a series in θ²,
κ_crit = (a ρ_L + a_B) κ̃, κ̃ → 1/(½ + d + α) as the rate → 0, i.e.
K_crit → (b + B)/(T(½ + d + τ_a/T)) (the filter drops out at leading order). K is
formed from (bρ_L + B)/T, so a rate that underflows (m = 1e300 kg) still gives
the positive limit. Checked against 60+ digit mpmath for rates 1e-16 … 1e-4 in
``tests/test_controlled_linear_small_rate.py`` (the float path was off by up to
3e-8 relative at the catalogue devices' rates, ~1e-5).

Examples
--------
>>> r = stable_stiffness(1.0, 2.0, 1e-3, Wall.of(1.0, damping=1.0))
>>> r.status.value, round(r.k_crit, 1)          # ≈ (b + B)/(T/2) = 6000 N/m as bT/m → 0
('interval', 5996.0)
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from ..checks import (
    check_beta,
    check_mu,
    check_nonnegative,
    check_positive,
    check_rate,
    check_real_array,
    check_type,
)
from ..core.zoh import zoh_coefficients
from ..core.zohlag import amplifier_zoh
from ..errors import DFAError, DFAValueError
from ..grids import geometric_grid
from ..model.elements import unit_circle_w
from ..model.wall import Wall, WallParams
from ..results.linear import StableRegion as StableRegion
from ..results.linear import StiffnessIntervals as StiffnessIntervals
from ..results.status import LinearStatus

__all__ = [
    "LinearStatus",
    "StiffnessIntervals",
    "StableRegion",
    "amplifier_zoh_coefficients",
    "controlled_characteristic_polynomial",
    "stable_stiffness",
    "stable_region",
]


# ----------------------------------------------------------------------------- plant and controller polynomials
def amplifier_zoh_coefficients(a: float, lag: float) -> tuple[float, float, float, float, float]:
    """Numerator (n₂, n₁, n₀) and poles p, q of the ZOH pulse transfer of 1/((αs + 1) s (s + a)) (module docstring).

    Parameters
    ----------
    a : float
        a = β/μ = bT/m >= 0 (device pole, per sample).
    lag : float
        Amplifier time constant α = τ_a/T > 0, samples.

    Returns
    -------
    tuple of float
        (n₂, n₁, n₀, p, q): G(z) = (n₂z² + n₁z + n₀)/(μ(z − 1)(z − p)(z − q)), p = e^{−a}, q = e^{−1/α}.

    Examples
    --------
    >>> [round(c * 6e9, 6) for c in amplifier_zoh_coefficients(0.0, 1e9)[:3]]   # ZOH of 1/(α s³)
    [1.0, 4.0, 1.0]
    """
    n2, n1, n0, p, q = amplifier_zoh(float(a), 1.0 / lag)  # the one implementation (dfa.core.zohlag)
    return float(n2), float(n1), float(n0), float(p), float(q)


def _plant(a: float, wall: WallParams, mu: float) -> tuple[np.ndarray, np.ndarray]:
    """(N_G, D_G) of G(z) = N_G/(μ D_G) in w = z − 1, highest power first: an element's between hold and device
    (:meth:`dfa.model.wall.WallParams.plant`, the amplifier lag), else the device alone (:mod:`dfa.core.zoh`:
    N_G = c₁z + c₀ = c₁w + φ₁(a), D_G = (z − 1)(z − p) = w(w + 1 − p))."""
    out = wall.plant(float(a), mu)
    if out is not None:
        return out
    c1, c0, _p = zoh_coefficients(float(a))
    return np.array([c1, c1 + c0]), np.array([1.0, -math.expm1(-float(a)), 0.0])


def _command(wall: WallParams) -> tuple[np.ndarray, np.ndarray, np.ndarray, int]:
    """(N₁, N₂, D_H/z^d, d) with H = (N₁ + β_B N₂)/D_H (module docstring) in w = z − 1, highest power first: the
    elements' polynomials (:meth:`dfa.model.wall.WallParams.command`); the delay's z^d is kept apart (never
    expanded as (w + 1)^d, whose terms reach 3^d on the circle: all digits lost from d ≈ 32 on)."""
    h = wall.command()
    return h.spring, h.velocity, h.denominator, int(h.delay)


class _Ray(NamedTuple):
    """κχ = P₀ + κQ with P₀ = z^d A + B: A, B, Q in w = z − 1, highest power first (deg B, deg Q < deg A)."""

    a: np.ndarray
    b: np.ndarray
    q: np.ndarray
    d: int


def _shift_z(pz: np.ndarray, d: int) -> np.ndarray:
    """z^d times a polynomial in z (highest power first): d zeros appended, exactly."""
    return np.concatenate([pz, np.zeros(d)])


def _to_z(pw: np.ndarray) -> np.ndarray:
    """The coefficients in z of a polynomial given in w = z − 1 (highest power first), by Horner's scheme."""
    out = np.zeros(1)
    for c in pw:
        out = np.polyadd(np.polymul(out, [1.0, -1.0]), [c])
    return np.asarray(out[-len(pw) :], dtype=float)


def controlled_characteristic_polynomial(mu: float, beta: float, params: WallParams) -> np.ndarray:
    """χ(z) = μ D_G D_H + N_G (N₁ + β_B N₂) of the sampled loop with a controller (module docstring).

    Parameters
    ----------
    mu, beta : float
        Dimensionless mass μ = m/(KT²) > 0 and damping β = b/(KT) >= 0 (paper Table 1).
    params : WallParams
        β_B, d, ν_c, α.

    Returns
    -------
    numpy.ndarray
        Coefficients, highest power first (degree d + 3 without filter or lag, one more for each).

    Examples
    --------
    >>> controlled_characteristic_polynomial(1.0, 0.0, WallParams.of(damping=0.5)).tolist()
    [1.0, -1.25, 1.5, -0.25]

    (z(z − 1)² + (½z + ½)(1.5z − 0.5) at μ = 1, β = 0, β_B = ½.)
    """
    r = _characteristic_ray(mu, beta, params)
    return np.asarray(np.polyadd(_shift_z(_to_z(r.a), r.d), _to_z(r.b)))


def _characteristic_ray(mu: float, beta: float, params: WallParams) -> _Ray:
    """χ = z^d A + B of :func:`controlled_characteristic_polynomial`, A and B in w = z − 1 (checked inputs)."""
    m, b = check_mu(mu), check_beta(beta)
    params = check_type("params", params, WallParams, "give a dfa.WallParams")
    ng, dg = _plant(b / m, params, m)
    n1, n2, dh, d = _command(params)
    return _Ray(m * np.polymul(dg, dh), np.polymul(ng, np.polyadd(n1, params.damping * n2)), np.zeros(1), d)


def _rho(ray: _Ray, kappa: Any) -> np.ndarray:
    """Spectral radius of z^d A + B + κQ at each κ, from the eigenvalues w = z − 1 of a state matrix minus I.

    The loop 1 + z^{−d}(B + κQ)/A = 0 as a state space: (B + κQ)/A (strictly proper) in controllable canonical
    form in w (the companion of A in w, as before: roots clustered near z = 1 keep their accuracy), closed
    through a d-sample shift register (the delay: exact zeros and ones, its z^d never expanded). Its
    characteristic polynomial is z^d A + B + κQ over A's leading coefficient, for any d >= 0.
    """
    kappa = np.atleast_1d(np.asarray(kappa, dtype=float))
    lead = ray.a[0]
    m, d = len(ray.a) - 1, ray.d
    if max(len(ray.b), len(ray.q)) > m:
        raise DFAError(f"the loop's polynomials {ray!r} are not strictly proper: please report this as a bug")
    c = np.zeros((kappa.size, m))
    for poly, scale in ((ray.b, np.ones_like(kappa)), (ray.q, kappa)):
        c[:, m - len(poly) :] += scale[:, None] * (poly / lead)[None, :]
    n = m + d
    mat = np.zeros((kappa.size, n, n))
    mat[:, 0, :m] = -ray.a[1:] / lead
    mat[:, np.arange(1, m), np.arange(m - 1)] = 1.0
    if d == 0:
        mat[:, 0, :m] -= c  # the error e = −y fed back at once
    else:
        mat[:, 0, n - 1] = -1.0  # e = −(the register's last state) into the first state of (B + κQ)/A
        mat[:, m, :m] = c  # the register's first state takes y
        idx = np.arange(m, n)
        mat[:, idx, idx] = -1.0  # the shift minus I
        mat[:, idx[1:], idx[:-1]] = 1.0
    return np.asarray(np.max(np.abs(1.0 + np.linalg.eigvals(mat)), axis=-1))


def controlled_spectral_radius(mu: float, beta: float, params: WallParams) -> float:
    """Largest root modulus of :func:`controlled_characteristic_polynomial` (< 1: asymptotically stable)."""
    return float(_rho(_characteristic_ray(mu, beta, params), 0.0)[0])


# ----------------------------------------------------------------------------- the stiffness ray
#: (b + B)T/m at or below which :func:`stable_stiffness` takes K_crit from the Taylor series of the ray at z = 1
#: (:func:`series_kappa`): a closed expansion there, which needs no root finding near z = 1 (the float crossings
#: in w agree with it where both are found; the series' own truncation is checked below 1e-16).
SERIES_RATE = 1e-4

#: (b + B)T/m below which the float ray analysis is not used (its crossings near z = 1 are lost in rounding).
#: Kept as a guard: if the series did not converge there, :func:`stable_stiffness` would refuse. Its radius is
#: set by the poles of P₀/Q: the zeros of N_G (near z = −1 or beyond) and the filter pole a_f, >= 6e-3 from z = 1
#: for any accepted cutoff (>= 1e-3 cycles per sample), while the crossing is at θ <= 4.5e-4 below this rate; the
#: amplifier lag adds a zero, not a pole, so no accepted input has been found that reaches the refusal.
MIN_RESOLVED_RATE = 1e-7

_N_TERMS = 16  # Taylor terms of the ray at z = 1


def _poly_series(*coef: float) -> np.ndarray:
    out = np.zeros(_N_TERMS)
    out[: len(coef)] = coef
    return out


def _series_mul(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Power series x·y, truncated to :data:`_N_TERMS` terms."""
    return np.convolve(x, y)[:_N_TERMS]


def _series_div(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Power series x/y (y[0] != 0), truncated to :data:`_N_TERMS` terms."""
    out = np.zeros(_N_TERMS)
    for k in range(_N_TERMS):
        out[k] = (x[k] - np.dot(out[:k], y[k:0:-1])) / y[0]
    return out


def _taylor_at_one(a: float, a_b: float, wall: WallParams) -> tuple[np.ndarray, float]:
    """Taylor coefficients φ_k in s of Φ = z^d D_G/N_G + a_B N₂/N₁ at z = e^s (κ = −Φ on the ray), and ρ_L.

    From the elements' own polynomials in w = z − 1 (:func:`_plant`, :meth:`WallParams.command
    <dfa.model.wall.WallParams.command>`; free of cancellation), divided as power series in w, composed with
    w = e^s − 1 and multiplied by e^{sd}. φ₀ = 0 and φ₁ = a ρ_L + a_B, with a ρ_L = D_G'(0)/N_G(0) (ρ_L = 1
    for the device alone, φ₁(a)(1 − q)/(n₂ + n₁ + n₀) with an amplifier lag, → 1 as a → 0): ρ_L is returned
    for the caller's exact scaling, taken at a = 1e-300 when a is smaller (where it equals its limit to rounding).
    """
    a_eff = max(a, 1e-300)  # a that underflows (m = 1e300 kg) keeps ρ_L: its limit, to rounding
    ng, dg = _plant(a_eff, wall, 1.0)  # no hand spring here (series_kappa)
    h = wall.command()
    lw = _series_div(_poly_series(*dg[::-1]), _poly_series(*ng[::-1]))
    rho_l = float(lw[1] / a_eff)
    lw[1] = a * rho_l
    vw = _series_div(_poly_series(*h.velocity[::-1]), _poly_series(*h.spring[::-1]))
    ws = np.array([0.0] + [1.0 / math.factorial(k) for k in range(1, _N_TERMS)])  # w = e^s − 1
    lo, vo, pw = np.zeros(_N_TERMS), np.zeros(_N_TERMS), _poly_series(1.0)
    for k in range(_N_TERMS):
        lo, vo, pw = lo + lw[k] * pw, vo + vw[k] * pw, _series_mul(pw, ws)
    ed = np.array([float(h.delay) ** k / math.factorial(k) for k in range(_N_TERMS)])  # e^{sd}
    return _series_mul(ed, lo) + a_b * vo, rho_l


def series_kappa(a: float, a_b: float, wall: WallParams) -> tuple[float, float] | None:
    """(ρ_L, κ̃) with κ_crit = (a ρ_L + a_B) κ̃ from the Taylor series at z = 1, or None if it does not converge.

    On z = e^{jθ} with u = θ² = φ₁v, Im Φ = 0 and κ = −Re Φ read (φ_k real, :func:`_taylor_at_one`)::

        1 − φ₃v + φ₅φ₁v² − φ₇φ₁²v³ + … = 0,    κ/φ₁ = κ̃ = φ₂v − φ₄φ₁v² + φ₆φ₁²v³ − …

    whose root near v = 1/φ₃ is found by Newton's method; φ₁ only scales the corrections, so an
    underflowing (b + B)T/m costs no accuracy (the caller forms K from (bρ_L + B)/T · κ̃). As φ₁ → 0:
    κ̃ → φ₂/φ₃ = 1/(d + ½ + α), i.e. K_crit → (b + B)/(T(½ + d + τ_a/T)). None when φ₃ <= 0 or the
    last terms are not below 1e-17 of the first (a pole of the filter or lag too close to z = 1).
    """
    if wall.hand_stiffness > 0.0:
        return None  # a hand spring moves the device's pole off z = 1: the series' premise
    f, rho_l = _taylor_at_one(a, a_b, wall)
    if not f[3] > 0.0:
        return None
    e = f[1]
    j = np.arange(1, (_N_TERMS - 1) // 2 + 1)
    im = np.concatenate([[1.0], (-1.0) ** j * f[2 * j + 1] * e ** (j - 1)])  # in powers of v
    re = np.concatenate([[0.0], (-1.0) ** (j + 1) * f[2 * j] * e ** (j - 1)])
    poly = np.polynomial.polynomial
    v = 1.0 / f[3]
    for _ in range(60):
        step = poly.polyval(v, im) / poly.polyval(v, poly.polyder(im))
        v -= step
        if abs(step) <= 1e-16 * abs(v):
            break
    powers = v ** np.arange(im.size)
    ti, tr = np.abs(im * powers), np.abs(re * powers)
    if not (v > 0.0 and ti[-1] <= 1e-17 * ti[0] and tr[-1] <= 1e-17 * tr[1] and abs(step) <= 1e-14 * v):
        return None
    return rho_l, float(np.dot(re, powers))


def _ray(a: float, a_b: float, wall: WallParams, mu: float = 1.0) -> _Ray:
    """P₀ = z^d A + B and Q of κχ = P₀ + κQ at fixed a = bT/m and a_B = BT/m (module docstring); ``wall`` gives
    the elements' structure (a filter counts only with a damper, a_B > 0) and ``mu`` its μ (a hand spring's
    ω² = κ_h/μ = k_h T²/m is fixed on the ray)."""
    ng, dg = _plant(a, wall, mu)
    n1, n2, dh, d = _command(wall)
    return _Ray(np.polymul(dg, dh), a_b * np.polymul(ng, n2), np.polymul(ng, n1), d)


def _pq(ray: _Ray, theta: Any) -> tuple[Any, Any]:
    """(P₀ conj(Q), Q) at z = e^{jθ}, 0 <= θ <= π: A, B and Q in w = e^{jθ} − 1 (full accuracy near z = 1), the
    delay's z^d = e^{jdθ} on its own (exact at θ = 0 and π)."""
    t = np.asarray(theta, dtype=float)
    end = t >= math.pi
    w = np.where(end, -2.0 + 0j, unit_circle_w(np.where(end, 1.0, t)))
    zd = np.where(end, (-1.0) ** ray.d + 0j, np.exp(1j * ray.d * t))
    qw = np.polyval(ray.q, w)
    return (zd * np.polyval(ray.a, w) + np.polyval(ray.b, w)) * np.conj(qw), qw


def _im_part(ray: _Ray, theta: Any) -> Any:
    """Im(P₀ Q̄) at z = e^{jθ}."""
    return np.imag(_pq(ray, theta)[0])


def _candidate_angles(ray: _Ray) -> np.ndarray:
    """Angles θ in [0, π] where Im(P₀ Q̄)(e^{jθ}) = 0: roots of R on the circle (found in z, then polished in w),
    grid sign changes, 0 and π (P₀, Q in w = z − 1).

    Every sign change of Im(P₀ Q̄) between neighbouring points of the angle grid (512(n + 1) uniform cells on
    [0, π], the first one refined geometrically down to θ = 1e-10) is a cell holding a root, and every such cell
    is refined (:func:`_roots_in_cells`, all cells at once) by bisection on the sign until its ends are
    neighbouring floats: no crossing between grid cells is missed, and each is found to the last bit of θ at
    which Im(P₀ Q̄), evaluated in w, changes sign (at least as tight as the 1e-15 of the ``brentq`` it
    replaces). The roots of R on the circle (np.roots in z, P₀ = z^d A + B with the shift exact: a few digits)
    are polished by :func:`_polish_all`.
    """
    pz = np.polyadd(_shift_z(_to_z(ray.a), ray.d), _to_z(ray.b))
    n = len(pz) - 1
    qz = _to_z(ray.q)
    qp = np.concatenate([np.zeros(n + 1 - len(qz)), qz])
    r: np.ndarray = np.polysub(np.polymul(pz, qp[::-1]), np.polymul(qp, pz[::-1]))
    ends = [math.pi]
    p_one = ray.a[-1] + ray.b[-1]  # P₀(z = 1) = A(w = 0) + B(0)
    if abs(p_one) > 1e-9 * (np.abs(ray.a).sum() + np.abs(ray.b).sum()):
        ends.append(0.0)  # z = 1 is a root of P₀ for the device (κ = 0); a crossing only for other pairs
    found = []
    nz = np.nonzero(np.abs(r) > 0.0)[0]
    if nz.size:
        for z in np.roots(r[nz[0] :]):
            if abs(abs(z) - 1.0) < 1e-4 and abs(np.angle(z)) > 1e-12:
                found.append(abs(float(np.angle(z))))
    lin = np.linspace(0.0, math.pi, 512 * (n + 1))
    # and geometrically down to 1e-10 inside the first cell: slow poles put the crossing at θ ~ 1e-4 … 1e-3
    grid = np.concatenate([[0.0], geometric_grid(1e-10, lin[1], 400, endpoint=False), lin[1:]])
    g = _im_part(ray, grid)
    i = np.nonzero(g[1:-1] * g[2:] < 0.0)[0] + 1  # from the first θ > 0: Im(P₀ Q̄) = 0 at θ = 0
    cells = _roots_in_cells(ray, grid[i], grid[i + 1], g[i], g[i + 1])
    return np.concatenate([ends, _polish_all(ray, np.array(found)), cells])


def _roots_in_cells(ray: _Ray, a: np.ndarray, b: np.ndarray, fa: np.ndarray, fb: np.ndarray) -> np.ndarray:
    """A root of Im(P₀ Q̄) in each cell [a, b] whose end values ``fa``, ``fb`` differ in sign, all cells at once.

    Bisection on the sign, vectorised over the cells, until the ends of every cell are neighbouring floats (at
    most ~60 halvings from a grid cell; the number of steps is bounded by the float format): the end where
    |Im(P₀ Q̄)| is smaller is returned, or the midpoint where it is exactly 0. A cell whose ends agree in sign
    (Im(P₀ Q̄) within rounding of zero at an end) is that end, the one nearer zero.

    Examples
    --------
    >>> ray = _Ray(np.array([1.0, -0.4, 0.3]), np.zeros(1), np.array([1.0, 0.2]), 0)  # P₀, Q in w
    >>> a, b = np.array([0.5]), np.array([1.5])
    >>> t = _roots_in_cells(ray, a, b, _im_part(ray, a), _im_part(ray, b))
    >>> bool(abs(_im_part(ray, t[0])) < 1e-15)
    True
    """
    lo, hi = np.array(a, dtype=float), np.array(b, dtype=float)
    flo, fhi = np.array(fa, dtype=float), np.array(fb, dtype=float)
    act = np.nonzero(flo * fhi < 0.0)[0]
    while act.size:
        mid = 0.5 * (lo[act] + hi[act])
        open_ = (mid > lo[act]) & (mid < hi[act])
        act, mid = act[open_], mid[open_]
        if not act.size:
            break
        fm = _im_part(ray, mid)
        zero = fm == 0.0
        low = (np.sign(fm) == np.sign(flo[act])) & ~zero  # the root lies in [mid, hi]
        lo[act[low]], flo[act[low]] = mid[low], fm[low]
        high = ~low & ~zero
        hi[act[high]], fhi[act[high]] = mid[high], fm[high]
        lo[act[zero]], hi[act[zero]], flo[act[zero]], fhi[act[zero]] = mid[zero], mid[zero], 0.0, 0.0
        act = act[~zero]
    return np.where(np.abs(flo) <= np.abs(fhi), lo, hi)


def _polish_all(ray: _Ray, t: np.ndarray) -> np.ndarray:
    """Refine roots θ of Im(P₀ Q̄) (from np.roots in z) by bracketing nearby, all at once.

    For each θ the first bracket (θ(1 − r), θ) or (θ, θ(1 + r)), r = 1e-12, 1e-9, …, 1e-2 (capped at π), with a
    sign change is bisected to neighbouring floats (:func:`_roots_in_cells`); a θ with none (a tangency) or at
    which Im(P₀ Q̄) = 0 exactly is kept as is.
    """
    t = np.asarray(t, dtype=float)
    if not t.size:
        return t
    rels = np.array([1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 1e-2])
    lo, hi = t[:, None] * (1.0 - rels), np.minimum(t[:, None] * (1.0 + rels), math.pi)
    pts = np.stack([lo, t[:, None] + 0.0 * rels, t[:, None] + 0.0 * rels, hi], axis=-1)  # (θ, r, pair ends)
    f = _im_part(ray, pts.reshape(-1)).reshape(pts.shape).reshape(t.size, -1, 2)  # pairs (lo, θ), (θ, hi)
    ok = f[..., 0] * f[..., 1] < 0.0
    f0 = _im_part(ray, t)
    has = ok.any(axis=1) & (f0 != 0.0) & (t < math.pi)  # π is kept as is
    first = np.argmax(ok, axis=1)[has]
    x = pts.reshape(t.size, -1, 2)[has, first]
    fx = f[has, first]
    out = t.copy()
    out[has] = _roots_in_cells(ray, x[:, 0], x[:, 1], fx[:, 0], fx[:, 1])
    return out


def _crossings(ray: _Ray) -> np.ndarray:
    """Every κ > 0 at which a root of P₀ + κQ lies on the unit circle, ascending, without repeats."""
    t = _candidate_angles(ray)
    pq, qw = _pq(ray, np.maximum(t, 0.0))
    qq = np.abs(qw) ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        k = -pq.real / qq
    keep = (qq > 0.0) & (k > 0.0) & np.isfinite(k) & (np.abs(pq.imag) <= 1e-6 * np.abs(pq))
    ks = np.sort(k[keep])
    out: list[float] = []
    for kk in ks:
        if not out or kk > out[-1] * (1.0 + 1e-10):
            out.append(float(kk))
    return np.array(out)


def _stable_kappa(a: float, a_b: float, wall: WallParams, mu: float = 1.0) -> list[tuple[float, float]]:
    """The stable set in κ = KT²/m as a list of open intervals (lo, hi), lo = 0 for the one from κ = 0+."""
    return _ray_intervals(_ray(a, a_b, wall, mu), (a, a_b, wall.cutoff, wall.lag, wall.delay))


def _ray_intervals(ray: _Ray, args: tuple) -> list[tuple[float, float]]:
    """Stable set in κ of P₀ + κQ (deg Q < deg P₀) as open intervals; ``args`` names the case in errors."""
    ks = _crossings(ray)
    if ks.size == 0:
        ks = np.array([1.0])  # no crossing: stability is the same for every κ (then unstable, deg Q < deg P₀)
    probes = np.concatenate([[0.5 * ks[0]], np.sqrt(ks[1:] * ks[:-1]), [2.0 * ks[-1]]])
    stable = _rho(ray, probes) < 1.0
    edges = np.concatenate([[0.0], ks, [math.inf]])
    out: list[tuple[float, float]] = []
    for i, s in enumerate(stable):
        if not s:
            continue
        if out and out[-1][1] == edges[i]:
            out[-1] = (out[-1][0], float(edges[i + 1]))  # a candidate that is not a boundary
        else:
            out.append((float(edges[i]), float(edges[i + 1])))
    _check_against_grid(ray, ks, out, args)
    return out


def _check_against_grid(ray: _Ray, ks: Any, intervals: Any, args: Any) -> None:
    """The stable set must agree with the spectral radius on an independent geometric grid of κ."""
    a1, a0 = (ray.a[-2], ray.a[-1]) if len(ray.a) > 1 else (0.0, ray.a[-1])
    b1 = ray.b[-2] if len(ray.b) > 1 else 0.0
    p1, q0 = a1 + ray.d * a0 + b1, ray.q[-1]  # P₀'(w = 0), with (1 + w)^d = 1 + dw + …, and Q(0)
    low = p1 / q0 if q0 != 0.0 else 0.0  # φ₁ = P₀'(w = 0)/Q(0): the scale of a crossing near z = 1
    low = low if 0.0 < low < ks[0] and math.isfinite(low) else ks[0]
    grid = geometric_grid(low * 1e-2, ks[-1] * 1e2, 241)
    near = np.min(np.abs(np.log(grid[:, None] / ks[None, :])), axis=1) < 1e-6
    rho = _rho(ray, grid)
    inside = np.array([any(lo < k < hi for lo, hi in intervals) for k in grid])
    bad = ~near & (np.abs(rho - 1.0) > 1e-9) & ((rho < 1.0) != inside)
    if np.any(bad) or any(math.isinf(hi) for _, hi in intervals):
        raise DFAError(
            f"the exact linear stability set for (bT/m, BT/m, ν_c, α, d) = {args!r} failed its spectral-radius "
            "check: please report this as a bug"
        )


def _stable_set(
    b: float, big_b: float, t: float, m: float, p: WallParams, mu: float = 1.0
) -> tuple[list[tuple[float, float]], float | None]:
    """Stable κ intervals and, when the Taylor series at z = 1 gives it, K_crit in N/m (else None).

    (b + B)T/m > :data:`SERIES_RATE` or 0: the float ray analysis alone. Below, where the series converges:
    (0, κ_crit) from the series (the float crossings near z = 1 are off there: 3e-5 relative, or a false
    'never', at (b + B)T/m = 1e-7 with an amplifier lag of 159 or 15915 samples), then any interval of the
    float ray analysis (from :data:`MIN_RESOLVED_RATE` up) starting at κ >= max(1e-3, 4κ_crit), where the float
    spectral radius resolves the roots near z = 1; every other κ of a grid up to 1e4 there must be unstable
    (checked). Between κ_crit and that bound the ray stays unstable: the roots at κ = O((b + B)T/m) lie in the closed unit disk away from
    z = 1, and the series' crossing is the unique root of its leading balance near z = 1.
    """
    a, a_b = b * t / m, big_b * t / m
    rate = (b + big_b) * t / m
    series = None
    if b + big_b > 0.0 and rate <= SERIES_RATE:
        series = series_kappa(a, a_b, p)
    if series is None:
        if p.hand_stiffness > 0.0:  # the hand spring keeps the device's poles off z = 1: the float ray
            return _stable_kappa(a, a_b, p, mu), None
        if 0.0 < rate < MIN_RESOLVED_RATE or (rate == 0.0 and b + big_b > 0.0):
            raise DFAValueError(
                f"(damping + controller.damping)·period/mass = {rate:g} is invalid for the exact linear bound with "
                f"this controller: below {MIN_RESOLVED_RATE:g} the bound comes from a series at z = 1, which does "
                "not converge here (the velocity filter's pole as close to z = 1 as the stability boundary); raise "
                "the filter cutoff, or check the mass and damping"
            )
        return _stable_kappa(a, a_b, p), None
    rho_l, k_tilde = series
    kappa = (a * rho_l + a_b) * k_tilde
    k_top = (b * rho_l + big_b) / t * k_tilde
    lo = max(1e-3, 4.0 * kappa)  # from here on the float spectral radius resolves the roots near z = 1
    higher: list[tuple[float, float]] = []
    if rate >= MIN_RESOLVED_RATE:  # below, none is looked for (costly at large d): one found by the grid is an error
        try:
            higher = [iv for iv in _stable_kappa(a, a_b, p) if iv[0] >= lo]
        except DFAError:  # its own check failed (the clustered roots near z = 1): no interval above is listed
            pass
    grid = geometric_grid(lo, 1e4, 29)
    grid = grid[[not any(x <= k <= y for x, y in higher) for k in grid]]
    if grid.size and np.any(_rho(_ray(a, a_b, p), grid) <= 1.0 + 1e-9):
        raise DFAError(
            f"the loop with (bT/m, BT/m, ν_c, α, d) = {(a, a_b, p.cutoff, p.lag, p.delay)!r} is stable at a large K "
            "outside the listed intervals although (b + B)T/m is small: please report this as a bug"
        )
    return [(0.0, kappa), *higher], k_top


def _status(intervals: list[tuple[float, float]]) -> LinearStatus:
    if not intervals:
        return LinearStatus.NEVER
    if intervals[0][0] > 0.0:
        return LinearStatus.NOT_AT_LOW_K
    return LinearStatus.INTERVAL if len(intervals) == 1 else LinearStatus.SEVERAL


# ----------------------------------------------------------------------------- results in physical units
def _device(mass: Any, damping: Any, period: Any) -> tuple[float, float, float]:
    m = check_positive("mass", mass, "give the moving mass in kg (rotary: kg·m²)")
    b = check_nonnegative("damping", damping, "give the viscous friction b in N·s/m")
    t = check_positive("period", period, "give the sampling period T in s (1 kHz: 0.001)")
    if not (t * t > 0.0 and math.isfinite(m / (t * t))):  # K = κ m/T²: a subnormal T would divide by zero
        raise DFAValueError(
            f"period = {t!r} is invalid with mass = {m!r}: mass/period² must be finite; give T in s (1 kHz: 0.001)"
        )
    if not math.isfinite(b * t / m):
        raise DFAValueError(f"damping·period/mass = {b * t / m!r} is invalid: it must be finite; check the units")
    return m, b, t


def stable_stiffness(mass: float, damping: float, period: float, wall: Wall) -> StiffnessIntervals:
    """Every stable stiffness K of the linear sampled loop with ``wall``'s damper, filter, delay and lag.

    The exact closed-loop characteristic polynomial of ZOH, amplifier lag and
    device with the controller H(z) (module docstring); K varies while the
    physical B, f_c, τ_a and d stay fixed (so β_B = B/(KT) varies with K).

    Parameters
    ----------
    mass : float
        Moving mass m > 0, kg (rotary: kg·m²).
    damping : float
        Viscous friction b >= 0, N·s/m (rotary: N·m·s/rad).
    period : float
        Sampling period T > 0, s.
    wall : Wall
        Its damping B, delay, filter cutoff and amplifier bandwidth are used; its stiffness is not
        (K is what is solved for).

    Returns
    -------
    StiffnessIntervals
        Every stable interval of K (N/m), K_crit (top of the one from K = 0) and the status.

    Raises
    ------
    DFAValueError
        A mass, damping or period out of range, a filter cutoff above the Nyquist frequency 1/(2T), or
        0 < (b + B)T/m < :data:`MIN_RESOLVED_RATE` where the series at z = 1 does not converge (a guard: no
        accepted input is known to reach it).
    DFATypeError
        ``wall`` is not a :class:`dfa.Wall`.

    See Also
    --------
    stable_region : The same at each B of a grid (the stable K–B region).
    dfa.analysis.linear.critical_stiffness : K_crit alone, vectorised; the spring's closed-form path.
    colgate_schenkel_damping : The (stricter) passivity condition.

    Examples
    --------
    >>> r = stable_stiffness(1.0, 0.0, 1e-3, Wall.of(1.0))     # b = B = 0: never stable
    >>> r.status.value, r.k_crit
    ('never', 0.0)
    """
    m, b, t = _device(mass, damping, period)
    c = check_type("wall", wall, Wall, "give a dfa.Wall")
    p = c.params(t)
    for name, value in (("damping", b), ("wall.damping", c.damping)):
        check_rate(name, value, m, t)
    kap, k_top = _stable_set(b, c.damping, t, m, p, m / (c.stiffness * t * t))  # μ at the wall's own K
    scale = m / (t * t)
    iv = np.array([[lo * scale, hi * scale] for lo, hi in kap]).reshape(-1, 2)
    status = _status(kap)
    if k_top is not None:  # the series' K_crit, formed without the possibly underflowing (b + B)T/m
        iv[0, 1] = k_top
    k_crit = float(iv[0, 1]) if status in (LinearStatus.INTERVAL, LinearStatus.SEVERAL) else 0.0
    ctrl = {k: v for k, v in c.to_dict().items() if k != "stiffness"}
    return StiffnessIntervals(iv, k_crit, status, m, b, t, ctrl)


def stable_region(
    mass: float,
    damping: float,
    period: float,
    virtual_damping: Any,
    *,
    wall: Wall | None = None,
) -> StableRegion:
    """The stable K–B region of the linear sampled loop: :func:`stable_stiffness` at each B of a grid.

    Parameters
    ----------
    mass, damping, period : float
        Device mass m (kg), viscous friction b (N·s/m), sampling period T (s).
    virtual_damping : array_like
        One or more virtual dampings B >= 0, N·s/m: the wall's damper at each point of the grid.
    wall : Wall, optional
        The rest of the wall, held fixed: its delay (samples), velocity filter and amplifier (its stiffness
        and damper are not used); default the spring.

    Returns
    -------
    StableRegion
        K_max(B) at each B, every stable interval and the status per B.

    Raises
    ------
    DFAValueError
        An empty grid, a negative B, or device or controller values out of range.
    DFATypeError
        A B that is not a real number (text, True/False).

    See Also
    --------
    stable_stiffness : One B.
    colgate_schenkel_damping : The passivity condition at a given K and B.

    Examples
    --------
    >>> r = stable_region(1.0, 2.0, 1e-3, [0.0, 1.0])
    >>> [round(k) for k in r.k_crit], r.status.value      # B = 0: the spring's bound
    ([4001, 5996], 'interval')
    """
    grid = np.atleast_1d(check_real_array("virtual_damping", virtual_damping, "give the dampings B in N·s/m"))
    if grid.ndim != 1 or grid.size == 0:
        raise DFAValueError(f"virtual_damping = {virtual_damping!r} is invalid: give one or more dampings B in N·s/m")
    if (grid < 0).any():  # the message names what the caller typed, not Wall's field `damping`
        bad = float(grid[grid < 0][0])
        raise DFAValueError(
            f"virtual_damping = {bad!r} is invalid: it must be a finite number >= 0; give the virtual damping B in "
            "N·s/m (0 for none)"
        )
    base = Wall(1.0) if wall is None else check_type("wall", wall, Wall, "give a dfa.Wall or None")
    rows = tuple(stable_stiffness(mass, damping, period, base.with_damping(float(bb))) for bb in grid)
    odd = [r.status for r in rows if r.status is not LinearStatus.INTERVAL]
    return StableRegion(grid, np.array([r.k_crit for r in rows]), rows, odd[0] if odd else LinearStatus.INTERVAL)
