"""``python -m dfa.cli.passivity_report``: what a passivity controller buys and costs, on the catalogue devices.

Parse → call (:func:`dfa.analysis.passivity_comparison.passivity_comparison`) → render
(:func:`dfa.render.passivity.passivity_markdown`, :func:`dfa.figures.passivity_plot`). Not a ``dfa`` subcommand:
it regenerates the committed report (a few minutes)::

    python -m dfa.cli.passivity_report --out reports/validation   # passivity_controller.md, .json and .png

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work); 1 a file could not be written; 130
interrupted (nothing written: the files are written together at the end, atomically).
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

PROG = "python -m dfa.cli.passivity_report"
#: The report's file name without its suffix.
STEM = "passivity_controller"


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
    from .._io import staged_folder
    from ..analysis.passivity_comparison import passivity_comparison
    from ..figures import save_figure
    from ..render.passivity import passivity_markdown
    from ..results.jsonable import dumps

    def work() -> None:
        args = build_parser().parse_args(list(sys.argv[1:] if argv is None else argv))
        check_int("--grid", args.grid, 2, "give at least 2 grid points")
        check_int("--speeds", args.speeds, 1, "simulate at least one speed")
        if args.velocity is not None:
            check_positive("--velocity", args.velocity, "give the impact speed in m/s (rotary: rad/s), > 0")
        check_output_folder("--out", args.out, create=True)
        c = passivity_comparison(velocity=args.velocity, grid=args.grid, speeds=args.speeds)
        with staged_folder(args.out) as stage:
            axes = c.plot()
            save_figure(axes[0].figure, stage / f"{STEM}.png")
            (stage / f"{STEM}.md").write_text(passivity_markdown(c, f"{STEM}.png"), encoding="utf-8")
            (stage / f"{STEM}.json").write_text(dumps(c, indent=1), encoding="utf-8")

    return report_script(PROG, work)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
