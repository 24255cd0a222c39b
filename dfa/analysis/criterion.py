"""Passivity criterion of Diolaiti et al. (ICRA 2005), eq. 6-12 and 35, with a computational delay and an initial position.

The theorem
-----------
Dimensionless loop (paper eq. 4-5) with a computational delay of d samples: the
force held over sample h is φ = −q(ξ_{h−d}), q(s) = ⌊s⌋ + ½ (eq. 5), and before the
first sample the controller's past readings equal ξ0. Let

    S = ½μξ'² + ½ξ²

(the paper's storage H_T of eq. 19 minus the bounded term ½(p − p²) ∈ [0, 1/8] of
eq. 18) and Δ_h = ξ_{h+1} − ξ_h. Over sample h the force does work φΔ_h and ½ξ²
changes by ξ_hΔ_h + ½Δ_h², so

    S_{h+1} − S_h = ½Δ_h² + (ξ_h − q(ξ_{h−d}))Δ_h − D_h,
    D_h = β∫ξ'² + σ∫|ξ'| >= βΔ_h² + σ|Δ_h|          (Cauchy-Schwarz; eq. 30, 32)
    ξ_h − q(ξ_{h−d}) = Σ_{j=1..d} Δ_{h−j} + (p_{h−d} − ½),   p = ξ − ⌊ξ⌋ (eq. 17), |p − ½| <= ½.

Summing over h = 0 … n−1 (Δ_k = 0 for k < 0) and bounding every cross product by
|Δ_hΔ_{h−j}| <= ½(Δ_h² + Δ_{h−j}²) (each Δ_k² then carries a total weight <= d)::

    S_n − S_0 <= Σ_h [ (½ + d − β)Δ_h² + (½ − σ)|Δ_h| ].

The same holds at any instant inside a sample (partial displacement Δ' over a part
of length ℓ <= 1, viscous ∫ξ'² >= Δ'²/ℓ >= Δ'²). Every bracket is <= 0 when
|Δ| <= V, σ >= ½ and (β − ½ − d)V + (σ − ½) >= 0. As ½μξ'² <= S, a first-exit-time
argument gives the criterion implemented here:

    (β − ½ − d)V + (σ − ½) >= 0   and   σ >= ½,   V = sqrt(ξ'0² + ξ0²/μ)

imply S(t) <= S(0) for all t: the energy never grows, |ξ'| <= V and
|ξ| <= sqrt(2S(0)); the loop cannot diverge. At equality the partial sample keeps
|Δ'| <= V, so the boundary is included. d = 0, ξ0 = 0 is the paper's eq. 6 / 35
exactly. The quantization term (p − ½) is what needs σ >= ½; without quantization
(Δ → 0) the criterion is (β − ½ − d)V + σ >= 0 (eq. 7 generalised). Its linear part
β >= ½ + d is the journal extension (Diolaiti et al., IEEE T-RO 22(2), 2006).

Energy-equivalent speed. This module uses V = sqrt(ξ'0² + 2H_c(ξ0)/μ) with the
paper's pseudo-elastic energy H_c of eq. 18 (without quantization H_c = ½ξ²). As
H_c(ξ0) >= ½ξ0², this V is never smaller than the one of the proof, and the left
side of the criterion falls with V, so the verdict stays sound; it matches the
paper's storage function H_T = ½μV². With ξ0 = 0, V = |ξ'0|. ξ0 ≠ 0 needs μ.

What the verdicts mean (and do not mean)
----------------------------------------
``passive`` (regions a, e) is proven by the argument above. Regions b, c and d only
mean that the criterion gives *no guarantee*: it is a sufficient condition, and
failing it is no proof of instability (exact simulation decides that).

=======  ==============================================  ==================================
region   condition (boundaries as assigned here)          meaning
=======  ==============================================  ==================================
``a``    β >= ½ + d and σ >= ½                            passive at every speed (proven)
``b``    β >= ½ + d and σ <  ½                            not passive at rest: cannot stop
``c``    β <  ½ + d and σ <  ½                            no guarantee at any speed
``d``    β <  ½ + d, σ >= ½ and margin < 0                no guarantee at this speed
``e``    β <  ½ + d, σ >= ½ and margin >= 0               passive up to the critical speed (proven)
=======  ==============================================  ==================================

with margin = (β − ½ − d)V + (σ − ½). Boundary points follow the non-strict
inequalities: β = ½ + d belongs to a/b (the margin no longer falls with speed),
σ = ½ to a/d/e, margin = 0 to e. Hence ``passive`` is exactly ``region in ("a", "e")``.
The critical speed (eq. 12 generalised) is V_c = (σ − ½)/(½ + d − β): passive for
every V <= V_c. Without quantization the σ-threshold ½ is replaced by 0 and regions
b and c are empty. In region b (σ < ½) the paper (d = 0) observes stable sub-tick
limit cycles; that is an observation, not part of the guarantee.

Examples
--------
>>> r = passivity_criterion(beta=0.002, sigma=2.03, xi_dot=1.0)   # Delta device, slow
>>> r.region, r.passive
('e', True)
>>> round(r.critical_xi_dot, 3)                                     # eq. 12
3.072
>>> passivity_criterion(beta=0.002, sigma=2.03, xi_dot=5.0).region
'd'
>>> passivity_criterion(beta=0.8, sigma=0.8, xi_dot=5.0, delay=1).passive   # 0.8 < ½ + 1
False
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..checks import (
    DELAY_FIX,
    MAX_DELAY,
    _fmt,
    check_beta,
    check_bool,
    check_delay,
    check_mu,
    check_nonnegative,
    check_positive,
    check_real,
    check_real_array,
    check_sigma,
    check_type,
)
from ..core.energy import spring_energy_core
from ..errors import DFATypeError, DFAValueError
from ..model.device import Device
from ..results.jsonable import explain_nulls, to_jsonable
from ..results.status import CriterionStatus

__all__ = [
    "CriticalLine",
    "CriterionResult",
    "passivity_criterion",
    "device_criterion",
    "classify_region",
    "equivalent_speed",
    "spring_energy",
    "REGION_DESCRIPTIONS",
]

#: One-line meaning of each region of paper Fig. 3 (text before the first colon: short label).
#: Only a and e are guarantees; b, c, d say what is *not* guaranteed.
REGION_DESCRIPTIONS = {s.region: s.message for s in CriterionStatus}

_REGION_CODES = np.array(["a", "b", "c", "d", "e"])


def _anchor(quantized, delay):
    """(σ₀, β₀) of the critical line: σ₀ = ½ with quantization (0 without), β₀ = ½ + d (broadcast)."""
    return np.where(np.asarray(quantized, dtype=bool), 0.5, 0.0), 0.5 + np.asarray(delay, dtype=float)


def _margin(beta, sigma, speed, sigma0, beta0):
    """(β − β₀)V + (σ − σ₀): the left side of eq. 6 (eq. 10's line is margin = 0). The one evaluation every verdict uses."""
    return (beta - beta0) * speed + (sigma - sigma0)


def equivalent_speed(xi_dot: float, xi0: float = 0.0, mu: float | None = None, *, quantized: bool = True) -> float:
    """Energy-equivalent speed V = sqrt(ξ'0² + 2H_c(ξ0)/μ) in ticks per sample (eq. 18-19).

    ½μV² is the paper's total stored energy H_T(ξ0, ξ'0) (eq. 19), with
    H_c(ξ) = ½ξ² + ½(p − p²) (eq. 18; ½ξ² without quantization). V >= the
    sqrt(ξ'0² + ξ0²/μ) of the proof in the module docstring, so using it is sound.

    Parameters
    ----------
    xi_dot : float
        Initial speed ξ'0 (ticks per sample); its sign is ignored.
    xi0 : float, optional
        Initial position ξ0 in ticks (default 0).
    mu : float, optional
        Dimensionless mass μ = m/(K T²); required when ``xi0`` is not 0.
    quantized : bool, optional
        Use H_c of eq. 18 (default) or ½ξ0² (no encoder).

    Examples
    --------
    >>> equivalent_speed(2.0)
    2.0
    >>> equivalent_speed(0.0, xi0=1.0, mu=1.0)            # H_c(1) = ½
    1.0
    """
    v = abs(check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample"))
    x = check_real("xi0", xi0, "give the initial position in encoder ticks")
    quantized = check_bool("quantized", quantized, "pass True (eq. 18's H_c) or False (½ξ0², no encoder)")
    if x == 0.0:
        if mu is not None:
            check_mu(mu)
        return v
    if mu is None:
        raise DFAValueError(
            f"mu = None is invalid with xi0 = {x!r}: it must be given (μ = m/(K T²) > 0) because the spring energy "
            "H_c(ξ0) enters the speed only through 2H_c/μ; pass mu, or use device_criterion(..., position=...)"
        )
    m = check_mu(mu)
    return math.sqrt(v * v + 2.0 * float(spring_energy(x, quantized)) / m)


def spring_energy(xi, quantize: bool = True):
    """Pseudo-elastic energy H_c(ξ) = ½ξ² + ½(p − p²), p = ξ − ⌊ξ⌋, of the quantized spring (eq. 18), vectorised.

    The exact integral of the restoring staircase ⌊s⌋ + ½ from 0 to ξ; ½ξ² without quantization.

    Examples
    --------
    >>> float(spring_energy(1.0)), float(spring_energy(0.5)), float(spring_energy(0.5, quantize=False))
    (0.5, 0.25, 0.125)
    """
    q = check_bool("quantize", quantize, "pass True (the quantized spring) or False (½ξ²)")
    return spring_energy_core(np.asarray(xi, dtype=float), q)


@dataclass(frozen=True)
class CriticalLine:
    """The critical line of eq. 10 in the (β, σ) plane for one speed: σ = σ₀ + V(β₀ − β).

    A line through the corner (β₀, σ₀) with slope −V, where V is the (energy-equivalent) speed. For the
    paper's spring with a delay of d samples the corner is (½ + d, ½), or (½ + d, 0) without quantization
    (:meth:`of`); a wall with a damper or a filter moves it (:mod:`dfa.analysis.wall_criterion`). Points
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

    def regions(self, beta, sigma) -> np.ndarray:
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

    def margin(self, beta, sigma) -> float | np.ndarray:
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
class CriterionResult:
    """Outcome of the passivity criterion for one operating point, speed, delay and initial position.

    Attributes
    ----------
    beta, sigma : float
        Dimensionless damping and Coulomb friction (inputs).
    xi_dot : float
        Speed abs(ξ'0) in encoder ticks per sample (input, made non-negative).
    quantized : bool
        True for eq. 6 (with the encoder), False for eq. 7 (Δ → 0).
    region : str
        ``"a"`` … ``"e"`` as in the module docstring.
    passive : bool
        Whether the criterion holds (proven: the energy cannot grow); equals
        ``region in ("a", "e")``.
    margin : float
        (β − ½ − d)V + (σ − σ₀), σ₀ = ½ (or 0 without quantization).
    critical_xi_dot : float or None
        Eq. 12 generalised: the largest energy-equivalent speed V for which
        the criterion holds, (σ − σ₀)/(½ + d − β), when β < ½ + d and σ >= σ₀;
        None when it does not exist (regions a, b, c). With ξ0 = 0 it is the
        critical initial speed abs(ξ'0).
    critical_line : CriticalLine
        The line of eq. 10 for this speed and delay.
    equivalent_speed : float
        V = sqrt(ξ'0² + 2H_c(ξ0)/μ) (ticks per sample); V = abs(ξ'0) when ξ0 = 0.
    delay : int
        Computational delay d in samples.
    xi0 : float
        Initial position ξ0 in ticks.
    mu : float or None
        Dimensionless mass (needed only when ξ0 ≠ 0).
    status : CriterionStatus
        The region's meaning: its ``message`` is :data:`REGION_DESCRIPTIONS` of the region.
    device, stiffness, velocity, critical_velocity, position
        Set by :func:`device_criterion`: the physical inputs and the critical
        (energy-equivalent) speed in m/s (rad/s); otherwise None.
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
    delay: int
    xi0: float
    mu: float | None
    status: CriterionStatus
    device: Device | None = None
    stiffness: float | None = None
    velocity: float | None = None
    critical_velocity: float | None = None
    position: float | None = None

    def as_dict(self) -> dict[str, object]:
        """JSON-ready summary (the ``dfa check --json`` contract plus extras).

        Returns
        -------
        dict
            Strict-JSON data: region, verdict, margin, inputs, status and its message, and the
            physical values when set by :func:`device_criterion`.
        """
        out: dict[str, object] = {
            "region": self.region,
            "passive": self.passive,
            "margin": self.margin,
            "critical_xi_dot": self.critical_xi_dot,
            "beta": self.beta,
            "sigma": self.sigma,
            "xi_dot": self.xi_dot,
            "quantized": self.quantized,
            "status": self.status,
            "status_message": self.status.message,
            "delay": self.delay,
            "xi0": self.xi0,
            "mu": self.mu,
            "equivalent_speed": self.equivalent_speed,
        }
        if self.device is not None:
            out.update(
                device=self.device.name,
                stiffness=self.stiffness,
                velocity=self.velocity,
                critical_velocity=self.critical_velocity,
                position=self.position,
            )
        none = f"no critical speed: {self.status.message}"
        why = {"critical_xi_dot": none, "critical_velocity": none, "stiffness": "dimensionless input: no stiffness"}
        why.update(velocity="no speed in physical units given", position="no position in physical units given")
        return explain_nulls(to_jsonable(out), why)

    def __post_init__(self) -> None:
        for name in ("beta", "sigma", "xi_dot", "margin", "equivalent_speed"):
            if math.isnan(getattr(self, name)):
                raise DFAValueError(
                    f"{name} = nan is invalid: results hold numbers; build results with passivity_criterion"
                )
        status = CriterionStatus.coerce(self.status)
        object.__setattr__(self, "status", status)
        if self.region not in REGION_DESCRIPTIONS or status.region != self.region:
            raise DFAValueError(
                f"status = {status.value!r} is invalid for region = {self.region!r}: they must agree "
                "(CriterionStatus.of_region); build results with passivity_criterion"
            )
        if self.passive != (self.region in ("a", "e")):
            raise DFAValueError(
                f"passive = {self.passive!r} is invalid for region {self.region!r}: only regions a and e are passive; "
                "build results with passivity_criterion"
            )

    def plot(self, ax=None, **kwargs):
        """The (β, σ) plane with regions a-e and this point (:func:`dfa.figures.regions_plot`); returns the Axes.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.
        **kwargs
            Passed on to :func:`dfa.figures.regions_plot`.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        from ..figures import regions_plot

        return regions_plot(self, ax, **kwargs)


def classify_region(beta, sigma, xi_dot, quantized=True, delay=0) -> np.ndarray:
    """Vectorised region a-e of the criterion over arrays of β, σ, speed V and delay d (broadcast).

    ``xi_dot`` is the (energy-equivalent) speed V; every argument, including
    ``quantized`` and ``delay`` (whole samples >= 0), may be an array.

    Parameters
    ----------
    beta : array_like
        Dimensionless viscous damping β.
    sigma : array_like
        Dimensionless Coulomb friction σ.
    xi_dot : array_like
        The (energy-equivalent) speed V in ticks per sample; its sign is ignored.
    quantized : bool or array_like of bool, optional
        True (default) for eq. 6 (σ₀ = ½); False for eq. 7 (σ₀ = 0).
    delay : int or array_like of int, optional
        Computational delay d in samples (default 0).

    Returns
    -------
    numpy.ndarray of str
        Region letters with the broadcast shape of the inputs.

    Raises
    ------
    DFAValueError
        If a delay is not a whole number >= 0.

    See Also
    --------
    passivity_criterion : The verdict, margin and critical speed for one point.
    REGION_DESCRIPTIONS : What each region letter means.

    Examples
    --------
    >>> classify_region([0.6, 0.6, 0.2, 0.2, 0.2], [0.6, 0.2, 0.2, 0.7, 2.0], 1.0).tolist()
    ['a', 'b', 'c', 'd', 'e']
    >>> classify_region(0.6, 0.6, 1.0, delay=[0, 1]).tolist()          # β = 0.6 < ½ + 1
    ['a', 'd']
    """
    b = check_real_array("beta", beta, "β = b/(K T) is a real number or an array of them")
    s = check_real_array("sigma", sigma, "σ = c/(K Δ) is a real number or an array of them")
    v = np.abs(check_real_array("xi_dot", xi_dot, "give speeds in ticks per sample"))
    d = np.asarray(delay)
    if (
        d.dtype == bool
        or not np.issubdtype(d.dtype, np.number)
        or np.iscomplexobj(d)
        or not np.all(np.isfinite(d))
        or np.any(d < 0)
        or np.any(d > MAX_DELAY)
        or np.any(d != np.floor(d))
    ):
        raise DFAValueError(
            f"delay = {_fmt(delay)} is invalid: it must be a whole number from 0 to {MAX_DELAY}; {DELAY_FIX}"
        )
    q = np.asarray(quantized)
    if q.dtype != bool:
        raise DFATypeError(f"quantized = {_fmt(quantized)} is invalid: it must be True or False (or an array of them)")
    s0, b0 = _anchor(q, d)
    return region_of(b, s, v, s0, b0)


def region_of(b, s, v, s0, b0) -> np.ndarray:
    """Region letters a-e of (β, σ) at speed V for the critical line through (β₀, σ₀) (no validation, broadcast).

    The one rule behind :func:`classify_region` and the controller's criterion
    (:mod:`dfa.analysis.wall_criterion`): a (β >= β₀, σ >= σ₀), b (β >= β₀, σ < σ₀),
    c (β < β₀, σ < σ₀), d/e (β < β₀, σ >= σ₀, margin < 0 / >= 0).
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


def passivity_criterion(
    beta: float,
    sigma: float,
    xi_dot: float,
    *,
    quantized: bool = True,
    delay: int = 0,
    xi0: float = 0.0,
    mu: float | None = None,
) -> CriterionResult:
    """Evaluate the passivity criterion (eq. 6, or eq. 7 without quantization), with delay and initial position.

    Passive when (β − ½ − d)V + (σ − σ₀) >= 0 and σ >= σ₀ (module docstring), with
    V = sqrt(ξ'0² + 2H_c(ξ0)/μ) and σ₀ = ½ (0 without quantization). d = 0,
    ξ0 = 0 is the paper's eq. 6 unchanged.

    Parameters
    ----------
    beta : float
        Dimensionless viscous damping β = b/(K T) >= 0.
    sigma : float
        Dimensionless Coulomb friction σ = c/(K Δ) >= 0.
    xi_dot : float
        Largest speed of interest ξ'0 = ẋ0 T/Δ in encoder ticks per sample
        (e.g. the impact speed); its sign is ignored.
    quantized : bool, optional
        True (default) for eq. 6; False for the encoder-free eq. 7.
    delay : int, optional
        Computational delay d in whole samples (the force of sample h uses
        the reading ξ(h − d)); default 0.
    xi0 : float, optional
        Initial position ξ0 in ticks (default 0); the past readings equal ξ0.
    mu : float, optional
        Dimensionless mass μ = m/(K T²); required when ``xi0`` is not 0.

    Returns
    -------
    CriterionResult
        Region, verdict, margin, critical speed and line, with the inputs and a ``status``.

    Raises
    ------
    DFAValueError, DFATypeError
        If β, σ or μ is out of range or not a number, the speed or position is not a finite number,
        the delay is not a whole number >= 0, or ``xi0`` is not 0 without ``mu``.

    See Also
    --------
    device_criterion : The same criterion from physical values.
    classify_region : The region letter over arrays of (β, σ, V, d).
    CriticalLine : The line of eq. 10.
    """
    b = check_beta(beta)
    s = check_sigma(sigma)
    d = check_delay(delay)
    xd = abs(check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample"))
    x0 = check_real("xi0", xi0, "give the initial position in encoder ticks")
    m = None if mu is None else check_mu(mu)
    if not isinstance(quantized, (bool, np.bool_)):
        raise DFATypeError(
            f"quantized = {_fmt(quantized)} has type {type(quantized).__name__}: it must be True (eq. 6) or False (eq. 7)"
        )
    v = equivalent_speed(xd, x0, m, quantized=quantized)
    line = CriticalLine.of(v, quantized=quantized, delay=d)
    s0, b0 = line.sigma0, line.beta0
    margin = float(_margin(b, s, v, s0, b0))
    region = str(classify_region(b, s, v, quantized, d))
    critical = (s - s0) / (b0 - b) if (b < b0 and s >= s0) else None
    return CriterionResult(
        beta=b,
        sigma=s,
        xi_dot=xd,
        quantized=bool(quantized),
        region=region,
        passive=region in ("a", "e"),
        margin=margin,
        critical_xi_dot=critical,
        critical_line=line,
        equivalent_speed=v,
        delay=d,
        xi0=x0,
        mu=m,
        status=CriterionStatus.of_region(region),
    )


def device_criterion(
    device: Device, stiffness: float, velocity: float, *, delay: int = 0, position: float = 0.0, quantized: bool = True
) -> CriterionResult:
    """Passivity criterion for a physical device, stiffness, speed, delay and initial position (paper eq. 11).

    Parameters
    ----------
    device : Device
        The physical device.
    stiffness : float
        Virtual spring stiffness K in N/m (rotary: N·m/rad).
    velocity : float
        Largest speed of interest ẋ0 in m/s (rotary: rad/s); its sign is ignored.
    delay : int, optional
        Computational delay d in whole samples (default 0).
    position : float, optional
        Initial position x0 in m (rotary: rad), default 0; ξ0 = x0/Δ.
    quantized : bool, optional
        True (default) for eq. 6; False for eq. 7.

    Returns
    -------
    CriterionResult
        As :func:`passivity_criterion`, with ``device``, ``stiffness``, ``velocity``,
        ``critical_velocity`` (m/s, rotary rad/s) and ``position`` set.

    Raises
    ------
    DFAValueError, DFATypeError
        If the stiffness is not > 0, the speed or position is not a finite number, the delay is
        not a whole number >= 0, or (μ, β, σ) cannot be held in a float.

    See Also
    --------
    passivity_criterion : The criterion in dimensionless parameters.
    stiffness_limits : The largest passive stiffness and the classic bounds.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> r = device_criterion(dev, 14500.0, 0.1)
    >>> r.region, round(r.critical_velocity, 4)
    ('e', 0.2765)
    >>> device_criterion(dev, 14500.0, 0.1, delay=1).region
    'd'
    """
    check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
    x0 = check_real("position", position, "give the initial position in m (rotary: rad)")
    p = device.params(k)
    xd = device.xi_dot(velocity)
    r = passivity_criterion(p.beta, p.sigma, xd, quantized=quantized, delay=delay, xi0=x0 / device.resolution, mu=p.mu)
    return replace(
        r,
        device=device,
        stiffness=k,
        velocity=abs(float(velocity)),
        critical_velocity=None if r.critical_xi_dot is None else device.velocity(r.critical_xi_dot),
        position=x0,
    )
