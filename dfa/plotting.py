"""Figures of dfa: the only module that imports matplotlib.

Every function takes a result object and an optional ``ax`` (or ``axes``)
and returns the axes it drew on, in the style of python-control's ``*_plot``
functions. Axis labels carry units: dimensionless quantities are marked (–),
positions are in encoder ticks, time in samples (or seconds when a sample
period is given).

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import dfa
>>> from dfa.plotting import regions_plot
>>> ax = regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
>>> ax.get_xlabel()
'β = b/(K T) (–)'
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import matplotlib
import matplotlib.lines
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.artist import Artist
from matplotlib.colors import ListedColormap
from matplotlib.patches import Patch

from .criterion import REGION_DESCRIPTIONS, CriterionResult, CriticalLine, classify_region

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
    "BETA_LABEL",
    "SIGMA_LABEL",
]

BETA_LABEL = "β = b/(K T) (–)"
SIGMA_LABEL = "σ = c/(K Δ) (–)"
REGION_COLORS = {"a": "#d9f0d3", "b": "#c6dbef", "c": "#f4a582", "d": "#fddbc7", "e": "#fff7bc"}
#: Colour of each simulated outcome (paper Fig. 4: white stable, light persisting oscillation, dark unstable).
OUTCOME_COLORS = {
    "rest": "#ffffff",
    "chatter": "#e0e0e0",
    "oscillating": "#a3a3a3",
    "unstable": "#252525",
    "undecided": "#e08214",
}
_OUTCOME_LABELS = {
    "rest": "rest (came to rest)",
    "chatter": "chatter (persisting, < 1 tick)",
    "oscillating": "oscillating (persisting, >= 1 tick)",
    "unstable": "unstable (diverged)",
    "undecided": "undecided (run too short)",
}


def _outcome_cmap() -> ListedColormap:
    from .simulation import OUTCOMES

    return ListedColormap([OUTCOME_COLORS[name] for name in OUTCOMES])  # indexed by the outcome code


def _axes(ax=None, figsize=(5.0, 4.0)):
    if ax is None:
        _fig, ax = plt.subplots(figsize=figsize, constrained_layout=True)
    return ax


def regions_plot(
    result: CriterionResult,
    ax=None,
    *,
    xi_dots: Sequence[float] = (),
    beta_max: float = 1.0,
    sigma_max: float = 2.0,
    legend: bool = True,
    legend_loc: str = "upper right",
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
        Further speeds whose critical lines (same delay) are drawn (dotted).
    """
    ax = _axes(ax)
    line = result.critical_line
    bmax = max(beta_max, 1.2 * result.beta, 0.6, 1.2 * line.beta0)
    smax = max(sigma_max, 1.2 * result.sigma, 0.6)
    b = np.linspace(0, bmax, 400)
    s = np.linspace(0, smax, 400)
    reg = classify_region(b[None, :], s[:, None], line.xi_dot, result.quantized, line.delay)
    codes = np.searchsorted(np.array(list("abcde")), reg)
    cmap = ListedColormap([REGION_COLORS[k] for k in "abcde"])
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
    ax.axvline(line.beta0, color="k", lw=0.8, ls="-.")
    if result.quantized:
        ax.axhline(line.sigma0, color="k", lw=0.8, ls="-.")
    dl = f", delay {line.delay}" if line.delay else ""
    ax.plot(b, line.sigma(b), "k--", lw=1.2, label=f"critical line, V = {line.xi_dot:.3g}{dl}")
    for v in xi_dots:
        ax.plot(b, CriticalLine(v, line.sigma0, line.delay).sigma(b), ":", color="0.3", lw=1.0, label=f"ξ'0 = {v:g}")
    ax.plot(
        [result.beta], [result.sigma], "o", color="#b2182b", ms=7, mec="k", label=f"operating point ({result.region})"
    )
    ax.set_xlim(0, bmax)
    ax.set_ylim(0, smax)
    ax.set_xlabel(BETA_LABEL)
    ax.set_ylabel(SIGMA_LABEL)
    ax.set_title("Regions of the (β, σ) plane (eq. 6, 10)" + (f", delay d = {line.delay}" if line.delay else ""))
    if legend:
        handles = [
            Patch(facecolor=REGION_COLORS[k], edgecolor="0.5", label=f"{k}: {REGION_DESCRIPTIONS[k].split(':')[0]}")
            for k in "abcde"
        ]
        lines, labels = ax.get_legend_handles_labels()
        ax.legend(handles=handles + lines, fontsize=7, loc=legend_loc, framealpha=0.9)
    return ax


