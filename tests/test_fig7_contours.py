"""Paper Fig. 7: amplitude/frequency contour maps of the small stable and large unstable families."""

import json
import math

import numpy as np
import pytest

import dfa
from dfa.analysis.contours import contour_maps, load_contours
from dfa.analysis.cycles import large_cycle_closed_form, limit_cycles, small_cycle_closed_form
from dfa.cli import main


@pytest.fixture(scope="module")
def maps():
    return contour_maps(5.0, grid=40)


def test_fig7_closed_form_maps_equal_eq42_45(maps):
    rng = np.random.default_rng(3)
    for _ in range(20):
        i, j = rng.integers(0, 40, 2)
        b, s = maps.beta[j], maps.sigma[i]
        lc = large_cycle_closed_form(5.0, b, s)
        if lc is not None and lc[0] >= 1:
            assert maps.large_amplitude_closed[i, j] == pytest.approx(lc[0], rel=1e-12)
            assert maps.large_frequency_closed[i, j] == pytest.approx(0.44175, abs=1e-5)
        sc = small_cycle_closed_form(5.0, b, s)
        if sc is not None:
            assert maps.small_amplitude_closed[i, j] == pytest.approx(sc[0], rel=1e-9)


def test_fig7_exact_maps_match_the_point_solver(maps):
    rng = np.random.default_rng(4)
    checked = 0
    for _ in range(25):
        i, j = rng.integers(1, 40, 2)
        res = limit_cycles(dfa.Params(5.0, maps.beta[j], maps.sigma[i]))
        small = [c for c in res.cycles if c.family == "small"]
        unstable = [c for c in res.unstable_cycles if c.amplitude <= maps.max_amplitude]
        if small:
            assert maps.small_amplitude[i, j] == pytest.approx(small[0].amplitude, rel=1e-12)
        else:
            assert math.isnan(maps.small_amplitude[i, j])
        if unstable:
            assert maps.large_amplitude[i, j] == pytest.approx(unstable[0].amplitude, rel=1e-5)
            assert maps.large_frequency[i, j] == pytest.approx(unstable[0].frequency, rel=1e-5)
            checked += 1
        else:
            assert math.isnan(maps.large_amplitude[i, j])
    assert checked >= 5


def test_fig7_families_need_sigma_below_half_and_beta_below_half(maps):
    bb, ss = np.meshgrid(maps.beta, maps.sigma)
    assert np.all(ss[np.isfinite(maps.small_amplitude)] < 0.5)  # small cycles need σ < ½
    assert np.all(bb[np.isfinite(maps.large_amplitude_closed)] < 0.5)  # large cycles need β < ½ (μ = 5: β < sin(ω/2)/ω)
    # the exact large family follows the closed form closely where both exist (D ≈ 1 for M >> 1)
    both = (
        np.isfinite(maps.large_amplitude)
        & np.isfinite(maps.large_amplitude_closed)
        & (maps.large_amplitude_closed > 10)
    )
    rel = np.abs(maps.large_amplitude[both] / maps.large_amplitude_closed[both] - 1)
    assert both.sum() > 10 and np.median(rel) < 0.05


def test_fig7_save_load(maps, tmp_path):
    back = load_contours(maps.save(tmp_path / "c.npz"))
    assert back.mu == 5.0 and np.array_equal(back.large_amplitude, maps.large_amplitude, equal_nan=True)


def test_fig7_bad_input():
    with pytest.raises(dfa.DFAValueError, match="grid"):
        contour_maps(5.0, grid=1)
    with pytest.raises(dfa.DFAValueError, match="mu"):
        contour_maps(0.0)
    with pytest.raises(dfa.DFAValueError, match="max_amplitude"):
        contour_maps(5.0, max_amplitude=0.5)


