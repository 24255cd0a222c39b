"""The same inputs give the same outputs whatever --jobs (issue 41): results are gathered in the order of the
tasks (dfa._parallel.run_in_order), never in the order they finish, and every point is computed alone, so how the
points are dealt to threads or processes changes no number.

Compared: the numbers with a stated tolerance (relative 1e-12: they are in fact equal), the rendered text exactly.
"""

import math
import os
from collections import defaultdict

import numpy as np
import pytest
from fixed_keywords import small_design_searches

import dfa
from dfa.cli import main

TWO_CORES = pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="--jobs 2 needs 2 cores")

#: Relative tolerance of the numbers compared (a difference in the order of the sums would show as ~1e-16).
RTOL = 1e-12


def _assert_same(a, b, where="") -> None:
    """``a`` and ``b`` (JSON-like: dicts, lists, numbers, text) equal, floats within :data:`RTOL`."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and a.keys() == b.keys(), where
        for k in a:
            _assert_same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list | tuple):
        assert isinstance(b, list | tuple) and len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _assert_same(x, y, f"{where}[{i}]")
    elif isinstance(a, float) and isinstance(b, float):
        assert (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=RTOL, abs_tol=0.0), (where, a, b)
    else:
        assert a == b, (where, a, b)


@TWO_CORES
def test_map_json_and_file_same_for_jobs_1_and_2(capsys, tmp_path):
    outs = {}
    for jobs in (1, 2):
        path = tmp_path / f"m{jobs}.npz"
        argv = ["map", "--mu", "100", "--xi-dot", "1", "3", "--grid", "9", "--samples", "3000", "--quiet", "--json"]
        assert main([*argv, "--jobs", str(jobs), "--out", str(path)]) == 0
        outs[jobs] = (capsys.readouterr().out, dfa.load_map(path))
    (out1, m1), (out2, m2) = outs[1], outs[2]
    assert out1.replace("m1.npz", "m2.npz") == out2
    np.testing.assert_array_equal(m1.outcome, m2.outcome)
    np.testing.assert_allclose(m1.amplitude, m2.amplitude, rtol=RTOL, equal_nan=True)
    np.testing.assert_allclose(m1.frequency, m2.frequency, rtol=RTOL, equal_nan=True)


@pytest.mark.slow
@TWO_CORES
def test_design_report_same_for_jobs_1_and_2(monkeypatch):
    """The committed report (``make report``: the Delta, every core) on a small grid: its stability map on threads,
    its Z-width grid on threads and the Z-width's columns on processes as the committed report's 20 columns are
    (here from 2 columns on): the same numbers and the same Markdown with one job and with two."""
    import dfa.analysis.limits.zwidth as zwidth
    from dfa.studies.design import design_analysis
    from dfa.studies.design_document import design_markdown

    monkeypatch.setattr(zwidth, "PROCESS_COLUMNS", 2)
    small_design_searches(monkeypatch)  # K_max and the stiffness-speed chart take no jobs: small searches
    runs = {}
    for jobs in (1, 2):
        a = design_analysis(
            dfa.get_device("delta"), map_grid=3, samples=2000, n_jobs=jobs, progress=False, zwidth_grid=3
        )
        runs[jobs] = (a.to_dict(), design_markdown(a, defaultdict(str), str))
    _assert_same(runs[1][0], runs[2][0])
    assert runs[1][1] == runs[2][1]
