"""Runs that record the storage function S = ½μξ'² + ½ξ² (paper eq. 18-19), for the soundness check.

:func:`storage_runs` simulates a list of points with the spring kernel (each with its own delay and encoder
setting) and keeps, for each, the largest relative growth of S over its samples: the fast path of the
spring's walls in :mod:`dfa.studies.soundness`, which checks a passivity verdict against it.
"""

from __future__ import annotations

import numpy as np

from . import kernel
from .jit import njit
from .kernel import BoolArray, FloatArray, IntArray

__all__ = ["storage_runs"]


@njit(cache=True)
def storage_runs(
    mus: FloatArray,
    betas: FloatArray,
    sigmas: FloatArray,
    x0s: FloatArray,
    v0s: FloatArray,
    ns: IntArray,
    delays: IntArray,
    quantized: BoolArray,
    ratio: FloatArray,
    codes: IntArray,
    worst_sample: IntArray,
) -> None:
    """Simulate every point (recording ξ, ξ') and the largest S(h)/S(0) − 1 over its samples.

    Point i is :func:`dfa.core.kernel.simulate_kernel` of (``mus[i]``, ``betas[i]``, ``sigmas[i]``, ``x0s[i]``,
    ``v0s[i]``) over ``ns[i]`` samples with the delay ``delays[i]`` (samples), the encoder ``quantized[i]``,
    bound 10⁶ and the default outcome rules;
    ``codes[i]`` receives its outcome code, ``ratio[i]`` the largest S(h)/S(0) − 1 with S = ½μξ'² + ½ξ² (a
    sample past the bound, and every NaN sample after it, counts as growth: inf) and ``worst_sample[i]`` the sample where it occurs.
    """
    nmax = 0
    for i in range(ns.shape[0]):
        nmax = max(nmax, ns[i])
    rx = np.empty(nmax + 1)
    rv = np.empty(nmax + 1)
    empty2 = np.empty((0, 4))
    stats = np.empty(kernel.NSTATS)
    for i in range(ns.shape[0]):
        n = ns[i]
        mu = mus[i]
        tail = min(8192, max(2, n // 4))
        device, initial, run = (mu, betas[i], sigmas[i]), (x0s[i], v0s[i]), (n, tail, 1.0e6, quantized[i])
        done, rest = kernel.simulate_kernel(device, initial, run, delays[i], rx[: n + 1], rv[: n + 1], empty2, stats)
        c, _a, _f, _c, _fpp = kernel.classify(n, done, rest, stats, 1.0, 1.25, 1.0e-3, quantized[i], mu)
        codes[i] = c
        s0 = 0.5 * mu * v0s[i] * v0s[i] + 0.5 * x0s[i] * x0s[i]
        worst = -np.inf
        at = 0
        for h in range(1, done + 1):
            s = 0.5 * mu * rv[h] * rv[h] + 0.5 * rx[h] * rx[h]
            r = (s - s0) / s0 if s0 > 0.0 else (np.inf if s > 0.0 else 0.0)
            if not abs(rx[h]) <= 1.0e6:  # past the bound (or NaN after it): growth without limit
                r = np.inf
            if not r <= worst:
                worst = r
                at = h
        ratio[i] = worst if done >= 1 else 0.0
        worst_sample[i] = at