def stability_map_plot(smap, axes=None, *, titles: bool = True):
    """Simulated outcome per (β, σ) for each initial speed (paper Fig. 4).

    As in the paper, white: came to rest; light: persisting oscillation, in
    two shades (lightest: chatter below one tick, darker: oscillating, one
    tick or more); dark: unstable; orange: undecided (the run was too short,
    :mod:`dfa.simulation`). The critical line of each speed
    (:class:`dfa.criterion.CriticalLine` with the map's delay d) is dashed, the
    region boundaries β = ½ + d, σ = ½ dash-dot.

    Parameters
    ----------
    smap : StabilityMap
    axes : sequence of Axes, optional
        One per speed.
    """
    n = len(smap.xi_dots)
    if axes is None:
        cols = min(n, 2)
        rows = int(math.ceil(n / cols))
        fig, axs = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.6 * rows), constrained_layout=True, squeeze=False)
        axes = list(axs.ravel())
        for extra in axes[n:]:
            extra.remove()
        axes = axes[:n]
    b, s = smap.beta, smap.sigma
    db = (b[1] - b[0]) / 2
    ds = (s[1] - s[0]) / 2
    extent = (b[0] - db, b[-1] + db, s[0] - ds, s[-1] + ds)
    cmap = _outcome_cmap()
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
        line = CriticalLine.of(v, quantized=smap.quantize, delay=smap.delay)
        ax.plot(bb, line.sigma(bb), "--", color="#b2182b", lw=1.3)
        ax.axvline(line.beta0, color="#2166ac", ls="-.", lw=1.0)
        if smap.quantize:
            ax.axhline(line.sigma0, color="#2166ac", ls="-.", lw=1.0)
        ax.set_xlim(extent[0], extent[1])
        ax.set_ylim(extent[2], extent[3])
        ax.set_xlabel(BETA_LABEL)
        ax.set_ylabel(SIGMA_LABEL)
        if titles:
            what = "preload equivalent to" if smap.preload else "initial speed"
            ax.set_title(
                f"μ = {smap.mu:.4g}, {what} ξ'0 = {v:.3g} ticks/sample"
                + (f", delay {smap.delay}" if smap.delay else ""),
                fontsize=9,
            )
    handles: list[Artist] = [
        Patch(facecolor=OUTCOME_COLORS[k], edgecolor="0.5", label=_OUTCOME_LABELS[k])
        for k in ("rest", "chatter", "oscillating", "unstable", "undecided")
    ]
    handles += [
        matplotlib.lines.Line2D([], [], color="#b2182b", ls="--", label="critical line (eq. 10)"),
        matplotlib.lines.Line2D(
            [], [], color="#2166ac", ls="-.", label="β = ½ + d, σ = ½" if smap.delay else "β = ½, σ = ½"
        ),
    ]
    axes[0].legend(handles=handles, fontsize=7, loc="upper right", framealpha=0.9)
    return axes


