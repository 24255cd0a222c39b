"""Deferred kernels (dfa.core.jit): numba loads on the first call, and the compiled code is the Python code."""

from __future__ import annotations

import math
import pickle

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from dfa.core import divdiff, exprel, jit, zohlag


def test_deferred_kernel_pickles_to_the_module_own_kernel():
    # joblib's workers receive kernels by name: the unpickled object is the module's own, not a copy
    assert pickle.loads(pickle.dumps(exprel.phi1)) is exprel.phi1
    assert repr(exprel.phi1) == "Deferred(dfa.core.exprel.phi1)"
    assert exprel.phi1.__doc__ == exprel.phi1.py_func.__doc__


def test_a_kernel_bound_under_another_name_pickles_to_a_deferred_of_its_function():
    from dfa.core import kernel

    back = pickle.loads(pickle.dumps(kernel._spring))  # njit(...)(spring_energy_core): not the module's own name
    assert isinstance(back, jit.Deferred) and back.py_func is kernel._spring.py_func
    assert back.targetoptions == kernel._spring.targetoptions


def test_threads_calling_a_kernel_first_share_one_dispatcher():
    import concurrent.futures

    fresh = jit.njit(cache=False)(exprel.phi1.py_func)
    with concurrent.futures.ThreadPoolExecutor(8) as pool:
        got = list(pool.map(lambda _: fresh.dispatcher, range(8)))
    assert all(d is got[0] for d in got) and fresh(0.25) == exprel.phi1(0.25)


@settings(max_examples=300)
@given(st.floats(min_value=-30.0, max_value=1e6, allow_nan=False))
def test_exprel_compiled_equals_its_python_source_bit_for_bit(u):
    """One implementation: numba compiles the Python source unchanged, so both give the same bits."""
    for f in (exprel.phi1, exprel.phi2, exprel.log1p_ratio):
        if f is exprel.log1p_ratio and u <= -1.0:
            continue
        assert f(u) == f.py_func(u)
    if u >= 0.0:
        for f in (exprel.psi, exprel.chi):
            assert f(u) == f.py_func(u)


def test_a_compiled_kernel_calls_a_deferred_one_that_is_not_inlined():
    # amplifier_zoh (compiled) calls exp_dd (deferred, not inlined): numba types it through jit's registration
    a, b = 0.3, 0.7
    got = zohlag.amplifier_zoh(a, b)
    assert all(math.isfinite(v) for v in got)
    x = np.array([0.0, -a, -b])
    assert divdiff.exp_dd(x) == divdiff.exp_dd.py_func(x) or math.isclose(
        divdiff.exp_dd(x), divdiff.exp_dd.py_func(x), rel_tol=1e-15
    )


def test_when_numba_loads_runs_now_once_numba_is_loaded_and_withdraw_is_harmless():
    exprel.phi1(0.1)  # a kernel has run: numba is loaded
    seen: list[object] = []
    withdraw = jit.when_numba_loads(seen.append)
    withdraw()
    assert len(seen) == 1 and seen[0].__name__ == "numba"


_QUICK_CASES = "[('delta', {}, 0.1), ('phantom', {'damping': 1.0}, 0.1), ('impulse', {'delay': 1}, 0.05)]"
_QUICK_SCRIPT = f"""
import json, sys
import dfa
from dfa.analysis.limits.kmax import design_answer
from dfa.core.jit import interpreted
from dfa.model.loop import Loop
from dfa.model.wall import Wall

from dfa.cli import main

with interpreted():
    out = [design_answer(Loop(dfa.get_device(n).device, Wall.of(1.0, **w)), v, simulate=False).to_dict()
           for n, w, v in {_QUICK_CASES}]
assert main(["stiffness", "--device", "delta", "--velocity", "0.1", "--quick", "--json"]) == 0  # its own block
print(json.dumps({{"numba": "numba" in sys.modules, "answers": out}}))
"""


def _numbers_close(a, b, path="") -> None:
    """The same JSON, every number within 1e-12 relative (interpreted and compiled run the same source)."""
    if isinstance(a, dict):
        assert a.keys() == b.keys(), path
        for k in a:
            _numbers_close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), path
        for i, (x, y) in enumerate(zip(a, b, strict=True)):
            _numbers_close(x, y, f"{path}[{i}]")
    elif isinstance(a, float) and isinstance(b, float):
        assert math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-300) or (math.isnan(a) and math.isnan(b)), (path, a, b)
    else:
        assert a == b, (path, a, b)


def test_interpreted_quick_answer_equals_the_compiled_one_and_never_loads_numba():
    """``dfa stiffness --quick``'s work (eq. 6, 11, the exact linear bound, the describing function's limit) run
    interpreted in a fresh process: numba never loads, and every number equals the compiled answer's here."""
    import ast
    import json
    import subprocess
    import sys

    import dfa
    from dfa.analysis.limits.kmax import design_answer
    from dfa.model.loop import Loop
    from dfa.model.wall import Wall

    done = subprocess.run([sys.executable, "-c", _QUICK_SCRIPT], capture_output=True, text=True, check=True)
    got = json.loads(done.stdout.splitlines()[-1])
    assert got["numba"] is False
    for (name, wall, v), answer in zip(ast.literal_eval(_QUICK_CASES), got["answers"], strict=True):
        compiled = design_answer(Loop(dfa.get_device(name).device, Wall.of(1.0, **wall)), v, simulate=False)
        exprel.phi1(0.5)  # compiled here: the comparison is against numba's code
        _numbers_close(answer, json.loads(json.dumps(compiled.to_dict())))
        assert answer["k_df"]["value"] > 0  # a describing-function limit was found, interpreted


def test_interpreted_block_past_its_budget_runs_compiled_and_a_raising_call_runs_compiled():
    fresh = jit.njit(cache=False)(exprel.phi1.py_func)
    with jit.interpreted(budget=2):
        assert fresh(0.25) == exprel.phi1(0.25) and fresh._dispatcher is None  # interpreted
        fresh(0.5)
        assert fresh._dispatcher is None
        fresh(0.75)  # the budget spent: compiled from here
        assert fresh._dispatcher is not None

    def inverse(x):
        return 1.0 / x  # Python raises ZeroDivisionError; numba's error_model="numpy" returns inf

    inv = jit.njit(cache=False, error_model="numpy")(inverse)
    with jit.interpreted():
        assert inv(0.0) == math.inf and inv._dispatcher is not None
    assert jit._INTERPRET_CALLS[0] == 0  # the block closed
