"""Passivity-criterion results: the criterion's verdict (:class:`CriterionResult`), its critical line, the `dfa check`
record (:class:`PassivityCheck`), the Colgate–Schenkel conditions, and the start state each guarantee is proven for
(computed in :mod:`dfa.analysis.criterion`, ``check`` and ``colgate_schenkel``)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from ..checks import (
    check_bool,
    check_delay,
    check_nonnegative,
    check_positive,
    check_real,
    check_type,
)
from ..errors import DFAValueError
from ..model.device import Device
from ..model.elements import Coverage
from ..model.wall import Wall, WallParams
from .base import Result, figure_function
from .status import CheckStatus, CriterionStatus, PassivityStatus

if TYPE_CHECKING:
    from matplotlib.axes import Axes

#: The loop's memory at t = 0 a guarantee can be asked for: the documented fresh start, or a moving history.
HISTORIES = ("fresh", "moving")


def start_state(wall: Any, history: str = "fresh") -> str:
    """The start state the criterion's guarantee for ``wall`` is proven for (module docstring, steps 2 and 3).

    A wall without delay or damper has no memory: only the reading at t = 0 (a sample instant) enters the proof,
    so any history will do. Otherwise the wall's memory must be fresh at t = 0, as if at rest there: the d pending
    commands equal the first (the spring force at the first reading), the previous reading equals the first (a
    velocity estimate of 0) and the filter's output is 0. From a memory of earlier motion an independent check
    found the energy above its start at points called passive (with a delay, and with a damper and a low-cutoff
    filter after an approach from free space): the spring with a delay is covered for a moving history
    (``history="moving"``, :func:`moving_history_speed`), a one-sided wall for its approach from free space.

    Parameters
    ----------
    wall : Wall or WallParams
        Anything with ``delay`` (samples) and ``damping`` (the virtual damper; 0 for none).
    history : {"fresh", "moving"}, optional
        The memory the guarantee was asked for (:data:`HISTORIES`; default the fresh start).

    Returns
    -------
    str
        The start state, in words.

    Examples
    --------
    >>> start_state(WallParams())[:40]
    'any: this wall has no memory (only the r'
    """
    if getattr(wall, "one_sided", False):
        return (
            "an approach from free space at V: the device reaches the wall's first seen position at V (the "
            "operator's force balancing friction until the first reading inside, then the push, if any)"
        )
    if history == "moving" and wall.delay:
        return (
            f"a moving history: the device moved at ξ'0 for the {wall.delay} sample{'s' if wall.delay != 1 else ''} "
            "before t = 0, and the pending commands are that motion's readings"
        )
    if not has_memory(wall):
        return "any: this wall has no memory (only the reading at t = 0, a sample instant, enters the proof)"
    fresh = []
    if wall.delay:
        pending = "the pending command equals" if wall.delay == 1 else f"the {wall.delay} pending commands equal"
        fresh.append(f"{pending} the first (the spring force at the first reading)")
    if wall.damping:
        fresh.append("the previous reading equals the first (velocity estimate 0)")
        if getattr(wall, "cutoff", getattr(wall, "filter_cutoff", None)) is not None:
            fresh.append("the filter's output is 0")
    moving = ": see history='moving' (--history moving)" if not wall.damping else " is not covered"
    return f"the wall's memory fresh at t = 0: {'; '.join(fresh)}; a memory of earlier motion{moving}"


def has_memory(wall: Any) -> bool:
    """Whether ``wall`` (a Wall or WallParams) has memory: a delay or a damper (:func:`start_state`)."""
    return not (wall.delay == 0 and wall.damping == 0.0)


#: One-line meaning of each region of paper Fig. 3 for the spring (text before the first colon: short label).
#: Only a and e are guarantees; b, c, d say what is *not* guaranteed.
REGION_DESCRIPTIONS = {s.region: s.message for s in CriterionStatus}


_REGION_CODES = np.array(["a", "b", "c", "d", "e"])


def _anchor(quantized: ArrayLike, delay: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """(σ₀, β₀) of the spring's critical line: σ₀ = ½ with quantization (0 without), β₀ = ½ + d (broadcast)."""
    return np.where(np.asarray(quantized, dtype=bool), 0.5, 0.0), 0.5 + np.asarray(delay, dtype=float)


