"""Exception types of the whole package (input checks: :mod:`dfa.checks`).

Every message names the parameter, the offending value, the rule it breaks and
how to fix it, so that the command-line tool can print it as a single line.

Examples
--------
>>> issubclass(DFAValueError, ValueError) and issubclass(DFATypeError, TypeError)
True
"""

from __future__ import annotations

__all__ = ["DFAError", "DFAValueError", "DFATypeError"]


class DFAError(Exception):
    """Base class of every error raised on purpose by :mod:`dfa`."""


class DFAValueError(DFAError, ValueError):
    """A parameter has the right type but a value outside its rule."""


class DFATypeError(DFAError, TypeError):
    """A parameter has the wrong type (for example text where a number is needed)."""
