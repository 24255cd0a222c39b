"""A hand with stiffness on the device (issue 28 §2): the simulator, the criterion, the linear bound, the DF.

The hand's spring k_h to the wall's origin makes the free device a damped oscillator between samples
(:mod:`dfa.core.oscillator`, :class:`dfa.HandSpring`, κ_h = k_h/K). Checked against independent methods:

- one sample against ``solve_ivp`` with stop and stick events (stick-slip, restarts, under- and over-damped), and
  the closed-form responses against the matrix exponential (mpmath, 40 digits), the series branch included;
- whole runs against the ``solve_ivp`` loop of ``tests/reference_ctl.py`` to 1e-8 (relative to the largest |ξ|);
- a hand of zero stiffness is the hand-free wall bit for bit, and a tiny one is close to it;
- the criterion (paper eq. 6 extended, storage ½κ_h ξ² added): S(h) <= S(0) at random passive points by exact
  simulation, and step 1's energy identity with the hand's spring by sympy;
- the exact linear bound's plant against ``control.c2d`` of 1/(μs² + βs + κ_h), and its K_crit against the
  linear loop simulated just below and above it;
- the describing function's predicted cycle frequency against ω ≈ √((1 + κ_h)/μ) of the large cycle;
- the command line: the groups users read, and the refusals (amplifier lag with a hand stiffness, a resonance
  above the Nyquist frequency).
"""

from __future__ import annotations

import json
import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from reference_ctl import _ivp, simulate_ivp_ctl

import dfa
from dfa.analysis.criterion import equivalent_speed, passivity_criterion
from dfa.analysis.linear_wall import controlled_spectral_radius, stable_stiffness
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.core import oscillator
from dfa.model.elements import HandSpring
from dfa.model.wall import Wall, WallParams
from dfa.studies.soundness import Population, criterion_soundness

finite = dict(allow_nan=False, allow_infinity=False)


# ------------------------------------------------------------------ the exact step
@pytest.mark.parametrize(
    "lam, w2, t",
    [
        (0.3, 1.0, 1.0),  # under-damped, ωt >= ½: closed form
        (0.01, 1e-6, 1.0),  # under-damped, ωt < ½: the series of H
        (0.0, 4.0, 0.9),  # undamped
        (2.0, 0.5, 1.0),  # over-damped
        (2.0, 1.0, 1.0),  # critical
        (5.0, 1e-8, 0.7),  # over-damped, nearly the free device
        (3.0, 2.2500001, 1.0),  # just under-damped
    ],
)
def test_oscillator_responses_against_matrix_exponential(lam, w2, t):
    """h, h', H of the held device equal the entries of exp(A t), A the state matrix with a unit-force state,
    by mpmath at 40 digits (scipy's expm is off by 2e-13 at λ = 5, t = 0.7; ours by < 1e-15)."""
    with mpmath.workdps(40):
        a = mpmath.matrix([[0, 1, 0], [-mpmath.mpf(w2), -mpmath.mpf(lam), 1], [0, 0, 0]]) * mpmath.mpf(t)
        e = mpmath.expm(a)
        ref = [float(e[0, 1]), float(e[1, 1]), float(e[0, 2])]
    h, hp, big = oscillator.responses(lam, w2, t)
    assert h == pytest.approx(ref[0], rel=1e-14)
    assert hp == pytest.approx(ref[1], rel=1e-14, abs=1e-16)
    assert big == pytest.approx(ref[2], rel=1e-14)


def _one_sample_ivp(x, v, c, mu, beta, sigma, kap):
    """One sample of μξ'' + βξ' + κξ + σ sgn ξ' = c by solve_ivp with stop events and the stick rule."""
    t = 0.0
    while t < 1.0:
        if v == 0.0:
            if abs(c - kap * x) <= sigma:
                break
            s = math.copysign(1.0, c - kap * x)
        else:
            s = math.copysign(1.0, v)

        def stop(_t, y):
            return y[1]

        stop.terminal, stop.direction = True, -s
        rhs = lambda _t, y, s=s: [y[1], (c - kap * y[0] - beta * y[1] - sigma * s) / mu]
        sol = _ivp(rhs, t, [x, v], stop)
        if sol.status == 1 and sol.t_events[0].size:
            t, x, v = float(sol.t_events[0][0]), float(sol.y_events[0][0][0]), 0.0
        else:
            (x, v), t = sol.y[:, -1], 1.0
    return float(x), float(v)


