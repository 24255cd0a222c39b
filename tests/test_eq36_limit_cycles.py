"""Limit-cycle solver: eq. 36 with the exact eq. 41, closed forms eq. 42-45, Loeb stability."""

import math
import warnings

import control
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import fsolve

import dfa
from dfa.analysis.cycles import (
    growth_threshold,
    large_cycle_closed_form,
    large_cycle_frequency,
    limit_cycles,
    small_cycle_closed_form,
)
from dfa.analysis.describing import quantizer_df
from dfa.analysis.loop import loop_response, loop_system
from dfa.analysis.nonlinearities import QuantizerNonlinearity
from dfa.model.wall import WallParams

params_st = st.builds(dfa.Params, st.floats(0.5, 200.0), st.floats(0.0, 0.6), st.floats(0.0, 2.5))


def residual(p, m, w, model="half-delay", delay=0, pade_order=4):
    return abs(
        1
        + quantizer_df(m) * loop_response(p, w, m, model=model, pade_order=pade_order, wall=WallParams.of(delay=delay))
    )


@settings(max_examples=60)
@given(params_st, st.sampled_from(["half-delay", "pade", "zoh"]), st.integers(0, 2))
def test_eq36_every_root_has_residual_below_1e10(p, model, delay):
    res = limit_cycles(p, model=model, wall=WallParams.of(delay=delay))
    for c in res.cycles:
        assert residual(p, c.amplitude, c.frequency, model, delay) <= 1e-10
        assert c.residual <= 1e-10
        assert 0 < c.frequency < math.pi


@pytest.mark.parametrize("model", ["half-delay", "zoh", "pade"])
@pytest.mark.parametrize(
    "p", [dfa.Params(5, 0.1, 0.3), dfa.Params(2, 0.4, 0.1), dfa.Params(155.17, 0.00207, 2.03), dfa.Params(5, 0.4, 0.0)]
)
def test_eq36_roots_agree_with_independent_2d_newton(p, model):
    res = limit_cycles(p, model=model)
    assert res.cycles
    for c in res.cycles:

        def f(x):
            z = 1 + quantizer_df(x[0]) * loop_response(p, x[1], x[0], model=model)
            return [z.real, z.imag]

        for k in (1 + 1e-4, 1 - 1e-4):
            m, w = fsolve(f, [c.amplitude * k, c.frequency * (2 - k)], xtol=1e-13)
            assert m == pytest.approx(c.amplitude, rel=1e-8) and w == pytest.approx(c.frequency, rel=1e-8)


@pytest.mark.parametrize("mu, omega", [(5.0, 0.44175), (100.0, 0.099938)])
def test_eq44_large_family_frequency(mu, omega):
    assert large_cycle_frequency(mu) == pytest.approx(omega, abs=6e-6)


@settings(max_examples=25)
@given(st.floats(0.5, 300.0), st.floats(0.0, 0.45), st.floats(0.05, 3.0))
def test_eq45_solver_with_unity_df_reproduces_closed_form(mu, beta, sigma):
    cf = large_cycle_closed_form(mu, beta, sigma)
    res = limit_cycles(dfa.Params(mu, beta, sigma), describing="unity")
    if cf is None or cf[0] > 1e4:
        return
    big = [c for c in res.cycles if abs(c.frequency - cf[1]) < 1e-6]
    assert len(big) == 1
    assert big[0].amplitude == pytest.approx(cf[0], rel=1e-12) and big[0].frequency == pytest.approx(cf[1], rel=1e-12)
    assert not big[0].stable  # eq. 45 cycles are unstable


@settings(max_examples=25)
@given(st.floats(0.5, 300.0), st.floats(0.0, 2.0), st.floats(0.01, 0.49))
def test_eq43_solver_with_small_df_reproduces_closed_form(mu, beta, sigma):
    cf = small_cycle_closed_form(mu, beta, sigma)
    res = limit_cycles(dfa.Params(mu, beta, sigma), describing="small")
    assert cf is not None
    match = [c for c in res.cycles if abs(c.frequency - cf[1]) < 1e-6 * cf[1]]
    assert len(match) == 1
    assert match[0].amplitude == pytest.approx(cf[0], rel=1e-12) and match[0].frequency == pytest.approx(
        cf[1], rel=1e-12
    )
    assert match[0].stable  # eq. 42-43 cycles are stable
    # eq. 42: (2/(πM)) cos(ω/2) = μω²
    m, w = cf
    assert 2 / (math.pi * m) * math.cos(w / 2) == pytest.approx(mu * w * w, rel=1e-12)