def trajectory_plot(sim, ax=None, *, period: float | None = None, max_samples: int | None = None):
    """Displacement in ticks against time with ±1 tick marked (paper Fig. 5, right).

    Parameters
    ----------
    sim : SimulationResult
        Must have been recorded (``record=True``).
    period : float, optional
        Sample period T in s: the time axis is then in seconds.
    max_samples : int, optional
        Draw only the first samples.
    """
    ax = _axes(ax, figsize=(6.0, 3.2))
    if sim.xi is None:
        raise ValueError("sim has no trajectory: run dfa.simulate(..., record=True)")
    n = sim.xi.size if max_samples is None else min(sim.xi.size, max_samples + 1)
    t = np.arange(n) * (period if period else 1.0)
    ax.plot(t, sim.xi[:n], lw=0.9, color="#2166ac")
    for y in (-1.0, 1.0):
        ax.axhline(y, color="0.4", ls="--", lw=0.8)
    ax.set_xlabel("time (s)" if period else "time (samples)")
    ax.set_ylabel("displacement ξ (encoder ticks)")
    ax.set_title(f"μ = {sim.mu:.4g}, β = {sim.beta:.3g}, σ = {sim.sigma:.3g}: {sim.outcome}", fontsize=9)
    ax.set_xlim(t[0], t[-1] if n > 1 else 1)
    return ax


def contour_plot(maps, axes=None):
    """Amplitude and frequency of the small stable and large unstable families (paper Fig. 7).

    Left: small stable cycles, amplitude filled, frequency as labelled white
    lines. Right: the smallest unstable cycle with the exact D (filled, log
    levels) with the paper's closed form eq. 44-45 overlaid as dashed contours
    of the same levels; its frequency is nearly constant and is printed.

    Parameters
    ----------
    maps : ContourMaps
    axes : pair of Axes, optional
    """
    from matplotlib.colors import BoundaryNorm

    if axes is None:
        _fig, axes = plt.subplots(1, 2, figsize=(10.5, 4.2), constrained_layout=True)
    bb, ss = np.meshgrid(maps.beta, maps.sigma)
    ax = axes[0]
    if np.isfinite(maps.small_amplitude).any():
        cf = ax.contourf(bb, ss, maps.small_amplitude, levels=np.linspace(0, 1, 11), cmap="viridis")
        plt.colorbar(cf, ax=ax).set_label("amplitude M (encoder ticks)")
        cs = ax.contour(bb, ss, maps.small_frequency, levels=6, colors="w", linewidths=0.7)
        ax.clabel(cs, fontsize=6, fmt="ω=%.2f")
    ax.set_title(f"μ = {maps.mu:g}: small stable cycles (M < 1, eq. 42-43)", fontsize=9)
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
        ax.legend(fontsize=7, loc="upper right", facecolor="0.5", labelcolor="w")
    if np.isfinite(maps.large_frequency).any():
        ax.text(
            0.52,
            0.80,
            f"exact: ω from {np.nanmin(maps.large_frequency):.4f}\nto {np.nanmax(maps.large_frequency):.4f} rad/sample\n"
            f"eq. 44: ω = {np.nanmax(maps.large_frequency_closed):.5f}",
            transform=ax.transAxes,
            fontsize=7,
            color="k",
        )
    ax.set_title(f"μ = {maps.mu:g}: large unstable cycles (exact D, eq. 41)", fontsize=9)
    line = CriticalLine(0.0)  # the maps' loop has no delay: region boundaries β = ½, σ = ½ (eq. 10)
    for ax in axes:
        ax.axvline(line.beta0, color="k", ls="-.", lw=0.8)
        ax.axhline(line.sigma0, color="k", ls="-.", lw=0.8)
        ax.set_xlabel(BETA_LABEL)
        ax.set_ylabel(SIGMA_LABEL)
        ax.set_xlim(maps.beta[0], maps.beta[-1])
        ax.set_ylim(maps.sigma[0], maps.sigma[-1])
    return axes


