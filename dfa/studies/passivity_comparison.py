"""What a passivity controller buys and costs on the catalogue devices (issue 30): the validation table.

For each catalogue device with complete values, at the design report's impact speed, the largest stiffness is
found as :func:`~dfa.analysis.limits.kmax.design_answer` finds it for three walls (:data:`CASES`):

``plain``
    the paper's spring;
``limited``
    the spring with the passivity controller (:class:`~dfa.model.elements.PassivityController`, an unbounded
    observer) whose force is limited to :data:`LIMIT_FRICTIONS` times the device's Coulomb friction c;
``unlimited``
    the textbook controller: no force limit.

The simulated no-divergence limit (``k_sim``) and rest limit (``k_sim_rest``) are kept with their statuses (no
criterion, linear bound or describing function covers the controller). The price, at the plain wall's own
no-divergence limit K₀ (the stiffest it renders; an impact at V from ξ0 = 0): the rendered force against the ideal
spring, RMS and peak over the impact (:func:`~dfa.analysis.observer.force_error`), without and with the limited
controller, and the share of readings at which it acts. And the case :data:`FAILURE_CASE`: a force limit too low
for the stiffness makes the controlled wall diverge.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> c = passivity_comparison([get_device("Impulse Engine")], grid=6, speeds=1)
>>> c.devices, sorted(c.limits[0])
(('Impulse Engine',), ['limited', 'plain', 'unlimited'])
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

from ..checks import check_positive
from ..model.catalogue import CatalogueEntry, get_device
from ..model.device import Device
from ..model.elements import PassivityController
from ..model.loop import Loop
from ..model.wall import Wall
from ..results.base import figure_function
from ..results.status import ComparisonStatus
from .catalogue_study import CatalogueComparison, catalogue_inputs, run_catalogue_study

__all__ = ["CASES", "LIMIT_FRICTIONS", "FAILURE_CASE", "PassivityComparison", "passivity_comparison", "impact"]

#: The walls compared, in the table's order.
CASES = ("plain", "limited", "unlimited")
#: The limited controller's force limit, in units of the device's Coulomb friction c.
LIMIT_FRICTIONS = 10.0
#: A force limit that makes the controller fail: (device, K in N/m, V in m/s, the force limits compared in N).
FAILURE_CASE = ("Phantom 1.0", 6000.0, 0.1, (0.3, 1.0))
#: Samples of the price's runs and of the failure case's.
IMPACT_SAMPLES = 60_000


def _wall(case: str, dev: Device, k: float = 1.0) -> Wall:
    """The wall of a case at stiffness K."""
    if case == "plain":
        return Wall(k)
    limit = LIMIT_FRICTIONS * dev.coulomb if case == "limited" else None
    return Wall(k, (PassivityController(force_limit=limit),))


def _walls(dev: Device) -> dict[str, Wall]:
    """The walls of :data:`CASES` for one device, at K = 1."""
    return {case: _wall(case, dev) for case in CASES}


def impact(dev: Device, wall: Wall, velocity: float, samples: int = IMPACT_SAMPLES) -> Any:
    """The recorded impact at ``velocity`` (m/s; rad/s) from ξ0 = 0 on ``wall`` (its K), as ``dfa simulate`` runs it.

    Parameters
    ----------
    dev : Device
        The device.
    wall : Wall
        The wall and its stiffness.
    velocity : float
        The impact speed.
    samples : int, optional
        Samples simulated.

    Returns
    -------
    SimulationResult
    """
    from ..analysis.simulation import simulate

    return simulate(Loop(dev, wall), dev.xi_dot(velocity), samples=samples)


def _price(dev: Device, k0: float | None, v: float) -> dict[str, Any]:
    """Force errors (KΔ → N, N·m) of the plain and the limited wall at K₀, and the controller's share of readings."""
    from ..analysis.observer import force_error, observe
    from ..model import units

    if k0 is None:
        return {"stiffness": None, "plain": None, "limited": None, "acting_share": None, "outcomes": None}
    out: dict[str, Any] = {"stiffness": k0, "outcomes": {}}
    for case in ("plain", "limited"):
        r = impact(dev, _wall(case, dev, k0), v)
        e = force_error(r)
        out[case] = {name: units.force(dev, k0, getattr(e, name)) for name in ("rms", "peak", "peak_ideal")}
        out["outcomes"][case] = r.outcome.value
        if case == "limited":
            out["acting_share"] = observe(r).acting_share
    return out


