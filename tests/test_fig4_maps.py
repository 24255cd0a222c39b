"""Stability maps (paper Fig. 4) and the `dfa simulate` / `dfa map` commands."""

import csv
import json
import math

import numpy as np
import pytest
from result_json import written

import dfa
from dfa.analysis.maps import load_map, stability_map
from dfa.analysis.simulation import OUTCOMES, preload_position, simulate
from dfa.cli import main


@pytest.fixture(scope="module")
def small_map():
    return stability_map(100.0, [1.0, 5.0], grid=12, samples=20_000, n_jobs=1, progress=False)


def test_fig4_map_points_equal_single_simulations(small_map):
    m = small_map
    rng = np.random.default_rng(0)
    for _ in range(6):
        k, i, j = rng.integers(0, 2), rng.integers(0, 12), rng.integers(0, 12)
        r = simulate(100.0, m.beta[j], m.sigma[i], m.xi_dots[k], 20_000, record=False)
        assert OUTCOMES[m.outcome[k, i, j]] == r.outcome


def test_fig4_map_is_deterministic_whatever_the_number_of_jobs(small_map):
    m2 = stability_map(100.0, [1.0, 5.0], grid=12, samples=20_000, n_jobs=2, progress=False)
    assert np.array_equal(small_map.outcome, m2.outcome)
    assert np.array_equal(small_map.amplitude, m2.amplitude, equal_nan=True)


def test_fig4_no_criterion_passive_point_is_unstable(small_map):
    m = small_map
    for k, v in enumerate(m.xi_dots):
        passive = dfa.classify_region(m.beta[None, :], m.sigma[:, None], v)
        passive = (passive == "a") | (passive == "e")
        assert not np.any(passive & (m.outcome[k] == 2))


def test_fig4_higher_speed_destabilises_more_points(small_map):
    counts = small_map.counts()
    assert counts[1]["unstable"] > counts[0]["unstable"]


def test_fig4_map_save_load_round_trip(small_map, tmp_path):
    path = small_map.save(tmp_path / "map.npz")
    back = load_map(path)
    assert back.xi_dots == small_map.xi_dots and back.samples == small_map.samples
    assert np.array_equal(back.outcome, small_map.outcome)


def test_fig4_preload_starts_at_rest_with_the_same_energy():
    m = stability_map(100.0, [3.0], grid=3, samples=3000, n_jobs=1, progress=False, preload=True)
    r = simulate(100.0, m.beta[1], m.sigma[1], 0.0, 3000, xi0=preload_position(100.0, 3.0), record=False)
    assert OUTCOMES[m.outcome[0, 1, 1]] == r.outcome and m.preload


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(grid=1), "grid"),
        (dict(beta_range=(1.0, 0.5)), "beta_range"),
        (dict(xi_dots=[]), "xi_dots"),
        (dict(n_jobs=0), "n_jobs"),
        (dict(mu=-1.0), "mu"),
        (dict(sigma_range=(0.0,)), "sigma_range"),
    ],
)
def test_map_bad_input(kwargs, needle):
    args = dict(mu=100.0, xi_dots=[1.0], grid=3, samples=10, progress=False)
    args.update(kwargs)
    mu = args.pop("mu")
    xi = args.pop("xi_dots")
    with pytest.raises(dfa.DFAValueError, match=needle):
        stability_map(mu, xi, **args)


