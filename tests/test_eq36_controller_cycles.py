"""Describing functions with a virtual-wall controller (issue 15 item 3; paper eq. 36, 40, 41).

The loop: D(M) multiplies the controller C(e^{jω}) = 1 + β_B(1 − e^{−jω})F(e^{jω}), the delay
e^{−jωd}, the amplifier lag and the device with Coulomb friction through β_eq (eq. 40). Checked here:
the spring-only results bit for bit, the residual at every root, the exact ZOH of amplifier + device
against python-control, the M → ∞ neutral cycle against the exact linear critical K computed
independently (control.c2d and numpy roots), the two loop models at low frequency, and simulation.
"""

from __future__ import annotations

import functools
import inspect
import math

import control
import numpy as np
import pytest
from scipy import optimize

import dfa
from dfa.analysis.cycles import growth_threshold
from dfa.analysis.cycles import limit_cycles as _limit_cycles
from dfa.analysis.describing import quantizer_df
from dfa.analysis.loop import loop_response, nyquist_locus_response
from dfa.core.zohlag import zoh_lag_response
from dfa.errors import DFATypeError, DFAValueError
from dfa.model.wall import Wall, WallParams

#: These tests check completeness and residuals, not the wall-clock budget: a loaded machine (or a cold numba cache
#: compiling the amplifier's ZOH) must not turn a complete search into TIME_BUDGET.
limit_cycles = functools.partial(_limit_cycles, time_budget=600.0)

CONTROLLERS = [
    WallParams.of(damping=0.05),
    WallParams.of(damping=0.2, cutoff=0.05),
    WallParams.of(damping=0.05, cutoff=0.1, lag=0.3, delay=1),
    WallParams.of(lag=0.5),
]


def _residual(p, m, w, model, ctl):
    """|1 + D(M)·L(jω; M)| recomputed from the public loop_response (independent of the solver's inverse)."""
    return abs(1.0 + quantizer_df(m) * loop_response(p, w, m, model=model, wall=ctl))


@pytest.mark.parametrize("model", ["half-delay", "zoh", "pade"])
@pytest.mark.parametrize("params", [dfa.Params(5.0, 0.1, 0.3), dfa.Params(5.0, 0.4, 0.0), dfa.Params(20.0, 0.8, 0.9)])
@pytest.mark.parametrize("delay", [0, 1])
def test_eq36_spring_wall_fast_path_matches_the_general_path(model, params, delay, monkeypatch):
    """The spring's fast path (chosen from the wall) and the general wall path give the same cycles."""
    w = np.geomspace(1e-3, 3.0, 50)
    amp = None if params.sigma == 0 else np.full_like(w, 1.7)
    ref = limit_cycles(params, model=model, wall=WallParams.of(delay=delay))
    ref_loop = loop_response(params, w, amp, model=model, wall=WallParams.of(delay=delay))
    assert ref.wall == WallParams.of(delay=delay) and ref.to_dict()["wall"]["delay"] == delay
    monkeypatch.setattr(WallParams, "is_spring", property(lambda self: False))  # force the general path
    got = limit_cycles(params, model=model, wall=WallParams.of(delay=delay))
    assert len(got.cycles) == len(ref.cycles)
    for a, b in zip(got.cycles, ref.cycles, strict=True):
        assert (a.amplitude, a.frequency, a.stable) == (
            pytest.approx(b.amplitude, rel=1e-7),
            pytest.approx(b.frequency, rel=1e-7),
            b.stable,
        )
    assert (got.status, got.linear_stable) == (ref.status, ref.linear_stable)
    got_loop = loop_response(params, w, amp, model=model, wall=WallParams.of(delay=delay))
    np.testing.assert_allclose(got_loop, ref_loop, rtol=1e-9)


def test_eq36_spring_controller_nyquist_crossings_unchanged():
    p = dfa.Params(5.0, 0.4, 0.0)
    assert nyquist_locus_response(p, wall=WallParams.of()).crossings == nyquist_locus_response(p).crossings


