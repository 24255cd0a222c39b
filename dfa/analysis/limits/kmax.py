"""The design answer: the largest stiffness K for an impact speed V, four ways (issue 14 §1).

For a device, an impact speed V (m/s; rotary rad/s) and a computational delay
of d samples:

``k_criterion``
    guaranteed by the passivity criterion (eq. 11 generalised to the delay,
    :func:`dfa.analysis.limits.closed_form.k_max_criterion`): a proof, for impacts up to V.
``k_linear``
    the exact linear bound of the sampled spring without encoder and Coulomb
    friction (all Jury conditions, :func:`dfa.analysis.limits.closed_form.k_gil`; JSON also
    keeps the name ``k_gil``).
``k_df``
    predicted by the describing function: the largest K (first crossing of
    an ascending scan, then bisection) whose predicted growth speed is at
    least V. The growth speed is the smallest speed amplitude M·ω (ticks per
    sample, eq. 36) over *every* unstable cycle; none with a stable linear
    loop and a complete search means no growth (infinite speed), none with an
    unstable linear loop means growth from any size (zero).
``k_sim``
    found by exact simulation: the largest *confirmed* K. A search first
    finds the largest K at which no impact at the simulated speeds V/n,
    2V/n, …, V, started from ξ0 = 0 and, separately, from rest with the
    spring preloaded to the same energy (section 5,
    :func:`dfa.analysis.simulation.preload_position`), diverges. That K is then
    swept and confirmed (:func:`_confirm`): at the search speeds, a sweep in
    K from K_criterion (without a criterion K > 0: the grid's lowest point)
    up to K in relative steps of ``SWEEP_STEP`` = 0.5 % (coarser only where
    that would take more than ``SWEEP_MAX_POINTS`` = 600 stiffnesses, 150
    with an amplifier lag; the claim gives the step) and a fine zone of 21 stiffnesses in [0.99K, K];
    at ``DENSE_FACTOR`` times as many speeds, 7 stiffnesses in [0.97K, K].
    Where a run diverges (or is undecided) the limit drops to just below
    the lowest such stiffness and is checked again, until every check
    passes; the failures met are reported (``dense_failures``, status
    ``"caveats"``), because safety need not be monotone in K or in the
    speed (the red team of issue 14 found divergent bands at 0.55 K_sim and
    divergence speckled within 0.4 % below it). "Confirmed" names exactly
    what was simulated (``confirmed``): no divergence at those speeds,
    starts and stiffnesses; narrower unsafe bands between the swept
    stiffnesses and other speeds are not excluded (``BELOW_K``).
``k_sim_rest``
    the largest confirmed K at which all those impacts come to rest (no
    chatter, no oscillation), at most ``k_sim``.

The simulated and predicted limits are searched over K: an ascending
geometric grid first, every point evaluated, then bisection between the last
safe and the first failing grid point. Safety need not be monotone in K; a
grid point found safe again above the first failure is reported
(``non_monotone``, ``safe_above``), not hidden. ``undecided`` runs (too short
to tell, :func:`dfa.analysis.simulation.simulate`) never count as safe: where one
limits the answer the result says so. All four are limits for impacts *up to
V* on the simulated speeds; only ``k_criterion`` is a proof.

Theory requires k_criterion <= k_sim (the criterion is sound, issue 12) and
k_sim_rest <= k_sim; every grid point at or below k_criterion is simulated,
and any divergence there is reported in ``counterexamples`` (a criterion bug).

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> r = design_answer(get_device("Impulse Engine").device, 0.2, grid=12, speeds=3)
>>> r.k_criterion < r.k_sim.value, r.k_sim_rest.value <= r.k_sim.value
(True, True)
>>> r.counterexamples
()
"""

from __future__ import annotations

import dataclasses
import math
import os
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from ..._parallel import deal, gather
from ...checks import _fmt, check_choice, check_delay, check_int, check_positive, check_real, check_speed, check_type
from ...errors import DFATypeError, DFAValueError
from ...model.device import Device
from ...model.wall import Wall, WallParams
from ...results.jsonable import explain_nulls
from ..simulation import (
    GROWTH,
    OUTCOMES,
    SETTLE,
    STABLE_AMPLITUDE,
    controller_run_codes,
    default_samples,
    divergence_bound,
    preload_position,
    run_points,
)
from .closed_form import k_abbott_okamura, k_colgate, k_gil, k_max_criterion, k_static, max_passive_velocity

__all__ = ["KSearch", "KMaxAssessment", "KMaxResult", "RunCache", "design_answer", "simulate_points"]

#: Relative width at which the bisection of a searched limit stops.
K_RTOL = 2e-3
#: Longest run (samples) of one design simulation; longer automatic lengths are cut and may be undecided.
DESIGN_MAX_SAMPLES = 1_000_000

#: |ξ| (ticks) past which a design run counts as diverged: at least this, and 100 × the energy amplitude.
DIVERGENCE_BOUND = 1.0e6

SAFE, UNSAFE, UNDECIDED = "safe", "unsafe", "undecided"


def simulate_points(
    points: Sequence[tuple[float, ...]],
    delay: int,
    max_samples: int,
    controller: WallParams | None = None,
    *,
    controllers: Sequence[WallParams | None] | None = None,
):
    """Outcomes of exact simulations at a list of points (μ, β, σ, ξ0, ξ'0), and the samples of each run.

    The run length of each point is :func:`dfa.analysis.simulation.default_samples` (with ``controller``), at most
    ``max_samples``; a run diverges past max(10⁶, 100 (A₀ + 1)) ticks, A₀ = √(2 H_T(0)) the energy amplitude
    of its start. One place for the many simulations of the design answer, run on threads (one per core):
    the compiled kernel releases the GIL, and each outcome depends on its own point only. ``controller``
    (dimensionless, its delay equal to ``delay``; None: the spring) runs every point with that controller;
    ``controllers`` (one per point) instead gives each point its own (the points of a sweep in K).

    Returns
    -------
    (list of str, list of int)
        Outcome names (:data:`dfa.analysis.simulation.OUTCOMES`) and run lengths.
    """
    ctls = [controller] * len(points) if controllers is None else list(controllers)
    if len(ctls) != len(points):
        raise DFAValueError(f"controllers has {len(ctls)} entries for {len(points)} points: give one per point")
    for c in ctls:
        if c is not None and c.delay != delay:
            raise DFAValueError(
                f"delay = {delay!r} is invalid with a controller of delay {c.delay}: the runs need the controller's "
                "own delay; pass delay=controller.delay"
            )
    jobs = []
    for (mu, beta, sigma, xi0, xi_dot0), c in zip(points, ctls, strict=True):
        n = min(default_samples(mu, beta, sigma, xi_dot0, xi0, delay, controller=c), max_samples)
        bound = divergence_bound(xi0, xi_dot0, mu, DIVERGENCE_BOUND)
        jobs.append((mu, beta, sigma, xi_dot0, n, xi0, bound, c))
    workers = min(len(jobs), os.cpu_count() or 1)
    plain = [j[7] is None or j[7].is_spring for j in jobs]  # the spring kernel, as simulate() routes a pure spring
    spring = [i for i, p in enumerate(plain) if p]
    other = [i for i, p in enumerate(plain) if not p]
    outcomes = [""] * len(jobs)
    for idx, outs in (
        (spring, _batched_outcomes([jobs[i] for i in spring], delay, workers)),
        (other, _batched_outcomes([jobs[i] for i in other], delay, workers, controllers=True)),
    ):
        for i, o in zip(idx, outs, strict=True):
            outcomes[i] = o
    return outcomes, [j[4] for j in jobs]


