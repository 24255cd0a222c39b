"""A logged run of a device: sample times, encoder readings and held forces (the input of identification).

A log is what a designer with a real device has: at each sample instant t_h the encoder's reading x_h (a
whole number of ticks Δ) and the force f_h commanded at t_h and held by the zero-order hold until t_{h+1}
(paper eq. 1-2; rotary: rad and N·m). :func:`read_log` reads one from a CSV file with a header naming the
columns ``t`` (s), ``x`` (m or rad) and ``f`` (N or N·m), a unit in brackets after the name allowed
(``t (s)``; ms, µs, mm, µm, mN and rotary mrad, deg, mN·m are converted to SI, another unit is refused); other
columns, and lines starting with ``#``, are ignored; commas, semicolons or tabs separate
(with semicolons or tabs a decimal comma is read as a point: ``0,001``). Every rule a log must keep
is checked before anything is analysed, and a bad log is refused in one line naming the row and the rule:
missing columns, text or NaN in a number, fewer than :data:`MIN_SAMPLES` rows or more than :data:`MAX_LOG_ROWS`,
time going backwards (a row repeating the time before it is kept: identification counts it as a repeated
sample and drops it), a file larger than :data:`MAX_LOG_BYTES` (refused before it is read).

Examples
--------
>>> import numpy as np
>>> log = DeviceLog(np.arange(20) * 1e-3, 1e-5 * np.arange(20), np.zeros(20), source="example")
>>> log.samples, round(log.duration, 6)
(20, 0.019)
"""

from __future__ import annotations

import csv
import io
import os
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from .._io import atomic_write_text
from ..checks import check_bool, check_int, check_positive, format_value
from ..errors import DFATypeError, DFAValueError

__all__ = [
    "DeviceLog",
    "LogError",
    "read_log",
    "write_log",
    "check_rows",
    "MAX_LOG_BYTES",
    "MAX_LOG_ROWS",
    "MIN_SAMPLES",
    "COLUMNS",
]

#: Largest log read (bytes): a larger file is refused before reading (rows with other columns are long; the
#: rows themselves are budgeted by :data:`MAX_LOG_ROWS`).
MAX_LOG_BYTES = 20_000_000
#: Most rows (samples) of a log: identification fits every sample, once and once per bootstrap replicate (11
#: fits by default); a fit of 100 000 samples takes half a minute and 0.1 GB (a 560 000-row log took 643 MB and
#: over a minute), while a few thousand samples with motion and reversals identify a device.
MAX_LOG_ROWS = 100_000
#: Fewest samples a log must hold to identify anything.
MIN_SAMPLES = 20
#: The columns a log must have: time (s), encoder reading (m or rad), held force (N or N·m).
COLUMNS = ("t", "x", "f")
#: The unit of positions given as encoder counts (multiplied by the resolution).
COUNTS = "counts"


class LogError(DFAValueError):
    """A log that cannot be used: the message names the file, the row or column, and the rule."""


def _array(name: str, value: Any, source: str) -> np.ndarray:
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise DFATypeError(f"{source}: column {name!r} must hold numbers") from None
    if a.ndim != 1:
        raise LogError(f"{source}: column {name!r} must be one-dimensional, not of shape {a.shape}")
    bad = np.flatnonzero(~np.isfinite(a))
    if bad.size:
        raise LogError(
            f"{source}: column {name!r} holds {format_value(float(a[bad[0]]))} at row {bad[0] + 2}: every value must be a "
            "finite number; remove or repair that row"
        )
    a.setflags(write=False)
    return a


