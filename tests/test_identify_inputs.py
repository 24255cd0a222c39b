"""Sharp edges of `dfa identify` and its log reader found by the fuzz (issue 41 §3): legal but extreme numbers, a
huge CSV cell, a log of too many rows, flags that no device on the log's grid can take. Each is refused in one line
naming the column or flag, the value, the rule and a fix (exit 2), before the fit where it can be; none gives a
traceback.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np
import pytest

import dfa
import dfa.analysis.identify as identify_module
from dfa.analysis.identify import MAX_FORCE_PER_TICK, MAX_TICKS, PERIOD_RANGE, identify, log_grid, synthetic_log
from dfa.cli import main
from dfa.errors import DFATypeError, ImplausibleInputWarning
from dfa.model.log import MAX_LOG_ROWS, DeviceLog, LogError, read_log


def _moving_log(n: int = 600, mass: float = 0.32) -> DeviceLog:
    """A log on a uniform grid of a device that moves and reverses (square plus sine force), so that a fit reaches
    its arithmetic; a heavier ``mass`` has its damping, friction and forces scaled with it (the same motion)."""
    k = mass / 0.32
    dev = dfa.Device(mass, 4.0 * k, 0.2 * k, 1e-5, 1e-3)
    t = np.arange(n) * 1e-3
    force = 0.6 * np.sign(np.sin(2 * np.pi * t / 0.48)) + 0.3 * np.sin(2 * np.pi * 3.3 * t / 0.48)
    return synthetic_log(dev, k * force)


def _write(path: Path, t: np.ndarray, x: np.ndarray, f: np.ndarray) -> str:
    """The columns written with every digit (repr), so that extreme values reach the reader as they are."""
    rows = "".join(f"{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in zip(t, x, f, strict=True))
    path.write_text("t,x,f\n" + rows, encoding="utf-8")
    return str(path)


def _refused(capsys, argv: list[str]) -> str:
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 2 and err.count("\n") == 1 and "Traceback" not in err and not out, (code, err)
    return err


def _no_fit(monkeypatch) -> None:
    """Make the fit fail loudly: a refusal that comes before it does not reach it."""

    def fit(*_a, **_k):
        raise AssertionError("the fit ran: the input should have been refused before it")

    monkeypatch.setattr(identify_module, "_fit", fit)


LOG = _moving_log()
#: Columns and flags no float arithmetic of the fit can take (the fuzz's tracebacks and the mass = inf message),
#: and what the refusal must name: the column or flag, the value, the limit.
EXTREME = {
    "force 1e308": ((LOG.t, LOG.x, np.where(LOG.f >= 0.0, 1e308, -1e308)), [],
                    ["column 'f' reaches 1e+308 N", f"at most {MAX_FORCE_PER_TICK:g}", "f in N"]),
    "readings near 1e-315": ((LOG.t, 1e-315 + np.rint(LOG.x / 1e-5) * 1e-320, LOG.f), [],
                             ["(the readings' step) is invalid", "normal float >= 2.23e-308", "x in m"]),
    "resolution 5e-324": ((LOG.t, LOG.x, LOG.f), ["--resolution", "5e-324"],
                          ["resolution = 4.941e-324 m is invalid", ">= 2.23e-308", "leave it out"]),
    "resolution 1e-300": ((LOG.t, LOG.x, LOG.f), ["--resolution", "1e-300"],
                          ["resolution = 1e-300 m is invalid", f"at most {MAX_TICKS:g}", "ticks of it"]),
    "time steps of 1e300": ((LOG.t * 1e303, LOG.x, LOG.f), [],
                            ["the sample period T = 1e+300 s (the step of column 't')", f"{PERIOD_RANGE[1]:.3g}] s",
                             "give t in s"]),
}  # fmt: skip


@pytest.mark.parametrize("case", list(EXTREME))
def test_identify_refuses_extreme_numbers_before_the_fit(tmp_path, capsys, monkeypatch, case):
    """Force 1e308, readings near 1e-315, --resolution 5e-324 or 1e-300 gave a traceback ('array must not contain
    infs or NaNs'); time steps of 1e300 'mass = inf … give the moving mass': now one line naming the user's value
    and the limit it crosses, before the fit."""
    columns, flags, needles = EXTREME[case]
    path = _write(tmp_path / "log.csv", *columns)
    _no_fit(monkeypatch)
    err = _refused(capsys, ["identify", path, "--bootstrap", "0", *flags])
    assert all(n in err for n in needles), err
    assert "moving mass" not in err


def test_identify_names_the_log_when_the_fit_gives_values_no_float_holds():
    """Readings over ±1e308 fit to a mass of 4e-311 kg: refused naming the log's grid, not as a mass the user gave
    (Device's 'mass = … give the moving mass')."""
    x = (LOG.x - LOG.x.mean()) / np.ptp(LOG.x) * 1.5e308
    with pytest.raises(LogError, match=r"overflow or vanish in a float with the log's period T = 0\.001 s"):
        identify(DeviceLog(LOG.t, x, LOG.f), bootstrap=0)


def test_identify_checks_stiffness_and_velocity_against_the_grid_before_the_fit(tmp_path, capsys, monkeypatch):
    """--stiffness 5e-324 exited 2 after the whole fit, naming the identified mass; --velocity 1e308 named an
    internal speed (1.67e307): both are refused before the fit, naming the flag and the product that leaves a float."""
    path = _write(tmp_path / "log.csv", LOG.t, LOG.x, LOG.f)
    _no_fit(monkeypatch)
    err = _refused(capsys, ["identify", path, "--stiffness", "5e-324"])
    assert "--stiffness 4.94066e-324 is invalid" in err and "K T² underflows a float" in err and "mass" not in err
    err = _refused(capsys, ["identify", path, "--stiffness", "500", "--velocity", "1e308"])
    assert "--velocity 1e+308 is invalid" in err and "V T/Δ overflows a float" in err


def test_identify_warns_of_implausible_flags_before_the_fit():
    """--stiffness 1e308 (a float a device's groups can take) ran without a word: it warns with the flag checks."""
    from dfa.cli.identify import _check_flags

    args = argparse.Namespace(resolution=None, period=None, stiffness=1e308, velocity=None, report=None, force=False,
                              plot=None, bootstrap=0, rotary=False)  # fmt: skip
    with pytest.warns(ImplausibleInputWarning, match=r"--stiffness 1e\+?308 is above"):
        _check_flags(args)


@pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")  # 200 kg: no haptic device
def test_identify_loop_names_the_identified_mass_not_a_flag(tmp_path, capsys):
    """A 200 kg device at K = 1e-300 N/m: μ = m/(K T²) overflows after the fit; the message calls m the identified
    mass (it named it 'mass = 200' as if the user had given it)."""
    log = _moving_log(mass=200.0)
    path = _write(tmp_path / "heavy.csv", log.t, log.x, log.f)
    err = _refused(capsys, ["identify", path, "--bootstrap", "0", "--stiffness", "1e-300"])
    assert "identified mass = " in err and "--stiffness = 1e-300" in err and "overflows" in err, err


def test_read_log_refuses_a_huge_cell_in_one_line(tmp_path, capsys):
    """A cell over the csv module's field limit raised `_csv.Error: field larger than field limit`."""
    path = tmp_path / "cell.csv"
    rows = "".join(f"{i * 1e-3},{i * 1e-5},1\n" for i in range(30))
    path.write_text("t,x,f\n" + rows + "0.03,3e-4," + "9" * 200_000 + "\n", encoding="utf-8")
    with pytest.raises(LogError, match="row 32 holds a cell of more than 131072 characters"):
        read_log(path)
    assert "cell of more than" in _refused(capsys, ["identify", str(path)])


def test_identify_budgets_the_rows(tmp_path, capsys, monkeypatch):
    """A log of more rows than MAX_LOG_ROWS (a 560 000-row log took 643 MB and minutes) is refused with the cap, the
    reason and the fix: by the reader as it reaches the row after the cap, and by identify before its fit."""
    n = MAX_LOG_ROWS + 1
    path = tmp_path / "long.csv"
    path.write_text("t,x,f\n" + "".join(f"{i}e-3,{i % 7}e-5,1\n" for i in range(n)), encoding="utf-8")
    err = _refused(capsys, ["identify", str(path)])
    assert f"more than {MAX_LOG_ROWS} rows" in err and "half a minute" in err and "cut the log" in err
    with pytest.raises(LogError, match="more than 40 rows"):
        read_log(path, max_rows=40)
    _no_fit(monkeypatch)
    long = DeviceLog(np.arange(n) * 1e-3, 1e-5 * (np.arange(n) % 7), np.ones(n))
    with pytest.raises(LogError, match=f"more than {MAX_LOG_ROWS} rows"):
        identify(long)


def test_log_flags_are_booleans():
    """DeviceLog(rotary=...) and identify(progress=...) read any object by its truth value (an empty array raised
    numpy's ValueError): True or False only."""
    with pytest.raises(DFATypeError, match="rotary = 'no'"):
        DeviceLog(LOG.t, LOG.x, LOG.f, rotary="no")  # type: ignore[arg-type]
    with pytest.raises(DFATypeError, match="progress = <array of shape"):
        identify(LOG, progress=np.array([]))  # type: ignore[arg-type]


def test_log_grid_is_what_identify_fits_with():
    """log_grid gives identify's Δ and T without a fit (the CLI checks its flags with it)."""
    delta, t = log_grid(LOG)
    assert delta == pytest.approx(1e-5, rel=1e-9) and t == pytest.approx(1e-3, rel=1e-9)
    r = identify(LOG, bootstrap=0)
    assert json.loads(json.dumps(r.device.to_dict()))["resolution"] == pytest.approx(delta, rel=1e-12)


def test_read_log_skips_blank_lines_before_the_header_and_names_a_file_of_comments_only(tmp_path):
    """A Markdown file (a comment line, a blank line, prose) is refused for its header, not called empty; blank
    lines before a log's header are skipped; a file of comments only is said to be that."""
    prose = tmp_path / "README.md"
    prose.write_text("# Example logs\n\nLogs to try dfa identify on\n", encoding="utf-8")
    with pytest.raises(LogError, match="the header 'Logs to try dfa identify on' has no column"):
        read_log(prose)
    comments = tmp_path / "c.csv"
    comments.write_text("# only\n\n# comments\n", encoding="utf-8")
    with pytest.raises(LogError, match="holds only comment lines"):
        read_log(comments)
    empty = tmp_path / "e.csv"
    empty.write_text("", encoding="utf-8")
    with pytest.raises(LogError, match="the file is empty"):
        read_log(empty)
    log = synthetic_log(dfa.get_device("impulse").device, np.full(40, 0.05))
    good = tmp_path / "g.csv"
    dfa.model.log.write_log(log, good)
    blank = tmp_path / "b.csv"
    blank.write_text("\n\n" + good.read_text(encoding="utf-8"), encoding="utf-8")
    assert np.array_equal(read_log(blank).x, read_log(good).x)


@pytest.mark.parametrize("seed", range(6))
def test_first_guess_nonnegative_least_squares_equals_scipy_nnls(seed):
    """The first guess's three-column non-negative least squares (written out to spare `dfa identify` the import
    of scipy.optimize) against scipy's nnls, an independent solver, on random problems with active bounds."""
    from scipy.optimize import nnls

    rng = np.random.default_rng(seed)
    rows = rng.normal(size=(500, 3))
    y = rows @ np.array([1.5, -0.7, 0.3]) * rng.choice([1.0, -1.0]) + 0.1 * rng.normal(size=500)
    ours = identify_module._nonnegative_least_squares(rows, y)
    theirs, _ = nnls(rows, y)
    np.testing.assert_allclose(ours, theirs, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("size", [5, 6, 10, 31, 95, 4000])
@pytest.mark.parametrize("deriv", [0, 1, 2])
def test_first_guess_savgol_equals_scipy_savgol_filter(size, deriv):
    """The readings' Savitzky–Golay smoothing and derivatives (written out to spare `dfa identify` the import of
    scipy.signal) against scipy's savgol_filter in its default mode, edges included, on quantized random walks
    (windows of 5 to 31 samples)."""
    from scipy.signal import savgol_filter

    n = np.floor(np.cumsum(np.random.default_rng(size).normal(0.0, 3.0, size)))
    ours = identify_module._savgol(n, deriv)
    theirs = savgol_filter(n, identify_module._window(size), 3, deriv=deriv)
    np.testing.assert_allclose(ours, theirs, rtol=0.0, atol=1e-12 * max(1.0, float(np.max(np.abs(n)))))


def test_intervals_t_quantile_equals_scipy_stdtrit():
    """Student's t quantile of the bootstrap's intervals (written out to spare `dfa identify` the import of
    scipy.special) against scipy's stdtrit for every count of replicates identify takes; and the closed forms
    at 1 and 2 degrees of freedom (tan(0.475 π), √(2/(1 − 0.95²)) · 0.95)."""
    from scipy.special import stdtrit

    from dfa.analysis.identify import MAX_BOOTSTRAP

    ours = np.array([identify_module._t_quantile(df) for df in range(1, MAX_BOOTSTRAP)])
    np.testing.assert_allclose(ours, stdtrit(np.arange(1, MAX_BOOTSTRAP), 0.975), rtol=1e-13)
    assert identify_module._t_quantile(1) == pytest.approx(np.tan(0.475 * np.pi), rel=1e-14)
    assert identify_module._t_quantile(2) == pytest.approx(0.95 * np.sqrt(2.0 / (1.0 - 0.95**2)), rel=1e-14)


def _fit_problem() -> tuple[np.ndarray, ...]:
    """A fitted log's readings, forces, weights, segments' starts, θ and bounds (a dropped sample included)."""
    log = _moving_log(1500)
    keep = np.r_[0:700, 701:1500]
    delta, timing, index, rows = identify_module._ticks(DeviceLog(log.t[keep], log.x[keep], log.f[keep]), None, None)
    n, phi, w = identify_module._on_grid(index, rows, log.f[keep] / delta)
    best, starts = identify_module._fit(n, phi, w)
    j = len(starts)
    lo = np.concatenate([[-np.inf, 0.0, 0.0, -np.inf], np.zeros(j), np.full(j, -np.inf)])
    hi = np.concatenate([[np.inf] * 4, np.ones(j), np.full(j, np.inf)])
    return n, phi, w, starts, best.x, lo, hi


def test_fit_jacobian_equals_column_by_column_forward_differences():
    """The fit's Jacobian, its six moved predictions run in one compiled call, against the forward differences
    taken one parameter group at a time with the prediction of the fit itself (_residual): bit for bit."""
    n, phi, w, starts, theta, lo, hi = _fit_problem()
    j = len(starts)
    seg = identify_module._segment_of(starts, len(n))
    r = identify_module._residual(theta, n, phi, w, starts, np.empty(len(n)))
    jac = identify_module._jacobian(theta, r, n, phi, w, starts, seg, lo, hi)
    h = identify_module.FD_STEP * np.where(theta >= 0.0, 1.0, -1.0) * np.maximum(1.0, np.abs(theta))
    h = np.where((theta + h > hi) | (theta + h < lo), -h, h)
    h = (theta + h) - theta
    for k, part in enumerate((slice(0, 1), slice(1, 2), slice(2, 3), slice(3, 4), slice(4, 4 + j), slice(4 + j, None))):
        moved = theta.copy()
        moved[part] += h[part]
        step = h[part][seg] if k >= 4 else h[part]
        column = (identify_module._residual(moved, n, phi, w, starts, np.empty(len(n))) - r) / step
        np.testing.assert_array_equal(jac[:, k], column)


def test_fit_normal_blocks_equal_numpy_sums():
    """The block-arrow normal equations summed in one compiled pass against numpy's sums of the same products
    (GᵀG, per segment GₖᵀLₖ, LₖᵀLₖ, Lₖᵀr, and Gᵀr), at a point away from the minimum (Jᵀr not near 0)."""
    n, phi, w, starts, theta, lo, hi = _fit_problem()
    theta = theta * 1.01
    r = identify_module._residual(theta, n, phi, w, starts, np.empty(len(n)))
    jac = identify_module._jacobian(theta, r, n, phi, w, starts, identify_module._segment_of(starts, len(n)), lo, hi)
    g, loc = jac[:, :4], jac[:, 4:]
    numpy_sums = (g.T @ g, np.add.reduceat(g[:, :, None] * loc[:, None, :], starts, axis=0),
                  np.add.reduceat(loc[:, :, None] * loc[:, None, :], starts, axis=0), g.T @ r,
                  np.add.reduceat(loc * r[:, None], starts, axis=0))  # fmt: skip
    for ours, theirs in zip(identify_module._normal_blocks(jac, r, starts), numpy_sums, strict=True):
        np.testing.assert_allclose(ours, theirs, rtol=1e-10, atol=1e-10 * float(np.max(np.abs(theirs))))
