"""The design answer: the largest stiffness K for an impact speed V, four ways, for the spring and any wall.

For a device, a wall (:class:`dfa.model.wall.Wall`: its elements held fixed in physical units while K varies,
so β_B = B/(KT) falls as K grows) and an impact speed V (m/s; rotary rad/s):

``k_criterion``
    guaranteed by the passivity criterion (eq. 11, extended to the wall, :mod:`dfa.analysis.criterion`): a
    proof, for impacts up to V. The spring's (any delay) is the closed form of eq. 11
    (:func:`dfa.analysis.limits.closed_form.k_max_criterion`); a wall's, the largest K the criterion's own
    verdict passes (both of its conditions are linear and decreasing in K, so the passive K form an interval
    (0, K*]; bisection, no second copy of the formula). None where no criterion covers the wall.
``k_linear``
    the exact linear bound without encoder and Coulomb friction (all Jury conditions): the spring's
    :func:`~dfa.analysis.limits.closed_form.k_gil`, a wall's top of the stable interval from K = 0
    (:func:`dfa.analysis.linear_wall.stable_stiffness`).
``k_df``
    predicted by the describing function: the largest K whose predicted growth speed (the smallest speed
    amplitude M·ω over every unstable cycle, :mod:`dfa.analysis.limits.runs`) is at least V.
``k_sim``, ``k_sim_rest``
    found by exact simulation: the largest *swept and confirmed* K at which no impact at the simulated speeds,
    from ξ0 = 0 and from the energy preload, diverges (``k_sim``), or every one comes to rest
    (``k_sim_rest``, at most ``k_sim``) (:mod:`dfa.analysis.limits.search`).

The searched limits run over one geometric grid from K_criterion/2 (without a criterion K: K_linear/2) to
8 × the largest closed-form bound; every limit is a :class:`~dfa.analysis.limits.search.KLimit` with its
evidence. Theory requires k_criterion <= k_sim (the criterion is sound, issue 12) and k_sim_rest <= k_sim;
every simulated impact at or below k_criterion that diverges is a counterexample (status ``counterexample``:
a criterion bug). Only ``k_criterion`` is a proof.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> r = design_answer(get_device("Impulse Engine").device, 0.2, grid=12, speeds=3)
>>> r.k_criterion.value < r.k_sim.value, r.k_sim_rest.value <= r.k_sim.value
(True, True)
>>> r.counterexamples, r.status.value in ("ok", "caveats")
((), True)
"""

from __future__ import annotations

import math

import numpy as np

from ...checks import check_bool, check_choice, check_int, check_speed, check_type
from ...errors import DFAValueError
from ...model.device import Device
from ...model.elements import Coverage
from ...model.loop import LOOP_FIX, Loop, loop_first
from ...model.wall import Wall
from ...progress import stage
from ...results.limits import (
    KMaxAssessment as KMaxAssessment,
)
from ...results.limits import (
    KMaxResult as KMaxResult,
)
from ...results.limits import (
    SearchEvidence as SearchEvidence,
)
from ...results.status import KMaxStatus, LimitStatus, StiffnessStatus, VelocityStatus
from ..criterion import device_criterion
from .closed_form import k_abbott_okamura, k_colgate, k_gil, k_max_criterion, k_static, max_passive_velocity
from .runs import Evidence, RunCache, start_points
from .search import (
    DENSE_FACTOR,
    Failure,
    KLimit,
    Sweep,
    check_stiffness_range,
    confirm,
    df_limit,
    search_grid,
    search_steps,
    simulated_limit,
)

__all__ = [
    "KMaxAssessment",
    "KMaxResult",
    "SearchEvidence",
    "design_answer",
    "closed_forms",
    "check_search_range",
    "wall_k_criterion",
    "damper_forbids",
    "max_proven_damping",
    "searched_limits",
    "passive_speed",
    "damper_friction_per_damping",
    "DESIGN_MAX_SAMPLES",
]

#: Longest run (samples) of one design simulation; longer automatic lengths are cut and may be undecided.
DESIGN_MAX_SAMPLES = 1_000_000
#: Relative width at which the bisection of a wall's K_criterion stops.
CRITERION_RTOL = 1e-12
#: Hold models of the describing function.
DF_MODELS = ("half-delay", "zoh", "pade")


