"""The describing function's sub-tick caveat (issue 15): where eq. 36's smallest unstable cycle lies just above the
first quantization level, "no growth below it" is contradicted by exact simulation, so every growth verdict resting
on it carries a caveat (limit_cycles, growth_threshold, `dfa limit-cycles` text and JSON) or becomes unknown (the
describing-function K_max with a wall, dfa.analysis.limits.runs.growth_at, used by the Z-width)."""

import json

import numpy as np
import pytest
from cli_text import unwrap
from fixed_keywords import fixed_keywords

import dfa
from dfa.analysis.cycles import SUBTICK_LIMIT, growth_threshold, limit_cycles, subtick_caveat
from dfa.analysis.limits.runs import SAFE, UNDECIDED, UNSAFE, Evidence, df_verdict, growth_at
from dfa.analysis.simulation import OUTCOMES, simulate_batch
from dfa.model.device import Params
from dfa.model.wall import Wall, WallParams
from dfa.render.limits import limit_text
from dfa.render.text import caveat_text, growth_meaning, limit_cycle_lines, limit_cycles_dict
from dfa.results.caveats import SubtickCaveat

# found by a random search (dfa.results.caveats): damper on a slowly filtered velocity (filter pole a = 0.974), d = 0
P = Params(3.749, 0.0, 0.155)
CTL = WallParams.of(damping=0.2838, cutoff=0.0042)


@pytest.fixture(scope="module")
def res():
    return limit_cycles(P, model="zoh", wall=CTL)


def test_eq36_subtick_point_df_predicts_settling_below_one_tick(res):
    st, un = res.stable_cycles, res.unstable_cycles
    assert len(st) == 1 and st[0].amplitude == pytest.approx(0.4019, abs=1e-3)
    assert un[0].amplitude == pytest.approx(1.0141, abs=1e-3) and un[0].amplitude < SUBTICK_LIMIT


def test_eq36_subtick_point_simulation_diverges_from_sub_tick_starts(res):
    """What the first harmonic misses: starts of energy amplitude 0.25 and 0.5 tick (below the stable cycle's
    basin edge M_u = 1.01 by a factor 2 to 4) diverge in exact simulation (15 of 32 at the time of writing)."""
    w = res.unstable_cycles[0].frequency
    ang = np.linspace(0.0, 2.0 * np.pi, 16, endpoint=False)
    x0 = np.concatenate([r * np.cos(ang) for r in (0.25, 0.5)])
    v0 = np.concatenate([r * np.sin(ang) * w for r in (0.25, 0.5)])
    b = simulate_batch(P.mu, P.beta, P.sigma, v0, 20_000, xi0=x0, wall=CTL)
    diverged = int(np.count_nonzero(np.asarray(b.outcome) == OUTCOMES.index("unstable")))
    assert diverged >= 10


def test_eq36_subtick_caveat_on_the_result_and_growth_threshold(res):
    assert res.caveat is not None and res.caveat == subtick_caveat(res)
    assert res.caveat == SubtickCaveat(res.unstable_cycles[0].amplitude) and f"{res.caveat.amplitude:.4g}" == "1.014"
    assert "not excluded" in caveat_text(res.caveat)  # the rendering layer words it
    g = growth_threshold(P, model="zoh", wall=CTL)
    assert g.caveat == res.caveat and "Caveat:" in growth_meaning(g)
    d = json.loads(json.dumps(g.to_dict()))
    caveat = {"amplitude": res.caveat.amplitude, "limit": SUBTICK_LIMIT}
    assert d["caveat"] == caveat and "meaning" not in d  # the record states the caveat as data; rendering words it
    assert json.loads(json.dumps(res.to_dict()))["caveat"] == caveat


def test_eq36_subtick_caveat_in_limit_cycles_text_and_json(res):
    """The numbers users read: `dfa limit-cycles` prints its lines with limit_cycle_lines and its JSON with
    limit_cycles_dict."""
    g = growth_threshold(P, model="zoh", wall=CTL)
    text = "\n".join(limit_cycle_lines(g, None))
    assert "Caveat: the smallest unstable cycle (M = 1.014 ticks)" in text
    d = limit_cycles_dict(g)
    assert d["caveat"] == d["growth_threshold"]["caveat"] == {"amplitude": res.caveat.amplitude, "limit": 1.25}


