"""The documented trust claims (docs/trust.md, linked from the README) are the committed validation runs' numbers.

`make readme` rewrites the console examples; the prose numbers below are checked here against the
JSON written by `dfa validate` and `python -m dfa.cli.soundness_report`, so a regenerated report that changes
them fails the suite until the README says the same.
"""

import json
import math
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TRUST_PAGE = (ROOT / "docs" / "trust.md").read_text(encoding="utf-8")
TRUST = TRUST_PAGE[TRUST_PAGE.index("## How far to trust it") : TRUST_PAGE.index("## Speed")]
PYTHON_PAGE = (ROOT / "docs" / "python.md").read_text(encoding="utf-8")
VALIDATION = json.loads((ROOT / "reports/validation/validation.json").read_text(encoding="utf-8"))
SUMMARY = VALIDATION.get("summary", VALIDATION)
DELAY = json.loads((ROOT / "reports/validation/delay_soundness.json").read_text(encoding="utf-8"))


def _int(n: int) -> str:
    """Thousands with a thin space as the README writes them (1 430)."""
    return f"{n:,}".replace(",", " ")


def _flat(text: str) -> str:
    return re.sub(r"\s+", " ", text)


def test_eq6_delay_soundness_counts_in_readme_match_the_committed_run():
    aware = {r["delay"]: r for r in DELAY if r["criterion"] == "delay-aware"}
    ignoring = {r["delay"]: r for r in DELAY if r["criterion"] == "d-ignoring"}
    assert sorted(aware) == [0, 1, 2, 3]
    assert all(r["violations"] == 0 and r["points"] == 100_000 for r in aware.values())
    flat = _flat(TRUST)
    assert "0 violations on 10⁵ random passive points for each d = 0, 1, 2, 3" in flat
    counts = [_int(ignoring[d]["violations"]) for d in range(4)]
    assert f"{counts[0]} (d = 0, ξ0 ≠ 0), {counts[1]}, {counts[2]} and {counts[3]}" in flat


def _committed_sound_run(stem: str, criterion: str) -> tuple[dict, dict]:
    """(this package's record, the failing criterion's) of reports/validation/{stem}.json: 10⁵ points, no violation."""
    ours, other = json.loads((ROOT / f"reports/validation/{stem}.json").read_text(encoding="utf-8"))[:2]
    assert ours["criterion"] == criterion and ours["points"] == 100_000 and ours["violations"] == 0
    return ours, other


def test_eq6_hand_soundness_counts_in_trust_page_match_the_committed_run():
    """docs/trust.md's hand-stiffness claim is reports/validation/hand_soundness.json."""
    aware, ignoring = _committed_sound_run("hand_soundness", "controller-aware")
    flat = _flat(TRUST)
    assert "0 violations on 10⁵ random walls' passive points," in flat
    assert f"{_int(aware['by_case']['hand stiffness'])} of them held by a hand" in flat
    assert f"the damper-ignoring criterion fails on {_int(ignoring['violations'])}." in flat


def test_eq6_one_sided_soundness_counts_in_trust_page_match_the_committed_run():
    """docs/trust.md's one-sided claim is reports/validation/one_sided_soundness.json."""
    _ours, bilateral = _committed_sound_run("one_sided_soundness", "one-sided")
    flat = _flat(TRUST)
    assert "0 violations on 10⁵ random passive points after an exactly simulated approach" in flat
    assert f"the bilateral criterion's claim (½μV²) fails on {_int(bilateral['violations'])}." in flat


def test_eq6_grid_soundness_and_conservatism_in_readme_match_the_committed_run():
    flat = _flat(TRUST)
    assert SUMMARY["soundness_violations"] == 0
    assert f"({_int(SUMMARY['soundness_points'])} runs without delay)" in flat
    assert f"calls {_int(SUMMARY['soundness_passive'])} points passive and none went unstable" in flat
    assert f"rejects {100 * SUMMARY['conservatism']:.0f} % of the points that come to rest" in flat
    lo, med = SUMMARY["criterion_conservatism_min"], SUMMARY["criterion_conservatism_median"]
    assert f"is {lo:.1f} to" in flat and f"(median {med:.1f})" in flat


