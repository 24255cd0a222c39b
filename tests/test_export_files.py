"""A wall to deploy round-trips through its YAML and its JSON exactly (issue 44, ``dfa export --format yaml|json``).

``DeployableWall.from_dict(yaml.safe_load(yaml_text(dep)))`` and ``from_dict(json.loads(json_text(dep)))`` equal
``dep`` field by field, every number exactly (both dumps write a double's shortest round-trip text: no tolerance),
for random devices (rotary, held by a hand, with a force limit and a travel) and walls of every element. The YAML
holds no null (a ROS parameter cannot be null) and its dimensionless parameters are the firmware's groups.
"""

from __future__ import annotations

import json

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st

import dfa
from dfa.errors import DFAValueError
from dfa.model.device import Device
from dfa.model.elements import (
    AmplifierLag,
    Damper,
    Delay,
    ForceLimit,
    HandSpring,
    OneSided,
    PassivityController,
    Push,
    Travel,
    VelocityFilter,
)
from dfa.model.hand import Hand
from dfa.model.loop import Loop
from dfa.model.wall import Wall
from dfa.render.export import export, json_text, yaml_text
from dfa.results.deploy import DeployableWall
from dfa.results.require import Recommendation
from dfa.results.status import DeployRule, RecommendRule

POS = st.floats(1e-3, 1e3, allow_subnormal=False)


@st.composite
def devices(draw: st.DrawFn) -> Device:
    dev = Device(
        draw(st.floats(0.005, 0.5)), draw(st.one_of(st.just(0.0), st.floats(1e-4, 5.0))), draw(st.one_of(st.just(0.0), st.floats(1e-4, 1.0))),
        draw(st.floats(1e-6, 1e-3)), draw(st.floats(2.5e-4, 2e-3)), name=draw(st.sampled_from(["Delta", "my arm"])),
        rotary=draw(st.booleans()), max_force=draw(st.one_of(st.none(), st.floats(0.5, 50.0))),
        travel=draw(st.one_of(st.none(), st.floats(0.01, 0.5))),
    )  # fmt: skip
    if draw(st.booleans()):
        dev = dev.holding(
            Hand(
                draw(st.floats(0.0, 0.5)), draw(st.one_of(st.just(0.0), st.floats(1e-4, 5.0))), name="a hand", source=""
            )
        )
    return dev


@st.composite
def walls(draw: st.DrawFn, period: float) -> Wall:
    els: list = []
    for kind, value in (
        (Delay, st.integers(1, 3)), (Damper, st.floats(0.01, 5.0)), (VelocityFilter, st.floats(0.002 / period, 0.45 / period)),
        (OneSided, st.floats(-2.0, 2.0)), (ForceLimit, st.floats(0.1, 10.0)), (Travel, st.floats(0.01, 0.2)),
    ):  # fmt: skip
        if draw(st.booleans()):
            els.append(kind(draw(value)))
    if draw(st.booleans()):
        els.append(PassivityController(draw(st.one_of(st.none(), st.floats(period, 0.1))),
                                       draw(st.one_of(st.none(), st.floats(0.01, 3.0)))))  # fmt: skip
    extra = draw(st.sampled_from(["none", "lag", "hand"]))
    if extra == "lag":
        els.append(AmplifierLag(draw(st.floats(100.0, 5000.0))))
    elif extra == "hand":
        els.append(HandSpring(draw(st.floats(1.0, 100.0))))
    if any(isinstance(e, OneSided) for e in els) and draw(st.booleans()):
        els.append(Push(draw(st.floats(0.01, 1.0))))
    return Wall(draw(st.floats(10.0, 5000.0)), tuple(els))


@st.composite
def deployables(draw: st.DrawFn) -> DeployableWall:
    dev = draw(devices())
    wall = draw(walls(dev.period))
    rule = draw(st.sampled_from(list(DeployRule)))
    if rule is DeployRule.GIVEN:
        return DeployableWall(dev, wall, command=draw(st.one_of(st.none(), st.just("dfa export --stiffness 'x y'"))))
    margin = None if rule is DeployRule.PROVEN else draw(st.floats(1.0, 10.0))
    return DeployableWall(dev, wall, draw(st.floats(0.001, 1.0)), rule, margin, draw(POS), "dfa export")


def same(a: DeployableWall, b: DeployableWall) -> None:
    """Field by field, exactly (the hand too: Device's equality leaves it out)."""
    assert a == b
    assert a.device.hand == b.device.hand
    assert a.device.to_dict() == b.device.to_dict() and a.wall.elements == b.wall.elements


