"""The passivity observer and controller (issue 30; Hannaford and Ryu, IEEE T-RO 2002): the wall element
:class:`dfa.model.elements.PassivityController`, its simulation, the observer as a diagnostic, and the gain.

Checked against:

- the spring's own energy ledger (:class:`dfa.analysis.simulation.EnergyRecord`): without the encoder the observer
  is the work done on the wall, −(Δ½μξ'² + Σ dissipated), sample by sample; with the encoder it differs by no more
  than the readings' rounding bound (summation by parts), and the half-sample-lagged pairing of 2002 does not;
- the ``solve_ivp`` loop of ``tests/reference_ctl.py`` with the controller written plainly from the element's
  docstring (a second implementation): whole runs to 1e-8, and the controller's forces;
- the bound the controller enforces: its ledger after every action is >= 0, or short of it by exactly what the
  force limit cut;
- a controller that never acts changes nothing, bit for bit;
- the Phantom 1.0 at K = 3000 N/m, 0.1 m/s: the plain wall diverges, the controlled one rests; at 6000 N/m a
  0.3 N force limit makes it fail (diverges) where 1 N does not;
- the refusals: criterion, exact linear bound, Colgate–Schenkel, describing function, ``dfa limit-cycles``;
- the numbers users read: ``dfa simulate --observer`` (text, JSON, ``--trace`` columns) and ``dfa stiffness
  --passivity-controller`` against the API.
"""

from __future__ import annotations

import csv
import itertools
import json
import math

import numpy as np
import pytest
from cli_text import unwrap
from hypothesis import given, settings
from hypothesis import strategies as st
from reference_ctl import Commands, simulate_ivp_ctl
from result_json import written

import dfa
from dfa.analysis.observer import force_error, observe
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.model.elements import NotCovered, OneSided, PassivityController
from dfa.model.wall import Wall, WallParams


def _pc(window: int = 0, limit: float | None = None, **groups) -> WallParams:
    return WallParams(((PassivityController, (window, limit)), *WallParams.of(**groups).groups))


def _exact_work(r) -> np.ndarray:
    """The work done on the wall up to each reading, from the device's energy balance and the spring's ledger."""
    e = r.energy
    lost = np.cumsum(e.dissipated_viscous + e.dissipated_coulomb)
    kinetic = 0.5 * r.mu * (r.xi_dot[1:] ** 2 - r.xi_dot[0] ** 2)
    return np.concatenate([[0.0], -(kinetic + lost)])


SPRINGS = st.tuples(
    st.floats(20.0, 400.0), st.floats(0.0, 1.0), st.floats(0.0, 0.5), st.floats(0.2, 6.0), st.integers(0, 2)
)


@given(SPRINGS)
def test_hannaford_ryu_observer_equals_energy_ledger_without_encoder(case):
    """Without the encoder, E_obs(h) = −Σ φ_{k−1}(ξ_k − ξ_{k−1}) is the work −∫φξ' done on the wall to reading h,
    sample by sample, by the device's energy balance with the kernel's closed-form dissipation."""
    mu, beta, sigma, v0, delay = case
    r = simulate(mu, beta, sigma, v0, samples=600, quantize=False, energy=True, wall=WallParams.of(delay=delay))
    n = r.samples_run + 1
    obs, work = r.observed_energy()[:n], _exact_work(r)[:n]
    scale = 1.0 + np.abs(work).max()
    assert np.allclose(obs, work, rtol=0.0, atol=1e-9 * scale), np.abs(obs - work).max()


