"""The stiffness–speed chart (issue 14 §2): data against the criterion (eq. 11-12), the orderings, the drawing."""

import json
import math

import numpy as np
import pytest

import dfa
from dfa.speed_chart import HAND_SPEED, stiffness_speed_chart
from dfa.stiffness import max_passive_velocity


@pytest.fixture(scope="module")
def chart():
    dev = dfa.get_device("phantom").device
    return stiffness_speed_chart(dev, stiffness=1015.0, velocity=0.2, grid=10, speeds=8)


def test_fig_chart_criterion_curve_is_eq12_capped_at_hand_speed(chart):
    assert chart.v_top == HAND_SPEED["linear"] == 2.0
    for k, v in zip(chart.criterion_stiffness[::20], chart.v_criterion[::20], strict=True):
        mpv = max_passive_velocity(chart.device, float(k))
        assert v == (0.0 if mpv is None else min(2.0, mpv))


def test_fig_chart_simulation_never_below_criterion_and_rest_below_no_divergence(chart):
    assert np.all(chart.v_rest <= chart.v_sim)
    for k, v_sim in zip(chart.stiffness, chart.v_sim, strict=True):
        mpv = max_passive_velocity(chart.device, float(k))
        proven = [s for s in chart.speeds if mpv is not None and s <= mpv]
        if proven:  # every speed the criterion proves passive must be safe in simulation
            assert v_sim >= proven[-1], (k, v_sim, proven[-1])
    # the chart reaches from "safe at every hand speed" to "not even the slowest speed"
    assert chart.v_sim[0] == chart.v_top and chart.v_sim[-1] == 0.0
    assert chart.simulations == 2 * len(chart.speeds) * len(chart.stiffness)


def test_fig_chart_rotary_hand_speed_and_json():
    c = stiffness_speed_chart(dfa.get_device("re35").device, grid=4, speeds=3)
    assert c.v_top == HAND_SPEED["rotary"]
    d = json.loads(json.dumps(c.as_dict(), allow_nan=False))
    assert d["stiffness_unit"] == "N·m/rad" and len(d["v_sim"]) == 4
    with pytest.raises(ValueError):
        c.v_sim[0] = 1.0  # read-only


def test_fig_chart_plot_axes_lines_and_design_point(chart):
    ax = chart.plot()
    assert ax.get_xscale() == "log" and ax.get_xlabel() == "stiffness K (N/m)"
    assert ax.get_ylabel() == "largest safe impact speed (m/s)"
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    for needle in (
        "criterion",
        "describing function",
        "no divergence",
        "comes to rest",
        "Abbott–Okamura",
        "Colgate–Schenkel",
        "exact linear bound",
        "design point K = 1015",
    ):
        assert any(needle in s for s in labels), needle
    top = ax.get_ylim()[1]
    assert top == pytest.approx(2.0 * 1.3) and math.isfinite(top)
