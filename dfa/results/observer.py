"""The passivity observer's results (:class:`ObserverSummary`, :class:`ForceError`; computed in
:mod:`dfa.analysis.observer`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ..checks import check_int, check_nonnegative, check_real
from ..errors import DFAValueError
from ..model.wall import WallParams
from .base import Result
from .status import ObserverStatus


@dataclass(frozen=True)
class ObserverSummary(Result):
    """What the passivity observer saw over one recorded run (module docstring).

    Attributes
    ----------
    produced : float
        The energy the wall produced over the run, −E_obs at the last reading, in KΔ² (negative: it absorbed).
    peak_produced : float
        The most it had produced at any reading, max(0, max −E_obs), in KΔ².
    peak_sample : int
        The reading of that peak (0 when it never produced any).
    samples : int
        Readings observed (to the run's last integrated sample).
    controller : bool
        Whether the wall has a passivity controller.
    acting : int
        Readings at which the controller added a force (0 without one).
    peak_controller_force : float
        Its largest force in KΔ (0 without one).
    wall : WallParams
        The wall of the run.
    status : ObserverStatus
        ``active`` when the wall produced energy at some reading, else ``passive``.
    """

    produced: float
    peak_produced: float
    peak_sample: int
    samples: int
    controller: bool
    acting: int
    peak_controller_force: float
    wall: WallParams = field(metadata={"json": lambda w: w.to_dict()})
    status: ObserverStatus = ObserverStatus.PASSIVE

    def __post_init__(self) -> None:
        object.__setattr__(self, "produced", check_real("produced", self.produced))
        object.__setattr__(self, "peak_produced", check_nonnegative("peak_produced", self.peak_produced))
        for name in ("peak_sample", "samples", "acting"):
            object.__setattr__(self, name, check_int(name, getattr(self, name), 0))
        force = check_nonnegative("peak_controller_force", self.peak_controller_force)
        object.__setattr__(self, "peak_controller_force", force)
        object.__setattr__(self, "status", ObserverStatus.coerce(self.status))
        if not isinstance(self.wall, WallParams):
            raise DFAValueError(f"wall = {self.wall!r} is invalid: it must be a WallParams; pass the run's wall")

    @property
    def acting_share(self) -> float:
        """The share of readings at which the controller acted (0 to 1)."""
        return self.acting / self.samples if self.samples else 0.0

    json_properties = ("acting_share",)

    def physical(self, device: Any, stiffness: float) -> dict[str, float]:
        """The energies in J (rotary J too) and the controller's force in N (rotary N·m) for a device at K.

        Parameters
        ----------
        device : Device
            The physical device (its resolution Δ).
        stiffness : float
            K in N/m (rotary N·m/rad).

        Returns
        -------
        dict
            ``produced_j``, ``peak_produced_j`` (E × K Δ²) and ``peak_controller_force_n`` (f × K Δ).
        """
        from ..model import units

        return {
            "produced_j": units.energy(device, stiffness, self.produced),
            "peak_produced_j": units.energy(device, stiffness, self.peak_produced),
            "peak_controller_force_n": units.force(device, stiffness, self.peak_controller_force),
        }


@dataclass(frozen=True)
class ForceError:
    """The force a wall renders against the ideal spring over an impact (units of KΔ).

    Attributes
    ----------
    rms, peak : float
        RMS and largest |φ_A − φ_ideal| over the impact's sample instants, φ_ideal = −(ξ − s)⁺ on a one-sided
        wall, −ξ on a bilateral one (the continuous spring K x); NaN when the run diverged within it.
    samples : int
        Sample instants of the impact: from the first one inside the wall to the first one back outside
        (ξ <= s), or the run's end.
    peak_ideal : float
        The ideal spring's largest force over the impact (what the errors compare with).
    """

    rms: float
    peak: float
    samples: int
    peak_ideal: float

    def to_dict(self) -> dict[str, Any]:
        """The errors as JSON-able data (NaN as None)."""
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in vars(self).items()}
