"""The stiffness–speed chart (issue 14 §2): the largest safe impact speed against the stiffness K.

For each stiffness K of a geometric grid, the largest impact speed (m/s;
rotary rad/s) that is safe by

* the criterion (eq. 11 with the delay: the critical speed of eq. 12, a
  proof; :func:`dfa.analysis.limits.closed_form.max_passive_velocity`),
* the describing function (the smallest speed amplitude M·ω over every
  unstable cycle, in physical units; a first-harmonic prediction),
* exact simulation, no divergence: the largest simulated speed such that no
  impact at it or at any slower simulated speed, from ξ0 = 0 or from the
  energy preload, diverges (undecided runs count as not safe),
* exact simulation, rest: the same with "comes to rest",

all limited to hand speeds (``v_top``, default 2 m/s; rotary 10 rad/s, or the
design speed when larger). Speeds above ``v_top`` are reported as ``v_top``
(``capped``). The closed-form stiffness bounds (exact linear bound,
Colgate-Schenkel, Abbott-Okamura, static 2c/Δ) are vertical lines; the
design point (K, V) is marked. Draw with :meth:`StiffnessSpeedChart.plot`.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> c = stiffness_speed_chart(Loop(get_device("Impulse Engine").device), grid=6, speeds=4)
>>> c.v_sim.shape, bool(c.v_top == 2.0)
((6,), True)
"""

from __future__ import annotations

import math
import sys
from typing import Any

import numpy as np

from ...checks import check_int, check_positive, check_speed, check_type
from ...errors import DFAValueError
from ...grids import geometric_grid
from ...model.device import Device
from ...model.loop import LOOP_FIX, Loop, loop_first
from ...model.wall import Wall
from ...plausibility import warn_if_from_outside
from ...results.limits import UNKNOWN_DF as UNKNOWN_DF
from ...results.limits import StiffnessSpeedChart as StiffnessSpeedChart
from .closed_form import HAND_SPEED, k_static
from .kmax import DESIGN_MAX_SAMPLES, closed_forms, passive_speed
from .runs import SAFE, Evidence, Growth, RunCache, judge_outcomes
from .search import check_stiffness_range

__all__ = ["StiffnessSpeedChart", "stiffness_speed_chart", "check_chart_range", "HAND_SPEED"]


def _ro(a: Any) -> np.ndarray:
    out = np.array(a, dtype=float)
    out.setflags(write=False)
    return out


def _largest_safe(verdicts: list[bool], speeds: np.ndarray) -> float:
    """The largest speed such that it and every slower simulated speed are safe (0: none)."""
    out = 0.0
    for ok, v in zip(verdicts, speeds, strict=True):
        if not ok:
            break
        out = float(v)
    return out


def _k_range(dev: Device, wall: Wall, v_top: float, design: float | None) -> tuple[float, float]:
    """The stiffness range: from a quarter of the lowest closed-form bound to 8 × the highest (and the design K);
    a one-sided wall's bounds but the criterion's are those of the wall it is in contact."""
    kc, kl, pub, _ref, _top = closed_forms(dev, wall, v_top)
    if not wall.linear:
        _kc, kl, pub, _ref, _top = closed_forms(dev, wall.in_contact().without_controller(), v_top)
    lows = [k for k in (kl.value, pub["k_colgate"], kc.value) if k is not None and k > 0]
    spring = (pub["k_static"], pub["k_colgate"]) if pub["k_static"] is not None else (k_static(dev), kl.value)
    highs = [k for k in spring if k is not None] + ([design] if design else [])
    lo = 0.25 * min(lows + ([design] if design else [])) if lows or design else 1e-3
    return lo, max(8.0 * max(highs), 16.0 * lo)


#: What the chart's stiffness range is, in the message of :func:`~dfa.analysis.limits.search.check_stiffness_range`.
CHART_RANGE = (
    "the stiffness–speed chart (a quarter of the lowest closed-form bound to 8 × the highest and the design K)"
)


def check_chart_range(device: Device, wall: Wall, stiffness: float, velocity: float) -> None:
    """Refuse, before any work, a design point whose chart (:func:`stiffness_speed_chart` with the default
    ``v_top``) would run over a stiffness range no float search can (:func:`~dfa.analysis.limits.search
    .check_stiffness_range`): ``dfa report --stiffness 1e308`` reached K = 8e308 = inf.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> check_chart_range(get_device("Delta").device, Wall(14500.0), 14500.0, 0.1)
    """
    top = max(HAND_SPEED["rotary" if device.rotary else "linear"], velocity)
    check_stiffness_range(device, *_k_range(device, wall, top, stiffness), CHART_RANGE, stiffness)


#: Most stiffnesses (``grid``) or speeds (``speeds``) one chart simulates.
_MAX_COUNT = 1000
#: Slowest impact speed simulated (``v_top``/200): the smallest normal float.
_SMALLEST_SPEED = sys.float_info.min


