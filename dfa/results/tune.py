"""Tuning results: the walls :func:`dfa.tune` screened and simulated, and the best of them (issue 44).

A :class:`TunedWall` is one candidate wall (its elements and the sample period it runs at), what the quick screen
gave (:attr:`TunedWall.screen`, a K in N/m to rank by, never recommended) and, for the walls simulated, the
recommendation by the rule of :mod:`dfa.analysis.limits.recommend` (a proof, or the simulated limit over the margin)
with the wall's fidelity at that K: its force error against the ideal spring over the first contact and how often
its passivity controller acts. A :class:`TuneResult` holds them all: the plain wall first, then the simulated walls
by recommended K, then the walls only screened.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..checks import check_type
from ..errors import DFATypeError, DFAValueError
from ..model.device import Device
from ..model.wall import Wall
from .base import Result, figure_function
from .require import Recommendation, check_margin
from .status import TunedStatus, TuneStatus

__all__ = ["TunedWall", "TuneResult", "within_cap"]


def _fraction(name: str, x: float | None, fix: str) -> None:
    """Refuse a fraction that is not None or a number in [0, ∞) (a force error may exceed 1; a share may not)."""
    if x is not None and not (isinstance(x, float) and x >= 0.0 and math.isfinite(x)):
        raise DFAValueError(f"{name} = {x!r} is invalid: it must be None or a finite float >= 0; {fix}")


def within_cap(error: float | None, cap: float | None) -> bool:
    """Whether a force error is known and at most ``cap`` (always, without a cap): the one rule of the tuning's cap.

    Examples
    --------
    >>> within_cap(0.4, 0.5), within_cap(None, 0.5), within_cap(None, None)
    (True, False, True)
    """
    return cap is None or (error is not None and error <= cap)


@dataclass(frozen=True)
class TunedWall(Result):
    """One candidate wall of a tuning: its elements, its sample period, its screen and (simulated) its recommendation.

    Attributes
    ----------
    device : Device
        The device at the candidate's sample period (``period``, s).
    wall : Wall
        The candidate's elements at its recommended K (simulated), or at the screen's K (screened; 1 N/m, a
        placeholder, when the screen gives none).
    screen : float
        The quick screen's stiffness (N/m; rotary N·m/rad): the larger of the criterion's K and the exact linear
        bound over the margin (0 where neither gives one). It ranks the candidates for simulation; it is never
        recommended.
    screen_force_error : float or None
        The force error (as ``force_error``) at the screen's K: the walls within the tuning's cap are simulated
        first. None where the screen gives no K or the impact diverged.
    recommendation : Recommendation or None
        For a simulated wall, its recommended stiffness and rule (:func:`dfa.analysis.limits.recommend.
        recommend_stiffness`); None for a wall only screened.
    force_error : float or None
        At the recommended K: the RMS difference between the force the wall applies and the ideal spring's (−K x,
        continuous, no delay) at the sample instants of the first contact of an impact at the tuning's speed, as a
        fraction of the ideal spring's peak force V·sqrt(m K). None when not simulated or no K is recommended.
    controller_share : float or None
        At the recommended K: the fraction of the samples of that impact (first contact and what follows, up to
        rest) at which the passivity controller added a force. None without a controller or a recommended K.
    status : TunedStatus
        ``simulated`` or ``screened``.
    """

    device: Device = field(metadata={"json": lambda d: {"name": d.name, "period": d.period}})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    screen: float
    screen_force_error: float | None = None
    recommendation: Recommendation | None = None
    force_error: float | None = None
    controller_share: float | None = None
    status: TunedStatus = TunedStatus.SCREENED

    units_of: ClassVar[dict[str, str]] = {"screen": "stiffness"}

    def __post_init__(self) -> None:
        fix = "TunedWall is built by dfa.tune; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        object.__setattr__(self, "status", TunedStatus.coerce(self.status))
        if not (isinstance(self.screen, float) and self.screen >= 0.0):
            raise DFAValueError(f"screen = {self.screen!r} is invalid: it must be a float >= 0; {fix}")
        if (self.recommendation is None) != (self.status is TunedStatus.SCREENED):
            raise DFAValueError(
                f"recommendation = {self.recommendation!r} is invalid for status {self.status.value!r}: a simulated "
                f"wall has one, a screened wall none; {fix}"
            )
        _fraction("force_error", self.force_error, fix)
        _fraction("screen_force_error", self.screen_force_error, fix)
        _fraction("controller_share", self.controller_share, fix)
        if self.controller_share is not None and self.controller_share > 1.0:
            raise DFAValueError(f"controller_share = {self.controller_share!r} is invalid: it is at most 1; {fix}")

    @property
    def k_recommended(self) -> float | None:
        """The recommended stiffness (N/m; rotary N·m/rad), None when screened only or none is recommended."""
        return None if self.recommendation is None else self.recommendation.k_recommended

    def null_reasons(self) -> dict[str, str]:
        """Why a field may be null (JSON).

        Returns
        -------
        dict of str to str
            Reasons by field name.
        """
        return {
            "recommendation": "screened only: not among the walls simulated",
            "force_error": "screened only, or no K is recommended",
            "screen_force_error": "the screen gives no K, or the impact at it diverged",
            "controller_share": "no passivity controller, screened only, or no K is recommended",
        }


@dataclass(frozen=True)
class TuneResult(Result):
    """The walls a tuning screened and simulated for one device and impact speed, best first after the plain wall.

    Attributes
    ----------
    device : Device
        The device as given (its own sample period).
    velocity : float
        Impact speed V, m/s (rotary rad/s).
    margin : float
        Gain margin of the simulated rule (>= 1).
    max_force_error : float or None
        The largest force error (a fraction of the ideal peak force) of a wall that can be the best; None: any.
    require_rest : bool
        True: the best wall must come to rest at its recommended K (not above its simulated rest limit) where any
        wall within the cap does; False: a wall that may buzz can be the best.
    walls : tuple of TunedWall
        The plain wall first (the given wall without a virtual damper, velocity filter or passivity controller, at
        the device's period), then the other simulated walls by recommended K (largest first), then the walls only
        screened, by screen.
    status : TuneStatus
        ``tuned`` (a wall beats the plain one), ``plain_best`` or ``none`` (no wall has a recommended K).
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    velocity: float
    margin: float
    max_force_error: float | None
    require_rest: bool
    walls: tuple[TunedWall, ...]
    status: TuneStatus = TuneStatus.NONE

    units_of: ClassVar[dict[str, str]] = {"velocity": "velocity"}
    json_properties: ClassVar[tuple[str, ...]] = ("best_index",)

    def __post_init__(self) -> None:
        fix = "TuneResult is built by dfa.tune; call that instead"
        check_type("device", self.device, Device, fix)
        if not isinstance(self.walls, (tuple, list)):
            raise DFATypeError(
                f"walls = {self.walls!r} has type {type(self.walls).__name__}: it must be a tuple; {fix}"
            )
        check_margin(self.margin)
        _fraction("max_force_error", self.max_force_error, fix)
        if not isinstance(self.require_rest, bool):
            raise DFATypeError(f"require_rest = {self.require_rest!r} is invalid: it must be a bool; {fix}")
        object.__setattr__(self, "walls", tuple(self.walls))
        if not self.walls or self.walls[0].status is not TunedStatus.SIMULATED:
            raise DFAValueError(f"walls = {self.walls!r} is invalid: the plain wall, simulated, comes first; {fix}")
        for w in self.walls:
            check_type("walls[i]", w, TunedWall, fix)
        object.__setattr__(self, "status", TuneStatus.coerce(self.status))

    @property
    def simulated(self) -> tuple[TunedWall, ...]:
        """The walls simulated, plain first, then by recommended K (largest first)."""
        return tuple(w for w in self.walls if w.status is TunedStatus.SIMULATED)

    @property
    def best_index(self) -> int | None:
        """Index in :attr:`walls` of the best wall: the stiffest within the cap that rests (module docstring).

        Returns
        -------
        int or None
            The wall with the largest recommended K whose force error is within :attr:`max_force_error` and, with
            :attr:`require_rest`, that comes to rest at that K, where any does (else the stiffest within the cap; the
            plain one on a tie); None when no wall within the cap has a recommended K.
        """
        candidates = [i for i, w in enumerate(self.walls) if w.k_recommended is not None and self.faithful(w)]
        if self.require_rest and any(self.rests(self.walls[i]) for i in candidates):
            candidates = [i for i in candidates if self.rests(self.walls[i])]
        best, k = None, -math.inf
        for i in candidates:
            kr = self.walls[i].k_recommended
            if kr is not None and kr > k:
                best, k = i, kr
        return best

    @staticmethod
    def rests(wall: TunedWall) -> bool:
        """Whether a simulated wall comes to rest at its recommended K (not above its simulated rest limit).

        Parameters
        ----------
        wall : TunedWall
            One of :attr:`walls`.

        Returns
        -------
        bool
            False for a wall only screened or without a recommended K.
        """
        rec = wall.recommendation
        return rec is not None and rec.k_recommended is not None and not rec.above_rest

    def faithful(self, wall: TunedWall) -> bool:
        """Whether a wall's force error is within :attr:`max_force_error` (always, without a cap).

        Parameters
        ----------
        wall : TunedWall
            One of :attr:`walls`.

        Returns
        -------
        bool
            True when its force error is known and at most the cap, or there is no cap.
        """
        return within_cap(wall.force_error, self.max_force_error)

    @property
    def best(self) -> TunedWall | None:
        """The wall with the largest recommended K (None when no wall has one)."""
        i = self.best_index
        return None if i is None else self.walls[i]

    def null_reasons(self) -> dict[str, str]:
        """Why ``best_index`` and ``max_force_error`` may be null (JSON).

        Returns
        -------
        dict of str to str
            Reasons by field name.
        """
        return {
            "best_index": "no wall has a recommended K at this speed within the force error allowed",
            "max_force_error": "no cap on the force error",
        }

    def plot(self, ax: Any = None) -> Any:
        """Draw recommended K (across, log) against the force error (up, %) of every simulated wall.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on (default: a new figure).

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        return figure_function("tune_plot")(self, ax)
