"""Input checks shared by the whole package: one function per rule, one message per rule.

Every message names the parameter, the offending value, the rule it breaks and
how to fix it, so that the command-line tool can print it as a single line. The
exception types live in :mod:`dfa.errors`.

Examples
--------
>>> from dfa.checks import check_positive
>>> from dfa.errors import DFAValueError
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
import os
import sys
from typing import Any

import numpy as np

from .errors import DFATypeError, DFAValueError

__all__ = [
    "check_real",
    "check_real_array",
    "check_positive",
    "check_nonnegative",
    "check_speed",
    "check_int",
    "check_choice",
    "check_type",
    "check_bool",
    "check_mu",
    "check_beta",
    "check_sigma",
    "check_delay",
    "check_jobs",
    "check_growth",
    "check_bound",
    "check_positive_array",
    "check_nonempty",
    "check_rate",
    "check_damping_rate",
    "check_range",
    "format_value",
    "INT_MAX",
    "MAX_RATE",
    "MAX_DELAY",
    "DELAY_FIX",
]


_MAX_SHOWN = 60  # characters of a value shown in a message


def format_value(value: Any) -> str:
    """A short, safe text for ``value`` in an error message (huge values abbreviated)."""
    try:
        if isinstance(value, (bool, np.bool_)):
            return str(bool(value))
        if isinstance(value, numbers.Integral):
            v = int(value)
            if abs(v) >= 10**18:
                return f"{'-' if v < 0 else ''}<integer of {int(abs(v).bit_length() * 0.30103) + 1} digits>"
            return str(v)
        if isinstance(value, np.ndarray):
            return f"<array of shape {value.shape}>"
        text = repr(value) if isinstance(value, (float, str, complex)) else str(value)
    except Exception:  # a hostile __str__/__repr__ must not hide the real message
        text = f"<{type(value).__name__} object>"
    if len(text) > _MAX_SHOWN:
        text = text[: _MAX_SHOWN - 15] + f"… ({len(text)} chars)"
    return text


#: Largest integer accepted by :func:`check_int` (the int64 range used by numpy and the compiled kernels).
INT_MAX = 2**63 - 1


def _as_scalar(value: Any) -> Any:
    """A 0-d numpy array becomes its scalar; everything else is returned unchanged."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value[()]
    return value


def _is_bool(value: Any) -> bool:
    return isinstance(value, (bool, np.bool_))


def _type_error(name: str, value: Any, what: str, fix: str | None) -> DFATypeError:
    kind = f"array of shape {value.shape}" if isinstance(value, np.ndarray) else f"type {type(value).__name__}"
    return DFATypeError(f"{name} = {format_value(value)} has {kind}: it must be {what}" + (f"; {fix}" if fix else ""))


