"""Text of an identification from a log (:mod:`dfa.analysis.identify`): one screen, the evidence on request."""

from __future__ import annotations

import shlex
from typing import TYPE_CHECKING

from ..formatting import fill, number, text_table

if TYPE_CHECKING:
    from ..analysis.identify import Estimate, Identification

__all__ = ["identify_lines", "loop_head", "device_flags"]


def _interval(e: Estimate, unit: str) -> list[str]:
    if e.low is None or e.high is None:
        return [f"{number(e.value, 4)} {unit}", "undetermined (no reversal: only c − f₀)"]
    return [f"{number(e.value, 4)} {unit}", f"{number(e.low, 4)} … {number(e.high, 4)}"]


def identify_lines(r: Identification) -> list[str]:
    """The identified values with their intervals (quantization only), the grid, the fit and the warnings."""
    dev, u = r.device, r.device.units
    grid = (
        f"T = {number(dev.period * 1e3, 4)} ms ({'given' if r.period_given else 'from the times'}), "
        f"Δ = {number(dev.resolution, 4)} {u['resolution']} ({'given' if r.resolution_given else 'from the readings'})"
    )
    rows = [
        ["mass m" if not dev.rotary else "inertia J", *_interval(r.mass, u["mass"])],
        ["viscous damping b", *_interval(r.damping, u["damping"])],
        ["Coulomb friction c", *_interval(r.coulomb, u["force"])],
        ["force offset f₀", *_interval(r.force_offset, u["force"])],
    ]
    fit = r.fit
    lines = [
        fill(f"{r.source}: {r.samples} samples, {number(r.samples * dev.period, 4)} s; {grid}"),
        "",
        *text_table(rows, ["identified", "value", "±1.96σ, quantization only"]).splitlines(),
        fill(
            "the intervals leave out force noise, the fit's convergence and unmodelled dynamics: read them as a "
            "lower bound on the uncertainty"
        ),
        "",
        fill(
            f"fit: {100 * fit.within_one_tick:.4g} % of samples predicted within one tick of the log "
            + (f"from each {r.segment}-sample segment's start" if r.segment < r.samples else "from its start")
            + " (largest "
            f"error {fit.max_tick_error} tick{'' if fit.max_tick_error == 1 else 's'}; RMS {number(fit.rms_ticks, 3)} ticks from the tick middles, about "
            "0.29 for a perfect model)"
        ),
        fill(
            f"run once over the whole log from its start, the model predicts {100 * r.free_run.within_one_tick:.4g} "
            f"% of the samples within one tick (largest error {r.free_run.max_tick_error})"
        ),
        fill(f"status {r.status.value}: {r.status.message}"),
    ]
    lines += [fill(f"warning: {w.message}") for w in r.warnings]
    return lines


def device_flags(r: Identification) -> str:
    """The identified device as the flags of every other command (``--mass ... --period ...``)."""
    d = r.device
    parts = ["--mass", repr(round(d.mass, 6)), "--damping", repr(round(d.damping, 6)), "--coulomb",
             repr(round(d.coulomb, 6)), "--resolution", f"{d.resolution:.6g}", "--period", f"{d.period:.6g}"]  # fmt: skip
    return " ".join(shlex.quote(p) for p in parts) + (" --rotary" if d.rotary else "")


def loop_head(r: Identification, velocity: float, measured: bool) -> list[str]:
    """The line that introduces the identified device's K_max (the speed, and where it came from)."""
    u = r.device.units
    speed = f"{number(velocity, 4)} {u['velocity']}" + (" (the log's peak speed)" if measured else "")
    return ["", fill(f"the identified device at {speed}; the same with any other speed or wall: "
                     f"dfa stiffness {device_flags(r)}"), ""]  # fmt: skip
