"""Status enums of the analysis results: one enum per meaning, every member with a message.

Each result class carries a ``status`` member of one of these enums (like
diffrax's ``RESULTS``). A member compares equal to its value, a short code
(``status == "ok"``), so JSON holds the code and :attr:`StatusEnum.message` says
in words what it means. Where a status needs numbers of the case at hand (how far
a search reached), the result carries them in a separate field (``detail``).

Examples
--------
>>> from dfa.results.status import StiffnessStatus
>>> StiffnessStatus.TOO_STIFF == "too_stiff", StiffnessStatus("ok") is StiffnessStatus.OK
(True, True)
>>> StiffnessStatus.OK.message
'passive at this speed (proven)'
"""

from __future__ import annotations

import enum
from typing import Any

from ..errors import DFAValueError

__all__ = [
    "TuneStatus",
    "TunedStatus",
    "StatusEnum",
    "RequireStatus",
    "GripStatus",
    "IdentifyStatus",
    "IdentifyWarning",
    "LoggedCycleStatus",
    "WallCheckStatus",
    "ClosedLoopStatus",
    "CriterionStatus",
    "CheckStatus",
    "StiffnessStatus",
    "VelocityStatus",
    "CurveStatus",
    "ChartStatus",
    "SimulationOutcome",
    "Fails",
    "BatchStatus",
    "ContactOutcome",
    "ObserverStatus",
    "GainStatus",
    "ComparisonStatus",
    "LimitStatus",
    "KMaxStatus",
    "SearchStatus",
    "UndecidedWhy",
    "GrowthStatus",
    "NyquistStatus",
    "MapStatus",
    "ContourStatus",
    "SoundnessStatus",
    "ValidationStatus",
    "DesignStatus",
    "ReportStatus",
    "ZWidthStatus",
    "RecommendRule",
    "DeployRule",
    "LinearStatus",
    "PassivityStatus",
    "ConfigurationStatus",
]


class StatusEnum(str, enum.Enum):
    """Base of the status enums: value a short code (a ``str``), ``message`` its meaning in words."""

    message: str

    def __new__(cls, value: str, message: str) -> StatusEnum:
        obj = str.__new__(cls, value)
        obj._value_ = value
        obj.message = message
        return obj

    def __str__(self) -> str:
        return str(self.value)

    def __format__(self, spec: str) -> str:
        return format(str(self.value), spec)

    @classmethod
    def coerce(cls, value: Any, name: str = "status") -> Any:
        """The member of this enum that ``value`` (a member or its code) names.

        Raises
        ------
        DFAValueError
            When ``value`` names no member.
        """
        for member in cls:
            if value is member or (isinstance(value, str) and value == member.value):
                return member
        codes = ", ".join(repr(m.value) for m in cls)
        raise DFAValueError(
            f"{name} = {value!r} is invalid: it must be a {cls.__name__} ({codes}); use the enum member"
        )