@pytest.mark.parametrize("model", ["half-delay", "zoh", "pade"])
@pytest.mark.parametrize("ctl", CONTROLLERS)
@pytest.mark.parametrize("params", [dfa.Params(5.0, 0.1, 0.3), dfa.Params(5.0, 0.4, 0.0), dfa.Params(20.0, 0.3, 0.2)])
def test_eq36_residual_at_every_root_with_a_controller(model, ctl, params):
    res = limit_cycles(params, model=model, wall=ctl)
    assert res.complete, res.search
    assert res.wall == ctl
    for c in res.cycles:
        assert c.residual <= 1e-10
        assert _residual(params, c.amplitude, c.frequency, model, ctl) <= 1e-10


def test_eq36_controller_changes_the_cycles():
    """The damper, filter and lag are not ignored: the predicted cycles move (and the residual is still exact)."""
    p = dfa.Params(5.0, 0.1, 0.3)
    spring = limit_cycles(p).cycles
    for ctl in CONTROLLERS:
        got = limit_cycles(p, wall=ctl).cycles
        assert got and [c.amplitude for c in got] != [c.amplitude for c in spring]


@pytest.mark.parametrize("beq", [0.0, 0.1, 2.0, 50.0])
@pytest.mark.parametrize("lag", [1e-3, 0.3, 0.2, 4.0])
def test_zoh_lag_response_matches_control_c2d(beq, lag):
    """Exact ZOH of amplifier 1/(αs + 1) + device 1/(μs² + β_eq s) against python-control's c2d (incl. a = λ)."""
    mu = 2.0 if beq != 2.0 else 1.0 / lag * 0.0 + beq * lag  # a = β_eq/μ = 1/α for beq = 2: the coincident poles
    plant = control.tf([1.0], [lag, 1.0]) * control.tf([1.0], [mu, beq, 0.0])
    w = np.array([1e-3, 0.05, 0.5, 1.5, 3.1])
    ref = control.c2d(plant, 1.0, method="zoh")(np.exp(1j * w))
    np.testing.assert_allclose(zoh_lag_response(mu, beq, w, lag), ref, rtol=2e-9)


def test_zoh_lag_response_tends_to_the_spring_plant_as_the_lag_vanishes():
    from dfa.analysis.loop import zoh_pulse_response

    w = np.array([0.01, 0.5, 2.0])
    for lag in (1e-3, 1e-5):
        err = np.max(np.abs(zoh_lag_response(3.0, 0.2, w, lag) / zoh_pulse_response(3.0, 0.2, w) - 1.0))
        assert err < 5 * lag


# ---------------------------------------------------------------- M → ∞: neutral cycle = exact linear critical K
M_KG, B_NSM, T_S = 0.5, 2.0, 1e-3


@functools.lru_cache(maxsize=8)
def _sampled_plant(bandwidth):
    """control.c2d(amplifier + plant, T, 'zoh') in physical units: (numerator, denominator) in z."""
    tau = 0.0 if bandwidth is None else 1.0 / (2 * math.pi * bandwidth)
    plant = control.tf([1.0], [M_KG, B_NSM, 0.0])
    if tau:
        plant = control.tf([1.0], [tau, 1.0]) * plant
    pd = control.c2d(plant, T_S, method="zoh")
    return np.ravel(pd.num[0][0]), np.ravel(pd.den[0][0])


def _physical_closed_loop_radius(k, damping, delay, cutoff, bandwidth):
    """Spectral radius of the sampled loop with the controller, built independently in physical units:
    control.c2d(amplifier + plant, T, 'zoh') and H(z) = z^{−d}(K + B(1 − z^{−1})F(z)/T), numpy roots."""
    npl, dpl = _sampled_plant(bandwidth)
    # velocity path (1 − z^{−1})/T · F(z): F = (1 − a)/(z − a) or 1
    if cutoff is None:
        nv, dv = np.array([1.0, -1.0]) / T_S, np.array([1.0, 0.0])
    else:
        a = math.exp(-2 * math.pi * cutoff * T_S)
        nv, dv = (1 - a) * np.array([1.0, -1.0]) / T_S, np.polymul([1.0, 0.0], [1.0, -a])
    nh = np.polyadd(k * dv, damping * nv)  # K + B·v-path over the common denominator dv
    dh = np.polymul(dv, np.concatenate([[1.0], np.zeros(delay)]))
    poly = np.polyadd(np.polymul(dh, dpl), np.polymul(nh, npl))
    return float(np.max(np.abs(np.roots(poly))))


