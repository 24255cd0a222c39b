"""Result conventions of h-results on the integrated code (design analysis, report, contours, Nyquist, JSON path)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import dfa
from dfa.analysis.contours import contour_maps
from dfa.analysis.loop import nyquist_locus_response
from dfa.errors import DFAValueError
from dfa.jsonable import NULL_REASONS_KEY, dumps
from dfa.model.device import Params
from dfa.render.text import flagged_text, search_why
from dfa.results.status import ContourStatus, DesignStatus, NyquistStatus, ReportStatus
from dfa.studies.design import _check_validation, design_analysis
from dfa.studies.report import ReportResult


def _strict(d):
    return json.loads(json.dumps(d, allow_nan=False))


def test_one_json_path_the_files_json_is_the_sanitisers():
    obj = {"k": float("nan"), "v": (1.5, float("-inf")), "u": "N·m", "s": ContourStatus.OK, "a": np.arange(2.0)}
    assert json.loads(dumps(obj, ensure_ascii=False)) == json.loads(dumps(obj))
    assert json.loads(dumps(obj, ensure_ascii=False))[NULL_REASONS_KEY] == {"/k": "NaN", "/v/1": "-inf"}
    assert "N·m" in dumps(obj, ensure_ascii=False)  # non-ASCII kept in files people read


def test_design_analysis_status_enum_and_strict_json():
    a = design_analysis(dfa.get_device("impulse"), velocity=0.05, map_grid=3, samples=2000, n_jobs=1)
    assert a.status is DesignStatus.OK and a.status == "ok"
    d = _strict(a.to_dict())
    assert d["status"] == "ok" and d["status_message"] == DesignStatus.OK.message
    assert d["outcome"]["outcome"] == a.outcome.outcome.value
    r = ReportResult((), (), {}, analysis=a)
    rd = _strict(r.to_dict())
    assert rd["status"] == "ok" and rd["status_message"] == ReportStatus.OK.message
    assert rd["analysis"]["criterion"]["status"] == a.criterion.status.value
    with pytest.raises(DFAValueError, match="ReportStatus"):
        ReportResult((), (), status="done")


def test_design_reads_a_null_validation_number_back_as_nan():
    summary = {
        "soundness_violations": 0,
        "soundness_passive": 10,
        "conservatism": None,  # strict validation.json: NaN stored as null
        "speed_df_median_error": 0.1,
        "short_period_frequency_error": 0.2,
        NULL_REASONS_KEY: {"/conservatism": "NaN"},
    }
    got = _check_validation(summary)
    assert got is not None and math.isnan(got["conservatism"]) and got["soundness_passive"] == 10


def test_fig7_contours_ok_without_the_degenerate_corner_flagged_with_it():
    ok = contour_maps(5.0, beta_range=(0.1, 1.0), grid=4, max_amplitude=10.0)
    assert ok.status is ContourStatus.OK and ok.flagged == () and flagged_text(ok) == ""
    assert ok.to_dict()["status_message"] == ContourStatus.OK.message
    flagged = contour_maps(5.0, grid=4, max_amplitude=10.0)
    d = _strict(flagged.to_dict())
    assert d["status"] == "flagged" and d["status_message"] == ContourStatus.FLAGGED.message
    assert d["flagged"] == [{"family": "small", "reason": "degenerate", "points": 1, "equations": "eq. 42-43"}]
    text = flagged_text(flagged)
    assert text.startswith("eq. 42-43: 1 point(s) NaN") and "β = σ = 0" in text and "DEGENERATE" not in text
    ds = flagged.to_xarray() if _has_xarray() else None
    if ds is not None:
        assert ds.attrs["status"] == "flagged" and ds.attrs["flagged_points"] == 1


def _has_xarray() -> bool:
    try:
        import xarray  # noqa: F401
    except ImportError:
        return False
    return True


def test_fig6_nyquist_sigma_zero_crossings_from_the_solver_status_ok():
    r = nyquist_locus_response(Params(mu=5.0, beta=0.4, sigma=0.0))
    assert r.status is NyquistStatus.OK and r.search is not None and r.search.reached is None
    d = _strict(r.to_dict())
    assert d["status"] == "ok" and len(d["crossings"]) == 2
    s = nyquist_locus_response(Params(mu=5.0, beta=0.4, sigma=0.3), amplitudes=[1.0, 2.0])
    assert s.status is NyquistStatus.CROSSINGS_NOT_COMPUTED and s.to_dict()["status_message"] == s.status.message


def test_fig6_nyquist_reports_an_incomplete_solver_search(monkeypatch):
    import dfa.analysis.cycles as cyc
    import dfa.analysis.cycles.solve as solve

    real = solve.limit_cycles

    def incomplete(p, **kw):
        res = real(p, **kw)
        return cyc.LimitCycleResult(
            res.params, res.model, res.wall, res.pade_order, res.describing, res.max_amplitude, res.cycles,
            False, cyc.SearchEvidence(res.max_amplitude, failures=1), cyc.SearchStatus.NUMERICAL,
        )  # fmt: skip

    monkeypatch.setattr(solve, "limit_cycles", incomplete)  # the function the locus calls
    r = nyquist_locus_response(Params(mu=5.0, beta=0.4, sigma=0.0))
    assert r.status is NyquistStatus.SEARCH_INCOMPLETE and r.search.failures == 1
    assert "1 root bracket(s) could not be refined" in search_why(r)
    assert _strict(r.to_dict())["search"]["failures"] == 1
