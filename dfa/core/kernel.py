"""Compiled kernel of the exact sampled-data simulator (numba, cached).

Dimensionless device (paper eq. 4-5), time in samples::

    μ ξ'' + β ξ' + σ sgn(ξ') = φ,   φ = −⌊ξ(h − d)⌋ − ½  constant on [h, h + 1).

While the device moves in direction s with constant force F = φ − σ s, the
exact solution after a time t is, with u = β t/μ and a = F/μ::

    ξ(t)  = ξ₀ + ξ'₀ t φ₁(u) + a t² φ₂(u)
    ξ'(t) = ξ'₀ e^{−u} + a t φ₁(u)
    φ₁(u) = (1 − e^{−u})/u,   φ₂(u) = (u − 1 + e^{−u})/u²

(φ₁ = 1, φ₂ = ½ at β = 0: the polynomial solution). The velocity reaches zero
at t* = (μ/β) log1p(−ξ'₀β/F) = −(ξ'₀μ/F)·λ(x), λ(x) = log1p(x)/x, x = −ξ'₀β/F
(t* = −ξ'₀μ/F at β = 0); there the device sticks
for the rest of the sample when |φ| <= σ, otherwise it restarts in direction
sgn φ and cannot stop again within the sample. Energy dissipated by the
viscous term over a phase (closed form)::

    β ∫ ξ'² dt = β [ξ'₀² t φ₁(2u) + 2 ξ'₀ a t² ψ(u) + a² t³ χ(u)]
    ψ(u) = ((1 − e^{−u}) − ½(1 − e^{−2u}))/u²,  χ(u) = (u − 2(1 − e^{−u}) + ½(1 − e^{−2u}))/u³

and by Coulomb friction σ|Δξ|. Every function is evaluated without
cancellation (series below u = 0.5, :mod:`dfa.core.exprel`).

Structure: one sample is a chain of small inlined steps (:func:`force`,
:func:`delayed_force`, :func:`at_rest`, :func:`step`, :func:`energy_terms`);
:func:`advance` runs any range of samples from a resumable state
(:func:`start`, :func:`finish`); :func:`simulate_kernel` runs a whole run and
:func:`serial_kernel` a list of independent runs. All release the GIL.

Hot path (issue 16): without delay, records or energy, the samples before
the tail run in :func:`advance_free`, whose loop carries (ξ, ξ') and the
peak only. There the state is (ξ, ξ') alone, so a run whose state repeats
bit for bit after P samples repeats them for ever: whole periods are
skipped (Brent's cycle detection; results bit for bit those of integrating
every sample, ``tests/test_eq4_period_skip.py``). Most chatter runs of a
stability map settle on such a cycle within a few thousand samples.

Rounding: the hot path divides by μ once per run (``sample_constants``) and
evaluates φ₁, φ₂ by Estrin's scheme; against the kernel before this change
(per-sample divisions, term-by-term series) trajectories agree to rounding
(at most 8·10⁻¹¹ relative after 2·10⁴ samples on 300 random runs), and the
outcomes of those runs and of two stability maps are unchanged. Later, the
sample sums the reading last and the stop time uses one division and the
series of λ(y) = log1p(y)/y (:func:`step`); against the kernel before that
(commit 9829bef) 300 random runs of 2·10⁴ samples (d = 0 … 2) agree to
4.4·10⁻¹⁰ of max(|ξ|, 1) and keep their outcomes, as do the points of three
stability maps (μ = 100 at 4 × 40 × 40 and 2 × 30 × 30, μ = 30 with d = 1).
Then φ₁, φ₂ and λ took eight terms below |u| = 1/32 (|y| = 1/128) and a stop
inside a sample one series for (φ₁, φ₂) of each phase (:func:`dfa.core.exprel.phi12`):
a sample with a stop is mostly multiply-adds of these series, and chatter
stops in nearly every sample. Against the kernel before that (commit 8313b4b)
the same 300 runs agree to 6.9·10⁻¹² of max(|ξ|, 1) and keep their outcomes,
as do the points of the same three maps.
"""

from __future__ import annotations

import math
from typing import TypeAlias

import numpy as np
import numpy.typing as npt

from .energy import spring_energy_core
from .exprel import chi, log1p_ratio, phi1, phi2, phi12, psi
from .jit import njit

