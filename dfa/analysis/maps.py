"""Stability maps over the (β, σ) plane (paper Fig. 4).

Every grid point is an independent exact simulation (:func:`dfa.simulate`
without recording), run in chunks of points, each chunk one compiled call
(:func:`dfa.analysis.simulation.run_points`); the result does not depend on the number
of jobs nor on the backend. A tqdm progress bar reports the chunks as they
finish. With a wall of more than a spring (``wall=``) the chunks are the same and run
the same way (:func:`dfa._parallel.run_in_order`): only the compiled kernel differs.
An interruption (Ctrl-C) cancels the chunks not started and returns nothing.

The maps keep their form (μ, the speeds, the β and σ ranges, ``wall=`` the wall's groups) rather than taking a
:class:`~dfa.model.loop.Loop`: a loop is one point (μ, β, σ), while a map sweeps β and σ over ranges that are not
centred on any point (the paper's Fig. 4 spans a fixed square); only μ and the wall's groups are shared by every
point. A caller with a loop passes ``loop.params.mu`` and ``wall=loop.wall_params``, as the design analysis does
around its operating point.

Backends
--------
``"threads"`` (default): the compiled kernel releases the GIL, so chunks run
on a thread pool in this process (no worker start-up, no re-import).
``"processes"``: joblib's process pool (loky). ``"joblib"``: whatever
``joblib.parallel_config`` selects, e.g. a dask cluster (``pip install
'dfa-haptics[dask]'``)::

    from dask.distributed import Client
    import joblib
    client = Client("tcp://scheduler:8786")
    with joblib.parallel_config(backend="dask"):
        m = stability_map(100.0, [1, 2, 5, 10], grid=400, backend="joblib")

Examples
--------
>>> m = stability_map(100.0, [2.0], grid=4, samples=2000, n_jobs=1, progress=False)
>>> m.outcome.shape, sorted(m.counts()[0])
((1, 4, 4), ['chatter', 'oscillating', 'rest', 'undecided', 'unstable'])

Outcome codes
-------------
``StabilityMap.outcome`` holds the kernel's codes, the index of the name in
:data:`dfa.analysis.simulation.OUTCOMES` (rules in :mod:`dfa.analysis.simulation`):

====  ===============  =====================================================
code  name             meaning
====  ===============  =====================================================
0     ``rest``         came to rest (absorbing state reached)
1     ``oscillating``  settled persistent cycle of 1 tick or more
2     ``unstable``     diverged: past the bound, or a growing envelope
3     ``chatter``      never rests; settled cycle below 1 tick
4     ``undecided``    envelope still changing at the end: run longer
====  ===============  =====================================================

The ``.npz`` file stores the names in ``outcome_names`` (index = code);
:func:`load_map` maps them back and rejects files written before these
classes existed (their ``stable`` mixed rest with chatter).
"""

from __future__ import annotations

import json
import math
import os
import zipfile
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .._io import check_memory
from .._parallel import PARALLEL_BACKENDS, deal, gather, progress_bar, run_in_order
from ..checks import (
    check_bool,
    check_bound,
    check_choice,
    check_damping_rate,
    check_int,
    check_jobs,
    check_mu,
    check_range,
    check_speed,
    format_value,
)
from ..core import kernel
from ..errors import DFATypeError, DFAValueError
from ..model.elements import Coverage
from ..model.loop import Loop
from ..model.wall import WallParams
from ..results.maps import StabilityMap as StabilityMap
from .simulation import (
    GROWTH,
    OUTCOMES,
    SETTLE,
    STABLE_AMPLITUDE,
    check_rules,
    check_wall,
    contact_codes,
    divergence_bound,
    preload_position,
    run_points,
)

if TYPE_CHECKING:
    from .simulation import SimulationResult

__all__ = [
    "StabilityMap",
    "stability_map",
    "simulate_point",
    "load_map",
    "map_memory_bytes",
    "check_jobs",
    "MAP_BACKENDS",
]

#: Execution backends of :func:`stability_map` (module docstring; :mod:`dfa._parallel`).
MAP_BACKENDS = PARALLEL_BACKENDS

