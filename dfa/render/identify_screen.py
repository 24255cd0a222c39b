"""The default text of ``dfa identify``: one screen, every line under 100 characters.

The full evidence (the fit in words, each warning's reason, the noise, K_max four ways with its notes, the contact
table in full) is what ``--explain`` prints (:mod:`dfa.render.identify`) and the JSON holds; this screen keeps
the identified values with their intervals, one line on the fit, each warning in a line, the stiffness answer in
its short form (the recommendation, K_max four ways in a line, the verdict on the wall's K), the logged contact
beside the prediction and the oscillation in a few lines.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..formatting import WIDTH, fill, number, text_table
from ..model.units import hertz, position
from .answer import recommendation_line, user_verdict
from .identify import _count, _interval, _seconds, timing_lines, wall_text

if TYPE_CHECKING:
    from ..model.device import Device
    from ..results.closed_loop import ClosedLoopEvidence, ContactMeasure
    from ..results.identify import Identification, LoggedCycle, PeriodEffect
    from ..results.limits import KLimit, KMaxResult
    from ..results.require import Recommendation

__all__ = [
    "identify_screen",
    "loop_screen",
    "cycle_screen",
    "closed_loop_screen",
    "period_effect_screen",
    "poor_fit_screen",
    "kmax_line",
    "EXPLAIN_LINE",
    "WARNING_SHORT",
    "STATUS_SHORT",
]

#: The last line of the default text.
EXPLAIN_LINE = "--explain for the evidence in full: the fit, each warning's reason, the limits' notes"

#: Each warning in a few words (its full sentence is in ``--explain`` and the JSON); the noise warnings are the
#: noise line's, the poorly determined values are joined in one line.
WARNING_SHORT = {
    "no_reversal": "no reversal: the device moves one way only, so c and f₀ cannot be told apart",
    "damping_friction_confounded": "b and c not separated: the log has no motion both fast and slow",
    "little_motion": "little motion (fewer than 300 samples moving): no value gets an interval",
    "friction_unresolved": "c is below 10⁻⁴ of the largest force: the log cannot resolve it",
    "poor_fit": "poor fit: the model does not reproduce the log; its values are not to be trusted",
    "constant_force": "constant force: the log shows only b v + c = f + f₀; log a force that changes",
    "jitter": "a logged period departs from T by more than 1 %: the limits move about as much",
}

#: Each status in a few words, when no warning follows it.
STATUS_SHORT = {
    "ok": "identified; the fit reproduces the log, and every parameter is excited",
    "caveats": "identified; its caveat is the noise above",
    "poor_fit": "the model does not reproduce the log: its values are not to be trusted",
}

#: The symbols of the poorly determined values, by warning code.
_LOOSE = {"loose_mass": "m", "loose_damping": "b", "loose_coulomb": "c"}

#: The noise warnings, said by the noise line.
_NOISE = ("force_noise", "position_noise")

_SYMBOL = {"mass": "m", "damping": "b", "coulomb": "c", "force_offset": "f₀"}


def _warning_lines(r: Identification) -> list[str]:
    """Each warning in a line (the poorly determined values together), the confounded pairs in a line."""
    codes = [w.value for w in r.warnings]
    lines = [f"warning: {WARNING_SHORT[c]}" for c in codes if c in WARNING_SHORT]
    loose = [_LOOSE[c] for c in codes if c in _LOOSE]
    if loose:
        lines.append(f"warning: {', '.join(loose)} poorly determined (95 % interval wider than ±25 %, or unbounded)")
    if r.confounded:
        pairs = ", ".join(f"{_SYMBOL[a]} and {_SYMBOL[b]} ({rho:.3f})" for a, b, rho in r.confounded)
        lines.append(fill(f"warning: the log cannot tell apart {pairs}: --explain for the motion that would"))
    return lines


def _noise_line(r: Identification) -> list[str]:
    """The noise estimated on the force column and the readings, in a line (nothing when none is)."""
    u = r.device.units
    parts = []
    if r.force_noise > 0.0:
        share = number(100 * r.force_noise_relative, 2)
        parts.append(f"force {number(r.force_noise, 3)} {u['force']} ({share} % of its spread)")
    if r.position_noise > 0.0:
        parts.append(f"readings {number(r.position_noise_ticks, 2)} ticks (no limit models it)")
    if not parts:
        return []
    tail = "; in the intervals" if r.status.value != "poor_fit" else ""
    return [fill(f"noise beyond quantization: {', '.join(parts)}{tail}")]


def _fit_line(r: Identification) -> str:
    """The fit in one line: within one tick by segments and over the whole log, the RMS."""
    fit = r.fit
    seg = f"{r.segment}-sample segments" if r.segment < r.samples else "from the start"
    return fill(
        f"fit: {100 * fit.within_one_tick:.4g} % within a tick ({seg}), {100 * r.free_run.within_one_tick:.4g} % "
        f"run whole; RMS {number(fit.rms_ticks, 3)} ticks (ideal 0.29)"
    )


def identify_screen(r: Identification) -> list[str]:
    """The identification's default text: the log, the values with their intervals, the fit, the warnings.

    Parameters
    ----------
    r : Identification
        From :func:`dfa.analysis.identify.identify`.

    Returns
    -------
    list of str
        The lines, each under 100 characters; the full text is :func:`dfa.render.identify.identify_lines`.
    """
    dev, u = r.device, r.device.units
    rows = [
        ["mass m" if not dev.rotary else "inertia J", *_interval(r.mass, u["mass"])],
        ["viscous damping b", *_interval(r.damping, u["damping"])],
        ["Coulomb friction c", *_interval(r.coulomb, u["force"])],
        ["force offset f₀", *_interval(r.force_offset, u["force"])],
    ]
    grid = f"T = {number(dev.period * 1e3, 4)} ms, Δ = {number(dev.resolution, 4)} {u['resolution']}"
    timing = [fill("timing: " + _timing_short(r))] if timing_lines(r.timing) else []
    warnings = _warning_lines(r)
    status = f"status {r.status.value}" + (f", {len(warnings)} warning{'s' if len(warnings) != 1 else ''}:"
                                           if warnings else ": " + STATUS_SHORT[r.status.value])  # fmt: skip
    return [
        fill(f"{r.source}: {r.samples} samples, {number(len(r.logged) * dev.period, 4)} s; {grid}"),
        *timing,
        "",
        *text_table(rows, ["identified", "value", "95 % interval"]).splitlines(),
        _fit_line(r),
        *_noise_line(r),
        fill(status),
        *warnings,
    ]


def _timing_short(r: Identification) -> str:
    """What the time column says beyond its period, in a few words."""
    tm, parts = r.timing, []
    if tm.exceeds:
        parts.append(f"periods jitter up to {number(100 * tm.jitter_max_s / tm.period, 3)} % of T")
    if tm.dropped:
        parts.append(f"{_count(tm.dropped, 'sample')} dropped in {_count(tm.gaps, 'gap')}")
    if tm.repeated:
        parts.append(f"{_count(tm.repeated, 'repeated row')} left out")
    return ", ".join(parts)


def _k_short(lim: KLimit) -> str:
    """A limit's value (in the unit the line names), "> K" above the range searched, or "none"."""
    if lim.value is not None:
        return number(lim.value, 5)
    if lim.range_end is not None and lim.status.value == "above_range":
        return f"> {number(lim.range_end, 5)}"
    return "none"


