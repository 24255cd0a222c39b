"""Every command answers for a device file's limiting configuration and names it (issue 46).

Two answers to one question must agree: each command run on a file with configurations answers exactly what it
answers with ``--configuration NAME`` of the limiting one, and the limiting one is the one its rule names (the
smallest criterion margin, eq. 6, computed here from the single devices given by flags). ``--normal`` along an
axis is the one-axis device with m_n = 1/(M⁻¹)_ii (numpy's inverse); the device template round-trips.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from configuration_files import HEAD, INERTIA
from configuration_files import device_file as _file
from configuration_files import run_cli as _run
from fixed_keywords import fixed_keywords

import dfa.analysis.limits.kmax as kmax
from dfa.analysis.criterion import device_criterion
from dfa.analysis.limits.zwidth import z_width
from dfa.cli.tune import export_command
from dfa.model.catalogue import device_template, load_device_file
from dfa.model.configurations import Configuration
from dfa.model.device import Device
from dfa.model.loop import Loop
from dfa.model.wall import Wall

#: Two configurations: at 0.05 m/s the slippery one has the smaller margin (less friction, eq. 6).
TWO = ('name = "near"', 'name = "slippery"\ncoulomb = 0.012')


def _json(capsys, *argv: str) -> dict:
    code, out, err = _run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def _margins(v: float) -> dict[str, float]:
    """Eq. 6's margin of each configuration as a single device (flags' values, not the file's)."""
    return {
        name: device_criterion(Loop(Device(0.032, 0.02, c, 314e-6, 2e-3), Wall.of(80.0)), v).margin
        for name, c in (("near", 0.024), ("slippery", 0.012))
    }


@pytest.mark.parametrize(
    ("command", "speed"),
    [
        (["simulate", "--velocity", "0.05", "--samples", "3000"], 0.05),
        (["require", "--stiffness", "80", "--velocity", "0.05", "--parameter", "coulomb"], 0.05),
        (["limit-cycles", "--max-amplitude", "4"], 0.0),
    ],
)
def test_eq6_commands_given_k_answer_for_the_smallest_margin_as_with_configuration(capsys, tmp_path, command, speed):
    path = _file(tmp_path, *TWO)
    worst = _json(capsys, *command, "--device-file", path)
    one = _json(capsys, *command, "--device-file", path, "--configuration", "slippery")
    rec = worst.pop("configuration")
    assert worst == one  # the same numbers, every one
    margins = _margins(speed)
    assert rec["name"] == "slippery" == min(margins, key=margins.__getitem__)
    assert rec["rule"] == "smallest_margin" and rec["normal"] is None and rec["velocity"] == speed
    assert {r["name"]: r["value"] for r in rec["rows"]} == pytest.approx(margins, rel=1e-10)
    code, out, _ = _run(capsys, *command, "--device-file", path)
    named = [line for line in out.splitlines() if line.startswith("limiting configuration: slippery (margin")]
    assert code == 0 and len(named) == 1 and "Arm [slippery]" in out


def test_eq6_export_of_a_given_k_is_the_limiting_configurations_wall(capsys, tmp_path):
    path = _file(tmp_path, *TWO)
    code, worst, err = _run(capsys, "export", "--device-file", path, "--stiffness", "80", "--format", "json")
    assert code == 0 and err.startswith("dfa export: limiting configuration: slippery (margin")
    one = _run(capsys, "export", "--device-file", path, "--stiffness", "80", "--format", "json",
               "--configuration", "slippery")[1]  # fmt: skip
    a, b = json.loads(worst), json.loads(one)
    a.pop("command"), b.pop("command")
    assert a == b and a["device"]["name"] == "Arm [slippery]"


def test_params_gives_a_row_per_configuration_each_its_own_params(capsys, tmp_path):
    path = _file(tmp_path, *TWO)
    got = _json(capsys, "params", "--device-file", path)
    for row in got["configurations"]:
        one = _json(capsys, "params", "--device-file", path, "--configuration", row["name"])
        assert (row["mu"], row["beta"], row["sigma"]) == (one["mu"], one["beta"], one["sigma"])
    assert [r["limiting"] for r in got["configurations"]] == [False, True]
    assert got["sigma"] == got["configurations"][1]["sigma"] and got["configuration"]["name"] == "slippery"
    code, out, _ = _run(capsys, "params", "--device-file", path)
    assert code == 0 and "limiting configuration: slippery" in out and out.count("◀ limiting") == 1


def test_contours_plane_is_the_limiting_configurations(capsys, tmp_path):
    path = _file(
        tmp_path, 'name = "light"\nmass = 0.016\ncoulomb = 0.05', 'name = "heavy"\nmass = 0.064\ncoulomb = 0.012'
    )
    argv = ["contours", "--grid", "4", "--max-amplitude", "2"]
    worst = _json(capsys, *argv, "--device-file", path)
    one = _json(capsys, *argv, "--device-file", path, "--configuration", "heavy")
    rec = worst.pop("configuration")
    assert worst == one and rec["name"] == "heavy" and worst["mu"] == pytest.approx(0.064 / (80 * 0.002**2))


