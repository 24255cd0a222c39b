"""Exact motion of the device held by a hand with stiffness: a damped oscillator with Coulomb stops (issue 28).

A hand of stiffness k_h to a fixed reference at the wall's origin (:class:`dfa.model.elements.HandSpring`,
group κ_h = k_h/K) adds the continuous force −κ_h ξ to the device (time in samples, ξ = x/Δ, forces in KΔ)::

    μ ξ'' + β ξ' + κ_h ξ + σ sgn ξ' = φ        (φ the held command, constant over the sample)

While the device moves in direction s the force F = φ − σ s is constant and, with λ = β/μ, ω² = κ_h/μ and
e = ξ − ξ₀, e'' + λ e' + ω² e = g, g = (F − κ_h ξ₀)/μ, e(0) = 0, e'(0) = ξ'₀. Hence::

    ξ(t)  = ξ₀ + ξ'₀ h(t) + g H(t),      ξ'(t) = ξ'₀ h'(t) + g h(t),

with h the impulse response (h'' + λh' + ω²h = 0, h(0) = 0, h'(0) = 1) and H = ∫₀ᵗ h (:func:`responses`):

- over-damped or critical (λ²/4 >= ω², λ > 0): the rates s₂ = λ/2 + γ, s₁ = ω²/s₂ (γ = √(λ²/4 − ω²), s₁
  without cancellation), δ = s₂ − s₁ = 2γ::

      h  = t e^{−s₁t} φ₁(δt),   h' = e^{−s₂t} − s₁ h,   H = t² [s₁ ρ(s₁t) + e^{−s₁t} δ φ₂(δt)]/s₂

  (φ₁, φ₂, ρ of :mod:`dfa.core.exprel`; H is the double integral of the amplifier lag's
  :func:`dfa.core.wall_kernel.lag_motion` with the rates s₁, s₂; sums of non-negative terms). At κ_h = 0
  (s₁ = 0, s₂ = λ) this is the free device of :func:`dfa.core.kernel.step`.
- under-damped (ω² > λ²/4): ω_d = √((ω − λ/2)(ω + λ/2)), h = e^{−λt/2} sin(ω_d t)/ω_d,
  h' = e^{−λt/2}(cos ω_d t − (λ/2) sin(ω_d t)/ω_d), and H = (1 − h' − λh)/ω² when ωt >= ½ (which loses
  less than a factor 8 to cancellation), else the Taylor series of H, whose coefficients follow from
  n(n − 1)a_n = −λ(n − 1)a_{n−1} − ω²a_{n−2}, a₂ = ½ (λt < 2ωt < 1: 24 terms reach rounding).

Stops. ξ' falls to zero at the first root of ξ'(t) in closed form: under-damped,
ξ'(t) = e^{−λt/2}[ξ'₀ cos ω_d t + B sin(ω_d t)/ω_d], B = g − λξ'₀/2, so ω_d t* = atan2(sξ'₀ω_d, −sB) (in
(0, π]; π when a restart begins at ξ'₀ = 0); over-damped, ξ'(t) = ξ'₀e^{−s₂t} + (g − s₁ξ'₀)(e^{−s₁t} −
e^{−s₂t})/δ has at most one root, t* = w log(1 + δw)/(δw) with w = −ξ'₀/(g − s₁ξ'₀) (when w > 0; the
free device's formula at δ = λ). At a stop the device sticks while the net static force obeys
|φ − κ_h ξ| <= σ (φ and ξ stay constant, so to the end of the sample), else restarts in direction
sgn(φ − κ_h ξ). A sample is a chain of such phases; the hand's resonance is below the Nyquist frequency
(ω < π, checked by the model), so there are at most a few.

The amplifier lag with a hand stiffness is not covered (the model refuses the pair).
``tests/test_hand_stiffness.py`` checks the samples against ``solve_ivp`` with stick-slip events.

Examples
--------
>>> x, v, lo, hi = hand_sample(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 1e-12)   # almost no hand: ξ = ξ' t
>>> round(x, 9), round(v, 9)
(1.0, 1.0)
"""

