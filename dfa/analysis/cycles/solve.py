"""The limit-cycle solver: bracket the roots of F(M) = D(M) + U(M, ω(M)) on every piece and refine them (eq. 36)."""

from __future__ import annotations

import math
import time
import warnings

import numpy as np
from scipy import optimize

from ...checks import check_choice, check_positive, check_type
from ...model.loop import LOOP_FIX, Loop, loop_first
from ...results.cycles import SEARCHED_MU as SEARCHED_MU
from ...results.cycles import LimitCycle, LimitCycleResult, LimitCycleSearchWarning, SearchEvidence, SearchStatus
from ..loop_models import check_model
from . import search
from .characteristic import DF_CHOICES, M_FLOOR, W_GRID, HarmonicLoop
from .controlled import WALL_FIX, linear_stable_of, resolve_wall
from .phase import PieceOmega, phase_pieces
from .search import envelope_bound, m_samples
from .stability import cycles_at_crossing, make_cycle

#: What a failing root finder raises; counted as a numerical failure of the search, never raised.
_NUMERICAL_ERRORS = (ValueError, RuntimeError, FloatingPointError, ZeroDivisionError, OverflowError)


def _refine(lp: HarmonicLoop, omega_of: PieceOmega, a: float, b: float) -> float | None:
    """Root of F(M) = D(M) + U(M, ω(M)) on [a, b] with the scalar ω(M); None when the ends do not bracket."""

    def g(mm: float) -> float:
        return lp.char(mm, omega_of.scalar(mm)).real

    ga, gb = g(a), g(b)
    if ga == 0.0 or gb == 0.0:
        return a if ga == 0.0 else b
    if (ga < 0) == (gb < 0) or not (math.isfinite(ga) and math.isfinite(gb)):
        return None
    return optimize.brentq(g, a, b, xtol=1e-300, rtol=4 * np.finfo(float).eps)


def _solve_sigma_zero(lp: HarmonicLoop, max_amp: float) -> tuple[list[LimitCycle], tuple | None, int, float]:
    """σ = 0: the loop does not depend on M; its phase crossings are the roots of Im(1/L) with Re(1/L) < 0."""
    cycles: list[LimitCycle] = []
    reach, failures, bound = None, 0, 0.0
    w = W_GRID
    c = lp.inv(1.0, w)
    idx = np.where((np.sign(c.imag[:-1]) != np.sign(c.imag[1:])) & (c.real[:-1] < 0) & (c.real[1:] < 0))[0]
    for i in idx:
        w0 = optimize.brentq(lambda x: float(np.imag(lp.inv(1.0, x))), w[i], w[i + 1], xtol=1e-15)
        g = -float(np.real(lp.inv(1.0, w0)))
        if g <= 0:
            continue
        if lp.df == "exact":
            mm = min(max_amp, float(search.INTERVAL_BUDGET))  # the same size budget as the σ > 0 scan
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
        cycles += cycles_at_crossing(lp, np.asarray(roots, dtype=float), w0)
    return cycles, reach, failures, bound


def _df_roots(g: float, max_amp: float) -> tuple[np.ndarray, bool, int]:
    """quantizer_df_inverse with its failure count (compiled Brent non-convergence)."""
    from ..describing import df_inverse_counted

    return df_inverse_counted(g, max_amp)


def _solve(
    lp: HarmonicLoop, max_amp: float, deadline: float = math.inf
) -> tuple[list[LimitCycle], tuple | None, int, float]:
    """All roots up to ``max_amp``: (cycles, reach, failures, bound); reach is None when the search is complete,
    and then no root exists beyond ``bound`` (ticks). Past ``deadline`` (time.monotonic) the pieces not yet
    searched are skipped: reach is then (smallest amplitude of a skipped piece, "time_budget", pieces done, pieces)."""
    if lp.params.sigma == 0.0:
        return _solve_sigma_zero(lp, max_amp)
    cycles: list[LimitCycle] = []
    reach, failures, bound = None, 0, 0.0
    pieces = [(ws, ms) for ws, ms in phase_pieces(lp) if np.isfinite(ms).any()]
    for k, (ws, ms) in enumerate(pieces):
        finite = np.isfinite(ms)
        lo = float(np.min(ms[finite]))
        if time.monotonic() > deadline:  # the time budget: no root below the skipped pieces' lowest amplitude is lost
            skipped = min(float(np.min(m[np.isfinite(m)])) for _, m in pieces[k:])
            below = min(skipped, reach[0]) if reach is not None else skipped
            return cycles, (min(below, max_amp), "time_budget", k, len(pieces)), failures, bound
        hi = float(np.max(ms))
        w_inf = float(ws[~finite][0]) if (~finite).any() else None
        omega_of = PieceOmega(lp, ws, ms)
        try:
            samples, r, b = m_samples(lo, hi, max_amp, lp, w_inf, omega_of)
            bound = max(bound, b)
            if r is not None:
                reach = r if reach is None else min(reach, r)
            if samples.size < 2:
                continue
            found, fails = _piece_roots(lp, omega_of, samples)
        except _NUMERICAL_ERRORS:
            found, fails = [], 1
        cycles += found
        failures += fails
    return cycles, reach, failures, bound


