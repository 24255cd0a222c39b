"""Text of an identification from a log (:mod:`dfa.analysis.identify`): one screen, the evidence on request."""

from __future__ import annotations

import shlex
from collections import Counter
from typing import TYPE_CHECKING

from ..formatting import fill, number, number_at, text_table
from ..model.units import hertz, position
from ..results.identify import POSITION_MISFIT

if TYPE_CHECKING:
    from ..model.catalogue import CatalogueEntry
    from ..model.device import Device
    from ..model.wall import Wall
    from ..results.closed_loop import ClosedLoopEvidence, ContactMeasure, WallForceCheck
    from ..results.identify import Estimate, Identification, LoggedCycle, PeriodEffect, Timing, Undetermined
    from ..results.status import IdentifyWarning

__all__ = [
    "identify_lines",
    "loop_head",
    "device_flags",
    "cycle_lines",
    "closed_loop_lines",
    "wall_text",
    "poor_fit_loop",
    "timing_lines",
    "period_effect_lines",
    "device_source",
    "device_notes",
    "device_file",
]


def _interval(e: Estimate, unit: str) -> list[str]:
    """The value and its interval to their meaningful digits (:attr:`Estimate.place`: the interval rounded
    outward); without an interval the value to 4 digits, or "–" when the log does not bound it at all (no digit
    of it is meaningful)."""
    if e.low is None or e.high is None or e.place is None:
        value = "–" if e.undetermined == "scatter" else f"{number(e.value, 4)} {unit}"
        return [value, f"undetermined ({_short(e.undetermined)})"]
    k, ends = e.place, (e.value, e.low, e.high)
    sci = any(x != 0.0 and not 1e-4 <= abs(x) < 1e6 for x in ends)  # the value and both ends alike
    value, low, high = (number_at(x, k, mode, scientific=sci) for x, mode in zip(ends, ("nearest", "down", "up"),
                                                                                   strict=True))  # fmt: skip
    return [f"{value} {unit}", f"{low} … {high}"]


#: A few words for a table cell of why an estimate has no interval, by its
#: :class:`~dfa.results.identify.Undetermined` code (the full reason, its message, is in the JSON).
UNDETERMINED_SHORT = {
    "no_reversal": "no reversal: only c − f₀",
    "friction_unresolved": "below the forces' resolution",
    "scatter": "unbounded by the log",
    "poor_fit": "poor fit",
    "little_motion": "too little motion",
    "constant_force": "constant force",
}


def _short(why: Undetermined | None) -> str:
    """A few words for a table cell of why an estimate has no interval (:data:`UNDETERMINED_SHORT`)."""
    return UNDETERMINED_SHORT.get(str(why), "too little motion")


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
        fill(f"{r.source}: {r.samples} samples, {number(len(r.logged) * dev.period, 4)} s; {grid}"),
        *timing_lines(r.timing),
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
            + (
                f", across the log's {_count(r.timing.gaps, 'gap')} with their forces interpolated"
                if r.timing.gaps
                else ""
            )
        ),
        *_noise_lines(r),
        fill(f"status {r.status.value}: {r.status.message}"),
    ]
    lines += [fill(f"warning: {_warning_text(r, w)}") for w in r.warnings]
    lines += [fill(f"warning: {confounded_text(a, b, rho)}") for a, b, rho in r.confounded]
    return lines


#: What each parameter is called in a sentence.
PARAMETER_NAMES = {"mass": "the mass m", "damping": "the damping b", "coulomb": "the Coulomb friction c",
                   "force_offset": "the force offset f₀"}  # fmt: skip

#: The motion that tells each pair of parameters apart.
SEPARATING_MOTION = {
    ("mass", "damping"): "force steps faster than the time constant m/b, so that the device accelerates before its "
    "speed settles",
    ("mass", "coulomb"): "force steps that start and stop the device, at different force levels",
    ("mass", "force_offset"): "force steps of different sizes, so that the accelerations differ",
    ("damping", "coulomb"): "motion both fast and slow (forces of several levels, each held until the speed settles)",
    ("damping", "force_offset"): "motion at several speeds in both directions",
    ("coulomb", "force_offset"): "reversals: motion in both directions (friction reverses, an offset does not)",
}


