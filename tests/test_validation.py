"""Validation (issue: DF predictions and the criterion against exact simulation), quick set.

The bounds below are derived from the full run committed in reports/validation/validation.md
(`dfa validate`): soundness violations 0 of 31240 passive points; criterion rejects 25 % of the
non-unstable points; DF (exact ZOH) growth threshold within 0.56 % (median) and 11.3 % (worst) of the
simulated critical speed; 94 % of predicted stable cycles persisted and 85 % of predicted unstable
cycles separated decay from growth. Each bound leaves a margin for the smaller quick set.
"""

import json

import pytest

from dfa.cli import main


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("validation")
    assert main(["validate", "--quick", "--quiet", "--jobs", "2", "--out", str(out)]) == 0
    return out, json.loads((out / "validation.json").read_text())


def test_validation_writes_report_and_figures(quick):
    out, _s = quick
    md = (out / "validation.md").read_text()
    for section in (
        "## 1. Limit cycles",
        "## 2. Critical impact speed",
        "## 3. Criterion soundness",
        "## 4. Where the describing function breaks down",
    ):
        assert section in md
    assert (out / "validation_cycles.png").stat().st_size > 2000 and (
        out / "validation_speeds.png"
    ).stat().st_size > 2000


def test_validation_json_is_strict_json(quick):
    out, s = quick

    def refuse(token):
        raise AssertionError(f"non-strict JSON token {token}")

    assert json.loads((out / "validation.json").read_text(), parse_constant=refuse) == s
    assert s["status"] == "ok" and s["soundness_points"] > 0


def test_eq6_criterion_is_sound_on_the_quick_grid(quick):
    _out, s = quick
    assert s["soundness_passive"] > 100
    assert s["soundness_violations"] == 0


def test_eq6_criterion_is_conservative_but_not_useless(quick):
    _out, s = quick
    assert 0.1 < s["conservatism"] < 0.5  # full run: 0.25


def test_eq12_criterion_speed_below_simulated_threshold(quick):
    _out, s = quick
    assert s["speeds_ordered"]
    assert s["criterion_conservatism_min"] >= 1.0


def test_df_growth_threshold_predicts_the_simulated_critical_speed(quick):
    _out, s = quick
    assert s["speed_df_median_error"] < 0.03  # full run: 0.0056
    assert s["speed_df_worst_error"] < 0.15  # full run: 0.113


def test_loeb_sign_convention_confirmed_by_simulation(quick):
    _out, s = quick
    lb = s["loeb"]
    assert lb["stable"] > 10 and lb["unstable"] > 10
    assert lb["stable_confirmed"] / lb["stable"] >= 0.85  # full run: 0.94
    assert lb["unstable_confirmed"] / lb["unstable"] >= 0.70  # full run: 0.85


def test_cli_validate_bad_output_folder(capsys):
    assert main(["validate", "--quick", "--out", "/nonexistent-parent/dir"]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_cli_validate_rejects_bad_jobs_before_running(capsys):
    assert main(["validate", "--quick", "--jobs", "0", "--out", "/tmp"]) == 2
    assert "--jobs" in capsys.readouterr().err


# ----------------------------------------------------------------- item 6: limit cycles with a wall controller
def test_validation_controller_rows_published_for_every_controller_and_model(quick):
    """Quick set (μ = 20, β = 0.05, σ = 0.3): every controller has stable cycles that persist in simulation with
    the same controller; errors as measured when written (pooled median 21 % amplitude, 9.7 % frequency)."""
    from dfa.studies.validation import CONTROLLERS

    out, s = quick
    rows = s["controller_cycles"]
    assert [(r["controller"], r["model"]) for r in rows] == [
        (n, m) for n, _ in CONTROLLERS for m in ("half-delay", "zoh")
    ]
    for r in rows:
        assert r["predicted"] >= 1 and r["persisted"] == r["predicted"]
        assert r["amplitude"]["n"] == r["persisted"] and r["amplitude"]["worst"] < 1.0
        assert r["frequency"]["worst"] < 0.3
    e = s["controller_errors"]
    assert e["persisted"] == e["predicted"] == sum(r["predicted"] for r in rows)
    assert e["amplitude"]["median"] < 0.4 and e["frequency"]["median"] < 0.2
    assert set(s["controllers"]) == {n for n, _ in CONTROLLERS}
    md = (out / "validation.md").read_text()
    assert "## 6. Limit cycles with a wall controller" in md
    # the table prints the JSON's numbers
    first = rows[0]
    assert f"| {first['controller']} | {first['model']} | {first['predicted']} | {first['persisted']} |" in md


def test_validation_controller_record_is_the_simulated_over_predicted_ratio():
    """An independent recomputation: one record of controller_cycle_checks against limit_cycles and simulate."""
    from dfa.analysis.cycles import limit_cycles
    from dfa.analysis.simulation import simulate
    from dfa.model.device import Params
    from dfa.model.wall import WallParams
    from dfa.studies.validation import controller_cycle_checks

    p, ctl = Params(20.0, 0.05, 0.3), WallParams.of(damping=0.2, cutoff=0.05)
    recs = controller_cycle_checks([p], samples=20_000, models=("half-delay",), controllers=(("f", ctl),))
    cyc = limit_cycles(p, model="half-delay", max_amplitude=2000.0, wall=ctl).cycles
    assert [r["amplitude"] for r in recs] == [c.amplitude for c in cyc]
    st = next(r for r in recs if r["stable"])
    sim = simulate(p.mu, p.beta, p.sigma, st["amplitude"] * st["frequency"], 20_000, record=False, wall=ctl)
    assert st["confirmed"] and st["amplitude_error"] == sim.amplitude / st["amplitude"] - 1
    assert st["controller"] == "f" and st["controller_params"] == ctl.to_dict()
    un = next(r for r in recs if not r["stable"])
    assert un["subtick"] == (un["amplitude"] < 1.25)
