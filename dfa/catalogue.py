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

from .device import Device, Params
from .errors import DFATypeError, DFAValueError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

__all__ = ["Discrepancy", "CatalogueEntry", "catalogue", "get_device", "DEFAULT_DEVICE"]

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
        """The physical :class:`~dfa.device.Device`; raises if the row is incomplete."""
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

    def as_dict(self) -> dict[str, object]:
        """JSON-ready record: physical values, recomputed and printed (μ, β, σ), discrepancies."""
        p = self.params
        return {
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
    text = resources.files("dfa").joinpath("data/devices.toml").read_text(encoding="utf-8")
    return tuple(_entry(raw) for raw in tomllib.loads(text)["devices"])


def _key(name: str) -> str:
    return re.sub(r"[^a-z0-9.]", "", name.lower())


def get_device(name: str) -> CatalogueEntry:
    """Look a catalogue row up by name.

    Matching is case-insensitive and ignores spaces and punctuation other than
    dots; an unambiguous prefix (``"phantom"``, ``"impulse"``) is enough.

    Raises
    ------
    DFAValueError
        For an unknown or ambiguous name, listing the closest names.
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
