"""Physical units where a device is known (issue 14 §3): conversions on known values (Table 1: ξ = x/Δ,
τ = t/T, φ = F/(KΔ)) and the CLI paths of limit-cycles, simulate, map and contours."""

import json
import math

import numpy as np
import pytest
from cli_text import unwrap

import dfa
from dfa.cli import main
from dfa.model.units import physical_quantities, unit_context

IMPULSE = dfa.Device(mass=0.032, damping=0.02, coulomb=0.024, resolution=314e-6, period=2e-3, name="Impulse Engine")
ROTARY = dfa.Device(mass=6.28e-6, damping=9e-5, coulomb=2e-2, resolution=2 * math.pi / 8192, period=1e-3, rotary=True)


def test_table1_ticks_to_metres_and_rad_per_sample_to_hz_known_values():
    q = physical_quantities(
        IMPULSE, 80.0, amplitude=10.0, frequency=math.pi / 2, period=4.0, xi_dot=1.0, force_steps=2.0
    )
    assert q["amplitude_m"] == pytest.approx(3.14e-3)  # 10 ticks of 314 µm
    assert q["frequency_hz"] == pytest.approx(125.0)  # a 4-sample period at 500 Hz sampling
    assert q["period_s"] == pytest.approx(8e-3)
    assert q["velocity_m_s"] == pytest.approx(0.157)  # one tick per 2 ms
    assert q["force_amplitude_n"] == pytest.approx(10 * 80 * 314e-6)
    assert q["force_peak_to_peak_n"] == pytest.approx(2 * 80 * 314e-6)
    r = physical_quantities(ROTARY, 5.0, amplitude=8192.0, frequency=2 * math.pi * 1e-3, force_steps=1.0)
    assert r["amplitude_rad"] == pytest.approx(2 * math.pi)  # one revolution of the 8192-count encoder
    assert r["frequency_hz"] == pytest.approx(1.0)
    assert r["force_peak_to_peak_nm"] == pytest.approx(5.0 * 2 * math.pi / 8192)
    assert physical_quantities(IMPULSE, 80.0, frequency=math.nan) == {"frequency_hz": None}
    c = unit_context(IMPULSE, 80.0, 0.1)
    assert c["force_step_n"] == pytest.approx(0.02512) and c["device"] == "Impulse Engine" and c["velocity"] == 0.1
    assert unit_context(ROTARY, 5.0)["force_unit"] == "N·m"
    with pytest.raises(dfa.DFAValueError, match="stiffness"):
        physical_quantities(IMPULSE, -1.0, amplitude=1.0)


def test_eq44_limit_cycle_physical_matches_period_and_closed_form():
    res = dfa.limit_cycles(IMPULSE.params(80.0))
    c = res.unstable_cycles[0]
    q = c.physical(IMPULSE, 80.0)
    assert q["period_s"] == pytest.approx(c.period * 2e-3) and q["frequency_hz"] * q["period_s"] == pytest.approx(1.0)
    assert q["velocity_m_s"] == pytest.approx(IMPULSE.velocity(c.amplitude * c.frequency))
    d = res.physical(IMPULSE, 80.0)
    assert d["stiffness"] == 80.0 and len(d["cycles"]) == len(res.cycles)


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_limit_cycles_json_carries_both_units(capsys):
    code, out, err = run(capsys, "limit-cycles", "--device", "impulse", "--json")
    assert code == 0, err
    d = json.loads(out)
    cyc = d["cycles"][0]
    assert cyc["amplitude_m"] == pytest.approx(cyc["amplitude"] * 314e-6)
    assert cyc["frequency_hz"] == pytest.approx(cyc["frequency"] / (2 * math.pi * 2e-3))
    assert cyc["period_s"] == pytest.approx(cyc["period"] * 2e-3)
    assert d["force_step_n"] == pytest.approx(80 * 314e-6) and d["device"] == "Impulse Engine" and d["stiffness"] == 80
    code, out, _ = run(capsys, "limit-cycles", "--device", "impulse")
    assert "M (m)" in out and "f (Hz)" in out and f"{cyc['amplitude_m']:.4g}" in out
    assert "one force step KΔ = 0.02512 N" in out
    code, out, _ = run(capsys, "limit-cycles", "--device", "re35", "--stiffness", "20", "--json")
    assert "amplitude_rad" in json.loads(out)["cycles"][0]


