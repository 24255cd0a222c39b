"""A wall ready for the firmware (issue 44): the device, the wall at the stiffness to deploy, and why that K.

:class:`DeployableWall` is what ``dfa export`` writes (:mod:`dfa.render.export`: a C99 header, a YAML parameter
file, JSON) and what ``dfa export --from FILE.json`` reads back: the device (every field), the wall at the exported
stiffness K, the impact speed K was chosen for and the rule behind it (:class:`~dfa.results.status.DeployRule`: a
recommendation's rule, or ``given``), the margin and the limit K rests on, the command line that made it and the
version of dfa.

The firmware is the part of the modelled loop that runs on the controller: the spring on the encoder's reading (paper
eq. 2), the delay, the damper on the backward difference, the velocity filter, a one-sided wall, the passivity
observer and controller and the actuator's force limit (:data:`FIRMWARE`). The amplifier's lag, the hand's
stiffness, the operator's push and the device's end stops are modelled by dfa but are the hardware's or the
operator's (:data:`OUTSIDE`): an export leaves them out of the code and says so.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.loop import Loop
>>> from dfa.model.wall import Wall
>>> dep = DeployableWall.given(Loop(get_device("impulse").device, Wall.of(100.0, damping=0.5)))
>>> dep.rule.value, dep.velocity, round(dep.force_step, 6)
('given', None, 0.0314)
>>> DeployableWall.from_dict(dep.to_dict()) == dep
True
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..checks import check_type
from ..errors import DFATypeError, DFAValueError
from ..model.device import DEVICE_FIELDS, Device
from ..model.elements import ELEMENTS, Element, Travel
from ..model.hand import Hand
from ..model.loop import Loop
from ..model.wall import Wall, WallParams
from .base import Result
from .require import Recommendation
from .status import DeployRule, RecommendRule

__all__ = ["DeployableWall", "FIRMWARE", "OUTSIDE", "device_from_dict", "package_version"]

#: The wall's elements that run in the firmware (each element's :attr:`~dfa.model.elements.Element.firmware`), in
#: the registry's order.
FIRMWARE: tuple[type[Element[Any]], ...] = tuple(k for k in ELEMENTS if k.firmware is True)
#: The modelled elements that are not the firmware's, and whose they are (each element's declaration).
OUTSIDE: dict[type[Element[Any]], str] = {k: k.firmware for k in ELEMENTS if isinstance(k.firmware, str)}
_FIX = "build it with DeployableWall.from_recommendation(rec) or DeployableWall.given(Loop(device, wall))"


def package_version() -> str:
    """The installed dfa's version (``importlib.metadata``; ``0+unknown`` from a source tree never installed)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("dfa-haptics")
    except PackageNotFoundError:  # pragma: no cover - a source tree that was never installed
        return "0+unknown"


def device_from_dict(data: Mapping[str, Any]) -> Device:
    """The device of :meth:`Device.to_dict <dfa.model.device.Device.to_dict>`'s record, every field exactly.

    Parameters
    ----------
    data : mapping
        ``name``, ``rotary``, each field of :data:`~dfa.model.device.DEVICE_FIELDS` (an optional one may be missing
        or None) and, for a held device, ``hand`` (:meth:`Hand.to_dict <dfa.model.hand.Hand.to_dict>`; ``mass`` and
        ``damping`` then include the hand's, as recorded).

    Returns
    -------
    Device

    Examples
    --------
    >>> dev = Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000, name="Delta", max_force=20.0)
    >>> device_from_dict(dev.to_dict()) == dev
    True
    """
    if not isinstance(data, Mapping):
        raise DFATypeError(f"device = {data!r} is invalid: it must be a device's record (Device.to_dict())")
    missing = [f.name for f in DEVICE_FIELDS if f.required and f.name not in data]
    if missing:
        raise DFAValueError(f"device record lacks {', '.join(missing)}: give every field of Device.to_dict()")
    values: dict[str, Any] = {f.name: data.get(f.name) for f in DEVICE_FIELDS}
    dev = Device(**values, name=str(data.get("name", "custom device")), rotary=bool(data.get("rotary", False)))
    hand = data.get("hand")
    if hand is not None:
        held = Hand(**{k: hand[k] for k in ("mass", "damping", "stiffness", "name", "source") if k in hand})
        object.__setattr__(dev, "hand", held)  # mass and damping as recorded (they include the hand's)
    return dev


