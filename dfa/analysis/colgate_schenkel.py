"""Colgate–Schenkel passivity of a sampled wall with a general discrete controller H(z) (issue 15 item 2).

Colgate & Schenkel (1997), "Passivity of a class of sampled-data systems:
application to haptic interfaces", J. Robotic Systems 14(1): a mass m with
viscous friction b, driven through a zero-order hold by a discrete controller
H(z) (position to force) of period T, is passive if and only if (their
necessary and sufficient condition, for that linear model: no quantizer, no
Coulomb friction, the ZOH driving the device directly)::

    b > (T/2) · max_{0 <= ω <= π/T} Re{(1 − e^{−jωT}) H(e^{jωT})}/(1 − cos ωT).

For the controller of :mod:`dfa.model.wall`, H = K H̃, H̃(z) = z^{−d}[1 + β_B (1 − z^{−1}) F(z)]
(β_B = B/(KT), F the exact ZOH low-pass (1 − a)z^{−1}/(1 − a z^{−1}), a = e^{−2πν_c},
or 1 without filter). With θ = ωT, 1 − e^{−jθ} = 2j sin(θ/2) e^{−jθ/2} and
1 − cos θ = 2 sin²(θ/2) cancel the removable singularity at θ = 0::

    b_min = K T β_min,   β_min = ½ max_{0 <= θ <= π} f(θ),
    f(θ) = D_d(θ) − 2β_B Re{e^{−j(d+1)θ} F(e^{jθ})},   D_d(θ) = sin((d + ½)θ)/sin(θ/2) = 1 + 2 Σ_{k=1}^{d} cos kθ

(D_d(0) = 2d + 1). Closed forms (``tests/test_passivity.py``): the spring, d = 0:
β_min = ½ (b > KT/2, eq. 8 of the paper); spring and damper, d = 0: f = 1 − 2β_B cos θ,
β_min = ½ + β_B (b > KT/2 + B); the spring with delay d: the Dirichlet kernel
peaks at θ = 0, β_min = d + ½ (b > KT(d + ½), the delay line of eq. 6 in :mod:`dfa.analysis.criterion`).

The maximum is certified. e^{−j(d+1)θ}F = (1 − a) Σ_{n>=1} a^{n−1} e^{−j(n+d+1)θ}, so
|f''| <= L₂ = d(d + 1)(2d + 1)/3 + 2β_B [(1 + a)/(1 − a)² + 2(d + 1)/(1 − a) + (d + 1)²]
((d + 1)² in the bracket without filter). On a grid with spacing h, f is at
most max(f_i, f_{i+1}) + L₂h²/8 between two nodes; intervals whose bound
exceeds the best value found are bisected (branch and bound) until every
bound is within 1e-12 (relative) of it, or a budget of evaluations is spent.
The result gives the best value found (attained at ``theta``, a lower bound of
the maximum) and the certified upper bound, rounding included; the condition
is met for any b above ``damping_bound`` (physical) — ``status`` says whether the two
agree to 1e-12.

The condition does not cover an amplifier lag (the ZOH no longer drives the
device directly): with α > 0 the functions refuse; the exact linear bound
(:func:`dfa.analysis.linear_wall.stable_stiffness`) and the exact simulation do.

Examples
--------
>>> round(colgate_schenkel_beta(WallParams.of(damping=0.3)).beta_min, 12)
0.8
>>> r = colgate_schenkel_damping(Wall.of(2000.0, damping=1.0), period=1e-3)
>>> round(r.damping_min, 9), round(r.frequency, 3)       # KT/2 + B at the Nyquist frequency
(2.0, 500.0)
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..checks import check_positive, check_type
from ..errors import DFAValueError
from ..model.wall import Wall, WallParams
from ..results.criterion import ColgateSchenkel as ColgateSchenkel
from ..results.criterion import ColgateSchenkelDamping as ColgateSchenkelDamping
from ..results.status import PassivityStatus

__all__ = [
    "PassivityStatus",
    "ColgateSchenkel",
    "ColgateSchenkelDamping",
    "colgate_schenkel_beta",
    "colgate_schenkel_damping",
]

_REL_TOL = 1e-12
_GRID = 4096
_BUDGET = 2_000_000  # evaluations of f
_EPS = np.finfo(float).eps


def _f(theta: np.ndarray, damping: float, delay: int, pole: float | None) -> np.ndarray:
    """f(θ) = D_d(θ) − 2β_B Re{e^{−j(d+1)θ} F(e^{jθ})} (module docstring), vectorised."""
    dirichlet, re = _terms(theta, delay, pole)
    return dirichlet - 2.0 * damping * re


def _terms(theta: np.ndarray, delay: int, pole: float | None) -> tuple[np.ndarray, np.ndarray]:
    """D_d(θ) and Re{e^{−j(d+1)θ} F(e^{jθ})}: f's terms that do not depend on β_B."""
    half = np.sin(0.5 * theta)
    with np.errstate(invalid="ignore", divide="ignore"):
        dirichlet = np.where(half == 0.0, 2.0 * delay + 1.0, np.sin((delay + 0.5) * theta) / half)
    z = np.exp(1j * theta)
    filt = 1.0 if pole is None else (1.0 - pole) / (z - pole)
    return dirichlet, np.real(z ** (-(delay + 1)) * filt)


