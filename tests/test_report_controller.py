"""The design report with a wall controller (issue 15, "Command line": "the report shows the controller and its Z-width").

Through ``dfa.cli.main``: the controller, its groups and the extended criterion's verdict in the Markdown and the JSON
are what `dfa check` with the same flags prints; with an amplifier lag the check is "not covered"; the Z-width
section is computed with the controller and its linear boundary is the exact linear bound
(:func:`dfa.analysis.linear_wall.stable_stiffness`) at each B; bad controller input is one line and exit 2; every null
of the JSON has a reason. The spring report is unchanged: its analysis equals, key by key and byte by byte in the
Markdown, a golden recorded from the code before controllers reached the report (commit 4b5ad71).
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import json
import re
from pathlib import Path

import pytest
from cli_text import unwrap
from fixed_keywords import fixed_keywords
from result_json import written
from test_cli_json_null_reasons import unexplained_nulls

import dfa
import dfa.analysis.limits.kmax
import dfa.studies.design
import dfa.studies.design_figures as figures
import dfa.studies.report
from dfa.analysis.linear_wall import stable_stiffness
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.jsonable import dumps
from dfa.model.wall import Wall, WallParams
from dfa.studies.design import design_analysis
from dfa.studies.design_document import design_markdown

SMALL = dict(map_grid=5, samples=3000, n_jobs=1)  # a small map: the numbers of the text do not depend on it
GOLDEN = Path(__file__).resolve().parent / "golden"
DELTA = ["--device", "delta", "--velocity", "0.05"]
B1 = [*DELTA, "--virtual-damping", "1"]
CTL = [*B1, "--velocity-filter", "200", "--delay", "1"]  # damper, filter and delay: proven passive at 0.05 m/s
LAG = [*B1, "--amplifier-bandwidth", "300"]
NAMES = ("speed_chart", "regions", "stiffness", "nyquist", "trajectories", "map", "zwidth")


def _stub(name: str):
    return lambda a: figures.ReportFigure(name, f"caption of {name}", b"\x89PNG stub")


@contextlib.contextmanager
def small_reports():
    """`dfa report` with a small stability map and placeholder figures (drawing takes seconds)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(dfa.studies.report, "design_analysis", fixed_keywords(design_analysis, **SMALL))
        mp.setattr(figures, "FIGURES", tuple(_stub(n) for n in NAMES))
        yield mp


def call(*argv: str) -> tuple[int, str]:
    """``main(argv)`` with its standard output."""
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main(list(argv))
    return code, buf.getvalue()


