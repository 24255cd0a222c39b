"""Compiled kernel of the exact sampled-data simulator (numba, cached).

Dimensionless device (paper eq. 4-5), time in samples::

    μ ξ'' + β ξ' + σ sgn(ξ') = φ,   φ = −⌊ξ(h − d)⌋ − ½  constant on [h, h + 1).

While the device moves in direction s with constant force F = φ − σ s, the
exact solution after a time t is, with u = β t/μ and a = F/μ::

    ξ(t)  = ξ₀ + ξ'₀ t φ₁(u) + a t² φ₂(u)
    ξ'(t) = ξ'₀ e^{−u} + a t φ₁(u)
    φ₁(u) = (1 − e^{−u})/u,   φ₂(u) = (u − 1 + e^{−u})/u²

(φ₁ = 1, φ₂ = ½ at β = 0: the polynomial solution). The velocity reaches zero
at t* = (μ/β) log1p(−ξ'₀β/F) = −(ξ'₀μ/F)·log1p(x)/x, x = −ξ'₀β/F
(t* = −ξ'₀μ/F at β = 0); there the device sticks
for the rest of the sample when |φ| <= σ, otherwise it restarts in direction
sgn φ and cannot stop again within the sample. Energy dissipated by the
viscous term over a phase (closed form)::

    β ∫ ξ'² dt = β [ξ'₀² t φ₁(2u) + 2 ξ'₀ a t² ψ(u) + a² t³ χ(u)]
    ψ(u) = ((1 − e^{−u}) − ½(1 − e^{−2u}))/u²,  χ(u) = (u − 2(1 − e^{−u}) + ½(1 − e^{−2u}))/u³

and by Coulomb friction σ|Δξ|. Every function is evaluated without
cancellation (series below u = 0.5).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# outcome codes (also the codes of dfa.maps.StabilityMap.outcome and its .npz file)
REST = 0  # came to rest: the absorbing state was reached
OSCILLATING = 1  # persistent, settled cycle of amplitude >= stable_amplitude (1 tick)
UNSTABLE = 2  # |ξ| beyond the bound, or a growing envelope
CHATTER = 3  # never rested; persistent, settled cycle below stable_amplitude
UNDECIDED = 4  # the envelope is still changing at the end of the run: run longer

NSEG = 8  # segments of the run used to judge a growing or changing envelope
NSTATS = NSEG + 10  # length of the stats array of simulate_kernel


@njit(cache=True, inline="always")
def _phi1(u):
    if u < 0.5:
        s = 0.0
        term = 1.0  # (-u)^n/(n+1)!
        for n in range(22):
            s += term
            term *= -u / (n + 2)
        return s
    return -math.expm1(-u) / u


@njit(cache=True, inline="always")
def _phi2(u):
    if u < 0.5:
        s = 0.0
        term = 0.5  # (-u)^n/(n+2)!
        for n in range(22):
            s += term
            term *= -u / (n + 3)
        return s
    return (math.expm1(-u) + u) / (u * u)


@njit(cache=True, inline="always")
def _psi(u):
    if u < 0.5:
        s = 0.0
        fact = 2.0  # n!
        upow = 1.0  # u^(n-2)
        sign = 1.0
        for n in range(2, 26):
            if n > 2:
                fact *= n
                upow *= u
                sign = -sign
            s += sign * (2.0 ** (n - 1) - 1.0) * upow / fact
        return s
    return (-math.expm1(-u) + 0.5 * math.expm1(-2.0 * u)) / (u * u)


@njit(cache=True, inline="always")
def _chi(u):
    if u < 0.5:
        s = 0.0
        fact = 6.0
        upow = 1.0
        sign = 1.0
        for n in range(3, 27):
            if n > 3:
                fact *= n
                upow *= u
                sign = -sign
            s += sign * (2.0 ** (n - 1) - 2.0) * upow / fact
        return s
    return (u + 2.0 * math.expm1(-u) - 0.5 * math.expm1(-2.0 * u)) / (u * u * u)


@njit(cache=True, inline="always")
def _viscous(v, a, beta, mu, t):
    """β ∫₀ᵗ ξ'² dt for one phase."""
    if beta == 0.0:
        return 0.0
    u = beta * t / mu
    return beta * (v * v * t * _phi1(2.0 * u) + 2.0 * v * a * t * t * _psi(u) + a * a * t * t * t * _chi(u))


