"""Eq. 6 extended to a virtual damper, velocity filter and delay (dfa.analysis.criterion; issue 15 item 2).

Theorem (module docstring of dfa.analysis.criterion): with β₀ = ½ + d + β_B and
σ₀ = ½ + (1 − a)β_B (0 without the encoder), (β − β₀)V + (σ − σ₀) >= 0 and σ >= σ₀
imply S = ½μξ'² + ½ξ² never exceeds S(0). Tested here: each step of the derivation
(sympy identities, the exact decomposition and the summed inequality on simulated
trajectories of an independent reference loop), the reductions to eq. 6 and to
Colgate-Schenkel, the physical form (eq. 11 extended), and soundness by simulation.
"""

import json
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from reference_ctl import controller_run

import dfa
from dfa.analysis.criterion import CriterionResult, device_criterion, passivity_criterion
from dfa.analysis.simulation import simulate
from dfa.core import kernel
from dfa.errors import DFATypeError, DFAValueError
from dfa.model.catalogue import get_device
from dfa.model.wall import Wall, WallParams
from dfa.studies.soundness import Population, criterion_soundness, sample_passive_points


# ------------------------------------------------------------------ an independent reference loop (pure Python)
def reference_run(mu, beta, sigma, x0, v0, n, ctl: WallParams, quantize=True):
    """ξ_h, ξ'_h, forces φ_h and turning-point storages of the loop, written from the transfer-function form.

    The damper input is the explicit convolution y_m = Σ_k (1 − a)a^{k−1} v_{m−k} (filter) or v_m,
    not the recursion of the wall kernel; the step is the exact per-sample step of dfa.simulate.
    """
    k = kernel.sample_constants(mu, beta)
    a, filtered = ctl.filter_pole, ctl.cutoff is not None
    xs, vs, reads, cmds, phis, turns = [x0], [v0], [], [], [], []
    for h in range(n):
        x = xs[-1]
        reads.append(math.floor(x) if quantize else x)
        vel = [0.0] + [reads[j] - reads[j - 1] for j in range(1, h + 1)]
        y = sum((1 - a) * a ** (kk - 1) * vel[h - kk] for kk in range(1, h + 1)) if filtered else vel[h]
        cmds.append(-(reads[h] + (0.5 if quantize else 0.0)) - ctl.damping * y)
        phi = cmds[h - ctl.delay] if h >= ctl.delay else cmds[0]
        phis.append(phi)
        x1, v1, xr, _t, _a, _a2, _tr, stopped = kernel.step(x, vs[-1], phi, mu, sigma, k)
        xs.append(x1)
        vs.append(v1)
        turns.append(0.5 * xr * xr if stopped else -np.inf)
    return np.array(xs), np.array(vs), np.array(phis), np.array(turns)


CONTROLLERS = [
    WallParams.of(),
    WallParams.of(damping=0.7),
    WallParams.of(damping=0.7, delay=2),
    WallParams.of(damping=1.3, delay=1, cutoff=0.05),
    WallParams.of(damping=0.4, cutoff=0.3),
]


# ------------------------------------------------------------------ step 1-3 of the derivation, symbolically
def test_eq6_controller_step1_energy_rate_identity_sympy():
    t, mu, beta, sigma, s, phi, xh = sp.symbols("tau mu beta sigma s phi xi_h", real=True)
    xi = sp.Function("xi")(t)
    xdd = (phi - beta * xi.diff(t) - sigma * s) / mu  # the plant under a constant force, sgn ξ' = s (eq. 4)
    storage = sp.Rational(1, 2) * mu * xi.diff(t) ** 2 + sp.Rational(1, 2) * xi**2
    rhs = sp.Rational(1, 2) * (xi - xh) ** 2 + (phi + xh) * (xi - xh)  # ½Δ² + (φ + ξ_h)Δ
    rate = storage.diff(t).subs(xi.diff(t, 2), xdd) - rhs.diff(t) + beta * xi.diff(t) ** 2 + sigma * s * xi.diff(t)
    assert sp.simplify(rate) == 0  # S_{h+1} − S_h = ½Δ² + (φ + ξ_h)Δ − β∫ξ'² − σ∫|ξ'|


