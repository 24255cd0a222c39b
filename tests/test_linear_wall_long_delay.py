"""The exact linear bound of a wall with a long delay (d >= 32 samples): dfa.analysis.linear_wall.stable_stiffness.

It expanded the delay's z^d as (w + 1)^d in w = z − 1, whose terms reach 3^d on the unit circle: from d = 32 on every
digit was lost and the bound came out 'never', K_crit = 0 (Delta, B = 1 N·s/m, 200 Hz velocity filter). The delay is
now a factor e^{jdθ} on the circle and a shift register in the spectral radius. Checked here against a closed loop
built independently of the module (the continuous device discretised by the matrix exponential, the controller's
difference equations with shift registers for the delay, K_crit by bisection on its spectral radius, no crossing)
and, for the spring alone, against dfa.analysis.limits.closed_form.k_gil (Jury conditions of the spring's own
polynomial).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm

import dfa
from dfa import Wall
from dfa.analysis.limits.closed_form import k_gil
from dfa.analysis.linear_wall import LinearStatus, stable_stiffness

DELTA = dfa.get_device("delta").device


def _loop_matrix(k: float, m: float, b: float, t: float, big_b: float, fc: float | None, d: int) -> np.ndarray:
    """State matrix of device, ZOH and controller f_h = −K x_{h−d} − B u_{h−d} at step h.

    u is the velocity estimate: u_h = (x_h − x_{h−1})/T without a filter, else its first-order low-pass
    u_{h+1} = a_f u_h + (1 − a_f)(x_h − x_{h−1})/T, a_f = exp(−2π f_c T) (H(z) of dfa.model.wall). State:
    [x_h, ẋ_h, x_{h−1} … x_{h−d−1}, u_h … u_{h−d}] (the u's only with a filter).
    """
    ac = np.array([[0.0, 1.0], [0.0, -b / m]])
    aug = np.zeros((3, 3))
    aug[:2, :2], aug[1, 2] = ac * t, t / m
    e = expm(aug)
    phi, gam = e[:2, :2], e[:2, 2]  # ZOH: s_{h+1} = Φ s_h + Γ f_h
    nx, nu = d + 1, (d + 1 if fc is not None else 0)
    n = 2 + nx + nu
    xi = [0] + list(range(2, 2 + nx))  # index of x_{h−j}, j = 0 … d + 1
    ui = list(range(2 + nx, n))  # index of u_{h−j}, j = 0 … d
    force = np.zeros(n)  # f_h as a row over the state
    force[xi[d]] -= k
    if fc is None:
        force[xi[d]] -= big_b / t
        force[xi[d + 1]] += big_b / t
    else:
        force[ui[d]] -= big_b
    mat = np.zeros((n, n))
    mat[:2, :2] = phi
    mat[:2, :] += np.outer(gam, force)
    mat[2, 0] = 1.0  # x_{h}    -> x_{(h+1)−1}
    for j in range(1, nx):
        mat[xi[j + 1], xi[j]] = 1.0
    if fc is not None:
        af = math.exp(-2.0 * math.pi * fc * t)
        mat[ui[0], ui[0]] = af
        mat[ui[0], xi[0]] += (1.0 - af) / t
        mat[ui[0], xi[1]] -= (1.0 - af) / t
        for j in range(1, nu):
            mat[ui[j], ui[j - 1]] = 1.0
    return mat


def _bisected_k_crit(k0: float, big_b: float, fc: float | None, d: int) -> float:
    """K at which the independent loop's spectral radius crosses 1, bisected from [K0/2, 2K0] to 1e-10."""
    m, b, t = DELTA.mass, DELTA.damping, DELTA.period

    def rho(k: float) -> float:
        return float(np.max(np.abs(np.linalg.eigvals(_loop_matrix(k, m, b, t, big_b, fc, d)))))

    lo, hi = 0.5 * k0, 2.0 * k0
    assert rho(lo) < 1.0 < rho(hi)
    while hi - lo > 1e-10 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if rho(mid) < 1.0 else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("d", [32, 48, 64])
def test_linear_wall_long_delay_k_crit_matches_a_shift_register_loop(d):
    """Delta, B = 1 N·s/m, 200 Hz filter: 'interval' with K_crit equal to the bisected bound of the independent
    loop to 1e-8 relative (it was 'never', K_crit = 0, from d = 32 on)."""
    wall = Wall.of(20000.0, damping=1.0, delay=d, filter_cutoff=200.0)
    r = stable_stiffness(DELTA.mass, DELTA.damping, DELTA.period, wall)
    assert r.status is LinearStatus.INTERVAL
    assert r.k_crit == pytest.approx(_bisected_k_crit(r.k_crit, 1.0, 200.0, d), rel=1e-8)


@pytest.mark.parametrize("d", [32, 48, 64])
def test_linear_wall_long_delay_spring_alone_matches_k_gil_and_the_shift_register_loop(d):
    """The spring alone (no damper, no filter) at the same delays: K_crit equals k_gil (the spring's own Jury
    path, dfa.analysis.linear) and the independent loop's bisected bound, both to 1e-8 relative."""
    r = stable_stiffness(DELTA.mass, DELTA.damping, DELTA.period, Wall.of(1.0, delay=d))
    assert r.status is LinearStatus.INTERVAL
    assert r.k_crit == pytest.approx(k_gil(DELTA, delay=d), rel=1e-8)
    assert r.k_crit == pytest.approx(_bisected_k_crit(r.k_crit, 0.0, None, d), rel=1e-8)


def test_linear_wall_damper_without_filter_long_delay_matches_the_shift_register_loop():
    """A damper on the raw difference velocity (no filter) at d = 40: the independent loop's bound to 1e-8."""
    wall = Wall.of(1.0, damping=0.5, delay=40)
    r = stable_stiffness(DELTA.mass, DELTA.damping, DELTA.period, wall)
    assert r.status is LinearStatus.INTERVAL
    assert r.k_crit == pytest.approx(_bisected_k_crit(r.k_crit, 0.5, None, 40), rel=1e-8)
