"""The describing function's growth band: from the smallest to the largest unstable cycle (beyond the paper)."""

from __future__ import annotations

from typing import Any

from ...checks import check_type
from ...model.device import Device, Params
from ...results.cycles import GrowthThreshold as GrowthThreshold
from ...results.cycles import LimitCycle
from ...results.status import GrowthStatus, SearchStatus
from .solve import limit_cycles


def growth_threshold(params: Params, device: Device | None = None, **kwargs: Any) -> GrowthThreshold:
    """Growth band of the describing function: smallest and largest unstable cycles (beyond the paper).

    Parameters
    ----------
    params : Params
        Dimensionless device (μ > 0, β >= 0, σ >= 0).
    device : Device, optional
        To express the amplitudes and speeds in physical units.
    **kwargs
        Passed to :func:`limit_cycles` (model, wall, …).

    Returns
    -------
    GrowthThreshold
        The band's smallest and largest unstable cycles, what it means and the underlying search.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device` or :func:`limit_cycles` refuses its inputs.

    See Also
    --------
    limit_cycles : Every cycle, stable and unstable.
    simulate : What the exact loop does from a given speed.
    """
    if device is not None:
        check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    res = limit_cycles(params, **kwargs)
    unstable = res.unstable_cycles
    if res.status is SearchStatus.FREQUENCY_RANGE:  # nothing searched: no claim on growth either way
        return GrowthThreshold(None, None, None, res, status=GrowthStatus.NOT_SEARCHED, grows_above=None)
    if not unstable:
        if res.linear_stable is False:
            status = GrowthStatus.LINEAR_UNSTABLE
        else:
            status = GrowthStatus.NO_UNSTABLE_CYCLE if res.complete else GrowthStatus.NO_UNSTABLE_CYCLE_SEARCHED
        return GrowthThreshold(
            None, None, None, res, status=status, grows_above=None if res.linear_stable is not False else True
        )
    lo, hi = unstable[0], unstable[-1]

    def phys(c: LimitCycle) -> tuple[float | None, float | None]:
        if device is None:
            return None, None
        return c.amplitude * device.resolution, device.velocity(c.amplitude * c.frequency)

    plo, vlo = phys(lo)
    phi, vhi = phys(hi)
    grows = not any(c.stable and c.amplitude > hi.amplitude for c in res.cycles)
    return GrowthThreshold(
        lo.amplitude,
        lo.frequency,
        lo.amplitude * lo.frequency,
        res,
        plo,
        vlo,
        GrowthStatus.OK,
        hi.amplitude,
        hi.frequency,
        hi.amplitude * hi.frequency,
        phi,
        vhi,
        len(unstable),
        grows,
    )
