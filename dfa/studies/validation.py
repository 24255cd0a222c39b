"""Validation of every analytic prediction against the exact simulator.

Six measurements, published whatever they show:

1. **Limit cycles, predicted vs simulated.** For operating points covering
   regions b, c, d and e and μ from 1 to 200, every cycle predicted by the
   harmonic balance (half-sample-delay and exact-ZOH loops, exact D) is
   simulated: a stable one from ξ0 = 0, ξ'0 = Mω (on the cycle), measuring
   the settled amplitude and frequency; an unstable one from ±25 % around it,
   which should decay below and grow above (this confirms the Loeb sign).
2. **Critical impact speed, three ways**: the criterion's worst case
   (eq. 12), the describing function's growth threshold M_u·ω, and the true
   threshold found by bisection on ξ'0 in simulation (from ξ0 = 0 and with the
   spring preload of section 5).
3. **Criterion soundness and conservatism** over a (β, σ, ξ'0) grid at
   several μ: points the criterion calls passive that the simulation finds
   unstable (expected 0; each one is listed), and the conservatism: the share
   of the points that truly come to rest (outcome ``"rest"``, the absorbing
   state) that the criterion rejects. Chattering, oscillating and undecided
   points are counted separately, not as evidence of conservatism.
4. **Where the describing function breaks down**: the cycle errors binned by
   period in samples.
5. **Clusters of cycles** (β just below the linear bound, small σ): the
   describing function's growth band (smallest to largest unstable cycle,
   :class:`dfa.analysis.cycles.GrowthThreshold`) against a fine scan of ξ'0 from ξ0 = 0
   in simulation: the first diverging and the last non-diverging speed, and
   the paper's eq. 45 speed M·ω at the same point.
6. **Limit cycles with a wall controller** (issue 15): item 1 repeated with the
   describing function of the controlled loop (D(M) multiplying
   1 + β_B(1 − e^{−jω})F, delay and amplifier lag) on a small fixed grid of
   (μ, β, σ) × controllers (:data:`CONTROLLERS`: virtual damper, damper and
   velocity filter, amplifier lag, one sample of delay), both hold models,
   against the exact simulator with the same controller; errors published per
   controller and model, and the unstable cycles within
   :data:`dfa.analysis.cycles.SUBTICK_LIMIT` of the first level counted apart (the
   sub-tick caveat of :func:`dfa.analysis.cycles.subtick_caveat`).

The result holds numbers and records only; :mod:`dfa.studies.validation_document` words it (``validation.md``).

Examples
--------
>>> s = soundness((5.0,), (1.0,), grid=4, samples=2000, n_jobs=1, progress=False)
>>> s.points, s.violations
(16, ())
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from ..analysis.criterion import classify_region, passivity_criterion
from ..analysis.cycles import SUBTICK_LIMIT, growth_threshold, large_cycle_closed_form, limit_cycles
from ..analysis.maps import map_start, stability_map
from ..analysis.simulation import OUTCOMES, SimulationResult, divergence_bound, simulate
from ..checks import check_bool, check_choice, check_jobs, check_type
from ..grids import geometric_grid
from ..jsonable import explain_nulls, to_jsonable
from ..model.device import Params
from ..model.elements import Coverage
from ..model.loop import Loop
from ..model.wall import WallParams
from ..results.base import Result, figure_function
from ..results.status import ValidationStatus

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "ValidationResult",
    "validate",
    "cycle_checks",
    "controller_cycle_checks",
    "CONTROLLERS",
    "critical_speeds",
    "first_unstable_speed",
    "soundness",
    "cluster_threshold",
    "CLUSTER_POINTS",
    "PERIOD_BINS",
]

#: Period bins (samples) used to judge the describing function's range of validity.
PERIOD_BINS = (2.0, 4.0, 8.0, 16.0, 32.0, math.inf)


def _grid(quick: bool) -> list[Params]:
    mus = (1.0, 5.0, 20.0, 100.0) if quick else (1.0, 2.0, 5.0, 20.0, 50.0, 100.0, 200.0)
    betas = (0.05, 0.3, 0.6) if quick else (0.02, 0.1, 0.25, 0.4, 0.6, 0.8)
    sigmas = (0.1, 0.3, 0.8) if quick else (0.05, 0.15, 0.3, 0.45, 0.6, 1.0, 1.6)
    return [Params(m, b, s) for m in mus for b in betas for s in sigmas]


def cycle_checks(
    points: Iterable[Params],
    samples: int = 40_000,
    models: Sequence[str] = ("half-delay", "zoh"),
    wall: WallParams | None = None,
) -> list[dict]:
    """Simulate every predicted cycle of every point (items 1 and 6); one record per (point, model, cycle).

    With ``wall`` the cycles are those of the loop with that wall and the simulations use the same
    wall (:func:`simulate` with ``wall=``).
    """
    out = []
    for p in points:
        region = str(classify_region(p.beta, p.sigma, 0.0))

        def run(v: float, p: Params = p) -> SimulationResult:
            return simulate(Loop.dimensionless(p.mu, p.beta, p.sigma, wall), v, samples, record=False)

        for model in models:
            res = limit_cycles(Loop.dimensionless(p.mu, p.beta, p.sigma, wall), model=model, max_amplitude=2000.0)
            for c in res.cycles:
                rec = dict(
                    mu=p.mu,
                    beta=p.beta,
                    sigma=p.sigma,
                    region=region,
                    model=model,
                    amplitude=c.amplitude,
                    frequency=c.frequency,
                    period=c.period,
                    stable=c.stable,
                    family=c.family,
                )
                v = c.amplitude * c.frequency
                if c.stable:
                    r = run(v)
                    persists = r.outcome in ("chatter", "oscillating") and r.frequency is not None
                    rec.update(
                        confirmed=persists,
                        sim_amplitude=r.amplitude if persists else float("nan"),
                        sim_frequency=r.frequency if persists else float("nan"),
                        sim_outcome=r.outcome,
                    )
                    if persists:
                        rec.update(
                            amplitude_error=r.amplitude / c.amplitude - 1, frequency_error=r.frequency / c.frequency - 1
                        )
                else:
                    lo, hi = run(0.75 * v), run(1.25 * v)
                    # separates decay from growth: from below the motion ends smaller than M, from above larger
                    # (unstable, or caught by a larger stable cycle of the same cluster)
                    decays = lo.outcome != "unstable" and lo.amplitude < c.amplitude
                    grows = hi.outcome == "unstable" or hi.amplitude > c.amplitude
                    rec.update(
                        confirmed=decays and grows,
                        below=lo.outcome,
                        above=hi.outcome,
                        below_amplitude=lo.amplitude,
                        above_amplitude=hi.amplitude,
                    )
                out.append(rec)
    return out


#: Item 6: the wall controllers validated (name, dimensionless groups): β_B = 0.2, ν_c = 0.05, α = 0.5, d = 1.
CONTROLLERS = (
    ("damper", WallParams.of(damping=0.2)),
    ("damper + filter", WallParams.of(damping=0.2, cutoff=0.05)),
    ("amplifier lag", WallParams.of(lag=0.5)),
    ("delay 1", WallParams.of(delay=1)),
)


def _controller_grid(quick: bool) -> list[Params]:
    if quick:  # one point where every controller has a stable and an unstable cycle (the lag's ZOH search is slowest)
        return [Params(20.0, 0.05, 0.3)]
    return [Params(m, b, s) for m in (2.0, 5.0, 20.0, 100.0) for b in (0.05, 0.3) for s in (0.1, 0.3)]


def controller_cycle_checks(
    points: Iterable[Params],
    samples: int = 40_000,
    models: Sequence[str] = ("half-delay", "zoh"),
    controllers: Sequence[tuple[str, WallParams]] = CONTROLLERS,
) -> list[dict]:
    """Item 6: :func:`cycle_checks` with each controller of ``controllers`` ((name, WallParams) pairs).

    Each record also holds ``controller`` (the name), ``controller_params`` (the groups) and ``subtick``: an
    unstable cycle below :data:`dfa.analysis.cycles.SUBTICK_LIMIT` ticks (its separation is the sub-tick caveat's case).
    """
    out = []
    for name, ctl in controllers:
        for rec in cycle_checks(points, samples, models, wall=ctl):
            rec.update(
                controller=name,
                controller_params=ctl.to_dict(),
                subtick=(not rec["stable"]) and rec["amplitude"] < SUBTICK_LIMIT,
            )
            out.append(rec)
    return out


def first_unstable_speed(
    p: Params,
    v_lo: float,
    v_hi: float,
    samples: int,
    preload: bool,
    steps: int = 40,
    wall: WallParams | None = None,
) -> float | None:
    """Smallest impact speed ξ'0 (ticks/sample) whose exact simulation diverges, or None.

    A geometric scan of ``steps`` speeds from ``v_lo`` to ``v_hi`` (ticks/sample); the first unstable one is
    refined by 12 bisection steps against the scan point below it. Runs start at ξ0 = 0 with speed ξ'0, or at
    rest with the spring preloaded to the same energy (``preload``), or a one-sided wall's with the approach
    (:func:`dfa.analysis.maps.map_start`, its samples added); ``samples`` per run, with the wall ``wall``
    (default the spring without delay; :func:`dfa.simulate`). Stability need not be monotone in speed: slower
    speeds between scan points may diverge too.
    """
    from ..analysis.approach import approach_samples

    w = WallParams() if wall is None else wall
    n = samples + (0 if w.covers(Coverage.SURFACE_START) else approach_samples(w))

    def unstable(v: float) -> bool:
        x0, v0 = map_start(p.mu, v, preload, w)
        bound = divergence_bound(x0, v0, p.mu)  # beyond the impact's own travel (eq. 18-19)
        r = simulate(Loop.dimensionless(p.mu, p.beta, p.sigma, w), v0, n, xi0=x0, record=False, bound=bound)
        return r.outcome == "unstable"

    speeds = geometric_grid(v_lo, v_hi, steps)
    prev = None
    for v in speeds:
        if unstable(v):
            if prev is None:
                return float(v)
            a, b = prev, float(v)
            for _ in range(12):
                mid = math.sqrt(a * b)
                if unstable(mid):
                    b = mid
                else:
                    a = mid
            return b
        prev = float(v)
    return None


def critical_speeds(points: Iterable[tuple[str, Params]], samples: int = 20_000) -> list[dict]:
    """Item 2: criterion (eq. 12), describing function (M_u·ω) and simulated critical speeds, ticks per sample."""
    rows = []
    for name, p in points:
        loop = Loop.dimensionless(p.mu, p.beta, p.sigma)
        crit = passivity_criterion(loop, 0.0).critical_xi_dot
        thr = {}
        for model in ("half-delay", "zoh"):
            un = limit_cycles(loop, model=model, max_amplitude=5000.0).unstable_cycles
            thr[model] = un[0].amplitude * un[0].frequency if un else None
        ref = crit if crit and crit > 0 else 1.0
        v_sim = first_unstable_speed(p, 0.2 * ref, 30.0 * ref, samples, preload=False)
        v_pre = first_unstable_speed(p, 0.2 * ref, 30.0 * ref, samples, preload=True)
        rows.append(
            dict(
                name=name,
                mu=p.mu,
                beta=p.beta,
                sigma=p.sigma,
                criterion=crit,
                df_half_delay=thr["half-delay"],
                df_zoh=thr["zoh"],
                simulated=v_sim,
                simulated_preload=v_pre,
            )
        )
    return rows


#: Item 5: the cluster of issue 12 (μ = 5, β = 0.48, σ = 0.0201) and the Fig. 7 grid point (β = 98/199,
#: σ = 4/199) where the exact smallest unstable cycle lies furthest (14.6×) below eq. 45.
CLUSTER_POINTS = (
    ("cluster, β below the ZOH linear bound", Params(5.0, 0.48, 0.0201)),
    ("Fig. 7 grid, worst eq. 45 ratio", Params(5.0, 98 / 199, 4 / 199)),
)


def cluster_threshold(name: str, p: Params, speeds: ArrayLike, samples: int) -> dict:
    """Item 5: growth band (both loop models) and eq. 45 against simulated divergence over a fine ξ'0 scan (ξ0 = 0).

    Returns a JSON-ready record: ``first_diverging`` (smallest scanned ξ'0 whose run went unstable, or None),
    ``last_non_diverging`` (largest scanned ξ'0 whose run did not), ``interleaved`` (non-diverging speeds above the
    first diverging one), the band ends M·ω per model, eq. 45's M·ω, and whether the exact ZOH linear loop is stable.
    """
    from ..analysis.linear import linear_stable

    speeds = np.asarray(speeds, dtype=float)
    div = np.array(
        [
            simulate(Loop.dimensionless(p.mu, p.beta, p.sigma), float(v), samples, record=False).outcome == "unstable"
            for v in speeds
        ]
    )
    first = float(speeds[div][0]) if div.any() else None
    last = float(speeds[~div][-1]) if (~div).any() else None
    rec = dict(
        name=name,
        mu=p.mu,
        beta=p.beta,
        sigma=p.sigma,
        samples=samples,
        scan=[float(speeds[0]), float(speeds[-1]), int(speeds.size)],
        diverging=int(div.sum()),
        first_diverging=first,
        last_non_diverging=last,
        interleaved=int(((~div) & (speeds > first)).sum()) if first is not None else 0,
        linear_stable_zoh=bool(linear_stable(p.mu, p.beta)),
    )
    for model in ("half-delay", "zoh"):
        g = growth_threshold(Loop.dimensionless(p.mu, p.beta, p.sigma), model=model)
        rec[f"band_{model}"] = [g.xi_dot, g.xi_dot_high]
        rec[f"band_amplitude_{model}"] = [g.amplitude, g.amplitude_high]
        rec[f"unstable_{model}"] = g.unstable_count
        rec[f"grows_above_{model}"] = g.grows_above
    cf = large_cycle_closed_form(p.mu, p.beta, p.sigma)
    rec["eq45_amplitude"] = cf[0] if cf else None
    rec["eq45_xi_dot"] = cf[0] * cf[1] if cf else None
    why = {"first_diverging": "no scanned speed diverged", "last_non_diverging": "every scanned speed diverged"}
    why.update(dict.fromkeys(("eq45_amplitude", "eq45_xi_dot"), "eq. 45 has no large-cycle solution here"))
    for model in ("half-delay", "zoh"):
        for key in (f"band_{model}", f"band_amplitude_{model}", f"grows_above_{model}"):
            why[key] = "no growth band: no unstable cycle predicted by this model"
    return explain_nulls(rec, why)


@dataclass(frozen=True)
class Soundness(Result):
    """Item 3 over a grid: criterion verdicts against simulated outcomes.

    Its JSON (:meth:`~dfa.results.base.Result.to_dict`) holds every field and the :attr:`conservatism` (null,
    with the reason, when no point came to rest).
    """

    mus: tuple
    xi_dots: tuple
    points: int
    passive: int
    violations: tuple = field(default_factory=tuple)
    not_unstable: int = 0
    rejected_not_unstable: int = 0
    rest: int = 0
    rejected_rest: int = 0
    undecided: int = 0

    json_properties: ClassVar[tuple[str, ...]] = ("conservatism",)

    def __post_init__(self) -> None:
        object.__setattr__(self, "mus", tuple(self.mus))
        object.__setattr__(self, "xi_dots", tuple(self.xi_dots))
        object.__setattr__(self, "violations", tuple(self.violations))

    @property
    def conservatism(self) -> float:
        """Share of the simulated points that come to rest (outcome ``"rest"``) the criterion rejects."""
        return self.rejected_rest / self.rest if self.rest else float("nan")


def soundness(
    mus: Sequence[float],
    xi_dots: Sequence[float],
    grid: int,
    samples: int,
    n_jobs: int = -1,
    progress: bool = True,
    beta_range: tuple[float, float] = (0.0, 1.0),
    sigma_range: tuple[float, float] = (0.0, 2.5),
) -> Soundness:
    """Compare the criterion with simulated outcomes on (β, σ, ξ'0) grids for each μ (item 3)."""
    total = passive_n = not_unst = rej_nu = rest = rej_rest = undecided = 0
    violations = []
    for mu in mus:
        m = stability_map(
            mu,
            list(xi_dots),
            grid=grid,
            samples=samples,
            n_jobs=n_jobs,
            progress=progress,
            beta_range=beta_range,
            sigma_range=sigma_range,
        )
        for k, v in enumerate(m.xi_dots):
            reg = classify_region(m.beta[None, :], m.sigma[:, None], v)
            passive = (reg == "a") | (reg == "e")
            out = m.outcome[k]
            total += out.size
            passive_n += int(passive.sum())
            bad = passive & (out == OUTCOMES.index("unstable"))
            for i, j in zip(*np.nonzero(bad), strict=False):
                violations.append(dict(mu=mu, beta=float(m.beta[j]), sigma=float(m.sigma[i]), xi_dot=v))
            nu = out != OUTCOMES.index("unstable")
            not_unst += int(nu.sum())
            rej_nu += int((nu & ~passive).sum())
            # points that truly came to rest (the absorbing state), the measure of conservatism
            st = out == OUTCOMES.index("rest")
            rest += int(st.sum())
            rej_rest += int((st & ~passive).sum())
            undecided += int((out == OUTCOMES.index("undecided")).sum())
    return Soundness(
        tuple(mus), tuple(xi_dots), total, passive_n, tuple(violations), not_unst, rej_nu, rest, rej_rest, undecided
    )


def _stats(values: Iterable[float | None]) -> dict:
    a = np.abs(np.asarray([v for v in values if v is not None and np.isfinite(v)], dtype=float))
    if a.size == 0:
        return dict(n=0, median=float("nan"), worst=float("nan"))
    return dict(n=int(a.size), median=float(np.median(a)), worst=float(np.max(a)))


def _median(values: list[float]) -> float:
    return float(np.median(values)) if values else float("nan")


def _cycle_summary(cycles: list[dict]) -> list[dict]:
    """Item 1 per model and family: confirmed stable cycles' errors (:meth:`ValidationResult.cycle_summary`)."""
    out = []
    for model in ("half-delay", "zoh"):
        for fam in ("small", "large"):
            recs = [
                r for r in cycles if r["model"] == model and r["family"] == fam and r["stable"] and r.get("confirmed")
            ]
            tried = [r for r in cycles if r["model"] == model and r["family"] == fam and r["stable"]]
            out.append(
                dict(
                    model=model,
                    family=fam,
                    predicted=len(tried),
                    persisted=len(recs),
                    amplitude=_stats(r["amplitude_error"] for r in recs),
                    frequency=_stats(r["frequency_error"] for r in recs),
                )
            )
    return out


def _controller_cycle_summary(records: list[dict]) -> list[dict]:
    """Item 6 per controller and model (:meth:`ValidationResult.controller_cycle_summary`)."""
    out = []
    names = list(dict.fromkeys(r["controller"] for r in records))
    for name in names:
        for model in ("half-delay", "zoh"):
            recs = [r for r in records if r["controller"] == name and r["model"] == model]
            st = [r for r in recs if r["stable"]]
            ok = [r for r in st if r.get("confirmed")]
            un = [r for r in recs if not r["stable"]]
            sub = [r for r in un if r["subtick"]]
            out.append(
                dict(
                    controller=name,
                    model=model,
                    predicted=len(st),
                    persisted=len(ok),
                    amplitude=_stats(r["amplitude_error"] for r in ok),
                    frequency=_stats(r["frequency_error"] for r in ok),
                    unstable=len(un),
                    unstable_confirmed=sum(bool(r["confirmed"]) for r in un),
                    subtick_unstable=len(sub),
                    subtick_confirmed=sum(bool(r["confirmed"]) for r in sub),
                )
            )
    return out


@dataclass(frozen=True)
class ValidationResult(Result):
    """All validation measurements and their summaries (see module docstring).

    Its JSON (:meth:`to_dict`) is the key numbers of :meth:`summary` and the status: ``quick``, ``clusters``,
    the summaries of ``cycles`` and ``controller_cycles`` (:meth:`cycle_summary`,
    :meth:`controller_cycle_summary`) under their names, the numbers of :attr:`json_properties`, and
    ``speeds_ordered`` and ``controller_errors``; not the raw ``speeds``, ``soundness`` and ``samples``.
    """

    quick: bool
    cycles: list = field(metadata={"json": _cycle_summary})  # written as its summary
    speeds: list = field(metadata={"json": None})
    soundness: Soundness = field(metadata={"json": None})  # its key numbers are properties
    samples: int = field(metadata={"json": None})
    status: ValidationStatus = ValidationStatus.OK
    clusters: list = field(default_factory=list)
    controller_cycles: list = field(default_factory=list, metadata={"json": _controller_cycle_summary})

    json_properties: ClassVar[tuple[str, ...]] = (
        "soundness_violations", "soundness_passive", "soundness_points", "conservatism", "speed_df_median_error",
        "speed_df_worst_error", "criterion_conservatism_median", "criterion_conservatism_min",
        "short_period_frequency_error", "long_period_frequency_error", "loeb", "controllers",
    )  # fmt: skip

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", ValidationStatus.coerce(self.status))
        check_type("soundness", self.soundness, Soundness, "ValidationResult is built by dfa.validate; call that")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready key numbers (:meth:`summary`) and the status; NaN becomes null with its reason.

        :meth:`dfa.results.base.Result.to_dict` with ``speeds_ordered`` and ``controller_errors`` added: both
        name methods (:meth:`speeds_ordered` per case, :meth:`controller_errors`), which the JSON holds pooled.

        Returns
        -------
        dict
            Strict-JSON data: the key numbers of :meth:`summary`, the status and its message.
        """
        pooled = {"speeds_ordered": all(self.speeds_ordered()), "controller_errors": self.controller_errors()}
        return to_jsonable({**super().to_dict(), **pooled})

    def plot(self, ax: Axes | None = None, which: str = "cycles") -> Axes:
        """A validation figure: ``which="cycles"`` (:func:`dfa.render.figures.cycle_error_plot`) or ``"speeds"``
        (:func:`dfa.render.figures.critical_speed_plot`); returns the Axes."""
        fn = {"cycles": "cycle_error_plot", "speeds": "critical_speed_plot"}
        return figure_function(fn[check_choice("which", which, tuple(fn))])(self, ax)

    # ----- summaries
    def cycle_summary(self) -> list[dict]:
        """Median and worst relative error of amplitude and frequency per model and family (confirmed stable cycles)."""
        return _cycle_summary(self.cycles)

    def controller_cycle_summary(self) -> list[dict]:
        """Item 6, per controller and model: stable cycles predicted and persisted, their amplitude and frequency
        errors (median and worst of abs(simulated/predicted − 1)), unstable cycles predicted and separated (Loeb),
        and those below :data:`dfa.analysis.cycles.SUBTICK_LIMIT` ticks (``subtick``) with how many separated."""
        return _controller_cycle_summary(self.controller_cycles)

    def controller_errors(self) -> dict:
        """Item 6 pooled over every controller and model: median and worst amplitude and frequency error of the
        stable cycles that persisted, and the share of predicted stable cycles that persisted."""
        st = [r for r in self.controller_cycles if r["stable"]]
        ok = [r for r in st if r.get("confirmed")]
        return dict(
            predicted=len(st),
            persisted=len(ok),
            amplitude=_stats(r["amplitude_error"] for r in ok),
            frequency=_stats(r["frequency_error"] for r in ok),
        )

    def loeb_summary(self) -> dict:
        """How often the stability assigned by the Loeb criterion was confirmed by simulation."""
        st = [r for r in self.cycles if r["stable"]]
        un = [r for r in self.cycles if not r["stable"]]
        return dict(
            stable=len(st),
            stable_confirmed=sum(bool(r["confirmed"]) for r in st),
            unstable=len(un),
            unstable_confirmed=sum(bool(r["confirmed"]) for r in un),
        )

    def period_summary(self, model: str = "zoh") -> list[dict]:
        """Frequency and amplitude error of confirmed stable cycles per period bin (item 4)."""
        out = []
        lo = 0.0
        for hi in PERIOD_BINS:
            recs = [
                r
                for r in self.cycles
                if r["model"] == model and r["stable"] and r.get("confirmed") and lo <= r["period"] < hi
            ]
            out.append(
                dict(
                    period=(lo, hi),
                    amplitude=_stats(r["amplitude_error"] for r in recs),
                    frequency=_stats(r["frequency_error"] for r in recs),
                )
            )
            lo = hi
        return out

    @property
    def soundness_violations(self) -> int:
        """Points the criterion calls passive that the simulation finds unstable (item 3; expected 0)."""
        return len(self.soundness.violations)

    @property
    def soundness_passive(self) -> int:
        """Points of the soundness grid the criterion calls passive."""
        return self.soundness.passive

    @property
    def soundness_points(self) -> int:
        """Points of the soundness grid."""
        return self.soundness.points

    @property
    def conservatism(self) -> float:
        """Share of the points that come to rest that the criterion rejects (:attr:`Soundness.conservatism`)."""
        return self.soundness.conservatism

    def _speed_df_errors(self) -> list[float]:
        return [abs(r["df_zoh"] / r["simulated"] - 1) for r in self.speeds if r["df_zoh"] and r["simulated"]]

    @property
    def speed_df_median_error(self) -> float:
        """Median of abs(M·ω growth threshold (exact ZOH) / simulated critical speed − 1); NaN without a case."""
        return _median(self._speed_df_errors())

    @property
    def speed_df_worst_error(self) -> float:
        """Largest of those errors; NaN without a case."""
        errors = self._speed_df_errors()
        return float(np.max(errors)) if errors else float("nan")

    def _criterion_ratios(self) -> list[float]:
        return [r["simulated"] / r["criterion"] for r in self.speeds if r["simulated"] and r["criterion"]]

    @property
    def criterion_conservatism_median(self) -> float:
        """Median of simulated critical speed / the criterion's speed (eq. 12); NaN without a case."""
        return _median(self._criterion_ratios())

    @property
    def criterion_conservatism_min(self) -> float:
        """Smallest of those ratios; NaN without a case."""
        ratios = self._criterion_ratios()
        return float(np.min(ratios)) if ratios else float("nan")

    def _zoh_frequency_errors(self, short: bool) -> list[float]:
        return [
            abs(r["frequency_error"])
            for r in self.cycles
            if r["model"] == "zoh" and r["stable"] and r.get("confirmed") and (r["period"] < 8) == short
        ]

    @property
    def short_period_frequency_error(self) -> float:
        """Median frequency error of the confirmed stable exact-ZOH cycles of period < 8 samples; NaN without one."""
        return _median(self._zoh_frequency_errors(True))

    @property
    def long_period_frequency_error(self) -> float:
        """The same for periods >= 8 samples; NaN without one."""
        return _median(self._zoh_frequency_errors(False))

    @property
    def loeb(self) -> dict:
        """:meth:`loeb_summary`."""
        return self.loeb_summary()

    @property
    def controllers(self) -> dict[str, dict]:
        """The groups of each wall controller of item 6 (:data:`CONTROLLERS`), by name."""
        return {name: explain_nulls(ctl.to_dict(), {"cutoff": "no velocity filter"}) for name, ctl in CONTROLLERS}

    def speeds_ordered(self) -> list[bool]:
        """For each critical-speed case: criterion <= simulated (the criterion is conservative)."""
        return [
            r["simulated"] is None or (r["criterion"] is not None and r["criterion"] <= r["simulated"] * (1 + 1e-9))
            for r in self.speeds
        ]

    def summary(self) -> dict:
        """Key numbers (JSON-ready), used by the design report and the tests."""
        return {
            "quick": self.quick,
            "soundness_violations": self.soundness_violations,
            "soundness_passive": self.soundness_passive,
            "soundness_points": self.soundness_points,
            "conservatism": self.conservatism,
            "speed_df_median_error": self.speed_df_median_error,
            "speed_df_worst_error": self.speed_df_worst_error,
            "criterion_conservatism_median": self.criterion_conservatism_median,
            "criterion_conservatism_min": self.criterion_conservatism_min,
            "speeds_ordered": all(self.speeds_ordered()),
            "short_period_frequency_error": self.short_period_frequency_error,
            "long_period_frequency_error": self.long_period_frequency_error,
            "loeb": self.loeb,
            "cycles": self.cycle_summary(),
            "clusters": self.clusters,
            "controller_cycles": self.controller_cycle_summary(),
            "controller_errors": self.controller_errors(),
            "controllers": self.controllers,
        }


def _speed_cases(quick: bool) -> list[tuple[str, Params]]:
    from ..model.catalogue import get_device

    cases = []
    names = ("Delta", "Impulse Engine") if quick else ("Delta", "Impulse Engine", "Phantom 1.0", "Toolhandle")
    for n in names:
        p = get_device(n).params
        assert p is not None  # these catalogue rows are complete
        cases.append((n, p))
    extra = (
        [(5.0, 0.1, 0.9), (20.0, 0.2, 1.2)]
        if quick
        else [(2.0, 0.1, 0.7), (5.0, 0.1, 0.9), (20.0, 0.2, 1.2), (100.0, 0.05, 1.5), (200.0, 0.3, 2.0)]
    )
    cases += [(f"μ={m:g}, β={b:g}, σ={s:g}", Params(m, b, s)) for m, b, s in extra]
    return cases


def validate(quick: bool = False, n_jobs: int = -1, progress: bool = True) -> ValidationResult:
    """Run the whole validation (``quick``: a reduced set that runs in well under a minute).

    Parameters
    ----------
    quick : bool, optional
        Run the reduced set (default False: the full set, several minutes).
    n_jobs : int, optional
        Workers of the soundness maps (-1, default: all cores; 1: in this thread).
    progress : bool, optional
        Show tqdm progress bars (default True).

    Returns
    -------
    ValidationResult
        The limit-cycle checks, critical speeds, criterion soundness, cluster thresholds and the
        limit-cycle checks with each wall controller (item 6), with their summaries.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``n_jobs`` is not -1 or a whole number >= 1, or ``quick``/``progress`` are not booleans.

    See Also
    --------
    limit_cycles : The predictions checked against simulation.
    simulate : The exact simulation used as the reference.
    """
    for name, flag in (("quick", quick), ("progress", progress)):
        check_bool(name, flag)
    check_jobs("n_jobs", n_jobs)
    samples = 20_000 if quick else 40_000
    cycles = cycle_checks(_grid(quick), samples=samples)
    speeds = critical_speeds(_speed_cases(quick), samples=10_000 if quick else 30_000)
    if quick:
        snd = soundness((5.0, 100.0), (1.0, 5.0), grid=16, samples=10_000, n_jobs=n_jobs, progress=progress)
    else:
        snd = soundness(
            (1.0, 5.0, 20.0, 100.0, 200.0),
            (0.5, 1.0, 2.0, 5.0, 10.0, 20.0),
            grid=41,
            samples=30_000,
            n_jobs=n_jobs,
            progress=progress,
        )
    scan = np.arange(0.1, 12.01, 0.2) if quick else np.arange(0.05, 30.001, 0.05)
    clusters = [cluster_threshold(name, p, scan, 10_000 if quick else 40_000) for name, p in CLUSTER_POINTS]
    ctl_cycles = controller_cycle_checks(_controller_grid(quick), samples=samples)
    return ValidationResult(quick, cycles, speeds, snd, samples, clusters=clusters, controller_cycles=ctl_cycles)
