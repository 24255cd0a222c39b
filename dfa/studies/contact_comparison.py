"""How much the bilateral spring understates what a one-sided wall allows (issue 28 §1), on the catalogue devices.

The paper analyses a bilateral spring: it pulls the device back as hard as it pushes, everywhere. Users render a
one-sided wall reached from free space (:class:`~dfa.model.elements.OneSided`), which pushes only inside and
never pulls, and the operator often presses on it. For each catalogue device with complete values, at one impact
speed, the largest stiffness is found as :func:`~dfa.analysis.limits.kmax.design_answer` finds it, for three
walls (:data:`CASES`):

``bilateral``
    the paper's spring (impacts from ξ0 = 0 and from the energy preload);
``one_sided``
    a one-sided wall at the origin, a free impact (no push: the device may leave for good);
``pushed``
    the same wall with the operator pushing toward it with :data:`PUSH_FRICTIONS` times the device's Coulomb
    friction from the first reading inside on (so the device comes back after a bounce).

Each one-sided impact starts with the approach from free space (:func:`~dfa.analysis.approach.approach_start`).
The criterion's K, the simulated no-divergence limit and the rest limit (for a one-sided wall: every impact
rests or leaves) are kept with their statuses; a limit above the searched range is a lower bound (its range end).

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> c = contact_comparison([get_device("Impulse Engine")], grid=6, speeds=1)
>>> c.devices, sorted(c.limits[0])
(('Impulse Engine',), ['bilateral', 'one_sided', 'pushed'])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..model.catalogue import CatalogueEntry
from ..model.device import Device
from ..model.elements import OneSided, Push
from ..model.wall import Wall
from ..results.status import ComparisonStatus
from .catalogue_study import CatalogueComparison, catalogue_inputs, complete_entries, limit_record, run_catalogue_study

__all__ = [
    "CASES",
    "LIMITS",
    "PUSH_FRICTIONS",
    "ContactComparison",
    "contact_comparison",
    "complete_entries",
    "limit_record",
    "CatalogueComparison",
]

#: The walls compared, in the table's order.
CASES = ("bilateral", "one_sided", "pushed")
#: The limits kept of each design answer (:class:`~dfa.analysis.limits.kmax.KMaxResult` fields).
LIMITS = ("k_criterion", "k_sim", "k_sim_rest")
#: The pushed wall's push, in units of the device's Coulomb friction c.
PUSH_FRICTIONS = 2.0


@dataclass(frozen=True)
class ContactComparison(CatalogueComparison):
    """The largest stiffness of the bilateral spring and of the one-sided wall, per catalogue device.

    Attributes
    ----------
    devices : tuple of str
        The catalogue devices.
    velocities : tuple of float
        The impact speed of each, m/s (rotary: rad/s).
    pushes : tuple of float
        The pushed wall's push F_p of each, N (rotary: N·m): :data:`PUSH_FRICTIONS` × c.
    device_units : tuple of dict
        Each device's units (``Device.units``).
    limits : tuple of dict
        Per device, case (:data:`CASES`) → limit (:data:`LIMITS`) → ``{"value", "status", "range_end"}``
        (N/m; rotary N·m/rad).
    counterexamples : int
        Simulated divergences at stiffnesses the criterion proves passive, over every answer (must be 0).
    grid, speeds : int
        The searches' grid points and impact speeds (:func:`~dfa.analysis.limits.kmax.design_answer`).
    status : ComparisonStatus
        ``ok``, or ``counterexample``.
    """

    devices: tuple[str, ...]
    velocities: tuple[float, ...]
    pushes: tuple[float, ...]
    device_units: tuple[dict[str, str], ...]
    limits: tuple[dict[str, dict[str, dict[str, Any]]], ...] = field(repr=False)
    counterexamples: int
    grid: int
    speeds: int
    status: ComparisonStatus

    json_properties: ClassVar[tuple[str, ...]] = ()

    #: The fields with one entry per device.
    per_device: ClassVar[tuple[str, ...]] = ("velocities", "pushes", "device_units", "limits")


def contact_comparison(
    entries: Sequence[CatalogueEntry] | None = None,
    *,
    velocity: float | None = None,
    grid: int = 16,
    speeds: int = 6,
) -> ContactComparison:
    """Compare the bilateral spring's largest stiffness with the one-sided wall's (module docstring).

    Parameters
    ----------
    entries : sequence of CatalogueEntry, optional
        The devices (default :func:`complete_entries`).
    velocity : float, optional
        Impact speed, m/s (rotary: rad/s); default 0.1 m/s (1 rad/s rotary), the design report's.
    grid, speeds : int, optional
        The searches' grid points and impact speeds (defaults those of ``dfa stiffness``).

    Returns
    -------
    ContactComparison

    See Also
    --------
    design_answer : The largest stiffness four ways, for one wall.
    run_catalogue_study : The runner both catalogue comparisons share.
    """
    devs, g, n_speeds = catalogue_inputs(entries, grid, speeds)
    run = run_catalogue_study(devs, velocity, g, n_speeds, _walls, LIMITS)
    pushes = tuple(float(PUSH_FRICTIONS * e.device.coulomb) for e in devs)
    return ContactComparison(
        run.devices, run.velocities, pushes, run.device_units, run.limits, run.counterexamples, g, n_speeds, run.status
    )


def _walls(dev: Device) -> dict[str, Wall]:
    """The walls of :data:`CASES` for one device, at K = 1 (the pushed wall's push :data:`PUSH_FRICTIONS` × c)."""
    return {
        "bilateral": Wall(1.0),
        "one_sided": Wall(1.0, (OneSided(0.0),)),
        "pushed": Wall(1.0, (OneSided(0.0), Push(PUSH_FRICTIONS * dev.coulomb))),
    }
