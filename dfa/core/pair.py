"""Independent runs of the exact simulator, two in flight, bit for bit one at a time (issue 16).

:func:`dfa.core.batch.batch_kernel` (stability maps, ``simulate_batch``, the K_max searches) is :func:`pair_kernel`.
Measured against :func:`dfa.core.kernel.serial_kernel` (one run after the other) in ``benchmarks/run.py``
(``reports/benchmarks.md``): once a stop inside a sample became a short chain of multiply-adds
(:func:`dfa.core.exprel.phi12`), chattering runs, which stop in nearly every sample, are bound by their chain's
latency, and two runs in flight take about 0.8 of the serial time on the points of a stability map (before
that change, 0.93-0.99: a sample was then bound by the instructions it issues).

One run's sample is a chain read → force → update (:mod:`dfa.core.kernel`)
whose latency, not its arithmetic, bounds a single trajectory. Two
independent runs advanced in the same loop (:func:`advance_pair`, the loop
of :func:`dfa.core.kernel.advance_free` written out for two runs, each in its own
local scalars) let the processor overlap their chains: measured at about
0.7 × the time of the two runs one after the other on chattering and
oscillating runs (a bare loop; see above). Four runs gain no
more on the development machine (their branch mispredictions at the stops
flush every run's work alike), so the batch is two.

:func:`pair_kernel` runs a list of independent runs, each with its own
length, bound and tail, with outputs bit for bit those of
:func:`dfa.core.kernel.simulate_kernel` for each run alone: without delay it keeps two runs in flight
("lanes"), each walking the ranges of samples of
:func:`dfa.core.kernel.simulate_kernel` (the envelope's eighths, split where the
tail starts). :func:`advance_pair` runs both lanes until either's range ends
(or its run comes to rest or passes the bound); that lane books its range's
peak and takes its next range or, when its run is over, the next run. The
other lane resumes where it stopped. Each lane runs exactly the operations of
:func:`dfa.core.kernel.advance_free`, in the same order; only the exact skip of
repeated periods restarts its cycle detection when a lane resumes, which
changes when a period is skipped, never a result (``tests/test_batch_kernel.py``).
Runs with a delay pair the same way (:func:`advance_pair_delayed`, the loop of
:func:`dfa.core.kernel.advance`, each run with its ring of pending readings).
"""

from __future__ import annotations

import numpy as np

from .jit import njit
from .kernel import (
    NSEG,
    NSTATE,
    SPOS,
    STMAX,
    STMIN,
    SV,
    SX,
    BatchRuns,
    Devices,
    FloatArray,
    IntArray,
    SampleConstants,
    Starts,
    advance,
    advance_free,
    at_rest,
    delayed_force,
    finish,
    force,
    free_sample,
    same_state,
    sample_constants,
    segment_ranges,
    start,
    step,
    tail_extremes,
)

__all__ = ["advance_pair", "advance_pair_delayed", "pair_delayed_kernel", "pair_free_kernel", "pair_kernel"]

# integer state of a lane: run index (-1: none), segment, part (0: before the tail, 1: in it), next sample, range end,
# the run's length and where its tail starts
PT, SEG, PART, H, END, N, TAIL = 0, 1, 2, 3, 4, 5, 6
NLANE = 7


