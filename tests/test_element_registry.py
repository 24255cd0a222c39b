"""The element registry (dfa.model.elements.ELEMENTS): every element declares its coverage, its command-line
rows and its JSON, and the wall, its groups and the map files read them back through the registry."""

from __future__ import annotations

import argparse

import numpy as np
import pytest

from dfa.analysis.maps import _wall_from
from dfa.cli.app import build_parser
from dfa.cli.walls import FLAG_ROWS
from dfa.model.elements import (
    ELEMENTS,
    Coverage,
    Covered,
    Damper,
    Delay,
    Element,
    ForceLimit,
    HandSpring,
    OneSided,
    PassivityController,
    Push,
    Travel,
    VelocityFilter,
)
from dfa.model.wall import Wall, WallParams

#: One element of each registered class, as a wall holds it (physical units; 1 kHz, K = 1000 N/m, Δ = 1e-5 m).
SAMPLES: dict[type[Element[object]], Element[object]] = {
    k: e
    for e in (
        Delay(2), Damper(1.5), VelocityFilter(100.0), HandSpring(80.0), OneSided(0.25), Push(0.4),
        PassivityController(window=0.05, force_limit=2.0), ForceLimit(3.0), Travel(0.05),
    )
    for k in (type(e),)
}  # fmt: skip
from dfa.model.elements import AmplifierLag  # noqa: E402

SAMPLES[AmplifierLag] = AmplifierLag(300.0)


def test_registry_lists_every_element_once_with_a_unique_key() -> None:
    keys = [k.key() for k in ELEMENTS]
    assert len(set(keys)) == len(keys) == len(ELEMENTS) and set(SAMPLES) == set(ELEMENTS)


@pytest.mark.parametrize("kind", ELEMENTS, ids=lambda k: k.key())
def test_element_declares_its_coverage_with_a_reason_for_each_missing_part(kind: type[Element[object]]) -> None:
    g = (
        SAMPLES[kind].group(1e-3, 1000.0, resolution=1e-5)
        if kind.needs_resolution
        else SAMPLES[kind].group(1e-3, 1000.0)
    )  # type: ignore[call-arg]
    cov = kind.coverage(g)
    assert isinstance(cov, Covered) and cov.covers(Coverage.SIMULATION)  # the exact simulation runs every element
    missing = [f for f in Coverage if f not in cov.flags and f is not Coverage.ALL and f.name]
    assert sorted(f.name for f, _ in cov.reasons) == sorted(f.name for f in missing)
    assert all(isinstance(why, str) and why for _, why in cov.reasons)


def test_neutral_group_covers_everything() -> None:
    assert Damper.coverage(0.0).flags == Coverage.ALL and Delay.coverage(0).flags == Coverage.ALL


def test_wall_coverage_is_what_all_its_elements_cover_with_the_first_reason() -> None:
    p = WallParams(((PassivityController, (0, None)), (OneSided, 0.0)))
    cov = p.coverage()
    assert cov.flags == Coverage.SIMULATION
    assert cov.reason(Coverage.LINEAR) == OneSided.linear_reason  # the first element's (OneSided comes first)
    assert cov.reason(Coverage.CRITERION) == p.not_covered()
    assert WallParams.of(delay=3).covers(Coverage.ALL) and WallParams.of(delay=3).is_spring
    assert not WallParams.of(damping=0.2).covers(Coverage.CLOSED_FORM)


@pytest.mark.parametrize("kind", ELEMENTS, ids=lambda k: k.key())
def test_element_flag_rows_are_options_of_dfa_check(kind: type[Element[object]]) -> None:
    rows = kind.flag_rows()
    assert rows and all(FLAG_ROWS[r.flag] == r for r in rows)
    sub = next(a for a in build_parser("check")._actions if isinstance(a, argparse._SubParsersAction))
    options = {s for a in sub.choices["check"]._actions for s in a.option_strings}
    for row in rows:
        assert row.flag in options and row.help


@pytest.mark.parametrize("kind", ELEMENTS, ids=lambda k: k.key())
def test_element_json_round_trip(kind: type[Element[object]]) -> None:
    e = SAMPLES[kind]
    assert Element.from_dict(e.to_dict()) == e


WALLS = [
    Wall.of(1000.0, damping=2.0, delay=1, filter_cutoff=100.0, amplifier_bandwidth=300.0),
    Wall(1000.0, (OneSided(0.25), Push(0.3), HandSpring(50.0))),
    Wall(1000.0, (OneSided(0.0),)),
    Wall(1000.0, (PassivityController(), Damper(1.0), Delay(1))),
    Wall(1000.0, (PassivityController(0.05, 2.0), HandSpring(100.0))),
    Wall(1000.0, (ForceLimit(3.0), Damper(1.0))),
    Wall(1000.0, (OneSided(0.0), Push(0.5), Travel(0.1))),
    Wall(1000.0),
]


@pytest.mark.parametrize("wall", WALLS, ids=range(len(WALLS)))
def test_wall_and_groups_json_round_trip(wall: Wall) -> None:
    assert Wall.from_dict(wall.to_dict()) == wall
    p = wall.params(1e-3, 1e-5)
    assert WallParams.from_dict(p.to_dict()) == p


class _Npz(dict):  # the part of np.lib.npyio.NpzFile that _wall_from reads
    @property
    def files(self) -> list[str]:
        return list(self)


def test_map_file_written_before_wall_json_still_loads() -> None:
    # the arrays of the earlier format: [β_B, ν_c (NaN), α], hand [κ_h], one_sided [s, p], passivity_controller [W, f_max]
    old = _Npz(
        wall=np.array([0.0, np.nan, 0.0]), hand=np.array([0.1]), one_sided=np.array([0.25, 3.0]),
        passivity_controller=np.array([50.0, np.inf]),
    )  # fmt: skip
    want = WallParams(
        (
            (OneSided, 0.25),
            (Push, 3.0),
            (PassivityController, (50, None)),
            *WallParams.of(delay=1, hand_stiffness=0.1).groups,
        )
    )
    assert _wall_from(old, 1) == want  # type: ignore[arg-type]
    assert _wall_from(_Npz(), 2) == WallParams.of(delay=2)  # type: ignore[arg-type]
