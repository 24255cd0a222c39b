"""Soundness of the delay-aware criterion by exact simulation (dfa.studies.soundness, the spring with delay d as
the wall WallParams.of(delay=d); issue 12 item 6), fast version.

The full run (10⁵ points per d) is committed as reports/validation/delay_soundness.md
(python -m dfa.cli.soundness_report).
"""

import math

import numpy as np
import pytest

import dfa
from dfa.model.wall import WallParams
from dfa.studies import soundness
from dfa.studies.soundness import Population, criterion_soundness, run_samples, sample_passive_points
from dfa.studies.soundness_document import soundness_markdown


@pytest.mark.parametrize("d", [0, 1, 2, 3])
def test_eq6_delay_sampled_passive_points_never_gain_energy(d):
    r = criterion_soundness(1000, Population(delay=d), seed=100 + d)
    assert r.criterion == "delay-aware" and r.delay == d
    assert r.points == 1000 and r.violations == 0 and r.energy_grew == 0 and r.diverged == 0
    assert r.worst_growth <= soundness.TOLERANCE
    assert r.by_kind["line"] > 200 and r.by_kind["sigma-edge"] > 80 and r.by_kind["beta-edge"] > 80


@pytest.mark.parametrize("d", [1, 2, 3])
def test_eq6_delay_the_same_sampler_finds_violations_of_the_d_ignoring_criterion(d):
    r = criterion_soundness(300, Population(delay=d), criterion="d-ignoring", seed=100 + d)
    assert r.energy_grew > 30 and r.diverged > 10  # the bug of issue 12: eq. 6 unchanged is unsound with a delay


def test_eq19_the_same_sampler_finds_violations_of_the_xi0_ignoring_criterion_at_zero_delay():
    r = criterion_soundness(1000, Population(delay=0, mu_range=(0.1, 10.0)), criterion="d-ignoring", seed=7)
    assert r.energy_grew > 0


def test_eq6_delay_sampler_points_are_passive_and_on_the_boundaries():
    pts = sample_passive_points(200, Population(delay=2), seed=3)
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
    # every point's wall is the spring with the delay, with the encoder
    assert (pts["delay"] == 2).all() and (pts["damping"] == 0.0).all() and np.isnan(pts["cutoff"]).all()
    assert pts["quantized"].all()


def test_eq6_delay_run_length_is_twenty_undamped_periods_at_least_2000():
    assert run_samples(1.0) == 2000
    assert run_samples(1e4) == int(np.ceil(20 * 2 * np.pi * 100))


def test_eq6_delay_markdown_summary_lists_every_run():
    rs = [criterion_soundness(20, Population(delay=d), seed=1) for d in (0, 1)]
    md = soundness_markdown(rs)
    assert md.count("| delay-aware |") == 2 and "violations" in md
    assert "python -m dfa.cli.soundness_report" in md


def _independent_counts(pts, d):
    """The counts of a spring-with-delay record recomputed from scratch: each point re-simulated with dfa.simulate
    (the wall WallParams.of(delay=d), bound 10⁶), its storage S = ½μξ'² + ½ξ² at every sample it ran (inf past the
    bound), the divergence from the run's outcome, and the tally written out here."""
    n = len(pts["mu"])
    ratio, at, div, lengths = np.empty(n), np.empty(n, dtype=int), np.empty(n, dtype=bool), np.empty(n, dtype=int)
    for i in range(n):
        mu, x0, v0 = pts["mu"][i], pts["xi0"][i], pts["xi_dot"][i]
        lengths[i] = max(2000, math.ceil(20.0 * 2.0 * math.pi * math.sqrt(mu)))  # twenty undamped periods
        with np.errstate(all="ignore"):
            sim = dfa.simulate(mu, pts["beta"][i], pts["sigma"][i], v0, int(lengths[i]), xi0=x0,
                               wall=WallParams.of(delay=d), bound=1e6)  # fmt: skip
        h = np.arange(1, sim.samples_run + 1)
        s = 0.5 * mu * sim.xi_dot[h] ** 2 + 0.5 * sim.xi[h] ** 2
        s0 = 0.5 * mu * v0 * v0 + 0.5 * x0 * x0
        growth = np.where(np.abs(sim.xi[h]) <= 1e6, (s - s0) / s0, np.inf)  # past the bound: without limit
        ratio[i], at[i] = growth.max(), h[np.argmax(growth)]
        div[i] = sim.outcome == "unstable"
    grew = ratio > 1e-9
    w = int(np.argmax(ratio))
    kinds = ("interior", "line", "sigma-edge", "beta-edge")
    worst = {k: float(pts[k][w]) for k in ("mu", "beta", "sigma", "xi0", "xi_dot")}
    worst.update(sample=int(at[w]), kind=kinds[int(pts["kind"][w])])
    return dict(
        by_kind={k: int(np.sum(pts["kind"] == j)) for j, k in enumerate(kinds)},
        energy_grew=int(grew.sum()),
        diverged=int(div.sum()),
        violations=int((grew | div).sum()),
        worst_growth=float(ratio[w]),
        worst_point=worst,
        samples_min=int(lengths.min()),
        samples_max=int(lengths.max()),
    )


