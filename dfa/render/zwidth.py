"""Notes under the ``dfa zwidth`` table: non-monotone columns and a damper the criterion cannot prove with.

Examples
--------
>>> non_monotone_mark(False), non_monotone_mark(True)
('', '*')
"""

from __future__ import annotations

from typing import Any

from ..formatting import number
from ..results.require import DamperGuidance

__all__ = ["criterion_damper_note", "non_monotone_mark", "non_monotone_notes"]


def non_monotone_mark(non_monotone: bool) -> str:
    """The mark of a non-monotone cell (``"*"``), empty otherwise."""
    return "*" if non_monotone else ""


def non_monotone_notes(zw: Any, columns: dict[str, str]) -> list[str]:
    """One line per non-monotone cell: where the runs were safe again above the limit the cell gives.

    Parameters
    ----------
    zw : ZWidth
    configuration : str, optional
        The configuration ``g`` is of (default "": a single device).
        From :func:`dfa.analysis.limits.zwidth.z_width`.
    columns : dict of str to str
        Column heading of each method.

    Returns
    -------
    list of str
        Lines (at most one per column, cells listed by B), empty when every column is monotone.
    """
    ku, bu = zw.device.units["stiffness"], zw.device.units["damping"]
    out = []
    for m, head in columns.items():
        cells = [(b, lim) for b, lim in zip(zw.damping, zw.limits[m], strict=True) if lim.non_monotone]
        if not cells:
            continue
        parts = []
        for b, lim in cells[:3]:
            above = ", ".join(number(k, 4) for k in lim.safe_above[:3]) + (" …" if len(lim.safe_above) > 3 else "")
            parts.append(f"B = {number(float(b), 4)}: safe again at K = {above} {ku}")
        more = f" (and {len(cells) - 3} more B, --json)" if len(cells) > 3 else ""
        out.append(f"* {head} non-monotone (the cell is the first failure): {'; '.join(parts)}{more} [{bu}]")
    return out


def criterion_damper_note(g: DamperGuidance, zw: Any, configuration: str = "") -> str:
    """Why the criterion column is '-' for B > 0 (or from some B on), and the largest B it proves a K with; empty
    if no B > 0 has a '-'. Over configurations, ``g`` is the strictest one's, named ``configuration``.

    Parameters
    ----------
    g : DamperGuidance
        :func:`dfa.analysis.limits.require.damper_guidance` for the Z-width's device, wall and speed.
    zw : ZWidth

    Returns
    -------
    str
    """
    crit = zw.limits["criterion"]
    dashes = [float(b) for b, lim in zip(zw.damping, crit, strict=True) if b > 0 and lim.value is None]
    if not dashes:
        return ""
    u = zw.device.units
    every = len(dashes) == sum(1 for b in zw.damping if b > 0)
    where = "for B > 0" if every else f"from B = {number(dashes[0], 4)} {u['damping']}"
    restore = (
        f"; c > {number(g.min_coulomb, 4)} {u['coulomb']} would restore it at the grid's first B > 0"
        if not g.proves_some_k
        else ""
    )
    return (
        f"criterion '-' {where}: with a damper it proves no K at {number(zw.velocity, 4)} {u['velocity']} "
        f"unless B < {number(g.max_virtual_damping, 4)} {u['damping']} (it costs friction (1 − a)BΔ/T and damping "
        f"B){restore}" + (f" (configuration {configuration}, the strictest)" if configuration else "")
    )


def damping_axis_note() -> str:
    """How the default damping axis is chosen (the grid line of ``dfa zwidth``)."""
    return ": twice where the passivity boundaries end, --damping-max sets it"
