"""The phase condition V = 0 of the harmonic balance: β*(ω), its monotone pieces M(ω) and ω(M) on a piece (eq. 36, 40)."""

from __future__ import annotations

import bisect
import math
from functools import lru_cache
from typing import Any

import numpy as np
from scipy import optimize

from ...core.bracket import bracketed_roots
from ...grids import geometric_grid
from ...model.wall import WallParams
from .characteristic import W_GRID, HarmonicLoop, inv_loop, phase_lead, wall_ratio, wall_ratio_scalar

# --------------------------------------------------------------- phase curve


def phase_beta(lp: HarmonicLoop, w: np.ndarray) -> np.ndarray:
    """β*(ω): the damping at which V = 0 with U < 0 (NaN where there is none)."""
    mu, d = lp.params.mu, lp.delay
    if lp.model != "zoh":
        # V = 0 ⇔ β_eq = μω tan φ, and then U = −μω²/cos φ < 0 ⇔ cos φ > 0; β_eq >= 0 ⇒ φ mod 2π ∈ [0, π/2)
        th = phase_lead(w, lp.model, d, lp.pade_order)
        if lp.wall is not None:  # 1/L = e^{jθ}·R(ω)·(−μω² + jωβ_eq): R adds its phase to the lead, |R| > 0
            th = th + np.angle(wall_ratio(lp.wall, w))
            if lp.wall.hand_stiffness > 0.0:
                return _hand_phase_beta(mu, lp.wall.hand_stiffness, w, th)
        ok = np.mod(th, 2 * math.pi) < math.pi / 2
        with np.errstate(invalid="ignore"):
            return np.where(ok, mu * w * np.tan(th), np.nan)
    if w is W_GRID:  # β* does not depend on β or σ: a sweep at fixed μ scans the grid once
        return zoh_phase_beta_grid(mu, d, lp.wall)
    return _zoh_phase_beta(mu, d, w, lp.wall)


def _hand_phase_beta(mu: float, kap: float, w: np.ndarray, th: np.ndarray) -> np.ndarray:
    """β*(ω) with a hand spring: 1/L = e^{jθ}(κ_h − μω² + jωβ_eq), so with a = μω² − κ_h, V = 0 ⇔
    β_eq = a tan θ/ω, and U = −a/cos θ < 0 ⇔ a/cos θ > 0; β_eq >= 0 ⇔ a tan θ >= 0 (a > 0: the spring's rule)."""
    a = mu * w * w - kap
    with np.errstate(invalid="ignore", divide="ignore"):
        ok = (a / np.cos(th) > 0.0) & (a * np.tan(th) >= 0.0)
        return np.where(ok, a * np.tan(th) / w, np.nan)


@lru_cache(maxsize=16)
def zoh_phase_beta_grid(mu: float, d: int, wall: WallParams | None = None) -> np.ndarray:
    out = _zoh_phase_beta(mu, d, W_GRID, wall)
    out.flags.writeable = False
    return out


def _zoh_phase_beta(mu: float, d: int, w: np.ndarray, wall: WallParams | None = None) -> np.ndarray:
    """β*(ω) of the exact ZOH loop: scan β on a log grid, bracket V's crossing with U < 0, bisect (vectorised)."""
    bgrid = np.concatenate([[0.0], geometric_grid(1e-9, 1e5, 400)])
    c = inv_loop(mu, bgrid[None, :], w[:, None], "zoh", d, 0, wall)
    v = c.imag
    sc = (np.sign(v[:, :-1]) != np.sign(v[:, 1:])) & (c.real[:, :-1] < 0) & (c.real[:, 1:] < 0)
    has = sc.any(axis=1)
    idx = np.argmax(sc, axis=1)
    lo = bgrid[idx]
    hi = bgrid[idx + 1]
    vlo = v[np.arange(w.size), idx]
    if w.size <= 4:  # a few frequencies (the ends of a phase-curve piece): Brent on the scalar loop inverse
        out = np.full(w.size, np.nan)
        for i in np.flatnonzero(has):
            wi = float(w[i])
            out[i] = optimize.brentq(
                lambda b, wi=wi: inv_loop(mu, b, wi, "zoh", d, 0, wall).imag,
                float(lo[i]),
                float(hi[i]),
                xtol=1e-300,
                rtol=4 * np.finfo(float).eps,
            )
        return out
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        vm = inv_loop(mu, mid, w, "zoh", d, 0, wall).imag
        left = np.sign(vm) == np.sign(vlo)
        lo = np.where(left, mid, lo)
        vlo = np.where(left, vm, vlo)
        hi = np.where(left, hi, mid)
    return np.where(has, 0.5 * (lo + hi), np.nan)


