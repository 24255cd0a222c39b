"""Codes of gridded outcomes that results store as integers and figures colour (one definition each).

The simulated outcome of a run is :class:`dfa.results.status.SimulationOutcome` (its order is the code of a
stability map); a grid point of the Z-width (:func:`dfa.analysis.limits.zwidth.z_width`) summarises every run
at that point in one of :data:`POINT_OUTCOMES`; :data:`ZWIDTH_METHODS` are the Z-width's boundaries K_max(B),
in the order of its table and plot.

Examples
--------
>>> POINT_OUTCOMES[DIVERGES], ZWIDTH_METHODS[0]
('diverges', 'linear')
"""

from __future__ import annotations

__all__ = [
    "POINT_OUTCOMES", "REST", "BOUNDED", "DIVERGES", "UNDECIDED_POINT", "LEFT_POINT", "ZWIDTH_METHODS",
    "REQUIRE_PARAMETERS",
]  # fmt: skip

#: Outcome of a Z-width grid point (index = code): every run rests; none diverges but some does not rest;
#: some run diverges; none diverges and some run was too short to tell; (a one-sided wall) every run rests or
#: leaves the wall for good and some leave.
POINT_OUTCOMES = ("rest", "bounded", "diverges", "undecided", "left")
REST, BOUNDED, DIVERGES, UNDECIDED_POINT, LEFT_POINT = range(5)
#: The per-method boundaries K_max(B) of a Z-width, in the order of the table and the plot.
ZWIDTH_METHODS = ("linear", "passivity", "criterion", "df", "sim", "rest")
#: The parameters of the inverse question (:mod:`dfa.analysis.limits.require`, ``dfa require --parameter``).
REQUIRE_PARAMETERS = ("period", "resolution", "coulomb", "damping", "virtual_damping", "delay")
