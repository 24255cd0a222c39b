"""Exact time-domain simulation of the sampled, quantized, frictional haptic loop.

The force is constant over each sample, so the dimensionless device
μξ'' + βξ' + σ sgn ξ' = φ (paper eq. 4-5) is integrated in closed form: no ODE
solver and no time step, exact to rounding at every sample instant, including
stick-slip (the exact time at which the velocity reaches zero, stiction while
|φ| <= σ, restart otherwise). See :mod:`dfa.core.kernel` for the formulas. The
compiled kernel (numba, cached on disk) allocates nothing per sample when no
trajectory is recorded.

Outcome of a run (``SimulationResult.outcome``)
-----------------------------------------------
Checked in this order; ``P_k`` is the peak |ξ| at the sample instants in the
k-th eighth of the run (``SimulationResult.envelope``).

``"rest"``
    the device came to rest: stuck (ξ' = 0, |φ| <= σ) with every pending
    force unchanged, the absorbing state that ends the run. Only this state
    is reported as rest. With the encoder (``quantize``) it needs σ >= ½,
    since |φ| = |⌊ξ⌋ + ½| >= ½ at every level: for σ < ½ a run never rests.
    Without quantization (``quantize=False``, the linear loop, which decays
    to rest but never reaches it exactly when σ = 0) rest also means an
    envelope that shrinks as the unstable rule below grows:
    P_4 > ``growth`` × P_7 (or a fall below 10⁻¹² of P_0, into the
    denormal numbers) and P_4 >= P_5 >= P_6 >= P_7.
``"unstable"``
    |ξ| exceeded ``bound`` ticks (default 10⁶), or the envelope grows:
    P_7 > ``growth`` (default 1.25) × P_4, P_7 > 1 tick (no tick floor
    without quantization: the linear loop has no scale), and
    P_4 <= P_5 <= P_6 <= P_7, in a run of at least 8 periods 2π√μ of the
    spring (in a shorter run |ξ| rises from the impact whatever the loop
    does, so the envelope decides nothing: such a run is undecided).
``"undecided"``
    the run was too short to tell: the envelope is still changing
    (max − min of P_5, P_6, P_7 exceeds ``settle`` (default 10⁻³) times
    their max: a decaying transient, or growth too slow for the rule above),
    or the tail holds less than one full cycle. The result carries
    ``suggested_samples``, a run length to try.
``"chatter"``
    never rested; the envelope is settled and the cycle's amplitude is below
    ``stable_amplitude`` (default 1 tick). The force still toggles between
    quantization levels (``force_peak_to_peak``, usually one step KΔ): a buzz
    the user feels (paper region b, "limit cycles of less than one tick").
``"oscillating"``
    settled, persistent cycle of ``stable_amplitude`` or more.

On steady cycles (μ from 1 to 1000, 4·10⁵ samples) the relative spread of
P_5..P_7 is below 10⁻⁴; a decaying or growing envelope shows a spread well
above 10⁻³ unless it changes by less than 0.1 % over a quarter of the run.

Amplitude and frequency are measured on the tail (the last quarter of the run,
at most max(8192, 4 periods 2π√μ) samples): amplitude is half the
peak-to-peak of ξ including the exact turning points inside samples,
frequency 2π/(mean period between upward crossings of the centre level).
``force_peak_to_peak`` is max − min of ⌊ξ⌋ over the tail's sample instants
(the force levels the controller output), in units of KΔ (of ξ itself
without quantization); multiply by K·Δ for newtons, or use
:meth:`SimulationResult.physical`. A saturated run of the spring with a force
limit gives the applied force's, the levels clipped to ±φ_max
(:func:`applied_peak_to_peak`). A run that left a one-sided wall or ended at
the device's end stop measured no cycle: its amplitude and force peak-to-peak
are NaN.

Default run length
------------------
With ``samples=None`` the run length follows the loop's own time scales
(:func:`default_samples`). The amplitude A of a free oscillation of the
sampled loop obeys, averaged over a period of 2π√μ samples, the
describing-function balance

    dA/dτ = −a A − c,   a = (β − ½ − d)/(2μ),   c = 2σ/(π√μ),

(viscous damping less the hold's half-sample delay and the computational
delay d, eq. 36-40; Coulomb friction removes 4σ ticks of amplitude per
period). From the energy amplitude A₀ = √(2 H_T(0)) (eq. 18-19) this gives
the time t_d to decay to one tick (infinite when the loop does not decay,
or A₀ is at or above the threshold c/|a| when a < 0). The default is
2 t_d + 40 periods, at least 50 000 samples (the paper's run, 50 s at
1 kHz) and at most 10⁷ (about 0.2 s of computation); when even that is
not enough the outcome is ``"undecided"`` rather than a guess. Example: the
Impulse Engine with its mass overridden to 50 kg (μ = 1.56·10⁵, β = 0.125,
σ = 0.955) hit at 0.1 m/s predicts t_d ≈ 1.8·10⁵ samples and rests at
sample 181 900; 50 000 samples alone end in a slowly decaying transient of
about 200 ticks (undecided).

Before the first sample the controller's past readings are taken equal to ξ0
(matters only with a computational delay).

With a wall (``wall=WallParams.of(...)``: computational delay, virtual damper,
velocity filter, amplifier lag; :mod:`dfa.model.wall`) the run goes
through :mod:`dfa.core.wall_kernel`, exact to rounding at the sample instants as well
(closed-form motion under the amplifier's exponential force, stops by a
bracketed root of the closed form, breakaway in closed form), with the same
outcome rules; "rest" then needs the proof that every future command and
amplifier force stays within ±σ while the device is stuck. A pure spring
controller runs the spring kernel unchanged. The default run length then uses
the controller's net damping β + β_B·G − ½ − d − α in ``a``
(:func:`default_samples`, :func:`net_damping`).

Examples
--------
>>> from dfa.model.loop import Loop
>>> r = simulate(Loop.dimensionless(100.0, 0.3, 1.5), xi_dot0=2.0, samples=20000)
>>> r.outcome.value, r.rest_sample is not None
('rest', True)
>>> r = simulate(Loop.dimensionless(100.0, 0.3, 0.3), xi_dot0=1.0)   # σ < ½: can never rest
>>> r.outcome.value, r.force_peak_to_peak
('chatter', 1.0)
>>> r = simulate(Loop.dimensionless(100.0, 0.0, 0.2), xi_dot0=2.0, samples=20000)
>>> r.outcome.value
'unstable'
>>> from dfa.model.wall import WallParams
>>> c = WallParams.of(damping=0.5, lag=0.3)   # virtual damper β_B, amplifier lag α (samples)
>>> r = simulate(Loop.dimensionless(100.0, 0.3, 1.5, c), xi_dot0=2.0, samples=20000)
>>> r.outcome.value, r.rest_sample
('rest', 203)
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator, Sequence
from fractions import Fraction

import numpy as np
from numpy.typing import ArrayLike

from .._parallel import progress_bar
from ..checks import (
    check_beta,
    check_bool,
    check_bound,
    check_damping_rate,
    check_growth,
    check_int,
    check_mu,
    check_nonnegative,
    check_real,
    check_sigma,
    check_type,
    format_value,
)
from ..core import batch, kernel, wall_kernel
from ..core.table import stack_tables
from ..errors import DFAValueError
from ..model.elements import Coverage, ForceLimit, OneSided, Travel
from ..model.loop import LOOP_FIX, Loop, loop_first
from ..model.wall import WallParams
from ..results.simulation import CONTACTS as CONTACTS
from ..results.simulation import OUTCOMES as OUTCOMES
from ..results.simulation import EnergyRecord as EnergyRecord
from ..results.simulation import SimulationBatch as SimulationBatch
from ..results.simulation import SimulationResult as SimulationResult
from ..results.simulation import check_wall as check_wall
from ..results.status import ContactOutcome, SimulationOutcome
from .criterion import spring_energy

__all__ = [
    "OUTCOMES",
    "SimulationResult",
    "EnergyRecord",
    "simulate",
    "preload_position",
    "stored_energy",
    "MAX_RECORD_BYTES",
    "default_samples",
    "SimulationBatch",
    "simulate_batch",
    "CHUNK",
    "check_wall",
    "wall_run_codes",
    "mark_end_stops",
]


#: Bounds of the automatic run length (:func:`default_samples`).
MIN_DEFAULT_SAMPLES = 50_000
MAX_DEFAULT_SAMPLES = 10_000_000

#: Largest trajectory (x, v and optional energy arrays) ``simulate`` will record.
MAX_RECORD_BYTES = 2 * 1024**3


def stored_energy(xi: ArrayLike, xi_dot: ArrayLike, mu: float, quantize: bool = True) -> float | np.ndarray:
    """Total stored energy H_T = ½μξ'² + H_c(ξ) (paper eq. 18-19), vectorised.

    H_c(ξ) = ½ξ² + ½(p − p²), p = ξ − ⌊ξ⌋, is the exact integral of the
    restoring staircase ⌊s⌋ + ½; without quantization H_c = ½ξ².
    """
    v = np.asarray(xi_dot, dtype=float)
    return 0.5 * mu * v * v + spring_energy(xi, quantize)


def preload_position(mu: float, xi_dot: float) -> float:
    """Initial displacement ξ0 >= 0 whose spring energy equals the kinetic energy ½μξ'0² (section 5).

    H_c is linear on each cell [k, k + 1) with slope k + ½ and H_c(k) = k²/2,
    so ξ0 = k + (E − k²/2)/(k + ½) with E = ½μξ'0² and k the cell holding E.

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(K T²), > 0.
    xi_dot : float
        Speed ξ'0 in ticks per sample; its sign is ignored.

    Returns
    -------
    float
        The preload ξ0 in ticks, >= 0.

    Raises
    ------
    DFAValueError, DFATypeError
        If μ is not a finite number > 0, the speed is not a finite number, or the kinetic energy
        overflows a float.

    See Also
    --------
    simulate : Start a run from this position (``xi0``).
    passivity_criterion : The criterion with an initial position.

    Examples
    --------
    >>> preload_position(1.0, 1.0)          # E = ½ = H_c(1)
    1.0
    >>> round(preload_position(100.0, 0.05), 6)   # E = 0.125 < ½: first cell, slope ½
    0.25
    """
    m = check_mu(mu)
    v = check_real("xi_dot", xi_dot)
    two_e = m * v * v  # 2E = μξ'0², exact to one rounding
    if not math.isfinite(two_e):
        raise DFAValueError(
            f"xi_dot = {v!r} is invalid with mu = {m!r}: the kinetic energy ½μξ'0² overflows a float; "
            "give a smaller speed"
        )
    # Closed form, no loop: with r = 2E exactly (a Fraction), the cell is k = isqrt(⌊r⌋), since
    # k² <= ⌊r⌋ <= r < ⌊r⌋ + 1 <= (k + 1)²; then ξ0 = k + (r − k²)/(2k + 1) exactly, rounded once.
    r = Fraction(two_e)
    k = math.isqrt(math.floor(r))
    return float(k + (r - k * k) / (2 * k + 1))


def divergence_bound(xi0: float, xi_dot0: float, mu: float, floor: float = 1.0e6) -> float:
    """|ξ| (ticks) past which a run from (ξ0, ξ'0) counts as diverged: max(floor, 100 (A₀ + 1)).

    A₀ = √(2 H_T(0)) is the energy amplitude of the start (eq. 18-19), which a passive run never
    leaves; a fixed bound below it would call the impact's own travel a divergence.

    Examples
    --------
    >>> divergence_bound(0.0, 1.0, 100.0)
    1000000.0
    >>> divergence_bound(0.0, 1.0e5, 800.0) > 2.8e8
    True
    """
    return _bound_of(_start_amplitude(xi0, xi_dot0, check_mu(mu)), floor)


def _bound_of(amp0: float, floor: float) -> float:
    """The divergence bound max(floor, 100 (A₀ + 1)) of a start of energy amplitude A₀ (:func:`divergence_bound`)."""
    return max(floor, 100.0 * (amp0 + 1.0))


def run_bounds(
    mu: float, beta: float, sigma: float, xi_dot0: float, xi0: float, wall: WallParams, floor: float
) -> tuple[int, float]:
    """(:func:`default_samples`, :func:`divergence_bound`) of a run whose groups and wall are already checked (a
    search's points, built from a valid device's groups): one energy amplitude for both, no validation (the
    searches ask for thousands; the checks were most of their cost).

    Examples
    --------
    >>> w = WallParams.of()
    >>> run_bounds(100.0, 0.3, 1.5, 2.0, 0.0, w, 1.0e6) == (default_samples(100.0, 0.3, 1.5, 2.0, wall=w),
    ...                                                   divergence_bound(0.0, 2.0, 100.0, 1.0e6))
    True
    """
    amp0 = _start_amplitude(xi0, xi_dot0, mu)
    return _samples_of(mu, beta, sigma, amp0, wall), _bound_of(amp0, floor)


def _start_amplitude(xi0: float, xi_dot0: float, mu: float, quantize: bool = True) -> float:
    """A₀ = √(2 H_T(0)), the energy amplitude of the start (eq. 18-19), or the package's error where 100 (A₀ + 1)
    (the divergence bound) overflows a float: the one rule of :func:`divergence_bound` and :func:`default_samples`.

    Examples
    --------
    >>> _start_amplitude(0.0, 2.0, 1.0)
    2.0
    """
    with np.errstate(over="ignore", invalid="ignore"):
        amp0 = math.sqrt(2.0 * float(stored_energy(xi0, xi_dot0, mu, quantize)))
    if not math.isfinite(100.0 * (amp0 + 1.0)):
        raise DFAValueError(
            f"xi_dot = {xi_dot0!r} is invalid with xi0 = {xi0!r}, mu = {mu!r}: the start's energy ½μξ'0² + H_c(ξ0) "
            "overflows a float; give a smaller speed or start"
        )
    return amp0


def _decay_time(mu: float, net: float, sigma: float, amp0: float) -> float:
    """Samples for the averaged amplitude dA/dτ = −aA − c, a = net/(2μ), to fall from ``amp0`` to 1 tick (inf: never)."""
    if amp0 <= 1.0:
        return 0.0
    a = net / (2.0 * mu)
    c = 2.0 * sigma / (math.pi * math.sqrt(mu))
    if a > 0.0:
        return math.log((amp0 + c / a) / (1.0 + c / a)) / a
    if a == 0.0:
        return (amp0 - 1.0) / c if c > 0.0 else math.inf
    threshold = c / -a  # the growth threshold: larger amplitudes grow
    if threshold <= amp0 or threshold <= 1.0:
        return math.inf
    return math.log((threshold - 1.0) / (threshold - amp0)) / -a


def damper_gain(mu: float, wall: WallParams) -> float:
    """In-phase gain G of the controller's damper at the spring's frequency ω₀ = 1/√μ (rad/sample).

    The damper's force on the plant, per unit of the velocity jωξ, at ω = ω₀ (first harmonic, exact
    zero-order hold, no quantization): backward difference, filter F, delay d, hold and amplifier lag::

        G = Re{ (1 − e^{−jω})² F(e^{jω}) e^{−jωd} / ((jω)² (1 + jωα)) },
        F(z) = (1 − a) z⁻¹/(1 − a z⁻¹)   (F = 1 without filter)

    so that the damper adds β_B·G to the physical damping β: G → 1 as ω → 0 (a plain damper), less
    with a filter whose cutoff is near or below ω₀ or a delay that turns the damper's force out of
    phase with the velocity (G < 0: the damper then pumps energy in).

    Examples
    --------
    >>> round(damper_gain(1.0e6, WallParams.of(damping=1.0)), 4)      # slow oscillation: a plain damper
    1.0
    >>> damper_gain(100.0, WallParams.of(damping=1.0, cutoff=0.001)) < 0.2   # filtered well below ω₀
    True
    """
    w = 1.0 / math.sqrt(mu)
    z1 = complex(math.cos(w), -math.sin(w))  # e^{−jω}
    a = wall.filter_pole
    f = 1.0 if wall.cutoff is None else (1.0 - a) * z1 / (1.0 - a * z1)
    g = (1.0 - z1) ** 2 * f * z1**wall.delay / ((1j * w) ** 2 * (1.0 + 1j * w * wall.lag))
    return g.real


def net_damping(mu: float, beta: float, wall: WallParams) -> float:
    """Net averaged damping of the loop, β − ½ − d for the spring; with a damper or lag also − α + β_B·G.

    The hold's half sample, the computational delay d and the amplifier lag α (the low-frequency
    delay of 1/(1 + jωα)) each turn the spring's force into a negative damping of their length (the
    linear rule K < b/(T(d + ½) + τ_a) of issue 15); the damper adds β_B·G
    (:func:`damper_gain`). For the spring (any delay) exactly β − ½ − d.

    Examples
    --------
    >>> net_damping(100.0, 0.3, WallParams.of(delay=1))
    -1.2
    >>> round(net_damping(1.0e6, 0.3, WallParams.of(damping=1.0, lag=0.5)), 4)   # 0.3 − ½ − 0.5 + 1
    0.3
    """
    net = beta - 0.5 - wall.delay
    if wall.covers(Coverage.CLOSED_FORM):
        return net
    return net - wall.lag + wall.damping * damper_gain(mu, wall)


def _check_run(
    mu: float, beta: float, sigma: float, xi_dot0: float, xi0: float
) -> tuple[float, float, float, float, float]:
    """The validated inputs of one run (Table 1 groups, initial state), shared by simulate and default_samples."""
    out = (
        check_mu(mu),
        check_beta(beta),
        check_sigma(sigma),
        check_real("xi_dot0", xi_dot0, "give the initial speed in ticks per sample"),
        check_real("xi0", xi0, "give the initial position in ticks"),
    )
    check_damping_rate(out[1], out[0])  # beyond, the exact step overflows to NaN (a false "unstable")
    return out


def default_samples(
    mu: float,
    beta: float,
    sigma: float,
    xi_dot0: float,
    xi0: float = 0.0,
    quantize: bool = True,
    *,
    cap: bool = True,
    wall: WallParams | None = None,
) -> int:
    """Run length (samples) long enough for the outcome to show (module docstring, "Default run length").

    2 t_d + 40 periods 2π√μ, where t_d is the time the averaged amplitude
    equation dA/dτ = −a·A − 2σ/(π√μ), a = (β − ½ − d)/(2μ), takes from the
    energy amplitude A₀ = √(2 H_T(0)) (eq. 18-19) to one tick; at least
    ``MIN_DEFAULT_SAMPLES`` (the paper's 5·10⁴) and, with ``cap``, at most
    ``MAX_DEFAULT_SAMPLES`` (10⁷). Without ``cap`` an infinite t_d gives
    ``MAX_DEFAULT_SAMPLES`` times 10.

    With a ``wall`` the damping in ``a`` is the wall's low-frequency net damping β + β_B·G − ½ − d − α
    (:func:`net_damping`): the damper counts with its in-phase gain G at the spring's frequency (filter,
    delay and lag included, :func:`damper_gain`), the amplifier lag α as a further delay. When that net
    damping is <= 0, t_d is infinite unless Coulomb friction stops the amplitude first (as for the spring).
    The spring's wall (any delay) gives the spring's length exactly.

    Examples
    --------
    >>> default_samples(100.0, 0.3, 1.5, 2.0)            # decays within the paper's run
    50000
    >>> default_samples(156250.0, 0.125, 0.9554, 0.637)  # Impulse Engine at 50 kg, 0.1 m/s
    462407
    >>> default_samples(156250.0, 0.125, 0.9554, 0.637, wall=WallParams.of(damping=0.5))  # damper helps
    415065
    """
    w = check_wall(wall)
    m, b, s, v0, x0 = _check_run(mu, beta, sigma, xi_dot0, xi0)
    cap = check_bool("cap", cap, "pass True to cap the length at MAX_DEFAULT_SAMPLES, False for no cap")
    return _samples_of(m, b, s, _start_amplitude(x0, v0, m, check_quantize(quantize)), w, cap)


def _samples_of(m: float, b: float, s: float, amp0: float, w: WallParams, cap: bool = True) -> int:
    """:func:`default_samples` of checked groups and the start's energy amplitude A₀ (:func:`_start_amplitude`)."""
    td = _decay_time(m, net_damping(m, b, w), s, amp0)
    top = MAX_DEFAULT_SAMPLES if cap else 10 * MAX_DEFAULT_SAMPLES
    n = 2.0 * td + 40.0 * 2.0 * math.pi * math.sqrt(m)
    if not n < top:
        return top
    return int(max(MIN_DEFAULT_SAMPLES, math.ceil(n)))


