"""How much stiffness a passivity controller buys (issue 30): K_max by simulation with and without it.

The criterion, the exact linear bound and the describing function do not cover a passivity controller
(:class:`dfa.model.elements.PassivityController`), so its gain is the simulated limits' (:func:`design_answer`'s
``k_sim``, no divergence, and ``k_sim_rest``, every impact rests, searched in the same way for both walls):
:func:`passivity_gain` runs both answers, :func:`gain_of` compares two answers already computed (what
``dfa stiffness --passivity-controller`` does).
"""

from __future__ import annotations

import math
from typing import Any

from ...checks import check_type
from ...errors import DFAValueError
from ...model.elements import PassivityController
from ...model.loop import LOOP_FIX, Loop, loop_first
from ...results.limits import PassivityGain as PassivityGain
from ...results.limits import _ratio as _ratio
from ...results.status import GainStatus, KMaxStatus
from .kmax import KMaxResult, design_answer

__all__ = ["PassivityGain", "passivity_gain", "gain_of"]


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
    if wall is None or wall.element(PassivityController) is None:
        raise DFAValueError(
            f"wall = {wall!r} is invalid: it must be a dfa.Wall with a passivity controller; add "
            "dfa.PassivityController() to its elements"
        )
    if not (isinstance(velocity, (int, float)) and math.isfinite(velocity) and velocity > 0):
        raise DFAValueError(f"velocity = {velocity!r} is invalid: it must be > 0 m/s; give the impact speed")
    with_controller = design_answer(loop, velocity, **kwargs)
    plain = design_answer(Loop(device, wall.without_controller()), velocity, **kwargs)
    return gain_of(with_controller, plain)
