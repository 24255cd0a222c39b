"""The inverse answer on one screen: what each parameter must be for a target stiffness (``dfa require``).

Every line is at most :data:`~dfa.formatting.WIDTH` characters; the JSON carries every number
(:meth:`dfa.analysis.limits.require.Requirements.to_dict`).
"""

from __future__ import annotations

import math

from ..formatting import WIDTH, fill, number, round_at, text_table
from ..results.require import ALL_METHODS, PARAMETERS, DamperGuidance, Requirement, Requirements
from ..results.status import RequireStatus
from .hand import device_title
from .start_state import start_state_clause

__all__ = ["LABELS", "damper_line", "require_screen", "requirement_cell"]

#: How each parameter is named in a table.
LABELS = {
    "period": "sample period T",
    "resolution": "encoder resolution Δ",
    "coulomb": "Coulomb friction c",
    "damping": "viscous damping b",
    "virtual_damping": "virtual damper B",
    "delay": "delay d",
}
_METHOD_HEADS = {
    "criterion": "criterion (proof)",
    "linear": "linear (necessary)",
    "df": "describing function",
}
_CELL = {
    RequireStatus.UNREACHABLE: "no value helps",
    RequireStatus.ANY: "any value",
    RequireStatus.NO_EFFECT: "not in this model",
    RequireStatus.NOT_COVERED: "not covered",
}


def _unit(units: dict[str, str], name: str, value: float = 0.0) -> str:
    kind = PARAMETERS[name]
    return ("sample" if value == 1 else "samples") if kind == "samples" else units[kind]


def _safe(x: float, bound: str) -> str:
    """``x`` at 4 significant digits rounded toward the side where K holds: up for a lower bound (≥), down for
    an upper bound (≤), so that the printed value itself meets the requirement.

    Examples
    --------
    >>> _safe(0.821000000238, "at_least"), _safe(1.49913e-04, "at_most"), _safe(0.0, "at_least")
    ('0.8211', '0.0001499', '0')
    """
    if x == 0.0 or not math.isfinite(x):
        return number(x, 4)
    place = math.floor(math.log10(abs(x))) - 3
    return number(round_at(x, place, "up" if bound == "at_least" else "down"), 4)


def requirement_cell(r: Requirement, units: dict[str, str]) -> str:
    """One table cell: ``"≤ 17.38 ms (holds)"``-like text, or what the status says instead of a value.

    Parameters
    ----------
    r : Requirement
    units : dict of str to str
        The device's units (:attr:`~dfa.model.device.Device.units`).

    Returns
    -------
    str
    """
    if r.required is None:
        return _CELL[r.status]
    sign = "≤" if r.bound == "at_most" else "≥"
    value = f"{r.required:.0f}" if r.parameter == "delay" else _safe(r.required, r.bound)
    now = "holds now" if r.status is RequireStatus.MET else "change"
    return f"{sign} {value} {_unit(units, r.parameter, r.required)} ({now})"


def require_screen(req: Requirements) -> list[str]:
    """The lines of ``dfa require``: the question, the table (parameter, now, each method), what the cells mean.

    Parameters
    ----------
    req : Requirements
        From :func:`dfa.analysis.limits.require.requirements`.

    Returns
    -------
    list of str
        Lines of at most :data:`WIDTH` characters.
    """
    dev, u = req.device, req.device.units
    methods = [m for m in ALL_METHODS if any(r.method == m for r in req.requirements)]
    names = [n for n in PARAMETERS if any(r.parameter == n for r in req.requirements)]
    head = (
        f"{device_title(dev)}: what each parameter must be for K = {number(req.stiffness, 5)} {u['stiffness']} at "
        f"{number(req.velocity, 4)} {u['velocity']}, the others held"
    )
    rows = []
    for name in names:
        current = req.find(methods[0], name).current
        now = f"{number(current, 4)} {_unit(u, name, current)}"
        label = "damping b + b_h (device and hand)" if name == "damping" and dev.hand is not None else LABELS[name]
        rows.append([label, now, *(requirement_cell(req.find(m, name), u) for m in methods)])
    lines = [fill(head, WIDTH, "  "), ""]
    lines += text_table(rows, ["parameter", "now", *(_METHOD_HEADS[m] for m in methods)], width=WIDTH).split("\n")
    lines.append(
        fill(
            "'holds now': K holds today and the value is how far the parameter may go before it fails; 'change': "
            f"the least change that makes K hold. Only the criterion is a proof{start_state_clause(req.wall)}; the "
            "linear loop (no encoder, no "
            "Coulomb friction) is necessary for stability, not sufficient"
            + (
                "; the describing function is a first-harmonic prediction, each value to 0.1 %"
                if "df" in methods
                else ""
            )
            + ". The simulation answers only by a search per value: change a parameter, run `dfa stiffness`. "
            "--json for every number.",
            WIDTH,
            "",
        )
    )
    return lines


def damper_line(g: DamperGuidance, units: dict[str, str], damping: float) -> str:
    """One line for a virtual damper that leaves the criterion nothing to prove, and what would restore it.

    Parameters
    ----------
    g : DamperGuidance
        From :func:`dfa.analysis.limits.require.damper_guidance`.
    units : dict of str to str
        The device's units.
    damping : float
        The wall's virtual damper B (same units as ``units["damping"]``).

    Returns
    -------
    str
        Empty when the criterion proves some K.
    """
    if g.proves_some_k:
        return ""
    fixes = [
        f"B < {number(g.max_virtual_damping, 4)} {units['damping']}",
        f"c > {number(g.min_coulomb, 4)} {units['coulomb']}",
    ]
    if g.max_resolution is not None:
        fixes.append(f"Δ < {number(g.max_resolution, 4)} {units['resolution']}")
    return (
        f"with B = {number(damping, 4)} {units['damping']} the criterion proves no K at this speed (the damper costs "
        f"friction (1 − a)BΔ/T and damping B); it would with {' or '.join(fixes)}"
    )