def test_eq17_controller_step3_velocity_estimate_identity_sympy():
    x1, x0, p1, p0 = sp.symbols("xi_j xi_jm1 p_j p_jm1", real=True)
    v = (x1 - p1) - (x0 - p0)  # n = ξ − p (eq. 17)
    assert sp.expand(v - ((x1 - x0) - (p1 - p0))) == 0


@pytest.mark.parametrize("terms", [1, 2, 3, 6])
def test_eq17_controller_step3_filtered_quantization_error_abel_sum_sympy(terms):
    a = sp.symbols("a", positive=True)
    p = sp.symbols(f"p0:{terms + 1}")  # p[k] = p_{m−k}, k = 0 … terms
    q = sp.expand((1 - a) * sum(a ** (k - 1) * (p[k - 1] - p[k]) for k in range(1, terms + 1)))
    coeffs = [sp.factor(q.coeff(pk)) for pk in p]
    assert sp.simplify(coeffs[0] - (1 - a)) == 0  # the only positive coefficient (0 < a < 1)
    assert sp.simplify(sum(coeffs)) == 0  # so the negative ones sum to −(1 − a): |Q| < 1 − a
    for c in coeffs[1:]:
        assert all(sp.simplify(c.subs(a, val)) <= 0 for val in (sp.Rational(1, 10), sp.Rational(9, 10)))


def test_eq6_controller_step4_filter_weights_sum_to_one_sympy():
    """The damper weights of a finite history sum to 1 − a^N <= 1 (each Δ² gets <= β_B in all)."""
    a = sp.symbols("a", positive=True)
    k, n = sp.symbols("k N", integer=True, positive=True)
    total = sp.summation((1 - a) * a ** (k - 1), (k, 1, n))
    assert sp.simplify(total - (1 - a**n)) == 0


# ------------------------------------------------------------------ steps 2-4 on simulated trajectories
@pytest.mark.parametrize("ctl", CONTROLLERS)
def test_eq6_controller_step2_3_decomposition_is_exact_on_trajectories(ctl):
    xs, _vs, phis, _ = reference_run(3.0, 0.1, 0.3, 0.37, 2.6, 300, ctl)
    dx = np.diff(xs)
    p = xs - np.floor(xs)
    a, d = ctl.filter_pole, ctl.delay
    dd = lambda j: dx[j] if j >= 0 else 0.0  # Δ_k = 0 before the start
    pp = lambda j: p[max(j, 0)]  # p_k = p_0 before the start
    cs = [(1 - a) * a ** (k - 1) for k in range(1, 301)] if ctl.cutoff is not None else None
    for h in range(300):
        spring = sum(dd(h - j) for j in range(1, d + 1)) + (pp(h - d) - 0.5)
        m = h - d
        if cs is None:
            lin, quant = dd(m - 1), pp(m) - pp(m - 1)
        else:
            lin = sum(cs[k - 1] * dd(m - k - 1) for k in range(1, m + 1))
            quant = sum(cs[k - 1] * (pp(m - k) - pp(m - k - 1)) for k in range(1, m + 1))
        assert abs(quant) < 1.0 - a + 1e-12  # step 3's bound
        expected = spring - ctl.damping * (lin - quant)
        assert phis[h] + xs[h] == pytest.approx(expected, abs=1e-9 * (1 + abs(xs[h])))


