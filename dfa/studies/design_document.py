"""The design report as Markdown (Jinja2 template) and as self-contained HTML (markdown-it-py).

Everything here reads a :class:`~dfa.studies.design.DesignAnalysis`; nothing computes a number the analysis does not
hold, and nothing writes files (:func:`dfa.studies.report.design_report` does, atomically).
"""

from __future__ import annotations

import base64
import html
from collections.abc import Callable, Mapping
from functools import lru_cache
from typing import Any

from ..errors import DFAValueError
from ..formatting import markdown_table, number, percent
from ..model.elements import Coverage, OneSided
from ..render.answer import recommendation_text
from ..render.contact import contact_text
from ..render.hand import grasp_text, grip_rows, grip_text, held_name, moving_symbols
from ..render.limits import spring_passive_text, spring_verdict_text
from ..render.start_state import start_state_clause
from ..render.text import growth_meaning, outside_searched_mu, search_why
from ..results.status import SearchStatus
from .design import DesignAnalysis

__all__ = ["design_html", "design_markdown", "markdown_to_html"]

_CSS = (
    "body{font-family:-apple-system,Segoe UI,Helvetica,Arial,sans-serif;max-width:980px;margin:2em auto;padding:0 1em;"
    "color:#222;line-height:1.45}table{border-collapse:collapse;margin:0.8em 0;font-size:0.92em}"
    "th,td{border:1px solid #ccc;padding:0.3em 0.6em;text-align:left}th{background:#f3f3f3}"
    "img{max-width:100%}h1{border-bottom:2px solid #2166ac}code{background:#f3f3f3;padding:0 0.2em}"
)


def _samples(n: int) -> str:
    return f"{n} sample{'s' if n != 1 else ''}"


def verdict_text(a: DesignAnalysis) -> str:
    """The verdict paragraph: what the criterion proves, at which speed and delay, and what simulation found."""
    if not a.covers(Coverage.CLOSED_FORM):
        return controller_verdict_text(a)
    dev, crit, lim, k, v = a.device, a.criterion, a.limits, a.stiffness, a.velocity
    assert crit is not None and lim is not None
    u = dev.units
    ds = f"a computational delay of {_samples(a.delay)}"
    if crit.passive:
        verdict = f"passive (proven: the energy cannot grow{start_state_clause(crit.wall)})"
    elif lim.velocity_status == "none":
        verdict = f"no passivity guarantee even at rest (K > 2c/Δ = {lim.k_static:.5g} {u['stiffness']})"
    else:
        verdict = "not proven passive (the criterion gives no guarantee; that is not a proof of instability)"
    text = (
        f"**Verdict.** With K = {k:g} {u['stiffness']}, an impact speed of {v:g} {u['velocity']} and {ds}, the {held_name(dev)} is "
        f"**{verdict}** (region {crit.region}: {crit.status.message}). "
    )
    if crit.critical_velocity:
        text += f"The criterion guarantees passivity up to {number(crit.critical_velocity)} {u['velocity']}; "
    text += (
        f"{'at' if crit.critical_velocity else 'At'} {v:g} {u['velocity']} with {ds} the largest passive stiffness "
        f"is {lim.k_max:.5g} {u['stiffness']}. "
    )
    return text + _simulated_text(a)


def _simulated_text(a: DesignAnalysis) -> str:
    """What the speed scan of exact simulations found (with the controller, if any)."""
    u = a.device.units
    with_ctl = "" if a.covers(Coverage.CLOSED_FORM) else " with the controller"
    if a.simulated_xi_dot:
        return (
            f"In exact simulation{with_ctl} an impact at {number(a.simulated_velocity)} {u['velocity']} diverges: the "
            "lowest unstable speed of a 40-point scan, refined by bisection; stability need not be monotone in speed, "
            "so slower impacts between scan points may diverge too."
        )
    return (
        f"No impact speed of a 40-point scan up to 30 times the reference speed diverged in exact simulation{with_ctl}."
    )


def _one_sided(a: Any) -> bool:
    """True for a one-sided wall's analysis (runs start with the approach)."""
    wall = getattr(a, "wall", None)
    return wall is not None and not wall.covers(Coverage.SURFACE_START)