#: Planned peak memory per grid point and initial speed (bytes): four float inputs, three
#: float outputs in chunks and concatenated, the int8 outcome, with margin.
MAP_BYTES_PER_RUN = 96
#: ... and per grid point (the meshgrid axes).
MAP_BYTES_PER_POINT = 16
#: Most planned samples (spring-kernel equivalent) in one chunk: about half a second of the spring kernel without
#: period skipping, so that Ctrl-C waits about that long for the running chunks and the progress bar keeps moving.
CHUNK_SAMPLES = 2.0e7
#: Cost per sample of the wall kernel relative to the spring's (measured on sub-tick chatter, which runs
#: to the end: spring with d = 1 26 ns, damper/filter 36-170 ns, amplifier lag ~1 µs per sample).
WALL_COST = {"wall": 4.0, "lag": 40.0}


def map_memory_bytes(grid: int, n_speeds: int) -> int:
    """Estimated peak memory of :func:`stability_map` in bytes (grid² points × speeds)."""
    return int(grid) ** 2 * (MAP_BYTES_PER_POINT + MAP_BYTES_PER_RUN * int(n_speeds))


def load_map(path: str | os.PathLike) -> StabilityMap:
    """Read a map written by :meth:`StabilityMap.save` (codes mapped through the file's ``outcome_names``).

    Parameters
    ----------
    path : str or os.PathLike
        A ``.npz`` file written by :meth:`StabilityMap.save`.

    Returns
    -------
    StabilityMap
        The map as it was saved.

    Raises
    ------
    DFAValueError
        If the file is missing, incomplete, written by an older dfa or names unknown outcomes.
    DFATypeError
        If ``path`` is not a path.

    See Also
    --------
    stability_map : Compute a map.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise DFATypeError(
            f"path = {format_value(path)} has type {type(path).__name__}: it must be the path of a .npz map file"
        )
    try:
        return _load_map(path)
    except (FileNotFoundError, IsADirectoryError, NotADirectoryError):
        raise DFAValueError(
            f"path = {os.fspath(path)!r} is invalid: no such file; give the .npz file written by `dfa map`"
        ) from None
    except (ValueError, KeyError, EOFError, zipfile.BadZipFile, TypeError) as exc:
        if isinstance(exc, DFAValueError):
            raise
        raise DFAValueError(
            f"path = {os.fspath(path)!r} is invalid: it is not a complete dfa map file ({type(exc).__name__}); "
            "recompute it with `dfa map`"
        ) from None


def _load_map(path: str | os.PathLike) -> StabilityMap:
    with np.load(path, allow_pickle=False) as z:
        samples, delay, quantize, preload = (int(v) for v in z["settings"])
        if "outcome_names" not in z.files:
            raise DFAValueError(
                f"map file {str(path)!r} is invalid: it was written by an older dfa whose outcome 'stable' mixed rest "
                "with sub-tick chatter; recompute it with `dfa map`"
            )
        names = [str(v) for v in z["outcome_names"]]
        unknown = sorted(set(names) - set(OUTCOMES))
        if unknown:
            raise DFAValueError(
                f"map file {str(path)!r} is invalid: unknown outcome names {unknown}; expected {list(OUTCOMES)}"
            )
        lut = np.array([OUTCOMES.index(v) for v in names], dtype=np.int8)
        codes = z["outcome"]
        integral = codes.dtype.kind in "iu"
        if not integral or (codes.size and not (0 <= codes.min() and codes.max() < lut.size)):
            held = f"codes {codes.min()} … {codes.max()}" if integral else f"{codes.dtype} values"
            raise DFAValueError(
                f"map file {str(path)!r} is invalid: its outcome array holds {held}, not the codes 0 … {lut.size - 1} "
                "of its outcome_names; recompute it with `dfa map`"
            )
        wall = _wall_from(z, delay)
        try:
            return StabilityMap(
                mu=z["mu"][()],
                xi_dots=z["xi_dots"],
                beta=z["beta"],
                sigma=z["sigma"],
                outcome=lut[codes],
                amplitude=z["amplitude"],
                frequency=z["frequency"],
                samples=samples,
                quantize=bool(quantize),
                preload=bool(preload),
                wall=wall,
                contact=z["contact"].astype(np.int8)
                if not wall.covers(Coverage.SURFACE_START) and "contact" in z.files
                else None,
            )
        except (DFAValueError, DFATypeError) as err:  # a value outside its rule: the file names it
            raise DFAValueError(f"map file {str(path)!r} is invalid ({err}); recompute it with `dfa map`") from None


def _wall_from(z: np.lib.npyio.NpzFile, delay: int) -> WallParams:
    """The wall of a map file: its ``wall_json`` read through the element registry
    (:meth:`dfa.model.wall.WallParams.from_dict`); in a file written before it, the arrays ``wall`` (or
    ``controller``), ``hand``, ``one_sided`` and ``passivity_controller`` (:func:`_legacy_wall`); the spring when
    there are none."""
    if "wall_json" in z.files:
        return WallParams.from_dict(json.loads(str(z["wall_json"][()])))
    return _legacy_wall(z, delay)


def _legacy_wall(z: np.lib.npyio.NpzFile, delay: int) -> WallParams:
    """The wall of a map file written before ``wall_json``: [β_B, ν_c (NaN: no filter), α] in ``wall`` (or
    ``controller`` as earlier files named it), [κ_h] in ``hand``, a one-sided wall's [s, p] in ``one_sided``, a
    passivity controller's [W, f_max] (inf: no limit) in ``passivity_controller``, read as the groups' record."""
    key = next((k for k in ("wall", "controller") if k in z.files), None)
    if key is None:
        return WallParams.of(delay=delay)
    damping, cutoff, lag = (float(v) for v in z[key])
    record: dict[str, object] = {"damping": damping, "delay": delay, "cutoff": None if math.isnan(cutoff) else cutoff}
    record |= {"lag": lag, "hand_stiffness": float(z["hand"][0]) if "hand" in z.files else 0.0}
    if "passivity_controller" in z.files:
        window, limit = (float(v) for v in z["passivity_controller"])
        record |= {"pc_window": int(window), "pc_force_limit": None if math.isinf(limit) else limit}
    if "one_sided" in z.files:
        surface, push = (float(v) for v in z["one_sided"])
        record |= {"one_sided": surface, "push": push}
    return WallParams.from_dict(record)


def _run_chunk(
    mu: float,
    betas: np.ndarray,
    sigmas: np.ndarray,
    x0s: np.ndarray,
    v0s: np.ndarray,
    samples: int,
    wall: WallParams,
    quantize: bool,
    bound: float,
    stable_amplitude: float,
    growth: float,
    settle: float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Codes, amplitudes, frequencies and (a one-sided wall's) contact kinds of one chunk of points (one compiled
    call; releases the GIL); the contact kinds are −1 for a bilateral wall."""
    mus = np.full(betas.size, mu)
    res = run_points(mus, betas, sigmas, x0s, v0s, samples, wall, quantize, bound, stable_amplitude, growth, settle)
    if not wall.covers(Coverage.SURFACE_START):
        stats = res[7]
        contact = contact_codes(res[0], stats[:, kernel.NSEG + 6], stats[:, kernel.NSEG + 8], wall, quantize)
    else:
        contact = np.full(betas.size, -1, dtype=np.int8)
    return res[0], res[1], res[2], contact


