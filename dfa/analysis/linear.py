"""Exact linear stability of the sampled spring (spec section 8: Gil et al. 2004, Diolaiti et al. 2006).

The device without encoder and Coulomb friction, m ẍ + b ẋ = F, rendering a
spring whose force is held by a zero-order hold and computed from a reading d
samples old, F_h = −K x(h − d). In the paper's dimensionless form (Table 1,
eq. 4-5 with σ = 0 and no quantizer; time in samples)::

    μ ξ'' + β ξ' = φ_h   on τ ∈ [h, h + 1),   φ_h = −ξ(h − d),   μ = m/(KT²), β = b/(KT).

The exact ZOH pulse transfer of 1/(μs² + βs) is (``control.c2d(…, 'zoh')`` in
closed form; :mod:`dfa.analysis.loop`)::

    G_d(z) = (c₁ z + c₀) / (μ (z − 1)(z − p)),   a = β/μ = bT/m,   p = e^{−a},
    c₁ = (a − 1 + p)/a²,   c₀ = (1 − p − a p)/a²       (c₁ = c₀ = ½ at a = 0),

so the closed loop 1 + z^{−d} G_d(z) = 0 has the characteristic polynomial of
degree d + 2::

    χ(z) = μ z^d (z − 1)(z − p) + c₁ z + c₀.

The stiffness ray. At fixed device and period, K enters only through
κ = 1/μ = KT²/m, while a = bT/m stays fixed: χ/μ = D(z) + κ N(z) with
D = z^d (z − 1)(z − p), N = c₁ z + c₀. For small κ every root is inside the
unit circle when a > 0 (the integrator's root moves to 1 − κ/a); a root reaches
the circle where κ = −D(z)/N(z) is real and positive on |z| = 1:

* z = −1. −D(−1)/N(−1) = (−1)^d · 2(1 + p)/(c₁ − c₀), and c₁ − c₀ > 0 for a > 0.
  For even d this is the crossing κ₋₁ = 2(1 + p)/(c₁ − c₀) = 2a²/(a − 2 tanh(a/2));
  for odd d no root leaves through z = −1 at K > 0. In (μ, β) with μ = β/a,
  κ < κ₋₁ reads 1/μ < 2a²/(a − 2 tanh(a/2)) ⇔ a − 2 tanh(a/2) < 2aβ ⇔

      β > ½ − tanh(a/2)/a                                                   (the z = −1 condition)

* z = e^{jθ}, 0 < θ < π. With z − 1 = 2j sin(θ/2) e^{jθ/2},
  D(z) N(z̄) = 2j sin(θ/2) w(θ), w = e^{j(d+½)θ} [(c₁ − pc₀) + c₀ e^{jθ} − pc₁ e^{−jθ}],
  so −D/N > 0 iff Re w = 0 and Im w > 0, where, with e₁ = c₁ − pc₀, e₀ = c₀ − pc₁::

      Re w(θ) = e₁ cos((d + ½)θ) + e₀ cos((d − ½)θ) − 2c₀ sin θ sin((d + ½)θ)

  (e₁ + e₀ = (1 − p)²/a and e₁ − e₀ = (1 + p)(c₁ − c₀), free of cancellation for
  small a), and κ(θ) = 2 sin(θ/2) |e^{jθ} − p| / |c₁ e^{jθ} + c₀|. In y = cos(θ/2)
  Re w is the Chebyshev series e₁T_{2d+1}(y) − pc₁T_{|2d−1|}(y) + c₀T_{2d+3}(y), whose
  roots in (0, 1) give every candidate θ at once; each is then polished on Re w.

The critical κ is the smallest candidate at which the spectral radius of χ
passes 1 (checked just below and above); K_crit = κ_crit m/T². For very small a
(r_d·a <= 1e-6, r_d = (2d² + 2d + 1)/(6(2d + 1))) the roots cluster at z = 1 with
|z| − 1 = O(a) and the float spectral radius cannot resolve the boundary; there
κ_crit is the small-a expansion of the interior crossing, κ = a/(½ + d)·(1 + r_d a),
whose neglected term is about 1.3 (r_d a)² <= 1.3e-12 (checked against 60-digit
mpmath in ``tests/test_gil_linear_bound_small_rate.py``). At d = 0 the
interior crossing is Gil et al.'s closed form κ = a f(a) (:func:`dfa.analysis.limits.closed_form.gil_factor`),
binding for a < a* ≈ 3.72; beyond it the z = −1 condition binds and the bound is
smaller. As a → 0, κ_crit → a/(½ + d), i.e. K_crit → b/(T(½ + d)) and
β_crit → ½ + d (Diolaiti et al. 2006).

In β at fixed μ the stable set is the interval β > β_crit(μ, d): κ_crit(a, d) is
increasing in a (checked on a dense grid of a in [1e-4, 1e3], d = 0..6, in
``tests/test_gil_linear_bound.py``), and the loop at (μ, β) is stable iff
1/μ < κ_crit(β/μ, d).

Examples
--------
>>> round(critical_stiffness(0.01, 5.0, 0.01), 1)      # a = bT/m = 5: z = −1 binds (Gil: 2587.8)
1651.9
>>> round(critical_beta(100.0), 5), round(critical_beta(1e6, delay=2), 4)
(0.49958, 2.5)
>>> characteristic_polynomial(2.0, 0.0).tolist()       # β = 0: 2(z − 1)² + ½z + ½
[2.0, -3.5, 2.5]
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.polynomial import chebyshev
from numpy.typing import ArrayLike

from ..checks import (
    check_beta,
    check_damping_rate,
    check_delay,
    check_mu,
    check_nonnegative,
    check_positive,
    check_rate,
    check_type,
)
from ..core.zoh import c1_minus_c0, zoh_coefficients
from ..errors import DFAError, DFAValueError
from ..grids import geometric_grid
from ..model.wall import Wall, WallParams

__all__ = [
    "characteristic_polynomial",
    "spectral_radius",
    "linear_stable",
    "critical_beta",
    "critical_stiffness",
]


def _verify_step(a: float) -> float:
    """Relative step in K for the spectral-radius check of a critical value.

    Across the boundary |z| changes by about a·step/2, which must stand clear of
    the roots' rounding (~1e-16 over their ~√κ spacing): 1e-6 down to
    a = bT/m = 1e-5, growing as 1e-11/a below (1e-3 at a = 1e-8).
    """
    return min(1e-2, max(1e-6, 1e-11 / a))


# ----------------------------------------------------------------------------- polynomial and spectral radius
def characteristic_polynomial(mu: float, beta: float, *, wall: WallParams | None = None) -> np.ndarray:
    """Closed-loop characteristic polynomial χ(z) = μ z^d (z − 1)(z − p) + c₁ z + c₀ of the sampled spring.

    The exact ZOH loop of μξ'' + βξ' = −ξ(h − d) (module docstring; spec
    section 8; Table 1 parameters, eq. 4-5 without quantizer or Coulomb friction).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(KT²) > 0.
    beta : float
        Dimensionless damping β = b/(KT) >= 0 (β = 0: the limit c₁ = c₀ = ½, p = 1).
    wall : WallParams, optional
        The wall's groups: its computational delay d in samples (the force of sample h uses ξ(h − d)); with a
        damper or an amplifier lag the polynomial of
        :func:`dfa.analysis.linear_wall.controlled_characteristic_polynomial`. None or a spring (any delay; a
        velocity filter without a damper filters nothing): the spring's polynomial.

    Returns
    -------
    numpy.ndarray
        The coefficients, highest power first (d + 3 for the spring).

    Examples
    --------
    >>> characteristic_polynomial(1.0, 0.0, wall=WallParams.of(delay=1)).tolist()   # z(z − 1)² + ½z + ½
    [1.0, -2.0, 1.5, 0.5]
    """
    m, b = check_mu(mu), check_beta(beta)
    c = _wall(wall)
    d = c.delay
    if _beyond_spring(c):
        from .linear_wall import controlled_characteristic_polynomial

        return controlled_characteristic_polynomial(m, b, c)
    c1, c0, p = zoh_coefficients(b / m)
    coef = np.zeros(d + 3)
    coef[:3] = m, -m * (1.0 + p), m * p
    coef[d + 1] += c1
    coef[d + 2] += c0
    return coef


def _rho(a: float | np.ndarray, kappa: float | np.ndarray, d: int) -> np.ndarray:
    """Spectral radius of D + κN (monic, degree d + 2), vectorised over a and κ (batched companion matrices)."""
    a, kappa = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(kappa, dtype=float))
    c1, c0, p = zoh_coefficients(a.ravel())
    k = kappa.ravel()
    n = d + 2
    coef = np.zeros((k.size, n + 1))
    coef[:, 0], coef[:, 1], coef[:, 2] = 1.0, -(1.0 + p), p
    coef[:, d + 1] += k * c1
    coef[:, d + 2] += k * c0
    comp = np.zeros((k.size, n, n))
    comp[:, 0, :] = -coef[:, 1:]
    idx = np.arange(n - 1)
    comp[:, idx + 1, idx] = 1.0
    rho = np.max(np.abs(np.linalg.eigvals(comp)), axis=-1)
    return rho.reshape(a.shape)


def _as_array(name: str, value: ArrayLike, check: Callable[[str, Any], float]) -> np.ndarray:
    """``value`` as a float array, every element passing ``check(name, element)`` (scalars: their own type check)."""
    if np.ndim(value) == 0:
        return np.asarray(check(name, value))
    arr = np.asarray(value, dtype=float)
    for v in arr.ravel():
        check(name, float(v))
    return arr


def _wall(wall: object) -> WallParams:
    """The wall's groups (None: the paper's spring), or the package's error."""
    return WallParams() if wall is None else check_type("wall", wall, WallParams, "give a dfa.WallParams or None")


