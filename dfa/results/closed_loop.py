"""Results of a log taken with the wall on (issue 45 b): the force column checked against the wall's law
(:class:`WallForceCheck`), the logged contact measured (:class:`ContactMeasure`) and set beside the prediction
for the identified device (:class:`ClosedLoopEvidence`); computed in :mod:`dfa.analysis.closed_loop`."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..checks import check_type
from ..jsonable import explain_nulls
from ..model.device import Device
from ..model.units import hertz, position
from ..model.wall import Wall
from .base import Result
from .status import ClosedLoopStatus, ContactOutcome, SimulationOutcome, WallCheckStatus

__all__ = ["WallForceCheck", "ContactMeasure", "ClosedLoopEvidence", "WALL_SHARE"]

#: Share of the checked samples whose logged force must lie within half a force step KΔ of the wall's law for the
#: force column to count as the wall's (a log of that wall: all of them; a K off by 10 % misses most in contact).
WALL_SHARE = 0.95


@dataclass(frozen=True)
class WallForceCheck(Result):
    """The log's force column against the given wall's force of the logged readings (:func:`check_wall_force`).

    Attributes
    ----------
    device : Device
        The device whose Δ and T the readings are taken on (the identified one).
    wall : Wall
        The wall given (K, B, delay, one-sided).
    samples : int
        Samples checked (the first d are left out: their force depends on readings before the log).
    force_step : float
        K Δ, N (rotary N·m): the wall's force per tick.
    max_mismatch, rms_mismatch : float
        Largest and root-mean-square |logged − law| over the checked samples, N.
    within : float
        Share of the checked samples within ½ K Δ of the law.
    ratio : float
        Median of logged/law over the samples where the law's force is at least 2 K Δ (NaN: none): about K_log/K
        when the log's wall is a spring of another stiffness.
    status : WallCheckStatus
        ``consistent`` when ``within`` >= :data:`WALL_SHARE`.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    samples: int
    force_step: float
    max_mismatch: float
    rms_mismatch: float
    within: float
    ratio: float
    status: WallCheckStatus

    units_of: ClassVar[dict[str, str]] = {"force_step": "force", "max_mismatch": "force", "rms_mismatch": "force"}

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, "WallForceCheck is built by check_wall_force; call that")
        object.__setattr__(self, "status", WallCheckStatus.coerce(self.status))

    def null_reasons(self) -> dict[str, str]:
        """Why the ratio may be null."""
        return {"ratio": "no sample where the wall's law pushes 2 K Δ or more"}


@dataclass(frozen=True)
class ContactMeasure:
    """The contact in a run's readings, classified by the simulator's own rules (:func:`measure_contact`).

    Attributes
    ----------
    samples : int
        Samples measured.
    impacts : int
        Contact episodes: runs of readings inside the wall (reading >= 0 tick, the wall occupying x >= 0).
    first_contact : int
        First sample inside (-1: none).
    contact_samples : int
        Samples inside.
    penetration : float
        Deepest reading inside, ticks (0 without contact).
    outcome : SimulationOutcome
        :func:`dfa.core.kernel.classify` applied to the readings' envelope and tail (the last quarter): rest
        (readings constant over the tail), chatter (a cycle below one tick), oscillating, unstable (a growing
        envelope), undecided (still changing), left (one-sided: the tail is all outside).
    contact : ContactOutcome or None
        A one-sided wall's contact (:func:`dfa.analysis.simulation.contact_codes`): rests, bounces (contact lost and
        regained over the tail), in_contact, left ...; None for the bilateral spring.
    amplitude : float
        Half the tail's peak-to-peak, ticks (±½ tick); 0 at rest, NaN when no cycle was measured.
    frequency : float
        Radians per sample over the tail's upward crossings of its centre (NaN: none measured).
    """

    samples: int
    impacts: int
    first_contact: int
    contact_samples: int
    penetration: float
    outcome: SimulationOutcome
    contact: ContactOutcome | None
    amplitude: float
    frequency: float

    def to_dict(self, device: Device | None = None) -> dict[str, Any]:
        """The numbers, the outcome's code; with ``device`` the amplitude in m (rad) and the frequency in Hz."""
        out: dict[str, Any] = {
            "samples": self.samples, "impacts": self.impacts, "first_contact": self.first_contact,
            "contact_samples": self.contact_samples, "penetration": self.penetration,
            "outcome": self.outcome.value, "contact": None if self.contact is None else self.contact.value,
            "amplitude": _finite(self.amplitude), "frequency": _finite(self.frequency),
        }  # fmt: skip
        if device is not None:
            out["penetration_si"] = position(device, self.penetration)
            out["amplitude_si"] = _finite(position(device, self.amplitude))
            out["frequency_hz"] = _finite(hertz(device, self.frequency))
        why = "no cycle measured: " + (
            "at rest" if self.outcome is SimulationOutcome.REST else "the tail did not settle"
        )
        reasons = {k: why for k in ("amplitude", "frequency", "amplitude_si", "frequency_hz")}
        return explain_nulls(out, reasons | {"contact": "a bilateral wall: no contact outcome"})