def _batched_outcomes(jobs: list[tuple], delay: int, workers: int, *, controllers: bool = False) -> list[str]:
    """Outcomes of runs through the batch kernels, chunks on threads: the spring's
    (:func:`dfa.analysis.simulation.run_points`), or with ``controllers`` each job's own controller
    (:func:`dfa.analysis.simulation.controller_run_codes`).

    Each run is :func:`dfa.simulate`'s, bit for bit (its own length, bound and tail; the default outcome rules).
    """
    if not jobs:
        return []
    mu, beta, sigma, v0, n, x0, bound = (np.array(c) for c in list(zip(*jobs, strict=True))[:7])
    ctls = [j[7] for j in jobs]
    chunks = deal(len(jobs), 4 * workers)

    def chunk(j: np.ndarray) -> np.ndarray:
        pts = (mu[j], beta[j], sigma[j], x0[j], v0[j], n[j], delay)
        if controllers:
            return controller_run_codes(*pts, bound[j], [ctls[i] for i in j])
        return run_points(*pts, True, bound[j], STABLE_AMPLITUDE, GROWTH, SETTLE)[0]  # simulate()'s rules

    if workers > 1:  # the compiled kernels release the GIL: threads overlap the chunks, results are per run
        with ThreadPoolExecutor(max_workers=workers) as pool:
            codes = gather(chunks, list(pool.map(chunk, chunks)))
    else:
        codes = gather(chunks, [chunk(j) for j in chunks])
    return [OUTCOMES[c] for c in codes]


def _check_bound(name: str, value: object, fix: str) -> float:
    """A real number that is not NaN (a stiffness bound may be +inf: no finite limit)."""
    if isinstance(value, float) and value == math.inf:
        return value
    return check_real(name, value, fix)


@dataclass(frozen=True)
class KSearch:
    """One searched stiffness limit (N/m; rotary N·m/rad) and the evidence behind it.

    Attributes
    ----------
    value : float or None
        The limit; None when undefined (``reason`` says why).
    reason : str or None
        Why ``value`` is None, or a caveat about it (undecided runs); None when plain.
    non_monotone : bool
        True when grid stiffnesses above ``value`` were found safe again.
    safe_above : tuple of float
        Those stiffnesses.
    undecided : tuple of float
        Stiffnesses at which some run was undecided (counted as not safe).
    first_failure : float or None
        The smallest stiffness found not safe.
    evaluations : int
        Stiffnesses evaluated.
    dense_failures : tuple of dict
        Failing or undecided runs the sweep in K and the confirmation met between ``value`` and
        ``searched_value`` (``stiffness``, ``velocity``, ``start``, ``outcome``, ``found_by``: ``"sweep"``,
        ``"confirmation"`` or ``"earlier runs"``): all above ``value``, evidence that safety is not monotone in K; the result's
        status says so.
    searched_value : float or None
        The limit the search found before the sweep and the confirmation (None: not confirmed, e.g. ``k_df``).
    confirmed : str or None
        What ``value`` claims when confirmed by simulation, in words: the dense speed grid, the starts, the
        stiffness band and the sweep below it (:func:`confirmation_text`); None when not confirmed.
    sweep_start, sweep_step : float or None
        The sweep's lowest stiffness and relative step (None: not swept).
    """

    value: float | None
    reason: str | None = None
    non_monotone: bool = False
    safe_above: tuple[float, ...] = ()
    undecided: tuple[float, ...] = ()
    first_failure: float | None = None
    evaluations: int = 0
    dense_failures: tuple[dict, ...] = ()
    searched_value: float | None = None
    confirmed: str | None = None
    sweep_start: float | None = None
    sweep_step: float | None = None

    def __post_init__(self) -> None:
        if self.value is not None:
            check_positive("value", self.value, "a stiffness limit is a finite K > 0, or None with a reason")
        for name in ("reason", "confirmed"):
            text = getattr(self, name)
            if text is not None and not isinstance(text, str):
                raise DFATypeError(f"{name} = {_fmt(text)} has type {type(text).__name__}: it must be text or None")
        for name in ("searched_value", "sweep_start", "sweep_step"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name), "a stiffness (or a relative step) > 0, or None")
        if self.value is None and not self.reason:
            raise DFAValueError("KSearch(value=None) needs a reason: say why the limit is undefined")
        if self.value is not None and not (math.isfinite(self.value) and self.value > 0):
            raise DFAValueError(f"value = {self.value!r} is invalid: a stiffness limit must be finite and > 0")

    def to_dict(self) -> dict[str, object]:
        """JSON-ready record of the search and its evidence (nulls with their reason).

        Returns
        -------
        dict
            The limit, its caveats, the non-monotone evidence and the confirmation.
        """
        out: dict[str, object] = {
            "value": self.value,
            "reason": self.reason,
            "non_monotone": self.non_monotone,
            "safe_above": list(self.safe_above),
            "undecided": list(self.undecided),
            "first_failure": self.first_failure,
            "evaluations": self.evaluations,
            "dense_failures": [dict(f) for f in self.dense_failures],
            "searched_value": self.searched_value,
            "confirmed": self.confirmed,
            "sweep_start": self.sweep_start,
            "sweep_step": self.sweep_step,
        }
        return explain_nulls(out, self.null_reasons())

    def null_reasons(self) -> dict[str, str]:
        """Why each field of :meth:`to_dict` may be null, by key.

        Returns
        -------
        dict of str to str
            Reasons for ``value``, ``reason``, ``first_failure``, ``searched_value`` and ``confirmed``.
        """
        return {
            "value": self.reason or "undefined",
            "reason": "no caveat: the limit stands as stated",
            "first_failure": "no stiffness searched failed",
            "searched_value": "not a simulated search: a prediction, with nothing to confirm",
            "confirmed": (
                "no limit to confirm"
                if self.value is None
                else "not confirmed by simulation: a first-harmonic prediction"
            ),
            "sweep_start": "not swept: a prediction, or no limit",
            "sweep_step": "not swept: a prediction, or no limit",
        }


#: What an undecided simulated verdict means (the reason of a limit it stops).
UNDECIDED_RUNS = "undecided runs: too short to tell"
#: Why an assessed K's predicted growth speed is unknown under the sub-tick caveat.
SUBTICK_UNKNOWN = (
    "unknown: the smallest unstable cycle lies below dfa.analysis.cycles.SUBTICK_LIMIT ticks (the sub-tick caveat), "
    "where simulation has diverged from starts the first harmonic says settle"
)
#: What an undecided describing-function verdict means (:func:`df_verdict`).
UNDECIDED_DF = "undecided predictions: the sub-tick caveat or an incomplete cycle search (dfa.analysis.cycles.caveats)"


