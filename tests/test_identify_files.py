"""A log's columns and units named on the command line, and the identified device written as a device file
(issue 45 d).

Checks: a log with other column names, times in ms and positions in encoder counts identifies the same device as
the same log in t, x, f and SI (an independent reading of the same run); bad combinations are refused in one line;
the written device file loads back (`load_device_file`) with the identified values to their printed digits, names
the log and its date, holds the intervals, and every command that takes a device runs with it.
"""

from __future__ import annotations

import datetime
import json
import os

import numpy as np
import pytest

import dfa
from dfa.analysis.identify import identify, synthetic_log
from dfa.cli import main
from dfa.model.catalogue import load_device_file
from dfa.model.log import DeviceLog, read_log, write_log

DEV = dfa.Device(0.1, 0.5, 0.2, 1e-5, 1e-3)


@pytest.fixture(scope="module")
def logs(tmp_path_factory):
    """The same run written twice: t,x,f in SI, and time;pos;force in ms and counts (semicolons)."""
    folder = tmp_path_factory.mktemp("logs")
    t = np.arange(3000) * DEV.period
    log = synthetic_log(DEV, 2.0 * np.sign(np.sin(2 * np.pi * 2.0 * t)) + 1.0 * np.sin(2 * np.pi * 7.0 * t))
    si = write_log(log, folder / "si.csv")
    rows = "".join(
        f"{a * 1e3:.12g};{round(x / DEV.resolution)};{f:.12g}\n" for a, x, f in zip(log.t, log.x, log.f, strict=True)
    )
    (folder / "named.csv").write_text("Time;Pos;force (N)\n" + rows, encoding="utf-8")
    return si, str(folder / "named.csv")


NAMED = ["--columns", "t=time,x=pos,f=force", "--t-unit", "ms", "--x-unit", "counts", "--resolution", "1e-5"]


def test_named_columns_in_ms_and_counts_identify_the_si_log(logs, capsys):
    si, named = logs
    log = read_log(named, columns={"t": "time", "x": "pos", "f": "force"}, units={"t": "ms", "x": "counts"}, count=1e-5)
    ref = read_log(si)
    assert np.allclose(log.t, ref.t, rtol=0, atol=1e-15) and np.allclose(log.x, ref.x, rtol=1e-12, atol=0)
    assert main(["identify", si, "--bootstrap", "0", "--json", "--resolution", "1e-5"]) == 0
    want = json.loads(capsys.readouterr().out)
    assert main(["identify", named, "--bootstrap", "0", "--json", *NAMED]) == 0
    got = json.loads(capsys.readouterr().out)
    for k in ("mass", "damping", "coulomb"):
        assert got[k]["value"] == pytest.approx(want[k]["value"], rel=1e-9)


@pytest.mark.parametrize(
    "extra, words",
    [
        (
            ["--columns", "t=time,x=pos,f=force", "--t-unit", "ms", "--x-unit", "counts"],
            "--x-unit counts needs --resolution",
        ),
        (["--columns", "t=time,x=pos,f=effort"], "no column 'effort' (for f)"),
        (["--columns", "t=time,x=pos,f=force,x=y"], "--columns"),
        (
            [
                "--columns",
                "t=time,x=pos,f=force",
                "--t-unit",
                "ms",
                "--x-unit",
                "counts",
                "--resolution",
                "1e-5",
                "--f-unit",
                "mN",
            ],
            "is in 'N' by the header but --f-unit says 'mN'",
        ),  # fmt: skip
        (["--columns", "t=time,x=pos,f=force", "--t-unit", "fortnight"], "column 't' is in 'fortnight'"),
    ],
    ids=["counts without resolution", "missing named column", "column twice", "unit conflict", "unknown unit"],
)
def test_bad_column_and_unit_flags_are_refused_in_one_line(logs, capsys, extra, words):
    assert main(["identify", logs[1], "--bootstrap", "0", *extra]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err, err


def test_written_device_file_reads_back_with_the_identified_values(logs, tmp_path, capsys):
    si = logs[0]
    path = tmp_path / "identified.toml"
    assert main(["identify", si, "--bootstrap", "2", "--json", "--write-device", str(path), "--stiffness", "500"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["device_file"] == str(path)
    e = load_device_file(path)
    for k in ("mass", "damping", "coulomb"):  # the value to its printed digits: within a tenth of the half-width
        half = (d[k]["high"] - d[k]["low"]) / 2
        assert abs(getattr(e, k) - d[k]["value"]) <= 0.1 * half + 1e-15, k
        assert getattr(e, k) == pytest.approx(getattr(DEV, k), rel=1e-3)
    assert (e.resolution, e.period, e.stiffness) == (1e-5, 1e-3, 500.0)
    date = datetime.datetime.fromtimestamp(os.stat(si).st_mtime, tz=datetime.timezone.utc).date().isoformat()
    assert "si.csv" in e.source and date in e.source and e.kind == "haptic device"
    assert e.notes.count("95 % interval") == 4 and "status ok" in e.notes
    for argv in (["params"], ["check", "--velocity", "0.05"], ["simulate", "--velocity", "0.05", "--samples", "100"],
                 ["limit-cycles", "--max-amplitude", "5"], ["stiffness", "--velocity", "0.05", "--quick"],
                 ["require", "--velocity", "0.05", "--stiffness", "500"]):  # fmt: skip
        assert main([argv[0], "--device-file", str(path), *argv[1:]]) == 0, argv
        out = capsys.readouterr().out
        assert "device identified from si.csv" in out, argv
    for argv, name in ((["map", "--grid", "4", "--velocity", "0.05"], "m.npz"), (["contours", "--grid", "20"], "c.npz"),
                       (["export", "--format", "json"], "w.json")):  # fmt: skip  # files: their written line
        out_file = tmp_path / name
        assert main([argv[0], "--device-file", str(path), *argv[1:], "--out", str(out_file)]) == 0, argv
        capsys.readouterr()
        assert out_file.stat().st_size > 0, argv
    assert json.loads((tmp_path / "w.json").read_text())["wall"]["stiffness"] == 500.0  # the file's K, exported


@pytest.mark.filterwarnings("ignore::dfa.plausibility.ImplausibleInputWarning")  # the poor fit's mass
def test_no_device_file_after_a_poor_fit(tmp_path, capsys):
    """A log whose force column is the opposite of what drove the device: poor fit, no file."""
    t = np.arange(3000) * DEV.period
    log = synthetic_log(DEV, 2.0 * np.sign(np.sin(2 * np.pi * 2.0 * t)))
    path = write_log(DeviceLog(log.t, log.x, -log.f), tmp_path / "wrong.csv")
    assert identify(read_log(path), bootstrap=0).status.value == "poor_fit"
    assert main(["identify", path, "--bootstrap", "0", "--write-device", str(tmp_path / "d.toml")]) == 2
    assert "not written" in capsys.readouterr().err and not (tmp_path / "d.toml").exists()
