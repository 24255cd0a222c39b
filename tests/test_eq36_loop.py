"""The linearised loop of paper Fig. 6 / eq. 36-40: half-sample delay, Padé and exact ZOH models."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from result_json import assert_json_from_fields

import dfa
from dfa.analysis.loop import (
    device_tf,
    device_zoh_tf,
    equivalent_damping,
    hold_delay_tf,
    loop_response,
    loop_system,
    nyquist_locus_response,
    zoh_pulse_response,
)
from dfa.model.wall import WallParams

W = np.linspace(0.01, 3.1, 300)


def test_eq40_device_transfer_function_and_equivalent_damping():
    p = dfa.Params(4.0, 0.2, 0.6)
    beq = equivalent_damping(p, 1.5, 0.3)
    assert beq == pytest.approx(0.2 + 4 * 0.6 / (math.pi * 1.5 * 0.3))
    G = device_tf(p, 1.5, 0.3)
    np.testing.assert_allclose(G.den[0][0], [4.0, beq, 0.0])
    with pytest.raises(dfa.DFAValueError, match="amplitude"):
        equivalent_damping(p)


@given(mu=st.floats(0.05, 500), beta=st.one_of(st.just(0.0), st.floats(1e-6, 50)), w=st.floats(0.01, math.pi))
def test_zoh_closed_form_equals_control_c2d(mu, beta, w):
    gd = device_zoh_tf(dfa.Params(mu, beta, 0.0))
    z = np.exp(1j * w)
    ref = complex(gd(z))
    # absolute floor: at ω = π and β = 0 the response is exactly 0 and c2d leaves a 1e-16 residue
    assert abs(zoh_pulse_response(mu, beta, w) - ref) <= 1e-9 * abs(ref) + 1e-13 / mu


@pytest.mark.parametrize("mu, beta", [(1.0, 0.3), (5.0, 0.1), (100.0, 0.01)])
def test_half_delay_and_exact_zoh_agree_at_low_frequency_and_differ_near_pi(mu, beta):
    p = dfa.Params(mu, beta, 0.0)
    w = np.array([1e-3, 1e-2, 0.05])
    rel = np.abs(loop_response(p, w) / loop_response(p, w, model="zoh") - 1)
    assert np.all(rel < 1e-2 * np.maximum(w / 0.05, 0.01) + 1e-6)
    assert rel[0] < rel[1] < rel[2]  # the discrepancy grows with ω (aliasing)
    # at the Nyquist frequency the sampled response is real; the half-delay model has a phase below −π
    lz = loop_response(p, math.pi, model="zoh")
    assert abs(lz.imag) < 1e-8 * abs(lz)  # e^{jπ} itself carries a 1e-16 imaginary part
    lh = loop_response(p, math.pi)
    assert np.angle(lh) > 0  # wrapped: phase below −π


@pytest.mark.parametrize("mu", [0.5, 1.0, 5.0, 100.0])
def test_exact_zoh_linear_loop_is_marginal_at_the_gil_bound(mu):
    """Linear loop (no quantizer, σ = 0): 1 + L = 0 exactly at β = β_crit(μ) of Gil et al."""
    b = dfa.gil_beta_critical(mu)
    w = np.linspace(1e-3, math.pi - 1e-9, 200001)

    def crossover_gain(beta):
        L = loop_response(dfa.Params(mu, beta, 0.0), w, model="zoh")
        i = np.where((np.sign(L.imag[:-1]) != np.sign(L.imag[1:])) & (L.real[:-1] < -0.1))[0]
        return -L.real[i].min()

    assert crossover_gain(b) == pytest.approx(1.0, abs=1e-4)
    assert crossover_gain(b * 1.01) < 1.0 < crossover_gain(b * 0.99)


def test_half_delay_linear_boundary_is_close_to_gil_for_large_mu():
    # half-delay: β = μω tan(ω/2) with μω² = cos(ω/2)  ->  β → ½ like Gil's bound
    from scipy.optimize import brentq

    for mu, tol in [(100.0, 1e-3), (5.0, 2e-2)]:
        w = brentq(lambda x, mu=mu: mu * x * x - math.cos(x / 2), 1e-6, math.pi)
        assert mu * w * math.tan(w / 2) == pytest.approx(dfa.gil_beta_critical(mu), abs=tol)


def test_pade_converges_to_half_delay():
    p = dfa.Params(5.0, 0.2, 0.0)
    ref = loop_response(p, W)
    errs = [np.max(np.abs(loop_response(p, W, model="pade", pade_order=n) / ref - 1)) for n in (1, 2, 4, 6)]
    assert errs[0] > errs[1] > errs[2] > errs[3] and errs[3] < 1e-6
    # and the rational system from python-control has the same response
    H = loop_system(p, model="pade", pade_order=4)
    np.testing.assert_allclose(H(1j * W), loop_response(p, W, model="pade", pade_order=4), rtol=1e-10)


@pytest.mark.parametrize("model", ["half-delay", "pade", "zoh"])
def test_computational_delay_adds_whole_samples(model):
    p = dfa.Params(5.0, 0.2, 0.3)
    amp = np.full_like(W, 2.0)
    l0 = loop_response(p, W, amp, model=model, pade_order=8)
    l2 = loop_response(p, W, amp, model=model, pade_order=8, wall=WallParams.of(delay=2))
    tol = 1e-12 if model != "pade" else 1e-2
    np.testing.assert_allclose(l2, l0 * np.exp(-2j * W), rtol=tol)


def test_zoh_discrete_system_with_delay_matches_response():
    p = dfa.Params(5.0, 0.2, 0.0)
    H = loop_system(p, model="zoh", wall=WallParams.of(delay=1))
    assert H.dt == 1.0
    np.testing.assert_allclose(
        H(np.exp(1j * W)), loop_response(p, W, model="zoh", wall=WallParams.of(delay=1)), rtol=1e-10
    )


def test_fig6_nyquist_crossings_satisfy_harmonic_balance():
    p = dfa.Params(5.0, 0.4, 0.0)
    r = nyquist_locus_response(p)
    assert len(r.crossings) == 2 and r.status == "ok"
    for m, w, _pt in r.crossings:
        assert abs(1 + dfa.analysis.describing.quantizer_df(m) * loop_response(p, w)) < 1e-10
    assert np.all(r.locus.imag == 0) and np.all(r.locus.real < 0)
    s = nyquist_locus_response(dfa.Params(5.0, 0.4, 0.3), amplitudes=[0.5, 2.0])
    assert s.curves.shape == (2, s.omega.size) and s.crossings == ()
    with pytest.raises(dfa.DFAValueError, match="amplitudes"):
        nyquist_locus_response(dfa.Params(5.0, 0.4, 0.3))


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(model="exact"), "model"),
        (dict(model="pade", pade_order=0), "pade_order"),
    ],
)
def test_loop_bad_input(kwargs, needle):
    with pytest.raises(dfa.DFAValueError, match=needle):
        loop_response(dfa.Params(1.0, 0.1, 0.0), 0.5, **kwargs)


@pytest.mark.parametrize("delay", [-1, 0.5])
def test_loop_bad_delay_is_refused_by_the_wall(delay):
    """The delay lives in the wall: a bad one is refused where the wall is built, naming ``delay``."""
    with pytest.raises((dfa.DFAValueError, dfa.DFATypeError), match="delay"):
        loop_response(dfa.Params(1.0, 0.1, 0.0), 0.5, wall=WallParams.of(delay=delay))
    with pytest.raises(dfa.DFATypeError, match="wall"):
        loop_response(dfa.Params(1.0, 0.1, 0.0), 0.5, wall=delay)


def test_loop_rejects_bad_frequency_and_params_type():
    with pytest.raises(dfa.DFAValueError, match="omega"):
        loop_response(dfa.Params(1.0, 0.1, 0.0), [0.5, -1.0])
    with pytest.raises(dfa.DFAValueError, match="omega"):
        loop_response(dfa.Params(1.0, 0.1, 0.0), math.nan)
    with pytest.raises(dfa.DFATypeError, match="params"):
        loop_response((1.0, 0.1, 0.0), 0.5)
    with pytest.raises(dfa.DFAValueError, match="pade_order"):
        hold_delay_tf(0, 0)


@pytest.mark.parametrize(
    "params, kwargs",
    [
        (dfa.Params(5.0, 0.4, 0.0), {}),
        (dfa.Params(5.0, 0.4, 0.0), dict(model="zoh")),
        (dfa.Params(20.0, 0.49, 0.0), {}),
        (dfa.Params(5.0, 0.4, 0.0), dict(model="pade", pade_order=6)),
    ],
)
def test_fig6_nyquist_markers_are_the_solvers_roots(params, kwargs):
    """σ = 0: one harmonic balance; the Nyquist crossings are limit_cycles' roots (residual <= 1e-10), not a grid interpolation."""
    r = nyquist_locus_response(params, **kwargs)
    cyc = dfa.limit_cycles(params, max_amplitude=float(r.locus_amplitude.max()), **kwargs).cycles
    assert r.status == "ok" and len(r.crossings) == len(cyc) > 0
    for (m, w, pt), c in zip(r.crossings, cyc, strict=True):
        assert abs(m - c.amplitude) <= 1e-10 * c.amplitude and abs(w - c.frequency) <= 1e-10 * c.frequency
        assert c.residual <= 1e-10
        assert abs(pt + 1.0 / dfa.analysis.describing.quantizer_df(m)) <= 1e-12  # the marker sits on the locus −1/D(M)
        # and on the curve: L(jω) at the root is the same point to 1e-10
        assert abs(loop_response(params, w, **kwargs) - pt) <= 1e-10 * abs(pt)