def _beyond_spring(wall: WallParams) -> bool:
    """True when the wall's linear loop is not the spring's: a damper, an amplifier lag or a hand stiffness (a
    filter without a damper filters nothing)."""
    return wall.damping > 0.0 or wall.lag > 0.0 or wall.hand_stiffness > 0.0


def spectral_radius(mu: ArrayLike, beta: ArrayLike, *, wall: WallParams | None = None) -> float | np.ndarray:
    """Largest root modulus of :func:`characteristic_polynomial` (vectorised over μ and β).

    Parameters
    ----------
    mu, beta : float or array_like
        Dimensionless mass (> 0) and damping (>= 0), broadcast together.
    wall : WallParams, optional
        The wall's groups: delay d, virtual damper β_B, filter ν_c and amplifier lag α
        (:mod:`dfa.analysis.linear_wall`); None or a spring (any delay; a filter without a damper filters
        nothing) gives the spring's result.

    Returns
    -------
    float or numpy.ndarray
        max |z| over the closed-loop poles; < 1 means asymptotically stable.

    Examples
    --------
    >>> float(spectral_radius(1.0, 0.0)) > 1.0                  # undamped: unstable for every K
    True
    """
    m = _as_array("mu", mu, lambda n, v: check_mu(v, n))
    b = _as_array("beta", beta, lambda n, v: check_beta(v, n))
    check_damping_rate(b, m)  # beyond, b/μ overflows and the eigenvalue solver is given inf
    c = _wall(wall)
    d = c.delay
    if _beyond_spring(c):
        from .linear_wall import controlled_spectral_radius

        m, b = np.broadcast_arrays(m, b)
        out = np.array(
            [controlled_spectral_radius(x, y, c) for x, y in zip(m.ravel(), b.ravel(), strict=True)]
        ).reshape(m.shape)
    else:
        out = _rho(b / m, 1.0 / m, d)
    return float(out) if out.ndim == 0 else out


