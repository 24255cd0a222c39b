"""The one flag table of the wall elements: every option of every element, from the element classes.

Each element declares its command-line rows (:meth:`~dfa.model.elements.Element.flag_rows`); this module gathers
them (:data:`FLAG_ROWS`) and adds an element's rows to a parser (:func:`add_rows`). :mod:`dfa.cli.walls`,
:mod:`dfa.cli.contact` and :mod:`dfa.cli.passivity` read it; it imports none of them.
"""

from __future__ import annotations

from typing import Any

from ..model.elements import ELEMENTS, Element, FlagRow
from .parsing import number

__all__ = ["FLAG_ROWS", "add_rows"]

#: The one flag table: every option of every element (:meth:`~dfa.model.elements.Element.flag_rows`), by flag.
FLAG_ROWS: dict[str, FlagRow] = {row.flag: row for k in ELEMENTS for row in k.flag_rows()}


def add_rows(g: Any, kind: type[Element]) -> None:
    """Add an element's options (its rows of :data:`FLAG_ROWS`) to a parser or argument group."""
    for row in kind.flag_rows():
        if row.metavar is None:
            g.add_argument(row.flag, action="store_true", help=row.help)
        else:
            g.add_argument(row.flag, type=number(row.flag, row.unit), metavar=row.metavar, help=row.help)
