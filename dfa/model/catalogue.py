"""Catalogue of real devices (paper Table 2 and the section 5 testbed).

The catalogue stores the physical columns as printed, recomputes (μ, β, σ)
from them and keeps the paper's printed values beside the recomputed ones.
A printed value *disagrees* with the recomputed one when they differ by more
than 5 % **and** by more than half a unit in the last printed digit (a value
printed as ``0.0003`` stands for anything in [0.00025, 0.00035)). Rows whose
physical columns are illegible in the source are kept with what is known and
marked incomplete.

Examples
--------
>>> entry = get_device("phantom")          # case-insensitive, unambiguous prefix
>>> entry.name
'Phantom 1.0'
>>> [d.parameter for d in entry.discrepancies]
['beta', 'sigma']
>>> round(entry.params.sigma, 3)
1.863
>>> get_device("Omega").incomplete
True

A device of your own is a file in the same format (:func:`device_template` writes one,
:func:`load_device_file` reads it back): one ``[[devices]]`` table of SI values.
"""

from __future__ import annotations

import difflib
import json
import math
import os
import re
import stat
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from decimal import Decimal
from functools import lru_cache
from importlib import resources
from typing import Any, TypeVar

from ..errors import DeviceFileError, DFAError, DFATypeError, DFAValueError
from ..jsonable import explain_nulls
from .configurations import Configuration, configurations_from_toml
from .device import DEVICE_FIELDS, STIFFNESS, Device, DeviceField, Params

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

__all__ = [
    "Discrepancy",
    "CatalogueEntry",
    "ResolvedDevice",
    "catalogue",
    "get_device",
    "resolve_device",
    "load_device_file",
    "device_template",
    "DEFAULT_DEVICE",
    "DEVICE_FILE_MAX_BYTES",
]

#: Name of the catalogue device used by ``make report`` and the CLI examples.
DEFAULT_DEVICE = "Delta"

#: Relative disagreement above which a printed value is reported (5 %).
RELATIVE_TOLERANCE = 0.05

#: The values of a catalogue row and a device file: the device's fields and the stiffness K.
_ROW_FIELDS: tuple[DeviceField, ...] = (*DEVICE_FIELDS, STIFFNESS)
#: The values every complete row gives (a device file always): the device's required fields.
_PHYSICAL = tuple(f.name for f in DEVICE_FIELDS if f.required)
#: The names of the device's fields (the keys of ``resolve_device(overrides=...)``).
_DEVICE_KEYS = tuple(f.name for f in DEVICE_FIELDS)
_BY_NAME = {f.name: f for f in _ROW_FIELDS}


@dataclass(frozen=True)
class Discrepancy:
    """A printed dimensionless value that does not follow from the physical columns.

    Attributes
    ----------
    parameter : str
        ``"mu"``, ``"beta"`` or ``"sigma"``.
    printed : str
        The value as printed in the paper.
    recomputed : float
        The value recomputed from the physical columns (paper Table 1).
    relative : float
        (recomputed − printed)/printed.
    """

    parameter: str
    printed: str
    recomputed: float
    relative: float

    def __post_init__(self) -> None:
        from ..checks import check_choice, check_real, format_value

        fix = "discrepancies are computed by CatalogueEntry.discrepancies"
        check_choice("parameter", self.parameter, ("mu", "beta", "sigma"))
        if not isinstance(self.printed, str):
            raise DFATypeError(f"printed = {format_value(self.printed)} has type {type(self.printed).__name__}: it "
                               f"must be the printed decimal text; {fix}")  # fmt: skip
        for name in ("recomputed", "relative"):
            object.__setattr__(self, name, check_real(name, getattr(self, name), fix))

    def __str__(self) -> str:
        return (
            f"{self.parameter}: printed {self.printed}, recomputed {self.recomputed:.4g} ({100 * self.relative:+.1f} %)"
        )


def _half_unit(printed: str) -> float:
    """Half a unit in the last printed digit of a decimal string."""
    exponent = Decimal(printed).as_tuple().exponent
    assert isinstance(exponent, int)
    return 0.5 * 10.0**exponent


T = TypeVar("T")


def _device_columns(cls: type[T]) -> type[T]:
    """Give ``cls`` (before ``@dataclass``) a field for every device field (:data:`DEVICE_FIELDS`) it does not declare.

    Each such field is optional, keyword only, a float in the field's unit or None (unknown or absent): a new device
    field becomes a catalogue column (its JSON, the device file's key, the template's row, the device) without a
    per-field edit here. The fields declared in the class body (the paper's columns, the force limit, the travel)
    keep their place and type (``tests/test_element_checklist.py`` checks that the two agree).
    """
    notes = cls.__dict__.get("__annotations__", {})
    for f in DEVICE_FIELDS:
        if f.name not in notes:
            notes[f.name] = "float | None"
            setattr(cls, f.name, field(default=None, kw_only=True))
    return cls


