"""Stability maps: the simulated outcome per (β, σ), one panel per impact speed (paper Fig. 4)."""

from __future__ import annotations

import math

import matplotlib
import matplotlib.layout_engine
import matplotlib.lines
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
from matplotlib.artist import Artist
from matplotlib.patches import Patch

from ...results.status import SimulationOutcome
from .style import (
    BETA_LABEL,
    OUTCOME_COLORS,
    OUTCOME_LABELS,
    POINT_STYLE,
    SIGMA_LABEL,
    SMALL_FONTSIZE,
    outcome_cmap,
    panels_legend,
    physical_map_axes,
)


def _outcome_handles(left: bool = False) -> list[Artist]:
    """One colour patch per outcome class, every class (also those absent from the figure); ``left`` (a one-sided
    wall's) only when ``left``."""
    return [
        Patch(facecolor=OUTCOME_COLORS[k], edgecolor="0.4", label=OUTCOME_LABELS[k])
        for k in ("rest", "chatter", "oscillating", "unstable", "undecided") + (("left",) if left else ())
    ]


def _speed_text(xi_dot: float, device) -> str:
    if device is None:
        return f"ξ'0 = {xi_dot:.3g} ticks/sample"
    return f"{device.velocity(xi_dot):.3g} {device.units['velocity']} (ξ'0 = {xi_dot:.3g})"


def _map_critical_line(
    ax, smap, v: float, bb: np.ndarray, ylim: tuple[float, float]
) -> tuple[float, float, str] | None:
    """Draw the critical line of one map panel (``smap.critical_line(v)``: eq. 10, or eq. 10 extended to the map's
    wall); with an amplifier lag no criterion covers the loop and nothing is drawn (None). Returns the corner
    (β₀, σ₀) and where the line lies: ``"in view"``, ``"above"`` or ``"below"`` the panel (``ylim``)."""
    line = smap.critical_line(v)
    if line is None:
        return None
    sig = np.asarray(line.sigma(bb), dtype=float)
    ax.plot(bb, sig, "--", color="#b2182b", lw=1.3)
    ax.axvline(line.beta0, color="#2166ac", ls="-.", lw=1.0)
    if smap.quantize:
        ax.axhline(line.sigma0, color="#2166ac", ls="-.", lw=1.0)
    seen = bool(np.any((sig >= ylim[0]) & (sig <= ylim[1])))
    return line.beta0, line.sigma0, "in view" if seen else ("above" if np.all(sig > ylim[1]) else "below")


def _map_line_handles(smap, drawn: list, extent: tuple[float, float, float, float]) -> list[Artist]:
    """Legend entries of the map's criterion lines: a line only for what lies inside the panels; what lies
    outside them is said in words (which side), without a line."""
    if all(d is None for d in drawn):
        why = "one-sided wall" if smap.wall.one_sided else ("amplifier lag" if smap.wall.lag else "not covered")
        return [matplotlib.lines.Line2D([], [], ls="none", label=f"no criterion line: {why}")]
    spring = smap.wall.is_spring
    name = "critical line (eq. 10)" if spring else "critical line, eq. 10 with the wall"
    wheres = [d[2] for d in drawn if d is not None]
    panels = "the panels" if len(drawn) > 1 else "the panel"
    out: list[Artist] = []
    if "in view" in wheres:
        out.append(matplotlib.lines.Line2D([], [], color="#b2182b", ls="--", label=name))
    else:
        side = "above" if all(w == "above" for w in wheres) else "outside"
        out.append(matplotlib.lines.Line2D([], [], ls="none", label=f"{name}: {side} {panels}"))
    b0, s0, _w = next(d for d in drawn if d is not None)
    x0, x1, y0, y1 = extent
    rows = [(_boundary_name("β", b0, smap.delay, spring), b0, x0, x1, "left of", "right of")]
    if smap.quantize:
        rows.append((_boundary_name("σ", s0, 0, spring), s0, y0, y1, "below", "above"))
    shown = [r[0] for r in rows if r[2] <= r[1] <= r[3]]
    if shown:
        label = f"region boundar{'ies' if len(shown) > 1 else 'y'} {' and '.join(shown)}"
        out.append(matplotlib.lines.Line2D([], [], color="#2166ac", ls="-.", label=label))
    for name, value, lo, hi, before, after in rows:  # each boundary off the panels: its own entry, no line
        if not lo <= value <= hi:
            side = before if value < lo else after
            out.append(matplotlib.lines.Line2D([], [], ls="none", label=f"region boundary {name}: {side} {panels}"))
    return out


def _boundary_name(symbol: str, value: float, delay: int, spring: bool) -> str:
    """A map's region boundary in words: ``"β = ½"``, ``"β = ½ + d = 1.5"`` (a number only where the symbol is not
    one already) or, with a controller, ``"β = β₀ = 0.31"``."""
    if not spring:
        return f"{symbol} = {symbol}₀ = {value:.3g}"
    return f"{symbol} = ½ + d = {value:.3g}" if delay else f"{symbol} = ½"


