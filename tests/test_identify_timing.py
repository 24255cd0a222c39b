"""The log's time column (issue 45 c): jitter, dropped and repeated samples are measured and reported, the fit
takes them into account, and the stiffness answer is set against the longest logged period.

Checks: m, b, c recovered from jittered, gapped and repeated-row logs of a known device as from the clean log;
the reported jitter against the jitter drawn (an independent number); the counts of dropped and repeated samples
against those made; the criterion at the longest period against eq. 11 written out; the numbers users read (CLI
text, JSON).
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import dfa
from dfa.analysis.identify import identify, log_timing, period_effect, synthetic_log
from dfa.cli import main
from dfa.model.log import DeviceLog, LogError, write_log
from dfa.results.status import IdentifyWarning

DEV = dfa.Device(0.1, 0.5, 0.2, 1e-5, 1e-3)


def _log(samples: int = 3000) -> DeviceLog:
    t = np.arange(samples) * DEV.period
    return synthetic_log(DEV, 2.0 * np.sign(np.sin(2 * np.pi * 2.0 * t)) + 1.0 * np.sin(2 * np.pi * 7.0 * t))


def _close(r, rel: float) -> None:
    for est, true in ((r.mass, DEV.mass), (r.damping, DEV.damping), (r.coulomb, DEV.coulomb)):
        assert est.value == pytest.approx(true, rel=rel)


def test_jittered_times_report_their_jitter_and_keep_the_values():
    """Sample instants jittered by σ = 2 % of T: steps of standard deviation σ√2; the fit's values stay within
    0.1 % of the device's; jitter beyond 1 % of T is a warning."""
    log = _log()
    sigma = 0.02 * DEV.period
    t = log.t + np.random.default_rng(3).normal(0.0, sigma, log.samples)
    r = identify(DeviceLog(t, log.x, log.f), bootstrap=0)
    assert r.timing.jitter_s == pytest.approx(sigma * np.sqrt(2.0), rel=0.05)
    assert r.timing.jitter_max_s > 3.0 * r.timing.jitter_s and r.timing.exceeds
    assert r.timing.period == pytest.approx(DEV.period, rel=1e-5)
    assert IdentifyWarning.JITTER in r.warnings and r.status.value == "caveats"
    _close(r, 1e-3)
    clean = identify(log, bootstrap=0)
    assert (
        not clean.timing.exceeds and clean.timing.jitter_max_s < 1e-12 and IdentifyWarning.JITTER not in clean.warnings
    )


def test_dropped_samples_are_counted_and_left_out_of_the_fit():
    """60 rows removed (one pair adjacent): 60 dropped in 59 gaps; values within 0.1 %, every logged sample within a
    tick of the fit."""
    log = _log()
    gone = np.r_[np.random.default_rng(1).choice(np.arange(20, 2980, 2), 58, replace=False), 1001, 1002]
    keep = np.setdiff1d(np.arange(log.samples), gone)
    assert gone.size == 60 and 1000 in keep and 1003 in keep
    r = identify(DeviceLog(log.t[keep], log.x[keep], log.f[keep]), bootstrap=0)
    gaps = np.count_nonzero(np.diff(keep) > 1)
    assert (r.timing.dropped, r.timing.gaps, r.timing.repeated) == (60, gaps, 0)
    assert r.fit.within_one_tick == 1.0 and len(r.logged) == log.samples
    _close(r, 1e-3)


def test_repeated_rows_are_dropped_and_change_nothing():
    """Rows repeating the time (and values) of the row before: counted, and the identification is the clean one's."""
    log = _log()
    rows = np.insert(np.arange(log.samples), [100, 200, 2000], [99, 199, 1999])
    r = identify(DeviceLog(log.t[rows], log.x[rows], log.f[rows]), bootstrap=0)
    clean = identify(log, bootstrap=0)
    assert r.timing.repeated == 3 and r.timing.dropped == 0
    for k in ("mass", "damping", "coulomb", "force_offset"):
        assert getattr(r, k).value == pytest.approx(getattr(clean, k).value, rel=1e-12, abs=1e-15)


def test_log_timing_counts_and_refuses_a_step_of_half_a_period():
    tm, index = log_timing([0.0, 1e-3, 2e-3, 2e-3, 5e-3, 6e-3])
    assert (tm.dropped, tm.gaps, tm.repeated) == (2, 1, 1) and index.tolist() == [0, 1, 2, -1, 5, 6]
    with pytest.raises(LogError, match=r"row 5 \(t = 0.0035 s\).* not a whole number of samples"):
        log_timing([0.0, 1e-3, 2e-3, 3.5e-3, 4.5e-3])
    with pytest.raises(LogError, match="goes backwards at row 4"):
        DeviceLog(np.r_[0.0, 1e-3, 0.5e-3, np.arange(3, 30) * 1e-3], np.zeros(30), np.zeros(30))


