"""The wall controller on the command line (issue 15 "Command line"): every path through main(argv).

The numbers users read (CLI JSON) equal the API's: the extended criterion of eq. 6
(:func:`dfa.analysis.criterion.device_criterion`), the general Colgate–Schenkel condition
(:func:`dfa.analysis.colgate_schenkel.colgate_schenkel_damping`), :func:`dfa.simulate`, :func:`dfa.limit_cycles` and
:func:`dfa.stability_map` with ``controller=``. B = 0 without filter or lag is the spring, byte for byte.
"""

import json

import numpy as np
import pytest
from cli_text import unwrap
from result_json import written

import dfa.analysis.limits.kmax
from dfa.analysis.colgate_schenkel import colgate_schenkel_damping
from dfa.analysis.criterion import device_criterion
from dfa.analysis.cycles import limit_cycles
from dfa.analysis.maps import load_map, stability_map
from dfa.analysis.simulation import OUTCOMES, divergence_bound, simulate
from dfa.cli import main
from dfa.model.catalogue import get_device
from dfa.model.device import Device
from dfa.model.wall import Wall, WallParams
from dfa.render.controller import NOT_COVERED

DEV = get_device("Delta").device
K = 14500.0  # the catalogue stiffness of Delta
BASE = ["--device", "delta"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys, *argv):
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def test_eq6_controller_check_json_equals_api(capsys):
    d = run_json(
        capsys,
        "check",
        *BASE,
        "--velocity",
        "0.1",
        "--virtual-damping",
        "5",
        "--velocity-filter",
        "100",
        "--delay",
        "1",
    )
    ctl = Wall.of(K, damping=5.0, delay=1, filter_cutoff=100.0)
    r = device_criterion(DEV, ctl, 0.1)
    for key in ("beta0", "sigma0", "margin", "region", "passive", "critical_velocity", "critical_xi_dot"):
        assert d["criterion"][key] == written(getattr(r, key))
    cs = colgate_schenkel_damping(ctl, DEV.period)
    assert d["colgate_schenkel_damping"] == written(cs.damping_min)
    assert d["colgate_schenkel_met"] is (DEV.damping > cs.damping_bound)
    dim = d["wall"]["dimensionless"]
    assert dim["damping"] == pytest.approx(5.0 / (K * DEV.period), rel=1e-15)
    assert dim["cutoff"] == pytest.approx(100.0 * DEV.period, rel=1e-15)
    assert dim["lag"] == 0.0 and dim["delay"] == 1
    assert d["wall"]["damping"] == 5.0 and d["wall"]["units"]["damping"] == "N·s/m"


def test_eq6_controller_check_text_names_both_conditions(capsys):
    code, out, _ = run(capsys, "check", *BASE, "--velocity", "0.1", "--virtual-damping", "5")
    out = unwrap(out)
    assert code == 0
    assert "controller: K = 14500 N/m, B = 5 N·s/m" in out and "β_B = B/(KT) = 1.034" in out
    assert "eq. 6 extended to the damper" in out and "Colgate–Schenkel" in out
    r = device_criterion(DEV, Wall.of(K, damping=5.0), 0.1)
    assert not r.passive and "no: no passivity guarantee (not a proof of instability)" in out


@pytest.mark.parametrize(
    "extra", [[], ["--virtual-damping", "3"], ["--velocity-filter", "200", "--virtual-damping", "1"]]
)
def test_check_amplifier_lag_is_not_covered_never_passive(capsys, extra):
    code, out, _ = run(capsys, "check", *BASE, "--velocity", "0.01", "--amplifier-bandwidth", "300", *extra)
    assert code == 0 and f"passive  {NOT_COVERED}" in out and "yes:" not in out and "(proven)" not in out
    d = run_json(capsys, "check", *BASE, "--velocity", "0.01", "--amplifier-bandwidth", "300", *extra)
    assert d["passive"] is None and d["status"] == "not_covered"
    assert d["wall"]["amplifier_bandwidth"] == 300.0
    assert d["wall"]["dimensionless"]["lag"] == pytest.approx(1.0 / (2 * np.pi * 300.0 * DEV.period))


