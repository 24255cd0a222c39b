"""Files other than the design report: a simulated trajectory as CSV, the validation report (all written atomically)."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from .._io import atomic_open, staged_folder
from ..results.jsonable import dumps

__all__ = ["write_trace_csv", "write_validation"]


def write_trace_csv(result: Any, path: str | os.PathLike) -> Path:
    """Write a recorded simulation (``record=True``) as CSV: ``sample,xi,xi_dot`` (ticks, ticks/sample).

    A run that stopped early (``unstable``) is written up to its last integrated sample
    (``samples_run``), without the NaN rows after it.

    Parameters
    ----------
    result : SimulationResult
        A run of :func:`dfa.simulate` with ``record=True``.
    path : path
        The CSV file; replaced atomically (the old file stays if writing fails).

    Returns
    -------
    Path
    """
    import numpy as np

    xi, xi_dot = result.xi, result.xi_dot
    # A run stopped early (diverged) holds NaN after its last sample: those rows are not data, leave them out.
    last = int(result.samples_run) + 1
    if last < xi.size and not (np.isfinite(xi[last:]).any() or np.isfinite(xi_dot[last:]).any()):
        xi, xi_dot = xi[:last], xi_dot[:last]
    with atomic_open(path, "w") as fh:
        fh.write("sample,xi,xi_dot\n")
        table = np.column_stack([np.arange(xi.size), xi, xi_dot])
        np.savetxt(fh, table, delimiter=",", fmt=["%d", "%.17g", "%.17g"])
    return Path(path)


def write_validation(result: Any, out: str | os.PathLike) -> dict[str, Any]:
    """Write ``validation.md``, ``validation.json`` and two figures into the folder ``out`` (all four, or none).

    Parameters
    ----------
    result : ValidationResult
        From :func:`dfa.validate`.
    out : path
        Folder (created if missing; its parent must exist).

    Returns
    -------
    dict
        The strict-JSON summary written to ``validation.json`` (:meth:`ValidationResult.to_dict`: the
        summary, NaN as null with ``null_reasons``, and the status).
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from .. import figures

    os.makedirs(out, exist_ok=True)
    summary = result.to_dict()
    figs = {}
    with staged_folder(out) as stage:
        for key, fn in (("cycles", figures.cycle_error_plot), ("speeds", figures.critical_speed_plot)):
            ax = fn(result)
            figs[key] = f"validation_{key}.png"
            ax.figure.savefig(stage / figs[key], dpi=120)
            plt.close(ax.figure)
        (stage / "validation.md").write_text(result.to_markdown(figs), encoding="utf-8")
        (stage / "validation.json").write_text(dumps(summary, indent=1), encoding="utf-8")
    return summary
