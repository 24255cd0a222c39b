"""Identification from logs taken with the wall on (issue 45 b, :mod:`dfa.analysis.closed_loop`).

Closed-loop logs come from the package's own exact simulator (an impact on a wall of known K, B, delay, bilateral
or one-sided, the wall's force per sample, :func:`dfa.analysis.identify.impact_log`), written to CSV and read
back. Independent references: the true device's values; the simulator's own outcome of the true run
(:func:`dfa.analysis.simulation.simulate`, its kernel's classification over its default run length) against the
measure of the log's readings; a spring of another K, whose force column is the given one scaled by K/K'.
"""

from __future__ import annotations

import dataclasses
import json
import warnings

import pytest

import dfa
from dfa.analysis.closed_loop import check_wall_force, closed_loop_evidence, logged_wall
from dfa.analysis.identify import identify, impact_log
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.formatting import number
from dfa.model.log import read_log, write_log
from dfa.model.loop import Loop

pytestmark = pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")

#: (device, wall, impact speed m/s, samples, the outcome the true run ends in): a chatter on a spring with a
#: damper, a growing oscillation with a damper and a delay, an impact that leaves a one-sided wall.
CASES = {
    "chatter": (dfa.Device(0.01, 0.2, 0.003, 1e-5, 1e-3), dict(stiffness=1000.0, damping=0.5), 0.05, 3000),
    "grows": (dfa.Device(0.02, 0.3, 0.002, 1e-5, 1e-3), dict(stiffness=800.0, damping=0.1, delay=1), 0.02, 4000),
    "leaves": (dfa.Device(0.01, 0.1, 0.003, 1e-5, 1e-3), dict(stiffness=1000.0, one_sided=True), 0.05, 3000),
}


def _log(tmp_path, case):
    """The case's closed-loop log, through a CSV file."""
    dev, wall, v, n = CASES[case]
    w = logged_wall(**wall)
    path = tmp_path / f"{case}.csv"
    write_log(impact_log(dev, w, v, n), path)
    return dev, w, v, path


