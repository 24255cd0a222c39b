"""The design analysis of one device: every number the design report states, computed once, rendered elsewhere.

:func:`design_analysis` runs the criterion (eq. 6-12), the stiffness limits (eq. 8, 9, 11 and the exact linear
bound), the limit cycles and growth thresholds of the describing function (eq. 36-45, half-delay and exact ZOH),
the simulated critical impact speed, the simulated outcomes and trajectories, the stability map around the
operating point and the Nyquist locus, and returns a frozen :class:`DesignAnalysis`.

With a wall controller (``controller=``, issue 15) every part that accepts one is computed with it: the passivity
check (extended criterion and Colgate–Schenkel, :func:`dfa.analysis.check.passivity_check`), K_max with the
controller (:func:`dfa.analysis.limits.kmax.design_answer` with the wall), the limit cycles, the simulations, the
stability map, the Nyquist locus and the Z-width (on by default). The spring-only parts (the criterion of eq. 6
and its stiffness limits and curve, the four-way design answer and the stiffness–speed chart) are not computed:
they would state the bare spring's numbers, not the controller's. Rendering
(:mod:`dfa.render`, :func:`dfa.report.design_report`) only reads it. Nothing here reads or writes files.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..checks import _fmt, check_delay, check_int, check_positive, check_real, check_speed, check_type
from ..errors import DFATypeError, DFAValueError
from ..model.catalogue import CatalogueEntry
from ..model.device import Device, Params
from ..model.wall import Wall, WallParams
from ..results.jsonable import explain_nulls, to_jsonable
from ..results.status import DesignStatus
from .check import PassivityCheck, passivity_check
from .criterion import CriterionResult, device_criterion
from .cycles import GrowthThreshold, growth_threshold
from .limits.closed_form import StiffnessLimits, StiffnessResponse, stiffness_limits, stiffness_response
from .limits.kmax import KMaxResult, RunCache, design_answer
from .limits.speed_chart import StiffnessSpeedChart, stiffness_speed_chart
from .limits.zwidth import ZWidth, z_width
from .loop import NyquistLocusResponse, nyquist_locus_response
from .maps import StabilityMap, stability_map
from .simulation import SimulationResult, divergence_bound, simulate
from .validation import first_unstable_speed

__all__ = ["DesignAnalysis", "design_analysis"]

#: Loop models of the describing-function analysis, in the order the report lists them.
MODELS = ("half-delay", "zoh")
#: Points per axis of the Z-width of a report with a controller when none is asked for (about 10 s on 2 cores).
CONTROLLER_ZWIDTH_GRID = 16
#: Why the spring-only parts are absent from an analysis with a controller.
SPRING_ONLY = (
    "the spring's (B = 0, no filter, ideal amplifier) result, not this controller's: not computed with a controller; "
    "see controller_check and controller_limits"
)

_VALIDATION_KEYS = (
    "soundness_violations",
    "soundness_passive",
    "conservatism",
    "speed_df_median_error",
    "short_period_frequency_error",
)


@dataclass(frozen=True)
class DesignAnalysis:
    """Everything the design report of one device states, at stiffness K, impact speed ẋ0 and delay d.

    Attributes
    ----------
    device : Device
        The device (physical units: SI, rotary in rad, N·m, kg·m²).
    stiffness : float
        Virtual wall stiffness K in N/m (rotary N·m/rad).
    velocity : float
        Impact speed ẋ0 in m/s (rotary rad/s), ≥ 0.
    delay : int
        Computational delay d in samples.
    params : Params
        (μ, β, σ) of the device at K (paper Table 1).
    criterion : CriterionResult or None
        The passivity criterion at ẋ0 (eq. 6, 10, 12); None with a controller (``controller_check``).
    limits : StiffnessLimits or None
        Stiffness limits at ẋ0 (eq. 8, 9, 11, exact linear bound); None with a controller (``controller_limits``).
    thresholds : tuple of (str, GrowthThreshold)
        Limit cycles and growth threshold per loop model (``half-delay``, ``zoh``; eq. 36-45).
    simulated_xi_dot : float or None
        Lowest impact speed ξ'0 (ticks/sample) that diverged in exact simulation (40-point scan, bisection);
        None when no scanned speed diverged.
    outcome : SimulationResult
        Exact simulation at the design speed, as long as the loop's time scales need.
    high_xi_dot : float
        Speed (ticks/sample) of the second simulated impact: just above ``simulated_xi_dot``, or twice the reference.
    outcome_high : SimulationResult
        Exact simulation at ``high_xi_dot``.
    trajectory, trajectory_high : SimulationResult
        Recorded runs (figure windows) at the two speeds.
    stiffness_curve : StiffnessResponse or None
        Largest passive stiffness against speed (figure); None with a controller.
    nyquist : NyquistLocusResponse
        Linearised loop and −1/D(M) (figure).
    stability_map : StabilityMap
        Simulated outcomes around the operating point at the design speed and twice it.
    design_answer : KMaxResult or None
        K_max four ways at the design speed (:func:`dfa.analysis.limits.kmax.design_answer`); None at speed 0 or with a controller.
    speed_chart : StiffnessSpeedChart or None
        Largest safe impact speed against K (:func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart`); None at speed 0 or
        with a controller.
    zwidth : ZWidth or None
        The Z-width at the design speed and delay (:func:`dfa.analysis.limits.zwidth.z_width`, a ``zwidth_grid`` grid); None at
        speed 0 or when not asked.
    catalogue : dict or None
        The paper's printed (μ, β, σ), the disagreements and the notes of a catalogue device.
    validation : dict or None
        Summary of a validation run (:meth:`dfa.analysis.validation.Validation.summary`) passed in; never read from a file.
    samples, map_grid : int
        Samples per run of the speed scan and the map, and the map's points per axis (inputs of the analysis).
    controller : Wall or None
        The wall controller of every simulation, limit cycle, map and the Z-width (its stiffness is K, its delay
        d); None: the paper's spring.
    controller_check : PassivityCheck or None
        With a controller: the extended criterion and Colgate–Schenkel at ẋ0 (not covered with an amplifier lag).
    controller_limits : KMaxResult or None
        With a controller and ẋ0 > 0: K_max with the controller (B, f_c, f_bw, d fixed;
        :func:`dfa.analysis.limits.kmax.design_answer` with the wall).
    status : DesignStatus
        ``OK``.
    """

    device: Device
    stiffness: float
    velocity: float
    delay: int
    params: Params
    criterion: CriterionResult | None
    limits: StiffnessLimits | None
    thresholds: tuple[tuple[str, GrowthThreshold], ...]
    simulated_xi_dot: float | None
    outcome: SimulationResult
    high_xi_dot: float
    outcome_high: SimulationResult
    trajectory: SimulationResult = field(repr=False)
    trajectory_high: SimulationResult = field(repr=False)
    stiffness_curve: StiffnessResponse | None = field(repr=False)
    nyquist: NyquistLocusResponse = field(repr=False)
    stability_map: StabilityMap = field(repr=False)
    design_answer: KMaxResult | None = field(default=None, repr=False)
    speed_chart: StiffnessSpeedChart | None = field(default=None, repr=False)
    zwidth: ZWidth | None = field(default=None, repr=False)
    catalogue: dict[str, Any] | None = None
    validation: dict[str, Any] | None = None
    samples: int = 30_000
    map_grid: int = 81
    controller: Wall | None = None
    controller_check: PassivityCheck | None = None
    controller_limits: KMaxResult | None = field(default=None, repr=False)
    status: DesignStatus = DesignStatus.OK

    def __post_init__(self) -> None:
        if not isinstance(self.device, Device):
            raise DFATypeError(f"device = {self.device!r} is invalid: it must be a dfa.Device")
        check_positive("stiffness", self.stiffness, "give the virtual wall stiffness K")
        if not check_real("velocity", self.velocity, "give the impact speed") >= 0.0:
            raise DFAValueError(f"velocity = {self.velocity!r} is invalid: the analysis holds |ẋ0| >= 0")
        check_delay(self.delay)
        fix = "DesignAnalysis is built by dfa.design_analysis; call that instead"
        for name, cls in (
            ("params", Params), ("outcome", SimulationResult), ("outcome_high", SimulationResult),
            ("trajectory", SimulationResult), ("trajectory_high", SimulationResult),
            ("nyquist", NyquistLocusResponse), ("stability_map", StabilityMap),
        ):  # fmt: skip
            check_type(name, getattr(self, name), cls, fix)
        self._check_parts(fix)
        for name, opt in (("design_answer", KMaxResult), ("speed_chart", StiffnessSpeedChart), ("zwidth", ZWidth)):
            if getattr(self, name) is not None:
                check_type(name, getattr(self, name), opt, fix)
        if self.simulated_xi_dot is not None:
            check_real("simulated_xi_dot", self.simulated_xi_dot, fix)
        check_real("high_xi_dot", self.high_xi_dot, fix)
        for name in ("catalogue", "validation"):
            value = getattr(self, name)
            if value is not None and not isinstance(value, dict):
                raise DFATypeError(
                    f"{name} = {_fmt(value)} has type {type(value).__name__}: it must be a dict or None; {fix}"
                )
        check_int("samples", self.samples, 1, fix)
        check_int("map_grid", self.map_grid, 2, fix)
        if not isinstance(self.thresholds, tuple) or not all(
            isinstance(t, tuple) and len(t) == 2 and isinstance(t[1], GrowthThreshold) for t in self.thresholds
        ):
            raise DFATypeError(
                f"thresholds = {_fmt(self.thresholds)} is invalid: it must be a tuple of (model, GrowthThreshold) "
                f"pairs; {fix}"
            )
        if tuple(m for m, _ in self.thresholds) != MODELS:
            raise DFAValueError(
                f"thresholds are for {[m for m, _ in self.thresholds]}: they must be for {list(MODELS)}"
            )
        object.__setattr__(self, "status", DesignStatus.coerce(self.status))

    def _check_parts(self, fix: str) -> None:
        """The spring's parts without a controller; the controller's (and none of the spring's) with one."""
        spring = (("criterion", CriterionResult), ("limits", StiffnessLimits), ("stiffness_curve", StiffnessResponse))
        if self.controller is None:
            for name, cls in spring:
                check_type(name, getattr(self, name), cls, fix)
            if self.controller_check is not None or self.controller_limits is not None:
                raise DFAValueError(f"controller_check and controller_limits need a controller; {fix}")
            return
        check_type("controller", self.controller, Wall, fix)
        check_type("controller_check", self.controller_check, PassivityCheck, fix)
        if self.controller_limits is not None:
            check_type("controller_limits", self.controller_limits, KMaxResult, fix)
        present = [n for n, _ in spring if getattr(self, n) is not None]
        present += [n for n in ("design_answer", "speed_chart") if getattr(self, n) is not None]
        if present or self.controller.stiffness != self.stiffness or self.controller.delay != self.delay:
            raise DFAValueError(
                f"with a controller the spring-only parts must be None (given: {', '.join(present) or 'none'}) and "
                f"the controller's K and delay must be the analysis's; {fix}"
            )

    @property
    def xi_dot(self) -> float:
        """The design speed in ticks/sample (the criterion's, or converted by the device with a controller)."""
        return self.criterion.xi_dot if self.criterion is not None else self.device.xi_dot(self.velocity)

    @property
    def controller_params(self) -> WallParams | None:
        """The controller's dimensionless groups (β_B, ν_c, α, d) at the device's period; None for the spring."""
        return None if self.controller is None else self.controller.params(self.device.period)

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
    def simulated_velocity(self) -> float | None:
        """``simulated_xi_dot`` in m/s (rotary rad/s), or None."""
        return None if self.simulated_xi_dot is None else self.device.velocity(self.simulated_xi_dot)

    def to_dict(self) -> dict[str, object]:
        """The numbers the report states, strict JSON data (SI units; speeds also in ticks/sample).

        Returns
        -------
        dict
            Strict-JSON data: device, inputs and every analysis of the report, with the status.
        """
        why = {
            "validation": "no validation summary passed in (dfa report --validation FILE)",
            "catalogue": "not a catalogue device with printed (μ, β, σ)",
            "simulated_xi_dot": "no scanned impact speed diverged",
            "simulated_velocity": "no scanned impact speed diverged",
            "design_answer": "impact speed 0: the design answer needs a speed > 0",
            "speed_chart": "impact speed 0: the chart needs a speed > 0",
            "zwidth": "impact speed 0 or zwidth_grid=None: no Z-width computed",
        }
        rec = self._record()
        if self.controller is not None:  # the spring's record is unchanged; a controller adds its parts
            why.update(criterion=SPRING_ONLY, limits=SPRING_ONLY, design_answer=SPRING_ONLY, speed_chart=SPRING_ONLY)
            why.update(zwidth="impact speed 0 or zwidth_grid=0: no Z-width computed")
            why.update(controller_limits="impact speed 0: K_max with the controller needs a speed > 0")
            rec.update(self._controller_record())
            _explain_filter_nulls(rec)
        return explain_nulls(rec, why)

    def _controller_record(self) -> dict[str, Any]:
        assert self.controller is not None and self.controller_check is not None
        cp = self.controller.params(self.device.period)
        ctl = to_jsonable({**self.controller.to_dict(), "dimensionless": cp.to_dict()})
        explain_nulls(ctl, {"filter_cutoff": "no velocity filter", "amplifier_bandwidth": "ideal amplifier (no lag)"})
        explain_nulls(ctl["dimensionless"], {"cutoff": "no velocity filter"})
        lim = None
        if self.controller_limits is not None:
            lim = to_jsonable(self.controller_limits.to_dict())  # its nulls are explained (JSON pointers)
        return {"controller": ctl, "controller_check": to_jsonable(self.controller_check.to_dict()),
                "controller_limits": lim}  # fmt: skip

    def _record(self) -> dict[str, Any]:
        return to_jsonable(
            {
                "device": self.device.to_dict(),
                "stiffness": self.stiffness,
                "velocity": self.velocity,
                "delay": self.delay,
                "params": self.params.to_dict(),
                "criterion": None if self.criterion is None else self.criterion.to_dict(),
                "limits": None if self.limits is None else self.limits.to_dict(),
                "growth_thresholds": {m: g.to_dict() for m, g in self.thresholds},
                "cycles": {m: g.result.to_dict() for m, g in self.thresholds},
                "simulated_xi_dot": self.simulated_xi_dot,
                "simulated_velocity": self.simulated_velocity,
                "outcome": self.outcome.to_dict(),
                "high_xi_dot": self.high_xi_dot,
                "outcome_high": self.outcome_high.to_dict(),
                "stability_map": self.stability_map.to_dict(),
                "design_answer": None if self.design_answer is None else self.design_answer.to_dict(),
                "speed_chart": None if self.speed_chart is None else self.speed_chart.to_dict(),
                "zwidth": None if self.zwidth is None else self.zwidth.to_dict(),
                "catalogue": self.catalogue,
                "validation": self.validation,
                "samples": self.samples,
                "map_grid": self.map_grid,
                "status": self.status,
                "status_message": self.status.message,
            }
        )


def _explain_filter_nulls(obj: Any) -> None:
    """Explain the null ``cutoff`` of every nested ``controller`` record (its dimensionless groups): no filter."""
    if isinstance(obj, list):
        for x in obj:
            _explain_filter_nulls(x)
    elif isinstance(obj, dict):
        for key, value in obj.items():
            if key == "controller" and isinstance(value, dict) and "cutoff" in value:
                explain_nulls(value, {"cutoff": "no velocity filter"})
            _explain_filter_nulls(value)


def _catalogue_notes(entry: CatalogueEntry | None) -> dict[str, Any] | None:
    if entry is None or not entry.printed_params:
        return None
    return {
        "printed": [[sym, entry.printed[i][1]] for i, sym in enumerate(("μ", "β", "σ")) if i < len(entry.printed)],
        "discrepancies": [str(x) for x in entry.discrepancies],
        "notes": entry.notes or "",
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
    # validation.json is strict JSON (dfa.results.jsonable): a NaN summary number was stored as null; read it back as NaN
    return {k: math.nan if k in _VALIDATION_KEYS and v is None else v for k, v in summary.items()}


def resolve_design_inputs(
    device, stiffness, velocity, delay
) -> tuple[CatalogueEntry | None, Device, float, float, int]:
    """(catalogue entry or None, device, K, |ẋ0|, d) of a design analysis, checked; the defaults filled in."""
    entry = device if isinstance(device, CatalogueEntry) else None
    dev = entry.device if entry is not None else device
    if not isinstance(dev, Device):
        raise DFAValueError(f"device = {device!r} is invalid: it must be a dfa.Device or a catalogue entry")
    k = stiffness if stiffness is not None else (entry.stiffness if entry is not None else None)
    if k is None:
        raise DFAValueError(
            f"stiffness = None is invalid for {dev.name!r}: the catalogue gives no K; pass the stiffness in {dev.units['stiffness']}"
        )
    k = check_positive("stiffness", k, "give the virtual wall stiffness K")
    v = check_speed("velocity", velocity if velocity is not None else (1.0 if dev.rotary else 0.1))
    return entry, dev, k, v, check_delay(delay)


def _simulations(
    p: Params, xi_dot: float, ref: float, v_sim: float | None, samples: int, wp: WallParams
) -> dict[str, Any]:
    """Recorded runs for the figure and full-length runs for the outcomes, at the design speed and above."""
    n_traj = int(min(samples, max(2000, 40 * 2 * math.pi * math.sqrt(p.mu))))
    v_show = v_sim * 1.05 if v_sim is not None else 2.0 * ref
    run = lambda v, n, rec: simulate(  # diverged only far beyond the impact's own travel (eq. 18-19)
        p.mu, p.beta, p.sigma, v, n, record=rec, bound=divergence_bound(0.0, v, p.mu), wall=wp
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


def design_analysis(
    device: Device | CatalogueEntry,
    stiffness: float | None = None,
    velocity: float | None = None,
    *,
    delay: int = 0,
    map_grid: int = 81,
    samples: int = 30_000,
    validation: dict[str, Any] | None = None,
    n_jobs: int = -1,
    progress: bool = False,
    zwidth_grid: int | None = None,
    controller: Wall | None = None,
) -> DesignAnalysis:
    """Compute every number of the design report of ``device`` at stiffness K, impact speed ẋ0 and delay d.

    Parameters
    ----------
    device : Device or CatalogueEntry
        A catalogue entry adds the paper's printed values and notes.
    stiffness : float, optional
        K in N/m (rotary N·m/rad); default the controller's K, else the catalogue K.
    velocity : float, optional
        Impact speed in m/s (rotary rad/s); default 0.1 m/s (1 rad/s rotary); >= 0 (a negative is refused).
    delay : int
        Computational delay d in whole samples (default 0), used by every part of the analysis; with a
        controller it is the controller's (give 0 or the same value).
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
        Points per axis of the report's Z-width (one impact speed, :func:`dfa.analysis.limits.zwidth.z_width`); default None:
        no Z-width for the spring, ``CONTROLLER_ZWIDTH_GRID`` (16) with a controller; 0: none.
    controller : Wall, optional
        The wall controller (physical K, B, d, f_c, f_bw; :class:`dfa.Wall`): every part that accepts
        one is computed with it, the spring-only parts are left out (module docstring). Default None, or a
        controller that is a pure spring: the paper's spring, unchanged.

    Returns
    -------
    DesignAnalysis
        Every number the design report states (frozen, JSON-able with ``to_dict()``).

    Raises
    ------
    DFAValueError, DFATypeError
        Not a Device or catalogue entry, no stiffness, a non-finite speed, a bad delay, a bad validation summary,
        a controller whose K or delay differs from ``stiffness`` or ``delay``, or a filter cutoff above Nyquist.

    See Also
    --------
    dfa.report.design_report : This analysis rendered as Markdown and/or HTML.
    design_answer : The largest stiffness four ways, for the design question alone.

    Examples
    --------
    >>> import dfa
    >>> a = design_analysis(dfa.get_device("impulse"), velocity=0.05, map_grid=3, samples=2000, n_jobs=1)
    >>> a.criterion.passive, round(a.limits.k_max, 1), a.outcome.outcome.value
    (True, 120.8, 'rest')
    """
    from tqdm.auto import tqdm

    ctl, stiffness, delay = resolve_controller(device, controller, stiffness, delay)
    entry, dev, k, v, dl = resolve_design_inputs(device, stiffness, velocity, delay)
    checked = _check_validation(validation)
    zg = check_int("zwidth_grid", zwidth_grid, 0, "give the Z-width's points per axis, or 0 for none") if (
        zwidth_grid is not None) else (CONTROLLER_ZWIDTH_GRID if ctl is not None else 0)  # fmt: skip
    steps = tqdm(total=4, desc=f"analysis {dev.name}", disable=not progress, leave=False)
    p = dev.params(k)
    wall = Wall.of(k, delay=dl) if ctl is None else ctl
    wp = wall.params(dev.period)
    head = _spring_parts(dev, k, v, dl) if ctl is None else _controller_parts(dev, ctl, v)
    steps.update()
    thr = tuple((m, growth_threshold(p, dev, model=m, wall=wp)) for m in MODELS)  # search range follows the problem
    steps.update()
    xi, crit_xi = head.pop("xi_dot"), head.pop("critical_xi_dot")
    ref = crit_xi if crit_xi else max(1.0, xi)
    v_sim = first_unstable_speed(p, 0.2 * ref, 30.0 * ref, samples, preload=False, wall=wp)
    steps.update()
    sims = _simulations(p, xi, ref, v_sim, samples, wp)
    ny = _nyquist(p, thr[1][1], wp)
    steps.update()
    smap = _map_around(p, xi, map_grid, samples, n_jobs, progress, wp)
    steps.close()
    figs: dict[str, Any] = dict(nyquist=ny, stability_map=smap)
    if v > 0 and ctl is None:  # the design answer, first in the report: K_max four ways and the stiffness-speed chart
        cache = RunCache()  # one set of runs for both: no (K, speed, start) simulated twice
        figs["design_answer"] = design_answer(dev, v, wall=wall, assess=True, cache=cache)
        figs["speed_chart"] = stiffness_speed_chart(dev, wall=wall, stiffness=k, velocity=v, cache=cache)
    if v > 0 and zg:
        figs["zwidth"] = _zwidth(dev, v, wall, ctl is not None, zg, n_jobs, progress)
    inputs: dict[str, Any] = dict(
        catalogue=_catalogue_notes(entry), validation=checked, samples=samples, map_grid=map_grid
    )
    return DesignAnalysis(dev, k, v, dl, p, thresholds=thr, simulated_xi_dot=v_sim, **head, **figs, **inputs, **sims)


def resolve_controller(
    device: Any, controller: Wall | None, stiffness: float | None, delay: int
) -> tuple[Wall | None, float | None, int]:
    """(controller or None for the spring, K, d) of a design analysis: the controller carries K and d."""
    if controller is None:
        return None, stiffness, delay
    ctl = check_type("controller", controller, Wall, "build one with dfa.Wall.of(K, B, ...), or None")
    if stiffness is not None and stiffness != ctl.stiffness:
        raise DFAValueError(
            f"stiffness = {_fmt(stiffness)} differs from controller.stiffness = {_fmt(ctl.stiffness)}: the controller "
            "carries K; give stiffness=None or the same value"
        )
    if check_delay(delay) not in (0, ctl.delay):
        raise DFAValueError(
            f"delay = {delay} is invalid with controller.delay = {ctl.delay}: the controller carries the delay; "
            "leave delay at 0 or give the same value"
        )
    dev = device.device if isinstance(device, CatalogueEntry) else device
    if isinstance(dev, Device) and ctl.params(dev.period).is_spring:  # B = 0, no filter, no lag: the spring
        return None, ctl.stiffness, ctl.delay
    return ctl, ctl.stiffness, ctl.delay


def _spring_parts(dev: Device, k: float, v: float, dl: int) -> dict[str, Any]:
    """The spring's criterion (eq. 6), stiffness limits and curve, with the design and critical speeds."""
    crit = device_criterion(dev, Wall.of(k, delay=dl), v)
    lim = stiffness_limits(dev, v, k, delay=dl)
    curve = stiffness_response(dev, stiffness=k, delay=dl)
    return dict(
        criterion=crit, limits=lim, stiffness_curve=curve, xi_dot=crit.xi_dot, critical_xi_dot=crit.critical_xi_dot
    )


def _controller_parts(dev: Device, ctl: Wall, v: float) -> dict[str, Any]:
    """The passivity check and K_max with the controller (no spring-only part), with the design and critical speeds."""
    chk = passivity_check(dev, ctl, v)
    lim = design_answer(dev, v, wall=ctl) if v > 0 else None
    crit_xi = None if chk.criterion is None else chk.criterion.critical_xi_dot
    return dict(
        criterion=None, limits=None, stiffness_curve=None, controller=ctl, controller_check=chk,
        controller_limits=lim, xi_dot=dev.xi_dot(v), critical_xi_dot=crit_xi,
    )  # fmt: skip


def _zwidth(dev: Device, v: float, wall: Wall, widen: bool, grid: int, n_jobs: int, progress: bool) -> ZWidth:
    """The Z-width at the design speed, with the wall's delay, filter and lag; B's axis holds the wall's B."""
    b_top = dev.mass / dev.period  # z_width's default range, widened to show the controller's B
    b_range = (0.0, 1.25 * wall.damping) if widen and wall.damping > b_top else None
    return z_width(dev, v, wall=wall, grid=grid, b_range=b_range, speeds=1, n_jobs=n_jobs, progress=progress)


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


def _nyquist(p: Params, zoh: GrowthThreshold, wp: WallParams) -> NyquistLocusResponse:
    """The Nyquist view of the exact ZOH loop (the model of the growth threshold): the locus reaches every cycle drawn."""
    res = zoh.result
    amps = [c.amplitude for c in res.cycles[:3]] if p.sigma > 0 else None
    if p.sigma > 0 and not amps:
        amps = [1.0]
    m_top = max([50.0] + [2.0 * c.amplitude for c in res.cycles])
    return nyquist_locus_response(
        p, amplitudes=amps, locus_amplitude=np.geomspace(0.05, m_top, 1500), model="zoh", wall=wp
    )
