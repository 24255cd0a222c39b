"""The virtual-wall controller: spring, damper, velocity filter, delay, amplifier lag.

A real haptic wall is rarely a bare spring. At sample h the controller reads the
quantized position q_h = Δ(⌊x(hT)/Δ⌋ + ½) (paper eq. 2), forms the
backward-difference velocity v_h = (q_h − q_{h−1})/T, optionally low-pass
filters it, and commands, d samples later (computational delay)::

    F_cmd,h = −K q_{h−d} − B y_{h−d},      y = filtered v (y = v without filter)

held by the zero-order hold. The velocity filter is the exact (step-invariant,
``control.c2d(..., method="zoh")``) discretisation of the first-order low-pass
ω_c/(s + ω_c), ω_c = 2π f_c::

    y_h = a y_{h−1} + (1 − a) v_{h−1},     a = e^{−2π f_c T}

(so the filter adds its own one-sample lag). The amplifier turns the held
command into force through a first-order lag of time constant
τ_a = 1/(2π f_bw)::

    τ_a dF_A/dt = F_cmd,h − F_A     on [hT, (h + 1)T)

(F_A = F_cmd without amplifier, the paper's model). ``Controller(K)`` is the
paper's pure spring (eq. 1-2) and every result for it is the spring-only
result.

Dimensionless form (beside paper Table 1, with τ = t/T, ξ = x/Δ, φ = F/(KΔ))::

    β_B = B/(K T)        virtual damping (the damper's analogue of β = b/(K T))
    ν_c = f_c T          filter cutoff in cycles per sample, 0 < ν_c < ½ (Nyquist)
    α   = τ_a/T          amplifier time constant in samples, >= 0
    d                    computational delay in whole samples

so that φ_cmd,h = −(⌊ξ_{h−d}⌋ + ½) − β_B ỹ_{h−d} with ỹ the (filtered)
difference ⌊ξ_h⌋ − ⌊ξ_{h−1}⌋ in ticks per sample, and α φ_A' = φ_cmd − φ_A.

Examples
--------
>>> c = Controller(stiffness=500.0, damping=0.5, delay=1, filter_cutoff=100.0)
>>> p = c.params(period=1e-3)
>>> round(p.damping, 6), p.delay, round(p.cutoff, 6), p.lag
(1.0, 1, 0.1, 0.0)
>>> round(p.filter_pole, 6)   # a = exp(-2π ν_c)
0.533488
>>> Controller(300.0).params(1e-3).is_spring
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import _fmt, check_delay, check_nonnegative, check_positive
from ..errors import DFAValueError

__all__ = ["Controller", "ControllerParams"]

_NYQUIST_FIX = "give a cutoff below the Nyquist frequency 1/(2T), or no filter (None)"


#: Smallest velocity-filter cutoff accepted, in cycles per sample (1 Hz at 1 kHz). Below it the filter pole
#: e^{−2πν_c} and the free mass's pole at z = 1 are too close to separate in double precision: a red-team check
#: found the exact linear bound calling a stable loop "never stable" at ν_c = 1e-6 (verified stable with 60-digit
#: roots); from 1e-3 to the Nyquist limit no such case was found.
MIN_CUTOFF = 1.0e-3


def _check_cutoff(name: str, value: object, nyquist: float, unit: str) -> float | None:
    """A filter cutoff: None (no filter) or MIN_CUTOFF·(2·nyquist) <= value < nyquist."""
    if value is None:
        return None
    out = check_positive(name, value, f"give the velocity-filter cutoff in {unit}, or None for no filter")
    floor = MIN_CUTOFF * 2.0 * nyquist  # 2·nyquist = samples per unit of the cutoff (1 or 1/T)
    per_sample = "" if unit == "cycles per sample" else f"{MIN_CUTOFF:g} cycles per sample; "
    if out < floor * (1 - 1e-12):  # the floor as printed (6 digits) is accepted despite rounding
        raise DFAValueError(
            f"{name} = {_fmt(out)} is invalid: it must be at least {floor:.6g} {unit} ({per_sample}below, the filter "
            "pole and the free mass's pole at z = 1 cannot be told apart in double precision and the linear analysis "
            f"is unreliable); give a cutoff of at least {floor:.6g} {unit}, "
            "or no filter"
        )
    if not out < nyquist:
        raise DFAValueError(
            f"{name} = {_fmt(out)} is invalid: it must be below the Nyquist frequency "
            f"{_fmt(nyquist)} {unit}; {_NYQUIST_FIX}"
        )
    return out


def _check_lag(lag: object) -> float:
    """α = 0 or α >= :data:`MIN_LAG`: the kernel's rate κ = 1/α stays finite (at 5e-324 it was inf, and NaN)."""
    a = check_nonnegative("lag", lag, "α = τ_a/T cannot be negative (0: none)")
    if 0.0 < a < MIN_LAG:
        raise DFAValueError(
            f"lag = {_fmt(a)} is invalid: it must be 0 or at least {_fmt(MIN_LAG)} samples (the kernel's rate "
            "1/α must stay finite); a lag this short is no lag: pass 0 (or no amplifier bandwidth)"
        )
    return a


#: Shortest amplifier lag α (samples) other than 0 (:class:`ControllerParams`): 1/α is then a finite float.
MIN_LAG = 1e-300


