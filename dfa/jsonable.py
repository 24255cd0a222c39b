"""JSON output of results: one sanitiser for the package and the command line.

:func:`to_jsonable` turns result data into plain Python that :func:`json.dumps`
accepts with ``allow_nan=False`` (strict JSON): numpy scalars and arrays become
Python numbers and lists, enums their value, paths text, complex numbers
``{"re": …, "im": …}``, and every NaN or infinity becomes ``null``. Nothing is
nulled silently: a dict that had a value nulled gains the key ``null_reasons``,
mapping the JSON pointer of each nulled value (relative to that dict) to why
(``"NaN"``, ``"+inf"``, ``"-inf"``; for arrays how many entries of each).
:func:`dumps` is :func:`json.dumps` of the sanitised data with every float rounded
to :data:`JSON_DIGITS` significant digits (:func:`round_floats`): a file or a line
of JSON carries the digits that mean something, not the last bits of one CPU's
arithmetic, so the same inputs give the same text on every machine (issue 41).

Examples
--------
>>> import numpy as np
>>> from dfa.jsonable import dumps, to_jsonable
>>> to_jsonable({"a": np.float64(1.5), "b": float("inf"), "c": np.array([1.0, np.nan])})
{'a': 1.5, 'b': None, 'c': [1.0, None], 'null_reasons': {'/b': '+inf', '/c': 'NaN at 1 of 2 entries'}}
>>> dumps([np.int64(3), float("nan")])
'[3, null]'
>>> dumps({"x": 0.1 + 0.2, "y": -0.0, "z": 2215.3109748349802})
'{"x": 0.3, "y": 0.0, "z": 2215.31097483}'
"""

from __future__ import annotations

import dataclasses
import enum
import json
import math
import os
from typing import Any

import numpy as np

__all__ = ["to_jsonable", "dumps", "explain_nulls", "round_floats", "round_sig", "NULL_REASONS_KEY", "JSON_DIGITS"]

#: Key added to a dict in which values were nulled (pointer → reason).
NULL_REASONS_KEY = "null_reasons"

#: Significant digits of every float written as JSON (files and the command line's ``--json``).
JSON_DIGITS = 12


def _reason(x: float) -> str:
    return "NaN" if math.isnan(x) else ("+inf" if x > 0 else "-inf")


def _escape(key: str) -> str:
    return key.replace("~", "~0").replace("/", "~1")


def _array_reason(a: np.ndarray) -> str | None:
    """How many entries of a float array are NaN, +inf, -inf (None when all are finite)."""
    if a.dtype.kind == "c":
        bad = ~np.isfinite(a)
        return f"non-finite at {int(bad.sum())} of {a.size} entries" if bad.any() else None
    if a.dtype.kind != "f":
        return None
    parts = [
        f"{label} at {n} of {a.size} entries"
        for label, n in (
            ("NaN", int(np.isnan(a).sum())),
            ("+inf", int(np.isposinf(a).sum())),
            ("-inf", int(np.isneginf(a).sum())),
        )
        if n
    ]
    return ", ".join(parts) or None


def _array(a: np.ndarray) -> Any:
    if a.dtype.kind == "c":
        return [_walk(complex(z), "", {}) for z in a.ravel()] if a.ndim <= 1 else [_array(r) for r in a]
    if a.dtype.kind == "f":
        out = a.astype(object)
        out[~np.isfinite(a)] = None
        return out.tolist()
    if a.dtype.kind in "biu":
        return a.tolist()
    return [_walk(v, "", {}) for v in a.tolist()]


def _walk(obj: Any, path: str, reasons: dict[str, str]) -> Any:
    """Sanitised copy of ``obj``; nulled non-finite values are recorded in ``reasons`` under ``path``."""
    if obj is None or isinstance(obj, (bool, str)) and not isinstance(obj, enum.Enum):
        return obj
    if isinstance(obj, enum.Enum):
        return _walk(obj.value, path, reasons)
    if isinstance(obj, (int, np.integer, np.bool_)):
        return obj.item() if isinstance(obj, np.generic) else int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        if math.isfinite(x):
            return x
        reasons[path] = _reason(x)
        return None
    if isinstance(obj, (complex, np.complexfloating)):
        z = complex(obj)
        return {"re": _walk(z.real, path + "/re", reasons), "im": _walk(z.imag, path + "/im", reasons)}
    if isinstance(obj, np.ndarray):
        why = _array_reason(obj)
        if why is not None:
            reasons[path] = why
        return _array(obj)
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    if hasattr(obj, "to_dict") and callable(obj.to_dict):
        return to_jsonable(obj.to_dict())
    if isinstance(obj, dict):
        return _dict(obj)
    if isinstance(obj, (list, tuple)):
        return [_walk(v, f"{path}/{i}", reasons) for i, v in enumerate(obj)]
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return _dict({f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)})
    raise TypeError(f"{type(obj).__name__} is not JSON-able: give plain numbers, text, arrays, enums or results")


