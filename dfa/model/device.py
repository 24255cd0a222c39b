"""Physical device model and its dimensionless form (paper Table 1).

A one-degree-of-freedom haptic device renders a virtual spring of stiffness
``K`` (paper section 2)::

    m x'' + b x' + c sgn(x') = F_H + F_A,
    F_A(t) = -K Δ floor(x(t_h)/Δ) - K Δ/2   for t in [t_h, t_h + T)

With τ = t/T, ξ = x/Δ and φ = F/(KΔ) this becomes (paper eq. 4-5)::

    μ ξ'' + β ξ' + σ sgn(ξ') = φ_H + φ_A,
    μ = m/(K T²),  β = b/(K T),  σ = c/(K Δ).

All analyses in :mod:`dfa` work on :class:`Params` (μ, β, σ); physical units
live only in :class:`Device`, the catalogue, the command line and report labels.

Examples
--------
>>> dev = Device(mass=0.032, damping=0.02, coulomb=0.024,
...              resolution=314e-6, period=2e-3, name="Impulse Engine")
>>> p = dev.params(stiffness=80.0)
>>> round(p.mu, 3), round(p.beta, 4), round(p.sigma, 4)
(100.0, 0.125, 0.9554)
>>> round(dev.stiffness_for_beta(0.5), 6)   # K at which β = 1/2 (Colgate-Schenkel)
20.0
"""

from __future__ import annotations

import dataclasses
import enum
import math
import sys
from dataclasses import dataclass, field

import numpy as np

from ..checks import (
    check_beta,
    check_mu,
    check_nonnegative,
    check_positive,
    check_real,
    check_sigma,
    check_type,
    format_value,
)
from ..errors import DFATypeError, DFAValueError
from ..plausibility import warn_if_from_outside
from .hand import Hand

__all__ = [
    "Params",
    "Device",
    "DeviceField",
    "DEVICE_FIELDS",
    "Rule",
    "STIFFNESS",
    "dimensionless_params",
    "device_units",
]


@dataclass(frozen=True)
class Params:
    """Dimensionless device parameters (paper Table 1).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(K T²), > 0.
    beta : float
        Dimensionless viscous damping β = b/(K T), >= 0.
    sigma : float
        Dimensionless Coulomb friction σ = c/(K Δ), >= 0.
    """

    mu: float
    beta: float
    sigma: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "mu", check_mu(self.mu))
        object.__setattr__(self, "beta", check_beta(self.beta))
        object.__setattr__(self, "sigma", check_sigma(self.sigma))

    def to_dict(self) -> dict[str, float]:
        """Return the three groups as a dictionary.

        Returns
        -------
        dict
            ``{"mu": μ, "beta": β, "sigma": σ}`` (plain floats, JSON-able).
        """
        return {"mu": self.mu, "beta": self.beta, "sigma": self.sigma}


class Rule(enum.Enum):
    """The rule a device field's value obeys; its value is the rule as messages and the template write it."""

    POSITIVE = "> 0"
    NONNEGATIVE = ">= 0"

    def check(self, name: str, value: object, fix: str | None = None) -> float:
        """``value`` as a float if it obeys the rule (:func:`dfa.checks.check_positive` or
        :func:`~dfa.checks.check_nonnegative`), else their error naming ``name`` and ``fix``."""
        check = check_positive if self is Rule.POSITIVE else check_nonnegative
        return check(name, value, fix)