@settings(max_examples=25)
@given(params_st)
def test_eq36_small_cycles_stable_large_threshold_unstable_and_alternating(p):
    res = limit_cycles(p)
    for c in res.cycles:
        if c.family == "small":
            assert c.stable
    large = [c for c in res.cycles if c.family == "large"]
    if large:
        assert not large[0].stable  # the smallest large cycle is the growth threshold
    # along the single branch of the d = 0 half-delay model, stability alternates with amplitude
    flags = [c.stable for c in res.cycles]
    assert all(a != b for a, b in zip(flags, flags[1:], strict=False))


def test_eq36_exact_df_adds_cycles_the_approximations_miss():
    p = dfa.Params(2.0, 0.4, 0.1)
    exact = limit_cycles(p).cycles
    assert len(exact) > 2 and sum(c.stable for c in exact if c.family == "large") >= 1
    # cycles in 1 < M < 2, where D exceeds 1
    assert any(1 < c.amplitude < 2 for c in exact)


def test_eq36_sigma_zero_and_beta_zero():
    assert limit_cycles(dfa.Params(5.0, 0.0, 0.0)).cycles == ()
    nb = limit_cycles(dfa.Params(5.0, 0.0, 0.3))
    assert nb.cycles and all(c.residual < 1e-10 for c in nb.cycles)
    ns = limit_cycles(dfa.Params(5.0, 0.4, 0.0))
    assert [round(c.amplitude, 4) for c in ns.cycles] == [0.7905, 1.0098]
    assert len({round(c.frequency, 12) for c in ns.cycles}) == 1  # σ = 0: one phase-crossover frequency


@pytest.mark.parametrize("model", ["half-delay", "zoh"])
def test_eq36_computational_delay(model):
    p = dfa.Params(20.0, 0.8, 0.9)
    res = limit_cycles(p, model=model, wall=WallParams.of(delay=1))
    assert res.cycles
    for c in res.cycles:
        assert residual(p, c.amplitude, c.frequency, model, delay=1) <= 1e-10
    # with one more sample of delay the linear bound moves from β ≈ ½ to β ≈ 3/2 (Diolaiti 2006)
    assert not limit_cycles(p, model=model).cycles or limit_cycles(p, model=model).cycles != res.cycles


def test_python_control_describing_function_response_agrees_with_solver():
    p = dfa.Params(5.0, 0.4, 0.0)
    H = loop_system(p, model="pade", pade_order=6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        resp = control.describing_function_response(
            H, QuantizerNonlinearity(), np.linspace(0.3, 3, 400), omega=np.geomspace(1e-2, np.pi, 3000)
        )
    ours = limit_cycles(p, model="pade", pade_order=6).cycles
    assert len(resp.intersections) == len(ours)
    for (a, w), c in zip(sorted(resp.intersections), ours, strict=False):
        assert a == pytest.approx(c.amplitude, rel=1e-4) and w == pytest.approx(c.frequency, rel=1e-4)


@pytest.mark.parametrize("mu, beta", [(20.0, 0.49), (100.0, 0.495)])
def test_python_control_finds_no_root_we_miss_with_its_default_grid(mu, beta):
    """Many close roots (β near the linear bound): python-control's every intersection is one of ours, one to one."""
    p = dfa.Params(mu, beta, 0.0)
    H = loop_system(p, model="pade", pade_order=6)
    amps = np.linspace(0.05, 10.0, 400)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        resp = control.describing_function_response(H, QuantizerNonlinearity(), amps)
    ours = [c for c in limit_cycles(p, model="pade", pade_order=6).cycles if c.amplitude <= amps[-1]]
    pc = sorted(resp.intersections)
    assert len(pc) == len(ours) >= 14
    for (a, w), c in zip(pc, ours, strict=False):  # sorted one-to-one; python-control's roots are grid-limited (~1e-3)
        assert a == pytest.approx(c.amplitude, rel=1e-2) and w == pytest.approx(c.frequency, rel=1e-3)
        assert c.residual <= 1e-13 < residual(p, a, w, model="pade", pade_order=6)


def test_growth_threshold_physical_units():
    entry = dfa.get_device("Delta")
    dev = entry.device
    p = dev.params(entry.stiffness)
    g = growth_threshold(p, dev)
    assert g.amplitude == pytest.approx(limit_cycles(p).unstable_cycles[0].amplitude)
    assert g.xi_dot == pytest.approx(g.amplitude * g.frequency)
    assert g.position == pytest.approx(g.amplitude * dev.resolution)
    assert g.velocity == pytest.approx(dev.velocity(g.xi_dot))
    none = growth_threshold(dfa.Params(5.0, 0.8, 1.0))
    assert none.amplitude is None and "no unstable" in none.status.message


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(model="exact"), "model"),
        (dict(max_amplitude=0), "max_amplitude"),
        (dict(describing="approx"), "describing"),
    ],
)
def test_limit_cycles_bad_input(kwargs, needle):
    with pytest.raises(dfa.DFAValueError, match=needle):
        limit_cycles(dfa.Params(5.0, 0.1, 0.3), **kwargs)
    with pytest.raises(dfa.DFATypeError):
        limit_cycles((5.0, 0.1, 0.3))
    with pytest.raises(dfa.DFATypeError, match="wall"):
        limit_cycles(dfa.Params(5.0, 0.1, 0.3), wall=1)
    with pytest.raises(dfa.DFAValueError, match="delay"):
        limit_cycles(dfa.Params(5.0, 0.1, 0.3), wall=WallParams.of(delay=-1))


