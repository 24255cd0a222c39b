"""Geometric grids that are the same doubles on every machine.

``numpy.geomspace`` forms its points with the vectorised ``log``/``exp`` of the machine's SIMD unit, whose last
bit differs between processors (AVX2 and AVX-512 builds of numpy disagree by an ulp). A grid point that reaches a
report (a stiffness of the speed chart's criterion curve) then printed ``17755.2911828`` on one machine and
``…827`` on another: the double lay within an ulp of the 12-digit rounding boundary. :func:`geometric_grid` forms
every point in decimal arithmetic (:mod:`decimal`, 40 digits, whose ``ln``, ``exp`` and products are specified
to the last digit, the same in every implementation) and rounds it once to the nearest double, so the grid, and every number computed from it, is
the same on every machine.

Examples
--------
>>> geometric_grid(1.0, 100.0, 3).tolist()
[1.0, 10.0, 100.0]
>>> geometric_grid(1.0, 8.0, 3, endpoint=False).tolist()
[1.0, 2.0, 4.0]
"""

from __future__ import annotations

import decimal
import functools

import numpy as np

from .errors import DFAValueError

__all__ = ["geometric_grid"]

_CONTEXT = decimal.Context(prec=40, rounding=decimal.ROUND_HALF_EVEN)


def geometric_grid(start: float, stop: float, num: int, *, endpoint: bool = True) -> np.ndarray:
    """Give ``num`` points from ``start`` to ``stop`` in geometric progression, the same on every machine.

    The drop-in for ``numpy.geomspace(start, stop, num, endpoint=endpoint)`` with positive ends: point i is
    start · (stop/start)^(i/m) (m = num − 1 with the endpoint, num without), formed in 40-digit decimal
    arithmetic and rounded once to a double; the ends are ``start`` and ``stop`` exactly.

    Parameters
    ----------
    start, stop : float
        The ends, finite and > 0 (any units: the grid has the units of its ends).
    num : int
        Number of points, >= 1.
    endpoint : bool, optional
        Whether ``stop`` is the last point (default True).

    Returns
    -------
    numpy.ndarray
        The points, float64, ascending when ``stop > start``.

    Raises
    ------
    DFAValueError
        If an end is not a finite number > 0 or ``num`` < 1.
    """
    lo, hi = float(start), float(stop)
    if not (0.0 < lo < float("inf") and 0.0 < hi < float("inf")):
        raise DFAValueError(
            f"start = {start!r}, stop = {stop!r} is invalid: a geometric grid needs finite ends > 0; give positive ends"
        )
    if int(num) != num or num < 1:
        raise DFAValueError(f"num = {num!r} is invalid: it must be a whole number >= 1; give the number of points")
    return _grid(lo, hi, int(num), bool(endpoint)).copy()  # a copy: the caller may write into its grid


@functools.lru_cache(maxsize=512)
def _grid(lo: float, hi: float, n: int, endpoint: bool) -> np.ndarray:
    """:func:`geometric_grid`'s points, formed once per (start, stop, num, endpoint): the searches ask for the
    same grids again and again, and a grid of 2000 points takes milliseconds in decimal arithmetic."""
    steps = n - 1 if endpoint else n
    if n == 1 or steps == 0:
        return np.array([lo])
    c = _CONTEXT
    point = decimal.Decimal(lo)
    step = c.exp(c.divide(c.ln(c.divide(decimal.Decimal(hi), point)), steps))  # (stop/start)^(1/m), 40 digits
    out = np.empty(n)
    for i in range(n):  # 40-digit products: after 10^5 steps still ~1e-34 from the exact point, far below an ulp
        out[i] = float(point)
        point = c.multiply(point, step)
    out[0] = lo
    if endpoint:
        out[-1] = hi
    return out
