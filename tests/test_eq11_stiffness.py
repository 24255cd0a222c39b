"""Stiffness limits for design: eq. 8, 9, 11 and the bounds of spec section 8."""

import math

import control
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from result_json import assert_json_from_fields

import dfa
from dfa.analysis.limits.closed_form import gil_factor, k_max_criterion
from dfa.model.wall import Wall

#: Deliberately outside what haptic devices have (extreme values test the numerics): the plausibility warning
#: (dfa.plausibility) is expected here, and tested in tests/test_plausibility.py.
pytestmark = pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")


DEVICES = ["Delta", "Impulse Engine", "Phantom 1.0", "Toolhandle"]


@pytest.mark.parametrize("name", DEVICES)
def test_eq11_kmax_falls_with_speed_from_2c_over_delta_to_2b_over_t(name):
    dev = dfa.get_device(name).device
    assert dev.damping / dev.period < dev.coulomb / dev.resolution  # true for every Table 2 device
    v = np.logspace(-6, 4, 400)
    k = k_max_criterion(dev, v)
    assert np.all(np.diff(k) <= 1e-9 * k[:-1])
    assert k_max_criterion(dev, 0.0) == pytest.approx(2 * dev.coulomb / dev.resolution)
    assert k[-1] == pytest.approx(2 * dev.damping / dev.period, rel=1e-2)
    assert np.all(k >= dfa.k_abbott_okamura(dev) * (1 - 1e-12))


@pytest.mark.parametrize("name", DEVICES)
@pytest.mark.parametrize("velocity", [0.0, 0.01, 0.1, 1.0])
def test_eq11_kmax_is_where_the_criterion_flips(name, velocity):
    dev = dfa.get_device(name).device
    k = k_max_criterion(dev, velocity)
    assert dfa.device_criterion(dev, k * (1 - 1e-9), velocity).passive
    assert not dfa.device_criterion(dev, k * (1 + 1e-9), velocity).passive


def test_eq11_kmax_constant_when_damping_dominates():
    dev = dfa.Device(mass=1.0, damping=100.0, coulomb=0.01, resolution=1e-3, period=1e-3)
    np.testing.assert_allclose(k_max_criterion(dev, [0, 1, 100]), 2 * dev.coulomb / dev.resolution)


@given(st.floats(1.0, 1e5))
def test_max_passive_velocity_inverts_kmax(k):
    dev = dfa.get_device("Delta").device
    v = dfa.max_passive_velocity(dev, k)
    if k > 2 * dev.coulomb / dev.resolution:
        assert v is None
    elif k <= 2 * dev.damping / dev.period:
        assert math.isinf(v)
    else:
        assert dfa.device_criterion(dev, k, v * (1 - 1e-9)).passive
        assert not dfa.device_criterion(dev, k, v * (1 + 1e-6)).passive
        assert k_max_criterion(dev, v) == pytest.approx(k, rel=1e-9)


def test_abbott_okamura_is_the_two_ends_of_eq11_and_colgate_is_eq8():
    dev = dfa.get_device("Impulse Engine").device
    assert dfa.k_colgate(dev) == pytest.approx(2 * 0.02 / 2e-3)
    assert dfa.k_abbott_okamura(dev) == pytest.approx(
        min(k_max_criterion(dev, 0.0), k_max_criterion(dev, 1e9)), rel=1e-6
    )


def test_stiffness_limits_result_and_verdict():
    dev = dfa.get_device("Impulse Engine").device
    lim = dfa.stiffness_limits(dev, 0.05, stiffness=80.0)
    assert lim.status == "ok" and lim.velocity_status == "bounded"
    assert lim.max_passive_velocity == pytest.approx((0.024 - 80 * 314e-6 / 2) / (80 * 2e-3 / 2 - 0.02))
    assert dfa.stiffness_limits(dev, 0.5, stiffness=80.0).status == "too_stiff"
    assert dfa.stiffness_limits(dev, 0.5, stiffness=10.0).velocity_status == "all_speeds"
    assert dfa.stiffness_limits(dev, 0.5, stiffness=1000.0).velocity_status == "none"
    d = dfa.stiffness_limits(dev, 0.5, stiffness=10.0).to_dict()
    assert d["max_passive_velocity"] is None  # JSON has no infinity; the status says "all_speeds"
    with pytest.raises(dfa.DFATypeError, match="device"):
        dfa.stiffness_limits("Impulse Engine", 0.1)


def _spectral_radius(m, b, period, k):
    """Exact ZOH discretisation of 1/(m s² + b s) with python-control, closed by u = −K x(kT)."""
    plant = control.ss([[0.0, 1.0], [0.0, -b / m]], [[0.0], [1.0 / m]], [[1.0, 0.0]], [[0.0]])
    d = control.c2d(plant, period, method="zoh")
    closed = d.A - d.B @ (k * d.C)
    return max(abs(np.linalg.eigvals(closed)))


