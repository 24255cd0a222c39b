"""The harmonic balance with a virtual-wall controller (issue 15): inputs, and the linear loop's stability.

With a :class:`~dfa.controller.ControllerParams` the quantizer's describing function D(M) multiplies the
controller H(z) = z^{−d}·C(z), C(z) = 1 + β_B(1 − z^{−1})F(z) (F the ZOH-exact velocity filter, 1 without one),
and the amplifier lag 1/(α s + 1) sits between the hold and the device (:func:`dfa.loop.loop_response`).
A controller that is a pure spring (:attr:`~dfa.controller.ControllerParams.is_spring`) is the paper's loop
with its delay: the solver then runs the spring-only code, bit for bit.
"""

from __future__ import annotations

import numpy as np

from ..checks import check_delay, check_type
from ..controller import ControllerParams
from ..errors import DFAValueError


def resolve_controller(controller: object, delay: int) -> tuple[ControllerParams | None, int]:
    """(controller for the solver, or None for the pure spring; effective delay) from the user's inputs.

    The delay is the controller's; ``delay`` may be left at 0 or must equal it.
    """
    d = check_delay(delay)
    if controller is None:
        return None, d
    ctl = check_type(
        "controller",
        controller,
        ControllerParams,
        "give dimensionless groups, e.g. dfa.Controller(K, B, ...).params(period), or None for the spring",
    )
    if d not in (0, ctl.delay):
        raise DFAValueError(
            f"delay = {d} is invalid with controller.delay = {ctl.delay}: the controller carries the delay; "
            "leave delay at 0 or give the same value"
        )
    return (None if ctl.is_spring else ctl), ctl.delay


def controller_polynomials(ctl: ControllerParams) -> tuple[np.ndarray, np.ndarray]:
    """(numerator, denominator) of C(z) in powers of z, highest first (no delay)."""
    b = ctl.damping
    if ctl.cutoff is None:  # 1 + β_B(1 − z^{−1}) = ((1 + β_B)z − β_B)/z
        return np.array([1.0 + b, -b]), np.array([1.0, 0.0])
    a = ctl.filter_pole  # 1 + β_B (z − 1)(1 − a)/(z(z − a))
    num = np.polyadd(np.array([1.0, -a, 0.0]), b * (1.0 - a) * np.array([1.0, -1.0]))
    return num, np.array([1.0, -a, 0.0])


def plant_polynomials(mu: float, beta: float, lag: float) -> tuple[np.ndarray, np.ndarray]:
    """(numerator, denominator) of the ZOH-sampled (amplifier lag +) device in powers of z, highest first."""
    if lag == 0.0:
        from ..linear import _zoh_coefficients

        c1, c0, p = (float(x) for x in _zoh_coefficients(beta / mu))
        return np.array([c1, c0]), mu * np.polymul([1.0, -1.0], [1.0, -p])
    from .._zohlag import zoh_lag_coefficients

    gf, gv, gx, fvf, fxf, fxv, q, p = zoh_lag_coefficients(np.array([beta / mu]), mu, lag)[0]
    zq, zp = np.array([1.0, -q]), np.array([1.0, -p])
    num = gx * np.polymul(zq, zp)
    num = np.polyadd(num, fxf * gf * zp)
    num = np.polyadd(num, fxv * np.polyadd(gv * zq, [fvf * gf]))
    return num, np.polymul(np.polymul([1.0, -1.0], zp), zq)


def closed_loop_polynomial(mu: float, beta: float, ctl: ControllerParams) -> np.ndarray:
    """Characteristic polynomial z^d·D_C·D_P + N_C·N_P of the linear loop (no encoder, no Coulomb friction)."""
    nc, dc = controller_polynomials(ctl)
    npl, dp = plant_polynomials(mu, beta, ctl.lag)
    lhs = np.polymul(np.polymul(dc, dp), np.concatenate([[1.0], np.zeros(ctl.delay)]))
    return np.polyadd(lhs, np.polymul(nc, npl))


def linear_stable_with_controller(mu: float, beta: float, ctl: ControllerParams) -> bool:
    """Whether the linear loop with the controller is asymptotically stable (every root inside |z| = 1)."""
    roots = np.roots(closed_loop_polynomial(mu, beta, ctl))
    return bool(np.max(np.abs(roots)) < 1.0)
