"""Passivity criterion, eq. 6-12 and 35, and the regions of paper Fig. 3."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dfa
from dfa import CriticalLine, classify_region, passivity_criterion
from dfa.model.wall import WallParams

beta_s = st.floats(0.0, 2.0)
sigma_s = st.floats(0.0, 3.0)
speed_s = st.floats(0.0, 50.0)


def eq6_by_hand(beta, sigma, v):
    return (beta - 0.5) * abs(v) + (sigma - 0.5) >= 0 and sigma >= 0.5


@pytest.mark.parametrize(
    "beta, sigma, v, region, passive",
    [
        (0.8, 0.9, 3.0, "a", True),  # β > ½, σ > ½
        (0.8, 0.3, 3.0, "b", False),  # β > ½, σ < ½: sub-tick cycles
        (0.2, 0.3, 3.0, "c", False),  # β < ½, σ < ½: globally unstable
        (0.2, 1.0, 3.0, "d", False),  # ½ < σ < ½ + 3·0.3 = 1.4
        (0.2, 1.5, 3.0, "e", True),  # σ above the critical line
    ],
)
def test_fig3_one_case_per_region(beta, sigma, v, region, passive):
    r = passivity_criterion(beta, sigma, v)
    assert (r.region, r.passive) == (region, passive)
    assert r.passive == eq6_by_hand(beta, sigma, v)
    assert r.status.message == dfa.REGION_DESCRIPTIONS[region] and r.status.region == region


@pytest.mark.parametrize(
    "beta, sigma, v, region",
    [
        (0.5, 0.5, 4.0, "a"),  # corner: both non-strict inequalities hold
        (0.5, 0.25, 4.0, "b"),  # β = ½ belongs to a/b
        (0.25, 0.5, 0.0, "e"),  # σ = ½ at rest: margin 0 -> e
        (0.25, 0.5, 1.0, "d"),  # σ = ½ moving: margin < 0 -> d
        (0.25, 1.0, 2.0, "e"),  # exactly on the critical line: margin = 0 -> e (passive)
        (0.25, 0.4375, 0.0, "c"),  # σ < ½ at rest is still c
    ],
)
def test_fig3_boundaries_are_assigned_deterministically(beta, sigma, v, region):
    r = passivity_criterion(beta, sigma, v)
    assert r.region == region
    assert r.passive == eq6_by_hand(beta, sigma, v)


@given(beta_s, sigma_s, speed_s)
def test_eq6_passive_iff_region_a_or_e_and_matches_inequalities(beta, sigma, v):
    r = passivity_criterion(beta, sigma, v)
    assert r.passive == (r.region in ("a", "e")) == eq6_by_hand(beta, sigma, v)
    assert r.margin == pytest.approx((beta - 0.5) * v + sigma - 0.5, abs=1e-12)
    assert classify_region(beta, sigma, v).item() == r.region


@given(beta_s, sigma_s, speed_s, speed_s)
def test_eq35_passivity_is_monotone_in_speed(beta, sigma, v1, v2):
    lo, hi = sorted((v1, v2))
    if passivity_criterion(beta, sigma, hi).passive:
        assert passivity_criterion(beta, sigma, lo).passive


@given(st.floats(0.0, 0.49), st.floats(0.5, 3.0))
def test_eq12_critical_speed_separates_passive_from_not(beta, sigma):
    r = passivity_criterion(beta, sigma, 0.0)
    crit = r.critical_xi_dot
    assert crit == pytest.approx((sigma - 0.5) / (0.5 - beta))
    assert passivity_criterion(beta, sigma, crit * (1 - 1e-9)).passive
    if crit > 0:
        assert not passivity_criterion(beta, sigma, crit * (1 + 1e-9) + 1e-12).passive


def test_eq12_critical_speed_absent_outside_d_e():
    for beta, sigma in [(0.7, 0.9), (0.7, 0.2), (0.2, 0.2)]:
        assert passivity_criterion(beta, sigma, 1.0).critical_xi_dot is None


def test_eq10_critical_line_passes_through_half_half_with_slope_minus_speed():
    line = passivity_criterion(0.1, 1.0, 2.5).critical_line
    assert line.sigma(0.5) == pytest.approx(0.5)
    assert line.slope == -2.5
    betas = np.linspace(0, 1, 5)
    np.testing.assert_allclose(line.sigma(betas), 0.5 + 2.5 * (0.5 - betas))


def test_eq7_without_quantization_and_eq8_colgate():
    # eq. 7: (β − ½)|ξ'| + σ >= 0; σ = 0 reduces it to β >= ½ (eq. 8)
    assert passivity_criterion(0.49, 0.0, 1.0, quantized=False).passive is False
    assert passivity_criterion(0.5, 0.0, 1.0, quantized=False).passive is True
    r = passivity_criterion(0.1, 0.2, 0.0, quantized=False)
    assert r.passive and r.critical_xi_dot == pytest.approx(0.2 / 0.4)
    # no quantization: regions b and c are empty
    assert set(
        classify_region(np.linspace(0, 1, 21)[:, None], np.linspace(0, 1, 21), 2.0, quantized=False).ravel()
    ) <= {"a", "d", "e"}


@given(beta_s, sigma_s, speed_s)
def test_eq7_is_weaker_than_eq6(beta, sigma, v):
    if passivity_criterion(beta, sigma, v).passive:
        assert passivity_criterion(beta, sigma, v, quantized=False).passive


def test_eq9_static_limit():
    # at rest only σ >= ½ (c >= KΔ/2) matters
    assert passivity_criterion(0.0, 0.5, 0.0).passive
    assert not passivity_criterion(10.0, 0.4999, 0.0).passive


def test_eq11_physical_criterion_and_eq12_physical_critical_speed():
    dev = dfa.get_device("Delta").device
    k = 14500.0
    r = dfa.device_criterion(dev, k, 0.1)
    crit_v = (2 * dev.coulomb - k * dev.resolution) / (k * dev.period - 2 * dev.damping)  # eq. 12
    assert r.critical_velocity == pytest.approx(crit_v, rel=1e-12)
    assert dfa.device_criterion(dev, k, crit_v * 0.999).passive
    assert not dfa.device_criterion(dev, k, crit_v * 1.001).passive
    assert r.to_dict()["device"] == "Delta"


def test_criterion_bad_input():
    with pytest.raises(dfa.DFAValueError, match="beta"):
        passivity_criterion(-0.1, 1.0, 1.0)
    with pytest.raises(dfa.DFAValueError, match="xi_dot"):
        passivity_criterion(0.1, 1.0, math.nan)
    with pytest.raises(dfa.DFATypeError, match="sigma"):
        passivity_criterion(0.1, "1.0", 1.0)


@settings(max_examples=60, deadline=None)
@given(
    st.floats(0.0, 3.0),
    st.floats(0.0, 4.0),
    st.floats(0.0, 20.0),
    st.integers(0, 3),
    st.booleans(),
)
def test_eq10_critical_line_is_the_one_margin_of_every_verdict(beta, sigma, v, d, quantized):
    """Eq. 6/10: the result's margin, its CriticalLine and classify_region are one formula (β − ½ − d)V + (σ − σ₀)."""
    r = passivity_criterion(beta, sigma, v, quantized=quantized, wall=WallParams.of(delay=d))
    line = r.critical_line
    s0 = 0.5 if quantized else 0.0
    assert line == CriticalLine.of(v, quantized=quantized, delay=d) and line.sigma0 == s0 and line.beta0 == 0.5 + d
    assert r.margin == line.margin(beta, sigma) == (beta - (0.5 + d)) * v + (sigma - s0)  # independent spelling
    # the line is where the margin vanishes, through (½ + d, σ₀) with slope −V
    assert line.sigma(0.5 + d) == s0 and line.margin(beta, line.sigma(beta)) == pytest.approx(0.0, abs=1e-12 * (1 + v))
    assert (str(classify_region(beta, sigma, v, quantized, d)) in "ae") == r.passive
