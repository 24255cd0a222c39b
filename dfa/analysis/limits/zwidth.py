"""The Z-width of a device: the renderable region of the (K, B) plane, four ways (issue 15, "Z-width").

For a device, an impact speed V and a wall (:class:`dfa.model.wall.Wall`: its delay, velocity filter and
amplifier held fixed), the wall F = −K q_{h−d} − B v_{h−d} is judged on a grid of virtual stiffness K (N/m,
geometric) × virtual damping B (N·s/m, linear; the wall's damper set to each B), and at each B the largest K
is found four ways, each a :class:`~dfa.analysis.limits.search.KLimit` with its status and evidence:

``linear``
    the exact linear bound: top of the stable K interval starting at K = 0 of
    the sampled loop without encoder and Coulomb friction
    (:func:`dfa.analysis.linear_wall.stable_stiffness`, every stable interval
    kept; not limited by the grid).
``passivity``
    Colgate–Schenkel for the general H(z) (:func:`dfa.analysis.colgate_schenkel.colgate_schenkel_damping`):
    the largest K with b above the certified ``damping_bound`` (the linear
    model's passivity, no encoder); and ``criterion``: the passivity criterion
    of eq. 6 extended to the damper, filter and delay
    (:func:`dfa.analysis.criterion.device_criterion`), a proof for
    the quantized device with Coulomb friction for impacts up to V. Both
    refuse an amplifier lag: then they are "not covered" (null with that
    reason), never guessed.
``df``
    the describing function: ``k_df`` of :func:`dfa.analysis.limits.kmax.design_answer` at this B, the same
    search over the same grid (from K_criterion/2 to 8 × the largest closed-form bound), so that the Z-width and
    the design answer give one answer to one question.
``sim``
    exact simulation at every grid point: impacts at the speeds V/n, 2V/n, …,
    V from ξ0 = 0 and, separately, from rest with the spring preloaded to the
    same energy (as ``k_sim`` of :mod:`dfa.analysis.limits.kmax`). A point *diverges* when any
    run diverges, is *undecided* when none diverges and some run is too
    short to tell even when run again up to 16 times longer (as the design runs,
    :func:`~dfa.analysis.limits.runs.decide_undecided`), comes *to rest* when every run rests, else is *bounded*
    (chatter or a sustained cycle). ``k_sim`` is the largest grid K below the
    first point (ascending in K) that diverges or is undecided; ``k_rest`` the
    largest below the first point that does not come to rest. These are grid
    values (resolution: one grid step in K), not bisected; points found safe
    again above the first failure are counted in ``non_monotone``. The runs are those of
    :func:`dfa.simulate` with the same inputs, outcomes included, run in chunks of
    :data:`POINTS_PER_CALL` points, each chunk one compiled call (:func:`dfa.core.batch.batch_wall_kernel`; pure-spring
    points through :func:`dfa.analysis.simulation.run_points`) on threads.

Any simulated divergence at a K the extended criterion proves passive is a
``counterexample`` (status ``"counterexample"``: a criterion bug). The
Colgate–Schenkel condition concerns the linear model; divergences below its
boundary are listed separately (``linear_passivity_violations``), not as
counterexamples.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> z = z_width(Loop(get_device("Impulse Engine").device), 0.1, grid=4, speeds=1, n_jobs=1)
>>> z.status in ("ok", "caveats"), z.counterexamples, z.stiffness.shape
(True, (), (4,))
>>> bool(z.boundary("linear")[0] > 0)      # the exact linear bound at B = 0: the spring's k_gil
True
"""

from __future__ import annotations

import os
from typing import Any

import numpy as np

from ..._parallel import progress_bar, run_in_order, started_in_order, warm_processes
from ...checks import (
    check_bool,
    check_choice,
    check_int,
    check_jobs,
    check_nonnegative,
    check_positive,
    check_speed,
    check_type,
    format_value,
)
from ...core import kernel
from ...errors import DFAValueError
from ...grids import geometric_grid
from ...model.device import Device
from ...model.elements import Coverage
from ...model.loop import LOOP_FIX, Loop, loop_first
from ...model.wall import Wall, WallParams
from ...plausibility import warn_if_from_outside
from ...results.codes import BOUNDED, DIVERGES, LEFT_POINT, POINT_OUTCOMES, REST, UNDECIDED_POINT, ZWIDTH_METHODS
from ...results.status import Fails, LimitStatus, LinearStatus, SimulationOutcome, ZWidthStatus
from ...results.zwidth import ZWidth as ZWidth
from ..colgate_schenkel import colgate_schenkel_damping
from ..linear_wall import stable_stiffness
from ..simulation import (
    GROWTH,
    SETTLE,
    STABLE_AMPLITUDE,
    run_bounds,
    run_points,
    wall_run_codes,
)
from .kmax import describing_limit, wall_k_criterion
from .runs import DIVERGENCE_BOUND, SAFE, UNSAFE, RunCache, decide_undecided, start_points, starts_of
from .search import KLimit, grid_search