def _omega_for_m(lp: HarmonicLoop, m: np.ndarray, wa: np.ndarray, wb: np.ndarray) -> np.ndarray:
    """Solve V(M, ω) = 0 for ω in the brackets [wa, wb] (:func:`dfa.core.bracket.bracketed_roots`: elementwise,
    the tolerances of scipy's ``find_root``, compiled steps).

    Where V does not change sign over a bracket (a root at an end, to rounding), the end with the
    smaller |V| is returned: the same rule as :meth:`PieceOmega.scalar`, so that the scan and the
    refinement of a root evaluate F(M) = D(M) + U(M, ω(M)) as one function.
    """
    va = lp.inv(m, wa).imag
    vb = lp.inv(m, wb).imag
    end = np.where(np.abs(va) <= np.abs(vb), wa, wb)
    no_change = (va == 0.0) | (vb == 0.0) | ((va < 0) == (vb < 0))
    if no_change.all():
        return end
    change = ~no_change
    x, _ = bracketed_roots(
        lambda w, mm: lp.inv(mm, w).imag, wa[change], wb[change], va[change], vb[change], (m[change],)
    )
    # a failure (no convergence, a non-finite V) gives NaN, never an end
    out = end.astype(float)
    out[change] = x
    return out


def phase_pieces(lp: HarmonicLoop) -> list[tuple[np.ndarray, np.ndarray]]:
    """Monotone pieces (ω, M) of the phase curve, each with an exact M = ∞ end where it reaches β* = β."""
    w = W_GRID
    bs = phase_beta(lp, w)
    beta, sigma = lp.params.beta, lp.params.sigma
    excess = bs - beta
    valid = np.isfinite(excess) & (excess > 0)
    out: list[tuple[np.ndarray, np.ndarray]] = []
    n = w.size
    # the runs [i, j] of valid grid points (the edges of the valid mask)
    edges = np.flatnonzero(np.diff(np.concatenate(([0], valid.astype(np.int8), [0]))))
    for i, j in zip(edges[::2].tolist(), (edges[1::2] - 1).tolist(), strict=True):
        ws = w[i : j + 1]
        ms = 4 * sigma / (math.pi * ws * excess[i : j + 1])
        # add the exact point where β* = β (M = ∞) at either end, when the curve crosses there
        ends = []
        for k_in, k_out in ((i, i - 1), (j, j + 1)):
            if 0 <= k_out < n and np.isfinite(excess[k_out]) and excess[k_out] <= 0:
                try:
                    ends.append((k_in, _infinite_end(lp, float(w[k_in]), float(w[k_out]))))
                except ValueError:
                    pass
        if i == 0 and beta == 0.0:
            ends.append((i, 0.0))  # every model is a double integrator at low ω: β* → 0 as ω → 0
        for k_in, w0 in ends:
            if k_in == i:
                ws = np.concatenate([[w0], ws])
                ms = np.concatenate([[np.inf], ms])
            else:
                ws = np.concatenate([ws, [w0]])
                ms = np.concatenate([ms, [np.inf]])
        out += _monotone_runs(ws, ms)
    return out


def _monotone_runs(ws: np.ndarray, ms: np.ndarray) -> list[tuple[np.ndarray, np.ndarray]]:
    """A run of the phase curve split into monotone runs of M, neighbours sharing their end point."""
    dm = np.sign(np.diff(ms))  # ±inf differences at an M = ∞ end keep their sign
    if not dm.size:
        return []
    cuts = [0, *(np.flatnonzero(dm[1:] != dm[:-1]) + 1).tolist(), dm.size]
    return [(ws[a : b + 1], ms[a : b + 1]) for a, b in zip(cuts[:-1], cuts[1:], strict=False)]


def _infinite_end(lp: HarmonicLoop, w_in: float, w_out: float) -> float:
    """The frequency between two grid points where β*(ω) = β (an M = ∞ end of a piece), by Brent's method;
    β* at one frequency in plain float arithmetic for the half-delay and Padé models (:func:`_phase_beta_scalar`).
    Raises ValueError when the ends do not bracket it."""
    beta = lp.params.beta
    if lp.model == "zoh":
        f = lambda x: float(phase_beta(lp, np.array([x]))[0] - beta)
    else:
        f = lambda x: _phase_beta_scalar(lp, x) - beta
    return float(optimize.brentq(f, min(w_in, w_out), max(w_in, w_out), xtol=1e-15))


