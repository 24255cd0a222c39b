"""The elements of a virtual wall: one class each, carrying its own mathematics.

A wall (:class:`dfa.model.wall.Wall`) is the paper's spring (eq. 1-2) and any of these blocks between the
encoder reading and the force on the device. Each element is a frozen dataclass in physical units (SI; a
rotary device uses rad, N·m, kg·m²) and states, as class attributes and class methods:

- its parameter, unit, command-line flag and dimensionless group beside paper Table 1 (:class:`Parameter`);
- :meth:`Element.group`: that group for a sample period T and a stiffness K, validated;
- :meth:`Element.corner`: its contribution to the corner (β₀, σ₀) of the passivity criterion (eq. 6 extended,
  :mod:`dfa.analysis.criterion`), or :class:`NotCovered` with the reason no sound criterion covers it;
- :attr:`Element.colgate_schenkel`: why the Colgate–Schenkel condition does not cover it (None: it does);
- :attr:`Element.kernel_code` and :meth:`Element.kernel_block`: its code and block in the wall's kernel table, the
  one array the compiled simulator reads (:mod:`dfa.core.table`, :class:`KernelBlock`);
- :meth:`Element.command` and :meth:`Element.plant`: its transfer function, as polynomials of the exact
  sampled loop (:mod:`dfa.analysis.linear_wall`), whose frequency responses the describing function uses;
- :attr:`Element.sweep_points`: how many stiffnesses a K_max sweep may simulate with it (run cost).

Every analysis reads the elements through these hooks only (:class:`dfa.model.wall.WallParams` composes
them), so a new element is one class here, its block in :mod:`dfa.core` when the simulator must integrate
something new, and nothing else (``docs/architecture.md``).

The loop, dimensionless (time in samples, ξ = x/Δ, φ = F/(KΔ)): at sample h the wall reads r_h = ⌊ξ_h⌋,
forms the backward-difference velocity v_h = r_h − r_{h−1}, optionally filters it (y_h = a y_{h−1} +
(1 − a) v_{h−1}, a = e^{−2πν_c}), and commands, d samples later, φ_cmd = −(r + ½) − β_B y; the amplifier
follows the held command through α φ_A' = φ_cmd − φ_A. In z (position to command, per unit K)::

    H(z) = z^{−d} [1 + β_B (1 − z^{−1}) F(z)],   F(z) = (1 − a) z^{−1}/(1 − a z^{−1})   (F = 1 without filter),

kept as H = (N₁ + β_B N₂)/(D_H z^d) (:class:`CommandPolynomials`).

Examples
--------
>>> Damper(2.0).group(period=1e-3, stiffness=1000.0)      # β_B = B/(K T)
2.0
>>> Damper.parameter.flag, Damper.parameter.units
('--virtual-damping', ('N·s/m', 'N·m·s/rad'))
>>> AmplifierLag.corner(0.5, quantized=True)
Traceback (most recent call last):
...
dfa.model.elements.NotCovered: no sound passivity criterion is proven with an amplifier lag (the force varies within a sample)
"""

from __future__ import annotations

import abc
import dataclasses
import enum
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar, Generic, NamedTuple, TypeVar

import numpy as np
import numpy.typing as npt

from ..checks import check_bool, check_delay, check_nonnegative, check_positive, check_real, format_value
from ..core import table as kt
from ..errors import DFAError, DFAValueError

__all__ = [
    "Coverage",
    "Covered",
    "Element",
    "ElementClass",
    "GroupRangeError",
    "Parameter",
    "FlagRow",
    "KernelBlock",
    "NotCovered",
    "CommandPolynomials",
    "unit_circle_w",
    "Damper",
    "VelocityFilter",
    "Delay",
    "AmplifierLag",
    "HandSpring",
    "OneSided",
    "Push",
    "PassivityController",
    "ForceLimit",
    "Travel",
    "largest_speed",
    "ELEMENTS",
    "ALWAYS_RECORDED",
    "MIN_CUTOFF",
    "MIN_LAG",
    "SWEEP_MAX_POINTS",
]

#: Smallest velocity-filter cutoff accepted, in cycles per sample (1 Hz at 1 kHz). Below it the filter pole
#: e^{−2πν_c} and the free mass's pole at z = 1 were too close to separate in powers of z: a red-team check found
#: the exact linear bound calling a stable loop "never stable" at ν_c = 1e-6 (verified stable with 60-digit roots).
#: The loop is now built in w = z − 1 (:class:`CommandPolynomials`), which keeps such poles apart; the floor stays
#: where the analyses have been validated (from 1e-3 to the Nyquist limit).
MIN_CUTOFF = 1.0e-3

#: Shortest amplifier lag α (samples) other than 0: 1/α is then a finite float (at 5e-324 the kernel's rate was
#: inf, a ZeroDivisionError compiled and NaN, "unstable", for a decaying loop in Python).
MIN_LAG = 1e-300

#: The largest float: a group above it is inf.
_FLOAT_MAX = 1.7976931348623157e308

#: Most stiffnesses one sweep of a K_max search simulates (:mod:`dfa.analysis.limits.kmax`); an element whose
#: runs cost more per sample lowers it (:attr:`Element.sweep_points`).
SWEEP_MAX_POINTS = 600

#: The type of an element's dimensionless group (float, int, or the passivity controller's (W, f_max)). Covariant:
#: a wall holds each element class beside its own group, as ``type[Element[object]]`` (:data:`ElementClass`),
#: the group validated by :meth:`Element.check_group` when the wall's groups are formed. A class hook taking the
#: group (``corner(g)``) is then typed with G as a parameter, which mypy flags for a covariant variable
#: (``type: ignore[misc]`` on the base's hooks only): each subclass's hook takes its own group type.
G = TypeVar("G", covariant=True)

#: A frequency response: a complex number for a scalar ω, an array of them for an array.
Response = complex | npt.NDArray[np.complex128]


class Coverage(enum.Flag):
    """What covers a wall: which analyses are sound for it (:meth:`Element.coverage`, :meth:`Covered.covers`).

    Examples
    --------
    >>> Damper.coverage(0.5).covers(Coverage.CRITERION | Coverage.LINEAR)
    True
    >>> Coverage.DESCRIBING_FUNCTION in OneSided.coverage(0.0).flags
    False
    """

    #: The passivity criterion (eq. 6 extended; :mod:`dfa.analysis.criterion`).
    CRITERION = enum.auto()
    #: The exact linear bound of the sampled loop (:mod:`dfa.analysis.linear_wall`).
    LINEAR = enum.auto()
    #: The describing function (harmonic balance on the linear loop's frequency response).
    DESCRIBING_FUNCTION = enum.auto()
    #: The Colgate–Schenkel condition (:mod:`dfa.analysis.colgate_schenkel`).
    COLGATE_SCHENKEL = enum.auto()
    #: The paper's closed forms for the spring with any delay (eq. 11, its Jury conditions) and the spring's
    #: compiled kernel (:mod:`dfa.core.kernel`), which runs such a loop fast.
    CLOSED_FORM = enum.auto()
    #: The exact simulation (:mod:`dfa.core.wall_kernel`): every registered element.
    SIMULATION = enum.auto()
    #: Runs that start at the wall's surface (the paper's impact ξ0 = 0 at V, the spring's preload) on a wall
    #: that holds the device on both sides. Without it every run starts with the approach from free space
    #: (:func:`dfa.analysis.approach.approach_start`), the criterion's speed is that approach's, and a run may leave
    #: the wall for good (:class:`OneSided`).
    SURFACE_START = enum.auto()
    #: Every analysis.
    ALL = CRITERION | LINEAR | DESCRIBING_FUNCTION | COLGATE_SCHENKEL | CLOSED_FORM | SIMULATION | SURFACE_START


@dataclass(frozen=True)
class Covered:
    """What covers an element or a wall (:class:`Coverage`) and, for each analysis that does not, why.

    Attributes
    ----------
    flags : Coverage
        The analyses that cover it.
    reasons : tuple of (Coverage, str)
        For each analysis missing from ``flags`` (one flag each), the first reason it does not cover it.
    """

    flags: Coverage = Coverage.ALL
    reasons: tuple[tuple[Coverage, str], ...] = ()

    def covers(self, what: Coverage) -> bool:
        """Tell whether every analysis of ``what`` covers it.

        Parameters
        ----------
        what : Coverage
            One analysis or several (``Coverage.LINEAR | Coverage.DESCRIBING_FUNCTION``).

        Returns
        -------
        bool
        """
        return what in self.flags

    def reason(self, what: Coverage) -> str | None:
        """Say why an analysis does not cover it.

        Parameters
        ----------
        what : Coverage
            One analysis.

        Returns
        -------
        str or None
            The first reason given for ``what``; None when it covers it.
        """
        for flag, why in self.reasons:
            if flag == what:
                return why
        return None

    def __and__(self, other: Covered) -> Covered:
        """What covers both: the common flags, and the first reason for each missing one."""
        flags = self.flags & other.flags
        known = {f for f, _ in self.reasons}
        reasons = self.reasons + tuple((f, r) for f, r in other.reasons if f not in known)
        return Covered(flags, tuple((f, r) for f, r in reasons if f not in flags))


class NotCovered(DFAError):
    """Raised by :meth:`Element.corner` for an element no sound passivity criterion covers; the message says why."""


#: Units of the quantities a group is formed with: (linear, rotary).
_K_UNITS, _T_UNITS, _D_UNITS = ("N/m", "N·m/rad"), ("s", "s"), ("m", "rad")


class GroupRangeError(DFAValueError):
    """An element's physical value is valid but its dimensionless group is not: it overflows a float (a damper of
    1e308 N·s/m over K T) or falls outside the group's rule (an amplifier lag far below a sample).

    The message names the physical value in its unit, the group, the quantities it is formed with and the value
    that would work; :meth:`dfa.model.wall.Wall.params` words it with the command line's flag
    (:meth:`message` with ``names``) and the units of a rotary device.

    Parameters
    ----------
    parameter : Parameter
        The element's parameter (name, units, group symbol).
    value : float
        The physical value (in the parameter's units).
    why : str
        What happens to the group, e.g. ``"overflows a float"``.
    inputs : tuple of (str, float, (str, str))
        The quantities the group is formed with: symbol, value, (linear unit, rotary unit).
    limit : float
        The value beyond which the group breaks (inf or 0: none worth giving).
    above : bool
        True when values above ``limit`` break it (give one below); False when values below do.
    hint : str
        The message's last words, in parentheses (default ``"check the units"``).
    """

    def __init__(
        self,
        parameter: Parameter,
        value: float,
        why: str,
        inputs: tuple[tuple[str, float, tuple[str, str]], ...],
        limit: float,
        above: bool = True,
        hint: str = "check the units",
    ) -> None:
        self.parameter, self.value, self.why, self.inputs = parameter, value, why, inputs
        self.limit, self.above, self.hint = limit, above, hint
        super().__init__(self.message())

    def message(self, names: dict[str, str] | None = None, rotary: bool = False) -> str:
        """The one-line message, naming the value by ``names`` (e.g. the flag: ``{"push": "--push"}``).

        Parameters
        ----------
        names : dict, optional
            How to call the parameter (default its name, ``push = 1e+308 N``; a flag gives ``--push 1e+308 N``).
        rotary : bool, optional
            Word the units of a rotary device (default linear).

        Returns
        -------
        str
        """
        par, i = self.parameter, int(bool(rotary))
        unit = par.units[i]
        name = (names or {}).get(par.name)
        shown = format_value(self.value)  # as typed: 5e-324, not 4.94066e-324
        subject = f"{name} {shown} {unit}" if name else f"{par.name} = {shown} {unit}"
        given = ", ".join(f"{sym} = {v:g} {units[i]}" for sym, v, units in self.inputs)
        side = "large" if self.above else "small"
        out = f"{subject} is too {side}: {par.symbol} {self.why} with {given}"
        if 0.0 < self.limit < math.inf:
            out += f"; give {name or par.name} in {unit} {'below' if self.above else 'above'} {self.limit:.3g}"
        return out + f" ({self.hint})"