@dataclass(frozen=True)
@_device_columns
class CatalogueEntry:
    """One catalogue row: physical values (SI), printed dimensionless values, notes.

    Missing physical values are ``None``; such rows have ``incomplete=True`` and
    :attr:`device` raises an error naming what is missing.

    Attributes
    ----------
    name : str
        Device name as in paper Table 2.
    kind : str
        ``"haptic device"``, ``"experimental testbed"`` or ``"human"``.
    source : str
        Where the values come from.
    notes : str
        Remarks on the row (assumptions, corrections).
    mass : float or None
        Moving mass m in kg (rotary: kg·m²).
    damping : float or None
        Viscous friction b in N·s/m (rotary: N·m·s/rad).
    coulomb : float or None
        Coulomb friction c in N (rotary: N·m).
    resolution : float or None
        Encoder resolution Δ in m (rotary: rad).
    period : float or None
        Sample period T in s.
    travel : float or None
        Travel from the centre to either end stop in m (rotary: rad); None: not given (unlimited).
    stiffness : float or None
        Virtual spring stiffness K of the row in N/m (rotary: N·m/rad).
    rotary : bool
        True when positions are angles and forces torques.
    max_force : float or None
        The actuator's force limit F_max in N (rotary: N·m), from a cited datasheet; None: unknown (unlimited).
    incomplete : bool
        True when some physical value is unknown.
    printed : tuple of (str, str)
        The (μ, β, σ) printed in the paper, as ``(name, decimal string)`` pairs.
    configurations : tuple of Configuration
        A device file's ``[[devices.configurations]]`` (:mod:`dfa.model.configurations`): the dynamics at its
        poses; empty for the catalogue's rows.
    """

    name: str
    kind: str
    source: str
    notes: str
    mass: float | None = None
    damping: float | None = None
    coulomb: float | None = None
    resolution: float | None = None
    period: float | None = None
    travel: float | None = None
    stiffness: float | None = None
    rotary: bool = False
    incomplete: bool = False
    max_force: float | None = None
    printed: tuple[tuple[str, str], ...] = field(default_factory=tuple)
    configurations: tuple[Configuration, ...] = field(default_factory=tuple)

    def __post_init__(self) -> None:
        from ..checks import check_bool, check_choice, format_value

        _check_configurations(self.configurations)

        fix = "build rows with get_device or load_device_file, or give the values in SI units"
        for name in ("name", "kind", "source", "notes"):
            value = getattr(self, name)
            if not isinstance(value, str):
                raise DFATypeError(
                    f"{name} = {format_value(value)} has type {type(value).__name__}: it must be text; {fix}"
                )
        for f in _ROW_FIELDS:  # the rules of Device and of a device file; None: unknown (or absent)
            if getattr(self, f.name) is not None:
                object.__setattr__(self, f.name, f.check(getattr(self, f.name), fix=fix))
        for name in ("rotary", "incomplete"):
            object.__setattr__(self, name, check_bool(name, getattr(self, name), fix))
        pairs = self.printed if isinstance(self.printed, tuple) else None
        if pairs is None or not all(isinstance(p, tuple) and len(p) == 2 and isinstance(p[1], str) for p in pairs):
            raise DFATypeError(
                f"printed = {format_value(self.printed)} is invalid: it must be a tuple of (name, decimal text) pairs, "
                f"e.g. (('mu', '0.3'),); {fix}"
            )
        for key, text in pairs:
            check_choice("printed name", key, ("mu", "beta", "sigma"))
            try:
                ok = math.isfinite(float(Decimal(text)))
            except ArithmeticError:
                ok = False
            if not ok:
                raise DFAValueError(f"printed {key} = {text!r} is invalid: it must be a finite decimal number; {fix}")

    @property
    def missing(self) -> tuple[str, ...]:
        """Names of the physical parameters that are unknown for this row."""
        return tuple(p for p in _PHYSICAL if getattr(self, p) is None)

    @property
    def printed_params(self) -> dict[str, float]:
        """The (μ, β, σ) printed in the paper, as floats (may be empty)."""
        return {k: float(v) for k, v in self.printed}

    @property
    def device(self) -> Device:
        """The physical :class:`~dfa.model.device.Device`; raises if the row is incomplete."""
        if self.missing:
            raise DFAValueError(
                f"device = {self.name!r} is invalid here: its catalogue row is incomplete "
                f"(unknown: {', '.join(self.missing)}); give the missing values explicitly "
                f"(e.g. --{self.missing[0]} on the command line)"
            )
        values = {f.name: getattr(self, f.name) for f in DEVICE_FIELDS}  # the required ones known (not missing)
        return Device(name=self.name, rotary=self.rotary, **values)

    @property
    def params(self) -> Params | None:
        """(μ, β, σ) recomputed from the physical columns at the catalogue K, or None."""
        if self.missing or self.stiffness is None:
            return None
        return self.device.params(self.stiffness)

    @property
    def discrepancies(self) -> tuple[Discrepancy, ...]:
        """Printed values that disagree with the recomputed ones (see module docstring)."""
        p = self.params
        if p is None:
            return ()
        out = []
        for key, text in self.printed:
            printed = float(text)
            value = getattr(p, key)
            diff = value - printed
            if abs(diff) > RELATIVE_TOLERANCE * abs(printed) and abs(diff) > _half_unit(text):
                out.append(Discrepancy(key, text, value, diff / printed))
        return tuple(out)

    def to_dict(self) -> dict[str, object]:
        """JSON-ready record: physical values, recomputed and printed (μ, β, σ), discrepancies.

        Returns
        -------
        dict
            The fields in SI units, ``mu``/``beta``/``sigma`` (None for an incomplete row),
            ``printed`` and ``discrepancies``.
        """
        p = self.params
        out: dict[str, object] = {
            "name": self.name,
            "kind": self.kind,
            "rotary": self.rotary,
            "incomplete": self.incomplete,
            **{f.name: getattr(self, f.name) for f in _ROW_FIELDS},
            "mu": None if p is None else p.mu,
            "beta": None if p is None else p.beta,
            "sigma": None if p is None else p.sigma,
            "printed": self.printed_params,
            "discrepancies": [
                {
                    "parameter": d.parameter,
                    "printed": float(d.printed),
                    "recomputed": d.recomputed,
                    "relative": d.relative,
                }
                for d in self.discrepancies
            ],
            "source": self.source,
            "notes": self.notes,
        }
        missing = "not given by the source: the catalogue row is incomplete"
        why = {f.name: missing if f.required else f.absent for f in DEVICE_FIELDS}
        why["stiffness"] = "the source gives no stiffness K for this device"
        why.update(dict.fromkeys(("mu", "beta", "sigma"), "not computable: the physical row is incomplete"))
        why["printed"] = "the paper prints no (μ, β, σ) for this device"
        if self.configurations:  # a device file's poses (issue 46); absent for the catalogue's rows
            out["configurations"] = [c.to_dict() for c in self.configurations]
        return explain_nulls(out, why)