@njit(cache=True, nogil=True)
def advance_pair(
    sa: FloatArray,
    ha: int,
    h1a: int,
    mua: float,
    siga: float,
    ka: SampleConstants,
    taila: FloatArray,
    bounda: float,
    ta: int,
    sb: FloatArray,
    hb: int,
    h1b: int,
    mub: float,
    sigb: float,
    kb: SampleConstants,
    tailb: FloatArray,
    boundb: float,
    tb: int,
    quantize: bool,
) -> tuple[int, int, float, bool, int, int, float, bool]:
    """:func:`dfa.core.kernel.advance_free` of two runs A and B at once, until either's range ends.

    ``sa``/``sb`` are the runs' state arrays (ξ, ξ', tail min and max), ``ha … h1a`` and ``hb … h1b``
    their ranges of samples (each wholly before the tail or in it), ``ka``/``kb`` their
    :func:`dfa.core.kernel.sample_constants`, ``bounda``/``boundb`` their bounds and ``ta``/``tb`` the samples
    where their tails start. Returns (h, why, peak, ended) of A then of B: the next sample,
    :func:`dfa.core.kernel.advance_free`'s ``why``, the peak |ξ| of the samples run here, and whether the range
    ended (ran through, at rest, or past the bound); at least one of the two ended.
    """
    xa, va, tmina, tmaxa = sa[SX], sa[SV], sa[STMIN], sa[STMAX]
    xb, vb, tminb, tmaxb = sb[SX], sb[SV], sb[STMIN], sb[STMAX]
    pa = pb = 0.0
    ina, inb = ha >= ta, hb >= tb
    rxa, rva, rha, spana = xa, va, ha, 1  # Brent's reference state of each run (dfa.core.kernel.advance_free)
    rxb, rvb, rhb, spanb = xb, vb, hb, 1
    wa = wb = 0
    fa = fb = False
    while not (fa or fb):
        xa, va, pa, wa, xra, sta = free_sample(xa, va, pa, mua, siga, quantize, bounda, ka)
        if wa == 1:
            fa = True
        else:
            if ina:
                taila[ha - ta] = xa
                tmina, tmaxa = tail_extremes(xa, xra, sta, tmina, tmaxa)
            ha += 1
            if wa == 2:
                fa = True
            elif same_state(xa, va, rxa, rva):
                skip = (h1a - ha) // (ha - rha) * (ha - rha)
                if ina:
                    for i in range(ha, ha + skip):
                        taila[i - ta] = taila[i - (ha - rha) - ta]
                ha += skip
                spana = h1a
            elif ha - rha == spana:
                rxa, rva, rha, spana = xa, va, ha, 2 * spana
            fa = fa or ha >= h1a
        xb, vb, pb, wb, xrb, stb = free_sample(xb, vb, pb, mub, sigb, quantize, boundb, kb)
        if wb == 1:
            fb = True
        else:
            if inb:
                tailb[hb - tb] = xb
                tminb, tmaxb = tail_extremes(xb, xrb, stb, tminb, tmaxb)
            hb += 1
            if wb == 2:
                fb = True
            elif same_state(xb, vb, rxb, rvb):
                skip = (h1b - hb) // (hb - rhb) * (hb - rhb)
                if inb:
                    for i in range(hb, hb + skip):
                        tailb[i - tb] = tailb[i - (hb - rhb) - tb]
                hb += skip
                spanb = h1b
            elif hb - rhb == spanb:
                rxb, rvb, rhb, spanb = xb, vb, hb, 2 * spanb
            fb = fb or hb >= h1b
    sa[SX], sa[SV], sa[STMIN], sa[STMAX] = xa, va, tmina, tmaxa
    sb[SX], sb[SV], sb[STMIN], sb[STMAX] = xb, vb, tminb, tmaxb
    return ha, wa, pa, fa, hb, wb, pb, fb


