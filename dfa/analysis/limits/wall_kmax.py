"""Largest stiffness with a wall controller, four ways (issue 15 item 5; issue 14 §1 with a controller).

With the controller's physical B, f_c, τ_a and d held fixed (so β_B = B/(KT) falls as K grows):

* ``k_criterion``: the largest K at which the criterion of eq. 6 extended to the damper, filter and
  delay (:func:`dfa.analysis.criterion.device_criterion`) proves an impact at the speed
  passive. In physical form (eq. 11 extended) both of its conditions are linear and decreasing in K, so
  the passive K form an interval (0, K*]; K* is found by bisection on the criterion's own verdict (no
  second copy of the formula). Not covered with an amplifier lag (no sound criterion): None and why.
* ``k_linear``: the top of the stable interval from K = 0 of the exact linear sampled loop
  (:func:`dfa.analysis.linear_wall.stable_stiffness`, all conditions, also with the lag).
* ``k_df``, ``k_sim``, ``k_sim_rest``: the describing-function and simulated limits, searched, swept in K
  (from K_criterion; with a lag or a zero K_criterion from the grid's lowest point) and confirmed exactly as
  for the spring (:func:`dfa.analysis.limits.kmax.design_answer`, the same implementation,
  :func:`dfa.analysis.limits.kmax.searched_limits`) with each K's own controller groups in the simulations and in the
  cycle search (:func:`dfa.analysis.cycles.limit_cycles` with ``controller=``). The geometric grid runs from
  half of K_criterion (with a lag: half of K_linear) to 8 × the largest of K_criterion, K_linear and the
  static limit 2c/Δ. Every impact simulated at or below K_criterion that diverges is a counterexample
  to the extended criterion (status ``"counterexample"``); with a lag there is no criterion and no such
  check (``counterexample_check`` says so). The preload start (at rest, spring energy equal to the
  impact's kinetic energy) is kept: the damper's velocity estimate and the filter start at 0, the delayed
  commands and the amplifier's force at the spring's force at ξ0, the steady state of a device held still
  there, a legitimate start of the controlled loop.
* The pure spring controller (B = 0, no filter, no lag) takes the spring's closed forms (eq. 11, the exact
  linear bound k_gil) and grid: its four limits are :func:`dfa.analysis.limits.kmax.design_answer`'s, bit for bit.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.wall import Wall
>>> r = controller_stiffness_limits(get_device("Delta").device, Wall.of(14500.0, damping=1.0), 0.1,
...                                 speeds=2, grid=6)
>>> round(r.k_criterion), r.k_criterion <= r.k_sim.value, r.k_sim_rest.value <= r.k_sim.value
(21916, True, True)
>>> r.status in ("ok", "caveats"), r.counterexamples
(True, ())
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...checks import _fmt, check_choice, check_int, check_positive, check_real, check_speed, check_type
from ...errors import DFATypeError, DFAValueError
from ...model.device import Device
from ...model.wall import Wall
from ...results.jsonable import explain_nulls
from ..criterion import device_criterion
from ..linear_wall import stable_stiffness
from .closed_form import k_colgate, k_gil, k_max_criterion, k_static
from .kmax import (
    DESIGN_MAX_SAMPLES,
    KMaxAssessment,
    KSearch,
    RunCache,
    _assess,
    _Evidence,
    _SearchedLimits,
    searched_limits,
)

__all__ = ["ControllerStiffnessLimits", "controller_stiffness_limits"]

#: Why the criterion gives no K with an amplifier lag.
LAG_REASON = (
    "not covered by the criterion: no sound passivity criterion is proven with an amplifier lag; "
    "see `dfa map`/`dfa zwidth`"
)
#: Why no counterexample check is made with an amplifier lag.
NO_CHECK_REASON = "no counterexample check: with an amplifier lag there is no sound criterion to contradict"
#: Relative width at which the bisection of K_criterion stops.
RTOL = 1e-12
#: Statuses of a result: as :class:`dfa.analysis.limits.kmax.KMaxResult`.
STATUSES = ("ok", "caveats", "counterexample")


@dataclass(frozen=True)
class ControllerStiffnessLimits(_SearchedLimits):
    """K_max with a controller four ways (module docstring); stiffnesses in N/m (rotary N·m/rad).

    Attributes
    ----------
    device : Device
    controller : Wall
        The controller held fixed (its stiffness is the one to assess, not the answer).
    velocity : float
        Impact speed, m/s (rotary: rad/s), > 0.
    k_criterion : float or None
        Largest K the extended criterion proves passive at ``velocity`` (0 if none); None with a lag.
    k_linear : float
        Top of the stable interval from K = 0 of the exact linear loop (0 if never stable).
    k_df, k_sim, k_sim_rest : KSearch
        Searched limits with their evidence (:class:`dfa.analysis.limits.kmax.KSearch`; value None with a reason).
    reasons : dict
        Why ``k_criterion`` is None or 0 (key ``"k_criterion"``), and why there is no counterexample check
        (``"counterexamples"``), where so.
    speeds : tuple of float
        Impact speeds simulated in the search, each from ξ0 = 0 and from the preload.
    simulations : int
        Exact simulations the searches and confirmations rest on.
    longest_run, max_samples : int
        Longest run of the search (samples) and the cap of every run.
    df_model : str
        Hold model of the describing function.
    k_range : tuple of float
        Smallest and largest stiffness of the search grid.
    counterexamples : tuple of dict
        Divergent impacts at or below ``k_criterion`` (empty unless the extended criterion is wrong).
    assessment : KMaxAssessment or None
        The controller's own stiffness assessed, when asked.
    status : str
        ``"ok"``, ``"caveats"`` (non-monotone, undecided-limited or lowered by the confirmation) or
        ``"counterexample"``.
    """

    device: Device
    controller: Wall
    velocity: float
    k_criterion: float | None
    k_linear: float
    k_df: KSearch
    k_sim: KSearch
    k_sim_rest: KSearch
    reasons: dict
    speeds: tuple[float, ...]
    simulations: int
    longest_run: int
    max_samples: int
    df_model: str
    k_range: tuple[float, float]
    counterexamples: tuple[dict[str, object], ...] = ()
    assessment: KMaxAssessment | None = None
    status: str = "ok"

    def __post_init__(self) -> None:
        fix = "use controller_stiffness_limits"
        check_type("device", self.device, Device, fix)
        check_type("controller", self.controller, Wall, fix)
        check_positive("velocity", self.velocity, fix)
        if self.k_criterion is not None:
            check_real("k_criterion", self.k_criterion, fix)
        check_real("k_linear", self.k_linear, fix)
        for name in ("k_df", "k_sim", "k_sim_rest"):
            check_type(name, getattr(self, name), KSearch, fix)
        for name in ("simulations", "longest_run", "max_samples"):
            check_int(name, getattr(self, name), 0, fix)
        check_choice("df_model", self.df_model, ("half-delay", "zoh", "pade"))
        for name in ("speeds", "k_range", "counterexamples"):
            if not isinstance(getattr(self, name), tuple):
                raise DFATypeError(f"{name} = {_fmt(getattr(self, name))} must be a tuple; {fix}")
        if not isinstance(self.reasons, dict):
            raise DFATypeError(f"reasons = {_fmt(self.reasons)} must be a dict of str; {fix}")
        if self.k_criterion is None and not self.reasons.get("k_criterion"):
            raise DFAValueError("k_criterion = None needs a reason in reasons['k_criterion']; " + fix)
        if self.assessment is not None:
            check_type("assessment", self.assessment, KMaxAssessment, fix)
        if self.status not in STATUSES:
            raise DFAValueError(f"status = {self.status!r} is invalid: it must be one of {', '.join(STATUSES)}")

    def evidence_text(self) -> str:
        """How the simulated limits were found, in one sentence (with the controller held fixed).

        Returns
        -------
        str
            Runs, speeds, stiffness range (device units), run lengths, hold model.
        """
        return super().evidence_text() + "; each K with its own β_B = B/(KT), filter, lag and delay held fixed"

    def to_dict(self) -> dict[str, object]:
        """JSON-ready record (SI units): the limits (null with a reason), the evidence, status.

        Returns
        -------
        dict
            velocity, k_criterion, k_linear, k_df, k_sim, k_sim_rest (with ``*_reason``), status, evidence,
            counterexample_check, searches, counterexamples, assessment, and ``null_reasons`` (JSON pointers).
        """
        out: dict[str, object] = {
            "velocity": self.velocity,
            "k_criterion": self.k_criterion,
            "k_linear": self.k_linear,
        }
        fields, why = self._search_fields()
        out.update(fields)
        why.update({k: str(v) for k, v in self.reasons.items()})
        why["assessment"] = "no stiffness to assess asked"
        starts = ["impact from ξ0 = 0", "spring preload of equal energy (damper velocity and filter at 0)"]
        out.update(
            status=self.status,
            **self._evidence_fields(starts, simulated_runs=self.simulations),
            counterexample_check=self.reasons.get("counterexamples", "every run at or below k_criterion"),
        )
        return explain_nulls(out, {k: v for k, v in why.items() if k != "counterexamples"})


def _passive(dev: Device, ctl: Wall, k: float, v: float) -> bool:
    """The criterion's verdict at stiffness k; a K whose groups are not representable is not proven passive."""
    try:
        return device_criterion(dev, ctl.with_stiffness(k), v).passive
    except DFAValueError:
        return False


