"""Compiled kernel of the exact simulator with a controller (damper, filter, delay, amplifier lag).

Dimensionless loop (:mod:`dfa.model.wall`; time in samples, ξ = x/Δ,
φ = F/(KΔ)). At sample h the controller reads r_h = ⌊ξ(h)⌋ (ξ(h) itself
without quantization), forms v_h = r_h − r_{h−1} (r_{−1} = r_0), filters it,
y_h = a y_{h−1} + (1 − a) v_{h−1} (y_0 = 0; y_h = v_h without filter), and
commands c_h = −(r_h + ½) − β_B y_h (−r_h − β_B y_h without quantization),
clipped to ±φ_max by an actuator's force limit (:func:`_clip`, after every
other element), applied d samples later (c_{h} = c_0 for h < 0). The amplifier output obeys
α φ_A' = c_{h−d} − φ_A on [h, h + 1), φ_A(0) = c_0, and the device
μ ξ'' + β ξ' + σ sgn ξ' = φ_A.

No lag (α = 0): φ_A = c_{h−d} is constant over the sample and the sample is
the spring kernel's exact step (:func:`dfa.core.kernel.step`) with that force.

With a lag (α > 0) the force within a sample is φ_A(t) = c + D e^{−κt}
(κ = 1/α, c the applied command, D = φ_A(0) − c). While the device moves in
direction s the motion from (ξ₀, ξ'₀) after a time t is, with λ = β/μ,
F = c − σ s, p = min(λ, κ), q = max(λ, κ), P = p t, Q' = (q − p) t::

    ξ'(t) = ξ'₀ e^{−λt} + (F/μ) t φ₁(λt) + (D/μ) t e^{−P} φ₁(Q')
    ξ(t)  = ξ₀ + ξ'₀ t φ₁(λt) + (F/μ) t² φ₂(λt) + (D/μ) t² [p ρ(P) + e^{−P}(q − p) φ₂(Q')]/q
    ρ(P)  = (1 − e^{−P}(1 + P))/P² = Σ (−P)ⁿ (n + 1)/(n + 2)!          (ρ(0) = ½)

Derivation: the response of ξ' to e^{−κt} is ∫₀ᵗ e^{−λ(t−τ)} e^{−κτ} dτ =
(e^{−pt} − e^{−qt})/(q − p) = t e^{−P} φ₁(Q') (symmetric in λ, κ); its
integral G(t) = t (φ₁(P) − φ₁(Q))/(q − p) with Q = q t. Writing
φ₁(P) − φ₁(Q) = [Q' − Q e^{−P} + P e^{−Q}]/(PQ) and Q e^{−P} − P e^{−Q} =
e^{−P} Q'(1 + P φ₁(Q')), then 1 − φ₁ = u φ₂, gives the sum of two
non-negative terms above: no cancellation for β/μ ≈ 1/α (Q' → 0), β = 0
(p = 0) or tiny α (q = κ huge, e^{−P}, φ₂ ≪ 1); only q > 0 is divided by.

Zero crossings of the velocity. With w(t) = e^{λt} ξ'(t) (same sign as ξ'),
μ w'(t) = e^{λt} (φ_A(t) − σ s): the net force g(t) = F + D e^{−κt} is
monotone in t, so it changes sign at most once, at t_c = α log(−D/F) (closed
form). Hence |ξ'| can reach zero at most once per phase, only where g
opposes the motion (s g < 0): before t_c if g opposes first, after t_c if
it assists first. That interval brackets the root when s ξ' <= 0 at its end;
the root is found by Newton's method on the closed form safeguarded by
bisection (the bracket shrinks every step; it stops when the Newton step is
below 4 ulp of t, or the bracket is that narrow), so no step size and no tolerance beyond rounding.

Stick-slip with a time-varying force. At ξ' = 0 the device restarts in the
direction sgn φ_A when |φ_A| > σ; otherwise it sticks while |φ_A(t)| <= σ.
φ_A moves monotonically toward c, so a stuck device breaks away iff |c| > σ,
at the time φ_A(t) = σ sgn c, t_b = α log(D/(σ sgn c − c)) (closed form);
it stays stuck to the end of the sample otherwise. A sample is a chain of
such phases (at most a few: each restart needs φ_A to cross a level ±σ,
which a monotone φ_A does at most twice).

Rest (absorbing state). At the start of sample h: ξ' = 0 and, if the device
stayed stuck, the reading would stay r = r_h, so v_k = 0 for k > h, the
filtered y decays geometrically from y_{h+1} = a y_h + (1 − a) v_h to 0
without changing sign (y = 0 from h + 1 on without filter), and every future
command lies in the hull of c_h, c(y_{h+1}) and c(0) = −(r + ½); the pending
commands c_{h−d} … c_{h−1} are in the delay ring; and φ_A stays in the hull
of its present value and the commands it follows. If all these lie in
[−σ, σ] the device provably never moves again (by induction: stuck ⇒ same
reading ⇒ same bounds): that is "rest". A run that ends stuck without this
proof is not rest.

Period skipping (issue 16). Between samples h − 1 and h the loop is the
state S_h that sample h reads (:func:`_sample`, line by line): ξ and ξ'
(the step and the reading r_h); r_{h−1} (v_h = r_h − r_{h−1}); with the
filter y_{h−1} and v_{h−1} (y_h = a y_{h−1} + (1 − a) v_{h−1}; without it
y_h = v_h and v_{h−1} is never read); with the lag φ_A (its start value in
the sample and its update; without it φ_A = c is set before any read); and
the d pending commands c_{h−d} … c_{h−1} in logical order, oldest first
(ring[pos + 1], …, ring[pos + d] mod d + 1; ring[pos] holds the applied
c_{h−d−1}, overwritten by c_h before anything reads the ring, and the
physical position only says where the next write goes). The only other
input is h itself, through ``h > 0`` (y_0 = 0): no reference is taken at
h = 0. Sample h is then a deterministic function of S_h alone, bit for bit
(the same compiled operations on the same doubles), and so are its rest
test (v, φ_A, the ring after the write, c(r_h), y_{h+1}), its exit test and
its contributions to the statistics (ξ at the end, the turning points).
So when S_h equals S_{h−P} bit for bit (±0 differ, NaN never equals:
:func:`dfa.core.kernel.same_state`'s rule), samples h, h + 1, … repeat samples
h − P, … for ever: none of them rests or leaves the bound, because those
P samples did not (a repeating state never rests). :func:`_advance` finds
P by Brent's method (a reference state renewed at doubling intervals,
within the range it runs: one segment of the run on one side of the tail
start) and jumps over the whole periods left in the range: their peaks,
tail extremes and turning points are those of the P samples after the
reference, already counted in the same segment (and the same tail), their
tail readings are copied, and the state after the jump is S_h (the ring's
contents in logical order; only its physical position differs). Every
later range knows P and takes its reference at its start: one period
integrated, then the jump. Same results bit for bit as integrating every
sample (``run_wall_kernel(..., skip=False)``,
``tests/test_eq4_controller_period_skip.py``); records switch skipping off.

With a passivity controller (issue 43) the observer's energy E is state
too, and an unbounded observer's accumulates: it never repeats. The loop
reads it only through the controller's force, which is 0 at v_h = 0, 0
while the ledger is >= 0 and exactly ± its limit while the ledger is
below −limit·|v_h|; a chattering loop whose controller is held at its limit
(E falling every period) or idle (E rising) repeats bit for bit once E is
beyond what the rest of the run can bring back (:func:`_pc_repeats`, with
a bound on the rounding of E's sum). The skip is taken only then, E left
where it was (whole periods of the same run earlier: the forces repeat from
it too). A windowed observer is never skipped
(``tests/test_eq4_passivity_controller_period_skip.py``).

Outcome-only runs (issue 43; :func:`outcome_wall_kernel`, what the searches
run). A chattering loop can return to its state in everything but ξ: a
controller held at its limit makes ξ' return bit for bit while ξ, a running
sum, drifts by rounding (an ulp a period), so the skip above never finds its
period. With the encoder, no amplifier lag, no hand and a bilateral wall, ξ
enters the loop only through its reading ⌊ξ⌋ (the commands, the observer, the
rest and exit tests read the readings), and one sample (:func:`dfa.core.kernel.step`,
eq. 4-5) computes ξ' from ξ' and the force alone and adds to ξ at most three
terms computed from them alone. So when every part of the state but ξ equals
that of P samples earlier and ξ has moved by δ (at most :data:`_XTOL`), one
more period from this state is integrated with its least distance of ξ to a
change of reading (the margin), its largest |ξ|, |ξ'| and |φ|, and again
returns with ξ moved by δ. Then ρ = 4u(max|ξ| + 1 + max|ξ'| + (max|φ| + σ)/μ)
bounds the rounding of one sample's additions to ξ, the exact sum S of the
terms one period adds obeys |S| <= |δ| + Pρ, and by induction over the R
samples left (the readings equal the period's while ξ stays within the margin,
so every command, ξ' and, by :func:`_pc_repeats`, the controller's force repeat)
ξ at sample h + mP + i lies within E = (R/P + 2)(|δ| + 2Pρ) of its value at
h + i. The proof asks E < 1/4, the margin above 2E + 2ρ and max|ξ| + 2E within
the divergence bound and the travel; the run then skips whole periods as above
(every sample it integrates later is one of the run's own, shifted by whole
periods, so the phase is kept), and every statistic of ξ (segment peaks, tail
samples and extremes, turning points) lies within 2E + 4ρ of the every-sample
run's while the flags (rest, bound, travel, saturation) are the same.
:func:`_robust` decides each rule of :func:`dfa.core.kernel.classify` with that
margin; where one is not decided the run is integrated again with the exact
skip alone. The outcome is then the every-sample run's; the other statistics
need not be (no result shows them: :func:`dfa.simulate` never runs this path).
(``tests/test_eq4_outcome_only_runs.py``.)

The wall reaches this kernel as one float64 array, its kernel table (layout and element codes:
:mod:`dfa.core.table`; built by :meth:`dfa.model.wall.WallParams.kernel_table`). :func:`decode_table` reads it
once per run, one loop over its blocks with a branch per element code, into the fixed tuple the hot loop reads
(``ctl`` of :func:`_sample` and :func:`_advance`, :data:`Controller`); an unknown code is refused
(:func:`dfa.core.table.check_table` before a call, the compiled decoder again).

Energy bookkeeping is not implemented for the controller path
(:func:`dfa.simulate` refuses ``energy=True`` with a controller).

The hot loop (:func:`_advance`) passes no array to a per-sample helper: numba counts a reference on each array
an inlined helper takes, at every call, a sizeable part of a controller sample. So it reads the wall's command
(:func:`_reading`), runs the passivity observer and controller inline with their state in local variables (E, E over
the whole run, the held energy still to count, the controller's mode; the bookings and a window's terms stay in
the observer's array, read and written in the loop itself; a window's update is a call of its own,
:func:`_windowed`), writes the command into the delay ring, and hands the sample its outputs. :func:`_command` is
the same controller on the observer's array, what :func:`applied_forces` replays: a recorded run steps under the
forces the replay gives, bit for bit (``tests/test_eq4_passivity_controller_locals.py``). The controller's quotient
L/v_h is taken without a division at v_h = ±1 (exact), and at d = 0 the command applied is c_h itself, not read
back from the ring. With the controller held at its limit on a bilateral wall with the encoder (the chatter of the
searches' confirmations) its force −limit·v_h is formed without a branch on v_h (:func:`_pc_command`), and without a
damper the command is the spring's part itself (−(r + ½) − 0·y is that part, bit for bit): shorter dependency chains
a sample, the same bits.

The searches run outcome-only runs two at a time where the wall allows (:mod:`dfa.core.wall_pair`): each lane runs
this loop's operations for a wall without delay, filter, lag or hand, sharing :func:`_reading`, :func:`_pc_command`,
:func:`_contact` (the absorbing tests of :func:`_sample`) and :func:`stepped` (its step without a lag or a hand), and
hands a range to :func:`_advance` where its state returns. An element added to this loop runs in those lanes only
once its update is written there too (:data:`dfa.core.wall_pair.LANE_CODES`).

Developers: this module compiles in :func:`dfa.core.kernel.step`,
:func:`~dfa.core.kernel.sample_constants`, :func:`~dfa.core.kernel.tail_stats`,
:func:`~dfa.core.kernel.tail_extremes` and :mod:`dfa.core.exprel`; numba keys its
cache of this module on this file alone, but dfa's cache folder is named after every
file of :mod:`dfa.core` (:mod:`dfa.core.cache`): only your own ``NUMBA_CACHE_DIR``
needs clearing after such an edit.
"""

