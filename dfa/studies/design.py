"""The design analysis of one device: every number the design report states, computed once, rendered elsewhere.

:func:`design_analysis` runs, for a device and a wall (the paper's spring with its delay, or a wall with a virtual
damper, velocity filter or amplifier lag, :class:`dfa.model.wall.Wall`), the passivity check (the criterion,
eq. 6-12, extended to the wall, and Colgate–Schenkel, :func:`dfa.analysis.check.passivity_check`), K_max four
ways (:func:`dfa.analysis.limits.kmax.design_answer`, the wall's elements held fixed while K varies), the limit
cycles and growth thresholds of the describing function (eq. 36-45, half-delay and exact ZOH), the simulated
critical impact speed, the simulated outcomes and trajectories, the stability map around the operating point,
the Nyquist locus and the Z-width, and returns a frozen :class:`DesignAnalysis`.

The spring's closed forms (the stiffness limits of eq. 8-11, their curve over speeds) and the stiffness–speed
chart are computed for the spring only: a wall's K_max is the design answer. Rendering (:mod:`dfa.render`,
:func:`dfa.studies.report.design_report`) only reads it. Nothing here reads or writes files.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar, TypeVar, cast

from .._parallel import progress_bar
from ..analysis.approach import approach_samples
from ..analysis.check import PassivityCheck, passivity_check
from ..analysis.criterion import CriterionResult
from ..analysis.cycles import GrowthThreshold, LimitCycleResult, growth_threshold
from ..analysis.limits.closed_form import StiffnessLimits, StiffnessResponse, stiffness_limits, stiffness_response
from ..analysis.limits.grip import GripSweep, grip_sweep
from ..analysis.limits.kmax import KMaxResult, RunCache, check_search_range, design_answer
from ..analysis.limits.recommend import Recommendation, recommend_stiffness
from ..analysis.limits.speed_chart import StiffnessSpeedChart, check_chart_range, stiffness_speed_chart
from ..analysis.limits.tune import TuneResult
from ..analysis.limits.tune import tune as tune_wall
from ..analysis.limits.zwidth import ZWidth, check_zwidth_size, default_damping_max, z_width
from ..analysis.loop import NyquistLocusResponse, nyquist_locus_response
from ..analysis.maps import StabilityMap, map_start, stability_map
from ..analysis.simulation import SimulationResult, divergence_bound, simulate
from ..checks import check_int, check_positive, check_real, check_speed, check_type, format_value
from ..errors import DFATypeError, DFAValueError
from ..grids import geometric_grid
from ..jsonable import explain_nulls, to_jsonable
from ..model.catalogue import CatalogueEntry
from ..model.catalogue import catalogue as catalogue_rows
from ..model.device import Device, Params
from ..model.elements import Coverage
from ..model.loop import LOOP_FIX, Loop
from ..model.wall import Wall, WallParams
from ..results.base import Result
from ..results.configurations import WorstConfiguration
from ..results.status import DesignStatus
from .validation import first_unstable_speed

__all__ = ["DesignAnalysis", "design_analysis"]

F = TypeVar("F", bound=Callable[..., Any])

#: Loop models of the describing-function analysis, in the order the report lists them.
MODELS = ("half-delay", "zoh")
#: Points per axis of the Z-width of a report with a wall beyond the spring when none is asked for (about 10 s).
WALL_ZWIDTH_GRID = 16
#: Why the spring's closed forms are absent from an analysis of a wall with a damper, filter or lag.
SPRING_ONLY = (
    "the spring's closed form (B = 0, no filter, ideal amplifier), not this wall's: not computed for a wall with a "
    "damper, filter or amplifier lag; its K_max is design_answer"
)

_VALIDATION_KEYS = (
    "soundness_violations",
    "soundness_passive",
    "conservatism",
    "speed_df_median_error",
    "short_period_frequency_error",
)


@dataclass(frozen=True)
class DesignAnalysis(Result):
    """Everything the design report of one device states, for a wall and an impact speed ẋ0.

    Its JSON (:meth:`to_dict`) holds the numbers the report states: the fields but the figures' data
    (``trajectory``, ``trajectory_high``, ``stiffness_curve``, ``nyquist``), the thresholds as
    ``growth_thresholds`` and their ``cycles``, and the derived ``stiffness``, ``delay``, ``criterion`` and
    ``simulated_velocity`` (:attr:`json_properties`); every null with its reason (:meth:`null_reasons`).

    Attributes
    ----------
    device : Device
        The device (physical units: SI, rotary in rad, N·m, kg·m²).
    wall : Wall
        The wall of every part: its stiffness K (N/m, rotary N·m/rad) and elements (delay d, virtual damper B,
        velocity filter, amplifier lag); the paper's spring with its delay when it has no other element.
    velocity : float
        Impact speed ẋ0 in m/s (rotary rad/s), ≥ 0.
    params : Params
        (μ, β, σ) of the device at K (paper Table 1).
    check : PassivityCheck
        The criterion at ẋ0 (eq. 6, 10, 12, extended to the wall) and Colgate–Schenkel; not covered with an
        amplifier lag.
    limits : StiffnessLimits or None
        The spring's stiffness limits at ẋ0 (eq. 8, 9, 11, exact linear bound); None for a wall with a damper,
        filter or lag (its K_max is ``design_answer``).
    thresholds : tuple of (str, GrowthThreshold)
        Limit cycles and growth threshold per loop model (``half-delay``, ``zoh``; eq. 36-45); empty for a
        one-sided wall (not a linear loop: no describing function).
    simulated_xi_dot : float or None
        Lowest impact speed ξ'0 (ticks/sample) that diverged in exact simulation (40-point scan, bisection);
        None when no scanned speed diverged. Every run of a one-sided wall (the scan, the outcomes, the
        trajectories, the map) starts with the approach from free space (:func:`dfa.analysis.maps.map_start`).
    outcome : SimulationResult
        Exact simulation at the design speed, as long as the loop's time scales need.
    high_xi_dot : float
        Speed (ticks/sample) of the second simulated impact: just above ``simulated_xi_dot``, or twice the reference.
    outcome_high : SimulationResult
        Exact simulation at ``high_xi_dot``.
    trajectory, trajectory_high : SimulationResult
        Recorded runs (figure windows) at the two speeds.
    stiffness_curve : StiffnessResponse or None
        The spring's largest passive stiffness against speed (figure); None for a wall beyond the spring.
    nyquist : NyquistLocusResponse or None
        Linearised loop and −1/D(M) (figure); None for a one-sided wall.
    stability_map : StabilityMap
        Simulated outcomes around the operating point at the design speed and twice it.
    design_answer : KMaxResult or None
        K_max four ways at the design speed with the wall's elements held fixed
        (:func:`dfa.analysis.limits.kmax.design_answer`, K assessed); None at speed 0.
    speed_chart : StiffnessSpeedChart or None
        Largest safe impact speed against K (:func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart`); the
        spring's, None at speed 0 or for a wall beyond the spring.
    zwidth : ZWidth or None
        The Z-width at the design speed with the wall's delay, filter and lag (:func:`dfa.analysis.limits.zwidth.z_width`,
        a ``zwidth_grid`` grid); None at speed 0 or when not asked.
    grip : GripSweep or None
        How firm a grip the wall needs at K and ẋ0 (:func:`dfa.analysis.limits.grip.grip_sweep`: the bare device,
        the hand's mass held); None at speed 0.
    configurations : WorstConfiguration or None
        A device file's configurations (:func:`dfa.analysis.configurations.worst_stiffness`): the report is the
        limiting configuration's, with a row per configuration; None for a device without configurations.
    tuned : TuneResult or None
        The deployable wall: :func:`dfa.tune` with its default lists at the design speed, the wall's other elements
        held (``tune=True``); None at speed 0 or when not asked.
    catalogue : dict or None
        The printed (μ, β, σ) of a device that has them, the disagreements and the notes; ``paper`` is True for
        the catalogue's own row (the paper printed them), False for another row (a device file: its source did).
    validation : dict or None
        Summary of a validation run (:meth:`dfa.studies.validation.Validation.summary`) passed in; never read from a file.
    samples, map_grid : int
        Samples per run of the speed scan and the map, and the map's points per axis (inputs of the analysis).
    status : DesignStatus
        ``OK``.
    """

    device: Device
    wall: Wall
    velocity: float
    params: Params
    check: PassivityCheck
    limits: StiffnessLimits | None
    thresholds: tuple[tuple[str, GrowthThreshold], ...] = field(metadata={"json": None})
    simulated_xi_dot: float | None
    outcome: SimulationResult
    high_xi_dot: float
    outcome_high: SimulationResult
    trajectory: SimulationResult = field(repr=False, metadata={"json": None})
    trajectory_high: SimulationResult = field(repr=False, metadata={"json": None})
    stiffness_curve: StiffnessResponse | None = field(repr=False, metadata={"json": None})
    nyquist: NyquistLocusResponse | None = field(repr=False, metadata={"json": None})
    stability_map: StabilityMap = field(repr=False)
    design_answer: KMaxResult | None = field(default=None, repr=False)
    speed_chart: StiffnessSpeedChart | None = field(default=None, repr=False)
    zwidth: ZWidth | None = field(default=None, repr=False)
    grip: GripSweep | None = field(default=None, repr=False)
    tuned: TuneResult | None = field(default=None, repr=False, metadata={"omit_none": True})
    configurations: WorstConfiguration | None = field(default=None, repr=False, metadata={"omit_none": True})
    catalogue: dict[str, Any] | None = None
    validation: dict[str, Any] | None = None
    samples: int = 30_000
    map_grid: int = 81
    status: DesignStatus = DesignStatus.OK

    json_properties: ClassVar[tuple[str, ...]] = (
        "stiffness", "delay", "criterion", "growth_thresholds", "cycles", "simulated_velocity", "recommendation",
    )  # fmt: skip

    def __post_init__(self) -> None:
        fix = "DesignAnalysis is built by dfa.design_analysis; call that instead"
        if not isinstance(self.device, Device):
            raise DFATypeError(f"device = {self.device!r} is invalid: it must be a dfa.Device")
        check_type("wall", self.wall, Wall, fix)
        if not check_real("velocity", self.velocity, "give the impact speed") >= 0.0:
            raise DFAValueError(f"velocity = {self.velocity!r} is invalid: the analysis holds |ẋ0| >= 0")
        for name, cls in (
            ("params", Params), ("check", PassivityCheck), ("outcome", SimulationResult),
            ("outcome_high", SimulationResult), ("trajectory", SimulationResult),
            ("trajectory_high", SimulationResult), ("stability_map", StabilityMap),
        ):  # fmt: skip
            check_type(name, getattr(self, name), cls, fix)
        if self.wall.linear == (self.nyquist is None):
            raise DFAValueError(f"nyquist must be None exactly for a wall that is not a linear loop; {fix}")
        if self.nyquist is not None:
            check_type("nyquist", self.nyquist, NyquistLocusResponse, fix)
        self._check_parts(fix)
        if self.simulated_xi_dot is not None:
            check_real("simulated_xi_dot", self.simulated_xi_dot, fix)
        check_real("high_xi_dot", self.high_xi_dot, fix)
        for name in ("catalogue", "validation"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, dict):
                raise DFATypeError(
                    f"{name} = {format_value(value)} has type {type(value).__name__}: it must be a dict or None; {fix}"
                )
        check_int("samples", self.samples, 1, fix)
        check_int("map_grid", self.map_grid, 2, fix)
        self._check_thresholds(fix)
        object.__setattr__(self, "status", DesignStatus.coerce(self.status))

    def _check_parts(self, fix: str) -> None:
        """The optional parts' types; the spring's closed forms only for the spring."""
        for name, cls in (
            ("limits", StiffnessLimits), ("stiffness_curve", StiffnessResponse), ("design_answer", KMaxResult),
            ("speed_chart", StiffnessSpeedChart), ("zwidth", ZWidth), ("tuned", TuneResult),
            ("configurations", WorstConfiguration),
        ):  # fmt: skip
            if getattr(self, name) is not None:
                check_type(name, getattr(self, name), cls, fix)
        if self.covers(Coverage.CLOSED_FORM) and (self.limits is None or self.stiffness_curve is None):
            raise DFAValueError(f"limits and stiffness_curve are required for the spring; {fix}")
        present = [n for n in ("limits", "stiffness_curve", "speed_chart") if getattr(self, n) is not None]
        if not self.covers(Coverage.CLOSED_FORM) and present:
            raise DFAValueError(f"{', '.join(present)} hold the spring's closed forms: None for this wall; {fix}")

    def _check_thresholds(self, fix: str) -> None:
        if not isinstance(self.thresholds, tuple) or not all(
            isinstance(t, tuple) and len(t) == 2 and isinstance(t[1], GrowthThreshold) for t in self.thresholds
        ):
            raise DFATypeError(
                f"thresholds = {format_value(self.thresholds)} is invalid: it must be a tuple of (model, GrowthThreshold) "
                f"pairs; {fix}"
            )
        if tuple(m for m, _ in self.thresholds) != (MODELS if self.wall.linear else ()):
            raise DFAValueError(
                f"thresholds are for {[m for m, _ in self.thresholds]}: they must be for {list(MODELS)}"
            )

    @property
    def stiffness(self) -> float:
        """Virtual wall stiffness K in N/m (rotary N·m/rad): the wall's."""
        return self.wall.stiffness

    @property
    def delay(self) -> int:
        """Computational delay d in samples: the wall's."""
        return self.wall_params.delay

    @property
    def wall_params(self) -> WallParams:
        """The wall's dimensionless groups (β_B, ν_c, α, d) at the device's period."""
        return self.wall.params(self.device.period, self.device.resolution)

    @property
    def is_spring(self) -> bool:
        """True for the paper's spring (with its delay): no damper, filter or amplifier lag."""
        return self.covers(Coverage.CLOSED_FORM)

    def covers(self, what: Coverage) -> bool:
        """Tell whether every analysis of ``what`` covers the wall (:meth:`dfa.model.wall.WallParams.covers`).

        Parameters
        ----------
        what : Coverage
            One analysis or several (``Coverage.CLOSED_FORM``: the spring's closed forms and their sections).

        Returns
        -------
        bool
            True when the analysed wall's coverage holds every flag of ``what``.
        """
        return self.wall_params.covers(what)

    @property
    def criterion(self) -> CriterionResult | None:
        """The criterion at ẋ0 (the check's); None where no criterion covers the wall (an amplifier lag)."""
        return self.check.criterion

    @property
    def xi_dot(self) -> float:
        """The design speed in ticks/sample."""
        return self.device.xi_dot(self.velocity)

    def threshold(self, model: str) -> GrowthThreshold:
        """The growth threshold of loop model ``model`` (``"half-delay"`` or ``"zoh"``).

        Parameters
        ----------
        model : {"half-delay", "zoh"}
            Loop model of the describing-function analysis.

        Returns
        -------
        GrowthThreshold
            The growth band of that model.
        """
        return dict(self.thresholds)[model]

    @property
    def growth_thresholds(self) -> dict[str, GrowthThreshold]:
        """The growth threshold of each loop model (:data:`MODELS`), by model."""
        return dict(self.thresholds)

    @property
    def cycles(self) -> dict[str, LimitCycleResult]:
        """The limit cycles of each loop model (its threshold's :class:`~dfa.analysis.cycles.LimitCycleResult`)."""
        return {m: g.result for m, g in self.thresholds}

    @property
    def simulated_velocity(self) -> float | None:
        """``simulated_xi_dot`` in m/s (rotary rad/s), or None."""
        return None if self.simulated_xi_dot is None else self.device.velocity(self.simulated_xi_dot)

    @property
    def recommendation(self) -> Recommendation | None:
        """The recommended stiffness of the design answer, or None at speed 0 (no design answer).

        :func:`~dfa.analysis.limits.recommend.recommend_stiffness` with the default gain margin: what
        ``dfa stiffness`` recommends for this wall and speed.
        """
        if self.design_answer is None:
            return None
        return recommend_stiffness(self.design_answer)

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            Why a part was not computed or passed in; the spring's closed forms for a wall beyond the spring.
        """
        why = {
            "recommendation": "impact speed 0: the recommendation needs the design answer (a speed > 0)",
            "validation": "no validation summary passed in (dfa report --validation FILE)",
            "catalogue": "not a catalogue device with printed (μ, β, σ)",
            "simulated_xi_dot": "no scanned impact speed diverged",
            "simulated_velocity": "no scanned impact speed diverged",
            "design_answer": "impact speed 0: the design answer needs a speed > 0",
            "speed_chart": "impact speed 0: the chart needs a speed > 0",
            "zwidth": "impact speed 0 or zwidth_grid=0: no Z-width computed",
            "criterion": "no passivity criterion covers this wall (an amplifier lag): see check",
        }
        if not self.covers(Coverage.CLOSED_FORM):
            why.update(limits=SPRING_ONLY, stiffness_curve=SPRING_ONLY, speed_chart=SPRING_ONLY)
        return why

    def to_dict(self) -> dict[str, Any]:
        """The numbers the report states, strict JSON data (SI units; speeds also in ticks/sample).

        :meth:`dfa.results.base.Result.to_dict` (the fields, :attr:`json_properties`, the status message and
        :meth:`null_reasons`), the wall's record completed by its dimensionless groups at the device's period,
        which the wall alone does not know.

        Returns
        -------
        dict
            Strict-JSON data: device, wall, inputs and every analysis of the report, with the status.
        """
        out = super().to_dict()
        wall = to_jsonable({**self.wall.to_dict(), "dimensionless": self.wall_params.to_dict()})
        out["wall"] = explain_nulls(
            wall, {"filter_cutoff": "no velocity filter", "amplifier_bandwidth": "ideal amplifier (no lag)"}
        )
        return out


def _catalogue_notes(entry: CatalogueEntry | None) -> dict[str, Any] | None:
    if entry is None or not entry.printed_params:
        return None
    return {
        "printed": [[{"mu": "μ", "beta": "β", "sigma": "σ"}[k], text] for k, text in entry.printed],
        "discrepancies": [str(x) for x in entry.discrepancies],
        "notes": entry.notes or "",
        "paper": entry in catalogue_rows(),  # the catalogue's own row (the paper printed it), not a device file's
    }


def _check_validation(summary: dict[str, Any] | None) -> dict[str, Any] | None:
    if summary is None:
        return None
    if not isinstance(summary, dict):
        raise DFATypeError(f"validation = {summary!r:.60} is invalid: pass the dict of Validation.summary() or None")
    missing = [k for k in _VALIDATION_KEYS if k not in summary]
    if missing:
        raise DFAValueError(
            f"validation lacks {', '.join(missing)}: pass the dict of dfa.validate(...).summary() (or None)"
        )
    # validation.json is strict JSON (dfa.jsonable): a NaN summary number was stored as null; read it back as NaN
    return {k: math.nan if k in _VALIDATION_KEYS and v is None else v for k, v in summary.items()}


def resolve_design_inputs(
    device: Device | CatalogueEntry, wall: Wall | float | None, velocity: float | None
) -> tuple[CatalogueEntry | None, Loop, float]:
    """(catalogue entry or None, loop, |ẋ0|) of a design analysis in the former form, checked; defaults filled in.

    ``wall`` is a :class:`Wall`, a stiffness K (the spring), or None (the spring at the catalogue K). The loop's
    groups are formed here, once (:class:`~dfa.model.loop.Loop`).
    """
    entry = device if isinstance(device, CatalogueEntry) else None
    dev = entry.device if entry is not None else device
    if not isinstance(dev, Device):
        raise DFAValueError(f"device = {device!r} is invalid: it must be a dfa.Device or a catalogue entry")
    if wall is None:
        if entry is None or entry.stiffness is None:
            raise DFAValueError(
                f"wall = None is invalid for {dev.name!r}: the catalogue gives no K; pass the wall, or its stiffness "
                f"in {dev.units['stiffness']}"
            )
        wall = entry.stiffness
    if not isinstance(wall, Wall):
        wall = Wall(check_positive("wall", wall, "give the wall, or the virtual wall stiffness K"))
    v = _design_speed(dev, velocity)
    loop = Loop(dev, wall)  # a filter above Nyquist or a group out of range is refused here, before any work
    _check_ranges(loop, v)
    return entry, loop, v


def _design_speed(dev: Device, velocity: float | None) -> float:
    """|ẋ0| of a design analysis: ``velocity`` checked, default 0.1 m/s (1 rad/s rotary)."""
    return check_speed("velocity", velocity if velocity is not None else (1.0 if dev.rotary else 0.1))


def _check_ranges(loop: Loop, v: float) -> None:
    """Refuse, before any work, a stiffness range no float search can run (the design answer's and the chart's)."""
    dev, wall = loop.physical("design_analysis")
    check_search_range(dev, wall, v)  # the design answer's …
    if v > 0 and loop.groups("design_analysis")[1].covers(Coverage.CLOSED_FORM):
        check_chart_range(dev, wall, wall.stiffness, v)  # … and the chart's: 8 K = inf at K = 1e308


def design_loop(loop: Loop, velocity: float | None, entry: CatalogueEntry | None = None) -> tuple[Loop, float]:
    """(loop, |ẋ0|) of a design analysis given a loop, checked: a loop at no given K takes the catalogue K.

    Parameters
    ----------
    loop : Loop
        The device and the wall (K in N/m, rotary N·m/rad); ``Loop(device)`` with a catalogue ``entry``: the
        spring at the catalogue K.
    velocity : float or None
        Impact speed in m/s (rotary rad/s); None: 0.1 m/s (1 rad/s rotary).
    entry : CatalogueEntry, optional
        The catalogue entry of the loop's device (its K, its printed values and notes).

    Returns
    -------
    tuple of (Loop, float)
        The loop at its K and the speed.

    Raises
    ------
    DFAValueError, DFATypeError
        Not a loop of a device, no stiffness, a bad speed, or a stiffness range no search can run.
    """
    check_type("loop", loop, Loop, LOOP_FIX)
    if entry is not None:
        check_type("entry", entry, CatalogueEntry, "give the device's dfa.catalogue() entry, or None")
        if loop.wall is None and entry.stiffness is not None and loop.device is not None:
            loop = loop.at(entry.stiffness)
    dev, _wall = loop.physical("design_analysis")
    v = _design_speed(dev, velocity)
    _check_ranges(loop, v)
    return loop, v


def design_first(func: F) -> F:
    """Let :func:`design_analysis` and :func:`dfa.report.design_report` (a :class:`Loop` first, the speed second,
    the catalogue entry a keyword) still be called in the former form (device or catalogue entry, wall, velocity),
    resolved by :func:`resolve_design_inputs`."""

    @functools.wraps(func)
    def design_first_wrapper(*args: Any, **kwargs: Any) -> Any:
        if (args and isinstance(args[0], Loop)) or "loop" in kwargs:
            return func(*args, **kwargs)
        names = ("device", "wall", "velocity")
        given = dict(zip(names, args, strict=False))
        given.update({n: kwargs.pop(n) for n in names[len(args) :] if n in kwargs})
        if "device" not in given:
            raise TypeError("missing the argument 'device' (or give a dfa.Loop first)")
        entry, loop, v = resolve_design_inputs(given["device"], given.get("wall"), given.get("velocity"))
        return func(loop, v, *args[3:], entry=entry, **kwargs)

    return cast(F, design_first_wrapper)


def _simulations(loop: Loop, xi_dot: float, ref: float, v_sim: float | None, samples: int) -> dict[str, Any]:
    """Recorded runs for the figure and full-length runs for the outcomes, at the design speed and above."""
    p, wp = loop.groups("design_analysis")
    n_traj = int(min(samples, max(2000, 40 * 2 * math.pi * math.sqrt(p.mu))))
    # a one-sided wall's runs start with the approach
    n_traj += 0 if wp.covers(Coverage.SURFACE_START) else approach_samples(wp)
    v_show = v_sim * 1.05 if v_sim is not None else 2.0 * ref

    def run(v: float, n: int | None, rec: bool) -> SimulationResult:
        x0, v0 = map_start(p.mu, v, False, wp)  # the impact at ξ0 = 0, or a one-sided wall's approach
        return simulate(  # diverged only far beyond the impact's own travel (eq. 18-19)
            loop, v0, n, xi0=x0, record=rec, bound=divergence_bound(x0, v0, p.mu)
        )

    return dict(
        trajectory=run(xi_dot, n_traj, True),
        outcome=run(
            xi_dot, None, False
        ),  # length from the loop's time scales (dfa.analysis.simulation.default_samples)
        high_xi_dot=v_show,
        trajectory_high=run(v_show, n_traj, True),
        outcome_high=run(v_show, None, False),
    )


@design_first
def design_analysis(
    loop: Loop,
    velocity: float | None = None,
    *,
    entry: CatalogueEntry | None = None,
    map_grid: int = 81,
    samples: int = 30_000,
    validation: dict[str, Any] | None = None,
    n_jobs: int = -1,
    progress: bool = False,
    zwidth_grid: int | None = None,
    tune: bool = False,
    configurations: WorstConfiguration | None = None,
) -> DesignAnalysis:
    """Compute every number of the design report of the loop's device with its wall at impact speed ẋ0.

    Parameters
    ----------
    loop : Loop
        The device and the wall (:class:`dfa.Wall`: K in N/m, rotary N·m/rad, and its elements: delay, virtual
        damper B, velocity filter, amplifier; or a stiffness K for the paper's spring), ``Loop(device, wall)``;
        ``Loop(device)`` with a catalogue ``entry``: the spring at the catalogue K. Its groups are formed once and
        passed to every section. The former call ``design_analysis(device_or_entry, wall, velocity)`` still works.
    velocity : float, optional
        Impact speed in m/s (rotary rad/s); default 0.1 m/s (1 rad/s rotary); >= 0 (a negative is refused).
    entry : CatalogueEntry, optional
        Keyword only: the catalogue entry of the loop's device, adding the paper's printed values and notes.
    map_grid, samples : int
        Points per axis of the stability map (default 81); samples per run of it and of the speed scan (30000).
    validation : dict, optional
        Summary of a validation run (``dfa.validate(...).summary()``) for the report's "how far to trust"
        paragraph; no file is ever read.
    n_jobs : int
        Parallel jobs of the stability map (default -1: all cores; see :func:`dfa.stability_map`).
    progress : bool
        Progress bar over the parts (default False).
    zwidth_grid : int or None
        Points per axis of the report's Z-width (one impact speed, :func:`dfa.analysis.limits.zwidth.z_width`);
        default None: none for the spring, :data:`WALL_ZWIDTH_GRID` (16) for a wall beyond it; 0: none.
    tune : bool
        Add the deployable wall (:func:`dfa.tune` with its default lists at the design speed; about 40 s;
        default False).
    configurations : WorstConfiguration or None
        A device file's configurations, already answered (the loop's device is the limiting one): a row per
        configuration in the report (default None).

    Returns
    -------
    DesignAnalysis
        Every number the design report states (frozen, JSON-able with ``to_dict()``).

    Raises
    ------
    DFAValueError, DFATypeError
        Not a Device or catalogue entry, no stiffness, a non-finite speed, a bad validation summary, or a wall
        element out of range (a filter cutoff above Nyquist).

    See Also
    --------
    dfa.studies.report.design_report : This analysis rendered as Markdown and/or HTML.
    design_answer : The largest stiffness four ways, for the design question alone.

    Examples
    --------
    >>> import dfa
    >>> entry = dfa.get_device("impulse")
    >>> a = design_analysis(dfa.Loop(entry.device), 0.05, entry=entry, map_grid=3, samples=2000, n_jobs=1)
    >>> a.criterion.passive, round(a.limits.k_max, 1), a.outcome.outcome.value
    (True, 120.8, 'rest')
    """
    loop, v = design_loop(loop, velocity, entry)
    dev, wall = loop.physical("design_analysis")
    p, wp = loop.groups("design_analysis")  # formed once, here
    checked = _check_validation(validation)
    zg = check_int("zwidth_grid", zwidth_grid, 0, "give the Z-width's points per axis, or 0 for none") if (
        zwidth_grid is not None) else (0 if wp.covers(Coverage.CLOSED_FORM) else WALL_ZWIDTH_GRID)  # fmt: skip
    check_zwidth_size(zg, names=("zwidth_grid", "speeds"))  # here, before the sections that run first
    with progress_bar(total=4, desc=f"analysis {dev.name}", disable=not progress, leave=False) as steps:
        head = _closed_forms(loop, v)
        steps.update()
        thr = () if not wp.linear else tuple((m, growth_threshold(loop, model=m)) for m in MODELS)
        steps.update()
        crit = head["check"].criterion
        ref = crit.critical_xi_dot if crit is not None and crit.critical_xi_dot else max(1.0, dev.xi_dot(v))
        v_sim = first_unstable_speed(p, 0.2 * ref, 30.0 * ref, samples, preload=False, wall=wp)
        steps.update()
        sims = _simulations(loop, dev.xi_dot(v), ref, v_sim, samples)
        ny = None if not wp.linear else _nyquist(loop, thr[1][1])
        steps.update()
        smap = _map_around(p, dev.xi_dot(v), map_grid, samples, n_jobs, progress, wp)
    figs: dict[str, Any] = dict(nyquist=ny, stability_map=smap)
    if v > 0:  # the design answer, first in the report: K_max four ways (and the spring's stiffness-speed chart)
        cache = RunCache()  # one set of runs for both: no (K, speed, start) simulated twice
        figs["design_answer"] = design_answer(loop, v, assess=True, cache=cache)
        if wp.covers(Coverage.CLOSED_FORM):
            figs["speed_chart"] = stiffness_speed_chart(loop, stiffness=wall.stiffness, velocity=v, cache=cache)
    if v > 0:  # how firm a grip the wall needs (the bare device, the hand's mass held)
        figs["grip"] = grip_sweep(dev.bare, wall, v, hand_mass=0.0 if dev.hand is None else dev.hand.mass)
    if v > 0 and zg:
        figs["zwidth"] = _zwidth(loop, v, not wp.covers(Coverage.CLOSED_FORM), zg, n_jobs, progress)
    if v > 0 and tune:
        figs["tuned"] = tune_wall(loop, v)
    if configurations is not None:
        figs["configurations"] = check_type(
            "configurations", configurations, WorstConfiguration, "give worst_stiffness's"
        )
    inputs: dict[str, Any] = dict(
        catalogue=_catalogue_notes(entry), validation=checked, samples=samples, map_grid=map_grid
    )
    return DesignAnalysis(dev, wall, v, p, thresholds=thr, simulated_xi_dot=v_sim, **head, **figs, **inputs, **sims)


def _closed_forms(loop: Loop, v: float) -> dict[str, Any]:
    """The passivity check at the design speed; for the spring also its stiffness limits and curve (eq. 8-11)."""
    chk = passivity_check(loop, v)
    dev, wall = loop.physical("design_analysis")
    wp = loop.groups("design_analysis")[1]
    if not wp.covers(Coverage.CLOSED_FORM):
        return dict(check=chk, limits=None, stiffness_curve=None)
    k, d = wall.stiffness, wp.delay
    lim = stiffness_limits(dev, v, k, delay=d)
    return dict(check=chk, limits=lim, stiffness_curve=stiffness_response(dev, stiffness=k, delay=d))


def _zwidth(loop: Loop, v: float, widen: bool, grid: int, n_jobs: int, progress: bool) -> ZWidth:
    """The Z-width at the design speed, with the wall's delay, filter and lag; B's axis holds the wall's B."""
    dev, wall = loop.physical("design_analysis")
    b_top = default_damping_max(dev, wall, v)  # z_width's default range, widened to show the controller's B
    b_range = (0.0, 1.25 * wall.damping) if widen and wall.damping > b_top else None
    return z_width(loop, v, grid=grid, b_range=b_range, speeds=1, n_jobs=n_jobs, progress=progress)


def _map_around(
    p: Params, xi_dot: float, grid: int, samples: int, n_jobs: int, progress: bool, wp: WallParams
) -> StabilityMap:
    """Simulated outcomes on (β, σ) around the operating point, at the design speed and twice it."""
    return stability_map(
        p.mu,
        [xi_dot, 2 * xi_dot] if xi_dot > 0 else [1.0, 2.0],
        beta_range=(0.0, max(0.25, 2 * p.beta)),
        sigma_range=(0.0, max(1.0, 2 * p.sigma)),
        grid=grid,
        samples=samples,
        progress=progress,
        n_jobs=n_jobs,
        bound=divergence_bound(0.0, 2 * xi_dot if xi_dot > 0 else 2.0, p.mu),  # beyond every start's travel
        wall=wp,
    )


def _nyquist(loop: Loop, zoh: GrowthThreshold) -> NyquistLocusResponse:
    """The Nyquist view of the exact ZOH loop (the model of the growth threshold), its cycles marked: the locus
    reaches every cycle drawn."""
    p = loop.groups("design_analysis")[0]
    res = zoh.result
    amps = [c.amplitude for c in res.cycles[:3]] if p.sigma > 0 else None
    if p.sigma > 0 and not amps:
        amps = [1.0]
    m_top = max([50.0] + [2.0 * c.amplitude for c in res.cycles])
    la = geometric_grid(0.05, m_top, 1500)
    return nyquist_locus_response(loop, amplitudes=amps, locus_amplitude=la, model="zoh", cycles=res)
