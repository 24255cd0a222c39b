"""Work refused up front (issue 27 §2): contours, zwidth and report's Z-width estimated over the CLI's time limit
are refused in one line naming the flags, the estimate and the fix, unless --force; the estimates scale as planned."""

from __future__ import annotations

import pytest

import dfa.cli.output as output
from dfa import get_device
from dfa.analysis.contours import contour_seconds
from dfa.analysis.limits.zwidth import MAX_SPEEDS, z_width, z_width_seconds
from dfa.cli import main
from dfa.errors import DFAValueError


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize(
    ("argv", "flags"),
    [
        (("contours", "--mu", "5", "--grid", "2000"), "--grid 2000 with --max-amplitude 200"),
        (("zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "200"), "--grid 200 with --speeds 2"),
        (("report", "--device", "impulse", "--velocity", "0.1", "--zwidth", "200", "--out", "unused"), "--zwidth 200"),
    ],
)
def test_work_over_the_time_limit_is_refused_in_one_line_before_any_work(capsys, tmp_path, argv, flags):
    argv = tuple(str(tmp_path / "r") if a == "unused" else a for a in argv)
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith(f"dfa {argv[0]}: error: {flags} could take up to ")
    assert f"(estimated; limit {output.WORK_TIME_LIMIT:g} s)" in err and err.rstrip().endswith(", or add --force")
    assert not (tmp_path / "r").exists()  # the report's folder is not made either


def test_force_runs_what_the_time_limit_refuses(capsys, monkeypatch):
    monkeypatch.setattr(output, "WORK_TIME_LIMIT", 1e-3)  # every estimate is above it now
    argv = ("contours", "--mu", "5", "--grid", "8", "--max-amplitude", "5")
    assert run(capsys, *argv)[0] == 2
    code, out, _ = run(capsys, *argv, "--force")
    assert code == 0 and "contour maps μ = 5" in out


def test_zwidth_speeds_above_the_maximum_are_refused_by_the_cli_and_the_api(capsys):
    code, _, err = run(
        capsys, "zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "3", "--speeds", "1000000"
    )
    assert code == 2 and f"it must be at most {MAX_SPEEDS}" in err
    dev = get_device("Impulse Engine").device
    with pytest.raises(DFAValueError, match=f"speeds = {MAX_SPEEDS + 1} is invalid"):
        z_width(dev, 0.1, grid=3, speeds=MAX_SPEEDS + 1)


def test_estimates_grow_with_the_work_they_plan():
    # contours: the grid's points and the amplitude samples per row; zwidth: the grid's points, the speeds, the cores
    c = [contour_seconds(g, m) for g, m in ((100, 10.0), (200, 10.0), (400, 10.0), (400, 1000.0))]
    assert c[0] < c[1] < c[2] < c[3]
    assert c[2] - c[1] > 2.0 * (c[1] - c[0])  # grid points grow as the square of the grid
    dev = get_device("Impulse Engine").device
    one = z_width_seconds(dev, 0.1, grid=24, n_jobs=1)
    assert z_width_seconds(dev, 0.1, grid=24, n_jobs=2) == pytest.approx(one / 2)
    assert z_width_seconds(dev, 0.1, grid=48, n_jobs=1) >= 3.0 * one  # samples ×4, boundary columns ×2
    assert z_width_seconds(dev, 0.1, grid=24, speeds=4, n_jobs=1) > one


def test_grid_limits_come_before_the_time_estimate_so_force_cannot_reach_them(capsys, tmp_path):
    # --force used to lift the time refusal only to meet the 200-point limit (report: after its other sections)
    code, _, err = run(capsys, "zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "300", "--force")
    assert code == 2 and "--grid 300 is invalid: it must be at most 200" in err
    argv = (
        "report",
        "--device",
        "impulse",
        "--velocity",
        "0.1",
        "--zwidth",
        "300",
        "--force",
        "--out",
        str(tmp_path / "r"),
    )
    code, _, err = run(capsys, *argv)
    assert code == 2 and "--zwidth 300 is invalid: it must be at most 200" in err and not (tmp_path / "r").exists()
    from dfa.studies.design import design_analysis

    with pytest.raises(DFAValueError, match="zwidth_grid = 300 is invalid"):
        design_analysis(get_device("Impulse Engine"), velocity=0.1, zwidth_grid=300)
