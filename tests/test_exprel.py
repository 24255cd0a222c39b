"""φ₁, φ₂, ψ, χ of the exact sampled-loop solution (paper eq. 4-5; dfa.core.exprel) against 50-digit mpmath."""

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dfa.core import exprel


def _ref(name: str, u: float) -> float:
    """Closed forms evaluated in 50 digits plus 3 per decade of smallness (the cancellation of χ), limits at u = 0."""
    if u == 0:
        return {"phi1": 1.0, "phi2": 0.5, "psi": 0.5, "chi": 1.0 / 3.0}[name]
    with mpmath.workdps(50 + 3 * max(0, -int(math.log10(abs(u))))):
        return _closed(name, mpmath.mpf(u))


def _closed(name: str, x) -> float:
    e1, e2 = -mpmath.expm1(-x), -mpmath.expm1(-2 * x)
    val = {
        "phi1": e1 / x,
        "phi2": (x - e1) / x**2,
        "psi": (e1 - e2 / 2) / x**2,
        "chi": (x - 2 * e1 + e2 / 2) / x**3,
    }[name]
    return float(val)


SHORT_EDGE = [0.0312499, 0.03125, 0.0312501]  # the eight-term series' edge, |u| = 1/32
ARGS = [0.0, 1e-300, 1e-17, 1e-9, 1e-4, *SHORT_EDGE, 0.1, 0.3, 0.4999999, 0.5, 0.5000001, 0.7, 1.0, 3.0, 30.0, 1e6]
ARGS += [700.0, 1e300]


@pytest.mark.parametrize("name", ["phi1", "phi2", "psi", "chi"])
@pytest.mark.parametrize("u", ARGS)
def test_eq4_exprel_matches_mpmath_tiny_to_huge(name, u):
    _assert_few_ulp(name, getattr(exprel, name)(u), _ref(name, u))


def _assert_few_ulp(name: str, got: float, ref: float) -> None:
    """φ₁, φ₂: within 4·10⁻¹⁶ relative (about 2 ulp); ψ = ½φ₁², χ (a product of e^{−2u} and a sum): 4 ulp."""
    if name in ("psi", "chi"):
        assert abs(got - ref) <= 4 * math.ulp(ref)
    else:
        assert got == pytest.approx(ref, rel=4e-16, abs=0.0)


@pytest.mark.parametrize("name", ["phi1", "phi2"])
@pytest.mark.parametrize("u", [-1e-12, -0.0312499, -0.03125, -0.2, -0.4999999, -0.5, -1.0, -10.0, -300.0])
def test_eq4_exprel_negative_arguments_for_gil_factor(name, u):
    assert getattr(exprel, name)(u) == pytest.approx(_ref(name, u), rel=4e-16, abs=0.0)


@given(st.floats(min_value=0.0, max_value=50.0))
def test_eq4_exprel_property_few_ulp(u):
    for name in ("phi1", "phi2", "psi", "chi"):
        _assert_few_ulp(name, getattr(exprel, name)(u), _ref(name, u))


@pytest.mark.parametrize("u", [0.5, 0.875, 1.0, 2.0, 4.99, 5.0, 7.0])
def test_eq4_exprel_psi_chi_without_cancellation_where_the_closed_forms_cancel(u):
    """0.875 was 25 ulp off when χ took its closed form above u = ½ (u − 2E + ½E(2 − E) cancels, E = 1 − e^{−u})."""
    for name in ("psi", "chi"):
        _assert_few_ulp(name, getattr(exprel, name)(u), _ref(name, u))
    assert exprel.psi(u) == 0.5 * exprel.phi1(u) ** 2


def test_eq4_exprel_identities_and_arrays():
    u = np.array([[0.0, 0.25], [0.75, 5.0]])
    np.testing.assert_array_equal(exprel.phi1_array(u), np.vectorize(exprel.phi1)(u))
    np.testing.assert_array_equal(exprel.phi2_array(u), np.vectorize(exprel.phi2)(u))
    assert exprel.phi2_array(np.zeros((0,))).shape == (0,)
    for x in (0.01, 0.4, 2.0):  # e^{−u} = 1 − u φ₁(u),  φ₁(u) = 1 − u φ₂(u)
        assert 1.0 - x * exprel.phi1(x) == pytest.approx(math.exp(-x), rel=1e-15)
        assert 1.0 - x * exprel.phi2(x) == pytest.approx(exprel.phi1(x), rel=1e-15)


