"""The grip sweep: how firm a grip the wall needs at its stiffness (paper Table 2; issue 28).

The paper analyses the device with nobody touching it and says a firm grip stabilises the wall while a light one
is the hardest case. A hand that holds the handle moves with it (:meth:`dfa.Device.holding`): its damping b_h
adds to the device's b. :func:`grip_sweep` answers, at the wall's stiffness K and an impact speed V, with the
hand's mass m_h held:

- per method, the least hand damping b_h with which K holds: the criterion (eq. 6 and 11 with b + b_h, a proof)
  and the exact linear bound (necessary for stability, not sufficient). Both come from the inverse question's
  one search (:func:`dfa.analysis.limits.require.requirements` for the device's damping, less the device's own);
- the exact simulator on a scan of grips (b_h = 0 and KT·2^i): the impact at V from ξ0 = 0 at each, and the
  least scanned b_h from which no firmer scanned grip diverges or is undecided.

The hand's mass is not searched: the criterion (eq. 6) does not contain μ, and the exact linear bound falls
slightly as the moving mass grows (the catalogue's Delta with b = 4.8 N·s/m: 29589 N/m at a moving mass of
0.01 kg, 28801 N/m at 10 kg), so no grip is "stable for a hand at least this heavy" by either; the mass is an
input, and the simulated scan uses it.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> e = get_device("phantom")
>>> g = grip_sweep(e.device, e.stiffness, 0.1, hand_mass=0.15, simulate_scan=False)
>>> [(n.method, n.status.value, round(n.hand_damping, 3)) for n in g.needs]
[('criterion', 'at_least', 0.225), ('linear', 'at_least', 0.502)]
"""

from __future__ import annotations

import math

from ...checks import check_bool, check_nonnegative, check_positive, check_type
from ...errors import DFAValueError
from ...model.device import Device
from ...model.hand import Hand
from ...model.loop import Loop
from ...model.wall import Wall
from ...results.grip import GRIP_METHODS as GRIP_METHODS
from ...results.grip import GripNeed as GripNeed
from ...results.grip import GripSweep as GripSweep
from ...results.status import Fails, GripStatus, RequireStatus, SimulationOutcome
from ..simulation import divergence_bound, simulate
from .require import Requirement, requirements

__all__ = ["GRIP_METHODS", "GRIP_SCAN", "GripNeed", "GripSweep", "grip_sweep"]

#: Exponents i of the simulated grips b_h = K T 2^i (with b_h = 0 first).
GRIP_SCAN = tuple(range(-6, 6))


def _need(req: Requirement, own: float) -> GripNeed:
    """A device-damping requirement as a hand damping: what the hand must add to the device's own b."""
    if req.status in (RequireStatus.MET, RequireStatus.ANY):
        return GripNeed(req.method, 0.0, GripStatus.ANY_GRIP, req)
    if req.status is RequireStatus.CHANGE and req.required is not None:
        return GripNeed(req.method, max(0.0, req.required - own), GripStatus.AT_LEAST, req)
    status = GripStatus.NOT_COVERED if req.status is RequireStatus.NOT_COVERED else GripStatus.UNREACHABLE
    return GripNeed(req.method, None, status, req)


def _scan(dev: Device, wall: Wall, v: float, hand_mass: float) -> tuple[tuple[float, ...], tuple[str, ...]]:
    """The impact at V from ξ0 = 0 (a one-sided wall's: after the approach) for each scanned grip (b_h = 0, K T 2^i)."""
    from ..maps import map_start

    dampings = (0.0, *(wall.stiffness * dev.period * 2.0**i for i in GRIP_SCAN))
    wp, xd = wall.params(dev.period, dev.resolution), dev.xi_dot(v)
    outcomes = []
    for b_h in dampings:
        held = dev.holding(Hand(hand_mass, b_h))
        p = held.params(wall.stiffness)
        x0, v0 = map_start(p.mu, xd, False, wp)
        r = simulate(Loop(held, wall), v0, None, xi0=x0, record=False, bound=divergence_bound(x0, v0, p.mu))
        outcomes.append(r.outcome.value)
    return dampings, tuple(outcomes)


#: The outcomes of a scanned grip that is not firm enough: those failing the no-divergence limit
#: (:attr:`SimulationOutcome.fails`) and the undecided.
_NOT_FIRM = SimulationOutcome.failing(Fails.NO_DIVERGENCE) | {SimulationOutcome.UNDECIDED.value}


def _least_safe(dampings: tuple[float, ...], outcomes: tuple[str, ...]) -> float | None:
    """The least scanned b_h from which no firmer scanned grip diverges or is undecided (None if the firmest is)."""
    best = None
    for b_h, o in reversed(list(zip(dampings, outcomes, strict=True))):
        if o in _NOT_FIRM:
            break
        best = b_h
    return best


def grip_sweep(
    device: Device,
    wall: Wall | float,
    velocity: float,
    *,
    hand_mass: float = 0.0,
    simulate_scan: bool = True,
) -> GripSweep:
    """How firm a grip the wall needs at its stiffness and an impact speed (module docstring).

    Parameters
    ----------
    device : Device
        The bare device (a held device is refused: give ``device`` without its hand and ``hand_mass``).
    wall : Wall or float
        The wall with its stiffness K (N/m, rotary N·m/rad), or K for the spring alone.
    velocity : float
        Impact speed V in m/s (rotary rad/s), >= 0.
    hand_mass : float, optional
        The hand's mass m_h in kg (rotary kg·m²), >= 0, held while its damping varies (default 0).
    simulate_scan : bool, optional
        Also simulate the impact at each scanned grip (default True; about 13 runs).

    Returns
    -------
    GripSweep

    Raises
    ------
    DFAValueError, DFATypeError
        On a held device, a negative speed or mass, or a wall that is not a Wall or a stiffness.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    if dev.hand is not None:
        raise DFAValueError(
            f"device = {dev.name!r} already holds {dev.hand.name!r}: give the bare device and hand_mass; the sweep "
            "varies the hand's damping"
        )
    w = wall if isinstance(wall, Wall) else Wall(check_positive("wall", wall, "give the stiffness K in N/m"))
    v = check_nonnegative("velocity", velocity, "give the impact speed in m/s")
    m_h = check_nonnegative("hand_mass", hand_mass, "give the hand's mass in kg (0 for none)")
    held = dev.holding(Hand(m_h)) if m_h > 0.0 else dev
    reqs = requirements(held, w.stiffness, v, wall=w, methods=GRIP_METHODS, parameters=("damping",))
    needs = tuple(_need(r, dev.damping) for r in reqs.requirements)
    if not check_bool("simulate_scan", simulate_scan) or v == 0.0 or not math.isfinite(dev.xi_dot(v)):
        return GripSweep(dev, w, v, m_h, needs)
    dampings, outcomes = _scan(dev, w, v, m_h)
    least = _least_safe(dampings, outcomes)
    return GripSweep(dev, w, v, m_h, needs, dampings, outcomes, least)
