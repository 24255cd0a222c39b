"""Compute, then render (issue 13 §1, issue 14 §4): DesignAnalysis, the rendering layer and the report files."""

from __future__ import annotations

import json
import math
import re

import pytest
from fixed_keywords import fixed_keywords
from result_json import assert_json_from_fields, written

import dfa
import dfa.studies.report
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.studies.design import design_analysis
from dfa.studies.design_document import design_markdown, markdown_to_html

SMALL = dict(map_grid=5, samples=3000, n_jobs=1)  # a small map: the numbers of the text do not depend on it


@pytest.fixture(scope="module")
def impulse():
    return design_analysis(dfa.get_device("impulse"), velocity=0.05, **SMALL)


@pytest.fixture
def small_reports(monkeypatch):
    """`dfa report` with a small stability map (the CLI path is unchanged otherwise)."""
    monkeypatch.setattr(dfa.studies.report, "design_analysis", fixed_keywords(design_analysis, **SMALL))


@pytest.fixture
def no_figures(monkeypatch, small_reports):
    """Placeholder figures (for tests of the text and the files only): drawing takes seconds."""
    import dfa.studies.design_figures as figures

    stub = lambda name: lambda a: figures.ReportFigure(name, f"caption of {name}", b"\x89PNG stub")
    monkeypatch.setattr(
        figures,
        "FIGURES",
        tuple(stub(n) for n in ("speed_chart", "regions", "stiffness", "nyquist", "trajectories", "map")),
    )


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


# ----------------------------------------------------------------- the analysis
def test_design_analysis_numbers_equal_the_api(impulse):
    dev = dfa.get_device("impulse").device
    assert impulse.stiffness == 80.0 and impulse.velocity == 0.05 and impulse.delay == 0
    assert impulse.criterion == dfa.device_criterion(dev, 80.0, 0.05)
    assert impulse.limits.k_max == dfa.stiffness_limits(dev, 0.05, 80.0).k_max
    p = dev.params(80.0)
    g = dfa.growth_threshold(p, dev, model="zoh")
    assert impulse.threshold("zoh").amplitude == g.amplitude
    assert impulse.outcome.outcome == dfa.simulate(p.mu, p.beta, p.sigma, impulse.criterion.xi_dot).outcome


def test_design_analysis_is_frozen_and_json_able(impulse):
    with pytest.raises(AttributeError):
        impulse.stiffness = 1.0  # type: ignore[misc]
    d = json.loads(dfa.jsonable.dumps(impulse.to_dict(), ensure_ascii=False))
    assert d["limits"]["k_max"] == written(impulse.limits.k_max)
    assert d["criterion"]["passive"] is True and d["status"] == "ok"
    assert set(d["growth_thresholds"]) == {"half-delay", "zoh"}


def test_design_analysis_validates_on_construction(impulse):
    from dataclasses import replace

    with pytest.raises(DFAValueError, match="thresholds"):
        replace(impulse, thresholds=impulse.thresholds[:1])
    with pytest.raises(DFAValueError, match="status"):
        replace(impulse, status="maybe")
    with pytest.raises(dfa.DFATypeError, match="wall"):
        replace(impulse, wall=-1.0)  # K and the delay are the wall's (a Wall checks them where it is built)
    with pytest.raises(DFAValueError, match="velocity"):
        replace(impulse, velocity=-0.1)
    with pytest.raises(DFAValueError, match="stiffness"):
        dfa.Wall(-1.0)


def test_design_analysis_bad_input_names_the_parameter():
    with pytest.raises(DFAValueError, match="wall = None .*the catalogue gives no K"):
        design_analysis(dfa.get_device("re35"))
    with pytest.raises(DFAValueError, match="validation lacks"):
        design_analysis(dfa.get_device("impulse"), validation={"quick": True}, **SMALL)
    with pytest.raises(dfa.DFATypeError, match="validation"):
        design_analysis(dfa.get_device("impulse"), validation=[1], **SMALL)  # type: ignore[arg-type]


# ------------------------------------------------------------------ rendering
def test_markdown_to_html_keeps_products_literal_and_nests_emphasis():
    page = markdown_to_html("K = 2 * c / Δ and b * T; **bold *nested***; a_b_c", "t")
    assert "2 * c / Δ and b * T" in page and "<em> c" not in page
    assert "<strong>bold <em>nested</em></strong>" in page
    assert "a_b_c" in page


def test_markdown_to_html_escapes_raw_html_and_renders_tables():
    page = markdown_to_html("<script>x</script>\n\n| a | b |\n|---|---|\n| 1 | 2 |\n", "<t>")
    assert "<script>" not in page and "&lt;script&gt;" in page
    assert "<table>" in page and "<td>1</td>" in page and "<title>&lt;t&gt;</title>" in page


