"""Soundness of the passivity criterion by exact simulation, for every wall (issue 12 item 6, issue 15 item 2).

The criterion of :mod:`dfa.analysis.criterion` (:func:`~dfa.analysis.criterion.passivity_criterion` with
``wall=``) claims more than "does not diverge": when it calls a point passive, the storage
S = ½μξ'² + ½ξ² (eq. 18-19 without the bounded ½(p − p²) term) can never exceed its initial value. This
module samples random points that a criterion calls passive, simulates each exactly with the same wall,
encoder and initial state, and checks at every sample instant

    S(h) <= S(0)(1 + 1e-9)      and      no divergence.

Two populations of points (:class:`Population`) share one sampler, one criterion and one simulation:

**The spring with delay d** (``Population(delay=d)``; issue 12): every point has the wall
``WallParams.of(delay=d)`` and the encoder; ξ0 = 0 for half the points, uniform in [−10, 10] ticks for
the other half. Its criteria: ``"delay-aware"`` (this package's) and ``"d-ignoring"`` (eq. 6 unchanged:
d = 0 and V = |ξ'0| whatever the delay and the initial position), whose violations are the bug of issue 12
(many of its "passive" points gain energy or diverge once d >= 1, or ξ0 ≠ 0).

**Random walls** (``Population()``; issue 15): per point d uniform in {0, …, 3}; β_B = 0 for a tenth of the
points, else log-uniform in [10⁻³, 3]; no filter for half the points, else ν_c uniform in [0.01, 0.49]; the
encoder on for 85 % of the points (off: the linear loop); no amplifier lag (no criterion covers it); ξ0 = 0
(impact at the wall's boundary, from its rest position) for three quarters of the points, else uniform in
[−10, 10] ticks. Its criteria: ``"controller-aware"`` (this package's, the same criterion as
``"delay-aware"``) and ``"damper-ignoring"`` (the spring's criterion with the wall's delay: β_B and the
filter ignored), whose violations show that the check can fail and that the damper must be paid for.

Sampling, both populations: μ log-uniform in [0.1, 10⁴]; ξ'0 uniform in [0, 10] ticks/sample with a
random sign. Half the points lie exactly on a boundary of the criterion's passive set, with the corner
(β₀, σ₀) of the wall the criterion sees: a quarter on the critical line σ = σ₀ + V(β₀ − β) (β < β₀), an
eighth on each edge σ = σ₀ (β >= β₀) and β = β₀ (σ >= σ₀), corners included. The other half are drawn
uniformly from the box β in [0, β₀ + 1], σ in [0, σ₀ + Vβ₀ + 1] and kept when the criterion calls them
passive (rejection sampling: this half does not rely on the boundary formula, so a criterion that accepts
too much is caught). Every point is confirmed passive by the criterion itself before it is simulated; a
point on the line that rounding puts just outside is moved up by a few ulps of σ.

Samples per run: max(2000, 20·2π√μ) (:func:`run_samples`), twenty periods of the undamped spring. Energy
growth, when it happens, shows within the first period (the start of a run is where the speed is
largest); divergence of the d-ignoring criterion's points takes tens of periods (μ = 100, d = 1: about 3000
samples), which the 2000-sample floor covers for μ <= 100.

The simulation (:func:`storage_growth`) takes the spring's fast path for a wall that is a spring (any delay,
encoder on or off): :func:`dfa.core.storage.storage_runs`, the kernel of :func:`dfa.simulate` compiled with
the storage check, all such points in one call; any other wall runs :func:`dfa.simulate`
(:mod:`dfa.core.wall_kernel`) point by point. Both paths share one rule: a run diverged when its outcome is
``"unstable"`` (|ξ| past the bound of 10⁶ ticks, or a growing envelope: the outcome rules of
:func:`dfa.simulate`), and its growth is the largest S/S(0) − 1 over the sample instants it ran, inf from the first sample
past the bound. Turning points inside a sample (ξ' = 0 between two instants) are not checked here: the
simulator records the sample instants only; the reference loop ``tests/reference_ctl.controller_run``
(bit-identical trajectories, tested) also checks them.

``python -m dfa.cli.soundness_report --points 100000 --out reports/validation`` writes
``delay_soundness.md``/``.json`` (the spring with d = 0, …, 3); with ``--walls``, ``controller_soundness.md``/
``.json`` (random walls).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from ..analysis.criterion import CriterionResult, criterion_from_groups, passivity_criterion
from ..analysis.simulation import simulate
from ..checks import check_bool, check_choice, check_delay, check_int, check_positive, check_type
from ..core import kernel
from ..core.storage import storage_runs
from ..errors import DFATypeError, DFAValueError
from ..model.elements import Coverage, Push
from ..model.loop import Loop
from ..model.wall import WallParams
from ..results.status import SimulationOutcome
from .soundness_counts import KINDS as KINDS
from .soundness_counts import TOLERANCE as TOLERANCE
from .soundness_counts import SoundnessCounts, tally

__all__ = [
    "Population",
    "CriterionSoundness",
    "CRITERIA",
    "sample_passive_points",
    "storage_growth",
    "criterion_soundness",
    "one_sided_soundness",
    "history_soundness",
    "run_samples",
    "point_wall",
    "BOUND",
    "KINDS",
    "TOLERANCE",
]

#: |ξ| beyond this (ticks) counts as divergence.
BOUND = 1.0e6
#: What each criterion sees of a point (module docstring): the wall (``"wall"``), its delay alone (``"delay"``)
#: or nothing of it (``"nothing"``, the paper's spring), and whether it sees the initial position ξ0.
CRITERIA: dict[str, tuple[str, bool]] = {
    "delay-aware": ("wall", True),
    "controller-aware": ("wall", True),
    "d-ignoring": ("nothing", False),
    "damper-ignoring": ("delay", True),
}
#: The fields that describe a point, and those of its wall.
STATE_KEYS = ("mu", "beta", "sigma", "xi0", "xi_dot")
WALL_KEYS = ("damping", "delay", "cutoff", "quantized")


def run_samples(mu: float) -> int:
    """Samples simulated for one point: max(2000, 20·2π√μ) (twenty undamped periods).

    Parameters
    ----------
    mu : float
        Dimensionless mass μ = m/(K T²).

    Returns
    -------
    int
        Run length, samples.
    """
    return int(max(2000, math.ceil(20.0 * 2.0 * math.pi * math.sqrt(mu))))


@dataclass(frozen=True)
class Population:
    """How the points are drawn (module docstring): the spring with a delay, or random walls.

    Attributes
    ----------
    delay : int or None
        The spring's delay d, samples: every point has the wall ``WallParams.of(delay=d)`` and the encoder.
        None (default): a random wall and encoder setting per point.
    mu_range : tuple of float
        Range of μ (log-uniform), dimensionless.
    xi_dot_max : float
        Largest |ξ'0|, ticks per sample (uniform, random sign).
    xi0_max : float
        Largest |ξ0| of the points not at ξ0 = 0, ticks (uniform).
    hand : bool
        Random walls only: a hand stiffness κ_h = k_h/K on half the points, log-uniform in [10⁻⁴, 1] and below
        ½π²μ (the hand's resonance below the Nyquist frequency; :class:`~dfa.model.elements.HandSpring`), drawn
        after the rest so that the other fields are those of ``hand=False`` (default False: no hand).
    """

    delay: int | None = None
    mu_range: tuple[float, float] = (0.1, 1.0e4)
    xi_dot_max: float = 10.0
    xi0_max: float = 10.0
    hand: bool = False

    def __post_init__(self) -> None:
        if self.delay is not None:
            object.__setattr__(self, "delay", check_delay(self.delay))
        fix = "give (smallest, largest) μ > 0, e.g. (0.1, 1e4)"
        pair = tuple(self.mu_range) if isinstance(self.mu_range, (tuple, list)) else ()
        if len(pair) != 2:
            raise DFATypeError(f"mu_range = {self.mu_range!r} is invalid: {fix}")
        lo, hi = (check_positive("mu_range", m, fix) for m in pair)
        if not lo <= hi:
            raise DFAValueError(f"mu_range = {self.mu_range!r} is invalid: give (smallest, largest) μ")
        object.__setattr__(self, "mu_range", (lo, hi))
        object.__setattr__(self, "xi_dot_max", check_positive("xi_dot_max", self.xi_dot_max))
        object.__setattr__(self, "xi0_max", check_positive("xi0_max", self.xi0_max))
        hand = check_bool("hand", self.hand, "pass True for a hand stiffness on half the points, False for none")
        if hand and self.delay is not None:
            raise DFAValueError(
                "hand = True is invalid with delay = d: the hand is drawn with random walls; pass delay=None"
            )
        object.__setattr__(self, "hand", hand)

    @property
    def criteria(self) -> tuple[str, str]:
        """This package's criterion and the one that ignores what this population's check is about."""
        return ("controller-aware", "damper-ignoring") if self.delay is None else ("delay-aware", "d-ignoring")

    @property
    def at_rest(self) -> float:
        """Share of the points that start at ξ0 = 0."""
        return 0.75 if self.delay is None else 0.5

    @property
    def point_keys(self) -> tuple[str, ...]:
        """The fields that describe a point of this population (its state; with random walls, its wall too)."""
        if self.delay is not None:
            return STATE_KEYS
        return STATE_KEYS + WALL_KEYS + (("hand_stiffness",) if self.hand else ())


def _seen(criterion: str, wall: WallParams) -> tuple[WallParams, bool]:
    """The wall a criterion sees of ``wall`` and whether it sees ξ0 (:data:`CRITERIA`)."""
    sees, sees_xi0 = CRITERIA[criterion]
    if sees == "wall":
        return wall, sees_xi0
    return (WallParams.of(delay=wall.delay) if sees == "delay" else WallParams.of()), sees_xi0


def _verdict(
    crit: str, b: float, s: float, xd: float, x0: float, mu: float, wall: WallParams, q: bool, history: str = "fresh"
) -> CriterionResult:
    """The criterion's result at one point (β, σ) of the point (ξ'0, ξ0, μ, wall, encoder, history)."""
    seen, sees_xi0 = _seen(crit, wall)
    if sees_xi0:
        return criterion_from_groups(b, s, xd, wall=seen, quantized=q, xi0=x0, mu=mu, history=history)
    return criterion_from_groups(b, s, xd, wall=seen, quantized=q)  # V = |ξ'0|: no μ, so no loop


def _point(
    rng: np.random.Generator,
    crit: str,
    kind: int,
    xd: float,
    x0: float,
    mu: float,
    wall: WallParams,
    q: bool,
    history: str = "fresh",
) -> tuple[float, float]:
    """(β, σ) of one point of ``kind`` that ``crit`` calls passive (module docstring)."""
    b0, s0 = _seen(crit, wall)[0].corner(q)
    v = _verdict(crit, 0.0, 0.0, xd, x0, mu, wall, q, history).equivalent_speed
    if kind == 0:  # interior: rejection sampling of the criterion's own passive set in a box (formula-free)
        for _ in range(10_000):
            b, s = rng.uniform(0.0, b0 + 1.0), rng.uniform(0.0, s0 + v * b0 + 1.0)
            if _verdict(crit, b, s, xd, x0, mu, wall, q, history).passive:
                break
    elif kind == 1:  # exactly on the critical line
        b = rng.uniform(0.0, b0)
        s = s0 + v * (b0 - b)
    elif kind == 2:  # σ = σ₀ edge, β >= β₀ (corner included)
        b, s = b0 + (0.0 if rng.random() < 0.2 else rng.uniform(0.0, 1.0)), s0
    else:  # β = β₀ edge
        b, s = b0, s0 + (0.0 if rng.random() < 0.2 else rng.uniform(0.0, 1.0))
    for _ in range(8):  # rounding on the line: move up by ulps until the criterion accepts
        if _verdict(crit, b, s, xd, x0, mu, wall, q, history).passive:
            return b, s
        s = float(np.nextafter(s, np.inf))
    raise DFAValueError(f"sampler bug: point beta = {b!r}, sigma = {s!r} is not passive under {crit}")


def _draw_walls(rng: np.random.Generator, n: int, delay: int | None) -> dict[str, np.ndarray]:
    """The walls and encoder flags of ``n`` points: the spring with ``delay``, or random (module docstring)."""
    if delay is not None:
        return dict(damping=np.zeros(n), delay=np.full(n, delay), cutoff=np.full(n, np.nan), quantized=np.ones(n, bool))
    damping = np.where(rng.random(n) < 0.1, 0.0, 10.0 ** rng.uniform(-3.0, math.log10(3.0), n))
    cutoff = np.where(rng.random(n) < 0.5, np.nan, rng.uniform(0.01, 0.49, n))
    return dict(damping=damping, delay=rng.integers(0, 4, n), cutoff=cutoff, quantized=rng.random(n) < 0.85)


def point_wall(damping: float, delay: int, cutoff: float, hand_stiffness: float = 0.0) -> WallParams:
    """The wall of one point from its fields (``cutoff`` NaN: no filter).

    Parameters
    ----------
    damping : float
        Virtual damping β_B, dimensionless.
    delay : int
        Computational delay d, samples.
    cutoff : float
        Filter cutoff ν_c, cycles per sample (NaN: no filter).
    hand_stiffness : float, optional
        Hand stiffness κ_h = k_h/K (default 0: none).

    Returns
    -------
    WallParams
    """
    cut = None if math.isnan(cutoff) else cutoff
    return WallParams.of(damping=float(damping), delay=int(delay), cutoff=cut, hand_stiffness=float(hand_stiffness))


def _walls_of(pts: dict[str, np.ndarray]) -> list[WallParams]:
    """Each point's wall (:func:`point_wall`; no hand stiffness when the points have none)."""
    hand = pts.get("hand_stiffness", np.zeros(pts["mu"].shape[0]))
    keys = (pts["damping"], pts["delay"], pts["cutoff"], hand)
    return [point_wall(b, d, c, k) for b, d, c, k in zip(*keys, strict=True)]