def test_cli_limit_cycles_json_contract(capsys):
    assert main(["limit-cycles", "--mu", "2", "--beta", "0.4", "--sigma", "0.1", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    amps = [c["amplitude"] for c in d["cycles"]]
    assert amps == sorted(amps) and len(amps) == len(limit_cycles(dfa.Params(2.0, 0.4, 0.1)).cycles)
    for c in d["cycles"]:
        assert set(c) >= {"amplitude", "frequency", "stable", "family"} and c["family"] in ("small", "large")
    assert main(["limit-cycles", "--device", "delta", "--model", "zoh", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["model"] == "zoh" and d["growth_threshold"]["velocity"] > 0


def test_cli_contours(capsys, tmp_path):
    out = tmp_path / "c.npz"
    assert main(["contours", "--mu", "5", "--grid", "12", "--out", str(out), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["grid"] == [12, 12] and load_contours(out).beta.size == 12


@pytest.mark.parametrize(
    "argv, needle",
    [
        (["limit-cycles", "--mu", "5", "--beta", "0.1", "--sigma", "0.3", "--model", "exact"], "--model"),
        (["limit-cycles", "--mu", "-5", "--beta", "0.1", "--sigma", "0.3"], "mu"),
        (["limit-cycles", "--mu", "5", "--beta", "nan", "--sigma", "0.3"], "beta"),
        (["limit-cycles", "--mu", "5", "--beta", "0.1", "--sigma", "0.3", "--delay", "-1"], "delay"),
        (["contours", "--mu", "5", "--grid", "1"], "grid"),
        (["contours", "--mu", "5", "--grid", "4", "--out", "/nonexistent-dir/c.npz"], "does not exist"),
    ],
)
def test_cli_limit_cycles_and_contours_bad_input(capsys, argv, needle):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and len(err.strip().splitlines()) == 1 and needle in err


@pytest.mark.parametrize(
    "argv, k, period, resolution, units",
    [
        (["--device", "delta"], 14500.0, 1 / 3000, 3e-05, ("N/m", "N·s/m", "N")),
        (["--device", "re35", "--stiffness", "0.5"], 0.5, 1e-3, 0.000767, ("N·m/rad", "N·m·s/rad", "N·m")),
    ],
)
def test_fig7_cli_contours_plot_physical_axes_with_device(
    capsys, tmp_path, monkeypatch, argv, k, period, resolution, units
):
    """`dfa contours --plot` with a device: b = βKT and c = σKΔ on secondary axes, as `dfa map --plot` (issue 14 §3)."""
    import dfa.cli.contours as cli

    shown = []
    real = cli.save_png
    monkeypatch.setattr(cli, "save_png", lambda flag, path, ax: shown.append(ax) or real(flag, path, ax))
    png = tmp_path / "c.png"
    assert main(["contours", *argv, "--grid", "6", "--max-amplitude", "20", "--plot", str(png)]) == 0
    assert png.stat().st_size > 0 and f"figure written to {png}" in capsys.readouterr().out
    axes = shown[0].figure.axes
    panels = [ax for ax in axes if ax.get_xlabel().startswith("β")]
    assert len(panels) == 2
    for ax in panels:
        top, right = ax.child_axes
        assert top.get_xlabel() == f"damping b at K = {k:.5g} {units[0]} ({units[1]})"
        assert right.get_ylabel() == f"Coulomb friction c ({units[2]})"
        assert np.allclose(top.get_xlim(), np.array(ax.get_xlim()) * k * period)  # b = β K T (Table 1)
        assert np.allclose(right.get_ylim(), np.array(ax.get_ylim()) * k * resolution)  # c = σ K Δ


def test_fig7_cli_contours_plot_dimensionless_has_no_physical_axes(tmp_path, monkeypatch):
    import dfa.cli.contours as cli

    shown = []
    real = cli.save_png
    monkeypatch.setattr(cli, "save_png", lambda flag, path, ax: shown.append(ax) or real(flag, path, ax))
    assert (
        main(["contours", "--mu", "5", "--grid", "6", "--max-amplitude", "20", "--plot", str(tmp_path / "c.png")]) == 0
    )
    assert all(not ax.child_axes for ax in shown[0].figure.axes)


#: Keys of the former hand-written ContourMaps.to_dict (before it moved onto dfa.results.base.Result).
CONTOUR_JSON_KEYS = {
    "mu", "beta_range", "sigma_range", "grid", "small_points", "large_points", "large_closed_points", "max_amplitude",
    "status", "status_message",
}  # fmt: skip


@pytest.mark.parametrize("beta_range", [(0.0, 1.0), (0.1, 0.9)])
def test_contour_maps_json_is_the_result_base(beta_range):
    """ContourMaps.to_dict is the Result base's: the scalar fields (``flagged`` typed), the grid and the point counts,
    not the arrays; every former key is there with its value; the flagged points are counted, not worded."""
    from result_json import assert_json_from_fields

    from dfa.analysis.contours import _ARRAYS

    c = contour_maps(5.0, grid=4, beta_range=beta_range, max_amplitude=30.0)
    d = assert_json_from_fields(c)
    assert set(d) >= CONTOUR_JSON_KEYS | {"flagged"} and not set(d) & set(_ARRAYS)
    assert (d["mu"], d["max_amplitude"], d["grid"]) == (5.0, 30.0, [4, 4])
    assert (d["beta_range"], d["sigma_range"]) == (list(beta_range), [0.0, 2.0])
    for key, arr in (("small_points", "small_amplitude"), ("large_points", "large_amplitude")):
        assert d[key] == int(np.isfinite(getattr(c, arr)).sum())
    assert d["large_closed_points"] == int(np.isfinite(c.large_amplitude_closed).sum())
    assert d["status"] == c.status.value == ("flagged" if beta_range[0] == 0.0 else "ok")
    assert d["status_message"] == c.status.message
    # the flagged groups count exactly the points the closed forms mark (β = σ = 0 is one degenerate point)
    flags = {(f["family"], f["reason"]): f["points"] for f in d["flagged"]}
    assert flags == ({("small", "degenerate"): 1} if beta_range[0] == 0.0 else {})
