"""What a soundness count is: its fields, checks, status and JSON, and the tally that fills them.

The frozen base of :class:`dfa.studies.soundness.CriterionSoundness` (which adds what belongs to one
population of points: the spring's ``delay``, the random walls' ``by_case``), and :func:`tally`, which counts
the simulated points of either population.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..checks import check_int
from ..errors import DFAValueError
from ..results.base import Result
from ..results.status import SoundnessStatus

__all__ = ["TOLERANCE", "KINDS", "SoundnessCounts", "tally"]

#: Relative tolerance on S(h) <= S(0): rounding of the exact integrator only.
TOLERANCE = 1e-9
#: How a point was drawn: inside the passive region, on the critical line, on σ = σ₀, on β = β₀.
KINDS = ("interior", "line", "sigma-edge", "beta-edge")


def tally(
    pts: Mapping[str, np.ndarray],
    keys: tuple[str, ...],
    ns: np.ndarray,
    ratio: np.ndarray,
    at: np.ndarray,
    div: np.ndarray,
) -> dict[str, Any]:
    """The count fields of a soundness record from its simulations (one implementation).

    Parameters
    ----------
    pts : mapping of str to numpy.ndarray
        The sampled points (arrays ``keys`` and ``kind``, an index into :data:`KINDS`).
    keys : tuple of str
        The fields that describe a point (reported for the worst one).
    ns : numpy.ndarray
        Run length of each point, samples.
    ratio : numpy.ndarray
        Largest S/S(0) − 1 of each run, dimensionless (inf: past the bound).
    at : numpy.ndarray
        The sample where it occurred.
    div : numpy.ndarray
        Whether each run diverged.

    Returns
    -------
    dict
        ``by_kind``, ``energy_grew``, ``diverged``, ``violations``, ``worst_growth``, ``worst_point``,
        ``samples_min``, ``samples_max``.
    """
    grew = ratio > TOLERANCE
    w = int(np.argmax(ratio))
    worst: dict[str, Any] = {k: pts[k][w].item() for k in keys}
    worst.update(sample=int(at[w]), kind=KINDS[int(pts["kind"][w])])
    return dict(
        by_kind={k: int(np.sum(pts["kind"] == i)) for i, k in enumerate(KINDS)},
        energy_grew=int(grew.sum()),
        diverged=int(div.sum()),
        violations=int((grew | div).sum()),
        worst_growth=float(ratio[w]),
        worst_point=worst,
        samples_min=int(ns.min()),
        samples_max=int(ns.max()),
    )


#: Key order of a soundness record's JSON: a population's own field (``delay``, ``by_case``) where it always stood.
JSON_ORDER = ("delay", "criterion", "points", "by_kind", "by_case", "energy_grew", "diverged", "violations",
              "worst_growth", "worst_point", "samples_min", "samples_max", "seed", "status", "status_message")  # fmt: skip


@dataclass(frozen=True, kw_only=True)
class SoundnessCounts(Result):
    """The count of simulated points a criterion called passive: fields, validation, ``status``, ``to_dict``.

    Attributes
    ----------
    criterion : str
        The criterion that called the points passive.
    points : int
        Points simulated.
    by_kind : dict of str to int
        Points per sampling kind (:data:`KINDS`).
    energy_grew : int
        Points where the storage S exceeded S(0)(1 + :data:`TOLERANCE`) at some sample.
    diverged : int
        Points whose run diverged.
    violations : int
        Points with grown energy or divergence.
    worst_growth : float
        Largest max S/S(0) − 1 over all points, dimensionless (inf: past the bound).
    worst_point : dict
        The point with that growth: its fields, the ``sample`` where the growth occurred and its ``kind``.
    samples_min, samples_max : int
        Shortest and longest run, samples.
    seed : int
        Seed of the random draw.
    status : SoundnessStatus
        ``sound`` when ``violations`` is 0, else ``violated`` (derived).
    """

    criterion: str
    points: int
    by_kind: dict[str, int]
    energy_grew: int
    diverged: int
    violations: int
    worst_growth: float
    worst_point: dict[str, Any] = field(default_factory=dict)
    samples_min: int = 0
    samples_max: int = 0
    seed: int = 0

    json_properties: ClassVar[tuple[str, ...]] = ("status",)
    #: The function whose counts the record holds (named in the fix of a bad record).
    SOURCE: ClassVar[str] = "the soundness function"
    #: Fields of one population only: left out of the JSON when None (the other population's record).
    POPULATION_FIELDS: ClassVar[tuple[str, ...]] = ()

    def __post_init__(self) -> None:
        fix = f"pass the counts {self.SOURCE} returned"
        for name in ("points", "energy_grew", "diverged", "violations"):
            check_int(name, getattr(self, name), 0, fix)
        if self.violations > self.points:
            raise DFAValueError(
                f"violations = {self.violations} is invalid: it cannot exceed points = {self.points}; {fix}"
            )

    @property
    def status(self) -> SoundnessStatus:
        """``SOUND`` when no simulated point violated the criterion, else ``VIOLATED``."""
        return SoundnessStatus.SOUND if self.violations == 0 else SoundnessStatus.VIOLATED

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready record: :meth:`Result.to_dict` in the key order of :data:`JSON_ORDER`.

        A field of :attr:`POPULATION_FIELDS` that is None (it belongs to the other population) is left out;
        an infinite growth becomes null, with the reason under ``null_reasons``.

        Returns
        -------
        dict
            The fields, ``status`` and ``status_message`` (then ``null_reasons`` if a value was nulled).
        """
        out = super().to_dict()
        for name in self.POPULATION_FIELDS:
            if getattr(self, name) is None:
                del out[name]
        rank = {k: i for i, k in enumerate(JSON_ORDER)}
        return dict(sorted(out.items(), key=lambda kv: rank.get(kv[0], len(rank))))