def _finite(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


@dataclass(frozen=True)
class ClosedLoopEvidence(Result):
    """A log taken with the wall on, next to what the exact simulation predicts for the identified device and that
    wall (:func:`dfa.analysis.closed_loop.closed_loop_evidence`).

    Attributes
    ----------
    device : Device
        The identified device.
    wall : Wall
        The wall the log was taken with.
    check : WallForceCheck
        The force column against the wall's law.
    logged : ContactMeasure
        The log's contact.
    predicted : ContactMeasure or None
        The same measure of the identified device's exact run with this wall from the fitted state at ``start``,
        over the log's remaining samples (None without contact).
    eventual : SimulationOutcome or None
        The simulator's own outcome of that run over its default length (50 000 samples or more).
    eventual_contact : ContactOutcome or None
        Its contact, one-sided walls only.
    start : int
        Sample the prediction starts from: the first of the fit's segment holding the first contact (-1: none).
    impact_speed : float
        Fitted speed at ``start``, m/s (rad/s); NaN without contact.
    status : ClosedLoopStatus
        ``agrees`` (the identified values' prediction is the logged contact), ``within_intervals`` (it is not, a
        replay's is), ``differs`` (no replay's is) or ``no_contact``.
    replays : tuple of (float, float, str, bool)
        The same run with b (N·s/m) and c (N) at the ends of their 95 % intervals and at their values: b, c, the
        outcome over the log's samples, whether the contact is the logged one (empty without contact).
    matching : int
        Replays whose contact is the logged one.
    """

    device: Device = field(metadata={"json": lambda d: d.to_dict()})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    check: WallForceCheck = field(metadata={"json": lambda c: c.to_dict()})
    logged: ContactMeasure = field(metadata={"json": None})
    predicted: ContactMeasure | None = field(metadata={"json": None})
    eventual: SimulationOutcome | None
    eventual_contact: ContactOutcome | None
    start: int
    impact_speed: float
    status: ClosedLoopStatus
    replays: tuple[tuple[float, float, str, bool], ...] = field(
        default=(),
        metadata={
            "json": lambda rs: [{"damping": b, "coulomb": c, "outcome": o, "matches": m} for b, c, o, m in rs]
        },  # fmt: skip
    )
    matching: int = 0

    units_of: ClassVar[dict[str, str]] = {"impact_speed": "velocity"}

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, "ClosedLoopEvidence is built by closed_loop_evidence; call that")
        check_type("wall", self.wall, Wall, "ClosedLoopEvidence is built by closed_loop_evidence; call that")
        object.__setattr__(self, "status", ClosedLoopStatus.coerce(self.status))

    def null_reasons(self) -> dict[str, str]:
        """Why the prediction may be null."""
        why = "no contact in the log: nothing to predict"
        return {"eventual": why, "impact_speed": why} | (
            {"eventual_contact": "a bilateral wall: no contact outcome"} if self.eventual is not None else {}
        )

    def to_dict(self) -> dict[str, Any]:
        """Every field; the contact measures with their amplitudes in m (rad) and frequencies in Hz."""
        out = super().to_dict()
        out["logged"] = self.logged.to_dict(self.device)
        out["predicted"] = None if self.predicted is None else self.predicted.to_dict(self.device)
        explain_nulls(out, {"predicted": "no contact in the log: nothing to predict"})
        out["units_of_contact"] = (
            "penetration and amplitude in ticks (_si: m or rad), frequency in rad per sample (_hz: Hz), samples from "
            "the log's first"
        )
        return out
