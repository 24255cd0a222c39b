"""Non-finite numbers and numpy's warnings (issue 27 §2): no inf or NaN printed as an answer, one line per refusal.

Each finding of the fuzz is reproduced first (the exact argv or call), then the fix is checked: the input is refused
up front with the package's error (one line on stderr, exit 2, naming the value, the rule and the fix), or the
answer is finite.
"""

import math
import os
import re
import subprocess
import sys
import warnings

import numpy as np
import pytest

import dfa
from dfa.analysis.simulation import default_samples, simulate_batch
from dfa.cli import main
from dfa.errors import DFAValueError

#: Deliberately outside what haptic devices have (extreme values test the numerics): the plausibility warning
#: (dfa.plausibility) is expected here, and tested in tests/test_plausibility.py.
pytestmark = pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")


DFA = [sys.executable, "-c", "import sys; from dfa.cli import main; sys.exit(main())"]


def refused(capsys, *argv):
    """Run in-process, expect exit 2 and one line on stderr; return it."""
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and err.startswith("dfa"), err
    return err


def run_dfa(*argv):
    """Run the dfa program in a subprocess (numpy's warnings reach stderr there, not pytest's record)."""
    env = dict(os.environ, PYTHONWARNINGS="")
    return subprocess.run(DFA + list(argv), capture_output=True, text=True, env=env, timeout=120)


# ------------------------------------------------------------------ numpy's RuntimeWarning lines
def test_cli_refused_start_prints_one_line_without_runtime_warnings():
    # found: "dfa: warning: overflow encountered in multiply (RuntimeWarning)" before the error line
    p = run_dfa("simulate", "--mu", "5", "--beta", "0.1", "--sigma", "0.3", "--xi-dot", "1e300")
    assert p.returncode == 2
    assert p.stderr.count("\n") == 1 and p.stderr.startswith("dfa simulate: error: xi_dot = 1e+300"), p.stderr
    assert "overflows a float" in p.stderr


def test_cli_runtime_warnings_of_a_run_become_one_line_at_the_end():
    p = run_dfa("limit-cycles", "--mu", "5", "--beta", "0", "--sigma", "1e300")  # (μ = 1e300 is no longer searched)
    assert p.returncode == 0, p.stderr
    lines = p.stderr.splitlines()
    numeric = [x for x in lines if x.endswith("(RuntimeWarning)")]
    assert len(numeric) == 1 and numeric[0] == lines[-1], p.stderr
    assert numeric[0].startswith("dfa: warning: numpy reported ") and "overflow encountered" in numeric[0]


def test_default_samples_refuses_an_overflowing_start_without_a_warning():
    # default_samples returned its cap with a RuntimeWarning where simulate() refuses the same start
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(DFAValueError, match="overflows a float"):
            default_samples(5.0, 0.1, 0.3, 1e300)
        with pytest.raises(DFAValueError, match="overflows a float"):
            dfa.simulate(5.0, 0.1, 0.3, 1e300)


# ------------------------------------------------------------------ β/μ = bT/m: the simulator and the linear loop
def test_simulate_huge_damping_rate_refused_not_a_false_divergence(capsys):
    # found: `dfa simulate --mu 1 --beta 1e308 --sigma 0 --xi-dot 10` said "unstable: diverged", final ξ = nan
    err = refused(capsys, "simulate", "--mu", "1", "--beta", "1e308", "--sigma", "0", "--xi-dot", "10")
    assert err.startswith(
        "dfa simulate: error: --beta = 1e+308 is invalid with --mu = 1: β/μ = bT/m must be at most 1e+08"
    )
    with pytest.raises(DFAValueError, match=r"β/μ = bT/m must be at most 1e\+08"):
        dfa.simulate(1.0, 1e308, 0.0, 10.0)
    with pytest.raises(DFAValueError, match="β/μ"):
        simulate_batch([1.0, 1.0], [0.1, 1e308], 0.0, 10.0, samples=100)
    r = dfa.simulate(1.0, 1e8, 1.0, 10.0, samples=100)  # at the limit: decided, finite
    assert r.outcome.value == "rest" and np.isfinite(r.final_xi)


