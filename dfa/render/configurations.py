"""The worst configuration of a device in words and tables (:class:`~dfa.results.configurations.WorstConfiguration`).

One row per configuration (the one-axis values along the normal, the normal, the command's number and its rule),
the limiting one marked, and a line naming it.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.results.configurations import ConfigurationRow, WorstConfiguration
>>> dev = get_device("impulse").device
>>> rows = (ConfigurationRow("near", 0.032, 0.02, 0.024, 314e-6, 101.2, "proven"),
...         ConfigurationRow("far", 0.064, 0.02, 0.012, 314e-6, 54.5, "proven"))
>>> w = WorstConfiguration(dev, 0.1, "k_recommended", rows, "far")
>>> print(limiting_line(w))
limiting configuration: far (recommended K 54.5 N/m, the smallest of 2 configurations)
"""

from __future__ import annotations

from ..errors import DFAValueError
from ..formatting import number
from ..results.configurations import WorstConfiguration
from ..results.status import ConfigurationStatus, CriterionStatus

__all__ = ["configuration_header", "configuration_rows", "limiting_line", "MARK"]

#: The mark of the limiting row.
MARK = "◀ limiting"
_WHAT = {"k_recommended": "recommended K", "margin": "margin"}


def _normal(row: object) -> str:
    n = getattr(row, "normal", None)
    if n is None:
        return "–"
    text = "(" + ", ".join(f"{x:.2f}" for x in n) + ")"
    return text + (" worst" if getattr(row, "searched", False) else "")


def _rule(quantity: str, rule: str) -> str:
    """The rule's cell: the recommendation's rule, or the criterion's region (a … e, as ``dfa check`` names it)."""
    if quantity != "margin":
        return rule
    try:
        return f"region {CriterionStatus.coerce(rule).region}"
    except DFAValueError:
        return rule.replace("_", " ")


def configuration_header(w: WorstConfiguration) -> list[str]:
    """The table's header: configuration, m, b, c, Δ (their units), normal, the number and its unit, rule, mark."""
    u = w.device.units
    value = _WHAT[w.quantity] + (f" ({w.value_unit})" if w.quantity == "k_recommended" else "")
    return [
        "configuration", f"m ({u['mass']})", f"b ({u['damping']})", f"c ({u['coulomb']})",
        f"Δ ({u['resolution']})", "normal", value, "rule", "",
    ]  # fmt: skip


def configuration_rows(w: WorstConfiguration) -> list[list[str]]:
    """One row per configuration, in the device file's order; the limiting one marked :data:`MARK`."""
    out = []
    for r in w.rows:
        out.append([
            r.name, number(r.mass), number(r.damping), number(r.coulomb), number(r.resolution), _normal(r),
            number(r.value), _rule(w.quantity, r.rule), MARK if r.name == w.limiting else "",
        ])  # fmt: skip
    return out


def limiting_line(w: WorstConfiguration) -> str:
    """One line naming the limiting configuration (its normal, if any) and its number (or why it has none)."""
    n = len(w.rows)
    what = _WHAT[w.quantity]
    name = w.limiting + _along(w.row)
    if w.status is ConfigurationStatus.NONE:
        return (f"limiting configuration: {name} (no {what} there: {w.row.rule}; none holds for the device "
                f"over its {n} configurations)")  # fmt: skip
    unit = f" {w.value_unit}" if w.quantity == "k_recommended" else ""
    if n == 1:
        return f"configuration: {name} ({what} {number(w.value)}{unit})"
    return f"limiting configuration: {name} ({what} {number(w.value)}{unit}, the smallest of {n} configurations)"


def _along(row: object) -> str:
    """`` along n = (x, y, z)`` (``worst n`` when searched) for a row with a normal; empty without one."""
    n = getattr(row, "normal", None)
    if n is None:
        return ""
    word = "the worst n" if getattr(row, "searched", False) else "n"
    return f" along {word} = (" + ", ".join(f"{x:.3g}" for x in n) + ")"
