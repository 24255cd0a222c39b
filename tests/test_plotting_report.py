"""Plots (Figs. 3-7 and beyond), the design report and the example scripts."""

import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
import pytest

import dfa
from dfa.analysis.contours import contour_maps
from dfa.analysis.cycles import limit_cycles
from dfa.analysis.limits.closed_form import stiffness_response
from dfa.analysis.loop import nyquist_locus_response
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import simulate
from dfa.cli import main
from dfa.model.wall import Wall
from dfa.render import figures
from dfa.render.limits import spring_passive_text

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
UNIT = re.compile(
    r"\((–|encoder ticks|ticks|samples|s|m/s|N/m|rad/s|N·m/rad|force ticks per position tick|%|ticks per sample)\)"
)


def rendered(fig, tmp_path, name):
    path = tmp_path / f"{name}.png"
    fig.savefig(path, dpi=60)
    img = plt.imread(path)
    plt.close(fig)
    assert path.stat().st_size > 2000
    assert img.std() > 0.01  # not a blank image
    return img


def assert_units(ax):
    assert UNIT.search(ax.get_xlabel()), ax.get_xlabel()
    assert UNIT.search(ax.get_ylabel()), ax.get_ylabel()


def test_fig3_regions_plot(tmp_path):
    ax = figures.regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0), xi_dots=[1, 5])
    assert_units(ax)
    rendered(ax.figure, tmp_path, "regions")


def test_fig4_stability_map_plot(tmp_path):
    m = stability_map(100.0, [1.0, 5.0], grid=8, samples=2000, n_jobs=1, progress=False)
    axes = figures.stability_map_plot(m)
    assert len(axes) == 2
    for ax in axes:
        assert_units(ax)
    rendered(axes[0].figure, tmp_path, "map")


def test_fig5_trajectory_plot(tmp_path):
    ax = figures.trajectory_plot(simulate(100.0, 0.1, 0.9, 2.0, 1500), period=1e-3)
    assert_units(ax)
    ys = sorted(line.get_ydata()[0] for line in ax.get_lines()[1:])
    assert ys == [-1.0, 1.0]  # ±1 tick marked
    rendered(ax.figure, tmp_path, "traj")
    with pytest.raises(ValueError):
        figures.trajectory_plot(simulate(1.0, 0.1, 0.9, 2.0, 10, record=False))


def test_fig7_contour_plot(tmp_path):
    axes = figures.contour_plot(contour_maps(5.0, grid=30))
    for ax in axes:
        assert_units(ax)
    rendered(axes[0].figure, tmp_path, "contours")


def test_nyquist_and_stiffness_and_validation_plots(tmp_path):
    p = dfa.Params(2.0, 0.4, 0.1)
    res = limit_cycles(p)
    ax = figures.nyquist_plot(nyquist_locus_response(p, amplitudes=[1.0, 2.0], cycles=res))
    assert_units(ax)
    rendered(ax.figure, tmp_path, "nyquist")
    dev = dfa.get_device("Delta").device
    ax = figures.stiffness_plot(stiffness_response(dev, stiffness=14500.0))
    assert_units(ax)
    assert "N/m" in ax.get_ylabel() and "m/s" in ax.get_xlabel()
    rendered(ax.figure, tmp_path, "stiffness")


def test_stiffness_response_bad_input():
    with pytest.raises(dfa.DFAValueError, match="velocity"):
        stiffness_response(dfa.get_device("Delta").device, velocity=[0.0, 1.0])


@pytest.fixture(scope="module")
def report_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("report")
    assert (
        main(["report", "--device", "impulse", "--velocity", "0.05", "--out", str(out), "--format", "both", "--quiet"])
        == 0
    )
    return out


def test_report_has_every_section_and_figure(report_dir):
    md = (report_dir / "design_report_impulse-engine.md").read_text()
    for section in (
        "# Design report: Impulse Engine",
        "## How stiff may the wall be? (four ways",
        "## Device",
        "## Passivity and stiffness limits",
        "## Predicted limit cycles",
        "## How far to trust these predictions",
        "**Verdict.**",
    ):
        assert section in md
    figs = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", md)
    assert len(figs) == 6  # the stiffness-speed chart first (issue 14 §2), then the five of the analysis
    assert figs[0].endswith("_speed_chart.png")
    for f in figs:
        assert (report_dir / f).is_file()


