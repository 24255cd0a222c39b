"""Identify a device from its log: mass, damping, Coulomb friction, encoder resolution and sample period.

A log (:class:`dfa.model.log.DeviceLog`) holds, per sample, the encoder reading x_h (a whole number of ticks)
and the force f_h held over the sample. :func:`identify` estimates what every analysis of :mod:`dfa` starts
from:

1. **The grid.** Each step of ``t`` spans a whole number of periods of its median step (within
   :data:`PERIOD_RTOL`, else it is refused): one, several (samples the log dropped: their readings are left out
   of the fit, whose segments restart after the gap) or none (a repeated row, dropped); the sample period T is
   the slope of the times against the sample index, and the jitter of the steps is reported
   (:func:`log_timing`, :class:`Timing`: the model holds the force over equal samples); the resolution Δ is the
   step of the lattice the readings lie on (the smallest gap between distinct readings, refined over the whole
   range; readings off that lattice by more than :data:`GRID_RTOL` are refused). Either may be given instead.
   A log whose numbers the fit's floats cannot hold is refused here, before any work (:func:`log_grid`): readings
   spanning more than :data:`MAX_TICKS` ticks, forces beyond :data:`MAX_FORCE_PER_TICK` per tick, a period
   outside :data:`PERIOD_RANGE`.
2. **A first guess** by equation error: a smoothed second derivative of the readings (Savitzky–Golay) in
   m ẍ + b ẋ + c sgn(ẋ) = f, by non-negative least squares over the samples in motion. Biased (finite
   differences of quantized positions), it only starts the fit.
3. **The output-error fit.** The exact per-sample solution of the simulator (paper eq. 4 driven by the held
   forces, stick-slip included; :func:`dfa.core.open_loop.segments_kernel`) predicts the position at every
   sample; (m, b, c), a force offset f₀ (the force applied is f + f₀) and the start of every segment of
   two time constants m/b, at least :data:`SEGMENT` samples (velocity, position within its first tick:
   multiple shooting, so that a small error
   does not accumulate over the whole log and trap the fit) minimise the distance, in ticks, between the
   prediction and the middle of each logged tick (Levenberg–Marquardt with Marquardt's scaling on the
   block-arrow normal equations: 4 global parameters, 2 per segment, eliminated segment by segment; a
   forward-difference Jacobian, the bounds by projection; it stops when the sum of squares falls by less than
   :data:`FTOL` of itself). Quantization is respected: a reading says the position lies in its
   tick, and the residual of a right model is the position within the tick, about ±½.
4. **The evidence.** A 95 % interval for each estimate: the larger of 1.96 standard errors from the fit's
   Jacobian (widened by the residuals' integrated autocorrelation time, :func:`correlation_time`, the residual
   variance never below quantization's 1/12) and a parametric bootstrap: the identified model's run read by
   encoders whose origin is shifted by a random fraction of a tick (where the true origin lies is what the
   readings do not say), each identified from scratch; the half-width is Student's t quantile × their spread
   about the estimate (:data:`BOOTSTRAP` replicates; their bias included). The Jacobian alone is too narrow:
   the residual is the position within a tick, not independent noise, and on 80 noiseless synthetic logs of
   random devices its intervals held the truth 56 to 95 % of the time, the bootstrapped ones 94 to 100 % on free
   motion (impacts: 78 % for c, with warnings). Residuals beyond quantization are put down to white noise on
   the force column (:func:`_noise`): its level estimated from their sum of squares, its covariance added to the
   Jacobian's (a sandwich), fresh noise of that level on each replicate's force column; with 2 to 5 % noise the
   intervals held the truth in 48 to 50 of 50 logs (``benchmarks/identify_noise_coverage.py``). Noise on the
   readings beyond their tick (an analog sensor, a noisy encoder) changes the residuals independently from one
   sample to the next, where force noise moves them smoothly: its variance is a sixth of the residuals' mean square
   second difference less quantization's 1/12 (:func:`_white`); above :data:`POSITION_NOISE_MIN` tick the fit is
   run again with the segments' starts free of their first reading's tick, the Jacobian's intervals take that white
   variance for quantization's, force noise is estimated beyond it (:data:`NOISE_Z`) and the replicates' readings
   get fresh noise of that level before their encoder; with 2 to 5 ticks the intervals held the truth in 37 to 40
   of 40 logs. Such a fit is poor when its residuals' mean square exceeds :data:`POSITION_MISFIT` times that white
   variance (white noise gives 1; with force noise of :data:`NOISE_MAX` on half a tick, about 90 on the tests'
   logs): a misfit's jumps, a
   diverging log's with force noise, read as noise on the readings, which would otherwise absorb it. Without a
   reversal c and f₀ get no interval (only c − f₀ is seen); with fewer than :data:`FEW_MOVING` samples in
   motion no estimate does (a device that rests fits many devices). Then the share of samples whose predicted
   tick is within one of the logged one, and warnings when the log does not excite a parameter
   (:class:`IdentifyWarning`).

Examples
--------
>>> import numpy as np
>>> from dfa.model.device import Device
>>> dev = Device(0.1, 0.5, 0.2, 1e-5, 1e-3)
>>> t = np.arange(3000) * 1e-3
>>> log = synthetic_log(dev, 2.0 * np.sign(np.sin(2 * np.pi * 2.0 * t)) + 1.0 * np.sin(2 * np.pi * 7.0 * t))
>>> r = identify(log)
>>> [round(v, 2) for v in (r.mass.value, r.damping.value, r.coulomb.value)]
[0.1, 0.5, 0.2]
>>> r.status.value, r.fit.within_one_tick > 0.99
('ok', True)
"""

from __future__ import annotations

import math
import sys
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .._parallel import new_bar
from ..checks import check_bool, check_int, check_nonnegative, check_positive, check_real, check_type, format_value
from ..core.open_loop import block_normal, open_loop_kernel, segments_jacobian, segments_kernel
from ..errors import DFAValueError
from ..model.device import Device, device_units
from ..model.log import MIN_SAMPLES, DeviceLog, LogError, check_rows
from ..model.loop import Loop
from ..model.wall import Wall
from ..results.identify import FEW_MOVING as FEW_MOVING
from ..results.identify import FRICTION_SHARE as FRICTION_SHARE
from ..results.identify import POSITION_MISFIT as POSITION_MISFIT
from ..results.identify import Estimate as Estimate
from ..results.identify import FitQuality as FitQuality
from ..results.identify import Identification as Identification
from ..results.identify import PeriodEffect as PeriodEffect
from ..results.identify import Timing as Timing
from ..results.identify import Undetermined
from ..results.limits import KMaxResult
from ..results.simulation import SimulationResult
from ..results.status import IdentifyStatus, IdentifyWarning

__all__ = [
    "Estimate",
    "FitQuality",
    "Identification",
    "identify",
    "synthetic_log",
    "impact_log",
    "run_positions",
    "estimate_period",
    "log_timing",
    "period_effect",
    "Timing",
    "PeriodEffect",
    "PERIOD_EFFECT_GRID",
    "correlation_time",
    "estimate_resolution",
    "log_grid",
    "PERIOD_RTOL",
    "BOOTSTRAP",
    "MAX_BOOTSTRAP",
    "SEGMENT",
    "SEGMENT_MAX",
    "GRID_RTOL",
    "MAX_TICKS",
    "MAX_FORCE_PER_TICK",
    "PERIOD_RANGE",
]

