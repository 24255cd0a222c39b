"""A run diverges only far beyond its start's energy amplitude √(2 H_T(0)) (eq. 18-19).

Red-team finding: with a fixed 10⁶-tick bound, `dfa simulate` called a fine-encoder impact (Impulse Engine,
Δ = 10 nm, K = 10 N/m, 0.5 m/s: region a, passive at every speed by eq. 6) "unstable: diverged" after 11 samples,
because the impact's own travel (A₀ ≈ 2.8·10⁶ ticks) passed the bound.
"""

import json
import math

from dfa.analysis.simulation import divergence_bound, stored_energy
from dfa.cli import main

ARGV = ["simulate", "--device", "impulse", "--resolution", "1e-8", "--velocity", "0.5", "--stiffness", "10"]


def test_eq19_fine_encoder_impact_is_not_called_divergent(capsys):
    assert main(["check", *ARGV[1:], "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["region"] == "a"  # passive at every speed (proven)
    assert main([*ARGV, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["outcome"] == "rest"


def test_eq19_divergence_bound_is_beyond_the_energy_amplitude():
    for xi0, xd, mu in [(0.0, 1e5, 800.0), (3.5, 0.0, 1.0), (0.0, 0.2, 100.0)]:
        amp0 = math.sqrt(2 * float(stored_energy(xi0, xd, mu)))
        assert divergence_bound(xi0, xd, mu) >= max(1e6, 100 * amp0)


def test_eq19_design_analysis_finds_no_divergence_where_eq6_proves_passivity():
    """Region a (β >= ½, σ >= ½): no simulated unstable speed, and the impacts rest (the report's numbers)."""
    import dataclasses

    from dfa.model.catalogue import get_device
    from dfa.studies.design import design_analysis

    dev = dataclasses.replace(get_device("impulse").device, resolution=1e-8)
    a = design_analysis(dev, 10.0, velocity=0.5, map_grid=3, samples=30_000, n_jobs=1)
    assert a.criterion.region == "a" and a.criterion.passive
    assert a.simulated_xi_dot is None
    assert a.outcome.outcome == "rest" and a.outcome_high.outcome == "rest"


def test_eq19_map_cli_calls_no_region_a_point_unstable(capsys, tmp_path):
    """`dfa map` at ξ'0 = 10⁵ ticks/sample, μ = 800 (A₀ ≈ 2.8·10⁶): β, σ >= ½ is passive (eq. 6), never unstable."""
    argv = ["map", "--mu", "800", "--xi-dot", "1e5", "--beta-range", "0.6", "1", "--sigma-range", "0.6", "2"]
    argv += ["--grid", "3", "--samples", "2000", "--out", str(tmp_path / "m.npz"), "--quiet", "--json", "--jobs", "1"]
    assert main(argv) == 0
    assert json.loads(capsys.readouterr().out)["counts"][0]["unstable"] == 0


def test_eq19_api_defaults_never_call_a_proven_passive_impact_unstable():
    # red-team finding left open: dfa.simulate(800, 1, 2.4e5, 1e5) said "unstable" with the fixed default
    # bound of 1e6 ticks while the criterion proves the point passive (region a) and the impact's own travel
    # is ~2.8e6 ticks. The library defaults now use divergence_bound as the CLI does.
    import dfa

    crit = dfa.passivity_criterion(1.0, 2.4e5, 1e5)
    assert crit.passive
    assert dfa.simulate(800.0, 1.0, 2.4e5, 1e5, record=False).outcome != "unstable"
    b = dfa.analysis.simulation.simulate_batch(800.0, [1.0, 1.0], [2.4e5, 2.4e5], [1e5, 1.0], samples=20000)
    assert "unstable" not in b.outcomes()
    m = dfa.stability_map(800.0, [1e5], beta_range=(0.5, 1.0), sigma_range=(0.5, 2.0), grid=3, samples=20000, n_jobs=1)
    assert m.counts()[0]["unstable"] == 0
    # and a run that does diverge still does under the default
    assert dfa.simulate(100.0, 0.0, 0.2, 5.0, 20000, record=False).outcome == "unstable"