def nyquist_plot(nyq, ax=None, *, cycles=None):
    """Nyquist plot of the loop L(jω; M) against the critical locus −1/D(M), cycles marked (paper Fig. 6).

    Parameters
    ----------
    nyq : NyquistLocusResponse
    cycles : LimitCycleResult, optional
        Cycles to mark (stable: filled circle, unstable: open circle).
    """
    ax = _axes(ax, figsize=(5.5, 4.5))
    for amp, curve in zip(nyq.amplitudes, nyq.curves, strict=False):
        lab = "L(jω)" if np.isnan(amp) else f"L(jω; M = {amp:.3g})"
        ax.plot(curve.real, curve.imag, lw=1.1, label=lab)
    ax.plot(
        nyq.locus.real,
        np.zeros_like(nyq.locus.real),
        color="#b2182b",
        lw=3,
        alpha=0.6,
        label=f"−1/D(M), M in [{nyq.locus_amplitude[0]:.2g}, {nyq.locus_amplitude[-1]:.2g}]",
    )
    if cycles is not None:
        from .loop import loop_response

        for c in cycles.cycles:
            pt = loop_response(
                nyq.params, c.frequency, c.amplitude, model=nyq.model, delay=nyq.delay, pade_order=nyq.pade_order
            )
            ax.plot([pt.real], [pt.imag], "o", mfc="k" if c.stable else "w", mec="k", ms=6)
        ax.plot([], [], "o", mfc="k", mec="k", label="stable cycle")
        ax.plot([], [], "o", mfc="w", mec="k", label="unstable cycle")
    lim = 1.6 * float(np.max(np.abs(nyq.locus)))  # the locus ends near −1/0.637: zoom on it
    ax.set_xlim(-lim, 0.4 * lim)
    ax.set_ylim(-lim, 0.4 * lim)
    ax.set_aspect("equal")
    ax.axhline(0, color="0.6", lw=0.5)
    ax.axvline(0, color="0.6", lw=0.5)
    ax.set_xlabel("Re L (force ticks per position tick)")
    ax.set_ylabel("Im L (force ticks per position tick)")
    ax.set_title(
        f"Nyquist: {nyq.model} model, μ = {nyq.params.mu:.4g}, β = {nyq.params.beta:.3g}, σ = {nyq.params.sigma:.3g}",
        fontsize=9,
    )
    ax.legend(fontsize=7, loc="lower left")
    return ax


def stiffness_plot(curve, ax=None):
    """Criterion stiffness limit against impact speed, with the published bounds (eq. 8, 9, 11).

    Parameters
    ----------
    curve : StiffnessResponse
        From :func:`dfa.stiffness.stiffness_response`.
    """
    ax = _axes(ax, figsize=(6.0, 4.0))
    u = curve.device.units
    d = getattr(curve, "delay", 0)
    cs = "2b/T" if d == 0 else f"b/(T(½ + {d}))"
    ax.loglog(
        curve.velocity,
        curve.k_max,
        color="#2166ac",
        lw=2,
        label="criterion K_max (eq. 11)" + (f", delay {d}" if d else ""),
    )
    ax.axhline(curve.k_static, color="#4d9221", ls="-.", lw=1, label="2c/Δ (eq. 9, at rest)")
    ax.axhline(curve.k_colgate, color="#b2182b", ls="--", lw=1, label=f"Colgate-Schenkel {cs}")
    ax.axhline(curve.k_abbott_okamura, color="#762a83", ls=":", lw=1.5, label=f"Abbott-Okamura min({cs}, 2c/Δ)")
    ax.axhline(
        curve.k_gil,
        color="0.3",
        ls=(0, (5, 1, 1, 1)),
        lw=1,
        label="exact linear bound (no encoder, no friction" + (f", delay {d})" if d else ")"),
    )
    if curve.stiffness is not None:
        ax.axhline(curve.stiffness, color="k", lw=1.2, label=f"chosen K = {curve.stiffness:.4g} {u['stiffness']}")
        if curve.max_passive_velocity is not None and np.isfinite(curve.max_passive_velocity):
            ax.axvline(curve.max_passive_velocity, color="k", lw=0.8, ls=":")
            ax.plot([curve.max_passive_velocity], [curve.stiffness], "o", color="k", ms=5)
    ax.set_xlabel(f"impact speed |ẋ0| ({u['velocity']})")
    ax.set_ylabel(f"stiffness K ({u['stiffness']})")
    ax.set_title(f"{curve.device.name}: largest passive stiffness", fontsize=9)
    ax.legend(fontsize=7, loc="lower left")
    ax.grid(True, which="both", alpha=0.3)
    return ax