# The kernels' array and tuple arguments, for annotations (numba compiles from the values passed)
FloatArray: TypeAlias = npt.NDArray[np.float64]
IntArray: TypeAlias = npt.NDArray[np.int64]
BoolArray: TypeAlias = npt.NDArray[np.bool_]
SampleConstants: TypeAlias = tuple[float, float, float, float, float, float]  # sample_constants
# The grouped arguments of the entry points (simulate_kernel, serial_kernel, dfa.core.batch, dfa.core.wall_kernel):
Device: TypeAlias = tuple[float, float, float]  # (μ, β, σ) of one run
Start: TypeAlias = tuple[float, float]  # (ξ0, ξ'0) of one run, ticks and ticks per sample
RunSettings: TypeAlias = tuple[int, int, float, bool]  # (n samples, tail length, bound |ξ| in ticks, quantize)
Devices: TypeAlias = tuple[FloatArray, FloatArray, FloatArray]  # (μ, β, σ) of many runs, one array each
Starts: TypeAlias = tuple[FloatArray, FloatArray]  # (ξ0, ξ'0) of many runs
BatchRuns: TypeAlias = tuple[IntArray, IntArray, FloatArray, bool]  # per run (n, tail length, bound); one quantize
Rules: TypeAlias = tuple[float, float, float]  # the outcome rules (stable amplitude, growth, settle) of classify
Outcomes: TypeAlias = tuple[IntArray, FloatArray, FloatArray, FloatArray, FloatArray]  # classify_batch's outputs
# The grouped arguments of the resumable steps (advance, finish) and of energy_terms:
Records: TypeAlias = tuple[FloatArray, FloatArray, FloatArray]  # (ξ, ξ' per instant: n + 1; energy terms: n × 4)
Keep: TypeAlias = tuple[bool, bool]  # (record ξ and ξ', record the energy terms): which Records are written
Phases: TypeAlias = tuple[float, float, float, float, float]  # (ξ_r, t*, a, a₂, t_r) of one sample (step's)

# outcome codes (also the codes of dfa.analysis.maps.StabilityMap.outcome and its .npz file)
REST = 0  # came to rest: the absorbing state was reached
OSCILLATING = 1  # persistent, settled cycle of amplitude >= stable_amplitude (1 tick)
UNSTABLE = 2  # |ξ| beyond the bound, or a growing envelope
CHATTER = 3  # never rested; persistent, settled cycle below stable_amplitude
UNDECIDED = 4  # the envelope is still changing at the end of the run: run longer
LEFT = 5  # a one-sided wall left for good: outside, moving away, nothing can bring the device back
SATURATED = 6  # bounded, never rested, the actuator's force limit reached in the tail (dfa.model.elements.ForceLimit)
END_STOP = 7  # past the device's travel: the run ended at an end stop (dfa.core.wall_kernel, flag 3)

NSEG = 8  # segments of the run used to judge a growing or changing envelope
#: stats[SATURATION]: the wall kernel's force-limit flag (0 never reached, 1 reached before the tail only, 2 reached
#: in the tail; always 0 for the spring's kernel, which has no force limit)
SATURATION = NSEG + 10
NSTATS = NSEG + 11  # length of the stats array of simulate_kernel


_spring = njit(cache=True, inline="always")(spring_energy_core)  # H_c (eq. 18): criterion's one formula


# ----------------------------------------------------------------------------- the steps of one sample


@njit(cache=True, inline="always")
def force(x: float, quantize: bool) -> float:
    """Force read from position ``x``: −⌊ξ⌋ − ½ with the encoder, −ξ without (units of KΔ)."""
    return -(math.floor(x) + 0.5) if quantize else -x


@njit(cache=True, inline="always")
def delayed_force(fnew: float, hist: FloatArray, pos: int, delay: int) -> tuple[float, int]:
    """Push this sample's reading into the ring ``hist`` (length d + 1); return (φ, new pos).

    ``hist[pos]`` holds the oldest reading; φ is the reading of d samples ago.
    """
    if delay == 0:
        return fnew, pos
    hist[pos] = fnew
    pos += 1
    if pos == delay + 1:
        pos = 0
    return hist[pos], pos


@njit(cache=True, inline="always")
def at_rest(v: float, phi: float, sigma: float, hist: FloatArray, delay: int) -> bool:
    """The absorbing state: stuck (ξ' = 0, |φ| <= σ) and every pending force equal to φ."""
    if v != 0.0 or not abs(phi) <= sigma:
        return False
    for i in range(delay):  # delay + 1 readings; with d = 0 the only one is φ
        if hist[i] != phi or hist[i + 1] != phi:
            return False
    return True


