"""Passivity criterion of Diolaiti et al. (ICRA 2005), eq. 6-12 and 35, for the spring and every wall it covers.

One criterion for every wall: the paper's spring with a computational delay of d samples and an initial
position, and a wall with a virtual damper and a velocity filter (:mod:`dfa.model.elements`). The corner
(β₀, σ₀) of its critical line is the spring's (½ + d, ½) moved by the elements
(:meth:`dfa.model.wall.WallParams.corner`); an amplifier lag is covered by no sound criterion, and the
criterion refuses it with the element's reason.

The loop (dimensionless, time in samples, ξ = x/Δ, φ = F/(KΔ))
-------------------------------------------------------------
Reading n_h = ⌊ξ_h⌋ (ξ_h itself without the encoder), velocity estimate v_h = n_h − n_{h−1} (v_0 = 0),
damper input y_h = v_h without filter, or the exact ZOH low-pass y_h = a·y_{h−1} + (1 − a)·v_{h−1},
y_0 = 0, a = e^{−2πν_c}; force held over sample h (ZOH, no amplifier lag)::

    φ_h = −(n_{h−d} + ½) − β_B·y_{h−d}          (φ_h = φ_0 for h < d; β_B = 0 for the spring)

and the plant μξ'' + βξ' + σ sgn ξ' = φ (eq. 4, stick-slip included). Before the first sample the wall's
past readings equal ξ0.

Step 1: the energy balance of one sample (exact)
    With S = ½μξ'² + ½ξ² (the storage H_T of eq. 19 minus ½(p − p²) ∈ [0, 1/8], eq. 18) and
    Δ_h = ξ_{h+1} − ξ_h, the work of the constant force is φ_hΔ_h and ½ξ² grows by ξ_hΔ_h + ½Δ_h², so

        S_{h+1} − S_h = ½Δ_h² + (φ_h + ξ_h)Δ_h − D_h,
        D_h = β∫ξ'² + σ∫|ξ'| >= βΔ_h² + σ|Δ_h|     (Cauchy-Schwarz; eq. 30, 32).

Step 2: the spring's part of φ_h + ξ_h
    With p = ξ − ⌊ξ⌋ (eq. 17) and Δ_k = 0, p_k = p_0 for k < 0 (the start convention):
    ξ_h − n_{h−d} − ½ = Σ_{j=1..d} Δ_{h−j} + (p_{h−d} − ½), |p − ½| <= ½.

Step 3: the damper's part
    v_j = Δ_{j−1} − (p_j − p_{j−1}) exactly (also v_0 = 0 with the convention), and
    y_m = Σ_{k>=1} c_k v_{m−k}, c_k = (1 − a)a^{k−1} (filter; Σc_k <= 1), or y_m = v_m (no filter). Hence
    −β_B y_{h−d} is a *linear* part −β_B Σ_k c_k Δ_{h−d−k−1} (a combination of earlier displacements) plus a
    *quantization* part β_B Q_h, Q_h = Σ_k c_k (p_{h−d−k} − p_{h−d−k−1}). By Abel summation the
    coefficients of the p's in Q_h have positive parts summing to 1 − a and negative parts summing to
    1 − a; as 0 <= p < 1, |Q_h| < 1 − a (no filter: Q_h = p_{h−d} − p_{h−d−1}, |Q_h| < 1 = 1 − 0).

Step 4: summing (the quadratic part)
    Over h = 0 … n − 1 every cross product is bounded by |Δ_hΔ_m| <= ½(Δ_h² + Δ_m²). The spring pairs
    (h, h − j), j = 1 … d, give each Δ_k² a total weight <= d; the damper pairs, with weights β_B c_k that
    sum to <= β_B, give each Δ_k² a weight <= ½β_B as the later sample and <= ½β_B as the earlier one:
    <= β_B in all. So::

        S_n − S_0 <= Σ_h [ (β₀ − β)Δ_h² + (σ₀ − σ)|Δ_h| ],
        β₀ = ½ + d + β_B,      σ₀ = ½ + (1 − a)β_B     (a = 0 without filter).

    The quantization parts (p_{h−d} − ½) and β_B Q_h are what σ₀ collects; without the encoder they vanish
    and σ₀ = 0 (eq. 7). The bound holds at any instant inside a sample too (partial displacement Δ' over a
    part ℓ <= 1 of the sample: the force is constant, ∫ξ'² >= Δ'²/ℓ >= Δ'²).

Step 5: the criterion (first exit)
    Every bracket is <= 0 when |Δ| <= V, σ >= σ₀ and (β − β₀)V + (σ − σ₀) >= 0. Let V = sqrt(ξ'0² + ξ0²/μ),
    so S_0 = ½μV², and t* the last time up to which S <= S_0. Up to t*, ½μξ'² <= S <= S_0 gives |ξ'| <= V,
    so every displacement over at most one sample is <= V; by continuity of ξ' this still holds a little
    beyond t* (the partial sample is shorter than one), hence S <= S_0 beyond t*: t* = ∞. Therefore::

        (β − β₀)V + (σ − σ₀) >= 0   and   σ >= σ₀

    imply S(t) <= S(0) for all t: the energy never grows, |ξ'| <= V and |ξ| <= sqrt(2S_0); the loop cannot
    diverge. At equality the partial sample keeps |Δ'| <= V, so the boundary is included.

Reductions (tested). The spring, d = 0, ξ0 = 0: β₀ = σ₀ = ½, the paper's eq. 6 / 35 exactly; its linear
part β >= ½ + d is the journal extension (Diolaiti et al., IEEE T-RO 22(2), 2006). Without encoder and
Coulomb friction, d = 0: β >= ½ + β_B, i.e. b >= KT/2 + B, the Colgate-Schenkel bound (spec section 8).
The wall's criterion at (β, σ) is the spring's at (β − β_B, σ − (1 − a)β_B): the damper costs β_B of
physical damping and (1 − a)β_B of Coulomb friction. Physical form (eq. 11):
(b − B − KT(½ + d))|ẋ0| + (c − KΔ/2 − (1 − a)BΔ/T) >= 0 and c >= KΔ/2 + (1 − a)BΔ/T.

Energy-equivalent speed. V = sqrt(ξ'0² + 2H_c(ξ0)/μ) with the paper's pseudo-elastic energy H_c of eq. 18
(without quantization H_c = ½ξ²). As H_c(ξ0) >= ½ξ0², this V is never smaller than the one of the proof,
and the left side of the criterion falls with V, so the verdict stays sound; it matches the paper's storage
function H_T = ½μV². With ξ0 = 0, V = |ξ'0|. ξ0 ≠ 0 needs μ.

A hand holding the device
    A hand's mass and damping move with the device (m + m_h, b + b_h: :meth:`dfa.Device.holding`), so β and μ
    include them and eq. 6 and 11 hold as written. A hand stiffness κ_h = k_h/K to a fixed reference at the
    wall's origin (:class:`~dfa.model.elements.HandSpring`) adds −κ_h ξ to the plant: μξ'' + βξ' + κ_hξ +
    σ sgn ξ' = φ. Its work over any motion is exactly −Δ(½κ_hξ²), so with S = ½μξ'² + ½ξ² + ½κ_hξ² step 1
    holds unchanged (the spring stores what it takes; the bounds on D_h hold for any motion within the sample),
    steps 2-4 concern the wall alone, and step 5 holds with S_0 = ½μV², V = sqrt(ξ'0² + (1 + κ_h)ξ0²/μ)
    (:func:`equivalent_speed`): the corner (β₀, σ₀) is unchanged, and the hand's stiffness has no memory to
    start in. ``tests/test_hand_stiffness.py`` checks S(h) <= S(0) by exact simulation
    (:mod:`dfa.core.oscillator`) at random points the criterion calls passive.

A one-sided wall reached from free space (:class:`~dfa.model.elements.OneSided`, with a delay, a push, a hand)
    The wall commands c = −(q − s) while the reading q = ⌊ξ⌋ + ½ is beyond the surface s, and 0 otherwise, held
    d samples later; from the first reading inside on the operator pushes with p >= 0
    (:class:`~dfa.model.elements.Push`). Take f = −(ξ − s)⁺ (1-Lipschitz, non-increasing), H_1 = ½((ξ − s)⁺)²
    and Q = ½μξ'² + H_1(ξ) − p(ξ − s) + ½p² >= ½μξ'² (H_1 − p(ξ − s) >= −½p²). The push's work is what its
    term −p(ξ − s) loses, and H_1(ξ + Δ) <= H_1(ξ) − f(ξ)Δ + ½Δ², so step 1 reads
    Q_{h+1} − Q_h <= ½Δ_h² + (φ_h − f(ξ_h))Δ_h − D_h. The quantization error |c_h − f(ξ_h)| <= ½ at every
    reading (inside with ξ >= s: ξ − q; inside with ξ < s: −(q − s) ∈ (−½, 0); outside with ξ > s: (ξ − s) ∈
    (0, ½)), and f(ξ_{h−d}) − f(ξ_h) = λ_h Σ_{j=1..d} Δ_{h−j} with a slope λ_h ∈ [0, 1]: steps 2 and 4 hold as
    for the spring, each cross term |λ_hΔ_{h−j}Δ_h| <= ½(Δ_{h−j}² + Δ_h²), so the corner is (½ + d, ½).
    The start: until the first reading inside (sample h_c) the operator's force σ + βV balances friction
    exactly (ξ' = V, nothing else changes), so at h_c, Q = ½μV² + φ(δ), φ(δ) = ½(δ⁺)² − pδ + ½p², δ = ξ − s in
    [c, c + V), c = ξ_e − s, ξ_e = ⌊s + ½⌋ the first position the wall sees
    (:meth:`~dfa.model.elements.OneSided.engage`; ξ_e = s without the encoder). φ is convex: Q <= ½μV² + ½m²,
    ½m² = max(φ(c), φ(c + V)) (without a push m = ε_max = (c + V)⁺,
    :meth:`~dfa.model.elements.OneSided.contact_excess`). From h_c the proof runs as for a fresh wall (past
    readings equal ξ_{h_c}), except that the d commands still pending are the approach's 0, not c_{h_c}: over
    samples h_c … h_c + d − 1 the wall pushes ε_q = q_{h_c} − s < c + V + ½ (c + V without the encoder) less
    than the fresh proof assumes, which adds at most ε_q·dV* (the displacement over d samples while
    |ξ'| <= V*). With V* the root of ½μV*² = ½μV² + ½m² + ε_q dV*
    (:meth:`~dfa.model.elements.OneSided.contact_speed`), step 5 (first exit at Q = ½μV*²) gives
    Q(t) <= ½μV*² for all t >= h_c: the corner (½ + d, ½) at V*. Alone (d = 0, p = 0), V* = √(V² + ε_max²/μ).
    The critical speed is the impact speed V whose V* is (σ − σ₀)/(β₀ − β)
    (:meth:`~dfa.model.elements.OneSided.impact_speed`). The verdict is monotone in K at fixed physical
    values (the passive K form an interval (0, K*], as :func:`~dfa.analysis.limits.kmax.wall_k_criterion`
    needs): with u = 1/K, β, σ, μ and p are proportional to u, and every term of μV*² grows at most in
    proportion to u (the push's p²/μ and −pc/μ; the others fall), so dV*/du <= V*/(2u); where the margin
    g = (β₀ − β)V* + ½ − σ is <= 0 (β < β₀), g' <= (V*(β₀ − 3β)/2 − σ)/u < 0, as (β₀ − β)V* <= σ − ½.
    A hand's spring κ_h = k_h/K to the wall's origin (:class:`~dfa.model.elements.HandSpring`) stores exactly
    what it takes and has no memory (as for the bilateral wall): Q gains ½κ_hξ², held by the operator during
    the approach as friction is (the approach is unchanged), so φ(δ) gains ½κ_h(s + δ)², still convex, and
    κ_h/μ = k_hT²/m does not change with K.
    With a damper or a filter (the approach's velocity estimate, and the clip at 0 that keeps the wall from
    pulling): not derived, refused
    (:meth:`dfa.model.wall.WallParams.uncovered`). ``tests/test_one_sided.py`` and ``python -m
    dfa.cli.soundness_report --one-sided`` check Q <= ½μV*² by exact simulation of the approach at random
    points the criterion calls passive.

A moving history (``history="moving"``; the spring with a delay, no damper or filter)
    The fresh start takes the displacements before t = 0 as 0 (the d pending commands equal the first one). If
    instead the device moved at ξ'0 for the d samples before, they are Δ_k = ξ'0 (k < 0), and step 2's identity
    ξ_h − n_{h−d} − ½ = Σ_{j=1..d} Δ_{h−j} + (p_{h−d} − ½) holds as it stands (the readings of the motion
    included, |p − ½| <= ½ for any reading). Step 4's cross terms then pair, for h < d, the d − h displacements
    of the history with Δ_h: each |ξ'0Δ_h| <= ½(ξ'0² + Δ_h²), the Δ_h² halves in the weight d already, the
    ½ξ'0² halves, d(d + 1)/2 of them, paid by no dissipation. So S_n − S_0 <= ¼d(d + 1)ξ'0² + Σ_h brackets, and
    step 5 with ½μV*² = ½μV² + ¼d(d + 1)ξ'0² (:func:`moving_history_speed`) gives S(t) <= ½μV*²: the corner
    (½ + d, ½) at V* = √(V² + d(d + 1)ξ'0²/(2μ)). The critical speed is then the speed ξ'0 whose V* is
    (σ − σ₀)/(β₀ − β). With a damper or a filter the velocity estimate and the filter's state of the motion
    enter the energy too: not derived, refused. ``python -m dfa.cli.soundness_report --history`` checks it by
    exact simulation of that start (:func:`dfa.simulate` with ``history="moving"``).

What is not proven
    * Amplifier lag (α > 0): the force varies within the sample, step 1's work φΔ no longer holds, and no
      sound closed form is derived here (:class:`~dfa.model.elements.AmplifierLag` says so; the criterion
      refuses it and points to the simulated map, :func:`dfa.stability_map`). A possible route, not carried
      out: write the lagged force as the exponentially weighted average Σ_j ω_j(τ)·φ_{h−j} of the held
      commands, keep the exact ½Δ² of the current sample, bound the cross terms by Cauchy-Schwarz with
      ∫ξ'² and the quantization terms by ½∫|ξ'|: this gives a β₀(α) > ½ + d + β_B that would need its own
      proof and simulator check.
    * Tightness: the criterion is sufficient only. β >= ½ + β_B is necessary for passivity of the linear
      loop at d = 0 (Colgate-Schenkel), but the σ-threshold ½ + (1 − a)β_B and the weights d, β_B with a
      delay or a filter are bounds, not known to be sharp. Probing below the thresholds by simulation finds
      storage growth for σ between ½ and σ₀ (about 1 point in 10³, the test
      ``test_eq6_controller_sigma0_needs_the_damper_term``): σ >= ½ alone is not enough with a damper.

What the verdicts mean (and do not mean)
----------------------------------------
``passive`` (regions a, e) is proven by the argument above. Regions b, c and d only mean that the criterion
gives *no guarantee*: it is a sufficient condition, and failing it is no proof of instability (exact
simulation decides that).

=======  ==============================================  ==================================
region   condition (boundaries as assigned here)          meaning
=======  ==============================================  ==================================
``a``    β >= β₀ and σ >= σ₀                              passive at every speed (proven)
``b``    β >= β₀ and σ <  σ₀                              no guarantee at rest (σ < ½: cannot stop)
``c``    β <  β₀ and σ <  σ₀                              no guarantee at any speed
``d``    β <  β₀, σ >= σ₀ and margin < 0                  no guarantee at this speed
``e``    β <  β₀, σ >= σ₀ and margin >= 0                 passive up to the critical speed (proven)
=======  ==============================================  ==================================

with margin = (β − β₀)V + (σ − σ₀). Boundary points follow the non-strict inequalities: β = β₀ belongs to
a/b (the margin no longer falls with speed), σ = σ₀ to a/d/e, margin = 0 to e. Hence ``passive`` is
exactly ``region in ("a", "e")``. The critical speed (eq. 12 generalised) is V_c = (σ − σ₀)/(β₀ − β):
passive for every V <= V_c. Without quantization σ₀ collects no quantization term (0 for the spring)
and regions b and c are empty. In region b with σ < ½ the paper (d = 0) observes stable sub-tick limit
cycles; that is an observation, not part of the guarantee.

Examples
--------
>>> r = passivity_criterion(beta=0.002, sigma=2.03, xi_dot=1.0)   # Delta device, slow
>>> r.region, r.passive
('e', True)
>>> round(r.critical_xi_dot, 3)                                     # eq. 12
3.072
>>> passivity_criterion(beta=0.002, sigma=2.03, xi_dot=5.0).region
'd'
>>> passivity_criterion(beta=0.8, sigma=0.8, xi_dot=5.0, wall=WallParams.of(delay=1)).passive   # 0.8 < ½ + 1
False
>>> r = passivity_criterion(1.2, 1.0, 2.0, wall=WallParams.of(damping=0.3))
>>> r.beta0, r.sigma0, r.region, r.passive            # β₀ = ½ + 0.3, σ₀ = ½ + 0.3
(0.8, 0.8, 'a', True)
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping
from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike

from ..checks import (
    DELAY_FIX,
    MAX_DELAY,
    check_beta,
    check_bool,
    check_choice,
    check_mu,
    check_nonnegative,
    check_real,
    check_real_array,
    check_sigma,
    check_type,
    format_value,
)
from ..core.energy import spring_energy_core
from ..errors import DFATypeError, DFAValueError
from ..model.elements import Coverage, OneSided, Push, largest_speed
from ..model.loop import LOOP_FIX, Loop, loop_first
from ..model.wall import Wall, WallParams
from ..results.criterion import _REGION_CODES as _REGION_CODES
from ..results.criterion import HISTORIES as HISTORIES
from ..results.criterion import REGION_DESCRIPTIONS as REGION_DESCRIPTIONS
from ..results.criterion import CriterionResult as CriterionResult
from ..results.criterion import CriticalLine as CriticalLine
from ..results.criterion import _anchor as _anchor
from ..results.criterion import _margin as _margin
from ..results.criterion import has_memory as has_memory
from ..results.criterion import region_of as region_of
from ..results.criterion import start_state as start_state
from ..results.status import CriterionStatus

if TYPE_CHECKING:
    pass

F = TypeVar("F", bound=Callable[..., Any])

__all__ = [
    "CriticalLine",
    "CriterionResult",
    "passivity_criterion",
    "criterion_from_groups",
    "start_state",
    "HISTORIES",
    "moving_history_speed",
    "has_memory",
    "device_criterion",
    "classify_region",
    "equivalent_speed",
    "spring_energy",
    "REGION_DESCRIPTIONS",
    "as_wall",
    "check_finite_verdict",
]


def moving_history_speed(speed: float, xi_dot: float, mu: float, delay: int) -> float:
    """The criterion's speed V* for a moving history (module docstring, "A moving history").

    The device has moved at ξ'0 for the d samples before t = 0, so the displacements before the start are
    Δ_k = ξ'0 (k < 0), not 0: step 2's cross terms pair d(d + 1)/2 of them with the first d samples', each at
    most ½(ξ'0² + Δ_h²), and the Δ_h² halves are in step 4's weights already. Hence
    ½μV*² = ½μV² + ¼d(d + 1)ξ'0²:  V* = √(V² + d(d + 1)ξ'0²/(2μ)) (V* = V for d = 0), with or without the encoder.

    Parameters
    ----------
    speed : float
        The energy-equivalent speed V of the start (:func:`equivalent_speed`), ticks per sample.
    xi_dot : float
        The speed ξ'0 of the history (and of the start), ticks per sample; its sign is ignored.
    mu : float
        Dimensionless mass μ = m/(K T²) > 0.
    delay : int
        The computational delay d, samples.

    Returns
    -------
    float
        V* in ticks per sample (>= V).

    Examples
    --------
    >>> moving_history_speed(2.0, 2.0, 1.0, 0)
    2.0
    >>> round(moving_history_speed(0.0, 2.0, 1.0, 1), 12)   # ½V*² = ¼·2·4
    2.0
    """
    return math.sqrt(speed * speed + delay * (delay + 1) * xi_dot * xi_dot / (2.0 * mu))


def equivalent_speed(
    xi_dot: float, xi0: float = 0.0, mu: float | None = None, *, quantized: bool = True, hand_stiffness: float = 0.0
) -> float:
    """Energy-equivalent speed V = sqrt(ξ'0² + (2H_c(ξ0) + κ_h ξ0²)/μ) in ticks per sample (eq. 18-19).

    ½μV² is the paper's total stored energy H_T(ξ0, ξ'0) (eq. 19), with
    H_c(ξ) = ½ξ² + ½(p − p²) (eq. 18; ½ξ² without quantization), plus the hand spring's ½κ_h ξ0² when a hand
    of stiffness κ_h = k_h/K holds the device. V >= the sqrt(ξ'0² + (1 + κ_h)ξ0²/μ) of the proof in the
    module docstring, so using it is sound.

    Parameters
    ----------
    xi_dot : float
        Initial speed ξ'0 (ticks per sample); its sign is ignored.
    xi0 : float, optional
        Initial position ξ0 in ticks (default 0).
    mu : float, optional
        Dimensionless mass μ = m/(K T²); required when ``xi0`` is not 0.
    quantized : bool, optional
        Use H_c of eq. 18 (default) or ½ξ0² (no encoder).
    hand_stiffness : float, optional
        The hand stiffness κ_h = k_h/K >= 0 (default 0: none; :class:`~dfa.model.elements.HandSpring`).

    Returns
    -------
    float
        V in ticks per sample.

    Examples
    --------
    >>> equivalent_speed(2.0)
    2.0
    >>> equivalent_speed(0.0, xi0=1.0, mu=1.0)            # H_c(1) = ½
    1.0
    >>> equivalent_speed(0.0, xi0=1.0, mu=1.0, hand_stiffness=3.0)   # and ½κ_h ξ0² = 3/2
    2.0
    """
    v = abs(check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample"))
    x = check_real("xi0", xi0, "give the initial position in encoder ticks")
    quantized = check_bool("quantized", quantized, "pass True (eq. 18's H_c) or False (½ξ0², no encoder)")
    if x == 0.0:
        if mu is not None:
            check_mu(mu)
        return v
    if mu is None:
        raise DFAValueError(
            f"mu = None is invalid with xi0 = {x!r}: it must be given (μ = m/(K T²) > 0) because the spring energy "
            "H_c(ξ0) enters the speed only through 2H_c/μ; pass mu, or use device_criterion(..., position=...)"
        )
    m = check_mu(mu)
    kap = check_nonnegative("hand_stiffness", hand_stiffness, "give κ_h = k_h/K >= 0 (0: no hand stiffness)")
    return math.sqrt(v * v + (2.0 * float(spring_energy(x, quantized)) + kap * x * x) / m)


def spring_energy(xi: ArrayLike, quantize: bool = True) -> float | np.ndarray:
    """Pseudo-elastic energy H_c(ξ) = ½ξ² + ½(p − p²), p = ξ − ⌊ξ⌋, of the quantized spring (eq. 18), vectorised.

    The exact integral of the restoring staircase ⌊s⌋ + ½ from 0 to ξ; ½ξ² without quantization.

    Examples
    --------
    >>> float(spring_energy(1.0)), float(spring_energy(0.5)), float(spring_energy(0.5, quantize=False))
    (0.5, 0.25, 0.125)
    """
    q = check_bool("quantize", quantize, "pass True (the quantized spring) or False (½ξ²)")
    return spring_energy_core(np.asarray(xi, dtype=float), q)


def classify_region(
    beta: ArrayLike, sigma: ArrayLike, xi_dot: ArrayLike, quantized: ArrayLike = True, delay: ArrayLike = 0
) -> np.ndarray:
    """Vectorised region a-e of the criterion over arrays of β, σ, speed V and delay d (broadcast).

    ``xi_dot`` is the (energy-equivalent) speed V; every argument, including
    ``quantized`` and ``delay`` (whole samples >= 0), may be an array.

    Parameters
    ----------
    beta : array_like
        Dimensionless viscous damping β.
    sigma : array_like
        Dimensionless Coulomb friction σ.
    xi_dot : array_like
        The (energy-equivalent) speed V in ticks per sample; its sign is ignored.
    quantized : bool or array_like of bool, optional
        True (default) for eq. 6 (σ₀ = ½); False for eq. 7 (σ₀ = 0).
    delay : int or array_like of int, optional
        Computational delay d in samples (default 0).

    Returns
    -------
    numpy.ndarray of str
        Region letters with the broadcast shape of the inputs.

    Raises
    ------
    DFAValueError
        If a delay is not a whole number >= 0.

    See Also
    --------
    passivity_criterion : The verdict, margin and critical speed for one point.
    REGION_DESCRIPTIONS : What each region letter means.

    Examples
    --------
    >>> classify_region([0.6, 0.6, 0.2, 0.2, 0.2], [0.6, 0.2, 0.2, 0.7, 2.0], 1.0).tolist()
    ['a', 'b', 'c', 'd', 'e']
    >>> classify_region(0.6, 0.6, 1.0, delay=[0, 1]).tolist()          # β = 0.6 < ½ + 1
    ['a', 'd']
    """
    b = check_real_array("beta", beta, "β = b/(K T) is a real number or an array of them")
    s = check_real_array("sigma", sigma, "σ = c/(K Δ) is a real number or an array of them")
    v = np.abs(check_real_array("xi_dot", xi_dot, "give speeds in ticks per sample"))
    d = np.asarray(delay)
    if (
        d.dtype == bool
        or not np.issubdtype(d.dtype, np.number)
        or np.iscomplexobj(d)
        or not np.all(np.isfinite(d))
        or np.any(d < 0)
        or np.any(d > MAX_DELAY)
        or np.any(d != np.floor(d))
    ):
        raise DFAValueError(
            f"delay = {format_value(delay)} is invalid: it must be a whole number from 0 to {MAX_DELAY}; {DELAY_FIX}"
        )
    q = np.asarray(quantized)
    if q.dtype != bool:
        raise DFATypeError(
            f"quantized = {format_value(quantized)} is invalid: it must be True or False (or an array of them)"
        )
    s0, b0 = _anchor(q, d)
    return region_of(b, s, v, s0, b0)


def _one_sided_speed(xd: float, x0: float, mu: float | None, wall: WallParams, quantized: bool) -> float:
    """V* of a one-sided wall's approach at V (:meth:`~dfa.model.elements.OneSided.contact_speed`; module
    docstring, "A one-sided wall"), or the error."""
    if mu is None or x0 != 0.0:
        raise DFAValueError(
            f"mu = {mu!r}, xi0 = {x0!r} are invalid with a one-sided wall: its criterion is for an approach from free "
            "space at xi_dot and needs μ (the storage at the first reading inside enters through ½ε²/μ); pass mu "
            "and xi0 = 0"
        )
    return OneSided.contact_speed(_surface(wall), xd, mu, wall.delay, _push(wall), quantized, wall.hand_stiffness)


def _surface(wall: WallParams) -> float:
    """The surface s of a one-sided wall, ticks."""
    return wall.surface


def _push(wall: WallParams) -> float:
    """The push group p of a one-sided wall (0 without one)."""
    return wall.group(Push) or 0.0


def _speed(xd: float, x0: float, mu: float | None, wall: WallParams, quantized: bool, history: str) -> float:
    """The criterion's speed: a one-sided wall's V*, a moving history's V*, else the energy-equivalent V."""
    if not wall.covers(Coverage.SURFACE_START):  # the approach from free space
        return _one_sided_speed(xd, x0, mu, wall, quantized)
    v = equivalent_speed(xd, x0, mu, quantized=quantized, hand_stiffness=wall.hand_stiffness)
    if history == "moving" and mu is not None:
        return moving_history_speed(v, xd, mu, wall.delay)
    return v


