"""The base of every analysis result: a frozen dataclass with a status, JSON derived from its fields.

A result class subclasses :class:`Result` (``@dataclass(frozen=True)``) and declares, beside its fields:

- ``status``, a member of a :class:`~dfa.results.status.StatusEnum` (a snake_case code and its message);
- :attr:`Result.json_properties`: derived values users read, written to JSON beside the fields;
- :attr:`Result.units_of`: the kind of physical unit of each field (a key of ``Device.units``), so that
  the JSON records the unit of every quantity (``"units": {"k_max": "N/m", ...}``) once a device is known;
- :meth:`Result.null_reasons`: why a field may be null for a reason other than NaN or infinity.

:meth:`Result.to_dict` builds strict JSON (:mod:`dfa.jsonable`) from exactly these, so no result
writes its JSON by hand; a field's ``metadata={"json": fn}`` gives what it writes instead of itself (the
device's name, say), ``metadata={"json": None}`` leaves it out, ``metadata={"omit_none": True}`` leaves it out
when it is None (a field of some cases only).

Examples
--------
>>> from dataclasses import dataclass
>>> from dfa.results.status import CurveStatus
>>> @dataclass(frozen=True)
... class Demo(Result):
...     k_max: float
...     status: CurveStatus = CurveStatus.OK
>>> Demo(float("inf")).to_dict()
{'k_max': None, 'status': 'ok', 'status_message': 'K_max computed at every speed', 'null_reasons': {'/k_max': '+inf'}}
"""

from __future__ import annotations

import dataclasses
from typing import Any, ClassVar

from ..jsonable import explain_nulls, to_jsonable

__all__ = ["Result"]


class Result:
    """Base of the analysis results (module docstring): JSON from the fields, the status and its message."""

    #: Properties written to JSON beside the fields.
    json_properties: ClassVar[tuple[str, ...]] = ()
    #: Kind of physical unit (a key of ``Device.units``) of each physical field.
    units_of: ClassVar[dict[str, str]] = {}

    @property
    def status_message(self) -> str:
        """What the status means, in words (the status's message; a result may add the numbers of its case)."""
        status = getattr(self, "status", None)
        return "" if status is None else str(status.message)

    def null_reasons(self) -> dict[str, str]:
        """Why each field may be null in JSON, by key (beyond NaN and infinity, which say so themselves).

        Returns
        -------
        dict of str to str
            Reasons by field name; empty by default.
        """
        return {}

    def units(self) -> dict[str, str]:
        """The unit of each physical field, from the result's device (empty without one).

        Returns
        -------
        dict of str to str
            Field name to unit, e.g. ``{"velocity": "m/s"}``.
        """
        device = getattr(self, "device", None)
        if device is None or not self.units_of:
            return {}
        return {name: device.units[kind] for name, kind in self.units_of.items()}

    def to_dict(self) -> dict[str, Any]:
        """Strict-JSON data of the result: its fields, :attr:`json_properties`, the status message and units.

        Returns
        -------
        dict
            Data that ``json.dumps(..., allow_nan=False)`` accepts; every null has its reason under
            ``null_reasons`` (:mod:`dfa.jsonable`).
        """
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):  # type: ignore[arg-type]
            value = getattr(self, f.name)
            how = f.metadata.get("json", _SELF)
            if how is None or (value is None and f.metadata.get("omit_none")):  # absent: not part of this case
                continue
            out[f.name] = value if how is _SELF or value is None else how(value)
        for name in self.json_properties:
            out[name] = getattr(self, name)
        hand_json = getattr(getattr(self, "device", None), "hand_json", None)  # a held device states its hand
        if hand_json is not None:
            out.update(hand_json())
        if getattr(self, "status", None) is not None:
            out["status_message"] = self.status_message
        units = self.units()
        if units:
            out["units"] = units
        return explain_nulls(to_jsonable(out), self.null_reasons())


_SELF = object()  # a field written as itself


def figure_function(name: str) -> Any:
    """The plotting function ``name`` of the rendering layer's figures, imported by name when a ``.plot()`` runs.

    A result's ``.plot()`` draws through the rendering layer, which sits above the results: a plain import
    (even inside the method) would be an upward edge. This is the one place that resolves it, by name and
    only when called, so ``import dfa`` loads no matplotlib and the results import nothing above them.

    Parameters
    ----------
    name : str
        A function of :mod:`dfa.render.figures` (``"stiffness_plot"``, ...).

    Returns
    -------
    callable
        The plotting function.
    """
    import importlib

    return getattr(importlib.import_module(FIGURES_MODULE), name)


#: Where the figures live (imported by name only, by :func:`figure_function`).
FIGURES_MODULE = "dfa.render.figures"
