"""The design answer on one screen: the recommended stiffness, the four ways, the user's K (issue 26).

Every line is at most :data:`WIDTH` characters; the evidence (the speeds, starts and stiffnesses simulated,
the failures that lowered a limit) is for ``explain`` (:func:`dfa.render.limits.kmax_rows`) and the JSON.

Examples
--------
>>> wrap("a " * 60).count("\\n")
1
"""

from __future__ import annotations

from ..formatting import WIDTH, fill, number, text_table
from ..model.elements import Coverage, ForceLimit, OneSided, PassivityController
from ..results.limits import KLimit, KMaxResult
from ..results.require import DamperGuidance, Recommendation
from ..results.status import LimitStatus, RecommendRule, StiffnessStatus, VelocityStatus
from .contact import contact_text
from .controller import travel_text
from .hand import device_title
from .limits import (
    ABOVE_RANGE,
    LEAVES,
    counterexample_lines,
    every_speed_bound,
    limit_tags,
    none_text,
    passive_text,
    source_text,
)
from .passivity import passivity_text
from .require import damper_line
from .start_state import start_state_clause, start_state_note

__all__ = [
    "WIDTH", "wrap", "recommendation_line", "recommendation_text", "stiffness_screen", "user_verdict", "work_line",
]  # fmt: skip


def wrap(text: str, indent: str = "  ") -> str:
    """``text`` wrapped at :data:`WIDTH` characters, continuation lines indented by ``indent``."""
    return fill(text, WIDTH, indent)


def _k(x: float, unit: str) -> str:
    return f"{number(x, 5)} {unit}"


def _limit_cell(lim: KLimit, unit: str, notes: list[str], name: str, linear_reason: str | None = None) -> str:
    """The K cell of one method: its value, a lower bound ("> K", no failure up to the range's top), or "none";
    a note mark when there is something to say."""
    if lim.value is None and lim.status is LimitStatus.ABOVE_RANGE and lim.range_end is not None:
        return f"> {_k(lim.range_end, unit)} *{_note(notes, name, ABOVE_RANGE)}"
    if lim.value is None:
        return f"none *{_note(notes, name, none_text(lim, unit, linear_reason))}"
    tags = limit_tags(lim, unit)
    if not tags:
        return _k(lim.value, unit)
    return f"{_k(lim.value, unit)} *{_note(notes, name, '; '.join(tags))}"


def _note(notes: list[str], name: str, text: str) -> int:
    """The mark of a note ``"name: text"``: a new one, or the one that already says ``text`` (names joined)."""
    for i, note in enumerate(notes):
        head, _, body = note.partition(": ")
        if body == text:
            notes[i] = f"{head}, {name}: {text}"
            return i + 1
    notes.append(f"{name}: {text}")
    return len(notes)


def recommendation_line(rec: Recommendation) -> str:
    """The recommended stiffness and its rule, wrapped at :data:`WIDTH`."""
    return wrap(recommendation_text(rec))


def recommendation_text(rec: Recommendation) -> str:
    """The recommended stiffness and its rule in one sentence (unwrapped: the report's, the terminal wraps it).

    Parameters
    ----------
    rec : Recommendation
        From :func:`dfa.analysis.limits.recommend.recommend_stiffness`.

    Returns
    -------
    str
    """
    u = rec.device.units
    at = f"at {number(rec.velocity, 4)} {u['velocity']}"
    if rec.status is RecommendRule.PROVEN:
        why = (
            f"the largest K the criterion proves passive {at} (a proof{start_state_clause(rec.wall)}; no margin needed)"
        )
    elif rec.status is RecommendRule.SIMULATED:
        assert rec.k_basis is not None
        why = (
            f"no proof {at}: the largest K no simulated impact diverged at, {_k(rec.k_basis, u['stiffness'])}, "
            f"divided by the gain margin {number(rec.margin, 3)} (--margin); not a proof"
        )
    elif rec.status is RecommendRule.SIMULATED_RANGE:
        assert rec.k_basis is not None
        why = (
            f"no proof {at}: no simulated impact diverged up to {_k(rec.k_basis, u['stiffness'])}, the top of the "
            f"range searched, divided by the gain margin {number(rec.margin, 3)} (--margin); not a proof"
        )
    else:
        return f"recommended K: none. {rec.status.message}" + _controller_text(rec)
    assert rec.k_recommended is not None
    plain = rec.controller is not None and not rec.controller.kept
    which = ", for the wall without the passivity controller" if plain else ""
    return f"recommended K = {_k(rec.k_recommended, u['stiffness'])}{which}: {why}{_rest_text(rec)}" + (
        _controller_text(rec)
    )


def _rest_text(rec: Recommendation) -> str:
    """The clause saying that the recommended K lies above the simulated rest limit ('' when it does not)."""
    if not rec.above_rest:
        return ""
    ku = rec.device.units["stiffness"]
    leave = "" if rec.wall.covers(Coverage.SURFACE_START) else " or leaves"
    if rec.k_rest is None:
        where = "every K searched for the rest limit: impacts failed to come to rest already at the lowest"
    else:
        where = (
            f"the simulated rest limit, {_k(rec.k_rest, ku)} (the largest K at which every simulated impact up to V "
            f"rests{leave})"
        )
    return f"; it lies above {where}: the wall may buzz or oscillate at this K"


