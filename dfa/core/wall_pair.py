"""Outcome-only runs with a wall, two in flight, each run's outcome that of
:func:`dfa.core.wall_kernel.outcome_wall_kernel` alone (issue 43).

:func:`dfa.core.batch.batch_wall_outcomes` (what the searches run) is :func:`pair_wall_outcomes`. The runs that
take most of a search's time with a passivity controller are chatters whose controller is held at its limit:
their state never repeats, so every sample is integrated, and a sample's chain (the reading, the command, the
motion with its stop inside the sample, :func:`dfa.core.kernel.step`) is bound by its latency. Two such runs
advanced in one loop (:func:`advance_wall_pair`, each in its own local scalars) let the processor overlap their
chains, as :mod:`dfa.core.pair` does for the spring.

The lanes run the walls of the common case alone (:func:`pairable`): the encoder, no delay, no filter, no
amplifier lag, no hand, a bilateral wall and, with a passivity controller, an unbounded observer; a damper, a
push, the actuator's force limit and the device's travel may be there (:data:`LANE_CODES`; a new element runs
alone until its update is written into the lanes). Every other run is
:func:`~dfa.core.wall_kernel.outcome_wall_kernel` alone. Each lane walks the ranges of samples of
:func:`dfa.core.wall_kernel._run_wall` (the envelope's eighths, split where the tail starts) and runs in each
exactly the operations of :func:`dfa.core.wall_kernel._advance`'s loop, in the same order, on the same doubles
(:func:`_lane_sample`): the delay ring of one command and the observer's state (its energy, its sums, its
booking) are locals. Its cycle check is :func:`~dfa.core.wall_kernel._advance`'s (Brent's reference, renewed at
doubling spans, within a range); where the state returns to the reference (:func:`~dfa.core.wall_kernel._same_loop`:
with no delay, filter or lag, ξ (or only ξ' and the last reading for an approximate return), ξ' and r), the
lane hands the rest of its range to :func:`~dfa.core.wall_kernel._advance` alone, which takes its own reference
from there and skips the periods. So only where a period is skipped changes, never a run's outcome: exact skips
are the every-sample run bit for bit, approximate ones decide the every-sample run's outcome
(:func:`~dfa.core.wall_kernel._robust`) or the run is run again with the exact skip alone, as
:func:`~dfa.core.wall_kernel.outcome_wall_kernel` does (``tests/test_eq4_wall_pair.py``).

Developers: numba keys this module's cache on this file alone, while it compiles in :mod:`dfa.core.wall_kernel`
and :mod:`dfa.core.kernel`; dfa's cache folder is named after every file of :mod:`dfa.core`
(:mod:`dfa.core.cache`).
"""

from __future__ import annotations

from typing import TypeAlias

import numpy as np

from .jit import njit
from .kernel import BatchRuns, Devices, FloatArray, IntArray, Rules, Starts, sample_constants
from .pair import _next_range as next_range
from .table import DAMPER, DELAY, FORCE_LIMIT, HEAD, PASSIVITY, PUSH, TRAVEL
from .wall_kernel import (
    _REF,
    _XTOL,
    CPER,
    CPRF,
    CRP,
    CV,
    CX,
    NCSTATE,
    PBK,
    PE,
    PINIT,
    PMODE,
    PTOT,
    Controller,
    Model,
    _advance,
    _clip,
    _contact,
    _ended,
    _extremes,
    _loaded,
    _pc_command,
    _peak,
    _reading,
    _run_wall,
    _same,
    _saturation,
    _store,
    _unliteral,
    begin_run,
    decode_table,
    end_run,
    observer_size,
    outcome_wall_kernel,
    stepped,
)

__all__ = ["advance_wall_pair", "pair_wall_outcomes", "pairable"]

# integer state of a lane: run index (-1: none), segment, part (0: before the tail, 1: in it), next sample, range
# end, the run's length, where its tail starts (the columns of dfa.core.pair's lanes, in its order), the reference's
# sample, the span to its renewal, the observer's size
PT, SEG, PART, H, END, N, TAIL, RH, SPAN, OBS = range(10)
NLANE = 10
# a lane's reference state (ξ, ξ', r_{h−1}; ξ NaN: none) beside its integer state
RX, RV, RR = 0, 1, 2

