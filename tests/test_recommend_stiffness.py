"""One recommended stiffness and its rule (issue 26 §1; dfa.analysis.limits.recommend), checked independently:
the proven K against the criterion itself (eq. 11 extended to the wall) just below and above it, the simulated K
by re-simulating the impacts, and the numbers users read (the one screen, the JSON)."""

import dataclasses
import functools
import json

import numpy as np
import pytest

import dfa
import dfa.analysis.limits.kmax as kmax
from dfa.analysis.criterion import device_criterion
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.recommend import DEFAULT_MARGIN, Recommendation, recommend_stiffness
from dfa.analysis.limits.search import KLimit
from dfa.analysis.simulation import preload_position, simulate
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.model.device import Device
from dfa.model.wall import Wall
from dfa.render.answer import WIDTH, stiffness_screen
from dfa.results.status import KMaxStatus, LimitStatus, RecommendRule

SMALL = {"speeds": 2, "grid": 6}
CUSTOM = Device(mass=0.1, damping=0.005, coulomb=0.02, resolution=1e-5, period=1e-3)
PROVEN_CASES = [
    ("impulse", None, 0.1),
    ("delta", Wall.of(1.0, delay=1), 0.1),
    ("custom", Wall.of(1.0, damping=0.1), 0.1),
    ("custom", Wall.of(1.0, damping=0.02, filter_cutoff=100.0), 0.05),
]


def _device(name):
    return CUSTOM if name == "custom" else dfa.get_device(name).device


@pytest.mark.parametrize(("name", "wall", "v"), PROVEN_CASES)
def test_eq11_recommended_k_is_the_largest_k_the_criterion_proves_passive(name, wall, v):
    dev = _device(name)
    ans = design_answer(dev, v, wall=wall, **SMALL)
    rec = recommend_stiffness(ans)
    assert rec.status is RecommendRule.PROVEN and rec.basis == "k_criterion"
    k = rec.k_recommended
    w = Wall(1.0) if wall is None else wall
    # independent of how K_criterion was found (closed form or bisection): the criterion's own verdict
    assert device_criterion(dev, w.with_stiffness(k * (1 - 1e-6)), v).passive
    assert not device_criterion(dev, w.with_stiffness(k * 1.01), v).passive


def _diverges(dev, wall, k, speeds, n):
    """Any impact at the given speeds, from ξ0 = 0 or from the preload, that diverges at stiffness k."""
    p, c = dev.params(k), wall.with_stiffness(k).params(dev.period)
    for v in speeds:
        xd = dev.xi_dot(v)
        for x0, v0 in ((0.0, xd), (preload_position(p.mu, xd), 0.0)):
            r = simulate(p.mu, p.beta, p.sigma, v0, n, x0, wall=c, record=False)
            if r.outcome == "unstable":
                return True
    return False


def test_eq11_without_a_proof_the_recommendation_is_the_simulated_limit_over_the_margin():
    dev, wall, v = dfa.get_device("phantom").device, Wall.of(1.0, amplifier_bandwidth=500.0), 0.1
    ans = design_answer(dev, v, wall=wall, **SMALL)
    assert ans.k_criterion.status is LimitStatus.NOT_COVERED  # an amplifier lag: no sound criterion
    rec = recommend_stiffness(ans)
    assert rec.status is RecommendRule.SIMULATED and rec.margin == DEFAULT_MARGIN == 2.0
    assert rec.k_recommended == pytest.approx(ans.k_sim.value / 2.0, rel=1e-15)
    # independent re-simulation at the recommended K: no impact up to V diverges, from either start
    speeds = v * np.arange(1, 7) / 6
    assert not _diverges(dev, wall, rec.k_recommended, speeds, 20000)
    for m in (1.0, 4.0):
        assert recommend_stiffness(ans, m).k_recommended == pytest.approx(ans.k_sim.value / m, rel=1e-15)


def test_eq11_a_counterexample_withdraws_the_proof_and_no_limit_means_no_recommendation():
    ans = design_answer(dfa.get_device("impulse").device, 0.1, **SMALL)
    bad = dataclasses.replace(ans, status=KMaxStatus.COUNTEREXAMPLE)
    rec = recommend_stiffness(bad)
    assert rec.status is RecommendRule.SIMULATED and rec.basis == "k_sim"
    none = dataclasses.replace(
        ans,
        k_criterion=KLimit(None, LimitStatus.NONE_PROVEN),
        k_sim=KLimit(None, LimitStatus.BELOW_RANGE, range_end=1.0, range_verdict="unstable"),
    )
    r = recommend_stiffness(none)
    assert r.status is RecommendRule.NONE and r.k_recommended is None
    d = r.to_dict()
    assert d["k_recommended"] is None and d["null_reasons"]["/k_recommended"] == RecommendRule.NONE.message
    json.dumps(d, allow_nan=False)


@pytest.mark.parametrize("margin", [0.5, float("nan"), float("inf"), -2.0])
def test_recommendation_refuses_a_margin_below_one(margin):
    ans = design_answer(dfa.get_device("impulse").device, 0.1, **SMALL)
    with pytest.raises(DFAValueError, match="^margin"):
        recommend_stiffness(ans, margin)


