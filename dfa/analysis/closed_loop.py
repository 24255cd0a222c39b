"""A log taken with the wall on (issue 45 b): its force column checked against the wall, its contact set beside the
prediction for the identified device.

What the log is taken to be
---------------------------
The device was released into (or thrown at) a virtual wall and logged with the wall on: per sample, the reading
x (on the encoder's lattice, in the wall's frame: the wall at x = 0, occupying x >= 0 as the simulator's, so the
device presses into it moving toward +x) and the force f the wall applied over that sample (the package's
convention: the command of the reading d samples before, as ``dfa simulate --trace`` writes it). The wall's
force is the only force on the device beside its own damping and friction: no hand holds it (cut the log where
the hand lets go). Then f is the force applied, whether in contact or not, and :func:`dfa.analysis.identify.identify`
fits m, b, c to the whole log, impacts included, exactly as to a free-motion log.

What is checked and compared
----------------------------
1. **The wall's law** (:func:`check_wall_force`): the wall given (K, virtual damper B, delay d, one-sided or
   the paper's bilateral spring) is replayed on the logged readings by the simulator's own controller step
   (:func:`dfa.core.wall_kernel.applied_forces`), and the logged force compared with it sample by sample (the
   first d samples left out: they depend on readings before the log). A log of that wall matches to rounding;
   a force column off by more than ½ K Δ at more than 5 % of the samples (:data:`dfa.results.closed_loop.WALL_SHARE`)
   is a ``mismatch`` (another K, B or delay, the wall elsewhere than x = 0, or the force logged when computed
   rather than when applied); the median ratio logged/law in contact reads about K_log/K for a spring.
2. **The logged contact** (:func:`measure_contact`): contact episodes (runs of readings inside, reading >= 0),
   the first contact, the deepest reading, and the outcome by the simulator's own classifier
   (:func:`dfa.core.kernel.classify`: its envelope over eighths of the log and its tail, the last quarter, built
   from the readings' tick middles; rest when the readings are constant over the tail; left when a one-sided
   wall's tail is all outside) and, for a one-sided wall, its contact outcome
   (:func:`dfa.analysis.simulation.contact_codes`: rests, bounces, in_contact ...). Amplitude (±½ tick) and
   frequency are the tail's.
3. **The prediction** (:func:`closed_loop_evidence`): the identified device's exact run with that wall
   (:func:`dfa.analysis.simulation.simulate`), started at the first contact from the fit's state there (the
   fitted state of the segment holding it, advanced by the exact per-sample solution under the logged forces),
   over the rest of the log, measured the same way (the log's readings before the contact kept): ``agrees``
   when the outcome and the contact outcome are the same and, for an oscillation (not a chatter between two
   readings, whose frequency any buzz matches), the amplitudes within ½ tick and
   :data:`dfa.analysis.logged_cycle.AMPLITUDE_TOL` and the frequencies within
   :data:`dfa.analysis.logged_cycle.FREQUENCY_TOL`. The same run over the simulator's default length gives
   its eventual outcome (the log may end before the contact settles).
4. **Across the intervals**: the same run, from the same fitted state, is replayed with b and c at the ends of
   their 95 % intervals and at their values (0 and the value where the log does not bound one), as
   :func:`dfa.analysis.logged_cycle.compare_logged_cycle` replays the paper's spring; a prediction for the
   identified values that differs from the log is ``within_intervals`` when a replay's contact is the logged
   one, and ``differs`` only when none is.

Examples
--------
>>> from dfa.model.device import Device
>>> from dfa.analysis.identify import identify, impact_log
>>> dev = Device(0.05, 0.02, 0.02, 1e-5, 1e-3)
>>> wall = logged_wall(400.0, delay=1, one_sided=True)
>>> log = impact_log(dev, wall, 0.02, 2000)
>>> check_wall_force(log, wall, dev).status.value
'consistent'
>>> e = closed_loop_evidence(identify(log, bootstrap=0), log, wall)
>>> e.logged.outcome.value == e.predicted.outcome.value, e.status.value
(True, 'agrees')
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..checks import check_bool, check_int, check_nonnegative, check_positive, check_type
from ..core import kernel
from ..core.wall_kernel import applied_forces
from ..model.device import Device
from ..model.elements import OneSided
from ..model.log import DeviceLog
from ..model.loop import Loop
from ..model.wall import Wall, WallParams
from ..results.closed_loop import WALL_SHARE, ClosedLoopEvidence, ContactMeasure, WallForceCheck
from ..results.simulation import CONTACTS, OUTCOMES
from ..results.status import ClosedLoopStatus, SimulationOutcome, WallCheckStatus
from .identify import Identification, run_positions
from .logged_cycle import AMPLITUDE_TOL, FREQUENCY_TOL, _span
from .simulation import GROWTH, SETTLE, STABLE_AMPLITUDE, contact_codes, simulate

__all__ = [
    "logged_wall",
    "check_wall_force",
    "measure_contact",
    "closed_loop_evidence",
    "WallForceCheck",
    "ContactMeasure",
    "ClosedLoopEvidence",
]


def logged_wall(stiffness: float, *, damping: float = 0.0, delay: int = 0, one_sided: bool = False) -> Wall:
    """The wall a log was taken with: a spring K, a virtual damper B, a delay d, bilateral or one-sided.

    Parameters
    ----------
    stiffness : float
        K in N/m (rotary N·m/rad), > 0.
    damping : float, optional
        Virtual damping B in N·s/m (rotary N·m·s/rad), >= 0 (default 0: none).
    delay : int, optional
        Computational delay d in whole samples, >= 0 (default 0).
    one_sided : bool, optional
        True: it pushes only while the reading is inside (x >= 0) and never pulls
        (:class:`~dfa.model.elements.OneSided`, surface at 0); False (default): the paper's bilateral spring.

    Returns
    -------
    Wall
        ``Wall.of(K, damping=B, delay=d)``, with a one-sided surface at 0 when asked.

    See Also
    --------
    closed_loop_evidence : The log against this wall.
    dfa.model.wall.Wall.of : The same from every element's value.
    """
    k = check_positive("stiffness", stiffness, "give the wall's K in N/m")
    b = check_nonnegative("damping", damping, "give the virtual damping B in N·s/m, 0 for none")
    d = check_int("delay", delay, 0, "give the computational delay in whole samples, 0 for none")
    side = check_bool("one_sided", one_sided, "pass True for a one-sided wall, False for the bilateral spring")
    wall = Wall.of(k, damping=b, delay=d)
    return Wall(k, (*wall.elements, OneSided(0.0))) if side else wall


def _groups(wall: Wall, device: Device) -> WallParams:
    return wall.params(device.period, device.resolution, rotary=device.rotary)


def _readings(log: DeviceLog, resolution: float) -> np.ndarray:
    """Each row's reading in whole ticks of the wall's frame (x = 0 at the wall)."""
    return np.rint(log.x / resolution)


def check_wall_force(log: DeviceLog, wall: Wall, device: Device) -> WallForceCheck:
    """The log's force column against ``wall``'s force of its readings (module docstring, step 1).

    Parameters
    ----------
    log : DeviceLog
        The log (readings in the wall's frame, the wall's force per sample).
    wall : Wall
        The wall the log is said to be taken with (:func:`logged_wall`).
    device : Device
        The device whose resolution Δ and period T the readings are on (the identified one).

    Returns
    -------
    WallForceCheck
        The mismatch in N, the share within ½ K Δ, the ratio logged/law; ``consistent`` or ``mismatch``.

    Raises
    ------
    DFAValueError, DFATypeError
        A log, wall or device of the wrong type; a log no longer than the wall's delay.

    See Also
    --------
    closed_loop_evidence : The whole comparison.
    """
    lg = check_type("log", log, DeviceLog, "read one with dfa.read_log(path)")
    w = check_type("wall", wall, Wall, "build one with logged_wall(K, damping=B, delay=d)")
    dev = check_type("device", device, Device, "take the identified one, dfa.identify(log).device")
    wp = _groups(w, dev)
    d = wp.delay
    check_int("log samples", lg.samples, d + 1, f"a log longer than the wall's delay of {d} samples")
    n = _readings(lg, dev.resolution)
    phi, energy, control = np.empty(n.size), np.empty(n.size), np.empty(n.size)
    applied_forces(np.ascontiguousarray(n, dtype=float), wp.kernel_table(), True, phi, energy, control)
    step = w.stiffness * dev.resolution
    law, f = phi[d:] * step, lg.f[d:]
    miss = np.abs(f - law)
    within = float(np.mean(miss <= 0.5 * step))
    strong = np.abs(law) >= 2.0 * step
    ratio = float(np.median(f[strong] / law[strong])) if strong.any() else math.nan
    status = WallCheckStatus.CONSISTENT if within >= WALL_SHARE else WallCheckStatus.MISMATCH
    return WallForceCheck(dev, w, int(law.size), step, float(miss.max()), float(np.sqrt(np.mean(miss**2))), within,
                          ratio, status)  # fmt: skip


def measure_contact(readings: np.ndarray, mu: float, wall: WallParams, *, diverged: bool = False) -> ContactMeasure:
    """The contact in ``readings`` (ticks, the wall's frame), classified by the simulator's rules (module docstring).

    Parameters
    ----------
    readings : numpy.ndarray
        One reading per sample, whole ticks; at least 8.
    mu : float
        μ = m/(K T²) of the device at the wall's K: the envelope rule's period 2π√μ (:func:`dfa.core.kernel.classify`).
    wall : WallParams
        The wall's groups (a one-sided wall gets a contact outcome).
    diverged : bool, optional
        The run behind the readings left the simulator's bound (outcome unstable); default False.

    Returns
    -------
    ContactMeasure
        Episodes, first contact, penetration, outcome, contact outcome, amplitude and frequency.

    See Also
    --------
    dfa.core.kernel.classify : The classifier (its rules).
    dfa.analysis.simulation.contact_codes : The one-sided wall's contact outcome.
    """
    n = np.asarray(readings, dtype=float)
    check_int("readings", n.size, 8, "measure at least 8 readings")
    one_sided = wall.group(OneSided) is not None
    engage = OneSided.engage(wall.surface, True) if one_sided else 0.0
    inside = n >= engage
    impacts = int(inside[0]) + int(np.sum(~inside[:-1] & inside[1:]))
    mid = n + 0.5
    tail_len = max(2, n.size // 4)
    tail = np.ascontiguousarray(mid[-tail_len:])
    stats = np.zeros(kernel.NSTATS)
    stats[: kernel.NSEG] = [float(np.max(np.abs(part))) for part in np.array_split(mid, kernel.NSEG)]
    rest = -1
    if diverged:
        stats[kernel.NSEG + 5] = 1.0
    elif one_sided and impacts and not inside[-tail_len:].any():  # left: nothing brings it back (no push)
        stats[kernel.NSEG + 5] = 2.0
    elif np.ptp(tail) == 0.0:
        changed = np.flatnonzero(np.diff(n))
        rest = int(changed[-1]) + 1 if changed.size else 0
    else:
        kernel.tail_stats(tail, tail_len, float(tail.min()), float(tail.max()), stats)
        stats[kernel.NSEG + 5] = -1.0 if one_sided else 0.0
    code, amp, freq, _c, _f = kernel.classify(n.size, n.size, rest, stats, STABLE_AMPLITUDE, GROWTH, SETTLE, True, mu)
    contact = None
    if one_sided:
        idx = contact_codes(np.array([code]), np.array([n[-1]]), np.array([float(n[-tail_len:].min())]), wall)
        contact = CONTACTS[int(idx[0])]
    depth = float(np.max(n[inside]) - engage) if impacts else 0.0
    return ContactMeasure(int(n.size), impacts, int(np.argmax(inside)) if impacts else -1, int(inside.sum()), depth,
                          SimulationOutcome.coerce(OUTCOMES[int(code)], "outcome"), contact, float(amp), float(freq))  # fmt: skip


def _same(a: ContactMeasure, b: ContactMeasure) -> bool:
    """Whether two measures are the same contact (module docstring, step 3)."""
    if a.outcome is not b.outcome or a.contact is not b.contact:
        return False
    if a.outcome is not SimulationOutcome.OSCILLATING:  # a chatter's frequency between two readings is not compared
        return True
    near = abs(a.amplitude - b.amplitude) <= 0.5 + AMPLITUDE_TOL * a.amplitude
    return near and abs(b.frequency / a.frequency - 1.0) <= FREQUENCY_TOL


def _state_at(ident: Identification, lg: DeviceLog, sample: int, base: float) -> tuple[float, float]:
    """The fitted state (ξ ticks in the wall's frame, ξ' ticks per sample) at ``sample``: the state of the fit's
    segment holding it, advanced by the exact per-sample solution (:func:`dfa.core.kernel.step`) under the logged
    forces on the identification's sample grid."""
    dev = ident.device
    states = ident.segment_states
    row = states[max(0, int(np.searchsorted(states[:, 0], sample, side="right")) - 1)]
    x, v = float(row[1]) + base, float(row[2])
    mu, beta, sigma = dev.mass / dev.period**2, dev.damping / dev.period, dev.coulomb / dev.resolution
    k = kernel.sample_constants(mu, beta)
    phis = np.interp(np.arange(int(row[0]), sample), lg.t / dev.period - lg.t[0] / dev.period, lg.f / dev.resolution)
    for phi in phis:
        x, v = kernel.step(x, v, float(phi), mu, sigma, k)[:2]
    return x, v


def closed_loop_evidence(identification: Identification, log: DeviceLog, wall: Wall) -> ClosedLoopEvidence:
    """A log taken with ``wall`` on: its force column checked, its contact beside the prediction (module docstring).

    Parameters
    ----------
    identification : Identification
        The device identified from the log (:func:`dfa.analysis.identify.identify`: the wall's force is the
        applied force, so the fit is the free-motion one).
    log : DeviceLog
        The log, readings in the wall's frame (the wall at x = 0, occupying x >= 0).
    wall : Wall
        The wall the log was taken with (:func:`logged_wall`).

    Returns
    -------
    ClosedLoopEvidence
        The wall check, the logged and the predicted contact, the simulator's eventual outcome, the replays across
        the intervals; ``agrees``, ``within_intervals``, ``differs`` or ``no_contact``.

    Raises
    ------
    DFAValueError, DFATypeError
        Inputs of the wrong type; a log no longer than the wall's delay or shorter than 8 samples; a wall whose
        groups on the identified device a float cannot hold.

    See Also
    --------
    check_wall_force, measure_contact : Its steps.
    dfa.analysis.logged_cycle.compare_logged_cycle : A sustained oscillation against the paper's spring, with
        replays across the intervals.
    """
    ident = check_type("identification", identification, Identification, "identify the log with dfa.identify")
    lg = check_type("log", log, DeviceLog, "read one with dfa.read_log(path)")
    w = check_type("wall", wall, Wall, "build one with logged_wall(K, damping=B, delay=d)")
    dev = ident.device
    check = check_wall_force(lg, w, dev)
    wp = _groups(w, dev)
    mu = dev.params(w.stiffness).mu
    base = float(np.rint(lg.x.min() / dev.resolution))
    n = np.asarray(ident.logged, dtype=float) + base  # on the fit's sample grid (a dropped sample: the one before)
    logged = measure_contact(n, mu, wp)
    if not logged.impacts:
        return ClosedLoopEvidence(dev, w, check, logged, None, None, None, -1, math.nan, ClosedLoopStatus.NO_CONTACT,
                                  (), 0)  # fmt: skip
    start = logged.first_contact
    x0, v0 = _state_at(ident, lg, start, base)
    loop = Loop(dev, w)
    predicted = _predict(loop, n, start, x0, v0, mu, wp)
    eventual = simulate(loop, v0, xi0=x0, record=False)
    replays = []
    for b in _span(ident.damping):
        for c in _span(ident.coulomb):
            other = loop if (b, c) == (dev.damping, dev.coulomb) else Loop(_with(dev, b, c), w)
            m = predicted if other is loop else _predict(other, n, start, x0, v0, mu, wp)
            replays.append((b, c, m.outcome.value, _same(logged, m)))
    matching = sum(r[3] for r in replays)
    if _same(logged, predicted):
        status = ClosedLoopStatus.AGREES
    else:
        status = ClosedLoopStatus.WITHIN_INTERVALS if matching else ClosedLoopStatus.DIFFERS
    return ClosedLoopEvidence(dev, w, check, logged, predicted, eventual.outcome, eventual.contact, start,
                              v0 * dev.resolution / dev.period, status, tuple(replays), int(matching))  # fmt: skip


def _with(dev: Device, damping: float, coulomb: float) -> Device:
    """The device with another b (N·s/m) and c (N)."""
    return dataclasses.replace(dev, damping=damping, coulomb=coulomb)


def _predict(loop: Loop, n: np.ndarray, start: int, x0: float, v0: float, mu: float, wp: WallParams) -> ContactMeasure:
    """The contact of the loop's exact run from (x0 ticks, v0 ticks per sample) at ``start`` over the rest of the
    log, measured with the log's readings ``n`` before it kept."""
    run = simulate(loop, v0, max(1, n.size - start - 1), xi0=x0, record=True)
    xs = run_positions(run)[: n.size - start]
    finite = xs[np.isfinite(xs)]
    return measure_contact(np.concatenate([n[:start], np.floor(finite)]), mu, wp, diverged=finite.size < xs.size)
