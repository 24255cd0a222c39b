"""The runs and predictions behind every searched stiffness limit: what each K gives, simulated or predicted once.

A K_max search (:mod:`dfa.analysis.limits.kmax`), the stiffness–speed chart and the Z-width ask, at many
stiffnesses K, two questions of the same wall (:class:`dfa.model.wall.Wall`, its elements held fixed in
physical units while K varies):

- how do impacts end in exact simulation (:func:`simulate_points`: runs on threads through the compiled
  batch kernels, each run :func:`dfa.simulate`'s bit for bit), from ξ0 = 0 and from rest with the spring
  preloaded to the same energy (section 5, :func:`dfa.analysis.simulation.preload_position`);
- what growth does the describing function predict (:func:`growth_at`, :func:`df_verdict`).

:class:`RunCache` keeps every run and prediction by its dimensionless inputs; :class:`Evidence` asks it per K
and counts what each search rests on.

Examples
--------
>>> c = RunCache()
>>> c.simulate([(100.0, 0.3, 1.5, 0.0, 2.0)] * 2, WallParams(), 10**6)[0], c.simulated
(['rest', 'rest'], 1)
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from typing import Any, NamedTuple

import numpy as np

from ..._parallel import NO_BAR, deal, gather, run_in_order
from ...errors import DFAValueError
from ...model.device import Device, Params
from ...model.elements import Coverage
from ...model.loop import device_groups
from ...model.wall import Wall, WallParams
from ...progress import advance
from ...results.status import Fails, SimulationOutcome
from ..simulation import (
    GROWTH,
    OUTCOMES,
    SETTLE,
    STABLE_AMPLITUDE,
    check_run_inputs,
    run_bounds,
    run_points,
    wall_run_codes,
)

__all__ = [
    "SAFE",
    "UNSAFE",
    "UNDECIDED",
    "FAILING",
    "DIVERGENCE_BOUND",
    "STARTS",
    "ONE_SIDED_STARTS",
    "starts_of",
    "start_points",
    "Growth",
    "growth_at",
    "df_verdict",
    "simulate_points",
    "decide_undecided",
    "judge_outcomes",
    "EXTEND_STEP",
    "EXTEND_CAP",
    "RunCache",
    "Evidence",
]

SAFE, UNSAFE, UNDECIDED = "safe", "unsafe", "undecided"

#: Outcomes that fail each simulated limit, read from the outcomes' declaration (:attr:`SimulationOutcome.fails`):
#: "undecided" neither passes nor fails (it is counted as not safe). "saturated" (a large motion held by the
#: actuator's force limit: the unlimited wall oscillates or diverges) and "end_stop" (the device ran out of its
#: travel: the wall did not hold it) fail both.
FAILING = {
    "unstable": SimulationOutcome.failing(Fails.NO_DIVERGENCE),
    "rest": SimulationOutcome.failing(Fails.REST),
}

#: |ξ| (ticks) past which a design run counts as diverged: at least this, and 100 × the energy amplitude.
DIVERGENCE_BOUND = 1.0e6

#: The two starts of every simulated impact: from ξ0 = 0 at the speed, and from rest with the spring preloaded
#: to the same energy (the damper's velocity estimate and filter at 0, the delayed commands and the amplifier's
#: force at the spring's force at ξ0: the steady state of a device held still there).
STARTS = ("impact", "preload")
#: The one start of a one-sided wall's impact: the approach from free space at the speed
#: (:func:`dfa.analysis.maps.map_start`, the map's rule).
ONE_SIDED_STARTS = ("approach",)


def starts_of(wall: WallParams | Wall) -> tuple[str, ...]:
    """The starts of every simulated impact with ``wall``: :data:`STARTS`, or a one-sided wall's approach.

    Examples
    --------
    >>> starts_of(WallParams())
    ('impact', 'preload')
    """
    return STARTS if wall.covers(Coverage.SURFACE_START) else ONE_SIDED_STARTS


def start_points(mu: float, beta: float, sigma: float, xi_dot: float, wall: WallParams) -> list[tuple[float, ...]]:
    """The runs (μ, β, σ, ξ0, ξ'0) of an impact at ``xi_dot``, one per start of :func:`starts_of`.

    Examples
    --------
    >>> start_points(100.0, 0.3, 1.5, 2.0, WallParams())[0]
    (100.0, 0.3, 1.5, 0.0, 2.0)
    """
    from ..maps import map_start  # the one start rule: the impact, its preload, a one-sided wall's approach

    preloads = (False, True) if wall.covers(Coverage.SURFACE_START) else (False,)
    return [(mu, beta, sigma, *map_start(mu, xi_dot, p, wall)) for p in preloads]


#: An undecided design run (too short to tell) is run again this many times longer, until it is decided ...
EXTEND_STEP = 4
#: ... or reaches this many times its own length (:func:`decide_undecided`); only then is it counted undecided.
EXTEND_CAP = 16


def decide_undecided(
    codes: Sequence[Any] | np.ndarray,
    lengths: Sequence[int] | np.ndarray,
    undecided: Any,
    rerun: Callable[[np.ndarray, np.ndarray], Any],
    extend: Sequence[bool] | np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Run the undecided runs again, :data:`EXTEND_STEP` times longer each time, up to :data:`EXTEND_CAP` times.

    A run too short to tell (slowly decaying sub-tick chatter, a slow envelope) is not counted as not safe at
    its first length: it is simulated again, longer, until its outcome is decided or its length reaches
    :data:`EXTEND_CAP` times its first (each run then is :func:`dfa.simulate`'s with ``samples`` that length).

    Parameters
    ----------
    codes : sequence
        Outcome of each run (names or kernel codes).
    lengths : sequence of int
        Length of each run, samples.
    undecided : object
        The value of ``codes`` that means undecided.
    rerun : callable
        ``rerun(indices, lengths)`` gives the outcomes of those runs at those lengths.
    extend : sequence of bool, optional
        Which runs may be run again (default all): a run already cut to the search's longest run is not, as
        the loop's time scales exceed what is simulated and longer runs would only take time; it stays undecided
        (not safe).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        The outcomes and the lengths they were decided at (the cap where still undecided).

    Examples
    --------
    >>> decide_undecided(["undecided", "rest"], [100, 100], "undecided",
    ...                  lambda i, n: ["chatter" if m >= 800 else "undecided" for m in n])[0].tolist()
    ['chatter', 'rest']
    """
    out = np.array(codes, dtype=object)
    ns = np.array(lengths, dtype=np.int64)
    allowed = np.ones(len(ns), bool) if extend is None else np.asarray(extend, bool)
    caps = ns * np.where(allowed, EXTEND_CAP, 1)
    while True:
        idx = np.flatnonzero((out == undecided) & (ns < caps))
        if idx.size == 0:
            return out, ns
        ns[idx] = np.minimum(ns[idx] * EXTEND_STEP, caps[idx])
        out[idx] = np.array(rerun(idx, ns[idx]), dtype=object)


def simulate_points(
    points: Sequence[tuple[float, ...]], walls: Sequence[WallParams], max_samples: int
) -> tuple[list[str], list[int]]:
    """Outcomes of exact simulations at a list of points (μ, β, σ, ξ0, ξ'0), each with its wall's groups.

    The run length of each point is :func:`dfa.analysis.simulation.default_samples` (with its wall), at most
    ``max_samples``; an undecided run is run again longer (:func:`decide_undecided`, up to :data:`EXTEND_CAP`
    times) unless it was cut to ``max_samples`` (then it stays undecided: not safe); a run diverges past
    max(10⁶, 100 (A₀ + 1)) ticks, A₀ = √(2 H_T(0)) the energy amplitude of
    its start. Runs go on threads (one per core) through the compiled batch kernels, which release the GIL;
    each outcome depends on its own point only. A wall the spring's kernel runs (``is_spring``) takes it.

    Returns
    -------
    (list of str, list of int)
        Outcome names (:data:`dfa.analysis.simulation.OUTCOMES`) and run lengths.
    """
    if len(walls) != len(points):
        raise DFAValueError(f"walls has {len(walls)} entries for {len(points)} points: give one per point")
    jobs, extend = [], []
    if points:  # every point checked as simulate checks it, in one numpy pass (not point by point: their cost)
        mu_, beta_, sigma_, xi0_, xi_dot0_ = zip(*points, strict=True)
        check_run_inputs(mu_, beta_, sigma_, xi_dot0_, xi0_)
    for (mu, beta, sigma, xi0, xi_dot0), w in zip(points, walls, strict=True):
        natural, bound = run_bounds(mu, beta, sigma, xi_dot0, xi0, w, DIVERGENCE_BOUND)  # checked groups
        jobs.append((mu, beta, sigma, xi_dot0, min(natural, max_samples), xi0, bound, w))
        extend.append(natural <= max_samples)  # cut to max_samples already: longer runs would only take time

    def rerun(idx: np.ndarray, ns: np.ndarray) -> list[str]:
        return _outcomes([jobs[i][:4] + (int(n),) + jobs[i][5:] for i, n in zip(idx, ns, strict=True)])

    outs, lengths = decide_undecided(_outcomes(jobs), [j[4] for j in jobs], "undecided", rerun, extend)
    return [str(o) for o in outs], [int(n) for n in lengths]


#: Runs per chunk of a batch of wall runs (:func:`_batched_outcomes`): each chunk is one compiled call (about 30 µs
#: of Python beside 6 µs a run) that keeps two of its runs in flight (:mod:`dfa.core.wall_pair`): 16 pair more of
#: the long chatters than 4 (82 % against 47 % of their samples on the passivity controller's confirmations), while a
#: batch's threads still finish within about one chunk of each other (``reports/benchmarks.md``).
WALL_CHUNK = 16


def _outcomes(jobs: list[tuple]) -> list[str]:
    """Outcome names of runs (μ, β, σ, ξ'0, n, ξ0, bound, wall): the spring kernel, then the wall kernel, by delay."""
    workers = min(len(jobs), os.cpu_count() or 1)
    outcomes = [""] * len(jobs)
    for spring in (True, False):  # the spring kernel, as simulate() routes a wall it runs, then the wall kernel
        idx = [i for i, j in enumerate(jobs) if j[7].covers(Coverage.CLOSED_FORM) == spring]
        by_delay: dict[int, list[int]] = {}
        for i in idx:
            by_delay.setdefault(jobs[i][7].delay, []).append(i)
        for d, ids in by_delay.items():
            for i, o in zip(ids, _batched_outcomes([jobs[i] for i in ids], d, workers, spring), strict=True):
                outcomes[i] = o
    return outcomes


def _batched_outcomes(jobs: list[tuple], delay: int, workers: int, spring: bool) -> list[str]:
    """Outcomes of runs of one delay through the batch kernels, chunks on threads: the spring's
    (:func:`dfa.analysis.simulation.run_points`), or each job's own wall (:func:`~dfa.analysis.simulation.wall_run_codes`).

    Each run is :func:`dfa.simulate`'s, bit for bit (its own length, bound and tail; the default outcome rules).
    """
    if not jobs:
        return []
    mu, beta, sigma, v0, n, x0, bound = (np.array(c) for c in list(zip(*jobs, strict=True))[:7])
    walls = [j[7] for j in jobs]
    # the wall's runs in chunks: their cost is known only once run (a chattering run integrates every sample, its
    # neighbour skips its periods), and the pool hands the next chunk to whichever thread is free
    chunks = deal(len(jobs), 4 * workers if spring else max(4 * workers, -(-len(jobs) // WALL_CHUNK)))

    def chunk(j: np.ndarray) -> np.ndarray:
        pts = (mu[j], beta[j], sigma[j], x0[j], v0[j], n[j])
        if not spring:
            return wall_run_codes(*pts, bound[j], [walls[i] for i in j])  # each wall's table holds the delay
        return run_points(*pts, walls[j[0]], True, bound[j], STABLE_AMPLITUDE, GROWTH, SETTLE)[0]  # simulate()'s rules

    # the compiled kernels release the GIL: threads overlap the chunks, results are per run, in order (dfa._parallel)
    codes = gather(chunks, run_in_order(chunk, [(j,) for j in chunks], [1] * len(chunks), workers, "threads", NO_BAR))
    return [OUTCOMES[c] for c in codes]


def judge_outcomes(outcomes: set[str] | frozenset[str], limit: str) -> str:
    """SAFE, UNSAFE (an outcome in ``FAILING[limit]``) or UNDECIDED (one undecided, none failing) for a set of runs.

    Examples
    --------
    >>> judge_outcomes({"rest", "chatter"}, "unstable"), judge_outcomes({"left", "rest"}, "rest")
    ('safe', 'safe')
    """
    if outcomes & FAILING[limit]:
        return UNSAFE
    return UNDECIDED if "undecided" in outcomes else SAFE


class Growth(NamedTuple):
    """The describing function's growth prediction at one operating point (:func:`growth_at`).

    ``xi_dot``: smallest speed amplitude M·ω (ticks/sample) over every unstable cycle; inf: no growth predicted
    (no unstable cycle, stable linear loop, complete search); 0: growth from any size (no unstable cycle, unstable
    linear loop, complete search); a positive lower bound when the search found none below its reach (the
    unstable cycle of an unstable linear loop lies beyond it); None: unknown (a search that failed).
    ``unstable``: number of unstable cycles. ``lower_bound``: ``xi_dot`` only bounds the growth speed from below.
    ``subtick``: the smallest unstable cycle lies below
    :data:`dfa.analysis.cycles.SUBTICK_LIMIT` ticks (the sub-tick caveat of :mod:`dfa.results.caveats`),
    so that "no growth below ``xi_dot``" is not a prediction to rely on. ``not_searched``: μ lies outside
    :data:`dfa.analysis.cycles.SEARCHED_MU`, where the cycle search claims nothing (``xi_dot`` None).
    """

    xi_dot: float | None
    unstable: int
    subtick: bool
    lower_bound: bool = False
    not_searched: bool = False


def growth_at(params: Params, wall: WallParams, model: str) -> Growth:
    """The describing function's growth prediction (:class:`Growth`) at (μ, β, σ) with the wall's groups.

    Without an unstable cycle: a complete search with an unstable linear loop predicts growth from any size
    (0), with a stable one none (inf). A search that stopped at its size budget (no cycle missed below
    ``max_amplitude``) bounds the growth speed from below by the smallest speed amplitude a cycle beyond that
    reach can have, M_reach·ω_min over the searched frequencies; the growth speed is otherwise unknown (None).
    """
    from ...model.loop import Loop
    from ...results.status import SearchStatus
    from ..cycles import limit_cycles
    from ..cycles.characteristic import W_GRID

    res = limit_cycles(Loop.dimensionless(params.mu, params.beta, params.sigma, wall), model=model)
    unstable = res.unstable_cycles
    if unstable:
        return Growth(min(c.amplitude * c.frequency for c in unstable), len(unstable), res.caveat is not None)
    if res.complete:
        return Growth(math.inf if res.linear_stable else 0.0, 0, False)
    if res.status is SearchStatus.BUDGET:  # no cycle missed below max_amplitude: any growth starts beyond it
        return Growth(res.max_amplitude * float(W_GRID[0]), 0, False, lower_bound=True)
    return Growth(None, 0, False, not_searched=res.status is SearchStatus.FREQUENCY_RANGE)


def df_verdict(growth: Growth, xi_dot: float) -> str:
    """The describing function's verdict on impacts up to ``xi_dot`` (ticks/sample): SAFE, UNSAFE or UNDECIDED.

    UNSAFE when growth is predicted from below ``xi_dot``; SAFE when it is predicted only from above, unless the
    sub-tick caveat holds (then UNDECIDED: simulation has diverged from starts the first harmonic says settle,
    spring and wall alike, :mod:`dfa.results.caveats`); UNDECIDED when the prediction is unknown, or
    only bounded from below by less than ``xi_dot`` (a search stopped at its size budget).

    Examples
    --------
    >>> df_verdict(Growth(0.5, 1, False), 0.4), df_verdict(Growth(0.5, 1, True), 0.4), df_verdict(Growth(0.5, 1, True), 0.6)
    ('safe', 'undecided', 'unsafe')
    """
    if growth.xi_dot is None:
        return UNDECIDED
    if growth.xi_dot < xi_dot:
        return UNDECIDED if growth.lower_bound else UNSAFE  # a bound below V says nothing about V
    return UNDECIDED if growth.subtick else SAFE


class RunCache:
    """Outcomes of design runs by their inputs, and growth predictions by (μ, β, σ, wall, model).

    One cache shared by the searches of a design analysis (:func:`dfa.analysis.limits.kmax.design_answer`, the
    confirmation, :func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart`) simulates each run
    (μ, β, σ, ξ0, ξ'0, wall's groups, run cap) at most once. Results do not depend on it: each search still
    counts every run it rests on.
    """

    def __init__(self) -> None:
        self.runs: dict[tuple, tuple[str, int]] = {}
        self.growth: dict[tuple, Growth] = {}
        self.simulated = 0

    def simulate(
        self,
        points: Sequence[tuple[float, float, float, float, float]],
        walls: WallParams | Sequence[WallParams],
        max_samples: int,
    ) -> tuple[list[str], list[int]]:
        """Outcomes and run lengths of ``points`` (as :func:`simulate_points`), simulating only the new ones.

        Parameters
        ----------
        points : sequence of (μ, β, σ, ξ0, ξ'0)
            Dimensionless runs (ξ0 in ticks, ξ'0 in ticks per sample).
        walls : WallParams or sequence of WallParams
            The wall's groups of every point, or one per point (the points of a sweep in K).
        max_samples : int
            Longest run in samples.

        Returns
        -------
        (list of str, list of int)
            Outcome names and run lengths, one per point.
        """
        ws = [walls] * len(points) if isinstance(walls, WallParams) else list(walls)
        keys = [(tuple(float(x) for x in pt), w, max_samples) for pt, w in zip(points, ws, strict=True)]
        todo = list(dict.fromkeys(k for k in keys if k not in self.runs))
        if todo:
            outs, lengths = simulate_points([k[0] for k in todo], [k[1] for k in todo], max_samples)
            self.simulated += len(todo)
            advance(runs=len(todo), step=0, samples=int(sum(lengths)))  # the progress line's count of runs
            self.runs.update({k: (o, n) for k, o, n in zip(todo, outs, lengths, strict=True)})
        return [self.runs[k][0] for k in keys], [self.runs[k][1] for k in keys]

    def growth_at(self, params: Params, wall: WallParams, model: str) -> Growth:
        """:func:`growth_at`, computed once per (μ, β, σ, wall's groups, model)."""
        key = (params.mu, params.beta, params.sigma, wall, model)
        if key not in self.growth:
            self.growth[key] = growth_at(params, wall, model)
        return self.growth[key]


class Evidence:
    """Simulations and predictions of one design search, per stiffness (dimensionless inside), through a cache.

    The wall's elements are held fixed in physical units (B, f_c, f_bw, d): each stiffness K runs with its own
    groups ``wall.with_stiffness(K).params(T)`` (β_B = B/(KT) falls as K grows), in the simulations and in the
    growth prediction. The impacts of each K are at the speeds ``speeds`` (m/s; rad/s), from both
    :data:`STARTS`.
    """

    def __init__(
        self,
        dev: Device,
        wall: Wall,
        speeds: np.ndarray,
        max_samples: int,
        model: str,
        cache: RunCache | None = None,
    ):
        self.dev, self.wall, self.max_samples, self.model = dev, wall, max_samples, model
        self.cache = RunCache() if cache is None else cache
        self.xi_dots = [dev.xi_dot(float(v)) for v in speeds]
        self.sims: dict[float, list[tuple[float, str, str]]] = {}
        self.growth: dict[float, Growth] = {}
        self.runs = 0
        self.longest = 0

    @property
    def speeds(self) -> tuple[float, ...]:
        """The impact speeds simulated, m/s (rotary: rad/s)."""
        return tuple(self.dev.velocity(x) for x in self.xi_dots)

    @property
    def starts(self) -> tuple[str, ...]:
        """The starts of every impact (:func:`starts_of`)."""
        return starts_of(self.wall)

    def params(self, k: float) -> tuple[Params, WallParams]:
        """The device's groups (μ, β, σ) and the wall's at stiffness ``k``, with the device's groups-only elements
        (its travel: a run that leaves it ends at the end stop, ``end_stop``, which fails both simulated limits;
        :func:`dfa.model.loop.device_groups`).

        Raises DFAValueError when a group is not representable at ``k``.
        """
        w = self.wall.with_stiffness(k).params(self.dev.period, self.dev.resolution)
        return self.dev.params(k), device_groups(w, self.dev)

    def outcomes(self, k: float) -> list[tuple[float, str, str]]:
        """(ξ'0, start, outcome) of every impact simulated at stiffness ``k``."""
        self.prefetch([k])
        return self.sims[k]

    def prefetch(self, ks: Sequence[float]) -> None:
        """Simulate the impacts of every stiffness of ``ks`` not yet seen, in one threaded batch (the cache's)."""
        pts: list[tuple[float, float, float, float, float]] = []
        walls: list[WallParams] = []
        tags: list[tuple[float, float, str]] = []
        for k in dict.fromkeys(float(x) for x in ks):
            if k in self.sims:
                continue
            try:
                p, w = self.params(k)
            except DFAValueError:  # μ, β or σ not representable at this K: nothing can be decided there
                self.sims[k] = [(xd, start, "undecided") for xd in self.xi_dots for start in self.starts]
                continue
            for xd in self.xi_dots:
                for start, pt in zip(self.starts, start_points(p.mu, p.beta, p.sigma, xd, w), strict=True):
                    pts.append(pt)  # type: ignore[arg-type]
                    walls.append(w)
                    tags.append((k, xd, start))
        if not pts:
            return
        outs, lengths = self.cache.simulate(pts, walls, self.max_samples)
        self.runs += len(pts)  # every run this evidence rests on, simulated here or earlier
        self.longest = max(self.longest, *lengths)
        for (k, xd, start), o in zip(tags, outs, strict=True):
            self.sims.setdefault(k, []).append((xd, start, o))

    def judge(self, k: float, limit: str) -> str:
        """SAFE, UNSAFE (an outcome in ``FAILING[limit]``) or UNDECIDED for every impact at stiffness ``k``."""
        return judge_outcomes({o for _, _, o in self.outcomes(k)}, limit)

    def no_divergence(self, k: float) -> str:
        """The judgement of the limit "no simulated impact diverges" at ``k``."""
        return self.judge(k, "unstable")

    def rest(self, k: float) -> str:
        """The judgement of the limit "every simulated impact comes to rest" at ``k``."""
        return self.judge(k, "rest")

    def growth_xi_dot(self, k: float) -> Growth:
        """The describing function's growth prediction at ``k`` (:func:`growth_at`; unknown where not representable)."""
        if k not in self.growth and not self.wall.linear:  # not a linear loop: nothing to predict
            self.growth[k] = Growth(None, 0, False)
        if k not in self.growth:
            try:
                p, w = self.params(k)
            except DFAValueError:  # not representable at this K
                self.growth[k] = Growth(None, 0, False)
                return self.growth[k]
            self.growth[k] = self.cache.growth_at(p, w, self.model)
        return self.growth[k]

    def predicted(self, k: float, xi_dot: float) -> str:
        """The describing function's verdict at ``k`` on impacts up to ``xi_dot`` (:func:`df_verdict`)."""
        return df_verdict(self.growth_xi_dot(k), xi_dot)

    def counterexamples(self, k_criterion: float | None) -> tuple[dict[str, Any], ...]:
        """Divergent impacts at stiffnesses the criterion proves passive (there must be none; None: no criterion)."""
        if k_criterion is None:  # no sound criterion (amplifier lag): nothing to contradict
            return ()
        out: list[dict[str, Any]] = []
        for k, rows in sorted(self.sims.items()):
            for xd, start, o in rows:
                if k <= k_criterion and o == "unstable":
                    out.append({"stiffness": k, "velocity": self.dev.velocity(xd), "start": start, "outcome": o})
        return tuple(out)
