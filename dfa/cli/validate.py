"""``dfa validate``: the predictions against exact simulation; writes validation.md and its data."""

from __future__ import annotations

import argparse
import os

from .._io import check_output_folder
from .output import add_progress_args, emit, progress, say, table
from .parsing import integer

COMMAND = "validate"
HELP = "validate the predictions against exact simulation; writes validation.md"
EXAMPLE = "dfa validate --quick --out reports/validation"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """--quick, --jobs, --out and --json."""
    p.add_argument("--quick", action="store_true", help="a reduced set, under a minute (default: the full set)")
    p.add_argument(
        "--jobs", type=integer("--jobs"), default=-1, metavar="J", help="parallel jobs (default: -1, all cores)"
    )
    p.add_argument(
        "--out",
        default="reports/validation",
        metavar="DIR",
        help="output folder, created if missing (its parent must exist; default: reports/validation)",
    )
    add_progress_args(p)
    p.add_argument("--json", action="store_true", help="print the summary as JSON (default: text)")


def run(args: argparse.Namespace) -> int:
    """Run the validation, write its files together (or none), print the summary."""
    from ..checks import check_jobs
    from ..studies.validation import validate
    from ..studies.validation_document import write_validation

    check_jobs("--jobs", args.jobs)
    check_output_folder("--out", args.out, create=True)  # the parent must exist; the folder itself is created
    v = validate(quick=args.quick, n_jobs=args.jobs, progress=progress(args))
    summary = write_validation(v, args.out)  # all four files appear together, or none (dfa._io)
    if args.json:
        emit(summary, ensure_ascii=False)
        return 0
    say(f"validation written to {os.path.join(args.out, 'validation.md')}")
    rows = [
        ["soundness violations", summary["soundness_violations"]],
        ["criterion rejects (share of points that come to rest)", f"{100 * summary['conservatism']:.1f} %"],
        ["DF growth threshold vs simulated speed, median error", f"{100 * summary['speed_df_median_error']:.2g} %"],
        ["criterion speed ≤ simulated in every case", "yes" if summary["speeds_ordered"] else "no"],
    ]
    say(table(rows))
    return 0