from __future__ import annotations

import math
from typing import TypeAlias

import numpy as np

from .exprel import phi1, phi2, rho
from .jit import njit
from .kernel import (
    CHATTER,
    NSEG,
    OSCILLATING,
    SATURATED,
    SATURATION,
    UNDECIDED,
    UNSTABLE,
    Device,
    Devices,
    FloatArray,
    IntArray,
    Rules,
    RunSettings,
    SampleConstants,
    Start,
    Starts,
    classify,
    sample_constants,
    segment_ranges,
    step,
    tail_extremes,
    tail_stats,
)
from .oscillator import hand_sample
from .table import DAMPER, DELAY, FILTER, FORCE_LIMIT, HAND, HEAD, LAG, ONE_SIDED, PASSIVITY, PUSH, TRAVEL

__all__ = [
    "decode_table",
    "run_wall_kernel",
    "outcome_wall_kernel",
    "rho",
    "lag_motion",
    "lag_sample",
    "simulate_wall_kernel",
    "serial_wall_kernel",
    "applied_forces",
    "observer_size",
    "held_energy",
]


_ULP4 = 4.0 * 2.220446049250313e-16  # four units in the last place, relative
MAX_PHASES = 16  # per sample; the derivation allows at most 5 (stuck, breakaway, stop, restart, stop)

Model: TypeAlias = tuple[float, float, float, int, bool]  # (μ, β, σ, d, quantize) of _sample
# (β_B, a, filtered, α, κ_h, one-sided, surface s, push p, passivity controller on, its window W, its force limit,
# the actuator's force limit φ_max, the device's travel ξ_travel): ctl of _sample and _advance
Controller: TypeAlias = tuple[float, float, bool, float, float, bool, float, float, bool, int, float, float, float]


@njit(cache=True, nogil=True)
def decode_table(table: FloatArray) -> tuple[int, Controller]:
    """The delay d and the hot loop's fixed tuple ``ctl`` (:data:`Controller`) of a kernel table, in one pass.

    Every element's default is the paper's spring (no damper, no filter, …); a block sets its element's fields
    (a later block of the same kind wins, the delays add up). An unknown code raises ValueError (the compiled
    guard behind :func:`check_table`).
    """
    delay = 0
    damping, pole, filtered, lag, spring = 0.0, 0.0, False, 0.0, 0.0
    onesided, surface, push, pc, window, limit = False, 0.0, 0.0, False, 0, math.inf
    top, travel = math.inf, math.inf
    j = 1
    for _ in range(int(table[0])):
        code, p = int(table[j]), j + HEAD
        if code == DELAY:
            delay += int(table[p])
        elif code == DAMPER:
            damping = table[p]
        elif code == FILTER:
            pole, filtered = table[p], True
        elif code == LAG:
            lag = table[p]
        elif code == HAND:
            spring = table[p]
        elif code == ONE_SIDED:
            onesided, surface = True, table[p]
        elif code == PUSH:
            push = table[p]
        elif code == PASSIVITY:
            pc, window, limit = True, int(table[p]), table[p + 1]
        elif code == FORCE_LIMIT:
            top = table[p]
        elif code == TRAVEL:
            travel = table[p]
        else:
            raise ValueError("dfa.core.wall_kernel.decode_table: unknown element code (see check_table)")
        j = p + int(table[j + 1])
    return delay, (damping, pole, filtered, lag, spring, onesided, surface, push, pc, window, limit, top, travel)


@njit(cache=True, inline="always")
def lag_motion(
    x0: float, v0: float, f: float, d: float, mu: float, lam: float, kap: float, t: float
) -> tuple[float, float]:
    """(ξ, ξ') after time ``t`` of μξ'' + βξ' = f + d e^{−κt} from (ξ₀, ξ'₀) (module docstring); λ = β/μ.

    Units: ticks, ticks per sample, samples; f, d in KΔ.

    Examples
    --------
    >>> lag_motion(0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0)   # unit force, no damping: (t²/2, t)
    (0.5, 1.0)
    >>> x, v = lag_motion(0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0)   # force e^{−t}: ξ' = 1 − e^{−1}
    >>> round(v, 12), round(x, 12)   # ξ = t − (1 − e^{−t}) = e^{−1}
    (0.632120558829, 0.367879441171)
    """
    u = lam * t
    p = lam if lam <= kap else kap
    q = kap if lam <= kap else lam
    pp = p * t
    dq = (q - p) * t
    e = math.exp(-pp)
    p1 = phi1(u)
    x = x0 + v0 * t * p1 + (f / mu) * t * t * phi2(u) + (d / mu) * t * t * (p * rho(pp) + e * (q - p) * phi2(dq)) / q
    v = v0 * math.exp(-u) + (f / mu) * t * p1 + (d / mu) * t * e * phi1(dq)
    return x, v


@njit(cache=True, inline="always")
def _root(
    x0: float, v0: float, f: float, d: float, mu: float, lam: float, kap: float, s: float, lo: float, hi: float
) -> float:
    """Time in [lo, hi] where s ξ' falls to 0 (s ξ'(lo) > 0 >= s ξ'(hi)): Newton safeguarded by bisection."""
    t = hi
    for _ in range(200):
        _, v = lag_motion(x0, v0, f, d, mu, lam, kap, t)
        sv = s * v
        if sv > 0.0:
            lo = t
        else:
            hi = t
            if sv == 0.0:
                return t
        acc = s * (f + d * math.exp(-kap * t) - lam * mu * v) / mu  # d(sξ')/dt, < 0 inside the bracket
        if acc < 0.0:
            step = sv / acc
            if abs(step) <= _ULP4 * t:
                return t  # the Newton step is below rounding: t is the root to rounding
            tn = t - step
        else:
            tn = 0.5 * (lo + hi)
        if not (lo < tn < hi):
            tn = 0.5 * (lo + hi)  # the safeguard: bisect when Newton leaves the bracket
        if hi - lo <= _ULP4 * hi:
            return hi  # the bracket has collapsed
        t = tn
    return hi


@njit(cache=True, inline="always")
def _stop_time(
    x0: float, v0: float, f: float, d: float, mu: float, lam: float, kap: float, s: float, tmax: float
) -> float:
    """First time in (0, tmax] at which ξ' reaches 0 in a phase of direction s, or −1 if it does not."""
    g0 = s * (f + d)
    g1 = s * (f + d * math.exp(-kap * tmax))
    if g0 >= 0.0 and g1 >= 0.0:
        return -1.0  # the net force never opposes the motion
    if g0 < 0.0 and g1 < 0.0:
        lo, hi = 0.0, tmax
    else:
        tc = math.log(-d / f) / kap  # g changes sign once, at t_c: e^{−κ t_c} = −F/D
        tc = min(max(tc, 0.0), tmax)
        lo, hi = (0.0, tc) if g0 < 0.0 else (tc, tmax)
    _, vh = lag_motion(x0, v0, f, d, mu, lam, kap, hi)
    if s * vh > 0.0:
        return -1.0
    if lo > 0.0:
        _, vl = lag_motion(x0, v0, f, d, mu, lam, kap, lo)
        if s * vl <= 0.0:
            return lo
    elif v0 == 0.0:
        return -1.0  # starts at rest with the force turning against it: cannot happen (see lag_sample)
    return _root(x0, v0, f, d, mu, lam, kap, s, lo, hi)


@njit(cache=True, inline="always")
def lag_sample(
    x: float, v: float, c: float, fa: float, mu: float, beta: float, sigma: float, lag: float
) -> tuple[float, float, float, float]:
    """One sample with the amplifier lag: (ξ, ξ', lowest and highest turning point; ±inf when none).

    ``c`` is the applied command, ``fa`` = φ_A at the start of the sample.
    """
    lam = beta / mu
    kap = 1.0 / lag
    t = 0.0
    lo_turn = np.inf
    hi_turn = -np.inf
    for phase in range(MAX_PHASES + 1):
        rem = 1.0 - t
        if rem <= 0.0:
            break
        if phase == MAX_PHASES:
            raise RuntimeError("dfa.core.wall_kernel.lag_sample: more phases in one sample than the derivation allows")
        d = (fa - c) * math.exp(-kap * t)
        if v == 0.0:
            if abs(c + d) <= sigma:  # stuck: breaks away when φ_A reaches σ sgn c (only if |c| > σ)
                if abs(c) <= sigma:
                    break
                target = sigma if c > 0.0 else -sigma
                tb = lag * math.log(d / (target - c))
                if not tb < rem:
                    break
                t += tb
                rem = 1.0 - t
                d = target - c
                s = 1.0 if c > 0.0 else -1.0
            else:
                s = 1.0 if c + d > 0.0 else -1.0
        else:
            s = 1.0 if v > 0.0 else -1.0
        f = c - sigma * s
        ts = _stop_time(x, v, f, d, mu, lam, kap, s, rem)
        if ts < 0.0:
            x, v = lag_motion(x, v, f, d, mu, lam, kap, rem)
            break
        x, _ = lag_motion(x, v, f, d, mu, lam, kap, ts)
        v = 0.0
        t += ts
        lo_turn = min(lo_turn, x)
        hi_turn = max(hi_turn, x)
    return x, v, lo_turn, hi_turn