@dataclass(frozen=True)
class DeviceLog:
    """A logged run: sample times ``t`` (s), encoder readings ``x`` (m; rotary rad), held forces ``f`` (N; N·m).

    Parameters
    ----------
    t, x, f : array_like
        One value per sample, finite; ``t`` never decreasing (a repeated time is a repeated sample, which
        identification drops and counts); at least :data:`MIN_SAMPLES` samples.
    source : str, optional
        Where the log came from (a file name), for messages and outputs.
    rotary : bool, optional
        True when positions are angles and forces torques (only changes units).
    """

    t: np.ndarray = field(repr=False)
    x: np.ndarray = field(repr=False)
    f: np.ndarray = field(repr=False)
    source: str = "log"
    rotary: bool = False

    def __post_init__(self) -> None:
        src = self.source
        object.__setattr__(self, "rotary", check_bool("rotary", self.rotary, "pass True for rad and N·m, else False"))
        for name in COLUMNS:
            object.__setattr__(self, name, _array(name, getattr(self, name), src))
        n = {len(self.t), len(self.x), len(self.f)}
        if len(n) != 1:
            raise LogError(f"{src}: columns t, x and f must have one value per sample each, not {sorted(n)}")
        if len(self.t) < MIN_SAMPLES:
            raise LogError(
                f"{src}: {len(self.t)} samples is too few: a log needs at least {MIN_SAMPLES}; log a longer run"
            )
        dt = np.diff(self.t)
        bad = np.flatnonzero(~(dt >= 0.0))
        if bad.size:
            raise LogError(
                f"{src}: time goes backwards at row {bad[0] + 3} (t = {format_value(float(self.t[bad[0] + 1]))}"
                f" after {format_value(float(self.t[bad[0]]))}); give the samples in time order, one row each"
            )
        if not dt.any():
            raise LogError(f"{src}: every row has the same time: give the samples' times in column 't'")

    @property
    def samples(self) -> int:
        """Number of samples."""
        return len(self.t)

    @property
    def duration(self) -> float:
        """Time from the first sample to the last, s."""
        return float(self.t[-1] - self.t[0])


def _header(row: list[str], source: str, columns: dict[str, str] | None = None) -> dict[str, int]:
    """Where each of t, x, f is in the header (by its name, or the name ``columns`` gives it)."""
    names = [c.split("(")[0].split("[")[0].strip().lower() for c in row]  # "t (s)", "x [m]": the name before a unit
    wanted = {c: (columns or {}).get(c, c).strip().lower() for c in COLUMNS}
    twice = [c for c in COLUMNS if names.count(wanted[c]) > 1]
    if twice:
        raise LogError(
            f"{source}: the header names column {wanted[twice[0]]!r} {names.count(wanted[twice[0]])} times: name each "
            "of t, x, f once"
        )
    missing = [c for c in COLUMNS if wanted[c] not in names]
    if missing:
        named = ", ".join(repr(wanted[m]) + ("" if wanted[m] == m else f" (for {m})") for m in missing)
        raise LogError(
            f"{source}: the header {','.join(row)!r} has no column {named}: a log needs "
            "a header with t (s), x (m, the encoder reading) and f (N, the force held over each sample), or their "
            "names in --columns t=NAME,x=NAME,f=NAME"
        )
    return {c: names.index(wanted[c]) for c in COLUMNS}


#: Units a header may give each column, and their factor to SI (linear; rotary below).
UNITS = {
    "t": {"s": 1.0, "ms": 1e-3, "us": 1e-6, "µs": 1e-6, "μs": 1e-6},
    "x": {"m": 1.0, "mm": 1e-3, "um": 1e-6, "µm": 1e-6, "μm": 1e-6, "nm": 1e-9},
    "f": {"n": 1.0, "mn": 1e-3, "kn": 1e3},
}
#: The same for a rotary log (--rotary): rad, mrad, deg and N·m, mN·m.
ROTARY_UNITS = {
    "t": UNITS["t"],
    "x": {"rad": 1.0, "mrad": 1e-3, "deg": 0.017453292519943295, "°": 0.017453292519943295},
    "f": {"n·m": 1.0, "nm": 1.0, "n m": 1.0, "n*m": 1.0, "mn·m": 1e-3, "mnm": 1e-3, "mn m": 1e-3},
}


def _unit(cell: str) -> str | None:
    """The unit written in brackets after a column's name (``t (ms)``, ``x [mm]``), None when none is."""
    for open_, close in (("(", ")"), ("[", "]")):
        if open_ in cell:
            return cell.split(open_, 1)[1].split(close, 1)[0].strip()
    return None


def _scales(
    row: list[str], where: dict[str, int], rotary: bool, source: str, units: dict[str, str], count: float | None
) -> tuple[float, float, float]:
    """The factor that brings each column to SI, from the units in the header or ``units`` (1 where none is
    written; positions in ``counts`` are multiplied by ``count``, the encoder's resolution)."""
    table = ROTARY_UNITS if rotary else UNITS
    out = []
    for c in COLUMNS:
        written, given = _unit(row[where[c]]), units.get(c)
        if written and given and written.lower() != given.strip().lower():
            raise LogError(
                f"{source}: column {c!r} is in {written!r} by the header but --{c}-unit says {given!r}: give the unit "
                "once, or the one the header writes"
            )
        unit = given or written
        if not unit:
            out.append(1.0)
            continue
        key = unit.strip().lower()
        if c == "x" and key == COUNTS:
            if count is None:
                raise LogError(f"{source}: positions in counts need the encoder's resolution: give --resolution")
            out.append(count)
            continue
        if key not in table[c]:
            kinds = ", ".join(table[c]) + (f", {COUNTS}" if c == "x" else "")
            other = " (a rotary log? give --rotary)" if not rotary and key in ROTARY_UNITS[c] else ""
            raise LogError(
                f"{source}: column {c!r} is in {unit!r}{other}: give it in one of {kinds}, or without a unit for SI"
            )
        out.append(table[c][key])
    return out[0], out[1], out[2]


