"""Every default text output line of the command line is at most 100 characters (issue 26 §1: the answer fits
one screen; the full evidence is for --explain and the JSON). The golden set's text commands are checked where
they run (tests/test_golden_numbers.py); here the commands with a wall, and the wrapping itself."""

import importlib.util
import tempfile
from pathlib import Path

import pytest

from dfa.cli.output import WIDTH
from dfa.formatting import fill, text_table

_HERE = Path(__file__).resolve().parent / "golden"
_spec = importlib.util.spec_from_file_location("dfa_make_golden_width", _HERE / "make_golden.py")
assert _spec is not None and _spec.loader is not None
golden = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(golden)

WALL = ["--virtual-damping", "1", "--velocity-filter", "200", "--delay", "1"]
WITH_WALL = {
    "check_wall": ["check", "--device", "delta", "--velocity", "0.1", *WALL],
    "simulate_wall": ["simulate", "--device", "delta", "--velocity", "0.1", *WALL],
    "cycles_wall": ["limit-cycles", "--device", "delta", "--model", "zoh", *WALL],
    "require_wall": ["require", "--device", "delta", "--stiffness", "20000", "--velocity", "0.1", *WALL],
    "zwidth_custom": [
        "zwidth",
        "--mass",
        "0.1",
        "--damping",
        "0.005",
        "--coulomb",
        "0.02",
        "--resolution",
        "1e-5",
        "--period",
        "1e-3",
        "--velocity",
        "0.1",
        "--delay",
        "1",
        "--grid",
        "3",
        "--speeds",
        "1",
    ],
}


@pytest.mark.parametrize("name", sorted(WITH_WALL))
def test_cli_default_output_lines_fit_one_screen(name):
    argv = WITH_WALL[name]
    with tempfile.TemporaryDirectory() as tmp:
        code, text = golden.run(argv, tmp)
    assert code == 0
    long = [line for line in text.splitlines() if len(line) > WIDTH]
    assert not long, f"{len(long)} line(s) over {WIDTH} characters, e.g. {long[0]!r}"


def test_wrapping_keeps_every_word_and_the_columns():
    text = "region d: no passivity guarantee at this speed: above the critical speed (not a proof of instability)"
    table = text_table([["region", text], ["margin", "0.5"]], width=60)
    assert max(len(line) for line in table.splitlines()) <= 60
    assert table.split() == ["region", *text.split(), "margin", "0.5"]  # nothing lost, nothing reordered
    assert all(line.startswith(" " * 8) for line in table.splitlines()[1:-1])  # continuations under the column
    prose = "a " * 80
    assert fill(prose, 50).split() == prose.split() and max(map(len, fill(prose, 50).splitlines())) <= 50
