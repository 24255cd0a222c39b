"""The Z-width of a device: the renderable region of the (K, B) plane, four ways (issue 15, "Z-width").

For a device, an impact speed V, a computational delay d and optionally a
velocity-filter cutoff f_c and an amplifier bandwidth f_bw, the wall
F = −K q_{h−d} − B v_{h−d} (:mod:`dfa.model.wall`) is judged on a grid of
virtual stiffness K (N/m, geometric) × virtual damping B (N·s/m, linear), and
at each B the largest K is found four ways:

``linear``
    the exact linear bound: top of the stable K interval starting at K = 0 of
    the sampled loop without encoder and Coulomb friction
    (:func:`dfa.analysis.linear_wall.stable_stiffness`, every stable interval
    kept; not limited by the grid).
``passivity``
    Colgate–Schenkel for the general H(z) (:func:`dfa.analysis.colgate_schenkel.colgate_schenkel_damping`):
    the largest K with b above the certified ``damping_bound`` (the linear
    model's passivity, no encoder); and ``criterion``: the passivity criterion
    of eq. 6 extended to the damper, filter and delay
    (:func:`dfa.analysis.criterion.device_criterion`), a proof for
    the quantized device with Coulomb friction for impacts up to V. Both
    refuse an amplifier lag: then they are "not covered" (null with that
    reason), never guessed.
``df``
    the describing function, by the rule of :mod:`dfa.analysis.limits.kmax` (``k_df``): the
    first crossing of an ascending scan of the K grid, then bisection, of the
    predicted growth speed (smallest M·ω over every unstable cycle,
    :func:`dfa.analysis.cycles.limit_cycles` with the controller) against V.
``sim``
    exact simulation at every grid point: impacts at the speeds V/n, 2V/n, …,
    V from ξ0 = 0 and, separately, from rest with the spring preloaded to the
    same energy (as ``k_sim`` of :mod:`dfa.analysis.limits.kmax`). A point *diverges* when any
    run diverges, is *undecided* when none diverges and some run is too
    short to tell, comes *to rest* when every run rests, else is *bounded*
    (chatter or a sustained cycle). ``k_sim`` is the largest grid K below the
    first point (ascending in K) that diverges or is undecided; ``k_rest`` the
    largest below the first point that does not come to rest. These are grid
    values (resolution: one grid step in K), not bisected; points found safe
    again above the first failure are counted in ``non_monotone``. The runs are those of
    :func:`dfa.simulate` with the same inputs, outcomes included, run in chunks of
    :data:`POINTS_PER_CALL` points, each chunk one compiled call (:func:`dfa.core.batch.batch_wall_kernel`; pure-spring
    points through :func:`dfa.analysis.simulation.run_points`) on threads.

Any simulated divergence at a K the extended criterion proves passive is a
``counterexample`` (status ``"counterexample"``: a criterion bug). The
Colgate–Schenkel condition concerns the linear model; divergences below its
boundary are listed separately (``linear_passivity_violations``), not as
counterexamples.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> z = z_width(get_device("Impulse Engine").device, 0.1, grid=4, speeds=1, n_jobs=1)
>>> z.status in ("ok", "caveats"), z.counterexamples, z.stiffness.shape
(True, (), (4,))
>>> bool(z.boundary("linear")[0] > 0)      # the exact linear bound at B = 0: the spring's k_gil
True
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..._parallel import run_in_order
from ...checks import (
    _fmt,
    check_bool,
    check_delay,
    check_int,
    check_jobs,
    check_nonnegative,
    check_positive,
    check_speed,
    check_type,
)
from ...core import kernel
from ...errors import DFAValueError
from ...model.device import Device
from ...model.wall import Wall, WallParams
from ...results.codes import BOUNDED, DIVERGES, POINT_OUTCOMES, REST, UNDECIDED_POINT, ZWIDTH_METHODS
from ...results.jsonable import explain_nulls
from ...results.status import ZWidthStatus
from ..colgate_schenkel import colgate_schenkel_damping
from ..criterion import device_criterion
from ..linear_wall import LinearStatus, stable_stiffness
from ..simulation import (
    GROWTH,
    SETTLE,
    STABLE_AMPLITUDE,
    controller_run_codes,
    default_samples,
    divergence_bound,
    preload_position,
    run_points,
)
from .kmax import DIVERGENCE_BOUND, K_RTOL, SAFE, UNDECIDED, UNSAFE, _growth_xi_dot, df_verdict

__all__ = ["ZWidth", "z_width", "ZWIDTH_METHODS", "POINT_OUTCOMES"]

#: Longest run of one Z-width simulation (samples); longer automatic lengths are cut (and may be undecided).
ZWIDTH_MAX_SAMPLES = 200_000
#: Largest planned work in simulated samples; more is refused up front.
MAX_WORK_SAMPLES = 2.0e10
#: Largest grid (points per axis).
MAX_GRID = 200
#: Grid points per compiled call of the simulations (every run of each point; one chunk per thread task).
POINTS_PER_CALL = 16
#: Fewest values of B whose boundary columns run in worker processes when several workers are asked (fewer:
#: threads). A column is mostly the describing-function scan, pure Python that holds the GIL (about 0.25 s of
#: one core per column on the catalogue devices): on threads it runs on one core whatever the workers; a
#: worker process starts in about 2 s of one core (imports), once per session (joblib reuses its workers).
PROCESS_COLUMNS = 16

_NOT_COVERED = (
    "not covered: the condition assumes the zero-order hold drives the device directly; with an amplifier lag no "
    "sound passivity condition is available here (see the linear bound and the simulation)"
)


@dataclass(frozen=True)
class ZWidth:
    """The Z-width of a device (module docstring): K_max(B) per method and the simulated grid, physical units.

    Attributes
    ----------
    device : Device
    velocity : float
        Impact speed V, m/s (rotary: rad/s).
    delay : int
        Computational delay d, samples.
    filter_cutoff, amplifier_bandwidth : float or None
        Velocity-filter cutoff and amplifier bandwidth, Hz (None: none).
    speeds : tuple of float
        Impact speeds simulated (m/s), each from ξ0 = 0 and from the preload.
    stiffness : numpy.ndarray
        K grid, N/m (rotary: N·m/rad), ascending geometric.
    damping : numpy.ndarray
        B grid, N·s/m (rotary: N·m·s/rad), ascending.
    boundaries : dict of str to numpy.ndarray
        K_max(B) per method (:data:`ZWIDTH_METHODS`), N/m; NaN where undefined (``reasons`` says why).
    reasons : dict of str to tuple
        Per method, per B: why the value is NaN, or a caveat; None when plain.
    outcome : numpy.ndarray of int8, shape (len(damping), len(stiffness))
        Code of each simulated grid point (:data:`POINT_OUTCOMES`).
    max_samples : int
        Longest run, samples.
    simulations : int
        Exact simulations run.
    df_model : str
        Hold model of the describing function.
    counterexamples : tuple of dict
        Divergent grid points at a K the extended criterion proves passive (must be empty).
    linear_passivity_violations : tuple of dict
        Divergent grid points below the Colgate–Schenkel boundary (linear model; not a proof for the device).
    status : ZWidthStatus
        ``OK``, ``CAVEATS`` (undecided points or non-monotone columns) or ``COUNTEREXAMPLE``; its value (the JSON
        ``status``) is ``"ok"``, ``"caveats"`` or ``"counterexample"`` and ``status.message`` says what it means.
    """

    device: Device
    velocity: float
    delay: int
    filter_cutoff: float | None
    amplifier_bandwidth: float | None
    speeds: tuple[float, ...]
    stiffness: np.ndarray
    damping: np.ndarray
    boundaries: dict[str, np.ndarray]
    reasons: dict[str, tuple[str | None, ...]]
    outcome: np.ndarray
    max_samples: int
    simulations: int
    df_model: str
    counterexamples: tuple[dict[str, object], ...] = ()
    linear_passivity_violations: tuple[dict[str, object], ...] = ()
    status: ZWidthStatus = ZWidthStatus.OK

    def __post_init__(self) -> None:
        fix = "ZWidth is built by dfa.analysis.limits.zwidth.z_width; call that instead"
        check_type("device", self.device, Device, fix)
        check_positive("velocity", self.velocity, fix)
        check_delay(self.delay)
        nk, nb = self.stiffness.size, self.damping.size
        if self.outcome.shape != (nb, nk):
            raise DFAValueError(f"outcome has shape {self.outcome.shape} but must be ({nb}, {nk}); {fix}")
        if set(self.boundaries) != set(ZWIDTH_METHODS) or set(self.reasons) != set(ZWIDTH_METHODS):
            raise DFAValueError(f"boundaries and reasons must have the keys {ZWIDTH_METHODS}; {fix}")
        for name in ZWIDTH_METHODS:
            if self.boundaries[name].shape != (nb,) or len(self.reasons[name]) != nb:
                raise DFAValueError(f"boundary {name!r} must have one value per B ({nb}); {fix}")
        st = ZWidthStatus.coerce(self.status)
        object.__setattr__(self, "status", st)
        if (st is ZWidthStatus.COUNTEREXAMPLE) != bool(self.counterexamples):
            raise DFAValueError(
                f"status = {st.value!r} is invalid with {len(self.counterexamples)} counterexample(s): the status is "
                f"'counterexample' exactly when there is one; {fix}"
            )
        for arr in (self.stiffness, self.damping, self.outcome, *self.boundaries.values()):
            arr.flags.writeable = False

    def boundary(self, method: str) -> np.ndarray:
        """K_max(B) of one method (:data:`ZWIDTH_METHODS`), N/m; NaN where undefined.

        Parameters
        ----------
        method : str
            One of :data:`ZWIDTH_METHODS`.

        Returns
        -------
        numpy.ndarray
            One value per B of the grid.
        """
        if method not in ZWIDTH_METHODS:
            raise DFAValueError(f"method = {method!r} is invalid: it must be one of {', '.join(ZWIDTH_METHODS)}")
        return self.boundaries[method]

    def to_dict(self) -> dict[str, object]:
        """JSON-ready record: inputs, grids, K_max(B) per method (null with a reason), outcomes, status.

        Returns
        -------
        dict
            Strict-JSON data in the device's units (``units``).
        """
        methods = {}
        for name in ZWIDTH_METHODS:
            vals = [None if not math.isfinite(x) else float(x) for x in self.boundaries[name]]
            rec = {"k_max": vals, "reason": list(self.reasons[name])}
            methods[name] = explain_nulls(rec, {"k_max": "undefined at some B: see reason"})
        u = self.device.units
        out: dict[str, object] = {
            "device": self.device.name,
            "velocity": self.velocity,
            "delay": self.delay,
            "filter_cutoff": self.filter_cutoff,
            "amplifier_bandwidth": self.amplifier_bandwidth,
            "speeds": list(self.speeds),
            "stiffness": self.stiffness.tolist(),
            "damping": self.damping.tolist(),
            "boundaries": methods,
            "outcome": [[POINT_OUTCOMES[c] for c in row] for row in self.outcome.tolist()],
            "outcome_layout": "outcome[i][j]: damping[i], stiffness[j]",
            "max_samples": self.max_samples,
            "simulations": self.simulations,
            "df_model": self.df_model,
            "counterexamples": [dict(c) for c in self.counterexamples],
            "linear_passivity_violations": [dict(c) for c in self.linear_passivity_violations],
            "status": self.status.value,
            "status_message": self.status.message,
            "units": {"stiffness": u["stiffness"], "damping": u["damping"], "velocity": u["velocity"]},
        }
        return explain_nulls(
            out,
            {
                "filter_cutoff": "no velocity filter",
                "amplifier_bandwidth": "ideal amplifier (no lag)",
            },
        )

    def plot(self, ax: Any = None, design_point: tuple[float, float] | None = None) -> Any:
        """Draw the Z-width (B across, K up on a log axis, one line per method, simulated region shaded).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Axes to draw on (default: a new figure).
        design_point : (float, float), optional
            A design point (B, K) in the device's units to star (in the legend too).

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on: B across, K (log) up, one line per method.
        """
        from ...figures import plot_zwidth

        return plot_zwidth(self, ax=ax, design_point=design_point)


# ----------------------------------------------------------------------------- boundaries per B
def _ctl(k: float, b: float, d: int, fc: float | None, fbw: float | None) -> Wall:
    return Wall.of(k, b, d, filter_cutoff=fc, amplifier_bandwidth=fbw)


def _linear(dev: Device, b: float, d: int, fc, fbw) -> tuple[float, str | None]:
    """Top of the stable K interval from K = 0 of the linear loop (exact), with a caveat for other shapes."""
    r = stable_stiffness(dev.mass, dev.damping, dev.period, _ctl(1.0, b, d, fc, fbw))
    if r.status in (LinearStatus.NEVER, LinearStatus.NOT_AT_LOW_K):
        iv = ", ".join(f"({lo:.4g}, {hi:.4g})" for lo, hi in r.intervals)
        return math.nan, f"linear loop {r.status.value} stable" + (f"; stable K intervals: {iv}" if iv else "")
    if r.status is LinearStatus.SEVERAL:
        more = ", ".join(f"({lo:.4g}, {hi:.4g})" for lo, hi in r.intervals[1:])
        return r.k_crit, f"further stable intervals above K_crit: {more}"
    return r.k_crit, None


def _crossing(judge, ks: np.ndarray, what: str, unit: str, bisect: bool) -> tuple[float, str | None, int]:
    """Largest K before the first non-safe judgement of an ascending scan of ``ks`` (then bisection).

    Returns (value or NaN, reason or None, index of the first non-safe grid point or len(ks)).
    """
    verdicts = []
    for k in ks:
        verdicts.append(judge(float(k)))
        if verdicts[-1] != SAFE:
            break
    i = len(verdicts) - 1
    if verdicts[-1] == SAFE:
        return math.nan, f"{what} at every K of the grid, up to {ks[-1]:.5g} {unit}: the limit is above it", len(ks)
    if i == 0:
        return math.nan, f"{what} fails already at the smallest K of the grid, {ks[0]:.5g} {unit}", 0
    lo, hi, last = float(ks[i - 1]), float(ks[i]), verdicts[-1]
    while bisect and hi - lo > K_RTOL * hi:
        mid = math.sqrt(lo * hi)
        v = judge(mid)
        lo, hi = (mid, hi) if v == SAFE else (lo, mid)
        last = last if v == SAFE else v
    reason = f"limited by an undecided verdict at {hi:.5g} {unit}" if last == UNDECIDED else None
    return lo, reason, i


def _passivity_judges(dev: Device, b: float, v: float, d: int, fc, fbw):
    """Judges SAFE/UNSAFE of Colgate–Schenkel (certified bound) and of the extended criterion at damper B."""

    def cs(k: float) -> str:
        r = colgate_schenkel_damping(_ctl(k, b, d, fc, fbw), dev.period)
        return SAFE if dev.damping > r.damping_bound else UNSAFE

    def crit(k: float) -> str:
        try:
            r = device_criterion(dev, _ctl(k, b, d, fc, fbw), v)
        except DFAValueError:  # a group not representable at this K: no proof there
            return UNSAFE
        return SAFE if r.passive else UNSAFE

    return cs, crit


def _df_judge(dev: Device, b: float, xi_dot: float, d: int, fc, fbw, model: str, subtick: list | None = None):
    """Judge of the describing function at damper B; the K it calls undecided under the sub-tick caveat of
    :mod:`dfa.analysis.cycles.caveats` (growth speed not relied on, spring and controller alike) are appended to ``subtick``."""

    def judge(k: float) -> str:
        try:
            p, ctl = dev.params(k), _ctl(k, b, d, fc, fbw).params(dev.period)
        except DFAValueError:
            return UNDECIDED
        growth = _growth_xi_dot(p.mu, p.beta, p.sigma, d, model, None if ctl.is_spring else ctl)
        verdict = df_verdict(growth, xi_dot)
        if verdict == UNDECIDED and growth.subtick and subtick is not None:
            subtick.append(k)
        return verdict

    return judge


# ----------------------------------------------------------------------------- simulation of the grid
def _runs(dev: Device, k: float, b: float, ctl: WallParams, xi_dots, cap: int) -> list[tuple]:
    """The runs (μ, β, σ, ξ0, ξ'0, samples, bound) of one grid point: each speed from ξ0 = 0 and from the preload."""
    p = dev.params(k)
    out = []
    for xd in xi_dots:
        for x0, v0 in ((0.0, xd), (preload_position(p.mu, xd), 0.0)):
            # run length from the loop's time scales with the controller's net damping (an estimate: a run
            # too short to tell is "undecided", never a verdict)
            n = min(default_samples(p.mu, p.beta, p.sigma, v0, x0, ctl.delay, controller=ctl), cap)
            out.append((p.mu, p.beta, p.sigma, x0, v0, n, divergence_bound(x0, v0, p.mu, DIVERGENCE_BOUND)))
    return out


def _chunks(tasks: list[tuple], size: int) -> list[list[int]]:
    """Indices of the tasks in chunks of at most ``size`` consecutive points, spring and controller apart.

    A pure-spring point (:attr:`~dfa.model.wall.WallParams.is_spring`: B = 0, no filter, no lag) runs
    the spring kernel, as :func:`dfa.analysis.simulation.simulate` routes it; every other point the controller kernel.
    """
    out: list[list[int]] = []
    for i, (_, ctl) in enumerate(tasks):
        if not out or len(out[-1]) >= size or tasks[out[-1][0]][1].is_spring != ctl.is_spring:
            out.append([])
        out[-1].append(i)
    return out


def _run_chunk(tasks: list[tuple]) -> np.ndarray:
    """Outcome code of every point of a chunk (runs, controller): every run of the chunk in one compiled call.

    The runs are those :func:`dfa.analysis.simulation.simulate` would make with the same inputs (its tail length and
    default outcome rules; the spring kernel for a pure spring, else :mod:`dfa.core.wall_kernel`), bit for bit, and are
    classified by :func:`dfa.core.kernel.classify_batch` as :func:`~dfa.analysis.simulation.simulate` classifies one; the
    point's code follows from its runs' outcomes (:func:`_point_codes`). No GIL is held in the compiled calls.
    """
    runs = [r for rs, _ in tasks for r in rs]
    mu, beta, sigma, x0, v0, n, bound = (np.array(c) for c in zip(*runs, strict=True))
    ns = n.astype(np.int64)
    d, spring = tasks[0][1].delay, tasks[0][1].is_spring
    if spring:
        codes = run_points(mu, beta, sigma, x0, v0, ns, d, True, bound, STABLE_AMPLITUDE, GROWTH, SETTLE)[0]
    else:
        codes = controller_run_codes(mu, beta, sigma, x0, v0, ns, d, bound, [c for rs, c in tasks for _ in rs])
    return _point_codes(codes.reshape(len(tasks), -1))


def _point_codes(run_codes: np.ndarray) -> np.ndarray:
    """Code of each point (row) from its runs' outcome codes (:mod:`dfa.core.kernel`; module docstring).

    Diverges if any run is unstable, else undecided if any run is, else rest if every run rests, else bounded.
    """
    out = np.full(run_codes.shape[0], BOUNDED, dtype=np.int8)
    out[(run_codes == kernel.REST).all(axis=1)] = REST
    out[(run_codes == kernel.UNDECIDED).any(axis=1)] = UNDECIDED_POINT
    out[(run_codes == kernel.UNSTABLE).any(axis=1)] = DIVERGES
    return out


def _simulate_grid(tasks: list[tuple], jobs: int, progress: bool, label: str) -> np.ndarray:
    """Outcome code of every task (runs, controller), in order, chunks of points on ``jobs`` threads.

    Each chunk (:data:`POINTS_PER_CALL` points, :func:`_chunks`) is one compiled call that releases the GIL
    (:func:`_run_chunk`), run like the chunks of a stability map (:func:`dfa._parallel.run_in_order`): the
    result does not depend on ``jobs``; a progress bar counts the points; an interruption cancels the
    chunks not started.
    """
    from tqdm.auto import tqdm

    chunks = _chunks(tasks, POINTS_PER_CALL)
    bar = tqdm(total=len(tasks), unit="point", desc=label, disable=not progress, leave=False)
    try:
        parts = run_in_order(
            _run_chunk, [([tasks[i] for i in c],) for c in chunks], [len(c) for c in chunks], jobs, "threads", bar
        )
    finally:
        bar.close()
    codes = np.empty(len(tasks), dtype=np.int8)
    for c, part in zip(chunks, parts, strict=True):
        codes[c] = part
    return codes


def _grid_boundary(row: np.ndarray, ks: np.ndarray, bad: set[int], what: str, unit: str) -> tuple[float, str | None]:
    """Largest grid K below the first point of ``row`` whose code is in ``bad`` (NaN with a reason if none)."""
    hit = [j for j, c in enumerate(row) if c in bad]
    if not hit:
        return math.nan, f"{what} at every K of the grid, up to {ks[-1]:.5g} {unit}: the limit is above it"
    j = hit[0]
    if j == 0:
        return math.nan, f"{what} fails already at the smallest K of the grid, {ks[0]:.5g} {unit}"
    notes = []
    if row[j] == UNDECIDED_POINT:
        notes.append(f"limited by undecided runs at {ks[j]:.5g} {unit} (too short to tell, counted as not safe)")
    above = sum(1 for c in row[j + 1 :] if c not in bad)
    if above:
        notes.append(f"non-monotone: {above} grid K above the first failure found safe again")
    notes.append(f"grid value: the limit lies in [{ks[j - 1]:.5g}, {ks[j]:.5g}) {unit}")
    return float(ks[j - 1]), "; ".join(notes)


# ----------------------------------------------------------------------------- the analysis
def _grids(dev: Device, v: float, d: int, fc, fbw, grid: int, k_range, b_range) -> tuple[np.ndarray, np.ndarray]:
    """Default grids: B from 0 to m/T; K geometric up to 8 × the largest linear bound or static limit 2c/Δ."""
    if b_range is None:
        b_range = (0.0, dev.mass / dev.period)
    b0 = check_nonnegative("b_range[0]", b_range[0], "give the smallest virtual damping B >= 0")
    b1 = check_positive("b_range[1]", b_range[1], "give the largest virtual damping B > 0")
    if not b1 > b0:
        raise DFAValueError(f"b_range = ({_fmt(b0)}, {_fmt(b1)}) is invalid: it must satisfy low < high")
    bs = np.linspace(b0, b1, grid)
    if k_range is None:
        lin = [_linear(dev, float(b), d, fc, fbw)[0] for b in (b0, b1)]
        top = 8.0 * max([2.0 * dev.coulomb / dev.resolution] + [k for k in lin if math.isfinite(k)])
        low = 0.5 * lin[0] if math.isfinite(lin[0]) and lin[0] > 0 else top * 1e-4
        k_range = (min(low, top * 1e-2), top)
    k0 = check_positive("k_range[0]", k_range[0], "give the smallest stiffness K > 0")
    k1 = check_positive("k_range[1]", k_range[1], "give the largest stiffness K")
    if not k1 > k0:
        raise DFAValueError(f"k_range = ({_fmt(k0)}, {_fmt(k1)}) is invalid: it must satisfy low < high")
    return np.geomspace(k0, k1, grid), bs


def _plan(dev: Device, ks, bs, d, fc, fbw, xi_dots, cap: int) -> tuple[list[tuple], float]:
    """The simulation tasks of the grid (B-major) and their planned samples."""
    tasks, work = [], 0.0
    for b in bs:
        for k in ks:
            ctl = _ctl(float(k), float(b), d, fc, fbw).params(dev.period)
            runs = _runs(dev, float(k), float(b), ctl, xi_dots, cap)
            work += sum(r[5] for r in runs)
            tasks.append((runs, ctl))
    return tasks, work


def z_width(
    device: Device,
    velocity: float,
    *,
    delay: int = 0,
    filter_cutoff: float | None = None,
    amplifier_bandwidth: float | None = None,
    grid: int = 40,
    k_range: tuple[float, float] | None = None,
    b_range: tuple[float, float] | None = None,
    speeds: int = 2,
    max_samples: int = ZWIDTH_MAX_SAMPLES,
    df_model: str = "half-delay",
    n_jobs: int = -1,
    progress: bool = False,
) -> ZWidth:
    """The Z-width of ``device`` at impact speed ``velocity``: K_max(B) four ways and the simulated grid.

    Parameters
    ----------
    device : Device
        The physical device.
    velocity : float
        Impact speed V, m/s (rotary: rad/s), > 0 (a negative is refused, not flipped).
    delay : int, optional
        Computational delay d, samples (default 0).
    filter_cutoff : float or None, optional
        Velocity-filter cutoff f_c, Hz, below the Nyquist frequency (default None: no filter).
    amplifier_bandwidth : float or None, optional
        Amplifier bandwidth f_bw, Hz (default None: ideal amplifier).
    grid : int, optional
        Points per axis (default 40, at most 200).
    k_range : (float, float), optional
        Smallest and largest K of the geometric grid, N/m (default: from half the linear bound at the
        smallest B to 8 × the largest of the linear bound and 2c/Δ).
    b_range : (float, float), optional
        Smallest and largest B of the linear grid, N·s/m (default: 0 to m/T).
    speeds : int, optional
        Impact speeds simulated: V/speeds, …, V (default 2), each from ξ0 = 0 and from the preload.
    max_samples : int, optional
        Longest run, samples (default 2·10⁵); longer automatic lengths are cut and may be undecided.
    df_model : {"half-delay", "zoh", "pade"}, optional
        Hold model of the describing function.
    n_jobs : int, optional
        Workers (-1: all cores): threads for the simulations; for the per-B boundaries threads, or worker
        processes from :data:`PROCESS_COLUMNS` values of B on (their describing-function scans hold the GIL).
        The result does not depend on it.
    progress : bool, optional
        Show a progress bar on stderr.

    Returns
    -------
    ZWidth
        K_max(B) per method with reasons, the grid outcomes and the status.

    Raises
    ------
    DFAValueError, DFATypeError
        Bad inputs (negative B, cutoff above Nyquist, bad delay, ...), or planned work above
        :data:`MAX_WORK_SAMPLES` simulated samples (the message says how to lower it).

    See Also
    --------
    dfa.analysis.linear_wall.stable_stiffness : The exact linear bound at one B.
    dfa.analysis.criterion.device_criterion : The extended eq. 6 criterion.
    dfa.analysis.limits.kmax.design_answer : The four K_max of the spring (B = 0).
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    v = check_speed("velocity", velocity, zero=False)
    d = check_delay(delay)
    g = check_int("grid", grid, minimum=2, fix="give at least 2 points per axis")
    if g > MAX_GRID:
        raise DFAValueError(f"grid = {g} is invalid: it must be at most {MAX_GRID} points per axis; lower --grid")
    n_speeds = check_int("speeds", speeds, minimum=1, fix="simulate at least one impact speed")
    cap = check_int("max_samples", max_samples, minimum=1000, fix="allow runs of at least 1000 samples")
    if df_model not in ("half-delay", "zoh", "pade"):
        raise DFAValueError(f"df_model = {df_model!r} is invalid: it must be half-delay, zoh or pade")
    jobs = check_jobs("n_jobs", n_jobs)
    progress = check_bool("progress", progress, "pass True to show a progress bar, False for none")
    workers = (os.cpu_count() or 1) if jobs == -1 else jobs
    _ctl(1.0, 0.0, d, filter_cutoff, amplifier_bandwidth).params(dev.period)  # bad controller values: refuse first
    ks, bs = _grids(dev, v, d, filter_cutoff, amplifier_bandwidth, g, k_range, b_range)
    vs = v * np.arange(1, n_speeds + 1) / n_speeds
    xi_dots = [dev.xi_dot(float(s)) for s in vs]
    tasks, work = _plan(dev, ks, bs, d, filter_cutoff, amplifier_bandwidth, xi_dots, cap)
    if work > MAX_WORK_SAMPLES:
        raise DFAValueError(
            f"grid = {g} is invalid with speeds = {n_speeds} and max_samples = {cap}: the Z-width would simulate "
            f"{work:.3g} samples (limit {MAX_WORK_SAMPLES:.3g}); lower the grid, the speeds or max_samples"
        )
    codes = _simulate_grid(tasks, workers, progress, f"Z-width {dev.name}").reshape(g, g)
    return _assemble(
        dev, v, d, filter_cutoff, amplifier_bandwidth, vs, ks, bs, codes, cap, len(tasks), df_model, workers, progress
    )


def _column(dev, v, d, fc, fbw, ks, b: float, row: np.ndarray, model: str) -> list[tuple[float, str | None]]:
    """(K_max, reason) of every method (:data:`ZWIDTH_METHODS` order) at one B."""
    unit = dev.units["stiffness"]
    out = [_linear(dev, b, d, fc, fbw)]
    if fbw is not None:
        out += [(math.nan, _NOT_COVERED), (math.nan, _NOT_COVERED)]
    else:
        cs, crit = _passivity_judges(dev, b, v, d, fc, fbw)
        out.append(_crossing(cs, ks, "b >= the Colgate–Schenkel bound", unit, True)[:2])
        out.append(
            _crossing(
                crit,
                ks,
                "the extended criterion's passivity guarantee (its absence is no proof of instability)",
                unit,
                True,
            )[:2]
        )
    subtick: list[float] = []
    df = _df_judge(dev, b, dev.xi_dot(v), d, fc, fbw, model, subtick)
    k_df, why = _crossing(df, ks, "predicted growth speed >= V", unit, True)[:2]
    if why is not None and subtick:  # say when an unknown verdict came from the sub-tick caveat
        from ..cycles import SUBTICK_LIMIT

        why += (
            f"; growth speed unknown from K = {min(subtick):.5g} {unit} (the describing function's sub-tick caveat: "
            f"smallest unstable cycle below {SUBTICK_LIMIT:g} ticks, where simulation diverges from starts it says "
            "settle; see dfa.analysis.cycles.caveats)"
        )
    out.append((k_df, why))
    out.append(_grid_boundary(row, ks, {DIVERGES, UNDECIDED_POINT}, "no divergence", unit))
    out.append(_grid_boundary(row, ks, {BOUNDED, DIVERGES, UNDECIDED_POINT}, "rest after every impact", unit))
    return out


def _assemble(dev, v, d, fc, fbw, vs, ks, bs, codes, cap, n_points, model, workers: int, progress=False) -> ZWidth:
    """Boundaries per method from the grid and the closed forms (columns on ``workers`` threads, or processes
    from :data:`PROCESS_COLUMNS` columns on); status."""
    from tqdm.auto import tqdm

    args = [(dev, v, d, fc, fbw, ks, float(b), codes[i], model) for i, b in enumerate(bs)]
    bar = tqdm(total=len(args), unit="B", desc=f"Z-width {dev.name} boundaries", disable=not progress, leave=False)
    try:  # in order (dfa._parallel): the result does not depend on workers; Ctrl-C cancels the columns not started
        how = "processes" if workers > 1 and len(args) >= PROCESS_COLUMNS else "threads"
        cols = run_in_order(_column, args, [1] * len(args), workers, how, bar)
    finally:
        bar.close()
    arrays = {m: np.array([c[n][0] for c in cols], dtype=float) for n, m in enumerate(ZWIDTH_METHODS)}
    reasons = {m: tuple(c[n][1] for c in cols) for n, m in enumerate(ZWIDTH_METHODS)}
    unit = dev.units["stiffness"]
    ce, lpv = _violations(codes, ks, bs, arrays, unit)
    caveat = bool((codes == UNDECIDED_POINT).any()) or any(
        r is not None and "non-monotone" in r for m in ("sim", "rest") for r in reasons[m]
    )
    status = ZWidthStatus.COUNTEREXAMPLE if ce else (ZWidthStatus.CAVEATS if caveat else ZWidthStatus.OK)
    return ZWidth(
        dev, v, d, fc, fbw, tuple(float(s) for s in vs), ks, bs, arrays, reasons, codes, cap,
        n_points * 2 * len(vs), model, ce, lpv, status,
    )  # fmt: skip


def _violations(codes, ks, bs, arrays, unit) -> tuple[tuple[dict, ...], tuple[dict, ...]]:
    """Divergent grid points at or below the criterion's and Colgate–Schenkel's boundaries."""
    out: dict[str, list[dict]] = {"criterion": [], "passivity": []}
    for name, rows in out.items():
        for i, b in enumerate(bs):
            top = arrays[name][i]
            for j, k in enumerate(ks):
                if math.isfinite(top) and k <= top and codes[i, j] == DIVERGES:
                    rows.append({"stiffness": float(k), "damping": float(b), "outcome": "diverges", "unit": unit})
    return tuple(out["criterion"]), tuple(out["passivity"])