def test_map_and_limit_cycles_refuse_a_huge_damping_rate(capsys, tmp_path):
    err = refused(capsys, "map", "--mu", "1e-9", "--xi-dot", "1", "--out", str(tmp_path / "m.npz"))
    assert "--beta-range = 1 is invalid with --mu = 1e-09" in err
    with pytest.raises(DFAValueError, match="β/μ"):
        dfa.stability_map(1e-9, [1.0], grid=2, samples=10)
    # found: limit_cycles(Params(0.001, 1e308, 0.1467), max_amplitude=1.0) raised numpy's LinAlgError
    with pytest.raises(DFAValueError, match=r"beta = 1e\+308 is invalid with mu = 0.001: β/μ"):
        dfa.limit_cycles(dfa.Params(0.001, 1e308, 0.1467), max_amplitude=1.0)
    err = refused(
        capsys, "limit-cycles", "--mu", "0.001", "--beta", "1e308", "--sigma", "0.1467", "--max-amplitude", "1"
    )
    assert "--beta = 1e+308 is invalid with --mu = 0.001" in err
    assert os.listdir(tmp_path) == []


# ------------------------------------------------------------------ dfa check: margin and critical speed
def test_check_margin_or_critical_speed_that_overflows_is_refused(capsys):
    from dfa.analysis.criterion import passivity_criterion

    # found: `dfa check --mu 100 --beta 1e308 --sigma 1 --xi-dot 2` printed "margin inf"
    err = refused(capsys, "check", "--mu", "100", "--beta", "1e308", "--sigma", "1", "--xi-dot", "2")
    assert err.startswith(
        "dfa check: error: --beta = 1e+308, --sigma = 1, --xi-dot = 2 are invalid together: the criterion's"
    )
    assert "margin" in err and "inf" not in err.split(":")[2]
    # found: `... --beta 0 --sigma 1e308 --xi-dot 1` printed "critical speed inf ticks/sample"
    err = refused(capsys, "check", "--mu", "100", "--beta", "0", "--sigma", "1e308", "--xi-dot", "1")
    assert "the critical speed (σ − σ₀)/(β₀ − β) (eq. 12) must be a finite number" in err
    with pytest.raises(DFAValueError, match="beta = 1e\\+308, sigma = 1, xi_dot = 2 are invalid together"):
        passivity_criterion(1e308, 1.0, 2.0)
    with pytest.raises(DFAValueError, match="critical speed"):
        passivity_criterion(0.0, 1e308, 1.0)
    r = passivity_criterion(1e308, 1.0, 1.0)  # the margin 1e308 is a float: answered
    assert r.margin == 1e308 and r.passive
    code = main(["check", "--mu", "100", "--beta", "0", "--sigma", "1e300", "--xi-dot", "1"])
    out, _ = capsys.readouterr()
    assert code == 0 and "inf" not in out and "2e+300 ticks/sample" in out


# ------------------------------------------------------------------ the stiffness searches and the chart
def test_grid_search_bisects_huge_and_tiny_stiffnesses():
    from dfa.analysis.limits.search import geometric_mean, grid_search

    # found: `dfa stiffness --device delta --velocity 0.1 --coulomb 1e300` ended in "limited_by = inf is invalid"
    # (√(lo·hi) overflowed to inf between 1e303 and 1e305 N/m; below 1e-154 the product underflows to 0)
    for grid, edge in ((np.array([1e300, 1e303, 1e305]), 2e303), (np.array([1e-300, 1e-297, 1e-295]), 2e-297)):
        lim = grid_search(lambda k, e=edge: "safe" if k < e else "undecided", grid)
        assert lim.value is not None and lim.limited_by is not None
        assert lim.value < edge <= lim.limited_by <= lim.value * 1.01, lim
    assert geometric_mean(1e-300, 1e-290) == pytest.approx(1e-295) and geometric_mean(2.0, 8.0) == 4.0


@pytest.mark.parametrize(
    "flag, value, mu",
    [("--resolution", "1e300", "2.55e+306 at K = 8.83e-301"), ("--coulomb", "1e300", "4.22e-300 at K = 5.33e+305")],
)
def test_stiffness_search_outside_the_mu_range_refused_up_front(capsys, flag, value, mu):
    # found: --resolution 1e300 printed 4 overflow warnings and "limited_by = 0.0 is invalid"; --coulomb 1e300
    # 17 LimitCycleSearchWarnings and "limited_by = inf is invalid"
    err = refused(capsys, "stiffness", "--device", "delta", "--velocity", "0.1", flag, value)
    assert f"where μ = m/(K T²) reaches {mu}: it must stay within 1e-150 … 1e+150" in err, err
    assert f"{flag.lstrip('-')} = {float(value):g}" in err