class Parameter(NamedTuple):
    """An element's parameter: its name, physical units, flag and dimensionless group.

    ``name`` is the keyword of :meth:`dfa.model.wall.Wall.of` and of the element's constructor; ``units`` the
    unit of a linear and of a rotary device; ``flag`` and ``metavar`` its command-line option (one row of the
    flag table of :mod:`dfa.cli`); ``help`` what the option does; ``group`` the keyword of
    :meth:`dfa.model.wall.WallParams.of` and the JSON key of the group; ``symbol`` its definition.
    """

    name: str
    units: tuple[str, str]
    flag: str
    metavar: str
    help: str
    group: str
    symbol: str


class FlagRow(NamedTuple):
    """One command-line option of an element (a row of the flag table of :mod:`dfa.cli.flag_table`).

    ``metavar`` None makes it a switch (``store_true``); ``unit`` is what its number is read in (its
    messages' unit); ``whole`` reads whole samples instead (``--delay``), with ``default``; ``needs`` is the switch
    it describes (``--one-sided`` for ``--push``): given without it, the command refuses it.
    """

    flag: str
    dest: str
    metavar: str | None
    help: str
    unit: str = ""
    whole: bool = False
    default: object = None
    needs: str | None = None


class KernelBlock(NamedTuple):
    """An element's block of the wall's kernel table (:mod:`dfa.core.table`), for one group.

    ``code`` is the element's code (:attr:`Element.kernel_code`), ``params`` its float parameters
    (dimensionless: ticks, samples, KΔ) and ``state`` the floats of state it adds to the loop between samples.
    """

    code: int
    params: tuple[float, ...]
    state: int


@dataclass(frozen=True)
class CommandPolynomials:
    """The wall's command H(z) = (N₁ + β_B N₂)/(D_H z^d) as polynomials in w = z − 1 (highest power first).

    In w every factor z − r is w + (1 − r) with 1 − r computed without cancellation (``expm1``), and the
    coefficients of a product of such factors (0 <= r <= 1) are sums of positive terms: the loop's
    polynomials keep full relative accuracy where their roots cluster near z = 1 (slow filters and
    amplifiers), which the expanded powers of z lose (:mod:`dfa.analysis.linear_wall`).

    Attributes
    ----------
    spring, velocity, denominator : numpy.ndarray
        N₁, N₂ and D_H (without the delay) in w: the spring's path, the damper's path per unit β_B, their
        common denominator.
    damping : float
        β_B, the damper's gain (0: no damper; the velocity path then filters nothing).
    delay : int
        d, whole samples of computational delay.
    """

    spring: np.ndarray
    velocity: np.ndarray
    denominator: np.ndarray
    damping: float = 0.0
    delay: int = 0

    @classmethod
    def spring_only(cls) -> CommandPolynomials:
        """H(z) = 1 of the paper's spring: N₁ = z = w + 1, N₂ = z − 1 = w (the backward difference), D_H = z."""
        return cls(np.array([1.0, 1.0]), np.array([1.0, 0.0]), np.array([1.0, 1.0]))

    def response(self, omega: npt.ArrayLike) -> Response:
        """C(e^{jω}) = (N₁ + β_B N₂)/D_H at z = e^{jω} (the command without its delay), vectorised.

        Examples
        --------
        >>> CommandPolynomials.spring_only().response(0.3)
        (1+0j)
        """
        w = unit_circle_w(omega)
        out = np.polyval(self.numerator, w) / np.polyval(self.denominator, w)
        return complex(out) if np.ndim(out) == 0 else out

    @cached_property
    def numerator(self) -> np.ndarray:
        """N₁ + β_B N₂ in w (highest power first), formed once (the polynomials are frozen; read-only)."""
        out = np.polyadd(self.spring, self.damping * self.velocity)
        out.flags.writeable = False
        return out


def unit_circle_w(omega: npt.ArrayLike) -> Response:
    """w = e^{jω} − 1 = −2 sin²(ω/2) + j sin ω, without the cancellation of cos ω − 1 near ω = 0.

    Examples
    --------
    >>> unit_circle_w(1e-9)
    (-5e-19+1e-09j)
    """
    om = np.asarray(omega, dtype=float)
    out = -2.0 * np.sin(0.5 * om) ** 2 + 1j * np.sin(om)
    return complex(out) if np.ndim(out) == 0 else out


