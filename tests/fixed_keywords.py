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
