"""Issue 42, "the element as the unit of change": a new element reaches every place through its declared hooks.

1. A toy element defined here, ``Stroke`` (an end stop at ±stroke, m; its block is the travel's, code 10, so it
   needs no new kernel code), registered by adding it to ``ELEMENTS`` (monkeypatched here: a real element adds
   itself to that one tuple in ``dfa/model/elements.py``), gets: its flag row and a parser that reads it, its
   wall's JSON and groups' JSON with a round trip, its coverage (what covers it and why not, from its hooks), its
   default from a device field (``device_field``, read by ``Loop`` and the command line through
   ``dfa.model.loop.device_elements``), its block in the kernel table, and runs that end with the outcome its block
   gives (``end_stop``), judged by the limits from the outcome's own declaration.
2. The outcomes: each simulated limit, the Z-width's point rule and the grip sweep read ``SimulationOutcome.fails``;
   the compiled kernel's outcome codes (``dfa.core.kernel.REST`` ...) are the enum's order, one constant per member;
   every outcome has a colour and a label in the figures (a default where no designer gave one).
3. The device fields: ``CatalogueEntry`` has one field per device field (``_device_columns`` adds any it does not
   declare); the elements' kernel codes agree with ``dfa.core.table.BLOCKS``.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import pytest

import dfa.model.elements as elements_module
import dfa.model.wall as wall_module
from dfa.analysis.limits import grip, runs, zwidth
from dfa.analysis.simulation import simulate
from dfa.cli.flag_table import add_rows
from dfa.core import kernel, table
from dfa.model import catalogue
from dfa.model.device import DEVICE_FIELDS, Device, DeviceField, Rule
from dfa.model.elements import ELEMENTS, Coverage, Element, KernelBlock, Parameter, Travel
from dfa.model.loop import Loop, device_elements
from dfa.model.wall import Wall, WallParams
from dfa.results.status import Fails, SimulationOutcome

RESOLUTION, PERIOD = 2e-5, 1e-3  # m, s


@dataclass(frozen=True)
class Stroke(Element[float]):
    """A toy end stop at ±stroke from the centre (m; rotary rad), group ξ_s = stroke/Δ (ticks); test only.

    Declared through the hooks alone: its block is the travel's (the run ends past ±ξ_s, outcome end_stop), its
    value a device's ``stroke`` by default, its flag a row of the wall's flag table.
    """

    stroke: float
    kernel_code: ClassVar[int] = table.TRAVEL
    parameter: ClassVar[Parameter] = Parameter(
        "stroke", ("m", "rad"), "--stroke", "M", "a toy end stop at ±stroke in m (default: none)", "stroke",
        "ξ_s = stroke/Δ (ticks)",
    )  # fmt: skip
    absent: ClassVar[object] = None
    needs_resolution: ClassVar[bool] = True
    device_field: ClassVar[str | None] = "stroke"

    def group(self, period: float, stiffness: float, resolution: float | None = None) -> float:
        assert resolution is not None
        return self.check_group(self.stroke / resolution)

    @classmethod
    def check_group(cls, value: object) -> float:
        return Travel.check_group(value)

    @classmethod
    def kernel_block(cls, g: float) -> KernelBlock:
        return KernelBlock(cls.kernel_code, (float(g),), 0)


@dataclass(frozen=True)
class StrokeDevice(Device):
    """A device with the toy's field (a real device field is a row of DEVICE_FIELDS and an attribute of Device)."""

    stroke: float | None = field(default=None, kw_only=True)


@pytest.fixture
def registered(monkeypatch: pytest.MonkeyPatch) -> None:
    """``Stroke`` in the registry, where a real element adds itself (``ELEMENTS`` of dfa/model/elements.py)."""
    for module in (elements_module, wall_module):
        monkeypatch.setattr(module, "ELEMENTS", (*ELEMENTS, Stroke))


