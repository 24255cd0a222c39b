"""The approach from free space to a one-sided wall (issue 28 §1): where the device starts, and why there.

A real contact begins in free space: the operator moves the device toward the wall's surface s (ticks) at about
constant speed, the wall silent, its velocity estimate, filter and delay line tracking the motion. The compiled
simulator runs such an approach whenever a one-sided wall's run starts outside moving toward it
(:mod:`dfa.core.wall_kernel`): the operator's force balances friction and damping (σ + βV) so the device keeps
its speed V, until the wall first reads it inside; from then on the operator's force is the push p (0 by
default: a free impact). :func:`approach_start` gives the start: D samples (less a phase, ½ by default) before
the device reaches, at V, the first position the wall sees, ξ_e = ⌊s + ½⌋ (the first whose reading ⌊ξ⌋ + ½ lies
beyond s; s itself without the encoder)::

    ξ0 = ξ_e − V (D − phase),    ξ'0 = V.

The run starts with fresh memory *outside* the wall, where every command is 0 whatever the memory holds: by the
time the device arrives, its velocity estimate is that of the approach (after one sample), the delay line holds
the zeros of free space (after d samples), and a velocity filter of pole a has forgotten its fresh start to
a^{D − d − 1} (D is chosen so that this is below 1e-16: 37/(2πν_c) samples beyond d + 2). This is the start state
an independent check found not covered by the spring's proof: the controller's memory is that of the approach,
not fresh.

Examples
--------
>>> approach_start(2.0, samples=5, phase=0.0)     # ξ_e − V D
(-10.0, 2.0, 5)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..checks import check_bool, check_int, check_real, check_type
from ..errors import DFAValueError
from ..model.elements import Coverage, OneSided
from ..model.loop import Loop
from ..model.wall import WallParams
from .simulation import MAX_RECORD_BYTES, default_samples, preload_position

__all__ = [
    "approach_start",
    "approach_samples",
    "SimulationPlan",
    "plan_simulation",
    "StartConflict",
    "ApproachSpeedError",
    "StartBeyondBound",
    "RecordBudgetError",
]

#: The filter's memory of the fresh start is forgotten to this factor by the time the device arrives.
FORGOTTEN = 1e-16


def approach_samples(wall: WallParams) -> int:
    """Samples of approach after which the controller's memory is that of the approach (module docstring).

    Parameters
    ----------
    wall : WallParams
        The one-sided wall (its delay d and velocity filter ν_c).

    Returns
    -------
    int
        d + 2, plus ⌈ln(1/1e-16)/(2πν_c)⌉ with a velocity filter.

    Examples
    --------
    >>> approach_samples(WallParams.of(delay=1, damping=0.5, cutoff=0.05))
    121
    """
    w = check_type("wall", wall, WallParams, "give the wall's WallParams")
    extra = 0 if w.cutoff is None or w.damping == 0.0 else math.ceil(-math.log(FORGOTTEN) / (2.0 * math.pi * w.cutoff))
    return w.delay + 2 + extra


def approach_start(
    xi_dot: float,
    *,
    wall: WallParams | None = None,
    samples: int | None = None,
    quantize: bool = True,
    phase: float = 0.5,
) -> tuple[float, float, int]:
    """The state D samples before the device reaches a one-sided wall at speed V (module docstring).

    Parameters
    ----------
    xi_dot : float
        Impact speed V > 0 toward the wall, ticks per sample.
    wall : WallParams, optional
        The one-sided wall (its surface s, delay and filter); default: the surface at 0.
    samples : int, optional
        Samples D of approach (default :func:`approach_samples`).
    quantize : bool, optional
        With the encoder (default): the wall first sees the device at ξ_e = ⌊s + ½⌋, the first position whose
        reading ⌊ξ⌋ + ½ lies beyond s; without it at ξ_e = s.
    phase : float, optional
        How long before sample D the device reaches ξ_e, in samples, in [0, 1) (default ½: mid-sample; at 0
        the first reading inside is decided by rounding, ξ_e being a tick boundary).

    Returns
    -------
    tuple of (float, float, int)
        (ξ0, ξ'0) in ticks and ticks per sample, and D.

    Raises
    ------
    DFATypeError
        For a ``quantize`` that is not True or False (an array was read by its truth value).
    DFAValueError
        For V <= 0, a phase outside [0, 1), or a start beyond a float (V (D − phase) overflows). (A hand's spring is held by the operator during the approach, as
        friction is: the simulator's approach is the same.)

    See Also
    --------
    simulate : Runs the approach from this state (the operator's force balances friction until contact).
    OneSided : The one-sided wall.
    """
    v = check_real("xi_dot", xi_dot, "give the impact speed toward the wall in ticks per sample")
    if not v > 0.0:
        raise DFAValueError(f"xi_dot = {v!r} is invalid: the device must approach the wall (V > 0); give V > 0")
    w = WallParams() if wall is None else check_type("wall", wall, WallParams, "give the wall's WallParams")
    d = approach_samples(w) if samples is None else check_int("samples", samples, 1, "give whole samples >= 1")
    q = check_bool("quantize", quantize, "pass True (with the encoder) or False (the wall sees the surface itself)")
    ph = check_real("phase", phase, "give the arrival's phase in samples, in [0, 1)")
    if not 0.0 <= ph < 1.0:
        raise DFAValueError(f"phase = {ph!r} is invalid: it must lie in [0, 1) samples; give e.g. 0.5")
    engage = OneSided.engage(w.surface, q)  # the first position the wall sees
    start = engage - v * (d - ph)
    if not math.isfinite(start):  # V (D − phase) beyond a float: the start would be −inf
        raise DFAValueError(
            f"xi_dot = {v!r} is invalid with samples = {d}: the start ξ0 = ξ_e − V (D − phase) = {start} overflows a "
            "float; give an impact speed of a device, a few ticks per sample (or fewer samples)"
        )
    return start, v, int(d)


# ----------------------------------------------------------------------------- the plan of one simulation


class StartConflict(DFAValueError):
    """Start inputs that exclude each other: ``given`` (``"preload"``, ``"xi0"``) with a one-sided wall's approach
    (``one_sided``), or the preload and ξ0 together."""

    def __init__(self, given: tuple[str, ...], one_sided: bool) -> None:
        self.given, self.one_sided = given, one_sided
        why = "the run starts in free space before contact" if one_sided else "the preload sets ξ0 from the speed"
        with_what = " with a one-sided wall" if one_sided else " together"
        super().__init__(f"{' and '.join(given)} cannot be given{with_what}: {why}; give neither (or one)")


class ApproachSpeedError(DFAValueError):
    """A one-sided wall's run whose speed ``speed`` (ticks per sample) does not approach the wall (> 0)."""

    def __init__(self, speed: float) -> None:
        self.speed = speed
        super().__init__(f"xi_dot = {speed!r} is invalid with a one-sided wall: the device must approach it; give > 0")


class StartBeyondBound(DFAValueError):
    """A start ξ0 (``xi0``, ticks; from the preload when ``preload``) at or beyond the run's bound ``bound``."""

    def __init__(self, xi0: float, bound: float, preload: bool) -> None:
        self.xi0, self.bound, self.preload = xi0, bound, preload
        super().__init__(f"xi0 = {xi0!r} is invalid: beyond the bound of {bound:g} ticks; give a smaller start")


class RecordBudgetError(DFAValueError):
    """A recorded run of ``samples`` samples whose trajectory (``nbytes``) exceeds :data:`MAX_RECORD_BYTES`."""

    def __init__(self, samples: int, nbytes: int) -> None:
        self.samples, self.nbytes = samples, nbytes
        super().__init__(
            f"samples = {samples} is invalid with a record: {nbytes / 1024**3:.1f} GiB of trajectory (limit "
            f"{MAX_RECORD_BYTES / 1024**3:.0f} GiB); record nothing or simulate fewer samples"
        )


@dataclass(frozen=True)
class SimulationPlan:
    """Where one run starts and how long it is (:func:`plan_simulation`).

    Attributes
    ----------
    xi0, xi_dot0 : float
        The start (ticks, ticks per sample).
    samples : int
        The run's length in samples, the approach included (the given length, or the automatic one plus D).
    approach : int or None
        D, the samples of a one-sided wall's approach (:func:`approach_start`); None without one.
    """

    xi0: float
    xi_dot0: float
    samples: int
    approach: int | None


def _plan_start(
    loop: Loop, xi_dot: float, xi0: float | None, preload: bool, quantize: bool, bound: float
) -> tuple[float, float, int | None]:
    """(ξ0, ξ'0, D or None) of :func:`plan_simulation`."""
    assert loop.params is not None
    wp = loop.wall_params if loop.wall_params is not None else WallParams()
    if not wp.covers(Coverage.SURFACE_START):  # a one-sided wall: the approach from free space
        given = tuple(name for name, on in (("preload", preload), ("xi0", xi0 is not None)) if on)
        if given:
            raise StartConflict(given, True)
        if not xi_dot > 0.0:
            raise ApproachSpeedError(xi_dot)
        return approach_start(xi_dot, wall=wp, quantize=quantize)
    if preload and xi0 is not None:
        raise StartConflict(("preload", "xi0"), False)
    x0, v0 = (preload_position(loop.params.mu, xi_dot), 0.0) if preload else ((0.0 if xi0 is None else xi0), xi_dot)
    if not abs(x0) < bound:
        raise StartBeyondBound(x0, bound, preload)
    return x0, v0, None


def plan_simulation(
    loop: Loop,
    xi_dot: float,
    *,
    samples: int | None = None,
    xi0: float | None = None,
    preload: bool = False,
    quantize: bool = True,
    bound: float = math.inf,
    record_bytes: int = 0,
) -> SimulationPlan:
    """The start and length of one run, checked before it is run (the work of ``dfa simulate`` before the run).

    Parameters
    ----------
    loop : Loop
        The dimensionless loop (its μ, β, σ and wall).
    xi_dot : float
        Speed ξ'0 in ticks per sample (signed: the direction of motion); with a one-sided wall the approach's, > 0.
    samples : int, optional
        The run's length; default :func:`dfa.analysis.simulation.default_samples` plus the approach's D.
    xi0 : float, optional
        Start position in ticks (default 0); not with ``preload`` nor a one-sided wall.
    preload : bool, optional
        Start at rest with the spring preloaded to the speed's kinetic energy (section 5; default False).
    quantize : bool, optional
        With the encoder (default).
    bound : float, optional
        |ξ0| must lie below it, in ticks (default: no bound).
    record_bytes : int, optional
        Bytes recorded per sample instant (0: no record); the n + 1 instants must fit in :data:`MAX_RECORD_BYTES`.

    Returns
    -------
    SimulationPlan
        (ξ0, ξ'0, samples, D).

    Raises
    ------
    StartConflict, ApproachSpeedError, StartBeyondBound, RecordBudgetError
        The start inputs exclude each other, a one-sided wall's speed is not > 0, ξ0 lies beyond ``bound``, or
        the record would exceed the budget.

    Examples
    --------
    >>> plan_simulation(Loop.dimensionless(100.0, 0.5, 0.2), 2.0, samples=1000)
    SimulationPlan(xi0=0.0, xi_dot0=2.0, samples=1000, approach=None)
    """
    x0, v0, d = _plan_start(loop, xi_dot, xi0, preload, quantize, bound)
    p, wp = loop.params, loop.wall_params
    assert p is not None
    n = samples if samples is not None else default_samples(p.mu, p.beta, p.sigma, v0, x0, quantize, wall=wp)
    n += 0 if d is None or samples is not None else d  # the approach, before contact
    if record_bytes and record_bytes * (n + 1) > MAX_RECORD_BYTES:
        raise RecordBudgetError(n, record_bytes * (n + 1))
    return SimulationPlan(x0, v0, n, d)