@settings(max_examples=40)
@given(dep=deployables())
def test_export_yaml_round_trips_exactly(dep):
    text = yaml_text(dep)
    data = yaml.safe_load(text)
    same(DeployableWall.from_dict(data), dep)
    params = data["dfa_wall"]["ros__parameters"]

    def walk(x):
        if isinstance(x, dict):
            return all(walk(v) for v in x.values())
        if isinstance(x, list):
            return all(walk(v) for v in x)
        return x is not None and x != ""

    assert walk(params), "a ROS parameter cannot be null or empty"
    assert params["force_step"] == dep.stiffness * dep.device.resolution
    firmware = dep.firmware_params
    assert params["dimensionless"]["damping"] == firmware.damping
    assert params["delay"] == firmware.delay
    if firmware.group(ForceLimit) is not None:
        assert params["dimensionless"]["force_limit"] == firmware.group(ForceLimit)


@settings(max_examples=40)
@given(dep=deployables())
def test_export_json_round_trips_exactly(dep):
    data = json.loads(json_text(dep))
    same(DeployableWall.from_dict(data), dep)
    assert data["rule"] == dep.rule.value and data["force_step"] == dep.force_step


def test_export_not_exported_names_lag_hand_push_and_the_device_travel():
    dev = Device(0.032, 0.02, 0.024, 314e-6, 2e-3, travel=0.05)
    dep = DeployableWall.given(Loop(dev, Wall(100.0, (OneSided(0.0), Push(0.1), HandSpring(10.0)))))
    assert dep.not_exported == ["hand_spring", "push", "travel"]
    assert yaml.safe_load(yaml_text(dep))["dfa_wall"]["ros__parameters"]["not_exported"] == dep.not_exported


def _recommendation(status: RecommendRule, k: float | None) -> Recommendation:
    dev = Device(0.032, 0.02, 0.024, 314e-6, 2e-3, name="Impulse Engine")
    basis = None if k is None else ("k_criterion" if status is RecommendRule.PROVEN else "k_sim")
    kb = None if k is None else (k if status is RecommendRule.PROVEN else 2.0 * k)
    return Recommendation(dev, Wall.of(1.0, damping=0.3), 0.05, k, basis, kb, 2.0, status)


def test_export_from_recommendation_takes_its_k_rule_and_margin():
    sim = DeployableWall.from_recommendation(_recommendation(RecommendRule.SIMULATED, 400.0), "dfa export x")
    assert (sim.stiffness, sim.rule, sim.margin, sim.k_basis, sim.velocity) == (
        400.0,
        DeployRule.SIMULATED,
        2.0,
        800.0,
        0.05,
    )
    assert sim.wall.damping == 0.3 and sim.command == "dfa export x"
    proven = DeployableWall.from_recommendation(_recommendation(RecommendRule.PROVEN, 300.0))
    assert (proven.rule, proven.margin, proven.k_basis) == (DeployRule.PROVEN, None, 300.0)
    text = export(_recommendation(RecommendRule.PROVEN, 300.0))
    assert "0.05 m/s by the rule 'proven'" in text


@pytest.mark.parametrize("status", [RecommendRule.NONE, RecommendRule.NOT_SIMULATED])
def test_export_refuses_a_recommendation_without_k(status):
    with pytest.raises(DFAValueError, match=f"recommendation rule = '{status.value}' is invalid for an export"):
        DeployableWall.from_recommendation(_recommendation(status, None))


def test_export_api_takes_a_loop_a_recommendation_or_a_deployable_wall():
    assert "export" in dfa.__all__ and "DeployableWall" in dfa.__all__
    loop = Loop(Device(0.032, 0.02, 0.024, 314e-6, 2e-3), Wall.of(100.0))
    dep = DeployableWall.given(loop, "cmd")
    assert dfa.export(loop, "json", command="cmd") == dfa.export(dep, "json")
    with pytest.raises(dfa.DFATypeError, match="source of type float is invalid"):
        dfa.export(100.0)
    with pytest.raises(DFAValueError, match="format = 'h' is invalid"):
        dfa.export(loop, "h")
    with pytest.raises(DFAValueError, match="has no stiffness"):
        DeployableWall.given(Loop(loop.device))


def test_export_deployable_wall_validates_its_rule_fields():
    dev, wall = Device(0.032, 0.02, 0.024, 314e-6, 2e-3), Wall.of(100.0)
    with pytest.raises(DFAValueError, match="velocity = 0.1 is invalid under the rule 'given'"):
        DeployableWall(dev, wall, velocity=0.1)
    with pytest.raises(DFAValueError, match="k_basis = None is invalid under the rule 'simulated'"):
        DeployableWall(dev, wall, 0.1, "simulated", 2.0, None)
    with pytest.raises(DFAValueError, match="margin = 0.5 is invalid"):
        DeployableWall(dev, wall, 0.1, "simulated", 0.5, 200.0)
