"""The harmonic balance with a virtual wall: its inputs, and the linear loop's stability.

With a wall (:class:`~dfa.model.wall.WallParams`) the quantizer's describing function D(M) multiplies the wall's
command H(z) = z^{−d}·C(z) (the elements' polynomials, :meth:`~dfa.model.wall.WallParams.command`), and an
amplifier lag sits between the hold and the device (:func:`dfa.analysis.loop.loop_response`). A wall the spring's
fast path covers (the paper's spring with any delay, ``Coverage.CLOSED_FORM``) is the paper's
loop with its delay: the solver then runs the spring-only code, bit for bit.
"""

from __future__ import annotations

from ...checks import check_type
from ...model.elements import Coverage
from ...model.wall import WallParams

__all__ = ["resolve_wall", "linear_stable_of"]


#: How the analyses of the dimensionless loop tell to give the wall's groups (their message refusing another wall).
WALL_FIX = "give dimensionless groups, e.g. dfa.Wall.of(K, B, ...).params(period), or None"


def resolve_wall(wall: object) -> tuple[WallParams, WallParams | None, int]:
    """(the wall's groups; the same, or None for the spring's fast path; its delay) from the user's input.

    Raises
    ------
    DFATypeError
        If ``wall`` is neither None nor a :class:`~dfa.model.wall.WallParams`.
    """
    w = WallParams() if wall is None else check_type("wall", wall, WallParams, WALL_FIX)
    return w, (None if w.covers(Coverage.CLOSED_FORM) else w), w.delay


def linear_stable_of(mu: float, beta: float, wall: WallParams) -> bool:
    """Whether the linear loop with the wall is asymptotically stable (every root inside abs(z) = 1).

    :func:`dfa.analysis.linear.linear_stable` with the wall (one implementation; no encoder, no Coulomb
    friction): the closed-loop spectral radius, and at tiny rates the small-rate bound (the float radius is
    decided by rounding there).
    """
    from ..linear import linear_stable

    return bool(linear_stable(mu, beta, wall=wall))
