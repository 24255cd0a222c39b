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
        a00 = a10 = a11 = a20 = a21 = a22 = a30 = a31 = a32 = a33 = 0.0  # this segment's GᵀG, lower triangle
        b00 = b01 = b10 = b11 = b20 = b21 = b30 = b31 = 0.0  # GᵀL
        c00 = c10 = c11 = g0 = g1 = g2 = g3 = l0r = l1r = 0.0  # LᵀL, Gᵀr, Lᵀr
        for h in range(starts[j], end):
            j0, j1, j2, j3, l0, l1, rh = jac[h, 0], jac[h, 1], jac[h, 2], jac[h, 3], jac[h, 4], jac[h, 5], r[h]
            a00 += j0 * j0
            a10 += j1 * j0
            a11 += j1 * j1
            a20 += j2 * j0
            a21 += j2 * j1
            a22 += j2 * j2
            a30 += j3 * j0
            a31 += j3 * j1
            a32 += j3 * j2
            a33 += j3 * j3
            b00 += j0 * l0
            b01 += j0 * l1
            b10 += j1 * l0
            b11 += j1 * l1
            b20 += j2 * l0
            b21 += j2 * l1
            b30 += j3 * l0
            b31 += j3 * l1
            c00 += l0 * l0
            c10 += l1 * l0
            c11 += l1 * l1
            g0 += j0 * rh
            g1 += j1 * rh
            g2 += j2 * rh
            g3 += j3 * rh
            l0r += l0 * rh
            l1r += l1 * rh
        for u, s, value in ((0, 0, a00), (1, 0, a10), (1, 1, a11), (2, 0, a20), (2, 1, a21), (2, 2, a22),
                            (3, 0, a30), (3, 1, a31), (3, 2, a32), (3, 3, a33)):  # fmt: skip
            a[u, s] += value
            if s != u:
                a[s, u] += value
        b[j, 0, 0], b[j, 0, 1], b[j, 1, 0], b[j, 1, 1] = b00, b01, b10, b11
        b[j, 2, 0], b[j, 2, 1], b[j, 3, 0], b[j, 3, 1] = b20, b21, b30, b31
        c[j, 0, 0], c[j, 1, 0], c[j, 0, 1], c[j, 1, 1] = c00, c10, c10, c11
        gr[0], gr[1], gr[2], gr[3] = gr[0] + g0, gr[1] + g1, gr[2] + g2, gr[3] + g3
        lr[j, 0], lr[j, 1] = l0r, l1r


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
