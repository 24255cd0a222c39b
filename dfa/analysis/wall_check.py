"""The passivity check of a device with a wall controller, as `dfa check` and the design report state it (issue 15).

Without an amplifier lag: the criterion of eq. 6 extended to the damper, filter and delay
(:func:`dfa.analysis.wall_criterion.device_controller_criterion`) and the Colgate–Schenkel minimum damping of the
controller's H(z) (:func:`dfa.analysis.colgate_schenkel.colgate_schenkel_damping`). With a lag neither covers the loop: the check
is "not covered", with the reason (:data:`LAG_WHY`). One implementation for the command and the report.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.wall import Wall
>>> dev = get_device("Delta").device
>>> chk = controller_check(dev, Wall.of(14500.0, damping=5.0), 0.1)
>>> chk.covered, chk.criterion.region, chk.passive
(True, 'd', False)
>>> controller_check(dev, Wall.of(14500.0, amplifier_bandwidth=500.0), 0.1).passive is None
True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..checks import check_real, check_speed, check_type
from ..errors import DFAValueError
from ..model.device import Device
from ..model.wall import Wall
from ..results.jsonable import explain_nulls, to_jsonable
from .colgate_schenkel import ColgateSchenkelDamping, colgate_schenkel_damping
from .wall_criterion import ControllerCriterionResult, device_controller_criterion

__all__ = ["LAG_WHY", "NOT_COVERED", "ControllerCheck", "controller_check"]

#: What the check says where no passivity criterion covers the controller (amplifier lag).
NOT_COVERED = "not covered by the criterion; see `dfa map`/`dfa zwidth`"
#: Why: neither the extended criterion nor Colgate–Schenkel covers an amplifier lag.
LAG_WHY = (
    "no sound passivity criterion is proven with an amplifier lag (the force varies within a sample), "
    "and the Colgate–Schenkel condition assumes the hold drives the device directly"
)


@dataclass(frozen=True)
class ControllerCheck:
    """The passivity check of ``device`` with ``controller`` at an impact speed (module docstring).

    Attributes
    ----------
    device : Device
    controller : Wall
    velocity : float
        Impact speed, m/s (rotary: rad/s), >= 0.
    criterion : ControllerCriterionResult or None
        The extended criterion (eq. 6); None with an amplifier lag (not covered).
    colgate_schenkel : ColgateSchenkelDamping or None
        The minimum physical damping b for passivity of the linear loop; None with an amplifier lag.
    """

    device: Device
    controller: Wall
    velocity: float
    criterion: ControllerCriterionResult | None
    colgate_schenkel: ColgateSchenkelDamping | None

    def __post_init__(self) -> None:
        fix = "ControllerCheck is built by dfa.analysis.wall_check.controller_check; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("controller", self.controller, Wall, fix)
        check_real("velocity", self.velocity, fix)
        lag = self.controller.amplifier_bandwidth is not None
        parts = (self.criterion, self.colgate_schenkel)
        if lag != all(x is None for x in parts) or (not lag and any(x is None for x in parts)):
            raise DFAValueError(
                "criterion and colgate_schenkel must both be None with an amplifier lag and both set without; " + fix
            )

    @property
    def covered(self) -> bool:
        """False with an amplifier lag: no passivity criterion covers the loop."""
        return self.criterion is not None

    @property
    def passive(self) -> bool | None:
        """The extended criterion's verdict (proven passive, or no guarantee); None where not covered."""
        return None if self.criterion is None else bool(self.criterion.passive)

    def as_dict(self) -> dict[str, object]:
        """The JSON of `dfa check` with this controller (without its ``"controller"`` object).

        Returns
        -------
        dict
            Covered: the criterion's record with ``colgate_schenkel`` (minimum damping, the device's b, ``met``).
            Not covered: ``passive`` null with the reason, ``status`` ``"not_covered"``, speed and device name.
        """
        if self.criterion is None or self.colgate_schenkel is None:
            rec: dict[str, Any] = {
                "passive": None,
                "status": "not_covered",
                "status_message": f"{NOT_COVERED}: {LAG_WHY}",
            }
            explain_nulls(rec, {"passive": NOT_COVERED})
            return {**rec, "velocity": self.velocity, "device": self.device.name}
        d = self.criterion.as_dict()
        cs = self.colgate_schenkel
        csd = to_jsonable(cs.as_dict())
        csd.update(device_damping=self.device.damping, met=bool(self.device.damping > cs.damping_bound))
        csd.pop("controller")  # the "controller" object of the output states it once
        explain_nulls(csd["dimensionless"]["params"], {"cutoff": "no velocity filter"})
        d["colgate_schenkel"] = csd
        return d


def controller_check(
    device: Device, controller: Wall, velocity: float, *, position: float = 0.0, quantized: bool = True
) -> ControllerCheck:
    """Check ``device`` with ``controller`` at an impact speed: extended criterion and Colgate–Schenkel.

    Parameters
    ----------
    device : Device
        The physical device.
    controller : Wall
        The wall controller (K, B, d, f_c, f_bw in physical units).
    velocity : float
        Impact speed in m/s (rotary: rad/s), >= 0 (a negative is refused, not flipped).
    position : float, optional
        Initial position in m (rotary: rad), default 0.
    quantized : bool, optional
        With the encoder (default, eq. 6) or without (eq. 7).

    Returns
    -------
    ControllerCheck
        Both conditions, or neither (not covered) with an amplifier lag.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad device, controller, speed or position.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    ctl = check_type("controller", controller, Wall, "build one with dfa.Wall.of(K, ...)")
    v = check_speed("velocity", velocity)
    if ctl.amplifier_bandwidth is not None:
        ctl.params(dev.period)  # refuses a filter cutoff above the Nyquist frequency
        return ControllerCheck(dev, ctl, v, None, None)
    r = device_controller_criterion(dev, ctl, v, position=position, quantized=quantized)
    return ControllerCheck(dev, ctl, v, r, colgate_schenkel_damping(ctl, dev.period))
