"""Stiffness limits in words: a :class:`~dfa.analysis.limits.search.KLimit` and the evidence of a K_max answer.

The analyses (:mod:`dfa.analysis.limits`) return typed records; this module alone words them, short by
default (one line of at most a few dozen characters per limit: the value and its caveats as tags) and in full
sentences with ``explain=True`` (what the search, the sweep and the confirmation simulated).

Examples
--------
>>> from dfa.analysis.limits.search import KLimit
>>> from dfa.results.status import LimitStatus
>>> limit_text(KLimit(517.13, non_monotone=True, safe_above=(900.0,)), "N/m")
'517.13 N/m (non-monotone: safe again at 900 N/m)'
>>> limit_text(KLimit(None, LimitStatus.ABOVE_RANGE, range_end=4000.0), "N/m")
'> 4000 N/m: no failure up to the top of the range searched'
"""

from __future__ import annotations

from ..formatting import number
from ..model.elements import Coverage
from ..model.wall import WallParams
from ..results.caveats import SUBTICK_LIMIT
from ..results.limits import (
    FINE_POINTS,
    FINE_STEP,
    SWEEP_STEP,
    Confirmation,
    KLimit,
    KMaxAssessment,
    KMaxResult,
    StiffnessLimits,
)
from ..results.status import LimitStatus, StiffnessStatus, VelocityStatus
from .hand import moving_symbols
from .start_state import start_state_clause

__all__ = [
    "ABOVE_RANGE",
    "BELOW_K",
    "PROOF_NOTE",
    "assessment_rows",
    "confirmation_text",
    "counterexample_lines",
    "evidence_text",
    "evidence_lines",
    "every_speed_bound",
    "kmax_rows",
    "limit_tags",
    "limit_text",
    "none_text",
    "passive_text",
    "spring_passive_text",
    "source_text",
    "spring_verdict_text",
    "verdict_text",
    "undecided_text",
]

#: What a simulated limit does not claim: unsafe stiffnesses between the simulated ones, or other speeds.
BELOW_K = (
    "narrower unsafe bands between the swept stiffnesses, and unsafe speeds between those simulated, are not "
    "excluded: stability need not be monotone in K"
)
#: A limit above the range searched: its top is a lower bound (``"> 4000 N/m: "`` before it).
ABOVE_RANGE = "no failure up to the top of the range searched"
#: The closing line of every K_max answer.
PROOF_NOTE = "only the criterion is a proof; the others hold for the simulated speeds, starts and stiffnesses"
#: :data:`PROOF_NOTE` of a quick answer (``dfa stiffness --quick``: nothing simulated).
QUICK_PROOF_NOTE = "only the criterion is a proof; a quick answer, without the simulated limits"

#: What stopped a search at an undecided judgement, in a few words, by its code
#: (:class:`~dfa.results.status.UndecidedWhy`).
_UNDECIDED = {
    "short_runs": "undecided runs (too short to tell)",
    "subtick": f"the sub-tick caveat (smallest unstable cycle below {SUBTICK_LIMIT:g} ticks)",
    "below_reach": "a growth speed bounded only from below V (cycle search at its size budget)",
    "unknown_growth": "an unknown growth speed (a cycle search that failed)",
    "outside_mu": "μ = m/(K T²) outside the range the cycle search covers (1e-6 … 1e8)",
}


def _k(x: float, unit: str) -> str:
    return f"{number(x, 5)} {unit}"


def undecided_text(why: str | None) -> str:
    """What stopped a search at an undecided judgement (:attr:`KLimit.limited_why`), in words."""
    return _UNDECIDED.get(why or "", "an undecided judgement")


