"""The contact a run assumed, in words (issue 28 §1): a one-sided wall reached from free space, and the push."""

from __future__ import annotations

from typing import Any

from ..formatting import number
from ..model.elements import Push
from ..model.wall import Wall, WallParams

__all__ = ["contact_line", "contact_text", "limit_cell"]


def contact_text(wall: Wall, units: dict[str, str]) -> str:
    """A one-sided wall's contact in physical units, a few words (the K_max answer's header).

    Examples
    --------
    >>> from dfa.model.elements import OneSided, Push
    >>> contact_text(Wall(1.0, (OneSided(0.25), Push(2.0))), {"force": "N"})
    'one-sided wall reached from free space (surface at 0.25 ticks), push 2 N'
    """
    e = wall.element(Push)
    f = 0.0 if e is None else e.push
    push = f"push {number(f, 4)} {units.get('force', 'N')}" if f else "no push (a free impact)"
    return f"one-sided wall reached from free space (surface at {number(wall.surface, 4)} ticks), {push}"


def contact_line(wall: WallParams, samples: int, speed: float) -> str:
    """One sentence: the surface, the push and the approach of a one-sided wall's run.

    Parameters
    ----------
    wall : WallParams
        The one-sided wall's groups.
    samples : int
        Samples of approach before the device reaches the wall.
    speed : float
        Impact speed, ticks per sample.

    Returns
    -------
    str

    Examples
    --------
    >>> from dfa.model.elements import OneSided
    >>> contact_line(WallParams(((OneSided, 0.0),)), 3, 2.0)
    'contact: one-sided wall, surface at 0 ticks, no push; the run starts 3 samples before the device reaches it at 2 ticks/sample, with the memory of that approach'
    """
    p = wall.group(Push)
    push = f"push p = F_p/(KΔ) = {number(p, 4)}" if p else "no push"
    return (
        f"contact: one-sided wall, surface at {number(wall.surface, 4)} ticks, {push}; the run starts {samples} "
        f"samples before the device reaches it at {number(speed, 4)} ticks/sample, with the memory of that approach"
    )


def limit_cell(lim: dict[str, Any]) -> str:
    """A compared limit in a table cell: its value, ``> range end`` above the searched range, or ``none``.

    Examples
    --------
    >>> limit_cell({"value": 1234.5, "status": "found", "range_end": None})
    '1234'
    >>> limit_cell({"value": None, "status": "above_range", "range_end": 4.7e5})
    '> 4.7e+05'
    """
    if lim["value"] is not None:
        return number(lim["value"], 4)
    if lim["status"] == "above_range":
        return f"> {number(lim['range_end'], 3)}"
    return f"none ({lim['status']})"