class CriterionStatus(StatusEnum):
    """Meaning of the region of paper Fig. 3 (eq. 6, 10) in which an operating point lies, for any covered wall.

    The regions a-e of the (β, σ) plane around the corner (β₀, σ₀) of the criterion's critical line: (½ + d, ½)
    for the paper's spring with a delay of d samples, moved by a damper or a filter
    (:mod:`dfa.analysis.criterion`). Region b has two meanings: with σ < ½ the device cannot stop (the force
    at rest is at least ½ in units of KΔ), with ½ <= σ < σ₀ the criterion gives no guarantee at rest.
    """

    PASSIVE_ALL_SPEEDS = (
        "passive_all_speeds",
        "passive at every speed: the energy cannot grow (proven; β >= β₀ and σ >= σ₀)",
    )
    NO_GUARANTEE_AT_REST = (
        "no_guarantee_at_rest",
        "no passivity guarantee even at rest: σ < σ₀ (not a proof of instability; sub-tick chatter possible)",
    )
    NOT_PASSIVE_AT_REST = (
        "not_passive_at_rest",
        "not passive at rest: σ < ½, the device cannot stop; sub-tick chatter expected (paper, d = 0)",
    )
    NO_GUARANTEE = (
        "no_guarantee",
        "no passivity guarantee at any speed: σ < σ₀ and β < β₀ (not a proof of instability)",
    )
    ABOVE_CRITICAL_SPEED = (
        "above_critical_speed",
        "no passivity guarantee at this speed: above the critical speed (not a proof of instability)",
    )
    PASSIVE_BELOW_CRITICAL_SPEED = (
        "passive_below_critical_speed",
        "passive up to the critical speed: the energy cannot grow (proven)",
    )

    @property
    def region(self) -> str:
        """The region letter ``"a"`` … ``"e"`` of paper Fig. 3."""
        return _REGIONS[self.value]

    @classmethod
    def of_region(cls, region: str, *, cannot_stop: bool = True) -> CriterionStatus:
        """The status of region ``"a"`` … ``"e"``; in region b, ``cannot_stop`` (σ < ½) picks which meaning."""
        if region == "b":
            return cls.NOT_PASSIVE_AT_REST if cannot_stop else cls.NO_GUARANTEE_AT_REST
        return next(s for s in cls if s.region == region)


_REGIONS = {
    "passive_all_speeds": "a",
    "no_guarantee_at_rest": "b",
    "not_passive_at_rest": "b",
    "no_guarantee": "c",
    "above_critical_speed": "d",
    "passive_below_critical_speed": "e",
}


class CheckStatus(StatusEnum):
    """Verdict of the passivity check of a device with a wall (:class:`dfa.analysis.check.PassivityCheck`)."""

    PASSIVE = ("passive", "passive: the criterion (eq. 6) proves the energy cannot grow up to this speed")
    NO_GUARANTEE = ("no_guarantee", "no passivity guarantee at this speed (not a proof of instability)")
    NOT_COVERED = ("not_covered", "not covered by the criterion; see `dfa map`/`dfa zwidth`")


class StiffnessStatus(StatusEnum):
    """Verdict on a chosen stiffness at the impact speed (eq. 11)."""

    OK = ("ok", "passive at this speed (proven)")
    NOT_REQUESTED = ("not_requested", "no stiffness given to assess: the limits alone")
    TOO_STIFF = ("too_stiff", "no passivity guarantee at this speed (K > K_max); not a proof of instability")
    NOT_COVERED = (
        "not_covered",
        "no sound passivity criterion covers the wall (an amplifier lag, a passivity controller, or a one-sided wall with a damper): no verdict",
    )


class VelocityStatus(StatusEnum):
    """What the largest passive speed of a chosen stiffness is (eq. 12)."""

    NOT_REQUESTED = ("not_requested", "no stiffness given")
    ALL_SPEEDS = ("all_speeds", "passive at every speed (K <= 2b/T, or b/(T(½ + d)) with a delay)")
    BOUNDED = ("bounded", "passive up to a finite speed")
    NONE = ("none", "no passivity guarantee even at rest (K > 2c/Δ; with a damper σ < σ₀)")
    NOT_COVERED = (
        "not_covered",
        "no sound passivity criterion covers the wall (an amplifier lag, a passivity controller, or a one-sided wall with a damper)",
    )


class CurveStatus(StatusEnum):
    """Status of a stiffness limit curve over impact speeds."""

    OK = ("ok", "K_max computed at every speed")


class ChartStatus(StatusEnum):
    """Status of the stiffness–speed chart (:mod:`dfa.analysis.limits.speed_chart`)."""

    OK = ("ok", "every method's largest safe speed found at every stiffness")
    DF_UNKNOWN = (
        "df_unknown",
        "the describing function cannot tell at some stiffnesses (no value there); the other methods are complete",
    )