def linear_stable(mu: ArrayLike, beta: ArrayLike, *, wall: WallParams | None = None) -> bool | np.ndarray:
    """True where the linear sampled loop is asymptotically stable (spectral radius < 1), vectorised.

    Parameters as :func:`spectral_radius` (``wall``: a :class:`WallParams`, or None for the spring).
    At tiny rates (spring: r_d β/μ <= 1e-6; controller: (β + β_B)/μ < 1e-7), where the float spectral radius is
    decided by rounding, the verdict is 1/μ < κ_crit of the small-rate bound (:func:`critical_stiffness`).

    Examples
    --------
    >>> linear_stable(100.0, 0.5), linear_stable(100.0, 0.49)
    (True, False)
    """
    r = spectral_radius(mu, beta, wall=wall)
    c = _wall(wall)
    d = c.delay
    m, b = np.broadcast_arrays(np.asarray(mu, dtype=float), np.asarray(beta, dtype=float))
    out = np.atleast_1d(np.asarray(r) < 1.0).ravel()
    for i, (x, y) in enumerate(zip(m.ravel(), b.ravel(), strict=True)):
        v = _small_rate_verdict(float(x), float(y), d, c)
        if v is not None:  # tiny rates: the float spectral radius is decided by rounding there
            out[i] = v
    return bool(out[0]) if isinstance(r, float) else out.reshape(np.shape(r))