def _check_history(history: object, wall: WallParams, mu: float | None) -> str:
    """The history of a verdict (:data:`HISTORIES`), or the package's error where it is not derived."""
    h = check_choice("history", history, HISTORIES)
    if h == "fresh" or not wall.delay:
        return h  # no pending commands: a moving history is the fresh start
    if not wall.covers(Coverage.SURFACE_START):
        raise DFAValueError(
            "history = 'moving' is invalid with a one-sided wall: its start is the approach from free space; "
            "pass history='fresh'"
        )
    if wall.damping or wall.cutoff is not None:
        raise DFAValueError(
            "history = 'moving' is not derived with a virtual damper or filter (the velocity estimate and the "
            "filter's state of the motion enter the energy); pass history='fresh' or drop the damper"
        )
    if not wall.covers(
        Coverage.CLOSED_FORM
    ):  # a hand stiffness: the simulator does not run that start, so it is not shown sound
        raise DFAValueError(
            "history = 'moving' is covered for the spring with a delay only (the simulator runs that start for it "
            "alone, so nothing else is shown sound); pass history='fresh' or drop the other elements"
        )
    if mu is None:
        raise DFAValueError(
            "history = 'moving' needs mu: the motion's energy enters through d(d + 1)ξ'0²/(2μ); pass mu"
        )
    return h


