"""The exact linear bound with a controller (dfa.analysis.linear_wall.stable_stiffness) at tiny (b + B)T/m, checked
against the spectral radius of the same characteristic polynomial in high-precision arithmetic (mpmath, the
reference helpers of ``test_gil_linear_bound_small_rate``), and against the float ray analysis where both hold.

Formerly refused (0 < (b + B)T/m < 1e-7: a DFAValueError; before that a false 'never stable', and K 3732 N/m above
the ~3000 N/m limit at m = 1e8 kg). Now K_crit comes from the Taylor series of the ray at z = 1
(``series_kappa``) for (b + B)T/m <= SERIES_RATE = 1e-4.
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_gil_linear_bound_small_rate import _rho_mp

from dfa.analysis.limits.kmax import closed_forms
from dfa.analysis.linear import critical_stiffness
from dfa.analysis.linear_wall import (
    LinearStatus,
    _stable_kappa,
    series_kappa,
    stable_region,
    stable_stiffness,
)
from dfa.cli import main
from dfa.model.device import Device
from dfa.model.wall import Wall
from dfa.render.limits import limit_text
from dfa.results.status import LimitStatus

T = 1e-3
#: (B, delay, filter cutoff Hz, amplifier bandwidth Hz) and the device's share of the rate
CONTROLLERS = {
    "pure damper": ((1.0, 0, None, None), 0.0),
    "damper + filter": ((0.5, 0, 100.0, None), 0.5),
    "damper + delay 3": ((0.5, 3, None, None), 0.5),
    "damper + lag": ((0.5, 0, None, 300.0), 0.5),
}


def _case(rate: float, name: str) -> tuple[float, float, Wall]:
    (big_b, d, fc, fa), share = CONTROLLERS[name]
    b = share / (1.0 - share) * big_b
    return (b + big_b) * T / rate, b, Wall.of(1000.0, big_b, d, fc, fa)


def _check(m: float, b: float, c: Wall, rel: float = 1e-4, period: float = T) -> float:
    """K_crit(1 − rel) stable and K_crit(1 + rel) unstable in 60+ digit arithmetic; returns K_crit."""
    r = stable_stiffness(m, b, period, c)
    assert r.status is LinearStatus.INTERVAL and np.isfinite(r.k_crit) and r.k_crit > 0.0
    p = c.params(period)
    ctl = {"a_b": c.damping * period / m, "cutoff": p.cutoff, "lag": p.lag}
    kappa = r.k_crit * period * period / m
    assert _rho_mp(b * period / m, kappa * (1 - rel), p.delay, **ctl) < 0.0, (m, b, c)
    assert _rho_mp(b * period / m, kappa * (1 + rel), p.delay, **ctl) > 0.0, (m, b, c)
    return r.k_crit


@pytest.mark.parametrize("name", list(CONTROLLERS))
@pytest.mark.parametrize("rate", [1e-16, 1e-11, 1e-8, 1e-6])
def test_controlled_linear_small_rate_grid_mpmath(rate, name):
    """Rates 1e-16 … 1e-6 × pure damper, damper + filter, damper + delay 3, damper + lag: K_crit(1 ∓ 1e-4)."""
    _check(*_case(rate, name))


def test_controlled_linear_small_rate_former_counterexample_mpmath():
    """m = 1e8 kg, b = 1, T = 1 ms, B = 0.5, d = 1, 100 Hz filter: formerly refused (before: a false 'never')."""
    k = _check(1e8, 1.0, Wall.of(1000.0, 0.5, 1, 100.0))
    assert k == pytest.approx(1.5 / (T * 1.5), rel=1e-6)  # → (b + B)/(T(½ + d)): the filter drops out


@pytest.mark.parametrize("name", list(CONTROLLERS))
def test_controlled_linear_small_rate_limit_is_b_plus_b_over_t_half_plus_d_plus_lag(name):
    """As (b + B)T/m → 0: K_crit → (b + B)/(T(½ + d + τ_a/T)) (the leading balance of the series)."""
    m, b, c = _case(1e-14, name)
    p = c.params(T)
    k = stable_stiffness(m, b, T, c).k_crit
    assert k == pytest.approx((b + c.damping) / (T * (0.5 + p.delay + p.lag)), rel=1e-12)


@pytest.mark.parametrize("name", list(CONTROLLERS))
@pytest.mark.parametrize("rate", [1e-5, 1e-4])
def test_controlled_linear_small_rate_series_agrees_with_the_float_ray(rate, name):
    """Two independent methods where both hold: the Taylor series at z = 1 and the float crossings + spectral radius."""
    m, b, c = _case(rate, name)
    p = c.params(T)
    a, a_b = b * T / m, c.damping * T / m
    rho_l, k_tilde = series_kappa(a, a_b, p)
    assert (a * rho_l + a_b) * k_tilde == pytest.approx(_stable_kappa(a, a_b, p)[0][1], rel=1e-8)


def test_controlled_linear_small_rate_unstable_above_k_crit_mpmath():
    """The INTERVAL verdict at a tiny rate: unstable on the ray above K_crit (60+ digits), up to κ = KT²/m = 10."""
    for name in ("damper + delay 3", "damper + lag", "damper + filter"):
        m, b, c = _case(1e-12, name)
        p = c.params(T)
        ctl = {"a_b": c.damping * T / m, "cutoff": p.cutoff, "lag": p.lag}
        kappa = stable_stiffness(m, b, T, c).k_crit * T * T / m
        for k in (3 * kappa, 1e3 * kappa, 1e-3, 10.0):
            assert _rho_mp(b * T / m, k, p.delay, **ctl) > 0.0, (name, k)


@settings(max_examples=6, deadline=None)
@given(st.floats(-16.0, -4.0), st.sampled_from(list(CONTROLLERS)), st.integers(0, 4))
def test_controlled_linear_small_rate_property_stable_below_unstable_above_mpmath(log_rate, name, delay):
    (big_b, _, fc, fa), share = CONTROLLERS[name]
    m, b, _ = _case(10.0**log_rate, name)
    _check(m, b, Wall.of(1000.0, big_b, delay, fc, fa))


@pytest.mark.parametrize("d", [0, 3, 100])
def test_controlled_linear_small_rate_underflow_huge_mass(d):
    """m = 1e300 kg (rates ~1e-303) and b, B = 1e-320 (subnormal): positive, finite K, not 0 or NaN."""
    for c in (Wall.of(1.0, 1.0, d), Wall.of(1.0, 1.0, d, 50.0, 200.0)):
        p = c.params(T)
        k = stable_stiffness(1e300, 1.0, T, c).k_crit
        assert k == pytest.approx(2.0 / (T * (0.5 + d + p.lag)), rel=1e-14)
        assert d == 100 or critical_stiffness(1e300, 1.0, T, wall=c) == k
    k = stable_stiffness(1.0, 1e-320, 1e-12, Wall.of(1.0, 1e-320, d)).k_crit
    assert k == pytest.approx(2e-320 / (1e-12 * (0.5 + d)), rel=1e-3)  # the subnormal inputs carry ~3 digits


@pytest.mark.parametrize("d", [0, 3, 100])
def test_gil_critical_stiffness_underflowing_rate_is_b_over_t_half_plus_d(d):
    """The spring: bT/m underflowing to 0 (b = 1e-320 N·s/m, m = 1e3 kg, T = 1e-12 s) is not reported as 0."""
    assert critical_stiffness(1e3, 1e-320, 1e-12, wall=Wall.of(1.0, delay=d)) == pytest.approx(
        1e-320 / (1e-12 * (0.5 + d)), rel=1e-3
    )
    assert critical_stiffness(1e300, 1.0, T, wall=Wall.of(1.0, delay=d)) == pytest.approx(
        1.0 / (T * (0.5 + d)), rel=1e-15
    )


def test_controlled_linear_small_rate_stable_region():
    """stable_region at m = 1e10 kg: every B, the series' K_crit (formerly refused)."""
    r = stable_region(1e10, 1.0, T, [0.0, 0.5, 2.0], wall=Wall.of(1.0, delay=2, filter_cutoff=100.0))
    assert r.status is LinearStatus.INTERVAL
    np.testing.assert_allclose(r.k_crit, [(1.0 + bb) / (T * 2.5) for bb in (0.0, 0.5, 2.0)], rtol=1e-9)