@njit(cache=True, inline="always")
def _inside(c: float, sigma: float) -> bool:
    return abs(c) <= sigma


@njit(cache=True, inline="always")
def _extent(ring: FloatArray) -> tuple[float, float]:
    """The least and the largest command in the delay ring (both NaN when one is NaN): all that the rest and exit
    tests read of it (:func:`_absorbing`, :func:`_gone`), so that the per-sample helpers take no array (an inline
    helper that takes one costs a reference count a sample)."""
    lo, hi = math.inf, -math.inf
    for i in range(ring.shape[0]):
        c = ring[i]
        if not c == c:
            return math.nan, math.nan
        lo, hi = min(lo, c), max(hi, c)
    return lo, hi


@njit(cache=True, inline="always")
def _absorbing(
    v: float, fa: float, sigma: float, pending: tuple[float, float], cbase: float, cnext: float, held: float
) -> bool:
    """The proven rest state (module docstring): stuck, and every future command and φ_A within [−σ, σ] of
    ``held`` = κ_h ξ − p (the hand spring's force less the push; ξ does not change while stuck). ``cbase`` is
    the command at this reading with y = 0, ``cnext`` with y_{h+1} (a one-sided wall's clip keeps the
    commands between them: it is monotone in y); ``pending`` the ring's least and largest command
    (:func:`_extent`): fl(c − held) is monotone in c, so every command of the ring lies within σ of ``held``
    exactly when both do (NaN in neither)."""
    if v != 0.0 or not _inside(fa - held, sigma) or not _inside(cbase - held, sigma):
        return False
    if not _inside(cnext - held, sigma):
        return False
    return _inside(pending[0] - held, sigma) and _inside(pending[1] - held, sigma)


@njit(cache=True, inline="always")
def _gone(v: float, fa: float, pending: tuple[float, float], inside: bool, ctl: Controller) -> bool:
    """A one-sided wall left for good: the reading outside, the device moving away (ξ' < 0), no push and no hand
    spring (nothing can bring it back: friction and damping only oppose the motion), and no force pending
    (every command in the delay line, between the ring's least and largest ``pending`` (:func:`_extent`), and φ_A
    zero). Every later reading is outside, so every command is 0."""
    if not ctl[5] or inside or not v < 0.0 or ctl[7] != 0.0 or ctl[4] != 0.0 or fa != 0.0:
        return False
    return pending[0] == 0.0 and pending[1] == 0.0


@njit(cache=True, inline="always")
def _base(r: float, quantize: bool, ctl: Controller) -> tuple[float, bool]:
    """The spring's part of the command at the reading r, −(r + ½) (−r without the encoder), or a one-sided
    wall's −(q − s) inside and 0 outside; and whether q = r + ½ (r) lies beyond the surface s."""
    onesided, surface = ctl[5], ctl[6]
    q = r + 0.5 if quantize else r
    inside = q > surface
    if not onesided:
        return -q, inside
    return (-(q - surface) if inside else 0.0), inside


@njit(cache=True, inline="always")
def _shape(c: float, inside: bool, onesided: bool) -> float:
    """The command a one-sided wall applies: none outside, and inside it pushes only (min(c, 0)); c otherwise."""
    if not onesided:
        return c
    return min(c, 0.0) if inside else 0.0


# state of a controller run between samples (module docstring, "Period skipping"): ξ, ξ', r_{h−1}, v_{h−1},
# y_{h−1}, φ_A, ring position; then bookkeeping: tail min and max, the period found (0: none yet)
CX, CV, CRP, CVP, CY, CFA, CPOS, CTMIN, CTMAX, CPER, CEXT, CAPP, CSAT, CPRF, CERR = range(15)
#: CEXT: the operator's force now (the approach's, σ + βV, until a one-sided wall first reads contact); CAPP: 1
#: during that approach, else 0 (a flag of its own: the approach's force may equal the push); CSAT: whether a
#: command reached the actuator's force limit (0 no, 1 before the tail, 2 in the tail: stats[SATURATION]); CPRF, CERR:
#: an outcome-only run's proven period (0: none) and the bound on how far its statistics of ξ may lie from the
#: every-sample run's (:func:`_drift_bound`, "Outcome-only runs" in the module docstring)
NCSTATE = 15
_REF = 6  # the reference state: ξ, ξ', r, v, y, φ_A at ref[0:6], then the d pending commands, oldest first


@njit(cache=True, inline="always")
def _same(a: float, b: float) -> bool:
    """``a`` equals ``b`` bit for bit (±0 differ; NaN never equals): :func:`dfa.core.kernel.same_state`'s rule."""
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


@njit(cache=True, inline="always")
def _keep(
    ref: FloatArray,
    ring: FloatArray,
    pos: int,
    delay: int,
    x: float,
    v: float,
    r_prev: float,
    v_prev: float,
    y: float,
    fa: float,
) -> None:
    """Store the loop's state in ``ref``, the pending commands in logical order (oldest first)."""
    ref[0], ref[1], ref[2], ref[3], ref[4], ref[5] = x, v, r_prev, v_prev, y, fa
    i = pos
    for j in range(delay):
        i = i + 1 if i < delay else 0
        ref[_REF + j] = ring[i]


@njit(cache=True, inline="always")
def _same_loop(
    ref: FloatArray,
    ring: FloatArray,
    pos: int,
    delay: int,
    x: float,
    v: float,
    r_prev: float,
    v_prev: float,
    y: float,
    fa: float,
    filtered: bool,
    lag: float,
) -> bool:
    """The loop's state equals the one kept in ``ref`` bit for bit (what the next sample reads; docstring)."""
    if not (_same(x, ref[0]) and _same(v, ref[1]) and _same(r_prev, ref[2])):
        return False
    if filtered and not (_same(v_prev, ref[3]) and _same(y, ref[4])):
        return False
    if lag != 0.0 and not _same(fa, ref[5]):
        return False
    i = pos
    for j in range(delay):
        i = i + 1 if i < delay else 0
        if not _same(ring[i], ref[_REF + j]):
            return False
    return True


# the passivity observer's and controller's state (issue 30; :func:`_command`): the observed energy E (over the
# window, as the controller sees it), the window's next position, the controller's force of this reading, the
# observed energy over the whole run, the energy the wall holds at the start (counted at reading 0:
# :func:`held_energy`), the mode of this reading's force (0 at v_h = 0, else IDLE, HELD or DEPENDS: what period
# skipping reads, :func:`_pc_repeats`), then the controller's d + 1 bookings (beside the command ring's slots), then
# the window's W terms
PE, PWPOS, PF, PTOT, PINIT, PMODE, PBK = 0, 1, 2, 3, 4, 5, 6
#: the controller's force at a reading with v_h ≠ 0 (:func:`_pc_force`): 0 as the ledger is >= 0 (IDLE), at its limit
#: (HELD), or a value that depends on the observed energy itself (DEPENDS); at v_h = 0 it is 0 whatever the energy
IDLE, HELD, DEPENDS = 1, 2, 4
_U = 2.0**-53  # the unit roundoff of a double: |fl(a ∘ b) − a ∘ b| <= u |a ∘ b|
#: An outcome-only run's approximate return: ξ within this many ticks of the reference (the rest proven, or not)
_XTOL = 1e-9


@njit(cache=True, inline="always")
def observer_size(delay: int, window: int) -> int:
    """Length of the observer's state array (:func:`_command`) for a delay of d samples and a window of W (0: none)."""
    return PBK + delay + 1 + window


@njit(cache=True, inline="always")
def _observe(pcs: FloatArray, applied: float, vh: float, delay: int, window: int) -> float:
    """E_obs(h) = E_obs(h − 1) − φ_{h−1} v_h: the energy into the wall up to reading h (KΔ²), over the last W
    samples with a window (W > 0), into ``pcs[PE]`` (and over the whole run into ``pcs[PTOT]``).

    φ_{h−1} = ``applied``, the command held over [h − 1, h) (the wall's own, its controller's force included),
    and v_h = r_h − r_{h−1} the readings' displacement over that sample: without the encoder and an amplifier
    lag, exactly the work the device did on the wall, −∫φ ξ' dτ over the sample (Ryu, Kim and Hannaford's
    sampled observer; see :class:`dfa.model.elements.PassivityController`).
    """
    term = -applied * vh + pcs[PINIT]  # reading 0 also counts the energy the wall holds at the start
    pcs[PINIT] = 0.0
    pcs[PTOT] += term
    e: float = pcs[PE] + term
    if window > 0:
        e = _windowed(pcs, e, term, delay, window)
    pcs[PE] = e
    return e


@njit(cache=True, nogil=True)
def _windowed(pcs: FloatArray, e: float, term: float, delay: int, window: int) -> float:
    """A windowed observer's E (:func:`_observe`): ``e`` = E + ``term`` less the term that leaves the last W, the
    new term stored in its place; at each wrap the window's sum afresh, so that no rounding accumulates over the
    run. Not inlined: only a windowed observer's runs call it (an inlined helper that takes an array costs a
    reference count a sample, :func:`_advance`)."""
    i = int(pcs[PWPOS])
    w0 = PBK + delay + 1
    e -= pcs[w0 + i]
    pcs[w0 + i] = term
    if i + 1 < window:
        pcs[PWPOS] = i + 1
    else:
        pcs[PWPOS] = 0
        e = 0.0
        for k in range(window):
            e += pcs[w0 + k]
    return e


@njit(cache=True, inline="always")
def held_energy(x0: float, quantize: bool, ctl: Controller) -> float:
    """E_obs(0): the energy the wall holds at ξ0 as its observer would have counted it had the device come there
    slowly (at rest, one tick at a time) from where the wall's force vanishes (KΔ²); 0 at ξ0 = 0 and outside a
    one-sided wall.

    Bilateral spring: the readings' staircase −(r + ½) vanishes between r = −1 and 0, so from r = 0 up,
    Σ_{0<=r<r0}(r + ½) = r0²/2, and from r = −1 down (|r0| − 1)²/2; without the encoder ½ξ0². A
    one-sided wall from its first reading inside r_e = ⌊s + ½⌋: Σ_{r=r_e}^{r0−1}(r + ½ − s) = n(r_e + ½ − s) +
    n(n − 1)/2, n = r0 − r_e; without the encoder ½((ξ0 − s)⁺)². Slow motion reads no velocity: the damper, filter
    and delay add nothing.
    """
    onesided, s = ctl[5], ctl[6]
    if not quantize:
        d = x0 - s if onesided else x0
        return 0.5 * d * d if (d > 0.0 or not onesided) else 0.0
    r0 = math.floor(x0)
    if not onesided:
        return 0.5 * r0 * r0 if r0 >= 0.0 else 0.5 * (r0 + 1.0) * (r0 + 1.0)
    re = math.floor(s + 0.5)
    n = r0 - re
    return n * (re + 0.5 - s) + 0.5 * n * (n - 1.0) if n > 0.0 else 0.0


