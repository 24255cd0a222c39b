"""Soundness of the delay-aware passivity criterion by exact simulation (issue 12 item 6).

The criterion of :mod:`dfa.analysis.criterion` claims more than "does not diverge": when
it calls a point passive, the storage S = ½μξ'² + ½ξ² (eq. 18-19 without the
bounded ½(p − p²) term) can never exceed its initial value. This module samples
random points that a criterion calls passive, simulates each exactly
(:func:`dfa.core.kernel.simulate_kernel`, the kernel of :func:`dfa.simulate`, with the
same delay d and initial state) and checks at every sample

    S(h) <= S(0)(1 + 1e-9)      and      no divergence (outcome not "unstable").

Sampling (per delay d): μ log-uniform in [0.1, 10⁴]; ξ'0 uniform in [0, 10]
ticks/sample with a random sign; ξ0 = 0 for half the points, uniform in
[−10, 10] ticks for the other half. Half the points lie exactly on a boundary of
the passive set, a quarter each of: the critical line σ = ½ + V(½ + d − β)
(β < ½ + d), and the edges σ = ½ (β >= ½ + d) / β = ½ + d (σ >= ½) including the
corner; the other half are drawn uniformly from the box β in [0, ½ + d + 1],
σ in [0, ½ + V(½ + d) + 1] and kept when the criterion calls them passive
(rejection sampling: this half does not rely on the boundary formula, so a
criterion that accepts too much is caught). Every point is confirmed passive by
the criterion itself (:func:`dfa.passivity_criterion`) before it is simulated; a
point on the line that rounding puts just outside is moved up by a few ulps of σ.

Samples per run: max(2000, 20·2π√μ), twenty periods of the undamped spring
(2π√μ samples). Energy growth, when it happens, shows within the first period
(the start of a run is where the speed is largest); divergence of the
d-ignoring criterion's points takes tens of periods (μ = 100, d = 1: about 3000
samples), which the 2000-sample floor covers for μ <= 100.

The same sampler applied to the d- and ξ0-ignoring criterion (eq. 6 unchanged,
V = |ξ'0|) finds the bug this module documents: many of its "passive" points
gain energy or diverge once d >= 1 (or ξ0 ≠ 0).

Run ``python -m dfa.analysis.soundness --points 100000 --out reports/validation`` to
write ``delay_soundness.md`` and ``delay_soundness.json``; with ``--controller``,
the controller's criterion (:mod:`dfa.analysis.wall_soundness`) is checked instead
and ``controller_soundness.md``/``.json`` are written.
"""

from __future__ import annotations

import argparse
import math
import os
import sys
from dataclasses import dataclass

import numpy as np

from .._io import atomic_write_text
from ..checks import check_choice, check_delay, check_int
from ..core import kernel
from ..core.storage import storage_runs
from ..errors import DFAValueError
from ..formatting import markdown_table
from ..model.wall import WallParams
from ..results.jsonable import dumps
from .criterion import CriticalLine, passivity_criterion
from .soundness_counts import KINDS as KINDS
from .soundness_counts import TOLERANCE as TOLERANCE
from .soundness_counts import SoundnessCounts, tally

__all__ = ["DelaySoundness", "sample_passive_points", "delay_soundness", "soundness_markdown", "main"]

CRITERIA = ("delay-aware", "d-ignoring")


def run_samples(mu: float) -> int:
    """Samples simulated for one point: max(2000, 20·2π√μ) (twenty undamped periods)."""
    return int(max(2000, math.ceil(20.0 * 2.0 * math.pi * math.sqrt(mu))))


def _passive(criterion: str, beta: float, sigma: float, xi_dot: float, xi0: float, mu: float, delay: int) -> bool:
    if criterion == "delay-aware":
        return passivity_criterion(beta, sigma, xi_dot, wall=WallParams.of(delay=delay), xi0=xi0, mu=mu).passive
    return passivity_criterion(beta, sigma, xi_dot).passive  # eq. 6 unchanged: d and ξ0 ignored


