"""Plausibility warnings (issue 27, section 1): a value no haptic device has (resolution above 1 mm or below 1 nm,
sample period above 0.1 s, impact speed above 10 m/s, stiffness above 1e7 N/m, mass above 100 kg) is computed as
given but warned about once, naming the value and the likely slip: one line on stderr on the command line, an
:class:`~dfa.errors.ImplausibleInputWarning` in the API. One rule (:mod:`dfa.plausibility`) serves both; the values
dfa derives itself (searches over K, grids of speeds) never warn."""

from __future__ import annotations

import warnings

import pytest

import dfa
from dfa.cli import main
from dfa.errors import ImplausibleInputWarning
from dfa.model.catalogue import catalogue, device_template, get_device
from dfa.plausibility import RANGES, implausible

DELTA = ["--device", "delta"]
TAIL = "(ImplausibleInputWarning)"


# ------------------------------------------------------------------ the rule
@pytest.mark.parametrize(
    "quantity, value, text",
    [
        (
            "resolution",
            10.0,
            "--resolution 10 is above 0.001 m, which no haptic device has: did you mean 10 µm = 1e-5 m?",
        ),
        ("resolution", 1e-11, "--resolution 1e-11 is below 1e-9 m, which no haptic device has: did you mean 1e-5 m?"),
        ("period", 1.0, "--period 1 is above 0.1 s, which no haptic device has: did you mean 1 ms = 0.001 s?"),
        (
            "velocity",
            100.0,
            "--velocity 100 is above 10 m/s, which no haptic device has: did you mean 100 mm/s = 0.1 m/s?",
        ),
        ("stiffness", 2e7, "--stiffness 2e7 is above 1e7 N/m, which no haptic device has: did you mean 2e4 N/m?"),
        ("mass", 250.0, "--mass 250 is above 100 kg, which no haptic device has: did you mean 250 g = 0.25 kg?"),
        ("mass", 1e6, "--mass 1e6 is above 100 kg, which no haptic device has: check its unit (dfa takes kg)"),
    ],
)
def test_message_names_the_value_and_the_slip(quantity, value, text):
    assert implausible(quantity, value, subject=f"--{quantity}") == text


@pytest.mark.parametrize(
    "quantity, inside, outside",
    [
        ("resolution", [1e-9, 1e-3, 30e-6], [1.1e-3, 0.9e-9]),
        ("period", [0.1, 1e-4], [0.11]),
        ("velocity", [10.0, -10.0, 0.0], [10.5, -11.0]),  # a speed's sign is not its size
        ("stiffness", [1e7, 1.0], [1.1e7]),
        ("mass", [100.0, 1e-6], [101.0]),
    ],
)
def test_the_bounds_of_the_issue(quantity, inside, outside):
    assert all(implausible(quantity, v) is None for v in inside)
    assert all(implausible(quantity, v) is not None for v in outside)


def test_rotary_ranges_and_slips():
    assert implausible("resolution", 2 * 3.14159 / 2000, rotary=True) is None  # 2000 counts per revolution
    assert "did you mean 500 °/s = 8.727 rad/s?" in implausible("velocity", 500.0, rotary=True)
    assert "did you mean 63 g·cm² = 6.3e-6 kg·m²?" in implausible("mass", 63.0, rotary=True)
    assert {q for q, _r in RANGES} == {"resolution", "period", "velocity", "stiffness", "mass", "force"}
    assert "did you mean 2000 N·mm = 2 N·m?" in implausible("force", 2000.0, rotary=True)  # a push


def test_non_numbers_and_non_finite_are_left_to_their_checks():
    assert implausible("mass", "x") is None and implausible("mass", float("nan")) is None  # type: ignore[arg-type]


def test_every_catalogue_value_is_plausible():
    for e in catalogue():
        for q in ("mass", "resolution", "period", "stiffness"):
            if getattr(e, q) is not None:
                assert implausible(q, getattr(e, q), rotary=e.rotary) is None, (e.name, q)


# ------------------------------------------------------------------ the API
def _caught(call):
    with warnings.catch_warnings(record=True) as got:
        warnings.simplefilter("always")
        call()
    return [str(w.message) for w in got if issubclass(w.category, ImplausibleInputWarning)]


DEV = get_device("delta").device


def test_device_warns_pointing_at_the_callers_line():
    with pytest.warns(
        ImplausibleInputWarning, match=r"^resolution = 10 m is above .*did you mean 10 µm = 1e-5 m\?$"
    ) as rec:
        dfa.Device(mass=0.25, damping=0.01, coulomb=0.9, resolution=10.0, period=1e-3)
    assert rec[0].filename == __file__
    got = _caught(lambda: dfa.Device(mass=250, damping=0.0, coulomb=0.0, resolution=1e-5, period=1.0))
    assert [m.split(" is ")[0] for m in got] == ["mass = 250 kg", "period = 1 s"]


@pytest.mark.parametrize(
    "call, start",
    [
        (lambda: DEV.params(2e7), "stiffness = 2e7 N/m"),
        (lambda: DEV.xi_dot(-100.0), "velocity = 100 m/s"),
        (lambda: dfa.Wall.of(3e7), "stiffness = 3e7 N/m"),
        (lambda: dfa.Wall(3e7), "stiffness = 3e7 N/m"),
        (lambda: dfa.k_max_criterion(DEV, [0.1, 20.0]), "velocity = 20 m/s"),
        (lambda: dfa.max_passive_velocity(DEV, 2e7), "stiffness = 2e7 N/m"),
        (lambda: dfa.stiffness_limits(DEV, 20.0, 1000.0), "velocity = 20 m/s"),
        (lambda: dfa.passivity_check(DEV, dfa.Wall.of(1000.0), 50.0), "velocity = 50 m/s"),
        (lambda: dfa.resolve_device("delta", overrides={"period": 1.0}), "period = 1 s"),
    ],
)
def test_api_warns_for_the_users_values(call, start):
    got = _caught(call)
    assert len(got) >= 1 and all(m.startswith(start) for m in got), got


