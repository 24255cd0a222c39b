"""Result objects users work with (issue 13 §3-§4): status enums, read-only arrays, strict JSON, plot(), to_xarray().

Every result class of the package is built here by the analysis that returns it; the properties are:
``to_dict()`` survives strict JSON (no NaN/Infinity tokens) unchanged, arrays cannot be written,
status members carry messages, construction refuses inconsistent data, ``.plot()`` returns labelled Axes.
"""

from __future__ import annotations

import enum
import importlib.metadata
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from result_json import assert_json_from_fields

import dfa
from dfa.analysis.contours import contour_maps
from dfa.analysis.cycles import growth_threshold, limit_cycles
from dfa.analysis.limits.closed_form import stiffness_limits, stiffness_response
from dfa.analysis.loop import nyquist_locus_response
from dfa.analysis.maps import StabilityMap, stability_map
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.errors import DFAError, DFAValueError
from dfa.jsonable import JSON_DIGITS, NULL_REASONS_KEY, dumps, round_floats, round_sig, to_jsonable
from dfa.model.device import Params
from dfa.model.wall import WallParams
from dfa.results import status as status_mod
from dfa.studies.soundness import Population, criterion_soundness
from dfa.studies.validation import Soundness, ValidationResult

ROOT = Path(__file__).resolve().parents[1]
DEV = dfa.get_device("Delta").device


def _refuse_constant(token):
    raise AssertionError(f"non-strict JSON token {token}")


def strict_roundtrip(d):
    """``d`` through strict JSON: no NaN/Infinity on the way out, none accepted on the way in, unchanged."""
    text = json.dumps(d, allow_nan=False)
    back = json.loads(text, parse_constant=_refuse_constant)
    assert back == json.loads(json.dumps(d)), "to_dict() holds tuples or non-string keys that JSON changes"
    return back


def _resolve(doc, pointer: str):
    """The value at a JSON pointer (RFC 6901) inside ``doc``."""
    for part in pointer.split("/")[1:]:
        part = part.replace("~1", "/").replace("~0", "~")
        doc = doc[int(part)] if isinstance(doc, list) else doc[part]
    return doc


# ------------------------------------------------------------------ fixtures: one result of each kind
@pytest.fixture(scope="module")
def small_map():
    return stability_map(20.0, [1.0, 4.0], grid=4, samples=3000, n_jobs=1, progress=False)


@pytest.fixture(scope="module")
def contours():
    return contour_maps(5.0, grid=6)


@pytest.fixture(scope="module")
def nyquist():
    return nyquist_locus_response(Params(5.0, 0.4, 0.0))


@pytest.fixture(scope="module")
def empty_validation():
    snd = Soundness((5.0,), (1.0,), 0, 0)
    return ValidationResult(True, [], [], snd, 100)


# ------------------------------------------------------------------ status enums
ENUMS = [
    obj
    for obj in vars(status_mod).values()
    if isinstance(obj, type) and issubclass(obj, status_mod.StatusEnum) and obj is not status_mod.StatusEnum
]


@pytest.mark.parametrize("cls", ENUMS, ids=lambda c: c.__name__)
def test_status_enum_members_carry_messages(cls):
    assert len(cls) >= 1
    for m in cls:
        assert isinstance(m.message, str) and len(m.message) > 5, m
        assert m == m.value and str(m) == m.value and f"{m}" == m.value and cls(m.value) is m
        assert json.loads(dumps({"s": m})) == {"s": m.value}
    with pytest.raises(DFAValueError, match=cls.__name__):
        cls.coerce("no such status")


def test_eq6_fig3_status_is_the_region_meaning():
    """One text per region: REGION_DESCRIPTIONS comes from CriterionStatus (paper Fig. 3)."""
    assert {s.region: s.message for s in status_mod.CriterionStatus} == dfa.REGION_DESCRIPTIONS
    for region in "abcde":
        assert status_mod.CriterionStatus.of_region(region).region == region


def test_search_status_is_the_cycle_module_enum():
    from dfa.analysis.cycles import SearchStatus

    assert SearchStatus is status_mod.SearchStatus
    res = limit_cycles(Params(5.0, 0.1, 0.6))
    assert res.status is SearchStatus.COMPLETE and res.status_code is res.status and res.complete


# ------------------------------------------------------------------ strict JSON of every result (hypothesis)
finite = st.floats(0.0, 3.0, allow_nan=False)