@pytest.mark.parametrize("axis", [0, 2])
def test_normal_along_an_axis_is_the_one_axis_device_with_the_effective_mass(capsys, tmp_path, axis):
    path = _file(tmp_path, f'name = "pose"\ninertia = {INERTIA}')
    normal = ["0", "0", "0"]
    normal[axis] = "-3"  # any length, either sign: the unit normal along the axis
    got = _json(capsys, "params", "--device-file", path, "--normal=" + ",".join(normal))  # '=': a leading minus
    m_n = 1.0 / float(np.linalg.inv(np.array(INERTIA))[axis, axis])
    one = _json(capsys, "params", "--mass", repr(m_n), "--damping", "0.02", "--coulomb", "0.024",
                "--resolution", "314e-6", "--period", "0.002", "--stiffness", "80")  # fmt: skip
    assert got["mu"] == pytest.approx(one["mu"], rel=1e-12) and got["sigma"] == one["sigma"]
    unit = [0.0, 0.0, 0.0]
    unit[axis] = -1.0
    assert got["configuration"]["normal"] == unit
    code, out, _ = _run(capsys, "params", "--device-file", path, "--normal=" + ",".join(normal))
    assert code == 0 and f"along n = ({', '.join(f'{x:g}' for x in unit)})" in out


@pytest.mark.parametrize(
    ("value", "words"),
    [("0,0,0", "length > 0"), ("1,2", "three finite numbers"), ("1,nan,0", "three finite numbers"),
     ("a,b,c", "three finite numbers")],
)  # fmt: skip
def test_bad_normals_are_refused_with_one_line(capsys, tmp_path, value, words):
    path = _file(tmp_path, f'name = "pose"\ninertia = {INERTIA}')
    code, _out, err = _run(capsys, "params", "--device-file", path, "--normal", value)
    assert code == 2 and words in err and err.count("\n") == 1


def test_normal_needs_an_inertia_matrix(capsys, tmp_path):
    path = _file(tmp_path, *TWO)
    code, _out, err = _run(capsys, "params", "--device-file", path, "--normal", "0,0,1")
    assert code == 2 and "needs an inertia matrix" in err and err.count("\n") == 1
    code, _out, err = _run(capsys, "params", "--device", "impulse", "--normal", "0,0,1")
    assert code == 2 and "has no configurations" in err


def test_xi_dot_is_refused_beside_configurations(capsys, tmp_path):
    code, _out, err = _run(capsys, "simulate", "--device-file", _file(tmp_path, *TWO), "--xi-dot", "0.3")
    assert code == 2 and "--xi-dot" in err and "--velocity" in err and err.count("\n") == 1


def test_configurations_plot_is_written_and_refused_without_configurations(capsys, tmp_path):
    path = _file(tmp_path, *TWO)
    fig = tmp_path / "c.svg"
    got = _json(capsys, "check", "--device-file", path, "--velocity", "0.05", "--configurations-plot", str(fig))
    assert got["configurations_plot"] == str(fig) and fig.read_text(encoding="utf-8").lstrip().startswith("<?xml")
    code, _out, err = _run(capsys, "check", "--device", "impulse", "--velocity", "0.05", "--configurations-plot",
                           str(fig))  # fmt: skip
    assert code == 2 and "needs a device file" in err


def test_the_template_writes_configurations_back_and_the_file_round_trips(tmp_path):
    confs = (
        Configuration("plain"),
        Configuration("far", mass=0.05, resolution=628e-6),
        Configuration("pose", inertia=INERTIA, damping=(0.02, 0.01, 0.04), normal=(1.0, 2.0, 3.0), pose=(0.1, 0, 0)),
        Configuration("open", inertia=INERTIA, coulomb=(0.03, 0.02, 0.025)),
    )
    entry = load_device_file(_file(tmp_path, *TWO))
    entry = type(entry)(**{**{f: getattr(entry, f) for f in entry.__dataclass_fields__}, "configurations": confs})
    path = tmp_path / "back.toml"
    path.write_text(device_template(entry), encoding="utf-8")
    again = load_device_file(str(path))
    assert again.configurations == confs and again == entry


def test_tune_prints_an_export_command_pinned_to_the_configuration_it_tuned():
    import argparse

    from dfa.cli import app
    from dfa.results.tune import TunedWall

    parser = app.build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction)).choices["tune"]
    dev = Device(0.032, 0.02, 0.024, 314e-6, 2e-3)
    argv = ["--device-file", "arm.toml", "--velocity", "0.05", "--configuration", "near", "--dampings", "0,1"]
    pin = ("--configuration", "far", "--normal", "0.0,0.6,0.8")
    cmd = export_command(argv, sub, TunedWall(dev, Wall.of(1.0), 100.0), dev, pin)
    assert cmd.startswith("dfa export --device-file arm.toml --velocity 0.05 --configuration far --normal 0.0,0.6,0.8")
    assert "near" not in cmd and "--dampings" not in cmd


