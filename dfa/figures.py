"""Figures of dfa: the only module that imports matplotlib.

Every function takes a result object and an optional ``ax`` (or ``axes``)
and returns the axes it drew on, in the style of python-control's ``*_plot``
functions. Axis labels carry units: dimensionless quantities are marked (–),
positions are in encoder ticks, time in samples (or seconds when a sample
period is given). Given a device (``device=``), trajectories get a second axis
in m (rotary rad) and map panels axes of damping b and Coulomb friction c at K.
Legends sit beside the axes (below a row of panels), never over the data; the operating point has one
style (``POINT_STYLE``) and each outcome class one colour in every figure.

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import dfa
>>> from dfa.figures import regions_plot
>>> ax = regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
>>> ax.get_xlabel()
'β = b/(K T) (–)'
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import matplotlib
import matplotlib.layout_engine
import matplotlib.lines
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
from matplotlib.artist import Artist
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from ._io import FIGURE_SUFFIXES, atomic_open, check_output_file
from .formatting import number
from .results.status import CriterionStatus, SimulationOutcome

__all__ = [
    "regions_plot",
    "stability_map_plot",
    "trajectory_plot",
    "contour_plot",
    "nyquist_plot",
    "stiffness_plot",
    "stiffness_speed_plot",
    "cycle_error_plot",
    "critical_speed_plot",
    "plot_zwidth",
    "plot_identification",
    "passivity_plot",
    "nyquist_needs_zoom",
    "save_figure",
    "FIGURE_SUFFIXES",
    "ZWIDTH_COLORS",
    "REGION_COLORS",
    "REGION_HATCH",
    "BETA_LABEL",
    "SIGMA_LABEL",
]

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
_OUTCOME_LABELS = {
    "rest": "rest (came to rest)",
    "chatter": "chatter (persisting, < 1 tick)",
    "oscillating": "oscillating (persisting, >= 1 tick)",
    "unstable": "unstable (diverged)",
    "undecided": "undecided (run too short)",
    "left": "left (a one-sided wall, for good)",
    "saturated": "saturated (held by the force limit)",
    "end_stop": "end stop (past the device's travel)",
}


def save_figure(figure: Any, path: str | os.PathLike, *, dpi: float = 120, tight: bool = True) -> Path:
    """Write a figure to ``path`` as PNG, PDF or SVG by its suffix (:data:`FIGURE_SUFFIXES`), atomically.

    Parameters
    ----------
    figure : matplotlib.figure.Figure or matplotlib.axes.Axes
        The figure, or an Axes of it (as the ``*_plot`` functions return).
    path : str or os.PathLike
        The file; its name must end in ``.png``, ``.pdf`` or ``.svg`` (anything else is refused
        before a byte is written), and its folder must exist.
    dpi : float, optional
        Resolution of a PNG (and of images inside a PDF or SVG), dots per inch (default 120).
    tight : bool, optional
        Crop the page to the drawn artists, legends beside the axes included (default True).

    Returns
    -------
    pathlib.Path
        The file written (a PDF or SVG without a creation date).

    Raises
    ------
    DFAValueError
        For another suffix, a folder, or a folder that does not exist.

    Examples
    --------
    >>> import matplotlib, os, tempfile
    >>> matplotlib.use("Agg")
    >>> import dfa
    >>> ax = regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
    >>> d = tempfile.mkdtemp()
    >>> [save_figure(ax, os.path.join(d, "regions" + s)).name for s in FIGURE_SUFFIXES]
    ['regions.png', 'regions.pdf', 'regions.svg']
    >>> try:
    ...     save_figure(ax, os.path.join(d, "regions.jpg"))
    ... except dfa.DFAValueError as e:
    ...     print(str(e).split(": ", 1)[1])
    the file name must end in .png, .pdf or .svg, not .jpg; give path ...regions.png
    """
    fig = getattr(figure, "figure", figure)  # an Axes knows its figure; a Figure is its own
    target = check_output_file("path", os.fspath(path), FIGURE_SUFFIXES)
    fmt = next(s for s in FIGURE_SUFFIXES if target.endswith(s))[1:]
    metadata = {"pdf": {"CreationDate": None}, "svg": {"Date": None}}.get(fmt)
    with atomic_open(target, "wb") as fh:
        fig.savefig(fh, format=fmt, dpi=dpi, bbox_inches="tight" if tight else None, metadata=metadata)
    return Path(target)


def _outcome_cmap() -> ListedColormap:
    return ListedColormap([OUTCOME_COLORS[o.value] for o in SimulationOutcome])  # indexed by the outcome code


def _axes(ax=None, figsize=(5.0, 4.0)):
    if ax is None:
        _fig, ax = plt.subplots(figsize=figsize, constrained_layout=True)
    return ax


#: One style for the operating point (design point) in every (β, σ) figure.
POINT_STYLE: dict[str, Any] = dict(marker="o", color="#b2182b", ms=8, mec="k", mew=1.0, ls="none", zorder=5)
#: Styles of further critical lines (regions plot), distinct from the dashed line of the operating point.
_EXTRA_LINES = (
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


def _legend_outside(ax, handles=None, fontsize: float = LEGEND_FONTSIZE, *, wrap: int | None = None) -> None:
    """The legend to the right of the axes, never over the data; ``wrap``: labels broken into lines of at most
    that many characters, so that a legend of long labels stays narrow beside its plot."""
    kw = dict(fontsize=fontsize, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, framealpha=0.9)
    if handles is None:
        handles, _labels = ax.get_legend_handles_labels()
    labels = [h.get_label() for h in handles]
    ax.legend(handles, labels if wrap is None else [_wrap_label(t, wrap) for t in labels], **kw)


def _wrap_label(text: str, width: int) -> str:
    """``text`` in lines of at most ``width`` characters where it can be, broken only outside parentheses: after
    ": " or ", ", or before " (" (a value stays with its unit, a parenthesis whole).

    Examples
    --------
    >>> print(_wrap_label("exact linear bound (no encoder, no friction): 60 N/m (= A–O, C–S)", 32))
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


