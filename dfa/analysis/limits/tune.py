"""The wall with the largest recommended stiffness among the elements an engineer allows (issue 44).

:func:`tune` tries every combination of the sample periods, delays, virtual dampers and velocity-filter cutoffs
allowed (each list has a default), in three stages:

1. **Screen** every candidate with the quick answer (:func:`dfa.analysis.limits.kmax.design_answer` with
   ``simulate=False``): the criterion's K (eq. 11, extended to the wall) and the exact linear bound (the describing
   function's K where the linear loop does not cover the wall). The screen's K is the larger of the proven K and
   that bound over the margin; its force error there comes from one short simulated impact. The walls whose error
   is within :data:`SCREEN_SLACK` times the cap come first, by screen's K. It recommends nothing.
2. **Simulate** the plain wall (the given wall without a virtual damper, velocity filter or passivity controller,
   at the device's own period) and the ``evaluate`` best-screened others in full, and recommend each wall's K by the
   one rule of :func:`dfa.analysis.limits.recommend.recommend_stiffness`: the largest proven K, or the simulated
   no-divergence limit over the margin, said as such.
3. **Passivity controller**: for each force limit allowed, the best simulated wall with the controller, compared
   with the same wall without it (the rule recommends the controller only where it raises K).

Each simulated wall's fidelity at its recommended K follows from one simulated impact
(:func:`dfa.analysis.fidelity.force_error`). Only stages 2 and 3 recommend: the screen's ranking decides which walls
are simulated, so a wall ranked low by the screen and never simulated could still do better (the result lists the
screened walls, and ``evaluate`` simulates more).

Defaults: the device's own period; the wall's delay; B = 0 and the 1-2-5 values from the largest damper with which
the criterion still proves some K (:func:`dfa.analysis.limits.kmax.max_proven_damping`) up to m/T (half of where the
backward-difference damper on the bare mass becomes unstable, BT/m = 2); no filter and the 1-2-5 cutoff nearest
below a tenth of the sample rate; no passivity controller (simulating one takes tens of seconds per force limit).

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.loop import Loop
>>> small = {"speeds": 2, "grid": 6}        # a coarser search than the default, for the example
>>> r = tune(Loop(get_device("impulse").device), 0.05, dampings=[0.0, 0.5], cutoffs=[None], evaluate=1, search=small)
>>> r.status.value, r.walls[0].wall.damping, r.best.wall.damping   # the damped wall buzzes at its K
('plain_best', 0.0, 0.0)
>>> r.walls[1].recommendation.above_rest, r.walls[1].k_recommended > r.walls[0].k_recommended
(True, True)
>>> dataclasses.replace(r, require_rest=False).best.wall.damping     # the stiffest, buzzing or not
0.5
"""

from __future__ import annotations

import dataclasses
import itertools
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ...checks import check_bool, check_positive, check_type
from ...errors import DFATypeError, DFAValueError
from ...model.device import Device
from ...model.elements import Damper, Delay, PassivityController, VelocityFilter
from ...model.loop import Loop
from ...model.wall import MIN_CUTOFF, Wall
from ...progress import advance, stage
from ...results.require import DEFAULT_MARGIN, check_margin
from ...results.status import TunedStatus, TuneStatus
from ...results.tune import TunedWall, TuneResult, within_cap
from ..fidelity import force_error
from .kmax import KMaxResult, design_answer, max_proven_damping
from .recommend import recommend_stiffness

__all__ = [
    "tune",
    "TuneResult",
    "TunedWall",
    "default_dampings",
    "default_cutoffs",
    "series_125",
    "MAX_CANDIDATES",
    "DEFAULT_MAX_FORCE_ERROR",
]