def _neutral_k_from_loop(damping, delay, cutoff, bandwidth, bracket):
    """K at which 1 + L(jω) = 0 for some ω (D = 1, σ = 0): the M → ∞ end of the harmonic balance (ZOH model)."""

    def gap(k):
        ctl = Wall.of(k, damping, delay, cutoff, bandwidth).params(T_S)
        p = dfa.Params(M_KG / (k * T_S**2), B_NSM / (k * T_S), 0.0)
        w = np.linspace(1e-3, math.pi - 1e-6, 4000)
        inv = 1.0 / loop_response(p, w, model="zoh", wall=ctl)
        idx = np.flatnonzero((np.sign(inv.imag[:-1]) != np.sign(inv.imag[1:])) & (inv.real[:-1] < 0))
        vals = []
        for i in idx:
            w0 = optimize.brentq(lambda x: (1.0 / loop_response(p, x, model="zoh", wall=ctl)).imag, w[i], w[i + 1])
            vals.append(-(1.0 / loop_response(p, w0, model="zoh", wall=ctl)).real - 1.0)
        return min(vals, key=abs)

    return optimize.brentq(gap, *bracket, xtol=1e-12, rtol=1e-13)


@pytest.mark.parametrize(
    "damping, delay, cutoff, bandwidth",
    [(0.0, 0, None, None), (0.5, 0, None, None), (0.5, 1, 100.0, None), (0.2, 1, None, 500.0), (1.0, 2, 50.0, 300.0)],
)
def test_eq36_neutral_cycle_at_infinite_amplitude_is_the_exact_linear_critical_k(damping, delay, cutoff, bandwidth):
    ks = np.geomspace(10.0, 1e6, 200)
    rho = np.array([_physical_closed_loop_radius(k, damping, delay, cutoff, bandwidth) for k in ks])
    i = int(np.argmax(rho >= 1.0))
    assert i > 0
    k_lin = optimize.brentq(
        lambda k: _physical_closed_loop_radius(k, damping, delay, cutoff, bandwidth) - 1.0, ks[i - 1], ks[i], xtol=1e-10
    )
    k_df = _neutral_k_from_loop(damping, delay, cutoff, bandwidth, (ks[i - 1], ks[i]))
    assert k_df == pytest.approx(k_lin, rel=1e-7)
    # and limit_cycles' linear verdict with the controller agrees on either side
    for k, stable in ((0.98 * k_lin, True), (1.02 * k_lin, False)):
        ctl = Wall.of(k, damping, delay, cutoff, bandwidth).params(T_S)
        p = dfa.Params(M_KG / (k * T_S**2), B_NSM / (k * T_S), 0.1)
        assert limit_cycles(p, max_amplitude=50.0, wall=ctl).linear_stable is stable


@pytest.mark.parametrize("ctl", CONTROLLERS)
def test_eq36_half_delay_and_zoh_models_agree_as_frequency_tends_to_zero(ctl):
    p = dfa.Params(5.0, 0.3, 0.0)
    errs = []
    for w in (1e-2, 1e-3, 1e-4):
        hd = loop_response(p, w, model="half-delay", wall=ctl)
        zo = loop_response(p, w, model="zoh", wall=ctl)
        errs.append(abs(zo / hd - 1.0))
    assert errs[2] < 1e-6 and errs[2] < errs[1] < errs[0]


def test_controller_growth_threshold_and_json():
    ctl = CONTROLLERS[2]
    g = growth_threshold(dfa.Params(5.0, 0.1, 0.3), wall=ctl)
    assert g.amplitude is not None and g.result.wall == ctl
    assert g.to_dict()["status"] == "ok"
    d = limit_cycles(dfa.Params(5.0, 0.1, 0.3), wall=ctl).to_dict()
    assert d["wall"] == ctl.to_dict() and d["delay"] == ctl.delay