def test_period_effect_is_eq11_at_the_longest_period():
    """K_max = min(2c/Δ, (b v + c)/(T v/2 + Δ/2)) (eq. 11, no delay) at T and at the longest logged period."""
    tm, _ = log_timing(np.r_[0.0, np.cumsum(np.r_[np.full(50, 1e-3), 1.08e-3, np.full(50, 1e-3)])])
    assert tm.period_max == pytest.approx(1.08e-3, rel=1e-9) and tm.exceeds
    dev = _with_period(DEV, tm.period)
    e = period_effect(dev, tm, 0.05)

    def eq11(period: float) -> float:
        return min(2 * DEV.coulomb / DEV.resolution,
                   (DEV.damping * 0.05 + DEV.coulomb) / (period * 0.05 / 2 + DEV.resolution / 2))  # fmt: skip

    assert e.k_criterion == pytest.approx(eq11(tm.period), rel=1e-12)
    assert e.k_criterion_max == pytest.approx(eq11(1.08e-3), rel=1e-9) and e.k_criterion_max < e.k_criterion


def _with_period(dev: dfa.Device, period: float) -> dfa.Device:
    return dfa.Device(dev.mass, dev.damping, dev.coulomb, dev.resolution, period)


def test_cli_prints_and_writes_the_timing(tmp_path, capsys):
    """The text names the jitter, the gaps and the repeated rows; JSON has jitter_s, jitter_max_s and the counts;
    --stiffness adds the criterion at the longest period."""
    log = _log()
    rng = np.random.default_rng(5)
    keep = np.setdiff1d(np.arange(log.samples), [500, 1500])
    rows = np.insert(keep, 10, keep[9])  # row 10 repeats row 9, its time too
    t = log.t + rng.normal(0.0, 0.02 * DEV.period, log.samples)
    path = write_log(DeviceLog(t[rows], log.x[rows], log.f[rows]), tmp_path / "jitter.csv")
    assert main(["identify", path, "--bootstrap", "0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["timing"]
    assert (d["dropped"], d["gaps"], d["repeated"], d["jitter_exceeds"]) == (2, 2, 1, True)
    assert 0.02 * DEV.period < d["jitter_s"] < 0.04 * DEV.period and d["jitter_max_s"] > d["jitter_s"]
    assert main(["identify", path, "--bootstrap", "0", "--stiffness", "1000"]) == 0
    out = capsys.readouterr().out
    assert "2 samples dropped in 2 gaps" in out and "1 repeated row " in out and "% of T" in out
    assert "at the longest logged period" in out and "warning: a logged period departs from T" in out


def test_period_effect_recommends_at_the_longest_period_eq11_when_proven(tmp_path, capsys):
    """Jitter of 2 % of T, --stiffness 1000 --velocity 0.05: the recommended stiffness at T is the loop's, and at the
    longest logged period, where the rule is the proof, eq. 11 of the cautious device written out at that period;
    text and JSON. An answer of another device is refused."""
    log = _log()
    t = log.t + np.random.default_rng(3).normal(0.0, 0.02 * DEV.period, log.samples)
    path = write_log(DeviceLog(t, log.x, log.f), tmp_path / "jitter.csv")
    args = ["identify", path, "--bootstrap", "0", "--stiffness", "1000", "--velocity", "0.05"]
    assert main([*args, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["loop"]
    e, dev = d["period_effect"], d["device"]
    assert e["k_recommended"] == d["recommendation"]["k_recommended"] and e["grid_at_period_max"] == 8
    assert e["rule"] == e["rule_at_period_max"] == "proven"
    b, c, res = dev["damping"], dev["coulomb"], dev["resolution"]
    eq11 = min(2 * c / res, (b * 0.05 + c) / (e["period_max_s"] * 0.05 / 2 + res / 2))
    assert e["k_recommended_at_period_max"] == pytest.approx(eq11, rel=1e-9)
    assert e["k_recommended_at_period_max"] < e["k_recommended"]
    assert main(args) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert f"{e['k_recommended_at_period_max']:.5g} N/m (proven) at the longest logged period" in out
    with pytest.raises(dfa.DFAValueError, match="answer is invalid"):
        from dfa.analysis.limits.kmax import design_answer
        from dfa.model.loop import Loop

        period_effect(DEV, log_timing(t)[0], 0.05, answer=design_answer(Loop(DEV, 1000.0), 0.1, grid=4, speeds=1))