def _not_linear(a: Any) -> bool:
    """True when the linear loop does not cover the analysis's wall (one-sided, a passivity controller): no
    describing function."""
    wall = getattr(a, "wall", None)
    return wall is not None and not wall.linear


def _extended_to(wall: Any) -> str:
    """What the criterion is extended to, in words."""
    return (
        "the damper, filter and delay"
        if wall.covers(Coverage.SURFACE_START)
        else "a one-sided wall reached from free space"
    )


def controller_verdict_text(a: DesignAnalysis) -> str:
    """The verdict with a wall controller: the extended criterion (or "not covered"), its K_max, simulation."""
    from ..render.controller import NOT_COVERED, not_covered_why

    dev, u, ctl, chk = a.device, a.device.units, a.wall, a.check
    text = (
        f"**Verdict.** With the wall controller below (K = {a.stiffness:g} {u['stiffness']}, virtual damping "
        f"B = {ctl.damping:g} {u['damping']}), an impact speed of {a.velocity:g} {u['velocity']} and a computational "
        f"delay of {_samples(a.delay)}"
        + (f", a {contact_text(ctl, u)}" if ctl.element(OneSided) is not None else "")
        + f", the {held_name(dev)} is "
    )
    r = chk.criterion
    if r is None:
        text += f"**{NOT_COVERED}**: {not_covered_why(chk)}. "
    else:
        verdict = (
            f"passive (proven: the energy cannot grow{start_state_clause(r.wall)})"
            if r.passive
            else "not proven passive (the extended criterion gives no guarantee; that is not a proof of instability)"
        )
        text += (
            f"**{verdict}** by the criterion of eq. 6 extended to {_extended_to(ctl)} (region {r.region}: "
            f"{r.status_message}). "
        )
        if r.critical_velocity:
            text += f"It guarantees passivity up to {number(r.critical_velocity)} {u['velocity']}. "
    lim = a.design_answer
    if lim is not None and lim.k_criterion.value is not None:
        text += (
            f"With this B, filter and delay the largest stiffness it proves passive at {a.velocity:g} {u['velocity']} "
            f"is {lim.k_criterion.value:.5g} {u['stiffness']}. "
        )
    return text + _simulated_text(a)


def spring_only_text(a: DesignAnalysis) -> str:
    """Which sections a report with a controller leaves out, and why ('' for the spring)."""
    if a.covers(Coverage.CLOSED_FORM):
        return ""
    return (
        "Not in this report: the criterion of eq. 6 for the bare spring with its stiffness limits (eq. 8–11), the "
        "stiffness–speed chart, and the stiffness figure (the regions figure below is the extended criterion's, "
        "where one covers the wall). The closed forms hold for the "
        "paper's spring (B = 0, no velocity filter, ideal amplifier), not for this controller; `dfa report` "
        "without the controller flags writes them (a separate file), and `dfa stiffness --plot` with the same flags "
        "draws this controller's stiffness–speed chart. "
        "Everything below is computed with the controller; the device table's μ, β, σ are the device's groups at K "
        "(paper Table 1)."
    )


def outcome_text(a: DesignAnalysis) -> str:
    """The simulated outcome at the design speed in words, with force step and frequency in physical units."""
    r, dev, u = a.outcome, a.device, a.device.units
    head = f"**Simulated impact at {a.velocity:g} {u['velocity']}** ({r.samples_run} of {r.samples} samples): "
    if r.outcome == "rest":
        rest = r.rest_sample if r.rest_sample is not None else r.samples_run  # a run at rest has its rest sample
        return head + f"the device comes to rest at sample {rest} ({number(rest * dev.period)} s)."
    if r.outcome == "unstable":
        return head + "the motion diverges (unstable)."
    if r.outcome == "left":
        return head + "the device leaves the one-sided wall for good (outside, moving away, nothing brings it back)."
    ph: dict[str, Any] = r.physical(dev, a.stiffness)
    step = (
        f"the force toggles over {r.force_peak_to_peak:.3g} KΔ peak-to-peak ({number(ph['force_peak_to_peak_si'])} "
        f"{ph['force_unit']})" + (f" at {ph['frequency_hz']:.4g} Hz" if ph["frequency_hz"] else "")
    )
    if r.outcome == "chatter":
        return head + (
            f"chatter: the device never comes to rest; {step} with a motion of {r.amplitude:.2g} ticks, "
            "a buzz the user feels."
        )
    if r.outcome == "oscillating":
        return head + (
            f"a persistent oscillation of {r.amplitude:.3g} ticks ({number(ph['amplitude_si'])} {u['position']}); {step}."
        )
    return head + (
        f"undecided: the motion is still changing at the end of the run (last {r.amplitude:.3g} ticks); "
        f"about {r.suggested_samples} samples would be needed to tell."
    )