def _dict(obj: dict) -> dict[str, Any]:
    reasons: dict[str, str] = {}
    out = {str(k): _walk(v, "/" + _escape(str(k)), reasons) for k, v in obj.items() if k != NULL_REASONS_KEY}
    merged = {**obj.get(NULL_REASONS_KEY, {}), **reasons} if isinstance(obj.get(NULL_REASONS_KEY), dict) else reasons
    if merged:
        out[NULL_REASONS_KEY] = dict(sorted(merged.items()))
    return out


def to_jsonable(obj: Any) -> Any:
    """Plain-Python, strict-JSON data for ``obj`` (see the module docstring).

    Parameters
    ----------
    obj : object
        Numbers, text, None, enums, numpy scalars and arrays, paths, dicts,
        lists, tuples, results with ``to_dict()`` and dataclasses, nested.

    Returns
    -------
    object
        Data that ``json.dumps(..., allow_nan=False)`` accepts.

    Raises
    ------
    TypeError
        For an object of none of these kinds (a programming error, not bad input).
    """
    return _walk(obj, "", {})  # a top-level dict keeps its reasons; a bare list has no place for them


def round_sig(x: float, digits: int = JSON_DIGITS) -> float:
    """``x`` rounded to ``digits`` significant digits (correctly rounded, by decimal formatting); -0 becomes 0.

    Parameters
    ----------
    x : float
        A finite number.
    digits : int
        Significant digits kept, 1 to 17.

    Returns
    -------
    float
        The nearest double to the rounded decimal, never negative zero.

    Examples
    --------
    >>> round_sig(0.39176060908879473), round_sig(0.3917606090887948)
    (0.391760609089, 0.391760609089)
    >>> round_sig(-1e-320), round_sig(-0.0), round_sig(123456.789, 4)
    (-1e-320, 0.0, 123500.0)
    """
    return float(f"{x:.{digits}g}") + 0.0  # + 0.0 turns -0.0 into 0.0 and leaves every other value as it is


def round_floats(data: Any, digits: int = JSON_DIGITS) -> Any:
    """A copy of plain JSON data (dicts, lists, numbers, text, None) with every float through :func:`round_sig`.

    Parameters
    ----------
    data : object
        What :func:`to_jsonable` returns.
    digits : int
        Significant digits kept.

    Returns
    -------
    object
        The same structure; integers, text, booleans and None unchanged.
    """
    if isinstance(data, float):
        return round_sig(data, digits) if math.isfinite(data) else data
    if isinstance(data, dict):
        return {k: round_floats(v, digits) for k, v in data.items()}
    if isinstance(data, list):
        return [round_floats(v, digits) for v in data]
    return data


def dumps(obj: Any, digits: int = JSON_DIGITS, **kwargs: Any) -> str:
    """Strict JSON text of ``obj`` through :func:`to_jsonable`, floats to ``digits`` significant digits.

    Parameters
    ----------
    obj : object
        As for :func:`to_jsonable`.
    digits : int
        Significant digits of every float (:func:`round_floats`); default :data:`JSON_DIGITS`.
    **kwargs
        ``indent``, ``sort_keys``, … of :func:`json.dumps` (``allow_nan`` is always False).

    Returns
    -------
    str
        JSON without NaN or Infinity tokens, ``-0`` or digits beyond ``digits``.
    """
    kwargs["allow_nan"] = False
    return json.dumps(round_floats(to_jsonable(obj), digits), **kwargs)


def explain_nulls(record: dict[str, Any], reasons: dict[str, str]) -> dict[str, Any]:
    """``record`` with a ``null_reasons`` entry for each key that is None (or a list holding None) with a reason.

    For values that are None by meaning (not measured, not requested, undefined) rather than non-finite;
    a reason already recorded is kept. The record is changed in place and returned.

    Parameters
    ----------
    record : dict
        A JSON-ready dict (e.g. from :func:`to_jsonable`).
    reasons : dict of str to str
        Why each key may be null, by key name.

    Returns
    -------
    dict
        ``record``, its ``null_reasons`` completed.

    Examples
    --------
    >>> explain_nulls({"rest_sample": None, "amplitude": 0.0}, {"rest_sample": "the run did not come to rest"})
    {'rest_sample': None, 'amplitude': 0.0, 'null_reasons': {'/rest_sample': 'the run did not come to rest'}}
    """
    have = dict(record.get(NULL_REASONS_KEY) or {})
    for key, why in reasons.items():
        ptr = "/" + _escape(key)
        value = record.get(key, 0)
        if (value is None or isinstance(value, list) and None in value) and ptr not in have:
            have[ptr] = why
    if have:
        record[NULL_REASONS_KEY] = dict(sorted(have.items()))
    return record
