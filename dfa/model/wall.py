"""The virtual wall: the paper's spring and the elements rendered with it, in physical and dimensionless form.

A real haptic wall is rarely a bare spring. At sample h the wall reads the quantized position
q_h = Δ(⌊x(hT)/Δ⌋ + ½) (paper eq. 2), forms the backward-difference velocity v_h = (q_h − q_{h−1})/T,
optionally low-pass filters it, and commands, d samples later (computational delay)::

    F_cmd,h = −K q_{h−d} − B y_{h−d},      y = filtered v (y = v without filter)

held by the zero-order hold; a current amplifier of finite bandwidth turns the held command into force
through a first-order lag. :class:`Wall` is the stiffness K and the elements of :mod:`dfa.model.elements`
(:class:`~dfa.model.elements.Delay`, :class:`~dfa.model.elements.Damper`,
:class:`~dfa.model.elements.VelocityFilter`, :class:`~dfa.model.elements.AmplifierLag`); ``Wall(K)`` is the
paper's spring (eq. 1-2) and every result for it is the spring-only result.

Dimensionless form (beside paper Table 1, τ = t/T, ξ = x/Δ, φ = F/(KΔ)): :class:`WallParams` holds each
element's group (β_B = B/(KT), ν_c = f_c T, α = τ_a/T, d), so that φ_cmd,h = −(⌊ξ_{h−d}⌋ + ½) − β_B ỹ_{h−d},
α φ_A' = φ_cmd − φ_A. It composes the elements' mathematics for the analyses: the criterion's corner
(:meth:`WallParams.corner`), the simulator's kernel table (:meth:`WallParams.kernel_table`), the exact sampled
loop (:meth:`WallParams.command`, :meth:`WallParams.plant`).

Examples
--------
>>> w = Wall.of(stiffness=500.0, damping=0.5, delay=1, filter_cutoff=100.0)
>>> w.elements
(Delay(delay=1), Damper(damping=0.5), VelocityFilter(filter_cutoff=100.0))
>>> p = w.params(period=1e-3)
>>> round(p.damping, 6), p.delay, round(p.cutoff, 6), p.lag
(1.0, 1, 0.1, 0.0)
>>> round(p.filter_pole, 6)   # a = exp(-2π ν_c)
0.533488
>>> Wall(300.0).params(1e-3).is_spring
True
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TypeVar, cast

import numpy as np
import numpy.typing as npt

from ..checks import check_positive, format_value
from ..core.table import check_table
from ..errors import DFATypeError, DFAValueError
from ..jsonable import explain_nulls
from ..plausibility import warn_if_from_outside
from .elements import (
    ALWAYS_RECORDED,
    ELEMENTS,
    MIN_CUTOFF,
    MIN_LAG,
    AmplifierLag,
    CommandPolynomials,
    Coverage,
    Covered,
    Damper,
    Delay,
    Element,
    ElementClass,
    ForceLimit,
    GroupRangeError,
    HandSpring,
    NotCovered,
    OneSided,
    PassivityController,
    Push,
    Response,
    Travel,
    VelocityFilter,
)

#: An element class (:func:`Wall.element`, :meth:`WallParams.group`).
E = TypeVar("E", bound="Element[object]")
#: An element's group type.
T = TypeVar("T")

__all__ = ["Wall", "WallParams", "MIN_CUTOFF", "MIN_LAG", "SPRING_CORNER"]

#: The analyses an element's class decides alone, whatever its group (:meth:`Wall.covers`).
_BY_CLASS = (
    Coverage.LINEAR | Coverage.DESCRIBING_FUNCTION | Coverage.COLGATE_SCHENKEL | Coverage.SURFACE_START
    | Coverage.SIMULATION
)  # fmt: skip

#: The corner (β₀, σ₀) of the paper's spring (eq. 6): (½, ½) with the encoder, (½, 0) without (eq. 7).
SPRING_CORNER = (0.5, 0.5)


def _ordered(elements: object) -> tuple[Element[object], ...]:
    """The elements as a tuple in the order of :data:`~dfa.model.elements.ELEMENTS` (others after, as given)."""
    if isinstance(elements, Element):
        elements = (elements,)
    try:  # a 0-d array is Iterable by its type yet refuses iteration
        items = tuple(elements) if isinstance(elements, Iterable) else None
    except TypeError:
        items = None
    if items is None:
        raise DFATypeError(
            f"elements = {format_value(elements)} is invalid: it must be a sequence of wall elements; "
            "give e.g. (dfa.Damper(1.0), dfa.Delay(1))"
        )
    for e in items:
        if not isinstance(e, Element):
            raise DFATypeError(
                f"elements holds {format_value(e)} of type {type(e).__name__}: every element must be a dfa wall element "
                "(Damper, VelocityFilter, Delay, AmplifierLag, HandSpring)"
            )
    kinds = [type(e) for e in items]
    twice = sorted({k.__name__ for k in kinds if kinds.count(k) > 1})
    if twice:
        raise DFAValueError(
            f"elements holds {', '.join(twice)} more than once: a wall has at most one of each element; "
            "combine them into one"
        )
    if AmplifierLag in kinds and HandSpring in kinds:
        raise DFAValueError(
            "elements holds an AmplifierLag and a HandSpring: an amplifier lag with a hand stiffness is not covered "
            "yet (the simulator's step with both is not derived); drop one of them"
        )
    rank = {k: i for i, k in enumerate(ELEMENTS)}
    return tuple(sorted(items, key=lambda e: rank.get(type(e), len(ELEMENTS))))


@dataclass(frozen=True)
class WallParams:
    """The wall's dimensionless groups, one per element (beside paper Table 1), composed for the analyses.

    Parameters
    ----------
    groups : tuple of (element class, group)
        Each element of the wall and its group, in the wall's order; :meth:`of` builds it for the built-in
        elements from their groups. An element that renders nothing (β_B = 0, α = 0, d = 0) is left out.

    Examples
    --------
    >>> WallParams.of(damping=0.2, cutoff=0.05).filter_pole > 0.7
    True
    >>> WallParams.of(damping=0.3, delay=1).corner(quantized=True)    # (½ + d + β_B, ½ + β_B)
    (1.8, 0.8)
    """

    groups: tuple[tuple[ElementClass, object], ...] = ()

    def __post_init__(self) -> None:
        fix = "each entry must be (element class, group), e.g. ((dfa.Damper, 0.3),); or use WallParams.of(...)"
        try:
            items = [] if isinstance(self.groups, (str, bytes)) else list(self.groups)
        except TypeError:
            items = []
        if not items and not (isinstance(self.groups, (tuple, list)) and len(self.groups) == 0):
            raise DFATypeError(
                f"groups of type {type(self.groups).__name__} is invalid: it must be a sequence of pairs; {fix}"
            )
        out = []
        for item in items:
            pair = tuple(item) if isinstance(item, (tuple, list)) else ()
            kind = pair[0] if len(pair) == 2 else None
            if not (isinstance(kind, type) and issubclass(kind, Element)):
                raise DFATypeError(
                    f"groups holds {format_value(item)}: it is not an (element class, group) pair; {fix}"
                )
            g = kind.check_group(pair[1])
            if not kind.renders_nothing(g):
                out.append((kind, g))
        rank = {k: i for i, k in enumerate(ELEMENTS)}
        kinds = [k for k, _ in out]
        if len(set(kinds)) != len(kinds):
            raise DFAValueError("groups holds an element more than once: a wall has at most one of each element")
        if AmplifierLag in kinds and HandSpring in kinds:
            raise DFAValueError(
                "an amplifier lag with a hand stiffness is not covered yet: the simulator's step with both (a "
                "third-order motion within the sample) is not derived; drop the amplifier bandwidth or the hand "
                "stiffness"
            )
        object.__setattr__(self, "groups", tuple(sorted(out, key=lambda kg: rank.get(kg[0], len(ELEMENTS)))))

    @classmethod
    def of(
        cls,
        damping: float = 0.0,
        delay: int = 0,
        cutoff: float | None = None,
        lag: float = 0.0,
        hand_stiffness: float = 0.0,
        force_limit: float | None = None,
        travel: float | None = None,
    ) -> WallParams:
        """The groups of the built-in elements: β_B, d, ν_c (None: no filter), α, κ_h, φ_max and ξ_travel.

        Parameters
        ----------
        damping : float, optional
            Virtual damping β_B = B/(K T) >= 0, dimensionless (B in N·s/m over K T) (default 0: no damper).
        delay : int, optional
            Computational delay d in whole samples, >= 0 (default 0).
        cutoff : float or None, optional
            Velocity-filter cutoff ν_c = f_c T in cycles per sample, MIN_CUTOFF <= ν_c < ½; None (default):
            no filter.
        lag : float, optional
            Amplifier time constant α = τ_a/T in samples, 0 or >= MIN_LAG (default 0: no lag).
        hand_stiffness : float, optional
            Hand stiffness κ_h = k_h/K >= 0, dimensionless (default 0: none; :class:`~dfa.model.elements.HandSpring`).
        force_limit : float or None, optional
            The actuator's force limit φ_max = F_max/(K Δ) > 0, in units of the force step K Δ (None, the default:
            unlimited; :class:`~dfa.model.elements.ForceLimit`).
        travel : float or None, optional
            The device's travel ξ_travel = travel/Δ > 0 in encoder ticks, from the centre to either end stop (None,
            the default: unlimited; :class:`~dfa.model.elements.Travel`).

        Returns
        -------
        WallParams
            The groups of the elements that render something.

        Examples
        --------
        >>> WallParams.of(force_limit=30.0, travel=3000.0).group(ForceLimit)
        30.0
        """
        items: list[tuple[ElementClass, object]] = [
            (Delay, delay), (Damper, damping), (AmplifierLag, lag), (HandSpring, hand_stiffness)
        ]  # fmt: skip
        if cutoff is not None:
            items.append((VelocityFilter, cutoff))
        items += [(kind, g) for kind, g in ((ForceLimit, force_limit), (Travel, travel)) if g is not None]
        return cls(tuple(items))

    def group(self, kind: type[Element[T]]) -> T | None:
        """Give the group of one element class.

        Parameters
        ----------
        kind : type
            An element class (:mod:`dfa.model.elements`).

        Returns
        -------
        float, int or None
            Its group, or its value when absent (:attr:`~dfa.model.elements.Element.absent`).
        """
        for k, g in self.groups:
            if k is kind:
                return cast(T, g)  # the group beside ``kind`` is its own (``kind.check_group`` formed it)
        return cast("T | None", kind.absent)

    def _number(self, kind: type[Element[float]]) -> float:
        """The group of an element whose group is a number, 0 when absent."""
        g = self.group(kind)
        return 0.0 if g is None else float(g)

    # ------------------------------------------------------------------ the built-in groups by name
    @property
    def damping(self) -> float:
        """The virtual damping β_B = B/(K T) (0 without damper)."""
        return self._number(Damper)

    @property
    def delay(self) -> int:
        """The computational delay d in samples: what every element delays the command by (0: none)."""
        blocks = (k.kernel_block(g) for k, g in self.groups)
        return sum(int(b.params[0]) for b in blocks if b.code == Delay.kernel_code)

    @property
    def cutoff(self) -> float | None:
        """The filter cutoff ν_c = f_c T in cycles per sample (None without filter)."""
        return self.group(VelocityFilter)

    @property
    def lag(self) -> float:
        """The amplifier time constant α = τ_a/T in samples (0 without amplifier lag)."""
        return self._number(AmplifierLag)

    @property
    def filter_pole(self) -> float:
        """Pole a = e^{−2π ν_c} of the discretised velocity filter (0 without filter)."""
        c = self.cutoff
        return 0.0 if c is None else VelocityFilter.pole(c)

    @property
    def hand_stiffness(self) -> float:
        """The hand stiffness κ_h = k_h/K (0: none; :class:`~dfa.model.elements.HandSpring`)."""
        return self._number(HandSpring)

    @property
    def surface(self) -> float:
        """A one-sided wall's surface s in encoder ticks (0 for a bilateral wall; :class:`~dfa.model.elements.OneSided`)."""
        s = self.group(OneSided)
        return 0.0 if s is None else float(s)

    @property
    def push(self) -> float:
        """The push p = F_p/(K Δ) toward a one-sided wall (0: none; :class:`~dfa.model.elements.Push`)."""
        return self._number(Push)

    @property
    def amplifier_pole(self) -> float:
        """Decay e^{−1/α} of the amplifier's force error over one sample (0 without lag)."""
        return 0.0 if self.lag == 0.0 else math.exp(-1.0 / self.lag)

    @property
    def is_spring(self) -> bool:
        """True when the spring's compiled kernel runs the loop (Coverage.CLOSED_FORM: the spring, any delay)."""
        return self.covers(Coverage.CLOSED_FORM)

    # ------------------------------------------------------------------ composed mathematics
    def velocity_gain(self) -> float:
        """Give the quantization gain of the damper's input.

        Returns
        -------
        float
            The product of every element's (1 − a with a filter, 1 without; the criterion's step 3).
        """
        out = 1.0
        for k, g in self.groups:
            out *= k.velocity_gain(g)
        return out

    def corner(self, quantized: bool = True) -> tuple[float, float]:
        """Give the corner (β₀, σ₀) of the criterion's critical line (eq. 6 extended).

        The spring's (½, ½), or (½, 0) without the encoder, plus every element's contribution
        (:mod:`dfa.analysis.criterion` derives them).

        Parameters
        ----------
        quantized : bool, optional
            With the encoder (default) or without (σ₀ then collects no quantization term).

        Returns
        -------
        tuple of float
            (β₀, σ₀).

        Raises
        ------
        NotCovered
            When an element is not covered by any sound criterion (the message says why).
        """
        bad = self.uncovered()
        if bad is not None:
            raise NotCovered(bad[2])
        beta0, sigma0 = SPRING_CORNER[0], (SPRING_CORNER[1] if quantized else 0.0)
        gain = self.velocity_gain()
        for k, g in self.groups:
            db, ds = k.corner(g, quantized=quantized, velocity_gain=gain)
            beta0, sigma0 = beta0 + db, sigma0 + ds
        return beta0, sigma0

    def uncovered(self) -> tuple[ElementClass, object, str] | None:
        """Find the first element no sound passivity criterion covers.

        Returns
        -------
        tuple or None
            (element class, its group, the reason), or None when the criterion covers the wall.
        """
        for k, g in self.groups:
            try:
                k.corner(g, quantized=True)
            except NotCovered as why:
                return k, g, str(why)
            beside = k.criterion_beside(g, tuple(o for o, _ in self.groups if o is not k))
            if beside is not None:
                return k, g, beside
        if not self.one_sided:
            push = self.group(Push)
            if push:
                return Push, push, "a constant push on a bilateral wall is not derived (a push needs a one-sided wall)"
            return None
        others = [
            k for k, g in self.groups if k not in (OneSided, Delay, Push, HandSpring) and not k.renders_nothing(g)
        ]
        if not others:
            return None
        names = ", ".join(k.key().replace("_", " ") for k in others)
        return (
            OneSided,
            self.group(OneSided),
            f"no passivity criterion is derived yet for a one-sided wall with {names} reached from free space (the "
            "damper's memory of the approach and its clip at 0 enter the energy; the exact simulation covers it; "
            "the spring with a delay, a push and a hand stiffness is covered)",
        )

    def not_covered(self) -> str | None:
        """Say why no sound passivity criterion covers this wall.

        Returns
        -------
        str or None
            The reason of the first element the criterion does not cover; None when it covers the wall.
        """
        bad = self.uncovered()
        return None if bad is None else bad[2]

    def colgate_schenkel_reason(self) -> str | None:
        """Say why the Colgate–Schenkel condition does not cover this wall.

        Returns
        -------
        str or None
            The reasons of the elements it does not cover; None when it covers the wall.
        """
        reasons = [k.colgate_schenkel for k, _ in self.groups if k.colgate_schenkel]
        return "; ".join(reasons) if reasons else None

    def coverage(self) -> Covered:
        """Give what covers this wall: what all its elements cover, with the first reason for each missing part.

        The criterion's and Colgate–Schenkel's reasons are the wall's (:meth:`not_covered`, which adds the rules of a
        push and of a one-sided wall, and :meth:`colgate_schenkel_reason`).

        Returns
        -------
        Covered
            The flags of the analyses that cover the wall, and the reason for each one that does not.

        Examples
        --------
        >>> WallParams.of(damping=0.3, lag=0.2).coverage().flags
        <Coverage.LINEAR|DESCRIBING_FUNCTION|SIMULATION|SURFACE_START: 102>
        """
        return self._coverage

    @cached_property
    def _coverage(self) -> Covered:
        """:meth:`coverage`, formed once (the groups are frozen)."""
        out = Covered()
        for k, g in self.groups:
            out = out & k.coverage(g)
        flags, reasons = out.flags, dict(out.reasons)
        for flag, why in (
            (Coverage.CRITERION, self.not_covered()),
            (Coverage.COLGATE_SCHENKEL, self.colgate_schenkel_reason()),
        ):
            if why is None:
                flags, _ = flags | flag, reasons.pop(flag, None)
            else:
                flags, reasons[flag] = flags & ~flag, why
        return Covered(flags, tuple(reasons.items()))

    def covers(self, what: Coverage) -> bool:
        """Tell whether every analysis of ``what`` covers this wall (:meth:`coverage`).

        Parameters
        ----------
        what : Coverage
            One analysis or several.

        Returns
        -------
        bool
            True when the wall's coverage holds every flag of ``what``.
        """
        return self.coverage().covers(what)

    def kernel_table(self) -> np.ndarray:
        """Give the wall's kernel table, the one array the compiled simulator reads (:mod:`dfa.core.wall_kernel`).

        Returns
        -------
        numpy.ndarray
            The float64 table: the number of blocks B, then one block per element in the wall's order, each
            its code, its parameter count m, its state size and its m parameters (:meth:`Element.kernel_block
            <dfa.model.elements.Element.kernel_block>`; the layout and the codes: :mod:`dfa.core.table`).
            ``[0.0]`` for the paper's spring.

        Examples
        --------
        >>> WallParams.of(damping=0.5, delay=1).kernel_table().tolist()   # Delay (code 1), Damper (code 2)
        [2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 0.0, 0.5]
        """
        out = [float(len(self.groups))]
        for k, g in self.groups:
            code, params, state = k.kernel_block(g)
            out += [float(code), float(len(params)), float(state), *params]
        return check_table(np.array(out, dtype=np.float64))

    def command(self) -> CommandPolynomials:
        """Give the wall's command H(z) = (N₁ + β_B N₂)/(D_H z^d) as polynomials.

        Returns
        -------
        CommandPolynomials
            The spring's H(z) = 1 with every element applied in order (:mod:`dfa.model.elements`).
        """
        self.check_linear()
        h = CommandPolynomials.spring_only()
        for k, g in self.groups:
            h = k.command(g, h)
        return h

    def linear_reason(self) -> str | None:
        """Say why the linear loop (exact linear bound, describing function) does not cover this wall.

        Returns
        -------
        str or None
            The first element's reason (a one-sided wall, a passivity controller); None when the linear loop covers
            the wall.
        """
        reasons = [k.linear_reason for k, _ in self.groups if k.linear_reason]
        return reasons[0] if reasons else None

    @property
    def linear(self) -> bool:
        """True when the linear loop (exact linear bound, describing function) covers the wall (:meth:`linear_reason`)."""
        return self.linear_reason() is None

    def check_linear(self) -> None:
        """Refuse a wall the linear loop does not cover (:meth:`linear_reason`), rather than treat it as bilateral.

        Raises
        ------
        NotCovered
            With the element's reason.
        """
        why = self.linear_reason()
        if why is not None:
            raise NotCovered(why)

    def plant(self, rate: float, mu: float) -> tuple[np.ndarray, np.ndarray] | None:
        """Give the exact ZOH plant when an element sits between hold and device, or acts on the device.

        Parameters
        ----------
        rate : float
            The device's rate a = β/μ = bT/m (per sample).
        mu : float
            The dimensionless mass μ = m/(K T²) at the stiffness of these groups.

        Returns
        -------
        tuple of numpy.ndarray, or None
            (N_G, D_G) in w = z − 1, G(z) = N_G/(μ D_G); None for the device alone (:mod:`dfa.core.zoh`).
        """
        for k, g in self.groups:
            out = k.plant(g, rate, mu)
            if out is not None:
                return out
        return None

    @property
    def one_sided(self) -> bool:
        """True for a one-sided wall (:class:`~dfa.model.elements.OneSided`)."""
        return self.group(OneSided) is not None

    @property
    def passivity_controller(self) -> bool:
        """True with a passivity controller (:class:`~dfa.model.elements.PassivityController`)."""
        return self.group(PassivityController) is not None

    def plant_response(self, omega: npt.ArrayLike) -> Response:
        """Give the continuous factor between hold and device.

        Parameters
        ----------
        omega : float or array_like
            Angular frequency ω in rad per sample.

        Returns
        -------
        complex or numpy.ndarray
            1/(1 + jωα) with an amplifier lag, 1 without.
        """
        out: Response = 1.0
        for k, g in self.groups:
            out = out * k.plant_response(g, omega)
        return out

    def zoh_response(self, mu: float, beta: npt.ArrayLike, omega: npt.ArrayLike) -> Response | None:
        """Give the exact ZOH plant's response when an element sits between hold and device.

        Parameters
        ----------
        mu : float
            Dimensionless mass μ = m/(K T²).
        beta : float or array_like
            The (equivalent) dimensionless damping β.
        omega : float or array_like
            Angular frequency ω in rad per sample.

        Returns
        -------
        complex, numpy.ndarray or None
            G(e^{jω}) of hold, element and device (:mod:`dfa.core.zohlag`); None for the device alone.
        """
        for k, g in self.groups:
            out = k.zoh_response(g, mu, beta, omega)
            if out is not None:
                return out
        return None

    def low_frequency_delay(self) -> float:
        """Give the samples of delay at low frequency.

        Returns
        -------
        float
            The delay d + α (the net damping of :func:`dfa.analysis.simulation.net_damping`).
        """
        return sum(k.low_frequency_delay(g) for k, g in self.groups)

    def sweep_points(self) -> int:
        """Give the most stiffnesses a K_max sweep simulates with this wall.

        Returns
        -------
        int
            The costliest element's :attr:`~dfa.model.elements.Element.sweep_points`.
        """
        from .elements import SWEEP_MAX_POINTS

        return min([SWEEP_MAX_POINTS] + [k.sweep_points for k, _ in self.groups])

    @classmethod
    def from_dict(cls, data: Mapping[str, object]) -> WallParams:
        """Give the groups of :meth:`to_dict`'s record, each element read by its class in :data:`ELEMENTS`.

        Parameters
        ----------
        data : mapping
            The record (its entries for absent elements may be None or missing).

        Returns
        -------
        WallParams

        Examples
        --------
        >>> p = WallParams.of(damping=0.3, delay=1, cutoff=0.05)
        >>> WallParams.from_dict(p.to_dict()) == p
        True
        """
        items = [(k, k.group_from_dict(data)) for k in ELEMENTS]
        return cls(tuple((k, g) for k, g in items if g is not None))

    def to_dict(self) -> dict[str, object]:
        """The groups as a JSON-able dictionary, every registered element's (its ``absent`` value when absent).

        Returns
        -------
        dict
            ``{"damping": β_B, "delay": d, "cutoff": ν_c or None, "lag": α}`` and any further element's group.
        """
        out: dict[str, object] = {k.parameter.group: self.group(k) for k in ALWAYS_RECORDED}
        for k, g in self.groups:
            out.update(k.group_json(g))
        why = {key: reason for k in ELEMENTS for key, reason in k.null_reasons}
        return explain_nulls(out, why)