def _population(population: Population | None) -> Population:
    """The population of a call (None: random walls), or the package's error."""
    if population is None:
        return Population()
    fix = "give Population(delay=d) for the spring with delay d, or Population() for random walls"
    return check_type("population", population, Population, fix)


def sample_passive_points(
    n: int, population: Population | None = None, *, criterion: str | None = None, seed: int = 0
) -> dict[str, np.ndarray]:
    """Random points that ``criterion`` calls passive, half on its boundaries (module docstring).

    Parameters
    ----------
    n : int
        Number of points.
    population : Population, optional
        How the points are drawn (default: random walls).
    criterion : str, optional
        One of the population's :attr:`~Population.criteria` (default: this package's criterion).
    seed : int
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    dict of numpy.ndarray
        ``mu, beta, sigma, xi0, xi_dot`` (ticks, ticks/sample), ``kind`` (an index into :data:`KINDS`) and
        each point's wall: ``damping``, ``delay``, ``cutoff`` (NaN: no filter), ``quantized``.
    """
    n = check_int("n", n, minimum=1)
    pop = _population(population)
    crit = check_choice("criterion", pop.criteria[0] if criterion is None else criterion, pop.criteria)
    rng = np.random.default_rng(seed)
    mu = 10.0 ** rng.uniform(np.log10(pop.mu_range[0]), np.log10(pop.mu_range[1]), n)
    xd = rng.uniform(0.0, pop.xi_dot_max, n) * rng.choice([-1.0, 1.0], n)
    x0 = np.where(rng.random(n) < pop.at_rest, 0.0, rng.uniform(-pop.xi0_max, pop.xi0_max, n))
    walls = _draw_walls(rng, n, pop.delay)
    kind = rng.choice(4, n, p=[0.5, 0.25, 0.125, 0.125])
    if pop.hand:  # drawn from a second stream: the other fields are those of the population without the hand
        hr = np.random.default_rng([seed, 28])
        kap = np.minimum(10.0 ** hr.uniform(-4.0, 0.0, n), 0.5 * math.pi**2 * mu)
        walls["hand_stiffness"] = np.where(hr.random(n) < 0.5, 0.0, kap)
    beta, sigma = np.empty(n), np.empty(n)
    for i, w in enumerate(_walls_of(walls | {"mu": mu})):
        beta[i], sigma[i] = _point(rng, crit, kind[i], xd[i], x0[i], mu[i], w, bool(walls["quantized"][i]))
    return dict(mu=mu, beta=beta, sigma=sigma, xi0=x0, xi_dot=xd, kind=kind, **walls)