class Fails(enum.Flag):
    """The simulated limits a run's outcome fails (:attr:`SimulationOutcome.fails`), declared once on the outcome.

    Every reading derives from it: the limits' verdicts (:data:`dfa.analysis.limits.runs.FAILING`), the point of a
    Z-width grid (a run failing :attr:`NO_DIVERGENCE` makes the point diverge) and the grip sweep (a grip with such a
    run, or an undecided one, is not firm enough).

    Examples
    --------
    >>> Fails.REST in SimulationOutcome.CHATTER.fails, Fails.NO_DIVERGENCE in SimulationOutcome.CHATTER.fails
    (True, False)
    """

    #: Fails no limit (the run came to rest, left a one-sided wall, or is undecided: neither passes nor fails).
    NONE = 0
    #: Fails "no simulated impact diverges": the run diverged, or a large motion was held only by the device.
    NO_DIVERGENCE = enum.auto()
    #: Fails "every simulated impact comes to rest".
    REST = enum.auto()
    #: Fails both.
    BOTH = NO_DIVERGENCE | REST


class SimulationOutcome(StatusEnum):
    """How an exact simulation ended (:mod:`dfa.analysis.simulation`); the order is the outcome code of the maps.

    The order is also the compiled kernel's code of each outcome (:mod:`dfa.core.kernel`: ``REST = 0`` ...,
    one constant per member, named as it). Each member declares, beside its code and message, the simulated
    limits it fails (:class:`Fails`, :attr:`fails`): a new outcome is one member here (and its code in the kernel),
    and the limits, the Z-width's points and the grip sweep read it.
    """

    fails: Fails

    def __new__(cls, value: str, message: str, fails: Fails = Fails.NONE) -> SimulationOutcome:
        obj = str.__new__(cls, value)
        obj._value_ = value
        obj.message = message
        obj.fails = fails
        return obj

    REST = ("rest", "came to rest")
    OSCILLATING = ("oscillating", "persistent oscillation of one tick or more", Fails.REST)
    UNSTABLE = ("unstable", "diverged (past the bound, or a growing envelope)", Fails.BOTH)
    CHATTER = (
        "chatter",
        "never comes to rest; the force keeps toggling below one tick of motion (a buzz)",
        Fails.REST,
    )
    UNDECIDED = ("undecided", "the motion is still changing at the end of the run")
    LEFT = ("left", "left the one-sided wall for good: outside, moving away, and nothing brings it back")
    #: A large motion held by the actuator's force limit (the unlimited wall oscillates or diverges): fails both.
    SATURATED = (
        "saturated",
        "never comes to rest; the force reached the actuator's limit at the end of the run: a large motion held by "
        "the actuator (the unlimited wall would oscillate or diverge), no stable wall",
        Fails.BOTH,
    )
    #: The device ran out of its travel (the wall did not hold it): fails both.
    END_STOP = (
        "end_stop",
        "reached the device's end stop: the position left its travel, where the run ends",
        Fails.BOTH,
    )

    @classmethod
    def failing(cls, fails: Fails) -> frozenset[str]:
        """Give the codes of the outcomes that fail ``fails``.

        Parameters
        ----------
        fails : Fails
            One limit (:attr:`Fails.NO_DIVERGENCE` or :attr:`Fails.REST`).

        Returns
        -------
        frozenset of str
            The outcomes' codes (``"unstable"``, ...).

        Examples
        --------
        >>> sorted(SimulationOutcome.failing(Fails.NO_DIVERGENCE))
        ['end_stop', 'saturated', 'unstable']
        """
        return frozenset(o.value for o in cls if fails in o.fails)

    @property
    def code(self) -> int:
        """The outcome's code: its place in the enum, the compiled kernel's constant of the same name."""
        return list(type(self)).index(self)


class ContactOutcome(StatusEnum):
    """How a run on a one-sided wall ended, as contact (:attr:`dfa.analysis.simulation.SimulationResult.contact`).

    From the outcome and where the wall saw the device (issue 28 §1): over the tail, a reading outside between
    readings inside is a bounce.
    """

    RESTS = ("rests", "comes to rest on the wall")
    RESTS_OFF = ("rests_off", "comes to rest off the wall (the push does not overcome friction)")
    IN_CONTACT = ("in_contact", "keeps moving (a cycle or a buzz) without leaving the wall")
    BOUNCES = ("bounces", "leaves the wall and returns, again and again, with bounded peaks")
    GROWS = ("grows", "diverged: past the bound (each bounce higher, or pushed through the wall)")
    LEFT = ("left", "leaves the wall for good")
    END_STOP = ("end_stop", "reaches the device's end stop (carried past its travel)")
    UNDECIDED = ("undecided", "the motion is still changing at the end of the run")