@given(SPRINGS)
def test_hannaford_ryu_observer_with_encoder_within_rounding_bound(case):
    """With the encoder the observer pairs each held force with the readings' displacement: it differs from the
    exact work by at most |φ_{n−1}| + |φ_0| + Σ|φ_k − φ_{k−1}| (summation by parts, 0 <= ξ − ⌊ξ⌋ < 1)."""
    mu, beta, sigma, v0, delay = case
    r = simulate(mu, beta, sigma, v0, samples=600, energy=True, wall=WallParams.of(delay=delay))
    n = r.samples_run + 1
    obs, work, phi = r.observed_energy()[:n], _exact_work(r)[:n], r.applied_force()[:n]
    steps = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(phi)))])  # Σ_{k<=h}|φ_k − φ_{k−1}|
    for h in range(1, n):
        bound = abs(phi[h - 1]) + abs(phi[0]) + steps[h - 1] + 1e-9 * (1 + abs(work[h]))
        assert abs(obs[h] - work[h]) <= bound, (h, obs[h], work[h], bound)


@given(st.floats(-40.0, 40.0), st.booleans(), st.sampled_from([None, 0.3, -0.4]))
def test_observer_starts_with_the_energy_the_wall_holds(x0, quantize, surface):
    """E_obs(0) is what the observer counts of a slow entry to ξ0 (the kernel's closed form against the readings
    walked one tick at a time by the reference); without the encoder ½ξ0² (½((ξ0 − s)⁺)² one-sided)."""
    wall = WallParams(((OneSided, surface),)) if surface is not None else WallParams.of(delay=1)
    r = simulate(100.0, 0.5, 0.3, 0.0, samples=5, xi0=x0, quantize=quantize, wall=wall)
    walked = Commands(wall, quantize).held(x0)
    assert r.observed_energy()[0] == pytest.approx(walked, rel=1e-12, abs=1e-12)
    if not quantize:
        d = x0 - surface if surface is not None else x0
        assert walked == pytest.approx(0.5 * d * d if (surface is None or d > 0) else 0.0, rel=1e-12, abs=1e-12)


def test_preload_start_releases_what_the_observer_counted_in():
    """A start at rest with the spring preloaded (the K_max searches' second start): the observer has counted the
    spring's energy in, so the release is not read as produced energy and the controller does not cancel the
    spring's force at once (it did: +30.5 against −30.5 at the first reading, before E_obs(0) held it)."""
    from dfa.analysis.simulation import preload_position

    x0 = preload_position(100.0, 3.0)
    r = simulate(100.0, 0.2, 0.3, 0.0, samples=400, xi0=x0, wall=_pc(limit=None))
    f = r.controller_force()
    assert f[1] == 0.0 and r.observed_energy()[0] > 0.5 * (math.floor(x0) - 1) ** 2


def test_hannaford_ryu_2002_pairing_lags():
    """The 2002 pairing φ_h v_h (the force of this reading with the displacement of the sample before) is not the
    work: on a run without the encoder it misses it by far more than rounding (a test that can fail)."""
    r = simulate(100.0, 0.2, 0.1, 3.0, samples=600, quantize=False, energy=True)
    n = r.samples_run + 1
    phi, xi = r.applied_force()[:n], r.xi[:n]
    lagged = -np.cumsum(np.concatenate([[0.0], phi[1:] * np.diff(xi)]))
    assert np.abs(lagged - _exact_work(r)[:n]).max() > 1.0
    assert np.abs(r.observed_energy()[:n] - _exact_work(r)[:n]).max() < 1e-9


PC_WALLS = st.builds(
    lambda w, lim, b, d, cut, lag, one: WallParams(
        (
            (PassivityController, (w, lim)),
            *(((OneSided, 0.0),) if one else ()),
            *WallParams.of(damping=b, delay=d, cutoff=cut, lag=lag).groups,
        )
    ),  # fmt: skip
    st.sampled_from([0, 7, 40]),
    st.sampled_from([None, 0.5, 3.0]),
    st.sampled_from([0.0, 0.4]),
    st.integers(0, 2),
    st.sampled_from([None, 0.1]),
    st.sampled_from([0.0, 0.3]),
    st.booleans(),
)


