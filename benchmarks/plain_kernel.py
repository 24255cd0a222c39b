"""A plain, independent exact kernel of the sampled loop: the baseline of issue 16's speed goal.

Written the straightforward way, independently of :mod:`dfa.core.kernel`: per
sample, read the encoder, shift the delay history, and integrate
μξ'' + βξ' + σ sgn ξ' = φ exactly over the sample (paper eq. 4-5) with the
stick-slip logic, computing the exponential factors as it goes; stop at rest
or past the bound. No statistics, no recording. Same model, so the same
trajectory to rounding (``tests/test_batch_kernel.py`` checks the final
states against :func:`dfa.simulate`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit


@njit(cache=True)
def _p1(u):
    return -math.expm1(-u) / u if u > 0.0 else 1.0


@njit(cache=True)
def _p2(u):
    if u > 1e-3:
        return (math.expm1(-u) + u) / (u * u)
    return 0.5 - u / 6.0 + u * u / 24.0 - u * u * u / 120.0


@njit(cache=True)
def plain_kernel(mu, beta, sigma, x0, v0, n, delay, quantize, bound):
    """Run up to ``n`` samples; return (samples done, ξ, ξ')."""
    hist = np.full(delay + 1, -(math.floor(x0) + 0.5) if quantize else -x0)
    x = x0
    v = v0
    r = beta / mu
    for h in range(n):
        for i in range(delay):
            hist[i] = hist[i + 1]
        hist[delay] = -(math.floor(x) + 0.5) if quantize else -x
        phi = hist[0]
        if v == 0.0 and abs(phi) <= sigma:
            if np.all(hist == phi):
                return h, x, v
            continue
        s = 1.0 if v > 0.0 or (v == 0.0 and phi > 0.0) else -1.0
        a = (phi - sigma * s) / mu
        xn = x + v * _p1(r) + a * _p2(r)
        vn = v * math.exp(-r) + a * _p1(r)
        if vn * s <= 0.0 and v != 0.0 and a != 0.0:  # ξ' reaches 0 at t* in this sample
            t = -v / a if r == 0.0 else math.log1p(-v * r / a) / r
            t = min(t, 1.0)
            x = x + v * t * _p1(r * t) + a * t * t * _p2(r * t)
            v = 0.0
            if abs(phi) > sigma:
                s = 1.0 if phi > 0.0 else -1.0
                a = (phi - sigma * s) / mu
                x = x + a * (1.0 - t) ** 2 * _p2(r * (1.0 - t))
                v = a * (1.0 - t) * _p1(r * (1.0 - t))
        else:
            x = xn
            v = vn
        if not abs(x) <= bound:
            return h + 1, x, v
    return n, x, v