#: Largest distance of a step of the times from a whole number of periods, in periods: a step within it spans
#: that many samples (a gap of dropped samples, or a repeated one), a step beyond it is refused (it cannot say how
#: many samples it spans). The jitter within it is reported (:class:`Timing`).
PERIOD_RTOL = 0.25
#: Largest relative difference of a given period from the median step of the log's times.
GIVEN_PERIOD_RTOL = 0.01
#: Largest distance of a reading from the lattice of the estimated resolution, in ticks.
GRID_RTOL = 1e-2
#: The same with the resolution given (readings written with few digits are rounded to their tick).
GIVEN_GRID_RTOL = 0.25
#: Speed (ticks per sample, smoothed) above which a sample counts as moving, for the first guess.
MOVING = 0.2
#: Relative step of the fit's forward-difference Jacobian: √ε, scipy's default.
FD_STEP = math.sqrt(np.finfo(float).eps)
#: Relative decrease of the sum of squares below which the fit stops (scipy's ``ftol`` is 1e-8: its fit stopped
#: where the last bits of the arithmetic moved b of the example impulse log by 3e-4 of its value).
FTOL = 1e-12
#: Most Jacobians of one fit (a fit of the example logs takes 10 to 40).
MAX_ITERATIONS = 200
#: Starting Levenberg–Marquardt damping λ (relative to Marquardt's scaling) and the largest tried before the fit
#: stops for want of a step that lowers its cost.
LM_DAMPING = 1e-3
LM_MAX_DAMPING = 1e12
#: Smallest Marquardt scale of a segment's start parameter, relative to the largest of its kind (:func:`_marquardt_scale`).
LOCAL_FLOOR = 1e-6
#: Fewest samples per segment of the multiple-shooting fit (each segment starts from its own fitted state);
#: segments span two time constants m/b of the first guess when that is longer (:func:`_segments`).
SEGMENT = 200
#: Most samples per segment: a light-damped device's two time constants can span the whole log, and one long
#: segment lets noise on the force column accumulate (a 20 s Phantom log with 1 % force noise: b 33 % off as one
#: segment, 12 % in segments of 1000).
SEGMENT_MAX = 1000
#: Variance of the residual of a right model, ticks²: the position within its tick, uniform over [−½, ½). The
#: residual variance used for the intervals is at least this (a run mostly at rest fits its rest exactly).
QUANTIZATION_VARIANCE = 1.0 / 12.0
#: Relative half-width of an interval (±1.96 standard errors) above which an estimate is called poorly determined.
LOOSE = 0.25
#: |correlation| of the damping and Coulomb estimates above which they are called not separated.
CONFOUNDED = 0.95
#: Range of μ = m/T² (at K = 1 N/m) the fit's prediction clamps its log μ to: 1e-13 to 1e26, far beyond any
#: device, so that a fit that runs away stays finite (μ = 0 would divide by zero).
LOG_MU = (-30.0, 60.0)
#: Share of samples predicted within one tick below which the fit is called poor, unless noise on the force column
#: of at most :data:`NOISE_MAX` of its spread explains the residuals.
POOR_FIT = 0.9
#: Largest force noise (standard deviation, relative to the logged force's) that a fit's misfit is put down to: a
#: model that needs more to explain the log does not reproduce it (a force column of the wrong sign needs 100 % and
#: more; 5 % noise, 5 %).
NOISE_MAX = 0.25
#: Mean square residual, in units of quantization's 1/12, up to which the residuals count as quantization alone (no
#: force noise is estimated: the clean logs' intervals are those of the encoder; a clean log's is 1.0 ± a few %).
NOISE_FLOOR = 1.5
#: Standard deviation of white noise on the readings beyond their quantization, ticks, above which the log is taken to
#: carry position noise (:func:`_white`): a clean log's residual second differences give at most 1/6 tick²
#: (quantization alone), so its level reads 0 to 0.29 ticks; below this, quantization's 1/12 stands for the readings.
POSITION_NOISE_MIN = 0.5
#: Standard errors by which the residuals' mean square must exceed the white variance of noisy readings for force
#: noise to be estimated beside the position noise (:func:`_noise`): noise on the readings hides force noise below it.
NOISE_Z = 2.0
#: Most ticks of the resolution the readings may span: a float holds a position there to 1e-4 of a tick (the
#: fit's residuals are fractions of a tick); beyond, the resolution is not that of the readings' unit.
MAX_TICKS = 1e12
#: Largest |f|/Δ, the force per tick the fit works in (N/m; rotary N·m/rad): beyond, its sums of squares
#: overflow a float (a force of 1e308 N, or readings of 1e-315 m with their resolution, gave a traceback).
MAX_FORCE_PER_TICK = 1e300
#: The sample periods T (s) the fit converts its mass back with, m = μ T²: for every μ it reaches (e^LOG_MU), m is
#: a normal float from the first to the second (a log with time steps of 1e300 s gave m = inf).
PERIOD_RANGE = (
    math.sqrt(sys.float_info.min / math.exp(LOG_MU[0])),
    math.sqrt(sys.float_info.max / math.exp(LOG_MU[1])),
)


def _sample_steps(times: np.ndarray, source: str) -> np.ndarray:
    """The whole number of periods each step of ``times`` spans (0: a repeated sample, 2 or more: dropped ones),
    against the median of the positive steps; a step off a whole number by more than :data:`PERIOD_RTOL` is
    refused, naming its row (it cannot say how many samples it spans)."""
    steps = np.diff(times)
    step = float(np.median(steps[steps > 0.0]))
    k = np.rint(steps / step)
    jump = np.abs(steps / step - k) > PERIOD_RTOL
    if jump.any():
        i = int(np.flatnonzero(jump)[0]) + 1
        raise LogError(
            f"{source}: the sample period is not uniform: row {i + 2} (t = {float(times[i]):.9g} s) comes "
            f"{float(steps[i - 1]):.6g} s after the row before it, {float(steps[i - 1]) / step:.3g} of the median "
            f"step {step:.6g} s, not a whole number of samples; cut the log there and identify the parts, or log "
            "equal samples"
        )
    return k.astype(np.int64)


def log_timing(t: ArrayLike, source: str = "log", period: float | None = None) -> tuple[Timing, np.ndarray]:
    """The log's timing and each kept row's sample index (step 1 of the module docstring).

    Each step of the times spans a whole number of periods (within :data:`PERIOD_RTOL`): one, several (the log
    dropped samples between the two rows) or none (the row repeats the sample before it, and is dropped). T is
    the slope of the kept rows' times against their sample index (rounded times, 3 kHz written to the µs, lie on
    that line within their rounding), or ``period`` when given; the jitter is the spread of the steps of one
    sample.

    Parameters
    ----------
    t : array_like
        The times, s, never decreasing.
    source : str, optional
        The log's name, for messages.
    period : float, optional
        T when given, s.

    Returns
    -------
    tuple of (Timing, ndarray of int)
        The timing, and the sample index of each row (-1 for a repeated row, which the fit drops).

    Examples
    --------
    >>> tm, index = log_timing([0.0, 1e-3, 2e-3, 2e-3, 4e-3, 5e-3])
    >>> round(tm.period, 12), tm.dropped, tm.repeated, index.tolist()
    (0.001, 1, 1, [0, 1, 2, -1, 4, 5])
    """
    times = np.asarray(t, dtype=float)
    k = _sample_steps(times, source)
    index = np.concatenate([[0], np.cumsum(k)])
    kept = np.concatenate([[True], k > 0])
    h = index[kept].astype(float)
    slope = float(np.polyfit(h, times[kept] - times[0], 1)[0]) if period is None else float(period)
    one = np.diff(times)[k == 1]
    jitter = float(np.std(one)) if one.size else 0.0
    worst = float(np.max(np.abs(one - slope))) if one.size else 0.0
    longest = float(np.max(one)) if one.size else slope
    timing = Timing(slope, jitter, worst, longest, int(np.sum(np.maximum(k - 1, 0))), int(np.sum(k > 1)),
                    int(np.sum(k == 0)))  # fmt: skip
    return timing, np.where(kept, index, -1)


def estimate_period(t: ArrayLike, source: str = "log") -> float:
    """The sample period T (s): the slope of the straight line through the times against their sample index.

    Times rounded when they were written (3 kHz logged to the µs: steps of 333 and 334 µs) lie on that line to
    within their rounding; a step that spans several periods counts them (dropped samples,
    :func:`log_timing`); a step off a whole number of periods by more than :data:`PERIOD_RTOL` is refused,
    naming the row.

    Examples
    --------
    >>> round(estimate_period([0.0, 1e-3, 2e-3, 3e-3]), 15)
    0.001
    >>> round(estimate_period(np.round(np.arange(3000) / 3000.0, 6)) * 3000.0, 5)   # µs rounding at 3 kHz
    1.0
    """
    return log_timing(t, source)[0].period


def estimate_resolution(x: ArrayLike, source: str = "log") -> float:
    """The encoder resolution Δ: the step of the lattice the readings lie on (module docstring).

    Examples
    --------
    >>> estimate_resolution([0.0, 2e-5, 1e-5, 5e-5, 3e-5])
    1e-05
    """
    u = np.unique(np.asarray(x, dtype=float))
    if u.size < 3:
        raise LogError(
            f"{source}: the readings take {u.size} value(s): too few to tell the encoder's resolution; give it "
            "(--resolution), or log a run that moves over several ticks"
        )
    gaps = np.diff(u)
    ticks = np.rint(gaps / gaps.min())
    off = float(np.max(np.abs(gaps / gaps.min() - ticks)))
    if off > GRID_RTOL:
        raise LogError(
            f"{source}: the readings do not lie on one grid (a gap is {off:.3g} ticks off the smallest gap "
            f"{format_value(float(gaps.min()))}): are they quantized encoder readings? give the resolution "
            "(--resolution)"
        )
    return float((u[-1] - u[0]) / ticks.sum())