@settings(max_examples=30)  # each example is 150 samples of solve_ivp (the suite's time budget)
@given(PC_WALLS, st.floats(30.0, 300.0), st.floats(0.0, 0.3), st.floats(0.0, 0.6), st.floats(0.5, 4.0))
def test_controller_run_equals_solve_ivp_reference(wall, mu, beta, sigma, v0):
    """The kernel runs the controller exactly: whole runs against the solve_ivp loop with the controller written
    plainly from the element's docstring (tests/reference_ctl.py), to 1e-8 in ξ and ξ'."""
    n = 150
    x0, vv = (-1.5, v0) if wall.one_sided else (0.0, v0)
    r = simulate(mu, beta, sigma, vv, samples=n, xi0=x0, wall=wall)
    xs, vs = simulate_ivp_ctl(mu, beta, sigma, x0, vv, n, wall)
    stop = r.samples_run + 1
    near = np.abs(xs[:stop] - np.round(xs[:stop])) < 1e-9  # a reading rounding decides: not comparable from there
    stop = int(np.argmax(near[1:]) + 1) if near[1:].any() else stop
    assert np.allclose(r.xi[:stop], xs[:stop], rtol=0, atol=1e-8 * (1 + np.abs(xs[:stop]).max()))
    assert np.allclose(r.xi_dot[:stop], vs[:stop], rtol=0, atol=1e-8 * (1 + np.abs(vs[:stop]).max()))


def _replay_ledger(r):
    """The reference controller replayed on the run's readings: its forces and ledgers, reading by reading."""
    cmd = Commands(r.wall, r.quantize)
    out = []
    for x in r.xi[: r.samples_run + 1]:
        cmd.applied(float(x))
        out.append((cmd.force, *cmd.ledger, cmd.energy))
    return np.array(out)


@given(PC_WALLS, st.floats(30.0, 300.0), st.floats(0.0, 0.3), st.floats(0.0, 0.6), st.floats(0.5, 6.0))
def test_controller_ledger_never_below_the_bound_it_enforces(wall, mu, beta, sigma, v0):
    """Hannaford–Ryu's guarantee, sample by sample: after every action the ledger (observed energy plus the
    dissipation booked for forces still pending) is >= 0, unless the force limit cut the force, and then short by
    exactly what was cut. The kernel's forces and observed energy are the reference's."""
    x0 = -1.5 if wall.one_sided else 0.0
    r = simulate(mu, beta, sigma, v0, samples=800, xi0=x0, wall=wall)
    ref = _replay_ledger(r)
    n = ref.shape[0]
    f, before, after, energy = ref.T
    scale = 1.0 + np.abs(energy).max()  # the window's sums differ from the reference's in their last bits
    assert np.allclose(r.controller_force()[:n], f, rtol=1e-9, atol=1e-9 * scale)
    assert np.allclose(r.observed_energy()[:n], energy, rtol=1e-12, atol=1e-9 * scale)
    limit = wall.group(PassivityController)[1] or math.inf
    v = np.diff(np.floor(r.xi[:n]), prepend=np.floor(r.xi[0]))
    for h in range(n):
        if f[h] == 0.0:
            continue
        cut = abs(before[h] / v[h]) - abs(f[h])  # the force the limit (or a one-sided clip) withheld
        if cut <= 1e-12 * (1 + abs(f[h])):
            assert after[h] >= -1e-9 * (1 + abs(before[h])), (h, before[h], after[h])
        else:
            assert abs(f[h]) <= limit * (1 + 1e-12) or wall.one_sided
            assert after[h] == pytest.approx(before[h] + abs(f[h] * v[h]), rel=1e-12, abs=1e-12)


def test_controller_that_never_acts_changes_nothing():
    """Where the controller never adds a force the run is the plain wall's, bit for bit: on a grid of devices with a
    damper (β_B = 2) and delays 0 to 2, about a third of the runs stay passive as observed and never see it act."""
    quiet = 0
    for mu, beta, sigma, v0, delay in itertools.product(
        [30.0, 100.0, 300.0], [0.0, 0.3], [0.0, 0.5, 1.0], [0.3, 1.0, 3.0], [0, 1, 2]
    ):
        r = simulate(mu, beta, sigma, v0, samples=3000, wall=_pc(damping=2.0, delay=delay))
        if np.any(r.controller_force() != 0.0):
            continue  # it acted: nothing to claim
        quiet += 1
        plain = simulate(mu, beta, sigma, v0, samples=3000, wall=WallParams.of(damping=2.0, delay=delay))
        assert np.array_equal(r.xi, plain.xi) and np.array_equal(r.xi_dot, plain.xi_dot)
        assert r.outcome is plain.outcome and r.rest_sample == plain.rest_sample
    assert quiet >= 20