@njit(cache=True, inline="always")
def sample_constants(mu: float, beta: float) -> SampleConstants:
    """Per-run constants of :func:`step`: (β/μ, e^{−β/μ}, φ₁(β/μ), φ₂(β/μ), φ₁/μ, φ₂/μ)."""
    rate = beta / mu
    p1 = phi1(rate)
    p2 = phi2(rate)
    return rate, math.exp(-rate), p1, p2, p1 / mu, p2 / mu


@njit(cache=True, inline="always")
def step(
    x: float, v: float, phi: float, mu: float, sigma: float, k: SampleConstants
) -> tuple[float, float, float, float, float, float, float, bool]:
    """Exact motion over one sample under the constant force φ (stick-slip included).

    ``k`` is :func:`sample_constants`. Returns (ξ, ξ' at the end; ξ_r, the
    position where ξ' reached 0 (the end position when it did not); t*, that
    time (1: no stop, 0: stuck all along); a, the first phase's acceleration;
    a₂, t_r, the restart phase's acceleration and duration (0, 0: no restart);
    stopped). Over a whole sample ξ gains ξ'φ₁ + (F/μ)φ₂ with F = φ − σ s,
    summed as (ξ + ξ'φ₁ − σ s φ₂/μ) + φ φ₂/μ so that the reading φ, the end of
    the chain ⌊ξ⌋ → φ, meets one product and one sum (the divisions by μ are in ``k``).
    """
    rate, e1, p1, p2, q1, q2 = k
    if v == 0.0 and abs(phi) <= sigma:
        return x, v, x, 0.0, 0.0, 0.0, 0.0, False  # stuck for the whole sample (ξ' = ±0 kept)
    s = 1.0 if (v > 0.0 or (v == 0.0 and phi > 0.0)) else -1.0
    ss = sigma * s
    f = phi - ss
    a = f / mu
    x1 = (x + v * p1 - ss * q2) + phi * q2  # the reading φ enters last: the chain ⌊ξ⌋ → φ → ξ is one product, one sum
    v1 = (v * e1 - ss * q1) + phi * q1
    if v1 * s > 0.0 or v == 0.0 or a == 0.0:  # a = 0: ξ' decays without crossing (may underflow to 0)
        return x1, v1, x1, 1.0, a, 0.0, 0.0, False
    # velocity reaches zero at t* within this sample: with w = −ξ'μ/F (t* at β = 0) and y = w β/μ >= 0,
    # t* = (μ/β) log1p(y) = w λ(y) (λ: log1p_ratio; one division on the chain, series at small y)
    w = -v / f * mu
    y = w * rate
    tstar = w * (log1p_ratio(y) if y > 0.0 else 1.0)  # y <= 0: only when ξ' and F underflow (as before)
    if tstar > 1.0:
        tstar = 1.0  # rounding guard: v1 * s <= 0 means t* <= 1
    f1, f2 = phi12(rate * tstar)
    xr = x + v * tstar * f1 + a * tstar * tstar * f2
    tr = 1.0 - tstar
    if abs(phi) > sigma and tr > 0.0:  # restarts in direction sgn φ; cannot stop again within the sample
        s2 = 1.0 if phi > 0.0 else -1.0
        a2 = (phi - sigma * s2) / mu
        g1, g2 = phi12(rate * tr)
        return xr + a2 * tr * tr * g2, a2 * tr * g1, xr, tstar, a, a2, tr, True
    return xr, 0.0, xr, tstar, a, 0.0, 0.0, True


@njit(cache=True, inline="always")
def viscous(v: float, a: float, beta: float, mu: float, t: float) -> float:
    """β ∫₀ᵗ ξ'² dt for one phase starting at speed v with acceleration a."""
    if beta == 0.0:
        return 0.0
    u = beta * t / mu
    return beta * (v * v * t * phi1(2.0 * u) + 2.0 * v * a * t * t * psi(u) + a * a * t * t * t * chi(u))


@njit(cache=True, inline="always")
def energy_terms(
    xs: float, vs: float, x: float, v: float, phi: float, phases: Phases, device: Device, quantize: bool
) -> tuple[float, float, float, float]:
    """(generated, viscous, Coulomb, stored) of one sample from (ξs, ξ's) to (ξ, ξ') (eq. 18-23).

    ``phases`` = (ξ_r, t*, a, a₂, t_r) of the sample (:func:`step`'s), ``device`` = (μ, β, σ).
    """
    xr, tstar, a, a2, tr = phases
    mu, beta, sigma = device
    dvisc = viscous(vs, a, beta, mu, tstar) if tstar > 0.0 else 0.0
    dcoul = sigma * abs(xr - xs) if tstar > 0.0 else 0.0
    if tr > 0.0:
        dvisc += viscous(0.0, a2, beta, mu, tr)
        dcoul += sigma * abs(x - xr)
    dx = x - xs
    # generated = ∫(φ + q(ξ))ξ' dτ = φΔξ + ΔH_c   (eq. 20-23)
    gen = phi * dx + (_spring(x, True) - _spring(xs, True)) if quantize else phi * dx + 0.5 * (x * x - xs * xs)
    return gen, dvisc, dcoul, 0.5 * mu * v * v + _spring(x, quantize)


