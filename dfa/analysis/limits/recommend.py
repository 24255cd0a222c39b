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
from dataclasses import dataclass, field
from typing import ClassVar

from ...checks import check_positive, check_type
from ...errors import DFAValueError
from ...model.device import Device
from ...model.wall import Wall
from ...results.base import Result
from ...results.status import KMaxStatus, LimitStatus, RecommendRule
from .kmax import KMaxResult

__all__ = ["Recommendation", "recommend_stiffness", "check_margin", "DEFAULT_MARGIN"]

#: Default gain margin of the simulated rule: the simulated limit divided by 2 (about 6 dB).
DEFAULT_MARGIN = 2.0


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
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    k_recommended: float | None
    basis: str | None
    k_basis: float | None
    margin: float = DEFAULT_MARGIN
    status: RecommendRule = RecommendRule.NONE

    units_of: ClassVar[dict[str, str]] = {
        "velocity": "velocity", "k_recommended": "stiffness", "k_basis": "stiffness",
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
        return {name: self.status.message for name in ("k_recommended", "basis", "k_basis")}


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


def recommend_stiffness(answer: KMaxResult, margin: float = DEFAULT_MARGIN) -> Recommendation:
    """One recommended stiffness for the answer's impact speed, by the rule of the module docstring.

    Parameters
    ----------
    answer : KMaxResult
        K_max four ways (:func:`dfa.analysis.limits.kmax.design_answer`).
    margin : float, optional
        Gain margin of the simulated rule, >= 1 (default 2, about 6 dB). The proven rule needs none.

    Returns
    -------
    Recommendation
        The stiffness, the limit it rests on and the rule.

    Raises
    ------
    DFATypeError, DFAValueError
        If ``answer`` is not a :class:`KMaxResult` or ``margin`` is not a finite number >= 1.
    """
    a = check_type("answer", answer, KMaxResult, "pass the result of dfa.design_answer")
    m = check_margin(margin)
    base = dict(device=a.device, wall=a.wall, velocity=a.velocity, margin=m)
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
