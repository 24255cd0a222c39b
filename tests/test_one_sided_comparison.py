"""The bilateral spring against the one-sided wall on the catalogue devices (issue 28 §1, the validation report).

``reports/validation/one_sided_comparison.md`` comes from ``python -m dfa.cli.contact_report``: its rows are
:func:`dfa.analysis.limits.kmax.design_answer`'s limits for the three walls (two answers to one question must
agree), its Markdown is the rendering of its JSON, and Delta's row is what the code computes now.
"""

from __future__ import annotations

import json
from pathlib import Path

from result_json import written

import dfa
from dfa.analysis.limits.kmax import design_answer
from dfa.cli.contact_report import STEM, main
from dfa.model.elements import OneSided, Push
from dfa.model.wall import Wall
from dfa.studies.contact_comparison import CASES, LIMITS, PUSH_FRICTIONS, ContactComparison, contact_comparison
from dfa.studies.contact_document import comparison_markdown

REPORT = Path(__file__).resolve().parent.parent / "reports" / "validation"


def _committed() -> ContactComparison:
    d = json.loads((REPORT / f"{STEM}.json").read_text(encoding="utf-8"))
    fields = ("devices", "velocities", "pushes", "device_units", "limits", "counterexamples", "grid", "speeds")
    return ContactComparison(*(tuple(d[f]) if isinstance(d[f], list) else d[f] for f in fields), d["status"])


def test_one_sided_comparison_rows_are_the_design_answers():
    """Each row is design_answer's limits for the bilateral spring, the free one-sided wall and the pushed one
    (push 2c), with the same grid and speeds."""
    entry = dfa.get_device("Impulse Engine")
    c = contact_comparison([entry], grid=6, speeds=1)
    dev = entry.device
    walls = {
        "bilateral": Wall(1.0),
        "one_sided": Wall(1.0, (OneSided(0.0),)),
        "pushed": Wall(1.0, (OneSided(0.0), Push(PUSH_FRICTIONS * dev.coulomb))),
    }
    assert c.pushes == (PUSH_FRICTIONS * dev.coulomb,) and c.velocities == (0.1,)
    for case in CASES:
        r = design_answer(dev, 0.1, wall=walls[case], grid=6, speeds=1)
        for limit in LIMITS:
            lim = getattr(r, limit)
            assert c.limits[0][case][limit] == {"value": lim.value, "status": lim.status.value,
                                                "range_end": lim.range_end}  # fmt: skip


def test_one_sided_comparison_report_is_its_json_and_the_code():
    """The committed Markdown renders the committed JSON, Delta's row is what the code computes now, no
    counterexample, and the table says what the simulation found: a free one-sided impact never diverged where
    the bilateral spring did."""
    c = _committed()
    assert (REPORT / f"{STEM}.md").read_text(encoding="utf-8") == comparison_markdown(c)
    assert c.counterexamples == 0 and c.status == "ok"
    i = c.devices.index("Delta")
    now = contact_comparison([dfa.get_device("Delta")], grid=c.grid, speeds=c.speeds)
    assert written(now.limits[0]) == c.limits[i]  # the committed JSON holds 12 digits
    bilateral, free = c.value(i, "bilateral", "k_sim"), c.limits[i]["one_sided"]["k_sim"]
    assert bilateral is not None and free["status"] == "above_range" and free["range_end"] > bilateral


def test_one_sided_comparison_cli_refuses_bad_input(capsys, tmp_path):
    for argv, words in ((["--grid", "1"], "--grid"), (["--velocity", "-1"], "--velocity")):
        assert main([*argv, "--out", str(tmp_path)]) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and words in err
    assert not any(tmp_path.iterdir())
