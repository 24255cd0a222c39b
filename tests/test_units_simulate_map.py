"""Physical units wherever a device is known (issue 26 §3): `dfa simulate` in s, m (rad), m/s (rad/s) and N (N·m)
in its text and JSON, the `--trace` CSV's physical columns, and `dfa map`'s outcome at the device's operating point.

Every physical number is checked against a value computed here from the device's Δ, T and K (paper Table 1:
x = ξΔ, t = kT, ẋ = ξ'Δ/T, F = φ·KΔ), never through :mod:`dfa.model.units`; the trace's force column against an
independent replay of the wall (``tests/reference_ctl.Commands``); the map's operating point against
`dfa simulate` at that point. Without a device the output stays in ticks and samples and says so."""

import csv
import json
import math

import numpy as np
import pytest
from cli_text import unwrap
from reference_ctl import Commands
from result_json import written

import dfa
from dfa.cli import main
from dfa.formatting import WIDTH
from dfa.model.wall import WallParams

PHANTOM = dfa.get_device("phantom").device  # K = 5000 N/m below (the catalogue's is 1015 N/m)
IMPULSE = dfa.get_device("impulse").device  # catalogue K = 80 N/m


def run(capsys, *argv):
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    assert code == 0, err
    return out


def run_json(capsys, *argv):
    return json.loads(run(capsys, *argv, "--json"))


def g4(x):
    """A number as the text prints it (four significant digits)."""
    return f"{x:.4g}"


# ---------------------------------------------------------------- dfa simulate: text and JSON


def test_simulate_chatter_in_seconds_metres_and_newtons(capsys):
    argv = ["simulate", "--device", "phantom", "--stiffness", "5000", "--velocity", "0.01"]
    d = run_json(capsys, *argv)
    delta, T, K = PHANTOM.resolution, PHANTOM.period, 5000.0
    assert d["outcome"] == "chatter" and d["rest_sample"] is None
    assert d["duration_s"] == pytest.approx(d["samples"] * T) and d["duration_s"] == pytest.approx(50.0)
    assert d["integrated_s"] == pytest.approx(d["samples_run"] * T)
    assert d["x0_m"] == 0.0 and d["v0_m_s"] == pytest.approx(0.01)  # ξ'0 Δ/T is the speed given
    assert d["v0_m_s"] == pytest.approx(d["xi_dot0"] * delta / T)
    assert d["final_x_m"] == pytest.approx(d["final_xi"] * delta)
    assert d["final_v_m_s"] == pytest.approx(d["final_xi_dot"] * delta / T)
    assert d["tick_m"] == delta and d["force_step_n"] == pytest.approx(K * delta)
    assert d["force_peak_to_peak_n"] == pytest.approx(d["force_peak_to_peak"] * K * delta)
    assert d["force_amplitude_n"] == pytest.approx(d["amplitude"] * K * delta)
    assert d["null_reasons"]["/rest_time_s"].startswith("the run did not come to rest")
    text = unwrap(run(capsys, *argv))
    assert f"{d['samples_run']} of {d['samples']} integrated = {g4(d['samples'] * T)} s of {g4(50.0)} s" in text
    assert f"ξ'0 = {d['xi_dot0']:.5g} ticks/sample = 0.01 m/s" in text
    assert f"ξ = {g4(d['final_xi'])} ticks = {g4(d['final_xi'] * delta)} m" in text
    assert f"ξ' = {g4(d['final_xi_dot'])} ticks/sample = {g4(d['final_xi_dot'] * delta / T)} m/s" in text
    assert f"= {g4(d['force_peak_to_peak'] * K * delta)} N (tail)" in text
    assert f"1 tick = Δ = {g4(delta)} m, 1 sample = T = {g4(T)} s, force step KΔ = {g4(K * delta)} N" in text


