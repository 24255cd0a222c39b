"""Passivity criterion of Diolaiti et al. (ICRA 2005), eq. 6-12 and 35.

Per sample, the hold and the quantizer generate at most ½(Δξ)² + ½|Δξ| of
energy (eq. 24, 26) while viscous and Coulomb friction dissipate at least
β(Δξ)² + σ|Δξ| (eq. 30, 32). The device is passive for speeds up to |ξ'0| when
(eq. 6)::

    (β − ½)|ξ'0| + (σ − ½) >= 0   and   σ >= ½.

Without quantization (Δ → 0) the criterion becomes (β − ½)|ξ'0| + σ >= 0 (eq. 7).

Regions of the (β, σ) plane (paper Fig. 3), for a given |ξ'0|
--------------------------------------------------------------
=======  ===========================================  =========================
region   condition (boundaries as assigned here)       behaviour
=======  ===========================================  =========================
``a``    β >= ½ and σ >= ½                             passive at every speed
``b``    β >= ½ and σ <  ½                             stable sub-tick limit cycles
``c``    β <  ½ and σ <  ½                             globally unstable
``d``    β <  ½, σ >= ½ and margin < 0                 locally unstable (from this speed)
``e``    β <  ½, σ >= ½ and margin >= 0                locally stable (passive up to this speed)
=======  ===========================================  =========================

with margin = (β − ½)|ξ'0| + (σ − ½). Boundary points are assigned by the
non-strict inequalities of eq. 6: β = ½ belongs to a/b (the margin no longer
depends on speed), σ = ½ to a/d/e, and margin = 0 to e. Hence
``passive`` is exactly ``region in ("a", "e")``. Without quantization the
σ-threshold ½ is replaced by 0, so regions b and c are empty.

Examples
--------
>>> r = passivity_criterion(beta=0.002, sigma=2.03, xi_dot=1.0)   # Delta device, slow
>>> r.region, r.passive
('e', True)
>>> round(r.critical_xi_dot, 3)                                     # eq. 12
3.072
>>> passivity_criterion(beta=0.002, sigma=2.03, xi_dot=5.0).region
'd'
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .device import Device
from .errors import check_beta, check_nonnegative, check_positive, check_real, check_sigma

__all__ = [
    "CriticalLine",
    "CriterionResult",
    "passivity_criterion",
    "device_criterion",
    "classify_region",
    "REGION_DESCRIPTIONS",
]

#: One-line meaning of each region of paper Fig. 3.
REGION_DESCRIPTIONS = {
    "a": "passive: stable at every speed",
    "b": "stable limit cycles of less than one encoder tick",
    "c": "globally unstable",
    "d": "locally unstable: unstable from this speed",
    "e": "locally stable: passive up to the critical speed",
}

_REGION_CODES = np.array(["a", "b", "c", "d", "e"])


@dataclass(frozen=True)
class CriticalLine:
    """The critical line of eq. 10 in the (β, σ) plane for one speed |ξ'0|.

    σ = σ₀ + |ξ'0|(½ − β): a line through (½, σ₀) with slope −|ξ'0|, where
    σ₀ = ½ with quantization and 0 without. Points on or above it satisfy the
    first inequality of eq. 6.

    Examples
    --------
    >>> line = CriticalLine(xi_dot=2.0)
    >>> line.slope, line.sigma(0.0)
    (-2.0, 1.5)
    """

    xi_dot: float
    sigma0: float = 0.5

    def __post_init__(self) -> None:
        object.__setattr__(self, "xi_dot", abs(check_real("xi_dot", self.xi_dot)))
        object.__setattr__(self, "sigma0", check_nonnegative("sigma0", self.sigma0))

    @property
    def slope(self) -> float:
        """dσ/dβ of the line, −|ξ'0|."""
        return -self.xi_dot

    def sigma(self, beta: float | np.ndarray) -> float | np.ndarray:
        """σ on the line at ``beta`` (vectorised)."""
        out = self.sigma0 + self.xi_dot * (0.5 - np.asarray(beta, dtype=float))
        return float(out) if out.ndim == 0 else out


