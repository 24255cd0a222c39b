"""The relative exponentials ("exprel") of the exact sampled-loop solution, one implementation.

With u = β t/μ the motion under a constant force over a time t (paper eq. 4-5,
:mod:`dfa.core.kernel`) and the ZOH pulse transfer function (:mod:`dfa.analysis.linear`)
need, without cancellation at small u::

    φ₁(u) = (1 − e^{−u})/u                      = Σ (−u)ⁿ/(n + 1)!
    φ₂(u) = (u − 1 + e^{−u})/u²                 = Σ (−u)ⁿ/(n + 2)!
    ψ(u)  = ((1 − e^{−u}) − ½(1 − e^{−2u}))/u²  = Σ (−1)ⁿ (2ⁿ⁻¹ − 1) uⁿ⁻²/n!,  n >= 2
    χ(u)  = (u − 2(1 − e^{−u}) + ½(1 − e^{−2u}))/u³ = Σ (−1)ⁿ⁺¹ (2ⁿ⁻¹ − 2) uⁿ⁻³/n!,  n >= 3

and, for the time at which the device stops inside a sample, the inverse's
relative form λ(y) = log(1 + y)/y = Σ (−y)ⁿ/(n + 1) (λ(0) = 1), y > −1.

(φ₁(0) = 1, φ₂(0) = ½, ψ(0) = ½, χ(0) = ⅓). φ₁, φ₂ are their series for |u| < ½
(by Estrin's scheme, the simulator's hot path, 8 terms below |u| = 1/32 and 16 above) and their closed forms
through ``expm1`` otherwise; ψ = ½φ₁² exactly; χ is e^{−2u} times a series of positive terms below u = 5
and its closed form above; λ is its series (Estrin, 8 terms below |y| = 1/128, 16 up
to 1/16) and ``log1p(y)/y`` otherwise (divided in steps beyond u = 10¹⁰⁰,
where u² or u³ would overflow): a few ulp everywhere (``tests/test_exprel.py`` checks
them against 50-digit mpmath). φ₁ and φ₂ take any real u (negative u appears
in Gil's factor, :func:`dfa.analysis.limits.closed_form.gil_factor`); ψ and χ are used for
u >= 0 only (their closed forms overflow for u < −354).

The scalar functions are numba ``njit`` functions (compiled on first call, :mod:`dfa.core.jit`), and
Python calls them like plain functions on floats. The compiled simulator inlines :func:`phi12` and
:func:`log1p_ratio` (the chain of a stop inside a sample, the hot path of chattering runs) and calls the
others: inlining all of them at every call site tripled the first compile (32 s against 16 s for
``dfa stiffness`` on a fresh cache) for no measurable speed (a 100 × 100 map: 13.3 s either way). The
``*_array`` wrappers evaluate the same compiled scalar code elementwise on
arrays of any shape.

Developers: numba keys its cache of :mod:`dfa.core.kernel` on that file alone
and does not notice edits here (or to :func:`dfa.core.energy.spring_energy_core`,
also compiled into the kernel); dfa's cache folder is named after every file of
:mod:`dfa.core` (:mod:`dfa.core.cache`), so an edit here takes a fresh folder. With
your own ``NUMBA_CACHE_DIR``, clear it after such an edit, or the kernel keeps the
old code. ``tests/test_kernel_steps.py`` compares the compiled
steps with the Python reference step, which calls these functions afresh.

Examples
--------
>>> phi1(0.0), phi2(0.0), psi(0.0), round(chi(0.0), 15)
(1.0, 0.5, 0.5, 0.333333333333333)
>>> phi2_array([0.0, 1.0]).round(12).tolist()     # ½ and e⁻¹
[0.5, 0.367879441171]
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numpy.typing import ArrayLike

from .jit import njit

__all__ = ["phi1", "phi2", "phi12", "rho", "psi", "chi", "log1p_ratio", "phi1_array", "phi2_array"]


# Taylor coefficients in x = −u: φ₁ = Σ xⁿ/(n + 1)!, φ₂ = Σ xⁿ/(n + 2)!, n = 0 … 15
# (the first omitted term is below 2·10⁻¹⁸ of the value for |u| < ½)
_C1 = tuple(1.0 / math.factorial(n + 1) for n in range(16))
_C2 = tuple(1.0 / math.factorial(n + 2) for n in range(16))
# λ(y) = Σ xⁿ/(n + 1) in x = −y, n = 0 … 15 (the first omitted term is below 2⁻⁶⁴/17 for |y| < 1/16)
_CL = tuple(1.0 / (n + 1) for n in range(16))
# Near 0 (the stop inside a sample at small β/μ: its chain is a division and two of these) eight terms suffice:
# the first omitted term is below 5·10⁻¹⁸ of the value for |u| < 1/32 (φ₁, φ₂) and 2·10⁻¹⁸ for |y| < 1/128 (λ)
SHORT_U = 0.03125
SHORT_Y = 0.0078125


@njit(cache=True, inline="always")
def _poly16(x: float, c: tuple[float, ...]) -> float:
    """Σ c[n] xⁿ, n = 0 … 15, by Estrin's scheme (depth 4: short dependency chains)."""
    x2 = x * x
    x4 = x2 * x2
    x8 = x4 * x4
    r0 = (c[0] + c[1] * x) + (c[2] + c[3] * x) * x2
    r1 = (c[4] + c[5] * x) + (c[6] + c[7] * x) * x2
    r2 = (c[8] + c[9] * x) + (c[10] + c[11] * x) * x2
    r3 = (c[12] + c[13] * x) + (c[14] + c[15] * x) * x2
    return (r0 + r1 * x4) + (r2 + r3 * x4) * x8


