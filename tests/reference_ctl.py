"""Slow, independent references of the loop with a controller (test code, not shipped).

* :func:`simulate_ivp_ctl` integrates μξ'' + βξ' + σ sgn ξ' = φ_A and the amplifier
  α φ_A' = c − φ_A (c clipped to ±φ_max by an actuator's force limit, the push outside it) numerically (scipy ``solve_ivp``, DOP853), sample by sample,
  with events at ξ' = 0 (stop) and at |φ_A| = σ (breakaway of a stuck device).
* :func:`controller_run` is the loop with damper, filter and delay (no amplifier lag)
  written as one plain compiled loop around the exact per-sample step of
  :func:`dfa.core.kernel.step`, with the storage S = ½μξ'² + ½ξ² checked at every sample
  and turning point (formerly in the controller's soundness check, now ``dfa.studies.soundness``; the package uses
  its simulator, :mod:`dfa.core.wall_kernel`, which ``test_eq6_controller_criterion`` compares with this).
* :func:`linear_ctl_recursion` is the linear loop (no quantizer, σ = 0) from the
  exact ZOH discretisation (``control.c2d``) of the plant with the amplifier,
  x_{h+1} = A_d x_h + B_d c_{h−d}.

Both share :class:`Commands`, the controller's sample-level recursion written
plainly (reading, difference, filter, command, delay) from the semantics in
:mod:`dfa.model.wall`.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from dfa.core import kernel
from dfa.model.elements import ForceLimit, PassivityController

__all__ = ["Commands", "controller_run", "simulate_ivp_ctl", "linear_ctl_recursion"]


def _args(ctl) -> dict:
    """The wall's one-sided contact, push and passivity controller, read from its groups (not from the kernel table:
    this reference stays independent of how the table is packed)."""
    window, limit = ctl.group(PassivityController) or (0, None)
    top = ctl.group(ForceLimit)  # the actuator's force limit φ_max: the command clipped last (None: unlimited)
    return {
        "onesided": ctl.one_sided, "surface": ctl.surface, "push": ctl.push, "pc": ctl.passivity_controller,
        "window": window, "limit": math.inf if limit is None else limit, "top": math.inf if top is None else top,
    }  # fmt: skip


class Commands:
    """The controller at the sample instants: ``applied(ξ_h)`` returns c_{h−d}."""

    def __init__(self, ctl, quantize: bool):
        self.ctl, self.q = ctl, quantize
        self.prev_r = None
        self.prev_v = 0.0
        self.y = 0.0
        self.hist: list[float] = []
        # the passivity observer and controller (dfa.model.elements.PassivityController's docstring), plainly: the
        # terms −φ_{h−1} v_h (the last W with a window), the controller's bookings beside the pending commands
        self.terms: list[float] = []
        self.booked: list[float] = []
        self.energy = 0.0  # E_obs over the whole run
        self.force = 0.0  # the controller's force of the last reading
        self.ledger = (0.0, 0.0)  # the ledger before and after the controller's action at the last reading

    def held(self, x: float) -> float:
        """The energy the wall holds at ξ0 as its observer counts a slow entry: the readings walked one tick at a
        time, at rest, from where the wall's force vanishes (r = 0 up or r = −1 down; outside a one-sided wall)."""
        a = _args(self.ctl)
        if not self.q:  # the continuous spring: the integral of the force
            d = x - a["surface"] if a["onesided"] else x
            return 0.5 * d * d if (d > 0 or not a["onesided"]) else 0.0
        r0 = math.floor(x)
        if a["onesided"]:
            start = math.floor(a["surface"] + 0.5) - 1  # a reading outside
        else:
            start = 0 if r0 >= 0 else -1

        def force(r):  # the wall's command at rest at reading r
            q = r + 0.5
            if a["onesided"]:
                return min(-(q - a["surface"]), 0.0) if q > a["surface"] else 0.0
            return -q

        e, r = 0.0, start
        step = 1 if r0 >= start else -1
        while r != r0:
            e -= force(r) * step
            r += step
        return e

    def _controller(self, v: float, w: float, shape, x: float) -> float:
        """The command with the passivity controller's force, from the wall's own command ``w``."""
        a = _args(self.ctl)
        # the command held over the sample just ended; at the first reading the energy the wall holds
        term = self.held(x) if not self.hist else -self.hist[0] * v
        self.energy += term
        self.terms.append(term)
        window = a["window"]
        seen = sum(self.terms[-window:]) if window else sum(self.terms)
        pending = sum(self.booked[1:]) if self.booked else 0.0  # commands not yet applied and observed
        ledger = seen + pending
        f = 0.0
        if a["pc"] and ledger < 0.0 and v != 0.0:
            f = max(-a["limit"], min(a["limit"], ledger / v))
        c = shape(w + f)
        self.force = c - shape(w)
        self.ledger = (ledger, ledger - self.force * v)
        return c

    def applied(self, x: float) -> float:
        r = math.floor(x) if self.q else x
        first = self.prev_r is None
        v = 0.0 if first else r - self.prev_r
        if self.ctl.cutoff is None:
            y = v
        else:
            a = self.ctl.filter_pole
            y = 0.0 if first else a * self.y + (1.0 - a) * self.prev_v
        self.prev_r, self.prev_v, self.y = r, v, y
        q = r + 0.5 if self.q else r
        a = _args(self.ctl)
        if a["onesided"]:  # pushes only beyond the surface, never pulls
            inside = q > a["surface"]
            self.inside = inside

            def shape(c: float) -> float:
                return min(c, 0.0) if inside else 0.0

            w = -(q - a["surface"]) - self.ctl.damping * y
        else:

            def shape(c: float) -> float:
                return c

            w = -q - self.ctl.damping * y
        c = self._controller(v, w, shape, x)
        c = max(-a["top"], min(a["top"], c))  # the actuator's force limit, after every other element
        if first:
            self.hist = [c] * (self.ctl.delay + 1)
            self.booked = [0.0] * (self.ctl.delay + 1)
        self.hist = self.hist[1:] + [c]
        self.booked = self.booked[1:] + [-self.force * v]
        return self.hist[0]


