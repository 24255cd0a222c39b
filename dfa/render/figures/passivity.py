"""Stiffness limits with and without a passivity controller, relative to the plain wall's, per device."""

from __future__ import annotations

import matplotlib
import matplotlib.layout_engine
import matplotlib.lines
import matplotlib.pyplot as plt
import matplotlib.ticker
from matplotlib.patches import Patch

from .style import SMALL_FONTSIZE, legend_outside

#: Colours of the walls of :func:`passivity_plot` (plain, limited controller, unlimited controller).
PASSIVITY_COLORS = {"plain": "0.55", "limited": "#2166ac", "unlimited": "#b2182b"}


def _passivity_bar(ax, x: float, lim: dict, base: float | None, color: str) -> None:
    """One bar of :func:`passivity_plot`: K/K_plain; hatched at the range end for a lower bound; 'none' else."""
    v = lim["value"] if lim["value"] is not None else (lim["range_end"] if lim["status"] == "above_range" else None)
    if v is None or base is None:
        ax.text(x, 1.0, "none", rotation=90, ha="center", va="bottom", fontsize=SMALL_FONTSIZE)
        return
    lower = lim["value"] is None
    ax.bar(x, v / base, width=0.25, color=color, hatch="//" if lower else None, edgecolor="k", lw=0.5)


def passivity_plot(comparison, axes=None):
    """Stiffness limits with and without a passivity controller, relative to the plain wall's, per device.

    Parameters
    ----------
    comparison : PassivityComparison
        :func:`dfa.studies.passivity_comparison.passivity_comparison`.
    axes : pair of matplotlib.axes.Axes, optional
        The no-divergence and the rest panels; a new figure when None.

    Returns
    -------
    pair of Axes
    """
    cases = list(comparison.limits[0]) if comparison.limits else []  # plain, limited, unlimited
    if axes is None:
        _fig, axes = plt.subplots(1, 2, figsize=(10.0, 4.0), sharey=True, constrained_layout=True)
    titles = {"k_sim": "no simulated impact diverges", "k_sim_rest": "every simulated impact rests"}
    n = len(comparison.devices)
    for ax, (limit, title) in zip(axes, titles.items(), strict=True):
        for i in range(n):
            base = comparison.value(i, "plain", limit)
            for j, case in enumerate(cases):
                _passivity_bar(ax, i + (j - 1) * 0.27, comparison.limits[i][case][limit], base, PASSIVITY_COLORS[case])
        ax.axhline(1.0, color="k", lw=0.6)
        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set_xticks(range(n), comparison.devices, rotation=20, fontsize=SMALL_FONTSIZE)
        ax.set_title(title, fontsize=10)
    axes[0].set_ylabel("largest K / the plain wall's (–)")
    handles = [Patch(color=PASSIVITY_COLORS[c], label=lab) for c, lab in
               (("plain", "paper's spring"), ("limited", f"controller, force limit {comparison.limit_frictions:g} c"),
                ("unlimited", "controller, no force limit"))]  # fmt: skip
    handles.append(Patch(facecolor="white", edgecolor="k", hatch="//", label="lower bound (top of range)"))
    legend_outside(axes[1], handles)
    return axes