def test_describing_function_numbers_in_readme_match_the_committed_run():
    flat = _flat(TRUST)
    assert (
        f"within {100 * SUMMARY['speed_df_median_error']:.2f} % (median) and {100 * SUMMARY['speed_df_worst_error']:.0f} % (worst)"
        in flat
    )
    assert f"median {100 * SUMMARY['short_period_frequency_error']:.0f} %" in flat
    assert f"{100 * SUMMARY['long_period_frequency_error']:.0f} % above" in flat
    loeb = SUMMARY["loeb"]
    assert f"{loeb['stable_confirmed']} of {loeb['stable']} predicted stable" in flat
    assert f"{loeb['unstable_confirmed']} of {loeb['unstable']} predicted unstable" in flat
    cl = SUMMARY["clusters"][0]
    lo, hi = cl["band_zoh"]
    assert f"diverges at ξ'0 = {cl['first_diverging']:.2g}" in flat
    assert f"exact-ZOH band ({lo:.2f} to {hi:.2f})" in flat
    assert f"with {cl['interleaved']} non-diverging speeds above it up to {cl['last_non_diverging']:.0f}" in flat


def _public(name: str):
    """A name of `dfa`, else of the `dfa.analysis` or `dfa.studies` module that defines it (the README names both)."""
    import importlib
    import pkgutil

    import dfa
    import dfa.analysis
    import dfa.studies

    if hasattr(dfa, name):
        return getattr(dfa, name)
    for package in (dfa.analysis, dfa.studies):
        for mod in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
            module = importlib.import_module(mod.name)
            if name in getattr(module, "__all__", ()):
                return getattr(module, name)
    raise AssertionError(f"the README names {name}, which no public module defines")


def test_readme_results_table_names_each_analysis_its_result_status_and_xarray_dims():
    """Every row of the README's results table: the analysis is public, returns the class named, whose status
    field is the enum named; a to_xarray column's dims are those of the Dataset the class builds (its doctest)."""
    import dataclasses
    import inspect
    import typing

    table = PYTHON_PAGE[
        PYTHON_PAGE.index("| scheme | analysis → result") : PYTHON_PAGE.index("- `status` is an enum member")
    ]
    rows = [r for r in table.splitlines()[2:] if r.startswith("|")]
    assert len(rows) >= 18
    for row in rows:
        cells = [c.strip() for c in row.strip("|").split("|")]
        names = re.findall(r"`(\w+)`", cells[1])
        *analyses, result = names
        hints = [typing.get_type_hints(_public(name))["return"] for name in analyses]
        assert hints and all(h.__name__ == result for h in hints), (analyses, hints, result)
        cls = hints[0]
        types = [str(f.type) for f in dataclasses.fields(cls)]
        if isinstance(getattr(cls, "status", None), property):  # a status computed from the fields
            types.append(str(typing.get_type_hints(cls.status.fget)["return"]))
        for status in re.findall(r"`(\w+)`", cells[2]):
            assert any(status in t for t in types), (result, status)
        if cells[4]:
            doc = inspect.getdoc(cls.to_xarray)
            for dim in re.findall(r"`([\w, ]+)`", cells[4]):
                assert all(d.strip() in doc for d in dim.split(",")), (result, dim)
        else:
            assert not hasattr(cls, "to_xarray"), f"{result}.to_xarray is missing from the README's table"