@lru_cache(maxsize=32)
def _grid_terms(delay: int, pole: float | None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The branch and bound's first grid on [0, π] and f's terms there (:func:`_terms`), formed once per delay and
    filter: a stiffness search evaluates f at many β_B = B/(KT) of one wall (read-only arrays)."""
    x = np.linspace(0.0, math.pi, _GRID + 1)
    out = (x, *_terms(x, delay, pole))
    for a in out:
        a.flags.writeable = False
    return out


def _curvature(damping: float, delay: int, pole: float | None) -> float:
    """L₂ >= |f''| on [0, π] (module docstring)."""
    c = delay + 1.0
    if pole is None:
        g2 = c * c
    else:
        g2 = (1.0 + pole) / (1.0 - pole) ** 2 + 2.0 * c / (1.0 - pole) + c * c
    return delay * (delay + 1.0) * (2.0 * delay + 1.0) / 3.0 + 2.0 * damping * g2


def _maximise(damping: float, delay: int, pole: float | None) -> tuple[float, float, float, int]:
    """(best f, θ of the best, certified upper bound of max f, evaluations): branch and bound on [0, π]."""
    l2 = _curvature(damping, delay, pole)
    slack = 64.0 * _EPS * (2.0 * delay + 1.0 + 2.0 * damping)  # rounding of one evaluation of f, generously
    x, dirichlet, re = _grid_terms(delay, pole)
    y = dirichlet - 2.0 * damping * re  # _f on the first grid
    i = int(np.argmax(y))
    best, arg = float(y[i]), float(x[i])
    lo, hi, ylo, yhi = x[:-1], x[1:], y[:-1], y[1:]
    evals = x.size
    while True:
        bound = np.maximum(ylo, yhi) + l2 * (hi - lo) ** 2 / 8.0 + slack
        tol = _REL_TOL * max(1.0, abs(best))
        keep = bound > best + tol
        if not np.any(keep) or evals >= _BUDGET:
            ub = max(best, float(bound[keep].max())) if np.any(keep) else best + tol
            return best, arg, max(ub, best + slack), evals
        lo, hi, ylo, yhi = lo[keep], hi[keep], ylo[keep], yhi[keep]
        mid = 0.5 * (lo + hi)
        ym = _f(mid, damping, delay, pole)
        evals += mid.size
        j = int(np.argmax(ym))
        if ym[j] > best:
            best, arg = float(ym[j]), float(mid[j])
        lo, hi = np.concatenate([lo, mid]), np.concatenate([mid, hi])
        ylo, yhi = np.concatenate([ylo, ym]), np.concatenate([ym, yhi])


def _refuse_uncovered(p: WallParams) -> None:
    """Refuse a wall with an element the condition does not cover (its reason), e.g. an amplifier lag."""
    why = p.colgate_schenkel_reason()
    if why is not None:
        raise DFAValueError(
            f"wall = {p.to_dict()} (amplifier lag α = τ_a/T = {p.lag:g}) is invalid for the Colgate–Schenkel "
            f"condition: {why}; drop the amplifier bandwidth, or use the exact linear bound "
            "(dfa.analysis.linear_wall.stable_stiffness) or the simulation"
        )


def colgate_schenkel_beta(wall: WallParams) -> ColgateSchenkel:
    """Minimum dimensionless damping β = b/(KT) for passivity (Colgate & Schenkel 1997) with a wall.

    Parameters
    ----------
    wall : WallParams
        The wall's dimensionless groups: virtual damping β_B, delay d, filter cutoff ν_c; the amplifier lag
        must be 0.

    Returns
    -------
    ColgateSchenkel
        The attained β_min, its certified upper bound β_bound, the θ of the maximum and the status.

    Raises
    ------
    DFAValueError
        With an amplifier lag (the condition does not cover it).
    DFATypeError
        ``wall`` is not a :class:`dfa.WallParams`.

    See Also
    --------
    colgate_schenkel_damping : The same in physical units.
    dfa.analysis.linear_wall.stable_stiffness : Exact linear stability (also with an amplifier lag).

    Examples
    --------
    >>> round(colgate_schenkel_beta(WallParams.of(delay=2)).beta_min, 12)     # d + ½
    2.5
    """
    p = check_type("wall", wall, WallParams, "give a dfa.WallParams (wall.params(period) of a dfa.Wall)")
    _refuse_uncovered(p)
    pole = None if p.cutoff is None else p.filter_pole
    best, arg, ub, _ = _maximise(p.damping, p.delay, pole)
    tol = _REL_TOL * max(1.0, abs(best))
    status = (
        PassivityStatus.CERTIFIED if ub - best <= tol + 1e3 * _EPS * max(1.0, abs(best)) else PassivityStatus.BOUNDED
    )
    return ColgateSchenkel(0.5 * best, 0.5 * ub, arg, p, status)


def colgate_schenkel_damping(wall: Wall, period: float) -> ColgateSchenkelDamping:
    """Minimum viscous friction b of the device for ``wall`` to be passive (Colgate & Schenkel 1997).

    Parameters
    ----------
    wall : Wall
        Stiffness K, damping B, delay d, filter cutoff f_c; no amplifier bandwidth (the condition does not cover it).
    period : float
        Sampling period T > 0, s.

    Returns
    -------
    ColgateSchenkelDamping
        The minimum b = K T β_min (N·s/m), its certified bound, the ω of the maximum (rad/s) and the status.

    Raises
    ------
    DFAValueError
        With an amplifier bandwidth (the condition does not cover the lag), a bad period, or a filter
        cutoff above the Nyquist frequency.
    DFATypeError
        ``wall`` is not a :class:`dfa.Wall`.

    See Also
    --------
    colgate_schenkel_beta : The dimensionless condition.
    dfa.analysis.linear_wall.stable_stiffness : Exact linear stability, which the condition is stricter than.

    Examples
    --------
    >>> r = colgate_schenkel_damping(Wall.of(1000.0, delay=1), 1e-3)
    >>> round(r.damping_min, 9), r.omega                 # K T (d + ½) at ω → 0
    (1.5, 0.0)
    """
    c = check_type("wall", wall, Wall, "give a dfa.Wall")
    t = check_positive("period", period, "give the sampling period T in s (1 kHz: 0.001)")
    _refuse_uncovered(c.params(t))
    dim = colgate_schenkel_beta(c.params(t))
    kt = c.stiffness * t
    return ColgateSchenkelDamping(kt * dim.beta_min, kt * dim.beta_bound, dim.theta / t, c, t, dim)