def _window(n: int) -> int:
    """Samples (odd) of the Savitzky–Golay window that smooths the readings: up to 31, at most a third of the log."""
    return max(5, min(31, (n // 3) | 1))


def _first_guess(v: np.ndarray, a: np.ndarray, phi: np.ndarray) -> tuple[float, float, float]:
    """(μ, β, σ) by equation error on the smoothed velocity ``v`` and acceleration ``a`` of the readings (only a
    start for the output-error fit)."""
    moving = np.abs(v) > MOVING
    if moving.sum() < 10:
        raise LogError(
            "the device barely moves in this log (fewer than 10 samples faster than "
            f"{MOVING:g} ticks per sample): nothing to identify; log a run with motion"
        )
    if not np.any(phi != 0.0):
        raise LogError(
            "the force column is zero throughout while the device moves: the log does not say what drives it; "
            "log the force commanded (or the wall's force) in column f"
        )
    rows = np.column_stack([a[moving], v[moving], np.sign(v[moving])])
    mu, beta, sigma = _nonnegative_least_squares(rows, phi[moving])
    scale = float(np.median(np.abs(phi[moving])) / max(np.median(np.abs(a[moving])), 1e-12))
    mu = mu if mu > 0.0 else scale
    if not (math.isfinite(mu) and mu > 0.0):
        mu = float(np.max(np.abs(phi))) or 1.0  # no acceleration seen at all: any start; the fit moves it
    return float(mu), float(beta), float(sigma)


def _nonnegative_least_squares(rows: np.ndarray, y: np.ndarray) -> np.ndarray:
    """argmin ‖rows x − y‖ over x >= 0 for a few columns: the least squares on each set of free columns (the
    others 0) whose solution is >= 0, the one of least residual (the minimum's own set is among them).

    ``scipy.optimize.nnls`` solves the same problem; importing scipy.optimize costs about 0.3 s of `dfa identify`,
    which needs nothing else from it (tests/test_identify_inputs.py checks the two agree)."""
    m, q = np.einsum("ni,nj->ij", rows, rows), np.einsum("ni,n->i", rows, y)
    best, low = np.zeros(rows.shape[1]), 0.0
    for mask in range(1, 2 ** rows.shape[1]):
        free = np.array([mask >> i & 1 for i in range(rows.shape[1])], dtype=bool)
        x = np.zeros(rows.shape[1])
        x[free] = np.linalg.lstsq(m[np.ix_(free, free)], q[free], rcond=None)[0]
        cost = float(x @ m @ x - 2.0 * q @ x)
        if np.all(x >= 0.0) and cost < low:
            best, low = x, cost
    return best


def _segments(n: int, mu: float, beta: float) -> np.ndarray:
    """Start of each segment of the multiple-shooting fit: segments of twice the first guess's time constant
    μ/β (damping shows over a time constant), at least :data:`SEGMENT` and at most :data:`SEGMENT_MAX` samples,
    equal (the last one longer)."""
    length = SEGMENT if beta <= 0.0 else max(SEGMENT, min(n, SEGMENT_MAX, int(2.0 * mu / beta)))
    k = max(1, n // length)
    return (np.arange(k) * (n // k)).astype(np.int64)


def _derivatives(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Smoothed velocity and acceleration of the readings ``n`` (ticks per sample, per sample²)."""
    return _savgol(n, 1), _savgol(n, 2)


def _savgol(n: np.ndarray, deriv: int) -> np.ndarray:
    """The ``deriv``-th derivative (per sample^deriv) of the cubic Savitzky–Golay smoothing of ``n`` over
    :func:`_window` samples: in the interior the least-squares cubic of the window about each sample; the first
    and last half-windows from the cubic of the first and last window (what ``scipy.signal.savgol_filter(n,
    window, 3, deriv)`` computes in its default mode ``interp``, to rounding; importing scipy.signal costs about
    0.6 s of ``dfa identify``, which needs nothing else from it: tests/test_identify_inputs.py checks the two
    agree)."""
    x = np.asarray(n, dtype=float)
    size = _window(len(x))
    half = size // 2
    pos = np.arange(size, dtype=float) - half  # positions within a window, about its middle
    power = np.arange(4)
    vander = pos[:, None] ** power  # the cubic's basis over one window
    fit = np.linalg.pinv(vander)  # 4 × size: the window's data to the cubic's coefficients
    at = np.zeros((size, 4))  # the deriv-th derivative of each basis power at each position
    k = power >= deriv
    fall = np.array([math.perm(int(p), deriv) for p in power[k]], dtype=float)
    at[:, k] = fall * pos[:, None] ** (power[k] - deriv)
    weights = at @ fit  # row i: the window's data to the derivative at its position i
    out = np.empty_like(x)
    out[half : len(x) - half] = np.convolve(x, weights[half][::-1], mode="valid")
    out[:half] = weights[:half] @ x[:size]
    out[len(x) - half :] = weights[size - half :] @ x[len(x) - size :]
    return out


class _Fit(NamedTuple):
    """A converged fit: θ (``x``), the residuals (ticks), the Jacobian's global columns (n × 4) and each sample's
    derivatives by its own segment's start position and velocity (n × 2)."""

    x: np.ndarray
    fun: np.ndarray
    glob: np.ndarray
    local: np.ndarray


def _fit(n: np.ndarray, phi: np.ndarray, w: np.ndarray, noisy: bool = False) -> tuple[_Fit, np.ndarray]:
    """The output-error fit (step 3 of the module docstring): the least-squares result (its ``x`` is
    θ = (log μ, β, σ, φ₀, the segments' start positions within their tick, their start velocities)) and the
    segments' starts.

    Multiple shooting: each segment (:func:`_segments`) starts from its own state (its position within the
    first tick and its velocity, fitted), so that an error of the start does not carry over the whole log.
    ``w`` weighs each sample's residual (0: a sample the log dropped); each segment starts at a logged sample, and
    a new one after each gap (the force over a dropped sample is not known, and what it did is the new start's).
    ``noisy``: the readings carry noise beyond their tick (:func:`_white`), so a segment's start is not within its
    first reading's tick: it starts from the smoothed readings, unbounded.
    """
    v, a = _derivatives(n)
    mu, beta, sigma = _first_guess(v, a, phi)
    starts = _segments(len(n), mu, beta)
    if not w.all():
        logged = np.flatnonzero(w)
        after = np.flatnonzero((w[1:] > 0) & (w[:-1] == 0)) + 1
        starts = np.unique(np.r_[logged[np.searchsorted(logged, starts).clip(max=logged.size - 1)], after])
    pos = _smoothed(n)[starts] - n[starts] + 0.5 if noisy else np.full(len(starts), 0.5)
    theta0 = np.concatenate([[math.log(mu), beta, sigma, 0.0], pos, v[starts]])
    return _solve(n, phi, w, starts, theta0, noisy), starts


def _smoothed(n: np.ndarray) -> np.ndarray:
    """The readings ``n`` smoothed (Savitzky–Golay, :func:`_savgol`), ticks."""
    return _savgol(n, 0)


def _fit_readings(n: np.ndarray, phi: np.ndarray, w: np.ndarray) -> tuple[_Fit, np.ndarray, float]:
    """The fit (:func:`_fit`), its segments' starts and the noise on the readings beyond their quantization (ticks,
    0 when none: :func:`_white`); refitted with the segments' starts free of their first tick when there is."""
    best, starts = _fit(n, phi, w)
    position = math.sqrt(max(0.0, _white(best.fun, w, starts) - QUANTIZATION_VARIANCE))
    if position <= POSITION_NOISE_MIN:
        return best, starts, 0.0
    best, starts = _fit(n, phi, w, noisy=True)
    return best, starts, math.sqrt(max(0.0, _white(best.fun, w, starts) - QUANTIZATION_VARIANCE))


def _white(r: np.ndarray, w: np.ndarray, starts: np.ndarray) -> float:
    """Variance (ticks²) of the white part of the residuals ``r``: a sixth of the mean square of their second
    differences over three successive logged samples of a segment.

    White noise of variance s² on the readings gives second differences of mean square 6 s², and the reading's
    quantization 1/12 more to s² (a noisy position read by an encoder is off its tick by a uniform amount). What
    moves the residuals smoothly hardly shows: a model error or noise on the force column changes them through the
    device's two integrations (5 % force noise on the example device: 0.007 tick per sample²; a force column of the
    wrong sign, 0.02). A clean log's quantization gives at most 1 per second difference (a wrap of the tick every
    other sample), 1/6 here, below :data:`POSITION_NOISE_MIN` once quantization's 1/12 is taken off."""
    ok = (w[2:] > 0.0) & (w[1:-1] > 0.0) & (w[:-2] > 0.0)
    first = np.r_[starts[1:] - 2, starts[1:] - 1]
    ok[first[(first >= 0) & (first < ok.size)]] = False  # a segment's first residuals do not follow the ones before
    d = np.diff(r, 2)[ok]
    return float(np.einsum("i,i->", d, d)) / (6.0 * d.size) if d.size else 0.0


def _predict(theta: np.ndarray, n: np.ndarray, phi: np.ndarray, starts: np.ndarray, into: np.ndarray) -> np.ndarray:
    """Positions (ticks) of every segment run from its start in θ (:func:`_fit`), written into ``into``."""
    j = len(starts)
    mu = math.exp(min(max(theta[0], LOG_MU[0]), LOG_MU[1]))  # a fit that runs away stays finite
    segments_kernel(n[starts] + theta[4 : 4 + j], theta[4 + j :].copy(), starts, phi + theta[3], mu, theta[1],
                    theta[2], into)  # fmt: skip
    return into


def _solve(
    n: np.ndarray, phi: np.ndarray, w: np.ndarray, starts: np.ndarray, theta0: np.ndarray, noisy: bool = False
) -> _Fit:
    """Least squares of the segments' prediction against the middles of the logged ticks, from ``theta0``:
    Levenberg–Marquardt on the block-arrow normal equations (:func:`_lm_step`), bounds by projection (a segment's
    start within its first tick, unless the readings are ``noisy``)."""
    j = len(starts)
    lo = np.concatenate([[-np.inf, 0.0, 0.0, -np.inf], np.full(j, -np.inf if noisy else 0.0), np.full(j, -np.inf)])
    hi = np.concatenate([[np.inf] * 4, np.full(j, np.inf if noisy else 1.0), np.full(j, np.inf)])
    seg = _segment_of(starts, len(n))
    theta = np.clip(theta0, lo, hi)
    r = _residual(theta, n, phi, w, starts, np.empty(len(n)))
    cost, lam, scale = _sum_squares(r), LM_DAMPING, np.zeros(len(theta))
    for _ in range(MAX_ITERATIONS):
        jac = _jacobian(theta, r, n, phi, w, starts, seg, lo, hi)
        blocks = _normal_blocks(jac, r, starts)
        scale = np.maximum(scale, _marquardt_scale(blocks))
        grad = np.concatenate([blocks[3], blocks[4][:, 0], blocks[4][:, 1]])
        free = ~(((theta <= lo) & (grad > 0.0)) | ((theta >= hi) & (grad < 0.0)))
        while True:
            trial = np.clip(theta + _lm_step(blocks, scale, lam, free), lo, hi)
            r_new = _residual(trial, n, phi, w, starts, np.empty(len(n)))
            cost_new = _sum_squares(r_new)
            if cost_new < cost or lam > LM_MAX_DAMPING:
                break
            lam *= 4.0
        if not cost_new < cost:
            break  # no step along the gradient lowers the cost: a minimum to the Jacobian's precision
        done = cost - cost_new <= FTOL * cost
        theta, r, cost, lam = trial, r_new, cost_new, max(lam / 3.0, LM_DAMPING * 1e-6)
        if done:
            break
    jac = _jacobian(theta, r, n, phi, w, starts, seg, lo, hi)
    return _Fit(theta, r, jac[:, :4], jac[:, 4:])


def _residual(
    theta: np.ndarray, n: np.ndarray, phi: np.ndarray, w: np.ndarray, starts: np.ndarray, into: np.ndarray
) -> np.ndarray:
    """The weighted distance (ticks) of the segments' prediction from the middle of each logged tick."""
    return (_predict(theta, n, phi, starts, into) - (n + 0.5)) * w


def _sum_squares(r: np.ndarray) -> float:
    """Σ r², without BLAS (its threads wake for a long vector's dot, milliseconds on a loaded machine)."""
    return float(np.einsum("i,i->", r, r))


def _jacobian(
    theta: np.ndarray, r: np.ndarray, n: np.ndarray, phi: np.ndarray, w: np.ndarray, starts: np.ndarray,
    seg: np.ndarray, lo: np.ndarray, hi: np.ndarray,
) -> np.ndarray:  # fmt: skip
    """Forward-difference Jacobian of the residuals ``r`` at θ: the columns of the 4 global parameters
    and each sample's derivatives by its own segment's start position and velocity (n × 2; the segments' starts
    are moved together, as each sample depends on its own segment's only). Steps √ε max(1, |θ|), reversed where
    a bound is in the way (scipy's ``approx_derivative``). The six moved predictions run in one compiled call
    (:func:`dfa.core.open_loop.segments_jacobian`), each as :func:`_predict` runs it: the n × 6 columns."""
    j = len(starts)
    h = FD_STEP * np.where(theta >= 0.0, 1.0, -1.0) * np.maximum(1.0, np.abs(theta))
    h = np.where((theta + h > hi) | (theta + h < lo), -h, h)
    h = (theta + h) - theta
    moved = np.tile(theta, (6, 1))
    for k, part in enumerate((slice(0, 1), slice(1, 2), slice(2, 3), slice(3, 4), slice(4, 4 + j), slice(4 + j, None))):
        moved[k, part] += h[part]
    params = np.column_stack([moved[:, 3], [math.exp(min(max(float(t0), LOG_MU[0]), LOG_MU[1])) for t0 in moved[:, 0]],
                              moved[:, 1], moved[:, 2]])  # fmt: skip
    steps = np.vstack([np.repeat(h[:4, None], j, axis=1), h[None, 4 : 4 + j], h[None, 4 + j :]])
    out = np.empty((len(n), 6))
    segments_jacobian(n[starts] + moved[:, 4 : 4 + j], np.ascontiguousarray(moved[:, 4 + j :]), starts, phi, params,
                      n + 0.5, w, r, steps, out)  # fmt: skip
    return out


def _normal_blocks(jac: np.ndarray, r: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, ...]:
    """The normal equations JᵀJ, Jᵀr in blocks: (GᵀG 4 × 4, per segment Gₖᵀ Lₖ 4 × 2 and Lₖᵀ Lₖ 2 × 2, Gᵀr,
    per segment Lₖᵀ r); G the global columns of ``jac`` (:func:`_jacobian`), Lₖ the segment's own two (summed in one compiled pass,
    :func:`dfa.core.open_loop.block_normal`)."""
    j = len(starts)
    a, b, c = np.empty((4, 4)), np.empty((j, 4, 2)), np.empty((j, 2, 2))
    gr, lr = np.empty(4), np.empty((j, 2))
    block_normal(jac, r, starts, a, b, c, gr, lr)
    return a, b, c, gr, lr


def _marquardt_scale(blocks: tuple[np.ndarray, ...]) -> np.ndarray:
    """The diagonal of JᵀJ, each segment's start position and velocity at least :data:`LOCAL_FLOOR` of the largest
    of its kind: a segment that starts at rest (its velocity exactly 0, where the prediction has a kink) would
    otherwise get a scale near 0 and every step along it."""
    c = blocks[2]
    p, v = c[:, 0, 0], c[:, 1, 1]
    return np.concatenate(
        [np.diag(blocks[0]), np.maximum(p, LOCAL_FLOOR * p.max()), np.maximum(v, LOCAL_FLOOR * v.max())]
    )


def _lm_step(blocks: tuple[np.ndarray, ...], scale: np.ndarray, lam: float, free: np.ndarray) -> np.ndarray:
    """The Levenberg–Marquardt step δ of (JᵀJ + λ D) δ = −Jᵀr (D: the largest diagonal of JᵀJ seen, Marquardt's
    scaling), the parameters not ``free`` held (a bound the gradient pushes against): the segments' 2 × 2 blocks
    eliminated (Schur complement), a 4 × 4 system left."""
    a, b, c, gg, gl = blocks
    j = len(c)
    d = 1.0 / np.sqrt(np.maximum(scale, 1e-300))
    dg, dl = d[:4], np.column_stack([d[4 : 4 + j], d[4 + j :]])
    fg, fl = free[:4].astype(float), np.column_stack([free[4 : 4 + j], free[4 + j :]]).astype(float)
    sg, sl = dg * fg, dl * fl  # scaled, frozen ones zeroed
    a_s = a * np.outer(sg, sg) + np.diag(lam + (1.0 - fg))
    b_s = b * sg[None, :, None] * sl[:, None, :]
    c_s = c * sl[:, :, None] * sl[:, None, :]
    c_s[:, 0, 0] += lam + 1.0 - fl[:, 0]
    c_s[:, 1, 1] += lam + 1.0 - fl[:, 1]
    g_s, l_s = gg * sg, gl * sl
    det = c_s[:, 0, 0] * c_s[:, 1, 1] - c_s[:, 0, 1] * c_s[:, 1, 0]
    c_inv = np.stack([np.stack([c_s[:, 1, 1], -c_s[:, 0, 1]], 1), np.stack([-c_s[:, 1, 0], c_s[:, 0, 0]], 1)], 1)
    c_inv /= det[:, None, None]
    bc = np.einsum("kab,kbc->kac", b_s, c_inv)
    schur = a_s - np.einsum("kac,kdc->ad", bc, b_s)
    step_g = np.linalg.solve(schur, -g_s + np.einsum("kac,kc->a", bc, l_s))
    step_l = np.einsum("kab,kb->ka", c_inv, -l_s - np.einsum("kab,a->kb", b_s, step_g))
    return np.concatenate([step_g * sg, step_l[:, 0] * sl[:, 0], step_l[:, 1] * sl[:, 1]])


def _segment_of(starts: np.ndarray, samples: int) -> np.ndarray:
    """The segment each sample belongs to."""
    return np.searchsorted(starts, np.arange(samples), side="right") - 1


def _linear_covariance(
    best: _Fit, starts: np.ndarray, logged: int, noise: _Noise | None = None, white: float | None = None
) -> np.ndarray:
    """Covariance of the 4 global parameters from the fit's Jacobian (step 4 of the module docstring): residual
    variance (at least quantization's 1/12) × correlation time × (JᵀJ)⁻¹ with the segments' starts eliminated.
    With force noise (``noise``): quantization's 1/12 × (JᵀJ)⁻¹ plus the noise's own (:func:`_noise`). With noise
    on the readings: the white residuals' variance ``white`` (:func:`_white`) × (JᵀJ)⁻¹ plus the force noise's."""
    n, j = len(best.fun), len(starts)
    cov = _global_covariance(best.glob, best.local, _segment_of(starts, n), j)
    extra = noise.covariance if noise is not None else np.zeros((4, 4))
    if white is not None:
        return white * cov + extra
    if noise is not None and noise.level > 0.0:
        return QUANTIZATION_VARIANCE * cov + noise.covariance
    s2 = max(float(best.fun @ best.fun) / max(1, logged - len(best.x)), QUANTIZATION_VARIANCE)
    return s2 * correlation_time(best.fun) * cov


class _Noise(NamedTuple):
    """Noise on the force column estimated from the residuals (:func:`_noise`): its standard deviation (force per
    tick) and the covariance of the 4 global parameters it causes."""

    level: float
    covariance: np.ndarray


def _impulse(theta: np.ndarray, length: int) -> np.ndarray:
    """Position (ticks) 1, 2, ..., ``length`` samples after a unit force per tick held over one sample, of the
    device moving (m ẍ + b ẋ = f, linear: Coulomb friction only shifts the force in motion)."""
    mu = math.exp(min(max(float(theta[0]), LOG_MU[0]), LOG_MU[1]))
    r = max(float(theta[1]), 0.0) / mu  # the decay per sample, b T/m
    j = np.arange(length, dtype=float)
    if r < 1e-6:
        return (0.5 + j) / mu
    x1 = (r + math.expm1(-r)) / (mu * r * r)
    return x1 + (-math.expm1(-r) / (mu * r)) * (-np.expm1(-r * j) / r)


def _noise(best: _Fit, xi: np.ndarray, w: np.ndarray, starts: np.ndarray, white: float | None = None) -> _Noise:
    """Force noise from the residuals: the method of moments on the residuals' sum of squares.

    A force error e_i held over sample i moves every later position of its segment by g(h − i) e_i
    (:func:`_impulse`, while the device moves: a device stuck by friction does not feel it); the fit absorbs part of
    it (the projection P = J A⁻¹ Jᵀ on all its columns: the segments' starts and the 4 global parameters, which on a
    4000-sample log take 15 % of it). The residuals' expected sum of squares is quantization's 1/12 per degree of
    freedom (N − p) plus s² ‖(I − P) G‖² (the same correction for the noise: with the segments' starts alone taken
    off, the level came out 10 % low at 4000 samples): s² follows, 0 when the residuals are
    those of quantization alone (their mean square below :data:`NOISE_FLOOR` × 1/12). The global parameters'
    covariance from the noise is then s² A⁻¹ (Σ Jₖᵀ Gₖ Gₖᵀ Jₖ) A⁻¹ (the sandwich, A = JᵀJ, segments' starts
    included). Readings with noise beyond their tick (:func:`_white`): their white variance ``white`` stands for
    quantization's 1/12, and force noise is estimated when the mean square residual exceeds it by more than
    :data:`NOISE_Z` standard errors of the difference (√(6/N) of it: the two estimates' own spreads, 2/N and 3.9/N
    of its square, added)."""
    n, j = len(best.fun), len(starts)
    dof = max(1.0, float(w.sum()) - len(best.x))
    rss = float(best.fun @ best.fun)
    floor = NOISE_FLOOR * QUANTIZATION_VARIANCE if white is None else white * (1.0 + NOISE_Z * math.sqrt(6.0 / dof))
    white = QUANTIZATION_VARIANCE if white is None else white
    if rss / dof <= floor:
        return _Noise(0.0, np.zeros((4, 4)))
    moving = np.r_[np.diff(xi) != 0.0, False].astype(float)
    ends = np.r_[starts[1:], n]
    g = _impulse(best.x, int(np.max(ends - starts)))
    total, size = 0.0, 4 + 2 * j
    a, b = np.zeros((size, size)), np.zeros((size, size))
    for k, (lo, hi) in enumerate(zip(starts, ends, strict=True)):
        m = hi - lo
        col = np.r_[0.0, g[: m - 1]]
        sens = _toeplitz(col) * moving[lo:hi][None, :] * w[lo:hi][:, None]  # rows: residuals, columns: forces
        total += float(np.einsum("ij,ij->", sens, sens))
        jac = np.column_stack([best.glob[lo:hi], best.local[lo:hi]])
        idx = np.r_[0:4, 4 + k, 4 + j + k]
        a[np.ix_(idx, idx)] += jac.T @ jac
        proj = sens.T @ jac
        b[np.ix_(idx, idx)] += proj.T @ proj
    inv = np.linalg.pinv(a)
    kappa = total - float(np.trace(inv @ b))  # ‖(I − P) G‖², P = J A⁻¹ Jᵀ: what the whole fit absorbs taken off
    s2 = max(0.0, (rss - white * dof) / kappa) if kappa > 0.0 else 0.0
    return _Noise(math.sqrt(s2), s2 * (inv @ b @ inv)[:4, :4])


def _toeplitz(col: np.ndarray) -> np.ndarray:
    """The lower-triangular Toeplitz matrix whose first column is ``col`` (entry (h, i) = col[h − i], h >= i)."""
    m = len(col)
    h = np.arange(m)
    d = h[:, None] - h[None, :]
    return np.where(d >= 0, col[np.clip(d, 0, m - 1)], 0.0)


def _bootstrap(
    xi: np.ndarray, phi: np.ndarray, w: np.ndarray, reps: int, progress: bool, noise: float = 0.0,
    position: float = 0.0,
) -> np.ndarray:  # fmt: skip
    """Global parameters of ``reps`` replicate logs (rows; fewer when a replicate does not move): the fitted
    model's positions ``xi`` read by an encoder whose origin is shifted by a uniform fraction of a tick, each
    identified from scratch like the log (first guess, segments, fit), its force column with fresh noise of the
    level estimated (``noise``, force per tick; none when 0), its readings with fresh noise of the level estimated
    before the encoder (``position``, ticks; none when 0). Deterministic (seeds 0, 1 and 2)."""
    rng, noisy, jitter = np.random.default_rng(0), np.random.default_rng(1), np.random.default_rng(2)
    draws = []
    bar = new_bar(iterable=range(reps), desc="bootstrap", unit="fit", leave=False) if progress else range(reps)
    for _ in bar:  # no bar, no tqdm (importing it costs about 0.05 s)
        nb = np.floor(xi + rng.uniform() + (jitter.normal(0.0, position, xi.size) if position > 0.0 else 0.0))
        try:
            logged = phi + noisy.normal(0.0, noise, phi.size) if noise > 0.0 else phi
            draws.append(_fit(nb - nb.min(), logged, w, position > 0.0)[0].x[:4])
        except LogError:  # a replicate too still to fit: its log says nothing either way
            continue
    return np.array(draws).reshape(-1, 4)


def _global_covariance(g: np.ndarray, local: np.ndarray, seg: np.ndarray, j: int) -> np.ndarray:
    """(JᵀJ)⁻¹ of the 4 global parameters with each segment's 2 start parameters eliminated (Schur complement)."""
    a = g.T @ g
    for k in range(j):
        rows = seg == k
        lk, gk = local[rows], g[rows]
        a -= (gk.T @ lk) @ np.linalg.pinv(lk.T @ lk) @ (lk.T @ gk)
    return np.linalg.pinv(a)


def _free_run(theta: np.ndarray, n: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """The identified model run once over the whole log from the first segment's fitted start."""
    j = (len(theta) - 4) // 2
    out = np.empty(len(n))
    open_loop_kernel(n[0] + theta[4], theta[4 + j], phi + theta[3], math.exp(theta[0]), theta[1], theta[2], out)
    return out


def correlation_time(r: np.ndarray) -> float:
    """The integrated autocorrelation time 1 + 2 Σ ρ_k of residuals ``r`` (>= 1; summed while ρ_k > 0.05).

    Correlated residuals carry fewer independent samples than their number: the least-squares covariance,
    which assumes independent residuals, is multiplied by this factor (the effective sample size N/τ).

    Examples
    --------
    >>> correlation_time(np.array([1.0, -1.0] * 50))
    1.0
    >>> correlation_time(np.repeat([1.0, -1.0], 25)) > 10
    True
    """
    x = r - r.mean()
    spec = np.fft.rfft(x, 2 * len(x))
    acf = np.fft.irfft(spec * np.conj(spec))[: len(x)]
    if acf[0] <= 0.0:
        return 1.0
    rho = acf / acf[0]
    tau = 1.0
    for k in range(1, len(x) // 2):
        if rho[k] <= 0.05:
            break
        tau += 2.0 * rho[k]
    return float(tau)


def _half(e: Estimate) -> float:
    """Half-width of an estimate's interval above its value."""
    return math.inf if e.high is None else e.high - e.value


#: Replicates of the bootstrap of the intervals (:func:`identify`).
BOOTSTRAP = 10
#: Most replicates :func:`identify` accepts.
MAX_BOOTSTRAP = 200
#: Ratio of an interval's end to the estimate beyond which the estimate counts as unbounded by the log.
SCATTER = 1e3


def _estimates(theta: np.ndarray, cov: np.ndarray, draws: np.ndarray, delta: float, t: float) -> dict[str, Estimate]:
    """m, b, c and f₀ in SI units with their 95 % intervals (step 4 of the module docstring): the half-width is
    the larger of 1.96 linearized standard errors and Student's t quantile × the replicates' spread about the
    estimate (their bias included); the intervals of b and c end at 0 at the lowest (their range), the mass's is
    symmetric in log m."""
    half = 1.959964 * np.sqrt(np.maximum(np.diag(cov), 0.0))
    if len(draws) >= 2:
        spread = np.sqrt(np.sum((draws - theta[:4]) ** 2, axis=0) / (len(draws) - 1))
        half = np.maximum(half, _t_quantile(len(draws) - 1) * spread)
    m, h = math.exp(theta[0]) * t * t, float(half[0])  # the dimensionless groups at K = 1 N/m: μ = m/T² ...
    est = {"mass": Estimate(m, m * h / 1.959964, m * math.exp(-h), m * math.exp(h)) if h < math.log(SCATTER) else
           Estimate(m, None, None, None, Undetermined.SCATTER)}  # fmt: skip
    for i, key, scale in ((1, "damping", t), (2, "coulomb", delta), (3, "force_offset", delta)):  # β = b/T, σ = c/Δ
        value, hw = float(theta[i]) * scale, float(half[i]) * scale
        bounded = hw < (SCATTER - 1.0) * abs(value) or key == "force_offset" and math.isfinite(hw)
        low = value - hw if key == "force_offset" else max(0.0, value - hw)  # b, c >= 0: their range ends at 0
        est[key] = Estimate(value, hw / 1.959964, low, value + hw) if bounded else Estimate(
            value, None, None, None, Undetermined.SCATTER)  # fmt: skip
    return est


def _t_two_sided(theta: float, df: int) -> float:
    """P(|T| < √df tan θ) of Student's t with ``df`` degrees of freedom, a whole number >= 1 (Abramowitz and
    Stegun 26.7.3 and 26.7.4: a finite sum of powers of cos θ)."""
    c2, s = math.cos(theta) ** 2, math.sin(theta)
    if df % 2 == 1:
        term, total = math.cos(theta), 0.0
        for k in range(1, (df - 1) // 2 + 1):  # cos θ, (2/3) cos³ θ, (2·4)/(3·5) cos⁵ θ, ...
            total += term
            term *= c2 * (2 * k) / (2 * k + 1)
        return 2.0 / math.pi * (theta + s * total)
    term, total = 1.0, 0.0
    for k in range(1, df // 2 + 1):  # 1, ½ cos² θ, (1·3)/(2·4) cos⁴ θ, ...
        total += term
        term *= c2 * (2 * k - 1) / (2 * k)
    return s * total


def _t_quantile(df: int, level: float = 0.95) -> float:
    """The two-sided ``level`` quantile of Student's t with ``df`` degrees of freedom (a whole number >= 1): the t
    of P(|T| < t) = ``level`` (0.975 one-sided), by bisection on θ = atan(t/√df) to the last bit
    (:func:`_t_two_sided`). ``scipy.special.stdtrit`` computes the same; importing scipy.special costs about
    0.2 s of ``dfa identify``, which needs nothing else from it (tests/test_identify_inputs.py checks the two
    agree)."""
    lo, hi = 0.0, math.pi / 2.0
    while True:
        mid = 0.5 * (lo + hi)
        if not lo < mid < hi:
            break
        lo, hi = (mid, hi) if _t_two_sided(mid, df) < level else (lo, mid)
    return math.sqrt(df) * math.tan(0.5 * (lo + hi))


def _motion_warnings(n: np.ndarray, coulomb: float, f_max: float) -> list[IdentifyWarning]:
    """The log's own shortcomings: friction (``coulomb``, N) below its resolution, little motion, no reversal."""
    out = []
    if coulomb < FRICTION_SHARE * f_max:
        out.append(IdentifyWarning.FRICTION_UNRESOLVED)
    steps = np.diff(n)
    if np.count_nonzero(steps) < FEW_MOVING:
        out.append(IdentifyWarning.LITTLE_MOTION)
    if not ((steps > 0).any() and (steps < 0).any()):
        out.append(IdentifyWarning.NO_REVERSAL)
    return out


def _withhold(est: dict[str, Estimate], warns: list[IdentifyWarning]) -> dict[str, Estimate]:
    """The estimates without the intervals the log cannot give (little motion: none; no reversal: c and f₀;
    friction below the forces' resolution: c)."""
    why: dict[str, Undetermined] = {}
    if IdentifyWarning.POOR_FIT in warns:
        return {k: Estimate(e.value, None, None, None, Undetermined.POOR_FIT) for k, e in est.items()}
    if IdentifyWarning.FRICTION_UNRESOLVED in warns:
        why["coulomb"] = Undetermined.FRICTION_UNRESOLVED
    if IdentifyWarning.NO_REVERSAL in warns:
        why |= dict.fromkeys(("coulomb", "force_offset"), Undetermined.NO_REVERSAL)
    if IdentifyWarning.LITTLE_MOTION in warns:
        why = dict.fromkeys(est, Undetermined.LITTLE_MOTION)
    if IdentifyWarning.CONSTANT_FORCE in warns:
        why = dict.fromkeys(est, Undetermined.CONSTANT_FORCE)
    return {k: Estimate(e.value, None, None, None, why[k]) if k in why else e for k, e in est.items()}


def _fit_warnings(est: dict[str, Estimate], cov: np.ndarray) -> list[IdentifyWarning]:
    """Loose estimates (of those with an interval), damping and friction not separated."""
    out = []
    loose = [k for k, e in est.items() if k != "force_offset" and (e.undetermined == Undetermined.SCATTER or (
        e.high is not None and _half(e) > LOOSE * abs(e.value)))]  # fmt: skip
    sd = np.sqrt(np.maximum(np.diag(cov)[1:3], 0.0))
    if sd.min() > 0.0 and abs(cov[1, 2] / (sd[0] * sd[1])) > CONFOUNDED and {"damping", "coulomb"} & set(loose):
        out.append(IdentifyWarning.DAMPING_FRICTION_CONFOUNDED)
    out += [IdentifyWarning.coerce(f"loose_{k}") for k in loose]
    return out


def _ticks(
    lg: DeviceLog, resolution: float | None, period: float | None
) -> tuple[float, Timing, np.ndarray, np.ndarray]:
    """(Δ, the timing, each row's sample index (-1: a repeated row), the readings in whole ticks from the lowest):
    step 1 of the module docstring."""
    check_rows(lg.samples, lg.source)
    dx = check_positive("resolution", resolution, "give Δ in m") if resolution is not None else None
    ts = check_positive("period", period, "give T in s") if period is not None else None
    dt = np.diff(lg.t)
    step = float(np.median(dt[dt > 0.0]))
    if ts is not None and abs(step / ts - 1.0) > GIVEN_PERIOD_RTOL:
        raise LogError(
            f"{lg.source}: period = {format_value(ts)} s disagrees with the log's times (their step is {step:.6g} s): "
            "give the period the log was sampled at, or leave it out"
        )
    timing, index = log_timing(lg.t, lg.source, ts)
    delta = dx if dx is not None else estimate_resolution(lg.x, lg.source)
    _check_scales(lg, delta, timing.period, dx is not None, ts is not None)
    n = np.rint((lg.x - lg.x.min()) / delta)
    off = np.abs((lg.x - lg.x.min()) / delta - n)
    if float(np.max(off)) > (GIVEN_GRID_RTOL if dx is not None else GRID_RTOL):  # given: allow written rounding
        i = int(np.argmax(off))
        raise LogError(
            f"{lg.source}: the readings are not whole ticks of resolution = {format_value(delta)}: row {i + 2} is "
            f"{float(off[i]):.3g} ticks off; another resolution, or readings written with too few digits?"
        )
    return delta, timing, index, n


def _on_grid(index: np.ndarray, n: np.ndarray, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The readings and forces on the grid of every sample, and each sample's weight in the fit (1: logged, 0:
    dropped by the log: its reading that of the sample before, unknown, and its force interpolated between the
    logged ones, a guess the fit does not rest on, :func:`_fit`). Repeated rows (index -1) are left out."""
    keep = index >= 0
    rows, where = n[keep], index[keep]
    observed = np.zeros(int(where[-1]) + 1, dtype=bool)
    observed[where] = True
    slot = np.zeros(observed.size, dtype=np.int64)
    slot[where] = np.arange(where.size)
    slot = np.maximum.accumulate(slot)  # each sample takes the last logged row at or before it
    force = np.interp(np.arange(observed.size), where, phi[keep]) if not observed.all() else phi[keep]
    return rows[slot], force, observed.astype(float)


def log_grid(log: DeviceLog, *, resolution: float | None = None, period: float | None = None) -> tuple[float, float]:
    """The resolution Δ and period T :func:`identify` fits ``log`` with (step 1 of the module docstring), checked.

    Cheap (no fit): the command line checks its flags against the log's grid with it before the work.

    Parameters
    ----------
    log : DeviceLog
        The logged run.
    resolution, period : float, optional
        Δ (m, rotary rad) and T (s) when known, as :func:`identify` takes them.

    Returns
    -------
    tuple of float
        (Δ, T).

    Raises
    ------
    LogError
        What :func:`identify` refuses before its fit: a log off a uniform time grid or an encoder lattice, or
        whose numbers a float cannot fit (:data:`MAX_TICKS`, :data:`MAX_FORCE_PER_TICK`, :data:`PERIOD_RANGE`).

    Examples
    --------
    >>> log = DeviceLog(np.arange(30) * 1e-3, 1e-5 * (np.arange(30) % 7), np.ones(30))
    >>> [round(v, 12) for v in log_grid(log)]
    [1e-05, 0.001]
    """
    lg = check_type("log", log, DeviceLog, "read one with dfa.read_log(path)")
    delta, timing, _index, _n = _ticks(lg, resolution, period)
    return delta, timing.period


def _check_scales(lg: DeviceLog, delta: float, t: float, delta_given: bool, t_given: bool) -> None:
    """Refuse a log whose numbers a float cannot fit, before the fit (:data:`MAX_TICKS`,
    :data:`MAX_FORCE_PER_TICK`, :data:`PERIOD_RANGE`), naming the log's value or the given one and the limit."""
    u = device_units(lg.rotary)
    res = f"resolution = {delta:.4g} {u['resolution']}" + ("" if delta_given else " (the readings' step)")
    slip = (
        "give the encoder's resolution in m (rad), or leave it out to take the readings' step"
        if delta_given
        else "is x in m (rad)? give it in SI units, or its unit in the header (x (mm))"
    )
    if not math.isfinite(delta) or delta < sys.float_info.min:
        raise LogError(f"{lg.source}: {res} is invalid: it must be a normal float >= {sys.float_info.min:.3g} (below, a "
                       f"float holds it to a few digits and the forces per tick overflow); {slip}")  # fmt: skip
    with np.errstate(over="ignore"):
        span = (float(np.max(lg.x)) - float(np.min(lg.x))) / delta
        per_tick = float(np.max(np.abs(lg.f))) / delta
    if not span <= MAX_TICKS:
        raise LogError(f"{lg.source}: {res} is invalid for this log: its readings span {span:.4g} ticks of it, at most "
                       f"{MAX_TICKS:g} (beyond, a float holds a position to less than a tick); {slip}")  # fmt: skip
    if not per_tick <= MAX_FORCE_PER_TICK:
        f = float(np.max(np.abs(lg.f)))
        raise LogError(
            f"{lg.source}: column 'f' reaches {f:.4g} {u['force']}, which is {per_tick:.4g} {u['force']} per tick of "
            f"{res}: at most {MAX_FORCE_PER_TICK:g} (beyond, the fit's sums of squares overflow a float); are f in N "
            "(N·m) and x in m (rad)? give them in SI units, or their units in the header (f (mN))"
        )
    lo, hi = PERIOD_RANGE
    if not lo <= t <= hi:
        what = f"period = {t:.4g} s" if t_given else f"the sample period T = {t:.4g} s (the step of column 't')"
        raise LogError(
            f"{lg.source}: {what} is invalid: it must lie in [{lo:.3g}, {hi:.3g}] s (outside, the identified mass "
            "m = μ T² overflows or vanishes in a float); are the times in s? give t in s, or its unit in the header "
            "(t (ms))"
        )


def _check_identified(est: dict[str, Estimate], delta: float, t: float, source: str) -> None:
    """Refuse identified values a float cannot hold (m = μ T², b = β T, c = σ Δ), naming the log's grid: the
    message of :class:`Device` would name a mass the user never gave."""
    m, b, c = (est[k].value for k in ("mass", "damping", "coulomb"))
    if math.isfinite(b) and math.isfinite(c) and math.isfinite(m) and m >= sys.float_info.min:
        return
    raise LogError(
        f"{source}: the fit's m = {m:.4g}, b = {b:.4g}, c = {c:.4g} (SI) overflow or vanish in a float with the log's "
        f"period T = {t:.4g} s and resolution Δ = {delta:.4g}: are t in s, x in m (rad) and f in N (N·m)? give the "
        "log in SI units, or the units in its header"
    )


def identify(
    log: DeviceLog,
    *,
    resolution: float | None = None,
    period: float | None = None,
    name: str | None = None,
    bootstrap: int = BOOTSTRAP,
    progress: bool = False,
) -> Identification:
    """Identify m, b, c (and Δ, T unless given) of the device that produced ``log`` (module docstring).

    Parameters
    ----------
    log : DeviceLog
        The logged run (:func:`dfa.model.log.read_log` reads one from CSV).
    resolution : float, optional
        Encoder resolution Δ in m (rotary rad), > 0; default: estimated from the readings.
    period : float, optional
        Sample period T in s, > 0; default: estimated from the times.
    name : str, optional
        Name of the identified device (default ``"device identified from <source>"``).
    bootstrap : int, optional
        Replicate logs of the intervals' bootstrap, 0 to :data:`MAX_BOOTSTRAP` (default :data:`BOOTSTRAP`; each
        costs one more fit). 0 gives the linearized intervals alone, which are too narrow (module docstring,
        step 4).
    progress : bool, optional
        Show a progress bar over the replicates (default False).

    Returns
    -------
    Identification
        The identified device, each estimate with its 95 % interval, the fit's quality and the warnings.

    Raises
    ------
    LogError
        (a DFAValueError) A log that is not on a uniform time grid or an encoder lattice, or that barely moves;
        before the fit, a log of more than :data:`dfa.model.log.MAX_LOG_ROWS` samples or whose numbers a float
        cannot fit (:data:`MAX_TICKS`, :data:`MAX_FORCE_PER_TICK`, :data:`PERIOD_RANGE`); after it, identified
        values beyond a float.
    DFAValueError, DFATypeError
        A resolution or period that is not a number > 0; a bootstrap that is not a whole number from 0 to
        :data:`MAX_BOOTSTRAP`; a log that is not a DeviceLog; a progress that is not True or False.

    See Also
    --------
    dfa.read_log : Read a log from CSV.
    synthetic_log, impact_log : Logs made by the exact simulator, to try identification on.
    """
    lg = check_type("log", log, DeviceLog, "read one with dfa.read_log(path)")
    reps = check_int("bootstrap", bootstrap, 0, "give a whole number of replicates, 0 for none")
    show = check_bool("progress", progress, "pass True to show a progress bar over the replicates, else False")
    if reps > MAX_BOOTSTRAP:
        raise DFAValueError(
            f"bootstrap = {reps} is too many: each replicate is one more fit of the whole log (seconds each); give "
            f"at most {MAX_BOOTSTRAP} (default {BOOTSTRAP})"
        )
    delta, timing, index, rows = _ticks(lg, resolution, period)  # refuses a log of too many rows too
    t = timing.period
    n, phi, w = _on_grid(index, rows, lg.f / delta)
    try:
        best, starts, position = _fit_readings(n, phi, w)
    except LogError as err:
        raise LogError(f"{lg.source}: {err}") from None
    theta, xi = best.x, _predict(best.x, n, phi, starts, np.empty(len(n)))
    white = position**2 + QUANTIZATION_VARIANCE if position > 0.0 else QUANTIZATION_VARIANCE
    spread = float(np.std(lg.f))
    noise = (
        _noise(best, xi, w, starts, white if position > 0.0 else None)
        if spread > 0.0
        else _Noise(0.0, np.zeros((4, 4)))
    )
    cov = _linear_covariance(best, starts, int(w.sum()), noise, white if position > 0.0 else None)
    fit = _quality(xi, n, w)
    relative = noise.level * delta / spread if spread > 0.0 else 0.0
    warns = _motion_warnings(np.floor(xi) if position > 0.0 else n, float(theta[2]) * delta,
                             float(np.max(np.abs(lg.f))))  # fmt: skip
    warns += [IdentifyWarning.POSITION_NOISE] if position > 0.0 else []
    warns += _noise_warnings(fit, relative, white if position > 0.0 else None) if spread > 0.0 else [
        IdentifyWarning.CONSTANT_FORCE]  # fmt: skip
    skip = {IdentifyWarning.LITTLE_MOTION, IdentifyWarning.POOR_FIT, IdentifyWarning.CONSTANT_FORCE} & set(warns)
    draws = _bootstrap(xi, phi, w, 0 if skip else reps, show, noise.level, position)
    est = _withhold(_estimates(theta, cov, draws, delta, t), warns)
    run = _free_run(theta, n, phi)
    free = _quality(run, n, w)
    warns += _fit_warnings(est, cov) + ([IdentifyWarning.JITTER] if timing.exceeds else [])
    _check_identified(est, delta, t, lg.source)
    dev = Device(est["mass"].value, est["damping"].value, est["coulomb"].value, delta, t,
                 name=name or f"device identified from {lg.source}", rotary=lg.rotary)  # fmt: skip
    v_peak = float(np.max(np.abs(np.diff(run)))) * delta / t
    status = IdentifyStatus.POOR_FIT if IdentifyWarning.POOR_FIT in warns else (
        IdentifyStatus.CAVEATS if warns else IdentifyStatus.OK)  # fmt: skip
    return Identification(dev, lg.source, lg.samples, est["mass"], est["damping"], est["coulomb"],
                          est["force_offset"], resolution is not None, period is not None, int(len(n) // len(starts)),
                          len(draws), reps, fit, free, timing, noise.level * delta, relative, position * delta,
                          _confounded(cov, est, warns) if spread > 0.0 else (), tuple(warns), v_peak, _states(theta, n, starts), run, n,
                          status)  # fmt: skip


#: The global parameters in the order of θ and the covariance (m as log μ).
GLOBAL = ("mass", "damping", "coulomb", "force_offset")


def _confounded(
    cov: np.ndarray, est: dict[str, Estimate], warns: list[IdentifyWarning]
) -> tuple[tuple[str, str, float], ...]:
    """The pairs of global parameters whose estimates the log does not tell apart: |correlation| above
    :data:`CONFOUNDED` in the fit's covariance (first, second, correlation) and one of m, b, c in the pair poorly
    determined (interval wider than ±:data:`LOOSE`, or none; a correlated pair whose intervals are narrow is told
    apart); not the pairs a warning names already (no reversal: c and f₀; damping and friction not separated)."""
    loose = {i for i, k in enumerate(GLOBAL[:3]) if est[k].high is None or _half(est[k]) > LOOSE * abs(est[k].value)}
    sd = np.sqrt(np.maximum(np.diag(cov), 0.0))
    said = {(2, 3)} if IdentifyWarning.NO_REVERSAL in warns else set()
    said |= {(1, 2)} if IdentifyWarning.DAMPING_FRICTION_CONFOUNDED in warns else set()
    out = []
    for i in range(4):
        for k in range(i + 1, 4):
            if (i, k) in said or not {i, k} & loose:
                continue
            if sd[i] > 0.0 and sd[k] > 0.0 and abs(cov[i, k] / (sd[i] * sd[k])) > CONFOUNDED:
                out.append((GLOBAL[i], GLOBAL[k], float(cov[i, k] / (sd[i] * sd[k]))))
    return tuple(out)


def _noise_warnings(fit: FitQuality, relative: float, white: float | None = None) -> list[IdentifyWarning]:
    """A poor fit (fewer than :data:`POOR_FIT` of the samples within a tick, and more force noise than
    :data:`NOISE_MAX` needed to explain it; with noise on the readings of white variance ``white`` (ticks²,
    :func:`_white`), also residuals whose mean square exceeds :data:`POSITION_MISFIT` times it), or force noise
    that explains the residuals."""
    if fit.within_one_tick < POOR_FIT and not relative <= NOISE_MAX:
        return [IdentifyWarning.POOR_FIT]
    if white is not None and not fit.rms_ticks**2 <= POSITION_MISFIT * white:
        return [IdentifyWarning.POOR_FIT]
    return [IdentifyWarning.FORCE_NOISE] if relative > 0.0 else []


def _states(theta: np.ndarray, n: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """Each segment's first sample, fitted position (ticks) and velocity (ticks per sample)."""
    j = len(starts)
    return np.column_stack([starts, n[starts] + theta[4 : 4 + j], theta[4 + j :]])


def _quality(xi: np.ndarray, n: np.ndarray, w: np.ndarray) -> FitQuality:
    """How a prediction ξ (ticks) matches the logged ticks n, over the samples the log holds (``w`` > 0)."""
    xi, n = xi[w > 0], n[w > 0]
    ticks = np.floor(xi) - n
    return FitQuality(float(np.sqrt(np.mean((xi - n - 0.5) ** 2))), int(np.max(np.abs(ticks))),
                      float(np.mean(np.abs(ticks) <= 1.0)))  # fmt: skip


def synthetic_log(
    device: Device,
    force: ArrayLike,
    *,
    x0: float = 0.0,
    v0: float = 0.0,
    force_offset: float = 0.0,
    force_noise: float = 0.0,
    position_noise: float = 0.0,
    seed: int = 0,
    source: str = "synthetic",
) -> DeviceLog:
    """A log made by the exact simulator: ``device`` driven by the held forces ``force`` (N), read by its encoder.

    Parameters
    ----------
    device : Device
        The device (its m, b, c, Δ, T).
    force : array_like
        The force commanded at each sample and held over it, N (rotary N·m): one per sample.
    x0, v0 : float, optional
        Start position (m) and velocity (m/s); default at rest at 0.
    force_offset : float, optional
        A force added to what is applied but not logged (an amplifier offset), N (default 0).
    force_noise : float, optional
        Standard deviation of noise on the logged force column, N (default 0): the log is not what was applied.
    position_noise : float, optional
        Standard deviation of noise on the position before the encoder reads it, m (rotary rad; default 0): the
        readings are Δ⌊(x + e)/Δ⌋ (an analog sensor read by a converter, a noisy encoder).
    seed : int, optional
        Seed of the noise (default 0; the position noise is drawn after the force noise).
    source : str, optional
        The log's name (default ``"synthetic"``).

    Returns
    -------
    DeviceLog
        Readings Δ⌊x/Δ⌋, times hT, the logged forces.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...)")
    f = np.asarray(force, dtype=float)
    if f.ndim != 1 or f.size == 0 or not np.all(np.isfinite(f)):
        raise DFAValueError("force must be a one-dimensional array of finite forces in N, one per sample")
    noise = check_nonnegative("force_noise", force_noise, "give the noise's standard deviation in N")
    jitter = check_nonnegative("position_noise", position_noise, "give the noise's standard deviation in m")
    offset = check_real("force_offset", force_offset, "give the offset in N")
    xi = np.empty(f.size)
    delta, t = dev.resolution, dev.period
    open_loop_kernel(x0 / delta, v0 * t / delta, (f + offset) / delta, dev.mass / (t * t),
                     dev.damping / t, dev.coulomb / delta, xi)  # fmt: skip
    rng = np.random.default_rng(seed)
    logged = f + (rng.normal(0.0, noise, f.size) if noise > 0.0 else 0.0)
    xi += rng.normal(0.0, jitter / delta, f.size) if jitter > 0.0 else 0.0
    return DeviceLog(np.arange(f.size) * t, delta * np.floor(xi), logged, source=source, rotary=dev.rotary)


def impact_log(
    device: Device, stiffness: float | Wall, velocity: float, samples: int, *, source: str = "impact"
) -> DeviceLog:
    """A log of an impact on a wall (exact simulation): readings and the wall's force, per sample.

    The device arrives at ``velocity`` (m/s) at the wall's origin (the first reading inside); the logged force is
    the wall's, applied over each sample: for the paper's spring −KΔ(⌊x/Δ⌋ + ½) (paper eq. 2), for a
    :class:`~dfa.model.wall.Wall` (a damper, a delay, one-sided: :func:`dfa.analysis.closed_loop.logged_wall`)
    its force replayed from the run, which identification takes as the held force like any other. A run that
    diverges is logged up to its divergence.

    Parameters
    ----------
    device : Device
        The device.
    stiffness : float or Wall
        K of the paper's spring in N/m (rotary N·m/rad), or the wall.
    velocity : float
        Impact speed, m/s (rad/s).
    samples : int
        Samples logged, at least :data:`dfa.model.log.MIN_SAMPLES`.
    source : str, optional
        The log's name (default ``"impact"``).

    Returns
    -------
    DeviceLog
        Times hT, readings Δ⌊x/Δ⌋ in the wall's frame, the wall's force.
    """
    from .simulation import simulate

    dev = check_type("device", device, Device, "build one with dfa.Device(...)")
    check_int("samples", samples, MIN_SAMPLES, f"a log needs at least {MIN_SAMPLES} samples")
    wall = stiffness if isinstance(stiffness, Wall) else Wall(stiffness)
    r = simulate(Loop(dev, wall), dev.xi_dot(velocity), samples - 1, record=True)
    xi = run_positions(r)
    keep = int(np.argmax(~np.isfinite(xi))) if not np.all(np.isfinite(xi)) else samples  # up to a divergence
    force = np.nan_to_num(r.applied_force(), nan=0.0)[:keep] * wall.stiffness * dev.resolution
    t = np.arange(keep) * dev.period
    return DeviceLog(t, dev.resolution * np.floor(xi[:keep]), force, source=source, rotary=dev.rotary)


def run_positions(run: SimulationResult) -> np.ndarray:
    """A recorded run's positions ξ (ticks) at every instant, continued past a one-sided wall's exit.

    The simulator ends a run that left a one-sided wall for good (outcome ``left``: outside, moving away, no
    force will act again) and records NaN after it; here the device moves on freely from its last state (the
    exact per-sample solution under no force, :func:`dfa.core.open_loop.open_loop_kernel`), as a log of it would
    go on. Any other run's record is returned as it is (NaN past a divergence).

    Parameters
    ----------
    run : SimulationResult
        A recorded run (``record=True``).

    Returns
    -------
    numpy.ndarray
        ξ at the instants 0 … samples, ticks.
    """
    sim = check_type("run", run, SimulationResult, "simulate with record=True")
    if sim.xi is None or sim.xi_dot is None:
        raise DFAValueError("run.xi = None is invalid: the trajectory was not recorded; simulate with record=True")
    xi = np.array(sim.xi, dtype=float)
    if sim.outcome.value != "left" or np.all(np.isfinite(xi)):
        return xi
    last = int(np.flatnonzero(np.isfinite(xi))[-1])
    rest = np.empty(xi.size - last)
    open_loop_kernel(float(xi[last]), float(sim.xi_dot[last]), np.zeros(rest.size), sim.mu, sim.beta, sim.sigma, rest)
    xi[last:] = rest
    return xi


#: Points of the stiffness grid of the design answer at the longest logged period (:func:`period_effect`): half the
#: default 16 (the grid only brackets each limit, which bisection refines to the same 2·10⁻³; the speeds are the
#: default's): one extra answer at about half the cost of the one at T.
PERIOD_EFFECT_GRID = 8


def period_effect(
    device: Device, timing: Timing, velocity: float, delay: int = 0, *, answer: KMaxResult | None = None
) -> PeriodEffect:
    """The criterion's K_max (eq. 11) of ``device`` at its period T and at the longest period of the log, and with
    ``answer`` the recommended stiffness at both.

    Every analysis takes each sample to last T; a sample that lasts longer loses passivity first (eq. 11 falls
    as T grows), so the limit at the longest logged period is where a log's jitter can take the proof. The
    simulated limits move too (a longer sample holds the force longer): with the design answer at T (``answer``,
    :func:`dfa.analysis.limits.kmax.design_answer`), one more answer of the same wall at the longest period (the
    same speeds, a grid of :data:`PERIOD_EFFECT_GRID` points) and the recommended stiffness of each
    (:func:`dfa.analysis.limits.recommend.recommend_stiffness`, its default margin).

    Parameters
    ----------
    device : Device
        The device (its T is the log's).
    timing : Timing
        The log's timing (:func:`log_timing`).
    velocity : float
        Impact speed, m/s (rad/s), >= 0.
    delay : int, optional
        Computational delay in samples of the criterion (default 0).
    answer : KMaxResult, optional
        The design answer of ``device`` (its wall, at ``velocity``) at T; default none: the criterion alone.

    Returns
    -------
    PeriodEffect
        K_max at T and at the longest period, and the recommended stiffness at both with ``answer``.

    Examples
    --------
    >>> dev = Device(0.1, 0.5, 0.2, 1e-5, 1e-3)
    >>> tm = Timing(1e-3, 1e-5, 5e-5, 1.05e-3, 0, 0, 0)
    >>> e = period_effect(dev, tm, 0.05)
    >>> e.k_criterion_max < e.k_criterion
    True
    """
    import dataclasses

    from .limits.closed_form import k_max_criterion

    dev = check_type("device", device, Device, "build one with dfa.Device(...)")
    tm = check_type("timing", timing, Timing, "take it from dfa.identify(...).timing")
    v = check_nonnegative("velocity", velocity, "give the impact speed in m/s (rad/s)")
    slow = dataclasses.replace(dev, period=max(tm.period_max, dev.period))
    k, k_slow = float(k_max_criterion(dev, v, delay)), float(k_max_criterion(slow, v, delay))
    if answer is None:
        return PeriodEffect(dev.period, slow.period, v, k, k_slow)
    from .limits.kmax import design_answer
    from .limits.recommend import recommend_stiffness

    ans = check_type("answer", answer, KMaxResult, "pass dfa.design_answer(Loop(device, wall), velocity)")
    if ans.device != dev or ans.velocity != v:
        raise DFAValueError(
            f"answer is invalid: it is the design answer of {ans.device.name!r} at {ans.velocity:g}, not of device "
            f"{dev.name!r} at velocity = {v:g}; pass design_answer(Loop(device, wall), velocity) of these"
        )
    rec = recommend_stiffness(ans)
    rec_slow = recommend_stiffness(design_answer(Loop(slow, ans.wall), v, grid=PERIOD_EFFECT_GRID))
    return PeriodEffect(dev.period, slow.period, v, k, k_slow, rec.k_recommended, rec_slow.k_recommended,
                        rec.status.value, rec_slow.status.value, PERIOD_EFFECT_GRID)  # fmt: skip
