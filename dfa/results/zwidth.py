"""The Z-width result (:class:`ZWidth`; computed in :mod:`dfa.analysis.limits.zwidth`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..checks import (
    check_positive,
    check_type,
)
from ..errors import DFAValueError
from ..model.device import Device
from ..model.wall import Wall
from .base import Result, figure_function
from .codes import POINT_OUTCOMES, ZWIDTH_METHODS
from .limits import KLimit
from .status import ZWidthStatus


@dataclass(frozen=True)
class ZWidth(Result):
    """The Z-width of a device (module docstring): K_max(B) per method and the simulated grid, physical units.

    Attributes
    ----------
    device : Device
    wall : Wall
        The wall whose delay, velocity filter and amplifier are held fixed (its damper and K are the grid's).
    velocity : float
        Impact speed V, m/s (rotary: rad/s).
    speeds : tuple of float
        Impact speeds simulated (m/s), each from ξ0 = 0 and from the preload.
    stiffness : numpy.ndarray
        K grid, N/m (rotary: N·m/rad), ascending geometric.
    damping : numpy.ndarray
        B grid, N·s/m (rotary: N·m·s/rad), ascending.
    limits : dict of str to tuple of KLimit
        K_max(B) per method (:data:`ZWIDTH_METHODS`), one limit per B, each with its status and evidence
        (:meth:`boundary` gives the values, NaN where undefined).
    outcome : numpy.ndarray of int8, shape (len(damping), len(stiffness))
        Code of each simulated grid point (:data:`POINT_OUTCOMES`).
    max_samples : int
        Longest run, samples.
    simulations : int
        Exact simulations run.
    df_model : str
        Hold model of the describing function.
    counterexamples : tuple of dict
        Divergent grid points at a K the criterion proves passive (must be empty).
    linear_passivity_violations : tuple of dict
        Divergent grid points below the Colgate–Schenkel boundary (linear model; not a proof for the device).
    status : ZWidthStatus
        ``ok``, ``caveats`` (undecided points or non-monotone columns) or ``counterexample``.
    limiting : dict of str to tuple of str, optional
        The Z-width of a device file's configurations (the minimum over them, B by B): per method, the name of the
        configuration whose limit each B takes (:func:`dfa.analysis.configurations.worst_z_width`); None (absent
        from JSON) for one device.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    speeds: tuple[float, ...]
    stiffness: np.ndarray
    damping: np.ndarray
    limits: dict[str, tuple[KLimit, ...]]
    outcome: np.ndarray = field(metadata={"json": lambda a: [[POINT_OUTCOMES[c] for c in row] for row in a.tolist()]})
    max_samples: int
    simulations: int
    df_model: str
    counterexamples: tuple[dict[str, object], ...] = ()
    linear_passivity_violations: tuple[dict[str, object], ...] = ()
    status: ZWidthStatus = ZWidthStatus.OK
    limiting: dict[str, tuple[str, ...]] | None = field(default=None, metadata={"omit_none": True})

    json_properties: ClassVar[tuple[str, ...]] = ("delay", "boundaries", "outcome_layout")
    units_of: ClassVar[dict[str, str]] = {"velocity": "velocity", "stiffness": "stiffness", "damping": "damping"}

    def __post_init__(self) -> None:
        fix = "ZWidth is built by dfa.analysis.limits.zwidth.z_width; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        check_positive("velocity", self.velocity, fix)
        nk, nb = self.stiffness.size, self.damping.size
        if self.outcome.shape != (nb, nk):
            raise DFAValueError(f"outcome has shape {self.outcome.shape} but must be ({nb}, {nk}); {fix}")
        if set(self.limits) != set(ZWIDTH_METHODS):
            raise DFAValueError(f"limits must have the keys {ZWIDTH_METHODS}; {fix}")
        for name in ZWIDTH_METHODS:
            if len(self.limits[name]) != nb or not all(isinstance(x, KLimit) for x in self.limits[name]):
                raise DFAValueError(f"limits[{name!r}] must hold one KLimit per B ({nb}); {fix}")
        if self.limiting is not None and (
            set(self.limiting) != set(ZWIDTH_METHODS) or any(len(v) != nb for v in self.limiting.values())
        ):
            raise DFAValueError(f"limiting must name one configuration per B ({nb}) for each method; {fix}")
        st = ZWidthStatus.coerce(self.status)
        object.__setattr__(self, "status", st)
        if (st is ZWidthStatus.COUNTEREXAMPLE) != bool(self.counterexamples):
            raise DFAValueError(
                f"status = {st.value!r} is invalid with {len(self.counterexamples)} counterexample(s): the status is "
                f"'counterexample' exactly when there is one; {fix}"
            )
        for arr in (self.stiffness, self.damping, self.outcome):
            arr.flags.writeable = False

    @property
    def delay(self) -> int:
        """The wall's computational delay d in samples."""
        return self.wall.delay

    @property
    def boundaries(self) -> dict[str, np.ndarray]:
        """K_max(B) per method, N/m: :meth:`boundary` of every method."""
        return {m: self.boundary(m) for m in ZWIDTH_METHODS}

    @property
    def outcome_layout(self) -> str:
        """How ``outcome`` is laid out."""
        return "outcome[i][j]: damping[i], stiffness[j]"

    def boundary(self, method: str) -> np.ndarray:
        """K_max(B) of one method (:data:`ZWIDTH_METHODS`), N/m; NaN where undefined.

        Parameters
        ----------
        method : str
            One of :data:`ZWIDTH_METHODS`.

        Returns
        -------
        numpy.ndarray
            One value per B of the grid (read-only).
        """
        if method not in ZWIDTH_METHODS:
            raise DFAValueError(f"method = {method!r} is invalid: it must be one of {', '.join(ZWIDTH_METHODS)}")
        out = np.array([math.nan if x.value is None else x.value for x in self.limits[method]], dtype=float)
        out.flags.writeable = False
        return out

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key.

        Returns
        -------
        dict of str to str
            The boundaries hold NaN (null) where a method's limit is undefined; its ``limits`` record says why.
        """
        return {"boundaries": "undefined at some B: see that B's record under limits"}

    def plot(self, ax: Any = None, design_point: tuple[float, float] | None = None) -> Any:
        """Draw the Z-width (B across, K up on a log axis, one line per method, simulated region shaded).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on (default: a new figure).
        design_point : (float, float), optional
            A design point (B, K) in the device's units to star (in the legend too).

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on: B across, K (log) up, one line per method.
        """
        plot_zwidth = figure_function("plot_zwidth")

        return plot_zwidth(self, ax=ax, design_point=design_point)

    def to_xarray(self) -> Any:
        """The Z-width as an :class:`xarray.Dataset` with labelled dims ``damping`` (B) and ``stiffness`` (K).

        Variables: ``outcome`` over (``damping``, ``stiffness``), the code of each simulated grid point
        (``flag_values`` and ``flag_meanings`` name them: :data:`POINT_OUTCOMES`); for each method of
        :data:`ZWIDTH_METHODS` its boundary ``k_max_<method>`` over ``damping`` (:meth:`boundary`, NaN where
        undefined) and ``k_max_<method>_status``, its limit's status code at each B (which says why). Units are
        the device's (``device.units``: N/m and N·s/m; rotary N·m/rad and N·m·s/rad). Attributes hold the device,
        the impact speed ``velocity`` and the ``speeds`` simulated (in ``velocity_units``), the wall held fixed
        (``delay`` in samples; ``filter_cutoff`` and ``amplifier_bandwidth`` in Hz, absent without one), the run
        settings, the numbers of counterexamples and of linear passivity violations, and the status.

        Returns
        -------
        xarray.Dataset
            The grid's outcome codes and the boundaries K_max(B), with coordinates ``damping`` and ``stiffness``.

        Raises
        ------
        DFAError
            When the optional package xarray is not installed (``pip install 'dfa-haptics[xarray]'``).

        Examples
        --------
        >>> from dfa.model.catalogue import get_device
        >>> from dfa.analysis.limits.zwidth import z_width
        >>> z = z_width(get_device("Impulse Engine").device, 0.1, grid=3, speeds=1, n_jobs=1)
        >>> ds = z.to_xarray()
        >>> ds["outcome"].dims, ds["k_max_linear"].dims, ds["stiffness"].attrs["units"]
        (('damping', 'stiffness'), ('damping',), 'N/m')
        """
        from .xarray import flag_attrs, import_xarray, netcdf_attrs, physical_attrs

        xr = import_xarray()
        u = self.device.units
        grid = ("damping", "stiffness")
        outcome = flag_attrs("simulated outcome", POINT_OUTCOMES)
        data: dict[str, Any] = {"outcome": (grid, np.array(self.outcome), outcome)}
        how = {
            "linear": "exact linear bound",
            "passivity": "Colgate–Schenkel passivity (linear model)",
            "criterion": "extended criterion (proof)",
            "df": "describing function",
            "sim": "simulation: no divergence",
            "rest": "simulation: comes to rest",
        }
        for m in ZWIDTH_METHODS:
            k_max = physical_attrs(f"K_max(B), {m}", u["stiffness"], description=how[m])
            data[f"k_max_{m}"] = ("damping", np.array(self.boundary(m)), k_max)
            codes = np.array([x.status.value for x in self.limits[m]], dtype=str)
            data[f"k_max_{m}_status"] = ("damping", codes, {"long_name": f"status of K_max(B), {m}"})
        b_attrs = physical_attrs("virtual damping B", u["damping"])
        k_attrs = physical_attrs("virtual stiffness K", u["stiffness"])
        return xr.Dataset(
            data,
            coords={
                "damping": ("damping", np.array(self.damping), b_attrs),
                "stiffness": ("stiffness", np.array(self.stiffness), k_attrs),
            },
            attrs=netcdf_attrs(
                {
                    "device": self.device.name,
                    "rotary": self.device.rotary,
                    "velocity": self.velocity,
                    "speeds": self.speeds,
                    "velocity_units": u["velocity"],
                    "delay": self.delay,
                    "filter_cutoff": self.wall.filter_cutoff,
                    "amplifier_bandwidth": self.wall.amplifier_bandwidth,
                    "max_samples": self.max_samples,
                    "simulations": self.simulations,
                    "df_model": self.df_model,
                    "counterexamples": len(self.counterexamples),
                    "linear_passivity_violations": len(self.linear_passivity_violations),
                    "status": self.status,
                    "status_message": self.status_message,
                }
            ),
        )