@dataclass(frozen=True)
class Element(abc.ABC, Generic[G]):
    """A block of a virtual wall in physical units (module docstring); subclasses define the hooks.

    A subclass is a frozen dataclass with one field, its physical parameter (:attr:`parameter` names it), and
    overrides the hooks that concern it; an override without a docstring takes the one of :class:`Element`.
    """

    #: The element's parameter (name, units, flag, dimensionless group).
    parameter: ClassVar[Parameter]
    #: Why the Colgate–Schenkel condition does not cover the element (None: it does).
    colgate_schenkel: ClassVar[str | None] = None
    #: Most stiffnesses a sweep of a K_max search simulates with this element in the wall.
    sweep_points: ClassVar[int] = SWEEP_MAX_POINTS
    #: The group's value when the element is absent (the wall's groups list every registered element).
    absent: ClassVar[object] = 0.0
    #: Whether the element's flag is a row of the wall's flag table (:mod:`dfa.cli.walls`).
    wall_flag: ClassVar[bool] = True
    #: Whether its group needs the encoder resolution Δ (``group(period, stiffness, resolution=Δ)``).
    needs_resolution: ClassVar[bool] = False
    #: Why the linear loop (exact linear bound, describing function) does not cover it (None: it does).
    linear_reason: ClassVar[str | None] = None
    #: Further analyses that cover no wall with this element whatever its group, each with the reason.
    never_covered: ClassVar[tuple[tuple[Coverage, str], ...]] = ()
    #: Its code in the wall's kernel table (:data:`dfa.core.table.CODES`), one per element class.
    kernel_code: ClassVar[int]
    #: Whether the firmware runs it (True: ``dfa export``'s C header implements it, :mod:`dfa.render.export`), or,
    #: a string, whose it is instead (the hardware's, the operator's): an export leaves it out and says so. Every
    #: element declares it (no default: an element the export does not know is refused, never dropped).
    firmware: ClassVar[bool | str]
    #: The device field (:data:`dfa.model.device.DEVICE_FIELDS`) whose value, when the device gives one, adds this
    #: element to every wall on the device that has none of its own (None: no device field); its constructor takes
    #: the value as its :attr:`parameter` (:func:`dfa.model.loop.device_elements`).
    device_field: ClassVar[str | None] = None
    #: Where a device's value goes: into the physical wall (True: its record and text show it, the force limit) or
    #: into the wall's groups only (False: the runs see it, the wall's record and text do not; its group must not
    #: depend on K, the travel).
    device_in_wall: ClassVar[bool] = True
    #: The physical value a wall's record gives for an element of :data:`ALWAYS_RECORDED` the wall does not have.
    recorded_absent: ClassVar[object] = None
    #: Why each of its keys in a record may be null, by key (the wall's record, :meth:`record`, and the groups',
    #: :meth:`group_json`): the records' ``null_reasons`` (:func:`dfa.jsonable.explain_nulls`).
    null_reasons: ClassVar[tuple[tuple[str, str], ...]] = ()

    def __init_subclass__(cls, **kwargs: object) -> None:
        super().__init_subclass__(**kwargs)
        for name, member in vars(cls).items():  # an undocumented override takes the protocol's docstring
            fn = getattr(member, "__func__", member)
            base = getattr(Element, name, None)
            if callable(fn) and not getattr(fn, "__doc__", None) and base is not None:
                fn.__doc__ = getattr(base, "__doc__", None)

    @property
    def value(self) -> object:
        """The physical parameter (:attr:`parameter` names it and its unit)."""
        return getattr(self, self.parameter.name)

    def _finite(self, group: float, inputs: tuple[tuple[str, float, tuple[str, str]], ...], scale: float) -> float:
        """``group`` = value/``scale`` (formed with ``inputs``), refused when it overflows a float
        (:class:`GroupRangeError`, naming the physical value and the largest that works)."""
        if math.isfinite(group):
            return group
        value = float(getattr(self, self.parameter.name))
        raise GroupRangeError(self.parameter, value, "overflows a float", inputs, _FLOAT_MAX * scale)

    def _per_force_step(self, symbol: str, stiffness: float, resolution: float | None) -> float:
        """The element's force (its :attr:`parameter`, in N) over the force step K Δ, unvalidated.

        ``symbol`` names the force in the group (F_p, F_max) for the error raised without a resolution.
        """
        name = self.parameter.name
        if resolution is None:
            raise DFAValueError(
                f"{name} needs the encoder resolution Δ for its group {symbol}/(K Δ): call "
                "Wall.params(period, resolution=Δ)"
            )
        step = stiffness * resolution
        inputs = (("K", stiffness, _K_UNITS), ("Δ", resolution, _D_UNITS))
        return self._finite(float(getattr(self, name)) / step, inputs, step)

    @abc.abstractmethod
    def group(self, period: float, stiffness: float) -> G:
        """Give the element's dimensionless group beside paper Table 1, validated.

        Parameters
        ----------
        period : float
            Sample period T in s.
        stiffness : float
            Virtual spring K in N/m (rotary: N·m/rad).

        Returns
        -------
        float or int
            The group (:attr:`parameter` gives its symbol).
        """

    @classmethod
    @abc.abstractmethod
    def check_group(cls, value: object) -> G:
        """Check a dimensionless group of this element.

        Parameters
        ----------
        value : float or int
            The group, e.g. β_B for a damper.

        Returns
        -------
        float or int
            The group, if valid.

        Raises
        ------
        DFAValueError, DFATypeError
            If it breaks the element's rule.
        """

    @classmethod
    def renders_nothing(cls, g: G) -> bool:  # type: ignore[misc]  # G is covariant (module note at G)
        """Tell whether the element with group ``g`` leaves the paper's spring unchanged (it is then left out).

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        bool
            True for a neutral group (β_B = 0, α = 0, d = 0).
        """
        return False

    @classmethod
    def spring_kernel(cls, g: G) -> bool:  # type: ignore[misc]  # G is covariant (module note at G)
        """Tell whether the spring's compiled kernel (:mod:`dfa.core.kernel`) runs the loop with this element.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        bool
            True when the spring's kernel covers it (a delay, or a neutral element).
        """
        return cls.renders_nothing(g)

    @classmethod
    def coverage(cls, g: G) -> Covered:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give what covers the wall with this element of group ``g``, and why the rest does not.

        The default reads the element's hooks: :meth:`corner` raising :class:`NotCovered` (the criterion),
        :meth:`class_coverage` (what the class decides alone) and :meth:`spring_kernel` (the closed forms); a
        neutral group (:meth:`renders_nothing`) covers all.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        Covered
        """
        if cls.renders_nothing(g):
            return Covered()
        reasons: list[tuple[Coverage, str]] = []
        try:
            cls.corner(g, quantized=True)
        except NotCovered as why:
            reasons.append((Coverage.CRITERION, str(why)))
        reasons += cls.class_coverage().reasons
        if not cls.spring_kernel(g):
            reasons.append(
                (
                    Coverage.CLOSED_FORM,
                    f"the paper's closed forms hold for the spring with a delay, not with a {cls.key().replace('_', ' ')}",
                )
            )
        flags = Coverage.ALL
        for flag, _ in reasons:
            flags &= ~flag
        return Covered(flags, tuple(reasons))

    @classmethod
    def class_coverage(cls) -> Covered:
        """Give what covers every wall with this element whatever its group, and why the rest does not.

        Read from the class alone: :attr:`linear_reason` (the exact linear bound and the describing function),
        :attr:`colgate_schenkel` and :attr:`never_covered`; the criterion and the closed forms depend on the group
        (:meth:`coverage`) and are not ruled out here.

        Returns
        -------
        Covered

        Examples
        --------
        >>> Coverage.SURFACE_START in OneSided.class_coverage().flags
        False
        """
        reasons: list[tuple[Coverage, str]] = []
        if cls.linear_reason:
            reasons += [(Coverage.LINEAR, cls.linear_reason), (Coverage.DESCRIBING_FUNCTION, cls.linear_reason)]
        if cls.colgate_schenkel:
            reasons.append((Coverage.COLGATE_SCHENKEL, cls.colgate_schenkel))
        reasons += cls.never_covered
        flags = Coverage.ALL
        for flag, _ in reasons:
            flags &= ~flag
        return Covered(flags, tuple(reasons))

    @classmethod
    def corner(cls, g: G, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give what the element adds to the corner (β₀, σ₀) of the passivity criterion (eq. 6 extended).

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.
        quantized : bool
            With the encoder (True) or without (False: no quantization term in σ₀).
        velocity_gain : float, optional
            The product of the wall's :meth:`velocity_gain` (1 − a with a filter, 1 without).

        Returns
        -------
        tuple of float
            (Δβ₀, Δσ₀).

        Raises
        ------
        NotCovered
            When no sound criterion covers the element (the message says why).
        """
        return 0.0, 0.0

    @classmethod
    def criterion_beside(cls, g: G, others: tuple[type[Element[object]], ...]) -> str | None:  # type: ignore[misc]  # G is covariant (module note at G)
        """Say why the passivity criterion does not cover the element beside the wall's other elements.

        :meth:`corner` judges the element alone; an element whose proof holds only with some others (the force
        limit: the spring alone) says here why not with ``others``.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.
        others : tuple of element classes
            The wall's other elements that render something.

        Returns
        -------
        str or None
            The reason; None (the default) when the element's corner holds beside any others.
        """
        return None

    @classmethod
    def velocity_gain(cls, g: G) -> float:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the element's factor on the quantization part of the damper's input (Abel summation).

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        float
            1 − a for a velocity filter of pole a; 1 for an element off the velocity path.
        """
        return 1.0

    @classmethod
    @abc.abstractmethod
    def kernel_block(cls, g: G) -> KernelBlock:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the element's block of the wall's kernel table (:mod:`dfa.core.table`).

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        KernelBlock
            Its :attr:`kernel_code`, its float parameters (the table's column for that code) and its state size.
        """

    @classmethod
    def command(cls, g: G, h: CommandPolynomials) -> CommandPolynomials:  # type: ignore[misc]  # G is covariant (module note at G)
        """Apply the element to the wall's command H(z) (module docstring).

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.
        h : CommandPolynomials
            H(z) of the elements applied before it.

        Returns
        -------
        CommandPolynomials
            H(z) with this element; the default leaves it unchanged.
        """
        return h

    @classmethod
    def plant(cls, g: G, rate: float, mu: float) -> tuple[np.ndarray, np.ndarray] | None:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the exact ZOH plant with this element between hold and device, or acting on the device.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.
        rate : float
            The device's rate a = β/μ = bT/m (per sample).
        mu : float
            The dimensionless mass μ = m/(K T²) at the stiffness K of ``g`` (a hand spring's ω² = κ_h/μ).

        Returns
        -------
        tuple of numpy.ndarray, or None
            (N_G, D_G) in w = z − 1 (:class:`CommandPolynomials`), G(z) = N_G/(μ D_G); None for an element off
            the plant.
        """
        return None

    @classmethod
    def low_frequency_delay(cls, g: G) -> float:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the samples of delay the element adds at low frequency.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        float
            The delay in samples (d for a delay, α for an amplifier lag, 0 otherwise).
        """
        return 0.0

    @classmethod
    def plant_response(cls, g: G, omega: npt.ArrayLike) -> Response:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the element's continuous factor between hold and device.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.
        omega : float or array_like
            Angular frequency ω in rad per sample.

        Returns
        -------
        complex or numpy.ndarray
            1 unless the element sits between hold and device.
        """
        return 1.0

    @classmethod
    def zoh_response(cls, g: G, mu: float, beta: npt.ArrayLike, omega: npt.ArrayLike) -> Response | None:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the exact ZOH plant's response with this element between hold and device, if it sits there.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.
        mu : float
            Dimensionless mass μ = m/(K T²).
        beta : float or array_like
            The (equivalent) dimensionless damping β.
        omega : float or array_like
            Angular frequency ω in rad per sample.

        Returns
        -------
        complex, numpy.ndarray or None
            G(e^{jω}) of hold, element and device; None for an element off the plant.
        """
        return None

    @classmethod
    def group_json(cls, g: G) -> dict[str, object]:  # type: ignore[misc]  # G is covariant (module note at G)
        """Give the element's group as JSON-able entries of :meth:`dfa.model.wall.WallParams.to_dict`.

        Parameters
        ----------
        g : float or int
            The element's dimensionless group.

        Returns
        -------
        dict
            ``{parameter.group: g}`` unless the element writes its group otherwise.
        """
        return {cls.parameter.group: g}

    def to_dict(self) -> dict[str, object]:
        """Give the element as JSON-able data.

        Returns
        -------
        dict
            Its key (:meth:`key`), physical value and unit (of a linear device).
        """
        return {"element": type(self).key(), self.parameter.name: self.value, "unit": self.parameter.units[0]}

    @classmethod
    def from_dict(cls, data: Mapping[str, object]) -> Element[object]:
        """Give the element of :meth:`to_dict`'s data, its class found by its key in :data:`ELEMENTS`.

        Parameters
        ----------
        data : mapping
            ``{"element": key, <field>: value, ...}`` (a ``unit`` entry is ignored).

        Returns
        -------
        Element

        Examples
        --------
        >>> Element.from_dict(Damper(2.0).to_dict())
        Damper(damping=2.0)
        """
        kind = data.get("element")
        registry = {k.key(): k for k in ELEMENTS}
        if kind not in registry:
            raise DFAValueError(
                f"element = {format_value(kind)} is invalid: it is no registered wall element; give one of "
                f"{', '.join(registry)}"
            )
        found = registry[str(kind)]
        names = [f.name for f in dataclasses.fields(found)]
        return found(**{n: data[n] for n in names if n in data})

    @classmethod
    def from_record(cls, data: Mapping[str, object]) -> Element[object] | None:
        """Give the element a wall's record holds (:meth:`dfa.model.wall.Wall.to_dict`), by its :attr:`record_keys`.

        Parameters
        ----------
        data : mapping
            A wall's record.

        Returns
        -------
        Element or None
            None when the record has none of the element's keys, a None value, or a neutral one (a damper of 0).
        """
        kwargs = {name: data[key] for key, name in cls.record_keys() if key in data}
        if not kwargs or (len(cls.record_keys()) == 1 and None in kwargs.values()):
            return None
        out = cls(**kwargs)
        return None if out.value == cls.absent else out

    @classmethod
    def record_keys(cls) -> tuple[tuple[str, str], ...]:
        """Give the keys of the element in a wall's record and the field each gives.

        Returns
        -------
        tuple of (str, str)
            (record key, constructor keyword); default its parameter's name for both.
        """
        return ((cls.parameter.name, cls.parameter.name),)

    def record(self) -> dict[str, object]:
        """Give the element's entries in a wall's record (:meth:`dfa.model.wall.Wall.to_dict`).

        Returns
        -------
        dict
            ``{record key: value}`` for each of :meth:`record_keys` (physical units); :meth:`from_record` reads it.
        """
        return {key: getattr(self, name) for key, name in type(self).record_keys()}

    @classmethod
    def absent_record(cls) -> dict[str, object]:
        """Give the entries a wall's record holds for the element when the wall has none (:data:`ALWAYS_RECORDED`).

        Returns
        -------
        dict
            ``{record key: recorded_absent}`` for each of :meth:`record_keys`.
        """
        return {key: cls.recorded_absent for key, _ in cls.record_keys()}

    @classmethod
    def group_from_dict(cls, data: Mapping[str, object]) -> object | None:
        """Give the element's group from :meth:`dfa.model.wall.WallParams.to_dict` (the inverse of :meth:`group_json`).

        Parameters
        ----------
        data : mapping
            The groups' record.

        Returns
        -------
        object or None
            The group; None when absent.
        """
        return data.get(cls.parameter.group)

    @classmethod
    def flag_rows(cls) -> tuple[FlagRow, ...]:
        """Give the element's command-line options (:mod:`dfa.cli.walls` builds the flag table from them).

        Returns
        -------
        tuple of FlagRow
            Default: its parameter's flag, read in its unit.
        """
        par = cls.parameter
        unit = par.units[0] if par.units[0] == par.units[1] else f"{par.units[0]} (rotary: {par.units[1]})"
        return (FlagRow(par.flag, par.flag.lstrip("-").replace("-", "_"), par.metavar, par.help, unit),)

    @classmethod
    def key(cls) -> str:
        """Give the element's name in outputs.

        Returns
        -------
        str
            Its class name in snake_case (``velocity_filter``).
        """
        name = cls.__name__
        return "".join("_" + c.lower() if c.isupper() and i else c.lower() for i, c in enumerate(name))


# ----------------------------------------------------------------------------- the built-in elements
@dataclass(frozen=True)
class Delay(Element[int]):
    """A computational delay of d whole samples: the force of sample h uses the reading of sample h − d.

    Adds d to β₀ (Diolaiti et al. 2006), z^{−d} to H(z), and ``delay`` to the simulator.

    Attributes
    ----------
    delay : int
        Computational delay d in whole samples, >= 0.

    Examples
    --------
    >>> Delay(2).group(1e-3, 500.0), Delay.corner(2, quantized=True)
    (2, (2.0, 0.0))
    """

    delay: int
    kernel_code: ClassVar[int] = kt.DELAY
    firmware: ClassVar[bool | str] = True
    parameter: ClassVar[Parameter] = Parameter(
        "delay", ("samples", "samples"), "--delay", "D",
        "computational delay in whole samples: the force of sample h uses the reading of sample h − D (default 0)",
        "delay", "d",
    )  # fmt: skip
    absent: ClassVar[object] = 0
    recorded_absent: ClassVar[object] = 0

    def __post_init__(self) -> None:
        object.__setattr__(self, "delay", check_delay(self.delay))

    @classmethod
    def flag_rows(cls) -> tuple[FlagRow, ...]:
        par = cls.parameter
        return (FlagRow(par.flag, "delay", par.metavar, par.help, "samples", whole=True, default=0),)

    def group(self, period: float, stiffness: float) -> int:
        return self.delay

    @classmethod
    def check_group(cls, value: object) -> int:
        return check_delay(value)

    @classmethod
    def renders_nothing(cls, g: int) -> bool:
        return g == 0

    @classmethod
    def spring_kernel(cls, g: int) -> bool:
        return True  # the spring kernel keeps a ring of pending readings

    @classmethod
    def corner(cls, g: int, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        return float(g), 0.0

    @classmethod
    def kernel_block(cls, g: int) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), int(g))  # the d pending commands

    @classmethod
    def command(cls, g: int, h: CommandPolynomials) -> CommandPolynomials:
        return CommandPolynomials(h.spring, h.velocity, h.denominator, h.damping, h.delay + int(g))

    @classmethod
    def low_frequency_delay(cls, g: int) -> float:
        return float(g)


