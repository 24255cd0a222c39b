"""Soundness of the controller's passivity criterion by exact simulation (issue 15 item 2).

:func:`dfa.analysis.criterion.passivity_criterion` with a wall claims that, when it calls a
point passive, the storage S = ½μξ'² + ½ξ² never exceeds its initial value. This
module samples random points that a criterion calls passive, simulates each
exactly with the package's simulator, :func:`dfa.simulate` with the controller
(virtual damper on the backward-difference velocity of the quantized position,
optional ZOH-exact low-pass, delay d; no amplifier lag; :mod:`dfa.core.wall_kernel`, or
the spring kernel when β_B = 0) and checks at every sample instant

    S <= S(0)(1 + 1e-9)      and      |ξ| stays below 10⁶ ticks (no divergence).

Turning points inside a sample (ξ' = 0 between two instants) are not checked
here: the simulator records the sample instants only. The reference loop
``tests/reference_ctl.controller_run`` (bit-identical trajectories, tested) also
checks them, and ``test_eq6_controller_criterion`` runs it on sampled points.

Sampling (per point): μ log-uniform in [0.1, 10⁴]; d uniform in {0, …, 3};
β_B = 0 for a tenth of the points, else log-uniform in [10⁻³, 3]; no filter for
half the points, else ν_c uniform in [0.01, 0.49]; the encoder on for 85 % of the
points (off: the linear loop); |ξ'0| uniform in [0, 10] ticks/sample with a
random sign; ξ0 = 0 (impact at the wall's boundary, from its rest position) for
three quarters of the points, else uniform in [−10, 10] ticks. Half the points
lie exactly on a boundary of the passive set (a quarter on the critical line at
the certified speed, an eighth on each edge σ = σ₀ and β = β₀, corners
included); the other half are drawn uniformly from the box β <= β₀ + 1,
σ <= σ₀ + Vβ₀ + 1 and kept when the criterion accepts them (formula-free:
a criterion that accepts too much is caught). Every point is confirmed passive by
the criterion itself; a point that rounding puts just outside is moved up by a
few ulps of σ. Samples per run: max(2000, 20·2π√μ) (:func:`dfa.analysis.soundness.run_samples`).

The same sampler applied to the damper-ignoring criterion (:func:`dfa.passivity_criterion`
with the delay, β_B and the filter ignored) finds violations: evidence that the
check can fail. The simulation has one call site, :func:`simulate_points`.

Run ``python -m dfa.analysis.soundness --controller --points 100000 --out reports/validation``
to write ``controller_soundness.md`` and ``controller_soundness.json``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..checks import check_choice, check_int
from ..errors import DFAValueError
from ..formatting import markdown_table
from ..model.wall import WallParams
from .criterion import passivity_criterion
from .simulation import simulate
from .soundness_counts import SoundnessCounts, tally

__all__ = [
    "ControllerSoundness",
    "sample_controller_points",
    "simulate_points",
    "controller_soundness",
    "controller_soundness_markdown",
]

#: |ξ| beyond this (ticks) counts as divergence.
BOUND = 1.0e6
CRITERIA = ("controller-aware", "damper-ignoring")


def run_samples(mu: float) -> int:
    """Samples simulated for one point: max(2000, 20·2π√μ) (twenty undamped periods)."""
    return int(max(2000, math.ceil(20.0 * 2.0 * math.pi * math.sqrt(mu))))


def _verdict(crit: str, b: float, s: float, xd: float, x0: float, mu: float, c: WallParams, q: bool):
    """(passive, V) of ``crit`` at one point."""
    if crit == "controller-aware":
        r = passivity_criterion(b, s, xd, wall=c, quantized=q, xi0=x0, mu=mu)
        return r.passive, r.equivalent_speed
    spring = WallParams.of(delay=c.delay)  # β_B and filter ignored
    r2 = passivity_criterion(b, s, xd, wall=spring, quantized=q, xi0=x0, mu=mu)
    return r2.passive, r2.equivalent_speed


def _corner(crit: str, c: WallParams, q: bool) -> tuple[float, float]:
    return (c if crit == "controller-aware" else WallParams.of(delay=c.delay)).corner(q)


def _draw_controllers(rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
    """Random controllers and encoder flags (module docstring)."""
    damping = np.where(rng.random(n) < 0.1, 0.0, 10.0 ** rng.uniform(-3.0, math.log10(3.0), n))
    cutoff = np.where(rng.random(n) < 0.5, np.nan, rng.uniform(0.01, 0.49, n))
    return dict(damping=damping, delay=rng.integers(0, 4, n), cutoff=cutoff, quantized=rng.random(n) < 0.85)


def _point(rng, crit, kind, xd, x0, mu, c, q) -> tuple[float, float]:
    """(β, σ) of one point of ``kind`` that ``crit`` calls passive."""
    b0, s0 = _corner(crit, c, q)
    v = _verdict(crit, 0.0, 0.0, xd, x0, mu, c, q)[1]
    if kind == 0:  # interior: rejection sampling in a box
        for _ in range(10_000):
            b, s = rng.uniform(0.0, b0 + 1.0), rng.uniform(0.0, s0 + v * b0 + 1.0)
            if _verdict(crit, b, s, xd, x0, mu, c, q)[0]:
                break
    elif kind == 1:  # on the critical line
        b = rng.uniform(0.0, b0)
        s = s0 + v * (b0 - b)
    elif kind == 2:  # σ = σ₀ edge, corner included
        b, s = b0 + (0.0 if rng.random() < 0.2 else rng.uniform(0.0, 1.0)), s0
    else:  # β = β₀ edge
        b, s = b0, s0 + (0.0 if rng.random() < 0.2 else rng.uniform(0.0, 1.0))
    for _ in range(8):  # rounding on the line: move up by ulps until the criterion accepts
        if _verdict(crit, b, s, xd, x0, mu, c, q)[0]:
            return b, s
        s = float(np.nextafter(s, np.inf))
    raise DFAValueError(f"sampler bug: point beta = {b!r}, sigma = {s!r} is not passive under {crit}")


def sample_controller_points(
    n: int, *, criterion: str = "controller-aware", seed: int = 0, mu_range: tuple[float, float] = (0.1, 1.0e4)
) -> dict[str, np.ndarray]:
    """Random points (plant, controller, initial state) that ``criterion`` calls passive (module docstring).

    Parameters
    ----------
    n : int
        Number of points.
    criterion : {"controller-aware", "damper-ignoring"}
        This package's criterion, or eq. 6 with the delay only (β_B and the filter ignored).
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    mu_range : tuple of float
        Range of μ (log-uniform).

    Returns
    -------
    dict of numpy.ndarray
        ``mu, beta, sigma, xi0, xi_dot, damping, delay, cutoff`` (NaN: no filter), ``quantized``, ``kind``.
    """
    n = check_int("n", n, minimum=1)
    crit = check_choice("criterion", criterion, CRITERIA)
    rng = np.random.default_rng(seed)
    mu = 10.0 ** rng.uniform(np.log10(mu_range[0]), np.log10(mu_range[1]), n)
    xd = rng.uniform(0.0, 10.0, n) * rng.choice([-1.0, 1.0], n)
    x0 = np.where(rng.random(n) < 0.75, 0.0, rng.uniform(-10.0, 10.0, n))
    ctl = _draw_controllers(rng, n)
    kind = rng.choice(4, n, p=[0.5, 0.25, 0.125, 0.125])
    beta, sigma = np.empty(n), np.empty(n)
    for i in range(n):
        c = _params(ctl["damping"][i], ctl["delay"][i], ctl["cutoff"][i])
        beta[i], sigma[i] = _point(rng, crit, kind[i], xd[i], x0[i], mu[i], c, bool(ctl["quantized"][i]))
    return dict(mu=mu, beta=beta, sigma=sigma, xi0=x0, xi_dot=xd, kind=kind, **ctl)


def _params(damping: float, delay: int, cutoff: float) -> WallParams:
    return WallParams.of(damping=float(damping), delay=int(delay), cutoff=None if math.isnan(cutoff) else cutoff)


def _storage_run(pt: dict[str, Any], n: int) -> tuple[float, int, bool]:
    """(largest S/S(0) − 1 at the sample instants, the sample where it occurred, diverged) of one point."""
    c = _params(pt["damping"], pt["delay"], pt["cutoff"])
    mu, x0, v0 = float(pt["mu"]), float(pt["xi0"]), float(pt["xi_dot"])
    with np.errstate(all="ignore"):
        r = simulate(
            mu, float(pt["beta"]), float(pt["sigma"]), v0, n, x0, quantize=bool(pt["quantized"]), wall=c,
            bound=BOUND,
        )  # fmt: skip
        xs, vs = np.asarray(r.xi)[1:], np.asarray(r.xi_dot)[1:]
        past = np.flatnonzero(~(np.abs(xs) <= BOUND))  # beyond the bound or NaN (after a bound exit)
        if past.size:
            return math.inf, int(past[0]) + 1, True
        s0 = 0.5 * mu * v0 * v0 + 0.5 * x0 * x0
        s = 0.5 * mu * vs * vs + 0.5 * xs * xs
        ratio = (s - s0) / s0 if s0 > 0.0 else np.where(s > 0.0, np.inf, 0.0)
    h = int(np.argmax(ratio))
    return float(ratio[h]), h + 1, False


def simulate_points(pts: dict[str, np.ndarray], ns: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Simulate every point of :func:`sample_controller_points` for ``ns[i]`` samples with :func:`dfa.simulate`.

    The package's own simulator with the controller (:mod:`dfa.core.wall_kernel`; the spring kernel when
    β_B = 0) runs each point; the storage is checked at every sample instant (module docstring).

    Returns
    -------
    tuple of numpy.ndarray
        (largest S/S(0) − 1, the sample where it occurred, diverged) per point.
    """
    m = pts["mu"].shape[0]
    ratio, at, div = np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.bool_)
    for i in range(m):
        ratio[i], at[i], div[i] = _storage_run({key: val[i] for key, val in pts.items()}, int(ns[i]))
    return ratio, at, div