def kmax_line(ans: KMaxResult) -> str:
    """K_max four ways in one sentence (the methods' table with its notes is ``--explain``'s).

    Parameters
    ----------
    ans : KMaxResult
        K_max four ways (:func:`dfa.analysis.limits.kmax.design_answer`).

    Returns
    -------
    str
        ``K_max (N/m): criterion …, linear …, describing function …, simulated …``: the exact linear
        bound and the simulated limit of no divergence (the rest limit is ``--explain``'s).
    """
    ku = ans.device.units["stiffness"]
    parts = [f"criterion {_k_short(ans.k_criterion)}", f"linear {_k_short(ans.k_linear)}",
             f"describing function {_k_short(ans.k_df)}"]  # fmt: skip
    if ans.k_sim.status.value != "not_simulated":
        parts.append(f"simulated {_k_short(ans.k_sim)}")
    return fill(f"K_max ({ku}): " + ", ".join(parts))


def loop_screen(ans: KMaxResult, rec: Recommendation, measured: bool) -> list[str]:
    """The stiffness answer of the cautious identified device in its short form.

    Parameters
    ----------
    ans : KMaxResult
        K_max four ways of the device with b and c at the lower ends of their 95 % intervals.
    rec : Recommendation
        The recommended stiffness.
    measured : bool
        Whether the speed is the log's peak speed (not --velocity).

    Returns
    -------
    list of str
        A blank line, the device and speed, the recommendation, K_max in a line and the verdict on the wall's K.
    """
    dev, u = ans.device, ans.device.units
    speed = f"{number(ans.velocity, 4)} {u['velocity']}" + (" (peak)" if measured else "")
    low = f"b = {number(dev.damping, 4)} {u['damping']}, c = {number(dev.coulomb, 4)} {u['force']}"
    lines = ["", fill(f"b, c at their intervals' lower ends ({low}), at {speed}:")]
    lines += [recommendation_line(rec), kmax_line(ans)]
    verdict = user_verdict(ans)
    return lines + ([verdict] if verdict else [])


