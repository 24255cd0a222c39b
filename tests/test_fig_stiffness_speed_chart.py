"""The stiffness–speed chart (issue 14 §2): data against the criterion (eq. 11-12), the orderings, the drawing."""

import json
import math

import numpy as np
import pytest

import dfa
from dfa.analysis.limits.closed_form import max_passive_velocity
from dfa.analysis.limits.speed_chart import HAND_SPEED, stiffness_speed_chart


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
    d = json.loads(json.dumps(c.to_dict(), allow_nan=False))
    assert d["units"]["stiffness"] == "N·m/rad" and d["units"]["v_sim"] == "rad/s" and len(d["v_sim"]) == 4
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


def _inside(inner, outer) -> bool:
    return inner.x0 >= outer.x0 and inner.x1 <= outer.x1 and inner.y0 >= outer.y0 and inner.y1 <= outer.y1


def test_fig_chart_title_one_short_line_and_details_in_a_note_inside_the_figure(chart):
    """Issue 14 §5: the two-line title crowded the figure; now one short line, the details in a note below."""
    ax = chart.plot()
    fig = ax.figure
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    title = ax.title.get_text()
    assert "\n" not in title and len(title) <= 70 and title.startswith("Phantom 1.0:")
    (note,) = [t for t in ax.texts if "bottom edge" in t.get_text()]
    assert f"from {chart.speeds[0]:.3g} to {chart.v_top:g} m/s" in note.get_text()
    boxes = {
        "title": ax.title.get_window_extent(r),
        "note": note.get_window_extent(r),
        "xlabel": ax.xaxis.label.get_window_extent(r),
        "axes": ax.get_window_extent(r),
    }
    for name in ("title", "note"):
        assert _inside(boxes[name], fig.bbox), name  # drawn whole, even without bbox_inches="tight"
    assert not boxes["title"].overlaps(boxes["axes"]) and boxes["title"].y0 >= boxes["axes"].y1
    assert boxes["note"].y1 <= boxes["xlabel"].y0  # below the axis label, not over it
    import matplotlib.pyplot as plt

    plt.close(fig)
