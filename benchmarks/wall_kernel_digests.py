"""Digests of the controller kernel's outputs on a seeded sweep of walls: compare a kernel edit with the code before.

Each case (a random wall: damper, delay, filter, amplifier lag, force limit, travel, passivity controller with or
without a window, one-sided wall and push; random device groups, start, length, tail and encoder) runs through
:func:`dfa.core.wall_kernel.run_wall_kernel` with and without period skipping,
:func:`~dfa.core.wall_kernel.outcome_wall_kernel`, a recorded :func:`~dfa.core.wall_kernel.simulate_wall_kernel`
and :func:`~dfa.core.wall_kernel.applied_forces`; the digest covers every returned value and every output array
byte for byte. Run it on both commits (each in its own checkout: numba compiles the kernel of that checkout) and
compare the two files::

    python benchmarks/wall_kernel_digests.py before.json 43 1500   # on the old commit
    python benchmarks/wall_kernel_digests.py after.json 43 1500    # on the new one
    cmp before.json after.json

Digests are bit for bit: compare files made on one machine (libm's exp and log may differ elsewhere).
"""

import hashlib
import json
import sys

import numpy as np

from dfa.core import kernel, wall_kernel
from dfa.model.elements import OneSided, PassivityController, Push
from dfa.model.wall import WallParams


def cases(seed, count):
    """``count`` seeded cases: (μ, β, σ), (ξ0, ξ'0), (n, tail, bound, quantize), the wall's groups."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        groups = WallParams.of(
            damping=float(rng.choice([0.0, rng.uniform(0, 1.5)])),
            delay=int(rng.integers(0, 4)),
            cutoff=None if rng.integers(2) else float(rng.uniform(0.01, 0.45)),
            lag=0.0 if rng.integers(3) else float(rng.uniform(0.05, 1.0)),
            force_limit=None if rng.integers(4) else float(rng.uniform(0.5, 20.0)),
            travel=None if rng.integers(5) else float(rng.uniform(5, 50.0)),
        ).groups
        extra = []
        if rng.integers(4):
            extra.append(
                (
                    PassivityController,
                    (
                        0 if rng.integers(3) else int(rng.integers(1, 60)),
                        None if not rng.integers(5) else float(rng.choice([0.2, 1.0, rng.uniform(0.05, 3.0)])),
                    ),
                )
            )
        if not rng.integers(5):
            extra.append((OneSided, float(rng.uniform(-0.5, 0.5))))
            if rng.integers(2):
                extra.append((Push, float(rng.uniform(0.0, 0.8))))
        wall = WallParams((*extra, *groups))
        mu = float(rng.choice([2.0, 10.0, 100.0, rng.uniform(0.5, 300)]))
        beta, sigma = float(rng.uniform(0, 2)), float(rng.choice([0.0, rng.uniform(0, 0.6)]))
        x0 = float(rng.choice([0.0, rng.uniform(-3, 3)]))
        v0 = float(rng.uniform(-3, 3))
        n = int(rng.choice([7, 777, 6001, 12001]))
        tail = int(rng.choice([0, n // 4, n // 3 + 1, n]))
        quantize = bool(rng.integers(5) > 0)
        yield (mu, beta, sigma), (x0, v0), (n, tail, 1e6, quantize), wall


def digest(dev, ini, run, wall):
    """The first 16 hex digits of a SHA-256 of every output of one case (module docstring)."""
    h = hashlib.sha256()
    table = wall.kernel_table()
    e = np.empty(0)
    for skip in (True, False):
        s = np.empty(kernel.NSTATS)
        h.update(repr(wall_kernel.run_wall_kernel(dev, ini, run, table, e, e, s, skip)).encode())
        h.update(s.tobytes())
    s = np.empty(kernel.NSTATS)
    h.update(repr(wall_kernel.outcome_wall_kernel(dev, ini, run, table, s, (1.0, 1.25, 1e-3))).encode())
    h.update(s.tobytes())
    n = run[0]
    rx, rv, s = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    h.update(repr(wall_kernel.simulate_wall_kernel(dev, ini, run, table, rx, rv, s)).encode())
    h.update(rx.tobytes())
    h.update(rv.tobytes())
    h.update(s.tobytes())
    out, en, ct = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)
    wall_kernel.applied_forces(rx, table, run[3], out, en, ct)
    h.update(out.tobytes())
    h.update(en.tobytes())
    h.update(ct.tobytes())
    return h.hexdigest()[:16]


if __name__ == "__main__":
    out = []
    for c in cases(int(sys.argv[2]), int(sys.argv[3])):
        try:
            out.append(digest(*c))
        except Exception as exc:
            out.append("error " + type(exc).__name__)
    json.dump(out, open(sys.argv[1], "w"))
    print(len(out), sum(o.startswith("error") for o in out))