def stiffness_speed_plot(chart, ax=None):
    """Largest safe impact speed against stiffness K, four ways, with the closed-form bounds (issue 14 §2).

    Parameters
    ----------
    chart : StiffnessSpeedChart
        From :func:`dfa.speed_chart.stiffness_speed_chart`.
    """
    ax = _axes(ax, figsize=(7.0, 4.6))
    u = chart.device.units
    floor = float(chart.speeds[0]) / 2.0  # "not even the slowest simulated speed" is drawn here

    def show(v):
        return np.where(np.asarray(v) < floor, floor, v)

    ax.plot(
        chart.criterion_stiffness, show(chart.v_criterion), color="#2166ac", lw=2.2, label="criterion (eq. 11, proof)"
    )
    ax.plot(
        chart.stiffness,
        show(chart.v_df),
        color="#e08214",
        lw=1.5,
        ls="--",
        marker="^",
        ms=4,
        label="describing function (growth speed)",
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
        label="simulation: comes to rest",
    )
    _bound_lines(ax, chart)
    _design_marks(ax, chart, floor)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(floor / 1.3, chart.v_top * 1.3)
    ax.set_xlim(chart.stiffness[0], chart.stiffness[-1])
    ax.set_xlabel(f"stiffness K ({u['stiffness']})")
    ax.set_ylabel(f"largest safe impact speed ({u['velocity']})")
    d = chart.delay
    title = f"{chart.device.name}: how stiff for which impact speed" + (f" (delay {d})" if d else "")
    ax.set_title(
        title + f"\nspeeds up to {chart.v_top:g} {u['velocity']}; bottom edge: not even "
        f"{chart.speeds[0]:.3g} {u['velocity']}",
        fontsize=9,
    )
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    return ax


def _bound_lines(ax, chart) -> None:
    """The closed-form stiffness bounds of the stiffness-speed chart as labelled vertical lines."""
    d = chart.delay
    cs = "2b/T" if d == 0 else f"b/(T(½ + {d}))"
    lines = [
        (chart.k_abbott_okamura, dict(color="#c2a5cf", lw=5, alpha=0.7), f"Abbott–Okamura min({cs}, 2c/Δ)"),
        (chart.k_colgate, dict(color="#762a83", lw=1.4, ls="--"), f"Colgate–Schenkel {cs}"),
        (chart.k_linear, dict(color="k", lw=1.0, ls=(0, (1, 1.5))), "exact linear bound (no encoder, no friction)"),
        (chart.k_static, dict(color="#4d9221", lw=1.2, ls="-."), "static limit 2c/Δ (eq. 9)"),
    ]
    for k, style, label in lines:
        if k > 0:
            ax.axvline(k, label=f"{label}: {k:.4g}", **style)


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
            label=f"design point K = {chart.design_stiffness:.4g}, V = {chart.design_velocity:.3g}",
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
    ax.text(8.3, floor * 1.5, "8 samples", fontsize=7, color="0.3")
    ax.set_xlabel("predicted period (samples)")
    ax.set_ylabel("|simulated/predicted − 1| (%)")
    ax.set_title("Describing function vs exact simulation, stable cycles", fontsize=9)
    ax.legend(fontsize=7, loc="lower right")
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
    ax.set_xticklabels([r["name"] for r in rows], rotation=20, ha="right", fontsize=7)
    ax.set_ylabel("critical speed ξ'0 (ticks per sample)")
    ax.set_title("Critical impact speed, three ways", fontsize=9)
    ax.legend(fontsize=7)
    return ax
