"""The criterion's stiffness limit against impact speed, with the published bounds (eq. 8, 9, 11)."""

from __future__ import annotations

import numpy as np

from ...formatting import number
from .bounds import closed_form_bounds, draw_bounds
from .style import LEGEND_WRAP, POINT_STYLE, legend_outside, new_axes


def stiffness_plot(curve, ax=None):
    """Criterion stiffness limit against impact speed, with the published bounds (eq. 8, 9, 11).

    Parameters
    ----------
    curve : StiffnessResponse
        From :func:`dfa.analysis.limits.closed_form.stiffness_response`.

    The speed axis spans the curve's speeds exactly (by default up to hand speeds), widened only to show the
    chosen K's largest passive speed.
    """
    ax = new_axes(ax, figsize=(9.8, 4.2))
    u = curve.device.units
    d = getattr(curve, "delay", 0)
    ax.loglog(
        curve.velocity,
        curve.k_max,
        color="#2166ac",
        lw=2,
        label="criterion K_max (eq. 11)" + (f", delay {d}" if d else ""),
    )
    bounds = closed_form_bounds(curve.k_static, curve.k_colgate, curve.k_abbott_okamura, curve.k_gil, d)
    draw_bounds(ax, bounds, u["stiffness"], vertical=False)
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
    legend_outside(ax, wrap=LEGEND_WRAP)
    ax.grid(True, which="both", alpha=0.3)
    return ax