@dataclass(frozen=True)
class DeviceField:
    """One physical value of a device: the row of :data:`DEVICE_FIELDS` that every place holding it reads.

    :class:`Device` (its attribute and validation), the catalogue (:class:`~dfa.model.catalogue.CatalogueEntry`,
    its JSON), device files (their keys and rules), the template (:func:`~dfa.model.catalogue.device_template`),
    the command line (``--mass`` ... ``--period``) and :func:`device_units` all read the table.

    Attributes
    ----------
    name : str
        The key everywhere: the :class:`Device` attribute, the device file's and the JSON's key; the flag is
        ``--`` and the name with ``-`` for ``_``.
    what : str
        What it is, in words (``"moving mass"``).
    symbol : str
        Its symbol (``"m"``); ``rotary_symbol`` for a rotary device (``"J"``), default the same.
    unit, rotary_unit : str
        Its SI unit for a linear device (``"kg"``) and for a rotary one (``"kg·m²"``).
    rule : Rule
        The rule the value obeys (> 0 or >= 0).
    required : bool
        True when every device has it; False for an optional value whose absence (None) means ``absent``.
    absent : str
        What None means for an optional value (``"unlimited"``); for a required one, empty.
    hint : str
        The fix that :class:`Device`'s message gives; default ``give the <what> <symbol> in <units>``.
    rotary_what : str
        What a rotary device calls it, when not the same (``"inertia"``).
    note : str
        Said after the rule in the template's comment (``": 30 µm is 30e-6"``).
    plausibility : str or None
        The quantity of :data:`dfa.plausibility.RANGES` its value is checked against (a warning, never an
        error); None for none.
    """

    name: str
    what: str
    symbol: str
    unit: str
    rotary_unit: str
    rule: Rule
    required: bool = True
    absent: str = ""
    hint: str = ""
    rotary_what: str = ""
    rotary_symbol: str = ""
    note: str = ""
    plausibility: str | None = None

    @property
    def flag(self) -> str:
        """The command-line flag (``--mass``, ``--max-force``)."""
        return "--" + self.name.replace("_", "-")

    @property
    def described(self) -> str:
        """What it is and its symbol (``"moving mass m"``)."""
        return f"{self.what} {self.symbol}"

    @property
    def units(self) -> str:
        """Its units for either device (``"kg (rotary: inertia in kg·m²)"``, ``"s"``)."""
        if self.rotary_unit == self.unit:
            return self.unit
        what = f"{self.rotary_what} in " if self.rotary_what else ""
        return f"{self.unit} (rotary: {what}{self.rotary_unit})"

    @property
    def fix(self) -> str:
        """The fix a refused value's message gives (:attr:`hint`, or ``give the <what> <symbol> in <units>``)."""
        return self.hint or f"give the {self.described} in {self.units}"

    @property
    def comment(self) -> str:
        """The template's comment above the key: what, units, rule, note (and ``optional``)."""
        units = self.unit
        if self.rotary_unit != self.unit:
            what = f"{self.rotary_what} {self.rotary_symbol or self.symbol} in " if self.rotary_what else ""
            units += f" (rotary: {what}{self.rotary_unit})"
        tail = "" if self.required else f"; optional{f', absent: {self.absent}' if self.absent else ''}"
        return f"{self.described} in {units}, {self.rule.value}{self.note}{tail}"

    def unit_of(self, rotary: bool) -> str:
        """Its unit for a rotary (``rotary``) or linear device."""
        return self.rotary_unit if rotary else self.unit

    def check(self, value: object, name: str | None = None, fix: str | None = None) -> float:
        """``value`` as a float by :attr:`rule`; the message names ``name`` (default :attr:`name`) and ``fix``
        (default :attr:`fix`)."""
        return self.rule.check(self.name if name is None else name, value, self.fix if fix is None else fix)


#: The physical values of a :class:`Device`, in its order (paper Table 1): one row each (:class:`DeviceField`).
DEVICE_FIELDS: tuple[DeviceField, ...] = (
    DeviceField("mass", "moving mass", "m", "kg", "kg·m²", Rule.POSITIVE, rotary_what="inertia", rotary_symbol="J",
                hint="give the moving mass in kg (rotary: kg·m²)", plausibility="mass"),
    DeviceField("damping", "viscous friction", "b", "N·s/m", "N·m·s/rad", Rule.NONNEGATIVE,
                hint="give the viscous friction b in N·s/m (0 for none)"),
    DeviceField("coulomb", "Coulomb friction", "c", "N", "N·m", Rule.NONNEGATIVE,
                hint="give the Coulomb friction c in N (0 for none)"),
    DeviceField("resolution", "encoder resolution", "Δ", "m", "rad", Rule.POSITIVE,
                hint="give the encoder resolution Δ in m (rotary: rad)", note=": 30 µm is 30e-6",
                plausibility="resolution"),
    DeviceField("period", "sample period", "T", "s", "s", Rule.POSITIVE, hint="give the sample period T in s (1 kHz: 0.001)",
                note=": a 1 kHz servo loop is 0.001", plausibility="period"),
    DeviceField("max_force", "actuator force limit", "F_max", "N", "N·m", Rule.POSITIVE, required=False,
                absent="unlimited", hint="give the actuator's force limit F_max in N (rotary: N·m), or none",
                note=": the wall's command is clipped to ±F_max"),
    DeviceField("travel", "travel from the centre to either end stop", "x_t", "m", "rad", Rule.POSITIVE,
                required=False, absent="unlimited", hint="give the travel from the centre to either end stop in m "
                "(rotary: rad), or leave it out for an unlimited one", note=" (a run ends at the stop: end_stop)"),
)  # fmt: skip

