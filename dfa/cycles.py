"""Limit cycles of the quantized, frictional loop by harmonic balance (paper section 7, eq. 36-45).

A cycle ξ = M sin ωτ exists where the characteristic function

    C(M, ω) = 1/L(jω; M) + D(M) = U + jV

vanishes (eq. 36 divided by L), with D the exact quantizer describing function
(eq. 41) and L the loop of :mod:`dfa.loop` (half-sample delay, Padé or exact
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

How far the search goes
-----------------------
Beyond n = 32 the march over integer intervals n stops where the envelope
|D(M) − 1| <= 0.38⌊M⌋^{-3/2} (see :mod:`dfa.describing`) can no longer meet
−U (−U at n and at the piece's far end on one side of 1, both farther than the
envelope), and intervals whose ends are both more than twice the envelope from
1 on one side are skipped. That stop is the amplitude beyond which no root can
exist for these (μ, β, σ, model, d) (``LimitCycleResult.search_bound``); by
default the search follows it up to ``AUTO_MAX_AMPLITUDE`` ticks, keeping at
most ``INTERVAL_BUDGET`` intervals per piece. A caller's ``max_amplitude``, the
budget or a numerical failure ends the search with ``complete=False`` and a
:class:`SearchStatus`; nothing is then claimed beyond the range searched. With
σ = 0 the phase condition gives isolated frequencies and D(M) = −U is inverted
exactly (compiled, :mod:`dfa._dfcore`).

Stability (Loeb criterion): a cycle is stable when
∂U/∂M·∂V/∂ω − ∂U/∂ω·∂V/∂M > 0, the sign that makes an amplitude increase
come with a decaying envelope (s = jω convention). For the half-delay model
∂V/∂ω < 0 at every root, so a stable cycle is one where F falls through zero.

Examples
--------
>>> from dfa.device import Params
>>> res = limit_cycles(Params(mu=5.0, beta=0.1, sigma=0.3))
>>> [(round(c.amplitude, 4), round(c.frequency, 4), c.stable, c.family) for c in res.cycles][:2]
[(0.058, 1.3172, True, 'small'), (2.1024, 0.4465, False, 'large')]
"""

from __future__ import annotations

import cmath
import enum
import math
import time
import warnings
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from scipy import optimize

from . import _dfcore
from .describing import DF_ENVELOPE
from .device import Device, Params
from .errors import DFAValueError, check_choice, check_mu, check_positive, check_type
from .loop import _check_model, _check_params, _zoh_coefficients

__all__ = [
    "LimitCycle",
    "LimitCycleResult",
    "limit_cycles",
    "small_cycle_closed_form",
    "large_cycle_closed_form",
    "large_cycle_frequency",
    "GrowthThreshold",
    "growth_threshold",
    "SearchStatus",
    "LimitCycleSearchWarning",
    "envelope_bound",
    "AUTO_MAX_AMPLITUDE",
    "INTERVAL_BUDGET",
    "DEFAULT_TIME_BUDGET",
]

_DF_CHOICES = ("exact", "small", "unity")

#: Amplitudes below this (ticks) are not searched: there F ≈ (2 − 4σ)/(πM) keeps its sign.
_M_FLOOR = 1e-9


#: Frequency grid (rad per sample) on which the phase curve is scanned before bracketing.
_W_GRID = np.concatenate([np.geomspace(1e-5, 0.05, 600, endpoint=False), np.linspace(0.05, math.pi - 1e-9, 3000)])
_W_GRID.flags.writeable = False


# ------------------------------------------------------------ loop inverse
# For the half-delay and Padé models 1/L = e^{jφ(ω)}·(−μω² + jωβ_eq): the device times an
# all-pass phase lead φ (the inverse of the hold's delay). Half-delay: φ = ω(d + ½). Padé:
# the diagonal approximant of e^{−sτ} has num(s) = den(−s), so den(jω)/num(jω) = e^{2j·arg den(jω)}.
# Scalars take a plain-complex path (the bracketing root finders call it thousands of times).


@lru_cache(maxsize=64)
def _grid_lead(model: str, delay: int, pade_order: int) -> tuple[np.ndarray, np.ndarray]:
    """(φ, e^{jφ}) on _W_GRID, cached: the grid is scanned once per solve."""
    lead = _lead_eval(_W_GRID, model, delay, pade_order)
    return lead, np.exp(1j * lead)


def _lead(w, model: str, delay: int, pade_order: int):
    """Phase lead φ(ω) of 1/L over the device's inverse (half-delay and Padé models), rad."""
    if w is _W_GRID:
        return _grid_lead(model, delay, pade_order)[0]
    return _lead_eval(w, model, delay, pade_order)


def _rotation(w, model: str, delay: int, pade_order: int):
    """e^{jφ(ω)} (vectorised), cached on _W_GRID."""
    if w is _W_GRID:
        return _grid_lead(model, delay, pade_order)[1]
    return np.exp(1j * _lead_eval(w, model, delay, pade_order))


def _lead_eval(w, model: str, delay: int, pade_order: int):
    if model == "half-delay":
        return w * (delay + 0.5)
    den = _pade(delay + 0.5, pade_order)
    if np.ndim(w) == 0:
        s, pd = 1j * float(w), 0j
        for c in den:
            pd = pd * s + c
        return 2.0 * cmath.phase(pd)
    return 2.0 * np.angle(np.polyval(den, 1j * np.asarray(w, dtype=float)))