@njit(cache=True, inline="always")
def _hc(x):
    """Pseudo-elastic energy of the quantized spring, H_c = ½ξ² + ½(p − p²) (eq. 18)."""
    p = x - math.floor(x)
    return 0.5 * x * x + 0.5 * (p - p * p)


@njit(cache=True)
def simulate_kernel(mu, beta, sigma, x0, v0, n, delay, quantize, bound, tail_len, rec_x, rec_v, rec_e, stats):
    """Run ``n`` samples; return the number of samples done and the rest sample (−1: none).

    ``rec_x``/``rec_v`` (length n + 1) and ``rec_e`` (n × 4: generated,
    viscous, Coulomb, stored energy at the end of the sample) are written only
    when they have that length; pass empty arrays otherwise. ``stats`` (length
    NSTATS) receives the segment peaks of |ξ| (at the sample instants), then
    the tail's min, max (turning points inside samples included),
    centre-crossing count, first and last crossing time, a flag for
    exceeding ``bound``, the final ξ and ξ', and the tail's min and max of ξ
    at the sample instants (the readings that set the force).
    """
    record = rec_x.shape[0] == n + 1
    energy = rec_e.shape[0] == n
    rate = beta / mu
    e1 = math.exp(-rate)
    p1 = _phi1(rate)
    p2 = _phi2(rate)
    hist = np.empty(delay + 1)  # forces read at the last delay + 1 samples
    f0 = -(math.floor(x0) + 0.5) if quantize else -x0
    for i in range(delay + 1):
        hist[i] = f0
    for i in range(NSTATS):
        stats[i] = 0.0
    tail_start = n - tail_len
    tail = np.empty(max(tail_len, 1))
    tmin = np.inf
    tmax = -np.inf
    x = x0
    v = v0
    if record:
        rec_x[0] = x
        rec_v[0] = v
    rest = -1
    done = n
    for h in range(n):
        # force of this sample: the reading d samples ago
        fnew = -(math.floor(x) + 0.5) if quantize else -x
        for i in range(delay):
            hist[i] = hist[i + 1]
        hist[delay] = fnew
        phi = hist[0]
        # absorbing rest: stuck, and every pending force equals this one
        if v == 0.0 and abs(phi) <= sigma:
            same = True
            for i in range(delay + 1):
                if hist[i] != phi:
                    same = False
            if same:
                rest = h
                done = h
                break
        xs = x
        dvisc = 0.0
        dcoul = 0.0
        if v == 0.0 and abs(phi) <= sigma:
            pass  # stuck for the whole sample
        else:
            s = 1.0 if (v > 0.0 or (v == 0.0 and phi > 0.0)) else -1.0
            a = (phi - sigma * s) / mu
            x1 = x + v * p1 + a * p2
            v1 = v * e1 + a * p1
            if v1 * s > 0.0 or v == 0.0 or a == 0.0:  # a = 0: ξ' decays without crossing (may underflow to 0)
                if energy:
                    dvisc = _viscous(v, a, beta, mu, 1.0)
                    dcoul = sigma * abs(x1 - x)
                x = x1
                v = v1
            else:
                # velocity reaches zero at t* within this sample
                # t* = (μ/β) log1p(x) = (−ξ'/a) log1p(x)/x, x = −ξ'β/(aμ) > 0 (t* = −ξ'/a at β = 0)
                xq = -v * beta / (a * mu)
                tstar = (-v / a) * (math.log1p(xq) / xq if xq > 0.0 else 1.0)
                if tstar > 1.0:
                    tstar = 1.0  # rounding guard: v1 * s <= 0 means t* <= 1
                u = rate * tstar
                xr = x + v * tstar * _phi1(u) + a * tstar * tstar * _phi2(u)
                if energy:
                    dvisc = _viscous(v, a, beta, mu, tstar)
                    dcoul = sigma * abs(xr - x)
                if h >= tail_start:
                    if xr < tmin:
                        tmin = xr
                    if xr > tmax:
                        tmax = xr
                x = xr
                v = 0.0
                tr = 1.0 - tstar
                if abs(phi) > sigma and tr > 0.0:
                    s2 = 1.0 if phi > 0.0 else -1.0
                    a2 = (phi - sigma * s2) / mu
                    u2 = rate * tr
                    x2 = x + a2 * tr * tr * _phi2(u2)
                    v = a2 * tr * _phi1(u2)
                    if energy:
                        dvisc += _viscous(0.0, a2, beta, mu, tr)
                        dcoul += sigma * abs(x2 - x)
                    x = x2
        if record:
            rec_x[h + 1] = x
            rec_v[h + 1] = v
        if energy:
            dx = x - xs
            # generated = ∫(φ + q(ξ))ξ' dτ = φΔξ + ΔH_c   (eq. 20-23)
            gen = phi * dx + (_hc(x) - _hc(xs)) if quantize else phi * dx + 0.5 * (x * x - xs * xs)
            rec_e[h, 0] = gen
            rec_e[h, 1] = dvisc
            rec_e[h, 2] = dcoul
            rec_e[h, 3] = 0.5 * mu * v * v + (_hc(x) if quantize else 0.5 * x * x)
        ax = abs(x)
        seg = (h * NSEG) // n
        if ax > stats[seg]:
            stats[seg] = ax
        if h >= tail_start:
            tail[h - tail_start] = x
            if x < tmin:
                tmin = x
            if x > tmax:
                tmax = x
        if not ax <= bound:  # also catches NaN
            stats[NSEG + 5] = 1.0
            done = h + 1
            break
    # tail measurement: crossings of the centre level, interpolated
    if done == n and rest < 0 and tail_len > 1:
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
    stats[NSEG + 6] = x
    stats[NSEG + 7] = v
    if record and done < n:
        for i in range(done + 1, n + 1):
            rec_x[i] = x if rest >= 0 else np.nan
            rec_v[i] = v if rest >= 0 else np.nan
    if energy and done < n:
        stored = (0.5 * mu * v * v + (_hc(x) if quantize else 0.5 * x * x)) if rest >= 0 else np.nan
        fill = 0.0 if rest >= 0 else np.nan
        for i in range(done, n):
            rec_e[i, 0] = fill
            rec_e[i, 1] = fill
            rec_e[i, 2] = fill
            rec_e[i, 3] = stored
    return done, rest


