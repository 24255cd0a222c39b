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
