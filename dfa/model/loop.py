"""The loop every analysis takes: a device and the wall rendered on it, with their dimensionless groups.

python-control's idea (one system object that every analysis takes first) for the haptic loop of paper
section 2: :class:`Loop` holds the :class:`~dfa.model.device.Device` (m, b, c, Δ, T), the physical
:class:`~dfa.model.wall.Wall` (the spring K and its elements) and, where the stiffness is known, the groups
formed once: :class:`~dfa.model.device.Params` (μ = m/(K T²), β = b/(K T), σ = c/(K Δ), paper Table 1) and
:class:`~dfa.model.wall.WallParams` (β_B = B/(K T), d, ν_c = f_c T, α = τ_a/T, ...).

Three kinds of loop:

- ``Loop(device, wall)``: a device and a wall of known K (or K alone, the paper's spring); groups formed;
- ``Loop(device)``: a device and the paper's spring at no given K, for the analyses that search over K
  (K_max, the stiffness–speed chart, the Z-width); :meth:`Loop.at` gives the loop at one K;
- :meth:`Loop.dimensionless`: the groups alone (μ, β, σ and the wall's), no device and no units.

Examples
--------
>>> from dfa.model.device import Device
>>> from dfa.model.wall import Wall
>>> dev = Device(0.032, 0.02, 0.024, 314e-6, 2e-3, name="Impulse Engine")
>>> loop = Loop(dev, Wall.of(80.0, damping=0.01))
>>> round(loop.params.mu, 3), round(loop.params.beta, 4), round(loop.wall_params.damping, 4)
(100.0, 0.125, 0.0625)
>>> Loop(dev).stiffness is None, Loop(dev).at(80.0).params == loop.params
(True, True)
>>> Loop.dimensionless(100.0, 0.125, 0.9554).to_dict()["params"]
{'mu': 100.0, 'beta': 0.125, 'sigma': 0.9554}
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Mapping
from dataclasses import InitVar, dataclass, field
from typing import Any, TypeVar, cast

import numpy as np

from ..checks import check_positive, check_type, format_value
from ..errors import DFATypeError, DFAValueError
from . import elements
from .device import Device, Params, dimensionless_params
from .elements import Element
from .wall import Wall, WallParams

__all__ = [
    "Loop", "as_loop", "device_elements", "device_groups", "device_wall", "limited", "loop_first", "with_travel",
    "LOOP_FIX",
]  # fmt: skip

F = TypeVar("F", bound=Callable[..., Any])

#: How a message tells to build a loop.
LOOP_FIX = "build it with dfa.Loop(device, wall), or dfa.Loop.dimensionless(mu, beta, sigma)"
_FIX_DEVICE = "build one with dfa.Device(...) or dfa.get_device(name).device"
_FIX_PARAMS = "build it with dfa.Params(mu, beta, sigma) or device.params(stiffness)"
_FIX_WALL_PARAMS = "give dfa.WallParams.of(...) or wall.params(period) of a dfa.Wall, or None for the spring"


def device_elements(device: Device | None, *, in_wall: bool) -> tuple[Element[object], ...]:
    """The elements a device's fields add to its walls by default: one per element class that names a device field.

    Each element class of :data:`~dfa.model.elements.ELEMENTS` whose :attr:`~dfa.model.elements.Element.device_field`
    the device gives (not None) is built from that value (the force limit from ``max_force``, the travel from
    ``travel``); the one declaration that :class:`Loop` and the command line read (:func:`device_wall`,
    :func:`device_groups`).

    Parameters
    ----------
    device : Device or None
        The device (None: none, no element).
    in_wall : bool
        Keyword only: the elements that go into the physical wall (True) or into its groups only (False), by
        :attr:`~dfa.model.elements.Element.device_in_wall`.

    Returns
    -------
    tuple of Element
        In the order of :data:`~dfa.model.elements.ELEMENTS`.

    Examples
    --------
    >>> device_elements(Device(0.072, 0.005, 0.038, 2e-5, 1e-3, max_force=3.0, travel=0.05), in_wall=True)
    (ForceLimit(max_force=3.0),)
    """
    if device is None:
        return ()
    out: list[Element[object]] = []
    for kind in elements.ELEMENTS:
        value = None if kind.device_field is None else getattr(device, kind.device_field)
        if value is not None and kind.device_in_wall == in_wall:
            out.append(kind(**{kind.parameter.name: value}))
    return tuple(out)


def device_groups(wall_params: WallParams, device: Device | None) -> WallParams:
    """The wall's groups with the device's groups-only elements added (:func:`device_elements`, ``in_wall=False``).

    A device's travel applies by default (:class:`~dfa.model.elements.Travel`, ξ_travel = travel/Δ): the real
    device has end stops. A wall that holds its own keeps it; a device without one (None: unlimited) leaves the
    groups unchanged.

    Parameters
    ----------
    wall_params : WallParams
        The wall's groups on the device.
    device : Device or None
        The device (None: no device, the groups unchanged).

    Returns
    -------
    WallParams

    Examples
    --------
    >>> from dfa.model.elements import Travel
    >>> dev = Device(0.072, 0.005, 0.038, 2e-5, 1e-3, travel=0.05)
    >>> device_groups(WallParams(), dev).group(Travel)
    2500.0
    """
    held = {k for k, _ in wall_params.groups}
    added = [e for e in device_elements(device, in_wall=False) if type(e) not in held]
    if device is None or not added:
        return wall_params
    groups = Wall(1.0, tuple(added)).params(device.period, device.resolution).groups  # no group of these needs K
    return WallParams((*wall_params.groups, *groups))


#: The former name of :func:`device_groups` (the travel was its first groups-only element).
with_travel = device_groups


def _wall_of(wall: object) -> Wall:
    """A :class:`Wall` from a wall or a stiffness K (the paper's spring), else the package's error."""
    if isinstance(wall, Wall):
        return wall
    if isinstance(wall, (int, float, np.integer, np.floating)) and not isinstance(wall, (bool, np.bool_)):
        return Wall(float(wall))  # Wall checks K (a finite number > 0)
    raise DFATypeError(
        f"wall = {format_value(wall)} has type {type(wall).__name__}: it must be a dfa.Wall or a stiffness K in N/m; "
        "give e.g. dfa.Wall.of(1000.0, damping=1.0), or 1000.0 for the spring alone"
    )


def device_wall(wall: Wall, device: Device) -> Wall:
    """The wall with the device's elements added (:func:`device_elements`, ``in_wall=True``) where the wall has
    none of its own (a wall's own, e.g. ``--max-force``'s force limit, wins).

    Parameters
    ----------
    wall : Wall
        The wall (K in N/m and its elements).
    device : Device
        The device; e.g. its ``max_force`` in N (rotary N·m) or None (unlimited).

    Returns
    -------
    Wall
        ``wall`` itself, or ``wall`` with e.g. ``ForceLimit(device.max_force)`` added.
    """
    added = [e for e in device_elements(device, in_wall=True) if wall.element(type(e)) is None]
    return Wall(wall.stiffness, (*wall.elements, *added)) if added else wall


#: The former name of :func:`device_wall` (the force limit was its first element).
limited = device_wall


@dataclass(frozen=True)
class Loop:
    """A haptic loop: a device, the wall rendered on it and their dimensionless groups (module docstring).

    Parameters
    ----------
    device : Device or None
        The physical device (m in kg, b in N·s/m, c in N, Δ in m, T in s; rotary: kg·m², N·m·s/rad, N·m, rad);
        None only for a dimensionless loop (:meth:`dimensionless`).
    wall : Wall or float or None, optional
        The virtual wall (its stiffness K in N/m, rotary N·m/rad, and its elements), or K alone for the paper's
        spring; None (default): the spring at no given K (an analysis that searches over K).
    params : Params or None, optional
        Keyword only, for a dimensionless loop: the groups (μ, β, σ); formed from the device otherwise.
    wall_params : WallParams or None, optional
        Keyword only, for a dimensionless loop: the wall's groups (default the spring); formed from the wall
        otherwise.
    names : mapping, optional
        How a message calls each wall element's physical value (the command line passes its flags,
        ``{"damping": "--virtual-damping"}``); default the parameter names. Not stored.

    Attributes
    ----------
    params : Params or None
        (μ, β, σ) at the wall's K (paper Table 1); None for a device loop at no given K.
    wall_params : WallParams or None
        The wall's groups at K and T; None for a device loop at no given K.

    Raises
    ------
    DFATypeError
        If ``device`` is not a :class:`Device`, ``wall`` not a :class:`Wall` or a number, or the groups not
        :class:`Params` / :class:`WallParams`.
    DFAValueError
        If K is not a finite number > 0, a group overflows or vanishes in a float, a filter cutoff is not below
        the Nyquist frequency, or a loop is given both a device and groups (or a wall without a device).
    """

    device: Device | None
    wall: Wall | None = None
    params: Params | None = field(default=None, kw_only=True)
    wall_params: WallParams | None = field(default=None, kw_only=True)
    names: InitVar[Mapping[str, str] | None] = field(default=None, kw_only=True)

    def __post_init__(self, names: Mapping[str, str] | None) -> None:
        if self.device is None:
            self._check_dimensionless()
            return
        check_type("device", self.device, Device, _FIX_DEVICE)
        if self.params is not None or self.wall_params is not None:
            given = self.params if self.params is not None else self.wall_params
            raise DFAValueError(
                f"params = {format_value(given)} is invalid with a device: the groups are formed from the device "
                "and the wall; give either Loop(device, wall), or the groups alone, "
                "Loop.dimensionless(mu, beta, sigma, wall_params)"
            )
        if self.wall is None:
            return
        wall = device_wall(_wall_of(self.wall), self.device)
        dev = self.device
        if names is None:
            wp = wall.params(dev.period, dev.resolution)
        else:
            wp = wall.params(dev.period, dev.resolution, names=names, rotary=dev.rotary)
        object.__setattr__(self, "wall", wall)
        object.__setattr__(self, "params", dimensionless_params(dev, wall.stiffness))
        object.__setattr__(self, "wall_params", device_groups(wp, dev))  # e.g. the device's end stops

    def _check_dimensionless(self) -> None:
        if self.wall is not None:
            raise DFAValueError(
                f"wall = {format_value(self.wall)} is invalid without a device: its groups need the sample period "
                "and the encoder resolution; give the device, Loop(device, wall), or the wall's groups, "
                "Loop.dimensionless(mu, beta, sigma, wall_params)"
            )
        if self.params is None:
            raise DFAValueError(
                "device = None is invalid without the groups: a loop needs a device or (μ, β, σ); give "
                "Loop(device, wall) or Loop.dimensionless(mu, beta, sigma)"
            )
        check_type("params", self.params, Params, _FIX_PARAMS)
        wp = WallParams() if self.wall_params is None else self.wall_params
        object.__setattr__(self, "wall_params", check_type("wall_params", wp, WallParams, _FIX_WALL_PARAMS))

    @classmethod
    def dimensionless(cls, mu: float, beta: float, sigma: float, wall_params: WallParams | None = None) -> Loop:
        """A loop of groups alone: no device, no physical units (positions in ticks, time in samples).

        Parameters
        ----------
        mu : float
            Dimensionless mass μ = m/(K T²), > 0.
        beta : float
            Dimensionless viscous damping β = b/(K T), >= 0.
        sigma : float
            Dimensionless Coulomb friction σ = c/(K Δ), >= 0.
        wall_params : WallParams or None, optional
            The wall's groups (β_B, d, ν_c, α, ...); None (default): the paper's spring.

        Returns
        -------
        Loop
            ``device`` and ``wall`` None, ``params`` and ``wall_params`` set.

        Examples
        --------
        >>> Loop.dimensionless(2.0, 0.1, 0.3).wall_params.is_spring
        True
        """
        return cls(None, params=Params(mu, beta, sigma), wall_params=wall_params)

    def at(self, stiffness: float) -> Loop:
        """The same device and wall elements at another stiffness K: how the searches over K form the groups.

        Parameters
        ----------
        stiffness : float
            Virtual spring K in N/m (rotary: N·m/rad), > 0.

        Returns
        -------
        Loop
            This loop's device, its wall's elements (none for the spring) at K, with the groups at K.

        Raises
        ------
        DFAValueError
            For a dimensionless loop (its groups have no K to vary), or K not a finite number > 0.
        """
        if self.device is None:
            raise DFAValueError(
                f"stiffness = {format_value(stiffness)} cannot be set on a dimensionless loop: its groups have no "
                "K to vary; build the loop from a device, Loop(device, wall)"
            )
        k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        return Loop(self.device, Wall(k) if self.wall is None else self.wall.with_stiffness(k))

    def physical(self, analysis: str) -> tuple[Device, Wall]:
        """The device and the wall of a loop at a given K, for an analysis in physical units.

        Parameters
        ----------
        analysis : str
            The analysis's name, for the message.

        Returns
        -------
        tuple of (Device, Wall)
            The device and the wall at its K.

        Raises
        ------
        DFAValueError
            For a dimensionless loop, or a device loop at no given K.
        """
        if self.device is None:
            raise DFAValueError(
                f"loop = a dimensionless loop is invalid for {analysis}: it works in physical units; build the loop "
                "from a device, Loop(device, wall)"
            )
        if self.wall is None:
            raise DFAValueError(
                f"loop = Loop({self.device.name!r}) has no stiffness, which {analysis} needs; give the wall or its K, "
                "Loop(device, wall) or loop.at(stiffness)"
            )
        return self.device, self.wall

    def search_device(self, analysis: str) -> Device:
        """The device of a loop whose K an analysis varies (a K_max search, a chart, a Z-width).

        Parameters
        ----------
        analysis : str
            The analysis's name, for the message.

        Returns
        -------
        Device
            The loop's device.

        Raises
        ------
        DFAValueError
            For a dimensionless loop (no K to vary).
        """
        if self.device is None:
            raise DFAValueError(
                f"loop = a dimensionless loop is invalid for {analysis}: it varies the stiffness K, which the groups "
                "do not hold; build the loop from a device, Loop(device) or Loop(device, wall)"
            )
        return self.device

    def groups(self, analysis: str) -> tuple[Params, WallParams]:
        """(μ, β, σ) and the wall's groups, for an analysis in dimensionless form.

        Parameters
        ----------
        analysis : str
            The analysis's name, for the message.

        Returns
        -------
        tuple of (Params, WallParams)
            (μ, β, σ) and the wall's groups.

        Raises
        ------
        DFAValueError
            For a device loop at no given K.
        """
        if self.params is None or self.wall_params is None:
            name = "custom device" if self.device is None else self.device.name
            raise DFAValueError(
                f"loop = Loop({name!r}) has no stiffness, so no (μ, β, σ), which {analysis} needs; give the wall or "
                "its K, Loop(device, wall) or loop.at(stiffness)"
            )
        return self.params, self.wall_params

    @property
    def stiffness(self) -> float | None:
        """The wall's stiffness K in N/m (rotary N·m/rad); None when no K is given (or no device)."""
        return None if self.wall is None else self.wall.stiffness

    @property
    def has_groups(self) -> bool:
        """True when (μ, β, σ) and the wall's groups are known (a stiffness is given, or the loop is dimensionless)."""
        return self.params is not None

    @property
    def spring(self) -> Wall:
        """The wall whose elements a search over K holds fixed: the wall, or the spring at a placeholder K = 1 N/m.

        The placeholder K is never analysed: the searches set K (:meth:`~dfa.model.wall.Wall.with_stiffness`).
        """
        return Wall(1.0) if self.wall is None else self.wall

    def to_dict(self) -> dict[str, Any]:
        """The loop as a JSON-able dictionary: the device, the wall and the groups (None where not known).

        Returns
        -------
        dict
            ``device`` (:meth:`Device.to_dict`), ``wall`` (:meth:`Wall.to_dict`), ``params`` (μ, β, σ) and
            ``wall_params`` (each element's group, :meth:`WallParams.to_dict`), each None where absent.
        """
        return {
            "device": None if self.device is None else self.device.to_dict(),
            "wall": None if self.wall is None else self.wall.to_dict(),
            "params": None if self.params is None else self.params.to_dict(),
            "wall_params": None if self.wall_params is None else self.wall_params.to_dict(),
        }