def _inv_loop(mu: float, beq, omega, model: str, delay: int, pade_order: int):
    """1/L(jω) for an equivalent damping β_eq (broadcast), time in samples; plain complex for scalars."""
    if (isinstance(omega, float) or np.ndim(omega) == 0) and (isinstance(beq, float) or np.ndim(beq) == 0):
        w, b = float(omega), float(beq)
        if model != "zoh":
            return cmath.exp(1j * _lead(w, model, delay, pade_order)) * complex(-mu * w * w, w * b)
        c1, c0, p = _zoh_coefficients(b / mu)
        z = cmath.exp(1j * w)
        return z**delay * mu * (z - 1.0) * (z - p) / (c1 * z + c0)
    w = omega if omega is _W_GRID else np.asarray(omega, dtype=float)
    b = np.asarray(beq, dtype=float)
    if model != "zoh":
        return _rotation(w, model, delay, pade_order) * (-mu * w * w + 1j * w * b)
    z = np.exp(1j * w)
    c1, c0, p = _zoh_coefficients(b / mu)
    return z**delay * mu * (z - 1.0) * (z - p) / (c1 * z + c0)


@lru_cache(maxsize=64)
def _pade(t: float, order: int) -> tuple[float, ...]:
    """Denominator of python-control's Padé approximant of e^{−st} (its numerator is den(−s))."""
    import control

    num, den = control.pade(t, order)
    den = np.asarray(den, dtype=float)
    if not np.allclose(np.asarray(num, dtype=float), den * (-1.0) ** np.arange(den.size)[::-1], rtol=1e-12, atol=0):
        raise RuntimeError("control.pade returned a non-diagonal approximant")  # pragma: no cover
    return tuple(float(c) for c in den / den[0])


@dataclass(frozen=True)
class _Loop:
    params: Params
    model: str
    delay: int
    pade_order: int
    df: str = "exact"

    def beq(self, m, w):
        if isinstance(m, float) and isinstance(w, float):
            return self.params.beta + 4.0 * self.params.sigma / (math.pi * m * w)
        return self.params.beta + 4.0 * self.params.sigma / (math.pi * np.asarray(m) * np.asarray(w))

    def inv(self, m, w):
        return _inv_loop(self.params.mu, self.beq(m, w), w, self.model, self.delay, self.pade_order)

    def d(self, m):
        """D(M) (compiled eq. 41 for the exact describing function; M > 0 is the solver's own)."""
        m = np.asarray(m, dtype=float)
        if self.df == "exact":
            return _dfcore.df_array(m.ravel()).reshape(m.shape) if m.ndim else _dfcore.df_value(float(m))
        if self.df == "small":
            return 2.0 / (math.pi * m)
        return np.ones_like(m) if m.ndim else 1.0

    def dprime(self, m):
        m = np.asarray(m, dtype=float)
        if self.df == "exact":
            return _dfcore.df_array(m.ravel(), True).reshape(m.shape) if m.ndim else _dfcore.df_derivative(float(m))
        if self.df == "small":
            return -2.0 / (math.pi * m * m)
        return np.zeros_like(m) if m.ndim else 0.0

    def char(self, m, w):
        return self.inv(m, w) + self.d(m)


# --------------------------------------------------------------- phase curve


def _phase_beta(lp: _Loop, w: np.ndarray) -> np.ndarray:
    """β*(ω): the damping at which V = 0 with U < 0 (NaN where there is none)."""
    mu, d = lp.params.mu, lp.delay
    if lp.model != "zoh":
        # V = 0 ⇔ β_eq = μω tan φ, and then U = −μω²/cos φ < 0 ⇔ cos φ > 0; β_eq >= 0 ⇒ φ mod 2π ∈ [0, π/2)
        th = _lead(w, lp.model, d, lp.pade_order)
        ok = np.mod(th, 2 * math.pi) < math.pi / 2
        with np.errstate(invalid="ignore"):
            return np.where(ok, mu * w * np.tan(th), np.nan)
    if w is _W_GRID:  # β* does not depend on β or σ: a sweep at fixed μ scans the grid once
        return _zoh_phase_beta_grid(mu, d)
    return _zoh_phase_beta(mu, d, w)


@lru_cache(maxsize=16)
def _zoh_phase_beta_grid(mu: float, d: int) -> np.ndarray:
    out = _zoh_phase_beta(mu, d, _W_GRID)
    out.flags.writeable = False
    return out


def _zoh_phase_beta(mu: float, d: int, w: np.ndarray) -> np.ndarray:
    """β*(ω) of the exact ZOH loop: scan β on a log grid, bracket V's crossing with U < 0, bisect (vectorised)."""
    bgrid = np.concatenate([[0.0], np.geomspace(1e-9, 1e5, 400)])
    c = _inv_loop(mu, bgrid[None, :], w[:, None], "zoh", d, 0)
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
                lambda b, wi=wi: _inv_loop(mu, b, wi, "zoh", d, 0).imag,
                float(lo[i]),
                float(hi[i]),
                xtol=1e-300,
                rtol=4 * np.finfo(float).eps,
            )
        return out
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        vm = _inv_loop(mu, mid, w, "zoh", d, 0).imag
        left = np.sign(vm) == np.sign(vlo)
        lo = np.where(left, mid, lo)
        vlo = np.where(left, vm, vlo)
        hi = np.where(left, hi, mid)
    return np.where(has, 0.5 * (lo + hi), np.nan)


