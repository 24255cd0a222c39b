"""The linear results of a wall with more than the spring (:class:`StiffnessIntervals`, :class:`StableRegion`;
computed in :mod:`dfa.analysis.linear_wall`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..errors import DFAValueError
from .base import Result
from .frozen import freeze_fields
from .status import LinearStatus


@dataclass(frozen=True)
class StiffnessIntervals(Result):
    """The stable stiffnesses of the linear sampled loop at a fixed controller damper, filter, delay and lag.

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`, SI units) holds every field and the status's message.

    Attributes
    ----------
    intervals : numpy.ndarray
        (n, 2) open intervals (K_lo, K_hi) of stable stiffness, N/m (rotary: N·m/rad), ascending; empty if none.
    k_crit : float
        Top of the interval starting at K = 0 (the loop is stable for every K in (0, k_crit)); 0 if none, N/m.
    status : LinearStatus
    mass, damping, period : float
        The device's m (kg), b (N·s/m) and T (s).
    wall : dict
        The wall held fixed: damping B (N·s/m), delay (samples), filter_cutoff (Hz or None),
        amplifier_bandwidth (Hz or None); its stiffness is what is solved for.
    """

    intervals: np.ndarray
    k_crit: float
    status: LinearStatus
    mass: float
    damping: float
    period: float
    wall: dict

    def __post_init__(self) -> None:
        freeze_fields(self, {"intervals": {"ndim": 2}})
        if self.intervals.shape[1:] != (2,):
            raise DFAValueError(
                f"intervals has shape {self.intervals.shape} but must be (n, 2); pass the computed array"
            )
        object.__setattr__(self, "status", LinearStatus.coerce(self.status))


@dataclass(frozen=True)
class StableRegion(Result):
    """The stable region of the (K, B) plane of the linear sampled loop: K_max(B) and every stable interval.

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`, SI units) holds the B grid, K_max(B), the status and,
    instead of the rows, their :attr:`intervals` and :attr:`row_status` and the :attr:`device`'s m, b and T.

    Attributes
    ----------
    virtual_damping : numpy.ndarray
        Grid of controller damping B >= 0, N·s/m (rotary: N·m·s/rad).
    k_crit : numpy.ndarray
        At each B, the top of the stable interval starting at K = 0 (0 if there is none), N/m.
    rows : tuple of StiffnessIntervals
        At each B, every stable interval and its status.
    status : LinearStatus
        INTERVAL when every B has one interval from K = 0; otherwise the first other status met along the grid.
    """

    virtual_damping: np.ndarray
    k_crit: np.ndarray
    rows: tuple = field(metadata={"json": None})
    status: LinearStatus

    json_properties: ClassVar[tuple[str, ...]] = ("intervals", "row_status", "device")

    def __post_init__(self) -> None:
        freeze_fields(self, {"virtual_damping": {"ndim": 1}, "k_crit": {"ndim": 1}})
        if not (len(self.rows) == self.k_crit.size == self.virtual_damping.size):
            raise DFAValueError("rows, k_crit and virtual_damping must have the same length; pass the computed values")
        object.__setattr__(self, "status", LinearStatus.coerce(self.status))

    @property
    def intervals(self) -> list[np.ndarray]:
        """At each B, the (n, 2) stable intervals (K_lo, K_hi) of its row, N/m."""
        return [r.intervals for r in self.rows]

    @property
    def row_status(self) -> list[LinearStatus]:
        """At each B, the status of its row."""
        return [r.status for r in self.rows]

    @property
    def device(self) -> dict[str, float] | None:
        """The device's ``mass`` (kg), ``damping`` b (N·s/m) and ``period`` T (s) of the rows; None without a row.

        The region holds the device's numbers, not a :class:`dfa.Device`.
        """
        if not self.rows:
            return None
        first = self.rows[0]
        return {"mass": first.mass, "damping": first.damping, "period": first.period}

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            ``device`` is null for a region without a B (not one :func:`~dfa.analysis.linear_wall.stable_region` builds).
        """
        return {"device": "no B in the grid"}

    def to_xarray(self, rotary: bool = False) -> Any:
        """The region as an :class:`xarray.Dataset` with the labelled dim ``virtual_damping`` (B).

        Variables over ``virtual_damping``: ``k_crit`` (K_max(B), the top of the stable interval from K = 0;
        0 where there is none) and ``row_status`` (the status code at each B); ``intervals`` over
        (``virtual_damping``, ``interval``, ``end``) holds every stable interval (K_lo, K_hi) at each B, NaN
        past the last one of that B. Attributes hold the device's m, b and T (units in ``mass_units``,
        ``damping_units``, ``period_units``), the wall held fixed (``delay`` in samples, ``filter_cutoff`` and
        ``amplifier_bandwidth`` in Hz, absent without one) and the status.

        Parameters
        ----------
        rotary : bool, optional
            Label the values with a rotary device's units (N·m/rad, N·m·s/rad, kg·m²) instead of the linear
            ones (N/m, N·s/m, kg); the region holds the device's numbers, not the device. Default False.

        Returns
        -------
        xarray.Dataset
            K_max(B), the status and the stable intervals at each B, with the coordinate ``virtual_damping``.

        Raises
        ------
        DFAError
            When the optional package xarray is not installed (``pip install 'dfa-haptics[xarray]'``).
        DFATypeError
            When ``rotary`` is not True or False.

        Examples
        --------
        >>> from dfa.analysis.linear_wall import stable_region
        >>> ds = stable_region(1.0, 2.0, 1e-3, [0.0, 1.0]).to_xarray()
        >>> ds["k_crit"].dims, ds["k_crit"].attrs["units"], ds["virtual_damping"].attrs["units"]
        (('virtual_damping',), 'N/m', 'N·s/m')
        """
        from ..checks import check_bool
        from ..model.device import device_units
        from .xarray import import_xarray, netcdf_attrs, physical_attrs

        rot = check_bool("rotary", rotary, "pass True for a rotary device's units, False for SI")
        u = device_units(rot)
        xr = import_xarray()
        codes = np.array([r.status.value for r in self.rows], dtype=str)
        n = max([len(r.intervals) for r in self.rows], default=0)
        intervals = np.full((len(self.rows), n, 2), np.nan)
        for i, r in enumerate(self.rows):
            intervals[i, : len(r.intervals)] = r.intervals
        stable = physical_attrs("stable stiffness intervals (K_lo, K_hi)", u["stiffness"], comment="NaN: no more")
        first = self.rows[0] if self.rows else None
        return xr.Dataset(
            {
                "k_crit": ("virtual_damping", np.array(self.k_crit), physical_attrs("K_max(B)", u["stiffness"])),
                "row_status": ("virtual_damping", codes, {"long_name": "status of the stable set at each B"}),
                "intervals": (("virtual_damping", "interval", "end"), intervals, stable),
            },
            coords={
                "virtual_damping": (
                    "virtual_damping",
                    np.array(self.virtual_damping),
                    physical_attrs("virtual damping B", u["damping"]),
                ),
                "end": ("end", np.array(["low", "high"])),
            },
            attrs=netcdf_attrs(
                {
                    "rotary": rot,
                    "mass": None if first is None else first.mass,
                    "damping": None if first is None else first.damping,
                    "period": None if first is None else first.period,
                    "mass_units": u["mass"],
                    "damping_units": u["damping"],
                    "period_units": u["period"],
                    "delay": None if first is None else first.wall["delay"],
                    "filter_cutoff": None if first is None else first.wall["filter_cutoff"],
                    "amplifier_bandwidth": None if first is None else first.wall["amplifier_bandwidth"],
                    "status": self.status,
                    "status_message": self.status.message,
                }
            ),
        )
