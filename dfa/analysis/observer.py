"""The passivity observer over a simulated run, and the force a wall renders against the ideal spring (issue 30).

:func:`observe` summarises what the passivity observer (Hannaford and Ryu 2002; the sampled form of
:class:`dfa.model.elements.PassivityController`) saw over a recorded run of :func:`dfa.simulate`: the energy the
wall produced (−E_obs, positive: active) at the end and at its most, and with a passivity controller how often it
acted and its largest force. :func:`force_error` is the price of a wall against the ideal spring −K x over the
impact: the RMS and peak of φ_A − φ_ideal. Both read the run's own replay
(:meth:`~dfa.analysis.simulation.SimulationResult.observed_energy`,
:meth:`~dfa.analysis.simulation.SimulationResult.controller_force`,
:meth:`~dfa.analysis.simulation.SimulationResult.applied_force`): one implementation of the observer, the
kernel's. Dimensionless (energy in KΔ², force in KΔ); :meth:`ObserverSummary.physical` gives J and N.

Examples
--------
The paper's spring at μ = 100, β = 0.1 (below the criterion's β > ½): the observer sees the wall produce energy.

>>> from dfa.analysis.simulation import simulate
>>> s = observe(simulate(100.0, 0.1, 0.05, 3.0, samples=2000))
>>> s.status.value, s.peak_produced > 0, s.acting
('active', True, 0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..checks import check_int, check_nonnegative, check_real, check_type
from ..errors import DFAValueError
from ..model.wall import WallParams
from ..results.base import Result
from ..results.status import ObserverStatus

__all__ = ["ObserverSummary", "ForceError", "observe", "force_error"]


@dataclass(frozen=True)
class ObserverSummary(Result):
    """What the passivity observer saw over one recorded run (module docstring).

    Attributes
    ----------
    produced : float
        The energy the wall produced over the run, −E_obs at the last reading, in KΔ² (negative: it absorbed).
    peak_produced : float
        The most it had produced at any reading, max(0, max −E_obs), in KΔ².
    peak_sample : int
        The reading of that peak (0 when it never produced any).
    samples : int
        Readings observed (to the run's last integrated sample).
    controller : bool
        Whether the wall has a passivity controller.
    acting : int
        Readings at which the controller added a force (0 without one).
    peak_controller_force : float
        Its largest force in KΔ (0 without one).
    wall : WallParams
        The wall of the run.
    status : ObserverStatus
        ``active`` when the wall produced energy at some reading, else ``passive``.
    """

    produced: float
    peak_produced: float
    peak_sample: int
    samples: int
    controller: bool
    acting: int
    peak_controller_force: float
    wall: WallParams = field(metadata={"json": lambda w: w.to_dict()})
    status: ObserverStatus = ObserverStatus.PASSIVE

    def __post_init__(self) -> None:
        object.__setattr__(self, "produced", check_real("produced", self.produced))
        object.__setattr__(self, "peak_produced", check_nonnegative("peak_produced", self.peak_produced))
        for name in ("peak_sample", "samples", "acting"):
            object.__setattr__(self, name, check_int(name, getattr(self, name), 0))
        force = check_nonnegative("peak_controller_force", self.peak_controller_force)
        object.__setattr__(self, "peak_controller_force", force)
        object.__setattr__(self, "status", ObserverStatus.coerce(self.status))
        if not isinstance(self.wall, WallParams):
            raise DFAValueError(f"wall = {self.wall!r} is invalid: it must be a WallParams; pass the run's wall")

    @property
    def acting_share(self) -> float:
        """The share of readings at which the controller acted (0 to 1)."""
        return self.acting / self.samples if self.samples else 0.0

    json_properties = ("acting_share",)

    def physical(self, device: Any, stiffness: float) -> dict[str, float]:
        """The energies in J (rotary J too) and the controller's force in N (rotary N·m) for a device at K.

        Parameters
        ----------
        device : Device
            The physical device (its resolution Δ).
        stiffness : float
            K in N/m (rotary N·m/rad).

        Returns
        -------
        dict
            ``produced_j``, ``peak_produced_j`` (E × K Δ²) and ``peak_controller_force_n`` (f × K Δ).
        """
        from ..model import units

        return {
            "produced_j": units.energy(device, stiffness, self.produced),
            "peak_produced_j": units.energy(device, stiffness, self.peak_produced),
            "peak_controller_force_n": units.force(device, stiffness, self.peak_controller_force),
        }


def _observed_span(result: Any) -> int:
    """Readings 0 … n of a recorded run that hold data (to the last integrated sample of a diverged run)."""
    from .simulation import SimulationResult

    check_type("result", result, SimulationResult, "give a run of dfa.simulate(..., record=True)")
    if result.xi is None:
        raise DFAValueError(
            "xi = None is invalid for the observer: the trajectory was not recorded; run simulate(..., record=True)"
        )
    return min(int(result.samples_run) + 1, result.xi.size)


def observe(result: Any) -> ObserverSummary:
    """Summarise the passivity observer over a recorded run (module docstring).

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`dfa.simulate` with ``record=True`` (any wall).

    Returns
    -------
    ObserverSummary
        The energy the wall produced (at the end and at most), and the controller's counts.

    Raises
    ------
    DFAValueError
        When the run was not recorded.
    DFATypeError
        When ``result`` is not a :class:`~dfa.analysis.simulation.SimulationResult`.

    See Also
    --------
    force_error : The rendered force against the ideal spring over the impact.
    dfa.PassivityController : The observer's and the controller's formulas.
    """
    n = _observed_span(result)
    _force, energy, control = result.replay()  # one replay for both
    produced, f = -np.asarray(energy[:n]), np.asarray(control[:n])
    finite = np.isfinite(produced)
    produced, f = produced[finite], f[finite]
    top = int(np.argmax(produced)) if produced.size else 0
    peak = max(float(produced[top]) if produced.size else 0.0, 0.0)
    return ObserverSummary(
        produced=float(produced[-1]) + 0.0 if produced.size else 0.0,  # + 0.0: no "-0 J"
        peak_produced=peak,
        peak_sample=top if peak > 0.0 else 0,
        samples=int(produced.size),
        controller=bool(result.wall.passivity_controller),
        acting=int(np.count_nonzero(f)),
        peak_controller_force=float(np.max(np.abs(f))) if f.size else 0.0,
        wall=result.wall,
        status=ObserverStatus.ACTIVE if peak > 0.0 else ObserverStatus.PASSIVE,
    )


@dataclass(frozen=True)
class ForceError:
    """The force a wall renders against the ideal spring over an impact (units of KΔ).

    Attributes
    ----------
    rms, peak : float
        RMS and largest |φ_A − φ_ideal| over the impact's sample instants, φ_ideal = −(ξ − s)⁺ on a one-sided
        wall, −ξ on a bilateral one (the continuous spring K x); NaN when the run diverged within it.
    samples : int
        Sample instants of the impact: from the first one inside the wall to the first one back outside
        (ξ <= s), or the run's end.
    peak_ideal : float
        The ideal spring's largest force over the impact (what the errors compare with).
    """

    rms: float
    peak: float
    samples: int
    peak_ideal: float

    def to_dict(self) -> dict[str, Any]:
        """The errors as JSON-able data (NaN as None)."""
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in vars(self).items()}


def force_error(result: Any) -> ForceError:
    """The RMS and peak error of the rendered force against the ideal spring over the run's first impact.

    Parameters
    ----------
    result : SimulationResult
        A recorded run of :func:`dfa.simulate` that enters the wall (ξ beyond the surface, 0 for a bilateral wall).

    Returns
    -------
    ForceError
        The RMS and peak error, the impact's length and the ideal spring's peak force.

    Raises
    ------
    DFAValueError
        When the run was not recorded or never entered the wall.
    """
    n = _observed_span(result)
    s = result.wall.surface
    xi, phi = np.asarray(result.xi[:n]), np.asarray(result.applied_force()[:n])
    inside = xi > s
    if not inside.any():
        raise DFAValueError("the run never entered the wall: no impact to compare; give a speed toward the wall")
    start = int(np.argmax(inside))
    out = np.flatnonzero(~inside[start:])
    stop = start + (int(out[0]) if out.size else xi.size - start)
    ideal = -(xi[start:stop] - s)
    err = phi[start:stop] - ideal
    return ForceError(
        rms=float(np.sqrt(np.mean(err**2))),
        peak=float(np.max(np.abs(err))),
        samples=int(stop - start),
        peak_ideal=float(np.max(np.abs(ideal))),
    )