def _omega_for_m(lp: _Loop, m: np.ndarray, wa: np.ndarray, wb: np.ndarray) -> np.ndarray:
    """Solve V(M, ω) = 0 for ω in the brackets [wa, wb] (vectorised bisection).

    Where V does not change sign over a bracket (a root at an end, to rounding), the end with the
    smaller |V| is returned: the same rule as :meth:`_PieceOmega.scalar`, so that the scan and the
    refinement of a root evaluate F(M) = D(M) + U(M, ω(M)) as one function.
    """
    va = lp.inv(m, wa).imag
    vb = lp.inv(m, wb).imag
    end = np.where(np.abs(va) <= np.abs(vb), wa, wb)
    no_change = (va == 0.0) | (vb == 0.0) | ((va < 0) == (vb < 0))
    lo, hi = wa.copy(), wb.copy()
    for _ in range(64):
        mid = 0.5 * (lo + hi)
        vm = lp.inv(m, mid).imag
        same = np.sign(vm) == np.sign(va)
        lo = np.where(same, mid, lo)
        va = np.where(same, vm, va)
        hi = np.where(same, hi, mid)
    return np.where(no_change, end, 0.5 * (lo + hi))


# ------------------------------------------------------------------ results
@dataclass(frozen=True)
class LimitCycle:
    """One harmonic-balance solution ξ = M sin ωτ.

    Attributes
    ----------
    amplitude : float
        M in encoder ticks.
    frequency : float
        ω in rad per sample.
    stable : bool
        Loeb criterion (module docstring).
    family : str
        ``"small"`` (M < 1) or ``"large"`` (M >= 1).
    loeb : float
        ∂U/∂M·∂V/∂ω − ∂U/∂ω·∂V/∂M at the root.
    residual : float
        |1 + D(M)·L(jω; M)| at the reported root.
    few_samples : bool
        True when the period is under 8 samples: first-harmonic analysis is
        least trustworthy there (validation issue).
    """

    amplitude: float
    frequency: float
    stable: bool
    family: str
    loeb: float
    residual: float
    few_samples: bool = False

    @property
    def period(self) -> float:
        """Period in samples, 2π/ω."""
        return 2.0 * math.pi / self.frequency

    def as_dict(self) -> dict[str, object]:
        return {
            "amplitude": self.amplitude,
            "frequency": self.frequency,
            "period": self.period,
            "stable": self.stable,
            "family": self.family,
            "loeb": self.loeb,
            "residual": self.residual,
            "few_samples": self.few_samples,
        }


@dataclass(frozen=True)
class LimitCycleResult:
    """All limit cycles of one operating point (an empty tuple is a valid answer).

    Attributes
    ----------
    params : Params
    model, delay, pade_order : loop model (see :func:`dfa.loop.loop_response`)
    describing : str
        ``"exact"`` (eq. 41), or the paper's approximations ``"small"`` (2/(πM)) and ``"unity"`` (1).
    max_amplitude : float
        Largest amplitude searched (ticks). When ``complete``, no root of eq. 36
        lies beyond the last one found (pieces of the phase curve ended, or the
        envelope bound of eq. 41 closed them); when not, the search stopped here.
    cycles : tuple of LimitCycle
        Sorted by amplitude.
    complete : bool
        True only when the search provably found every root (status ``COMPLETE``).
    status : str
        One-line message: ``"ok"`` or ``"incomplete: …"`` (why).
    status_code : SearchStatus
        How the search ended.
    search_bound : float or None
        When complete: the amplitude (ticks) beyond which no root of eq. 36 exists
        (the phase curve's pieces end there, or the eq. 41 envelope excludes
        roots); 0 when the loop's phase condition has no solution at all.
    linear_stable : bool or None
        Whether the linear loop without encoder and Coulomb friction (always the
        exact ZOH loop with the same delay, :func:`dfa.linear.linear_stable`) is
        asymptotically stable; when it is not, amplitudes beyond the largest
        unstable cycle are predicted to grow without bound.
    """

    params: Params
    model: str
    delay: int
    pade_order: int
    describing: str
    max_amplitude: float
    cycles: tuple = field(default_factory=tuple)
    complete: bool = True
    status: str = "ok"
    status_code: SearchStatus | None = None
    linear_stable: bool | None = None
    search_bound: float | None = None

    @property
    def stable_cycles(self) -> tuple:
        return tuple(c for c in self.cycles if c.stable)

    @property
    def unstable_cycles(self) -> tuple:
        return tuple(c for c in self.cycles if not c.stable)

    def as_dict(self) -> dict[str, object]:
        """JSON-ready record (the ``dfa limit-cycles --json`` contract plus extras)."""
        return {
            "cycles": [c.as_dict() for c in self.cycles],
            "mu": self.params.mu,
            "beta": self.params.beta,
            "sigma": self.params.sigma,
            "model": self.model,
            "delay": self.delay,
            "complete": self.complete,
            "max_amplitude": self.max_amplitude,
            "status": self.status,
            "status_code": None if self.status_code is None else self.status_code.value,
            "linear_stable": self.linear_stable,
            "linear_model": "zoh",
            "search_bound": self.search_bound,
        }


# ------------------------------------------------------------------- solver
def _loeb(lp: _Loop, m: float, w: float) -> float:
    hm = 1e-7 * max(m, 1e-3)
    hw = 1e-7 * w
    cm = (lp.inv(m + hm, w) - lp.inv(m - hm, w)) / (2 * hm) + lp.dprime(m)
    cw = (lp.inv(m, w + hw) - lp.inv(m, w - hw)) / (2 * hw)
    return float(cm.real * cw.imag - cw.real * cm.imag)


