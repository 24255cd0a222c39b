"""Describing functions (paper section 7): quantizer eq. 41 and Coulomb friction eq. 38-40."""

import functools
import math
import warnings

import control
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import dfa
from dfa.analysis.describing import (
    DF_ENVELOPE,
    coulomb_df,
    coulomb_df_expression,
    coulomb_equivalent_damping,
    numeric_df,
    quantizer_df,
    quantizer_df_derivative,
    quantizer_df_expression,
    quantizer_df_inverse,
    quantizer_df_peak,
)
from dfa.analysis.nonlinearities import CoulombNonlinearity, QuantizerNonlinearity


def eq41(m):
    """Eq. 41 typed in from the paper, as an independent reference."""
    n = int(math.floor(m))
    return 2 / (math.pi * m) + 4 / (math.pi * m) * sum(math.sqrt(1 - (k / m) ** 2) for k in range(1, n + 1))


def staircase(x):
    return math.floor(x) + 0.5


M_GRID = np.concatenate([np.geomspace(0.05, 50, 300), np.arange(1, 51) + 1e-7, np.arange(1, 51) - 1e-7])


def test_eq41_sympy_lambdified_equals_paper_formula():
    got = quantizer_df(M_GRID)
    ref = np.array([eq41(m) for m in M_GRID])
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-13)


def test_eq41_symbolic_expression_evaluates_to_the_same():
    expr = quantizer_df_expression()
    (M,) = expr.free_symbols
    for m in ["1/2", "3/2", "7/3", "10"]:
        val = float(expr.subs(M, sp.Rational(m)).doit().evalf(30))
        assert val == pytest.approx(quantizer_df(float(sp.Rational(m))), rel=1e-14)


def test_eq41_matches_numeric_quadrature_to_1e9():
    ms = np.geomspace(0.05, 50, 120)
    num = numeric_df(staircase, ms, jumps=range(1, 51))
    assert np.max(np.abs(num - quantizer_df(ms))) <= 1e-9


def test_eq41_matches_adaptive_quadrature_without_breakpoints():
    # the generic quadrature, not told where the staircase jumps, still agrees (looser)
    ms = np.array([0.3, 1.7, 4.2])
    assert np.max(np.abs(numeric_df(staircase, ms) - quantizer_df(ms))) <= 1e-6


def test_eq41_small_cycles_are_two_over_pi_m():
    ms = np.linspace(0.01, 1.0, 50)
    np.testing.assert_allclose(quantizer_df(ms), 2 / (np.pi * ms), rtol=1e-14)


def test_eq41_continuous_at_integers():
    n = np.arange(1, 60, dtype=float)
    assert np.max(np.abs(quantizer_df(n + 1e-10) - quantizer_df(n - 1e-10))) < 1e-4


def test_eq41_peak_and_limit():
    m, d = quantizer_df_peak()
    assert m == pytest.approx(1.242, abs=1e-3) and d == pytest.approx(1.1206, abs=1e-4)
    assert quantizer_df(1e5) == pytest.approx(1.0, abs=1e-6)
    ms = np.geomspace(1.0, 200, 5000)  # for M < 1, D = 2/(πM) grows without bound
    assert np.max(quantizer_df(ms)) <= d + 1e-12


def test_eq41_envelope_bounds_every_excursion_from_one():
    ms = np.concatenate([np.linspace(1, 30, 20000), np.linspace(30, 2000, 20000)])
    excursion = np.abs(quantizer_df(ms) - 1) * np.floor(ms) ** 1.5
    assert np.max(excursion) <= DF_ENVELOPE
    assert np.max(excursion) > 0.37  # the bound is tight: 1 − D(n) → 0.3743 n^{-3/2}


def test_eq41_derivative_matches_finite_differences():
    ms = np.array([0.4, 1.3, 2.5, 7.7, 20.2])
    h = 1e-6
    fd = (quantizer_df(ms + h) - quantizer_df(ms - h)) / (2 * h)
    np.testing.assert_allclose(quantizer_df_derivative(ms), fd, rtol=1e-6)


@functools.lru_cache(maxsize=1)
def dense_df():
    ms = np.linspace(0.05, 40.0, 400001)
    return ms, quantizer_df(ms)


@given(st.floats(0.5, 1.12))
def test_eq41_inverse_finds_every_root(g):
    roots, complete = quantizer_df_inverse(g, max_amplitude=40.0)
    assert np.all(np.abs(quantizer_df(roots) - g) < 1e-11)
    # brute force: sign changes of D − g on a dense grid (roots closer than the grid step may pair up)
    _ms, d = dense_df()
    s = np.sign(d - g)
    brute = int(np.sum(s[:-1] * s[1:] < 0))
    assert len(roots) >= brute
    assert len(roots) - brute in (0, 2, 4) or not complete


def test_eq41_inverse_reports_incomplete_search_near_one():
    roots, complete = quantizer_df_inverse(1.0, max_amplitude=30.0)
    assert not complete and len(roots) >= 50


def test_eq40_coulomb_symbolic_and_numeric():
    A, sig = sorted(coulomb_df_expression().free_symbols, key=str)
    assert sp.simplify(coulomb_df_expression() - 4 * sig / (sp.pi * A)) == 0
    amps = np.geomspace(0.01, 100, 60)
    num = numeric_df(lambda v: 0.7 * np.sign(v), amps, jumps=())
    assert np.max(np.abs(num - coulomb_df(amps, 0.7))) <= 1e-9
    assert coulomb_equivalent_damping(0.7, 2.0, 0.25) == pytest.approx(4 * 0.7 / (np.pi * 2.0 * 0.25))