@given(beta=finite, sigma=finite, xi_dot=st.floats(-20, 20, allow_nan=False), delay=st.integers(0, 3))
def test_eq6_criterion_to_dict_is_strict_json(beta, sigma, xi_dot, delay):
    r = dfa.passivity_criterion(beta, sigma, xi_dot, wall=WallParams.of(delay=delay))
    d = strict_roundtrip(r.to_dict())
    assert d["status"] == r.status.value and d["status_message"] == r.status.message
    assert r.status.region == r.region


@given(
    velocity=st.floats(0.0, 5.0, allow_nan=False),
    stiffness=st.one_of(st.none(), st.floats(1.0, 1e6)),
    delay=st.integers(0, 2),
)
def test_eq11_stiffness_to_dict_is_strict_json(velocity, stiffness, delay):
    lim = stiffness_limits(DEV, velocity, stiffness, delay)
    d = strict_roundtrip(lim.to_dict())
    assert (
        d["status"] in ("ok", "too_stiff", "not_requested")
        and d["max_passive_velocity_status"] == lim.velocity_status.value
    )
    assert (d["status"] == "not_requested") == (stiffness is None)  # no "ok" for a verdict nobody asked for
    curve = stiffness_response(DEV, [velocity + 1e-3, velocity + 1.0], stiffness, delay)
    c = strict_roundtrip(curve.to_dict())
    assert c["k_max"] == pytest.approx(list(curve.k_max), rel=0, abs=0)
    if stiffness is not None and math.isinf(curve.max_passive_velocity or 0.0):
        assert c["max_passive_velocity"] is None and c[NULL_REASONS_KEY]["/max_passive_velocity"] == "+inf"


@settings(max_examples=25)
@given(
    mu=st.floats(1.0, 200.0),
    beta=st.floats(0.0, 1.0),
    sigma=st.floats(0.0, 1.5),
    xi_dot0=st.floats(-5.0, 5.0),
    quantize=st.booleans(),
)
def test_eq4_simulation_to_dict_is_strict_json(mu, beta, sigma, xi_dot0, quantize):
    r = simulate(mu, beta, sigma, xi_dot0, samples=400, quantize=quantize, energy=True, bound=50.0)
    d = strict_roundtrip(r.to_dict())
    assert d["outcome"] == r.outcome.value and d["status_message"] == r.status.message
    reasons = d.get(NULL_REASONS_KEY, {})
    for key, reason in reasons.items():  # every reason names a null ...
        assert _resolve(d, key) is None and reason
    assert all(f"/{k}" in reasons for k, v in d.items() if v is None)  # ... and every null has one
    strict_roundtrip(r.energy.to_dict())


@settings(max_examples=12)
@given(mu=st.floats(2.0, 50.0), beta=st.floats(0.0, 0.45), sigma=st.floats(0.0, 1.0), delay=st.integers(0, 1))
def test_eq36_limit_cycles_and_growth_to_dict_are_strict_json(mu, beta, sigma, delay):
    g = growth_threshold(Params(mu, beta, sigma), DEV, wall=WallParams.of(delay=delay))
    d = strict_roundtrip(g.to_dict())
    assert d["status"] == g.status.value and (d["amplitude"] is None) == (g.status is not status_mod.GrowthStatus.OK)
    r = strict_roundtrip(g.result.to_dict())
    assert r["status"] == g.result.status.value and r["complete"] == (r["status"] == "complete")


def test_fig6_nyquist_to_dict_is_strict_json(nyquist):
    d = strict_roundtrip(nyquist.to_dict())
    assert [(round(c["amplitude"], 4), round(c["frequency"], 4)) for c in d["crossings"]] == [
        (0.7905, 0.3974),
        (1.0098, 0.3974),
    ]
    assert len(d["curves"]) == 1 and len(d["curves"][0]) == nyquist.omega.size
    assert "/locus" in d[NULL_REASONS_KEY] or np.all(np.isfinite(nyquist.locus))  # -1/D(M) is -inf where D = 0


@settings(max_examples=10)
@given(
    mu=st.floats(1.0, 100.0),
    beta=st.floats(0.0, 1.0),
    sigma=st.floats(0.01, 1.0),
    amplitudes=st.lists(st.floats(0.05, 50.0), min_size=1, max_size=3),
)
def test_eq40_nyquist_with_friction_to_dict_is_strict_json(mu, beta, sigma, amplitudes):
    r = nyquist_locus_response(Params(mu, beta, sigma), amplitudes, omega=np.geomspace(1e-3, np.pi, 50))
    d = strict_roundtrip(r.to_dict())
    assert d["status"] == "crossings_not_computed" and d["crossings"] == [] and len(d["curves"]) == len(amplitudes)
    assert r.status.message.startswith("crossings not computed for sigma > 0")


