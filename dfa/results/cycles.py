"""Result types of the limit-cycle search: one cycle, all cycles of an operating point, how the search ended."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from ..checks import (
    check_bool,
    check_nonnegative,
    check_positive,
    check_real,
    format_value,
)
from ..errors import DFATypeError, DFAValueError
from ..model.device import Device, Params
from ..model.wall import WallParams
from .base import Result
from .caveats import NO_CAVEAT, NO_REST_CAVEAT, NoRestCaveat, SubtickCaveat, no_rest_caveat, subtick_caveat
from .status import GrowthStatus, SearchStatus
from .summaries import OperatingPoint

#: μ = m/(KT²) over which the search claims completeness: there every cycle's frequency lies well inside the
#: scanned grid ``W_GRID`` = [1e-5, π − 1e-9] rad/sample (the large family's ω ≈ 1/√μ reaches 1e-5 at μ = 1e10,
#: a cycle near Nyquist has π − ω ≈ 20μ; ``tests/test_eq36_cycle_search.py`` checks both ends). Outside it
#: :func:`limit_cycles` searches nothing and says so (status ``FREQUENCY_RANGE``).
SEARCHED_MU = (1e-6, 1e8)


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
        from ..model.units import physical_quantities

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
        from ..model.units import unit_context

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


class ClosedFormStatus(enum.IntEnum):
    """Why a closed-form cycle is, or is not, given at a point (:attr:`ClosedFormCycles.status`)."""

    #: the closed form holds: amplitude and frequency are finite
    OK = 0
    #: the family does not exist here (small: σ >= ½; large: sin(ω/2) <= βω)
    NO_CYCLE = 1
    #: β = σ = 0 for the small family: eq. 43's root is ω = 0 with M = ∞, no cycle
    DEGENERATE = 2
    #: the root finder reported a failure (non-finite value, no convergence), or (small family) ω lies
    #: within rounding of π, where eq. 42's M ∝ cos(ω/2) cannot be computed in floating point
    NOT_SOLVED = 3

    @property
    def reason(self) -> str:
        """One line in words."""
        return _REASONS[self]


_REASONS = {
    ClosedFormStatus.OK: "ok",
    ClosedFormStatus.NO_CYCLE: "no cycle of this family at this point",
    ClosedFormStatus.DEGENERATE: "degenerate: with β = σ = 0 eq. 43 gives ω → 0 and M → ∞ (no cycle)",
    ClosedFormStatus.NOT_SOLVED: (
        "not solved here: the root finder failed (non-finite value or no convergence), or ω is within rounding "
        "of π (β/μ too large for eq. 42-43 in floating point)"
    ),
}


@dataclass(frozen=True)
class ClosedFormCycles:
    """Closed-form cycles over broadcast (μ, β, σ): NaN wherever ``status`` is not OK.

    Attributes
    ----------
    amplitude : numpy.ndarray
        M in encoder ticks (read-only).
    frequency : numpy.ndarray
        ω in rad per sample (read-only).
    status : numpy.ndarray of int8
        :class:`ClosedFormStatus` values (read-only).
    """

    amplitude: np.ndarray
    frequency: np.ndarray
    status: np.ndarray

    def __post_init__(self) -> None:
        for name in ("amplitude", "frequency", "status"):
            a = np.array(getattr(self, name))  # a copy, so that the caller's array stays writeable
            a.flags.writeable = False
            object.__setattr__(self, name, a)

    @property
    def codes(self) -> list[ClosedFormStatus]:
        """The status of each point as enum members (flattened)."""
        return [ClosedFormStatus(int(s)) for s in self.status.ravel()]


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
        """Why the caveat (:data:`~dfa.results.caveats.NO_CAVEAT`) and the band's top may be null in JSON.

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