@pytest.mark.parametrize(
    "dev",
    [dfa.get_device(n).device for n in DEVICES]
    + [dfa.Device(mass=0.01, damping=5.0, coulomb=0.0, resolution=1e-5, period=2e-3)],  # γ = 1: far from 2b/T
    ids=DEVICES + ["heavily damped"],
)
def test_gil_bound_matches_spectral_radius_of_exact_zoh_loop(dev):
    k = dfa.k_gil(dev)
    assert _spectral_radius(dev.mass, dev.damping, dev.period, k * (1 - 1e-4)) < 1.0
    assert _spectral_radius(dev.mass, dev.damping, dev.period, k * (1 + 1e-4)) > 1.0


@pytest.mark.parametrize("mu, beta_crit", [(1.0, 0.4617), (5.0, 0.4918), (100.0, 0.49958)])
def test_gil_dimensionless_bound_matches_spec_section8(mu, beta_crit):
    assert dfa.gil_beta_critical(mu) == pytest.approx(beta_crit, abs=6e-5)


@given(st.floats(0.5, 500.0))
def test_gil_dimensionless_bound_is_the_spectral_radius_one_point(mu):
    b = dfa.gil_beta_critical(mu)
    assert _spectral_radius(mu, b * (1 + 1e-6), 1.0, 1.0) < 1.0 < _spectral_radius(mu, b * (1 - 1e-6), 1.0, 1.0)


def test_gil_factor_series_matches_direct_formula_and_limit():
    g = np.array([1e-3, 0.1, 0.3, 0.49])
    direct = g * (1 - np.exp(-g)) / (1 - np.exp(-g) - g * np.exp(-g))
    np.testing.assert_allclose(gil_factor(g), direct, rtol=1e-9)
    assert gil_factor(0.0) == 2.0
    # continuity across the switch between series and closed form
    assert gil_factor(0.5 - 1e-12) == pytest.approx(gil_factor(0.5 + 1e-12), rel=1e-10)


def test_eq11_max_passive_velocity_agrees_with_the_criterion_where_kt_minus_b_cancels():
    """K = 60 N/m on the Delta is one rounding step above 2b/T: the largest passive speed must still be one
    at which device_criterion says passive (it claimed 5.08e17 m/s where eq. 6 already failed at 3.97e17)."""
    import dfa

    dev = dfa.get_device("Delta").device
    for k in (60.0, np.nextafter(60.0, 0.0), np.nextafter(60.0, 100.0), 2 * dev.damping / dev.period):
        v = dfa.max_passive_velocity(dev, k)
        if v is None or math.isinf(v):
            assert dfa.device_criterion(dev, k, 1e30).passive == math.isinf(v or 0.0)
            continue
        assert dfa.device_criterion(dev, k, v * (1 - 1e-9)).passive
        assert not dfa.device_criterion(dev, k, v * (1 + 1e-9)).passive


def test_eq11_k_max_passes_its_own_criterion_with_delay():
    """Red-team finding: K_max failed device_criterion at margin −1e-16 in a third of random cases."""
    import dfa

    rng = np.random.default_rng(3)
    for name in ("Delta", "Impulse Engine", "Phantom 1.0", "Toolhandle"):
        dev = dfa.get_device(name).device
        for _ in range(150):
            v = 10 ** rng.uniform(-3, 0.5)
            d = int(rng.integers(0, 3))
            k = dfa.k_max_criterion(dev, v, delay=d)
            assert dfa.device_criterion(dev, Wall.of(k, delay=d), v).passive, (name, v, d)
            assert dfa.stiffness_limits(dev, v, k, delay=d).status == "ok"
            assert not dfa.device_criterion(
                dev, Wall.of(k * (1 + 1e-9), delay=d), v
            ).passive or k == dfa.k_max_criterion(dev, 0.0)


def test_stiffness_limits_and_response_json_from_their_fields():
    """StiffnessLimits and StiffnessResponse write the Result base's JSON: fields, json_properties, message."""
    dev = dfa.get_device("Impulse Engine").device
    for lim in (
        dfa.stiffness_limits(dev, 0.05),
        dfa.stiffness_limits(dev, 0.05, stiffness=80.0, delay=1),
        dfa.stiffness_limits(dev, 0.5, stiffness=10.0),  # every speed: max_passive_velocity null, with its reason
    ):
        d = assert_json_from_fields(lim)
        assert d["device"] == dev.name and d["max_passive_velocity_status"] == lim.velocity_status.value
    d = assert_json_from_fields(dfa.stiffness_limits(dev, 0.5, stiffness=10.0))
    assert d["null_reasons"] == {"/max_passive_velocity": "passive at every speed (no finite limit)"}
    resp = dfa.stiffness_response(dev, [0.01, 0.1], stiffness=80.0, delay=1)
    d = assert_json_from_fields(resp)
    assert "limits" not in d and d["k_colgate"] == resp.limits.k_colgate and d["delay"] == 1