def _check_configurations(configurations: object) -> None:
    """A row's configurations: a tuple of :class:`Configuration` with distinct names."""
    from ..checks import format_value

    ok = isinstance(configurations, tuple) and all(isinstance(c, Configuration) for c in configurations)
    if not ok:
        raise DFATypeError(
            f"configurations = {format_value(configurations)} is invalid: it must be a tuple of Configuration; "
            "read them from a device file (load_device_file)"
        )
    names = [c.name for c in configurations if isinstance(c, Configuration)]  # type: ignore[attr-defined]
    if len(set(names)) != len(names):
        raise DFAValueError(f"configurations = {names} is invalid: each configuration needs its own name")


def _entry(raw: dict[str, Any]) -> CatalogueEntry:
    printed = tuple((k, str(raw.get("printed", {})[k])) for k in ("mu", "beta", "sigma") if k in raw.get("printed", {}))
    values = {f.name: (float(raw[f.name]) if f.name in raw else None) for f in _ROW_FIELDS}
    entry = CatalogueEntry(
        name=raw["name"],
        kind=raw.get("kind", "haptic device"),
        source=raw.get("source", ""),
        notes=" ".join(raw.get("notes", "").split()),
        rotary=bool(raw.get("rotary", False)),
        incomplete=bool(raw.get("incomplete", False)),
        printed=printed,
        **values,  # type: ignore[arg-type]
    )
    if bool(entry.missing) and not entry.incomplete:
        raise RuntimeError(f"catalogue row {entry.name!r} lacks {entry.missing} but is not marked incomplete")
    for v in values.values():
        if v is not None and not (math.isfinite(v) and v >= 0):
            raise RuntimeError(f"catalogue row {entry.name!r} has an invalid value {v!r}")
    return entry


@lru_cache(maxsize=1)
def catalogue() -> tuple[CatalogueEntry, ...]:
    """All catalogue rows, in the order of paper Table 2, then the testbed."""
    text = resources.files("dfa.model").joinpath("data/devices.toml").read_text(encoding="utf-8")
    return tuple(_entry(raw) for raw in tomllib.loads(text)["devices"])


def _key(name: str) -> str:
    return re.sub(r"[^a-z0-9.]", "", name.lower())


def get_device(name: str) -> CatalogueEntry:
    """Look a catalogue row up by name.

    Matching is case-insensitive and ignores spaces and punctuation other than
    dots; an unambiguous prefix (``"phantom"``, ``"impulse"``) is enough.

    Parameters
    ----------
    name : str
        Device name or unambiguous prefix (``dfa devices`` lists them).

    Returns
    -------
    CatalogueEntry
        The matching row; ``.device`` is its :class:`Device`.

    Raises
    ------
    DFAValueError
        For an unknown or ambiguous name, listing the closest names.
    DFATypeError
        If ``name`` is not a string.

    See Also
    --------
    catalogue : All rows.
    resolve_device : A catalogue device with values replaced, or a custom device.
    """
    if not isinstance(name, str):
        raise DFATypeError(f"device = {name!r} has type {type(name).__name__}: it must be a device name (str)")
    rows = catalogue()
    key = _key(name)
    names = [r.name for r in rows]
    if key:
        exact = [r for r in rows if _key(r.name) == key]
        if exact:
            return exact[0]
        pref = [r for r in rows if _key(r.name).startswith(key)]
        if len(pref) == 1:
            return pref[0]
        if len(pref) > 1:
            raise DFAValueError(
                f"device = {name!r} is ambiguous: it must name one catalogue device; "
                f"it matches {', '.join(r.name for r in pref)}"
            )
    close = difflib.get_close_matches(name, names, n=3, cutoff=0.5) or difflib.get_close_matches(
        key, [_key(n) for n in names], n=3, cutoff=0.5
    )
    if close and close[0] not in names:  # matched on normalised keys
        close = [n for n in names if _key(n) in close]
    hint = f"did you mean {', '.join(repr(c) for c in close)}?" if close else "run `dfa devices` for the list"
    raise DFAValueError(f"device = {name!r} is invalid: it must be a catalogue device ({', '.join(names)}); {hint}")