def none_text(lim: KLimit, unit: str, linear_reason: str | None = None) -> str:
    """Why a limit has no value, with the stiffness that bounds it where there is one (above the range searched:
    ``"> K_top N/m: …"``, a lower bound). A wall the linear loop does not cover says why with ``linear_reason``
    (:meth:`dfa.model.wall.Wall.linear_reason`: its element's reason, a one-sided wall, a passivity controller, a
    force limit), else with the status's general message."""
    s = lim.status
    if s is LimitStatus.NOT_LINEAR and linear_reason:
        return f"none: not covered: {linear_reason}"
    if s is LimitStatus.ABOVE_RANGE and lim.range_end is not None:
        return f"> {_k(lim.range_end, unit)}: {ABOVE_RANGE}"
    if s is LimitStatus.BELOW_RANGE and lim.range_end is not None and lim.limited_why is not None:
        return f"none: undecided already at {_k(lim.range_end, unit)}, the lowest K searched: {undecided_text(lim.limited_why)}"
    if s is LimitStatus.BELOW_RANGE and lim.range_end is not None:
        return f"none: fails already at {_k(lim.range_end, unit)}, the lowest K searched ({lim.range_verdict})"
    if s is LimitStatus.NOT_CONFIRMED and lim.range_end is not None:
        return f"none: no stiffness confirmed down to {_k(lim.range_end, unit)} ({len(lim.failures)} failing runs)"
    return f"none: {s.message}"


def _lowered(lim: KLimit, unit: str, explain: bool, vu: str) -> str:
    """Why a limit was lowered from the searched one: the lowest failure (with ``explain``: its speed, the highest
    failure and how many there were)."""
    low = min(lim.failures, key=lambda f: f.stiffness)
    searched = _k(lim.searched_value or 0.0, unit)
    if not explain:
        return f"lowered from {searched}: {low.outcome} at K = {_k(low.stiffness, unit)} ({low.start} start, {low.found_by})"
    top = max(lim.failures, key=lambda f: f.stiffness)
    upto = "" if top.stiffness == low.stiffness else f", failures up to K = {_k(top.stiffness, unit)}"
    return (
        f"lowered from the searched {searched}: the {low.found_by} found {low.outcome} at K = {_k(low.stiffness, unit)}"
        f" ({low.velocity:.3g} {vu}, {low.start} start){upto} ({len(lim.failures)} failing or undecided runs in all, "
        "none at or below the limit)"
    )


def limit_tags(lim: KLimit, unit: str, explain: bool = False, vu: str = "") -> list[str]:
    """The caveats of a found limit, each a few words (with ``explain``, the lowering in full)."""
    tags = []
    if lim.limited_by is not None:
        tags.append(f"limited by {undecided_text(lim.limited_why)} at {_k(lim.limited_by, unit)}")
    if lim.non_monotone:
        tags.append(f"non-monotone: safe again at {', '.join(number(k, 4) for k in lim.safe_above)} {unit}")
    if lim.failures and lim.searched_value is not None:
        tags.append(_lowered(lim, unit, explain, vu))
    if lim.capped_at is not None:
        tags.append(f"capped at K_sim = {_k(lim.capped_at, unit)}: coming to rest implies no divergence")
    return tags


def limit_text(
    lim: KLimit, unit: str, *, explain: bool = False, velocity_unit: str = "", linear_reason: str | None = None
) -> str:
    """One stiffness limit in words: its value and caveats, or why it has none.

    Parameters
    ----------
    lim : KLimit
        The limit.
    unit : str
        The stiffness unit (``"N/m"``; rotary ``"N·m/rad"``).
    explain : bool, optional
        Add what a confirmed limit claims (:func:`confirmation_text`).
    velocity_unit : str, optional
        The speed unit of the confirmation (with ``explain``).
    linear_reason : str or None, optional
        Why the linear loop does not cover the wall (:func:`none_text`), for a limit that needs it.

    Returns
    -------
    str
        ``"517.13 N/m"``, with caveats in parentheses; ``"none: …"`` without a value.
    """
    if lim.value is None:
        return none_text(lim, unit, linear_reason)
    txt = _k(lim.value, unit)
    tags = limit_tags(lim, unit, explain, velocity_unit)
    if tags:
        txt += f" ({'; '.join(tags)})"
    if explain and lim.confirmation is not None:
        txt += f"; confirmed: {confirmation_text(lim.confirmation, unit, velocity_unit)}"
    return txt


