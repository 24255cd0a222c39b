"""The wall's kernel table (issue 42): every element declares its block, a table of one element runs that element.

1. Every registered element (``dfa.model.elements.ELEMENTS``) declares a kernel block with its own code, the code
   :mod:`dfa.core.table` names after it, and as many parameters as the code's block carries.
2. A table holding one element alone decodes to that element's run: an element neutral in the command (a filter
   without a damper, a zero push, hand, lag) runs bit for bit the spring's kernel (eq. 4-5 with the delay); the
   delay and the damper bit for bit the plain compiled loop of ``tests/reference_ctl.py`` (``controller_run``, the
   same exact step); the lag, the hand, the one-sided wall, the push and the passivity controller the numerical
   reference of the same file (``simulate_ivp_ctl``, DOP853 at rtol 1e-12) to 1e-8 of the run's scale.
3. An unknown code is refused: by :func:`dfa.core.table.check_table` (a DFAValueError naming the block, the code and
   the codes known) before any kernel call, and by the compiled decoder itself.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from reference_ctl import controller_run, simulate_ivp_ctl

from dfa.core import kernel, table, wall_kernel
from dfa.errors import DFAValueError
from dfa.model.elements import (
    ELEMENTS,
    AmplifierLag,
    Damper,
    Delay,
    ForceLimit,
    HandSpring,
    OneSided,
    PassivityController,
    Push,
    Travel,
    VelocityFilter,
)
from dfa.model.wall import WallParams

#: A group of each element that changes the loop (the one-sided wall's surface in ticks; the controller's (W, f_max)).
GROUPS = {
    Delay: 2, Damper: 0.7, VelocityFilter: 0.05, AmplifierLag: 0.3, HandSpring: 0.08, OneSided: 0.25, Push: 0.4,
    PassivityController: (8, 2.0), ForceLimit: 3.0, Travel: 40.0,
}  # fmt: skip
E = np.empty(0)


def _run(wall: WallParams, mu: float, beta: float, sigma: float, x0: float, v0: float, n: int):
    """(done, rest, ξ, ξ', stats) of the wall kernel given the wall's table, recorded."""
    rx, rv, st = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    done, rest = wall_kernel.simulate_wall_kernel((mu, beta, sigma), (x0, v0), (n, n // 4, 1e6, True),
                                                  wall.kernel_table(), rx, rv, st)  # fmt: skip
    return done, rest, rx, rv, st


def test_every_element_declares_a_block_with_its_own_code():
    codes = [k.kernel_code for k in ELEMENTS]
    assert len(set(codes)) == len(ELEMENTS) == len(table.CODES)
    assert set(GROUPS) == set(ELEMENTS)
    for k in ELEMENTS:
        assert table.CODES[k.kernel_code] == k.__name__
        block = k.kernel_block(GROUPS[k])
        assert block.code == k.kernel_code and len(block.params) == table.BLOCK_PARAMS[block.code]
        assert all(isinstance(p, float) for p in block.params) and block.state >= 0
        t = WallParams(((k, GROUPS[k]),)).kernel_table()  # one element alone: [1, code, m, state, params]
        assert t.tolist() == [1.0, float(block.code), float(len(block.params)), float(block.state), *block.params]


def test_table_layout_of_a_full_wall_in_the_walls_order():
    """Delay, damper, filter, lag: blocks in the order of ELEMENTS, the filter's pole computed in Python."""
    w = WallParams.of(damping=0.5, cutoff=0.1, delay=1, lag=0.2)
    t = w.kernel_table()
    a = math.exp(-0.2 * math.pi)
    assert t.tolist() == [4.0, 1, 1, 1, 1.0, 2, 1, 0, 0.5, 3, 1, 2, a, 4, 1, 1, 0.2]
    assert WallParams.of().kernel_table().tolist() == [0.0]  # the paper's spring: no block
    # rows of different lengths, padded after the last block, decode to the same walls
    rows = table.stack_tables([t, WallParams.of().kernel_table()])
    assert rows.shape == (2, t.size) and rows[1].tolist() == [0.0] * t.size
    assert wall_kernel.decode_table(rows[0]) == wall_kernel.decode_table(t)
    assert wall_kernel.decode_table(rows[1]) == (
        0,
        (0.0, 0.0, False, 0.0, 0.0, False, 0.0, 0.0, False, 0, math.inf, math.inf, math.inf),
    )


@pytest.mark.parametrize(
    "kind, g",
    [(VelocityFilter, 0.05), (Push, 0.0), (HandSpring, 0.0), (AmplifierLag, 0.0), (Delay, 0), (Travel, 1e9)],
)
@pytest.mark.parametrize("mu, beta, sigma, v0", [(2.0, 0.4, 0.1, 2.0), (50.0, 0.2, 0.8, 3.0)])
def test_eq4_neutral_element_alone_runs_the_spring_kernel_bit_for_bit(kind, g, mu, beta, sigma, v0):
    """A block that leaves the command unchanged: the wall kernel's run is the spring kernel's (eq. 4-5)."""
    n = 3000
    done, rest, rx, rv, st = _run(WallParams(((kind, g),)), mu, beta, sigma, 0.0, v0, n)
    sx, sv, ss = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    ref = kernel.simulate_kernel((mu, beta, sigma), (0.0, v0), (n, n // 4, 1e6, True), 0, sx, sv, np.empty((0, 4)), ss)
    assert (done, rest) == ref
    assert rx.tobytes() == sx.tobytes() and rv.tobytes() == sv.tobytes()


@pytest.mark.parametrize("kind, g", [(Delay, 2), (Damper, 0.7)])
@pytest.mark.parametrize("mu, beta, sigma, x0, v0", [(2.0, 0.4, 0.1, 0.0, 2.0), (30.0, 0.1, 0.3, 1.3, -1.5)])
def test_eq4_delay_or_damper_alone_equals_the_plain_reference_loop(kind, g, mu, beta, sigma, x0, v0):
    """The delay d and the damper β_B, each alone: bit for bit the reference's plain loop around the same exact step."""
    n = 2000
    done, rest, rx, rv, _ = _run(WallParams(((kind, g),)), mu, beta, sigma, x0, v0, n)
    rec = np.empty((n + 1, 2))
    damping, delay = (g, 0) if kind is Damper else (0.0, g)
    _, at, div = controller_run(mu, beta, sigma, x0, v0, n, damping, delay, 0.0, False, True, 1e6, np.empty(3), rec)
    assert div == (done < n and rest < 0) and (not div or at == done)  # both stop past the bound at the same sample
    k = (rest if rest >= 0 else done) + 1  # after a rest the kernel holds the state the reference keeps integrating
    assert np.array_equal(rx[:k], rec[:k, 0]) and np.array_equal(rv[:k], rec[:k, 1])


@pytest.mark.parametrize(
    "kind, g, x0, v0",
    [
        (AmplifierLag, 0.3, 0.0, 2.0),
        (HandSpring, 0.08, 0.0, 2.0),
        (OneSided, 0.25, -1.5, 1.2),
        (Push, 0.4, 0.0, 2.0),
        (PassivityController, (8, 2.0), 0.0, 2.0),
    ],
)
def test_eq4_element_alone_equals_the_numerical_reference(kind, g, x0, v0):
    """The lag, hand, one-sided wall, push and passivity controller, each alone, against solve_ivp (1e-8 of scale)."""
    mu, beta, sigma, n = 3.0, 0.3, 0.2, 40
    wall = WallParams(((kind, g),))
    done, rest, rx, rv, _ = _run(wall, mu, beta, sigma, x0, v0, n)
    ix, iv = simulate_ivp_ctl(mu, beta, sigma, x0, v0, n, wall)
    k = n + 1 if rest >= 0 else done + 1
    assert np.all(np.abs(ix[1:k] - np.round(ix[1:k])) > 1e-9)  # no reading decided by rounding (ξ0 is exact)
    scale = max(1.0, float(np.max(np.abs(ix[:k]))))
    assert np.max(np.abs(rx[:k] - ix[:k])) <= 1e-8 * scale
    assert np.max(np.abs(rv[:k] - iv[:k])) <= 1e-8 * scale


def test_unknown_code_is_refused_before_the_call_and_by_the_kernel():
    bad = np.array([2.0, table.DAMPER, 1, 0, 0.5, 99.0, 1, 0, 1.0])
    with pytest.raises(
        DFAValueError, match=r"table block 1 code = 99 is invalid: the kernel knows the codes 1 Delay, .*, 10 Travel"
    ):
        table.check_table(bad)
    with pytest.raises(DFAValueError, match="parameter count = 2 is invalid"):
        table.check_table(np.array([1.0, table.DAMPER, 2, 0, 0.5, 0.5]))
    with pytest.raises(DFAValueError, match="runs past its end"):
        table.check_table(np.array([2.0, table.DAMPER, 1, 0, 0.5]))
    with pytest.raises(DFAValueError, match="1-D float64"):
        table.check_table(np.array([0, 1]))
    st = np.empty(kernel.NSTATS)
    with pytest.raises(ValueError, match="unknown element code"):
        wall_kernel.simulate_wall_kernel((2.0, 0.4, 0.1), (0.0, 2.0), (100, 25, 1e6, True), bad, E, E, st)
