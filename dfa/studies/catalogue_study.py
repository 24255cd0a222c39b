"""The runner both catalogue comparisons share: each device's largest stiffness for a few walls, as
:func:`~dfa.analysis.limits.kmax.design_answer` finds it, kept as limit records.

A comparison names its walls (a case → a wall of K = 1 for each device, :data:`WallsOf`) and the limits it keeps;
:func:`run_catalogue_study` runs every case on every device (at each device's impact speed: the one given, else
the design report's 0.1 m/s, rotary 1 rad/s) and returns the rows with the counterexamples found.
:class:`CatalogueComparison` is what the comparisons' results share (:mod:`~dfa.studies.contact_comparison`,
:mod:`~dfa.studies.passivity_comparison`).

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.wall import Wall
>>> devs, g, n = catalogue_inputs([get_device("Impulse Engine")], 6, 1)
>>> run = run_catalogue_study(devs, None, g, n, lambda dev: {"spring": Wall(1.0)}, ("k_sim",))
>>> run.velocities, sorted(run.limits[0]["spring"])
((0.1,), ['k_sim'])
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, ClassVar

from ..checks import check_int
from ..errors import DFAValueError
from ..model.catalogue import CatalogueEntry, catalogue
from ..model.device import Device
from ..model.loop import Loop
from ..model.wall import Wall
from ..results.base import Result
from ..results.status import ComparisonStatus

__all__ = [
    "CatalogueComparison",
    "CatalogueRun",
    "WallsOf",
    "catalogue_inputs",
    "complete_entries",
    "limit_record",
    "run_catalogue_study",
]

#: A comparison's walls for one device: case → the wall at K = 1 (the search scales its stiffness).
WallsOf = Callable[[Device], Mapping[str, Wall]]


def limit_record(lim: Any) -> dict[str, Any]:
    """A limit as (value, status, range end): enough to say "K", "none (why)" or "> range end"."""
    return {"value": lim.value, "status": lim.status.value, "range_end": lim.range_end}


def complete_entries() -> tuple[CatalogueEntry, ...]:
    """The catalogue devices whose values are complete (the others cannot be simulated).

    Returns
    -------
    tuple of CatalogueEntry
    """
    return tuple(e for e in catalogue() if not e.incomplete)


def catalogue_inputs(
    entries: Sequence[CatalogueEntry] | None, grid: int, speeds: int
) -> tuple[tuple[CatalogueEntry, ...], int, int]:
    """The devices (default :func:`complete_entries`), grid points and impact speeds of a comparison, checked.

    Parameters
    ----------
    entries : sequence of CatalogueEntry or None
        The devices; None for every catalogue device with complete values.
    grid, speeds : int
        The searches' grid points (at least 2) and impact speeds (at least 1).

    Returns
    -------
    (tuple of CatalogueEntry, int, int)

    Raises
    ------
    DFAValueError
        For no entries, or too few grid points or speeds.
    """
    devs = complete_entries() if entries is None else tuple(entries)
    if not devs:
        raise DFAValueError("entries is empty: give at least one catalogue entry with complete values")
    g = check_int("grid", grid, minimum=2, fix="give at least 2 grid points")
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one speed")
    return devs, g, n_speeds


@dataclass(frozen=True)
class CatalogueRun:
    """What :func:`run_catalogue_study` found, one entry per device in each tuple.

    Attributes
    ----------
    entries : tuple of CatalogueEntry
        The devices.
    velocities : tuple of float
        The impact speed of each, m/s (rotary: rad/s).
    device_units : tuple of dict
        Each device's units (``Device.units``).
    limits : tuple of dict
        Per device, case → limit → ``{"value", "status", "range_end"}`` (:func:`limit_record`; N/m, rotary N·m/rad).
    counterexamples : int
        Simulated divergences at stiffnesses the criterion proves passive, over every answer (must be 0).
    """

    entries: tuple[CatalogueEntry, ...]
    velocities: tuple[float, ...]
    device_units: tuple[dict[str, str], ...]
    limits: tuple[dict[str, dict[str, dict[str, Any]]], ...]
    counterexamples: int

    @property
    def devices(self) -> tuple[str, ...]:
        """The devices' names."""
        return tuple(e.name for e in self.entries)

    @property
    def status(self) -> ComparisonStatus:
        """``counterexample`` when any answer has one, else ``ok``."""
        return ComparisonStatus.COUNTEREXAMPLE if self.counterexamples else ComparisonStatus.OK


def run_catalogue_study(
    entries: tuple[CatalogueEntry, ...],
    velocity: float | None,
    grid: int,
    speeds: int,
    walls: WallsOf,
    limits: Sequence[str],
) -> CatalogueRun:
    """Each device's largest stiffness for each wall of ``walls`` (:func:`~dfa.analysis.limits.kmax.design_answer`).

    Parameters
    ----------
    entries : tuple of CatalogueEntry
        The devices, checked (:func:`catalogue_inputs`).
    velocity : float or None
        Impact speed, m/s (rotary: rad/s); None: 0.1 m/s (1 rad/s rotary), the design report's.
    grid, speeds : int
        The searches' grid points and impact speeds, checked.
    walls : callable
        A device → its walls by case, in the table's order (each at K = 1).
    limits : sequence of str
        The :class:`~dfa.analysis.limits.kmax.KMaxResult` limits kept (``k_criterion``, ``k_sim``, ``k_sim_rest``).

    Returns
    -------
    CatalogueRun
    """
    from ..analysis.limits.kmax import design_answer

    vels, units, rows, bad = [], [], [], 0
    for e in entries:
        dev = e.device
        v = velocity if velocity is not None else (1.0 if dev.rotary else 0.1)
        row: dict[str, dict[str, dict[str, Any]]] = {}
        for case, wall in walls(dev).items():
            r = design_answer(Loop(dev, wall), v, grid=grid, speeds=speeds)
            bad += len(r.counterexamples)
            row[case] = {name: limit_record(getattr(r, name)) for name in limits}
        vels.append(float(v))
        units.append(dict(dev.units))
        rows.append(row)
    return CatalogueRun(entries, tuple(vels), tuple(units), tuple(rows), bad)


class CatalogueComparison(Result):
    """What the catalogue comparisons share (:class:`~dfa.studies.contact_comparison.ContactComparison`, and the
    passivity controller's): one entry per device in each field of :attr:`per_device`, the status coerced, and a
    limit's value by device and case.

    Not a dataclass: each subclass is a frozen dataclass with (at least) the fields annotated here.
    """

    devices: tuple[str, ...]
    limits: tuple[dict[str, dict[str, dict[str, Any]]], ...]
    status: ComparisonStatus
    #: The fields with one entry per device (each subclass names its own).
    per_device: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", ComparisonStatus.coerce(self.status, "status"))
        n = len(self.devices)
        for name in self.per_device:
            if len(getattr(self, name)) != n:
                raise DFAValueError(f"{name} has {len(getattr(self, name))} entries for {n} devices: give one each")

    def value(self, device: int, case: str, limit: str) -> float | None:
        """One limit's value (None where it has none), N/m (rotary N·m/rad).

        Parameters
        ----------
        device : int
            The device's index.
        case : str
            One of the comparison's cases (``CASES`` of its module).
        limit : str
            One of the limits it keeps (``k_sim``, ``k_sim_rest``; ``k_criterion`` for the contact comparison).

        Returns
        -------
        float or None
        """
        v = self.limits[device][case][limit]["value"]
        return None if v is None else float(v)