@dataclass(frozen=True)
class ResolvedDevice:
    """A device resolved from a catalogue name and/or physical values (:func:`resolve_device`).

    Attributes
    ----------
    device : Device
        The device with every override applied.
    stiffness : float or None
        K in N/m (rotary N·m/rad): the one given, else the catalogue K, else None.
    entry : CatalogueEntry or None
        The catalogue row when the device is that row unchanged (no physical override, no new name),
        so that reports can quote the paper's printed values; None otherwise.
    """

    device: Device
    stiffness: float | None
    entry: CatalogueEntry | None = None

    @property
    def label(self) -> str:
        """``"<name>, K = <K> <unit>"`` (or just the name without a stiffness)."""
        if self.stiffness is None:
            return self.device.name
        return f"{self.device.name}, K = {self.stiffness:g} {self.device.units['stiffness']}"


def _counts_resolution(counts: int, rotary: bool, flag: str) -> float:
    """Encoder resolution Δ from counts per revolution (rotary, Δ = 2π/N rad) or per metre (Δ = 1/N m)."""
    from ..checks import check_int

    if isinstance(counts, bool) or not isinstance(counts, int):
        raise DFATypeError(f"{flag} = {counts!r} is invalid: it must be a whole number of encoder counts")
    if counts >= 1:
        counts = check_int(flag, counts, 1, f"give the encoder counts per {'revolution' if rotary else 'metre'}")
    if counts < 1:
        raise DFAValueError(
            f"{flag} {counts} is invalid: give the encoder counts per {'revolution' if rotary else 'metre'} (at least 1)"
        )
    return 2.0 * math.pi / counts if rotary else 1.0 / counts


def resolve_device(
    name: str | None = None,
    *,
    overrides: dict[str, float | None] | None = None,
    counts: int | None = None,
    rotary: bool = False,
    stiffness: float | None = None,
    label: str | None = None,
    flags: dict[str, str] | None = None,
    entry: CatalogueEntry | None = None,
) -> ResolvedDevice:
    """A device from a catalogue name, physical values, or a catalogue device with some values replaced.

    Parameters
    ----------
    name : str, optional
        Catalogue device (:func:`get_device` matching); None for a custom device.
    overrides : dict, optional
        Physical values replacing the catalogue's (or every required one for a custom device), keyed by the
        names of :data:`~dfa.model.device.DEVICE_FIELDS`: ``mass`` in kg (rotary: inertia in kg·m²), ``damping``
        in N·s/m (N·m·s/rad), ``coulomb`` in N (N·m), ``resolution`` in m (rad), ``period`` in s. None values are
        ignored.
    counts : int, optional
        Encoder counts per revolution (``rotary``) or per metre, instead of ``resolution``: Δ = 2π/N rad or 1/N m.
    rotary : bool
        Rotary units (rad, N·m, kg·m²); a rotary catalogue device stays rotary.
    stiffness : float, optional
        K in N/m (rotary N·m/rad); default the catalogue K (None for a custom device).
    label : str, optional
        Device name used in outputs and report file names (default the catalogue name, or ``"custom device"``).
    flags : dict, optional
        Names of the inputs in messages (the command line passes ``{"mass": "--mass", ...}``).
    entry : CatalogueEntry, optional
        A row that is not in the catalogue, instead of ``name``: a device file (:func:`load_device_file`);
        ``overrides``, ``counts``, ``stiffness`` and ``label`` replace its values as they replace a catalogue
        row's.

    Returns
    -------
    ResolvedDevice
        The device, its stiffness and (when unchanged) the catalogue row.

    Raises
    ------
    DFAValueError, DFATypeError
        Unknown name, missing or out-of-range value, ``counts`` with ``resolution``, (μ, β, σ) a float cannot hold.

    See Also
    --------
    get_device : A catalogue row by name.
    Device : A physical device from its five values.

    Examples
    --------
    >>> r = resolve_device("phantom", overrides={"coulomb": 0.05})
    >>> r.device.coulomb, r.stiffness, r.entry is None
    (0.05, 1015.0, True)
    >>> r = resolve_device(overrides=dict(mass=6.3e-6, damping=9e-5, coulomb=0.02, period=1e-3), counts=2000,
    ...                    rotary=True, stiffness=0.5, label="testbed")  # a rotary encoder of 2000 counts
    >>> round(r.device.resolution, 6), r.label
    (0.003142, 'testbed, K = 0.5 N·m/rad')
    """
    _check_resolve_arguments(name, overrides, flags, label, rotary, entry)
    fl = {k: k for k in (*_DEVICE_KEYS, "stiffness", "counts", "name")} | (flags or {})
    given = {k: v for k, v in (overrides or {}).items() if v is not None}
    unknown = sorted(set(given) - set(_DEVICE_KEYS))
    if unknown:
        raise DFAValueError(f"overrides has {unknown}: physical values are {', '.join(_DEVICE_KEYS)}")
    if entry is None and name:
        entry = get_device(name)
    values: dict[str, float | None] = {k: getattr(entry, k) for k in _DEVICE_KEYS} if entry else {}
    rotary = bool(rotary or (entry is not None and entry.rotary))
    if counts is not None:
        if "resolution" in given:
            raise DFAValueError(
                f"{fl['counts']} and {fl['resolution']} cannot both be given: the counts set the resolution"
            )
        given["resolution"] = _counts_resolution(counts, rotary, fl["counts"])
    values |= {k: _BY_NAME[k].check(v, fl[k], f"give {k} in {_BY_NAME[k].units}") for k, v in given.items()}
    missing = [fl[k] for k in _PHYSICAL if values.get(k) is None]
    if missing:
        _refuse_missing(entry, given, missing, fl)
    dev = Device(name=label or (entry.name if entry else "custom device"), rotary=rotary, **values)  # type: ignore[arg-type]
    k = _resolved_stiffness(dev, stiffness, entry, given, fl)
    same = entry is not None and not given and (label is None or label == entry.name)
    return ResolvedDevice(dev, k, entry if same else None)