def test_eq36_subtick_growth_speed_with_a_wall_is_not_relied_on():
    """Before the caveat, the describing-function K_max and the Z-width used M_u·ω = 0.47 ticks/sample here as the
    speed below which no impact grows; simulation contradicts it, so impacts below it are now undecided (growth
    predicted from above it stays unsafe)."""
    growth = growth_at(P, CTL, "zoh")
    assert growth.subtick and growth.unstable == 1 and growth.xi_dot is not None
    assert df_verdict(growth, 0.5 * growth.xi_dot) == UNDECIDED
    assert df_verdict(growth, 1.5 * growth.xi_dot) == UNSAFE


def test_eq36_no_caveat_well_above_the_first_level():
    res = limit_cycles(Params(5.0, 0.1, 0.3), model="zoh")
    assert res.unstable_cycles[0].amplitude > 2.0
    assert res.caveat is None and subtick_caveat(res) is None
    d = res.to_dict()
    assert d["caveat"] is None and "/caveat" in d["null_reasons"]
    g = growth_threshold(Params(5.0, 0.1, 0.3), model="zoh")
    assert "Caveat" not in growth_meaning(g) and g.to_dict()["caveat"] is None


def test_eq36_subtick_caveat_spring_alike():
    """The paper's spring shows the same failure (random search, dfa.results.caveats): its result carries the caveat
    and, as with a wall, its describing function no longer calls impacts below M_u·ω safe (one rule)."""
    p = Params(1.2433, 0.41264, 0.21593)
    res = limit_cycles(p, model="zoh", wall=WallParams.of(delay=1))
    assert res.unstable_cycles[0].amplitude < 1.01 and res.caveat is not None
    growth = growth_at(p, WallParams.of(delay=1), "zoh")
    assert growth.subtick and growth.xi_dot == pytest.approx(
        min(c.amplitude * c.frequency for c in res.unstable_cycles)
    )
    assert df_verdict(growth, 0.5 * growth.xi_dot) == UNDECIDED
    assert df_verdict(growth._replace(subtick=False), 0.5 * growth.xi_dot) == SAFE


def test_eq36_subtick_caveat_named_in_the_zwidth_df_reason():
    """A device whose wall at K = 1000 N/m is the point above (μ = 3.749, β = 0, σ = 0.155,
    β_B = B/(KT) = 0.2838, ν_c = f_c·T = 0.0042): the Z-width's describing-function column says why it stops.

    The column is now k_df of design_answer at this B (its own grid, not the Z-width's K grid): it stops where the
    sub-tick caveat makes the prediction undecided (``limited_by``), and its text must name that caveat."""
    from dfa.analysis.limits.zwidth import _column
    from dfa.model.device import Device

    dev = Device(mass=3.749e-3, damping=0.0, coulomb=1.55e-3, resolution=1e-5, period=1e-3)
    wall = Wall.of(1000.0, damping=0.2838, filter_cutoff=4.2)
    v = dev.velocity(0.01)
    ev = Evidence(dev, wall, np.array([v]), 10**6, "zoh")
    assert ev.predicted(1000.0, 0.01) == UNDECIDED and ev.growth_xi_dot(1000.0).subtick
    ks = np.array([900.0, 1000.0])
    k_df = _column(dev, wall, v, ks, "zoh")[3]
    assert k_df.limited_by is not None and ev.growth_xi_dot(k_df.limited_by).subtick
    assert k_df.limited_by in k_df.undecided and k_df.caveat
    why = limit_text(k_df, "N/m")
    assert "sub-tick caveat" in why and f"below {SUBTICK_LIMIT:g} ticks" in why


_CLI = ["limit-cycles", "--mass", "3.749e-3", "--damping", "0", "--coulomb", "1.55e-3", "--resolution", "1e-5",
        "--period", "1e-3", "--stiffness", "1000", "--virtual-damping", "0.2838", "--velocity-filter", "4.2",
        "--model", "zoh"]  # fmt: skip


