"""Input rules (dfa.checks): one function and one message per rule, whichever entry point is called."""

from __future__ import annotations

import inspect

import pytest

import dfa
import dfa.errors
from dfa import checks
from dfa.analysis.cycles import large_cycle_closed_forms, small_cycle_closed_forms
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import simulate


def _message(fn, *args, **kwargs) -> str:
    with pytest.raises(dfa.DFAValueError) as err:
        fn(*args, **kwargs)
    return str(err.value)


@pytest.mark.parametrize("bad", [1.0, 0.5])
def test_growth_rule_reads_the_same_in_simulate_and_stability_map(bad):
    expected = _message(checks.check_growth, bad)
    assert "growth = " in expected and "> 1" in expected
    assert _message(simulate, 5.0, 0.1, 0.6, 1.0, samples=10, growth=bad) == expected
    assert _message(stability_map, 5.0, [1.0], grid=2, samples=10, growth=bad, n_jobs=1, progress=False) == expected


def test_bound_rule_reads_the_same_in_simulate_and_stability_map():
    assert _message(simulate, 5.0, 0.1, 0.6, 1.0, samples=10, bound=-1.0) == _message(checks.check_bound, -1.0)
    assert _message(stability_map, 5.0, [1.0], grid=2, samples=10, bound=0.0, n_jobs=1, progress=False) == _message(
        checks.check_bound, 0.0
    )
    # beyond the initial position, in the simulator and in a preload map alike
    expected = _message(checks.check_bound, 2.0, 3.0)
    assert _message(simulate, 5.0, 0.1, 0.6, 0.0, xi0=3.0, samples=10, bound=2.0) == expected
    pre = _message(stability_map, 5.0, [5.0], grid=2, samples=10, bound=2.0, preload=True, n_jobs=1, progress=False)
    assert pre.startswith("bound = 2.0 is invalid: it must be > |xi0| = ")


def test_jobs_rule_is_one_function():
    from dfa.analysis import maps

    assert maps.check_jobs is checks.check_jobs
    assert _message(stability_map, 5.0, [1.0], grid=2, samples=10, n_jobs=0, progress=False) == _message(
        checks.check_jobs, "n_jobs", 0
    )


@pytest.mark.parametrize(
    "name, bad, scalar",
    [("mu", 0.0, checks.check_mu), ("beta", -1.0, checks.check_beta), ("sigma", -2.0, checks.check_sigma)],
)
def test_table1_rules_read_the_same_for_arrays(name, bad, scalar):
    args = {"mu": 5.0, "beta": [0.1, 0.2], "sigma": [0.1, 0.2]}
    args[name] = [0.3, bad] if name != "mu" else [5.0, bad]
    expected = _message(scalar, bad)
    assert _message(small_cycle_closed_forms, args["mu"], args["beta"], args["sigma"]) == expected
    assert _message(large_cycle_closed_forms, args["mu"], args["beta"], args["sigma"]) == expected
    assert _message(dfa.Params, **{"mu": 5.0, "beta": 0.1, "sigma": 0.1, name: bad}) == expected


def test_errors_module_holds_exception_types_only():
    defined = [v for k, v in vars(dfa.errors).items() if not k.startswith("_") and inspect.getmodule(v) is dfa.errors]
    assert defined and all(isinstance(v, type) and issubclass(v, Exception) for v in defined)
    assert set(dfa.errors.__all__) == {
        "DFAError", "DFAValueError", "DFATypeError", "DeviceFileError", "ImplausibleInputWarning"
    }  # fmt: skip
    assert all(inspect.getmodule(getattr(checks, n)) is checks for n in checks.__all__ if callable(getattr(checks, n)))


def test_positive_array_rule_reads_the_same_for_amplitudes_and_frequencies():
    from dfa.analysis.describing import coulomb_equivalent_damping, quantizer_df
    from dfa.analysis.loop import loop_response

    rule = "is invalid: it must be a finite number > 0; give "
    assert _message(quantizer_df, [1.0, -1.0]).startswith("amplitude = -1.0 " + rule)
    assert _message(coulomb_equivalent_damping, 0.5, 1.0, 0.0).startswith("omega = 0.0 " + rule)
    assert _message(loop_response, dfa.Params(5.0, 0.1, 0.0), [0.1, float("nan")]).startswith("omega = nan " + rule)