@njit(cache=True, inline="always")
def _poly8(x: float, c: tuple[float, ...]) -> float:
    """Σ c[n] xⁿ, n = 0 … 7, by Estrin's scheme (depth 3), for arguments near 0."""
    x2 = x * x
    r0 = (c[0] + c[1] * x) + (c[2] + c[3] * x) * x2
    r1 = (c[4] + c[5] * x) + (c[6] + c[7] * x) * x2
    return r0 + r1 * (x2 * x2)


@njit(cache=True, inline="never")
def phi1(u: float) -> float:
    """φ₁(u) = (1 − e^{−u})/u (φ₁(0) = 1), dimensionless."""
    if abs(u) < SHORT_U:
        return _poly8(-u, _C1)
    if abs(u) < 0.5:
        return _poly16(-u, _C1)
    return -math.expm1(-u) / u


@njit(cache=True, inline="never")
def phi2(u: float) -> float:
    """φ₂(u) = (u − 1 + e^{−u})/u² (φ₂(0) = ½), dimensionless."""
    if abs(u) < SHORT_U:
        return _poly8(-u, _C2)
    if abs(u) < 0.5:
        return _poly16(-u, _C2)
    if u > 1e100:  # u² would overflow
        return (math.expm1(-u) + u) / u / u
    return (math.expm1(-u) + u) / (u * u)


@njit(cache=True, inline="always")
def phi12(u: float) -> tuple[float, float]:
    """(φ₁(u), φ₂(u)) from one series near 0 (φ₁ = 1 − u φ₂, within an ulp there), else :func:`phi1`, :func:`phi2`."""
    if abs(u) < SHORT_U:
        p2 = _poly8(-u, _C2)
        return 1.0 - u * p2, p2
    return phi1(u), phi2(u)


@njit(cache=True, inline="always")
def log1p_ratio(y: float) -> float:
    """λ(y) = log(1 + y)/y (λ(0) = 1), dimensionless, for y > −1.

    The simulator's stop time t* = w λ(y) (:func:`dfa.core.kernel.step`): below |y| = 1/16 the series,
    a short chain of multiply-adds instead of ``log1p`` and a division.
    """
    if abs(y) < SHORT_Y:
        return _poly8(-y, _CL)
    if abs(y) < 0.0625:
        return _poly16(-y, _CL)
    return math.log1p(y) / y


# Taylor coefficients of ρ in x = −P: (n + 1)/(n + 2)!, n = 0 … 17 (first omitted term < 10⁻¹⁸ at |P| < ½)
_CR = tuple((n + 1) / math.factorial(n + 2) for n in range(18))


@njit(cache=True, inline="always")
def rho(u: float) -> float:
    """ρ(u) = (1 − e^{−u}(1 + u))/u² (ρ(0) = ½), dimensionless, for u >= 0.

    Examples
    --------
    >>> rho(0.0), round(rho(1.0), 12)   # ½ and 1 − 2/e
    (0.5, 0.264241117657)
    """
    if u < 0.5:
        s = 0.0
        for n in range(17, -1, -1):
            s = s * (-u) + _CR[n]
        return s
    num = -math.expm1(-u) - u * math.exp(-u)
    if u > 1e100:
        return num / u / u
    return num / (u * u)


@njit(cache=True, inline="never")
def psi(u: float) -> float:
    """ψ(u) = ((1 − e^{−u}) − ½(1 − e^{−2u}))/u² = ½ φ₁(u)² (ψ(0) = ½), for u >= 0.

    With E = 1 − e^{−u}, 1 − e^{−2u} = E(2 − E), so the numerator is ½E²: no cancellation anywhere.
    """
    p1 = phi1(u)
    return 0.5 * p1 * p1


# χ(u) e^{2u} = Σ c_k u^{k−3}, c_k = ((k − 3) 2^{k−1} + 2)/k! > 0, k = 3 … 62: positive terms, no cancellation,
# below u = 5 (the first omitted term is below 10⁻¹⁹ of the sum there); the closed form above (it cancels by
# less than a factor 1.6 there)
_CHI = tuple(((k - 3) * 2.0 ** (k - 1) + 2.0) / math.factorial(k) for k in range(3, 63))


@njit(cache=True, inline="never")
def chi(u: float) -> float:
    """χ(u) = (u − 2(1 − e^{−u}) + ½(1 − e^{−2u}))/u³ (χ(0) = ⅓), for u >= 0."""
    if u < 5.0:
        s = 0.0
        for c in _CHI[::-1]:
            s = s * u + c
        return s * math.exp(-2.0 * u)
    if u > 1e100:
        return (u + 2.0 * math.expm1(-u) - 0.5 * math.expm1(-2.0 * u)) / u / u / u
    return (u + 2.0 * math.expm1(-u) - 0.5 * math.expm1(-2.0 * u)) / (u * u * u)


@njit(cache=True)
def _phi_flat(u: npt.NDArray[np.float64], order: int) -> npt.NDArray[np.float64]:  # pragma: no cover - compiled
    out = np.empty(u.shape[0])
    for i in range(u.shape[0]):
        out[i] = phi1(u[i]) if order == 1 else phi2(u[i])
    return out


def _elementwise(u: ArrayLike, order: int) -> np.ndarray:
    a = np.asarray(u, dtype=float)
    return _phi_flat(np.ascontiguousarray(a).ravel(), order).reshape(a.shape)


def phi1_array(u: ArrayLike) -> np.ndarray:
    """φ₁ elementwise on an array (any shape), the compiled scalar :func:`phi1`."""
    return _elementwise(u, 1)


def phi2_array(u: ArrayLike) -> np.ndarray:
    """φ₂ elementwise on an array (any shape), the compiled scalar :func:`phi2`."""
    return _elementwise(u, 2)
