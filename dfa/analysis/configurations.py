"""The worst configuration of a device whose dynamics change over its workspace (issue 46).

A device with configurations (:mod:`dfa.model.configurations`) is analysed once per configuration, as the
one-axis device felt along the wall's normal there; the device is only as good as its worst configuration:

- :func:`worst_stiffness` (``dfa stiffness``): the recommended stiffness
  (:func:`~dfa.analysis.limits.kmax.design_answer` and :func:`~dfa.analysis.limits.recommend.recommend_stiffness`)
  of each configuration; the limiting one has the smallest (a configuration with none limits the most).
  Timing: every configuration gets the quick answer (no simulation, ~0.25 s); the full answer (with the simulated
  limits, seconds) only where the quick one proves no K (the criterion's K, eq. 11, is the full answer's
  recommendation too wherever it is proven) and for the limiting configuration (its screen). ``simulate=False``
  (``--quick``) never simulates.
- :func:`worst_check` (``dfa check``): the criterion's margin (β − β₀)V + (σ − σ₀) (eq. 6) of each configuration
  at the wall's K; the limiting one has the smallest (one not covered by the criterion limits the most).
- An inertia matrix without a normal: :func:`worst_direction` searches the normal of the worst answer over a
  Fibonacci hemisphere of normals, the axes and the eigenvectors of M (the directions of the extreme masses),
  then refines the best by a shrinking pattern search on the sphere (about 100 to 150 normals). ``dfa check``
  evaluates its margin. The criterion's K (eq. 11) does not depend on the mass, the simulated limits do: ``dfa
  stiffness`` first searches the criterion's K alone (closed form); where it proves a K along every normal and
  that K changes with the direction (per-axis friction, damping or resolution), that is the recommended K and
  the search is done. Otherwise it searches the quick answer's rank (the recommended K, then the describing
  function's limit, which depends on the mass; ~0.25 s a normal judged whole). Two things make that search
  cheap without changing its answer:

  - *bounds*: a rank is judged lazily (:class:`_QuickRank`): the describing function's limit is a grid search
    and bisection, and after each judgement its value is known to lie in an interval (the grid points judged
    safe bound it below, the first one judged not safe and the bisection bound it above). Comparing two normals
    judges only until their intervals are disjoint: a normal whose lower bound lies above the best one's upper
    bound cannot be the worst, and is not judged further. Every decision is the one the whole keys give (the
    same judgements in the same order; tests/test_configurations.py), so the search visits the same normals and
    returns the same normal and K as when each normal's quick answer is computed whole, in about half the time.
  - *one dimension*: a configuration without per-axis values is, along n, a function of the effective mass m_n
    alone, which takes exactly the values [λ_min, λ_max] (the extreme eigenvalues of M); the search runs over
    the masses (:func:`_worst_mass`: 17 masses, then a pattern search in m) instead of the sphere, 5 to 8 times
    fewer judgements (about 1 s a configuration instead of 10 s).

  The full answer is then computed along the worst normal found.

Examples
--------
>>> import numpy as np
>>> f = lambda n: (float(n @ np.diag([3.0, 2.0, 1.0]) @ n),)   # smallest along z
>>> n, value, count = worst_direction(f, np.eye(3), samples=16)
>>> [round(abs(x), 6) for x in n], round(value[0], 9)
([0.0, 0.0, 1.0], 1.0)
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ..checks import check_int, check_type
from ..errors import DFAValueError
from ..model.configurations import PER_AXIS, Configuration, fibonacci_normals
from ..model.device import Device
from ..model.elements import Coverage, PassivityController
from ..model.loop import Loop
from ..model.wall import Wall
from ..results.configurations import ConfigurationRow, WorstConfiguration
from ..results.status import ConfigurationStatus, LimitStatus, RecommendRule

__all__ = [
    "worst_direction",
    "worst_stiffness",
    "worst_check",
    "worst_z_width",
    "z_width_common_ranges",
    "DEFAULT_NORMALS",
]

#: Normals sampled on the hemisphere before the pattern search refines the best.
DEFAULT_NORMALS = 32
_REFINEMENTS = 8  # halvings of the pattern search's step (its last step: the spacing / 256, about 0.1°)

_R2 = math.sqrt(2.0)
Objective = Callable[[np.ndarray], Any]  # a tuple of floats, or any value ordered by <


def _candidates(inertia: np.ndarray, samples: int) -> np.ndarray:
    """The hemisphere's normals, the axes and the eigenvectors of M (each with z >= 0: n and −n are one wall)."""
    _w, vecs = np.linalg.eigh(inertia)
    extra = np.vstack([np.eye(3), vecs.T])
    extra = np.where(extra[:, 2:3] < 0.0, -extra, extra)
    return np.vstack([fibonacci_normals(samples), extra])


