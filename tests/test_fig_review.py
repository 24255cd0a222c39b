"""Figures a design review accepts (issue 14 §5) and physical units on figures (§3), checked on the drawn artists.

Each test reproduces one finding of the visual review: the operating point of Fig. 3 at β ≈ 0, legends over the
data (Figs. 3, 5, stiffness plot), the ξ'0 reference lines of Fig. 3, coinciding closed-form bounds (eq. 8, 9),
the Nyquist view of Fig. 6 (limits, zoom, loop model), trajectory windows (Fig. 5), the Fig. 4 map panels and
Fig. 7's contour labels.
"""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.transforms import Bbox

import dfa
from dfa.analysis.contours import contour_maps
from dfa.analysis.cycles import limit_cycles
from dfa.analysis.limits.closed_form import stiffness_response
from dfa.analysis.limits.speed_chart import stiffness_speed_chart
from dfa.analysis.loop import loop_response, nyquist_locus_response
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import simulate
from dfa.model.wall import WallParams
from dfa.render import figures


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def _boxes(fig):
    fig.canvas.draw()
    return fig.canvas.get_renderer()


def _legend_of(ax):
    """The axes' legend, or its figure's (a legend below or beside a figure's panels)."""
    return ax.get_legend() or next(iter(ax.figure.legends))


def _legend_clear_of_axes(ax, legend=None) -> bool:
    """The legend's box does not overlap the axes' plotting area (window extents, pixels)."""
    r = _boxes(ax.figure)
    leg = (legend or _legend_of(ax)).get_window_extent(r)
    return not Bbox.intersection(leg, ax.get_window_extent(r))


def test_fig3_operating_point_at_beta_zero_lies_inside_the_axes_and_the_legend_beside_them():
    r = dfa.passivity_criterion(0.00207, 2.03, 2.22)  # the Delta at 0.2 m/s: β ≈ 0
    ax = figures.regions_plot(r, xi_dots=[1.0, 5.0])
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    point = next(ln for ln in ax.get_lines() if ln.get_label().startswith("operating point"))
    rend = _boxes(ax.figure)
    px, py = ax.transData.transform((r.beta, r.sigma))
    box = ax.get_window_extent(rend)
    radius = point.get_markersize() / 72 * ax.figure.dpi / 2
    assert box.x0 + radius <= px <= box.x1 - radius and box.y0 + radius <= py <= box.y1 - radius
    assert x0 < 0 < r.beta < x1 and y0 < r.sigma < y1
    assert _legend_clear_of_axes(ax)


def test_fig3_reference_speed_lines_have_distinct_styles_and_legend_entries():
    r = dfa.passivity_criterion(0.25, 1.2, 2.0)
    ax = figures.regions_plot(r, xi_dots=[0.5, 1.0, 5.0])
    lines = [ln for ln in ax.get_lines() if ln.get_label().startswith("ξ'0 = ")]
    assert [ln.get_label() for ln in lines] == ["ξ'0 = 0.5", "ξ'0 = 1", "ξ'0 = 5"]
    styles = {(str(ln.get_linestyle()), ln.get_color(), ln.get_linewidth()) for ln in lines}
    assert len(styles) == 3
    legend = [t.get_text() for t in _legend_of(ax).get_texts()]
    assert all(ln.get_label() in legend for ln in lines)


def _bound_lines(ax):
    names = ("Abbott–Okamura", "Colgate–Schenkel", "exact linear bound", "static limit")
    return {n: ln for ln in ax.get_lines() for n in names if ln.get_label().startswith(n)}


def test_eq8_eq9_coinciding_bounds_drawn_distinctly_and_labelled_with_values_and_units():
    dev = dfa.get_device(
        "Delta"
    ).device  # 2b/T = 60 N/m: Colgate–Schenkel, Abbott–Okamura and the linear bound coincide
    ax = figures.stiffness_plot(stiffness_response(dev, stiffness=14500.0))
    lines = _bound_lines(ax)
    assert len(lines) == 4
    coinciding = [lines[n] for n in ("Abbott–Okamura", "Colgate–Schenkel", "exact linear bound")]
    assert len({(str(ln.get_linestyle()), ln.get_color(), ln.get_linewidth()) for ln in coinciding}) == 3
    cs = lines["Colgate–Schenkel"].get_label()
    assert "60 N/m" in cs and "(= A–O, linear)" in cs
    assert "5.887e+04 N/m" in lines["static limit"].get_label() and "(=" not in lines["static limit"].get_label()
    assert _legend_clear_of_axes(ax)


def test_fig_chart_bounds_legend_gives_values_with_rotary_units():
    chart = stiffness_speed_chart(dfa.get_device("re35").device, stiffness=0.1, velocity=2.0, grid=4, speeds=3)
    ax = chart.plot()
    for name, ln in _bound_lines(ax).items():
        assert "N·m/rad" in ln.get_label(), name
    assert any("design point K = 0.1 N·m/rad" in t.get_text() for t in ax.get_legend().get_texts())
    assert _legend_clear_of_axes(ax)


def _cycle_points(nyq, cycles):
    return [
        complex(
            loop_response(nyq.params, c.frequency, c.amplitude, model=nyq.model, wall=WallParams.of(delay=nyq.delay))
        )
        for c in cycles.cycles
    ]