#: One lane's run between samples, as :func:`dfa.core.wall_kernel._advance` keeps it in locals: ξ, ξ', r_{h−1},
#: v_{h−1}, y_{h−1}, φ_A, the operator's force, approaching, saturation, the command in the ring (c_{h−1}), the
#: controller's booking, the observer's E, E over the run, the held energy still to count and the mode, the tail's
#: extremes, the peak |ξ| of the samples run, the next sample h, and the cycle check's reference (ξ, ξ', r, its
#: sample, the span to its renewal)
LaneState: TypeAlias = tuple[
    float, float, float, float, float, float, float, bool, float, float, float, float, float, float, int, float,
    float, float, int, float, float, float, int, int,
]  # fmt: skip
#: What a lane's samples read and never change: the model (μ, β, σ, d, quantize), the wall's ``ctl``, the sample
#: constants, the divergence bound, the device's travel, whether the range is in the tail, an approximate return
#: allowed, the range's end and where the tail starts
LaneSettings: TypeAlias = tuple[
    Model, Controller, tuple[float, float, float, float, float, float], float, float, bool, bool, int, int
]


#: The element codes a lane runs (:func:`pairable`); a wall with any other block runs alone, so that an element added
#: to the kernel runs in a lane only once its update is in :func:`_lane_sample` and its code here.
LANE_CODES = (DAMPER, PASSIVITY, FORCE_LIMIT, TRAVEL, PUSH, DELAY)


@njit(cache=True, inline="always")
def pairable(table: FloatArray, quantize: bool) -> bool:
    """Whether a run with the wall of kernel table ``table`` runs in a lane (module docstring): the encoder, blocks of
    :data:`LANE_CODES` alone, no delay and, with a passivity controller, no window on its observer.

    Examples
    --------
    The paper's spring, a damper β_B = 0.5 (code, 1 parameter, no state), a velocity filter (a lane has no filter):

    >>> from dfa.core.table import DAMPER, FILTER
    >>> pairable(np.array([0.0]), True), pairable(np.array([1.0, DAMPER, 1, 0, 0.5]), True)
    (True, True)
    >>> pairable(np.array([1.0, FILTER, 1, 2, 0.5]), True), pairable(np.array([0.0]), False)
    (False, False)
    """
    delay, ctl = decode_table(table)
    if not quantize or delay != 0 or ctl[9] != 0:
        return False
    j = 1
    for _ in range(int(table[0])):
        if int(table[j]) not in LANE_CODES:
            return False
        j += HEAD + int(table[j + 1])
    return True


@njit(cache=True, inline="always")
def _lane_sample(s: LaneState, c: LaneSettings) -> tuple[LaneState, int, bool, int]:
    """Sample h of one lane: :func:`dfa.core.wall_kernel._advance`'s loop body for a :func:`pairable` wall, the ring
    of one command and the observer in locals. Returns the state after it, why the run ends (0: it goes on; 1 at
    rest at h, 2 past the bound, 4 past the travel: :func:`~dfa.core.wall_kernel._advance`'s), whether the state is
    back at the reference (the caller hands the range on), and the tail's index to write ξ at (−1: none)."""
    x, v, r_prev, v_prev, y, fa, ext, appr, sat, cprev, bk, pe, ptot, pinit, pmode, tmin, tmax, peak, h = s[:19]
    rx, rv, rr, rh, span = s[19:]
    model, ctl, k, bound, travel, in_tail, apx, _, tail_start = c
    r, vh, yh, base, w, cmd, inside = _reading(x, r_prev, v_prev, y, h, True, ctl)
    if ctl[8]:  # _advance's observer and controller: slot 0 of the ring of one holds c_{h−1}, no booking pending
        term = -cprev * vh + pinit
        pinit, ptot, pe = 0.0, ptot + term, pe + term
        f, cmd, pmode = _pc_command(pe + 0.0, vh, w, cmd, inside, ctl, True)  # + the pending sum, +0 as there
        bk = -f * vh
    cmd = _clip(cmd, ctl[11])
    sat = _saturation(sat, abs(cmd) >= ctl[11], in_tail)
    cprev = cmd
    ends = (cmd, cmd) if v == 0.0 else (0.0, 0.0)  # the ring's least and largest command (_extent)
    # _sample with no lag and no hand: the absorbing tests, then the step under the command and the push
    fa, ext, appr, why = _contact(x, v, yh, fa, ends, model[2], ctl, ext, appr, (vh, base, cmd, inside))
    back, tw, y = False, -1, yh  # _sample returns y_h, at rest too
    if why == 0:
        x, v, lo_t, hi_t = stepped(x, v, cmd + ext, model[0], model[2], k)
        r_prev, v_prev = r, vh
        ax = abs(x)
        peak = _peak(peak, ax)
        if in_tail:
            tw = h - tail_start
            tmin, tmax = _extremes(x, lo_t, hi_t, tmin, tmax)
        h += 1
        why = _ended(ax, bound, travel)
        if why == 0:
            near = _same(x, rx) or (apx and abs(x - rx) <= _XTOL)
            back = near and _same(v, rv) and _same(r_prev, rr)  # _same_loop, no delay, filter or lag
            if not back and h - rh == span:
                rx, rv, rr, rh, span = (x if not appr else np.nan), v, r_prev, h, 2 * span
    out = (x, v, r_prev, v_prev, y, fa, ext, appr, sat, cprev, bk, pe, ptot, pinit, pmode, tmin, tmax, peak, h,
           rx, rv, rr, rh, span)  # fmt: skip
    return out, why, back, tw


