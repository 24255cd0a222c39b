"""The describing function's growth band: from the smallest to the largest unstable cycle (beyond the paper)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, ClassVar

from ...checks import check_type
from ...errors import DFAValueError
from ...model.device import Device, Params
from ...model.loop import Loop, as_loop
from ...model.wall import WallParams
from ...results.base import Result
from ...results.status import GrowthStatus, SearchStatus
from ..loop_models import check_params
from .caveats import NO_CAVEAT, SubtickCaveat
from .controlled import WALL_FIX
from .results import LimitCycle, LimitCycleResult
from .solve import limit_cycles


# --------------------------------------------------------- design threshold
@dataclass(frozen=True)
class GrowthThreshold(Result):
    """The describing function's growth band: from the smallest to the largest unstable cycle.

    Where the large family is a single unstable cycle the band is one amplitude
    M_u and the first-harmonic analysis predicts growth above it. Where it is a
    cluster of alternating stable and unstable cycles (β near the linear bound,
    D(M) oscillating about 1, eq. 41) there is no single threshold: below the
    band every predicted cycle is stable, inside it growth depends on the initial
    condition, above the largest unstable cycle growth is predicted (unless a
    larger stable cycle catches it). All of this is a first-harmonic
    approximation (eq. 36), not a proof.

    Attributes
    ----------
    amplitude, frequency, xi_dot : float or None
        Smallest unstable cycle: M_u (ticks), ω (rad per sample) and the speed
        amplitude M_u·ω (ticks per sample), to compare with eq. 12.
    result : LimitCycleResult
        The full solution it came from.
    position, velocity : float or None
        M_u and M_u·ω in physical units (m or rad, m/s or rad/s) when a device was given.
    status : GrowthStatus
        ``OK`` (unstable cycles found), ``NO_UNSTABLE_CYCLE``, ``NO_UNSTABLE_CYCLE_SEARCHED``
        (none up to an incomplete search's limit) or ``LINEAR_UNSTABLE``.
    amplitude_high, frequency_high, xi_dot_high, position_high, velocity_high : float or None
        The same for the largest unstable cycle (the top of the band).
    unstable_count : int
        Number of unstable cycles in the band.
    grows_above : bool or None
        True when no stable cycle lies above the largest unstable one, so that
        the first-harmonic analysis predicts growth above the band.
    """

    amplitude: float | None
    frequency: float | None
    xi_dot: float | None
    result: LimitCycleResult = field(metadata={"json": None})  # its numbers: band, complete, linear_stable
    position: float | None = None
    velocity: float | None = None
    status: GrowthStatus = GrowthStatus.OK
    amplitude_high: float | None = None
    frequency_high: float | None = None
    xi_dot_high: float | None = None
    position_high: float | None = None
    velocity_high: float | None = None
    unstable_count: int = 0
    grows_above: bool | None = None

    json_properties: ClassVar[tuple[str, ...]] = ("band", "complete", "linear_stable", "linear_model", "caveat")

    def __post_init__(self) -> None:
        st = GrowthStatus.coerce(self.status)
        object.__setattr__(self, "status", st)
        if (st is GrowthStatus.OK) != (self.amplitude is not None) or (self.amplitude is None) != (
            self.unstable_count == 0
        ):
            raise DFAValueError(
                f"status = {st.value!r} is invalid with amplitude = {self.amplitude!r} and unstable_count = "
                f"{self.unstable_count!r}: status OK exactly when an unstable cycle was found; build it with growth_threshold"
            )

    @property
    def is_band(self) -> bool:
        """True for a cluster: more than one unstable cycle."""
        return self.unstable_count > 1

    @property
    def caveat(self) -> SubtickCaveat | None:
        """The sub-tick caveat of the search (:attr:`LimitCycleResult.caveat`), or None.

        Set when the band's bottom lies just above the first quantization level, where "no growth below it"
        is not borne out by simulation.
        """
        return self.result.caveat

    @property
    def band(self) -> dict[str, dict[str, float | None]]:
        """The band's bottom (``low``: the smallest unstable cycle) and top (``high``: the largest), each as
        amplitude, frequency, xi_dot, position and velocity (None where undefined)."""
        names = ("amplitude", "frequency", "xi_dot", "position", "velocity")
        return {
            "low": {n: getattr(self, n) for n in names},
            "high": {n: getattr(self, f"{n}_high") for n in names},
        }

    @property
    def complete(self) -> bool:
        """Whether the cycle search was complete (:attr:`LimitCycleResult.complete`)."""
        return self.result.complete

    @property
    def linear_stable(self) -> bool | None:
        """Whether the linear loop is stable (:attr:`LimitCycleResult.linear_stable`)."""
        return self.result.linear_stable

    @property
    def linear_model(self) -> str:
        """The model of :attr:`linear_stable`: always the exact ZOH loop (``"zoh"``)."""
        return "zoh"

    def null_reasons(self) -> dict[str, str]:
        """Why the caveat (:data:`~dfa.analysis.cycles.caveats.NO_CAVEAT`) and the band's top may be null in JSON.

        Returns
        -------
        dict of str to str
            The reason by key.
        """
        none = "no unstable cycle: no growth band"
        phys = "no unstable cycle, or no device given (physical units need one)"
        return {
            "caveat": NO_CAVEAT,
            **{n: none for n in ("amplitude_high", "frequency_high", "xi_dot_high")},
            **{n: phys for n in ("position_high", "velocity_high")},
        }


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