def test_controller_with_zero_force_changes_nothing():
    """A force limit that lets nothing through (the smallest positive) leaves a diverging wall as it was."""
    p = dfa.get_device("Phantom 1.0").device.params(3000.0)
    tiny = _pc(limit=5e-324)
    a = simulate(p.mu, p.beta, p.sigma, 3.0, samples=2000, wall=tiny)
    b = simulate(p.mu, p.beta, p.sigma, 3.0, samples=2000, wall=WallParams())
    assert np.array_equal(a.xi, b.xi, equal_nan=True)


def _phantom(k: float, limit: float | None, v: float = 0.1):
    dev = dfa.get_device("Phantom 1.0").device
    p = dev.params(k)
    wall = Wall(k, (PassivityController(force_limit=limit),)).params(dev.period, dev.resolution)
    run = simulate(p.mu, p.beta, p.sigma, dev.xi_dot(v), samples=60_000, wall=wall, record=False)
    plain = simulate(p.mu, p.beta, p.sigma, dev.xi_dot(v), samples=60_000, record=False)
    return plain, run


def test_phantom_plain_wall_diverges_controlled_rests():
    """Phantom 1.0 at K = 3000 N/m, an impact at 0.1 m/s: the paper's spring diverges; with the passivity
    controller (1 N limit) it comes to rest."""
    plain, run = _phantom(3000.0, 1.0)
    assert plain.outcome.value == "unstable" and run.outcome.value == "rest"


def test_phantom_force_limit_makes_it_fail():
    """Phantom 1.0 at K = 6000 N/m, 0.1 m/s: the controller limited to 0.3 N cannot dissipate what the wall
    produces and the run diverges; at 1 N it does not (the validation report lists this case)."""
    plain, weak = _phantom(6000.0, 0.3)
    _, strong = _phantom(6000.0, 1.0)
    assert plain.outcome.value == "unstable" and weak.outcome.value == "unstable"
    assert strong.outcome.value != "unstable"


def test_observer_summary_matches_the_replay():
    """observe(): the produced energy and the controller's counts are those of the replayed arrays."""
    r = simulate(100.0, 0.1, 0.05, 3.0, samples=3000, wall=_pc(limit=3.0))
    s = observe(r)
    e, f = r.observed_energy(), r.controller_force()
    n = r.samples_run + 1
    assert s.produced == -e[n - 1] and s.peak_produced == max(0.0, float(np.max(-e[:n])))
    assert s.acting == int(np.count_nonzero(f[:n])) and s.peak_controller_force == float(np.max(np.abs(f[:n])))
    assert s.status.value == ("active" if s.peak_produced > 0 else "passive")
    assert json.loads(json.dumps(s.to_dict()))["acting_share"] == pytest.approx(s.acting / s.samples)


def test_force_error_of_the_ideal_spring_without_encoder_is_the_hold():
    """Without the encoder the rendered force is −ξ at each instant (no delay): zero error at the instants."""
    r = simulate(100.0, 0.5, 0.1, 2.0, samples=400, quantize=False)
    e = force_error(r)
    assert e.rms == 0.0 and e.peak == 0.0 and e.samples > 10
    q = force_error(simulate(100.0, 0.5, 0.1, 2.0, samples=400))
    assert 0.0 < q.peak <= 0.5 + 1e-12  # the encoder's staircase: −(⌊ξ⌋ + ½) against −ξ