@settings(max_examples=6)
@given(mu=st.floats(1.0, 200.0), grid=st.integers(2, 5))
def test_fig7_contours_as_dict_is_strict_json(mu, grid):
    c = contour_maps(mu, grid=grid)
    d = strict_roundtrip(c.to_dict())
    assert d["grid"] == [grid, grid] and d["large_points"] == int(np.isfinite(c.large_amplitude).sum())


def test_eq6_criterion_refuses_nan_fields():
    r = dfa.passivity_criterion(0.2, 0.7, 2.0)
    with pytest.raises(DFAValueError, match="margin = nan"):
        type(r)(**{**vars(r), "margin": math.nan})


def test_fig4_map_and_fig7_contours_as_dict_are_strict_json(small_map, contours):
    m = strict_roundtrip(small_map.to_dict())
    assert sum(m["counts"][0].get(k, 0) for k in dfa.analysis.simulation.OUTCOMES) == 16 and m["status"] == "ok"
    c = strict_roundtrip(contours.to_dict())
    assert c["small_points"] == int(np.isfinite(contours.small_amplitude).sum())


def test_soundness_and_validation_as_dict_null_nan_with_reason(empty_validation):
    d = strict_roundtrip(empty_validation.to_dict())
    assert d["conservatism"] is None and d[NULL_REASONS_KEY]["/conservatism"] == "NaN"
    assert d["status"] == "ok"
    s = strict_roundtrip(empty_validation.soundness.to_dict())
    assert s["conservatism"] is None and s[NULL_REASONS_KEY] == {"/conservatism": "NaN"}
    r = criterion_soundness(4, Population(delay=1), seed=3)
    j = strict_roundtrip(r.to_dict())
    assert j["violations"] == r.violations and j["status"] == r.status.value


# ------------------------------------------------------------------ the sanitiser itself
json_leaf = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-(10**6), 10**6),
    st.floats(allow_nan=True, allow_infinity=True),
    st.text(max_size=5),
    st.sampled_from(list(status_mod.SimulationOutcome)),
    st.floats(allow_nan=True, allow_infinity=True).map(np.float64),
    st.integers(-100, 100).map(np.int64),
    st.lists(st.floats(allow_nan=True, allow_infinity=True), max_size=4).map(np.array),
)
json_tree = st.recursive(
    json_leaf,
    lambda kids: st.one_of(st.lists(kids, max_size=3), st.dictionaries(st.text(max_size=4), kids, max_size=3)),
    max_leaves=12,
)


@given(st.dictionaries(st.text(max_size=4), json_tree, max_size=4))
def test_sanitiser_output_is_strict_json_and_every_null_has_a_reason(tree):
    out = to_jsonable(tree)
    back = json.loads(dumps(tree), parse_constant=_refuse_constant)
    assert back == round_floats(out)
    for pointer, reason in out.get(NULL_REASONS_KEY, {}).items():
        target = _resolve(out, pointer)
        assert target is None or isinstance(target, list), (pointer, target)
        assert "NaN" in reason or "inf" in reason


@given(st.floats(allow_nan=False, allow_infinity=False))
def test_json_floats_carry_twelve_digits_within_half_a_unit_and_never_minus_zero(x):
    """Issue 41: every float written as JSON is x to JSON_DIGITS = 12 significant digits: within half a unit of the
    12th digit (relative 5e-12), idempotent, and never -0; the text holds at most 12 significant digits."""
    y = round_sig(x)
    assert JSON_DIGITS == 12
    assert abs(y - x) <= 5e-12 * abs(x) * (1 + 1e-15) + 5e-324
    assert round_sig(y) == y and not (y == 0 and math.copysign(1, y) < 0)
    text = dumps(x)
    mantissa = text.lower().split("e")[0].replace("-", "").replace(".", "").strip("0")
    assert len(mantissa) <= 12 and json.loads(text) == y