@pytest.mark.parametrize("model", ["half-delay", "zoh"])
def test_fig6_nyquist_limits_contain_every_crossing_and_sub_tick_cycles_get_a_zoom(model):
    p = dfa.Params(mu=2.0, beta=0.4, sigma=0.1)  # a stable cycle below one tick among larger ones
    res = limit_cycles(p, model=model)
    assert min(c.amplitude for c in res.cycles) < 1.0
    nyq = nyquist_locus_response(p, amplitudes=[c.amplitude for c in res.cycles[:3]], model=model, cycles=res)
    ax = figures.nyquist_plot(nyq)
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    for pt in _cycle_points(nyq, res):
        assert x0 < pt.real < x1 and y0 < pt.imag < y1
    assert x0 < nyq.locus.real.min() and nyq.locus.real.max() < x1
    assert len(ax.child_axes) == 1  # the zoom inset
    (i0, i1), (j0, j1) = ax.child_axes[0].get_xlim(), ax.child_axes[0].get_ylim()
    for pt in _cycle_points(nyq, res):
        assert i0 < pt.real < i1 and j0 < pt.imag < j1
    assert ("exact ZOH" if model == "zoh" else "half-sample delay") in ax.get_title()
    assert _legend_clear_of_axes(ax)


def test_fig6_nyquist_scales_to_each_device_and_skips_the_zoom_for_one_large_cycle():
    limits = []
    for p in (dfa.Params(155.2, 0.00207, 2.03), dfa.Params(2.0, 0.4, 0.1)):
        res = limit_cycles(p, model="zoh")
        nyq = nyquist_locus_response(p, amplitudes=[c.amplitude for c in res.cycles[:3]], model="zoh", cycles=res)
        ax = figures.nyquist_plot(nyq)
        limits.append(ax.get_ylim())
        if len(res.cycles) == 1 and res.cycles[0].amplitude >= 1.0:
            assert not ax.child_axes and not figures.nyquist_needs_zoom(nyq)
    assert limits[0] != limits[1]  # no fixed [−2.5, 1]² window


def test_report_nyquist_uses_the_exact_zoh_loop_of_its_growth_threshold():
    from dfa.studies.design import design_analysis
    from dfa.studies.design_figures import design_figures

    # at rest (speed 0) the analysis skips the costly stiffness-speed chart; the Nyquist view is the same
    a = design_analysis(dfa.get_device("impulse"), velocity=0.0, map_grid=3, samples=2000, n_jobs=1)
    assert a.nyquist.model == "zoh"
    nyq = {f.name: f for f in design_figures(a)}["nyquist"]
    assert "exact ZOH" in nyq.caption and "half" not in nyq.caption


def test_fig5_a_run_that_comes_to_rest_fills_its_time_axis():
    dev = dfa.get_device("Delta").device
    p = dev.params(14500.0)
    r = simulate(p.mu, p.beta, p.sigma, dev.xi_dot(0.2), 4000)  # the Delta's report: at rest after ~330 samples
    assert r.rest_sample is not None and 5 <= r.rest_sample < 1000
    ax = figures.trajectory_plot(r, device=dev)
    t1 = ax.get_xlim()[1]
    assert r.rest_sample * dev.period <= t1 <= 4 * r.rest_sample * dev.period + 1e-12
    assert r.rest_sample * dev.period / t1 >= 0.2  # the motion is at least a fifth of the axis, not 2-5 %
    whole = figures.trajectory_plot(r, device=dev, window=False)
    assert whole.get_xlim()[1] == pytest.approx((r.xi.size - 1) * dev.period)


@pytest.mark.parametrize(("name", "unit"), [("re35", "rad"), ("Delta", "m")])
def test_fig5_trajectory_axes_in_seconds_and_metres_or_radians_for_a_device(name, unit):
    dev = dfa.get_device(name).device
    p = dev.params(1.0 if dev.rotary else 14500.0)
    r = simulate(p.mu, p.beta, p.sigma, 2.0, 1500)
    ax = figures.trajectory_plot(r, device=dev)
    assert ax.get_xlabel() == "time (s)"
    (sec,) = ax.child_axes
    _boxes(ax.figure)  # a secondary axis takes its limits when drawn
    label = sec.get_ylabel()
    assert label.endswith(f"{unit})") and label.split("(")[-1][:-1] in {unit, "m" + unit, "µ" + unit, "n" + unit}
    scale = {"": 1.0, "m": 1e3, "µ": 1e6, "n": 1e9}[label.split("(")[-1][: -1 - len(unit)]]
    assert np.allclose(sec.get_ylim(), np.array(ax.get_ylim()) * dev.resolution * scale)  # ξ·Δ