def run(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def report(out_dir: Path, *argv: str) -> tuple[dict, str]:
    """The report's JSON (``--json``) and its Markdown text."""
    code, out = call("report", *argv, "--out", str(out_dir), "--format", "md", "--json")
    assert code == 0
    data = json.loads(out)
    return data, Path(data["paths"][0]).read_text(encoding="utf-8")


def _case(tmp: Path, flags: list[str], extra: tuple[str, ...] = ()) -> dict:
    """One controller case: `dfa check` (text and JSON), `dfa stiffness --json` and the report (JSON, Markdown).

    The Z-width's grid asked for is recorded (``grids``) and run at 4 points per axis.
    """
    grids: list[int] = []
    real = dfa.studies.design.z_width
    with small_reports() as mp:
        mp.setattr(
            dfa.studies.design, "z_width", lambda *a, **kw: grids.append(kw["grid"]) or real(*a, **{**kw, "grid": 4})
        )
        data, md = report(tmp, *flags, *extra)
    return dict(
        grids=grids,
        check_text=unwrap(call("check", *flags)[1]),  # rows whole, as the report writes them
        check=json.loads(call("check", *flags, "--json")[1]),
        stiffness=json.loads(call("stiffness", *flags, "--json")[1]),
        data=data,
        md=md,
    )


@pytest.fixture(scope="module")
def ctl(tmp_path_factory):
    return _case(tmp_path_factory.mktemp("ctl"), CTL)


@pytest.fixture(scope="module")
def lag(tmp_path_factory):
    return _case(tmp_path_factory.mktemp("lag"), LAG, ("--zwidth", "0"))  # no Z-width asked for


def check_table(text: str) -> list[tuple[str, str]]:
    """(label, value) rows of `dfa check` text output (after the device and controller lines)."""
    rows = [re.split(r"\s{2,}", line, maxsplit=1) for line in text.splitlines()[2:]]
    return [(a, b) for a, b in rows]


def md_row(label: str, value: str) -> str:
    esc = lambda s: s.replace("|", "\\|")
    return f"| {esc(label)} | {esc(value)} |"


# ------------------------------------------------------------------ the numbers users read, as `dfa check` prints them
def test_controller_report_states_what_dfa_check_prints(ctl):
    text, check, data, md = ctl["check_text"], ctl["check"], ctl["data"], ctl["md"]
    line = text.splitlines()[1]
    assert line.startswith("controller: ") and "ν_c = f_c·T = 0.06667" in line and line in md.splitlines()
    rows = check_table(text)
    assert len(rows) == 12 and rows[6][0] == "passive" and rows[6][1].startswith("yes: ")
    fresh = dfa.analysis.criterion.start_state(WallParams.of(damping=0.2, delay=1, cutoff=0.05))  # d, B, filter
    assert rows[7] == ("start state", fresh) and "the pending command equals the first" in fresh and "filter's" in fresh
    for label, value in rows:
        assert md_row(label, value) in md, label
    a = data["analysis"]
    # dfa check states the physical controller once (its "controller"); the analysis keeps the criterion's groups
    assert {k: v for k, v in a["check"].items() if k != "wall"} == {k: v for k, v in check.items() if k != "wall"}
    assert data["numbers"]["wall"] == check["wall"]
    assert data["numbers"]["wall"]["dimensionless"]["damping"] == pytest.approx(1.0 / (14500.0 / 3000.0))
    assert data["numbers"]["passive"] is True and data["numbers"]["region"] == check["criterion"]["region"]
    assert data["numbers"]["critical_xi_dot"] == check["criterion"]["critical_xi_dot"]
    verdict = md.splitlines()[2]  # the verdict paragraph says the same
    assert (
        "**passive (proven: the energy cannot grow, for a wall whose memory is fresh at t = 0)** by the criterion of eq. 6 extended"
        in verdict
    )
    assert f"up to {check['criterion']['critical_velocity']:.4g} m/s" in verdict


def test_controller_report_kmax_equals_dfa_stiffness(ctl):
    data, md, stiff = ctl["data"], ctl["md"], ctl["stiffness"]
    lim = data["analysis"]["design_answer"]
    for key in ("k_criterion", "k_linear", "k_df", "k_sim", "k_sim_rest"):
        assert lim[key] == stiff[key], key
        if lim[key]["value"] is None:  # every null of the record is stated with its reason
            assert lim[key]["null_reasons"]["/value"] in md
    kc, kl = stiff["k_criterion"]["value"], stiff["k_linear"]["value"]
    assert data["numbers"]["k_max"] == kc and data["numbers"]["k_linear"] == kl
    label = "criterion K_max at this speed (eq. 11 extended to the wall)"
    assert md_row(label, f"{kc:.5g} N/m") in md
    assert f"{kl:.5g} N/m" in md
    for key, label in (
        ("k_df", "describing function: largest K with growth speed >= V"),
        ("k_sim", "simulation: largest K, no simulated impact up to V diverges"),
        ("k_sim_rest", "simulation: largest K, every simulated impact up to V rests"),
    ):  # the searched limits read as in `dfa stiffness`: the number with its unit, never a raw record
        row = next(line for line in md.splitlines() if line.startswith(f"| {label} |"))
        v = stiff[key]["value"]
        value = "none:" if v is None else f"| {v:.5g} N/m"
        assert value in row and "{'" not in row, row
    from dfa.render.limits import evidence_text

    ans = dfa.analysis.limits.kmax.design_answer(
        dfa.get_device("delta").device, data["analysis"]["velocity"], wall=Wall.of(14500.0, 1.0, 1, 200.0)
    )  # the report's own answer (without `dfa stiffness`'s assessment of K)
    assert lim["evidence"] == json.loads(dumps(ans.to_dict()))["evidence"]
    assert md_row("evidence", evidence_text(ans)) not in md  # below the table, not in a cell (issue 26 §4)
    assert f"- **Simulations run:** {evidence_text(ans)}." in md.split("| status |", 1)[1]
    assert "{'" not in md and "not available (" not in md


def test_controller_report_with_lag_is_not_covered(lag):
    check, data, md = lag["check"], lag["data"], lag["md"]
    assert check["status"] == "not_covered" and check["passive"] is None
    a = data["analysis"]
    assert {k: v for k, v in a["check"].items() if k != "wall"} == {k: v for k, v in check.items() if k != "wall"}
    kc = a["design_answer"]["k_criterion"]
    assert kc["value"] is None and kc["status"] == "not_covered"
    assert "amplifier lag" in kc["null_reasons"]["/value"]
    assert data["numbers"]["passive"] is None and "/passive" in data["numbers"]["null_reasons"]
    section = md.split("## Passivity with the controller")[1].split("\n## ")[0]
    assert "not covered by the criterion" in section and "(proven)" not in section and "yes:" not in section
    for label, value in check_table(lag["check_text"]):
        assert md_row(label, value) in section
    assert "**not covered by the criterion" in md.splitlines()[2]  # the verdict
    assert "α = τ_a/T = 1.592" in md and "not covered" in md.split("## How far to trust")[1]


def test_controller_report_leaves_out_the_spring_only_sections(ctl):
    a, md = ctl["data"]["analysis"], ctl["md"]
    for key in ("limits", "speed_chart"):  # the spring's closed forms and chart
        assert a.get(key) is None and "not this wall's" in a["null_reasons"][f"/{key}"]
    assert a["criterion"] == a["check"]["criterion"] and a["design_answer"]["wall"]["damping"] == 1.0
    assert "## Passivity and stiffness limits" not in md and "How stiff may the wall be? (four ways" not in md
    assert "Not in this report: the criterion of eq. 6 for the bare spring" in md
    assert "caption of stiffness" not in md and "caption of speed_chart" not in md
    # the regions figure is the extended criterion's (it covers a damper, filter and delay), in the controller's section
    assert md.index("caption of regions") > md.index("## Passivity with the controller")
    assert "## Predicted limit cycles (describing function, eq. 36–41) with the controller" in md
    # the sections that accept a controller are computed with it
    dev = dfa.get_device("delta").device
    cp = Wall.of(14500.0, 1.0, 1, 200.0).params(dev.period)
    assert a["stability_map"]["wall"] == written(cp.to_dict()) and a["delay"] == 1
    p = dev.params(14500.0)
    g = dfa.growth_threshold(p, model="zoh", wall=cp)
    assert a["growth_thresholds"]["zoh"]["amplitude"] == written(g.amplitude)
    xi = a["check"]["criterion"]["xi_dot"]
    bound = dfa.analysis.simulation.divergence_bound(0.0, xi, p.mu)
    sim = dfa.simulate(p.mu, p.beta, p.sigma, xi, None, record=False, bound=bound, wall=cp)
    assert a["outcome"]["outcome"] == sim.outcome.value and a["outcome"]["samples_run"] == sim.samples_run


# ------------------------------------------------------------------ the Z-width of the controller
def test_controller_report_zwidth_linear_boundary_is_the_exact_bound(ctl):
    z, md = ctl["data"]["analysis"]["zwidth"], ctl["md"]
    assert z["wall"]["filter_cutoff"] == 200.0 and z["delay"] == 1 and z["wall"]["amplifier_bandwidth"] is None
    dev = dfa.get_device("delta").device
    lin = z["boundaries"]["linear"]
    assert sum(k is not None for k in lin) >= 2
    for b, k in zip(z["damping"], lin, strict=True):
        if k is not None:
            exact = stable_stiffness(dev.mass, dev.damping, dev.period, Wall.of(1.0, b, 1, 200.0)).k_crit
            assert k == pytest.approx(exact, rel=1e-11)  # JSON: 12 digits
    assert "## Z-width: stiffness against virtual damping" in md and "the star in the figure is the design point" in md


def test_controller_zwidth_on_by_default_and_can_be_turned_off(ctl, lag):
    """With a controller the report has a 16 x 16 Z-width unless asked otherwise (0: none)."""
    assert ctl["grids"] == [dfa.studies.design.WALL_ZWIDTH_GRID] == [16] and ctl["data"]["analysis"]["zwidth"]
    a = lag["data"]["analysis"]
    assert lag["grids"] == [] and a["zwidth"] is None and "## Z-width" not in lag["md"]
    assert "zwidth_grid=0" in a["null_reasons"]["/zwidth"]


def test_controller_report_html_self_contained_with_its_figures(tmp_path, monkeypatch):
    """Real figures: the five that take the controller (the extended criterion's regions, Nyquist, trajectories, map,
    Z-width), embedded; no spring-only figure, no PNG file."""
    monkeypatch.setattr(dfa.studies.report, "design_analysis", fixed_keywords(design_analysis, **SMALL))
    code, _ = call("report", *B1, "--zwidth", "3", "--out", str(tmp_path), "--format", "html")
    assert code == 0
    page = (tmp_path / "design_report_delta_controller.html").read_text(encoding="utf-8")
    assert page.count("data:image/png;base64,") == 5  # regions, Nyquist, trajectories, map, Z-width
    assert not list(tmp_path.glob("**/*.png")) and "<h2>Wall controller</h2>" in page


# ------------------------------------------------------------------ files: never the spring report's
def test_controller_report_never_overwrites_the_spring_report(capsys, tmp_path):
    spring = {n: f"# Design report: Delta\n{n}\n" for n in ("design_report_delta.md", "design_report_delta.json")}
    for name, text in spring.items():  # a spring report of the device in the folder
        (tmp_path / name).write_text(text, encoding="utf-8")
    with small_reports():
        code, _, err = run(capsys, "report", *B1, "--zwidth", "3", "--out", str(tmp_path), "--format", "md")
        assert code == 0, err
        assert {n: (tmp_path / n).read_text(encoding="utf-8") for n in spring} == spring
        assert (tmp_path / "design_report_delta_controller.md").is_file()
        # another controller in the way: refused before any analysis (one line, exit 2)
        other = [*DELTA, "--virtual-damping", "2", "--out", str(tmp_path), "--format", "md"]
        code, out, err = run(capsys, "report", *other)
    assert code == 2 and out == "" and err.count("\n") == 1 and "controller B = 1.0" in err and "--force" in err


# ------------------------------------------------------------------ bad input
ERRORS = [
    ([*DELTA, "--virtual-damping", "-1"], "B must be >= 0"),
    ([*B1, "--velocity-filter", "1600"], "Nyquist frequency 1500 Hz"),
    ([*B1, "--amplifier-bandwidth", "0"], "--amplifier-bandwidth 0 is invalid"),
    ([*B1, "--zwidth", "-1"], "--zwidth -1 is invalid"),
    ([*B1, "--delay", "0.5"], "--delay"),
    (
        [
            "--mass",
            "0.05",
            "--damping",
            "0",
            "--coulomb",
            "0.02",
            "--resolution",
            "2e-5",
            "--period",
            "0.001",
            "--velocity",
            "0.1",
            "--virtual-damping",
            "1",
        ],
        "missing --stiffness",
    ),  # fmt: skip
]


@pytest.mark.parametrize("argv, text", ERRORS)
def test_controller_report_bad_input_is_one_line_exit_2(capsys, tmp_path, argv, text):
    code, out, err = run(capsys, "report", *argv, "--out", str(tmp_path / "r"))
    assert code == 2 and out == ""
    assert text in err and err.count("\n") == 1 and "Traceback" not in err


def test_design_analysis_takes_k_and_the_delay_from_the_wall_only():
    """One place for K and the delay: the wall (the "must match" checks of stiffness= and delay= are gone)."""
    e = dfa.get_device("delta")
    with pytest.raises(TypeError, match="controller"):
        design_analysis(e, 1000.0, controller=Wall.of(14500.0, 1.0))  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="delay"):
        design_analysis(e, delay=2)  # type: ignore[call-arg]
    with pytest.raises(DFAValueError, match="filter_cutoff"):
        design_analysis(e, Wall.of(14500.0, 1.0, filter_cutoff=1e6))  # above Nyquist: refused before any work