def test_json_of_two_values_one_ulp_apart_is_the_same_text():
    """The committed report's floats that differed between machines in their last bit (issue 41) print the same."""
    for a in (0.39176060908879473, 2215.31097483498, 1 / 3, 2.0 / 3.0 * 1e-7):
        b = np.nextafter(a, 2 * a)
        assert dumps({"v": a}) == dumps({"v": b}), a


def test_sanitiser_refuses_what_json_cannot_hold():
    with pytest.raises(TypeError, match="not JSON-able"):
        to_jsonable({"x": object()})
    assert to_jsonable({"z": 1 + 2j, "p": Path("a/b")}) == {"z": {"re": 1.0, "im": 2.0}, "p": "a/b"}


# ------------------------------------------------------------------ the CLI prints strict JSON
CLI_JSON = [
    ["devices"],
    ["params", "--device", "Delta"],
    ["check", "--device", "Delta", "--velocity", "0.1"],
    ["stiffness", "--device", "Delta", "--velocity", "0.1", "--stiffness", "1e9"],
    ["simulate", "--mu", "5", "--beta", "0.05", "--sigma", "0.2", "--xi-dot", "50", "--samples", "300"],
    ["simulate", "--mu", "5", "--beta", "0.6", "--sigma", "0.6", "--xi-dot", "2", "--samples", "300"],
    ["limit-cycles", "--mu", "5", "--beta", "0.1", "--sigma", "0.6"],
    ["limit-cycles", "--mu", "5", "--beta", "0.7", "--sigma", "0.0"],
    ["contours", "--mu", "5", "--grid", "5"],
]


@pytest.mark.parametrize("argv", CLI_JSON, ids=lambda a: " ".join(a[:3]))
def test_cli_json_is_strict(capsys, argv):
    assert main([*argv, "--json"]) == 0
    out = capsys.readouterr().out
    data = json.loads(out, parse_constant=_refuse_constant)
    for d in data if isinstance(data, list) else [data]:
        for pointer in d.get(NULL_REASONS_KEY, {}):
            assert _resolve(d, pointer) is None or isinstance(_resolve(d, pointer), list)


def test_cli_map_json_is_strict(capsys, tmp_path):
    argv = ["map", "--mu", "20", "--xi-dot", "1", "--grid", "3", "--samples", "500", "--jobs", "1", "--quiet"]
    assert main([*argv, "--out", str(tmp_path / "m.npz"), "--json"]) == 0
    data = json.loads(capsys.readouterr().out, parse_constant=_refuse_constant)
    assert data["status"] == "ok" and data["grid"] == [3, 3]


def test_cli_simulate_unstable_json_says_why_amplitude_is_null(capsys):
    assert (
        main(["simulate", "--mu", "5", "--beta", "0", "--sigma", "0", "--xi-dot", "30", "--samples", "4000", "--json"])
        == 0
    )
    d = json.loads(capsys.readouterr().out, parse_constant=_refuse_constant)
    assert d["outcome"] == "unstable" and d["amplitude"] is None
    assert d[NULL_REASONS_KEY]["/amplitude"] == "+inf"


# ------------------------------------------------------------------ read-only arrays, copies, validation
def _arrays(result):
    return {k: v for k, v in vars(result).items() if isinstance(v, np.ndarray)}


def test_arrays_of_results_are_read_only(small_map, contours, nyquist):
    sim = simulate(5.0, 0.3, 0.6, 2.0, samples=200, energy=True)
    curve = stiffness_response(DEV)
    for res in (small_map, contours, nyquist, sim, sim.energy, curve):
        arrays = _arrays(res)
        assert arrays, type(res).__name__
        for name, a in arrays.items():
            with pytest.raises(ValueError, match="read-only"):
                a.flat[0] = a.flat[0]
            assert not a.flags.writeable, (type(res).__name__, name)


def test_results_copy_their_input_arrays(small_map):
    beta = np.array(small_map.beta)
    m = StabilityMap(
        small_map.mu,
        small_map.xi_dots,
        beta,
        small_map.sigma,
        small_map.outcome,
        small_map.amplitude,
        small_map.frequency,
        small_map.samples,
    )
    beta[0] = 99.0
    assert m.beta[0] == small_map.beta[0]