@pytest.mark.parametrize(
    "x, v, c, mu, beta, sigma, kap",
    [
        (0.76, 0.0, -0.47, 0.07, 0.0, 0.0099, 0.27),  # restart at rest, under-damped, stops again (ω ≈ 2)
        (0.2, 0.4, 0.2, 1.5, 0.3, 0.5, 0.3),  # stops and sticks
        (0.2, -0.3, 2.0, 1.5, 0.3, 0.5, 0.3),  # stops, restarts upward
        (1.0, 0.0, 0.5, 1.5, 0.0, 0.2, 0.6),  # stuck: |c − κξ| <= σ
        (-2.0, 0.5, 0.0, 0.2, 3.0, 0.1, 0.05),  # over-damped, stops
        (-2.0, 0.0, 0.0, 0.2, 3.0, 0.01, 0.05),  # over-damped restart: no second stop
        (0.0, 3.0, -1.0, 0.05, 0.01, 0.3, 0.4),  # fast hand (ω ≈ 2.8): several stops in one sample
    ],
)
def test_eq4_hand_sample_stick_slip_against_solve_ivp(x, v, c, mu, beta, sigma, kap):
    got = oscillator.hand_sample(x, v, c, mu, beta, sigma, kap)
    ref = _one_sample_ivp(x, v, c, mu, beta, sigma, kap)
    assert got[0] == pytest.approx(ref[0], abs=1e-10)
    assert got[1] == pytest.approx(ref[1], abs=1e-10)


HANDS = st.builds(
    lambda d, b, cut, k: WallParams.of(damping=b, delay=d, cutoff=cut, hand_stiffness=k),
    st.integers(0, 2),
    st.sampled_from([0.0, 0.5]),
    st.sampled_from([None, 0.1]),
    st.floats(1e-4, 0.9, **finite),
)


@settings(max_examples=40, derandomize=True, deadline=None)
@given(
    HANDS,
    st.floats(0.1, 100.0, **finite),
    st.sampled_from([0.0, 0.05, 2.0]),
    st.floats(0.0, 1.5, **finite),
    st.floats(-2.0, 2.0, **finite),
    st.floats(-3.0, 3.0, **finite),
)
def test_eq4_hand_runs_against_solve_ivp(wall, mu, beta, sigma, x0, v0):
    """Whole runs (quantized, stick-slip, the wall's damper, filter, delay) to 1e-8 of the solve_ivp loop."""
    n = 40
    r = simulate(mu, beta, sigma, v0, samples=n, xi0=x0, wall=wall, record=True)
    ix, iv = simulate_ivp_ctl(mu, beta, sigma, x0, v0, n, wall)
    k = n + 1 if r.rest_sample is not None else r.samples_run + 1
    scale = max(1.0, float(np.max(np.abs(ix[:k]))))
    assert np.max(np.abs(r.xi[:k] - ix[:k])) <= 1e-8 * scale
    assert np.max(np.abs(r.xi_dot[:k] - iv[:k])) <= 1e-8 * scale


def test_eq4_hand_of_zero_stiffness_is_the_wall_without_it_and_tiny_is_close():
    """κ_h = 0 renders nothing (the same wall, bit for bit); κ_h = 1e-12 stays within 1e-9 of the run without."""
    base = WallParams.of(damping=0.3, delay=1)
    assert WallParams.of(damping=0.3, delay=1, hand_stiffness=0.0) == base
    assert Wall.of(1000.0, damping=1.0, hand_stiffness=0.0) == Wall.of(1000.0, damping=1.0)
    a = simulate(50.0, 1.0, 2.0, 1.3, samples=2000, record=True, wall=base)
    b = simulate(50.0, 1.0, 2.0, 1.3, samples=2000, record=True, wall=WallParams.of(0.3, 1, hand_stiffness=1e-12))
    assert a.outcome == b.outcome == "rest" and a.rest_sample == b.rest_sample
    assert np.max(np.abs(a.xi - b.xi)) <= 1e-9