# ------------------------------------------- the solver's fast loop inverse (dfa.analysis.cycles)
@settings(max_examples=60)
@given(
    st.floats(0.2, 300.0),
    st.floats(0.0, 3.0),
    st.floats(1e-3, 3.1),
    st.sampled_from(["half-delay", "pade", "zoh"]),
    st.integers(0, 2),
)
def test_eq36_solver_loop_inverse_scalar_and_vector_paths_equal_loop_response(mu, beq, w, model, delay):
    """The solver's 1/L (plain-complex scalar path, numpy path, Padé as an all-pass phase lead) is loop_response's."""
    from dfa.analysis.cycles import inv_loop

    p = dfa.Params(mu, beq, 0.0)
    ref = 1.0 / complex(loop_response(p, w, model=model, pade_order=6, wall=WallParams.of(delay=delay)))
    scalar = inv_loop(mu, beq, w, model, delay, 6)
    vector = inv_loop(mu, np.array([beq, beq]), np.array([w, w]), model, delay, 6)
    assert isinstance(scalar, complex)
    tol = 1e-12 * abs(ref) + 1e-300
    assert abs(scalar - ref) <= tol and np.all(np.abs(vector - ref) <= tol)


@pytest.mark.parametrize("model, delay", [("half-delay", 0), ("pade", 0), ("pade", 1), ("zoh", 0), ("zoh", 1)])
def test_eq36_phase_curve_beta_star_puts_the_loop_on_the_negative_real_axis(model, delay):
    """β*(ω) (closed form μω tan φ for half-delay and Padé, numeric for ZOH) gives V = 0 with U < 0 (eq. 36 phase condition)."""
    from dfa.analysis.cycles import HarmonicLoop, phase_beta
    from dfa.analysis.cycles.characteristic import W_GRID as _W_GRID

    mu = 7.0
    lp = HarmonicLoop(dfa.Params(mu, 0.0, 0.0), model, delay, 4)
    for w in (_W_GRID, np.array(_W_GRID[::97])):  # the cached grid and a fresh array
        bs = phase_beta(lp, w)
        ok = np.isfinite(bs)
        assert ok.sum() > 100 if w is _W_GRID else ok.sum() > 3
        inv = np.array(
            [
                1.0 / complex(loop_response(dfa.Params(mu, b, 0.0), x, model=model, wall=WallParams.of(delay=delay)))
                for x, b in zip(w[ok], bs[ok], strict=False)
            ]
        )
        assert np.all(np.abs(inv.imag) <= 1e-9 * np.abs(inv)) and np.all(inv.real < 0)


# ------------------------------------------------------------- JSON of the results: the dfa.results.base.Result base
#: Keys of the former hand-written to_dict of each result (before they moved onto the Result base).
CYCLE_JSON_KEYS = {"amplitude", "frequency", "period", "stable", "family", "loeb", "residual", "few_samples"}
SEARCH_JSON_KEYS = {
    "wall", "cycles", "mu", "beta", "sigma", "model", "delay", "complete", "max_amplitude", "status",
    "status_message", "linear_stable", "linear_model", "search_bound", "caveat",
}  # fmt: skip
GROWTH_JSON_KEYS = {
    "amplitude", "frequency", "xi_dot", "position", "velocity", "band", "unstable_count", "grows_above", "complete",
    "linear_stable", "linear_model", "status", "status_message", "caveat",
}  # fmt: skip