def _phase_beta_scalar(lp: HarmonicLoop, w: float) -> float:
    """:func:`phase_beta` at one frequency of the half-delay and Padé models (NaN where there is none)."""
    th = phase_lead(w, lp.model, lp.delay, lp.pade_order)
    mu = lp.params.mu
    if lp.wall is not None:
        r = wall_ratio_scalar(lp.wall, w)
        th = th + math.atan2(r.imag, r.real)
        kap = lp.wall.hand_stiffness
        if kap > 0.0:  # as _hand_phase_beta
            a = mu * w * w - kap
            c, t = math.cos(th), math.tan(th)
            return a * t / w if (a / c > 0.0) and (a * t >= 0.0) else math.nan
    return mu * w * math.tan(th) if th % (2 * math.pi) < math.pi / 2 else math.nan


class PieceOmega:
    """ω(M) on one monotone piece of the phase curve: V(M, ω) = 0 bracketed by the piece's grid."""

    def __init__(self, lp: HarmonicLoop, ws: np.ndarray, ms: np.ndarray):
        order = np.argsort(ms)
        self.lp, self.ms, self.ws = lp, ms[order], ws[order]
        self._known_m, self._known_w = np.empty(0), np.empty(0)  # amplitudes solved (ascending) and their ω
        self._wanted: list[np.ndarray] = []
        self._ms_list: list[float] | None = None  # the sorted pieces as lists, for the scalar path's brackets
        self._ws_list: list[float] = []

    def _brackets(self, m: float | np.ndarray) -> tuple[Any, Any]:
        k = np.clip(np.searchsorted(self.ms, m), 1, self.ms.size - 1)
        return self.ws[k - 1], self.ws[k]

    def want(self, m: np.ndarray) -> None:
        """Amplitudes whose ω the next call solves as well, in the same run of the root finder.

        The root finder is elementwise (each amplitude's iterations are its own), so an ω does not depend on
        the amplitudes solved beside it: asking early only saves the root finder's fixed cost of a run.
        """
        self._wanted.append(np.asarray(m, dtype=float).ravel())

    def __call__(self, m: np.ndarray) -> np.ndarray:
        """ω(M) at the amplitudes ``m`` (and those :meth:`want` asked for), each solved once per piece.

        The amplitudes solved are kept sorted with their ω; a call solves the new ones (each once, however often
        asked) in one run of the root finder and looks every asked one up by :func:`numpy.searchsorted`.
        """
        m = np.asarray(m, dtype=float)
        asked = np.concatenate([m.ravel(), *self._wanted])
        self._wanted = []
        new = np.unique(asked[~self._known(asked)])
        if new.size:
            wa, wb = self._brackets(new)
            ms = np.concatenate([self._known_m, new])
            order = np.argsort(ms, kind="stable")
            self._known_m = ms[order]
            self._known_w = np.concatenate([self._known_w, _omega_for_m(self.lp, new, wa, wb)])[order]
        return self._known_w[np.searchsorted(self._known_m, m.ravel())].reshape(m.shape)

    def _known(self, m: np.ndarray) -> np.ndarray:
        """Whether each amplitude of ``m`` is solved already."""
        k = np.minimum(np.searchsorted(self._known_m, m), max(self._known_m.size - 1, 0))
        return self._known_m[k] == m if self._known_m.size else np.zeros(m.shape, dtype=bool)

    def scalar(self, m: float) -> float:
        """The same for one amplitude, by Brent's method on the scalar loop inverse (same end rule as the vector path)."""
        if self._ms_list is None:
            self._ms_list, self._ws_list = self.ms.tolist(), self.ws.tolist()
        k = min(max(bisect.bisect_left(self._ms_list, m), 1), len(self._ms_list) - 1)  # as _brackets: searchsorted
        wa, wb = self._ws_list[k - 1], self._ws_list[k]
        lp = self.lp

        def v(w: float) -> float:
            return lp.inv(m, w).imag

        va, vb = v(wa), v(wb)
        if va == 0.0 or vb == 0.0 or (va < 0) == (vb < 0):  # a root on a bracket end (rounding): take the smaller |V|
            return wa if abs(va) <= abs(vb) else wb
        return optimize.brentq(v, wa, wb, xtol=1e-300, rtol=4 * np.finfo(float).eps)
