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

from ..checks import check_int
from ..errors import DFAValueError
from ..model.catalogue import CatalogueEntry, catalogue
from ..model.elements import OneSided, Push
from ..model.loop import Loop
from ..model.wall import Wall
from ..results.base import Result
from ..results.status import ComparisonStatus

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


def limit_record(lim: Any) -> dict[str, Any]:
    """A limit as (value, status, range end): enough to say "K", "none (why)" or "> range end"."""
    return {"value": lim.value, "status": lim.status.value, "range_end": lim.range_end}


class CatalogueComparison(Result):
    """What the catalogue comparisons share (:class:`ContactComparison`, and the passivity controller's): one entry
    per device in each field of :attr:`per_device`, the status coerced, and a limit's value by device and case.

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


def complete_entries() -> tuple[CatalogueEntry, ...]:
    """The catalogue devices whose values are complete (the others cannot be simulated).

    Returns
    -------
    tuple of CatalogueEntry
    """
    return tuple(e for e in catalogue() if not e.incomplete)


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
    """
    from ..analysis.limits.kmax import design_answer

    devs = complete_entries() if entries is None else tuple(entries)
    if not devs:
        raise DFAValueError("entries is empty: give at least one catalogue entry with complete values")
    g = check_int("grid", grid, minimum=2, fix="give at least 2 grid points")
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one speed")
    vels, pushes, units, limits, bad = [], [], [], [], 0
    for e in devs:
        dev = e.device
        v = velocity if velocity is not None else (1.0 if dev.rotary else 0.1)
        push = PUSH_FRICTIONS * dev.coulomb
        walls = {
            "bilateral": Wall(1.0),
            "one_sided": Wall(1.0, (OneSided(0.0),)),
            "pushed": Wall(1.0, (OneSided(0.0), Push(push))),
        }
        row: dict[str, dict[str, dict[str, Any]]] = {}
        for case in CASES:
            r = design_answer(Loop(dev, walls[case]), v, grid=g, speeds=n_speeds)
            bad += len(r.counterexamples)
            row[case] = {name: limit_record(getattr(r, name)) for name in LIMITS}
        vels.append(float(v))
        pushes.append(float(push))
        units.append(dict(dev.units))
        limits.append(row)
    status = ComparisonStatus.COUNTEREXAMPLE if bad else ComparisonStatus.OK
    return ContactComparison(
        tuple(e.name for e in devs), tuple(vels), tuple(pushes), tuple(units), tuple(limits), bad, g, n_speeds, status
    )