def test_fig4_map_refuses_inconsistent_shapes_and_nan_axes(small_map):
    kw = dict(vars(small_map))
    with pytest.raises(DFAValueError, match="outcome has shape"):
        StabilityMap(**{**kw, "outcome": small_map.outcome[:, :, :2]})
    with pytest.raises(DFAValueError, match="beta"):
        StabilityMap(**{**kw, "beta": np.where(np.arange(4) == 1, np.nan, small_map.beta)})
    with pytest.raises(DFAValueError, match="codes outside"):
        StabilityMap(**{**kw, "outcome": np.full_like(small_map.outcome, 9)})


def test_fig7_contours_refuse_inconsistent_shapes(contours):
    kw = dict(vars(contours))
    with pytest.raises(DFAValueError, match="large_amplitude has shape"):
        type(contours)(**{**kw, "large_amplitude": contours.large_amplitude[:-1]})


def test_eq6_criterion_refuses_inconsistent_status():
    r = dfa.passivity_criterion(0.2, 0.7, 2.0)
    with pytest.raises(DFAValueError, match="region"):
        type(r)(**{**vars(r), "status": status_mod.CriterionStatus.PASSIVE_ALL_SPEEDS})
    with pytest.raises(DFAValueError, match="passive"):
        type(r)(**{**vars(r), "passive": True})


def test_eq11_stiffness_refuses_inconsistent_status():
    lim = stiffness_limits(DEV, 0.1, 14500.0)
    with pytest.raises(DFAValueError, match="velocity_status"):
        type(lim)(**{**vars(lim), "velocity_status": "all_speeds"})


def test_eq36_results_refuse_inconsistent_status():
    res = limit_cycles(Params(5.0, 0.1, 0.6))
    with pytest.raises(DFAValueError, match="complete"):
        type(res)(**{**vars(res), "complete": False})
    g = growth_threshold(Params(5.0, 0.1, 0.6))
    with pytest.raises(DFAValueError, match="status"):
        type(g)(**{**vars(g), "status": status_mod.GrowthStatus.NO_UNSTABLE_CYCLE})


def test_eq4_simulation_refuses_wrong_trajectory_length():
    r = simulate(5.0, 0.3, 0.6, 2.0, samples=50)
    with pytest.raises(DFAValueError, match="xi has shape"):
        type(r)(**{**vars(r), "xi": r.xi[:-1]})
    with pytest.raises(DFAValueError, match="outcome"):
        type(r)(**{**vars(r), "outcome": "exploded"})


# ------------------------------------------------------------------ .plot()
def _labelled(ax):
    assert ax.get_xlabel() and ax.get_ylabel(), type(ax)
    return True


def test_plot_methods_return_labelled_axes(small_map, contours, nyquist, empty_validation):
    import matplotlib.pyplot as plt
    from matplotlib.axes import Axes

    sim = simulate(5.0, 0.3, 0.6, 2.0, samples=200)
    single = [
        dfa.passivity_criterion(0.2, 0.7, 2.0).plot(),
        stiffness_response(DEV, stiffness=14500.0).plot(),
        sim.plot(),
        nyquist.plot(),
    ]
    for ax in single:
        assert isinstance(ax, Axes) and _labelled(ax)
    for axes in (small_map.plot(), contours.plot()):
        assert len(axes) >= 2 and all(isinstance(a, Axes) and _labelled(a) for a in axes)
    with pytest.raises(DFAValueError, match="record=True"):
        simulate(5.0, 0.3, 0.6, 2.0, samples=20, record=False).plot()
    _fig, given_ax = plt.subplots()
    assert sim.plot(ax=given_ax) is given_ax
    with pytest.raises(DFAValueError, match="which"):
        empty_validation.plot(which="nothing")
    plt.close("all")


# ------------------------------------------------------------------ to_xarray
def test_fig4_map_to_xarray_has_labelled_dims(small_map):
    pytest.importorskip("xarray")
    ds = small_map.to_xarray()
    assert ds["outcome"].dims == ("xi_dot", "sigma", "beta")
    assert ds["beta"].attrs["long_name"].startswith("β") and ds["sigma"].attrs["long_name"].startswith("σ")
    assert ds["xi_dot"].attrs["units"] == "ticks/sample" and ds["amplitude"].attrs["units"] == "ticks"
    np.testing.assert_array_equal(ds["outcome"].values, small_map.outcome)
    k, i, j = 1, 2, 3
    sel = ds.sel(xi_dot=small_map.xi_dots[k], sigma=small_map.sigma[i], beta=small_map.beta[j])
    assert int(sel["outcome"]) == small_map.outcome[k, i, j]
    assert ds.attrs["mu"] == small_map.mu and ds.attrs["status"] == "ok"
    assert ds["outcome"].attrs["flag_meanings"].split() == list(dfa.analysis.simulation.OUTCOMES)