def test_markdown_of_a_device_named_like_markup_stays_text(impulse):
    from dataclasses import replace

    dev = replace(impulse.device, name="pen <b>*2*</b> | x")
    md = design_markdown(
        replace(impulse, device=dev),
        {n: n for n in ("speed_chart", "regions", "stiffness", "nyquist", "trajectories", "map")},
        str,
    )
    html = markdown_to_html(md, "t")
    assert "<b>" not in html and "&lt;b&gt;" in html


def test_report_says_your_source_prints_for_a_device_files_printed_values(impulse, tmp_path):
    """The paper's printed (μ, β, σ) are "Paper Table 2 prints" only for the catalogue's own row: a device file's
    are its source's ("your source prints"), and a device made from `dfa devices --template` by changing the
    physical values carries neither the Delta's printed values nor its notes."""
    from dataclasses import replace

    from dfa.model.catalogue import device_template, load_device_file
    from dfa.studies.design import _catalogue_notes

    names = {n: n for n in ("speed_chart", "regions", "stiffness", "nyquist", "trajectories", "map")}

    def report(entry):
        return design_markdown(replace(impulse, catalogue=_catalogue_notes(entry)), names, str)

    own = report(dfa.get_device("impulse"))
    assert "Paper Table 2 prints μ = 100.78, β = 0.13, σ = 0.97; the recomputed values agree." in own
    path = tmp_path / "mine.toml"
    path.write_text(device_template().replace("mass = 0.25", "mass = 0.12"), encoding="utf-8")
    mine = report(load_device_file(str(path)))
    assert "Table 2" not in mine and "prints μ" not in mine and "Force Dimension Delta" not in mine
    mu = 0.12 / (14500.0 * (1 / 3000) ** 2)  # μ = m/(K T²) of the changed mass
    path.write_text(
        device_template().replace("mass = 0.25", "mass = 0.12").replace("# printed = ", "printed = "), encoding="utf-8"
    )
    text = " ".join(report(load_device_file(str(path))).split())
    assert "Paper Table 2" not in text and "Your source prints μ = 155.2, β = 0.002, σ = 2.03" in text
    assert f"mu: printed 155.2, recomputed {mu:.4g}" in text


def test_report_of_a_rotary_device_says_inertia_not_mass(tmp_path, capsys, no_figures):
    code, out, err = run(capsys, "report", "--device", "re35", "--stiffness", "0.5", "--velocity", "1",
                         "--out", str(tmp_path), "--format", "md", "--quiet")  # fmt: skip
    assert code == 0, err
    md = (tmp_path / "design_report_re35-testbed.md").read_text()
    assert "| inertia J | 6.28e-06 kg·m² |" in md and "| mass m |" not in md


# --------------------------------------------------------------- report files
def test_report_html_only_writes_no_png_and_embeds_every_figure(tmp_path, capsys, small_reports):
    code, out, err = run(
        capsys, "report", "--device", "impulse", "--velocity", "0.05", "--out", str(tmp_path), "--quiet"
    )
    assert code == 0, err
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        "design_report_impulse-engine.html",
        "design_report_impulse-engine.json",
    ]
    html = (tmp_path / "design_report_impulse-engine.html").read_text()
    assert html.count('src="data:image/png;base64,') == 6 and not re.search(r'src="(?!data:)', html)


def test_report_never_reads_a_stray_validation_json(tmp_path, capsys, no_figures):
    (tmp_path / "validation").mkdir()
    stray = {"soundness_violations": 99, "soundness_passive": 100, "conservatism": 0.5, "speed_df_median_error": 0.1,
             "short_period_frequency_error": 0.3}  # fmt: skip
    (tmp_path / "validation" / "validation.json").write_text(json.dumps(stray))
    assert run(capsys, "report", "--device", "impulse", "--out", str(tmp_path), "--format", "md", "--quiet")[0] == 0
    md = (tmp_path / "design_report_impulse-engine.md").read_text()
    assert "Across the validation set" not in md and "99 of 100" not in md
    # passed in explicitly, it is stated
    code, out, err = run(capsys, "report", "--device", "impulse", "--out", str(tmp_path), "--format", "md", "--quiet",
                         "--validation", str(tmp_path / "validation" / "validation.json"))  # fmt: skip
    assert code == 0, err
    md = (tmp_path / "design_report_impulse-engine.md").read_text()
    assert "99 of 100 points the criterion calls passive" in md and "median 10 %" in md