#: The most candidate walls one tuning screens (about 0.3 s each): more is refused up front.
MAX_CANDIDATES = 200
#: The default cap on the best wall's force error (a fraction of the ideal spring's peak force).
DEFAULT_MAX_FORCE_ERROR = 0.5
#: The screen ranks first the walls whose force error at the screen's K is within this factor of the cap: the error
#: at the recommended K differs (the screen's K is not it), by a few per cent of the peak force on the catalogue's
#: devices.
SCREEN_SLACK = 1.25
#: The keywords of design_answer a tuning's ``search`` may set.
_SEARCH_KEYS = frozenset({"speeds", "grid", "max_samples", "df_model"})
#: The most values one default list holds.
_MAX_DEFAULT = 6


def series_125(lo: float, hi: float) -> list[float]:
    """The 1-2-5 values (1, 2, 5 × 10ⁿ) in [lo, hi], ascending: round numbers a command line repeats exactly.

    Examples
    --------
    >>> series_125(0.12, 16.0)
    [0.2, 0.5, 1.0, 2.0, 5.0, 10.0]
    """
    if not (0.0 < lo <= hi and math.isfinite(hi)):
        return []
    out = []
    for n in range(math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1):
        for m in (1, 2, 5):
            x = float(f"{m}e{n}")  # the decimal 1-2-5 value itself, not m·10ⁿ rounded twice
            if lo <= x <= hi:
                out.append(x)
    return out


def default_dampings(device: Device, wall: Wall, velocity: float) -> tuple[float, ...]:
    """0 and the 1-2-5 dampers from the largest with which the criterion proves some K up to m/T (module
    docstring), at most six (the largest kept), N·s/m (rotary N·m·s/rad).

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> default_dampings(get_device("impulse").device, Wall(1.0), 0.05)
    (0.0, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0)
    """
    hi = device.mass / device.period
    lo = max_proven_damping(device, wall.without_controller(), velocity)
    lo = lo if lo > 0.0 else hi / 100.0
    return (0.0, *series_125(lo, hi)[-_MAX_DEFAULT:])


def default_cutoffs(device: Device) -> tuple[float | None, ...]:
    """No filter, and the 1-2-5 cutoff nearest below a tenth of the sample rate (Hz).

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> default_cutoffs(get_device("impulse").device)     # T = 2 ms: 500 Hz sampling
    (None, 50.0)
    """
    fs = 1.0 / device.period
    below = series_125(max(MIN_CUTOFF * fs, fs / 1000.0), fs / 10.0)
    return (None, below[-1]) if below else (None,)


def _check_lists(
    device: Device, dampings: Sequence[float], cutoffs: Sequence[float | None], delays: Sequence[int],
    periods: Sequence[float], pc_limits: Sequence[float],
) -> None:  # fmt: skip
    """Refuse an empty list, a negative damper, a delay that is not a whole number >= 0, a period <= 0, a force
    limit <= 0, a cutoff outside (0, Nyquist) of the shortest period, or too many candidates."""
    for name, values in (("dampings", dampings), ("cutoffs", cutoffs), ("delays", delays), ("periods", periods)):
        if len(values) == 0:
            raise DFAValueError(f"{name} = [] is invalid: give at least one value, or None for the default")
    for b in dampings:
        if not (isinstance(b, (int, float)) and math.isfinite(b) and b >= 0.0):
            raise DFAValueError(f"dampings value {b!r} is invalid: a virtual damper B is a finite number >= 0 N·s/m")
    for d in delays:
        if not (isinstance(d, int) and d >= 0):
            raise DFAValueError(f"delays value {d!r} is invalid: a delay is a whole number of samples >= 0")
    for t in periods:
        check_positive("periods value", t, "give sample periods in s, e.g. [0.001, 0.002]")
    for f in pc_limits:
        check_positive("pc_limits value", f, "give the passivity controller's force limits in N (rotary N·m)")
    for fc in cutoffs:  # the filter's own rule (at least MIN_CUTOFF cycles per sample, below Nyquist) at every period
        if fc is None:
            continue
        if not isinstance(fc, (int, float)):
            raise DFAValueError(
                f"cutoffs value {fc!r} is invalid: a filter cutoff is a number of Hz, or None (no filter)"
            )
        for t in periods:
            Wall.of(1.0, filter_cutoff=float(fc)).params(float(t), device.resolution)
    n = len(dampings) * len(cutoffs) * len(delays) * len(periods)
    if n > MAX_CANDIDATES:
        raise DFAValueError(
            f"{len(dampings)} dampings x {len(cutoffs)} cutoffs x {len(delays)} delays x {len(periods)} periods = {n} "
            f"candidate walls is too many: at most {MAX_CANDIDATES} (about 0.3 s each); give shorter lists"
        )


