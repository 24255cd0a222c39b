"""Z-width (issue 15): the linear boundary is the exact bound at each B, simulation never diverges below the
extended criterion (eq. 6 redone), the B = 0 column is the spring-only K_max of dfa.analysis.limits.kmax (its
describing-function limit the design answer's, whatever the grid), jobs do not change the result, and `dfa zwidth`
prints the API's numbers and refuses bad input with exit 2."""

import json
import math

import numpy as np
import pytest
from result_json import written

import dfa
import dfa.analysis.limits.zwidth as zmod
from dfa.analysis.limits.closed_form import k_gil, k_max_criterion
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.runs import SAFE, Evidence
from dfa.analysis.limits.search import K_RTOL
from dfa.analysis.limits.zwidth import DIVERGES, POINT_OUTCOMES, ZWIDTH_METHODS, z_width
from dfa.analysis.linear_wall import stable_stiffness
from dfa.cli import main
from dfa.model.catalogue import get_device
from dfa.model.device import Device
from dfa.model.wall import Wall
from dfa.results.status import LimitStatus, ZWidthStatus

DEV = "Impulse Engine"
V = 0.1


@pytest.fixture(scope="module")
def zw():
    return z_width(get_device(DEV).device, V, grid=6, speeds=2, n_jobs=1)


@pytest.fixture(scope="module")
def zw_delay():
    return z_width(
        get_device(DEV).device, V, grid=4, speeds=1, n_jobs=1, wall=Wall.of(1.0, delay=1, filter_cutoff=100.0)
    )


def _exact(dev, b, d=0, fc=None, fbw=None):
    r = stable_stiffness(dev.mass, dev.damping, dev.period, Wall.of(1.0, b, d, fc, fbw))
    return r.k_crit if r.k_crit > 0 else math.nan


def test_zwidth_linear_boundary_equals_exact_bound_at_each_B(zw, zw_delay):
    for z in (zw, zw_delay):
        want = [_exact(z.device, float(b), z.delay, z.wall.filter_cutoff) for b in z.damping]
        np.testing.assert_array_equal(z.boundary("linear"), np.array(want))


def test_zwidth_linear_boundary_with_amplifier_lag_and_passivity_not_covered():
    dev = get_device(DEV).device
    z = z_width(dev, V, grid=3, speeds=1, n_jobs=1, wall=Wall.of(1.0, amplifier_bandwidth=200.0))
    want = [_exact(dev, float(b), 0, None, 200.0) for b in z.damping]
    np.testing.assert_array_equal(z.boundary("linear"), np.array(want))
    for m in ("passivity", "criterion"):
        assert np.isnan(z.boundary(m)).all()
        assert all(x.value is None and x.status is LimitStatus.NOT_COVERED for x in z.limits[m])
    rec = json.loads(json.dumps(z.to_dict()))
    assert rec["boundaries"]["criterion"] == [None] * 3
    for x in rec["limits"]["criterion"]:
        assert x["status"] == "not_covered" and x["null_reasons"]["/value"] == LimitStatus.NOT_COVERED.message


@pytest.mark.parametrize("name", ["zw", "zw_delay"])
def test_eq6_zwidth_simulation_never_diverges_below_the_criterion(name, request):
    """Soundness: every simulated point at or below the extended criterion's K_max(B) stays bounded."""
    z = request.getfixturevalue(name)
    assert z.counterexamples == ()
    assert z.status in (ZWidthStatus.OK, ZWidthStatus.CAVEATS)
    crit, sim = z.boundary("criterion"), z.boundary("sim")
    for i in range(z.damping.size):
        below = z.stiffness <= crit[i] if math.isfinite(crit[i]) else np.zeros(z.stiffness.size, bool)
        assert not (z.outcome[i][below] == DIVERGES).any()
        if below.any() and math.isfinite(sim[i]):
            assert sim[i] >= z.stiffness[below].max()


def test_eq11_zwidth_B0_column_is_the_spring_kmax(zw):
    dev = zw.device
    assert zw.boundary("linear")[0] == pytest.approx(k_gil(dev, delay=0), rel=1e-9)
    assert zw.boundary("criterion")[0] == pytest.approx(k_max_criterion(dev, V, 0), rel=2 * K_RTOL)
    # the simulated column against dfa.analysis.limits.kmax's own runs (simulate_points) at every grid K
    ev = Evidence(dev, Wall(1.0), np.array(zw.speeds), zw.max_samples, "half-delay")
    kmax_safe = [ev.no_divergence(float(k)) == SAFE for k in zw.stiffness]
    zw_safe = [POINT_OUTCOMES[c] in ("rest", "bounded") for c in zw.outcome[0]]
    assert kmax_safe == zw_safe
    first = kmax_safe.index(False) if False in kmax_safe else None
    if first is not None and first > 0:
        assert zw.boundary("sim")[0] == zw.stiffness[first - 1]


