"""The arguments every catalogue-comparison report script shares: ``--out``, ``--velocity``, ``--grid``, ``--speeds``.

``python -m dfa.cli.contact_report`` and ``python -m dfa.cli.passivity_report`` compare walls on every catalogue
device with complete values, each limit found as ``dfa stiffness`` finds it; both parse and check these flags here
(before any work), then compute and write (:func:`dfa.cli.output.report_script`). Each script is a
:class:`CatalogueScript`: its name, its comparison and what it writes; the parser and ``main`` are the same.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._io import check_output_folder
from ..checks import check_int, check_positive
from .parsing import Parser, integer, number

__all__ = ["catalogue_parser", "catalogue_args", "catalogue_main", "CatalogueScript"]


def catalogue_parser(prog: str, description: str) -> argparse.ArgumentParser:
    """The parser: --out, --velocity, --grid and --speeds.

    Parameters
    ----------
    prog : str
        The script's name (``"python -m dfa.cli.contact_report"``).
    description : str
        What it writes, one line.

    Returns
    -------
    argparse.ArgumentParser
    """
    ap = Parser(prog=prog, description=description)
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


def catalogue_args(parser: argparse.ArgumentParser, argv: Sequence[str]) -> argparse.Namespace:
    """Parse and check the arguments before any work (the package's errors name the flag and the rule).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        From :func:`catalogue_parser`.
    argv : sequence of str
        The arguments.

    Returns
    -------
    argparse.Namespace
        ``out`` (created if missing), ``velocity`` (None: each device's default), ``grid``, ``speeds``.
    """
    args = parser.parse_args(list(argv))
    check_int("--grid", args.grid, 2, "give at least 2 grid points")
    check_int("--speeds", args.speeds, 1, "simulate at least one speed")
    if args.velocity is not None:
        check_positive("--velocity", args.velocity, "give the impact speed in m/s (rotary: rad/s), > 0")
    check_output_folder("--out", args.out, create=True)
    return args


def catalogue_main(
    prog: str,
    parser: argparse.ArgumentParser,
    argv: Sequence[str] | None,
    compare: Callable[..., Any],
    write: Callable[[Any, Path], None],
) -> int:
    """Parse, compare, write every file together; return the exit code (:func:`dfa.cli.output.report_script`).

    Parameters
    ----------
    prog : str
        The script's name for the messages.
    parser : argparse.ArgumentParser
        From :func:`catalogue_parser`.
    argv : sequence of str or None
        The arguments (None: ``sys.argv[1:]``).
    compare : callable
        The comparison, called with ``velocity``, ``grid`` and ``speeds``.
    write : callable
        Writes the comparison's files into the staging folder it is given (they replace those in ``--out``
        together, atomically).

    Returns
    -------
    int
        0 ok, 2 bad input, 1 a file error, 130 interrupted.
    """
    from .._io import make_output_folder, staged_folder
    from .output import report_script

    def work() -> None:
        args = catalogue_args(parser, sys.argv[1:] if argv is None else argv)
        c = compare(velocity=args.velocity, grid=args.grid, speeds=args.speeds)
        make_output_folder("--out", args.out)  # a missing last folder is made (it was refused as a failed write)
        with staged_folder(args.out) as stage:
            write(c, stage)

    return report_script(prog, work)


@dataclass(frozen=True)
class CatalogueScript:
    """One catalogue-comparison report script: its parser and ``main``, from what sets it apart.

    Attributes
    ----------
    prog : str
        The script's name (``"python -m dfa.cli.contact_report"``).
    description : str
        What it writes (its module docstring: the first line describes the parser).
    study : str
        The comparison's dotted name (``"dfa.studies.contact_comparison.contact_comparison"``), imported when the
        script runs and called with ``velocity``, ``grid`` and ``speeds``.
    write : callable
        Writes the comparison's files into the staging folder it is given (:func:`catalogue_main`).
    """

    prog: str
    description: str
    study: str
    write: Callable[[Any, Path], None]

    def build_parser(self) -> argparse.ArgumentParser:
        """The parser: --out, --velocity, --grid and --speeds (:func:`catalogue_parser`).

        Returns
        -------
        argparse.ArgumentParser
        """
        return catalogue_parser(self.prog, self.description.split("\n")[0])

    def main(self, argv: Sequence[str] | None = None) -> int:
        """Run the comparison and write its files; return the exit code (the script's module docstring).

        Parameters
        ----------
        argv : sequence of str, optional
            The arguments (default: ``sys.argv[1:]``).

        Returns
        -------
        int
            0 ok, 2 bad input, 1 a file error, 130 interrupted.
        """
        import importlib

        module, _, name = self.study.rpartition(".")
        compare = getattr(importlib.import_module(module), name)
        return catalogue_main(self.prog, self.build_parser(), argv, compare, self.write)
