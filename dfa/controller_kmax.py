"""Largest stiffness with a wall controller: the extended criterion and the exact linear bound (issue 15 item 5).

With the controller's physical B, f_c, τ_a and d held fixed (so β_B = B/(KT) falls as K grows):

* ``k_criterion``: the largest K at which the criterion of eq. 6 extended to the damper, filter and
  delay (:func:`dfa.controller_passivity.device_controller_criterion`) proves an impact at the speed
  passive. In physical form (eq. 11 extended) both of its conditions are linear and decreasing in K, so
  the passive K form an interval (0, K*]; K* is found by bisection on the criterion's own verdict (no
  second copy of the formula). Not covered with an amplifier lag (no sound criterion): None and why.
* ``k_linear``: the top of the stable interval from K = 0 of the exact linear sampled loop
  (:func:`dfa.controlled_linear.stable_stiffness`, all conditions, also with the lag).

The describing-function and simulated K_max with a controller (``design_answer(controller=)``) are not
computed here: ``k_df`` and ``k_sim`` are None with the reason; use ``dfa map`` with the controller.

Examples
--------
>>> from dfa.catalogue import get_device
>>> from dfa.controller import Controller
>>> r = controller_stiffness_limits(get_device("Delta").device, Controller(14500.0, damping=1.0), 0.1)
>>> round(r.k_criterion), r.k_sim is None
(21916, True)
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from .checks import check_positive, check_real, check_type
from .controlled_linear import stable_stiffness
from .controller import Controller
from .controller_passivity import device_controller_criterion
from .device import Device
from .errors import DFAValueError
from .jsonable import to_jsonable

__all__ = ["ControllerStiffnessLimits", "controller_stiffness_limits"]

#: Why the criterion gives no K with an amplifier lag.
LAG_REASON = (
    "not covered by the criterion: no sound passivity criterion is proven with an amplifier lag; "
    "see `dfa map`/`dfa zwidth`"
)
#: Why the describing-function and simulated K_max are absent with a controller.
NOT_COMPUTED = "not computed with a controller yet; simulate the controller with `dfa map`/`dfa simulate`"
#: Relative width at which the bisection of K_criterion stops.
RTOL = 1e-12


@dataclass(frozen=True)
class ControllerStiffnessLimits:
    """K_max with a controller by the extended criterion and the exact linear bound (module docstring).

    Attributes
    ----------
    device : Device
    controller : Controller
        The controller held fixed (its stiffness is the one to assess, not the answer).
    velocity : float
        Impact speed, m/s (rotary: rad/s), > 0.
    k_criterion : float or None
        Largest K (N/m) the extended criterion proves passive at ``velocity`` (0 if none); None with a lag.
    k_linear : float
        Top of the stable interval from K = 0 of the exact linear loop, N/m (0 if never stable).
    k_df, k_sim, k_sim_rest : None
        Not computed with a controller (``reasons``).
    reasons : dict
        Why each None is None.
    status : str
        ``"ok"`` or ``"partial"`` (some K_max not computed).
    """

    device: Device
    controller: Controller
    velocity: float
    k_criterion: float | None
    k_linear: float
    k_df: float | None
    k_sim: float | None
    k_sim_rest: float | None
    reasons: dict
    status: str

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, "use controller_stiffness_limits")
        check_type("controller", self.controller, Controller, "use controller_stiffness_limits")
        if self.status not in ("ok", "partial"):
            raise DFAValueError(f"status = {self.status!r} is invalid: it must be 'ok' or 'partial'")

    def as_dict(self) -> dict[str, object]:
        """JSON-ready record (SI units); null values explained in ``null_reasons``.

        Returns
        -------
        dict
            velocity, k_criterion, k_linear, k_df, k_sim, k_sim_rest, null_reasons, status.
        """
        return to_jsonable(
            {
                "velocity": self.velocity,
                "k_criterion": self.k_criterion,
                "k_linear": self.k_linear,
                "k_df": self.k_df,
                "k_sim": self.k_sim,
                "k_sim_rest": self.k_sim_rest,
                "null_reasons": dict(self.reasons),
                "status": self.status,
            }
        )


def _passive(dev: Device, ctl: Controller, k: float, v: float) -> bool:
    """The criterion's verdict at stiffness k; a K whose groups are not representable is not proven passive."""
    try:
        return device_controller_criterion(dev, replace(ctl, stiffness=k), v).passive
    except DFAValueError:
        return False


def _k_criterion(dev: Device, ctl: Controller, v: float) -> float:
    """Largest K the extended criterion proves passive (bisection; the passive K are an interval (0, K*])."""
    lo, hi = 0.0, 1.0
    while _passive(dev, ctl, hi, v):  # the criterion fails for K large enough (σ₀ grows with K)
        lo, hi = hi, 2.0 * hi
        if hi > 1e300:
            raise DFAValueError("the criterion passes at every stiffness: check the device's friction values")
    if lo == 0.0:
        lo = hi
        while lo > 1e-300 and not _passive(dev, ctl, lo, v):
            lo *= 0.5
        if not _passive(dev, ctl, lo, v):
            return 0.0
        hi = 2.0 * lo
    while hi - lo > RTOL * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _passive(dev, ctl, mid, v) else (lo, mid)
    return lo


def controller_stiffness_limits(device: Device, controller: Controller, velocity: float) -> ControllerStiffnessLimits:
    """K_max with ``controller`` (B, f_c, f_bw, d fixed) at an impact speed: extended criterion and linear bound.

    Parameters
    ----------
    device : Device
        The physical device.
    controller : Controller
        The wall controller; its damping B (N·s/m), delay, filter cutoff (Hz) and amplifier bandwidth (Hz)
        are held fixed while K varies.
    velocity : float
        Impact speed in m/s (rotary: rad/s), > 0 (sign ignored).

    Returns
    -------
    ControllerStiffnessLimits
        ``k_criterion`` (None with an amplifier lag), ``k_linear``; ``k_df``/``k_sim`` None with reasons.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad device, controller or speed.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    ctl = check_type("controller", controller, Controller, "build one with dfa.controller.Controller(K, ...)")
    v = abs(check_real("velocity", velocity, "give the impact speed in m/s (rotary: rad/s)"))
    check_positive("velocity", v, "give an impact speed > 0 in m/s (rotary: rad/s)")
    ctl.params(dev.period)  # refuses a filter cutoff above the Nyquist frequency
    reasons = {"k_df": NOT_COMPUTED, "k_sim": NOT_COMPUTED, "k_sim_rest": NOT_COMPUTED}
    if ctl.amplifier_bandwidth is None:
        kc: float | None = _k_criterion(dev, ctl, v)
    else:
        kc, reasons["k_criterion"] = None, LAG_REASON
    kl = stable_stiffness(dev.mass, dev.damping, dev.period, ctl).k_crit
    return ControllerStiffnessLimits(dev, ctl, v, kc, kl, None, None, None, reasons, "partial")