def _small_rate_verdict(mu: float, beta: float, d: int, c: WallParams) -> bool | None:
    """Stability from the small-rate bound (1/μ < κ_crit, in β form: no underflow), or None outside that regime.

    Spring: r_d β/μ <= 1e-6, stable iff β(1 + r_d β/μ) > ½ + d (:func:`_small_rate_kappa`). With a damper or
    lag: (β + β_B)/μ < :data:`dfa.analysis.linear_wall.MIN_RESOLVED_RATE`, stable iff (βρ_L + β_B) κ̃ > 1
    (:func:`dfa.analysis.linear_wall.series_kappa`).
    """
    a = beta / mu
    if _beyond_spring(c):
        from .linear_wall import MIN_RESOLVED_RATE, series_kappa

        if not (beta + c.damping > 0.0 and (beta + c.damping) / mu < MIN_RESOLVED_RATE):
            return None
        series = series_kappa(a, c.damping / mu, c)
        return None if series is None else bool((beta * series[0] + c.damping) * series[1] > 1.0)
    r = (2.0 * d * d + 2.0 * d + 1.0) / (6.0 * (2.0 * d + 1.0))
    if not (beta > 0.0 and r * a <= _ASYMPTOTIC_LIMIT):
        return None
    return bool(beta * (1.0 + r * a) > 0.5 + d)


# ----------------------------------------------------------------------------- boundary crossings on the stiffness ray
def _crossings(a: float, d: int) -> list[float]:
    """Every κ > 0 at which a root of D + κN lies on the unit circle (a > 0), ascending (module docstring)."""
    c1, c0, p = zoh_coefficients(a)
    dc = c1_minus_c0(a)
    s = math.expm1(-a) ** 2 / a  # e₁ + e₀ = (1 − p)²/a
    delta = (1.0 + p) * dc  # e₁ − e₀
    e1, e0 = 0.5 * (s + delta), 0.5 * (s - delta)
    out = [2.0 * (1.0 + p) / dc] if d % 2 == 0 else []  # z = −1

    def re_w(t: float) -> float:
        return (
            e1 * math.cos((d + 0.5) * t)
            + e0 * math.cos((d - 0.5) * t)
            - 2.0 * c0 * math.sin(t) * math.sin((d + 0.5) * t)
        )

    def im_w(t: float) -> float:
        return e1 * math.sin((d + 0.5) * t) + c0 * math.sin((d + 1.5) * t) - p * c1 * math.sin((d - 0.5) * t)

    cheb = np.zeros(2 * d + 4)
    cheb[2 * d + 1] += e1
    cheb[abs(2 * d - 1)] -= p * c1
    cheb[2 * d + 3] += c0
    for y in chebyshev.chebroots(cheb):
        if abs(y.imag) > 1e-6 or not 0.0 < y.real < 1.0:
            continue
        t = _polish(re_w, 2.0 * math.acos(y.real))
        if not 0.0 < t < math.pi or im_w(t) <= 0.0:
            continue
        h = math.sin(0.5 * t)
        num = 2.0 * h * math.sqrt(math.expm1(-a) ** 2 + 4.0 * p * h * h)  # |z − 1| |z − p|
        den = math.sqrt(dc * dc + 4.0 * c1 * c0 * (1.0 - h * h))  # |c₁z + c₀|
        out.append(num / den)
    return sorted(k for k in out if k > 0.0 and math.isfinite(k))


