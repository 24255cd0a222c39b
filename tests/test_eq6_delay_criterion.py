"""The passivity criterion with a computational delay d and an initial position ξ0 (eq. 6, 10, 12, 18-19 generalised).

Theorem (module docstring of dfa.analysis.criterion): (β − ½ − d)V + (σ − ½) >= 0 and σ >= ½ with
V² = ξ'0² + 2H_c(ξ0)/μ imply S = ½μξ'² + ½ξ² never exceeds S(0).
"""

import json
import math

import numpy as np
import pytest
from cli_text import unwrap
from hypothesis import example, given
from hypothesis import strategies as st
from result_json import written

import dfa
from dfa import classify_region, passivity_criterion
from dfa.analysis.criterion import CriticalLine, equivalent_speed
from dfa.analysis.limits.closed_form import k_max_criterion, k_static, stiffness_response
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.model.wall import Wall, WallParams


def storage(sim):
    return 0.5 * sim.mu * sim.xi_dot**2 + 0.5 * sim.xi**2


def hc(x):
    p = x - math.floor(x)
    return 0.5 * x * x + 0.5 * (p - p * p)


# ------------------------------------------------------------------ the reported wrong answers (issue 12)
def test_eq6_delay_reproducer_mu100_beta_sigma_08_speed5_d1_is_not_passive_and_diverges():
    old = passivity_criterion(0.8, 0.8, 5.0)  # eq. 6 with d ignored: region a
    assert old.passive and old.region == "a"
    new = passivity_criterion(0.8, 0.8, 5.0, wall=WallParams.of(delay=1))
    assert not new.passive and new.region == "d"
    assert new.margin == pytest.approx((0.8 - 1.5) * 5.0 + 0.3)
    assert simulate(100.0, 0.8, 0.8, 5.0, 5000, record=False, wall=WallParams.of(delay=1)).outcome == "unstable"


def test_eq19_initial_position_reproducer_mu1_xi0_10_is_not_passive_and_diverges():
    assert passivity_criterion(0.3, 1.0, 2.0).passive  # ξ0 ignored
    r = passivity_criterion(0.3, 1.0, 2.0, xi0=10.0, mu=1.0)
    assert not r.passive
    assert r.equivalent_speed == pytest.approx(math.sqrt(4.0 + 2.0 * 50.0))
    assert simulate(1.0, 0.3, 1.0, 2.0, 5000, xi0=10.0, record=False).outcome == "unstable"


# ------------------------------------------------------------------ d = 0, ξ0 = 0 is eq. 6 unchanged
@given(st.floats(0.0, 2.0), st.floats(0.0, 3.0), st.floats(-50.0, 50.0), st.floats(0.01, 1e4), st.booleans())
def test_eq6_unchanged_at_zero_delay_and_zero_position(beta, sigma, v, mu, quantized):
    a = passivity_criterion(beta, sigma, v, quantized=quantized)
    b = passivity_criterion(beta, sigma, v, quantized=quantized, wall=WallParams.of(delay=0), xi0=0.0, mu=mu)
    s0 = 0.5 if quantized else 0.0
    assert (a.region, a.passive, a.margin, a.critical_xi_dot) == (b.region, b.passive, b.margin, b.critical_xi_dot)
    assert a.equivalent_speed == abs(v) and a.delay == 0
    assert a.passive == ((beta - 0.5) * abs(v) + sigma - s0 >= 0 and sigma >= s0)


@given(st.floats(0.0, 4.0), st.floats(0.0, 5.0), st.floats(0.0, 20.0), st.integers(0, 3))
@example(2.5, 0.5, 3.0, 2)  # corner β = ½ + d, σ = ½
@example(1.5, 0.4999, 0.0, 1)  # σ < ½ at rest: b
def test_eq6_delay_passive_iff_inequalities_and_region_a_or_e(beta, sigma, v, d):
    r = passivity_criterion(beta, sigma, v, wall=WallParams.of(delay=d))
    by_hand = (beta - 0.5 - d) * v + (sigma - 0.5) >= 0 and sigma >= 0.5
    assert r.passive == by_hand == (r.region in ("a", "e"))
    assert classify_region(beta, sigma, v, delay=d).item() == r.region
    # a delay can only remove guarantees
    if r.passive and d > 0:
        assert passivity_criterion(beta, sigma, v, wall=WallParams.of(delay=d - 1)).passive