def _search(
    judge: Callable[[float], str], grid: np.ndarray, what: str, unit: str, undecided_why: str = UNDECIDED_RUNS
) -> KSearch:
    """Largest K before the first non-safe judgement on an ascending ``grid``, refined by bisection.

    ``undecided_why`` says what an undecided judgement means, for the reason of a limit it stops.
    """
    verdicts = [judge(float(k)) for k in grid]
    undecided = {float(k) for k, v in zip(grid, verdicts, strict=True) if v == UNDECIDED}
    bad = [i for i, v in enumerate(verdicts) if v != SAFE]
    if not bad:
        return KSearch(
            None,
            f"{what} at every stiffness searched, up to {grid[-1]:.5g} {unit}: the limit is above that",
            evaluations=len(grid),
        )
    i = bad[0]
    safe_above = tuple(float(k) for k, v in zip(grid[i + 1 :], verdicts[i + 1 :], strict=True) if v == SAFE)
    if i == 0:
        return KSearch(
            None,
            f"{what} fails already at the smallest stiffness searched, {grid[0]:.5g} {unit} ({verdicts[0]})",
            bool(safe_above),
            safe_above,
            tuple(sorted(undecided)),
            float(grid[0]),
            len(grid),
        )
    lo, hi, n = float(grid[i - 1]), float(grid[i]), len(grid)
    hi_verdict = verdicts[i]
    while hi - lo > K_RTOL * hi:
        mid = math.sqrt(lo * hi)
        v = judge(mid)
        n += 1
        if v == UNDECIDED:
            undecided.add(mid)
        if v == SAFE:
            lo = mid
        else:
            hi, hi_verdict = mid, v
    reason = None
    if hi_verdict == UNDECIDED:
        why, _, means = undecided_why.partition(": ")
        reason = f"limited by {why} at {hi:.5g} {unit}: {means}, counted as not safe"
    return KSearch(lo, reason, bool(safe_above), safe_above, tuple(sorted(undecided)), hi, n)


@dataclass(frozen=True)
class KMaxAssessment:
    """A chosen stiffness K assessed at the impact speed (physical units).

    Attributes
    ----------
    stiffness : float
    source : str
        ``"--stiffness"``/``"given"`` or ``"catalogue"``: where K came from.
    max_passive_velocity : float or None
        Largest speed the criterion proves passive (inf: every speed; None: none).
    growth_speed : float or None
        Smallest predicted growth speed over every unstable cycle (m/s; inf: none; None: unknown).
    unstable_cycles : int
        Unstable cycles predicted (describing function).
    outcomes : dict
        Simulated outcome of an impact at V from ξ0 = 0 (``"impact"``) and from the preload (``"preload"``).
    passive_reason : str or None
        Why ``max_passive_velocity`` is None, when not the spring's K > 2c/Δ (a controller's criterion).
    growth_reason : str or None
        Why ``growth_speed`` is None when the cycle search was complete (the sub-tick caveat).
    """

    stiffness: float
    source: str
    max_passive_velocity: float | None
    growth_speed: float | None
    unstable_cycles: int
    outcomes: dict[str, str] = field(default_factory=dict)
    passive_reason: str | None = None
    growth_reason: str | None = None

    def to_dict(self) -> dict[str, object]:
        def fin(x):
            return None if x is None or math.isinf(x) else x

        mpv, g = self.max_passive_velocity, self.growth_speed
        out: dict[str, object] = {
            "stiffness": self.stiffness,
            "source": self.source,
            "max_passive_velocity": fin(mpv),
            "passive_at_every_speed": mpv is not None and math.isinf(mpv),
            "growth_speed": fin(g),
            "growth_predicted": g is not None and not math.isinf(g),
            "unstable_cycles": self.unstable_cycles,
            "outcomes": dict(self.outcomes),
        }
        why = {
            "max_passive_velocity": (
                (self.passive_reason or "no passivity guarantee even at rest (K > 2c/Δ)")
                if mpv is None
                else "passive at every speed"
            ),
            "growth_speed": (
                (self.growth_reason or "unknown: the cycle search was incomplete and found no unstable cycle")
                if g is None
                else "no growth predicted (no unstable cycle, stable linear loop)"
            ),
        }
        return explain_nulls(out, why)


class Growth(NamedTuple):
    """The describing function's growth prediction at one operating point (:func:`_growth_xi_dot`).

    ``xi_dot``: smallest speed amplitude M·ω (ticks/sample) over every unstable cycle; inf: no growth predicted
    (no unstable cycle, stable linear loop, complete search); 0: growth from any size (no unstable cycle, unstable
    linear loop); None: unknown (incomplete search, none found). ``unstable``: number of unstable cycles. ``subtick``: the
    smallest unstable cycle lies below :data:`dfa.analysis.cycles.SUBTICK_LIMIT` ticks (the sub-tick caveat of
    :mod:`dfa.analysis.cycles.caveats`), so that "no growth below ``xi_dot``" is not a prediction to rely on.
    """

    xi_dot: float | None
    unstable: int
    subtick: bool


def _growth_xi_dot(mu: float, beta: float, sigma: float, delay: int, model: str, controller: Any = None) -> Growth:
    """The describing function's growth prediction (:class:`Growth`) at (μ, β, σ), delay and hold model.

    ``controller`` (a WallParams whose delay is ``delay``, or None for the spring) is passed to
    :func:`dfa.analysis.cycles.limit_cycles`.
    """
    from ...model.device import Params
    from ..cycles import limit_cycles

    if controller is None:
        res = limit_cycles(Params(mu, beta, sigma), model=model, delay=delay)
    else:
        res = limit_cycles(Params(mu, beta, sigma), model=model, controller=controller)
    unstable = res.unstable_cycles
    if unstable:
        return Growth(min(c.amplitude * c.frequency for c in unstable), len(unstable), res.caveat is not None)
    if res.linear_stable is False:
        return Growth(0.0, 0, False)
    return Growth(math.inf if res.complete else None, 0, False)


def df_verdict(growth: Growth, xi_dot: float) -> str:
    """The describing function's verdict on impacts up to ``xi_dot`` (ticks/sample): SAFE, UNSAFE or UNDECIDED.

    UNSAFE when growth is predicted from below ``xi_dot``; SAFE when it is predicted only from above, unless the
    sub-tick caveat holds (then UNDECIDED: simulation has diverged from starts the first harmonic says settle,
    spring and controller alike, :mod:`dfa.analysis.cycles.caveats`); UNDECIDED when the prediction is unknown.

    Examples
    --------
    >>> df_verdict(Growth(0.5, 1, False), 0.4), df_verdict(Growth(0.5, 1, True), 0.4), df_verdict(Growth(0.5, 1, True), 0.6)
    ('safe', 'undecided', 'unsafe')
    """
    if growth.xi_dot is None:
        return UNDECIDED
    if growth.xi_dot < xi_dot:
        return UNSAFE
    return UNDECIDED if growth.subtick else SAFE


#: Outcomes that fail each simulated limit; "undecided" neither passes nor fails (it is counted as not safe).
FAILING = {"unstable": frozenset({"unstable"}), "rest": frozenset({"oscillating", "unstable", "chatter"})}


