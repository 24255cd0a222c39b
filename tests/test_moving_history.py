"""A moving history (issue 28 §1): the spring with a delay whose d pending commands are those of a motion at
ξ'0 before t = 0, not the first reading's (the start an independent check found the fresh criterion unsound for).

Checked: ``dfa.simulate(..., history="moving")`` against ``solve_ivp`` with the ring filled by that motion; the
criterion for it (``history="moving"``, V* of :func:`dfa.analysis.criterion.moving_history_speed`) never
exceeded on sampled passive points, where the fresh criterion's claim fails; the issue's counterexample; the
command line.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import reference_ctl
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import dfa
from dfa.analysis.criterion import moving_history_speed, passivity_criterion
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.model.wall import WallParams

finite = dict(allow_nan=False, allow_infinity=False)


class _MovingCommands(reference_ctl.Commands):
    """The reference controller with its delay line filled by a motion at ``speed`` before t = 0."""

    speed = 0.0

    def applied(self, x: float) -> float:
        first = self.prev_r is None
        c = super().applied(x)
        if not first:
            return c
        past = [x - j * self.speed for j in range(self.ctl.delay, 0, -1)]  # ξ0 − dV … ξ0 − V, oldest first
        self.hist = [-(math.floor(p) + 0.5) if self.q else -p for p in past] + [c]
        return self.hist[0]


@settings(max_examples=25, derandomize=True, deadline=None)
@given(
    st.integers(1, 3),
    st.floats(0.5, 200.0, **finite),
    st.sampled_from([0.0, 0.05, 1.0]),
    st.sampled_from([0.0, 0.3, 2.0]),
    st.floats(-6.0, 6.0, **finite),
    st.floats(-4.0, 4.0, **finite),
    st.booleans(),
)
def test_eq4_moving_history_runs_against_solve_ivp(d, mu, beta, sigma, speed, x0, q):
    """The moving-history run (its first d forces are those of ξ0 − jξ'0) against solve_ivp to 1e-8."""
    assume(abs(speed) > 1e-3 and all(abs((x0 - j * speed) % 1.0 - 0.5) < 0.5 - 1e-9 for j in range(d + 1)))
    w = WallParams.of(delay=d)
    n = 60
    run = simulate(mu, beta, sigma, speed, n, x0, quantize=q, wall=w, history="moving", record=True)
    _MovingCommands.speed = speed
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(reference_ctl, "Commands", _MovingCommands)
        xs, vs = reference_ctl.simulate_ivp_ctl(mu, beta, sigma, x0, speed, n, w, quantize=q)
    m = run.samples_run + 1
    assume(np.all(np.abs(np.asarray(xs[:m]) % 1.0 - 0.5) < 0.5 - 1e-9) or not q)  # no reading on a tick boundary
    np.testing.assert_allclose(run.xi[:m], xs[:m], rtol=1e-12, atol=1e-8)  # relative: runs that grow
    np.testing.assert_allclose(run.xi_dot[:m], vs[:m], rtol=1e-12, atol=1e-8)


def test_eq6_moving_history_criterion_is_sound_where_the_fresh_claim_fails():
    """1500 derandomised passive points from a moving history: S = ½μξ'² + ½ξ² never exceeds ½μV*²; the fresh
    start's claim (S <= ½μV²) fails at many of them (the check can fail, the pending commands must be paid for).

    The 10⁵-point run: ``python -m dfa.cli.soundness_report --history`` (reports/validation)."""
    from dfa.studies.soundness import history_soundness

    r = history_soundness(1500, seed=2026)
    assert r.points == 1500 and r.violations == 0 and r.criterion == "moving"
    assert r.by_case is not None and min(r.by_case[f"d = {d}"] for d in (1, 2, 3)) > 400
    assert history_soundness(400, criterion="fresh", seed=2026).energy_grew > 40


def test_eq6_moving_history_the_issue_counterexample():
    """The independent check's point (μ = 171.9, β = 3.379, σ = 3.127, d = 3, ξ'0 = 21.71): the fresh criterion
    calls it passive and its fresh start keeps S <= S(0); from a moving history S rises above S(0), and the
    moving criterion does not call it passive (V*² = V² + d(d + 1)ξ'0²/(2μ))."""
    mu, beta, sigma, d, v = 171.9, 3.379, 3.127, 3, 21.71
    w = WallParams.of(delay=d)
    assert passivity_criterion(beta, sigma, v, wall=w, mu=mu).passive
    moving = passivity_criterion(beta, sigma, v, wall=w, mu=mu, history="moving")
    assert moving.equivalent_speed == pytest.approx(math.sqrt(v * v + d * (d + 1) * v * v / (2 * mu)), rel=1e-14)
    assert not moving.passive and moving.start_state.startswith("a moving history")
    for history, grows in (("fresh", False), ("moving", True)):
        run = simulate(mu, beta, sigma, v, 20_000, wall=w, history=history)
        rec = simulate(mu, beta, sigma, v, min(20_000, run.samples_run + 1), wall=w, history=history, record=True)
        peak = np.max(0.5 * mu * rec.xi_dot**2 + 0.5 * rec.xi**2) / (0.5 * mu * v * v)
        assert (peak > 1.0 + 1e-6) == grows, (history, peak)
    # the moving criterion's critical speed is a speed ξ'0: just below it the verdict passes
    vc = moving.critical_xi_dot
    assert vc is not None and passivity_criterion(beta, sigma, vc * (1 - 1e-9), wall=w, mu=mu, history="moving").passive
    assert moving_history_speed(v, v, mu, 0) == v  # no delay: no pending command, the fresh start


def test_moving_history_cli_and_refusals(capsys):
    """`dfa check --history moving` states the start and the verdict of the API; it needs --mu without a device
    and is refused with a damper; simulate refuses a moving history with a wall beyond the spring."""
    argv = ["check", "--beta", "3.379", "--sigma", "3.127", "--xi-dot", "21.71", "--delay", "3", "--mu", "171.9"]
    assert main([*argv, "--history", "moving", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["passive"] is False and d["start_state"].startswith("a moving history") and d["history"] == "moving"
    assert main([*argv[:-2], "--history", "moving"]) == 2
    assert "--history moving needs --mu" in capsys.readouterr().err
    dev = ["check", "--device", "delta", "--velocity", "0.05", "--delay", "1", "--history", "moving"]
    assert main(dev) == 0 and "a moving history" in " ".join(capsys.readouterr().out.split())
    assert main([*dev, "--virtual-damping", "1"]) == 2
    assert "--history moving is derived for the spring with a delay only" in capsys.readouterr().err
    with pytest.raises(dfa.DFAValueError, match="history = 'moving' is invalid with this wall"):
        simulate(100.0, 0.3, 1.0, 1.0, 100, wall=WallParams.of(delay=1, damping=0.2), history="moving")
    with pytest.raises(dfa.DFAValueError, match="not derived with a virtual damper"):
        passivity_criterion(1.0, 1.0, 1.0, wall=WallParams.of(delay=1, damping=0.2), mu=10.0, history="moving")
    with pytest.raises(dfa.DFAValueError, match="covered for the spring with a delay only"):  # not run by simulate
        passivity_criterion(1.0, 1.0, 1.0, wall=WallParams.of(delay=1, hand_stiffness=0.1), mu=10.0, history="moving")
