"""Result types of the limit-cycle search: one cycle, all cycles of an operating point, how the search ended."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

from ...checks import check_bool, check_nonnegative, check_positive, check_real, format_value
from ...errors import DFATypeError, DFAValueError
from ...model.device import Device, Params
from ...model.wall import WallParams
from ...results.base import Result
from ...results.status import SearchStatus
from ...results.summaries import OperatingPoint
from .caveats import NO_CAVEAT, NO_REST_CAVEAT, NoRestCaveat, SubtickCaveat, no_rest_caveat, subtick_caveat


# ------------------------------------------------------------------ results
@dataclass(frozen=True)
class SearchEvidence(Result):
    """The numbers behind a limit-cycle search's status (:class:`~dfa.results.status.SearchStatus`), as data.

    The rendering layer words them (:func:`dfa.render.text.search_text`); the JSON carries them under ``search``.

    Attributes
    ----------
    requested : float
        The largest amplitude asked for, ticks (the caller's ``max_amplitude``, or the automatic range).
    reached : float or None
        Where an incomplete search stopped, ticks: no root below it was missed (None: complete, or a numerical
        failure with no range lost).
    failures : int
        Root brackets that could not be refined (status ``NUMERICAL``).
    pieces_searched, pieces_total : int or None
        Pieces of the phase curve searched and in all, when the time budget ended the search.
    time_budget : float or None
        The time budget in seconds, when it ended the search.
    frequency_range : bool
        μ lies outside :data:`~dfa.analysis.cycles.SEARCHED_MU`, where a cycle's frequency may fall outside the
        scanned ω grid: nothing was searched (status ``FREQUENCY_RANGE``).

    Examples
    --------
    >>> SearchEvidence(requested=10.0, reached=4.0).reached
    4.0
    """

    requested: float
    reached: float | None = None
    failures: int = 0
    pieces_searched: int | None = None
    pieces_total: int | None = None
    time_budget: float | None = None
    frequency_range: bool = False

    def __post_init__(self) -> None:
        check_positive("requested", self.requested, "give the largest amplitude searched, in ticks")
        if self.reached is not None:
            check_positive("reached", self.reached, "give the amplitude where the search stopped, in ticks")
        if isinstance(self.failures, bool) or not isinstance(self.failures, int) or self.failures < 0:
            raise DFAValueError(f"failures = {self.failures!r} is invalid: it must be a whole number >= 0")

    def null_reasons(self) -> dict[str, str]:
        """Why ``reached`` and the time-budget numbers may be null (JSON).

        Returns
        -------
        dict of str to str
            Reasons by field name.
        """
        budget = "the time budget did not end the search"
        return {
            "reached": "the search did not stop short of the range asked for",
            "pieces_searched": budget,
            "pieces_total": budget,
            "time_budget": budget,
        }


@dataclass(frozen=True)
class LimitCycle(Result):
    """One harmonic-balance solution ξ = M sin ωτ.

    Attributes
    ----------
    amplitude : float
        M in encoder ticks.
    frequency : float
        ω in rad per sample.
    stable : bool
        Loeb criterion (module docstring).
    family : str
        ``"small"`` (M < 1) or ``"large"`` (M >= 1).
    loeb : float
        ∂U/∂M·∂V/∂ω − ∂U/∂ω·∂V/∂M at the root.
    residual : float
        abs(1 + D(M)·L(jω; M)) at the reported root.
    few_samples : bool
        True when the period is under 8 samples: first-harmonic analysis is
        least trustworthy there (validation issue).
    """

    amplitude: float
    frequency: float
    stable: bool
    family: str
    loeb: float
    residual: float
    few_samples: bool = False

    json_properties: ClassVar[tuple[str, ...]] = ("period",)

    @property
    def period(self) -> float:
        """Period in samples, 2π/ω."""
        return 2.0 * math.pi / self.frequency

    def __post_init__(self) -> None:
        fix = "build cycles with limit_cycles"
        if not isinstance(self.family, str) or self.family not in ("small", "large"):
            raise DFAValueError(
                f"family = {format_value(self.family)} is invalid: it must be 'small' or 'large'; {fix}"
            )
        for name in ("amplitude", "frequency"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name), fix))
        object.__setattr__(self, "loeb", check_real("loeb", self.loeb, fix))
        object.__setattr__(self, "residual", check_nonnegative("residual", self.residual, fix))
        for name in ("stable", "few_samples"):
            object.__setattr__(self, name, check_bool(name, getattr(self, name), fix))

    def physical(self, device: Device, stiffness: float) -> dict[str, float | None]:
        """Express this cycle in physical units for a device at stiffness K (:mod:`dfa.model.units`).

        Parameters
        ----------
        device : Device
            The physical device.
        stiffness : float
            Virtual spring stiffness K in N/m (rotary: N·m/rad), > 0.

        Returns
        -------
        dict
            ``amplitude_m`` (rotary: rad), ``force_amplitude_n`` (N·m), ``frequency_hz``, ``period_s``
            and ``velocity_m_s`` (rad/s, the speed amplitude M·ω).
        """
        from ...model.units import physical_quantities

        return physical_quantities(
            device,
            stiffness,
            amplitude=self.amplitude,
            frequency=self.frequency,
            period=self.period,
            xi_dot=self.amplitude * self.frequency,
        )


@dataclass(frozen=True)
class LimitCycleResult(OperatingPoint, Result):
    """All limit cycles of one operating point (an empty tuple is a valid answer).

    Attributes
    ----------
    params : Params
    model, pade_order : loop model (see :func:`dfa.analysis.loop.loop_response`)
    wall : WallParams
        The wall's groups in the loop (none for the paper's spring; :attr:`delay` its delay).
    describing : str
        ``"exact"`` (eq. 41), or the paper's approximations ``"small"`` (2/(πM)) and ``"unity"`` (1).
    max_amplitude : float
        Largest amplitude searched (ticks). When ``complete``, no root of eq. 36
        lies beyond the last one found (pieces of the phase curve ended, or the
        envelope bound of eq. 41 closed them); when not, the search stopped here.
    cycles : tuple of LimitCycle
        Sorted by amplitude.
    complete : bool
        True only when the search provably found every root (status ``COMPLETE``).
    search : SearchEvidence
        The numbers behind the status: how far the search got, failures, the time budget.
    status : SearchStatus
        How the search ended (``COMPLETE``, ``MAX_AMPLITUDE``, ``BUDGET``, ``NUMERICAL``);
        ``status_code`` is a deprecated alias.
    search_bound : float or None
        When complete: the amplitude (ticks) beyond which no root of eq. 36 exists
        (the phase curve's pieces end there, or the eq. 41 envelope excludes
        roots); 0 when the loop's phase condition has no solution at all.
    linear_stable : bool or None
        Whether the linear loop without encoder and Coulomb friction (always the
        exact ZOH loop with the same delay, :func:`dfa.analysis.linear.linear_stable`) is
        asymptotically stable; when it is not, amplitudes beyond the largest
        unstable cycle are predicted to grow without bound. With a controller: the
        exact linear loop with that controller (and amplifier lag).
    """

    params: Params = field(metadata={"json": None})  # written as mu, beta, sigma
    model: str
    wall: WallParams
    pade_order: int
    describing: str
    max_amplitude: float
    cycles: tuple = field(default_factory=tuple)
    complete: bool = True
    search: SearchEvidence | None = None
    status: SearchStatus = SearchStatus.COMPLETE
    linear_stable: bool | None = None
    search_bound: float | None = None

    json_properties: ClassVar[tuple[str, ...]] = (
        "mu", "beta", "sigma", "delay", "linear_model", "caveat", "rest_caveat",
    )  # fmt: skip

    def __post_init__(self) -> None:
        if not isinstance(self.wall, WallParams):
            raise DFATypeError("wall must be a WallParams; build results with limit_cycles")
        st = SearchStatus.coerce(self.status)
        object.__setattr__(self, "status", st)
        if self.search is None:
            object.__setattr__(self, "search", SearchEvidence(requested=self.max_amplitude))
        elif not isinstance(self.search, SearchEvidence):
            raise DFATypeError("search must be a SearchEvidence; build results with limit_cycles")
        object.__setattr__(self, "cycles", tuple(self.cycles))
        if self.complete != (st is SearchStatus.COMPLETE):
            raise DFAValueError(
                f"complete = {self.complete!r} is invalid with status = {st.value!r}: a search is complete exactly "
                "when its status is COMPLETE; build results with limit_cycles"
            )
        if not all(isinstance(c, LimitCycle) for c in self.cycles):
            raise DFATypeError("cycles must hold LimitCycle objects; build results with limit_cycles")

    @property
    def delay(self) -> int:
        """The wall's computational delay d in samples."""
        return self.wall.delay

    @property
    def linear_model(self) -> str:
        """The model of :attr:`linear_stable`: always the exact ZOH loop (``"zoh"``)."""
        return "zoh"

    @property
    def status_code(self) -> SearchStatus:
        """Deprecated alias of :attr:`status`."""
        return self.status

    @property
    def caveat(self) -> SubtickCaveat | None:
        """The sub-tick caveat (:func:`dfa.analysis.cycles.subtick_caveat`), or None.

        Set (M of the smallest unstable cycle) when that cycle lies just above the first quantization level, where the
        growth verdict resting on it is contradicted by simulation; None otherwise.
        """
        return subtick_caveat(self)

    @property
    def rest_caveat(self) -> NoRestCaveat | None:
        """The no-rest caveat (:func:`dfa.analysis.cycles.caveats.no_rest_caveat`), or None.

        Set when σ < ½: the device never rests, it chatters below one tick where the describing function sees no
        cycle, so "no limit cycle" speaks of amplitudes above one tick only.
        """
        return no_rest_caveat(self)

    @property
    def stable_cycles(self) -> tuple:
        """The stable cycles (Loeb's criterion), by increasing amplitude."""
        return tuple(c for c in self.cycles if c.stable)

    @property
    def unstable_cycles(self) -> tuple:
        """The unstable cycles (Loeb's criterion), by increasing amplitude."""
        return tuple(c for c in self.cycles if not c.stable)

    def physical(self, device: Device, stiffness: float) -> dict[str, object]:
        """Every cycle in physical units (:meth:`LimitCycle.physical`), with the device, K and force step KΔ.

        Parameters
        ----------
        device : Device
            The physical device.
        stiffness : float
            Virtual spring stiffness K in N/m (rotary: N·m/rad), > 0.

        Returns
        -------
        dict
            The device, K, force step KΔ and units, and ``cycles``: one dict per cycle.
        """
        from ...model.units import unit_context

        return {**unit_context(device, stiffness), "cycles": [c.physical(device, stiffness) for c in self.cycles]}

    def null_reasons(self) -> dict[str, str]:
        """Why the caveat may be null in JSON (:data:`~dfa.analysis.cycles.caveats.NO_CAVEAT`).

        Returns
        -------
        dict of str to str
            The reason by key.
        """
        return {"caveat": NO_CAVEAT, "rest_caveat": NO_REST_CAVEAT}


class LimitCycleSearchWarning(RuntimeWarning):
    """A limit-cycle search ended incomplete because of a numerical failure."""
