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