#: The device of the grid-dependent describing-function column (fixed): the Z-width's K_max at B = 0 was 173.2 N/m
#: with grid 10 but 3.328 N/m with grid 40, where `dfa stiffness --delay 1` gives 173.18 N/m.
DF_GRID_DEVICE = Device(mass=0.1, damping=0.005, coulomb=0.02, resolution=1e-5, period=1e-3)


@pytest.mark.parametrize("grid", [3, 4])
def test_zwidth_df_column_at_B0_is_the_design_answer_k_df_for_any_grid(grid):
    """The describing-function column at B = 0 is k_df of the design answer with the same wall, whatever the Z-width's
    grid (its own search over the design answer's grid; before the fix it searched the Z-width's K grid: 173.196 N/m
    with grid 3, 172.988 N/m with grid 4, 3.328 N/m with grid 40)."""
    wall = Wall.of(1.0, delay=1)
    z = z_width(DF_GRID_DEVICE, 0.1, wall=wall, grid=grid, speeds=1, n_jobs=1)
    want = design_answer(DF_GRID_DEVICE, 0.1, wall=wall).k_df
    assert want.status is LimitStatus.FOUND and want.value == pytest.approx(173.18, rel=K_RTOL)
    assert z.boundary("df")[0] == want.value
    assert z.limits["df"][0] == want


def test_zwidth_deterministic_for_any_number_of_jobs():
    dev = get_device(DEV).device
    a = z_width(dev, V, grid=4, speeds=1, n_jobs=1).to_dict()
    b = z_width(dev, V, grid=4, speeds=1, n_jobs=2).to_dict()
    assert json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)


def test_zwidth_to_dict_is_strict_json_with_reasons(zw):
    rec = zw.to_dict()
    text = json.dumps(rec, allow_nan=False)
    back = json.loads(text)
    assert set(back["boundaries"]) - {"null_reasons"} == set(ZWIDTH_METHODS) == set(back["limits"])
    for m in ZWIDTH_METHODS:
        vals, lims = back["boundaries"][m], back["limits"][m]
        assert len(vals) == len(lims) == 6
        assert vals == [x["value"] for x in lims]
        if None in vals:  # the boundary's nulls point to the limits' records ...
            assert f"/{m}" in back["boundaries"]["null_reasons"]
        for x in lims:  # ... and every null has its reason: the status and its message
            if x["value"] is None:
                assert x["status"] != "found" and x["null_reasons"]["/value"] == LimitStatus(x["status"]).message
    assert back["units"]["damping"] == "N·s/m"


def test_zwidth_plot_has_labelled_log_axes(zw):
    import matplotlib

    matplotlib.use("Agg")
    ax = zw.plot()
    assert ax.get_yscale() == "log"
    assert "N·s/m" in ax.get_xlabel() and "N/m" in ax.get_ylabel()


def test_zwidth_plot_design_star_does_not_hide_the_criterion_point_at_b0():
    """The criterion is defined at B = 0 only here: its marker lies above the design point's star, both in the legend.

    The damping axis to m/T (the default of old): its first B > 0 lies above where the criterion proves any K."""
    import matplotlib

    matplotlib.use("Agg")
    dev = get_device(DEV).device
    zw = z_width(dev, V, grid=3, speeds=1, n_jobs=1, b_range=(0.0, dev.mass / dev.period))
    crit = zw.boundary("criterion")
    assert np.isfinite(crit[0]) and np.isfinite(crit).sum() == 1  # the case of the fix: a single point at B = 0
    ax = zw.plot(design_point=(0.0, float(crit[0])))  # the star exactly on the criterion's point
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    star, point = lines["design point (B, K)"], lines["extended criterion (proof, eq. 6)"]
    assert star.get_marker() == "*" and point.get_marker() == "o"
    assert list(star.get_xydata()[0]) == [0.0, pytest.approx(crit[0])]
    assert point.get_xydata()[0] == pytest.approx(star.get_xydata()[0])  # same place ...
    assert point.get_zorder() > star.get_zorder()  # ... the criterion's marker drawn on top
    assert point.get_markersize() < star.get_markersize()  # and smaller: the star shows around it
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "design point (B, K)" in labels and "extended criterion (proof, eq. 6)" in labels
    import matplotlib.pyplot as plt

    plt.close(ax.figure)


