"""``to_xarray()`` of every gridded result (issue 25): labelled dims, coordinates and variables with units.

For each result: the Dataset's values are the result's arrays (and the numbers of its ``to_dict()``), the
dims, coordinates and units are right (the device's, rotary ones for a rotary device), NaN stays NaN (nothing
clipped), and without xarray the call fails with a package error naming the pip fix.
"""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import pytest

import dfa
from dfa.analysis.contours import contour_maps
from dfa.analysis.limits.closed_form import stiffness_response
from dfa.analysis.limits.speed_chart import UNKNOWN_DF, stiffness_speed_chart
from dfa.analysis.limits.zwidth import z_width
from dfa.analysis.linear_wall import LinearStatus, stable_region
from dfa.errors import DFAError, DFATypeError
from dfa.results.codes import POINT_OUTCOMES, ZWIDTH_METHODS

IMPULSE = dfa.get_device("Impulse Engine").device
ROTARY = dfa.get_device("RE35 testbed").device


def _nan_equal(a, b) -> bool:
    return np.array_equal(np.asarray(a, dtype=float), np.asarray(b, dtype=float), equal_nan=True)


def _json_numbers(values) -> np.ndarray:
    """A ``to_dict()`` list of numbers with its nulls back as NaN."""
    return np.array([math.nan if v is None else v for v in values], dtype=float)


@pytest.fixture(scope="module")
def zwidth():
    return z_width(IMPULSE, 0.1, grid=4, speeds=1, n_jobs=1)


@pytest.fixture(scope="module")
def chart():
    return stiffness_speed_chart(IMPULSE, grid=6, speeds=4, stiffness=80.0, velocity=0.05)


@pytest.fixture(scope="module")
def region():
    return stable_region(1.0, 0.0, 1e-3, [0.0, 2.0, 5.0])  # b = B = 0: never stable (no interval), then one


@pytest.fixture(scope="module")
def response():
    return stiffness_response(IMPULSE, [0.01, 0.05, 0.5], stiffness=80.0)


@pytest.fixture(scope="module")
def contours():
    return contour_maps(5.0, grid=6)


# ------------------------------------------------------------------ Z-width
def test_zwidth_outcome_is_the_grid_over_damping_and_stiffness_with_named_codes(zwidth):
    pytest.importorskip("xarray")
    ds = zwidth.to_xarray()
    assert ds["outcome"].dims == ("damping", "stiffness")
    np.testing.assert_array_equal(ds["outcome"].values, zwidth.outcome)
    np.testing.assert_array_equal(ds["damping"].values, zwidth.damping)
    np.testing.assert_array_equal(ds["stiffness"].values, zwidth.stiffness)
    attrs = ds["outcome"].attrs
    assert attrs["flag_meanings"].split() == list(POINT_OUTCOMES) and attrs["flag_values"] == list(
        range(len(POINT_OUTCOMES))
    )
    names = [[attrs["flag_meanings"].split()[c] for c in row] for row in ds["outcome"].values.tolist()]
    assert names == zwidth.to_dict()["outcome"]  # the JSON's names, point for point
    i, j = 2, 1
    point = ds["outcome"].sel(damping=zwidth.damping[i], stiffness=zwidth.stiffness[j])
    assert int(point) == zwidth.outcome[i, j]


def test_zwidth_boundaries_are_variables_over_damping_with_nan_kept(zwidth):
    pytest.importorskip("xarray")
    ds = zwidth.to_xarray()
    boundaries = zwidth.to_dict()["boundaries"]
    for m in ZWIDTH_METHODS:
        var = ds[f"k_max_{m}"]
        assert var.dims == ("damping",) and var.attrs["units"] == "N/m"
        assert _nan_equal(var.values, zwidth.boundary(m))
        assert _nan_equal(var.values, _json_numbers(boundaries[m]))
        assert ds[f"k_max_{m}_status"].values.tolist() == [x.status.value for x in zwidth.limits[m]]
    assert np.isnan(ds["k_max_passivity"].values).any()  # this grid has undefined boundaries: still NaN
    nan_at = np.isnan(ds["k_max_passivity"].values)
    assert all(s != "found" for s in ds["k_max_passivity_status"].values[nan_at])  # the status says why