def test_fig5_figure_legend_and_preload_panel(tmp_path):
    import importlib.util
    import pathlib

    path = pathlib.Path(__file__).parents[1] / "examples" / "fig5_trajectories.py"
    spec = importlib.util.spec_from_file_location("fig5_trajectories", path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    res = mod.main(str(tmp_path), quick=True)
    fig = plt.gcf()
    r = _boxes(fig)
    (legend,) = fig.legends
    leg = legend.get_window_extent(r)
    assert all(not Bbox.intersection(leg, ax.get_window_extent(r)) for ax in fig.axes)
    preload = fig.axes[5]  # third row, trajectory: the preloaded start is shown, not a flat line
    ymin, ymax = preload.get_ylim()
    data = preload.get_lines()[0].get_ydata()
    assert (data.max() - data.min()) / (ymax - ymin) > 0.5
    assert res["cases"][2]["outcome"] == "rest"


def test_fig4_map_panels_physical_axes_every_outcome_in_the_legend_and_the_point():
    dev = dfa.get_device("phantom").device
    k = 1015.0
    p = dev.params(k)
    m = stability_map(p.mu, [dev.xi_dot(0.05)], grid=6, samples=2000, n_jobs=1, progress=False)
    (ax,) = figures.stability_map_plot(m, device=dev, stiffness=k, point=(p.beta, p.sigma))
    (legend,) = ax.figure.legends  # the panels' legend is the figure's, beside them
    labels = [t.get_text() for t in legend.get_texts()]
    for outcome in ("rest", "chatter", "oscillating", "unstable", "undecided"):
        assert any(s.startswith(outcome) for s in labels), outcome
    assert "m/s" in ax.get_title()
    top, right = ax.child_axes
    _boxes(ax.figure)  # a secondary axis takes its limits when drawn
    assert "(N·s/m)" in top.get_xlabel() and "(N)" in right.get_ylabel()
    assert top.get_xlim()[1] == pytest.approx(ax.get_xlim()[1] * k * dev.period)  # b = βKT (Table 1)
    assert right.get_ylim()[1] == pytest.approx(ax.get_ylim()[1] * k * dev.resolution)  # c = σKΔ
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert x0 < p.beta < x1 and y0 < p.sigma < y1
    assert _legend_clear_of_axes(ax, legend)


def test_fig4_outcome_colours_are_the_same_in_every_figure():
    from dfa.analysis.simulation import OUTCOMES

    cmap = figures.style.outcome_cmap()
    assert [matplotlib.colors.to_hex(cmap(i)) for i in range(len(OUTCOMES))] == [
        figures.OUTCOME_COLORS[o] for o in OUTCOMES
    ]
    assert len(set(figures.OUTCOME_COLORS.values())) == len(OUTCOMES)


def test_fig7_small_family_panel_shows_its_band_and_no_contour_label_is_clipped():
    c = contour_maps(5.0, grid=30)
    axes = figures.contour_plot(c)
    bb, ss = np.meshgrid(c.beta, c.sigma)
    top = ss[np.isfinite(c.small_amplitude)].max()
    assert top < 0.5 and axes[0].get_ylim()[1] <= max(1.15 * top, 0.55) + 1e-12
    for ax in axes:
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        for t in ax.texts:
            if t.get_transform() is ax.transData:
                x, y = t.get_position()
                assert x0 < x < x1 and y0 < y < y1, t.get_text()
    assert any(t.get_transform() is axes[0].transData for t in axes[0].texts)  # frequency labels remain


def test_fig5_a_diverged_run_is_shown_up_to_where_it_stopped():
    r = simulate(20.0, 0.05, 0.6, 30.0, 20_000, record=True, bound=1e4)  # stops early: beyond the bound
    assert r.outcome == "unstable" and r.samples_run < 20_000
    ax = figures.trajectory_plot(r, period=1e-3)
    assert ax.get_xlim()[1] == pytest.approx(r.samples_run * 1e-3)


# --- issue 26 §3: figures are written as .png, .pdf or .svg wherever a figure path is accepted ---------------------

_MAGIC = {".png": b"\x89PNG\r\n\x1a\n", ".pdf": b"%PDF-", ".svg": b"<?xml"}


@pytest.mark.parametrize("suffix", sorted(_MAGIC))
def test_save_figure_writes_each_file_type_by_its_suffix(tmp_path, suffix):
    ax = figures.regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
    for target in (ax, ax.figure):  # an Axes (as the *_plot functions return) or its Figure; a Path or a str
        path = figures.save_figure(
            target, tmp_path / f"regions{suffix}" if target is ax else str(tmp_path / f"f{suffix}")
        )
        data = path.read_bytes()
        assert data.startswith(_MAGIC[suffix]) and len(data) > 5000
        if suffix == ".svg":
            assert b"<svg" in data and b"</svg>" in data
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([f"regions{suffix}", f"f{suffix}"])


@pytest.mark.parametrize("name", ["regions.jpg", "regions.PDF", "regions", "regions.png.eps"])
def test_save_figure_refuses_another_suffix_and_writes_nothing(tmp_path, name):
    ax = figures.regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
    with pytest.raises(dfa.DFAValueError, match=r"must end in \.png, \.pdf or \.svg"):
        figures.save_figure(ax, tmp_path / name)
    assert list(tmp_path.iterdir()) == []


def _cli(capsys, *argv):
    from dfa.cli import main

    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("suffix", sorted(_MAGIC))
def test_cli_plot_writes_each_file_type(capsys, tmp_path, suffix):
    path = tmp_path / f"z{suffix}"
    code, out, err = _cli(capsys, "zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "3", "--speeds",
                          "1", "--jobs", "1", "--quiet", "--plot", str(path))  # fmt: skip
    assert code == 0, err
    assert path.read_bytes().startswith(_MAGIC[suffix]) and path.stat().st_size > 5000
    assert [p.name for p in tmp_path.iterdir()] == [path.name]


@pytest.mark.parametrize(
    "argv",
    [
        ["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "3"],
        ["stiffness", "--device", "impulse", "--velocity", "0.2"],
        ["contours", "--mu", "5", "--grid", "6"],
        ["map", "--mu", "5", "--xi-dot", "1", "--grid", "3", "--out", "{tmp}/m.npz"],
    ],
)
def test_cli_plot_refuses_another_suffix_before_any_work(capsys, tmp_path, argv):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    code, out, err = _cli(capsys, *argv, "--plot", str(tmp_path / "f.jpg"))
    assert code == 2 and err.count("\n") == 1
    assert "--plot" in err and "must end in .png, .pdf or .svg, not .jpg" in err and "f.png" in err
    assert list(tmp_path.iterdir()) == []


# --- issue 26 §4: legends readable at the saved size (>= 9 pt) ----------------------------------------------------


def _validation_stub():
    from types import SimpleNamespace

    cycles = [
        dict(model=m, stable=True, confirmed=True, period=p, frequency_error=e, amplitude_error=2 * e)
        for m in ("half-delay", "zoh")
        for p, e in ((3.0, 0.2), (12.0, 0.01))
    ]
    speeds = [dict(name=n, criterion=1.0, df_zoh=2.0, simulated=2.2, simulated_preload=2.1) for n in ("a", "b")]
    return SimpleNamespace(cycles=cycles, speeds=speeds)


def _impulse():
    return dfa.get_device("impulse").device


_FIGURES = {
    "regions": lambda: figures.regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0), xi_dots=[5.0]),
    "stiffness": lambda: figures.stiffness_plot(stiffness_response(_impulse(), stiffness=80.0)),
    "speed chart": lambda: stiffness_speed_chart(_impulse(), stiffness=80.0, velocity=0.1, grid=3, speeds=2).plot(),
    "nyquist": lambda: figures.nyquist_plot(
        nyquist_locus_response(
            dfa.Params(2.0, 0.4, 0.1),
            amplitudes=[0.3, 3.0],
            model="zoh",
            cycles=limit_cycles(dfa.Params(2.0, 0.4, 0.1), model="zoh"),
        )
    ),
    "map": lambda: figures.stability_map_plot(
        stability_map(100.0, [1.0], grid=3, samples=500, n_jobs=1, progress=False), point=(0.1, 0.9)
    )[0],
    "contours": lambda: figures.contour_plot(contour_maps(5.0, grid=12))[1],
    "zwidth": lambda: (
        __import__("dfa.analysis.limits.zwidth", fromlist=["z_width"])
        .z_width(_impulse(), 0.1, grid=3, speeds=1, n_jobs=1)
        .plot(design_point=(0.0, 80.0))
    ),
    "cycle errors": lambda: figures.cycle_error_plot(_validation_stub()),
    "critical speeds": lambda: figures.critical_speed_plot(_validation_stub()),
}


