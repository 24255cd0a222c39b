"""Amplitude and frequency of the small stable and large unstable limit-cycle families (paper Fig. 7)."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .style import BETA_LABEL, LEGEND_FONTSIZE, SIGMA_LABEL, SMALL_FONTSIZE, physical_map_axes


def contour_plot(maps, axes=None, *, device=None, stiffness=None):
    """Amplitude and frequency of the small stable and large unstable families (paper Fig. 7).

    Left: small stable cycles, amplitude filled, frequency as labelled white
    lines. Right: the smallest unstable cycle with the exact D (filled, log
    levels) with the paper's closed form eq. 44-45 overlaid as dashed contours
    of the same levels; its frequency is nearly constant and is printed.

    Parameters
    ----------
    maps : ContourMaps
    axes : pair of Axes, optional
    device : Device, optional
        With ``stiffness``: secondary axes b = βKT (N·s/m; rotary N·m·s/rad) and c = σKΔ (N; N·m),
        as on :func:`stability_map_plot`.
    stiffness : float, optional
        K in N/m (rotary N·m/rad) for the secondary axes.
    """
    from matplotlib.colors import BoundaryNorm

    if axes is None:
        _fig, axes = plt.subplots(1, 2, figsize=(10.5, 4.2), constrained_layout=True)
    bb, ss = np.meshgrid(maps.beta, maps.sigma)
    ax = axes[0]
    small = np.isfinite(maps.small_amplitude)
    if small.any():
        small_fill = ax.contourf(bb, ss, maps.small_amplitude, levels=np.linspace(0, 1, 11), cmap="viridis")
        plt.colorbar(small_fill, ax=ax).set_label("amplitude M (encoder ticks)")
        cs = ax.contour(bb, ss, maps.small_frequency, levels=6, colors="w", linewidths=0.7)
        ax.clabel(cs, fontsize=SMALL_FONTSIZE, fmt="%.2f")
    ax.set_title(f"μ = {maps.mu:g}: small stable cycles (M < 1, eq. 42-43)\nwhite: ω (rad/sample)", fontsize=9)
    ax = axes[1]
    nice = np.array([1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200, 300, 500, 1000])
    finite = maps.large_amplitude[np.isfinite(maps.large_amplitude)]
    if finite.size:
        levels = nice[(nice >= 1) & (nice <= max(2.0, finite.max()))]
        norm = BoundaryNorm(levels, plt.get_cmap("viridis").N, extend="max")
        cf = ax.contourf(bb, ss, maps.large_amplitude, levels=levels, cmap="viridis", norm=norm, extend="max")
        plt.colorbar(cf, ax=ax).set_label("amplitude M_u (encoder ticks)")
        if np.isfinite(maps.large_amplitude_closed).any():
            ax.contour(bb, ss, maps.large_amplitude_closed, levels=levels, colors="w", linewidths=0.8, linestyles="--")
        ax.plot([], [], "w--", label="eq. 45 (D = 1), same levels")
        ax.legend(fontsize=LEGEND_FONTSIZE, loc="upper right", facecolor="0.5", labelcolor="w")
    if np.isfinite(maps.large_frequency).any():
        ax.text(
            0.52,
            0.80,
            f"exact: ω from {np.nanmin(maps.large_frequency):.4f}\nto {np.nanmax(maps.large_frequency):.4f} rad/sample\n"
            f"eq. 44: ω = {np.nanmax(maps.large_frequency_closed):.5f}",
            transform=ax.transAxes,
            fontsize=SMALL_FONTSIZE,
            color="k",
        )
    ax.set_title(f"μ = {maps.mu:g}: large unstable cycles (exact D, eq. 41)", fontsize=9)
    beta0, sigma0 = maps.corner  # the maps' loop has no delay: region boundaries β = ½, σ = ½ (eq. 10)
    for ax in axes:
        ax.axvline(beta0, color="k", ls="-.", lw=0.8)
        ax.axhline(sigma0, color="k", ls="-.", lw=0.8)
        ax.set_xlabel(BETA_LABEL)
        ax.set_ylabel(SIGMA_LABEL)
        ax.set_xlim(maps.beta[0], maps.beta[-1])
        ax.set_ylim(maps.sigma[0], maps.sigma[-1])
    if small.any():  # the small family needs σ < ½: show the band where it exists, not an empty panel
        top = float(ss[small].max())
        axes[0].set_ylim(maps.sigma[0], min(maps.sigma[-1], max(1.15 * top, 0.55)))
    for ax in axes:
        _drop_edge_labels(ax)
        if device is not None and stiffness is not None:
            physical_map_axes(ax, device, float(stiffness))
    fill = _band_colour(small_fill, maps.beta, maps.sigma, maps.small_amplitude) if small.any() else None
    _clear_labels_of_lines(axes[0], beta0, sigma0, fill)
    return axes


def _drop_edge_labels(ax, margin: float = 0.05) -> None:
    """Remove contour labels centred within ``margin`` (axes fraction) of an edge: they would be clipped."""
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    labels = [t for c in ax.collections for t in getattr(c, "labelTexts", [])]
    for t in labels:
        x, y = t.get_position()
        fx, fy = (x - x0) / (x1 - x0), (y - y0) / (y1 - y0)
        if not (margin < fx < 1 - margin and margin < fy < 1 - margin):
            t.remove()


def _clear_labels_of_lines(ax, beta0: float, sigma0: float, fill=None) -> None:
    """Contour labels that the region boundaries β = β₀, σ = σ₀ would cross (Fig. 7's "2.80" on σ = ½) get a box
    in the colour of the fill under them (``fill(β, σ)``), drawn over the line: the number reads whole and the
    line resumes beyond it. Without ``fill`` such a label is removed. Measured on the laid-out figure (one draw)."""
    labels = [t for c in ax.collections for t in getattr(c, "labelTexts", []) if t.axes is ax]
    if not labels:
        return
    ax.figure.canvas.draw()  # the layout (colour bars, constrained layout) fixes the label boxes in pixels
    px, py = ax.transData.transform((beta0, sigma0))
    pad = 1.5  # pixels: the dash-dot line's half width and a little air
    for t in labels:
        box = t.get_window_extent()
        if not (box.y0 - pad <= py <= box.y1 + pad or box.x0 - pad <= px <= box.x1 + pad):
            continue
        if fill is None:
            t.remove()
            continue
        t.set_bbox({"boxstyle": "square,pad=0.1", "fc": fill(*t.get_position()), "ec": "none"})
        t.set_zorder(3)  # over the boundary lines (zorder 2)


def _band_colour(cf, beta: np.ndarray, sigma: np.ndarray, values: np.ndarray):
    """The colour a filled contour ``cf`` of ``values`` (rows σ, columns β) paints at a point (white outside it)."""
    levels = np.asarray(cf.levels, dtype=float)

    def colour(x: float, y: float):
        v = values[int(np.argmin(np.abs(sigma - y))), int(np.argmin(np.abs(beta - x)))]
        if not np.isfinite(v):
            return "white"
        k = int(np.clip(np.searchsorted(levels, v) - 1, 0, levels.size - 2))
        return cf.cmap(cf.norm(0.5 * (levels[k] + levels[k + 1])))

    return colour