@njit(cache=True)
def classify(n, done, rest, stats, stable_amplitude, growth, settle, quantize, mu):
    """Outcome code, amplitude, frequency, centre and force peak-to-peak of a run from its stats.

    In this order (``P_k``: peak |ξ| at the sample instants in the k-th eighth of the run):

    * rest: the kernel reached the absorbing state (``rest >= 0``);
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
        return UNSTABLE, amp, freq, centre, fpp
    if decay:  # linear loop: the envelope shrinks geometrically, i.e. it decays to rest
        return REST, amp, freq, centre, fpp
    hi = max(stats[NSEG - 3], stats[NSEG - 2], stats[NSEG - 1])
    lo = min(stats[NSEG - 3], stats[NSEG - 2], stats[NSEG - 1])
    if hi - lo > settle * hi or not count >= 2:
        return UNDECIDED, amp, freq, centre, fpp
    if amp < stable_amplitude:
        return CHATTER, amp, freq, centre, fpp
    return OSCILLATING, amp, freq, centre, fpp


@njit(cache=True)
def map_kernel(
    mu,
    betas,
    sigmas,
    x0s,
    v0s,
    n,
    delay,
    quantize,
    bound,
    tail_len,
    stable_amplitude,
    growth,
    settle,
    codes,
    amps,
    freqs,
):
    """Run one simulation per (β, σ, ξ0, ξ'0) point, recording nothing."""
    empty = np.empty(0)
    empty2 = np.empty((0, 4))
    stats = np.empty(NSTATS)
    for i in range(betas.shape[0]):
        done, rest = simulate_kernel(
            mu, betas[i], sigmas[i], x0s[i], v0s[i], n, delay, quantize, bound, tail_len, empty, empty, empty2, stats
        )
        c, a, f, _centre, _fpp = classify(n, done, rest, stats, stable_amplitude, growth, settle, quantize, mu)
        codes[i] = c
        amps[i] = a
        freqs[i] = f