@dataclass(frozen=True)
class Wall:
    """A virtual wall in physical units: the spring K and its elements (see the module docstring).

    Parameters
    ----------
    stiffness : float
        Virtual spring K in N/m (rotary: N·m/rad), > 0.
    elements : sequence of Element, optional
        The wall's elements (:mod:`dfa.model.elements`), at most one of each kind; default none, the paper's
        spring. :meth:`of` builds a wall from the built-in elements' physical values.

    Warns
    -----
    ImplausibleInputWarning
        For a K above 1e7 (N/m or N·m/rad), which no haptic device renders (:mod:`dfa.plausibility`), when the
        wall is built outside dfa; dfa's own searches over K never warn.

    Examples
    --------
    >>> from dfa.model.elements import AmplifierLag
    >>> Wall(1000.0, [AmplifierLag(1000.0)]).amplifier_time_constant
    0.00015915494309189535
    >>> Wall.of(1000.0, damping=0.0).elements      # a damper of 0 is no damper
    ()
    """

    stiffness: float
    elements: tuple[Element[object], ...] = field(default=())

    def __post_init__(self) -> None:
        fix = "give the virtual wall stiffness K in N/m"
        object.__setattr__(self, "stiffness", check_positive("stiffness", self.stiffness, fix))
        object.__setattr__(self, "elements", _ordered(self.elements))
        warn_if_from_outside("stiffness", self.stiffness)  # K above any haptic wall, given from outside dfa

    @classmethod
    def of(
        cls,
        stiffness: float,
        damping: float = 0.0,
        delay: int = 0,
        filter_cutoff: float | None = None,
        amplifier_bandwidth: float | None = None,
        hand_stiffness: float = 0.0,
        max_force: float | None = None,
        travel: float | None = None,
    ) -> Wall:
        """A wall of the built-in elements from their physical values (a neutral value adds no element).

        Parameters
        ----------
        stiffness : float
            Virtual spring K in N/m (rotary: N·m/rad), > 0.
        damping : float, optional
            Virtual damper B in N·s/m (rotary: N·m·s/rad), >= 0 (default 0: none).
        delay : int, optional
            Computational delay d in whole samples, >= 0 (default 0).
        filter_cutoff : float or None, optional
            Cutoff f_c in Hz of the first-order low-pass on the velocity estimate, below the Nyquist frequency
            1/(2T); None (default) for no filter.
        amplifier_bandwidth : float or None, optional
            Bandwidth f_bw in Hz of the current amplifier (a first-order lag τ_a = 1/(2π f_bw)); None
            (default) for an ideal amplifier.
        hand_stiffness : float, optional
            Stiffness k_h in N/m (rotary: N·m/rad) of a hand holding the device, a spring to a fixed reference
            at the wall's origin, >= 0 (default 0: none; :class:`~dfa.model.elements.HandSpring`).
        max_force : float or None, optional
            The actuator's force limit F_max in N (rotary: N·m), > 0: the wall's command is clipped to ±F_max
            (None, the default: the wall sets none, and a :class:`~dfa.model.loop.Loop` adds its device's;
            :class:`~dfa.model.elements.ForceLimit`).
        travel : float or None, optional
            The device's travel in m (rotary: rad) from the centre to either end stop, > 0 (None, the default: the
            wall sets none, and a :class:`~dfa.model.loop.Loop` adds its device's; :class:`~dfa.model.elements.Travel`).

        Returns
        -------
        Wall

        Examples
        --------
        >>> Wall.of(1000.0, max_force=3.0, travel=0.05).elements
        (ForceLimit(max_force=3.0), Travel(travel=0.05))
        """
        check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        elements: list[Element[object]] = []
        d = Delay(delay)
        if d.delay:
            elements.append(d)
        b = Damper(damping)
        if b.damping:
            elements.append(b)
        if filter_cutoff is not None:
            elements.append(VelocityFilter(filter_cutoff))
        if amplifier_bandwidth is not None:
            elements.append(AmplifierLag(amplifier_bandwidth))
        hand = HandSpring(hand_stiffness)
        if hand.hand_stiffness:
            elements.append(hand)
        if max_force is not None:
            elements.append(ForceLimit(max_force))
        if travel is not None:
            elements.append(Travel(travel))
        return cls(stiffness, tuple(elements))

    def element(self, kind: type[E]) -> E | None:
        """Give the wall's element of one class, to read its value (the push's force, a controller's window).

        Parameters
        ----------
        kind : type
            An element class (:mod:`dfa.model.elements`).

        Returns
        -------
        Element or None
            The wall's element of that class; None when the wall has none.

        Examples
        --------
        >>> Wall.of(1000.0, damping=2.0).element(Damper)
        Damper(damping=2.0)
        """
        for e in self.elements:
            if isinstance(e, kind):
                return e
        return None

    @property
    def damping(self) -> float:
        """Virtual damper B in N·s/m (0: none)."""
        e = self.element(Damper)
        return 0.0 if e is None else float(e.damping)

    @property
    def delay(self) -> int:
        """Computational delay d in samples (0: none)."""
        e = self.element(Delay)
        return 0 if e is None else int(e.delay)

    @property
    def filter_cutoff(self) -> float | None:
        """Velocity-filter cutoff f_c in Hz (None: no filter)."""
        e = self.element(VelocityFilter)
        return None if e is None else e.filter_cutoff

    @property
    def amplifier_bandwidth(self) -> float | None:
        """Amplifier bandwidth f_bw in Hz (None: an ideal amplifier)."""
        e = self.element(AmplifierLag)
        return None if e is None else e.amplifier_bandwidth

    @property
    def hand_stiffness(self) -> float:
        """Hand stiffness k_h in N/m (0: none)."""
        e = self.element(HandSpring)
        return 0.0 if e is None else float(e.hand_stiffness)

    @property
    def one_sided(self) -> bool:
        """True for a one-sided wall (:class:`~dfa.model.elements.OneSided`)."""
        return self.element(OneSided) is not None

    @property
    def surface(self) -> float | None:
        """A one-sided wall's surface s in encoder ticks (None for a bilateral wall)."""
        e = self.element(OneSided)
        return None if e is None else float(e.surface)

    @property
    def push(self) -> float:
        """The operator's push toward a one-sided wall F_p in N (rotary: N·m); 0 for none."""
        e = self.element(Push)
        return 0.0 if e is None else float(e.push)

    @property
    def passivity_controller(self) -> PassivityController | None:
        """The wall's passivity controller (:class:`~dfa.model.elements.PassivityController`), or None."""
        return self.element(PassivityController)

    def covers(self, what: Coverage) -> bool:
        """Tell whether every analysis of ``what`` covers this wall, for the analyses the elements' classes decide.

        The linear loop, the describing function, Colgate–Schenkel, the start at the surface and the simulation
        (:meth:`Element.class_coverage <dfa.model.elements.Element.class_coverage>`) need no groups; the criterion
        and the closed forms do: ask the groups, ``wall.params(T, Δ).covers(...)`` (:meth:`WallParams.covers`).

        Parameters
        ----------
        what : Coverage
            One analysis or several, among those the classes decide.

        Returns
        -------
        bool
            True when every element class of the wall covers every flag of ``what``.

        Raises
        ------
        DFAValueError
            For the criterion or the closed forms.

        Examples
        --------
        >>> from dfa.model.elements import OneSided
        >>> Wall(100.0, (OneSided(0.25),)).covers(Coverage.SURFACE_START), Wall(100.0).covers(Coverage.LINEAR)
        (False, True)
        """
        if what & ~_BY_CLASS:
            raise DFAValueError(
                f"what = {what!r} is invalid: whether it covers a wall depends on the elements' groups; ask "
                "wall.params(T, Δ).covers(what), or pass one of the analyses the classes decide alone"
            )
        return all(type(e).class_coverage().covers(what) for e in self.elements)

    def linear_reason(self) -> str | None:
        """Say why the linear loop (exact linear bound, describing function) does not cover this wall.

        Returns
        -------
        str or None
            The first element's reason (a one-sided wall, a passivity controller); None when it covers the wall.
        """
        reasons = [type(e).linear_reason for e in self.elements if type(e).linear_reason]
        return reasons[0] if reasons else None

    @property
    def linear(self) -> bool:
        """True when the linear loop (exact linear bound, describing function) covers the wall."""
        return self.linear_reason() is None

    def without_controller(self) -> Wall:
        """The same wall without its passivity controller: what the controller is compared against.

        Returns
        -------
        Wall
            This wall's stiffness and other elements.
        """
        return Wall(self.stiffness, tuple(e for e in self.elements if not isinstance(e, PassivityController)))

    @property
    def amplifier_time_constant(self) -> float:
        """Amplifier time constant τ_a = 1/(2π f_bw) in s (0 for an ideal amplifier)."""
        bw = self.amplifier_bandwidth
        return 0.0 if bw is None else 1.0 / (2.0 * math.pi * bw)

    def with_stiffness(self, stiffness: float) -> Wall:
        """The same elements at another stiffness K (N/m; N·m/rad): how K_max searches vary K.

        Parameters
        ----------
        stiffness : float
            The new stiffness K in N/m (rotary: N·m/rad), > 0.

        Returns
        -------
        Wall
            This wall's elements with that spring.
        """
        return Wall(stiffness, self.elements)

    def in_contact(self) -> Wall:
        """The wall as it acts while the device is in contact: without its one-sided contact and push.

        Returns
        -------
        Wall
            This wall's stiffness and other elements (the bilateral wall a one-sided wall is in contact); the wall
            itself when it is bilateral.

        Examples
        --------
        >>> from dfa.model.elements import OneSided
        >>> Wall(100.0, (OneSided(0.25),)).in_contact().one_sided
        False
        """
        return Wall(self.stiffness, tuple(e for e in self.elements if not isinstance(e, (OneSided, Push))))

    def with_damping(self, damping: float) -> Wall:
        """The same wall with its virtual damper set to B (N·s/m; rotary N·m·s/rad; 0: no damper).

        Parameters
        ----------
        damping : float
            The virtual damping B in N·s/m (rotary: N·m·s/rad), >= 0.

        Returns
        -------
        Wall
            This wall's other elements and stiffness with that damper: how a Z-width varies B.
        """
        others = tuple(e for e in self.elements if not isinstance(e, Damper))
        b = Damper(damping)
        return Wall(self.stiffness, others + ((b,) if b.damping else ()))

    def params(
        self,
        period: float,
        resolution: float | None = None,
        *,
        names: Mapping[str, str] | None = None,
        rotary: bool = False,
    ) -> WallParams:
        """Dimensionless groups (β_B, d, ν_c, α and any further element's) at sample period ``period``.

        Parameters
        ----------
        period : float
            Sample period T in s, > 0.
        resolution : float, optional
            Encoder resolution Δ in m (rotary: rad), for elements whose group needs it (a push, p = F_p/(K Δ)).
        names : mapping, optional
            How a message calls each element's physical value, by its parameter name (the command line passes its
            flags, ``{"damping": "--virtual-damping"}``); default the parameter names.
        rotary : bool, optional
            Word a message's units for a rotary device (default linear).

        Returns
        -------
        WallParams
            Each element's group, e.g. β_B = B/(K T), d, ν_c = f_c T and α = τ_a/T.

        Raises
        ------
        DFAValueError
            If the filter cutoff is not below the Nyquist frequency 1/(2T), or a group a float cannot hold (a
            damper of 1e308 N·s/m over K T; :class:`~dfa.model.elements.GroupRangeError`: the message names the
            physical value, what overflowed and the value that works).
        """
        t = check_positive("period", period, "give the sample period T in s (1 kHz: 0.001)")

        def group(e: Element[object]) -> object:
            try:
                if type(e).needs_resolution:
                    return e.group(t, self.stiffness, resolution=resolution)  # type: ignore[call-arg]
                return e.group(t, self.stiffness)
            except GroupRangeError as err:
                if names is None and not rotary:
                    raise
                raise DFAValueError(err.message(dict(names or {}), rotary)) from None

        return WallParams(tuple((type(e), group(e)) for e in self.elements))

    @classmethod
    def from_dict(cls, data: Mapping[str, object]) -> Wall:
        """Give the wall of :meth:`to_dict`'s record, each element read by its class in :data:`ELEMENTS`.

        Parameters
        ----------
        data : mapping
            The record: ``stiffness`` and each element's keys (:meth:`~dfa.model.elements.Element.record_keys`).

        Returns
        -------
        Wall

        Examples
        --------
        >>> w = Wall.of(1000.0, damping=2.0, delay=1, filter_cutoff=100.0)
        >>> Wall.from_dict(w.to_dict()) == w
        True
        """
        stiffness = data.get("stiffness")
        if not isinstance(stiffness, (int, float)):
            raise DFATypeError(f"stiffness = {format_value(stiffness)} is invalid: a wall's record gives its K in N/m")
        items = [k.from_record(data) for k in ELEMENTS]
        return cls(float(stiffness), tuple(e for e in items if e is not None))

    def to_dict(self) -> dict[str, object]:
        """The wall's physical parameters as a JSON-able dictionary.

        Returns
        -------
        dict
            Stiffness, damping, delay, filter cutoff and amplifier bandwidth (SI units, None where absent).
        """
        out: dict[str, object] = {"stiffness": self.stiffness}
        for k in ALWAYS_RECORDED:  # the spring's record: these elements' entries, absent values where absent
            e = self.element(k)
            out.update(k.absent_record() if e is None else e.record())
        for e in self.elements:  # any other element's entries (its record keys), only when the wall has it
            if type(e) not in ALWAYS_RECORDED:
                out.update(e.record())
        why = {key: reason for k in ELEMENTS for key, reason in k.null_reasons}
        return explain_nulls(out, why)
