"""Text of an identification from a log (:mod:`dfa.analysis.identify`): one screen, the evidence on request."""

from __future__ import annotations

import math
import shlex
from typing import TYPE_CHECKING

from ..formatting import fill, number, text_table

if TYPE_CHECKING:
    from ..analysis.identify import Estimate, Identification
    from ..analysis.logged_cycle import LoggedCycle

__all__ = ["identify_lines", "loop_head", "device_flags", "cycle_lines"]


def _interval(e: Estimate, unit: str) -> list[str]:
    if e.low is None or e.high is None:
        return [f"{number(e.value, 4)} {unit}", f"undetermined ({_short(e.undetermined)})"]
    return [f"{number(e.value, 4)} {unit}", f"{number(e.low, 4)} … {number(e.high, 4)}"]


def _short(why: str) -> str:
    """A few words for a table cell of why an estimate has no interval (the full reason is in the JSON)."""
    from ..analysis.identify import FRICTION_UNRESOLVED_WHY, NO_REVERSAL_WHY, SCATTER_WHY

    short = {NO_REVERSAL_WHY: "no reversal: only c − f₀", FRICTION_UNRESOLVED_WHY: "below the forces' resolution",
             SCATTER_WHY: "unbounded by the log"}  # fmt: skip
    return short.get(why, "too little motion")


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
        *text_table(rows, ["identified", "value", "95 % interval"]).splitlines(),
        fill(_interval_note(r)),
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


def _interval_note(r: Identification) -> str:
    """How the intervals were made, and what they leave out."""
    if r.bootstrap:
        how = f"from the fit and {r.bootstrap} replicate fits with the encoder's origin shifted"
    else:
        how = "from the fit's Jacobian alone (--bootstrap 0): too narrow, read them as a lower bound"
    return f"intervals {how}; they leave out noise on the force column and dynamics the model lacks"


def cycle_lines(c: LoggedCycle) -> list[str]:
    """The log's sustained oscillation next to the predicted limit cycles (:mod:`dfa.analysis.logged_cycle`)."""
    dev, u = c.device, c.device.units
    if c.logged is None:
        return ["", fill(f"oscillation: {c.status.message}")]
    lines = [""]
    if c.origin_spread > 1.0:  # the replays assume the log is of this wall
        lines.append(fill(
            f"warning: the force column is not the paper's spring of K = {number(c.stiffness, 4)} "
            f"{u['stiffness']}: the wall's origin it implies wanders by {number(c.origin_spread, 3)} ticks"))  # fmt: skip
    hz = c.logged.frequency / (2.0 * math.pi * dev.period)
    amp = c.logged.amplitude * dev.resolution
    lines.append(fill(
        f"the log ends in a sustained oscillation of {number(c.logged.amplitude, 3)} ticks "
        f"({number(amp, 3)} {u['resolution']}, ±½ tick) at {number(hz, 4)} Hz over {c.logged.periods} periods"))  # fmt: skip
    verdict = "it is the limit cycle predicted" if c.matching else "it is not one predicted"
    lines.append(fill(
        f"{verdict} for the identified device and this wall: {c.matching} of {len(c.replays)} exact replays "
        "from the fitted state end in it"))  # fmt: skip
    cycles = ", ".join(f"{number(a, 3)} ticks at {number(w / (2.0 * math.pi * dev.period), 4)} Hz"
                       for a, w in c.describing) or "none"  # fmt: skip
    lines.append(fill(f"describing function's stable cycles (eq. 36-45, exact hold): {cycles}"))
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
