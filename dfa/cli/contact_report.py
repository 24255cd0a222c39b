"""``python -m dfa.cli.contact_report``: the bilateral spring against the one-sided wall, on the catalogue devices.

Parse → call (:func:`dfa.analysis.contact_comparison.contact_comparison`) → render
(:func:`dfa.render.contact.comparison_markdown`). Not a ``dfa`` subcommand: it regenerates the committed report::

    python -m dfa.cli.contact_report --out reports/validation      # one_sided_comparison.md and .json

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work); 1 a file could not be written; 130
interrupted (nothing written: both files are written together at the end, atomically).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .._io import check_output_folder
from ..checks import check_int, check_positive
from .output import report_script
from .parsing import Parser, integer, number

__all__ = ["build_parser", "main", "STEM"]

PROG = "python -m dfa.cli.contact_report"
#: The report's file name without its suffix.
STEM = "one_sided_comparison"


def build_parser() -> argparse.ArgumentParser:
    """The parser: --out, --velocity, --grid and --speeds."""
    ap = Parser(prog=PROG, description=(__doc__ or "").split("\n")[0])
    ap.add_argument(
        "--out", default="reports/validation", metavar="DIR", help="output folder (default: reports/validation)"
    )
    ap.add_argument(
        "--velocity",
        type=number("--velocity", "m/s (rotary: rad/s)"),
        default=None,
        metavar="V",
        help="impact speed for every device (default: 0.1 m/s, rotary 1 rad/s, the design report's)",
    )
    ap.add_argument("--grid", type=integer("--grid"), default=16, help="stiffness grid points (default 16)")
    ap.add_argument("--speeds", type=integer("--speeds"), default=6, help="impact speeds simulated (default 6)")
    return ap


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
    from .._io import staged_folder
    from ..analysis.contact_comparison import contact_comparison
    from ..render.contact import comparison_markdown
    from ..results.jsonable import dumps

    def work() -> None:
        args = build_parser().parse_args(list(sys.argv[1:] if argv is None else argv))
        check_int("--grid", args.grid, 2, "give at least 2 grid points")
        check_int("--speeds", args.speeds, 1, "simulate at least one speed")
        if args.velocity is not None:
            check_positive("--velocity", args.velocity, "give the impact speed in m/s (rotary: rad/s), > 0")
        check_output_folder("--out", args.out, create=True)
        c = contact_comparison(velocity=args.velocity, grid=args.grid, speeds=args.speeds)
        with staged_folder(args.out) as stage:
            (stage / f"{STEM}.md").write_text(comparison_markdown(c), encoding="utf-8")
            (stage / f"{STEM}.json").write_text(dumps(c, indent=1), encoding="utf-8")

    return report_script(PROG, work)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