@njit(cache=True, inline="always")
def tail_extremes(x: float, xr: float, stopped: bool, tmin: float, tmax: float) -> tuple[float, float]:
    """Tail min and max updated with the sample's end position and, if ξ' reached 0 inside it, the turning point."""
    if stopped:
        if xr < tmin:
            tmin = xr
        if xr > tmax:
            tmax = xr
    if x < tmin:
        tmin = x
    if x > tmax:
        tmax = x
    return tmin, tmax


@njit(cache=True, inline="always")
def free_sample(
    x: float, v: float, peak: float, mu: float, sigma: float, quantize: bool, bound: float, k: SampleConstants
) -> tuple[float, float, float, int, float, bool]:
    """One unrecorded sample without delay: the body of :func:`advance_free`.

    Returns (ξ, ξ', peak |ξ|, why, ξ_r, stopped) (ξ_r, stopped: :func:`step`'s):
    why = 0 integrated, 1 at rest (not integrated: with d = 0 the absorbing
    state is ξ' = 0, |φ| <= σ), 2 past ``bound`` (or NaN). The same operations
    as :func:`advance`'s loop with d = 0.
    """
    phi = force(x, quantize)
    if v == 0.0 and abs(phi) <= sigma:
        return x, v, peak, 1, x, False
    x, v, xr, tstar, a, a2, tr, stopped = step(x, v, phi, mu, sigma, k)
    ax = abs(x)
    if ax > peak:
        peak = ax
    if not ax <= bound:  # also catches NaN
        return x, v, peak, 2, xr, stopped
    return x, v, peak, 0, xr, stopped


@njit(cache=True, inline="always")
def same_state(x: float, v: float, rx: float, rv: float) -> bool:
    """(ξ, ξ') equals (rx, rv) bit for bit (so ±0 differ; NaN never equals)."""
    return (
        x == rx
        and v == rv
        and math.copysign(1.0, x) == math.copysign(1.0, rx)
        and math.copysign(1.0, v) == math.copysign(1.0, rv)
    )


@njit(cache=True, nogil=True)
def advance_free(
    state: FloatArray,
    h0: int,
    h1: int,
    mu: float,
    sigma: float,
    quantize: bool,
    bound: float,
    k: SampleConstants,
    tail: FloatArray,
    tail_start: int,
) -> tuple[int, int, float]:
    """:func:`advance` over samples h0 … h1 − 1 without delay, unrecorded (the hot path).

    The range lies before the tail (h1 <= ``tail_start``) or in it (h0 >= ``tail_start``).
    With d = 0 the state of the loop is (ξ, ξ') alone, so once it repeats bit
    for bit after P samples the run repeats those P samples for ever (no exit
    among them, or it would have stopped): whole periods up to h1 are skipped,
    found by Brent's cycle detection (a reference state renewed at doubling
    intervals). The reference lies in this range, so a skipped period's peak
    and tail extremes are already counted; its tail readings are copied. Same
    results bit for bit as integrating every sample.
    """
    x, v, tmin, tmax = state[SX], state[SV], state[STMIN], state[STMAX]
    peak = 0.0
    in_tail = h0 >= tail_start
    rx, rv, rh, span = x, v, h0, 1  # reference state, its sample, renewal interval
    h = h0
    why = 0
    while h < h1:
        x, v, peak, why, xr, stopped = free_sample(x, v, peak, mu, sigma, quantize, bound, k)
        if why == 1:
            break
        if in_tail:
            tail[h - tail_start] = x
            tmin, tmax = tail_extremes(x, xr, stopped, tmin, tmax)
        h += 1
        if why == 2:
            break
        if same_state(x, v, rx, rv):  # period h − rh: skip the whole periods left in this range
            skip = (h1 - h) // (h - rh) * (h - rh)
            if in_tail:
                for i in range(h, h + skip):
                    tail[i - tail_start] = tail[i - (h - rh) - tail_start]
            h += skip
            span = h1  # no more renewals: fewer than one period is left
        elif h - rh == span:
            rx, rv, rh, span = x, v, h, 2 * span
    state[SX], state[SV], state[STMIN], state[STMAX] = x, v, tmin, tmax
    return h, why, peak