def test_zwidth_bad_input_is_refused():
    dev = get_device(DEV).device
    with pytest.raises(dfa.DFAValueError, match="grid"):
        z_width(dev, V, grid=1)
    with pytest.raises(dfa.DFAValueError, match="grid"):
        z_width(dev, V, grid=201)
    with pytest.raises(dfa.DFAValueError, match="Nyquist"):
        z_width(dev, V, grid=2, wall=Wall.of(1.0, filter_cutoff=1e4))
    with pytest.raises(dfa.DFAValueError, match="velocity"):
        z_width(dev, 0.0, grid=2)
    with pytest.raises(dfa.DFAValueError, match="b_range"):
        z_width(dev, V, grid=2, b_range=(2.0, 1.0))
    with pytest.raises(dfa.DFATypeError):
        z_width("impulse", V, grid=2)


def test_zwidth_refuses_too_much_work_up_front(monkeypatch):
    monkeypatch.setattr(zmod, "MAX_WORK_SAMPLES", 1e5)
    with pytest.raises(dfa.DFAValueError, match="lower the grid"):
        z_width(get_device(DEV).device, V, grid=3)


def test_cli_zwidth_json_numbers_equal_the_api(capsys):
    assert main(["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "3", "--speeds", "1", "--jobs", "1",
                 "--json"]) == 0  # fmt: skip
    rec = json.loads(capsys.readouterr().out)
    api = z_width(get_device(DEV).device, V, grid=3, speeds=1, n_jobs=1)
    for m in ZWIDTH_METHODS:
        want = written([None if not math.isfinite(x) else x for x in api.boundary(m).tolist()])
        assert rec["boundaries"][m] == want
    assert rec["stiffness"] == written(api.stiffness.tolist())