class RunCache:
    """Outcomes of design runs by their inputs, and growth predictions by (μ, β, σ, d, model, controller).

    One cache shared by the searches of a design analysis (:func:`design_answer`, the confirmation and
    :func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart`) simulates each run (μ, β, σ, ξ0, ξ'0, d, run cap,
    dimensionless controller) at most once. Results do not depend on it: each search still counts every run it rests on.

    Examples
    --------
    >>> c = RunCache()
    >>> c.simulate([(100.0, 0.3, 1.5, 0.0, 2.0)] * 2, 0, 10**6)[0], c.simulated
    (['rest', 'rest'], 1)
    """

    def __init__(self) -> None:
        self.runs: dict[tuple, tuple[str, int]] = {}
        self.growth: dict[tuple, Growth] = {}
        self.simulated = 0

    def simulate(
        self,
        points: Sequence[tuple[float, float, float, float, float]],
        delay: int,
        max_samples: int,
        controller: WallParams | None = None,
        *,
        controllers: Sequence[WallParams | None] | None = None,
    ):
        """Outcomes and run lengths of ``points`` (as :func:`simulate_points`), simulating only the new ones.

        Parameters
        ----------
        points : sequence of (μ, β, σ, ξ0, ξ'0)
            Dimensionless runs (ξ0 in ticks, ξ'0 in ticks per sample).
        delay : int
            Computational delay d in samples.
        max_samples : int
            Longest run in samples.
        controller : WallParams, optional
            The dimensionless controller of every point (part of each run's key); None: the spring.
        controllers : sequence of WallParams or None, optional
            One controller per point instead of ``controller`` (the points of a sweep in K).

        Returns
        -------
        (list of str, list of int)
            Outcome names and run lengths, one per point.
        """
        ctls = [controller] * len(points) if controllers is None else list(controllers)
        keys = [(tuple(float(x) for x in pt), delay, max_samples, c) for pt, c in zip(points, ctls, strict=True)]
        todo = list(dict.fromkeys(k for k in keys if k not in self.runs))
        if todo:
            outs, lengths = simulate_points([k[0] for k in todo], delay, max_samples, controllers=[k[3] for k in todo])
            self.simulated += len(todo)
            self.runs.update({k: (o, n) for k, o, n in zip(todo, outs, lengths, strict=True)})
        return [self.runs[k][0] for k in keys], [self.runs[k][1] for k in keys]


class _Evidence:
    """Simulations and predictions of one design search, per stiffness (dimensionless inside), through a cache.

    With a physical ``controller`` (B, f_c, f_bw and its delay, which must be ``delay``, held fixed) each
    stiffness K runs with its own groups ``replace(controller, stiffness=K).params(T)`` (β_B = B/(KT) falls
    as K grows), in the simulations and in the growth prediction; a controller whose groups are the pure
    spring's (B = 0, no filter, no lag) is the spring, bit for bit. The preload start (spring energy equal
    to the impact's kinetic energy, at rest) is kept with a controller: the damper's velocity estimate
    and the filter start at 0, the delayed commands and the amplifier's force at the spring's force at ξ0
    (:mod:`dfa.core.wall_kernel`), the steady state of a device held still at ξ0, a legitimate start of the
    controlled loop.
    """

    def __init__(
        self,
        dev: Device,
        speeds: np.ndarray,
        delay: int,
        max_samples: int,
        model: str,
        cache: RunCache | None = None,
        controller: Wall | None = None,
    ):
        self.dev, self.delay, self.max_samples, self.model = dev, delay, max_samples, model
        self.controller = controller
        self.cache = RunCache() if cache is None else cache
        self.xi_dots = [dev.xi_dot(float(v)) for v in speeds]
        self.sims: dict[float, list[tuple[float, str, str]]] = {}
        self.growth: dict[float, Growth] = {}
        self.runs = 0
        self.longest = 0

    def params(self, k: float) -> tuple[Any, WallParams | None]:
        """The device's groups (μ, β, σ) and the controller's (None: the spring) at stiffness ``k``.

        Raises DFAValueError when a group is not representable at ``k``.
        """
        p = self.dev.params(k)
        if self.controller is None:
            return p, None
        c = dataclasses.replace(self.controller, stiffness=k).params(self.dev.period)
        return p, (None if c.is_spring else c)

    def outcomes(self, k: float) -> list[tuple[float, str, str]]:
        """(ξ'0, start, outcome) of every impact simulated at stiffness ``k``."""
        self.prefetch([k])
        return self.sims[k]

    def prefetch(self, ks: Sequence[float]) -> None:
        """Simulate the impacts of every stiffness of ``ks`` not yet seen, in one threaded batch (the cache's)."""
        pts: list[tuple[float, float, float, float, float]] = []
        ctls: list[WallParams | None] = []
        tags: list[tuple[float, float, str]] = []
        for k in dict.fromkeys(float(x) for x in ks):
            if k in self.sims:
                continue
            try:
                p, c = self.params(k)
            except DFAValueError:  # μ, β or σ not representable at this K: nothing can be decided there
                self.sims[k] = [(xd, start, "undecided") for xd in self.xi_dots for start in ("impact", "preload")]
                continue
            for xd in self.xi_dots:
                pts += [(p.mu, p.beta, p.sigma, 0.0, xd), (p.mu, p.beta, p.sigma, preload_position(p.mu, xd), 0.0)]
                ctls += [c, c]
                tags += [(k, xd, "impact"), (k, xd, "preload")]
        if not pts:
            return
        outs, lengths = self.cache.simulate(pts, self.delay, self.max_samples, controllers=ctls)
        self.runs += len(pts)  # every run this evidence rests on, simulated here or earlier
        self.longest = max(self.longest, *lengths)
        for (k, xd, start), o in zip(tags, outs, strict=True):
            self.sims.setdefault(k, []).append((xd, start, o))

    def judge(self, k: float, limit: str) -> str:
        """SAFE, UNSAFE (an outcome in ``FAILING[limit]``) or UNDECIDED for every impact at stiffness ``k``."""
        outs = {o for _, _, o in self.outcomes(k)}
        if outs & FAILING[limit]:
            return UNSAFE
        return UNDECIDED if "undecided" in outs else SAFE

    def no_divergence(self, k: float) -> str:
        return self.judge(k, "unstable")

    def rest(self, k: float) -> str:
        return self.judge(k, "rest")

    def growth_xi_dot(self, k: float) -> Growth:
        if k not in self.growth:
            try:
                p, c = self.params(k)
            except DFAValueError:  # not representable at this K
                self.growth[k] = Growth(None, 0, False)
                return self.growth[k]
            key = (p.mu, p.beta, p.sigma, self.delay, self.model) + (() if c is None else (c,))
            if key not in self.cache.growth:
                self.cache.growth[key] = _growth_xi_dot(p.mu, p.beta, p.sigma, self.delay, self.model, c)
            self.growth[k] = self.cache.growth[key]
        return self.growth[k]

    def predicted(self, k: float, xi_dot: float) -> str:
        return df_verdict(self.growth_xi_dot(k), xi_dot)

    def counterexamples(self, k_criterion: float | None) -> tuple[dict[str, object], ...]:
        """Divergent impacts at stiffnesses the criterion proves passive (there must be none; None: no criterion)."""
        out: list[dict[str, object]] = []
        if k_criterion is None:  # no sound criterion (amplifier lag): nothing to contradict
            return ()
        for k, rows in sorted(self.sims.items()):
            for xd, start, o in rows:
                if k <= k_criterion and o == "unstable":
                    out.append({"stiffness": k, "velocity": self.dev.velocity(xd), "start": start, "outcome": o})
        return tuple(out)


#: The confirmation of a simulated limit K uses this many times the searched speeds ...
DENSE_FACTOR = 4
#: ... at the stiffnesses of a band below K: DENSE_RUNGS geometric rungs spanning a relative width DENSE_BAND ...
DENSE_RUNGS = 5
DENSE_BAND = 0.03
#: ... and at these fractions below K (where a search's bisection ended).
DENSE_FINE = (0.001, 0.003)


def _band(k: float) -> list[float]:
    """The confirmation band below K, descending: K, K (1 - f) for f in DENSE_FINE, then the rungs
    K (1 - DENSE_BAND)^(i / (DENSE_RUNGS - 1)), i = 1 … DENSE_RUNGS - 1."""
    rungs = [k * (1.0 - DENSE_BAND) ** (i / (DENSE_RUNGS - 1)) for i in range(1, DENSE_RUNGS)]
    return [k] + [k * (1.0 - f) for f in DENSE_FINE] + rungs