@given(st.floats(0.0, 3.49), st.floats(0.5, 3.0), st.integers(0, 3))
def test_eq12_delay_critical_speed_separates_passive_from_not(beta, sigma, d):
    if beta >= 0.5 + d:
        assert passivity_criterion(beta, sigma, 0.0, wall=WallParams.of(delay=d)).critical_xi_dot is None
        return
    crit = passivity_criterion(beta, sigma, 0.0, wall=WallParams.of(delay=d)).critical_xi_dot
    assert crit == pytest.approx((sigma - 0.5) / (0.5 + d - beta))
    assert passivity_criterion(beta, sigma, crit * (1 - 1e-9), wall=WallParams.of(delay=d)).passive
    if crit > 0:
        assert not passivity_criterion(beta, sigma, crit * (1 + 1e-9) + 1e-12, wall=WallParams.of(delay=d)).passive


def test_eq10_delayed_critical_line_through_half_plus_d_with_slope_minus_speed():
    r = passivity_criterion(0.1, 3.0, 2.0, wall=WallParams.of(delay=2))
    line = r.critical_line
    assert (r.delay, line.beta0, line.slope) == (2, 2.5, -2.0)
    assert line.sigma(2.5) == pytest.approx(0.5)
    np.testing.assert_allclose(line.sigma(np.array([0.0, 1.0])), [0.5 + 2.0 * 2.5, 0.5 + 2.0 * 1.5])
    # without quantization the line goes through (½ + d, 0)
    assert (
        passivity_criterion(0.1, 3.0, 2.0, wall=WallParams.of(delay=2), quantized=False).critical_line.sigma(2.5) == 0.0
    )


def test_eq18_equivalent_speed_uses_hc_and_needs_mu():
    assert equivalent_speed(0.0, xi0=0.5, mu=2.0) == pytest.approx(math.sqrt(2 * 0.25 / 2.0))  # H_c(½) = ¼
    assert equivalent_speed(3.0, xi0=-2.3, mu=5.0) == pytest.approx(math.sqrt(9.0 + 2 * hc(-2.3) / 5.0))
    assert equivalent_speed(0.0, xi0=0.5, mu=2.0, quantized=False) == pytest.approx(0.5 / math.sqrt(2.0))
    with pytest.raises(dfa.DFAValueError, match="mu = None"):
        passivity_criterion(0.3, 1.0, 2.0, xi0=1.0)
    with pytest.raises(dfa.DFAValueError, match="delay"):
        passivity_criterion(0.3, 1.0, 2.0, wall=WallParams.of(delay=-1))
    with pytest.raises(dfa.DFAValueError, match="delay"):
        passivity_criterion(0.3, 1.0, 2.0, wall=WallParams.of(delay=0.5))


def test_classify_region_broadcasts_over_delay_and_quantized_arrays():
    b = np.array([0.6, 1.6, 0.2])
    out = classify_region(b[:, None], 0.8, 1.0, quantized=np.array([True, False]), delay=np.array([[0], [1], [0]]))
    assert out.shape == (3, 2)
    for i in range(3):
        for j, q in enumerate((True, False)):
            d = [0, 1, 0][i]
            assert out[i, j] == passivity_criterion(b[i], 0.8, 1.0, quantized=q, wall=WallParams.of(delay=d)).region
    with pytest.raises(dfa.DFAValueError, match="delay"):
        classify_region(0.5, 0.5, 1.0, delay=[0, -1])


def test_fig3_region_words_do_not_overclaim():
    for k in "bcd":
        text = dfa.REGION_DESCRIPTIONS[k]
        assert "unstable" not in text and "passive:" not in text
    for k in "cd":
        assert (
            "no passivity guarantee" in dfa.REGION_DESCRIPTIONS[k]
            and "not a proof of instability" in dfa.REGION_DESCRIPTIONS[k]
        )
    assert "not passive at rest" in dfa.REGION_DESCRIPTIONS["b"]
    for k in "ae":
        assert "proven" in dfa.REGION_DESCRIPTIONS[k] and "energy cannot grow" in dfa.REGION_DESCRIPTIONS[k]


