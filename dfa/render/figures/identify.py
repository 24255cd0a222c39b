"""A logged run against its identified model: ticks over time, residual below."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from .style import legend_outside

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
    legend_outside(top)
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