def _wall_from(data: Any) -> Wall:
    """The wall of a record: :meth:`Wall.to_dict`'s, ``{"stiffness": K, "elements": [Element.to_dict(), ...]}``, or
    the YAML's ``{"stiffness": K, "elements": {name: record without "element", ...}}`` (no nulls, no list of maps:
    ROS parameters hold neither)."""
    if not isinstance(data, Mapping):
        raise DFATypeError(f"wall = {data!r} is invalid: it must be a wall's record (Wall.to_dict())")
    elements = data.get("elements")
    if isinstance(elements, Mapping):  # the YAML's: each element's record under its name
        elements = [{"element": name, **record} for name, record in elements.items()]
    if isinstance(elements, list):
        return Wall(float(data["stiffness"]), tuple(Element.from_dict(e) for e in elements))
    return Wall.from_dict(data)


@dataclass(frozen=True)
class DeployableWall(Result):
    """A wall to deploy: the device, the wall at the exported stiffness, and the reason for its K (module docstring).

    Attributes
    ----------
    device : Device
        The device (SI units; rotary: rad, N·m).
    wall : Wall
        The wall at the exported stiffness K, N/m (rotary N·m/rad); the device's own elements (its force limit,
        its travel) join it in :attr:`loop`.
    velocity : float or None
        The impact speed K was chosen for, m/s (rotary rad/s); None when K was given.
    rule : DeployRule
        The rule behind K: ``proven``, ``simulated``, ``simulated_range`` (a recommendation's) or ``given``.
    margin : float or None
        The gain margin the simulated limit was divided by (>= 1); None under ``proven`` (a proof needs none) and
        ``given``.
    k_basis : float or None
        The limit K rests on, N/m (rotary N·m/rad): K_criterion under ``proven``, the simulated limit (or the top of
        the range searched) under the simulated rules; None under ``given``.
    command : str or None
        The command line that made it (``dfa export ...``); None from the API.
    dfa_version : str
        The version of dfa that made it (default: the installed one).
    """

    device: Device = field(metadata={"json": lambda d: d.to_dict()})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float | None = None
    rule: DeployRule = DeployRule.GIVEN
    margin: float | None = None
    k_basis: float | None = None
    command: str | None = None
    dfa_version: str = field(default_factory=package_version)

    json_properties: ClassVar[tuple[str, ...]] = ("rule_message", "force_step", "firmware", "not_exported")
    units_of: ClassVar[dict[str, str]] = {"velocity": "velocity", "k_basis": "stiffness", "force_step": "force"}

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, _FIX)
        check_type("wall", self.wall, Wall, _FIX)
        object.__setattr__(self, "rule", DeployRule.coerce(self.rule, "rule"))
        for e in self.wall.elements:
            if type(e) not in FIRMWARE and type(e) not in OUTSIDE:
                raise DFAValueError(
                    f"wall element {type(e).__name__} cannot be exported: the export knows "
                    f"{', '.join(k.__name__ for k in (*FIRMWARE, *OUTSIDE))}; drop it from the wall"
                )
        given = self.rule is DeployRule.GIVEN
        for name in ("velocity", "k_basis", "margin"):
            value = getattr(self, name)
            absent = given or (name == "margin" and self.rule is DeployRule.PROVEN)
            if absent and value is not None:
                raise DFAValueError(
                    f"{name} = {value!r} is invalid under the rule {self.rule.value!r}: it must be None; {_FIX}"
                )
            if not absent and not (isinstance(value, (int, float)) and math.isfinite(value) and value >= 0):
                raise DFAValueError(
                    f"{name} = {value!r} is invalid under the rule {self.rule.value!r}: it must be a finite number "
                    f">= 0; {_FIX}"
                )
        if self.margin is not None and self.margin < 1.0:
            raise DFAValueError(f"margin = {self.margin!r} is invalid: it must be >= 1; {_FIX}")
        if not (self.command is None or isinstance(self.command, str)) or not isinstance(self.dfa_version, str):
            raise DFATypeError(f"command = {self.command!r}, dfa_version = {self.dfa_version!r}: both must be text")
        self.loop  # noqa: B018  (forms the groups: a cutoff above Nyquist, a group that overflows, is refused here)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_recommendation(cls, rec: Recommendation, command: str | None = None) -> DeployableWall:
        """The recommended wall: its K (:func:`dfa.analysis.limits.recommend.recommend_stiffness`) and its rule.

        Parameters
        ----------
        rec : Recommendation
            A recommendation with a K (rule ``proven``, ``simulated`` or ``simulated_range``).
        command : str or None, optional
            The command line that made it (default None).

        Returns
        -------
        DeployableWall

        Raises
        ------
        DFAValueError
            For a recommendation with no K (rule ``none`` or ``not_simulated``).
        """
        rec = check_type("rec", rec, Recommendation, "pass the result of dfa.recommend_stiffness")
        if rec.k_recommended is None or rec.status in (RecommendRule.NONE, RecommendRule.NOT_SIMULATED):
            raise DFAValueError(
                f"recommendation rule = {rec.status.value!r} is invalid for an export: {rec.status.message}; give "
                "the stiffness instead (DeployableWall.given(Loop(device, wall)), dfa export --stiffness K)"
            )
        rule = DeployRule.coerce(rec.status.value, "rule")
        margin = None if rule is DeployRule.PROVEN else rec.margin
        wall = rec.wall.with_stiffness(rec.k_recommended)
        return cls(rec.device, wall, rec.velocity, rule, margin, rec.k_basis, command)

    @classmethod
    def given(cls, loop: Loop, command: str | None = None) -> DeployableWall:
        """The loop's wall at its own stiffness (rule ``given``).

        Parameters
        ----------
        loop : Loop
            A device and a wall with a stiffness, ``Loop(device, wall)``.
        command : str or None, optional
            The command line that made it (default None).

        Returns
        -------
        DeployableWall
        """
        loop = check_type("loop", loop, Loop, "give dfa.Loop(device, wall) with the wall's stiffness")
        device, wall = loop.physical("an export")
        return cls(device, wall, command=command)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> DeployableWall:
        """The wall of :meth:`to_dict`'s record, or of the YAML of :func:`dfa.render.export.yaml_text` (parsed).

        Parameters
        ----------
        data : mapping
            The record (extra keys, the derived ones among them, are ignored).

        Returns
        -------
        DeployableWall

        Raises
        ------
        DFATypeError, DFAValueError
            For a record that is not a wall's to deploy.
        """
        if not isinstance(data, Mapping):
            raise DFATypeError(f"data of type {type(data).__name__} is invalid: give DeployableWall.to_dict()'s record")
        if "dfa_wall" in data:  # the YAML: the record is its provenance
            data = data["dfa_wall"]["ros__parameters"]["provenance"]
        missing = [k for k in ("device", "wall", "rule") if k not in data]
        if missing:
            raise DFAValueError(f"record lacks {', '.join(missing)}: give DeployableWall.to_dict()'s record")
        opt: dict[str, Any] = {k: data.get(k) for k in ("velocity", "margin", "k_basis", "command")}
        version = data.get("dfa_version")
        extra: dict[str, Any] = {} if version is None else {"dfa_version": version}
        return cls(device_from_dict(data["device"]), _wall_from(data["wall"]), rule=data["rule"], **opt, **extra)

    # ------------------------------------------------------------------ derived
    @property
    def loop(self) -> Loop:
        """The device and the wall with the device's elements (its force limit, its travel) and their groups."""
        return Loop(self.device, self.wall)

    @property
    def stiffness(self) -> float:
        """The exported stiffness K, N/m (rotary N·m/rad)."""
        return self.wall.stiffness

    @property
    def force_step(self) -> float:
        """K·Δ, N (rotary N·m): the force of one encoder count, the unit of the firmware's dimensionless force."""
        return self.wall.stiffness * self.device.resolution

    @property
    def rule_message(self) -> str:
        """What the rule means, in words."""
        return str(self.rule.message)

    @property
    def firmware_params(self) -> WallParams:
        """The firmware's groups (:data:`FIRMWARE`): delay d, β_B, the filter's ν_c, s, (W, f_max), φ_max."""
        _p, wp = self.loop.groups("an export")
        return WallParams(tuple((k, g) for k, g in wp.groups if k in FIRMWARE))

    @property
    def firmware(self) -> dict[str, object]:
        """The firmware's groups as a record (:meth:`WallParams.to_dict`), the filter's pole a among them."""
        p = self.firmware_params
        return p.to_dict() | {"filter_pole": p.filter_pole if p.cutoff is not None else None}

    @property
    def outside(self) -> tuple[tuple[Element[Any], str], ...]:
        """The modelled elements that are not the firmware's (the device's travel included), with whose they are."""
        loop = self.loop
        assert loop.wall is not None and loop.wall_params is not None
        own = [(e, OUTSIDE[type(e)]) for e in loop.wall.elements if type(e) in OUTSIDE]
        travel = loop.wall_params.group(Travel)
        if self.device.travel is not None and travel is not None and loop.wall.element(Travel) is None:
            own.append((Travel(self.device.travel), OUTSIDE[Travel]))
        return tuple(own)

    @property
    def not_exported(self) -> list[str]:
        """The keys of the elements left out of the firmware (:attr:`outside`)."""
        return [type(e).key() for e, _why in self.outside]

    def null_reasons(self) -> dict[str, str]:
        """Why a field may be null.

        Returns
        -------
        dict of str to str
            Field name to the reason it is null.
        """
        return {
            "velocity": "the stiffness was given: no impact speed chose it",
            "margin": "no margin: a proof needs none, and a given K has none",
            "k_basis": "the stiffness was given: it rests on no limit",
            "command": "made through the API, not the command line",
        }