__all__ = [
    "ZWidth",
    "z_width",
    "z_width_seconds",
    "start_workers",
    "check_zwidth_size",
    "damping_ends",
    "default_damping_max",
    "z_width_ranges",
    "ZWIDTH_METHODS",
    "POINT_OUTCOMES",
]

#: The default damping axis ends at this multiple of the B where the last passivity boundary ends.
DAMPING_MARGIN = 2.0
#: Longest run of one Z-width simulation (samples); longer automatic lengths are cut (and may be undecided).
ZWIDTH_MAX_SAMPLES = 200_000
#: Largest planned work in simulated samples; more is refused up front.
MAX_WORK_SAMPLES = 2.0e10
#: Largest grid (points per axis).
MAX_GRID = 200
#: Most impact speeds simulated at each grid point (each from two starts).
MAX_SPEEDS = 100
#: Planned cost of one simulated sample (ns, one core; the worst case measured, as ``dfa simulate``'s).
NS_PER_SAMPLE = 100.0
#: Planned cost of the boundaries at one B (s, one core): the describing-function scan, the criterion, the
#: linear bound (about 0.25 s measured on the catalogue devices; planned at twice that).
COLUMN_SECONDS = 0.5
#: Points per axis of the small grid whose planned samples :func:`z_width_seconds` scales up.
ESTIMATE_GRID = 6
#: Grid points per compiled call of the simulations (every run of each point; one chunk per thread task).
POINTS_PER_CALL = 16
#: Fewest values of B whose boundary columns run in worker processes when several workers are asked (fewer:
#: threads). A column is mostly the describing-function scan, pure Python that holds the GIL (about 0.2 s of
#: one core per column on the catalogue devices): on threads it runs on one core whatever the workers; a
#: worker process starts in about 1.5 s of one core (imports), once per session (loky reuses its workers). This
#: process is one of the workers (:func:`dfa._parallel.started_in_order`): n workers start n − 1 processes.
PROCESS_COLUMNS = 16

#: Points of the describing function's search grid at each B (as :func:`~dfa.analysis.limits.kmax.design_answer`).
DF_GRID = 16


# ----------------------------------------------------------------------------- boundaries per B
def _linear(dev: Device, wall: Wall) -> KLimit:
    """Top of the stable K interval from K = 0 of the linear loop (exact); further intervals as ``safe_above``;
    none for a wall that is not a linear loop (one-sided, a passivity controller)."""
    return _linear_bound(dev, wall)[0]


def _linear_bound(dev: Device, wall: Wall) -> tuple[KLimit, float | None]:
    """:func:`_linear` and the stable interval's top as :func:`~dfa.analysis.limits.kmax.linear_limit` gives it
    (N/m; None for a wall that is not a linear loop): one :func:`~dfa.analysis.linear_wall.stable_stiffness`."""
    if not wall.linear:
        return KLimit(None, LimitStatus.NOT_LINEAR), None
    r = stable_stiffness(dev.mass, dev.damping, dev.period, wall)
    if r.status in (LinearStatus.NEVER, LinearStatus.NOT_AT_LOW_K):
        return KLimit(None, LimitStatus.NO_STABLE_K, safe_above=tuple(float(lo) for lo, _ in r.intervals)), float(
            r.k_crit
        )
    more = tuple(float(lo) for lo, _ in r.intervals[1:])
    return KLimit(r.k_crit, non_monotone=bool(more), safe_above=more), float(r.k_crit)


def _colgate_schenkel(dev: Device, wall: Wall, ks: np.ndarray) -> KLimit:
    """Largest K of the grid (then bisection) with b above the certified Colgate–Schenkel bound at this wall."""
    if wall.params(dev.period, dev.resolution).colgate_schenkel_reason() is not None:
        return KLimit(None, LimitStatus.NOT_COVERED)

    def judge(k: float) -> str:
        return (
            SAFE if dev.damping > colgate_schenkel_damping(wall.with_stiffness(k), dev.period).damping_bound else UNSAFE
        )

    return grid_search(judge, ks)