from __future__ import annotations

import math

import numpy as np

from .exprel import log1p_ratio, phi1, phi2, rho
from .jit import njit

__all__ = ["responses", "responses_array", "hand_motion", "hand_stop", "hand_sample"]

#: ω² = κ_h/μ below this is a spring below rounding: the free device (its force on |ξ| <= 1e6 ticks is < 1e-194,
#: and ω_d = √(ω²) would underflow in the stop time's division).
TINY = 1e-200

MAX_PHASES = 16  # per sample; with ω < π a sample holds at most one stop and restart (more are refused)


@njit(cache=True, inline="always")
def _series_h(lam: float, w2: float, t: float) -> float:
    """H(t) of the under-damped case from its Taylor series (module docstring), for λt, ωt below 1."""
    a2, a1 = 0.5, 0.0  # a_{n-1}, a_{n-2} while n runs from 3
    tn = t * t
    total = a2 * tn
    prev, prev2 = a2, a1
    for n in range(3, 27):
        an = (-lam * (n - 1) * prev - w2 * prev2) / (n * (n - 1))
        tn *= t
        total += an * tn
        prev2, prev = prev, an
    return total


@njit(cache=True, inline="always")
def responses(lam: float, w2: float, t: float) -> tuple[float, float, float]:
    """(h, h', H) at time ``t`` of the device held by a spring (module docstring); λ = β/μ, ω² = κ_h/μ > 0.

    Examples
    --------
    >>> h, hp, big = responses(0.0, 1.0, math.pi / 2)      # undamped, ω = 1: sin t, cos t, 1 − cos t
    >>> round(h, 12), round(hp, 12), round(big, 12)
    (1.0, 0.0, 1.0)
    """
    half = 0.5 * lam
    w2 = w2 if w2 >= TINY else 0.0
    om = math.sqrt(w2)
    if w2 == 0.0:  # a spring below rounding (κ_h/μ < TINY): the free device (dfa.core.kernel.step's φ₁, φ₂)
        return t * phi1(lam * t), math.exp(-lam * t), t * t * phi2(lam * t)
    if half >= om:  # over-damped or critical: two real rates
        gam = math.sqrt((half - om) * (half + om))
        s2 = half + gam
        s1 = w2 / s2
        dl = 2.0 * gam
        e1 = math.exp(-s1 * t)
        h = t * e1 * phi1(dl * t)
        hp = math.exp(-s2 * t) - s1 * h
        big = t * t * (s1 * rho(s1 * t) + e1 * dl * phi2(dl * t)) / s2
        return h, hp, big
    wd = math.sqrt((om - half) * (om + half))
    e = math.exp(-half * t)
    arg = wd * t
    sinc = t * (math.sin(arg) / arg if arg > 0.0 else 1.0)  # sin(ω_d t)/ω_d
    h = e * sinc
    hp = e * (math.cos(arg) - half * sinc)
    big = (1.0 - hp - lam * h) / w2 if om * t >= 0.5 else _series_h(lam, w2, t)
    return h, hp, big


@njit(cache=True)
def _responses_flat(lam: np.ndarray, w2: float, out: np.ndarray) -> None:  # pragma: no cover - compiled
    for i in range(lam.shape[0]):
        out[0, i], out[1, i], out[2, i] = responses(lam[i], w2, 1.0)


