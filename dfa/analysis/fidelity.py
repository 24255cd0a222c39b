"""How faithfully a wall renders the ideal spring: its force error over an impact, and how often its controller acts.

A stable wall may still feel wrong: the encoder's ticks, the delay, a damper and a passivity controller all make the
force the device receives differ from the ideal spring's −K x. :func:`force_error` measures that difference over
the first contact of an impact, the part of the touch a user feels most, in one number comparable across walls:

    e = sqrt(mean_h (φ_A(h) − φ_ideal(ξ(h)))²) / (ξ'0 sqrt(μ)),   h = 0 … n_c,

with φ_A(h) the force the wall applies from instant h (:meth:`dfa.results.simulation.SimulationResult.replay`, units
of KΔ), φ_ideal(ξ) = −ξ (a one-sided wall: −(ξ − s)⁺) the ideal spring at the true position (no delay, no encoder),
ξ'0 sqrt(μ) = V sqrt(m K)/(K Δ) the ideal spring's peak force on a free mass hit at V (paper Table 1: μ = m/(K T²),
time in samples), and n_c = ⌈π sqrt(μ)⌉ + d + 2 samples: the ideal first contact, half a period of the mass on the
spring, plus the delay d and two samples. The same simulated impact, run on to 10 n_c samples (at least 200), gives
the share of samples at which a passivity controller added a force.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.loop import Loop
>>> dev = get_device("impulse").device
>>> e, share = force_error(Loop(dev, 100.0), 0.05)
>>> 0.0 < e < 0.5, share is None
(True, True)
"""

from __future__ import annotations

import math

import numpy as np

from ..checks import check_positive, check_type
from ..errors import DFAValueError
from ..model.elements import OneSided, PassivityController
from ..model.loop import Loop
from .simulation import simulate

__all__ = ["force_error", "contact_samples", "MAX_MU"]

#: The largest μ = m/(K T²) whose first contact :func:`force_error` simulates (about 31,000 samples of contact).
MAX_MU = 1e8


def contact_samples(mu: float, delay: int) -> int:
    """n_c = ⌈π sqrt(μ)⌉ + d + 2: the ideal spring's first contact with a free mass, in samples, plus the delay.

    Examples
    --------
    >>> contact_samples(100.0, 0)    # π·10 = 31.4 samples, rounded up, + 2
    34
    """
    return math.ceil(math.pi * math.sqrt(mu)) + int(delay) + 2


def _surface(loop: Loop) -> float | None:
    """A one-sided wall's surface s in ticks (None: bilateral)."""
    _p, wp = loop.groups("force_error")
    for kind, g in wp.groups:
        if kind is OneSided:
            return float(g)  # type: ignore[arg-type]
    return None


def force_error(loop: Loop, velocity: float) -> tuple[float | None, float | None]:
    """The wall's force error against the ideal spring over an impact's first contact, and its controller's share.

    Parameters
    ----------
    loop : Loop
        A device and a wall at its stiffness K (``Loop(device, wall)``).
    velocity : float
        Impact speed V, m/s (rotary rad/s), > 0.

    Returns
    -------
    force_error : float or None
        The RMS force error over the first contact as a fraction of the ideal peak force (module docstring); None
        when the impact diverged within the first contact (no finite force to compare).
    controller_share : float or None
        The fraction of the simulated samples (up to rest, at most 10 n_c) at which the passivity controller
        added a force; None for a wall without one.

    Raises
    ------
    DFAValueError
        If ``velocity`` is not a finite number > 0, or the loop has no device or no stiffness.
    DFATypeError
        If ``loop`` is not a :class:`~dfa.model.loop.Loop`.

    See Also
    --------
    dfa.tune : The force error of each tuned wall at its recommended K.
    """
    check_type("loop", loop, Loop, "give Loop(device, wall) with the wall's stiffness")
    check_positive("velocity", velocity, "give the impact speed in m/s (rotary rad/s)")
    if loop.device is None:
        raise DFAValueError(
            "loop = a dimensionless loop is invalid for force_error: the impact speed is physical; give "
            "Loop(device, wall)"
        )
    params, wp = loop.groups("force_error")
    xi_dot = loop.device.xi_dot(velocity)
    if not params.mu <= MAX_MU:
        raise DFAValueError(
            f"loop = a wall of μ = {params.mu:.4g} is invalid for force_error: its first contact lasts more than "
            f"{contact_samples(MAX_MU, 0)} samples (μ <= {MAX_MU:g}); give a stiffer wall or a longer sample period"
        )
    n_c = contact_samples(params.mu, wp.delay)
    run = simulate(loop, xi_dot, samples=max(10 * n_c, 200), record=True)
    force, _energy, control = run.replay()
    xs = np.asarray(run.xi, dtype=float)
    s = _surface(loop)
    ideal = -xs if s is None else -np.maximum(xs - s, 0.0)
    err = force[: n_c + 1] - ideal[: n_c + 1]
    error = None
    if np.all(np.isfinite(err)):
        error = float(math.sqrt(float(np.mean(err * err))) / (xi_dot * math.sqrt(params.mu)))
    share = None
    if loop.wall is not None and loop.wall.element(PassivityController) is not None:
        n = run.recorded_samples + 1
        share = float(np.count_nonzero(control[:n] != 0.0) / n)
    return error, share