@pytest.mark.slow  # one full answer: the one end-to-end check of the stiffness rule outside dfa stiffness
def test_export_velocity_exports_the_smallest_recommended_k_of_dfa_stiffness(capsys, tmp_path, monkeypatch):
    # the full answer's simulated limits searched small (2 speeds, 6 points): the K exported is the criterion's proof
    monkeypatch.setattr(kmax, "design_answer", fixed_keywords(kmax.design_answer, speeds=2, grid=6))
    path = tmp_path / "arm.toml"
    path.write_text(HEAD.replace("period = 0.002", "period = 0.001").replace("stiffness = 80.0\n", "")
                    + "".join("\n[[devices.configurations]]\n" + t + "\n" for t in TWO), encoding="utf-8")  # fmt: skip
    code, out, err = _run(capsys, "export", "--device-file", str(path), "--velocity", "0.1", "--format", "json")
    assert code == 0 and err.startswith("dfa export: limiting configuration: slippery (recommended K")
    got = json.loads(out)
    rows = _json(capsys, "stiffness", "--device-file", str(path), "--velocity", "0.1", "--quick")["rows"]
    ks = {r["name"]: r["value"] for r in rows}  # dfa stiffness's rule: the proven K of each, the smallest limits
    assert min(ks, key=ks.__getitem__) == "slippery" and got["rule"] == "proven"
    assert got["wall"]["stiffness"] == pytest.approx(ks["slippery"], rel=1e-12)
    assert got["device"]["name"] == "Arm [slippery]"


def _lowest(values: list) -> tuple[int, float | None]:
    """The index of the smallest of a B's limits over configurations (a limit without value, first), and it."""
    j = min(range(len(values)), key=lambda i: (values[i] is not None, values[i] or 0.0))
    return j, values[j]


@pytest.mark.slow  # three Z-widths of 3 × 3 (their describing-function columns): about 5 s
def test_zwidth_of_two_configurations_is_the_minimum_of_their_z_widths_b_by_b(capsys, tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(HEAD.replace("stiffness = 80.0\n", "") + '\n[[devices.configurations]]\nname = "near"\n'
                    '\n[[devices.configurations]]\nname = "slippery"\ncoulomb = 0.012\n', encoding="utf-8")  # fmt: skip
    code, out, _ = _run(capsys, "zwidth", "--device-file", str(path), "--velocity", "0.1", "--grid", "3",
                        "--speeds", "1", "--jobs", "1", "--json")  # fmt: skip
    assert code == 0
    zw = json.loads(out)
    assert zw["configuration"]["rule"] == "minimum_per_damping"
    ks, bs = zw["stiffness"], zw["damping"]
    singles = {}  # each configuration's own Z-width on the same grid, by flags (its device file is not read)
    for name, c in (("near", 0.024), ("slippery", 0.012)):
        dev = Device(0.032, 0.02, c, 314e-6, 0.002, name=name)
        singles[name] = z_width(Loop(dev), 0.1, grid=3, k_range=(ks[0], ks[-1]), b_range=(bs[0], bs[-1]), speeds=1,
                                n_jobs=1).boundaries  # fmt: skip
    names = list(singles)
    for m in ("linear", "criterion", "df", "sim", "rest"):
        for i in range(3):
            values = [None if math.isnan(singles[n][m][i]) else float(singles[n][m][i]) for n in names]
            j, low = _lowest(values)
            assert zw["boundaries"][m][i] == (None if low is None else pytest.approx(low, rel=1e-9)), (m, i)
            if len({v for v in values}) > 1:  # a tie names the first
                assert zw["limiting"][m][i] == names[j], (m, i)
    assert zw["limiting"]["criterion"][0] == "slippery"  # less friction: a smaller proven K at B = 0


def test_devices_template_of_a_device_file_writes_it_back_and_it_round_trips(capsys, tmp_path):
    path = _file(
        tmp_path, *TWO, f'name = "pose"\ninertia = {INERTIA}\ncoulomb = [0.03, 0.02, 0.025]\npose = [0.1, 0, 0]'
    )
    code, out, _ = _run(capsys, "devices", "--template", "--device-file", path)
    assert code == 0 and out.count("[[devices.configurations]]") == 3
    back = tmp_path / "back.toml"
    back.write_text(out, encoding="utf-8")
    assert load_device_file(str(back)) == load_device_file(path)  # every value and configuration, read back
    code, again, _ = _run(capsys, "devices", "--template", "--device-file", str(back))
    assert code == 0 and again == out  # a fixed point: written twice, the same text
    code, out, _ = _run(capsys, "devices", "--template", "--device", "impulse")
    assert code == 0 and 'name = "Impulse Engine"' in out and "[[devices.configurations]]" not in out


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (("--device", "impulse"), "needs --template"),
        (("--template", "--device", "impulse", "--device-file", "x.toml"), "cannot both be given"),
        (("--template", "--device-file", "missing.toml"), "cannot be read"),
    ],
)
def test_devices_template_flags_are_refused_with_one_line(capsys, argv, words):
    code, out, err = _run(capsys, "devices", *argv)
    assert code == 2 and out == "" and err.count("\n") == 1 and words in err, err