def stability_map(
    mu: float,
    xi_dots: ArrayLike,
    *,
    beta_range: tuple[float, float] = (0.0, 1.0),
    sigma_range: tuple[float, float] = (0.0, 2.0),
    grid: int = 100,
    samples: int = 50_000,
    quantize: bool = True,
    preload: bool = False,
    n_jobs: int = -1,
    backend: str = "threads",
    progress: bool = True,
    bound: float | None = None,
    stable_amplitude: float = STABLE_AMPLITUDE,
    growth: float = GROWTH,
    settle: float = SETTLE,
    wall: WallParams | None = None,
) -> StabilityMap:
    """Simulate every point of a (β, σ) grid for each initial speed (paper Fig. 4).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ > 0 (the paper's Fig. 4 uses 100).
    xi_dots : sequence of float
        Initial speeds ξ'0 in ticks per sample (from ξ0 = 0), or with
        ``preload`` the equivalent speeds of an initial spring preload.
    beta_range, sigma_range : (float, float)
        Grid extents (inclusive).
    grid : int
        Points per axis (>= 2).
    samples : int
        Samples per run (paper: 5·10⁴, 50 s at 1 kHz). Fixed for the whole
        grid; points that need longer are ``"undecided"``.
    quantize : bool, optional
        True (default): the encoder quantizes the position; False: the linear spring.
    preload : bool, optional
        Start from the spring preload of each speed (:func:`preload_position`) at rest, instead of
        from ξ0 = 0 with speed ξ'0 (default False). A one-sided wall's runs start with the approach from free
        space instead (:func:`map_start`; ``samples`` then counts after the approach), and refuse a preload.
    n_jobs : int
        Workers (-1: all cores; 1: in this thread). The result does not depend on it.
    backend : {"threads", "processes", "joblib"}
        Where the workers run (module docstring): threads of this process
        (default), joblib's process pool, or joblib's configured backend
        (dask). The result does not depend on it.
    progress : bool
        Show a tqdm progress bar.
    bound, stable_amplitude, growth, settle : float, optional
        Outcome rules, as in :func:`dfa.simulate` (default bound: beyond the fastest start's own travel,
        :func:`dfa.analysis.simulation.divergence_bound`).
    wall : WallParams, optional
        The wall of every run (:mod:`dfa.model.wall`; ``Wall.of(...).params(T)`` or ``WallParams.of(...)``):
        computational delay, virtual damper, velocity filter, amplifier lag. Each point is then
        :func:`dfa.simulate` with ``wall=``. Default: the paper's spring without delay.

    Returns
    -------
    StabilityMap
        Outcome, amplitude and frequency of every point for each speed; ``.plot()`` draws it.

    Raises
    ------
    DFAValueError, DFATypeError
        If an input is out of range or not a number, a flag (``quantize``, ``preload``, ``progress``) is not
        True or False, or the map would not fit in memory.

    See Also
    --------
    simulate : One point of the map.
    contour_maps : The describing-function cycles over the same plane.
    load_map : Read a saved map.
    """
    m = check_mu(mu)
    speeds = _check_speeds(xi_dots)
    b0, b1 = check_range("beta_range", beta_range)
    check_damping_rate(b1, m, ("beta_range[1]", "mu"))  # the simulator's rule, at the map's largest β
    s0, s1 = check_range("sigma_range", sigma_range)
    g = check_int("grid", grid, minimum=2, fix="use at least 2 points per axis")
    n = check_int("samples", samples, minimum=1)
    w = check_wall(wall)
    jobs = check_jobs("n_jobs", n_jobs)
    how = check_choice("backend", backend, MAP_BACKENDS)
    quantize = check_bool("quantize", quantize, "pass True (with the encoder) or False (the linear spring)")
    preload = check_bool("preload", preload, "pass True (start from the spring preload) or False (from ξ0 = 0)")
    progress = check_bool("progress", progress, "pass True to show a progress bar, False for none")
    if not w.covers(Coverage.SURFACE_START):  # the approach's samples before contact come first
        from .approach import approach_samples

        n += approach_samples(w)
    starts = [map_start(m, v, preload, w, quantize) for v in speeds]
    if bound is None:
        bound = _map_bound(m, speeds, starts, w)
    rules = check_rules(bound, stable_amplitude, growth, settle)
    check_memory("grid", g, map_memory_bytes(g, len(speeds)), "lower grid (points per axis) or give fewer speeds")
    beta, sigma = np.linspace(b0, b1, g), np.linspace(s0, s1, g)
    pts_b, pts_s, x0, v0 = _points(beta, sigma, starts)
    if preload or not w.covers(Coverage.SURFACE_START):
        check_bound(rules[0], float(np.max(np.abs(x0))))  # the rule simulate() applies: the bound lies beyond ξ0
    workers = (os.cpu_count() or 1) if jobs == -1 else jobs
    chunks = _chunks(pts_b.size, workers, _chunk_cost(n, w))
    tail = (n, w, quantize, *rules)
    tasks = [(m, pts_b[c], pts_s[c], x0[c], v0[c], *tail) for c in chunks]
    _run_chunk(m, pts_b[:1], pts_s[:1], x0[:1], v0[:1], 1, *tail[1:])  # compile or load the kernel once, first

    label = f"stability map μ={m:g}"
    with progress_bar(total=pts_b.size, unit="run", desc=label, disable=not progress, leave=False) as bar:
        # any wall: the same chunks, in order (dfa._parallel), Ctrl-C cancels the pending ones
        results = run_in_order(_run_chunk, tasks, [c.size for c in chunks], workers, how, bar)
    codes, amps, freqs, contact = (gather(chunks, [r[k] for r in results]).reshape(len(speeds), g, g) for k in range(4))
    out = (codes.astype(np.int8), amps, freqs, n, quantize, preload)
    kinds = None if w.covers(Coverage.SURFACE_START) else contact.astype(np.int8)
    return StabilityMap(m, speeds, beta, sigma, *out, wall=w, contact=kinds)