def test_toy_element_gets_its_flag_row_and_parser(registered: None) -> None:
    (row,) = Stroke.flag_rows()
    assert (row.flag, row.dest, row.metavar, row.unit) == ("--stroke", "stroke", "M", "m (rotary: rad)")
    p = argparse.ArgumentParser()
    add_rows(p, Stroke)
    assert p.parse_args(["--stroke", "0.01"]).stroke == 0.01 and p.parse_args([]).stroke is None


def test_toy_element_json_round_trips_through_its_record(registered: None) -> None:
    w = Wall(1000.0, (Stroke(0.01),))
    d = json.loads(json.dumps(w.to_dict()))
    assert d["stroke"] == 0.01 and Wall.from_dict(d) == w  # the record's keys from Element.record_keys
    assert Element.from_dict(Stroke(0.01).to_dict()) == Stroke(0.01)
    g = w.params(PERIOD, RESOLUTION)
    assert g.group(Stroke) == pytest.approx(500.0, rel=1e-15) and g.to_dict()["stroke"] == g.group(Stroke)
    assert WallParams.from_dict(json.loads(json.dumps(g.to_dict()))) == g
    # the spring's record keeps its shape: the toy's key only with the toy
    assert "stroke" not in Wall(1000.0).to_dict() and "stroke" not in WallParams().to_dict()


def test_toy_element_coverage_comes_from_its_hooks(registered: None) -> None:
    cov = WallParams(((Stroke, 500.0),)).coverage()
    assert cov.covers(Coverage.CRITERION | Coverage.LINEAR | Coverage.SIMULATION)
    assert not cov.covers(Coverage.CLOSED_FORM) and "stroke" in (cov.reason(Coverage.CLOSED_FORM) or "")


def test_toy_element_takes_its_default_from_the_device_field(registered: None) -> None:
    dev = StrokeDevice(0.072, 0.005, 0.038, RESOLUTION, PERIOD, stroke=0.01)
    assert device_elements(dev, in_wall=True) == (Stroke(0.01),) and device_elements(dev, in_wall=False) == ()
    loop = Loop(dev, Wall(1000.0))
    assert loop.wall is not None and loop.wall.element(Stroke) == Stroke(0.01)  # the Loop adds it
    assert loop.wall_params is not None and loop.wall_params.group(Stroke) == pytest.approx(500.0, rel=1e-15)
    own = Loop(dev, Wall(1000.0, (Stroke(0.02),)))
    assert own.wall is not None and own.wall.element(Stroke) == Stroke(0.02)  # a wall's own value wins
    plain = StrokeDevice(0.072, 0.005, 0.038, RESOLUTION, PERIOD)
    assert Loop(plain, Wall(1000.0)).wall == Wall(1000.0)  # no value: no element


def test_toy_element_runs_end_with_its_blocks_outcome_judged_by_the_declaration(registered: None) -> None:
    """μ = 2, β = σ = 0 diverges (eq. 11 fails); the toy's block (the travel's) ends the run past ±40 ticks."""
    w = WallParams(((Stroke, 40.0),))
    t = w.kernel_table()
    assert t.tolist() == [1.0, float(table.TRAVEL), 1.0, 0.0, 40.0]
    r = simulate(Loop.dimensionless(2.0, 0.0, 0.0, w), 3.0, samples=2000)
    assert r.outcome is SimulationOutcome.END_STOP and 40.0 < abs(r.final_xi)
    assert runs.judge_outcomes({r.outcome.value}, "unstable") == runs.UNSAFE
    assert runs.judge_outcomes({r.outcome.value}, "rest") == runs.UNSAFE