def _polish(lp: _Loop, m: float, w: float) -> tuple[float, float]:
    """2-D Newton on (U, V) from a bracketed root; keeps the start if Newton wanders."""

    def f(x):
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


def _make_cycle(lp: _Loop, m: float, w: float, polish: bool = True) -> LimitCycle:
    if polish:
        m, w = _polish(lp, m, w)
    inv = lp.inv(m, w)
    return _cycle(m, w, _loeb(lp, m, w), float(abs(1.0 + lp.d(m) / inv)))


def _cycle(m: float, w: float, loeb: float, residual: float) -> LimitCycle:
    return LimitCycle(
        amplitude=float(m),
        frequency=float(w),
        stable=bool(loeb > 0),
        family="small" if m < 1.0 else "large",
        loeb=float(loeb),
        residual=float(residual),
        few_samples=bool(2 * math.pi / w < 8.0),
    )


def _cycles_at_crossing(lp: _Loop, roots: np.ndarray, w: float) -> list[LimitCycle]:
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
    return [_cycle(m, w, lo, r) for m, lo, r in zip(roots.tolist(), loeb.tolist(), resid.tolist(), strict=False)]


def _pieces(lp: _Loop) -> list[tuple[np.ndarray, np.ndarray]]:
    """Monotone pieces (ω, M) of the phase curve, each with an exact M = ∞ end where it reaches β* = β."""
    w = _W_GRID
    bs = _phase_beta(lp, w)
    beta, sigma = lp.params.beta, lp.params.sigma
    excess = bs - beta
    valid = np.isfinite(excess) & (excess > 0)
    out = []
    i = 0
    n = w.size
    while i < n:
        if not valid[i]:
            i += 1
            continue
        j = i
        while j + 1 < n and valid[j + 1]:
            j += 1
        ws = w[i : j + 1]
        ms = 4 * sigma / (math.pi * ws * excess[i : j + 1])
        # add the exact point where β* = β (M = ∞) at either end, when the curve crosses there
        ends = []
        for k_in, k_out in ((i, i - 1), (j, j + 1)):
            if 0 <= k_out < n and np.isfinite(excess[k_out]) and excess[k_out] <= 0:
                f = lambda x: float(_phase_beta(lp, np.array([x]))[0] - beta)
                try:
                    ends.append((k_in, optimize.brentq(f, min(w[k_in], w[k_out]), max(w[k_in], w[k_out]), xtol=1e-15)))
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
        # split into monotone runs of M
        dm = np.sign(np.diff(ms))  # ±inf differences at an M = ∞ end keep their sign
        start = 0
        for k in range(1, dm.size + 1):
            if k == dm.size or dm[k] != dm[start]:
                out.append((ws[start : k + 1], ms[start : k + 1]))
                start = k
        i = j + 1
    return out


#: Most far intervals [n, n + 1] (n > 32) sampled point by point per piece; beyond, the search ends incomplete.
INTERVAL_BUDGET = 20_000


def _m_samples(
    lo: float, hi: float, max_amp: float, lp: _Loop, w_inf: float | None, omega_of
) -> tuple[np.ndarray, tuple | None]:
    """Sample amplitudes on [lo, hi] ∩ (0, max_amp], stopping by the envelope rule.

    Returns (samples, reach, bound): ``reach`` is None when every root of the piece lies
    among the samples' brackets (the piece ends, or the envelope bound
    |D − 1| <= 0.38⌊M⌋^{-3/2} proves there is no root beyond the last sample), else
    (amplitude searched up to, "max_amplitude" or "budget"); ``bound`` is the amplitude
    (ticks) beyond which the piece has no root when ``reach`` is None.
    """
    pts = []
    if lo < 1.0 and hi > _M_FLOOR:
        pts.append(np.geomspace(max(lo, _M_FLOOR), min(1.0, hi), 400))
    reach, bound = None, min(hi, 1.0)
    if hi > 1.0:
        n0 = max(1, int(math.floor(lo)))
        n_end = int(math.ceil(min(hi, max_amp)))
        if lp.df != "exact":
            # the paper's approximations have no integer structure: a geometric grid suffices
            pts.append(np.geomspace(max(lo, 1.0), min(hi, max_amp), 4000))
            return (
                np.unique(np.concatenate(pts)),
                (None if hi <= max_amp else (max_amp, "max_amplitude")),
                min(hi, max_amp),
            )
        near = np.arange(n0, min(n_end, 32) + 1)
        if w_inf is not None:  # −U at the piece's far end: M = ∞, where β_eq = β (at ω = 0 the loop inverse is 0)
            u_far = (
                0.0
                if w_inf == 0.0
                else -float(np.real(_inv_loop(lp.params.mu, lp.params.beta, w_inf, lp.model, lp.delay, lp.pade_order)))
            )
        else:  # a finite far end (hi, its ω)
            u_far = -float(np.real(lp.inv(float(hi), float(omega_of(np.array([hi]))[0]))))
        far, n_stop, budget_hit = _far_intervals(lp, max(n0, 33), n_end, u_far, omega_of, lo, hi)
        if budget_hit:
            reach = (float(n_stop), "budget")
        elif n_stop >= n_end and hi > max_amp:
            reach = (max_amp, "max_amplitude")
        # n + t² resolves the √ at each integer; far out D's excursions are tiny and self-similar: fewer points
        t_near, t_far = np.linspace(0.0, 1.0, 25), np.linspace(0.0, 1.0, 9)
        grid = np.concatenate(
            [(near[:, None] + (t_near * t_near)[None, :]).ravel(), (far[:, None] + (t_far * t_far)[None, :]).ravel()]
        )
        top = min(hi, max_amp, float(n_stop) + 1.0)
        bound = top
        pts.append(grid[(grid >= lo) & (grid <= top)])
    if not pts:
        return np.array([]), reach, bound
    return np.unique(np.concatenate(pts)), reach, bound