@dataclass(frozen=True)
class CriterionResult:
    """Outcome of the passivity criterion for one operating point and speed.

    Attributes
    ----------
    beta, sigma : float
        Dimensionless damping and Coulomb friction (inputs).
    xi_dot : float
        Speed |ξ'0| in encoder ticks per sample (input, made non-negative).
    quantized : bool
        True for eq. 6 (with the encoder), False for eq. 7 (Δ → 0).
    region : str
        ``"a"`` … ``"e"`` as in the module docstring.
    passive : bool
        Whether eq. 6 (or 7) holds; equals ``region in ("a", "e")``.
    margin : float
        (β − ½)|ξ'0| + (σ − σ₀), σ₀ = ½ (or 0 without quantization).
    critical_xi_dot : float or None
        Eq. 12: the speed above which the criterion fails, (σ − σ₀)/(½ − β),
        when β < ½ and σ >= σ₀; None when it does not exist (regions a, b, c).
    critical_line : CriticalLine
        The line of eq. 10 for this speed.
    status : str
        Plain-language meaning of the region.
    device, stiffness, velocity, critical_velocity
        Set by :func:`device_criterion`: the physical inputs and the critical
        speed in m/s (rad/s); otherwise None.
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
    status: str
    device: Device | None = None
    stiffness: float | None = None
    velocity: float | None = None
    critical_velocity: float | None = None

    def as_dict(self) -> dict[str, object]:
        """JSON-ready summary (the ``dfa check --json`` contract plus extras)."""
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
        }
        if self.device is not None:
            out.update(
                device=self.device.name,
                stiffness=self.stiffness,
                velocity=self.velocity,
                critical_velocity=self.critical_velocity,
            )
        return out


def classify_region(beta, sigma, xi_dot, quantized: bool = True) -> np.ndarray:
    """Vectorised region a-e of eq. 6 over arrays of β, σ and |ξ'0| (broadcast).

    Returns
    -------
    numpy.ndarray of str
        Region letters with the broadcast shape of the inputs.

    Examples
    --------
    >>> classify_region([0.6, 0.6, 0.2, 0.2, 0.2], [0.6, 0.2, 0.2, 0.7, 2.0], 1.0).tolist()
    ['a', 'b', 'c', 'd', 'e']
    """
    b = np.asarray(beta, dtype=float)
    s = np.asarray(sigma, dtype=float)
    v = np.abs(np.asarray(xi_dot, dtype=float))
    s0 = 0.5 if quantized else 0.0
    margin = (b - 0.5) * v + (s - s0)
    high_beta = b >= 0.5
    high_sigma = s >= s0
    idx = np.where(
        high_beta,
        np.where(high_sigma, 0, 1),
        np.where(high_sigma, np.where(margin >= 0.0, 4, 3), 2),
    )
    return _REGION_CODES[idx]


def passivity_criterion(beta: float, sigma: float, xi_dot: float, *, quantized: bool = True) -> CriterionResult:
    """Evaluate the passivity criterion (paper eq. 6, or eq. 7 without quantization).

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

    Returns
    -------
    CriterionResult
    """
    b = check_beta(beta)
    s = check_sigma(sigma)
    v = abs(check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample"))
    s0 = 0.5 if quantized else 0.0
    margin = (b - 0.5) * v + (s - s0)
    region = str(classify_region(b, s, v, quantized))
    critical = (s - s0) / (0.5 - b) if (b < 0.5 and s >= s0) else None
    return CriterionResult(
        beta=b,
        sigma=s,
        xi_dot=v,
        quantized=bool(quantized),
        region=region,
        passive=region in ("a", "e"),
        margin=margin,
        critical_xi_dot=critical,
        critical_line=CriticalLine(v, s0),
        status=REGION_DESCRIPTIONS[region],
    )


def device_criterion(device: Device, stiffness: float, velocity: float, *, quantized: bool = True) -> CriterionResult:
    """Passivity criterion for a physical device, stiffness and speed (paper eq. 11).

    Parameters
    ----------
    device : Device
        The physical device.
    stiffness : float
        Virtual spring stiffness K in N/m (rotary: N·m/rad).
    velocity : float
        Largest speed of interest ẋ0 in m/s (rotary: rad/s); its sign is ignored.

    Examples
    --------
    >>> from dfa.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> r = device_criterion(dev, 14500.0, 0.1)
    >>> r.region, round(r.critical_velocity, 4)
    ('e', 0.2765)
    """
    k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
    p = device.params(k)
    xd = device.xi_dot(velocity)
    r = passivity_criterion(p.beta, p.sigma, xd, quantized=quantized)
    return replace(
        r,
        device=device,
        stiffness=k,
        velocity=abs(float(velocity)),
        critical_velocity=None if r.critical_xi_dot is None else device.velocity(r.critical_xi_dot),
    )