#: The CLI case: (b + B)T/m = 2e-11 with a delay of 3 and a 100 Hz filter (formerly refused, exit 2).
SMALL_RATE_ARGV = ["stiffness", "--mass", "1", "--damping", "1e-8", "--coulomb", "0", "--resolution", "1e-6",
                   "--period", "1e-3", "--stiffness", "1000", "--virtual-damping", "1e-8", "--delay", "3",
                   "--velocity-filter", "100"]  # fmt: skip
SMALL_RATE_DEVICE = Device(mass=1.0, damping=1e-8, coulomb=0.0, resolution=1e-6, period=T)
SMALL_RATE_WALL = Wall.of(1000.0, 1e-8, 3, 100.0)
SMALL_RATE_K_LINEAR = 2e-8 / (T * 3.5)  # (b + B)/(T(½ + d)): the filter drops out


def test_controlled_linear_small_rate_k_linear_of_the_design_answer():
    """The design answer's K_linear at (b + B)T/m = 2e-11 and 0.1 m/s (formerly refused): finite, (b + B)/(T(½ + d)),
    not 0 or NaN. The closed forms of :func:`dfa.analysis.limits.kmax.design_answer` alone
    (:func:`~dfa.analysis.limits.kmax.closed_forms`): the four-way search is not what is tested here."""
    dev, wall = SMALL_RATE_DEVICE, SMALL_RATE_WALL
    _kc, kl, _pub, _k_ref, top = closed_forms(dev, wall, 0.1)
    assert kl.status is LimitStatus.FOUND and np.isfinite(kl.value)
    assert kl.value == pytest.approx(SMALL_RATE_K_LINEAR, rel=1e-9)
    assert kl.value == stable_stiffness(dev.mass, dev.damping, T, wall).k_crit
    assert np.isfinite(top) and top > 0.0  # the searches have a finite grid
    assert closed_forms(dev, wall, 0.0)[1] == kl  # the linear bound does not depend on the impact speed


