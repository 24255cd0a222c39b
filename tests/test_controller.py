"""The controller model (issue 15): validation, dimensionless groups, the pure spring."""

from __future__ import annotations

import math

import control
import numpy as np
import pytest

from dfa import DFATypeError, DFAValueError, Wall, WallParams


def test_controller_dimensionless_groups_match_definitions():
    c = Wall.of(stiffness=2000.0, damping=3.0, delay=2, filter_cutoff=50.0, amplifier_bandwidth=400.0)
    t = 5e-4
    p = c.params(t)
    assert p.damping == pytest.approx(3.0 / (2000.0 * t), rel=1e-15)
    assert p.delay == 2
    assert p.cutoff == pytest.approx(50.0 * t, rel=1e-15)
    assert p.lag == pytest.approx(1.0 / (2 * math.pi * 400.0) / t, rel=1e-15)
    assert p.filter_pole == pytest.approx(math.exp(-2 * math.pi * 50.0 * t), rel=1e-15)
    assert p.amplifier_pole == pytest.approx(math.exp(-t * 2 * math.pi * 400.0), rel=1e-12)
    assert not p.is_spring


def test_controller_spring_is_paper_model():
    p = Wall.of(300.0, delay=3).params(1e-3)
    assert p.is_spring and p == WallParams.of(delay=3)
    d = WallParams.of().to_dict()
    assert d.pop("null_reasons") == {"/cutoff": "no velocity filter"}
    assert d == {"damping": 0.0, "delay": 0, "cutoff": None, "lag": 0.0}


def test_controller_filter_pole_equals_c2d_zoh():
    """The filter recursion y_h = a y_{h-1} + (1 - a) v_{h-1} is control.c2d(ω/(s+ω), T, 'zoh')."""
    fc, t = 120.0, 1e-3
    w = 2 * math.pi * fc
    d = control.c2d(control.tf([w], [1, w]), t, method="zoh")
    a = Wall.of(1.0, filter_cutoff=fc).params(t).filter_pole
    num, den = np.ravel(d.num[0][0]), np.ravel(d.den[0][0])
    assert den[-1] / den[0] == pytest.approx(-a, rel=1e-12)
    assert num[-1] / den[0] == pytest.approx(1 - a, rel=1e-12)


@pytest.mark.parametrize(
    ("kwargs", "exc", "words"),
    [
        ({"stiffness": -1.0}, DFAValueError, "stiffness"),
        ({"stiffness": 1.0, "damping": -0.1}, DFAValueError, "damping"),
        ({"stiffness": 1.0, "delay": 1.5}, DFAValueError, "delay"),
        ({"stiffness": 1.0, "filter_cutoff": 0.0}, DFAValueError, "filter_cutoff"),
        ({"stiffness": 1.0, "amplifier_bandwidth": -5.0}, DFAValueError, "amplifier_bandwidth"),
        ({"stiffness": "1"}, DFATypeError, "stiffness"),
    ],
)
def test_controller_bad_input_names_parameter(kwargs, exc, words):
    with pytest.raises(exc, match=words):
        Wall.of(**kwargs)


def test_controller_cutoff_above_nyquist_is_refused_with_the_fix():
    c = Wall.of(1.0, filter_cutoff=600.0)
    with pytest.raises(DFAValueError, match=r"filter_cutoff = 600.*Nyquist frequency 500.*below"):
        c.params(1e-3)
    with pytest.raises(DFAValueError, match="cutoff"):
        WallParams.of(cutoff=0.5)


def test_controller_subnormal_lag_refused_shortest_lag_runs(capsys):
    """α = 5e-324 made the kernel's rate 1/α infinite (a ZeroDivisionError, or NaN: "unstable" for a decaying
    loop, found by hypothesis); α below MIN_LAG is refused with the fix, α = MIN_LAG runs like no lag."""
    from dfa import simulate
    from dfa.cli import main
    from dfa.model.wall import MIN_LAG

    with pytest.raises(DFAValueError, match=r"lag = 5e-324 is invalid: it must be 0 or at least 1e-300.*pass 0"):
        WallParams.of(damping=1.0, lag=5e-324)
    runs = [
        simulate(100.0, 0.0, 0.0, 10.0, None, quantize=False, record=False, bound=1e12, wall=c)
        for c in (WallParams.of(damping=1.0, lag=MIN_LAG), WallParams.of(damping=1.0))
    ]
    assert [r.outcome for r in runs] == ["rest", "rest"]
    assert main(["stiffness", "--device", "delta", "--velocity", "0.1", "--amplifier-bandwidth", "1e306"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "--amplifier-bandwidth 1e+306 Hz is too large" in err  # the value typed
    assert "below the shortest lag" in err and "give --amplifier-bandwidth in Hz below" in err  # issue 41