# ------------------------------------------------------------------ soundness: the theorem's strong claim by simulation
@given(
    st.floats(0.1, 1000.0),
    st.floats(0.0, 4.0),
    st.floats(0.0, 1.0),
    st.floats(-8.0, 8.0),
    st.floats(-6.0, 6.0),
    st.integers(0, 3),
)
@example(mu=100.0, beta=0.8, lift=0.0, xi_dot=5.0, xi0=0.0, d=1)  # the reproducer's speed, now on the d = 1 line
@example(mu=1.0, beta=0.3, lift=0.0, xi_dot=2.0, xi0=6.0, d=0)  # the ξ0 reproducer's kind, on the line
@example(mu=50.0, beta=0.0, lift=0.0, xi_dot=3.0, xi0=0.0, d=2)  # β = 0
@example(mu=5.0, beta=1.5, lift=0.0, xi_dot=4.0, xi0=-2.5, d=1)  # β = ½ + d and σ = ½: the corner
@example(mu=5.0, beta=3.0, lift=0.0, xi_dot=4.0, xi0=0.0, d=1)  # σ = ½, β > ½ + d
@example(mu=2.0, beta=0.2, lift=0.0, xi_dot=0.0, xi0=3.7, d=3)  # ξ'0 = 0: all energy in the spring
def test_eq6_delay_soundness_energy_never_grows_on_and_above_the_line(mu, beta, lift, xi_dot, xi0, d):
    v = equivalent_speed(xi_dot, xi0, mu)
    sigma = max(0.5, 0.5 + v * (0.5 + d - beta)) + lift
    r = passivity_criterion(beta, sigma, xi_dot, wall=WallParams.of(delay=d), xi0=xi0, mu=mu)
    if not r.passive:  # rounding put the point on the line just outside: step up by one ulp
        sigma = float(np.nextafter(sigma, np.inf))
        r = passivity_criterion(beta, sigma, xi_dot, wall=WallParams.of(delay=d), xi0=xi0, mu=mu)
    assert r.passive
    sim = simulate(mu, beta, sigma, xi_dot, 3000, xi0=xi0, wall=WallParams.of(delay=d))
    s = storage(sim)
    assert sim.outcome != "unstable"
    assert np.all(s <= s[0] * (1 + 1e-9) + 1e-300)


def test_eq6_delay_soundness_check_can_fail_old_criterion_point_gains_energy():
    # the same storage check on the reproducer (passive under eq. 6 with d ignored) fails at once
    sim = simulate(100.0, 0.8, 0.8, 5.0, 3000, wall=WallParams.of(delay=1))
    assert storage(sim).max() > storage(sim)[0] * 1.1


# ------------------------------------------------------------------ stiffness (eq. 11 with delay)
DEV = dfa.get_device("Delta").device


@pytest.mark.parametrize("d", [0, 1, 3])
@pytest.mark.parametrize("velocity", [0.0, 0.02, 0.3, 5.0])
def test_eq11_delay_kmax_closed_form_and_flip(d, velocity):
    b, c, dx, t = DEV.damping, DEV.coulomb, DEV.resolution, DEV.period
    closed = min(2 * c / dx, (b * velocity + c) / (t * (0.5 + d) * velocity + dx / 2))
    k = k_max_criterion(DEV, velocity, delay=d)
    assert k == pytest.approx(closed, rel=2e-12)  # K_max is rounded down by 1e-12 (k_max_criterion)
    assert dfa.device_criterion(DEV, Wall.of(k * (1 - 1e-9), delay=d), velocity).passive
    assert not dfa.device_criterion(DEV, Wall.of(k * (1 + 1e-9), delay=d), velocity).passive


