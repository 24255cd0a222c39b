"""Non-finite numbers and numpy's warnings (issue 27 §2): no inf or NaN printed as an answer, one line per refusal.

Each finding of the fuzz is reproduced first (the exact argv or call), then the fix is checked: the input is refused
up front with the package's error (one line on stderr, exit 2, naming the value, the rule and the fix), or the
answer is finite.
"""

import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import dfa
from dfa.analysis.simulation import default_samples, simulate_batch
from dfa.cli import main
from dfa.errors import DFAValueError

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
    assert p.stderr.count("\n") == 1 and p.stderr.startswith("dfa: error: xi_dot = 1e+300"), p.stderr
    assert "overflows a float" in p.stderr


def test_cli_runtime_warnings_of_a_run_become_one_line_at_the_end():
    p = run_dfa("limit-cycles", "--mu", "1e300", "--beta", "0", "--sigma", "2")
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
    assert err.startswith("dfa: error: --beta = 1e+308 is invalid with --mu = 1: β/μ = bT/m must be at most 1e+08")
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
        "dfa: error: --beta = 1e+308, --sigma = 1, --xi-dot = 2 are invalid together: the criterion's"
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