def as_loop(first: Loop | Device | Params, wall: Wall | WallParams | float | None = None) -> Loop:
    """The loop of an analysis called with its former first argument (a device or the groups), for the transition.

    Parameters
    ----------
    first : Loop, Device or Params
        A loop (returned as it is; then ``wall`` must be None), a device (with ``wall``, a :class:`Wall`, a
        stiffness K in N/m or None), or the groups (μ, β, σ) (with ``wall``, a :class:`WallParams` or None).
    wall : Wall, WallParams, float or None, optional
        The wall of a device, or the wall's groups of dimensionless ``first``.

    Returns
    -------
    Loop

    Raises
    ------
    DFAValueError
        If a loop is given with a separate wall (the loop holds its wall).
    DFATypeError
        If ``first`` is none of these, or ``wall`` does not fit it (as :class:`Loop`).

    Examples
    --------
    >>> from dfa.model.device import Params
    >>> as_loop(Params(2.0, 0.1, 0.3)).params
    Params(mu=2.0, beta=0.1, sigma=0.3)
    """
    if isinstance(first, Loop):
        if wall is not None:
            raise DFAValueError(
                f"wall = {format_value(wall)} is invalid with a loop: the loop holds its wall; build the loop with "
                "it, Loop(device, wall)"
            )
        return first
    if isinstance(first, Params):
        if wall is not None and not isinstance(wall, WallParams):  # the former analyses' own message
            raise DFATypeError(
                f"wall = {wall!r} is invalid: it must be a WallParams or None; "
                "pass Wall.of(...).params(period) or WallParams.of(...)"
            )
        return Loop(None, params=first, wall_params=wall)
    if isinstance(wall, WallParams):
        raise DFATypeError(
            f"wall = {format_value(wall)} has type WallParams: a device's wall must be a dfa.Wall or a stiffness "
            "K in N/m; give dfa.Wall.of(K, ...)"
        )
    return Loop(check_type("device", first, Device, _FIX_DEVICE), None if wall is None else _wall_of(wall))


