"""The paper's closed forms of the small stable (eq. 42-43) and large unstable (eq. 44-45) cycle families.

One vectorised implementation of each (:func:`small_cycle_closed_forms`,
:func:`large_cycle_closed_forms`, :func:`large_cycle_frequencies`), with the
scalar functions of :mod:`dfa.analysis.cycles` as thin wrappers. The frequency equations
are monotone on (0, π) and solved by :func:`scipy.optimize.elementwise.find_root`
(Chandrupatla's bracketing method), whose per-element status is kept: a point
where no cycle exists, or where the family degenerates, is NaN with a
:class:`ClosedFormStatus` saying why, never a bracket end posing as a root.

* Small family (D = 2/(πM), exact for M < 1)::

      σ = ½ sin(ω/2) − β cos(ω/2)/(2μω)      (eq. 43: ω, the right side increases on (0, π))
      M = 2 cos(ω/2)/(π μ ω²)                 (eq. 42)

  No root for σ >= ½. At β = σ = 0 the root is ω = 0 with M = ∞: the point is
  flagged ``DEGENERATE`` (an unbounded bracket search would return ω ≈ 1e-12).
* Large family (D ≈ 1)::

      cos(ω/2) = μω²                          (eq. 44)
      M = (4σ/π)/(sin(ω/2) − βω)              (eq. 45, where the denominator is > 0)

Examples
--------
>>> cf = small_cycle_closed_forms(5.0, [0.0, 0.1, 0.0], [0.0, 0.3, 0.6])
>>> np.round(cf.frequency, 4).tolist(), [s.name for s in cf.codes]
([nan, 1.3172, nan], ['DEGENERATE', 'OK', 'NO_CYCLE'])
>>> round(large_cycle_frequency(5.0), 5)
0.44175
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize.elementwise import find_root

from ...checks import check_beta, check_mu, check_sigma
from ...errors import DFAValueError
from ...model.device import Params
from ...model.elements import Coverage
from ...results.cycles import _REASONS as _REASONS
from ...results.cycles import ClosedFormCycles as ClosedFormCycles
from ...results.cycles import ClosedFormStatus as ClosedFormStatus

if TYPE_CHECKING:
    from ...model.wall import WallParams

__all__ = [
    "ClosedFormStatus",
    "ClosedFormCycles",
    "small_cycle_closed_forms",
    "large_cycle_closed_forms",
    "large_cycle_frequencies",
    "small_cycle_closed_form",
    "large_cycle_closed_form",
    "large_cycle_frequency",
]


def _check_spring(wall: object) -> None:
    """Refuse a wall the closed forms do not hold for: they assume the spring and the half-sample hold."""
    if wall is None:
        return
    from ...checks import check_type
    from ...model.wall import WallParams

    ctl = check_type("wall", wall, WallParams, "give dfa.WallParams.of(...) or None")
    if not (ctl.covers(Coverage.CLOSED_FORM) and ctl.delay == 0):
        raise DFAValueError(
            f"wall = {ctl.to_dict()} is invalid here: the paper's closed forms (eq. 42-45) hold for the "
            "pure spring without computational delay only; use dfa.limit_cycles(params, wall=...) "
            "(the numeric harmonic-balance solver) instead"
        )


def _grid(mu: ArrayLike, beta: ArrayLike, sigma: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Broadcast float arrays of μ > 0, β >= 0, σ >= 0; a bad element raises the scalar rule's own message."""
    out = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (mu, beta, sigma)))
    for a, lowest, check in (
        (out[0], sys.float_info.min, check_mu),
        (out[1], 0.0, check_beta),
        (out[2], 0.0, check_sigma),
    ):
        bad = ~(np.isfinite(a) & (a >= lowest))
        if bad.any():
            check(a[bad].ravel()[0])  # raises DFAValueError: one message per rule (dfa.checks)
    return out[0].copy(), out[1].copy(), out[2].copy()


def _solve(f: Callable[..., np.ndarray], lo: np.ndarray, hi: np.ndarray, args: tuple) -> tuple[np.ndarray, np.ndarray]:
    """find_root of an increasing ``f`` on [lo, hi] elementwise: (root, ok); a root at ``hi`` to rounding is kept."""
    if lo.size == 0:
        return lo.copy(), np.ones(lo.shape, dtype=bool)
    res = find_root(f, (lo, hi), args=args)
    x = np.asarray(res.x, dtype=float)
    ok = np.asarray(res.status) == 0
    at_hi = f(hi, *args) <= 0.0  # f(hi) = ½ − σ − (rounding of cos(π/2)): the root is hi to rounding
    return np.where(at_hi, hi, x), ok | at_hi