def _failures(ev: _Evidence, k: float, bad: str, found_by: str) -> list[dict[str, Any]]:
    """Runs of ``ev`` at ``k`` that fail limit ``bad`` or are undecided (neither counts as safe)."""
    return [
        {"stiffness": k, "velocity": ev.dev.velocity(xd), "start": start, "outcome": str(o), "found_by": found_by}
        for xd, start, o in ev.outcomes(k)
        if o in FAILING[bad] or o == "undecided"
    ]


#: The sweep in K below a simulated limit: relative step between its stiffnesses (target) ...
SWEEP_STEP = 0.005
#: ... and at most this many stiffnesses per sweep (a wider range takes a coarser step, and says so); with an
#: amplifier lag, whose runs cost about 18 times the spring's per sample (reports/benchmarks.md), at most
#: SWEEP_MAX_POINTS_LAG, so that a design answer stays within its 30 s goal ...
SWEEP_MAX_POINTS = 600
SWEEP_MAX_POINTS_LAG = 150
#: ... and, just below K, a fine zone of FINE_POINTS stiffnesses K (1 - FINE_STEP)^j, j = 0 … FINE_POINTS - 1
#: (unsafe K can lie speckled within a few tenths of a percent below a limit, red team of issue 14) ...
FINE_STEP = 0.0005
FINE_POINTS = 21
#: ... lowering the candidate at most this many times (each time just below the lowest failure found).
MAX_LOWERINGS = 200


class Sweep(NamedTuple):
    """A sweep in K: ascending stiffnesses ``start`` (1 + ``step``)^j, j = 0, 1, …, at the search speeds.

    ``start`` is K_criterion (``from_criterion``) or, without a criterion K > 0, the search grid's lowest point.
    """

    start: float
    step: float
    from_criterion: bool
    max_points: int = SWEEP_MAX_POINTS

    def points(self, top: float) -> list[float]:
        """The sweep's stiffnesses up to ``top``, ascending (every limit swept from ``start`` shares them)."""
        n = math.floor(math.log(top / self.start) / math.log1p(self.step) + 1e-9) if top >= self.start else -1
        return [self.start * (1.0 + self.step) ** j for j in range(n + 1)]


def _sweep_for(k_lo: float, from_criterion: bool, k_hi: float, max_points: int = SWEEP_MAX_POINTS) -> Sweep:
    """The sweep from ``k_lo`` up to ``k_hi``: :data:`SWEEP_STEP`, coarser when that takes over ``max_points``."""
    need = math.log(max(k_hi, k_lo) / k_lo) / max_points
    return Sweep(k_lo, max(SWEEP_STEP, math.expm1(need)), from_criterion, max_points)


def _max_points(ev: _Evidence) -> int:
    """:data:`SWEEP_MAX_POINTS`, or :data:`SWEEP_MAX_POINTS_LAG` for a controller with an amplifier lag."""
    lag = ev.controller is not None and ev.controller.amplifier_bandwidth is not None
    return SWEEP_MAX_POINTS_LAG if lag else SWEEP_MAX_POINTS


def _fine(k: float) -> list[float]:
    """The fine zone just below K, descending: K (1 - FINE_STEP)^j, j = 0 … FINE_POINTS - 1."""
    return [k * (1.0 - FINE_STEP) ** j for j in range(FINE_POINTS)]


#: What a simulated limit does not claim: unsafe stiffnesses between the simulated ones, or other speeds.
BELOW_K = (
    "narrower unsafe bands between the swept stiffnesses, and unsafe speeds between those simulated, are not "
    "excluded: stability need not be monotone in K"
)


def sweep_text(sweep: Sweep, ev: _Evidence, k: float) -> str:
    """What the sweep below a limit K simulated, in words (device units): fine zone, range, step, speeds."""
    u = ev.dev.units
    vs = [ev.dev.velocity(x) for x in ev.xi_dots]
    n = len(sweep.points(k))
    where = "K_criterion" if sweep.from_criterion else "the search grid's lowest stiffness"
    fine_lo = (1.0 - FINE_STEP) ** (FINE_POINTS - 1)
    coarse = "" if sweep.step <= SWEEP_STEP * (1 + 1e-9) else f" (coarser than {100 * SWEEP_STEP:g} %: at most "
    coarse += f"{sweep.max_points} stiffnesses)" if coarse else ""
    below = (
        f"a sweep of {n} stiffnesses from {where} = {sweep.start:.5g} {u['stiffness']} up to K in relative steps "
        f"of {100 * sweep.step:.3g} %{coarse}"
        if n
        else f"no sweep below, K lies below its start, {where} = {sweep.start:.5g} {u['stiffness']}"
    )
    return (
        f"at the {len(vs)} search speeds in [{min(vs):.4g}, {max(vs):.4g}] {u['velocity']} (both starts), "
        f"{FINE_POINTS} stiffnesses in [{fine_lo:.4g}K, K] (steps of {100 * FINE_STEP:g} %) and {below}"
    )


def confirmation_text(dense: _Evidence, bad: str, swept: str = "") -> str:
    """What a confirmed limit K claims, in words (device units): the dense band, the sweep below it (``swept``)."""
    u = dense.dev.units
    vs = [dense.dev.velocity(x) for x in dense.xi_dots]
    what = "no divergence" if bad == "unstable" else "every run at rest"
    return (
        f"{what}, none undecided, at {len(vs)} speeds in [{min(vs):.4g}, {max(vs):.4g}] {u['velocity']} "
        f"(from ξ0 = 0 and from the preload) and {DENSE_RUNGS + len(DENSE_FINE)} stiffnesses in [{1 - DENSE_BAND:g}K, K]"
        f"{'; ' + swept if swept else ''}; {BELOW_K}"
    )


def _lowest_failures(k: float, ev: _Evidence, dense: _Evidence, bad: str, sweep: Sweep) -> list[dict[str, Any]]:
    """The failing runs of the first check at K that fails (empty: none fails): the sweep up to K and the fine zone
    at the search speeds (``ev``), the confirmation band at the dense speeds, then every run already simulated at
    or below K (``"earlier runs"``: the searches', another limit's checks); each new check is one threaded batch."""
    checks = (
        (ev, sweep.points(k), "sweep"),
        (ev, _fine(k), "sweep"),
        (dense, _band(k), "confirmation"),
        (ev, [kk for kk in ev.sims if kk <= k], "earlier runs"),
        (dense, [kk for kk in dense.sims if kk <= k], "earlier runs"),
    )
    for e, ks, by in checks:
        e.prefetch(ks)  # the cache's runs are free
        fails = [f for kk in ks for f in _failures(e, kk, bad, by)]
        if fails:
            return fails
    return []