#: The former first parameters an analysis may still be called with (:func:`loop_first`).
OLD_FORMS = ("device, wall", "device, *, wall", "device, velocity, wall", "params, *, wall", "mu, beta, sigma, *, wall")


def _old_call(
    old: str, args: tuple[Any, ...], kwargs: dict[str, Any], wall_fix: str | None = None
) -> tuple[Loop, tuple[Any, ...]]:
    """The loop and the positional arguments after it of a call in the former form ``old``; the former leading
    parameters (and ``wall``) are popped from ``kwargs``; ``wall_fix``: the former analysis's fix of a wall that is
    not a :class:`WallParams` (its message kept)."""
    names = old.replace(", *", "").split(", ")
    if "*" in old:
        names.remove("wall")
    given = list(args[: len(names)])
    for name in names[len(given) :]:
        if name not in kwargs:
            raise TypeError(f"missing the argument {name!r} (or give a dfa.Loop first)")
        given.append(kwargs.pop(name))
    rest = args[len(names) :]
    if old == "device, wall":
        return as_loop(given[0], given[1]), rest
    if old == "device, velocity, wall":
        return as_loop(given[0], given[2]), (given[1], *rest)
    if len(given) == 3:
        return as_loop(Params(*given), kwargs.pop("wall", None)), rest
    first, wall = given[0], kwargs.pop("wall", None)
    if old.startswith("params"):  # the former analyses' own messages
        check_type("params", first, Params, _FIX_PARAMS)
        if wall is not None and wall_fix is not None:
            check_type("wall", wall, WallParams, wall_fix)
    return as_loop(first, wall), rest