def test_zwidth_units_and_attrs_follow_the_device(zwidth):
    pytest.importorskip("xarray")
    ds = zwidth.to_xarray()
    assert ds["damping"].attrs["units"] == "N·s/m" and ds["stiffness"].attrs["units"] == "N/m"
    assert ds["damping"].attrs["long_name"] == "virtual damping B"
    assert ds.attrs["velocity"] == zwidth.velocity and ds.attrs["velocity_units"] == "m/s"
    assert ds.attrs["speeds"] == list(zwidth.speeds) and ds.attrs["delay"] == zwidth.delay
    assert ds.attrs["status"] == zwidth.status.value and ds.attrs["device"] == IMPULSE.name
    assert ds.attrs["simulations"] == zwidth.simulations and ds.attrs["counterexamples"] == 0
    assert "filter_cutoff" not in ds.attrs and "amplifier_bandwidth" not in ds.attrs  # the spring: none
    rotary = dataclasses.replace(zwidth, device=ROTARY).to_xarray()  # same numbers, a rotary device's units
    assert rotary["damping"].attrs["units"] == "N·m·s/rad" and rotary["stiffness"].attrs["units"] == "N·m/rad"
    assert rotary["k_max_sim"].attrs["units"] == "N·m/rad" and rotary.attrs["velocity_units"] == "rad/s"


# ------------------------------------------------------------------ stiffness-speed chart
def test_speed_chart_speeds_are_over_stiffness_and_criterion_over_its_own_grid(chart):
    pytest.importorskip("xarray")
    ds = chart.to_xarray()
    data = chart.to_dict()
    for name in ("v_df", "v_sim", "v_rest"):
        assert ds[name].dims == ("stiffness",) and ds[name].attrs["units"] == "m/s"
        assert _nan_equal(ds[name].values, getattr(chart, name))
        assert _nan_equal(ds[name].values, _json_numbers(data[name]))
    assert ds["v_criterion"].dims == ("criterion_stiffness",)
    assert ds.sizes["criterion_stiffness"] == chart.criterion_stiffness.size != ds.sizes["stiffness"]
    np.testing.assert_array_equal(ds["v_criterion"].values, data["v_criterion"])
    np.testing.assert_array_equal(ds["criterion_stiffness"].values, data["criterion_stiffness"])
    np.testing.assert_array_equal(ds["stiffness"].values, data["stiffness"])
    np.testing.assert_array_equal(ds["speeds"].values, chart.speeds)
    assert ds["stiffness"].attrs["units"] == ds["criterion_stiffness"].attrs["units"] == "N/m"
    assert ds.attrs["v_top"] == chart.v_top and ds.attrs["k_linear"] == chart.k_linear
    assert ds.attrs["design_stiffness"] == 80.0 and ds.attrs["design_velocity"] == 0.05
    assert ds.attrs["stiffness_units"] == "N/m" and ds.attrs["velocity_units"] == "m/s"
    assert ds.attrs["simulations"] == chart.simulations and ds.attrs["delay"] == 0


def test_speed_chart_nan_stays_nan_and_nothing_is_clipped(chart):
    pytest.importorskip("xarray")
    v_df = np.array(chart.v_df)
    v_df[1] = math.nan  # the describing function cannot tell there
    v_df[2] = 10.0 * chart.v_top  # above v_top: what the result holds is what the Dataset holds
    ds = dataclasses.replace(chart, v_df=v_df).to_xarray()
    assert math.isnan(ds["v_df"].values[1]) and ds["v_df"].values[2] == 10.0 * chart.v_top
    assert UNKNOWN_DF in ds["v_df"].attrs["comment"]


def test_speed_chart_units_of_a_rotary_device():
    pytest.importorskip("xarray")
    ds = stiffness_speed_chart(ROTARY, grid=3, speeds=2).to_xarray()
    assert ds["v_sim"].attrs["units"] == ds["v_criterion"].attrs["units"] == "rad/s"
    assert ds["stiffness"].attrs["units"] == "N·m/rad" and ds.attrs["damping_units"] == "N·m·s/rad"
    assert ds.attrs["rotary"] == 1 and ds.attrs["v_top"] == 10.0


# ------------------------------------------------------------------ stable region of the linear loop
def test_stable_region_k_crit_over_virtual_damping_equals_the_result(region):
    pytest.importorskip("xarray")
    ds = region.to_xarray()
    data = region.to_dict()
    assert ds["k_crit"].dims == ("virtual_damping",)
    np.testing.assert_array_equal(ds["k_crit"].values, region.k_crit)
    np.testing.assert_array_equal(ds["k_crit"].values, data["k_crit"])
    np.testing.assert_array_equal(ds["virtual_damping"].values, data["virtual_damping"])
    assert ds["row_status"].values.tolist() == data["row_status"] == ["never", "interval", "interval"]
    assert ds["k_crit"].attrs["units"] == "N/m" and ds["virtual_damping"].attrs["units"] == "N·s/m"
    assert ds.attrs["status"] == LinearStatus.NEVER.value and ds.attrs["mass"] == 1.0 and ds.attrs["damping"] == 0.0
    assert ds.attrs["period"] == 1e-3 and ds.attrs["delay"] == 0


