"""The start state a passivity guarantee is proven for, in a few words (the short forms of
:func:`dfa.results.criterion.start_state`, whose full sentence is the JSON's ``start_state``).

Examples
--------
>>> from dfa.model.wall import WallParams
>>> start_state_clause(WallParams.of(delay=1))
', for a wall whose memory is fresh at t = 0'
>>> start_state_note(WallParams())
''
"""

from __future__ import annotations

from typing import Any

from ..results.criterion import has_memory

__all__ = ["FRESH_NOTE", "APPROACH_NOTE", "start_state_clause", "start_state_note"]

#: The short form of the start state of a wall with memory (:func:`start_state_note`).
FRESH_NOTE = "for a wall whose memory is fresh at t = 0"


#: ... and of a one-sided wall's (the lone spring's: :func:`dfa.results.criterion.start_state`).
APPROACH_NOTE = "for an approach from free space at the impact speed"


def start_state_clause(wall: Any) -> str:
    """``", for a wall whose memory is fresh at t = 0"`` for a wall with memory, else empty
    (:func:`dfa.results.criterion.start_state`).

    Parameters
    ----------
    wall : Wall or WallParams
        Anything with ``delay`` (samples) and ``damping``; :func:`start_state_note` is the same in brackets.

    Returns
    -------
    str
        The clause; empty for a wall without memory; a one-sided wall's :data:`APPROACH_NOTE`.
    """
    note = _start_note(wall)
    return f", {note}" if note else ""


def start_state_note(wall: Any) -> str:
    """The same as :func:`start_state_clause` in brackets: ``" (for a wall …)"``, or empty."""
    note = _start_note(wall)
    return f" ({note})" if note else ""


def _start_note(wall: Any) -> str:
    """The short start state of a guarantee: a one-sided wall's approach, a wall with memory's fresh memory, or ""."""
    if getattr(wall, "one_sided", False):
        return APPROACH_NOTE
    return FRESH_NOTE if has_memory(wall) else ""
