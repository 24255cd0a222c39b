"""Which amplitudes the limit-cycle search samples, and where the eq. 41 envelope proves that no root lies beyond."""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from ...grids import geometric_grid
from ..describing import DF_ENVELOPE
from .characteristic import M_FLOOR, HarmonicLoop, inv_loop

if TYPE_CHECKING:
    from .phase import PieceOmega

#: Most far intervals [n, n + 1] (n > 32) sampled point by point per piece; beyond, the search ends incomplete.
INTERVAL_BUDGET = 20_000


def m_samples(
    lo: float, hi: float, max_amp: float, lp: HarmonicLoop, w_inf: float | None, omega_of: PieceOmega
) -> tuple[np.ndarray, tuple[float, str] | None, float]:
    """Sample amplitudes on [lo, hi] ∩ (0, max_amp], stopping by the envelope rule.

    Returns (samples, reach, bound): ``reach`` is None when every root of the piece lies
    among the samples' brackets (the piece ends, or the envelope bound
    |D − 1| <= 0.38⌊M⌋^{-3/2} proves there is no root beyond the last sample), else
    (amplitude searched up to, "max_amplitude" or "budget"); ``bound`` is the amplitude
    (ticks) beyond which the piece has no root when ``reach`` is None.
    """
    pts = []
    if lo < 1.0 and hi > M_FLOOR:
        pts.append(geometric_grid(max(lo, M_FLOOR), min(1.0, hi), 400))
    reach, bound = None, min(hi, 1.0)
    if hi > 1.0:
        n0 = max(1, int(math.floor(lo)))
        n_end = int(math.ceil(min(hi, max_amp)))
        if lp.df != "exact":
            # the paper's approximations have no integer structure: a geometric grid suffices
            pts.append(geometric_grid(max(lo, 1.0), min(hi, max_amp), 4000))
            return (
                np.unique(np.concatenate(pts)),
                (None if hi <= max_amp else (max_amp, "max_amplitude")),
                min(hi, max_amp),
            )
        near = np.arange(n0, min(n_end, 32) + 1)
        # n + t² resolves the √ at each integer; far out D's excursions are tiny and self-similar: fewer points
        t_near, t_far = np.linspace(0.0, 1.0, 25), np.linspace(0.0, 1.0, 9)
        near_grid = (near[:, None] + (t_near * t_near)[None, :]).ravel()
        # the samples known before the far intervals: their ω in the root finder's first run (PieceOmega.want)
        omega_of.want(np.concatenate([*pts, near_grid[(near_grid >= lo) & (near_grid <= min(hi, max_amp))]]))
        if w_inf is None:  # a finite far end: its ω solved with the first far block's (PieceOmega.want)
            omega_of.want(np.array([hi]))
        far_u = functools.partial(_far_end_u, lp, hi, w_inf, omega_of)
        far, n_stop, budget_hit = _far_intervals(lp, max(n0, 33), n_end, far_u, omega_of, lo, hi)
        if budget_hit:
            reach = (float(n_stop), "budget")
        elif n_stop >= n_end and hi > max_amp:
            reach = (max_amp, "max_amplitude")
        grid = np.concatenate([near_grid, (far[:, None] + (t_far * t_far)[None, :]).ravel()])
        top = min(hi, max_amp, float(n_stop) + 1.0)
        bound = top
        pts.append(grid[(grid >= lo) & (grid <= top)])
    if not pts:
        return np.array([]), reach, bound
    return np.unique(np.concatenate(pts)), reach, bound


def _far_end_u(lp: HarmonicLoop, hi: float, w_inf: float | None, omega_of: PieceOmega) -> float:
    """−U at the piece's far end: at M = ∞ (at ``w_inf``), where β_eq = β (at ω = 0 the loop inverse is 0), else at
    the finite far end ``hi`` and its ω."""
    if w_inf is None:
        return -float(np.real(lp.inv(float(hi), float(omega_of(np.array([hi]))[0]))))
    if w_inf == 0.0:
        return 0.0
    return -float(np.real(inv_loop(lp.params.mu, lp.params.beta, w_inf, lp.model, lp.delay, lp.pade_order, lp.wall)))


def _far_intervals(
    lp: HarmonicLoop,
    n_from: int,
    n_end: int,
    far_u: Callable[[], float],
    omega_of: PieceOmega,
    lo: float,
    hi: float,
) -> tuple[np.ndarray, int, bool]:
    """Far intervals [n, n + 1] (n >= n_from > 32) that can hold a root, up to the envelope stop.

    −U = −Re(1/L) along the piece decides both, under the premise that far out −U moves
    monotonically in M along a monotone piece, towards ``u_far = far_u()`` (its value at the piece's far
    end; at M = ∞, where β_eq = β; evaluated after the first block, whose run of the root finder solves its ω):
    (1) the stop: the first block start n where −U(n) and u_far lie on one side of 1, both farther
        from 1 than the envelope 0.38 n^{-3/2}: no root exists beyond (eq. 41 envelope);
    (2) which intervals to sample: a block [n_a, n_b] whose two ends have −U on one side of 1, farther
        than twice the envelope at n_a, holds no root; other blocks are split into unit intervals.
    Blocks are n/128 ticks long, so a search to 10⁶ ticks costs ~10⁴ evaluations of ω(M) plus the kept
    intervals. Returns (kept n, n_stop, budget_hit); at most INTERVAL_BUDGET intervals are kept.
    """
    if n_from > n_end:
        return np.array([], dtype=np.int64), n_end, False
    kept: list[np.ndarray] = []
    count, start = 0, n_from
    u_far: float | None = None
    while start <= n_end:
        step = max(1, start // 128)
        edges = np.unique(np.minimum(start + step * np.arange(0, 257), n_end + 1)).astype(float)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = -np.real(lp.inv(np.clip(edges, lo, hi), omega_of(np.clip(edges, lo, hi)))) - 1.0
        if u_far is None:
            u_far = far_u()
        ns = edges[:-1]
        env = DF_ENVELOPE * ns**-1.5
        a, b = u[:-1], u[1:]
        meets = ~(np.isfinite(a) & np.isfinite(b) & (a * b > 0) & (np.minimum(np.abs(a), np.abs(b)) > 2.0 * env))
        stop = np.isfinite(a) & (a * (u_far - 1.0) > 0) & (np.minimum(np.abs(a), abs(u_far - 1.0)) > env)
        last = int(np.argmax(stop)) if stop.any() else ns.size
        for i in np.flatnonzero(meets[:last]):
            k = np.arange(int(edges[i]), int(edges[i + 1]))
            if count + k.size > INTERVAL_BUDGET:
                k = k[: INTERVAL_BUDGET - count]
                kept.append(k)
                return np.concatenate(kept).astype(np.int64), int(k[-1]) if k.size else int(edges[i]), True
            kept.append(k)
            count += k.size
        if last < ns.size:
            return _cat(kept), int(ns[last]), False
        start = int(edges[-1])
        if start > n_end:
            break
    return _cat(kept), n_end, False


def _cat(parts: list) -> np.ndarray:
    return np.concatenate(parts).astype(np.int64) if parts else np.array([], dtype=np.int64)


def envelope_bound(u: float) -> float:
    """Amplitude (ticks) beyond which D(M) = u has no root: ⌊M⌋ > (0.38/|u − 1|)^{2/3} (eq. 41 envelope).

    Infinite for u = 1 (D → 1 as M → ∞: roots at every amplitude).
    """
    if u == 1.0:
        return math.inf
    return math.floor((DF_ENVELOPE / abs(u - 1.0)) ** (2.0 / 3.0)) + 1.0
