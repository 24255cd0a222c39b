"""Grip results: the hand stiffness a wall needs to stay safe (:class:`GripNeed`, :class:`GripSweep`; computed in
:mod:`dfa.analysis.limits.grip`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

from ..checks import check_choice, check_type
from ..errors import DFAValueError
from ..model.device import Device
from ..model.wall import Wall
from .base import Result
from .require import Requirement
from .status import GripStatus, SimulationOutcome

#: The methods that answer how firm a grip must be (in the order of the report's table).
GRIP_METHODS = ("criterion", "linear")


@dataclass(frozen=True)
class GripNeed(Result):
    """The least hand damping with which the wall's K holds, by one method.

    Attributes
    ----------
    method : str
        ``"criterion"`` (a proof) or ``"linear"`` (the linear loop's stability: necessary, not sufficient).
    hand_damping : float or None
        b_h in N·s/m (rotary N·m·s/rad): 0 when any grip will do; None when unreachable or not covered.
    status : GripStatus
    requirement : Requirement
        The device-damping requirement it rests on (:func:`dfa.analysis.limits.require.requirements`).
    """

    method: str
    hand_damping: float | None
    status: GripStatus
    requirement: Requirement

    units_of: ClassVar[dict[str, str]] = {"hand_damping": "damping"}

    def __post_init__(self) -> None:
        check_choice("method", self.method, GRIP_METHODS)
        object.__setattr__(self, "status", GripStatus.coerce(self.status))
        has = self.status in (GripStatus.ANY_GRIP, GripStatus.AT_LEAST)
        if (self.hand_damping is not None) != has:
            raise DFAValueError(
                f"hand_damping = {self.hand_damping!r} is invalid with status {self.status.value!r}: a value is "
                "given exactly when the status is 'any_grip' or 'at_least'; build it with grip_sweep"
            )

    def null_reasons(self) -> dict[str, str]:
        """Why ``hand_damping`` may be null (JSON): the status's message."""
        return {"hand_damping": self.status.message}


@dataclass(frozen=True)
class GripSweep(Result):
    """How firm a grip the wall needs at its stiffness and an impact speed (module docstring).

    Attributes
    ----------
    device : Device
        The bare device (no hand).
    wall : Wall
        The wall, with its stiffness K.
    velocity : float
        Impact speed V in m/s (rotary rad/s), >= 0.
    hand_mass : float
        The hand's mass m_h held while its damping varies, kg (rotary kg·m²).
    needs : tuple of GripNeed
        One per method of :data:`GRIP_METHODS`.
    scan_damping : tuple of float
        The simulated hand dampings b_h, N·s/m (empty when not simulated or V = 0).
    scan_outcome : tuple of str
        The simulated outcome of the impact at V from ξ0 = 0 at each (a :class:`SimulationOutcome` value).
    simulated_damping : float or None
        The least scanned b_h from which no firmer scanned grip diverges or is undecided; None when the firmest
        does or nothing was simulated.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    hand_mass: float
    needs: tuple[GripNeed, ...]
    scan_damping: tuple[float, ...] = ()
    scan_outcome: tuple[str, ...] = ()
    simulated_damping: float | None = None

    units_of: ClassVar[dict[str, str]] = {"velocity": "velocity", "hand_mass": "mass", "simulated_damping": "damping"}

    def __post_init__(self) -> None:
        fix = "GripSweep is built by grip_sweep; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        if self.device.hand is not None:
            raise DFAValueError(
                f"device = {self.device.name!r} holds a hand: a grip sweep is of the bare device; {fix}"
            )
        if len(self.scan_damping) != len(self.scan_outcome):
            raise DFAValueError(f"scan_damping and scan_outcome must have one entry per simulated grip; {fix}")
        for o in self.scan_outcome:
            SimulationOutcome.coerce(o)

    def need(self, method: str) -> GripNeed:
        """The answer of one method of :data:`GRIP_METHODS`."""
        for n in self.needs:
            if n.method == method:
                return n
        raise DFAValueError(f"method = {method!r} is not answered here: give one of {GRIP_METHODS}")

    def null_reasons(self) -> dict[str, str]:
        """Why ``simulated_damping`` may be null (JSON)."""
        if self.simulated_damping is not None:
            return {}
        why = "not simulated" if not self.scan_damping else "the firmest scanned grip diverges or is undecided"
        return {"simulated_damping": why}