def test_fig7_contours_to_xarray_has_labelled_dims(contours):
    pytest.importorskip("xarray")
    ds = contours.to_xarray()
    assert ds["small_amplitude"].dims == ("sigma", "beta") and ds["large_frequency"].attrs["units"] == "rad/sample"
    np.testing.assert_array_equal(ds["large_amplitude"].values, contours.large_amplitude)
    assert ds.attrs["max_amplitude"] == contours.max_amplitude


def test_to_xarray_without_xarray_names_the_fix(small_map, contours, monkeypatch):
    monkeypatch.setitem(sys.modules, "xarray", None)  # import xarray now raises ImportError
    for res in (small_map, contours):
        with pytest.raises(DFAError, match=r"pip install 'dfa-haptics\[xarray\]'"):
            res.to_xarray()


# ------------------------------------------------------------------ version
def test_version_is_single_sourced_from_pyproject():
    try:
        import tomllib
    except ImportError:  # pragma: no cover - Python 3.10
        import tomli as tomllib
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["version"]
    assert dfa.__version__ == importlib.metadata.version("dfa-haptics") == declared
    assert '__version__ = "' not in (ROOT / "dfa" / "__init__.py").read_text(encoding="utf-8")


def test_enum_members_serialise_by_value_everywhere():
    class Plain(enum.Enum):
        A = 3

    assert to_jsonable({"a": Plain.A, "b": status_mod.MapStatus.OK}) == {"a": 3, "b": "ok"}


def test_import_dfa_and_result_helpers_load_no_matplotlib_nor_xarray():
    import subprocess

    code = (
        "import sys, dfa, dfa.results.status, dfa.jsonable, dfa.analysis.limits.closed_form; "
        "print(sorted(m for m in ('matplotlib', 'xarray', 'control') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "[]"


def test_soundness_and_validation_result_json_from_their_fields(empty_validation):
    """Soundness and ValidationResult write the Result base's JSON (the latter: the key numbers of summary())."""
    snd = Soundness((5.0,), (1.0,), 4, 2, rest=2, rejected_rest=1)
    d = assert_json_from_fields(snd)
    assert d["conservatism"] == 0.5
    d = assert_json_from_fields(empty_validation, extra={"speeds_ordered", "controller_errors"})
    assert set(d) - {"status", "status_message", "null_reasons"} == set(empty_validation.summary())


def test_maps_and_cycles_json_from_fields():
    """StabilityMap, ContourMaps, LimitCycle, LimitCycleResult and GrowthThreshold on the Result base: their JSON
    is the fields (the arrays and the inner search left out) and the summary properties, strict JSON."""
    from dfa.analysis.contours import contour_maps
    from dfa.analysis.cycles.growth import growth_threshold

    dev = dfa.get_device("delta").device
    m = dfa.stability_map(100.0, [1.0, 5.0], grid=4, samples=2000, n_jobs=1)
    d = assert_json_from_fields(m, extra={"counts"})
    assert d["grid"] == [4, 4] and [c["xi_dot"] for c in d["counts"]] == [1.0, 5.0]
    assert all(sum(v for k, v in c.items() if k != "xi_dot") == 16 for c in d["counts"])
    assert "outcome" not in d and d["wall"]["delay"] == 0
    c = assert_json_from_fields(contour_maps(5.0, grid=6))
    assert c["small_points"] <= 36 and c["status_message"] == status_mod.ContourStatus(c["status"]).message
    r = dfa.limit_cycles(dev.params(14500.0), model="zoh")
    d = assert_json_from_fields(r)
    assert (d["mu"], d["beta"], d["sigma"]) == (r.params.mu, r.params.beta, r.params.sigma)
    assert d["status_message"] == r.status.message and d["linear_model"] == "zoh"
    assert d["search"]["requested"] == r.search.requested and d["search"]["failures"] == 0
    assert [assert_json_from_fields(x)["period"] for x in r.cycles] == [x.period for x in r.cycles]
    g = growth_threshold(dev.params(14500.0), dev)
    d = assert_json_from_fields(g)
    assert d["band"]["low"]["amplitude"] == g.amplitude and d["band"]["high"]["amplitude"] == g.amplitude_high
    assert d["complete"] is g.result.complete and "result" not in d