# ----------------------------------------------------------------------------- the model and the refusals
def test_passivity_controller_group_and_errors():
    pc = PassivityController(window=0.05, force_limit=2.0)
    assert pc.group(1e-3, 1000.0, resolution=1e-5) == (50, 200.0)
    with pytest.raises(DFAValueError, match="force_limit needs the encoder resolution"):
        pc.group(1e-3, 1000.0)
    with pytest.raises(DFAValueError, match="window = 0.0001 s is invalid: it must span at least one sample"):
        PassivityController(window=1e-4).group(1e-3, 1000.0)
    with pytest.raises(DFAValueError, match="force_limit"):
        PassivityController(force_limit=-1.0)
    with pytest.raises(DFAValueError, match="passivity_controller window"):
        WallParams(((PassivityController, (-1, None)),))
    assert _pc(3, 2.0).to_dict()["pc_window"] == 3


def test_analyses_refuse_a_passivity_controller_by_name():
    dev = dfa.get_device("Phantom 1.0").device
    wall = Wall(3000.0, (PassivityController(force_limit=1.0),))
    with pytest.raises(NotCovered, match="passivity controller"):
        wall.params(dev.period, dev.resolution).corner()
    chk = dfa.passivity_check(dev, wall, velocity=0.1)
    assert chk.criterion is None and "passivity controller" in chk.reasons["criterion"]
    with pytest.raises(NotCovered, match="not a linear loop"):
        wall.params(dev.period, dev.resolution).command()
    assert wall.linear_reason() is not None and not wall.params(dev.period, dev.resolution).linear


def test_map_file_keeps_the_passivity_controller(tmp_path):
    wall = _pc(5, 2.5, damping=0.2)
    m = dfa.stability_map(50.0, [1.0], grid=3, samples=500, wall=wall, progress=False)
    path = m.save(tmp_path / "m.npz")
    back = dfa.load_map(path)
    assert back.wall == wall and np.array_equal(back.outcome, m.outcome)


# ----------------------------------------------------------------------------- the command line
PHANTOM = ["--device", "Phantom 1.0", "--stiffness", "3000", "--velocity", "0.1"]