@dataclass(frozen=True)
class ControllerParams:
    """Dimensionless controller (the groups beside paper Table 1).

    Parameters
    ----------
    damping : float, optional
        Virtual damping β_B = B/(K T) >= 0 (default 0: no damper).
    delay : int, optional
        Computational delay d in whole samples, >= 0 (default 0).
    cutoff : float or None, optional
        Velocity-filter cutoff ν_c = f_c T in cycles per sample, 0 < ν_c < ½;
        None (default) for no filter.
    lag : float, optional
        Amplifier time constant α = τ_a/T in samples, >= 0 (default 0: no lag).

    Examples
    --------
    >>> ControllerParams(damping=0.2, cutoff=0.05).filter_pole > 0.7
    True
    """

    damping: float = 0.0
    delay: int = 0
    cutoff: float | None = None
    lag: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "damping", check_nonnegative("damping", self.damping, "β_B = B/(K T) cannot be negative")
        )
        object.__setattr__(self, "delay", check_delay(self.delay))
        object.__setattr__(self, "cutoff", _check_cutoff("cutoff", self.cutoff, 0.5, "cycles per sample"))
        object.__setattr__(self, "lag", _check_lag(self.lag))

    @property
    def filter_pole(self) -> float:
        """Pole a = e^{−2π ν_c} of the discretised velocity filter (0 without filter)."""
        return 0.0 if self.cutoff is None else math.exp(-2.0 * math.pi * self.cutoff)

    @property
    def amplifier_pole(self) -> float:
        """Decay e^{−1/α} of the amplifier's force error over one sample (0 without lag)."""
        return 0.0 if self.lag == 0.0 else math.exp(-1.0 / self.lag)

    @property
    def is_spring(self) -> bool:
        """True for the paper's spring (no damper, filter or amplifier lag; any delay)."""
        return self.damping == 0.0 and self.cutoff is None and self.lag == 0.0

    def as_dict(self) -> dict[str, object]:
        """The four groups as a JSON-able dictionary.

        Returns
        -------
        dict
            ``{"damping": β_B, "delay": d, "cutoff": ν_c or None, "lag": α}``.
        """
        return {"damping": self.damping, "delay": self.delay, "cutoff": self.cutoff, "lag": self.lag}


@dataclass(frozen=True)
class Controller:
    """A virtual wall controller in physical units (see the module docstring).

    Parameters
    ----------
    stiffness : float
        Virtual spring K in N/m (rotary: N·m/rad), > 0.
    damping : float, optional
        Virtual damper B in N·s/m (rotary: N·m·s/rad), >= 0 (default 0).
    delay : int, optional
        Computational delay d in whole samples, >= 0 (default 0).
    filter_cutoff : float or None, optional
        Cutoff f_c in Hz of the first-order low-pass on the velocity estimate,
        below the Nyquist frequency 1/(2T); None (default) for no filter.
    amplifier_bandwidth : float or None, optional
        Bandwidth f_bw in Hz of the current amplifier, modelled as a first-order
        lag τ_a = 1/(2π f_bw); None (default) for an ideal amplifier.

    Examples
    --------
    >>> Controller(1000.0, amplifier_bandwidth=1000.0).amplifier_time_constant
    0.00015915494309189535
    """

    stiffness: float
    damping: float = 0.0
    delay: int = 0
    filter_cutoff: float | None = None
    amplifier_bandwidth: float | None = None

    def __post_init__(self) -> None:
        object.__setattr__(
            self, "stiffness", check_positive("stiffness", self.stiffness, "give the virtual wall stiffness K in N/m")
        )
        object.__setattr__(
            self,
            "damping",
            check_nonnegative("damping", self.damping, "give the virtual damping B in N·s/m (0 for none)"),
        )
        object.__setattr__(self, "delay", check_delay(self.delay))
        if self.filter_cutoff is not None:
            object.__setattr__(
                self,
                "filter_cutoff",
                check_positive("filter_cutoff", self.filter_cutoff, "give the cutoff in Hz, or None for no filter"),
            )
        if self.amplifier_bandwidth is not None:
            object.__setattr__(
                self,
                "amplifier_bandwidth",
                check_positive(
                    "amplifier_bandwidth",
                    self.amplifier_bandwidth,
                    "give the amplifier bandwidth in Hz, or None for an ideal amplifier",
                ),
            )

    @property
    def amplifier_time_constant(self) -> float:
        """Amplifier time constant τ_a = 1/(2π f_bw) in s (0 for an ideal amplifier)."""
        return 0.0 if self.amplifier_bandwidth is None else 1.0 / (2.0 * math.pi * self.amplifier_bandwidth)

    def params(self, period: float) -> ControllerParams:
        """Dimensionless groups (β_B, d, ν_c, α) at sample period ``period``.

        Parameters
        ----------
        period : float
            Sample period T in s, > 0.

        Returns
        -------
        ControllerParams
            The groups β_B = B/(K T), d, ν_c = f_c T and α = τ_a/T.

        Raises
        ------
        DFAValueError
            If the filter cutoff is not below the Nyquist frequency 1/(2T).
        """
        t = check_positive("period", period, "give the sample period T in s (1 kHz: 0.001)")
        cutoff = _check_cutoff("filter_cutoff", self.filter_cutoff, 0.5 / t, "Hz")
        return ControllerParams(
            damping=self.damping / (self.stiffness * t),
            delay=self.delay,
            cutoff=None if cutoff is None else cutoff * t,
            lag=self.amplifier_time_constant / t,
        )

    def as_dict(self) -> dict[str, object]:
        """The controller's physical parameters as a JSON-able dictionary.

        Returns
        -------
        dict
            Stiffness, damping, delay, filter cutoff and amplifier bandwidth (SI units, None where absent).
        """
        return {
            "stiffness": self.stiffness,
            "damping": self.damping,
            "delay": self.delay,
            "filter_cutoff": self.filter_cutoff,
            "amplifier_bandwidth": self.amplifier_bandwidth,
        }
