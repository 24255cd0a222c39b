"""Text of a hand holding the device (:mod:`dfa.model.hand`): one label for every output that states the grasp."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..formatting import number

if TYPE_CHECKING:
    from ..analysis.limits.grip import GripSweep
    from ..model.device import Device
    from ..model.hand import Hand

__all__ = ["hand_label", "grasp_text", "device_title", "grip_rows", "grip_text"]


def hand_label(hand: Hand, units: dict[str, str]) -> str:
    """``"human operator (paper Table 2): 0.15 kg, 4.8 N·s/m"``: the hand's name and the values it adds.

    Examples
    --------
    >>> from dfa.model.hand import Hand
    >>> from dfa.model.device import device_units
    >>> hand_label(Hand(0.15, 4.8, name="a hand"), device_units())
    'a hand: 0.15 kg, 4.8 N·s/m'
    """
    return f"{hand.name}: {number(hand.mass, 4)} {units['mass']}, {number(hand.damping, 4)} {units['damping']}"


def grasp_text(device: Device) -> str:
    """The grasp an analysis assumed, in one sentence (the paper's worst case when nobody holds the device).

    Examples
    --------
    >>> from dfa.model.device import Device
    >>> from dfa.model.hand import Hand
    >>> dev = Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000)
    >>> grasp_text(dev)
    "grasp: none (nobody holds the device: the paper's worst case)"
    >>> grasp_text(dev.holding(Hand(0.15, 4.8)))
    'grasp: hand: 0.15 kg, 4.8 N·s/m, moving with the device (m = 0.4 kg, b = 4.81 N·s/m in all)'
    """
    hand, u = device.hand, device.units
    if hand is None:
        return "grasp: none (nobody holds the device: the paper's worst case)"
    return (
        f"grasp: {hand_label(hand, u)}, moving with the device (m = {number(device.mass, 4)} {u['mass']}, "
        f"b = {number(device.damping, 4)} {u['damping']} in all)"
    )


def device_title(device: Device) -> str:
    """The device's name, with the hand that holds it: ``"Delta, held by a hand: 0.15 kg, 4.8 N·s/m"``.

    Examples
    --------
    >>> from dfa.model.device import Device
    >>> from dfa.model.hand import Hand
    >>> dev = Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000, name="Delta")
    >>> device_title(dev), device_title(dev.holding(Hand(0.15, 4.8, name="a hand")))
    ('Delta', 'Delta, held by a hand: 0.15 kg, 4.8 N·s/m')
    """
    hand = device.hand
    return device.name if hand is None else f"{device.name}, held by {hand_label(hand, device.units)}"


_GRIP_METHOD = {
    "criterion": "criterion (eq. 6 with b + b_h; a proof)",
    "linear": "exact linear bound (necessary, not sufficient)",
}


def grip_rows(g: GripSweep) -> list[list[str]]:
    """Rows (method, least hand damping, meaning) of the grip sweep's table; the simulated scan last."""
    u = g.device.units
    rows = []
    for n in g.needs:
        value = "–" if n.hand_damping is None else f"{number(n.hand_damping, 4)} {u['damping']}"
        rows.append([_GRIP_METHOD[n.method], value, n.status.message])
    if g.scan_damping:
        value = "–" if g.simulated_damping is None else f"{number(g.simulated_damping, 4)} {u['damping']}"
        diverged = sum(o == "unstable" for o in g.scan_outcome)
        why = (
            f"{len(g.scan_damping)} grips simulated (0 and K T·2^i); {diverged} diverged; none diverges from this "
            "grip up"
            if g.simulated_damping is not None
            else "the firmest scanned grip diverges"
        )
        rows.append(["exact simulation, impact from ξ0 = 0", value, why])
    return rows


def grip_text(g: GripSweep) -> str:
    """The sentence above the grip table: the stiffness, speed and the hand's mass held."""
    u = g.device.units
    return (
        f"Least hand damping b_h with which K = {number(g.wall.stiffness, 5)} {u['stiffness']} holds at "
        f"{number(g.velocity, 4)} {u['velocity']}, for a hand of mass m_h = {number(g.hand_mass, 4)} {u['mass']} "
        "(a firmer grip damps more; the lightest grip is the hardest case). By each method, K holds for grips at "
        "least this firm:"
    )
