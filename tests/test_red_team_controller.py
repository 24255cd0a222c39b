"""Red-team findings on the controller analyses (issue 15): regressions and one open counterexample.

Each test reproduces one finding of the red team at commit 47174bf: bad input that was
silently accepted or crashed with a Python error, and (xfail, strict) a wrong
"never stable" verdict of the exact linear bound with a very slow velocity filter.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from dfa.analysis.colgate_schenkel import colgate_schenkel_beta
from dfa.analysis.linear_wall import controlled_characteristic_polynomial, stable_stiffness
from dfa.analysis.simulation import simulate, simulate_batch
from dfa.errors import DFATypeError, DFAValueError
from dfa.model.wall import Wall, WallParams

CTL = WallParams.of(damping=0.2, delay=1, cutoff=0.1)


@pytest.mark.parametrize("delay", [True, 1 + 0j, "1"])
def test_wall_delay_must_be_a_whole_number(delay):
    # was accepted: True == 1 and (1 + 0j) == 1; the delay is checked where the wall is built
    with pytest.raises(DFATypeError, match=r"^delay = .* whole number"):
        WallParams.of(damping=0.2, delay=delay, cutoff=0.1)


def test_simulate_takes_the_delay_from_the_wall_only():
    with pytest.raises(TypeError, match=r"delay"):
        simulate(20.0, 0.3, 0.7, 1.0, samples=10, delay=2, wall=CTL)
    with pytest.raises(TypeError, match=r"delay"):
        simulate_batch([20.0], [0.3], [0.7], [1.0], 10, delay=1, wall=CTL)


@pytest.mark.parametrize("quantize", ["False", None, 0, 1.0, [True]])
def test_simulate_quantize_must_be_a_bool(quantize):
    # was bool(quantize): quantize="False" ran the loop with the encoder
    with pytest.raises(DFATypeError, match=r"^quantize = .* must be True .* or False"):
        simulate(20.0, 0.3, 0.7, 1.0, samples=10, quantize=quantize)
    with pytest.raises(DFATypeError, match=r"^quantize = "):
        simulate(20.0, 0.3, 0.7, 1.0, samples=10, quantize=quantize, wall=CTL)
    with pytest.raises(DFATypeError, match=r"^quantize = "):
        simulate_batch([20.0], [0.3], [0.7], [1.0], 10, quantize=quantize)


def test_simulate_quantize_numpy_bool_equals_python_bool():
    a = simulate(20.0, 0.3, 0.7, 1.0, samples=200, quantize=np.bool_(False), wall=CTL)
    b = simulate(20.0, 0.3, 0.7, 1.0, samples=200, quantize=False, wall=CTL)
    assert a.quantize is False and np.array_equal(a.xi, b.xi)


@pytest.mark.parametrize("period", [5e-324, 1e-160])
def test_stable_stiffness_subnormal_period_is_the_package_error(period):
    # was ZeroDivisionError in K = κ m/T² (T² underflows to 0)
    with pytest.raises(DFAValueError, match=r"^period = .* mass/period² must be finite"):
        stable_stiffness(1.0, 1.0, period, Wall.of(1.0))


@pytest.mark.parametrize("cutoff", [1e-300, 1e-18])
def test_filter_cutoff_whose_pole_rounds_to_one_is_refused(cutoff):
    # was ZeroDivisionError in colgate_schenkel_beta (curvature bound divides by 1 − a = 0)
    assert math.exp(-2.0 * math.pi * cutoff) == 1.0
    with pytest.raises(DFAValueError, match=r"^cutoff = .* at least 0.001 cycles per sample"):
        colgate_schenkel_beta(WallParams.of(damping=1.0, cutoff=cutoff))
    with pytest.raises(DFAValueError, match=r"at least 0.001 Hz \(0.001 cycles per sample; below"):
        Wall.of(1.0, damping=1.0, filter_cutoff=cutoff).params(1.0)
    assert WallParams.of(damping=1.0, cutoff=1e-3).filter_pole < 1.0  # the smallest accepted still filters


# A counterexample found by the red team and not fixed: b ≈ 0, a large damper behind a
# very slow filter (ν_c = 1e-6 cycles per sample), delay 3 and an amplifier lag.
SLOW = dict(mass=1.3209770941153516, damping=0.0002846187896837431, period=0.0005603865033489327)
SLOW_CTL = dict(damping=9.183334519574379, delay=3, filter_cutoff=1e-6 / 0.0005603865033489327)
SLOW_CTL["amplifier_bandwidth"] = 588.1529142369977


def _radius_mp(mu: float, beta: float, params: WallParams) -> float:
    """Spectral radius of the loop's own characteristic polynomial, roots in 60 digits."""
    mpmath.mp.dps = 60
    c = controlled_characteristic_polynomial(mu, beta, params)
    roots = mpmath.polyroots([mpmath.mpf(float(x)) for x in c], maxsteps=400, extraprec=400)
    return float(max(abs(r) for r in roots))


def test_slow_filter_is_refused_not_misjudged():
    """ν_c = 1e-6: the loop is stable at small K (60-digit roots) but double precision called it 'never': refused."""
    k, t = 0.05, SLOW["period"]
    p = WallParams.of(damping=SLOW_CTL["damping"] / (k * t), delay=3, cutoff=1e-3, lag=1.0 / (2 * math.pi * 588.15 * t))
    good = p.to_dict() | {"cutoff": 1e-6}
    assert _radius_mp(SLOW["mass"] / (k * t * t), SLOW["damping"] / (k * t), WallParams.of(**p.to_dict())) < 1.0
    with pytest.raises(DFAValueError, match=r"cutoff = 1e-06 is invalid: it must be at least 0.001 cycles per sample"):
        WallParams.of(**good)
    with pytest.raises(DFAValueError, match=r"filter_cutoff = .* it must be at least 1.78.* Hz"):
        Wall.of(1.0, **SLOW_CTL).params(t)


def test_slow_filter_at_the_floor_linear_bound_agrees_with_60_digit_roots():
    """At the smallest accepted cutoff the exact bound's verdicts match high-precision roots on both sides."""
    m, b, t = SLOW["mass"], SLOW["damping"], SLOW["period"]
    ctl = dict(SLOW_CTL, filter_cutoff=1e-3 / t)
    r = stable_stiffness(m, b, t, Wall.of(1.0, **ctl))
    assert r.status.value != "never" and r.k_crit > 0
    for k, stable in ((0.5 * r.k_crit, True), (1.05 * r.k_crit, False)):
        p = Wall.of(k, **ctl).params(t)
        assert (_radius_mp(m / (k * t * t), b / (k * t), p) < 1.0) is stable