def _check_speeds(xi_dots: ArrayLike) -> tuple[float, ...]:
    speeds = tuple(
        check_speed("xi_dot", v, "ticks per sample") for v in np.atleast_1d(np.asarray(xi_dots, dtype=object))
    )
    if not speeds:
        raise DFAValueError("xi_dots = [] is invalid: it must hold at least one initial speed")
    return speeds


def map_start(mu: float, speed: float, preload: bool, wall: WallParams, quantize: bool = True) -> tuple[float, float]:
    """(ξ0, ξ'0) of a map's runs at one speed: the impact at the wall's origin, its spring preload, or a one-sided
    wall's approach from free space (:func:`dfa.analysis.approach.approach_start`; the map's run length counts
    the approach's samples too).

    Raises
    ------
    DFAValueError
        For a preload with a one-sided wall (its runs start with the approach).
    """
    if not wall.covers(Coverage.SURFACE_START):
        if preload:
            raise DFAValueError(
                "preload = True is invalid with a one-sided wall: its runs start in free space with the approach; "
                "pass preload=False"
            )
        from .approach import approach_start

        x0, v0, _d = approach_start(speed, wall=wall, quantize=quantize)
        return x0, v0
    return (preload_position(mu, speed), 0.0) if preload else (0.0, speed)