def test_report_validation_file_errors_are_one_line(tmp_path, capsys):
    (tmp_path / "bad.json").write_text("{nope")
    (tmp_path / "other.json").write_text("[1]")
    for arg, needle in (
        ("missing.json", "cannot be read"),
        ("bad.json", "not JSON"),
        ("other.json", "not a validation"),
    ):
        code, out, err = run(
            capsys, "report", "--device", "impulse", "--out", str(tmp_path), "--validation", str(tmp_path / arg)
        )
        assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and needle in err


def test_report_json_prints_one_object_with_paths_and_numbers(tmp_path, capsys, small_reports):
    out_dir = tmp_path / "new"
    code, out, err = run(capsys, "report", "--device", "impulse", "--velocity", "0.05", "--out", str(out_dir),
                         "--format", "both", "--quiet", "--json")  # fmt: skip
    assert code == 0, err
    d = json.loads(out)
    assert out_dir.is_dir()  # --out DIR is created
    assert [p.rsplit("/", 1)[-1] for p in d["paths"]] == [
        "design_report_impulse-engine.md", "design_report_impulse-engine.html", "design_report_impulse-engine.json"
    ]  # fmt: skip
    assert len(d["figures"]) == 6 and all(
        (out_dir / "figures").joinpath(p.rsplit("/", 1)[-1]).is_file() for p in d["figures"]
    )
    lim = dfa.stiffness_limits(dfa.get_device("impulse").device, 0.05, 80.0)
    assert d["numbers"]["k_max"] == written(lim.k_max)
    assert d["analysis"]["limits"]["k_gil"] == pytest.approx(lim.k_gil, rel=1e-12)
    on_disk = json.loads((out_dir / "design_report_impulse-engine.json").read_text())
    assert on_disk["numbers"] == d["numbers"] and on_disk["identity"]["velocity"] == 0.05


def test_report_refuses_to_overwrite_another_speed_or_device_unless_forced(tmp_path, capsys, no_figures):
    base = ["report", "--device", "re35", "--stiffness", "0.5", "--out", str(tmp_path), "--format", "md", "--quiet"]
    assert run(capsys, *base, "--velocity", "1")[0] == 0
    assert run(capsys, *base, "--velocity", "1")[0] == 0  # the same report again: replaced
    before = (tmp_path / "design_report_re35-testbed.md").read_text()
    code, out, err = run(capsys, *base, "--velocity", "2")
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1
    assert "would be overwritten" in err and "--force" in err and "--name" in err
    assert (tmp_path / "design_report_re35-testbed.md").read_text() == before
    assert run(capsys, *base, "--velocity", "2", "--force")[0] == 0
    assert "impact speed of 2 rad/s" in (tmp_path / "design_report_re35-testbed.md").read_text()


def test_report_refuses_a_legacy_report_of_another_device(tmp_path, capsys):
    (tmp_path / "design_report_custom-device.md").write_text("# Design report: Delta\n")
    custom = ["--mass", "0.05", "--damping", "0.01", "--coulomb", "0.02", "--resolution", "2e-5", "--period", "0.001"]
    code, out, err = run(capsys, "report", *custom, "--stiffness", "500", "--out", str(tmp_path), "--format", "md")
    assert code == 2 and "another device" in err


def test_report_name_sets_the_file_names(tmp_path, capsys, no_figures):
    custom = ["--mass", "0.05", "--damping", "0.01", "--coulomb", "0.02", "--resolution", "2e-5", "--period", "0.001"]
    code, out, err = run(capsys, "report", *custom, "--stiffness", "500", "--name", "My pen #2", "--out", str(tmp_path),
                         "--format", "md", "--quiet")  # fmt: skip
    assert code == 0, err
    assert (tmp_path / "design_report_my-pen-2.md").read_text().startswith("# Design report: My pen #2\n")
    assert sorted(p.name for p in (tmp_path / "figures").iterdir())[0].startswith("my-pen-2_")


# ------------------------------------------------------------ device options
def test_resolve_device_counts_per_revolution_and_per_metre():
    rot = dfa.resolve_device("re35", counts=2000, stiffness=0.5)
    assert rot.device.resolution == pytest.approx(2 * math.pi / 2000, rel=1e-15) and rot.device.rotary
    assert rot.entry is None  # an override makes it a custom device
    lin = dfa.resolve_device("phantom", counts=50_000)
    assert lin.device.resolution == pytest.approx(2e-5, rel=1e-15) and lin.stiffness == 1015.0
    assert dfa.resolve_device("phantom").entry is dfa.get_device("phantom")