def _corner(wall: WallParams, quantized: bool) -> tuple[float, float]:
    """(β₀, σ₀) of the wall, or the package's error naming the element no criterion covers."""
    bad = wall.uncovered()
    if bad is not None:
        kind, g, why = bad
        raise DFAValueError(
            f"wall.{kind.parameter.group} = {format_value(g)} is invalid for the passivity criterion: {why}; use the "
            "simulated map dfa.stability_map (or the exact simulation) instead, or drop that element"
        )
    return wall.corner(quantized)


def _criterion_loop_first(func: F) -> F:
    """Let :func:`passivity_criterion` (a :class:`Loop` first) still be called in its former form (β, σ, ξ'0, ...,
    ``mu`` optional): such a call is :func:`criterion_from_groups`, unchanged."""

    @functools.wraps(func)
    def criterion_wrapper(*args: Any, **kwargs: Any) -> Any:
        if (args and isinstance(args[0], Loop)) or "loop" in kwargs:
            for name in ("wall", "mu"):
                if name in kwargs:
                    raise DFAValueError(
                        f"{name} = {format_value(kwargs[name])} is invalid with a loop: the loop holds it; build the "
                        "loop with it, Loop.dimensionless(mu, beta, sigma, wall_params)"
                    )
            return func(*args, **kwargs)
        return criterion_from_groups(*args, **kwargs)

    return cast(F, criterion_wrapper)