def loop_first(old: str, *, wall_fix: str | None = None) -> Callable[[F], F]:
    """Let an analysis that takes a :class:`Loop` first still be called with its former first arguments.

    A call whose first argument is a :class:`Loop` goes through unchanged; any other is read in the former form
    ``old`` (a device and its wall, or the groups and the wall's groups) and its loop built by :func:`as_loop`.

    Parameters
    ----------
    old : str
        The former form, one of :data:`OLD_FORMS`: ``"device, wall"`` (the wall second), ``"device, *, wall"``
        (the wall a keyword, default none), ``"device, velocity, wall"``, ``"params, *, wall"`` (a
        :class:`Params` and the keyword ``wall``, a :class:`WallParams`), ``"mu, beta, sigma, *, wall"``.
    wall_fix : str, optional
        Keyword only, for the ``"params, *, wall"`` form: the fix of the former analysis's message refusing a
        wall that is not a :class:`WallParams` (the message is kept); default :func:`as_loop`'s.

    Returns
    -------
    callable
        The decorator.
    """
    if old not in OLD_FORMS:  # pragma: no cover - a programming error in dfa itself
        raise ValueError(f"old = {old!r} is not one of {OLD_FORMS}")

    def decorate(func: F) -> F:
        @functools.wraps(func)
        def loop_first_wrapper(*args: Any, **kwargs: Any) -> Any:
            if (args and isinstance(args[0], Loop)) or "loop" in kwargs:
                if "wall" in kwargs:
                    as_loop(args[0] if args else kwargs["loop"], kwargs["wall"])  # refuses a wall beside the loop
                return func(*args, **kwargs)
            kw = dict(kwargs)
            loop, rest = _old_call(old, args, kw, wall_fix)
            return func(loop, *rest, **kw)

        return cast(F, loop_first_wrapper)

    return decorate