#: The virtual wall's stiffness K that a catalogue row and a device file may give beside the device's fields.
STIFFNESS = DeviceField("stiffness", "virtual wall stiffness", "K", "N/m", "N·m/rad", Rule.POSITIVE, required=False,
                        plausibility="stiffness")  # fmt: skip

#: The quantities that are not device fields, each with its (linear, rotary) unit.
_OTHER_UNITS = {"velocity": ("m/s", "rad/s"), "position": ("m", "rad"), "force": ("N", "N·m")}
_LINEAR_UNITS = {f.name: f.unit for f in (*DEVICE_FIELDS, STIFFNESS)} | {k: u for k, (u, _r) in _OTHER_UNITS.items()}
_ROTARY_UNITS = {f.name: f.rotary_unit for f in (*DEVICE_FIELDS, STIFFNESS)} | {
    k: r for k, (_u, r) in _OTHER_UNITS.items()
}


def device_units(rotary: bool = False) -> dict[str, str]:
    """Unit strings of each physical quantity: SI for a linear device; rad, N·m and kg·m² for a rotary one.

    :attr:`Device.units` of a device; for results that hold a device's values but not the device.

    Parameters
    ----------
    rotary : bool, optional
        True for a rotary joint (positions are angles, forces are torques).

    Returns
    -------
    dict of str to str
        Quantity (``"stiffness"``, ``"velocity"``, ``"damping"``, ...) to its unit.

    Examples
    --------
    >>> device_units()["stiffness"], device_units(rotary=True)["stiffness"]
    ('N/m', 'N·m/rad')
    """
    return dict(_ROTARY_UNITS if rotary else _LINEAR_UNITS)