def _map_bound(mu: float, speeds: Sequence[float], starts: Sequence[tuple[float, float]], wall: WallParams) -> float:
    """|ξ| past which a map's run diverged: beyond the fastest start's own travel
    (:func:`dfa.analysis.simulation.divergence_bound`), and beyond a one-sided wall's approach start."""
    if not wall.covers(Coverage.SURFACE_START):
        return max(divergence_bound(x, v, mu) for x, v in starts)
    return divergence_bound(0.0, float(np.max(np.abs(speeds))), mu)


def _points(beta: np.ndarray, sigma: np.ndarray, starts: Sequence[tuple[float, float]]) -> tuple[np.ndarray, ...]:
    """β, σ, ξ0, ξ'0 of every run: grid rows σ, columns β, one grid per start (:func:`map_start`, one per speed)."""
    bb, ss = np.meshgrid(beta, sigma)
    pts_b = np.tile(bb.ravel(), len(starts))
    pts_s = np.tile(ss.ravel(), len(starts))
    s = np.array(starts, dtype=float)
    return pts_b, pts_s, np.repeat(s[:, 0], bb.size), np.repeat(s[:, 1], bb.size)


def _chunk_cost(samples: int, wall: WallParams) -> float:
    """Planned cost of one point in spring-kernel samples (:data:`CHUNK_SAMPLES`, :data:`WALL_COST`)."""
    if wall.covers(Coverage.CLOSED_FORM):
        return float(samples)
    return samples * WALL_COST["lag" if wall.lag > 0 else "wall"]


def _chunks(total: int, workers: int, cost: float = 0.0) -> list[np.ndarray]:
    """Indices of the points in chunks: 16 per worker (progress and load balance), 64 in one thread, and more
    when a chunk would plan over :data:`CHUNK_SAMPLES` (``cost``: per point, from :func:`_chunk_cost`).

    The points are dealt out in turn (:func:`dfa._parallel.deal`: chunk i holds points i, i + N, … of N chunks),
    so that the chunks carry like work and the workers finish together.
    """
    nchunks = workers * 16 if workers > 1 else 64
    return deal(total, max(1, nchunks, math.ceil(total * cost / CHUNK_SAMPLES)))


def simulate_point(
    smap: StabilityMap, beta: float, sigma: float, *, bound: float | None = None
) -> tuple[SimulationResult, ...]:
    """The runs the map would hold at (β, σ) were it a grid point: one per speed, with the map's settings.

    Each is :func:`dfa.simulate` of (μ, β, σ) at the map's speed (or its spring preload), run length,
    wall and quantization, with the default outcome rules; :func:`stability_map` runs its grid points the
    same way (bit for bit). For a device's operating point, which rarely lies on the grid.

    Parameters
    ----------
    smap : StabilityMap
        The map (its μ, speeds, run length, wall and quantization).
    beta, sigma : float
        The point, dimensionless (>= 0).
    bound : float, optional
        Divergence bound (ticks); default :func:`stability_map`'s, beyond the fastest start's own travel.

    Returns
    -------
    tuple of SimulationResult
        One run per speed, in the order of :attr:`xi_dots` (nothing recorded).
    """
    from .simulation import simulate

    starts = [map_start(smap.mu, v, smap.preload, smap.wall, smap.quantize) for v in smap.xi_dots]
    if bound is None:
        bound = _map_bound(smap.mu, smap.xi_dots, starts, smap.wall)
    runs = []
    for x0, v0 in starts:
        runs.append(
            simulate(
                Loop.dimensionless(smap.mu, beta, sigma, smap.wall),
                v0,
                smap.samples,
                xi0=x0,
                quantize=smap.quantize,
                record=False,
                bound=bound,
            )  # fmt: skip
        )
    return tuple(runs)