def test_eq4_every_user_imports_the_one_exprel():
    """No second φ₁/φ₂: the kernel, the ZOH coefficients, Gil's factor and the test reference step share dfa.core.exprel."""
    import inspect

    from dfa.analysis.limits import closed_form as stiffness
    from dfa.core import kernel, zoh

    assert kernel.phi1 is exprel.phi1 and kernel.phi2 is exprel.phi2
    assert "from .exprel import" in inspect.getsource(zoh)
    assert "core.exprel" in inspect.getsource(stiffness.gil_factor)
    c1, c0, p = zoh.zoh_coefficients(0.3)
    assert (c1, c0) == pytest.approx((_ref("phi2", 0.3), _ref("phi1", 0.3) - _ref("phi2", 0.3)), rel=1e-15)


LAMBDA_EDGE = [0.0078124, 0.0078125, 0.0078126, -0.0078124]  # the eight-term series' edge, |y| = 1/128


def _ref_lambda(y: float) -> float:
    if y == 0:
        return 1.0
    with mpmath.workdps(60):
        return float(mpmath.log1p(mpmath.mpf(y)) / y)


@pytest.mark.parametrize(
    "y", [0.0, 1e-300, 1e-17, 1e-9, 1e-4, *LAMBDA_EDGE, 0.03, 0.0624999, 0.0625, 0.07, 0.5, 3.0, 1e6, -0.03, -0.5]
)
def test_eq4_stop_time_ratio_matches_mpmath(y):
    """λ(y) = log1p(y)/y of the stop time t* = w λ(y) (dfa.core.kernel.step): series and closed form, a few ulp."""
    assert exprel.log1p_ratio(y) == pytest.approx(_ref_lambda(y), rel=4e-16, abs=0.0)


@given(st.floats(min_value=-0.9, max_value=50.0))
def test_eq4_stop_time_ratio_property_few_ulp(y):
    assert exprel.log1p_ratio(y) == pytest.approx(_ref_lambda(y), rel=4e-16, abs=0.0)


@given(st.floats(min_value=-exprel.SHORT_U, max_value=exprel.SHORT_U))
def test_eq4_exprel_short_series_property_few_ulp(u):
    """The eight-term series near 0 (the simulator's stop inside a sample): φ₁, φ₂ within a few ulp."""
    for name in ("phi1", "phi2"):
        assert getattr(exprel, name)(u) == pytest.approx(_ref(name, u), rel=4e-16, abs=0.0)


@given(st.floats(min_value=-exprel.SHORT_Y, max_value=exprel.SHORT_Y))
def test_eq4_stop_time_ratio_short_series_property_few_ulp(y):
    assert exprel.log1p_ratio(y) == pytest.approx(_ref_lambda(y), rel=4e-16, abs=0.0)


@pytest.mark.parametrize("u", [0.0, 1e-300, 1e-9, -0.01, 0.0312499, 0.03125, 0.2, 3.0])
def test_eq4_exprel_pair_of_one_phase_matches_mpmath(u):
    """(φ₁, φ₂) of a phase inside a sample (dfa.core.kernel.step): near 0, φ₁ = 1 − u φ₂ from one series."""
    f1, f2 = exprel.phi12(u)
    assert f1 == pytest.approx(_ref("phi1", u), rel=4e-16, abs=0.0)
    assert f2 == pytest.approx(_ref("phi2", u), rel=4e-16, abs=0.0)
    if abs(u) >= exprel.SHORT_U:
        assert (f1, f2) == (exprel.phi1(u), exprel.phi2(u))


@given(st.floats(min_value=-exprel.SHORT_U, max_value=exprel.SHORT_U))
def test_eq4_exprel_pair_property_few_ulp(u):
    f1, f2 = exprel.phi12(u)
    assert f1 == pytest.approx(_ref("phi1", u), rel=4e-16, abs=0.0)
    assert f2 == exprel.phi2(u)
