"""The wall controller in the ``dfa`` commands' text and JSON (issue 15), from results only.

A controller is stated with its physical values (K, B, d, f_c, f_bw in the device's units) and its
dimensionless groups beside paper Table 1 (β_B = B/(KT), ν_c = f_c T, α = τ_a/T; :mod:`dfa.model.wall`).

Examples
--------
>>> from dfa.model.wall import Wall
>>> controller_line(Wall.of(1000.0, damping=0.5, filter_cutoff=100.0), 1e-3, {"stiffness": "N/m",
...     "damping": "N·s/m"})
'controller: K = 1000 N/m, B = 0.5 N·s/m, delay 0 samples, velocity filter 100 Hz, ideal amplifier; β_B = B/(KT) = 0.5, ν_c = f_c·T = 0.1, α = τ_a/T = 0'
"""

from __future__ import annotations

from typing import Any

from ..formatting import number
from ..jsonable import explain_nulls, to_jsonable
from ..model.elements import ForceLimit, OneSided, PassivityController, Push, Travel
from ..results.criterion import PassivityCheck
from ..results.status import CheckStatus

__all__ = [
    "NOT_COVERED",
    "check_table_rows",
    "controller_check_rows",
    "wall_dict",
    "controller_line",
    "controller_parts",
    "controller_short",
    "travel_text",
]


#: What a check says where no passivity criterion covers the wall (an amplifier lag).
NOT_COVERED = CheckStatus.NOT_COVERED.message


#: What a verdict given with a device's travel assumes (:attr:`dfa.model.elements.Travel.assumption`), short.
TRAVEL_ASSUMES = (
    "the criterion, the linear bounds, the describing function and the closed forms assume the motion stays inside "
    "(their verdicts hold while it does); a simulated run that leaves it ends there (end_stop)"
)


def travel_text(travel: float | None, resolution: float, unit: str) -> str | None:
    """The device's travel and what the analyses assume of it, in one sentence (None without a travel).

    Parameters
    ----------
    travel : float or None
        The device's travel from the centre to either end stop, m (rotary: rad); None: unlimited.
    resolution : float
        The encoder resolution Δ in m (rotary: rad).
    unit : str
        The travel's unit (``"m"`` or ``"rad"``).

    Returns
    -------
    str or None

    Examples
    --------
    >>> travel_text(0.05, 2e-5, "m")[:65]
    'travel: ±0.05 m from the centre (ξ_travel = travel/Δ = 2500 ticks'
    """
    if travel is None:
        return None
    ticks = Travel(travel).group(1.0, 1.0, resolution=resolution)
    return f"travel: ±{_g(travel)} {unit} from the centre (ξ_travel = travel/Δ = {_g(ticks)} ticks); {TRAVEL_ASSUMES}"


def not_covered_why(chk: PassivityCheck) -> str:
    """Why the check is not covered: the reasons of the criterion and of Colgate–Schenkel, in one sentence."""
    return "; ".join(chk.reasons[k] for k in ("criterion", "colgate_schenkel") if k in chk.reasons)


def _g(x: float | None, digits: int = 4) -> str:
    return number(x, digits, none="-", inf="inf")


