"""The paper's closed forms of the small stable (eq. 42-43) and large unstable (eq. 44-45) cycle families."""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from ..device import Params
from ..errors import check_mu


# --------------------------------------------------------------- closed forms
def large_cycle_frequency(mu: float) -> float:
    """ω of the paper's large-cycle family: cos(ω/2) = μω² (eq. 44), rad per sample.

    Examples
    --------
    >>> round(large_cycle_frequency(5.0), 5), round(large_cycle_frequency(100.0), 6)
    (0.44175, 0.099938)
    """
    m = check_mu(mu)
    return float(
        optimize.brentq(lambda w: m * w * w - math.cos(w / 2), 0.0, math.pi, xtol=1e-16, rtol=4 * np.finfo(float).eps)
    )


def large_cycle_closed_form(mu: float, beta: float, sigma: float) -> tuple[float, float] | None:
    """(M, ω) of the paper's large unstable cycle (eq. 44-45, D ≈ 1), or None when sin(ω/2) <= βω.

    M = (4σ/π)/(sin(ω/2) − βω) with ω from :func:`large_cycle_frequency`.
    """
    p = Params(mu, beta, sigma)
    w = large_cycle_frequency(p.mu)
    den = math.sin(w / 2) - p.beta * w
    if den <= 0:
        return None
    return 4 * p.sigma / (math.pi * den), w


def small_cycle_closed_form(mu: float, beta: float, sigma: float) -> tuple[float, float] | None:
    """(M, ω) of the paper's small stable cycle (eq. 42-43, D = 2/(πM)), or None when σ >= ½.

    ω solves σ = ½ sin(ω/2) − β cos(ω/2)/(2μω) on (0, π) (the right side
    increases from −∞ to ½), then M = 2 cos(ω/2)/(π μ ω²).
    """
    p = Params(mu, beta, sigma)
    if p.sigma >= 0.5:
        return None
    f = lambda w: 0.5 * math.sin(w / 2) - p.beta * math.cos(w / 2) / (2 * p.mu * w) - p.sigma
    hi = math.pi
    lo = 1e-300 if p.beta > 0 else 0.0
    if p.beta == 0.0:
        w = 2 * math.asin(2 * p.sigma) if p.sigma > 0 else None
        if w is None:
            return None
    else:
        w = optimize.brentq(f, lo, hi, xtol=1e-16, rtol=4 * np.finfo(float).eps)
    return 2 * math.cos(w / 2) / (math.pi * p.mu * w * w), w
