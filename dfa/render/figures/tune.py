"""The tuning's trade-off: recommended stiffness against force error, one point per simulated wall."""

from __future__ import annotations

from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from ...results.status import RecommendRule
from ..tune import wall_label
from .style import SMALL_FONTSIZE, legend_outside, new_axes


def tune_plot(result, ax=None):
    """Recommended K (across, log) against the force error (up, %) of every simulated wall of a tuning.

    Parameters
    ----------
    result : TuneResult
        From :func:`dfa.tune`.
    ax : matplotlib.axes.Axes, optional
        Axes to draw on (default: a new figure).

    Returns
    -------
    matplotlib.axes.Axes

    Notes
    -----
    A filled marker is a proven K (eq. 11, extended), a hollow one the simulated limit over the margin (not a
    proof); red where the recommended K lies above the simulated rest limit (the wall may buzz there). The plain
    wall is the square. Up and to the left is a stiffer-feeling, less faithful wall; the best trade-off lies low
    and to the right. The star is the best wall, the dashed line the force-error cap. Walls without a recommended K
    or a force error are left out.
    """
    ax = new_axes(ax, figsize=(8.0, 4.8))
    u = result.device.units
    drawn, notes = {}, []
    for i, w in enumerate(result.walls):
        k, e = w.k_recommended, w.force_error
        if k is None or e is None:
            continue
        rec = w.recommendation
        proven = rec.status is RecommendRule.PROVEN
        colour = "#b2182b" if rec.above_rest else "#2166ac"
        key = (proven, rec.above_rest, i == 0)
        label = (
            ("plain wall, " if i == 0 else "")
            + ("proven K" if proven else "simulated K / margin")
            + (", may buzz" if rec.above_rest else ", rests")
        )
        ax.plot([k], [100.0 * e], ls="none", marker="s" if i == 0 else "o", ms=8, color=colour,
                mfc=colour if proven else "white", mew=1.6, label=label if key not in drawn else None)  # fmt: skip
        drawn[key] = True
        notes.append(ax.annotate(
            wall_label(w.wall, w.device, u, result.device.period), (k, 100.0 * e), xytext=(6, 4),
            textcoords="offset points", fontsize=SMALL_FONTSIZE,
        ))  # fmt: skip
    best = result.best
    if best is not None and best.k_recommended is not None and best.force_error is not None:
        ax.plot([best.k_recommended], [100.0 * best.force_error], ls="none", marker="*", ms=16, color="#e08214",
                zorder=0, label="best (stiffest within the cap)")  # fmt: skip
    if result.max_force_error is not None:
        ax.axhline(100.0 * result.max_force_error, color="0.4", ls="--", lw=1.0, label="force-error cap")
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))  # 1-2-5 labels: a span under a decade has some
    ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _pos: f"{x:g}"))
    ax.xaxis.set_minor_formatter(NullFormatter())  # the other minor ticks unlabelled: their labels overlap
    ax.margins(x=0.2, y=0.15)
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel(f"recommended stiffness K ({u['stiffness']})")
    ax.set_ylabel("force error over the first contact (% of peak)")
    ax.set_title(f"{result.device.name}: stiffness against fidelity at {result.velocity:g} {u['velocity']}")
    ax.grid(True, which="both", alpha=0.3)
    legend_outside(ax)
    _labels_inside(ax, notes)
    return ax


def _labels_inside(ax, notes) -> None:
    """A point's label to its left where, to its right, it would reach the axes' frame (measured once the figure is
    laid out: a draw)."""
    ax.figure.canvas.draw()
    renderer = ax.figure.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    for note in notes:
        if note.get_window_extent(renderer).x1 > frame.x1:
            note.set_position((-6, 4))
            note.set_horizontalalignment("right")
