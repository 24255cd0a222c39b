"""Independent runs of the exact simulator in one compiled call, each with its own length, bound and tail.

:func:`batch_kernel` is what :func:`dfa.analysis.simulation.run_points` (stability maps, :func:`dfa.analysis.simulation.simulate_batch`)
and the K_max searches (:func:`dfa.analysis.limits.kmax.simulate_points`) run for the spring: each run bit for bit
:func:`dfa.core.kernel.simulate_kernel` alone, the GIL released (callers run chunks on threads). It keeps two runs in
flight (:func:`dfa.core.pair.pair_kernel`), so that their dependency chains overlap: about 0.8 of the time of one run
after the other (:func:`dfa.core.kernel.serial_kernel`) on the points of a stability map (``reports/benchmarks.md``).

:func:`batch_wall_kernel` runs runs with a wall one after the other (each run its own kernel table,
:meth:`dfa.model.wall.WallParams.kernel_table`; each :func:`dfa.core.wall_kernel.simulate_wall_kernel` alone,
bit for bit): :func:`dfa.analysis.limits.zwidth.z_width` runs a chunk of grid points per call. :func:`batch_wall_outcomes`
runs them for their outcomes alone (:func:`dfa.core.wall_kernel.outcome_wall_kernel`: the outcome bit for bit, the
other statistics within a proven bound), what the searches read, two in flight where the wall allows
(:mod:`dfa.core.wall_pair`).

Developers: numba keys the cached kernels of this module on this file alone, while they compile in
:mod:`dfa.core.kernel` and :mod:`dfa.core.wall_kernel`; dfa's cache folder is named after every file of
:mod:`dfa.core` (:mod:`dfa.core.cache`), so an edit there takes a fresh folder. With your own ``NUMBA_CACHE_DIR``,
clear it after such an edit.
"""

from __future__ import annotations

import numpy as np

from .jit import njit
from .kernel import BatchRuns, Devices, FloatArray, IntArray, Rules, Starts
from .pair import pair_kernel
from .wall_kernel import simulate_wall_kernel
from .wall_pair import pair_wall_outcomes

__all__ = ["batch_kernel", "batch_wall_kernel", "batch_wall_outcomes"]


def batch_kernel(
    devices: Devices, initials: Starts, runs: BatchRuns, delay: int, stats: FloatArray, done: IntArray, rest: IntArray
) -> None:
    """Independent runs, two in flight: run i is :func:`dfa.core.kernel.simulate_kernel` of its own inputs, bit for bit.

    Run i has (μ, β, σ) = (``devices[0][i]``, ``devices[1][i]``, ``devices[2][i]``), (ξ0, ξ'0) =
    (``initials[0][i]``, ``initials[1][i]``) and, from ``runs`` = (ns, tail_lens, bounds, quantize),
    ``ns[i]`` samples, tail ``tail_lens[i]`` and bound ``bounds[i]`` (ticks); every run has the delay
    ``delay`` (samples) and the encoder ``quantize``. ``stats[i]`` (NSTATS), ``done[i]`` and ``rest[i]``
    receive what :func:`dfa.core.kernel.simulate_kernel` returns for it (nothing recorded).

    A Python function, not a kernel: :func:`dfa.core.pair.pair_kernel` compiles the loops of a delay only when
    ``delay`` >= 1.
    """
    pair_kernel(devices, initials, runs, delay, stats, done, rest)


@njit(cache=True, nogil=True)
def batch_wall_kernel(
    devices: Devices,
    initials: Starts,
    runs: BatchRuns,
    tables: FloatArray,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
) -> None:
    """Independent runs with a wall, one after the other: run i is
    :func:`dfa.core.wall_kernel.simulate_wall_kernel` of its own inputs.

    As :func:`batch_kernel` (run i: ``ns[i]`` samples, tail ``tail_lens[i]``, bound ``bounds[i]``), and run i
    has the wall of the kernel table ``tables[i]`` (one table a row, each row padded after its last block:
    :func:`dfa.core.wall_kernel.stack_tables`), its delay included. ``stats[i]`` (NSTATS), ``done[i]`` and
    ``rest[i]`` receive what :func:`dfa.core.wall_kernel.simulate_wall_kernel` returns for it (nothing recorded).
    """
    e = np.empty(0)
    mus, betas, sigmas = devices
    x0s, v0s = initials
    ns, tail_lens, bounds, quantize = runs
    for i in range(mus.shape[0]):
        done[i], rest[i] = simulate_wall_kernel(
            (mus[i], betas[i], sigmas[i]), (x0s[i], v0s[i]), (ns[i], tail_lens[i], bounds[i], quantize), tables[i],
            e, e, stats[i],
        )  # fmt: skip


def batch_wall_outcomes(
    devices: Devices,
    initials: Starts,
    runs: BatchRuns,
    tables: FloatArray,
    rules: Rules,
    stats: FloatArray,
    done: IntArray,
    rest: IntArray,
) -> None:
    """:func:`batch_wall_kernel` for the runs' outcomes alone: run i has the outcome of
    :func:`dfa.core.wall_kernel.outcome_wall_kernel` of its own inputs with the outcome ``rules`` (stable
    amplitude, growth, settle) of :func:`dfa.core.kernel.classify`, whose outcome of ``stats[i]`` is the
    every-sample run's.

    Two runs in flight where their walls allow (:func:`dfa.core.wall_pair.pair_wall_outcomes`); a Python function,
    not a kernel, so that the lanes compile in their own module's cache alone.
    """
    pair_wall_outcomes(devices, initials, runs, tables, rules, stats, done, rest)