@njit(cache=True, inline="always")
def _pending(pcs: FloatArray, delay: int, pos: int) -> float:
    """The dissipation the passivity controller has booked for its forces not yet applied and observed: the
    bookings of the d + 1 slots but slot ``pos``, which holds the command just observed (applied over [h − 1, h)),
    summed in slot order."""
    pending = 0.0
    for i in range(delay + 1):
        if i != pos:
            pending += pcs[PBK + i]
    return pending


@njit(cache=True, inline="always")
def _pc_force(ledger: float, vh: float, limit: float) -> tuple[float, int]:
    """The passivity controller's force at reading h (Hannaford and Ryu 2002): a damper α = −L/v_h² on v_h when
    the ledger L = E_obs + (:func:`_pending`) is negative, the force −α v_h = L/v_h clipped to ±``limit``; 0 when
    L >= 0 or v_h = 0. And the reading's mode (:data:`IDLE`, :data:`HELD`, :data:`DEPENDS`; 0 at v_h = 0; NaN:
    DEPENDS), what period skipping reads (:func:`_pc_repeats`)."""
    if not (ledger < 0.0 and vh != 0.0):
        return 0.0, (0 if vh == 0.0 else (IDLE if ledger >= 0.0 else DEPENDS))
    q = ledger if vh == 1.0 else (-ledger if vh == -1.0 else ledger / vh)  # ± a tick: exact, without a division
    return max(-limit, min(limit, q)), (HELD if (q <= -limit or q >= limit) else DEPENDS)


@njit(cache=True, inline="always")
def _controlled(
    ledger: float, vh: float, w: float, c: float, inside: bool, ctl: Controller
) -> tuple[float, float, int]:
    """The controller's force f (:func:`_pc_force`, its limit ``ctl[10]``) joined to the wall's command ``c``: the
    command (w + f) through a one-sided wall's clip (:func:`_shape`), and the force it lets through; and the mode."""
    f, mode = _pc_force(ledger, vh, ctl[10])
    if f != 0.0:
        cf = _shape(w + f, inside, ctl[5])
        f, c = cf - c, cf
    return f, c, mode


@njit(cache=True, inline="always")
def _pc_command(
    ledger: float, vh: float, w: float, c: float, inside: bool, ctl: Controller, quantize: bool
) -> tuple[float, float, int]:
    """:func:`_controlled` as :func:`_advance` runs it: the same force, command and mode, bit for bit, and with the
    controller held at its limit (or v_h = 0) on a bilateral wall with the encoder, no branch on v_h's value.

    There v_h = r_h − r_{h−1} is a whole number and the command ``c`` is w (no clip yet): with a finite ``ctl[10]`` =
    limit > 0, a ledger L <= −limit, |v_h| <= 1 and w finite and not ±0 (−(r_h + ½) is not zero), :func:`_pc_force`
    gives f = −limit·v_h at v_h = ±1 (|L/v_h| = |L| >= limit: held, mode :data:`HELD`) and f = +0, mode 0 at v_h = 0,
    and :func:`_controlled` the command w + f and the force (w + f) − w; at v_h = ±0, w + (−limit·v_h) = w ± 0 = w and
    w − w = +0, that f. Both computed here
    without branching on v_h: in a chatter (the sign of v_h changing at random) a branch on it mispredicts, on the
    loop's dependency chain (the reading, the force, the next sample's motion)."""
    limit = ctl[10]
    if quantize and not ctl[5] and 0.0 < limit < math.inf and ledger <= -limit and abs(vh) <= 1.0:
        if 0.0 < abs(w) < math.inf:
            cf = w + -limit * vh  # at v_h = ±0: w ± 0 = w (w is not ±0)
            return cf - w, cf, HELD * int(abs(vh))
    return _controlled(ledger, vh, w, c, inside, ctl)


@njit(cache=True, inline="always")
def _pc_track(
    e: float, m: int, lo: float, hi: float, modes: int, vmax: float, vh: float
) -> tuple[float, float, int, float]:
    """One more reading of a tracked period (:func:`_pc_repeats`) at energy ``e`` and mode ``m``: the range of E,
    the modes met, the largest |v_h| at a held force."""
    if m == HELD:
        vmax = max(vmax, abs(vh))
    return min(lo, e), max(hi, e), modes | m, vmax


@njit(cache=True, nogil=True)
def _pc_repeats(
    pcs: FloatArray,
    delay: int,
    limit: float,
    period: int,
    remaining: int,
    track: tuple[float, float, float, int, float],
) -> bool:
    """Whether a passivity controller's force repeats with the loop's state for the ``remaining`` readings of the run.

    Called when the loop's state (:func:`_same_loop`) is back after ``period`` readings over which ``track`` =
    (E at the start, least and largest E, the modes met, the largest |v_h| at a held force; :func:`_pc_track`) was
    kept. An unbounded observer's energy E is no part of that state (it accumulates), but the controller reads it
    only through its force f, which is 0 at v_h = 0, 0 while the ledger L = E + (booked) is >= 0 (IDLE), and
    exactly ±``limit`` while |L/v_h| >= limit with L < 0 (HELD): fl(L/v_h) lies beyond the representable limit
    whenever the exact quotient does. So if every reading of the period had v_h = 0 or one of these modes (not
    both), and E cannot leave that mode's side over the rest of the run, every later force is the period's, bit
    for bit, and the loop repeats (by induction over the readings). The terms t = −φ v_h repeat with the state.
    Each addition to E rounds by at most u |result|: the period's exact sum ΔE and its exact partial sums lie
    within (P + 2) u max|E| of E_h − E_0 and of (E over the period) − E_0; E after i more readings lies within
    E_h + m ΔE + (a partial sum) ± i u E_max, E_max bounding |E| over the R remaining readings. So E stays at most
    E_h + (max E − E_0) (+ rounding) when ΔE <= 0, and at least E_h − (E_0 − min E) when ΔE >= 0. The bookings
    pending (d of the d + 1 slots) are each at most limit·max|v_h| (held) or 0 (idle), or the one stored now.
    HELD: ΔE <= 0 and E + rise + bookings + limit·max|v_h| + rounding <= 0; IDLE: ΔE >= 0 and E − fall − bookings
    − rounding >= 0; a period with v_h = 0 throughout: always. Every rounding allowance is doubled, plus (P + d +
    8) u times every magnitude (the check's own roundings). NaN or inf anywhere: False. A skip leaves E where it
    was (a state of the same run whole periods earlier: the forces repeat from it as well).
    """
    e0, lo, hi, modes, vmax = track
    if modes & DEPENDS or (modes & IDLE and modes & HELD):
        return False
    if modes == 0:
        return True  # v_h = 0 at every reading: the force is 0 whatever the energy
    held = modes & HELD != 0
    f = limit * vmax if held else 0.0
    bk, least = 0.0, math.inf  # d of the d + 1 slots are pending at a reading: at most all but the least
    for i in range(delay + 1):
        b = max(abs(pcs[PBK + i]), f)
        bk += b
        least = min(least, b)
    bk -= least
    e, rem = pcs[PE], float(remaining)
    loc = max(abs(lo), abs(hi))
    err = (period + 2) * _U * loc  # the rounding of the period's sums
    de = e - e0
    efut = 2.0 * (abs(e) + (rem / period + 1.0) * (abs(de) + err) + (hi - lo) + err)
    slack = 2.0 * (rem * _U * efut + err + (period + delay + 8) * _U * (loc + (hi - lo) + bk + f))
    if not (math.isfinite(slack) and math.isfinite(bk) and rem * _U < 0.25):  # E_max holds while R u <= 1/2
        return False
    if held:
        return de + err <= 0.0 and e + (hi - e0) + bk + f + slack <= 0.0
    return de - err >= 0.0 and e - (e0 - lo) - bk - slack >= 0.0


@njit(cache=True, inline="always")
def _clip(c: float, top: float) -> float:
    """The actuator's force limit (:class:`dfa.model.elements.ForceLimit`): the command ``c`` clipped to ±``top``
    (φ_max = F_max/(KΔ); inf: none), after every other element. A command within the limit is returned as it is,
    bit for bit (no arithmetic: a limit never reached leaves the run unchanged)."""
    if c > top:
        return top
    if c < -top:
        return -top
    return c


@njit(cache=True, inline="always")
def _reading(
    x: float, r_prev: float, v_prev: float, y: float, h: int, quantize: bool, ctl: Controller
) -> tuple[float, float, float, float, float, float, bool]:
    """The wall's reading at sample h (:func:`_command` without the observer and the ring): r_h, v_h, y_h, the
    spring's part, w = that part − β_B y_h, the command c = w shaped by a one-sided wall (:func:`_shape`), and
    whether the reading is inside it. Without a damper, with the encoder, w is the spring's part itself (that is not
    −0, so subtracting 0·y = ±0 from it changes nothing while y is finite): one product and one difference fewer on
    the loop's dependency chain."""
    damping, pole, filtered = ctl[0], ctl[1], ctl[2]
    r = math.floor(x) if quantize else x
    vh = r - r_prev
    if filtered:
        y = pole * y + (1.0 - pole) * v_prev if h > 0 else 0.0
    else:
        y = vh
    base, inside = _base(r, quantize, ctl)
    w = base if (damping == 0.0 and quantize and abs(y) < math.inf) else base - damping * y  # base is not −0: exact
    return r, vh, y, base, w, _shape(w, inside, ctl[5]), inside


