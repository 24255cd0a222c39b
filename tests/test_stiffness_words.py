"""The words of ``dfa stiffness`` a new user tripped over (issue 41 §2): where the assessed K came from, what a
one-sided wall's criterion proves, a simulated limit above the range searched, and a passivity controller that
makes the wall worse or a recommended K that does not come to rest.

The searches run small (1 speed, 4 grid points; ``small_search``): the words do not depend on the grid.
"""

from __future__ import annotations

import functools
import json
import re

import pytest
from cli_text import unwrap
from result_json import written

import dfa
import dfa.analysis.limits.kmax as kmax
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.recommend import recommend_stiffness
from dfa.analysis.simulation import preload_position, simulate
from dfa.cli import main
from dfa.formatting import number
from dfa.model.catalogue import device_template, get_device
from dfa.model.elements import PassivityController
from dfa.model.wall import Wall
from dfa.render.answer import WIDTH
from dfa.results.status import LimitStatus, RecommendRule

SMALL = {"speeds": 1, "grid": 4}


@pytest.fixture
def small_search(monkeypatch):
    monkeypatch.setattr(kmax, "design_answer", functools.partial(design_answer, **SMALL))


def _run(capsys, *argv: str) -> tuple[str, dict]:
    """The text (wrapped lines joined) and the JSON of one ``dfa stiffness`` command."""
    assert main(["stiffness", *argv]) == 0
    raw = capsys.readouterr().out
    assert max(len(line) for line in raw.splitlines()) <= WIDTH
    assert main(["stiffness", *argv, "--json"]) == 0
    return unwrap(raw), json.loads(capsys.readouterr().out)


