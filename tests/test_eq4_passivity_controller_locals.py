"""The passivity controller in the run's locals is the controller of the replay, bit for bit (issue 43; eq. 4-5).

:func:`dfa.core.wall_kernel._advance` keeps the observer's energy and the controller's mode in local variables and
computes the observer and the controller inline (an inlined helper that takes the observer's array costs a
reference count a sample), while :func:`dfa.core.wall_kernel.applied_forces` replays the readings through
:func:`dfa.core.wall_kernel._command`, the observer's state in its array. Checked here: every sample of a recorded
controller run is the exact step (:func:`dfa.core.kernel.step`, eq. 4-5) under the force the replay gives at that
instant, bit for bit (any difference between the two paths changes a force, and so the next ξ); and the controller's
quotient L/v_h, taken without a division at v_h = ±1, is the clipped quotient of the definition, bit for bit.
"""

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from dfa.core import kernel, wall_kernel
from dfa.core.wall_kernel import DEPENDS, HELD, IDLE
from dfa.model.elements import PassivityController
from dfa.model.wall import WallParams


def _pc(window, limit, **groups):
    """The wall's groups with a passivity controller (window W samples, 0: unbounded; force limit in KΔ)."""
    return WallParams(((PassivityController, (window, limit)), *WallParams.of(**groups).groups))


def _replayed_steps(mu, beta, sigma, x0, v0, n, wall, quantize):
    """Samples of the recorded run that are not the exact step under the replayed force (none when the two agree),
    and the samples compared."""
    rx, rv, stats = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    table = wall.kernel_table()
    done, _ = wall_kernel.simulate_wall_kernel((mu, beta, sigma), (x0, v0), (n, n // 4, 1e6, quantize), table, rx, rv,
                                               stats)  # fmt: skip
    force, energy, control = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)
    wall_kernel.applied_forces(rx, table, quantize, force, energy, control)
    k = kernel.sample_constants(mu, beta)
    bad = []
    for h in range(done):
        x, v = kernel.step(rx[h], rv[h], force[h] + 0.0, mu, sigma, k)[:2]  # the kernel adds the push (0 here)
        if not (x == rx[h + 1] and v == rv[h + 1] and math.copysign(1, v) == math.copysign(1, rv[h + 1])):
            bad.append(h)
    return bad, done


@given(
    mu=st.sampled_from([2.0, 10.0, 13.6, 100.0]) | st.floats(0.5, 300.0),
    beta=st.just(0.0) | st.floats(0.0, 2.0),
    sigma=st.just(0.0) | st.floats(0.0, 1.0),
    x0=st.just(0.0) | st.floats(-3.0, 3.0),
    v0=st.floats(-4.0, 4.0),
    window=st.just(0) | st.integers(1, 40),
    limit=st.none() | st.sampled_from([0.2, 1.0, 3.56]) | st.floats(0.01, 5.0),
    damping=st.just(0.0) | st.floats(0.0, 2.0),
    cutoff=st.none() | st.floats(0.01, 0.45),
    delay=st.integers(0, 3),
    force_limit=st.none() | st.floats(0.5, 20.0),
    quantize=st.booleans(),
)
def test_eq4_passivity_controller_in_locals_steps_under_the_replayed_force(
    mu, beta, sigma, x0, v0, window, limit, damping, cutoff, delay, force_limit, quantize
):
    wall = _pc(window, limit, damping=damping, cutoff=cutoff, delay=delay, force_limit=force_limit)
    bad, _ = _replayed_steps(mu, beta, sigma, x0, v0, 3001, wall, quantize)
    assert bad == []


def test_eq4_passivity_controller_in_locals_on_a_chattering_phantom_run():
    """The search's costliest kind of run (dfa stiffness --device phantom --passivity-controller --pc-force-limit
    0.38 near its limit): sub-tick chatter with the controller held at its limit, every sample compared."""
    bad, done = _replayed_steps(13.567, 0.000942, 0.3562, 0.0, 3.3167, 100_000, _pc(0, 3.5624), True)
    assert done == 100_000 and bad == []


def test_eq4_replay_check_can_fail():
    """The check sees a force one ulp off: the same run replayed with the controller's limit one ulp higher."""
    mu, beta, sigma, v0, n = 13.567, 0.000942, 0.3562, 3.3167, 20_000
    rx, rv, stats = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    wall_kernel.simulate_wall_kernel((mu, beta, sigma), (0.0, v0), (n, n // 4, 1e6, True),
                                     _pc(0, 3.5624).kernel_table(), rx, rv, stats)  # fmt: skip
    force, energy, control = np.empty(n + 1), np.empty(n + 1), np.empty(n + 1)
    wall_kernel.applied_forces(rx, _pc(0, math.nextafter(3.5624, 4.0)).kernel_table(), True, force, energy, control)
    k = kernel.sample_constants(mu, beta)
    steps = [kernel.step(rx[h], rv[h], force[h] + 0.0, mu, sigma, k)[0] == rx[h + 1] for h in range(n)]
    assert not all(steps)


finite = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)


@given(ledger=finite | st.sampled_from([-0.0, 0.0, -1e-300, -3.5624]),
       vh=st.sampled_from([1.0, -1.0, 2.0, -3.0, 0.0, -0.0, 0.5]) | finite,
       limit=st.sampled_from([math.inf, 3.5624, 0.2]) | st.floats(1e-3, 10.0))  # fmt: skip
def test_pc_force_is_the_clipped_quotient_of_hannaford_ryu(ledger, vh, limit):
    """f = L/v_h clipped to ±limit when L < 0 and v_h ≠ 0 (Hannaford and Ryu 2002), else 0; the mode says which."""
    f, mode = wall_kernel._pc_force(ledger, vh, limit)
    if ledger < 0.0 and vh != 0.0:
        q = ledger / vh
        want = max(-limit, min(limit, q))
        assert f == want and math.copysign(1, f) == math.copysign(1, want)
        assert mode == (HELD if abs(q) >= limit else DEPENDS)
    else:
        assert f == 0.0 and mode == (0 if vh == 0.0 else IDLE)
