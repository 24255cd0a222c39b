"""The inverse question: for a target stiffness at an impact speed, what must each parameter be?

:func:`requirements` holds everything else fixed and, for each parameter (sample period T, encoder resolution
Δ, Coulomb friction c, viscous damping b, virtual damper B, delay d) and each method that can answer it,
finds the value at which the target K is exactly that method's limit:

- ``criterion``: the passivity criterion (eq. 6, 11, extended to the wall's damper, filter and delay;
  :func:`~dfa.analysis.limits.kmax.criterion_passes`) proves K passive at the speed: a proof;
- ``linear``: K lies in the stable interval from K = 0 of the linear loop without encoder and Coulomb
  friction (:func:`~dfa.analysis.limits.kmax.linear_limit`): necessary for stability, not sufficient;
- ``df`` (asked for: ``methods=(..., "df")``, ``dfa require --describing-function``): K is at most the
  describing function's K_df (:func:`~dfa.analysis.limits.kmax.describing_limit`, the design answer's), a
  first-harmonic prediction. Each value tried is a K search, so it is slower, and found to :data:`DF_RTOL`.

The simulation answers the same question only by a confirmed search per value (seconds each): change the
parameter and run ``dfa stiffness``.

How a value is found: each method's verdict at K is evaluated with the parameter changed and everything else
held. When K holds now, the parameter is moved away (the harmful way) until it fails; when it does not, the
helpful way until it holds; when that way never makes K hold, the other way is searched too (a parameter
that helps one term and costs another: with a virtual damper a longer period T costs the speed term but
shrinks the damper's friction term (1 − a)BΔ/T, which may be what fails). The move doubles or halves (whole
samples for the delay) over a stated range, and the change of verdict is bisected to a relative :data:`RTOL`; the value returned is the last one at which K
holds, so at it the target K is the method's limit (``dfa stiffness`` there reads K). A parameter whose
verdict changes more than once in the range is reported at the change nearest to today's value.

The one-line guidance for a damper that leaves the criterion nothing to prove is :func:`damper_guidance`: the
criterion needs c/Δ > (1 − a)B/T at every K (eq. 11 with the damper's terms), whatever K.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> dev = get_device("delta").device
>>> req = requirements(dev, 1000.0, 0.1)
>>> r = req.find("criterion", "coulomb")
>>> r.status.value, r.bound
('met', 'at_least')
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from typing import Any

from ...checks import check_choice, check_nonnegative, check_positive, check_type
from ...errors import DFAValueError
from ...model.device import Device
from ...model.elements import Damper, Delay
from ...model.wall import Wall
from ...progress import advance, stage
from ...results.require import ALL_METHODS as ALL_METHODS
from ...results.require import PARAMETERS as PARAMETERS
from ...results.require import (
    DamperGuidance as DamperGuidance,
)
from ...results.require import (
    Requirement as Requirement,
)
from ...results.require import (
    Requirements as Requirements,
)
from ...results.status import RequireStatus
from .kmax import criterion_passes, damper_friction_per_damping, describing_limit, linear_limit, max_proven_damping

__all__ = [
    "PARAMETERS",
    "METHODS",
    "ALL_METHODS",
    "DF_RTOL",
    "RTOL",
    "HELPS",
    "DamperGuidance",
    "Requirement",
    "Requirements",
    "damper_guidance",
    "damper_guidance_for",
    "strictest_damper_guidance",
    "requirements",
]

#: The direction of each parameter that helps each method (+1: larger helps). The criterion: eq. 11 with the
#: damper's terms (B costs damping and friction). The linear loop: damping of either kind helps (its stable B
#: form an interval; the bound reported is its lower end when K holds, the least B that stabilises when not).
HELPS: dict[str, dict[str, int]] = {
    "criterion": {"period": -1, "resolution": -1, "coulomb": +1, "damping": +1, "virtual_damping": -1, "delay": -1},
    "linear": {"period": -1, "resolution": -1, "coulomb": +1, "damping": +1, "virtual_damping": +1, "delay": -1},
    "df": {"period": -1, "resolution": -1, "coulomb": +1, "damping": +1, "virtual_damping": +1, "delay": -1},
}
#: The methods of the inverse question: by default the two that evaluate in closed form; ``"df"`` when asked.
METHODS = ("criterion", "linear")
#: Relative resolution of a value found by the describing function (each value tried is a K search).
DF_RTOL = 1e-3
#: Relative resolution of a returned value (bisection on the method's own verdict).
RTOL = 1e-9
#: How far a parameter is moved: by factors of two up to this ratio of today's value (the delay: samples).
RANGE_RATIO = 2.0**20
DELAY_RANGE = 64
#: The describing function's narrower range (each value tried is a K search): factors of two up to 2^8, 8 samples.
DF_RANGE_RATIO = 2.0**8
DF_DELAY_RANGE = 8
#: Parameters the linear loop does not see (it has no encoder and no Coulomb friction).
_LINEAR_BLIND = ("resolution", "coulomb")


def _changed(dev: Device, wall: Wall, name: str, x: float) -> tuple[Device, Wall]:
    """The device and wall with one parameter set to ``x`` (may raise DFAValueError: not representable)."""
    if name in ("period", "resolution", "coulomb", "damping"):
        values: dict[str, Any] = {name: x}
        return dataclasses.replace(dev, **values), wall
    kind: type = Damper if name == "virtual_damping" else Delay
    others = tuple(e for e in wall.elements if not isinstance(e, kind))
    new = kind(int(x)) if kind is Delay else kind(x)
    return dev, Wall(wall.stiffness, others + ((new,) if new.value else ()))


def _verdict(method: str, k: float, v: float) -> Callable[[Device, Wall], bool]:
    """Whether K holds by ``method`` for a device and wall (a configuration that cannot be built does not)."""

    def holds(dev: Device, wall: Wall) -> bool:
        try:
            if method == "criterion":
                return criterion_passes(dev, wall, k, v)
            if method == "df":
                kdf = describing_limit(dev, wall, v).value
                return kdf is not None and k <= kdf
            return k < linear_limit(dev, wall)
        except DFAValueError:
            return False

    return holds


def _current(dev: Device, wall: Wall, name: str) -> float:
    if name == "virtual_damping":
        return wall.damping
    if name == "delay":
        return float(wall.delay)
    return float(getattr(dev, name))


def _scale(dev: Device, k: float, name: str) -> float:
    """A starting value for a parameter that is 0 today: the size at which it meets K (eq. 11's terms)."""
    return {"coulomb": 0.5 * k * dev.resolution, "damping": k * dev.period, "virtual_damping": k * dev.period}.get(
        name, 1.0
    )


def _bisect(ok: Callable[[float], bool], good: float, bad: float, integer: bool, rtol: float = RTOL) -> float:
    """The last value at which ``ok`` holds between ``good`` (holds) and ``bad`` (fails)."""
    while abs(bad - good) > 1 if integer else abs(bad - good) > rtol * max(abs(good), abs(bad)):
        mid = math.floor(0.5 * (good + bad)) if integer else 0.5 * (good + bad)
        if mid in (good, bad):
            break
        good, bad = (mid, bad) if ok(mid) else (good, mid)
    return good


def _steps(x0: float, up: bool, integer: bool, scale: float, short: bool = False) -> list[float]:
    """The values tried from ``x0`` one way: doubling or halving (0 reached at the end going down); ``short``: the
    describing function's narrower range (:data:`DF_RANGE_RATIO`, :data:`DF_DELAY_RANGE`)."""
    if integer:
        top = DF_DELAY_RANGE if short else DELAY_RANGE
        return [float(d) for d in (range(int(x0) + 1, int(x0) + top + 1) if up else range(int(x0) - 1, -1, -1))]
    if not up and x0 == 0.0:
        return []  # already at the floor: nothing below to try
    n = int(math.log2(DF_RANGE_RATIO if short else RANGE_RATIO))
    if x0 == 0.0:  # up from nothing: around the scale at which the parameter meets K
        return [scale * 2.0**i for i in range(-n, n + 1)]
    if up:
        return [x0 * 2.0**i for i in range(1, n + 1)]
    return [x0 * 0.5**i for i in range(1, n + 1)] + [0.0]


def _search(
    ok: Callable[[float], bool], x0: float, up: bool, name: str, scale: float, method: str
) -> tuple[float | None, list[float]]:
    """The value one way from ``x0`` (up: larger) where the verdict ``ok`` changes from today's, bisected to the
    last value that holds; None when it does not change over the range. Also the values tried."""
    integer = name == "delay"
    now = ok(x0)
    prev, tried = x0, []
    for x in _steps(x0, up, integer, scale, short=method == "df"):
        if x == 0.0 and name in ("period", "resolution"):
            break
        tried.append(x)
        if ok(x) != now:
            good, bad = (prev, x) if now else (x, prev)
            return float(_bisect(ok, good, bad, integer, DF_RTOL if method == "df" else RTOL)), tried
        prev = x
    return None, tried


def _one(dev: Device, wall: Wall, method: str, name: str, k: float, v: float) -> Requirement:
    """One parameter by one method (module docstring)."""
    helpful = HELPS[method][name]
    bound = "at_least" if helpful > 0 else "at_most"
    x0 = _current(dev, wall, name)
    if method == "linear" and name in _LINEAR_BLIND:
        return Requirement(method, name, x0, None, bound, RequireStatus.NO_EFFECT, (x0, x0))
    holds = _verdict(method, k, v)

    def ok(x: float) -> bool:
        try:
            return holds(*_changed(dev, wall, name, x))
        except DFAValueError:
            return False

    now = ok(x0)
    go_up = (helpful > 0) != now  # holds now: move the harmful way; else the helpful way
    scale = _scale(dev, k, name)
    value, tried = _search(ok, x0, go_up, name, scale, method)
    if value is None and not now:  # the usual way never helps: the other (a damper's BΔ/T shrinks as T grows)
        value, back = _search(ok, x0, not go_up, name, scale, method)
        tried += back
        if value is not None:
            bound = "at_least" if value > x0 else "at_most"
    searched = (min([x0, *tried]), max([x0, *tried]))
    if value is not None:
        return Requirement(method, name, x0, value, bound, RequireStatus.MET if now else RequireStatus.CHANGE, searched)
    status = RequireStatus.ANY if now else RequireStatus.UNREACHABLE
    return Requirement(method, name, x0, None, bound, status, searched)


def requirements(
    device: Device,
    stiffness: float,
    velocity: float,
    *,
    wall: Wall | None = None,
    methods: tuple[str, ...] = METHODS,
    parameters: tuple[str, ...] = tuple(PARAMETERS),
) -> Requirements:
    """What each parameter must be for a target stiffness at an impact speed, by each method (module docstring).

    Parameters
    ----------
    device : Device
        The physical device.
    stiffness : float
        Target stiffness K in N/m (rotary: N·m/rad), > 0.
    velocity : float
        Impact speed in m/s (rotary: rad/s), >= 0.
    wall : Wall, optional
        The wall's elements held fixed (its stiffness is replaced by ``stiffness``); default the spring.
    methods : tuple of str, optional
        Some of :data:`ALL_METHODS` (default :data:`METHODS`; ``"df"`` adds the describing function, slower).
    parameters : tuple of str, optional
        Some keys of :data:`PARAMETERS` (default all), in that order.

    Returns
    -------
    Requirements

    Raises
    ------
    DFAValueError, DFATypeError
        On a stiffness that is not a finite number > 0, a negative speed, or an unknown method.
    """
    dev = check_type("device", device, Device, "build it with Device(...) or get_device(name).device")
    k = check_positive("stiffness", stiffness, "give the target stiffness K in N/m")
    v = check_nonnegative("velocity", velocity, "give the impact speed in m/s")
    w = Wall(k) if wall is None else check_type("wall", wall, Wall, "build it with Wall.of(...)").with_stiffness(k)
    ms = tuple(check_choice("methods", m, ALL_METHODS) for m in methods)
    names = [n for n in PARAMETERS if n in {check_choice("parameters", p, tuple(PARAMETERS)) for p in parameters}]
    if not names or not ms:
        raise DFAValueError("methods and parameters must each name at least one; give e.g. methods=('criterion',)")
    out = []
    with stage("requirements", len(ms) * len(names), "parameter", eta=False):
        for m in ms:
            uncovered = w.params(dev.period, dev.resolution).not_covered() if m == "criterion" else None
            if uncovered is not None or (m != "criterion" and not w.linear):  # not a linear loop
                out += [Requirement(m, n, _current(dev, w, n), None, "at_least" if HELPS[m][n] > 0 else "at_most",
                                    RequireStatus.NOT_COVERED) for n in names]  # fmt: skip
                advance(step=len(names), unit="parameter")
                continue
            for n in names:
                out.append(_one(dev, w, m, n, k, v))
                advance(unit="parameter")
    met = all(r.status in (RequireStatus.MET, RequireStatus.ANY, RequireStatus.NO_EFFECT) for r in out)
    return Requirements(dev, w, v, tuple(out), RequireStatus.MET if met else RequireStatus.CHANGE)


def damper_guidance_for(device: Device, wall: Wall, velocity: float) -> DamperGuidance | None:
    """:func:`damper_guidance` where it means something: None without a damper, or where no criterion covers the
    wall at all (an amplifier lag, a one-sided wall with a damper: no B would let it prove a K).

    Parameters
    ----------
    device : Device
    wall : Wall
    velocity : float
        Impact speed, m/s (rotary: rad/s), >= 0.

    Returns
    -------
    DamperGuidance or None
    """
    if wall.damping == 0 or wall.params(device.period, device.resolution).not_covered() is not None:
        return None
    return damper_guidance(device, wall, velocity)


def strictest_damper_guidance(
    devices: Sequence[tuple[str, Device]], wall: Wall, velocity: float
) -> tuple[str, DamperGuidance] | None:
    """:func:`damper_guidance_for` of the configuration whose damper bound is the smallest (the criterion's column
    of a Z-width over configurations is their minimum: the first to prove no K limits it), with its name.

    Parameters
    ----------
    devices : sequence of (str, Device)
        Each configuration's name and one-axis device.
    wall : Wall
    velocity : float
        Impact speed, m/s (rotary: rad/s), >= 0.

    Returns
    -------
    (str, DamperGuidance) or None
        None where no configuration has guidance (no damper, or no criterion covers the wall).

    See Also
    --------
    damper_guidance_for : one device's.
    """
    found = [(n, g) for n, d in devices if (g := damper_guidance_for(d, wall, velocity)) is not None]
    return min(found, key=lambda ng: ng[1].max_virtual_damping) if found else None


def damper_guidance(device: Device, wall: Wall, velocity: float) -> DamperGuidance:
    """The one-line guidance for a damper the criterion cannot prove anything with (:class:`DamperGuidance`).

    Parameters
    ----------
    device : Device
    wall : Wall
        Its damper B and velocity filter (pole a = e^{−2π f_c T}; 0 without a filter) are read.
    velocity : float
        Impact speed, m/s (rotary: rad/s), >= 0.

    Returns
    -------
    DamperGuidance

    Examples
    --------
    >>> dev = Device(0.1, 0.005, 0.02, 1e-5, 1e-3)
    >>> g = damper_guidance(dev, Wall.of(1.0, damping=0.5), 0.1)
    >>> g.proves_some_k, round(g.max_virtual_damping, 4)
    (False, 0.1864)
    """
    v = check_nonnegative("velocity", velocity, "give the impact speed in m/s")
    b, c, big_b = device.damping, device.coulomb, wall.damping
    per_b = damper_friction_per_damping(device, wall)  # eq. 11's (1 − a)Δ/T per unit of B
    speed_cost = max(0.0, (big_b - b) * v)  # the friction the speed term needs when B exceeds b
    max_b = max_proven_damping(device, wall, v)
    room = c - speed_cost  # what friction is left for the damper's (1 − a)BΔ/T
    if big_b == 0:
        max_res: float | None = math.inf
    else:
        max_res = room * device.resolution / (per_b * big_b) if room > 0 else None  # (1 − a)BΔ/T = room
    return DamperGuidance(big_b < max_b, max_b, big_b * per_b + speed_cost, max_res)
