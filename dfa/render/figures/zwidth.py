"""The Z-width of a device: B across, K up, one boundary per method, the simulated grid shaded."""

from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from .style import legend_outside, new_axes

#: Line styles of the Z-width boundaries, by method (:data:`dfa.analysis.limits.zwidth.ZWIDTH_METHODS`).
_ZWIDTH_STYLES: dict[str, tuple[str, dict[str, Any]]] = {
    "linear": ("exact linear bound", dict(color="#2166ac", ls="-", lw=1.6)),
    "passivity": ("Colgate–Schenkel passivity (linear model)", dict(color="#762a83", ls="--", lw=1.4)),
    "criterion": ("extended criterion (proof, eq. 6)", dict(color="#1b7837", ls="-", lw=2.0)),
    "df": ("describing function", dict(color="#8c510a", ls=(0, (4, 1.5, 1, 1.5)), lw=1.4)),
    "sim": ("simulation: no divergence (grid value)", dict(color="#b2182b", ls="none", marker="o", ms=4.5)),
    "rest": (
        "simulation: comes to rest (grid value)",
        dict(color="#333333", ls="none", marker="s", ms=5, mfc="none", mew=1.2),
    ),
}
#: The Z-width's methods whose boundary is a value of the K grid: markers only, never joined by a line (a line
#: between two B would claim values between grid stiffnesses, and one isolated grid point draws a spike).
_ZWIDTH_GRID_VALUED = ("sim", "rest")
#: Shade of each simulated outcome of the Z-width grid; "diverges" is dark as in the maps (never white on white).
ZWIDTH_COLORS = {
    "rest": "#d1e5f0", "bounded": "#fddbc7", "diverges": "#a3a3a3", "undecided": "#e08214", "left": "#e7f4e4",
}  # fmt: skip


#: A Z-width method defined at a single B: a marker above the design point's star (zorder 6), never under it.
_LONE: dict[str, Any] = {"marker": "o", "ms": 6, "mec": "white", "mew": 0.8, "zorder": 7}
#: The design point on the Z-width.
_STAR: dict[str, Any] = {"marker": "*", "ms": 16, "color": "k", "mfc": "gold", "ls": "none", "zorder": 6}


def plot_zwidth(zw, ax=None, design_point: tuple[float, float] | None = None):
    """The Z-width of a device: B across, K up (log), one line per method, the simulated region shaded.

    The Z-width of a device file's configurations (``zw.limiting``) names the configuration of the simulated
    boundary beside each of its markers. The simulated boundaries are values of the K grid and are drawn as markers, one per B, never joined
    (a line would claim stiffnesses between the grid's and draw an isolated grid value as a spike). A
    method defined at a single B (often the criterion, at B = 0 only) is a marker drawn above
    everything else, the design point's star included, so that neither hides the other. The shades are
    :data:`ZWIDTH_COLORS`: where the grid's runs diverge is grey, distinct from the white of the page.

    Parameters
    ----------
    zw : dfa.analysis.limits.zwidth.ZWidth
        The result of :func:`dfa.analysis.limits.zwidth.z_width`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).
    design_point : (float, float), optional
        A design point (B, K) in the device's units (N·s/m, N/m; rotary N·m·s/rad, N·m/rad), starred
        and in the legend; a K outside the grid is drawn at the grid's edge.

    Returns
    -------
    matplotlib.axes.Axes
    """
    from ...results.codes import BOUNDED, DIVERGES, LEFT_POINT, REST, UNDECIDED_POINT, ZWIDTH_METHODS

    ax = new_axes(ax, figsize=(7.6, 4.6))
    u = zw.device.units
    ks, bs = np.asarray(zw.stiffness), np.asarray(zw.damping)
    shade = np.full(zw.outcome.shape, np.nan)
    colours = {REST: ZWIDTH_COLORS["rest"], BOUNDED: ZWIDTH_COLORS["bounded"], DIVERGES: ZWIDTH_COLORS["diverges"],
               UNDECIDED_POINT: ZWIDTH_COLORS["undecided"], LEFT_POINT: ZWIDTH_COLORS["left"]}  # fmt: skip
    cmap = ListedColormap([colours[c] for c in (REST, BOUNDED, DIVERGES, UNDECIDED_POINT, LEFT_POINT)])
    shade[:] = zw.outcome
    kedges = np.sqrt(ks[1:] * ks[:-1])
    kedges = np.concatenate([[ks[0] ** 2 / kedges[0]], kedges, [ks[-1] ** 2 / kedges[-1]]])
    bstep = bs[1] - bs[0] if bs.size > 1 else 1.0
    bedges = np.concatenate([bs - bstep / 2, [bs[-1] + bstep / 2]])
    ax.pcolormesh(bedges, kedges, shade.T, cmap=cmap, vmin=-0.5, vmax=4.5, shading="flat")
    for m in ZWIDTH_METHODS:
        label, style = _ZWIDTH_STYLES[m]
        y = np.asarray(zw.boundary(m), dtype=float)
        if np.isfinite(y).any():
            lone = {"zorder": _LONE["zorder"]} if m in _ZWIDTH_GRID_VALUED else _LONE
            ax.plot(bs, y, label=label, **{**style, **(lone if np.isfinite(y).sum() < 2 else {})})
    if zw.limiting:  # a device file's configurations: which one limits the simulated boundary at each B
        for b, k, name in zip(bs, zw.boundary("sim"), zw.limiting["sim"], strict=True):
            if np.isfinite(k):
                ax.annotate(name, (b, k), xytext=(4, 4), textcoords="offset points", fontsize=7, color="#b2182b")
    ax.set_yscale("log")
    ax.set_ylim(kedges[0], kedges[-1])
    ax.set_xlim(bedges[0], bedges[-1])
    ax.set_xlabel(f"virtual damping B ({u['damping']})")
    ax.set_ylabel(f"virtual stiffness K ({u['stiffness']})")
    contact = ", one-sided wall reached from free space" if zw.wall.one_sided else ""
    over = " (the minimum over its configurations, B by B)" if zw.limiting else ""
    ax.set_title(f"Z-width of {zw.device.name}{over}, impacts up to {zw.velocity:.3g} {u['velocity']}{contact}",
                 fontsize=9)  # fmt: skip
    if design_point is not None:
        b, k = design_point
        lo, hi = kedges[0], kedges[-1]
        ax.plot([b], [min(max(k, lo), hi)], label="design point (B, K)", **_STAR)
    handles, _ = ax.get_legend_handles_labels()
    handles += [
        Patch(facecolor=colours[REST], edgecolor="0.5", label="simulated: rest"),
        *(
            [Patch(facecolor=colours[LEFT_POINT], edgecolor="0.5", label="simulated: rest or left the wall")]
            if contact
            else []
        ),  # fmt: skip
        Patch(facecolor=colours[BOUNDED], edgecolor="0.5", label="simulated: bounded (chatter or cycle)"),
        Patch(facecolor=colours[UNDECIDED_POINT], edgecolor="0.5", label="simulated: undecided"),
        Patch(facecolor=colours[DIVERGES], edgecolor="0.5", label="simulated: diverges"),
    ]
    legend_outside(ax, handles)
    return ax
