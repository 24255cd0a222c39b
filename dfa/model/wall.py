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
(:meth:`WallParams.corner`), the simulator's arguments (:meth:`WallParams.kernel_args`), the exact sampled
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
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from ..checks import check_positive, format_value
from ..errors import DFATypeError, DFAValueError
from ..jsonable import explain_nulls
from ..plausibility import warn_if_from_outside
from .elements import (
    ELEMENTS,
    MIN_CUTOFF,
    MIN_LAG,
    AmplifierLag,
    CommandPolynomials,
    Damper,
    Delay,
    Element,
    GroupRangeError,
    HandSpring,
    NotCovered,
    OneSided,
    PassivityController,
    Push,
    VelocityFilter,
)

__all__ = ["Wall", "WallParams", "MIN_CUTOFF", "MIN_LAG", "SPRING_CORNER"]

#: The corner (β₀, σ₀) of the paper's spring (eq. 6): (½, ½) with the encoder, (½, 0) without (eq. 7).
SPRING_CORNER = (0.5, 0.5)


def _ordered(elements: Any) -> tuple[Element, ...]:
    """The elements as a tuple in the order of :data:`~dfa.model.elements.ELEMENTS` (others after, as given)."""
    if isinstance(elements, Element):
        elements = (elements,)
    try:
        items = tuple(elements)
    except TypeError:
        raise DFATypeError(
            f"elements = {format_value(elements)} is invalid: it must be a sequence of wall elements; "
            "give e.g. (dfa.Damper(1.0), dfa.Delay(1))"
        ) from None
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

    groups: tuple[tuple[type[Element], Any], ...] = ()

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
    ) -> WallParams:
        """The groups of the built-in elements: β_B, d, ν_c (None: no filter), α and κ_h.

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

        Returns
        -------
        WallParams
            The groups of the elements that render something.
        """
        items: list[tuple[type[Element], Any]] = [
            (Delay, delay), (Damper, damping), (AmplifierLag, lag), (HandSpring, hand_stiffness)
        ]  # fmt: skip
        if cutoff is not None:
            items.append((VelocityFilter, cutoff))
        return cls(tuple(items))

    def group(self, kind: type[Element]) -> Any:
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
                return g
        return kind.absent

    # ------------------------------------------------------------------ the built-in groups by name
    @property
    def damping(self) -> float:
        """The virtual damping β_B = B/(K T) (0 without damper)."""
        return float(self.group(Damper))

    @property
    def delay(self) -> int:
        """The computational delay d in samples: what every element delays the command by (0: none)."""
        return int(self.kernel_args()["delay"])

    @property
    def cutoff(self) -> float | None:
        """The filter cutoff ν_c = f_c T in cycles per sample (None without filter)."""
        return self.group(VelocityFilter)

    @property
    def lag(self) -> float:
        """The amplifier time constant α = τ_a/T in samples (0 without amplifier lag)."""
        return float(self.group(AmplifierLag))

    @property
    def filter_pole(self) -> float:
        """Pole a = e^{−2π ν_c} of the discretised velocity filter (0 without filter)."""
        c = self.cutoff
        return 0.0 if c is None else VelocityFilter.pole(c)

    @property
    def hand_stiffness(self) -> float:
        """The hand stiffness κ_h = k_h/K (0: none; :class:`~dfa.model.elements.HandSpring`)."""
        return float(self.group(HandSpring))

    @property
    def amplifier_pole(self) -> float:
        """Decay e^{−1/α} of the amplifier's force error over one sample (0 without lag)."""
        return 0.0 if self.lag == 0.0 else math.exp(-1.0 / self.lag)

    @property
    def is_spring(self) -> bool:
        """True when the spring's compiled kernel runs the loop: the paper's spring with any delay."""
        return all(k.spring_kernel(g) for k, g in self.groups)

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

    def uncovered(self) -> tuple[type[Element], Any, str] | None:
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

    def kernel_args(self) -> dict[str, Any]:
        """Give the compiled simulator's arguments (:mod:`dfa.core.wall_kernel`).

        Returns
        -------
        dict
            ``delay`` (samples), ``damping`` β_B, ``pole`` a, ``filtered``, ``lag`` α, ``spring`` κ_h (the hand
            stiffness), ``onesided``, ``surface`` s, ``push`` p, and the passivity controller's ``pc`` (on),
            ``window`` W (samples; 0: unbounded) and ``limit`` (K Δ; inf: none), from every element.
        """
        out: dict[str, Any] = {
            "delay": 0, "damping": 0.0, "pole": 0.0, "filtered": False, "lag": 0.0, "spring": 0.0,
            "onesided": False, "surface": 0.0, "push": 0.0, "pc": False, "window": 0, "limit": math.inf,
        }  # fmt: skip
        for k, g in self.groups:
            for key, value in k.kernel(g).items():
                out[key] = out[key] + value if key == "delay" else value
        return out

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

    def plant(self, rate: float, mu: float) -> tuple[Any, Any] | None:
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

    def plant_response(self, omega: Any) -> Any:
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
        out: Any = 1.0
        for k, g in self.groups:
            out = out * k.plant_response(g, omega)
        return out

    def zoh_response(self, mu: float, beta: Any, omega: Any) -> Any:
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

    def to_dict(self) -> dict[str, Any]:
        """The groups as a JSON-able dictionary, every registered element's (its ``absent`` value when absent).

        Returns
        -------
        dict
            ``{"damping": β_B, "delay": d, "cutoff": ν_c or None, "lag": α}`` and any further element's group.
        """
        out = {k.parameter.group: self.group(k) for k in (Damper, Delay, VelocityFilter, AmplifierLag)}
        for k, g in self.groups:
            out.update(k.group_json(g))
        why = {"cutoff": "no velocity filter", "pc_force_limit": "no force limit (the passivity controller's)"}
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
    elements: tuple[Element, ...] = field(default=())

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

        Returns
        -------
        Wall
        """
        check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        elements: list[Element] = []
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
        return cls(stiffness, tuple(elements))

    def _value(self, kind: type[Element], absent: Any) -> Any:
        for e in self.elements:
            if isinstance(e, kind):
                return e.value
        return absent

    @property
    def damping(self) -> float:
        """Virtual damper B in N·s/m (0: none)."""
        return float(self._value(Damper, 0.0))

    @property
    def delay(self) -> int:
        """Computational delay d in samples (0: none)."""
        return int(self._value(Delay, 0))

    @property
    def filter_cutoff(self) -> float | None:
        """Velocity-filter cutoff f_c in Hz (None: no filter)."""
        return self._value(VelocityFilter, None)

    @property
    def amplifier_bandwidth(self) -> float | None:
        """Amplifier bandwidth f_bw in Hz (None: an ideal amplifier)."""
        return self._value(AmplifierLag, None)

    @property
    def hand_stiffness(self) -> float:
        """Hand stiffness k_h in N/m (0: none)."""
        return float(self._value(HandSpring, 0.0))

    @property
    def one_sided(self) -> bool:
        """True for a one-sided wall (:class:`~dfa.model.elements.OneSided`)."""
        return self._value(OneSided, None) is not None

    @property
    def surface(self) -> float | None:
        """A one-sided wall's surface s in encoder ticks (None for a bilateral wall)."""
        value = self._value(OneSided, None)
        return None if value is None else float(value)

    @property
    def push(self) -> float:
        """The operator's push toward a one-sided wall F_p in N (rotary: N·m); 0 for none."""
        return float(self._value(Push, 0.0))

    @property
    def passivity_controller(self) -> PassivityController | None:
        """The wall's passivity controller (:class:`~dfa.model.elements.PassivityController`), or None."""
        for e in self.elements:
            if isinstance(e, PassivityController):
                return e
        return None

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

        def group(e: Element) -> Any:
            try:
                if type(e).needs_resolution:
                    return e.group(t, self.stiffness, resolution=resolution)  # type: ignore[call-arg]
                return e.group(t, self.stiffness)
            except GroupRangeError as err:
                if names is None and not rotary:
                    raise
                raise DFAValueError(err.message(dict(names or {}), rotary)) from None

        return WallParams(tuple((type(e), group(e)) for e in self.elements))

    def to_dict(self) -> dict[str, object]:
        """The wall's physical parameters as a JSON-able dictionary.

        Returns
        -------
        dict
            Stiffness, damping, delay, filter cutoff and amplifier bandwidth (SI units, None where absent).
        """
        out: dict[str, object] = {
            "stiffness": self.stiffness,
            "damping": self.damping,
            "delay": self.delay,
            "filter_cutoff": self.filter_cutoff,
            "amplifier_bandwidth": self.amplifier_bandwidth,
        }
        if self.hand_stiffness:  # only with a hand stiffness: every other wall's record is unchanged
            out["hand_stiffness"] = self.hand_stiffness
        if self.surface is not None:  # only for a one-sided wall, and its push if any
            out["one_sided_surface"] = self.surface
            out["push"] = self.push
        pc = self.passivity_controller
        if pc is not None:  # only with a passivity controller: its window (s) and force limit (N)
            out["passivity_controller_window"] = pc.window
            out["passivity_controller_force_limit"] = pc.force_limit
        why = {
            "filter_cutoff": "no velocity filter",
            "amplifier_bandwidth": "ideal amplifier (no lag)",
            "passivity_controller_window": "an unbounded observer (the whole run)",
            "passivity_controller_force_limit": "no force limit",
        }
        return explain_nulls(out, why)
