"""Bad values of numeric flags found by running every subcommand with one bad value per flag (issue 17 style):
each is refused with one line on stderr, exit 2, naming the flag the user typed, the value, the rule and a fix;
none is silently transformed and none ends in a traceback."""

from __future__ import annotations

import re

import pytest

from dfa.analysis.linear import critical_stiffness
from dfa.cli import main
from dfa.errors import DFAValueError


def _refused(capsys, *argv: str) -> str:
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and err.startswith("dfa") and "Traceback" not in err, err
    return err


DIMLESS = ["--mu", "5", "--beta", "0.1", "--sigma", "0.3"]
MAP = ["map", "--mu", "100", "--xi-dot", "1", "--grid", "2", "--samples", "10", "--jobs", "1"]


@pytest.mark.parametrize(
    "argv, text",
    [
        # --delay: ASCII digits only (int() took '1_0' as 10), and the flag's name in every command
        (["check", "--device", "impulse", "--velocity", "0.05", "--delay", "1_0"], "'1_0' is not a whole number"),
        (["check", "--device", "impulse", "--velocity", "0.05", "--delay", "9" * 25], "--delay takes at most 100"),
        (["simulate", *DIMLESS, "--xi-dot", "1", "--delay=-1"], "--delay must be a whole number of samples >= 0"),
        (["simulate", *DIMLESS, "--xi-dot", "1", "--delay", "20000"], "--delay takes at most 100 samples"),
        (["limit-cycles", *DIMLESS, "--delay=-1"], "--delay must be a whole number of samples >= 0"),
        ([*MAP, "--delay=-2"], "--delay must be a whole number of samples >= 0"),
        # map / contours: --mu, --grid, the ranges, --max-amplitude named as typed
        ([*MAP[:1], "--mu=-1", *MAP[3:]], "--mu = -1.0 is invalid"),
        (["contours", "--mu", "0", "--grid", "3"], "--mu = 0.0 is invalid"),
        ([*MAP[:5], "--grid", "1"], "--grid 1 is invalid: it must be a whole number >= 2 (points per axis); give"),
        ([*MAP, "--beta-range", "1", "1"], "--beta-range 1 1 is invalid: it must be LOW HIGH with 0 <= LOW < HIGH"),
        (["contours", "--mu", "100", "--sigma-range", "-1", "1"], "--sigma-range -1 1 is invalid"),
        (["contours", "--mu", "100", "--max-amplitude", "0.5"], "--max-amplitude 0.5 is invalid: it must be >= 1"),
        # map with a device: the flag and value typed, not the speed converted to ticks
        (["map", "--device", "impulse", "--velocity=-0.05", "--grid", "2", "--samples", "10"], "--velocity -0.05 is"),
        # zwidth: its own flags, not the API's parameter names
        (["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "1"], "--grid 1 is invalid"),
        (["zwidth", "--device", "impulse", "--velocity", "0.1", "--speeds", "0"], "--speeds 0 is invalid"),
        (["zwidth", "--device", "impulse", "--velocity", "0.1", "--jobs", "0"], "--jobs = 0 is invalid"),
        (["zwidth", "--device", "impulse", "--velocity", "0.1", "--virtual-damping", "x"], "--virtual-damping takes"),
        # a ZeroDivisionError traceback before: bT/m = 4e295 in the exact linear bound
        (["stiffness", "--device", "impulse", "--velocity", "0.05", "--mass", "1e-300"], "must be at most 1e+08"),
    ],
)
def test_cli_bad_numeric_flag_is_one_line_naming_it(capsys, tmp_path, argv, text):
    if argv[0] == "map":
        argv = [*argv, "--out", str(tmp_path / "m.npz")]
    err = _refused(capsys, *argv)
    assert text in err, err
    assert not (tmp_path / "m.npz").exists()


def test_cli_map_negative_velocity_does_not_name_xi_dot(capsys, tmp_path):
    err = _refused(capsys, "map", "--device", "impulse", "--velocity=-0.05", "--out", str(tmp_path / "m.npz"))
    assert "--xi-dot" not in err and "give --velocity 0.05" in err


def test_gil_linear_bound_refuses_an_overflowing_rate_like_the_controller_path():
    # critical_stiffness and stable_stiffness apply one rule (dfa.checks.check_rate) to bT/m
    with pytest.raises(DFAValueError, match=r"^damping = 0\.02 is invalid with mass = 1e-300 .*at most 1e\+08"):
        critical_stiffness(1e-300, 0.02, 0.002)
    assert critical_stiffness(0.032, 0.02, 0.002) > 0.0


def test_cli_warnings_are_one_line_on_stderr(monkeypatch, capsys):
    """A warning of an accepted input (e.g. ``limit-cycles --max-amplitude 1e30``: the search's own, or numpy's
    overflow) is printed as one 'dfa: warning:' line while a command runs, never Python's file:line and code line."""
    import warnings

    from dfa.cli import devices

    seen = []

    def command(args):
        seen.append(warnings.formatwarning("bracket\n  not refined", UserWarning, "dfa/cycles/growth.py", 195))
        return 0

    monkeypatch.setattr(devices, "run", command)  # the parser is built per call: it takes the patched run
    before = warnings.formatwarning
    assert main(["devices"]) == 0
    assert seen == ["dfa: warning: bracket not refined (UserWarning)\n"]
    assert warnings.formatwarning is before  # restored after the command


DELTA = ["--device", "delta", "--velocity", "0.05"]


@pytest.mark.parametrize(
    "argv, typed, crossed",
    [
        # issue 41: "push = inf … cannot be negative", "lag = inf … cannot be negative", "xi0 = -inf …", "damping =
        # inf …": the dimensionless group overflowed and its check named it, with a hint that did not apply
        (["simulate", *DELTA, "--one-sided", "--push", "1e308"], "--push 1e+308 N is too large", "p = F_p/(K Δ)"),
        (["check", *DELTA, "--one-sided", "--push", "1e308"], "--push 1e+308 N is too large", "K = 14500 N/m"),
        (["stiffness", *DELTA, "--one-sided", "--push", "1e308"], "--push 1e+308 N is too large", "Δ = 3e-05 m"),
        (["check", *DELTA, "--amplifier-bandwidth", "5e-324"], "--amplifier-bandwidth 5e-324 Hz is too small", "α"),
        (["simulate", *DELTA, "--amplifier-bandwidth", "5e-324"], "--amplifier-bandwidth 5e-324 Hz", "above"),
        (["stiffness", *DELTA, "--amplifier-bandwidth", "1e308"], "--amplifier-bandwidth 1e+308 Hz is too large", "α"),
        (["zwidth", *DELTA, "--amplifier-bandwidth", "5e-324"], "--amplifier-bandwidth 5e-324 Hz", "overflows"),
        (["check", *DELTA, "--position", "-1e308"], "--position -1e+308 m is too large", "ξ = x/Δ"),
        (["check", *DELTA, "--virtual-damping", "1", "--position", "-1e308"], "--position -1e+308 m", "Δ = 3e-05 m"),
        (
            ["simulate", *DELTA, "--stiffness", "100", "--virtual-damping=1e308"],
            "--virtual-damping 1e+308 N·s/m",
            "B·T/m",
        ),
        (["check", *DELTA, "--virtual-damping=1e308"], "--virtual-damping 1e+308 N·s/m is too large", "B·T/m"),
        (["stiffness", *DELTA, "--virtual-damping=1e308"], "--virtual-damping 1e+308 N·s/m is too large", "B·T/m"),
        (["check", *DELTA, "--rotary", "--one-sided", "--push", "1e308"], "--push 1e+308 N·m is too large", "rad"),
    ],
)
def test_overflowing_value_is_named_as_typed_with_the_limit_it_crossed(capsys, argv, typed, crossed):
    err = _refused(capsys, *argv)
    assert typed in err and crossed in err, err
    assert "inf" not in err.replace("info", "") and "cannot be negative" not in err, err
    assert re.search(r"; give .* (below|above) \d", err), err  # a fix that applies: the value that works


def test_overflowing_group_names_the_physical_value_in_the_api():
    """The API words the same error with the parameter's name and states the value that works."""
    from dfa.model.elements import GroupRangeError
    from dfa.model.wall import Wall

    with pytest.raises(GroupRangeError, match=r"^damping = 1e\+308 N·s/m is too large: β_B = B/\(K T\) overflows"):
        Wall.of(100.0, damping=1e308).params(1e-3, 1e-5)
    with pytest.raises(GroupRangeError) as err:
        Wall.of(1.0, amplifier_bandwidth=5e-324).params(1e-3)
    least = err.value.limit  # the smallest bandwidth whose α = 1/(2π f T) a float holds
    assert not err.value.above and Wall.of(1.0, amplifier_bandwidth=least * 1.01).params(1e-3).lag > 1e300