def _k_criterion(dev: Device, ctl: Wall, v: float) -> float:
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


def _bounds(dev: Device, ctl: Wall, v: float) -> tuple[float | None, float, float, float, dict[str, str]]:
    """K_criterion (None with a lag), K_linear, the grid's reference K and top, and the reasons for None (or 0).

    The pure spring (B = 0, no filter, no lag; any delay) uses the spring's closed forms and grid
    (eq. 11, the exact linear bound, 8 × the largest closed-form bound), so that its limits are
    :func:`dfa.analysis.limits.kmax.design_answer`'s bit for bit.
    """
    reasons: dict[str, str] = {}
    if ctl.damping == 0.0 and ctl.filter_cutoff is None and ctl.amplifier_bandwidth is None:
        kc0, kl0 = float(k_max_criterion(dev, v, ctl.delay)), k_gil(dev, delay=ctl.delay)
        return kc0, kl0, kc0, 8.0 * max(k_static(dev), k_colgate(dev, ctl.delay), kl0, kc0), reasons
    if ctl.amplifier_bandwidth is None:
        kc: float | None = _k_criterion(dev, ctl, v)
        if kc == 0.0:  # say why: σ >= σ₀ = ½ + (1 − a)β_B at some K needs c/Δ > (1 − a)B/T
            never = dev.coulomb / dev.resolution <= (1 - ctl.params(dev.period).filter_pole) * ctl.damping / dev.period
            reasons["k_criterion"] = "the extended criterion proves no K passive at this speed" + (
                ": σ >= σ₀ needs c/Δ > (1 − a)B/T" if never else ""
            )
    else:
        kc, reasons["k_criterion"], reasons["counterexamples"] = None, LAG_REASON, NO_CHECK_REASON
    kl = stable_stiffness(dev.mass, dev.damping, dev.period, ctl).k_crit
    return kc, kl, (kl if kc is None else kc), 8.0 * max(k_static(dev), kl, kc or 0.0), reasons