# ----------------------------------------------------------------------------- the closed-form limits of a wall
def criterion_passes(dev: Device, wall: Wall, k: float, v: float) -> bool:
    """The criterion's verdict at stiffness k; a K whose groups are not representable is not proven passive."""
    try:
        return device_criterion(Loop(dev, wall.with_stiffness(k)), v).passive
    except DFAValueError:  # (a one-sided wall's impact at v is monotone in K too: V'² = V² + ε²KT²/m)
        return False


def damper_friction_per_damping(dev: Device, wall: Wall) -> float:
    """The Coulomb friction one unit of virtual damping B costs the criterion: (1 − a)Δ/T (N per N·s/m).

    Eq. 11 with a damper spends (1 − a)BΔ/T of the friction c on the damper's quantized velocity (a the
    velocity filter's pole, 0 without filter; :mod:`dfa.analysis.criterion`): with c <= (1 − a)BΔ/T no K is
    proven passive. The one formula of :func:`closed_forms` (status ``never``) and of
    :func:`dfa.analysis.limits.require.damper_guidance`.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> damper_friction_per_damping(dev, Wall.of(1.0, damping=1.0)) == dev.resolution / dev.period
    True
    """
    return wall.params(dev.period, dev.resolution).velocity_gain() * dev.resolution / dev.period


def max_proven_damping(dev: Device, wall: Wall, v: float) -> float:
    """The largest virtual damping B (N·s/m; rotary N·m·s/rad) with which the criterion proves some K at speed v.

    Eq. 11 with the damper's terms, K → 0: multiplied by KΔ, its conditions σ >= σ₀ and (β − β₀)V + σ − σ₀ >= 0
    read c − (1 − a)BΔ/T >= O(K) and (b − B)v + c − (1 − a)BΔ/T >= O(K) (the O(K) terms, ½ + d in β₀ and ½ in σ₀,
    only shrink what is proven), so B < min(c/((1 − a)Δ/T), (bv + c)/(v + (1 − a)Δ/T)) (the one formula of
    :func:`dfa.analysis.limits.require.damper_guidance`; :func:`damper_friction_per_damping`).

    Parameters
    ----------
    dev : Device
    wall : Wall
        Its velocity filter (pole a; 0 without) is read.
    v : float
        Impact speed, m/s (rotary: rad/s), >= 0.

    Returns
    -------
    float
        B in N·s/m (rotary: N·m·s/rad).

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> round(max_proven_damping(get_device("Delta").device, Wall(1.0), 0.1), 3)
    4.653
    """
    b, c = dev.damping, dev.coulomb
    per_b = damper_friction_per_damping(dev, wall)
    return min(c / per_b, (b * v + c) / (v + per_b))


#: Relative margin by which a damper B must exceed :func:`max_proven_damping` for :func:`damper_forbids`: far above
#: the rounding of the criterion's groups (σ = c/(KΔ), β_B = B/(KT), ...) at any K.
NEVER_MARGIN = 1e-9


def damper_forbids(dev: Device, wall: Wall, v: float) -> bool:
    """Whether the criterion proves no K passive at speed v because of the wall's damper: B above
    (1 + :data:`NEVER_MARGIN`) × :func:`max_proven_damping`.

    Then at every K > 0 one of the criterion's conditions fails (:func:`max_proven_damping`: the speed V >= v of a
    one-sided wall's impact only adds (b − B)(V − v) <= 0 where B > b, and where B <= b the first term of the min
    is the one exceeded, σ < σ₀ whatever V; every element adds >= 0 to β₀ and σ₀), so :func:`wall_k_criterion`'s
    halving down to 1e-300 N/m (about a thousand verdicts) ends at 0: it returns 0 at once.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("Delta").device
    >>> damper_forbids(dev, Wall.of(1.0, damping=4.7), 0.1), damper_forbids(dev, Wall.of(1.0, damping=4.6), 0.1)
    (True, False)
    """
    return wall.damping > (1.0 + NEVER_MARGIN) * max_proven_damping(dev, wall, abs(v))