@_criterion_loop_first
def passivity_criterion(
    loop: Loop,
    xi_dot: float,
    *,
    quantized: bool = True,
    xi0: float = 0.0,
    names: Mapping[str, str] | None = None,
    history: str = "fresh",
) -> CriterionResult:
    """Evaluate the passivity criterion (eq. 6, or eq. 7 without quantization) for the loop's wall at a speed.

    :func:`criterion_from_groups` with the loop's groups (β, σ, μ) and its wall's (module docstring).

    Parameters
    ----------
    loop : Loop
        The groups (μ, β, σ) and the wall's (delay d, damper β_B, filter ν_c),
        ``Loop.dimensionless(mu, beta, sigma, wall_params)`` or ``Loop(device, wall)``. The former call
        ``passivity_criterion(beta, sigma, xi_dot, wall=..., mu=...)`` (μ optional) still works: it is
        :func:`criterion_from_groups`.
    xi_dot : float
        Largest speed of interest ξ'0 = ẋ0 T/Δ in encoder ticks per sample; its sign is ignored.
    quantized : bool, optional
        True (default) for eq. 6; False for the encoder-free eq. 7.
    xi0 : float, optional
        Initial position ξ0 in ticks (default 0); the wall's past readings equal ξ0.
    names : mapping of str to str, optional
        How an overflow message names ``beta``, ``sigma`` and ``xi_dot`` (:func:`criterion_from_groups`).
    history : {"fresh", "moving"}, optional
        The loop's memory at t = 0 (:data:`HISTORIES`, :func:`criterion_from_groups`); default ``"fresh"``.

    Returns
    -------
    CriterionResult
        Region, verdict, margin, critical speed and line, with the inputs and a ``status``.

    Raises
    ------
    DFAValueError, DFATypeError
        As :func:`criterion_from_groups`; also for a loop at no given stiffness, or a ``wall`` or ``mu`` given
        beside the loop.

    See Also
    --------
    device_criterion : The same criterion from physical values.
    """
    p, wp = check_type("loop", loop, Loop, LOOP_FIX).groups("passivity_criterion")
    return criterion_from_groups(
        p.beta, p.sigma, xi_dot, wall=wp, quantized=quantized, xi0=xi0, mu=p.mu, names=names, history=history
    )