def sample_passive_points(
    n: int,
    delay: int,
    *,
    criterion: str = "delay-aware",
    seed: int = 0,
    mu_range: tuple[float, float] = (0.1, 1.0e4),
    xi_dot_max: float = 10.0,
    xi0_max: float = 10.0,
) -> dict[str, np.ndarray]:
    """Random points that ``criterion`` calls passive, half on its boundaries (module docstring).

    Parameters
    ----------
    n : int
        Number of points.
    delay : int
        Delay d (samples) of the loop; the ``"delay-aware"`` criterion uses it,
        the ``"d-ignoring"`` one (eq. 6 unchanged) uses d = 0 and ξ0 = 0.
    criterion : {"delay-aware", "d-ignoring"}
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    mu_range, xi_dot_max, xi0_max
        Sampling ranges (μ log-uniform; |ξ'0| and |ξ0| uniform, ticks).

    Returns
    -------
    dict of numpy.ndarray
        ``mu, beta, sigma, xi0, xi_dot, kind`` (kind: index into :data:`KINDS`).
    """
    n = check_int("n", n, minimum=1)
    d = check_delay(delay)
    crit = check_choice("criterion", criterion, CRITERIA)
    rng = np.random.default_rng(seed)
    lo, hi = np.log10(mu_range[0]), np.log10(mu_range[1])
    mu = 10.0 ** rng.uniform(lo, hi, n)
    xd = rng.uniform(0.0, xi_dot_max, n) * rng.choice([-1.0, 1.0], n)
    x0 = np.where(rng.random(n) < 0.5, 0.0, rng.uniform(-xi0_max, xi0_max, n))
    kind = rng.choice(4, n, p=[0.5, 0.25, 0.125, 0.125])
    beta = np.empty(n)
    sigma = np.empty(n)
    d_crit = d if crit == "delay-aware" else 0
    b0 = 0.5 + d_crit
    for i in range(n):
        v = passivity_criterion(
            0.0, 0.0, xd[i], wall=WallParams.of(delay=d_crit), xi0=x0[i] if crit == "delay-aware" else 0.0, mu=mu[i]
        ).equivalent_speed
        k = kind[i]
        line = CriticalLine.of(v, delay=d_crit)
        if k == 0:  # interior: rejection sampling of the criterion's own passive set in a box (formula-free)
            top = float(line.sigma(0.0)) + 1.0
            for _ in range(10_000):
                b = rng.uniform(0.0, b0 + 1.0)
                s = rng.uniform(0.0, top)
                if _passive(crit, b, s, xd[i], x0[i], mu[i], d):
                    break
        elif k == 1:  # exactly on the critical line
            b = rng.uniform(0.0, b0)
            s = float(line.sigma(b))
        elif k == 2:  # σ = ½ edge, β >= ½ + d (corner included)
            b = b0 + (0.0 if rng.random() < 0.2 else rng.uniform(0.0, 1.0))
            s = 0.5
        else:  # β = ½ + d edge
            b = b0
            s = 0.5 + (0.0 if rng.random() < 0.2 else rng.uniform(0.0, 1.0))
        for _ in range(8):  # rounding on the line: move up by ulps until the criterion accepts
            if _passive(crit, b, s, xd[i], x0[i], mu[i], d):
                break
            s = float(np.nextafter(s, np.inf))
        else:
            raise DFAValueError(f"sampler bug: point beta = {b!r}, sigma = {s!r} is not passive under {crit}")
        beta[i], sigma[i] = b, s
    return dict(mu=mu, beta=beta, sigma=sigma, xi0=x0, xi_dot=xd, kind=kind)


@dataclass(frozen=True, kw_only=True)
class DelaySoundness(SoundnessCounts):
    """Outcome of :func:`delay_soundness` for one delay and one criterion.

    Attributes
    ----------
    delay : int
        Delay d of the simulated loop (samples).
    criterion : str
        ``"delay-aware"`` (this package) or ``"d-ignoring"`` (eq. 6 unchanged).
    points : int
        Points simulated (all called passive by ``criterion``).
    by_kind : dict
        Points per sampling kind (interior, line, sigma-edge, beta-edge).
    energy_grew : int
        Points where S(h) > S(0)(1 + 1e-9) at some sample.
    diverged : int
        Points whose run ended ``"unstable"`` (bound exceeded or growing envelope).
    violations : int
        Points with grown energy or divergence.
    worst_growth : float
        Largest max_h S(h)/S(0) − 1 over all points (inf: past the bound).
    worst_point : dict
        The point with that growth (μ, β, σ, ξ0, ξ'0, sample).
    samples_min, samples_max : int
        Samples per run (module docstring).
    seed : int
    status : SoundnessStatus
        ``SOUND`` when ``violations`` is 0, else ``VIOLATED`` (derived).
    """

    delay: int  # the count fields: SoundnessCounts (keyword-only)

    _SOURCE = "delay_soundness"


def delay_soundness(
    points: int, delay: int, *, criterion: str = "delay-aware", seed: int = 0, **ranges
) -> DelaySoundness:
    """Sample ``points`` passive points of ``criterion`` for delay d, simulate each and count violations.

    Parameters
    ----------
    points : int
    delay : int
        Delay d of the simulated loop (samples).
    criterion : {"delay-aware", "d-ignoring"}
    seed : int
    **ranges
        ``mu_range``, ``xi_dot_max``, ``xi0_max`` of :func:`sample_passive_points`.
    """
    pts = sample_passive_points(points, delay, criterion=criterion, seed=seed, **ranges)
    ns = np.array([run_samples(m) for m in pts["mu"]], dtype=np.int64)
    ratio = np.empty(points)
    codes = np.empty(points, dtype=np.int64)
    at = np.empty(points, dtype=np.int64)
    storage_runs(pts["mu"], pts["beta"], pts["sigma"], pts["xi0"], pts["xi_dot"], ns, int(delay), ratio, codes, at)
    div = codes == kernel.UNSTABLE
    counts = tally(pts, ("mu", "beta", "sigma", "xi0", "xi_dot"), ns, ratio, at, div)
    return DelaySoundness(delay=int(delay), criterion=criterion, points=int(points), seed=seed, **counts)


