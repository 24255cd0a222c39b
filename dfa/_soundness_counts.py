"""What every soundness count shares: its checks, its status and its JSON (one implementation).

Mixed into the frozen result records :class:`dfa.soundness.DelaySoundness` and
:class:`dfa.controller_soundness.ControllerSoundness`, whose fields include ``points``,
``energy_grew``, ``diverged`` and ``violations``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .checks import check_int
from .errors import DFAValueError
from .jsonable import to_jsonable
from .status import SoundnessStatus

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


class SoundnessCounts:
    """Validation, ``status`` and ``as_dict`` of a count of simulated points called passive."""

    #: The function whose counts the record holds (named in the fix of a bad record).
    _SOURCE = "the soundness function"

    def __post_init__(self) -> None:
        fix = f"pass the counts {self._SOURCE} returned"
        for name in ("points", "energy_grew", "diverged", "violations"):
            check_int(name, getattr(self, name), 0, fix)
        points, violations = getattr(self, "points"), getattr(self, "violations")  # noqa: B009 - fields of the subclass
        if violations > points:
            raise DFAValueError(f"violations = {violations} is invalid: it cannot exceed points = {points}; {fix}")

    @property
    def status(self) -> SoundnessStatus:
        """``SOUND`` when no simulated point violated the criterion, else ``VIOLATED``."""
        return SoundnessStatus.SOUND if getattr(self, "violations") == 0 else SoundnessStatus.VIOLATED  # noqa: B009

    def as_dict(self) -> dict[str, object]:
        """JSON-ready record (an infinite growth becomes null, with the reason under ``null_reasons``).

        Returns
        -------
        dict
            Every field, plus ``status`` and ``status_message``.
        """
        return to_jsonable({**self.__dict__, "status": self.status, "status_message": self.status.message})