def confounded_text(a: str, b: str, rho: float) -> str:
    """Which parameter the log cannot tell from which, and the motion that would."""
    return (f"the log cannot tell {PARAMETER_NAMES[a]} from {PARAMETER_NAMES[b]} (their estimates' correlation "
            f"{rho:.3f}): log {SEPARATING_MOTION[(a, b)]}")  # fmt: skip


def _misfit_ratio(r: Identification) -> float | None:
    """The residuals' mean square over the readings' white level (position noise² + 1/12, ticks²) when that is what
    made the fit poor (beyond :data:`~dfa.results.identify.POSITION_MISFIT`), else None."""
    if r.position_noise_ticks <= 0.0:
        return None
    ratio = r.fit.rms_ticks**2 / (r.position_noise_ticks**2 + 1.0 / 12.0)
    return ratio if ratio > POSITION_MISFIT else None


def _warning_text(r: Identification, w: IdentifyWarning) -> str:
    """A warning's sentence; the position noise's with its level in ticks; a poor fit's with the rule that made it."""
    if w.value == "position_noise":
        return f"{number(r.position_noise_ticks, 2)} ticks of noise on the readings (standard deviation): {w.message}"
    ratio = _misfit_ratio(r) if w.value == "poor_fit" else None
    if ratio is not None:
        return (f"poor fit: the residuals' mean square is {number(ratio, 3)} times the readings' white level (their "
                f"noise's square and quantization's 1/12), more than the {POSITION_MISFIT:g} that noise on the readings "
                "and the force column explains: a misfit whose jumps read as noise; the model does not reproduce the "
                "log")  # fmt: skip
    return w.message


def _noise_lines(r: Identification) -> list[str]:
    """The noise on the readings and on the force column that explains the residuals beyond quantization (nothing
    when none is estimated)."""
    u = r.device.units
    out = []
    if r.position_noise > 0.0:
        out.append(fill(
            f"position noise: about {number(r.position_noise_ticks, 2)} ticks ({number(r.position_noise, 3)} "
            f"{u['resolution']}) of white noise on the readings beyond their quantization, measured on the residuals' "
            "second differences; the fit's segments start off their first reading's tick"
            + (" and the intervals include it" if r.status.value != "poor_fit" else "")))  # fmt: skip
    if not r.force_noise > 0.0:
        return out
    return out + [fill(
        f"force noise: about {number(r.force_noise, 3)} {u['force']} ({number(100 * r.force_noise_relative, 2)} % of "
        "the force's standard deviation) on the force column explains the residuals beyond the encoder's "
        "quantization" + ("; the intervals include it" if r.status.value != "poor_fit" else
                          ", but the fit is poor (below)" if _misfit_ratio(r) is not None else
                          ", more than the 25 % a fit's misfit is put down to"))]  # fmt: skip


def _interval_note(r: Identification) -> str:
    """How the intervals were made, and what they leave out."""
    if all(e.low is None for e in (r.mass, r.damping, r.coulomb, r.force_offset)):
        return "no intervals: the log does not bound the values (the table says why)"
    if r.force_noise > 0.0 or r.position_noise > 0.0:
        which = " and ".join(k for k, v in (("force", r.force_noise), ("position", r.position_noise)) if v > 0.0)
        noise = f" with the {which} noise estimated below"
        how = _replicates(r, f"from the fit's Jacobian{noise} and", f" and fresh {which} noise", f",{noise}")
        return f"intervals {how}; they leave out dynamics the model lacks"
    how = _replicates(r, "from the fit and", "", "")
    return f"intervals {how}; they leave out noise on the force column and dynamics the model lacks"


