"""Contour maps of limit-cycle amplitude and frequency over the (β, σ) plane (paper Fig. 7).

For one μ and the paper's half-sample-delay loop (d = 0), two families (the maps take μ and the β, σ ranges, not
a :class:`~dfa.model.loop.Loop`, for the reason :mod:`dfa.analysis.maps` states: a loop is one point of the plane
they sweep):

* **small stable** cycles (M < 1). With D = 2/(πM), exact for M < 1, the
  cycle is the closed form of eq. 42-43; the exact solver finds the same
  (D has no approximation there).
* **large unstable** cycles: the paper's closed form eq. 44-45 (D ≈ 1), and
  the exact one: the smallest unstable cycle with M >= 1 under the exact D
  (the growth threshold), which lies near the closed form but sees D's
  oscillation around 1.

The exact large family is vectorised. For each β the phase condition
c(ω) = μω² tan(ω/2) − βω (= 4σ/(πM)) is tabulated once on a fine ω grid
where it increases, so ω(M) for every σ follows by interpolation; the
residual F(M) = D(M) − μω²/cos(ω/2) is scanned on a shared amplitude grid
(n + t² on each integer interval) for its first rising zero crossing (F
rising through zero marks an unstable cycle, see :mod:`dfa.analysis.cycles`),
then refined by secant steps with the exact D. Amplitudes beyond
``max_amplitude`` are reported as NaN (outside the map's range).

Examples
--------
>>> maps = contour_maps(5.0, grid=5)
>>> maps.large_amplitude.shape
(5, 5)
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np

from .._io import check_memory
from .._parallel import new_bar
from ..checks import check_bool, check_int, check_mu, check_positive, check_range
from ..errors import DFAValueError
from ..grids import geometric_grid
from ..results.contours import _ARRAYS
from ..results.contours import ContourMaps as ContourMaps
from ..results.contours import FlaggedPoints as FlaggedPoints
from ..results.status import ContourStatus
from .cycles import ClosedFormStatus, large_cycle_closed_forms, small_cycle_closed_forms
from .describing import quantizer_df

__all__ = ["ContourMaps", "FlaggedPoints", "contour_maps", "load_contours", "contour_memory_bytes", "contour_seconds"]


def load_contours(path: str | os.PathLike) -> ContourMaps:
    """Read maps written by :meth:`ContourMaps.save`."""
    with np.load(path) as z:
        return ContourMaps(mu=float(z["mu"]), max_amplitude=float(z["max_amplitude"]), **{k: z[k] for k in _ARRAYS})


def _large_exact(
    mu: float, beta: np.ndarray, sigma: np.ndarray, amax: float, progress: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Smallest unstable cycle with M >= 1 for every (σ, β), exact D (see module docstring)."""
    n_all = np.arange(1, int(math.ceil(amax)) + 1)
    t = np.linspace(0.0, 1.0, 17)
    msamp = np.unique((n_all[:, None] + (t * t)[None, :]).ravel())
    msamp = msamp[msamp <= amax]
    dsamp = quantizer_df(msamp)
    wgrid = np.concatenate([geometric_grid(1e-7, 1e-2, 2000, endpoint=False), np.linspace(1e-2, math.pi - 1e-6, 20000)])
    large_m = np.full((sigma.size, beta.size), np.nan)
    large_w = np.full((sigma.size, beta.size), np.nan)
    rows_all = np.nonzero(sigma > 0)[0]
    if rows_all.size == 0:
        return large_m, large_w
    bar = new_bar(iterable=beta, unit="β column", desc=f"contours μ={mu:g}", disable=not progress, leave=False)
    for j, b in enumerate(bar):
        c = mu * wgrid**2 * np.tan(wgrid / 2) - b * wgrid  # = 4σ/(πM) on the phase curve, increasing where > 0
        ok = c > 0
        if not ok.any():
            continue
        cw, ww = np.maximum.accumulate(c[ok]), wgrid[ok]  # guard monotonicity against rounding
        target = (4.0 * sigma[rows_all, None] / math.pi) / msamp[None, :]  # (σ, M)
        wm = np.interp(target, cw, ww, left=np.nan, right=np.nan)
        f = dsamp[None, :] - mu * wm**2 / np.cos(wm / 2)
        rising = (f[:, :-1] < 0) & (f[:, 1:] >= 0)
        has = rising.any(axis=1)
        if not has.any():
            continue
        kk = np.argmax(rising, axis=1)[has]
        rows = rows_all[has]
        ma, mb = msamp[kk], msamp[kk + 1]
        fa, fb = f[has, kk], f[has, kk + 1]
        sg = sigma[rows]
        mc = mb
        for _ in range(4):  # secant steps with the exact D, kept inside the bracket
            with np.errstate(invalid="ignore", divide="ignore"):
                mc = np.where(fb != fa, mb - fb * (mb - ma) / (fb - fa), mb)
            mc = np.clip(mc, ma, mb)
            wc = np.interp(4 * sg / (math.pi * mc), cw, ww)
            fc = quantizer_df(mc) - mu * wc * wc / np.cos(wc / 2)
            neg = fc < 0
            ma, fa = np.where(neg, mc, ma), np.where(neg, fc, fa)
            mb, fb = np.where(neg, mb, mc), np.where(neg, fb, fc)
        large_m[rows, j] = mc
        large_w[rows, j] = np.interp(4 * sg / (math.pi * mc), cw, ww)
    return large_m, large_w