def _f43(w: np.ndarray, mu: np.ndarray, beta: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore"):  # −∞ at ω = 0, the bracket's low end when √(β/μ) underflows: its limit
        return 0.5 * np.sin(w / 2) - beta * np.cos(w / 2) / (2 * mu * w) - sigma


def _f44(w: np.ndarray, mu: np.ndarray) -> np.ndarray:
    return mu * w * w - np.cos(w / 2)


def small_cycle_closed_forms(
    mu: ArrayLike, beta: ArrayLike, sigma: ArrayLike, *, wall: WallParams | None = None
) -> ClosedFormCycles:
    """Small stable cycles of eq. 42-43 (D = 2/(πM)) over broadcast (μ, β, σ).

    Parameters
    ----------
    mu, beta, sigma : float or array_like
        Dimensionless mass μ > 0, damping β >= 0 and Coulomb friction σ >= 0 (Table 1).
    wall : WallParams, optional
        Accepted only as the pure spring without delay (the closed forms' assumption); any other
        wall is refused (DFAValueError): use :func:`dfa.limit_cycles` with it.

    Returns
    -------
    ClosedFormCycles
        M (ticks) and ω (rad per sample); NaN with ``NO_CYCLE`` where σ >= ½ and
        ``DEGENERATE`` at β = σ = 0.
    """
    _check_spring(wall)
    m, b, s = _grid(mu, beta, sigma)
    w = np.full(m.shape, np.nan)
    status = np.full(m.shape, int(ClosedFormStatus.NO_CYCLE), dtype=np.int8)
    exists = s < 0.5
    status[exists & (b == 0.0) & (s == 0.0)] = ClosedFormStatus.DEGENERATE
    undamped = exists & (b == 0.0) & (s > 0.0)
    w[undamped] = 2.0 * np.arcsin(2.0 * s[undamped])  # eq. 43 with β = 0
    status[undamped] = ClosedFormStatus.OK
    damped = exists & (b > 0.0)
    mb, bb, sb = m[damped], b[damped], s[damped]
    # f(lo) < 0: f ≈ lo/4 − β/(2μ lo) − σ and lo <= ½√(β/μ) (the right side of eq. 43 → −∞ as ω → 0)
    lo = np.minimum(1e-12, 0.5 * np.sqrt(bb / mb))
    root, ok = _solve(_f43, lo, np.full(lo.shape, math.pi), (mb, bb, sb))
    ok &= root < math.pi  # ω = π to rounding: M = 2cos(ω/2)/(πμω²) would be rounding noise, not a cycle
    w[damped] = np.where(ok, root, np.nan)
    status[damped] = np.where(ok, int(ClosedFormStatus.OK), int(ClosedFormStatus.NOT_SOLVED))
    with np.errstate(over="ignore", divide="ignore"):  # M beyond a float (σ → 0 at β = 0): inf, refused by _scalar
        amp = 2 * np.cos(w / 2) / (math.pi * m * w * w)
    return ClosedFormCycles(amp, w, status)


def large_cycle_frequencies(mu: ArrayLike) -> np.ndarray:
    """ω of the large-cycle family, cos(ω/2) = μω² (eq. 44), rad per sample, vectorised over μ > 0.

    Examples
    --------
    >>> np.round(large_cycle_frequencies([5.0, 100.0]), 6).tolist()
    [0.441748, 0.099938]
    """
    m = _grid(mu, 0.0, 0.0)[0]
    flat = m.ravel()
    # f(0) = −1 < 0 and f(π) = μπ² − cos(π/2) > 0: a bracket for every μ > 0
    root, ok = _solve(_f44, np.zeros(flat.shape), np.full(flat.shape, math.pi), (flat,))
    return np.where(ok, root, np.nan).reshape(m.shape)


def large_cycle_closed_forms(
    mu: ArrayLike, beta: ArrayLike, sigma: ArrayLike, *, wall: WallParams | None = None
) -> ClosedFormCycles:
    """Large unstable cycles of eq. 44-45 (D ≈ 1) over broadcast (μ, β, σ).

    Parameters
    ----------
    mu, beta, sigma : float or array_like
        Dimensionless mass μ > 0, damping β >= 0 and Coulomb friction σ >= 0 (Table 1).
    wall : WallParams, optional
        Accepted only as the pure spring without delay; any other wall is refused
        (DFAValueError): use :func:`dfa.limit_cycles` with it.

    Returns
    -------
    ClosedFormCycles
        M = (4σ/π)/(sin(ω/2) − βω) (ticks) and ω of eq. 44; NaN with
        ``NO_CYCLE`` where sin(ω/2) <= βω.
    """
    _check_spring(wall)
    m, b, s = _grid(mu, beta, sigma)
    w = large_cycle_frequencies(m)
    den = np.sin(w / 2) - b * w
    exists = den > 0
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):  # M beyond a float: inf (refused by _scalar)
        amp = np.where(exists, 4 * s / (math.pi * den), np.nan)
    status = np.where(
        exists,
        int(ClosedFormStatus.OK),
        np.where(np.isfinite(w), int(ClosedFormStatus.NO_CYCLE), int(ClosedFormStatus.NOT_SOLVED)),
    ).astype(np.int8)
    return ClosedFormCycles(amp, np.where(exists, w, np.nan), status)