@given(
    mu=st.floats(0.2, 50.0),
    beta=st.floats(0.0, 1.0),
    sigma=st.floats(0.0, 1.0),
    v0=st.floats(-6.0, 6.0),
    x0=st.floats(-3.0, 3.0),
    damping=st.floats(0.0, 2.0),
    delay=st.integers(0, 3),
    cutoff=st.none() | st.floats(0.01, 0.49),
    quantize=st.booleans(),
)
def test_eq6_controller_step4_summed_inequality_holds_for_every_parameter(
    mu, beta, sigma, v0, x0, damping, delay, cutoff, quantize
):
    """S_n − S_0 <= Σ_h (β₀ − β)Δ_h² + (σ₀ − σ)|Δ_h| for every n, passive or not (the heart of the proof)."""
    ctl = WallParams.of(damping=damping, delay=delay, cutoff=cutoff)
    xs, vs, _, _ = reference_run(mu, beta, sigma, x0, v0, 120, ctl, quantize)
    if not np.all(np.isfinite(xs)) or np.max(np.abs(xs)) > 1e6:
        return
    b0, s0 = ctl.corner(quantize)
    dx = np.diff(xs)
    bound = np.cumsum((b0 - beta) * dx**2 + (s0 - sigma) * np.abs(dx))
    storage = 0.5 * mu * vs**2 + 0.5 * xs**2
    gained = storage[1:] - storage[0]
    assert np.all(gained <= bound + 1e-9 * (1.0 + storage[0] + np.abs(bound)))


@pytest.mark.parametrize("ctl", CONTROLLERS)
def test_eq6_controller_compiled_loop_matches_the_reference_loop(ctl):
    runs = [(3.0, 0.1, 0.3, 0.37, 2.6), (40.0, 0.02, 0.9, 0.0, 4.0), (0.5, 2.0, 0.1, -2.2, 0.3), (2.0, 4.5, 4.0, 0, 3)]
    for mu, beta, sigma, x0, v0 in runs:
        with np.errstate(all="ignore"):
            xs, vs, _, turns = reference_run(mu, beta, sigma, x0, v0, 400, ctl)
        worst, at, div = controller_run(
            mu, beta, sigma, x0, v0, 400, ctl.damping, ctl.delay, ctl.filter_pole, ctl.cutoff is not None, True,
            1e6, np.empty(ctl.delay + 1),
        )  # fmt: skip
        past = np.flatnonzero(~(np.abs(xs) <= 1e6))
        if past.size:  # diverged: at the same sample
            assert div and worst == np.inf and at == past[0]
            continue
        s = np.maximum(0.5 * mu * vs[1:] ** 2 + 0.5 * xs[1:] ** 2, turns)
        s0 = 0.5 * mu * v0**2 + 0.5 * x0**2
        assert not div and worst == pytest.approx(np.max((s - s0) / s0), rel=1e-12, abs=1e-15)
        assert at == int(np.argmax((s - s0) / s0)) + 1


@pytest.mark.parametrize("delay", [0, 1, 3])
def test_eq4_controller_spring_only_reference_loop_equals_dfa_simulate(delay):
    """WallParams.of(delay=d) is today's spring loop: same trajectory as dfa.simulate."""
    for quantize in (True, False):
        sim = dfa.simulate(7.0, 0.05, 0.6, 3.0, 300, xi0=0.4, quantize=quantize, wall=WallParams.of(delay=delay))
        xs, vs, _, _ = reference_run(7.0, 0.05, 0.6, 0.4, 3.0, 300, WallParams.of(delay=delay), quantize)
        m = int(np.sum(np.isfinite(sim.xi)))  # a diverged run stops at its last integrated sample
        assert m > 20
        np.testing.assert_allclose(xs[:m], sim.xi[:m], rtol=1e-14, atol=1e-12)
        np.testing.assert_allclose(vs[:m], sim.xi_dot[:m], rtol=1e-14, atol=1e-12)


# ------------------------------------------------------------------ reductions: eq. 6 and Colgate-Schenkel
@given(
    beta=st.floats(0.0, 5.0),
    sigma=st.floats(0.0, 5.0),
    xi_dot=st.floats(-20.0, 20.0),
    delay=st.integers(0, 4),
    cutoff=st.none() | st.floats(0.01, 0.49),
    quantized=st.booleans(),
    xi0=st.sampled_from([0.0, 0.3, -4.7]),
)
def test_eq6_controller_without_damper_equals_passivity_criterion(beta, sigma, xi_dot, delay, cutoff, quantized, xi0):
    ctl = WallParams.of(delay=delay, cutoff=cutoff)
    new = passivity_criterion(beta, sigma, xi_dot, wall=ctl, quantized=quantized, xi0=xi0, mu=2.0)
    old = dfa.passivity_criterion(
        beta, sigma, xi_dot, quantized=quantized, wall=WallParams.of(delay=delay), xi0=xi0, mu=2.0
    )
    assert (new.region, new.passive, new.margin, new.critical_xi_dot) == (
        old.region,
        old.passive,
        old.margin,
        old.critical_xi_dot,
    )
    assert new.equivalent_speed == old.equivalent_speed and new.status.region == old.status.region