@njit(cache=True, inline="always")
def _lane_in(st: FloatArray, ring: FloatArray, pcs: FloatArray, lane: IntArray, ref: FloatArray) -> LaneState:
    """A lane's state from its arrays (:func:`_lane_sample`'s locals)."""
    x, v, r_prev, v_prev, y, fa, _, tmin, tmax, _, ext, appr, sat = _loaded(st)
    obs = pcs.shape[0] > 0
    bk, pe, ptot, pinit = (pcs[PBK], pcs[PE], pcs[PTOT], pcs[PINIT]) if obs else (0.0, 0.0, 0.0, 0.0)
    pmode = int(pcs[PMODE]) if obs else 0
    return (x, v, r_prev, v_prev, y, fa, ext, appr, sat, ring[0], bk, pe, ptot, pinit, pmode, tmin, tmax, 0.0,
            lane[H], ref[RX], ref[RV], ref[RR], lane[RH], lane[SPAN])  # fmt: skip


@njit(cache=True, inline="always")
def _lane_out(s: LaneState, st: FloatArray, ring: FloatArray, pcs: FloatArray, lane: IntArray, ref: FloatArray) -> None:
    """A lane's state back into its arrays (as :func:`dfa.core.wall_kernel._advance` leaves them)."""
    x, v, r_prev, v_prev, y, fa, ext, appr, sat, cprev, bk, pe, ptot, pinit, pmode, tmin, tmax, _, h = s[:19]
    _store(st, (x, v, r_prev, v_prev, y, fa, 0.0, tmin, tmax, st[CPER], ext, 1.0 if appr else 0.0, sat))
    ring[0] = cprev
    if pcs.shape[0] > 0:
        pcs[PBK], pcs[PE], pcs[PTOT], pcs[PINIT], pcs[PMODE] = bk, pe, ptot, pinit, pmode
    lane[H], lane[RH], lane[SPAN] = h, s[22], s[23]
    ref[RX], ref[RV], ref[RR] = s[19], s[20], s[21]


@njit(cache=True, nogil=True)
def advance_wall_pair(
    a: tuple[FloatArray, FloatArray, FloatArray, FloatArray, IntArray, FloatArray], ca: LaneSettings,
    b: tuple[FloatArray, FloatArray, FloatArray, FloatArray, IntArray, FloatArray], cb: LaneSettings,
) -> tuple[tuple[int, float, bool], tuple[int, float, bool]]:  # fmt: skip
    """Two lanes' runs A and B at once (:func:`_lane_sample`), until either's range ends, its run ends or its state
    is back at its reference.

    ``a``, ``b``: each lane's arrays (state, ring, observer, tail, integer state, reference; :func:`_lane_in`),
    ``ca``, ``cb`` its settings. Returns (why, peak |ξ| of the samples run here, back) of A then of B; the next
    sample is in each lane's integer state.
    """
    sa, sb = _lane_in(a[0], a[1], a[2], a[4], a[5]), _lane_in(b[0], b[1], b[2], b[4], b[5])
    taila, tailb, h1a, h1b = a[3], b[3], ca[7], cb[7]
    wa = wb = 0
    ba = bb = False
    while True:
        sa, wa, ba, twa = _lane_sample(sa, ca)
        sb, wb, bb, twb = _lane_sample(sb, cb)
        if twa >= 0:
            taila[twa] = sa[0]
        if twb >= 0:
            tailb[twb] = sb[0]
        if wa != 0 or ba or sa[18] >= h1a or wb != 0 or bb or sb[18] >= h1b:
            break
    _lane_out(sa, a[0], a[1], a[2], a[4], a[5])
    _lane_out(sb, b[0], b[1], b[2], b[4], b[5])
    return (wa, sa[17], ba), (wb, sb[17], bb)