class ObserverStatus(StatusEnum):
    """What the passivity observer saw over a run (:class:`dfa.analysis.observer.ObserverSummary`; issue 30)."""

    PASSIVE = ("passive", "the wall never produced energy: the observed energy into it stayed >= 0 at every reading")
    ACTIVE = ("active", "the wall produced energy: the observed energy into it fell below 0 at some reading")


class GainStatus(StatusEnum):
    """What a passivity controller's gain rests on (:class:`dfa.analysis.limits.passivity_gain.PassivityGain`)."""

    OK = ("ok", "both walls' simulated limits stand as searched: monotone, decided, confirmed")
    CAVEATS = (
        "caveats",
        "a simulated limit of one of the walls has caveats (non-monotone, undecided runs, lowered; see each limit)",
    )
    COUNTEREXAMPLE = (
        "counterexample",
        "an impact on the wall without the controller diverged at a stiffness the criterion proves passive: a "
        "criterion bug (see its answer)",
    )


class ComparisonStatus(StatusEnum):
    """What the bilateral-versus-one-sided comparison rests on (:mod:`dfa.studies.contact_comparison`)."""

    OK = ("ok", "every limit found or bounded by its search, no counterexample")
    COUNTEREXAMPLE = (
        "counterexample",
        "a simulated impact diverged at a stiffness the criterion proves passive: a criterion bug (see the rows)",
    )


class BatchStatus(StatusEnum):
    """Status of a batch of simulations (:class:`dfa.analysis.simulation.SimulationBatch`)."""

    OK = ("ok", "every run simulated")


class LimitStatus(StatusEnum):
    """What a stiffness limit is, or why it has no value (:class:`dfa.analysis.limits.search.KLimit`)."""

    FOUND = ("found", "the limit stands as stated, with its evidence")
    ABOVE_RANGE = ("above_range", "no failure at any stiffness searched: the limit lies above the range searched")
    BELOW_RANGE = ("below_range", "it fails already at the smallest stiffness searched")
    NO_RANGE = (
        "no_range",
        "no search range: the device has neither viscous nor Coulomb friction, or there is no finite closed-form bound",
    )
    NOT_CONFIRMED = (
        "not_confirmed",
        "no stiffness confirmed: failures below the searched limit reach the lowest stiffness searched, or the "
        "confirmation did not settle",
    )
    NOT_COVERED = (
        "not_covered",
        "not covered by the criterion: no sound passivity criterion covers an element of the wall (an amplifier lag, "
        "a passivity controller; a one-sided wall with a damper or filter)",
    )
    NOT_LINEAR = (
        "not_linear",
        "not covered: the wall is not a linear loop (a one-sided wall leaves it; a passivity controller switches its "
        "damper with the energy); the exact linear bound and the describing function need one",
    )
    NONE_PROVEN = ("none_proven", "the criterion proves no stiffness passive at this speed")
    NEVER = (
        "never",
        "the criterion proves no stiffness passive even at rest with this wall: σ >= σ₀ needs c/Δ > (1 − a)B/T",
    )
    NO_STABLE_K = ("no_stable_k", "the linear loop is unstable already at small K (no stable interval from K = 0)")
    NOT_SEARCHED = ("not_searched", "not searched: the describing-function and simulated limits need a speed > 0")
    NOT_SIMULATED = (
        "not_simulated",
        "not simulated: a quick answer (dfa stiffness --quick) computes the criterion, the static and exact linear "
        "bounds and the describing function only",
    )


