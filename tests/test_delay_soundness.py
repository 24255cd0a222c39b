"""Soundness of the delay-aware criterion by exact simulation (dfa.analysis.soundness; issue 12 item 6), fast version.

The full run (10⁵ points per d) is committed as reports/validation/delay_soundness.md.
"""

import numpy as np
import pytest

import dfa
from dfa.analysis import soundness
from dfa.analysis.soundness import delay_soundness, run_samples, sample_passive_points
from dfa.model.wall import WallParams


@pytest.mark.parametrize("d", [0, 1, 2, 3])
def test_eq6_delay_sampled_passive_points_never_gain_energy(d):
    r = delay_soundness(1000, d, seed=100 + d)
    assert r.points == 1000 and r.violations == 0 and r.energy_grew == 0 and r.diverged == 0
    assert r.worst_growth <= soundness.TOLERANCE
    assert r.by_kind["line"] > 200 and r.by_kind["sigma-edge"] > 80 and r.by_kind["beta-edge"] > 80


@pytest.mark.parametrize("d", [1, 2, 3])
def test_eq6_delay_the_same_sampler_finds_violations_of_the_d_ignoring_criterion(d):
    r = delay_soundness(300, d, criterion="d-ignoring", seed=100 + d)
    assert r.energy_grew > 30 and r.diverged > 10  # the bug of issue 12: eq. 6 unchanged is unsound with a delay


def test_eq19_the_same_sampler_finds_violations_of_the_xi0_ignoring_criterion_at_zero_delay():
    r = delay_soundness(1000, 0, criterion="d-ignoring", seed=7, mu_range=(0.1, 10.0))
    assert r.energy_grew > 0


def test_sampler_points_are_passive_and_on_the_boundaries():
    pts = sample_passive_points(200, 2, seed=3)
    b0 = 2.5
    for i in range(200):
        r = dfa.passivity_criterion(
            pts["beta"][i],
            pts["sigma"][i],
            pts["xi_dot"][i],
            wall=WallParams.of(delay=2),
            xi0=pts["xi0"][i],
            mu=pts["mu"][i],
        )
        assert r.passive
        kind = soundness.KINDS[pts["kind"][i]]
        if kind == "line":
            assert r.margin == pytest.approx(0.0, abs=1e-12 * max(1.0, r.sigma))
        elif kind == "sigma-edge":
            assert pts["sigma"][i] == 0.5 and pts["beta"][i] >= b0
        elif kind == "beta-edge":
            assert pts["beta"][i] == b0 and pts["sigma"][i] >= 0.5
    assert np.mean(pts["xi0"] == 0.0) == pytest.approx(0.5, abs=0.15)


def test_run_length_is_twenty_undamped_periods_at_least_2000():
    assert run_samples(1.0) == 2000
    assert run_samples(1e4) == int(np.ceil(20 * 2 * np.pi * 100))


def test_markdown_summary_lists_every_run():
    rs = [delay_soundness(20, d, seed=1) for d in (0, 1)]
    md = soundness.soundness_markdown(rs)
    assert md.count("| delay-aware |") == 2 and "violations" in md
