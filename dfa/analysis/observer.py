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

from typing import Any

import numpy as np

from ..checks import check_type
from ..errors import DFAValueError
from ..model.elements import PassivityController
from ..results.observer import ForceError as ForceError
from ..results.observer import ObserverSummary as ObserverSummary
from ..results.status import ObserverStatus

__all__ = ["ObserverSummary", "ForceError", "observe", "force_error"]


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
        controller=result.wall.group(PassivityController) is not None,
        acting=int(np.count_nonzero(f)),
        peak_controller_force=float(np.max(np.abs(f))) if f.size else 0.0,
        wall=result.wall,
        status=ObserverStatus.ACTIVE if peak > 0.0 else ObserverStatus.PASSIVE,
    )


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
