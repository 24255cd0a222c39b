"""Devices from a file (issue 27, section 1): ``--device-file my_device.toml`` in the catalogue's own format for
every command that takes a device, ``dfa devices --template`` that loads back unchanged, and one clear error
(:class:`~dfa.errors.DeviceFileError`; on the command line one line, exit 2) for every way a file can be wrong."""

from __future__ import annotations

import argparse
import json
import os
import re

import pytest
from result_json import written

import dfa
from dfa.cli import main
from dfa.cli.app import build_parser
from dfa.errors import DeviceFileError, DFAValueError
from dfa.model.catalogue import (
    DEFAULT_DEVICE,
    DEVICE_FILE_MAX_BYTES,
    catalogue,
    device_template,
    get_device,
    load_device_file,
    resolve_device,
)

COMPLETE = [e for e in catalogue() if not e.missing]


def _run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def _refused(capsys, *argv: str) -> str:
    code, out, err = _run(capsys, *argv)
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and err.startswith("dfa") and "Traceback" not in err, err
    return err


def _write(tmp_path, text: str, name: str = "dev.toml") -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


# ------------------------------------------------------------------ the template and the round trip
@pytest.mark.parametrize("entry", COMPLETE, ids=[e.name for e in COMPLETE])
def test_template_of_every_complete_row_loads_back_unchanged(tmp_path, entry):
    path = _write(tmp_path, device_template(entry))
    assert load_device_file(path) == entry  # every field: values to the last bit, text, printed, notes


def test_template_is_commented_and_short(tmp_path):
    text = device_template()
    assert text.startswith("# ") and "[[devices]]" in text and "--device-file" in text
    assert all(len(line) <= 110 for line in text.splitlines())
    for key in ("name", "mass", "damping", "coulomb", "resolution", "period", "stiffness"):
        i = next(i for i, line in enumerate(text.splitlines()) if line.startswith(f"{key} = "))
        assert text.splitlines()[i - 1].startswith("# "), key  # each key under its comment


def test_cli_template_round_trip(capsys, tmp_path):
    """`dfa devices --template > f.toml` and `--device-file f.toml` give the template device's own numbers."""
    code, out, err = _run(capsys, "devices", "--template")
    assert code == 0 and err == "" and out == device_template()
    path = _write(tmp_path, out)
    for cmd in (["params", "--json"], ["check", "--velocity", "0.1", "--json"]):
        from_file = _run(capsys, cmd[0], "--device-file", path, *cmd[1:])
        from_name = _run(capsys, cmd[0], "--device", DEFAULT_DEVICE, *cmd[1:])
        assert from_file[0] == 0 and from_file[2] == "", from_file
        assert json.loads(from_file[1]) == json.loads(from_name[1])


def test_template_leaves_the_examples_source_printed_and_notes_commented_out(capsys, tmp_path):
    """`dfa devices --template`: the Delta's source, printed (μ, β, σ) and notes are placeholders, commented out,
    so a device made from it by changing the physical values does not carry them; uncommented, they load."""
    code, text, _ = _run(capsys, "devices", "--template")
    assert code == 0
    lines = text.splitlines()
    for key in ("source", "printed", "notes"):
        assert not any(line.startswith(f"{key} = ") for line in lines), key
        assert any(line.startswith(f"# {key} = ") for line in lines), key  # the placeholder is there to edit
    mine = load_device_file(_write(tmp_path, text.replace("mass = 0.25", "mass = 0.12")))
    assert mine.printed == () and mine.notes == "" and "Diolaiti" not in mine.source
    uncommented = "\n".join(line.removeprefix("# ") if line.startswith(("# source =", "# printed =", "# notes =")) else line
                            for line in lines)  # fmt: skip
    full = load_device_file(_write(tmp_path, uncommented, "full.toml"))
    assert full.printed == get_device(DEFAULT_DEVICE).printed and full.source == get_device(DEFAULT_DEVICE).source


def test_template_refuses_an_incomplete_row():
    with pytest.raises(DFAValueError, match="incomplete"):
        device_template(get_device("Omega"))


# ------------------------------------------------------------------ every command that takes a device
def _commands() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def test_every_command_with_device_takes_device_file():
    with_device = [  # dfa devices takes --device and --device-file to write that row as a template, nothing else
        c for c, p in _commands().items() if any("--device" in a.option_strings for a in p._actions) and c != "devices"
    ]
    assert len(with_device) >= 9
    for cmd in with_device:
        p = _commands()[cmd]
        assert any("--device-file" in a.option_strings for a in p._actions), cmd
        assert "replace its values" in " ".join(p.format_help().split()), cmd  # the rule is in --help