def _far_intervals(lp: _Loop, n_from: int, n_end: int, u_far: float, omega_of, lo: float, hi: float):
    """Far intervals [n, n + 1] (n >= n_from > 32) that can hold a root, up to the envelope stop.

    −U = −Re(1/L) along the piece decides both, under the premise that far out −U moves
    monotonically in M along a monotone piece, towards ``u_far`` (its value at the piece's far end;
    at M = ∞, where β_eq = β):
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
    while start <= n_end:
        step = max(1, start // 128)
        edges = np.unique(np.minimum(start + step * np.arange(0, 257), n_end + 1)).astype(float)
        with np.errstate(divide="ignore", invalid="ignore"):
            u = -np.real(lp.inv(np.clip(edges, lo, hi), omega_of(np.clip(edges, lo, hi)))) - 1.0
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


class _PieceOmega:
    """ω(M) on one monotone piece of the phase curve: V(M, ω) = 0 bracketed by the piece's grid."""

    def __init__(self, lp: _Loop, ws: np.ndarray, ms: np.ndarray):
        order = np.argsort(ms)
        self.lp, self.ms, self.ws = lp, ms[order], ws[order]

    def _brackets(self, m):
        k = np.clip(np.searchsorted(self.ms, m), 1, self.ms.size - 1)
        return self.ws[k - 1], self.ws[k]

    def __call__(self, m: np.ndarray) -> np.ndarray:
        wa, wb = self._brackets(m)
        return _omega_for_m(self.lp, m, wa, wb)

    def scalar(self, m: float) -> float:
        """The same for one amplitude, by Brent's method on the scalar loop inverse (same end rule as the vector path)."""
        wa, wb = (float(x) for x in self._brackets(m))
        lp = self.lp

        def v(w):
            return lp.inv(m, w).imag

        va, vb = v(wa), v(wb)
        if va == 0.0 or vb == 0.0 or (va < 0) == (vb < 0):  # a root on a bracket end (rounding): take the smaller |V|
            return wa if abs(va) <= abs(vb) else wb
        return optimize.brentq(v, wa, wb, xtol=1e-300, rtol=4 * np.finfo(float).eps)


class SearchStatus(enum.Enum):
    """How a limit-cycle search ended (:attr:`LimitCycleResult.status_code`)."""

    #: every root of eq. 36 was found: the pieces ended or the envelope bound closed them
    COMPLETE = "complete"
    #: roots may exist beyond the caller's ``max_amplitude``
    MAX_AMPLITUDE = "max_amplitude"
    #: the envelope bound lies beyond the size budget of the automatic search range
    BUDGET = "budget"
    #: a root finder failed (no sign change where the scan saw one, or no convergence)
    NUMERICAL = "numerical"
    #: the time budget ran out before every piece of the phase curve was searched
    TIME_BUDGET = "time_budget"


class LimitCycleSearchWarning(RuntimeWarning):
    """A limit-cycle search ended incomplete because of a numerical failure."""


def _refine(lp: _Loop, omega_of: _PieceOmega, a: float, b: float) -> float | None:
    """Root of F(M) = D(M) + U(M, ω(M)) on [a, b] with the scalar ω(M); None when the ends do not bracket."""

    def g(mm):
        return lp.char(mm, omega_of.scalar(mm)).real

    ga, gb = g(a), g(b)
    if ga == 0.0 or gb == 0.0:
        return a if ga == 0.0 else b
    if (ga < 0) == (gb < 0) or not (math.isfinite(ga) and math.isfinite(gb)):
        return None
    return optimize.brentq(g, a, b, xtol=1e-300, rtol=4 * np.finfo(float).eps)


def _solve_sigma_zero(lp: _Loop, max_amp: float) -> tuple[list[LimitCycle], tuple | None, int, float]:
    """σ = 0: the loop does not depend on M; its phase crossings are the roots of Im(1/L) with Re(1/L) < 0."""
    cycles: list[LimitCycle] = []
    reach, failures, bound = None, 0, 0.0
    w = _W_GRID
    c = lp.inv(1.0, w)
    idx = np.where((np.sign(c.imag[:-1]) != np.sign(c.imag[1:])) & (c.real[:-1] < 0) & (c.real[1:] < 0))[0]
    for i in idx:
        w0 = optimize.brentq(lambda x: float(np.imag(lp.inv(1.0, x))), w[i], w[i + 1], xtol=1e-15)
        g = -float(np.real(lp.inv(1.0, w0)))
        if g <= 0:
            continue
        if lp.df == "exact":
            mm = min(max_amp, float(INTERVAL_BUDGET))  # the same size budget as the σ > 0 scan
            roots, comp, fails = _df_roots(g, mm)
            failures += fails
            if not comp:
                r = (mm, "budget" if mm < max_amp else "max_amplitude")
                reach = r if reach is None else min(reach, r)
            else:
                bound = max(bound, min(mm, envelope_bound(g)), 2.0 / (math.pi * g))
        elif lp.df == "small":
            roots = np.array([2.0 / (math.pi * g)])
            bound = max(bound, float(roots[0]))
        else:
            roots = np.array([])
        # exact D inversion at an exact phase crossing: nothing to polish
        cycles += _cycles_at_crossing(lp, np.asarray(roots, dtype=float), w0)
    return cycles, reach, failures, bound


