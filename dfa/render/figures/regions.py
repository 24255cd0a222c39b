"""The (β, σ) plane with the regions a-e of the criterion (paper Fig. 3, eq. 10)."""

from __future__ import annotations

from collections.abc import Sequence

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from ...results.status import CriterionStatus
from .style import (
    BETA_LABEL,
    EXTRA_LINES,
    POINT_STYLE,
    REGION_COLORS,
    REGION_HATCH,
    SIGMA_LABEL,
    new_axes,
    panels_legend,
    plane_margin,
)


def regions_plot(
    result,
    ax=None,
    *,
    xi_dots: Sequence[float] = (),
    beta_max: float = 1.0,
    sigma_max: float = 2.0,
    legend: bool = True,
):
    """The (β, σ) plane with regions a-e shaded for the result's speed and delay (paper Fig. 3, eq. 10).

    Parameters
    ----------
    result : CriterionResult
        The operating point (β, σ), its (energy-equivalent) speed V and delay d;
        the point is marked and its critical line (``result.critical_line``)
        drawn dashed.
    ax : matplotlib Axes, optional
    xi_dots : sequence of float
        Further speeds (ticks/sample) whose critical lines (same delay) are drawn, each in its own style.
    beta_max, sigma_max : float
        Smallest upper limits of the axes (–); the point and β = ½ + d are always inside.
    legend : bool
        Legend below the axes (default True; right of the axes when ``ax`` is not laid out by
        constrained layout).
    """
    ax = new_axes(ax, figsize=(5.6, 6.9) if legend else (5.6, 4.4))
    line = result.critical_line
    bmax = max(beta_max, 1.2 * result.beta, 0.6, 1.2 * line.beta0)
    smax = max(sigma_max, 1.2 * result.sigma, 0.6)
    b = np.linspace(0, bmax, 400)
    s = np.linspace(0, smax, 400)
    reg = line.regions(b[None, :], s[:, None])
    codes = np.searchsorted(np.array(list("abcde")), reg)
    cmap = ListedColormap([REGION_COLORS[k] for k in "abcde"])
    ax.set_facecolor("0.85")  # β < 0 or σ < 0: outside the plane, only there to show a point at the edge whole
    ax.imshow(
        codes,
        origin="lower",
        extent=(0, bmax, 0, smax),
        aspect="auto",
        cmap=cmap,
        vmin=-0.5,
        vmax=4.5,
        interpolation="nearest",
    )
    for k, (hatch, colour) in REGION_HATCH.items():
        inside = (codes == "abcde".index(k)).astype(float)
        if inside.any():
            with plt.rc_context({"hatch.color": colour, "hatch.linewidth": 0.7}):
                ax.contourf(b, s, inside, levels=[0.5, 1.5], colors="none", hatches=[hatch])
    ax.axvline(line.beta0, color="k", lw=0.8, ls="-.")
    if result.quantized:
        ax.axhline(line.sigma0, color="k", lw=0.8, ls="-.")
    dl = f", d = {result.delay}" if result.delay else ""
    ax.plot(
        b,
        line.sigma(b),
        "k--",
        lw=1.4,
        label=f"critical line at the operating point's speed, ξ'0 = {line.xi_dot:.3g}{dl}",
    )
    for v, style in zip(xi_dots, EXTRA_LINES * (1 + len(xi_dots) // len(EXTRA_LINES)), strict=False):
        ax.plot(b, line.at_speed(v).sigma(b), label=f"ξ'0 = {v:g}", **style)
    ax.plot([result.beta], [result.sigma], label=f"operating point (region {result.region})", **POINT_STYLE)
    ax.set_xlim(-plane_margin(bmax), bmax)
    ax.set_ylim(-plane_margin(smax), smax)
    ax.set_xlabel(BETA_LABEL)
    ax.set_ylabel(SIGMA_LABEL)
    ax.set_title("Regions (eq. 6, 10)" + (f", delay d = {result.delay}" if result.delay else ""), fontsize=9)
    if legend:
        handles: list[Artist] = [
            Patch(
                facecolor=REGION_COLORS[k],
                edgecolor=REGION_HATCH[k][1] if k in REGION_HATCH else "0.5",
                hatch=REGION_HATCH[k][0] if k in REGION_HATCH else None,
                label=f"{k}: {CriterionStatus.of_region(k).message.split(':')[0]}",
            )
            for k in "abcde"
        ]
        lines, _labels = ax.get_legend_handles_labels()
        panels_legend([ax], handles + lines, below=True, ncols=1)  # below: a figure as narrow as its plane
    return ax
