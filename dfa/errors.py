"""Error types and input validation shared by the whole package.

Every message names the parameter, the offending value, the rule it breaks and
how to fix it, so that the command-line tool can print it as a single line.

Examples
--------
>>> from dfa.errors import check_positive, DFAValueError
>>> check_positive("mass", 0.25)
0.25
>>> try:
...     check_positive("mass", -1.0, fix="give the moving mass in kg")
... except DFAValueError as err:
...     print(err)
mass = -1.0 is invalid: it must be a finite number > 0; give the moving mass in kg
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import numpy as np

__all__ = [
    "DFAError",
    "DFAValueError",
    "DFATypeError",
    "check_real",
    "check_positive",
    "check_nonnegative",
    "check_int",
    "check_choice",
    "check_type",
    "check_mu",
    "check_beta",
    "check_sigma",
]


class DFAError(Exception):
    """Base class of every error raised on purpose by :mod:`dfa`."""


class DFAValueError(DFAError, ValueError):
    """A parameter has the right type but a value outside its rule."""


class DFATypeError(DFAError, TypeError):
    """A parameter has the wrong type (for example text where a number is needed)."""


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, str):
        return repr(value)
    return str(value)


def _message(name: str, value: Any, rule: str, fix: str | None) -> str:
    msg = f"{name} = {_fmt(value)} is invalid: it must be {rule}"
    if fix:
        msg += f"; {fix}"
    return msg


def check_real(name: str, value: Any, fix: str | None = None) -> float:
    """Return ``value`` as a finite Python float, or raise.

    Parameters
    ----------
    name : str
        Parameter name used in the message.
    value : object
        The value to check. Booleans and text are rejected with
        :class:`DFATypeError`; NaN and infinities with :class:`DFAValueError`.
    fix : str, optional
        A hint appended to the message.
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise DFATypeError(
            f"{name} = {_fmt(value)} has type {type(value).__name__}: it must be a real number"
            + (f"; {fix}" if fix else "")
        )
    out = float(value)
    if not math.isfinite(out):
        raise DFAValueError(_message(name, out, "a finite number", fix))
    return out


def check_positive(name: str, value: Any, fix: str | None = None) -> float:
    """Return ``value`` as a float if it is finite and strictly positive."""
    out = check_real(name, value, fix)
    if not out > 0.0:
        raise DFAValueError(_message(name, out, "a finite number > 0", fix))
    return out


def check_nonnegative(name: str, value: Any, fix: str | None = None) -> float:
    """Return ``value`` as a float if it is finite and >= 0."""
    out = check_real(name, value, fix)
    if out < 0.0:
        raise DFAValueError(_message(name, out, "a finite number >= 0", fix))
    return out


def check_int(name: str, value: Any, minimum: int | None = None, fix: str | None = None) -> int:
    """Return ``value`` as an int if it is integral (and >= ``minimum``)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
            fv = float(value)
            if math.isfinite(fv) and fv == int(fv):
                value = int(fv)
            else:
                raise DFAValueError(_message(name, value, "a whole number", fix))
        else:
            raise DFATypeError(
                f"{name} = {_fmt(value)} has type {type(value).__name__}: it must be a whole number"
                + (f"; {fix}" if fix else "")
            )
    out = int(value)
    if minimum is not None and out < minimum:
        raise DFAValueError(_message(name, out, f"a whole number >= {minimum}", fix))
    return out


def check_choice(name: str, value: Any, choices: tuple[str, ...]) -> str:
    """Return ``value`` if it is one of ``choices`` (case-insensitive)."""
    if not isinstance(value, str):
        raise DFATypeError(
            f"{name} = {_fmt(value)} has type {type(value).__name__}: it must be one of "
            + ", ".join(choices)
        )
    low = value.lower()
    for c in choices:
        if c.lower() == low:
            return c
    raise DFAValueError(_message(name, value, "one of " + ", ".join(repr(c) for c in choices), None))


def check_type(name: str, value: Any, cls: type, fix: str) -> Any:
    """Return ``value`` if it is an instance of ``cls``, else raise :class:`DFATypeError` with ``fix``."""
    if not isinstance(value, cls):
        raise DFATypeError(f"{name} = {value!r} has type {type(value).__name__}: it must be a dfa.{cls.__name__}; {fix}")
    return value


# -------------------------------------------- the paper's dimensionless parameters (Table 1)
def check_mu(value: Any, name: str = "mu") -> float:
    """Dimensionless mass μ = m/(K T²) > 0, as a float."""
    return check_positive(name, value, "μ = m/(K T²) must be positive")


def check_beta(value: Any, name: str = "beta") -> float:
    """Dimensionless viscous damping β = b/(K T) >= 0, as a float."""
    return check_nonnegative(name, value, "β = b/(K T) cannot be negative")


def check_sigma(value: Any, name: str = "sigma") -> float:
    """Dimensionless Coulomb friction σ = c/(K Δ) >= 0, as a float."""
    return check_nonnegative(name, value, "σ = c/(K Δ) cannot be negative")