def test_controlled_linear_small_rate_cli_prints_finite_numbers(capsys):
    """`dfa stiffness --virtual-damping` at (b + B)T/m = 2e-11 (formerly: one line on stderr, exit 2): the JSON and
    the text state the finite K_linear. At impact speed 0: the closed forms without the four-way search (K_linear
    does not depend on the speed, the test above)."""
    argv = [*SMALL_RATE_ARGV, "--velocity", "0"]
    assert main([*argv, "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["k_linear"]["value"] == pytest.approx(SMALL_RATE_K_LINEAR, rel=1e-9)  # no NaN, not 0
    assert rec["k_linear"]["status"] == "found"
    assert main(argv) == 0
    row = next(line for line in capsys.readouterr().out.splitlines() if line.startswith("exact linear bound"))
    kl = closed_forms(SMALL_RATE_DEVICE, SMALL_RATE_WALL, 0.0)[1]
    assert f"  {limit_text(kl, 'N/m')}  " in row and limit_text(kl, "N/m") == "5.7143e-06 N/m"  # the K column


def test_controlled_linear_small_rate_catalogue_delta_filter_lag_mpmath():
    """Delta (bT/m ≈ 1.3e-5) with B = 1e-6, 30 Hz filter, 200 Hz amplifier: K_crit to 1e-9 (60+ digits). The float
    ray analysis gave 10.3915617704 N/m, 3e-8 above the boundary (unstable); the series gives 10.3915614443."""
    from dfa.model.catalogue import get_device

    dev = get_device("Delta").device
    k = _check(dev.mass, dev.damping, Wall.of(1.0, 1e-6, 0, 30.0, 200.0), rel=1e-9, period=dev.period)
    assert k == pytest.approx(10.391561444, rel=1e-10)


@pytest.mark.parametrize(
    "beta, d, ctl",
    [
        (0.45, 0, None),
        (0.55, 0, None),
        (2.4, 2, None),
        (2.6, 2, None),
        (1.5, 1, {"a_b": 0.2, "cutoff": 0.05, "lag": 0.3}),
        (1.7, 1, {"a_b": 0.2, "cutoff": 0.05, "lag": 0.3}),
    ],
)
def test_linear_stable_small_rate_verdict_mpmath(beta, d, ctl):
    """linear_stable at μ = 1e14 (β/μ ~ 1e-14): formerly the float spectral radius (rounding decided it: at μ = 1e16,
    β = 0.55 > β_crit ≈ ½ came out unstable); now the small-rate bound, against 60+ digit mpmath."""
    from dfa.analysis.linear import linear_stable
    from dfa.model.wall import WallParams

    mu = 1e14
    wall = WallParams.of(delay=d)
    if ctl is not None:
        wall = WallParams.of(damping=ctl["a_b"], delay=d, cutoff=ctl["cutoff"], lag=ctl["lag"])
    extra = {} if ctl is None else {**ctl, "a_b": ctl["a_b"] / mu}
    truth = _rho_mp(beta / mu, 1.0 / mu, d, **extra) < 0.0
    assert bool(linear_stable(mu, beta, wall=wall)) is truth


@pytest.mark.parametrize("bandwidth", [1.0, 0.01, 1e-6])
def test_controlled_linear_small_rate_slow_amplifier_former_counterexample_mpmath(bandwidth):
    """(b + B)T/m = 1e-7 (m = 1e4 kg, b = B = 0.5, T = 1 ms) with a slow amplifier (α = 159, 15915 samples): the float
    ray analysis gave K_crit 3e-5 above the boundary (1 Hz) and a false 'never stable' (0.01 Hz); α = 1.6e8 (1 μHz)."""
    _check(1e4, 0.5, Wall.of(1.0, 0.5, 0, None, bandwidth), rel=1e-6)


def test_limit_cycles_linear_verdict_with_controller_uses_the_small_rate_bound():
    """dfa.analysis.cycles' linear verdict with a controller is dfa.analysis.linear.linear_stable's (the float spectral radius
    alone said unstable at μ = 1e16, β = 0.55 with a tiny damper, where the loop is stable)."""
    from dfa.analysis.cycles.controlled import linear_stable_of
    from dfa.analysis.linear import linear_stable
    from dfa.model.wall import WallParams

    c = WallParams.of(damping=1e-3, delay=1)
    for mu, beta in ((1e16, 0.55), (1e16, 0.1), (100.0, 0.5), (100.0, 0.1)):
        assert linear_stable_of(mu, beta, c) == bool(linear_stable(mu, beta, wall=c))
    assert linear_stable_of(1e16, 2.0, c) and not linear_stable_of(1e16, 0.5, c)