@njit(cache=True, inline="always")
def _next_range(lane: IntArray, ref: FloatArray, st: FloatArray) -> bool:
    """Move ``lane`` to its run's next nonempty range (:func:`dfa.core.pair._next_range`: the lanes share the first
    columns of its integer state), its cycle check's reference taken at the range's start as
    :func:`dfa.core.wall_kernel._advance` takes it; False when no range is left."""
    if not next_range(lane):
        return False
    period, a = int(st[CPER]), lane[H]
    lane[RH], lane[SPAN] = a, (period if period > 0 else 1)
    ref[RX], ref[RV], ref[RR] = (st[CX] if a > 0 else np.nan), st[CV], st[CRP]
    return True


@njit(cache=True, inline="always")
def _settings(i: int, lane: IntArray, devices: Devices, runs: BatchRuns, tables: FloatArray) -> LaneSettings:
    """The settings of lane ``lane``'s run ``i`` in its present range (:data:`LaneSettings`)."""
    mu, beta, sigma = devices[0][i], devices[1][i], devices[2][i]
    delay, ctl = decode_table(tables[i])
    model = (mu, beta, sigma, delay, True)
    in_tail = lane[H] >= lane[TAIL]
    return model, ctl, sample_constants(mu, beta), runs[2][i], ctl[12], in_tail, True, lane[END], lane[TAIL]


@njit(cache=True, nogil=True)
def _alone(
    i: int, lane: IntArray, st: FloatArray, ring: FloatArray, ref: FloatArray, pcs: FloatArray, tail: FloatArray,
    devices: Devices, runs: BatchRuns, tables: FloatArray,
) -> tuple[int, float]:  # fmt: skip
    """The rest of lane ``lane``'s range by :func:`dfa.core.wall_kernel._advance` alone (an outcome-only run, its own
    reference from here); returns (why, peak) and leaves the next sample in the lane."""
    model, ctl, _, bound, _, _, _, h1, tail_start = _settings(i, lane, devices, runs, tables)
    mu, beta, sigma, delay, _ = model
    e, yes = np.empty(0), _unliteral(True)
    h, why, peak, _ = _advance(
        st, ring, ref, lane[H], h1, mu, beta, sigma, delay, runs[3], bound, ctl, tail, tail_start, e, e, yes, pcs,
        lane[N], yes,
    )  # fmt: skip
    lane[H] = h
    return why, peak


@njit(cache=True, nogil=True)
def _over(
    w: int, why: int, lanes: IntArray, states: FloatArray, tails: FloatArray, devices: Devices, initials: Starts,
    runs: BatchRuns, tables: FloatArray, rules: Rules, outs: tuple[FloatArray, IntArray, IntArray],
) -> None:  # fmt: skip
    """Lane ``w``'s run is over (``why`` as :func:`dfa.core.wall_kernel._advance`'s; 0: ran through): its statistics
    finished and its outcome checked as :func:`dfa.core.wall_kernel.outcome_wall_kernel` does, the run again with
    the exact skip alone where an approximate return does not decide it; the lane emptied."""
    stats, done, rest = outs
    lane = lanes[w]
    i, n, h = lane[PT], lane[N], lane[H]
    tail_len, e = n - lane[TAIL], np.empty(0)
    d, r, sure = end_run(states[w], tails[w], tail_len, n, h, why, stats[i], rules, devices[0][i], e, e)
    if not sure:
        device, initial = (devices[0][i], devices[1][i], devices[2][i]), (initials[0][i], initials[1][i])
        run = (n, tail_len, runs[2][i], runs[3])  # runs[3] and _unliteral, not literals: one compiled _run_wall
        yes, no = _unliteral(True), _unliteral(False)
        d, r, _, _ = _run_wall(device, initial, run, tables[i], e, e, stats[i], yes, rules, no)
    done[i], rest[i] = d, r
    lane[PT] = -1


@njit(cache=True, nogil=True)
def _load(
    w: int, i: int, lanes: IntArray, states: FloatArray, rings: FloatArray, refs: FloatArray, pcss: FloatArray,
    devices: Devices, initials: Starts, runs: BatchRuns, tables: FloatArray, stats: FloatArray,
) -> bool:  # fmt: skip
    """Start run ``i`` in lane ``w`` (:func:`dfa.core.wall_kernel.begin_run`, its first range) when it is
    :func:`pairable`; False (nothing done) when it is not. The lane holds no range when the run has none."""
    ns, tail_lens, _, quantize = runs
    if not pairable(tables[i], quantize):
        return False
    _, ctl = decode_table(tables[i])
    lane = lanes[w]
    lane[PT], lane[SEG], lane[PART], lane[N], lane[TAIL] = i, 0, -1, ns[i], ns[i] - tail_lens[i]
    lane[OBS] = observer_size(0, 0) if ctl[8] else 0
    lane[H] = lane[END] = 0
    device, initial = (devices[0][i], devices[1][i], devices[2][i]), (initials[0][i], initials[1][i])
    begin_run(states[w], rings[w], pcss[w, : lane[OBS]], stats[i], device, initial, True, ctl)
    _next_range(lane, refs[w], states[w])
    return True