def _sweep_text(c: Confirmation, unit: str, velocity_unit: str) -> str:
    sw = c.sweep
    vs = c.search_speeds
    where = "K_criterion" if sw.from_criterion else "the search grid's lowest stiffness"
    fine_lo = (1.0 - FINE_STEP) ** (FINE_POINTS - 1)
    coarse = f" (coarser than {100 * SWEEP_STEP:g} %: at most {sw.max_points} stiffnesses)" if sw.coarse else ""
    below = (
        f"a sweep of {sw.points} stiffnesses from {where} = {_k(sw.start, unit)} up to K in relative steps of "
        f"{100 * sw.step:.3g} %{coarse}"
        if sw.points
        else f"no sweep below, K lies below its start, {where} = {_k(sw.start, unit)}"
    )
    return (
        f"at the {len(vs)} search speeds in [{min(vs):.4g}, {max(vs):.4g}] {velocity_unit} ({starts_text(c.starts)}), "
        f"{FINE_POINTS} stiffnesses in [{fine_lo:.4g}K, K] (steps of {100 * FINE_STEP:g} %) and {below}"
    )


#: A one-sided wall's rest limit: a run that leaves the wall for good ends its contact as one at rest does.
LEAVES = {False: "", True: " or leaves"}

#: The starts of each impact (:func:`dfa.analysis.limits.runs.starts_of`) in words: in two words, in a
#: confirmation, in a search's evidence.
START_WORDS = {
    ("impact", "preload"): (
        "both starts",
        "from ξ0 = 0 and from the preload",
        "each from ξ0 = 0 and from the energy preload",
    ),
    ("approach",): (
        "the approach",
        "each after the approach from free space",
        "each after the approach from free space",
    ),
}


def starts_text(starts: tuple[str, ...]) -> str:
    """The starts of each impact in two words: ``"both starts"`` or ``"the approach"``.

    Examples
    --------
    >>> starts_text(("approach",))
    'the approach'
    """
    return START_WORDS[tuple(starts)][0]


def confirmation_text(c: Confirmation, unit: str, velocity_unit: str) -> str:
    """What a confirmed limit K claims, in words: the dense band, the sweep below it, and what is not excluded."""
    what = "no divergence" if c.limit == "unstable" else "every run at rest" + LEAVES[c.starts == ("approach",)]
    vs = c.speeds
    return (
        f"{what}, none undecided, at {len(vs)} speeds in [{min(vs):.4g}, {max(vs):.4g}] {velocity_unit} "
        f"({START_WORDS[tuple(c.starts)][1]}) and {c.band_stiffnesses} stiffnesses in [{c.band[0]:g}K, K]; "
        f"{_sweep_text(c, unit, velocity_unit)}; {BELOW_K}"
    )


def evidence_text(r: KMaxResult) -> str:
    """How the searched limits of a K_max answer were found, in one sentence (device units)."""
    e, u = r.evidence, r.device.units
    if r.k_sim.status is LimitStatus.NOT_SIMULATED:
        return (
            f"a quick answer (--quick): no simulation; describing function over stiffnesses {e.k_range[0]:.4g} to "
            f"{e.k_range[1]:.4g} {u['stiffness']}, {e.df_model} hold model, every unstable cycle"
        )
    sp = ", ".join(f"{v:.3g}" for v in e.speeds)
    return (
        f"{e.simulations} exact simulations: impacts at {sp} {u['velocity']}, {START_WORDS[tuple(e.starts)][2]}, "
        f"over stiffnesses {e.k_range[0]:.4g} to {e.k_range[1]:.4g} {u['stiffness']}; runs "
        f"from the loop's time scales, longest {e.longest_run} samples (cap {e.max_samples}); describing "
        f"function: {e.df_model} hold model, every unstable cycle"
    )