def test_cli_simulate_json_contract(capsys):
    assert main(["simulate", "--mu", "100", "--beta", "0.1", "--sigma", "0.9", "--xi-dot", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert set(out) >= {"outcome", "amplitude", "frequency", "final_xi", "final_xi_dot", "rest_sample"}
    r = simulate(100.0, 0.1, 0.9, 2.0, 50_000)
    assert (
        out["outcome"] == r.outcome and out["rest_sample"] == r.rest_sample and out["final_xi"] == written(r.final_xi)
    )


def test_cli_simulate_device_preload_and_trace(capsys, tmp_path):
    trace = tmp_path / "t.csv"
    assert (
        main(
            [
                "simulate",
                "--device",
                "impulse",
                "--velocity",
                "0.05",
                "--preload",
                "--samples",
                "500",
                "--trace",
                str(trace),
                "--json",
            ]
        )
        == 0
    )
    out = json.loads(capsys.readouterr().out)
    rows = list(csv.reader(trace.open()))
    assert rows[0][:4] == ["sample", "xi", "xi_dot", "phi"]  # then t_s, x_m, … (a device)
    assert out["outcome"] == "rest" and len(rows) == out["rest_sample"] + 2  # header, samples 0 .. rest (issue 41)
    p = dfa.get_device("impulse").device.params(80.0)
    x0 = preload_position(p.mu, dfa.get_device("impulse").device.xi_dot(0.05))
    assert float(rows[1][1]) == pytest.approx(x0) and float(rows[1][2]) == 0.0
    assert out["xi0"] == pytest.approx(x0)


def test_cli_map_json_counts(capsys, tmp_path):
    out_file = tmp_path / "m.npz"
    code = main(
        [
            "map",
            "--mu",
            "100",
            "--xi-dot",
            "1",
            "5",
            "--grid",
            "6",
            "--samples",
            "3000",
            "--jobs",
            "1",
            "--out",
            str(out_file),
            "--json",
            "--quiet",
        ]
    )
    assert code == 0
    d = json.loads(capsys.readouterr().out)
    assert [c["xi_dot"] for c in d["counts"]] == [1.0, 5.0]
    assert all(sum(c.get(k, 0) for k in OUTCOMES) == 36 and "left" not in c for c in d["counts"])  # bilateral
    assert load_map(out_file).counts() == [{k: c[k] for k in OUTCOMES[:5]} for c in d["counts"]]


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["simulate", "--mu", "1", "--beta", "0.1", "--sigma", "0.1", "--xi-dot", "1", "--samples", "0"], "samples"),
        (["simulate", "--mu", "1", "--beta", "0.1", "--sigma", "0.1", "--xi-dot", "1", "--delay", "-2"], "delay"),
        (
            ["simulate", "--mu", "1", "--beta", "0.1", "--sigma", "0.1", "--xi-dot", "1", "--samples", "many"],
            "--samples",
        ),
        (
            ["simulate", "--mu", "1", "--beta", "0.1", "--sigma", "0.1", "--xi-dot", "1", "--xi0", "1", "--preload"],
            "--preload",
        ),
        (
            [
                "simulate",
                "--mu",
                "1",
                "--beta",
                "0.1",
                "--sigma",
                "0.1",
                "--xi-dot",
                "1",
                "--samples",
                "2000000000",
                "--trace",
                "t.csv",
            ],
            "drop --trace",
        ),
        (["map", "--mu", "100", "--xi-dot", "1", "--grid", "1", "--out", "x.npz"], "grid"),
        (["map", "--mu", "100", "--xi-dot", "1", "--out", "/nonexistent-dir/x.npz"], "does not exist"),
        (["map", "--mu", "100", "--xi-dot", "1"], "--out"),
        (["map", "--mu", "0", "--xi-dot", "1", "--out", "x.npz"], "mu"),
    ],
)
def test_cli_simulate_and_map_bad_input(capsys, argv, needle):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1 and needle in err and "Traceback" not in err