@pytest.mark.parametrize("name", sorted(_FIGURES))
def test_every_legend_is_at_least_9_pt_at_the_saved_size(name):
    fig = _FIGURES[name]().figure
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None] + list(fig.legends)
    assert legends, name
    sizes = [t.get_fontsize() for leg in legends for t in leg.get_texts()]
    assert sizes and min(sizes) >= 9.0, (name, min(sizes))


# --- issue 26 §4: the Z-width's "diverges" is visible, its grid values are markers ---------------------------------


def _luminance(colour) -> float:
    """Relative luminance (WCAG) of a matplotlib colour, 0 (black) to 1 (white)."""
    rgb = np.array(matplotlib.colors.to_rgb(colour))
    lin = np.where(rgb <= 0.03928, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    return float(lin @ [0.2126, 0.7152, 0.0722])


def _contrast(a, b) -> float:
    la, lb = sorted((_luminance(a), _luminance(b)))
    return (lb + 0.05) / (la + 0.05)


@pytest.fixture(scope="module")
def small_zwidth():
    from dfa.analysis.limits.zwidth import z_width

    return z_width(_impulse(), 0.1, grid=4, speeds=1, n_jobs=1)


def test_zwidth_diverges_shade_stands_out_from_the_page_and_the_legend(small_zwidth):
    ax = small_zwidth.plot()
    legend = ax.get_legend()
    patch = next(h for h, t in zip(legend.legend_handles, legend.get_texts(), strict=True)
                 if t.get_text() == "simulated: diverges")  # fmt: skip
    face = patch.get_facecolor()
    for background in (legend.get_frame().get_facecolor(), ax.get_facecolor(), ax.figure.get_facecolor()):
        assert _contrast(face, background) >= 1.5, (face, background)  # was white on white (contrast 1)
    mesh = next(c for c in ax.collections if isinstance(c, matplotlib.collections.QuadMesh))
    shades = {matplotlib.colors.to_hex(mesh.cmap(i)) for i in range(mesh.cmap.N)}
    assert shades == {c.lower() for c in figures.ZWIDTH_COLORS.values()}  # the grid is drawn in these shades
    assert matplotlib.colors.to_hex(face) == figures.ZWIDTH_COLORS["diverges"]  # and the legend says which


def test_zwidth_grid_valued_boundaries_are_markers_never_a_joined_line(small_zwidth):
    ax = small_zwidth.plot()
    grid_valued = [ln for ln in ax.get_lines() if ln.get_label().startswith("simulation:")]
    assert {ln.get_label() for ln in grid_valued} == {
        "simulation: no divergence (grid value)",
        "simulation: comes to rest (grid value)",
    }
    for ln in grid_valued:
        assert ln.get_linestyle() == "None" and ln.get_marker() not in (None, "None", "", " "), ln.get_label()
    linear = next(ln for ln in ax.get_lines() if ln.get_label() == "exact linear bound")
    assert linear.get_linestyle() == "-"  # a closed form stays a line


# --- issue 26 §4: the Nyquist inset zooms in, inside the main axes, its connectors inside the figure --------------


def _assert_inset_zooms_in(ax):
    (ins,) = ax.child_axes
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    (i0, i1), (j0, j1) = ins.get_xlim(), ins.get_ylim()
    assert x0 <= i0 < i1 <= x1 and y0 <= j0 < j1 <= y1, ((i0, i1, j0, j1), (x0, x1, y0, y1))
    assert (i1 - i0) <= 0.5 * (x1 - x0) and (j1 - j0) <= 0.5 * (y1 - y0)  # a zoom in both directions
    r = _boxes(ax.figure)
    page = ax.figure.bbox
    (indicator,) = [c for c in ax.get_children() if type(c).__name__ == "InsetIndicator"]
    for c in indicator.connectors:
        if c.get_visible():
            box = c.get_window_extent(r)
            assert page.x0 - 1 <= box.x0 and box.x1 <= page.x1 + 1 and page.y0 - 1 <= box.y0 and box.y1 <= page.y1 + 1
    return ins


def test_fig6_controller_nyquist_inset_zooms_in_on_the_sub_tick_cycle():
    """The Toolhandle with B = 5 N·s/m, f_c = 200 Hz, d = 1: a 0.07-tick stable cycle near the origin and a 25-tick
    unstable one at −1; the inset was a square in data units, taller than the main axes (zoomed out), its
    connectors running off the figure."""
    from dfa.model.wall import Wall

    dev = dfa.get_device("toolhandle").device
    wp = Wall.of(3125.0, damping=5.0, delay=1, filter_cutoff=200.0).params(dev.period)
    p = dev.params(3125.0)
    res = limit_cycles(p, model="zoh", wall=wp)
    assert sorted(c.amplitude < 1.0 for c in res.cycles) == [False, True]
    nyq = nyquist_locus_response(
        p,
        amplitudes=[c.amplitude for c in res.cycles],
        model="zoh",
        wall=wp,
        locus_amplitude=np.geomspace(0.05, 60, 400),
        cycles=res,
    )
    ax = figures.nyquist_plot(nyq, controller="B = 5 N·s/m, f_c = 200 Hz, d = 1")
    ins = _assert_inset_zooms_in(ax)
    pt = next(c.point for c in nyq.cycle_marks if c.amplitude < 1.0)
    assert ins.get_xlim()[0] < pt.real < ins.get_xlim()[1] and ins.get_ylim()[0] < pt.imag < ins.get_ylim()[1]


def test_fig6_paper_nyquist_inset_zooms_in_on_every_crossing():
    p = dfa.Params(mu=2.0, beta=0.4, sigma=0.1)
    res = limit_cycles(p, model="zoh")
    nyq = nyquist_locus_response(p, amplitudes=[c.amplitude for c in res.cycles[:3]], model="zoh", cycles=res)
    _assert_inset_zooms_in(figures.nyquist_plot(nyq))


# --- issue 26 §4: a map's legend draws only the lines in view; a uniform panel says so ----------------------------


def _drawn_in_view(ax, handle) -> bool:
    """Some line of ``ax`` in the handle's colour and dash has a vertex inside the axes (display coordinates)."""
    _boxes(ax.figure)
    box = ax.get_window_extent()
    for ln in ax.get_lines():
        same = matplotlib.colors.to_hex(ln.get_color()) == matplotlib.colors.to_hex(handle.get_color())
        if same and ln.get_linestyle() == handle.get_linestyle():
            pts = ln.get_transform().transform(ln.get_xydata())
            inside = (pts[:, 0] >= box.x0 - 0.5) & (pts[:, 0] <= box.x1 + 0.5)
            inside &= (pts[:, 1] >= box.y0 - 0.5) & (pts[:, 1] <= box.y1 + 0.5)
            if inside.any():
                return True
    return False


def _map_legend(axes):
    fig = axes[0].figure
    legend = next(iter(fig.legends), None) or next(ax.get_legend() for ax in axes if ax.get_legend() is not None)
    return list(zip(legend.legend_handles, [t.get_text() for t in legend.get_texts()], strict=True))


def test_fig4_controller_map_legend_draws_only_lines_in_view_and_names_the_others():
    """The custom device (0.1 kg, 0.005 N·s/m, 0.02 N, 10 µm, 1 kHz) at K = 2000 N/m with B = 1 N·s/m, f_c =
    200 Hz, d = 1: every point diverges, the extended criterion's line lies above the panels and its β₀ right of
    them. The legend showed the spring's lines (the map's wall was read from a field that no longer exists)."""
    from dfa.analysis.simulation import OUTCOMES
    from dfa.model.device import Device
    from dfa.model.wall import Wall

    dev = Device(name="custom", mass=0.1, damping=0.005, coulomb=0.02, resolution=1e-5, period=1e-3)
    k = 2000.0
    p = dev.params(k)
    wp = Wall.of(k, damping=1.0, delay=1, filter_cutoff=200.0).params(dev.period)
    m = stability_map(p.mu, [dev.xi_dot(0.1)], beta_range=(0, 0.25), sigma_range=(0, 2), grid=3, samples=600,
                      n_jobs=1, progress=False, wall=wp)  # fmt: skip
    assert (m.outcome == OUTCOMES.index("unstable")).all()  # every point diverges: an all-dark panel
    (ax,) = figures.stability_map_plot(m, device=dev, stiffness=k, point=(p.beta, p.sigma))
    entries = _map_legend([ax])
    texts = [t for _h, t in entries]
    assert "critical line, eq. 10 with the wall: above the panel" in texts
    assert any(t.startswith("region boundary σ = σ₀ = ") for t in texts)
    beta0 = next(t for t in texts if t.startswith("region boundary β = β₀ = "))
    assert beta0.endswith(": right of the panel")
    assert not any("½" in t or t == "critical line (eq. 10)" for t in texts)  # not the spring's lines
    for handle, text in entries:
        if isinstance(handle, matplotlib.lines.Line2D) and handle.get_linestyle() != "None":
            assert _drawn_in_view(ax, handle), text
    notes = [t.get_text() for t in ax.texts]
    assert "all 9 grid points: unstable (diverged)" in notes


def test_fig4_spring_map_with_delay_names_its_corner_off_the_panel():
    m = stability_map(155.2, [1.11], beta_range=(0, 0.25), sigma_range=(0, 2), grid=3, samples=600, n_jobs=1,
                      progress=False, wall=WallParams.of(delay=1))  # fmt: skip
    (ax,) = figures.stability_map_plot(m)
    texts = [t for _h, t in _map_legend([ax])]
    assert "critical line (eq. 10)" in texts
    assert "region boundary σ = ½" in texts
    assert "region boundary β = ½ + d = 1.5: right of the panel" in texts
    for handle, text in _map_legend([ax]):
        if isinstance(handle, matplotlib.lines.Line2D) and handle.get_linestyle() != "None":
            assert _drawn_in_view(ax, handle), text


# --- issue 26 §4: the stiffness-speed chart's criterion is not clipped flat; the stiffness figure's speeds -----------


def test_fig_chart_criterion_leaves_through_the_top_instead_of_running_flat_along_the_top_speed():
    chart = stiffness_speed_chart(_impulse(), stiffness=80.0, velocity=0.1, grid=3, speeds=2)
    capped = np.asarray(chart.v_criterion) >= chart.v_top
    assert capped.any() and (~capped).any()  # the criterion proves more than v_top at the softest stiffnesses
    ax = chart.plot()
    (line,) = [ln for ln in ax.get_lines() if ln.get_label().startswith("criterion")]
    y = np.asarray(line.get_ydata(), dtype=float)
    y0, y1 = ax.get_ylim()
    assert chart.v_top < y1 <= 1.5 * chart.v_top
    drawn = y[np.isfinite(y)]
    assert not np.any(np.isclose(drawn, chart.v_top, rtol=1e-9))  # no point, let alone a run, on the cap
    assert np.any(drawn > y1)  # it exits through the top edge
    inside = drawn[drawn <= y1]
    assert inside.size >= 0.2 * (~capped).sum()  # the uncapped curve itself is drawn
    x0, x1 = ax.get_xlim()
    assert x0 >= chart.stiffness[0] * (1 - 1e-9) and x1 <= chart.stiffness[-1] * (1 + 1e-9)


@pytest.mark.parametrize(("name", "top"), [("delta", 2.0), ("impulse", 2.0), ("re35", 10.0)])
def test_fig_stiffness_speed_axis_stays_within_the_speeds_computed_up_to_hand_speeds(name, top):
    import warnings

    dev = dfa.get_device(name).device
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the default speeds are plausible ones: no warning about 100 m/s
        curve = stiffness_response(dev)
    assert curve.velocity.max() == pytest.approx(top)  # was 1000 Δ/T: 92 m/s for the Delta
    ax = figures.stiffness_plot(curve)
    x0, x1 = ax.get_xlim()
    assert curve.velocity.min() * (1 - 1e-9) <= x0 < x1 <= curve.velocity.max() * (1 + 1e-9)


# --- issue 26 §4: Fig. 7's contour labels are not cut by the region boundaries ---------------------------------------


def test_fig7_a_contour_label_on_a_region_boundary_is_boxed_over_the_line():
    """On an 80 × 80 grid the small family's "2.00" label lands on β = ½ (in the report's 200 × 200 figure "2.80"
    lands on σ = ½): a label the line would cut gets a box in the fill's colour, drawn over the line."""
    c = contour_maps(5.0, grid=80)
    ax = figures.contour_plot(c)[0]
    ax.figure.canvas.draw()
    beta0, sigma0 = c.corner
    px, py = ax.transData.transform((beta0, sigma0))
    lines = [ln for ln in ax.get_lines() if ln.get_linestyle() == "-."]
    assert len(lines) == 2
    crossed = []
    for t in ax.texts:
        box = t.get_window_extent()
        if box.y0 - 1.5 <= py <= box.y1 + 1.5 or box.x0 - 1.5 <= px <= box.x1 + 1.5:
            crossed.append(t.get_text())
            patch = t.get_bbox_patch()
            assert patch is not None and patch.get_facecolor()[3] == 1.0, t.get_text()  # opaque
            assert t.get_zorder() > max(ln.get_zorder() for ln in lines)
            fill = matplotlib.colors.to_hex(patch.get_facecolor())
            assert fill not in ("#ffffff", "#000000")  # the viridis band under the label, not a white patch
    assert crossed == ["2.00"]


# --- issue 26 §4: Fig. 3's legend and regions c and d --------------------------------------------------------------


def _lab(colour) -> np.ndarray:
    """CIE L*a*b* (D65) of a matplotlib colour."""
    rgb = np.array(matplotlib.colors.to_rgb(colour))
    lin = np.where(rgb <= 0.04045, rgb / 12.92, ((rgb + 0.055) / 1.055) ** 2.4)
    m = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    xyz = m @ lin / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > 216 / 24389, np.cbrt(xyz), (24389 / 27 * xyz + 16) / 116)
    return np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])


