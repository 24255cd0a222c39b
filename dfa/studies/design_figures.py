"""Figures of the design report, drawn from a :class:`~dfa.studies.design.DesignAnalysis` only (PNG bytes in memory)."""

from __future__ import annotations

import io
from dataclasses import dataclass
from typing import Any

from ..model.elements import Coverage
from ..render.hand import held_name
from .design import DesignAnalysis

__all__ = ["ReportFigure", "design_figures"]


@dataclass(frozen=True)
class ReportFigure:
    """One figure of the report: a short name (file ``{slug}_{name}.png``), its caption and the PNG bytes."""

    name: str
    caption: str
    png: bytes = b""


def _png(fig: Any) -> bytes:
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=120)
    plt.close(fig)
    return buf.getvalue()


def _delay_text(dl: int) -> str:
    return f", delay {dl} sample{'s' if dl != 1 else ''}" if dl else ""


def _with_ctl(a: DesignAnalysis) -> str:
    """' with the wall controller (β_B = …, ν_c = …, α = …)' for a report with a controller, '' for the spring."""
    if a.covers(Coverage.CLOSED_FORM):
        return ""
    cp = a.wall_params
    nu = "none" if cp.cutoff is None else f"{cp.cutoff:.3g}"
    return f" with the wall controller (β_B = {cp.damping:.3g}, ν_c = {nu}, α = {cp.lag:.3g}, d = {cp.delay})"


def _regions(a: DesignAnalysis) -> ReportFigure | None:
    from ..render import figures

    crit, p, u = a.criterion, a.params, a.device.units
    if crit is None:  # a controller: the regions of eq. 6 are the spring's (the report says so)
        return None
    ax = figures.regions_plot(
        crit,
        xi_dots=[x for x in (1.0, 5.0) if abs(x - crit.xi_dot) > 0.2],
        beta_max=max(1.0, 2 * p.beta),
        sigma_max=max(2.0, 1.5 * p.sigma),
    )
    caption = (
        f"Operating point of the {held_name(a.device)} in the (β, σ) plane with its critical line at {a.velocity:g} "
        f"{u['velocity']}{_delay_text(a.delay)} (eq. 6, 10)."
    )
    return ReportFigure("regions", caption, _png(ax.figure))


def _stiffness(a: DesignAnalysis) -> ReportFigure | None:
    from ..render import figures

    if a.stiffness_curve is None:  # a controller: eq. 11 is the spring's (the report says so)
        return None
    ax = figures.stiffness_plot(a.stiffness_curve)
    caption = (
        "Largest passive stiffness against impact speed (eq. 11) and the published bounds (values in the legend; "
        "bounds that coincide are drawn on top of each other and say so)."
    )
    return ReportFigure("stiffness", caption, _png(ax.figure))


def _nyquist(a: DesignAnalysis) -> ReportFigure | None:
    from ..render import figures
    from ..render.controller import controller_short

    if a.nyquist is None:  # a one-sided wall: not a linear loop
        return None
    model = a.nyquist.model
    ctl = None if a.covers(Coverage.CLOSED_FORM) else controller_short(a.wall, a.device.units)
    ax = figures.nyquist_plot(a.nyquist, controller=ctl)
    name = figures.MODEL_NAMES.get(model, model)
    caption = (
        f"Nyquist plot of the linearised loop{_with_ctl(a)} ({name} model, as the growth threshold above) against −1/D(M), "
        f"with its predicted limit cycles (filled: stable, open: unstable){_inset_text(ax)}."
    )
    return ReportFigure("nyquist", caption, _png(ax.figure))


def _inset_text(ax: Any) -> str:
    """The caption's words for the Nyquist figure's zoom: only when one is drawn (an inset is a child axes)."""
    if not ax.child_axes:
        return ""
    return "; the inset at the upper left zooms on the cycles (they crowd or lie below one tick)"


def _trajectories(a: DesignAnalysis) -> ReportFigure:
    import matplotlib.pyplot as plt

    from ..render import figures

    u, dev = a.device.units, a.device
    fig, axs = plt.subplots(2, 1, figsize=(7, 5.6), constrained_layout=True)
    figures.trajectory_plot(a.trajectory, ax=axs[0], device=dev)
    axs[0].set_title(
        f"impact at {a.velocity:g} {u['velocity']} (ξ'0 = {a.xi_dot:.3g}): {a.outcome.outcome}", fontsize=9
    )
    figures.trajectory_plot(a.trajectory_high, ax=axs[1], device=dev)
    axs[1].set_title(
        f"impact at {dev.velocity(a.high_xi_dot):.3g} {u['velocity']} (ξ'0 = {a.high_xi_dot:.3g}): "
        f"{a.outcome_high.outcome}",
        fontsize=9,
    )
    caption = (
        f"Simulated displacement (exact sampled-data integration){_with_ctl(a)} at the design speed and "
        + (
            "just above the simulated critical speed"
            if a.simulated_xi_dot is not None
            else "at twice the reference speed (no scanned speed diverged)"
        )  # fmt: skip
        + ", each with its own time window and scale (a run that came to rest is shown up to about "
        "four times its settling time); left axis in encoder ticks, right axis in "
        f"{u['position']}; dashed: ±1 tick."
    )
    return ReportFigure("trajectories", caption, _png(fig))