def device_rows(a: DesignAnalysis) -> list[list[str]]:
    """Rows of the device table; a rotary device's first row is its inertia (kg·m²), not a mass."""
    dev, p, u = a.device, a.params, a.device.units
    m, b = moving_symbols(dev)
    mass = ("inertia J" if dev.rotary else "mass m") + (" + m_h" if dev.hand is not None else "")
    return [
        [mass, f"{dev.mass:g} {u['mass']}"],
        ["viscous damping " + b.strip("()"), f"{dev.damping:g} {u['damping']}"],
        *([["grasp", grasp_text(dev).removeprefix("grasp: ")]] if dev.hand is not None else []),
        ["Coulomb friction c", f"{dev.coulomb:g} {u['force']}"],
        ["encoder resolution Δ", f"{dev.resolution:.4g} {u['resolution']}"],
        ["sample period T", f"{dev.period:.4g} s ({1 / dev.period:.4g} Hz)"],
        ["stiffness K", f"{a.stiffness:g} {u['stiffness']}"],
        [f"μ = {m}/(K T²)", f"{p.mu:.5g}"],
        [f"β = {b}/(K T)", f"{p.beta:.5g}"],
        ["σ = c/(K Δ)", f"{p.sigma:.5g}"],
    ]


def catalogue_text(a: DesignAnalysis) -> str:
    """The printed (μ, β, σ) of a device and their disagreements ('' without them): the paper's for the
    catalogue's own rows, "your source" for a device file's."""
    c = a.catalogue
    if not c:
        return ""
    dis = c["discrepancies"]
    return (
        ("Paper Table 2 prints " if c.get("paper", True) else "Your source prints ")
        + ", ".join(f"{sym} = {val}" for sym, val in c["printed"])
        + (
            "; disagreements with the recomputed values: " + "; ".join(dis) + "."
            if dis
            else "; the recomputed values agree."
        )
        + (f" Note: {c['notes']}" if c["notes"] else "")
    )


def limits_rows(a: DesignAnalysis) -> list[list[str]]:
    """Rows of the passivity and stiffness-limits table."""
    crit, lim, u = a.criterion, a.limits, a.device.units
    assert crit is not None and lim is not None
    crit_speed = (
        "none"
        if crit.critical_xi_dot is None
        else f"{crit.critical_xi_dot:.4g} ticks/sample = {number(crit.critical_velocity)} {u['velocity']}"
    )
    return [
        ["impact speed ẋ0", f"{a.velocity:g} {u['velocity']} = {crit.xi_dot:.4g} ticks/sample"],
        ["region (paper Fig. 3)", f"{crit.region}: {crit.status.message}"],
        ["computational delay d", _samples(a.delay)],
        [
            "passive (eq. 6)",
            "yes (proven: the energy cannot grow)" if crit.passive else "no guarantee (not a proof of instability)",
        ],
        ["start state", crit.start_state],
        ["margin (β − ½ − d)|ξ'0| + (σ − ½)", f"{crit.margin:.4g}"],
        ["critical speed (eq. 12)", crit_speed],
        ["K_max at this speed (eq. 11)", f"{lim.k_max:.5g} {u['stiffness']}"],
        ["2c/Δ (eq. 9, at rest)", f"{lim.k_static:.5g} {u['stiffness']}"],
        ["Colgate–Schenkel 2b/T (eq. 8)", f"{lim.k_colgate:.5g} {u['stiffness']}"],
        ["Abbott–Okamura min(2b/T, 2c/Δ)", f"{lim.k_abbott_okamura:.5g} {u['stiffness']}"],
        [
            "exact linear bound of the sampled spring (all Jury conditions; Gil et al. where binding)",
            f"{lim.k_gil:.5g} {u['stiffness']}",
        ],
        [f"largest passive speed at K = {a.stiffness:g}", spring_passive_text(lim)],
        ["verdict for this K at this speed", spring_verdict_text(lim)],
    ]


