"""Slow, independent reference integrators of the same sampled loop (test and benchmark code, not shipped).

They exist to check :func:`dfa.simulate` and to measure its speed against
(``benchmarks/run.py``); ``import reference`` with ``tests/`` on the path.

* :func:`simulate_ivp` integrates μξ'' + βξ' + σ sgn ξ' = φ numerically with
  :func:`scipy.integrate.solve_ivp` (DOP853), sample by sample, with an event
  at ξ' = 0 for the stick-slip logic.
* :func:`simulate_control` runs the loop as a discrete-time
  :class:`control.NonlinearIOSystem` (dt = 1) through python-control's
  ``input_output_response``; its update function is the exact per-sample map
  written in plain Python (:func:`step_python`).
* :func:`linear_zoh_recursion` is the linear loop (no quantizer, no Coulomb
  friction) from ``control.c2d(…, 'zoh')``: x_{h+1} = A_d x_h − B_d ξ_{h−d}.
"""

from __future__ import annotations

import math

import numpy as np

from dfa.core.exprel import log1p_ratio, phi1, phi2, phi12  # the one φ₁/φ₂/λ (called as plain Python functions here)

__all__ = [
    "simulate_ivp",
    "step_python",
    "simulate_control",
    "linear_zoh_recursion",
    "zwidth_point_one_by_one",
    "recorded_period",
]


def _force(x: float, quantize: bool) -> float:
    return -(math.floor(x) + 0.5) if quantize else -x


def simulate_ivp(mu, beta, sigma, xi0, xi_dot0, samples, *, quantize=True, delay=0, rtol=1e-12, atol=1e-13):
    """Reference trajectory (ξ, ξ') at the samples 0 … samples, by solve_ivp with events."""
    from scipy.integrate import solve_ivp

    xs = np.empty(samples + 1)
    vs = np.empty(samples + 1)
    x, v = float(xi0), float(xi_dot0)
    xs[0], vs[0] = x, v
    hist = [_force(x, quantize)] * (delay + 1)
    for h in range(samples):
        hist = hist[1:] + [_force(x, quantize)]
        phi = hist[0]
        t = 0.0
        while t < 1.0:
            if v == 0.0:
                if abs(phi) <= sigma:
                    break  # stuck for the rest of the sample
                s = math.copysign(1.0, phi)
            else:
                s = math.copysign(1.0, v)

            def rhs(_t, y, s=s, phi=phi):
                return [y[1], (phi - beta * y[1] - sigma * s) / mu]

            def stop(_t, y, s=s):
                return y[1]

            stop.terminal = True
            stop.direction = -s
            sol = solve_ivp(rhs, (t, 1.0), [x, v], method="DOP853", rtol=rtol, atol=atol, events=stop)
            if sol.status == 1 and sol.t_events[0].size:
                t = float(sol.t_events[0][0])
                x = float(sol.y_events[0][0][0])
                v = 0.0
            else:
                x, v = float(sol.y[0, -1]), float(sol.y[1, -1])
                t = 1.0
        xs[h + 1], vs[h + 1] = x, v
    return xs, vs


def step_python(x, v, phi, mu, beta, sigma):
    """The exact per-sample map in plain Python (the compiled kernel's closed form, operation for operation)."""
    rate = beta / mu
    p1, p2 = phi1(rate), phi2(rate)
    if v == 0.0 and abs(phi) <= sigma:
        return x, v
    s = 1.0 if (v > 0 or (v == 0 and phi > 0)) else -1.0
    ss = sigma * s
    f = phi - ss
    a = f / mu
    x1 = (x + v * p1 - ss * (p2 / mu)) + phi * (p2 / mu)
    v1 = (v * math.exp(-rate) - ss * (p1 / mu)) + phi * (p1 / mu)
    if v1 * s > 0 or v == 0.0 or a == 0.0:
        return x1, v1
    w = -v / f * mu
    y = w * rate
    tstar = min(1.0, w * (log1p_ratio(y) if y > 0 else 1.0))
    f1, f2 = phi12(rate * tstar)
    x = x + v * tstar * f1 + a * tstar * tstar * f2
    tr = 1.0 - tstar
    if abs(phi) <= sigma or tr <= 0.0:
        return x, 0.0
    s2 = math.copysign(1.0, phi)
    a2 = (phi - sigma * s2) / mu
    g1, g2 = phi12(rate * tr)
    return x + a2 * tr * tr * g2, a2 * tr * g1


def simulate_control(mu, beta, sigma, xi0, xi_dot0, samples, *, quantize=True):
    """The sampled loop as a discrete-time python-control NonlinearIOSystem, run by input_output_response."""
    import control

    def update(_t, state, _u, _params):
        x, v = state
        return np.array(step_python(x, v, _force(x, quantize), mu, beta, sigma))

    sys = control.nlsys(update, None, inputs=0, outputs=2, states=2, dt=1, name="haptic_loop")
    resp = control.input_output_response(sys, np.arange(samples + 1), 0, X0=[xi0, xi_dot0])
    return resp.states[0], resp.states[1]


def linear_zoh_recursion(mu, beta, xi0, xi_dot0, samples, *, delay=0):
    """Linear sampled spring φ = −ξ(h − d) from the exact ZOH discretisation of 1/(μs² + βs)."""
    import control

    plant = control.ss([[0.0, 1.0], [0.0, -beta / mu]], [[0.0], [1.0 / mu]], [[1.0, 0.0]], [[0.0]])
    d = control.c2d(plant, 1.0, method="zoh")
    ad, bd = np.asarray(d.A), np.asarray(d.B)[:, 0]
    xs = np.empty(samples + 1)
    vs = np.empty(samples + 1)
    state = np.array([xi0, xi_dot0], dtype=float)
    xs[0], vs[0] = state
    hist = [float(xi0)] * (delay + 1)
    for h in range(samples):
        hist = hist[1:] + [state[0]]
        state = ad @ state - bd * hist[0]
        xs[h + 1], vs[h + 1] = state
    return xs, vs


def zwidth_point_one_by_one(runs, ctl) -> int:
    """A Z-width grid point's code as before batching (dfa.analysis.limits.zwidth._point at 8313b4b): one simulate() per run, in
    order, stopping at the first unstable run (used by tests/test_zwidth_batch.py and make bench's comparison row)."""
    import dfa.analysis.limits.zwidth as zmod
    from dfa.analysis.simulation import simulate

    outs = set()
    for mu, beta, sigma, x0, v0, n, bound in runs:
        r = simulate(mu, beta, sigma, v0, n, xi0=x0, record=False, bound=bound, wall=ctl)
        outs.add(str(r.outcome))
        if "unstable" in outs:
            return zmod.DIVERGES
    if "undecided" in outs:
        return zmod.UNDECIDED_POINT
    return zmod.REST if outs == {"rest"} else zmod.BOUNDED


def recorded_period(xs, vs):
    """First (sample, period) at which a recorded state (ξ, ξ') repeats bit for bit, or None (the period-skip tests)."""
    seen: dict[bytes, int] = {}
    for h in range(len(xs)):
        key = xs[h].tobytes() + vs[h].tobytes()
        if key in seen:
            return seen[key], h - seen[key]
        seen[key] = h
    return None
