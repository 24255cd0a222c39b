"""Eq. 42-45: one vectorised implementation of each closed form, checked against independent solutions."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dfa.analysis.contours import contour_maps
from dfa.analysis.cycles import (
    ClosedFormStatus,
    large_cycle_closed_form,
    large_cycle_closed_forms,
    large_cycle_frequencies,
    small_cycle_closed_form,
    small_cycle_closed_forms,
)
from dfa.errors import DFAValueError
from dfa.render.text import flagged_text


def _mp_small(mu: float, beta: float, sigma: float) -> tuple[float, float]:
    """Eq. 43 by mpmath bisection/Anderson at 40 digits (independent of scipy), then eq. 42."""
    mp.mp.dps = 40
    f = lambda w: mp.sin(w / 2) / 2 - beta * mp.cos(w / 2) / (2 * mu * w) - sigma
    w = mp.findroot(f, (mp.mpf("1e-30"), mp.pi), solver="anderson")
    return float(2 * mp.cos(w / 2) / (mp.pi * mu * w * w)), float(w)


@settings(max_examples=40, deadline=None)
@given(st.floats(0.3, 500.0), st.floats(1e-4, 3.0), st.floats(0.0, 0.45))
def test_eq43_vectorised_root_equals_mpmath(mu, beta, sigma):
    m_ref, w_ref = _mp_small(mu, beta, sigma)
    cf = small_cycle_closed_forms(mu, beta, sigma)
    assert cf.codes == [ClosedFormStatus.OK]
    assert float(cf.frequency) == pytest.approx(w_ref, rel=1e-13)
    assert float(cf.amplitude) == pytest.approx(m_ref, rel=1e-11)


def test_eq43_undamped_closed_form_omega_is_2_asin_2sigma():
    sigma = np.array([0.01, 0.1, 0.25, 0.4])
    cf = small_cycle_closed_forms(5.0, 0.0, sigma)
    np.testing.assert_allclose(cf.frequency, 2 * np.arcsin(2 * sigma), rtol=1e-15)
    np.testing.assert_allclose(cf.amplitude, 2 * np.cos(cf.frequency / 2) / (math.pi * 5.0 * cf.frequency**2))


def test_eq43_beta_sigma_zero_is_flagged_not_returned_as_tiny_omega():
    cf = small_cycle_closed_forms(5.0, [0.0, 0.0, 1e-9], [0.0, 0.6, 0.0])
    assert cf.codes == [ClosedFormStatus.DEGENERATE, ClosedFormStatus.NO_CYCLE, ClosedFormStatus.OK]
    assert np.isnan(cf.frequency[:2]).all() and np.isnan(cf.amplitude[:2]).all()
    assert "β = σ = 0" in ClosedFormStatus.DEGENERATE.reason
    assert small_cycle_closed_form(5.0, 0.0, 0.0) is None
    # a tiny β still has its (slow) cycle: ω ≈ √(2β/μ) from eq. 43 at small ω
    assert float(cf.frequency[2]) == pytest.approx(math.sqrt(2e-9 / 5.0), rel=1e-6)


def test_fig7_maps_flag_the_beta_sigma_zero_point():
    maps = contour_maps(5.0, grid=5)
    assert np.isnan(maps.small_amplitude_closed[0, 0])  # β = σ = 0 corner
    assert maps.status == "flagged" and [(f.family, f.reason, f.points) for f in maps.flagged] == [
        ("small", "degenerate", 1)
    ]
    text = flagged_text(maps)
    assert "DEGENERATE" not in text and "β = σ = 0" in text and "1 point(s)" in text


def test_eq44_frequency_matches_mpmath_and_paper():
    mus = np.array([0.5, 5.0, 100.0, 1e4])
    mp.mp.dps = 40
    ref = [float(mp.findroot(lambda w, m=m: m * w * w - mp.cos(w / 2), (0, mp.pi), solver="anderson")) for m in mus]
    np.testing.assert_allclose(large_cycle_frequencies(mus), ref, rtol=4e-16)
    assert large_cycle_frequencies(5.0) == pytest.approx(0.44175, abs=6e-6)  # paper Fig. 7 (μ = 5)


@settings(max_examples=30, deadline=None)
@given(st.floats(0.5, 300.0), st.floats(0.0, 1.0), st.floats(0.0, 3.0))
def test_eq45_vectorised_equals_formula_and_scalar_wrapper(mu, beta, sigma):
    w = float(large_cycle_frequencies(mu))
    den = math.sin(w / 2) - beta * w
    cf = large_cycle_closed_forms(mu, beta, sigma)
    scalar = large_cycle_closed_form(mu, beta, sigma)
    if den <= 0:
        assert scalar is None and cf.codes == [ClosedFormStatus.NO_CYCLE] and np.isnan(cf.amplitude)
    else:
        assert scalar == (float(cf.amplitude), float(cf.frequency))
        assert scalar[0] == pytest.approx(4 * sigma / (math.pi * den), rel=1e-15)


def test_eq42_45_closed_forms_broadcast_and_are_read_only():
    cf = small_cycle_closed_forms(5.0, np.linspace(0, 1, 3)[None, :], np.linspace(0, 1, 4)[:, None])
    assert cf.amplitude.shape == cf.status.shape == (4, 3)
    with pytest.raises(ValueError):
        cf.amplitude[0, 0] = 1.0


@pytest.mark.parametrize("args", [(0.0, 0.1, 0.1), (5.0, -0.1, 0.1), (5.0, 0.1, math.nan)])
def test_eq42_45_closed_forms_reject_bad_input(args):
    with pytest.raises(DFAValueError, match="is invalid: it must be"):
        small_cycle_closed_forms(*args)
    with pytest.raises(DFAValueError, match="is invalid: it must be"):
        large_cycle_closed_forms(*args)
