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
"""

from __future__ import annotations

import difflib
import math
import re
import sys
from dataclasses import dataclass, field
from decimal import Decimal
from functools import lru_cache
from importlib import resources

from ..errors import DFATypeError, DFAValueError
from ..results.jsonable import explain_nulls
from .device import Device, Params

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
    "DEFAULT_DEVICE",
]

#: Name of the catalogue device used by ``make report`` and the CLI examples.
DEFAULT_DEVICE = "Delta"

#: Relative disagreement above which a printed value is reported (5 %).
RELATIVE_TOLERANCE = 0.05

_PHYSICAL = ("mass", "damping", "coulomb", "resolution", "period")


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

    def __str__(self) -> str:
        return (
            f"{self.parameter}: printed {self.printed}, recomputed {self.recomputed:.4g} ({100 * self.relative:+.1f} %)"
        )


def _half_unit(printed: str) -> float:
    """Half a unit in the last printed digit of a decimal string."""
    exponent = Decimal(printed).as_tuple().exponent
    assert isinstance(exponent, int)
    return 0.5 * 10.0**exponent


@dataclass(frozen=True)
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
    stiffness : float or None
        Virtual spring stiffness K of the row in N/m (rotary: N·m/rad).
    rotary : bool
        True when positions are angles and forces torques.
    incomplete : bool
        True when some physical value is unknown.
    printed : tuple of (str, str)
        The (μ, β, σ) printed in the paper, as ``(name, decimal string)`` pairs.
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
    stiffness: float | None = None
    rotary: bool = False
    incomplete: bool = False
    printed: tuple[tuple[str, str], ...] = field(default_factory=tuple)

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
        return Device(
            mass=self.mass,  # type: ignore[arg-type]
            damping=self.damping,  # type: ignore[arg-type]
            coulomb=self.coulomb,  # type: ignore[arg-type]
            resolution=self.resolution,  # type: ignore[arg-type]
            period=self.period,  # type: ignore[arg-type]
            name=self.name,
            rotary=self.rotary,
        )

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
            "mass": self.mass,
            "damping": self.damping,
            "coulomb": self.coulomb,
            "resolution": self.resolution,
            "period": self.period,
            "stiffness": self.stiffness,
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
        why = dict.fromkeys(("mass", "damping", "coulomb", "resolution", "period"), missing)
        why["stiffness"] = "the source gives no stiffness K for this device"
        why.update(dict.fromkeys(("mu", "beta", "sigma"), "not computable: the physical row is incomplete"))
        why["printed"] = "the paper prints no (μ, β, σ) for this device"
        return explain_nulls(out, why)


def _entry(raw: dict) -> CatalogueEntry:
    printed = tuple((k, str(raw.get("printed", {})[k])) for k in ("mu", "beta", "sigma") if k in raw.get("printed", {}))
    values = {p: (float(raw[p]) if p in raw else None) for p in (*_PHYSICAL, "stiffness")}
    entry = CatalogueEntry(
        name=raw["name"],
        kind=raw.get("kind", "haptic device"),
        source=raw.get("source", ""),
        notes=" ".join(raw.get("notes", "").split()),
        rotary=bool(raw.get("rotary", False)),
        incomplete=bool(raw.get("incomplete", False)),
        printed=printed,
        **values,
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
) -> ResolvedDevice:
    """A device from a catalogue name, physical values, or a catalogue device with some values replaced.

    Parameters
    ----------
    name : str, optional
        Catalogue device (:func:`get_device` matching); None for a custom device.
    overrides : dict, optional
        Physical values replacing the catalogue's (or all five for a custom device): ``mass`` in kg (rotary:
        inertia in kg·m²), ``damping`` in N·s/m (N·m·s/rad), ``coulomb`` in N (N·m), ``resolution`` in m (rad),
        ``period`` in s. None values are ignored.
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
    from ..checks import check_positive, format_value
    from .device import dimensionless_params

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
    fl = {k: k for k in (*_PHYSICAL, "stiffness", "counts", "name")} | (flags or {})
    given = {k: v for k, v in (overrides or {}).items() if v is not None}
    unknown = sorted(set(given) - set(_PHYSICAL))
    if unknown:
        raise DFAValueError(f"overrides has {unknown}: physical values are {', '.join(_PHYSICAL)}")
    entry = get_device(name) if name else None
    values: dict[str, float | None] = {k: getattr(entry, k) for k in _PHYSICAL} if entry else {}
    rotary = bool(rotary or (entry is not None and entry.rotary))
    if counts is not None:
        if "resolution" in given:
            raise DFAValueError(
                f"{fl['counts']} and {fl['resolution']} cannot both be given: the counts set the resolution"
            )
        given["resolution"] = _counts_resolution(counts, rotary, fl["counts"])
    values |= _checked(given, fl)
    missing = [fl[k] for k in _PHYSICAL if values.get(k) is None]
    if missing:
        _refuse_missing(entry, given, missing, fl)
    dev = Device(name=label or (entry.name if entry else "custom device"), rotary=rotary, **values)  # type: ignore[arg-type]
    k = stiffness if stiffness is not None else (entry.stiffness if entry else None)
    if k is not None:
        k = check_positive(fl["stiffness"], k, f"give the virtual wall stiffness K in {dev.units['stiffness']}")
        names = {key: fl[key] for key in given} | ({"stiffness": fl["stiffness"]} if stiffness is not None else {})
        dimensionless_params(dev, k, names)  # refuses μ, β, σ that overflow or vanish, naming these inputs
    same = entry is not None and not given and (label is None or label == entry.name)
    return ResolvedDevice(dev, None if k is None else float(k), entry if same else None)


def _checked(given: dict[str, float], fl: dict[str, str]) -> dict[str, float | None]:
    """Physical values checked: mass, resolution and period > 0; damping and Coulomb friction >= 0."""
    from ..checks import check_nonnegative, check_positive

    out: dict[str, float | None] = {}
    for k, v in given.items():
        check = check_positive if k in ("mass", "resolution", "period") else check_nonnegative
        out[k] = check(fl[k], v, f"give {k} in {_UNITS[k]}")
    return out


_UNITS = {
    "mass": "kg (rotary: inertia in kg·m²)",
    "damping": "N·s/m (rotary: N·m·s/rad)",
    "coulomb": "N (rotary: N·m)",
    "resolution": "m (rotary: rad)",
    "period": "s",
}


def _refuse_missing(entry: CatalogueEntry | None, given: dict, missing: list[str], fl: dict[str, str]) -> None:
    if entry is not None:
        raise DFAValueError(
            f"device {entry.name!r} is incomplete in the catalogue: give {' '.join(missing)} explicitly"
        )
    every = " ".join(fl[k] for k in _PHYSICAL)
    if not given:
        raise DFAValueError(f"no device given: give a catalogue name (see `dfa devices`), or {every}")
    raise DFAValueError(f"missing {' '.join(missing)}: a physical device needs all of {every}")
