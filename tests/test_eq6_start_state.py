"""The start state of the criterion's guarantee (issue 28 §1): stated with every verdict, and what it depends on.

The proof (dfa.analysis.criterion, steps 2 and 3) reads the past only through the delay line (d ≥ 1) and the
damper's velocity estimate and filter: the paper's spring without delay has no memory, so any history will do;
any other wall needs its memory fresh at t = 0. Also: a simulated run already cut to the search's longest is not
run again longer (a device of Δ = 1 km took 71 s in `dfa stiffness`).
"""

from __future__ import annotations

import json

import numpy as np

from dfa.analysis.criterion import passivity_criterion, start_state
from dfa.analysis.limits.runs import EXTEND_CAP, decide_undecided
from dfa.cli import main
from dfa.model.wall import Wall, WallParams
from dfa.render.start_state import start_state_note


def test_eq6_start_state_names_only_the_memory_the_wall_has():
    """No memory: any start. Delay: the pending commands; damper: the previous reading; filter: its output."""
    assert start_state(WallParams()).startswith("any: this wall has no memory")
    assert start_state_note(WallParams()) == "" and start_state_note(Wall.of(1000.0)) == ""
    delay = start_state(WallParams.of(delay=2))
    assert "the 2 pending commands equal the first" in delay and "previous reading" not in delay
    damper = start_state(WallParams.of(damping=0.3))
    assert "previous reading equals the first" in damper and "filter" not in damper and "pending" not in damper
    full = start_state(Wall.of(1000.0, damping=0.5, delay=1, filter_cutoff=100.0))
    assert "the pending command equals the first" in full and "filter's output is 0" in full
    assert start_state_note(WallParams.of(delay=1)) == " (for a wall whose memory is fresh at t = 0)"
    r = passivity_criterion(beta=0.002, sigma=2.03, xi_dot=1.0, wall=WallParams.of(delay=1))
    assert r.start_state == start_state(WallParams.of(delay=1)) == r.to_dict()["start_state"]


def test_eq6_start_state_in_the_cli_text_and_json(capsys):
    """`dfa check` prints the start state of its wall in a row and in the JSON, the same text."""
    for extra, memory in (([], False), (["--delay", "2"], True), (["--virtual-damping", "1"], True)):
        assert main(["check", "--device", "delta", "--velocity", "0.1", *extra, "--json"]) == 0
        d = json.loads(capsys.readouterr().out)
        state = d["start_state"]  # top level, for the spring's check and the controller's
        assert state == (d.get("criterion") or d)["start_state"]
        assert state.startswith("the wall's memory fresh") == memory
        assert main(["check", "--device", "delta", "--velocity", "0.1", *extra]) == 0
        out = " ".join(capsys.readouterr().out.split())
        assert f"start state {state}" in out


def test_runs_cut_to_the_longest_are_not_run_again():
    """decide_undecided runs an undecided run again (4×, up to 16× its length) only where allowed: a run already
    cut to the search's longest stays undecided, at its length, and is never handed to rerun."""
    asked = []

    def rerun(idx, ns):
        asked.extend(int(i) for i in idx)
        return ["undecided"] * len(idx)

    out, ns = decide_undecided(["undecided", "undecided"], [100, 100], "undecided", rerun, extend=[True, False])
    assert set(asked) == {0} and ns.tolist() == [100 * EXTEND_CAP, 100] and list(out) == ["undecided"] * 2
    assert np.all(out == "undecided")


def test_eq6_every_proof_claim_of_a_wall_with_memory_says_fresh(capsys):
    """The recommendation "(a proof …)", `dfa stiffness`'s closing note and `dfa require`'s "Only the criterion is a
    proof" carry the start state for a wall with memory (a delay), and nothing for the spring without delay."""
    base = ["--device", "delta", "--velocity", "0.1"]
    for extra, fresh in (([], False), (["--delay", "1"], True)):
        assert main(["stiffness", *base, *extra]) == 0
        out = " ".join(capsys.readouterr().out.split())
        assert ("a proof, for a wall whose memory is fresh at t = 0; no margin needed" in out) == fresh
        assert ("only the criterion is a proof (for a wall whose memory is fresh at t = 0)" in out) == fresh
        assert main(["require", *base, "--stiffness", "20000", *extra]) == 0
        out = " ".join(capsys.readouterr().out.split())
        assert ("Only the criterion is a proof, for a wall whose memory is fresh at t = 0;" in out) == fresh
