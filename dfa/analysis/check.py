"""The passivity check of a device with a wall at an impact speed: what ``dfa check`` and the design report state.

Two conditions, each where it applies:

- the passivity criterion (eq. 6, extended to a delay, a damper and a velocity filter,
  :mod:`dfa.analysis.criterion`): a proof for the quantized device with Coulomb friction, for impacts up to
  the speed; an element no sound criterion covers (an amplifier lag) leaves it "not covered", with the
  element's reason;
- the Colgate–Schenkel condition on the device's viscous friction for the wall's H(z)
  (:func:`dfa.analysis.colgate_schenkel.colgate_schenkel_beta`): necessary and sufficient for the passivity
  of the linear sampled loop (no encoder, no Coulomb friction); not covered with an amplifier lag.

One implementation for the spring and every wall.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.wall import Wall
>>> dev = get_device("Delta").device
>>> chk = passivity_check(dev, Wall.of(14500.0, damping=5.0), 0.1)
>>> chk.status.value, chk.criterion.region, chk.passive
('no_guarantee', 'd', False)
>>> passivity_check(dev, Wall.of(14500.0, amplifier_bandwidth=500.0), 0.1).passive is None
True
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..checks import check_real, check_speed, check_type
from ..errors import DFAValueError
from ..model.device import Device
from ..model.loop import LOOP_FIX, Loop, loop_first
from ..model.wall import Wall
from ..plausibility import warn_if_from_outside
from ..results.base import Result
from ..results.status import CheckStatus
from .colgate_schenkel import ColgateSchenkel, colgate_schenkel_beta
from .criterion import CriterionResult, device_criterion, start_state

__all__ = ["PassivityCheck", "passivity_check"]


@dataclass(frozen=True)
class PassivityCheck(Result):
    """The passivity check of ``device`` with ``wall`` at an impact speed (module docstring).

    Attributes
    ----------
    device : Device
    wall : Wall
    velocity : float
        Impact speed, m/s (rotary: rad/s), >= 0.
    criterion : CriterionResult or None
        The criterion (eq. 6 extended); None where no sound criterion covers the wall (``reasons`` says why).
    colgate_schenkel : ColgateSchenkel or None
        The Colgate–Schenkel condition, dimensionless (β_min); None where it does not cover the wall.
    reasons : dict of str to str
        Why ``criterion`` or ``colgate_schenkel`` is None, by that name.
    status : CheckStatus
        ``passive`` (proven by the criterion), ``no_guarantee`` or ``not_covered``.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    criterion: CriterionResult | None
    colgate_schenkel: ColgateSchenkel | None
    reasons: dict[str, str]
    status: CheckStatus

    json_properties: ClassVar[tuple[str, ...]] = (
        "passive", "start_state", "colgate_schenkel_damping", "colgate_schenkel_bound", "colgate_schenkel_met",
    )  # fmt: skip
    units_of: ClassVar[dict[str, str]] = {
        "velocity": "velocity", "colgate_schenkel_damping": "damping", "colgate_schenkel_bound": "damping",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "PassivityCheck is built by dfa.analysis.check.passivity_check; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        check_real("velocity", self.velocity, fix)
        object.__setattr__(self, "status", CheckStatus.coerce(self.status))
        for name in ("criterion", "colgate_schenkel"):
            if (getattr(self, name) is None) != (name in self.reasons):
                raise DFAValueError(f"{name} is None exactly when reasons[{name!r}] says why; {fix}")

    @property
    def covered(self) -> bool:
        """False where no sound criterion covers the wall (an amplifier lag)."""
        return self.criterion is not None

    @property
    def passive(self) -> bool | None:
        """The criterion's verdict (proven passive, or no guarantee); None where not covered."""
        return None if self.criterion is None else bool(self.criterion.passive)

    @property
    def start_state(self) -> str:
        """The start state ``passive`` is proven for (:func:`dfa.analysis.criterion.start_state` of the wall)."""
        return start_state(self.wall)

    @property
    def colgate_schenkel_damping(self) -> float | None:
        """The least viscous friction b = K T β_min the condition needs, N·s/m (rotary: N·m·s/rad)."""
        cs = self.colgate_schenkel
        return None if cs is None else self.wall.stiffness * self.device.period * cs.beta_min

    @property
    def colgate_schenkel_bound(self) -> float | None:
        """Any b above this meets the condition (certified, rounding included), N·s/m (rotary: N·m·s/rad)."""
        cs = self.colgate_schenkel
        return None if cs is None else self.wall.stiffness * self.device.period * cs.beta_bound

    @property
    def colgate_schenkel_met(self) -> bool | None:
        """Whether the device's b meets the condition for sure (above the certified bound); None: not covered."""
        bound = self.colgate_schenkel_bound
        return None if bound is None else bool(self.device.damping > bound)

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            The reasons for the criterion and the Colgate–Schenkel condition where they do not apply.
        """
        out = dict(self.reasons)
        if "criterion" in out:
            out["passive"] = f"not covered by the criterion: {out['criterion']}"
        if "colgate_schenkel" in out:
            for k in ("colgate_schenkel_damping", "colgate_schenkel_bound", "colgate_schenkel_met"):
                out[k] = out["colgate_schenkel"]
        return out


@loop_first("device, wall")
def passivity_check(loop: Loop, velocity: float, *, position: float = 0.0, quantized: bool = True) -> PassivityCheck:
    """Check the loop's device with its wall at an impact speed: the criterion and Colgate–Schenkel, where they apply.

    Parameters
    ----------
    loop : Loop
        The device and the wall (stiffness K in N/m, rotary N·m/rad, and its elements), ``Loop(device, wall)``
        (the wall may be K alone, the paper's spring). The former call ``passivity_check(device, wall, velocity)``
        still works.
    velocity : float
        Impact speed in m/s (rotary: rad/s), >= 0 (a negative is refused, not flipped).
    position : float, optional
        Initial position in m (rotary: rad), default 0.
    quantized : bool, optional
        With the encoder (default, eq. 6) or without (eq. 7).

    Returns
    -------
    PassivityCheck
        Both conditions, each None with its reason where it does not cover the wall.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad device, wall, speed or position.

    See Also
    --------
    device_criterion : The criterion alone.
    colgate_schenkel_damping : The Colgate–Schenkel condition alone, in physical units.
    """
    dev, w = check_type("loop", loop, Loop, LOOP_FIX).physical("passivity_check")
    v = check_speed("velocity", velocity, dev.units["velocity"])
    warn_if_from_outside("velocity", v, rotary=dev.rotary)
    _, p = loop.groups("passivity_check")  # Loop refused a filter cutoff above the Nyquist frequency
    reasons: dict[str, Any] = {}
    crit: CriterionResult | None = None
    why = p.not_covered()
    if why is None:
        crit = device_criterion(loop, v, position=position, quantized=quantized)
    else:
        reasons["criterion"] = why
    cs: ColgateSchenkel | None = None
    why_cs = p.colgate_schenkel_reason()
    if why_cs is None:
        cs = colgate_schenkel_beta(p)
    else:
        reasons["colgate_schenkel"] = why_cs
    status = (
        CheckStatus.NOT_COVERED if crit is None else (CheckStatus.PASSIVE if crit.passive else CheckStatus.NO_GUARANTEE)
    )
    return PassivityCheck(dev, w, v, crit, cs, reasons, status)