def _margin(
    beta: float | np.ndarray,
    sigma: float | np.ndarray,
    speed: float | np.ndarray,
    sigma0: float | np.ndarray,
    beta0: float | np.ndarray,
) -> float | np.ndarray:
    """(β − β₀)V + (σ − σ₀): the left side of eq. 6 (eq. 10's line is margin = 0). The one evaluation every verdict uses."""
    return (beta - beta0) * speed + (sigma - sigma0)


def region_of(
    b: float | np.ndarray, s: float | np.ndarray, v: float | np.ndarray, s0: float | np.ndarray, b0: float | np.ndarray
) -> np.ndarray:
    """Region letters a-e of (β, σ) at speed V for the critical line through (β₀, σ₀) (no validation, broadcast).

    The one rule behind every verdict: a (β >= β₀, σ >= σ₀), b (β >= β₀, σ < σ₀), c (β < β₀, σ < σ₀),
    d/e (β < β₀, σ >= σ₀, margin < 0 / >= 0).
    """
    with np.errstate(over="ignore"):  # an overflowing margin keeps its sign, which is all that is used
        margin = _margin(b, s, v, s0, b0)
    high_beta = b >= b0
    high_sigma = s >= s0
    idx = np.where(
        high_beta,
        np.where(high_sigma, 0, 1),
        np.where(high_sigma, np.where(margin >= 0.0, 4, 3), 2),
    )
    return _REGION_CODES[idx]