# ------------------------------------------------------------------ null reasons
@pytest.mark.parametrize("case", ["ctl", "lag"])
def test_controller_report_json_every_null_has_a_reason(case, request):
    data = request.getfixturevalue(case)["data"]
    assert unexplained_nulls(data) == []


# ------------------------------------------------------------------ the spring report is unchanged
def test_spring_report_unchanged_golden_from_before_the_controller():
    """Impulse Engine at 0.05 m/s (small map): JSON key by key (floats to 1e-9) and Markdown byte for byte.

    Recorded from commit 4b5ad71 (before the report took a controller); a pure-spring Wall gives the same. The
    grip section (issue 28, added later) is removed before comparing; the start state's row (issue 28 §1, added
    later) is written into the recorded Markdown; everything else is as recorded.
    """
    spec = importlib.util.spec_from_file_location("dfa_make_golden", GOLDEN / "make_golden.py")
    assert spec is not None and spec.loader is not None
    golden = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(golden)
    old = json.loads((GOLDEN / "design_analysis_impulse_small.json").read_text(encoding="utf-8"))
    old_md = (GOLDEN / "design_analysis_impulse_small.md").read_text(encoding="utf-8")
    e = dfa.get_device("impulse")
    for wall in (None, Wall.of(e.stiffness)):  # the pure spring as a Wall is the spring
        a = design_analysis(e, wall, velocity=0.05, **SMALL)
        new = json.loads(dumps(a.to_dict(), ensure_ascii=False))
        assert new.pop("grip")["needs"][0]["method"] == "criterion"
        assert set(new) == set(old) and golden.compare_json(old, new) == []
        md = design_markdown(a, {n: f"caption of {n}" for n in NAMES}, lambda n: f"figures/{n}.png")
        head, grip = md.split("## How firm a grip does the wall need?\n\n")
        assert head + grip[grip.index("## ") :] == old_md