def test_nyquist_locus_response_json_from_its_fields():
    """NyquistLocusResponse writes the Result base's JSON: fields (params as μ, β, σ), json_properties, message."""
    from dfa.model.device import Params

    for p, wall in ((Params(5.0, 0.1, 0.0), None), (Params(5.0, 0.1, 0.5), WallParams.of(damping=0.2, delay=1))):
        r = nyquist_locus_response(p, amplitudes=[1.0, 3.0], omega=np.geomspace(0.01, 3.0, 20), wall=wall)
        d = assert_json_from_fields(r)
        assert (d["mu"], d["beta"], d["sigma"]) == (p.mu, p.beta, p.sigma)
        assert d["status_message"] == r.status.message
        assert (d["search"] is None) == (p.sigma > 0)  # the solver's evidence where it ran (σ = 0)
        assert all(set(c) == {"amplitude", "frequency", "point"} for c in d["crossings"])


@pytest.mark.parametrize("model", ["half-delay", "zoh"])
def test_fig6_nyquist_cycle_marks_are_the_loop_at_each_cycle(model):
    """The analysis places each cycle given (``cycles=``) at L(jω; M) of its own loop (model, wall), as
    ``loop_response`` evaluates it, so that the figure draws the marks without an analysis; without cycles there are
    no marks and no ``cycle_marks`` in the JSON."""
    from dfa.analysis.cycles import limit_cycles

    p, wall = dfa.Params(2.0, 0.4, 0.1), WallParams.of(damping=0.02)  # a controller: cycles off the spring's curve
    res = limit_cycles(p, model=model, wall=wall)
    assert res.cycles
    amps = [c.amplitude for c in res.cycles]
    r = nyquist_locus_response(p, amplitudes=amps, model=model, wall=wall, cycles=res)
    assert [(m.amplitude, m.frequency, m.stable) for m in r.cycle_marks] == [
        (c.amplitude, c.frequency, c.stable) for c in res.cycles
    ]
    for mark in r.cycle_marks:
        expected = complex(loop_response(p, mark.frequency, mark.amplitude, model=model, wall=wall))
        assert abs(mark.point - expected) <= 1e-12 * abs(expected)
    d = assert_json_from_fields(r)
    assert all(set(m) == {"amplitude", "frequency", "stable", "point"} for m in d["cycle_marks"])
    bare = nyquist_locus_response(p, amplitudes=amps, model=model, wall=wall)
    assert bare.cycle_marks is None and "cycle_marks" not in bare.to_dict()
    with pytest.raises(dfa.DFATypeError, match="cycles"):
        nyquist_locus_response(p, amplitudes=amps, model=model, wall=wall, cycles=res.cycles)