def _piece_roots(lp: HarmonicLoop, omega_of: PieceOmega, samples: np.ndarray) -> tuple[list[LimitCycle], int]:
    """Scan F on the samples, bracket its sign changes and refine each (see the module docstring)."""
    wsamp = omega_of(samples)
    dvals = lp.d(samples)
    u = np.real(lp.inv(samples, wsamp))
    f = u + dvals
    # F is a difference of two terms of size ~D: a sign change with both ends at rounding level is noise
    noise = 64 * np.finfo(float).eps * (np.abs(dvals) + np.abs(u))
    real = (np.abs(f[:-1]) > noise[:-1]) | (np.abs(f[1:]) > noise[1:])
    sc = np.where(np.isfinite(f[:-1]) & np.isfinite(f[1:]) & (np.sign(f[:-1]) != np.sign(f[1:])) & real)[0]
    # ω(M) is NaN only where its root finder failed: a sample that cannot be scanned is a numerical failure
    out, failures = [], int(np.count_nonzero(np.isnan(wsamp)))
    for i in sc:
        m0 = _refine(lp, omega_of, float(samples[i]), float(samples[i + 1]))
        if m0 is None:
            failures += 1
            continue
        if m0 <= M_FLOOR * (1 + 1e-6):
            continue  # on the search floor: the degenerate σ = ½ end of the small family (M → 0, ω → π)
        out.append(make_cycle(lp, m0, omega_of.scalar(m0)))
    return out, failures


#: Size budget of the automatic search range (ticks): the envelope bound is followed up to here.
AUTO_MAX_AMPLITUDE = 1.0e6

#: Default wall-clock budget of one limit-cycle search (seconds).
DEFAULT_TIME_BUDGET = 10.0