def test_fig6_nyquist_cycle_marks_lie_on_the_locus_with_a_controller():
    """The report's Nyquist figure marks each cycle at L(jω; M) of the loop drawn, with its controller: on −1/D(M).

    (Before, the mark was the spring's L, off the controller's curve.)
    """
    from dfa.analysis.loop import nyquist_locus_response, quantizer_df

    dev = dfa.get_device("impulse").device
    cp = Wall.of(80.0, 0.05, 1, 100.0, 200.0).params(dev.period)
    p = dev.params(80.0)
    res = dfa.limit_cycles(p, model="zoh", wall=cp)
    assert res.cycles
    ny = nyquist_locus_response(p, amplitudes=[c.amplitude for c in res.cycles], model="zoh", wall=cp, cycles=res)
    assert len(ny.cycle_marks) == len(res.cycles)
    for mark in ny.cycle_marks:
        assert abs(mark.point - (-1.0 / quantizer_df(mark.amplitude))) <= 1e-8


def test_fig6_nyquist_title_names_the_controller(monkeypatch):
    """The report's Nyquist figure names its controller in the title (as its caption does), the spring's does not."""
    from dfa.render.figures import MODEL_NAMES

    titles: list[str] = []

    def keep_title(fig):
        titles.append(fig.axes[0].get_title())
        return b""

    monkeypatch.setattr(figures, "_png", keep_title)
    entry = dfa.get_device("delta")
    ctl = Wall.of(entry.stiffness, 1.0, 1, 200.0)
    a = design_analysis(entry, ctl, velocity=0.05, zwidth_grid=0, **SMALL)
    fig = figures._nyquist(a)
    loop = f"Nyquist, {MODEL_NAMES[a.nyquist.model]} loop"
    assert titles[-1] == f"{loop} with B = 1 N·s/m, f_c = 200 Hz, d = 1"
    assert "with the wall controller (β_B = " in fig.caption  # the caption names it too (dimensionless)
    lag = Wall.of(entry.stiffness, 0.5, 0, None, 300.0)
    figures._nyquist(design_analysis(entry, lag, velocity=0.05, zwidth_grid=0, **SMALL))
    assert titles[-1] == f"{loop} with B = 0.5 N·s/m, f_bw = 300 Hz, d = 0"
    figures._nyquist(design_analysis(entry, Wall.of(entry.stiffness, delay=1), velocity=0.05, **SMALL))
    assert titles[-1] == f"{loop}, delay 1"