def _storage_run(pt: dict[str, Any], n: int) -> tuple[float, int, bool]:
    """(largest S/S(0) − 1 at the sample instants, the sample where it occurred, diverged) of one point."""
    c = point_wall(pt["damping"], pt["delay"], pt["cutoff"], pt.get("hand_stiffness", 0.0))
    mu, x0, v0 = float(pt["mu"]), float(pt["xi0"]), float(pt["xi_dot"])
    kap = c.hand_stiffness  # the hand spring's ½κ_h ξ² is stored energy (dfa.analysis.criterion)
    with np.errstate(all="ignore"):
        r = simulate(
            Loop.dimensionless(mu, float(pt["beta"]), float(pt["sigma"]), c), v0, n, x0,
            quantize=bool(pt["quantized"]), bound=BOUND,
        )  # fmt: skip
        xs, vs = np.asarray(r.xi)[1:], np.asarray(r.xi_dot)[1:]
        diverged = r.outcome is SimulationOutcome.UNSTABLE  # the compiled path's rule (module docstring)
        s0 = 0.5 * mu * v0 * v0 + 0.5 * (1.0 + kap) * x0 * x0
        s = 0.5 * mu * vs * vs + 0.5 * (1.0 + kap) * xs * xs
        ratio = (s - s0) / s0 if s0 > 0.0 else np.where(s > 0.0, np.inf, 0.0)
        ratio = np.where(np.abs(xs) <= BOUND, ratio, np.inf)  # past the bound, or NaN after it: inf
    h = int(np.argmax(ratio))
    return float(ratio[h]), h + 1, diverged