@dataclass(frozen=True)
class Damper(Element[float]):
    """A virtual damper B on the backward-difference velocity of the quantized position (N·s/m; N·m·s/rad).

    Group β_B = B/(K T). Adds β_B to β₀ and β_B times the velocity path's quantization gain to σ₀ (the
    criterion's steps 3-4, :mod:`dfa.analysis.criterion`); β_B (1 − z^{−1}) F(z) to H(z).

    Attributes
    ----------
    damping : float
        Virtual damper B in N·s/m (rotary: N·m·s/rad), >= 0.

    Examples
    --------
    >>> Damper.corner(0.3, quantized=True), Damper.corner(0.3, quantized=True, velocity_gain=0.5)
    ((0.3, 0.3), (0.3, 0.15))
    """

    damping: float
    kernel_code: ClassVar[int] = kt.DAMPER
    firmware: ClassVar[bool | str] = True
    parameter: ClassVar[Parameter] = Parameter(
        "damping", ("N·s/m", "N·m·s/rad"), "--virtual-damping", "B",
        "virtual damper B >= 0 in N·s/m (rotary: N·m·s/rad) on the backward-difference velocity (default: none)",
        "damping", "β_B = B/(K T)",
    )  # fmt: skip
    recorded_absent: ClassVar[object] = 0.0

    def __post_init__(self) -> None:
        fix = "give the virtual damping B in N·s/m (0 for none)"
        object.__setattr__(self, "damping", check_nonnegative("damping", self.damping, fix))

    def group(self, period: float, stiffness: float) -> float:
        kt = stiffness * period
        return self._finite(self.damping / kt, (("K", stiffness, _K_UNITS), ("T", period, _T_UNITS)), kt)

    @classmethod
    def check_group(cls, value: object) -> float:
        return check_nonnegative("damping", value, "β_B = B/(K T) cannot be negative")

    @classmethod
    def renders_nothing(cls, g: float) -> bool:
        return g == 0.0

    @classmethod
    def corner(cls, g: float, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        return float(g), (velocity_gain * float(g) if quantized else 0.0)

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)

    @classmethod
    def command(cls, g: float, h: CommandPolynomials) -> CommandPolynomials:
        return CommandPolynomials(h.spring, h.velocity, h.denominator, float(g), h.delay)


def _check_cutoff(name: str, value: object, nyquist: float, unit: str) -> float:
    """A filter cutoff: MIN_CUTOFF·(2·nyquist) <= value < nyquist, in ``unit`` (Hz, or cycles per sample)."""
    out = check_positive(name, value, f"give the velocity-filter cutoff in {unit}, or no filter")
    floor = MIN_CUTOFF * 2.0 * nyquist  # 2·nyquist = samples per unit of the cutoff (1 or 1/T)
    per_sample = "" if unit == "cycles per sample" else f"{MIN_CUTOFF:g} cycles per sample; "
    if out < floor * (1 - 1e-12):  # the floor as printed (6 digits) is accepted despite rounding
        raise DFAValueError(
            f"{name} = {format_value(out)} is invalid: it must be at least {floor:.6g} {unit} ({per_sample}below, the filter "
            "pole lies so close to the free mass's pole at z = 1 that the linear analysis has not been validated "
            f"there); give a cutoff of at least {floor:.6g} {unit}, or no filter"
        )
    if not out < nyquist:
        raise DFAValueError(
            f"{name} = {format_value(out)} is invalid: it must be below the Nyquist frequency {format_value(nyquist)} {unit}; "
            "give a cutoff below the Nyquist frequency 1/(2T), or no filter (None)"
        )
    return out


@dataclass(frozen=True)
class VelocityFilter(Element[float]):
    """A first-order low-pass of cutoff f_c (Hz) on the damper's velocity, discretised exactly (ZOH).

    y_h = a y_{h−1} + (1 − a) v_{h−1}, a = e^{−2π f_c T} (``control.c2d(..., "zoh")`` of ω_c/(s + ω_c)), so
    the filter adds its own one-sample lag. Group ν_c = f_c T (cycles per sample), MIN_CUTOFF <= ν_c < ½.
    It multiplies the damper's path by F(z) = (1 − a)/(z − a) and the damper's quantization part by 1 − a
    (so σ₀ gains (1 − a)β_B); without a damper it filters nothing and is left out of the linear loop.

    Attributes
    ----------
    filter_cutoff : float
        Cutoff f_c in Hz, below the Nyquist frequency 1/(2T) of the device it runs on.

    Examples
    --------
    >>> round(VelocityFilter.pole(0.1), 6), round(VelocityFilter.velocity_gain(0.1), 6)
    (0.533488, 0.466512)
    """

    filter_cutoff: float
    kernel_code: ClassVar[int] = kt.FILTER
    firmware: ClassVar[bool | str] = True
    parameter: ClassVar[Parameter] = Parameter(
        "filter_cutoff", ("Hz", "Hz"), "--velocity-filter", "HZ",
        "cutoff in Hz of a first-order low-pass on the velocity, below the Nyquist frequency 1/(2T) "
        "(default: no filter)",
        "cutoff", "ν_c = f_c T",
    )  # fmt: skip
    absent: ClassVar[object] = None
    null_reasons: ClassVar[tuple[tuple[str, str], ...]] = (
        ("filter_cutoff", "no velocity filter"), ("cutoff", "no velocity filter")
    )  # fmt: skip

    def __post_init__(self) -> None:
        fix = "give the cutoff in Hz, or None for no filter"
        object.__setattr__(self, "filter_cutoff", check_positive("filter_cutoff", self.filter_cutoff, fix))

    def group(self, period: float, stiffness: float) -> float:
        return _check_cutoff("filter_cutoff", self.filter_cutoff, 0.5 / period, "Hz") * period

    @classmethod
    def check_group(cls, value: object) -> float:
        return _check_cutoff("cutoff", value, 0.5, "cycles per sample")

    @staticmethod
    def pole(g: float) -> float:
        """Give the filter's pole.

        Parameters
        ----------
        g : float
            The cutoff ν_c = f_c T in cycles per sample.

        Returns
        -------
        float
            The pole a = e^{−2πν_c}.
        """
        return math.exp(-2.0 * math.pi * g)

    @staticmethod
    def pole_gap(g: float) -> float:
        """Give 1 − a_f = −expm1(−2πν_c), without cancellation for a slow filter (a_f near 1).

        Parameters
        ----------
        g : float
            The cutoff ν_c = f_c T in cycles per sample.

        Returns
        -------
        float
            1 − a_f, the gap between the filter's pole and z = 1.

        Examples
        --------
        >>> round(VelocityFilter.pole_gap(1e-12) / (2e-12 * math.pi), 9)   # 1 − e^{−x} = x(1 − x/2 + …)
        1.0
        """
        return -math.expm1(-2.0 * math.pi * g)

    @classmethod
    def velocity_gain(cls, g: float) -> float:
        return cls.pole_gap(g)

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (cls.pole(g),), 2)  # y_{h−1}, v_{h−1}

    @classmethod
    def command(cls, g: float, h: CommandPolynomials) -> CommandPolynomials:
        if h.damping == 0.0:  # a filter without a damper filters nothing: its own mode is no pole of the loop
            return h
        gap = cls.pole_gap(g)  # z − a_f = w + (1 − a_f)
        return CommandPolynomials(
            np.polymul(h.spring, [1.0, gap]), np.polymul(h.velocity, [gap]), np.polymul(h.denominator, [1.0, gap]),
            h.damping, h.delay,
        )  # fmt: skip