class KMaxStatus(StatusEnum):
    """What a K_max answer rests on (:class:`dfa.analysis.limits.kmax.KMaxResult`)."""

    OK = ("ok", "every searched limit stands as searched: monotone, decided, confirmed")
    CAVEATS = (
        "caveats",
        "a searched limit is non-monotone in K, limited by undecided judgements, or was lowered by failures the "
        "sweep or the confirmation found (see each limit)",
    )
    COUNTEREXAMPLE = (
        "counterexample",
        "an impact diverged at a stiffness the criterion proves passive: a criterion bug (see counterexamples)",
    )
    NOT_SIMULATED = (
        "not_simulated",
        "a quick answer: the criterion, the linear bounds and the describing function; nothing simulated or confirmed",
    )


class UndecidedWhy(StatusEnum):
    """Why a judgement of a stiffness search was undecided (:attr:`dfa.results.limits.KLimit.limited_why`, which
    holds the code; :mod:`dfa.render.limits` words it)."""

    SHORT_RUNS = ("short_runs", "simulated runs too short to tell")
    SUBTICK = (
        "subtick",
        "the sub-tick caveat: the smallest unstable cycle lies below dfa.analysis.cycles.SUBTICK_LIMIT ticks",
    )
    BELOW_REACH = (
        "below_reach",
        "a cycle search that stopped at its size budget bounds the growth speed only from below V",
    )
    UNKNOWN_GROWTH = ("unknown_growth", "a cycle search that failed: the growth speed is unknown")
    OUTSIDE_MU = (
        "outside_mu",
        "μ = m/(K T²) outside dfa.analysis.cycles.SEARCHED_MU, where the cycle search claims nothing",
    )


class SearchStatus(StatusEnum):
    """How a limit-cycle search ended (:attr:`dfa.analysis.cycles.LimitCycleResult.status`)."""

    COMPLETE = ("complete", "every root of eq. 36 was found: the pieces ended or the envelope bound closed them")
    MAX_AMPLITUDE = ("max_amplitude", "incomplete: roots may exist beyond the caller's max_amplitude")
    BUDGET = (
        "budget",
        "incomplete: the envelope bound lies beyond the size budget of the automatic search range",
    )
    NUMERICAL = (
        "numerical",
        "incomplete: a root finder failed (no sign change where the scan saw one, or no convergence)",
    )
    TIME_BUDGET = (
        "time_budget",
        "incomplete: the time budget ran out before every piece of the phase curve was searched",
    )
    FREQUENCY_RANGE = (
        "frequency_range",
        "not searched: μ lies outside the range where every cycle's frequency falls inside the scanned ω grid",
    )


class GrowthStatus(StatusEnum):
    """What the describing function predicts about growth (:class:`dfa.analysis.cycles.GrowthThreshold`)."""

    OK = ("ok", "unstable cycles found: growth is predicted above the band (first-harmonic approximation)")
    NO_UNSTABLE_CYCLE = ("no_unstable_cycle", "no unstable cycle predicted")
    NO_UNSTABLE_CYCLE_SEARCHED = (
        "no_unstable_cycle_searched",
        "no unstable cycle predicted up to the amplitude searched (the search was incomplete)",
    )
    LINEAR_UNSTABLE = (
        "linear_unstable",
        "no unstable cycle predicted, but the linear loop (exact ZOH model) is unstable: amplitudes grow without bound",
    )
    NOT_SEARCHED = (
        "not_searched",
        "no prediction: μ lies outside the range the limit-cycle search covers (dfa.analysis.cycles.SEARCHED_MU)",
    )


class NyquistStatus(StatusEnum):
    """What a Nyquist locus response holds (:class:`dfa.results.loop.NyquistLocusResponse`)."""

    OK = ("ok", "curves, locus and crossings computed")
    CROSSINGS_NOT_COMPUTED = (
        "crossings_not_computed",
        "crossings not computed for sigma > 0: use the limit-cycle solver",
    )
    SEARCH_INCOMPLETE = (
        "search_incomplete",
        "crossings may be missing: the limit-cycle solver's search ended incomplete (see detail)",
    )