def test_recommendation_record_is_validated():
    dev = dfa.get_device("impulse").device
    with pytest.raises(DFAValueError, match="None exactly under 'none'"):
        Recommendation(dev, Wall(1.0), 0.1, None, "k_sim", None, status=RecommendRule.SIMULATED)


@pytest.fixture
def small_search(monkeypatch):
    monkeypatch.setattr(kmax, "design_answer", functools.partial(design_answer, **SMALL))


CLI_CASES = [
    ["--device", "impulse", "--velocity", "0.05", "--stiffness", "2000"],
    ["--device", "phantom", "--velocity", "0.1", "--amplifier-bandwidth", "500"],
    ["--mass", "0.1", "--damping", "0.005", "--coulomb", "0.02", "--resolution", "1e-5", "--period", "1e-3",
     "--velocity", "0.1", "--virtual-damping", "0.1"],
    ["--device", "re35", "--velocity", "2", "--delay", "1", "--velocity-filter", "100"],
]  # fmt: skip


@pytest.mark.parametrize("argv", CLI_CASES)
def test_cli_stiffness_leads_with_the_recommendation_on_one_screen(capsys, small_search, argv):
    assert main(["stiffness", *argv]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert max(len(line) for line in lines) <= WIDTH
    assert len(lines) <= 30  # one screen
    assert main(["stiffness", *argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    rec = d["recommendation"]
    assert rec["status"] in {r.value for r in RecommendRule}
    k = rec["k_recommended"]
    head = "\n".join(lines[:4])
    assert (f"recommended K = {k:.5g} " in head) if k is not None else ("recommended K: none" in head)
    if rec["status"] == "proven":
        assert k == d["k_criterion"]["value"]
    elif rec["status"] == "simulated":
        assert k == pytest.approx(d["k_sim"]["value"] / rec["margin"], rel=1e-11)  # JSON: 12 digits


def test_cli_stiffness_margin_changes_the_simulated_recommendation(capsys, small_search, monkeypatch):
    argv = ["stiffness", "--device", "phantom", "--velocity", "0.1", "--amplifier-bandwidth", "500", "--json"]
    assert main([*argv, "--margin", "4"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["recommendation"]["k_recommended"] == pytest.approx(d["k_sim"]["value"] / 4, rel=1e-11)
    monkeypatch.setattr(kmax, "design_answer", lambda *a, **k: pytest.fail("searched before refusing the margin"))
    assert main([*argv, "--margin", "0.5"]) == 2  # refused up front, before the search
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "margin" in err[0] and "Traceback" not in err[0]


def test_cli_stiffness_diverging_k_is_not_called_merely_unguaranteed(capsys, small_search):
    """The user's K: "diverges in simulation from both starts" where the runs diverged (not only "no passivity
    guarantee"), consistent with the runs shown in the JSON."""
    argv = ["stiffness", "--device", "impulse", "--velocity", "0.05", "--stiffness", "2000"]
    assert main([*argv, "--json"]) == 0
    outcomes = json.loads(capsys.readouterr().out)["assessment"]["outcomes"]
    assert main(argv) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert outcomes["impact"] == outcomes["preload"] == "unstable"  # 13 × 2c/Δ: both runs diverge
    assert "your K = 2000 N/m: diverges in simulation at 0.05 m/s from both starts" in out
    assert "no passivity guarantee even at rest" in out  # the criterion's word stays, after the runs'


def test_screen_is_rendered_from_the_result_alone():
    ans = design_answer(dfa.get_device("delta").device, 0.1, wall=Wall.of(14500.0, damping=1.0), assess=True, **SMALL)
    lines = stiffness_screen(ans, recommend_stiffness(ans))
    assert all("\n" not in line and len(line) <= WIDTH for line in lines)
    assert lines[2].startswith("recommended K = ")  # device line, wall line, then the answer


def test_recommend_simulated_range_when_no_impact_diverged_in_the_range():
    """k_sim above the searched range (no divergence anywhere in it): the range's top over the margin, said so in
    the CLI line (it used to read "no simulated stiffness free of divergence", the opposite)."""
    from dataclasses import replace

    from dfa.analysis.limits.kmax import design_answer
    from dfa.analysis.limits.recommend import recommend_stiffness
    from dfa.analysis.limits.search import KLimit
    from dfa.model.catalogue import get_device
    from dfa.model.wall import Wall
    from dfa.render.answer import recommendation_text
    from dfa.results.status import LimitStatus, RecommendRule

    dev = get_device("Impulse Engine").device
    ans = design_answer(dev, 0.05, wall=Wall.of(1.0, amplifier_bandwidth=500.0), speeds=1, grid=6)
    top = 1234.5
    above = replace(ans, k_sim=KLimit(None, LimitStatus.ABOVE_RANGE, range_end=top))
    rec = recommend_stiffness(above, 2.0)
    assert rec.status is RecommendRule.SIMULATED_RANGE and rec.k_recommended == top / 2.0 and rec.k_basis == top
    assert "no simulated impact diverged up to 1234.5 N/m, the top of the range searched" in recommendation_text(rec)