@pytest.mark.parametrize(
    "argv",
    [
        ["params"],
        ["check", "--velocity", "0.05"],
        ["simulate", "--velocity", "0.05", "--samples", "100"],
        ["limit-cycles", "--max-amplitude", "5"],
        ["map", "--velocity", "0.05", "--grid", "2", "--samples", "10", "--jobs", "1", "--quiet", "--out", "{m}"],
        ["contours", "--grid", "2", "--max-amplitude", "2"],
    ],
    ids=lambda a: a[0],
)
def test_commands_run_with_a_device_file(capsys, tmp_path, argv):
    path = _write(tmp_path, device_template(get_device("impulse")))
    argv = [a.replace("{m}", str(tmp_path / "m.npz")) for a in argv]
    code, out, err = _run(capsys, argv[0], "--device-file", path, *argv[1:])
    assert code == 0 and err == "", err
    _run(capsys, argv[0], "--device", "impulse", *argv[1:])


# ------------------------------------------------------------------ the rule with --device and the flags
def test_flags_replace_the_files_values(capsys, tmp_path):
    path = _write(tmp_path, device_template(get_device("impulse")))
    got = json.loads(
        _run(capsys, "params", "--device-file", path, "--coulomb", "0.05", "--stiffness", "100", "--json")[1]
    )
    want = dfa.resolve_device("impulse", overrides={"coulomb": 0.05}, stiffness=100.0)
    assert got == written(want.device.params(want.stiffness).to_dict())
    code, out, _ = _run(capsys, "params", "--device-file", path, "--name", "my pen")
    assert code == 0 and out.startswith("my pen, K = 80 N/m")


def test_device_and_device_file_together_are_refused(capsys, tmp_path):
    path = _write(tmp_path, device_template())
    err = _refused(capsys, "params", "--device", "delta", "--device-file", path)
    assert "--device 'delta' and --device-file" in err and "cannot both be given" in err
    assert "cannot be combined with --device-file" in _refused(
        capsys, "params", "--device-file", path, "--mu", "5", "--beta", "0.1", "--sigma", "0.3"
    )


def test_a_file_without_stiffness_names_the_file(capsys, tmp_path):
    text = "\n".join(line for line in device_template().splitlines() if not line.startswith("stiffness"))
    path = _write(tmp_path, text)
    err = _refused(capsys, "params", "--device-file", path)
    assert f"device file {path!r} gives no stiffness" in err
    assert _run(capsys, "params", "--device-file", path, "--stiffness", "1000")[0] == 0
    assert load_device_file(path).stiffness is None


def test_report_takes_the_file_not_the_default_device(capsys, tmp_path):
    path = _write(tmp_path, device_template(get_device("impulse")))
    err = _refused(capsys, "report", "--device-file", path, "--format", "pdf")  # refused before any work
    assert "invalid choice" in err
    args = build_parser().parse_args(["report", "--device-file", path])
    assert args.device is None and args.device_file == path


def test_resolve_device_takes_an_entry(tmp_path):
    entry = load_device_file(_write(tmp_path, device_template(get_device("phantom"))))
    r = resolve_device(entry=entry, overrides={"coulomb": 0.05})
    assert r.device.coulomb == 0.05 and r.stiffness == 1015.0 and r.entry is None
    assert resolve_device(entry=entry).entry == entry
    with pytest.raises(DFAValueError, match="cannot both be given"):
        resolve_device("delta", entry=entry)


# ------------------------------------------------------------------ every way a file can be wrong
GOOD = device_template(get_device(DEFAULT_DEVICE))  # every key written (the template comments some out)


def _without(key: str) -> str:
    return "\n".join(line for line in GOOD.splitlines() if not line.startswith(f"{key} = "))


def _with(key: str, value: str) -> str:
    return "\n".join(f"{key} = {value}" if line.startswith(f"{key} = ") else line for line in GOOD.splitlines())