def _controller_text(rec: Recommendation) -> str:
    """What the comparison with the wall without its passivity controller decided, in a sentence."""
    c = rec.controller
    if c is None:
        return ""
    ku = rec.device.units["stiffness"]
    if c.kept:
        other = "none" if c.plain_k_recommended is None else _k(c.plain_k_recommended, ku)
        return f". Without the passivity controller the recommended K would be {other}"
    textbook = "; it has no force limit (the textbook controller): --pc-force-limit N bounds its force"
    textbook = textbook if c.force_limit is None else ""
    if c.lowers_limit:
        with_it = "fails already at the lowest K searched" if c.k_sim is None else f"is {_k(c.k_sim, ku)}"
        return (
            f". The passivity controller makes this wall worse: with it the simulated no-divergence limit {with_it}, "
            f"against {_k(c.plain_k_sim or 0.0, ku)} without it{textbook}"
        )
    mine = "none" if c.k_recommended is None else _k(c.k_recommended, ku)
    return f". With the passivity controller the recommended K would be {mine}: it gains no stiffness here{textbook}"


def _method_rows(r: KMaxResult, notes: list[str]) -> list[list[str]]:
    """(method, K, what it rests on) for each way and the spring's published bounds."""
    ku = r.device.units["stiffness"]
    n = len(r.evidence.speeds)
    starts = "2 starts" if r.wall.covers(Coverage.SURFACE_START) else "after the approach"
    sims = f"simulated: {n} speed{'s' if n != 1 else ''} up to V, {starts}"
    spring = r.wall.params(r.device.period, r.device.resolution).covers(Coverage.CLOSED_FORM)
    why = r.wall.linear_reason()  # the wall's own element's reason, where the linear loop does not cover it
    rows = [["criterion (eq. 11" + (")" if spring else ", extended)"),
             _limit_cell(r.k_criterion, ku, notes, "criterion"), "proof"]]  # fmt: skip
    published = (
        ("static limit 2c/Δ (eq. 9)", r.k_static, "proof, at rest only"),
        ("Colgate-Schenkel (eq. 8)", r.k_colgate, "linear, no encoder or Coulomb"),
        ("Abbott-Okamura", r.k_abbott_okamura, "min of eq. 8 and eq. 9"),
    )
    rows += [[name, _k(k, ku), why] for name, k, why in published if k is not None]
    rows += [
        [
            "exact linear bound",
            _limit_cell(r.k_linear, ku, notes, "exact linear bound", why),
            "linear, no encoder or Coulomb",
        ],
        ["describing function", _limit_cell(r.k_df, ku, notes, "describing function", why), "first harmonic"],
    ]
    if r.k_sim.status is LimitStatus.NOT_SIMULATED:  # the quick answer: one row says so
        return [*rows, ["simulation", "not run", "a quick answer (--quick): no simulation"]]
    rows += [
        [
            "simulation, no divergence",
            _limit_cell(r.k_sim, ku, notes, "simulation, no divergence"),
            sims + _resolution(r.k_sim),
        ],
        [
            "simulation, every impact rests" + LEAVES[not r.wall.covers(Coverage.SURFACE_START)],
            _limit_cell(r.k_sim_rest, ku, notes, "simulation, rests"),
            sims + _resolution(r.k_sim_rest),
        ],
    ]
    return rows


def _resolution(lim: KLimit) -> str:
    """The K resolution a simulated limit's claim rests on: its sweep's step (narrower bands are not excluded)."""
    c = lim.confirmation
    if c is None or c.sweep.points == 0:
        return ""
    return f", K steps {number(100.0 * c.sweep.step, 2)} %"


def _proof_text(r: KMaxResult, at: str) -> str:
    """What the criterion says of the assessed K at the speed, in a few words."""
    a = r.assessment
    assert a is not None
    if a.velocity_status is VelocityStatus.NOT_COVERED:
        return "no criterion covers this wall"
    upto = passive_text(r)
    if a.velocity_status is VelocityStatus.ALL_SPEEDS:
        bound = every_speed_bound(r)
        return "passive at every speed (proven" + (f": {bound})" if bound else ")")
    if a.verdict is StiffnessStatus.OK:
        return f"passive {at} (proven, up to {upto})"
    if a.velocity_status is VelocityStatus.NONE:
        return upto.replace("none: ", "", 1)
    if a.max_passive_velocity == 0.0:
        return f"no passivity guarantee {at} ({upto.removeprefix('none: ')})"
    return f"no passivity guarantee {at} (proven passive up to {upto})"


