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

from ..checks import check_bool, check_int, check_real, check_type
from ..errors import DFAValueError
from ..model.elements import OneSided
from ..model.wall import WallParams

__all__ = ["approach_start", "approach_samples"]

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