def _plain(wall: Wall) -> Wall:
    """The wall without a virtual damper, velocity filter or passivity controller."""
    tuned = (Damper, VelocityFilter, PassivityController)
    return Wall(wall.stiffness, tuple(e for e in wall.elements if not isinstance(e, tuned)))


def _candidate(base: Wall, delay: int, damping: float, cutoff: float | None) -> Wall:
    """The plain wall with this delay, damper and filter (the delay replaces the wall's own)."""
    w = Wall.of(base.stiffness, damping=damping, delay=delay, filter_cutoff=cutoff)
    others = tuple(e for e in base.elements if not isinstance(e, Delay))
    return Wall(base.stiffness, w.elements + others)


def _screen_of(ans: KMaxResult, margin: float) -> float:
    """The screen's K: the larger of the proven K and the linear bound (else the describing function's) over the
    margin; 0 where none is finite."""
    proven = ans.k_criterion.value or 0.0
    bound = ans.k_linear.value if ans.k_linear.value is not None else ans.k_df.value
    est = max(proven, (bound or 0.0) / margin)
    return est if math.isfinite(est) else 0.0


def _simulated(
    device: Device, wall: Wall, velocity: float, margin: float, screen: TunedWall, plain: KMaxResult | None = None,
    search: dict[str, Any] | None = None,
) -> tuple[TunedWall, KMaxResult]:  # fmt: skip
    """The wall searched in full, its recommendation and its fidelity at the recommended K (and its answer)."""
    ans = design_answer(Loop(device, wall), velocity, **(search or {}))
    rec = recommend_stiffness(ans, margin, plain=plain)
    error = share = None
    if rec.k_recommended is not None:
        chosen = rec.wall if rec.controller is None or rec.controller.kept else rec.wall.without_controller()
        error, share = force_error(Loop(device, chosen.with_stiffness(rec.k_recommended)), velocity)
    at = wall if rec.k_recommended is None else wall.with_stiffness(rec.k_recommended)
    tuned = TunedWall(device, at, screen.screen, screen.screen_force_error, rec, error, share, TunedStatus.SIMULATED)
    return tuned, ans


def _screened(
    device: Device, base: Wall, velocity: float, margin: float, lists: tuple[Sequence, ...],
    search: dict[str, Any] | None = None,
) -> list[TunedWall]:  # fmt: skip
    """Every candidate (period x delay x damper x cutoff), screened by its quick answer."""
    periods, delays, dampings, cutoffs = lists
    combos = list(itertools.product(periods, delays, dampings, cutoffs))
    out = []
    with stage("screening the walls", len(combos), "wall"):
        for t, d, b, fc in combos:
            dev = device if t == device.period else dataclasses.replace(device, period=float(t))
            wall = _candidate(base, d, float(b), None if fc is None else float(fc))
            ans = design_answer(Loop(dev, wall), velocity, simulate=False, **(search or {}))
            k = float(_screen_of(ans, margin))
            error = _screen_error(Loop(dev, wall.with_stiffness(k)), velocity) if k > 0.0 else None
            out.append(TunedWall(dev, wall.with_stiffness(k) if k > 0.0 else wall, k, error))
            advance(step=1, unit="wall")
    return out


def _screen_error(loop: Loop, velocity: float) -> float | None:
    """The force error at the screen's K (None where the impact is too long to simulate: a very soft wall)."""
    try:
        return force_error(loop, velocity)[0]
    except DFAValueError:
        return None