@dataclass(frozen=True)
class CriticalLine:
    """The critical line of eq. 10 in the (β, σ) plane for one speed: σ = σ₀ + V(β₀ − β).

    A line through the corner (β₀, σ₀) with slope −V, where V is the (energy-equivalent) speed. For the
    paper's spring with a delay of d samples the corner is (½ + d, ½), or (½ + d, 0) without quantization
    (:meth:`of`); a wall with a damper or a filter moves it (:mod:`dfa.analysis.criterion`). Points
    on or above the line satisfy the first inequality of the criterion (eq. 6 for the corner (½, ½)).

    Attributes
    ----------
    xi_dot : float
        The (energy-equivalent) speed V in ticks per sample, made non-negative; the slope is −V.
    beta0 : float
        β₀, where the line meets σ = σ₀: ½ + d for the spring with a delay of d samples (eq. 10;
        Diolaiti et al. 2006 for d > 0).
    sigma0 : float
        σ₀: ½ with quantization (eq. 6), 0 without (eq. 7), for the spring.

    Examples
    --------
    >>> line = CriticalLine(xi_dot=2.0)
    >>> line.slope, line.sigma(0.0)
    (-2.0, 1.5)
    >>> CriticalLine.of(2.0, delay=1).sigma(0.0)          # through (1.5, 0.5)
    3.5
    >>> line.regions([0.2, 0.6], [2.0, 0.2]).tolist()
    ['e', 'b']
    """

    xi_dot: float
    beta0: float = 0.5
    sigma0: float = 0.5

    def __post_init__(self) -> None:
        object.__setattr__(self, "xi_dot", abs(check_real("xi_dot", self.xi_dot)))
        object.__setattr__(self, "beta0", check_nonnegative("beta0", self.beta0))
        object.__setattr__(self, "sigma0", check_nonnegative("sigma0", self.sigma0))

    @classmethod
    def of(cls, xi_dot: float, *, quantized: bool = True, delay: int = 0) -> CriticalLine:
        """The spring's line with (eq. 6) or without (eq. 7) quantization and a delay: corner (½ + d, ½ or 0).

        Parameters
        ----------
        xi_dot : float
            The (energy-equivalent) speed V in ticks per sample; its sign is ignored.
        quantized : bool, optional
            True (default) for σ₀ = ½ (eq. 6); False for σ₀ = 0 (eq. 7).
        delay : int, optional
            Computational delay d in samples (default 0).

        Returns
        -------
        CriticalLine
            The line through (½ + d, σ₀) with slope −V.

        Raises
        ------
        DFAValueError, DFATypeError
            If the speed is not a finite number or the delay not a whole number >= 0.

        Examples
        --------
        >>> CriticalLine.of(2.0, quantized=False).sigma0
        0.0
        """
        q = check_bool("quantized", quantized, "pass True (eq. 6, σ₀ = ½) or False (eq. 7, σ₀ = 0)")
        s0, b0 = _anchor(q, check_delay(delay))
        return cls(xi_dot, float(b0), float(s0))

    def at_speed(self, xi_dot: float) -> CriticalLine:
        """The line of the same corner at another speed.

        Parameters
        ----------
        xi_dot : float
            The (energy-equivalent) speed V in ticks per sample; its sign is ignored.

        Returns
        -------
        CriticalLine
            The line through the same corner (β₀, σ₀) with slope −V.
        """
        return replace(self, xi_dot=xi_dot)

    def regions(self, beta: ArrayLike, sigma: ArrayLike) -> np.ndarray:
        """Region letters a-e (paper Fig. 3) of (β, σ) at this line's speed and corner (vectorised, broadcast).

        Parameters
        ----------
        beta, sigma : array_like
            Dimensionless damping β and Coulomb friction σ.

        Returns
        -------
        numpy.ndarray of str
            The letters of :func:`region_of`, the one rule of every verdict.
        """
        b = np.asarray(beta, dtype=float)
        s = np.asarray(sigma, dtype=float)
        return region_of(b, s, self.xi_dot, self.sigma0, self.beta0)

    @property
    def slope(self) -> float:
        """The slope dσ/dβ of the line, −V."""
        return -self.xi_dot

    def sigma(self, beta: float | np.ndarray) -> float | np.ndarray:
        """The σ on the line at ``beta`` (vectorised): σ₀ + V(β₀ − β), where :meth:`margin` is 0.

        Parameters
        ----------
        beta : float or numpy.ndarray
            Dimensionless damping β.

        Returns
        -------
        float or numpy.ndarray
            The σ of the line, a float for a scalar ``beta``.
        """
        out = self.sigma0 + self.xi_dot * (self.beta0 - np.asarray(beta, dtype=float))
        return float(out) if out.ndim == 0 else out

    def margin(self, beta: ArrayLike, sigma: ArrayLike) -> float | np.ndarray:
        """(β − β₀)V + (σ − σ₀) at (β, σ) (vectorised): >= 0 on or above the line (eq. 6, 10).

        Parameters
        ----------
        beta, sigma : float or array_like
            Dimensionless damping β and Coulomb friction σ (broadcast together).

        Returns
        -------
        float or numpy.ndarray
            The margin, a float for scalar inputs.

        Examples
        --------
        >>> CriticalLine(xi_dot=2.0).margin(0.0, 1.5)
        0.0
        """
        out = np.asarray(
            _margin(np.asarray(beta, dtype=float), np.asarray(sigma, dtype=float), self.xi_dot, self.sigma0, self.beta0)
        )
        return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class CriterionResult(Result):
    """Outcome of the passivity criterion for one operating point, speed, wall and initial position.

    Attributes
    ----------
    beta, sigma : float
        Dimensionless damping β = b/(K T) and Coulomb friction σ = c/(K Δ) (inputs).
    xi_dot : float
        Speed abs(ξ'0) in encoder ticks per sample (input, made non-negative).
    quantized : bool
        True for eq. 6 (with the encoder), False for eq. 7 (Δ → 0).
    region : str
        ``"a"`` … ``"e"`` as in the module docstring.
    passive : bool
        Whether the criterion holds (proven: the energy cannot grow); equals ``region in ("a", "e")``.
    margin : float
        (β − β₀)V + (σ − σ₀).
    critical_xi_dot : float or None
        Eq. 12 generalised: the largest energy-equivalent speed V for which the criterion holds,
        (σ − σ₀)/(β₀ − β), when β < β₀ and σ >= σ₀; None when it does not exist (regions a, b, c). With
        ξ0 = 0 it is the critical initial speed abs(ξ'0); for a one-sided wall, the largest impact speed V
        whose V* it is (:meth:`~dfa.model.elements.OneSided.impact_speed`).
    critical_line : CriticalLine
        The line of eq. 10 for this speed through the corner (β₀, σ₀).
    equivalent_speed : float
        V = sqrt(ξ'0² + 2H_c(ξ0)/μ) (ticks per sample); V = abs(ξ'0) when ξ0 = 0.
    xi0 : float
        Initial position ξ0 in ticks; the wall's past readings equal it.
    mu : float or None
        Dimensionless mass (needed only when ξ0 ≠ 0).
    status : CriterionStatus
        The region's meaning (:attr:`status_message` adds this case's corner and critical speed).
    wall : WallParams
        The wall's dimensionless groups (none for the paper's spring).
    device : Device or None
        The physical device, set by :func:`device_criterion`; None for dimensionless input.
    stiffness, velocity, critical_velocity, position : float or None
        Set by :func:`device_criterion`: K (N/m; N·m/rad), the speed and the critical (energy-equivalent)
        speed (m/s; rad/s), the initial position (m; rad); otherwise None.
    history : {"fresh", "moving"}
        The loop's memory at t = 0 the verdict is for (:data:`HISTORIES`; :attr:`start_state` says it).
    """

    beta: float
    sigma: float
    xi_dot: float
    quantized: bool
    region: str
    passive: bool
    margin: float
    critical_xi_dot: float | None
    critical_line: CriticalLine
    equivalent_speed: float
    xi0: float
    mu: float | None
    status: CriterionStatus
    wall: WallParams = field(default_factory=WallParams)
    device: Device | None = field(default=None, metadata={"json": lambda d: d.name})
    stiffness: float | None = None
    velocity: float | None = None
    critical_velocity: float | None = None
    position: float | None = None
    history: str = "fresh"

    json_properties: ClassVar[tuple[str, ...]] = ("delay", "beta0", "sigma0", "start_state")
    units_of: ClassVar[dict[str, str]] = {
        "stiffness": "stiffness", "velocity": "velocity", "critical_velocity": "velocity", "position": "position",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "build results with passivity_criterion"
        for name in ("beta", "sigma", "xi_dot", "margin", "equivalent_speed"):
            if math.isnan(getattr(self, name)):
                raise DFAValueError(f"{name} = nan is invalid: results hold numbers; {fix}")
        check_type("wall", self.wall, WallParams, fix)
        status = CriterionStatus.coerce(self.status)
        object.__setattr__(self, "status", status)
        if self.region not in REGION_DESCRIPTIONS or status.region != self.region:
            raise DFAValueError(
                f"status = {status.value!r} is invalid for region = {self.region!r}: they must agree "
                f"(CriterionStatus.of_region); {fix}"
            )
        if self.passive != (self.region in ("a", "e")):
            raise DFAValueError(
                f"passive = {self.passive!r} is invalid for region {self.region!r}: they must agree (only regions a "
                f"and e are passive); {fix}"
            )

    @property
    def delay(self) -> int:
        """Computational delay d in samples (the wall's)."""
        return self.wall.delay

    @property
    def start_state(self) -> str:
        """The loop's state at t = 0 that the guarantee assumes (:func:`start_state` of the wall and history)."""
        return start_state(self.wall, self.history)

    @property
    def critical_symbol(self) -> str:
        """Name what :attr:`critical_xi_dot` bounds: the speed ξ'0 itself, or the energy-equivalent V.

        ``"ξ'0"`` for a one-sided wall's impact and a moving history, ``"V"`` otherwise (ξ'0 when ξ0 = 0).
        """
        return (
            "ξ'0" if not self.wall.covers(Coverage.SURFACE_START) or (self.history == "moving" and self.delay) else "V"
        )

    @property
    def beta0(self) -> float:
        """The corner's β₀: ½ + d for the spring, ½ + d + β_B with a damper."""
        return self.critical_line.beta0

    @property
    def sigma0(self) -> float:
        """The corner's σ₀: ½ for the spring (0 without the encoder), ½ + (1 − a)β_B with a damper."""
        return self.critical_line.sigma0

    @property
    def status_message(self) -> str:
        """The status message, with this case's corner (β₀, σ₀) (and critical speed) filled in for a wall.

        Examples
        --------
        >>> from dfa.analysis.criterion import passivity_criterion
        >>> passivity_criterion(0.2, 2.03, 5.0, wall=WallParams.of(damping=0.1)).status_message.split("; ")[-1]
        'here β₀ = 0.6, σ₀ = 0.6, critical speed 3.575 ticks/sample'
        """
        if (self.beta0, self.sigma0) == (0.5 + self.delay, 0.5 if self.quantized else 0.0):
            return self.status.message  # the spring's corner: the message says it
        extra = f"here β₀ = {self.beta0:.6g}, σ₀ = {self.sigma0:.6g}"
        if self.critical_xi_dot is not None:
            extra += f", critical speed {self.critical_xi_dot:.6g} ticks/sample"
        return f"{self.status.message}; {extra}"

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            Reasons for the critical speed, the physical inputs and μ.
        """
        none = f"no critical speed: {self.status.message}"
        return {
            "critical_xi_dot": none,
            "critical_velocity": none,
            "stiffness": "dimensionless input: no stiffness",
            "velocity": "no speed in physical units given",
            "position": "no position in physical units given",
            "device": "dimensionless input: no device",
            "mu": "not needed: the start is at ξ0 = 0",
            "cutoff": "no velocity filter",
        }

    def plot(self, ax: Axes | None = None, **kwargs: Any) -> Axes:
        """The (β, σ) plane with regions a-e and this point (:func:`dfa.render.figures.regions_plot`); returns the Axes.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.
        **kwargs
            Passed on to :func:`dfa.render.figures.regions_plot`.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        regions_plot = figure_function("regions_plot")

        return regions_plot(self, ax, **kwargs)


@dataclass(frozen=True)
class PassivityCheck(Result):
    """The passivity check of ``device`` with ``wall`` at an impact speed (module docstring).

    Attributes
    ----------
    device : Device
    wall : Wall
    velocity : float
        Impact speed, m/s (rotary: rad/s), >= 0.
    criterion : CriterionResult or None
        The criterion (eq. 6 extended); None where no sound criterion covers the wall (``reasons`` says why).
    colgate_schenkel : ColgateSchenkel or None
        The Colgate–Schenkel condition, dimensionless (β_min); None where it does not cover the wall.
    reasons : dict of str to str
        Why ``criterion`` or ``colgate_schenkel`` is None, by that name.
    status : CheckStatus
        ``passive`` (proven by the criterion), ``no_guarantee`` or ``not_covered``.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    criterion: CriterionResult | None
    colgate_schenkel: ColgateSchenkel | None
    reasons: dict[str, str]
    status: CheckStatus

    json_properties: ClassVar[tuple[str, ...]] = (
        "passive", "start_state", "colgate_schenkel_damping", "colgate_schenkel_bound", "colgate_schenkel_met",
    )  # fmt: skip
    units_of: ClassVar[dict[str, str]] = {
        "velocity": "velocity", "colgate_schenkel_damping": "damping", "colgate_schenkel_bound": "damping",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "PassivityCheck is built by dfa.analysis.check.passivity_check; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        check_real("velocity", self.velocity, fix)
        object.__setattr__(self, "status", CheckStatus.coerce(self.status))
        for name in ("criterion", "colgate_schenkel"):
            if (getattr(self, name) is None) != (name in self.reasons):
                raise DFAValueError(f"{name} is None exactly when reasons[{name!r}] says why; {fix}")

    @property
    def covered(self) -> bool:
        """False where no sound criterion covers the wall (an amplifier lag)."""
        return self.criterion is not None

    @property
    def passive(self) -> bool | None:
        """The criterion's verdict (proven passive, or no guarantee); None where not covered."""
        return None if self.criterion is None else bool(self.criterion.passive)

    @property
    def start_state(self) -> str:
        """The start state ``passive`` is proven for (:func:`dfa.analysis.criterion.start_state` of the wall)."""
        return start_state(self.wall)

    @property
    def colgate_schenkel_damping(self) -> float | None:
        """The least viscous friction b = K T β_min the condition needs, N·s/m (rotary: N·m·s/rad)."""
        cs = self.colgate_schenkel
        return None if cs is None else self.wall.stiffness * self.device.period * cs.beta_min

    @property
    def colgate_schenkel_bound(self) -> float | None:
        """Any b above this meets the condition (certified, rounding included), N·s/m (rotary: N·m·s/rad)."""
        cs = self.colgate_schenkel
        return None if cs is None else self.wall.stiffness * self.device.period * cs.beta_bound

    @property
    def colgate_schenkel_met(self) -> bool | None:
        """Whether the device's b meets the condition for sure (above the certified bound); None: not covered."""
        bound = self.colgate_schenkel_bound
        return None if bound is None else bool(self.device.damping > bound)

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            The reasons for the criterion and the Colgate–Schenkel condition where they do not apply.
        """
        out = dict(self.reasons)
        if "criterion" in out:
            out["passive"] = f"not covered by the criterion: {out['criterion']}"
        if "colgate_schenkel" in out:
            for k in ("colgate_schenkel_damping", "colgate_schenkel_bound", "colgate_schenkel_met"):
                out[k] = out["colgate_schenkel"]
        return out


@dataclass(frozen=True)
class ColgateSchenkel(Result):
    """Dimensionless Colgate–Schenkel condition: passive iff β = b/(KT) > β_min (module docstring).

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`) holds every field (``params`` as the wall's groups) and
    the status's message.

    Attributes
    ----------
    beta_min : float
        ½ max f found (attained at ``theta``): the condition needs β above it.
    beta_bound : float
        Certified upper bound of ½ max f (rounding included): β above it meets the condition.
    theta : float
        Where the maximum was found, rad/sample (ωT), in [0, π].
    params : WallParams
        The controller (β_B, d, ν_c; α = 0).
    status : PassivityStatus
    """

    beta_min: float
    beta_bound: float
    theta: float
    params: WallParams
    status: PassivityStatus

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", PassivityStatus.coerce(self.status))
        if not (math.isfinite(self.beta_min) and self.beta_min <= self.beta_bound and 0.0 <= self.theta <= math.pi):
            raise DFAValueError(
                f"beta_min = {self.beta_min!r}, beta_bound = {self.beta_bound!r}, theta = {self.theta!r} are "
                "invalid: they must be finite, beta_min <= beta_bound, 0 <= theta <= π; pass the computed values"
            )


@dataclass(frozen=True)
class ColgateSchenkelDamping(Result):
    """Minimum physical damping b for passivity of a device with ``wall`` at period T (Colgate–Schenkel).

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`, SI units) holds every field, the :attr:`frequency` (Hz),
    the :attr:`status` and its message.

    Attributes
    ----------
    damping_min : float
        K T β_min, N·s/m (rotary: N·m·s/rad): the condition needs b above it.
    damping_bound : float
        K T β_bound: any b above it meets the condition (certified), N·s/m.
    omega : float
        Angular frequency θ/T of the maximum, rad/s.
    wall : Wall
        The wall (stiffness K and its elements) whose H(z) is checked.
    period : float
        Sampling period T, s.
    dimensionless : ColgateSchenkel
    """

    damping_min: float
    damping_bound: float
    omega: float
    wall: Wall
    period: float
    dimensionless: ColgateSchenkel

    json_properties: ClassVar[tuple[str, ...]] = ("frequency", "status")

    def __post_init__(self) -> None:
        fix = "ColgateSchenkelDamping is built by colgate_schenkel_damping; call that instead"
        check_type("wall", self.wall, Wall, fix)
        check_type("dimensionless", self.dimensionless, ColgateSchenkel, fix)
        check_positive("period", self.period, fix)

    @property
    def frequency(self) -> float:
        """Frequency of the maximum, Hz."""
        return self.omega / (2.0 * math.pi)

    @property
    def status(self) -> PassivityStatus:
        """As :attr:`ColgateSchenkel.status`."""
        return self.dimensionless.status

    def passive(self, damping: float) -> bool:
        """Tell whether a device damping meets the condition for sure (above the certified bound).

        Parameters
        ----------
        damping : float
            The device's viscous friction b, N·s/m (rotary: N·m·s/rad), > 0.

        Returns
        -------
        bool
            True if b > ``damping_bound``.
        """
        return check_positive("damping", damping, "give the device's viscous friction b in N·s/m") > self.damping_bound