@njit(cache=True, inline="always")
def _command(
    x: float,
    r_prev: float,
    v_prev: float,
    y: float,
    pos: int,
    ring: FloatArray,
    h: int,
    delay: int,
    quantize: bool,
    ctl: Controller,
    pcs: FloatArray,
) -> tuple[float, float, float, float, int, float, bool]:
    """The controller at sample h (module docstring): read ξ(h), command c_h into the delay ring.

    Returns the reading r_h, the difference v_h, the filtered y_h, the spring's part −(r_h + ½) (a one-sided
    wall's: −(r_h + ½ − s) inside, 0 outside), the ring's new position, the command applied now, c_{h−d},
    and whether the reading is inside a one-sided wall (r_h + ½ > s; r_h > s without the encoder).

    With a state ``pcs`` (non-empty: :func:`observer_size`) the passivity observer adds the sample just ended
    (:func:`_observe`) and, with the controller on (``ctl[8]``), its force (:func:`_controlled`) joins the command
    (through a one-sided wall's clip: the force it adds is what the clip lets through), its booked dissipation
    −f v_h beside the command's slot and f in ``pcs[PF]``. Last, the actuator's force limit clips the command to
    ±φ_max (``ctl[11]``; :func:`_clip`) before it enters the delay ring: what the controller booked is its force
    before that clip.
    """
    r, vh, y, base, w, c, inside = _reading(x, r_prev, v_prev, y, h, quantize, ctl)
    if pcs.shape[0] > 0:
        e = _observe(pcs, ring[pos], vh, delay, ctl[9])
        f = 0.0
        if ctl[8]:
            f, c, mode = _controlled(e + _pending(pcs, delay, pos), vh, w, c, inside, ctl)
            pcs[PMODE] = mode
        pcs[PF] = f
        pcs[PBK + pos] = -f * vh
    c = _clip(c, ctl[11])
    ring[pos] = c
    pos = pos + 1 if pos < delay else 0
    return r, vh, y, base, pos, ring[pos], inside


@njit(cache=True, inline="always")
def _sample(
    x: float,
    v: float,
    r_prev: float,
    v_prev: float,
    y: float,
    fa: float,
    pos: int,
    pending: tuple[float, float],
    h: int,
    model: Model,
    ctl: Controller,
    k: SampleConstants,
    e_lag: float,
    ext: float,
    appr: bool,
    cmd: tuple[float, float, float, float, int, float, bool],
) -> tuple[float, float, float, float, float, float, int, float, float, int, float, bool]:
    """Sample h from the state between samples (module docstring); ``model`` = (μ, β, σ, d, quantize).

    Returns the next state (ξ, ξ', r, v, y, φ_A, ring position), the sample's
    lowest and highest turning point (±inf when none), whether the loop
    was in an absorbing state at the start of the sample (then not integrated): 0 no, 1 at rest, 3 a one-sided
    wall left for good (:func:`_gone`), and the operator's force ``ext``: the push p from the first reading
    inside a one-sided wall on (the approach's force before it; p throughout otherwise). ``cmd``: what
    :func:`_command` returned at this sample, and ``pending`` the ring's least and largest command after it
    (:func:`_extent`; read only at ξ' = 0 and with a one-sided wall): the caller runs both, as an inline helper
    that takes the observer's array or the ring costs a reference count of each a sample, a third of the
    controller kernel's time.
    """
    mu, beta, sigma, _, _ = model
    lag, kap = ctl[3], ctl[4]
    r, vh, y, base, pos, c, inside = cmd
    fa, ext, appr, absorbed = _contact(x, v, y, fa, pending, sigma, ctl, ext, appr, (vh, base, c, inside))
    if absorbed:
        return x, v, r_prev, v_prev, y, fa, pos, np.inf, -np.inf, absorbed, ext, appr
    push = ext
    if kap > 0.0 and not appr:  # the approach: the operator holds the speed against friction and the hand
        if lag != 0.0:
            raise RuntimeError("dfa.core.wall_kernel: an amplifier lag with a hand stiffness is not covered")
        x, v, lo_t, hi_t = hand_sample(x, v, c + push, mu, beta, sigma, kap)
    elif lag == 0.0:
        x, v, lo_t, hi_t = stepped(x, v, c + push, mu, sigma, k)
    else:
        x, v, lo_t, hi_t = lag_sample(x, v, c + push, fa + push, mu, beta, sigma, lag)
        fa = c + (fa - c) * e_lag  # e_lag = e^{−1/α}
    return x, v, r, vh, y, fa, pos, lo_t, hi_t, 0, ext, appr


@njit(cache=True, inline="always")
def _contact(
    x: float, v: float, y: float, fa: float, pending: tuple[float, float], sigma: float, ctl: Controller, ext: float,
    appr: bool, cmd: tuple[float, float, float, bool],
) -> tuple[float, float, bool, int]:  # fmt: skip
    """What :func:`_sample` settles before the motion: φ_A (the command itself without a lag), the operator's force and
    the approach (the push from the first reading inside a one-sided wall), and whether the loop is in an absorbing
    state (0 no, 1 at rest, 3 a one-sided wall left for good). ``cmd`` = (v_h, the spring's part, the command
    applied, inside) of this sample, ``y`` its y_h."""
    damping, pole, filtered, lag, kap, onesided, push = ctl[0], ctl[1], ctl[2], ctl[3], ctl[4], ctl[5], ctl[7]
    vh, base, c, inside = cmd
    if inside:
        ext, appr = push, False  # contact: the operator's force is the push from now on
    if lag == 0.0:
        fa = c
    if v == 0.0:
        ynext = pole * y + (1.0 - pole) * vh if filtered else 0.0
        cbase, cnext = _shape(base, inside, onesided), _shape(base - damping * ynext, inside, onesided)
        cbase, cnext = _clip(cbase, ctl[11]), _clip(cnext, ctl[11])  # monotone: the hull's ends, clipped
        if not appr and _absorbing(v, fa, sigma, pending, cbase, cnext, kap * x - push):
            return fa, ext, appr, 1
    elif not appr and _gone(v, fa, pending, inside, ctl):
        return fa, ext, appr, 3
    return fa, ext, appr, 0


@njit(cache=True, inline="always")
def stepped(
    x: float, v: float, phi: float, mu: float, sigma: float, k: SampleConstants
) -> tuple[float, float, float, float]:
    """One sample without a lag or a hand (:func:`dfa.core.kernel.step` under the force ``phi``): ξ, ξ' and the
    sample's lowest and highest turning point (±inf when none)."""
    x, v, xr, _, _, _, _, stopped = step(x, v, phi, mu, sigma, k)
    lo_t, hi_t = (xr, xr) if stopped else (np.inf, -np.inf)
    return x, v, lo_t, hi_t


@njit(cache=True, inline="always")
def _margin(x: float) -> float:
    """How far ξ lies from the nearest change of its reading ⌊ξ⌋ (ticks): min(ξ − ⌊ξ⌋, ⌊ξ⌋ + 1 − ξ)."""
    r = math.floor(x)
    return min(x - r, r + 1.0 - x)


@njit(cache=True, inline="always")
def _drift_bound(
    delta: float, period: int, remaining: int, ymax: float, vmax: float, fmax: float, mu: float, sigma: float
) -> tuple[float, float]:
    """(E, ρ) of an outcome-only run's proven period ("Outcome-only runs" in the module docstring): ρ bounds the
    rounding of one sample's update of ξ (three additions of terms |ξ'φ₁| <= |ξ'|, |(σ ± φ)φ₂/μ| <= (σ + |φ|)/μ
    to |ξ| <= ``ymax`` + 1), E how far ξ may drift from the period's values over the ``remaining`` samples:
    (R/P + 2)(|δ| + 2Pρ), δ the period's measured drift."""
    rho = 4.0 * _U * (ymax + 1.0 + vmax + (fmax + sigma) / mu)
    m = remaining // period + 2
    return m * (abs(delta) + 2.0 * period * rho), rho


#: The statistics of a period under proof before its first sample: largest |ξ|, |ξ'|, |φ|; least margin (:func:`_seen`).
_UNSEEN = (0.0, 0.0, 0.0, np.inf)


@njit(cache=True, inline="always")
def _seen(
    seen: tuple[float, float, float, float], x: float, v_old: float, v: float, force: float
) -> tuple[float, float, float, float]:
    """A period under proof with one more sample: the largest |ξ|, |ξ'| (at the sample's start and end) and |φ|,
    the least margin of ξ to a reading's change (:func:`_margin`)."""
    ymax, wmax, fmax, marg = seen
    return max(ymax, abs(x)), max(wmax, abs(v_old), abs(v)), max(fmax, abs(force)), min(marg, _margin(x))


@njit(cache=True, inline="always")
def _pc_fresh(pcs: FloatArray, pc: bool) -> tuple[float, float, float, int, float]:
    """A passivity controller's period watched from now (:func:`_pc_track`): E at its start, E's range, modes, the
    largest |v_h| (E = 0 without a controller)."""
    e = pcs[PE] if pc else 0.0
    return e, e, e, 0, 0.0


@njit(cache=True, inline="always")
def _pc_tracked(
    track: tuple[float, float, float, int, float], e: float, m: int, vh: float
) -> tuple[float, float, float, int, float]:
    """A watched period (:func:`_pc_fresh`) with one more reading at energy ``e`` and mode ``m``
    (:func:`_pc_track`); E at its start kept."""
    e0, elo, ehi, modes, vmax = track
    elo, ehi, modes, vmax = _pc_track(e, m, elo, ehi, modes, vmax, vh)
    return e0, elo, ehi, modes, vmax


@njit(cache=True, inline="always")
def _ended(ax: float, bound: float, travel: float) -> int:
    """Why a run ends at |ξ| = ``ax``: 2 past the divergence ``bound`` (NaN too), 4 past the device's ``travel``
    (its end stop: a repeating state never reaches it), else 0."""
    if not ax <= bound:
        return 2
    if ax > travel:
        return 4
    return 0


@njit(cache=True, inline="always")
def _loaded(
    st: FloatArray,
) -> tuple[float, float, float, float, float, float, int, float, float, int, float, bool, float]:
    """The run's state from ``st`` (as :func:`_store` writes it): ξ, ξ', r, v, y, φ_A, ring position, the tail's
    extremes, the period, the operator's force, approaching, saturated."""
    return (st[CX], st[CV], st[CRP], st[CVP], st[CY], st[CFA], int(st[CPOS]), st[CTMIN], st[CTMAX], int(st[CPER]),
            st[CEXT], st[CAPP] > 0.0, st[CSAT])  # fmt: skip


@njit(cache=True, inline="always")
def _peak(peak: float, ax: float) -> float:
    """The largest |ξ| so far (a NaN ``ax`` leaves it: the bound's test catches NaN)."""
    return ax if ax > peak else peak


@njit(cache=True, inline="always")
def _extremes(x: float, lo_t: float, hi_t: float, tmin: float, tmax: float) -> tuple[float, float]:
    """The tail's extremes with sample h's ξ and the turning points within it (:func:`tail_extremes`)."""
    tmin, tmax = tail_extremes(x, lo_t, lo_t < np.inf, tmin, tmax)
    return tail_extremes(x, hi_t, hi_t > -np.inf, tmin, tmax)


@njit(cache=True, inline="always")
def _saturation(sat: float, at_limit: bool, in_tail: bool) -> float:
    """The saturation flag: 1 once a command reached the actuator's force limit before the tail, 2 in the tail
    (never with no limit: the limit is inf)."""
    return max(sat, 2.0 if in_tail else 1.0) if at_limit else sat