def _rotate(n: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    """n turned by ``angle`` (rad) towards the tangent ``axis``, kept a unit vector."""
    out = math.cos(angle) * n + math.sin(angle) * axis
    return out / float(np.linalg.norm(out))


def worst_direction(
    objective: Objective,
    inertia: Sequence[Sequence[float]] | np.ndarray,
    *,
    samples: int = DEFAULT_NORMALS,
    refinements: int = _REFINEMENTS,
) -> tuple[tuple[float, float, float], Any, int]:
    """The wall normal where ``objective`` is smallest (module docstring): sampled, then refined.

    Parameters
    ----------
    objective : callable
        A unit normal (ndarray of 3) to a tuple of floats, compared in order (smaller is worse), or to any value
        ordered by ``<`` (``dfa stiffness``'s ranks, judged lazily as they are compared).
    inertia : array-like
        The inertia matrix M (3 × 3); its eigenvectors are among the normals tried.
    samples : int, optional
        Normals on the Fibonacci hemisphere (default :data:`DEFAULT_NORMALS`), >= 1.
    refinements : int, optional
        Halvings of the pattern search's step, from the hemisphere's spacing (default 8: about 0.1° at the end).

    Returns
    -------
    normal : tuple of float
        The worst unit normal found.
    value : tuple of float
        The objective there (as ``objective`` returns it).
    evaluations : int
        How many normals were evaluated.
    """
    count = check_int("samples", samples, 1, "give the number of normals to sample, e.g. 32")
    seen: dict[tuple[float, ...], Any] = {}

    def f(n: np.ndarray) -> Any:
        key = tuple(np.round(n, 12) * (1.0 if n[2] >= 0 else -1.0))
        if key not in seen:
            out = objective(n)
            seen[key] = tuple(out) if isinstance(out, (list, tuple, np.ndarray)) else out
        return seen[key]

    cands = _candidates(np.asarray(inertia, dtype=float), count)
    values = [f(n) for n in cands]
    best = cands[min(range(len(cands)), key=values.__getitem__)]
    best_value = f(best)
    step = math.sqrt(2.0 * math.pi / count)  # the spacing of the hemisphere's normals, rad
    for _ in range(refinements):
        improved = True
        while improved:
            improved = False
            a = np.cross(best, [1.0, 0.0, 0.0] if abs(best[0]) < 0.9 else [0.0, 1.0, 0.0])
            a /= float(np.linalg.norm(a))
            b = np.cross(best, a)
            for axis in (a, -a, b, -b, (a + b) / _R2, -(a + b) / _R2, (a - b) / _R2, (b - a) / _R2):
                trial = _rotate(best, axis, step)
                value = f(trial)
                if value < best_value:
                    best, best_value, improved = trial, value, True
                    break
        step /= 2.0
    if best[2] < 0.0:
        best = -best
    return (float(best[0]), float(best[1]), float(best[2])), best_value, len(seen)


def _row(c: Configuration, dev: Device, value: float | None, rule: str, normal: Any, count: int) -> ConfigurationRow:
    return ConfigurationRow(
        c.name, dev.own_mass, dev.own_damping, dev.coulomb, dev.resolution, value, rule,
        normal=None if normal is None else (float(normal[0]), float(normal[1]), float(normal[2])), searched=c.directional,
        evaluations=count, pose=c.pose,
    )  # fmt: skip


def _limiting(rows: list[ConfigurationRow]) -> ConfigurationRow:
    """The row without a value (the first), else the smallest value (the first of equal ones)."""
    return min(rows, key=lambda r: (r.value is not None, -math.inf if r.value is None else r.value))


def _check_inputs(device: object, configurations: object) -> tuple[Configuration, ...]:
    check_type("device", device, Device, "give the device whose configurations these are")
    if not isinstance(configurations, (tuple, list)) or not configurations:
        raise DFAValueError("configurations = [] is invalid: give at least one Configuration (a device file's)")
    for c in configurations:
        check_type("configurations", c, Configuration, "give dfa.model.configurations.Configuration objects")
    return tuple(configurations)


def _answer(dev: Device, wall: Wall, velocity: float, margin: float, simulate: bool, kw: dict[str, Any]) -> Any:
    """The answer and recommendation of one one-axis device (with the wall without its controller, if any)."""
    from .limits.kmax import design_answer
    from .limits.recommend import recommend_stiffness

    ans = design_answer(Loop(dev, wall), velocity, simulate=simulate, **kw)
    plain = None
    if wall.element(PassivityController) is not None:
        plain = design_answer(Loop(dev, wall.without_controller()), velocity, simulate=simulate)
    return ans, recommend_stiffness(ans, margin, plain=plain)


def _quick_key(rec: Any, ans: Any, margin: float) -> tuple[float, float]:
    """The quick answer's rank: its recommended K, else the describing function's limit over the margin (an
    estimate of the simulated rule); then the describing function's limit (it depends on the mass). A limit with
    no value counts as 0 below the range searched (cycles predicted at the smallest K: the most limiting) and as
    inf otherwise (none predicted)."""
    k_df = ans.k_df.value
    if k_df is None:
        k_df = 0.0 if ans.k_df.status is LimitStatus.BELOW_RANGE else math.inf
    k = rec.k_recommended if rec.k_recommended is not None else k_df / margin
    return (k, k_df)


class _QuickRank:
    """:func:`_quick_key` of one one-axis device, judged lazily: compared with ``<``, two ranks judge only what
    decides the comparison (:class:`~dfa.analysis.limits.search.GridBracket`), and the decision is the one the
    full keys give (the same judgements, in the same order, up to where they decide).

    The recommended K of the quick answer is the criterion's (eq. 11) where it proves one (a closed form, exact
    at once), else none; the describing function's limit ``k_df`` is a grid search and bisection
    (:func:`~dfa.analysis.limits.search.df_limit`). Sound bounds of ``k_df`` after each judgement: every grid
    point judged safe so far bounds it from below; the first one judged not safe, and then the bisection's upper
    end, bound it from above. Two ranks whose intervals do not overlap are ordered without judging further: a
    normal whose lower bound lies above another's upper bound cannot be the worse one.
    """

    def __init__(self, dev: Device, wall: Wall, velocity: float, margin: float):
        from .limits.kmax import DESIGN_MAX_SAMPLES, closed_forms
        from .limits.runs import Evidence, RunCache
        from .limits.search import GridBracket, check_stiffness_range, search_grid

        kc, _kl, _pub, k_ref, top = closed_forms(dev, wall, velocity)
        proven = kc.status is LimitStatus.FOUND and kc.value is not None and kc.value > 0
        self.k: float | None = float(kc.value) if proven and kc.value is not None else None
        self.margin = margin
        self.bracket: GridBracket | None = None
        if velocity > 0 and top > 0 and math.isfinite(top):  # design_answer's k_df (else none: inf)
            pts = search_grid(k_ref, top, 16)
            what = "the stiffness search (K_criterion/2 to 8 × the largest closed-form bound)"
            check_stiffness_range(dev, float(pts[0]), float(pts[-1]), what)
            if wall.linear:
                vs = velocity * np.arange(1, 7) / 6
                ev = Evidence(dev, wall, vs, DESIGN_MAX_SAMPLES, "half-delay", RunCache())
                xd = dev.xi_dot(velocity)
                self.bracket = GridBracket(lambda k: ev.predicted(k, xd), pts)

    @property
    def exact(self) -> bool:
        return self.bracket is None or self.bracket.exact

    def parts(self) -> tuple[tuple[float, float], tuple[float, float]]:
        """The intervals of (K, k_df): K the recommended one, else k_df / margin (:func:`_quick_key`)."""
        df = (math.inf, math.inf) if self.bracket is None else self.bracket.bounds
        k = (self.k, self.k) if self.k is not None else (df[0] / self.margin, df[1] / self.margin)
        return k, df

    def __lt__(self, other: _QuickRank) -> bool:
        while True:
            decided = _less(self.parts(), other.parts())
            if decided is not None:
                return decided
            open_ = [r for r in (self, other) if not r.exact]
            # the one further from its value: the grid's (hi = inf) from the lower point, else the wider bracket
            pick = min(open_, key=lambda r: (-_spread(*r.parts()[1]), r.parts()[1][0]))
            assert pick.bracket is not None
            pick.bracket.refine()


def _spread(lo: float, hi: float) -> float:
    """hi / lo of an interval of stiffnesses: inf while nothing is judged safe (lo = 0) or nothing failed."""
    return math.inf if not lo > 0.0 else hi / lo


def _less(a: Sequence[tuple[float, float]], b: Sequence[tuple[float, float]]) -> bool | None:
    """a < b in order of the parts, each known within its interval (lo, hi); None where the intervals do not say."""
    for (alo, ahi), (blo, bhi) in zip(a, b, strict=True):
        if ahi < blo:
            return True
        if alo > bhi:
            return False
        if not alo == ahi == blo == bhi:  # overlapping intervals (both exact and equal: the next part decides)
            return None
    return False


def _criterion_k(dev: Device, wall: Wall, velocity: float) -> float:
    """The criterion's K (eq. 11, extended to the wall; inf where it proves none): :func:`closed_forms`'s
    ``k_criterion`` without its other bounds (the spring's closed form, under a millisecond)."""
    from .limits.closed_form import k_max_criterion
    from .limits.kmax import closed_forms

    p = wall.params(dev.period, dev.resolution)
    if wall.linear and p.covers(Coverage.CLOSED_FORM):
        kc: float | None = float(k_max_criterion(dev, velocity, p.delay))
        kc = kc if kc is not None and kc > 0.0 else None
    else:
        kc = closed_forms(dev, wall, velocity)[0].value
    return math.inf if kc is None else float(kc)


def _worst_mass(
    objective: Objective, inertia: Sequence[Sequence[float]], samples: int, refinements: int
) -> tuple[tuple[float, float, float], Any, int]:
    """:func:`worst_direction` of an objective that depends on the normal only through its effective mass m_n.

    The one-axis device along n is a function of m_n alone when a configuration gives no per-axis values; m_n =
    1/(nᵀ M⁻¹ n) takes every value of [λ_min, λ_max] (the extreme eigenvalues of M) and no other, and does so on
    the quarter of great circle n(θ) = cos θ e_min + sin θ e_max (θ in [0, π/2], m_n increasing with θ). The
    search over the sphere is therefore the search over that arc: ``samples`` masses evenly spread over
    [λ_min, λ_max] (both eigenvectors among them), then a pattern search in m whose step halves ``refinements``
    times.
    """
    w, vecs = np.linalg.eigh(np.asarray(inertia, dtype=float))
    lo, hi = float(w[0]), float(w[2])
    e_min, e_max = vecs[:, 0], vecs[:, 2]
    seen: dict[float, Any] = {}

    def normal(m: float) -> np.ndarray:
        c2 = 1.0 if hi <= lo else min(1.0, max(0.0, (1.0 / m - 1.0 / hi) / (1.0 / lo - 1.0 / hi)))
        n = math.sqrt(c2) * e_min + math.sqrt(1.0 - c2) * e_max
        return n if n[2] >= 0.0 else -n

    def f(m: float) -> Any:
        if m not in seen:
            out = objective(normal(m))
            seen[m] = tuple(out) if isinstance(out, (list, tuple, np.ndarray)) else out
        return seen[m]

    count = 1 if hi <= lo * (1.0 + 1e-12) else max(2, samples)
    masses = [lo + (hi - lo) * j / (count - 1) for j in range(count)] if count > 1 else [lo]
    best = min(masses, key=f)
    step = (hi - lo) / max(1, count - 1)
    for _ in range(refinements if count > 1 else 0):
        improved = True
        while improved:
            improved = False
            for trial in (best - step, best + step):
                if lo <= trial <= hi and f(trial) < f(best):
                    best, improved = trial, True
                    break
        step /= 2.0
    n = normal(best)
    return (float(n[0]), float(n[1]), float(n[2])), f(best), len(seen)


def _stiffness_direction(
    c: Configuration, device: Device, wall: Wall, velocity: float, margin: float, normals: int
) -> tuple[tuple[float, float, float], int]:
    """The worst normal of a directional configuration for ``dfa stiffness``, and the normals evaluated.

    First the criterion's K alone (eq. 11 extended, closed form, under a millisecond a normal): where it proves
    a K along every normal tried and that K changes with the direction, it is the recommended K (the proven
    rule) and its smallest is the worst direction. Otherwise (no proof, or the same K along every normal: no
    per-axis friction, damping or resolution) the quick answer's rank (:func:`_quick_key`, over a coarser
    refinement), compared lazily (:class:`_QuickRank`: a normal is judged only until it is known not to be the
    worst). A configuration without per-axis values is a function of the effective mass alone: the search runs
    over the masses (:func:`_worst_mass`, one dimension) instead of the sphere.
    """
    seen: list[float] = []
    by_mass = not any(isinstance(getattr(c, k), tuple) for k in PER_AXIS)
    assert c.inertia is not None

    def search(f: Objective, refinements: int) -> tuple[tuple[float, float, float], Any, int]:
        if by_mass:
            return _worst_mass(f, c.inertia, normals // 2 + 1, refinements)  # type: ignore[arg-type]
        return worst_direction(f, c.inertia, samples=normals, refinements=refinements)  # type: ignore[arg-type]

    def criterion(n: np.ndarray) -> tuple[float, ...]:
        seen.append(_criterion_k(c.device_at(device, n), wall, velocity))
        return (seen[-1],)

    normal, _v, count = search(criterion, _REFINEMENTS)
    if all(math.isfinite(k) for k in seen) and max(seen) - min(seen) > 1e-9 * max(seen):
        return normal, count
    lazy = wall.element(PassivityController) is None  # a controller's rank compares two answers: computed whole

    def key(n: np.ndarray) -> Any:
        dev = c.device_at(device, n)
        if lazy:
            return _QuickRank(dev, wall, velocity, margin)
        ans, rec = _answer(dev, wall, velocity, margin, False, {})
        return _quick_key(rec, ans, margin)

    normal, _v, more = search(key, 4)
    return normal, count + more


def worst_stiffness(
    device: Device,
    configurations: Sequence[Configuration],
    velocity: float,
    *,
    wall: Wall | None = None,
    margin: float = 2.0,
    simulate: bool = True,
    normals: int = DEFAULT_NORMALS,
    **answer: Any,
) -> WorstConfiguration:
    """The recommended stiffness of every configuration and the limiting one (module docstring).

    Parameters
    ----------
    device : Device
        The device (its own values fill what a configuration does not give; its hand is kept).
    configurations : sequence of Configuration
        At least one.
    velocity : float
        Impact speed V, m/s (rotary rad/s), >= 0.
    wall : Wall, optional
        The wall whose elements are held fixed while K varies (default the spring, ``Wall.of(1.0)``).
    margin : float, optional
        Gain margin of the simulated rule (default 2).
    simulate : bool, optional
        False: the quick answer only (``--quick``); default True.
    normals : int, optional
        Normals sampled for a configuration without one (default :data:`DEFAULT_NORMALS`).
    **answer
        Passed to :func:`~dfa.analysis.limits.kmax.design_answer` for the full answers (``assess``, ``source``,
        ``source_file``: the verdict on the device's K in the limiting configuration's answer).

    Returns
    -------
    WorstConfiguration
        ``quantity="k_recommended"``; ``details`` the limiting configuration's (answer, recommendation).

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("impulse").device
    >>> cs = (Configuration("near"), Configuration("slippery", coulomb=0.012))
    >>> w = worst_stiffness(dev, cs, 0.1, simulate=False)
    >>> w.limiting, [round(r.value, 2) for r in w.rows]
    ('slippery', [101.17, 54.47])
    """
    confs = _check_inputs(device, configurations)
    wall = Wall.of(1.0) if wall is None else check_type("wall", wall, Wall, "give a dfa.Wall")
    rows: list[ConfigurationRow] = []
    full: dict[str, Any] = {}
    for c in confs:
        normal, count = c.normal, 1
        if c.directional:
            normal, count = _stiffness_direction(c, device, wall, velocity, margin, normals)
        dev = c.device_at(device, normal)
        ans, rec = _answer(dev, wall, velocity, margin, False, {})
        if simulate and rec.status is not RecommendRule.PROVEN:  # no proof: the simulated rule needs the runs
            ans, rec = full[c.name] = _answer(dev, wall, velocity, margin, True, answer)
        rows.append(_row(c, dev, rec.k_recommended, rec.status.value, normal, count))
    worst = _limiting(rows)
    c = next(x for x in confs if x.name == worst.name)
    if worst.name in full:  # its full answer, already computed
        details = full[worst.name]
    else:
        details = _answer(c.device_at(device, worst.normal), wall, velocity, margin, simulate, answer)
    status = ConfigurationStatus.NONE if worst.value is None else ConfigurationStatus.FOUND
    return WorstConfiguration(device, float(velocity), "k_recommended", tuple(rows), worst.name, status,
                              simulated=simulate, details=details)  # fmt: skip


def _criterion(dev: Device, wall: Wall, velocity: float, kw: dict[str, Any]) -> Any:
    """The check of one one-axis device: the criterion (or the passivity check with the wall's elements)."""
    from .check import passivity_check
    from .criterion import device_criterion

    if kw.get("history", "fresh") != "fresh":
        return device_criterion(Loop(dev, wall), velocity, **kw)
    return passivity_check(Loop(dev, wall), velocity, **kw)


def _margin(result: Any) -> tuple[float | None, str]:
    crit = getattr(result, "criterion", result)
    if crit is None:
        return None, "not_covered"
    return float(crit.margin), crit.status.value


def worst_check(
    device: Device,
    configurations: Sequence[Configuration],
    velocity: float,
    wall: Wall,
    *,
    normals: int = DEFAULT_NORMALS,
    **check: Any,
) -> WorstConfiguration:
    """The criterion's margin of every configuration at the wall's K and the limiting one (module docstring).

    Parameters
    ----------
    device : Device
    configurations : sequence of Configuration
    velocity : float
        Impact speed, m/s (rotary rad/s), >= 0.
    wall : Wall
        The wall (its K and elements).
    normals : int, optional
        Normals sampled for a configuration without one.
    **check
        ``position``, ``quantized``, ``history`` of :func:`~dfa.analysis.criterion.device_criterion`
        (``history="fresh"``: :func:`~dfa.analysis.check.passivity_check`, which covers a wall's elements).

    Returns
    -------
    WorstConfiguration
        ``quantity="margin"``; ``details`` the limiting configuration's check.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("impulse").device
    >>> w = worst_check(dev, (Configuration("a"), Configuration("coarse", resolution=628e-6)), 0.05, Wall.of(80.0))
    >>> w.limiting, w.rows[1].value < w.rows[0].value
    ('coarse', True)
    """
    confs = _check_inputs(device, configurations)
    check_type("wall", wall, Wall, "give a dfa.Wall (its K and elements)")
    rows: list[ConfigurationRow] = []
    results: dict[str, Any] = {}
    for c in confs:
        normal, count = c.normal, 1
        if c.directional:

            def key(n: np.ndarray, c: Configuration = c) -> tuple[float, ...]:
                m, _rule = _margin(_criterion(c.device_at(device, n), wall, velocity, check))
                return (-math.inf if m is None else m,)

            normal, _v, count = worst_direction(key, c.inertia, samples=normals)  # type: ignore[arg-type]
        dev = c.device_at(device, normal)
        results[c.name] = _criterion(dev, wall, velocity, check)
        value, rule = _margin(results[c.name])
        rows.append(_row(c, dev, value, rule, normal, count))
    worst = _limiting(rows)
    status = ConfigurationStatus.NONE if worst.value is None else ConfigurationStatus.FOUND
    return WorstConfiguration(device, float(velocity), "margin", tuple(rows), worst.name, status,
                              details=(results[worst.name],))  # fmt: skip


def z_width_common_ranges(
    devices: Sequence[Device], wall: Wall, velocity: float, b_range: tuple[float, float] | None = None
) -> tuple[tuple[float, float], tuple[float, float]]:
    """The one K and B grid of several devices' Z-widths: the union of each one's default ranges (N/m, N·s/m).

    Parameters
    ----------
    devices : sequence of Device
        The one-axis devices (a device file's configurations, :meth:`Configuration.device_at`).
    wall : Wall
        The wall whose elements the Z-width holds (its K and damper are the grid's).
    velocity : float
        Impact speed, m/s (rotary rad/s), > 0.
    b_range : (float, float), optional
        The B axis, N·s/m (default: the union of the devices' defaults).

    Returns
    -------
    ((float, float), (float, float))
        The K range and the B range.
    """
    from .limits.zwidth import z_width_ranges

    ends = [z_width_ranges(Loop(d, wall), velocity, b_range) for d in devices]
    k_range = (min(e[0][0] for e in ends), max(e[0][1] for e in ends))
    return k_range, (min(e[1][0] for e in ends), max(e[1][1] for e in ends))


#: The order of the simulated outcomes from least to most severe: a point of the Z-width of several devices is
#: the most severe of theirs (each boundary's failing set, {bounded, diverges, undecided} for ``rest`` and
#: {diverges, undecided} for ``sim``, is a top segment of this order).
_SEVERITY = ("rest", "left", "bounded", "undecided", "diverges")


def _limit_rank(x: Any) -> tuple[int, float]:
    """The order of one B's limits over devices: none (no K: below the range, not covered, no stable K) first,
    then the values, then none above the range (every K of the grid)."""
    if x.value is not None:
        return (1, float(x.value))
    return (2, math.inf) if x.status is LimitStatus.ABOVE_RANGE else (0, 0.0)


def worst_z_width(
    device: Device,
    devices: Sequence[tuple[str, Device]],
    velocity: float,
    wall: Wall,
    **zwidth: Any,
) -> Any:
    """The Z-width of a device whose dynamics change over its workspace: inside only where inside for all.

    Every configuration's one-axis device gets its Z-width (:func:`~dfa.analysis.limits.zwidth.z_width`) on one
    grid (:func:`z_width_common_ranges`); at each B, each method's K_max is the smallest over the configurations
    (a limit without value: none below the range, not covered, no stable K, counts as the smallest; above the range
    as the largest), with the evidence of the configuration that gives it, named in ``limiting``; a grid point's
    outcome is the most severe of the configurations' (so the simulated boundaries of the outcome grid are the
    minima too). Counterexamples of every configuration are kept, each with its configuration's name.

    Parameters
    ----------
    device : Device
        The device (its name and units head the result).
    devices : sequence of (str, Device)
        The configurations' names and one-axis devices (a directional configuration along its worst normal under
        ``dfa stiffness``'s rule), at least one.
    velocity : float
        Impact speed, m/s (rotary rad/s), > 0.
    wall : Wall
        The wall whose elements are held (K and damper are the grid's).
    **zwidth
        ``grid``, ``b_range``, ``speeds``, ``max_samples``, ``df_model``, ``n_jobs``, ``progress`` of
        :func:`~dfa.analysis.limits.zwidth.z_width` (``k_range`` is the common grid's).

    Returns
    -------
    ZWidth
        The minimum over the configurations, ``limiting`` naming each method's configuration B by B.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("impulse").device
    >>> pair = [(c.name, c.device_at(dev)) for c in (Configuration("a"), Configuration("slippery", coulomb=0.012))]
    >>> z = worst_z_width(dev, pair, 0.1, Wall.of(1.0), grid=2, speeds=1, n_jobs=1)
    >>> z.limiting["criterion"][0]  # at B = 0 the criterion proves the smaller K with less friction
    'slippery'
    """
    from ..results.codes import POINT_OUTCOMES, ZWIDTH_METHODS
    from ..results.status import ZWidthStatus
    from .limits.zwidth import z_width

    check_type("device", device, Device, "give the device whose configurations these are")
    if not devices:
        raise DFAValueError("devices = [] is invalid: give at least one (name, Device) pair")
    k_range, b_range = z_width_common_ranges([d for _n, d in devices], wall, velocity, zwidth.pop("b_range", None))
    zws = [z_width(Loop(d, wall), velocity, k_range=k_range, b_range=b_range, **zwidth) for _n, d in devices]
    names = [n for n, _d in devices]
    nb = zws[0].damping.size
    limits: dict[str, tuple[Any, ...]] = {}
    limiting: dict[str, tuple[str, ...]] = {}
    for m in ZWIDTH_METHODS:
        picks = [min(range(len(zws)), key=lambda j: _limit_rank(zws[j].limits[m][i])) for i in range(nb)]
        limits[m] = tuple(zws[j].limits[m][i] for i, j in enumerate(picks))
        limiting[m] = tuple(names[j] for j in picks)
    rank = np.array([_SEVERITY.index(o) for o in POINT_OUTCOMES])
    codes = np.stack([z.outcome for z in zws])
    worst = np.take_along_axis(codes, np.argmax(rank[codes], axis=0)[None], axis=0)[0].astype(codes.dtype)
    ce = tuple(c | {"configuration": n} for n, z in zip(names, zws, strict=True) for c in z.counterexamples)
    lpv = tuple(
        c | {"configuration": n} for n, z in zip(names, zws, strict=True) for c in z.linear_passivity_violations
    )
    caveat = any(z.status is ZWidthStatus.CAVEATS for z in zws)
    status = ZWidthStatus.COUNTEREXAMPLE if ce else (ZWidthStatus.CAVEATS if caveat else ZWidthStatus.OK)
    z0 = zws[0]
    return type(z0)(
        device, z0.wall, z0.velocity, z0.speeds, z0.stiffness.copy(), z0.damping.copy(), limits, worst,
        z0.max_samples, sum(z.simulations for z in zws), z0.df_model, ce, lpv, status, limiting=limiting,
    )  # fmt: skip