# ----------------------------------------------------------------------------- a run, in ranges of samples

# state array of a run: ξ, ξ', ring position, tail min, tail max
SX, SV, SPOS, STMIN, STMAX = 0, 1, 2, 3, 4
NSTATE = 5


@njit(cache=True, nogil=True)
def start(
    x0: float, v0: float, delay: int, quantize: bool, state: FloatArray, hist: FloatArray, stats: FloatArray
) -> None:
    """Initial state of a run: (ξ0, ξ'0), past readings equal to ξ0's, stats cleared."""
    f0 = force(x0, quantize)
    for i in range(delay + 1):
        hist[i] = f0
    for i in range(stats.shape[0]):
        stats[i] = 0.0
    state[SX] = x0
    state[SV] = v0
    state[SPOS] = 0.0
    state[STMIN] = np.inf
    state[STMAX] = -np.inf


@njit(cache=True, nogil=True)
def advance(
    state: FloatArray,
    hist: FloatArray,
    h0: int,
    h1: int,
    device: Device,
    run: RunSettings,
    delay: int,
    tail: FloatArray,
    records: Records,
    keep: Keep,
) -> tuple[int, int, float]:
    """Run samples h0 … h1 − 1 from ``state``; return (end, why, peak).

    ``device`` = (μ, β, σ), ``run`` = (n, tail length, bound, quantize) (:data:`RunSettings`), ``delay`` d in
    samples, ``records`` = (rec_x, rec_v, rec_e), ``keep`` = (record, energy).
    why = 0: ran through (end = h1); 1: at rest at sample ``end`` (not
    integrated); 2: |ξ| passed ``bound`` (or NaN) in sample end − 1. ``peak``
    is the largest |ξ| at the sample instants h0 + 1 … end. Samples at or
    after the tail's start (n − tail length) also update the tail (``tail``, min and max with the
    turning points). With ``record``, ξ and ξ' after sample h go to
    ``rec_x[h + 1]``/``rec_v[h + 1]``; with ``energy``, its energy terms to
    ``rec_e[h]`` (generated, viscous, Coulomb, stored).
    """
    mu, beta, sigma = device
    n, tail_len, bound, quantize = run
    rec_x, rec_v, rec_e = records
    record, energy = keep
    tail_start = n - tail_len
    k = sample_constants(mu, beta)
    if delay == 0 and not record and not energy and (h1 <= tail_start or h0 >= tail_start):
        return advance_free(state, h0, h1, mu, sigma, quantize, bound, k, tail, tail_start)
    x = state[SX]
    v = state[SV]
    pos = int(state[SPOS])
    tmin = state[STMIN]
    tmax = state[STMAX]
    peak = 0.0
    end = h1
    why = 0
    for h in range(h0, h1):
        phi, pos = delayed_force(force(x, quantize), hist, pos, delay)
        if v == 0.0 and at_rest(v, phi, sigma, hist, delay):
            end = h
            why = 1
            break
        xs = x
        vs = v
        x, v, xr, tstar, a, a2, tr, stopped = step(x, v, phi, mu, sigma, k)
        if record:
            rec_x[h + 1] = x
            rec_v[h + 1] = v
        if energy:
            g, dv, dc, st = energy_terms(xs, vs, x, v, phi, (xr, tstar, a, a2, tr), device, quantize)
            rec_e[h, 0] = g
            rec_e[h, 1] = dv
            rec_e[h, 2] = dc
            rec_e[h, 3] = st
        ax = abs(x)
        if ax > peak:
            peak = ax
        if h >= tail_start:
            tail[h - tail_start] = x
            tmin, tmax = tail_extremes(x, xr, stopped, tmin, tmax)
        if not ax <= bound:  # also catches NaN
            end = h + 1
            why = 2
            break
    state[SX] = x
    state[SV] = v
    state[SPOS] = pos
    state[STMIN] = tmin
    state[STMAX] = tmax
    return end, why, peak


@njit(cache=True, inline="always")
def segment_bounds(k: int, n: int) -> tuple[int, int]:
    """First and one-past-last sample of the k-th of NSEG segments of a run of n samples."""
    return (k * n + NSEG - 1) // NSEG, ((k + 1) * n + NSEG - 1) // NSEG