def test_eq36_subtick_caveat_printed_by_dfa_limit_cycles(capsys):
    from dfa.cli import main

    assert main(_CLI) == 0
    text = unwrap(capsys.readouterr().out)
    assert "μ = 3.749, β = 0, σ = 0.155" in text
    assert "Caveat: the smallest unstable cycle (M = 1.014 ticks) lies below 1.25 ticks" in text
    assert main([*_CLI, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert f"{d['caveat']['amplitude']:.4g}" == "1.014" and d["caveat"]["limit"] == 1.25
    assert d["growth_threshold"]["caveat"] == d["caveat"] and "Caveat:" in d["growth_threshold"]["meaning"]


def test_eq36_subtick_assessed_stiffness_says_why_its_growth_speed_is_unknown(capsys, monkeypatch):
    """Impulse Engine at K = 540 N/m: the smallest unstable cycle lies below SUBTICK_LIMIT (the caveat), so the
    assessment of that K in `dfa stiffness` states the sub-tick reason, not "search incomplete" (text and JSON)."""
    import dfa.analysis.limits.kmax as kmax
    from dfa.analysis.limits.kmax import KMaxAssessment
    from dfa.cli import main

    # the limits searched small (2 speeds, 6 points): the assessment of the given K is its own, at any search size
    monkeypatch.setattr(kmax, "design_answer", fixed_keywords(kmax.design_answer, speeds=2, grid=6))

    e = dfa.get_device("impulse").device
    p = e.params(540.0)
    assert growth_at(p, WallParams(), "half-delay").subtick
    reasons = {
        why: KMaxAssessment(540.0, "given", None, "none", "too_stiff", None, why, 1).null_reasons()["growth_speed"]
        for why in ("subtick", "incomplete")
    }
    argv = ["stiffness", "--device", "impulse", "--velocity", "0.02", "--stiffness", "540"]
    assert main([*argv, "--explain"]) == 0
    row = next(
        line for line in capsys.readouterr().out.splitlines() if line.startswith("predicted cycles at K = 540 N/m")
    )
    assert reasons["subtick"] in row and "search incomplete" not in row and reasons["incomplete"] not in row
    assert main([*argv, "--json"]) == 0
    a = json.loads(capsys.readouterr().out)["assessment"]
    assert a["growth_speed"] is None and a["growth_unknown"] == "subtick"
    assert a["null_reasons"]["/growth_speed"] == reasons["subtick"]


def test_eq36_no_limit_cycle_at_sigma_below_half_carries_the_rest_caveat(capsys):
    """σ < ½ (eq. 9: c < KΔ/2): the search finds no cycle, yet the device never rests; it chatters below a tick."""
    from dfa.analysis.cycles import NoRestCaveat, limit_cycles
    from dfa.analysis.simulation import simulate
    from dfa.cli import main
    from dfa.model.device import Params

    res = limit_cycles(Params(20.0, 0.55, 0.45), model="zoh")
    assert res.complete and not res.cycles and res.rest_caveat == NoRestCaveat(0.45)
    for xd in (0.05, 0.5, 2.0):  # independent: exact simulation never comes to rest, and stays below a tick
        r = simulate(20.0, 0.55, 0.45, xd, record=False)
        assert r.outcome == "chatter" and r.amplitude < 1.0
    ok = limit_cycles(Params(20.0, 0.55, 0.6), model="zoh")
    assert ok.rest_caveat is None and simulate(20.0, 0.55, 0.6, 0.5, record=False).outcome == "rest"
    assert ok.to_dict()["null_reasons"]["/rest_caveat"].startswith("no caveat")
    assert main(["limit-cycles", "--mu", "20", "--beta", "0.55", "--sigma", "0.45", "--model", "zoh"]) == 0
    out = capsys.readouterr().out
    assert "no limit cycle predicted" in out and "caveat: σ = 0.45 < ½" in out
    assert all(len(line) <= 100 for line in out.splitlines())