@loop_first("params, *, wall", wall_fix=WALL_FIX)
def limit_cycles(
    loop: Loop,
    *,
    model: str = "half-delay",
    pade_order: int = 4,
    max_amplitude: float | None = None,
    describing: str = "exact",
    time_budget: float = DEFAULT_TIME_BUDGET,
) -> LimitCycleResult:
    """Every limit cycle (M, ω) of the harmonic balance 1 + D(M)L(jω; M) = 0 (eq. 36).

    Parameters
    ----------
    loop : Loop
        The loop: its groups (μ > 0, β >= 0, σ >= 0) and its virtual wall's (:class:`dfa.WallParams`: delay d,
        damper β_B, velocity filter ν_c, amplifier lag α), ``Loop.dimensionless(mu, beta, sigma, wall_params)``
        or ``Loop(device, wall)``; D(M) then multiplies the wall's command C(e^{jω}) = 1 + β_B(1 − e^{−jω})F(e^{jω})
        and its delay, and the amplifier lag 1/(jωα + 1) sits between hold and device
        (:func:`dfa.analysis.loop.loop_response`). No wall groups: the paper's spring. A spring with a delay
        (``is_spring``) runs the spring-only code with that delay. ``linear_stable`` is the exact linear loop with
        the wall. The former call ``limit_cycles(params, ..., wall=wall_params)`` still works.
    model : {"half-delay", "pade", "zoh"}
        Model of the hold (:func:`dfa.analysis.loop.loop_response`); ``"zoh"`` is exact.
    pade_order : int
        Order of the Padé approximation for ``model="pade"``.
    max_amplitude : float, optional
        Largest amplitude searched, in ticks. Default (None): up to the
        amplitude beyond which the envelope abs(D − 1) <= 0.38⌊M⌋^{-3/2} of
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

    Raises
    ------
    DFAValueError, DFATypeError
        If ``loop`` is not a :class:`Loop` with groups, the model or ``describing`` is unknown, the delay or
        Padé order is not a valid whole number, or ``max_amplitude`` is not a finite number > 0.

    See Also
    --------
    growth_threshold : The smallest and largest unstable cycles, in words.
    small_cycle_closed_form, large_cycle_closed_form : The paper's closed forms (eq. 42-45).
    nyquist_locus_response : The same balance drawn as a Nyquist plot.
    """
    p, wall = check_type("loop", loop, Loop, LOOP_FIX).groups("limit_cycles")
    w, ctl, d = resolve_wall(wall)
    m, d, n = check_model(model, d, pade_order)
    auto = max_amplitude is None
    amax = (
        AUTO_MAX_AMPLITUDE
        if auto
        else check_positive("max_amplitude", max_amplitude, "give the largest amplitude to search, in ticks")
    )
    df = check_choice("describing", describing, DF_CHOICES)
    seconds = check_positive("time_budget", time_budget, "give the longest search time in seconds, e.g. 10")
    lp = HarmonicLoop(p, m, d, n, df, ctl)
    if not SEARCHED_MU[0] <= p.mu <= SEARCHED_MU[1]:  # a cycle's frequency may lie outside W_GRID: no claim
        cycles: list[LimitCycle] = []
        reach, failures, bound = None, 0, math.nan
        code, evidence = SearchStatus.FREQUENCY_RANGE, SearchEvidence(amax, frequency_range=True)
    else:
        try:
            cycles, reach, failures, bound = _solve(lp, amax, time.monotonic() + seconds)
        except _NUMERICAL_ERRORS:  # pragma: no cover - last resort
            cycles, reach, failures, bound = [], None, 1, math.nan
        code, evidence = _search_status(failures, reach, auto, amax, seconds)
    if code is SearchStatus.NUMERICAL:
        warnings.warn(
            f"limit_cycles(μ = {p.mu:g}, β = {p.beta:g}, σ = {p.sigma:g}, model {m}, delay {d}"
            + (f", wall {ctl.to_dict()}" if ctl is not None else "")
            + f"): {failures} root bracket(s) could not be refined (numerical failure); cycles may be missing",
            LimitCycleSearchWarning,
            stacklevel=2,
        )
    searched = reach[0] if reach is not None else amax
    return LimitCycleResult(
        p,
        m,
        w,
        n,
        df,
        searched,
        _unique(cycles),
        code is SearchStatus.COMPLETE,
        evidence,
        code,
        linear_stable_of(p.mu, p.beta, w),
        bound if code is SearchStatus.COMPLETE else None,
    )


def _unique(cycles: list[LimitCycle]) -> tuple[LimitCycle, ...]:
    """Cycles sorted by amplitude, a root found from two neighbouring brackets kept once."""
    uniq: list[LimitCycle] = []
    for c in sorted(cycles, key=lambda c: c.amplitude):
        if (
            not uniq
            or abs(c.amplitude - uniq[-1].amplitude) > 1e-9 * c.amplitude
            or abs(c.frequency - uniq[-1].frequency) > 1e-9
        ):
            uniq.append(c)
    return tuple(uniq)


def _search_status(
    failures: int, reach: tuple | None, auto: bool, amax: float, seconds: float = math.inf
) -> tuple[SearchStatus, SearchEvidence]:
    """How the search ended, and its numbers as data (:class:`SearchEvidence`; the renderer words them)."""
    reached = float(reach[0]) if reach is not None else None
    if failures:
        return SearchStatus.NUMERICAL, SearchEvidence(amax, reached, failures)
    if reach is None:
        return SearchStatus.COMPLETE, SearchEvidence(amax)
    if reach[1] == "time_budget":
        return SearchStatus.TIME_BUDGET, SearchEvidence(amax, reached, 0, int(reach[2]), int(reach[3]), seconds)
    budget = reach[1] == "budget" or (auto and reach[0] >= amax)
    return (SearchStatus.BUDGET if budget else SearchStatus.MAX_AMPLITUDE), SearchEvidence(amax, reached)