def _df_roots(g: float, max_amp: float) -> tuple[np.ndarray, bool, int]:
    """quantizer_df_inverse with its failure count (compiled Brent non-convergence)."""
    from .describing import _df_inverse_counted

    return _df_inverse_counted(g, max_amp)


def _solve(lp: _Loop, max_amp: float, deadline: float = math.inf) -> tuple[list[LimitCycle], tuple | None, int, float]:
    """All roots up to ``max_amp``: (cycles, reach, failures, bound); reach is None when the search is complete,
    and then no root exists beyond ``bound`` (ticks). Past ``deadline`` (time.monotonic) the pieces not yet
    searched are skipped: reach is then (smallest amplitude of a skipped piece, "time_budget", pieces done, pieces)."""
    if lp.params.sigma == 0.0:
        return _solve_sigma_zero(lp, max_amp)
    cycles: list[LimitCycle] = []
    reach, failures, bound = None, 0, 0.0
    pieces = [(ws, ms) for ws, ms in _pieces(lp) if np.isfinite(ms).any()]
    for k, (ws, ms) in enumerate(pieces):
        finite = np.isfinite(ms)
        lo = float(np.min(ms[finite]))
        if time.monotonic() > deadline:  # the time budget: no root below the skipped pieces' lowest amplitude is lost
            skipped = min(float(np.min(m[np.isfinite(m)])) for _, m in pieces[k:])
            below = min(skipped, reach[0]) if reach is not None else skipped
            return cycles, (min(below, max_amp), "time_budget", k, len(pieces)), failures, bound
        hi = float(np.max(ms))
        w_inf = float(ws[~finite][0]) if (~finite).any() else None
        omega_of = _PieceOmega(lp, ws, ms)
        try:
            samples, r, b = _m_samples(lo, hi, max_amp, lp, w_inf, omega_of)
            bound = max(bound, b)
            if r is not None:
                reach = r if reach is None else min(reach, r)
            if samples.size < 2:
                continue
            found, fails = _piece_roots(lp, omega_of, samples)
        except (ValueError, RuntimeError, FloatingPointError, ZeroDivisionError, OverflowError):
            found, fails = [], 1
        cycles += found
        failures += fails
    return cycles, reach, failures, bound


def _piece_roots(lp: _Loop, omega_of: _PieceOmega, samples: np.ndarray) -> tuple[list[LimitCycle], int]:
    """Scan F on the samples, bracket its sign changes and refine each (see the module docstring)."""
    wsamp = omega_of(samples)
    dvals = lp.d(samples)
    u = np.real(lp.inv(samples, wsamp))
    f = u + dvals
    # F is a difference of two terms of size ~D: a sign change with both ends at rounding level is noise
    noise = 64 * np.finfo(float).eps * (np.abs(dvals) + np.abs(u))
    real = (np.abs(f[:-1]) > noise[:-1]) | (np.abs(f[1:]) > noise[1:])
    sc = np.where(np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (np.sign(f[:-1]) != np.sign(f[1:])) & real)[0]
    out, failures = [], 0
    for i in sc:
        m0 = _refine(lp, omega_of, float(samples[i]), float(samples[i + 1]))
        if m0 is None:
            failures += 1
            continue
        if m0 <= _M_FLOOR * (1 + 1e-6):
            continue  # on the search floor: the degenerate σ = ½ end of the small family (M → 0, ω → π)
        out.append(_make_cycle(lp, m0, omega_of.scalar(m0)))
    return out, failures


#: Size budget of the automatic search range (ticks): the envelope bound is followed up to here.
AUTO_MAX_AMPLITUDE = 1.0e6

#: Default wall-clock budget of one limit-cycle search (seconds).
DEFAULT_TIME_BUDGET = 10.0


