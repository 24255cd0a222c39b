"""A function with some keywords fixed whatever its caller passes (tests shrink work the CLI sizes itself).

``functools.partial(design_analysis, map_grid=5)`` is not that: a caller's own ``map_grid=81`` overrides a partial's
keyword, and ``design_report`` passes its defaults (map_grid=81, samples=30000) explicitly, so `dfa report` ran the
full map under a "small" patch.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any


def fixed_keywords(func: Callable[..., Any], **fixed: Any) -> Callable[..., Any]:
    """``func`` called with ``fixed`` replacing the same keywords of every call (the other arguments passed on)."""

    @functools.wraps(func)
    def call(*args: Any, **kwargs: Any) -> Any:
        return func(*args, **{**kwargs, **fixed})

    return call


#: A small stability map for `dfa report` in tests whose checks do not read the map (its numbers are its own).
SMALL_MAP = {"map_grid": 3, "samples": 2000, "n_jobs": 1}
#: Small searches of the design answer (K_max four ways) and of the stiffness-speed chart (the report's first
#: section and figure), for tests that check other sections: 2 speeds, 6 grid points (the searches' defaults
#: are 6 and 16, the chart's 14 and 24).
SMALL_SEARCH = {"speeds": 2, "grid": 6}


def small_report_map(monkeypatch: Any) -> None:
    """`dfa report` (``design_report``) with :data:`SMALL_MAP`'s map instead of its 81 × 81 on every core."""
    import dfa.studies.report
    from dfa.studies.design import design_analysis

    monkeypatch.setattr(dfa.studies.report, "design_analysis", fixed_keywords(design_analysis, **SMALL_MAP))


def small_design_searches(monkeypatch: Any) -> None:
    """The design analysis' answer and stiffness-speed chart searched with :data:`SMALL_SEARCH` (for tests of
    other sections: the answer's numbers are then the small search's own)."""
    import dfa.studies.design as design

    monkeypatch.setattr(design, "design_answer", fixed_keywords(design.design_answer, **SMALL_SEARCH))
    monkeypatch.setattr(design, "stiffness_speed_chart", fixed_keywords(design.stiffness_speed_chart, **SMALL_SEARCH))