def _ranked(walls: list[TunedWall]) -> list[TunedWall]:
    """The simulated walls by recommended K (largest first; none last), then the screened by screen."""

    def key(w: TunedWall) -> tuple[int, float]:
        if w.status is TunedStatus.SIMULATED:
            return (0, -(w.k_recommended if w.k_recommended is not None else -1.0))
        return (1, -w.screen)

    return sorted(walls, key=key)


def tune(
    loop: Loop,
    velocity: float,
    *,
    dampings: Sequence[float] | None = None,
    cutoffs: Sequence[float | None] | None = None,
    delays: Sequence[int] | None = None,
    periods: Sequence[float] | None = None,
    pc_limits: Sequence[float] = (),
    margin: float = DEFAULT_MARGIN,
    evaluate: int = 3,
    max_force_error: float | None = DEFAULT_MAX_FORCE_ERROR,
    require_rest: bool = True,
    search: dict[str, Any] | None = None,
) -> TuneResult:
    """The wall with the largest recommended stiffness among the elements allowed, and the trade-off (module docstring).

    Parameters
    ----------
    loop : Loop
        The device and the wall whose other elements are held (a one-sided contact, the device's force limit, an
        amplifier; its stiffness is ignored): ``Loop(device)`` for the spring.
    velocity : float
        Impact speed V, m/s (rotary rad/s), > 0.
    dampings : sequence of float, optional
        Virtual dampers B to try, N·s/m (rotary N·m·s/rad), >= 0 (0: none). Default: :func:`default_dampings`.
    cutoffs : sequence of float or None, optional
        Velocity-filter cutoffs to try, Hz, below the Nyquist frequency (None: no filter). Default:
        :func:`default_cutoffs`.
    delays : sequence of int, optional
        Delays to try, whole samples >= 0. Default: the wall's delay.
    periods : sequence of float, optional
        Sample periods the hardware offers, s. Default: the device's period.
    pc_limits : sequence of float, optional
        Force limits of a passivity controller to try on the best wall, N (rotary N·m). Default: none (no
        controller tried; each takes tens of seconds to simulate).
    margin : float, optional
        Gain margin of the simulated rule, >= 1 (default 2, about 6 dB).
    evaluate : int, optional
        How many of the best-screened walls besides the plain one are simulated in full (default 3), >= 1.

    max_force_error : float or None, optional
        The largest force error (RMS over the first contact, a fraction of the ideal spring's peak force;
        :func:`dfa.analysis.fidelity.force_error`) of a wall that can be the best (default 0.5); None: any. A wall
        above it is listed, not chosen: a heavy damper buys K with a wall that feels like a damper. At most 1
        (100 %).
    require_rest : bool, optional
        The best wall must come to rest at its recommended K where any wall within the cap does (default True): a
        wall that buzzes at its K (above its simulated rest limit) is listed, not chosen. False: the stiffest within
        the cap, buzzing or not.
    search : dict, optional
        Keyword arguments of every stiffness search (:func:`~dfa.analysis.limits.kmax.design_answer`'s ``speeds``,
        ``grid``, ``max_samples``); default its own (6 speeds, a 16-point grid).

    Returns
    -------
    TuneResult
        The plain wall first, then the other simulated walls by recommended K, then the screened ones.

    Raises
    ------
    DFAValueError
        For a speed that is not > 0, an empty or invalid list, too many candidates (:data:`MAX_CANDIDATES`) or
        ``evaluate`` < 1.
    DFATypeError
        If ``loop`` is not a :class:`~dfa.model.loop.Loop`.

    See Also
    --------
    design_answer : The largest stiffness of one wall, four ways.
    dfa.export : The best wall for the firmware (``TuneResult.best.recommendation``).
    """
    check_type("loop", loop, Loop, "give Loop(device) or Loop(device, wall)")
    device = loop.search_device("tune")
    check_positive("velocity", velocity, "give the impact speed in m/s (rotary rad/s), e.g. 0.05")
    check_margin(margin)
    if max_force_error is not None:
        fraction = check_positive("max_force_error", max_force_error, "give a fraction of the peak force, e.g. 0.5")
        if not fraction <= 1.0:
            raise DFAValueError(
                f"max_force_error = {max_force_error!r} is invalid: it is a fraction of the ideal spring's peak force, "
                "at most 1 (100 %); give e.g. 0.5 for 50 %, or None for no cap"
            )
    rest = check_bool("require_rest", require_rest, "pass True to choose among walls that rest, False for any")
    if search is not None and not (isinstance(search, dict) and set(search) <= _SEARCH_KEYS):
        raise DFATypeError(
            f"search = {search!r} is invalid: it must be None or a dict of {', '.join(sorted(_SEARCH_KEYS))} "
            "(design_answer's keywords)"
        )
    if not (isinstance(evaluate, int) and evaluate >= 1):
        raise DFAValueError(f"evaluate = {evaluate!r} is invalid: simulate at least 1 wall besides the plain one")
    for name, values in (("dampings", dampings), ("cutoffs", cutoffs), ("delays", delays), ("periods", periods),
                         ("pc_limits", pc_limits)):  # fmt: skip
        if values is not None and not isinstance(values, (list, tuple, np.ndarray)):
            raise DFATypeError(
                f"{name} = {values!r} has type {type(values).__name__}: it must be a list of values (or None for "
                "the default)"
            )
    base = _plain(loop.spring)
    dampings = default_dampings(device, base, velocity) if dampings is None else tuple(dampings)
    cutoffs = default_cutoffs(device) if cutoffs is None else tuple(cutoffs)
    delays = (base.delay,) if delays is None else tuple(delays)
    periods = (device.period,) if periods is None else tuple(periods)
    _check_lists(device, dampings, cutoffs, delays, periods, tuple(pc_limits))
    plain = _candidate(base, base.delay, 0.0, None)
    screened = _screened(device, base, velocity, margin, (periods, delays, dampings, cutoffs), search)
    others = [w for w in screened if not (w.wall.elements == plain.elements and w.device == device)]
    plain_screen = next((w for w in screened if w not in others), None)
    if plain_screen is None:  # the lists leave the plain wall out: screen it too
        lists = ((device.period,), (base.delay,), (0.0,), (None,))
        plain_screen = _screened(device, base, velocity, margin, lists, search)[0]
    loose = None if max_force_error is None else SCREEN_SLACK * max_force_error  # the screen's K is not the K chosen
    others.sort(key=lambda w: (not within_cap(w.screen_force_error, loose), -w.screen))
    with stage("simulating the best walls", 1 + min(evaluate, len(others)) + len(pc_limits), "wall", eta=False):
        first, plain_ans = _simulated(device, plain, velocity, margin, plain_screen, search=search)
        advance(step=1, unit="wall")
        done = [(first, plain_ans)]
        for w in others[:evaluate]:
            done.append(_simulated(w.device, w.wall, velocity, margin, w, search=search))
            advance(step=1, unit="wall")
        faithful = [p for p in done if within_cap(p[0].force_error, max_force_error)] or done[:1]
        best_tuned, best_ans = max(faithful, key=lambda p: p[0].k_recommended or -1.0)
        for limit in pc_limits:
            held = best_ans.wall  # the wall its answer searched (at the placeholder K the search varies)
            wall = Wall(held.stiffness, (*held.elements, PassivityController(force_limit=limit)))
            done.append(_simulated(best_tuned.device, wall, velocity, margin, best_tuned, best_ans, search))
            advance(step=1, unit="wall")
    walls = (first, *_ranked([t for t, _a in done[1:]] + others[evaluate:]))
    cap = None if max_force_error is None else float(max_force_error)
    out = TuneResult(device, float(velocity), float(margin), cap, rest, walls)
    return dataclasses.replace(out, status=_status(out))


def _status(r: TuneResult) -> TuneStatus:
    """tuned: the best wall is not the plain one; plain_best: it is; none: no wall within the cap has a K."""
    i = r.best_index
    return TuneStatus.NONE if i is None else (TuneStatus.PLAIN_BEST if i == 0 else TuneStatus.TUNED)