def _margin(hi: float) -> float:
    """A margin left of / below 0 so that a point at β ≈ 0 or σ ≈ 0 is drawn whole (grey: outside the plane)."""
    return 0.03 * hi


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
    ax = _axes(ax, figsize=(5.6, 6.9) if legend else (5.6, 4.4))
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
    for v, style in zip(xi_dots, _EXTRA_LINES * (1 + len(xi_dots) // len(_EXTRA_LINES)), strict=False):
        ax.plot(b, line.at_speed(v).sigma(b), label=f"ξ'0 = {v:g}", **style)
    ax.plot([result.beta], [result.sigma], label=f"operating point (region {result.region})", **POINT_STYLE)
    ax.set_xlim(-_margin(bmax), bmax)
    ax.set_ylim(-_margin(smax), smax)
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
        _panels_legend([ax], handles + lines, below=True, ncols=1)  # below: a figure as narrow as its plane
    return ax


def _outcome_handles(left: bool = False) -> list[Artist]:
    """One colour patch per outcome class, every class (also those absent from the figure); ``left`` (a one-sided
    wall's) only when ``left``."""
    return [
        Patch(facecolor=OUTCOME_COLORS[k], edgecolor="0.4", label=_OUTCOME_LABELS[k])
        for k in ("rest", "chatter", "oscillating", "unstable", "undecided") + (("left",) if left else ())
    ]


def _physical_map_axes(ax, device, stiffness: float) -> None:
    """Secondary axes of a (β, σ) panel at the device's K: damping b = βKT and Coulomb friction c = σKΔ (Table 1)."""
    u = device.units
    kt, kd = stiffness * device.period, stiffness * device.resolution
    size = ax.yaxis.label.get_fontsize()  # as large as the β and σ axes' labels: as readable
    top = ax.secondary_xaxis("top", functions=(lambda x: x * kt, lambda x: x / kt))
    top.set_xlabel(f"damping b at K = {stiffness:.5g} {u['stiffness']} ({u['damping']})", fontsize=size)
    right = ax.secondary_yaxis("right", functions=(lambda y: y * kd, lambda y: y / kd))
    right.set_ylabel(f"Coulomb friction c ({u['coulomb']})", fontsize=size)


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
    what = _OUTCOME_LABELS[list(SimulationOutcome)[int(codes[0])].value]
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
    cmap = _outcome_cmap()
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
            _physical_map_axes(ax, device, float(stiffness))
        if titles:
            what = "preload ≡" if smap.preload else "impact"
            head, tail = f"μ = {smap.mu:.4g}", f"{what} {_speed_text(v, device)}"
            tail += f", delay {smap.delay}" if smap.delay else ""
            ax.set_title(head + (",\n" if len(head + tail) > 42 else ", ") + tail, fontsize=9)  # within the panel
    handles = _outcome_handles(bool(smap.wall.one_sided)) + _map_line_handles(smap, drawn, extent)
    if point is not None:
        handles.append(matplotlib.lines.Line2D([], [], label="operating point", **POINT_STYLE))
    _panels_legend(axes, handles, below=len(axes) > 1)
    return axes


def _panels_legend(axes, handles: list[Artist], *, below: bool, ncols: int = 2) -> None:
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
    _legend_outside(ax, handles)
    if ax.child_axes:  # a secondary axis' labels sit where the legend would go: start past them
        renderer = fig.canvas.get_renderer()
        right = max(c.get_tightbbox(renderer).x1 for c in ax.child_axes)
        box = ax.get_window_extent(renderer)
        ax.get_legend().set_bbox_to_anchor(((right - box.x0) / box.width + 0.02, 1.0))


def _scaled_unit(base: str, largest: float) -> tuple[float, str]:
    """(factor, unit) so that ``value × factor`` of a quantity in ``base`` (m or rad) reads in m/mm/µm (rad/mrad/µrad)."""
    for factor, prefix in ((1.0, ""), (1e3, "m"), (1e6, "µ")):
        if largest * factor >= 1.0:
            return factor, prefix + base
    return 1e9, "n" + base


def _shown_samples(sim, n: int) -> int:
    """Samples worth showing: a run that came to rest up to about four times its settling time (>= 20 samples),
    a run stopped early (diverged) up to its last integrated sample."""
    if getattr(sim, "rest_sample", None) is not None:
        return min(n, max(20, 4 * int(sim.rest_sample)) + 1)
    run = getattr(sim, "samples_run", None)
    return min(n, int(run) + 1) if run is not None and run > 0 else n


def trajectory_plot(
    sim, ax=None, *, period: float | None = None, max_samples: int | None = None, device=None, window: bool = True
):
    """Displacement in ticks against time with ±1 tick marked (paper Fig. 5, right).

    Parameters
    ----------
    sim : SimulationResult
        Must have been recorded (``record=True``).
    period : float, optional
        Sample period T in s: the time axis is then in seconds.
    max_samples : int, optional
        Draw only the first samples.
    device : Device, optional
        Time in s (its period) and a secondary axis with the displacement in m (rotary rad), scaled to mm/µm.
    window : bool
        Default True: a run that came to rest is shown up to about four times its settling time, so that its
        motion fills the axis, a diverged run up to where it stopped; False: the whole run.
    """
    ax = _axes(ax, figsize=(6.0, 3.2))
    if sim.xi is None:
        raise ValueError("sim has no trajectory: run dfa.simulate(..., record=True)")
    if device is not None:
        period = device.period
    n = sim.xi.size if max_samples is None else min(sim.xi.size, max_samples + 1)
    if window:
        n = _shown_samples(sim, n)
    t = np.arange(n) * (period if period else 1.0)
    ax.plot(t, sim.xi[:n], lw=0.9, color="#2166ac")
    for y in (-1.0, 1.0):
        ax.axhline(y, color="0.4", ls="--", lw=0.8)
    ax.set_xlabel("time (s)" if period else "time (samples)")
    ax.set_ylabel("displacement ξ (encoder ticks)")
    if device is not None:
        res = device.resolution
        finite = np.abs(sim.xi[:n][np.isfinite(sim.xi[:n])])
        factor, unit = _scaled_unit(device.units["position"], res * max(1.0, float(finite.max()) if finite.size else 1))
        sec = ax.secondary_yaxis("right", functions=(lambda y: y * res * factor, lambda x: x / (res * factor)))
        sec.set_ylabel(f"displacement ({unit})")
    ax.set_title(f"μ = {sim.mu:.4g}, β = {sim.beta:.3g}, σ = {sim.sigma:.3g}: {sim.outcome}", fontsize=9)
    ax.set_xlim(t[0], t[-1] if n > 1 else 1)
    return ax


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
            _physical_map_axes(ax, device, float(stiffness))
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


#: Names of the loop models in titles and captions (:func:`dfa.analysis.loop.loop_response`).
MODEL_NAMES = {"half-delay": "half-sample delay", "zoh": "exact ZOH", "pade": "Padé ZOH"}


def _cycle_points(nyq, cycles) -> list[tuple[complex, bool, float]]:
    """(point L(jω; M) of the cycle, stable, M) for each cycle, with the Nyquist data's loop model."""
    if cycles is None:
        return []
    return [(nyq.loop_at(c.frequency, c.amplitude), bool(c.stable), float(c.amplitude)) for c in cycles.cycles]


def _nyquist_limits(nyq, pts, room: bool = False) -> tuple[tuple[float, float], tuple[float, float]]:
    """Limits around the data that matter: the critical locus, every cycle, the origin (x, 15 % margin) and the
    curves within that x range (y, at most one x range from the real axis, at least a tenth of it); ``room``:
    the data in the lower half only."""
    loc = nyq.locus[np.isfinite(nyq.locus)]
    xs = np.concatenate([loc.real, [p.real for p, _s, _m in pts], [0.0]])
    pad = 0.15 * max(xs.max() - xs.min(), 1e-9)
    x0, x1 = xs.min() - pad, xs.max() + pad
    c = np.asarray(nyq.curves).ravel()
    inside = c[np.isfinite(c) & (c.real >= x0) & (c.real <= x1)]
    reach = x1 - x0  # the curves' far branches (resonance, high frequency): not beyond one x range of the real axis
    near = inside.imag[np.abs(inside.imag) <= reach]
    ys = np.concatenate([near, [p.imag for p, _s, _m in pts], [0.0]])
    span = max(ys.max() - ys.min(), 0.1 * (x1 - x0))
    y0, y1 = ys.min() - 0.1 * span, ys.max() + 0.1 * span
    if room:
        y1 = y0 + 2.0 * (y1 - y0)
    return (x0, x1), (y0, y1)


def _nyquist_draw(ax, nyq, pts, *, labels: bool) -> None:
    for amp, curve in zip(nyq.amplitudes, nyq.curves, strict=False):
        lab = "L(jω)" if np.isnan(amp) else f"L(jω; M = {amp:.3g} ticks)"
        ax.plot(curve.real, curve.imag, lw=1.1, label=lab if labels else None)
    rng = f"M in [{nyq.locus_amplitude[0]:.2g}, {nyq.locus_amplitude[-1]:.2g}] ticks"
    ax.plot(nyq.locus.real, np.zeros_like(nyq.locus.real), color="#b2182b", lw=3, alpha=0.6,
            label=f"−1/D(M), {rng}" if labels else None)  # fmt: skip
    for pt, stable, _m in pts:
        ax.plot([pt.real], [pt.imag], "o", mfc="k" if stable else "w", mec="k", ms=6, zorder=5)
    ax.axhline(0, color="0.6", lw=0.5)
    ax.axvline(0, color="0.6", lw=0.5)


def nyquist_needs_zoom(nyq, cycles) -> bool:
    """True when the cycles need an inset: a cycle below one tick, or several crossings within 10 % of the axis."""
    pts = _cycle_points(nyq, cycles)
    if not pts:
        return False
    if min(m for _p, _s, m in pts) < 1.0:
        return True
    (x0, x1), _y = _nyquist_limits(nyq, pts)
    xs = [p.real for p, _s, _m in pts]
    return len(xs) > 1 and (max(xs) - min(xs)) < 0.1 * (x1 - x0)


def nyquist_plot(nyq, ax=None, *, cycles=None, controller: str | None = None):
    """Nyquist plot of the loop L(jω; M) against the critical locus −1/D(M), cycles marked (paper Fig. 6).

    The axes are scaled to the locus, the cycles and the origin; when a cycle is below one tick or several
    crossings crowd within 10 % of the axis, an inset (upper half, above the data) zooms on them. The title names the loop model.

    Parameters
    ----------
    nyq : NyquistLocusResponse
    cycles : LimitCycleResult, optional
        Cycles to mark (stable: filled circle, unstable: open circle), computed with the same loop model.
    controller : str, optional
        The loop's wall controller in words (e.g. ``"B = 1 N·s/m, f_c = 200 Hz, d = 1"``), named in the
        title as "… loop with {controller}" in place of the delay (default: the title names the delay only).
    """
    ax = _axes(ax, figsize=(8.4, 4.6))
    pts = _cycle_points(nyq, cycles)
    _nyquist_draw(ax, nyq, pts, labels=True)
    if cycles is not None:
        for stable, name in ((True, "stable cycle"), (False, "unstable cycle")):
            if any(s == stable for _p, s, _m in pts):
                ax.plot([], [], "o", mfc="k" if stable else "w", mec="k", label=name)
        if not pts:
            ax.plot([], [], " ", label="no limit cycle predicted")
    xlim, ylim = _nyquist_limits(nyq, pts)
    window = _inset_window(nyq, pts, xlim, ylim) if nyquist_needs_zoom(nyq, cycles) else None
    if window is not None:  # the data in the lower half, the inset above it
        ylim = (ylim[0], ylim[0] + 2.0 * (ylim[1] - ylim[0]))
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)
    ax.set_xlabel("Re L (force ticks per position tick)")
    ax.set_ylabel("Im L (force ticks per position tick)")
    dl = f" with {controller}" if controller else (f", delay {nyq.delay}" if nyq.delay else "")
    ax.set_title(f"Nyquist, {MODEL_NAMES.get(nyq.model, nyq.model)} loop{dl}", fontsize=9)
    if window is not None:
        _nyquist_inset(ax, nyq, pts, window)
    _legend_outside(ax)
    return ax


#: Largest share of the main axes' data range (each direction) an inset may show: beyond it, it is no zoom.
_MAX_ZOOM_SHARE = 0.45


def _inset_window(nyq, pts, xlim, ylim) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The region the Nyquist inset shows: around every crossing, or only the cycles below one tick when the
    crossings span too much, with the curves of those cycles near them; inside the main axes' data range
    (``xlim``, ``ylim``) and at most :data:`_MAX_ZOOM_SHARE` of it in each direction. None when even the cycles
    below one tick span more (no zoom to show)."""
    (x0, x1), (y0, y1) = xlim, ylim
    wx, wy = x1 - x0, y1 - y0

    def half_width(group) -> float:
        xs = [p.real for p, _s, _m in group]
        return max(0.65 * (max(xs) - min(xs)), 0.04 * wx)

    targets = pts if 2.0 * half_width(pts) <= _MAX_ZOOM_SHARE * wx else [p for p in pts if p[2] < 1.0]
    if not targets or 2.0 * half_width(targets) > _MAX_ZOOM_SHARE * wx:
        return None
    hx = half_width(targets)
    xs = np.array([p.real for p, _s, _m in targets])
    ys = np.array([p.imag for p, _s, _m in targets])
    cx = float(np.clip((xs.min() + xs.max()) / 2, x0 + hx, x1 - hx))
    cy = (ys.min() + ys.max()) / 2
    amps = np.asarray(nyq.amplitudes, dtype=float)
    near = [0.65 * (ys.max() - ys.min()), 0.04 * wy]
    for _p, _s, m in targets:  # the target cycles' own curves within the window's x range: their loop near the cycle
        if amps.size and np.isfinite(amps).any():
            curve = np.asarray(nyq.curves[int(np.nanargmin(np.abs(amps - m)))])
            inside = curve[np.isfinite(curve) & (np.abs(curve.real - cx) <= hx)]
            near.append(1.1 * float(np.abs(inside.imag - cy).max()) if inside.size else 0.0)
    hy = min(max(near), _MAX_ZOOM_SHARE * wy / 2.0)
    cy = float(np.clip(cy, y0 + hy, y1 - hy))
    return (cx - hx, cx + hx), (cy - hy, cy + hy)


def _nyquist_inset(ax, nyq, pts, window) -> None:
    """Zoom on ``window`` (:func:`_inset_window`, inside the main axes) in an inset at the upper left of the axes,
    linked to the region it shows."""
    ins = ax.inset_axes([0.12, 0.56, 0.4, 0.36])
    _nyquist_draw(ins, nyq, pts, labels=False)
    ins.set_xlim(*window[0])
    ins.set_ylim(*window[1])
    ins.tick_params(labelsize=SMALL_FONTSIZE - 1)
    ins.set_title("zoom on the cycles", fontsize=SMALL_FONTSIZE)
    ax.indicate_inset_zoom(ins, edgecolor="0.3")


#: One style per closed-form stiffness bound (stiffness plot, stiffness-speed chart): coinciding lines stay
#: visible because they differ in width, dash and colour (the wide pale line under the thin ones).
_BOUND_STYLES = {
    "abbott_okamura": dict(color="#c2a5cf", lw=6.0, alpha=0.8, ls="-"),
    "colgate": dict(color="#762a83", lw=1.6, ls="--"),
    "linear": dict(color="k", lw=1.1, ls=(0, (1, 1.5))),
    "static": dict(color="#4d9221", lw=1.3, ls="-."),
}


def _bounds(k_static: float, k_colgate: float, k_ao: float, k_linear: float, delay: int):
    """(key, value, name) of the closed-form bounds (eq. 8, 9 and the exact linear bound), widest line first."""
    cs = "2b/T" if delay == 0 else f"b/(T(½ + {delay}))"
    return [
        ("abbott_okamura", k_ao, f"Abbott–Okamura min({cs}, 2c/Δ)"),
        ("colgate", k_colgate, f"Colgate–Schenkel {cs}"),
        ("linear", k_linear, "exact linear bound (no encoder, no friction)"),
        ("static", k_static, "static limit 2c/Δ (eq. 9)"),
    ]


def _bound_lines(ax, bounds, unit: str, *, vertical: bool) -> None:
    """Draw each bound as a labelled line; a label names the bounds it coincides with (equal to 0.1 %)."""
    short = {"abbott_okamura": "A–O", "colgate": "C–S", "linear": "linear", "static": "2c/Δ"}
    for key, k, name in bounds:
        if k is None or not (k > 0 and np.isfinite(k)):  # None: a bound the wall does not have (the spring's)
            continue
        same = [short[o] for o, ko, _n in bounds if o != key and ko is not None and ko > 0 and abs(ko - k) <= 1e-3 * k]
        label = f"{name}: {number(k)} {unit}" + (f" (= {', '.join(same)})" if same else "")
        (ax.axvline if vertical else ax.axhline)(k, label=label, **_BOUND_STYLES[key])


def stiffness_plot(curve, ax=None):
    """Criterion stiffness limit against impact speed, with the published bounds (eq. 8, 9, 11).

    Parameters
    ----------
    curve : StiffnessResponse
        From :func:`dfa.analysis.limits.closed_form.stiffness_response`.

    The speed axis spans the curve's speeds exactly (by default up to hand speeds), widened only to show the
    chosen K's largest passive speed.
    """
    ax = _axes(ax, figsize=(9.8, 4.2))
    u = curve.device.units
    d = getattr(curve, "delay", 0)
    ax.loglog(
        curve.velocity,
        curve.k_max,
        color="#2166ac",
        lw=2,
        label="criterion K_max (eq. 11)" + (f", delay {d}" if d else ""),
    )
    bounds = _bounds(curve.k_static, curve.k_colgate, curve.k_abbott_okamura, curve.k_gil, d)
    _bound_lines(ax, bounds, u["stiffness"], vertical=False)
    if curve.stiffness is not None:
        ax.axhline(
            curve.stiffness, color="#b2182b", lw=1.0, label=f"chosen K = {number(curve.stiffness)} {u['stiffness']}"
        )
        if curve.max_passive_velocity is not None and np.isfinite(curve.max_passive_velocity):
            ax.axvline(curve.max_passive_velocity, color="#b2182b", lw=0.8, ls=":")
            ax.plot(
                [curve.max_passive_velocity],
                [curve.stiffness],
                label=f"passive up to {number(curve.max_passive_velocity)} {u['velocity']}",
                **POINT_STYLE,
            )
    v = np.asarray(curve.velocity, dtype=float)
    lo, hi = float(v.min()), float(v.max())
    mpv = curve.max_passive_velocity if curve.stiffness is not None else None
    if mpv is not None and np.isfinite(mpv) and mpv > 0:
        lo, hi = min(lo, mpv / 1.5), max(hi, mpv * 1.5)
    if hi > lo:  # one speed: matplotlib's own limits
        ax.set_xlim(lo, hi)
    ax.set_xlabel(f"impact speed |ẋ0| ({u['velocity']})")
    ax.set_ylabel(f"stiffness K ({u['stiffness']})")
    ax.set_title(f"{curve.device.name}: largest passive stiffness", fontsize=9)
    _legend_outside(ax, wrap=LEGEND_WRAP)
    ax.grid(True, which="both", alpha=0.3)
    return ax


def stiffness_speed_plot(chart, ax=None):
    """Largest safe impact speed against stiffness K, four ways, with the closed-form bounds (issue 14 §2).

    Parameters
    ----------
    chart : StiffnessSpeedChart
        From :func:`dfa.analysis.limits.speed_chart.stiffness_speed_chart`.

    Notes
    -----
    The chart's speeds stop at its top speed ``v_top`` (the band above it is shaded): a simulated curve at
    ``v_top`` is safe at every speed simulated, one on the bottom edge not even at the slowest. The criterion is
    a closed form, not a simulation: where it proves more than ``v_top`` its curve leaves through the top edge
    instead of running flat along ``v_top`` (which read as a plateau).
    """
    ax = _axes(ax, figsize=(11.0, 4.8))
    u = chart.device.units
    floor = float(chart.speeds[0]) / 2.0  # "not even the slowest simulated speed" is drawn here
    ceiling = chart.v_top * 1.3

    def show(v):
        return np.where(np.asarray(v) < floor, floor, v)

    ax.axhspan(chart.v_top, ceiling * 10, color="0.92", lw=0, zorder=0,
               label=f"above the simulated speeds (> {chart.v_top:g} {u['velocity']})")  # fmt: skip
    kc, vc = _leaving_top(chart.criterion_stiffness, show(chart.v_criterion), chart.v_top, ceiling * 3)
    one_sided = chart.wall.one_sided
    if chart.criterion_covered:
        ax.plot(kc, vc, color="#2166ac", lw=2.2, label="criterion (eq. 11, proof)")
    else:
        ax.plot([], [], color="#2166ac", lw=2.2, label="criterion: not covered (no proof for this wall)")
    ax.plot(
        chart.stiffness,
        show(chart.v_df),
        color="#e08214",
        lw=1.5,
        ls="--",
        marker="^",
        ms=4,
        label="describing function: not a linear loop" if one_sided else "describing function (growth speed)",
    )
    ax.plot(
        chart.stiffness, show(chart.v_sim), color="#b2182b", lw=1.5, marker="o", ms=4, label="simulation: no divergence"
    )
    ax.plot(
        chart.stiffness,
        show(chart.v_rest),
        color="#1b7837",
        lw=1.2,
        ls=":",
        marker="s",
        ms=3.5,
        label="simulation: comes to rest" + (" or leaves" if one_sided else ""),
    )
    bounds = _bounds(chart.k_static, chart.k_colgate, chart.k_abbott_okamura, chart.k_linear, chart.delay)
    _bound_lines(ax, bounds, u["stiffness"], vertical=True)
    _design_marks(ax, chart, floor)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(floor / 1.3, ceiling)
    ax.set_xlim(chart.stiffness[0], chart.stiffness[-1])
    ax.set_xlabel(f"stiffness K ({u['stiffness']})")
    ax.set_ylabel(f"largest safe impact speed ({u['velocity']})")
    d = chart.delay
    ax.set_title(f"{chart.device.name}: how stiff for which impact speed" + (f", delay {d}" if d else ""), fontsize=9)
    # the details go in a note under the axes (a two-line title crowded the top of the figure)
    ax.annotate(
        f"Impact speeds simulated from {chart.speeds[0]:.3g} to {chart.v_top:g} {u['velocity']}: a simulated curve at "
        f"{chart.v_top:g} {u['velocity']} is safe at every speed simulated, one on the bottom edge not even at "
        f"{chart.speeds[0]:.3g} {u['velocity']};\nthe criterion's curve leaves the top where it proves more than "
        f"{chart.v_top:g} {u['velocity']}.",
        xy=(0.0, 0.0),
        xycoords="axes fraction",
        xytext=(0.0, -34.0),
        textcoords="offset points",
        va="top",
        ha="left",
        fontsize=SMALL_FONTSIZE,
        color="0.25",
    )
    ax.grid(True, which="both", alpha=0.3)
    _legend_outside(ax, wrap=LEGEND_WRAP)
    return ax


def _leaving_top(k: np.ndarray, v: np.ndarray, top: float, beyond: float) -> tuple[np.ndarray, np.ndarray]:
    """A curve capped at ``top`` (its data say "at least top") drawn as leaving the axes upward: capped points are
    dropped (a gap, not a flat run along ``top``), and each capped neighbour of an uncapped point is moved to
    ``beyond`` (above the axes) along the curve's last slope (log-log), so that the line exits through the top
    edge as it was heading."""
    k, v = np.array(k, dtype=float), np.asarray(v, dtype=float)
    capped = v >= top * (1.0 - 1e-9)
    out = np.where(capped, np.nan, v)
    lk, lv = np.log(k), np.log(np.where(capped, top, np.maximum(v, 1e-300)))
    for e in np.flatnonzero(capped):
        for u, w in ((e - 1, e - 2), (e + 1, e + 2)):  # the uncapped neighbour u and the one beyond it, w
            if 0 <= u < k.size and not capped[u]:
                out[e] = beyond
                if 0 <= w < k.size and not capped[w] and lk[u] != lk[w]:
                    slope = (lv[u] - lv[w]) / (lk[u] - lk[w])
                    step = (np.log(beyond) - lv[u]) / slope if slope != 0 else np.inf
                    if np.isfinite(step) and np.sign(step) == np.sign(lk[e] - lk[u]):
                        k[e] = np.exp(lk[u] + np.clip(step, -abs(lk[e] - lk[u]) * 10, abs(lk[e] - lk[u]) * 10))
                break
    return k, out


def _design_marks(ax, chart, floor: float) -> None:
    """The design speed (horizontal line) and the design point (star) of the stiffness-speed chart."""
    u = chart.device.units
    if chart.design_velocity is not None and chart.design_velocity > 0:
        ax.axhline(chart.design_velocity, color="0.4", lw=0.8, ls="--",
                   label=f"design speed V = {chart.design_velocity:.3g} {u['velocity']}")  # fmt: skip
    if chart.design_stiffness is not None and chart.design_velocity is not None:
        ax.plot(
            [chart.design_stiffness],
            [max(chart.design_velocity, floor)],
            marker="*",
            color="k",
            ms=13,
            ls="none",
            label=f"design point K = {number(chart.design_stiffness)} {u['stiffness']}, "
            f"V = {chart.design_velocity:.3g} {u['velocity']}",
        )


def cycle_error_plot(validation, ax=None):
    """Relative error of simulated vs predicted stable cycles against their period (validation item 4).

    Errors below 0.1 % are drawn at 0.1 % (log axis).
    """
    from matplotlib.ticker import FixedLocator, NullLocator, ScalarFormatter

    ax = _axes(ax, figsize=(6.0, 4.0))
    floor = 0.1
    for model, marker in (("half-delay", "o"), ("zoh", "s")):
        recs = [r for r in validation.cycles if r["model"] == model and r["stable"] and r.get("confirmed")]
        if recs:
            per = [r["period"] for r in recs]
            ax.plot(
                per,
                [max(floor, 100 * abs(r["frequency_error"])) for r in recs],
                marker,
                mfc="none",
                alpha=0.8,
                label=f"{model}: frequency",
            )
            ax.plot(
                per,
                [max(floor, 100 * abs(r["amplitude_error"])) for r in recs],
                marker,
                ms=3,
                alpha=0.6,
                label=f"{model}: amplitude",
            )
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.xaxis.set_major_locator(FixedLocator([2, 4, 8, 16, 32, 64]))
    ax.xaxis.set_minor_locator(NullLocator())
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.axvline(8, color="0.4", ls="--", lw=0.8)
    ax.text(8.3, floor * 1.5, "8 samples", fontsize=SMALL_FONTSIZE, color="0.3")
    ax.set_xlabel("predicted period (samples)")
    ax.set_ylabel("|simulated/predicted − 1| (%)")
    ax.set_title("Describing function vs exact simulation, stable cycles", fontsize=9)
    ax.legend(fontsize=LEGEND_FONTSIZE, loc="lower right")
    ax.grid(True, which="both", alpha=0.3)
    return ax


def critical_speed_plot(validation, ax=None):
    """Critical impact speed three ways per case: criterion, describing function, simulation (validation item 2)."""
    ax = _axes(ax, figsize=(7.0, 3.8))
    rows = validation.speeds
    x = np.arange(len(rows))
    w = 0.2
    series = [
        ("criterion", "criterion (eq. 12)", "#b2182b"),
        ("df_zoh", "DF growth threshold (exact ZOH)", "#2166ac"),
        ("simulated", "simulated", "0.2"),
        ("simulated_preload", "simulated, preload", "0.6"),
    ]
    for i, (key, label, color) in enumerate(series):
        vals = [r[key] if r[key] is not None else np.nan for r in rows]
        ax.bar(x + (i - 1.5) * w, vals, w, label=label, color=color)
    ax.set_xticks(x)
    ax.set_xticklabels([r["name"] for r in rows], rotation=20, ha="right", fontsize=SMALL_FONTSIZE)
    ax.set_ylabel("critical speed ξ'0 (ticks per sample)")
    ax.set_title("Critical impact speed, three ways", fontsize=9)
    ax.legend(fontsize=LEGEND_FONTSIZE)
    return ax


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

    The simulated boundaries are values of the K grid and are drawn as markers, one per B, never joined
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
    from .results.codes import BOUNDED, DIVERGES, LEFT_POINT, REST, UNDECIDED_POINT, ZWIDTH_METHODS

    ax = _axes(ax, figsize=(7.6, 4.6))
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
    ax.set_yscale("log")
    ax.set_ylim(kedges[0], kedges[-1])
    ax.set_xlim(bedges[0], bedges[-1])
    ax.set_xlabel(f"virtual damping B ({u['damping']})")
    ax.set_ylabel(f"virtual stiffness K ({u['stiffness']})")
    contact = ", one-sided wall reached from free space" if zw.wall.one_sided else ""
    ax.set_title(f"Z-width of {zw.device.name}, impacts up to {zw.velocity:.3g} {u['velocity']}{contact}", fontsize=9)
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
    _legend_outside(ax, handles)
    return ax


#: Samples above which the identification figure adds an inset of the log's last samples.
ZOOM_AFTER = 1500


def plot_identification(ident, axes=None):
    """A logged run against the identified model (issue 29): ticks over time above, residual below; a log longer
    than :data:`ZOOM_AFTER` samples gets an inset of its last twentieth (at least 375 samples).

    Parameters
    ----------
    ident : Identification
        :func:`dfa.analysis.identify.identify`'s result.
    axes : pair of Axes, optional
        Top (trajectory) and bottom (residual) axes; a new figure when None.

    Returns
    -------
    pair of Axes
    """
    if axes is None:
        _fig, axes = plt.subplots(2, 1, figsize=(9.0, 5.0), sharex=True, constrained_layout=True,
                                  gridspec_kw={"height_ratios": [3, 1]})  # fmt: skip
    t = np.arange(ident.samples) * ident.device.period
    top, bottom = axes
    top.step(t, ident.logged, where="post", color="0.3", lw=1.0, label="logged reading")
    top.plot(t, ident.predicted, color="C0", lw=1.0, label="identified model, run once from the start")
    top.set_ylabel("position (encoder ticks)")
    top.set_title(f"{ident.source}: {100 * ident.free_run.within_one_tick:.4g} % of samples within one tick",
                  fontsize=10)  # fmt: skip
    _legend_outside(top)
    if ident.samples > ZOOM_AFTER:  # a long log is a band at this scale: its last samples, where a cycle shows
        k = max(ZOOM_AFTER // 4, ident.samples // 20)
        inset = top.inset_axes((0.62, 0.58, 0.36, 0.38))
        inset.step(t[-k:], ident.logged[-k:], where="post", color="0.3", lw=0.8)
        inset.plot(t[-k:], ident.predicted[-k:], color="C0", lw=0.8)
        inset.set_title(f"last {k} samples", fontsize=7)
        inset.tick_params(labelsize=6)
    bottom.plot(t, ident.predicted - ident.logged - 0.5, color="C3", lw=0.8)
    for y in (-0.5, 0.5):
        bottom.axhline(y, color="0.6", lw=0.6, ls="--")
    bottom.set_ylabel("model − tick middle\n(ticks)")
    bottom.set_xlabel("time (s)")
    return axes


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
    _legend_outside(axes[1], handles)
    return axes