def _uniform_note(ax, outcome: np.ndarray) -> None:
    """Say it in the panel when every grid point has one outcome (an all-dark panel reads as a rendering fault); at
    the bottom, clear of the operating point's label, which points to the panel's middle."""
    codes = np.unique(outcome)
    if codes.size != 1:
        return
    what = OUTCOME_LABELS[list(SimulationOutcome)[int(codes[0])].value]
    ax.text(0.5, 0.04, f"all {outcome.size} grid points: {what}", transform=ax.transAxes, ha="center", va="bottom",
            fontsize=SMALL_FONTSIZE, bbox={"boxstyle": "round,pad=0.3", "fc": "white", "ec": "0.4", "alpha": 0.9})  # fmt: skip


def stability_map_plot(smap, axes=None, *, titles: bool = True, device=None, stiffness=None, point=None):
    """Simulated outcome per (β, σ) for each initial speed (paper Fig. 4).

    As in the paper, white: came to rest; light: persisting oscillation, in
    two shades (lightest: chatter below one tick, darker: oscillating, one
    tick or more); dark: unstable; orange: undecided (the run was too short,
    :mod:`dfa.analysis.simulation`). The critical line of each speed
    (:class:`dfa.analysis.criterion.CriticalLine` with the map's delay d) is dashed, the
    region boundaries β = ½ + d, σ = ½ dash-dot; with a controller, the line of the
    criterion extended to it (corner β₀, σ₀), or none with an amplifier lag. The legend
    (right of one panel, below several) lists every outcome class, present or not, the lines
    and the operating point: a line outside the panels is named with its side, without a line.
    A panel whose grid points all have one outcome says so in its middle.

    Parameters
    ----------
    smap : StabilityMap
    axes : sequence of Axes, optional
        One per speed.
    titles : bool
        A title per panel with μ and the speed (default True).
    device : Device, optional
        With ``stiffness``: speeds in physical units in the titles and secondary axes
        b = βKT (N·s/m; rotary N·m·s/rad) and c = σKΔ (N; N·m).
    stiffness : float, optional
        K in N/m (rotary N·m/rad) for the secondary axes.
    point : (float, float), optional
        The operating point (β, σ), marked in every panel.
    """
    n = len(smap.xi_dots)
    if axes is None:
        cols = min(n, 2)
        rows = int(math.ceil(n / cols))
        size = (4.0 * cols + (3.0 if n == 1 else 0.0), 3.8 * rows + (1.3 if n > 1 else 0.0))  # the legend beside one
        fig, axs = plt.subplots(rows, cols, figsize=size, constrained_layout=True, squeeze=False)  # panel, else below
        axes = list(axs.ravel())
        for extra in axes[n:]:
            extra.remove()
        axes = axes[:n]
    b, s = smap.beta, smap.sigma
    db = (b[1] - b[0]) / 2
    ds = (s[1] - s[0]) / 2
    extent = (b[0] - db, b[-1] + db, s[0] - ds, s[-1] + ds)
    cmap = outcome_cmap()
    physical = device is not None and stiffness is not None
    drawn: list[tuple[float, float, str] | None] = []
    for k, ax in enumerate(axes):
        ax.imshow(
            smap.outcome[k],
            origin="lower",
            extent=extent,
            aspect="auto",
            cmap=cmap,
            vmin=-0.5,
            vmax=cmap.N - 0.5,
            interpolation="nearest",
        )
        v = smap.xi_dots[k]
        bb = np.linspace(b[0], b[-1], 200)
        drawn.append(_map_critical_line(ax, smap, v, bb, (extent[2], extent[3])))
        _uniform_note(ax, smap.outcome[k])
        if point is not None:
            ax.plot([point[0]], [point[1]], clip_on=False, **POINT_STYLE)
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_xlabel(BETA_LABEL)
        ax.set_ylabel(SIGMA_LABEL)
        if physical:
            physical_map_axes(ax, device, float(stiffness))
        if titles:
            what = "preload ≡" if smap.preload else "impact"
            head, tail = f"μ = {smap.mu:.4g}", f"{what} {_speed_text(v, device)}"
            tail += f", delay {smap.delay}" if smap.delay else ""
            ax.set_title(head + (",\n" if len(head + tail) > 42 else ", ") + tail, fontsize=9)  # within the panel
    handles = _outcome_handles(bool(smap.wall.one_sided)) + _map_line_handles(smap, drawn, extent)
    if point is not None:
        handles.append(matplotlib.lines.Line2D([], [], label="operating point", **POINT_STYLE))
    panels_legend(axes, handles, below=len(axes) > 1)
    return axes
