"""Runs too short to tell are run again longer before they count as not safe (issue 26 §2).

On the Impulse Engine with B = 1 N·s/m and d = 1 at 0.05 m/s, the no-divergence limit was 257 N/m "limited by
undecided runs": slowly decaying sub-tick chatter that ``dfa simulate`` calls undecided at its default length and
chatter at 400,000 samples. Extended, the limit moves up to where runs really diverge, near the describing
function's 478 N/m.
"""

from __future__ import annotations

import numpy as np

from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.runs import EXTEND_CAP, EXTEND_STEP, decide_undecided, simulate_points
from dfa.analysis.simulation import simulate
from dfa.model.catalogue import get_device
from dfa.model.wall import Wall

DEV = get_device("impulse").device
K, V = 257.14, 0.05 * 23 / 24  # a confirmation speed (24 speeds up to 0.05 m/s): 0.0479 m/s


def _point():
    p = DEV.params(K)
    w = Wall.of(K, damping=1.0, delay=1).params(DEV.period)
    return p, w, DEV.xi_dot(V)


def test_eq4_impulse_undecided_at_default_length_is_chatter_when_run_longer():
    p, w, xd = _point()
    short = simulate(p.mu, p.beta, p.sigma, xd, wall=w, record=False)
    long = simulate(p.mu, p.beta, p.sigma, xd, samples=400_000, wall=w, record=False)
    assert (short.outcome, long.outcome) == ("undecided", "chatter")
    outs, lengths = simulate_points([(p.mu, p.beta, p.sigma, 0.0, xd)], [w], 10**6)
    # the design run is simulate()'s at its extended length: decided, at most EXTEND_CAP × its first length
    assert outs == ["chatter"] and short.samples < lengths[0] <= EXTEND_CAP * short.samples
    again = simulate(p.mu, p.beta, p.sigma, xd, samples=lengths[0], wall=w, record=False)
    assert again.outcome == "chatter"


def test_eq4_decide_undecided_stops_at_the_cap_and_keeps_decided_runs():
    calls = []

    def rerun(idx, ns):
        calls.append((idx.tolist(), ns.tolist()))
        return ["undecided"] * len(idx)

    out, ns = decide_undecided(["undecided", "rest", "unstable"], [100, 100, 100], "undecided", rerun)
    assert out.tolist() == ["undecided", "rest", "unstable"] and ns.tolist() == [100 * EXTEND_CAP, 100, 100]
    assert [c[1][0] for c in calls] == [100 * EXTEND_STEP**i for i in range(1, 3)]
    assert all(c[0] == [0] for c in calls)


def test_eq4_impulse_no_divergence_limit_not_dragged_down_by_undecided_runs():
    ans = design_answer(DEV, 0.05, wall=Wall.of(1.0, damping=1.0, delay=1))
    k_sim, k_df = ans.k_sim.value, ans.k_df.value
    assert k_sim is not None and k_df is not None
    assert k_sim > 0.9 * k_df  # was 257 N/m against 478 N/m
    assert all(f.outcome != "undecided" for f in ans.k_sim.failures if f.stiffness < 0.9 * k_df)
    # independent check: a divergent impact just above the limit (what lowered it) is a divergence in simulate()
    f = min(ans.k_sim.failures, key=lambda f: f.stiffness)
    p = DEV.params(f.stiffness)
    w = Wall.of(f.stiffness, damping=1.0, delay=1).params(DEV.period)
    xd = DEV.xi_dot(f.velocity)
    from dfa.analysis.simulation import preload_position

    x0, v0 = (0.0, xd) if f.start == "impact" else (preload_position(p.mu, xd), 0.0)
    assert f.outcome == "unstable" and simulate(p.mu, p.beta, p.sigma, v0, xi0=x0, wall=w, record=False).outcome == (
        "unstable"
    )
    assert np.isfinite(k_sim) and k_sim < f.stiffness