class MapStatus(StatusEnum):
    """Status of a simulated stability map (:class:`dfa.analysis.maps.StabilityMap`)."""

    OK = ("ok", "every grid point simulated; amplitude and frequency NaN where not measured")


class ContourStatus(StatusEnum):
    """Status of the cycle contour maps (:class:`dfa.analysis.contours.ContourMaps`)."""

    OK = ("ok", "every grid point solved; NaN where a family does not exist or lies beyond max_amplitude")
    FLAGGED = (
        "flagged",
        "the closed forms flagged grid points (NaN): β = σ = 0 is degenerate, or a root finder failed",
    )


class SoundnessStatus(StatusEnum):
    """Whether simulation contradicted a passivity verdict (:class:`dfa.studies.soundness.CriterionSoundness`)."""

    SOUND = ("sound", "no simulated point called passive gained energy or diverged")
    VIOLATED = ("violated", "some points called passive gained energy or diverged: the criterion is not sound here")


class ValidationStatus(StatusEnum):
    """Status of a validation run (:class:`dfa.studies.validation.ValidationResult`)."""

    OK = ("ok", "every validation item ran")


class DesignStatus(StatusEnum):
    """Status of a design analysis (:class:`dfa.studies.design.DesignAnalysis`)."""

    OK = ("ok", "every number of the design report computed")


class ReportStatus(StatusEnum):
    """Status of a written design report (:class:`dfa.studies.report.ReportResult`)."""

    OK = ("ok", "every file of the report written")


class ZWidthStatus(StatusEnum):
    """What a Z-width rests on (:class:`dfa.analysis.limits.zwidth.ZWidth`)."""

    OK = ("ok", "every grid point decided, every simulated column monotone in K, no counterexample")
    CAVEATS = (
        "caveats",
        "some grid points are undecided (runs too short to tell) or a simulated column is non-monotone in K "
        "(see the reasons)",
    )
    COUNTEREXAMPLE = (
        "counterexample",
        "a grid point diverged at a stiffness the extended criterion proves passive: a criterion bug "
        "(see counterexamples)",
    )


class LinearStatus(StatusEnum):
    """Shape of the stable set in K of the linear sampled loop (:func:`dfa.analysis.linear_wall.stable_stiffness`)."""

    INTERVAL = ("interval", "stable exactly for 0 < K < K_crit (every stability condition checked)")
    SEVERAL = (
        "several_intervals",
        "the stable set in K has several intervals: K_crit is the top of the one starting at K = 0; see intervals",
    )
    NOT_AT_LOW_K = (
        "not_at_low_k",
        "unstable for small K: stable only on the listed intervals (K_crit = 0)",
    )
    NEVER = ("never", "unstable for every K > 0 (K_crit = 0)")


class PassivityStatus(StatusEnum):
    """How tightly the maximum of the Colgate–Schenkel condition is known."""

    CERTIFIED = ("certified", "maximum found and certified to 1e-12 (relative)")
    BOUNDED = (
        "bounded",
        "evaluation budget spent: the maximum lies between beta_min and beta_bound (use the bound to be safe)",
    )


class RecommendRule(StatusEnum):
    """The rule a recommended stiffness follows (:func:`dfa.analysis.limits.recommend.recommend_stiffness`)."""

    PROVEN = ("proven", "the largest K the criterion proves passive at this speed (a proof: no margin needed)")
    SIMULATED = (
        "simulated",
        "no proof at this speed: the largest K no simulated impact diverged at, divided by the gain margin",
    )
    SIMULATED_RANGE = (
        "simulated_range",
        "no proof at this speed: no simulated impact diverged up to the top of the range searched; that K divided by "
        "the gain margin (the simulated limit lies above it)",
    )
    NONE = ("none", "no K to recommend: no proof, and no simulated stiffness free of divergence, at this speed")
    NOT_SIMULATED = (
        "not_simulated",
        "no K to recommend: no proof at this speed, and the simulated limits were not computed (a quick answer, "
        "--quick); run without --quick for them",
    )


