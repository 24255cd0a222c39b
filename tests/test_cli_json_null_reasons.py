"""Every null in every JSON the command line prints has a reason (issue 14: `simulate --json` of a diverged run gave
``amplitude_m: null`` without one). The walk covers each subcommand in a diverged, undefined or not-requested case."""

import json

import pytest
from fixed_keywords import small_design_searches, small_report_map

from dfa.cli import main
from dfa.jsonable import explain_nulls

_CUSTOM = ["--mass", "0.05", "--damping", "0", "--coulomb", "0.02", "--resolution", "2e-5", "--period", "0.001"]

CASES = {
    "devices": ["devices", "--json"],  # incomplete catalogue rows
    "params_custom": ["params", *_CUSTOM, "--stiffness", "1000", "--json"],
    "check_no_critical_speed": ["check", "--mu", "50", "--beta", "0", "--sigma", "0.2", "--xi-dot", "3", "--json"],
    "check_device": ["check", "--device", "phantom", "--velocity", "0.5", "--json"],
    "stiffness_not_requested": ["stiffness", *_CUSTOM, "--velocity", "0.1", "--json"],
    "stiffness_speed_zero": ["stiffness", "--device", "delta", "--velocity", "0", "--json"],
    "stiffness_too_stiff": ["stiffness", "--device", "phantom", "--velocity", "0.2", "--stiffness", "3000", "--json"],
    "simulate_diverged_device": ["simulate", "--device", "phantom", "--velocity", "0.5", "--json"],
    "simulate_diverged": ["simulate", "--mu", "100", "--beta", "0", "--sigma", "0.2", "--xi-dot", "2", "--json"],
    "simulate_rest": ["simulate", "--mu", "100", "--beta", "0.3", "--sigma", "1.5", "--xi-dot", "2", "--json"],
    "simulate_undecided": ["simulate", "--device", "phantom", "--velocity", "0.05", "--samples", "50", "--json"],
    "limit_cycles_device": ["limit-cycles", "--device", "phantom", "--json"],
    "limit_cycles_none": ["limit-cycles", "--mu", "50", "--beta", "0.6", "--sigma", "0.6", "--json"],
    "map": [
        "map",
        "--mu",
        "50",
        "--grid",
        "4",
        "--xi-dot",
        "2",
        "5",
        "--samples",
        "2000",
        "--json",
        "--out",
        "{tmp}/m.npz",
    ],
    "contours": ["contours", "--mu", "50", "--grid", "4", "--json"],
    "report": ["report", "--device", "impulse", "--velocity", "0.2", "--out", "{tmp}/rep", "--json", "--format", "md"],
    "validate": ["validate", "--quick", "--json", "--out", "{tmp}/val"],
}


def unexplained_nulls(obj, path=""):
    """JSON pointers of nulls (also inside lists) with no entry in the ``null_reasons`` of a dict holding them."""
    out = []
    if isinstance(obj, dict):
        reasons = obj.get("null_reasons", {})
        for key, value in obj.items():
            if key == "null_reasons":
                continue
            ptr = "/" + key.replace("~", "~0").replace("/", "~1")
            if value is None:
                out += [] if ptr in reasons else [path + ptr]
            elif isinstance(value, list) and ptr in reasons:
                out += [
                    p for i, x in enumerate(value) if x is not None for p in unexplained_nulls(x, f"{path}{ptr}/{i}")
                ]
            else:
                out += unexplained_nulls(value, path + ptr)
    elif isinstance(obj, list):
        for i, x in enumerate(obj):
            out += [f"{path}/{i}"] if x is None else unexplained_nulls(x, f"{path}/{i}")
    return out


def test_unexplained_nulls_walker_can_fail():
    assert unexplained_nulls({"a": None, "b": [1, None], "c": {"d": None, "null_reasons": {"/d": "why"}}}) == [
        "/a",
        "/b/1",
    ]
    assert unexplained_nulls(explain_nulls({"a": None, "b": [None]}, {"a": "x", "b": "y"})) == []


@pytest.mark.parametrize("name", list(CASES))
def test_cli_json_every_null_has_a_reason(name, capsys, tmp_path, monkeypatch):
    small_report_map(monkeypatch)  # the report's nulls and reasons are its sections', whatever the searches' sizes
    small_design_searches(monkeypatch)
    argv = [a.replace("{tmp}", str(tmp_path)) for a in CASES[name]]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 0, err
    data = json.loads(out)
    assert unexplained_nulls(data) == []
    if name == "simulate_diverged_device":  # the red-team case: the physical amplitude of a diverged run
        assert data["outcome"] == "unstable" and data["amplitude_m"] is None
        assert "diverged" in data["null_reasons"]["/amplitude_m"]
    if name == "stiffness_not_requested":
        assert data["null_reasons"]["/stiffness_source"] and data["null_reasons"]["/assessment"].startswith(
            "no stiffness given"
        )