def _criterion(dev: Device, wall: Wall, v: float) -> tuple[KLimit, float | None]:
    """The largest K the criterion proves passive at this wall (:func:`~dfa.analysis.limits.kmax.wall_k_criterion`),
    as a limit and as the bisection's value (N/m; 0: none proven; None: no criterion covers the wall)."""
    if wall.params(dev.period, dev.resolution).not_covered() is not None:
        return KLimit(None, LimitStatus.NOT_COVERED), None
    k = wall_k_criterion(dev, wall, v)
    return (KLimit(k) if k > 0.0 else KLimit(None, LimitStatus.NONE_PROVEN)), k


# ----------------------------------------------------------------------------- simulation of the grid
def _runs(dev: Device, k: float, ctl: WallParams, xi_dots: Any, cap: int) -> list[tuple]:
    """The runs (μ, β, σ, ξ0, ξ'0, samples, bound) of one grid point: each speed from ξ0 = 0 and from the preload
    (a one-sided wall's: after the approach, :func:`~dfa.analysis.limits.runs.start_points`)."""
    p = dev.params(k)
    out = []
    for xd in xi_dots:
        for _mu, _b, _s, x0, v0 in start_points(p.mu, p.beta, p.sigma, xd, ctl):
            # run length from the loop's time scales with the controller's net damping (an estimate: a run
            # too short to tell is "undecided", never a verdict)
            n, bound = run_bounds(p.mu, p.beta, p.sigma, v0, x0, ctl, DIVERGENCE_BOUND)  # a valid device's groups
            out.append((p.mu, p.beta, p.sigma, x0, v0, min(n, cap), bound))
    return out


def _chunks(tasks: list[tuple], size: int) -> list[list[int]]:
    """Indices of the tasks in chunks of at most ``size`` consecutive points, spring and controller apart.

    A pure-spring point (``Coverage.CLOSED_FORM``: B = 0, no filter, no lag) runs
    the spring kernel, as :func:`dfa.analysis.simulation.simulate` routes it; every other point the controller kernel.
    """
    out: list[list[int]] = []
    for i, (_, ctl) in enumerate(tasks):
        if (
            not out
            or len(out[-1]) >= size
            or tasks[out[-1][0]][1].covers(Coverage.CLOSED_FORM) != ctl.covers(Coverage.CLOSED_FORM)
        ):
            out.append([])
        out[-1].append(i)
    return out


def _run_chunk(tasks: list[tuple]) -> np.ndarray:
    """Outcome code of every point of a chunk (runs, controller): every run of the chunk in one compiled call.

    The runs are those :func:`dfa.analysis.simulation.simulate` would make with the same inputs (its tail length and
    default outcome rules; the spring kernel for a pure spring, else :mod:`dfa.core.wall_kernel`), bit for bit, and are
    classified by :func:`dfa.core.kernel.classify_batch` as :func:`~dfa.analysis.simulation.simulate` classifies one; the
    point's code follows from its runs' outcomes (:func:`_point_codes`). No GIL is held in the compiled calls.
    """
    runs = [r for rs, _ in tasks for r in rs]
    mu, beta, sigma, x0, v0, n, bound = (np.array(c) for c in zip(*runs, strict=True))
    w = tasks[0][1]
    walls = [c for rs, c in tasks for _ in rs]

    def codes_of(i: np.ndarray, ns: np.ndarray) -> np.ndarray:
        ns = np.asarray(ns, dtype=np.int64)
        if w.covers(Coverage.CLOSED_FORM):
            return run_points(mu[i], beta[i], sigma[i], x0[i], v0[i], ns, w, True, bound[i], STABLE_AMPLITUDE, GROWTH,
                              SETTLE)[0]  # fmt: skip
        return wall_run_codes(mu[i], beta[i], sigma[i], x0[i], v0[i], ns, bound[i], [walls[j] for j in i])

    every = np.arange(len(runs))
    codes, _ = decide_undecided(codes_of(every, n), n, kernel.UNDECIDED, codes_of)  # as the design runs
    return _point_codes(codes.astype(np.int64).reshape(len(tasks), -1))