def check_rows(rows: int, source: str, limit: int = MAX_LOG_ROWS) -> None:
    """Refuse a log of more than ``limit`` rows (:data:`MAX_LOG_ROWS`), naming the cap, its reason and the fix.

    Examples
    --------
    >>> check_rows(3000, "log.csv")
    """
    if rows > limit:
        raise LogError(
            f"{source}: holds more than {limit} rows (samples), the most a log may have: identification fits every "
            "sample, once and once per bootstrap replicate, and a fit of 100000 samples takes about half a minute; "
            "cut the log to the part to identify (a few thousand samples with motion and reversals are enough)"
        )


def _rows(reader: Any, source: str) -> Iterator[list[str]]:
    """The rows of a CSV reader; a row it cannot split is a :class:`LogError` naming the row (a cell over the csv
    module's field limit, 131072 characters by default: a 5 MB cell raised ``_csv.Error``)."""
    while True:
        try:
            row = next(reader)
        except StopIteration:
            return
        except csv.Error as exc:
            limit = "field larger than field limit" in str(exc)
            why = (
                f"holds a cell of more than {csv.field_size_limit()} characters" if limit else f"cannot be read ({exc})"
            )
            raise LogError(
                f"{source}: row {reader.line_num} {why}: a log's cells are numbers; give a CSV log of t, x, f (cut "
                "other columns with long text out of it)"
            ) from None
        yield row


class _Layout(NamedTuple):
    """How a log's columns are named and in what units (:func:`read_log`'s ``columns``, ``units``, ``count``)."""

    columns: dict[str, str] | None = None
    units: dict[str, str] | None = None
    per_count: float | None = None


def _parse(
    text: str, source: str, rotary: bool = False, max_rows: int = MAX_LOG_ROWS, layout: _Layout | None = None
) -> tuple[list[float], list[float], list[float]]:
    layout = layout or _Layout()
    lines = [ln for ln in text.splitlines() if not ln.lstrip().startswith("#")]  # comment lines
    first = next((ln for ln in lines if ln.strip()), "")
    delimiter = ";" if ";" in first and "," not in first else "\t" if "\t" in first and "," not in first else ","
    rows = _rows(csv.reader(io.StringIO("\n".join(lines)), delimiter=delimiter), source)
    head = next(rows, None)
    while head is not None and not any(c.strip() for c in head):  # blank lines before the header
        head = next(rows, None)
    if head is None:
        what = "is empty" if not text.strip() else "holds only comment lines (#) and blank lines"
        raise LogError(f"{source}: the file {what}: a log needs a header (t,x,f) and one row per sample")
    where = _header(head, source, layout.columns)
    scale = _scales(head, where, rotary, source, layout.units or {}, layout.per_count)
    comma = delimiter != ","  # a decimal comma (3,25) where the separator is not one (spreadsheet exports)
    cols: tuple[list[float], list[float], list[float]] = ([], [], [])
    for i, row in enumerate(rows, start=2):
        if not any(c.strip() for c in row):
            continue
        check_rows(len(cols[0]) + 1, source, max_rows)  # before the rows past the cap are read
        for j, c in enumerate(COLUMNS):
            try:
                cell = row[where[c]]
                cols[j].append(float(cell.replace(",", ".") if comma else cell) * scale[j])
            except (IndexError, ValueError):
                cell = row[where[c]] if where[c] < len(row) else "nothing"
                raise LogError(f"{source}: row {i}, column {c!r} holds {cell!r}: it must be a number") from None
    return cols