@given(st.floats(1.0, 6e4), st.integers(0, 3))
def test_eq12_delay_max_passive_velocity_inverts_kmax(k, d):
    v = dfa.max_passive_velocity(DEV, k, delay=d)
    if k > 2 * DEV.coulomb / DEV.resolution:
        assert v is None
    elif k * DEV.period * (0.5 + d) <= DEV.damping:
        assert math.isinf(v)
    else:
        assert dfa.device_criterion(DEV, Wall.of(k, delay=d), v * (1 - 1e-9)).passive
        assert not dfa.device_criterion(DEV, Wall.of(k, delay=d), v * (1 + 1e-6)).passive


def test_eq8_colgate_with_delay_and_one_source_for_the_static_limit():
    assert dfa.k_colgate(DEV, delay=2) == pytest.approx(DEV.damping / (DEV.period * 2.5))
    assert dfa.k_colgate(DEV) == pytest.approx(2 * DEV.damping / DEV.period)
    static = 2 * DEV.coulomb / DEV.resolution  # eq. 9, independent of this package
    for d in (0, 2):
        lim = dfa.stiffness_limits(DEV, 0.1, 14500.0, delay=d)
        curve = stiffness_response(DEV, stiffness=14500.0, delay=d)
        assert curve.k_static == pytest.approx(static, rel=1e-12) == lim.k_static == k_static(DEV)
        assert (curve.k_colgate, curve.k_abbott_okamura, curve.k_gil) == (
            lim.k_colgate,
            lim.k_abbott_okamura,
            lim.k_gil,
        )
        assert curve.k_abbott_okamura == pytest.approx(min(static, DEV.damping / (DEV.period * (0.5 + d))))
        assert k_max_criterion(DEV, 1e-12, delay=d) == pytest.approx(curve.k_static)
        np.testing.assert_allclose(curve.k_max, k_max_criterion(DEV, curve.velocity, delay=d))
        assert curve.max_passive_velocity == lim.max_passive_velocity and curve.delay == d


def test_eq11_stiffness_curve_reads_its_bounds_from_stiffness_limits(monkeypatch):
    """StiffnessCurve holds a StiffnessLimits and recomputes none of its bounds (one evaluation of each)."""
    import dfa.analysis.limits.closed_form as stf

    calls = []
    real = stf.k_gil
    monkeypatch.setattr(stf, "k_gil", lambda *a, **k: calls.append(1) or real(*a, **k))
    curve = stiffness_response(DEV, stiffness=14500.0, delay=1)
    assert len(calls) == 1 and isinstance(curve.limits, stf.StiffnessLimits)
    assert curve.limits == stf.stiffness_limits(DEV, float(curve.velocity[0]), 14500.0, delay=1)
    assert curve.k_max[0] == curve.limits.k_max


# ------------------------------------------------------------------ command line
def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def row(out, label):
    lines = [ln for ln in unwrap(out).splitlines() if ln.startswith(label)]
    assert len(lines) == 1, (label, out)
    return lines[0][len(label) :].strip()


def test_cli_check_text_zero_delay(capsys):
    code, out, _ = run(capsys, "check", "--device", "delta", "--velocity", "0.1")
    assert code == 0
    r = dfa.device_criterion(DEV, 14500.0, 0.1)
    assert (
        row(out, "passive")
        == f"yes: the energy cannot grow for speeds up to V = {r.critical_xi_dot:.4g} ticks/sample (proven)"
    )
    assert row(out, "region").startswith("e: passive up to the critical speed")
    assert (
        row(out, "critical speed (eq. 12, d = 0)")
        == f"{r.critical_xi_dot:.4g} ticks/sample ({r.critical_velocity:.4g} m/s)"
    )
    assert row(out, "delay d") == "0 samples"


def test_cli_check_text_with_delay(capsys):
    code, out, _ = run(
        capsys, "check", "--mu", "100", "--beta", "0.8", "--sigma", "0.8", "--xi-dot", "5", "--delay", "1"
    )
    assert code == 0
    assert row(out, "passive") == "no: no passivity guarantee (not a proof of instability)"
    assert row(out, "region").startswith("d: no passivity guarantee at this speed")
    assert row(out, "critical speed (eq. 12, d = 1)") == f"{0.3 / 0.7:.4g} ticks/sample"
    assert row(out, "margin") == f"{-3.2:.4g}"
    code, out, _ = run(capsys, "check", "--beta", "2.6", "--sigma", "0.6", "--xi-dot", "5", "--delay", "2")
    assert row(out, "passive") == "yes: the energy cannot grow at every speed (proven)" and row(
        out, "region"
    ).startswith("a:")


