"""What every soundness count shares: its fields, checks, status and JSON (one declaration, one implementation).

The frozen base of the result records :class:`dfa.analysis.soundness.DelaySoundness` (which adds ``delay``) and
:class:`dfa.analysis.wall_soundness.ControllerSoundness` (which adds ``by_case``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..checks import check_int
from ..errors import DFAValueError
from ..results.jsonable import to_jsonable
from ..results.status import SoundnessStatus

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
):
    """The count fields of a soundness record from its simulations (one implementation).

    Parameters
    ----------
    pts : mapping of str to numpy.ndarray
        The sampled points (arrays ``keys`` and ``kind``, an index into :data:`KINDS`).
    keys : tuple of str
        The fields that describe a point (reported for the worst one).
    ns, ratio, at, div : numpy.ndarray
        Run length, max S/S(0) − 1, its sample, and whether the run diverged, per point.

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


#: Key order of a soundness record's JSON: a record's own field (``delay``, ``by_case``) where it always stood.
_JSON_ORDER = ("delay", "criterion", "points", "by_kind", "by_case", "energy_grew", "diverged", "violations",
               "worst_growth", "worst_point", "samples_min", "samples_max", "seed")  # fmt: skip


@dataclass(frozen=True, kw_only=True)
class SoundnessCounts:
    """The count of simulated points a criterion called passive: fields, validation, ``status``, ``to_dict``.

    Attributes
    ----------
    criterion : str
        The criterion that called the points passive.
    points : int
        Points simulated.
    by_kind : dict
        Points per sampling kind (:data:`KINDS`).
    energy_grew, diverged, violations : int
        Points where the storage S exceeded S(0)(1 + :data:`TOLERANCE`) at some sample; that diverged; either.
    worst_growth : float
        Largest max S/S(0) − 1 over all points (inf: diverged).
    worst_point : dict
        The point with that growth.
    samples_min, samples_max, seed : int
        Shortest and longest run (samples) and the random seed.
    status : SoundnessStatus
        ``SOUND`` when ``violations`` is 0, else ``VIOLATED`` (derived).
    """

    criterion: str
    points: int
    by_kind: dict
    energy_grew: int
    diverged: int
    violations: int
    worst_growth: float
    worst_point: dict = field(default_factory=dict)
    samples_min: int = 0
    samples_max: int = 0
    seed: int = 0

    #: The function whose counts the record holds (named in the fix of a bad record).
    _SOURCE: ClassVar[str] = "the soundness function"

    def __post_init__(self) -> None:
        fix = f"pass the counts {self._SOURCE} returned"
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

    def to_dict(self) -> dict[str, object]:
        """JSON-ready record (an infinite growth becomes null, with the reason under ``null_reasons``).

        Returns
        -------
        dict
            Every field (in the order of ``_JSON_ORDER``, then any other), plus ``status`` and ``status_message``.
        """
        rank = {k: i for i, k in enumerate(_JSON_ORDER)}
        ordered = sorted(self.__dict__.items(), key=lambda kv: rank.get(kv[0], len(rank)))
        return to_jsonable({**dict(ordered), "status": self.status, "status_message": self.status.message})