@njit(cache=True, inline="always")
def _proved(
    st: FloatArray, drift: float, period: int, remaining: int, seen: tuple[float, float, float, float],
    model: tuple[float, float, float, int, bool], limit: float, pc_changes: bool,
) -> int:  # fmt: skip
    """``period`` when the period just watched proves the rest of an outcome-only run, else 0 ("Outcome-only runs"
    in the module docstring): the drift bound E < ¼, the least margin ``seen[3]`` of ξ to a reading's change above
    2E + 2ρ, the largest |ξ| ``seen[0]`` plus 2E within ``limit`` (the divergence bound and the travel), and no
    change of a passivity controller's force (``pc_changes``); records the period and the statistics' error in
    ``st``."""
    ymax, wmax, fmax, marg = seen
    err, rho = _drift_bound(drift, period, remaining, ymax, wmax, fmax, model[0], model[2])
    if err < 0.25 and marg > 2.0 * err + 2.0 * rho and ymax + 2.0 * err <= limit and not pc_changes:
        st[CPRF], st[CERR] = float(period), max(st[CERR], 2.0 * err + 4.0 * rho)
        return period
    return 0


@njit(cache=True, inline="always")
def _jumped(tail: FloatArray, in_tail: bool, h: int, h1: int, period: int, tail_start: int) -> int:
    """The samples of the whole periods left before h1, skipped: the tail's copied from the period before."""
    jump = (h1 - h) // period * period
    if in_tail:
        for i in range(h, h + jump):
            tail[i - tail_start] = tail[i - period - tail_start]
    return jump


@njit(cache=True, inline="always")
def _store(st: FloatArray, values: tuple[float, ...]) -> None:
    """The run's state back into ``st`` at the end of a range (CX … CAPP in order, then CSAT)."""
    x, v, r_prev, v_prev, y, fa, pos, tmin, tmax, period, ext, appr, sat = values
    st[CX], st[CV], st[CRP], st[CVP], st[CY], st[CFA] = x, v, r_prev, v_prev, y, fa
    st[CPOS], st[CTMIN], st[CTMAX], st[CPER], st[CEXT], st[CAPP] = pos, tmin, tmax, period, ext, appr
    st[CSAT] = sat


@njit(cache=True, inline="always")
def _observed(pcs: FloatArray, e: float, total: float, held: float, mode: int) -> None:
    """The observer's state that :func:`_advance` keeps in locals back into ``pcs`` (nothing without an observer)."""
    if pcs.shape[0] > 0:
        pcs[PE], pcs[PTOT], pcs[PINIT], pcs[PMODE] = e, total, held, mode


@njit(cache=True, nogil=True)
def _returned(
    st: FloatArray, ref: FloatArray, ring: FloatArray, pcs: FloatArray, e: float, tail: FloatArray,
    loop: tuple[float, float, float, float, float, float, int], exact: bool, at: tuple[int, int, int, int, bool],
    watch: tuple[int, bool, bool, float, int, int, tuple[float, float, float, float],
                 tuple[float, float, float, int, float]],
    model: Model, ctl: Controller, limit: float,
) -> tuple[int, int, int, int, bool, bool, float, int, int, tuple[float, float, float, float],
           tuple[float, float, float, int, float]]:  # fmt: skip
    """:func:`_advance` at sample h = ``at[0]`` of its range (h1, the run's n, the tail's start, whether in it
    follow), where the loop's state ``loop`` (ξ, ξ', r, v, y, φ_A, ring position) is back at the reference's, bit
    for bit (``exact``) or with ξ within :data:`_XTOL`: the period P found, and the whole periods left skipped
    once nothing can change them (module docstring: a passivity controller's force proven to repeat,
    :func:`_pc_repeats`; an approximate return proven over one more period, :func:`_proved`), else one more period
    watched from here. ``watch`` = (the proven period, verifying, tracking, the reference's ξ and sample, the
    span to its renewal, the watched period's statistics :func:`_seen` and :func:`_pc_tracked`). Returns P, h
    after the skip, the samples skipped and ``watch`` updated; ``e`` is the observer's E, kept in a local by
    :func:`_advance`, into ``pcs`` (what :func:`_pc_repeats` and :func:`_pc_fresh` read). Not inlined: it runs
    at returns of the state alone, and an inlined helper that takes arrays costs a reference count each."""
    if pcs.shape[0] > 0:
        pcs[PE] = e
    x, v, r_prev, v_prev, y, fa, pos = loop
    h, h1, n, tail_start, in_tail = at
    proven, verifying, tracking, rx, rh, span, seen, track = watch
    delay, pc = model[3], ctl[8]
    period = h - rh
    if not exact and proven == 0:  # an approximate return: one more period proves the rest of the run, or not
        if verifying:
            changes = pc and not _pc_repeats(pcs, delay, ctl[10], period, n - h + 1, track)
            proven = _proved(st, x - rx, period, n - h, seen, model, limit, changes)
            verifying = False
        if proven == 0:  # watch the next period from this state
            _keep(ref, ring, pos, delay, x, v, r_prev, v_prev, y, fa)
            return period, h, 0, proven, True, pc, x, h, 2 * period, _UNSEEN, _pc_fresh(pcs, pc)
    elif pc and proven == 0 and not (tracking and _pc_repeats(pcs, delay, ctl[10], period, n - h + 1, track)):
        # the controller's force may yet change: watch it over the next period, from this same state
        return period, h, 0, proven, False, True, rx, h, 2 * period, seen, _pc_fresh(pcs, True)
    jump = _jumped(tail, in_tail, h, h1, period, tail_start)
    return period, h + jump, jump, proven, False, tracking, rx, rh, h1, seen, track  # no renewals: < 1 period left


@njit(cache=True, nogil=True)
def _advance(
    st: FloatArray, ring: FloatArray, ref: FloatArray, h0: int, h1: int, mu: float, beta: float, sigma: float,
    delay: int, quantize: bool, bound: float, ctl: Controller, tail: FloatArray, tail_start: int,
    rec_x: FloatArray, rec_v: FloatArray, skip: bool, pcs: FloatArray, n: int, approx: bool,
) -> tuple[int, int, float, int]:  # fmt: skip
    """Samples h0 … h1 − 1 of a run of ``n`` samples from the state ``st``; return (end, why, peak |ξ|, samples skipped).

    ``ctl`` = (β_B, a, filtered, α, κ_h, one-sided, s, p, ..., φ_max, ξ_travel); why as :func:`dfa.core.kernel.advance`
    (0 ran through, 1 at rest at sample ``end``, 2 past ``bound`` in sample end − 1, 3 left a one-sided wall for
    good at sample ``end``, 4 past the device's travel in sample end − 1: |ξ| > ξ_travel, within the bound).
    The range lies before the tail or in it. With ``skip`` (no records),
    whole periods are skipped once the loop's state repeats bit for bit
    (Brent's cycle detection, the reference within this range; module docstring). With a passivity controller
    (an unbounded observer) only when its force provably repeats with the state to the run's end
    (:func:`_pc_repeats`; its accumulating energy ``pcs`` is not compared); not with a windowed observer.
    With ``approx`` (an outcome-only run) also when every part of the state but ξ repeats bit for bit and ξ has
    drifted by at most :data:`_XTOL`, once one more period proves the rest of the run ("Outcome-only runs").
    The reference of the cycle check is the state at sample ``rh`` (none at sample 0, where y_0 = 0 is forced, nor
    during an approach, whose operator's force is not part of the compared state), renewed after ``span`` samples.
    """
    filtered, lag, travel = ctl[2], ctl[3], ctl[12]
    model = (mu, beta, sigma, delay, quantize)
    k = sample_constants(mu, beta)
    e_lag = math.exp(-1.0 / lag) if lag > 0.0 else 0.0
    x, v, r_prev, v_prev, y, fa, pos, tmin, tmax, period, ext, appr, sat = _loaded(st)
    record, pc, top, obs = rec_x.shape[0] > 0, ctl[8], ctl[11], pcs.shape[0] > 0
    skip = skip and not record and (not pc or ctl[9] == 0)
    # an approximate return of ξ is provable only where ξ enters the loop through its reading alone (module docstring)
    apx = approx and skip and quantize and lag == 0.0 and ctl[4] == 0.0 and not ctl[5]
    proven = int(st[CPRF])  # the proven period of an outcome-only run (0: none yet)
    in_tail, peak, why, skipped, h = h0 >= tail_start, 0.0, 0, 0, h0
    rx, rh, span = (x if h0 > 0 and not appr else np.nan), h0, (period if period > 0 else 1)
    if skip:
        _keep(ref, ring, pos, delay, x, v, r_prev, v_prev, y, fa)
    tracking, track = False, _pc_fresh(pcs, False)  # a passivity controller's period under watch (_pc_fresh)
    verifying, seen = False, _UNSEEN  # an approximate return under proof: the period's statistics (_seen)
    # the observer's E, E over the run, the held energy still to count and the controller's mode: locals (_command)
    pe, ptot, pinit, pmode = (pcs[PE], pcs[PTOT], pcs[PINIT], int(pcs[PMODE])) if obs else (0.0, 0.0, 0.0, 0)
    while h < h1:
        r_old, v_old = r_prev, v  # r_{h−1}; ξ' at the sample's start
        r, vh, yh, base, w, c, inside = _reading(x, r_prev, v_prev, y, h, quantize, ctl)
        if obs:  # _command's observer and controller, inline (an inlined helper taking pcs costs a count a sample)
            term = -ring[pos] * vh + pinit  # _observe
            pinit, ptot, pe = 0.0, ptot + term, pe + term
            pe = _windowed(pcs, pe, term, delay, ctl[9]) if ctl[9] > 0 else pe
            pend = 0.0
            for i in range(delay + 1 if pc else 0):  # _pending (slot pos holds the command just observed)
                pend += pcs[PBK + i] if i != pos else 0.0  # pend is never −0: adding +0 leaves it bit for bit
            f, c, pmode = _pc_command(pe + pend, vh, w, c, inside, ctl, quantize) if pc else (0.0, c, pmode)
            pcs[PBK + pos] = -f * vh
        c = _clip(c, top)
        sat = _saturation(sat, abs(c) >= top, in_tail)  # c_h at the actuator's force limit
        ring[pos] = c  # c_h into the ring
        pos = pos + 1 if pos < delay else 0
        ends = _extent(ring) if (v == 0.0 or ctl[5]) else (0.0, 0.0)  # what the rest and exit tests read of the ring
        x, v, r_prev, v_prev, y, fa, pos, lo_t, hi_t, absorbed, ext, appr = _sample(
            x, v, r_prev, v_prev, y, fa, pos, ends, h, model, ctl, k, e_lag, ext, appr,
            (r, vh, yh, base, pos, c if delay == 0 else ring[pos], inside),  # d = 0: c_h, not read back
        )  # fmt: skip
        track = _pc_tracked(track, pe, pmode, r_prev - r_old) if tracking else track
        seen = _seen(seen, x, v_old, v, fa + ext) if verifying else seen
        if absorbed:
            why = absorbed  # 1 at rest, 3 left the one-sided wall for good
            break
        if record:  # the arrays are written here, not in a helper: passing them costs a reference count a sample
            rec_x[h + 1], rec_v[h + 1] = x, v
        ax = abs(x)
        peak = _peak(peak, ax)
        if in_tail:
            tail[h - tail_start] = x
            tmin, tmax = _extremes(x, lo_t, hi_t, tmin, tmax)
        h += 1
        why = _ended(ax, bound, travel)
        if why:
            break
        exact = _same(x, rx)  # ξ back bit for bit (rx is ref[0]; NaN: no reference), or within _XTOL (approx)
        back = exact or (apx and abs(x - rx) <= _XTOL)
        if (
            skip and back and (proven == 0 or (h - rh) % proven == 0)
            and _same_loop(ref, ring, pos, delay, rx, v, r_prev, v_prev, y, fa, filtered, lag)
        ):  # fmt: skip
            period, h, jump, proven, verifying, tracking, rx, rh, span, seen, track = _returned(
                st, ref, ring, pcs, pe, tail, (x, v, r_prev, v_prev, y, fa, pos), exact, (h, h1, n, tail_start, in_tail),
                (proven, verifying, tracking, rx, rh, span, seen, track), model, ctl, min(bound, travel),
            )  # fmt: skip
            skipped += jump
        elif skip and h - rh == span:
            rx, rh, span = (x if not appr else np.nan), h, 2 * span
            _keep(ref, ring, pos, delay, x, v, r_prev, v_prev, y, fa)
            tracking = verifying = False
    _observed(pcs, pe, ptot, pinit, pmode)
    _store(st, (x, v, r_prev, v_prev, y, fa, float(pos), tmin, tmax, float(period), ext, 1.0 if appr else 0.0, sat))
    return h, why, peak, skipped


