"""Stiffness-limit results: a limit with its evidence (:class:`KLimit`), K_max four ways (:class:`KMaxResult`),
the closed-form limits and curves, the passivity gain and the stiffness-speed chart (computed in :mod:`dfa.analysis.limits`)."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..checks import (
    check_int,
    check_positive,
    check_real,
    check_type,
)
from ..errors import DFATypeError, DFAValueError
from ..model.device import Device
from ..model.elements import PassivityController
from ..model.wall import Wall
from .base import Result, figure_function
from .caveats import SUBTICK_LIMIT
from .frozen import check_shape, freeze_fields, frozen_array
from .status import (
    ChartStatus,
    CurveStatus,
    GainStatus,
    KMaxStatus,
    LimitStatus,
    StiffnessStatus,
    UndecidedWhy,
    VelocityStatus,
)

if TYPE_CHECKING:
    from ..model.device import Device

#: ... and, just below K, a fine zone of FINE_POINTS stiffnesses K (1 - FINE_STEP)^j, j = 0 … FINE_POINTS - 1
#: (unsafe K can lie speckled within a few tenths of a percent below a limit, red team of issue 14) ...
FINE_STEP = 0.0005


FINE_POINTS = 21


def _ratio(a: KLimit, b: KLimit) -> float | None:
    """a/b of two found limits; None when either has no value."""
    if a.value is None or b.value is None or not b.value > 0.0:
        return None
    return a.value / b.value


#: Why the describing function's largest safe speed is unknown (null) at a stiffness.
UNKNOWN_DF = (
    "unknown: the describing function cannot tell there (the sub-tick caveat of dfa.analysis.cycles.caveats: smallest "
    f"unstable cycle below {SUBTICK_LIMIT:g} ticks; or an incomplete cycle search; or a one-sided wall, not a linear "
    "loop)"
)


#: The sweep in K below a simulated limit: relative step between its stiffnesses (target; at most the wall's
#: :meth:`~dfa.model.wall.WallParams.sweep_points` stiffnesses per sweep: a wider range takes a coarser step) ...
SWEEP_STEP = 0.005


@dataclass(frozen=True)
class Failure:
    """One simulated impact that failed a limit, or was undecided (neither counts as safe).

    Attributes
    ----------
    stiffness : float
        K, N/m (rotary: N·m/rad).
    velocity : float
        Impact speed, m/s (rotary: rad/s).
    start : str
        ``"impact"`` (from ξ0 = 0) or ``"preload"`` (from rest, spring preloaded to the same energy).
    outcome : str
        The run's outcome (:class:`dfa.results.status.SimulationOutcome` code).
    found_by : str
        ``"sweep"`` (the sweep in K or its fine zone), ``"confirmation"`` (the dense speeds over the band)
        or ``"earlier runs"`` (the searches', another limit's checks).
    """

    stiffness: float
    velocity: float
    start: str
    outcome: str
    found_by: str

    def to_dict(self) -> dict[str, Any]:
        """The failure as JSON-able data (its fields)."""
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class SweepRecord:
    """What a sweep in K below a limit simulated, at the search speeds and both starts.

    Attributes
    ----------
    start : float
        Its lowest stiffness, N/m: K_criterion (``from_criterion``), or the search grid's lowest point.
    step : float
        Relative step between its stiffnesses (at least :data:`SWEEP_STEP`; coarser when the budget binds).
    from_criterion : bool
        True when it starts at K_criterion.
    points : int
        Stiffnesses swept, from ``start`` up to the limit (0: the limit lies below the start).
    max_points : int
        The sweep's budget of stiffnesses (the wall's :meth:`~dfa.model.wall.WallParams.sweep_points`).
    coarse : bool
        True when the budget made the step coarser than :data:`SWEEP_STEP`.
    fine_points, fine_step : int, float
        The fine zone just below K: :data:`FINE_POINTS` stiffnesses K (1 − fine_step)^j.
    """

    start: float
    step: float
    from_criterion: bool
    points: int
    max_points: int
    coarse: bool
    fine_points: int = FINE_POINTS
    fine_step: float = FINE_STEP

    def to_dict(self) -> dict[str, Any]:
        """The sweep as JSON-able data (its fields)."""
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class Confirmation:
    """What a confirmed simulated limit claims: every run at these speeds, starts and stiffnesses passed.

    Attributes
    ----------
    limit : str
        ``"unstable"`` (no run diverges) or ``"rest"`` (every run comes to rest); none is undecided.
    speeds : tuple of float
        The dense speeds of the band, m/s (rotary: rad/s), each from every start of ``starts``.
    band : tuple of float
        The band's relative bounds (1 − :data:`DENSE_BAND`, 1): stiffnesses in [band[0]·K, K].
    band_stiffnesses : int
        Stiffnesses simulated over the band.
    search_speeds : tuple of float
        The search speeds of the sweep, m/s.
    sweep : SweepRecord
        The sweep in K below the limit at the search speeds.
    starts : tuple of str
        The starts of every impact (:func:`dfa.analysis.limits.runs.starts_of`): ``("impact", "preload")``,
        or a one-sided wall's ``("approach",)``.

    A finite set of speeds and stiffnesses: narrower unsafe bands between the swept stiffnesses, and
    unsafe speeds between those simulated, are not excluded (stability need not be monotone in K).
    """

    limit: str
    speeds: tuple[float, ...]
    band: tuple[float, float]
    band_stiffnesses: int
    search_speeds: tuple[float, ...]
    sweep: SweepRecord
    starts: tuple[str, ...] = ("impact", "preload")

    def to_dict(self) -> dict[str, Any]:
        """The confirmation as JSON-able data (its fields, the sweep nested)."""
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class KLimit(Result):
    """One stiffness limit (N/m; rotary N·m/rad) and the evidence behind it; None with a status that says why.

    The same record for every limit of :class:`dfa.analysis.limits.kmax.KMaxResult`: a closed form (the
    criterion's, the exact linear bound) carries its value and status; a searched one (describing function,
    simulation) also its search and confirmation.

    Attributes
    ----------
    value : float or None
        The limit; None when undefined (``status`` says why).
    status : LimitStatus
        ``found``; or why ``value`` is None (``above_range``, ``below_range``, ``no_range``, ``not_confirmed``,
        ``not_covered``, ``none_proven``, ``not_searched``, ``not_simulated``).
    limited_by : float or None
        Where an undecided judgement (runs too short to tell, or a prediction the describing function cannot
        make) stopped the search, counted as not safe; None when a definite failure did.
    limited_why : str or None
        Why the judgement at ``limited_by`` was undecided, a code of :class:`~dfa.results.status.UndecidedWhy`:
        ``short_runs`` (simulated runs too short to tell), ``subtick`` (the sub-tick caveat of
        :mod:`dfa.analysis.cycles.caveats`), ``below_reach`` (a cycle search that stopped at its size budget bounds
        the growth speed only from below V), ``unknown_growth`` (a cycle search that failed), ``outside_mu`` (μ outside the range the cycle search
        covers); None with ``limited_by`` None.
    range_end : float or None
        The stiffness that bounds the answer where ``status`` is ``above_range`` (the grid's top) or
        ``below_range`` (its lowest point); for ``not_confirmed`` the lowest stiffness reached.
    range_verdict : str or None
        The judgement at the grid's lowest point for ``below_range``.
    non_monotone : bool
        True when grid stiffnesses above ``value`` were found safe again.
    safe_above : tuple of float
        Those stiffnesses.
    undecided : tuple of float
        Stiffnesses at which some judgement was undecided (counted as not safe).
    first_failure : float or None
        The smallest stiffness the search found not safe.
    evaluations : int
        Stiffnesses judged.
    failures : tuple of Failure
        Failing or undecided runs the sweep and the confirmation met above ``value`` (evidence that safety is
        not monotone in K); non-empty means the limit was lowered from ``searched_value``.
    searched_value : float or None
        The limit the search found before the sweep and the confirmation (None: not confirmed, a prediction).
    capped_at : float or None
        The limit was capped there (``k_sim_rest`` at ``k_sim``: coming to rest implies no divergence).
    lowerings : int
        How many times the confirmation lowered the candidate (``not_confirmed``: it gave up after
        :data:`MAX_LOWERINGS`).
    confirmation : Confirmation or None
        What a simulated limit claims (None: not confirmed by simulation).
    """

    value: float | None
    status: LimitStatus = LimitStatus.FOUND
    limited_by: float | None = None
    limited_why: str | None = None
    range_end: float | None = None
    range_verdict: str | None = None
    non_monotone: bool = False
    safe_above: tuple[float, ...] = ()
    undecided: tuple[float, ...] = ()
    first_failure: float | None = None
    evaluations: int = 0
    failures: tuple[Failure, ...] = ()
    searched_value: float | None = None
    capped_at: float | None = None
    lowerings: int = 0
    confirmation: Confirmation | None = None

    json_properties: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self) -> None:
        fix = "a stiffness limit is a finite K > 0, or None with its status"
        for name in ("value", "limited_by", "first_failure", "searched_value", "capped_at"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name), fix)
        object.__setattr__(self, "status", LimitStatus.coerce(self.status))
        if (self.value is None) == (self.status is LimitStatus.FOUND):
            raise DFAValueError(
                f"value = {self.value!r} is invalid with status = {self.status.value!r}: a limit has a value exactly "
                f"when its status is found; {fix}"
            )
        if (self.limited_why is None) != (self.limited_by is None) or (
            self.limited_why is not None and self.limited_why not in {m.value for m in UndecidedWhy}
        ):
            raise DFAValueError(
                f"limited_why = {self.limited_why!r} is invalid with limited_by = {self.limited_by!r}: give one of "
                f"{sorted(m.value for m in UndecidedWhy)} exactly when limited_by is set; {fix}"
            )
        for name in ("safe_above", "undecided", "failures"):
            if not isinstance(getattr(self, name), tuple):
                raise DFATypeError(f"{name} = {getattr(self, name)!r} must be a tuple; {fix}")
        if self.confirmation is not None and not isinstance(self.confirmation, Confirmation):
            raise DFATypeError(f"confirmation must be a Confirmation or None; {fix}")

    @property
    def lowered(self) -> bool:
        """True when the sweep or the confirmation lowered the limit below the searched one."""
        return bool(self.failures)

    @property
    def caveat(self) -> bool:
        """True when the limit stands with a caveat: non-monotone, undecided, or lowered by failures."""
        return bool(self.non_monotone or self.undecided or self.failures)

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            The limit's status message for ``value``, and what the absence of each other field means.
        """
        return {
            "value": self.status.message,
            "limited_by": "a definite failure, not an undecided judgement, bounds the limit",
            "limited_why": "a definite failure, not an undecided judgement, bounds the limit",
            "range_end": "the limit lies inside the searched range",
            "range_verdict": "the lowest stiffness searched passed",
            "first_failure": "no stiffness searched failed",
            "searched_value": "not a simulated search: a closed form or a prediction, with nothing to confirm",
            "capped_at": "not capped",
            "confirmation": "not confirmed by simulation: a closed form or a first-harmonic prediction",
        }


@dataclass(frozen=True)
class StiffnessLimits(Result):
    """Stiffness limits of a device at an impact speed (all N/m, rotary N·m/rad).

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`, the ``dfa stiffness --json`` contract plus extras) holds
    the fields, the device by name and ``velocity_status`` as ``max_passive_velocity_status``; an infinite
    ``max_passive_velocity`` (every speed) is null with the reason of its status.

    Attributes
    ----------
    device : Device
    velocity : float
        Impact speed abs(ẋ0) in m/s (rad/s).
    xi_dot : float
        The same speed in encoder ticks per sample.
    k_max : float
        Criterion limit (eq. 11, with the delay) at this speed.
    k_static : float
        2c/Δ, the limit at rest (eq. 9).
    k_colgate : float
        2b/T (eq. 8, Colgate & Schenkel 1997); b/(T(½ + d)) with a delay.
    k_abbott_okamura : float
        min(2b/T, 2c/Δ) (Abbott & Okamura 2005); min(b/(T(½ + d)), 2c/Δ) with a delay.
    k_gil : float
        Exact linear bound of the sampled spring with the same delay, all Jury conditions (:func:`k_gil`).
    stiffness : float or None
        The stiffness under study, if given.
    max_passive_velocity : float or None
        For ``stiffness``: largest passive speed (inf: every speed; None: none).
    velocity_status : VelocityStatus
        ``NOT_REQUESTED``, ``ALL_SPEEDS``, ``BOUNDED`` or ``NONE`` (codes ``"not_requested"``,
        ``"all_speeds"``, ``"bounded"``, ``"none"``).
    status : StiffnessStatus
        ``OK`` (code ``"ok"``) when ``stiffness`` passes at ``velocity``, ``TOO_STIFF`` (``"too_stiff"``)
        when it does not, ``NOT_REQUESTED`` (``"not_requested"``) when no stiffness was given.
    delay : int
        Computational delay d in samples.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    velocity: float
    xi_dot: float
    k_max: float
    k_static: float
    k_colgate: float
    k_abbott_okamura: float
    k_gil: float
    stiffness: float | None = None
    max_passive_velocity: float | None = field(  # inf (every speed) is null with its status's reason
        default=None, metadata={"json": lambda v: None if math.isinf(v) else v}
    )
    velocity_status: VelocityStatus = field(default=VelocityStatus.NOT_REQUESTED, metadata={"json": None})
    status: StiffnessStatus = StiffnessStatus.NOT_REQUESTED
    delay: int = 0

    json_properties: ClassVar[tuple[str, ...]] = ("max_passive_velocity_status",)

    def __post_init__(self) -> None:
        for name in ("velocity", "xi_dot", "k_max", "k_static", "k_colgate", "k_abbott_okamura", "k_gil"):
            if math.isnan(getattr(self, name)):
                raise DFAValueError(f"{name} = nan is invalid: limits are numbers; build results with stiffness_limits")
        vs = VelocityStatus.coerce(self.velocity_status, "velocity_status")
        st = StiffnessStatus.coerce(self.status)
        object.__setattr__(self, "velocity_status", vs)
        object.__setattr__(self, "status", st)
        mpv = self.max_passive_velocity
        expected = (
            VelocityStatus.NOT_REQUESTED
            if self.stiffness is None
            else (
                VelocityStatus.NONE
                if mpv is None
                else (VelocityStatus.ALL_SPEEDS if math.isinf(mpv) else VelocityStatus.BOUNDED)
            )
        )
        if vs is not expected or ((self.stiffness is None) != (st is StiffnessStatus.NOT_REQUESTED)):
            raise DFAValueError(
                f"velocity_status = {vs.value!r}, status = {st.value!r} are invalid for stiffness = {self.stiffness!r}, "
                f"max_passive_velocity = {mpv!r}: they must agree; build results with stiffness_limits"
            )

    @property
    def max_passive_velocity_status(self) -> VelocityStatus:
        """:attr:`velocity_status`, under the name the JSON gives it (the status of ``max_passive_velocity``)."""
        return self.velocity_status

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            Why ``max_passive_velocity`` is null (by :attr:`velocity_status`) and why ``stiffness`` is.
        """
        why = {
            VelocityStatus.NOT_REQUESTED: "no stiffness given",
            VelocityStatus.ALL_SPEEDS: "passive at every speed (no finite limit)",
            VelocityStatus.NONE: "no passivity guarantee even at rest (K > 2c/Δ)",
        }.get(self.velocity_status, "undefined")
        return {"max_passive_velocity": why, "stiffness": "no stiffness given to assess"}


@dataclass(frozen=True)
class StiffnessResponse(Result):
    """K_max (eq. 11, with the delay) over a range of impact speeds, with the speed-independent bounds (N/m).

    The bounds and the chosen stiffness's largest passive speed are not recomputed:
    they are read from :attr:`limits`, the :class:`StiffnessLimits` of the same
    device, stiffness and delay. Its JSON (:meth:`~dfa.results.base.Result.to_dict`, device units) holds the
    device by name, the speeds, K_max, those bounds, the stiffness, its largest passive speed and the delay
    (:attr:`json_properties`), not :attr:`limits` itself.

    Attributes
    ----------
    device : Device
    velocity : numpy.ndarray
        Impact speeds (m/s or rad/s).
    k_max : numpy.ndarray
        Criterion limit at each speed.
    limits : StiffnessLimits
        The limits at the first speed: source of ``k_static``, ``k_colgate``,
        ``k_abbott_okamura``, ``k_gil``, ``stiffness``, ``max_passive_velocity``
        and ``delay`` (read-only properties here).
    status : CurveStatus

    Arrays are read-only copies of the inputs.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    velocity: np.ndarray
    k_max: np.ndarray
    limits: StiffnessLimits = field(metadata={"json": None})
    status: CurveStatus = CurveStatus.OK

    json_properties: ClassVar[tuple[str, ...]] = (
        "k_static", "k_colgate", "k_abbott_okamura", "k_gil", "stiffness", "max_passive_velocity", "delay",
    )  # fmt: skip

    @property
    def k_static(self) -> float:
        """2c/Δ (eq. 9), N/m."""
        return self.limits.k_static

    @property
    def k_colgate(self) -> float:
        """2b/T (eq. 8); b/(T(½ + d)) with a delay, N/m."""
        return self.limits.k_colgate

    @property
    def k_abbott_okamura(self) -> float:
        """The Abbott-Okamura bound min(2b/T, 2c/Δ) (with the delay), N/m."""
        return self.limits.k_abbott_okamura

    @property
    def k_gil(self) -> float:
        """Exact linear bound of the sampled spring (:func:`k_gil`), N/m."""
        return self.limits.k_gil

    @property
    def stiffness(self) -> float | None:
        """The chosen stiffness to mark, N/m (None: none)."""
        return self.limits.stiffness

    @property
    def max_passive_velocity(self) -> float | None:
        """Its largest passive speed (inf: every speed; None: none), m/s."""
        return self.limits.max_passive_velocity

    @property
    def delay(self) -> int:
        """Computational delay d in samples."""
        return self.limits.delay

    def __post_init__(self) -> None:
        freeze_fields(self, {"velocity": {"ndim": 1}, "k_max": {"ndim": 1}})
        check_shape("k_max", self.k_max, self.velocity.shape)
        object.__setattr__(self, "status", CurveStatus.coerce(self.status))

    def plot(self, ax: Any = None) -> Any:
        """K_max against impact speed with the published bounds (:func:`dfa.render.figures.stiffness_plot`); returns the Axes.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        stiffness_plot = figure_function("stiffness_plot")

        return stiffness_plot(self, ax)

    def to_xarray(self) -> Any:
        """The curve as an :class:`xarray.Dataset` with the labelled dim ``velocity`` (the impact speeds).

        Variable ``k_max``: the criterion's largest passive stiffness at each speed (eq. 11 with the delay).
        Units are the device's (``device.units``: N/m and m/s; rotary N·m/rad and rad/s). Attributes hold the
        device, the delay (samples), the speed-independent bounds ``k_static``, ``k_colgate``,
        ``k_abbott_okamura`` and ``k_gil`` (in ``stiffness_units``), the chosen ``stiffness`` and its
        ``max_passive_velocity`` (in ``velocity_units``; inf: every speed; absent when None) and the status.

        Returns
        -------
        xarray.Dataset
            K_max with the coordinate ``velocity``.

        Raises
        ------
        DFAError
            When the optional package xarray is not installed (``pip install 'dfa-haptics[xarray]'``).

        Examples
        --------
        >>> from dfa.model.catalogue import get_device
        >>> from dfa.analysis.limits.closed_form import stiffness_response
        >>> ds = stiffness_response(get_device("Impulse Engine").device, [0.01, 0.1]).to_xarray()
        >>> ds["k_max"].dims, ds["k_max"].attrs["units"], ds["velocity"].attrs["units"]
        (('velocity',), 'N/m', 'm/s')
        """
        from .xarray import import_xarray, netcdf_attrs, physical_attrs

        xr = import_xarray()
        u = self.device.units
        k_max = physical_attrs("largest passive stiffness K_max, criterion (eq. 11)", u["stiffness"])
        return xr.Dataset(
            {"k_max": ("velocity", np.array(self.k_max), k_max)},
            coords={"velocity": ("velocity", np.array(self.velocity), physical_attrs("impact speed", u["velocity"]))},
            attrs=netcdf_attrs(
                {
                    "device": self.device.name,
                    "rotary": self.device.rotary,
                    "delay": self.delay,
                    "k_static": self.k_static,
                    "k_colgate": self.k_colgate,
                    "k_abbott_okamura": self.k_abbott_okamura,
                    "k_gil": self.k_gil,
                    "stiffness": self.stiffness,
                    "max_passive_velocity": self.max_passive_velocity,
                    "stiffness_units": u["stiffness"],
                    "velocity_units": u["velocity"],
                    "status": self.status,
                    "status_message": self.status.message,
                }
            ),
        )


@dataclass(frozen=True)
class KMaxAssessment(Result):
    """The wall's own stiffness K assessed at the impact speed (physical units).

    Attributes
    ----------
    stiffness : float
        K, N/m (rotary: N·m/rad).
    source : str
        Where K came from: ``"given"``, ``"catalogue"`` or ``"device file"``.
    max_passive_velocity : float or None
        Largest speed the criterion proves passive, m/s (inf: every speed; None: ``velocity_status`` says why).
    velocity_status : VelocityStatus
        ``all_speeds``, ``bounded``, ``none`` (no guarantee even at rest) or ``not_covered`` (no criterion).
    verdict : StiffnessStatus
        The criterion's verdict on K at the impact speed: ``ok`` (proven passive: ``max_passive_velocity``
        >= V), ``too_stiff`` (no guarantee; not a proof of instability) or ``not_covered`` (no criterion
        covers the wall).
    growth_speed : float or None
        Smallest predicted growth speed over every unstable cycle, m/s (inf: none; None: ``growth_unknown``).
    growth_unknown : str or None
        Why the growth speed is unknown: ``"subtick"`` (the sub-tick caveat of
        :mod:`dfa.analysis.cycles.caveats`), ``"incomplete"`` (the cycle search was incomplete) or
        ``"not_linear"`` (a one-sided wall or a passivity controller: no describing function).
    unstable_cycles : int
        Unstable cycles predicted (describing function).
    outcomes : dict
        Simulated outcome of an impact at V from ξ0 = 0 (``"impact"``) and from the preload (``"preload"``);
        a one-sided wall's after the approach from free space (``"approach"``).
    source_file : str or None
        The device file K came from, as given (``source="device file"``); None otherwise (absent from JSON).
    """

    stiffness: float
    source: str
    max_passive_velocity: float | None
    velocity_status: VelocityStatus
    verdict: StiffnessStatus
    growth_speed: float | None
    growth_unknown: str | None
    unstable_cycles: int
    outcomes: dict[str, str] = field(default_factory=dict)
    source_file: str | None = field(default=None, metadata={"omit_none": True})

    json_properties: ClassVar[tuple[str, ...]] = ("passive_at_every_speed", "growth_predicted")

    def __post_init__(self) -> None:
        object.__setattr__(self, "velocity_status", VelocityStatus.coerce(self.velocity_status, "velocity_status"))
        object.__setattr__(self, "verdict", StiffnessStatus.coerce(self.verdict, "verdict"))

    @property
    def passive_at_every_speed(self) -> bool:
        """True when the criterion proves K passive at every speed."""
        return self.velocity_status is VelocityStatus.ALL_SPEEDS

    @property
    def growth_predicted(self) -> bool:
        """True when the describing function predicts growth from a finite speed."""
        return self.growth_speed is not None and not math.isinf(self.growth_speed)

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            Reasons for the largest passive speed and the growth speed.
        """
        return {
            "max_passive_velocity": self.velocity_status.message,
            "growth_speed": {
                "subtick": "unknown: the smallest unstable cycle lies below dfa.analysis.cycles.SUBTICK_LIMIT ticks "
                "(the sub-tick caveat), where simulation has diverged from starts the first harmonic says settle",
                "incomplete": "unknown: the cycle search was incomplete and found no unstable cycle",
                "not_linear": "not predicted: the wall is not a linear loop (the describing function needs one)",
            }.get(self.growth_unknown or "", "no growth predicted (no unstable cycle, stable linear loop)"),
            "growth_unknown": "the growth speed is known",
        }


@dataclass(frozen=True)
class SearchEvidence:
    """How the searched limits were found: the simulated speeds and starts, the runs, the grid and the models.

    Attributes
    ----------
    speeds : tuple of float
        Impact speeds simulated in the search, m/s (rotary: rad/s), each from every start.
    starts : tuple of str
        ``"impact"`` (from ξ0 = 0) and ``"preload"`` (from rest, the spring preloaded to the same energy).
    dense_factor : int
        The confirmation runs this many times as many speeds.
    simulations : int
        Exact simulations the searches and confirmations rest on.
    longest_run, max_samples : int
        Longest run (samples) and the cap of every run.
    df_model : str
        Hold model of the describing function.
    k_range : tuple of float
        Smallest and largest stiffness of the search grid, N/m.
    """

    speeds: tuple[float, ...]
    starts: tuple[str, ...]
    dense_factor: int
    simulations: int
    longest_run: int
    max_samples: int
    df_model: str
    k_range: tuple[float, float]

    def to_dict(self) -> dict[str, Any]:
        """The evidence as JSON-able data (its fields)."""
        return dataclasses.asdict(self)


@dataclass(frozen=True)
class KMaxResult(Result):
    """K_max four ways for a device, a wall and an impact speed (module docstring); stiffnesses in N/m (N·m/rad).

    Attributes
    ----------
    device : Device
    wall : Wall
        The wall whose elements are held fixed while K varies (its own K is the one assessed, if asked).
    velocity : float
        Impact speed V, m/s (rotary: rad/s), >= 0 (at 0 the searched limits are ``not_searched``).
    xi_dot : float
        V in encoder ticks per sample.
    k_criterion, k_linear, k_df, k_sim, k_sim_rest : KLimit
        The four ways (the criterion's proof, the exact linear bound, the describing function's prediction,
        the simulated limits), each with its status and evidence.
    k_static, k_colgate, k_abbott_okamura : float or None
        The spring's published bounds (eq. 9, eq. 8, Abbott-Okamura, with the delay); None for a wall with a
        damper, filter or lag (they are the spring's).
    evidence : SearchEvidence
        What the searched limits rest on.
    counterexamples : tuple of Failure
        Divergent impacts at or below ``k_criterion`` (empty unless the criterion is wrong).
    assessment : KMaxAssessment or None
        The wall's own stiffness assessed, when asked.
    status : KMaxStatus
        ``ok``; ``caveats`` (non-monotone, undecided-limited or lowered searches); ``counterexample``.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    xi_dot: float
    k_criterion: KLimit
    k_linear: KLimit
    k_df: KLimit
    k_sim: KLimit
    k_sim_rest: KLimit
    k_static: float | None
    k_colgate: float | None
    k_abbott_okamura: float | None
    evidence: SearchEvidence
    counterexamples: tuple[Failure, ...] = ()
    assessment: KMaxAssessment | None = None
    status: KMaxStatus = KMaxStatus.OK

    json_properties: ClassVar[tuple[str, ...]] = ("delay",)
    units_of: ClassVar[dict[str, str]] = {
        "velocity": "velocity", "k_criterion": "stiffness", "k_linear": "stiffness", "k_df": "stiffness",
        "k_sim": "stiffness", "k_sim_rest": "stiffness", "k_static": "stiffness", "k_colgate": "stiffness",
        "k_abbott_okamura": "stiffness",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "KMaxResult is built by dfa.design_answer; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        for name in self.limits:
            check_type(name, getattr(self, name), KLimit, fix)
        check_type("evidence", self.evidence, SearchEvidence, fix)
        if self.assessment is not None:
            check_type("assessment", self.assessment, KMaxAssessment, fix)
        object.__setattr__(self, "status", KMaxStatus.coerce(self.status))

    #: The four ways' fields, in the order they are stated.
    limits: ClassVar[tuple[str, ...]] = ("k_criterion", "k_linear", "k_df", "k_sim", "k_sim_rest")

    @property
    def delay(self) -> int:
        """The wall's computational delay d in samples."""
        return self.wall.delay

    @property
    def searches(self) -> dict[str, KLimit]:
        """The three searched limits by name: ``k_df``, ``k_sim`` and ``k_sim_rest``."""
        return {"k_df": self.k_df, "k_sim": self.k_sim, "k_sim_rest": self.k_sim_rest}

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            Reasons for the published bounds (a wall's) and the assessment.
        """
        spring = "the spring's published bound (B = 0, no filter, no lag): not this wall's"
        return {
            "k_static": spring,
            "k_colgate": spring,
            "k_abbott_okamura": spring,
            "assessment": "no stiffness given to assess (and no catalogue K)",
        }


@dataclass(frozen=True)
class PassivityGain(Result):
    """The simulated stiffness limits of a wall with its passivity controller and without it (N/m; N·m/rad).

    Attributes
    ----------
    device : Device
        The device.
    wall : Wall
        The wall with its passivity controller (at any K: K is what is searched).
    velocity : float
        The impact speed V in m/s (rad/s).
    k_sim, k_sim_rest : KLimit
        With the controller: the largest K no simulated impact up to V diverged at, and at which every impact
        rests (:func:`dfa.analysis.limits.kmax.design_answer`).
    plain_k_sim, plain_k_sim_rest : KLimit
        The same without the controller (:meth:`dfa.model.wall.Wall.without_controller`).
    status : GainStatus
        ``ok``; ``caveats`` when a limit of either wall has them; ``counterexample`` from the plain wall's answer.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    k_sim: KLimit
    k_sim_rest: KLimit
    plain_k_sim: KLimit
    plain_k_sim_rest: KLimit
    status: GainStatus = GainStatus.OK

    json_properties = ("gain", "gain_rest")
    units_of = {"velocity": "velocity"}

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, "give a dfa.Device")
        check_type("wall", self.wall, Wall, "give the dfa.Wall with its passivity controller")
        for name in ("k_sim", "k_sim_rest", "plain_k_sim", "plain_k_sim_rest"):
            check_type(name, getattr(self, name), KLimit, "give the KLimit of a design answer")
        check_real("velocity", self.velocity)
        if self.wall.element(PassivityController) is None:
            raise DFAValueError("wall has no passivity controller: add dfa.PassivityController() to its elements")
        object.__setattr__(self, "status", GainStatus.coerce(self.status))

    @property
    def gain(self) -> float | None:
        """The no-divergence limit with the controller over the one without it (None when either has no value)."""
        return _ratio(self.k_sim, self.plain_k_sim)

    @property
    def gain_rest(self) -> float | None:
        """The rest limit with the controller over the one without it (None when either has no value)."""
        return _ratio(self.k_sim_rest, self.plain_k_sim_rest)

    def null_reasons(self) -> dict[str, str]:
        """Why the gains may be null: a limit without a value (its status says why).

        Returns
        -------
        dict of str to str
            Reasons for ``gain`` and ``gain_rest``.
        """
        why = "a limit of one of the walls has no value (see its status)"
        return {"gain": why, "gain_rest": why}


@dataclass(frozen=True)
class StiffnessSpeedChart(Result):
    """Data of the stiffness–speed chart (module docstring); speeds in m/s (rad/s), K in N/m (N·m/rad).

    Attributes
    ----------
    device : Device
    wall : Wall
        The wall whose elements are held fixed while K varies (:attr:`delay` its delay).
    v_top : float
        Top of the speed range (hand speeds).
    stiffness : numpy.ndarray
        Stiffness grid of the simulated and predicted curves.
    v_df, v_sim, v_rest : numpy.ndarray
        Largest safe speed at each K by describing function, simulation (no divergence) and simulation
        (rest); 0: not even the slowest simulated speed; NaN (``v_df``): unknown (:data:`UNKNOWN_DF`).
    criterion_stiffness, v_criterion : numpy.ndarray
        A finer grid and the criterion's largest passive speed on it (0 above 2c/Δ).
    speeds : numpy.ndarray
        Impact speeds simulated at each K (geometric, v_top/200 to v_top).
    k_linear : float
        The exact linear bound (a vertical line; 0: none).
    k_colgate, k_abbott_okamura, k_static : float or None
        The spring's published bounds (vertical lines); None for a wall with a damper, filter or lag.
    design_stiffness, design_velocity : float or None
        The design point.
    simulations : int
        Runs simulated.
    status : ChartStatus
        Derived from ``v_df`` (:attr:`status`).
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    v_top: float
    stiffness: np.ndarray = field(repr=False)
    v_df: np.ndarray = field(repr=False)
    v_sim: np.ndarray = field(repr=False)
    v_rest: np.ndarray = field(repr=False)
    criterion_stiffness: np.ndarray = field(repr=False)
    v_criterion: np.ndarray = field(repr=False)
    speeds: np.ndarray = field(repr=False)
    k_linear: float
    k_colgate: float | None
    k_abbott_okamura: float | None
    k_static: float | None
    design_stiffness: float | None = None
    design_velocity: float | None = None
    simulations: int = 0

    json_properties: ClassVar[tuple[str, ...]] = ("delay", "status")
    units_of: ClassVar[dict[str, str]] = {
        "v_top": "velocity", "stiffness": "stiffness", "v_df": "velocity", "v_sim": "velocity", "v_rest": "velocity",
        "criterion_stiffness": "stiffness", "v_criterion": "velocity", "speeds": "velocity", "k_linear": "stiffness",
        "k_colgate": "stiffness", "k_abbott_okamura": "stiffness", "k_static": "stiffness",
        "design_stiffness": "stiffness", "design_velocity": "velocity",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "StiffnessSpeedChart is built by dfa.stiffness_speed_chart; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        check_positive("v_top", self.v_top, fix)
        arrays = ("stiffness", "v_df", "v_sim", "v_rest", "criterion_stiffness", "v_criterion", "speeds")
        for name in arrays:  # v_df holds NaN where the describing function cannot tell (documented)
            object.__setattr__(self, name, frozen_array(name, getattr(self, name), ndim=1, finite=name != "v_df"))
        for a, b in (("stiffness", "v_df"), ("stiffness", "v_sim"), ("stiffness", "v_rest"),
                     ("criterion_stiffness", "v_criterion")):  # fmt: skip
            if getattr(self, a).shape != getattr(self, b).shape:
                raise DFAValueError(
                    f"{b} has {getattr(self, b).size} values for {getattr(self, a).size} in {a}: "
                    f"it must have one per stiffness; {fix}"
                )
        for name in ("k_linear", "k_colgate", "k_abbott_okamura", "k_static"):
            value = getattr(self, name)
            if value is not None and not (isinstance(value, float) and value == math.inf):  # inf: no finite bound
                check_real(name, value, fix)
        for name in ("design_stiffness", "design_velocity"):
            if getattr(self, name) is not None:
                check_real(name, getattr(self, name), fix)
        check_int("simulations", self.simulations, 0, fix)

    @property
    def status(self) -> ChartStatus:
        """``df_unknown`` where the describing function cannot tell at some stiffness (NaN in ``v_df``), else ``ok``.

        Examples
        --------
        >>> from dfa.model.catalogue import get_device
        >>> from dfa.analysis.limits.speed_chart import stiffness_speed_chart
        >>> stiffness_speed_chart(get_device("Impulse Engine").device, grid=4, speeds=3).status.value
        'ok'
        """
        return ChartStatus.DF_UNKNOWN if bool(np.isnan(self.v_df).any()) else ChartStatus.OK

    def plot(self, ax: Any = None) -> Any:
        """Draw the chart (:func:`dfa.render.figures.stiffness_speed_plot`); returns the axes.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        stiffness_speed_plot = figure_function("stiffness_speed_plot")

        return stiffness_speed_plot(self, ax)

    def to_xarray(self) -> Any:
        """The chart as an :class:`xarray.Dataset` with labelled dims ``stiffness`` and ``criterion_stiffness``.

        Variables over ``stiffness``: ``v_df``, ``v_sim`` and ``v_rest``, the largest safe impact speed by the
        describing function, by simulation (no divergence) and by simulation (comes to rest); over
        ``criterion_stiffness`` (its own, finer grid): ``v_criterion``, the criterion's largest passive speed.
        Values are the chart's: 0 where not even the slowest simulated speed is safe (the criterion: none
        proven), NaN in ``v_df`` where the describing function cannot tell (:data:`UNKNOWN_DF`), and speeds
        above ``v_top`` are the analysis's ``v_top`` (capped there, not here). The coordinate ``speeds`` holds
        the impact speeds simulated at each K. Units are the device's (``device.units``: m/s and N/m; rotary
        rad/s and N·m/rad). Attributes hold the device, ``v_top``, the closed-form bounds and the design point
        (absent when None; in ``stiffness_units`` and ``velocity_units``), the wall held fixed (its damper
        ``virtual_damping`` in ``damping_units``, ``delay`` in samples, ``filter_cutoff`` and
        ``amplifier_bandwidth`` in Hz) and the number of simulations.

        Returns
        -------
        xarray.Dataset
            The largest safe speeds with coordinates ``stiffness``, ``criterion_stiffness`` and ``speeds``.

        Raises
        ------
        DFAError
            When the optional package xarray is not installed (``pip install 'dfa-haptics[xarray]'``).

        Examples
        --------
        >>> from dfa.model.catalogue import get_device
        >>> from dfa.analysis.limits.speed_chart import stiffness_speed_chart
        >>> ds = stiffness_speed_chart(get_device("Impulse Engine").device, grid=3, speeds=2).to_xarray()
        >>> ds["v_sim"].dims, ds["v_criterion"].dims, ds["v_sim"].attrs["units"]
        (('stiffness',), ('criterion_stiffness',), 'm/s')
        """
        from .xarray import import_xarray, netcdf_attrs, physical_attrs

        xr = import_xarray()
        u = self.device.units
        capped = "at most v_top (speeds above it are reported as v_top); 0: not even the slowest simulated speed"
        speed = {
            "v_df": ("describing function", f"{capped}; NaN: {UNKNOWN_DF}"),
            "v_sim": ("simulation: no divergence", capped),
            "v_rest": ("simulation: comes to rest", capped),
        }
        data = {}
        for name, (what, comment) in speed.items():
            attrs = physical_attrs(f"largest safe impact speed, {what}", u["velocity"], comment=comment)
            data[name] = ("stiffness", np.array(getattr(self, name)), attrs)
        criterion = physical_attrs(
            "largest passive impact speed, criterion (proof)", u["velocity"], comment="at most v_top; 0: none proven"
        )
        data["v_criterion"] = ("criterion_stiffness", np.array(self.v_criterion), criterion)
        k_attrs = physical_attrs("virtual stiffness K", u["stiffness"])
        return xr.Dataset(
            data,
            coords={
                "stiffness": ("stiffness", np.array(self.stiffness), k_attrs),
                "criterion_stiffness": ("criterion_stiffness", np.array(self.criterion_stiffness), k_attrs),
                "speeds": ("speeds", np.array(self.speeds), physical_attrs("impact speed simulated", u["velocity"])),
            },
            attrs=netcdf_attrs(
                {
                    "device": self.device.name,
                    "rotary": self.device.rotary,
                    "v_top": self.v_top,
                    "k_linear": self.k_linear,
                    "k_colgate": self.k_colgate,
                    "k_abbott_okamura": self.k_abbott_okamura,
                    "k_static": self.k_static,
                    "design_stiffness": self.design_stiffness,
                    "design_velocity": self.design_velocity,
                    "stiffness_units": u["stiffness"],
                    "velocity_units": u["velocity"],
                    "virtual_damping": self.wall.damping,
                    "damping_units": u["damping"],
                    "delay": self.delay,
                    "filter_cutoff": self.wall.filter_cutoff,
                    "amplifier_bandwidth": self.wall.amplifier_bandwidth,
                    "simulations": self.simulations,
                }
            ),
        )

    @property
    def delay(self) -> int:
        """The wall's computational delay d in samples."""
        return self.wall.delay

    @property
    def criterion_covered(self) -> bool:
        """True when a passivity criterion covers the wall (``v_criterion`` is then a proof; else all 0)."""
        return self.wall.params(self.device.period, self.device.resolution).not_covered() is None

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            Reasons for the describing function's unknown speeds, the spring's bounds and the design point.
        """
        spring = "the spring's published bound (B = 0, no filter, no lag): not this wall's"
        return {
            "v_df": UNKNOWN_DF, "k_colgate": spring, "k_abbott_okamura": spring, "k_static": spring,
            "design_stiffness": "no design point given", "design_velocity": "no design point given",
        }  # fmt: skip
