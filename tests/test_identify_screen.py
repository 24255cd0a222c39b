"""`dfa identify`'s default text is one screen; `--explain` is the full evidence (:mod:`dfa.render.identify_screen`).

The longest case: a log taken with the paper's spring on (eq. 2), noise on its force column, three warnings,
K_max four ways, a sustained oscillation (the light device of examples/logs/limit_cycle.csv) and the contact set
beside the prediction. Independent reference for `--explain`: the full text assembled from the API's results by
the renderers the command used before it had a default screen.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import dfa
from dfa.analysis.closed_loop import closed_loop_evidence, logged_wall
from dfa.analysis.identify import identify, impact_log
from dfa.analysis.logged_cycle import compare_logged_cycle
from dfa.cli import main
from dfa.formatting import number
from dfa.model.log import read_log, write_log
from dfa.render.identify import closed_loop_lines, cycle_lines, identify_lines

pytestmark = pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")

K = 1000.0


@pytest.fixture(scope="module")
def noisy_cycle(tmp_path_factory):
    """An impact at 0.012 m/s on K = 1000 N/m that ends in a limit cycle, 2 % noise on the logged force."""
    log = impact_log(dfa.Device(0.01, 0.4, 0.001, 1e-5, 1e-3), K, 0.012, 3000, source="cycle.csv")
    f = log.f + np.random.default_rng(1).normal(0.0, 0.02 * np.std(log.f), log.samples)
    return write_log(dataclasses.replace(log, f=f), tmp_path_factory.mktemp("screen") / "cycle.csv")


def _split(lines: list[str]) -> list[str]:
    """The lines as printed (a wrapped sentence holds newlines)."""
    return "\n".join(lines).split("\n")


def _block(lines: list[str], block: list[str]) -> bool:
    """Whether ``block`` appears in ``lines`` as consecutive lines."""
    return any(lines[i : i + len(block)] == block for i in range(len(lines) - len(block) + 1))


def test_identify_default_is_one_screen_and_explain_holds_the_rest(noisy_cycle, capsys):
    """The default text of the longest case fits 30 lines under 100 characters and ends by pointing to --explain;
    --explain prints the identification, the oscillation and the contact in full (as assembled from the API), the
    stiffness method table and every warning's whole sentence: every line the default drops."""
    args = ["identify", str(noisy_cycle), "--stiffness", str(K), "--wall-on", "--bootstrap", "0"]
    assert main(args) == 0
    short = capsys.readouterr().out.splitlines()
    assert len(short) <= 30 and max(len(line) for line in short) < 100
    assert short[-1].startswith("--explain for the evidence")
    assert main([*args, "--explain"]) == 0
    full = capsys.readouterr().out.splitlines()
    assert len(full) > 2 * len(short) and not any(line.startswith("--explain for") for line in full)
    log = read_log(noisy_cycle)
    r = identify(log, bootstrap=0)
    assert len(r.warnings) >= 3 and r.force_noise > 0.0
    ev = closed_loop_evidence(r, log, logged_wall(K))
    cyc = compare_logged_cycle(r, log, K)
    head, contact = _split(identify_lines(r)), _split(closed_loop_lines(ev))
    assert full[: len(head)] == head and full[-len(contact) :] == contact
    assert _block(full, _split(cycle_lines(cyc))[1:])
    text = " ".join(" ".join(full).split())
    for w in r.warnings:  # each warning's whole sentence (the default has a few words of it)
        assert w.message in text
    assert "method K rests on" in text and "the same with any other speed or wall: dfa stiffness --mass" in text
    # the numbers the default keeps are the full text's
    rows = {line[:26].strip(): line[26:].split("  ") for line in short[-6:-2]}
    got = [c.strip() for c in rows["impacts / samples inside"] if c.strip()]
    assert got == [f"{m.impacts} / {m.contact_samples}" for m in (ev.logged, ev.predicted)]
    assert f"oscillation at the end: {number(cyc.logged.amplitude, 3)} ticks" in " ".join(short)
    assert f"({cyc.matching} of {len(cyc.replays)} replays end in it)" in " ".join(short)
    assert short[-2].startswith(f"contact {ev.status.value} ")
    assert _block(full, short[2:8])  # the table of values is the full text's
