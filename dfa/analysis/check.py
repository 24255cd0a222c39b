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

from typing import Any

from ..checks import check_speed, check_type
from ..model.loop import LOOP_FIX, Loop, loop_first
from ..plausibility import warn_if_from_outside
from ..results.criterion import PassivityCheck as PassivityCheck
from ..results.status import CheckStatus
from .colgate_schenkel import ColgateSchenkel, colgate_schenkel_beta
from .criterion import CriterionResult, device_criterion

__all__ = ["PassivityCheck", "passivity_check"]


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