@njit(cache=True, inline="always")
def segment_ranges(k: int, n: int, tail_start: int) -> tuple[int, int, int]:
    """(lo, cut, hi): the k-th segment [lo, hi) of a run cut where the tail starts, its two ranges [lo, cut) and
    [cut, hi) (either may be empty): the ranges every kernel runs a run in (one implementation)."""
    lo, hi = segment_bounds(k, n)
    return lo, min(max(lo, tail_start), hi), hi


@njit(cache=True, inline="always")
def tail_stats(tail: FloatArray, tail_len: int, tmin: float, tmax: float, stats: FloatArray) -> None:
    """Crossings of the tail's centre level (interpolated), its extremes and instant extremes into ``stats``."""
    centre = 0.5 * (tmin + tmax)
    count = 0
    first = 0.0
    last = 0.0
    smin = tail[0]
    smax = tail[0]
    for i in range(1, tail_len):
        if tail[i] < smin:
            smin = tail[i]
        if tail[i] > smax:
            smax = tail[i]
        y0 = tail[i - 1] - centre
        y1 = tail[i] - centre
        if y0 < 0.0 and y1 >= 0.0:
            t = (i - 1) + y0 / (y0 - y1)
            if count == 0:
                first = t
            last = t
            count += 1
    stats[NSEG] = tmin
    stats[NSEG + 1] = tmax
    stats[NSEG + 2] = count
    stats[NSEG + 3] = first
    stats[NSEG + 4] = last
    stats[NSEG + 8] = smin
    stats[NSEG + 9] = smax


@njit(cache=True, nogil=True)
def finish(
    state: FloatArray,
    done: int,
    rest: int,
    mu: float,
    run: RunSettings,
    tail: FloatArray,
    stats: FloatArray,
    records: Records,
    keep: Keep,
) -> None:
    """Tail statistics, final state, and the records past an early stop (rest state, or NaN).

    ``done``, ``rest`` as :func:`simulate_kernel` returns them, ``mu`` μ, ``run`` = (n, tail length, bound,
    quantize) (:data:`RunSettings`), ``records`` = (rec_x, rec_v, rec_e), ``keep`` = (record, energy).
    """
    n, tail_len, _, quantize = run
    rec_x, rec_v, rec_e = records
    record, energy = keep
    x = state[SX]
    v = state[SV]
    if done == n and rest < 0 and tail_len > 1:
        tail_stats(tail, tail_len, state[STMIN], state[STMAX], stats)
    stats[NSEG + 6] = x
    stats[NSEG + 7] = v
    if record and done < n:
        for i in range(done + 1, n + 1):
            rec_x[i] = x if rest >= 0 else np.nan
            rec_v[i] = v if rest >= 0 else np.nan
    if energy and done < n:
        stored = (0.5 * mu * v * v + _spring(x, quantize)) if rest >= 0 else np.nan
        fill = 0.0 if rest >= 0 else np.nan
        for i in range(done, n):
            rec_e[i, 0] = fill
            rec_e[i, 1] = fill
            rec_e[i, 2] = fill
            rec_e[i, 3] = stored


@njit(cache=True, nogil=True)
def simulate_kernel(
    device: Device,
    initial: Start,
    run: RunSettings,
    delay: int,
    rec_x: FloatArray,
    rec_v: FloatArray,
    rec_e: FloatArray,
    stats: FloatArray,
) -> tuple[int, int]:
    """Run ``n`` samples; return the number of samples done and the rest sample (−1: none).

    ``device`` = (μ, β, σ), ``initial`` = (ξ0, ξ'0) (ticks, ticks per sample), ``run`` = (n, tail length,
    bound, quantize) (:data:`RunSettings`), ``delay`` d in samples. ``rec_x``/``rec_v`` (length n + 1) and
    ``rec_e`` (n × 4: generated, viscous, Coulomb, stored energy at the end of the sample) are written only
    when they have that length; pass empty arrays otherwise. ``stats`` (length
    NSTATS) receives the segment peaks of |ξ| (at the sample instants), then
    the tail's min, max (turning points inside samples included),
    centre-crossing count, first and last crossing time, a flag for
    exceeding ``bound``, the final ξ and ξ', and the tail's min and max of ξ
    at the sample instants (the readings that set the force).

    The run is :func:`start`, :func:`advance` over each segment (split where
    the tail starts), :func:`finish`: callers may run any ranges of samples.
    """
    mu = device[0]
    x0, v0 = initial
    n, tail_len, _, quantize = run
    record = rec_x.shape[0] == n + 1
    energy = rec_e.shape[0] == n
    records = (rec_x, rec_v, rec_e)
    keep = (record, energy)
    state = np.empty(NSTATE)
    hist = np.empty(delay + 1)
    tail = np.empty(max(tail_len, 1))
    start(x0, v0, delay, quantize, state, hist, stats)
    if record:
        rec_x[0] = x0
        rec_v[0] = v0
    tail_start = n - tail_len
    done = n
    rest = -1
    for k in range(NSEG):
        lo, cut, hi = segment_ranges(k, n, tail_start)
        why = 0
        for a, b in ((lo, cut), (cut, hi)):
            if b > a:
                end, why, peak = advance(state, hist, a, b, device, run, delay, tail, records, keep)
                if peak > stats[k]:
                    stats[k] = peak
                if why != 0:
                    done = end
                    rest = end if why == 1 else -1
                    if why == 2:
                        stats[NSEG + 5] = 1.0
                    break
        if why != 0:
            break
    finish(state, done, rest, mu, run, tail, stats, records, keep)
    return done, rest