def _check_resolve_arguments(
    name: object, overrides: object, flags: object, label: object, rotary: object, entry: object
) -> None:
    """The types of :func:`resolve_device`'s arguments, and not both a name and an entry."""
    from ..checks import format_value

    for arg, mapping in (("overrides", overrides), ("flags", flags)):
        if mapping is not None and not isinstance(mapping, dict):
            raise DFATypeError(
                f"{arg} = {format_value(mapping)} has type {type(mapping).__name__}: it must be a dict or None; "
                f"give a dict such as {{'mass': 0.1}}"
            )
    for arg, text in (("name", name), ("label", label)):
        if text is not None and not isinstance(text, str):
            raise DFATypeError(
                f"{arg} = {format_value(text)} has type {type(text).__name__}: it must be text or None; give a device name"
            )
    if not isinstance(rotary, bool):
        raise DFATypeError(
            f"rotary = {format_value(rotary)} has type {type(rotary).__name__}: it must be True or False"
        )
    if entry is not None and not isinstance(entry, CatalogueEntry):
        raise DFATypeError(
            f"entry = {format_value(entry)} has type {type(entry).__name__}: it must be a CatalogueEntry or None; "
            "read a device file with load_device_file(path)"
        )
    if entry is not None and name is not None:
        raise DFAValueError(
            f"name = {name!r} and entry = {entry.name!r} cannot both be given: give one device (a catalogue name or "
            "a device file's row)"
        )


def _resolved_stiffness(
    dev: Device, stiffness: float | None, entry: CatalogueEntry | None, given: dict[str, Any], fl: dict[str, str]
) -> float | None:
    """K: the one given, else the row's, else None; checked > 0, with (μ, β, σ) a float can hold."""
    from ..checks import check_positive
    from .device import dimensionless_params

    k = stiffness if stiffness is not None else (entry.stiffness if entry else None)
    if k is None:
        return None
    k = check_positive(fl["stiffness"], k, f"give the virtual wall stiffness K in {dev.units['stiffness']}")
    names = {key: fl[key] for key in given} | ({"stiffness": fl["stiffness"]} if stiffness is not None else {})
    dimensionless_params(dev, k, names)  # refuses μ, β, σ that overflow or vanish, naming these inputs
    return float(k)


def _refuse_missing(
    entry: CatalogueEntry | None, given: dict[str, Any], missing: list[str], fl: dict[str, str]
) -> None:
    if entry is not None:
        raise DFAValueError(
            f"device {entry.name!r} is incomplete in the catalogue: give {' '.join(missing)} explicitly"
        )
    every = " ".join(fl[k] for k in _PHYSICAL)
    if not given:
        raise DFAValueError(f"no device given: give a catalogue name (see `dfa devices`), or {every}")
    raise DFAValueError(f"missing {' '.join(missing)}: a physical device needs all of {every}")


# ------------------------------------------------------------------ device files
#: Largest device file read (bytes): a device is a few hundred bytes; ``/dev/zero`` is refused, not read.
DEVICE_FILE_MAX_BYTES = 100_000

_KINDS = ("haptic device", "experimental testbed", "human")
_TEXT_KEYS = ("name", "kind", "source", "notes")
_FILE_KEYS = (
    "name", "kind", "source", "rotary", *(f.name for f in _ROW_FIELDS), "printed", "notes", "incomplete",
    "configurations",
)  # fmt: skip
_REQUIRED = ("name", *_PHYSICAL)
_OPTIONAL = tuple(f.name for f in _ROW_FIELDS if not f.required)
_TEMPLATE = "`dfa devices --template > my_device.toml` writes one"