@dataclass(frozen=True, kw_only=True)
class ControllerSoundness(SoundnessCounts):
    """Outcome of :func:`controller_soundness` for one criterion.

    Attributes
    ----------
    criterion : str
        ``"controller-aware"`` (this package) or ``"damper-ignoring"`` (eq. 6 with the delay only).
    points : int
        Points simulated (all called passive by ``criterion``).
    by_kind : dict
        Points per sampling kind (interior, line, sigma-edge, beta-edge).
    by_case : dict
        Points with a filter, without the encoder, at the wall's rest position (ξ0 = 0), with β_B = 0.
    energy_grew, diverged, violations : int
        Points where S > S(0)(1 + 1e-9) somewhere; that diverged; either.
    worst_growth : float
        Largest max S/S(0) − 1 over all points (inf: diverged).
    worst_point : dict
        The point with that growth.
    samples_min, samples_max, seed : int
    """

    by_case: dict  # the count fields: SoundnessCounts (keyword-only)

    _SOURCE = "controller_soundness"


def controller_soundness(
    points: int, *, criterion: str = "controller-aware", seed: int = 0, mu_range: tuple[float, float] = (0.1, 1.0e4)
) -> ControllerSoundness:
    """Sample ``points`` passive points of ``criterion``, simulate each exactly and count violations.

    Parameters
    ----------
    points : int
    criterion : {"controller-aware", "damper-ignoring"}
    seed : int
    mu_range : tuple of float
        Range of μ (log-uniform).

    Returns
    -------
    ControllerSoundness
    """
    pts = sample_controller_points(points, criterion=criterion, seed=seed, mu_range=mu_range)
    ns = np.array([run_samples(m) for m in pts["mu"]], dtype=np.int64)
    ratio, at, div = simulate_points(pts, ns)
    keys = ("mu", "beta", "sigma", "xi0", "xi_dot", "damping", "delay", "cutoff", "quantized")
    case = {
        "filter": int(np.sum(~np.isnan(pts["cutoff"]))),
        "no encoder": int(np.sum(~pts["quantized"])),
        "xi0 = 0": int(np.sum(pts["xi0"] == 0.0)),
        "no damper": int(np.sum(pts["damping"] == 0.0)),
    }
    return ControllerSoundness(
        criterion=criterion, points=int(points), by_case=case, seed=seed, **tally(pts, keys, ns, ratio, at, div)
    )