def cycle_rows(a: DesignAnalysis) -> list[list[str]]:
    """One row per predicted limit cycle of each loop model, in ticks and in physical units."""
    dev, u = a.device, a.device.units
    return [
        [
            m,
            f"{c.amplitude:.5g}",
            f"{c.amplitude * dev.resolution:.3g} {u['position']}",
            f"{c.frequency:.4g}",
            f"{1 / (c.period * dev.period):.4g} Hz",
            "stable" if c.stable else "unstable",
            c.family + (" (period < 8 samples)" if c.few_samples else ""),
        ]
        for m, g in a.thresholds
        for c in g.result.cycles
    ]


#: The limit-cycle section of a one-sided wall's report.
NOT_LINEAR = (
    "No describing function: a one-sided wall is not a linear loop (it pushes only inside and leaves the wall), "
    "so first-harmonic cycles do not describe it; the exact simulation below does (`dfa map --one-sided`)."
)
NOT_LINEAR_PC = (
    "No describing function: a passivity controller is not a linear loop (its damper switches with the observed "
    "energy), so first-harmonic cycles do not describe it; the exact simulation below does."
)


def absence_lines(a: DesignAnalysis) -> list[str]:
    """Sentences for loop models without cycles: never an absence the search did not prove."""
    if _not_linear(a):
        return [NOT_LINEAR if _one_sided(a) else NOT_LINEAR_PC]
    out = []
    for m, g in a.thresholds:
        res = g.result
        why = search_why(res)
        if res.cycles:
            if not res.complete:
                out.append(
                    f"{m} loop: search incomplete beyond M = {res.max_amplitude:g} ticks ({why}); more cycles may exist."
                )
            continue
        if res.status is SearchStatus.FREQUENCY_RANGE:
            out.append(f"{m} loop: no limit-cycle search: {outside_searched_mu(res.mu)}.")
        elif not res.complete:
            out.append(
                f"{m} loop: no limit cycle found up to M = {res.max_amplitude:g} ticks (search incomplete: {why})."
            )
        elif res.linear_stable is False:
            out.append(
                f"{m} loop: no limit cycle predicted, but the linear loop without encoder and Coulomb friction (exact ZOH model) "
                "is unstable: amplitudes grow without bound."
            )
        else:
            out.append(f"{m} loop: no limit cycle is predicted (search complete).")
    return out


def growth_text(a: DesignAnalysis) -> str:
    """The exact-ZOH growth threshold, or band for a cluster, with its meaning ('' when there is none)."""
    if _not_linear(a):
        return ""
    g, u = a.threshold("zoh"), a.device.units
    if g.amplitude is None:
        return ""
    if g.is_band:
        return (
            f"**Growth band** (exact ZOH loop): {g.unstable_count} unstable cycles from M = {g.amplitude:.4g} to {g.amplitude_high:.4g} ticks "
            f"({number(g.position)} to {number(g.position_high)} {u['position']}); speeds M·ω = {g.xi_dot:.4g} to {g.xi_dot_high:.4g} ticks/sample "
            f"= {number(g.velocity)} to {number(g.velocity_high)} {u['velocity']}. {growth_meaning(g)}"
        )
    return (
        f"**Growth threshold** (exact ZOH loop): M_u = {g.amplitude:.4g} ticks ({number(g.position)} {u['position']}); "
        f"the matching impact speed is M_u·ω = {g.xi_dot:.4g} ticks/sample = {number(g.velocity)} {u['velocity']}. {growth_meaning(g)}"
    )