def test_limits_zwidth_and_grip_read_the_outcomes_declaration() -> None:
    for o in SimulationOutcome:
        assert (o.value in runs.FAILING["unstable"]) == (Fails.NO_DIVERGENCE in o.fails)
        assert (o.value in runs.FAILING["rest"]) == (Fails.REST in o.fails)
        assert (o.code in zwidth._DIVERGES) == (Fails.NO_DIVERGENCE in o.fails)
        assert (o.value in grip._NOT_FIRM) == (Fails.NO_DIVERGENCE in o.fails or o is SimulationOutcome.UNDECIDED)
        rows = np.array([[kernel.REST, o.code]], dtype=np.int64)  # one run of the outcome beside a rest
        assert (zwidth._point_codes(rows)[0] == zwidth.DIVERGES) == (Fails.NO_DIVERGENCE in o.fails)
    # the paper's outcomes as they were (FAILING before the declaration)
    assert runs.FAILING["unstable"] == {"unstable", "saturated", "end_stop"}
    assert runs.FAILING["rest"] == {"oscillating", "unstable", "chatter", "saturated", "end_stop"}


def test_kernel_outcome_codes_are_the_enums_order() -> None:
    """One constant of dfa.core.kernel per outcome, named as the member, valued its place in the enum."""
    for i, o in enumerate(SimulationOutcome):
        assert o.code == i and getattr(kernel, o.name) == i, o


def test_every_outcome_has_a_colour_and_a_label() -> None:
    from dfa.render.figures.style import OUTCOME_COLORS, OUTCOME_LABELS, outcome_cmap

    for o in SimulationOutcome:
        assert o.value in OUTCOME_COLORS and o.value in OUTCOME_LABELS
    assert outcome_cmap().N == len(SimulationOutcome)


def test_elements_kernel_codes_are_the_tables_blocks() -> None:
    assert {k.kernel_code: k.__name__ for k in ELEMENTS} == {c: name for c, (name, _m) in table.BLOCKS.items()}
    assert table.CODES == {c: name for c, (name, _m) in table.BLOCKS.items()}
    assert table.BLOCK_PARAMS == {c: m for c, (_name, m) in table.BLOCKS.items()}


def test_device_field_elements_name_real_device_fields() -> None:
    names = {f.name for f in DEVICE_FIELDS}
    for k in ELEMENTS:
        if k.device_field is not None:
            assert k.device_field in names and k.device_field in {f.name for f in dataclasses.fields(Device)}
            assert k.parameter.name == k.device_field  # the constructor takes the device's value by that name


def test_catalogue_entry_has_a_field_per_device_field(monkeypatch: pytest.MonkeyPatch) -> None:
    fields = {f.name: f for f in dataclasses.fields(catalogue.CatalogueEntry)}
    for f in DEVICE_FIELDS:
        assert f.name in fields and fields[f.name].default is None, f.name
        assert fields[f.name].type in ("float | None", float | None)
    # a new optional device field becomes a column without an edit of the class
    extra = DeviceField("stroke", "toy end stop", "x_s", "m", "rad", Rule.POSITIVE, required=False, absent="none")
    monkeypatch.setattr(catalogue, "DEVICE_FIELDS", (*DEVICE_FIELDS, extra))

    @dataclass(frozen=True)
    @catalogue._device_columns
    class Row:
        name: str
        mass: float | None = None

    assert Row("x", stroke=0.01).stroke == 0.01 and Row("x").stroke is None  # type: ignore[attr-defined,call-arg]
    assert {f.name for f in dataclasses.fields(Row)} == {"name", *(f.name for f in (*DEVICE_FIELDS, extra))}


def test_every_element_declares_whether_the_firmware_runs_it() -> None:
    """``dfa export`` reads each element's own ``firmware`` declaration (True, or whose it is): none is inherited, so
    a new element the export does not know is refused, never dropped silently."""
    from dfa.results.deploy import FIRMWARE, OUTSIDE

    for kind in ELEMENTS:
        assert "firmware" in vars(kind), kind.__name__
        assert kind.firmware is True or (isinstance(kind.firmware, str) and kind.firmware)
    assert set(FIRMWARE) | set(OUTSIDE) == set(ELEMENTS) and not set(FIRMWARE) & set(OUTSIDE)
    with pytest.raises(AttributeError):
        Stroke.firmware  # the toy declares none: the export refuses a wall with it  # noqa: B018
