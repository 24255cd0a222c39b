"""Compiled open loop: the device driven by a given sequence of held forces (identification from logs).

The device of paper eq. 4 without the wall's feedback: over sample h the force φ_h is held (zero-order hold)
and the device moves exactly as in the simulator (:func:`dfa.core.kernel.step`: stick-slip included)::

    μ ξ'' + β ξ' + σ sgn(ξ') = φ_h    on [h, h + 1)

:func:`open_loop_kernel` returns the position ξ at every sample instant: what an encoder reads, before
quantization. :mod:`dfa.analysis.identify` fits (μ, β, σ) of a logged run with it: :func:`segments_jacobian` runs
the fit's segments for several moved parameter sets in one call (its forward differences), :func:`block_normal` sums the fit's
block-arrow normal equations.

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

__all__ = ["open_loop_kernel", "segments_kernel", "segments_jacobian", "block_normal"]


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
def segments_jacobian(
    x0s: FloatArray,
    v0s: FloatArray,
    starts: IntArray,
    phis: FloatArray,
    params: FloatArray,
    target: FloatArray,
    weights: FloatArray,
    r: FloatArray,
    steps: FloatArray,
    out: FloatArray,
) -> None:
    """Forward differences of a multiple-shooting fit's residuals r = (ξ − target) w, one column per moved
    parameter set k: the segments (as :func:`segments_kernel`) start from (``x0s[k, j]``, ``v0s[k, j]``), the
    force over [h, h + 1) is ``phis[h] + params[k, 0]`` and the device (μ, β, σ) = ``params[k, 1:4]``;
    ``out[h, k]`` = ((ξ_k(h) − target[h]) w[h] − r[h]) / ``steps[k, j]`` (j: the segment of sample h)."""
    n = out.shape[0]
    for k in range(out.shape[1]):
        offset, mu, sigma = params[k, 0], params[k, 1], params[k, 3]
        const = sample_constants(mu, params[k, 2])
        for j in range(starts.shape[0]):
            end = starts[j + 1] if j + 1 < starts.shape[0] else n
            x, v, step_k = x0s[k, j], v0s[k, j], steps[k, j]
            for h in range(starts[j], end):
                out[h, k] = ((x - target[h]) * weights[h] - r[h]) / step_k
                if h + 1 < end:
                    x, v, _xr, _t, _a, _a2, _tr, _s = step(x, v, phis[h] + offset, mu, sigma, const)


@njit(cache=True, nogil=True)
def block_normal(
    jac: FloatArray, r: FloatArray, starts: IntArray, a: FloatArray, b: FloatArray, c: FloatArray, gr: FloatArray,
    lr: FloatArray,
) -> None:  # fmt: skip
    """The block-arrow normal equations of a multiple-shooting fit, summed sample by sample. ``jac`` (n × 6): the
    columns of 4 global parameters G, then each sample's own segment's 2 (L); ``a`` = GᵀG (4 × 4), per segment j
    ``b[j]`` = G_jᵀ L_j (4 × 2) and ``c[j]`` = L_jᵀ L_j (2 × 2), ``gr`` = Gᵀr, ``lr[j]`` = L_jᵀ r (G_j, L_j: the
    rows from ``starts[j]`` to the next start). The outputs are overwritten."""
    n = jac.shape[0]
    a[:, :] = 0.0
    gr[:] = 0.0
    for j in range(starts.shape[0]):
        end = starts[j + 1] if j + 1 < starts.shape[0] else n
        sa = np.zeros((4, 4))
        sb = np.zeros((4, 2))
        sc = np.zeros((2, 2))
        sg = np.zeros(4)
        sl = np.zeros(2)
        for h in range(starts[j], end):
            rh = r[h]
            l0, l1 = jac[h, 4], jac[h, 5]
            for u in range(4):
                gu = jac[h, u]
                sg[u] += gu * rh
                sb[u, 0] += gu * l0
                sb[u, 1] += gu * l1
                for s in range(u + 1):
                    sa[u, s] += gu * jac[h, s]
            sc[0, 0] += l0 * l0
            sc[1, 0] += l1 * l0
            sc[1, 1] += l1 * l1
            sl[0] += l0 * rh
            sl[1] += l1 * rh
        for u in range(4):
            gr[u] += sg[u]
            for s in range(u + 1):
                a[u, s] += sa[u, s]
                a[s, u] = a[u, s]
        b[j, :, :] = sb
        c[j, 0, 0], c[j, 1, 0], c[j, 0, 1], c[j, 1, 1] = sc[0, 0], sc[1, 0], sc[1, 0], sc[1, 1]
        lr[j, 0], lr[j, 1] = sl[0], sl[1]


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