def test_python_control_uses_our_exact_describing_functions():
    q = QuantizerNonlinearity()
    np.testing.assert_allclose(np.real(control.describing_function(q, M_GRID)), quantizer_df(M_GRID), rtol=1e-14)
    c = CoulombNonlinearity(0.4)
    np.testing.assert_allclose(np.real(control.describing_function(c, [0.5, 2.0])), coulomb_df([0.5, 2.0], 0.4))


def test_python_control_generic_numeric_df_error_is_documented():
    """python-control's own numeric DF (100-point rule) on the staircase: max error ≈ 0.032, median ≈ 0.002."""
    ms = np.geomspace(0.05, 50, 400)
    err = np.abs(np.real(control.describing_function(QuantizerNonlinearity(), ms, try_method=False)) - quantizer_df(ms))
    assert 0.01 < np.max(err) < 0.05
    assert 5e-4 < np.median(err) < 5e-3


def test_python_control_response_tools_accept_our_nonlinearity():
    p = dfa.Params(5.0, 0.4, 0.0)
    H = dfa.analysis.loop.loop_system(p, model="pade", pade_order=6)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        resp = control.describing_function_response(
            H, QuantizerNonlinearity(), np.linspace(0.3, 3, 200), omega=np.geomspace(1e-2, np.pi, 2000)
        )
    ours = dfa.analysis.loop.nyquist_locus_response(p).crossings
    assert len(resp.intersections) == len(ours) == 2
    for (a, w), (m, w2, _pt) in zip(sorted(resp.intersections), ours, strict=False):
        assert a == pytest.approx(m, rel=1e-4) and w == pytest.approx(w2, rel=1e-4)
    import matplotlib

    matplotlib.use("Agg")
    out = control.describing_function_plot(resp)
    assert out is not None


@pytest.mark.parametrize("bad", [0.0, -1.0, math.nan, math.inf])
def test_describing_functions_reject_bad_amplitude(bad):
    with pytest.raises(dfa.DFAValueError, match="amplitude"):
        quantizer_df(bad)
    with pytest.raises(dfa.DFAValueError, match="amplitude"):
        coulomb_df(bad, 0.5)
    with pytest.raises(dfa.DFAValueError, match="omega"):
        coulomb_equivalent_damping(0.5, 1.0, bad)
    with pytest.raises(dfa.DFAValueError, match="sigma"):
        CoulombNonlinearity(-0.1)


# ---------------------------------------------------- compiled core (dfa.core.dfcore)
amplitudes_st = st.one_of(
    st.floats(1e-3, 400.0),
    st.builds(lambda n, e: n + e, st.integers(1, 300), st.floats(-1e-9, 1e-9)),  # next to an integer
)


@settings(max_examples=200)
@given(amplitudes_st)
def test_eq41_compiled_core_equals_sympy_lambdified(m):
    from dfa.core import dfcore

    assert dfcore.df_value(m) == pytest.approx(quantizer_df(m), rel=1e-14)
    # D' cancels near an integer (the √ terms grow like 1/√(M − k)): compare with a tolerance that admits it
    assert dfcore.df_derivative(m) == pytest.approx(quantizer_df_derivative(m), rel=1e-9, abs=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3, 7, 40, 400])
def test_eq41_compiled_interval_peak_matches_scipy_and_zero_slope(n):
    from scipy import optimize

    from dfa.core import dfcore

    mp, dp = dfcore.interval_peak(n)
    ref = optimize.minimize_scalar(
        lambda x: -quantizer_df(x), bounds=(n, n + 1.0), method="bounded", options={"xatol": 1e-10}
    )
    assert dp == pytest.approx(-ref.fun, rel=1e-14)
    assert abs(mp - ref.x) < 1e-5  # D is flat at its peak: the location is known to ~√eps
    assert abs(quantizer_df_derivative(mp)) < 1e-6 * abs(quantizer_df_derivative(n + 0.9))
    assert n + 0.2 < mp < n + 0.32  # maxima near n + 0.30, at 1.242 on [1, 2] (module docstring)


@settings(max_examples=100)
@given(st.floats(0.65, 1.12))
def test_eq41_compiled_inverse_agrees_with_scipy_brentq_on_every_bracket(g):
    """The compiled Brent (a port of scipy's) converges to the roots scipy's brentq finds on the same brackets."""
    from scipy import optimize

    roots, _complete = quantizer_df_inverse(g, max_amplitude=60.0)
    big = roots[roots > 1.0]
    for r in big:
        n = math.floor(r)
        # bracket the root by the interval's monotone branch, from the independent scipy peak
        peak = optimize.minimize_scalar(
            lambda x: -quantizer_df(x), bounds=(n, n + 1.0), method="bounded", options={"xatol": 1e-12}
        ).x
        lo, hi = (n, peak) if r < peak else (peak, n + 1.0)
        f = lambda x: quantizer_df(x) - g
        if f(lo) * f(hi) > 0:  # root within the peak's flat top: both agree to the peak's precision
            assert abs(r - peak) < 1e-5
            continue
        ref = optimize.brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps)
        assert r == pytest.approx(ref, rel=1e-11)
