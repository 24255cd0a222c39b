"""Parsing of command-line values: one rule per kind of flag, one line on stderr for bad input.

Numbers are decimal ASCII only (``float()`` would take ``1_000``, other scripts' digits, ``nan`` and ``inf``);
every message names the flag, the value, the rule and the fix.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
from collections.abc import Callable
from typing import Any

from ..checks import MAX_DELAY
from ..errors import DFAValueError

__all__ = ["NEGATIVE_NUMBER", "UsageError", "Parser", "number", "integer", "name", "delay", "add_margin_arg"]


class UsageError(DFAValueError):
    """Wrong or contradictory command-line inputs."""


#: What argparse must read as a value, not as a flag: a number with a minus sign, in every form :func:`number`
#: takes (argparse's own pattern knows only ``-1`` and ``-1.5``, so ``--position -1e-5`` failed with "expected one
#: argument"), and the non-finite words, so that ``--mu -inf`` gets the number's own message.
NEGATIVE_NUMBER = re.compile(r"^-(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|nan|inf|infinity)$", re.IGNORECASE)


class Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit code 2.

    Three departures from argparse, so that every flag behaves the same whichever way it is written:

    - ``--flag -1e-5`` takes ``-1e-5`` as the value (:data:`NEGATIVE_NUMBER`; no flag of dfa looks like a number);
    - ``--flag=--`` gives the flag the value ``--``, which its type refuses with its one-line message (Python
      3.11's argparse dropped the ``--`` and stored an empty list without calling the type);
    - a closed stdout while printing the help raises :class:`BrokenPipeError` (exit 141) instead of being ignored.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBER

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: error: {message}")

    def _get_values(self, action: argparse.Action, arg_strings: list[str]) -> Any:
        if (
            action.option_strings
            and arg_strings == ["--"]
            and action.nargs not in (0, argparse.PARSER, argparse.REMAINDER)
        ):
            value = self._get_value(action, "--")  # the flag's type refuses it (or takes it, for a file name)
            self._check_value(action, value)
            return value if action.nargs in (None, argparse.OPTIONAL) else [value]
        return super()._get_values(action, arg_strings)

    def _print_message(self, message: str, file: Any = None) -> None:
        if message:
            try:
                (file or sys.stderr).write(message)
            except BrokenPipeError:
                raise
            except (AttributeError, OSError):  # as argparse: nowhere to print
                pass


# Decimal ASCII only: no '1_000', no Arabic-Indic or full-width digits, no 'nan'/'inf' (float() takes them all).
_DECIMAL = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_WHOLE = re.compile(r"[+-]?[0-9]+")


def number(flag: str, unit: str) -> Callable[[str], float]:
    """The parser of a flag that takes a finite decimal number in ``unit``."""

    def parse(text: str) -> float:
        if not _DECIMAL.fullmatch(text):
            what = (
                "not a finite number"
                if text.strip().lower().lstrip("+-") in ("nan", "inf", "infinity")
                else "not a number"
            )
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is {what}: {flag} takes a finite decimal number in {unit}, written with ASCII digits "
                "(e.g. 0.25, 3, 1e-3; no '_', no other scripts)"
            )
        value = float(text)
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is too large: {flag} takes a number below 1.8e308 in {unit}"
            )
        if value == 0.0 and any(c in "123456789" for c in text.lower().split("e")[0]):
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is too small: it rounds to 0; {flag} takes a number above 1e-308 in {unit} (or 0)"
            )
        return value + 0.0  # -0 is zero

    parse.__name__ = flag
    return parse


def integer(flag: str) -> Callable[[str], int]:
    """The parser of a flag that takes a whole number (ASCII digits, below 10^18)."""

    def parse(text: str) -> int:
        if not _WHOLE.fullmatch(text):
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is not a whole number: {flag} takes an integer written with ASCII digits "
                "(e.g. 2000; no '_', '.', 'e')"
            )
        if len(text.lstrip("+-").lstrip("0")) > 18:
            raise argparse.ArgumentTypeError(f"{text[:40]!r} is too large: {flag} takes an integer below 10^18")
        return int(text)

    parse.__name__ = flag
    return parse


def name(text: str) -> str:
    """``--name``: a printable device name of 1 to 100 characters."""
    if not text.strip() or any(not c.isprintable() for c in text) or len(text) > 100:
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is invalid: --name takes a printable device name of 1 to 100 characters (e.g. 'my pen')"
        )
    return text.strip()


def delay(text: str) -> int:
    """--delay: ASCII digits only (int() would take '1_0' or other scripts' digits), 0 to MAX_DELAY samples."""
    if not _WHOLE.fullmatch(text):
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is not a whole number: --delay takes the computational delay in samples (integer >= 0, "
            "ASCII digits, e.g. 1)"
        )
    digits = text.lstrip("+-").lstrip("0")
    out = int(text) if len(digits) <= 18 else (-1 if text.startswith("-") else MAX_DELAY + 1)
    if out < 0:
        raise argparse.ArgumentTypeError(f"{text!r} is invalid: --delay must be a whole number of samples >= 0")
    if out > MAX_DELAY:
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is too large: --delay takes at most {MAX_DELAY} samples; give the computational delay "
            "in samples of the servo period (e.g. 1)"
        )
    return out


def add_margin_arg(p: Any, when: str = "") -> None:
    """``--margin G``: the gain margin >= 1 of a recommended K without proof (``dfa stiffness``, ``tune``, ``export``),
    ``when`` a prefix of its help (``"with --velocity: "``)."""
    p.add_argument(
        "--margin",
        type=number("--margin", "dimensionless units (a gain >= 1)"),
        default=2.0,
        metavar="G",
        help=f"{when}gain margin >= 1 of the recommended K when no proof exists: the simulated no-divergence limit "
        "divided by G (default 2, about 6 dB)",
    )