def _polish(f: Callable[[float], float], t: float) -> float:
    """Refine a root t of f (a candidate from the Chebyshev roots) by bisection on a sign change nearby."""
    from scipy.optimize import brentq  # imported here: scipy.optimize takes about 0.3 s to load

    f0 = f(t)
    if f0 == 0.0:
        return t
    for rel in (1e-10, 1e-8, 1e-6, 1e-4):
        lo, hi = t * (1.0 - rel), min(t * (1.0 + rel), math.pi)
        if f(lo) * f0 < 0.0:
            return brentq(f, lo, t, xtol=1e-300, rtol=4 * np.finfo(float).eps)
        if f(hi) * f0 < 0.0:
            return brentq(f, t, hi, xtol=1e-300, rtol=4 * np.finfo(float).eps)
    return t  # a tangency (double root): keep the candidate; the spectral-radius check decides


#: r_d·a below which :func:`_critical_kappa` uses its small-a expansion (relative error ~(r_d a)², ~1e-12).
_ASYMPTOTIC_LIMIT = 1e-6


def _small_rate_kappa(a: float, d: int) -> float:
    """κ_crit = a/(½ + d) · (1 + r_d a + O(a²)), r_d = (2d² + 2d + 1)/(6(2d + 1)), for small a = bT/m.

    The interior crossing θ² = a/(½ + d)(1 − a/6 + O(a²)) of Re w(θ) = 0 (module docstring), expanded
    in a (d = 0: r_0 = 1/6, β_crit = ½ − 1/(24μ)); checked against 60-digit mpmath in
    ``tests/test_gil_linear_bound_small_rate.py``. There the float spectral radius cannot resolve the
    boundary (the roots cluster at z = 1 with |z| − 1 = O(a)), so no crossing is verified with it.
    """
    r = (2.0 * d * d + 2.0 * d + 1.0) / (6.0 * (2.0 * d + 1.0))
    return a / (0.5 + d) * (1.0 + r * a)


def _critical_kappa(a: float, d: int) -> float:
    """Smallest κ = KT²/m > 0 at which the loop leaves stability, for a = bT/m >= 0, delay d."""
    if a == 0.0:
        return 0.0  # undamped: the double pole at z = 1 leaves the circle for every K > 0
    if a * (2.0 * d * d + 2.0 * d + 1.0) / (6.0 * (2.0 * d + 1.0)) <= _ASYMPTOTIC_LIMIT:
        return _small_rate_kappa(a, d)
    step = _verify_step(a)
    for k in _crossings(a, d):
        if _rho(a, k * (1.0 + step), d) > 1.0:
            if _rho(a, k * (1.0 - step), d) < 1.0:
                return k
            break  # unstable just below the first crossing found: one was missed
    return _critical_kappa_scan(a, d)


def _critical_kappa_scan(a: float, d: int) -> float:
    """Fallback: first κ with spectral radius >= 1 on a fine geometric grid, then bisection on ρ − 1."""
    from scipy.optimize import brentq  # imported here: scipy.optimize takes about 0.3 s to load

    hint = a / (0.5 + d) if a < 1.0 else 2.0 * a
    ks = geometric_grid(1e-6 * hint, 1e3 * hint, 4000)
    rho = _rho(a, ks, d)
    bad = np.nonzero(rho >= 1.0)[0]
    if bad.size == 0 or bad[0] == 0:
        raise DFAError(f"no stability boundary found for a = bT/m = {a!r}, delay = {d}: please report this as a bug")
    i = int(bad[0])
    return float(brentq(lambda k: float(_rho(a, k, d)) - 1.0, ks[i - 1], ks[i], xtol=1e-300, rtol=1e-14))