#: Default outcome rules of :func:`simulate`, :func:`simulate_batch` and :func:`dfa.analysis.maps.stability_map`: a
#: settled cycle below STABLE_AMPLITUDE ticks is chatter; an envelope growing by GROWTH is unstable; one that
#: changes by more than SETTLE (relative) is undecided.
STABLE_AMPLITUDE, GROWTH, SETTLE = 1.0, 1.25, 1.0e-3


def _tail_lengths(samples: np.ndarray, mu: np.ndarray) -> np.ndarray:
    """Tail measured for amplitude and frequency: a quarter of the run, at most max(8192, 4 periods 2π√μ)."""
    periods = np.minimum(4 * 2.0 * math.pi * np.sqrt(mu), 2.0**62)  # above any run length: no int64 overflow
    cap = np.maximum(8192, periods.astype(np.int64))
    return np.minimum(samples, np.minimum(cap, np.maximum(2, samples // 4))).astype(np.int64)


def _tail_length(samples: int, mu: float) -> int:
    """:func:`_tail_lengths` of one run."""
    return int(_tail_lengths(np.array([samples], dtype=np.int64), np.array([mu], dtype=float))[0])


#: Samples per kernel call of a long run (:func:`_run_chunked`): about 0.05 s each.
CHUNK = 1 << 22


def _run_chunked(
    device: kernel.Device,
    initial: kernel.Start,
    run: kernel.RunSettings,
    d: int,
    rx: np.ndarray,
    rv: np.ndarray,
    re: np.ndarray,
    stats: np.ndarray,
    *,
    progress: bool = False,
    moving: bool = False,
) -> tuple[int, int]:
    """The kernel run of :func:`simulate` in pieces of at most ``CHUNK`` samples, bit for bit the single call.

    The same :func:`dfa.core.kernel.start` / :func:`~dfa.core.kernel.advance` / :func:`~dfa.core.kernel.finish` steps as
    :func:`dfa.core.kernel.simulate_kernel`, with the sample ranges cut into chunks: the run's state (ξ, ξ', the
    delay ring, the tail extremes) lives in arrays between calls, so Ctrl-C is honoured between chunks and a
    progress bar can follow the run. Any delay. With ``moving`` the delay ring starts with the forces of the
    readings ξ0 − jξ'0 (j = d … 1, oldest first: a motion at ξ'0 before t = 0) instead of ξ0's. Returns
    (done, rest). The arguments are :func:`dfa.core.kernel.simulate_kernel`'s.
    """
    (m, _, _), (x0, v0), (n, tail_len, _, quantize) = device, initial, run
    record, energy = rx.shape[0] == n + 1, re.shape[0] == n
    records, keep = (rx, rv, re), (record, energy)
    state, hist, tail = np.empty(kernel.NSTATE), np.empty(d + 1), np.empty(max(tail_len, 1))
    kernel.start(x0, v0, d, quantize, state, hist, stats)
    if moving:  # hist[j] is read j samples from now as the force of d samples before: ξ0 − (d + 1 − j)ξ'0
        for j in range(1, d + 1):
            hist[j] = kernel.force(x0 - (d + 1 - j) * v0, quantize)
    if record:
        rx[0], rv[0] = x0, v0
    tail_start, done, rest = n - tail_len, n, -1
    bar_kw = dict(total=n, unit="sample", unit_scale=True, desc="simulate", disable=not progress, leave=False)
    with progress_bar(**bar_kw) as bar:
        for lo, hi, k in _chunk_spans(n, tail_start):
            end, why, peak = kernel.advance(state, hist, lo, hi, device, run, d, tail, records, keep)
            if peak > stats[k]:
                stats[k] = peak
            bar.update(end - lo)
            if why != 0:
                done, rest = end, (end if why == 1 else -1)
                if why == 2:
                    stats[kernel.NSEG + 5] = 1.0
                break
    kernel.finish(state, done, rest, m, run, tail, stats, records, keep)
    return done, rest


def _chunk_spans(n: int, tail_start: int) -> Iterator[tuple[int, int, int]]:
    """(first, end, segment) of each kernel call: the eight envelope segments, cut where the tail starts and
    every ``CHUNK`` samples (the cuts :func:`dfa.core.kernel.simulate_kernel` makes, and more)."""
    for k in range(kernel.NSEG):
        lo, cut, hi = kernel.segment_ranges(k, n, tail_start)
        for a, z in ((lo, cut), (cut, hi)):
            for c in range(a, z, CHUNK):
                yield c, min(c + CHUNK, z), k


@loop_first("mu, beta, sigma, *, wall")
def simulate(
    loop: Loop,
    xi_dot0: float,
    samples: int | None = None,
    xi0: float = 0.0,
    quantize: bool = True,
    *,
    record: bool = True,
    energy: bool = False,
    bound: float | None = None,
    stable_amplitude: float = STABLE_AMPLITUDE,
    growth: float = GROWTH,
    settle: float = SETTLE,
    progress: bool = False,
    history: str = "fresh",
) -> SimulationResult:
    """Simulate the sampled haptic loop exactly (paper eq. 4-5) from (ξ0, ξ'0).

    Parameters
    ----------
    loop : Loop
        The loop's groups: dimensionless mass μ (> 0), damping β (>= 0) and Coulomb friction σ (>= 0), and the
        wall's (``loop.wall_params``: computational delay d, the force of sample h using ξ(h − d), virtual damper,
        velocity filter, amplifier lag; the paper's spring when it has none). ``Loop.dimensionless(mu, beta,
        sigma, wall_params)``, or ``Loop(device, wall)`` at the wall's K. The spring, or a spring with any delay,
        runs the spring kernel; otherwise :mod:`dfa.core.wall_kernel` runs the loop with the wall, exact to
        rounding at the sample instants (one compiled call: no progress bar, no energy record). A one-sided
        wall's run that starts outside moving toward it is an approach at constant speed (the operator's force
        balances friction until the first reading inside, then is the wall's push; :func:`dfa.approach_start`
        gives such a start). The former call ``simulate(mu, beta, sigma, xi_dot0, ..., wall=wall_params)``
        still works.
    xi_dot0 : float
        Initial velocity ξ'0 in ticks per sample.
    samples : int or None
        Number of samples to simulate (>= 1); None (default): chosen from the
        loop's time scales by :func:`default_samples` (50 000 to 10⁷).
    xi0 : float, optional
        Initial position in ticks (default 0). See :func:`preload_position`.
    quantize : bool, optional
        True (default): φ = −⌊ξ⌋ − ½; False: the linear spring φ = −ξ.
    record : bool, optional
        Keep the trajectory (default True). Turn off for long runs.
    energy : bool, optional
        Keep the per-sample energy bookkeeping (off the fast path).
    bound : float, optional
        Position abs(ξ) (ticks) beyond which the run is declared unstable and stopped. Default:
        :func:`divergence_bound`, max(10⁶, 100(A₀ + 1)) with A₀ the start's energy amplitude
        (eq. 18-19), so that an impact's own travel is never called a divergence.
    stable_amplitude : float, optional
        Tail amplitude (ticks) below which a settled cycle is ``"chatter"``
        rather than ``"oscillating"``.
    growth : float, optional
        Envelope growth ratio that marks a run unstable (> 1).
    settle : float, optional
        Largest relative spread of the last three envelope peaks of a
        settled run (>= 0); a larger spread is ``"undecided"``.
    progress : bool, optional
        Show a tqdm progress bar with an estimate of the time left on stderr
        (runs of more than ``CHUNK`` samples; they are integrated in chunks
        of ``CHUNK`` samples, so Ctrl-C is honoured between chunks, with
        results identical to a single pass).
    history : {"fresh", "moving"}, optional
        The loop's memory at t = 0: ``"fresh"`` (default: the past readings equal the first, as if at rest
        there) or ``"moving"``: the device moved at ξ'0 for the d samples before, so the d pending forces are
        those of the readings ξ0 − jξ'0, j = 1 … d (the spring with a delay; the start of
        :func:`~dfa.analysis.criterion.passivity_criterion`'s ``history="moving"``).

    Returns
    -------
    SimulationResult
        The outcome (rest, chatter, oscillating, unstable, undecided), the measured cycle and,
        with ``record``, the trajectory; ``.plot()`` draws it.

    Raises
    ------
    DFAValueError, DFATypeError
        If an input is out of range or not a number, ``bound`` does not exceed abs(ξ0), or the
        record would not fit in memory.

    See Also
    --------
    preload_position : A start position with the spring energy of a speed.
    stability_map : The outcome over a (β, σ) grid.
    passivity_criterion : The proven verdict the simulation is compared with.
    """
    record = check_bool("record", record, "pass True to keep the trajectory, False for the outcome only")
    energy = check_bool("energy", energy, "pass True to keep the energy bookkeeping, False for none")
    progress = check_bool("progress", progress, "pass True to show a progress bar, False for none")
    params, wp = check_type("loop", loop, Loop, LOOP_FIX).groups("simulate")
    w = check_wall(wp, energy)
    d = w.delay
    m, b, s, v0, x0 = _check_run(params.mu, params.beta, params.sigma, xi_dot0, xi0)
    check_hand_resonance(m, w)
    q = check_quantize(quantize)
    auto = samples is None
    fix = "simulate at least one sample"
    n = default_samples(m, b, s, v0, x0, q, wall=w) if auto else check_int("samples", samples, minimum=1, fix=fix)
    if bound is None:  # beyond the start's own travel: a passive run never counts as diverged
        bound = divergence_bound(x0, v0, m)
    bnd, sa, gr, st = check_rules(bound, stable_amplitude, growth, settle)
    check_bound(bnd, x0)
    _check_record_size(n, record, energy)
    rx = np.empty(n + 1) if record else np.empty(0)
    rv = np.empty(n + 1) if record else np.empty(0)
    re = np.empty((n, 4)) if energy else np.empty((0, 4))
    stats = np.empty(kernel.NSTATS)
    stop = travel_bound(bnd, w)  # the spring's kernel ends a run at the device's travel as at its bound
    tail_len = _tail_length(n, m)
    device, initial, settings = (m, b, s), (x0, v0), (n, tail_len, stop, q)
    moving = _check_history(history, w)
    if not w.covers(Coverage.CLOSED_FORM):
        settings = (n, tail_len, bnd, q)  # the controller kernel's table holds the travel (its own exit test)
        done, rest = wall_kernel.simulate_wall_kernel(device, initial, settings, w.kernel_table(), rx, rv, stats)
    elif n > CHUNK or moving:
        done, rest = _run_chunked(device, initial, settings, d, rx, rv, re, stats, progress=progress, moving=moving)
    else:
        done, rest = kernel.simulate_kernel(device, initial, settings, d, rx, rv, re, stats)
    mark_end_stops(stats, w, bnd)
    code, amp, freq, centre, fpp = kernel.classify(n, done, rest, stats, sa, gr, st, q, m)
    fpp = float(applied_peak_to_peak(np.array([code]), np.array([fpp]), stats[None, :], w, q)[0])
    suggest = max(4 * n, default_samples(m, b, s, v0, x0, q, cap=False, wall=w)) if code == kernel.UNDECIDED else None
    en = None
    if energy:
        h0 = float(stored_energy(x0, v0, m, q))
        en = EnergyRecord(re[:, 0].copy(), re[:, 1].copy(), re[:, 2].copy(), re[:, 3].copy(), h0)
    fields = (m, b, s, x0, v0, n, w, q, *_measured(code, amp, freq, centre, fpp, done, rest, stats), suggest, auto)
    contact = contact_outcome(code, float(stats[kernel.NSEG + 6]), float(stats[kernel.NSEG + 8]), w, q)
    return SimulationResult(
        *fields, contact=contact, xi=rx if record else None, xi_dot=rv if record else None, energy=en
    )


def travel_bound(bound: float, wall: WallParams) -> float:
    """The bound |ξ| (ticks) the spring's kernel runs with: ``bound``, or the device's travel ξ_travel if nearer.

    The spring's kernel (:mod:`dfa.core.kernel`) has no table: a wall it runs that holds a
    :class:`~dfa.model.elements.Travel` ends its runs at the travel through this bound (the same exit test, |ξ| >
    the bound at a sample instant, as the controller kernel's travel block), and :func:`mark_end_stops` names them.

    Parameters
    ----------
    bound : float
        The divergence bound in ticks.
    wall : WallParams
        The wall's groups.

    Returns
    -------
    float
        min(bound, ξ_travel); ``bound`` itself without a travel.
    """
    travel = wall.group(Travel)
    return bound if travel is None else min(bound, travel)


def mark_end_stops(stats: np.ndarray, wall: WallParams, bound: float | np.ndarray) -> None:
    """Flag, in the runs' ``stats``, the runs the spring's kernel stopped at the device's travel (outcome ``end_stop``).

    A run stopped past :func:`travel_bound` (flag 1 in ``stats[..., NSEG + 5]``) whose final |ξ| is within the
    divergence ``bound`` stopped at the travel: its flag becomes 3, as the controller kernel sets it
    (:mod:`dfa.core.wall_kernel`), and :func:`dfa.core.kernel.classify` gives ``end_stop``. Past ``bound`` (or NaN)
    it stays a divergence. Nothing changes without a travel.

    Parameters
    ----------
    stats : numpy.ndarray
        One run's stats (:data:`dfa.core.kernel.NSTATS`) or one row per run, changed in place.
    wall : WallParams
        The wall's groups.
    bound : float or numpy.ndarray
        The divergence bound(s) in ticks, one or one per run.
    """
    if wall.group(Travel) is None:
        return
    flag, final = stats[..., kernel.NSEG + 5], np.abs(stats[..., kernel.NSEG + 6])
    stats[..., kernel.NSEG + 5] = np.where((flag == 1.0) & (final <= bound), 3.0, flag)


def contact_outcome(
    code: int, final_xi: float, tail_min: float, wall: WallParams, quantize: bool = True
) -> ContactOutcome | None:
    """A one-sided wall's run as contact (issue 28 §1), from its outcome code and where the wall saw it.

    The wall sees the device inside while ξ >= ξ_e = ⌊s + ½⌋ (:meth:`~dfa.model.elements.OneSided.engage`; s
    without the encoder). At rest: on the wall when the final position is inside, else off it; a bounded run
    (oscillating, chatter) is ``bounces`` when a tail sample reads outside (``tail_min`` < ξ_e: contact lost and
    regained), else ``in_contact``; ``unstable`` is ``grows``, ``left`` is ``left`` and ``end_stop`` (past the
    device's travel) ``end_stop``.

    Parameters
    ----------
    code : int
        The kernel's outcome code (:data:`OUTCOMES` order).
    final_xi, tail_min : float
        The final position and the smallest position at the tail's sample instants, ticks.
    wall : WallParams
        The wall (None returned for a bilateral one).
    quantize : bool, optional
        With the encoder (default).

    Returns
    -------
    ContactOutcome or None

    Examples
    --------
    >>> w = WallParams(((OneSided, 0.0),))
    >>> contact_outcome(kernel.CHATTER, 0.2, -0.3, w).value, contact_outcome(kernel.REST, 0.4, 0.0, w).value
    ('bounces', 'rests')
    """
    if wall.covers(Coverage.SURFACE_START):  # the device cannot leave a wall that holds it
        return None
    arrays = (np.array([code]), np.array([final_xi]), np.array([tail_min]))
    return CONTACTS[int(contact_codes(*arrays, wall, quantize)[0])]


def contact_codes(
    codes: np.ndarray, final_xi: np.ndarray, tail_min: np.ndarray, wall: WallParams, quantize: bool = True
) -> np.ndarray:
    """:func:`contact_outcome` of many runs of one one-sided wall, as indices into :data:`CONTACTS` (one rule).

    Parameters
    ----------
    codes : numpy.ndarray of int
        The kernel's outcome codes.
    final_xi, tail_min : numpy.ndarray
        Final positions and the tails' smallest positions at the sample instants, ticks.
    wall : WallParams
        The one-sided wall.
    quantize : bool, optional
        With the encoder (default).

    Returns
    -------
    numpy.ndarray of int8
        Indices into :data:`CONTACTS`.
    """
    engage = OneSided.engage(wall.surface, quantize)
    c = np.asarray(codes)
    idx = {k: CONTACTS.index(k) for k in CONTACTS}
    out = np.full(c.shape, idx[ContactOutcome.UNDECIDED], dtype=np.int8)
    inside = np.asarray(final_xi) >= engage
    out[(c == kernel.REST) & inside] = idx[ContactOutcome.RESTS]
    out[(c == kernel.REST) & ~inside] = idx[ContactOutcome.RESTS_OFF]
    bounded = (c == kernel.OSCILLATING) | (c == kernel.CHATTER)
    out[bounded & (np.asarray(tail_min) < engage)] = idx[ContactOutcome.BOUNCES]
    out[bounded & ~(np.asarray(tail_min) < engage)] = idx[ContactOutcome.IN_CONTACT]
    out[c == kernel.UNSTABLE] = idx[ContactOutcome.GROWS]
    out[c == kernel.LEFT] = idx[ContactOutcome.LEFT]
    out[c == kernel.END_STOP] = idx[ContactOutcome.END_STOP]
    return out


def _check_history(history: object, wall: WallParams) -> bool:
    """True for a moving history (:func:`simulate`'s ``history``), or the package's error."""
    from ..checks import check_choice

    h = check_choice("history", history, ("fresh", "moving"))
    if h == "moving" and not wall.covers(Coverage.CLOSED_FORM):
        raise DFAValueError(
            "history = 'moving' is invalid with this wall: it is run for the spring with a delay (the delay ring); "
            "pass history='fresh'"
        )
    return h == "moving" and wall.delay > 0


def check_hand_resonance(mu: float | np.ndarray, wall: WallParams) -> None:
    """Refuse a hand stiffness whose resonance with the held mass reaches the Nyquist frequency.

    The device held by a spring of κ_h = k_h/K oscillates at ω = √(κ_h/μ) rad per sample
    (:mod:`dfa.core.oscillator`); the simulator's sample holds at most a few stops while ω < π, i.e.
    √(k_h/m)/(2π) below the Nyquist frequency 1/(2T), where every haptic grasp lies (k_h T²/m of the
    HapticMaster trial at 1 kHz: 2.4e-4).

    Raises
    ------
    DFAValueError
        If κ_h/μ >= π² for any μ.
    """
    kap = wall.hand_stiffness
    if kap > 0.0 and np.any(kap / np.asarray(mu, dtype=float) >= math.pi**2):
        w = math.sqrt(kap / float(np.min(mu)))
        raise DFAValueError(
            f"hand_stiffness = {format_value(kap)} (κ_h = k_h/K) is invalid with μ = {format_value(float(np.min(mu)))}: the "
            f"hand's resonance √(κ_h/μ) = {w:.4g} rad per sample must stay below π (the Nyquist frequency; "
            "√(k_h/m)/(2π) < 1/(2T)); give a hand stiffness below π² m/T², or check its units"
        )


def check_quantize(quantize: object) -> bool:
    """``quantize`` if it is True or False (numpy bools too); otherwise the package's error (never ``bool(x)``).

    Raises
    ------
    DFATypeError
        If ``quantize`` is not a bool: a string such as ``"False"`` would otherwise run with the encoder.
    """
    return check_bool("quantize", quantize, "pass True (with the encoder) or False (the linear spring)")


def wall_run_codes(
    mu: np.ndarray,
    beta: np.ndarray,
    sigma: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    ns: np.ndarray,
    bound: np.ndarray,
    walls: Sequence[WallParams],
) -> np.ndarray:
    """Outcome codes (:mod:`dfa.core.kernel`) of runs, each with its own wall, in one compiled call.

    Run i's outcome is what :func:`simulate` makes of (``mu[i]``, …, ``v0[i]``), ``ns[i]`` samples, bound
    ``bound[i]`` and ``walls[i]`` (WallParams the spring kernel does not run; its delay included), with simulate()'s
    tail length and default outcome rules (:func:`dfa.core.batch.batch_wall_outcomes`, then
    :func:`dfa.core.kernel.classify_batch`): a run is integrated until its outcome is proven
    (:func:`dfa.core.wall_kernel.outcome_wall_kernel`). No GIL is held: callers may run several calls on threads.
    """
    k = mu.size
    for w in walls:
        check_hand_resonance(mu, w)
    tables = stack_tables([w.kernel_table() for w in walls])
    stats, done, rest = np.empty((k, kernel.NSTATS)), np.empty(k, dtype=np.int64), np.empty(k, dtype=np.int64)
    runs = (ns, _tail_lengths(ns, mu), bound, True)
    rules = (STABLE_AMPLITUDE, GROWTH, SETTLE)
    batch.batch_wall_outcomes((mu, beta, sigma), (x0, v0), runs, tables, rules, stats, done, rest)
    codes = np.empty(k, dtype=np.int64)
    out = (codes, np.empty(k), np.empty(k), np.empty(k), np.empty(k))
    kernel.classify_batch(mu, ns, done, rest, stats, rules, True, out)
    return codes


def _measured(
    code: int, amp: float, freq: float, centre: float, fpp: float, done: int, rest: int, stats: np.ndarray
) -> tuple[SimulationOutcome, float, float | None, float, int | None, int, float, float, float, tuple]:
    """Outcome … envelope fields of a :class:`SimulationResult` (in field order) from the kernel's outputs.

    A run that left a one-sided wall for good or ended at the device's end stop measured no cycle: its amplitude
    and force peak-to-peak are NaN (null in JSON, with the reason of :meth:`SimulationResult.null_reasons`), not
    the kernel's placeholder 0, which would read as a run at rest.
    """
    if code in (kernel.LEFT, kernel.END_STOP):
        amp = fpp = math.nan
    return (
        list(SimulationOutcome)[code],  # OUTCOMES is in the enum's order
        float(amp),
        None if not np.isfinite(freq) else float(freq),
        float(centre),
        None if rest < 0 else int(rest),
        int(done),
        float(stats[kernel.NSEG + 6]),
        float(stats[kernel.NSEG + 7]),
        float(fpp),
        tuple(float(v) for v in stats[: kernel.NSEG]),
    )


def check_rules(
    bound: float, stable_amplitude: float, growth: float, settle: float
) -> tuple[float, float, float, float]:
    """Validated outcome rules (bound > 0, stable_amplitude >= 0, growth > 1, settle >= 0) of a simulation or map."""
    bnd = check_bound(bound)
    sa = check_nonnegative("stable_amplitude", stable_amplitude)
    return bnd, sa, check_growth(growth), check_nonnegative("settle", settle)


def _check_record_size(n: int, record: bool, energy: bool) -> None:
    nbytes = (16 * (n + 1) if record else 0) + (32 * n if energy else 0)
    if nbytes > MAX_RECORD_BYTES:
        raise DFAValueError(
            f"samples = {n} is invalid with record={record}, energy={energy}: the trajectory would need "
            f"{nbytes / 1024**3:.1f} GiB (limit {MAX_RECORD_BYTES / 1024**3:.0f} GiB); pass record=False "
            "(and energy=False) to get the outcome without storing the trajectory"
        )


def check_run_inputs(
    mu: ArrayLike, beta: ArrayLike, sigma: ArrayLike, xi_dot0: ArrayLike, xi0: ArrayLike
) -> tuple[np.ndarray, ...]:
    """Broadcast the per-run inputs to 1-D float arrays, each element checked as :func:`simulate` checks it
    (:func:`simulate_batch`'s and the searches' :func:`dfa.analysis.limits.runs.simulate_points`' check, one
    numpy pass however many runs)."""
    try:
        arrs = np.broadcast_arrays(
            *(np.atleast_1d(np.asarray(a, dtype=float)) for a in (mu, beta, sigma, xi_dot0, xi0))
        )
    except (TypeError, ValueError) as exc:
        raise DFAValueError(
            f"mu, beta, sigma, xi_dot0, xi0 are invalid: they must be numbers or arrays that broadcast together ({exc})"
        ) from None
    out = tuple(np.ascontiguousarray(a.ravel()) for a in arrs)
    m, b, s, v, x = out
    # μ a normal number (check_mu's rule: 1/μ must not overflow), β, σ >= 0, all finite
    bad = ~(np.isfinite(m) & (m >= sys.float_info.min) & np.isfinite(b) & (b >= 0) & np.isfinite(s) & (s >= 0))
    bad |= ~(np.isfinite(v) & np.isfinite(x))
    if bad.any():
        i = int(np.flatnonzero(bad)[0])
        _check_run(m[i], b[i], s[i], v[i], x[i])  # raises the message simulate would give for this run
        raise DFAValueError(f"run {i} is invalid: mu = {m[i]!r}, beta = {b[i]!r}, sigma = {s[i]!r} must be finite")
    check_damping_rate(b, m)
    return out


def simulate_batch(
    mu: ArrayLike,
    beta: ArrayLike,
    sigma: ArrayLike,
    xi_dot0: ArrayLike,
    samples: int,
    xi0: ArrayLike = 0.0,
    quantize: bool = True,
    *,
    bound: float | None = None,
    stable_amplitude: float = STABLE_AMPLITUDE,
    growth: float = GROWTH,
    settle: float = SETTLE,
    wall: WallParams | None = None,
) -> SimulationBatch:
    """Simulate many independent runs in one compiled call; each equals :func:`simulate` of that run alone.

    Parameters
    ----------
    mu, beta, sigma, xi_dot0, xi0 : float or array_like
        Per-run inputs (as in :func:`simulate`), broadcast together to a 1-D list of runs.
    samples : int
        Samples of every run (>= 1); give the same run length you would give :func:`simulate`.
    quantize, bound, stable_amplitude, growth, settle, wall
        Shared by every run, as in :func:`simulate`.

    Returns
    -------
    SimulationBatch
        Outcome and measurements of run i at index i; run i is bit for bit
        ``simulate(mu[i], …, samples, record=False)``.

    Examples
    --------
    >>> b = simulate_batch(100.0, [0.3, 0.0], [1.5, 0.2], 2.0, samples=20000)
    >>> b.outcomes()
    ['rest', 'unstable']
    """
    w = check_wall(wall)
    m, b, s, v0, x0 = check_run_inputs(mu, beta, sigma, xi_dot0, xi0)
    n = check_int("samples", samples, minimum=1, fix="simulate at least one sample")
    if bound is None:  # one bound for the batch: beyond the largest start's travel (divergence_bound)
        bound = max(divergence_bound(float(a), float(c), float(mm)) for a, c, mm in zip(x0, v0, m, strict=True))
    rules = check_rules(bound, stable_amplitude, growth, settle)
    if not np.all(rules[0] > np.abs(x0)):
        raise DFAValueError(f"bound = {rules[0]!r} is invalid: it must exceed every |xi0| ({np.abs(x0).max()!r})")
    res = run_points(m, b, s, x0, v0, n, w, check_quantize(quantize), *rules)
    codes, amps, freqs, centres, fpps, done, rest, stats = res
    return SimulationBatch(
        mu=m,
        beta=b,
        sigma=s,
        xi0=x0,
        xi_dot0=v0,
        samples=n,
        wall=w,
        quantize=bool(quantize),
        outcome=codes.astype(np.int8),
        amplitude=amps,
        frequency=freqs,
        centre=centres,
        force_peak_to_peak=fpps,
        rest_sample=rest,
        samples_run=done,
        final_xi=stats[:, kernel.NSEG + 6].copy(),
        final_xi_dot=stats[:, kernel.NSEG + 7].copy(),
        envelope=stats[:, : kernel.NSEG].copy(),
    )


def run_points(
    mu: np.ndarray,
    beta: np.ndarray,
    sigma: np.ndarray,
    x0: np.ndarray,
    v0: np.ndarray,
    n: int | np.ndarray,
    wall: WallParams,
    quantize: bool,
    bound: float | np.ndarray,
    stable_amplitude: float,
    growth: float,
    settle: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Validated float arrays in, kernel outputs out: (codes, amps, freqs, centres, fpps, done, rest, stats).

    ``n`` (samples) and ``bound`` are one value for every run or one per run. The spring runs in one call of
    :func:`dfa.core.batch.batch_kernel` (each run bit for bit :func:`dfa.core.kernel.simulate_kernel`, its tail
    length following its μ and length as in :func:`simulate`);
    no GIL is held, so callers may run several calls on threads. A ``wall`` (WallParams) the spring's kernel
    does not run (a damper, filter or lag) runs :func:`dfa.core.wall_kernel.serial_wall_kernel` instead, one
    call per group of runs with the same tail length (one ``n`` and ``bound`` for all).
    """
    delay = wall.delay
    check_hand_resonance(mu, wall)
    k = mu.shape[0]
    codes = np.empty(k, dtype=np.int64)
    amps, freqs, centres, fpps = np.empty(k), np.empty(k), np.empty(k), np.empty(k)
    done = np.empty(k, dtype=np.int64)
    rest = np.empty(k, dtype=np.int64)
    stats = np.empty((k, kernel.NSTATS))
    # writable copies: a read-only view (k = 1) would be another type, compiled once more by numba
    ns = np.array(np.broadcast_to(np.asarray(n, dtype=np.int64), (k,)))
    tails = _tail_lengths(ns, mu)
    if wall.covers(Coverage.CLOSED_FORM):
        bounds = np.array(np.broadcast_to(np.asarray(bound, dtype=float), (k,)))
        travel = wall.group(Travel)  # the device's travel, if any, is the spring kernel's bound (travel_bound)
        stops = bounds if travel is None else np.minimum(bounds, travel)
        batch.batch_kernel((mu, beta, sigma), (x0, v0), (ns, tails, stops, quantize), delay, stats, done, rest)
        mark_end_stops(stats, wall, bounds)
    else:
        table = wall.kernel_table()
        for t in np.unique(tails):
            j = np.flatnonzero(tails == t)
            st = np.empty((j.size, kernel.NSTATS))
            dn = np.empty(j.size, dtype=np.int64)
            rs = np.empty(j.size, dtype=np.int64)
            settings = (int(n), int(t), float(bound), quantize)
            wall_kernel.serial_wall_kernel((mu[j], beta[j], sigma[j]), (x0[j], v0[j]), settings, table, st, dn, rs)
            stats[j], done[j], rest[j] = st, dn, rs
    rules = (stable_amplitude, growth, settle)
    kernel.classify_batch(mu, ns, done, rest, stats, rules, quantize, (codes, amps, freqs, centres, fpps))
    fpps = applied_peak_to_peak(codes, fpps, stats, wall, quantize)
    return codes, amps, freqs, centres, fpps, done, rest, stats


#: The elements beside which the spring's force levels are the applied force (neither adds a force).
_FORCELESS = (ForceLimit, Travel)


def applied_peak_to_peak(
    codes: np.ndarray, fpps: np.ndarray, stats: np.ndarray, wall: WallParams, quantize: bool
) -> np.ndarray:
    """The force peak-to-peak of saturated runs of the spring with a force limit: the applied force's, clipped.

    The kernel measures max − min of the spring's levels ⌊ξ⌋ + ½ (ξ without the encoder) over the tail's sample
    instants (:func:`dfa.core.kernel.classify`). A run that reaches the actuator's force limit in its tail
    (``saturated``) applies those levels clipped to ±φ_max (:class:`~dfa.model.elements.ForceLimit`): on the spring
    alone with a limit (and a travel, which adds no force) its applied force's peak-to-peak is
    clip(⌊ξ_max⌋ + ½) − clip(⌊ξ_min⌋ + ½), at most 2 φ_max. Every other run keeps the kernel's value (a limit
    not reached in the tail clips nothing there); on a wall with other elements the value stays the spring's
    levels' (the rendering says so).

    Parameters
    ----------
    codes : numpy.ndarray
        The runs' outcome codes (:data:`OUTCOMES` order).
    fpps : numpy.ndarray
        The kernel's force peak-to-peaks in KΔ, one per run.
    stats : numpy.ndarray
        The runs' stats, one row per run (:data:`dfa.core.kernel.NSTATS`).
    wall : WallParams
        The wall's groups.
    quantize : bool
        With the encoder.

    Returns
    -------
    numpy.ndarray
        The force peak-to-peaks in KΔ (``fpps`` itself when nothing changes).

    Examples
    --------
    >>> st = np.zeros((1, kernel.NSTATS))
    >>> st[0, kernel.NSEG + 8], st[0, kernel.NSEG + 9] = -3983.2, 3983.7
    >>> applied_peak_to_peak(np.array([kernel.SATURATED]), np.array([7967.0]), st, WallParams.of(force_limit=29.85), True)
    array([59.7])
    """
    top = wall.group(ForceLimit)
    if top is None or any(k not in _FORCELESS for k, _ in wall.groups):
        return fpps
    lo, hi = stats[:, kernel.NSEG + 8], stats[:, kernel.NSEG + 9]
    if quantize:
        lo, hi = np.floor(lo) + 0.5, np.floor(hi) + 0.5
    applied = np.clip(hi, -top, top) - np.clip(lo, -top, top)
    return np.where(codes == kernel.SATURATED, applied, fpps)
