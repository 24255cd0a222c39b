"""Colgate–Schenkel passivity with a general discrete controller (issue 15 item 2): dfa.analysis.colgate_schenkel.

Checked against: the closed forms of Colgate & Schenkel (1997) — pure spring d = 0:
b > KT/2 (paper eq. 8); spring and damper d = 0: b > KT/2 + B; the spring with a delay
of d samples: b > KT(d + ½), derived here with sympy (the limit θ → 0 of the condition's
ratio, which is its maximum) and equal to the delay line β = ½ + d of eq. 6 in dfa.analysis.criterion
(dfa.k_colgate with a delay); a brute-force evaluation of the condition as written,
Re{(1 − e^{−jθ}) H(e^{jθ})}/(1 − cos θ) on a dense grid, for random controllers; the
refusal with an amplifier lag.
"""

import json
import math

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from result_json import assert_json_from_fields, written

from dfa import Device, Wall, WallParams, k_colgate
from dfa.analysis.colgate_schenkel import PassivityStatus, colgate_schenkel_beta, colgate_schenkel_damping
from dfa.errors import DFAValueError
from dfa.jsonable import dumps


def test_colgate_schenkel_spring_d0_is_eq8():
    """Spring, d = 0: b_min = KT/2 (eq. 8), the ratio being 1 at every ω."""
    r = colgate_schenkel_damping(Wall.of(3000.0), 1e-3)
    assert r.damping_min == pytest.approx(1.5, rel=1e-12) and r.damping_bound >= 1.5
    assert r.status is PassivityStatus.CERTIFIED and r.damping_bound - r.damping_min <= 1e-11


@pytest.mark.parametrize("big_b", [0.01, 0.5, 3.0, 40.0])
def test_colgate_schenkel_spring_damper_d0(big_b):
    """Spring + damper, d = 0: b_min = KT/2 + B, at the Nyquist frequency ω = π/T."""
    r = colgate_schenkel_damping(Wall.of(2000.0, damping=big_b), 1e-3)
    assert r.damping_min == pytest.approx(1.0 + big_b, rel=1e-12)
    assert r.omega == pytest.approx(math.pi / 1e-3, rel=1e-9) and r.frequency == pytest.approx(500.0, rel=1e-9)


@pytest.mark.parametrize("d", [1, 2, 3, 5, 12])
def test_colgate_schenkel_spring_with_delay_sympy(d):
    """Spring with delay d: the condition's ratio, derived with sympy, peaks at θ → 0 with 2d + 1: b_min = KT(d + ½)."""
    th = sp.symbols("theta", real=True)
    ratio = sp.re(sp.expand_complex((1 - sp.exp(-sp.I * th)) * sp.exp(-sp.I * d * th))) / (1 - sp.cos(th))
    peak = sp.limit(ratio, th, 0)
    assert peak == 2 * d + 1
    f = sp.lambdify(th, ratio, "numpy")
    grid = np.linspace(1e-4, math.pi, 20001)
    assert np.max(f(grid)) <= 2 * d + 1  # θ → 0 is the maximum (Dirichlet kernel)
    r = colgate_schenkel_beta(WallParams.of(delay=d))
    assert r.beta_min == pytest.approx(float(peak) / 2, rel=1e-12) and r.theta == 0.0
    # the delay line of eq. 6: passive at every speed for b >= K T (½ + d), i.e. K <= b/(T(½ + d))
    dev = Device(mass=0.1, damping=2.0, coulomb=0.1, resolution=1e-5, period=1e-3)
    k = k_colgate(dev, delay=d)
    assert colgate_schenkel_damping(Wall.of(k, delay=d), 1e-3).damping_min == pytest.approx(2.0, rel=1e-12)


def _brute(p: WallParams) -> float:
    """½ max of Re{(1 − e^{−jθ}) H̃(e^{jθ})}/(1 − cos θ) as written (H̃ from the controller's definition), dense grid."""
    th = np.linspace(0.02, math.pi, 100001)  # from 0.02: 1 − cos θ without cancellation (rel. error < 1e-12)
    z = np.exp(1j * th)
    filt = 1.0 if p.cutoff is None else (1.0 - p.filter_pole) / (z - p.filter_pole)
    h = z ** (-p.delay) * (1.0 + p.damping * (1.0 - 1.0 / z) * filt)
    return 0.5 * float(np.max(np.real((1.0 - 1.0 / z) * h) / (1.0 - np.cos(th))))


@settings(max_examples=30)
@given(
    p=st.builds(
        WallParams.of,
        damping=st.floats(0.0, 20.0),
        delay=st.integers(0, 6),
        cutoff=st.one_of(st.none(), st.floats(1e-3, 0.49)),
    )
)
def test_colgate_schenkel_max_is_certified_vs_brute_force(p):
    """The certified bound is >= every value of the condition as written; the best value found is attained (>= grid)."""
    r = colgate_schenkel_beta(p)
    brute = _brute(p)
    assert r.beta_bound >= brute - 1e-12 * max(1.0, abs(brute))
    assert r.beta_min >= brute - 1e-9 * max(1.0, abs(brute))
    assert r.beta_bound - r.beta_min <= 1e-11 * max(1.0, abs(r.beta_min))
    assert r.status is PassivityStatus.CERTIFIED


def test_colgate_schenkel_refuses_amplifier_lag():
    with pytest.raises(DFAValueError, match="amplifier lag .* Colgate–Schenkel"):
        colgate_schenkel_damping(Wall.of(1000.0, amplifier_bandwidth=500.0), 1e-3)
    with pytest.raises(DFAValueError, match="zero-order hold drives the device directly"):
        colgate_schenkel_beta(WallParams.of(lag=0.1))


def test_colgate_schenkel_physical_is_dimensionless_times_kt_and_json():
    c = Wall.of(1500.0, damping=0.7, delay=1, filter_cutoff=80.0)
    r = colgate_schenkel_damping(c, 1e-3)
    assert r.damping_min == 1500.0 * 1e-3 * r.dimensionless.beta_min
    assert r.omega == r.dimensionless.theta / 1e-3
    assert r.passive(r.damping_bound * 1.001) and not r.passive(r.damping_min * 0.999)
    data = json.loads(dumps(r.to_dict()))
    assert data["damping_min"] == written(r.damping_min) and data["wall"]["filter_cutoff"] == 80.0
    assert data["dimensionless"]["params"]["delay"] == 1


def test_large_delay_is_fast_and_exact():
    """d = MAX_DELAY: Dirichlet kernel in closed form, maximum 2d + 1 at θ = 0 (no per-k sum): β_min = d + ½."""
    from dfa.checks import MAX_DELAY

    r = colgate_schenkel_beta(WallParams.of(delay=MAX_DELAY))
    assert r.beta_min == pytest.approx(MAX_DELAY + 0.5, rel=1e-12) and r.status is PassivityStatus.CERTIFIED


def test_colgate_schenkel_json_from_its_fields():
    """ColgateSchenkel and ColgateSchenkelDamping write the Result base's JSON; the wall is under "wall"."""
    assert_json_from_fields(colgate_schenkel_beta(WallParams.of(damping=0.3, cutoff=0.05)))
    r = colgate_schenkel_damping(Wall.of(1500.0, damping=0.7, filter_cutoff=80.0), 1e-3)
    d = assert_json_from_fields(r)
    assert d["wall"] == json.loads(dumps(r.wall.to_dict())) and "controller" not in d
    assert d["status"] == r.status.value and d["frequency"] == r.frequency