def test_fig3_legend_names_the_operating_points_critical_line_in_words():
    r = dfa.passivity_criterion(0.00207, 2.03, 1.11, wall=WallParams.of(delay=1))
    ax = figures.regions_plot(r, xi_dots=[5.0])
    texts = [t.get_text() for t in _legend_of(ax).get_texts()]
    assert "critical line at the operating point's speed, ξ'0 = 1.11, d = 1" in texts
    assert not any("(point)" in t for t in texts)


def test_fig3_regions_c_and_d_read_apart_in_colour_and_hatching():
    r = dfa.passivity_criterion(0.2, 1.0, 2.0)  # regions c and d both on the plane
    ax = figures.regions_plot(r)
    c, d = figures.REGION_COLORS["c"], figures.REGION_COLORS["d"]
    assert np.linalg.norm(_lab(c) - _lab(d)) >= 35.0  # two tints of one orange were 27 apart, mostly in lightness
    legend = _legend_of(ax)
    patches = {t.get_text()[0]: h for h, t in zip(legend.legend_handles, legend.get_texts(), strict=True)
               if t.get_text()[1:2] == ":"}  # fmt: skip
    assert patches["c"].get_hatch() and not patches["d"].get_hatch()
    hatched = [col for col in ax.collections if any(h for h in getattr(col, "hatches", None) or [])]
    assert hatched  # region c is hatched in the plane too, not only in the legend