def critical_stiffness(
    mass: ArrayLike, damping: ArrayLike, period: ArrayLike, *, wall: Wall | None = None
) -> float | np.ndarray:
    """Exact stability limit K_crit of the linear sampled spring, all Jury conditions, with delay (spec section 8).

    The smallest K > 0 at which a closed-loop root of :func:`characteristic_polynomial`
    reaches the unit circle: the least of the z = −1 crossing (even d) and the
    crossings at z = e^{jθ}, each κ = −D/N real and positive (module docstring),
    verified by the spectral radius at K(1 ∓ ε), ε = 1e-6 (more below bT/m = 1e-5); for tiny bT/m (below
    1e-6·6(2d + 1)/(2d² + 2d + 1)) the small-a expansion K = b/(T(½ + d))·(1 + r_d bT/m) (module docstring,
    relative error <= 1.3e-12), formed from b/T so that an underflowing bT/m (m = 1e300 kg) still gives
    the positive limit. The loop is stable for every
    K in (0, K_crit). Gil et al. (2004)'s closed form (b/T) f(bT/m)
    (:func:`dfa.analysis.limits.closed_form.gil_factor`) is the d = 0 interior crossing: it is the
    bound for bT/m < 3.72, beyond it the z = −1 condition β > ½ − tanh(a/2)/a binds.
    As bT/m → 0, K_crit → b/(T(½ + d)) (eq. 8 for d = 0; Diolaiti et al. 2006).

    Parameters
    ----------
    mass : float or array_like
        Moving mass m > 0, kg (rotary: kg·m²).
    damping : float or array_like
        Viscous friction b >= 0, N·s/m (rotary: N·m·s/rad).
    period : float or array_like
        Sampling period T > 0, s.
    wall : Wall, optional
        The wall: its computational delay d in samples (F_h = −K x(h − d)); with a virtual damper B or an
        amplifier lag, K_crit is :attr:`dfa.analysis.linear_wall.StiffnessIntervals.k_crit` of
        :func:`dfa.analysis.linear_wall.stable_stiffness` (B, f_c, τ_a, d held fixed while K varies; the
        wall's own stiffness is not used; the stable set may have further intervals above K_crit, which
        that function lists). None or a spring (a filter without a damper filters nothing): the spring's
        result.

    Returns
    -------
    float or numpy.ndarray
        K_crit in N/m (rotary: N·m/rad); 0 when the loop is unstable at small K (b = 0 for the spring).

    Examples
    --------
    >>> round(critical_stiffness(0.01, 5.0, 0.01, wall=Wall.of(1.0, delay=1)), 1)
    482.1
    >>> critical_stiffness(1.0, 0.0, 1e-3)
    0.0
    """
    m = _as_array("mass", mass, lambda n, v: check_positive(n, v, "give the moving mass in kg (rotary: kg·m²)"))
    b = _as_array("damping", damping, lambda n, v: check_nonnegative(n, v, "give the viscous friction in N·s/m"))
    t = _as_array("period", period, lambda n, v: check_positive(n, v, "give the sampling period in s"))
    c = Wall(1.0) if wall is None else check_type("wall", wall, Wall, "give a dfa.Wall or None")
    m, b, t = np.broadcast_arrays(m, b, t)
    groups = c.params(float(t.flat[0])) if t.size else WallParams()  # every element's delay, summed
    d = groups.delay
    if _beyond_spring(groups):
        from .linear_wall import stable_stiffness

        rows = zip(m.ravel(), b.ravel(), t.ravel(), strict=True)
        flat = [stable_stiffness(float(x), float(y), float(z), c).k_crit for x, y, z in rows]
        out = np.array(flat).reshape(m.shape)
        return float(out) if out.ndim == 0 else out
    a = b * t / m
    if not np.all(np.isfinite(a)):
        raise DFAValueError(f"damping·period/mass = {a!r} is invalid: it must be finite; check the units")
    for x, y, z in zip(m.ravel(), b.ravel(), t.ravel(), strict=True):  # bT/m <= MAX_RATE, as stable_stiffness
        check_rate("damping", float(y), float(x), float(z))
    flat = [
        _critical_k(float(x), float(y), float(z), d) for x, y, z in zip(m.ravel(), b.ravel(), t.ravel(), strict=True)
    ]
    out = np.array(flat).reshape(m.shape)
    return float(out) if out.ndim == 0 else out


