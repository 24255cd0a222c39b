"""Describing functions of the encoder quantizer and of Coulomb friction (paper section 7).

Both are derived symbolically with sympy, as the Fourier fundamental of the
nonlinearity over one period of a sinusoidal input, and turned into fast
numeric functions with :func:`sympy.lambdify` once (cached):

* **Quantizer** q(ξ) = ⌊ξ⌋ + ½ (odd, static, so its describing function is real
  and frequency independent). It is a sum of relays: ½·sgn(ξ) plus a unit
  step at every level ±k, k = 1, 2, …. sympy integrates the fundamental of one
  level crossed by ξ = M sin θ; summing the ⌊M⌋ crossed levels gives eq. 41::

      D(M) = 2/(π M) + (4/(π M)) Σ_{k=1}^{⌊M⌋} √(1 − (k/M)²)

  D equals 2/(πM) for M ≤ 1, is continuous, peaks at D ≈ 1.1206 near
  M ≈ 1.242 and tends to 1, oscillating: 1 − D(n) ≈ 0.3743 n^{-3/2} at the
  integers (local minima) and D − 1 ≈ 0.168 n^{-3/2} at the maxima near n + 0.30.
  From M = 1000 ticks (``dfa.core.dfcore.ASYMPTOTIC_FROM``) on, D and D' are evaluated
  by a generalised Euler–Maclaurin expansion in the Hurwitz zeta function
  (see :mod:`dfa.core.dfcore`): O(1) work instead of ⌊M⌋ terms, exact to rounding,
  and valid up to the largest float (the level count would overflow int64).
* **Coulomb friction** σ·sgn(ξ') driven by the velocity ξ' = Mω cos ωτ of
  ξ = M sin ωτ: the relay's fundamental is (4σ/π) cos ωτ, i.e. a describing
  function 4σ/(πA) of the velocity amplitude A = Mω, or an equivalent viscous
  damping 4σ/(πMω) (eq. 38-40).

:func:`numeric_df` computes the describing function of any odd static
nonlinearity by adaptive quadrature over one period and cross-checks both.
:class:`~dfa.analysis.nonlinearities.QuantizerNonlinearity` and
:class:`~dfa.analysis.nonlinearities.CoulombNonlinearity` (in their own module, so that the everyday
commands do not load python-control) subclass :class:`control.DescribingFunctionNonlinearity`, so python-control's
``describing_function``, ``describing_function_response`` and
``describing_function_plot`` accept them. python-control's generic numeric
describing function (``try_method=False``) uses a 100-point rectangle rule on
the discontinuous staircase; its error against the exact D(M) is about 1e-2
(see ``tests/test_eq41_describing.py``, which measures it).

Examples
--------
>>> import numpy as np
>>> d = quantizer_df([0.5, 1.0, 1.242, 50.0])
>>> np.round(d, 4).tolist()
[1.2732, 0.6366, 1.1206, 0.9989]
>>> round(coulomb_equivalent_damping(sigma=1.0, amplitude=2.0, omega=0.5), 6)   # 4σ/(πMω)
1.27324
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from ..checks import check_positive, check_positive_array, check_real_array, check_sigma, format_value
from ..core import dfcore
from ..errors import DFATypeError, DFAValueError

if TYPE_CHECKING:
    import sympy as sp

__all__ = [
    "quantizer_df",
    "quantizer_df_derivative",
    "quantizer_df_inverse",
    "quantizer_df_expression",
    "coulomb_df",
    "coulomb_equivalent_damping",
    "coulomb_df_expression",
    "numeric_df",
    "quantizer_df_peak",
    "DF_ENVELOPE",
]

#: Envelope constant: |D(M) − 1| <= DF_ENVELOPE · ⌊M⌋^{-3/2} for M >= 1
#: (the limits of the scaled excursions are 0.3743 below 1 and 0.1681 above).
DF_ENVELOPE = 0.38


# ---------------------------------------------------------------- derivations
@lru_cache(maxsize=1)
def _level_derivation() -> tuple[sp.Symbol, sp.Symbol, sp.Expr, sp.Expr, sp.Expr]:
    """sympy: fundamental of a unit relay with dead zone k driven by M sin θ.

    Returns the sympy symbols (M, k) and expressions (N_k(M), dN_k/dM), where
    N_k(M) = b1/M is the describing function of one level crossing, s(x) = H(x − k) − H(−x − k).
    The cosine coefficient a1 is derived too and must vanish (the describing function is real).
    """
    import sympy as sp

    M, k, th = sp.symbols("M k theta", positive=True)
    t0 = sp.asin(k / M)  # where M sin θ crosses the level k (0 <= k <= M)
    # one period: +1 on (t0, π − t0), −1 on (π + t0, 2π − t0), 0 elsewhere
    b1 = (
        sp.integrate(sp.sin(th), (th, t0, sp.pi - t0)) - sp.integrate(sp.sin(th), (th, sp.pi + t0, 2 * sp.pi - t0))
    ) / sp.pi
    a1 = (
        sp.integrate(sp.cos(th), (th, t0, sp.pi - t0)) - sp.integrate(sp.cos(th), (th, sp.pi + t0, 2 * sp.pi - t0))
    ) / sp.pi
    if sp.simplify(a1) != 0:  # pragma: no cover - a derivation error, not a user error
        raise RuntimeError(f"quantizer level describing function is not real: a1 = {a1}")
    level = sp.simplify(b1 / M)  # = 4 sqrt(1 - k²/M²)/(π M)
    # numerically better form: sqrt((M − k)(M + k)) avoids cancellation near k ≈ M
    stable = 4 * sp.sqrt((M - k) * (M + k)) / (sp.pi * M**2)
    if sp.simplify(level - stable) != 0:  # pragma: no cover
        raise RuntimeError(f"unexpected level describing function {level}")
    return M, k, level, sp.diff(stable, M), stable


@lru_cache(maxsize=1)
def _level_functions() -> tuple[Callable, Callable]:
    import sympy as sp

    M, k, _level, dlevel, stable = _level_derivation()
    return sp.lambdify((k, M), stable, "numpy"), sp.lambdify((k, M), dlevel, "numpy")


def quantizer_df_expression() -> sp.Expr:
    """sympy expression of eq. 41, D(M), with the sum over the ⌊M⌋ crossed levels.

    Examples
    --------
    >>> import sympy as sp
    >>> expr = quantizer_df_expression()
    >>> M = sorted(expr.free_symbols, key=str)[0]
    >>> float(expr.subs(M, sp.Rational(1, 2)).doit()) == 4 / sp.pi.evalf() / 1   # 2/(π·½)
    True
    """
    import sympy as sp

    M, k, level, _d, _s = _level_derivation()
    return sp.Rational(1, 2) * level.subs(k, 0) + sp.Sum(level, (k, 1, sp.floor(M)))


@lru_cache(maxsize=1)
def _coulomb_derivation() -> tuple[sp.Symbol, sp.Symbol, sp.Expr]:
    import sympy as sp

    A, sig, th = sp.symbols("A sigma theta", positive=True)
    # relay σ·sgn(A cos θ): +σ on (−π/2, π/2), −σ on (π/2, 3π/2); fundamental along cos θ
    a1 = (
        sp.integrate(sig * sp.cos(th), (th, -sp.pi / 2, sp.pi / 2))
        - sp.integrate(sig * sp.cos(th), (th, sp.pi / 2, 3 * sp.pi / 2))
    ) / sp.pi
    b1 = (
        sp.integrate(sig * sp.sin(th), (th, -sp.pi / 2, sp.pi / 2))
        - sp.integrate(sig * sp.sin(th), (th, sp.pi / 2, 3 * sp.pi / 2))
    ) / sp.pi
    if sp.simplify(b1) != 0:  # pragma: no cover
        raise RuntimeError("Coulomb describing function is not in phase with the velocity")
    return A, sig, sp.simplify(a1 / A)


def coulomb_df_expression() -> sp.Expr:
    """sympy expression of the Coulomb describing function 4σ/(πA) of velocity amplitude A.

    Examples
    --------
    >>> coulomb_df_expression()
    4*sigma/(pi*A)
    """
    return _coulomb_derivation()[2]


@lru_cache(maxsize=1)
def _coulomb_function() -> Callable:
    import sympy as sp

    A, sig, expr = _coulomb_derivation()
    return sp.lambdify((A, sig), expr, "numpy")


# ------------------------------------------------------------------ numerics
def _amplitudes(amplitude: ArrayLike, name: str = "amplitude") -> np.ndarray:
    fix = (
        "give the sinusoid's amplitude in encoder ticks"
        if name == "amplitude"
        else "give the frequency in rad per sample"
    )
    return check_positive_array(name, amplitude, fix)


def _level_sum(m: np.ndarray, fn: Callable, budget: int = 4_000_000) -> np.ndarray:
    """Σ_{k=1}^{⌊M⌋} fn(k, M), vectorised over M in chunks of at most ``budget`` terms."""
    flat = m.ravel()
    out = np.zeros_like(flat)
    order = np.argsort(flat)
    levels = np.floor(flat[order]).astype(np.int64)
    i = 0
    while i < flat.size:
        j = i + 1  # sorted, so the chunk's largest ⌊M⌋ is its last
        while j < flat.size and (j - i + 1) * max(1, levels[j]) <= budget:
            j += 1
        idx, nmax = order[i:j], int(levels[j - 1])
        if nmax >= 1 and nmax * (j - i) <= budget:
            k = np.arange(1, nmax + 1, dtype=float)[None, :]
            mm = flat[idx][:, None]
            out[idx] = np.where(k <= mm, fn(k, mm), 0.0).sum(axis=1)
        elif nmax >= 1:  # one huge amplitude: sum its levels in blocks
            mv = float(flat[idx[0]])
            out[idx[0]] = sum(
                float(np.sum(fn(np.arange(s, min(nmax, s + budget - 1) + 1, dtype=float), mv)))
                for s in range(1, nmax + 1, budget)
            )
        i = j
    return out.reshape(m.shape)


def quantizer_df(amplitude: ArrayLike) -> Any:  # float for one amplitude, else numpy.ndarray
    """Describing function D(M) of the quantizer q(ξ) = ⌊ξ⌋ + ½ (paper eq. 41).

    Parameters
    ----------
    amplitude : float or array_like
        Amplitude M > 0 of the sinusoid ξ = M sin θ, in encoder ticks.

    Returns
    -------
    float or numpy.ndarray
        D(M), dimensionless (force ticks per position tick); real because the
        quantizer is odd and static.

    Raises
    ------
    DFAValueError, DFATypeError
        If an amplitude is not a finite number > 0.

    See Also
    --------
    quantizer_df_inverse : The amplitudes at which D takes a given value.
    quantizer_df_peak : The maximum of D over M >= 1.
    dfa.analysis.nonlinearities.QuantizerNonlinearity : The quantizer for python-control.
    """
    m = _amplitudes(amplitude)
    level, _dlevel = _level_functions()
    big = m >= dfcore.ASYMPTOTIC_FROM
    ms = np.where(big, 1.0, m)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):  # M² underflows for M < 1e-154: D = inf
        out = 0.5 * level(0.0, ms) + _level_sum(ms, level)
    if np.any(big):  # the ⌊M⌋-term sum is slow and overflows int64 far out: the asymptotic expansion (_dfcore)
        out = np.where(big, dfcore.df_array(np.where(big, m, 1e3).ravel()).reshape(m.shape), out)
    tiny = m < 1e-150
    if np.any(tiny):  # M² underflows: below one tick only the k = 0 term is left, homogeneous of degree −1 in M
        with np.errstate(over="ignore"):
            out = np.where(tiny, 0.5 * level(0.0, 1.0) / np.where(tiny, m, 1.0), out)
    _check_finite_df("amplitude", m, out)
    return float(out) if out.ndim == 0 else out


def _check_finite_df(name: str, m: np.ndarray, out: ArrayLike) -> None:
    """Refuse amplitudes so small that the describing function (∝ 1/M) overflows a float."""
    bad = ~np.isfinite(np.asarray(out))
    if np.any(bad):
        v = float(np.broadcast_to(m, np.shape(bad))[bad].ravel()[0])
        raise DFAValueError(
            f"{name} = {v!r} is invalid: the describing function (∝ 1/{name}) overflows a float; "
            "give an amplitude above 1e-307"
        )


def quantizer_df_derivative(amplitude: ArrayLike) -> float | np.ndarray:
    """dD/dM (1/tick) of eq. 41, from the sympy derivative of each level's term.

    Infinite from the right at integer M (a new level's √ starts there); this
    function returns the left derivative at integers.
    """
    m = _amplitudes(amplitude)
    _level, dlevel = _level_functions()
    big = m >= dfcore.ASYMPTOTIC_FROM
    at_int = np.floor(m) == m
    mm = np.where(big, 0.5, np.where(at_int, m * (1 - 1e-15), m))  # left derivative at integers
    with np.errstate(invalid="ignore", divide="ignore"):
        out = 0.5 * dlevel(0.0, mm) + _level_sum(mm, dlevel)
    if np.any(big):
        out = np.where(big, dfcore.df_array(np.where(big, m, 1e3).ravel(), True).reshape(m.shape), out)
    return float(out) if out.ndim == 0 else out


def _interval_peak(n: int) -> tuple[float, float]:
    """(M, D) of the local maximum of D on [n, n + 1] (D is unimodal there; compiled, see :mod:`dfa.core.dfcore`)."""
    mp, dp = dfcore.interval_peak(int(n))
    return float(mp), float(dp)


def quantizer_df_inverse(gain: float, max_amplitude: float = 1.0e4) -> tuple[np.ndarray, bool]:
    """Every amplitude M with D(M) = ``gain`` (eq. 41), sorted.

    D is 2/(πM) on (0, 1] and unimodal on each [n, n + 1] (minimum at the
    integers, maximum near n + 0.30), so each interval holds at most two roots,
    found by bracketing. Beyond ⌊M⌋ = (DF_ENVELOPE/abs(gain − 1))^{2/3} no root
    exists; the search stops there, at ``max_amplitude`` or after
    ``INVERSE_MAX_INTERVALS`` intervals (then ``complete`` is False). A compiled
    Brent solve that does not converge gives ``complete=False`` and a
    RuntimeWarning, never a bracket end posing as a root.

    Parameters
    ----------
    gain : float
        The wanted value of D, > 0.
    max_amplitude : float, optional
        Largest amplitude searched, in ticks (default 1e4).

    Returns
    -------
    roots : numpy.ndarray
        The amplitudes, increasing.
    complete : bool
        False when roots may exist beyond ``max_amplitude`` or the interval
        budget (only when ``gain`` is within DF_ENVELOPE·max_amplitude^{-3/2} of 1),
        or when an interval could not be solved.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``gain`` or ``max_amplitude`` is not a finite number > 0.

    Warns
    -----
    RuntimeWarning
        When an interval could not be solved (``complete`` is then False).

    See Also
    --------
    quantizer_df : D(M) itself.

    Examples
    --------
    >>> roots, complete = quantizer_df_inverse(1.1)
    >>> np.round(roots, 4).tolist(), complete
    ([0.5787, 1.1494, 1.3698], True)
    """
    g = check_positive("gain", gain, "D(M) is positive for every amplitude")
    mmax = check_positive("max_amplitude", max_amplitude)
    out, complete, failures = df_inverse_counted(g, mmax)
    if failures:
        import warnings

        warnings.warn(
            f"quantizer_df_inverse({g!r}): {failures} interval(s) could not be solved; roots may be missing",
            RuntimeWarning,
            stacklevel=2,
        )
    return out, bool(complete and not failures)


#: Most intervals [n, n + 1] the inverse scans (its result is incomplete beyond).
INVERSE_MAX_INTERVALS = 2_000_000


def df_inverse_counted(g: float, mmax: float) -> tuple[np.ndarray, bool, int]:
    """(roots, complete, failures) of D(M) = g up to ``mmax`` (validated inputs)."""
    roots = [2 / (math.pi * g)] if g >= 2 / math.pi and 2 / (math.pi * g) <= mmax else []
    n_last = (
        int(min(float(INVERSE_MAX_INTERVALS) + 1, math.floor((DF_ENVELOPE / abs(g - 1.0)) ** (2.0 / 3.0)) + 1))
        if g != 1.0
        else None
    )
    if n_last is None or n_last > INVERSE_MAX_INTERVALS:
        n_last = int(min(mmax, INVERSE_MAX_INTERVALS)) + 1
        complete = False
    else:
        complete = n_last <= mmax
    n_stop = int(min(n_last, math.floor(mmax)))
    # compiled scan of the intervals [n, n + 1]: peak and both branches by Brent's method in t, M = n + t²
    found, failures = dfcore.df_inverse(g, n_stop, mmax, DF_ENVELOPE)
    out = np.concatenate([roots, found])
    if out.size > 1:  # a root at a shared bracket end can be found twice; keep the values as found
        out = out[np.concatenate([[True], np.diff(out) > 1e-12 * out[1:]])]
    return out, bool(complete), int(failures)


def quantizer_df_peak() -> tuple[float, float]:
    """(M, D) of the maximum of eq. 41 over M >= 1: D ≈ 1.1206 at M ≈ 1.242.

    Returns
    -------
    amplitude : float
        The amplitude M of the peak, in ticks.
    value : float
        D at that amplitude (dimensionless).

    See Also
    --------
    quantizer_df : D(M) itself.

    Examples
    --------
    >>> m, d = quantizer_df_peak()
    >>> round(m, 3), round(d, 4)
    (1.242, 1.1206)
    """
    return _interval_peak(1)


def coulomb_df(amplitude: ArrayLike, sigma: float) -> float | np.ndarray:
    """Describing function 4σ/(πA) of Coulomb friction σ·sgn(v) at velocity amplitude A.

    Parameters
    ----------
    amplitude : float or array_like
        Velocity amplitude A > 0 (ticks per sample).
    sigma : float
        Dimensionless Coulomb friction σ >= 0.

    Returns
    -------
    float or numpy.ndarray
        The describing function (dimensionless), a float for a scalar amplitude.

    Raises
    ------
    DFAValueError, DFATypeError
        If an amplitude is not a finite number > 0 or σ is out of range.

    See Also
    --------
    coulomb_equivalent_damping : The same friction as a viscous damping.
    dfa.analysis.nonlinearities.CoulombNonlinearity : The friction for python-control.
    """
    a = _amplitudes(amplitude, "amplitude")
    s = check_sigma(sigma)
    with np.errstate(over="ignore"):
        out = np.asarray(_coulomb_function()(a, s), dtype=float) * np.ones_like(a)
    _check_finite_df("amplitude", a, out)
    return float(out) if out.ndim == 0 else out


def coulomb_equivalent_damping(sigma: float, amplitude: ArrayLike, omega: ArrayLike) -> float | np.ndarray:
    """Equivalent viscous damping 4σ/(πMω) of Coulomb friction on ξ = M sin ωτ (eq. 40).

    Parameters
    ----------
    sigma : float
        Dimensionless Coulomb friction σ >= 0.
    amplitude : float or array_like
        Position amplitude M > 0 in ticks.
    omega : float or array_like
        Frequency ω > 0 in rad per sample.

    Returns
    -------
    float or numpy.ndarray
        The equivalent dimensionless damping, broadcast over ``amplitude`` and ``omega``.

    Raises
    ------
    DFAValueError, DFATypeError
        If an amplitude or frequency is not a finite number > 0 or σ is out of range.

    See Also
    --------
    coulomb_df : The describing function at velocity amplitude Mω.
    """
    m = _amplitudes(amplitude)
    w = _amplitudes(omega, "omega")
    try:
        speed = m * w
    except ValueError:
        raise DFAValueError(
            f"amplitude of shape {m.shape} is invalid with omega of shape {w.shape}: they must broadcast together"
        ) from None
    if np.any(speed == 0.0):
        raise DFAValueError(
            f"amplitude = {format_value(amplitude)} with omega = {format_value(omega)} is invalid: the velocity amplitude M·ω "
            "underflows to 0 (below 1e-308); give a larger amplitude or frequency"
        )
    return coulomb_df(speed, sigma)


def numeric_df(
    f: Callable[[float], float], amplitude: ArrayLike, jumps: Sequence[float] = (), tol: float = 1e-13
) -> float | np.ndarray:
    """Describing function of an odd static nonlinearity by quadrature over one period.

    Computes b1/M with b1 = (1/π)∫₀^{2π} f(M sin θ) sin θ dθ = (4/π)∫₀^{π/2} f(M sin θ) sin θ dθ
    (quarter-wave symmetry of an odd static nonlinearity) with adaptive
    Gauss-Kronrod quadrature. Inputs at which ``f`` jumps may be given in
    ``jumps`` (in units of the input): they become quadrature breakpoints
    θ = asin(j/M), which makes a piecewise-smooth ``f`` exact to rounding.

    Parameters
    ----------
    f : callable
        The nonlinearity, evaluated on scalars.
    amplitude : float or array_like
        Amplitudes M > 0.
    jumps : sequence of float, optional
        Positive inputs where ``f`` is discontinuous.
    tol : float, optional
        Absolute and relative tolerance of the quadrature.

    Returns
    -------
    float or numpy.ndarray
        The ratio b1/M at each amplitude, a float for a scalar amplitude.

    Raises
    ------
    DFAValueError, DFATypeError
        If an amplitude is not a finite number > 0, or so small that b1/M overflows a float (the rule of
        :func:`quantizer_df`).

    See Also
    --------
    quantizer_df : The closed form for the encoder quantizer.
    coulomb_df : The closed form for Coulomb friction.

    Examples
    --------
    >>> round(numeric_df(lambda x: np.floor(x) + 0.5, 2.5, jumps=[1, 2]), 10) == round(quantizer_df(2.5), 10)
    True
    """
    from scipy import integrate  # imported here: the everyday commands never integrate numerically

    if not callable(f):
        raise DFATypeError(
            f"f = {format_value(f)} is invalid: it must be a function of the input (an odd static nonlinearity)"
        )
    m = _amplitudes(amplitude)
    js = check_real_array("jumps", jumps, "give the inputs at which f jumps, e.g. [1, 2]").ravel()
    tol = check_positive("tol", tol, "give the quadrature tolerance, e.g. 1e-13")
    if tol < 1e-13:
        raise DFAValueError(f"tol = {tol!r} is invalid: it must be at least 1e-13 (the quadrature's finest); use 1e-13")

    def fval(x: float) -> float:  # x: the input, a numpy float as before
        try:
            y = float(f(x))
        except (TypeError, ValueError, OverflowError):
            raise DFATypeError(f"f({x!r}) is not a real number: f must return one real number per input") from None
        if not math.isfinite(y):
            raise DFAValueError(f"f({x!r}) = {y!r} is invalid: f must return finite numbers")
        return y

    out = np.empty(m.shape)
    for idx, mv in np.ndenumerate(m):
        pts = sorted({math.asin(j / mv) for j in js if 0 < j < mv})
        edges = [0.0, *pts, math.pi / 2]
        total = 0.0
        for a, b in zip(edges[:-1], edges[1:], strict=False):
            if b > a:
                # evaluate strictly inside each piece so a jump at an edge is not sampled
                val, _err = integrate.quad(
                    lambda t, mv=mv: fval(mv * math.sin(t)) * math.sin(t), a, b, epsabs=tol, epsrel=tol, limit=200
                )
                total += val
        with np.errstate(over="ignore"):  # refused below, with quantizer_df's message
            out[idx] = 4.0 / math.pi * total / mv
    _check_finite_df("amplitude", m, out)  # quantizer_df's rule: a ratio b1/M that overflows is refused
    return float(out) if out.ndim == 0 else out