@njit(cache=True, nogil=True)
def classify(
    n: int,
    done: int,
    rest: int,
    stats: FloatArray,
    stable_amplitude: float,
    growth: float,
    settle: float,
    quantize: bool,
    mu: float,
) -> tuple[int, float, float, float, float]:
    """Outcome code, amplitude, frequency, centre and force peak-to-peak of a run from its stats.

    In this order (``P_k``: peak |ξ| at the sample instants in the k-th eighth of the run):

    * rest: the kernel reached the absorbing state (``rest >= 0``);
    * left: the device left a one-sided wall for good (flag 2 in ``stats[NSEG + 5]``);
    * end stop: the device passed its travel ±ξ_travel, within the bound (flag 3 in ``stats[NSEG + 5]``: the
      controller kernel's exit test, or :func:`dfa.analysis.simulation.mark_end_stops` after this kernel's run
      with the travel as its bound);
    * a one-sided wall's run (flag −1) is unstable only past the bound: a growing envelope is undecided, as
      its bounces carry the device away from the wall and back while its storage stays bounded (a run too
      short to see it return or stop is no divergence);
    * saturated: within the bound, the actuator's force limit was reached in the tail (flag 2 in
      ``stats[SATURATION]``; :class:`dfa.model.elements.ForceLimit`): a large motion held by the actuator, whatever
      the envelope (a limit touched only before the tail leaves the outcome to the rules below);
    * unstable: |ξ| exceeded the bound, or the envelope grows: P_7 exceeds
      ``growth`` times P_4 and 1 tick, and P_4 <= P_5 <= P_6 <= P_7, in a run
      of at least 8 periods 2π√μ (shorter runs are never called unstable by
      the envelope: they are undecided);
      without quantization (the linear loop, which has no tick scale) the
      1-tick floor is dropped, and an envelope that shrinks the same way
      (P_4 > ``growth`` P_7, or P_7 <= 1e-12 P_0, with P_4 >= P_5 >= P_6 >= P_7) is rest: it decays to
      rest geometrically and never reaches it exactly;
    * undecided: the envelope has not settled: max − min of P_5, P_6, P_7
      exceeds ``settle`` times their max, or the tail holds less than one
      full cycle (fewer than two upward crossings of its centre);
    * chatter: settled, amplitude (half the tail's peak-to-peak, turning
      points included) below ``stable_amplitude`` ticks;
    * oscillating: settled, amplitude of ``stable_amplitude`` or more.

    The force peak-to-peak (units of KΔ) is (max − min) of ⌊ξ⌋ over the
    tail's sample instants, or of ξ itself without quantization.
    """
    freq = np.nan
    if rest >= 0:
        return REST, 0.0, np.nan, 0.0, 0.0
    if stats[NSEG + 5] == 2.0:  # the controller kernel's exit from a one-sided wall (dfa.core.wall_kernel._gone)
        return LEFT, 0.0, np.nan, 0.0, 0.0
    if stats[NSEG + 5] == 3.0:  # an end stop: the device's travel, not the loop, ended the run
        return END_STOP, 0.0, np.nan, 0.0, 0.0
    if stats[NSEG + 5] > 0.0:
        return UNSTABLE, np.inf, np.nan, 0.0, np.inf
    tmin = stats[NSEG]
    tmax = stats[NSEG + 1]
    amp = 0.5 * (tmax - tmin)
    centre = 0.5 * (tmax + tmin)
    if quantize:
        fpp = math.floor(stats[NSEG + 9]) - math.floor(stats[NSEG + 8])
    else:
        fpp = stats[NSEG + 9] - stats[NSEG + 8]
    count = stats[NSEG + 2]
    if count >= 2 and stats[NSEG + 4] > stats[NSEG + 3]:
        freq = 2.0 * math.pi * (count - 1) / (stats[NSEG + 4] - stats[NSEG + 3])
    # without quantization the loop is linear and has no tick scale: growth needs no 1-tick floor.
    # The envelope rules need every eighth of the run to hold a full period 2π√μ of the spring:
    # within the first quarter-period |ξ| rises from the impact whatever the loop does.
    if stats.shape[0] > SATURATION and stats[SATURATION] >= 2.0:
        return SATURATED, amp, freq, centre, fpp
    long_enough = n >= NSEG * 2.0 * math.pi * math.sqrt(mu)
    grow = long_enough and stats[NSEG - 1] > growth * stats[NSEG // 2] and (stats[NSEG - 1] > 1.0 or not quantize)
    decay = (
        long_enough
        and not quantize
        and (stats[NSEG - 1] * growth < stats[NSEG // 2] or stats[NSEG - 1] <= 1e-12 * stats[0])
    )  # decayed to denormals
    for i in range(NSEG - 4, NSEG - 1):
        if stats[i + 1] < stats[i]:
            grow = False
        if stats[i + 1] > stats[i]:
            decay = False
    if grow:
        return (UNDECIDED if stats[NSEG + 5] < 0.0 else UNSTABLE), amp, freq, centre, fpp
    if decay:  # linear loop: the envelope shrinks geometrically, i.e. it decays to rest
        return REST, amp, freq, centre, fpp
    hi = max(stats[NSEG - 3], stats[NSEG - 2], stats[NSEG - 1])
    lo = min(stats[NSEG - 3], stats[NSEG - 2], stats[NSEG - 1])
    if hi - lo > settle * hi or not count >= 2:
        return UNDECIDED, amp, freq, centre, fpp
    if amp < stable_amplitude:
        return CHATTER, amp, freq, centre, fpp
    return OSCILLATING, amp, freq, centre, fpp


@njit(cache=True, nogil=True)
def classify_batch(
    mus: FloatArray,
    ns: IntArray,
    done: IntArray,
    rest: IntArray,
    stats: FloatArray,
    rules: Rules,
    quantize: bool,
    out: Outcomes,
) -> None:
    """:func:`classify` for every run of a batch, run i of ``ns[i]`` samples (outputs written in place).

    ``rules`` = (stable amplitude, growth, settle) of :func:`classify`; ``out`` = (codes, amplitudes,
    frequencies, centres, force peak-to-peaks), one array each, receives its outputs run by run.
    """
    stable_amplitude, growth, settle = rules
    codes, amps, freqs, centres, fpps = out
    for i in range(mus.shape[0]):
        c, a, f, ce, fp = classify(
            ns[i], done[i], rest[i], stats[i], stable_amplitude, growth, settle, quantize, mus[i]
        )
        codes[i] = c
        amps[i] = a
        freqs[i] = f
        centres[i] = ce
        fpps[i] = fp


@njit(cache=True, nogil=True)
def serial_kernel(
    devices: Devices,
    initials: Starts,
    run: RunSettings,
    delay: int,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
) -> None:
    """Independent runs, one after the other; nothing recorded.

    Run i has (μ, β, σ) = (``devices[0][i]``, …) and (ξ0, ξ'0) = (``initials[0][i]``, ``initials[1][i]``);
    every run has the settings ``run`` and the delay ``delay`` (:func:`simulate_kernel`). ``stats[i]``
    (NSTATS), ``done[i]`` and ``rest[i]`` receive what :func:`simulate_kernel`
    returns for it. :func:`dfa.core.batch.batch_kernel` runs runs of different
    lengths, bounds and tails, two in flight and bit for bit the same (about
    0.8 of this loop's time on map points; four in registers,
    ``benchmarks/lanes_kernel.py``, took more).
    """
    mus, betas, sigmas = devices
    x0s, v0s = initials
    empty = np.empty(0)
    empty2 = np.empty((0, 4))
    for i in range(mus.shape[0]):
        done[i], rest[i] = simulate_kernel(
            (mus[i], betas[i], sigmas[i]), (x0s[i], v0s[i]), run, delay, empty, empty, empty2, stats[i]
        )
