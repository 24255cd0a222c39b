"""The relative exponentials ("exprel") of the exact sampled-loop solution, one implementation.

With u = β t/μ the motion under a constant force over a time t (paper eq. 4-5,
:mod:`dfa._kernel`) and the ZOH pulse transfer function (:mod:`dfa.linear`)
need, without cancellation at small u::

    φ₁(u) = (1 − e^{−u})/u                      = Σ (−u)ⁿ/(n + 1)!
    φ₂(u) = (u − 1 + e^{−u})/u²                 = Σ (−u)ⁿ/(n + 2)!
    ψ(u)  = ((1 − e^{−u}) − ½(1 − e^{−2u}))/u²  = Σ (−1)ⁿ (2ⁿ⁻¹ − 1) uⁿ⁻²/n!,  n >= 2
    χ(u)  = (u − 2(1 − e^{−u}) + ½(1 − e^{−2u}))/u³ = Σ (−1)ⁿ⁺¹ (2ⁿ⁻¹ − 2) uⁿ⁻³/n!,  n >= 3

and, for the time at which the device stops inside a sample, the inverse's
relative form λ(y) = log(1 + y)/y = Σ (−y)ⁿ/(n + 1) (λ(0) = 1), y > −1.

(φ₁(0) = 1, φ₂(0) = ½, ψ(0) = ½, χ(0) = ⅓). Each is its series for |u| < ½
(φ₁, φ₂: 16 terms by Estrin's scheme, the simulator's hot path; ψ, χ: 24 terms) and its closed form through
``expm1`` otherwise; λ is its series (16 terms, Estrin) for |y| < 1/16 and ``log1p(y)/y`` otherwise (divided in steps beyond u = 10¹⁰⁰,
where u² or u³ would overflow): a few ulp everywhere (``tests/test_exprel.py`` checks
them against 50-digit mpmath). φ₁ and φ₂ take any real u (negative u appears
in Gil's factor, :func:`dfa.stiffness.gil_factor`); ψ and χ are used for
u >= 0 only (their closed forms overflow for u < −354).

The scalar functions are numba ``njit`` functions: the compiled simulator
inlines them, and Python calls them like plain functions on floats. The
``*_array`` wrappers evaluate the same compiled scalar code elementwise on
arrays of any shape.

Developers: numba's on-disk cache of :mod:`dfa._kernel` is keyed on that
file alone and does not notice edits here (or to
:func:`dfa.criterion.spring_energy_core`, also compiled into the kernel):
after such an edit clear the cache (``rm -rf .cache/numba``), or the kernel
keeps the old code. ``tests/test_kernel_steps.py`` compares the compiled
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
from numba import njit

__all__ = ["phi1", "phi2", "psi", "chi", "log1p_ratio", "phi1_array", "phi2_array"]


# Taylor coefficients in x = −u: φ₁ = Σ xⁿ/(n + 1)!, φ₂ = Σ xⁿ/(n + 2)!, n = 0 … 15
# (the first omitted term is below 2·10⁻¹⁸ of the value for |u| < ½)
_C1 = tuple(1.0 / math.factorial(n + 1) for n in range(16))
_C2 = tuple(1.0 / math.factorial(n + 2) for n in range(16))
# λ(y) = Σ xⁿ/(n + 1) in x = −y, n = 0 … 15 (the first omitted term is below 2⁻⁶⁴/17 for |y| < 1/16)
_CL = tuple(1.0 / (n + 1) for n in range(16))


@njit(cache=True, inline="always")
def _poly16(x, c):
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
def phi1(u: float) -> float:
    """φ₁(u) = (1 − e^{−u})/u (φ₁(0) = 1), dimensionless."""
    if abs(u) < 0.5:
        return _poly16(-u, _C1)
    return -math.expm1(-u) / u


@njit(cache=True, inline="always")
def phi2(u: float) -> float:
    """φ₂(u) = (u − 1 + e^{−u})/u² (φ₂(0) = ½), dimensionless."""
    if abs(u) < 0.5:
        return _poly16(-u, _C2)
    if u > 1e100:  # u² would overflow
        return (math.expm1(-u) + u) / u / u
    return (math.expm1(-u) + u) / (u * u)


@njit(cache=True, inline="always")
def log1p_ratio(y: float) -> float:
    """λ(y) = log(1 + y)/y (λ(0) = 1), dimensionless, for y > −1.

    The simulator's stop time t* = w λ(y) (:func:`dfa._kernel.step`): below |y| = 1/16 the series,
    a short chain of multiply-adds instead of ``log1p`` and a division.
    """
    if abs(y) < 0.0625:
        return _poly16(-y, _CL)
    return math.log1p(y) / y


@njit(cache=True, inline="always")
def psi(u: float) -> float:
    """ψ(u) = ((1 − e^{−u}) − ½(1 − e^{−2u}))/u² (ψ(0) = ½), for u >= 0."""
    if abs(u) < 0.5:
        s = 0.0
        fact = 2.0  # n!
        upow = 1.0  # u^(n-2)
        sign = 1.0
        for n in range(2, 26):
            if n > 2:
                fact *= n
                upow *= u
                sign = -sign
            s += sign * (2.0 ** (n - 1) - 1.0) * upow / fact
        return s
    if u > 1e100:
        return (-math.expm1(-u) + 0.5 * math.expm1(-2.0 * u)) / u / u
    return (-math.expm1(-u) + 0.5 * math.expm1(-2.0 * u)) / (u * u)


@njit(cache=True, inline="always")
def chi(u: float) -> float:
    """χ(u) = (u − 2(1 − e^{−u}) + ½(1 − e^{−2u}))/u³ (χ(0) = ⅓), for u >= 0."""
    if abs(u) < 0.5:
        s = 0.0
        fact = 6.0
        upow = 1.0
        sign = 1.0
        for n in range(3, 27):
            if n > 3:
                fact *= n
                upow *= u
                sign = -sign
            s += sign * (2.0 ** (n - 1) - 2.0) * upow / fact
        return s
    if u > 1e100:
        return (u + 2.0 * math.expm1(-u) - 0.5 * math.expm1(-2.0 * u)) / u / u / u
    return (u + 2.0 * math.expm1(-u) - 0.5 * math.expm1(-2.0 * u)) / (u * u * u)


@njit(cache=True)
def _phi_flat(u, order):  # pragma: no cover - compiled
    out = np.empty(u.shape[0])
    for i in range(u.shape[0]):
        out[i] = phi1(u[i]) if order == 1 else phi2(u[i])
    return out


def _elementwise(u, order: int) -> np.ndarray:
    a = np.asarray(u, dtype=float)
    return _phi_flat(np.ascontiguousarray(a).ravel(), order).reshape(a.shape)


def phi1_array(u) -> np.ndarray:
    """φ₁ elementwise on an array (any shape), the compiled scalar :func:`phi1`."""
    return _elementwise(u, 1)


def phi2_array(u) -> np.ndarray:
    """φ₂ elementwise on an array (any shape), the compiled scalar :func:`phi2`."""
    return _elementwise(u, 2)