def _replicates(r: Identification, with_fits: str, fresh: str, noise: str) -> str:
    """How the intervals were made, from the replicates that were fitted: ``with_fits`` and their number (their
    readings with the encoder's origin shifted and ``fresh`` noise), else the Jacobian alone (``noise``: with the
    noise estimated) and why: none asked for, none moved enough to fit, or one, whose spread is not taken."""
    if r.bootstrap >= 2:
        how = f"{with_fits} {r.bootstrap} replicate fits with the encoder's origin shifted{fresh}"
        if r.bootstrap < r.bootstrap_requested:
            how += f" ({r.bootstrap_requested - r.bootstrap} of {r.bootstrap_requested} replicates too still to fit)"
        return how
    if r.bootstrap == 1:
        return (
            f"from the fit's Jacobian alone (one replicate fit: a spread needs two){noise}: too narrow, a lower bound"
        )
    if r.bootstrap_requested:
        return f"from the fit's Jacobian alone (no replicate moved enough to fit){noise}: too narrow, a lower bound"
    return f"from the fit's Jacobian alone (--bootstrap 0){noise}: too narrow, read them as a lower bound"


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
    hz, amp = hertz(dev, c.logged.frequency), position(dev, c.logged.amplitude)
    lines.append(fill(
        f"the log ends in a sustained oscillation of {number(c.logged.amplitude, 3)} ticks "
        f"({number(amp, 3)} {u['resolution']}, ±½ tick) at {number(hz, 4)} Hz over {c.logged.periods} periods"))  # fmt: skip
    counts = Counter("diverge" if o == "unstable" else o for _b, _c, o, _a, _w in c.replays)
    counts["oscillating"] -= c.matching
    others = ", ".join(f"{n} {'another cycle' if o == 'oscillating' else o}" for o, n in sorted(counts.items()) if n)
    how = (f"{c.matching} of {len(c.replays)} exact replays (b and c across their 95 % intervals, 9 starts near the "
           f"fitted state) end in it" + (f"; the others: {others}" if others else ""))  # fmt: skip
    if c.matching:
        lines.append(fill(f"it is the limit cycle predicted for the identified device and this wall: {how}"))
    else:
        lines.append(fill(f"it is not one predicted for the identified device and this wall: {how} (another wall, "
                          "a delay or filter, values outside their intervals, or dynamics the model lacks)"))  # fmt: skip
    cycles = ", ".join(f"{number(a, 3)} ticks at {number(hertz(dev, w), 4)} Hz"
                       for a, w in c.describing) or "none"  # fmt: skip
    lines.append(fill(f"describing function's stable cycles (eq. 36-45, exact hold): {cycles}"))
    return lines


def wall_text(wall: Wall, units: dict[str, str]) -> str:
    """The logged wall in a few words: K, B, the delay, one-sided or bilateral."""
    from ..model.elements import Damper, Delay, OneSided

    damper, lag, side = wall.element(Damper), wall.element(Delay), wall.element(OneSided)
    parts = [f"K = {number(wall.stiffness, 4)} {units['stiffness']}"]
    parts += [f"B = {number(damper.damping, 4)} {units['damping']}"] if damper is not None else []
    parts += [f"delay {lag.delay} sample{'s' if lag.delay != 1 else ''}"] if lag is not None else []
    return ", ".join(parts) + (", one-sided" if side is not None else ", bilateral")


def _check_line(c: WallForceCheck) -> str:
    """The force column against the wall's law, in one sentence."""
    u = c.device.units
    head = (f"{c.within * 100:.3g} % of {c.samples} samples within ½ K Δ = {number(c.force_step, 3)} {u['force']} of "
            f"the wall's law of the readings, largest miss {number(c.max_mismatch, 2)} {u['force']}")  # fmt: skip
    if c.status.value == "consistent":
        return fill(f"force column: the wall's ({head})")
    ratio = "" if c.ratio != c.ratio else f"; logged/law where it pushes: {number(c.ratio, 3)}"
    return fill(f"warning: force column: {c.status.message} ({head}{ratio})")


def _measure_rows(m: ContactMeasure | None, dev: Device) -> list[str]:
    """One column of the contact table."""
    if m is None:
        return ["–"] * 7
    u = dev.units
    cyc = m.outcome.value in ("oscillating", "chatter", "undecided") and m.amplitude == m.amplitude
    amp = f"{number(m.amplitude, 3)} ticks ({number(position(dev, m.amplitude), 3)} {u['resolution']})" if cyc else "–"
    hz = f"{number(hertz(dev, m.frequency), 4)} Hz" if cyc and m.frequency == m.frequency else "–"
    depth = f"{number(m.penetration, 4)} ticks ({number(position(dev, m.penetration), 3)} {u['resolution']})"
    return [str(m.impacts), str(m.contact_samples), depth, m.outcome.value,
            "–" if m.contact is None else m.contact.value, amp, hz]  # fmt: skip