def trust_rows(a: DesignAnalysis) -> list[list[str]]:
    """Critical impact speed four ways: criterion, describing function (two loop models), exact simulation."""
    u, v_sim = a.device.units, a.simulated_xi_dot
    rows = [_criterion_speed_row(a)]
    for m, t in a.thresholds:
        m = "exact ZOH" if m == "zoh" else m
        band = t.is_band
        rows.append(
            [
                f"describing function, {m}" + (" (growth band)" if band else ""),
                number(t.xi_dot) + (f" to {number(t.xi_dot_high)}" if band else ""),
                number(t.velocity) + (f" to {number(t.velocity_high)}" if band else "") + f" {u['velocity']}",
            ]
        )
    sim = f"{number(a.simulated_velocity) if v_sim else '–'} {u['velocity']}"
    start = "after the approach from free space" if _one_sided(a) else "from ξ0 = 0"
    rows.append([f"exact simulation (bisection on ξ'0, {start})", number(v_sim), sim])
    return rows


def _criterion_speed_row(a: DesignAnalysis) -> list[str]:
    """The criterion's critical speed (the extended criterion's with a controller; "not covered" with a lag)."""
    u = a.device.units
    if a.covers(Coverage.CLOSED_FORM) and a.criterion is not None:
        crit = a.criterion
        return [
            "criterion (eq. 12), guaranteed",
            number(crit.critical_xi_dot),
            f"{number(crit.critical_velocity)} {u['velocity']}",
        ]
    from ..render.controller import NOT_COVERED

    r = a.criterion
    if r is None:
        return ["extended criterion, guaranteed", "–", NOT_COVERED]
    return [
        "extended criterion (eq. 12 with the damper, filter and delay), guaranteed",
        number(r.critical_xi_dot),
        f"{number(r.critical_velocity)} {u['velocity']}",
    ]


def _critical_xi_dot(a: DesignAnalysis) -> float | None:
    return None if a.criterion is None else a.criterion.critical_xi_dot


def trust_text(a: DesignAnalysis) -> str:
    """How conservative the criterion is and how close the describing function comes, for this device."""
    v_sim, crit_xi = a.simulated_xi_dot, _critical_xi_dot(a)
    g = None if _not_linear(a) else a.threshold("zoh")
    msg = []
    if v_sim and crit_xi:
        name = "The criterion" if a.covers(Coverage.CLOSED_FORM) else "The extended criterion"
        msg.append(f"{name} is conservative by a factor {v_sim / crit_xi:.3g} for this device")
    if v_sim and g is not None and g.xi_dot:
        msg.append(
            f"the describing function's threshold is within {100 * abs(g.xi_dot / v_sim - 1):.2g} % of the simulated one"
        )
    return "; ".join(msg) + "." if msg else ""


def validation_text(a: DesignAnalysis) -> str:
    """The validation paragraph, from the summary passed to the analysis ('' without one)."""
    s = a.validation
    if not s:
        return ""
    return (
        f"Across the validation set (`dfa validate`): {s['soundness_violations']} of {s['soundness_passive']} points the "
        f"criterion calls passive went unstable in simulation; the criterion rejects {100 * s['conservatism']:.0f} % of the points that "
        f"came to rest; the describing function's growth threshold is within a median {percent(s['speed_df_median_error'])} "
        f"of the simulated critical speed; stable cycles with periods under 8 samples are poorly predicted (median frequency error "
        f"{percent(s['short_period_frequency_error'])})."
    )


def _figure_markdown(captions: Mapping[str, str], src: Callable[[str], str]) -> Callable[[str], str]:
    def figure(name: str, optional: bool = False) -> str:
        if optional and name not in captions:  # e.g. no regions figure where no criterion covers the wall
            return ""
        return f"![{captions[name]}]({src(name)})\n\n*{captions[name]}*"

    return figure


@lru_cache(maxsize=1)
def _template() -> Any:
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("dfa.render", "templates"),
        autoescape=False,  # Markdown, not HTML: markdown-it escapes when it renders HTML
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
    )
    return env.get_template("design_report.md.j2")