def test_eq4_controller_simulate_json_equals_api(capsys):
    argv = ["simulate", *BASE, "--velocity", "0.1", "--virtual-damping", "2", "--amplifier-bandwidth", "500"]
    d = run_json(capsys, *argv)
    ctl = Wall.of(K, damping=2.0, amplifier_bandwidth=500.0).params(DEV.period)
    p = DEV.params(K)
    xd = DEV.xi_dot(0.1)
    r = simulate(p.mu, p.beta, p.sigma, xd, None, bound=divergence_bound(0.0, xd, p.mu, 1e6), wall=ctl)
    assert d["outcome"] == r.outcome and d["final_xi"] == written(r.final_xi) and d["rest_sample"] == r.rest_sample
    assert d["wall"]["dimensionless"]["damping"] == written(ctl.damping)
    code, out, _ = run(capsys, *argv)
    out = unwrap(out)
    assert code == 0 and "controller: K = 14500 N/m, B = 2 N·s/m" in out and "amplifier bandwidth 500 Hz" in out


def test_eq36_controller_limit_cycles_json_equals_api(capsys):
    d = run_json(capsys, "limit-cycles", *BASE, "--virtual-damping", "2", "--delay", "1")
    ctl = Wall.of(K, damping=2.0, delay=1).params(DEV.period)
    res = limit_cycles(DEV.params(K), wall=ctl)
    assert [c["amplitude"] for c in d["cycles"]] == written([c.amplitude for c in res.cycles])
    assert d["wall"]["delay"] == 1 and d["wall"]["dimensionless"]["damping"] == written(ctl.damping)
    code, out, _ = run(capsys, "limit-cycles", *BASE, "--virtual-damping", "2", "--delay", "1")
    assert code == 0 and "controller: K = 14500 N/m, B = 2 N·s/m, delay 1 sample" in out


def test_fig4_controller_map_json_equals_api(capsys, tmp_path):
    out = tmp_path / "m.npz"
    argv = ["map", *BASE, "--velocity", "0.1", "--virtual-damping", "2", "--velocity-filter", "200"]
    argv += ["--grid", "3", "--samples", "2000", "--jobs", "1", "--out", str(out)]
    d = run_json(capsys, *argv)
    ctl = Wall.of(K, damping=2.0, filter_cutoff=200.0).params(DEV.period)
    p = DEV.params(K)
    m = stability_map(p.mu, [DEV.xi_dot(0.1)], grid=3, samples=2000, n_jobs=1, progress=False, wall=ctl)
    assert d["counts"] == written(m.to_dict()["counts"])
    assert load_map(out).wall == ctl
    assert d["wall"]["filter_cutoff"] == 200.0


def test_fig4_controller_map_outcomes_equal_simulate_per_point():
    """stability_map(controller=) is simulate(controller=) at every point (damper, filter, delay, lag)."""
    ctl = WallParams.of(damping=0.3, delay=1, cutoff=0.1, lag=0.5)
    m = stability_map(100.0, [2.0], grid=3, samples=3000, n_jobs=2, progress=False, wall=ctl)
    assert m.wall == ctl and m.delay == 1
    for i, s in enumerate(m.sigma):
        for j, b in enumerate(m.beta):
            r = simulate(100.0, b, s, 2.0, 3000, wall=ctl)
            assert r.outcome == OUTCOMES[m.outcome[0, i, j]]
            assert np.array_equal(r.amplitude, m.amplitude[0, i, j], equal_nan=True)


def test_fig4_spring_wall_map_fast_path_is_the_general_path(monkeypatch):
    """A spring wall (delay only) runs the spring's kernel; the wall kernel, forced, gives the same map."""
    kw = dict(grid=3, samples=2000, n_jobs=1, progress=False, wall=WallParams.of(delay=1))
    a = stability_map(100.0, [2.0], **kw)
    d = a.to_dict()  # a spring's map states its wall (the delay alone) like every result
    assert d["delay"] == 1 and d["wall"]["delay"] == 1 and d["wall"]["damping"] == 0.0
    monkeypatch.setattr(WallParams, "is_spring", property(lambda self: False))  # force the wall kernel
    b = stability_map(100.0, [2.0], **kw)
    assert np.array_equal(a.outcome, b.outcome)
    np.testing.assert_allclose(b.amplitude, a.amplitude, rtol=1e-9, equal_nan=True)