def _critical_k(m: float, b: float, t: float, d: int) -> float:
    """K_crit = κ_crit m/T² in N/m; in the small-rate regime b/(T(½ + d))·(1 + r_d a), formed without a = bT/m.

    A device whose bT/m underflows (m = 1e300 kg, or b = 1e-320 N·s/m) still has the positive limit
    K → b/(T(½ + d)): it is not computed as κ m/T² from an underflowed κ (which gave 0 for b > 0).
    """
    a = b * t / m
    r = (2.0 * d * d + 2.0 * d + 1.0) / (6.0 * (2.0 * d + 1.0))
    if b > 0.0 and r * a <= _ASYMPTOTIC_LIMIT:
        return b / t / (0.5 + d) * (1.0 + r * a)
    return _critical_kappa(a, d) * m / (t * t)


#: μ range in which :func:`critical_beta` is computed reliably (checked against its asymptote ½ + d − c_d/μ,
#: c_0 = 1/24, and its spectral-radius test); outside, the root search loses the boundary in rounding.
CRITICAL_BETA_MU_RANGE = (1e-16, 1e10)


def critical_beta(mu: float, delay: int = 0) -> float:
    """The β below which the linear sampled spring is unstable at this μ, all Jury conditions (spec section 8).

    Dimensionless form of :func:`critical_stiffness`: the loop at (μ, β) is stable
    iff 1/μ < κ_crit(β/μ, d), and κ_crit is increasing in a = β/μ, so the stable
    set in β is the interval β > β_crit(μ, d) (module docstring). d = 0 gives
    the spec's values where Gil et al.'s condition binds (μ = 1: 0.4617, μ = 5:
    0.4918, μ = 100: 0.49958); β_crit → ½ + d as μ → ∞ (Diolaiti et al. 2006).
    The answer is checked by the spectral radius at β(1 ∓ ε), ε = 1e-6 (more below β/μ = 1e-5).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(KT²) > 0.
    delay : int, optional
        Computational delay d in samples.

    Returns
    -------
    float
        β_crit, dimensionless (β = b/(KT)).

    Examples
    --------
    >>> round(critical_beta(1.0), 4), round(critical_beta(1.0, delay=1), 4)
    (0.4617, 1.2127)
    """
    from scipy.optimize import brentq  # imported here: scipy.optimize takes about 0.3 s to load

    m, d = check_mu(mu), check_delay(delay)
    lo_mu, hi_mu = CRITICAL_BETA_MU_RANGE
    if not lo_mu <= m <= hi_mu:
        raise DFAValueError(
            f"mu = {m!r} is invalid for the exact linear bound: it must be from {lo_mu:g} to {hi_mu:g}, where "
            "β_crit is computed reliably (beyond, the Jury boundary is lost in rounding); as μ grows β_crit "
            f"tends to ½ + d = {0.5 + d:g} from below"
        )
    target = 1.0 / m

    def f(a: float) -> float:
        return _critical_kappa(a, d) - target

    lo = hi = (0.5 + d) / m
    while f(lo) >= 0.0:
        lo *= 0.25
    while f(hi) <= 0.0:
        hi *= 4.0
    a = brentq(f, lo, hi, xtol=1e-300, rtol=1e-14)
    beta = m * a
    step = _verify_step(a)
    if not (_rho(a * (1.0 + step), target, d) < 1.0 < _rho(a * (1.0 - step), target, d)):
        raise DFAError(
            f"critical_beta(mu={m!r}, delay={d}) = {beta!r} failed its spectral-radius check: please report this as a bug"
        )
    return float(beta)