#: The kernel's codes of the outcomes that make a Z-width point diverge: those failing the no-divergence limit
#: (:attr:`dfa.results.status.SimulationOutcome.fails`; the code is the outcome's place in the enum).
_DIVERGES = tuple(o.code for o in SimulationOutcome if Fails.NO_DIVERGENCE in o.fails)


def _point_codes(run_codes: np.ndarray) -> np.ndarray:
    """Code of each point (row) from its runs' outcome codes (:mod:`dfa.core.kernel`; module docstring).

    Diverges if any run fails the no-divergence limit (:data:`_DIVERGES`: unstable, saturated, held by the actuator's
    force limit, or at an end stop), else undecided if any run is, else rest if every run rests, left if every run
    rests or leaves a one-sided wall for good (some leave), else bounded.
    """
    out = np.full(run_codes.shape[0], BOUNDED, dtype=np.int8)
    ended = np.isin(run_codes, (kernel.REST, kernel.LEFT)).all(axis=1)  # a one-sided wall's run may leave
    out[ended & (run_codes == kernel.LEFT).any(axis=1)] = LEFT_POINT
    out[(run_codes == kernel.REST).all(axis=1)] = REST
    out[(run_codes == kernel.UNDECIDED).any(axis=1)] = UNDECIDED_POINT
    out[np.isin(run_codes, _DIVERGES).any(axis=1)] = DIVERGES
    return out


def _simulate_grid(tasks: list[tuple], jobs: int, progress: bool, label: str) -> np.ndarray:
    """Outcome code of every task (runs, controller), in order, chunks of points on ``jobs`` threads.

    Each chunk (:data:`POINTS_PER_CALL` points, :func:`_chunks`) is one compiled call that releases the GIL
    (:func:`_run_chunk`), run like the chunks of a stability map (:func:`dfa._parallel.run_in_order`): the
    result does not depend on ``jobs``; a progress bar counts the points; an interruption cancels the
    chunks not started.
    """
    chunks = _chunks(tasks, POINTS_PER_CALL)
    with progress_bar(total=len(tasks), unit="point", desc=label, disable=not progress, leave=False) as bar:
        parts = run_in_order(
            _run_chunk, [([tasks[i] for i in c],) for c in chunks], [len(c) for c in chunks], jobs, "threads", bar
        )
    codes = np.empty(len(tasks), dtype=np.int8)
    for c, part in zip(chunks, parts, strict=True):
        codes[c] = part
    return codes


def _grid_boundary(row: np.ndarray, ks: np.ndarray, bad: set[int]) -> KLimit:
    """Largest grid K below the first point of ``row`` whose code is in ``bad`` (a grid value: ``first_failure`` is
    the next grid K, the limit lies between them)."""
    hit = [j for j, c in enumerate(row) if c in bad]
    if not hit:
        return KLimit(None, LimitStatus.ABOVE_RANGE, range_end=float(ks[-1]), evaluations=len(ks))
    j = hit[0]
    if j == 0:
        return KLimit(None, LimitStatus.BELOW_RANGE, range_end=float(ks[0]), first_failure=float(ks[0]))
    above = tuple(float(k) for k, c in zip(ks[j + 1 :], row[j + 1 :], strict=True) if c not in bad)
    undecided = float(ks[j]) if row[j] == UNDECIDED_POINT else None
    return KLimit(
        float(ks[j - 1]), limited_by=undecided, limited_why=None if undecided is None else "short_runs",
        non_monotone=bool(above), safe_above=above,
        first_failure=float(ks[j]), evaluations=len(ks),
    )  # fmt: skip


