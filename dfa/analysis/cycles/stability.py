"""Stability of a harmonic-balance root by the Loeb criterion, and the Newton polish of a bracketed root (eq. 36)."""

from __future__ import annotations

import math

import numpy as np
from scipy import optimize

from ...results.cycles import LimitCycle
from .characteristic import HarmonicLoop


# ------------------------------------------------------------------- solver
def _loeb(lp: HarmonicLoop, m: float, w: float) -> float:
    hm = 1e-7 * max(m, 1e-3)
    hw = 1e-7 * w
    cm = (lp.inv(m + hm, w) - lp.inv(m - hm, w)) / (2 * hm) + lp.dprime(m)
    cw = (lp.inv(m, w + hw) - lp.inv(m, w - hw)) / (2 * hw)
    return float(cm.real * cw.imag - cw.real * cm.imag)


def _polish(lp: HarmonicLoop, m: float, w: float) -> tuple[float, float]:
    """2-D Newton on (U, V) from a bracketed root; keeps the start if Newton wanders."""

    def f(x: np.ndarray) -> list[float]:
        c = lp.char(x[0], x[1])
        return [float(np.real(c)), float(np.imag(c))]

    try:
        sol = optimize.root(f, [m, w], method="hybr", options={"xtol": 1e-15})
        mm, ww = float(sol.x[0]), float(sol.x[1])
        if (
            sol.success
            and abs(mm - m) <= 1e-6 * max(1.0, m)
            and abs(ww - w) <= 1e-6 * w
            and mm > 0
            and 0 < ww < math.pi
        ):
            if abs(lp.char(mm, ww)) <= abs(lp.char(m, w)):
                return mm, ww
    except (ValueError, FloatingPointError):  # pragma: no cover
        pass
    return m, w


def make_cycle(lp: HarmonicLoop, m: float, w: float, polish: bool = True) -> LimitCycle:
    if polish:
        m, w = _polish(lp, m, w)
    inv = lp.inv(m, w)
    return limit_cycle_at(m, w, _loeb(lp, m, w), float(abs(1.0 + lp.d(m) / inv)))


def limit_cycle_at(m: float, w: float, loeb: float, residual: float) -> LimitCycle:
    return LimitCycle(
        amplitude=float(m),
        frequency=float(w),
        stable=bool(loeb > 0),
        family="small" if m < 1.0 else "large",
        loeb=float(loeb),
        residual=float(residual),
        few_samples=bool(2 * math.pi / w < 8.0),
    )


def cycles_at_crossing(lp: HarmonicLoop, roots: np.ndarray, w: float) -> list[LimitCycle]:
    """Cycles at one phase crossing ω of an amplitude-independent loop (σ = 0), all roots at once.

    There ∂(1/L)/∂M = 0, so the Loeb quantity reduces to D'(M)·∂V/∂ω.
    """
    if roots.size == 0:
        return []
    inv = complex(lp.inv(1.0, w))
    hw = 1e-7 * w
    cw = complex((lp.inv(1.0, w + hw) - lp.inv(1.0, w - hw)) / (2 * hw))
    loeb = np.asarray(lp.dprime(roots), dtype=float) * cw.imag
    resid = np.abs(1.0 + np.asarray(lp.d(roots), dtype=float) / inv)
    return [
        limit_cycle_at(m, w, lo, r) for m, lo, r in zip(roots.tolist(), loeb.tolist(), resid.tolist(), strict=False)
    ]