# --- issue 26 §4: the report's K_max tables keep their cells short, the evidence goes below them -------------------


@pytest.fixture(scope="module")
def delta_answers():
    from dfa.analysis.limits.kmax import design_answer
    from dfa.model.wall import Wall

    dev = dfa.get_device("delta").device
    small = dict(speeds=2, grid=6, max_samples=20000)
    spring = design_answer(dev, 0.1, **small)
    ctl = design_answer(dev, 0.1, wall=Wall.of(14500.0, 1.0, 1, 200.0), **small)
    return dev, spring, ctl


def _words(cell: str) -> int:
    return len(cell.split())


def test_report_kmax_tables_cells_short_and_the_evidence_below_them(delta_answers):
    """The committed reports' cells held 47-130 words (600-900 characters) of confirmation and evidence."""
    from types import SimpleNamespace

    from dfa.render.controller import controller_limit_rows
    from dfa.render.limits import evidence_lines
    from dfa.studies.design_document import answer_rows, evidence_markdown

    dev, spring, ctl = delta_answers
    rows = answer_rows(SimpleNamespace(design_answer=spring, device=dev, is_spring=True, covers=lambda what: True))
    for r, tables in ((spring, [rows]), (ctl, [controller_limit_rows(ctl, dev.units)])):
        for table in tables:
            cells = [c for row in table for c in row]
            assert max(_words(c) for c in cells) <= 30, max(cells, key=_words)
            assert not any("confirmed:" in c or "exact simulations:" in c for c in cells)
        below = evidence_markdown(r)
        lines = evidence_lines(r)
        assert any("confirmed:" in line for line in lines) and lines[-1].startswith("simulations run: ")
        for line in lines:  # every sentence of evidence is in the list below the table
            assert line.partition(": ")[2] in below
        assert below.startswith("What the simulated limits rest on:") and below.count("\n- **") == len(lines)