BAD_FILES = {
    "not TOML": ("mass = = 1", "is not valid TOML ("),
    "not UTF-8": (b"\xff\xfe name", "is not UTF-8 text"),
    "empty": ("", "has no [[devices]] table"),
    "keys at the top": ('name = "x"\nmass = 1.0\n', "has its keys at the top: put them under a [[devices]] line"),
    "unknown top key": (GOOD + "\n[other]\na = 1\n", "has unknown key 'other' at the top"),
    "two devices": (GOOD + "\n[[devices]]\n" + GOOD.split("\n[[devices]]\n")[1], "holds 2 [[devices]]"),
    "unknown key": (GOOD + "mas = 1.0\n", "has unknown key 'mas' in [[devices]]: did you mean 'mass'?"),
    "missing keys": (_without("period"), "lacks period: a device file gives name, mass"),
    "text number": (_with("mass", '"0.25"'), "has mass = '0.25': it must be a number in SI units, without quotes"),
    "bool number": (_with("damping", "true"), "has damping = True: it must be a number"),
    "negative": (_with("coulomb", "-0.1"), ": coulomb = -0.1 is invalid: it must be a finite number >= 0"),
    "zero period": (_with("period", "0.0"), ": period = 0.0 is invalid: it must be a finite number > 0"),
    "nan": (_with("resolution", "nan"), ": resolution = nan is invalid"),
    "inf": (_with("stiffness", "inf"), ": stiffness = inf is invalid"),
    "empty name": (_with("name", '"  "'), "has name = '  ': it must be printable text of 1 to 100 characters"),
    "name type": (_with("name", "3"), "has name = 3: it must be text in quotes"),
    "kind": (_with("kind", '"robot"'), "has kind = 'robot': it must be one of 'haptic device'"),
    "rotary": (_with("rotary", '"no"'), "has rotary = 'no': it must be true or false"),
    "incomplete": (GOOD + "incomplete = true\n", "has incomplete = true: a device file gives every physical value"),
    "printed key": (
        _with("printed", '{ sgima = "1" }'),
        "has unknown key 'sgima' in printed: did you mean 'sigma'?",
    ),
    "printed value": (_with("printed", '{ mu = "x" }'), "has printed mu = 'x': it must be a finite decimal number"),
    "nested brackets": ("a = " + "[" * 5000 + "]" * 5000 + "\n", "nests brackets or braces too deeply"),  # fuzz
    "nested braces": ("a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n", "nests brackets or braces too deeply"),
}


@pytest.mark.parametrize("case", list(BAD_FILES))
def test_bad_files_are_one_clear_error(capsys, tmp_path, case):
    content, needle = BAD_FILES[case]
    path = tmp_path / "dev.toml"
    path.write_bytes(content if isinstance(content, bytes) else content.encode("utf-8"))
    with pytest.raises(DeviceFileError) as info:
        load_device_file(path)
    assert str(info.value).startswith(f"device file {str(path)!r}") and needle in str(info.value), str(info.value)
    err = _refused(capsys, "params", "--device-file", str(path))
    assert needle in err


def test_a_file_with_a_byte_order_mark_is_read(capsys, tmp_path):
    """A UTF-8 byte-order mark (Windows editors write one) is dropped, as read_log drops a CSV's (issue 41)."""
    path = tmp_path / "bom.toml"
    path.write_bytes(b"\xef\xbb\xbf" + GOOD.encode("utf-8"))
    assert load_device_file(path) == load_device_file(_write(tmp_path, GOOD, "plain.toml"))
    code, out, err = _run(capsys, "params", "--device-file", str(path))
    assert code == 0 and not err, err


def test_missing_unreadable_and_huge_files(capsys, tmp_path):
    missing = str(tmp_path / "nope.toml")
    assert "cannot be read (No such file or directory)" in _refused(capsys, "params", "--device-file", missing)
    assert "is not a regular file" in _refused(capsys, "params", "--device-file", str(tmp_path))
    if os.path.exists("/dev/zero"):
        assert "is not a regular file" in _refused(capsys, "check", "--device-file", "/dev/zero", "--velocity", "1")
    big = tmp_path / "big.toml"
    with open(big, "wb") as fh:
        fh.truncate(DEVICE_FILE_MAX_BYTES + 1)
    assert "is too large" in _refused(capsys, "params", "--device-file", str(big))
    assert "'--' cannot be read" in _refused(capsys, "params", "--device-file=--")


def test_load_device_file_refuses_a_non_path():
    with pytest.raises(dfa.DFATypeError, match="it must be a file path"):
        load_device_file(3)  # type: ignore[arg-type]