def criterion_from_groups(
    beta: float,
    sigma: float,
    xi_dot: float,
    *,
    wall: WallParams | None = None,
    quantized: bool = True,
    xi0: float = 0.0,
    mu: float | None = None,
    names: Mapping[str, str] | None = None,
    history: str = "fresh",
) -> CriterionResult:
    """Evaluate the passivity criterion (eq. 6, or eq. 7 without quantization) for a wall and an initial position.

    Passive when (β − β₀)V + (σ − σ₀) >= 0 and σ >= σ₀ (module docstring), with V = sqrt(ξ'0² + 2H_c(ξ0)/μ)
    and the corner (β₀, σ₀) of the wall: (½ + d, ½) for the spring (σ₀ = 0 without quantization), moved by a
    damper and a filter. The spring, d = 0, ξ0 = 0 is the paper's eq. 6 unchanged.

    Parameters
    ----------
    beta : float
        Dimensionless viscous damping β = b/(K T) >= 0.
    sigma : float
        Dimensionless Coulomb friction σ = c/(K Δ) >= 0.
    xi_dot : float
        Largest speed of interest ξ'0 = ẋ0 T/Δ in encoder ticks per sample (e.g. the impact speed); its
        sign is ignored.
    wall : WallParams, optional
        The wall's dimensionless groups (computational delay d in samples, damper β_B, filter ν_c); default
        the paper's spring. An amplifier lag is refused: no sound criterion covers it.
    quantized : bool, optional
        True (default) for eq. 6; False for the encoder-free eq. 7.
    xi0 : float, optional
        Initial position ξ0 in ticks (default 0); the wall's past readings equal ξ0.
    mu : float, optional
        Dimensionless mass μ = m/(K T²); required when ``xi0`` is not 0.
    names : mapping of str to str, optional
        How the message of a margin or critical speed that overflows names ``beta``, ``sigma`` and ``xi_dot``
        (the command line passes its flags); default those names.
    history : {"fresh", "moving"}, optional
        The loop's memory at t = 0 (:data:`HISTORIES`): ``"fresh"`` (default, module docstring) or
        ``"moving"``, the device having moved at ξ'0 for the d samples before (the spring with a delay; needs
        ``mu``; the speed is then :func:`moving_history_speed`'s V*, the critical speed a speed ξ'0).

    Returns
    -------
    CriterionResult
        Region, verdict, margin, critical speed and line, with the inputs and a ``status``.

    Raises
    ------
    DFAValueError, DFATypeError
        If β, σ or μ is out of range or not a number, the speed or position is not a finite number, the
        wall is not a WallParams or holds an element no criterion covers, ``xi0`` is not 0 without ``mu``, or
        the margin or the critical speed overflows a float (:func:`check_finite_verdict`).

    See Also
    --------
    passivity_criterion : The same criterion for a :class:`Loop`.
    device_criterion : The same criterion from physical values.
    classify_region : The spring's region letter over arrays of (β, σ, V, d).
    CriticalLine : The line of eq. 10.
    """
    b = check_beta(beta)
    s = check_sigma(sigma)
    w = WallParams() if wall is None else check_type("wall", wall, WallParams, "give WallParams.of(...) or None")
    xd = abs(check_real("xi_dot", xi_dot, "give the speed in encoder ticks per sample"))
    x0 = check_real("xi0", xi0, "give the initial position in encoder ticks")
    m = None if mu is None else check_mu(mu)
    if not isinstance(quantized, (bool, np.bool_)):
        raise DFATypeError(
            f"quantized = {format_value(quantized)} has type {type(quantized).__name__}: it must be True (eq. 6) or False (eq. 7)"
        )
    q = bool(quantized)
    hist = _check_history(history, w, m)
    b0, s0 = _corner(w, q)
    v = _speed(xd, x0, m, w, q, hist)
    region = str(region_of(b, s, v, s0, b0))
    margin = float(_margin(b, s, v, s0, b0))
    critical = (s - s0) / (b0 - b) if (b < b0 and s >= s0) else None
    check_finite_verdict(margin, critical, {"beta": b, "sigma": s, "xi_dot": xd}, names)
    if (
        critical is not None
        and m is not None
        and (not w.covers(Coverage.SURFACE_START) or (hist == "moving" and w.delay))
    ):
        critical = largest_speed(lambda u: _speed(u, x0, m, w, q, hist), critical)  # a speed ξ'0, not V*
    return CriterionResult(
        beta=b,
        sigma=s,
        xi_dot=xd,
        quantized=q,
        region=region,
        passive=region in ("a", "e"),
        margin=margin,
        critical_xi_dot=critical,
        critical_line=CriticalLine(v, b0, s0),
        equivalent_speed=v,
        xi0=x0,
        mu=m,
        history=hist,
        # region b with the spring's σ₀ = ½: σ < ½, the force at rest exceeds σ and the device cannot stop
        status=CriterionStatus.of_region(region, cannot_stop=s0 <= 0.5),
        wall=w,
    )