@njit(cache=True, nogil=True)
def pair_wall_outcomes(
    devices: Devices, initials: Starts, runs: BatchRuns, tables: FloatArray, rules: Rules, stats: FloatArray,
    done: IntArray, rest: IntArray,
) -> None:  # fmt: skip
    """:func:`dfa.core.batch.batch_wall_outcomes`, two :func:`pairable` runs in flight (module docstring); every other
    run :func:`dfa.core.wall_kernel.outcome_wall_kernel` alone. Each run's outcome (:func:`dfa.core.kernel.classify`
    of ``stats[i]`` with ``rules``, ``done[i]``, ``rest[i]``) is that of
    :func:`~dfa.core.wall_kernel.outcome_wall_kernel` alone, the every-sample run's."""
    ns, tail_lens, bounds, quantize = runs
    m = ns.shape[0]
    lanes = np.full((2, NLANE), -1, dtype=np.int64)
    states, rings, refs = np.empty((2, NCSTATE)), np.empty((2, 1)), np.empty((2, 3))
    kept, pcss = np.empty((2, _REF)), np.zeros((2, observer_size(0, 0)))
    tails = np.empty((2, max(1, np.max(tail_lens)) if m else 1))  # type: ignore[type-var]
    outs = (stats, done, rest)
    nxt = np.int64(0)  # not the literal 0: numba would compile _load once more for it
    while True:
        for w in range(2):  # an empty lane takes the next pairable run; the others run alone meanwhile
            while lanes[w, PT] < 0 and nxt < m:
                i = nxt
                nxt += 1
                if not _load(w, i, lanes, states, rings, refs, pcss, devices, initials, runs, tables, stats):
                    run = (ns[i], tail_lens[i], bounds[i], quantize)
                    device, initial = (devices[0][i], devices[1][i], devices[2][i]), (initials[0][i], initials[1][i])
                    done[i], rest[i], _ = outcome_wall_kernel(device, initial, run, tables[i], stats[i], rules)
                elif lanes[w, H] >= lanes[w, END]:  # a run of no samples (np.int64: one compiled _over)
                    _over(w, np.int64(0), lanes, states, tails, devices, initials, runs, tables, rules, outs)
        ia, ib = lanes[0, PT], lanes[1, PT]
        if ia < 0 and ib < 0:
            return
        both = ia >= 0 and ib >= 0 and states[0, CPRF] == 0.0 and states[1, CPRF] == 0.0
        ends = ((0, 0.0, False), (0, 0.0, False))
        if both:
            a = (states[0], rings[0], pcss[0, : lanes[0, OBS]], tails[0], lanes[0], refs[0])
            b = (states[1], rings[1], pcss[1, : lanes[1, OBS]], tails[1], lanes[1], refs[1])
            ca, cb = _settings(ia, lanes[0], devices, runs, tables), _settings(ib, lanes[1], devices, runs, tables)
            ends = advance_wall_pair(a, ca, b, cb)
        alone = 0 if (ib < 0 or (ia >= 0 and states[0, CPRF] != 0.0)) else 1  # a proven run first: it ends soon
        for w in range(2):
            i = lanes[w, PT]
            if i < 0 or (not both and w != alone):
                continue  # one lane alone at a time
            why, peak, back = ends[w] if both else (0, 0.0, True)  # alone: _advance takes the rest of the range
            if peak > stats[i, lanes[w, SEG]]:
                stats[i, lanes[w, SEG]] = peak
            if why == 0 and back:
                pcs = pcss[w, : lanes[w, OBS]]
                why, peak = _alone(i, lanes[w], states[w], rings[w], kept[w], pcs, tails[w], devices, runs, tables)
                if peak > stats[i, lanes[w, SEG]]:
                    stats[i, lanes[w, SEG]] = peak
            if why != 0 or (lanes[w, H] >= lanes[w, END] and not _next_range(lanes[w], refs[w], states[w])):
                _over(w, why, lanes, states, tails, devices, initials, runs, tables, rules, outs)