def test_simulate_rest_time_in_seconds(capsys):
    argv = ["simulate", "--device", "impulse", "--velocity", "0.1"]
    d = run_json(capsys, *argv)
    T = IMPULSE.period
    assert d["outcome"] == "rest" and d["rest_sample"] == d["samples_run"] > 0
    assert d["rest_time_s"] == pytest.approx(d["rest_sample"] * T)
    assert d["final_v_m_s"] == 0.0 and d["stiffness"] == 80.0
    text = run(capsys, *argv)
    assert f"rest at sample  {d['rest_sample']} = {g4(d['rest_sample'] * T)} s" in text


def test_simulate_undecided_says_how_long_to_run_in_seconds(capsys):
    argv = ["simulate", "--device", "phantom", "--velocity", "0.05", "--samples", "50"]
    d = run_json(capsys, *argv)
    assert d["outcome"] == "undecided"
    assert d["suggested_duration_s"] == pytest.approx(d["suggested_samples"] * PHANTOM.period)
    assert f"--samples {d['suggested_samples']} ({g4(d['suggested_samples'] * PHANTOM.period)} s)" in run(capsys, *argv)


def test_simulate_rotary_device_in_rad_and_newton_metres(capsys):
    argv = ["simulate", "--device", "re35", "--stiffness", "0.5", "--rotary", "--velocity", "2", "--samples", "200"]
    d = run_json(capsys, *argv)
    dev = dfa.get_device("re35").device
    delta = dev.resolution
    assert d["v0_rad_s"] == pytest.approx(2.0) and d["final_x_rad"] == pytest.approx(d["final_xi"] * delta)
    assert d["force_step_nm"] == pytest.approx(0.5 * delta) and d["tick_rad"] == written(delta)
    assert not any(k.endswith(("_m", "_m_s", "_n")) for k in d)
    text = run(capsys, *argv)
    assert f"= {g4(d['final_xi'] * delta)} rad" in text and "rad/s" in text and f"{g4(0.5 * delta)} N·m" in text


def test_simulate_without_a_device_stays_dimensionless_and_says_so(capsys):
    argv = ["simulate", "--mu", "50", "--beta", "0.2", "--sigma", "0.4", "--xi-dot", "1", "--samples", "3000"]
    d = run_json(capsys, *argv)
    physical = ("duration_s", "integrated_s", "rest_time_s", "x0_m", "v0_m_s", "final_x_m", "final_v_m_s",
                "force_step_n", "amplitude_m", "frequency_hz", "force_peak_to_peak_n", "device", "stiffness")  # fmt: skip
    for key in physical:
        assert key in d and d[key] is None, key
        assert d["null_reasons"][f"/{key}"].startswith("dimensionless input: no device"), key
    text = run(capsys, *argv)
    assert "dimensionless (no device): positions in ticks, time in samples, forces in KΔ" in text
    assert " m/s" not in text and " s of " not in text and " N" not in text


def test_simulate_default_text_fits_one_screen(capsys):
    for argv in (
        ["simulate", "--device", "phantom", "--stiffness", "5000", "--velocity", "0.01"],
        ["simulate", "--device", "re35", "--stiffness", "0.5", "--rotary", "--velocity", "2", "--samples", "200"],
        ["simulate", "--device", "phantom", "--velocity", "0.05", "--samples", "50", "--preload"],
    ):
        text = run(capsys, *argv)
        assert max(map(len, text.splitlines())) <= WIDTH, text


# ---------------------------------------------------------------- --trace (12 significant digits: rel 1e-11)


def read_trace(path):
    rows = list(csv.reader(path.open()))
    return rows[0], np.array(rows[1:], dtype=float)


def reference_force(xs, wall, quantize=True):
    """φ_A at each instant from the recorded positions by the reference controller, independent of the package;
    the amplifier's first-order lag over one held sample in closed form."""
    cmd, out, fa = Commands(wall, quantize), np.empty(xs.size), None
    for h, x in enumerate(xs):
        c = cmd.applied(x)
        fa = c if fa is None or wall.lag == 0.0 else fa
        out[h] = fa
        if wall.lag != 0.0:
            fa = c + (fa - c) * math.exp(-1.0 / wall.lag)
    return out


