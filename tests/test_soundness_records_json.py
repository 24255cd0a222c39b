"""The soundness record (dfa.studies.soundness.CriterionSoundness, one for both populations: the spring with a
delay and random walls) declares its count fields once (dfa.studies.soundness_counts.SoundnessCounts); its JSON is
byte-identical to the two records declared field by field before (the declarations of commit 9829bef, kept below as
the reference and fed the same small runs)."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import pytest

from dfa.errors import DFAValueError
from dfa.jsonable import dumps, to_jsonable
from dfa.results.status import SoundnessStatus
from dfa.studies.soundness import CriterionSoundness, Population, criterion_soundness


class _OldCounts:
    """The mixin of commit 9829bef: ``as_dict`` from the instance's ``__dict__`` (field declaration order)."""

    @property
    def status(self) -> SoundnessStatus:
        return SoundnessStatus.SOUND if getattr(self, "violations") == 0 else SoundnessStatus.VIOLATED  # noqa: B009

    def to_dict(self) -> dict[str, object]:
        return to_jsonable({**self.__dict__, "status": self.status, "status_message": self.status.message})


@dataclass(frozen=True)
class _OldDelaySoundness(_OldCounts):
    delay: int
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


@dataclass(frozen=True)
class _OldControllerSoundness(_OldCounts):
    criterion: str
    points: int
    by_kind: dict
    by_case: dict
    energy_grew: int
    diverged: int
    violations: int
    worst_growth: float
    worst_point: dict = field(default_factory=dict)
    samples_min: int = 0
    samples_max: int = 0
    seed: int = 0


def _as_old(record):
    old_cls = _OldControllerSoundness if record.delay is None else _OldDelaySoundness
    return old_cls(**{f.name: getattr(record, f.name) for f in dataclasses.fields(old_cls)})


@pytest.fixture(scope="module")
def runs():
    return [
        criterion_soundness(24, Population(delay=1), seed=5),
        criterion_soundness(12, Population(delay=2), criterion="d-ignoring", seed=7),
        criterion_soundness(8, Population(), seed=3),
        criterion_soundness(8, Population(), criterion="damper-ignoring", seed=4),
    ]


def test_soundness_records_json_byte_identical_to_the_field_by_field_declarations(runs):
    olds = [_as_old(r) for r in runs]
    for new, old in zip(runs, olds, strict=True):
        assert list(new.to_dict()) == list(old.to_dict())  # same keys, same order
        assert dumps(new) == dumps(old) and dumps(new, indent=1) == dumps(old, indent=1)
        assert new.status == old.status
    # the files `python -m dfa.cli.soundness_report` writes: a list of records, indented
    assert dumps(runs[:2], indent=1) == dumps(olds[:2], indent=1)
    assert dumps(runs[2:], indent=1) == dumps(olds[2:], indent=1)


def test_soundness_records_declare_the_counts_once():
    from dfa.studies.soundness_counts import SoundnessCounts

    shared = {f.name for f in dataclasses.fields(SoundnessCounts)}
    assert {"points", "energy_grew", "diverged", "violations", "worst_growth", "seed"} <= shared
    own = {k for k, v in CriterionSoundness.__dict__.get("__annotations__", {}).items() if "ClassVar" not in str(v)}
    assert not own & shared, own & shared  # nothing declared twice
    assert own == {"delay", "by_case"}  # the fields of one population each


def test_soundness_records_still_validated_on_construction(runs):
    with pytest.raises(DFAValueError, match="violations = 30 is invalid: it cannot exceed points = 24"):
        dataclasses.replace(runs[0], violations=30)
    with pytest.raises(DFAValueError, match="^diverged = -1 is invalid"):
        dataclasses.replace(runs[2], diverged=-1)
    with pytest.raises(DFAValueError, match="pass the counts criterion_soundness returned"):
        dataclasses.replace(runs[2], points=-1)