@dataclass(frozen=True)
class Device:
    """A physical haptic device (SI units; a rotary device uses rad, N·m, kg·m²).

    Parameters
    ----------
    mass : float
        Moving mass m in kg (rotary: inertia in kg·m²), > 0.
    damping : float
        Viscous friction b in N·s/m (rotary: N·m·s/rad), >= 0.
    coulomb : float
        Dynamic Coulomb friction c in N (rotary: N·m), >= 0.
    resolution : float
        Encoder resolution Δ in m (rotary: rad), > 0.
    period : float
        Sample period T in s, > 0.
    name : str, optional
        A label used in reports.
    rotary : bool, optional
        True when positions are angles and forces are torques (only changes units).
    max_force : float or None, optional
        The actuator's force limit F_max in N (rotary: N·m), > 0; None (default): unlimited. The analyses of a
        :class:`~dfa.model.loop.Loop` clip the wall's command to ±F_max (:class:`~dfa.model.elements.ForceLimit`).
    travel : float or None, optional
        Keyword only: the travel from the centre (x = 0, where the wall's spring is zero) to either end stop, in m
        (rotary: rad), > 0; None (default): unlimited. A :class:`~dfa.model.loop.Loop` of the device adds it to the
        wall (:class:`~dfa.model.elements.Travel`): a run that leaves it ends there (outcome ``end_stop``).

    Attributes
    ----------
    hand : Hand or None
        The hand holding the device, set only by :meth:`holding` (then ``mass`` and ``damping`` include the
        hand's); None for the bare device. It is provenance for outputs: every analysis reads ``mass`` and
        ``damping``.

    Warns
    -----
    ImplausibleInputWarning
        For a mass, resolution or period no haptic device has (:mod:`dfa.plausibility`: a resolution above
        1 mm is most likely µm written as m), when the device is built outside dfa (a script, a notebook).

    Notes
    -----
    The physical values are the rows of :data:`DEVICE_FIELDS`, each checked by its rule (an optional one, absent,
    is None); a new value is a row there and an attribute here, in the same order (an optional one after
    ``rotary``, keyword only in practice: ``name`` stays the sixth positional argument).
    """

    mass: float
    damping: float
    coulomb: float
    resolution: float
    period: float
    name: str = "custom device"
    rotary: bool = False
    max_force: float | None = None
    hand: Hand | None = field(default=None, init=False)
    travel: float | None = field(default=None, kw_only=True)

    def __post_init__(self) -> None:
        for f in DEVICE_FIELDS:  # each value by its rule; an optional one may be absent (None)
            value = getattr(self, f.name)
            if value is not None or f.required:
                object.__setattr__(self, f.name, f.check(value))
        if not isinstance(self.name, str):
            raise DFATypeError(
                f"name = {format_value(self.name)} has type {type(self.name).__name__}: it must be text; give the device name"
            )
        if not isinstance(self.rotary, (bool, np.bool_)):
            raise DFATypeError(
                f"rotary = {format_value(self.rotary)} has type {type(self.rotary).__name__}: it must be True or False; pass rotary=True for a rotary joint"
            )
        object.__setattr__(self, "rotary", bool(self.rotary))
        for f in DEVICE_FIELDS:  # a value no haptic device has: warn, naming the slip
            if f.plausibility is not None and getattr(self, f.name) is not None:
                warn_if_from_outside(f.plausibility, getattr(self, f.name), rotary=self.rotary)

    # ------------------------------------------------------------------ units
    @property
    def units(self) -> dict[str, str]:
        """Unit strings of each physical quantity for this device (:func:`device_units`)."""
        return device_units(self.rotary)

    # ------------------------------------------------------------------ a hand
    def holding(self, hand: Hand) -> Device:
        """The device held by ``hand``: its mass and damping added to the device's (paper Table 2).

        A hand that holds the handle moves with it: (m + m_h) ẍ + (b + b_h) ẋ + c sgn(ẋ) = F_A (paper eq. 3
        with F_H = −m_h ẍ − b_h ẋ), so every analysis of the held device is that of a bare device with
        m + m_h and b + b_h, exactly (a hand of zero mass and damping gives the device back bit for bit).

        Parameters
        ----------
        hand : Hand
            The hand (:func:`dfa.get_hand` for a preset); its stiffness must be 0 (a hand stiffness acts beside
            the wall: :func:`dfa.hold` gives the device and the wall with it).

        Returns
        -------
        Device
            Same name, friction, encoder and period; ``mass`` m + m_h, ``damping`` b + b_h, ``hand`` set.

        Raises
        ------
        HandNotCovered
            For a hand stiffness > 0 (use :func:`dfa.hold`).
        DFAValueError
            If the device already holds a hand.

        Examples
        --------
        >>> from dfa.model.hand import Hand
        >>> dev = Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000, name="Delta").holding(Hand(0.15, 4.8))
        >>> round(dev.mass, 12), round(dev.damping, 12), dev.hand.mass
        (0.4, 4.81, 0.15)
        """
        hand = check_type("hand", hand, Hand, "give a dfa.Hand (dfa.get_hand('paper') for the paper's)")
        hand.check_covered()
        return self.held_by(hand)

    def held_by(self, hand: Hand) -> Device:
        """:meth:`holding` without its refusal of a hand stiffness, for :func:`dfa.hold` (which adds it to the wall).

        Parameters
        ----------
        hand : Hand
            The hand; its mass and damping are added, its stiffness is only recorded in ``hand``.

        Returns
        -------
        Device
            As :meth:`holding`.
        """
        if self.hand is not None:
            raise DFAValueError(
                f"hand = {hand.name!r} cannot be added: the device {self.name!r} already holds {self.hand.name!r}; "
                "call holding() on the bare device"
            )
        held = dataclasses.replace(self, mass=self.mass + hand.mass, damping=self.damping + hand.damping)
        object.__setattr__(held, "hand", hand)  # not an argument of Device(): mass and damping include it
        return held

    @property
    def bare(self) -> Device:
        """The device without its hand (itself when none holds it): ``mass`` and ``damping`` less the hand's."""
        if self.hand is None:
            return self
        return dataclasses.replace(self, mass=self.own_mass, damping=self.own_damping)  # hand: None, not an argument

    @property
    def own_mass(self) -> float:
        """The device's own moving mass (kg, rotary kg·m²): ``mass`` less the hand's (for outputs)."""
        return self.mass if self.hand is None else self.mass - self.hand.mass

    @property
    def own_damping(self) -> float:
        """The device's own viscous friction (N·s/m): ``damping`` less the hand's (for outputs)."""
        return self.damping if self.hand is None else self.damping - self.hand.damping

    # ------------------------------------------------------- dimensionless form
    def params(self, stiffness: float) -> Params:
        """Dimensionless (μ, β, σ) for a virtual spring of stiffness ``K`` (paper Table 1).

        Parameters
        ----------
        stiffness : float
            Virtual spring stiffness K in N/m (rotary: N·m/rad), > 0.

        Returns
        -------
        Params
            The groups μ = m/(K T²), β = b/(K T), σ = c/(K Δ).

        Raises
        ------
        DFAValueError
            If ``stiffness`` is not a finite number > 0, or a group overflows or vanishes in a float.

        Warns
        -----
        ImplausibleInputWarning
            If K is above what any haptic device renders (:mod:`dfa.plausibility`), given from outside dfa.
        """
        k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        warn_if_from_outside("stiffness", k, rotary=self.rotary)
        return dimensionless_params(self, k)

    def xi(self, position: float, name: str = "position") -> float:
        """Dimensionless position ξ = x/Δ (encoder ticks) of a physical position.

        Parameters
        ----------
        position : float
            Position x in m (rotary: rad); its sign is kept.
        name : str, optional
            How a message calls it (default ``"position"``; the command line gives its flag, ``"--position"``).

        Returns
        -------
        float
            The position ξ in encoder ticks.

        Raises
        ------
        DFAValueError
            If ``position`` is not a finite number or ξ overflows a float (the message names the position in its
            unit, the resolution it is divided by and the largest position that works).
        """
        unit = self.units["position"]
        x = check_real(name, position, f"give the position in {unit}")
        out = x / self.resolution
        if not math.isfinite(out):
            shown = format_value(x)
            subject = f"{name} {shown} {unit}" if name.startswith("-") else f"{name} = {shown} {unit}"
            top = 1.7976931348623157e308 * self.resolution
            raise DFAValueError(
                f"{subject} is too large: ξ = x/Δ (encoder ticks) overflows a float with Δ = {self.resolution:g} "
                f"{unit}; give a position in {unit} of size below {top:.3g} (check the units)"
            )
        return out

    def xi_dot(self, velocity: float) -> float:
        """Dimensionless speed ξ' = ẋ T/Δ (encoder ticks per sample) of a physical speed.

        Independent of the stiffness K (spec section 2).

        Parameters
        ----------
        velocity : float
            Physical speed ẋ in m/s (rotary: rad/s); its sign is kept.

        Returns
        -------
        float
            The speed ξ' in encoder ticks per sample.

        Raises
        ------
        DFAValueError
            If ``velocity`` is not a finite number or ξ' overflows a float.

        Warns
        -----
        ImplausibleInputWarning
            If |ẋ| is above any impact speed on a haptic device (:mod:`dfa.plausibility`), given from outside dfa.
        """
        v = check_real("velocity", velocity, "give the speed in m/s (rotary: rad/s)")
        warn_if_from_outside("velocity", v, rotary=self.rotary)
        out = v * self.period / self.resolution
        if not math.isfinite(out):
            raise DFAValueError(
                f"velocity = {v!r} is too large: ξ' = ẋT/Δ overflows a float with period = {self.period!r}, "
                f"resolution = {self.resolution!r}; give the speed in m/s (rotary: rad/s)"
            )
        return out

    def velocity(self, xi_dot: float) -> float:
        """Physical speed ẋ = ξ' Δ/T (m/s or rad/s) of a dimensionless speed.

        Parameters
        ----------
        xi_dot : float
            Dimensionless speed ξ' in encoder ticks per sample; its sign is kept.

        Returns
        -------
        float
            The speed ẋ in m/s (rotary: rad/s).

        Raises
        ------
        DFAValueError
            If ``xi_dot`` is not a finite number or ẋ overflows a float.
        """
        xd = check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample")
        out = xd * self.resolution / self.period
        if not math.isfinite(out):
            raise DFAValueError(
                f"xi_dot = {xd!r} is too large: ẋ = ξ'Δ/T overflows a float with period = {self.period!r}, "
                f"resolution = {self.resolution!r}; give a smaller speed in ticks per sample"
            )
        return out

    def stiffness_for_mu(self, mu: float) -> float:
        """The stiffness K (N/m) at which μ = m/(K T²) takes the value ``mu``.

        Parameters
        ----------
        mu : float
            Dimensionless mass μ, > 0.

        Returns
        -------
        float
            K = m/(μ T²) in N/m (rotary: N·m/rad).
        """
        m = check_mu(mu)
        return _stiffness("mu", m, self.mass, self.period * self.period, "K = m/(μ T²)")

    def stiffness_for_beta(self, beta: float) -> float:
        """The stiffness K (N/m) at which β = b/(K T) takes the value ``beta``.

        For β = ½ this is the Colgate-Schenkel bound 2b/T (paper eq. 8).

        Parameters
        ----------
        beta : float
            Dimensionless damping β, > 0.

        Returns
        -------
        float
            K = b/(β T) in N/m (rotary: N·m/rad).

        Raises
        ------
        DFAValueError
            If ``beta`` is not > 0 or the device has no damping (b = 0).
        """
        b = check_positive("beta", beta, "β must be > 0 to solve for K")
        if self.damping == 0.0:
            raise DFAValueError(
                "damping = 0.0 is invalid here: it must be > 0 to reach a given beta; "
                "β = b/(K T) is zero for every K when b = 0"
            )
        return _stiffness("beta", b, self.damping, self.period, "K = b/(β T)")

    def stiffness_for_sigma(self, sigma: float) -> float:
        """The stiffness K (N/m) at which σ = c/(K Δ) takes the value ``sigma``.

        For σ = ½ this is the static bound 2c/Δ (paper eq. 9).

        Parameters
        ----------
        sigma : float
            Dimensionless Coulomb friction σ, > 0.

        Returns
        -------
        float
            K = c/(σ Δ) in N/m (rotary: N·m/rad).

        Raises
        ------
        DFAValueError
            If ``sigma`` is not > 0 or the device has no Coulomb friction (c = 0).
        """
        s = check_positive("sigma", sigma, "σ must be > 0 to solve for K")
        if self.coulomb == 0.0:
            raise DFAValueError(
                "coulomb = 0.0 is invalid here: it must be > 0 to reach a given sigma; "
                "σ = c/(K Δ) is zero for every K when c = 0"
            )
        return _stiffness("sigma", s, self.coulomb, self.resolution, "K = c/(σ Δ)")

    def to_dict(self) -> dict[str, object]:
        """Physical values in SI units, with name and kind.

        Returns
        -------
        dict
            ``name``, ``rotary``, then each of :data:`DEVICE_FIELDS` (``mass``, ``damping``, ``coulomb``,
            ``resolution``, ``period``; an optional one only when given); with a hand
            also ``hand`` (:meth:`Hand.to_dict`), and ``mass`` and ``damping`` include the hand's.
        """
        out: dict[str, object] = {"name": self.name, "rotary": self.rotary}
        for f in DEVICE_FIELDS:  # an optional value that is absent (None) is left out
            if getattr(self, f.name) is not None or f.required:
                out[f.name] = getattr(self, f.name)
        return out | self.hand_json()

    def hand_json(self) -> dict[str, object]:
        """The entry every JSON output that names the device adds for its grasp.

        Returns
        -------
        dict
            ``{"hand": ...}`` (:meth:`Hand.to_dict`) for a held device, ``{}`` for a bare one.
        """
        return {} if self.hand is None else {"hand": self.hand.to_dict()}