def test_cli_simulate_json_carries_both_units(capsys):
    code, out, err = run(
        capsys, "simulate", "--device", "phantom", "--stiffness", "5000", "--velocity", "0.01", "--json"
    )
    assert code == 0, err
    d = json.loads(out)
    assert d["outcome"] == "chatter"
    assert d["frequency_hz"] == pytest.approx(d["frequency"] / (2 * math.pi * 1e-3))
    assert d["period_s"] == pytest.approx(d["period"] * 1e-3)
    assert d["force_peak_to_peak_n"] == pytest.approx(d["force_peak_to_peak"] * 5000 * 20.1e-6)
    assert d["force_step_n"] == pytest.approx(5000 * 20.1e-6) and d["velocity"] == 0.01
    assert d["device"] == "Phantom 1.0" and d["stiffness"] == 5000.0
    code, out, _ = run(capsys, "simulate", "--device", "phantom", "--stiffness", "5000", "--velocity", "0.01")
    assert f"{d['period_s']:.4g} s" in out and f"{d['amplitude_m']:.4g} m" in out


def test_cli_map_with_device_json_and_plot(capsys, tmp_path):
    out_npz, png = tmp_path / "m.npz", tmp_path / "m.png"
    argv = ["map", "--device", "impulse", "--velocity", "0.2", "--grid", "4", "--samples", "2000", "--quiet"]
    code, out, err = run(capsys, *argv, "--out", str(out_npz), "--plot", str(png), "--json")
    assert code == 0, err
    d = json.loads(out)
    p = IMPULSE.params(80.0)
    assert d["mu"] == pytest.approx(p.mu) and d["operating_point"]["beta"] == pytest.approx(p.beta)
    assert d["velocities"] == [pytest.approx(0.2)] and d["stiffness"] == 80.0 and d["tick_m"] == 314e-6
    assert png.read_bytes()[:4] == b"\x89PNG"
    m = dfa.load_map(str(out_npz))
    assert np.allclose(m.xi_dots, [IMPULSE.xi_dot(0.2)])


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["map", "--mu", "100", "--device", "impulse", "--xi-dot", "1"], "--mu cannot be combined"),
        (["map", "--xi-dot", "1"], "missing --mu"),
        (["map", "--mu", "100", "--velocity", "0.1"], "--velocity needs a device"),
        (["map", "--device", "impulse", "--velocity", "0.1", "--xi-dot", "1"], "cannot both be given"),
        (["map", "--device", "impulse"], "missing speeds"),
        (["map", "--mu", "100", "--xi-dot", "1", "--plot", "x.jpg"], "--plot"),
        (["contours", "--device", "re35"], "--stiffness"),
        (["contours", "--mu", "5", "--mass", "1"], "--mu cannot be combined"),
    ],
)
def test_cli_map_contours_device_errors_one_line(capsys, tmp_path, argv, needle):
    if argv[0] == "map":
        argv = [*argv, "--out", str(tmp_path / "m.npz"), "--grid", "2", "--samples", "100"]
    code, _, err = run(capsys, *argv)
    assert code == 2 and err.count("\n") == 1 and needle in err, err


def test_cli_contours_with_device_text_json_and_plot(capsys, tmp_path):
    png = tmp_path / "c.png"
    code, out, err = run(capsys, "contours", "--device", "re35", "--stiffness", "5", "--grid", "6", "--plot", str(png))
    assert code == 0, err
    out = unwrap(out)
    assert "1 tick = 0.000767 rad" in out and "159.2 Hz" in out and "outside the (β, σ) range" in out
    assert png.read_bytes()[:4] == b"\x89PNG"
    code, out, _ = run(capsys, "contours", "--device", "impulse", "--grid", "4", "--json")
    d = json.loads(out)
    assert d["mu"] == pytest.approx(IMPULSE.params(80.0).mu) and d["force_step_n"] == pytest.approx(0.02512)
    assert d["frequency_hz_per_rad_per_sample"] == pytest.approx(1 / (2 * math.pi * 2e-3))