def wall_k_criterion(dev: Device, wall: Wall, v: float) -> float:
    """Largest K the criterion proves passive with ``wall``'s elements at speed v (bisection; 0 if none).

    The passive K form an interval (0, K*]: both conditions of the criterion are linear and decreasing in K
    (module docstring). Found on the criterion's own verdict, to a relative :data:`CRITERION_RTOL`. Where it
    fails at K = 1 and the damper is above the largest with which it proves any K (:func:`damper_forbids`), 0
    without the halving (the same value: the criterion proves no K).
    """
    lo, hi = 0.0, 1.0
    while criterion_passes(dev, wall, hi, v):  # the criterion fails for K large enough (σ₀ grows with K)
        lo, hi = hi, 2.0 * hi
        if hi > 1e300:
            raise DFAValueError("the criterion passes at every stiffness: check the device's friction values")
    if lo == 0.0 and damper_forbids(dev, wall, v):
        return 0.0
    if lo == 0.0:
        lo = hi
        while lo > 1e-300 and not criterion_passes(dev, wall, lo, v):
            lo *= 0.5
        if not criterion_passes(dev, wall, lo, v):
            return 0.0
        hi = 2.0 * lo
    while hi - lo > CRITERION_RTOL * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if criterion_passes(dev, wall, mid, v) else (lo, mid)
    return lo


def closed_forms(
    dev: Device, wall: Wall, v: float, *, k_criterion: float | None = None, k_linear: float | None = None
) -> tuple[KLimit, KLimit, dict[str, float | None], float, float]:
    """K_criterion and K_linear as limits, the published bounds, and the search grid's reference K and top.

    The spring (any delay) takes the closed forms of eq. 11 and the exact linear bound k_gil, and the grid
    from K_criterion/2 to 8 × the largest closed-form bound; a wall, the criterion's verdict (none where no
    criterion covers it) and the linear loop with the wall, its grid from K_criterion/2 (else K_linear/2).
    A caller that has already computed a wall's :func:`wall_k_criterion` or :func:`linear_limit` (the Z-width's
    columns) passes them as ``k_criterion`` and ``k_linear`` (N/m): they replace those calls for a linear wall
    other than the spring, nothing else (the spring's are closed forms).
    """
    if not wall.linear:
        return _nonlinear_forms(dev, wall, v)
    p = wall.params(dev.period, dev.resolution)
    spring = p.covers(Coverage.CLOSED_FORM)
    kl = k_linear if k_linear is not None and not spring else linear_limit(dev, wall)
    if spring:
        d = p.delay
        kc = float(k_max_criterion(dev, v, d))
        pub: dict[str, float | None] = dict(
            k_static=k_static(dev), k_colgate=k_colgate(dev, d), k_abbott_okamura=k_abbott_okamura(dev, d)
        )
        top = 8.0 * max(k_static(dev), k_colgate(dev, d), kl, kc)
        return _limit(kc, LimitStatus.NONE_PROVEN), _limit(kl, LimitStatus.NO_STABLE_K), pub, kc, top
    pub = dict(k_static=None, k_colgate=None, k_abbott_okamura=None)
    if p.not_covered() is not None:
        crit = KLimit(None, LimitStatus.NOT_COVERED)
        return crit, _limit(kl, LimitStatus.NO_STABLE_K), pub, kl, 8.0 * max(k_static(dev), kl)
    kc = wall_k_criterion(dev, wall, v) if k_criterion is None else k_criterion
    never = dev.coulomb <= wall.damping * damper_friction_per_damping(dev, wall)
    crit = _limit(kc, LimitStatus.NEVER if never else LimitStatus.NONE_PROVEN)
    return crit, _limit(kl, LimitStatus.NO_STABLE_K), pub, kc, 8.0 * max(k_static(dev), kl, kc)