@njit(cache=True, nogil=True)
def advance_pair_delayed(
    sa: FloatArray, ha: int, h1a: int, mua: float, siga: float, ka: SampleConstants,
    taila: FloatArray, bounda: float, ta: int, hista: FloatArray,
    sb: FloatArray, hb: int, h1b: int, mub: float, sigb: float, kb: SampleConstants,
    tailb: FloatArray, boundb: float, tb: int, histb: FloatArray,
    delay: int, quantize: bool,
) -> tuple[int, int, float, bool, int, int, float, bool]:  # fmt: skip
    """:func:`dfa.core.kernel.advance` (no records) of two runs with a delay of ``delay`` samples, until either's range ends.

    As :func:`advance_pair`, with each run's ring of pending readings (``hista``, ``histb``; its position in the
    state array); nothing is skipped. Returns (h, why, peak, ended) of A then of B.
    """
    xa, va, pa_, tmina, tmaxa = sa[SX], sa[SV], int(sa[SPOS]), sa[STMIN], sa[STMAX]
    xb, vb, pb_, tminb, tmaxb = sb[SX], sb[SV], int(sb[SPOS]), sb[STMIN], sb[STMAX]
    pka = pkb = 0.0
    wa = wb = 0
    fa = fb = False
    while not (fa or fb):
        phia, pa_ = delayed_force(force(xa, quantize), hista, pa_, delay)
        if va == 0.0 and at_rest(va, phia, siga, hista, delay):
            wa, fa = 1, True
        else:
            xa, va, xra, _t, _a, _a2, _tr, sta = step(xa, va, phia, mua, siga, ka)
            axa = abs(xa)
            if axa > pka:
                pka = axa
            if ha >= ta:
                taila[ha - ta] = xa
                tmina, tmaxa = tail_extremes(xa, xra, sta, tmina, tmaxa)
            ha += 1
            if not axa <= bounda:  # also catches NaN
                wa, fa = 2, True
            fa = fa or ha >= h1a
        phib, pb_ = delayed_force(force(xb, quantize), histb, pb_, delay)
        if vb == 0.0 and at_rest(vb, phib, sigb, histb, delay):
            wb, fb = 1, True
        else:
            xb, vb, xrb, _t, _a, _a2, _tr, stb = step(xb, vb, phib, mub, sigb, kb)
            axb = abs(xb)
            if axb > pkb:
                pkb = axb
            if hb >= tb:
                tailb[hb - tb] = xb
                tminb, tmaxb = tail_extremes(xb, xrb, stb, tminb, tmaxb)
            hb += 1
            if not axb <= boundb:
                wb, fb = 2, True
            fb = fb or hb >= h1b
    sa[SX], sa[SV], sa[SPOS], sa[STMIN], sa[STMAX] = xa, va, pa_, tmina, tmaxa
    sb[SX], sb[SV], sb[SPOS], sb[STMIN], sb[STMAX] = xb, vb, pb_, tminb, tmaxb
    return ha, wa, pka, fa, hb, wb, pkb, fb


@njit(cache=True, inline="always")
def _next_range(lane: IntArray) -> bool:
    """Move ``lane`` (its row of integer state) to its run's next nonempty range; False when none is left.

    The order of :func:`dfa.core.kernel.simulate_kernel`: segment k = 0 … NSEG − 1, each split where the tail starts.
    """
    n, tail_start = lane[N], lane[TAIL]
    while True:
        lane[PART] += 1
        if lane[PART] == 2:
            lane[PART] = 0
            lane[SEG] += 1
        if lane[SEG] == NSEG:
            return False
        lo, cut, hi = segment_ranges(lane[SEG], n, tail_start)
        a, b = (lo, cut) if lane[PART] == 0 else (cut, hi)
        if b > a:
            lane[H], lane[END] = a, b
            return True


@njit(cache=True, nogil=True)
def _load(
    lane: IntArray,
    i: int,
    devices: Devices,
    initials: Starts,
    runs: BatchRuns,
    delay: int,
    state: FloatArray,
    hist: FloatArray,
    stats: FloatArray,
    consts: FloatArray,
) -> None:
    """Start run ``i`` in ``lane`` (state, delay ring, stats cleared, its sample constants, its first range)."""
    ns, tail_lens, _, quantize = runs
    start(initials[0][i], initials[1][i], delay, quantize, state, hist, stats[i])
    rate, e1, p1, p2, q1, q2 = sample_constants(devices[0][i], devices[1][i])
    consts[0], consts[1], consts[2], consts[3], consts[4], consts[5] = rate, e1, p1, p2, q1, q2
    lane[PT], lane[SEG], lane[PART], lane[N], lane[TAIL] = i, 0, -1, ns[i], ns[i] - tail_lens[i]
    _next_range(lane)