# ----------------------------------------------------------------------------- where K came from
def test_stiffness_names_the_device_file_its_k_came_from(capsys, tmp_path):
    """`--device-file my.toml`: the file's K is "the K of device file my.toml", not "(catalogue K)", on the screen,
    with --explain and in the JSON (speed 0: the closed forms alone, the words are the same)."""
    path = tmp_path / "my.toml"
    path.write_text(device_template(get_device("impulse")).replace("mass = 0.032", "mass = 0.04"), encoding="utf-8")
    argv = ["--device-file", str(path), "--velocity", "0"]
    text, d = _run(capsys, *argv)
    assert f"your K = 80 N/m (the K of device file {path}):" in text and "catalogue K" not in text
    assert d["stiffness_source"] == "device file"
    assert d["assessment"]["source"] == "device file" and d["assessment"]["source_file"] == str(path)
    assert main(["stiffness", *argv, "--explain"]) == 0
    explained = capsys.readouterr().out
    assert f"largest passive speed at K = 80 N/m (the K of device file {path})" in explained
    assert "catalogue K" not in explained
    assert main(["stiffness", *argv, "--stiffness", "70", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["stiffness_source"] == "--stiffness" and d["assessment"]["source"] == "given"
    assert "source_file" not in d["assessment"]


def test_design_answer_refuses_a_source_file_without_a_device_file_source():
    dev = get_device("impulse").device
    with pytest.raises(dfa.DFAValueError, match="source_file = 'x.toml' is invalid with source = 'given'"):
        design_answer(dev, 0.0, wall=80.0, assess=True, source_file="x.toml")


# ----------------------------------------------------------------------------- a one-sided wall, a held device
def test_one_sided_push_says_no_speed_is_proven_and_a_limit_above_the_range_is_a_lower_bound(capsys, small_search):
    """With a push the storage at first contact alone can exceed the criterion's bound: the largest passive
    speed is 0, which reads "no speed is proven" and why (not "proven passive up to 0 m/s"); a simulated limit
    with no failure in the range searched reads "> K_top" with its note (not "none *2")."""
    dev = get_device("delta").device
    from dfa.analysis.limits.kmax import passive_speed
    from dfa.model.elements import OneSided, Push

    assert passive_speed(dev, Wall(58000.0, (OneSided(0.0), Push(1.0))), 58000.0)[0] == 0.0  # the case itself
    text, d = _run(capsys, "--device", "delta", "--one-sided", "--push", "1", "--stiffness", "58000",
                   "--velocity", "0.05")  # fmt: skip
    assert "0 m/s)" not in text and "up to 0 m/s" not in text
    assert (
        "your K = 58000 N/m: no passivity guarantee at 0.05 m/s (no speed is proven: the storage at the first "
        "reading inside (the penetration, the push, the pending commands) alone exceeds the criterion's bound)"
    ) in text
    assert d["assessment"]["max_passive_velocity"] == 0.0
    assert d["k_sim"]["status"] == LimitStatus.ABOVE_RANGE.value
    top = number(d["k_sim"]["range_end"], 5)
    row = re.search(r"^simulation, no divergence +(.*?) {2,}", text, re.M)
    assert row is not None and re.fullmatch(rf"> {re.escape(top)} N/m \*(\d)", row.group(1)), row
    mark = re.fullmatch(r".*\*(\d)", row.group(1)).group(1)  # type: ignore[union-attr]
    assert f"*{mark} simulation, no divergence: no failure up to the top of the range searched" in text
    assert "none *" not in text.split("simulation, no divergence", 1)[1].splitlines()[0]


def test_every_speed_reads_once_with_the_held_devices_bound(capsys, small_search):
    """`--hand paper` on the Phantom: K <= 2(b + b_h)/T, passive at every speed, said once in plain words (it read
    "proven, up to every speed (K <= 2b/T = 9610 N/m))")."""
    text, d = _run(capsys, "--device", "phantom", "--hand", "paper", "--velocity", "0.1")
    assert d["assessment"]["velocity_status"] == "all_speeds"
    k_cs = number(d["k_colgate"], 5)
    assert f"your K = 1015 N/m (catalogue K): passive at every speed (proven: K <= 2(b + b_h)/T = {k_cs} N/m);" in text
    assert "))" not in text and "up to every speed" not in text


# ----------------------------------------------------------------------------- the passivity controller
IMPULSE = ["--device", "impulse", "--velocity", "0.05", "--passivity-controller"]


def test_textbook_controller_that_lowers_the_limit_is_said_and_the_plain_wall_recommended(capsys, small_search):
    """Without --pc-force-limit the controller (the textbook one) lowers the Impulse Engine's simulated limit at
    0.05 m/s: the answer says so and recommends the wall without it, by that wall's own rule."""
    dev = get_device("impulse").device
    wall = Wall(80.0, (PassivityController(),))
    plain = design_answer(dev, 0.05, wall=wall.without_controller(), **SMALL)
    controlled = design_answer(dev, 0.05, wall=wall, **SMALL)
    assert controlled.k_sim.value < plain.k_sim.value  # the case: the controller makes the wall worse
    text, d = _run(capsys, *IMPULSE)
    rec = d["recommendation"]
    assert rec["k_recommended"] == written(plain.k_criterion.value) and rec["status"] == RecommendRule.PROVEN.value
    assert rec["wall"]["stiffness"] == 80.0 and "elements" not in rec["wall"]  # the plain wall's
    c = rec["controller"]
    assert c["kept"] is False and c["lowers_limit"] is True and c["force_limit"] is None
    assert c["k_sim"] == written(controlled.k_sim.value) and c["plain_k_sim"] == written(plain.k_sim.value)
    k, ks, kp = (number(x, 5) for x in (plain.k_criterion.value, controlled.k_sim.value, plain.k_sim.value))
    assert "passivity controller (unbounded observer, no force limit: the textbook controller)" in text
    assert f"recommended K = {k} N/m, for the wall without the passivity controller: the largest K the " in text
    assert (
        f"The passivity controller makes this wall worse: with it the simulated no-divergence limit is {ks} N/m, "
        f"against {kp} N/m without it; it has no force limit (the textbook controller): --pc-force-limit N bounds "
        "its force"
    ) in text


def test_recommended_k_above_the_rest_limit_says_the_wall_may_buzz(capsys, small_search):
    """With a force limit the controller keeps the Impulse Engine from diverging over the whole range, so the
    recommended K is the range's top over the margin: far above the rest limit, where every impact chatters
    (checked by simulation). The answer says so."""
    dev = get_device("impulse").device
    text, d = _run(capsys, *IMPULSE, "--pc-force-limit", "0.5")
    rec = d["recommendation"]
    assert rec["status"] == RecommendRule.SIMULATED_RANGE.value and rec["controller"]["kept"] is True
    assert rec["above_rest"] is True and rec["k_rest"] == d["k_sim_rest"]["value"] < rec["k_recommended"]
    k = rec["k_recommended"]
    assert f"recommended K = {number(k, 5)} N/m: no proof at 0.05 m/s: no simulated impact diverged up to " in text
    assert (
        f"; it lies above the simulated rest limit, {number(rec['k_rest'], 5)} N/m (the largest K at which every "
        "simulated impact up to V rests): the wall may buzz or oscillate at this K. Without the passivity "
        f"controller the recommended K would be {number(rec['controller']['plain_k_recommended'], 5)} N/m"
    ) in text
    # independently: at the recommended K the impact at V, from ξ0 = 0 and from the preload, does not rest
    w = Wall(k, (PassivityController(force_limit=0.5),)).params(dev.period, dev.resolution)
    p, xd = dev.params(k), dev.xi_dot(0.05)
    for x0, v0 in ((0.0, xd), (preload_position(p.mu, xd), 0.0)):
        assert simulate(p.mu, p.beta, p.sigma, v0, 200_000, x0, wall=w, record=False).outcome == "chatter"


def test_a_recommendation_below_the_rest_limit_says_nothing_of_it():
    ans = design_answer(get_device("impulse").device, 0.05, **SMALL)
    rec = recommend_stiffness(ans)
    assert rec.k_rest == ans.k_sim_rest.value and rec.k_recommended < rec.k_rest and rec.above_rest is False
    assert rec.controller is None and "controller" not in rec.to_dict()
    from dfa.render.answer import recommendation_text

    assert "rest limit" not in recommendation_text(rec) and "controller" not in recommendation_text(rec)


def test_recommend_with_plain_refuses_an_answer_of_another_wall():
    dev = get_device("impulse").device
    wall = Wall(80.0, (PassivityController(force_limit=0.5),))
    ans = design_answer(dev, 0.0, wall=wall)  # speed 0: the closed forms alone
    other = design_answer(dev, 0.0, wall=Wall.of(80.0, damping=0.1))
    with pytest.raises(dfa.DFAValueError, match="plain is not the answer of the same wall"):
        recommend_stiffness(ans, plain=other)


def test_no_guarantee_prints_its_proven_speed_below_the_impact_speed():
    """A new user's finding: "no passivity guarantee at 0.1 m/s (proven passive up to 0.1 m/s)". The proven
    speed just below the impact speed prints with the digits that show it below (eq. 12's critical speed)."""
    import re

    from dfa.analysis.limits.closed_form import k_max_criterion, max_passive_velocity
    from dfa.analysis.limits.kmax import design_answer
    from dfa.model.wall import Wall
    from dfa.render.answer import user_verdict

    dev, v = dfa.get_device("delta").device, 0.1
    k = float(k_max_criterion(dev, v, 0)) * (1.0 + 1e-6)  # just too stiff: proven up to just below 0.1 m/s
    mpv = float(max_passive_velocity(dev, k, 0))
    assert mpv < v and f"{mpv:.4g}" == "0.1"  # the case: 4 digits would print the impact speed itself
    r = design_answer(dev, v, wall=Wall.of(k), assess=True, grid=4, speeds=1)
    text = " ".join(user_verdict(r).split())
    m = re.search(r"no passivity guarantee at [0-9.]+ m/s \(proven passive up to ([0-9.]+) m/s\)", text)
    assert m is not None, text
    assert float(m.group(1)) < v and abs(float(m.group(1)) - mpv) <= 1e-6 * mpv
