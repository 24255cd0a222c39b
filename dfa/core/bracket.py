"""Roots of many scalar functions at once, each in its own sign-changing bracket: the steps compiled.

ω(M) on a phase-curve piece (:func:`dfa.analysis.cycles.phase._omega_for_m`) solves V(M, ω) = 0 for ω at up to
a few thousand amplitudes M in one run, each in the bracket of two neighbouring grid frequencies, some
twenty-five runs per describing-function search of a Z-width column. scipy's elementwise ``find_root`` spent
about 2 ms of array bookkeeping per run on them against 0.7 ms in V (the Delta's Z-width, issue 43). Here
the function is evaluated by the caller, vectorised over the elements still running, and everything else of a
step is one compiled call (:func:`bracket_step`) over those elements.

Method
------
Regula falsi with the Illinois modification (when the same end of a bracket is kept two steps in a row, the
value the secant uses at that end is halved, so that the other end moves too), safeguarded twice: a step is a
bisection whenever the two steps before it did not halve the bracket, and a trial point closer than the
tolerance to an end is moved in to the tolerance (a root found to full precision then closes the bracket with
one more evaluation). Each element stops on its own, with the tolerances of ``find_root``'s defaults: the
bracket narrower than 4·tiny + 4·eps·|x|, or |f(x)| <= tiny (f = 0 included), x the end with the smaller |f|;
the root is that end. A bracket without a sign change, a non-finite value, or no convergence in
:data:`MAX_STEPS` evaluations is a failure: NaN, never an end. The bisection safeguard halves a bracket at
least every third step, so any finite bracket closes well within :data:`MAX_STEPS`.

Examples
--------
>>> x, ok = bracketed_roots(lambda x, c: x * x - c, np.array([1.0, 0.0]), np.array([2.0, 3.0]),
...                         np.array([-1.0, -4.0]), np.array([2.0, 5.0]), (np.array([2.0, 4.0]),))
>>> bool(abs(x[0] - 2.0**0.5) <= 4e-16 * 2.0**0.5), float(x[1]), ok.tolist()
(True, 2.0, [True, True])
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from .jit import interpreting, njit

__all__ = ["bracketed_roots", "bracket_step", "step_arrays", "MAX_STEPS"]

#: Most evaluations of each element's function.
MAX_STEPS = 400

_TINY = float(np.finfo(np.float64).tiny)
_EPS = float(np.finfo(np.float64).eps)
# the rows of a bracket's state: ends a < b, f there, the secant's values there (Illinois-halved), the end the
# last step replaced (+1: a, -1: b, 0: none yet), the widths before the last step and before the one before it
_A, _B, _GA, _GB, _WA, _WB, _SIDE, _W1, _W2 = range(9)


def bracketed_roots(
    f: Callable[..., Any],
    lo: npt.ArrayLike,
    hi: npt.ArrayLike,
    f_lo: npt.ArrayLike,
    f_hi: npt.ArrayLike,
    args: Sequence[npt.ArrayLike] = (),
) -> tuple[np.ndarray, np.ndarray]:
    """Root of ``f(x, *args)`` in each bracket [lo, hi] (either order), elementwise (module docstring).

    Parameters
    ----------
    f : callable
        ``f(x, *a)`` for 1-D float arrays ``x`` and ``a`` (the running elements' arguments), elementwise, real.
    lo, hi : array_like
        The brackets' ends (1-D, one length).
    f_lo, f_hi : array_like
        ``f`` at the ends: of opposite signs, or one of them zero (that end is the root).
    args : sequence of array_like, optional
        Further arguments of ``f``, one value per element.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The roots (NaN where an element failed) and whether each converged.

    See Also
    --------
    scipy.optimize.elementwise.find_root : The library's elementwise bracketing solver (the same tolerances).
    """
    lo, hi = np.asarray(lo, dtype=np.float64).ravel(), np.asarray(hi, dtype=np.float64).ravel()
    f_lo, f_hi = np.asarray(f_lo, dtype=np.float64).ravel(), np.asarray(f_hi, dtype=np.float64).ravel()
    swap = lo > hi
    state = np.empty((9, lo.size))
    state[_A], state[_B] = np.where(swap, hi, lo), np.where(swap, lo, hi)
    state[_GA], state[_GB] = np.where(swap, f_hi, f_lo), np.where(swap, f_lo, f_hi)
    state[_WA], state[_WB] = state[_GA], state[_GB]
    state[_SIDE], state[_W1], state[_W2] = 0.0, np.inf, np.inf
    extra = [np.asarray(v, dtype=np.float64).ravel() for v in args]
    x = np.full(lo.size, np.nan)
    none = np.empty(0)
    step = step_arrays if interpreting(bracket_step) else bracket_step  # dfa stiffness --quick loads no numba
    idx, t = step(state, np.arange(lo.size, dtype=np.int64), none, none, x, False)
    for _ in range(MAX_STEPS):
        if idx.size == 0:
            break
        ft = np.asarray(f(t, *(v[idx] for v in extra)), dtype=np.float64)
        idx, t = step(state, idx, t, ft, x, True)
    return x, np.isfinite(x)


@njit(cache=True)
def bracket_step(
    state: npt.NDArray[np.float64],
    idx: npt.NDArray[np.int64],
    t: npt.NDArray[np.float64],
    ft: npt.NDArray[np.float64],
    x: npt.NDArray[np.float64],
    update: bool,
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]:  # pragma: no cover - compiled
    """One step of :func:`bracketed_roots` for the elements ``idx``: with ``update``, f(t) = ``ft`` replaces
    the end of its sign (a failure where it is not finite); each element that has converged gets its root in
    ``x``; the others' next trial points. Returns (elements still running, their trial points).

    On the first call (``update`` False) a bracket whose ends are not finite or have one sign fails.
    """
    n = idx.size
    out_idx = np.empty(n, dtype=np.int64)
    out_t = np.empty(n)
    k = 0
    for p in range(n):
        j = idx[p]
        a, b, ga, gb = state[_A, j], state[_B, j], state[_GA, j], state[_GB, j]
        if update:
            fv, tv = ft[p], t[p]
            if not math.isfinite(fv):
                continue  # a failure: x[j] stays NaN
            state[_W2, j], state[_W1, j] = state[_W1, j], b - a
            if (fv < 0.0) == (ga < 0.0) and fv != 0.0:  # t replaces a
                if state[_SIDE, j] == 1.0:
                    state[_WB, j] *= 0.5
                a, ga = tv, fv
                state[_A, j], state[_GA, j], state[_WA, j], state[_SIDE, j] = tv, fv, fv, 1.0
            else:
                if state[_SIDE, j] == -1.0:
                    state[_WA, j] *= 0.5
                b, gb = tv, fv
                state[_B, j], state[_GB, j], state[_WB, j], state[_SIDE, j] = tv, fv, fv, -1.0
        elif not (math.isfinite(a) and math.isfinite(b) and math.isfinite(ga) and math.isfinite(gb)) or (
            (ga < 0.0) == (gb < 0.0) and ga != 0.0 and gb != 0.0
        ):
            continue  # no bracket: a failure
        best = a if abs(ga) <= abs(gb) else b
        if min(abs(ga), abs(gb)) <= _TINY or b - a < 4.0 * _TINY + 4.0 * _EPS * abs(best):
            x[j] = best
            continue
        out_idx[k] = j
        out_t[k] = _trial(a, b, state[_WA, j], state[_WB, j], state[_W2, j])
        k += 1
    return out_idx[:k], out_t[:k]


@njit(cache=True, inline="always")
def _trial(a: float, b: float, wa: float, wb: float, w2: float) -> float:  # pragma: no cover - compiled
    """The next point of a bracket a < b: the weighted secant, or the midpoint when the two steps before did not
    halve the bracket (width before them ``w2``); at least the tolerance inside the ends."""
    width = b - a
    mid = a + 0.5 * width
    t = mid
    if width <= 0.5 * w2 and wb != wa:
        s = a - wa * width / (wb - wa)
        if math.isfinite(s):
            t = s
    tol = 2.0 * _TINY + 2.0 * _EPS * max(abs(a), abs(b))
    t = min(max(t, a + tol), b - tol)
    return t if a < t < b else mid


def step_arrays(
    state: np.ndarray, idx: np.ndarray, t: np.ndarray, ft: np.ndarray, x: np.ndarray, update: bool
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`bracket_step` in array operations, the same arithmetic element by element (the tests compare the two
    bit for bit): the step of an interpreted run (:func:`dfa.core.jit.interpreted`), where the kernel's element loop
    in Python would cost more than numba's load.

    Parameters and returns as :func:`bracket_step`.
    """
    a, b, ga, gb, wa, wb, side, w1, w2 = state[:, idx]
    if update:
        keep = np.isfinite(ft)
        w2, w1 = w1, b - a
        left = ((ft < 0.0) == (ga < 0.0)) & (ft != 0.0)  # t replaces a
        wb = np.where(left & (side == 1.0), wb * 0.5, wb)
        wa = np.where(~left & (side == -1.0), wa * 0.5, wa)
        a, ga, wa = np.where(left, t, a), np.where(left, ft, ga), np.where(left, ft, wa)
        b, gb, wb = np.where(left, b, t), np.where(left, gb, ft), np.where(left, wb, ft)
        side = np.where(left, 1.0, -1.0)
    else:
        finite = np.isfinite(a) & np.isfinite(b) & np.isfinite(ga) & np.isfinite(gb)
        keep = finite & (((ga < 0.0) != (gb < 0.0)) | (ga == 0.0) | (gb == 0.0))
    state[:, idx] = np.stack([a, b, ga, gb, wa, wb, side, w1, w2])
    best = np.where(np.abs(ga) <= np.abs(gb), a, b)
    done = keep & ((np.minimum(np.abs(ga), np.abs(gb)) <= _TINY) | (b - a < 4.0 * _TINY + 4.0 * _EPS * np.abs(best)))
    x[idx[done]] = best[done]
    run = keep & ~done
    a, b, wa, wb, w2 = a[run], b[run], wa[run], wb[run], w2[run]
    width = b - a
    mid = a + 0.5 * width
    with np.errstate(all="ignore"):
        sec = a - wa * width / (wb - wa)
    t = np.where((width <= 0.5 * w2) & (wb != wa) & np.isfinite(sec), sec, mid)
    tol = 2.0 * _TINY + 2.0 * _EPS * np.maximum(np.abs(a), np.abs(b))
    t = np.minimum(np.maximum(t, a + tol), b - tol)
    return idx[run], np.where((a < t) & (t < b), t, mid)
