"""Limit cycles of the quantized, frictional loop by harmonic balance (paper section 7, eq. 36-45).

A cycle ξ = M sin ωτ exists where the characteristic function

    C(M, ω) = 1/L(jω; M) + D(M) = U + jV

vanishes (eq. 36 divided by L), with D the exact quantizer describing function
(eq. 41) and L the loop of :mod:`dfa.analysis.loop` (half-sample delay, Padé or exact
ZOH, plus d samples of delay), Coulomb friction entering through
β_eq = β + 4σ/(πMω) (eq. 40).

How every root is found
-----------------------
The phase condition V = 0 fixes, for each ω, the equivalent damping β*(ω)
at which the loop's phase crosses −180° (half-delay: β* = μω tan θ,
θ = ω(d + ½), on the branches where θ mod 2π ∈ [0, π/2); Padé: the same with
θ the phase of the all-pass approximant; exact ZOH: bisection, there is at
most one crossing with U < 0 per ω, cached per (μ, d)). With σ > 0 this
gives M(ω) = 4σ/(πω(β* − β)), cut into monotone pieces; on each piece the
problem is one-dimensional in M: F(M) = D(M) + U(M, ω(M)) = 0. F is sampled
on every integer interval [n, n + 1] (points n + t², resolving the √ that D
has at each integer) and on (0, 1) geometrically, sign changes are bracketed
and refined with :func:`scipy.optimize.brentq` (ω(M) by a nested scalar Brent
solve of V = 0 inside the piece's bracket), and each root is polished
with a 2-D Newton step on (U, V). Amplitudes below 1e-9 ticks are not searched
(as M → 0, F ≈ (2 − 4σ)/(πM) keeps one sign). The scan and the refinement
evaluate ω(M) by one rule (a bracket without a sign change of V gives its end
with the smaller |V| in both), so a bracket the scan found is a bracket for
Brent's method too; any bracket that still fails is counted, never raised.

With a wall (issue 15)
----------------------
``limit_cycles(..., wall=WallParams.of(...))`` puts the virtual wall in the loop: D(M)
multiplies the wall's command C(e^{jω}) = 1 + β_B(1 − e^{−jω})F(e^{jω}) (F the ZOH-exact velocity filter;
the elements' polynomials, :meth:`dfa.model.wall.WallParams.command`) and its delay e^{−jωd}; the amplifier
lag is 1/(jωα + 1) in the half-delay and Padé models and is inside the exact ZOH model (the ZOH-sampled
amplifier + device, :mod:`dfa.core.zohlag`). For the half-delay and Padé models the factor
R(ω) = (1 + jωα)/C(e^{jω}) does not depend on β_eq, so the phase condition keeps its closed form with the
lead φ + arg R(ω); the ZOH model bisects as before (its premise of one crossing per ω is checked in the
tests). A spring with any delay runs the spring-only code, bit for bit; the closed forms (eq. 42-45)
refuse any other wall; ``linear_stable`` is the exact linear loop with the wall
(:mod:`dfa.analysis.cycles.controlled`).

How far the search goes
-----------------------
Beyond n = 32 the march over integer intervals n stops where the envelope
|D(M) − 1| <= 0.38⌊M⌋^{-3/2} (see :mod:`dfa.analysis.describing`) can no longer meet
−U (−U at n and at the piece's far end on one side of 1, both farther than the
envelope), and intervals whose ends are both more than twice the envelope from
1 on one side are skipped. That stop is the amplitude beyond which no root can
exist for these (μ, β, σ, model, d) (``LimitCycleResult.search_bound``); by
default the search follows it up to ``AUTO_MAX_AMPLITUDE`` ticks, keeping at
most ``INTERVAL_BUDGET`` intervals per piece. A caller's ``max_amplitude``, the
budget or a numerical failure ends the search with ``complete=False`` and a
:class:`SearchStatus`; nothing is then claimed beyond the range searched. With
σ = 0 the phase condition gives isolated frequencies and D(M) = −U is inverted
exactly (compiled, :mod:`dfa.core.dfcore`).

Modules
-------
:mod:`~dfa.analysis.cycles.characteristic` C(M, ω) = 1/L + D;  :mod:`~dfa.analysis.cycles.phase` the phase
condition and ω(M);  :mod:`~dfa.analysis.cycles.search` the amplitudes sampled and the envelope stop;
:mod:`~dfa.analysis.cycles.solve` bracketing and refinement (:func:`limit_cycles`);
:mod:`~dfa.analysis.cycles.stability` the Loeb criterion;  :mod:`~dfa.results.cycles` the result types;
:mod:`~dfa.analysis.cycles.closed_forms` eq. 42-45;  :mod:`~dfa.analysis.cycles.growth` the growth band;
:mod:`~dfa.analysis.cycles.controlled` the controller's inputs and the linear loop with it;
:mod:`~dfa.results.caveats` the sub-tick caveat (where "no growth below the smallest unstable cycle" fails).

Stability (Loeb criterion): a cycle is stable when
∂U/∂M·∂V/∂ω − ∂U/∂ω·∂V/∂M > 0, the sign that makes an amplitude increase
come with a decaying envelope (s = jω convention). For the half-delay model
∂V/∂ω < 0 at every root, so a stable cycle is one where F falls through zero.

Examples
--------
>>> from dfa.model.device import Params
>>> res = limit_cycles(Params(mu=5.0, beta=0.1, sigma=0.3))
>>> [(round(c.amplitude, 4), round(c.frequency, 4), c.stable, c.family) for c in res.cycles][:2]
[(0.058, 1.3172, True, 'small'), (2.1024, 0.4465, False, 'large')]
"""