@pytest.mark.parametrize(
    "flags, wall",
    [
        ([], WallParams.of()),
        (["--delay", "2"], WallParams.of(delay=2)),
        (["--virtual-damping", "0.5", "--velocity-filter", "100", "--delay", "1"], None),
        (["--virtual-damping", "0.5", "--amplifier-bandwidth", "300"], None),
    ],
)
def test_trace_physical_columns_follow_the_tick_columns(capsys, tmp_path, flags, wall):
    path = tmp_path / "t.csv"
    argv = ["simulate", "--device", "impulse", "--velocity", "0.2", "--samples", "400", *flags]
    d = run_json(capsys, *argv, "--trace", path)
    header, t = read_trace(path)
    assert header == ["sample", "xi", "xi_dot", "phi", "t_s", "x_m", "v_m_per_s", "force_n"]
    sample, xi, xi_dot, phi, t_s, x_m, v, force = t.T
    delta, T, K = IMPULSE.resolution, IMPULSE.period, 80.0
    # the trace ends where the outcome was decided (a rest: the state repeats from there on)
    assert np.array_equal(sample, np.arange(d["trace"]["last_sample"] + 1)) and sample.size == d["trace"]["rows"]
    assert sample.size <= 401 and xi[-1] == d["final_xi"]
    assert np.allclose(t_s, sample * T, rtol=1e-11, atol=0)
    assert np.allclose(x_m, xi * delta, rtol=1e-11, atol=0)
    assert np.allclose(v, xi_dot * delta / T, rtol=1e-11, atol=0)
    assert np.allclose(force, phi * K * delta, rtol=1e-11, atol=0)
    if wall is None:  # the wall of the flags in its groups: β_B = B/(KT), ν_c = f_c·T, α = 1/(2π f_bw T)
        wall = WallParams.of(
            damping=0.5 / (K * T),
            delay=1 if "--delay" in flags else 0,
            cutoff=100.0 * T if "--velocity-filter" in flags else None,
            lag=1.0 / (2 * math.pi * 300.0 * T) if "--amplifier-bandwidth" in flags else 0.0,
        )
    assert np.allclose(phi, reference_force(xi, wall), rtol=1e-11, atol=1e-12)
    if not flags:  # the spring in contact: F = −KΔ(⌊x/Δ⌋ + ½), within half a force step of −K·x
        assert np.all(np.abs(force + K * x_m) <= K * delta / 2 * (1 + 1e-12))
        assert np.array_equal(phi, -(np.floor(xi) + 0.5))


def test_trace_rotary_and_dimensionless_columns(capsys, tmp_path):
    rot, dim = tmp_path / "r.csv", tmp_path / "d.csv"
    run(capsys, "simulate", "--device", "re35", "--stiffness", "0.5", "--rotary", "--velocity", "2",
        "--samples", "100", "--trace", rot)  # fmt: skip
    header, t = read_trace(rot)
    assert header == ["sample", "xi", "xi_dot", "phi", "t_s", "x_rad", "v_rad_per_s", "force_nm"]
    dev = dfa.get_device("re35").device
    assert np.allclose(t[:, 7], t[:, 3] * 0.5 * dev.resolution, rtol=1e-11, atol=0)
    run(capsys, "simulate", "--mu", "50", "--beta", "0", "--sigma", "0.2", "--xi-dot", "2", "--samples", "20000",
        "--trace", dim)  # fmt: skip
    header, t = read_trace(dim)
    assert header == ["sample", "xi", "xi_dot", "phi"]  # no device: no physical columns
    assert np.isfinite(t).all()  # a diverged run stops at its last sample, force included
    assert np.array_equal(t[:, 3], -(np.floor(t[:, 1]) + 0.5))


def test_applied_force_needs_a_record_and_is_nan_past_a_divergence():
    r = dfa.simulate(50.0, 0.0, 0.2, 2.0, samples=20_000)
    f = r.applied_force()
    assert r.outcome == "unstable" and f.size == r.xi.size and not f.flags.writeable
    ok = np.isfinite(r.xi)
    assert np.array_equal(f[ok], -(np.floor(r.xi[ok]) + 0.5)) and np.isnan(f[~ok]).all()
    with pytest.raises(dfa.DFAValueError, match="record=True"):
        dfa.simulate(50.0, 0.2, 0.4, 1.0, samples=100, record=False).applied_force()


