"""The Nyquist plot of the loop against the describing function's critical locus, cycles marked (paper Fig. 6)."""

from __future__ import annotations

import numpy as np

from .style import SMALL_FONTSIZE, legend_outside, new_axes

#: Names of the loop models in titles and captions (:func:`dfa.analysis.loop.loop_response`).
MODEL_NAMES = {"half-delay": "half-sample delay", "zoh": "exact ZOH", "pade": "Padé ZOH"}


def _cycle_points(nyq) -> list[tuple[complex, bool, float]]:
    """(point L(jω; M) of the cycle, stable, M) for each cycle the Nyquist data marks (``nyq.cycle_marks``, placed
    by the analysis on its loop)."""
    return [(c.point, c.stable, c.amplitude) for c in nyq.cycle_marks or ()]


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


def nyquist_needs_zoom(nyq) -> bool:
    """True when the cycles marked (``nyq.cycle_marks``) need an inset: a cycle below one tick, or several crossings
    within 10 % of the axis."""
    pts = _cycle_points(nyq)
    if not pts:
        return False
    if min(m for _p, _s, m in pts) < 1.0:
        return True
    (x0, x1), _y = _nyquist_limits(nyq, pts)
    xs = [p.real for p, _s, _m in pts]
    return len(xs) > 1 and (max(xs) - min(xs)) < 0.1 * (x1 - x0)


def nyquist_plot(nyq, ax=None, *, controller: str | None = None):
    """Nyquist plot of the loop L(jω; M) against the critical locus −1/D(M), cycles marked (paper Fig. 6).

    The axes are scaled to the locus, the cycles and the origin; when a cycle is below one tick or several
    crossings crowd within 10 % of the axis, an inset (upper half, above the data) zooms on them. The title names the loop model.

    Parameters
    ----------
    nyq : NyquistLocusResponse
        Its ``cycle_marks`` (``nyquist_locus_response(..., cycles=...)``) are marked (stable: filled circle,
        unstable: open circle), at the points the analysis placed them on its loop.
    controller : str, optional
        The loop's wall controller in words (e.g. ``"B = 1 N·s/m, f_c = 200 Hz, d = 1"``), named in the
        title as "… loop with {controller}" in place of the delay (default: the title names the delay only).
    """
    ax = new_axes(ax, figsize=(8.4, 4.6))
    pts = _cycle_points(nyq)
    _nyquist_draw(ax, nyq, pts, labels=True)
    if nyq.cycle_marks is not None:
        for stable, name in ((True, "stable cycle"), (False, "unstable cycle")):
            if any(s == stable for _p, s, _m in pts):
                ax.plot([], [], "o", mfc="k" if stable else "w", mec="k", label=name)
        if not pts:
            ax.plot([], [], " ", label="no limit cycle predicted")
    xlim, ylim = _nyquist_limits(nyq, pts)
    window = _inset_window(nyq, pts, xlim, ylim) if nyquist_needs_zoom(nyq) else None
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
    legend_outside(ax)
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