def test_controller_bad_input():
    p = dfa.Params(5.0, 0.1, 0.3)
    with pytest.raises(DFATypeError, match="wall"):
        limit_cycles(p, wall=Wall.of(300.0))  # physical: its groups need the period
    with pytest.raises(TypeError, match="delay"):
        limit_cycles(p, delay=2, wall=WallParams.of(delay=1))  # one place for the delay: the wall
    with pytest.raises(TypeError, match="delay"):
        loop_response(p, 0.5, 1.0, delay=2)
    assert limit_cycles(p, wall=WallParams.of(delay=1)).delay == 1


# ---------------------------------------------------------------- against the exact simulator (h-csim)
def _simulate_with_controller():
    from dfa.analysis import simulation

    assert "loop" in inspect.signature(simulation.simulate).parameters  # the loop holds the wall
    return simulation.simulate


@pytest.mark.parametrize("ctl", [CONTROLLERS[0], CONTROLLERS[2]])
def test_eq36_controller_growth_threshold_brackets_the_simulated_critical_speed(ctl):
    """Below the smallest unstable cycle's speed the simulation does not diverge; well above it, it does."""
    simulate = _simulate_with_controller()
    p = dfa.Params(5.0, 0.1, 0.3)
    g = growth_threshold(p, model="zoh", wall=ctl)
    assert g.amplitude is not None and g.grows_above
    lo = simulate(p.mu, p.beta, p.sigma, 0.5 * g.xi_dot, 20_000, record=False, wall=ctl)
    hi = simulate(p.mu, p.beta, p.sigma, 3.0 * g.xi_dot_high, 20_000, record=False, wall=ctl)
    assert lo.outcome != "unstable" and hi.outcome == "unstable"


def test_eq42_45_closed_forms_refuse_a_controller_they_do_not_hold_for():
    from dfa.analysis.cycles import large_cycle_closed_form, small_cycle_closed_form, small_cycle_closed_forms

    assert small_cycle_closed_form(5.0, 0.1, 0.3, wall=WallParams.of()) == small_cycle_closed_form(5.0, 0.1, 0.3)
    for ctl in [*CONTROLLERS, WallParams.of(delay=1)]:
        with pytest.raises(DFAValueError, match="closed forms .eq. 42-45. hold for the pure spring"):
            large_cycle_closed_form(5.0, 0.1, 0.3, wall=ctl)
        with pytest.raises(DFAValueError, match="limit_cycles"):
            small_cycle_closed_forms([5.0], [0.1], [0.3], wall=ctl)
    with pytest.raises(DFATypeError, match="wall"):
        small_cycle_closed_form(5.0, 0.1, 0.3, wall="spring")


@pytest.mark.parametrize("ctl", CONTROLLERS)
def test_eq36_controller_describing_small_reproduces_the_exact_small_cycle(ctl):
    """describing='small' (D = 2/(πM), exact for M < 1) gives the same small cycles as the exact D."""
    p = dfa.Params(5.0, 0.1, 0.3)
    exact = [c for c in limit_cycles(p, wall=ctl).cycles if c.amplitude < 1.0]
    small = [c for c in limit_cycles(p, describing="small", wall=ctl).cycles if c.amplitude < 1.0]
    assert [c.amplitude for c in small] == pytest.approx([c.amplitude for c in exact], rel=1e-9)


@pytest.mark.parametrize("mu", [0.5, 5.0, 100.0])
def test_eq36_zoh_phase_condition_has_at_most_one_crossing_per_frequency_with_a_controller(mu):
    """The solver's premise for the exact ZOH model (one β* per ω with U < 0), checked on its own β grid."""
    from dfa.analysis.cycles.characteristic import W_GRID, inv_loop

    bgrid = np.concatenate([[0.0], np.geomspace(1e-9, 1e5, 400)])
    for ctl in [
        *CONTROLLERS,
        WallParams.of(damping=2.0, cutoff=0.05),
        WallParams.of(damping=1.0, lag=1.0, delay=2),
    ]:
        c = inv_loop(mu, bgrid[None, :], W_GRID[:, None], "zoh", ctl.delay, 0, ctl)
        sc = (np.sign(c.imag[:, :-1]) != np.sign(c.imag[:, 1:])) & (c.real[:, :-1] < 0) & (c.real[:, 1:] < 0)
        assert sc.sum(axis=1).max() <= 1


