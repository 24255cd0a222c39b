"""The `dfa` command line: devices, params, check, stiffness (JSON contract and errors)."""

import json
import subprocess
import sys

import pytest
from result_json import written

import dfa
from dfa.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def test_cli_devices_json_lists_catalogue_with_recomputed_and_printed(capsys):
    rows = run_json(capsys, "devices")
    by = {r["name"]: r for r in rows}
    assert by["Toolhandle"]["mu"] == pytest.approx(38.08)
    assert by["Toolhandle"]["printed"]["mu"] == 33.19
    assert [d["parameter"] for d in by["Toolhandle"]["discrepancies"]] == ["mu"]
    assert by["Omega"]["mu"] is None and by["Omega"]["incomplete"]
    for r in rows:
        for key in (
            "name",
            "mass",
            "damping",
            "coulomb",
            "resolution",
            "period",
            "mu",
            "beta",
            "sigma",
            "printed",
            "discrepancies",
        ):
            assert key in r


def test_cli_devices_table(capsys):
    code, out, _ = run(capsys, "devices")
    assert code == 0 and "Phantom 1.0" in out and "sigma +44%" in out


def test_cli_params_from_device_physical_and_dimensionless(capsys):
    p = run_json(capsys, "params", "--device", "impulse")
    assert p == pytest.approx({"mu": 100.0, "beta": 0.125, "sigma": 0.024 / (80 * 314e-6)})
    q = run_json(
        capsys,
        "params",
        "--mass",
        "0.032",
        "--damping",
        "0.02",
        "--coulomb",
        "0.024",
        "--resolution",
        "314e-6",
        "--period",
        "2e-3",
        "--stiffness",
        "80",
    )
    assert q == pytest.approx(p)
    r = run_json(capsys, "params", "--mu", "5", "--beta", "0.1", "--sigma", "0.7")
    assert r == {"mu": 5.0, "beta": 0.1, "sigma": 0.7}
    # a physical flag overrides the catalogue value (the Phantom with Δ = 29 µm)
    s = run_json(capsys, "params", "--device", "phantom", "--resolution", "29e-6")
    assert s["sigma"] == pytest.approx(1.291, abs=1e-3)


def test_cli_check_json_contract(capsys):
    r = run_json(capsys, "check", "--device", "delta", "--velocity", "0.1")
    assert set(r) >= {"region", "passive", "margin", "critical_xi_dot"}
    api = dfa.device_criterion(dfa.get_device("Delta").device, 14500.0, 0.1)
    assert (r["region"], r["passive"], r["margin"], r["critical_xi_dot"]) == (
        api.region,
        api.passive,
        written(api.margin),
        written(api.critical_xi_dot),
    )
    c = run_json(capsys, "check", "--beta", "0.2", "--sigma", "0.3", "--xi-dot", "1")
    assert c["region"] == "c" and c["critical_xi_dot"] is None and c["passive"] is False
    n = run_json(capsys, "check", "--beta", "0.2", "--sigma", "0.3", "--xi-dot", "1", "--no-quantization")
    assert n["passive"] is True


def test_cli_check_table(capsys):
    code, out, _ = run(capsys, "check", "--device", "delta", "--xi-dot", "5")
    assert code == 0 and "region" in out and "d: no passivity guarantee at this speed" in out
    assert "unstable" not in out.replace("not a proof of instability", "")  # the criterion alone never says unstable


def test_cli_stiffness_json_contract(capsys):
    r = run_json(capsys, "stiffness", "--device", "impulse", "--velocity", "0.05", "--stiffness", "80")
    dev = dfa.get_device("impulse").device
    lim = dfa.stiffness_limits(dev, 0.05, 80.0)
    assert r["k_criterion"]["value"] == written(lim.k_max) and r["k_linear"]["value"] == written(lim.k_gil)
    assert r["k_colgate"] == lim.k_colgate and r["k_abbott_okamura"] == lim.k_abbott_okamura
    assert r["assessment"]["max_passive_velocity"] == pytest.approx(lim.max_passive_velocity)
    assert r["assessment"]["verdict"] == lim.status.value and r["assessment"]["velocity_status"] == "bounded"
    r2 = run_json(capsys, "stiffness", "--device", "impulse", "--velocity", "0.05")
    assert r2["stiffness_source"] == "catalogue" and r2["assessment"]["source"] == "catalogue"  # the catalogue K
    assert r2["assessment"]["stiffness"] == dfa.get_device("impulse").stiffness
    r3 = run_json(capsys, "stiffness", "--device", "impulse", "--xi-dot", "1")
    assert r3["velocity"] == pytest.approx(dev.velocity(1.0))


def test_cli_stiffness_table(capsys):
    code, out, _ = run(capsys, "stiffness", "--device", "delta", "--velocity", "0.1", "--stiffness", "14500")
    assert code == 0 and "exact linear bound" in out and "N/m" in out


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["check", "--device", "fantom", "--xi-dot", "1"], "did you mean 'Phantom 1.0'"),
        (["params", "--mass", "abc"], "--mass"),
        (
            [
                "params",
                "--mass",
                "-1",
                "--damping",
                "0.1",
                "--coulomb",
                "0.1",
                "--resolution",
                "1e-5",
                "--period",
                "1e-3",
                "--stiffness",
                "10",
            ],
            "mass = -1.0",
        ),
        (
            [
                "params",
                "--mass",
                "nan",
                "--damping",
                "0.1",
                "--coulomb",
                "0.1",
                "--resolution",
                "1e-5",
                "--period",
                "1e-3",
                "--stiffness",
                "10",
            ],
            "finite",
        ),
        (
            [
                "params",
                "--mass",
                "1",
                "--damping",
                "0.1",
                "--coulomb",
                "0.1",
                "--resolution",
                "1e-5",
                "--period",
                "inf",
                "--stiffness",
                "10",
            ],
            "period",
        ),
        (["params", "--mass", "1", "--damping", "0.1"], "missing --coulomb --resolution --period"),
        (["params", "--mu", "1", "--beta", "0.1", "--sigma", "1", "--device", "delta"], "cannot be combined"),
        (["params", "--mu", "1", "--beta", "0.1"], "missing --sigma"),
        (["params", "--mu", "-1", "--beta", "0.1", "--sigma", "1"], "mu = -1.0"),
        (["params"], "no device given"),
        (["params", "--device", "omega"], "incomplete"),
        (["params", "--device", "re35"], "missing --stiffness"),
        (["check", "--device", "delta"], "missing speed"),
        (["check", "--device", "delta", "--velocity", "1", "--xi-dot", "1"], "cannot both"),
        (["check", "--beta", "0.1", "--sigma", "1", "--velocity", "1"], "cannot be combined"),
        (["check", "--device", "delta", "--xi-dot", "fast"], "--xi-dot"),
        (["stiffness", "--device", "delta", "--velocity", "nan"], "velocity"),
        (["stiffness", "--device", "delta", "--velocity", "1", "--stiffness", "0"], "stiffness = 0.0"),
        (["frobnicate"], "invalid choice"),
    ],
)
def test_cli_bad_input_is_one_line_on_stderr_with_exit_2(capsys, argv, needle):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert needle in lines[0]
    assert "Traceback" not in err


def test_cli_console_script_exit_code_and_no_traceback():
    proc = subprocess.run(
        [sys.executable, "-m", "dfa.cli", "check", "--device", "nope", "--xi-dot", "1"], capture_output=True, text=True
    )
    assert proc.returncode == 2 and "Traceback" not in proc.stderr and proc.stderr.count("\n") == 1