def evidence_lines(r: KMaxResult) -> list[str]:
    """What a K_max answer's simulated limits rest on, in full sentences: one line per limit with more to say than
    its value and short tags (its lowering and confirmation, :func:`limit_text` with ``explain``), and the
    simulations run (:func:`evidence_text`). For below a table whose cells hold the short form.

    Parameters
    ----------
    r : KMaxResult
        The answer (:func:`dfa.analysis.limits.kmax.design_answer`).

    Returns
    -------
    list of str
        ``"what: sentence"`` lines, the simulations last.
    """
    ku, vu = r.device.units["stiffness"], r.device.units["velocity"]
    out = []
    for name, what in (
        ("k_sim", "simulation, no simulated impact up to V diverges"),
        ("k_sim_rest", "simulation, every simulated impact up to V rests"),
    ):
        lim = getattr(r, name)
        full = limit_text(lim, ku, explain=True, velocity_unit=vu)
        if full != limit_text(lim, ku):
            out.append(f"{what}: {full}")
    out.append(f"simulations run: {evidence_text(r)}")
    return out


def counterexample_lines(r: KMaxResult) -> list[list[str]]:
    """One table row per counterexample to the criterion (an impact that diverged at or below K_criterion)."""
    ku, vu = r.device.units["stiffness"], r.device.units["velocity"]
    return [
        ["COUNTEREXAMPLE to the criterion", f"K = {_k(c.stiffness, ku)}, {c.velocity:.4g} {vu}, {c.start}: diverged"]
        for c in r.counterexamples
    ]


def _growth_text(a: KMaxAssessment, vu: str) -> str:
    if a.growth_speed is None:
        why = str(a.null_reasons()["growth_speed"])
        return why if why.startswith("not predicted") else "unknown: " + why.removeprefix("unknown: ")
    if a.growth_speed == float("inf"):
        return "no growth predicted"
    return f"growth predicted from {a.growth_speed:.4g} {vu} ({a.unstable_cycles} unstable cycle(s))"


def _rest_bound(r: KMaxResult) -> str:
    """Why no speed is passive: K > 2c/Δ for the spring, σ < σ₀ with a damper."""
    if r.k_static is not None:
        return f"K > 2c/Δ = {_k(r.k_static, r.device.units['stiffness'])}"
    return "σ < σ₀ = ½ + (1 − a)β_B"


def passive_text(r: KMaxResult) -> str:
    """The largest speed the criterion proves passive at the assessed K, in words (``"–"`` without one)."""
    a = r.assessment
    if a is None:
        return "–"
    mpv, vu = a.max_passive_velocity, r.device.units["velocity"]
    if a.velocity_status is VelocityStatus.NONE:
        return f"none: no passivity guarantee even at rest ({_rest_bound(r)})"
    if mpv is None:
        return f"none: {a.velocity_status.message}"
    if mpv == float("inf"):
        bound = every_speed_bound(r)
        return "every speed" + (f" ({bound})" if bound else "")
    if mpv == 0.0:
        return f"none: {NO_SPEED_PROVEN}" + ("" if r.wall.covers(Coverage.SURFACE_START) else NO_SPEED_ONE_SIDED)
    return f"{_below(mpv, r.velocity)} {vu}"


def _below(speed: float, velocity: float) -> str:
    """``speed`` at 4 significant digits, more where those would not print it below the impact ``velocity`` it
    lies below: "no passivity guarantee at 0.1 m/s (proven passive up to 0.09999 m/s)", not "up to 0.1 m/s".

    Examples
    --------
    >>> _below(0.0999998, 0.1), _below(0.0999998, 0.05), _below(0.27652, 0.1)
    ('0.0999998', '0.1', '0.2765')
    """
    digits = 4
    text = f"{speed:.{digits}g}"
    while speed < velocity and float(text) >= velocity and digits < 17:
        digits += 1
        text = f"{speed:.{digits}g}"
    return text


#: A largest passive speed of 0: the criterion holds at no speed > 0.
NO_SPEED_PROVEN = "no speed is proven"
#: Why, for a one-sided wall (its storage at first contact: the penetration, the push, the pending commands).
NO_SPEED_ONE_SIDED = (
    ": the storage at the first reading inside (the penetration, the push, the pending commands) alone exceeds "
    "the criterion's bound"
)