def limit_cycles(
    params: Params,
    *,
    model: str = "half-delay",
    delay: int = 0,
    pade_order: int = 4,
    max_amplitude: float | None = None,
    describing: str = "exact",
    time_budget: float = DEFAULT_TIME_BUDGET,
) -> LimitCycleResult:
    """Every limit cycle (M, ω) of the harmonic balance 1 + D(M)L(jω; M) = 0 (eq. 36).

    Parameters
    ----------
    params : Params
        Dimensionless device (μ > 0, β >= 0, σ >= 0).
    model : {"half-delay", "pade", "zoh"}
        Model of the hold (:func:`dfa.loop.loop_response`); ``"zoh"`` is exact.
    delay : int
        Computational delay in samples.
    pade_order : int
        Order of the Padé approximation for ``model="pade"``.
    max_amplitude : float, optional
        Largest amplitude searched, in ticks. Default (None): up to the
        amplitude beyond which the envelope |D − 1| <= 0.38⌊M⌋^{-3/2} of
        eq. 41 proves that no root exists, for these (μ, β, σ, model, d), within
        a budget of ``AUTO_MAX_AMPLITUDE`` ticks (beyond it the result is
        incomplete, status ``BUDGET``).
    describing : {"exact", "small", "unity"}
        ``"exact"`` uses eq. 41; ``"small"`` and ``"unity"`` replace D by the
        paper's approximations 2/(πM) and 1 (to reproduce eq. 42-45).
    time_budget : float
        Seconds of wall-clock time the search may take (default
        ``DEFAULT_TIME_BUDGET``, 10 s; typical searches take milliseconds).
        When it runs out the pieces of the phase curve not yet searched are
        skipped and the result is incomplete (status ``TIME_BUDGET``), with
        ``max_amplitude`` the amplitude below which no cycle was missed.

    Returns
    -------
    LimitCycleResult
        Cycles sorted by amplitude; an empty tuple when there is none. A
        numerical failure never raises: it gives ``complete=False``, status
        ``NUMERICAL`` and a :class:`LimitCycleSearchWarning`.
    """
    p = _check_params(params)
    m, d, n = _check_model(model, delay, pade_order)
    auto = max_amplitude is None
    amax = (
        AUTO_MAX_AMPLITUDE
        if auto
        else check_positive("max_amplitude", max_amplitude, "give the largest amplitude to search, in ticks")
    )
    df = check_choice("describing", describing, _DF_CHOICES)
    seconds = check_positive("time_budget", time_budget, "give the longest search time in seconds, e.g. 10")
    lp = _Loop(p, m, d, n, df)
    try:
        cycles, reach, failures, bound = _solve(lp, amax, time.monotonic() + seconds)
    except (
        ValueError,
        RuntimeError,
        FloatingPointError,
        ZeroDivisionError,
        OverflowError,
    ):  # pragma: no cover - last resort
        cycles, reach, failures, bound = [], None, 1, math.nan
    cycles = sorted(cycles, key=lambda c: c.amplitude)
    # de-duplicate roots found from two neighbouring brackets
    uniq: list[LimitCycle] = []
    for c in cycles:
        if (
            not uniq
            or abs(c.amplitude - uniq[-1].amplitude) > 1e-9 * c.amplitude
            or abs(c.frequency - uniq[-1].frequency) > 1e-9
        ):
            uniq.append(c)
    if failures:
        code = SearchStatus.NUMERICAL
        status = (
            f"incomplete: {failures} root bracket(s) could not be refined (numerical failure); "
            "cycles may be missing" + (f", and beyond {reach[0]:g} ticks" if reach is not None else "")
        )
        warnings.warn(
            f"limit_cycles(μ = {p.mu:g}, β = {p.beta:g}, σ = {p.sigma:g}, model {m}, delay {d}): {status}",
            LimitCycleSearchWarning,
            stacklevel=2,
        )
    elif reach is not None and reach[1] == "time_budget":
        code = SearchStatus.TIME_BUDGET
        status = (
            f"incomplete: time budget of {seconds:g} s hit after searching {reach[2]} of {reach[3]} pieces of the "
            f"phase curve; no cycle missed below M = {reach[0]:.4g} ticks (raise time_budget)"
        )
    elif reach is not None:
        budget = reach[1] == "budget" or (auto and reach[0] >= amax)
        code = SearchStatus.BUDGET if budget else SearchStatus.MAX_AMPLITUDE
        why = (
            f"searched up to the size budget ({reach[0]:g} ticks) short of the envelope bound"
            if budget
            else f"cycles may exist beyond max_amplitude = {amax:g} ticks"
        )
        status = f"incomplete: {why}"
    else:
        code, status = SearchStatus.COMPLETE, "ok"
    searched = reach[0] if reach is not None else amax
    return LimitCycleResult(
        p,
        m,
        d,
        n,
        df,
        searched,
        tuple(uniq),
        code is SearchStatus.COMPLETE,
        status,
        code,
        _linear_stable(p.mu, p.beta, d),
        bound if code is SearchStatus.COMPLETE else None,
    )


def _linear_stable(mu: float, beta: float, delay: int) -> bool:
    """The linear loop without encoder and Coulomb friction (exact ZOH, d delays) is asymptotically stable."""
    from .linear import linear_stable

    return bool(linear_stable(mu, beta, delay))


# --------------------------------------------------------------- closed forms
def large_cycle_frequency(mu: float) -> float:
    """ω of the paper's large-cycle family: cos(ω/2) = μω² (eq. 44), rad per sample.

    Examples
    --------
    >>> round(large_cycle_frequency(5.0), 5), round(large_cycle_frequency(100.0), 6)
    (0.44175, 0.099938)
    """
    m = check_mu(mu)
    f = lambda w: m * w * w - math.cos(w / 2)
    if f(math.pi) <= 0.0:  # μπ² below cos(π/2) rounded (6e-17): the root π − 2π²μ + … is π to rounding
        return math.pi
    return float(optimize.brentq(f, 0.0, math.pi, xtol=1e-16, rtol=4 * np.finfo(float).eps))


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
        if not f(hi) > 0.0:  # cos(π/2) rounds to 6e-17, not 0: with β/μ above ~1e16 f(π) loses its sign
            raise DFAValueError(
                f"beta = {p.beta!r} with mu = {p.mu!r} is invalid here: β/μ = {p.beta / p.mu:.3g} puts the small "
                "cycle's frequency within rounding of π (eq. 42-43 cannot be solved in floating point); "
                "use a smaller β/μ"
            )
        w = optimize.brentq(f, lo, hi, xtol=1e-16, rtol=4 * np.finfo(float).eps)
    return 2 * math.cos(w / 2) / (math.pi * p.mu * w * w), w