@pytest.mark.parametrize(
    "kwargs, needle",
    [
        (dict(counts=0), "counts 0 is invalid"),
        (dict(counts=2000, overrides={"resolution": 1e-5}), "cannot both be given"),
        (dict(overrides={"mass": -1.0}), "mass"),
        (dict(overrides={"inertia": 1.0}), "physical values are"),
        (dict(counts=2.5), "whole number"),
    ],
)
def test_resolve_device_errors_name_the_input(kwargs, needle):
    with pytest.raises((DFAValueError, dfa.DFATypeError), match=needle):
        dfa.resolve_device("phantom", **kwargs)


def test_cli_counts_rotary_equals_the_resolution_by_hand(capsys):
    base = ["params", "--mass", "6.28e-6", "--damping", "9e-5", "--coulomb", "0.02", "--period", "0.001", "--rotary",
            "--stiffness", "0.5", "--json"]  # fmt: skip
    by_counts = json.loads(run(capsys, *base, "--counts", "8192")[1])
    by_hand = json.loads(run(capsys, *base, "--resolution", repr(2 * math.pi / 8192))[1])
    assert by_counts == pytest.approx(by_hand, rel=1e-15)


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["params", "--device", "phantom", "--counts", "0"], "--counts 0 is invalid"),
        (["params", "--device", "phantom", "--counts", "1000", "--resolution", "1e-5"], "cannot both be given"),
        (["params", "--device", "phantom", "--counts", "1.5"], "--counts"),
        (["params", "--device", "phantom", "--name", "  "], "--name"),
        (["params", "--mu", "1", "--beta", "0.1", "--sigma", "1", "--name", "x"], "cannot be combined with --name"),
        (["report", "--device", "impulse", "--format", "pdf"], "invalid choice"),
        (["report", "--device", "impulse", "--out", "/nonexistent-parent/x"], "does not exist"),
    ],
)
def test_cli_device_option_errors_are_one_line_exit_2(capsys, argv, needle):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == "" and len(err.strip().splitlines()) == 1 and needle in err, err


def test_cli_name_labels_the_output(capsys):
    code, out, err = run(capsys, "params", "--device", "phantom", "--name", "lab Phantom")
    assert code == 0 and out.startswith("lab Phantom, K = 1015 N/m\n")


# ----------------------------------------------------------------- CLI polish
def test_cli_version_from_the_installed_metadata(capsys):
    from importlib import metadata

    code, out, err = run(capsys, "--version")
    assert code == 0 and out == f"dfa {metadata.version('dfa-haptics')}\n"


def test_cli_bare_dfa_prints_the_help_and_exits_2(capsys):
    code, out, err = run(capsys)
    assert code == 2 and out.startswith("usage: dfa") and "COMMAND" in out and "report" in out


def _subparsers():
    import argparse

    from dfa.cli.app import build_parser

    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return sub.choices


def test_cli_every_subcommand_help_has_a_description_and_an_example():
    for name, p in _subparsers().items():
        assert p.description and p.description.endswith("."), name
        assert p.epilog and f"\n  dfa {name} " in p.epilog, name


def test_cli_every_option_states_its_default():
    for name, p in _subparsers().items():
        for a in p._actions:
            if a.option_strings and a.option_strings[0] != "-h":
                assert a.help and ("default" in a.help or "required" in a.help), f"{name} {a.option_strings}"


@pytest.mark.parametrize("name", sorted(_subparsers()))
def test_cli_subcommand_help_runs(capsys, name):
    code, out, err = run(capsys, name, "--help")
    assert code == 0 and "example:" in out and err == ""


def test_design_analysis_json_from_its_fields(impulse):
    """DesignAnalysis writes the Result base's JSON: the fields but the figures' data, json_properties, message."""
    d = assert_json_from_fields(impulse)
    assert not {"thresholds", "trajectory", "trajectory_high", "stiffness_curve", "nyquist"} & set(d)
    assert set(d["growth_thresholds"]) == set(d["cycles"]) == {"half-delay", "zoh"}
    assert d["wall"]["dimensionless"] == json.loads(json.dumps(impulse.wall_params.to_dict()))


def test_report_first_section_leads_with_the_recommended_stiffness(impulse):
    """Issue 26: the report's first section states the recommendation of `dfa stiffness` (one answer), JSON too."""
    from collections import defaultdict

    from dfa.analysis.limits.recommend import recommend_stiffness

    rec = recommend_stiffness(impulse.design_answer)
    assert impulse.recommendation == rec and rec.k_recommended is not None
    md = design_markdown(impulse, defaultdict(str), lambda name: name)
    first = md.split("\n## ", 1)[0]
    assert f"**Recommended stiffness:** K = {rec.k_recommended:.5g} N/m" in first
    d = impulse.to_dict()
    assert d["recommendation"]["k_recommended"] == pytest.approx(rec.k_recommended)
    assert d["recommendation"]["status"] == rec.status.value
