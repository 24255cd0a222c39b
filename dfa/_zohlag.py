"""Exact ZOH pulse response of amplifier lag + device, compiled (numba, cached).

With a first-order amplifier 1/(α s + 1) between the zero-order hold and the
device 1/(μ s² + β_eq s) (time in samples, T = 1), the ZOH-sampled plant from
the held command to the position has the states (f, v, ξ) — amplifier force,
velocity, position — driven by the held input u::

    f' = λ(u − f),   v' = f/μ − a v,   ξ' = v,       λ = 1/α,  a = β_eq/μ.

Over one sample, (u, f, v, ξ) evolves by E = exp(A) with the lower-bidiagonal
A of the chain u → f → v → ξ. A is Metzler (off-diagonals >= 0), so
A + cI (c = max(λ, a)) is non-negative; scaling and squaring its Taylor series
adds only non-negative terms, which gives every entry of E to a small relative
error (no cancellation, including a ≈ λ, a = 0 and very stiff a), where the
partial-fraction form λ/(λ − a)·[G_d(a) − G_d(λ)] would cancel. From
E the pulse transfer function is, by forward substitution of the triangular
system (z = e^{jω})::

    y_f = Γ_f/(z − q),  y_v = (Γ_v + Φ_vf y_f)/(z − p),  P_d = (Γ_ξ + Φ_ξf y_f + Φ_ξv y_v)/(z − 1)

with q = e^{−λ}, p = e^{−a}, Γ = E[:, u] and Φ the other entries of E.
``tests/test_controller_cycles.py`` checks P_d against ``control.c2d(..., "zoh")``.

Examples
--------
>>> import numpy as np
>>> c = zoh_lag_coefficients(np.array([0.02]), 5.0, 0.5)
>>> c.shape
(1, 8)
>>> bool(abs(c[0, 7] - np.exp(-0.02)) < 1e-15)   # p = e^{-a}
True
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["zoh_lag_coefficients", "zoh_lag_response"]

_TAYLOR_TERMS = 40


@njit(cache=True, error_model="numpy")
def _lower_matmul(x, y, out):
    """out = x @ y for 4×4 lower-triangular x, y (no allocation)."""
    for i in range(4):
        for j in range(4):
            acc = 0.0
            for k in range(j, i + 1):
                acc += x[i, k] * y[k, j]
            out[i, j] = acc


@njit(cache=True, error_model="numpy")
def _expm_chain(lam, inv_mu, a):
    """exp(A) of the 4×4 lower-bidiagonal Metzler chain (u, f, v, ξ), entrywise-accurate (module docstring).

    Scaling and squaring multiplies rounding errors by about 2^s ≈ max(λ, a)/4: the relative error of an
    entry is ~1e-13 for max(λ, a) <= 10³ and grows in proportion beyond (α < 10⁻³ or very stiff β_eq/μ).
    """
    c = max(lam, a)
    nmat = np.zeros((4, 4))
    nmat[0, 0] = c
    nmat[1, 0] = lam
    nmat[1, 1] = c - lam
    nmat[2, 1] = inv_mu
    nmat[2, 2] = c - a
    nmat[3, 2] = 1.0
    nmat[3, 3] = c
    norm = max(c, lam + c - lam, inv_mu + c - a, 1.0 + c)
    s = 0
    if norm > 4.0:
        s = int(math.ceil(math.log2(norm / 4.0)))
    scale = 2.0**-s
    nmat *= scale
    # Taylor series of exp(N/2^s) (norm <= 4: 40 terms leave < 1e-20): every term non-negative
    out = np.eye(4)
    term = np.eye(4)
    tmp = np.empty((4, 4))
    for k in range(1, _TAYLOR_TERMS):
        _lower_matmul(term, nmat, tmp)
        done = True
        for i in range(4):
            for j in range(i + 1):
                term[i, j] = tmp[i, j] / k
                out[i, j] += term[i, j]
                if term[i, j] > 1e-17 * out[i, j]:  # non-negative terms: stop when none moves its entry
                    done = False
        if done:
            break
    out *= math.exp(-c * scale)
    for _ in range(s):
        _lower_matmul(out, out, tmp)
        out[:, :] = tmp
    return out


@njit(cache=True, error_model="numpy")
def _coefficients(a, lam, inv_mu):
    out = np.empty((a.size, 8))
    for i in range(a.size):
        e = _expm_chain(lam, inv_mu, a[i])
        # Γ_f, Γ_v, Γ_ξ, Φ_vf, Φ_ξf, Φ_ξv, q, p
        out[i, 0] = e[1, 0]
        out[i, 1] = e[2, 0]
        out[i, 2] = e[3, 0]
        out[i, 3] = e[2, 1]
        out[i, 4] = e[3, 1]
        out[i, 5] = e[3, 2]
        out[i, 6] = e[1, 1]
        out[i, 7] = e[2, 2]
    return out


@njit(cache=True, error_model="numpy")
def _response_scalar(mu, beq, w, lag):
    """P_d(e^{jω}) for one (β_eq, ω): the scalar path of the root finders (same arithmetic as the array path)."""
    e = _expm_chain(1.0 / lag, 1.0 / mu, beq / mu)
    z = complex(math.cos(w), math.sin(w))
    yf = e[1, 0] / (z - e[1, 1])
    yv = (e[2, 0] + e[2, 1] * yf) / (z - e[2, 2])
    return (e[3, 0] + e[3, 1] * yf + e[3, 2] * yv) / (z - 1.0)


def zoh_lag_coefficients(a, mu: float, lag: float) -> np.ndarray:
    """Entries (Γ_f, Γ_v, Γ_ξ, Φ_vf, Φ_ξf, Φ_ξv, q, p) of the one-sample transition, per a = β_eq/μ.

    Parameters
    ----------
    a : array_like
        β_eq/μ >= 0 (1/samples).
    mu : float
        Dimensionless mass μ > 0.
    lag : float
        Amplifier time constant α > 0 in samples.

    Returns
    -------
    numpy.ndarray
        Shape ``a.shape + (8,)``.
    """
    arr = np.asarray(a, dtype=float)
    out = _coefficients(np.ascontiguousarray(arr.ravel()), 1.0 / lag, 1.0 / mu)
    return out.reshape(arr.shape + (8,))


def zoh_lag_response(mu: float, beta_eq, omega, lag: float):
    """P_d(e^{jω}) of the ZOH-sampled amplifier lag + device (module docstring), broadcast over β_eq and ω.

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
        return complex(_response_scalar(float(mu), float(beta_eq), float(omega), float(lag)))
    c = zoh_lag_coefficients(np.asarray(beta_eq, dtype=float) / mu, mu, lag)
    gf, gv, gx, fvf, fxf, fxv, q, p = np.moveaxis(c, -1, 0)
    z = np.exp(1j * np.asarray(omega, dtype=float))
    yf = gf / (z - q)
    yv = (gv + fvf * yf) / (z - p)
    out = (gx + fxf * yf + fxv * yv) / (z - 1.0)
    return complex(out) if np.ndim(out) == 0 else out
