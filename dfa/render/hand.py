"""Text of a hand holding the device (:mod:`dfa.model.hand`): one label for every output that states the grasp."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..formatting import number
from ..model.elements import Coverage
from ..results.status import GripStatus

if TYPE_CHECKING:
    from ..model.device import Device
    from ..model.hand import Hand
    from ..results.grip import GripNeed, GripSweep

__all__ = [
    "hand_label", "grasp_text", "device_title", "held_name", "moving_symbols", "grip_rows", "grip_text", "at_least",
]  # fmt: skip


def hand_label(hand: Hand, units: dict[str, str]) -> str:
    """``"human operator (paper Table 2): 0.15 kg, 4.8 N·s/m"``: the hand's name and the values it adds.

    Examples
    --------
    >>> from dfa.model.hand import Hand
    >>> from dfa.model.device import device_units
    >>> hand_label(Hand(0.15, 4.8, name="a hand"), device_units())
    'a hand: 0.15 kg, 4.8 N·s/m'
    """
    out = f"{hand.name}: {number(hand.mass, 4)} {units['mass']}, {number(hand.damping, 4)} {units['damping']}"
    return out + (f", {number(hand.stiffness, 4)} {units['stiffness']}" if hand.stiffness else "")


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
    spring = "; its stiffness pulls toward the wall's origin" if hand.stiffness else ""
    return (
        f"grasp: {hand_label(hand, u)}, moving with the device (m = {number(device.mass, 4)} {u['mass']}, "
        f"b = {number(device.damping, 4)} {u['damping']} in all){spring}"
    )


def held_name(device: Device) -> str:
    """The device's name, with the name of the hand that holds it: ``"Delta held by human operator (...)"``."""
    return device.name if device.hand is None else f"{device.name} held by {device.hand.name}"


def moving_symbols(device: Device | None) -> tuple[str, str]:
    """The symbols of the moving mass and damping: ``("m", "b")``, or ``("(m + m_h)", "(b + b_h)")`` when held.

    Examples
    --------
    >>> from dfa.model.device import Device
    >>> from dfa.model.hand import Hand
    >>> moving_symbols(Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000).holding(Hand(0.15, 4.8)))
    ('(m + m_h)', '(b + b_h)')
    """
    return ("m", "b") if device is None or device.hand is None else ("(m + m_h)", "(b + b_h)")


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


#: What each grip answer rests on (the report's third column).
_GRIP_BASIS = {
    "criterion": "a proof: eq. 6 and 11 with b + b_h",
    "linear": "the linear loop without encoder or Coulomb friction (friction can hold a wall below it)",
}
_GRIP_METHOD = {"criterion": "criterion", "linear": "exact linear bound"}


def at_least(x: float, digits: int = 4) -> str:
    """``x`` rounded up to ``digits`` significant digits: a least value as printed still holds.

    Examples
    --------
    >>> at_least(0.2245075), at_least(0.5), at_least(0.0)
    ('0.2246', '0.5', '0')
    """
    text = number(x, digits)
    if not (math.isfinite(x) and x > 0.0) or float(text) >= x:
        return text
    step = 10.0 ** (math.floor(math.log10(x)) - digits + 1)
    v = math.ceil(x / step) * step
    while float(number(v, digits)) < x:  # rounding of v itself
        v += step
    return number(v, digits)


def _need_value(n: GripNeed, unit: str) -> str:
    if n.status is GripStatus.ANY_GRIP:
        return "0: any grip"
    if n.hand_damping is None:
        return "none found" if n.status is GripStatus.UNREACHABLE else "not covered"
    return f"{at_least(n.hand_damping)} {unit}"


def grip_rows(g: GripSweep) -> list[list[str]]:
    """Rows (method, least hand damping, what it rests on) of the grip sweep's table; the simulated scan last."""
    unit = g.device.units["damping"]
    rows = [[_GRIP_METHOD[n.method], _need_value(n, unit), _GRIP_BASIS[n.method]] for n in g.needs]
    if g.scan_damping:
        value = "none found" if g.simulated_damping is None else f"{number(g.simulated_damping, 4)} {unit}"
        rows.append(["exact simulation", value, _scan_text(g)])
    return rows


def _scan_text(g: GripSweep) -> str:
    """What the simulated grip scan ran, in words: ``"an impact at 0.1 m/s from the wall's surface, simulated with no
    grip and with 12 grips from 0.07552 to 154.7 N·s/m (each twice the one before): none diverged or was
    undecided"``."""
    u = g.device.units
    start = "from the wall's surface" if g.wall.covers(Coverage.SURFACE_START) else "after the approach"
    grips = sorted(b for b in g.scan_damping if b > 0)
    scanned = "with no grip" if 0.0 in g.scan_damping else ""
    if grips:
        scanned += " and with " if scanned else "with "
        scanned += (
            f"{len(grips)} grip{'s' if len(grips) > 1 else ''} from {number(grips[0], 4)} to "
            f"{number(grips[-1], 4)} {u['damping']} (each twice the one before)"
            if len(grips) > 1
            else f"one grip of {number(grips[0], 4)} {u['damping']}"
        )
    bad = {o: sum(x == o for x in g.scan_outcome) for o in ("unstable", "undecided")}
    if not any(bad.values()):
        found = "none diverged or was undecided"
    else:
        found = (
            f"{bad['unstable']} diverged and {bad['undecided']} were undecided, "
            "none of them at this grip or a firmer one"
        )
    return f"an impact at {number(g.velocity, 4)} {u['velocity']} {start}, simulated {scanned}: {found}"


def grip_text(g: GripSweep) -> str:
    """The sentence above the grip table: the stiffness, speed and the hand's mass held, in words."""
    u = g.device.units
    mass = (
        "a hand that adds damping but no mass"
        if g.hand_mass == 0.0
        else f"a hand that adds {number(g.hand_mass, 4)} {u['mass']} to the moving mass"
    )
    return (
        f"The least hand damping b_h with which K = {number(g.wall.stiffness, 5)} {u['stiffness']} holds at "
        f"{number(g.velocity, 4)} {u['velocity']}, by each method, for {mass}; a firmer grip damps more, and the "
        "lightest grip is the hardest case. Values are rounded up:"
    )