def test_cli_check_json_delay_and_initial_position(capsys):
    code, out, _ = run(
        capsys, "check", "--mu", "1", "--beta", "0.3", "--sigma", "1", "--xi-dot", "2", "--xi0", "10", "--json"
    )
    r = json.loads(out)
    assert code == 0 and r["passive"] is False and r["xi0"] == 10.0 and r["delay"] == 0
    assert r["equivalent_speed"] == pytest.approx(math.sqrt(104.0))
    code, out, _ = run(capsys, "check", "--mu", "1", "--beta", "0.3", "--sigma", "1", "--xi-dot", "2", "--xi0", "10")
    assert (
        row(out, "critical speed (eq. 12, d = 0)") == "2.5 ticks/sample, a bound on the equivalent speed V, not on ξ'0"
    )
    assert row(out, "equivalent speed V").startswith(f"{math.sqrt(104.0):.4g} ticks/sample")
    code, out, _ = run(
        capsys, "check", "--device", "delta", "--velocity", "0.1", "--position", "3e-4", "--delay", "1", "--json"
    )
    r = json.loads(out)
    api = dfa.device_criterion(DEV, Wall.of(14500.0, delay=1), 0.1, position=3e-4)
    assert (r["region"], r["margin"], r["equivalent_speed"], r["delay"]) == (
        api.region,
        written(api.margin),
        written(api.equivalent_speed),
        1,
    )
    assert r["xi0"] == pytest.approx(10.0) and r["position"] == 3e-4


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["check", "--beta", "0.3", "--sigma", "1", "--xi-dot", "2", "--xi0", "1"], "--xi0 1 needs --mu"),
        (
            ["check", "--beta", "0.3", "--sigma", "1", "--xi-dot", "2", "--position", "1e-3"],
            "--position needs a physical device",
        ),
        (["check", "--device", "delta", "--xi-dot", "2", "--xi0", "1"], "--xi0 is for dimensionless input"),
        (
            ["check", "--beta", "0.3", "--sigma", "1", "--xi-dot", "2", "--delay", "-1"],
            "--delay must be a whole number",
        ),
        (["stiffness", "--device", "delta", "--velocity", "0.1", "--delay", "1.5"], "--delay takes"),
    ],
)
def test_cli_delay_and_position_errors_are_one_line(capsys, argv, needle):
    code, out, err = run(capsys, *argv)
    assert code == 2 and needle in err and err.count("\n") == 1 and out == ""


def test_cli_stiffness_above_static_limit_is_answered_not_crashed(capsys):
    code, out, err = run(
        capsys, "stiffness", "--device", "delta", "--velocity", "0.1", "--stiffness", "60000", "--explain"
    )
    assert code == 0, err
    static = 2 * DEV.coulomb / DEV.resolution
    assert row(out, "verdict at this speed") == (
        f"too stiff: no passivity guarantee even at rest (K > 2c/Δ = {static:.5g} N/m); not a proof of instability"
    )
    assert row(out, "largest passive speed at K = 60000 N/m").startswith("none: no passivity guarantee even at rest")
    code, out, _ = run(capsys, "stiffness", "--device", "delta", "--velocity", "0.1", "--stiffness", "60000", "--json")
    a = json.loads(out)["assessment"]
    assert a["velocity_status"] == "none" and a["verdict"] == "too_stiff" and a["max_passive_velocity"] is None


