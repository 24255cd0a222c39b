"""The search behind a simulated or predicted stiffness limit: a grid, a bisection, a sweep and a confirmation.

Every searched limit of :mod:`dfa.analysis.limits.kmax` (``k_df``, ``k_sim``, ``k_sim_rest``), for the spring
and every wall alike, is found here, and its evidence is returned as typed records (no sentences: the
rendering layer words them, :mod:`dfa.render.limits`):

:func:`grid_search`
    the largest K before the first non-safe judgement on an ascending geometric grid, then bisection
    between the last safe and the first failing grid point to a relative :data:`K_RTOL`. Safety need not
    be monotone in K: grid points found safe again above the first failure are kept (``safe_above``).
:func:`confirm`
    the largest *swept and confirmed* K at or below a simulated limit: from both starts, no run fails and
    none is undecided at the search speeds over a sweep in K (:class:`Sweep`: relative steps of
    :data:`SWEEP_STEP`, coarser past the wall's sweep budget) from K_criterion (else the grid's lowest point)
    up to K, over a fine zone just below K (:data:`FINE_POINTS` steps of :data:`FINE_STEP`), and at
    :data:`DENSE_FACTOR` times as many speeds over a band below K (:func:`band`). A failure drops the
    candidate just below it and every check runs again; each failure met is kept (:class:`Failure`).

Examples
--------
>>> s = grid_search(lambda k: "safe" if k < 3.0 else "unsafe", geometric_grid(1.0, 10.0, 5))
>>> 3.0 * (1 - K_RTOL) <= s.value < 3.0 <= s.first_failure, s.status.value
(True, 'found')
"""

from __future__ import annotations

import dataclasses
import math
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ...errors import DFAValueError
from ...grids import geometric_grid
from ...progress import advance
from ...results.limits import FINE_POINTS as FINE_POINTS
from ...results.limits import FINE_STEP as FINE_STEP
from ...results.limits import SWEEP_STEP as SWEEP_STEP
from ...results.limits import (
    Confirmation as Confirmation,
)
from ...results.limits import (
    Failure as Failure,
)
from ...results.limits import (
    KLimit as KLimit,
)
from ...results.limits import (
    SweepRecord as SweepRecord,
)
from ...results.status import LimitStatus
from .runs import FAILING, SAFE, UNDECIDED, Evidence

if TYPE_CHECKING:
    from ...model.device import Device

__all__ = [
    "K_RTOL",
    "Failure",
    "SweepRecord",
    "Confirmation",
    "KLimit",
    "Sweep",
    "grid_search",
    "GridBracket",
    "geometric_mean",
    "df_limit",
    "simulated_limit",
    "confirm",
    "search_grid",
    "search_steps",
    "check_stiffness_range",
    "MU_RANGE",
    "band",
    "SWEEP_STEP",
    "FINE_STEP",
    "FINE_POINTS",
    "DENSE_FACTOR",
    "DENSE_BAND",
    "DENSE_RUNGS",
    "DENSE_FINE",
    "MAX_LOWERINGS",
]

#: Relative width at which the bisection of a searched limit stops.
K_RTOL = 2e-3
#: The confirmation of a simulated limit K uses this many times the searched speeds ...
DENSE_FACTOR = 4
#: ... at the stiffnesses of a band below K: DENSE_RUNGS geometric rungs spanning a relative width DENSE_BAND ...
DENSE_RUNGS = 5
DENSE_BAND = 0.03
#: ... and at these fractions below K (where a search's bisection ended).
DENSE_FINE = (0.001, 0.003)
#: ... lowering the candidate at most this many times (each time just below the lowest failure found).
MAX_LOWERINGS = 200


def geometric_mean(lo: float, hi: float) -> float:
    """√(lo·hi) of two stiffnesses > 0, also where lo·hi overflows or underflows a float (then √lo·√hi).

    ``math.sqrt(lo * hi)`` gave inf between 1e155 and 1e305 N/m (``dfa stiffness --coulomb 1e300``: "undecided
    runs at inf N/m"); the product's own value is kept wherever it is a normal float, so results elsewhere are
    bit for bit those of before.

    Examples
    --------
    >>> geometric_mean(4.0, 9.0), geometric_mean(4e300, 9e300)
    (6.0, 6e+300)
    """
    p = lo * hi
    return math.sqrt(p) if sys.float_info.min <= p < math.inf else math.sqrt(lo) * math.sqrt(hi)