@dataclass(frozen=True)
class AmplifierLag(Element[float]):
    """A current amplifier of bandwidth f_bw (Hz): a first-order lag τ_a = 1/(2π f_bw) between hold and device.

    τ_a dF_A/dt = F_cmd − F_A within each sample; group α = τ_a/T (samples), 0 or >= MIN_LAG. The force then
    varies within a sample, which neither the criterion (eq. 6 extended) nor Colgate–Schenkel covers.

    Attributes
    ----------
    amplifier_bandwidth : float
        Bandwidth f_bw in Hz, > 0.

    Examples
    --------
    >>> round(AmplifierLag(1000.0).group(1e-3, 1.0), 6)
    0.159155
    """

    amplifier_bandwidth: float
    kernel_code: ClassVar[int] = kt.LAG
    firmware: ClassVar[bool | str] = "the current amplifier's lag (hardware)"
    parameter: ClassVar[Parameter] = Parameter(
        "amplifier_bandwidth", ("Hz", "Hz"), "--amplifier-bandwidth", "HZ",
        "bandwidth in Hz of the current amplifier, a first-order lag τ_a = 1/(2π f_bw) (default: ideal)",
        "lag", "α = τ_a/T",
    )  # fmt: skip
    colgate_schenkel: ClassVar[str | None] = (
        "the Colgate–Schenkel condition assumes the zero-order hold drives the device directly"
    )
    #: With an amplifier lag a run costs about 18 times the spring's per sample (reports/benchmarks.md).
    sweep_points: ClassVar[int] = 150
    null_reasons: ClassVar[tuple[tuple[str, str], ...]] = (("amplifier_bandwidth", "ideal amplifier (no lag)"),)

    def __post_init__(self) -> None:
        fix = "give the amplifier bandwidth in Hz, or None for an ideal amplifier"
        object.__setattr__(
            self, "amplifier_bandwidth", check_positive("amplifier_bandwidth", self.amplifier_bandwidth, fix)
        )

    @property
    def time_constant(self) -> float:
        """The time constant τ_a = 1/(2π f_bw) in s."""
        return 1.0 / (2.0 * math.pi * self.amplifier_bandwidth)

    def group(self, period: float, stiffness: float) -> float:
        a = 1.0 / (2.0 * math.pi) / self.amplifier_bandwidth / period  # α = 1/(2π f_bw T), no product overflowing
        inputs = (("T", period, _T_UNITS),)
        if not math.isfinite(a):
            least = 1.0 / (2.0 * math.pi) / _FLOAT_MAX / period
            raise GroupRangeError(self.parameter, self.amplifier_bandwidth, "overflows a float", inputs, least, False)
        if a < MIN_LAG:  # also 0: a lag that underflows is no lag, not silently none
            why = f"= {a:.3g} samples is below the shortest lag, {MIN_LAG:g} samples,"
            top = 1.0 / (2.0 * math.pi) / MIN_LAG / period
            hint = "a lag this short is no lag: an ideal amplifier has no bandwidth given"
            raise GroupRangeError(self.parameter, self.amplifier_bandwidth, why, inputs, top, hint=hint)
        return self.check_group(a)

    @classmethod
    def check_group(cls, value: object) -> float:
        a = check_nonnegative("lag", value, "α = τ_a/T cannot be negative (0: none)")
        if 0.0 < a < MIN_LAG:
            raise DFAValueError(
                f"lag = {format_value(a)} is invalid: it must be 0 or at least {format_value(MIN_LAG)} samples (the kernel's rate "
                "1/α must stay finite); a lag this short is no lag: pass 0 (or no amplifier bandwidth)"
            )
        return a

    @classmethod
    def renders_nothing(cls, g: float) -> bool:
        return g == 0.0

    @classmethod
    def corner(cls, g: float, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        raise NotCovered(
            "no sound passivity criterion is proven with an amplifier lag (the force varies within a sample)"
        )

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 1)  # φ_A

    @classmethod
    def plant(cls, g: float, rate: float, mu: float) -> tuple[np.ndarray, np.ndarray] | None:
        if g == 0.0 or not math.isfinite(1.0 / g):  # 1/α overflowing: the lag is below rounding
            return None
        from ..core.zohlag import amplifier_zoh  # the one implementation, compiled

        n2, n1, n0, _p, _q = (float(x) for x in amplifier_zoh(float(rate), 1.0 / g))
        # in w = z − 1: N_G(w + 1) (sums of positive terms) and D_G = w (w + 1 − p)(w + 1 − q)
        gaps = np.polymul([1.0, -math.expm1(-float(rate))], [1.0, -math.expm1(-1.0 / g)])
        return np.array([n2, 2.0 * n2 + n1, n2 + n1 + n0]), np.polymul([1.0, 0.0], gaps)

    @classmethod
    def low_frequency_delay(cls, g: float) -> float:
        return float(g)

    @classmethod
    def plant_response(cls, g: float, omega: npt.ArrayLike) -> Response:
        return 1.0 / (1.0 + 1j * np.asarray(omega, dtype=float) * g)

    @classmethod
    def zoh_response(cls, g: float, mu: float, beta: npt.ArrayLike, omega: npt.ArrayLike) -> Response | None:
        from ..core.zohlag import zoh_lag_response  # the one implementation, compiled

        return zoh_lag_response(mu, beta, omega, g)


@dataclass(frozen=True)
class HandSpring(Element[float]):
    """The stiffness k_h of a hand holding the device, a spring to a fixed reference at the wall's origin.

    The hand's mass and damping move with the device (:meth:`dfa.Device.holding`); its stiffness acts on the
    device in continuous time, beside the wall's held force: μ ξ'' + β ξ' + κ_h ξ + σ sgn ξ' = φ
    (:mod:`dfa.core.oscillator`), group κ_h = k_h/K. The spring stores ½κ_h ξ² and neither generates nor
    dissipates energy, so the criterion's corner (β₀, σ₀) is unchanged and its storage gains ½κ_h ξ²
    (:mod:`dfa.analysis.criterion`); Colgate–Schenkel's condition is the wall's passivity, which a passive
    hand does not change. The plant of the exact linear bound is the ZOH of 1/(μs² + βs + κ_h): with h, H of
    :func:`dfa.core.oscillator.responses` at t = 1 (λ = a = β/μ, ω² = κ_h/μ) the state transition is
    Φ = [[1 − ω²H, h], [−ω²h, h']], Γ = [H, h]/μ, and with 1 − h' = λh + ω²H (positive terms)::

        N_G = H w + H(λh + ω²H) + h²,   D_G = w² + (λh + 2ω²H) w + ω² N_G(0)     (w = z − 1, G(1) = 1/κ_h)

    which at κ_h → 0 are the device's c₁ w + c₁ + c₀ and w(w + 1 − e^{−a}) (:mod:`dfa.core.zoh`).

    Its flag, ``--hand-stiffness``, belongs to the hand's group of the command line (with ``--hand PRESET``).

    Attributes
    ----------
    hand_stiffness : float
        Hand stiffness k_h in N/m (rotary: N·m/rad), >= 0.

    Examples
    --------
    >>> HandSpring(135.0).group(1e-3, 1350.0), HandSpring.corner(0.1, quantized=True)
    (0.1, (0.0, 0.0))
    """

    hand_stiffness: float
    kernel_code: ClassVar[int] = kt.HAND
    firmware: ClassVar[bool | str] = "the hand's stiffness (the operator)"
    parameter: ClassVar[Parameter] = Parameter(
        "hand_stiffness", ("N/m", "N·m/rad"), "--hand-stiffness", "X",
        "hand stiffness k_h to a fixed reference at the wall's origin, in N/m (rotary: N·m/rad) (default: none)",
        "hand_stiffness", "κ_h = k_h/K",
    )  # fmt: skip
    #: Its flag is the hand group's (:mod:`dfa.cli.inputs`), not a row of the wall's flag table.
    wall_flag: ClassVar[bool] = False

    def __post_init__(self) -> None:
        fix = "give the hand stiffness k_h in N/m (0 for none)"
        object.__setattr__(self, "hand_stiffness", check_nonnegative("hand_stiffness", self.hand_stiffness, fix))

    def group(self, period: float, stiffness: float) -> float:
        g = self._finite(self.hand_stiffness / stiffness, (("K", stiffness, _K_UNITS),), stiffness)
        return self.check_group(g)

    @classmethod
    def check_group(cls, value: object) -> float:
        return check_nonnegative("hand_stiffness", value, "κ_h = k_h/K cannot be negative (0: no hand stiffness)")

    @classmethod
    def renders_nothing(cls, g: float) -> bool:
        return g == 0.0

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)

    @classmethod
    def plant(cls, g: float, rate: float, mu: float) -> tuple[np.ndarray, np.ndarray] | None:
        # the class docstring's N_G, D_G (the state transition over one sample)
        if g == 0.0:
            return None
        from ..core.oscillator import responses  # the simulator's own closed form, compiled

        w2 = float(g) / mu
        h, hp, big = (float(x) for x in responses(float(rate), w2, 1.0))
        one_minus = float(rate) * h + w2 * big  # 1 − h'
        n0 = big * one_minus + h * h
        return np.array([big, n0]), np.array([1.0, float(rate) * h + 2.0 * w2 * big, w2 * n0])

    @classmethod
    def zoh_response(cls, g: float, mu: float, beta: npt.ArrayLike, omega: npt.ArrayLike) -> Response | None:
        # G(e^{jω}) = N_G/(μ D_G) of plant(), vectorised over β (and ω) for the harmonic balance
        if g == 0.0:
            return None
        from ..core.oscillator import responses_array  # the simulator's own closed form, compiled

        b, om = np.broadcast_arrays(np.asarray(beta, dtype=float), np.asarray(omega, dtype=float))
        rate = b / mu
        w2 = float(g) / mu
        h, _hp, big = responses_array(rate, w2)
        n0 = big * (rate * h + w2 * big) + h * h
        w = unit_circle_w(om)
        out = (big * w + n0) / (mu * (w * w + (rate * h + 2.0 * w2 * big) * w + w2 * n0))
        return complex(out) if np.ndim(out) == 0 else out


def largest_speed(speed_of: Callable[[float], float], equivalent: float) -> float:
    """Give the largest speed V in [0, ``equivalent``] whose ``speed_of(V)`` is at most ``equivalent``.

    For a criterion whose speed V* = ``speed_of(V)`` grows with the speed of interest V and is never below it
    (a one-sided wall's approach, a moving history): bisection to the last double, one implementation.

    Parameters
    ----------
    speed_of : callable
        V ↦ V*, non-decreasing, V* >= V.
    equivalent : float
        The largest V* allowed (the criterion's critical speed), >= 0.

    Returns
    -------
    float
        V; 0 when not even ``speed_of(0)`` is within.

    Examples
    --------
    >>> largest_speed(lambda v: 2.0 * v, 3.0)
    1.5
    """
    lo, hi = 0.0, float(equivalent)
    if speed_of(hi) <= equivalent:
        return hi
    if not speed_of(lo) <= equivalent:
        return 0.0
    while True:
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            return lo
        lo, hi = (mid, hi) if speed_of(mid) <= equivalent else (lo, mid)


_ONE_SIDED_LINEAR = (
    "a one-sided wall is not a linear loop (it pushes only inside and is zero outside): the exact linear bound, "
    "Colgate–Schenkel and the describing function do not cover it; the exact simulation does"
)

_ONE_SIDED_START = (
    "a one-sided wall holds the device only in contact: every run starts with the approach from free space and "
    "may leave the wall for good"
)