from __future__ import annotations

# private names re-exported for the tests and benchmarks that reach into the solver
from ...results.caveats import SUBTICK_LIMIT, NoRestCaveat, SubtickCaveat, no_rest_caveat, subtick_caveat
from ...results.cycles import LimitCycle, LimitCycleResult, LimitCycleSearchWarning, SearchEvidence, SearchStatus
from .characteristic import W_GRID, HarmonicLoop, grid_lead, inv_loop, pade_denominator  # noqa: F401
from .closed_forms import (
    ClosedFormCycles,
    ClosedFormStatus,
    large_cycle_closed_form,
    large_cycle_closed_forms,
    large_cycle_frequencies,
    large_cycle_frequency,
    small_cycle_closed_form,
    small_cycle_closed_forms,
)
from .growth import GrowthThreshold, growth_threshold
from .phase import PieceOmega, phase_beta, zoh_phase_beta_grid  # noqa: F401
from .search import INTERVAL_BUDGET, envelope_bound
from .solve import AUTO_MAX_AMPLITUDE, DEFAULT_TIME_BUDGET, SEARCHED_MU, limit_cycles
from .stability import limit_cycle_at  # noqa: F401

__all__ = [
    "LimitCycle",
    "LimitCycleResult",
    "limit_cycles",
    "small_cycle_closed_form",
    "large_cycle_closed_form",
    "large_cycle_frequency",
    "small_cycle_closed_forms",
    "large_cycle_closed_forms",
    "large_cycle_frequencies",
    "ClosedFormCycles",
    "ClosedFormStatus",
    "GrowthThreshold",
    "growth_threshold",
    "SearchStatus",
    "SearchEvidence",
    "LimitCycleSearchWarning",
    "envelope_bound",
    "AUTO_MAX_AMPLITUDE",
    "DEFAULT_TIME_BUDGET",
    "SEARCHED_MU",
    "INTERVAL_BUDGET",
    "SUBTICK_LIMIT",
    "subtick_caveat",
    "NoRestCaveat",
    "no_rest_caveat",
    "SubtickCaveat",
]