def check_finite_verdict(
    margin: float, critical: float | None, given: Mapping[str, float], names: Mapping[str, str] | None = None
) -> None:
    """Refuse inputs whose margin (β − β₀)V + (σ − σ₀) or critical speed (σ − σ₀)/(β₀ − β) overflows a float.

    The verdict itself keeps its sign, but a margin or a critical speed of inf is no answer to state (``dfa check
    --beta 1e308 --xi-dot 2`` printed "margin inf"); such values lie far beyond any haptic device.

    Parameters
    ----------
    margin, critical : float, float or None
        The criterion's margin and critical speed (None where there is none).
    given : mapping of str to float
        The inputs named in the message (``beta``, ``sigma``, ``xi_dot``), by name.
    names : mapping of str to str, optional
        How to call each input (the command line passes its flags); default its name.

    Examples
    --------
    >>> check_finite_verdict(1.5, None, {"beta": 0.6, "sigma": 1.0, "xi_dot": 2.0})
    >>> try:
    ...     check_finite_verdict(float("inf"), None, {"beta": 1e308, "sigma": 1.0, "xi_dot": 2.0})
    ... except DFAValueError as err:
    ...     print(err)
    beta = 1e+308, sigma = 1, xi_dot = 2 are invalid together: the criterion's margin (β − β₀)V + (σ − σ₀) must be a finite number (it overflows a float here); give the β, σ and speed of a haptic device (β and σ below about 1e3, a few ticks per sample)
    """
    what = None
    if not math.isfinite(margin):
        what = "the criterion's margin (β − β₀)V + (σ − σ₀)"
    elif critical is not None and not math.isfinite(critical):
        what = "the critical speed (σ − σ₀)/(β₀ − β) (eq. 12)"
    if what is None:
        return
    called = names or {}
    inputs = ", ".join(f"{called.get(k, k)} = {v:g}" for k, v in given.items())
    raise DFAValueError(
        f"{inputs} are invalid together: {what} must be a finite number (it overflows a float here); give the β, σ "
        "and speed of a haptic device (β and σ below about 1e3, a few ticks per sample)"
    )


