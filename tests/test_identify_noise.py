"""Noise on the force column (issue 45 a): identification stays consistent, its intervals cover the truth, and a
misfit that noise explains is no poor fit.

Checks: the issue's goal (5 % force noise on a 12 000-sample log: m, b, c within 5 %, a stiffness answer); the
noise level estimated against the one drawn (independent: the draw's own standard deviation); the 95 % intervals'
coverage over seeds (12 here, fast, Jacobian only; the 50-seed study with the bootstrap is
benchmarks/identify_noise_coverage.py, its result in reports/identify_noise_coverage.md); a clean log estimates
no noise; a log whose force column is not what drove the device is still a poor fit.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import dfa
from dfa.analysis.identify import NOISE_MAX, identify, synthetic_log
from dfa.cli import main
from dfa.model.log import DeviceLog, write_log
from dfa.results.status import IdentifyWarning


def _excited(samples: int):
    """m = 0.32 kg, b = 4 N·s/m, c = 0.2 N, Δ = 10 µm, T = 1 ms, and a square-plus-sine force that reverses."""
    dev = dfa.Device(0.32, 4.0, 0.2, 1e-5, 1e-3)
    f1 = 1.0 / (6.0 * 80.0 * dev.period)
    t = np.arange(samples) * dev.period
    return dev, 0.6 * np.sign(np.sin(2 * np.pi * f1 * t)) + 0.3 * np.sin(2 * np.pi * 3.3 * f1 * t)


def test_issue_goal_five_percent_noise_on_12000_samples(tmp_path, capsys):
    """5 % noise (of the force's standard deviation): m, b, c within 5 % (they are within 2 %), each interval holds
    the truth, the noise is estimated within 15 %, and --stiffness answers."""
    dev, force = _excited(12000)
    log = synthetic_log(dev, force, force_noise=0.05 * np.std(force), seed=4)
    r = identify(log, bootstrap=0)
    assert r.status.value == "caveats" and IdentifyWarning.FORCE_NOISE in r.warnings
    assert r.fit.within_one_tick < 0.9  # what the old criterion called a poor fit
    drawn = np.std(log.f - force) / np.std(log.f)
    assert r.force_noise_relative == pytest.approx(drawn, rel=0.15)
    for k in ("mass", "damping", "coulomb"):
        e, true = getattr(r, k), getattr(dev, k)
        assert e.value == pytest.approx(true, rel=0.02) and e.low <= true <= e.high, k
    path = write_log(log, tmp_path / "noisy.csv")
    assert main(["identify", path, "--bootstrap", "0", "--stiffness", "2000", "--velocity", "0.05", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["loop"]["recommendation"]["k_recommended"] > 0 and d["force_noise_relative"] == pytest.approx(
        r.force_noise_relative,
        rel=1e-6,  # the CSV holds the log to its written digits
    )


def test_intervals_cover_the_truth_under_noise_over_seeds():
    """2 % noise on 4000 samples, 12 seeds, the Jacobian's intervals with the noise term alone (no bootstrap): each
    parameter's 95 % interval holds the truth in at least 9 of 12 (at a true 95 %, 9 or more in 99.8 % of such
    studies; over seeds 0 to 99 these held m 95, b 93, c 93 of 100, and the bootstrapped ones more, in
    reports/identify_noise_coverage.md). The noise level is unbiased: its ratio to the drawn one averages within 8 %
    of 1 over these seeds (0.95; 0.99 over 100 seeds). With only the segments' starts taken off the noise's share of
    the residuals (not the global parameters' 15 %), it averaged 0.91 over 100 seeds."""
    dev, force = _excited(4000)
    covered = {"mass": 0, "damping": 0, "coulomb": 0}
    ratio = []
    for seed in range(12):
        log = synthetic_log(dev, force, force_noise=0.02 * np.std(force), seed=100 + seed)
        r = identify(log, bootstrap=0)
        assert r.status.value != "poor_fit"
        ratio.append(r.force_noise_relative / (np.std(log.f - force) / np.std(log.f)))
        for k in covered:
            e = getattr(r, k)
            covered[k] += e.low <= getattr(dev, k) <= e.high
    assert min(covered.values()) >= 9, covered
    assert np.mean(ratio) == pytest.approx(1.0, abs=0.08), ratio


def test_a_clean_log_estimates_no_noise_and_a_wrong_force_column_is_still_a_poor_fit():
    dev, force = _excited(4000)
    clean = identify(synthetic_log(dev, force), bootstrap=0)
    assert clean.force_noise == 0.0 and IdentifyWarning.FORCE_NOISE not in clean.warnings
    log = synthetic_log(dev, force)
    with pytest.warns(dfa.ImplausibleInputWarning):
        wrong = identify(DeviceLog(log.t, log.x, -log.f), bootstrap=0)
    assert wrong.status.value == "poor_fit" and wrong.force_noise_relative > NOISE_MAX


@pytest.mark.parametrize(
    ("bootstrap", "position", "expected"),
    [
        ("0", 0.0, "intervals from the fit's Jacobian alone (--bootstrap 0), with the force noise estimated below: "
         "too narrow, read them as a lower bound; they leave out dynamics the model lacks"),
        ("1", 0.0, "intervals from the fit's Jacobian alone (one replicate fit: a spread needs two), with the force "
         "noise estimated below: too narrow, a lower bound;"),
        ("2", 0.0, "intervals from the fit's Jacobian with the force noise estimated below and 2 replicate fits with "
         "the encoder's origin shifted and fresh force noise; they leave out dynamics the model lacks"),
        ("0", 2e-5, "intervals from the fit's Jacobian alone (--bootstrap 0), with the force and position noise "
         "estimated below: too narrow, read them as a lower bound;"),
    ],
)  # fmt: skip
def test_explain_interval_note_counts_the_replicates_with_noise(tmp_path, capsys, bootstrap, position, expected):
    """Found by review: with force noise and --bootstrap 0, --explain said the intervals came "from the fit's Jacobian
    ... and 0 replicate fits". No replicate: the Jacobian alone, named a lower bound as without noise; one: its
    spread is not taken (a spread needs two), so the same; two: counted."""
    dev, force = _excited(3000)
    log = synthetic_log(dev, force, force_noise=0.05 * np.std(force), position_noise=position, seed=4)
    path = write_log(log, tmp_path / "noisy.csv")
    assert main(["identify", path, "--bootstrap", bootstrap, "--explain"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert expected in out and "0 replicate" not in out and "1 replicate fits" not in out
