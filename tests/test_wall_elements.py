"""One model of the wall (issue 25): an element defined outside the package, and the spring's fast paths.

1. A toy element written here, a second computational delay whose criterion is refused, goes through the
   criterion's refusal, the exact linear bound and the simulator without any change to the package. It must
   act as the built-in ``Delay`` of the summed delay (Diolaiti et al. 2006; eq. 6 with d).
2. The spring's fast paths (the spring's compiled kernel, its closed-form linear bound, its loop inverse) are
   chosen from the wall (``WallParams.is_spring``). Forcing the general wall path on the same spring gives
   the same answer (hypothesis over random loops): the two are one implementation, not two stacks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import dfa
from dfa.analysis.criterion import passivity_criterion
from dfa.analysis.linear import critical_stiffness, spectral_radius
from dfa.analysis.linear_wall import stable_stiffness
from dfa.analysis.simulation import simulate
from dfa.checks import check_delay
from dfa.errors import DFAValueError
from dfa.model.elements import CommandPolynomials, Element, KernelBlock, NotCovered, Parameter
from dfa.model.wall import Wall, WallParams

TOY_REASON = "the toy delay has no proven criterion (a test of the refusal path)"


@dataclass(frozen=True)
class ToyDelay(Element):
    """A second computational delay of whole samples, refusing the criterion (defined in this test only)."""

    toy_delay: int
    parameter: ClassVar[Parameter] = Parameter(
        "toy_delay", ("samples", "samples"), "--toy-delay", "N", "a test element", "toy_delay", "d_toy"
    )
    absent: ClassVar[Any] = 0

    def group(self, period: float, stiffness: float) -> int:
        return check_delay(self.toy_delay)

    @classmethod
    def check_group(cls, value: Any) -> int:
        return check_delay(value)

    @classmethod
    def renders_nothing(cls, g: Any) -> bool:
        return g == 0

    @classmethod
    def spring_kernel(cls, g: Any) -> bool:
        return True

    @classmethod
    def corner(cls, g: Any, *, quantized: bool, velocity_gain: float = 1.0) -> tuple[float, float]:
        raise NotCovered(TOY_REASON)

    #: Its block in the kernel table is the built-in delay's (same code): the simulator adds the delays up.
    kernel_code: ClassVar[int] = dfa.Delay.kernel_code

    @classmethod
    def kernel_block(cls, g: Any) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), int(g))

    @classmethod
    def command(cls, g: Any, h: CommandPolynomials) -> CommandPolynomials:
        return CommandPolynomials(h.spring, h.velocity, h.denominator, h.damping, h.delay + int(g))

    @classmethod
    def low_frequency_delay(cls, g: Any) -> float:
        return float(g)


M, B, T = 0.05, 0.01, 1e-3  # kg, N·s/m, s


@pytest.mark.parametrize("d", [0, 1, 2])
def test_toy_element_criterion_is_refused_with_its_reason(d):
    wall = WallParams(((ToyDelay, 1),)) if d == 0 else WallParams(((dfa.Delay, d), (ToyDelay, 1)))
    assert wall.not_covered() == TOY_REASON and wall.delay == d + 1
    with pytest.raises(DFAValueError, match="toy delay has no proven criterion"):
        passivity_criterion(0.8, 0.7, 1.0, wall=wall)


@pytest.mark.parametrize("d", [0, 1, 3])
def test_toy_element_linear_bound_is_the_summed_delays(d):
    """K_crit of the loop with Delay(d) and ToyDelay(1) is the built-in Delay(d + 1)'s (closed form, all Jury
    conditions) and the general characteristic polynomial's (linear_wall)."""
    toy = Wall(1.0, [dfa.Delay(d), ToyDelay(1)] if d else [ToyDelay(1)])
    ref = critical_stiffness(M, B, T, wall=Wall.of(1.0, delay=d + 1))
    assert critical_stiffness(M, B, T, wall=toy) == ref
    assert stable_stiffness(M, B, T, toy).k_crit == pytest.approx(ref, rel=1e-9)
    assert ref == pytest.approx(B / (T * (1.5 + d)), rel=0.05)  # b/(T(½ + d)) for small bT/m (eq. 8 with delay)