def _failure() -> dict[str, Any]:
    """The failure case: the outcome of the plain wall and of the controller at each force limit."""
    name, k, v, limits = FAILURE_CASE
    dev = get_device(name).device
    rows = {"plain": impact(dev, Wall(k), v, IMPACT_SAMPLES).outcome.value}
    for f in limits:
        rows[f"{f:g}"] = impact(dev, Wall(k, (PassivityController(force_limit=f),)), v).outcome.value
    return {"device": name, "stiffness": k, "velocity": v, "force_limits": list(limits), "outcomes": rows}


@dataclass(frozen=True)
class PassivityComparison(CatalogueComparison):
    """The largest stiffness without and with a passivity controller, and its price, per catalogue device.

    Attributes
    ----------
    devices : tuple of str
        The catalogue devices.
    velocities : tuple of float
        The impact speed of each, m/s (rotary: rad/s).
    force_limits : tuple of float
        The limited controller's force limit of each, N (rotary: N·m): ``limit_frictions`` × c.
    limit_frictions : float
        That limit in units of each device's Coulomb friction c (:data:`LIMIT_FRICTIONS`).
    device_units : tuple of dict
        Each device's units (``Device.units``).
    limits : tuple of dict
        Per device, case (:data:`CASES`) → ``k_sim``/``k_sim_rest`` → ``{"value", "status", "range_end"}``.
    prices : tuple of dict
        Per device, at the plain wall's no-divergence limit K₀ (``stiffness``): the force error of the ``plain``
        and ``limited`` walls (``rms``, ``peak``, ``peak_ideal``, N; rotary N·m), the controller's
        ``acting_share`` and the runs' ``outcomes``; None values without a K₀.
    failure : dict
        :data:`FAILURE_CASE`'s outcomes (``plain`` and each force limit).
    counterexamples : int
        Simulated divergences of the plain wall at stiffnesses the criterion proves passive (must be 0).
    grid, speeds : int
        The searches' grid points and impact speeds.
    status : ComparisonStatus
        ``ok``, or ``counterexample``.
    """

    devices: tuple[str, ...]
    velocities: tuple[float, ...]
    force_limits: tuple[float, ...]
    limit_frictions: float
    device_units: tuple[dict[str, str], ...]
    limits: tuple[dict[str, dict[str, dict[str, Any]]], ...] = field(repr=False)
    prices: tuple[dict[str, Any], ...] = field(repr=False)
    failure: dict[str, Any] = field(repr=False)
    counterexamples: int
    grid: int
    speeds: int
    status: ComparisonStatus

    json_properties: ClassVar[tuple[str, ...]] = ()

    #: The fields with one entry per device.
    per_device: ClassVar[tuple[str, ...]] = ("velocities", "force_limits", "device_units", "limits", "prices")

    def plot(self, ax: Any = None) -> Any:
        """Bars of the no-divergence and rest limits per device and wall (:func:`dfa.render.figures.passivity_plot`).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on; a new figure when None.

        Returns
        -------
        matplotlib.axes.Axes
        """
        passivity_plot = figure_function("passivity_plot")
        return passivity_plot(self, ax)


def passivity_comparison(
    entries: Sequence[CatalogueEntry] | None = None,
    *,
    velocity: float | None = None,
    grid: int = 16,
    speeds: int = 6,
) -> PassivityComparison:
    """Compare the plain wall's largest stiffness with the controlled wall's, and the price (module docstring).

    Parameters
    ----------
    entries : sequence of CatalogueEntry, optional
        The devices (default: every catalogue device with complete values).
    velocity : float, optional
        Impact speed, m/s (rotary: rad/s); default 0.1 m/s (1 rad/s rotary), the design report's.
    grid, speeds : int, optional
        The searches' grid points and impact speeds (defaults those of ``dfa stiffness``).

    Returns
    -------
    PassivityComparison

    See Also
    --------
    run_catalogue_study : The runner both catalogue comparisons share.
    """
    devs, g, n_speeds = catalogue_inputs(entries, grid, speeds)
    if velocity is not None:
        check_positive("velocity", velocity, "give the impact speed in m/s (rotary: rad/s)")
    run = run_catalogue_study(devs, velocity, g, n_speeds, _walls, ("k_sim", "k_sim_rest"))
    forces = tuple(LIMIT_FRICTIONS * e.device.coulomb for e in devs)
    prices = tuple(
        _price(e.device, row["plain"]["k_sim"]["value"], v)
        for e, row, v in zip(devs, run.limits, run.velocities, strict=True)
    )
    return PassivityComparison(
        run.devices, run.velocities, forces, LIMIT_FRICTIONS, run.device_units, run.limits, prices,
        _failure(), run.counterexamples, g, n_speeds, run.status,
    )  # fmt: skip