@pytest.mark.parametrize(
    ("beta", "sigma", "xi_dot", "region"),
    [(2.0, 2.0, 1.0, "a"), (2.0, 0.1, 1.0, "b"), (0.1, 0.1, 1.0, "c"), (0.2, 2.03, 9.0, "d"), (0.2, 2.03, 0.5, "e")],
)
def test_eq6_controller_status_states_the_controller_thresholds(beta, sigma, xi_dot, region):
    """The messages name β₀, σ₀ (not the spring's ½ + d, ½) and the result fills in their values."""
    ctl = WallParams.of(damping=0.3, delay=1, cutoff=0.1)
    r = passivity_criterion(beta, sigma, xi_dot, wall=ctl)
    b0, s0 = 1.5 + 0.3, 0.5 + (1.0 - np.exp(-0.2 * np.pi)) * 0.3
    assert r.region == region and r.status.region == region
    assert "½ + d" not in r.status.message and "σ < ½" not in r.status.message
    assert "not passive at rest" not in r.status.message  # σ < σ₀ is only the lack of a guarantee here
    assert f"β₀ = {b0:.6g}, σ₀ = {s0:.6g}" in r.status_message
    assert r.to_dict()["status_message"] == r.status_message
    if region in ("b", "c", "d"):
        assert "not a proof of instability" in r.status_message


def test_eq6_controller_default_is_the_paper_spring():
    r = passivity_criterion(0.002, 2.03, 1.0)
    assert (r.region, round(r.critical_xi_dot, 3), r.beta0, r.sigma0) == ("e", 3.072, 0.5, 0.5)


@pytest.mark.parametrize("damping", [0.0, 0.25, 1.0, 4.0])
def test_eq8_controller_colgate_schenkel_b_above_kt_half_plus_b(damping):
    """No encoder, no Coulomb friction, d = 0: passive at every speed iff β >= ½ + β_B (b >= KT/2 + B)."""
    ctl = WallParams.of(damping=damping)
    edge = 0.5 + damping
    assert passivity_criterion(edge, 0.0, 7.0, wall=ctl, quantized=False).region == "a"
    assert not passivity_criterion(np.nextafter(edge, 0.0), 0.0, 7.0, wall=ctl, quantized=False).passive


def test_eq6_controller_anchor_values():
    assert WallParams.of(damping=0.3).corner() == (0.8, 0.8)
    b0, s0 = WallParams.of(damping=0.3, delay=2, cutoff=0.1).corner()
    assert b0 == pytest.approx(2.8) and s0 == pytest.approx(0.5 + 0.3 * (1 - math.exp(-0.2 * math.pi)))
    assert WallParams.of(damping=0.3, delay=2, cutoff=0.1).corner(quantized=False)[1] == 0.0


@given(
    beta=st.floats(0.0, 4.0),
    sigma=st.floats(0.0, 4.0),
    xi_dot=st.floats(0.0, 10.0),
    damping=st.floats(0.0, 2.0),
    delay=st.integers(0, 3),
    cutoff=st.none() | st.floats(0.01, 0.49),
)
def test_eq10_controller_regions_and_critical_speed(beta, sigma, xi_dot, damping, delay, cutoff):
    ctl = WallParams.of(damping=damping, delay=delay, cutoff=cutoff)
    r = passivity_criterion(beta, sigma, xi_dot, wall=ctl)
    b0, s0 = r.beta0, r.sigma0
    assert r.passive == (sigma >= s0 and (beta - b0) * xi_dot + (sigma - s0) >= 0.0)
    if r.critical_xi_dot is not None:  # eq. 12 extended: passive up to V_c
        assert r.region in ("d", "e") and r.passive == (xi_dot <= r.critical_xi_dot * (1 + 1e-12) or r.margin >= 0)
        assert r.critical_xi_dot == pytest.approx((sigma - s0) / (b0 - beta))
    assert json.loads(json.dumps(r.to_dict(), allow_nan=False))["wall"]["delay"] == delay