def _file_error(path: str, what: str) -> DeviceFileError:
    return DeviceFileError(f"device file {path!r} {what}")


def _read_toml(path: str) -> dict[str, Any]:
    """The file's TOML table; every way it cannot be read is a :class:`DeviceFileError`."""
    try:
        st = os.stat(path)
    except (OSError, ValueError) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else "not a path"
        raise _file_error(path, f"cannot be read ({why}): give the path of a TOML file ({_TEMPLATE})") from None
    if not stat.S_ISREG(st.st_mode):
        raise _file_error(path, f"is not a regular file: give the path of a TOML file ({_TEMPLATE})")
    if st.st_size > DEVICE_FILE_MAX_BYTES:
        raise _file_error(
            path, f"is too large ({st.st_size} bytes, at most {DEVICE_FILE_MAX_BYTES}): a device file holds one device"
        )
    try:
        with open(path, "rb") as fh:
            text = fh.read(DEVICE_FILE_MAX_BYTES + 1).decode("utf-8-sig")  # a BOM (Windows editors) is dropped
    except OSError as exc:
        raise _file_error(path, f"cannot be read ({exc.strerror or exc}): check its permissions") from None
    except UnicodeDecodeError:
        raise _file_error(path, "is not UTF-8 text: save it as a UTF-8 TOML file") from None
    try:
        data: dict[str, Any] = tomllib.loads(text)
        return data
    except tomllib.TOMLDecodeError as exc:
        raise _file_error(path, f"is not valid TOML ({exc}); compare it with `dfa devices --template`") from None
    except RecursionError:  # the reader recurses once per bracket: [[[[…]]]] of thousands
        raise _file_error(
            path,
            "nests brackets or braces too deeply for the TOML reader (thousands of levels): a device file "
            "holds one [[devices]] table of numbers and text; compare it with `dfa devices --template`",
        ) from None


def _unknown(path: str, keys: list[str], allowed: tuple[str, ...], where: str) -> DeviceFileError:
    close = difflib.get_close_matches(keys[0], allowed, n=1, cutoff=0.6)
    hint = f"did you mean {close[0]!r}? " if close else ""
    return _file_error(
        path,
        f"has unknown key{'s' if len(keys) > 1 else ''} {', '.join(map(repr, keys))} {where}: {hint}"
        f"the keys are {', '.join(allowed)}",
    )


def _file_row(path: str, data: dict[str, Any]) -> dict[str, Any]:
    """The one ``[[devices]]`` table of a device file."""
    rows = data.get("devices")
    if set(data) - {"devices"}:
        extra = sorted(set(data) - {"devices"})
        if rows is None and set(extra) & set(_FILE_KEYS):
            raise _file_error(
                path, f"has its keys at the top: put them under a [[devices]] line, as the catalogue does ({_TEMPLATE})"
            )
        raise _unknown(path, extra, ("devices",), "at the top")
    if not isinstance(rows, list) or not rows or not all(isinstance(r, dict) for r in rows):
        raise _file_error(path, f"has no [[devices]] table: a device file holds one ({_TEMPLATE})")
    if len(rows) > 1:
        raise _file_error(
            path, f"holds {len(rows)} [[devices]] tables: a device file holds one device; put each in its own file"
        )
    row: dict[str, Any] = rows[0]
    return row


def _file_text(path: str, key: str, value: object) -> str:
    """``name``, ``kind``, ``source`` or ``notes`` of a device file: text, by the rule of its key."""
    from ..checks import format_value

    if not isinstance(value, str):
        raise _file_error(path, f"has {key} = {format_value(value)}: it must be text in quotes")
    text = " ".join(value.split()) if key == "notes" else value.strip()
    if key == "name" and (not text or len(text) > 100 or not text.isprintable()):
        raise _file_error(path, f"has name = {value[:40]!r}: it must be printable text of 1 to 100 characters")
    if key == "kind" and text not in _KINDS:
        raise _file_error(path, f"has kind = {value[:40]!r}: it must be one of {', '.join(map(repr, _KINDS))}")
    return text


def _file_flag(path: str, key: str, value: object) -> bool:
    """``rotary`` or ``incomplete`` of a device file: true or false (``incomplete`` only false)."""
    from ..checks import format_value

    if not isinstance(value, bool):
        raise _file_error(path, f"has {key} = {format_value(value)}: it must be true or false")
    if key == "incomplete" and value:
        raise _file_error(
            path, f"has incomplete = true: a device file gives every physical value ({', '.join(_PHYSICAL)})"
        )
    return value


