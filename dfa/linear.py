"""Linear stability of the sampled spring without encoder and Coulomb friction (placeholder).

Minimal version for the limit-cycle branch; the linear-bound branch replaces this
module at merge by the full one with the same :func:`linear_stable`.

The device 1/(μ s² + β s) behind a zero-order hold (T = 1) has the pulse transfer
function G_d(z) = (c₁ z + c₀)/(μ (z − 1)(z − p)) (:mod:`dfa.loop`); the unit spring
φ = −ξ read d samples late closes the loop, whose characteristic polynomial is

    μ (z − 1)(z − p) z^d + c₁ z + c₀ = 0.

The loop is asymptotically stable when every root lies inside the unit circle
(spectral radius of the companion matrix < 1). It reproduces Gil et al.'s bound
(paper section 8 anchors): β_crit = 0.4918 at μ = 5 with d = 0.
"""

from __future__ import annotations

import numpy as np

from .errors import check_beta, check_int, check_mu

__all__ = ["linear_stable"]


def linear_stable(mu: float, beta: float, delay: int = 0) -> bool:
    """True when the exact ZOH loop (no quantization, no Coulomb friction, d delays) is asymptotically stable.

    Parameters
    ----------
    mu : float
        μ = m/(K T²) > 0.
    beta : float
        β = b/(K T) >= 0.
    delay : int, optional
        Computational delay d in whole samples.
    """
    from .loop import _zoh_coefficients

    m = check_mu(mu)
    b = check_beta(beta)
    d = check_int("delay", delay, minimum=0, fix="give the computational delay in whole samples")
    c1, c0, p = _zoh_coefficients(b / m)
    poly = np.polymul(m * np.polymul([1.0, -1.0], [1.0, -p]), np.r_[1.0, np.zeros(d)])
    poly = np.polyadd(poly, [c1, c0])
    return bool(np.max(np.abs(np.roots(poly))) < 1.0)