def test_cli_simulate_observer_text_json_and_trace(capsys, tmp_path):
    """`dfa simulate --observer`: the energy printed and written is the API's, in J; the trace's columns are the
    replayed arrays."""
    trace = tmp_path / "t.csv"
    args = ["simulate", *PHANTOM, "--passivity-controller", "--pc-force-limit", "1", "--observer", "--samples", "2000"]
    assert main([*args, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    dev = dfa.get_device("Phantom 1.0").device
    p = dev.params(3000.0)
    wall = Wall(3000.0, (PassivityController(force_limit=1.0),)).params(dev.period, dev.resolution)
    r = simulate(p.mu, p.beta, p.sigma, dev.xi_dot(0.1), samples=2000, wall=wall)
    s = observe(r)
    joule = 3000.0 * dev.resolution**2
    assert d["observer"]["produced_j"] == pytest.approx(s.produced * joule, rel=1e-12)
    assert d["observer"]["acting"] == s.acting and d["observer"]["status"] == s.status.value
    assert main([*args, "--trace", str(trace)]) == 0
    text = unwrap(capsys.readouterr().out)
    assert f"acted at {s.acting} of {s.samples} readings" in text
    assert f"{dfa.formatting.number(s.peak_produced * joule, 4)} J at most" in text
    with open(trace) as fh:
        rows = list(csv.DictReader(fh))
    e = -np.array([float(row["produced_energy"]) for row in rows])
    f = np.array([float(row["controller_phi"]) for row in rows])
    # the trace's 12 significant digits (issue 41): within half a unit of the 12th digit
    assert np.allclose(e, r.observed_energy()[: e.size], rtol=5e-12, atol=0)
    assert np.allclose(f, r.controller_force()[: f.size], rtol=5e-12, atol=0)
    assert float(rows[-1]["produced_energy_j"]) == pytest.approx(-e[-1] * joule, rel=1e-12)


def test_cli_flags_refused_with_reason(capsys):
    assert main(["simulate", *PHANTOM, "--pc-window", "0.01"]) == 2
    assert "--pc-window needs --passivity-controller" in capsys.readouterr().err
    assert main(["limit-cycles", "--device", "Phantom 1.0", "--stiffness", "3000", "--passivity-controller"]) == 2
    assert "describing function" in capsys.readouterr().err
    assert main(["simulate", *PHANTOM, "--passivity-controller", "--pc-force-limit", "-1"]) == 2
    assert "--pc-force-limit -1 is invalid" in capsys.readouterr().err
    assert (
        main(["simulate", "--mu", "50", "--beta", "0", "--sigma", "0", "--xi-dot", "1", "--passivity-controller"]) == 2
    )
    assert "needs a physical device" in capsys.readouterr().err
    assert main(["simulate", *PHANTOM, "--observer", "--samples", "60000000"]) == 2  # 40 bytes a sample: 2.2 GiB
    assert "--observer with --samples 60000000 would need 2.2 GiB" in capsys.readouterr().err


@pytest.mark.slow
def test_cli_stiffness_passivity_gain_is_the_api(capsys):
    """`dfa stiffness --passivity-controller`: the gain lines and JSON are gain_of the two answers."""
    from dfa.analysis.limits.kmax import design_answer
    from dfa.analysis.limits.passivity_gain import gain_of

    dev = dfa.get_device("Impulse Engine").device
    wall = Wall(80.0, (PassivityController(force_limit=0.5),))
    g = gain_of(design_answer(dev, 0.05, wall=wall, assess=True, source="catalogue"),
                design_answer(dev, 0.05, wall=wall.without_controller()))  # fmt: skip
    args = ["stiffness", "--device", "Impulse Engine", "--velocity", "0.05", "--passivity-controller"]
    assert main([*args, "--pc-force-limit", "0.5", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["passivity_gain"]
    assert d["k_sim"]["value"] == written(g.k_sim.value) and d["plain_k_sim"]["value"] == written(g.plain_k_sim.value)
    assert d["gain"] == (None if g.gain is None else pytest.approx(g.gain, rel=1e-15))
    assert main([*args, "--pc-force-limit", "0.5"]) == 0
    text = capsys.readouterr().out
    unit = "N/m"
    cell = f"{dfa.formatting.number(g.k_sim.value, 5)} {unit} with it" if g.k_sim.value else "with it"
    assert cell in text and "passivity controller, simulated (no proof covers it):" in text
    assert math.isfinite(g.k_sim.value or math.inf) or g.k_sim.status.value == "above_range"


def test_passivity_report_script_refuses_bad_input_before_any_work(capsys, tmp_path):
    """`python -m dfa.cli.passivity_report`: one line on stderr and exit 2, nothing written."""
    from dfa.cli import passivity_report

    for argv, says in (
        (["--grid", "1"], "--grid"),
        (["--velocity", "-1"], "--velocity"),
        (["--speeds", "0"], "--speeds"),
    ):
        assert passivity_report.main([*argv, "--out", str(tmp_path / "r")]) == 2
        err = capsys.readouterr().err
        assert says in err and err.count("\n") == 1
    assert not (tmp_path / "r" / "passivity_controller.md").exists()


def test_passivity_report_script_writes_into_a_new_folder(monkeypatch, tmp_path):
    """The report script makes a missing --out folder (one level) and writes its three files there together."""
    import dfa.studies.passivity_comparison as comparison
    from dfa.cli import passivity_report
    from dfa.model.catalogue import get_device

    whole = comparison.passivity_comparison
    monkeypatch.setattr(comparison, "passivity_comparison", lambda **kw: whole([get_device("Impulse Engine")], **kw))
    out = tmp_path / "new"
    assert passivity_report.main(["--out", str(out), "--grid", "4", "--speeds", "1"]) == 0
    assert sorted(p.name for p in out.iterdir()) == [f"passivity_controller.{s}" for s in ("json", "md", "png")]
    d = json.loads((out / "passivity_controller.json").read_text(encoding="utf-8"))
    assert d["devices"] == ["Impulse Engine"] and d["grid"] == 4
