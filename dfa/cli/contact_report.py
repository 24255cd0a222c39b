"""``python -m dfa.cli.contact_report``: the bilateral spring against the one-sided wall, on the catalogue devices.

Parse → call (:func:`dfa.studies.contact_comparison.contact_comparison`) → render
(:func:`dfa.studies.contact_document.comparison_markdown`). Not a ``dfa`` subcommand: it regenerates the committed report::

    python -m dfa.cli.contact_report --out reports/validation      # one_sided_comparison.md and .json

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work); 1 a file could not be written; 130
interrupted (nothing written: both files are written together at the end, atomically).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .catalogue_report import catalogue_main, catalogue_parser

__all__ = ["build_parser", "main", "STEM"]

PROG = "python -m dfa.cli.contact_report"
#: The report's file name without its suffix.
STEM = "one_sided_comparison"


def build_parser() -> argparse.ArgumentParser:
    """The parser: --out, --velocity, --grid and --speeds (:func:`dfa.cli.catalogue_report.catalogue_parser`)."""
    return catalogue_parser(PROG, (__doc__ or "").split("\n")[0])


def main(argv: Sequence[str] | None = None) -> int:
    """Run the comparison and write its Markdown and JSON; return the exit code (module docstring).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 ok, 2 bad input, 1 a file error, 130 interrupted.
    """
    from ..jsonable import dumps
    from ..studies.contact_comparison import contact_comparison
    from ..studies.contact_document import comparison_markdown

    def write(c: Any, stage: Path) -> None:
        (stage / f"{STEM}.md").write_text(comparison_markdown(c), encoding="utf-8")
        (stage / f"{STEM}.json").write_text(dumps(c, indent=1), encoding="utf-8")

    return catalogue_main(PROG, build_parser(), argv, contact_comparison, write)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