# --- issue 41 §2: the maps' legend, their secondary axes and `dfa map --plot`'s operating point --------------------

#: Width of the design report's column in CSS pixels (its HTML: ``body{max-width:980px}``); a wider PNG is shrunk.
_REPORT_COLUMN_PX = 980.0


def _report_like_map(speeds=(0.1, 0.2)):
    """The design report's map of the Delta (two speeds, physical axes, the operating point), on a small grid."""
    entry = dfa.get_device("delta")
    dev, k = entry.device, entry.stiffness
    p = dev.params(k)
    m = stability_map(p.mu, [dev.xi_dot(v) for v in speeds], beta_range=(0, 0.25), sigma_range=(0, 4), grid=3,
                      samples=300, n_jobs=1, progress=False)  # fmt: skip
    return figures.stability_map_plot(m, device=dev, stiffness=k, point=(p.beta, p.sigma))


def test_map_legend_names_each_region_boundary_in_its_own_entry_without_equating_numbers():
    """The Delta's map (β up to 0.25) read "σ = ½ (β = ½ = 0.5: right of the panels)": one entry for a line drawn
    and one off the panels, with "½ = 0.5"."""
    m = stability_map(155.2, [1.11], beta_range=(0, 0.25), sigma_range=(0, 2), grid=3, samples=300, n_jobs=1,
                      progress=False)  # fmt: skip
    (ax,) = figures.stability_map_plot(m)
    entries = _map_legend([ax])
    texts = [t for _h, t in entries]
    assert "region boundary σ = ½" in texts
    hidden = next(h for h, t in entries if t == "region boundary β = ½: right of the panel")
    assert hidden.get_linestyle() == "None"  # off the panel: words, no line
    assert not any("½ =" in t or "(" in t and "panel" in t for t in texts), texts


def test_map_secondary_axis_labels_as_large_as_the_main_ones_and_readable_in_the_report_column():
    """The right axis' "Coulomb c (N)" was 8 pt on an 11-inch figure the report's 980-px column shrinks to 72 %:
    about 6 px tall. At least 9 pt as shown, and as large as the σ axis' label."""
    axes = _report_like_map()
    fig = axes[0].figure
    _boxes(fig)
    shrink = min(1.0, _REPORT_COLUMN_PX / (fig.get_figwidth() * 120.0))  # the report's PNGs are saved at 120 dpi
    for ax in axes:
        top, right = ax.child_axes
        for label in (top.xaxis.label, right.yaxis.label):
            assert label.get_fontsize() >= ax.yaxis.label.get_fontsize()
            assert label.get_fontsize() * shrink >= 9.0, (label.get_text(), label.get_fontsize(), shrink)


def _panel_box(ax, r) -> Bbox:
    """A panel with its tick labels, axis labels, title and secondary axes (pixels), its legend left out."""
    parts = [ax.get_window_extent(r), ax.xaxis.get_tightbbox(r), ax.yaxis.get_tightbbox(r)]
    parts += [ax.title.get_window_extent(r)] if ax.get_title() else []
    return Bbox.union(parts + [c.get_tightbbox(r) for c in ax.child_axes])


