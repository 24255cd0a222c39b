"""``python -m dfa.cli.passivity_report``: what a passivity controller buys and costs, on the catalogue devices.

Parse → call (:func:`dfa.studies.passivity_comparison.passivity_comparison`) → render
(:func:`dfa.render.passivity.passivity_markdown`, :func:`dfa.render.figures.passivity_plot`). Not a ``dfa`` subcommand:
it regenerates the committed report (a few minutes)::

    python -m dfa.cli.passivity_report --out reports/validation   # passivity_controller.md, .json and .png

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work); 1 a file could not be written; 130
interrupted (nothing written: the files are written together at the end, atomically).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from .catalogue_report import catalogue_main, catalogue_parser

__all__ = ["build_parser", "main", "STEM"]

PROG = "python -m dfa.cli.passivity_report"
#: The report's file name without its suffix.
STEM = "passivity_controller"


def build_parser() -> argparse.ArgumentParser:
    """The parser: --out, --velocity, --grid and --speeds (:func:`dfa.cli.catalogue_report.catalogue_parser`)."""
    return catalogue_parser(PROG, (__doc__ or "").split("\n")[0])


def main(argv: Sequence[str] | None = None) -> int:
    """Run the comparison and write its Markdown, JSON and figure; return the exit code (module docstring).

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
    from ..render.figures import save_figure
    from ..render.passivity import passivity_markdown
    from ..studies.passivity_comparison import passivity_comparison

    def write(c: Any, stage: Path) -> None:
        save_figure(c.plot()[0].figure, stage / f"{STEM}.png")
        (stage / f"{STEM}.md").write_text(passivity_markdown(c, f"{STEM}.png"), encoding="utf-8")
        (stage / f"{STEM}.json").write_text(dumps(c, indent=1), encoding="utf-8")

    return catalogue_main(PROG, build_parser(), argv, passivity_comparison, write)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