def test_report_numbers_equal_the_api(report_dir):
    md = (report_dir / "design_report_impulse-engine.md").read_text()
    dev = dfa.get_device("impulse").device
    lim = dfa.stiffness_limits(dev, 0.05, 80.0)
    crit = dfa.device_criterion(dev, 80.0, 0.05)
    assert f"| K_max at this speed (eq. 11) | {lim.k_max:.5g} N/m |" in md
    assert (
        f"| exact linear bound of the sampled spring (all Jury conditions; Gil et al. where binding) | {lim.k_gil:.5g} N/m |"
        in md
    )
    assert f"{crit.critical_xi_dot:.4g} ticks/sample" in md
    assert f"region {crit.region}" in md
    g = dfa.analysis.cycles.growth_threshold(dev.params(80.0), dev, model="zoh", max_amplitude=5000.0)
    assert f"M_u = {g.amplitude:.4g} ticks" in md


def test_report_verdict_says_what_is_proven_and_names_speed_and_delay(report_dir):
    md = (report_dir / "design_report_impulse-engine.md").read_text()
    dev = dfa.get_device("impulse").device
    lim = dfa.stiffness_limits(dev, 0.05, 80.0)
    assert "**passive (proven: the energy cannot grow)**" in md
    assert (
        f"at 0.05 m/s with a computational delay of 0 samples the largest passive stiffness is {lim.k_max:.5g} N/m"
        in md
    )
    assert "| computational delay d | 0 samples |" in md
    assert "locally unstable" not in md and "globally unstable" not in md


def _verdict_text(dev, k, v, dl, crit, lim, v_sim):
    from types import SimpleNamespace

    from dfa.studies.design_document import verdict_text

    a = SimpleNamespace(
        device=dev,
        stiffness=k,
        velocity=v,
        delay=dl,
        criterion=crit,
        limits=lim,
        is_spring=True,
        covers=lambda what: True,
    )
    a.simulated_xi_dot, a.simulated_velocity = v_sim, None if v_sim is None else dev.velocity(v_sim)
    return verdict_text(a)


def test_report_verdict_for_a_stiffness_above_the_static_limit_and_with_delay():
    dev = dfa.get_device("Delta").device
    crit = dfa.device_criterion(dev, Wall.of(60000.0, delay=1), 0.1)
    lim = dfa.stiffness_limits(dev, 0.1, 60000.0, delay=1)
    text = _verdict_text(dev, 60000.0, 0.1, 1, crit, lim, None)
    assert f"**no passivity guarantee even at rest (K > 2c/Δ = {2 * dev.coulomb / dev.resolution:.5g} N/m)**" in text
    assert (
        f"At 0.1 m/s with a computational delay of 1 sample the largest passive stiffness is {lim.k_max:.5g} N/m"
        in text
    )
    assert spring_passive_text(lim).startswith(
        "none: no passivity guarantee even at rest"
    )  # formatted None before the fix
    crit = dfa.device_criterion(dev, Wall.of(20000.0, delay=1), 0.1)
    lim = dfa.stiffness_limits(dev, 0.1, 20000.0, delay=1)
    text = _verdict_text(dev, 20000.0, 0.1, 1, crit, lim, None)
    assert "**not proven passive (the criterion gives no guarantee; that is not a proof of instability)**" in text


def test_report_html_is_self_contained(report_dir):
    html = (report_dir / "design_report_impulse-engine.html").read_text()
    assert html.count("data:image/png;base64,") == 6
    assert not re.search(r'src="(?!data:)', html)
    assert "<table>" in html and "Impulse Engine" in html


def test_report_bad_input(capsys, tmp_path):
    assert main(["report", "--device", "re35", "--out", str(tmp_path)]) == 2
    assert "stiffness" in capsys.readouterr().err
    assert main(["report", "--out", str(tmp_path / "missing" / "dir")]) == 2
    assert "does not exist" in capsys.readouterr().err


EXAMPLES = [
    "table2_devices",
    "fig3_regions",
    "fig4_stability_maps",
    "fig5_trajectories",
    "fig7_contours",
    "nyquist",
    "design_stiffness",
]


@pytest.mark.parametrize("name", EXAMPLES)
def test_example_script_runs_and_writes_its_output(name, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    proc = subprocess.run(
        [sys.executable, os.path.join(ROOT, "examples", f"{name}.py"), "--out", str(tmp_path), "--quick"],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    produced = list(tmp_path.iterdir())
    assert produced and all(p.stat().st_size > 0 for p in produced)
    if name != "table2_devices":
        assert any(p.suffix == ".png" for p in produced)


def test_examples_cover_every_paper_figure_and_table():
    have = set(os.listdir(os.path.join(ROOT, "examples")))
    for name in EXAMPLES:
        assert f"{name}.py" in have