def test_design_answer_and_chart_refuse_their_ranges_before_any_work():
    from dataclasses import replace

    from dfa.analysis.limits.kmax import design_answer
    from dfa.analysis.limits.speed_chart import stiffness_speed_chart
    from dfa.model.catalogue import get_device

    dev = get_device("Delta").device
    with pytest.raises(DFAValueError, match="the stiffness search .* μ = m/\\(K T²\\) reaches"):
        design_answer(replace(dev, coulomb=1e300), 0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", dfa.ImplausibleInputWarning)
        with pytest.raises(DFAValueError, match="runs from K = 15 N/m to beyond the largest float"):
            stiffness_speed_chart(dev, stiffness=1e308, velocity=0.1)


def test_report_with_a_stiffness_beyond_the_chart_prints_one_line(capsys, tmp_path):
    # found: `dfa report ... --stiffness 1e308` printed 5 RuntimeWarning lines, then "stiffness = inf is invalid"
    out = tmp_path / "rep"
    err = refused(capsys, "report", "--device", "delta", "--velocity", "0.1", "--stiffness", "1e308", "--out", str(out))
    assert "the stiffness–speed chart" in err and "stiffness = 1e+308 N/m" in err and "inf" not in err
    assert not out.exists()


# ------------------------------------------------------------------ the API findings
@pytest.fixture(scope="module")
def saved_map(tmp_path_factory):
    m = dfa.stability_map(100.0, [1.0], grid=3, samples=200, n_jobs=1)
    path = m.save(tmp_path_factory.mktemp("map") / "m.npz")
    with np.load(path) as z:
        return path, dict(z)


@pytest.mark.parametrize(
    "change, says",
    [
        (lambda z: {"outcome": z["outcome"].astype(float)}, "its outcome array holds float64 values"),
        (lambda z: {"outcome": z["outcome"].astype(np.int64) + 10}, "its outcome array holds codes 10"),
        (lambda z: {"outcome": z["outcome"].astype(np.int64) - 1}, "its outcome array holds codes -1"),
        (lambda z: {"mu": np.float64("nan")}, "(mu = nan is invalid"),
        (lambda z: {"mu": np.array([1.0, 2.0])}, "(mu = <array of shape (2,)>"),
        (lambda z: {"xi_dots": np.array([np.inf])}, "(xi_dots = <array of shape (1,)> is invalid"),
        (lambda z: {"beta": z["beta"] * np.nan}, "(beta = <array of shape (3,)> is invalid"),
    ],
)
def test_load_map_validates_a_corrupted_file(saved_map, tmp_path, change, says):
    # found: an outcome array of floats raised IndexError, and a NaN mu loaded silently
    path, z = saved_map
    bad = tmp_path / "bad.npz"
    np.savez(bad, **{**z, **change(z)})
    with pytest.raises(DFAValueError, match="recompute it with `dfa map`") as err:
        dfa.load_map(bad)
    assert f"map file {str(bad)!r} is invalid" in str(err.value) and says in str(err.value)
    assert dfa.load_map(path).mu == 100.0


def test_stability_map_validates_mu_and_speeds_on_construction(saved_map):
    m = dfa.load_map(saved_map[0])
    from dataclasses import replace

    for field, value in (("mu", float("nan")), ("mu", 1 + 1j), ("xi_dots", (float("nan"),)), ("samples", 0)):
        with pytest.raises((DFAValueError, dfa.DFATypeError)):
            replace(m, **{field: value})


@pytest.mark.parametrize("kw", [{"amplitudes": np.array([])}, {"omega": np.array([])}])
def test_nyquist_locus_response_refuses_empty_arrays(kw):
    # found: amplitudes=np.array([]) raised numpy's "need at least one array to concatenate"
    p = dfa.Params(5.0, 0.1, 0.3)
    name = next(iter(kw))
    with pytest.raises(
        DFAValueError, match=f"{name} = <array of shape \\(0,\\)> is invalid: it must be an array of at"
    ):
        dfa.nyquist_locus_response(p, **kw)
    with pytest.raises(DFAValueError, match="locus_amplitude"):
        dfa.nyquist_locus_response(dfa.Params(5.0, 0.1, 0.0), locus_amplitude=[])


def test_numeric_df_refuses_what_quantizer_df_refuses():
    # found: numeric_df(f, 1e-320) returned inf where quantizer_df refuses the same amplitude
    def q(x):
        return math.floor(x) + 0.5

    for fn in (dfa.quantizer_df, lambda a: dfa.numeric_df(q, a)):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            with pytest.raises(DFAValueError, match="amplitude = 1e-320 is invalid: the describing function"):
                fn(1e-320)
    assert dfa.numeric_df(q, 1e-300) == pytest.approx(dfa.quantizer_df(1e-300), rel=1e-12)


def test_k_max_criterion_at_huge_speeds_is_its_limit_not_nan():
    from dfa.analysis.limits.closed_form import k_max_criterion

    # found: k_max_criterion(dev, 1e308) returned nan (b·ẋ0 and T·ẋ0 both overflow) or 2c/Δ (b·ẋ0 alone)
    for period in (1e-3, 4.0):
        dev = dfa.Device(mass=1.0, damping=2.0, coulomb=1.0, resolution=1e-5, period=period)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", dfa.ImplausibleInputWarning)
            k = k_max_criterion(dev, [1e308, 1e300, 0.1])
        assert np.all(np.isfinite(k)) and k[0] == pytest.approx(2.0 / (0.5 * period), rel=1e-9), k
        assert k[2] == (2.0 * 0.1 + 1.0) / (0.5 * period * 0.1 + 0.5e-5) * (1.0 - 1e-12)  # unchanged below
    huge = dfa.Device(mass=1.0, damping=2.0, coulomb=1e308, resolution=1e-5, period=1e-3)
    with pytest.raises(DFAValueError, match="K_max <= 2c/Δ overflows a float"):
        k_max_criterion(huge, 0.1)


@pytest.mark.parametrize(
    "field, value",
    [
        ("amplitude", float("nan")),
        ("frequency", 1 + 2j),
        ("loeb", np.array([1.0, 2.0])),
        ("loeb", float("nan")),
        ("residual", float("inf")),
        ("residual", -1.0),
        ("stable", "yes"),
        ("few_samples", 1),
        ("family", ["small"]),
    ],
)
def test_limit_cycle_validated_on_construction(field, value):
    good = dict(amplitude=1.5, frequency=0.4, stable=True, family="large", loeb=0.2, residual=1e-12)
    assert dfa.LimitCycle(**good).period == pytest.approx(2 * math.pi / 0.4)
    with pytest.raises((DFAValueError, dfa.DFATypeError), match=f"{field} = "):
        dfa.LimitCycle(**{**good, field: value})


def test_stiffness_for_a_group_that_overflows_is_refused():
    from dfa.model.catalogue import get_device

    dev = get_device("Delta").device
    # found: Device.stiffness_for_sigma(2.2e-313) returned inf
    for method, value, formula in (
        ("stiffness_for_sigma", 2.2e-313, "K = c/(σ Δ)"),
        ("stiffness_for_beta", 1e-310, "K = b/(β T)"),
        ("stiffness_for_mu", 2.3e-308, "K = m/(μ T²)"),
    ):
        with pytest.raises(DFAValueError, match=f"is invalid for this device: {re.escape(formula)} overflows a float"):
            getattr(dev, method)(value)
    assert dev.stiffness_for_sigma(0.5) == pytest.approx(2 * dev.coulomb / dev.resolution)


def test_contours_force_step_that_overflows_is_refused(capsys):
    # found: `dfa contours --device impulse --resolution 1e308` printed "force step KΔ = inf N" (σ = c/inf = 0)
    err = refused(capsys, "contours", "--device", "impulse", "--resolution", "1e308")
    assert "σ = c/(K Δ) cannot be formed (the force step K Δ overflows a float)" in err and "--resolution" in err
    dev = dfa.Device(mass=0.032, damping=0.02, coulomb=0.0, resolution=1e308, period=0.002)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", dfa.ImplausibleInputWarning)
        with pytest.raises(DFAValueError, match="force step K Δ overflows"):
            dev.params(80.0)  # c = 0: σ would be 0/inf = 0, the force step still inf


@pytest.mark.parametrize(
    "field, value",
    [
        ("mass", float("nan")),
        ("damping", 1 + 1j),
        ("coulomb", np.array([1.0, 2.0])),
        ("stiffness", -1.0),
        ("rotary", "no"),
        ("name", 3),
        ("printed", (("mu", "nan"),)),
        ("printed", [("mu", "1")]),
    ],
)
def test_catalogue_entry_validated_on_construction(field, value):
    from dfa.model.catalogue import CatalogueEntry

    good = dict(name="pen", kind="haptic device", source="s", notes="", mass=0.1, damping=0.01, coulomb=0.02)
    good |= dict(resolution=1e-5, period=1e-3, stiffness=1000.0, printed=(("mu", "100"),))
    assert CatalogueEntry(**good).params is not None
    with pytest.raises((DFAValueError, dfa.DFATypeError), match=f"{field}"):
        CatalogueEntry(**{**good, field: value})


@pytest.mark.parametrize(
    "field, value", [("recomputed", float("nan")), ("relative", 1j), ("parameter", "zeta"), ("printed", 0.3)]
)
def test_discrepancy_validated_on_construction(field, value):
    from dfa.model.catalogue import Discrepancy

    good = dict(parameter="mu", printed="0.3", recomputed=0.31, relative=0.0333)
    assert str(Discrepancy(**good)).startswith("mu: printed 0.3")
    with pytest.raises((DFAValueError, dfa.DFATypeError), match=f"{field}"):
        Discrepancy(**{**good, field: value})