def controller_soundness_markdown(results: list[ControllerSoundness]) -> str:
    """The summary table of ``reports/validation/controller_soundness.md``."""
    lines = [
        "# Soundness of the controller's passivity criterion (exact simulation)",
        "",
        "Generated by `python -m dfa.analysis.soundness --controller` (module `dfa.analysis.wall_soundness`). Random points that a",
        "criterion calls passive (half exactly on its boundaries: critical line, σ = σ₀, β = β₀; half drawn uniformly",
        "from a box and kept when the criterion accepts them), each with a random controller (β_B, d <= 3, optional",
        "velocity filter, encoder on or off) and initial state (ξ0 = 0 for 3/4 of the points), are simulated exactly;",
        "μ log-uniform in [0.1, 10⁴], |ξ'0| <= 10 ticks/sample, max(2000, 20·2π√μ) samples per run. A violation is a",
        "run whose storage S = ½μξ'² + ½ξ² exceeds S(0)(1 + 1e-9) at a sample instant, or that diverges.",
        "",
    ]
    head = ["criterion", "points", "line / σ-edge / β-edge", "filter / no encoder / ξ0 = 0 / β_B = 0",
            "energy grew", "diverged", "violations", "worst max S/S(0) − 1"]  # fmt: skip
    rows = [
        [r.criterion, r.points, f"{r.by_kind['line']} / {r.by_kind['sigma-edge']} / {r.by_kind['beta-edge']}",
         " / ".join(str(v) for v in r.by_case.values()), r.energy_grew, r.diverged, r.violations,
         f"{r.worst_growth:.3g}" if math.isfinite(r.worst_growth) else "∞"]
        for r in results
    ]  # fmt: skip
    lines.append(markdown_table(head, rows))
    lines += [
        "",
        "*controller-aware*: `dfa.analysis.criterion` ((β − β₀)V + (σ − σ₀) ≥ 0 and σ ≥ σ₀, β₀ = ½ + d + β_B,",
        "σ₀ = ½ + (1 − a)β_B with the encoder, 0 without; V² = ξ'0² + 2H_c(ξ0)/μ).",
        "*damper-ignoring*: the spring's criterion with the delay (β₀ = ½ + d, σ₀ = ½): its violations show that the",
        "check can fail and that the damper must be paid for. A negative worst growth means the energy fell everywhere.",
        "",
    ]
    return "\n".join(lines)