# --------------------------------------------------------- design threshold
@dataclass(frozen=True)
class GrowthThreshold:
    """The describing function's growth band: from the smallest to the largest unstable cycle.

    Where the large family is a single unstable cycle the band is one amplitude
    M_u and the first-harmonic analysis predicts growth above it. Where it is a
    cluster of alternating stable and unstable cycles (β near the linear bound,
    D(M) oscillating about 1, eq. 41) there is no single threshold: below the
    band every predicted cycle is stable, inside it growth depends on the initial
    condition, above the largest unstable cycle growth is predicted (unless a
    larger stable cycle catches it). All of this is a first-harmonic
    approximation (eq. 36), not a proof.

    Attributes
    ----------
    amplitude, frequency, xi_dot : float or None
        Smallest unstable cycle: M_u (ticks), ω (rad per sample) and the speed
        amplitude M_u·ω (ticks per sample), to compare with eq. 12.
    result : LimitCycleResult
        The full solution it came from.
    position, velocity : float or None
        M_u and M_u·ω in physical units (m or rad, m/s or rad/s) when a device was given.
    status : str
    amplitude_high, frequency_high, xi_dot_high, position_high, velocity_high : float or None
        The same for the largest unstable cycle (the top of the band).
    unstable_count : int
        Number of unstable cycles in the band.
    grows_above : bool or None
        True when no stable cycle lies above the largest unstable one, so that
        the first-harmonic analysis predicts growth above the band.
    """

    amplitude: float | None
    frequency: float | None
    xi_dot: float | None
    result: LimitCycleResult
    position: float | None = None
    velocity: float | None = None
    status: str = "ok"
    amplitude_high: float | None = None
    frequency_high: float | None = None
    xi_dot_high: float | None = None
    position_high: float | None = None
    velocity_high: float | None = None
    unstable_count: int = 0
    grows_above: bool | None = None

    @property
    def is_band(self) -> bool:
        """True for a cluster: more than one unstable cycle."""
        return self.unstable_count > 1

    def meaning(self) -> str:
        """What the band means, in words that claim no more than the describing function shows."""
        res = self.result
        if self.amplitude is None:
            return self.status
        lo, hi = self.amplitude, self.amplitude_high
        tail = ""
        if not res.complete:
            tail = f" The search was incomplete ({res.status}): more unstable cycles may lie above {res.max_amplitude:g} ticks."
        if self.grows_above:
            above = f"above {hi:.4g} ticks the first-harmonic analysis predicts growth" + (
                " without bound (the linear loop, exact ZOH model, is unstable)" if res.linear_stable is False else ""
            )
        else:
            nxt = next(c for c in res.cycles if c.amplitude > hi and c.stable)
            above = f"above {hi:.4g} ticks it predicts settling on the stable cycle at M = {nxt.amplitude:.4g} ticks"
        if not self.is_band:
            return f"Describing function (first-harmonic approximation): below M_u = {lo:.4g} ticks no growth is predicted; {above}.{tail}"
        return (
            f"Describing function (first-harmonic approximation): {self.unstable_count} unstable cycles alternate with stable ones "
            f"between {lo:.4g} and {hi:.4g} ticks. Below the band every predicted cycle is stable (no growth predicted); "
            f"inside it, whether an oscillation grows depends on its initial condition; {above}.{tail}"
        )

    def as_dict(self) -> dict[str, object]:
        """JSON-ready record (``dfa limit-cycles --json``, key ``growth_threshold``)."""
        return {
            "amplitude": self.amplitude,
            "frequency": self.frequency,
            "xi_dot": self.xi_dot,
            "position": self.position,
            "velocity": self.velocity,
            "band": {
                "low": {
                    "amplitude": self.amplitude,
                    "frequency": self.frequency,
                    "xi_dot": self.xi_dot,
                    "position": self.position,
                    "velocity": self.velocity,
                },
                "high": {
                    "amplitude": self.amplitude_high,
                    "frequency": self.frequency_high,
                    "xi_dot": self.xi_dot_high,
                    "position": self.position_high,
                    "velocity": self.velocity_high,
                },
            },
            "unstable_count": self.unstable_count,
            "grows_above": self.grows_above,
            "complete": self.result.complete,
            "linear_stable": self.result.linear_stable,
            "linear_model": "zoh",
            "status": self.status,
            "meaning": self.meaning(),
        }


def growth_threshold(params: Params, device: Device | None = None, **kwargs) -> GrowthThreshold:
    """Growth band of the describing function: smallest and largest unstable cycles (beyond the paper).

    Parameters
    ----------
    params : Params
    device : Device, optional
        To express the amplitudes and speeds in physical units.
    **kwargs
        Passed to :func:`limit_cycles` (model, delay, …).
    """
    if device is not None:
        check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    res = limit_cycles(params, **kwargs)
    unstable = res.unstable_cycles
    if not unstable:
        if res.linear_stable is False:
            status = "no unstable cycle predicted" + (
                "" if res.complete else f" up to M = {res.max_amplitude:g} ticks (search {res.status})"
            )
            status += ", but the linear loop (exact ZOH model) is unstable: amplitudes grow without bound"
        else:
            status = "no unstable cycle predicted" + (
                "" if res.complete else f" up to M = {res.max_amplitude:g} ticks (search {res.status})"
            )
        return GrowthThreshold(
            None, None, None, res, status=status, grows_above=None if res.linear_stable is not False else True
        )
    lo, hi = unstable[0], unstable[-1]

    def phys(c):
        if device is None:
            return None, None
        return c.amplitude * device.resolution, device.velocity(c.amplitude * c.frequency)

    plo, vlo = phys(lo)
    phi, vhi = phys(hi)
    grows = not any(c.stable and c.amplitude > hi.amplitude for c in res.cycles)
    return GrowthThreshold(
        lo.amplitude,
        lo.frequency,
        lo.amplitude * lo.frequency,
        res,
        plo,
        vlo,
        "ok",
        hi.amplitude,
        hi.frequency,
        hi.amplitude * hi.frequency,
        phi,
        vhi,
        len(unstable),
        grows,
    )