def test_stable_region_intervals_padded_with_nan_past_the_last(region):
    pytest.importorskip("xarray")
    ds = region.to_xarray()
    assert ds["intervals"].dims == ("virtual_damping", "interval", "end")
    assert ds["end"].values.tolist() == ["low", "high"]
    for i, row in enumerate(region.to_dict()["intervals"]):
        got = ds["intervals"].values[i]
        np.testing.assert_array_equal(got[: len(row)], np.array(row).reshape(-1, 2))
        assert np.isnan(got[len(row) :]).all()
    assert np.isnan(ds["intervals"].values[0]).all()  # B = 0 without friction: no stable interval


def test_stable_region_rotary_units_and_a_refused_flag(region):
    pytest.importorskip("xarray")
    ds = region.to_xarray(rotary=True)
    assert ds["k_crit"].attrs["units"] == "N·m/rad" and ds["virtual_damping"].attrs["units"] == "N·m·s/rad"
    assert ds.attrs["mass_units"] == "kg·m²" and ds.attrs["rotary"] == 1
    with pytest.raises(DFATypeError, match="rotary"):
        region.to_xarray(rotary="yes")


# ------------------------------------------------------------------ K_max over speed
def test_stiffness_response_k_max_over_velocity_equals_the_result(response):
    pytest.importorskip("xarray")
    ds = response.to_xarray()
    data = response.to_dict()
    assert ds["k_max"].dims == ("velocity",)
    np.testing.assert_array_equal(ds["k_max"].values, response.k_max)
    np.testing.assert_array_equal(ds["k_max"].values, data["k_max"])
    np.testing.assert_array_equal(ds["velocity"].values, data["velocity"])
    assert ds["k_max"].attrs["units"] == "N/m" and ds["velocity"].attrs["units"] == "m/s"
    for name in ("k_static", "k_colgate", "k_abbott_okamura", "k_gil", "stiffness", "max_passive_velocity", "delay"):
        assert ds.attrs[name] == data[name], name
    assert ds.attrs["status"] == data["status"] and ds.attrs["stiffness_units"] == "N/m"


def test_stiffness_response_keeps_inf_and_leaves_out_none():
    pytest.importorskip("xarray")
    soft = stiffness_response(IMPULSE, [0.01, 0.1], stiffness=1.0)  # passive at every speed
    assert soft.max_passive_velocity == math.inf
    ds = soft.to_xarray()
    assert ds.attrs["max_passive_velocity"] == math.inf  # not clipped, not dropped
    bare = stiffness_response(IMPULSE, [0.01, 0.1]).to_xarray()
    assert "stiffness" not in bare.attrs and "max_passive_velocity" not in bare.attrs


def test_stiffness_response_units_of_a_rotary_device():
    pytest.importorskip("xarray")
    ds = stiffness_response(ROTARY, [0.1, 1.0]).to_xarray()
    assert ds["k_max"].attrs["units"] == "N·m/rad" and ds["velocity"].attrs["units"] == "rad/s"
    assert ds.attrs["velocity_units"] == "rad/s" and ds.attrs["rotary"] == 1


# ------------------------------------------------------------------ contour maps
def test_contours_every_array_over_sigma_and_beta_with_nan_kept(contours):
    pytest.importorskip("xarray")
    ds = contours.to_xarray()
    data = contours.to_dict()
    arrays = [f.name for f in dataclasses.fields(contours) if isinstance(getattr(contours, f.name), np.ndarray)]
    for name in arrays:
        if name in ("beta", "sigma"):
            np.testing.assert_array_equal(ds[name].values, getattr(contours, name))
            continue
        assert ds[name].dims == ("sigma", "beta")
        assert ds[name].attrs["units"] == ("ticks" if "amplitude" in name else "rad/sample")
        assert _nan_equal(ds[name].values, getattr(contours, name))
    assert np.isnan(ds["small_amplitude"].values).any()  # the family does not exist everywhere: NaN there
    assert int(np.isfinite(ds["small_amplitude"].values).sum()) == data["small_points"]
    assert int(np.isfinite(ds["large_amplitude"].values).sum()) == data["large_points"]
    assert [ds.sizes["beta"], ds.sizes["sigma"]] == data["grid"]
    assert ds.attrs["mu"] == data["mu"] and ds.attrs["status"] == data["status"]


# ------------------------------------------------------------------ without xarray
@pytest.mark.parametrize("name", ["zwidth", "chart", "region", "response", "contours"])
def test_without_xarray_every_gridded_result_names_the_pip_fix(name, request, monkeypatch):
    result = request.getfixturevalue(name)
    monkeypatch.setitem(sys.modules, "xarray", None)  # import xarray now raises ImportError
    with pytest.raises(DFAError, match=r"pip install 'dfa-haptics\[xarray\]'"):
        result.to_xarray()