def wall_dict(
    controller: Any, period: float, units: dict[str, str], resolution: float | None = None
) -> dict[str, object]:
    """The ``"wall"`` object of the JSON output: physical values, units and dimensionless groups.

    Parameters
    ----------
    controller : dfa.model.wall.Wall
        The wall controller (physical units).
    period : float
        Sample period T in s.
    units : dict
        The device's unit strings (:attr:`dfa.Device.units`).
    resolution : float, optional
        The encoder resolution Δ (m, rad), for a push's group F_p/(K Δ).

    Returns
    -------
    dict
        Strict-JSON data: stiffness K, damping B, delay d (samples), filter_cutoff f_c (Hz or null),
        amplifier_bandwidth f_bw (Hz or null), amplifier_time_constant τ_a (s), ``units``, and
        ``dimensionless``: the groups as :meth:`dfa.model.wall.WallParams.to_dict` names them (damping β_B,
        delay d, cutoff ν_c, lag α).
    """
    p = controller.params(period, resolution)
    out = dict(controller.to_dict())
    out["amplifier_time_constant"] = controller.amplifier_time_constant
    out["units"] = {
        "stiffness": units["stiffness"],
        "damping": units["damping"],
        "delay": "samples",
        "filter_cutoff": "Hz",
        "amplifier_bandwidth": "Hz",
        "amplifier_time_constant": "s",
    }
    if controller.hand_stiffness:
        out["units"]["hand_stiffness"] = units["stiffness"]
    if "one_sided_surface" in out:
        out["units"] |= {"one_sided_surface": "ticks", "push": units["force"]}
    if "max_force" in out:
        out["units"]["max_force"] = units["force"]
    no_filter = "no velocity filter"
    out["dimensionless"] = explain_nulls(to_jsonable(p.to_dict()), {"cutoff": no_filter})
    why = {"filter_cutoff": no_filter, "amplifier_bandwidth": "ideal amplifier (no lag)"}
    return explain_nulls(to_jsonable(out), why)


def controller_short(controller: Any, units: dict[str, str]) -> str:
    """The controller in a few words for a figure's title: B, the filter and amplifier when present, d.

    Parameters
    ----------
    controller : dfa.model.wall.Wall
        The wall controller.
    units : dict
        The device's unit strings (:attr:`dfa.Device.units`).

    Returns
    -------
    str
        ``B = … {damping unit}[, f_c = … Hz][, f_bw = … Hz], d = …`` (f_c: velocity filter cutoff,
        f_bw: amplifier bandwidth, d: delay in samples).

    Examples
    --------
    >>> from dfa.model.wall import Wall
    >>> controller_short(Wall.of(1000.0, 1.0, 1, 200.0), {"damping": "N·s/m"})
    'B = 1 N·s/m, f_c = 200 Hz, d = 1'
    """
    parts = [f"B = {_g(controller.damping)} {units['damping']}"]
    if controller.filter_cutoff is not None:
        parts.append(f"f_c = {_g(controller.filter_cutoff)} Hz")
    if controller.amplifier_bandwidth is not None:
        parts.append(f"f_bw = {_g(controller.amplifier_bandwidth)} Hz")
    return ", ".join([*parts, f"d = {controller.delay}"])


def _hand_storage(wall: Any) -> str:
    """``", with the hand's storage ½κ_h ξ²"`` when a hand stiffness is in the wall, else empty."""
    return ", with the hand's storage ½κ_h ξ²" if getattr(wall, "hand_stiffness", 0.0) else ""