@pytest.mark.parametrize("mu, beta, sigma, v0", [(50.0, 0.8, 0.2, 1.0), (20.0, 0.3, 0.7, 3.0), (5.0, 0.1, 0.3, 2.0)])
def test_toy_element_simulates_as_the_builtin_delay(mu, beta, sigma, v0):
    """The simulator takes the toy's delay from its kernel block: bit for bit the built-in Delay(2)."""
    toy = simulate(mu, beta, sigma, v0, 4000, wall=WallParams(((dfa.Delay, 1), (ToyDelay, 1))))
    ref = simulate(mu, beta, sigma, v0, 4000, wall=WallParams.of(delay=2))
    assert toy.outcome == ref.outcome and toy.delay == ref.delay == 2
    np.testing.assert_array_equal(toy.xi, ref.xi)
    np.testing.assert_array_equal(toy.xi_dot, ref.xi_dot)


# ------------------------------------------------------------------ 2. the spring's fast paths = the general path
def _general_path():
    """A context in which every wall takes the general path (the wall kernel, the general loop)."""
    mp = pytest.MonkeyPatch()
    mp.setattr(WallParams, "is_spring", property(lambda self: False))
    return mp


@settings(max_examples=40, deadline=None)
@given(
    mu=st.floats(0.5, 500.0),
    beta=st.floats(0.0, 2.0),
    sigma=st.floats(0.0, 2.0),
    v0=st.floats(0.05, 20.0),
    d=st.integers(0, 2),
)
def test_spring_wall_simulation_fast_path_equals_the_wall_kernel(mu, beta, sigma, v0, d):
    """simulate() of a spring wall: the spring's compiled kernel and the wall kernel give the same run."""
    wall = WallParams.of(delay=d)
    fast = simulate(mu, beta, sigma, v0, 3000, record=False, wall=wall)
    mp = _general_path()
    try:
        general = simulate(mu, beta, sigma, v0, 3000, record=False, wall=wall)
    finally:
        mp.undo()
    assert general.outcome == fast.outcome
    scale = max(1.0, abs(fast.final_xi), abs(fast.final_xi_dot))
    assert abs(general.final_xi - fast.final_xi) <= 1e-9 * scale
    assert abs(general.final_xi_dot - fast.final_xi_dot) <= 1e-9 * scale


@settings(max_examples=60, deadline=None)
@given(mu=st.floats(0.2, 1e4), beta=st.floats(0.0, 5.0), d=st.integers(0, 3))
def test_spring_wall_spectral_radius_fast_path_equals_the_general_polynomial(mu, beta, d):
    """The spring's characteristic polynomial and the general wall polynomial have the same spectral radius."""
    wall = WallParams.of(delay=d)
    fast = float(spectral_radius(mu, beta, wall=wall))
    mp = _general_path()
    try:
        general = float(spectral_radius(mu, beta, wall=wall))
    finally:
        mp.undo()
    assert general == pytest.approx(fast, rel=1e-9, abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(
    mass=st.floats(1e-3, 10.0),
    damping=st.floats(1e-3, 10.0),
    period=st.floats(1e-4, 1e-2),
    d=st.integers(0, 3),
)
def test_spring_wall_linear_bound_closed_form_equals_the_general_loop(mass, damping, period, d):
    """K_crit of a spring wall: the spring's closed form (critical_stiffness) and the general loop's stable
    interval (stable_stiffness) agree."""
    wall = Wall.of(1.0, delay=d)
    fast = critical_stiffness(mass, damping, period, wall=wall)
    mp = _general_path()
    try:
        general = stable_stiffness(mass, damping, period, wall).k_crit
    finally:
        mp.undo()
    assert general == pytest.approx(fast, rel=1e-7)


@settings(max_examples=60, deadline=None)
@given(
    mass=st.floats(1e-3, 10.0),
    damping=st.floats(0.0, 5.0),
    coulomb=st.floats(1e-3, 1.0),
    resolution=st.floats(1e-6, 1e-3),
    period=st.floats(1e-4, 1e-2),
    velocity=st.floats(0.0, 1.0),
    d=st.integers(0, 3),
)
def test_eq11_spring_k_criterion_closed_form_equals_the_walls_bisection(
    mass, damping, coulomb, resolution, period, velocity, d
):
    """K_max of eq. 11 (the spring's closed form, with delay) is the largest K the criterion itself passes: the
    bisection on the criterion's verdict that serves every wall (dfa.analysis.limits.kmax.wall_k_criterion)."""
    from dfa.analysis.limits.closed_form import k_max_criterion
    from dfa.analysis.limits.kmax import wall_k_criterion

    dev = dfa.Device(mass=mass, damping=damping, coulomb=coulomb, resolution=resolution, period=period)
    closed = float(k_max_criterion(dev, velocity, d))
    general = wall_k_criterion(dev, Wall.of(1.0, delay=d), velocity)
    assert general == pytest.approx(closed, rel=1e-9, abs=1e-300)