def test_eq4_hand_period_skip_is_bit_identical_to_every_sample():
    """The controller kernel's period skip (a repeated state) holds with the hand's spring in the loop."""
    from dfa.core import kernel, wall_kernel

    ctl = WallParams.of(damping=0.4, delay=1, hand_stiffness=0.05)
    device, initial, run = (5.0, 0.1, 0.3), (0.0, 1.5), (20_000, 5000, 1e6, True)
    out = []
    for skip in (True, False):
        st_ = np.empty(kernel.NSTATS)
        e = np.empty(0)
        d, r, integrated = wall_kernel.run_wall_kernel(device, initial, run, ctl.kernel_table(), e, e, st_, skip)
        out.append((d, r, st_.tobytes(), integrated))
    assert out[0][:3] == out[1][:3] and ctl.hand_stiffness == 0.05


# ------------------------------------------------------------------ the criterion
def test_eq6_hand_step1_energy_identity_sympy():
    """With S = ½μξ'² + ½ξ² + ½κ_hξ², dS/dt = (φ + ξ)ξ' − βξ'² − σ|ξ'| along μξ'' + βξ' + κ_hξ + σ s = φ."""
    t, mu, beta, sigma, kap, phi, s = sp.symbols("t mu beta sigma kappa phi s")
    xi = sp.Function("xi")(t)
    xdd = (phi - beta * xi.diff(t) - kap * xi - sigma * s) / mu
    storage = sp.Rational(1, 2) * (mu * xi.diff(t) ** 2 + xi**2 + kap * xi**2)
    rate = storage.diff(t).subs(xi.diff(t, 2), xdd)
    assert sp.simplify(rate - ((phi + xi) * xi.diff(t) - beta * xi.diff(t) ** 2 - sigma * s * xi.diff(t))) == 0


def test_eq19_hand_equivalent_speed_adds_the_hand_storage():
    """V² = ξ'0² + (2H_c(ξ0) + κ_hξ0²)/μ; ξ0 = 0 leaves it |ξ'0| (the hand stores nothing there)."""
    v = equivalent_speed(1.0, xi0=2.5, mu=4.0, hand_stiffness=0.2)
    assert v * v == pytest.approx(1.0 + (2.0 * (0.5 * 2.5**2 + 0.5 * 0.25) + 0.2 * 2.5**2) / 4.0, rel=1e-14)
    r = passivity_criterion(0.3, 1.0, 2.0, wall=WallParams.of(hand_stiffness=0.4))
    assert (r.equivalent_speed, r.critical_line.beta0, r.critical_line.sigma0) == (2.0, 0.5, 0.5)


def test_eq6_hand_sampled_passive_points_never_gain_energy():
    """1500 derandomised points (half with κ_h), S with ½κ_hξ², exact runs: no growth, no divergence.

    The 10⁵-point run: ``python -m dfa.cli.soundness_report --walls --hand`` (reports/validation)."""
    r = criterion_soundness(1500, Population(hand=True), seed=2024)
    assert r.points == 1500 and r.violations == 0 and r.energy_grew == 0 and r.diverged == 0
    assert r.by_case is not None and r.by_case["hand stiffness"] > 600 and r.by_case["xi0 = 0"] < 1300


def test_eq6_hand_soundness_command_writes_hand_soundness(tmp_path, capsys):
    """``python -m dfa.cli.soundness_report --walls --hand`` writes hand_soundness.md/.json; --hand alone is refused."""
    from dfa.cli.soundness_report import main as report

    assert report(["--walls", "--hand", "--points", "30", "--out", str(tmp_path)]) == 0
    md = (tmp_path / "hand_soundness.md").read_text()
    data = json.loads((tmp_path / "hand_soundness.json").read_text())
    assert "| controller-aware | 30 |" in md and "κ_h > 0" in md and "½κ_hξ²" in md
    assert data[0]["violations"] == 0 and data[0]["by_case"]["hand stiffness"] > 0
    assert report(["--hand", "--points", "5", "--out", str(tmp_path)]) == 2
    assert "--hand needs --walls" in capsys.readouterr().err


