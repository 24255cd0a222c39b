"""``dfa export`` on the command line (issue 44): the header's constants are the device's and the wall's, its comment
names the device, the speed, the rule and the command; --from reads a JSON export back; bad input is one line on
stderr and exit 2. The recommended K is recommend_stiffness's (the API), and the header the CLI writes compiles and
gives the simulator's forces (tests/test_export_c.py's check)."""

from __future__ import annotations

import json
import re
import sys

import pytest
import yaml
from test_export_c import check_equal, crossings, readings

from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.recommend import recommend_stiffness
from dfa.cli import main
from dfa.model.catalogue import get_device
from dfa.model.loop import Loop
from dfa.model.wall import Wall
from dfa.results.deploy import DeployableWall

DEV = get_device("impulse").device
ARGV = ["export", "--device", "impulse", "--stiffness", "100", "--virtual-damping", "0.5"]


def run(capsys, monkeypatch, *argv):
    monkeypatch.setattr(sys, "argv", ["dfa", *argv])
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def defines(header: str) -> dict[str, float]:
    return {
        m[1]: float(m[2].strip("()"))
        for m in re.finditer(r"^#define (DFA_WALL_\w+)\s+(\(?[-\d.e+]+\)?)\s", header, re.M)
    }


def test_export_cli_header_constants_match_the_device_and_wall(capsys, monkeypatch, tmp_path):
    out = tmp_path / "f.h"
    code, stdout, err = run(capsys, monkeypatch, *ARGV, "--format", "c", "--out", str(out))
    assert code == 0, err
    assert str(out) in stdout
    header = out.read_text(encoding="ascii")
    c = defines(header)
    assert c["DFA_WALL_FORCE_STEP"] == pytest.approx(100.0 * DEV.resolution, rel=1e-15)
    assert c["DFA_WALL_STIFFNESS"] == 100.0 and c["DFA_WALL_RESOLUTION"] == DEV.resolution
    assert c["DFA_WALL_PERIOD"] == DEV.period and c["DFA_WALL_DELAY"] == 0
    assert c["DFA_WALL_DAMPING"] == pytest.approx(0.5 / (100.0 * DEV.period), rel=1e-15)  # β_B = B/(K T)
    comment = " ".join(header.split("*/")[0].replace("*", " ").split())
    assert "Impulse Engine" in comment and "rule 'given'" in comment
    assert (
        f"Command: dfa export --device impulse --stiffness 100 --virtual-damping 0.5 --format c --out {out}" in comment
    )
    dep = DeployableWall.given(Loop(DEV, Wall.of(100.0, damping=0.5)))
    check_equal(dep, readings(4), tmp_path)  # the same wall's forces, compiled from the API's header
    assert header.split("#ifndef")[1] == dfa_header(dep).split("#ifndef")[1]


def dfa_header(dep: DeployableWall) -> str:
    from dfa.render.export import c_header

    return c_header(dep)


def test_export_cli_velocity_exports_the_recommended_k_and_its_rule(capsys, monkeypatch, tmp_path):
    code, out, err = run(capsys, monkeypatch, "export", "--device", "impulse", "--velocity", "0.1", "--format", "json")
    assert code == 0, err
    data = json.loads(out)
    rec = recommend_stiffness(design_answer(Loop(DEV), 0.1))
    assert data["rule"] == rec.status.value and data["velocity"] == 0.1
    assert data["wall"]["stiffness"] == pytest.approx(rec.k_recommended, rel=1e-12)
    assert data["command"] == "dfa export --device impulse --velocity 0.1 --format json"
    path = tmp_path / "w.json"
    path.write_text(out, encoding="utf-8")
    code, header, err = run(capsys, monkeypatch, "export", "--from", str(path))
    assert code == 0, err
    comment = " ".join(header.split("*/")[0].replace("*", " ").split())
    assert f"impact speed of 0.1 m/s by the rule '{rec.status.value}'" in comment
    assert "(the wall of: dfa export --device impulse --velocity 0.1 --format json)" in comment
    dep = DeployableWall.from_dict(data)
    check_equal(dep, crossings(5), tmp_path)
    assert defines(header) == defines(dfa_header(dep))


def test_export_cli_yaml_reads_back(capsys, monkeypatch):
    code, out, err = run(
        capsys, monkeypatch, *ARGV, "--format", "yaml", "--passivity-controller", "--pc-window", "0.01"
    )
    assert code == 0, err
    dep = DeployableWall.from_dict(yaml.safe_load(out))
    assert dep.stiffness == 100.0 and dep.wall.passivity_controller is not None
    assert dep.wall.passivity_controller.window == 0.01 and dep.rule.value == "given"


@pytest.mark.parametrize(
    "argv, message",
    [
        (["--device", "impulse", "--stiffness", "100", "--velocity", "0.1"], "--velocity and --stiffness cannot both"),
        ([*ARGV[1:], "--format", "c", "--out", "wall.yaml"], "--out 'wall.yaml' is invalid: the file name must end"),
        ([*ARGV[1:], "--out", "no/such/folder/wall.h"], "does not exist"),
        (["--from", "missing.json"], "--from 'missing.json' is invalid: no such file"),
        (["--from", "x.json", "--device", "impulse"], "--from 'x.json' cannot be combined with device flags"),
        (
            ["--mass", "0.1", "--damping", "0", "--coulomb", "0", "--resolution", "1e-5", "--period", "1e-3"],
            "missing --stiffness",
        ),
        ([*ARGV[1:], "--format", "h"], "--format"),
    ],
    ids=["both", "suffix", "folder", "from_missing", "from_and_device", "no_k", "format"],
)
def test_export_cli_bad_input_one_line_exit_2(capsys, monkeypatch, argv, message):
    code, out, err = run(capsys, monkeypatch, "export", *argv)
    assert code == 2
    assert out == "" and message in err and len(err.strip().splitlines()) == 1, err


def test_export_cli_from_refuses_a_file_that_is_no_export(capsys, monkeypatch, tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"device": {"name": "x"}}', encoding="utf-8")
    code, out, err = run(capsys, monkeypatch, "export", "--from", str(path))
    assert code == 2 and f"--from '{path}' is invalid" in err and len(err.strip().splitlines()) == 1
