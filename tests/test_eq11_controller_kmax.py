"""K_max with a wall controller (issue 15 item 5): the extended criterion (eq. 6/11) and the exact linear bound.

Independent checks: the physical closed form of the extended criterion (dfa.analysis.criterion docstring,
(b − B − KT(½ + d))|v| + (c − KΔ/2 − (1 − a)BΔ/T) >= 0 and c >= KΔ/2 + (1 − a)BΔ/T) against the bisection,
the spring's eq. 11 K_max, a scan over exact simulations with the controller (no divergence at or below
K_criterion), and a scan over linear simulations across the exact linear bound.
"""

import json
import math

import pytest

from dfa.analysis.limits.closed_form import stiffness_limits
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.linear_wall import stable_stiffness
from dfa.analysis.simulation import simulate
from dfa.model.catalogue import get_device
from dfa.model.device import Device
from dfa.model.wall import Wall
from dfa.render.limits import kmax_rows
from dfa.results.status import KMaxStatus, LimitStatus

DELTA = get_device("Delta").device


def _closed_form(dev, ctl, v):
    b, c, dx, t = dev.damping, dev.coulomb, dev.resolution, dev.period
    a = 0.0 if ctl.filter_cutoff is None else math.exp(-2 * math.pi * ctl.filter_cutoff * t)
    q = c - (1 - a) * ctl.damping * dx / t
    return max(0.0, min(q / (dx / 2), ((b - ctl.damping) * v + q) / (t * (0.5 + ctl.delay) * v + dx / 2)))


@pytest.mark.parametrize(
    "ctl",
    [
        Wall.of(1.0, damping=1.0),
        Wall.of(1.0, damping=1.0, delay=1, filter_cutoff=100.0),
        Wall.of(1.0, damping=3.0, delay=2, filter_cutoff=20.0),
        Wall.of(1.0, damping=40.0),  # more damper than the friction can pay for: no K at all
    ],
)
@pytest.mark.parametrize("v", [0.01, 0.1, 1.0])
def test_eq11_controller_k_criterion_equals_closed_form(ctl, v):
    r = design_answer(DELTA, v, wall=ctl, simulate=False)  # the quick answer: k_criterion is what is tested
    want = _closed_form(DELTA, ctl, v)
    if want > 0.0:
        assert r.k_criterion.status is LimitStatus.FOUND
        assert r.k_criterion.value == pytest.approx(want, rel=1e-9, abs=1e-9)
    else:  # no K at all: None, and why (σ >= σ₀ fails at every K when c/Δ <= (1 − a)B/T, whatever the speed)
        assert r.k_criterion.value is None
        q = DELTA.coulomb - (1 - ctl.params(DELTA.period).filter_pole) * ctl.damping * DELTA.resolution / DELTA.period
        assert r.k_criterion.status is (LimitStatus.NEVER if q <= 0.0 else LimitStatus.NONE_PROVEN)


@pytest.mark.parametrize("v", [0.01, 0.1, 1.0])
def test_eq11_spring_controller_is_the_spring_k_max(v):
    r = design_answer(DELTA, v, wall=Wall.of(1.0), simulate=False)  # closed forms: the quick answer
    s = stiffness_limits(DELTA, v)
    assert r.k_criterion.value == pytest.approx(s.k_max, rel=1e-9)
    assert r.k_linear.value == pytest.approx(s.k_gil, rel=1e-9)


@pytest.mark.parametrize("ctl", [Wall.of(1.0, damping=1.0), Wall.of(1.0, damping=1.0, delay=1, filter_cutoff=100.0)])
def test_eq6_controller_k_criterion_sound_by_simulation(ctl):
    """No impact up to the speed diverges at any K the extended criterion proves passive (exact simulation)."""
    v = 0.1
    r = design_answer(DELTA, v, wall=ctl, simulate=False)  # k_criterion is what is tested: the quick answer
    kc = r.k_criterion.value
    assert kc is not None and kc > 0
    for k in (kc, 0.5 * kc, 0.1 * kc):
        c = Wall.of(k, ctl.damping, ctl.delay, ctl.filter_cutoff).params(DELTA.period)
        p = DELTA.params(k)
        for i in (1, 2, 3, 4):
            run = simulate(p.mu, p.beta, p.sigma, DELTA.xi_dot(v * i / 4), 20_000, wall=c)
            assert run.outcome != "unstable", (k, i, run.outcome)


@pytest.mark.parametrize(
    "ctl",
    [Wall.of(1.0, damping=0.5), Wall.of(1.0, damping=0.5, delay=1), Wall.of(1.0, amplifier_bandwidth=300.0)],
)
def test_controller_k_linear_matches_a_linear_simulation_scan(ctl):
    """Without encoder and Coulomb friction the loop is linear: it decays below K_linear and diverges above."""
    dev = Device(mass=0.1, damping=1.0, coulomb=0.0, resolution=1e-5, period=1e-3)
    kl = design_answer(dev, 0.1, wall=ctl, simulate=False).k_linear.value  # the quick answer: its exact linear bound
    assert kl is not None and kl > 0
    for k, diverges in ((0.9 * kl, False), (1.1 * kl, True)):
        c = Wall.of(k, ctl.damping, ctl.delay, ctl.filter_cutoff, ctl.amplifier_bandwidth).params(dev.period)
        p = dev.params(k)
        run = simulate(p.mu, p.beta, 0.0, 1.0, 200_000, quantize=False, bound=1e8, wall=c)
        assert (run.outcome == "unstable") is diverges, (k, run.outcome)


def test_controller_lag_criterion_not_covered():
    """With an amplifier lag no criterion covers the wall: K_criterion is None with status not_covered (its message
    in the JSON and the rows), and there is no criterion for a simulated divergence to contradict: no
    counterexample, whatever the runs (the former ``counterexample_check`` sentence: the status says it now)."""
    ctl = Wall.of(1.0, damping=1.0, amplifier_bandwidth=300.0)
    r = design_answer(DELTA, 0.1, wall=ctl, speeds=2, grid=6)
    assert r.k_criterion.value is None and r.k_criterion.status is LimitStatus.NOT_COVERED
    assert r.k_linear.value == stable_stiffness(DELTA.mass, DELTA.damping, DELTA.period, ctl).k_crit
    assert r.counterexamples == () and r.status is not KMaxStatus.COUNTEREXAMPLE  # nothing to contradict
    d = json.loads(json.dumps(r.to_dict(), allow_nan=False))
    assert d["k_criterion"]["value"] is None and d["k_criterion"]["status"] == "not_covered"
    assert d["k_criterion"]["null_reasons"]["/value"] == LimitStatus.NOT_COVERED.message
    assert d["counterexamples"] == [] and d["status"] != "counterexample"
    row = next(v for k, v in kmax_rows(r) if k.startswith("criterion K_max"))
    assert row == f"none: {LimitStatus.NOT_COVERED.message}" and "amplifier lag" in row