# ------------------------------------------------------------------ physical form (eq. 11 extended)
def test_eq11_controller_physical_form_and_spring_equals_device_criterion():
    dev = get_device("Delta").device
    old = dfa.device_criterion(dev, Wall.of(14500.0, delay=1), 0.1)
    new = device_criterion(dev, Wall.of(14500.0, delay=1), 0.1)
    assert (new.region, new.critical_velocity) == (old.region, old.critical_velocity)
    k, b_v, v = 3000.0, 1.5, 0.05
    for fc in (None, 50.0):
        r = device_criterion(dev, Wall.of(k, damping=b_v, filter_cutoff=fc), v)
        a = 0.0 if fc is None else math.exp(-2 * math.pi * fc * dev.period)
        b, c, t, dx = dev.damping, dev.coulomb, dev.period, dev.resolution
        lhs = (b - b_v - k * t / 2) * v + (c - k * dx / 2 - (1 - a) * b_v * dx / t)
        assert r.margin * k * dx == pytest.approx(lhs, rel=1e-12)
        assert r.passive == (lhs >= 0 and c >= k * dx / 2 + (1 - a) * b_v * dx / t)


# ------------------------------------------------------------------ refusals and bad input
def test_eq6_controller_refuses_amplifier_lag_and_offers_the_simulated_map():
    with pytest.raises(DFAValueError, match=r"wall.lag = 0.5 is invalid.*stability_map"):
        passivity_criterion(1.0, 1.0, 1.0, wall=WallParams.of(lag=0.5))
    dev = get_device("Delta").device
    with pytest.raises(DFAValueError, match="stability_map"):
        device_criterion(dev, Wall.of(1000.0, amplifier_bandwidth=500.0), 0.1)
    with pytest.raises(DFATypeError, match="wall"):
        passivity_criterion(1.0, 1.0, 1.0, wall=Wall.of(1000.0))
    with pytest.raises(DFAValueError, match="mu"):
        passivity_criterion(1.0, 1.0, 1.0, wall=WallParams.of(damping=0.1), xi0=1.0)
    with pytest.raises(DFATypeError, match="quantized"):
        passivity_criterion(1.0, 1.0, 1.0, quantized="yes")
    with pytest.raises(DFAValueError, match="they must agree"):
        r = passivity_criterion(1.0, 1.0, 1.0)
        CriterionResult(**{**r.__dict__, "passive": False})