def controller_parts(
    controller: Any, period: float, units: dict[str, str], resolution: float | None = None
) -> tuple[str, str]:
    """The controller's physical values and its dimensionless groups, the two halves of :func:`controller_line`.

    Parameters
    ----------
    controller : dfa.model.wall.Wall
        The wall controller.
    period : float
        Sample period T in s.
    units : dict
        The device's unit strings.
    resolution : float, optional
        The encoder resolution Δ (m, rad), for a push's group F_p/(K Δ).

    Returns
    -------
    tuple of str
        ``controller: K = …, B = …, delay …, velocity filter …, amplifier …`` and ``β_B = …, ν_c = …, α = …``.
    """
    p = controller.params(period, resolution)
    d = controller.delay
    filt = (
        "no velocity filter"
        if controller.filter_cutoff is None
        else f"velocity filter {_g(controller.filter_cutoff)} Hz"
    )
    amp = (
        "ideal amplifier"
        if controller.amplifier_bandwidth is None
        else f"amplifier bandwidth {_g(controller.amplifier_bandwidth)} Hz (τ_a = {_g(controller.amplifier_time_constant)} s)"
    )
    nu = "none" if p.cutoff is None else _g(p.cutoff)
    values = (
        f"controller: K = {_g(controller.stiffness, 5)} {units['stiffness']}, B = {_g(controller.damping)} "
        f"{units['damping']}, delay {d} sample{'s' if d != 1 else ''}, {filt}, {amp}"
    )
    groups = f"β_B = B/(KT) = {_g(p.damping)}, ν_c = f_c·T = {nu}, α = τ_a/T = {_g(p.lag)}"
    if controller.hand_stiffness:  # the hand's spring acts beside the controller: named after it
        values += f"; hand stiffness k_h = {_g(controller.hand_stiffness)} {units['stiffness']}"
        groups += f", κ_h = k_h/K = {_g(p.hand_stiffness)}"
    pc = controller.element(PassivityController)
    if pc is not None:  # named after the wall it watches
        from .passivity import passivity_text

        window, limit = p.group(type(pc))
        values += "; " + passivity_text(pc, units)
        groups += f", W = {window} sample{'s' if window != 1 else ''}" if window else ""
        groups += "" if limit is None else f", f_max = F_max/(KΔ) = {_g(limit)}"
    top = controller.element(ForceLimit)
    if top is not None:  # the actuator's force limit, last: it clips the whole command
        values += f"; actuator force limit F_max = {_g(top.max_force)} {units['force']}"
        groups += f", φ_max = F_max/(KΔ) = {_g(p.group(ForceLimit))}"
    return values, groups


def controller_line(controller: Any, period: float, units: dict[str, str], resolution: float | None = None) -> str:
    """One text line stating the controller, physical values then the dimensionless groups (:func:`controller_parts`).

    Parameters
    ----------
    controller : dfa.model.wall.Wall
        The wall controller.
    period : float
        Sample period T in s.
    units : dict
        The device's unit strings.
    resolution : float, optional
        Encoder resolution Δ (for a push's group).

    Returns
    -------
    str
        ``controller: K = …, B = …, delay …, velocity filter …, amplifier …; β_B = …, ν_c = …, α = …``.
    """
    return "; ".join(controller_parts(controller, period, units, resolution))


def _criterion_rows(r: Any, vu: str) -> list[list[str]]:
    """The extended criterion's rows (:func:`dfa.analysis.criterion.passivity_criterion` with a wall)."""
    crit = "none" if r.critical_xi_dot is None else f"{r.critical_xi_dot:.4g} ticks/sample"
    if r.critical_velocity is not None:
        crit += f" ({r.critical_velocity:.4g} {vu})"
    if r.critical_xi_dot == 0.0:  # a one-sided wall's storage at first contact (a push's energy) alone is too much
        crit += ": no speed is proven, the storage at the first reading inside alone exceeds the bound"
    s0 = "σ₀" if r.quantized else "0"
    rule = f"(β − β₀)V + (σ − {s0}) ≥ 0" + (" and σ ≥ σ₀" if r.quantized else "")
    if r.passive:
        upto = (
            "at every speed"
            if r.region == "a"
            else f"for speeds up to {r.critical_symbol} = {r.critical_xi_dot:.4g} ticks/sample"
        )
        verdict = f"yes: the energy cannot grow {upto} (proven)"
    else:
        verdict = "no: no passivity guarantee (not a proof of instability)"
    corner = f"β₀ = ½ + d + β_B = {r.beta0:.4g}, σ₀ = " + (
        f"½ + (1 − a)β_B = {r.sigma0:.4g}" if r.quantized else "0 (no encoder)"
    )
    if getattr(r.wall, "one_sided", False):
        energy = (
            "½μV² = the most the storage holds from the first reading inside on: the penetration, the push and the "
            "commands pending from the approach"
        )
        family = "eq. 6 for a one-sided spring reached from free space"
    else:
        energy = "½μV² = stored energy, eq. 19"
        family = f"eq. 6 extended to the damper, filter and delay{_hand_storage(r.wall)}"
    return [
        ["equivalent speed V", f"{r.equivalent_speed:.4g} ticks/sample ({energy})"],
        ["criterion", f"{family} (dfa.analysis.criterion): {rule}"],
        ["corner", corner],
        ["region", f"{r.region}: {r.status.message}"],
        ["passive", verdict],
        ["start state", r.start_state],
        ["margin", f"{r.margin:.4g}"],
        ["critical speed (eq. 12 extended)", crit],
    ]