def test_cli_zwidth_text_table_prints_the_boundaries(capsys, tmp_path):
    png = tmp_path / "z.png"
    assert main(["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "3", "--speeds", "1", "--jobs", "1",
                 "--plot", str(png)]) == 0  # fmt: skip
    out = capsys.readouterr().out
    api = z_width(get_device(DEV).device, V, grid=3, speeds=1, n_jobs=1)
    assert f"{api.boundary('linear')[1]:.4g}" in out
    assert png.stat().st_size > 0


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["--device", "impulse", "--velocity", "0.1", "--velocity-filter", "600"], "Nyquist"),
        (["--device", "impulse", "--velocity", "0.1", "--velocity-filter", "-5"], "velocity-filter"),
        (["--device", "impulse", "--velocity", "0.1", "--amplifier-bandwidth", "0"], "amplifier"),
        (["--device", "impulse", "--velocity", "0.1", "--delay", "1.5"], "delay"),
        (["--device", "impulse", "--velocity", "0.1", "--stiffness", "80"], "--stiffness"),
        (["--device", "impulse", "--velocity", "0.1", "--virtual-damping", "1"], "grid of B from 0"),
        (["--device", "impulse", "--velocity", "0.1", "--velocity-filter", "0.4"], "at least 0.5 Hz"),
        (["--device", "impulse", "--velocity", "0.1", "--grid", "500"], "grid"),
        (["--velocity", "0.1"], "device"),
        (["--device", "impulse"], "velocity"),
        (["--device", "impulse", "--velocity", "0.1", "--damping-max", "0"], "--damping-max 0 is invalid"),
        (["--device", "impulse", "--velocity", "0.1", "--damping-max", "inf"], "--damping-max"),
    ],
)
def test_cli_zwidth_errors_one_line_exit_2(argv, needle, capsys):
    assert main(["zwidth", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and needle in err


def test_report_zwidth_section_states_the_api_numbers(tmp_path, capsys, monkeypatch):
    """`dfa report --zwidth N` adds the Z-width table and figure; the JSON record holds the analysis' boundaries."""
    import dfa.studies.report
    from dfa.studies.design import design_analysis

    analyses = []  # the report's own analysis (a small stability map: the Z-width does not depend on it)

    def small(*args, **kwargs):
        analyses.append(design_analysis(*args, **{**kwargs, "map_grid": 3, "samples": 2000, "n_jobs": 1}))
        return analyses[-1]

    monkeypatch.setattr(dfa.studies.report, "design_analysis", small)
    argv = ["report", "--device", "impulse", "--velocity", "0.1", "--zwidth", "3", "--format", "md",
            "--out", str(tmp_path), "--quiet"]  # fmt: skip
    assert main(argv) == 0
    md = next(tmp_path.glob("*.md")).read_text(encoding="utf-8")
    assert "## Z-width" in md and "_zwidth.png" in md
    z = z_width(get_device(DEV).device, V, grid=3, speeds=1, n_jobs=1)
    assert f"{z.boundary('linear')[1]:.4g}" in md
    assert len(analyses) == 1 and analyses[0].zwidth is not None
    assert analyses[0].to_dict()["zwidth"]["boundaries"]["linear"] == z.to_dict()["boundaries"]["linear"]


@pytest.mark.parametrize("seed", [7])
def test_zwidth_columns_at_B_positive_equal_dfa_stiffness_with_that_B(seed):
    """Issue 26 §2: at a grid value B > 0 the criterion, linear and describing-function columns are `design_answer`
    (what `dfa stiffness --virtual-damping B` prints) with that damper, on a random device: one number per question."""
    rng = np.random.default_rng(seed)
    dev = Device(
        mass=float(rng.uniform(0.05, 0.5)), damping=float(rng.uniform(0.001, 0.05)),
        coulomb=float(rng.uniform(0.05, 0.5)), resolution=float(10 ** rng.uniform(-5.5, -4.5)), period=1e-3,
    )  # fmt: skip
    z = z_width(dev, 0.05, wall=Wall.of(1.0, delay=1), grid=3, speeds=1, n_jobs=1)
    i = 1
    b = float(z.damping[i])
    ans = design_answer(dev, 0.05, wall=Wall.of(1.0, damping=b, delay=1), speeds=1)
    for col, lim in (("criterion", ans.k_criterion), ("linear", ans.k_linear), ("df", ans.k_df)):
        want = math.nan if lim.value is None else lim.value
        got = z.boundary(col)[i]
        assert (math.isnan(got) and math.isnan(want)) or got == pytest.approx(want, rel=2 * K_RTOL), (col, got, want)


@pytest.mark.parametrize("name, v", [("delta", 0.05), ("impulse", 0.1), ("phantom", 0.1)])
def test_zwidth_default_damping_axis_ends_past_the_last_passivity_boundary(name, v):
    """Issue 41: the axis ran to m/T = 750 N·s/m on the Delta while the criterion proves nothing above a few
    N·s/m and Colgate–Schenkel nothing above b; the default top is now twice where the last of them ends, each end
    checked against its method directly (just below it some K holds, just above none)."""
    from dfa.analysis.colgate_schenkel import colgate_schenkel_damping
    from dfa.analysis.limits.kmax import wall_k_criterion

    dev = get_device(name).device
    ends = zmod.damping_ends(dev, Wall(1.0), v)
    top = zmod.default_damping_max(dev, Wall(1.0), v)
    assert top == pytest.approx(2.0 * max(ends.values()), rel=1e-12) and top < 0.1 * dev.mass / dev.period
    crit = ends["criterion"]
    assert wall_k_criterion(dev, Wall.of(1.0, damping=crit * (1 - 1e-6)), v) > 0.0
    assert wall_k_criterion(dev, Wall.of(1.0, damping=crit * (1 + 1e-6)), v) == 0.0
    k = 1e-12 * dev.mass / dev.period**2  # Colgate–Schenkel: b above the bound at K → 0, just below its end
    for factor, holds in ((1 - 1e-3, True), (1 + 1e-3, False)):
        bound = colgate_schenkel_damping(Wall.of(k, damping=ends["passivity"] * factor), dev.period).damping_bound
        assert (dev.damping > bound) is holds


def test_cli_zwidth_damping_max_sets_the_axis_and_the_default_is_stated(capsys):
    argv = ["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "2", "--speeds", "1", "--jobs", "1"]
    assert main([*argv, "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    dev = get_device(DEV).device
    assert rec["damping"][-1] == pytest.approx(zmod.default_damping_max(dev, Wall(1.0), V), rel=1e-9)
    assert main([*argv, "--damping-max", "3"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "B 0 to 3 N·s/m)" in out and "\n3 " not in out
    assert main(argv) == 0
    assert "twice where the passivity boundaries end, --damping-max sets it" in " ".join(
        capsys.readouterr().out.split()
    )