@pytest.mark.parametrize(("d", "criterion"), [(0, "delay-aware"), (2, "delay-aware"), (1, "d-ignoring")])
def test_eq6_delay_soundness_of_the_spring_as_a_wall_equals_an_independent_resimulation(d, criterion):
    """The merged analysis (the spring with delay d as the wall WallParams.of(delay=d), its compiled fast path)
    counts exactly what re-simulating its points one by one with dfa.simulate and recomputing the storage gives:
    the numbers the delay-only module gave before the merge (issue 25)."""
    pop = Population(delay=d)
    r = criterion_soundness(150, pop, criterion=criterion, seed=40 + d)
    pts = sample_passive_points(150, pop, criterion=criterion, seed=40 + d)
    expected = _independent_counts(pts, d)
    got = {k: getattr(r, k) for k in expected}
    assert got == expected
    assert r.delay == d and r.by_case is None and r.criterion == criterion
    if criterion == "d-ignoring":  # the comparison criterion's violations are there to be counted
        assert r.diverged > 0 and r.energy_grew > 0


def test_eq6_delay_soundness_command_writes_markdown_and_json(tmp_path, capsys):
    import json

    from dfa.cli.soundness_report import main

    assert main(["--points", "30", "--old-points", "20", "--delays", "0", "2", "--out", str(tmp_path)]) == 0
    md = (tmp_path / "delay_soundness.md").read_text()
    data = json.loads((tmp_path / "delay_soundness.json").read_text())
    assert [(r["criterion"], r["delay"], r["points"], r["seed"]) for r in data] == [
        ("delay-aware", 0, 30, 12), ("delay-aware", 2, 30, 14), ("d-ignoring", 0, 20, 12), ("d-ignoring", 2, 20, 14),
    ]  # fmt: skip
    assert all("by_case" not in r for r in data) and data[0]["status"] == "sound"
    assert "| delay-aware | 2 | 30 |" in md and "| d-ignoring | 0 | 20 |" in md
    err = capsys.readouterr().err
    assert "delay-aware d = 2: 0 violations of 30" in err and len(err.splitlines()) == 4
    assert sorted(p.name for p in tmp_path.iterdir()) == ["delay_soundness.json", "delay_soundness.md"]


@pytest.mark.parametrize(
    "argv, word",
    [
        (["--points", "0"], "--points"),
        (["--points", "1e3"], "--points"),
        (["--old-points", "-2"], "--old-points"),
        (["--delays", "-1"], "--delays"),
        (["--seed", "-3"], "--seed"),
        (["--walls", "--bogus"], "unrecognized"),
    ],
)
def test_eq6_delay_soundness_command_bad_input_is_one_line_exit_2_nothing_written(argv, word, tmp_path, capsys):
    from dfa.cli.soundness_report import main

    assert main([*argv, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1 and word in err and err.startswith("python -m dfa.cli.soundness_report: error:")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("d", [0, 2])
def test_eq18_storage_the_compiled_path_and_the_simulator_path_share_one_rule_of_divergence(d):
    """The spring's points through the compiled storage runs and, point by point, through dfa.simulate (the
    path of every other wall): the same growth, the same worst sample and the same divergence verdict."""
    pts = sample_passive_points(60, Population(delay=d), criterion="d-ignoring", seed=11 + d)
    ns = np.array([run_samples(m) for m in pts["mu"]])
    ratio, at, div = soundness.storage_growth(pts, ns)
    slow = [soundness._storage_run({k: v[i] for k, v in pts.items()}, int(ns[i])) for i in range(ns.size)]
    s_ratio, s_at, s_div = (np.array(c) for c in zip(*slow, strict=True))
    np.testing.assert_array_equal(div, s_div)
    np.testing.assert_allclose(ratio, s_ratio, rtol=1e-9, atol=1e-12)
    grew = ratio > soundness.TOLERANCE
    np.testing.assert_array_equal(at[grew], s_at[grew])
    if d:
        assert div.sum() >= 3  # the d-ignoring criterion's points diverge with a delay: the rule is exercised
