"""One recommended stiffness for an impact speed, and the rule it follows (issue 26).

The four ways of :func:`dfa.analysis.limits.kmax.design_answer` give four stiffnesses that rest on different
things. A designer needs one, with its reason. The rule:

1. **proven**: where the criterion proves some K passive at the impact speed V (eq. 11, extended to the wall),
   the largest such K. A proof needs no margin. This rule is skipped when the answer holds a counterexample.
2. **simulated**: otherwise, the largest K at which no simulated impact up to V diverged (``k_sim``), divided
   by a gain margin (default 2, about 6 dB). This is not a proof. It holds for the simulated speeds and starts.
   **simulated_range**: when no simulated impact diverged anywhere in the range searched (``k_sim`` above the
   range), the range's top divided by the margin (the simulated limit lies above it).
3. **none**: no K is recommended when no rule applies.

Whatever the rule, the recommendation states whether K lies above the simulated rest limit (``k_sim_rest``,
the largest K at which every simulated impact up to V comes to rest): there the wall may buzz or oscillate (the
search found an impact that does not rest just above that limit; stability need not be monotone in K, so this is
a warning, not a verdict on K).

A wall with a passivity controller is compared with the same wall without it (``plain=``): the wall without
the controller is recommended (by the same rules) when the controller lowers the simulated no-divergence limit,
or when the wall without it gets at least as high a K; the recommendation says so (``controller``). The
controller is not covered by any proof, and without a force limit (the textbook controller) it can make a
sampled wall worse: this rule never recommends it where it does.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.analysis.limits.kmax import design_answer
>>> ans = design_answer(get_device("impulse").device, 0.1, speeds=2, grid=6)
>>> rec = recommend_stiffness(ans)
>>> rec.status.value, rec.k_recommended == ans.k_criterion.value
('proven', True)
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from ...checks import check_type
from ...model.elements import PassivityController
from ...results.require import DEFAULT_MARGIN as DEFAULT_MARGIN
from ...results.require import ControllerChoice as ControllerChoice
from ...results.require import Recommendation as Recommendation
from ...results.require import check_margin as check_margin
from ...results.status import KMaxStatus, LimitStatus, RecommendRule
from .kmax import KMaxResult

__all__ = ["ControllerChoice", "Recommendation", "recommend_stiffness", "check_margin", "DEFAULT_MARGIN"]


def recommend_stiffness(
    answer: KMaxResult, margin: float = DEFAULT_MARGIN, *, plain: KMaxResult | None = None
) -> Recommendation:
    """One recommended stiffness for the answer's impact speed, by the rule of the module docstring.

    Parameters
    ----------
    answer : KMaxResult
        K_max four ways (:func:`dfa.analysis.limits.kmax.design_answer`).
    margin : float, optional
        Gain margin of the simulated rule, >= 1 (default 2, about 6 dB). The proven rule needs none.
    plain : KMaxResult, optional
        For a wall with a passivity controller: the answer of the same wall without it (same device and
        speed, ``design_answer(device, velocity, wall=wall.without_controller())``). The wall without the
        controller is recommended when the controller lowers the simulated limit or gains no K (module
        docstring); ``controller`` says which and why.

    Returns
    -------
    Recommendation
        The stiffness, the limit it rests on, the rule, and whether K lies above the simulated rest limit.

    Raises
    ------
    DFATypeError, DFAValueError
        If ``answer`` is not a :class:`KMaxResult`, ``margin`` is not a finite number >= 1, or ``plain`` is
        not the answer of the same wall without its passivity controller.
    """
    a = check_type("answer", answer, KMaxResult, "pass the result of dfa.design_answer")
    m = check_margin(margin)
    if plain is None:
        return _recommend(a, m)
    from .passivity_gain import gain_of

    gain = gain_of(a, check_type("plain", plain, KMaxResult, "pass design_answer of wall.without_controller()"))
    own, other = _recommend(a, m), _recommend(plain, m)
    k, kp = own.k_recommended, other.k_recommended
    lowers = gain.gain is not None and gain.gain < 1.0
    lowers |= a.k_sim.status is LimitStatus.BELOW_RANGE and plain.k_sim.value is not None
    if lowers:
        kept = False
    else:  # the controller is kept only for a higher K (neither wall has one: the wall as given)
        kept = kp is None or (k is not None and k > kp)
    pc = a.wall.element(PassivityController)
    assert pc is not None  # gain_of refuses a wall without one
    choice = ControllerChoice(kept, lowers, a.k_sim.value, plain.k_sim.value, k, kp, pc.force_limit)
    return replace(own if kept else other, controller=choice)


def _above_rest(a: KMaxResult, k: float | None) -> tuple[float | None, bool]:
    """The rest limit's value, and whether ``k`` lies above it (or at or above the lowest K searched, where
    impacts already failed to rest, when it has no value)."""
    rest = a.k_sim_rest
    if k is None:
        return rest.value, False
    if rest.value is not None:
        return rest.value, k > rest.value
    below = rest.status is LimitStatus.BELOW_RANGE and rest.range_end is not None and k >= rest.range_end
    return None, below


def _recommend(a: KMaxResult, m: float) -> Recommendation:
    """The rule of the module docstring for one answer (no comparison)."""
    rec = _rule(a, m)
    k_rest, above = _above_rest(a, rec.k_recommended)
    return replace(rec, k_rest=k_rest, above_rest=above)


def _rule(a: KMaxResult, m: float) -> Recommendation:
    """Rules 1 to 3 of the module docstring."""
    base: dict[str, Any] = dict(device=a.device, wall=a.wall, velocity=a.velocity, margin=m)
    kc, ks = a.k_criterion, a.k_sim
    trusted = a.status is not KMaxStatus.COUNTEREXAMPLE
    if trusted and kc.status is LimitStatus.FOUND and kc.value is not None and kc.value > 0:
        return Recommendation(**base, k_recommended=kc.value, basis="k_criterion", k_basis=kc.value,
                              status=RecommendRule.PROVEN)  # fmt: skip
    if ks.value is not None and ks.value > 0:
        return Recommendation(**base, k_recommended=ks.value / m, basis="k_sim", k_basis=ks.value,
                              status=RecommendRule.SIMULATED)  # fmt: skip
    top = ks.range_end
    if ks.status is LimitStatus.ABOVE_RANGE and top is not None and math.isfinite(top) and top > 0:
        return Recommendation(**base, k_recommended=top / m, basis="k_sim", k_basis=top,
                              status=RecommendRule.SIMULATED_RANGE)  # fmt: skip
    none = RecommendRule.NOT_SIMULATED if ks.status is LimitStatus.NOT_SIMULATED else RecommendRule.NONE
    return Recommendation(**base, k_recommended=None, basis=None, k_basis=None, status=none)
