"""ω(M) on a phase-curve piece (eq. 36, V = 0): the compiled elementwise bracketing solver (dfa.core.bracket).

Checked against scipy's elementwise ``find_root`` (an independent solver with the same tolerances), against
roots known in closed form, element by element against the same elements solved one at a time (the Z-width's
describing-function search relies on it: ω(M) is solved once per amplitude, in whatever batch), and through the
limit-cycle search: the cycles with the solver are those with ``find_root``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize.elementwise import find_root

import dfa
import dfa.analysis.cycles.phase as phase
from dfa.analysis.cycles import limit_cycles
from dfa.analysis.cycles.characteristic import HarmonicLoop
from dfa.analysis.cycles.phase import PieceOmega, phase_pieces
from dfa.core import bracket, jit
from dfa.core.bracket import MAX_STEPS, bracketed_roots
from dfa.model.wall import WallParams

EPS = float(np.finfo(float).eps)
TINY = float(np.finfo(float).tiny)

roots = st.floats(-1e6, 1e6, allow_nan=False).filter(lambda r: abs(r) > 1e-6)
widths = st.floats(1e-9, 10.0)
kinks = st.floats(0.0, 50.0)


def _cubic(x: np.ndarray, r: np.ndarray, c: np.ndarray) -> np.ndarray:
    """(x − r)(1 + c (x − r)²): one simple root at r, its sign exact near r (x − r is exact there)."""
    d = x - r
    return d * (1.0 + c * d * d)


@settings(deadline=None)
@given(st.lists(st.tuples(roots, widths, widths, kinks), min_size=1, max_size=40))
def test_eq36_bracketed_roots_bracket_the_known_root_to_find_roots_tolerance(cases):
    """Each root lies within find_root's tolerance 4·tiny + 4·eps·|x| of the true root r (the sign of f is exact
    near r), and within twice that of scipy's own root."""
    r, below, above, c = (np.array(v) for v in zip(*cases, strict=True))
    lo, hi = r - below * np.maximum(1.0, abs(r)), r + above * np.maximum(1.0, abs(r))
    x, ok = bracketed_roots(_cubic, lo, hi, _cubic(lo, r, c), _cubic(hi, r, c), (r, c))
    assert ok.all()
    tol = 4.0 * TINY + 4.0 * EPS * np.abs(x)
    assert (np.abs(x - r) <= tol).all()
    ref = find_root(_cubic, (lo, hi), args=(r, c))
    assert (ref.status == 0).all()
    assert (np.abs(x - ref.x) <= 2.0 * tol).all()


@settings(deadline=None)
@given(st.lists(st.tuples(roots, widths, widths, kinks), min_size=2, max_size=40), st.randoms(use_true_random=False))
def test_eq36_bracketed_roots_of_a_batch_are_those_of_each_element_alone(cases, rnd):
    """Elementwise: an element's root does not depend on the elements solved beside it, bit for bit (PieceOmega
    solves each amplitude once, in whichever run asks first)."""
    r, below, above, c = (np.array(v) for v in zip(*cases, strict=True))
    lo, hi = r - below * np.maximum(1.0, abs(r)), r + above * np.maximum(1.0, abs(r))
    x, _ = bracketed_roots(_cubic, lo, hi, _cubic(lo, r, c), _cubic(hi, r, c), (r, c))
    order = list(range(len(cases)))
    rnd.shuffle(order)
    shuffled, _ = bracketed_roots(
        _cubic, hi[order], lo[order], _cubic(hi[order], r[order], c[order]), _cubic(lo[order], r[order], c[order]),
        (r[order], c[order]),
    )  # fmt: skip
    np.testing.assert_array_equal(shuffled, x[order])
    for i in range(len(cases)):
        one, _ = bracketed_roots(_cubic, lo[i : i + 1], hi[i : i + 1], _cubic(lo[i : i + 1], r[i], c[i]),
                                 _cubic(hi[i : i + 1], r[i], c[i]), (r[i : i + 1], c[i : i + 1]))  # fmt: skip
        assert one[0] == x[i]


def test_eq36_bracketed_roots_failures_are_nan_never_an_end():
    """No sign change, a non-finite end or a NaN inside: NaN and not converged; a zero at an end is that end."""
    lo, hi = np.array([1.0, 1.0, 0.0, 2.0, np.nan]), np.array([2.0, 2.0, 4.0, 3.0, 1.0])

    def f(x: np.ndarray, k: np.ndarray) -> np.ndarray:
        return np.where(k == 2.0, np.nan, x - 2.0)  # element 2: NaN inside its bracket

    k = np.arange(5.0)
    x, ok = bracketed_roots(f, lo, hi, np.array([1.0, -1.0, -2.0, 0.0, 1.0]), np.array([3.0, 0.0, 2.0, 1.0, -1.0]),
                            (k,))  # fmt: skip
    assert ok.tolist() == [False, True, False, True, False]
    assert math.isnan(x[0]) and x[1] == 2.0 and math.isnan(x[2]) and x[3] == 2.0 and math.isnan(x[4])


def test_eq36_bracketed_roots_close_a_wide_bracket_by_bisection_within_the_step_budget():
    """The secant alone would crawl on f = x¹⁰ − 1 from [0, 1e3] (one end kept); the bisection safeguard closes it."""
    f = lambda x: x**10 - 1.0
    lo, hi = np.array([0.0]), np.array([1e3])
    calls = []

    def counted(x: np.ndarray) -> np.ndarray:
        calls.append(x.size)
        return f(x)

    x, ok = bracketed_roots(counted, lo, hi, f(lo), f(hi))
    assert ok[0] and abs(x[0] - 1.0) <= 8 * EPS
    assert len(calls) < MAX_STEPS // 4