def _message(name: str, value: Any, rule: str, fix: str | None) -> str:
    msg = f"{name} = {format_value(value)} is invalid: it must be {rule}"
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
    value = _as_scalar(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise _type_error(name, value, "a real number", fix)
    try:
        out = float(value)
    except (OverflowError, ValueError, TypeError):
        raise DFAValueError(_message(name, value, "a finite number (this one overflows a float)", fix)) from None
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


def check_speed(name: str, value: Any, unit: str = "m/s (rotary: rad/s)", *, zero: bool = True) -> float:
    """Return an impact speed, the magnitude of ẋ0 (or ξ'0), as a float: finite and >= 0 (> 0 if not ``zero``).

    A negative speed is refused, never replaced by its magnitude: the analyses use ``abs(ẋ0)``
    (eq. 11), and a sign the caller meant is not silently dropped.

    Parameters
    ----------
    name : str
        Parameter (or command-line flag) named in the message.
    value : object
        The speed to check.
    unit : str, optional
        Its unit, shown in the fix (default ``"m/s (rotary: rad/s)"``).
    zero : bool, optional
        Whether 0 is a meaningful speed here (default True).

    Examples
    --------
    >>> check_speed("velocity", 0.05)
    0.05
    >>> try:
    ...     check_speed("velocity", -0.05)
    ... except DFAValueError as err:
    ...     print(err)
    velocity = -0.05 is invalid: it must be a finite number >= 0, the impact speed's magnitude (its sign is not used); give the impact speed's magnitude, e.g. 0.05 m/s (rotary: rad/s)
    """
    out = check_real(name, value, f"give the impact speed's magnitude in {unit}")
    if out < 0.0:
        rule = f"a finite number {'>=' if zero else '>'} 0, the impact speed's magnitude (its sign is not used)"
        raise DFAValueError(_message(name, out, rule, f"give the impact speed's magnitude, e.g. {-out:g} {unit}"))
    if out == 0.0 and not zero:
        rule = "a finite number > 0 (no impact to analyse at speed 0)"
        raise DFAValueError(_message(name, out, rule, f"give an impact speed > 0 in {unit}, e.g. 0.05"))
    return out


def check_int(name: str, value: Any, minimum: int | None = None, fix: str | None = None) -> int:
    """Return ``value`` as an int if it is integral (and >= ``minimum``)."""
    value = _as_scalar(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
            try:
                fv = float(value)
            except (OverflowError, ValueError, TypeError):
                fv = math.inf
            if not (math.isfinite(fv) and fv == int(fv)):
                raise DFAValueError(_message(name, value, "a whole number", fix))
            value = int(fv)
        else:
            raise _type_error(name, value, "a whole number", fix)
    out = int(value)
    if minimum is not None and out < minimum:
        raise DFAValueError(_message(name, out, f"a whole number >= {minimum}", fix))
    if abs(out) > INT_MAX:
        raise DFAValueError(_message(name, out, f"a whole number of at most {INT_MAX} in size", fix))
    return out


def check_choice(name: str, value: Any, choices: tuple[str, ...]) -> str:
    """Return ``value`` if it is one of ``choices`` (case-insensitive)."""
    if not isinstance(value, str):
        raise _type_error(name, value, "one of " + ", ".join(choices), None)
    low = value.lower()
    for c in choices:
        if c.lower() == low:
            return c
    raise DFAValueError(_message(name, value, "one of " + ", ".join(repr(c) for c in choices), None))


def check_type(name: str, value: Any, cls: type, fix: str) -> Any:
    """Return ``value`` if it is an instance of ``cls``, else raise :class:`DFATypeError` with ``fix``."""
    if not isinstance(value, cls):
        raise DFATypeError(
            f"{name} = {format_value(value)} has type {type(value).__name__}: it must be a dfa.{cls.__name__}; {fix}"
        )
    return value


def check_bool(name: str, value: Any, fix: str | None = None) -> bool:
    """Return ``value`` as a Python bool if it is True or False (numpy bools too), else raise.

    Never ``bool(value)``: the text ``"False"``, a number or a list would otherwise count as a flag.

    Examples
    --------
    >>> check_bool("preload", False)
    False
    >>> try:
    ...     check_bool("preload", "no", "pass True or False")
    ... except DFATypeError as err:
    ...     print(err)
    preload = 'no' has type str: it must be True or False; pass True or False
    """
    value = _as_scalar(value)
    if not isinstance(value, (bool, np.bool_)):
        raise _type_error(name, value, "True or False", fix)
    return bool(value)


# -------------------------------------------- the paper's dimensionless parameters (Table 1)
def check_mu(value: Any, name: str = "mu") -> float:
    """Dimensionless mass μ = m/(K T²) > 0, as a float (a normal float: 1/μ must not overflow)."""
    out = check_positive(name, value, "μ = m/(K T²) must be positive")
    if out < sys.float_info.min:
        raise DFAValueError(
            _message(
                name,
                out,
                f"at least {sys.float_info.min:.3g} (1/μ overflows below)",
                "μ = m/(K T²) must be a normal positive number",
            )
        )
    return out


def check_beta(value: Any, name: str = "beta") -> float:
    """Dimensionless viscous damping β = b/(K T) >= 0, as a float."""
    return check_nonnegative(name, value, "β = b/(K T) cannot be negative")


def check_sigma(value: Any, name: str = "sigma") -> float:
    """Dimensionless Coulomb friction σ = c/(K Δ) >= 0, as a float."""
    return check_nonnegative(name, value, "σ = c/(K Δ) cannot be negative")


#: Largest bT/m (and BT/m) accepted by the exact linear bounds: beyond, the loop's polynomials overflow.
MAX_RATE = 1e8


def check_rate(name: str, value: float, mass: float, period: float) -> None:
    """Refuse a damping ``value`` whose value·period/mass exceeds :data:`MAX_RATE` (the exact linear bounds).

    Examples
    --------
    >>> check_rate("damping", 0.02, 0.032, 0.002)
    >>> try:
    ...     check_rate("damping", 0.02, 1e-300, 0.002)
    ... except DFAValueError as err:
    ...     print(err)
    damping = 0.02 is invalid with mass = 1e-300 and period = 0.002: damping·period/mass must be at most 1e+08 (beyond, the loop's polynomials overflow); check the units
    """
    if not value * period / mass <= MAX_RATE:
        raise DFAValueError(
            f"{name} = {value:g} is invalid with mass = {mass:g} and period = {period:g}: {name}·period/mass must be "
            f"at most {MAX_RATE:g} (beyond, the loop's polynomials overflow); check the units"
        )


def check_damping_rate(beta: Any, mu: Any, names: tuple[str, str] = ("beta", "mu")) -> None:
    """Refuse β/μ = bT/m above :data:`MAX_RATE`: the rule of :func:`check_rate` in the dimensionless groups.

    β/μ is the damping's decay per sample, e^{−β/μ} (the same for every stiffness K). Above 1e8 the damping's time
    constant m/b is under 1e-8 samples; beyond, the exact step of the simulator (NaN at β = 1e308) and the linear
    loop's polynomials (an eigenvalue solver given inf) overflow. ``beta`` and ``mu`` may be arrays (broadcast):
    the message names the first offending pair.

    Examples
    --------
    >>> check_damping_rate(0.1, 5.0)
    >>> try:
    ...     check_damping_rate(1e308, 100.0)
    ... except DFAValueError as err:
    ...     print(err)
    beta = 1e+308 is invalid with mu = 100: β/μ = bT/m must be at most 1e+08 (the damping's time constant m/b would be under 1e-08 samples; beyond, the loop's exponentials and polynomials overflow); check the units of the damping and the mass
    """
    b, m = np.broadcast_arrays(np.asarray(beta, dtype=float), np.asarray(mu, dtype=float))
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        bad = ~(b / m <= MAX_RATE)
    if np.any(bad):
        i = np.flatnonzero(bad.ravel())[0]
        nb, nm = names
        raise DFAValueError(
            f"{nb} = {float(b.ravel()[i]):g} is invalid with {nm} = {float(m.ravel()[i]):g}: β/μ = bT/m must be at most "
            f"{MAX_RATE:g} (the damping's time constant m/b would be under {1 / MAX_RATE:g} samples; beyond, the loop's "
            "exponentials and polynomials overflow); check the units of the damping and the mass"
        )


#: Largest computational delay accepted, in samples (0.1 s at 1 kHz, far beyond a haptic servo's few samples):
#: the exact linear bound finds the roots of a polynomial of degree d + 2, at a cost growing as d³, for every
#: stiffness a search tries (`dfa stiffness --delay 300` took a minute; 10 000 ran out of memory), and the
#: simulator keeps d + 1 pending forces.
MAX_DELAY = 100

#: How to fix a bad delay (the one hint of every delay message).
DELAY_FIX = "give the computational delay in whole samples (0: the force uses the current reading)"


def check_delay(value: Any) -> int:
    """Return the computational delay d (whole samples, 0 <= d <= :data:`MAX_DELAY`).

    Examples
    --------
    >>> check_delay(2)
    2
    """
    d = check_int("delay", value, minimum=0, fix=DELAY_FIX)
    if d > MAX_DELAY:
        raise DFAValueError(
            f"delay = {d} is invalid: it must be at most {MAX_DELAY} samples; give the computational delay "
            "in samples of the servo period (e.g. 1 for one sample of computation)"
        )
    return d


def check_jobs(name: str, jobs: object) -> int:
    """Validate a joblib job count: -1 (all cores) or 1 … os.cpu_count(); return it.

    Nothing is silently clipped: more jobs than cores is refused (it only adds
    processes and memory, and changes no result).

    Examples
    --------
    >>> check_jobs("n_jobs", -1)
    -1
    """
    j = check_int(name, jobs)
    cores = os.cpu_count() or 1
    if j == 0 or j < -1:
        raise DFAValueError(f"{name} = {j} is invalid: it must be -1 (all cores) or a positive count")
    if j > cores:
        raise DFAValueError(
            f"{name} = {j} is invalid: this machine has {cores} cores; give at most {cores} (or -1 for all)"
        )
    return j


def check_growth(value: Any, name: str = "growth") -> float:
    """Envelope growth ratio > 1 that calls a run unstable (a ratio of successive envelope peaks), as a float.

    Examples
    --------
    >>> check_growth(1.5)
    1.5
    """
    out = check_positive(name, value, "give the ratio of envelope peaks that calls a run unstable, e.g. 1.5")
    if out <= 1.0:
        raise DFAValueError(
            _message(
                name, out, "> 1 (a ratio of envelope peaks)", "give e.g. 1.5 (1 would call a steady cycle unstable)"
            )
        )
    return out


def check_bound(value: Any, xi0: float = 0.0, name: str = "bound") -> float:
    """Position bound (ticks) beyond which a run counts as unstable: > 0 and > |ξ0|, as a float.

    Examples
    --------
    >>> check_bound(1e6, xi0=3.0)
    1000000.0
    """
    out = check_positive(name, value, "give the position bound in encoder ticks")
    if not out > abs(xi0):
        raise DFAValueError(_message(name, out, f"> |xi0| = {abs(xi0)!r} (the initial position)", "raise the bound"))
    return out


def check_positive_array(name: str, value: Any, fix: str | None = None) -> np.ndarray:
    """Return ``value`` as a float array whose elements are all finite and > 0 (the rule of :func:`check_positive`).

    The message names the first offending element.

    Examples
    --------
    >>> check_positive_array("omega", [0.1, 1.0]).tolist()
    [0.1, 1.0]
    """
    try:
        a = check_real_array(name, value, fix)  # types: text, complex, objects are refused there
    except DFAValueError:  # non-finite elements: reported below with this rule's message
        try:
            a = np.asarray(value, dtype=float)
        except OverflowError:
            raise DFAValueError(_message(name, value, "finite numbers > 0 (one overflows a float)", fix)) from None
    good = np.isfinite(a) & (a > 0)
    if a.size and not np.all(good):
        raise DFAValueError(_message(name, float(a[~good].ravel()[0]), "a finite number > 0", fix))
    return a


def check_nonempty(name: str, value: np.ndarray, fix: str | None = None) -> np.ndarray:
    """Return the array ``value`` if it holds at least one element, else the package's error.

    Examples
    --------
    >>> try:
    ...     check_nonempty("amplitudes", np.array([]), "give the amplitudes M in ticks")
    ... except DFAValueError as err:
    ...     print(err)
    amplitudes = <array of shape (0,)> is invalid: it must be an array of at least one value (it is empty); give the amplitudes M in ticks
    """
    if np.size(value) == 0:
        raise DFAValueError(_message(name, value, "an array of at least one value (it is empty)", fix))
    return value


def check_real_array(name: str, value: Any, fix: str | None = None) -> np.ndarray:
    """Return ``value`` (a real number or an array-like of them) as a float array of finite values, or raise.

    Text, booleans, complex numbers and objects are rejected with
    :class:`DFATypeError`; NaN, infinities and integers too large for a float
    with :class:`DFAValueError`.

    Examples
    --------
    >>> check_real_array("beta", [0.5, 1])
    array([0.5, 1. ])
    >>> try:
    ...     check_real_array("beta", [0.5, float("nan")])
    ... except DFAValueError as err:
    ...     print(err)
    beta = [0.5, nan] is invalid: it must be finite numbers (element 1 is nan)
    """
    if isinstance(value, (str, bytes)):
        raise _type_error(name, value, "a real number or an array of them", fix)
    try:
        arr = np.asarray(value)
    except (ValueError, TypeError, OverflowError):  # ragged nesting and the like
        raise _type_error(name, value, "a real number or an array of them", fix) from None
    if arr.dtype.kind == "O":
        flat = [check_real(f"{name}[{i}]" if arr.ndim else name, v, fix) for i, v in enumerate(arr.ravel())]
        return np.array(flat, dtype=float).reshape(arr.shape)
    if arr.dtype.kind not in "iuf":
        raise _type_error(name, value, "a real number or an array of them", fix)
    if (
        not isinstance(value, np.ndarray)
        and arr.size
        and any(_is_bool(v) for v in np.asarray(value, dtype=object).ravel())
    ):
        raise _type_error(name, value, "a real number or an array of them (True/False are not numbers here)", fix)
    with np.errstate(over="ignore"):
        out = arr.astype(float)
    bad = ~np.isfinite(out)
    if bad.any():
        i = int(np.flatnonzero(bad.ravel())[0])
        where = f" (element {i} is {float(out.ravel()[i])!r})" if out.ndim else ""
        raise DFAValueError(_message(name, value, "finite numbers" + where, fix))
    return out


def check_range(name: str, rng: Any) -> tuple[float, float]:
    """A (low, high) pair of numbers >= 0 with low < high, or the package's error naming ``name``."""
    try:
        a, b = rng
    except (TypeError, ValueError):
        raise DFAValueError(f"{name} = {rng!r} is invalid: it must be a pair (low, high)") from None
    lo = check_nonnegative(f"{name}[0]", a)
    hi = check_nonnegative(f"{name}[1]", b)
    if not hi > lo:
        raise DFAValueError(f"{name} = ({lo}, {hi}) is invalid: it must satisfy low < high")
    return lo, hi