def _ivp(rhs, t0, y0, event):
    from scipy.integrate import solve_ivp

    return solve_ivp(rhs, (t0, 1.0), y0, method="DOP853", rtol=1e-12, atol=1e-13, events=event)


def _stuck(t, fa, c, lag, sigma):
    """Integrate φ_A alone while stuck; return (t, φ_A, broke_away)."""
    if lag == 0.0 or abs(c) <= sigma:
        return 1.0, (fa if lag == 0.0 else c + (fa - c) * math.exp(-(1.0 - t) / lag)), False

    def ev(_t, y):
        return abs(y[0]) - sigma

    ev.terminal, ev.direction = True, 1
    sol = _ivp(lambda _t, y: [(c - y[0]) / lag], t, [fa], ev)
    if sol.status == 1 and sol.t_events[0].size:
        return float(sol.t_events[0][0]), math.copysign(sigma, c), True
    return 1.0, float(sol.y[0, -1]), False


def simulate_ivp_ctl(mu, beta, sigma, xi0, xi_dot0, samples, ctl, *, quantize=True):
    """Reference trajectory (ξ, ξ') at the samples 0 … samples with controller ``ctl`` (WallParams)."""
    lag, kap = ctl.lag, ctl.hand_stiffness  # a hand stiffness only without a lag (the model refuses both)
    args = _args(ctl)
    q0 = math.floor(xi0) + 0.5 if quantize else xi0
    # a one-sided wall's run that starts outside moving toward it is an approach at constant speed: the
    # operator's force balances friction and damping until the wall first reads contact, then is the push
    approaching = args["onesided"] and not q0 > args["surface"] and xi_dot0 > 0.0
    push = sigma + beta * xi_dot0 if approaching else args["push"]
    xs, vs = np.empty(samples + 1), np.empty(samples + 1)
    x, v = float(xi0), float(xi_dot0)
    xs[0], vs[0] = x, v
    cmd = Commands(ctl, quantize)
    fa = None
    for h in range(samples):
        c = cmd.applied(x)
        if getattr(cmd, "inside", False):
            push, approaching = args["push"], False
        kap = 0.0 if approaching else ctl.hand_stiffness  # the operator holds the approach against the hand too
        fa = c if (fa is None or lag == 0.0) else fa
        t = 0.0
        while t < 1.0:
            if v == 0.0:
                if abs(fa + push - kap * x) <= sigma:
                    t, fa, broke = _stuck(t, fa + push, c + push, lag, sigma)
                    fa -= push
                    if not broke:
                        break
                s = math.copysign(1.0, fa + push - kap * x)
            else:
                s = math.copysign(1.0, v)

            def rhs(_t, y, s=s, c=c, push=push, kap=kap):
                dfa = 0.0 if lag == 0.0 else (c - y[2]) / lag
                return [y[1], (y[2] + push - kap * y[0] - beta * y[1] - sigma * s) / mu, dfa]

            def stop(_t, y):
                return y[1]

            stop.terminal, stop.direction = True, -s
            sol = _ivp(rhs, t, [x, v, fa], stop)
            if sol.status == 1 and sol.t_events[0].size:
                t = float(sol.t_events[0][0])
                x, v, fa = float(sol.y_events[0][0][0]), 0.0, float(sol.y_events[0][0][2])
            else:
                x, v, fa = (float(z) for z in sol.y[:, -1])
                t = 1.0
        xs[h + 1], vs[h + 1] = x, v
    return xs, vs


