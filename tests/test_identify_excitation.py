"""Poor excitation said precisely (issue 45 e): which parameter a log cannot tell from which, and what motion would;
a constant force column is said to be one, not a poor fit.

Checks: a constant push on the Phantom gives pairs of estimates correlated beyond 0.95 (m with b, m with c), named
with the motion that separates them, in the text and the JSON; a well-excited log names none; a constant force
column gets no intervals, the constant-force reason, no force noise and no poor fit (the issue: m = 7e-16 kg flagged
with a reason that did not apply).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import dfa
from dfa.analysis.identify import identify, synthetic_log
from dfa.cli import main
from dfa.model.log import write_log
from dfa.render.identify import identify_lines
from dfa.results.status import IdentifyWarning


@pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")
def test_a_constant_push_names_the_pairs_it_cannot_tell_apart(tmp_path, capsys):
    ph = dfa.get_device("phantom").device
    log = synthetic_log(ph, np.full(3000, 0.1))
    r = identify(log, bootstrap=0)
    pairs = {(a, b): rho for a, b, rho in r.confounded}
    assert abs(pairs[("mass", "damping")]) > 0.95 and ("coulomb", "force_offset") not in pairs  # no_reversal says it
    text = "\n".join(identify_lines(r))
    assert "cannot tell the mass m from the damping b" in text and "force steps faster than the time constant" in text
    path = write_log(log, tmp_path / "push.csv")
    assert main(["identify", path, "--bootstrap", "0", "--json"]) == 0
    got = json.loads(capsys.readouterr().out)["confounded"]
    assert ["mass", "damping", pytest.approx(pairs[("mass", "damping")], rel=1e-9)] in got


def test_a_well_excited_log_names_no_pair():
    dev = dfa.Device(0.1, 0.5, 0.2, 1e-5, 1e-3)
    t = np.arange(3000) * dev.period
    r = identify(synthetic_log(dev, 2.0 * np.sign(np.sin(2 * np.pi * 2.0 * t)) + np.sin(2 * np.pi * 7.0 * t)))
    assert r.confounded == () and r.status.value == "ok"


@pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")
def test_a_constant_force_column_is_said_to_be_one():
    dev = dfa.Device(0.1, 0.5, 0.2, 1e-5, 1e-3)
    r = identify(synthetic_log(dev, np.full(3000, 0.5)), bootstrap=0)
    assert IdentifyWarning.CONSTANT_FORCE in r.warnings and r.status.value == "caveats"
    assert r.force_noise == 0.0 and r.confounded == ()
    for k in ("mass", "damping", "coulomb", "force_offset"):
        e = getattr(r, k)
        assert e.low is None and e.undetermined.value == "constant_force"
    assert "undetermined (constant force)" in "\n".join(identify_lines(r))
