"""``python -m dfa.cli.passivity_report``: what a passivity controller buys and costs, on the catalogue devices.

Parse → call (:func:`dfa.studies.passivity_comparison.passivity_comparison`) → render
(:func:`dfa.render.passivity.passivity_markdown`, :func:`dfa.render.figures.passivity_plot`). Not a ``dfa`` subcommand:
it regenerates the committed report (a few minutes)::

    python -m dfa.cli.passivity_report --out reports/validation   # passivity_controller.md, .json and .png

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work); 1 a file could not be written; 130
interrupted (nothing written: the files are written together at the end, atomically).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from .catalogue_report import CatalogueScript

__all__ = ["build_parser", "main", "STEM", "SCRIPT"]

PROG = "python -m dfa.cli.passivity_report"
#: The report's file name without its suffix.
STEM = "passivity_controller"


def _write(c: Any, stage: Path) -> None:
    """The report's figure, Markdown and JSON."""
    from ..jsonable import dumps
    from ..render.figures import save_figure
    from ..render.passivity import passivity_markdown

    save_figure(c.plot()[0].figure, stage / f"{STEM}.png")
    (stage / f"{STEM}.md").write_text(passivity_markdown(c, f"{STEM}.png"), encoding="utf-8")
    (stage / f"{STEM}.json").write_text(dumps(c, indent=1), encoding="utf-8")


SCRIPT = CatalogueScript(PROG, __doc__ or "", "dfa.studies.passivity_comparison.passivity_comparison", _write)
#: The parser: --out, --velocity, --grid and --speeds (:func:`dfa.cli.catalogue_report.catalogue_parser`).
build_parser = SCRIPT.build_parser
#: Run the comparison and write its files; return the exit code (module docstring).
main = SCRIPT.main


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
