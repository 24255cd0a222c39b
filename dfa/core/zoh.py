"""The exact ZOH pulse transfer of the device, without cancellation (one implementation).

The device 1/(μs² + βs) (paper eq. 4 without Coulomb friction; time in samples) behind a zero-order hold
has the pulse transfer (``control.c2d(…, 'zoh')`` in closed form)::

    G_d(z) = (c₁ z + c₀) / (μ (z − 1)(z − p)),   a = β/μ = bT/m,   p = e^{−a},
    c₁ = (a − 1 + p)/a²,   c₀ = (1 − p − a p)/a²       (c₁ = c₀ = ½ at a = 0).

:func:`zoh_coefficients` evaluates (c₁, c₀, p) through the relative exponentials of :mod:`dfa.core.exprel`;
:func:`c1_minus_c0` gives c₁ − c₀ by its series where the closed form cancels. The exact linear bound
(:mod:`dfa.analysis.linear`), the loop's frequency response (:mod:`dfa.analysis.loop`) and the harmonic balance
(:mod:`dfa.analysis.cycles`) all take them from here.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .exprel import phi1, phi1_array, phi2, phi2_array

__all__ = ["zoh_coefficients", "c1_minus_c0"]

# c₁ − c₀ = Σ (2 − n)(−a)^{n−2}/n! (= a/6 − a²/12 + …), exact coefficients
_DC_TUPLE = tuple(((2.0 - n) / math.factorial(n)) for n in range(17, 1, -1))


def zoh_coefficients(a: Any) -> tuple[Any, Any, Any]:
    """(c₁, c₀, p) of the ZOH pulse transfer function, without cancellation for small a (plain floats for a float).

    c₁ = φ₂(a) and, below a = ½, c₀ = φ₁(a) − φ₂(a) (:mod:`dfa.core.exprel`); c₀ = (1 − p − a p)/a² above.

    Examples
    --------
    >>> c1, c0, p = zoh_coefficients(0.0)
    >>> c1, c0, p
    (0.5, 0.5, 1.0)
    """
    if isinstance(a, float):
        pf = math.exp(-a)
        c1f = phi2(a)
        return c1f, (phi1(a) - c1f if a < 0.5 else (1.0 - pf - a * pf) / (a * a)), pf
    a = np.asarray(a, dtype=float)
    p = np.exp(-a)
    c1 = phi2_array(a)
    al = np.where(a < 0.5, 1.0, a)
    with np.errstate(invalid="ignore", divide="ignore"):
        c0 = np.where(a < 0.5, phi1_array(a) - c1, (1.0 - p - al * p) / (al * al))
    return c1, c0, p


def c1_minus_c0(a: float) -> float:
    """c₁ − c₀ = (a(1 + p) − 2(1 − p))/a² > 0 for a > 0, without cancellation (series below a = ½)."""
    if a >= 0.5:
        p = math.exp(-a)
        return (a * (1.0 + p) + 2.0 * math.expm1(-a)) / (a * a)
    s = 0.0
    for k in _DC_TUPLE:
        s = s * -a + k
    return s