def _settle(
    k0: float, ev: _Evidence, dense: _Evidence, bad: str, sweep: Sweep, floor: float
) -> tuple[float | None, list[dict[str, Any]], str, Sweep]:
    """The largest K at or below ``k0`` that every check of :func:`_lowest_failures` passes, lowering the candidate
    to just below (1 - FINE_STEP) the lowest failure found each time; the failures met, why None, and the sweep
    (restarted from ``floor``, the search grid's lowest point, when the candidate falls below its start)."""
    k = k0
    fails: list[dict[str, Any]] = []
    for _ in range(MAX_LOWERINGS):
        if k < sweep.start * (1.0 - 1e-12):
            if sweep.start <= floor:
                return None, fails, f"the failures reach the search grid's lowest stiffness, {floor:.5g}", sweep
            sweep = _sweep_for(floor, False, k, sweep.max_points)
        f = _lowest_failures(k, ev, dense, bad, sweep)
        if not f:
            return k, fails, "", sweep
        fails += f
        k = min(float(r["stiffness"]) for r in f) * (1.0 - FINE_STEP)
    return None, fails, f"not settled after {MAX_LOWERINGS} lowerings, down to {k:.5g}", sweep


def _lowered_note(fails: list[dict[str, Any]], searched: float, dev: Device) -> str:
    """Why a limit was lowered from the searched one: the lowest failure found, by what, and the highest."""
    u, uv = dev.units["stiffness"], dev.units["velocity"]
    w = max(fails, key=lambda r: float(r["stiffness"]))
    lo = min(fails, key=lambda r: float(r["stiffness"]))
    return (
        f"lowered from the searched {searched:.5g} {u}: the {lo['found_by']} found {lo['outcome']} at K = "
        f"{lo['stiffness']:.5g} {u} ({lo['velocity']:.3g} {uv}, {lo['start']} start)"
        + ("" if w["stiffness"] == lo["stiffness"] else f", failures up to K = {w['stiffness']:.5g} {u}")
        + f" ({len(fails)} failing or undecided runs in all, none at or below the limit)"
    )


def _confirm(
    found: KSearch, ev: _Evidence, dense: _Evidence, bad: str, sweep: Sweep, floor: float, top: float | None = None
) -> KSearch:
    """The largest *swept and confirmed* K at or below a searched limit (and at or below ``top``).

    The search saw only its own speeds and grid, and assumed safety monotone in K between its points. A
    candidate K is kept when, from both starts, no run fails ``bad`` ("unstable": diverges; "rest": does not
    come to rest) and none is undecided: at the search speeds of ``ev``, at every stiffness of a sweep in K
    (:class:`Sweep`: relative steps of :data:`SWEEP_STEP`, coarser only past :data:`SWEEP_MAX_POINTS`
    stiffnesses) from K_criterion (else the grid's lowest point) up to K, and at the fine zone just below K
    (:func:`_fine`); and at :data:`DENSE_FACTOR` times as many speeds at the stiffnesses of :func:`_band`
    spanning [(1 - DENSE_BAND) K, K]. Otherwise the candidate drops to just below the lowest failure found
    (:func:`_settle`; below K_criterion the sweep restarts from ``floor``, the search grid's lowest point); a
    run already simulated at or below K (the searches', another limit's) counts too. Every failure met (all
    above the result) is kept in ``dense_failures`` (``found_by``: ``"sweep"``, ``"confirmation"`` or
    ``"earlier runs"``) and said in ``reason``. A finite set of speeds and stiffnesses is simulated: this is
    evidence at those points (the claim says which), not a proof for all speeds or every K.
    """
    if found.value is None:
        return found
    k0 = found.value if top is None else min(found.value, top)
    value, fails, why, sweep = _settle(k0, ev, dense, bad, sweep, floor)
    u = dense.dev.units["stiffness"]
    fields: dict[str, Any] = dict(searched_value=found.value, dense_failures=tuple(fails))
    fields.update(sweep_start=sweep.start, sweep_step=sweep.step)
    if value is None:
        claim = confirmation_text(dense, bad, sweep_text(sweep, ev, k0))
        note = f"; {_lowered_note(fails, found.value, dense.dev)}" if fails else ""
        return dataclasses.replace(
            found, value=None, reason=f"no stiffness confirmed: {why} {u}{note} ({claim})", **fields
        )
    reason = found.reason
    if fails:
        note = _lowered_note(fails, found.value, dense.dev)
        reason = note if not reason else f"{reason}; {note}"
    if k0 < found.value:
        note = f"capped at K_sim = {k0:.5g} {u}: coming to rest implies no divergence"
        reason = note if not reason else f"{reason}; {note}"
    claim = confirmation_text(dense, bad, sweep_text(sweep, ev, value))
    return dataclasses.replace(found, value=value, reason=reason, confirmed=claim, **fields)


def _search_grid(k_criterion: float, top: float, grid: int) -> np.ndarray:
    """Ascending stiffness grid from k_criterion/2 to ``top``, holding k_criterion itself."""
    lo = 0.5 * k_criterion if k_criterion > 0 else top * 1e-4
    pts = np.geomspace(lo, top, grid)
    if k_criterion > 0:
        pts = np.unique(np.append(pts, k_criterion))
    return pts


class _SearchedLimits:
    """What :class:`KMaxResult` and :class:`dfa.analysis.limits.wall_kmax.ControllerStiffnessLimits` share: the three
    searched limits, the sentence on their evidence and their JSON fields (one implementation)."""

    device: Device
    k_df: KSearch
    k_sim: KSearch
    k_sim_rest: KSearch
    speeds: tuple[float, ...]
    simulations: int
    longest_run: int
    max_samples: int
    df_model: str
    k_range: tuple[float, float]
    counterexamples: tuple[dict[str, object], ...]
    assessment: KMaxAssessment | None

    @property
    def searches(self) -> dict[str, KSearch]:
        """The three searched limits by name: ``k_df``, ``k_sim`` and ``k_sim_rest``."""
        return {"k_df": self.k_df, "k_sim": self.k_sim, "k_sim_rest": self.k_sim_rest}

    def evidence_text(self) -> str:
        """How the simulated limits were found, in one sentence.

        Returns
        -------
        str
            The number of runs, the impact speeds and stiffness range (device units), run lengths and hold model.
        """
        return evidence_text(
            self.device, self.speeds, self.k_range, self.simulations, self.longest_run, self.max_samples, self.df_model
        )

    def _search_fields(self) -> tuple[dict[str, object], dict[str, str]]:
        """The limits with their ``*_reason`` and why each may be null."""
        out: dict[str, object] = {}
        why: dict[str, str] = {}
        for name, s in self.searches.items():
            out[name] = s.value
            out[f"{name}_reason"] = s.reason
            why[name] = s.reason or "undefined"
            why[f"{name}_reason"] = "no caveat: the limit stands as stated"
        return out, why

    def _evidence_fields(self, starts: list[str], **extra: object) -> dict[str, object]:
        """The evidence, searches, counterexamples and assessment of the JSON record."""
        evidence: dict[str, object] = {"speeds": list(self.speeds), "starts": starts, "simulations": self.simulations}
        evidence.update(extra)
        evidence.update(
            longest_run_samples=self.longest_run,
            max_samples=self.max_samples,
            df_model=self.df_model,
            k_range=list(self.k_range),
            text=self.evidence_text(),
        )
        return {
            "evidence": evidence,
            "searches": {k: s.to_dict() for k, s in self.searches.items()},
            "counterexamples": [dict(c) for c in self.counterexamples],
            "assessment": None if self.assessment is None else self.assessment.to_dict(),
        }


