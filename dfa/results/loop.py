"""The result of the Nyquist view of the harmonic balance (paper Fig. 6): the loop's curves, the critical locus,
the crossings and the cycles to mark, each at its point of the loop (computed by the analysis, so that the figure
draws without one).

The analysis is :func:`dfa.analysis.loop.nyquist_locus_response` (which re-exports these classes); the figure
:func:`dfa.render.figures.nyquist_plot`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from ..checks import check_bool, check_positive, check_type
from ..model.device import Params
from ..model.wall import WallParams
from .base import Result, figure_function
from .cycles import SearchEvidence
from .frozen import check_shape, freeze_fields
from .status import NyquistStatus
from .summaries import OperatingPoint

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = ["CycleMark", "NyquistLocusResponse"]


@dataclass(frozen=True)
class CycleMark(Result):
    """A limit cycle where the Nyquist figure marks it: its point L(jω; M) of the loop drawn.

    Attributes
    ----------
    amplitude : float
        M in encoder ticks.
    frequency : float
        ω in rad per sample.
    stable : bool
        The cycle's stability (Loeb criterion): a filled mark when stable, an open one when not.
    point : complex
        L(jω; M) of the response's loop (model, wall, delay) at the cycle, force ticks per position tick.
    """

    amplitude: float
    frequency: float
    stable: bool
    point: complex

    def __post_init__(self) -> None:
        fix = "build it with nyquist_locus_response(..., cycles=...)"
        object.__setattr__(self, "amplitude", check_positive("amplitude", self.amplitude, fix))
        object.__setattr__(self, "frequency", check_positive("frequency", self.frequency, fix))
        object.__setattr__(self, "stable", check_bool("stable", self.stable, fix))
        check_type("point", self.point, complex, fix)


@dataclass(frozen=True)
class NyquistLocusResponse(OperatingPoint, Result):
    """Data of a Nyquist plot of the loop against the critical locus −1/D(M).

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`; complex numbers as ``{"re", "im"}``) holds the fields,
    (μ, β, σ) of ``params`` flat, the delay, the crossings as ``{"amplitude", "frequency", "point"}`` records,
    and ``search``, the solver's evidence (:class:`~dfa.analysis.cycles.SearchEvidence`) when it ran.

    Attributes
    ----------
    params : Params
        The inputs.
    model, pade_order
        Loop model (see :func:`~dfa.analysis.loop.loop_response`).
    wall : WallParams
        The wall's groups in the loop (none for the paper's spring; :attr:`delay` its delay).
    omega : numpy.ndarray
        Frequencies (rad per sample) of the curves.
    amplitudes : numpy.ndarray
        The amplitude M at which each curve was linearised (NaN when σ = 0:
        the curve does not depend on M).
    curves : numpy.ndarray of complex, shape (len(amplitudes), len(omega))
        L(jω; M) for each amplitude.
    locus_amplitude : numpy.ndarray
        Amplitudes M of the critical locus.
    locus : numpy.ndarray of complex
        −1/D(M) (on the negative real axis, since D is real).
    crossings : tuple of (M, ω, point)
        Harmonic-balance solutions where a curve meets the locus at its own
        amplitude: for σ = 0 (every curve is the same) the roots of the
        limit-cycle solver (:func:`dfa.analysis.cycles.limit_cycles`, residual <= 1e-10)
        with ω in the plotted range and M up to the locus's largest amplitude,
        the point being −1/D(M); for σ > 0 use the solver directly.
    status : NyquistStatus
        ``OK``, ``CROSSINGS_NOT_COMPUTED`` (σ > 0) or ``SEARCH_INCOMPLETE`` (the solver's
        search ended incomplete; crossings may be missing, the numbers in ``search``).
    search : SearchEvidence or None
        How far the limit-cycle solver's search got (σ = 0, where it runs); None when it did not run.
    cycle_marks : tuple of CycleMark or None
        The limit cycles given to :func:`~dfa.analysis.loop.nyquist_locus_response` (``cycles=``), each at its
        point L(jω; M) of this loop, where the figure marks it; an empty tuple when the cycles given are none,
        None when no cycles were given (then absent from the JSON).

    Arrays are read-only copies.
    """

    params: Params = field(metadata={"json": None})  # written as mu, beta, sigma
    model: str
    wall: WallParams
    pade_order: int
    omega: np.ndarray = field(repr=False)
    amplitudes: np.ndarray
    curves: np.ndarray = field(repr=False)
    locus_amplitude: np.ndarray = field(repr=False)
    locus: np.ndarray = field(repr=False)
    crossings: tuple = field(
        metadata={"json": lambda c: [{"amplitude": m, "frequency": w, "point": pt} for m, w, pt in c]}
    )
    status: NyquistStatus
    search: SearchEvidence | None = None
    cycle_marks: tuple[CycleMark, ...] | None = field(default=None, metadata={"omit_none": True})

    json_properties: ClassVar[tuple[str, ...]] = ("mu", "beta", "sigma", "delay")

    def __post_init__(self) -> None:
        check_type("wall", self.wall, WallParams, "build it with nyquist_locus_response")
        freeze_fields(
            self,
            {
                "omega": {"ndim": 1},
                "amplitudes": {"ndim": 1, "finite": False},
                "curves": {"dtype": complex, "ndim": 2, "finite": False},
                "locus_amplitude": {"ndim": 1},
                "locus": {"dtype": complex, "ndim": 1, "finite": False},
            },
        )
        check_shape("curves", self.curves, (self.amplitudes.size, self.omega.size))
        check_shape("locus", self.locus, self.locus_amplitude.shape)
        object.__setattr__(self, "status", NyquistStatus.coerce(self.status))
        object.__setattr__(self, "crossings", tuple(self.crossings))
        if self.search is not None:
            check_type("search", self.search, SearchEvidence, "build it with nyquist_locus_response")
        if self.cycle_marks is not None:
            marks = tuple(self.cycle_marks)
            for k, mark in enumerate(marks):
                check_type(
                    f"cycle_marks[{k}]", mark, CycleMark, "build them with nyquist_locus_response(..., cycles=...)"
                )
            object.__setattr__(self, "cycle_marks", marks)

    @property
    def delay(self) -> int:
        """The wall's computational delay d in samples."""
        return self.wall.delay

    def plot(self, ax: Axes | None = None, **kwargs: Any) -> Axes:
        """Nyquist plot against the critical locus (:func:`dfa.render.figures.nyquist_plot`, paper Fig. 6); returns the Axes.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.
        **kwargs
            Passed on to :func:`dfa.render.figures.nyquist_plot`.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        nyquist_plot = figure_function("nyquist_plot")
        return nyquist_plot(self, ax, **kwargs)
