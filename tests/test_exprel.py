"""φ₁, φ₂, ψ, χ of the exact sampled-loop solution (paper eq. 4-5; dfa._exprel) against 50-digit mpmath."""

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from dfa import _exprel


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


ARGS = [0.0, 1e-300, 1e-17, 1e-9, 1e-4, 0.1, 0.3, 0.4999999, 0.5, 0.5000001, 0.7, 1.0, 3.0, 30.0, 700.0, 1e6, 1e300]


@pytest.mark.parametrize("name", ["phi1", "phi2", "psi", "chi"])
@pytest.mark.parametrize("u", ARGS)
def test_eq4_exprel_matches_mpmath_tiny_to_huge(name, u):
    got = getattr(_exprel, name)(u)
    assert got == pytest.approx(_ref(name, u), rel=4e-16, abs=0.0)


@pytest.mark.parametrize("name", ["phi1", "phi2"])
@pytest.mark.parametrize("u", [-1e-12, -0.2, -0.4999999, -0.5, -1.0, -10.0, -300.0])
def test_eq4_exprel_negative_arguments_for_gil_factor(name, u):
    assert getattr(_exprel, name)(u) == pytest.approx(_ref(name, u), rel=4e-16, abs=0.0)


@given(st.floats(min_value=0.0, max_value=50.0))
def test_eq4_exprel_property_few_ulp(u):
    for name in ("phi1", "phi2", "psi", "chi"):
        assert getattr(_exprel, name)(u) == pytest.approx(_ref(name, u), rel=4e-16, abs=0.0)


def test_eq4_exprel_identities_and_arrays():
    u = np.array([[0.0, 0.25], [0.75, 5.0]])
    np.testing.assert_array_equal(_exprel.phi1_array(u), np.vectorize(_exprel.phi1)(u))
    np.testing.assert_array_equal(_exprel.phi2_array(u), np.vectorize(_exprel.phi2)(u))
    assert _exprel.phi2_array(np.zeros((0,))).shape == (0,)
    for x in (0.01, 0.4, 2.0):  # e^{−u} = 1 − u φ₁(u),  φ₁(u) = 1 − u φ₂(u)
        assert 1.0 - x * _exprel.phi1(x) == pytest.approx(math.exp(-x), rel=1e-15)
        assert 1.0 - x * _exprel.phi2(x) == pytest.approx(_exprel.phi1(x), rel=1e-15)


def test_eq4_every_user_imports_the_one_exprel():
    """No second φ₁/φ₂: the kernel, the ZOH coefficients, Gil's factor and the test reference step share dfa._exprel."""
    import inspect

    from dfa import _kernel, linear, stiffness

    assert _kernel.phi1 is _exprel.phi1 and _kernel.phi2 is _exprel.phi2
    assert "_exprel" in inspect.getsource(linear._zoh_coefficients)
    assert "_exprel" in inspect.getsource(stiffness.gil_factor)
    c1, c0, p = linear._zoh_coefficients(0.3)
    assert (c1, c0) == pytest.approx((_ref("phi2", 0.3), _ref("phi1", 0.3) - _ref("phi2", 0.3)), rel=1e-15)


def _ref_lambda(y: float) -> float:
    if y == 0:
        return 1.0
    with mpmath.workdps(60):
        return float(mpmath.log1p(mpmath.mpf(y)) / y)


@pytest.mark.parametrize(
    "y", [0.0, 1e-300, 1e-17, 1e-9, 1e-4, 0.03, 0.0624999, 0.0625, 0.07, 0.5, 3.0, 1e6, -0.03, -0.5]
)
def test_eq4_stop_time_ratio_matches_mpmath(y):
    """λ(y) = log1p(y)/y of the stop time t* = w λ(y) (dfa._kernel.step): series and closed form, a few ulp."""
    assert _exprel.log1p_ratio(y) == pytest.approx(_ref_lambda(y), rel=4e-16, abs=0.0)


@given(st.floats(min_value=-0.9, max_value=50.0))
def test_eq4_stop_time_ratio_property_few_ulp(y):
    assert _exprel.log1p_ratio(y) == pytest.approx(_ref_lambda(y), rel=4e-16, abs=0.0)