@dataclass(frozen=True)
class KMaxResult(_SearchedLimits):
    """K_max four ways for a device at an impact speed (module docstring); stiffnesses in N/m (N·m/rad).

    Attributes
    ----------
    device : Device
    velocity : float
        Impact speed V (m/s; rotary rad/s).
    xi_dot : float
        V in encoder ticks per sample.
    delay : int
        Computational delay d in samples.
    k_criterion, k_linear, k_static, k_colgate, k_abbott_okamura : float
        Closed-form limits (eq. 8, 9, 11 and the exact linear bound).
    k_df, k_sim, k_sim_rest : KSearch
        Searched limits with their evidence.
    speeds : tuple of float
        Impact speeds simulated (m/s; rad/s), each from ξ0 = 0 and from the preload.
    simulations : int
        Exact simulations run.
    longest_run : int
        Longest run in samples (each run: :func:`dfa.analysis.simulation.default_samples`, at most ``max_samples``).
    max_samples : int
    df_model : str
        Hold model of the describing-function search (:func:`dfa.analysis.cycles.limit_cycles`).
    k_range : tuple of float
        Smallest and largest stiffness of the search grid.
    counterexamples : tuple of dict
        Divergent impacts at or below ``k_criterion`` (empty unless the criterion is wrong).
    assessment : KMaxAssessment or None
        The chosen stiffness, if one was given.
    status : str
        ``"ok"``; ``"caveats"`` (non-monotone or undecided-limited searches); ``"counterexample"``.
    """

    device: Device
    velocity: float
    xi_dot: float
    delay: int
    k_criterion: float
    k_linear: float
    k_static: float
    k_colgate: float
    k_abbott_okamura: float
    k_df: KSearch
    k_sim: KSearch
    k_sim_rest: KSearch
    speeds: tuple[float, ...]
    simulations: int
    longest_run: int
    max_samples: int
    df_model: str
    k_range: tuple[float, float]
    counterexamples: tuple[dict[str, object], ...] = ()
    assessment: KMaxAssessment | None = None
    status: str = "ok"

    def __post_init__(self) -> None:
        fix = "KMaxResult is built by dfa.design_answer; call that instead"
        check_type("device", self.device, Device, fix)
        for name in ("velocity", "xi_dot", "k_criterion", "k_linear", "k_static", "k_colgate", "k_abbott_okamura"):
            _check_bound(name, getattr(self, name), fix)
        check_delay(self.delay)
        for name in ("k_df", "k_sim", "k_sim_rest"):
            check_type(name, getattr(self, name), KSearch, fix)
        for name in ("simulations", "longest_run", "max_samples"):
            check_int(name, getattr(self, name), 0, fix)
        for name, n in (("speeds", None), ("k_range", 2)):
            value = getattr(self, name)
            if not isinstance(value, tuple) or (n is not None and len(value) != n):
                raise DFATypeError(
                    f"{name} = {_fmt(value)} has type {type(value).__name__}: it must be a tuple of "
                    f"{n or 'any number of'} speeds or stiffnesses; {fix}"
                )
            for i, v in enumerate(value):
                check_real(f"{name}[{i}]", v, fix)
        check_choice("df_model", self.df_model, ("half-delay", "zoh", "pade"))
        if not isinstance(self.counterexamples, tuple):
            raise DFATypeError(f"counterexamples = {_fmt(self.counterexamples)} must be a tuple of dicts; {fix}")
        if self.assessment is not None:
            check_type("assessment", self.assessment, KMaxAssessment, fix)
        if not isinstance(self.status, str):
            raise DFATypeError(f"status = {_fmt(self.status)} must be ok, caveats or counterexample; {fix}")
        if self.status not in ("ok", "caveats", "counterexample"):
            raise DFAValueError(f"status = {self.status!r} is invalid: it must be ok, caveats or counterexample")

    def to_dict(self) -> dict[str, object]:
        """JSON-ready record: the four limits (null with a reason), the bounds, the evidence.

        Returns
        -------
        dict
            Strict-JSON data: the limits, bounds, evidence, assessment, status and its message.
        """
        out: dict[str, object] = {
            "device": self.device.name,
            "velocity": self.velocity,
            "xi_dot": self.xi_dot,
            "delay": self.delay,
            "k_criterion": self.k_criterion,
            "k_linear": self.k_linear,
            "k_gil": self.k_linear,
            "k_static": self.k_static,
            "k_colgate": self.k_colgate,
            "k_abbott_okamura": self.k_abbott_okamura,
        }
        fields, why = self._search_fields()
        out.update(fields)
        why["assessment"] = "no stiffness given to assess (and no catalogue K)"
        out.update(
            stiffness_unit=self.device.units["stiffness"],
            velocity_unit=self.device.units["velocity"],
            design_status=self.status,
            **self._evidence_fields(["impact from ξ0 = 0", "spring preload of equal energy"]),
        )
        return explain_nulls(out, why)


def _passive_speed(dev: Device, k: float, delay: int, controller: Wall | None) -> tuple[float | None, str | None]:
    """Largest speed the criterion proves passive at K (inf: every speed; None: none), and why None.

    The spring: eq. 11-12 (:func:`dfa.analysis.limits.closed_form.max_passive_velocity`). A controller without amplifier
    lag: the extended criterion (:mod:`dfa.analysis.criterion`), passive up to (σ − σ₀)/(β₀ − β) ticks per
    sample when σ >= σ₀. With a lag there is no sound criterion (None and the reason).
    """
    if controller is None:
        return max_passive_velocity(dev, k, delay), None
    if controller.amplifier_bandwidth is not None:
        return None, "no sound passivity criterion with an amplifier lag"
    from ..criterion import device_criterion

    r = device_criterion(dev, controller.with_stiffness(k), 0.0)
    if r.sigma < r.sigma0:
        return None, f"no passivity guarantee even at rest (σ = {r.sigma:.4g} < σ₀ = {r.sigma0:.4g})"
    return (math.inf if r.critical_velocity is None else r.critical_velocity), None


def evidence_text(
    device: Device,
    speeds: Sequence[float],
    k_range: tuple[float, float],
    simulations: int,
    longest: int,
    max_samples: int,
    df_model: str,
) -> str:
    """How searched limits were found, in one sentence (device units): runs, speeds, stiffnesses, run lengths.

    Returns
    -------
    str
        The sentence :meth:`KMaxResult.evidence_text` prints.
    """
    u = device.units["velocity"]
    sp = ", ".join(f"{v:.3g}" for v in speeds)
    return (
        f"{simulations} exact simulations: impacts at {sp} {u}, each from ξ0 = 0 and from the "
        f"energy preload, over stiffnesses {k_range[0]:.4g} to {k_range[1]:.4g} "
        f"{device.units['stiffness']}; runs from the loop's time scales, longest {longest} samples "
        f"(cap {max_samples}); describing function: {df_model} hold model, every unstable cycle"
    )


def _assess(ev: _Evidence, k: float, source: str, velocity: float, delay: int) -> KMaxAssessment:
    """The chosen stiffness at the impact speed: criterion, predicted cycles, simulated outcomes (``ev``'s controller)."""
    dev = ev.dev
    g, count, subtick = ev.growth_xi_dot(k)
    g = None if subtick else g  # the sub-tick caveat: the growth speed is not a threshold to rely on
    g_why = SUBTICK_UNKNOWN if subtick else None
    p, c = ev.params(k)
    xd = dev.xi_dot(velocity)
    outs, _ = ev.cache.simulate(
        [(p.mu, p.beta, p.sigma, 0.0, xd), (p.mu, p.beta, p.sigma, preload_position(p.mu, xd), 0.0)],
        delay,
        ev.max_samples,
        c,
    )
    ev.runs += 2
    gs = None if g is None else (math.inf if math.isinf(g) else dev.velocity(g))
    mpv, why = _passive_speed(dev, k, delay, ev.controller)
    return KMaxAssessment(k, source, mpv, gs, count, {"impact": outs[0], "preload": outs[1]}, why, g_why)


