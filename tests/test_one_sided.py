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
from fixed_keywords import small_design_searches, small_report_map
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference_ctl import simulate_ivp_ctl
from result_json import written

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


WALLS = st.builds(  # a hand stiffness (held by the operator during the approach) without a lag: no step for both
    lambda s, p, b, d, cut, lag, h: _wall(
        s, p, damping=b, delay=d, cutoff=cut, lag=0.0 if h else lag, hand_stiffness=h
    ),
    st.sampled_from([0.0, 0.3, -0.4]),
    st.sampled_from([0.0, 0.3, 2.0]),
    st.sampled_from([0.0, 0.5]),
    st.integers(0, 2),
    st.sampled_from([None, 0.1]),
    st.sampled_from([0.0, 0.3]),
    st.sampled_from([0.0, 0.0, 0.05]),
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
        assert wall.push == 0.0 and np.all(np.diff(ix[k - 1 :]) <= 0.0)
        assert np.all(np.floor(ix[k - 1 :]) + 0.5 <= wall.surface)


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
    """The criterion refuses a one-sided wall with a damper or filter, and a push on a bilateral wall; the linear
    loop and the describing function refuse any one-sided wall, with the reason."""
    w = _wall()
    with pytest.raises(NotCovered, match="one-sided wall with damper reached from free space"):
        _wall(damping=0.2, delay=1).corner()
    with pytest.raises(dfa.DFAValueError, match="push needs a one-sided wall"):
        passivity_criterion(1.0, 1.0, 1.0, wall=WallParams(((Push, 0.5),)), mu=10.0)
    assert _wall(push=0.5, delay=2).corner() == (2.5, 0.5)  # the delay's corner; the push enters V*
    assert "not a linear loop" in (w.linear_reason() or "") and w.colgate_schenkel_reason()
    with pytest.raises(NotCovered, match="not a linear loop"):
        w.command()
    with pytest.raises(dfa.DFAError, match="needs μ"):
        passivity_criterion(1.0, 1.0, 1.0, wall=w)
    with pytest.raises(dfa.DFAError, match="not a linear loop"):
        dfa.limit_cycles(dfa.Params(100.0, 0.1, 0.3), wall=w)
    with pytest.raises(dfa.DFAValueError, match="resolution"):
        Wall(1000.0, (OneSided(0.0), Push(1.0))).params(1e-3)
    assert Wall(1000.0, (OneSided(0.0), Push(0.9))).params(1e-3, 3e-5).push == pytest.approx(30.0)


def test_one_sided_cli_simulate_text_json_and_refusals(capsys):
    """dfa simulate --one-sided states the contact and the approach; its JSON the groups; bad use is refused."""
    argv = ["simulate", "--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided"]
    assert main([*argv, "--push", "1"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "contact: one-sided wall, surface at 0 ticks, push p = F_p/(KΔ) = 1.667" in out
    assert "the run starts 2 samples before the device reaches it at 0.5556 ticks/sample" in out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == d["contact"] == "left" and d["wall"]["dimensionless"]["one_sided"] == 0.0
    assert main([*argv, "--push", "1", "--json"]) == 0
    kind = json.loads(capsys.readouterr().out)["contact"]
    assert f"contact {kind}: " in out  # the text's contact row is the JSON's
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
    assert main([*argv, "--push", "2000"]) == 0  # a push no hand gives: warned, not refused
    assert "--push 2000 is above 1000 N" in capsys.readouterr().err


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
            assert dfa.analysis.simulation.CONTACTS[m.contact[0, i, j]] is r.contact  # the contact kind too
    assert "left" in m.counts()[0] and sum(m.counts()[0].values()) == 9
    assert sum(m.contact_counts()[0].values()) == 9 and m.contact_counts()[0]["left"] == m.counts()[0]["left"]
    back = dfa.load_map(m.save(tmp_path / "os.npz"))  # the file keeps the one-sided wall and the contact kinds
    assert back.wall == w and np.array_equal(back.contact, m.contact)
    with pytest.raises(dfa.DFAValueError, match="preload = True is invalid with a one-sided wall"):
        stability_map(20.0, [0.8], grid=2, samples=100, wall=w, preload=True, n_jobs=1, progress=False)
    argv = ["map", "--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided", "--grid", "4"]
    assert main([*argv, "--out", str(tmp_path / "m.npz"), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["counts"][0]["left"] == 16 and d["operating_point_runs"][0]["outcome"] == "left"  # free impacts
    assert d["contact_counts"][0]["left"] == 16
    assert main([*argv, "--out", str(tmp_path / "m.npz")]) == 0
    assert "as contact:" in capsys.readouterr().out
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


@settings(max_examples=60, derandomize=True, deadline=None)
@given(
    st.sampled_from([0.0, 0.3, -0.4, 0.7, 12.45]),
    st.booleans(),
    st.floats(1e-3, 1e4, **finite),
    st.floats(0.0, 0.49, **finite),
    st.floats(0.5, 50.0, **finite),
)
def test_eq12_one_sided_critical_speed_is_the_largest_passive_impact_speed(surface, q, mu, beta, sigma):
    """Eq. 12 for a one-sided wall: the critical speed is an impact speed V (OneSided.impact_speed inverts
    V' = √(V² + ε(V)²/μ)); the criterion's own verdict passes just below it and fails just above it."""
    w = _wall(surface)
    r = passivity_criterion(beta, sigma, 1.0, wall=w, mu=mu, quantized=q)
    vc = r.critical_xi_dot
    assume(vc is not None and vc > 1e-6)
    assert passivity_criterion(beta, sigma, vc * (1 - 1e-9), wall=w, mu=mu, quantized=q).passive
    assert not passivity_criterion(beta, sigma, vc * (1 + 1e-9), wall=w, mu=mu, quantized=q).passive
    # and V' at the critical impact speed is eq. 12's (σ − σ₀)/(β₀ − β)
    at = passivity_criterion(beta, sigma, vc, wall=w, mu=mu, quantized=q).equivalent_speed
    assert at == pytest.approx((sigma - (0.5 if q else 0.0)) / (0.5 - beta), rel=1e-9)


def test_eq6_one_sided_sampled_passive_points_never_exceed_the_contact_energy():
    """1500 derandomised points: S = ½μξ'² + ½((ξ − s)⁺)² never exceeds ½μV'² after an exact approach; the
    bilateral spring's claim S <= ½μV² fails at almost every point (the check can fail).

    The 10⁵-point run: ``python -m dfa.cli.soundness_report --one-sided`` (reports/validation)."""
    from dfa.studies.soundness import one_sided_soundness

    r = one_sided_soundness(1500, seed=2024)
    assert r.points == 1500 and r.violations == 0 and r.criterion == "one-sided"
    assert r.by_case is not None and r.by_case["surface != 0"] > 900 and r.by_case["no encoder"] > 150
    assert one_sided_soundness(300, criterion="bilateral", seed=2024).energy_grew > 250


def test_eq6_one_sided_cli_check_states_the_proof_its_start_and_the_linear_refusal(capsys):
    """`dfa check --one-sided`: the criterion's verdict at V' (the same as the API's), the approach as its start
    state, Colgate–Schenkel not covered; and the device's approach run keeps S <= ½μV'²."""
    argv = ["check", "--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided"]
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    dev = dfa.get_device("delta").device
    p = dev.params(20000.0)
    r = passivity_criterion(p.beta, p.sigma, dev.xi_dot(0.05), wall=_wall(), mu=p.mu)
    assert d["passive"] is r.passive is True and d["criterion"]["equivalent_speed"] == written(r.equivalent_speed)
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


def test_eq11_one_sided_kmax_criterion_approach_runs_and_no_linear_loop():
    """K_max four ways for a one-sided wall: K_criterion is the largest K whose criterion (at V', the approach)
    passes; the linear bound and the describing function say "not a linear loop"; every simulated impact is the
    approach run of dfa.simulate (the assessed K's outcome is the approach's); with a push, the one-sided wall
    does not diverge where the bilateral spring does (it cannot pull the device back)."""
    from dfa.analysis.criterion import device_criterion
    from dfa.analysis.limits.kmax import design_answer

    dev = dfa.get_device("delta").device
    w = Wall(14500.0, (OneSided(0.25),))
    r = design_answer(dev, 0.05, wall=w, assess=True, grid=8, speeds=2)
    kc = r.k_criterion.value
    assert kc is not None
    assert device_criterion(dev, w.with_stiffness(kc * (1 - 1e-6)), 0.05).passive
    assert not device_criterion(dev, w.with_stiffness(kc * (1 + 1e-6)), 0.05).passive
    assert r.k_linear.status.value == r.k_df.status.value == "not_linear" and r.evidence.starts == ("approach",)
    a = r.assessment
    assert a is not None and set(a.outcomes) == {"approach"} and a.growth_unknown == "not_linear"
    p, wp = dev.params(14500.0), w.params(dev.period, dev.resolution)
    x0, v0, _n = approach_start(dev.xi_dot(0.05), wall=wp)
    assert a.outcomes["approach"] == simulate(p.mu, p.beta, p.sigma, v0, xi0=x0, wall=wp).outcome
    # the critical speed is the impact speed: at it, the criterion passes
    assert a.max_passive_velocity == pytest.approx(device_criterion(dev, w, 0.0).critical_velocity, rel=1e-12)
    assert device_criterion(dev, w, a.max_passive_velocity * (1 - 1e-9)).passive

    push = Wall(1.0, (OneSided(0.0), Push(2.0)))
    pushed = design_answer(dev, 0.05, wall=push, grid=8, speeds=2)
    bilateral = design_answer(dev, 0.05, grid=8, speeds=2)
    kp = pushed.k_criterion.value
    assert kp is not None and device_criterion(dev, push.with_stiffness(kp * (1 - 1e-6)), 0.05).passive
    assert not device_criterion(dev, push.with_stiffness(kp * (1 + 1e-6)), 0.05).passive
    # the verdict is monotone in K (criterion module docstring): every K below K_criterion passes
    assert all(device_criterion(dev, push.with_stiffness(k), 0.05).passive for k in np.geomspace(kp * 1e-6, kp, 400))
    assert bilateral.k_sim.value is not None and pushed.k_sim.value is None
    assert pushed.k_sim.status.value == "above_range" and pushed.k_sim.range_end > 2 * bilateral.k_sim.value


def test_one_sided_cli_stiffness_text_and_json(capsys):
    """`dfa stiffness --one-sided`: the contact in the header, the linear rows "not a linear loop", the runs
    "after the approach", and the JSON's starts and limits as the API's."""
    from dfa.analysis.limits.kmax import design_answer

    argv = ["stiffness", "--device", "delta", "--velocity", "0.05", "--one-sided", "--surface", "0.25"]
    assert main(argv) == 0
    raw = capsys.readouterr().out
    out = " ".join(raw.split())
    assert "one-sided wall reached from free space (surface at 0.25 ticks), no push (a free impact)" in out
    assert "not a linear loop" in out and "after the approach" in out and "rests or leaves" in out
    assert max(len(line) for line in raw.splitlines()) <= 100  # the package's WIDTH
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    dev = dfa.get_device("delta").device
    r = design_answer(dev, 0.05, wall=Wall(14500.0, (OneSided(0.25),)), assess=True)
    assert d["evidence"]["starts"] == ["approach"] and d["k_criterion"]["value"] == written(r.k_criterion.value)
    assert d["wall"]["one_sided_surface"] == 0.25 and d["assessment"]["outcomes"] == r.assessment.outcomes


def _approach_outcome(dev, k, wall, speed):
    """dfa.simulate's outcome of an impact at ``speed`` (m/s) on ``wall`` at K = k, after the approach."""
    p, wp = dev.params(k), wall.with_stiffness(k).params(dev.period, dev.resolution)
    x0, v0, _n = approach_start(dev.xi_dot(speed), wall=wp)
    return simulate(p.mu, p.beta, p.sigma, v0, xi0=x0, wall=wp).outcome


@pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")  # the grid's top K, 1.2e7 N/m
def test_zwidth_one_sided_points_are_approach_runs_and_agree_with_kmax():
    """The Z-width of a one-sided wall: every grid point's code follows from dfa.simulate's approach runs (left:
    left, which the rest limit counts as ended; unstable: diverges), no linear columns ("not a linear loop"), and its criterion column at B = 0 is
    the K_max answer's K_criterion (two answers to one question)."""
    from dfa.analysis.limits.kmax import design_answer
    from dfa.analysis.limits.zwidth import z_width
    from dfa.results.codes import BOUNDED, DIVERGES, LEFT_POINT, REST, UNDECIDED_POINT

    dev = dfa.get_device("delta").device
    for w in (Wall(1.0, (OneSided(0.0), Push(2.0))), Wall(1.0, (OneSided(0.3),))):
        z = z_width(dev, 0.05, wall=w, grid=3, speeds=1, n_jobs=1)
        assert {x.status.value for m in ("linear", "df") for x in z.limits[m]} == {"not_linear"}
        assert z.simulations == 9  # one start per speed: the approach
        for i, b in enumerate(z.damping):
            for j, k in enumerate(z.stiffness):
                o = _approach_outcome(dev, float(k), w.with_damping(float(b)), 0.05)
                want = {"rest": REST, "left": LEFT_POINT, "unstable": DIVERGES, "undecided": UNDECIDED_POINT}.get(
                    o, BOUNDED
                )
                assert z.outcome[i, j] == want, (b, k, o)
    free = Wall(1.0, (OneSided(0.3),))
    z = z_width(dev, 0.05, wall=free, grid=2, speeds=1, n_jobs=1)
    assert z.limits["criterion"][0].value == design_answer(dev, 0.05, wall=free, grid=4, speeds=1).k_criterion.value


def test_speed_chart_one_sided_safe_speeds_are_approach_runs():
    """The stiffness–speed chart of a one-sided wall: at every K, each simulated speed up to v_sim is an approach
    run that does not diverge (and up to v_rest one that rests or leaves); the criterion's curve is the criterion's
    critical impact speed."""
    from dfa.analysis.criterion import device_criterion
    from dfa.analysis.limits.speed_chart import stiffness_speed_chart
    from dfa.model.elements import Damper

    dev = dfa.get_device("delta").device
    assert not stiffness_speed_chart(dev, wall=Wall(1.0, (OneSided(0.0), Damper(5.0))), grid=2).criterion_covered
    w = Wall(1.0, (OneSided(0.0), Push(2.0)))
    c = stiffness_speed_chart(dev, wall=w, grid=3, speeds=3)
    assert c.criterion_covered
    for k, vs, vr in zip(c.stiffness, c.v_sim, c.v_rest, strict=True):
        outs = {v: _approach_outcome(dev, float(k), w, float(v)) for v in c.speeds}
        assert all(outs[v] not in ("unstable", "undecided") for v in c.speeds if v <= vs)
        assert all(outs[v] in ("rest", "left") for v in c.speeds if v <= vr)
    free = Wall(1.0, (OneSided(0.0),))
    c = stiffness_speed_chart(dev, wall=free, grid=3, speeds=2)
    k = float(c.criterion_stiffness[50])
    mpv = device_criterion(dev, free.with_stiffness(k), 0.0).critical_velocity
    assert c.v_criterion[50] == pytest.approx(min(mpv, c.v_top), rel=1e-12)


@pytest.mark.parametrize(
    ("push", "k", "kind"),
    [(0.0, 30000.0, "left"), (0.0, 5000.0, "rests"), (0.3, 30000.0, "rests_off"), (2.0, 3e5, "bounces"),
     (5.0, 2e5, "in_contact"), (20.0, 7e4, "grows")],
)  # fmt: skip
def test_one_sided_contact_outcome_agrees_with_the_recorded_readings(push, k, kind):
    """The contact kinds of a one-sided wall's run (issue 28 §1: rests, chatters or cycles in contact, bounces,
    grows, leaves), from the kernel's statistics, against the recorded trajectory: a tail reading outside
    (ξ < ⌊s + ½⌋) between readings inside is a bounce; none, in contact; at rest, on or off the wall by the final
    reading; ``left`` outside moving away. Each kind occurs among these Delta runs (0.05 m/s, the approach)."""
    from dfa.analysis.simulation import _tail_length

    dev = dfa.get_device("delta").device
    w = Wall(k, (OneSided(0.0),) + ((Push(push),) if push else ()))
    p, wp = dev.params(k), w.params(dev.period, dev.resolution)
    x0, v0, _n = approach_start(dev.xi_dot(0.05), wall=wp)
    n = 200_000
    run = simulate(p.mu, p.beta, p.sigma, v0, samples=n, xi0=x0, wall=wp, record=True)
    assert run.contact is not None and run.contact.value == kind
    assert simulate(p.mu, p.beta, p.sigma, v0, samples=n, xi0=x0, wall=wp).contact == run.contact  # unrecorded
    tail = run.xi[n - _tail_length(n, p.mu) :]
    inside = tail >= 0.0  # ⌊0 + ½⌋ = 0: the first position the wall sees
    if kind == "bounces":
        assert inside.any() and not inside.all() and np.count_nonzero(np.diff(inside.astype(int)) == 1) >= 2
    elif kind == "in_contact":
        assert inside.all() and np.ptp(tail) > 0
    elif kind in ("rests", "rests_off"):
        assert run.rest_sample is not None and (run.xi[-1] >= 0.0) == (kind == "rests")
    elif kind == "left":
        assert run.final_xi < 0.0 and run.final_xi_dot < 0.0
    else:
        assert run.outcome == "unstable"
    assert json.loads(json.dumps(run.to_dict()))["contact"] == kind
    bilateral = simulate(p.mu, p.beta, p.sigma, 0.5, samples=1000)
    assert bilateral.contact is None and "contact" not in bilateral.to_dict()


def test_one_sided_cli_limit_cycles_refuses_with_the_reason(capsys, tmp_path):
    """`dfa limit-cycles --one-sided`: one line on stderr, exit 2, the reason (no describing function for a
    one-sided wall) and where it is covered."""
    for argv, why in ((["limit-cycles", "--device", "delta", "--one-sided"], "not a linear loop"),):
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and why in err and "zwidth or report with --one-sided" in err
    assert not any(tmp_path.iterdir())


def test_one_sided_design_report_runs_start_with_the_approach(tmp_path, monkeypatch):
    """`dfa report --one-sided --push`: the design analysis's runs are the approach runs of dfa.simulate, no
    describing function (no thresholds, no Nyquist figure; the report says why), the contact stated, and its
    own file name; the JSON's headline numbers say why the describing function's are null."""
    from dfa.analysis.maps import map_start
    from dfa.studies.design import design_analysis

    dev = dfa.get_device("delta")
    w = Wall(14500.0, (OneSided(0.0), Push(2.0)))
    a = design_analysis(dev, w, 0.1, map_grid=3, samples=3000, n_jobs=1, zwidth_grid=0)
    assert a.thresholds == () and a.nyquist is None and a.design_answer is not None
    p, wp = a.params, w.params(dev.device.period, dev.device.resolution)
    x0, v0 = map_start(p.mu, a.xi_dot, False, wp)
    r = simulate(p.mu, p.beta, p.sigma, v0, xi0=x0, wall=wp)
    assert (a.outcome.outcome, a.outcome.rest_sample, a.outcome.final_xi) == (r.outcome, r.rest_sample, r.final_xi)
    assert a.outcome.contact is not None and a.grip is not None
    small_report_map(monkeypatch)  # the text and JSON checked below read neither the map nor K_max's search
    small_design_searches(monkeypatch)
    assert main(["report", "--device", "delta", "--one-sided", "--push", "2", "--zwidth", "0", "--out", str(tmp_path),
                 "--format", "md"]) == 0  # fmt: skip
    text = " ".join((tmp_path / "design_report_delta_one_sided.md").read_text(encoding="utf-8").split())
    assert "No describing function: a one-sided wall is not a linear loop" in text
    assert "Contact: one-sided wall reached from free space (surface at 0 ticks), push 2 N" in text
    assert "nyquist" not in text and "after the approach from free space" in text
    d = json.loads((tmp_path / "design_report_delta_one_sided.json").read_text(encoding="utf-8"))
    assert d["analysis"]["growth_thresholds"] == {} and d["numbers"]["wall"]["push"] == 2.0
    assert d["numbers"]["null_reasons"]["/df_xi_dot"] == "not a linear loop: no describing function"
    assert not any("nyquist" in f for f in d["figures"])


def test_eq6_one_sided_hand_stiffness_adds_its_storage_at_contact(capsys):
    """A hand's spring on a one-sided wall: the operator holds it during the approach (the approach run is the one
    without it, sample for sample, until the first reading inside), and the criterion's V* adds its storage at the
    first reading inside, ½κ_h(s + δ)² at the end of δ's interval that maximises the storage; `dfa check` and
    `dfa simulate --one-sided --hand hapticmaster` take it."""
    mu, kap, s, v = 50.0, 0.05, 0.3, 1.3
    with_hand, bare = _wall(s, hand_stiffness=kap), _wall(s)
    x0, v0, d = approach_start(v, wall=with_hand)
    a = simulate(mu, 0.2, 0.5, v0, samples=d, xi0=x0, wall=with_hand, record=True)
    b = simulate(mu, 0.2, 0.5, v0, samples=d, xi0=x0, wall=bare, record=True)
    np.testing.assert_array_equal(a.xi, b.xi)  # the approach: the hand's spring held by the operator
    # ... also when the approach's force σ + βV equals the push (the approach is a flag, not a force's value)
    w = _wall(0.3, push=2.0, hand_stiffness=0.05)
    x0, v0, d = approach_start(2.0, wall=w)
    run = simulate(20.0, 0.25, 1.5, v0, samples=d + 3, xi0=x0, wall=w, record=True)
    np.testing.assert_allclose(run.xi[: d + 1], x0 + 2.0 * np.arange(d + 1), rtol=0, atol=1e-12)
    c = OneSided.engage(s) - s
    storage = max(0.5 * max(e, 0.0) ** 2 + 0.5 * kap * (s + e) ** 2 for e in (c, c + v))
    r = passivity_criterion(0.3, 1.0, v, wall=with_hand, mu=mu)
    assert r.equivalent_speed == pytest.approx(np.sqrt(v * v + 2.0 * storage / mu), rel=1e-14)
    argv = ["--device", "delta", "--stiffness", "20000", "--velocity", "0.05", "--one-sided", "--hand", "hapticmaster"]
    assert main(["check", *argv, "--json"]) == 0 and json.loads(capsys.readouterr().out)["criterion"] is not None
    assert main(["simulate", *argv, "--json"]) == 0 and json.loads(capsys.readouterr().out)["contact"] is not None