@settings(max_examples=40, deadline=None, derandomize=True)
@given(
    mu=st.floats(0.1, 1e4),
    beta=st.floats(0.0, 3.0),
    sigma=st.floats(0.0, 3.0),
    x0=st.floats(-10.0, 10.0),
    v0=st.floats(-10.0, 10.0),
    damping=st.floats(1e-3, 3.0),
    delay=st.integers(0, 3),
    cutoff=st.none() | st.floats(0.01, 0.49),
    quantize=st.booleans(),
)
def test_eq4_controller_simulator_is_bit_identical_to_the_reference_loop(
    mu, beta, sigma, x0, v0, damping, delay, cutoff, quantize
):
    """dfa.simulate(controller=...) (the compiled _ckernel, no lag) against tests/reference_ctl.controller_run.

    The same arithmetic in the same order: the trajectories agree bit for bit at every sample up to the
    simulator's own stop (rest detected or the bound passed); after a detected rest the reference stays put.
    """
    ctl = WallParams.of(damping=damping, delay=delay, cutoff=cutoff)
    n = 600
    rec = np.empty((n + 1, 2))
    with np.errstate(all="ignore"):
        controller_run(mu, beta, sigma, x0, v0, n, damping, delay, ctl.filter_pole, cutoff is not None, quantize,
                       1e6, np.empty(delay + 1), rec)  # fmt: skip
        r = simulate(mu, beta, sigma, v0, n, x0, quantize=quantize, bound=1e6, wall=ctl)
    xs, vs = np.asarray(r.xi), np.asarray(r.xi_dot)
    ok = np.isfinite(xs) & (np.abs(rec[:, 0]) <= 1e6)  # the simulator's record is NaN after a bound exit
    assert ok[: n // 2].all() or r.outcome == "unstable"
    assert np.array_equal(xs[ok], rec[ok, 0]) and np.array_equal(vs[ok], rec[ok, 1])


# ------------------------------------------------------------------ soundness by simulation (fast version)
def test_eq6_controller_sampled_passive_points_never_gain_energy():
    """Derandomised sample; the 10⁵-point run is python -m dfa.cli.soundness_report --walls (reports/validation)."""
    r = criterion_soundness(1500, Population(), seed=2024)
    assert r.criterion == "controller-aware" and r.delay is None
    assert r.points == 1500 and r.violations == 0 and r.energy_grew == 0 and r.diverged == 0
    assert r.by_kind["line"] > 300 and r.by_kind["sigma-edge"] > 120 and r.by_kind["beta-edge"] > 120
    assert r.by_case["filter"] > 600 and r.by_case["no encoder"] > 150 and r.by_case["xi0 = 0"] > 1000


def test_eq6_controller_the_same_sampler_finds_violations_of_the_damper_ignoring_criterion():
    r = criterion_soundness(1500, Population(), criterion="damper-ignoring", seed=2024)
    assert r.energy_grew > 5 and r.diverged > 0  # the check can fail: the damper must be paid for


def test_eq6_controller_sampler_points_are_passive_and_on_the_boundaries():
    pts = sample_passive_points(150, Population(), seed=5)
    for i in range(150):
        cut = pts["cutoff"][i]
        ctl = WallParams.of(float(pts["damping"][i]), int(pts["delay"][i]), None if math.isnan(cut) else cut)
        q = bool(pts["quantized"][i])
        r = passivity_criterion(
            pts["beta"][i], pts["sigma"][i], pts["xi_dot"][i], wall=ctl, quantized=q, xi0=pts["xi0"][i], mu=pts["mu"][i]
        )
        assert r.passive
        if pts["kind"][i] == 1:
            assert r.margin == pytest.approx(0.0, abs=1e-12 * max(1.0, r.sigma))
        elif pts["kind"][i] == 2:
            assert pts["sigma"][i] == r.sigma0
        elif pts["kind"][i] == 3:
            assert pts["beta"][i] == r.beta0


def test_eq6_controller_sigma0_needs_the_damper_term():
    """σ >= ½ is not enough with a quantized damper: found by probing below σ₀ = ½ + β_B (d = 0, no filter).

    Starting at the tick boundary ξ0 = 0 moving down, the first reading change gives v = −1 and the
    damper's kick β_B pushes the device on; the storage grows although β is far above β₀.
    """
    mu, beta, sigma, damping, v0 = (
        0.12826279395871265,
        5.365932651609205,
        1.818211901320726,
        2.2556065841556014,
        -0.4135842201830031,
    )
    ctl = WallParams.of(damping=damping)
    assert dfa.passivity_criterion(beta, sigma, v0).passive  # the spring's criterion, damper ignored
    r = passivity_criterion(beta, sigma, v0, wall=ctl)
    assert not r.passive and r.region == "b" and sigma < r.sigma0
    worst, _at, div = controller_run(mu, beta, sigma, 0.0, v0, 200, damping, 0, 0.0, False, True, 1e6, np.empty(1))
    assert worst > 0.4 and not div  # S grew by more than 40 %


def test_eq6_controller_soundness_command_writes_markdown_and_json(tmp_path, capsys):
    from dfa.cli.soundness_report import main

    assert main(["--walls", "--points", "40", "--out", str(tmp_path)]) == 0
    md = (tmp_path / "controller_soundness.md").read_text()
    data = json.loads((tmp_path / "controller_soundness.json").read_text())
    assert "| controller-aware | 40 |" in md and "| damper-ignoring | 40 |" in md
    assert data[0]["criterion"] == "controller-aware" and data[0]["violations"] == 0 and data[0]["status"] == "sound"
    assert "controller-aware: 0 violations of 40" in capsys.readouterr().err