# ----------------------------------------------------------------------------- the analysis
def damping_ends(device: Device, wall: Wall, velocity: float) -> dict[str, float]:
    """Where the passivity boundaries of the Z-width end: the largest virtual damping B (N·s/m; rotary
    N·m·s/rad) with some K proven, by method (only those that cover the wall).

    ``criterion``: :func:`~dfa.analysis.limits.require.damper_guidance`'s largest B (eq. 11 with the damper's
    terms, K → 0, closed form). ``passivity``: Colgate–Schenkel's bound is linear in the wall's H(z), so at
    K → 0 it is B times its value for B = 1: it ends at b over that. The linear bound, the describing function
    and the simulations usually run on beyond m/T (a damper stabilises the linear loop): they have no end here.

    Parameters
    ----------
    device : Device
    wall : Wall
        Its delay, filter and other elements are held; its stiffness and damper are replaced.
    velocity : float
        Impact speed, m/s (rotary: rad/s).

    Returns
    -------
    dict
        ``{"criterion": B, "passivity": B}``, those that cover the wall.
    """
    from .require import damper_guidance_for

    out: dict[str, float] = {}
    one = wall.in_contact().with_damping(1.0)
    guide = damper_guidance_for(device, one, velocity)
    if guide is not None:
        out["criterion"] = float(guide.max_virtual_damping)
    if one.params(device.period, device.resolution).colgate_schenkel_reason() is None:
        k = 1e-9 * device.mass / device.period**2  # K → 0: the K part of the bound is negligible
        per_b = colgate_schenkel_damping(one.with_stiffness(k), device.period).damping_bound
        per_b -= colgate_schenkel_damping(one.with_damping(0.0).with_stiffness(k), device.period).damping_bound
        if per_b > 0.0:
            out["passivity"] = device.damping / per_b
    return out


def default_damping_max(device: Device, wall: Wall, velocity: float) -> float:
    """The top of the Z-width's default damping axis: :data:`DAMPING_MARGIN` times where the last passivity
    boundary ends (:func:`damping_ends`), at most m/T (the axis of old, where the damper's time constant is one
    sample); m/T when no boundary ends inside it.

    Parameters
    ----------
    device : Device
    wall : Wall
    velocity : float
        Impact speed, m/s (rotary: rad/s).

    Returns
    -------
    float
        B in N·s/m (rotary: N·m·s/rad), > 0.
    """
    top = device.mass / device.period
    ends = [b for b in damping_ends(device, wall, velocity).values() if 0.0 < b < top]
    return min(top, DAMPING_MARGIN * max(ends)) if ends else top


def _grids(dev: Device, wall: Wall, grid: int, k_range: Any, b_range: Any, v: float) -> tuple[np.ndarray, np.ndarray]:
    """Default grids: B from 0 to :func:`default_damping_max`; K geometric up to 8 × the largest linear bound or
    static limit 2c/Δ."""
    if b_range is None:
        b_range = (0.0, default_damping_max(dev, wall, v))
    b0 = check_nonnegative("b_range[0]", b_range[0], "give the smallest virtual damping B >= 0")
    b1 = check_positive("b_range[1]", b_range[1], "give the largest virtual damping B > 0")
    if not b1 > b0:
        raise DFAValueError(
            f"b_range = ({format_value(b0)}, {format_value(b1)}) is invalid: it must satisfy low < high"
        )
    bs = np.linspace(b0, b1, grid)
    if k_range is None:
        lin = [_linear(dev, wall.in_contact().with_damping(float(b))).value for b in (b0, b1)]
        top = 8.0 * max([2.0 * dev.coulomb / dev.resolution] + [k for k in lin if k is not None])
        low = 0.5 * lin[0] if lin[0] is not None else top * 1e-4
        k_range = (min(low, top * 1e-2), top)
    k0 = check_positive("k_range[0]", k_range[0], "give the smallest stiffness K > 0")
    k1 = check_positive("k_range[1]", k_range[1], "give the largest stiffness K")
    if not k1 > k0:
        raise DFAValueError(
            f"k_range = ({format_value(k0)}, {format_value(k1)}) is invalid: it must satisfy low < high"
        )
    return geometric_grid(k0, k1, grid), bs