def test_limit_cycle_json_is_the_result_base():
    """LimitCycle.to_dict is the Result base's: its fields and the period, exactly the former keys."""
    from result_json import assert_json_from_fields

    cycles = limit_cycles(dfa.Params(5.0, 0.48, 0.0201)).cycles
    assert len(cycles) >= 2
    for c in cycles:
        d = assert_json_from_fields(c)
        assert set(d) == CYCLE_JSON_KEYS and d["period"] == c.period == 2 * math.pi / c.frequency
        for key in CYCLE_JSON_KEYS - {"period"}:
            assert d[key] == getattr(c, key)


@pytest.mark.parametrize(
    "params, kwargs",
    [
        (dfa.Params(5.0, 0.48, 0.0201), {}),  # a cluster, with the sub-tick caveat
        (dfa.Params(5.0, 0.1, 0.3), dict(max_amplitude=1.5)),  # incomplete: no caveat, its null explained
        (dfa.Params(5.0, 0.1, 0.3), dict(model="zoh", wall=WallParams.of(damping=0.1, cutoff=0.3, lag=0.2))),
    ],
)
def test_limit_cycle_result_json_is_the_result_base(params, kwargs):
    """LimitCycleResult.to_dict is the Result base's: the fields but params (written as mu, beta, sigma; new:
    describing, pade_order, detail), delay, linear_model, caveat; every former key there with its value."""
    from result_json import assert_json_from_fields

    from dfa.jsonable import to_jsonable

    r = limit_cycles(params, **kwargs)
    d = assert_json_from_fields(r)
    assert set(d) >= SEARCH_JSON_KEYS | {"describing", "pade_order", "search"} and "params" not in d
    assert (d["mu"], d["beta"], d["sigma"]) == (params.mu, params.beta, params.sigma)
    assert d["wall"] == to_jsonable(r.wall) and d["cycles"] == [c.to_dict() for c in r.cycles]
    for key in ("model", "delay", "complete", "max_amplitude", "pade_order", "describing", "linear_stable"):
        assert d[key] == getattr(r, key)
    assert (d["status"], d["status_message"]) == (r.status.value, r.status.message)
    assert d["search"] == to_jsonable(r.search) and d["search"]["requested"] >= r.max_amplitude
    assert (d["linear_model"], d["search_bound"]) == ("zoh", r.search_bound)
    assert d["caveat"] == to_jsonable(r.caveat) and (r.caveat is not None or "/caveat" in d["null_reasons"])


@pytest.mark.parametrize(
    "params, device",
    [
        (dfa.Params(5.0, 0.48, 0.0201), None),  # a band of several unstable cycles
        (dfa.Params(5.0, 0.8, 1.0), None),  # no unstable cycle
        ("delta", "delta"),  # one threshold, in physical units
    ],
)
def test_growth_threshold_json_is_the_result_base(params, device):
    """GrowthThreshold.to_dict is the Result base's: the fields but the inner search (new: the band's top at the top
    level, each null with its reason), band, complete, linear_stable, linear_model, caveat; every former key there
    with its value."""
    from result_json import assert_json_from_fields

    from dfa.jsonable import to_jsonable

    if params == "delta":
        entry = dfa.get_device("Delta")
        params, device = entry.device.params(entry.stiffness), entry.device
    g = growth_threshold(params, device)
    d = assert_json_from_fields(g)
    assert set(d) >= GROWTH_JSON_KEYS and "result" not in d
    names = ("amplitude", "frequency", "xi_dot", "position", "velocity")
    assert d["band"] == {"low": {n: d[n] for n in names}, "high": {n: d[f"{n}_high"] for n in names}}
    assert [d[n] for n in names] == [getattr(g, n) for n in names]
    assert [d[f"{n}_high"] for n in names] == [getattr(g, f"{n}_high") for n in names]
    assert (d["unstable_count"], d["grows_above"], d["status"]) == (g.unstable_count, g.grows_above, g.status.value)
    assert (d["complete"], d["linear_stable"], d["linear_model"]) == (g.result.complete, g.result.linear_stable, "zoh")
    assert d["caveat"] == to_jsonable(g.caveat) and d["status_message"] == g.status.message
    for key in ("caveat", *(f"{n}_high" for n in names)):
        assert d[key] is not None or f"/{key}" in d["null_reasons"]
