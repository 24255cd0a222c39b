"""A one-sided wall reached from free space (issue 28 §1, in part): the exact simulator and `dfa simulate`.

The wall pushes only while the reading is beyond its surface and never pulls (:class:`dfa.model.elements.OneSided`);
the operator may push toward it (:class:`dfa.model.elements.Push`); a run that starts outside moving toward it is
an approach at constant speed whose operator's force becomes the push at the first reading inside
(:mod:`dfa.analysis.approach`). Checked:

- whole runs (contact, release, stick-slip, the damper's clip, delay, filter, amplifier lag) against the
  ``solve_ivp`` loop of ``tests/reference_ctl.py`` to 1e-8, up to the sample the kernel stops at (runs with a
  sample instant within 1e-9 of a tick boundary left out: rounding decides that reading);
- ``left`` only when nothing can bring the device back (no push), and never with a push;
- the approach's memory: a run after a longer approach is the same run (the filter forgot its fresh start);
- the analyses without a derivation for it refuse it (criterion, linear bound, describing function);
- ``dfa simulate --one-sided`` (text, JSON) and its refusals.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference_ctl import simulate_ivp_ctl

import dfa
from dfa.analysis.approach import approach_samples, approach_start
from dfa.analysis.criterion import passivity_criterion
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.model.elements import NotCovered, OneSided, Push
from dfa.model.wall import Wall, WallParams

finite = dict(allow_nan=False, allow_infinity=False)


def _wall(surface=0.0, push=0.0, **groups) -> WallParams:
    extra = ((Push, push),) if push else ()
    return WallParams(((OneSided, surface), *extra, *WallParams.of(**groups).groups))


WALLS = st.builds(
    lambda s, p, b, d, cut, lag: _wall(s, p, damping=b, delay=d, cutoff=cut, lag=lag),
    st.sampled_from([0.0, 0.3, -0.4]),
    st.sampled_from([0.0, 0.3, 2.0]),
    st.sampled_from([0.0, 0.5]),
    st.integers(0, 2),
    st.sampled_from([None, 0.1]),
    st.sampled_from([0.0, 0.3]),
)


@settings(max_examples=40, derandomize=True, deadline=None)
@given(
    WALLS,
    st.floats(0.3, 300.0, **finite),
    st.sampled_from([0.0, 0.01, 1.0]),
    st.sampled_from([0.0, 0.2, 1.5]),
    st.floats(0.05, 5.0, **finite),
)
def test_eq4_one_sided_runs_against_solve_ivp(wall, mu, beta, sigma, speed):
    """Approach, contact, release and return (or rest, or leaving) to 1e-8 of the solve_ivp loop."""
    x0, v0, d = approach_start(speed, wall=wall)
    n = d + 120
    r = simulate(mu, beta, sigma, v0, samples=n, xi0=x0, wall=wall, record=True)
    ix, iv = simulate_ivp_ctl(mu, beta, sigma, x0, v0, n, wall)
    k = n + 1 if r.rest_sample is not None else r.samples_run + 1
    edge = np.abs(ix[:k] - np.round(ix[:k]))  # a reading at a tick boundary is decided by rounding (V = 2: ξ = 1)
    assume(np.all(edge[np.isfinite(edge)] > 1e-9))
    scale = max(1.0, float(np.max(np.abs(ix[:k]))))
    assert np.max(np.abs(r.xi[:k] - ix[:k])) <= 1e-8 * scale
    assert np.max(np.abs(r.xi_dot[:k] - iv[:k])) <= 1e-8 * scale
    if r.outcome == "left":  # nothing brings it back: no push, and the reference keeps moving away, outside
        assert wall.kernel_args()["push"] == 0.0 and np.all(np.diff(ix[k - 1 :]) <= 0.0)
        assert np.all(np.floor(ix[k - 1 :]) + 0.5 <= wall.kernel_args()["surface"])


def test_eq4_one_sided_free_impact_leaves_and_a_push_keeps_contact():
    """Without friction a free impact bounces off and leaves; a push above friction holds it against the wall."""
    w = _wall()
    x0, v0, d = approach_start(1.0, wall=w)
    free = simulate(50.0, 0.0, 0.0, v0, samples=d + 500, xi0=x0, wall=w)
    assert free.outcome == "left" and free.final_xi_dot < 0.0
    pushed = _wall(push=0.8)
    held = simulate(50.0, 0.3, 0.5, v0, samples=d + 20_000, xi0=x0, wall=pushed)
    assert held.outcome != "left" and held.outcome == "rest" and np.floor(held.final_xi) + 0.5 > 0.0  # inside
    bilateral = simulate(50.0, 0.3, 0.5, 1.0, samples=20_000)
    assert bilateral.outcome != "left"  # a bilateral wall never leaves


def test_eq4_one_sided_approach_memory_is_the_approach_not_the_start():
    """After D or D + 500 samples of approach the run from contact on is the same (to 1e-9): the filter forgot."""
    w = _wall(damping=0.8, delay=1, cutoff=0.02)
    d = approach_samples(w)
    assert d == 1 + 2 + int(np.ceil(np.log(1e16) / (2 * np.pi * 0.02)))
    runs = []
    for extra in (0, 500):
        x0, v0, dd = approach_start(0.7, wall=w, samples=d + extra)
        r = simulate(20.0, 0.05, 0.3, v0, samples=dd + 400, xi0=x0, wall=w, record=True)
        runs.append(r.xi[dd - 5 :])
    np.testing.assert_allclose(runs[0], runs[1], rtol=0.0, atol=1e-9, equal_nan=True)  # left at the same sample


def test_one_sided_analyses_without_a_derivation_refuse():
    """The criterion refuses a one-sided wall with memory or a push; the linear loop and the describing function
    refuse any one-sided wall, with the reason."""
    w = _wall()
    with pytest.raises(NotCovered, match="one-sided wall with delay, damper reached from free space"):
        _wall(damping=0.2, delay=1).corner()
    with pytest.raises(dfa.DFAValueError, match="operator.s constant push"):
        passivity_criterion(1.0, 1.0, 1.0, wall=_wall(push=0.5), mu=10.0)
    assert "not a linear loop" in (w.linear_reason() or "") and w.colgate_schenkel_reason()
    with pytest.raises(NotCovered, match="not a linear loop"):
        w.command()
    with pytest.raises(dfa.DFAError, match="needs μ"):
        passivity_criterion(1.0, 1.0, 1.0, wall=w)
    with pytest.raises(dfa.DFAError, match="not a linear loop"):
        dfa.limit_cycles(dfa.Params(100.0, 0.1, 0.3), wall=w)
    with pytest.raises(dfa.DFAValueError, match="resolution"):
        Wall(1000.0, (OneSided(0.0), Push(1.0))).params(1e-3)
    assert Wall(1000.0, (OneSided(0.0), Push(0.9))).params(1e-3, 3e-5).kernel_args()["push"] == pytest.approx(30.0)


def test_one_sided_cli_simulate_text_json_and_refusals(capsys):
    """dfa simulate --one-sided states the contact and the approach; its JSON the groups; bad use is refused."""
    argv = ["simulate", "--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided"]
    assert main([*argv, "--push", "1"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "contact: one-sided wall, surface at 0 ticks, push p = F_p/(KΔ) = 1.667" in out
    assert "the run starts 2 samples before the device reaches it at 0.5556 ticks/sample" in out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == "left" and d["wall"]["dimensionless"]["one_sided"] == 0.0
    assert (d["wall"]["one_sided_surface"], d["wall"]["push"], d["wall"]["units"]["push"]) == (0.0, 0.0, "N")
    assert d["xi0"] == pytest.approx(-1.5 * 0.05 / (3e-5 * 3000.0), rel=1e-12)  # ξ_e − V(D − ½), D = 2
    for extra, words in (
        (["--preload"], "--preload cannot be combined with --one-sided"),
        (["--xi0", "1"], "--xi0 cannot be combined with --one-sided"),
        (["--push", "-1"], "--push -1 is invalid"),
    ):
        assert main([*argv, *extra]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and words in err, err
    assert main(argv[:-1] + ["--surface", "0.5"]) == 2
    assert "--surface needs --one-sided" in capsys.readouterr().err


def test_fig4_one_sided_map_points_are_the_approach_runs(capsys, tmp_path):
    """Every point of a one-sided wall's map is `simulate` from the approach start, with the approach's samples
    added to the run length; its counts and legend name `left`; a preload is refused."""
    from dfa.analysis.maps import stability_map

    w = _wall(damping=0.3, delay=1)
    m = stability_map(20.0, [0.8], grid=3, samples=300, wall=w, n_jobs=1, progress=False)
    x0, v0, d = approach_start(0.8, wall=w)
    assert m.samples == 300 + d
    for i, s in enumerate(m.sigma):
        for j, b in enumerate(m.beta):
            r = simulate(20.0, b, s, v0, samples=m.samples, xi0=x0, wall=w)
            assert dfa.analysis.simulation.OUTCOMES[m.outcome[0, i, j]] == r.outcome.value
    assert "left" in m.counts()[0] and sum(m.counts()[0].values()) == 9
    with pytest.raises(dfa.DFAValueError, match="preload = True is invalid with a one-sided wall"):
        stability_map(20.0, [0.8], grid=2, samples=100, wall=w, preload=True, n_jobs=1, progress=False)
    argv = ["map", "--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided", "--grid", "4"]
    assert main([*argv, "--out", str(tmp_path / "m.npz"), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["counts"][0]["left"] == 16 and d["operating_point_runs"][0]["outcome"] == "left"  # free impacts
    assert main([*argv, "--out", str(tmp_path / "m.npz"), "--preload"]) == 2
    assert "preload" in capsys.readouterr().err


def test_eq6_one_sided_criterion_is_the_spring_at_the_contact_speed():
    """The lone one-sided spring: corner (½, ½) at V' = √(V² + ε²/μ), ε = ⌊s + ½⌋ − s + V (s − s + V = V without
    the encoder), and its start state is the approach."""
    from dfa.analysis.criterion import start_state

    for s, q, eps in ((0.0, True, 2.0), (0.3, True, 0.0 - 0.3 + 2.0), (0.7, True, 1.0 - 0.7 + 2.0), (0.3, False, 2.0)):
        r = passivity_criterion(0.3, 1.0, 2.0, wall=_wall(s), mu=10.0, quantized=q)
        assert (r.critical_line.beta0, r.critical_line.sigma0) == (0.5, 0.5 if q else 0.0)
        assert r.equivalent_speed == pytest.approx(np.sqrt(4.0 + eps * eps / 10.0), rel=1e-14)
    assert start_state(_wall()).startswith("an approach from free space at V")


def test_eq6_one_sided_sampled_passive_points_never_exceed_the_contact_energy():
    """1500 derandomised points: S = ½μξ'² + ½((ξ − s)⁺)² never exceeds ½μV'² after an exact approach; the
    bilateral spring's claim S <= ½μV² fails at almost every point (the check can fail).

    The 10⁵-point run: ``python -m dfa.cli.soundness_report --one-sided`` (reports/validation)."""
    from dfa.analysis.soundness import one_sided_soundness

    r = one_sided_soundness(1500, seed=2024)
    assert r.points == 1500 and r.violations == 0 and r.criterion == "one-sided"
    assert r.by_case is not None and r.by_case["surface != 0"] > 900 and r.by_case["no encoder"] > 150
    assert one_sided_soundness(300, criterion="bilateral", seed=2024).energy_grew > 250


def test_one_sided_searches_that_start_at_the_origin_refuse_it():
    """K_max, the Z-width, the speed chart and the design report start their runs at the wall's origin: they
    refuse a one-sided wall (rather than miss its approach)."""
    from dfa.analysis.design import design_analysis
    from dfa.analysis.limits.kmax import design_answer
    from dfa.analysis.limits.speed_chart import stiffness_speed_chart
    from dfa.analysis.limits.zwidth import z_width

    dev = dfa.get_device("delta").device
    w = Wall(2000.0, (OneSided(0.0),))
    for call in (
        lambda: design_answer(dev, 0.05, wall=w),
        lambda: z_width(dev, 0.05, wall=w, grid=2),
        lambda: stiffness_speed_chart(dev, wall=w),
        lambda: design_analysis(dev, w, 0.05),
    ):
        with pytest.raises(dfa.DFAValueError, match="one-sided wall is not covered by"):
            call()


def test_eq6_one_sided_cli_check_states_the_proof_its_start_and_the_linear_refusal(capsys):
    """`dfa check --one-sided`: the criterion's verdict at V' (the same as the API's), the approach as its start
    state, Colgate–Schenkel not covered; and the device's approach run keeps S <= ½μV'²."""
    argv = ["check", "--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided"]
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    dev = dfa.get_device("delta").device
    p = dev.params(20000.0)
    r = passivity_criterion(p.beta, p.sigma, dev.xi_dot(0.05), wall=_wall(), mu=p.mu)
    assert d["passive"] is r.passive is True and d["criterion"]["equivalent_speed"] == r.equivalent_speed
    assert d["start_state"].startswith("an approach from free space") and "colgate_schenkel" in d["reasons"]
    assert main(argv) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "eq. 6 for a one-sided spring reached from free space" in out and "Colgate–Schenkel not covered" in out
    x0, v0, n0 = approach_start(dev.xi_dot(0.05), wall=_wall())
    run = simulate(p.mu, p.beta, p.sigma, v0, samples=n0 + 4000, xi0=x0, wall=_wall(), record=True)
    xs, vs = run.xi[np.isfinite(run.xi)], run.xi_dot[np.isfinite(run.xi)]
    assert np.max(0.5 * p.mu * vs**2 + 0.5 * np.maximum(xs, 0.0) ** 2) <= 0.5 * p.mu * r.equivalent_speed**2 * (
        1 + 1e-9
    )
