"""Eq. 11 uses the impact speed's magnitude |ẋ0|: a negative impact speed is refused, never flipped.

The CLI used to take ``--velocity -0.05`` as 0.05 (documented, but a silent transformation of the
input); every entry point that takes an impact speed now refuses it with the one rule of
:func:`dfa.checks.check_speed` (flag or parameter, value, rule, fix). ``dfa simulate`` keeps a signed
initial speed: there ξ'0 is an initial condition, its sign the direction of motion.
"""

from __future__ import annotations

import pytest

import dfa
from dfa.analysis.check import passivity_check
from dfa.analysis.limits.closed_form import stiffness_limits, stiffness_response
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.speed_chart import stiffness_speed_chart
from dfa.analysis.limits.zwidth import z_width
from dfa.analysis.maps import stability_map
from dfa.checks import check_speed
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.model.wall import Wall
from dfa.results.status import KMaxStatus, LimitStatus
from dfa.studies.design import design_analysis

IMPULSE = ["--device", "impulse"]


def _refused(capsys, *argv: str) -> str:
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and err.startswith(f"dfa {argv[0]}: error: ") and "Traceback" not in err, err
    assert out == ""
    return err


@pytest.mark.parametrize(
    "argv",
    [
        ["stiffness", *IMPULSE, "--velocity", "-0.05"],
        ["stiffness", *IMPULSE, "--velocity", "-0.05", "--virtual-damping", "1"],
        ["check", *IMPULSE, "--velocity", "-0.05"],
        ["zwidth", *IMPULSE, "--velocity", "-0.05", "--grid", "2"],
        ["report", *IMPULSE, "--velocity", "-0.05", "--out", "{tmp}"],
    ],
)
def test_eq11_cli_refuses_a_negative_velocity_naming_flag_value_rule_fix(capsys, tmp_path, argv):
    argv = [a.replace("{tmp}", str(tmp_path / "out")) for a in argv]
    err = _refused(capsys, *argv)
    assert "--velocity = -0.05 is invalid" in err
    assert "0, the impact speed's magnitude" in err  # the rule
    assert "give the impact speed's magnitude, e.g. 0.05 m/s" in err  # the fix
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_eq11_cli_refuses_a_negative_xi_dot_in_ticks(capsys):
    err = _refused(capsys, "check", "--mu", "5", "--beta", "0.1", "--sigma", "0.5", "--xi-dot", "-2")
    assert "--xi-dot = -2.0 is invalid" in err and "e.g. 2 ticks per sample" in err
    err = _refused(capsys, "stiffness", *IMPULSE, "--xi-dot", "-1")
    assert "--xi-dot = -1.0 is invalid" in err


def test_eq11_cli_zwidth_refuses_zero_velocity(capsys):
    err = _refused(capsys, "zwidth", *IMPULSE, "--velocity", "0", "--grid", "2")
    assert "--velocity = 0.0 is invalid: it must be a finite number > 0" in err and "give an impact speed > 0" in err


def test_eq11_cli_positive_velocity_reads_the_same_as_before(capsys):
    assert main(["stiffness", *IMPULSE, "--velocity", "0", "--json"]) == 0  # zero: the static end of eq. 11
    capsys.readouterr()
    assert main(["check", *IMPULSE, "--velocity", "0.05", "--json"]) == 0
    assert '"velocity": 0.05' in capsys.readouterr().out


def test_eq4_cli_simulate_keeps_a_signed_initial_speed(capsys):
    code = main(["simulate", "--mu", "5", "--beta", "0.1", "--sigma", "0.5", "--xi-dot", "-1", "--samples", "100"])
    assert code == 0, capsys.readouterr().err


@pytest.fixture(scope="module")
def impulse():
    return dfa.get_device("impulse").device


@pytest.mark.parametrize(
    "call",
    [
        lambda dev: design_answer(dev, -0.05),
        lambda dev: z_width(dev, -0.05, grid=2),
        lambda dev: design_answer(dev, -0.05, wall=Wall.of(100.0, damping=1.0)),
        lambda dev: stiffness_speed_chart(dev, velocity=-0.05),
        lambda dev: stiffness_limits(dev, -0.05),
        lambda dev: stiffness_response(dev, [0.1, -0.05]),
        lambda dev: design_analysis(dfa.get_device("impulse"), velocity=-0.05),
        lambda dev: passivity_check(dev, Wall.of(100.0, damping=1.0), -0.05),
    ],
    ids=[
        "design_answer",
        "z_width",
        "design_answer_wall",
        "speed_chart",
        "limits",
        "response",
        "design",
        "controller_check",
    ],
)
def test_eq11_api_refuses_a_negative_impact_speed_naming_the_parameter(impulse, call):
    with pytest.raises(DFAValueError) as err:
        call(impulse)
    assert str(err.value).startswith("velocity = -0.05 is invalid: it must be a finite number ")
    assert "the impact speed's magnitude" in str(err.value) and "e.g. 0.05" in str(err.value)


def test_eq11_api_refuses_zero_where_no_impact_is_analysed(impulse):
    with pytest.raises(DFAValueError, match=r"^velocity = 0\.0 is invalid: it must be a finite number > 0"):
        z_width(impulse, 0.0, grid=2)


@pytest.mark.parametrize("wall", [None, Wall.of(100.0, damping=1.0)], ids=["spring", "wall"])
def test_eq11_design_answer_at_zero_speed_searches_nothing(impulse, wall):
    """design_answer takes V = 0 (the static end of eq. 11, as `dfa stiffness --velocity 0`): the closed forms hold
    at rest, the describing-function and simulated limits are not searched (no impact to analyse), no run."""
    r = design_answer(impulse, 0.0, wall=wall)
    for lim in (r.k_df, r.k_sim, r.k_sim_rest):
        assert lim.value is None and lim.status is LimitStatus.NOT_SEARCHED
    assert r.evidence.simulations == 0 and r.counterexamples == () and r.status is KMaxStatus.OK
    assert r.k_linear.status is LimitStatus.FOUND


def test_fig4_stability_map_refuses_a_negative_speed():
    with pytest.raises(DFAValueError, match=r"^xi_dot = -1\.0 is invalid: .*e\.g\. 1 ticks per sample"):
        stability_map(5.0, [1.0, -1.0], grid=2, samples=10, n_jobs=1, progress=False)


def test_eq11_check_speed_one_rule():
    assert check_speed("v", 0.0) == 0.0 and check_speed("v", 2) == 2.0
    with pytest.raises(DFAValueError, match=r"^v = 0\.0 is invalid"):
        check_speed("v", 0.0, zero=False)
    with pytest.raises(
        DFAValueError, match=r"^v = -0\.5 is invalid: .*; give the impact speed's magnitude, e\.g\. 0\.5"
    ):
        check_speed("v", -0.5, "rad/s")
