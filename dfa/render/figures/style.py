"""Shared look of the figures: axis labels, colours of regions and outcomes, the operating point's style, font
sizes, new axes and legends placed beside the data (never over it)."""

from __future__ import annotations

from typing import Any

import matplotlib
import matplotlib.layout_engine
import matplotlib.lines
import matplotlib.pyplot as plt
import matplotlib.ticker
from matplotlib.artist import Artist
from matplotlib.colors import ListedColormap

from ...results.status import SimulationOutcome

BETA_LABEL = "β = b/(K T) (–)"
SIGMA_LABEL = "σ = c/(K Δ) (–)"
#: Shade of each region of eq. 10 (Fig. 3); c (no guarantee at any speed) is also hatched (:data:`REGION_HATCH`) and
#: d (no guarantee at this speed) pink, so that the two read apart (they were two tints of one orange).
REGION_COLORS = {"a": "#d9f0d3", "b": "#c6dbef", "c": "#f4a582", "d": "#f1b6da", "e": "#fff7bc"}
#: Hatching of region c and its colour.
REGION_HATCH = {"c": ("///", "#b35806")}
#: Colour of each simulated outcome (paper Fig. 4: white stable, light persisting oscillation, dark unstable).
OUTCOME_COLORS = {
    "rest": "#ffffff",
    "chatter": "#d4d4d4",
    "oscillating": "#969696",
    "unstable": "#252525",
    "undecided": "#e08214",
    "left": "#9ecae1",  # a one-sided wall's run only (dfa.OneSided)
    "saturated": "#cb181d",  # a wall with an actuator's force limit only (dfa.model.elements.ForceLimit)
    "end_stop": "#b2182b",  # past the device's travel only (dfa.Travel)
}
OUTCOME_LABELS = {
    "rest": "rest (came to rest)",
    "chatter": "chatter (persisting, < 1 tick)",
    "oscillating": "oscillating (persisting, >= 1 tick)",
    "unstable": "unstable (diverged)",
    "undecided": "undecided (run too short)",
    "left": "left (a one-sided wall, for good)",
    "saturated": "saturated (held by the force limit)",
    "end_stop": "end stop (past the device's travel)",
}
#: A new outcome (a member of :class:`SimulationOutcome`) without a designer's colour and label above gets a default:
#: dark red when it fails a simulated limit, grey otherwise; its code in words with its message.
for _o in SimulationOutcome:
    OUTCOME_COLORS.setdefault(_o.value, "#a50f15" if _o.fails else "#bdbdbd")
    OUTCOME_LABELS.setdefault(_o.value, f"{_o.value.replace('_', ' ')} ({_o.message})")
del _o


def outcome_cmap() -> ListedColormap:
    return ListedColormap([OUTCOME_COLORS[o.value] for o in SimulationOutcome])  # indexed by the outcome code


def new_axes(ax=None, figsize=(5.0, 4.0)):
    if ax is None:
        _fig, ax = plt.subplots(figsize=figsize, constrained_layout=True)
    return ax


#: One style for the operating point (design point) in every (β, σ) figure.
POINT_STYLE: dict[str, Any] = dict(marker="o", color="#b2182b", ms=8, mec="k", mew=1.0, ls="none", zorder=5)
#: Styles of further critical lines (regions plot), distinct from the dashed line of the operating point.
EXTRA_LINES = (
    dict(color="#4d4d4d", ls=":", lw=1.4),
    dict(color="#2166ac", ls=(0, (6, 2)), lw=1.1),
    dict(color="#762a83", ls=(0, (4, 1.5, 1, 1.5)), lw=1.1),
    dict(color="#8c510a", ls=(0, (1, 3)), lw=1.6),
)


#: Font size of every legend, points at the saved size (a figure is saved at its own size in inches, any dpi).
LEGEND_FONTSIZE = 9.0
#: Characters per line of a legend label beside a plot of many long labels (bounds, speed chart).
LEGEND_WRAP = 32
#: Font size of secondary texts (physical axes, insets, contour labels, notes), points.
SMALL_FONTSIZE = 8.0


