"""Compiled core of the quantizer describing function (numba, cached): eq. 41, its derivative and inverse.

The reference implementation is :func:`dfa.describing.quantizer_df`, lambdified
from the sympy derivation; this module evaluates the same sum in compiled
loops for the limit-cycle solver (``tests/test_eq41_describing.py`` checks the
two against each other)::

    D(M)  = 2/(πM) + (4/(πM²)) Σ_{k=1}^{⌊M⌋} √((M − k)(M + k))
    D'(M) = −2/(πM²) + Σ_{k=1}^{⌊M⌋} 4(2k² − M²)/(πM³√((M − k)(M + k)))

On an interval [n, n + 1] the substitution M = n + t², t ∈ [0, 1], makes D
smooth (the level k = n contributes √(t²(2n + t²)) = t√(2n + t²)), so the peak
and both branches of D(M) = g are found with Brent's method in t.

All functions take and return plain floats; the root finder is a port of
scipy's ``brentq`` (Brent 1973), so the compiled inverse converges the same way
:func:`scipy.optimize.brentq` does.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

_PI = math.pi


@njit(cache=True, error_model="numpy")
def df_value(m):
    """D(M) of eq. 41 for a scalar M > 0."""
    if m <= 1.0:
        return 2.0 / (_PI * m)
    n = int(math.floor(m))
    s = 0.0
    for k in range(1, n + 1):
        s += math.sqrt((m - k) * (m + k))
    return (2.0 * m + 4.0 * s) / (_PI * m * m)


@njit(cache=True, error_model="numpy")
def df_derivative(m):
    """dD/dM of eq. 41 for a scalar M > 0 (the left derivative at an integer M)."""
    n = int(math.floor(m))
    if n == m:
        n -= 1
    s = -0.5 * m
    for k in range(1, n + 1):
        s += (2.0 * k * k - m * m) / math.sqrt((m - k) * (m + k))
    return 4.0 * s / (_PI * m * m * m)


@njit(cache=True, error_model="numpy")
def df_array(m, derivative=False):
    """D(M), or dD/dM when ``derivative``, for a 1-D array of amplitudes."""
    out = np.empty(m.size)
    for i in range(m.size):
        out[i] = df_derivative(m[i]) if derivative else df_value(m[i])
    return out


@njit(cache=True, error_model="numpy")
def _d_in_t(n, t):
    """D(n + t²) for t in [0, 1]: levels k <= n (the level n + 1 contributes 0 at t = 1)."""
    m = n + t * t
    s = t * math.sqrt(2.0 * n + t * t)  # level k = n without cancellation
    for k in range(1, n):
        s += math.sqrt((m - k) * (m + k))
    return (2.0 * m + 4.0 * s) / (_PI * m * m)


@njit(cache=True, error_model="numpy")
def _dd_dt(n, t):
    """d/dt D(n + t²) = 2t·D'(n + t²), finite at t = 0 (where the level n's √ starts)."""
    m = n + t * t
    r = math.sqrt(2.0 * n + t * t)
    s = 2.0 * (2.0 * n * n - m * m) / r  # 2t · (2n² − M²)/(t·r): the level k = n
    acc = -0.5 * m
    for k in range(1, n):
        acc += (2.0 * k * k - m * m) / math.sqrt((m - k) * (m + k))
    return 4.0 * (s + 2.0 * t * acc) / (_PI * m * m * m)


@njit(cache=True, error_model="numpy")
def _f(kind, n, g, x):
    if kind == 0:
        return _d_in_t(n, x) - g
    return _dd_dt(n, x)


@njit(cache=True, error_model="numpy")
def _brent(kind, n, g, xa, xb, xtol, rtol):
    """scipy's brentq (bracketing, superlinear) on _f(kind, n, g, ·) over [xa, xb]; the ends must bracket."""
    xpre, xcur = xa, xb
    xblk = 0.0
    fblk = 0.0
    spre = 0.0
    scur = 0.0
    fpre = _f(kind, n, g, xpre)
    fcur = _f(kind, n, g, xcur)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    for _ in range(200):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk = xpre
            fblk = fpre
            spre = xcur - xpre
            scur = spre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = 0.5 * (xtol + rtol * abs(xcur))
        sbis = 0.5 * (xblk - xcur)
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre = scur
                scur = stry
            else:
                spre = sbis
                scur = sbis
        else:
            spre = sbis
            scur = sbis
        xpre = xcur
        fpre = fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0 else -delta
        fcur = _f(kind, n, g, xcur)
    return xcur


_EPS4 = 4.0 * np.finfo(np.float64).eps


@njit(cache=True, error_model="numpy")
def interval_peak(n):
    """(M, D) of the maximum of D on [n, n + 1], n >= 1 (D is unimodal there)."""
    t = _brent(1, n, 0.0, 0.0, 1.0, 1e-15, _EPS4)
    return n + t * t, _d_in_t(n, t)


@njit(cache=True, error_model="numpy")
def df_inverse(g, n_stop, mmax, envelope):
    """Amplitudes M > 1 in [1, min(n_stop + 1, mmax)] with D(M) = g, increasing (at most two per interval)."""
    out = np.empty(2 * n_stop + 2)
    count = 0
    d_lo = df_value(1.0)
    for n in range(1, n_stop + 1):
        d_hi = _d_in_t(n, 1.0)
        lo = d_lo
        d_lo = d_hi
        # fast rejection: the minimum on [n, n + 1] is an end; above 1 + envelope n^{-3/2} there is no root (n > 1)
        if g < min(lo, d_hi) - 1e-15 or (n > 1 and g > 1.0 + envelope * n**-1.5):
            continue
        mp, dp = interval_peak(n)
        if g > dp:
            continue
        tp = math.sqrt(mp - n)
        if (lo - g) * (dp - g) <= 0.0 and mp <= mmax:
            t = _brent(0, n, g, 0.0, tp, 1e-15, _EPS4)
            out[count] = n + t * t
            count += 1
        t_hi = 1.0 if n + 1.0 <= mmax else math.sqrt(mmax - n)
        hi_end = n + t_hi * t_hi
        if mp < hi_end and (dp - g) * (_d_in_t(n, t_hi) - g) < 0.0:
            t = _brent(0, n, g, tp, t_hi, 1e-15, _EPS4)
            out[count] = n + t * t
            count += 1
    return out[:count]
