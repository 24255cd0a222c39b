"""Where the describing function's growth verdict is no stronger than a guess: the sub-tick caveat.

The first-harmonic analysis separates, at the smallest unstable cycle M_u, the starts that settle on a
stable cycle below it from those that grow. When M_u lies just above the first quantization level
(M_u < :data:`SUBTICK_LIMIT` ticks, on the steep flank of D(M) right above M = 1, eq. 41), that separation
rests on the sub-tick cycles, whose amplitude the first harmonic predicts poorly: the real sub-tick
chatter is not a sinusoid, reaches further than the predicted cycle, touches the level at ±1 tick and
then grows. Measured by exact simulation (200 000 samples) of 60 random starts with energy amplitude below
0.9·M_u, at 790 (operating point, hold model) pairs with 1 <= M_u < 1.4 from a random search with and without a
wall controller (virtual damper, velocity filter, one sample of delay; 222 of them the paper's spring): divergence
from at least a third of the starts at 122 of the 156 pairs with M_u < 1.005; from more than 10 % of them at 50
of 245 pairs with 1.005 <= M_u < 1.03 (at worst 82 %) and at 5 of 214 with 1.03 <= M_u < 1.1 (at worst 87 %,
M_u = 1.066); at most 3 % of the starts at the 175 pairs with M_u >= 1.1. The same happens with the paper's
spring (36 of its 222 pairs diverged from a third of the starts or more); it is not the controller's doing. It is not
D(M) vanishing below ½ tick either: the quantizer q = ⌊ξ⌋ + ½ is a relay there, D = 2/(πM). Example (exact ZOH
model, d = 0): μ = 3.749, β = 0, σ = 0.155, β_B = 0.2838, ν_c = 0.0042 (filter pole a = 0.974) predicts a stable
cycle at M = 0.40 and M_u = 1.014; the simulated chatter has amplitude 0.74–0.81 tick, its peaks come within
1–5 % of the level before the runs that diverge cross it, and about half of the starts of 0.25 and 0.5 tick
diverge (``tests/test_eq36_subtick_caveat.py``). At the point a red team reported (μ = 17.14, β = 0.0158,
σ = 0.130, β_B = 0.0338, a = 0.959, d = 0) the exact-ZOH M_u is 1.20 ticks and simulation agreed with the
describing function (2 of 399 grid starts below one tick diverged; every start above 1.5 ticks but 10 of 380 did);
it lies below :data:`SUBTICK_LIMIT` and carries the caveat.

:func:`subtick_caveat` says so for a :class:`~dfa.analysis.cycles.LimitCycleResult`; the growth verdicts that use the
smallest unstable cycle (:class:`~dfa.analysis.cycles.GrowthThreshold`, the describing-function K_max of
:mod:`dfa.analysis.limits.kmax` and the Z-width) carry it, or become unknown.

Examples
--------
>>> from dfa.model.device import Params
>>> from dfa.analysis.cycles import limit_cycles
>>> subtick_caveat(limit_cycles(Params(5.0, 0.1, 0.3))) is None     # M_u = 2.1 ticks
True
>>> SubtickCaveat(1.014)
SubtickCaveat(amplitude=1.014, limit=1.25)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from ..errors import DFAValueError

__all__ = ["SUBTICK_LIMIT", "SubtickCaveat", "subtick_caveat", "NoRestCaveat", "no_rest_caveat", "NO_REST_CAVEAT"]

#: Smallest unstable cycles below this amplitude (ticks) get the sub-tick caveat: 1.25, the top of the rising
#: flank of D(M) above the first level (its peak, 1.1206 at M ≈ 1.242); simulation found sub-tick starts diverging
#: at points with M_u up to 1.066 (module docstring).
SUBTICK_LIMIT = 1.25

#: The reason of a null ``caveat`` in JSON.
NO_CAVEAT = f"no caveat: no unstable cycle below SUBTICK_LIMIT = {SUBTICK_LIMIT:g} ticks"


@dataclass(frozen=True)
class SubtickCaveat:
    """The sub-tick caveat of a growth verdict (module docstring), as data: the rendering layer words it.

    Attributes
    ----------
    amplitude : float
        M of the smallest unstable cycle, ticks (below ``limit``).
    limit : float
        :data:`SUBTICK_LIMIT`, ticks.
    """

    amplitude: float
    limit: float = SUBTICK_LIMIT

    def __post_init__(self) -> None:
        if not (math.isfinite(self.amplitude) and 0.0 < self.amplitude < self.limit):
            raise DFAValueError(
                f"amplitude = {self.amplitude!r} is invalid: the caveat holds for 0 < M < {self.limit:g} ticks; "
                "build it with subtick_caveat"
            )


def subtick_caveat(result: Any) -> SubtickCaveat | None:
    """The sub-tick caveat of a limit-cycle result, or None when its growth verdict does not rest on it.

    Parameters
    ----------
    result : LimitCycleResult
        From :func:`dfa.analysis.cycles.limit_cycles`.

    Returns
    -------
    SubtickCaveat or None
        The caveat when the smallest unstable cycle lies below :data:`SUBTICK_LIMIT` ticks (module docstring);
        None otherwise (no unstable cycle, or the smallest is larger).
    """
    unstable = [c for c in result.cycles if not c.stable]
    if not unstable or unstable[0].amplitude >= SUBTICK_LIMIT:
        return None
    return SubtickCaveat(float(unstable[0].amplitude))


#: The reason of a null ``rest_caveat`` in JSON.
NO_REST_CAVEAT = "no caveat: σ >= ½, the friction can hold the spring's half force step KΔ/2 (the device can rest)"


@dataclass(frozen=True)
class NoRestCaveat:
    """σ < ½: the device can never rest, so "no limit cycle" does not mean it comes to rest (issue 26 §2).

    At rest the quantized spring pushes with up to half a force step KΔ/2, which Coulomb friction c holds only
    when σ = c/(KΔ) >= ½ (eq. 9). Below, the device moves at every sample and chatters below one tick (measured
    at 0.0005-0.005 tick at μ = 20, β = 0.55, σ = 0.45, exact ZOH model, where the search finds no cycle): the
    describing function of eq. 41 has no such cycle, so "no limit cycle predicted" holds above one tick only.

    Attributes
    ----------
    sigma : float
        The operating point's σ, in [0, ½).

    Examples
    --------
    >>> NoRestCaveat(0.45).sigma
    0.45
    """

    sigma: float

    def __post_init__(self) -> None:
        if not (math.isfinite(self.sigma) and 0.0 <= self.sigma < 0.5):
            raise DFAValueError(
                f"sigma = {self.sigma!r} is invalid: the caveat holds for 0 <= σ < ½; build it with no_rest_caveat"
            )


def no_rest_caveat(result: Any) -> NoRestCaveat | None:
    """The no-rest caveat of a limit-cycle result (:class:`NoRestCaveat`), or None when σ >= ½.

    Parameters
    ----------
    result : LimitCycleResult
        From :func:`dfa.analysis.cycles.limit_cycles`.

    Returns
    -------
    NoRestCaveat or None
    """
    sigma = float(result.params.sigma)
    return NoRestCaveat(sigma) if sigma < 0.5 else None