SPRING_CASES = [
    ["check", *BASE, "--velocity", "0.1"],
    ["check", *BASE, "--velocity", "0.1", "--delay", "1", "--json"],
    ["simulate", *BASE, "--velocity", "0.1"],
    ["simulate", *BASE, "--velocity", "0.1", "--json"],
    ["limit-cycles", *BASE, "--json"],
]


@pytest.mark.parametrize("argv", SPRING_CASES)
def test_zero_virtual_damping_is_the_spring_byte_for_byte(capsys, argv):
    assert run(capsys, *argv) == run(capsys, *argv, "--virtual-damping", "0")


def test_zero_virtual_damping_map_is_the_spring(capsys, tmp_path):
    argv = ["map", *BASE, "--velocity", "0.1", "--grid", "3", "--samples", "1000", "--jobs", "1", "--json"]
    a = json.loads(run(capsys, *argv, "--out", str(tmp_path / "a.npz"))[1])
    b = json.loads(run(capsys, *argv, "--out", str(tmp_path / "b.npz"), "--virtual-damping", "0")[1])
    a.pop("out"), b.pop("out")
    assert a == b and "controller" not in b


ERRORS = [
    (["check", *BASE, "--velocity", "0.1", "--virtual-damping", "-1"], "--virtual-damping -1 is invalid"),
    (["check", *BASE, "--velocity", "0.1", "--velocity-filter", "0"], "--velocity-filter 0 is invalid"),
    (["simulate", *BASE, "--velocity", "0.1", "--velocity-filter", "2000"], "Nyquist frequency 1500 Hz"),
    (
        ["map", *BASE, "--velocity", "0.1", "--velocity-filter", "1500", "--out", "/tmp/x.npz"],
        "Nyquist frequency 1500 Hz",
    ),
    (["limit-cycles", *BASE, "--amplifier-bandwidth", "0"], "--amplifier-bandwidth 0 is invalid"),
    (["check", *BASE, "--velocity", "0.1", "--amplifier-bandwidth", "-5"], "--amplifier-bandwidth -5 is invalid"),
    (["check", *BASE, "--velocity", "0.1", "--virtual-damping", "1", "--delay", "1.5"], "'1.5' is not a whole number"),
    (["simulate", *BASE, "--velocity", "0.1", "--virtual-damping", "1", "--delay", "-1"], "delay"),
    (
        ["simulate", "--mu", "100", "--beta", "0.2", "--sigma", "1", "--xi-dot", "1", "--virtual-damping", "1"],
        "needs a physical device",
    ),
    (["check", "--beta", "0.2", "--sigma", "1", "--xi-dot", "1", "--velocity-filter", "10"], "needs a physical device"),
    (
        ["map", "--mu", "100", "--xi-dot", "1", "--virtual-damping", "1", "--out", "/tmp/x.npz"],
        "needs a physical device",
    ),
    (["stiffness", *BASE, "--velocity", "0.1", "--velocity-filter", "1600"], "Nyquist frequency 1500 Hz"),
    (
        ["report", *BASE, "--velocity", "0.1", "--amplifier-bandwidth", "-100", "--out", "/tmp/ccli-r"],
        "--amplifier-bandwidth -100 is invalid",
    ),
    (["check", *BASE, "--velocity", "0.1", "--virtual-damping", "nan"], "not a finite number"),
]


@pytest.mark.parametrize("argv, text", ERRORS)
def test_controller_bad_input_is_one_line_exit_2(capsys, argv, text):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert text in err and err.count("\n") == 1 and "Traceback" not in err


NULL_CASES = [
    ["check", *BASE, "--velocity", "0.1", "--virtual-damping", "5", "--json"],
    ["check", *BASE, "--velocity", "0.1", "--amplifier-bandwidth", "300", "--json"],
    ["simulate", *BASE, "--velocity", "0.1", "--virtual-damping", "2", "--json"],
    ["limit-cycles", *BASE, "--velocity-filter", "100", "--virtual-damping", "2", "--json"],
    ["stiffness", *BASE, "--velocity", "0.1", "--amplifier-bandwidth", "300", "--json"],
]


