"""Issue 46: the design report of a device file with configurations is the limiting configuration's, with a row per
configuration and the limiting one marked; the numbers are worst_stiffness's, and the limiting one is the smallest."""

from collections import defaultdict
from pathlib import Path

import pytest
from fixed_keywords import small_design_searches

from dfa.analysis.configurations import worst_stiffness
from dfa.model.catalogue import load_device_file
from dfa.model.loop import Loop
from dfa.model.wall import Wall
from dfa.studies.design import design_analysis
from dfa.studies.design_document import design_markdown

ARM = Path(__file__).resolve().parent.parent / "examples" / "arm_configurations.toml"


def test_report_rows_per_configuration_and_the_limiting_one_marked(monkeypatch):
    small_design_searches(monkeypatch)  # the section's rows are worst_stiffness's, not the spring's own search
    entry = load_device_file(ARM)
    w = worst_stiffness(entry.device, entry.configurations, 0.1, simulate=False)
    ans, _rec = w.details
    a = design_analysis(Loop(ans.device, Wall(entry.stiffness)), 0.1, map_grid=3, samples=2000, n_jobs=1,
                        configurations=w)  # fmt: skip
    md = design_markdown(a, defaultdict(lambda: "caption"), lambda n: f"{n}.png")
    section = md.split("## Configurations", 1)[1].split("\n## ", 1)[0]
    rows = [line for line in section.splitlines() if line.startswith("| ") and not line.startswith("| configuration")]
    assert [r.split("|")[1].strip() for r in rows] == [c.name for c in entry.configurations]
    marked = [r.split("|")[1].strip() for r in rows if "◀ limiting" in r]
    values = {r.name: r.value for r in w.rows}
    assert marked == [w.limiting] and values[w.limiting] == min(v for v in values.values() if v is not None)
    assert a.device.mass == pytest.approx(w.row.mass, rel=1e-12)  # the report is the limiting configuration's
    assert f"limiting configuration: {w.limiting}" in section
    assert "configurations" in a.to_dict()
