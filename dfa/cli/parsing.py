"""Parsing of command-line values: one rule per kind of flag, one line on stderr for bad input.

Numbers are decimal ASCII only (``float()`` would take ``1_000``, other scripts' digits, ``nan`` and ``inf``);
every message names the flag, the value, the rule and the fix.
"""

from __future__ import annotations

import argparse
import math
import re
from collections.abc import Callable

from ..checks import MAX_DELAY
from ..errors import DFAValueError

__all__ = ["UsageError", "Parser", "number", "integer", "name", "delay"]


class UsageError(DFAValueError):
    """Wrong or contradictory command-line inputs."""


class Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit code 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: error: {message}")


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
                "(e.g. 0.25, -3, 1e-3; no '_', no other scripts)"
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