# ------------------------------------------------------------ scalar wrappers
def large_cycle_frequency(mu: float) -> float:
    """ω of the paper's large-cycle family: cos(ω/2) = μω² (eq. 44), rad per sample.

    Examples
    --------
    >>> round(large_cycle_frequency(5.0), 5), round(large_cycle_frequency(100.0), 6)
    (0.44175, 0.099938)
    """
    return float(large_cycle_frequencies(check_mu(mu)))


def _scalar(cf: ClosedFormCycles, p: Params) -> tuple[float, float] | None:
    """(M, ω) of one point, None where the family has no cycle; a point not solved is refused, never None."""
    if int(cf.status) == ClosedFormStatus.NOT_SOLVED:
        raise DFAValueError(
            f"beta = {p.beta!r} with mu = {p.mu!r}, sigma = {p.sigma!r} is invalid here (β/μ = {p.beta / p.mu:.3g}): "
            f"{ClosedFormStatus.NOT_SOLVED.reason}; use a smaller β/μ or dfa.limit_cycles"
        )
    if int(cf.status) != ClosedFormStatus.OK:
        return None
    if not math.isfinite(float(cf.amplitude)):  # σ = 1.797e308, or σ = 1e-320 at β = 0: M beyond a float
        raise DFAValueError(
            f"mu = {p.mu!r}, beta = {p.beta!r}, sigma = {p.sigma!r} is invalid here: the cycle's amplitude M "
            f"overflows a float (more than {sys.float_info.max:.4g} ticks); give the groups of a device (Table 1)"
        )
    return float(cf.amplitude), float(cf.frequency)


def large_cycle_closed_form(
    mu: float, beta: float, sigma: float, *, wall: WallParams | None = None
) -> tuple[float, float] | None:
    """(M, ω) of the paper's large unstable cycle (eq. 44-45, D ≈ 1), or None when sin(ω/2) <= βω.

    M = (4σ/π)/(sin(ω/2) − βω) with ω from :func:`large_cycle_frequency`
    (scalar form of :func:`large_cycle_closed_forms`).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(K T²), > 0.
    beta : float
        Dimensionless viscous damping β = b/(K T), >= 0.
    sigma : float
        Dimensionless Coulomb friction σ = c/(K Δ), >= 0.
    wall : WallParams, optional
        Only the pure spring without delay (None, the default, or ``WallParams.of()``); any
        other wall is refused: the closed forms assume the paper's loop.

    Returns
    -------
    tuple of float or None
        The amplitude M in ticks and frequency ω in rad per sample, or None when the family has no cycle.

    Raises
    ------
    DFAValueError, DFATypeError
        If μ, β or σ is out of range or not a number, or a wall other than the spring is given.

    See Also
    --------
    small_cycle_closed_form : The small stable family (eq. 42-43).
    limit_cycles : Every cycle with the exact describing function.
    """
    p = Params(mu, beta, sigma)
    return _scalar(large_cycle_closed_forms(p.mu, p.beta, p.sigma, wall=wall), p)


def small_cycle_closed_form(
    mu: float, beta: float, sigma: float, *, wall: WallParams | None = None
) -> tuple[float, float] | None:
    """(M, ω) of the paper's small stable cycle (eq. 42-43, D = 2/(πM)), or None when σ >= ½ or β = σ = 0.

    ω solves σ = ½ sin(ω/2) − β cos(ω/2)/(2μω) on (0, π) (the right side
    increases from −∞ to ½), then M = 2 cos(ω/2)/(π μ ω²) (scalar form of
    :func:`small_cycle_closed_forms`).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(K T²), > 0.
    beta : float
        Dimensionless viscous damping β = b/(K T), >= 0.
    sigma : float
        Dimensionless Coulomb friction σ = c/(K Δ), >= 0.
    wall : WallParams, optional
        Only the pure spring without delay (None, the default, or ``WallParams.of()``); any
        other wall is refused: the closed forms assume the paper's loop.

    Returns
    -------
    tuple of float or None
        The amplitude M in ticks and frequency ω in rad per sample, or None when the family has no cycle.

    Raises
    ------
    DFAValueError, DFATypeError
        If μ, β or σ is out of range or not a number, or a wall other than the spring is given.

    See Also
    --------
    large_cycle_closed_form : The large unstable family (eq. 44-45).
    limit_cycles : Every cycle with the exact describing function.
    """
    p = Params(mu, beta, sigma)
    return _scalar(small_cycle_closed_forms(p.mu, p.beta, p.sigma, wall=wall), p)
