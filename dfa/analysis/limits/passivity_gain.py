"""How much stiffness a passivity controller buys (issue 30): K_max by simulation with and without it.

The criterion, the exact linear bound and the describing function do not cover a passivity controller
(:class:`dfa.model.elements.PassivityController`), so its gain is the simulated limits' (:func:`design_answer`'s
``k_sim``, no divergence, and ``k_sim_rest``, every impact rests, searched in the same way for both walls):
:func:`passivity_gain` runs both answers, :func:`gain_of` compares two answers already computed (what
``dfa stiffness --passivity-controller`` does).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from ...checks import check_real, check_type
from ...errors import DFAValueError
from ...model.device import Device
from ...model.loop import LOOP_FIX, Loop, loop_first
from ...model.wall import Wall
from ...results.base import Result
from ...results.status import GainStatus, KMaxStatus
from .kmax import KMaxResult, design_answer
from .search import KLimit

__all__ = ["PassivityGain", "passivity_gain", "gain_of"]


def _ratio(a: KLimit, b: KLimit) -> float | None:
    """a/b of two found limits; None when either has no value."""
    if a.value is None or b.value is None or not b.value > 0.0:
        return None
    return a.value / b.value


@dataclass(frozen=True)
class PassivityGain(Result):
    """The simulated stiffness limits of a wall with its passivity controller and without it (N/m; N·m/rad).

    Attributes
    ----------
    device : Device
        The device.
    wall : Wall
        The wall with its passivity controller (at any K: K is what is searched).
    velocity : float
        The impact speed V in m/s (rad/s).
    k_sim, k_sim_rest : KLimit
        With the controller: the largest K no simulated impact up to V diverged at, and at which every impact
        rests (:func:`dfa.analysis.limits.kmax.design_answer`).
    plain_k_sim, plain_k_sim_rest : KLimit
        The same without the controller (:meth:`dfa.model.wall.Wall.without_controller`).
    status : GainStatus
        ``ok``; ``caveats`` when a limit of either wall has them; ``counterexample`` from the plain wall's answer.
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    k_sim: KLimit
    k_sim_rest: KLimit
    plain_k_sim: KLimit
    plain_k_sim_rest: KLimit
    status: GainStatus = GainStatus.OK

    json_properties = ("gain", "gain_rest")
    units_of = {"velocity": "velocity"}

    def __post_init__(self) -> None:
        check_type("device", self.device, Device, "give a dfa.Device")
        check_type("wall", self.wall, Wall, "give the dfa.Wall with its passivity controller")
        for name in ("k_sim", "k_sim_rest", "plain_k_sim", "plain_k_sim_rest"):
            check_type(name, getattr(self, name), KLimit, "give the KLimit of a design answer")
        check_real("velocity", self.velocity)
        if self.wall.passivity_controller is None:
            raise DFAValueError("wall has no passivity controller: add dfa.PassivityController() to its elements")
        object.__setattr__(self, "status", GainStatus.coerce(self.status))

    @property
    def gain(self) -> float | None:
        """The no-divergence limit with the controller over the one without it (None when either has no value)."""
        return _ratio(self.k_sim, self.plain_k_sim)

    @property
    def gain_rest(self) -> float | None:
        """The rest limit with the controller over the one without it (None when either has no value)."""
        return _ratio(self.k_sim_rest, self.plain_k_sim_rest)

    def null_reasons(self) -> dict[str, str]:
        """Why the gains may be null: a limit without a value (its status says why).

        Returns
        -------
        dict of str to str
            Reasons for ``gain`` and ``gain_rest``.
        """
        why = "a limit of one of the walls has no value (see its status)"
        return {"gain": why, "gain_rest": why}


def gain_of(with_controller: KMaxResult, plain: KMaxResult) -> PassivityGain:
    """Compare two answers: a wall with its passivity controller, and the same wall without it.

    Parameters
    ----------
    with_controller, plain : KMaxResult
        :func:`~dfa.analysis.limits.kmax.design_answer` of the two walls, same device and speed.

    Returns
    -------
    PassivityGain
        The simulated limits with and without the controller, and their ratios.

    Raises
    ------
    DFAValueError
        When the answers are not of one device and speed, or ``plain`` is not ``with_controller`` without it.
    """
    a, b = with_controller, plain
    if a.device != b.device or a.velocity != b.velocity or b.wall.elements != a.wall.without_controller().elements:
        raise DFAValueError(
            "plain is not the answer of the same wall without its passivity controller (same device and speed): "
            "compute it with design_answer(device, velocity, wall=wall.without_controller())"
        )
    statuses = {a.status, b.status}
    status = (
        GainStatus.COUNTEREXAMPLE
        if KMaxStatus.COUNTEREXAMPLE in statuses
        else (GainStatus.CAVEATS if KMaxStatus.CAVEATS in statuses else GainStatus.OK)
    )
    return PassivityGain(a.device, a.wall, a.velocity, a.k_sim, a.k_sim_rest, b.k_sim, b.k_sim_rest, status)


@loop_first("device, velocity, wall")
def passivity_gain(loop: Loop, velocity: float, **kwargs: Any) -> PassivityGain:
    """K_max by simulation with and without the wall's passivity controller (module docstring).

    Parameters
    ----------
    loop : Loop
        The device and a wall with a :class:`~dfa.model.elements.PassivityController` (its K is what is
        searched), ``Loop(device, wall)``. The former call ``passivity_gain(device, velocity, wall)`` still works.
    velocity : float
        The impact speed V in m/s (rotary rad/s), > 0.
    **kwargs
        Passed on to both :func:`~dfa.analysis.limits.kmax.design_answer` calls (``speeds``, ``grid``, …).

    Returns
    -------
    PassivityGain
        The simulated limits with and without the controller, and their ratios.

    Raises
    ------
    DFAValueError
        For a wall without a passivity controller, or a speed that is not > 0.

    See Also
    --------
    design_answer : K_max four ways, for one wall.
    dfa.PassivityController : The controller.
    """
    device = check_type("loop", loop, Loop, LOOP_FIX).search_device("passivity_gain")
    wall = loop.wall
    if wall is None or wall.passivity_controller is None:
        raise DFAValueError(
            f"wall = {wall!r} is invalid: it must be a dfa.Wall with a passivity controller; add "
            "dfa.PassivityController() to its elements"
        )
    if not (isinstance(velocity, (int, float)) and math.isfinite(velocity) and velocity > 0):
        raise DFAValueError(f"velocity = {velocity!r} is invalid: it must be > 0 m/s; give the impact speed")
    with_controller = design_answer(loop, velocity, **kwargs)
    plain = design_answer(Loop(device, wall.without_controller()), velocity, **kwargs)
    return gain_of(with_controller, plain)
