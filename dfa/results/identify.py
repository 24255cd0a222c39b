"""Identification results: the estimates fitted to a logged impact (:class:`Identification`, :class:`Estimate`,
:class:`FitQuality`, :class:`Timing`) with why an estimate is unresolved, the identified device as a catalogue row
(:func:`identified_entry`), and a logged cycle (:class:`LoggedCycle`); computed in :mod:`dfa.analysis.identify`
and :mod:`dfa.analysis.logged_cycle`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..checks import check_type
from ..formatting import round_at, uncertainty_place
from ..jsonable import explain_nulls
from ..model.device import Device
from ..model.units import hertz, position, speed
from .base import Result, figure_function
from .status import IdentifyStatus, IdentifyWarning, LoggedCycleStatus, StatusEnum

if TYPE_CHECKING:
    from ..model.catalogue import CatalogueEntry

#: Coulomb friction below this share of the largest logged force is not resolved by the log (a diverging
#: impact with forces of kN against a friction of 1 N fits any friction within a few per cent).
FRICTION_SHARE = 1e-4

#: Fewest samples in motion (the reading changes) for a log to count as exciting the dynamics.
FEW_MOVING = 300

#: Largest ratio of the residuals' mean square to the white variance of noisy readings (the position noise's square
#: plus quantization's 1/12, :mod:`dfa.analysis.identify`) of a fit that reproduces the log: white noise gives 1, force noise
#: on top of it more (0.6 tick and 21 % force noise on the free-motion logs of tests/test_identify_position_noise.py:
#: 69; 0.5 tick and 25 %, about 90). Beyond it the residuals are not noise on the readings but a misfit whose jumps
#: read as white noise (diverging logs with force noise read 330 to 4600 ticks of "position noise" at ratios of 420
#: to 1700): the fit is poor, whatever force noise would explain.
POSITION_MISFIT = 200.0


class Undetermined(StatusEnum):
    """Why an estimate has no interval (:attr:`Estimate.undetermined`): a short code, ``message`` its definition,
    the JSON's null reason of the interval's ends (:mod:`dfa.render.identify` has the few words of a table cell)."""

    NO_REVERSAL = (
        "no_reversal",
        "no reversal in the log: Coulomb friction and the force offset act the same way, only c − f₀ is seen",
    )
    FRICTION_UNRESOLVED = (
        "friction_unresolved",
        f"unresolved: below {FRICTION_SHARE:g} of the largest logged force, the log cannot resolve it, whatever its "
        "fit says",
    )
    POOR_FIT = (
        "poor_fit",
        "poor fit: the model does not reproduce the log, and noise on the force column does not explain it (dynamics "
        "the model lacks, or a force column that is not what drove the device), so the fit's spread says nothing "
        "about the values",
    )
    SCATTER = (
        "scatter",
        "the fits of the log and its replicates differ by orders of magnitude: the log does not bound it",
    )
    CONSTANT_FORCE = (
        "constant_force",
        "the force column is constant: the log shows only the balance b v + c = f + f₀ where the speed settles, "
        "which fits many devices; log a force that changes",
    )
    LITTLE_MOTION = (
        "little_motion",
        f"the log holds fewer than {FEW_MOVING} samples in motion: too few to bound the estimates (a fit of a device "
        "at rest can be far off and look exact); log a longer run with motion",
    )


@dataclass(frozen=True)
class Estimate:
    """One identified value, its 95 % interval [low, high] and stderr, the interval's half-width / 1.96 (SI units).

    The interval comes from the fit's Jacobian and a bootstrap over the encoder's unknown origin (module
    docstring, step 4): it covers the readings' quantization, the fit's convergence and the force noise the
    residuals show (:attr:`Identification.force_noise`), not dynamics the model lacks. ``undetermined`` says why there is no interval (an :class:`Undetermined`
    code, None with an interval): the log cannot
    separate this value from another, or holds too little motion to bound it.
    """

    value: float
    stderr: float | None
    low: float | None
    high: float | None
    undetermined: Undetermined | None = None

    def __post_init__(self) -> None:
        if self.undetermined is not None:
            object.__setattr__(self, "undetermined", Undetermined.coerce(self.undetermined, "undetermined"))

    @property
    def place(self) -> int | None:
        """Exponent k of the last meaningful decimal place 10^k (:func:`dfa.formatting.uncertainty_place` of the
        interval's wider half); None without an interval. Digits below it move with the last bits of the
        arithmetic (the fit's stopping point), from one machine to another."""
        if self.low is None or self.high is None:
            return None
        return uncertainty_place(max(self.high - self.value, self.value - self.low))

    def to_dict(self) -> dict[str, Any]:
        """The value, its standard error and interval (null with the reason when undetermined)."""
        out: dict[str, Any] = {"value": self.value, "stderr": self.stderr, "low": self.low, "high": self.high}
        why = "" if self.undetermined is None else self.undetermined.message
        return explain_nulls(out, dict.fromkeys(("stderr", "low", "high"), why))


@dataclass(frozen=True)
class FitQuality:
    """How well the identified device reproduces the log.

    Attributes
    ----------
    rms_ticks : float
        RMS distance of the predicted position from the middle of each logged tick (about 0.29 for a perfect
        model: the position within the tick).
    max_tick_error : int
        Largest |predicted tick − logged tick|.
    within_one_tick : float
        Share of samples whose predicted tick is within one of the logged one.
    """

    rms_ticks: float
    max_tick_error: int
    within_one_tick: float

    def to_dict(self) -> dict[str, float | int]:
        """The three numbers."""
        return {"rms_ticks": self.rms_ticks, "max_tick_error": self.max_tick_error,
                "within_one_tick": self.within_one_tick}  # fmt: skip


#: Largest departure of a logged period from T, relative to T, that the fixed-period analyses absorb: every
#: analysis takes each sample to last exactly T, and a limit such as eq. 11 moves about as much as T does.
JITTER_RTOL = 0.01


@dataclass(frozen=True)
class Timing:
    """The log's time column: the period the fit takes, how the logged periods depart from it, and the samples
    the log lacks or repeats (:func:`dfa.analysis.identify.log_timing`).

    Attributes
    ----------
    period : float
        T, s: the slope of the times against the sample index (dropped samples counted), or the given period.
    jitter_s : float
        Standard deviation of the logged periods (the steps of one sample), s.
    jitter_max_s : float
        Largest |step − T| over the steps of one sample, s.
    period_max : float
        Longest step of one sample, s.
    dropped : int
        Samples missing from the log: a step of k periods (k >= 2) lacks k − 1; the fit holds the force over them
        and leaves their readings out.
    gaps : int
        Steps that lack samples.
    repeated : int
        Rows whose time repeats the row before (a step under half a period): dropped from the fit.
    """

    period: float
    jitter_s: float
    jitter_max_s: float
    period_max: float
    dropped: int
    gaps: int
    repeated: int

    @property
    def exceeds(self) -> bool:
        """Whether a logged period departs from T by more than :data:`JITTER_RTOL` of it (the fixed-period
        analyses' assumption fails)."""
        return self.jitter_max_s > JITTER_RTOL * self.period

    def to_dict(self) -> dict[str, Any]:
        """The numbers, in s, and whether the jitter exceeds what the analyses assume."""
        return {"period_s": self.period, "jitter_s": self.jitter_s, "jitter_max_s": self.jitter_max_s,
                "period_max_s": self.period_max, "dropped": self.dropped, "gaps": self.gaps,
                "repeated": self.repeated, "jitter_exceeds": self.exceeds, "jitter_rtol": JITTER_RTOL}  # fmt: skip


@dataclass(frozen=True)
class PeriodEffect:
    """How the proven stiffness limit (eq. 11, the cautious device) and the recommended stiffness move from T to the
    longest logged period.

    Attributes
    ----------
    period, period_max : float
        T and the longest logged period, s.
    velocity : float
        Impact speed, m/s (rad/s).
    k_criterion, k_criterion_max : float
        The criterion's K_max at T and at the longest period, N/m (rotary N·m/rad).
    k_recommended, k_recommended_max : float or None
        The recommended stiffness (:func:`dfa.analysis.limits.recommend.recommend_stiffness`'s rule) of the design
        answer at T and of the one at the longest period, N/m; None when no answer was given, or no K is recommended.
    rule, rule_max : str or None
        The rule each rests on (``proven``, ``simulated``, ``simulated_range``, ``none``); None without an answer.
    grid : int or None
        Points of the stiffness grid of the answer at the longest period (the same speeds as the one at T, a coarser
        grid; bisection refines either limit to the same 2·10⁻³); None without an answer.
    """

    period: float
    period_max: float
    velocity: float
    k_criterion: float
    k_criterion_max: float
    k_recommended: float | None = None
    k_recommended_max: float | None = None
    rule: str | None = None
    rule_max: str | None = None
    grid: int | None = None

    def to_dict(self) -> dict[str, Any]:
        """The numbers (SI), the rules, and why a recommendation is null."""
        out = {"period_s": self.period, "period_max_s": self.period_max, "velocity": self.velocity,
               "k_criterion": self.k_criterion, "k_criterion_at_period_max": self.k_criterion_max,
               "k_recommended": self.k_recommended, "k_recommended_at_period_max": self.k_recommended_max,
               "rule": self.rule, "rule_at_period_max": self.rule_max, "grid_at_period_max": self.grid}  # fmt: skip
        none = "no design answer given" if self.rule is None else "no stiffness is recommended (rule none)"
        slow = "no design answer given" if self.rule_max is None else "no stiffness is recommended (rule none)"
        return explain_nulls(out, {"k_recommended": none, "rule": none, "grid_at_period_max": none,
                                   "k_recommended_at_period_max": slow, "rule_at_period_max": slow})  # fmt: skip


@dataclass(frozen=True)
class Identification(Result):
    """A device identified from its log (:func:`identify`).

    Attributes
    ----------
    device : Device
        The identified device (m, b, c, Δ, T).
    source : str
        The log's name.
    samples : int
        Samples in the log.
    mass, damping, coulomb, force_offset : Estimate
        m (kg), b (N·s/m), c (N) and the force offset f₀ (N; the force applied is f + f₀); rotary kg·m², N·m·s/rad,
        N·m.
    resolution_given, period_given : bool
        Whether Δ and T were given (else estimated from the log).
    segment : int
        Samples per segment of the multiple-shooting fit (the last one may be longer).
    bootstrap : int
        Replicate logs whose fits set the intervals (0: the linearized intervals alone; module docstring, step 4).
    bootstrap_requested : int
        Replicates asked for: more than ``bootstrap`` when some did not move enough to be fitted, or when the
        intervals were withheld (little motion, a poor fit) and none was run.
    fit : FitQuality
        The fit's own prediction: each segment from its fitted start.
    free_run : FitQuality
        The identified model run once over the whole log from the fitted start (errors accumulate).
    timing : Timing
        The time column: T, jitter, dropped and repeated samples.
    force_noise : float
        Standard deviation of the noise on the force column that explains the residuals beyond the encoder's
        quantization, N (rotary N·m); 0 when the residuals are quantization's alone.
    force_noise_relative : float
        The same relative to the logged force's standard deviation.
    position_noise : float
        Standard deviation of the white noise on the readings beyond their quantization, m (rotary rad): noise of
        more than :data:`dfa.analysis.identify.POSITION_NOISE_MIN` tick (an analog sensor, a noisy encoder); 0 when
        the readings are quantization's alone. :attr:`position_noise_ticks` in ticks.
    confounded : tuple of (str, str, float)
        Pairs of estimates the log does not tell apart (their correlation beyond 0.95 in the fit's covariance), with
        the correlation (:mod:`dfa.render.identify` says what motion would).
    warnings : tuple of IdentifyWarning
        What the log does not excite, or a poor fit.
    velocity_peak : float
        Largest speed of the fitted run, m/s (rad/s).
    segment_states : ndarray
        One row per segment of the fit: its first sample, fitted position there (ticks from the lowest reading)
        and velocity (ticks per sample).
    predicted, logged : ndarray
        The free run's position and the logged tick at each sample, in ticks from the lowest reading (the figure).
    status : IdentifyStatus
    """

    device: Device = field(metadata={"json": lambda d: d.to_dict()})
    source: str
    samples: int
    mass: Estimate
    damping: Estimate
    coulomb: Estimate
    force_offset: Estimate
    resolution_given: bool
    period_given: bool
    segment: int
    bootstrap: int
    bootstrap_requested: int
    fit: FitQuality
    free_run: FitQuality
    timing: Timing
    force_noise: float
    force_noise_relative: float
    position_noise: float
    confounded: tuple[tuple[str, str, float], ...]
    warnings: tuple[IdentifyWarning, ...]
    velocity_peak: float
    segment_states: np.ndarray = field(repr=False, metadata={"json": None})
    predicted: np.ndarray = field(repr=False, metadata={"json": None})
    logged: np.ndarray = field(repr=False, metadata={"json": None})
    status: IdentifyStatus = IdentifyStatus.OK

    json_properties: ClassVar[tuple[str, ...]] = ("start_velocity", "position_noise_ticks")
    units_of: ClassVar[dict[str, str]] = {"velocity_peak": "velocity", "start_velocity": "velocity",
                                          "force_noise": "force", "position_noise": "resolution"}  # fmt: skip

    def __post_init__(self) -> None:
        fix = "Identification is built by dfa.identify; call that instead"
        check_type("device", self.device, Device, fix)
        for name in ("mass", "damping", "coulomb", "force_offset"):
            check_type(name, getattr(self, name), Estimate, fix)
        object.__setattr__(self, "warnings", tuple(IdentifyWarning.coerce(w) for w in self.warnings))
        object.__setattr__(self, "status", IdentifyStatus.coerce(self.status))
        for name in ("segment_states", "predicted", "logged"):
            a = np.array(getattr(self, name), dtype=float)
            a.setflags(write=False)
            object.__setattr__(self, name, a)

    @property
    def start_velocity(self) -> float:
        """The fitted velocity at the log's first sample, m/s (rad/s): the free run's start (the first segment's)."""
        return float(speed(self.device, self.segment_states[0, 2]))

    @property
    def position_noise_ticks(self) -> float:
        """:attr:`position_noise` in ticks of the resolution."""
        return self.position_noise / self.device.resolution

    def cautious(self) -> Device:
        """The identified device with b and c at the lower ends of their 95 % intervals.

        Where the log does not bound them they are 0. A stiffness limit for the real device can rest on this
        device, as every limit of :mod:`dfa` rises with damping and friction. Each value keeps its meaningful
        digits only (:attr:`Estimate.place`; b and c rounded down, m to the nearest, to 4 significant digits
        without an interval), so that the limits computed from it and the flags that repeat them are the same on
        every machine.

        Returns
        -------
        Device
            The identified m, Δ and T with b and c lowered, named ``"<name> (cautious)"``.
        """
        b, c = (round_at(e.low, e.place, "down") if e.low is not None and e.place is not None else 0.0
                for e in (self.damping, self.coulomb))  # fmt: skip
        place = self.mass.place
        m = round_at(self.mass.value, place) if place is not None else 0.0
        m = m if m > 0.0 else float(f"{self.mass.value:.4g}")  # no interval, or one wider than the value
        d = self.device
        return Device(m, b, c, d.resolution, d.period, name=f"{d.name} (cautious)", rotary=d.rotary)

    def plot(self, ax: Any = None) -> Any:
        """The logged ticks against the identified model's free run, residual below.

        Parameters
        ----------
        ax : pair of matplotlib Axes, optional
            Top and bottom axes; a new figure when None.

        Returns
        -------
        pair of matplotlib Axes
            The trajectory axes and the residual axes (:func:`dfa.render.figures.plot_identification`).
        """
        plot_identification = figure_function("plot_identification")

        return plot_identification(self, ax)


@dataclass(frozen=True)
class LoggedOscillation:
    """A sustained oscillation measured on readings (:func:`measure_oscillation`).

    Attributes
    ----------
    amplitude : float
        Half the peak-to-peak of the readings over the tail, ticks (uncertain by ±½ tick).
    frequency : float
        Radians per sample.
    periods : int
        Full periods in the tail.
    start : int
        First sample of the tail.
    """

    amplitude: float
    frequency: float
    periods: int
    start: int

    def to_dict(self) -> dict[str, float | int]:
        """The four numbers."""
        return {"amplitude": self.amplitude, "frequency": self.frequency, "periods": self.periods, "start": self.start}


@dataclass(frozen=True)
class LoggedCycle(Result):
    """The log's oscillation next to the predicted limit cycles (:func:`compare_logged_cycle`).

    Attributes
    ----------
    device : Device
        The identified device.
    stiffness : float
        K of the wall the log ran against, N/m (rotary N·m/rad).
    origin, origin_spread : float
        The wall's origin in ticks above the lowest reading, and how far the samples' own estimates of it lie
        from it, ticks (:func:`wall_origin`; more than a tick: the force column is not this wall).
    logged : LoggedOscillation or None
        The log's sustained oscillation (None: none).
    replays : tuple of (float, float, str, float, float)
        Each replay's damping b (N·s/m) and friction c (N), outcome (``dfa.analysis.simulation``), amplitude
        (ticks) and frequency (rad per sample; NaN when not measured); empty when no oscillation was logged.
    matching : int
        Replays that end in the logged cycle.
    describing : tuple of (float, float)
        The describing function's stable limit cycles (amplitude in ticks, frequency in rad per sample).
    status : LoggedCycleStatus
    """

    device: Device = field(metadata={"json": lambda d: d.to_dict()})
    stiffness: float
    origin: float
    origin_spread: float
    logged: LoggedOscillation | None
    replays: tuple[tuple[float, float, str, float, float], ...]
    matching: int
    describing: tuple[tuple[float, float], ...]
    status: LoggedCycleStatus

    units_of: ClassVar[dict[str, str]] = {"stiffness": "stiffness"}

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, "LoggedCycle is built by compare_logged_cycle; call that")
        object.__setattr__(self, "status", LoggedCycleStatus.coerce(self.status))

    def to_dict(self) -> dict[str, Any]:
        """Every field, the oscillations as their numbers (null when there is none)."""
        out = super().to_dict()
        lg = self.logged
        out["logged"] = None if lg is None else lg.to_dict() | {
            "amplitude_si": position(self.device, lg.amplitude), "frequency_hz": hertz(self.device, lg.frequency)}  # fmt: skip
        out["replays"] = [{"damping": b, "coulomb": c, "outcome": o, "amplitude": a,
                           "frequency": None if math.isnan(w) else w} for b, c, o, a, w in self.replays]  # fmt: skip
        out["describing"] = [{"amplitude": a, "frequency": w} for a, w in self.describing]
        reasons = {
            k: v for k, v in out.get("null_reasons", {}).items() if not k.startswith(("/replays", "/describing"))
        }
        reasons |= {f"/replays/{i}/frequency": "not measured: the replay did not settle in a cycle"
                    for i, r in enumerate(self.replays) if math.isnan(r[4])}  # fmt: skip
        out["null_reasons"] = reasons
        out["units_of_cycles"] = "amplitude in ticks (amplitude_si in m or rad), frequency in rad per sample"
        return out


def identified_entry(r: Identification, *, source: str, notes: str, stiffness: float | None = None) -> CatalogueEntry:
    """The identified device as a catalogue row (:class:`dfa.model.catalogue.CatalogueEntry`), for a device file.

    m, b and c are the identified values to their meaningful digits (:attr:`Estimate.place`; 4 significant digits
    without an interval), so that the file is the same on every machine; Δ and T are the log's (12 digits).

    Parameters
    ----------
    r : Identification
        The identification.
    source, notes : str
        The row's source (the log's name and date) and notes (the intervals; :mod:`dfa.render.identify` words them).
    stiffness : float, optional
        The wall's K the row gives (N/m; rotary N·m/rad); default none.

    Returns
    -------
    CatalogueEntry
        A complete row of kind "haptic device" named after the identified device.
    """
    from ..model.catalogue import CatalogueEntry

    check_type("r", r, Identification, "identify a log with dfa.identify(...)")

    def digits(e: Estimate) -> float:
        return round_at(e.value, e.place) if e.place is not None else float(f"{e.value:.4g}")

    m = digits(r.mass)
    m = m if m > 0.0 else float(f"{r.mass.value:.4g}")
    b, c = (max(0.0, digits(e)) for e in (r.damping, r.coulomb))
    d = r.device  # Δ and T to 12 digits: the last bits of a slope or a lattice's step are no part of them
    return CatalogueEntry(d.name[:100], "haptic device", source, notes, mass=m, damping=b, coulomb=c,
                          resolution=float(f"{d.resolution:.12g}"), period=float(f"{d.period:.12g}"),
                          stiffness=stiffness, rotary=d.rotary)  # fmt: skip
