"""The rest and exit tests read the delay ring through its least and largest command (issue 43; paper eq. 4-5).

:func:`dfa.core.wall_kernel._sample` takes no array (an inline helper that takes one costs a reference count a
sample): the proven rest state (:func:`dfa.core.wall_kernel._absorbing`: every pending command within σ of the
held force) and a one-sided wall left for good (:func:`dfa.core.wall_kernel._gone`: every pending command zero) are
decided from the ring's extremes (:func:`dfa.core.wall_kernel._extent`). Checked here against the definition, every
entry of the ring tested one by one, on rings with ±0, NaN, ±inf and values at the band's edges; and on a run that
comes to rest with a delay (its whole ring within the band at the rest sample).
"""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from dfa.core import kernel, wall_kernel
from dfa.model.wall import WallParams

EMPTY = np.empty(0)
ONE_SIDED_CTL = (0.0, 0.0, False, 0.0, 0.0, True, 0.0, 0.0, False, 0, math.inf, math.inf, math.inf)
EDGES = [0.0, -0.0, 0.5, -0.5, 0.3, 1.0 - 2.0**-53, 1.0, 1.0 + 2.0**-52, math.nan, math.inf, -math.inf, 7.25]


def _within(ring, held, sigma):
    """The definition: every pending command within σ of ``held``, entry by entry."""
    return all(abs(c - held) <= sigma for c in ring)


values = st.one_of(st.sampled_from(EDGES), st.floats(-3.0, 3.0, allow_nan=False))


@given(st.lists(values, min_size=1, max_size=5), st.sampled_from([0.0, 0.25, -0.5, 0.5, math.nan]),
       st.sampled_from([0.0, 0.5, 1.0, 1.5]))  # fmt: skip
def test_eq4_rest_test_from_the_ring_extremes_is_the_entry_by_entry_test(ring, held, sigma):
    pending = wall_kernel._extent(np.array(ring))
    got = wall_kernel._absorbing(0.0, held, sigma, pending, held, held, held)
    assert got == (_within(ring, held, sigma) and abs(held - held) <= sigma)


@given(st.lists(values, min_size=1, max_size=5))
def test_eq4_left_for_good_from_the_ring_extremes_is_every_command_zero(ring):
    pending = wall_kernel._extent(np.array(ring))
    got = wall_kernel._gone(-1.0, 0.0, pending, False, ONE_SIDED_CTL)
    assert got == all(c == 0.0 for c in ring)


def test_eq4_extent_is_nan_when_an_entry_is_nan():
    assert all(math.isnan(v) for v in wall_kernel._extent(np.array([0.0, math.nan, 1.0])))
    assert wall_kernel._extent(np.array([2.0, -0.0, -1.5])) == (-1.5, 2.0)


def test_eq4_runs_with_a_delay_rest_where_every_pending_command_is_within_the_friction_band():
    # a delay of 3 samples: the ring holds four commands; at the rest sample the kernel found, every one of them
    # lies within σ of the held force (0: no hand, no push), entry by entry, read back from the recorded run
    wall = WallParams.of(delay=3, damping=0.5)
    n = 4000
    rx, rv, stats = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    run = (n, 1000, 1e6, True)
    done, rest = wall_kernel.simulate_wall_kernel((10.0, 2.0, 1.5), (0.0, 2.0), run, wall.kernel_table(), rx, rv, stats)
    assert 0 < rest == done
    forces, energy, control = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)
    wall_kernel.applied_forces(rx, wall.kernel_table(), True, forces, energy, control)
    # the commands applied at instants rest … rest + 3 were pending at the rest sample: all within σ = 1.5
    assert np.all(np.abs(forces[rest : rest + 4]) <= 1.5)
    assert rv[rest] == 0.0
