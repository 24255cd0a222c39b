"""Stability maps over the (β, σ) plane (paper Fig. 4).

Every grid point is an independent exact simulation (:func:`dfa.simulate`
without recording), so maps run in parallel with joblib in chunks of points
and the result does not depend on the number of jobs. A tqdm progress bar
reports the chunks as they finish.

Running on a dask cluster
-------------------------
joblib's dask backend sends the same chunks to a cluster (``pip install
'dfa[dask]'``)::

    from dask.distributed import Client
    import joblib
    client = Client("tcp://scheduler:8786")
    with joblib.parallel_config(backend="dask"):
        m = stability_map(100.0, [1, 2, 5, 10], grid=400)

Examples
--------
>>> m = stability_map(100.0, [2.0], grid=4, samples=2000, n_jobs=1, progress=False)
>>> m.outcome.shape, sorted(m.counts()[0])
((1, 4, 4), ['chatter', 'oscillating', 'rest', 'undecided', 'unstable'])

Outcome codes
-------------
``StabilityMap.outcome`` holds the kernel's codes, the index of the name in
:data:`dfa.simulation.OUTCOMES` (rules in :mod:`dfa.simulation`):

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

import os
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import _kernel
from ._io import atomic_open, check_memory
from .errors import (
    DFATypeError,
    DFAValueError,
    _fmt,
    check_delay,
    check_int,
    check_mu,
    check_nonnegative,
    check_positive,
    check_real,
)
from .simulation import OUTCOMES, _tail_length, preload_position

__all__ = ["StabilityMap", "stability_map", "load_map", "map_memory_bytes", "check_jobs"]

#: Planned peak memory per grid point and initial speed (bytes): four float inputs, three
#: float outputs in chunks and concatenated, the int8 outcome, with margin.
MAP_BYTES_PER_RUN = 96
#: ... and per grid point (the meshgrid axes).
MAP_BYTES_PER_POINT = 16


def map_memory_bytes(grid: int, n_speeds: int) -> int:
    """Estimated peak memory of :func:`stability_map` in bytes (grid² points × speeds)."""
    return int(grid) ** 2 * (MAP_BYTES_PER_POINT + MAP_BYTES_PER_RUN * int(n_speeds))


def check_jobs(name: str, jobs: object) -> int:
    """Validate a joblib job count: -1 (all cores) or 1 … os.cpu_count(); return it.

    Nothing is silently clipped: more jobs than cores is refused (it only adds
    processes and memory, and changes no result).
    """
    j = check_int(name, jobs)
    cores = os.cpu_count() or 1
    if j == 0 or j < -1:
        raise DFAValueError(f"{name} = {j} is invalid: it must be -1 (all cores) or a positive count")
    if j > cores:
        raise DFAValueError(
            f"{name} = {j} is invalid: this machine has {cores} cores; give at most {cores} (or -1 for all)"
        )
    return j


@dataclass(frozen=True)
class StabilityMap:
    """Outcome of the exact simulation over a (β, σ) grid for one μ and several initial speeds.

    Attributes
    ----------
    mu : float
        Dimensionless mass.
    xi_dots : tuple of float
        Initial speeds ξ'0 (ticks per sample); with ``preload`` the equivalent
        speeds of the spring preload (ξ'0 = 0, H_c(ξ0) = ½μξ'0²).
    beta, sigma : numpy.ndarray
        Grid axes.
    outcome : numpy.ndarray of int8, shape (len(xi_dots), len(sigma), len(beta))
        0 rest, 1 oscillating, 2 unstable, 3 chatter, 4 undecided (module
        docstring; :data:`dfa.simulation.OUTCOMES`).
    amplitude, frequency : numpy.ndarray
        Measured cycle amplitude (ticks) and frequency (rad per sample); NaN where not measured.
    samples, delay, quantize, preload
        Simulation settings.
    status : str
        ``"ok"``.
    """

    mu: float
    xi_dots: tuple
    beta: np.ndarray = field(repr=False)
    sigma: np.ndarray = field(repr=False)
    outcome: np.ndarray = field(repr=False)
    amplitude: np.ndarray = field(repr=False)
    frequency: np.ndarray = field(repr=False)
    samples: int
    delay: int = 0
    quantize: bool = True
    preload: bool = False
    status: str = "ok"

    def counts(self) -> list[dict[str, int]]:
        """Number of grid points per outcome, one dict per initial speed."""
        return [{name: int(np.sum(o == code)) for code, name in enumerate(OUTCOMES)} for o in self.outcome]

    def as_dict(self) -> dict[str, object]:
        """JSON-ready summary (grid, settings and counts per speed)."""
        return {
            "mu": self.mu,
            "xi_dots": list(self.xi_dots),
            "beta_range": [float(self.beta[0]), float(self.beta[-1])],
            "sigma_range": [float(self.sigma[0]), float(self.sigma[-1])],
            "grid": [int(self.beta.size), int(self.sigma.size)],
            "samples": self.samples,
            "delay": self.delay,
            "quantize": self.quantize,
            "preload": self.preload,
            "counts": [dict(xi_dot=v, **c) for v, c in zip(self.xi_dots, self.counts(), strict=False)],
        }

    def save(self, path: str | os.PathLike) -> Path:
        """Write the map to a ``.npz`` file (see :func:`load_map`), atomically.

        ``.npz`` is appended when ``path`` has another suffix (numpy's rule);
        the path written is returned.
        """
        p = Path(path)
        p = p if p.suffix == ".npz" else p.with_name(p.name + ".npz")
        with atomic_open(p, "wb") as fh:  # never a half-written map (dfa._io)
            np.savez_compressed(
                fh,
                mu=self.mu,
                xi_dots=np.asarray(self.xi_dots, dtype=float),
                beta=self.beta,
                sigma=self.sigma,
                outcome=self.outcome,
                outcome_names=np.array(OUTCOMES),
                amplitude=self.amplitude,
                frequency=self.frequency,
                settings=np.array([self.samples, self.delay, int(self.quantize), int(self.preload)], dtype=np.int64),
            )
        return p


def load_map(path: str | os.PathLike) -> StabilityMap:
    """Read a map written by :meth:`StabilityMap.save` (codes mapped through the file's ``outcome_names``)."""
    if not isinstance(path, (str, os.PathLike)):
        raise DFATypeError(
            f"path = {_fmt(path)} has type {type(path).__name__}: it must be the path of a .npz map file"
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
        return StabilityMap(
            mu=float(z["mu"]),
            xi_dots=tuple(float(v) for v in z["xi_dots"]),
            beta=z["beta"],
            sigma=z["sigma"],
            outcome=lut[z["outcome"]],
            amplitude=z["amplitude"],
            frequency=z["frequency"],
            samples=samples,
            delay=delay,
            quantize=bool(quantize),
            preload=bool(preload),
        )


def _run_chunk(mu, betas, sigmas, x0s, v0s, samples, delay, quantize, bound, stable_amplitude, growth, settle):
    n = betas.size
    codes = np.empty(n, dtype=np.int64)
    amps = np.empty(n)
    freqs = np.empty(n)
    _kernel.map_kernel(
        mu,
        betas,
        sigmas,
        x0s,
        v0s,
        samples,
        delay,
        quantize,
        bound,
        _tail_length(samples, mu),
        stable_amplitude,
        growth,
        settle,
        codes,
        amps,
        freqs,
    )
    return codes, amps, freqs


def _check_range(name: str, rng) -> tuple[float, float]:
    try:
        a, b = rng
    except (TypeError, ValueError):
        raise DFAValueError(f"{name} = {rng!r} is invalid: it must be a pair (low, high)") from None
    lo = check_nonnegative(f"{name}[0]", a)
    hi = check_nonnegative(f"{name}[1]", b)
    if not hi > lo:
        raise DFAValueError(f"{name} = ({lo}, {hi}) is invalid: it must satisfy low < high")
    return lo, hi


def stability_map(
    mu: float,
    xi_dots,
    *,
    beta_range=(0.0, 1.0),
    sigma_range=(0.0, 2.0),
    grid: int = 100,
    samples: int = 50_000,
    delay: int = 0,
    quantize: bool = True,
    preload: bool = False,
    n_jobs: int = -1,
    progress: bool = True,
    bound: float = 1.0e6,
    stable_amplitude: float = 1.0,
    growth: float = 1.25,
    settle: float = 1.0e-3,
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
    n_jobs : int
        joblib workers (-1: all cores; 1: in this process). The result does
        not depend on it.
    progress : bool
        Show a tqdm progress bar.
    bound, stable_amplitude, growth, settle
        Outcome rules, as in :func:`dfa.simulate`.

    Returns
    -------
    StabilityMap
    """
    m = check_mu(mu)
    speeds = tuple(
        abs(check_real("xi_dot", v, "give initial speeds in ticks per sample"))
        for v in np.atleast_1d(np.asarray(xi_dots, dtype=object))
    )
    if not speeds:
        raise DFAValueError("xi_dots = [] is invalid: it must hold at least one initial speed")
    b0, b1 = _check_range("beta_range", beta_range)
    s0, s1 = _check_range("sigma_range", sigma_range)
    g = check_int("grid", grid, minimum=2, fix="use at least 2 points per axis")
    n = check_int("samples", samples, minimum=1)
    d = check_delay(delay)
    jobs = check_jobs("n_jobs", n_jobs)
    bnd = check_positive("bound", bound)
    sa = check_nonnegative("stable_amplitude", stable_amplitude)
    gr = check_positive("growth", growth)
    if gr <= 1.0:
        raise DFAValueError(f"growth = {gr!r} is invalid: it must be > 1")
    st = check_nonnegative("settle", settle)
    check_memory("grid", g, map_memory_bytes(g, len(speeds)), "lower grid (points per axis) or give fewer speeds")

    beta = np.linspace(b0, b1, g)
    sigma = np.linspace(s0, s1, g)
    bb, ss = np.meshgrid(beta, sigma)  # (σ, β) layout: rows σ, columns β
    pts_b = np.tile(bb.ravel(), len(speeds))
    pts_s = np.tile(ss.ravel(), len(speeds))
    if preload:
        x0 = np.repeat([preload_position(m, v) for v in speeds], bb.size)
        v0 = np.zeros_like(x0)
    else:
        x0 = np.zeros(pts_b.size)
        v0 = np.repeat(np.asarray(speeds, dtype=float), bb.size)
    total = pts_b.size
    workers = (os.cpu_count() or 1) if jobs == -1 else jobs
    nchunks = max(1, min(total, workers * 16)) if workers > 1 else max(1, min(total, 64))
    bounds = np.linspace(0, total, nchunks + 1).astype(int)
    chunks = [slice(bounds[i], bounds[i + 1]) for i in range(nchunks) if bounds[i + 1] > bounds[i]]
    args = (m,)
    tail = (n, d, bool(quantize), bnd, sa, gr, st)
    # compile (or load from the on-disk cache) once here, before the workers start
    _run_chunk(
        m, pts_b[:1].copy(), pts_s[:1].copy(), x0[:1].copy(), v0[:1].copy(), 1, d, bool(quantize), bnd, sa, gr, st
    )

    from tqdm.auto import tqdm

    bar = tqdm(total=total, unit="run", desc=f"stability map μ={m:g}", disable=not progress, leave=False)
    results = []
    try:
        if workers == 1:
            for c in chunks:
                results.append(_run_chunk(*args, pts_b[c], pts_s[c], x0[c], v0[c], *tail))
                bar.update(c.stop - c.start)
        else:
            from joblib import Parallel, delayed

            # never more workers than chunks (same result, fewer processes)
            par = Parallel(n_jobs=min(workers, len(chunks)), return_as="generator")
            gen = par(delayed(_run_chunk)(*args, pts_b[c], pts_s[c], x0[c], v0[c], *tail) for c in chunks)
            try:
                for c, res in zip(chunks, gen, strict=False):  # the generator yields in submission order
                    results.append(res)
                    bar.update(c.stop - c.start)
            finally:
                gen.close()  # on an interruption: cancel the pending chunks, stop the workers
    finally:
        bar.close()
    codes = np.concatenate([r[0] for r in results]).astype(np.int8)
    amps = np.concatenate([r[1] for r in results])
    freqs = np.concatenate([r[2] for r in results])
    shape = (len(speeds), g, g)
    return StabilityMap(
        mu=m,
        xi_dots=speeds,
        beta=beta,
        sigma=sigma,
        outcome=codes.reshape(shape),
        amplitude=amps.reshape(shape),
        frequency=freqs.reshape(shape),
        samples=n,
        delay=d,
        quantize=bool(quantize),
        preload=bool(preload),
    )
