"""Requirement results: the parameter a target stiffness needs (:class:`Requirement`, :class:`Requirements`), the
damper guidance and the recommended stiffness (computed in :mod:`dfa.analysis.limits.require` and ``recommend``)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import ClassVar

from ..checks import check_choice, check_positive, check_type
from ..errors import DFAValueError
from ..model.device import Device
from ..model.wall import Wall
from .base import Result
from .codes import REQUIRE_PARAMETERS
from .status import RecommendRule, RequireStatus

#: The parameters asked about, with their unit kind (a key of ``Device.units``; the delay in samples).
PARAMETERS: dict[str, str] = dict(
    zip(REQUIRE_PARAMETERS, ("period", "resolution", "coulomb", "damping", "damping", "samples"), strict=True)
)


ALL_METHODS = ("criterion", "linear", "df")


#: Default gain margin of the simulated rule: the simulated limit divided by 2 (about 6 dB).
DEFAULT_MARGIN = 2.0


def check_margin(margin: float) -> float:
    """The gain margin, a finite number >= 1 (1: the simulated limit itself), or the package's error naming it.

    Parameters
    ----------
    margin : float
        Gain margin of the simulated rule.

    Returns
    -------
    float
        ``margin``.

    Raises
    ------
    DFAValueError, DFATypeError
        If it is not a finite number >= 1.
    """
    m = check_positive("margin", margin, "give a gain margin >= 1, e.g. 2 (about 6 dB)")
    if not (math.isfinite(m) and m >= 1.0):
        raise DFAValueError(f"margin = {margin!r} is invalid: it must be a finite number >= 1; give e.g. 2 (6 dB)")
    return m


@dataclass(frozen=True)
class Requirement(Result):
    """What one parameter must be for the target K, by one method.

    Attributes
    ----------
    method : str
        ``"criterion"`` (a proof) or ``"linear"`` (the linear loop's stability: necessary, not sufficient).
    parameter : str
        A key of :data:`PARAMETERS`.
    current : float
        Today's value (SI units; the delay in samples).
    required : float or None
        The value at which the target K is exactly the method's limit (None: see the status).
    bound : str
        ``"at_most"`` or ``"at_least"``: which side of ``required`` keeps the target K.
    status : RequireStatus
        ``met`` (K holds now; ``required`` is how far the parameter may move), ``change`` (the least change that
        makes K hold), ``unreachable``, ``any``, ``no_effect`` or ``not_covered``.
    searched : (float, float)
        The range of values evaluated.
    """

    method: str
    parameter: str
    current: float
    required: float | None
    bound: str
    status: RequireStatus
    searched: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        check_choice("method", self.method, ALL_METHODS)
        check_choice("parameter", self.parameter, tuple(PARAMETERS))
        check_choice("bound", self.bound, ("at_most", "at_least"))
        object.__setattr__(self, "status", RequireStatus.coerce(self.status))
        has = self.status in (RequireStatus.MET, RequireStatus.CHANGE)
        if (self.required is not None) != has:
            raise DFAValueError(
                f"required = {self.required!r} is invalid with status {self.status.value!r}: a value is given "
                "exactly when the status is 'met' or 'change'; build it with requirements"
            )

    def null_reasons(self) -> dict[str, str]:
        """Why ``required`` may be null (JSON): the status's message."""
        return {"required": self.status.message}


@dataclass(frozen=True)
class Requirements(Result):
    """The inverse answer for one target stiffness and speed: each parameter by each method.

    Attributes
    ----------
    device : Device
    wall : Wall
        The wall held fixed, at the target stiffness.
    velocity : float
        Impact speed, m/s (rotary: rad/s).
    requirements : tuple of Requirement
        One per (method, parameter), methods first.
    status : RequireStatus
        ``met`` when every method holds K today, else ``change``.
    """

    device: Device = field(metadata={"json": lambda d: d.to_dict()})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    requirements: tuple[Requirement, ...]
    status: RequireStatus

    json_properties: ClassVar[tuple[str, ...]] = ("stiffness",)

    @property
    def stiffness(self) -> float:
        """The target stiffness K, N/m (rotary: N·m/rad)."""
        return self.wall.stiffness

    def find(self, method: str, parameter: str) -> Requirement:
        """The requirement of one method on one parameter.

        Parameters
        ----------
        method : str
            One of :data:`METHODS`.
        parameter : str
            A key of :data:`PARAMETERS`.

        Returns
        -------
        Requirement
        """
        for r in self.requirements:
            if (r.method, r.parameter) == (method, parameter):
                return r
        raise DFAValueError(f"({method!r}, {parameter!r}) is not answered here: give one of {ALL_METHODS} and a key "
                            f"of {tuple(PARAMETERS)}")  # fmt: skip


@dataclass(frozen=True)
class DamperGuidance(Result):
    """What would let the criterion prove anything with a virtual damper at a speed (K → 0, eq. 11 extended).

    With the damper the criterion needs (b − B)|ẋ0| + c − (1 − a)BΔ/T > 0 and c − (1 − a)BΔ/T > 0 for some
    K > 0 (the wall's criterion is the spring's with β − β_B and σ − (1 − a)β_B). Each field is the bound on one
    parameter with the others held; None where no value of it helps.

    Attributes
    ----------
    proves_some_k : bool
        Whether some K > 0 is proven passive today.
    max_virtual_damping : float
        The largest B for which some K is proven, N·s/m.
    min_coulomb : float
        The least c, N.
    max_resolution : float or None
        The largest Δ, m (None: no Δ helps, the speed term alone fails).
    """

    proves_some_k: bool
    max_virtual_damping: float
    min_coulomb: float
    max_resolution: float | None

    def null_reasons(self) -> dict[str, str]:
        """Why ``max_resolution`` may be null (JSON)."""
        return {"max_resolution": "no encoder resolution helps: (B − b)·speed exceeds the Coulomb friction"}


@dataclass(frozen=True)
class ControllerChoice(Result):
    """The wall with its passivity controller against the wall without it (K in N/m; rotary N·m/rad).

    Attributes
    ----------
    kept : bool
        True: the wall with the controller is recommended; False: the wall without it (the controller lowers
        the simulated no-divergence limit, or the wall without it gets at least as high a K).
    lowers_limit : bool
        True when the controller lowers the simulated no-divergence limit (``k_sim``), or fails already at the
        lowest K searched where the wall without it has a limit.
    k_sim, plain_k_sim : float or None
        The simulated no-divergence limit with the controller and without it (None: that limit has no value;
        its answer's status says why).
    k_recommended, plain_k_recommended : float or None
        The K each wall is recommended on its own (None: no rule applies).
    force_limit : float or None
        The controller's force limit, N (rotary N·m); None: none, the textbook controller.
    """

    kept: bool
    lowers_limit: bool
    k_sim: float | None
    plain_k_sim: float | None
    k_recommended: float | None
    plain_k_recommended: float | None
    force_limit: float | None = None

    def null_reasons(self) -> dict[str, str]:
        """Why a limit or a recommended K may be null: that wall's limit has no value, or no rule applies.

        Returns
        -------
        dict of str to str
        """
        why = "that wall's limit has no value (its answer's status says why), or no rule recommends a K for it"
        out = dict.fromkeys(("k_sim", "plain_k_sim", "k_recommended", "plain_k_recommended"), why)
        return out | {"force_limit": "no force limit: the textbook controller"}


@dataclass(frozen=True)
class Recommendation(Result):
    """A recommended stiffness and its rule (module docstring); K in N/m (rotary N·m/rad).

    Attributes
    ----------
    device : Device
    wall : Wall
        The wall whose elements were held fixed while K varied.
    velocity : float
        Impact speed V, m/s (rotary: rad/s).
    k_recommended : float or None
        The recommended stiffness; None under the rule ``none``.
    basis : str or None
        The limit it comes from: ``"k_criterion"`` or ``"k_sim"`` (None under ``none``).
    k_basis : float or None
        That limit's value (under ``simulated_range`` the top of the range searched, a lower bound of it).
    margin : float
        Gain margin of the simulated rule (>= 1); ``k_recommended = k_basis / margin`` under ``simulated``.
    status : RecommendRule
        The rule followed: ``proven``, ``simulated``, ``simulated_range`` (no divergence in the whole range
        searched) or ``none``.
    k_rest : float or None
        The simulated rest limit of the recommended wall (``k_sim_rest``: every simulated impact up to V comes
        to rest up to it); None when it has no value (``above_rest`` then says whether K lies above the lowest
        K searched, where impacts already failed to rest).
    above_rest : bool
        True when the recommended K lies above the rest limit: the wall may buzz or oscillate there (just above
        the limit some simulated impact up to V did not come to rest).
    controller : ControllerChoice or None
        With a passivity controller compared with the wall without it (``recommend_stiffness(..., plain=)``):
        which wall is recommended and why; otherwise None (absent from JSON).
    """

    device: Device = field(metadata={"json": lambda d: d.name})
    wall: Wall = field(metadata={"json": lambda w: w.to_dict()})
    velocity: float
    k_recommended: float | None
    basis: str | None
    k_basis: float | None
    margin: float = DEFAULT_MARGIN
    status: RecommendRule = RecommendRule.NONE
    k_rest: float | None = None
    above_rest: bool = False
    controller: ControllerChoice | None = field(default=None, metadata={"omit_none": True})

    units_of: ClassVar[dict[str, str]] = {
        "velocity": "velocity", "k_recommended": "stiffness", "k_basis": "stiffness", "k_rest": "stiffness",
    }  # fmt: skip

    def __post_init__(self) -> None:
        fix = "Recommendation is built by recommend_stiffness; call that instead"
        check_type("device", self.device, Device, fix)
        check_type("wall", self.wall, Wall, fix)
        object.__setattr__(self, "status", RecommendRule.coerce(self.status))
        check_margin(self.margin)
        none = self.status in (RecommendRule.NONE, RecommendRule.NOT_SIMULATED)
        if none != (self.k_recommended is None) or none != (self.basis is None):
            raise DFAValueError(
                f"k_recommended = {self.k_recommended!r}, basis = {self.basis!r} are invalid for the rule "
                f"{self.status.value!r}: both must be None exactly under 'none' and 'not_simulated'; {fix}"
            )
        if self.k_recommended is not None and not (math.isfinite(self.k_recommended) and self.k_recommended > 0):
            raise DFAValueError(f"k_recommended = {self.k_recommended!r} is invalid: it must be finite and > 0; {fix}")

    def null_reasons(self) -> dict[str, str]:
        """Why the recommendation may be null, by key.

        Returns
        -------
        dict of str to str
            The rule's message for ``k_recommended``, ``basis`` and ``k_basis``.
        """
        out = {name: self.status.message for name in ("k_recommended", "basis", "k_basis")}
        out["k_rest"] = "the simulated rest limit has no value (see k_sim_rest's status in the answer)"
        return out