def answer_rows(a: DesignAnalysis) -> list[list[str]]:
    """Rows of the report's design answer: K_max four ways at the design speed, each with what it rests on in a
    few words (the full evidence goes below the table, :func:`evidence_markdown`)."""
    from ..render.limits import limit_text

    ans = a.design_answer
    assert ans is not None
    ku = a.device.units["stiffness"]
    return [
        ["criterion (eq. 11; a proof)", limit_text(ans.k_criterion, ku)],
        ["exact linear bound (no encoder, no friction)", limit_text(ans.k_linear, ku)],
        ["describing function (growth speed >= V; first harmonic)", limit_text(ans.k_df, ku)],
        ["simulation: no simulated impact up to V diverges", limit_text(ans.k_sim, ku)],
        ["simulation: every simulated impact up to V rests", limit_text(ans.k_sim_rest, ku)],
    ]


def evidence_markdown(r: Any) -> str:
    """What a K_max table's simulated limits rest on, as a Markdown list below the table (its cells stay short).

    Parameters
    ----------
    r : dfa.analysis.limits.kmax.KMaxResult
        The answer the table shows.

    Returns
    -------
    str
    """
    from ..render.limits import evidence_lines

    items = []
    for line in evidence_lines(r):
        what, _sep, text = line.partition(": ")
        items.append(f"- **{what[0].upper()}{what[1:]}:** {text}.")
    return "What the simulated limits rest on:\n\n" + "\n".join(items)


def zwidth_rows(a: DesignAnalysis) -> list[list[str]]:
    """Rows of the report's Z-width: K_max(B) per method at each B of the grid ("-": undefined, see the JSON)."""
    import math

    from ..results.codes import ZWIDTH_METHODS

    z = a.zwidth
    assert z is not None
    cols = [z.boundary(m) for m in ZWIDTH_METHODS]
    return [
        [number(float(b), 4)] + [number(None if not math.isfinite(c[i]) else float(c[i]), 4, none="-") for c in cols]
        for i, b in enumerate(z.damping)
    ]


ZWIDTH_HEADER = ("linear", "Colgate–Schenkel", "criterion (proof)", "describing fn", "sim: no divergence", "sim: rest")


def _controller_parts(a: DesignAnalysis) -> dict[str, str]:
    """The template's controller sections (empty strings for the spring: its report is unchanged)."""
    from ..render.controller import check_table_rows, controller_limit_rows, controller_line, controller_rows

    keys = ("controller_line", "controller_table", "check_table", "climits_table", "climits_evidence", "spring_only",
            "with_ctl")  # fmt: skip
    if a.covers(Coverage.CLOSED_FORM):
        return dict.fromkeys(keys, "")
    dev, u = a.device, a.device.units
    lim = a.design_answer
    line = controller_line(a.wall, dev.period, u, dev.resolution)
    if a.wall.element(OneSided) is not None:
        line += f". Contact: {contact_text(a.wall, u)}; every simulated impact starts with the approach"
    return dict(
        controller_line=line,
        controller_table=markdown_table(["quantity", "value"], controller_rows(a.wall, dev.period, u, dev.resolution)),
        check_table=markdown_table(["quantity", "value"], check_table_rows(a.check)),
        climits_table="" if lim is None else markdown_table(
            ["largest stiffness K with this controller", "value"], controller_limit_rows(lim, u)
        ),
        climits_evidence="" if lim is None else evidence_markdown(lim),
        spring_only=spring_only_text(a),
        with_ctl=" with the controller",
    )  # fmt: skip


def _device_flags(a: DesignAnalysis) -> str:
    """The device as ``dfa export`` takes it: its catalogue name when the catalogue's device is this one, else its
    physical values (6 significant digits)."""
    from ..model.catalogue import get_device
    from ..render.identify import device_flags

    try:
        same = get_device(a.device.name).device == a.device
    except DFAValueError:
        same = False
    return f"--device {a.device.name.split()[0].lower()}" if same else device_flags(a.device)


def _configuration_parts(a: DesignAnalysis) -> dict[str, str]:
    """The configurations' table and the limiting one ('' without configurations)."""
    w = a.configurations
    if w is None:
        return {"configuration_table": "", "configuration_line": ""}
    from ..render.configurations import configuration_header, configuration_rows, limiting_line

    header = configuration_header(w)
    header[-1] = "limiting"
    return {
        "configuration_table": markdown_table(header, configuration_rows(w)),
        "configuration_line": limiting_line(w),
    }


