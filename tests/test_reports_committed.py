"""The committed reports/ are what `make report` writes (issue 27 §1), checked without running make.

`make report` must reproduce reports/design_report_delta.* and its figures exactly. The suite cannot afford the
run (a 20 × 20 Z-width), so it checks what made the tree dirty before: the Makefile's command and the committed
report agree on the device and the Z-width grid, every figure a report names exists and every committed figure is
named by a report or the README (no stale file such as an unreferenced delta_zwidth.png), and the numbers the
Markdown states are the JSON's.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import dfa
from dfa.formatting import number

ROOT = Path(__file__).resolve().parent.parent
REPORTS = ROOT / "reports"


def _make_report_command() -> str:
    text = (ROOT / "Makefile").read_text(encoding="utf-8")
    m = re.search(r"^report:.*\n\t(.*)$", text, re.M)
    assert m, "the Makefile has no report target"
    return m.group(1)


def test_make_report_command_and_the_committed_report_agree():
    cmd = _make_report_command()
    data = json.loads((REPORTS / "design_report_delta.json").read_text(encoding="utf-8"))
    grid = int(re.search(r"--zwidth (\d+)", cmd).group(1))
    z = data["analysis"]["zwidth"]
    assert z is not None and len(z["stiffness"]) == grid and len(z["damping"]) == grid
    assert "--device" not in cmd and data["identity"]["device"]["name"] == dfa.get_device(dfa.DEFAULT_DEVICE).name
    assert ("--validation" in cmd) == (data["analysis"]["validation"] is not None)
    assert data["paths"] == [f"reports/design_report_delta.{s}" for s in ("md", "html", "json")]


def test_every_committed_figure_is_named_and_every_named_figure_exists():
    named: set[str] = set()
    for doc in [*REPORTS.glob("*.md"), ROOT / "README.md", *(ROOT / "docs").glob("*.md")]:
        named |= set(re.findall(r"figures/([\w.-]+\.(?:png|svg|pdf))", doc.read_text(encoding="utf-8")))
    on_disk = {p.name for p in (REPORTS / "figures").iterdir() if p.suffix in (".png", ".svg", ".pdf")}
    assert named - on_disk == set(), "a report names a figure that is not committed"
    assert on_disk - named == set(), "a committed figure no report names (stale output)"
    for report in REPORTS.glob("design_report_*.json"):
        for fig in json.loads(report.read_text(encoding="utf-8"))["figures"]:
            assert (ROOT / fig).is_file(), fig


def test_committed_report_markdown_states_the_json_numbers():
    data = json.loads((REPORTS / "design_report_delta.json").read_text(encoding="utf-8"))
    md = (REPORTS / "design_report_delta.md").read_text(encoding="utf-8")
    nums, a = data["numbers"], data["analysis"]
    assert f"the largest passive stiffness is {nums['k_max']:.5g} N/m" in md
    rec = a["recommendation"]
    assert f"**Recommended stiffness:** K = {number(rec['k_recommended'], 5)} N/m" in md
    crit = a["design_answer"]["k_criterion"]["value"]
    assert f"| criterion (eq. 11; a proof) | {number(crit, 5)} N/m |" in md
