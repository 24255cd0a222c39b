"""Compiled open loop: the device driven by a given sequence of held forces (identification from logs).

The device of paper eq. 4 without the wall's feedback: over sample h the force φ_h is held (zero-order hold)
and the device moves exactly as in the simulator (:func:`dfa.core.kernel.step`: stick-slip included)::

    μ ξ'' + β ξ' + σ sgn(ξ') = φ_h    on [h, h + 1)

:func:`open_loop_kernel` returns the position ξ at every sample instant: what an encoder reads, before
quantization. :mod:`dfa.analysis.identify` fits (μ, β, σ) of a logged run with it.

Examples
--------
>>> import numpy as np
>>> xs = np.empty(3)
>>> open_loop_kernel(0.0, 0.0, np.array([2.0, 2.0, 2.0]), 1.0, 0.0, 0.0, xs)  # μ ξ'' = 2 from rest: ξ = τ²
>>> [float(round(x, 12)) for x in xs]
[0.0, 1.0, 4.0]
"""

from __future__ import annotations

import numpy as np

from .jit import njit
from .kernel import FloatArray, IntArray, sample_constants, step

__all__ = ["open_loop_kernel", "segments_kernel"]


def open_loop_kernel(
    x0: float, v0: float, phis: FloatArray, mu: float, beta: float, sigma: float, out: FloatArray
) -> None:
    """Positions ξ at the sample instants 0, 1, …, n − 1 from (ξ0, ξ'0) under the held forces ``phis``.

    ``out[h]`` is ξ(h) (``out[0] = x0``); the force ``phis[h]`` acts over [h, h + 1) for h < n − 1 (the last
    force acts after the last position and is not used). A velocity exactly 0 with |φ| <= σ sticks. The one
    segment of :func:`segments_kernel`.
    """
    segments_kernel(np.array([x0]), np.array([v0]), np.zeros(1, dtype=np.int64), phis, mu, beta, sigma, out)


@njit(cache=True, nogil=True)
def segments_kernel(
    x0s: FloatArray,
    v0s: FloatArray,
    starts: IntArray,
    phis: FloatArray,
    mu: float,
    beta: float,
    sigma: float,
    out: FloatArray,
) -> None:
    """:func:`open_loop_kernel` restarted at each segment: segment j covers samples ``starts[j]`` to
    ``starts[j + 1] - 1`` (the last to the end) and starts from (``x0s[j]``, ``v0s[j]``); the force
    ``phis[h]`` is held over [h, h + 1) (stick when a velocity exactly 0 meets |φ| <= σ)."""
    k = sample_constants(mu, beta)
    n = out.shape[0]
    for j in range(starts.shape[0]):
        end = starts[j + 1] if j + 1 < starts.shape[0] else n
        x, v = x0s[j], v0s[j]
        for h in range(starts[j], end):
            out[h] = x
            if h + 1 < end:
                x, v, _xr, _t, _a, _a2, _tr, _s = step(x, v, phis[h], mu, sigma, k)
