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
from dataclasses import dataclass, field, replace
from typing import Any, ClassVar

from ...checks import check_positive, check_type
from ...errors import DFAValueError
from ...model.device import Device
from ...model.wall import Wall
from ...results.base import Result
from ...results.status import KMaxStatus, LimitStatus, RecommendRule
from .kmax import KMaxResult

__all__ = ["ControllerChoice", "Recommendation", "recommend_stiffness", "check_margin", "DEFAULT_MARGIN"]

#: Default gain margin of the simulated rule: the simulated limit divided by 2 (about 6 dB).
DEFAULT_MARGIN = 2.0


@dataclass(frozen=True)
class ControllerChoice(Result):
    """The wall with its passivity controller against the wall without it (K in N/m; rotary N·m/rad).

    Attributes
    ----------
    kept : bool
        True: the wall with the controller is recommended; False: the wall without it (the controller lowers
        the simulated no-divergence limit, or the wall without it gets at least as high a K).
    lowers_limit : bool
        True when the controller lowers the simulated no-divergence limit (``k_sim``), or fails already at the
        lowest K searched where the wall without it has a limit.
    k_sim, plain_k_sim : float or None
        The simulated no-divergence limit with the controller and without it (None: that limit has no value;
        its answer's status says why).
    k_recommended, plain_k_recommended : float or None
        The K each wall is recommended on its own (None: no rule applies).
    force_limit : float or None
        The controller's force limit, N (rotary N·m); None: none, the textbook controller.
    """

    kept: bool
    lowers_limit: bool
    k_sim: float | None
    plain_k_sim: float | None
    k_recommended: float | None
    plain_k_recommended: float | None
    force_limit: float | None = None

    def null_reasons(self) -> dict[str, str]:
        """Why a limit or a recommended K may be null: that wall's limit has no value, or no rule applies.

        Returns
        -------
        dict of str to str
        """
        why = "that wall's limit has no value (its answer's status says why), or no rule recommends a K for it"
        out = dict.fromkeys(("k_sim", "plain_k_sim", "k_recommended", "plain_k_recommended"), why)
        return out | {"force_limit": "no force limit: the textbook controller"}


@dataclass(frozen=True)
class Recommendation(Result):
    """A recommended stiffness and its rule (module docstring); K in N/m (rotary N·m/rad).

    Attributes
    ----------
    device : Device
    wall : Wall
        The wall whose elements were held fixed while K varied.
    velocity : float
        Impact speed V, m/s (rotary: rad/s).
    k_recommended : float or None
        The recommended stiffness; None under the rule ``none``.
    basis : str or None
        The limit it comes from: ``"k_criterion"`` or ``"k_sim"`` (None under ``none``).
    k_basis : float or None
        That limit's value (under ``simulated_range`` the top of the range searched, a lower bound of it).
    margin : float
        Gain margin of the simulated rule (>= 1); ``k_recommended = k_basis / margin`` under ``simulated``.
    status : RecommendRule
        The rule followed: ``proven``, ``simulated``, ``simulated_range`` (no divergence in the whole range
        searched) or ``none``.
    k_rest : float or None
        The simulated rest limit of the recommended wall (``k_sim_rest``: every simulated impact up to V comes
        to rest up to it); None when it has no value (``above_rest`` then says whether K lies above the lowest
        K searched, where impacts already failed to rest).
    above_rest : bool
        True when the recommended K lies above the rest limit: the wall may buzz or oscillate there (just above
        the limit some simulated impact up to V did not come to rest).
    controller : ControllerChoice or None
        With a passivity controller compared with the wall without it (``recommend_stiffness(..., plain=)``):
        which wall is recommended and why; otherwise None (absent from JSON).
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    k_recommended: float | None
    basis: str | None
    k_basis: float | None
    margin: float = DEFAULT_MARGIN
    status: RecommendRule = RecommendRule.NONE
    k_rest: float | None = None
    above_rest: bool = False
    controller: ControllerChoice | None = field(default=None, metadata={"omit_none": True})

    units_of: ClassVar[dict[str, str]] = {
        "velocity": "velocity", "k_recommended": "stiffness", "k_basis": "stiffness", "k_rest": "stiffness",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "Recommendation is built by recommend_stiffness; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        object.__setattr__(self, "status", RecommendRule.coerce(self.status))
        check_margin(self.margin)
        none = self.status is RecommendRule.NONE
        if none != (self.k_recommended is None) or none != (self.basis is None):
            raise DFAValueError(
                f"k_recommended = {self.k_recommended!r}, basis = {self.basis!r} are invalid for the rule "
                f"{self.status.value!r}: both must be None exactly under 'none'; {fix}"
            )
        if self.k_recommended is not None and not (math.isfinite(self.k_recommended) and self.k_recommended > 0):
            raise DFAValueError(f"k_recommended = {self.k_recommended!r} is invalid: it must be finite and > 0; {fix}")

    def null_reasons(self) -> dict[str, str]:
        """Why the recommendation may be null, by key.

        Returns
        -------
        dict of str to str
            The rule's message for ``k_recommended``, ``basis`` and ``k_basis``.
        """
        out = {name: self.status.message for name in ("k_recommended", "basis", "k_basis")}
        out["k_rest"] = "the simulated rest limit has no value (see k_sim_rest's status in the answer)"
        return out


def check_margin(margin: float) -> float:
    """The gain margin, a finite number >= 1 (1: the simulated limit itself), or the package's error naming it.

    Parameters
    ----------
    margin : float
        Gain margin of the simulated rule.

    Returns
    -------
    float
        ``margin``.

    Raises
    ------
    DFAValueError, DFATypeError
        If it is not a finite number >= 1.
    """
    m = check_positive("margin", margin, "give a gain margin >= 1, e.g. 2 (about 6 dB)")
    if not (math.isfinite(m) and m >= 1.0):
        raise DFAValueError(f"margin = {margin!r} is invalid: it must be a finite number >= 1; give e.g. 2 (6 dB)")
    return m


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
    pc = a.wall.passivity_controller
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
    return Recommendation(**base, k_recommended=None, basis=None, k_basis=None, status=RecommendRule.NONE)