def controller_stiffness_limits(
    device: Device,
    controller: Wall,
    velocity: float,
    *,
    speeds: int = 6,
    grid: int = 16,
    max_samples: int = DESIGN_MAX_SAMPLES,
    df_model: str = "half-delay",
    assess: str | None = None,
    cache: RunCache | None = None,
) -> ControllerStiffnessLimits:
    """K_max with ``controller`` (B, f_c, f_bw, d fixed) at an impact speed, four ways (module docstring).

    Parameters
    ----------
    device : Device
        The physical device.
    controller : Wall
        The wall controller; its damping B (N·s/m), delay, filter cutoff (Hz) and amplifier bandwidth (Hz)
        are held fixed while K varies.
    velocity : float
        Impact speed in m/s (rotary: rad/s), > 0 (a negative is refused, not flipped).
    speeds : int, optional
        Impact speeds simulated: V/speeds, 2V/speeds, …, V (default 6), each from two starts.
    grid : int, optional
        Points of the geometric stiffness grid (default 16); bisection refines each limit.
    max_samples : int, optional
        Longest run in samples (default 10⁶); each run's length is
        :func:`dfa.analysis.simulation.default_samples` with the controller.
    df_model : {"half-delay", "zoh", "pade"}, optional
        Hold model of the describing function (default ``"half-delay"``).
    assess : str, optional
        Also assess the controller's own stiffness; the text says where it came from (``"given"``,
        ``"catalogue"``). None (default): no assessment.
    cache : RunCache, optional
        Runs and predictions already computed; the result does not depend on it.

    Returns
    -------
    ControllerStiffnessLimits
        ``k_criterion`` (None with an amplifier lag), ``k_linear``, ``k_df``, ``k_sim``, ``k_sim_rest``.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad device, controller, speed or search setting.

    See Also
    --------
    design_answer : The same four ways for the spring.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    ctl = check_type("controller", controller, Wall, "build one with dfa.model.wall.Wall.of(K, ...)")
    v = check_speed("velocity", velocity, zero=False)
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one impact speed")
    n_grid = check_int("grid", grid, minimum=2, fix="give at least 2 stiffness grid points")
    cap = check_int("max_samples", max_samples, minimum=1000, fix="allow runs of at least 1000 samples")
    model = check_choice("df_model", df_model, ("half-delay", "zoh", "pade"))
    if assess is not None:
        check_choice("assess", assess, ("given", "--stiffness", "catalogue"))
    if cache is not None:
        check_type("cache", cache, RunCache, "pass a dfa.analysis.limits.kmax.RunCache, or None")
    ctl.params(dev.period)  # refuses a filter cutoff above the Nyquist frequency
    kc, kl, k_ref, top, reasons = _bounds(dev, ctl, v)
    vs = v * np.arange(1, n_speeds + 1) / n_speeds
    ev = _Evidence(dev, vs, ctl.delay, cap, model, RunCache() if cache is None else cache, ctl)
    k_df, k_sim, k_rest, k_range, ce, status = searched_limits(ev, v, n_speeds, kc, k_ref, top, n_grid)
    a = None if assess is None else _assess(ev, ctl.stiffness, assess, v, ctl.delay)
    return ControllerStiffnessLimits(
        dev,
        ctl,
        v,
        kc,
        kl,
        k_df,
        k_sim,
        k_rest,
        reasons,
        tuple(float(x) for x in vs),
        ev.runs,
        ev.longest,
        cap,
        model,
        k_range,
        ce,
        a,
        status,
    )