def user_verdict(r: KMaxResult) -> str:
    """The verdict on the wall's own K, consistent with the criterion and the runs at V (one line or two)."""
    a = r.assessment
    if a is None:
        return ""
    u = r.device.units
    src = source_text(a)
    at = f"at {number(r.velocity, 4)} {u['velocity']}"
    runs = a.outcomes
    diverged = [s for s, o in runs.items() if o == "unstable"]
    proof = _proof_text(r, at)
    if len(diverged) == 2:
        head = f"diverges in simulation {at} from both starts; {proof}"
    elif diverged:
        head = f"diverges in simulation {at} from the {diverged[0]} start; {proof}"
    elif runs:
        sim = ", ".join(f"{o} ({s})" for s, o in runs.items())
        head = f"{proof}; simulated {at}: {sim}"
    else:  # the quick answer: not simulated
        head = proof
    return wrap(f"your K = {_k(a.stiffness, u['stiffness'])}{src}: {head}")


def _header(r: KMaxResult) -> list[str]:
    """The device and speed; the wall held fixed while K varies (the spring: its delay)."""
    u = r.device.units
    w = r.wall
    d = f"delay {w.delay} sample{'s' if w.delay != 1 else ''}"
    head = f"{device_title(r.device)}, impact at {number(r.velocity, 4)} {u['velocity']} ({number(r.xi_dot, 4)} ticks/sample)"
    travel = travel_text(r.device.travel, r.device.resolution, u["position"])
    tail = [] if travel is None else [wrap(travel)]
    if w.params(r.device.period, r.device.resolution).covers(Coverage.CLOSED_FORM):
        return [wrap(f"{head}; the spring, {d}"), *tail]
    parts = [contact_text(w, u)] if w.element(OneSided) is not None else []
    parts += [f"B = {number(w.damping, 4)} {u['damping']}"] if w.damping else []
    parts.append(d)
    if w.filter_cutoff is not None:
        parts.append(f"velocity filter {number(w.filter_cutoff, 4)} Hz")
    if w.amplifier_bandwidth is not None:
        parts.append(f"amplifier bandwidth {number(w.amplifier_bandwidth, 4)} Hz")
    pc = w.element(PassivityController)
    if pc is not None:
        parts.append(passivity_text(pc, u))
    top = w.element(ForceLimit)
    if top is not None:
        parts.append(f"actuator force limit F_max = {number(top.max_force, 4)} {u['force']}")
    return [wrap(head), wrap(f"wall held fixed while K varies: {', '.join(parts)}"), *tail]


def stiffness_screen(r: KMaxResult, rec: Recommendation, guidance: DamperGuidance | None = None) -> list[str]:
    """The default output of ``dfa stiffness``: every line at most :data:`WIDTH` characters.

    Parameters
    ----------
    r : KMaxResult
        K_max four ways.
    rec : Recommendation
        The recommended stiffness (:func:`dfa.analysis.limits.recommend.recommend_stiffness`).
    guidance : DamperGuidance, optional
        What would let the criterion prove a K with the wall's damper
        (:func:`dfa.analysis.limits.require.damper_guidance`): one line when it proves none.

    Returns
    -------
    list of str
        The lines (none holds a newline): the device and wall, the recommendation, the table of methods, the caveats, the verdict on
        the wall's own K, and where the evidence is.
    """
    notes: list[str] = []
    lines = [*_header(r), recommendation_line(rec), ""]
    lines += text_table(_method_rows(r, notes), ["method", "K", "rests on"], width=WIDTH).splitlines()
    lines += [wrap(f"{row[0]}: {row[1]}") for row in counterexample_lines(r)]
    lines += [wrap(f"*{i} {note}", "    ") for i, note in enumerate(notes, 1)]
    if guidance is not None and not guidance.proves_some_k:
        lines.append(wrap(damper_line(guidance, r.device.units, r.wall.damping)))
    verdict = user_verdict(r)
    if verdict:
        lines += ["", verdict]
    if r.k_sim.status is LimitStatus.NOT_SIMULATED:
        lines.append(fill(f"only the criterion is a proof{start_state_note(r.wall)}; a quick answer, without the "
                          "simulated limits: run without --quick for them", indent=""))  # fmt: skip
    elif r.velocity > 0:
        lines.append(fill(f"only the criterion is a proof{start_state_note(r.wall)}; simulated limits hold at the "
                          "stiffnesses and speeds simulated (narrower unsafe bands between them are not excluded); "
                          "--explain for the evidence", indent=""))  # fmt: skip
    else:
        lines.append("impact speed 0: the describing-function and simulated limits need a speed > 0")
    return "\n".join(lines).split("\n")


def work_line(seconds: float, runs: int) -> str:
    """The last line of ``dfa stiffness --explain``: how long the answer took and how many simulations it ran.

    ``runs`` counts the runs simulated: a run the searches ask for again is taken from the run cache, so the
    evidence's count of simulations (what the searches asked for) can be larger.

    Examples
    --------
    >>> work_line(2.345, 1234)
    'answered in 2.3 s (wall clock, this machine); 1234 runs simulated (repeats taken from the cache)'
    >>> work_line(0.0123, 0)
    'answered in 0.012 s (wall clock, this machine); no simulation run'
    """
    if runs == 0:
        return f"answered in {number(seconds, 2)} s (wall clock, this machine); no simulation run"
    ran = f"{runs} run{'s' if runs != 1 else ''} simulated (repeats taken from the cache)"
    return f"answered in {number(seconds, 2)} s (wall clock, this machine); {ran}"
