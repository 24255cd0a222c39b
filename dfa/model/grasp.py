"""A hand on the device: its mass and damping join the device, its stiffness joins the loop (issue 28 §2).

A hand holding the handle (paper Table 2; :class:`~dfa.model.hand.Hand`) moves with it: its mass and damping add
to the device's (:meth:`dfa.Device.holding`), and its stiffness k_h, a spring to a fixed reference at the wall's
origin, acts on the device in continuous time beside the wall's held force (:class:`~dfa.model.elements.HandSpring`,
simulated exactly by :mod:`dfa.core.oscillator`). :func:`hold` gives both halves at once; every analysis then takes
the pair as it takes any device and wall.

Examples
--------
>>> from dfa.model.device import Device
>>> from dfa.model.hand import Hand
>>> from dfa.model.wall import Wall
>>> dev, wall = hold(Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000), Wall.of(2000.0), Hand(0.554, 6.45, 135.0))
>>> round(dev.mass, 6), round(dev.damping, 6), wall.hand_stiffness
(0.804, 6.46, 135.0)
"""

from __future__ import annotations

from ..checks import check_type
from ..errors import DFAValueError
from .device import Device
from .elements import HandSpring
from .hand import Hand
from .wall import Wall

__all__ = ["hold"]


def hold(device: Device, wall: Wall, hand: Hand) -> tuple[Device, Wall]:
    """The device held by ``hand`` and the wall with the hand's stiffness (use the two together).

    Parameters
    ----------
    device : Device
        The bare device (not already held).
    wall : Wall
        The wall, without a hand stiffness of its own.
    hand : Hand
        The hand: mass m_h (kg), damping b_h (N·s/m) and stiffness k_h (N/m) to a fixed reference at the wall's
        origin (:func:`dfa.get_hand` for a preset).

    Returns
    -------
    tuple of (Device, Wall)
        The device with m + m_h and b + b_h (:meth:`Device.holding`; ``hand`` recorded), and ``wall`` with a
        :class:`~dfa.model.elements.HandSpring` of k_h (unchanged for k_h = 0).

    Raises
    ------
    DFATypeError
        If an argument has the wrong type.
    DFAValueError
        If the device already holds a hand, the wall already has a hand stiffness, or the wall has an amplifier
        lag and the hand a stiffness (not covered yet).

    See Also
    --------
    Device.holding : Mass and damping alone.
    HandSpring : The hand's stiffness as a wall element.
    """
    dev = check_type("device", device, Device, "give a dfa.Device")
    w = check_type("wall", wall, Wall, "give a dfa.Wall")
    h = check_type("hand", hand, Hand, "give a dfa.Hand (dfa.get_hand('hapticmaster') for a preset)")
    if w.hand_stiffness:
        raise DFAValueError(
            f"wall has a hand stiffness of {w.hand_stiffness:g} already: hold() adds the hand's own; give the wall "
            "without a HandSpring"
        )
    held = dev.held_by(h)
    if not h.stiffness:
        return held, w
    return held, Wall(w.stiffness, (*w.elements, HandSpring(h.stiffness)))
