"""``python -m dfa.cli.contact_report``: the bilateral spring against the one-sided wall, on the catalogue devices.

Parse → call (:func:`dfa.studies.contact_comparison.contact_comparison`) → render
(:func:`dfa.studies.contact_document.comparison_markdown`). Not a ``dfa`` subcommand: it regenerates the committed report::

    python -m dfa.cli.contact_report --out reports/validation      # one_sided_comparison.md and .json

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work); 1 a file could not be written; 130
interrupted (nothing written: both files are written together at the end, atomically).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from .catalogue_report import CatalogueScript

__all__ = ["build_parser", "main", "STEM", "SCRIPT"]

PROG = "python -m dfa.cli.contact_report"
#: The report's file name without its suffix.
STEM = "one_sided_comparison"


def _write(c: Any, stage: Path) -> None:
    """The report's Markdown and JSON."""
    from ..jsonable import dumps
    from ..studies.contact_document import comparison_markdown

    (stage / f"{STEM}.md").write_text(comparison_markdown(c), encoding="utf-8")
    (stage / f"{STEM}.json").write_text(dumps(c, indent=1), encoding="utf-8")


SCRIPT = CatalogueScript(PROG, __doc__ or "", "dfa.studies.contact_comparison.contact_comparison", _write)
#: The parser: --out, --velocity, --grid and --speeds (:func:`dfa.cli.catalogue_report.catalogue_parser`).
build_parser = SCRIPT.build_parser
#: Run the comparison and write its files; return the exit code (module docstring).
main = SCRIPT.main


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