class DeployRule(StatusEnum):
    """The rule behind an exported wall's stiffness (:class:`dfa.results.deploy.DeployableWall`): a recommendation's
    rule (:class:`RecommendRule`, those that give a K) or ``given``."""

    PROVEN = (RecommendRule.PROVEN.value, RecommendRule.PROVEN.message)
    SIMULATED = (RecommendRule.SIMULATED.value, RecommendRule.SIMULATED.message)
    SIMULATED_RANGE = (RecommendRule.SIMULATED_RANGE.value, RecommendRule.SIMULATED_RANGE.message)
    GIVEN = ("given", "the stiffness was given: no impact speed or rule chose it, and nothing here proves it passive")


class RequireStatus(StatusEnum):
    """What one parameter must be for a target stiffness, by one method (:class:`dfa.analysis.limits.require.Requirement`)."""

    MET = ("met", "the target K holds now; the value is how far this parameter may move before it fails")
    CHANGE = ("change", "the target K does not hold now; the value is the least change that makes it hold")
    UNREACHABLE = ("unreachable", "no value of this parameter in the range searched makes the target K hold")
    ANY = ("any", "the target K holds at every value of this parameter in the range searched")
    NO_EFFECT = ("no_effect", "this method does not depend on this parameter")
    NOT_COVERED = ("not_covered", "the criterion does not cover this wall (no proof either way)")


class GripStatus(StatusEnum):
    """How firm a grip one method needs at the design K (:class:`dfa.analysis.limits.grip.GripNeed`)."""

    ANY_GRIP = ("any_grip", "holds with no hand damping: any grip, the lightest included")
    AT_LEAST = ("at_least", "holds for a hand damping at least this (a firmer grip)")
    UNREACHABLE = ("unreachable", "no hand damping in the range searched makes it hold")
    NOT_COVERED = ("not_covered", "the criterion does not cover this wall (no proof either way)")


class IdentifyStatus(StatusEnum):
    """How far an identification from a log can be used (:class:`dfa.analysis.identify.Identification`)."""

    OK = ("ok", "identified: the fit reproduces the log segment by segment, and every parameter is excited")
    CAVEATS = ("caveats", "identified, with the warnings below (what the log does not excite or show well)")
    POOR_FIT = ("poor_fit", "the identified model does not reproduce the log: its values are not to be trusted")


class LoggedCycleStatus(StatusEnum):
    """Whether a logged oscillation is a predicted limit cycle (:class:`dfa.analysis.logged_cycle.LoggedCycle`)."""

    PREDICTED = (
        "predicted",
        "the log's sustained oscillation is the limit cycle predicted for the identified device and this wall "
        "(the exact simulation's, within tolerance)",
    )
    NOT_PREDICTED = (
        "not_predicted",
        "the log oscillates, but not as predicted for the identified device and this wall: another wall, a "
        "delay or filter, or dynamics the model lacks",
    )
    NO_OSCILLATION = ("no_oscillation", "the log ends without a sustained oscillation")


class WallCheckStatus(StatusEnum):
    """Whether a log's force column is the given wall's law of its readings
    (:class:`dfa.results.closed_loop.WallForceCheck`)."""

    CONSISTENT = ("consistent", "the force column is the given wall's force of the logged readings")
    MISMATCH = (
        "mismatch",
        "the force column is not the given wall's force of the logged readings: another K, B or delay, the wall "
        "elsewhere than x = 0, or a force logged when computed rather than when applied",
    )


class ClosedLoopStatus(StatusEnum):
    """How the logged contact compares with the prediction for the identified device and the logged wall
    (:class:`dfa.results.closed_loop.ClosedLoopEvidence`)."""

    AGREES = (
        "agrees",
        "the logged contact is the one the exact simulation predicts for the identified device and this wall",
    )
    WITHIN_INTERVALS = (
        "within_intervals",
        "the logged contact is not the one predicted for the identified values, but it is for a device with b and c "
        "within their 95 % intervals and this wall",
    )
    DIFFERS = (
        "differs",
        "the logged contact is not the one predicted for any device with b and c within their 95 % intervals and "
        "this wall: another wall, values outside their intervals, or dynamics the model lacks",
    )
    NO_CONTACT = ("no_contact", "the log holds no reading inside the wall (x >= 0): no contact to compare")


