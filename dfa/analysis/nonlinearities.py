"""python-control's view of the describing functions of :mod:`dfa.analysis.describing` (paper section 7).

:class:`QuantizerNonlinearity` (eq. 41) and :class:`CoulombNonlinearity` (eq. 38-40) subclass
:class:`control.DescribingFunctionNonlinearity`, so python-control's ``describing_function``,
``describing_function_response`` and ``describing_function_plot`` accept them. They live here, apart from
the numerics, because importing python-control takes over a second: only code that hands a nonlinearity to
python-control loads it.
"""

from __future__ import annotations

import control
import numpy as np
from numpy.typing import ArrayLike

from ..checks import check_sigma
from .describing import coulomb_df, quantizer_df

__all__ = ["QuantizerNonlinearity", "CoulombNonlinearity"]


class QuantizerNonlinearity(control.DescribingFunctionNonlinearity):
    """The encoder quantizer q(ξ) = ⌊ξ⌋ + ½ (ticks in, force ticks out) for python-control.

    Its :meth:`describing_function` is the exact eq. 41 (vectorised over the
    amplitude), so python-control's ``describing_function``,
    ``describing_function_response`` and ``describing_function_plot`` use it.

    Examples
    --------
    >>> import control
    >>> q = QuantizerNonlinearity()
    >>> q(0.3), q(-0.3), q(1.7)
    (0.5, -0.5, 1.5)
    >>> complex(control.describing_function(q, 1.0)).real == quantizer_df(1.0)
    True
    """

    def __call__(self, x: ArrayLike) -> float | np.ndarray:
        out = np.floor(np.asarray(x, dtype=float)) + 0.5
        return float(out) if out.ndim == 0 else out

    def _isstatic(self) -> bool:
        return True

    def describing_function(self, A: ArrayLike) -> float | np.ndarray:
        """Exact D(A) of eq. 41 (real), vectorised over the amplitude A > 0 in ticks.

        Parameters
        ----------
        A : float or array_like
            Amplitude of the position sinusoid in ticks, > 0.

        Returns
        -------
        float or numpy.ndarray
            D(A), as :func:`quantizer_df`.
        """
        return quantizer_df(A)


class CoulombNonlinearity(control.DescribingFunctionNonlinearity):
    """Coulomb friction σ·sgn(v) of the velocity v, for python-control.

    Parameters
    ----------
    sigma : float
        Dimensionless Coulomb friction σ = c/(KΔ) >= 0.

    Examples
    --------
    >>> c = CoulombNonlinearity(0.5)
    >>> c(2.0), c(-2.0), c(0.0)
    (0.5, -0.5, 0.0)
    >>> round(c.describing_function(1.0), 6)      # 4σ/(πA) at A = 1
    0.63662
    """

    def __init__(self, sigma: float):
        super().__init__()
        self.sigma = check_sigma(sigma)

    def __call__(self, v: ArrayLike) -> float | np.ndarray:
        out = self.sigma * np.sign(np.asarray(v, dtype=float))
        return float(out) if out.ndim == 0 else out

    def _isstatic(self) -> bool:
        return True

    def describing_function(self, A: ArrayLike) -> float | np.ndarray:
        """Return 4σ/(πA), vectorised over the velocity amplitude A > 0.

        Parameters
        ----------
        A : float or array_like
            Amplitude of the velocity sinusoid in ticks per sample, > 0.

        Returns
        -------
        float or numpy.ndarray
            The describing function, as :func:`coulomb_df`.
        """
        return coulomb_df(A, self.sigma)