def _file_printed(path: str, key: str, value: object) -> tuple[tuple[str, str], ...]:
    """``printed`` of a device file: a table of the (μ, β, σ) a source printed, as decimal text."""
    from ..checks import format_value

    if not isinstance(value, dict):
        raise _file_error(path, 'has printed that is not a table: write printed = { mu = "155.2", ... }')
    unknown = sorted(set(value) - {"mu", "beta", "sigma"})
    if unknown:
        raise _unknown(path, unknown, ("mu", "beta", "sigma"), "in printed")
    out = []
    for k in (k for k in ("mu", "beta", "sigma") if k in value):
        v = value[k]
        digits = ""
        if isinstance(v, str):
            digits = v.strip()
        elif isinstance(v, (int, float)) and not isinstance(v, bool):
            digits = repr(v)
        try:
            ok = bool(digits) and math.isfinite(float(Decimal(digits)))
        except (ArithmeticError, ValueError):
            ok = False
        if not ok:
            raise _file_error(path, f"has printed {k} = {format_value(v)}: it must be a finite decimal number")
        out.append((k, digits))
    return tuple(out)


def _file_number(path: str, key: str, value: object) -> float:
    """A physical value of a device file (one of the device's fields, or the stiffness): a number by its rule."""
    from ..checks import format_value

    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _file_error(
            path,
            f"has {key} = {format_value(value)}: it must be a number in SI units, without quotes (e.g. {key} = 0.25)",
        )
    try:
        return _BY_NAME[key].check(value, fix=f"give {key} in {_BY_NAME[key].units}")
    except DFAError as exc:
        raise DeviceFileError(f"device file {path!r}: {exc}") from None


def _file_configurations(path: str, key: str, value: object) -> tuple[Configuration, ...]:
    """``[[devices.configurations]]`` of a device file (:func:`~dfa.model.configurations.configurations_from_toml`)."""
    try:
        return configurations_from_toml(value, f"device file {path!r}")
    except DFAError as exc:
        raise DeviceFileError(str(exc)) from None


#: How each key of a device file is read and checked (its value, the file's path and the key).
_FILE_READERS: dict[str, Callable[[str, str, object], object]] = {
    **dict.fromkeys(_TEXT_KEYS, _file_text),
    **dict.fromkeys(("rotary", "incomplete"), _file_flag),
    "printed": _file_printed,
    "configurations": _file_configurations,
    **dict.fromkeys((f.name for f in _ROW_FIELDS), _file_number),
}


def _file_value(path: str, key: str, value: object) -> object:
    """One value of a device file, checked by the rule of its key."""
    return _FILE_READERS[key](path, key, value)


def load_device_file(path: str | os.PathLike[str]) -> CatalogueEntry:
    """Read a device of your own from a TOML file in the catalogue's format (:func:`device_template`).

    The file holds one ``[[devices]]`` table: ``name`` and the five physical values in SI units (``mass``,
    ``damping``, ``coulomb``, ``resolution``, ``period``) are required; ``stiffness``, ``rotary``, ``kind``,
    ``source``, ``notes`` and ``printed`` (the (μ, β, σ) a source printed) are optional, and so are
    ``[[devices.configurations]]`` tables (:mod:`dfa.model.configurations`: the dynamics at the device's poses).

    Parameters
    ----------
    path : str or path-like
        The file (at most :data:`DEVICE_FILE_MAX_BYTES` bytes, UTF-8).

    Returns
    -------
    CatalogueEntry
        The row; ``.device`` is its :class:`Device` (which warns, :class:`~dfa.errors.ImplausibleInputWarning`,
        for values no haptic device has), ``.params`` its (μ, β, σ) at its stiffness.

    Raises
    ------
    DeviceFileError
        A missing or unreadable file, not TOML, no or several ``[[devices]]`` tables, a key missing or unknown,
        a value of the wrong type or outside its rule; the message names the file and the key (a
        :class:`~dfa.errors.DFAValueError`).
    DFATypeError
        If ``path`` is not a path.

    See Also
    --------
    device_template : A commented file to start from.
    resolve_device : The device with some values replaced (``entry=``).

    Examples
    --------
    >>> import os, tempfile
    >>> path = os.path.join(tempfile.mkdtemp(), "delta.toml")
    >>> with open(path, "w", encoding="utf-8") as fh:
    ...     _ = fh.write(device_template(get_device("Delta")))
    >>> load_device_file(path) == get_device("Delta")
    True
    """
    if not isinstance(path, (str, os.PathLike)):
        raise DFATypeError(f"path = {path!r} has type {type(path).__name__}: it must be a file path (str)")
    name = os.fspath(path)
    if not isinstance(name, str):
        name = os.fsdecode(name)
    row = _file_row(name, _read_toml(name))
    unknown = [k for k in row if k not in _FILE_KEYS]
    if unknown:
        raise _unknown(name, unknown, _FILE_KEYS, "in [[devices]]")
    missing = [k for k in _REQUIRED if k not in row]
    if missing:
        raise _file_error(
            name,
            f"lacks {', '.join(missing)}: a device file gives {_and(_REQUIRED)} "
            f"({_and(_OPTIONAL)} {'is' if len(_OPTIONAL) == 1 else 'are'} optional; {_TEMPLATE})",
        )
    values = {k: _file_value(name, k, v) for k, v in row.items()}
    values.pop("incomplete", None)
    fields: dict[str, Any] = {"kind": "haptic device", "source": "", "notes": ""} | values
    fields["source"] = fields["source"] or f"device file {os.path.basename(name)}"
    return CatalogueEntry(**fields)