def every_speed_bound(r: KMaxResult) -> str:
    """The bound under which K is passive at every speed (``"K <= 2b/T = 10 N/m"``; '' without one)."""
    if r.k_colgate is None:
        return ""
    b = moving_symbols(r.device)[1]  # a held device: (b + b_h)
    cs = f"2{b}/T" if r.delay == 0 else f"{b}/(T(½ + d))"
    return f"K <= {cs} = {_k(r.k_colgate, r.device.units['stiffness'])}"


def verdict_text(r: KMaxResult) -> str:
    """The criterion's verdict on the assessed K at the impact speed, in words (what is proven, what is not)."""
    a = r.assessment
    if a is None:
        return "not requested: no --stiffness given, and no K in the catalogue or the device file"
    not_proof = "not a proof of instability"
    if a.velocity_status is VelocityStatus.NOT_COVERED:
        return f"not covered: {a.velocity_status.message}"
    if a.velocity_status is VelocityStatus.NONE:
        return f"too stiff: no passivity guarantee even at rest ({_rest_bound(r)}); {not_proof}"
    if a.verdict is StiffnessStatus.OK:
        return f"ok: passive at this speed (proven{start_state_clause(r.wall)})"
    kc = r.k_criterion.value
    bound = "" if kc is None else f" (K > K_max = {_k(kc, r.device.units['stiffness'])})"
    return f"too stiff: no passivity guarantee at this speed{bound}; {not_proof}"


def source_text(a: KMaxAssessment) -> str:
    """Where the assessed K came from, in parentheses after it ('' for a K the user gave).

    Examples
    --------
    >>> from dfa.analysis.limits.kmax import KMaxAssessment
    >>> a = KMaxAssessment(800.0, "device file", 0.1, "bounded", "ok", None, None, 0, {}, "my.toml")
    >>> source_text(a)
    ' (the K of device file my.toml)'
    """
    if a.source == "catalogue":
        return " (catalogue K)"
    if a.source == "device file":
        return f" (the K of device file {a.source_file})" if a.source_file else " (the device file's K)"
    return ""


def assessment_rows(r: KMaxResult) -> list[list[str]]:
    """Rows stating the wall's own K at the impact speed: the criterion's speed, the prediction, the runs."""
    a = r.assessment
    if a is None:
        return []
    vu = r.device.units["velocity"]
    k = f"K = {a.stiffness:g} {r.device.units['stiffness']}{source_text(a)}"
    rows = [
        [f"largest passive speed at {k}", passive_text(r)],
        [f"predicted cycles at {k}", _growth_text(a, vu)],
    ]
    if a.outcomes:  # none in a quick answer
        rows.append([f"simulated at {k}, impact at V", outcomes_text(a.outcomes)])
    return rows


def outcomes_text(outcomes: dict[str, str]) -> str:
    """The simulated outcome of each start of an impact, in words.

    Examples
    --------
    >>> outcomes_text({"impact": "rest", "preload": "chatter"}), outcomes_text({"approach": "left"})
    ('rest (from ξ0 = 0), chatter (preload)', 'left (after the approach)')
    """
    where = {"impact": "from ξ0 = 0", "preload": "preload", "approach": "after the approach"}
    return ", ".join(f"{o} ({where[s]})" for s, o in outcomes.items())


def _criterion_row(r: KMaxResult) -> list[str]:
    ku = r.device.units["stiffness"]
    p = r.wall.params(r.device.period, r.device.resolution)
    what = f"eq. 11, d = {p.delay}" if p.covers(Coverage.CLOSED_FORM) else "eq. 11 extended to the wall"
    return [f"criterion K_max at this speed ({what})", limit_text(r.k_criterion, ku)]