class IdentifyWarning(StatusEnum):
    """What a log does not show (:class:`dfa.analysis.identify.Identification`)."""

    NO_REVERSAL = (
        "no_reversal",
        "the device moves one way only: Coulomb friction and a force offset cannot be told apart",
    )
    DAMPING_FRICTION_CONFOUNDED = (
        "damping_friction_confounded",
        "damping and Coulomb friction are not separated: the log has no motion both fast and slow",
    )
    LITTLE_MOTION = (
        "little_motion",
        "the log holds little motion (fewer than 300 samples in which the reading changes): too little to bound "
        "the estimates, which get no interval",
    )
    FRICTION_UNRESOLVED = (
        "friction_unresolved",
        "the Coulomb friction is below 10⁻⁴ of the largest logged force: the log cannot resolve it, whatever "
        "its interval says",
    )
    LOOSE_MASS = ("loose_mass", "the mass is poorly determined (95 % interval wider than ±25 %, or unbounded)")
    LOOSE_DAMPING = ("loose_damping", "the damping is poorly determined (95 % interval wider than ±25 %, or unbounded)")
    LOOSE_COULOMB = (
        "loose_coulomb",
        "the Coulomb friction is poorly determined (95 % interval wider than ±25 %, or unbounded)",
    )
    POOR_FIT = (
        "poor_fit",
        "fewer than 90 % of the samples are predicted within one tick, and noise on the force column explains the "
        "misfit only if it exceeds 25 % of the force's spread; or, with noise on the readings, the residuals' mean "
        "square exceeds 200 times their white level: the model does not reproduce the log",
    )
    CONSTANT_FORCE = (
        "constant_force",
        "the force column holds one value: the log shows only where the device's speed settles (b v + c = f + f₀), "
        "not m, b, c and f₀ apart; log a force that changes (steps up and down, reversing the motion)",
    )
    FORCE_NOISE = (
        "force_noise",
        "the residuals exceed the encoder's quantization: noise on the force column explains them, and the intervals "
        "include it",
    )
    POSITION_NOISE = (
        "position_noise",
        "the readings carry noise beyond their quantization (white, from one sample to the next: an analog sensor or "
        "a noisy encoder): the fit and its intervals include it, but the analyses model the readings as quantized "
        "alone, and a wall fed such readings pushes with its noise",
    )
    JITTER = (
        "jitter",
        "a logged period departs from T by more than 1 % of it: every analysis takes each sample to last T, and its "
        "limits move about as much as the period does",
    )


class TuneStatus(StatusEnum):
    """What a tuning found (:func:`dfa.analysis.limits.tune.tune`)."""

    TUNED = ("tuned", "a wall with the elements allowed gets a higher recommended K than the plain wall")
    PLAIN_BEST = ("plain_best", "no wall with the elements allowed gets a higher recommended K than the plain wall")
    NONE = (
        "none",
        "no wall tried has a recommended K at this speed within the force error allowed (no proof and no simulated K "
        "free of divergence, or too large a force error)",
    )


class TunedStatus(StatusEnum):
    """How far one candidate wall of a tuning was taken (:class:`dfa.results.tune.TunedWall`)."""

    SIMULATED = ("simulated", "its stiffness searched in full: proof, simulated limits and the recommendation")
    SCREENED = ("screened", "screened only (criterion and exact linear bound): ranked below the walls simulated")


class ConfigurationStatus(StatusEnum):
    """The worst configuration of a device (:class:`dfa.results.configurations.WorstConfiguration`, issue 46)."""

    FOUND = ("found", "the limiting configuration has the smallest value of all (the wall must hold there)")
    NONE = (
        "none",
        "the limiting configuration has no value: no recommended stiffness (or no covered margin) there, so none "
        "holds for the device",
    )