def test_api_stays_quiet_for_plausible_values_and_its_own_derived_ones():
    assert _caught(lambda: dfa.stiffness_limits(DEV, 0.1, 1000.0)) == []
    # a device whose static limit 2c/Δ = 2e7 N/m lies above 1e7: the searches evaluate K up there, silently
    dev = dfa.Device(mass=0.1, damping=0.01, coulomb=1.0, resolution=1e-7, period=1e-3)
    assert _caught(lambda: dfa.stiffness_response(dev, [0.01, 0.1])) == []
    assert _caught(lambda: dfa.max_passive_velocity(dev, 1e6)) == []


def test_the_rule_of_who_warns():
    """A value from outside dfa warns; through one public function of dfa too; deeper, it is dfa's own."""
    assert len(_caught(lambda: DEV.params(5e7))) == 1
    direct = {"__name__": "dfa.analysis.fake2", "DEV": DEV}
    exec(
        "def public():\n    return DEV.params(5e7)\n"
        "def _private():\n    return DEV.params(5e7)\n"
        "def public_via_private():\n    return _private()\n"
        "def public_via_public():\n    return public()\n",
        direct,
    )
    assert len(_caught(direct["public"])) == 1
    assert _caught(direct["public_via_private"]) == [] and _caught(direct["public_via_public"]) == []


# ------------------------------------------------------------------ the command line
def _run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize(
    "argv, line",
    [
        (
            ["--resolution", "10"],
            "dfa: warning: --resolution 10 is above 0.001 m, which no haptic device has: did you mean 10 µm = 1e-5 m?",
        ),
        (
            ["--period", "1"],
            "dfa: warning: --period 1 is above 0.1 s, which no haptic device has: did you mean 1 ms = 0.001 s?",
        ),
        (
            ["--mass", "250"],
            "dfa: warning: --mass 250 is above 100 kg, which no haptic device has: did you mean 250 g = 0.25 kg?",
        ),
        (["--stiffness", "2e7"], "dfa: warning: --stiffness 2e7 is above 1e7 N/m"),
        (
            ["--counts", "10"],
            "dfa: warning: --counts 10: resolution = 0.1 m is above 0.001 m, which no haptic device has: --counts is per metre",
        ),
    ],
)
def test_cli_one_warning_line_naming_the_flag(capsys, argv, line):
    code, out, err = _run(capsys, "params", *DELTA, *argv)
    assert code == 0 and out  # computed as given
    assert err.count("\n") == 1 and err.startswith(line) and err.rstrip().endswith(TAIL), err


def test_cli_impact_speed_warns_in_every_command_that_takes_one(capsys, tmp_path):
    for argv in (
        ["check", *DELTA, "--velocity", "100"],
        ["simulate", *DELTA, "--velocity=-100", "--samples", "100"],
        ["stiffness", *DELTA, "--velocity", "100", "--stiffness", "1000", "--margin", "2"],
        [
            "map",
            *DELTA,
            "--velocity",
            "100",
            "--grid",
            "2",
            "--samples",
            "10",
            "--jobs",
            "1",
            "--quiet",
            "--out",
            str(tmp_path / "m.npz"),
        ],
        ["zwidth", *DELTA, "--velocity", "100", "--grid", "2", "--speeds", "1", "--jobs", "1", "--quiet"],
    ):
        code, _out, err = _run(capsys, *argv)
        warned = [line for line in err.splitlines() if "ImplausibleInputWarning" in line]
        assert (
            code == 0 and len(warned) == 1 and warned[0].startswith("dfa: warning: --velocity 100 is above 10 m/s")
        ), (argv, err)


def test_cli_warns_again_on_every_run_and_not_for_the_catalogue(capsys):
    for _ in range(2):
        assert _run(capsys, "params", *DELTA, "--period", "1")[2].count("--period 1 is above") == 1
    assert _run(capsys, "params", "--device", "re35", "--stiffness", "0.5")[2] == ""


def test_cli_device_file_values_are_named_by_file_and_key(capsys, tmp_path):
    text = device_template().replace("resolution = 3e-05", "resolution = 10.0")
    path = tmp_path / "my.toml"
    path.write_text(text, encoding="utf-8")
    code, _out, err = _run(capsys, "params", "--device-file", str(path))
    assert code == 0 and err.startswith(f"dfa: warning: {str(path)}: resolution = 10 m is above 0.001 m"), err
    assert _run(capsys, "params", "--device-file", str(path), "--resolution", "2e-5")[2] == ""  # replaced: no warning


def test_cli_a_refused_run_prints_its_error_line_alone(capsys):
    """The warnings are held until the inputs are accepted: exit 2 is one line on stderr, as ever."""
    code, _out, err = _run(capsys, "params", *DELTA, "--period", "1e300")
    assert code == 2 and err.count("\n") == 1 and err.startswith("dfa params: error:") and "--period" in err, err
    code, _out, err = _run(capsys, "check", *DELTA, "--period", "1", "--velocity", "-1")
    assert code == 2 and err.count("\n") == 1 and "--velocity" in err, err
    code, out, err = _run(capsys, "check", *DELTA, "--period", "1", "--velocity", "0.1")  # accepted: warned
    assert code == 0 and err.startswith("dfa: warning: --period 1 is above 0.1 s") and out
