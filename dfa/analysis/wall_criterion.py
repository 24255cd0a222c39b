"""Passivity criterion (paper eq. 6) for a wall with a virtual damper, velocity filter and delay (issue 15 item 2).

The energy argument of the paper (eq. 20-35) and of :mod:`dfa.analysis.criterion` redone
for the controller of :mod:`dfa.model.wall` without amplifier lag (α = 0).

The loop (dimensionless, time in samples, ξ = x/Δ, φ = F/(KΔ))
-------------------------------------------------------------
Reading n_h = ⌊ξ_h⌋ (ξ_h itself without the encoder), velocity estimate
v_h = n_h − n_{h−1} (v_0 = 0), damper input y_h = v_h without filter, or the
exact ZOH low-pass y_h = a·y_{h−1} + (1 − a)·v_{h−1}, y_0 = 0, a = e^{−2πν_c};
force held over sample h (ZOH, no amplifier lag)::

    φ_h = −(n_{h−d} + ½) − β_B·y_{h−d}          (φ_h = φ_0 for h < d)

and the plant μξ'' + βξ' + σ sgn ξ' = φ (eq. 4, stick-slip included).

Step 1: the energy balance of one sample (exact)
    With S = ½μξ'² + ½ξ² (the storage H_T of eq. 19 minus ½(p − p²) ∈ [0, 1/8],
    eq. 18) and Δ_h = ξ_{h+1} − ξ_h, the work of the constant force is φ_hΔ_h
    and ½ξ² grows by ξ_hΔ_h + ½Δ_h², so

        S_{h+1} − S_h = ½Δ_h² + (φ_h + ξ_h)Δ_h − D_h,
        D_h = β∫ξ'² + σ∫|ξ'| >= βΔ_h² + σ|Δ_h|     (Cauchy-Schwarz; eq. 30, 32).

Step 2: the spring's part of φ_h + ξ_h (as in :mod:`dfa.analysis.criterion`)
    With p = ξ − ⌊ξ⌋ (eq. 17) and Δ_k = 0, p_k = p_0 for k < 0 (the start
    convention): ξ_h − n_{h−d} − ½ = Σ_{j=1..d} Δ_{h−j} + (p_{h−d} − ½).

Step 3: the damper's part
    v_j = Δ_{j−1} − (p_j − p_{j−1}) exactly (also v_0 = 0 with the convention),
    and y_m = Σ_{k>=1} c_k v_{m−k}, c_k = (1 − a)a^{k−1} (filter; Σc_k <= 1),
    or y_m = v_m (no filter). Hence −β_B y_{h−d} is a *linear* part
    −β_B Σ_k c_k Δ_{h−d−k−1} (a combination of earlier displacements) plus a
    *quantization* part β_B Q_h, Q_h = Σ_k c_k (p_{h−d−k} − p_{h−d−k−1}).
    By Abel summation the coefficients of the p's in Q_h have positive parts
    summing to 1 − a and negative parts summing to 1 − a; as 0 <= p < 1,
    |Q_h| < 1 − a (no filter: Q_h = p_{h−d} − p_{h−d−1}, |Q_h| < 1 = 1 − 0).

Step 4: summing (the quadratic part)
    Over h = 0 … n − 1 every cross product is bounded by
    |Δ_hΔ_m| <= ½(Δ_h² + Δ_m²). The spring pairs (h, h − j), j = 1 … d, give
    each Δ_k² a total weight <= d (:mod:`dfa.analysis.criterion`); the damper pairs, with
    weights β_B c_k that sum to <= β_B, give each Δ_k² a weight <= ½β_B as the
    later sample and <= ½β_B as the earlier one: <= β_B in all. So::

        S_n − S_0 <= Σ_h [ (β₀ − β)Δ_h² + (σ₀ − σ)|Δ_h| ],
        β₀ = ½ + d + β_B,      σ₀ = ½ + (1 − a)β_B     (a = 0 without filter).

    The quantization parts (p_{h−d} − ½) and β_B Q_h are what σ₀ collects;
    without the encoder they vanish and σ₀ = 0. The bound holds at any instant
    inside a sample too (partial displacement Δ' over a part ℓ <= 1 of the
    sample: the force is constant, ∫ξ'² >= Δ'²/ℓ >= Δ'²).

Step 5: the criterion (first exit)
    Every bracket is <= 0 when |Δ| <= V, σ >= σ₀ and (β − β₀)V + (σ − σ₀) >= 0.
    Let V = sqrt(ξ'0² + ξ0²/μ), so S_0 = ½μV², and t* the last time up to
    which S <= S_0. Up to t*, ½μξ'² <= S <= S_0 gives |ξ'| <= V, so every
    displacement over at most one sample is <= V; by continuity of ξ' this
    still holds a little beyond t* (the partial sample is shorter than one),
    hence S <= S_0 beyond t*: t* = ∞. Therefore::

        (β − β₀)V + (σ − σ₀) >= 0   and   σ >= σ₀

    imply S(t) <= S(0) for all t (no energy gain, |ξ'| <= V, |ξ| <= sqrt(2S_0):
    no divergence). V = sqrt(ξ'0² + 2H_c(ξ0)/μ) (eq. 18) is used, as in
    :func:`dfa.equivalent_speed`; it is never smaller, so the verdict stays sound.

Reductions (tested)
    β_B = 0: β₀ = ½ + d, σ₀ = ½: :func:`dfa.passivity_criterion` (eq. 6 for
    d = 0) exactly, with or without a filter. Without encoder and Coulomb
    friction, d = 0: β >= ½ + β_B, i.e. b >= KT/2 + B, the Colgate-Schenkel
    bound (spec section 8). Equivalently, the controller's criterion at (β, σ)
    is the spring's at (β − β_B, σ − (1 − a)β_B): the damper costs β_B of
    physical damping and (1 − a)β_B of Coulomb friction. Physical form
    (eq. 11): (b − B − KT(½ + d))|ẋ0| + (c − KΔ/2 − (1 − a)BΔ/T) >= 0 and
    c >= KΔ/2 + (1 − a)BΔ/T.

What is not proven (and refused)
    * Amplifier lag (α > 0): the force varies within the sample, step 1's
      work φΔ no longer holds, and no sound closed form is derived here;
      :func:`controller_criterion` refuses α > 0 and points to the simulated
      map (:func:`dfa.stability_map`).
      A possible route, not carried out: write the lagged force as the
      exponentially weighted average Σ_j ω_j(τ)·φ_{h−j} of the held commands
      (Σω_j = 1), keep the exact ½Δ² of the current sample, bound the cross
      terms ∫ω_jξ'·Δ_{h−i} by Cauchy-Schwarz with ∫ξ'² (dissipated as β∫ξ'²)
      and the quantization terms by ½∫|ξ'| (dissipated as σ∫|ξ'|): this gives
      a β₀(α) > ½ + d + β_B that would need its own proof and simulator check.
    * Tightness: the criterion is sufficient only. β >= ½ + β_B is necessary
      for passivity of the linear loop at d = 0 (Colgate-Schenkel), but the
      σ-threshold ½ + (1 − a)β_B and the weights d, β_B with a delay or a
      filter are bounds, not known to be sharp. Failing the criterion is no
      proof of instability. Probing below the thresholds by simulation finds
      storage growth for σ between ½ and σ₀ (about 1 point in 10³, e.g. the test
      ``test_eq6_controller_sigma0_needs_the_damper_term``): σ >= ½ alone is not
      enough with a quantized damper.

Examples
--------
>>> from dfa.model.wall import WallParams
>>> r = controller_criterion(1.2, 1.0, 2.0, WallParams.of(damping=0.3))
>>> r.beta0, r.sigma0, r.region, r.passive            # β₀ = ½ + 0.3, σ₀ = ½ + 0.3
(0.8, 0.8, 'a', True)
>>> controller_criterion(0.2, 2.03, 1.0, WallParams.of(damping=0.1)).region
'e'
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..checks import _fmt, check_beta, check_mu, check_positive, check_real, check_sigma, check_type
from ..errors import DFATypeError, DFAValueError
from ..model.device import Device
from ..model.wall import Wall, WallParams
from ..results.jsonable import to_jsonable
from ..results.status import ControllerCriterionStatus
from .criterion import _margin, equivalent_speed, region_of

__all__ = ["ControllerCriterionResult", "controller_criterion", "device_controller_criterion", "controller_anchor"]

_LAG_FIX = (
    "no sound closed-form passivity criterion is proven with amplifier lag (the force varies within a sample); "
    "set lag = 0 (amplifier_bandwidth=None), or use the simulated map dfa.stability_map instead"
)


def _check_controller(controller: object) -> WallParams:
    """A :class:`WallParams` without amplifier lag (the criterion's scope), or the package's error."""
    c = check_type("controller", controller, WallParams, "build one with dfa.model.wall.WallParams.of(...)")
    if c.lag != 0.0:
        raise DFAValueError(f"controller.lag = {_fmt(c.lag)} is invalid: it must be 0; {_LAG_FIX}")
    return c


def controller_anchor(controller: WallParams, quantized: bool = True) -> tuple[float, float]:
    """The corner (β₀, σ₀) of the critical line with the controller (module docstring, step 4).

    β₀ = ½ + d + β_B and σ₀ = ½ + (1 − a)β_B with the encoder (0 without), a the
    filter pole (0 without filter).

    Parameters
    ----------
    controller : WallParams
        Dimensionless controller without amplifier lag.
    quantized : bool, optional
        True (default) with the encoder; False for the encoder-free loop.

    Returns
    -------
    tuple of float
        (β₀, σ₀).

    Raises
    ------
    DFAValueError, DFATypeError
        If ``controller`` is not a WallParams or has amplifier lag.

    Examples
    --------
    >>> controller_anchor(WallParams.of(damping=1.0, delay=1))
    (2.5, 1.5)
    >>> controller_anchor(WallParams.of(damping=1.0), quantized=False)
    (1.5, 0.0)
    """
    c = _check_controller(controller)
    q = _check_quantized(quantized)
    return 0.5 + c.delay + c.damping, (0.5 + (1.0 - c.filter_pole) * c.damping) if q else 0.0


def _check_quantized(quantized: object) -> bool:
    if not isinstance(quantized, (bool, np.bool_)):
        raise DFATypeError(
            f"quantized = {_fmt(quantized)} has type {type(quantized).__name__}: it must be True (with the "
            "encoder) or False (without)"
        )
    return bool(quantized)


@dataclass(frozen=True)
class ControllerCriterionResult:
    """Outcome of :func:`controller_criterion` for one operating point, speed, controller and initial position.

    Attributes
    ----------
    beta, sigma : float
        Dimensionless damping β = b/(KT) and Coulomb friction σ = c/(KΔ) (inputs).
    xi_dot : float
        Speed abs(ξ'0) in ticks per sample (input).
    controller : WallParams
        The dimensionless controller (β_B, d, ν_c; α = 0).
    quantized : bool
        With (True) or without the encoder.
    beta0, sigma0 : float
        The corner of the critical line: ½ + d + β_B and ½ + (1 − a)β_B (0 without encoder).
    region : str
        ``"a"`` … ``"e"`` as in :mod:`dfa.analysis.criterion` with (β₀, σ₀) in place of (½ + d, ½).
    passive : bool
        Proven: the storage ½μξ'² + ½ξ² never exceeds its initial value; ``region in ("a", "e")``.
    margin : float
        (β − β₀)V + (σ − σ₀).
    critical_xi_dot : float or None
        Largest energy-equivalent speed that is passive, (σ − σ₀)/(β₀ − β), when β < β₀ and σ >= σ₀.
    equivalent_speed : float
        V = sqrt(ξ'0² + 2H_c(ξ0)/μ), ticks per sample.
    xi0 : float
        Initial position (ticks); the past readings equal it.
    mu : float or None
        Dimensionless mass (needed only when ξ0 ≠ 0).
    status : ControllerCriterionStatus
        The region's meaning in terms of β₀, σ₀ (:attr:`status_message` gives their values).
    device, stiffness, velocity, critical_velocity, position
        Set by :func:`device_controller_criterion` (SI units); otherwise None.
    """

    beta: float
    sigma: float
    xi_dot: float
    controller: WallParams
    quantized: bool
    beta0: float
    sigma0: float
    region: str
    passive: bool
    margin: float
    critical_xi_dot: float | None
    equivalent_speed: float
    xi0: float
    mu: float | None
    status: ControllerCriterionStatus
    device: Device | None = None
    stiffness: float | None = None
    velocity: float | None = None
    critical_velocity: float | None = None
    position: float | None = None

    def __post_init__(self) -> None:
        fix = "results hold the numbers controller_criterion computed; use controller_criterion"
        for name in ("beta", "sigma", "xi_dot", "margin", "equivalent_speed", "beta0", "sigma0", "xi0"):
            object.__setattr__(self, name, check_real(name, getattr(self, name), fix))
        check_type("controller", self.controller, WallParams, fix)
        for name in ("quantized", "passive"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                raise DFATypeError(f"{name} = {_fmt(getattr(self, name))} is invalid: it must be True or False; {fix}")
        status = ControllerCriterionStatus.coerce(self.status)
        object.__setattr__(self, "status", status)
        if (
            not isinstance(self.region, str)
            or status.region != self.region
            or self.passive != (self.region in ("a", "e"))
        ):
            raise DFAValueError(
                f"region = {self.region!r}, passive = {self.passive!r}, status = {status.value!r} are invalid: "
                "they must agree (only a and e are passive); use controller_criterion"
            )

    @property
    def status_message(self) -> str:
        """The status message with this case's thresholds β₀, σ₀ (and critical speed) filled in.

        Examples
        --------
        >>> controller_criterion(0.2, 2.03, 5.0, WallParams.of(damping=0.1)).status_message.split("; ")[-1]
        'here β₀ = 0.6, σ₀ = 0.6, critical speed 3.575 ticks/sample'
        """
        extra = f"here β₀ = {self.beta0:.6g}, σ₀ = {self.sigma0:.6g}"
        if self.critical_xi_dot is not None:
            extra += f", critical speed {self.critical_xi_dot:.6g} ticks/sample"
        return f"{self.status.message}; {extra}"

    def as_dict(self) -> dict[str, object]:
        """JSON-ready summary: verdict, margin, thresholds, inputs, controller, status and its message.

        Returns
        -------
        dict
            Strict-JSON data (physical values too when set by :func:`device_controller_criterion`).
        """
        out = {k: getattr(self, k) for k in self.__dataclass_fields__ if k not in ("device", "controller")}
        out.update(controller=self.controller.as_dict(), status_message=self.status_message)
        out["device"] = None if self.device is None else self.device.name
        return to_jsonable(out)


def controller_criterion(
    beta: float,
    sigma: float,
    xi_dot: float,
    controller: WallParams | None = None,
    *,
    quantized: bool = True,
    xi0: float = 0.0,
    mu: float | None = None,
) -> ControllerCriterionResult:
    """Passivity criterion with virtual damper, velocity filter and delay (module docstring; eq. 6 extended).

    Passive when (β − β₀)V + (σ − σ₀) >= 0 and σ >= σ₀, with β₀ = ½ + d + β_B,
    σ₀ = ½ + (1 − a)β_B (0 without encoder) and V = sqrt(ξ'0² + 2H_c(ξ0)/μ).
    For ``WallParams.of()`` (and any β_B = 0) this is :func:`dfa.passivity_criterion`.

    Parameters
    ----------
    beta : float
        Dimensionless viscous damping β = b/(K T) >= 0.
    sigma : float
        Dimensionless Coulomb friction σ = c/(K Δ) >= 0.
    xi_dot : float
        Largest speed of interest ξ'0 in ticks per sample (sign ignored).
    controller : WallParams, optional
        The dimensionless controller: damping β_B = B/(KT), delay d (samples),
        cutoff ν_c (cycles per sample); the amplifier lag must be 0. Default: the paper's spring.
    quantized : bool, optional
        With the encoder (default) or without (the linear loop).
    xi0 : float, optional
        Initial position in ticks (default 0); needs ``mu`` when not 0.
    mu : float, optional
        Dimensionless mass μ = m/(K T²).

    Returns
    -------
    ControllerCriterionResult
        Region, verdict, margin, thresholds (β₀, σ₀), critical speed, with the inputs and a ``status``.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad β, σ, μ, speed or position; a controller with amplifier lag (no sound
        closed form: use :func:`dfa.stability_map`); ``xi0`` without ``mu``.

    See Also
    --------
    passivity_criterion : The spring's criterion (β_B = 0), which this reduces to.
    device_controller_criterion : The same criterion from physical values.

    Examples
    --------
    >>> r = controller_criterion(0.4, 1.0, 1.0, WallParams.of(damping=0.2, cutoff=0.1))
    >>> round(r.sigma0, 4), round(r.critical_xi_dot, 4)   # σ₀ = ½ + (1 − e^{−0.2π})·0.2
    (0.5933, 1.3557)
    """
    c = WallParams.of() if controller is None else _check_controller(controller)
    b, s = check_beta(beta), check_sigma(sigma)
    q = _check_quantized(quantized)
    xd = abs(check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample"))
    x0 = check_real("xi0", xi0, "give the initial position in encoder ticks")
    m = None if mu is None else check_mu(mu)
    v = equivalent_speed(xd, x0, m, quantized=q)
    b0, s0 = controller_anchor(c, q)
    region = str(region_of(b, s, v, s0, b0))  # the spring's rule (dfa.analysis.criterion) with the controller's corner
    margin = float(_margin(b, s, v, s0, b0))
    return ControllerCriterionResult(
        beta=b,
        sigma=s,
        xi_dot=xd,
        controller=c,
        quantized=q,
        beta0=b0,
        sigma0=s0,
        region=region,
        passive=region in ("a", "e"),
        margin=margin,
        critical_xi_dot=(s - s0) / (b0 - b) if (b < b0 and s >= s0) else None,
        equivalent_speed=v,
        xi0=x0,
        mu=m,
        status=ControllerCriterionStatus.of_region(region),
    )


def device_controller_criterion(
    device: Device, controller: Wall, velocity: float, *, position: float = 0.0, quantized: bool = True
) -> ControllerCriterionResult:
    """The criterion for a physical device and controller at a speed (eq. 11 extended; SI units at the edge).

    Parameters
    ----------
    device : Device
        The physical device.
    controller : Wall
        Stiffness K, damping B, delay, filter cutoff (no amplifier bandwidth).
    velocity : float
        Largest speed of interest in m/s (rotary: rad/s); sign ignored.
    position : float, optional
        Initial position in m (rotary: rad), default 0.
    quantized : bool, optional
        With the encoder (default) or without.

    Returns
    -------
    ControllerCriterionResult
        With ``device``, ``stiffness``, ``velocity``, ``critical_velocity`` (m/s) and ``position`` set.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad inputs, a cutoff above Nyquist, or an amplifier bandwidth (refused: use dfa.stability_map).

    See Also
    --------
    controller_criterion : The criterion in dimensionless parameters.
    device_criterion : The spring's criterion from physical values.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> device_controller_criterion(dev, Wall.of(14500.0), 0.1).region      # = device_criterion
    'e'
    >>> device_controller_criterion(dev, Wall.of(14500.0, damping=5.0), 0.1).region     # B = 5 N·s/m
    'd'
    """
    check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    check_type("controller", controller, Wall, "build one with dfa.model.wall.Wall.of(K, ...)")
    x0 = check_real("position", position, "give the initial position in m (rotary: rad)")
    k = check_positive("stiffness", controller.stiffness)
    p = device.params(k)
    r = controller_criterion(
        p.beta,
        p.sigma,
        device.xi_dot(velocity),
        controller.params(device.period),
        quantized=quantized,
        xi0=x0 / device.resolution,
        mu=p.mu,
    )
    crit = None if r.critical_xi_dot is None else device.velocity(r.critical_xi_dot)
    return replace(r, device=device, stiffness=k, velocity=abs(float(velocity)), critical_velocity=crit, position=x0)
