"""A simulated trajectory: displacement in ticks against time (paper Fig. 5, right)."""

from __future__ import annotations

import numpy as np

from .style import new_axes


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
    ax = new_axes(ax, figsize=(6.0, 3.2))
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
