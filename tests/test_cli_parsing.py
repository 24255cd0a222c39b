"""Every flag behaves the same however it is written (issue 27, section 2): ``--flag=--`` is a value the flag's
type refuses (Python 3.11's argparse stored an empty list without calling the type: tracebacks), ``--flag -X``
takes a negative number as the value ("expected one argument" before), and a closed stdout ends with 141."""

from __future__ import annotations

import argparse
import os
import subprocess
import sys

import pytest

from dfa.cli import main, parsing
from dfa.cli.app import build_parser
from dfa.cli.parsing import NEGATIVE_NUMBER, UsageError

DFA = [sys.executable, "-c", "import sys; from dfa.cli import main; sys.exit(main())"]


PARSER = build_parser()


def _commands() -> dict[str, argparse.ArgumentParser]:
    sub = next(a for a in PARSER._actions if isinstance(a, argparse._SubParsersAction))
    return dict(sub.choices)


def _value_flags(numeric: bool) -> list[tuple[str, str, object]]:
    """(command, flag, nargs) of every flag that takes a value (``numeric``: a number)."""
    out = []
    for cmd, p in _commands().items():
        for a in p._actions:
            if not a.option_strings or a.nargs == 0 or a.option_strings[0] in ("-h", "--help"):
                continue
            if (a.type not in (None, parsing.name)) == numeric:
                out.append((cmd, a.option_strings[0], a.nargs))
    return out


NUMERIC = _value_flags(numeric=True)
TEXT = _value_flags(numeric=False)


def test_the_flag_tables_are_not_empty():
    flags = {f for _c, f, _n in NUMERIC}
    assert {"--position", "--xi0", "--virtual-damping", "--grid", "--samples", "--mass", "--delay"} <= flags
    assert len(NUMERIC) > 100 and {"--device", "--out", "--name"} <= {f for _c, f, _n in TEXT}


@pytest.mark.parametrize("text", ["-1", "-1.5", "-.5", "-1.", "-1e-5", "-2.5e0", "-3E+2", "-.5e-3", "-inf", "-NaN"])
def test_negative_number_pattern(text):
    assert NEGATIVE_NUMBER.match(text)


@pytest.mark.parametrize("text", ["-", "--", "-e5", "-1e", "-x", "--json", "-1x", "-h", "- 1"])
def test_negative_number_pattern_leaves_flags_alone(text):
    assert not NEGATIVE_NUMBER.match(text)


def _parse(cmd: str, flag: str, nargs: object, value: str, joined: bool) -> argparse.Namespace | str:
    """Parse ``dfa cmd flag value`` (``flag=value`` if ``joined``); the error text when refused."""
    values = [value] * (nargs if isinstance(nargs, int) else 1)
    argv = [cmd, f"{flag}={value}"] if joined and len(values) == 1 else [cmd, flag, *values]
    if cmd == "map" and flag != "--out":
        argv += ["--out", "m.npz"]
    if cmd == "zwidth" and flag != "--velocity":
        argv += ["--velocity", "1"]
    if cmd == "identify":
        argv.insert(1, "log.csv")  # its positional LOG.csv
    try:
        return PARSER.parse_args(argv)
    except UsageError as err:
        return str(err)


@pytest.mark.parametrize("cmd, flag, nargs", NUMERIC, ids=[f"{c} {f}" for c, f, _n in NUMERIC])
def test_every_numeric_flag_takes_a_negative_number_after_a_space(cmd, flag, nargs):
    for text in ("-2.5e0", "-1e-5", "-3"):
        values = [text] * (nargs if isinstance(nargs, int) else 1)
        got = _parse(cmd, flag, nargs, text, joined=False)
        if isinstance(got, str):  # refused by the flag's own type (an integer flag and -2.5e0), never by argparse
            assert "expected" not in got and f"argument {flag}" in got and repr(text) in got, got
        else:
            value = getattr(got, next(a.dest for a in _commands()[cmd]._actions if flag in a.option_strings))
            assert value in (float(text), [float(text)] * len(values)), (value, text)


@pytest.mark.parametrize("cmd, flag, nargs", NUMERIC, ids=[f"{c} {f}" for c, f, _n in NUMERIC])
def test_every_numeric_flag_refuses_a_double_dash_value(cmd, flag, nargs):
    got = _parse(cmd, flag, nargs, "--", joined=True)
    assert isinstance(got, str), got
    assert f"argument {flag}: '--' is not" in got or "expected" in got, got


def test_double_dash_values_are_one_line_errors_not_tracebacks(capsys):
    """The issue's examples: a list reached the code (TypeError in the controller) or was accepted silently."""
    base = ["check", "--device", "delta", "--velocity", "0.1"]
    for extra in (["--virtual-damping=--"], ["--velocity-filter=--"], ["--amplifier-bandwidth=--"], ["--position=--"]):
        assert main(base + extra) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and f"argument {extra[0][:-3]}: '--' is not a number" in err, err
    assert main(["simulate", "--mu", "5", "--beta", "0.1", "--sigma", "0.3", "--xi-dot", "1", "--samples=--"]) == 2
    assert "argument --samples: '--' is not a whole number" in capsys.readouterr().err


def test_the_help_examples_with_negative_values_run(capsys):
    assert main(["check", "--device", "delta", "--velocity", "0.1", "--position", "-1e-5", "--json"]) == 0
    assert main(["check", "--mu", "5", "--beta", "0.1", "--sigma", "0.3", "--xi-dot", "1", "--xi0", "-2.5e0"]) == 0
    assert main(["params", "--mu", "-1e-3", "--beta", "0", "--sigma", "0"]) == 2
    assert "--mu = -0.001 is invalid" in capsys.readouterr().err


class _ClosedPipe:
    """A stdout whose reader has gone: every write (or the flush of a buffered one) raises BrokenPipeError."""

    def __init__(self, buffered: bool) -> None:
        self.buffered, self.pending = buffered, ""

    def write(self, text: str) -> int:
        if not self.buffered:
            raise BrokenPipeError(32, "Broken pipe")
        self.pending += text
        return len(text)

    def flush(self) -> None:
        if self.pending:
            raise BrokenPipeError(32, "Broken pipe")


@pytest.mark.parametrize("buffered", [False, True])
@pytest.mark.parametrize("argv", [["--help"], ["check", "--help"], ["devices"], ["--version"]])
def test_closed_stdout_exits_141_in_process(monkeypatch, capsys, argv, buffered):
    monkeypatch.setattr(sys, "stdout", _ClosedPipe(buffered))
    assert main(argv) == 141
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("unbuffered", ["1", ""])
def test_help_into_a_closed_pipe_exits_141_quietly(unbuffered):
    """`dfa --help | true`: exit 141 and nothing on stderr, whether stdout is buffered (exit 120 and "Exception
    ignored" before) or not (exit 0 before: argparse ignored the error)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"} | (
        {"PYTHONUNBUFFERED": unbuffered} if unbuffered else {}
    )
    proc = subprocess.Popen(DFA + ["--help"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    proc.stdout.close()  # the reader is gone before dfa writes
    err = proc.stderr.read()
    proc.wait(timeout=60)
    assert proc.returncode == 141 and err == b"", (proc.returncode, err)
