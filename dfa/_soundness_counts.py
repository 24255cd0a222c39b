"""What every soundness count shares: its checks, its status and its JSON (one implementation).

Mixed into the frozen result records :class:`dfa.soundness.DelaySoundness` and
:class:`dfa.controller_soundness.ControllerSoundness`, whose fields include ``points``,
``energy_grew``, ``diverged`` and ``violations``.
"""

from __future__ import annotations

from .checks import check_int
from .errors import DFAValueError
from .jsonable import to_jsonable
from .status import SoundnessStatus


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