def grid_search(
    judge: Callable[[float], str], grid: np.ndarray, why: str | Callable[[float], str] = "short_runs"
) -> KLimit:
    """The largest K before the first non-safe judgement on an ascending ``grid``, refined by bisection.

    Parameters
    ----------
    judge : callable
        K (N/m) -> ``"safe"``, ``"unsafe"`` or ``"undecided"`` (counted as not safe).
    grid : numpy.ndarray
        Ascending stiffnesses to judge first.
    why : str or callable, optional
        What an undecided judgement means (a code of :class:`~dfa.results.status.UndecidedWhy`; default ``"short_runs"``), or a
        callable giving it at the stiffness where one stopped the search.

    Returns
    -------
    KLimit
        ``found`` with the search's evidence, or ``above_range``/``below_range``.
    """
    verdicts = [_judged(judge, float(k)) for k in grid]
    undecided = {float(k) for k, v in zip(grid, verdicts, strict=True) if v == UNDECIDED}
    bad = [i for i, v in enumerate(verdicts) if v != SAFE]
    if not bad:
        return KLimit(None, LimitStatus.ABOVE_RANGE, range_end=float(grid[-1]), evaluations=len(grid))
    i = bad[0]
    safe_above = tuple(float(k) for k, v in zip(grid[i + 1 :], verdicts[i + 1 :], strict=True) if v == SAFE)
    if i == 0:  # an undecided first judgement says why (limited_by: the lowest K)
        k0 = float(grid[0])
        why0 = (why(k0) if callable(why) else why) if verdicts[0] == UNDECIDED else None
        return KLimit(
            None, LimitStatus.BELOW_RANGE, range_end=k0, range_verdict=verdicts[0],
            limited_by=None if why0 is None else k0, limited_why=why0,
            non_monotone=bool(safe_above), safe_above=safe_above, undecided=tuple(sorted(undecided)),
            first_failure=k0, evaluations=len(grid),
        )  # fmt: skip
    lo, hi, n = float(grid[i - 1]), float(grid[i]), len(grid)
    hi_verdict = verdicts[i]
    while hi - lo > K_RTOL * hi:
        mid = geometric_mean(lo, hi)
        v = _judged(judge, mid)
        n += 1
        if v == UNDECIDED:
            undecided.add(mid)
        if v == SAFE:
            lo = mid
        else:
            hi, hi_verdict = mid, v
    limited = hi_verdict == UNDECIDED
    return KLimit(
        lo, limited_by=hi if limited else None, limited_why=(why(hi) if callable(why) else why) if limited else None,
        non_monotone=bool(safe_above), safe_above=safe_above,
        undecided=tuple(sorted(undecided)), first_failure=hi, evaluations=n,
    )  # fmt: skip


class GridBracket:
    """:func:`grid_search`'s value, judged lazily: an interval that holds it, narrowed one judgement at a time.

    The same judgements in the same order as :func:`grid_search` (the grid ascending up to the first non-safe
    point, then the bisection), stopped whenever the caller knows enough: after the grid points
    ``grid[0..j-1]`` were judged safe the value is >= ``grid[j-1]`` (or there is none, ``above_range``); after
    the first non-safe grid point ``grid[i]`` it lies in [lo, hi) of the bisection. Once :attr:`exact`,
    :attr:`value` is :func:`grid_search`'s ``value`` bit for bit (None for ``above_range`` or ``below_range``).
    It does not judge the grid points above the first failure (``safe_above``: :func:`grid_search` reports them).

    Examples
    --------
    >>> b = GridBracket(lambda k: "safe" if k < 3.0 else "unsafe", geometric_grid(1.0, 10.0, 5))
    >>> b.bounds
    (0.0, inf)
    >>> while not b.exact:
    ...     b.refine()
    >>> b.value == grid_search(lambda k: "safe" if k < 3.0 else "unsafe", geometric_grid(1.0, 10.0, 5)).value
    True
    """

    def __init__(self, judge: Callable[[float], str], grid: np.ndarray):
        self.judge, self.grid = judge, [float(k) for k in grid]
        self.next = 0  # the next grid point to judge (every one below it safe)
        self.lo, self.hi = 0.0, math.inf  # the value's interval (0: nothing judged safe yet; inf: none found above)
        self.exact = False
        self.value: float | None = None
        self.below = False  # below_range: the first grid point already not safe
        self.judgements = 0

    @property
    def bounds(self) -> tuple[float, float]:
        """(lo, hi) with lo <= value <= hi, N/m; no value counts as +inf above the range (nothing failed) and as 0
        below it (the smallest stiffness already fails: the most limiting, never the least)."""
        if self.exact:
            v = (0.0 if self.below else math.inf) if self.value is None else self.value
            return v, v
        return self.lo, self.hi

    def refine(self) -> None:
        """One more judgement (nothing once :attr:`exact`)."""
        if self.exact:
            return
        if self.hi == math.inf:  # the grid, ascending
            k = self.grid[self.next]
            verdict = self.judge(k)
            self.judgements += 1
            if verdict == SAFE:
                self.lo, self.next = k, self.next + 1
                if self.next == len(self.grid):  # above_range
                    self.exact = True
            elif self.next == 0:  # below_range
                self.exact = self.below = True
            else:
                self.hi = k
            self._settle()
            return
        mid = geometric_mean(self.lo, self.hi)
        self.judgements += 1
        if self.judge(mid) == SAFE:
            self.lo = mid
        else:
            self.hi = mid
        self._settle()

    def _settle(self) -> None:
        """Exact once the bisection is as narrow as :func:`grid_search` makes it."""
        if not self.exact and self.hi < math.inf and not self.hi - self.lo > K_RTOL * self.hi:
            self.exact, self.value = True, self.lo