def as_wall(wall: object) -> Wall:
    """A :class:`~dfa.model.wall.Wall` from a wall or a stiffness K (the paper's spring), else the package's error.

    Parameters
    ----------
    wall : Wall or float
        A wall, or a stiffness K in N/m (rotary: N·m/rad) > 0 for the spring alone.

    Returns
    -------
    Wall
    """
    if isinstance(wall, Wall):
        return wall
    if isinstance(wall, (int, float, np.integer, np.floating)) and not isinstance(wall, (bool, np.bool_)):
        return Wall(wall)  # type: ignore[arg-type]  # Wall checks K (a finite number > 0)
    raise DFATypeError(
        f"wall = {format_value(wall)} has type {type(wall).__name__}: it must be a dfa.Wall or a stiffness K in N/m; "
        "give e.g. dfa.Wall.of(1000.0, damping=1.0), or 1000.0 for the spring alone"
    )


@loop_first("device, wall")
def device_criterion(
    loop: Loop,
    velocity: float,
    *,
    position: float = 0.0,
    quantized: bool = True,
    history: str = "fresh",
) -> CriterionResult:
    """Passivity criterion for a physical device, wall, speed and initial position (paper eq. 11, extended).

    Parameters
    ----------
    loop : Loop
        The device and the wall (its stiffness K in N/m, rotary N·m/rad, and elements), ``Loop(device, wall)``
        (the wall may be K alone, the paper's spring). The former call ``device_criterion(device, wall, velocity)``
        still works.
    velocity : float
        Largest speed of interest ẋ0 in m/s (rotary: rad/s); its sign is ignored.
    position : float, optional
        Initial position x0 in m (rotary: rad), default 0; ξ0 = x0/Δ.
    quantized : bool, optional
        True (default) for eq. 6; False for eq. 7.
    history : {"fresh", "moving"}, optional
        The loop's memory at t = 0 (:func:`passivity_criterion`).

    Returns
    -------
    CriterionResult
        As :func:`passivity_criterion`, with ``device``, ``stiffness``, ``velocity``, ``critical_velocity``
        (m/s, rotary rad/s) and ``position`` set.

    Raises
    ------
    DFAValueError, DFATypeError
        If the stiffness is not > 0, the speed or position is not a finite number, a filter cutoff is above
        the Nyquist frequency, the wall holds an element no criterion covers (an amplifier lag), or
        (μ, β, σ) cannot be held in a float.

    See Also
    --------
    passivity_criterion : The criterion in dimensionless parameters.
    stiffness_limits : The largest passive stiffness and the classic bounds.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> r = device_criterion(Loop(dev, 14500.0), 0.1)
    >>> r.region, round(r.critical_velocity, 4)
    ('e', 0.2765)
    >>> device_criterion(Loop(dev, Wall.of(14500.0, delay=1)), 0.1).region
    'd'
    >>> device_criterion(Loop(dev, Wall.of(14500.0, damping=5.0)), 0.1).region     # B = 5 N·s/m
    'd'
    """
    device, w = check_type("loop", loop, Loop, LOOP_FIX).physical("device_criterion")
    v = abs(check_real("velocity", velocity, "give the speed in m/s (rotary: rad/s)"))
    x0 = check_real("position", position, "give the initial position in m (rotary: rad)")
    xi0 = device.xi(x0)  # refused with the position's own message when x0/Δ overflows
    p, wp = loop.groups("device_criterion")
    r = passivity_criterion(loop, device.xi_dot(v), quantized=quantized, xi0=xi0, history=history)
    crit = None if r.critical_xi_dot is None else device.velocity(r.critical_xi_dot)
    return replace(r, device=device, stiffness=w.stiffness, velocity=v, critical_velocity=crit, position=x0)
