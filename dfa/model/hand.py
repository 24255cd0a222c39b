"""A hand holding the device: its mass and damping move with the device's (paper Table 2, section 5).

The paper analyses the device with nobody touching it, its worst case, and lists a human operator beside the
devices of its Table 2: about 0.150 kg and 4.8 N·s/m, "to be added to the device's own when grasping"; a firm
grip stabilises the wall and a light one is the hardest case. A hand that holds the handle rigidly moves with
it, so (paper eq. 3, F_H the hand's force)::

    F_H = −m_h ẍ − b_h ẋ − k_h (x − x_h)
    (m + m_h) ẍ + (b + b_h) ẋ + c sgn(ẋ) + k_h (x − x_h) = F_A

With k_h = 0 this is the bare device with m + m_h and b + b_h, exactly, and every analysis of :mod:`dfa` holds
for it as for any device (:meth:`dfa.Device.holding`): the criterion's β = (b + b_h)/(K T) (eq. 6), the exact
linear bound, the describing function, the simulator. A hand stiffness k_h > 0 (to a fixed reference at the
wall's origin) makes the device a damped oscillator between samples: it joins the loop as a wall element,
:class:`~dfa.model.elements.HandSpring`, and :func:`dfa.hold` gives the held device and that wall together
(:meth:`Device.holding` alone refuses it rather than leave it out).

Examples
--------
>>> h = get_hand("paper")
>>> h.mass, h.damping, h.stiffness
(0.15, 4.8, 0.0)
>>> Hand(0.1, 2.0).to_dict()["name"]
'hand'
"""

from __future__ import annotations

from dataclasses import dataclass

from ..checks import check_nonnegative, format_value
from ..errors import DFATypeError, DFAValueError

__all__ = ["Hand", "HAND_PRESETS", "get_hand", "HandNotCovered"]


class HandNotCovered(DFAValueError):
    """A hand stiffness k_h > 0 given where only mass and damping can be added (:meth:`dfa.Device.holding`)."""


@dataclass(frozen=True)
class Hand:
    """A hand holding the device: mass, damping and stiffness to a fixed reference (SI; rotary: kg·m², N·m·s/rad).

    Parameters
    ----------
    mass : float
        Hand mass m_h in kg (rotary: inertia in kg·m²), >= 0; moves with the device's.
    damping : float, optional
        Hand damping b_h in N·s/m (rotary: N·m·s/rad), >= 0 (default 0); adds to the device's.
    stiffness : float, optional
        Hand stiffness k_h to a fixed reference at the wall's origin in N/m (rotary: N·m/rad), >= 0 (default 0);
        :func:`dfa.hold` adds it to the wall (:meth:`dfa.Device.holding` alone refuses it).
    name : str, optional
        A label for outputs (default ``"hand"``).
    source : str, optional
        Where the values come from (a citation), or empty.
    """

    mass: float
    damping: float = 0.0
    stiffness: float = 0.0
    name: str = "hand"
    source: str = ""

    def __post_init__(self) -> None:
        units = {"mass": "kg (rotary: kg·m²)", "damping": "N·s/m (rotary: N·m·s/rad)", "stiffness": "N/m"}
        for key, unit in units.items():
            fix = f"give the hand {key} in {unit}, 0 for none"
            object.__setattr__(self, key, check_nonnegative(f"hand_{key}", getattr(self, key), fix))
        for key in ("name", "source"):
            if not isinstance(getattr(self, key), str):
                value = getattr(self, key)
                raise DFATypeError(
                    f"hand {key} = {format_value(value)} has type {type(value).__name__}: it must be text"
                )

    @property
    def is_empty(self) -> bool:
        """True when the hand adds nothing (zero mass, damping and stiffness)."""
        return self.mass == 0.0 and self.damping == 0.0 and self.stiffness == 0.0

    def check_covered(self) -> None:
        """Refuse a hand stiffness where only mass and damping can be added (:class:`HandNotCovered`, naming the fix)."""
        if self.stiffness > 0.0:
            raise HandNotCovered(
                f"hand_stiffness = {format_value(self.stiffness)} cannot be added to the device alone: a hand "
                "stiffness is a spring to a fixed reference acting beside the wall; use dfa.hold(device, wall, hand), "
                "which adds the hand's mass and damping to the device and its stiffness to the wall (dfa.HandSpring)"
            )

    def to_dict(self) -> dict[str, object]:
        """Name, source and the three values (SI units).

        Returns
        -------
        dict
            ``name``, ``source``, ``mass``, ``damping``, ``stiffness``.
        """
        return {
            "name": self.name,
            "source": self.source,
            "mass": self.mass,
            "damping": self.damping,
            "stiffness": self.stiffness,
        }


#: Hand presets by name (linear devices, SI units).
HAND_PRESETS: dict[str, Hand] = {
    "none": Hand(0.0, 0.0, 0.0, name="no hand", source="the paper's worst case: nobody touches the device"),
    "paper": Hand(
        0.150,
        4.8,
        0.0,
        name="human operator (paper Table 2)",
        source="Diolaiti et al., ICRA 2005, Table 2: 0.150 kg, about 4.8 N·s/m, added to the device's own; "
        "its stiffness column (about 600 N/m) is not applied",
    ),
    "light": Hand(
        0.150,
        0.0,
        0.0,
        name="light touch (a bound: the paper's hand mass, no damping)",
        source="Diolaiti et al., ICRA 2005, Table 2's hand mass (0.150 kg) with none of its damping: the light end "
        "of a grasp as a bound, not a measured grasp (no published light-touch values were found); the report's "
        "grip sweep spans the grasps between it and a firm one",
    ),
    "hapticmaster": Hand(
        0.554,
        6.45,
        135.0,
        name="arm on a HapticMaster (one trial)",
        source="'Haptic perception of force magnitude and its relation to postural arm dynamics in 3D', "
        "Sci. Rep. 5, 18004 (2015), Fig. 3: one trial's mass-damper-spring fit, M = 0.554 kg, B = 6.45 N·s/m, "
        "K = 135 N/m",
    ),
}


def get_hand(name: str) -> Hand:
    """A hand preset of :data:`HAND_PRESETS` by name (case-insensitive).

    Parameters
    ----------
    name : str
        ``"none"``, ``"paper"``, ``"light"`` or ``"hapticmaster"``.

    Returns
    -------
    Hand
        The preset (mass, damping and stiffness in SI units, its name and source).

    Raises
    ------
    DFAValueError
        For an unknown name (the message lists the presets).

    See Also
    --------
    Device.holding : The device held by a hand.

    Examples
    --------
    >>> get_hand("None").mass
    0.0
    """
    key = name.strip().lower() if isinstance(name, str) else None
    if key not in HAND_PRESETS:
        raise DFAValueError(
            f"hand = {format_value(name)} is not a hand preset: choose one of {', '.join(HAND_PRESETS)}, "
            "or give the hand's mass and damping"
        )
    return HAND_PRESETS[key]