@dataclass(frozen=True)
class OneSided(Element[float]):
    """A one-sided wall: it pushes only while the reading is beyond the surface, and is zero outside.

    With the surface at s ticks of the encoder grid (default 0, the paper's origin; the wall occupies ξ > s) the
    wall reads q_h = ⌊ξ_h⌋ + ½ (ξ_h without the encoder) and commands, d samples later,
    φ = min(0, −(q_h − s) − β_B y_h) while q_h > s, and 0 otherwise: it never pulls (a damper's pull on the way
    out is cut at 0). The device arrives from free space (:func:`dfa.analysis.approach.approach_start`), and may
    leave the wall for good (outcome ``left``). The simulator runs it exactly (:mod:`dfa.core.wall_kernel`).

    The criterion covers it with a delay, a push and a hand stiffness (no damper, filter or amplifier lag), for an
    approach at V (:mod:`dfa.analysis.criterion`, "A one-sided wall"): the corner (½ + d, ½) at the speed V*
    of :meth:`contact_speed` (V' = √(V² + ε²/μ) alone, ε = :meth:`contact_excess`). The linear bound and the
    describing function do not cover it (not a linear loop), and say so.

    Attributes
    ----------
    surface : float
        The surface's position s in encoder ticks (a fraction of a tick places it within the grid), default 0.

    Examples
    --------
    >>> OneSided().group(1e-3, 1000.0), OneSided.kernel_block(0.25)
    (0.0, KernelBlock(code=6, params=(0.25,), state=0))
    """

    surface: float = 0.0
    kernel_code: ClassVar[int] = kt.ONE_SIDED
    firmware: ClassVar[bool | str] = True
    parameter: ClassVar[Parameter] = Parameter(
        "surface", ("ticks", "ticks"), "--surface", "TICKS",
        "with --one-sided: the surface's position in encoder ticks (default 0, the paper's origin)",
        "one_sided", "s (ticks)",
    )  # fmt: skip
    colgate_schenkel: ClassVar[str | None] = _ONE_SIDED_LINEAR
    #: Its flags (--one-sided, --surface) are the contact group's (:mod:`dfa.cli.contact`).
    wall_flag: ClassVar[bool] = False
    absent: ClassVar[object] = None
    #: Why the linear loop (exact linear bound, describing function) does not cover the element.
    linear_reason: ClassVar[str | None] = _ONE_SIDED_LINEAR
    never_covered: ClassVar[tuple[tuple[Coverage, str], ...]] = ((Coverage.SURFACE_START, _ONE_SIDED_START),)

    def __post_init__(self) -> None:
        object.__setattr__(self, "surface", self.check_group(self.surface))

    @classmethod
    def record_keys(cls) -> tuple[tuple[str, str], ...]:
        return (("one_sided_surface", "surface"),)

    def record(self) -> dict[str, object]:
        """Give the one-sided wall's entries in a wall's record (:meth:`Element.record`).

        Returns
        -------
        dict
            Its surface and the push, 0 until a :class:`Push` of the wall gives its own.
        """
        return {"one_sided_surface": self.surface, "push": 0.0}

    @classmethod
    def flag_rows(cls) -> tuple[FlagRow, ...]:
        switch = FlagRow(
            "--one-sided", "one_sided", None,
            "a one-sided wall reached from free space: it pushes only while the reading is beyond the surface "
            "and never pulls; the run starts in free space before contact (default: bilateral)",
        )  # fmt: skip
        par = cls.parameter
        return (switch, FlagRow(par.flag, "surface", par.metavar, par.help, "ticks", needs=switch.flag))

    def group(self, period: float, stiffness: float) -> float:
        return self.surface

    @classmethod
    def check_group(cls, value: object) -> float:
        return check_real("surface", value, "give the surface's position in encoder ticks (0: the paper's origin)")

    @classmethod
    def corner(cls, g: float, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        return 0.0, 0.0  # the spring's corner; only alone (dfa.model.wall.WallParams.uncovered), see the class

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)

    @staticmethod
    def contact_excess(surface: float, speed: float, quantized: bool = True) -> float:
        """Give the most the storage ½((ξ − s)⁺)² holds at the first reading inside, as a length ε (ticks).

        The device reaches the first position the wall sees, ξ_e = ⌊s + ½⌋ (s without the encoder), moving at V:
        at the first reading inside it is less than a sample's travel beyond it, so ε = (ξ − s)⁺ < ξ_e − s + V.

        Parameters
        ----------
        surface : float
            The surface s in ticks.
        speed : float
            The impact speed V in ticks per sample.
        quantized : bool, optional
            With the encoder (default).

        Returns
        -------
        float
            The length ε >= 0 in ticks.
        """
        return max(OneSided.engage(surface, quantized) - surface + abs(speed), 0.0)

    @staticmethod
    def contact_speed(
        surface: float,
        speed: float,
        mu: float,
        delay: int = 0,
        push: float = 0.0,
        quantized: bool = True,
        hand: float = 0.0,
    ) -> float:
        """Give the criterion's speed V* of an approach at V (:mod:`dfa.analysis.criterion`, "A one-sided wall").

        At the first reading inside, δ = ξ − s lies in [c, c + V), c = ξ_e − s (ξ_e = :meth:`engage`), and the
        storage Q = ½μξ'² + ½(δ⁺)² − pδ + ½p² + ½κ_h ξ² (>= ½μξ'²; a hand's spring κ_h = k_h/K to the wall's
        origin, held by the operator during the approach) is ½μV² + φ(δ), φ convex: at most ½μV² + ½m²,
        ½m² = max(φ(c), φ(c + V)). The d commands still pending from the approach (0) differ from the first one
        inside by at most ε_q = c + V + ½ (c + V = V without the encoder) and add at most ε_q·d·V*. Hence
        ½μV*² = ½μV² + ½m² + ε_q d V*:

            V* = (ε_q d + √((ε_q d)² + μ(μV² + m²)))/μ,    V* = √(V² + ε²/μ) for d = 0, p = 0
            (ε = :meth:`contact_excess`).

        Parameters
        ----------
        surface : float
            The surface s in ticks.
        speed : float
            The impact speed V >= 0 in ticks per sample.
        mu : float
            Dimensionless mass μ = m/(K T²) > 0.
        delay : int, optional
            The computational delay d in samples (default 0).
        push : float, optional
            The operator's push p = F_p/(K Δ) from the first reading inside on (default 0).
        quantized : bool, optional
            With the encoder (default).
        hand : float, optional
            A hand's stiffness κ_h = k_h/K >= 0 (default 0).

        Returns
        -------
        float
            V* in ticks per sample (>= V).

        Examples
        --------
        >>> round(OneSided.contact_speed(0.0, 3.0, 1.0) ** 2, 12)      # V² + ε²/μ, ε = V
        18.0
        """
        c = OneSided.engage(surface, quantized) - surface
        top = c + speed

        def phi(d: float) -> float:  # ½(δ⁺)² − pδ + ½p² + ½κ_h(s + δ)²: the storage beyond ½μV² at δ = ξ − s
            return 0.5 * max(d, 0.0) ** 2 - push * d + 0.5 * push * push + 0.5 * hand * (surface + d) ** 2

        m2 = 2.0 * max(phi(c), phi(top))
        if delay == 0:
            return math.sqrt(speed * speed + m2 / mu)
        eq = (top + 0.5 if quantized else top) * delay
        return (eq + math.sqrt(eq * eq + mu * (mu * speed * speed + m2))) / mu

    @staticmethod
    def impact_speed(
        surface: float,
        equivalent: float,
        mu: float,
        delay: int = 0,
        push: float = 0.0,
        quantized: bool = True,
        hand: float = 0.0,
    ) -> float:
        """Give the largest impact speed V whose :meth:`contact_speed` V* is at most ``equivalent``.

        V* grows with V, and V <= V*: bisection on [0, ``equivalent``] to the last double (one formula for V*).

        Parameters
        ----------
        surface : float
            The surface s in ticks.
        equivalent : float
            The speed V* >= 0 in ticks per sample (the criterion's critical speed).
        mu : float
            Dimensionless mass μ = m/(K T²) > 0.
        delay : int, optional
            The computational delay d in samples.
        push : float, optional
            The push p = F_p/(K Δ).
        quantized : bool, optional
            With the encoder (default).
        hand : float, optional
            A hand's stiffness κ_h = k_h/K (default 0).

        Returns
        -------
        float
            The impact speed V >= 0 in ticks per sample; 0 when not even V = 0 reaches (then V*(0) > ``equivalent``).

        Examples
        --------
        >>> v = OneSided.impact_speed(0.0, 3.0, 2.0)           # c = 0: V² (1 + 1/μ) = V*²
        >>> round(v * v * 1.5, 12)
        9.0
        """

        return largest_speed(lambda v: OneSided.contact_speed(surface, v, mu, delay, push, quantized, hand), equivalent)

    @staticmethod
    def engage(surface: float, quantized: bool = True) -> float:
        """Give the first position the wall sees, ξ_e = ⌊s + ½⌋ (the first whose reading ⌊ξ⌋ + ½ lies beyond s).

        Parameters
        ----------
        surface : float
            The surface s in ticks.
        quantized : bool, optional
            With the encoder (default); without it ξ_e = s.

        Returns
        -------
        float
            The position ξ_e in ticks.
        """
        q = check_bool("quantized", quantized, "pass True (with the encoder) or False (the surface itself)")
        return float(math.floor(surface + 0.5)) if q else float(surface)


@dataclass(frozen=True)
class Push(Element[float]):
    """The operator's constant force toward the wall (N; rotary N·m), which keeps the device in contact.

    The paper's bias force: F_p >= 0 pushes in +ξ, into the wall, beside the wall's force; group
    p = F_p/(K Δ), so it needs the encoder resolution (:meth:`dfa.model.wall.Wall.params` with ``resolution``).
    Default none: a free impact that may leave the wall for good.

    Attributes
    ----------
    push : float
        The force F_p >= 0 in N (rotary: N·m).

    Examples
    --------
    >>> Push(0.9).group(1e-3, 1000.0, resolution=3e-5)     # p = F_p/(K Δ)
    30.0
    """

    push: float
    kernel_code: ClassVar[int] = kt.PUSH
    firmware: ClassVar[bool | str] = "the operator's push toward the wall (the operator)"
    parameter: ClassVar[Parameter] = Parameter(
        "push", ("N", "N·m"), "--push", "N",
        "with --one-sided: the operator's constant force toward the wall in N (rotary: N·m) (default: none)",
        "push", "p = F_p/(K Δ)",
    )  # fmt: skip
    colgate_schenkel: ClassVar[str | None] = "the Colgate–Schenkel condition has no operator's force"
    wall_flag: ClassVar[bool] = False
    #: Its group needs the encoder resolution Δ (:meth:`dfa.model.wall.Wall.params`).
    needs_resolution: ClassVar[bool] = True

    @classmethod
    def flag_rows(cls) -> tuple[FlagRow, ...]:
        par = cls.parameter
        return (FlagRow(par.flag, "push", par.metavar, par.help, "N", needs="--one-sided"),)

    def __post_init__(self) -> None:
        fix = "give the operator's force toward the wall in N (0 for none)"
        object.__setattr__(self, "push", check_nonnegative("push", self.push, fix))

    def group(self, period: float, stiffness: float, resolution: float | None = None) -> float:
        """Give the push's group p = F_p/(K Δ), validated.

        Parameters
        ----------
        period : float
            Sample period T in s (unused).
        stiffness : float
            Virtual spring K in N/m (rotary: N·m/rad).
        resolution : float
            Encoder resolution Δ in m (rotary: rad); required.

        Returns
        -------
        float
            The push p, in units of the force step K Δ.

        Raises
        ------
        DFAValueError
            Without a resolution.
        """
        return self.check_group(self._per_force_step("F_p", stiffness, resolution))

    @classmethod
    def check_group(cls, value: object) -> float:
        return check_nonnegative("push", value, "p = F_p/(K Δ) cannot be negative (0: no push)")

    @classmethod
    def renders_nothing(cls, g: float) -> bool:
        return g == 0.0

    @classmethod
    def corner(cls, g: float, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        return 0.0, 0.0  # on a one-sided wall only (WallParams.uncovered); it enters V* (OneSided.contact_speed)

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)