def _colgate_rows(chk: PassivityCheck) -> list[list[str]]:
    """The general Colgate–Schenkel condition (:func:`dfa.analysis.colgate_schenkel.colgate_schenkel_beta`)."""
    cs, dev = chk.colgate_schenkel, chk.device
    assert cs is not None and chk.colgate_schenkel_damping is not None and chk.colgate_schenkel_bound is not None
    b, bu = dev.damping, dev.units["damping"]
    if b > chk.colgate_schenkel_bound:
        verdict = "met: the linear sampled loop (no encoder, no Coulomb friction) is passive"
    elif b <= chk.colgate_schenkel_damping:
        verdict = "not met: the linear sampled loop is not passive (necessary and sufficient for it)"
    else:
        verdict = "undecided: b lies within the rounding of the bound"
    hz = cs.theta / dev.period / (2.0 * 3.141592653589793)
    return [
        [
            "Colgate–Schenkel",
            f"b ≥ (T/2)·max_ω Re{{(1 − e^(−jωT))H(e^(jωT))}}/(1 − cos ωT) = {chk.colgate_schenkel_damping:.4g} {bu} "
            f"(at {hz:.4g} Hz); device b = {b:.4g} {bu}",
        ],
        ["linear passivity", verdict],
    ]


def controller_check_rows(chk: PassivityCheck, vu: str) -> list[list[str]]:
    """Rows of `dfa check` with a controller: the extended criterion (eq. 6) and Colgate–Schenkel.

    Parameters
    ----------
    chk : PassivityCheck
        The check, covered (criterion and Colgate–Schenkel computed).
    vu : str
        Velocity unit.

    Returns
    -------
    list of list of str
        Table rows; every verdict says what is proven and by which condition.
    """
    r = chk.criterion
    assert r is not None and r.device is not None
    speed = f"{r.xi_dot:.4g} ticks/sample" + (f" ({r.velocity:.4g} {vu})" if r.velocity is not None else "")
    rows = [["β, σ", f"{r.beta:.4g}, {r.sigma:.4g}"], ["speed |ξ'0|", speed]]
    if r.xi0 != 0.0:
        rows.append(["initial position ξ0", f"{r.xi0:.4g} ticks ({r.position:.4g} {r.device.units['position']})"])
    rows += _criterion_rows(r, vu)
    if chk.colgate_schenkel is None:  # a one-sided wall: the criterion covers it, the linear loop does not
        return rows + [["Colgate–Schenkel", f"not covered: {chk.reasons.get('colgate_schenkel', '')}"]]
    return rows + _colgate_rows(chk)


def check_table_rows(chk: PassivityCheck) -> list[list[str]]:
    """The table of `dfa check` (and of the design report) for a :class:`~dfa.analysis.wall_check.PassivityCheck`.

    Parameters
    ----------
    chk : PassivityCheck
        The passivity check with the controller.

    Returns
    -------
    list of list of str
        :func:`controller_check_rows` where the criterion covers the wall (with Colgate–Schenkel's reason where
        it does not: a one-sided wall); with an amplifier lag the speed, "not covered" and why.
    """
    dev = chk.device
    if chk.criterion is None or (chk.colgate_schenkel_damping is None and "colgate_schenkel" not in chk.reasons):
        speed = f"{chk.velocity:.4g} {dev.units['velocity']}"
        return [["speed", speed], ["passive", NOT_COVERED], ["why", not_covered_why(chk)]]
    return controller_check_rows(chk, dev.units["velocity"])


