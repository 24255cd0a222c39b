"""The describing function's growth band: from the smallest to the largest unstable cycle (beyond the paper)."""

from __future__ import annotations

from typing import Any

from ...checks import check_type
from ...errors import DFAValueError
from ...model.device import Device, Params
from ...model.loop import Loop, as_loop
from ...model.wall import WallParams
from ...results.cycles import GrowthThreshold as GrowthThreshold
from ...results.cycles import LimitCycle
from ...results.status import GrowthStatus, SearchStatus
from ..loop_models import check_params
from .controlled import WALL_FIX
from .solve import limit_cycles


def growth_threshold(loop: Loop | Params, device: Device | None = None, **kwargs: Any) -> GrowthThreshold:
    """Growth band of the describing function: smallest and largest unstable cycles (beyond the paper).

    Parameters
    ----------
    loop : Loop
        The loop (its groups μ > 0, β >= 0, σ >= 0 and its wall's), ``Loop(device, wall)``, whose device
        expresses the amplitudes and speeds in physical units, or ``Loop.dimensionless(mu, beta, sigma,
        wall_params)``. The former call ``growth_threshold(params, device, wall=wall_params)`` still works.
    device : Device, optional
        Only with the former call (the groups first): the device expressing the amplitudes and speeds in
        physical units (a loop's own device does that).
    **kwargs
        Passed to :func:`limit_cycles` (model, …; ``wall`` with the former call).

    Returns
    -------
    GrowthThreshold
        The band's smallest and largest unstable cycles, what it means and the underlying search.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``device`` is not a :class:`Device`, is given beside a loop, or :func:`limit_cycles` refuses its
        inputs.

    See Also
    --------
    limit_cycles : Every cycle, stable and unstable.
    simulate : What the exact loop does from a given speed.
    """
    if isinstance(loop, Loop):
        if device is not None:
            raise DFAValueError(
                f"device = {device!r:.60} is invalid with a loop: the loop holds its device; build the loop with "
                "it, Loop(device, wall)"
            )
        device = loop.device
    else:  # the former form: the groups, the device for the units, wall= the wall's groups
        if device is not None:
            check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
        wall = kwargs.pop("wall", None)
        loop = as_loop(check_params(loop), None if wall is None else check_type("wall", wall, WallParams, WALL_FIX))
    res = limit_cycles(loop, **kwargs)
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
