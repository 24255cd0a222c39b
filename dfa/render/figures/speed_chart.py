"""The stiffness-speed chart: largest safe impact speed against K, four ways, with the closed-form bounds."""

from __future__ import annotations

import numpy as np

from ...formatting import number
from .bounds import closed_form_bounds, draw_bounds
from .style import LEGEND_WRAP, SMALL_FONTSIZE, legend_outside, new_axes


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
    ax = new_axes(ax, figsize=(11.0, 4.8))
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
    bounds = closed_form_bounds(chart.k_static, chart.k_colgate, chart.k_abbott_okamura, chart.k_linear, chart.delay)
    draw_bounds(ax, bounds, u["stiffness"], vertical=True)
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
    legend_outside(ax, wrap=LEGEND_WRAP)
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