def storage_growth(pts: dict[str, np.ndarray], ns: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Simulate every point of :func:`sample_passive_points` for ``ns[i]`` samples; the storage at every sample.

    The spring's walls run in one compiled call (:func:`dfa.core.storage.storage_runs`), the others with
    :func:`dfa.simulate` point by point; both share one rule of divergence (module docstring).

    Parameters
    ----------
    pts : dict of numpy.ndarray
        The points (:func:`sample_passive_points`).
    ns : numpy.ndarray
        Run length of each point, samples.

    Returns
    -------
    tuple of numpy.ndarray
        (largest S/S(0) − 1, the sample where it occurred, diverged) per point.
    """
    m = pts["mu"].shape[0]
    ratio, at, div = np.empty(m), np.empty(m, dtype=np.int64), np.empty(m, dtype=np.bool_)
    walls = _walls_of(pts)
    spring = np.array(
        [w.covers(Coverage.CLOSED_FORM) for w in walls], dtype=np.bool_
    )  # the spring with any delay: its fast path
    fast = np.flatnonzero(spring)
    if fast.size:
        r, codes, a = np.empty(fast.size), np.empty(fast.size, dtype=np.int64), np.empty(fast.size, dtype=np.int64)
        mu, beta, sigma, x0, v0 = (pts[k][fast] for k in STATE_KEYS)  # fancy indexing: contiguous copies
        delays, quantized = pts["delay"][fast].astype(np.int64), pts["quantized"][fast].astype(np.bool_)
        storage_runs(mu, beta, sigma, x0, v0, ns[fast].astype(np.int64), delays, quantized, r, codes, a)
        ratio[fast], at[fast], div[fast] = r, a, codes == kernel.UNSTABLE
    for i in np.flatnonzero(~spring):
        ratio[i], at[i], div[i] = _storage_run({key: val[i] for key, val in pts.items()}, int(ns[i]))
    return ratio, at, div


@dataclass(frozen=True, kw_only=True)
class CriterionSoundness(SoundnessCounts):
    """Outcome of :func:`criterion_soundness` for one population and one criterion.

    Attributes
    ----------
    delay : int or None
        The spring's delay d, samples (None with random walls: each point's is in ``worst_point``).
    criterion : str
        The criterion that called the points passive (:data:`CRITERIA`).
    points : int
        Points simulated (all called passive by ``criterion``).
    by_kind : dict of str to int
        Points per sampling kind (interior, line, sigma-edge, beta-edge).
    by_case : dict of str to int or None
        Random walls: points with a filter, without the encoder, at the wall's rest position (ξ0 = 0), with
        β_B = 0 (None for the spring).
    energy_grew : int
        Points where S(h) > S(0)(1 + 1e-9) at some sample.
    diverged : int
        Points whose run diverged (module docstring).
    violations : int
        Points with grown energy or divergence.
    worst_growth : float
        Largest max_h S(h)/S(0) − 1 over all points, dimensionless (inf: past the bound).
    worst_point : dict
        The point with that growth (μ, β, σ, ξ0, ξ'0; with random walls its wall too; the sample, the kind).
    samples_min, samples_max : int
        Shortest and longest run, samples (:func:`run_samples`).
    seed : int
        Seed of the random draw.
    status : SoundnessStatus
        ``sound`` when ``violations`` is 0, else ``violated`` (derived).
    """

    delay: int | None = None
    by_case: dict[str, int] | None = None

    SOURCE: ClassVar[str] = "criterion_soundness"
    POPULATION_FIELDS: ClassVar[tuple[str, ...]] = ("delay", "by_case")


def _cases(pts: dict[str, np.ndarray]) -> dict[str, int]:
    """Points with a filter, without the encoder, at ξ0 = 0, without a damper."""
    return {
        "filter": int(np.sum(~np.isnan(pts["cutoff"]))),
        "no encoder": int(np.sum(~pts["quantized"])),
        "xi0 = 0": int(np.sum(pts["xi0"] == 0.0)),
        "no damper": int(np.sum(pts["damping"] == 0.0)),
    } | ({"hand stiffness": int(np.sum(pts["hand_stiffness"] > 0.0))} if "hand_stiffness" in pts else {})


def criterion_soundness(
    points: int, population: Population | None = None, *, criterion: str | None = None, seed: int = 0
) -> CriterionSoundness:
    """Sample ``points`` passive points of ``criterion``, simulate each exactly and count violations.

    Parameters
    ----------
    points : int
        Number of points.
    population : Population, optional
        How the points are drawn: ``Population(delay=d)`` the spring with delay d (the wall
        ``WallParams.of(delay=d)``), ``Population()`` (default) random walls.
    criterion : str, optional
        One of the population's :attr:`~Population.criteria` (default: this package's criterion).
    seed : int
        Seed of the random draw.

    Returns
    -------
    CriterionSoundness

    Examples
    --------
    >>> r = criterion_soundness(50, Population(delay=1), seed=1)
    >>> r.criterion, r.points, r.violations, r.status.value
    ('delay-aware', 50, 0, 'sound')
    """
    pop = _population(population)
    crit = pop.criteria[0] if criterion is None else criterion
    pts = sample_passive_points(points, pop, criterion=crit, seed=seed)
    ns = np.array([run_samples(m) for m in pts["mu"]], dtype=np.int64)
    ratio, at, div = storage_growth(pts, ns)
    counts = tally(pts, pop.point_keys, ns, ratio, at, div)
    case = _cases(pts) if pop.delay is None else None
    return CriterionSoundness(delay=pop.delay, criterion=crit, points=int(points), by_case=case, seed=seed, **counts)


def _one_sided_wall(surface: float, delay: int, push: float, bilateral: bool = False, hand: float = 0.0) -> WallParams:
    """The one-sided wall of a soundness point (the bilateral spring's claim: the same wall, no push)."""
    from ..model.elements import OneSided

    extra = ((Push, push),) if push and not bilateral else ()
    return WallParams(((OneSided, surface), *extra, *WallParams.of(delay=delay, hand_stiffness=hand).groups))


def _one_sided_run(
    mu: float, beta: float, sigma: float, speed: float, wall: WallParams, q: bool, bilateral: bool = False
) -> tuple:
    """(largest Q/(½μV*²) − 1 from the first reading inside on, its sample, diverged, run length) of one approach
    to a one-sided wall: Q = ½μξ'² + ½((ξ − s)⁺)² − p(ξ − s) + ½p², the bound the criterion states
    (dfa.analysis.criterion, "A one-sided wall"; the bilateral spring's claim: ½μV², Q without the push)."""
    from ..analysis.approach import approach_start

    surface, push = wall.surface, wall.group(Push) or 0.0
    x0, v0, d = approach_start(speed, wall=wall, quantize=q)
    n = d + run_samples(mu)
    vstar = (
        speed
        if bilateral
        else passivity_criterion(Loop.dimensionless(mu, 1.0, 1.0, wall), speed, quantized=q).equivalent_speed
    )
    claim = 0.5 * mu * vstar * vstar
    with np.errstate(all="ignore"):
        r = simulate(Loop.dimensionless(mu, beta, sigma, wall), v0, n, x0, quantize=q, bound=BOUND, record=True)
        xs, vs = np.asarray(r.xi)[1:], np.asarray(r.xi_dot)[1:]
        dl = xs - surface
        stored = 0.5 * mu * vs * vs + 0.5 * np.maximum(dl, 0.0) ** 2 - push * dl + 0.5 * push * push
        stored = stored + 0.5 * wall.hand_stiffness * xs * xs  # a hand's spring to the wall's origin
        ratio = np.where(np.abs(xs) <= BOUND, stored / claim - 1.0, np.inf)
        ratio = np.where(np.isnan(xs) & (r.outcome is SimulationOutcome.LEFT), -1.0, ratio)  # left: nothing after
        reading = np.floor(xs) + 0.5 if q else xs
        contact = np.flatnonzero(reading > surface)  # the claim holds from the first reading inside on
        ratio[: contact[0] if contact.size else len(ratio)] = -1.0
    h = int(np.argmax(ratio))
    return float(ratio[h]), h + 1, r.outcome is SimulationOutcome.UNSTABLE, n


def one_sided_soundness(points: int, *, criterion: str = "one-sided", seed: int = 0) -> CriterionSoundness:
    """The criterion for a one-sided wall reached from free space, checked by exact simulation of the approach.

    Points: μ log-uniform in [0.1, 10⁴], V uniform in (0, 10] ticks/sample, the surface s uniform in [−1, 1]
    ticks (0 for 30 %), a delay d of 0 (half) to 3 samples, a push p = F_p/(KΔ) (none for half, else
    log-uniform in [0.01, 10]), a hand's spring κ_h (30 %, log-uniform in [10⁻⁴, 1] below ½π²μ), the encoder
    on for 85 %; half on the criterion's boundaries (as
    :func:`sample_passive_points`). Each run starts :func:`~dfa.analysis.approach.approach_start` samples
    before contact and runs :func:`run_samples` more; a violation is Q = ½μξ'² + ½((ξ − s)⁺)² − p(ξ − s) + ½p²
    + ½κ_hξ² above ½μV*² (1 + 1e-9) at a sample instant from the first reading inside on, or divergence (module
    docstring of :mod:`dfa.analysis.criterion`, "A one-sided wall").

    Parameters
    ----------
    points : int
        Number of points.
    criterion : {"one-sided", "bilateral"}
        This package's (V* of :meth:`~dfa.model.elements.OneSided.contact_speed`), or the bilateral spring's
        with its delay applied to the approach without a push (V, claim ½μV²), whose violations show that the
        check can fail and that the approach must be paid for.
    seed : int
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    CriterionSoundness
        With ``by_case``: points with s ≠ 0, without the encoder, with a delay, with a push and with a hand.
    """
    n = check_int("points", points, minimum=1)
    crit = check_choice("criterion", criterion, ("one-sided", "bilateral"))
    bilateral = crit == "bilateral"
    rng = np.random.default_rng(seed)
    mu = 10.0 ** rng.uniform(-1.0, 4.0, n)
    xd = rng.uniform(0.0, 10.0, n)
    xd = np.where(xd > 0.0, xd, 1.0)
    surface = np.where(rng.random(n) < 0.3, 0.0, rng.uniform(-1.0, 1.0, n))
    quantized = rng.random(n) < 0.85
    delay = np.where(rng.random(n) < 0.5, 0, rng.integers(1, 4, n))
    push = np.where((rng.random(n) < 0.5) | bilateral, 0.0, 10.0 ** rng.uniform(-2.0, 1.0, n))
    kind = rng.choice(4, n, p=[0.5, 0.25, 0.125, 0.125])
    # a hand's spring on 30 % (drawn last: the other fields are those of a draw without it), resonance below Nyquist
    hand = np.where(rng.random(n) < 0.3, np.minimum(10.0 ** rng.uniform(-4.0, 0.0, n), 0.5 * np.pi**2 * mu), 0.0)
    walls = [
        _one_sided_wall(float(surface[i]), int(delay[i]), float(push[i]), bilateral, float(hand[i])) for i in range(n)
    ]
    beta, sigma = np.empty(n), np.empty(n)
    for i in range(n):
        w = WallParams.of(delay=int(delay[i])) if bilateral else walls[i]
        beta[i], sigma[i] = _point(rng, "controller-aware", kind[i], xd[i], 0.0, mu[i], w, bool(quantized[i]))
    pts = dict(mu=mu, beta=beta, sigma=sigma, xi0=np.zeros(n), xi_dot=xd, kind=kind, surface=surface,
               delay=delay, push=push, hand_stiffness=hand, quantized=quantized)  # fmt: skip
    runs = [
        _one_sided_run(float(mu[i]), float(beta[i]), float(sigma[i]), float(xd[i]), walls[i], bool(quantized[i]),
                       bilateral)
        for i in range(n)
    ]  # fmt: skip
    ratio, at, div, ns = (np.array(c) for c in zip(*runs, strict=True))
    counts = tally(pts, (*STATE_KEYS, "surface", "delay", "push", "hand_stiffness", "quantized"), ns, ratio, at, div)
    case = {
        "surface != 0": int(np.sum(surface != 0.0)), "no encoder": int(np.sum(~quantized)),
        "delay > 0": int(np.sum(delay > 0)), "push > 0": int(np.sum(push > 0.0)),
        "hand > 0": int(np.sum(hand > 0.0)),
    }  # fmt: skip
    return CriterionSoundness(delay=None, criterion=crit, points=n, by_case=case, seed=seed, **counts)


def _history_run(mu: float, beta: float, sigma: float, x0: float, xd: float, d: int, q: bool, fresh: bool) -> tuple:
    """(largest S/(½μV*²) − 1, its sample, diverged, run length) of one moving-history start of the spring with
    delay d: S = ½μξ'² + ½ξ², V* of :func:`~dfa.analysis.criterion.moving_history_speed` (``fresh``: the fresh
    start's claim, S <= ½μV², V the energy-equivalent speed)."""
    wall = WallParams.of(delay=d)
    hist = "fresh" if fresh else "moving"
    vstar = passivity_criterion(
        Loop.dimensionless(mu, 1.0, 1.0, wall), xd, quantized=q, xi0=x0, history=hist
    ).equivalent_speed
    n = run_samples(mu)
    with np.errstate(all="ignore"):
        r = simulate(
            Loop.dimensionless(mu, beta, sigma, wall), xd, n, x0, quantize=q, bound=BOUND, record=True, history="moving"
        )
        xs, vs = np.asarray(r.xi), np.asarray(r.xi_dot)
        stored = 0.5 * mu * vs * vs + 0.5 * xs * xs
        ratio = np.where(np.abs(xs) <= BOUND, stored / (0.5 * mu * vstar * vstar) - 1.0, np.inf)
    h = int(np.argmax(ratio))
    return float(ratio[h]), h, r.outcome is SimulationOutcome.UNSTABLE, n


def history_soundness(points: int, *, criterion: str = "moving", seed: int = 0) -> CriterionSoundness:
    """The spring's criterion with a delay for a moving history (the device moved at ξ'0 for the d samples before
    t = 0), checked by exact simulation of that start (:func:`~dfa.analysis.simulation.simulate` with
    ``history="moving"``).

    Points: d uniform in {1, 2, 3}, μ log-uniform in [0.1, 10⁴], ξ'0 uniform in [−10, 10] ticks/sample, ξ0 = 0
    for half and uniform in [−10, 10] ticks for the rest, the encoder on for 85 %; half on the criterion's
    boundaries. A violation is S = ½μξ'² + ½ξ² above ½μV*² (1 + 1e-9) at a sample instant, or divergence (the
    criterion's module docstring, "A moving history"; the ½ξ² of the proof, below the paper's H_c).

    Parameters
    ----------
    points : int
        Number of points.
    criterion : {"moving", "fresh"}
        This package's criterion for the moving history (V* of
        :func:`~dfa.analysis.criterion.moving_history_speed`), or the fresh start's applied to it (claim ½μV²),
        whose violations show that the check can fail and that the pending commands must be paid for.
    seed : int
        Seed of :func:`numpy.random.default_rng`.

    Returns
    -------
    CriterionSoundness
        With ``by_case``: points per delay, at ξ0 = 0 and without the encoder.
    """
    n = check_int("points", points, minimum=1)
    crit = check_choice("criterion", criterion, ("moving", "fresh"))
    rng = np.random.default_rng(seed)
    delay = rng.integers(1, 4, n)
    mu = 10.0 ** rng.uniform(-1.0, 4.0, n)
    xd = rng.uniform(-10.0, 10.0, n)
    x0 = np.where(rng.random(n) < 0.5, 0.0, rng.uniform(-10.0, 10.0, n))
    quantized = rng.random(n) < 0.85
    kind = rng.choice(4, n, p=[0.5, 0.25, 0.125, 0.125])
    beta, sigma = np.empty(n), np.empty(n)
    for i in range(n):
        w = WallParams.of(delay=int(delay[i]))
        beta[i], sigma[i] = _point(rng, "delay-aware", kind[i], xd[i], x0[i], mu[i], w, bool(quantized[i]),
                                   "fresh" if crit == "fresh" else "moving")  # fmt: skip
    pts = dict(mu=mu, beta=beta, sigma=sigma, xi0=x0, xi_dot=xd, kind=kind, delay=delay, quantized=quantized)
    runs = [
        _history_run(float(mu[i]), float(beta[i]), float(sigma[i]), float(x0[i]), float(xd[i]), int(delay[i]),
                     bool(quantized[i]), crit == "fresh")
        for i in range(n)
    ]  # fmt: skip
    ratio, at, div, ns = (np.array(c) for c in zip(*runs, strict=True))
    counts = tally(pts, (*STATE_KEYS, "delay", "quantized"), ns, ratio, at, div)
    case = {f"d = {d}": int(np.sum(delay == d)) for d in (1, 2, 3)} | {
        "xi0 = 0": int(np.sum(x0 == 0.0)), "no encoder": int(np.sum(~quantized)),
    }  # fmt: skip
    return CriterionSoundness(delay=None, criterion=crit, points=n, by_case=case, seed=seed, **counts)