# ------------------------------------------------------------------ the linear bound and the DF
@pytest.mark.parametrize("mu, beta, kap", [(2.0, 0.3, 0.5), (100.0, 0.0, 0.01), (0.5, 2.0, 1e-6)])
def test_eq5_hand_plant_against_control_c2d(mu, beta, kap):
    """N_G/(μ D_G) of HandSpring.plant is the ZOH of 1/(μs² + βs + κ_h) (python-control), G(1) = 1/κ_h."""
    import control

    ng, dg = HandSpring.plant(kap, beta / mu, mu)
    z = np.exp(1j * np.array([0.0, 0.3, 1.7, math.pi]))
    ours = np.polyval(ng, z - 1.0) / (mu * np.polyval(dg, z - 1.0))
    ref = control.c2d(control.tf([1.0], [mu, beta, kap]), 1.0, "zoh")(z)
    assert np.allclose(ours, ref, rtol=1e-9, atol=1e-12 * np.max(np.abs(ref)))  # c2d's rounding at z = −1
    assert ours[0].real == pytest.approx(1.0 / kap, rel=1e-9)


@pytest.mark.parametrize("delay, damping, kh", [(0, 0.0, 135.0), (1, 0.5, 135.0), (0, 0.0, 600.0)])
def test_eq5_hand_k_crit_is_where_the_linear_loop_stops_decaying(delay, damping, kh):
    """Just below K_crit the simulated linear loop (no encoder, no friction) decays, just above it grows."""
    m, b, t = 0.5, 0.5, 1e-3
    r = stable_stiffness(m, b, t, Wall.of(1000.0, damping=damping, delay=delay, hand_stiffness=kh))
    assert r.status.value == "interval"
    for f, grows in ((0.95, False), (1.05, True)):
        k = f * r.k_crit
        w = Wall.of(k, damping=damping, delay=delay, hand_stiffness=kh).params(t)
        mu, beta = m / (k * t * t), b / (k * t)
        rho = controlled_spectral_radius(mu, beta, w)
        assert (rho > 1.0) is grows
        n = int(math.log(100.0) / abs(math.log(rho))) + 2000  # the dominant mode grows or decays 100×
        run = simulate(mu, beta, 0.0, 1.0, samples=n, quantize=False, bound=1e300, wall=w, record=True)
        first, last = np.max(np.abs(run.xi[1000:2000])), np.max(np.abs(run.xi[-1000:]))
        assert (last > 10.0 * first) if grows else (last < 0.1 * first)


def test_eq36_hand_large_cycle_frequency_follows_the_held_spring():
    """The DF's large cycle of μ = 100 (half-delay) sits at ω ≈ √((1 + κ_h)/μ): the hand stiffens the loop."""
    p = dfa.Params(100.0, 0.1, 0.3)
    for kap in (0.0, 0.5):
        r = dfa.limit_cycles(p, wall=WallParams.of(damping=0.2, hand_stiffness=kap))
        big = max(r.cycles, key=lambda c: c.amplitude)
        assert big.frequency == pytest.approx(math.sqrt((1.0 + kap) / 100.0), rel=0.01)
    tiny = dfa.limit_cycles(p, wall=WallParams.of(damping=0.2, hand_stiffness=1e-9))
    none = dfa.limit_cycles(p, wall=WallParams.of(damping=0.2))
    assert [c.amplitude for c in tiny.cycles] == pytest.approx([c.amplitude for c in none.cycles], rel=1e-6)


# ------------------------------------------------------------------ the model and the command line
def test_hand_hold_gives_device_and_wall():
    """dfa.hold adds m_h, b_h to the device and k_h to the wall; the HapticMaster preset's values and source."""
    h = dfa.get_hand("hapticmaster")
    assert (h.mass, h.damping, h.stiffness) == (0.554, 6.45, 135.0) and "18004" in h.source
    dev, wall = dfa.hold(dfa.get_device("delta").device, Wall.of(2000.0, damping=1.0), h)
    assert dev.mass == pytest.approx(0.25 + 0.554) and dev.hand is h and wall.hand_stiffness == 135.0
    assert wall.params(dev.period).hand_stiffness == pytest.approx(135.0 / 2000.0, rel=1e-15)
    with pytest.raises(dfa.DFAValueError, match="hand stiffness of 135"):
        dfa.hold(dfa.get_device("delta").device, wall, h)