def test_map_legend_starts_just_past_the_secondary_axis_and_clear_of_every_panel():
    """The legend was anchored at 1.3 axes widths to clear the right axis' label, leaving a blank gap beside it."""
    for axes in (_report_like_map(), _report_like_map((0.1,))):
        fig = axes[0].figure
        r = _boxes(fig)
        legend = next(iter(fig.legends), None) or next(ax.get_legend() for ax in axes if ax.get_legend())
        leg = legend.get_window_extent(r)
        boxes = [_panel_box(ax, r) for ax in axes]
        assert not any(Bbox.intersection(leg, box) for box in boxes)
        panels = Bbox.union(boxes)
        if leg.x0 >= panels.x1:  # beside the panels
            assert leg.x0 - panels.x1 < 0.25 * fig.dpi  # a quarter inch at most
        else:  # below them
            assert panels.y0 - leg.y1 < 0.25 * fig.dpi and leg.width <= panels.width


def test_cli_map_plot_has_the_operating_point_in_its_legend_and_draws_it_once(capsys, tmp_path, monkeypatch):
    import dfa.cli.maps as cli

    shown = []
    real = cli.save_png
    monkeypatch.setattr(cli, "save_png", lambda flag, path, ax: shown.append(ax) or real(flag, path, ax))
    code, _out, err = _cli(capsys, "map", "--device", "delta", "--velocity", "0.1", "--grid", "3", "--samples", "300",
                           "--jobs", "1", "--quiet", "--out", str(tmp_path / "m.npz"), "--plot",
                           str(tmp_path / "m.png"))  # fmt: skip
    assert code == 0, err
    fig = shown[0].figure
    texts = [t for _h, t in _map_legend([shown[0]])]
    assert "operating point" in texts
    for ax in (a for a in fig.axes if a.get_xlabel().startswith("β")):
        points = [ln for ln in ax.get_lines() if ln.get_marker() == figures.POINT_STYLE["marker"]]
        assert len(points) == 1


@pytest.mark.parametrize("name", ["speed chart", "stiffness"])
def test_bounds_legend_beside_the_plot_is_under_half_as_wide_as_it(name):
    """The speed chart's legend (eleven long labels on one line each) was as wide as its plot: labels break after
    a colon or comma, never inside a parenthesis or between a value and its unit."""
    ax = _FIGURES[name]()
    r = _boxes(ax.figure)
    legend = ax.get_legend()
    assert legend.get_window_extent(r).width < 0.5 * ax.get_window_extent(r).width
    assert _legend_clear_of_axes(ax)
    for text in legend.get_texts():
        for line in text.get_text().split("\n"):
            assert line.count("(") == line.count(")"), line  # a parenthesis whole on its line
            assert not line.startswith(("N/m", "m/s", "N·m")), line  # a value keeps its unit


@pytest.mark.parametrize("params", [dfa.Params(155.2, 0.00207, 2.03), dfa.Params(2.0, 0.4, 0.1)], ids=["one", "crowd"])
def test_report_nyquist_caption_names_an_inset_only_when_one_is_drawn(params):
    """The Delta's caption said "the inset zooms on the cycles when they crowd or lie below one tick" under a figure
    with no inset."""
    from types import SimpleNamespace

    from dfa.studies.design_figures import _nyquist

    res = limit_cycles(params, model="zoh")
    nyq = nyquist_locus_response(params, amplitudes=[c.amplitude for c in res.cycles[:3]], model="zoh", cycles=res)
    shown = []
    real = figures.nyquist_plot
    analysis = SimpleNamespace(nyquist=nyq, is_spring=True, covers=lambda what: True)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(figures, "nyquist_plot", lambda *a, **k: shown.append(real(*a, **k)) or shown[-1])
        caption = _nyquist(analysis).caption
    assert ("inset" in caption) == bool(shown[0].child_axes)
    assert bool(shown[0].child_axes) == (len(res.cycles) > 1)


#: Width of the documentation's text column in CSS pixels: the pydata theme's article at a 1440-px-wide window,
#: between its two sidebars (88rem page, 25 % and 17rem sidebars, 4rem of padding). A wider PNG is shrunk to it.
_DOCS_COLUMN_PX = 720.0


def test_fig3_legend_legible_at_the_docs_page_width():
    """Fig. 3 (examples/fig3_regions.py, saved at 130 dpi) was 1066 px wide with its legend beside the plane: shrunk
    to the docs' column its 9-pt legend read as 6 pt. The legend goes below the plane, and the figure is narrow
    enough that it reads as 8 pt or more."""
    r = dfa.passivity_criterion(beta=0.25, sigma=1.2, xi_dot=2.0)
    ax = figures.regions_plot(r, xi_dots=[0.5, 1.0, 5.0])
    fig = ax.figure
    fig.set_dpi(130)
    rend = _boxes(fig)
    width = fig.get_tightbbox(rend).width * 130  # inches × dpi: the PNG's width
    shrink = min(1.0, _DOCS_COLUMN_PX / width)
    legend = _legend_of(ax)
    assert min(t.get_fontsize() for t in legend.get_texts()) * shrink >= 8.0, (width, shrink)
    assert _legend_clear_of_axes(ax)
    page = fig.bbox
    box = legend.get_window_extent(rend)
    assert page.x0 <= box.x0 and box.x1 <= page.x1 and page.y0 <= box.y0  # on the page, not cut