def _published_rows(r: KMaxResult) -> list[list[str]]:
    """The spring's published bounds (eq. 8, 9, Abbott-Okamura); none for a wall with more than a delay."""
    if r.k_static is None or r.k_colgate is None or r.k_abbott_okamura is None:
        return []
    ku = r.device.units["stiffness"]
    cs = "2b/T" if r.delay == 0 else "b/(T(½ + d))"
    return [
        ["static limit 2c/Δ (eq. 9)", _k(r.k_static, ku)],
        [f"Colgate-Schenkel {cs} (eq. 8)", _k(r.k_colgate, ku)],
        [f"Abbott-Okamura min({cs}, 2c/Δ)", _k(r.k_abbott_okamura, ku)],
    ]


def kmax_rows(r: KMaxResult, *, explain: bool = False) -> list[list[str]]:
    """The K_max answer as (method, K) rows: the criterion, published bounds, linear, DF, simulation.

    Parameters
    ----------
    r : KMaxResult
        The answer (:func:`dfa.analysis.limits.kmax.design_answer`).
    explain : bool, optional
        Add to each simulated limit what its confirmation simulated.

    Returns
    -------
    list of list of str
        Rows, then one per counterexample and, with an assessed K, its rows (:func:`assessment_rows`).
    """
    u = r.device.units
    ku, vu = u["stiffness"], u["velocity"]
    p = r.wall.params(r.device.period, r.device.resolution)
    loop = (f"all Jury conditions, delay {p.delay}" if p.delay else "all Jury conditions") if p.covers(Coverage.CLOSED_FORM) else (
        "the wall's loop, all Jury conditions")  # fmt: skip
    rows = [_criterion_row(r), *_published_rows(r)]
    why = r.wall.linear_reason()
    rows.append([f"exact linear bound ({loop})", limit_text(r.k_linear, ku, linear_reason=why)])
    for name, what in (
        ("k_df", "describing function: largest K with growth speed >= V"),
        ("k_sim", "simulation: largest K, no simulated impact up to V diverges"),
        (
            "k_sim_rest",
            "simulation: largest K, every simulated impact up to V rests"
            + LEAVES[not r.wall.covers(Coverage.SURFACE_START)],
        ),
    ):
        rows.append([what, limit_text(getattr(r, name), ku, explain=explain, velocity_unit=vu, linear_reason=why)])
    rows += counterexample_lines(r)
    return rows + assessment_rows(r)


def spring_passive_text(lim: StiffnessLimits) -> str:
    """The spring's largest passive speed at the assessed K in words (eq. 12; ``"–"`` without a stiffness).

    Examples
    --------
    >>> from dfa.analysis.limits.closed_form import stiffness_limits
    >>> from dfa.model.catalogue import get_device
    >>> spring_passive_text(stiffness_limits(get_device("impulse").device, 0.1, 80.0))
    '0.1907 m/s'
    """
    unit, ku = lim.device.units["velocity"], lim.device.units["stiffness"]
    if lim.velocity_status == "none":
        return f"none: no passivity guarantee even at rest (K > 2c/Δ = {lim.k_static:.5g} {ku})"
    if lim.velocity_status == "all_speeds":
        return f"every speed (K <= {'2b/T' if lim.delay == 0 else 'b/(T(½ + d))'} = {lim.k_colgate:.5g} {ku})"
    if lim.velocity_status == "not_requested" or lim.max_passive_velocity is None:
        return "–"
    return f"{lim.max_passive_velocity:.4g} {unit}"


def spring_verdict_text(lim: StiffnessLimits) -> str:
    """The spring's verdict on the assessed K at the impact speed in words (eq. 11; ``"–"`` without a stiffness)."""
    if lim.stiffness is None:
        return "–"
    ku = lim.device.units["stiffness"]
    if lim.velocity_status == "none":
        return (
            f"too stiff: no passivity guarantee even at rest (K > 2c/Δ = {lim.k_static:.5g} {ku}); "
            "not a proof of instability"
        )
    if lim.status == "ok":
        return f"ok: passive at this speed (proven{start_state_clause(WallParams.of(delay=lim.delay))})"
    return (
        f"too stiff: no passivity guarantee at this speed (K > K_max = {lim.k_max:.5g} {ku}); "
        "not a proof of instability"
    )