def _and(names: tuple[str, ...]) -> str:
    """``"a, b and c"``."""
    return names[0] if len(names) == 1 else f"{', '.join(names[:-1])} and {names[-1]}"


def _toml_value(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return json.dumps(value, ensure_ascii=False)  # a TOML basic string: JSON's escapes are TOML's


_TEMPLATE_COMMENTS = {
    "name": "shown in outputs and report file names (1 to 100 characters)",
    "kind": '"haptic device", "experimental testbed" or "human"',
    "source": "where the values come from (a datasheet, a measurement)",
    "rotary": "true: positions in rad, forces in N·m, the mass an inertia in kg·m²",
    **{f.name: f.comment for f in _ROW_FIELDS},
    "printed": "optional: the (μ, β, σ) your source printed, compared with the recomputed ones",
    "notes": "optional remarks",
}


#: The template's optional keys written commented out (:func:`device_template` without a row): the example
#: device's own statements, not values to keep for another device.
_PLACEHOLDERS = ("source", "printed", "notes")


def device_template(entry: CatalogueEntry | None = None) -> str:
    """A commented device file to edit (TOML, the catalogue's format), or a row that reads back unchanged.

    Parameters
    ----------
    entry : CatalogueEntry, optional
        The row to write in full (every field; it loads back unchanged). Default: a template to edit, the
        catalogue's :data:`DEFAULT_DEVICE` as the example values, with ``source``, ``printed`` and ``notes``
        commented out (placeholders: the Delta's source and printed values, and a remark to replace; a device
        made by changing the physical values would otherwise carry them as its own).

    Returns
    -------
    str
        The file's text: a header saying how to use it, then one ``[[devices]]`` table, each key under a comment
        with its unit and rule, then the row's ``[[devices.configurations]]`` tables (issue 46), if any.

    Raises
    ------
    DFAValueError
        For an incomplete row (a device file gives every physical value).
    DFATypeError
        If ``entry`` is not a :class:`CatalogueEntry`.

    See Also
    --------
    load_device_file : Reads the file back.
    catalogue : The rows of the catalogue.
    """
    e = get_device(DEFAULT_DEVICE) if entry is None else entry
    placeholders = entry is None
    if not isinstance(e, CatalogueEntry):
        raise DFATypeError(f"entry = {e!r} has type {type(e).__name__}: it must be a CatalogueEntry or None")
    if e.missing:
        raise DFAValueError(
            f"entry = {e.name!r} is incomplete (unknown: {', '.join(e.missing)}): a device file gives every physical "
            "value; choose a complete row"
        )
    values: dict[str, object] = {"name": e.name, "kind": e.kind, "source": e.source, "rotary": e.rotary}
    values |= {f.name: getattr(e, f.name) for f in _ROW_FIELDS if f.required or getattr(e, f.name) is not None}
    lines = [f"{k} = {_toml_value(v)}" for k, v in values.items()]
    if e.printed:
        lines.append("printed = { " + ", ".join(f"{k} = {_toml_value(v)}" for k, v in e.printed) + " }")
    if placeholders:  # the example's own notes are about it, and long: a placeholder to fill in
        lines.append(f"notes = {_toml_value('remarks on your device (assumptions, corrections)')}")
    elif e.notes:
        lines.append(f"notes = {_toml_value(e.notes)}")
    body = []
    for line in lines:
        key = line.split(" ", 1)[0]
        body += [f"# {_TEMPLATE_COMMENTS[key]}", f"# {line}" if placeholders and key in _PLACEHOLDERS else line]
    head = [
        "# A device for dfa, in the format of dfa's own catalogue: one [[devices]] table, SI units.",
        "# Use it with every command that takes a device, e.g.",
        "#   dfa check --device-file my_device.toml --velocity 0.1",
        "# Flags given with it (--mass ... --period, --counts, --stiffness, --name, --rotary) replace its values.",
        f"# The values below are the catalogue's {e.name}: put your device's in their place.",
        *(
            [
                "# The keys commented out (source, printed, notes) are placeholders, not your device's: to give",
                "# yours, remove the '# ' before the key and write your own.",
            ]
            if placeholders
            else []
        ),
        "",
        "[[devices]]",
    ]
    return "\n".join(head + body + _configuration_tables(e.configurations)) + "\n"


def _configuration_tables(configurations: tuple[Configuration, ...]) -> list[str]:
    """The ``[[devices.configurations]]`` tables of a row (issue 46): each configuration's given keys, every number
    as its shortest round-tripping decimal (``load_device_file`` reads the same doubles back)."""
    if not configurations:
        return []
    out = [
        "",
        "# configurations: the values felt along the wall's normal at a pose (mass, damping, coulomb, resolution",
        "# that differ, or inertia with per-axis values and an optional normal); docs/cli.md, configurations",
    ]
    for c in configurations:
        out += ["", "[[devices.configurations]]", *(f"{k} = {_toml_value(v)}" for k, v in c.to_dict().items())]
    return out