@loop_first("device, *, wall")
def stiffness_speed_chart(
    loop: Loop,
    *,
    stiffness: float | None = None,
    velocity: float | None = None,
    v_top: float | None = None,
    grid: int = 24,
    speeds: int = 14,
    max_samples: int = DESIGN_MAX_SAMPLES,
    cache: RunCache | None = None,
) -> StiffnessSpeedChart:
    """Compute the stiffness–speed chart of a device (module docstring).

    Parameters
    ----------
    loop : Loop
        The device and the wall whose elements (delay d in samples, damper B in N·s/m, filter, amplifier) are
        held fixed while K varies, ``Loop(device, wall)``; ``Loop(device)``: the spring. The former call
        ``stiffness_speed_chart(device, wall=wall)`` still works.
    stiffness, velocity : float, optional
        The design point (N/m; m/s), marked on the chart.
    v_top : float, optional
        Top of the speed range (default :data:`HAND_SPEED`, or ``velocity`` when larger).
    grid : int, optional
        Stiffnesses simulated (default 24, geometric; at most 1000).
    speeds : int, optional
        Impact speeds simulated per stiffness (default 14, geometric from v_top/200; at most 1000), two starts each.
    max_samples : int, optional
        Longest run in samples.
    cache : RunCache, optional
        Runs and predictions already computed (:class:`dfa.analysis.limits.kmax.RunCache`, shared with
        :func:`dfa.analysis.limits.kmax.design_answer` by the design analysis); a fresh one when None. The chart does not depend on it.

    Returns
    -------
    StiffnessSpeedChart
        For each stiffness, the largest speed that passes the criterion, the simulation and the
        describing function, with the classic bounds; ``.plot()`` draws it.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``loop`` is not a :class:`Loop` of a device, a speed or stiffness is not a finite number > 0, or
        another input is out of range.

    See Also
    --------
    design_answer : The largest stiffness at one speed, four ways.
    stiffness_response : The criterion's K_max over speeds (no simulation).
    """
    dev = check_type("loop", loop, Loop, LOOP_FIX).search_device("stiffness_speed_chart")
    w = loop.spring
    k_design = None if stiffness is None else check_positive("stiffness", stiffness, "give K in N/m")
    v_design = None if velocity is None else check_speed("velocity", velocity)
    for quantity, value in (("stiffness", k_design), ("velocity", v_design)):
        if value is not None:
            warn_if_from_outside(quantity, value, rotary=dev.rotary)
    fix_top = "give the top of the speed range in m/s (rad/s rotary), e.g. 0.5"
    top = HAND_SPEED["rotary" if dev.rotary else "linear"] if v_top is None else v_top
    top = max(check_positive("v_top", top, fix_top), v_design or 0.0)
    if not top / 200.0 >= _SMALLEST_SPEED:  # the slowest speed simulated is v_top/200: a normal float
        raise DFAValueError(
            f"v_top = {top!r} is invalid: it must be a finite number >= {200 * _SMALLEST_SPEED!r}; {fix_top}"
        )
    n_k = check_int("grid", grid, minimum=2, fix="give at least 2 stiffnesses")
    n_v = check_int("speeds", speeds, minimum=1, fix="simulate at least one speed")
    if n_k > _MAX_COUNT or n_v > _MAX_COUNT:
        arg, n = ("grid", n_k) if n_k > _MAX_COUNT else ("speeds", n_v)
        raise DFAValueError(
            f"{arg} = {n} is invalid: it must be a whole number <= {_MAX_COUNT}; each one is a set of simulations"
        )
    n_max = check_int("max_samples", max_samples, minimum=1000, fix="give the longest run in samples")
    vs = geometric_grid(top / 200.0, top, n_v) if n_v > 1 else np.array([top])
    lo, hi = _k_range(dev, w, top, k_design)
    check_stiffness_range(dev, lo, hi, CHART_RANGE, k_design)
    ks = geometric_grid(lo, hi, n_k)
    if cache is not None:
        check_type("cache", cache, RunCache, "pass a dfa.analysis.limits.runs.RunCache, or None")
    ev = Evidence(dev, w, vs, n_max, "half-delay", cache)
    v_sim, v_rest, v_df = [], [], []
    n = len(ev.starts)
    for k in ks:
        rows = ev.outcomes(float(k))
        per_speed = [{o for _, _, o in rows[n * i : n * (i + 1)]} for i in range(len(vs))]  # every start
        v_sim.append(_largest_safe([judge_outcomes(o, "unstable") == SAFE for o in per_speed], vs))
        v_rest.append(_largest_safe([judge_outcomes(o, "rest") == SAFE for o in per_speed], vs))
        v_df.append(_df_speed(ev.growth_xi_dot(float(k)), dev, top))
    kc = geometric_grid(lo, hi, 200)
    vc = []
    for k in kc:
        mpv, _status = passive_speed(dev, w, float(k))
        vc.append(0.0 if mpv is None else min(top, mpv))
    _c, kl, pub, _r, _t = closed_forms(dev, w, top)
    return StiffnessSpeedChart(
        dev, w, top, _ro(ks), _ro(v_df), _ro(v_sim), _ro(v_rest), _ro(kc), _ro(vc), _ro(vs),
        kl.value or 0.0, pub["k_colgate"], pub["k_abbott_okamura"], pub["k_static"], k_design, v_design, ev.runs,
    )  # fmt: skip


def _df_speed(g: Growth, dev: Device, top: float) -> float:
    """The describing function's largest safe speed (m/s) from its growth prediction: NaN where unknown (the sub-tick
    caveat, a failed search, or a lower bound below ``top``), at most ``top``."""
    if g.xi_dot is None or g.subtick:
        return math.nan
    v = dev.velocity(g.xi_dot) if math.isfinite(g.xi_dot) else math.inf
    if g.lower_bound and v < top:
        return math.nan
    return min(top, v)