def _nonlinear_forms(dev: Device, wall: Wall, v: float) -> tuple[KLimit, KLimit, dict[str, float | None], float, float]:
    """:func:`closed_forms` of a wall that is not a linear loop: the criterion where one covers it (a one-sided
    wall's lone spring, its impact at v from free space), no linear bound, and the grid of the linear wall beneath
    it (a one-sided wall's in contact, :meth:`~dfa.model.wall.Wall.in_contact`; without a passivity controller,
    :meth:`~dfa.model.wall.Wall.without_controller`; without any element that declares a ``linear_reason``, such
    as an actuator's force limit), from its own K_criterion/2 where it has one."""
    contact = wall.in_contact()
    beneath = Wall(contact.stiffness, tuple(e for e in contact.elements if type(e).linear_reason is None))
    _kc, _kl, _pub, k_ref, top = closed_forms(dev, beneath, v)
    pub: dict[str, float | None] = dict(k_static=None, k_colgate=None, k_abbott_okamura=None)
    linear = KLimit(None, LimitStatus.NOT_LINEAR)
    if wall.params(dev.period, dev.resolution).not_covered() is not None:
        return KLimit(None, LimitStatus.NOT_COVERED), linear, pub, k_ref, top
    kc = wall_k_criterion(dev, wall, v)
    return _limit(kc, LimitStatus.NONE_PROVEN), linear, pub, (kc if kc > 0.0 else k_ref), top


def linear_limit(dev: Device, wall: Wall) -> float:
    """K_linear: the top of the stable interval from K = 0 of the linear loop (no encoder, no Coulomb friction).

    The spring (any delay) takes the exact bound :func:`~dfa.analysis.limits.closed_form.k_gil`; a wall, the
    linear loop with its elements (:func:`~dfa.analysis.linear_wall.stable_stiffness`). 0 when no K is stable.
    """
    from ..linear_wall import stable_stiffness

    p = wall.params(dev.period, dev.resolution)
    if p.covers(Coverage.CLOSED_FORM):
        return float(k_gil(dev, delay=p.delay))
    return float(stable_stiffness(dev.mass, dev.damping, dev.period, wall).k_crit)


def describing_limit(
    dev: Device,
    wall: Wall,
    v: float,
    model: str = "half-delay",
    cache: RunCache | None = None,
    grid: int = 16,
    *,
    k_criterion: float | None = None,
    k_linear: float | None = None,
) -> KLimit:
    """K_df of :func:`design_answer` for ``wall`` at speed v: the same grid (:func:`closed_forms`) and search.

    The one describing-function limit of a wall: the Z-width's column and the inverse question
    (:mod:`dfa.analysis.limits.require`) call it; the design answer computes it in the same way.
    ``k_criterion`` and ``k_linear``: the wall's :func:`wall_k_criterion` and :func:`linear_limit` (N/m) where the
    caller has them (:func:`closed_forms`), so that they are not computed twice.
    """
    if not wall.linear:
        return KLimit(None, LimitStatus.NOT_LINEAR)
    _kc, _kl, _pub, k_ref, top = closed_forms(dev, wall, v, k_criterion=k_criterion, k_linear=k_linear)
    if not (top > 0 and math.isfinite(top)):
        return KLimit(None, LimitStatus.NO_RANGE)
    ev = Evidence(dev, wall, np.array([v]), DESIGN_MAX_SAMPLES, model, RunCache() if cache is None else cache)
    return df_limit(ev, search_grid(k_ref, top, grid), dev.xi_dot(v))


def _check_search_range(dev: Device, k_ref: float, top: float, grid: int) -> None:
    """Refuse the searches' grid (:func:`search_grid`) where μ leaves its range (:func:`check_stiffness_range`);
    a top that is not finite is no range (the searches say ``no_range``)."""
    if top > 0 and math.isfinite(top):
        pts = search_grid(k_ref, top, grid)
        what = "the stiffness search (K_criterion/2 to 8 × the largest closed-form bound)"
        check_stiffness_range(dev, float(pts[0]), float(pts[-1]), what)


def check_search_range(device: Device, wall: Wall, velocity: float, grid: int = 16) -> None:
    """Refuse, before any work, a device and wall whose stiffness search (:func:`design_answer` at ``velocity``)
    would run where μ = m/(K T²) leaves :data:`~dfa.analysis.limits.search.MU_RANGE` (``dfa stiffness --resolution
    1e300``: μ = 2.5e306 at the grid's lowest K).

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> check_search_range(get_device("Delta").device, Wall(1.0), 0.1)
    """
    if velocity > 0:
        _kc, _kl, _pub, k_ref, top = closed_forms(device, wall, velocity)
        _check_search_range(device, k_ref, top, grid)


def _limit(k: float, why: LimitStatus) -> KLimit:
    """A closed-form limit: its value, or None with ``why`` when it is 0."""
    return KLimit(k) if k > 0.0 else KLimit(None, why)


