"""The contour map results (:class:`ContourMaps`, :class:`FlaggedPoints`; computed in :mod:`dfa.analysis.contours`)."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from .._io import atomic_open
from ..checks import check_choice, check_int, check_type
from ..errors import DFAValueError
from .base import Result, figure_function
from .criterion import CriticalLine
from .frozen import check_shape, freeze_fields
from .status import ContourStatus
from .summaries import PlaneGrid

_ARRAYS = (
    "beta",
    "sigma",
    "small_amplitude",
    "small_frequency",
    "large_amplitude",
    "large_frequency",
    "large_amplitude_closed",
    "large_frequency_closed",
    "small_amplitude_closed",
)


@dataclass(frozen=True)
class FlaggedPoints(Result):
    """Grid points of :class:`ContourMaps` that one closed form flags (NaN), and why, as data.

    Attributes
    ----------
    family : str
        ``"small"`` (eq. 42-43) or ``"large"`` (eq. 44-45).
    reason : str
        The :class:`~dfa.analysis.cycles.ClosedFormStatus` name in snake_case: ``"degenerate"`` (β = σ = 0)
        or ``"not_solved"`` (the root finder failed).
    points : int
        How many grid points, >= 1.

    Examples
    --------
    >>> FlaggedPoints("small", "degenerate", 1).equations
    'eq. 42-43'
    """

    family: str
    reason: str
    points: int

    json_properties: ClassVar[tuple[str, ...]] = ("equations",)

    def __post_init__(self) -> None:
        check_choice("family", self.family, ("small", "large"))
        check_choice("reason", self.reason, ("degenerate", "not_solved"))
        check_int("points", self.points, minimum=1, fix="count the flagged grid points")

    @property
    def equations(self) -> str:
        """The paper's equations of the family's closed form."""
        return "eq. 42-43" if self.family == "small" else "eq. 44-45"


@dataclass(frozen=True)
class ContourMaps(PlaneGrid, Result):
    """Amplitude (ticks) and frequency (rad per sample) of both cycle families over a (β, σ) grid.

    Arrays have shape (len(sigma), len(beta)); NaN where the family does not
    exist (or, for the exact large family, lies beyond ``max_amplitude``).

    Attributes
    ----------
    mu : float
    beta, sigma : numpy.ndarray
    small_amplitude, small_frequency : numpy.ndarray
        Small stable family (eq. 42-43, exact for M < 1).
    large_amplitude, large_frequency : numpy.ndarray
        Smallest unstable cycle with the exact D (eq. 41).
    large_amplitude_closed, large_frequency_closed : numpy.ndarray
        The paper's closed form eq. 44-45 (D = 1).
    small_amplitude_closed : numpy.ndarray
        Eq. 42-43 without the M < 1 restriction (the paper's approximation).
    max_amplitude : float
    status : ContourStatus
        ``OK``: every point solved (NaN where a family does not exist or lies beyond ``max_amplitude``);
        ``FLAGGED``: the closed forms flagged grid points (NaN), counted in ``flagged``.
    flagged : tuple of FlaggedPoints
        Which grid points the closed forms flag (β = σ = 0, solver failures) and why; empty when ``OK``.

    Arrays are read-only copies; shapes are checked on construction.
    """

    mu: float
    beta: np.ndarray = field(repr=False, metadata={"json": None})
    sigma: np.ndarray = field(repr=False, metadata={"json": None})
    small_amplitude: np.ndarray = field(repr=False, metadata={"json": None})
    small_frequency: np.ndarray = field(repr=False, metadata={"json": None})
    large_amplitude: np.ndarray = field(repr=False, metadata={"json": None})
    large_frequency: np.ndarray = field(repr=False, metadata={"json": None})
    large_amplitude_closed: np.ndarray = field(repr=False, metadata={"json": None})
    large_frequency_closed: np.ndarray = field(repr=False, metadata={"json": None})
    small_amplitude_closed: np.ndarray = field(repr=False, metadata={"json": None})
    max_amplitude: float = 200.0
    status: ContourStatus = ContourStatus.OK
    flagged: tuple[FlaggedPoints, ...] = ()

    json_properties: ClassVar[tuple[str, ...]] = (
        "beta_range", "sigma_range", "grid", "small_points", "large_points", "large_closed_points",
    )  # fmt: skip

    def __post_init__(self) -> None:
        freeze_fields(self, {"beta": {"ndim": 1}, "sigma": {"ndim": 1}})
        freeze_fields(self, {k: {"ndim": 2, "finite": False} for k in _ARRAYS if k not in ("beta", "sigma")})
        for k in _ARRAYS:
            if k not in ("beta", "sigma"):
                check_shape(k, getattr(self, k), (self.sigma.size, self.beta.size))
        object.__setattr__(self, "status", ContourStatus.coerce(self.status))
        object.__setattr__(self, "flagged", tuple(self.flagged))
        for f in self.flagged:
            check_type("flagged", f, FlaggedPoints, "build the maps with contour_maps")
        if bool(self.flagged) != (self.status is ContourStatus.FLAGGED):
            raise DFAValueError(
                f"status = {self.status.value!r} is invalid with {len(self.flagged)} flagged group(s): the maps are "
                "flagged exactly when a closed form flags points; build the maps with contour_maps"
            )

    @property
    def corner(self) -> tuple[float, float]:
        """The corner (β, σ) = (½, ½) of the criterion's regions for the maps' loop (eq. 6, 10: no delay)."""
        line = CriticalLine.of(0.0)
        return line.beta0, line.sigma0

    def plot(self, ax: Any = None) -> Any:
        """Amplitude and frequency of both families (:func:`dfa.render.figures.contour_plot`, paper Fig. 7).

        Parameters
        ----------
        ax : pair of matplotlib.axes.Axes, optional
            Axes for the amplitude and the frequency panels; a new figure when None.

        Returns
        -------
        pair of matplotlib.axes.Axes
            The axes drawn on.
        """
        contour_plot = figure_function("contour_plot")
        return contour_plot(self, ax)

    def to_xarray(self) -> Any:
        """The maps as an :class:`xarray.Dataset` with labelled dims ``sigma``, ``beta``.

        One variable per array (amplitudes in ticks, frequencies in rad/sample; NaN where a
        family does not exist); attributes hold μ, ``max_amplitude`` and the status.

        Returns
        -------
        xarray.Dataset
            The maps with coordinates ``sigma`` and ``beta``.

        Raises
        ------
        DFAError
            When the optional package xarray is not installed (``pip install 'dfa-haptics[xarray]'``).

        Examples
        --------
        >>> from dfa.analysis.contours import contour_maps
        >>> ds = contour_maps(5.0, grid=3).to_xarray()
        >>> ds["large_amplitude"].dims, ds["small_frequency"].attrs["units"], ds["beta"].attrs["units"]
        (('sigma', 'beta'), 'rad/sample', '1')
        """
        from .xarray import BETA_ATTRS, SIGMA_ATTRS, import_xarray

        xr = import_xarray()
        names = [k for k in _ARRAYS if k not in ("beta", "sigma")]
        unit = {"amplitude": "ticks", "frequency": "rad/sample"}
        data = {
            k: (
                ("sigma", "beta"),
                np.array(getattr(self, k)),
                {"units": unit[k.split("_")[1]], "long_name": k.replace("_", " ")},
            )
            for k in names
        }
        return xr.Dataset(
            data,
            coords={
                "sigma": ("sigma", np.array(self.sigma), SIGMA_ATTRS),
                "beta": ("beta", np.array(self.beta), BETA_ATTRS),
            },
            attrs={
                "mu": self.mu,
                "max_amplitude": self.max_amplitude,
                "status": self.status.value,
                "status_message": self.status.message,
                "flagged_points": sum(f.points for f in self.flagged),
            },
        )

    def save(self, path: str | os.PathLike) -> Path:
        """Write all maps to a ``.npz`` file (see :func:`~dfa.analysis.contours.load_contours`), atomically.

        Parameters
        ----------
        path : str or os.PathLike
            File to write; ``.npz`` is appended when it has another suffix.

        Returns
        -------
        pathlib.Path
            The path written.
        """
        p = Path(path)
        p = p if p.suffix == ".npz" else p.with_name(p.name + ".npz")
        with atomic_open(p, "wb") as fh:  # never a half-written file (dfa._io)
            np.savez_compressed(
                fh, mu=self.mu, max_amplitude=self.max_amplitude, **{k: getattr(self, k) for k in _ARRAYS}
            )
        return p

    @property
    def small_points(self) -> int:
        """Grid points that carry a small-family cycle."""
        return int(np.isfinite(self.small_amplitude).sum())

    @property
    def large_points(self) -> int:
        """Grid points that carry a large-family cycle (exact describing function)."""
        return int(np.isfinite(self.large_amplitude).sum())

    @property
    def large_closed_points(self) -> int:
        """Grid points that carry a large-family cycle by the closed forms (eq. 44-45)."""
        return int(np.isfinite(self.large_amplitude_closed).sum())