@njit(cache=True, nogil=True)
def _book(
    lane: IntArray,
    h: int,
    why: int,
    peak: float,
    ended: bool,
    state: FloatArray,
    tail: FloatArray,
    tail_len: int,
    mu: float,
    quantize: bool,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
) -> bool:
    """Book a lane's advance: its range's peak; if the range ended, the next range or the run's end.

    Returns True while the lane's run goes on, False when it is over (``done``, ``rest``, stats finished
    exactly as :func:`dfa.core.kernel.simulate_kernel` does).
    """
    i, n = lane[PT], lane[N]
    lane[H] = h
    if peak > stats[i, lane[SEG]]:
        stats[i, lane[SEG]] = peak
    if not ended or (why == 0 and _next_range(lane)):
        return True
    done[i] = h if why != 0 else n
    rest[i] = h if why == 1 else -1
    if why == 2:
        stats[i, NSEG + 5] = 1.0
    e = np.empty(0)
    run = (n, tail_len, np.inf, quantize)  # the bound is not read by finish
    finish(state, done[i], rest[i], mu, run, tail, stats[i], (e, e, np.empty((0, 4))), (False, False))
    lane[PT] = -1
    return False


def pair_kernel(
    devices: Devices, initials: Starts, runs: BatchRuns, delay: int, stats: FloatArray, done: IntArray, rest: IntArray
) -> None:
    """Independent runs, two in flight: run i is :func:`dfa.core.kernel.simulate_kernel` of its own inputs.

    Run i has (μ, β, σ) = (``devices[0][i]``, ``devices[1][i]``, ``devices[2][i]``), (ξ0, ξ'0) =
    (``initials[0][i]``, ``initials[1][i]``) and, from ``runs`` = (ns, tail_lens, bounds, quantize), ``ns[i]``
    samples, tail ``tail_lens[i]`` and bound ``bounds[i]``; every run has the delay ``delay`` and the encoder
    ``quantize``. ``stats[i]`` (NSTATS), ``done[i]`` and ``rest[i]`` receive what
    :func:`dfa.core.kernel.simulate_kernel` returns for it, bit for bit (nothing recorded).

    Not compiled itself: it calls :func:`pair_free_kernel` without a delay and :func:`pair_delayed_kernel` with
    one, so that a command without a delay never compiles the delayed loops (numba compiles every branch of a
    kernel, taken or not).
    """
    if delay == 0:
        pair_free_kernel(devices, initials, runs, stats, done, rest)
    else:
        pair_delayed_kernel(devices, initials, runs, delay, stats, done, rest)


@njit(cache=True, nogil=True)
def pair_free_kernel(
    devices: Devices, initials: Starts, runs: BatchRuns, stats: FloatArray, done: IntArray, rest: IntArray
) -> None:
    """:func:`pair_kernel` without a delay: only :func:`advance_pair` and :func:`dfa.core.kernel.advance_free` compiled."""
    _pair_runs(devices, initials, runs, 0, stats, done, rest, False)


@njit(cache=True, nogil=True)
def pair_delayed_kernel(
    devices: Devices, initials: Starts, runs: BatchRuns, delay: int, stats: FloatArray, done: IntArray, rest: IntArray
) -> None:
    """:func:`pair_kernel` with a delay of ``delay`` >= 1 samples: only :func:`advance_pair_delayed` and
    :func:`dfa.core.kernel.advance` compiled."""
    _pair_runs(devices, initials, runs, delay, stats, done, rest, True)