def period_effect_screen(e: PeriodEffect, unit: str) -> list[str]:
    """The criterion's K_max and the recommended stiffness at the longest logged period beside their values at T.

    Parameters
    ----------
    e : PeriodEffect
        From :func:`dfa.analysis.identify.period_effect`.
    unit : str
        The stiffness unit.

    Returns
    -------
    list of str
        A line or two.
    """
    lines = [fill(f"at the longest logged period, {_seconds(e.period_max)}: the criterion's K_max "
                  f"{number(e.k_criterion_max, 5)} {unit} (at T: {number(e.k_criterion, 5)} {unit})")]  # fmt: skip
    if e.rule is None:
        return lines

    def rec(k: float | None, rule: str | None) -> str:
        return "none" if k is None else f"{number(k, 5)} {unit} ({rule})"

    return lines + [fill(f"recommended {rec(e.k_recommended_max, e.rule_max)} at the longest logged period, "
                         f"{rec(e.k_recommended, e.rule)} at T")]  # fmt: skip


def poor_fit_screen(r: Identification) -> list[str]:
    """No stiffness limits after a poor fit, in a line."""
    return ["", fill(f"no stiffness limits: the model reproduces only {100 * r.fit.within_one_tick:.3g} % of the log "
                     "within one tick")]  # fmt: skip


def cycle_screen(c: LoggedCycle) -> list[str]:
    """The log's sustained oscillation beside the predicted cycles, in a line or two."""
    dev, u = c.device, c.device.units
    if c.logged is None:
        return [fill(f"oscillation: {c.status.message}")]
    lines = []
    if c.origin_spread > 1.0:
        lines.append(fill(f"warning: the force column is not the paper's spring of K = {number(c.stiffness, 4)} "
                          f"{u['stiffness']}"))  # fmt: skip
    hz = number(hertz(dev, c.logged.frequency), 4)
    head = f"oscillation at the end: {number(c.logged.amplitude, 3)} ticks at {hz} Hz"  # the tail's, not the contact's
    amp = f"({number(position(dev, c.logged.amplitude), 3)} {u['resolution']})"
    verdict = "predicted" if c.matching else "not predicted"
    lines.append(fill(f"{head} {amp}: {verdict} ({c.matching} of {len(c.replays)} replays end in it)"))
    return lines


def _outcome(m: ContactMeasure | None, dev: Device) -> str:
    """A measure's outcome, with a cycle's amplitude and frequency."""
    if m is None:
        return "–"
    cyc = m.outcome.value in ("oscillating", "chatter", "undecided") and m.amplitude == m.amplitude
    text = m.outcome.value + (f" ({m.contact.value})" if m.contact is not None else "")
    if cyc and m.frequency == m.frequency:
        text += f", {number(m.amplitude, 3)} ticks at {number(hertz(dev, m.frequency), 4)} Hz"
    return text


def _contact_rows(m: ContactMeasure | None) -> list[str]:
    """The short column of one contact measure."""
    if m is None:
        return ["–", "–"]
    return [f"{m.impacts} / {m.contact_samples}", f"{number(m.penetration, 4)} ticks"]


def closed_loop_screen(e: ClosedLoopEvidence) -> list[str]:
    """The log taken with the wall on: the force check and the contact beside the prediction, in a few lines.

    Parameters
    ----------
    e : ClosedLoopEvidence
        From :func:`dfa.analysis.closed_loop.closed_loop_evidence`.

    Returns
    -------
    list of str
        The wall and its force check, a table of the logged and predicted contact, and the verdict.
    """
    dev, c = e.device, e.check
    share = f"{c.within * 100:.3g} % within ½ K Δ"
    check = "the wall's" if c.status.value == "consistent" else "not the wall's law (warning)"
    lines = ["", fill(f"wall on: {wall_text(e.wall, dev.units)}; force column {check} ({share})")]
    if e.predicted is None:
        return [*lines, fill(f"contact: {e.status.message}")]
    rows = [[a, *b] for a, b in zip(("impacts / samples inside", "deepest reading", "outcome"),
                                     zip(_contact_rows(e.logged) + [_outcome(e.logged, dev)],
                                         _contact_rows(e.predicted) + [_outcome(e.predicted, dev)], strict=True),
                                     strict=True)]  # fmt: skip
    head = [f"contact from sample {e.start}", "logged", "predicted"]
    lines += text_table([head, *rows], width=WIDTH).splitlines()  # no rule under the head: one screen
    after = "–" if e.eventual is None else e.eventual.value
    lines.append(fill(f"contact {e.status.value} ({e.matching} of {len(e.replays)} replays within the intervals "
                      f"match; run on, it ends {after})"))  # fmt: skip
    return lines