def linear_ctl_recursion(mu, beta, xi0, xi_dot0, samples, ctl):
    """Linear loop (no quantizer, no friction) with controller ``ctl`` from control.c2d of plant + amplifier."""
    import control

    if ctl.lag == 0.0:
        plant = control.ss([[0.0, 1.0], [0.0, -beta / mu]], [[0.0], [1.0 / mu]], np.eye(2), np.zeros((2, 1)))
    else:
        k = 1.0 / ctl.lag
        a = [[0.0, 1.0, 0.0], [0.0, -beta / mu, 1.0 / mu], [0.0, 0.0, -k]]
        plant = control.ss(a, [[0.0], [0.0], [k]], np.eye(3), np.zeros((3, 1)))
    dsys = control.c2d(plant, 1.0, method="zoh")
    ad, bd = np.asarray(dsys.A), np.asarray(dsys.B)[:, 0]
    cmd = Commands(ctl, False)
    xs, vs = np.empty(samples + 1), np.empty(samples + 1)
    state = np.array([xi0, xi_dot0] + ([] if ctl.lag == 0.0 else [np.nan]), dtype=float)
    xs[0], vs[0] = xi0, xi_dot0
    for h in range(samples):
        c = cmd.applied(state[0])
        if h == 0 and ctl.lag > 0.0:
            state[2] = c
        state = ad @ state + bd * c
        xs[h + 1], vs[h + 1] = state[0], state[1]
    return xs, vs


@njit(cache=True)
def controller_run(mu, beta, sigma, x0, v0, n, damping, delay, pole, filtered, quantize, bound, hist, rec=None):
    """Exact run of the loop with damper, filter and delay (no amplifier lag); returns (max S/S(0) − 1, at, diverged).

    The command of sample h is −(n_h + ½) − β_B y_h (−ξ_h − β_B y_h without the
    encoder) with n_h = ⌊ξ_h⌋, v_h = n_h − n_{h−1} (v_0 = 0) and y_h = v_h, or
    y_h = a y_{h−1} + (1 − a) v_{h−1} (y_0 = 0) with the filter; the force of
    sample h is the command of sample h − d (the first command before that).
    ``hist`` is scratch of length >= d + 1. S is checked at every sample and
    at every turning point (where ξ' = 0 inside a sample). ``rec`` (shape (n + 1, 2), optional)
    receives (ξ, ξ') at every sample instant.
    """
    k = kernel.sample_constants(mu, beta)
    x, v = x0, v0
    s0 = 0.5 * mu * v0 * v0 + 0.5 * x0 * x0
    worst, at = -np.inf, 0
    nprev = math.floor(x0) if quantize else x0
    y, vprev = 0.0, 0.0
    record = rec is not None
    if record:
        rec[0, 0], rec[0, 1] = x0, v0
    for h in range(n):
        rd = math.floor(x) if quantize else x
        vel = rd - nprev
        nprev = rd
        if filtered:
            y = pole * y + (1.0 - pole) * vprev if h > 0 else 0.0
            vprev = vel
        else:
            y = vel
        hist[h % (delay + 1)] = -(rd + 0.5 if quantize else rd) - damping * y
        phi = hist[(h - delay) % (delay + 1)] if h >= delay else hist[0]
        x, v, xr, _t, _a, _a2, _tr, stopped = kernel.step(x, v, phi, mu, sigma, k)
        if record:
            rec[h + 1, 0], rec[h + 1, 1] = x, v
        s = 0.5 * mu * v * v + 0.5 * x * x
        if stopped:
            s = max(s, 0.5 * xr * xr)
        r = (s - s0) / s0 if s0 > 0.0 else (np.inf if s > 0.0 else 0.0)
        if not r <= worst:  # NaN counts as growth
            worst, at = (r if r == r else np.inf), h + 1
        if not abs(x) <= bound:
            return np.inf, h + 1, True
    return worst, at, False


@njit(cache=True)
def _batch(mus, betas, sigmas, x0s, v0s, ns, damping, delay, pole, filtered, quantized, bound, ratio, at, div):
    hist = np.empty(int(delay.max()) + 1)
    for i in range(mus.shape[0]):
        ratio[i], at[i], div[i] = controller_run(
            mus[i], betas[i], sigmas[i], x0s[i], v0s[i], ns[i], damping[i], delay[i], pole[i], filtered[i],
            quantized[i], bound, hist,
        )  # fmt: skip