def _map(a: DesignAnalysis) -> ReportFigure:
    from ..render import figures

    axs = figures.stability_map_plot(
        a.stability_map, device=a.device, stiffness=a.stiffness, point=(a.params.beta, a.params.sigma)
    )
    caption = (
        f"Simulated stability{_with_ctl(a)} around the operating point (red circle) at the design speed and twice it"
        + ("; the controller's groups are held fixed over the map" if not a.covers(Coverage.CLOSED_FORM) else "")
        + "; "
        f"μ = {a.params.mu:.4g}. Top and right axes: the damping b and Coulomb friction c that give β and σ at "
        f"K = {a.stiffness:.4g} {a.device.units['stiffness']}. The legend lists every outcome class, present or not."
    )
    return ReportFigure("map", caption, _png(axs[0].figure))


def _speed_chart(a: DesignAnalysis) -> ReportFigure | None:
    if a.speed_chart is None:
        return None
    ax = a.speed_chart.plot()
    caption = (
        f"Largest safe impact speed against stiffness K for the {held_name(a.device)}{_delay_text(a.delay)}: criterion "
        "(proof), describing function and simulation, with the closed-form bounds; the star is the design point."
    )
    return ReportFigure("speed_chart", caption, _png(ax.figure))


def _zwidth(a: DesignAnalysis) -> ReportFigure | None:
    if a.zwidth is None:
        return None
    z = a.zwidth
    ax = z.plot(design_point=None if a.covers(Coverage.CLOSED_FORM) else (a.wall.damping, a.stiffness))
    caption = (
        f"Z-width of the {held_name(a.device)}{_delay_text(a.delay)} for impacts up to {z.velocity:.3g} "
        f"{a.device.units['velocity']}: largest K at each virtual damping B by the exact linear bound, passivity, "
        f"the describing function and exact simulation on a {z.stiffness.size} × {z.damping.size} grid (shaded)."
    )
    if not a.covers(Coverage.CLOSED_FORM):
        caption += _design_point_text(ax, a)
    return ReportFigure("zwidth", caption, _png(ax.figure))


def _tuned(a: DesignAnalysis) -> ReportFigure | None:
    if a.tuned is None:
        return None
    ax = a.tuned.plot()
    caption = (
        f"The walls tuned for the {held_name(a.device)} at {a.tuned.velocity:.3g} {a.device.units['velocity']}: "
        "recommended K against the force error over the first contact; filled: proven, hollow: the simulated limit "
        "over the margin; red: above the simulated rest limit (may buzz)."
    )
    return ReportFigure("tune", caption, _png(ax.figure))


def _design_point_text(ax: Any, a: DesignAnalysis) -> str:
    """The caption's sentence about the controller's (B, K), starred on the Z-width by its ``plot``."""
    b, k = a.wall.damping, a.stiffness
    u = a.device.units
    lo, hi = ax.get_ylim()
    where = "" if lo <= k <= hi else " (outside the K grid: drawn at its edge)"
    filt = []
    if a.wall.filter_cutoff is not None:
        filt.append(f"velocity filter {a.wall.filter_cutoff:.4g} Hz")
    if a.wall.amplifier_bandwidth is not None:
        filt.append(f"amplifier bandwidth {a.wall.amplifier_bandwidth:.4g} Hz")
    return (
        f" With the controller's {', '.join(filt) or 'delay'}; the star is the design point K = {k:.5g} "
        f"{u['stiffness']}, B = {b:.4g} {u['damping']}{where}."
    )


#: The report's figures in the order they appear.
FIGURES = (_speed_chart, _regions, _stiffness, _nyquist, _trajectories, _map, _zwidth, _tuned)


def design_figures(analysis: DesignAnalysis) -> tuple[ReportFigure, ...]:
    """The five figures of the design report (regions, stiffness, Nyquist, trajectories, map) as PNG bytes.

    Parameters
    ----------
    analysis : DesignAnalysis
        From :func:`dfa.studies.design.design_analysis`; only read.

    Returns
    -------
    tuple of ReportFigure
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    return tuple(f for f in (draw(analysis) for draw in FIGURES) if f is not None)