# ----------------------------------------------------------------------------- the searches
def _searches(
    ev: Evidence, v: float, k_ref: float, top: float, n_grid: int, simulate: bool = True
) -> tuple[KLimit, KLimit, KLimit, tuple]:
    """K_df, K_sim, K_sim_rest over one geometric grid from k_ref/2 to ``top``, and the grid's range (without
    ``simulate``: K_df alone, the simulated limits ``not_simulated``)."""
    if not (top > 0 and math.isfinite(top)):
        none = KLimit(None, LimitStatus.NO_RANGE)
        return none, none, none, (0.0, 0.0)
    pts = search_grid(k_ref, top, n_grid)
    xd = ev.dev.xi_dot(v)
    steps = search_steps(pts)
    with stage("K_df (describing function)", steps, "judgement"):  # describing_limit's search
        k_df = df_limit(ev, pts, xd) if ev.wall.linear else KLimit(None, LimitStatus.NOT_LINEAR)
    if not simulate:
        k_sim = k_rest = KLimit(None, LimitStatus.NOT_SIMULATED)
    else:
        with stage("K_sim (no divergence)", steps, "judgement"):
            k_sim = simulated_limit(ev, pts, "unstable")
        with stage("K_sim_rest (every impact rests)", steps, "judgement"):
            k_rest = simulated_limit(ev, pts, "rest")
    return k_df, k_sim, k_rest, (float(pts[0]), float(pts[-1]))


def searched_limits(
    ev: Evidence, v: float, n_speeds: int, kc: float | None, k_ref: float, top: float, n_grid: int
) -> tuple[KLimit, KLimit, KLimit, tuple[float, float], tuple[Failure, ...], KMaxStatus]:
    """K_df, K_sim, K_sim_rest searched and confirmed with ``ev`` (the one implementation, spring or wall).

    The simulated limits are swept in K from ``kc`` (None or 0: from the grid's lowest point) at the search
    speeds and confirmed at :data:`~dfa.analysis.limits.search.DENSE_FACTOR` × ``n_speeds`` speeds; divergent
    runs at or below ``kc`` are counterexamples (``kc`` None: no criterion, no check). ``ev.runs`` counts every
    run, sweep and confirmation included.

    Returns
    -------
    (KLimit, KLimit, KLimit, (float, float), tuple of Failure, KMaxStatus)
        k_df, k_sim, k_sim_rest, the grid's range, the counterexamples and the status.
    """
    k_df, k_sim, k_rest, k_range = _searches(ev, v, k_ref, top, n_grid)
    dense_vs = v * np.arange(1, DENSE_FACTOR * n_speeds + 1) / (DENSE_FACTOR * n_speeds)
    dense = Evidence(ev.dev, ev.wall, dense_vs, ev.max_samples, ev.model, ev.cache)
    found = [s.value for s in (k_sim, k_rest) if s.value is not None]
    if found:  # one sweep from K_criterion (else the grid's lowest point): k_sim_rest's points are k_sim's
        k_lo, by_criterion = (kc, True) if kc else (k_range[0], False)
        budget = ev.wall.params(ev.dev.period, ev.dev.resolution).sweep_points()
        sweep = Sweep.up_to(k_lo, by_criterion, max(found), budget)
        with stage("sweep in K and confirmation"):
            ev.prefetch(sweep.points(max(found)))  # one threaded batch for both limits
            k_sim = confirm(k_sim, ev, dense, "unstable", sweep, k_range[0])
            k_rest = confirm(k_rest, ev, dense, "rest", sweep, k_range[0], k_sim.value)
    ev.runs += dense.runs
    ce = tuple(Failure(c["stiffness"], c["velocity"], c["start"], c["outcome"], "search") for c in
               ev.counterexamples(kc) + dense.counterexamples(kc))  # fmt: skip
    caveat = any(s.caveat for s in (k_df, k_sim, k_rest))
    status = KMaxStatus.COUNTEREXAMPLE if ce else (KMaxStatus.CAVEATS if caveat else KMaxStatus.OK)
    return k_df, k_sim, k_rest, k_range, ce, status