def test_eq4_trace_csv_stops_at_the_last_integrated_sample(capsys, tmp_path):
    # redteam2: a diverged run of 10^6 samples wrote 10^6 rows, all "nan,nan" after the divergence
    trace = tmp_path / "t.csv"
    argv = ["simulate", "--mu", "500", "--beta", "0.02", "--sigma", "0.4", "--xi-dot", "2"]
    assert main([*argv, "--samples", "1000000", "--trace", str(trace), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["outcome"] == "unstable" and out["samples_run"] < 100_000
    rows = list(csv.reader(trace.open()))
    assert len(rows) == out["samples_run"] + 2  # header, samples 0 .. samples_run
    assert all(math.isfinite(float(v)) for row in rows[1:] for v in row)
    assert float(rows[-1][1]) == out["final_xi"]


@pytest.mark.parametrize("command", ["map", "contours"])
def test_table1_map_and_contours_take_counts_and_name(capsys, tmp_path, command):
    # redteam2: `map`/`contours` refused --counts and --name ("unrecognized arguments"), which the README
    # gives for every device; Δ = 1/2000 m must give the same μ and σ as --resolution 0.0005
    dev = ["--mass", "0.05", "--damping", "0.002", "--coulomb", "0.02", "--period", "0.001", "--stiffness", "100"]
    extra = ["--velocity", "0.1", "--out", str(tmp_path / "m.npz")] if command == "map" else []
    outs = []
    for enc in (["--counts", "2000", "--name", "pen"], ["--resolution", "0.0005"]):
        assert main([command, *dev, *enc, *extra, "--grid", "4", "--quiet", "--json"]) == 0
        outs.append(json.loads(capsys.readouterr().out))
    assert outs[0]["device"] == "pen" and outs[1]["device"] == "custom device"
    assert outs[0]["mu"] == pytest.approx(outs[1]["mu"]) == pytest.approx(500.0)
    assert outs[0]["tick_m"] == pytest.approx(outs[1]["tick_m"]) == pytest.approx(0.0005)
    assert outs[0]["operating_point"] == pytest.approx(outs[1]["operating_point"])


#: Keys of the former hand-written StabilityMap.to_dict (before it moved onto dfa.results.base.Result).
MAP_JSON_KEYS = {
    "mu", "xi_dots", "beta_range", "sigma_range", "grid", "samples", "delay", "quantize", "preload", "counts",
    "status", "status_message",
}  # fmt: skip


@pytest.mark.parametrize("wall", [None, "damper"])
def test_stability_map_json_is_the_result_base_plus_counts(wall):
    """StabilityMap.to_dict is the Result base's (the fields but the arrays, and beta_range, sigma_range, grid,
    delay) plus ``counts`` per speed; every former key is there with its value, and ``wall`` now also for the spring."""
    from result_json import assert_json_from_fields

    from dfa.jsonable import to_jsonable
    from dfa.model.wall import WallParams

    w = None if wall is None else WallParams.of(damping=0.2, delay=1, cutoff=0.3)
    m = stability_map(50.0, [2.0, 5.0], grid=3, samples=1000, n_jobs=1, progress=False, wall=w)
    d = assert_json_from_fields(m, extra={"counts"})
    assert set(d) >= MAP_JSON_KEYS | {"wall"}
    assert not set(d) & {"beta", "sigma", "outcome", "amplitude", "frequency"}
    assert (d["mu"], d["xi_dots"], d["samples"], d["quantize"], d["preload"]) == (50.0, [2.0, 5.0], 1000, True, False)
    assert (d["beta_range"], d["sigma_range"], d["grid"]) == ([0.0, 1.0], [0.0, 2.0], [3, 3])
    assert d["delay"] == m.delay == (0 if wall is None else 1) and d["wall"] == to_jsonable(m.wall)
    assert (d["status"], d["status_message"]) == ("ok", m.status.message)
    assert d["counts"] == [dict(xi_dot=v, **c) for v, c in zip(m.xi_dots, m.counts(), strict=True)]


def test_trace_stops_where_the_device_comes_to_rest_and_says_so(capsys, tmp_path):
    # issue 41: a run that came to rest at sample 55 of 50,000 wrote 50,001 rows (the rest state repeated)
    trace = tmp_path / "t.csv"
    argv = ["simulate", "--device", "delta", "--velocity", "0.05", "--trace", str(trace)]
    assert main([*argv, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["outcome"] == "rest" and out["rest_sample"] < out["samples"] // 100
    rows = list(csv.reader(trace.open()))
    assert len(rows) == out["rest_sample"] + 2  # header, samples 0 .. the rest sample
    assert out["trace"]["last_sample"] == out["rest_sample"] and out["trace"]["rows"] == len(rows) - 1
    assert "rest" in out["trace"]["ends"]
    assert float(rows[-1][1]) == pytest.approx(out["final_xi"], abs=1e-9)
    assert main(argv) == 0
    text = " ".join(capsys.readouterr().out.split())  # the line wraps after a long path
    assert f"samples 0 to {out['rest_sample']} (at rest from there on)" in text


def test_trace_of_an_undecided_run_holds_the_whole_run_and_says_why(capsys, tmp_path):
    trace = tmp_path / "t.csv"
    argv = ["simulate", "--mu", "100", "--beta", "0.001", "--sigma", "0.2", "--xi-dot", "1", "--samples", "3000"]
    assert main([*argv, "--trace", str(trace), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["samples_run"] == 3000 and out["trace"]["last_sample"] == 3000
    assert len(list(csv.reader(trace.open()))) == 3002 and out["trace"]["ends"].startswith("the whole run")
