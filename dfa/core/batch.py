"""Independent runs of the exact simulator in one compiled call, each with its own length, bound and tail.

:func:`batch_kernel` is what :func:`dfa.analysis.simulation.run_points` (stability maps, :func:`dfa.analysis.simulation.simulate_batch`)
and the K_max searches (:func:`dfa.analysis.limits.kmax.simulate_points`) run for the spring: each run bit for bit
:func:`dfa.core.kernel.simulate_kernel` alone, the GIL released (callers run chunks on threads). It keeps two runs in
flight (:func:`dfa.core.pair.pair_kernel`), so that their dependency chains overlap: about 0.8 of the time of one run
after the other (:func:`dfa.core.kernel.serial_kernel`) on the points of a stability map (``reports/benchmarks.md``).

:func:`batch_wall_kernel` runs runs with a controller one after the other (each run its own damper, filter and lag;
each :func:`dfa.core.wall_kernel.simulate_wall_kernel` alone, bit for bit): :func:`dfa.analysis.limits.zwidth.z_width` runs a chunk of
grid points per call.

Developers: numba keys the cached kernels of this module on this file alone, while they compile in
:mod:`dfa.core.kernel` and :mod:`dfa.core.wall_kernel`; dfa's cache folder is named after every file of
:mod:`dfa.core` (:mod:`dfa.core.cache`), so an edit there takes a fresh folder. With your own ``NUMBA_CACHE_DIR``,
clear it after such an edit.
"""

from __future__ import annotations

import numpy as np

from .jit import njit
from .kernel import BoolArray, FloatArray, IntArray
from .pair import pair_kernel
from .wall_kernel import simulate_wall_kernel

__all__ = ["batch_kernel", "batch_wall_kernel"]


def batch_kernel(
    mus: FloatArray,
    betas: FloatArray,
    sigmas: FloatArray,
    x0s: FloatArray,
    v0s: FloatArray,
    ns: IntArray,
    delay: int,
    quantize: bool,
    bounds: FloatArray,
    tail_lens: IntArray,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
) -> None:
    """Independent runs, two in flight: run i is :func:`dfa.core.kernel.simulate_kernel` of its own inputs, bit for bit.

    Run i has (μ, β, σ, ξ0, ξ'0) = (``mus[i]``, …, ``v0s[i]``), ``ns[i]`` samples, bound ``bounds[i]`` and
    tail ``tail_lens[i]``; every run has the delay ``delay``. ``stats[i]`` (NSTATS), ``done[i]`` and
    ``rest[i]`` receive what :func:`dfa.core.kernel.simulate_kernel` returns for it (nothing recorded).

    A Python function, not a kernel: :func:`dfa.core.pair.pair_kernel` compiles the loops of a delay only when
    ``delay`` >= 1.
    """
    pair_kernel(mus, betas, sigmas, x0s, v0s, ns, delay, quantize, bounds, tail_lens, stats, done, rest)


@njit(cache=True, nogil=True)
def batch_wall_kernel(
    mus: FloatArray, betas: FloatArray, sigmas: FloatArray, x0s: FloatArray, v0s: FloatArray, ns: IntArray,
    delay: int, quantize: bool, bounds: FloatArray, tail_lens: IntArray,
    dampings: FloatArray, poles: FloatArray, filtered: BoolArray, lags: FloatArray, springs: FloatArray,
    onesided: BoolArray, surfaces: FloatArray, pushes: FloatArray, pcs: BoolArray, windows: IntArray,
    limits: FloatArray, stats: FloatArray, done: IntArray, rest: IntArray,
) -> None:  # fmt: skip
    """Independent runs with a controller, one after the other: run i is
    :func:`dfa.core.wall_kernel.simulate_wall_kernel` of its own inputs.

    As :func:`batch_kernel` (run i: ``ns[i]`` samples, bound ``bounds[i]``, tail ``tail_lens[i]``; one
    ``delay`` for all), and run i has the controller (β_B, a, filtered, α, κ_h, one-sided, s, p) = (``dampings[i]``, ``poles[i]``,
    ``filtered[i]``, ``lags[i]``, ``springs[i]``, ``onesided[i]``, ``surfaces[i]``, ``pushes[i]``) (:func:`dfa.analysis.simulation._controller_args` of its WallParams).
    ``stats[i]`` (NSTATS), ``done[i]`` and ``rest[i]`` receive what
    :func:`dfa.core.wall_kernel.simulate_wall_kernel` returns for it (nothing recorded).
    """
    e = np.empty(0)
    for i in range(mus.shape[0]):
        done[i], rest[i] = simulate_wall_kernel(
            mus[i], betas[i], sigmas[i], x0s[i], v0s[i], ns[i], delay, quantize, bounds[i], tail_lens[i],
            dampings[i], poles[i], filtered[i], lags[i], springs[i], onesided[i], surfaces[i], pushes[i], pcs[i],
            windows[i], limits[i], e, e, stats[i],
        )  # fmt: skip