@njit(cache=True, inline="always")
def _start(
    st: FloatArray, ring: FloatArray, x0: float, v0: float, quantize: bool, ctl: Controller, friction: float
) -> None:
    """Initial state: r_{−1} = r_0, v_{−1} = y_{−1} = 0, every past command and φ_A equal to c_0 (y = 0).

    A one-sided wall's run that starts outside, moving toward it (ξ'0 > 0), is an approach at constant speed: the
    operator's force balances the friction, ``friction`` = σ + β ξ'0 (and a hand's spring, which it holds, so that
    the sample is the step without it), until the wall first reads the device inside, and is the push p from then
    on (:func:`_sample`); otherwise it is p throughout.
    """
    r0 = math.floor(x0) if quantize else x0
    base, inside = _base(r0, quantize, ctl)
    onesided = ctl[5]
    base0 = _clip(_shape(base, inside, onesided), ctl[11])
    for i in range(ring.shape[0]):
        ring[i] = base0
    st[CX], st[CV], st[CRP], st[CVP], st[CY], st[CFA] = x0, v0, r0, 0.0, 0.0, base0
    st[CPOS], st[CTMIN], st[CTMAX], st[CPER], st[CSAT], st[CPRF], st[CERR] = 0.0, np.inf, -np.inf, 0.0, 0.0, 0.0, 0.0
    approach = onesided and not inside and v0 > 0.0
    st[CEXT], st[CAPP] = (friction, 1.0) if approach else (ctl[7], 0.0)


@njit(cache=True, nogil=True)
def applied_forces(
    xs: FloatArray, table: FloatArray, quantize: bool, out: FloatArray, energy: FloatArray, control: FloatArray
) -> None:
    """The force φ_A on the device at each sample instant of a recorded run (units of KΔ) into ``out``, the
    passivity observer's energy E_obs into ``energy`` (KΔ²) and the passivity controller's force into ``control``.

    ``xs`` holds ξ at the instants 0 … n (:func:`simulate_wall_kernel`'s ``rec_x``, or the spring kernel's:
    the spring is this loop with β_B = 0, no filter, no lag). The controller reads only these positions, so
    replaying it on them (the same :func:`_command` and lag update as the run) gives, bit for bit, the
    command applied from instant h (c_{h−d}, held over [h, h + 1) without a lag) or, with a lag, the
    amplifier's output at the instant; at h = n the force the next sample would apply. ``energy[h]`` is
    E_obs(h), the energy into the wall over the readings 0 … h (:func:`_observe`; over the whole run, whatever
    the controller's ``window``), for any wall; with a passivity controller in ``table`` (the wall's kernel table,
    :mod:`dfa.core.table`) it acts as in the run and ``control[h]`` is the force it added to the command c_h (0 where
    it did not act). The hand spring and the push do not enter the command: they are ignored.
    """
    delay, c = decode_table(table)
    lag = c[3]
    ctl = (c[0], c[1], c[2], lag, 0.0, c[5], c[6], 0.0, c[8], c[9], c[10], c[11], c[12])  # no hand, no push
    ring, st = np.empty(delay + 1), np.empty(NCSTATE)
    pcs = np.zeros(observer_size(delay, ctl[9]))
    pcs[PINIT] = held_energy(xs[0], quantize, ctl)
    _start(st, ring, xs[0], 0.0, quantize, ctl, 0.0)
    r_prev, v_prev, y, fa, pos = st[CRP], st[CVP], st[CY], st[CFA], 0
    e_lag = math.exp(-1.0 / lag) if lag > 0.0 else 0.0
    for h in range(xs.shape[0]):
        if not math.isfinite(xs[h]):  # past a divergence the record holds NaN: so does the force
            out[h:] = np.nan
            energy[h:] = np.nan
            control[h:] = np.nan
            break
        r_prev, v_prev, y, _, pos, cmd, _ = _command(xs[h], r_prev, v_prev, y, pos, ring, h, delay, quantize, ctl, pcs)
        energy[h], control[h] = pcs[PTOT], pcs[PF]
        if lag == 0.0:
            fa = cmd
        out[h] = fa
        if lag != 0.0:
            fa = cmd + (fa - cmd) * e_lag


@njit(cache=True, nogil=True)
def run_wall_kernel(
    device: Device,
    initial: Start,
    run: RunSettings,
    table: FloatArray,
    rec_x: FloatArray,
    rec_v: FloatArray,
    stats: FloatArray,
    skip: bool,
) -> tuple[int, int, int]:
    """:func:`simulate_wall_kernel` with period skipping on or off; return (done, rest, samples integrated).

    The run is each of the NSEG segments (split where the tail starts) in
    :func:`_advance`. ``skip=False`` integrates every sample (the reference
    of ``tests/test_eq4_controller_period_skip.py``); records switch skipping off.
    The wall's ``table`` is decoded once (:func:`decode_table`).

    Examples
    --------
    A chattering loop (μ = 2, β = 2, σ = 0.1, ξ'0 = 2; damper, filter ν_c = 0.1, delay 1, lag α = 0.2)
    settles on a cycle of its whole state, bit for bit: of 50 001 samples, 231 are integrated.

    >>> from dfa.core.kernel import NSTATS
    >>> e, stats = np.empty(0), np.empty(NSTATS)
    >>> table = np.array([4.0, DELAY, 1, 1, 1.0, DAMPER, 1, 0, 0.5, FILTER, 1, 2, math.exp(-0.2 * math.pi),
    ...                   LAG, 1, 1, 0.2])
    >>> run_wall_kernel((2.0, 2.0, 0.1), (0.0, 2.0), (50_001, 8192, 1e6, True), table, e, e, stats, True)
    (50001, -1, 231)
    >>> run_wall_kernel((2.0, 2.0, 0.1), (0.0, 2.0), (50_001, 8192, 1e6, True), table, e, e, stats, False)
    (50001, -1, 50001)
    """
    done, rest, integrated, _ = _run_wall(
        device, initial, run, table, rec_x, rec_v, stats, _unliteral(skip), (1.0, 1.25, 1e-3), _unliteral(False)
    )
    return done, rest, integrated


@njit(cache=True, nogil=True)
def outcome_wall_kernel(
    device: Device, initial: Start, run: RunSettings, table: FloatArray, stats: FloatArray, rules: Rules
) -> tuple[int, int, int]:
    """:func:`simulate_wall_kernel`'s run for its outcome alone; return (done, rest, samples integrated).

    The outcome :func:`dfa.core.kernel.classify` gives ``stats`` with ``rules`` (stable amplitude, growth,
    settle) is the every-sample run's; the other statistics of ξ may differ from its by a bound far below the
    margins of the outcome's rules ("Outcome-only runs" in the module docstring): a run whose state returns
    with ξ drifted by rounding alone (a passivity controller held at its limit while the device chatters) stops
    being integrated once the rest of the run is proven, and is run again in full where the proof does not
    decide the outcome.
    """
    e, yes, no = np.empty(0), _unliteral(True), _unliteral(False)
    done, rest, integrated, sure = _run_wall(device, initial, run, table, e, e, stats, yes, rules, yes)
    if not sure:
        done, rest, integrated, _ = _run_wall(device, initial, run, table, e, e, stats, yes, rules, no)
    return done, rest, integrated


@njit(cache=True, inline="always")
def _unliteral(flag: bool) -> bool:
    """``flag`` typed as numba types a bool computed at run time, never as the literal ``True`` or ``False``.

    The kernels pass their flags to :func:`_run_wall` and :func:`_advance` through it, so that every caller
    shares one compiled copy of each: numba compiles a kernel again for each literal argument (about 25 s each
    on a cold cache, in every process that compiles), while the flags only feed run-time tests."""
    return bool(flag)