@pytest.mark.parametrize("argv", NULL_CASES)
def test_controller_json_nulls_have_reasons(capsys, argv):
    from test_cli_json_null_reasons import unexplained_nulls

    code, out, err = run(capsys, *argv)
    assert code == 0, err
    assert unexplained_nulls(json.loads(out)) == []


def test_eq11_controller_stiffness_json_equals_api(capsys):
    from dfa.analysis.limits.kmax import design_answer

    d = run_json(capsys, "stiffness", *BASE, "--velocity", "0.1", "--virtual-damping", "1", "--delay", "1")
    r = design_answer(DEV, 0.1, wall=Wall.of(K, damping=1.0, delay=1), assess=True)
    kc, kl = r.k_criterion.value, r.k_linear.value
    assert d["k_criterion"]["value"] == written(kc) and d["k_linear"]["value"] == written(kl)
    assert d["wall"]["delay"] == 1 and d["wall"]["dimensionless"]["delay"] == 1
    for key in ("k_df", "k_sim", "k_sim_rest"):  # searched with the controller (tests/test_kmax_controller.py)
        assert d[key]["value"] == written(getattr(r, key).value) and d[key]["status"] == getattr(r, key).status.value
    code, out, _ = run(
        capsys, "stiffness", *BASE, "--velocity", "0.1", "--virtual-damping", "1", "--delay", "1", "--explain"
    )
    assert code == 0 and f"{kc:.5g} N/m" in out and f"{kl:.5g} N/m" in out
    assert "controller: K = 14500 N/m, B = 1 N·s/m, delay 1 sample" in out


@pytest.mark.parametrize("cutoff", ["0.5", "2.9"])
def test_cli_velocity_filter_below_the_floor_names_the_flag(capsys, cutoff):
    """A cutoff below MIN_CUTOFF cycles per sample (3 Hz on the 3 kHz Delta) is refused naming the flag the user
    typed and the allowed range in plain numbers; the floor as printed is accepted (red team)."""
    assert main(["check", "--device", "delta", "--velocity", "0.1", "--velocity-filter", cutoff]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"dfa check: error: --velocity-filter {cutoff} is invalid") and "\n" not in err
    assert "at least 3 Hz" in err and "[3, 1500)" in err and "filter_cutoff" not in err
    assert main(["check", "--device", "delta", "--velocity", "0.1", "--velocity-filter", "3"]) == 0


def test_stiffness_with_a_wall_searches_k_without_stiffness(capsys):
    """`dfa stiffness` with a custom device and a damper needs no --stiffness: K is what it searches (issue 25)."""
    custom = ["--mass", "0.1", "--damping", "0.005", "--coulomb", "0.02", "--resolution", "1e-5", "--period", "0.001"]
    d = run_json(capsys, "stiffness", *custom, "--velocity", "0.1", "--virtual-damping", "0.5", "--delay", "1")
    assert d["stiffness_source"] is None and d["assessment"] is None and d["wall"]["damping"] == 0.5
    dev = Device(mass=0.1, damping=0.005, coulomb=0.02, resolution=1e-5, period=0.001)
    ref = dfa.analysis.limits.kmax.design_answer(dev, 0.1, wall=Wall.of(1.0, damping=0.5, delay=1))
    assert d["k_sim"]["value"] == written(ref.k_sim.value)
    assert d["k_criterion"]["value"] == written(ref.k_criterion.value)


def test_stiffness_plot_with_a_wall_draws_the_walls_chart(capsys, tmp_path):
    """The stiffness-speed chart takes the wall's elements (held fixed while K varies), as the four K_max do."""
    png = tmp_path / "chart.png"
    argv = ["stiffness", *BASE, "--velocity", "0.1", "--virtual-damping", "1", "--plot", str(png), "--json"]
    d = run_json(capsys, *argv)
    assert png.stat().st_size > 1000 and d["plot"] == str(png)