def legend_outside(ax, handles=None, fontsize: float = LEGEND_FONTSIZE, *, wrap: int | None = None) -> None:
    """The legend to the right of the axes, never over the data; ``wrap``: labels broken into lines of at most
    that many characters, so that a legend of long labels stays narrow beside its plot."""
    kw = dict(fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, framealpha=0.9)
    if handles is None:
        handles, _labels = ax.get_legend_handles_labels()
    labels = [h.get_label() for h in handles]
    ax.legend(handles, labels if wrap is None else [wrap_label(t, wrap) for t in labels], **kw)


def wrap_label(text: str, width: int) -> str:
    """``text`` in lines of at most ``width`` characters where it can be, broken only outside parentheses: after
    ": " or ", ", or before " (" (a value stays with its unit, a parenthesis whole).

    Examples
    --------
    >>> print(wrap_label("exact linear bound (no encoder, no friction): 60 N/m (= A–O, C–S)", 32))
    exact linear bound
    (no encoder, no friction):
    60 N/m (= A–O, C–S)
    """
    pieces, depth, start = [], 0, 0
    for i, ch in enumerate(text):
        depth += (ch == "(") - (ch == ")")
        cut = i + 1 if depth == 0 and ch == " " and text[i - 1] in ":," else None
        if depth == 0 and text.startswith(" (", i):
            cut = i
        if cut is not None and cut > start:
            pieces.append(text[start:cut])
            start = cut
    pieces.append(text[start:])
    lines = [""]
    for piece in pieces:
        if lines[-1] and len(lines[-1] + piece.rstrip()) > width:
            lines.append(piece.lstrip())
        else:
            lines[-1] += piece
    return "\n".join(line.rstrip() for line in lines)


def plane_margin(hi: float) -> float:
    """A margin left of / below 0 so that a point at β ≈ 0 or σ ≈ 0 is drawn whole (grey: outside the plane)."""
    return 0.03 * hi


def physical_map_axes(ax, device, stiffness: float) -> None:
    """Secondary axes of a (β, σ) panel at the device's K: damping b = βKT and Coulomb friction c = σKΔ (Table 1)."""
    u = device.units
    kt, kd = stiffness * device.period, stiffness * device.resolution
    size = ax.yaxis.label.get_fontsize()  # as large as the β and σ axes' labels: as readable
    top = ax.secondary_xaxis("top", functions=(lambda x: x * kt, lambda x: x / kt))
    top.set_xlabel(f"damping b at K = {stiffness:.5g} {u['stiffness']} ({u['damping']})", fontsize=size)
    right = ax.secondary_yaxis("right", functions=(lambda y: y * kd, lambda y: y / kd))
    right.set_ylabel(f"Coulomb friction c ({u['coulomb']})", fontsize=size)


def panels_legend(axes, handles: list[Artist], *, below: bool, ncols: int = 2) -> None:
    """The legend of a figure of panels, beside them (``below``: under them, in ``ncols`` columns, so that the
    figure is no wider than its panels), clear of every axis label, the secondary axes' included. A figure laid out by constrained layout gets a figure legend placed outside the panels
    by the layout; otherwise the legend goes right of the last panel, past its secondary axis when it has one
    (measured on the drawn figure)."""
    fig = axes[0].figure
    if isinstance(fig.get_layout_engine(), matplotlib.layout_engine.ConstrainedLayoutEngine):
        kw = dict(ncols=ncols, loc="outside lower center") if below else dict(loc="outside right upper")
        fig.legend(handles=handles, fontsize=LEGEND_FONTSIZE, framealpha=0.9, **kw)
        return
    ax = axes[-1]
    legend_outside(ax, handles)
    if ax.child_axes:  # a secondary axis' labels sit where the legend would go: start past them
        renderer = fig.canvas.get_renderer()
        right = max(c.get_tightbbox(renderer).x1 for c in ax.child_axes)
        box = ax.get_window_extent(renderer)
        ax.get_legend().set_bbox_to_anchor(((right - box.x0) / box.width + 0.02, 1.0))
