"""Terminal text of the ``dfa`` commands, from analysis results only (tables via :func:`dfa.formatting.text_table`)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from ..formatting import number, text_table
from ..jsonable import explain_nulls
from ..model.elements import Coverage, ForceLimit, Travel
from ..results.status import GrowthStatus, SearchStatus, SimulationOutcome

if TYPE_CHECKING:  # annotations only: importing the limit-cycle package would load python-control (`dfa check`)
    from ..results.caveats import NoRestCaveat, SubtickCaveat

__all__ = [
    "OUTCOME_TEXT",
    "caveat_text",
    "check_rows",
    "flagged_text",
    "growth_meaning",
    "limit_cycle_lines",
    "limit_cycles_dict",
    "outside_searched_mu",
    "rest_caveat_text",
    "search_text",
    "search_why",
    "simulation_rows",
]

#: One phrase per simulated outcome class (:mod:`dfa.analysis.simulation`): each member's message.
OUTCOME_TEXT = {o.value: o.message for o in SimulationOutcome}


def _g(x: float | None, digits: int = 4) -> str:
    return number(x, digits, none="-", inf="inf")


def _amplitude_text(r: Any, amp_si: float | None, unit: str) -> str:
    """The simulated amplitude; a diverged run has none ("unbounded"), not "inf ticks"; a run that left the wall or
    ended at the end stop has none either, and says why (the JSON's null reason)."""
    if r.amplitude is not None and math.isinf(r.amplitude):
        return "unbounded (the run diverged: no amplitude to measure)"
    if r.amplitude is not None and math.isnan(r.amplitude):
        return str(r.null_reasons()["amplitude"])
    return f"{_g(r.amplitude)} ticks" + ("" if amp_si is None else f" = {amp_si:.4g} {unit}")


def check_rows(r: Any, quantized: bool, vu: str) -> list[list[str]]:
    """Rows of the `dfa check` table; every verdict says what is proven and what is not."""
    d = r.delay
    crit = "none" if r.critical_xi_dot is None else f"{r.critical_xi_dot:.4g} ticks/sample"
    if r.critical_velocity is not None:
        crit += f" ({r.critical_velocity:.4g} {vu})"
    if r.critical_xi_dot is not None and r.xi0 != 0.0 and r.critical_symbol == "V":
        crit += ", a bound on the equivalent speed V, not on ξ'0"
    speed = f"{r.xi_dot:.4g} ticks/sample" + (f" ({r.velocity:.4g} {vu})" if r.velocity is not None else "")
    s0 = "½" if quantized else "0"
    rule = f"(β − ½ − d)V + (σ − {s0}) ≥ 0" + (" and σ ≥ ½" if quantized else "")
    if r.passive:
        upto = (
            "at every speed"
            if r.region == "a"
            else f"for speeds up to {r.critical_symbol} = {r.critical_xi_dot:.4g} ticks/sample"
        )
        verdict = f"yes: the energy cannot grow {upto} (proven)"
    else:
        verdict = "no: no passivity guarantee (not a proof of instability)"
    rows = [["β, σ", f"{r.beta:.4g}, {r.sigma:.4g}"], ["speed |ξ'0|", speed]]
    if r.xi0 != 0.0:
        pos = f" ({r.position:.4g} {r.device.units['position']})" if r.device is not None else ""
        rows.append(["initial position ξ0", f"{r.xi0:.4g} ticks{pos}"])
    rows += [
        [
            "equivalent speed V",
            f"{r.equivalent_speed:.4g} ticks/sample ({ENERGY_OF[r.history if r.delay else 'fresh']})",
        ],
        ["delay d", f"{d} sample{'s' if d != 1 else ''}"],
        ["criterion", ("eq. 6 (with encoder)" if quantized else "eq. 7 (no quantization)") + f": {rule}"],
        ["region", f"{r.region}: {r.status.message}"],
        ["passive", verdict],
        ["start state", r.start_state],
        ["margin", f"{r.margin:.4g}"],
        [f"critical speed (eq. 12, d = {d})", crit],
    ]
    return rows


#: What ½μV² of the criterion's speed stands for, by the start's memory (:data:`dfa.analysis.criterion.HISTORIES`).
ENERGY_OF = {
    "fresh": "½μV² = stored energy, eq. 19",
    "moving": "½μV² = stored energy and the pending commands' work, moving history",
}


def simulation_rows(r: Any, x0: float, v0: float, preload: bool, phys: dict | None) -> list[list[str]]:
    """Rows of the `dfa simulate` table: ticks, samples and KΔ, and beside them s, m (rad), m/s (rad/s), Hz and
    N (N·m) when a device is known (``phys``: :meth:`~dfa.analysis.simulation.SimulationResult.physical`);
    without one the last row says the output is dimensionless."""
    u = None if phys is None or phys.get("device") is None else phys
    pos = "" if u is None else u["position_unit"]
    vel = "" if u is None else u["velocity_unit"]
    px, vx = ("rad", "rad_s") if u is not None and u["rotary"] else ("m", "m_s")

    def si(key: str, unit: str) -> str:
        """`` = value unit`` of a physical key, empty without a device or a value."""
        return "" if u is None or u.get(key) is None else f" = {_g(u[key])} {unit}"

    freq = "-" if r.frequency is None else f"{r.frequency:.4g} rad/sample (period {r.period:.4g} samples)"
    if u is not None and u["frequency_hz"] is not None:
        freq += f", {u['frequency_hz']:.4g} Hz (period {u['period_s']:.4g} s)"
    amp_si = None if u is None else u.get("amplitude_si")
    samples = f"{r.samples_run} of {r.samples} integrated"
    if u is not None:
        samples += f" = {_g(u['integrated_s'])} s of {_g(u['duration_s'])} s"
    rows = [
        [
            "initial state",
            f"ξ0 = {x0:.5g} ticks{si(f'x0_{px}', pos)}, ξ'0 = {v0:.5g} ticks/sample{si(f'v0_{vx}', vel)}"
            + (" (spring preload)" if preload else ""),
        ],
        [
            "samples",
            samples
            + (" (length from the loop's time scales)" if r.samples_auto else "")
            + (f", delay {r.delay}" if r.delay else ""),
        ],
        ["outcome", f"{r.outcome}: {OUTCOME_TEXT[r.outcome]}"],
    ]
    if getattr(r, "contact", None) is not None:  # a one-sided wall's run, as contact
        rows.append(["contact", f"{r.contact.value}: {r.contact.message}"])
    if r.suggested_samples is not None:
        longer = "" if u is None else f" ({_g(u['suggested_duration_s'])} s)"
        rows.append(["to decide", f"run longer: --samples {r.suggested_samples}{longer}"])
    rows += [
        ["rest at sample", "-" if r.rest_sample is None else f"{r.rest_sample}{si('rest_time_s', 's')}"],
        ["amplitude", _amplitude_text(r, amp_si, pos)],
        ["frequency", freq],
    ]
    if r.outcome in ("chatter", "oscillating", "undecided", "saturated"):
        rows.append(_force_row(r, u))
    rows.append(
        [
            "final state",
            f"ξ = {_g(r.final_xi)}{' ticks' if u else ''}{si(f'final_x_{px}', pos)}, "
            f"ξ' = {_g(r.final_xi_dot)}{' ticks/sample' if u else ''}{si(f'final_v_{vx}', vel)}",
        ]
    )
    if u is None:
        rows.append(["units", "dimensionless (no device): positions in ticks, time in samples, forces in KΔ"])
    else:
        step = u["force_step_nm" if u["rotary"] else "force_step_n"]
        rows.append(
            [
                "units",
                f"1 tick = Δ = {_g(u[f'tick_{px}'])} {pos}, 1 sample = T = "
                f"{_g(u['sample_period_s'])} s, force step KΔ = {_g(step)} {u['force_unit']}",
            ]
        )
    return rows


def _force_row(r: Any, u: dict | None) -> list[str]:
    """The force peak-to-peak row of a bounded run: the applied force's on the spring (with a force limit: clipped
    to ±F_max, :func:`dfa.analysis.simulation.applied_peak_to_peak`), else the spring's levels only."""
    force = f"{_g(r.force_peak_to_peak)} KΔ" + ("" if r.quantize else " (linear spring)")
    if u is not None and u["force_peak_to_peak_si"] is not None:
        force += f" = {u['force_peak_to_peak_si']:.4g} {u['force_unit']}"
    alone = all(k in (ForceLimit, Travel) for k, _ in r.wall.groups)  # the spring, with a limit or a travel
    if r.outcome == "saturated" and alone:
        return ["force peak-to-peak", force + " (tail; the applied force, clipped at the actuator's limit ±F_max)"]
    if r.outcome == "saturated":
        why = " (tail; before the actuator's limit clips it; the wall's other forces not included)"
        return ["spring force peak-to-peak", force + why]
    # beyond the spring the levels read are the spring's part of the force only
    spring = alone or r.wall.covers(Coverage.CLOSED_FORM)
    label = "force peak-to-peak" if spring else "spring force peak-to-peak"
    return [label, force + (" (tail)" if spring else " (tail; the wall's other forces not included)")]


def search_why(res: Any) -> str:
    """Why a limit-cycle search (:class:`~dfa.analysis.cycles.LimitCycleResult`) ended incomplete, from its evidence.

    Parameters
    ----------
    res : LimitCycleResult or NyquistLocusResponse
        A result whose ``search`` holds :class:`~dfa.analysis.cycles.SearchEvidence` and whose status says how
        the search ended.

    Returns
    -------
    str
        One clause with the numbers; the status's message when the search was complete.

    Examples
    --------
    >>> from dfa.analysis.cycles import limit_cycles
    >>> from dfa.model.device import Params
    >>> search_why(limit_cycles(Params(5.0, 0.1, 0.3), max_amplitude=1.5))
    'cycles may exist beyond max_amplitude = 1.5 ticks'
    """
    ev = res.search
    status = getattr(res, "status", None)
    code = status if isinstance(status, SearchStatus) else _solver_status(ev, res)
    if code is SearchStatus.FREQUENCY_RANGE:
        return f"not searched: {outside_searched_mu(res.mu)}"
    if code is SearchStatus.NUMERICAL:
        beyond = f", and beyond {ev.reached:g} ticks" if ev.reached is not None else ""
        return f"{ev.failures} root bracket(s) could not be refined (numerical failure); cycles may be missing{beyond}"
    if code is SearchStatus.TIME_BUDGET:
        return (
            f"time budget of {ev.time_budget:g} s hit after searching {ev.pieces_searched} of {ev.pieces_total} "
            f"pieces of the phase curve; no cycle missed below M = {ev.reached:.4g} ticks (raise time_budget)"
        )
    if code is SearchStatus.BUDGET:
        return f"searched up to the size budget ({ev.reached:g} ticks) short of the envelope bound"
    if code is SearchStatus.MAX_AMPLITUDE:
        return f"cycles may exist beyond max_amplitude = {ev.requested:g} ticks"
    return str(SearchStatus.COMPLETE.message)


def outside_searched_mu(mu: float) -> str:
    """Why a limit-cycle search at ``mu`` searched nothing (status ``frequency_range``), one clause.

    Examples
    --------
    >>> outside_searched_mu(1e10)[:40]
    'μ = 1e+10 lies outside 1e-06 … 1e+08, wh'
    """
    from ..results.cycles import SEARCHED_MU  # here: it loads the limit-cycle package

    return (
        f"μ = {mu:.3g} lies outside {SEARCHED_MU[0]:g} … {SEARCHED_MU[1]:g}, where cycle "
        "frequencies may fall outside the scanned grid (haptic devices lie between about 1e-2 and 1e7)"
    )


def _solver_status(ev: Any, res: Any) -> SearchStatus:
    """The solver's status behind a Nyquist response's evidence (its own status says only incomplete or not)."""
    if ev.frequency_range:
        return SearchStatus.FREQUENCY_RANGE
    if ev.failures:
        return SearchStatus.NUMERICAL
    if ev.time_budget is not None:
        return SearchStatus.TIME_BUDGET
    if ev.reached is None:
        return SearchStatus.COMPLETE
    return SearchStatus.BUDGET if ev.reached < ev.requested else SearchStatus.MAX_AMPLITUDE


def search_text(res: Any) -> str:
    """How a limit-cycle search ended, in words: ``"incomplete: …"`` with the numbers, or the status's message.

    Parameters
    ----------
    res : LimitCycleResult
        From :func:`dfa.analysis.cycles.limit_cycles`.

    Returns
    -------
    str
        One line.
    """
    return str(res.status.message) if res.complete else f"incomplete: {search_why(res)}"


def flagged_text(maps: Any) -> str:
    """Which grid points of contour maps (:class:`~dfa.analysis.contours.ContourMaps`) the closed forms flag.

    Parameters
    ----------
    maps : ContourMaps
        From :func:`dfa.analysis.contours.contour_maps`.

    Returns
    -------
    str
        ``"eq. 42-43: 1 point(s) NaN, …"`` per group, joined by ``"; "``; empty when none is flagged.
    """
    from ..results.cycles import ClosedFormStatus

    return "; ".join(
        f"{f.equations}: {f.points} point(s) NaN, {ClosedFormStatus[f.reason.upper()].reason}" for f in maps.flagged
    )


def _no_cycle_line(res: Any, lin: str) -> str:
    why = search_why(res)
    if res.status is SearchStatus.FREQUENCY_RANGE:
        return f"no limit-cycle search: {outside_searched_mu(res.mu)}"
    if not res.complete:
        return f"no limit cycle found up to M = {res.max_amplitude:g} ticks (search incomplete: {why})"
    if res.linear_stable is False:
        return f"no limit cycle predicted, but {lin} is unstable: amplitudes grow without bound"
    if res.search_bound:
        return f"no limit cycle predicted (search complete: eq. 36 has no root beyond M = {res.search_bound:.4g} ticks)"
    return "no limit cycle predicted (search complete: the loop never meets the phase condition of eq. 36)"


def _cycle_table(res: Any, phys: dict | None = None) -> str:
    """Table of the cycles: ticks and rad/sample, and with a device (``phys``) m (rad), Hz, s and N (N·m)."""
    header = ["M (ticks)", "ω (rad/sample)", "samples/cycle", "stability", "family"]
    rows = [
        [
            f"{c.amplitude:.6g}",
            f"{c.frequency:.6g}",
            f"{c.period:.4g}",
            "stable" if c.stable else "unstable",
            c.family + (" (period < 8 samples)" if c.few_samples else ""),
        ]
        for c in res.cycles
    ]
    if phys is not None:
        pos, force = phys["position_unit"], phys["force_unit"]
        pk = "amplitude_rad" if phys["rotary"] else "amplitude_m"
        fk = "force_amplitude_nm" if phys["rotary"] else "force_amplitude_n"
        for row, q in zip(rows, phys["cycles"], strict=True):
            row[3:3] = [f"{q[pk]:.4g}", f"{q['frequency_hz']:.4g}", f"{q['period_s']:.4g}", f"{q[fk]:.4g}"]
        header[3:3] = [f"M ({pos})", "f (Hz)", "period (s)", f"force ({force})"]
    return text_table(rows, header, width=100)  # force: the amplitude of K·q


def _growth_line(g: Any, device: Any) -> str:
    u = device.units if device is not None else None

    def speed(xd: float, vel: float | None, pos: float | None) -> str:
        txt = f"M·ω = {xd:.4g} ticks/sample"
        if u is not None and vel is not None:
            txt += f" = {vel:.4g} {u['velocity']}; M = {pos:.4g} {u['position']}"
        return txt

    if g.is_band:
        return (
            f"growth band: {g.unstable_count} unstable cycles from M = {g.amplitude:.4g} to {g.amplitude_high:.4g} ticks "
            f"(speeds {speed(g.xi_dot, g.velocity, g.position)} to {speed(g.xi_dot_high, g.velocity_high, g.position_high)})"
        )
    return f"growth threshold: M_u = {g.amplitude:.4g} ticks ({speed(g.xi_dot, g.velocity, g.position)})"


def limit_cycle_lines(g: Any, device: Any, phys: dict | None = None) -> list[str]:
    """Text of `dfa limit-cycles`: the table, the search's completeness, the linear loop and the growth band."""
    res = g.result
    lin = (
        "the linear loop without encoder and Coulomb friction (exact ZOH model"
        + (f", delay {res.delay}" if res.delay else "")
        + ")"
    )
    lines = []
    if not res.cycles:
        lines.append(_no_cycle_line(res, lin))
    else:
        lines.append(_cycle_table(res, phys))
        if phys is not None:
            fs = phys["force_step_nm" if phys["rotary"] else "force_step_n"]
            lines.append(
                f"one tick = {device.resolution:.4g} {phys['position_unit']} = one force step KΔ = {fs:.4g} {phys['force_unit']}"
            )
        if not res.complete:
            why = search_why(res)
            lines.append(f"search incomplete beyond M = {res.max_amplitude:g} ticks ({why}): more cycles may exist")
    if res.rest_caveat is not None and not any(c.amplitude < 1.0 for c in res.cycles):
        lines.append(f"caveat: {rest_caveat_text(res.rest_caveat)}")
    if g.amplitude is not None:
        lines += [_growth_line(g, device), growth_meaning(g)]
    elif res.cycles and res.linear_stable is False:
        lines.append(
            f"no unstable cycle predicted{'' if res.complete else ' in the range searched'}, but {lin} is unstable: "
            "large oscillations are predicted to grow without bound"
        )
    if res.model != "zoh" and (res.linear_stable is False or g.amplitude is not None):
        lines.append(f"(the linear verdict uses the exact ZOH loop; the limit cycles, the {res.model} model)")
    return lines


def limit_cycles_dict(g: Any, phys: dict | None = None) -> dict[str, object]:
    """JSON of `dfa limit-cycles`: the cycle search (:meth:`LimitCycleResult.to_dict`) and its growth threshold.

    With ``phys`` (:meth:`LimitCycleResult.physical`) each cycle carries both: ticks, rad/sample and m (rad), Hz,
    s, N (N·m), and the record gains the device, K and force step.
    """
    d = g.result.to_dict()
    d["growth_threshold"] = _growth_dict(g)
    if phys is not None:
        phys = dict(phys)
        for cyc, extra in zip(d["cycles"], phys.pop("cycles"), strict=True):
            cyc.update(extra)
        d.update(phys)
        explain_nulls(d, {"velocity": "no impact speed given: the cycles do not depend on it"})
    return d


def _growth_dict(g: Any) -> dict[str, Any]:
    """The growth threshold's JSON, every null with its reason (no band predicted, or no device for units)."""
    out = g.to_dict()
    out["meaning"] = growth_meaning(g)
    none = f"no growth band: {g.status.message}"
    nodev = none if g.amplitude is None else "no device given: physical values need one"
    why = dict.fromkeys(("amplitude", "frequency", "xi_dot", "grows_above"), none)
    why.update(dict.fromkeys(("position", "velocity"), nodev))
    for part in (out, out["band"]["low"], out["band"]["high"]):
        explain_nulls(part, why)
    return out


def caveat_text(c: SubtickCaveat) -> str:
    """The sub-tick caveat (:class:`dfa.results.caveats.SubtickCaveat`) in words.

    Examples
    --------
    >>> from dfa.results.caveats import SubtickCaveat
    >>> caveat_text(SubtickCaveat(1.014))[:62]
    'the smallest unstable cycle (M = 1.014 ticks) lies below 1.25 '
    """
    return (
        f"the smallest unstable cycle (M = {c.amplitude:.4g} ticks) lies below {c.limit:g} ticks, just "
        "above the first quantization level, where the first harmonic is a poor guide to the sub-tick chatter's "
        "amplitude; exact simulation has diverged from sub-tick starts at such points (from a third of them or more "
        "at most random cases with M < 1.005 ticks, and at some up to 1.07 ticks), so growth from below M is not "
        "excluded (check with `dfa simulate`)"
    )


def rest_caveat_text(c: NoRestCaveat) -> str:
    """The no-rest caveat (:class:`dfa.results.caveats.NoRestCaveat`) in words.

    Examples
    --------
    >>> from dfa.results.caveats import NoRestCaveat
    >>> rest_caveat_text(NoRestCaveat(0.45))[:40]
    'σ = 0.45 < ½: the Coulomb friction canno'
    """
    return (
        f"σ = {c.sigma:.4g} < ½: the Coulomb friction cannot hold the spring's half force step KΔ/2, so the device "
        "never rests; it chatters below one tick, which the describing function does not predict here (check "
        "with `dfa simulate`)"
    )


def growth_meaning(g: Any) -> str:
    """What a growth band (:class:`dfa.analysis.cycles.GrowthThreshold`) means, in words that claim no more than
    the describing function shows, with the sub-tick caveat when it holds."""
    text = _growth_meaning(g)
    return text if g.caveat is None else f"{text} Caveat: {caveat_text(g.caveat)}."


def _growth_meaning(g: Any) -> str:
    res = g.result
    if g.status is GrowthStatus.NO_UNSTABLE_CYCLE_SEARCHED:
        return f"no unstable cycle predicted up to M = {res.max_amplitude:g} ticks (search {search_text(res)})"
    if g.status is GrowthStatus.LINEAR_UNSTABLE and not res.complete:
        return (
            f"no unstable cycle predicted up to M = {res.max_amplitude:g} ticks (search {search_text(res)}), but the "
            "linear loop (exact ZOH model) is unstable: amplitudes grow without bound"
        )
    if g.amplitude is None:
        return g.status.message
    lo, hi = g.amplitude, g.amplitude_high
    tail = ""
    if not res.complete:
        tail = f" The search was incomplete ({search_text(res)}): more unstable cycles may lie above {res.max_amplitude:g} ticks."
    if g.grows_above:
        above = f"above {hi:.4g} ticks the first-harmonic analysis predicts growth" + (
            " without bound (the linear loop, exact ZOH model, is unstable)" if res.linear_stable is False else ""
        )
    else:
        nxt = next(c for c in res.cycles if c.amplitude > hi and c.stable)
        above = f"above {hi:.4g} ticks it predicts settling on the stable cycle at M = {nxt.amplitude:.4g} ticks"
    if not g.is_band:
        return f"Describing function (first-harmonic approximation): below M_u = {lo:.4g} ticks no growth is predicted; {above}.{tail}"
    return (
        f"Describing function (first-harmonic approximation): {g.unstable_count} unstable cycles alternate with stable ones "
        f"between {lo:.4g} and {hi:.4g} ticks. Below the band every predicted cycle is stable (no growth predicted); "
        f"inside it, whether an oscillation grows depends on its initial condition; {above}.{tail}"
    )
