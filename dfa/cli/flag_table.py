"""The one flag table of the wall elements: every option of every element, from the element classes.

Each element declares its command-line rows (:meth:`~dfa.model.elements.Element.flag_rows`); this module gathers
them (:data:`FLAG_ROWS`), adds an element's rows to a parser (:func:`add_rows`) and reads which were given
(:func:`given_rows`, and :func:`needing` for the rows a switch's absence refuses). :mod:`dfa.cli.walls`,
:mod:`dfa.cli.contact` and :mod:`dfa.cli.passivity` read it; it imports none of them.
"""

from __future__ import annotations

import argparse
from collections.abc import Mapping
from typing import Any

from ..model.elements import ELEMENTS, Element, FlagRow
from .parsing import delay, number

__all__ = ["FLAG_ROWS", "add_rows", "given_rows", "is_given", "needing"]

#: The one flag table: every option of every element (:meth:`~dfa.model.elements.Element.flag_rows`), by flag.
FLAG_ROWS: dict[str, FlagRow] = {row.flag: row for k in ELEMENTS for row in k.flag_rows()}


def add_rows(g: Any, kind: type[Element], help_text: Mapping[str, str] | None = None) -> None:
    """Add an element's options (its rows of :data:`FLAG_ROWS`) to a parser or argument group.

    ``help_text`` replaces the help of the flags it names (``dfa zwidth`` says why it refuses ``--virtual-damping``).
    """
    for row in kind.flag_rows():
        text = (help_text or {}).get(row.flag, row.help)
        if row.metavar is None:
            g.add_argument(row.flag, action="store_true", help=text)
        elif row.whole:
            g.add_argument(row.flag, dest=row.dest, type=delay, default=row.default, metavar=row.metavar, help=text)
        else:
            parse = number(row.flag, row.unit)
            g.add_argument(row.flag, dest=row.dest, type=parse, default=row.default, metavar=row.metavar, help=text)


def is_given(args: argparse.Namespace, row: FlagRow) -> bool:
    """Tell whether a row's option was given: a switch set, a value not None (False on a command without it)."""
    value = getattr(args, row.dest, None)
    return bool(value) if row.metavar is None else value is not None


def given_rows(args: argparse.Namespace, kind: type[Element]) -> list[str]:
    """The flags of an element's rows given on the command line, in the element's order."""
    return [row.flag for row in kind.flag_rows() if is_given(args, row)]


def needing(args: argparse.Namespace, switch: str) -> list[str]:
    """The given flags whose row needs ``switch`` (:attr:`~dfa.model.elements.FlagRow.needs`), in table order."""
    return [row.flag for row in FLAG_ROWS.values() if row.needs == switch and is_given(args, row)]
