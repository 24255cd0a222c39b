"""The worst configuration of a device whose dynamics change over its workspace (issue 46).

:class:`ConfigurationRow` is one configuration's answer: the one-axis values felt along the wall's normal, the
normal (given or searched) and the command's number (the recommended stiffness, or the criterion's margin).
:class:`WorstConfiguration` holds every row and names the limiting one: the smallest number, or a configuration
without one (no recommended K, or not covered), which limits the device the most. Computed by
:mod:`dfa.analysis.configurations`; worded by :mod:`dfa.render.configurations`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..checks import check_choice, check_type
from ..errors import DFAValueError
from ..model.device import Device
from .base import Result, figure_function
from .status import ConfigurationStatus

__all__ = ["ConfigurationRow", "WorstConfiguration", "QUANTITIES"]

#: What a row's ``value`` is: the recommended stiffness (``dfa stiffness``) or the criterion's margin (``dfa check``).
QUANTITIES = ("k_recommended", "margin")
_FIX = "rows are built by dfa.analysis.configurations (worst_stiffness, worst_check)"


def _vector(v: Any) -> list[float] | None:
    return None if v is None else [float(x) for x in v]


@dataclass(frozen=True)
class ConfigurationRow(Result):
    """One configuration's answer.

    Attributes
    ----------
    name : str
        The configuration's name.
    mass, damping, coulomb, resolution : float
        The one-axis values along the normal (SI units: kg, N·s/m, N, m; rotary kg·m², N·m·s/rad, N·m, rad).
    value : float or None
        The recommended stiffness K (N/m) or the criterion's margin (dimensionless, (β − β₀)V + (σ − σ₀), eq. 6);
        None where there is none (``rule`` says why).
    rule : str
        The recommendation's rule (``proven``, ``simulated``, ...) or the criterion's status (``a_passive``, ...,
        ``not_covered``).
    normal : tuple of float or None
        The wall's unit normal (an inertia matrix's); None for a configuration of values.
    searched : bool
        True when the normal is the worst direction found (:func:`~dfa.analysis.configurations.worst_direction`).
    evaluations : int
        How many normals were evaluated for it (1 for a given normal or none).
    pose : tuple of float or None
        The pose (m), when the device file gives one.
    """

    name: str
    mass: float
    damping: float
    coulomb: float
    resolution: float
    value: float | None
    rule: str
    normal: tuple[float, float, float] | None = field(default=None, metadata={"json": _vector})
    searched: bool = False
    evaluations: int = 1
    pose: tuple[float, float, float] | None = field(default=None, metadata={"json": _vector, "omit_none": True})

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise DFAValueError(f"name = {self.name!r} is invalid: a row names its configuration; {_FIX}")
        if self.value is not None and not math.isfinite(self.value):
            raise DFAValueError(f"value = {self.value!r} is invalid: it must be finite or None; {_FIX}")
        if self.searched and self.normal is None:
            raise DFAValueError(f"searched = True is invalid without a normal; {_FIX}")

    def null_reasons(self) -> dict[str, str]:
        """Why ``value`` or ``normal`` may be null."""
        return {
            "value": f"no value under {self.rule!r}: no recommended stiffness, or the criterion does not cover the wall",
            "normal": "a configuration of values, not an inertia matrix: no direction",
        }


@dataclass(frozen=True)
class WorstConfiguration(Result):
    """Every configuration's answer and the limiting one (module docstring).

    Attributes
    ----------
    device : Device
        The device the configurations change (its own values).
    velocity : float
        Impact speed, m/s (rotary rad/s).
    quantity : {"k_recommended", "margin"}
        What the rows' values are.
    rows : tuple of ConfigurationRow
        One per configuration, in the device file's order.
    limiting : str
        The name of the limiting configuration: the smallest value, or the first without one.
    status : ConfigurationStatus
        ``found`` or ``none`` (the limiting configuration has no value).
    simulated : bool or None
        For ``k_recommended``: whether the rows come from the full answer (True) or the quick one (``--quick``);
        None (absent from JSON) for ``margin``.
    details : tuple
        The limiting configuration's full results (the answer and its recommendation, or the check), for the
        command's screen; not in the JSON (the command writes them).
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    velocity: float
    quantity: str
    rows: tuple[ConfigurationRow, ...]
    limiting: str
    status: ConfigurationStatus = ConfigurationStatus.FOUND
    simulated: bool | None = field(default=None, metadata={"omit_none": True})
    details: tuple[Any, ...] = field(default=(), metadata={"json": None})

    units_of: ClassVar[dict[str, str]] = {"velocity": "velocity"}
    json_properties: ClassVar[tuple[str, ...]] = ("value_unit",)

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, _FIX)
        check_choice("quantity", self.quantity, QUANTITIES)
        if not self.rows or not all(isinstance(r, ConfigurationRow) for r in self.rows):
            raise DFAValueError(f"rows = {self.rows!r} is invalid: it must be a non-empty tuple of rows; {_FIX}")
        object.__setattr__(self, "status", ConfigurationStatus.coerce(self.status))
        names = [r.name for r in self.rows]
        if self.limiting not in names:
            raise DFAValueError(f"limiting = {self.limiting!r} is invalid: it must name a row ({names}); {_FIX}")
        if (self.row.value is None) != (self.status is ConfigurationStatus.NONE):
            raise DFAValueError(f"status = {self.status.value!r} is invalid for the limiting row's value "
                                f"{self.row.value!r}: 'none' exactly when it has none; {_FIX}")  # fmt: skip

    @property
    def row(self) -> ConfigurationRow:
        """The limiting configuration's row."""
        return next(r for r in self.rows if r.name == self.limiting)

    @property
    def value(self) -> float | None:
        """The limiting value: the device's recommended stiffness (or margin) over every configuration."""
        return self.row.value

    @property
    def value_unit(self) -> str:
        """The unit of the rows' values (the stiffness's, or ``"1"`` for the dimensionless margin)."""
        return self.device.units["stiffness"] if self.quantity == "k_recommended" else "1"

    def plot(self, ax: Any = None) -> Any:
        """The rows' values over the configurations (over the poses when every row has one); the limiting one
        marked (:func:`dfa.render.figures.configurations.configurations_plot`)."""
        return figure_function("configurations_plot")(self, ax=ax)
