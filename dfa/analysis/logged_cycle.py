"""A sustained oscillation in a log, next to the limit cycles predicted for the identified device (issue 29).

A log of the device against a wall of stiffness K may end in a sustained oscillation (a limit cycle, paper
section V). :func:`measure_oscillation` measures it on the readings themselves: over the last quarter of the log,
the amplitude is half the peak-to-peak of the readings in ticks (quantization leaves it uncertain by ±½ tick), the
frequency 2π over the mean spacing of the upward crossings of the centre level, and the oscillation counts as
sustained when it spans at least :data:`FEW_PERIODS` periods with a steady envelope (the peak-to-peak of the
tail's two halves within one tick and :data:`STEADY` of each other).

:func:`compare_logged_cycle` puts it next to what the package predicts for the identified device and that wall:

- the exact simulation (paper eq. 4-5) replayed from the fitted state (position and velocity) of the last
  segment of the identification's fit that starts before the tail, relative to the wall's origin
  (:func:`wall_origin`, from the force column), and from 8 states around it (a quantized loop's cycles can have
  basins smaller than a tick: one start may end in the logged cycle and its neighbour in chatter or growth),
  each with b and c at the ends of their 95 % intervals and at their values (0 and the value where the log
  does not bound them): up to 81 replays;
- the describing function's stable limit cycles of at least :data:`DF_SMALLEST` tick (eq. 36-45, the exact
  zero-order hold) for the identified values.

The verdict rests on the simulation, which is exact: the logged oscillation is a predicted limit cycle when at
least one replay ends in an oscillation of its amplitude (within ½ tick and :data:`AMPLITUDE_TOL`) and frequency
(within :data:`FREQUENCY_TOL`); the result says how many did, and what the others did. Otherwise it is not one
the package predicts for this device and wall (another wall, a delay, a filter, values outside their intervals,
or dynamics the model lacks). A chatter between two readings is not compared.

Examples
--------
>>> import numpy as np
>>> n = np.floor(6.0 * np.sin(np.arange(400) * 0.3))   # readings of a steady cycle of amplitude 6 ticks
>>> m = measure_oscillation(n)
>>> round(m.amplitude, 1), round(m.frequency, 2)        # readings -6 … 5: within ½ tick of 6
(5.5, 0.3)
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..checks import check_positive, check_type
from ..model.log import DeviceLog
from ..model.loop import Loop
from ..results.identify import LoggedCycle as LoggedCycle
from ..results.identify import LoggedOscillation as LoggedOscillation
from ..results.status import LoggedCycleStatus
from .identify import Estimate, Identification

__all__ = [
    "LoggedOscillation",
    "LoggedCycle",
    "measure_oscillation",
    "compare_logged_cycle",
    "wall_origin",
    "FEW_PERIODS",
    "STEADY",
    "AMPLITUDE_TOL",
    "FREQUENCY_TOL",
    "REPLAYS",
]

#: Fewest full periods in the tail for an oscillation to count as sustained.
FEW_PERIODS = 4
#: Largest relative difference of the peak-to-peak of the tail's two halves (beyond one tick) of a steady cycle.
STEADY = 0.2
#: Largest relative difference of the logged and the simulated amplitude (beyond ½ tick) of the same cycle.
AMPLITUDE_TOL = 0.15
#: Largest relative difference of the logged and the simulated frequency of the same cycle.
FREQUENCY_TOL = 0.1
#: Smallest amplitude (ticks) of a describing-function cycle listed (smaller ones are sub-tick artefacts).
DF_SMALLEST = 0.5
#: Samples of each replay.
REPLAY_SAMPLES = 20_000
#: Offsets of the replays' start positions (ticks) and velocities (ticks per sample) from the fitted state.
REPLAY_POSITIONS = (-0.1, 0.0, 0.1)
REPLAY_VELOCITIES = (-0.03, 0.0, 0.03)
#: Replays per pair of (b, c) values (up to 9 pairs: each at its interval's ends and its value).
REPLAYS = len(REPLAY_POSITIONS) * len(REPLAY_VELOCITIES)


def measure_oscillation(readings: ArrayLike) -> LoggedOscillation | None:
    """The sustained oscillation over the last quarter of ``readings`` (ticks), None when there is none.

    Parameters
    ----------
    readings : array_like
        Encoder readings in ticks, one per sample.

    Returns
    -------
    LoggedOscillation or None
        Amplitude (ticks), frequency (rad per sample) and the number of full periods (module docstring); None when
        the tail is at rest or chatters between two readings (less than a tick), holds fewer than
        :data:`FEW_PERIODS` periods or its envelope is not steady.
    """
    n = np.asarray(readings, dtype=float)
    start = len(n) - len(n) // 4
    tail = n[start:] + 0.5  # the middle of each tick
    if len(tail) < 8:
        return None
    first, second = float(np.ptp(tail[: len(tail) // 2])), float(np.ptp(tail[len(tail) // 2 :]))
    if min(first, second) < 2.0 or abs(first - second) > 1.0 + STEADY * max(first, second):  # 1 tick: chatter
        return None
    centre = 0.5 * (tail.max() + tail.min())
    below = tail[:-1] < centre
    up = np.flatnonzero(below & (tail[1:] >= centre))
    if len(up) < FEW_PERIODS + 1:
        return None
    frac = (centre - tail[up]) / (tail[up + 1] - tail[up])  # the crossing between the two samples
    crossings = up + frac
    spacing = float(np.mean(np.diff(crossings)))
    return LoggedOscillation(0.5 * float(np.ptp(tail)), 2.0 * math.pi / spacing, len(up) - 1, int(start))


def _same(logged: LoggedOscillation, outcome: str, amplitude: float, frequency: float) -> bool:
    """Whether a replay ends in the logged cycle (module docstring's tolerances)."""
    return (outcome == "oscillating" and abs(amplitude - logged.amplitude) <= 0.5 + AMPLITUDE_TOL * logged.amplitude
            and abs(frequency / logged.frequency - 1.0) <= FREQUENCY_TOL)  # fmt: skip


def wall_origin(log: DeviceLog, resolution: float, stiffness: float) -> tuple[float, float]:
    """(The wall's origin in ticks above the lowest reading, the spread of its per-sample estimates in ticks): the
    paper's spring (eq. 2) pushes f_h = −KΔ(n_h − n_w + ½), so each sample says n_w = n_h + ½ + f_h/(KΔ); the
    median, and the largest distance of a sample's value from it (0 for a log of exactly that wall)."""
    n = np.rint((log.x - log.x.min()) / resolution)
    each = n + 0.5 + log.f / (stiffness * resolution)
    origin = float(np.median(each))
    return origin, float(np.max(np.abs(each - origin)))


def compare_logged_cycle(identification: Identification, log: DeviceLog, stiffness: float) -> LoggedCycle:
    """The log's sustained oscillation next to the limit cycles predicted for the identified device and a wall.

    Parameters
    ----------
    identification : Identification
        The device identified from the log (:func:`dfa.analysis.identify.identify`).
    log : DeviceLog
        The log (of the device against the wall).
    stiffness : float
        K of the paper's spring the log ran against, N/m (rotary N·m/rad), > 0.

    Returns
    -------
    LoggedCycle
        ``predicted`` when a replay of the exact simulation of the identified device and wall, from a state
        consistent with the log's (module docstring), ends in a sustained oscillation of the logged amplitude and
        frequency; ``not_predicted`` when none does; ``no_oscillation`` when the log ends without a sustained one.

    Raises
    ------
    DFAValueError, DFATypeError
        A stiffness that is not a number > 0; an identification that is not an Identification.

    See Also
    --------
    measure_oscillation : How the oscillation is measured.
    dfa.analysis.cycles.limit_cycles : The describing function's cycles.
    """
    from .cycles import limit_cycles
    from .simulation import OUTCOMES, simulate_batch

    ident = check_type("identification", identification, Identification, "identify the log with dfa.identify")
    lg = check_type("log", log, DeviceLog, "read one with dfa.read_log(path)")
    k = check_positive("stiffness", stiffness, "give the wall's K in N/m")
    dev = ident.device
    logged = measure_oscillation(ident.logged)
    origin, spread = wall_origin(lg, dev.resolution, k)
    if logged is None:
        return LoggedCycle(dev, k, origin, spread, None, (), 0, (), LoggedCycleStatus.NO_OSCILLATION)
    p = dev.params(k)
    df = tuple((c.amplitude, c.frequency) for c in limit_cycles(Loop.dimensionless(p.mu, p.beta, p.sigma), model="zoh").cycles
               if c.stable and c.amplitude >= DF_SMALLEST)  # fmt: skip
    states = ident.segment_states
    row = states[max(0, int(np.searchsorted(states[:, 0], logged.start, side="right")) - 1)]
    b, c, dx, dv = (a.ravel() for a in np.meshgrid(_span(ident.damping), _span(ident.coulomb), REPLAY_POSITIONS,
                                                    REPLAY_VELOCITIES, indexing="ij"))  # fmt: skip
    runs = simulate_batch(p.mu, b / (k * dev.period), c / (k * dev.resolution), row[2] + dv, REPLAY_SAMPLES,
                          xi0=row[1] + dx - origin)  # fmt: skip
    replays = tuple((float(bi), float(ci), OUTCOMES[int(o)], float(a), float(w))
                    for bi, ci, o, a, w in zip(b, c, runs.outcome, runs.amplitude, runs.frequency, strict=True))  # fmt: skip
    matching = sum(_same(logged, *r[2:]) for r in replays)
    status = LoggedCycleStatus.PREDICTED if matching else LoggedCycleStatus.NOT_PREDICTED
    return LoggedCycle(dev, k, origin, spread, logged, replays, matching, df, status)


def _span(e: Estimate) -> list[float]:
    """The values of one estimate the replays take: its interval's ends and its value (0 and the value when the
    log does not bound it), N·s/m or N."""
    ends = [0.0, e.value] if e.low is None or e.high is None else [e.low, e.value, e.high]
    return sorted(set(ends))
