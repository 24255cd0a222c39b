"""Files other than the reports: a simulated trajectory as CSV (the studies write their own documents:
:func:`dfa.studies.validation_document.write_validation`, :func:`dfa.studies.soundness_document.write_soundness`).

All written atomically (:mod:`dfa._io`): a report's files appear together, or none.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from .._io import atomic_open
from ..jsonable import JSON_DIGITS

__all__ = ["trace_extent", "write_trace_csv"]


def write_trace_csv(
    result: Any, path: str | os.PathLike, device: Any = None, stiffness: float | None = None, *, observer: bool = False
) -> Path:
    """Write a recorded simulation (``record=True``) as CSV, one row per sample instant.

    Columns ``sample,xi,xi_dot,phi``: ticks, ticks per sample, and the force on the device φ_A in units of KΔ
    (:meth:`~dfa.analysis.simulation.SimulationResult.applied_force`). With a device (and K) the same in
    physical units beside them (:func:`dfa.model.units.trace_columns`): ``t_s`` (sample × T), ``x_m`` (ξΔ),
    ``v_m_per_s`` (ξ'Δ/T), ``force_n`` (φ_A·KΔ); rotary ``x_rad``, ``v_rad_per_s``, ``force_nm``.
    With ``observer`` a column ``produced_energy`` (KΔ², the energy the wall has produced up to the sample, −E_obs
    of :meth:`~dfa.analysis.simulation.SimulationResult.observed_energy`: positive when it has been active), and
    ``controller_phi`` (KΔ, the passivity controller's force) for a wall with one; with a device
    ``produced_energy_j`` and ``controller_force_n`` (rotary ``controller_force_nm``) beside them. A run that
    stopped at a decided outcome (rest proven, divergence, left the wall) is written up to that sample
    (:attr:`~dfa.analysis.simulation.SimulationResult.recorded_samples`), without the repeated rest state or the
    NaN rows after it; :func:`trace_extent` says where and why. Numbers carry 12 significant digits.

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`dfa.simulate` with ``record=True``.
    path : path
        The CSV file; replaced atomically (the old file stays if writing fails).
    device : Device, optional
        The physical device, for the physical columns (none without it: dimensionless input).
    stiffness : float, optional
        K in N/m (rotary N·m/rad), with ``device``.
    observer : bool, optional
        Add the passivity observer's columns (default False).

    Returns
    -------
    Path
    """
    import numpy as np

    from ..checks import check_positive
    from ..model import units
    from ..model.elements import PassivityController

    xi, xi_dot = result.xi, result.xi_dot
    phi, energy, control = result.replay()  # one replay for every column
    pc = observer and result.wall.group(PassivityController) is not None
    extra = ([-energy] if observer else []) + ([control] if pc else [])
    # A run stopped at a decided outcome holds after its last sample the rest state (rest proven) or NaN
    # (diverged, left the wall): those rows are no data, the trace ends there (trace_extent says why).
    last = result.recorded_samples + 1
    xi, xi_dot, phi = xi[:last], xi_dot[:last], phi[:last]
    extra = [e[:last] for e in extra]
    sample = np.arange(xi.size)
    names, cols = ["sample", "xi", "xi_dot", "phi"], [sample, xi, xi_dot, phi]
    names += ["produced_energy", "controller_phi"][: len(extra)]
    cols += extra
    if device is not None:
        stiffness = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
        c = units.trace_columns(device)
        names += [c["time"], c["position"], c["velocity"], c["force"]]
        cols += [
            units.seconds(device, sample),
            units.position(device, xi),
            units.speed(device, xi_dot),
            units.force(device, stiffness, phi),
        ]
        if extra:
            names.append("produced_energy_j")
            cols.append(units.energy(device, stiffness, extra[0]))
        if pc:
            names.append(c["force"].replace("force", "controller_force"))
            cols.append(units.force(device, stiffness, extra[1]))
    with atomic_open(path, "w") as fh:
        fh.write(",".join(names) + "\n")
        # 12 significant digits (JSON's, dfa.jsonable.JSON_DIGITS); + 0.0 writes -0 as 0
        table = np.column_stack(cols) + 0.0
        np.savetxt(fh, table, delimiter=",", fmt=["%d"] + [f"%.{JSON_DIGITS}g"] * (len(cols) - 1))
    return Path(path)


def trace_extent(result: Any) -> tuple[int, str]:
    """The last sample a trace of ``result`` holds (:func:`write_trace_csv`), and why it ends there.

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`dfa.simulate`.

    Returns
    -------
    tuple
        (last sample, the reason in a few words: the decided outcome, or why the whole run is written).
    """
    last = int(result.recorded_samples)
    outcome = str(result.outcome.value)
    if last < int(result.samples):
        why = {
            "rest": "at rest from there on",
            "unstable": "diverged there",
            "left": "left the wall for good there",
        }.get(outcome, f"the run stopped there ({outcome})")
        return last, why
    whole = {
        "unstable": "the whole run: its growth is judged over the run",
        "undecided": "the whole run: still undecided at its end",
    }
    return last, whole.get(outcome, f"the whole run: {outcome} is judged over its tail")