def soundness_markdown(results: list[DelaySoundness]) -> str:
    """The summary table of ``reports/validation/delay_soundness.md``."""
    lines = [
        "# Soundness of the delay-aware passivity criterion (exact simulation)",
        "",
        "Generated by `python -m dfa.analysis.soundness` (module `dfa.analysis.soundness`). For each computational delay d, random points that a",
        "criterion calls passive (half exactly on its boundaries: critical line, σ = ½, β = ½ + d; half drawn uniformly from",
        "the box β ≤ ½ + d + 1, σ ≤ ½ + V(½ + d) + 1 and kept when the criterion accepts them) are simulated exactly",
        "with that delay and initial state; μ log-uniform in [0.1, 10⁴], |ξ'0| ≤ 10 ticks/sample, ξ0 = 0 for half the",
        "points and |ξ0| ≤ 10 ticks for the rest; max(2000, 20·2π√μ) samples per run. A violation is a run whose",
        "storage S = ½μξ'² + ½ξ² exceeds S(0)(1 + 1e-9) at some sample, or that diverges.",
        "",
    ]
    head = ["criterion", "d", "points", "on line / σ-edge / β-edge", "energy grew", "diverged", "violations",
            "worst max S/S(0) − 1"]  # fmt: skip
    rows = [
        [r.criterion, r.delay, r.points, f"{r.by_kind['line']} / {r.by_kind['sigma-edge']} / {r.by_kind['beta-edge']}",
         r.energy_grew, r.diverged, r.violations, f"{r.worst_growth:.3g}" if math.isfinite(r.worst_growth) else "∞"]
        for r in results
    ]  # fmt: skip
    lines.append(markdown_table(head, rows))
    lines += [
        "",
        "*delay-aware*: the criterion of `dfa.analysis.criterion` ((β − ½ − d)V + (σ − ½) ≥ 0, σ ≥ ½, V² = ξ'0² + 2H_c(ξ0)/μ).",
        "*d-ignoring*: eq. 6 unchanged (d = 0 and V = |ξ'0| whatever the delay and initial position): its violations",
        "are the evidence of the bug the delay-aware criterion fixes (issue 12). A negative worst growth means the",
        "energy fell at every sample of every run.",
        "",
    ]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    """``python -m dfa.analysis.soundness``: run the check and write the Markdown and JSON summaries."""
    ap = argparse.ArgumentParser(prog="python -m dfa.analysis.soundness", description=__doc__.split("\n")[0])
    ap.add_argument("--points", type=int, default=100_000, help="points per delay and criterion (default 100000)")
    ap.add_argument(
        "--old-points", type=int, default=None, help="points for the d-ignoring criterion (default: --points)"
    )
    ap.add_argument("--delays", type=int, nargs="+", default=[0, 1, 2, 3])
    ap.add_argument("--seed", type=int, default=12)
    ap.add_argument("--out", default="reports/validation", help="folder for delay_soundness.md/.json")
    ap.add_argument(
        "--controller",
        action="store_true",
        help="check the controller's criterion (damper, filter, delay; dfa.analysis.wall_soundness) instead and write "
        "controller_soundness.md/.json",
    )
    args = ap.parse_args(argv)
    if args.controller:
        return _controller_main(args)
    results = []
    for crit, n in (("delay-aware", args.points), ("d-ignoring", args.old_points or args.points)):
        for d in args.delays:
            r = delay_soundness(n, d, criterion=crit, seed=args.seed + d)
            print(f"{crit} d = {d}: {r.violations} violations of {r.points}", file=sys.stderr)
            results.append(r)
    os.makedirs(args.out, exist_ok=True)
    atomic_write_text(os.path.join(args.out, "delay_soundness.md"), soundness_markdown(results))
    atomic_write_text(os.path.join(args.out, "delay_soundness.json"), dumps(results, indent=1))
    return 0


def _controller_main(args: argparse.Namespace) -> int:
    """``--controller``: both criteria of :mod:`dfa.analysis.wall_soundness`, written beside the delay check."""
    from .wall_soundness import controller_soundness, controller_soundness_markdown

    results = []
    for crit, n in (("controller-aware", args.points), ("damper-ignoring", args.old_points or args.points)):
        r = controller_soundness(n, criterion=crit, seed=args.seed)
        print(f"{crit}: {r.violations} violations of {r.points}", file=sys.stderr)
        results.append(r)
    os.makedirs(args.out, exist_ok=True)
    atomic_write_text(os.path.join(args.out, "controller_soundness.md"), controller_soundness_markdown(results))
    atomic_write_text(os.path.join(args.out, "controller_soundness.json"), dumps(results, indent=1))
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