#: Planned peak memory per grid point (bytes): about 25 float arrays of the grid's shape.
CONTOUR_BYTES_PER_POINT = 200
#: ... per grid row and amplitude sample of the exact large family (five float arrays).
CONTOUR_BYTES_PER_ROW_SAMPLE = 40
#: Amplitude samples per tick of ``max_amplitude`` (17 per cell, see ``_large_exact``).
CONTOUR_SAMPLES_PER_TICK = 17


def contour_memory_bytes(grid: int, max_amplitude: float) -> float:
    """Estimated peak memory of :func:`contour_maps` in bytes."""
    n_m = CONTOUR_SAMPLES_PER_TICK * (float(max_amplitude) + 1.0)
    return float(grid) ** 2 * CONTOUR_BYTES_PER_POINT + float(grid) * n_m * CONTOUR_BYTES_PER_ROW_SAMPLE + 32.0 * n_m


#: Planned time of :func:`contour_maps`, measured on one core with the kernels cached (an upper estimate):
#: a fixed part (imports, the limit-cycle package), per grid point, per grid row and amplitude sample.
CONTOUR_SECONDS_FIXED = 5.0
CONTOUR_SECONDS_PER_POINT = 1.0e-4
CONTOUR_SECONDS_PER_ROW_SAMPLE = 5.0e-6


def contour_seconds(grid: int, max_amplitude: float) -> float:
    """Planned time of :func:`contour_maps` in seconds (an upper estimate, before any work).

    Examples
    --------
    >>> contour_seconds(2000, 200.0) > 60.0 > contour_seconds(200, 200.0)
    True
    """
    n_m = CONTOUR_SAMPLES_PER_TICK * (float(max_amplitude) + 1.0)
    return (
        CONTOUR_SECONDS_FIXED
        + float(grid) ** 2 * CONTOUR_SECONDS_PER_POINT
        + float(grid) * n_m * CONTOUR_SECONDS_PER_ROW_SAMPLE
    )


def check_contour_memory(grid: int, max_amplitude: float, names: tuple[str, str] = ("grid", "max_amplitude")) -> None:
    """Refuse a map planned to need too much memory (see :func:`dfa._io.check_memory`), naming the input that drives it."""
    need = contour_memory_bytes(grid, max_amplitude)
    by_amplitude = float(grid) * CONTOUR_SAMPLES_PER_TICK * (float(max_amplitude) + 1.0) * CONTOUR_BYTES_PER_ROW_SAMPLE
    if by_amplitude > float(grid) ** 2 * CONTOUR_BYTES_PER_POINT:
        check_memory(
            names[1],
            f"{max_amplitude:g}",
            need,
            f"lower {names[1]} (the largest amplitude searched, ticks) or {names[0]}",
        )
    else:
        check_memory(names[0], grid, need, f"lower {names[0]} (points per axis) or {names[1]}")