def _judged(judge: Callable[[float], str], k: float) -> str:
    """``judge(k)``, one judgement for the progress line (:func:`dfa.progress.advance`)."""
    verdict = judge(k)
    advance(unit="judgement")
    return verdict


def search_steps(grid: np.ndarray) -> int:
    """Judgements :func:`grid_search` makes on ``grid`` when it bisects once (the progress line's estimate): the
    grid's points and the bisection of one grid step to :data:`K_RTOL`."""
    ratio = float(grid[1] / grid[0]) if len(grid) > 1 else 2.0
    return len(grid) + max(1, math.ceil(math.log2(max(ratio - 1.0, K_RTOL) / K_RTOL)))


def df_limit(ev: Evidence, grid: np.ndarray, xi_dot: float) -> KLimit:
    """The describing function's limit ``k_df`` on ``grid``: growth predicted only from speeds >= ``xi_dot``.

    Where an undecided prediction stopped the search, :attr:`KLimit.limited_why` says why (the sub-tick caveat,
    a search that stopped at its size budget, or one that failed).
    """

    def why(k: float) -> str:
        g = ev.growth_xi_dot(k)
        if g.not_searched:
            return "outside_mu"
        return "subtick" if g.subtick else ("below_reach" if g.lower_bound else "unknown_growth")

    return grid_search(lambda k: ev.predicted(k, xi_dot), grid, why)


def simulated_limit(ev: Evidence, grid: np.ndarray, limit: str) -> KLimit:
    """A simulated limit on ``grid``: no run fails ``limit`` (``"unstable"`` or ``"rest"``) at the search speeds."""
    return grid_search(lambda k: ev.judge(k, limit), grid, "short_runs")


#: The dimensionless mass μ = m/(K T²) a stiffness search or chart may reach at either end of its range: μ and 1/μ
#: at most 1e150, so that μ² (the loop's polynomials, the harmonic balance) stays a float. Haptic devices lie
#: between about 1e-2 and 1e7; beyond this range the searches overflowed (``dfa stiffness --resolution 1e300``:
#: μ = 2.5e306 at the grid's lowest K) or ran for minutes.
MU_RANGE = (1e-150, 1e150)