@loop_first("device, *, wall")
def z_width_ranges(
    loop: Loop, velocity: float, b_range: tuple[float, float] | None = None
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The K and B ranges :func:`z_width` takes by default for this loop (N/m and N·s/m): its grids' ends.

    The Z-width of several devices on one grid (a device file's configurations) spans the union of theirs.

    Returns
    -------
    ((float, float), (float, float))
        (K low, K high) and (B low, B high).
    """
    dev = check_type("loop", loop, Loop, LOOP_FIX).search_device("z_width_ranges")
    ks, bs = _grids(dev, loop.spring, 2, None, b_range, velocity)
    return (float(ks[0]), float(ks[-1])), (float(bs[0]), float(bs[-1]))


def _plan(dev: Device, wall: Wall, ks: Any, bs: Any, xi_dots: Any, cap: int) -> tuple[list[tuple], float]:
    """The simulation tasks of the grid (B-major) and their planned samples."""
    tasks, work = [], 0.0
    for b in bs:
        wb = wall.with_damping(float(b))
        for k in ks:
            ctl = wb.with_stiffness(float(k)).params(dev.period, dev.resolution)
            runs = _runs(dev, float(k), ctl, xi_dots, cap)
            work += sum(r[5] for r in runs)
            tasks.append((runs, ctl))
    return tasks, work


@loop_first("device, *, wall")
def z_width(
    loop: Loop,
    velocity: float,
    *,
    grid: int = 40,
    k_range: tuple[float, float] | None = None,
    b_range: tuple[float, float] | None = None,
    speeds: int = 2,
    max_samples: int = ZWIDTH_MAX_SAMPLES,
    df_model: str = "half-delay",
    n_jobs: int = -1,
    progress: bool = False,
) -> ZWidth:
    """The Z-width of the loop's device at impact speed ``velocity``: K_max(B) four ways and the simulated grid.

    Parameters
    ----------
    loop : Loop
        The device and the wall whose computational delay (samples), velocity filter (Hz) and amplifier (Hz)
        are held fixed, ``Loop(device, wall)``; its stiffness and damper are the grid's. ``Loop(device)``: the
        spring, no delay. The former call ``z_width(device, velocity, wall=wall)`` still works.
    velocity : float
        Impact speed V, m/s (rotary: rad/s), > 0 (a negative is refused, not flipped).
    grid : int, optional
        Points per axis (default 40, at most 200).
    k_range : (float, float), optional
        Smallest and largest K of the geometric grid, N/m (default: from half the linear bound at the
        smallest B to 8 × the largest of the linear bound and 2c/Δ).
    b_range : (float, float), optional
        Smallest and largest B of the linear grid, N·s/m (default: 0 to :func:`default_damping_max`, twice the B
        where the criterion's and Colgate–Schenkel's boundaries end, at most m/T).
    speeds : int, optional
        Impact speeds simulated: V/speeds, …, V (default 2), each from ξ0 = 0 and from the preload.
    max_samples : int, optional
        Longest run, samples (default 2·10⁵); longer automatic lengths are cut and may be undecided.
    df_model : {"half-delay", "zoh", "pade"}, optional
        Hold model of the describing function.
    n_jobs : int, optional
        Workers (-1: all cores): threads for the simulations; for the per-B boundaries threads, or from
        :data:`PROCESS_COLUMNS` values of B on this process and n_jobs − 1 worker processes, started before the
        simulations (their describing-function scans hold the GIL). The result does not depend on it.
    progress : bool, optional
        Show a progress bar on stderr.

    Returns
    -------
    ZWidth
        K_max(B) per method with their evidence, the grid outcomes and the status.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad inputs (cutoff above Nyquist, ...), or planned work above :data:`MAX_WORK_SAMPLES` simulated
        samples (the message says how to lower it).

    See Also
    --------
    dfa.analysis.linear_wall.stable_stiffness : The exact linear bound at one B.
    dfa.analysis.criterion.device_criterion : The criterion with the wall.
    dfa.analysis.limits.kmax.design_answer : The four K_max at one B.
    """
    dev = check_type("loop", loop, Loop, LOOP_FIX).search_device("z_width")
    v = check_speed("velocity", velocity, dev.units["velocity"], zero=False)
    warn_if_from_outside("velocity", v, rotary=dev.rotary)
    base = loop.spring
    g = check_int("grid", grid, minimum=2, fix="give at least 2 points per axis")
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one impact speed")
    check_zwidth_size(g, n_speeds)
    cap = check_int("max_samples", max_samples, minimum=1000, fix="allow runs of at least 1000 samples")
    model = check_choice("df_model", df_model, ("half-delay", "zoh", "pade"))
    jobs = check_jobs("n_jobs", n_jobs)
    progress = check_bool("progress", progress, "pass True to show a progress bar, False for none")
    workers = _workers(jobs)
    ks, bs = _grids(dev, base, g, k_range, b_range, v)
    vs = v * np.arange(1, n_speeds + 1) / n_speeds
    xi_dots = [dev.xi_dot(float(s)) for s in vs]
    # the boundary columns start first: in worker processes they (and the workers' start) overlap the planning and
    # the simulations on threads, which need no boundary (dfa._parallel.started_in_order)
    args = [(dev, base.with_damping(float(b)), v, ks, model) for b in bs]
    how = "processes" if workers > 1 and len(args) >= PROCESS_COLUMNS else "threads"
    with started_in_order(_column, args, [1] * len(args), workers, how) as columns:
        tasks, work = _plan(dev, base, ks, bs, xi_dots, cap)
        if work > MAX_WORK_SAMPLES:
            raise DFAValueError(
                f"grid = {g} is invalid with speeds = {n_speeds} and max_samples = {cap}: the Z-width would simulate "
                f"{work:.3g} samples (limit {MAX_WORK_SAMPLES:.3g}); lower the grid, the speeds or max_samples"
            )
        codes = _simulate_grid(tasks, workers, progress, f"Z-width {dev.name}").reshape(g, g)
        label = f"Z-width {dev.name} boundaries"
        with progress_bar(total=len(args), unit="B", desc=label, disable=not progress, leave=False) as bar:
            cols = columns(bar)  # in order: the result does not depend on workers
    return _assemble(dev, base, v, vs, ks, bs, codes, cap, len(tasks), model, cols)


def check_zwidth_size(grid: int, speeds: int = 1, names: tuple[str, str] = ("grid", "speeds")) -> None:
    """Refuse a Z-width grid above :data:`MAX_GRID` points per axis or more than :data:`MAX_SPEEDS` speeds.

    The one rule of :func:`z_width`, the report's Z-width and the command line (``names``: the inputs as the
    caller calls them, a flag printed as ``--grid 300``), checked before any work or time estimate.

    Examples
    --------
    >>> check_zwidth_size(300, names=("--zwidth", "--speeds"))
    Traceback (most recent call last):
    ...
    dfa.errors.DFAValueError: --zwidth 300 is invalid: it must be at most 200 points per axis; lower --zwidth
    """
    limits = ((grid, MAX_GRID, "points per axis", "lower"), (speeds, MAX_SPEEDS, _PER_POINT, "give fewer"))
    for name, (value, top, what, fix) in zip(names, limits, strict=True):
        if value > top:
            shown = f"{name} {value}" if name.startswith("--") else f"{name} = {value}"
            raise DFAValueError(f"{shown} is invalid: it must be at most {top} {what}; {fix} {name}")


#: What a speed limit counts (the message of :func:`check_zwidth_size`).
_PER_POINT = "impact speeds per grid point (each simulated from two starts)"


def start_workers(grid: int, n_jobs: int = -1) -> None:
    """Start now the worker processes :func:`z_width` with this grid and ``n_jobs`` will run its boundary columns
    in (none below :data:`PROCESS_COLUMNS` values of B or with one worker), so that their start (a second or two
    of imports each) overlaps the caller's work until then (the command line's inputs and time estimate).

    Parameters
    ----------
    grid : int
        Points per axis of the coming :func:`z_width`.
    n_jobs : int, optional
        Its workers (-1: all cores).

    Returns
    -------
    None
        The processes start in the background; :func:`z_width` takes them up (its result does not depend on them).

    See Also
    --------
    z_width : The Z-width that then uses them.
    dfa._parallel.warm_processes : The processes started.
    """
    workers = _workers(check_jobs("n_jobs", n_jobs))
    if workers > 1 and int(grid) >= PROCESS_COLUMNS:
        warm_processes(min(workers, int(grid)), __name__)


def warm_worker() -> None:
    """Load numba and a compiled kernel of the boundary columns (the linear bound's φ₂) in a worker process that
    :func:`start_workers` started, while it waits for its first column (:func:`dfa._parallel.warm_processes`):
    numba's start, about 0.45 s of one core, then overlaps this process's planning instead of delaying that
    column (issue 43)."""
    from ...core import exprel

    exprel.phi2_array(np.zeros(1))


def _workers(jobs: int) -> int:
    """The workers of ``n_jobs`` (-1: every core)."""
    return (os.cpu_count() or 1) if jobs == -1 else jobs


@loop_first("device, *, wall")
def z_width_seconds(
    loop: Loop,
    velocity: float,
    *,
    grid: int = 40,
    speeds: int = 2,
    max_samples: int = ZWIDTH_MAX_SAMPLES,
    n_jobs: int = -1,
    b_range: tuple[float, float] | None = None,
) -> float:
    """The planned time of :func:`z_width` with these inputs (s, wall clock): an upper estimate, before any work.

    The samples of an :data:`ESTIMATE_GRID`-point grid's plan, scaled by the number of grid points, at
    :data:`NS_PER_SAMPLE` each, plus :data:`COLUMN_SECONDS` per value of B, over the workers. Runs stop
    early (at rest or divergence), so the Z-width usually takes less; undecided runs extended 4× to 16×
    (:func:`~dfa.analysis.limits.runs.decide_undecided`) can take more.

    Parameters
    ----------
    loop, velocity, grid, speeds, max_samples, n_jobs, b_range
        As :func:`z_width` (the inputs are not validated here: :func:`z_width` does that); the former call
        ``z_width_seconds(device, velocity, wall=wall)`` still works.

    Returns
    -------
    float
        Seconds.

    Examples
    --------
    >>> from dfa import get_device
    >>> dev = get_device("Impulse Engine").device
    >>> z_width_seconds(Loop(dev), 0.1, grid=200) > 60.0 > z_width_seconds(Loop(dev), 0.1, grid=12)
    True
    """
    device, base = loop.search_device("z_width_seconds"), loop.spring
    small = min(int(grid), ESTIMATE_GRID)
    ks, bs = _grids(device, base, small, None, b_range, velocity)
    vs = velocity * np.arange(1, speeds + 1) / speeds
    _, work = _plan(device, base, ks, bs, [device.xi_dot(float(s)) for s in vs], max_samples)
    workers = max(_workers(int(n_jobs)), 1)
    samples = work * (float(grid) / small) ** 2
    return (samples * NS_PER_SAMPLE * 1e-9 + grid * COLUMN_SECONDS) / workers


def _column(dev: Device, wall: Wall, v: float, ks: np.ndarray, model: str) -> list[KLimit]:
    """The limits at one B (``wall`` has that damper) of the methods that do not simulate: linear, passivity,
    criterion and describing function (:data:`ZWIDTH_METHODS` order).

    The linear bound and the criterion's bisection are computed once: the describing function's search grid
    (:func:`~dfa.analysis.limits.kmax.closed_forms`) takes their values.
    """
    linear, k_linear = _linear_bound(dev, wall)
    criterion, k_criterion = _criterion(dev, wall, v)
    return [
        linear,
        _colgate_schenkel(dev, wall, ks),
        criterion,
        describing_limit(dev, wall, v, model, RunCache(), DF_GRID, k_criterion=k_criterion, k_linear=k_linear),
    ]


def _assemble(
    dev: Device,
    wall: Wall,
    v: float,
    vs: Any,
    ks: Any,
    bs: Any,
    codes: Any,
    cap: int,
    n_points: int,
    model: str,
    columns: list[list[KLimit]],
) -> ZWidth:
    """Limits per method from the boundary columns (:func:`_column`) and the simulated grid's rows; status."""
    cols = [
        [
            *c,
            _grid_boundary(row, ks, {DIVERGES, UNDECIDED_POINT}),
            _grid_boundary(row, ks, {BOUNDED, DIVERGES, UNDECIDED_POINT}),
        ]
        for c, row in zip(columns, codes, strict=True)
    ]
    limits = {m: tuple(c[n] for c in cols) for n, m in enumerate(ZWIDTH_METHODS)}
    ce, lpv = _violations(codes, ks, bs, limits, dev.units["stiffness"])
    caveat = bool((codes == UNDECIDED_POINT).any()) or any(x.non_monotone for m in ("sim", "rest") for x in limits[m])
    status = ZWidthStatus.COUNTEREXAMPLE if ce else (ZWidthStatus.CAVEATS if caveat else ZWidthStatus.OK)
    return ZWidth(
        dev, wall, v, tuple(float(s) for s in vs), ks, bs, limits, codes, cap, n_points * len(starts_of(wall)) * len(vs),
        model, ce,
        lpv, status,
    )  # fmt: skip


def _violations(codes: Any, ks: Any, bs: Any, limits: Any, unit: str) -> tuple[tuple[dict, ...], tuple[dict, ...]]:
    """Divergent grid points at or below the criterion's and Colgate–Schenkel's boundaries."""
    out: dict[str, list[dict]] = {"criterion": [], "passivity": []}
    for name, rows in out.items():
        for i, b in enumerate(bs):
            top = limits[name][i].value
            for j, k in enumerate(ks):
                if top is not None and k <= top and codes[i, j] == DIVERGES:
                    rows.append({"stiffness": float(k), "damping": float(b), "outcome": "diverges", "unit": unit})
    return tuple(out["criterion"]), tuple(out["passivity"])
