"""Compile the kernels the suite runs before it starts, each once, in parallel processes (``make test``).

On a cold kernel cache every pytest worker compiles each kernel it needs on its first call, and the workers of
``pytest -n 2`` start with tests that need the same big kernels: both compile them at the same time, about
100 s of each worker's first minutes. Here the kernels compile once, in two processes that share nothing but
the cache folder (:mod:`dfa.core.cache`: the same folder for every process started from this checkout), and
the workers then load them from it. With a warm cache this takes the time of loading them (a few seconds).

The work is split where it depends: the wall's kernel (:func:`dfa.core.wall_kernel._advance`, about 25 s)
must be compiled before the two-runs-in-flight lanes that call it (:mod:`dfa.core.wall_pair`, about 20 s), so
that chain is one process; the spring's kernels and the rest are the other. Each group makes the calls the
package makes (its public functions, small cases), so the kernels compile with the argument types the suite
uses; a kernel it misses is compiled by the suite as before (``tests/test_compile_kernels.py`` checks the list).

Usage: ``python tests/compile_kernels.py`` (both groups, one process each when there are 2 cores or more) or
``python tests/compile_kernels.py GROUP`` (one group in this process).
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Callable

# a run of the wall's kernel, and its lanes: the Impulse with a damper (the undecided-extension test's point)
K_IMPULSE, V_IMPULSE = 257.14, 0.05


def wall_chain() -> None:
    """The wall's kernel, then the searches' lanes that call it (one chain: each needs the one before)."""
    from dfa.analysis.limits.runs import simulate_points
    from dfa.analysis.simulation import simulate
    from dfa.model.catalogue import get_device
    from dfa.model.elements import PassivityController
    from dfa.model.wall import Wall

    dev = get_device("impulse").device
    p, xd = dev.params(K_IMPULSE), dev.xi_dot(V_IMPULSE)
    damped = Wall.of(K_IMPULSE, damping=1.0, delay=1).params(dev.period)
    simulate(p.mu, p.beta, p.sigma, xd, samples=2_000, wall=damped, record=False)  # simulate_wall_kernel
    controlled = Wall(K_IMPULSE, (PassivityController(),)).params(dev.period)
    simulate_points([(p.mu, p.beta, p.sigma, 0.0, xd)] * 2, [controlled] * 2, 2_000)  # pair_wall_outcomes


def spring_and_rest() -> None:
    """The spring's kernels (one run, runs in flight with and without a delay) and the smaller ones: the describing
    function's and the cycle search's (the everyday answer, ``dfa stiffness``), then :func:`scalar_kernels`."""
    import contextlib
    import io

    from dfa.analysis.limits.runs import simulate_points
    from dfa.analysis.observer import force_error
    from dfa.analysis.simulation import simulate
    from dfa.cli.app import main as cli
    from dfa.model.catalogue import get_device
    from dfa.model.wall import WallParams

    dev = get_device("delta").device
    p, xd = dev.params(2_000.0), dev.xi_dot(0.1)
    run = simulate(p.mu, p.beta, p.sigma, xd, samples=2_000, wall=WallParams.of(delay=1))  # simulate_kernel
    force_error(run)  # applied_forces, the replay of the wall's force
    for delay in (0, 1):  # pair_free_kernel, pair_delayed_kernel
        simulate_points([(p.mu, p.beta, p.sigma, 0.0, xd)] * 2, [WallParams.of(delay=delay)] * 2, 2_000)
    with contextlib.redirect_stdout(io.StringIO()):
        cli(["stiffness", "--device", "delta", "--velocity", "0.1"])
    scalar_kernels()


def scalar_kernels() -> None:
    """Kernels of a few seconds each that the tests also call directly: one sample with the amplifier lag and with
    the hand, the amplifier's sampled lag, the quantizer's inverse describing function, the force replay on a
    writable record (the export's check)."""
    import numpy as np

    from dfa.analysis.describing import quantizer_df_inverse
    from dfa.core import oscillator, wall_kernel, zohlag
    from dfa.model.wall import WallParams

    wall_kernel.lag_sample(0.0, 1.0, 0.0, 0.0, 2.0, 0.5, 0.1, 0.5)
    oscillator.hand_sample(0.0, 1.0, 0.0, 2.0, 0.5, 0.1, 0.2)
    zohlag.amplifier_zoh(0.5, 2.0)
    quantizer_df_inverse(0.5)
    xs, out, energy, control = np.zeros(4), np.empty(4), np.empty(4), np.empty(4)
    wall_kernel.applied_forces(xs, WallParams.of(delay=1).kernel_table(), True, out, energy, control)


GROUPS: dict[str, Callable[[], None]] = {"wall_chain": wall_chain, "spring_and_rest": spring_and_rest}


def main(argv: list[str]) -> int:
    """Run the groups named in ``argv`` here, or every group in a process of its own; returns the exit code."""
    if argv:
        for name in argv:
            GROUPS[name]()
        return 0
    start = time.perf_counter()
    if (os.cpu_count() or 1) < 2:
        main(list(GROUPS))
    else:
        procs = [subprocess.Popen([sys.executable, __file__, name]) for name in GROUPS]
        if any([p.wait() != 0 for p in procs]):  # a list: every process waited for
            print("compile_kernels: a group failed (the suite compiles what it needs itself)", file=sys.stderr)
            return 1
    print(f"compile_kernels: the suite's kernels compiled or loaded in {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