# ----------------------------------------------------------------------------- the assessment of the wall's own K
def passive_speed(dev: Device, wall: Wall, k: float) -> tuple[float | None, VelocityStatus]:
    """Largest speed (m/s) the criterion proves passive at K with ``wall``'s elements (inf: every speed; None:
    none), and its status: eq. 11-12 for the spring, the criterion with the wall otherwise."""
    p = wall.params(dev.period, dev.resolution)
    if p.covers(Coverage.CLOSED_FORM):
        mpv = max_passive_velocity(dev, k, p.delay)
    elif p.not_covered() is not None:
        return None, VelocityStatus.NOT_COVERED
    else:
        r = device_criterion(Loop(dev, wall.with_stiffness(k)), 0.0)
        mpv = None if r.sigma < r.sigma0 else (math.inf if r.critical_velocity is None else r.critical_velocity)
    if mpv is None:
        return None, VelocityStatus.NONE
    return mpv, (VelocityStatus.ALL_SPEEDS if math.isinf(mpv) else VelocityStatus.BOUNDED)


def _assess(
    ev: Evidence, k: float, source: str, source_file: str | None, velocity: float, simulate: bool = True
) -> KMaxAssessment:
    """The wall's own stiffness at the impact speed: criterion, predicted cycles, simulated outcomes (none
    without ``simulate``)."""
    dev = ev.dev
    g = ev.growth_xi_dot(k)
    unknown = "subtick" if g.subtick else ("incomplete" if g.xi_dot is None else None)
    unknown = "not_linear" if not ev.wall.linear else unknown
    xi = None if g.subtick else g.xi_dot  # the sub-tick caveat: the growth speed is not a threshold to rely on
    outs: list[str] = []
    if simulate:
        p, w = ev.params(k)
        pts = start_points(p.mu, p.beta, p.sigma, dev.xi_dot(velocity), w)
        outs, _ = ev.cache.simulate(pts, w, ev.max_samples)  # type: ignore[arg-type]
        ev.runs += len(pts)
    gs = None if xi is None else (math.inf if math.isinf(xi) else dev.velocity(xi))
    mpv, vstatus = passive_speed(dev, ev.wall, k)
    verdict = StiffnessStatus.OK if mpv is not None and mpv >= velocity else StiffnessStatus.TOO_STIFF
    if vstatus is VelocityStatus.NOT_COVERED:
        verdict = StiffnessStatus.NOT_COVERED
    outcomes = dict(zip(ev.starts, outs, strict=True)) if simulate else {}
    return KMaxAssessment(k, source, mpv, vstatus, verdict, gs, unknown, g.unstable, outcomes, source_file)