def controller_rows(
    controller: Any, period: float, units: dict[str, str], resolution: float | None = None
) -> list[list[str]]:
    """Table rows of the controller: physical values, then the dimensionless groups beside paper Table 1.

    Parameters
    ----------
    controller : dfa.model.wall.Wall
        The wall controller.
    period : float
        Sample period T in s.
    units : dict
        The device's unit strings.
    resolution : float, optional
        Encoder resolution Δ (for a push's group).

    Returns
    -------
    list of list of str
        (quantity, value) rows, read from :func:`wall_dict`; a one-sided wall's surface and push too.
    """
    c: dict[str, Any] = wall_dict(controller, period, units, resolution)
    dim: Any = c["dimensionless"]
    fc, bw = c["filter_cutoff"], c["amplifier_bandwidth"]
    amp = "ideal (no lag)" if bw is None else f"{_g(bw)} Hz (τ_a = 1/(2π f_bw) = {_g(c['amplifier_time_constant'])} s)"
    d = controller.delay
    hand = (  # only with a hand stiffness: every other wall's table is unchanged
        [["hand stiffness k_h (to the wall's origin)", f"{_g(controller.hand_stiffness)} {units['stiffness']}"]]
        if controller.hand_stiffness
        else []
    )
    groups = [["κ_h = k_h/K", _g(dim["hand_stiffness"])]] if controller.hand_stiffness else []
    if controller.element(OneSided) is not None:  # only for a one-sided wall: every other wall's table is unchanged
        push = controller.element(Push)
        push = None if push is None or not push.push else push  # a push of 0 N is none
        hand += [
            ["contact", "one-sided wall reached from free space (pushes only inside, never pulls)"],
            ["surface s", f"{_g(controller.surface)} ticks"],
            ["operator's push F_p", f"{_g(push.push)} {units['force']}" if push else "none"],
        ]
        groups += [["p = F_p/(KΔ)", _g(dim["push"])]] if push else []
    pc = controller.element(PassivityController)
    if pc is not None:  # only with a passivity controller: every other wall's table is unchanged
        window = "the whole run" if pc.window is None else f"{_g(pc.window)} s"
        limit = "none" if pc.force_limit is None else f"{_g(pc.force_limit)} {units['force']}"
        hand += [["passivity controller: observer window", window], ["passivity controller: force limit", limit]]
        groups += [["W (samples; 0: the whole run)", str(dim["pc_window"])]]
        groups += [["f_max = F_max/(KΔ)", _g(dim["pc_force_limit"])]] if pc.force_limit is not None else []
    return [
        ["stiffness K", f"{_g(controller.stiffness, 5)} {units['stiffness']}"],
        ["virtual damping B (backward-difference velocity)", f"{_g(controller.damping)} {units['damping']}"],
        ["computational delay d", f"{d} sample{'s' if d != 1 else ''}"],
        ["velocity filter cutoff f_c", "none" if fc is None else f"{_g(fc)} Hz (first-order low-pass)"],
        ["amplifier bandwidth f_bw", amp],
        *hand,
        ["β_B = B/(KT)", _g(dim["damping"])],
        ["ν_c = f_c·T", "none" if dim["cutoff"] is None else _g(dim["cutoff"])],
        ["α = τ_a/T", _g(dim["lag"])],
        *groups,
    ]


def controller_limit_rows(lim: Any, units: dict[str, str]) -> list[list[str]]:
    """Rows of K_max with a controller, worded as the spring's design answer (:func:`dfa.render.limits.kmax_rows`).

    Parameters
    ----------
    lim : dfa.analysis.limits.kmax.KMaxResult
        The limits with the controller held fixed.
    units : dict
        The device's unit strings.

    Returns
    -------
    list of list of str
        (quantity, value) rows: speed, the four K_max (values and short caveats), counterexamples and status;
        what the simulated limits rest on, in full, goes below the table (:func:`dfa.render.limits.evidence_lines`).
    """
    from .limits import kmax_rows

    return [
        ["impact speed V", f"{number(lim.velocity, 4)} {units['velocity']}"],
        *kmax_rows(lim),
        ["status", str(lim.status)],
    ]
