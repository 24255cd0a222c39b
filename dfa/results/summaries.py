"""Summary properties shared by results: the operating point's groups, and the (β, σ) grid of a map.

Mixins for :class:`~dfa.results.base.Result` subclasses, so that a JSON key means one thing everywhere
(``mu``, ``beta``, ``sigma``; ``beta_range``, ``sigma_range``, ``grid``).

Examples
--------
>>> from dataclasses import dataclass
>>> import numpy as np
>>> @dataclass(frozen=True)
... class Demo(PlaneGrid):
...     beta: np.ndarray
...     sigma: np.ndarray
>>> Demo(np.linspace(0, 1, 3), np.linspace(0, 2, 5)).grid
[3, 5]
"""

from __future__ import annotations

from typing import Any

__all__ = ["OperatingPoint", "PlaneGrid"]


class OperatingPoint:
    """``mu``, ``beta``, ``sigma`` of a result's ``params`` (the dimensionless groups of paper Table 1)."""

    params: Any

    @property
    def mu(self) -> float:
        """The μ of the operating point (:attr:`params`)."""
        return float(self.params.mu)

    @property
    def beta(self) -> float:
        """The β of the operating point (:attr:`params`)."""
        return float(self.params.beta)

    @property
    def sigma(self) -> float:
        """The σ of the operating point (:attr:`params`)."""
        return float(self.params.sigma)


class PlaneGrid:
    """``beta_range``, ``sigma_range`` and ``grid`` of a result over a (β, σ) grid (its ``beta``, ``sigma``)."""

    beta: Any
    sigma: Any

    @property
    def beta_range(self) -> list[float]:
        """The first and last β of the grid."""
        return [float(self.beta[0]), float(self.beta[-1])]

    @property
    def sigma_range(self) -> list[float]:
        """The first and last σ of the grid."""
        return [float(self.sigma[0]), float(self.sigma[-1])]

    @property
    def grid(self) -> list[int]:
        """Points along β and along σ."""
        return [int(self.beta.size), int(self.sigma.size)]