@pytest.mark.parametrize("ctl", CONTROLLERS)
@pytest.mark.parametrize("sigma, amp", [(0.0, None), (0.3, 0.7), (0.3, 4.0)])
def test_eq36_zoh_loop_equals_python_control_c2d_with_the_controller(ctl, sigma, amp):
    """L = z^{−d}C(z)·c2d(1/(αs + 1)·1/(μs² + β_eq s)) evaluated independently (β_eq of eq. 40)."""
    p = dfa.Params(3.0, 0.2, sigma)
    w = np.array([0.02, 0.3, 1.0, 2.5])
    beq = p.beta + (0.0 if amp is None else 4 * sigma / (math.pi * amp * w))
    ref = []
    for wi, bi in zip(w, np.broadcast_to(beq, w.shape), strict=True):
        plant = control.tf([1.0], [p.mu, bi, 0.0])
        if ctl.lag:
            plant = control.tf([1.0], [ctl.lag, 1.0]) * plant
        z = np.exp(1j * wi)
        f = 1.0 if ctl.cutoff is None else (1 - ctl.filter_pole) / (z - ctl.filter_pole)
        h = z ** (-ctl.delay) * (1.0 + ctl.damping * (1.0 - 1.0 / z) * f)
        ref.append(h * control.c2d(plant, 1.0, method="zoh")(z))
    amps = None if amp is None else np.full_like(w, amp)
    np.testing.assert_allclose(loop_response(p, w, amps, model="zoh", wall=ctl), ref, rtol=1e-9)


@pytest.mark.parametrize("ctl", CONTROLLERS)
def test_eq36_half_delay_loop_is_the_stated_product(ctl):
    """L = e^{−jω(d + ½)}·C(e^{jω})/(jωα + 1)/(μ(jω)² + jωβ_eq), written out."""
    p = dfa.Params(3.0, 0.2, 0.3)
    w = np.array([0.02, 0.3, 1.0, 2.5])
    s, z = 1j * w, np.exp(1j * w)
    f = 1.0 if ctl.cutoff is None else (1 - ctl.filter_pole) / (z - ctl.filter_pole)
    c = 1.0 + ctl.damping * (1.0 - 1.0 / z) * f
    beq = p.beta + 4 * p.sigma / (math.pi * 1.5 * w)
    ref = np.exp(-s * (ctl.delay + 0.5)) * c / (ctl.lag * s + 1.0) / (p.mu * s * s + beq * s)
    np.testing.assert_allclose(loop_response(p, w, 1.5, wall=ctl), ref, rtol=1e-12)


def test_eq36_controller_stable_cycle_matches_simulated_chatter():
    """Damper + filter + delay + lag: the predicted stable cycle (M = 0.642, period 16.1 samples) against the
    simulated chatter, which locks onto whole-sample periods (16 or 18 samples by initial speed, amplitudes
    0.51 or 0.64 ticks when measured with h-csim's simulator): frequency within 12 %, amplitude within 25 %."""
    simulate = _simulate_with_controller()
    p, ctl = dfa.Params(5.0, 0.1, 0.3), CONTROLLERS[2]
    (cyc,) = [c for c in limit_cycles(p, model="zoh", wall=ctl).cycles if c.stable]
    for v in (0.1, 0.2, 0.3):
        r = simulate(p.mu, p.beta, p.sigma, v, 20_000, record=False, wall=ctl)
        assert r.outcome == "chatter"
        assert r.frequency == pytest.approx(cyc.frequency, rel=0.12)
        assert r.amplitude == pytest.approx(cyc.amplitude, rel=0.25)