def check_stiffness_range(dev: Device, lo: float, hi: float, what: str, stiffness: float | None = None) -> None:
    """Refuse a stiffness range [lo, hi] (N/m) that is not finite or where μ = m/(K T²) leaves :data:`MU_RANGE`.

    Parameters
    ----------
    dev : Device
        The device (its values are named in the message: the likely slip is a unit).
    lo, hi : float
        The range's ends, N/m (rotary: N·m/rad).
    what : str
        What runs over the range, for the message (e.g. ``"the stiffness search (K_criterion/2 to 8 × the largest
        closed-form bound)"``).
    stiffness : float, optional
        A stiffness the range holds (the chart's design K), named in the message with the device's values.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> check_stiffness_range(get_device("Delta").device, 100.0, 1e6, "the search")
    """
    unit = dev.units["stiffness"]
    values = ", ".join(f"{k} = {getattr(dev, k):g}" for k in ("mass", "damping", "coulomb", "resolution", "period"))
    if stiffness is None:
        fix = f"check the units of the device's values ({values})"
    else:
        fix = f"check the units of the stiffness = {stiffness:g} {unit} and of the device's values ({values})"
    if not (0.0 < lo <= hi < math.inf):
        end = f"{hi:.3g} {unit}" if math.isfinite(hi) else f"beyond the largest float ({sys.float_info.max:.3g})"
        raise DFAValueError(f"{what} runs from K = {lo:.3g} {unit} to {end}: it must be a finite range of K > 0; {fix}")
    t2 = dev.period * dev.period
    mu_lo, mu_hi = dev.mass / (hi * t2), dev.mass / (lo * t2)  # μ falls as K grows
    low, high = MU_RANGE
    if not (low <= mu_lo and mu_hi <= high):
        k, mu = (lo, mu_hi) if mu_hi > high else (hi, mu_lo)
        raise DFAValueError(
            f"{what} runs from K = {lo:.3g} {unit} to {hi:.3g} {unit}, where μ = m/(K T²) reaches {mu:.3g} at K = {k:.3g}: "
            f"it must stay within {low:g} … {high:g} (μ² must be a float; haptic devices lie between about 1e-2 "
            f"and 1e7); {fix}"
        )


def search_grid(k_ref: float, top: float, grid: int) -> np.ndarray:
    """Ascending stiffness grid from k_ref/2 to ``top``, holding k_ref itself (k_ref <= 0: from top·10⁻⁴)."""
    lo = 0.5 * k_ref if k_ref > 0 else top * 1e-4
    pts = geometric_grid(lo, top, grid)
    if k_ref > 0:
        pts = np.unique(np.append(pts, k_ref))
    return pts


def band(k: float) -> list[float]:
    """The confirmation band below K, descending: K, K (1 - f) for f in DENSE_FINE, then the rungs
    K (1 - DENSE_BAND)^(i / (DENSE_RUNGS - 1)), i = 1 … DENSE_RUNGS - 1."""
    rungs = [k * (1.0 - DENSE_BAND) ** (i / (DENSE_RUNGS - 1)) for i in range(1, DENSE_RUNGS)]
    return [k] + [k * (1.0 - f) for f in DENSE_FINE] + rungs


def _fine(k: float) -> list[float]:
    """The fine zone just below K, descending: K (1 - FINE_STEP)^j, j = 0 … FINE_POINTS - 1."""
    return [k * (1.0 - FINE_STEP) ** j for j in range(FINE_POINTS)]


class Sweep(NamedTuple):
    """A sweep in K: ascending stiffnesses ``start`` (1 + ``step``)^j, j = 0, 1, …, at the search speeds.

    ``start`` is K_criterion (``from_criterion``) or, without a criterion K > 0, the search grid's lowest point.
    """

    start: float
    step: float
    from_criterion: bool
    max_points: int

    @classmethod
    def up_to(cls, k_lo: float, from_criterion: bool, k_hi: float, max_points: int) -> Sweep:
        """The sweep from ``k_lo`` up to ``k_hi``: :data:`SWEEP_STEP`, coarser when that takes over ``max_points``."""
        need = math.log(max(k_hi, k_lo) / k_lo) / max_points
        return cls(k_lo, max(SWEEP_STEP, math.expm1(need)), from_criterion, max_points)

    def points(self, top: float) -> list[float]:
        """The sweep's stiffnesses up to ``top``, ascending (every limit swept from ``start`` shares them)."""
        n = math.floor(math.log(top / self.start) / math.log1p(self.step) + 1e-9) if top >= self.start else -1
        return [self.start * (1.0 + self.step) ** j for j in range(n + 1)]

    def record(self, k: float) -> SweepRecord:
        """What this sweep simulates below a limit K (:class:`SweepRecord`)."""
        coarse = self.step > SWEEP_STEP * (1 + 1e-9)
        return SweepRecord(self.start, self.step, self.from_criterion, len(self.points(k)), self.max_points, coarse)


def _failures(ev: Evidence, k: float, bad: str, found_by: str) -> list[Failure]:
    """Runs of ``ev`` at ``k`` that fail limit ``bad`` or are undecided (neither counts as safe)."""
    return [
        Failure(k, ev.dev.velocity(xd), start, str(o), found_by)
        for xd, start, o in ev.outcomes(k)
        if o in FAILING[bad] or o == "undecided"
    ]