def _loop(mu: float, beta: float, sigma: float, damping: float, delay: int, model: str) -> HarmonicLoop:
    return HarmonicLoop(
        dfa.Params(mu, beta, sigma), model, delay, 4, "exact", WallParams.of(damping=damping, delay=delay)
    )


loops = st.tuples(
    st.floats(0.5, 500.0), st.floats(0.0, 0.5), st.floats(0.05, 0.9), st.floats(0.01, 1.0), st.integers(0, 2),
    st.sampled_from(["half-delay", "pade"]),
)  # fmt: skip


@settings(deadline=None, max_examples=25)
@given(loops)
def test_eq36_omega_of_m_is_find_roots_to_rounding_and_one_per_amplitude(case):
    """ω(M) on every piece of a wall's phase curve: within 1e-12 (relative) of scipy's find_root on V(M, ω) = 0 (the
    two differ at rounding level, where V is flat to rounding: up to ~100 ulps seen), and each amplitude's ω is the
    same bit for bit whether solved with the others or alone."""
    lp = _loop(*case)
    for ws, ms in phase_pieces(lp):
        finite = np.isfinite(ms)
        if finite.sum() < 2:
            continue
        m = np.geomspace(max(float(ms[finite].min()), 1e-9), float(ms[finite].max()), 25)
        omega = PieceOmega(lp, ws, ms)
        w = omega(m)
        wa, wb = omega._brackets(m)
        va, vb = lp.inv(m, wa).imag, lp.inv(m, wb).imag
        change = (va != 0.0) & (vb != 0.0) & ((va < 0) != (vb < 0))
        ref = find_root(lambda x, mm: lp.inv(mm, x).imag, (wa[change], wb[change]), args=(m[change],))
        ok = ref.status == 0
        np.testing.assert_allclose(w[change][ok], ref.x[ok], rtol=1e-12, atol=0.0)
        for i in range(0, m.size, 6):
            assert PieceOmega(lp, ws, ms)(m[i : i + 1])[0] == w[i] or (math.isnan(w[i]))


def _find_root_omega(lp: HarmonicLoop, m: np.ndarray, wa: np.ndarray, wb: np.ndarray) -> np.ndarray:
    """ω(M) by scipy's find_root (the solver of before), the same end rule."""
    va, vb = lp.inv(m, wa).imag, lp.inv(m, wb).imag
    end = np.where(np.abs(va) <= np.abs(vb), wa, wb)
    no_change = (va == 0.0) | (vb == 0.0) | ((va < 0) == (vb < 0))
    if no_change.all():
        return end
    res = find_root(lambda w, mm: lp.inv(mm, w).imag, (wa, wb), args=(m,))
    return np.where(no_change, end, np.where(res.status == 0, res.x, np.nan))


@pytest.mark.parametrize(
    ("mu", "beta", "sigma", "damping", "delay", "model"),
    [(20.0, 0.1, 0.3, 0.0, 0, "half-delay"), (5.0, 0.05, 0.8, 0.2, 1, "pade"), (200.0, 0.02, 0.4, 0.5, 2, "half-delay"),
     (2.0, 0.0, 0.6, 0.05, 0, "half-delay"), (50.0, 0.3, 0.1, 1.0, 1, "pade")],
)  # fmt: skip
def test_eq36_limit_cycles_with_the_compiled_solver_are_those_with_find_root(monkeypatch, mu, beta, sigma, damping,
                                                                             delay, model):  # fmt: skip
    """The search's cycles, status and bound are the same with either ω(M) solver: ω only places the scan's
    samples and brackets; each root is refined by the scalar path (Brent on the scalar loop inverse)."""
    wall = WallParams.of(damping=damping, delay=delay)
    ours = limit_cycles(dfa.Params(mu, beta, sigma), wall=wall, model=model)
    monkeypatch.setattr(phase, "_omega_for_m", _find_root_omega)
    theirs = limit_cycles(dfa.Params(mu, beta, sigma), wall=wall, model=model)
    assert ours.status == theirs.status and ours.search_bound == theirs.search_bound
    assert [(c.amplitude, c.frequency, c.stable) for c in ours.cycles] == [
        (c.amplitude, c.frequency, c.stable) for c in theirs.cycles
    ]


@settings(deadline=None)
@given(st.lists(st.tuples(roots, widths, widths, kinks), min_size=1, max_size=40))
def test_eq36_bracketed_roots_interpreted_steps_are_the_compiled_ones_bit_for_bit(cases):
    """The array form of a step (an interpreted run, ``dfa stiffness --quick``: no numba) gives the compiled
    kernel's roots bit for bit."""
    r, below, above, c = (np.array(v) for v in zip(*cases, strict=True))
    lo, hi = r - below * np.maximum(1.0, abs(r)), r + above * np.maximum(1.0, abs(r))
    args = (_cubic, lo, hi, _cubic(lo, r, c), _cubic(hi, r, c), (r, c))
    compiled, _ = bracketed_roots(*args)
    assert bracket.bracket_step._dispatcher is not None
    with jit.interpreted():
        assert jit.interpreting(bracket.bracket_step) is False  # compiled already: stays compiled
    fresh = jit.njit(cache=False)(bracket.bracket_step.py_func)
    with jit.interpreted():
        assert jit.interpreting(fresh)
    real = bracket.bracket_step
    try:
        bracket.bracket_step = fresh  # not compiled: bracketed_roots takes the array form
        with jit.interpreted():
            arrays, _ = bracketed_roots(*args)
        assert fresh._dispatcher is None
    finally:
        bracket.bracket_step = real
    np.testing.assert_array_equal(arrays, compiled)