def test_the_package_exports_the_device_file_api():
    assert dfa.load_device_file is load_device_file and dfa.device_template is device_template
    assert issubclass(dfa.DeviceFileError, dfa.DFAValueError)


# ----------------------------------------------------------------- the device's fields as one table (issue 42)
def test_device_fields_table_is_what_device_catalogue_files_flags_and_template_read():
    """Each row of DEVICE_FIELDS is a Device attribute (in order), a catalogue column, a device-file key, a flag
    and a template comment: a field added to the table and not to one of them fails here."""
    import dataclasses

    from dfa.cli.inputs import PHYS_FLAGS
    from dfa.model.catalogue import _FILE_KEYS, _TEMPLATE_COMMENTS, CatalogueEntry
    from dfa.model.device import DEVICE_FIELDS, STIFFNESS, Device, device_units

    names = [f.name for f in DEVICE_FIELDS]
    device_values = [f.name for f in dataclasses.fields(Device) if f.init and f.name not in ("name", "rotary")]
    assert names == device_values
    entry_fields = {f.name for f in dataclasses.fields(CatalogueEntry)}
    for f in (*DEVICE_FIELDS, STIFFNESS):
        assert f.name in entry_fields and f.name in _FILE_KEYS
        assert _TEMPLATE_COMMENTS[f.name] == f.comment
        assert device_units()[f.name] == f.unit and device_units(rotary=True)[f.name] == f.rotary_unit
    assert PHYS_FLAGS == {f.name: (f.flag, f.units) for f in DEVICE_FIELDS}
    assert PHYS_FLAGS["mass"] == ("--mass", "kg (rotary: inertia in kg·m²)")
    row = get_device(DEFAULT_DEVICE).to_dict()
    assert [k for k in row if k in names] == names  # the JSON's columns in the table's order


def test_device_fields_table_rules_are_devices_rules():
    """The table's rule is Device's: > 0 for mass, resolution, period and the optional force limit and travel; >= 0 for the frictions."""
    from dfa.model.device import DEVICE_FIELDS

    rules = {f.name: f.rule.value for f in DEVICE_FIELDS}
    assert rules == {
        "mass": "> 0", "damping": ">= 0", "coulomb": ">= 0", "resolution": "> 0", "period": "> 0", "max_force": "> 0", "travel": "> 0"
    }  # fmt: skip
    good = {f.name: 1e-3 for f in DEVICE_FIELDS}
    for f in DEVICE_FIELDS:
        for bad in (-1.0, 0.0):
            if bad == 0.0 and f.rule.value == ">= 0":
                assert getattr(dfa.Device(**(good | {f.name: bad})), f.name) == 0.0
                continue
            message = f"{f.name} = {bad} is invalid: it must be a finite number {f.rule.value}; {f.fix}"
            with pytest.raises(DFAValueError, match="^" + re.escape(message) + "$"):
                dfa.Device(**(good | {f.name: bad}))


def test_device_field_row_for_an_optional_value_without_default():
    """An optional row (absent: None, e.g. a force limit) derives its flag, units, template comment and fix."""
    from dfa.model.device import DeviceField, Rule

    row = DeviceField(
        "max_force", "force limit", "F_max", "N", "N·m", Rule.POSITIVE, required=False, absent="unlimited"
    )
    assert row.flag == "--max-force"
    assert row.units == "N (rotary: N·m)"
    assert row.comment == "force limit F_max in N (rotary: N·m), > 0; optional, absent: unlimited"
    assert row.fix == "give the force limit F_max in N (rotary: N·m)"
    assert row.check(2) == 2.0
    with pytest.raises(
        DFAValueError, match="^max_force = 0.0 is invalid: it must be a finite number > 0; give the force"
    ):
        row.check(0.0)


def test_cli_device_given_a_device_file_points_to_device_file(capsys, tmp_path):
    """`--device examples/x.toml` (a file where a catalogue name goes) says to give --device-file, which reads it."""
    from pathlib import Path

    from dfa.cli import main

    path = Path(__file__).parents[1] / "examples" / "arm_configurations.toml"
    assert main(["params", "--device", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("dfa params: error: --device ")
    assert f"give --device-file {path}" in err
    assert main(["params", "--device-file", str(path)]) == 0
    assert "limiting configuration" in capsys.readouterr().out