# ---------------------------------------------------------------- dfa map at the operating point


def simulate_at(capsys, device_args, v, samples, *extra):
    return run_json(capsys, "simulate", *device_args, "--velocity", v, "--samples", samples, *extra)


@pytest.mark.parametrize(
    "device_args, speeds, extra",
    [
        (["--device", "phantom"], ["0.05", "0.2"], []),
        (["--device", "impulse"], ["0.1", "0.3"], ["--preload"]),
        (["--device", "delta"], ["0.1"], ["--virtual-damping", "1", "--delay", "1"]),
    ],
)
def test_map_outcome_at_the_operating_point_is_dfa_simulate_there(capsys, tmp_path, device_args, speeds, extra):
    argv = ["map", *device_args, "--velocity", *speeds, "--grid", "3", "--samples", "4000", "--quiet", *extra,
            "--out", tmp_path / "m.npz"]  # fmt: skip
    d = run_json(capsys, *argv)
    runs = d["operating_point_runs"]
    assert len(runs) == len(speeds)
    for v, rec in zip(speeds, runs, strict=True):
        sim = simulate_at(capsys, device_args, v, 4000, *extra)
        assert rec["outcome"] == sim["outcome"]
        for key in ("amplitude", "frequency", "rest_sample", "samples_run", "rest_time_s", "amplitude_m"):
            assert rec[key] == sim[key], key
        assert rec["velocity_m_s"] == pytest.approx(float(v))
    text = run(capsys, *argv)
    assert max(map(len, text.splitlines())) <= WIDTH
    how = "--samples 4000" + (" --preload" if "--preload" in extra else "")
    assert f"(as `dfa simulate {how}`):" in text
    for v, rec in zip(speeds, runs, strict=True):
        want = (
            f"rest at {g4(rec['rest_time_s'])} s"
            if rec["outcome"] == "rest"
            else rec["outcome"] + ("" if rec["amplitude_m"] is None else f", amplitude {rec['amplitude_m']:.3g} m")
        )
        assert any(line.split()[1:2] == [g4(float(v))] and line.endswith(want) for line in text.splitlines()), want


def test_map_figure_marks_the_operating_point_with_its_outcome(capsys, tmp_path, monkeypatch):
    import dfa.cli.maps as cli_maps

    seen = []

    def keep(flag, path, ax):
        seen.extend(t.get_text() for a in ax.figure.axes for t in a.texts)
        return path

    monkeypatch.setattr(cli_maps, "save_png", keep)
    argv = ["map", "--device", "phantom", "--velocity", "0.05", "0.2", "--grid", "3", "--samples", "4000",
            "--quiet", "--out", tmp_path / "m.npz"]  # fmt: skip
    d = run_json(capsys, *argv, "--plot", tmp_path / "m.png")
    notes = [
        f"rest at {g4(r['rest_time_s'])} s" if r["outcome"] == "rest" else r["outcome"]
        for r in d["operating_point_runs"]
    ]
    labels = [t for t in seen if t.startswith("Phantom 1.0, K = 1015 N/m: ")]
    assert len(labels) == 2 and [lab.split(": ", 1)[1].split(",")[0] for lab in labels] == notes


def test_map_without_a_device_has_no_operating_point(capsys, tmp_path):
    argv = ["map", "--mu", "50", "--xi-dot", "1", "--grid", "3", "--samples", "1000", "--quiet",
            "--out", tmp_path / "m.npz"]  # fmt: skip
    d = run_json(capsys, *argv)
    assert d["operating_point"] is None and d["operating_point_runs"] is None
    assert d["null_reasons"]["/operating_point"].startswith("dimensionless input (--mu): no device")
    assert "operating point" not in run(capsys, *argv)