def _tune_parts(a: DesignAnalysis) -> dict[str, str]:
    """The deployable wall's table, best wall and export command ('' without a tuning)."""
    if a.tuned is None:
        return {"tune_table": "", "tune_best": "", "export_command": "", "tune_choice": ""}
    from ..render.tune import TUNE_HEADER, best_text, choice_text, export_command, tune_rows

    return {
        "tune_table": markdown_table(["#", *TUNE_HEADER[1:]], tune_rows(a.tuned)),
        "tune_best": best_text(a.tuned),
        "export_command": export_command(a.tuned, _device_flags(a)) or "",
        "tune_choice": choice_text(a.tuned),
    }


def design_markdown(a: DesignAnalysis, captions: Mapping[str, str], src: Callable[[str], str]) -> str:
    """The report as Markdown; ``src(name)`` gives each figure's link (a relative path or a data URI).

    Parameters
    ----------
    a : DesignAnalysis
        The analysis (only read).
    captions : mapping
        Figure name → caption (:func:`dfa.studies.design_figures.design_figures`).
    src : callable
        Figure name → image address.

    Returns
    -------
    str
    """
    cycles = cycle_rows(a)
    return _template().render(
        a=a,
        verdict=verdict_text(a),
        fresh=start_state_clause(a.wall),
        recommendation=""
        if a.recommendation is None
        else recommendation_text(a.recommendation).removeprefix("recommended "),
        **_controller_parts(a),
        **_tune_parts(a),
        **_configuration_parts(a),
        device_table=markdown_table(["quantity", "value"], device_rows(a)),
        grip_text=grip_text(a.grip) if a.grip is not None else "",
        grip_table=markdown_table(["method", "least hand damping b_h", "rests on"], grip_rows(a.grip))
        if a.grip is not None
        else "",
        catalogue_text=catalogue_text(a),
        limits_table=markdown_table(["quantity", "value"], limits_rows(a)) if a.limits is not None else "",
        answer_table=markdown_table(["largest stiffness K at this speed", "value"], answer_rows(a))
        if a.design_answer is not None and a.covers(Coverage.CLOSED_FORM)
        else "",
        answer_evidence=evidence_markdown(a.design_answer)
        if a.design_answer is not None and a.covers(Coverage.CLOSED_FORM)
        else "",
        cycle_table=markdown_table(
            ["loop model", "M (ticks)", "amplitude", "ω (rad/sample)", "frequency", "stability", "family"], cycles
        )
        if cycles
        else "",
        zwidth_table=markdown_table([f"B ({a.device.units['damping']})", *ZWIDTH_HEADER], zwidth_rows(a))
        if a.zwidth is not None
        else "",
        absence=absence_lines(a),
        growth=growth_text(a),
        trust_table=markdown_table(["critical impact speed", "ticks/sample", "physical"], trust_rows(a)),
        trust_text=trust_text(a),
        validation_text=validation_text(a),
        outcome=outcome_text(a),
        figure=_figure_markdown(captions, src),
    )


def markdown_to_html(markdown: str, title: str) -> str:
    """A complete HTML page from Markdown (CommonMark + tables, raw HTML escaped), with the report's style.

    Examples
    --------
    >>> page = markdown_to_html("2 * c / Δ and b * T, **bold *nested***", "t")
    >>> "<p>2 * c / Δ and b * T, <strong>bold <em>nested</em></strong></p>" in page
    True
    """
    from markdown_it import MarkdownIt

    body = MarkdownIt("commonmark", {"html": False}).enable("table").render(markdown)
    return (
        f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
        f"<style>{_CSS}</style></head><body>{body}</body></html>\n"
    )


def design_html(a: DesignAnalysis, figures: Mapping[str, tuple[str, bytes]]) -> str:
    """The report as one self-contained HTML page: figures (name → (caption, PNG bytes)) embedded as base64."""
    captions = {n: c for n, (c, _png) in figures.items()}
    data = lambda n: "data:image/png;base64," + base64.b64encode(figures[n][1]).decode("ascii")
    return markdown_to_html(design_markdown(a, captions, data), f"dfa design report: {held_name(a.device)}")