def test_one_sided_comparison_numbers_in_trust_page_match_the_committed_run():
    """docs/trust.md's bilateral-versus-one-sided numbers are reports/validation/one_sided_comparison.json's."""
    d = json.loads((ROOT / "reports" / "validation" / "one_sided_comparison.json").read_text(encoding="utf-8"))
    free, crit, pushed_found = [], [], []
    for lim in d["limits"]:
        b = lim["bilateral"]["k_sim"]["value"]
        f = lim["one_sided"]["k_sim"]
        assert f["status"] == "above_range"  # "no free impact diverged up to the top of the searched range"
        free.append(f["range_end"] / b)
        crit.append(lim["one_sided"]["k_criterion"]["value"] / lim["bilateral"]["k_criterion"]["value"])
        if lim["pushed"]["k_sim"]["value"] is not None:
            pushed_found.append(lim["pushed"]["k_sim"]["value"] / b)
    flat = _flat(TRUST)
    n = len(d["devices"])
    assert f"on the {n} complete catalogue devices" in flat
    assert f"{min(free):.1f} to {max(free):.1f} times the bilateral spring's no-divergence limit" in flat
    assert f"the criterion's K is {min(crit):.2f} to {max(crit):.2f} times the bilateral one" in flat
    assert len(pushed_found) == 1 and f"never diverged in the range on {n - 1} of them" in flat
    assert f"diverged at {pushed_found[0]:.2f} times the bilateral limit" in flat


def test_eq6_moving_history_soundness_counts_in_trust_page_match_the_committed_run():
    """docs/trust.md's moving-history claim is reports/validation/history_soundness.json."""
    ours, fresh = _committed_sound_run("history_soundness", "moving")
    flat = _flat(TRUST)
    assert ours["violations"] == 0 and ours["points"] == 100_000
    assert "finds 0 violations on 10⁵ random passive points of it," in flat
    assert f"where the fresh start's claim fails on {_int(fresh['violations'])}." in flat


def test_passivity_controller_numbers_in_trust_page_and_cli_page_match_the_committed_run():
    """docs/trust.md's passivity-controller numbers, and docs/cli.md's summary of them, are
    reports/validation/passivity_controller.json's."""
    d = json.loads((ROOT / "reports" / "validation" / "passivity_controller.json").read_text(encoding="utf-8"))
    names = d["devices"]

    def value(name: str, case: str, limit: str) -> float | None:
        return d["limits"][names.index(name)][case][limit]["value"]

    gain = {n: (value(n, "limited", "k_sim") or math.nan) / value(n, "plain", "k_sim") for n in names}
    flat = _flat(TRUST)
    assert f"On the {len(names)} complete catalogue devices at the design report's speed, the controller" in flat
    light = sorted((gain["Phantom 1.0"], gain["Toolhandle"]))
    assert f"limit {light[0]:.1f} to {light[1]:.1f} times on the Phantom 1.0 and the Toolhandle" in flat
    assert f"and {gain['Delta']:.2f} times on the Delta" in flat
    assert d["limits"][names.index("Impulse Engine")]["limited"]["k_sim"]["status"] == "above_range"
    assert gain["RE35 testbed"] < 1 and f"lowered it to {gain['RE35 testbed']:.2f} times on the RE35" in flat
    lowered = sum(1 for n in names if (value(n, "limited", "k_sim_rest") or math.inf) < value(n, "plain", "k_sim_rest"))
    assert f"it lowered the rest limit on {lowered} of them" in flat
    never = [n for n in names if value(n, "unlimited", "k_sim") is None]
    unlimited = {n: value(n, "unlimited", "k_sim") / value(n, "plain", "k_sim") for n in names if n not in never}
    worse = [n for n, g in unlimited.items() if g < 1]
    better = [n for n, g in unlimited.items() if g > 1]
    assert (
        f"did worse than the plain wall on {len(worse)} devices, no stiffness was confirmed with it on {len(never)}"
        in flat
    )
    assert better == ["Phantom 1.0"] and f"Phantom 1.0 did it do better ({unlimited['Phantom 1.0']:.2f} times)" in flat
    assert unlimited["Phantom 1.0"] < gain["Phantom 1.0"]
    fc = d["failure"]
    assert fc["outcomes"]["plain"] == "unstable" and fc["outcomes"]["0.3"] == "unstable"
    assert fc["outcomes"]["1"] != "unstable"
    cli = _flat((ROOT / "docs" / "cli.md").read_text(encoding="utf-8"))
    assert "severalfold on the lightly damped Phantom 1.0 and Toolhandle" in cli and min(light) > 3
    assert "the textbook controller without a force limit does" in cli and "worse than none on most devices" in cli
    assert len(worse) > len(names) / 2
