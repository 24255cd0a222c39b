"""The README's trust claims are the committed validation runs' numbers (reports/validation/*.json).

`make readme` rewrites the console examples; the prose numbers below are checked here against the
JSON written by `dfa validate` and `python -m dfa.cli.soundness_report`, so a regenerated report that changes
them fails the suite until the README says the same.
"""

import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
README = (ROOT / "README.md").read_text(encoding="utf-8")
TRUST = README[README.index("## How far to trust it") : README.index("## Speed")]
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