_PC_SWITCHES = "its damper switches with the observed energy, a gain that depends on the run's history"
_PC_NOT_COVERED = f"no passivity criterion covers a passivity controller ({_PC_SWITCHES}); the exact simulation does"
_PC_NOT_LINEAR = (
    f"a passivity controller is not a linear loop ({_PC_SWITCHES}): the exact linear bound and the describing "
    "function do not cover it; the exact simulation does"
)


@dataclass(frozen=True)
class PassivityController(Element[tuple[int, float | None]]):
    """The time-domain passivity observer and controller (Hannaford and Ryu, IEEE T-RO 18(1), 2002) on the wall.

    Observer: at reading h the energy the device has put into the wall (a one-port),

        E_obs(h) = E_obs(h − 1) − φ_{h−1} v_h,   E_obs(0) = E_0   (KΔ²; x K Δ² in J),

    with v_h = r_h − r_{h−1} the velocity estimate the wall already forms (paper eq. 2: the readings' backward
    difference) and φ_{h−1} the force the wall held over the sample just ended, [h − 1, h) (its command c_{h−1−d},
    this controller's part included); E_0 is the energy the wall holds at the start as the observer would have
    counted a slow entry (:func:`dfa.core.wall_kernel.held_energy`: 0 from ξ0 = 0 and outside a one-sided wall; a
    start with the spring preloaded has received its energy). This pairs each sample's force with the displacement
    the readings saw over that same sample (the sampled observer of Ryu, Kim and Hannaford, IEEE T-RO 20(4), 2004);
    pairing it with the sample's own v_h instead (the 2002 form) would lag half a sample. Without the encoder and an
    amplifier lag it is exactly the work −Σ∫φ ξ' dτ done on the wall (by the device's energy balance, −(Δ½μξ'² + Σ
    dissipated) with the spring's :class:`dfa.analysis.simulation.EnergyRecord`); with the encoder it differs by the
    readings' rounding (at most ``|φ_{h−1}| + |φ_0| + Σ|φ_k − φ_{k−1}|`` in KΔ², summation by parts); with a lag it
    uses the command, not the amplifier's output. E_obs < 0: the wall has produced energy (active). A ``window``
    of W samples sums only the last W terms (an unbounded observer accumulates a passive past that lets a later
    active spell through).
    With the encoder, sub-tick motion that toggles the reading across one tick reads as the wall producing energy
    at every toggle (the readings' rounding, not the device's energy): an unbounded observer accumulates it for
    ever and the controller keeps firing on each toggle, which can sustain a buzz where the plain wall rests; a
    window bounds it.

    Controller: when the ledger L = E_obs(h) + B_h is negative, B_h >= 0 the dissipation it has booked for its own
    forces not yet observed (those in the d commands c_{h−d} … c_{h−1}, of which c_{h−d} is applied now; each
    booked −f v at its reading), it adds the damper α_h = −L/v_h² on v_h, the force f_h = −α_h v_h = L/v_h clipped
    to ±``force_limit``; it books −f_h v_h (= −L, or less at the limit), so L after its action is >= 0 unless the
    limit cut it. Nothing when v_h = 0. On a one-sided wall the clip to pushing only applies to the sum: f is what
    it lets through. Without a force limit (the textbook controller, the default) the force L/v_h is unbounded;
    the exact simulation shows it can make a sampled wall diverge that rests or buzzes without it (what it books,
    −f v_h, is not what the next sample's motion dissipates), so give the actuator's limit.

    Group: (W, f_max) = (window/T rounded, force_limit/(K Δ)); no criterion, linear bound, Colgate–Schenkel or
    describing function covers it (they refuse it by name); the exact simulator runs it.

    Attributes
    ----------
    window : float or None
        The observer's window in s (rounded to whole samples, at least one); None (default): unbounded.
    force_limit : float or None
        The most force the controller adds, in N (rotary: N·m); None (default): no limit (the textbook
        controller, which can destabilise a sampled wall: give the actuator's limit).

    Examples
    --------
    >>> PassivityController(window=0.05, force_limit=2.0).group(1e-3, 1000.0, resolution=1e-5)
    (50, 200.0)
    >>> PassivityController().group(1e-3, 1000.0)
    (0, None)
    """

    window: float | None = None
    force_limit: float | None = None
    kernel_code: ClassVar[int] = kt.PASSIVITY
    firmware: ClassVar[bool | str] = True
    parameter: ClassVar[Parameter] = Parameter(
        "force_limit", ("N", "N·m"), "--pc-force-limit", "N",
        "with --passivity-controller: the most force it adds, in N (rotary: N·m) (default: no limit, the textbook "
        "controller, which can destabilise a sampled wall: give the actuator's limit)",
        "passivity_controller", "(W, f_max) = (window/T, F_max/(K Δ))",
    )  # fmt: skip
    colgate_schenkel: ClassVar[str | None] = "the Colgate–Schenkel condition has no energy-switched damper"
    linear_reason: ClassVar[str | None] = _PC_NOT_LINEAR
    #: Its flags are the controller group's (:mod:`dfa.cli.passivity`).
    wall_flag: ClassVar[bool] = False
    absent: ClassVar[object] = None
    needs_resolution: ClassVar[bool] = True
    #: Its runs cost more than the spring's: the observed energy is part of the state, so a period repeats (and is
    #: skipped) only once the controller holds at its limit, and a chatter whose ξ drifts by rounding is integrated
    #: until its outcome is proven (:mod:`dfa.core.wall_kernel`, "Outcome-only runs").
    sweep_points: ClassVar[int] = 300

    def __post_init__(self) -> None:
        if self.window is not None:
            fix = "give the observer's window in s, or None for an unbounded observer"
            object.__setattr__(self, "window", check_positive("window", self.window, fix))
        if self.force_limit is not None:
            fix = "give the most force the controller adds in N, or None for no limit"
            object.__setattr__(self, "force_limit", check_positive("force_limit", self.force_limit, fix))

    def group(self, period: float, stiffness: float, resolution: float | None = None) -> tuple[int, float | None]:
        """Give the controller's group (W, f_max): the window in samples (0: none), the force limit in K Δ.

        Parameters
        ----------
        period : float
            Sample period T in s.
        stiffness : float
            Virtual spring K in N/m (rotary: N·m/rad).
        resolution : float or None
            Encoder resolution Δ in m (rotary: rad); required with a force limit.

        Returns
        -------
        tuple
            (W, f_max): W >= 1 whole samples or 0 for an unbounded observer; f_max = F_max/(K Δ) or None.

        Raises
        ------
        DFAValueError
            For a window shorter than half a sample, or a force limit without a resolution.
        """
        w = 0
        if self.window is not None:
            w = round(self.window / period)
            if w < 1:
                raise DFAValueError(
                    f"window = {format_value(self.window)} s is invalid: it must span at least one sample "
                    f"(T = {format_value(period)} s); give a longer window, or None for an unbounded observer"
                )
        if self.force_limit is None:
            return self.check_group((w, None))
        if resolution is None:
            raise DFAValueError(
                "force_limit needs the encoder resolution Δ for its group F_max/(K Δ): call "
                "Wall.params(period, resolution=Δ)"
            )
        step = stiffness * resolution
        limit = self.force_limit / step
        if not math.isfinite(limit):
            inputs = (("K", stiffness, _K_UNITS), ("Δ", resolution, _D_UNITS))
            raise GroupRangeError(self.parameter, self.force_limit, "overflows a float", inputs, _FLOAT_MAX * step)
        return self.check_group((w, limit))

    @classmethod
    def check_group(cls, value: object) -> tuple[int, float | None]:
        fix = "give (W, f_max): the window in whole samples (0: unbounded) and the force limit in K Δ (None: none)"
        if not (isinstance(value, (tuple, list)) and len(value) == 2):
            raise DFAValueError(f"passivity_controller = {format_value(value)} is invalid: {fix}")
        w, limit = value
        if isinstance(w, bool) or not isinstance(w, (int, np.integer)) or w < 0:
            raise DFAValueError(f"passivity_controller window = {format_value(w)} is invalid: {fix}")
        if limit is not None:
            limit = check_positive("passivity_controller force limit", limit, fix)
        return int(w), limit

    @classmethod
    def corner(cls, g: tuple[int, float | None], *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        raise NotCovered(_PC_NOT_COVERED)

    @classmethod
    def kernel_block(cls, g: tuple[int, float | None]) -> KernelBlock:
        w, limit = g
        params = (float(w), math.inf if limit is None else float(limit))
        return KernelBlock(cls.kernel_code, params, 5 + int(w))  # E_obs, window position, f, total, E_0, W terms

    @classmethod
    def group_json(cls, g: tuple[int, float | None]) -> dict[str, object]:
        return {"pc_window": int(g[0]), "pc_force_limit": g[1]}

    @classmethod
    def group_from_dict(cls, data: Mapping[str, object]) -> object | None:
        return (data["pc_window"], data.get("pc_force_limit")) if "pc_window" in data else None

    null_reasons: ClassVar[tuple[tuple[str, str], ...]] = (
        ("passivity_controller_window", "an unbounded observer (the whole run)"),
        ("passivity_controller_force_limit", "no force limit"),
        ("pc_force_limit", "no force limit (the passivity controller's)"),
    )

    @classmethod
    def record_keys(cls) -> tuple[tuple[str, str], ...]:
        return (("passivity_controller_window", "window"), ("passivity_controller_force_limit", "force_limit"))

    @classmethod
    def flag_rows(cls) -> tuple[FlagRow, ...]:
        par = cls.parameter
        return (
            FlagRow(
                "--passivity-controller", "passivity_controller", None,
                "add the time-domain passivity observer and controller (Hannaford–Ryu): a damper that dissipates the "
                "energy the wall has produced (default: off)",
            ),
            FlagRow(
                "--pc-window", "pc_window", "S",
                "with --passivity-controller: the observer's window in s (default: the whole run)", "s",
                needs="--passivity-controller",
            ),
            FlagRow(par.flag, "pc_force_limit", par.metavar, par.help, "N", needs="--passivity-controller"),
        )  # fmt: skip

    @property
    def value(self) -> object:
        """The controller's (window, force limit) in s and N (None: unbounded, no limit)."""
        return self.window, self.force_limit

    def to_dict(self) -> dict[str, object]:
        """Give the controller as JSON-able data.

        Returns
        -------
        dict
            Its key, window (s) and force limit (N), None where absent.
        """
        return {"element": type(self).key(), "window": self.window, "force_limit": self.force_limit, "unit": "s, N"}


_FL_NOT_LINEAR = (
    "an actuator's force limit is not linear (the command is clipped at ±F_max): the exact linear bound does not "
    "cover it and no describing function of the clip is implemented; the exact simulation does"
)


@dataclass(frozen=True)
class ForceLimit(Element[float]):
    """The actuator's force limit: the wall's command clipped to ±F_max (N; rotary N·m) before the amplifier.

    The real device saturates: whatever the spring, damper, filter, one-sided shaping and passivity controller
    command, the force it applies is c clipped to [−φ_max, φ_max], group φ_max = F_max/(K Δ) (so it needs the
    encoder resolution). The clip is the last element: the command is clipped before it enters the delay line
    and the amplifier (:func:`dfa.core.wall_kernel._clip`); a limit the command never reaches leaves a run bit
    for bit unchanged. A run that reaches the limit in its tail without coming to rest ends ``saturated``: a
    large motion held by the actuator, no stable wall. It is the device's ``max_force``
    (:data:`dfa.model.device.DEVICE_FIELDS`; ``--max-force``): a catalogue device that gives one applies it.

    The criterion covers the paper's spring with a force limit, unchanged (eq. 6). Its proof (paper §3) bounds
    the energy the held staircase generates in a sample, D_G(ξ1, ξh) = ∫_{ξh}^{ξ1} (g(s) − g(ξh)) ds with
    g(s) = ⌊s⌋ + ½, by the ZOH and quantization terms (24) + (26), which the viscous and Coulomb dissipation
    (32), (30) exceed when (35) holds at the sample's speed. With the clip the wall commands −f(ξh),
    f = sat(g) = max(−φ_max, min(φ_max, g)). The clip is monotone and 1-Lipschitz, and g is non-decreasing, so
    for s between ξh and ξ1, f(s) − f(ξh) has the sign of g(s) − g(ξh) and at most its size: the integrand of
    D_F(ξ1, ξh) = ∫_{ξh}^{ξ1} (f(s) − f(ξh)) ds lies between 0 and that of D_G, for ξ1 above or below ξh, so
    0 <= D_F <= D_G for any two positions (D depends on the sample's end points only, whatever the path), and
    the summed bound (33) holds for D_F. The dissipation terms are the device's on its own path. The storage
    H_F = ½μξ'² + ∫₀^ξ f is >= ½μξ'² and radially unbounded (∫₀^ξ f grows as φ_max·abs(ξ)), with H_F <= H_T of
    the spring (19) at the same state: H_F never increases, so the speed stays below the criterion's speed and
    the position bounded. With other elements (damper, filter, delay, amplifier lag, hand spring, one-sided
    wall, push, passivity controller) the clip acts on their sum, and the decomposition of the extended
    criterion into the spring's part and theirs no longer holds: not covered (:meth:`criterion_beside`).
    The exact linear bound and the describing function do not cover it (a clip is not linear; no describing
    function of it is implemented), nor Colgate–Schenkel's linear condition, nor the spring's closed forms and
    kernel (:data:`Coverage`); the exact simulation does.

    Attributes
    ----------
    max_force : float
        The actuator's largest force F_max > 0 in N (rotary: N·m).

    Examples
    --------
    >>> ForceLimit(3.0).group(1e-3, 1000.0, resolution=1e-5)     # φ_max = F_max/(K Δ)
    300.0
    >>> ForceLimit.coverage(300.0).covers(Coverage.CRITERION), ForceLimit.coverage(300.0).covers(Coverage.LINEAR)
    (True, False)
    """

    max_force: float
    kernel_code: ClassVar[int] = kt.FORCE_LIMIT
    firmware: ClassVar[bool | str] = True
    parameter: ClassVar[Parameter] = Parameter(
        "max_force", ("N", "N·m"), "--max-force", "N",
        "the actuator's force limit F_max in N (rotary: N·m): the wall's command is clipped to ±F_max (default: "
        "the catalogue device's, else unlimited)",
        "force_limit", "φ_max = F_max/(K Δ)",
    )  # fmt: skip
    colgate_schenkel: ClassVar[str | None] = (
        "the Colgate–Schenkel condition is a linear one; the force limit clips the command (the criterion covers "
        "the spring with a limit)"
    )
    linear_reason: ClassVar[str | None] = _FL_NOT_LINEAR
    #: Its flag is the device's ``--max-force`` (a row of the device's field table, :mod:`dfa.cli.inputs`).
    wall_flag: ClassVar[bool] = False
    absent: ClassVar[object] = None
    needs_resolution: ClassVar[bool] = True
    #: The device's ``max_force`` adds it to the device's walls (their record and text show it).
    device_field: ClassVar[str | None] = "max_force"

    def __post_init__(self) -> None:
        fix = "give the actuator's force limit F_max in N (rotary: N·m), or no limit"
        object.__setattr__(self, "max_force", check_positive("max_force", self.max_force, fix))

    def group(self, period: float, stiffness: float, resolution: float | None = None) -> float:
        """Give the limit's group φ_max = F_max/(K Δ), validated.

        Parameters
        ----------
        period : float
            Sample period T in s (unused).
        stiffness : float
            Virtual spring K in N/m (rotary: N·m/rad).
        resolution : float
            Encoder resolution Δ in m (rotary: rad); required.

        Returns
        -------
        float
            The limit φ_max, in units of the force step K Δ.

        Raises
        ------
        DFAValueError
            Without a resolution.
        """
        return self.check_group(self._per_force_step("F_max", stiffness, resolution))

    @classmethod
    def check_group(cls, value: object) -> float:
        return check_positive("force_limit", value, "φ_max = F_max/(K Δ) must be > 0 (no limit: leave it out)")

    @classmethod
    def corner(cls, g: float, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        return 0.0, 0.0  # the spring's corner, alone (criterion_beside; the class docstring's proof)

    @classmethod
    def criterion_beside(cls, g: float, others: tuple[ElementClass, ...]) -> str | None:
        others = tuple(k for k in others if k is not Travel)  # the travel adds no force: the proof holds inside it
        if not others:
            return None
        names = ", ".join(k.key().replace("_", " ") for k in others)
        return (
            f"no passivity criterion is derived for an actuator's force limit with {names}: the clip acts on the "
            "sum of their forces and the spring's, and the extended criterion's decomposition no longer holds "
            "(the spring alone with a limit is covered); the exact simulation covers it"
        )

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)

    @classmethod
    def flag_rows(cls) -> tuple[FlagRow, ...]:
        par = cls.parameter
        return (FlagRow(par.flag, "max_force", par.metavar, par.help, "N"),)


_TRAVEL_INSIDE = (
    "the criterion, the linear bounds, the describing function and the closed forms do not model the end stops: "
    "they speak of the motion inside the travel, and a verdict (passive, stable, a predicted cycle) stays true "
    "while the device stays inside; the exact simulation ends a run at the stop (outcome end_stop)"
)


@dataclass(frozen=True)
class Travel(Element[float]):
    """The device's travel: the distance from the centre (ξ = 0, where the wall's spring is zero) to either end stop.

    A real device stops at the end of its workspace; the simulation ends a run whose position leaves
    [−ξ_travel, ξ_travel] there, with the outcome ``end_stop`` (the kernel's exit test beside the divergence
    bound: :mod:`dfa.core.wall_kernel`; the spring's kernel runs it with the travel as its bound,
    :func:`dfa.analysis.simulation.mark_end_stops`). The stop is not modelled beyond that (no impact, no
    rebound). Group ξ_travel = travel/Δ (ticks), so it needs the encoder resolution.

    The value is the device's (:data:`dfa.model.device.DEVICE_FIELDS`, ``travel``; flag ``--travel``): a
    :class:`dfa.model.loop.Loop` of a device with a travel adds this element to its wall's groups
    (:func:`dfa.model.loop.device_groups`). Coverage: every analysis covers it, as a statement about the motion
    inside the travel (:attr:`assumption`): they do not model the stop.

    Attributes
    ----------
    travel : float
        The travel in m (rotary: rad), > 0.

    Examples
    --------
    >>> Travel(0.05).group(1e-3, 1000.0, resolution=2e-5)     # ξ_travel = travel/Δ
    2500.0
    >>> Travel.kernel_block(2500.0)
    KernelBlock(code=10, params=(2500.0,), state=0)
    """

    travel: float
    kernel_code: ClassVar[int] = kt.TRAVEL
    firmware: ClassVar[bool | str] = "the device's end stops (hardware)"
    parameter: ClassVar[Parameter] = Parameter(
        "travel", ("m", "rad"), "--travel", "M",
        "the device's travel from the centre to either end stop, in m (rotary: rad); a run ends there (end_stop) "
        "(default: the catalogue value, else unlimited)",
        "travel", "ξ_travel = travel/Δ (ticks)",
    )  # fmt: skip
    #: Its flag is the device's field (:data:`dfa.model.device.DEVICE_FIELDS`), in the device's group of options.
    wall_flag: ClassVar[bool] = False
    absent: ClassVar[object] = None
    needs_resolution: ClassVar[bool] = True
    #: What the analyses that cover it assume: the motion stays inside the travel.
    assumption: ClassVar[str] = _TRAVEL_INSIDE
    #: The device's ``travel`` adds it to the groups of the device's walls (the runs' end stops; the wall's record
    #: and text are unchanged, the command line states the travel beside them).
    device_field: ClassVar[str | None] = "travel"
    device_in_wall: ClassVar[bool] = False

    def __post_init__(self) -> None:
        fix = "give the device's travel from the centre to either end stop in m (rotary: rad)"
        object.__setattr__(self, "travel", check_positive("travel", self.travel, fix))

    def group(self, period: float, stiffness: float, resolution: float | None = None) -> float:
        """Give the travel's group ξ_travel = travel/Δ, validated.

        Parameters
        ----------
        period : float
            Sample period T in s (unused).
        stiffness : float
            Virtual spring K in N/m (unused).
        resolution : float
            Encoder resolution Δ in m (rotary: rad); required.

        Returns
        -------
        float
            The travel ξ_travel in encoder ticks.

        Raises
        ------
        DFAValueError
            Without a resolution.
        """
        if resolution is None:
            raise DFAValueError(
                "travel needs the encoder resolution Δ for its group travel/Δ: call Wall.params(period, resolution=Δ)"
            )
        inputs = (("Δ", resolution, _D_UNITS),)
        return self.check_group(self._finite(self.travel / resolution, inputs, resolution))

    @classmethod
    def check_group(cls, value: object) -> float:
        return check_positive("travel", value, "ξ_travel = travel/Δ is the travel in encoder ticks, > 0")

    @classmethod
    def spring_kernel(cls, g: float) -> bool:
        return True  # the spring's kernel runs it with the travel as its bound (dfa.analysis.simulation)

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)


#: An element class of any group type, as a wall holds it beside its group (:class:`dfa.model.wall.WallParams`).
ElementClass = type[Element[object]]

#: The registered elements, in the order a wall applies them (delay, damper, filter, amplifier, hand spring,
#: one-sided contact, push, passivity controller, the actuator's force limit, the device's travel).
ELEMENTS: tuple[ElementClass, ...] = (
    Delay, Damper, VelocityFilter, AmplifierLag, HandSpring, OneSided, Push, PassivityController, ForceLimit, Travel
)  # fmt: skip

#: The elements whose entries stand in every wall's record and groups' record, their absent values when the wall has
#: none (:attr:`Element.recorded_absent`, :attr:`Element.absent`), in the records' order: the paper's spring's records
#: (damping, delay, filter cutoff, amplifier) as they always were. Any other element's entries appear only when the
#: wall has it, after these, in the order of :data:`ELEMENTS` (:meth:`Element.record`, :meth:`Element.group_json`).
ALWAYS_RECORDED: tuple[ElementClass, ...] = (Damper, Delay, VelocityFilter, AmplifierLag)
