"""The suite's warm-up (``tests/compile_kernels.py``, run by ``make test`` before pytest) reaches the kernels it
is there to compile, with the argument types the package passes them.

Each group runs here in this process (with the warm-up's cache, it loads rather than compiles) and must leave
compiled the kernels it names; a refactor that routes a call elsewhere fails here instead of silently making the
suite compile them in every worker again. The types are the ones the package's own calls make, checked against
a second, independent call of the same entry point.
"""

from __future__ import annotations

import compile_kernels
import pytest

from dfa.core import dfcore, oscillator, pair, wall_kernel, wall_pair, zohlag
from dfa.core import kernel as spring_kernel

#: The kernels each group is there for: the costly ones to compile (tens of seconds on a cold cache).
EXPECTED = {
    "wall_chain": (wall_kernel.simulate_wall_kernel, wall_pair.pair_wall_outcomes),
    "spring_and_rest": (
        spring_kernel.simulate_kernel,
        pair.pair_free_kernel,
        pair.pair_delayed_kernel,
        wall_kernel.applied_forces,
        wall_kernel.lag_sample,
        oscillator.hand_sample,
        zohlag.amplifier_zoh,
        dfcore.df_inverse,
    ),
}


def test_compile_kernels_groups_are_the_listed_ones():
    assert set(compile_kernels.GROUPS) == set(EXPECTED)


@pytest.mark.parametrize("group", sorted(EXPECTED))
def test_compile_kernels_group_leaves_its_kernels_compiled(group):
    compile_kernels.GROUPS[group]()
    for kernel in EXPECTED[group]:
        assert kernel.dispatcher.signatures, f"{group} did not compile {kernel!r}"


def test_compile_kernels_wall_chain_types_are_the_searches():
    """The lanes' kernel compiled by the warm-up is the one a search's call uses: a second search adds no
    signature (a new one would mean the suite compiles the lanes again in each worker)."""
    from dfa.analysis.limits.runs import simulate_points
    from dfa.model.catalogue import get_device
    from dfa.model.elements import Damper, PassivityController
    from dfa.model.wall import Wall

    compile_kernels.GROUPS["wall_chain"]()
    before = set(wall_pair.pair_wall_outcomes.dispatcher.signatures)
    dev = get_device("phantom").device
    p, xd = dev.params(400.0), dev.xi_dot(0.1)
    walls = [Wall(400.0, (Damper(0.5), PassivityController())).params(dev.period)] * 3
    outs, _ = simulate_points([(p.mu, p.beta, p.sigma, 0.0, xd)] * 3, walls, 3_000)
    assert len(outs) == 3
    assert set(wall_pair.pair_wall_outcomes.dispatcher.signatures) == before