@loop_first("device, *, wall")
def design_answer(
    loop: Loop,
    velocity: float,
    *,
    assess: bool = False,
    source: str = "given",
    source_file: str | None = None,
    speeds: int = 6,
    grid: int = 16,
    max_samples: int = DESIGN_MAX_SAMPLES,
    df_model: str = "half-delay",
    cache: RunCache | None = None,
    simulate: bool = True,
) -> KMaxResult:
    """The largest stiffness for impacts up to ``velocity``, four ways, for the spring or a wall (module docstring).

    Parameters
    ----------
    loop : Loop
        The device and the wall whose elements (delay d in samples, damper B in N·s/m, filter, amplifier) are
        held fixed while K varies, ``Loop(device, wall)`` (the wall may be a stiffness K in N/m, rotary N·m/rad,
        for the spring alone); ``Loop(device)``: the spring at no given K. The former call
        ``design_answer(device, velocity, wall=wall)`` still works.
    velocity : float
        Impact speed V in m/s (rotary: rad/s), >= 0 (a negative is refused, not flipped). At 0 only the
        closed forms are computed; the searched limits are ``not_searched``.
    assess : bool, optional
        Also assess the wall's own stiffness K (default False).
    source : str, optional
        Where that K came from, for the assessment: ``"given"`` (default), ``"catalogue"`` or ``"device file"``.
    source_file : str, optional
        With ``source="device file"``: the file, as the user named it (said in the verdict on K).
    speeds : int, optional
        Number of impact speeds simulated: V/speeds, 2V/speeds, …, V (default 6), each with two starts.
    grid : int, optional
        Points of the geometric stiffness grid (default 16); bisection refines each limit to a relative 2·10⁻³.
    max_samples : int, optional
        Longest run, in samples (default 10⁶); longer automatic lengths are cut and may be undecided.
    df_model : {"half-delay", "zoh", "pade"}, optional
        Hold model of the describing function (default ``"half-delay"``; ``"zoh"`` is exact but ~10× slower).
    cache : RunCache, optional
        Runs and predictions already computed (shared with the stiffness–speed chart by the design
        analysis); a fresh one when None. The result does not depend on it.
    simulate : bool, optional
        False: a quick answer without simulation (``dfa stiffness --quick``): the criterion (eq. 11), the static
        and exact linear bounds and the describing function as in the full answer, the simulated limits
        ``not_simulated``, and the wall's own K assessed without its two impacts (default True).

    Returns
    -------
    KMaxResult
        The four limits with their evidence, the spring's published bounds and, with ``assess``, the
        assessment of the wall's K.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, the speed is not a finite number > 0, or another input is
        out of range.

    See Also
    --------
    stiffness_limits : The spring's closed-form limits alone (fast).
    stiffness_speed_chart : The same limits over a range of speeds.
    design_analysis : Everything the design report states.
    """
    dev = check_type("loop", loop, Loop, LOOP_FIX).search_device("design_answer")
    v = check_speed("velocity", velocity, dev.units["velocity"])
    wall, w = loop.wall, loop.spring
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one impact speed")
    n_grid = check_int("grid", grid, minimum=2, fix="give at least 2 stiffness grid points")
    cap = check_int("max_samples", max_samples, minimum=1000, fix="allow runs of at least 1000 samples")
    model = check_choice("df_model", df_model, DF_MODELS)
    check_choice("source", source, ("given", "catalogue", "device file"))
    if source_file is not None and (source != "device file" or not isinstance(source_file, str)):
        raise DFAValueError(
            f"source_file = {source_file!r} is invalid with source = {source!r}: it names the device file K came "
            'from (a str), with source = "device file" only'
        )
    if cache is not None:
        check_type("cache", cache, RunCache, "pass a dfa.analysis.limits.runs.RunCache, or None")
    assess = check_bool("assess", assess, "pass True to assess the wall's own K, or False")
    simulate = check_bool("simulate", simulate, "pass False for a quick answer without simulation, or True")
    if assess and wall is None:
        raise DFAValueError("assess = True is invalid without a wall: give the wall (or its K) to assess")
    kc, kl, published, k_ref, top = closed_forms(dev, w, v)
    if v > 0:
        _check_search_range(dev, k_ref, top, n_grid)  # up front: a range no float search can run
    vs = v * np.arange(1, n_speeds + 1) / n_speeds if v > 0 else np.zeros(0)
    ev = Evidence(dev, w, vs, cap, model, RunCache() if cache is None else cache)
    # the criterion's K for the sweep and the counterexample check: None where no criterion covers the wall
    k_crit = None if kc.status is LimitStatus.NOT_COVERED else (kc.value or 0.0)
    if v > 0 and simulate:
        k_df, k_sim, k_rest, k_range, ce, status = searched_limits(ev, v, n_speeds, k_crit, k_ref, top, n_grid)
    elif v > 0:  # the quick answer: the describing function's search alone, on the full answer's grid
        k_df, k_sim, k_rest, k_range = _searches(ev, v, k_ref, top, n_grid, simulate=False)
        ce, status = (), KMaxStatus.NOT_SIMULATED
    else:  # no impact: nothing to search (the closed forms hold at rest)
        k_df = k_sim = k_rest = KLimit(None, LimitStatus.NOT_SEARCHED)
        k_range, ce, status = (0.0, 0.0), (), KMaxStatus.OK
    evidence = SearchEvidence(ev.speeds, ev.starts, DENSE_FACTOR, ev.runs, ev.longest, cap, model, k_range)
    # the assessment's two runs are not the limits' evidence
    a = _assess(ev, w.stiffness, source, source_file, v, simulate) if assess else None
    return KMaxResult(
        dev, w, v, dev.xi_dot(v), kc, kl, k_df, k_sim, k_rest, published["k_static"], published["k_colgate"],
        published["k_abbott_okamura"], evidence, ce, a, status,
    )  # fmt: skip
