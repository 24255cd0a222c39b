"""Compiled core of the quantizer describing function (numba, cached): eq. 41, its derivative and inverse.

The reference implementation is :func:`dfa.analysis.describing.quantizer_df`, lambdified
from the sympy derivation; this module evaluates the same sum in compiled
loops for the limit-cycle solver (``tests/test_eq41_describing.py`` checks the
two against each other)::

    D(M)  = 2/(πM) + (4/(πM²)) Σ_{k=1}^{⌊M⌋} √((M − k)(M + k))
    D'(M) = −2/(πM²) + Σ_{k=1}^{⌊M⌋} 4(2k² − M²)/(πM³√((M − k)(M + k)))

On an interval [n, n + 1] the substitution M = n + t², t ∈ [0, 1], makes D
smooth (the level k = n contributes √(t²(2n + t²)) = t√(2n + t²)), so the peak
and both branches of D(M) = g are found with Brent's method in t.

Large amplitudes (M >= ``ASYMPTOTIC_FROM`` = 1000 ticks) use the generalised
Euler–Maclaurin expansion (Navot 1961) of the sum instead of its ⌊M⌋ terms:
f(x) = √(M² − x²) is even (every regular end correction at x = 0 vanishes)
and has an algebraic singularity at x = M, f = √(2M)·Σ_r binom(½, r)(−u/(2M))^r u^{½ + r}
with u = M − x, so with θ = M − ⌊M⌋ (the lattice points lie at u = θ, θ + 1, …)::

    D(M) = 1 + (4√2/π) M^{−3/2} Σ_{r=0}^{R} binom(½, r) (−1/(2M))^r ζ(−½ − r, θ)

with ζ(s, q) the Hurwitz zeta function (its own Euler–Maclaurin sum here).
The leading term gives the envelope constants (4√2/π)|ζ(−½)| = 0.3743 at the
integers; R = 4 leaves a truncation error below 1e-20 at M = 1000, and the
switch is tested for continuity against the exact sum and against mpmath.

All functions take and return plain floats; the root finder is a port of
scipy's ``brentq`` (Brent 1973), so the compiled inverse converges the same way
:func:`scipy.optimize.brentq` does, except that it returns NaN (never a bracket
end) when the ends do not bracket a sign change or it has not converged.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from .jit import njit

_PI = math.pi

#: Amplitude (ticks) from which D and D' use the asymptotic expansion instead of the ⌊M⌋-term sum.
ASYMPTOTIC_FROM = 1000.0
_R_TERMS = 5
# binom(½, r)·(−½)^r, r = 0..4
_ASYM_C = np.array([1.0, -0.25, -0.03125, -0.0078125, -0.00244140625])
# B_2j/(2j)!, j = 1..8
_BERN = np.array(
    [
        1.0 / 12,
        -1.0 / 720,
        1.0 / 30240,
        -1.0 / 1209600,
        1.0 / 47900160,
        -691.0 / 1307674368000,
        1.0 / 74724249600,
        -3617.0 / 10670622842880000,
    ]
)
_K_ASYM = 4.0 * math.sqrt(2.0) / math.pi


@njit(cache=True, error_model="numpy")
def hurwitz_zeta(s: float, q: float) -> float:
    """Hurwitz ζ(s, q) = Σ_{k>=0} (q + k)^{−s} (analytically continued), real s ≠ 1, q > 0 (or q = 0 when s < 0).

    Euler–Maclaurin with a shift of 20 terms and 8 Bernoulli corrections
    (relative error ~1e-16 for −6 <= s <= 2).
    """
    n = 20
    total: float = 0.0
    for k in range(n):
        x = q + k
        if x > 0.0:
            total += x ** (-s)
    a = q + n
    total += a ** (1.0 - s) / (s - 1.0) + 0.5 * a ** (-s)
    poch = s  # s(s + 1)…(s + 2j − 2)
    for j in range(8):
        total += _BERN[j] * poch * a ** (-s - 2.0 * j - 1.0)
        poch *= (s + 2.0 * j + 1.0) * (s + 2.0 * j + 2.0)
    return total


@njit(cache=True, error_model="numpy")
def _asym_value(m: float, th: float) -> float:
    """D(M) − 1 by the expansion of the module docstring (M >= ASYMPTOTIC_FROM, θ = M − ⌊M⌋ in [0, 1])."""
    acc = 0.0
    scale = 1.0
    for r in range(_R_TERMS):
        acc += _ASYM_C[r] * scale * hurwitz_zeta(-0.5 - r, th)
        scale /= m
    return _K_ASYM * acc / (m * math.sqrt(m))


@njit(cache=True, error_model="numpy")
def _asym_derivative(m: float, th: float, t: float) -> float:
    """dD/dM by the expansion at M = ⌊M⌋ + θ, θ in (0, 1]; with t >= 0 (θ = t²) returns 2t·dD/dM, finite at t = 0.

    ∂ζ(s, θ)/∂θ = −s ζ(s + 1, θ); the singular θ^{−½} of ζ(½, θ) is taken out so that 2t·½θ^{−½} = 1 exactly.
    """
    a = 0.0  # Σ c_r M^{−r} ζ(−½ − r, θ)
    da = 0.0  # its d/dM without the singular ½θ^{−½}
    scale = 1.0
    for r in range(_R_TERMS):
        z = hurwitz_zeta(-0.5 - r, th)
        a += _ASYM_C[r] * scale * z
        da -= _ASYM_C[r] * r * scale / m * z
        if r == 0:
            da += 0.5 * hurwitz_zeta(0.5, th + 1.0)  # ½ζ(½, θ) = ½θ^{−½} + ½ζ(½, θ + 1)
        else:
            da += _ASYM_C[r] * scale * (0.5 + r) * hurwitz_zeta(0.5 - r, th)
        scale /= m
    m32 = m * math.sqrt(m)
    base = -1.5 * a / (m32 * m) + da / m32
    if t >= 0.0:
        return _K_ASYM * (2.0 * t * base + 1.0 / m32)
    return _K_ASYM * (base + 0.5 / (math.sqrt(th) * m32))


@njit(cache=True, error_model="numpy")
def df_value(m: float) -> float:
    """D(M) of eq. 41 for a scalar M > 0."""
    if m <= 1.0:
        return 2.0 / (_PI * m)
    if m >= ASYMPTOTIC_FROM:
        return 1.0 + _asym_value(m, m % 1.0)  # not m − floor(m): math.floor is an int64 in numba (overflows)
    n = int(math.floor(m))
    s = 0.0
    for k in range(1, n + 1):
        s += math.sqrt((m - k) * (m + k))
    return (2.0 * m + 4.0 * s) / (_PI * m * m)


@njit(cache=True, error_model="numpy")
def df_derivative(m: float) -> float:
    """dD/dM of eq. 41 for a scalar M > 0 (the left derivative at an integer M)."""
    if m >= ASYMPTOTIC_FROM:
        th = m % 1.0
        return _asym_derivative(m, 1.0 if th == 0.0 else th, -1.0)  # θ = 1: the left derivative at an integer
    n = int(math.floor(m))
    if n == m:
        n -= 1
    s = -0.5 * m
    for k in range(1, n + 1):
        s += (2.0 * k * k - m * m) / math.sqrt((m - k) * (m + k))
    return 4.0 * s / (_PI * m * m * m)


@njit(cache=True, error_model="numpy")
def df_array(m: npt.NDArray[np.float64], derivative: bool = False) -> npt.NDArray[np.float64]:
    """D(M), or dD/dM when ``derivative``, for a 1-D array of amplitudes."""
    out = np.empty(m.size)
    for i in range(m.size):
        out[i] = df_derivative(m[i]) if derivative else df_value(m[i])
    return out


@njit(cache=True, error_model="numpy")
def _d_in_t(n: int, t: float) -> float:
    """D(n + t²) for t in [0, 1]: levels k <= n (the level n + 1 contributes 0 at t = 1)."""
    m = n + t * t
    if n >= ASYMPTOTIC_FROM:
        return 1.0 + _asym_value(m, t * t)
    s = t * math.sqrt(2.0 * n + t * t)  # level k = n without cancellation
    for k in range(1, n):
        s += math.sqrt((m - k) * (m + k))
    return (2.0 * m + 4.0 * s) / (_PI * m * m)


@njit(cache=True, error_model="numpy")
def _dd_dt(n: int, t: float) -> float:
    """d/dt D(n + t²) = 2t·D'(n + t²), finite at t = 0 (where the level n's √ starts)."""
    m = n + t * t
    if n >= ASYMPTOTIC_FROM:
        return _asym_derivative(m, t * t, t)
    r = math.sqrt(2.0 * n + t * t)
    s = 2.0 * (2.0 * n * n - m * m) / r  # 2t · (2n² − M²)/(t·r): the level k = n
    acc = -0.5 * m
    for k in range(1, n):
        acc += (2.0 * k * k - m * m) / math.sqrt((m - k) * (m + k))
    return 4.0 * (s + 2.0 * t * acc) / (_PI * m * m * m)


@njit(cache=True, error_model="numpy")
def _f(kind: int, n: int, g: float, x: float) -> float:
    if kind == 0:
        return _d_in_t(n, x) - g
    return _dd_dt(n, x)


@njit(cache=True, error_model="numpy")
def _brent(kind: int, n: int, g: float, xa: float, xb: float, xtol: float, rtol: float) -> float:
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
    if not ((fpre < 0.0) != (fcur < 0.0)):  # no sign change (or NaN): nothing to converge to
        return math.nan
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
    return math.nan  # not converged in 200 steps: the caller reports it, never a bracket end


_EPS4 = 4.0 * np.finfo(np.float64).eps


@njit(cache=True, error_model="numpy")
def interval_peak(n: int) -> tuple[float, float]:
    """(M, D) of the maximum of D on [n, n + 1], n >= 1 (D is unimodal there)."""
    t = _brent(1, n, 0.0, 0.0, 1.0, 1e-15, _EPS4)
    return n + t * t, _d_in_t(n, t)


@njit(cache=True, error_model="numpy")
def df_inverse(g: float, n_stop: int, mmax: float, envelope: float) -> tuple[npt.NDArray[np.float64], int]:
    """Amplitudes M > 1 in [1, min(n_stop + 1, mmax)] with D(M) = g, increasing (at most two per interval).

    Returns (roots, failures): ``failures`` counts the Brent solves (peak or
    root) that did not converge; their intervals may hold roots not returned.
    """
    out = np.empty(2 * n_stop + 2)
    count = 0
    failures = 0
    d_lo = df_value(1.0)
    for n in range(1, n_stop + 1):
        d_hi = _d_in_t(n, 1.0)
        lo = d_lo
        d_lo = d_hi
        # fast rejection: the minimum on [n, n + 1] is an end; above 1 + envelope n^{-3/2} there is no root (n > 1)
        if g < min(lo, d_hi) - 1e-15 or (n > 1 and g > 1.0 + envelope * n**-1.5):
            continue
        mp, dp = interval_peak(n)
        if mp != mp:
            failures += 1
            continue
        if g > dp:
            continue
        tp = math.sqrt(mp - n)
        if (lo - g) * (dp - g) <= 0.0 and mp <= mmax:
            t = _brent(0, n, g, 0.0, tp, 1e-15, _EPS4)
            if t != t:
                failures += 1
            else:
                out[count] = n + t * t
                count += 1
        t_hi = 1.0 if n + 1.0 <= mmax else math.sqrt(mmax - n)
        hi_end = n + t_hi * t_hi
        if mp < hi_end and (dp - g) * (_d_in_t(n, t_hi) - g) < 0.0:
            t = _brent(0, n, g, tp, t_hi, 1e-15, _EPS4)
            if t != t:
                failures += 1
            else:
                out[count] = n + t * t
                count += 1
    return out[:count], failures