@njit(cache=True, inline="always")
def _pair_runs(
    devices: Devices,
    initials: Starts,
    runs: BatchRuns,
    delay: int,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
    delayed: bool,
) -> None:
    """The loop of :func:`pair_kernel`; ``delayed`` (a constant where it is inlined) picks the lanes' loops,
    the other branches are pruned before numba compiles them (:func:`_advance_lanes`)."""
    mus, betas, sigmas = devices
    _, tail_lens, bounds, quantize = runs
    lanes = np.full((2, NLANE), -1, dtype=np.int64)
    states = np.empty((2, NSTATE))
    hists = np.empty((2, delay + 1))
    # numpy's stubs type max(1, np.int64) as a comparable, not an int: the shape is ints at run time
    tails = np.empty((2, max(1, np.max(tail_lens)) if tail_lens.shape[0] else 1))  # type: ignore[type-var]
    consts = np.empty((2, 6))
    nxt = np.int64(0)  # not the literal 0: numba would compile _load once more for it
    while True:
        for w in range(2):  # an empty lane takes the next run
            if lanes[w, PT] < 0 and nxt < mus.shape[0]:
                _load(lanes[w], nxt, devices, initials, runs, delay, states[w], hists[w], stats, consts[w])
                nxt += 1
        if lanes[0, PT] < 0 and lanes[1, PT] < 0:
            return
        res = _advance_lanes(lanes, states, hists, tails, consts, mus, betas, sigmas, delay, quantize, bounds, delayed)
        for w in range(2):
            i = lanes[w, PT]
            if i >= 0:
                h, why, peak, ended = res[w]
                _book(
                    lanes[w],
                    h,
                    why,
                    peak,
                    ended,
                    states[w],
                    tails[w],
                    tail_lens[i],
                    mus[i],
                    quantize,
                    stats,
                    done,
                    rest,
                )


@njit(cache=True, inline="always")
def _kc(c: FloatArray) -> SampleConstants:
    return (c[0], c[1], c[2], c[3], c[4], c[5])


@njit(cache=True, inline="always")
def _advance_lanes(
    lanes: IntArray,
    states: FloatArray,
    hists: FloatArray,
    tails: FloatArray,
    consts: FloatArray,
    mus: FloatArray,
    betas: FloatArray,
    sigmas: FloatArray,
    delay: int,
    quantize: bool,
    bounds: FloatArray,
    delayed: bool,
) -> tuple[tuple[int, int, float, bool], tuple[int, int, float, bool]]:
    """Advance the lanes in flight: both together (:func:`advance_pair`, :func:`advance_pair_delayed`), or the
    only one alone (:func:`dfa.core.kernel.advance_free`, :func:`dfa.core.kernel.advance`).

    ``delayed`` (``delay`` >= 1) is a constant where this is inlined: the branches test it alone (``if
    delayed``), the form numba prunes before typing, so the loops of the other case are never compiled.
    """
    a, b = lanes[0], lanes[1]
    ia, ib = a[PT], b[PT]
    if ia >= 0 and ib >= 0:
        run_a = (states[0], a[H], a[END], mus[ia], sigmas[ia], _kc(consts[0]), tails[0], bounds[ia], a[TAIL])
        run_b = (states[1], b[H], b[END], mus[ib], sigmas[ib], _kc(consts[1]), tails[1], bounds[ib], b[TAIL])
        if delayed:
            ha, wa, pa, fa, hb, wb, pb, fb = advance_pair_delayed(*run_a, hists[0], *run_b, hists[1], delay, quantize)
        else:
            ha, wa, pa, fa, hb, wb, pb, fb = advance_pair(*run_a, *run_b, quantize)
        return (ha, wa, pa, fa), (hb, wb, pb, fb)
    w = 0 if ia >= 0 else 1
    lane = lanes[w]
    i = lane[PT]
    if delayed:
        e = np.empty(0)
        device = (mus[i], betas[i], sigmas[i])
        run = (lane[N], lane[N] - lane[TAIL], bounds[i], quantize)  # lane[TAIL] = n − tail length: its start
        records = (e, e, np.empty((0, 4)))
        h, why, peak = advance(
            states[w], hists[w], lane[H], lane[END], device, run, delay, tails[w], records, (False, False)
        )
    else:
        h, why, peak = advance_free(
            states[w], lane[H], lane[END], mus[i], sigmas[i], quantize, bounds[i], _kc(consts[w]), tails[w], lane[TAIL]
        )
    one = (h, why, peak, True)
    other = (0, 0, 0.0, False)
    return (one, other) if w == 0 else (other, one)