@njit(cache=True, nogil=True)
def _run_wall(
    device: Device, initial: Start, run: RunSettings, table: FloatArray, rec_x: FloatArray, rec_v: FloatArray,
    stats: FloatArray, skip: bool, rules: Rules, approx: bool,
) -> tuple[int, int, int, bool]:  # fmt: skip
    """:func:`run_wall_kernel`, with ``approx`` an outcome-only run (:func:`outcome_wall_kernel`); the fourth value
    says whether the outcome of ``stats`` under ``rules`` is the every-sample run's (:func:`_robust`)."""
    mu, beta, sigma = device
    x0, v0 = initial
    n, tail_len, bound, quantize = run
    delay, ctl = decode_table(table)
    pc, window = ctl[8], ctl[9]
    record = rec_x.shape[0] == n + 1
    rx_, rv_ = (rec_x, rec_v) if record else (rec_x[:0], rec_v[:0])
    st, ring, ref = np.empty(NCSTATE), np.empty(delay + 1), np.empty(_REF + delay)
    tail = np.empty(max(tail_len, 1))
    pcs = np.empty(observer_size(delay, window) if pc else 0)  # zeroed by begin_run
    begin_run(st, ring, pcs, stats, device, initial, quantize, ctl)
    if record:
        rec_x[0], rec_v[0] = x0, v0
    tail_start = n - tail_len
    end, why, integrated = n, 0, 0
    for seg in range(NSEG):
        lo, cut, hi = segment_ranges(seg, n, tail_start)
        why = 0
        for a, b in ((lo, cut), (cut, hi)):
            if b > a:
                end, why, peak, skipped = _advance(
                    st, ring, ref, a, b, mu, beta, sigma, delay, quantize, bound, ctl, tail, tail_start, rx_, rv_,
                    skip, pcs, n, approx,
                )  # fmt: skip
                integrated += end - a - skipped
                if peak > stats[seg]:
                    stats[seg] = peak
                if why != 0:
                    break
        if why != 0:
            break
    done, rest, sure = end_run(st, tail, tail_len, n, end, why, stats, rules, mu, rec_x, rec_v)
    return done, rest, integrated, sure


@njit(cache=True, nogil=True)
def end_run(
    st: FloatArray, tail: FloatArray, tail_len: int, n: int, end: int, why: int, stats: FloatArray, rules: Rules,
    mu: float, rec_x: FloatArray, rec_v: FloatArray,
) -> tuple[int, int, bool]:  # fmt: skip
    """A run's end (:func:`_run_wall`, and the lanes of :mod:`dfa.core.wall_pair`): ``why`` as :func:`_advance`'s at
    sample ``end`` (0: it ran through its ``n`` samples); the flag of a run past the bound, out of a one-sided wall or
    past the travel into ``stats``, its statistics finished (:func:`_finish`, the records when ``rec_x`` has n + 1
    entries) and closed (:func:`close_run`). Returns (samples done, rest sample or −1, whether the outcome under
    ``rules`` is the every-sample run's). Not inlined: it runs once a run, and its callers compile it once."""
    done, rest = (end, end if why == 1 else -1) if why != 0 else (n, -1)
    if why >= 2:
        stats[NSEG + 5] = float(why - 1)  # 1 past the bound, 2 left, 3 past the travel (an end stop)
    _finish(st, tail, tail_len, n, done, rest, stats, rec_x, rec_v, rec_x.shape[0] == n + 1)
    return done, rest, close_run(st, tail, tail_len, n, done, rest, stats, rules, mu)


@njit(cache=True, inline="always")
def begin_run(
    st: FloatArray, ring: FloatArray, pcs: FloatArray, stats: FloatArray, device: Device, initial: Start,
    quantize: bool, ctl: Controller,
) -> None:  # fmt: skip
    """A run's start (:func:`_run_wall`, and the lanes of :mod:`dfa.core.wall_pair`): ``stats`` cleared (a one-sided
    wall's flag −1 set), the state ``st`` and the ring (:func:`_start`), the observer ``pcs`` (empty without a
    passivity controller) zeroed with the energy the wall holds at ξ0 (:func:`held_energy`)."""
    _, beta, sigma = device
    x0, v0 = initial
    for i in range(stats.shape[0]):
        stats[i] = 0.0
    if ctl[5]:  # flag −1: a one-sided wall's run, never unstable by its envelope alone (kernel.classify)
        stats[NSEG + 5] = -1.0
    _start(st, ring, x0, v0, quantize, ctl, sigma + beta * v0)
    for i in range(pcs.shape[0]):
        pcs[i] = 0.0
    if pcs.shape[0] > 0:
        pcs[PINIT] = held_energy(x0, quantize, ctl)


@njit(cache=True, inline="always")
def close_run(
    st: FloatArray, tail: FloatArray, tail_len: int, n: int, done: int, rest: int, stats: FloatArray, rules: Rules,
    mu: float,
) -> bool:  # fmt: skip
    """A run's saturation flag into ``stats`` once :func:`_finish` has run, and whether its outcome under ``rules`` is
    the every-sample run's (no approximate return proven, or one that decides every rule: :func:`_robust`)."""
    if stats.shape[0] > SATURATION:
        stats[SATURATION] = st[CSAT]
    return st[CERR] == 0.0 or _robust(n, done, rest, stats, tail, tail_len, rules, mu, st[CERR])


@njit(cache=True, nogil=True)
def _robust(
    n: int, done: int, rest: int, stats: FloatArray, tail: FloatArray, tail_len: int, rules: Rules, mu: float,
    err: float,
) -> bool:  # fmt: skip
    """Whether :func:`dfa.core.kernel.classify` gives ``stats`` the outcome it gives every run whose statistics of ξ
    lie within ``err`` of these (segment peaks, tail extremes, tail samples; the flags and the saturation exact):
    each rule of classify is decided with that margin ("Outcome-only runs" in the module docstring)."""
    stable, growth, settle = rules
    if rest >= 0 or done != n or stats[NSEG + 5] != 0.0 or tail_len < 2 or not math.isfinite(err):
        return False
    code = classify(n, done, rest, stats, stable, growth, settle, True, mu)[0]
    if stats[SATURATION] >= 2.0:
        return code == SATURATED  # the commands repeat exactly: so does the saturation flag
    top, mid = stats[NSEG - 1], stats[NSEG // 2]
    long_enough = n >= NSEG * 2.0 * math.pi * math.sqrt(mu)
    may = long_enough and top + err > growth * (mid - err) and top + err > 1.0
    must = long_enough and top - err > growth * (mid + err) and top - err > 1.0
    for i in range(NSEG - 4, NSEG - 1):
        may = may and stats[i + 1] + 2.0 * err >= stats[i]
        must = must and stats[i + 1] - 2.0 * err >= stats[i]
    if must:
        return code == UNSTABLE
    if may:
        return False
    hi = max(stats[NSEG - 3], stats[NSEG - 2], stats[NSEG - 1])
    lo = min(stats[NSEG - 3], stats[NSEG - 2], stats[NSEG - 1])
    centre, e2 = 0.5 * (stats[NSEG] + stats[NSEG + 1]), 2.0 * err
    sure, maybe = 0, 0  # upward crossings of the centre certain, and possible, within the margin
    for i in range(1, tail_len):
        y0, y1 = tail[i - 1] - centre, tail[i] - centre
        sure += 1 if (y0 < -e2 and y1 >= e2) else 0
        maybe += 1 if (y0 < e2 and y1 >= -e2) else 0
    if hi - lo - e2 > settle * (hi + err) or maybe < 2:
        return code == UNDECIDED
    if hi - lo + e2 > settle * (hi - err) or sure < 2:
        return False
    amp = 0.5 * (stats[NSEG + 1] - stats[NSEG])
    if amp + err < stable:
        return code == CHATTER
    return amp - err >= stable and code == OSCILLATING


@njit(cache=True, inline="always")
def _finish(
    st: FloatArray,
    tail: FloatArray,
    tail_len: int,
    n: int,
    done: int,
    rest: int,
    stats: FloatArray,
    rec_x: FloatArray,
    rec_v: FloatArray,
    record: bool,
) -> None:
    """The run's closing statistics (the tail's, the final state) and the record after a rest (held) or a stop (NaN)."""
    x, v = st[CX], st[CV]
    if done == n and rest < 0 and tail_len > 1:
        tail_stats(tail, tail_len, st[CTMIN], st[CTMAX], stats)
    stats[NSEG + 6], stats[NSEG + 7] = x, v
    if record:
        for i in range(done + 1, n + 1):
            rec_x[i] = x if rest >= 0 else np.nan
            rec_v[i] = v if rest >= 0 else np.nan


@njit(cache=True, nogil=True)
def simulate_wall_kernel(
    device: Device,
    initial: Start,
    run: RunSettings,
    table: FloatArray,
    rec_x: FloatArray,
    rec_v: FloatArray,
    stats: FloatArray,
) -> tuple[int, int]:
    """Run ``n`` samples with the wall; return (samples done, rest sample or −1).

    ``device`` = (μ, β, σ), ``initial`` = (ξ0, ξ'0) (ticks, ticks per sample), ``run`` = (n, tail length,
    bound, quantize) as for :func:`dfa.core.kernel.simulate_kernel`; ``table`` the wall's kernel table
    (:mod:`dfa.core.table`; :meth:`dfa.model.wall.WallParams.kernel_table`): its delay d, damper β_B, filter pole a,
    lag α, hand stiffness κ_h (:mod:`dfa.core.oscillator`; not with a lag), a one-sided wall's surface s (ticks;
    it pushes only while the reading is beyond it) and push p (a constant force toward the wall, KΔ), and the
    passivity controller (:func:`_command`) with its observer's window W in samples (0: unbounded) and its
    force limit (KΔ; inf: none), the actuator's force limit φ_max (KΔ; inf: none) on the command, and the device's
    travel ξ_travel (ticks; inf: none): a sample instant with |ξ| > ξ_travel (within ``bound``) ends the run there, at
    an end stop (flag 3 in ``stats[NSEG + 5]``, the final state that sample's). ``rec_x``/``rec_v`` (length n + 1)
    are written when they have that length. ``stats`` as in :func:`dfa.core.kernel.simulate_kernel` (segment peaks,
    tail, bound flag, final state), and ``stats[SATURATION]``: 0 no command reached the force limit, 1 one did
    before the tail only, 2 one did in the tail (:func:`dfa.core.kernel.classify` calls such a run saturated).
    Unrecorded runs skip repeated periods (:func:`run_wall_kernel`; same results bit for bit).
    """
    done, rest, _ = run_wall_kernel(device, initial, run, table, rec_x, rec_v, stats, _unliteral(True))
    return done, rest


@njit(cache=True, nogil=True)
def serial_wall_kernel(
    devices: Devices,
    initials: Starts,
    run: RunSettings,
    table: FloatArray,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
) -> None:
    """:func:`simulate_wall_kernel` for independent runs, one after the other; nothing recorded.

    Run i has (μ, β, σ) = (``devices[0][i]``, …) and (ξ0, ξ'0) = (``initials[0][i]``, ``initials[1][i]``);
    every run has the settings ``run`` and the wall ``table``.
    """
    empty = np.empty(0)
    mus, betas, sigmas = devices
    x0s, v0s = initials
    for i in range(mus.shape[0]):
        done[i], rest[i] = simulate_wall_kernel(
            (mus[i], betas[i], sigmas[i]), (x0s[i], v0s[i]), run, table, empty, empty, stats[i]
        )