def test_hand_refusals_name_the_fix(capsys):
    """An amplifier lag with a hand stiffness, and a hand resonance at the Nyquist frequency, are refused."""
    with pytest.raises(dfa.DFAValueError, match="AmplifierLag and a HandSpring"):
        Wall(1000.0, (dfa.AmplifierLag(500.0), HandSpring(100.0)))
    with pytest.raises(dfa.DFAValueError, match="amplifier lag with a hand stiffness"):
        WallParams.of(lag=0.3, hand_stiffness=0.1)
    with pytest.raises(dfa.DFAValueError, match="below π"):
        simulate(0.1, 0.0, 0.5, 1.0, wall=WallParams.of(hand_stiffness=1.0))
    code = main(["check", "--device", "delta", "--stiffness", "2000", "--velocity", "0.05", "--hand",
                 "hapticmaster", "--amplifier-bandwidth", "500"])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "--amplifier-bandwidth" in err and "hand stiffness" in err


def test_hand_cli_states_the_hand_and_its_group(capsys):
    """The text names k_h and κ_h = k_h/K; the JSON's β is (b + b_h)/(K T) and its wall holds κ_h."""
    argv = ["check", "--device", "delta", "--stiffness", "2000", "--velocity", "0.05", "--hand", "hapticmaster"]
    assert main(argv) == 0
    out = " ".join(capsys.readouterr().out.split())  # the lines wrap at 100 characters
    assert "hand stiffness k_h = 135 N/m" in out and "κ_h = k_h/K = 0.0675" in out
    assert "eq. 6 extended to the damper, filter and delay, with the hand's storage ½κ_h ξ²" in out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    t = 1.0 / 3000.0
    assert d["criterion"]["beta"] == pytest.approx((0.01 + 6.45) / (2000.0 * t), rel=1e-12)
    assert d["wall"]["dimensionless"]["hand_stiffness"] == pytest.approx(0.0675, rel=1e-15)


def test_hand_every_command_takes_or_refuses_it(capsys):
    """The Z-width's wall holds k_h (its linear K_max moves with it); the contour maps (the spring's closed forms)
    refuse it; a resonance at the Nyquist frequency is refused with the largest k_h in N/m; a spring below
    rounding is the free device (no crash)."""
    base = ["zwidth", "--device", "delta", "--velocity", "0.05", "--grid", "3", "--speeds", "1", "--json"]
    rows = []
    for k in ("135", "0"):
        assert main([*base, "--hand", "hapticmaster", "--hand-stiffness", k]) == 0
        rows.append(json.loads(capsys.readouterr().out))
    assert rows[0]["wall"]["hand_stiffness"] == 135.0 and "hand_stiffness" not in rows[1]["wall"]
    assert rows[0]["limits"]["linear"][0]["value"] != rows[1]["limits"]["linear"][0]["value"]
    assert main(["contours", "--device", "delta", "--stiffness", "2000", "--hand", "hapticmaster"]) == 2
    assert "closed forms for the spring" in capsys.readouterr().err
    argv = ["check", "--device", "delta", "--stiffness", "2000", "--velocity", "0.05", "--hand-stiffness", "1e8"]
    assert main(argv) == 2
    err = capsys.readouterr().err
    top = math.pi**2 * 0.25 / (1.0 / 3000.0) ** 2
    assert err.count("\n") == 1 and f"π² m/T² = {top:.4g} N/m" in err
    tiny = ["simulate", "--mass", "1", "--damping", "0", "--coulomb", "0.1", "--resolution", "1e-5", "--period",
            "1e-3", "--stiffness", "1000", "--velocity", "0.01"]  # fmt: skip
    assert main([*tiny, "--hand-stiffness", "1e-320", "--json"]) == 0
    held = json.loads(capsys.readouterr().out)
    assert main([*tiny, "--json"]) == 0
    free = json.loads(capsys.readouterr().out)
    assert held["outcome"] == free["outcome"] and held["final_xi"] == pytest.approx(free["final_xi"], rel=1e-12)


def test_hand_report_wall_table_names_k_h_and_its_group():
    """The design report's wall table (dfa.render.controller.controller_rows) has k_h and κ_h = k_h/K rows with a
    hand stiffness, and no such rows without one."""
    from dfa.render.controller import controller_rows

    dev = dfa.get_device("delta").device
    rows = dict(controller_rows(Wall.of(2000.0, hand_stiffness=135.0), dev.period, dev.units))
    assert rows["hand stiffness k_h (to the wall's origin)"] == "135 N/m" and rows["κ_h = k_h/K"] == "0.0675"
    assert not any("k_h" in k for k in dict(controller_rows(Wall.of(2000.0, damping=1.0), dev.period, dev.units)))
