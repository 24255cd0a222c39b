"""Exact ZOH pulse transfer of amplifier lag + device, in closed form (one implementation, compiled).

With a first-order amplifier 1/(α s + 1) between the zero-order hold and the
device 1/(μ s² + β s) (time in samples, T = 1), a = β/μ, b = 1/α, p = e^{−a},
q = e^{−b}, the pulse transfer from the held command to the position is
(derivation in :mod:`dfa.analysis.linear_wall`)::

    G(z) = (n₂z² + n₁z + n₀)/(μ (z − 1)(z − p)(z − q)),
    n₂ = −b f[0, 0, a, b],   n₀ = −b f[a, b, a + b, a + b],
    n₁ = −b (f[0, a, a, b] + f[a, a, b, a + b] + f[0, a, b, b] + f[a, b, b, a + b]),

every coefficient a sum of positive terms built from divided differences of
f(u) = e^{−u} (:mod:`dfa.core.divdiff`, a few ulp): no cancellation for coincident or
close poles (a ≈ b), a = 0, very stiff a or extreme α. When 1/α overflows the lag
is below rounding and G is the device alone, (c₁z + c₀)/(μ(z − 1)(z − p)),
c₁ = f[0, 0, a], c₀ = f[0, a, a]. :func:`dfa.analysis.linear_wall.amplifier_zoh_coefficients`
(the exact linear bound) and the describing function with amplifier lag
(:mod:`dfa.analysis.cycles.characteristic`, varying β_eq) both use :func:`amplifier_zoh`.
``tests/test_controlled_linear.py`` and ``tests/test_eq36_controller_cycles.py`` check
it against ``control.c2d(..., "zoh")`` and 50-digit mpmath.

Examples
--------
>>> n2, n1, n0, p, q = amplifier_zoh(0.0, 1e-9)      # α = 10⁹: the ZOH of 1/(α s³)
>>> [round(c * 6e9, 6) for c in (n2, n1, n0)]
[1.0, 4.0, 1.0]
>>> abs(zoh_lag_response(5.0, 0.0, 1e-3, 0.5) * (1e-3) ** 2 * 5.0 + 1.0) < 1e-2   # ≈ −1/(μω²) at low ω, β = 0
True
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from numpy.typing import ArrayLike

from .divdiff import exp_dd
from .jit import njit

__all__ = ["amplifier_zoh", "zoh_lag_response"]


@njit(cache=True)
def _f(x0: float, x1: float, x2: float, x3: float) -> float:
    return exp_dd(np.array([x0, x1, x2, x3]))


@njit(cache=True)
def amplifier_zoh(a: float, b: float) -> tuple[float, float, float, float, float]:
    """(n₂, n₁, n₀, p, q) of the pulse transfer (module docstring) for a = β/μ >= 0 and b = 1/α > 0 (may be inf)."""
    if not b < np.inf:  # the lag is below rounding: the device alone
        return exp_dd(np.array([0.0, 0.0, a])), exp_dd(np.array([0.0, a, a])), 0.0, math.exp(-a), 0.0
    n2 = -b * _f(0.0, 0.0, a, b)
    n1 = -b * (_f(0.0, a, a, b) + _f(a, a, b, a + b) + _f(0.0, a, b, b) + _f(a, b, b, a + b))
    n0 = -b * _f(a, b, a + b, a + b)
    return n2, n1, n0, math.exp(-a), math.exp(-b)


@njit(cache=True)
def _response(mu: float, beq: float, w: float, lag: float) -> complex:
    """G(e^{jω}) for one (β_eq, ω)."""
    n2, n1, n0, p, q = amplifier_zoh(beq / mu, 1.0 / lag)
    z = complex(math.cos(w), math.sin(w))
    return (n2 * z * z + n1 * z + n0) / (mu * (z - 1.0) * (z - p) * (z - q))


@njit(cache=True)
def _coefficients(a: np.ndarray, b: float) -> np.ndarray:
    out = np.empty((a.size, 5))
    for i in range(a.size):
        out[i, 0], out[i, 1], out[i, 2], out[i, 3], out[i, 4] = amplifier_zoh(a[i], b)
    return out


def zoh_lag_response(
    mu: float, beta_eq: ArrayLike, omega: ArrayLike, lag: float
) -> complex | npt.NDArray[np.complex128]:
    """G(e^{jω}) of the ZOH-sampled amplifier lag + device (module docstring), broadcast over β_eq and ω.

    Parameters
    ----------
    mu : float
        Dimensionless mass μ > 0.
    beta_eq : float or array_like
        (Equivalent) damping >= 0.
    omega : float or array_like
        Frequency in rad per sample, in (0, π].
    lag : float
        Amplifier time constant α > 0 in samples.

    Returns
    -------
    complex or numpy.ndarray of complex
        The pulse response, shape of ``beta_eq`` and ``omega`` broadcast.
    """
    if np.ndim(beta_eq) == 0 and np.ndim(omega) == 0:
        # 0-d here: a number (or a 0-d array), which numpy.typing's ArrayLike does not tell apart
        return complex(_response(float(mu), float(beta_eq), float(omega), float(lag)))  # type: ignore[arg-type]
    beq = np.asarray(beta_eq, dtype=float)
    c = _coefficients(np.ascontiguousarray(beq.ravel()) / mu, 1.0 / lag).reshape(beq.shape + (5,))
    n2, n1, n0, p, q = np.moveaxis(c, -1, 0)
    z = np.exp(1j * np.asarray(omega, dtype=float))
    out = (n2 * z * z + n1 * z + n0) / (mu * (z - 1.0) * (z - p) * (z - q))
    return complex(out) if np.ndim(out) == 0 else out
