"""``python -m dfa.cli.soundness_report``: the passivity criterion's soundness by exact simulation, as reports.

Parse → call (:func:`dfa.studies.soundness.criterion_soundness`, this package's criterion and the one that
ignores what each check is about) → study document (:func:`dfa.studies.soundness_document.write_soundness`). Not a ``dfa``
subcommand: it regenerates the committed reports::

    python -m dfa.cli.soundness_report --points 100000 --out reports/validation           # delay_soundness.md
    python -m dfa.cli.soundness_report --walls --points 100000 --out reports/validation   # controller_soundness.md
    python -m dfa.cli.soundness_report --walls --hand --points 100000 --out reports/validation  # hand_soundness.md
    python -m dfa.cli.soundness_report --one-sided --points 100000 --out reports/validation  # one_sided_soundness.md
    python -m dfa.cli.soundness_report --history --points 100000 --out reports/validation    # history_soundness.md

The spring's check runs each delay of ``--delays`` with the seed ``--seed`` + d; the random walls' runs once
with ``--seed``. One line per record on stderr as it completes. Exit codes: 0 ok; 2 bad input (one line on
stderr, before any work); 1 a file could not be written; 130 interrupted (nothing written: both files are
written together at the end, atomically).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .._io import check_output_folder
from ..checks import check_delay, check_int
from ..errors import DFAValueError
from ..studies.soundness import (
    CriterionSoundness,
    Population,
    criterion_soundness,
    history_soundness,
    one_sided_soundness,
)
from ..studies.soundness_document import soundness_line, write_soundness
from .output import report_script
from .parsing import Parser, integer

__all__ = ["build_parser", "main"]

PROG = "python -m dfa.cli.soundness_report"


def build_parser() -> argparse.ArgumentParser:
    """The parser: --points, --old-points, --delays, --seed, --out, --walls and --hand."""
    ap = Parser(prog=PROG, description=(__doc__ or "").split("\n")[0])
    ap.add_argument(
        "--points", type=integer("--points"), default=100_000, help="points per delay and criterion (default 100000)"
    )
    ap.add_argument(
        "--old-points",
        type=integer("--old-points"),
        default=None,
        help="points for the criterion that ignores the delay or the damper (default: --points)",
    )
    ap.add_argument(
        "--delays",
        type=integer("--delays"),
        nargs="+",
        default=[0, 1, 2, 3],
        help="the spring's delays d (default 0 1 2 3)",
    )
    ap.add_argument(
        "--seed", type=integer("--seed"), default=12, help="random seed (default 12; the spring's: seed + d)"
    )
    ap.add_argument(
        "--out", default="reports/validation", metavar="DIR", help="output folder (default: reports/validation)"
    )
    ap.add_argument(
        "--walls",
        "--controller",
        dest="walls",
        action="store_true",
        help="check random walls (damper, filter, delay, encoder on or off) and write controller_soundness.md/.json "
        "instead of the spring's delay_soundness.md/.json",
    )
    ap.add_argument(
        "--hand",
        action="store_true",
        help="with --walls: hold half the points by a hand with stiffness and write hand_soundness.md/.json",
    )
    ap.add_argument(
        "--one-sided",
        action="store_true",
        help="check a one-sided wall reached from free space and write one_sided_soundness.md/.json",
    )
    ap.add_argument(
        "--history",
        action="store_true",
        help="check the spring with a delay from a moving history and write history_soundness.md/.json",
    )
    return ap


def _check(args: argparse.Namespace) -> None:
    """Refuse bad values before any work (the analysis checks them too, but only once it runs)."""
    fix = "give a whole number of points >= 1"
    check_int("--points", args.points, 1, fix)
    if args.old_points is not None:
        check_int("--old-points", args.old_points, 1, fix)
    for d in args.delays:
        check_delay(check_int("--delays", d, 0, "give the spring's delays in whole samples >= 0, e.g. 0 1 2 3"))
    check_int("--seed", args.seed, 0, "give a whole number >= 0")
    check_output_folder("--out", args.out, create=True)
    if args.hand and not args.walls:
        raise DFAValueError("--hand needs --walls: the hand is drawn with random walls; add --walls")
    if sum(map(bool, (args.one_sided, args.history, args.walls))) > 1:
        raise DFAValueError(
            "--one-sided, --history and --walls (with --hand) are populations of their own: give one of them"
        )


def _records(args: argparse.Namespace) -> list[CriterionSoundness]:
    """Run every check the arguments ask for, one line on stderr per record."""
    if args.one_sided or args.history:
        check, crits = (one_sided_soundness, ("one-sided", "bilateral")) if args.one_sided else (
            history_soundness, ("moving", "fresh"))  # fmt: skip
        out = []
        for k, crit in enumerate(crits):
            n = args.points if k == 0 else (args.old_points or args.points)
            r = check(n, criterion=crit, seed=args.seed)
            print(soundness_line(r), file=sys.stderr, flush=True)
            out.append(r)
        return out
    walls = [(Population(hand=args.hand), args.seed)]
    pops = walls if args.walls else [(Population(delay=d), args.seed + d) for d in args.delays]
    results = []
    for k, crit in enumerate(pops[0][0].criteria):
        n = args.points if k == 0 else (args.old_points or args.points)
        for pop, seed in pops:
            r = criterion_soundness(n, pop, criterion=crit, seed=seed)
            print(soundness_line(r), file=sys.stderr, flush=True)
            results.append(r)
    return results


def main(argv: Sequence[str] | None = None) -> int:
    """Run the check and write its Markdown and JSON; return the exit code (module docstring).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 ok, 2 bad input, 1 a file error, 130 interrupted.
    """

    def work() -> None:
        args = build_parser().parse_args(list(sys.argv[1:] if argv is None else argv))
        _check(args)
        write_soundness(_records(args), args.out)

    return report_script(PROG, work)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
