"""The validation's figures: errors of the predicted cycles, critical speeds three ways."""

from __future__ import annotations

import numpy as np

from .style import LEGEND_FONTSIZE, SMALL_FONTSIZE, new_axes


def cycle_error_plot(validation, ax=None):
    """Relative error of simulated vs predicted stable cycles against their period (validation item 4).

    Errors below 0.1 % are drawn at 0.1 % (log axis).
    """
    from matplotlib.ticker import FixedLocator, NullLocator, ScalarFormatter

    ax = new_axes(ax, figsize=(6.0, 4.0))
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
    ax = new_axes(ax, figsize=(7.0, 3.8))
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