def _identified(path):
    """The log read back from its CSV file and identified (no bootstrap; the closed-loop logs' warnings, such as
    little motion, are not what these tests check)."""
    log = read_log(path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return log, identify(log, bootstrap=0)


@pytest.mark.parametrize("case", list(CASES))
def test_eq4_closed_loop_log_contact_is_the_simulators(tmp_path, case):
    """The wall's force column is that wall's law of the readings (to rounding); the log's contact, measured on its
    readings, is the outcome the simulator gives the true run (its own classifier over its default length), and
    the prediction for the identified device agrees with it."""
    dev, w, v, path = _log(tmp_path, case)
    log, r = _identified(path)
    e = closed_loop_evidence(r, log, w)
    truth = simulate(Loop(dev, w), dev.xi_dot(v), record=False)
    assert e.check.status.value == "consistent" and e.check.within == 1.0
    assert e.check.max_mismatch <= 1e-9 * e.check.force_step
    assert e.logged.outcome == truth.outcome and e.logged.contact == truth.contact
    assert e.status.value == "agrees" and e.predicted.outcome == truth.outcome
    assert e.start == 0 and e.impact_speed == pytest.approx(v, rel=0.05)
    assert e.logged.impacts >= 1 and e.logged.first_contact == 0


@pytest.mark.parametrize("case", list(CASES))
def test_eq4_closed_loop_replays_across_the_intervals(tmp_path, case):
    """The prediction is replayed with b and c at the ends of their 95 % intervals and at their values (each pair
    once; 0 and the value where the log does not bound one); the identified values' replay is the prediction, the
    count is of replays whose contact is the logged one, and ``agrees`` needs the prediction itself to match."""
    dev, w, _v, path = _log(tmp_path, case)
    log, r = _identified(path)
    e = closed_loop_evidence(r, log, w)
    grid = {(b, c) for b in _ends(r.damping) for c in _ends(r.coulomb)}
    assert {(b, c) for b, c, _o, _m in e.replays} == grid and len(e.replays) == len(grid)
    nominal = [m for b, c, o, m in e.replays if (b, c) == (r.device.damping, r.device.coulomb)]
    assert nominal == [True] and e.status.value == "agrees"
    assert e.matching == sum(m for *_x, m in e.replays) >= 1
    for _b, _c, o, m in e.replays:  # a replay that matches has the logged outcome, one that does not another
        assert (o == e.logged.outcome.value) or not m
    d = e.to_dict()
    assert d["matching"] == e.matching and len(d["replays"]) == len(e.replays)


def _ends(est):
    """An estimate's interval ends and its value (0 and the value when unbounded)."""
    return sorted({0.0, est.value} if est.low is None else {est.low, est.value, est.high})


def test_eq4_closed_loop_differs_only_when_no_device_in_the_intervals_matches(tmp_path):
    """The chatter on a spring with a damper: with c at the top of its interval the exact simulation rests
    (independent: the simulator's own outcome of that device's run), while the truth chatters. An identification
    whose values put c at that top, its interval unchanged, is ``within_intervals`` (replays inside the interval
    chatter as logged); with the interval shrunk onto the top as well, no replay matches: ``differs``."""
    dev, w, v, path = _log(tmp_path, "chatter")
    log, r = _identified(path)
    top = r.coulomb.high
    high_c = dataclasses.replace(r.device, coulomb=top)
    assert simulate(Loop(high_c, w), high_c.xi_dot(v), record=False).outcome.value == "rest"
    assert simulate(Loop(dev, w), dev.xi_dot(v), record=False).outcome.value == "chatter"
    assert r.coulomb.low <= dev.coulomb <= top and r.damping.low <= dev.damping <= r.damping.high
    e = closed_loop_evidence(dataclasses.replace(r, device=high_c), log, w)
    assert e.logged.outcome.value == "chatter" and e.predicted.outcome.value == "rest"
    assert e.status.value == "within_intervals" and 1 <= e.matching < len(e.replays)
    assert all(not m for _b, c, _o, m in e.replays if c == top)
    pinned = dataclasses.replace(r.coulomb, value=top, low=top, high=top)
    e = closed_loop_evidence(dataclasses.replace(r, device=high_c, coulomb=pinned), log, w)
    assert e.status.value == "differs" and e.matching == 0 and "within their 95 % intervals" in e.status.message


def test_eq4_closed_loop_identifies_m_b_c():
    """Identification uses the wall's force as the applied force, in contact or not: a growing oscillation against
    a spring with a damper and a delay gives m, b within 1 % and c within 5 % of the truth."""
    dev, wall, v, n = CASES["grows"]
    log = impact_log(dev, logged_wall(**wall), v, n)
    r = identify(log, bootstrap=0)
    assert r.mass.value == pytest.approx(dev.mass, rel=0.01)
    assert r.damping.value == pytest.approx(dev.damping, rel=0.01)
    assert r.coulomb.value == pytest.approx(dev.coulomb, rel=0.05)


@pytest.mark.parametrize("factor", [1.1, 0.8])
def test_eq2_wrong_stiffness_is_flagged(factor):
    """A K that is not the log's: the force column misses the law at most samples in contact (mismatch), and the
    ratio logged/law is K_log/K_given."""
    dev, wall, v, n = CASES["grows"]
    log = impact_log(dev, logged_wall(**wall), v, n)
    k = wall["stiffness"] * factor
    c = check_wall_force(log, logged_wall(k, damping=wall["damping"] * factor, delay=1), dev)
    assert c.status.value == "mismatch" and c.within < 0.5
    assert c.ratio == pytest.approx(1.0 / factor, rel=1e-6)
    d = check_wall_force(log, logged_wall(wall["stiffness"], damping=wall["damping"], delay=0), dev)
    assert d.status.value == "mismatch"  # the delay given wrong


def test_closed_loop_cli_text_and_json_carry_the_numbers(tmp_path, capsys):
    """`dfa identify --wall-on`: the JSON's closed_loop record and the text's contact table carry the same
    numbers (impacts, samples inside, the deepest reading in ticks and m, the outcomes, the check's share), and
    the logged outcome is the simulator's of the true run (an impact that comes to rest on the spring)."""
    dev = dfa.Device(0.1, 0.5, 0.2, 1e-5, 1e-3)
    path = tmp_path / "spring.csv"
    write_log(impact_log(dev, 2000.0, 0.05, 1000), path)
    truth = simulate(Loop(dev, 2000.0), dev.xi_dot(0.05), record=False)
    args = ["identify", str(path), "--stiffness", "2000", "--wall-on", "--bootstrap", "0"]
    assert main([*args, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["closed_loop"]
    assert d["check"]["status"] == "consistent" and d["check"]["within"] == 1.0 and d["wall"]["stiffness"] == 2000.0
    lg, pr = d["logged"], d["predicted"]
    assert lg["outcome"] == pr["outcome"] == truth.outcome.value == "rest" and d["status"] == "agrees"
    assert lg["penetration_si"] == pytest.approx(lg["penetration"] * 1e-5)
    assert d["null_reasons"]["/eventual_contact"] and lg["null_reasons"]["/frequency"].startswith("no cycle")
    assert main(args) == 0  # one screen: the check's share and a short table
    out = capsys.readouterr().out
    assert "wall on: K = 2000 N/m, bilateral; force column the wall's (100 % within ½ K Δ)" in out
    rows = {line[:26].strip(): line[26:].split("  ") for line in out.splitlines()[-6:-2]}
    rows = {k: [c.strip() for c in v if c.strip()] for k, v in rows.items()}
    inside = [f"{m['impacts']} / {m['contact_samples']}" for m in (lg, pr)]
    assert rows["impacts / samples inside"] == inside and rows["outcome"] == ["rest", "rest"]
    assert rows["deepest reading"] == [f"{number(m['penetration'], 4)} ticks" for m in (lg, pr)]
    assert out.splitlines()[-2].startswith("contact agrees") and out.splitlines()[-1].startswith("--explain")
    assert main([*args, "--explain"]) == 0  # the evidence: the full table, in ticks and m
    out = capsys.readouterr().out
    assert "logged with the wall on: K = 2000 N/m, bilateral" in out
    assert f"100 % of {d['check']['samples']} samples within ½ K Δ = 0.02 N" in out
    rows = {line[:19].strip(): line[19:].split() for line in out.splitlines()[-12:]}
    assert rows["impacts"] == [str(lg["impacts"]), str(pr["impacts"])]
    assert rows["samples inside"] == [str(lg["contact_samples"]), str(pr["contact_samples"])]
    deep = f"{number(lg['penetration'], 4)} ticks ({number(lg['penetration_si'], 3)} m)"
    assert deep in out and rows["outcome"] == ["rest", "rest"] and "contact agrees" in out


@pytest.mark.parametrize(
    ("extra", "says"),
    [
        (["--wall-on"], "--wall-on needs --stiffness"),
        (["--delay", "1"], "--delay needs --wall-on"),
        (["--one-sided", "--stiffness", "800"], "--one-sided needs --wall-on"),
        (["--virtual-damping", "0.1", "--stiffness", "800"], "--virtual-damping needs --wall-on"),
        (["--wall-on", "--stiffness", "800", "--virtual-damping", "-1"], "--virtual-damping -1 is invalid"),
        (["--wall-on", "--stiffness", "800", "--delay", "x"], "not a whole number"),
    ],
)
def test_closed_loop_cli_bad_inputs_exit_2(tmp_path, capsys, extra, says):
    """Flags of the logged wall without --wall-on (or it without K), a negative B, a delay that is no whole
    number: one line on stderr, exit 2, before the log is read."""
    code = None
    try:
        code = main(["identify", str(tmp_path / "never_read.csv"), *extra])
    except SystemExit as exc:  # argparse's own refusal
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2 and says in err and "Traceback" not in err