def _stiffness(name: str, value: float, numerator: float, factor: float, formula: str) -> float:
    """The stiffness K = numerator/(value·factor) solved for a group, or the package's error where it overflows a
    float (``sigma = 2.2e-313`` gave K = inf; ``sigma = 1e-320`` a ZeroDivisionError, value·factor underflowing to
    0) or vanishes below the smallest normal float (the groups at that K overflow)."""
    den = value * factor
    k = numerator / den if den != 0.0 else math.inf
    if not math.isfinite(k):
        raise DFAValueError(
            f"{name} = {value!r} is invalid for this device: {formula} overflows a float; give a larger {name}"
        )
    if k < sys.float_info.min:
        raise DFAValueError(
            f"{name} = {value!r} is invalid for this device: {formula} = {k:.3g} vanishes (below "
            f"{sys.float_info.min:.3g}, where the other groups overflow); give a smaller {name}"
        )
    return k


_GROUPS = (
    ("mu", "the dimensionless mass μ = m/(K T²)", ("mass", "stiffness", "period")),
    ("beta", "the dimensionless damping β = b/(K T)", ("damping", "stiffness", "period")),
    ("sigma", "the dimensionless friction σ = c/(K Δ)", ("coulomb", "stiffness", "resolution")),
)


def dimensionless_params(device: Device, stiffness: float, names: dict[str, str] | None = None) -> Params:
    """(μ, β, σ) of ``device`` at stiffness K (paper Table 1), refusing groups a float cannot hold.

    A group overflows (inf) or vanishes (zero or subnormal, below
    ``sys.float_info.min`` ≈ 2.2e-308, where 1/μ overflows and the simulation
    returns NaN) only for physically absurd inputs (for example a mass of
    1e-320 kg); the error names the inputs that produce it.

    Parameters
    ----------
    device : Device
    stiffness : float
        K in N/m (rotary: N·m/rad), already checked > 0.
    names : dict, optional
        How to call each physical input in the message (the command line
        passes its flags, e.g. ``{"mass": "--mass"}``); default the parameter names.
    """
    k = float(stiffness)
    vals = {
        "mass": device.mass,
        "damping": device.damping,
        "coulomb": device.coulomb,
        "resolution": device.resolution,
        "period": device.period,
        "stiffness": k,
    }

    def div(
        a: float, b: float
    ) -> float:  # a denominator that underflows to 0 gives inf (or NaN for 0/0), not an exception
        return a / b if b != 0.0 else (math.inf if a > 0.0 else math.nan)

    dens = {"mu": k * (device.period * device.period), "beta": k * device.period, "sigma": k * device.resolution}
    out = {  # p*p: inf, not OverflowError
        "mu": div(device.mass, dens["mu"]),
        "beta": div(device.damping, dens["beta"]),
        "sigma": div(device.coulomb, dens["sigma"]),
    }
    products = {"mu": "K T²", "beta": "K T", "sigma": "the force step K Δ"}
    names = names or {}
    for key, what, inputs in _GROUPS:
        value = out[key]
        if math.isinf(dens[key]):  # c/inf = 0 is no group (contours --resolution 1e308 printed KΔ = inf N)
            value = math.nan
        elif math.isfinite(value) and (value >= sys.float_info.min or (value == 0.0 and key != "mu")):
            continue
        given = ", ".join(f"{names.get(n, n)} = {vals[n]:g}" for n in inputs)
        how = (
            "overflows to inf"
            if math.isinf(value)
            else f"cannot be formed ({products[key]} overflows a float)"
            if math.isinf(dens[key])
            else "is undefined (0/0)"
            if math.isnan(value)
            else f"vanishes ({value:.3g}, below {sys.float_info.min:.3g})"
        )
        raise DFAValueError(
            f"{given} is invalid: {what} {how}; give ordinary physical values in SI units "
            f"({', '.join(device.units[n] for n in inputs)})"
        )
    return Params(**out)