def _lowest_failures(k: float, ev: Evidence, dense: Evidence, bad: str, sweep: Sweep) -> list[Failure]:
    """The failing runs of the first check at K that fails (empty: none fails): the sweep up to K and the fine zone
    at the search speeds (``ev``), the confirmation band at the dense speeds, then every run already simulated at
    or below K (``"earlier runs"``: the searches', another limit's checks); each new check is one threaded batch."""
    checks = (
        (ev, sweep.points(k), "sweep"),
        (ev, _fine(k), "sweep"),
        (dense, band(k), "confirmation"),
        (ev, [kk for kk in ev.sims if kk <= k], "earlier runs"),
        (dense, [kk for kk in dense.sims if kk <= k], "earlier runs"),
    )
    for e, ks, by in checks:
        e.prefetch(ks)  # the cache's runs are free
        fails = [f for kk in ks for f in _failures(e, kk, bad, by)]
        if fails:
            return fails
    return []


def _settle(
    k0: float, ev: Evidence, dense: Evidence, bad: str, sweep: Sweep, floor: float
) -> tuple[float | None, list[Failure], int, Sweep]:
    """The largest K at or below ``k0`` that every check of :func:`_lowest_failures` passes, lowering the candidate
    to just below (1 - FINE_STEP) the lowest failure found each time; the failures met, the lowerings, and the sweep
    (restarted from ``floor``, the search grid's lowest point, when the candidate falls below its start). None when
    the failures reach ``floor`` or :data:`MAX_LOWERINGS` is spent."""
    k = k0
    fails: list[Failure] = []
    for n in range(MAX_LOWERINGS):
        if k < sweep.start * (1.0 - 1e-12):
            if sweep.start <= floor:
                return None, fails, n, sweep
            sweep = Sweep.up_to(floor, False, k, sweep.max_points)
        f = _lowest_failures(k, ev, dense, bad, sweep)
        if not f:
            return k, fails, n, sweep
        fails += f
        k = min(r.stiffness for r in f) * (1.0 - FINE_STEP)
    return None, fails, MAX_LOWERINGS, sweep


def confirm(
    found: KLimit, ev: Evidence, dense: Evidence, bad: str, sweep: Sweep, floor: float, top: float | None = None
) -> KLimit:
    """The largest *swept and confirmed* K at or below a searched limit (and at or below ``top``; module docstring).

    Parameters
    ----------
    found : KLimit
        The searched limit.
    ev, dense : Evidence
        The runs at the search speeds, and at :data:`DENSE_FACTOR` times as many speeds.
    bad : str
        ``"unstable"`` (the limit "no divergence") or ``"rest"`` (the limit "every run at rest").
    sweep : Sweep
        The sweep in K below the limit.
    floor : float
        The search grid's lowest point, where a sweep restarts when the candidate falls below its start.
    top : float, optional
        A cap (``k_sim`` for ``k_sim_rest``).

    Returns
    -------
    KLimit
        Confirmed (``confirmation`` says what was simulated), lowered below failures (``failures``), capped,
        or ``not_confirmed``.
    """
    if found.value is None:
        return found
    k0 = found.value if top is None else min(found.value, top)
    value, fails, lowerings, sweep = _settle(k0, ev, dense, bad, sweep, floor)
    fields: dict[str, Any] = dict(searched_value=found.value, failures=tuple(fails), lowerings=lowerings)
    if value is None:  # the failures reached the grid's lowest point, or the lowerings ran out at the last one
        last = min([f.stiffness for f in fails] + [k0]) * (1.0 - FINE_STEP)
        end = floor if lowerings < MAX_LOWERINGS else last
        return dataclasses.replace(
            found, value=None, status=LimitStatus.NOT_CONFIRMED, range_end=end,
            confirmation=_claim(ev, dense, bad, sweep, k0), **fields,
        )  # fmt: skip
    capped = k0 if k0 < found.value else None
    return dataclasses.replace(
        found, value=value, capped_at=capped, confirmation=_claim(ev, dense, bad, sweep, value), **fields
    )


def _claim(ev: Evidence, dense: Evidence, bad: str, sweep: Sweep, k: float) -> Confirmation:
    """What a limit K confirmed by ``ev`` and ``dense`` over ``sweep`` claims (:class:`Confirmation`)."""
    return Confirmation(
        bad, dense.speeds, (1.0 - DENSE_BAND, 1.0), DENSE_RUNGS + len(DENSE_FINE), ev.speeds, sweep.record(k),
        ev.starts,
    )  # fmt: skip
