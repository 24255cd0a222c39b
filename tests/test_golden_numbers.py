"""The numbers every command and the design report print are unchanged (issue 13, "Done when").

Golden outputs recorded from the code before the compute/render split by ``tests/golden/make_golden.py``; this
re-runs the same commands in-process through ``dfa.cli.main`` and compares key by key (JSON, floats to rel 1e-9)
and line by line (text: every golden line's numbers, in order, on some line). New keys and lines are allowed.
"""

from __future__ import annotations

import importlib.util
import json
import tempfile
from pathlib import Path

import pytest

from dfa.cli.output import WIDTH

_HERE = Path(__file__).resolve().parent / "golden"
_spec = importlib.util.spec_from_file_location("dfa_make_golden", _HERE / "make_golden.py")
assert _spec is not None and _spec.loader is not None
golden = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(golden)

CLI = json.loads((_HERE / "cli.json").read_text(encoding="utf-8"))
REPORT = json.loads((_HERE / "report.json").read_text(encoding="utf-8"))


def test_golden_covers_every_subcommand():
    used = {e["argv"][0] for e in CLI.values()} | {REPORT["argv"][0]}
    assert used >= {"devices", "params", "check", "stiffness", "limit-cycles", "simulate", "map", "contours", "report"}
    assert set(CLI) == set(golden.COMMANDS)


@pytest.mark.parametrize("name", sorted(CLI))
def test_golden_cli_numbers_unchanged(name):
    entry = CLI[name]
    with tempfile.TemporaryDirectory() as tmp:
        code, text = golden.run(entry["argv"], tmp)
    assert code == entry["exit"]
    if "json" in entry:
        problems = golden.compare_json(entry["json"], json.loads(text))
    else:
        problems = golden.compare_text(entry["text"], text, name)
        if "--explain" not in entry["argv"]:  # the default text fits one screen (issue 26 §1; --explain is unbound)
            problems += [f"{name}: line over {WIDTH} characters: {line!r}" for line in text.splitlines()
                         if len(line) > WIDTH]  # fmt: skip
    assert not problems, "\n".join(problems)


def test_golden_report_markdown_numbers_unchanged():
    with tempfile.TemporaryDirectory() as tmp:
        code, text = golden.run(REPORT["argv"], tmp)
        files = {str(p.relative_to(tmp)): p.read_text(encoding="utf-8") for p in Path(tmp).rglob("*.md")}
    assert code == REPORT["exit"] == 0
    problems = golden.compare_text(REPORT["text"], text, "stdout")
    for rel, want in REPORT["files"].items():
        assert rel in files, f"{rel} not written; written: {sorted(files)}"
        problems += golden.compare_text(want, files[rel], rel)
    assert not problems, "\n".join(problems)


# The comparison itself must be able to fail.
def test_compare_json_catches_a_changed_float_and_a_missing_key_allows_new_keys():
    g = {"a": 1.0, "b": [1, "x"], "c": {"d": None}}
    assert golden.compare_json(g, {"a": 1.0 + 1e-12, "b": [1, "x"], "c": {"d": None}, "new": 3}) == []
    assert golden.compare_json(g, {"a": 1.0 + 1e-6, "b": [1, "x"], "c": {"d": None}})
    assert golden.compare_json(g, {"a": 1.0, "b": [1, "y"], "c": {"d": None}})
    assert golden.compare_json(g, {"a": 1.0, "b": [1, "x"], "c": {}})
    assert golden.compare_json({"n": 2}, {"n": 2.0})  # an int that became a float is a change
    assert golden.compare_json({"p": True}, {"p": 1})


def test_compare_text_catches_a_changed_number_allows_new_lines_and_numbers():
    g = "K_max  641.13 N/m\nstatic limit 2c/Δ (eq. 9)  3781 N/m\nverdict: passive\n"
    assert (
        golden.compare_text(g, "new line 7\nK_max  641.13 N/m (or 0.5 more)\nstatic limit 2c/Δ (eq. 9)  3781 N/m\n")
        == []
    )
    assert golden.compare_text(g, "K_max  641.14 N/m\nstatic limit 2c/Δ (eq. 9)  3781 N/m\n")
    assert golden.compare_text(g, "K_max  641.13 N/m\nstatic limit 2c/Δ (eq. 8)  3781 N/m\n")
    # a line wrapped at 100 characters (continuations indented) keeps its numbers; a new line is no continuation
    assert golden.compare_text(g, "K_max  641.13\n       N/m\nstatic limit 2c/Δ (eq.\n  9)  3781 N/m\n") == []
    assert golden.compare_text(g, "K_max  641.13 N/m\nstatic limit 2c/Δ (eq.\n9)  3781 N/m\n")