def closed_loop_lines(e: ClosedLoopEvidence) -> list[str]:
    """A log taken with the wall on: the force check, the logged contact beside the prediction
    (:mod:`dfa.analysis.closed_loop`)."""
    dev = e.device
    lines = ["", f"logged with the wall on: {wall_text(e.wall, dev.units)}", _check_line(e.check)]
    if e.predicted is None:
        return [*lines, fill(f"contact: {e.status.message}")]
    names = ["impacts", "samples inside", "deepest reading", "outcome", "contact", "amplitude (±½ tick)", "frequency"]
    rows = [[n, a, b] for n, a, b in zip(names, _measure_rows(e.logged, dev), _measure_rows(e.predicted, dev),
                                             strict=True)]  # fmt: skip
    speed = f"{number(e.impact_speed, 4)} {dev.units['velocity']}"
    lines.append(fill(f"contact from sample {e.start} at the fitted {speed}, against the exact simulation of the "
                      "identified device with this wall over the rest of the log:"))  # fmt: skip
    lines += text_table(rows, ["", "logged", "predicted"]).split("\n")
    after = e.eventual.value if e.eventual is not None else "–"
    contact = e.eventual_contact.value if e.eventual_contact is not None else after
    after += f" ({contact})" if contact != after else ""
    lines.append(fill(f"the simulation run on (50 000 samples or more) ends: {after}"))
    if e.replays:
        outs = ", ".join(f"{n} {o}" for o, n in sorted(Counter(o for _b, _c, o, _m in e.replays).items()))
        lines.append(fill(f"replayed with b and c at the ends of their 95 % intervals and at their values: "
                          f"{e.matching} of {len(e.replays)} reproduce the logged contact (outcomes: {outs})"))  # fmt: skip
    lines.append(fill(f"contact {e.status.value}: {e.status.message}"))
    return lines


def device_flags(d: Device) -> str:
    """A device as the flags of every other command (``--mass ... --period ...``, 6 significant digits)."""
    parts = ["--mass", f"{d.mass:.6g}", "--damping", f"{d.damping:.6g}", "--coulomb", f"{d.coulomb:.6g}",
             "--resolution", f"{d.resolution:.6g}", "--period", f"{d.period:.6g}"]  # fmt: skip
    return " ".join(shlex.quote(p) for p in parts) + (" --rotary" if d.rotary else "")


def loop_head(device: Device, velocity: float, measured: bool) -> list[str]:
    """The lines that introduce the limits of the cautious device (:meth:`Identification.cautious`)."""
    u = device.units
    speed = f"{number(velocity, 4)} {u['velocity']}" + (" (the log's peak speed)" if measured else "")
    low = f"b = {number(device.damping, 4)} {u['damping']}, c = {number(device.coulomb, 4)} {u['force']}"
    return ["", fill(f"the identified device with b and c at the lower ends of their 95 % intervals ({low}; 0 where "
                     f"undetermined), at {speed}; the same with any other speed or wall: dfa stiffness "
                     f"{device_flags(device)}"), ""]  # fmt: skip


def poor_fit_loop(r: Identification) -> list[str]:
    """What --stiffness says when the fit is poor: no limits."""
    return ["", fill(f"no stiffness limits: the identified model reproduces only {100 * r.fit.within_one_tick:.3g} % "
                     "of the log within one tick, and noise on the force column would have to be "
                     f"{number(100 * r.force_noise_relative, 2)} % of the force's spread to explain that, so no limit "
                     "computed from it would hold for the device; check the log's units and columns (is f the force "
                     "that drove x?), or the device has dynamics the model lacks")]  # fmt: skip


def _count(k: int, what: str) -> str:
    """``k`` things, plural when not one."""
    return f"{k} {what}{'' if k == 1 else 's'}"