def responses_array(lam: np.ndarray, w2: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(h, h', H) at t = 1 for each λ of an array (any shape), ω² = ``w2``: :func:`responses` elementwise.

    Examples
    --------
    >>> h, hp, big = responses_array(np.array([0.0, 1.0]), 1e-300)   # the free device: φ₁(λ), e^{−λ}, φ₂(λ)
    >>> h.round(12).tolist(), big.round(12).tolist()
    ([1.0, 0.632120558829], [0.5, 0.367879441171])
    """
    a = np.array(lam, dtype=float)  # a copy, C-contiguous, of any shape (0-d included)
    out = np.empty((3, a.size))
    _responses_flat(a.ravel(), float(w2), out)
    return out[0].reshape(a.shape), out[1].reshape(a.shape), out[2].reshape(a.shape)


@njit(cache=True, inline="always")
def hand_motion(x0: float, v0: float, g: float, lam: float, w2: float, t: float) -> tuple[float, float]:
    """(ξ, ξ') after time ``t`` from (ξ₀, ξ'₀) under e'' + λe' + ω²e = g (module docstring).

    Examples
    --------
    >>> x, v = hand_motion(0.0, 0.0, 1.0, 0.0, 1.0, math.pi)   # undamped from rest: 1 − cos t, sin t
    >>> round(x, 12), round(v, 12)
    (2.0, 0.0)
    """
    h, hp, big = responses(lam, w2, t)
    return x0 + v0 * h + g * big, v0 * hp + g * h


@njit(cache=True, inline="always")
def hand_stop(v0: float, g: float, lam: float, w2: float, s: float) -> float:
    """First time t > 0 at which s ξ' falls to 0 in a phase of direction s (module docstring), or inf.

    ``v0`` has s v0 >= 0; at v0 = 0 (a restart) s g > 0.

    Examples
    --------
    >>> round(hand_stop(1.0, 0.0, 0.0, 1.0, 1.0), 12)   # undamped, ω = 1, from the centre: a quarter period
    1.570796326795
    """
    half = 0.5 * lam
    w2 = w2 if w2 >= TINY else 0.0
    om = math.sqrt(w2)
    if half >= om:
        gam = math.sqrt((half - om) * (half + om))
        s2 = half + gam
        s1 = w2 / s2 if s2 > 0.0 else 0.0  # s2 = 0 only for the undamped free device (ω² underflowed)
        den = g - s1 * v0
        if v0 == 0.0 or not s * den < 0.0:
            return np.inf  # the net acceleration never opposes the motion enough to stop it
        w = -v0 / den
        return w * log1p_ratio(2.0 * gam * w)
    wd = math.sqrt((om - half) * (om + half))
    b = g - half * v0
    return math.atan2(abs(v0) * wd, -s * b) / wd  # |ξ'₀| = s ξ'₀, never −0 (atan2(−0, x < 0) = −π)


@njit(cache=True, inline="always")
def hand_sample(
    x: float, v: float, c: float, mu: float, beta: float, sigma: float, kap: float
) -> tuple[float, float, float, float]:
    """One sample under the held command ``c`` with the hand stiffness κ_h = ``kap`` (module docstring).

    Returns (ξ, ξ' at the end, lowest and highest turning point; ±inf when none).
    """
    lam = beta / mu
    w2 = kap / mu
    t = 0.0
    lo_turn, hi_turn = np.inf, -np.inf
    for phase in range(MAX_PHASES + 1):
        rem = 1.0 - t
        if rem <= 0.0:
            break
        if phase == MAX_PHASES:
            raise RuntimeError("dfa.core.oscillator.hand_sample: more phases in one sample than ω < π allows")
        net = c - kap * x
        if v == 0.0:
            if abs(net) <= sigma:
                break  # stuck: the net static force stays within friction to the end of the sample
            s = 1.0 if net > 0.0 else -1.0
        else:
            s = 1.0 if v > 0.0 else -1.0
        g = (net - sigma * s) / mu
        ts = hand_stop(v, g, lam, w2, s)
        if not ts < rem:
            x, v = hand_motion(x, v, g, lam, w2, rem)
            break
        x, _ = hand_motion(x, v, g, lam, w2, ts)
        v = 0.0
        t += ts
        lo_turn = min(lo_turn, x)
        hi_turn = max(hi_turn, x)
    return x, v, lo_turn, hi_turn