def contour_maps(
    mu: float,
    *,
    beta_range: tuple[float, float] = (0.0, 1.0),
    sigma_range: tuple[float, float] = (0.0, 2.0),
    grid: int = 200,
    max_amplitude: float = 200.0,
    progress: bool = False,
) -> ContourMaps:
    """Amplitude and frequency maps of both cycle families over a (β, σ) grid (paper Fig. 7).

    Parameters
    ----------
    mu : float
        Dimensionless mass (paper Fig. 7: μ = 5).
    beta_range, sigma_range : (float, float)
        Grid extents.
    grid : int
        Points per axis (>= 2).
    max_amplitude : float
        Largest amplitude (ticks) searched for the exact large family (>= 1).
    progress : bool
        Show a tqdm progress bar (one step per β column) with an estimate of the time left, on stderr.

    Returns
    -------
    ContourMaps
        Amplitude (ticks) and frequency (rad per sample) of the small and large families, exact and
        closed-form, NaN where a family does not exist; ``.plot()`` draws them.

    Raises
    ------
    DFAValueError, DFATypeError
        If an input is out of range or not a number, or the maps would not fit in memory.

    See Also
    --------
    limit_cycles : The cycles at one point.
    small_cycle_closed_form, large_cycle_closed_form : The closed forms at one point.
    stability_map : The simulated outcome over the same plane.
    """
    m = check_mu(mu)
    b0, b1 = check_range("beta_range", beta_range)
    s0, s1 = check_range("sigma_range", sigma_range)
    g = check_int("grid", grid, minimum=2, fix="use at least 2 points per axis")
    amax = check_positive("max_amplitude", max_amplitude)
    if amax < 1.0:
        raise DFAValueError(f"max_amplitude = {amax} is invalid: it must be >= 1 tick (the large family has M >= 1)")
    check_contour_memory(g, amax)
    beta = np.linspace(b0, b1, g)
    sigma = np.linspace(s0, s1, g)
    bb, ss = np.meshgrid(beta, sigma)
    # closed forms (paper eq. 42-45), one implementation (dfa.analysis.cycles.closed_forms)
    small = small_cycle_closed_forms(m, bb, ss)
    sm_cf, sw_cf = np.array(small.amplitude), np.array(small.frequency)
    large = large_cycle_closed_forms(m, bb, ss)
    lm_cf = np.where(large.amplitude >= 1.0, large.amplitude, np.nan)  # the large family has M >= 1
    lw_cf = np.where(np.isfinite(lm_cf), large.frequency, np.nan)
    small_m = np.where(sm_cf < 1.0, sm_cf, np.nan)
    small_w = np.where(sm_cf < 1.0, sw_cf, np.nan)
    large_m, large_w = _large_exact(m, beta, sigma, amax, check_bool("progress", progress, "pass True or False"))
    flagged = _flagged_points(small, large)
    status = ContourStatus.FLAGGED if flagged else ContourStatus.OK
    return ContourMaps(m, beta, sigma, small_m, small_w, large_m, large_w, lm_cf, lw_cf, sm_cf, amax, status, flagged)


def _flagged_points(small: Any, large: Any) -> tuple[FlaggedPoints, ...]:
    """Which grid points the closed forms flag (β = σ = 0, solver failures) and why; empty when none."""
    out = []
    for family, cf in (("small", small), ("large", large)):
        for code in (ClosedFormStatus.DEGENERATE, ClosedFormStatus.NOT_SOLVED):
            count = int(np.count_nonzero(cf.status == code))
            if count:
                out.append(FlaggedPoints(family, code.name.lower(), count))
    return tuple(out)