def _seconds(x: float) -> str:
    """A time to 3 significant digits in s, ms or µs."""
    for scale, unit in ((1.0, "s"), (1e-3, "ms"), (1e-6, "µs")):
        if abs(x) >= scale * (1.0 - 5e-4):  # what rounds to 1 at 3 digits (T = 0.9999999 ms is 1 ms)
            return f"{number(x / scale, 3)} {unit}"
    return f"{number(x / 1e-9, 3)} ns"


def timing_lines(tm: Timing) -> list[str]:
    """What the time column says beyond its period: jitter beyond what the analyses absorb, dropped and repeated
    samples (nothing for a clean log)."""
    parts = []
    if tm.exceeds:
        parts.append(
            f"the periods jitter by {_seconds(tm.jitter_s)} (standard deviation), up to {_seconds(tm.jitter_max_s)} "
            f"({number(100 * tm.jitter_max_s / tm.period, 3)} % of T; longest period {_seconds(tm.period_max)}), "
            "more than the 1 % the fixed-period analyses absorb"
        )
    if tm.dropped:
        parts.append(
            f"{_count(tm.dropped, 'sample')} dropped in {_count(tm.gaps, 'gap')} (their readings left out of the fit, "
            "a segment started after each gap)"
        )
    if tm.repeated:
        parts.append(f"{_count(tm.repeated, 'repeated row')} (the time of the row before) left out")
    return [fill("timing: " + "; ".join(parts))] if parts else []


def period_effect_lines(e: PeriodEffect, unit: str) -> list[str]:
    """How the proven limit (eq. 11) and the recommended stiffness move from T to the longest logged period."""
    lines = [
        "",
        fill(
            f"at the longest logged period, {_seconds(e.period_max)} instead of T = {_seconds(e.period)}, the "
            f"criterion's K_max (eq. 11, the same device and speed) is {number(e.k_criterion_max, 5)} {unit} instead "
            f"of {number(e.k_criterion, 5)} {unit}: every limit above takes each sample to last T"
        ),
    ]
    if e.rule is None:
        return lines

    def rec(k: float | None, rule: str | None) -> str:
        return "none" if k is None else f"{number(k, 5)} {unit} ({rule})"

    lines.append(fill(
        f"recommended stiffness (the rule above; the same wall and speeds, a stiffness grid of {e.grid} points): "
        f"{rec(e.k_recommended_max, e.rule_max)} at the longest logged period, {rec(e.k_recommended, e.rule)} at T"))  # fmt: skip
    return lines


def device_source(r: Identification, date: str) -> str:
    """A device file's source: the log's name and date."""
    return f"identified by dfa identify from the log {r.source} of {date}"


def device_notes(r: Identification) -> str:
    """A device file's notes: the 95 % intervals, the fit and the warnings."""
    u = r.device.units
    rows = (("m", r.mass, u["mass"]), ("b", r.damping, u["damping"]), ("c", r.coulomb, u["force"]),
            ("f₀", r.force_offset, u["force"]))  # fmt: skip
    parts = []
    for key, e, unit in rows:
        value, interval = _interval(e, unit)
        parts.append(f"{key} = {value}, 95 % interval {interval}")
    warn = "; ".join(w.value for w in r.warnings) or "none"
    return (
        f"{'; '.join(parts)}; {r.samples} samples, {100 * r.fit.within_one_tick:.4g} % predicted within one tick; "
        f"status {r.status.value}; warnings: {warn}. The values are the identified ones; a limit that must hold "
        "takes b and c at the lower ends of their intervals (dfa identify --stiffness)."
    )


def device_file(entry: CatalogueEntry, r: Identification) -> str:
    """The device file of an identified device: the catalogue's format (:func:`device_template`, which reads back
    unchanged), under a header that says where it comes from."""
    from ..model.catalogue import device_template

    body = device_template(entry)
    head = [
        f"# The device identified by `dfa identify` from the log {r.source}: m, b, c the identified values,",
        "# Δ and T the log's; the 95 % intervals are in the notes. Use it with every command that takes a device,",
        f"#   dfa check --device-file FILE.toml --velocity {number(r.velocity_peak, 3)}",
        "# Flags given with it (--mass ... --period, --stiffness, --name) replace its values.",
        "",
        "",
    ]
    return "\n".join(head) + body[body.index("\n[[devices]]") + 1 :]
