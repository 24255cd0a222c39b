"""Exact time-domain simulation of the sampled, quantized, frictional haptic loop.

The force is constant over each sample, so the dimensionless device
μξ'' + βξ' + σ sgn ξ' = φ (paper eq. 4-5) is integrated in closed form: no ODE
solver and no time step, exact to rounding at every sample instant, including
stick-slip (the exact time at which the velocity reaches zero, stiction while
|φ| <= σ, restart otherwise). See :mod:`dfa._kernel` for the formulas. The
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
:meth:`SimulationResult.physical`.

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

Examples
--------
>>> r = simulate(mu=100.0, beta=0.3, sigma=1.5, xi_dot0=2.0, samples=20000)
>>> r.outcome, r.rest_sample is not None
('rest', True)
>>> r = simulate(mu=100.0, beta=0.3, sigma=0.3, xi_dot0=1.0)   # σ < ½: can never rest
>>> r.outcome, r.force_peak_to_peak
('chatter', 1.0)
>>> r = simulate(mu=100.0, beta=0.0, sigma=0.2, xi_dot0=2.0, samples=20000)
>>> r.outcome
'unstable'
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np

from . import _kernel
from .criterion import spring_energy
from .errors import (
    DFAValueError,
    check_beta,
    check_delay,
    check_int,
    check_mu,
    check_nonnegative,
    check_positive,
    check_real,
    check_sigma,
)

__all__ = [
    "OUTCOMES",
    "SimulationResult",
    "EnergyRecord",
    "simulate",
    "preload_position",
    "stored_energy",
    "MAX_RECORD_BYTES",
    "default_samples",
    "CHUNK",
]

#: Outcome names indexed by the kernel's codes (the codes of ``StabilityMap.outcome``):
#: 0 rest, 1 oscillating, 2 unstable, 3 chatter, 4 undecided.
OUTCOMES = ("rest", "oscillating", "unstable", "chatter", "undecided")

#: Bounds of the automatic run length (:func:`default_samples`).
MIN_DEFAULT_SAMPLES = 50_000
MAX_DEFAULT_SAMPLES = 10_000_000

#: Largest trajectory (x, v and optional energy arrays) ``simulate`` will record.
MAX_RECORD_BYTES = 2 * 1024**3


def stored_energy(xi, xi_dot, mu: float, quantize: bool = True):
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


def _decay_time(mu: float, beta: float, sigma: float, amp0: float, delay: int) -> float:
    """Samples for the averaged amplitude dA/dτ = −aA − c to fall from ``amp0`` to 1 tick (inf: never)."""
    if amp0 <= 1.0:
        return 0.0
    a = (beta - 0.5 - delay) / (2.0 * mu)
    c = 2.0 * sigma / (math.pi * math.sqrt(mu))
    if a > 0.0:
        return math.log((amp0 + c / a) / (1.0 + c / a)) / a
    if a == 0.0:
        return (amp0 - 1.0) / c if c > 0.0 else math.inf
    threshold = c / -a  # the growth threshold: larger amplitudes grow
    if threshold <= amp0 or threshold <= 1.0:
        return math.inf
    return math.log((threshold - 1.0) / (threshold - amp0)) / -a


def _check_run(mu, beta, sigma, xi_dot0, xi0, delay) -> tuple[float, float, float, float, float, int]:
    """The validated inputs of one run (Table 1 groups, initial state, delay), shared by simulate and default_samples."""
    return (
        check_mu(mu),
        check_beta(beta),
        check_sigma(sigma),
        check_real("xi_dot0", xi_dot0, "give the initial speed in ticks per sample"),
        check_real("xi0", xi0, "give the initial position in ticks"),
        check_delay(delay),
    )


def default_samples(
    mu: float,
    beta: float,
    sigma: float,
    xi_dot0: float,
    xi0: float = 0.0,
    delay: int = 0,
    quantize: bool = True,
    *,
    cap: bool = True,
) -> int:
    """Run length (samples) long enough for the outcome to show (module docstring, "Default run length").

    2 t_d + 40 periods 2π√μ, where t_d is the time the averaged amplitude
    equation dA/dτ = −(β − ½ − d)/(2μ)·A − 2σ/(π√μ) takes from the energy
    amplitude A₀ = √(2 H_T(0)) (eq. 18-19) to one tick; at least
    ``MIN_DEFAULT_SAMPLES`` (the paper's 5·10⁴) and, with ``cap``, at most
    ``MAX_DEFAULT_SAMPLES`` (10⁷). Without ``cap`` an infinite t_d gives
    ``MAX_DEFAULT_SAMPLES`` times 10.

    Examples
    --------
    >>> default_samples(100.0, 0.3, 1.5, 2.0)            # decays within the paper's run
    50000
    >>> default_samples(156250.0, 0.125, 0.9554, 0.637)  # Impulse Engine at 50 kg, 0.1 m/s
    462407
    """
    m, b, s, v0, x0, d = _check_run(mu, beta, sigma, xi_dot0, xi0, delay)
    amp0 = math.sqrt(2.0 * float(stored_energy(x0, v0, m, bool(quantize))))
    td = _decay_time(m, b, s, amp0, d)
    top = MAX_DEFAULT_SAMPLES if cap else 10 * MAX_DEFAULT_SAMPLES
    n = 2.0 * td + 40.0 * 2.0 * math.pi * math.sqrt(m)
    if not n < top:
        return top
    return int(max(MIN_DEFAULT_SAMPLES, math.ceil(n)))


@dataclass(frozen=True)
class EnergyRecord:
    """Per-sample energy bookkeeping (paper section 6.1, eq. 18-23).

    Arrays of length ``samples``; entry h covers [h, h + 1).

    Attributes
    ----------
    generated : numpy.ndarray
        Energy generated by hold and quantizer, ∫(φ_A + ⌊ξ⌋ + ½)ξ' dτ.
    dissipated_viscous : numpy.ndarray
        β∫ξ'² dτ (closed form, computed independently of the trajectory update).
    dissipated_coulomb : numpy.ndarray
        σ∫|ξ'| dτ.
    stored : numpy.ndarray
        H_T at the end of each sample.
    initial_stored : float
        H_T at τ = 0.
    """

    generated: np.ndarray = field(repr=False)
    dissipated_viscous: np.ndarray = field(repr=False)
    dissipated_coulomb: np.ndarray = field(repr=False)
    stored: np.ndarray = field(repr=False)
    initial_stored: float

    def balance_residual(self) -> np.ndarray:
        """ΔH_T − (generated − dissipated) per sample; zero to rounding."""
        prev = np.concatenate([[self.initial_stored], self.stored[:-1]])
        return (self.stored - prev) - (self.generated - self.dissipated_viscous - self.dissipated_coulomb)


@dataclass(frozen=True)
class SimulationResult:
    """Result of :func:`simulate` (inputs, trajectory, outcome and measurements).

    Attributes
    ----------
    mu, beta, sigma, xi0, xi_dot0, samples, delay, quantize
        The inputs.
    xi, xi_dot : numpy.ndarray or None
        Position (ticks) and velocity (ticks per sample) at the samples
        0 … samples (length samples + 1); after an early rest they hold the
        rest state, after an unstable early stop NaN. None if not recorded.
    outcome : str
        ``"rest"``, ``"chatter"``, ``"oscillating"``, ``"unstable"`` or
        ``"undecided"`` (module docstring).
    amplitude : float
        Measured amplitude of the steady cycle in ticks (0 at rest, inf when the bound was exceeded).
    frequency : float or None
        Measured frequency in rad per sample (None when not measurable).
    centre : float
        Centre of the steady cycle in ticks.
    rest_sample : int or None
        First sample at which the device is at rest for good.
    samples_run : int
        Samples actually integrated (fewer at rest or past the bound).
    final_xi, final_xi_dot : float
        State at the end of the run.
    force_peak_to_peak : float
        Peak-to-peak of the force over the tail in units of KΔ: (max − min)
        of the levels ⌊ξ⌋ read at the tail's sample instants (of ξ without
        quantization); 0 at rest, inf past the bound.
    envelope : tuple of float
        Peak |ξ| (ticks, at the sample instants) of each eighth of the run;
        the growth and settling rules read it.
    suggested_samples : int or None
        For ``"undecided"``: a run length to try (at least 4 × samples).
    samples_auto : bool
        True when ``samples`` was chosen by :func:`default_samples`.
    energy : EnergyRecord or None
        Per-sample energy bookkeeping when requested.
    """

    mu: float
    beta: float
    sigma: float
    xi0: float
    xi_dot0: float
    samples: int
    delay: int
    quantize: bool
    outcome: str
    amplitude: float
    frequency: float | None
    centre: float
    rest_sample: int | None
    samples_run: int
    final_xi: float
    final_xi_dot: float
    force_peak_to_peak: float = 0.0
    envelope: tuple = ()
    suggested_samples: int | None = None
    samples_auto: bool = False
    xi: np.ndarray | None = field(default=None, repr=False)
    xi_dot: np.ndarray | None = field(default=None, repr=False)
    energy: EnergyRecord | None = field(default=None, repr=False)

    @property
    def period(self) -> float | None:
        """Period of the measured cycle in samples, 2π/ω."""
        return None if not self.frequency else 2.0 * math.pi / self.frequency

    def physical(self, device, stiffness: float) -> dict[str, object]:
        """Force step and frequency in physical units for a :class:`~dfa.device.Device` at stiffness K.

        Returns ``force_peak_to_peak_si`` (``force_peak_to_peak`` × KΔ, in N;
        N·m for a rotary device), ``force_unit``, ``frequency_hz`` (ω/(2πT),
        None when not measured) and ``amplitude_si`` (amplitude × Δ, m or rad).
        """
        k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        u = device.units
        hz = None if not self.frequency else self.frequency / (2.0 * math.pi * device.period)
        fpp = self.force_peak_to_peak * k * device.resolution
        amp = self.amplitude * device.resolution
        return {
            "force_peak_to_peak_si": fpp if math.isfinite(fpp) else None,
            "force_unit": u["force"],
            "frequency_hz": hz,
            "amplitude_si": amp if math.isfinite(amp) else None,
            "position_unit": u["position"],
        }

    def as_dict(self) -> dict[str, object]:
        """JSON-ready summary (the ``dfa simulate --json`` contract plus extras)."""

        def fin(x):
            return None if x is None or not math.isfinite(x) else x

        return {
            "outcome": self.outcome,
            "amplitude": fin(self.amplitude),
            "frequency": fin(self.frequency),
            "final_xi": fin(self.final_xi),
            "final_xi_dot": fin(self.final_xi_dot),
            "rest_sample": self.rest_sample,
            "samples_run": self.samples_run,
            "centre": fin(self.centre),
            "period": fin(self.period),
            "force_peak_to_peak": fin(self.force_peak_to_peak),
            "envelope": [fin(v) for v in self.envelope],
            "suggested_samples": self.suggested_samples,
            "samples_auto": self.samples_auto,
            "mu": self.mu,
            "beta": self.beta,
            "sigma": self.sigma,
            "xi0": self.xi0,
            "xi_dot0": self.xi_dot0,
            "samples": self.samples,
            "delay": self.delay,
            "quantize": self.quantize,
        }


def _tail_length(samples: int, mu: float) -> int:
    """Tail measured for amplitude and frequency: a quarter of the run, at most max(8192, 4 periods)."""
    cap = max(8192, int(4 * 2.0 * math.pi * math.sqrt(mu)))
    return int(min(samples, min(cap, max(2, samples // 4))))


#: Samples per kernel call of a long run (:func:`_run_chunked`): about 0.05 s each.
CHUNK = 1 << 22
#: Longest tail run in chunks: the tail is one call, recorded (16 bytes a sample, 64 MiB at most).
_TAIL_CALL_MAX = 1 << 22


def _run_chunked(m, b, s, x0, v0, n, d, quantize, bnd, tail, rx, rv, re, stats, *, progress=False):
    """The kernel run of :func:`simulate` in chunks, bit for bit the single call's result (delay 0 only).

    The state between samples is (ξ, ξ') alone when d = 0. Chunks never straddle one of the eight
    envelope segments ⌈kn/8⌉ or the tail; the tail is one call (its crossing measurements need it
    whole), whose segment peaks are read from its recorded trajectory. Returns (done, rest).
    """
    from tqdm.auto import tqdm

    start = n - tail
    segs = {-(-k * n // _kernel.NSEG) for k in range(1, _kernel.NSEG)}  # ⌈kn/8⌉: first sample of segment k
    cuts = sorted({0, start} | {c for c in segs if c < start} | set(range(0, start, CHUNK)))
    spans = [*zip(cuts[:-1], cuts[1:], strict=True), (start, n)]
    stats[:] = 0.0
    cs = np.empty(_kernel.NSTATS)
    x, v, done, rest = x0, v0, n, -1
    bar = tqdm(total=n, unit="sample", unit_scale=True, desc="simulate", disable=not progress, leave=False)
    try:
        for a, z in spans:
            k, is_tail = z - a, a == start
            sx = rx[a : z + 1] if rx.size else (np.empty(k + 1) if is_tail else rx)
            sv = rv[a : z + 1] if rv.size else (np.empty(k + 1) if is_tail else rv)
            c_done, c_rest = _kernel.simulate_kernel(
                m, b, s, x, v, k, d, quantize, bnd, k if is_tail else 0, sx, sv, re[a:z] if re.size else re, cs
            )
            if is_tail:  # segment peaks of the tail from its trajectory (the kernel's running max ignores NaN)
                h = np.arange(a, a + c_done)
                peaks = np.abs(sx[1 : c_done + 1])
                for seg in np.unique((h * _kernel.NSEG) // n):
                    sel = peaks[(h * _kernel.NSEG) // n == seg]
                    stats[seg] = max(stats[seg], float(np.fmax.reduce(sel, initial=0.0)))
                stats[_kernel.NSEG : _kernel.NSEG + 5] = cs[_kernel.NSEG : _kernel.NSEG + 5]
                stats[_kernel.NSEG + 8 :] = cs[_kernel.NSEG + 8 :]
            else:
                seg = (a * _kernel.NSEG) // n
                stats[seg] = max(stats[seg], float(cs[: _kernel.NSEG].max()))
            x, v = float(cs[_kernel.NSEG + 6]), float(cs[_kernel.NSEG + 7])
            stopped = c_rest >= 0 or cs[_kernel.NSEG + 5] == 1.0
            bar.update(c_done)
            if stopped:
                done, rest = a + c_done, (a + c_rest if c_rest >= 0 else -1)
                stats[_kernel.NSEG + 5] = cs[_kernel.NSEG + 5]
                _fill_after_stop(rx, rv, re, z, rest >= 0)
                break
    finally:
        bar.close()
    stats[_kernel.NSEG + 6], stats[_kernel.NSEG + 7] = x, v
    return done, rest


def _fill_after_stop(rx, rv, re, z, at_rest):
    """After a stop inside the chunk ending at sample z: the rest state (or NaN) for the samples beyond it."""
    if rx.size:
        rx[z + 1 :] = rx[z] if at_rest else np.nan
        rv[z + 1 :] = rv[z] if at_rest else np.nan
    if re.size:
        re[z:] = re[z - 1] if at_rest else np.nan


def simulate(
    mu: float,
    beta: float,
    sigma: float,
    xi_dot0: float,
    samples: int | None = None,
    xi0: float = 0.0,
    delay: int = 0,
    quantize: bool = True,
    *,
    record: bool = True,
    energy: bool = False,
    bound: float = 1.0e6,
    stable_amplitude: float = 1.0,
    growth: float = 1.25,
    settle: float = 1.0e-3,
    progress: bool = False,
) -> SimulationResult:
    """Simulate the sampled haptic loop exactly (paper eq. 4-5) from (ξ0, ξ'0).

    Parameters
    ----------
    mu, beta, sigma : float
        Dimensionless mass (> 0), damping (>= 0) and Coulomb friction (>= 0).
    xi_dot0 : float
        Initial velocity ξ'0 in ticks per sample.
    samples : int or None
        Number of samples to simulate (>= 1); None (default): chosen from the
        loop's time scales by :func:`default_samples` (50 000 to 10⁷).
    xi0 : float, optional
        Initial position in ticks (default 0). See :func:`preload_position`.
    delay : int, optional
        Computational delay d in samples: the force of sample h uses ξ(h − d).
    quantize : bool, optional
        True (default): φ = −⌊ξ⌋ − ½; False: the linear spring φ = −ξ.
    record : bool, optional
        Keep the trajectory (default True). Turn off for long runs.
    energy : bool, optional
        Keep the per-sample energy bookkeeping (off the fast path).
    bound : float, optional
        |ξ| (ticks) beyond which the run is declared unstable and stopped.
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
        (runs of more than ``CHUNK`` samples without delay; they are
        integrated in chunks of ``CHUNK`` samples, so Ctrl-C is honoured
        between chunks, with results identical to a single pass).

    Returns
    -------
    SimulationResult
    """
    m, b, s, v0, x0, d = _check_run(mu, beta, sigma, xi_dot0, xi0, delay)
    auto = samples is None
    if auto:
        n = default_samples(m, b, s, v0, x0, d, bool(quantize))
    else:
        n = check_int("samples", samples, minimum=1, fix="simulate at least one sample")
    bnd = check_positive("bound", bound)
    if not bnd > abs(x0):
        raise DFAValueError(f"bound = {bnd!r} is invalid: it must exceed |xi0| = {abs(x0)!r}; raise the bound")
    sa = check_nonnegative("stable_amplitude", stable_amplitude)
    gr = check_positive("growth", growth)
    if gr <= 1.0:
        raise DFAValueError(f"growth = {gr!r} is invalid: it must be > 1 (a ratio of envelope peaks)")
    st = check_nonnegative("settle", settle)
    nbytes = (16 * (n + 1) if record else 0) + (32 * n if energy else 0)
    if nbytes > MAX_RECORD_BYTES:
        raise DFAValueError(
            f"samples = {n} is invalid with record={record}, energy={energy}: the trajectory would need "
            f"{nbytes / 1024**3:.1f} GiB (limit {MAX_RECORD_BYTES / 1024**3:.0f} GiB); pass record=False "
            "(and energy=False) to get the outcome without storing the trajectory"
        )
    rx = np.empty(n + 1) if record else np.empty(0)
    rv = np.empty(n + 1) if record else np.empty(0)
    re = np.empty((n, 4)) if energy else np.empty((0, 4))
    stats = np.empty(_kernel.NSTATS)
    tail = _tail_length(n, m)
    run = (m, b, s, x0, v0, n, d, bool(quantize), bnd, tail, rx, rv, re, stats)
    if d == 0 and n > CHUNK and tail <= _TAIL_CALL_MAX:
        done, rest = _run_chunked(*run, progress=progress)
    else:
        done, rest = _kernel.simulate_kernel(*run)
    code, amp, freq, centre, fpp = _kernel.classify(n, done, rest, stats, sa, gr, st, bool(quantize), m)
    suggest = None
    if code == _kernel.UNDECIDED:
        suggest = max(4 * n, default_samples(m, b, s, v0, x0, d, bool(quantize), cap=False))
    fx, fv = float(stats[_kernel.NSEG + 6]), float(stats[_kernel.NSEG + 7])
    en = None
    if energy:
        en = EnergyRecord(
            re[:, 0].copy(),
            re[:, 1].copy(),
            re[:, 2].copy(),
            re[:, 3].copy(),
            float(stored_energy(x0, v0, m, bool(quantize))),
        )
    return SimulationResult(
        mu=m,
        beta=b,
        sigma=s,
        xi0=x0,
        xi_dot0=v0,
        samples=n,
        delay=d,
        quantize=bool(quantize),
        outcome=OUTCOMES[code],
        amplitude=float(amp),
        frequency=None if not np.isfinite(freq) else float(freq),
        centre=float(centre),
        rest_sample=None if rest < 0 else int(rest),
        samples_run=int(done),
        final_xi=fx,
        final_xi_dot=fv,
        force_peak_to_peak=float(fpp),
        envelope=tuple(float(v) for v in stats[: _kernel.NSEG]),
        suggested_samples=suggest,
        samples_auto=auto,
        xi=rx if record else None,
        xi_dot=rv if record else None,
        energy=en,
    )
