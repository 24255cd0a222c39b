"""Paper Table 1: physical device ↔ dimensionless (μ, β, σ), and input validation."""

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

import dfa

#: Deliberately outside what haptic devices have (extreme values test the numerics): the plausibility warning
#: (dfa.plausibility) is expected here, and tested in tests/test_plausibility.py.
pytestmark = pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")


pos = st.floats(1e-6, 1e6, allow_nan=False)


@given(m=pos, b=pos, c=pos, d=pos, t=st.floats(1e-5, 1e-1), k=pos)
def test_table1_inverse_stiffness_round_trips(m, b, c, d, t, k):
    dev = dfa.Device(m, b, c, d, t)
    p = dev.params(k)
    assert dev.stiffness_for_mu(p.mu) == pytest.approx(k, rel=1e-12)
    assert dev.stiffness_for_beta(p.beta) == pytest.approx(k, rel=1e-12)
    assert dev.stiffness_for_sigma(p.sigma) == pytest.approx(k, rel=1e-12)


def test_table1_xi_dot_does_not_depend_on_stiffness():
    dev = dfa.get_device("Delta").device
    assert dev.xi_dot(0.09) == pytest.approx(0.09 * dev.period / dev.resolution)
    assert dev.velocity(dev.xi_dot(0.09)) == pytest.approx(0.09)


def test_eq8_colgate_stiffness_is_beta_half():
    dev = dfa.get_device("Impulse Engine").device
    assert dev.stiffness_for_beta(0.5) == pytest.approx(2 * dev.damping / dev.period)
    assert dev.stiffness_for_sigma(0.5) == pytest.approx(2 * dev.coulomb / dev.resolution)


@pytest.mark.parametrize("field", ["mass", "resolution", "period"])
@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf])
def test_device_rejects_nonpositive_and_nonfinite(field, value):
    kw = dict(mass=1.0, damping=0.1, coulomb=0.1, resolution=1e-5, period=1e-3)
    kw[field] = value
    with pytest.raises(dfa.DFAValueError) as err:
        dfa.Device(**kw)
    msg = str(err.value)
    assert field in msg and "must be" in msg and repr(float(value)) in msg


@pytest.mark.parametrize("field", ["damping", "coulomb"])
def test_device_allows_zero_friction_but_not_negative(field):
    kw = dict(mass=1.0, damping=0.1, coulomb=0.1, resolution=1e-5, period=1e-3)
    kw[field] = 0.0
    dfa.Device(**kw)
    kw[field] = -0.1
    with pytest.raises(dfa.DFAValueError, match=field):
        dfa.Device(**kw)


def test_device_rejects_text_with_type_error():
    with pytest.raises(dfa.DFATypeError, match="mass"):
        dfa.Device("heavy", 0.1, 0.1, 1e-5, 1e-3)
    with pytest.raises(dfa.DFAValueError, match="stiffness"):
        dfa.Device(1.0, 0.1, 0.1, 1e-5, 1e-3).params(0.0)


def test_params_validated_and_frozen():
    p = dfa.Params(5.0, 0.1, 0.2)
    with pytest.raises(AttributeError):
        p.mu = 3.0
    with pytest.raises(dfa.DFAValueError, match="mu"):
        dfa.Params(0.0, 0.1, 0.2)
    with pytest.raises(dfa.DFAValueError, match="beta"):
        dfa.Params(1.0, -0.1, 0.2)


def test_stiffness_for_beta_needs_damping():
    dev = dfa.Device(1.0, 0.0, 0.1, 1e-5, 1e-3)
    with pytest.raises(dfa.DFAValueError, match="damping"):
        dev.stiffness_for_beta(0.5)


@pytest.mark.parametrize(
    "name, bad, call",
    [
        ("mu", -2.0, lambda v: dfa.Params(v, 0.1, 0.1)),
        ("mu", -2.0, lambda v: dfa.simulate(v, 0.1, 0.1, 1.0, 10)),
        ("mu", -2.0, lambda v: dfa.contour_maps(v, grid=2)),
        ("mu", -2.0, lambda v: dfa.stability_map(v, [1.0], grid=2, samples=10, progress=False)),
        ("beta", -0.5, lambda v: dfa.Params(1.0, v, 0.1)),
        ("beta", -0.5, lambda v: dfa.passivity_criterion(v, 0.1, 1.0)),
        ("beta", -0.5, lambda v: dfa.simulate(1.0, v, 0.1, 1.0, 10)),
        ("sigma", -0.5, lambda v: dfa.Params(1.0, 0.1, v)),
        ("sigma", -0.5, lambda v: dfa.passivity_criterion(0.1, v, 1.0)),
        ("sigma", -0.5, lambda v: dfa.simulate(1.0, 0.1, v, 1.0, 10)),
        ("sigma", -0.5, lambda v: dfa.coulomb_df(1.0, v)),
    ],
)
def test_table1_dimensionless_parameter_rules_read_the_same_everywhere(name, bad, call):
    """Table 1's μ > 0, β >= 0, σ >= 0: one message (name, value, rule, definition) from every entry point."""
    from dfa.checks import check_beta, check_mu, check_sigma

    checker = {"mu": check_mu, "beta": check_beta, "sigma": check_sigma}[name]
    with pytest.raises(dfa.DFAValueError) as expected:
        checker(bad)
    msg = str(expected.value)
    assert msg.startswith(f"{name} = {bad!r} is invalid: it must be a finite number") and "/(K" in msg
    with pytest.raises(dfa.DFAValueError) as got:
        call(bad)
    assert str(got.value) == msg
