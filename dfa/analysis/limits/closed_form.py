"""Stiffness limits for design (paper eq. 8, 9, 11 and the published bounds of spec section 8).

Solving the physical criterion (eq. 11, generalised to a computational delay of
d samples as in :mod:`dfa.analysis.criterion`)::

    (b − K T(½ + d))|ẋ0| + (c − K Δ/2) >= 0   and   c >= K Δ/2

for K gives the largest passive stiffness at impact speed ẋ0::

    K_max(ẋ0, d) = min( 2c/Δ, (b|ẋ0| + c)/(T(½ + d)|ẋ0| + Δ/2) )

which falls from 2c/Δ at rest (eq. 9) towards b/(T(½ + d)) at high speed (eq. 8;
2b/T for d = 0) when b/(T(½ + d)) < 2c/Δ. Every limit here is a *passivity* limit:
above it the criterion gives no guarantee, which is not a proof of instability.
Published bounds for comparison:

* Colgate & Schenkel (1997): K < 2b/T (no Coulomb friction, no encoder); with a
  delay of d samples b/(T(½ + d)) (Diolaiti et al. 2006).
* Abbott & Okamura (2005): K < min(2b/T, 2c/Δ), the ξ'0 → ∞ and ξ'0 → 0 ends of
  eq. 11 (with a delay: min(b/(T(½ + d)), 2c/Δ)).
* Gil, Avello, Rubio & Flórez (2004): for the linear sampled spring (no encoder,
  no Coulomb friction), K_crit = (b/T) f(γ) with
  f(γ) = γ(1 − δ)/(1 − δ − γδ), γ = bT/m, δ = e^{−γ} — one Jury condition of
  the linear sampled spring. :func:`k_gil` is the exact linear bound, all Jury
  conditions and an optional delay (:mod:`dfa.analysis.linear`); it equals Gil's form for
  γ < 3.72 without delay.

These bounds stay closed-form helpers of numbers (a :class:`~dfa.model.device.Device`, a speed, a stiffness K and
a whole delay d), not analyses of a :class:`~dfa.model.loop.Loop`: they are formulas in K (solved for it, or
vectorised over K and ẋ0) that the searches over K, the charts and the design answer evaluate at many K for one
device, and the only wall element they cover is the delay, a plain integer. A Loop would hold one K (which these
functions solve for or sweep) and elements they refuse (damper, filter, lag); a caller with a loop passes
``loop.device`` and ``loop.wall_params.delay`` (``Loop(device, wall)``), as :func:`dfa.analysis.design.design_analysis`
does. The analyses of a loop that search over K (:func:`~dfa.analysis.limits.kmax.design_answer`,
:func:`~dfa.analysis.limits.speed_chart.stiffness_speed_chart`, :func:`~dfa.analysis.limits.zwidth.z_width`)
take the Loop (``Loop(device)``: the spring at no given K) and call these with its device and delay.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> dev = get_device("Impulse Engine").device
>>> lim = stiffness_limits(dev, velocity=0.05)
>>> round(lim.k_max, 2), round(lim.k_colgate, 2), round(lim.k_abbott_okamura, 2)
(120.77, 20.0, 20.0)
>>> round(gil_beta_critical(100.0), 5)                       # spec section 8
0.49958
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ...checks import check_delay, check_positive, check_real_array, check_speed, check_type
from ...errors import DFAValueError
from ...grids import geometric_grid
from ...model.device import Device
from ...model.loop import Loop
from ...model.wall import Wall
from ...plausibility import warn_if_from_outside
from ...results.limits import StiffnessLimits as StiffnessLimits
from ...results.limits import StiffnessResponse as StiffnessResponse
from ...results.status import StiffnessStatus, VelocityStatus
from ..criterion import device_criterion
from ..linear import critical_beta, critical_stiffness

__all__ = [
    "StiffnessLimits",
    "stiffness_limits",
    "k_max_criterion",
    "k_colgate",
    "k_static",
    "k_abbott_okamura",
    "k_gil",
    "gil_factor",
    "gil_beta_critical",
    "max_passive_velocity",
    "StiffnessResponse",
    "StiffnessCurve",
    "HAND_SPEED",
    "stiffness_response",
]

#: Top of the speeds a hand brings to a wall (m/s for a linear device, rad/s for a rotary one): the default end of
#: the speed axes (:func:`stiffness_response`, :func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart`).
HAND_SPEED = {"linear": 2.0, "rotary": 10.0}


def _check_device(device: object) -> Device:
    return check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")


def k_static(device: Device) -> float:
    """Static limit 2c/Δ (paper eq. 9), N/m: above it the criterion gives no passivity guarantee even at rest.

    The one place every stiffness result takes it from.
    """
    dev = _check_device(device)
    return 2.0 * dev.coulomb / dev.resolution


def k_max_criterion(device: Device, velocity: ArrayLike, delay: int = 0) -> Any:
    """Largest stiffness passing the criterion at impact speed ``velocity`` and delay d (eq. 11 generalised), N/m.

    K_max = min(2c/Δ, (b·abs(ẋ0) + c)/(T(½ + d)·abs(ẋ0) + Δ/2)). Vectorised over
    ``velocity`` (m/s or rad/s; sign ignored); ``delay`` in whole samples.

    Parameters
    ----------
    device : Device
        The physical device.
    velocity : float or array_like
        Impact speed ẋ0 in m/s (rotary: rad/s); its sign is ignored.
    delay : int, optional
        Computational delay d in samples (default 0).

    Returns
    -------
    float or numpy.ndarray
        K_max in N/m (rotary: N·m/rad), a float for a scalar ``velocity``.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, a speed is not finite or the delay is not a whole number >= 0.

    See Also
    --------
    max_passive_velocity : The inverse: the largest passive speed of a stiffness.
    stiffness_limits : K_max with the published bounds.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> k = k_max_criterion(dev, [0.0, 1.0, 1e6])
    >>> bool(np.isclose(k[0], 2 * dev.coulomb / dev.resolution))
    True
    >>> bool(np.isclose(k[-1], 2 * dev.damping / dev.period, rtol=1e-3))
    True
    """
    dev = _check_device(device)
    v = np.abs(check_real_array("velocity", velocity, "give speeds in m/s (rotary: rad/s)"))
    d = check_delay(delay)
    if v.size:
        warn_if_from_outside("velocity", float(np.max(v)), rotary=dev.rotary)  # the user's, not a search's
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        num = dev.damping * v + dev.coulomb
        den = dev.period * (0.5 + d) * v + 0.5 * dev.resolution
        k_dyn = num / den
        big = ~(np.isfinite(num) & np.isfinite(den))  # b·ẋ0 or T·ẋ0 overflows (ẋ0 = 1e308): divide through by ẋ0
        if np.any(big):
            k_dyn = np.where(
                big, (dev.damping + dev.coulomb / v) / (dev.period * (0.5 + d) + 0.5 * dev.resolution / v), k_dyn
            )
    # rounded down by 1e-12 (relative) so that device_criterion accepts K_max itself: the two evaluate
    # the same inequality in physical and dimensionless form, and margin = 0 must stay on the passive side
    out = np.minimum(k_static(dev), k_dyn) * (1.0 - 1e-12)
    if not np.all(np.isfinite(out)):
        raise DFAValueError(
            f"coulomb = {dev.coulomb:g} is invalid with resolution = {dev.resolution:g}: K_max <= 2c/Δ overflows a "
            f"float; give the Coulomb friction in {dev.units['force']} and the resolution in {dev.units['position']}"
        )
    return float(out) if out.ndim == 0 else out


def k_colgate(device: Device, delay: int = 0) -> float:
    """Colgate-Schenkel bound 2b/T (paper eq. 8), N/m; b/(T(½ + d)) with a delay of d samples.

    Parameters
    ----------
    device : Device
        The physical device.
    delay : int, optional
        Computational delay d in samples (default 0).

    Returns
    -------
    float
        The bound in N/m (rotary: N·m/rad).

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device` or the delay is not a whole number >= 0.

    See Also
    --------
    k_abbott_okamura : This bound capped by the static limit 2c/Δ.
    k_gil : The exact bound of the linear sampled spring.
    """
    dev = _check_device(device)
    return dev.damping / (dev.period * (0.5 + check_delay(delay)))


def k_abbott_okamura(device: Device, delay: int = 0) -> float:
    """Abbott-Okamura bound min(2b/T, 2c/Δ), N/m; min(b/(T(½ + d)), 2c/Δ) with a delay of d samples.

    Parameters
    ----------
    device : Device
        The physical device.
    delay : int, optional
        Computational delay d in samples (default 0).

    Returns
    -------
    float
        The bound in N/m (rotary: N·m/rad).

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device` or the delay is not a whole number >= 0.

    See Also
    --------
    k_colgate : The damping bound 2b/T alone.
    k_max_criterion : The speed-dependent bound of the criterion.
    """
    dev = _check_device(device)
    return min(k_colgate(dev, delay), k_static(dev))


def _bounds(dev: Device, delay: int) -> dict[str, float]:
    """The speed-independent limits of :class:`StiffnessLimits` (which :class:`StiffnessResponse` reads)."""
    return dict(
        k_static=k_static(dev),
        k_colgate=k_colgate(dev, delay),
        k_abbott_okamura=k_abbott_okamura(dev, delay),
        k_gil=k_gil(dev, delay=delay),
    )


def gil_factor(gamma: ArrayLike) -> Any:
    """f(γ) = γ(1 − e^{−γ}) / (1 − (1 + γ)e^{−γ}) of Gil et al. (2004), vectorised.

    The closed form of one Jury condition only (the pair of roots crossing the
    unit circle at z = e^{±jθ}, no delay): (b/T) f(bT/m) is the stability bound
    for bT/m < 3.7208; beyond it a root leaves through z = −1 first and the
    bound is smaller (:func:`k_gil`, :mod:`dfa.analysis.linear`). Computed without
    cancellation for small γ (f = φ₁(−γ)/φ₂(−γ), :mod:`dfa.core.exprel`); f(0) = 2, so
    (b/T) f(γ) → 2b/T as b T/m → 0.

    Examples
    --------
    >>> float(gil_factor(0.0)), round(float(gil_factor(1e-9)), 9)
    (2.0, 2.0)
    """
    g = np.asarray(gamma, dtype=float)
    if np.any(g < 0) or not np.all(np.isfinite(g)):
        raise DFAValueError(f"gamma = {gamma!r} is invalid: it must be finite and >= 0 (γ = bT/m)")
    from ...core.exprel import phi1_array, phi2_array  # compiled; loaded on first use

    small = g < 0.5
    gs = -np.where(small, g, 0.0)
    # f = φ₁(−γ)/φ₂(−γ): γ(1 − e^{−γ}) = γ² e^{−γ} φ₁(−γ) and 1 − (1 + γ)e^{−γ} = γ² e^{−γ} φ₂(−γ) (dfa.core.exprel)
    f_small = phi1_array(gs) / phi2_array(gs)
    with np.errstate(divide="ignore", invalid="ignore"):
        gl = np.where(small, 1.0, g)
        one_minus_delta = -np.expm1(-gl)
        f_large = gl * one_minus_delta / (one_minus_delta - gl * np.exp(-gl))
    out = np.where(small, f_small, f_large)
    return float(out) if out.ndim == 0 else out


def k_gil(device: Device, *, delay: int = 0) -> float:
    """Exact linear bound of the sampled spring, all Jury conditions (Gil et al. 2004's closed form is one of them), N/m.

    The smallest K at which the linear loop m ẍ + b ẋ = −K x(h − d) (ZOH, no
    encoder, no Coulomb friction) loses stability (spec section 8;
    :func:`dfa.analysis.linear.critical_stiffness`). Without delay it equals Gil et al.'s
    (b/T) f(bT/m) (:func:`gil_factor`) for bT/m < 3.7208 and is smaller beyond
    (a root leaves through z = −1). Zero when b = 0: the undamped sampled spring
    is unstable for every K > 0.

    Parameters
    ----------
    device : Device
        The physical device (its Coulomb friction and encoder are ignored).
    delay : int, optional
        Computational delay d in samples (the force of sample h uses x(h − d)).

    Returns
    -------
    float
        The bound in N/m (rotary: N·m/rad).

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device` or the delay is not a whole number >= 0.

    See Also
    --------
    gil_beta_critical : The same bound in dimensionless form.
    k_colgate : The bound 2b/T it tends to for a large mass.

    Examples
    --------
    >>> from dfa.model.device import Device
    >>> dev = Device(mass=0.01, damping=5.0, coulomb=0.0, resolution=1e-5, period=0.01)
    >>> round(k_gil(dev), 1), round(5.0 / 0.01 * float(gil_factor(5.0)), 1)   # z = −1 binds
    (1651.9, 2587.8)
    """
    dev = _check_device(device)
    return float(critical_stiffness(dev.mass, dev.damping, dev.period, wall=Wall.of(1.0, delay=check_delay(delay))))


def gil_beta_critical(mu: float, *, delay: int = 0) -> float:
    """Dimensionless form of :func:`k_gil`: the β below which the linear loop is unstable, all Jury conditions.

    The linear sampled spring μξ'' + βξ' = −ξ(h − d) (no encoder, no Coulomb
    friction) is stable iff β > β_crit(μ, d) (:func:`dfa.analysis.linear.critical_beta`).
    Without delay this is Gil et al.'s β f(β/μ) = 1 while β/μ < 3.7208
    (spec section 8: μ = 1: 0.4617, μ = 5: 0.4918, μ = 100: 0.49958);
    β_crit → ½ + d as μ → ∞ (Diolaiti et al. 2006).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(K T²) > 0.
    delay : int, optional
        Computational delay d in samples.

    Returns
    -------
    float
        The critical dimensionless damping β_crit.

    Raises
    ------
    DFAValueError, DFATypeError
        If μ is not a finite number > 0 or the delay is not a whole number >= 0.

    See Also
    --------
    k_gil : The same bound as a stiffness.
    """
    return critical_beta(mu, delay)


def max_passive_velocity(device: Device, stiffness: float, delay: int = 0) -> float | None:
    """Largest impact speed for which stiffness K passes the criterion with delay d (eq. 11, 12), m/s.

    Parameters
    ----------
    device : Device
        The physical device.
    stiffness : float
        Virtual spring stiffness K in N/m (rotary: N·m/rad), > 0.
    delay : int, optional
        Computational delay d in samples (default 0).

    Returns
    -------
    float or None
        ``math.inf`` when K T(½ + d) <= b and K <= 2c/Δ (passive at every speed),
        None when K > 2c/Δ (no passivity guarantee even at rest), otherwise
        (c − KΔ/2)/(KT(½ + d) − b) in m/s (rotary: rad/s).

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, the stiffness is not > 0 or the delay is not a whole
        number >= 0.

    See Also
    --------
    k_max_criterion : The inverse: the largest passive stiffness at a speed.
    device_criterion : The full verdict at one speed.
    """
    dev = _check_device(device)
    k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
    # one implementation: the criterion's own critical speed (eq. 12), so that this speed and the
    # verdict of device_criterion agree to rounding even where K T(½ + d) − b cancels
    r = device_criterion(Loop(dev, Wall.of(k, delay=check_delay(delay))), 0.0)
    if r.region in ("b", "c"):
        return None
    if r.region == "a":
        return math.inf
    return r.critical_velocity


def stiffness_limits(
    device: Device, velocity: float, stiffness: float | None = None, delay: int = 0
) -> StiffnessLimits:
    """All stiffness limits of ``device`` at impact speed ``velocity`` and delay d.

    Parameters
    ----------
    device : Device
        The physical device.
    velocity : float
        Impact speed, the magnitude of ẋ0, in m/s (rotary: rad/s), >= 0 (a negative is refused).
    stiffness : float, optional
        A stiffness K in N/m (rotary: N·m/rad) to assess: its largest passive speed is reported.
    delay : int, optional
        Computational delay d in whole samples (default 0).

    Returns
    -------
    StiffnessLimits
        K_max, the published bounds and, with ``stiffness``, its verdict and largest passive speed.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, the speed is not finite, the stiffness is not > 0 or
        the delay is not a whole number >= 0.

    See Also
    --------
    stiffness_response : K_max over a range of speeds.
    k_max_criterion : K_max alone, vectorised over speeds.
    """
    dev = _check_device(device)
    v = check_speed("velocity", velocity)
    d = check_delay(delay)
    mpv: float | None = None
    vstatus = VelocityStatus.NOT_REQUESTED
    status = StiffnessStatus.NOT_REQUESTED
    k = None
    if stiffness is not None:
        k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        mpv = max_passive_velocity(dev, k, d)
        vstatus = (
            VelocityStatus.NONE
            if mpv is None
            else (VelocityStatus.ALL_SPEEDS if math.isinf(mpv) else VelocityStatus.BOUNDED)
        )
        status = StiffnessStatus.OK if (mpv is not None and mpv >= v) else StiffnessStatus.TOO_STIFF
    return StiffnessLimits(
        device=dev,
        velocity=v,
        xi_dot=dev.xi_dot(v),
        k_max=float(k_max_criterion(dev, v, d)),
        **_bounds(dev, d),
        stiffness=k,
        max_passive_velocity=mpv,
        velocity_status=vstatus,
        status=status,
        delay=d,
    )


#: Deprecated alias of :class:`StiffnessResponse` (the name before the ``*_response`` → ``*Response`` scheme).
StiffnessCurve = StiffnessResponse


def stiffness_response(
    device: Device, velocity: ArrayLike | None = None, stiffness: float | None = None, delay: int = 0
) -> StiffnessResponse:
    """K_max against impact speed for a device (eq. 11, with delay d), for :func:`dfa.render.figures.stiffness_plot`.

    Parameters
    ----------
    device : Device
        The physical device.
    velocity : array_like, optional
        Speeds in m/s (rad/s); default: 200 points from three decades below the speed Δ/T (one tick per
        sample; lower still when Δ/T is fast) up to hand speeds, :data:`HAND_SPEED` (2 m/s; rotary 10 rad/s).
    stiffness : float, optional
        A chosen stiffness in N/m (rotary: N·m/rad) to assess and mark.
    delay : int, optional
        Computational delay d in whole samples (default 0).

    Returns
    -------
    StiffnessResponse
        K_max at each speed with the speed-independent bounds; ``.plot()`` draws it.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, a speed is not finite and > 0, the stiffness is not
        > 0 or the delay is not a whole number >= 0.

    See Also
    --------
    stiffness_limits : The limits at one speed.
    stiffness_speed_chart : K_max with the simulated and describing-function speeds.
    """
    dev = _check_device(device)
    d = check_delay(delay)
    if velocity is None:
        top = HAND_SPEED["rotary" if dev.rotary else "linear"]  # no haptic device sees impacts of 100 m/s
        velocity = geometric_grid(min(1e-3 * dev.resolution / dev.period, 1e-3 * top), top, 200)
    fix = f"give impact speeds in {dev.units['velocity']}"
    v = np.atleast_1d(check_real_array("velocity", velocity, fix)).ravel()
    if np.any(v < 0):
        check_speed("velocity", float(v[v < 0][0]), dev.units["velocity"])  # refused: a magnitude, never flipped
    if v.size == 0 or np.any(v <= 0):
        shown = "an empty array" if v.size == 0 else f"{float(v[v <= 0][0])!r}"
        raise DFAValueError(f"velocity = {shown} is invalid: it must hold finite speeds > 0; {fix}")
    k = (
        None
        if stiffness is None
        else check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
    )
    warn_if_from_outside("velocity", float(np.max(v)), rotary=dev.rotary)
    if k is not None:
        warn_if_from_outside("stiffness", k, rotary=dev.rotary)
    limits = stiffness_limits(dev, float(v[0]), k, d)
    return StiffnessResponse(dev, v, np.atleast_1d(k_max_criterion(dev, v, d)), limits)