def _none(reason: str) -> KSearch:
    return KSearch(None, reason)


def design_answer(
    device: Device,
    velocity: float,
    delay: int = 0,
    *,
    stiffness: float | None = None,
    stiffness_source: str = "given",
    speeds: int = 6,
    grid: int = 16,
    max_samples: int = DESIGN_MAX_SAMPLES,
    df_model: str = "half-delay",
    cache: RunCache | None = None,
) -> KMaxResult:
    """The largest stiffness for impacts up to ``velocity``, four ways (module docstring).

    Parameters
    ----------
    device : Device
        The physical device.
    velocity : float
        Impact speed V in m/s (rotary: rad/s), > 0 (a negative is refused, not flipped).
    delay : int, optional
        Computational delay d in samples.
    stiffness : float, optional
        A stiffness K (N/m; N·m/rad) to assess as well; ``stiffness_source`` says where it came from.
    stiffness_source : str, optional
        Where ``stiffness`` came from, for the assessment's wording: ``"given"`` (default) or
        ``"catalogue"``.
    speeds : int, optional
        Number of impact speeds simulated: V/speeds, 2V/speeds, …, V (default 6), each with two starts.
    grid : int, optional
        Points of the geometric stiffness grid (default 16), from K_criterion/2 to 8 × the largest
        closed-form bound; bisection refines each limit to a relative 2·10⁻³.
    max_samples : int, optional
        Longest run, in samples (default 10⁶); longer automatic lengths are cut and may be undecided.
    df_model : {"half-delay", "zoh", "pade"}, optional
        Hold model of the describing function (default ``"half-delay"``; ``"zoh"`` is exact but ~10× slower).
    cache : RunCache, optional
        Runs and predictions already computed (shared with :func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart` by
        :func:`dfa.analysis.design.design_analysis`); a fresh one when None. The result does not depend on it.

    Returns
    -------
    KMaxResult
        K_max by the criterion, the describing function and simulation (to rest and without
        instability), the classic bounds, the evidence and, with ``stiffness``, its assessment.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, the speed is not a finite number > 0, or another
        input is out of range.

    See Also
    --------
    stiffness_limits : The closed-form limits alone (fast).
    stiffness_speed_chart : The same limits over a range of speeds.
    design_analysis : Everything the design report states.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    v = check_speed("velocity", velocity, zero=False)
    d = check_delay(delay)
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one impact speed")
    n_grid = check_int("grid", grid, minimum=2, fix="give at least 2 stiffness grid points")
    cap = check_int("max_samples", max_samples, minimum=1000, fix="allow runs of at least 1000 samples")
    model = check_choice("df_model", df_model, ("half-delay", "zoh", "pade"))
    k_given = None if stiffness is None else check_positive("stiffness", stiffness, "give K in N/m")
    vs = v * np.arange(1, n_speeds + 1) / n_speeds
    if cache is not None:
        check_type("cache", cache, RunCache, "pass a dfa.analysis.limits.kmax.RunCache, or None")
    cache = RunCache() if cache is None else cache
    ev = _Evidence(dev, vs, d, cap, model, cache)
    kc, kl = float(k_max_criterion(dev, v, d)), k_gil(dev, delay=d)
    top = 8.0 * max(k_static(dev), k_colgate(dev, d), kl, kc)
    k_df, k_sim, k_rest, k_range, ce, status = searched_limits(ev, v, n_speeds, kc, kc, top, n_grid)
    return KMaxResult(
        dev,
        v,
        dev.xi_dot(v),
        d,
        kc,
        kl,
        k_static(dev),
        k_colgate(dev, d),
        k_abbott_okamura(dev, d),
        k_df,
        k_sim,
        k_rest,
        tuple(float(s) for s in vs),
        ev.runs,
        ev.longest,
        cap,
        model,
        k_range,
        ce,
        None if k_given is None else _assess(ev, k_given, stiffness_source, v, d),
        status,
    )


def searched_limits(ev: _Evidence, v: float, n_speeds: int, kc: float | None, k_ref: float, top: float, n_grid: int):
    """K_df, K_sim, K_sim_rest searched and confirmed with ``ev`` (the one implementation, spring or controller).

    The grid runs from ``k_ref``/2 (``k_ref`` itself included) to ``top``; the simulated limits are swept in K
    from ``kc`` (None or 0: from the grid's lowest point) at the search speeds and confirmed at
    :data:`DENSE_FACTOR` × ``n_speeds`` speeds with ``ev``'s controller (:func:`_confirm`); divergent runs at or
    below ``kc`` are counterexamples (``kc`` None: no criterion, no check). ``ev.runs`` counts every run, sweep
    and confirmation included.

    Returns
    -------
    (KSearch, KSearch, KSearch, (float, float), tuple of dict, str)
        k_df, k_sim, k_sim_rest, the grid's range, the counterexamples and the status
        (``"ok"``, ``"caveats"`` or ``"counterexample"``).
    """
    k_df, k_sim, k_rest, k_range = _three_searches(ev, v, k_ref, top, n_grid)
    dense_vs = v * np.arange(1, DENSE_FACTOR * n_speeds + 1) / (DENSE_FACTOR * n_speeds)
    dense = _Evidence(ev.dev, dense_vs, ev.delay, ev.max_samples, ev.model, ev.cache, ev.controller)
    found = [s.value for s in (k_sim, k_rest) if s.value is not None]
    if found:  # one sweep from K_criterion (else the grid's lowest point): k_sim_rest's points are k_sim's
        k_lo, by_criterion = (kc, True) if kc else (k_range[0], False)
        sweep = _sweep_for(k_lo, by_criterion, max(found), _max_points(ev))
        ev.prefetch(sweep.points(max(found)))  # one threaded batch for both limits
        k_sim = _confirm(k_sim, ev, dense, "unstable", sweep, k_range[0])
        k_rest = _confirm(k_rest, ev, dense, "rest", sweep, k_range[0], k_sim.value)
    ev.runs += dense.runs
    ce = ev.counterexamples(kc) + dense.counterexamples(kc)
    caveat = any(s.non_monotone or s.undecided or s.dense_failures for s in (k_df, k_sim, k_rest))
    return k_df, k_sim, k_rest, k_range, ce, "counterexample" if ce else ("caveats" if caveat else "ok")


def _three_searches(ev: _Evidence, v: float, k_ref: float, top: float, n_grid: int):
    """K_df, K_sim, K_sim_rest over one geometric grid from k_ref/2 (K_criterion/2 for the spring) to ``top``."""
    dev = ev.dev
    if not (top > 0 and math.isfinite(top)):
        why = "no search range: the device has neither viscous nor Coulomb friction (b = c = 0)"
        if top > 0:
            why = "no search range: no finite closed-form bound to search up to"
        return _none(why), _none(why), _none(why), (0.0, 0.0)
    unit = dev.units["stiffness"]
    pts = _search_grid(k_ref, top, n_grid)
    xd = dev.xi_dot(v)
    k_df = _search(lambda k: ev.predicted(k, xd), pts, "predicted growth speed >= V", unit, UNDECIDED_DF)
    k_sim = _search(ev.no_divergence, pts, "no divergence", unit)
    k_rest = _search(ev.rest, pts, "rest after every impact", unit)
    return k_df, k_sim, k_rest, (float(pts[0]), float(pts[-1]))
