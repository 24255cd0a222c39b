"""The harmonic balance with a virtual-wall controller (issue 15): inputs, and the linear loop's stability.

With a :class:`~dfa.model.wall.WallParams` the quantizer's describing function D(M) multiplies the
controller H(z) = z^{−d}·C(z), C(z) = 1 + β_B(1 − z^{−1})F(z) (F the ZOH-exact velocity filter, 1 without one),
and the amplifier lag 1/(α s + 1) sits between the hold and the device (:func:`dfa.analysis.loop.loop_response`).
A controller that is a pure spring (:attr:`~dfa.model.wall.WallParams.is_spring`) is the paper's loop
with its delay: the solver then runs the spring-only code, bit for bit.
"""

from __future__ import annotations

from ...checks import check_delay, check_type
from ...errors import DFAValueError
from ...model.wall import WallParams


def resolve_controller(controller: object, delay: int) -> tuple[WallParams | None, int]:
    """(controller for the solver, or None for the pure spring; effective delay) from the user's inputs.

    The delay is the controller's; ``delay`` may be left at 0 or must equal it.
    """
    d = check_delay(delay)
    if controller is None:
        return None, d
    ctl = check_type(
        "controller",
        controller,
        WallParams,
        "give dimensionless groups, e.g. dfa.Wall.of(K, B, ...).params(period), or None for the spring",
    )
    if d not in (0, ctl.delay):
        raise DFAValueError(
            f"delay = {d} is invalid with controller.delay = {ctl.delay}: the controller carries the delay; "
            "leave delay at 0 or give the same value"
        )
    return (None if ctl.is_spring else ctl), ctl.delay


def linear_stable_with_controller(mu: float, beta: float, ctl: WallParams) -> bool:
    """Whether the linear loop with the controller is asymptotically stable (every root inside abs(z) = 1).

    :func:`dfa.analysis.linear.linear_stable` with the controller (one implementation; no encoder, no Coulomb friction):
    the closed-loop spectral radius, and at tiny rates the small-rate bound (the float radius is decided by
    rounding there).
    """
    from ..linear import linear_stable

    return bool(linear_stable(mu, beta, controller=ctl))
