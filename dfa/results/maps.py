"""The stability map result (:class:`StabilityMap`; computed and loaded in :mod:`dfa.analysis.maps`)."""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from .._io import atomic_open
from ..checks import check_int, check_mu, check_real_array
from ..errors import DFAValueError
from ..model.elements import Coverage
from ..model.wall import WallParams
from .base import Result, figure_function
from .criterion import CriticalLine
from .frozen import check_shape, freeze_fields
from .simulation import CONTACTS, OUTCOMES, check_wall
from .status import MapStatus
from .summaries import PlaneGrid

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.axes import Axes


@dataclass(frozen=True)
class StabilityMap(PlaneGrid, Result):
    """Outcome of the exact simulation over a (β, σ) grid for one μ and several initial speeds.

    Attributes
    ----------
    mu : float
        Dimensionless mass.
    xi_dots : tuple of float
        Initial speeds ξ'0 (ticks per sample); with ``preload`` the equivalent
        speeds of the spring preload (ξ'0 = 0, H_c(ξ0) = ½μξ'0²).
    beta, sigma : numpy.ndarray
        Grid axes.
    outcome : numpy.ndarray of int8, shape (len(xi_dots), len(sigma), len(beta))
        0 rest, 1 oscillating, 2 unstable, 3 chatter, 4 undecided (module
        docstring; :data:`dfa.analysis.simulation.OUTCOMES`).
    amplitude, frequency : numpy.ndarray
        Measured cycle amplitude (ticks) and frequency (rad per sample); NaN where not measured.
    samples, quantize, preload
        Simulation settings.
    contact : numpy.ndarray of int8 or None
        A one-sided wall's contact kind of each run (index into :data:`dfa.analysis.simulation.CONTACTS`:
        :func:`~dfa.analysis.simulation.contact_codes`, :attr:`SimulationResult.contact`'s rule); None for a
        bilateral wall.
    status : MapStatus
        ``OK``: every point simulated (amplitude and frequency NaN where not measured).
    wall : WallParams
        The wall of every run (delay d, virtual damper β_B, filter ν_c, amplifier lag α); default the
        paper's spring. ``delay`` is its delay.

    Arrays are read-only copies; shapes are checked on construction.
    """

    mu: float
    xi_dots: tuple
    beta: np.ndarray = field(repr=False, metadata={"json": None})
    sigma: np.ndarray = field(repr=False, metadata={"json": None})
    outcome: np.ndarray = field(repr=False, metadata={"json": None})
    amplitude: np.ndarray = field(repr=False, metadata={"json": None})
    frequency: np.ndarray = field(repr=False, metadata={"json": None})
    samples: int
    quantize: bool = True
    preload: bool = False
    status: MapStatus = MapStatus.OK
    wall: WallParams = field(default_factory=WallParams)
    contact: np.ndarray | None = field(default=None, repr=False, metadata={"json": None})

    json_properties: ClassVar[tuple[str, ...]] = ("beta_range", "sigma_range", "grid", "delay")

    def __post_init__(self) -> None:
        object.__setattr__(self, "mu", check_mu(self.mu))
        xd = check_real_array("xi_dots", self.xi_dots, "give the initial speeds in ticks per sample")
        object.__setattr__(self, "xi_dots", tuple(float(v) for v in np.atleast_1d(xd).ravel()))
        object.__setattr__(self, "samples", check_int("samples", self.samples, minimum=1))
        object.__setattr__(self, "wall", check_wall(self.wall))
        freeze_fields(
            self,
            {
                "beta": {"ndim": 1},
                "sigma": {"ndim": 1},
                "outcome": {"dtype": np.int8, "ndim": 3},
                "amplitude": {"ndim": 3, "finite": False},
                "frequency": {"ndim": 3, "finite": False},
            },
        )
        shape = (len(self.xi_dots), self.sigma.size, self.beta.size)
        for name in ("outcome", "amplitude", "frequency"):
            check_shape(name, getattr(self, name), shape)
        if self.outcome.size and not (0 <= self.outcome.min() and self.outcome.max() < len(OUTCOMES)):
            raise DFAValueError(
                f"outcome holds codes outside 0 … {len(OUTCOMES) - 1}: they index dfa.analysis.simulation.OUTCOMES; "
                "pass the codes the simulation returned"
            )
        if (self.contact is None) != self.wall.covers(Coverage.SURFACE_START):
            raise DFAValueError(
                "contact must be given exactly for a one-sided wall's map; build maps with stability_map"
            )
        if self.contact is not None:
            freeze_fields(self, {"contact": {"dtype": np.int8, "ndim": 3}})
            check_shape("contact", self.contact, shape)
            if self.contact.size and not (0 <= self.contact.min() and self.contact.max() < len(CONTACTS)):
                raise DFAValueError(
                    f"contact holds codes outside 0 … {len(CONTACTS) - 1}: they index dfa.analysis.simulation.CONTACTS; "
                    "pass the codes the simulation returned"
                )
        object.__setattr__(self, "status", MapStatus.coerce(self.status))

    @property
    def delay(self) -> int:
        """Computational delay d of the wall, samples."""
        return self.wall.delay

    def critical_line(self, xi_dot: float) -> CriticalLine | None:
        """The criterion's critical line (eq. 10) at speed ``xi_dot`` for this map's loop; None where none applies.

        The spring's line through (½ + d, ½) (σ₀ = 0 without quantization), or with more elements the line
        of the criterion extended to them (:meth:`dfa.model.wall.WallParams.corner`); None with an
        amplifier lag, which no criterion covers.

        Parameters
        ----------
        xi_dot : float
            The speed V in ticks per sample (sign ignored).

        Returns
        -------
        CriticalLine or None
            The line through the map's corner (β₀, σ₀) with slope −V; None with an amplifier lag.
        """
        if self.wall.not_covered() is not None:
            return None
        b0, s0 = self.wall.corner(self.quantize)
        return CriticalLine(xi_dot, b0, s0)

    def plot(self, ax: Sequence[Axes] | None = None, **kwargs: Any) -> list[Axes]:
        """Outcome per (β, σ), one panel per speed (:func:`dfa.render.figures.stability_map_plot`, paper Fig. 4).

        Parameters
        ----------
        ax : sequence of matplotlib.axes.Axes, optional
            One Axes per speed; a new figure when None.
        **kwargs
            Passed on to :func:`dfa.render.figures.stability_map_plot`.

        Returns
        -------
        list of matplotlib.axes.Axes
            The axes drawn on, one per speed.
        """
        stability_map_plot = figure_function("stability_map_plot")
        return stability_map_plot(self, ax, **kwargs)

    def to_xarray(self) -> xr.Dataset:
        """The map as an :class:`xarray.Dataset` with labelled dims ``xi_dot``, ``sigma``, ``beta``.

        Variables ``outcome`` (codes, ``flag_meanings`` names them), ``amplitude`` (ticks) and
        ``frequency`` (rad/sample); attributes hold μ, the settings and the status.

        Returns
        -------
        xarray.Dataset
            The map with coordinates ``xi_dot`` (ticks per sample), ``sigma`` and ``beta``.

        Raises
        ------
        DFAError
            When the optional package xarray is not installed (``pip install 'dfa-haptics[xarray]'``).
        """
        from .xarray import BETA_ATTRS, SIGMA_ATTRS, XI_DOT_ATTRS, import_xarray

        xr = import_xarray()
        dims = ("xi_dot", "sigma", "beta")
        codes = {"flag_values": list(range(len(OUTCOMES))), "flag_meanings": " ".join(OUTCOMES)}
        return xr.Dataset(
            {
                "outcome": (dims, np.array(self.outcome), {"long_name": "simulated outcome", **codes}),
                "amplitude": (dims, np.array(self.amplitude), {"long_name": "cycle amplitude", "units": "ticks"}),
                "frequency": (dims, np.array(self.frequency), {"long_name": "cycle frequency", "units": "rad/sample"}),
            },
            coords={
                "xi_dot": ("xi_dot", np.array(self.xi_dots), XI_DOT_ATTRS),
                "sigma": ("sigma", np.array(self.sigma), SIGMA_ATTRS),
                "beta": ("beta", np.array(self.beta), BETA_ATTRS),
            },
            attrs={
                "mu": self.mu,
                "samples": self.samples,
                "delay": self.delay,
                "quantize": int(self.quantize),
                "preload": int(self.preload),
                "status": self.status.value,
                "status_message": self.status.message,
            },
        )

    def counts(self) -> list[dict[str, int]]:
        """Number of grid points per outcome, one dict per initial speed.

        Returns
        -------
        list of dict
            ``{outcome name: count}`` for each initial speed, in the order of ``xi_dots`` (the outcomes from ``left``
            on, a one-sided wall's and the device's end stop, only where some run ended so).
        """
        last = OUTCOMES.index("undecided")  # the classes after it (left, saturated: an element's) only where present
        return [
            {name: int(np.sum(o == code)) for code, name in enumerate(OUTCOMES) if code <= last or np.any(o == code)}
            for o in self.outcome
        ]

    def contact_counts(self) -> list[dict[str, int]] | None:
        """Count a one-sided wall's grid points per contact kind, one dict per initial speed.

        The kinds are :class:`~dfa.results.status.ContactOutcome`'s; None for a bilateral wall.

        Returns
        -------
        list of dict or None
            ``{contact kind: count}`` for each initial speed, every kind.
        """
        if self.contact is None:
            return None
        return [{k.value: int(np.sum(c == i)) for i, k in enumerate(CONTACTS)} for c in self.contact]

    def to_dict(self) -> dict[str, Any]:
        """Strict-JSON summary: the scalar fields, the grid and the counts per speed, not the arrays.

        :meth:`dfa.results.base.Result.to_dict` (the arrays left out; :attr:`json_properties`) with ``counts``,
        the outcome counts of :meth:`counts` with their speed ``xi_dot``.

        Returns
        -------
        dict
            The μ, speeds, wall, grid, settings, counts per speed, status and its message.
        """
        counts = [dict(xi_dot=v, **c) for v, c in zip(self.xi_dots, self.counts(), strict=True)]
        out = {**super().to_dict(), "counts": counts}
        contact = self.contact_counts()
        if contact is not None:  # a one-sided wall's map only: a bilateral map's record is unchanged
            out["contact_counts"] = [dict(xi_dot=v, **c) for v, c in zip(self.xi_dots, contact, strict=True)]
        return out

    def save(self, path: str | os.PathLike) -> Path:
        """Write the map to a ``.npz`` file (see :func:`load_map`), atomically.

        ``.npz`` is appended when ``path`` has another suffix (numpy's rule);
        the path written is returned.

        Parameters
        ----------
        path : str or os.PathLike
            File to write.

        Returns
        -------
        pathlib.Path
            The path written (with the ``.npz`` suffix).
        """
        p = Path(path)
        p = p if p.suffix == ".npz" else p.with_name(p.name + ".npz")
        with atomic_open(p, "wb") as fh:  # never a half-written map (dfa._io)
            np.savez_compressed(
                fh,
                mu=self.mu,
                xi_dots=np.asarray(self.xi_dots, dtype=float),
                beta=self.beta,
                sigma=self.sigma,
                outcome=self.outcome,
                outcome_names=np.array(OUTCOMES),
                amplitude=self.amplitude,
                frequency=self.frequency,
                settings=np.array([self.samples, self.delay, int(self.quantize), int(self.preload)], dtype=np.int64),
                **_wall_arrays(self.wall, self.contact),
            )
        return p


def _wall_arrays(wall: WallParams, contact: np.ndarray | None = None) -> dict[str, Any]:
    """The wall entries of a map file: ``wall_json``, the groups' JSON (:meth:`dfa.model.wall.WallParams.to_dict`),
    and a one-sided wall's ``contact`` kinds; none for the spring (its delay is in ``settings``)."""
    if wall.covers(Coverage.CLOSED_FORM):
        return {}
    out = {"wall_json": np.array(json.dumps(wall.to_dict(), sort_keys=True))}
    if contact is not None:
        out["contact"] = contact
    return out