def test_cli_stiffness_with_delay(capsys):
    code, out, _ = run(
        capsys,
        "stiffness",
        "--device",
        "delta",
        "--velocity",
        "0.1",
        "--stiffness",
        "20000",
        "--delay",
        "1",
        "--explain",
    )
    assert code == 0
    k = k_max_criterion(DEV, 0.1, delay=1)
    assert row(out, "criterion K_max at this speed (eq. 11, d = 1)") == f"{k:.5g} N/m"
    assert row(out, "Colgate-Schenkel b/(T(½ + d)) (eq. 8)") == f"{DEV.damping / (DEV.period * 1.5):.5g} N/m"
    assert row(out, "verdict at this speed").startswith("too stiff: no passivity guarantee at this speed")
    code, out, _ = run(
        capsys, "stiffness", "--device", "delta", "--velocity", "0.1", "--stiffness", "20000", "--delay", "1", "--json"
    )
    r = json.loads(out)
    assert r["delay"] == 1 and r["k_criterion"]["value"] == pytest.approx(k)


# ------------------------------------------------------------------ plots draw the CriticalLine
def test_fig4_map_plot_draws_the_delayed_critical_line():
    import matplotlib.pyplot as plt

    from dfa.analysis.maps import stability_map
    from dfa.render import figures

    m = stability_map(
        100.0, [2.0], beta_range=(0.0, 2.0), grid=4, samples=300, n_jobs=1, progress=False, wall=WallParams.of(delay=1)
    )
    ax = figures.stability_map_plot(m)[0]
    dashed = [ln for ln in ax.get_lines() if ln.get_linestyle() == "--"]
    assert len(dashed) == 1
    x, y = dashed[0].get_data()
    np.testing.assert_allclose(y, 0.5 + 2.0 * (1.5 - np.asarray(x)))  # through (½ + d, ½), slope −ξ'0
    assert any(np.allclose(ln.get_xdata(), 1.5) for ln in ax.get_lines() if ln.get_linestyle() == "-.")
    plt.close(ax.figure)


def test_fig3_regions_plot_draws_the_result_critical_line_with_delay():
    import matplotlib.pyplot as plt

    from dfa.render import figures

    r = passivity_criterion(0.3, 3.0, 2.0, wall=WallParams.of(delay=1), xi0=1.0, mu=4.0)
    ax = figures.regions_plot(r, xi_dots=[1.0])
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    x, y = next(v for k, v in lines.items() if k.startswith("critical line")).get_data()
    np.testing.assert_allclose(y, 0.5 + r.equivalent_speed * (1.5 - np.asarray(x)))
    x, y = lines["ξ'0 = 1"].get_data()
    np.testing.assert_allclose(y, CriticalLine.of(1.0, delay=1).sigma(np.asarray(x)))
    plt.close(ax.figure)


@pytest.mark.parametrize("d", [0, 1, 2])
@pytest.mark.parametrize("beta_share", [0.0, 0.5, 1.0])
def test_eq7_delay_without_quantization_energy_never_grows_on_the_line(d, beta_share):
    # eq. 7 generalised: (β − ½ − d)V + σ >= 0; on the line, including σ = 0 at β = ½ + d
    mu, xi_dot, xi0 = 20.0, 3.0, 1.5
    beta = beta_share * (0.5 + d)
    v = equivalent_speed(xi_dot, xi0, mu, quantized=False)
    sigma = v * (0.5 + d - beta)
    r = passivity_criterion(beta, sigma, xi_dot, quantized=False, wall=WallParams.of(delay=d), xi0=xi0, mu=mu)
    if not r.passive:
        sigma = float(np.nextafter(sigma, np.inf))
        r = passivity_criterion(beta, sigma, xi_dot, quantized=False, wall=WallParams.of(delay=d), xi0=xi0, mu=mu)
    assert r.passive
    sim = simulate(mu, beta, sigma, xi_dot, 3000, xi0=xi0, quantize=False, wall=WallParams.of(delay=d))
    s = storage(sim)
    assert np.all(s <= s[0] * (1 + 1e-9))
    # just below the line (β = 0, σ = 0) the same loop gains energy
    if beta_share == 0.0:
        s_bad = storage(simulate(mu, 0.0, 0.0, xi_dot, 3000, xi0=xi0, quantize=False, wall=WallParams.of(delay=d)))
        assert np.nanmax(s_bad) > s_bad[0] * 1.01  # NaN: diverged past the bound