def read_log(
    path: str | os.PathLike[str],
    *,
    rotary: bool = False,
    max_bytes: int = MAX_LOG_BYTES,
    max_rows: int = MAX_LOG_ROWS,
    columns: dict[str, str] | None = None,
    units: dict[str, str] | None = None,
    count: float | None = None,
) -> DeviceLog:
    """Read a log from a CSV file with a header naming ``t``, ``x`` and ``f`` (module docstring).

    Parameters
    ----------
    path : str or path-like
        The CSV file (UTF-8; other columns are ignored).
    rotary : bool, optional
        Positions in rad and forces in N·m (default False: m and N).
    max_bytes : int, optional
        Largest file read (default :data:`MAX_LOG_BYTES`); a larger one is refused before it is opened.
    max_rows : int, optional
        Most rows read (default :data:`MAX_LOG_ROWS`); a file with more is refused when its row after the cap is
        reached (:func:`check_rows`).
    columns : dict, optional
        The header's names of the columns ``t``, ``x``, ``f`` (``{"t": "time", "x": "pos"}``; default: their
        own names).
    units : dict, optional
        The unit of a column whose header gives none (``{"x": "mm"}``; :data:`UNITS`, rotary
        :data:`ROTARY_UNITS`; positions may be ``"counts"``, with ``count``); a header's own unit must agree.
    count : float, optional
        The encoder's resolution (m, rotary rad) that positions in counts are multiplied by.

    Returns
    -------
    DeviceLog
        The log's times, readings and forces, named after the file.

    Raises
    ------
    LogError
        (a DFAValueError) A missing or unreadable file, a file too large or with too many rows, no header, a missing column, a cell
        that is not a finite number, too few rows, or time going backwards (the message names the row).
    DFATypeError
        A path that is not text or path-like.

    See Also
    --------
    write_log : Write a log in this format.
    dfa.identify : Identify the device that produced a log.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise DFATypeError(f"path = {format_value(path)} has type {type(path).__name__}: give the path of a CSV log")
    check_bool("rotary", rotary)
    limit = check_int("max_bytes", max_bytes, 1, "give the largest file to read, in bytes")
    rows = check_int("max_rows", max_rows, MIN_SAMPLES, "give the most rows to read")
    src = os.fspath(path)
    try:
        size = os.stat(src).st_size
        regular = os.path.isfile(src)
    except OSError as exc:
        raise LogError(f"{src}: cannot be read ({exc.strerror}); give the path of a CSV log") from None
    if not regular:
        raise LogError(f"{src}: is not a regular file; give the path of a CSV log")
    if size > limit:
        raise LogError(
            f"{src}: is {size / 1e6:.4g} MB, larger than the {limit / 1e6:.4g} MB a log may be; log a shorter "
            "run, or cut the file to the part to identify"
        )
    try:
        with open(src, encoding="utf-8-sig", newline="") as fh:  # a BOM (spreadsheet export) is dropped
            text = fh.read(limit + 1)
    except (OSError, UnicodeDecodeError) as exc:
        why = exc.strerror if isinstance(exc, OSError) else "not UTF-8 text"
        raise LogError(f"{src}: cannot be read ({why}); give a CSV log") from None
    t, x, f = _parse(text, src, rotary, rows, _layout(columns, units, count))
    if not t:
        raise LogError(f"{src}: has a header but no rows: log at least {MIN_SAMPLES} samples")
    return DeviceLog(np.array(t), np.array(x), np.array(f), source=os.path.basename(src), rotary=rotary)


def _layout(columns: dict[str, str] | None, units: dict[str, str] | None, count: float | None) -> _Layout:
    """``columns``, ``units`` and ``count`` of :func:`read_log`, checked."""
    for what, given in (("columns", columns), ("units", units)):
        if given is None:
            continue
        if not isinstance(given, dict) or not all(isinstance(k, str) and isinstance(v, str) for k, v in given.items()):
            raise DFATypeError(f"{what} = {format_value(given)} must be a dict of text, e.g. {{'x': 'pos'}}")
        bad = sorted(set(given) - set(COLUMNS))
        if bad:
            raise DFAValueError(f"{what} names column {bad[0]!r}: the columns are t, x and f")
    if count is not None:
        check_positive("count", count, "give the encoder's resolution in m (rad)")
    return _Layout(columns, units, count)


def write_log(log: DeviceLog, path: str | os.PathLike[str]) -> str:
    """Write ``log`` as CSV (header ``t,x,f``; 12 significant digits), atomically: what :func:`read_log` reads.

    Returns
    -------
    str
        The path written.
    """
    rows = "".join(f"{t:.12g},{x:.12g},{f:.12g}\n" for t, x, f in zip(log.t, log.x, log.f, strict=True))
    return str(atomic_write_text(path, "t,x,f\n" + rows))
