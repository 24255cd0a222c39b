"""The recommended stiffness (or margin) over a device's configurations; over its poses when each has one.

With a pose for every configuration (``pose = [x, y, z]`` in the device file: a pose grid), the value is drawn
over the poses' x and y (m), coloured, the limiting pose starred; otherwise one bar per configuration, the
limiting one dark. A configuration without a value (no recommended K) is marked with a cross at the bottom.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .style import new_axes

__all__ = ["configurations_plot"]

_STAR: dict[str, Any] = {"marker": "*", "s": 260, "c": "gold", "edgecolors": "k", "zorder": 5}


def configurations_plot(w, ax=None):
    """The rows of a :class:`~dfa.results.configurations.WorstConfiguration`, the limiting one marked.

    Parameters
    ----------
    w : WorstConfiguration
    ax : matplotlib Axes, optional

    Returns
    -------
    matplotlib Axes
    """
    label = "recommended K" if w.quantity == "k_recommended" else "criterion margin"
    unit = w.value_unit if w.quantity == "k_recommended" else "–"
    values = np.array([np.nan if r.value is None else r.value for r in w.rows], dtype=float)
    if all(r.pose is not None for r in w.rows):
        ax = new_axes(ax, figsize=(5.6, 4.4))
        xy = np.array([r.pose[:2] for r in w.rows], dtype=float)
        ok = np.isfinite(values)
        sc = ax.scatter(xy[ok, 0], xy[ok, 1], c=values[ok], s=90, cmap="viridis", edgecolors="k", linewidths=0.5)
        ax.figure.colorbar(sc, ax=ax, label=f"{label} ({unit})")
        if (~ok).any():
            ax.scatter(xy[~ok, 0], xy[~ok, 1], marker="x", c="#b2182b", s=70, label="no value")
        i = [r.name for r in w.rows].index(w.limiting)
        ax.scatter([xy[i, 0]], [xy[i, 1]], label=f"limiting: {w.limiting}", **_STAR)
        ax.set_xlabel("pose x (m)")
        ax.set_ylabel("pose y (m)")
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, frameon=False)
        ax.set_title(f"{w.device.name}: {label} over the poses", fontsize=10)
        return ax
    ax = new_axes(ax, figsize=(max(4.0, 0.6 * len(w.rows) + 2.0), 4.0))
    x = np.arange(len(w.rows))
    colors = ["#1b7837" if r.name == w.limiting else "#a6dba0" for r in w.rows]
    ax.bar(x, np.nan_to_num(values, nan=0.0), color=colors, edgecolor="k", linewidth=0.5)
    for j in np.flatnonzero(~np.isfinite(values)):
        ax.plot([x[j]], [0.0], marker="x", color="#b2182b", ms=9)
    ax.set_xticks(x, [r.name for r in w.rows], rotation=30, ha="right", fontsize=8)
    ax.set_ylabel(f"{label} ({unit})")
    ax.set_title(f"{w.device.name}: limiting configuration {w.limiting}", fontsize=10)
    return ax
