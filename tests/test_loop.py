"""dfa.Loop (dfa/model/loop.py): the device and the wall, with the groups of paper Table 1 formed once.

The Loop's groups are those of ``dimensionless_params`` and ``Wall.params`` exactly; the analyses give the same
result from a Loop as from their former first arguments (a device and a wall, or (μ, β, σ) and the wall's groups);
bad input names the parameter, the value, the rule and the fix.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

import dfa
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.simulation import simulate
from dfa.model.device import dimensionless_params
from dfa.model.loop import Loop, as_loop

DELTA = dfa.get_device("Delta").device
DAMPED = dfa.Wall.of(14500.0, damping=5.0, delay=1)


def test_table1_loop_groups_equal_dimensionless_params_and_wall_params():
    loop = Loop(DELTA, DAMPED)
    assert loop.params == dimensionless_params(DELTA, 14500.0)  # bit for bit: the same division
    assert loop.wall_params == DAMPED.params(DELTA.period, DELTA.resolution)
    assert loop.stiffness == 14500.0 and loop.device is DELTA and loop.wall is DAMPED


def test_table1_loop_dimensionless_equals_device_loop_groups():
    p, wp = Loop(DELTA, DAMPED).groups("test")
    dim = Loop.dimensionless(p.mu, p.beta, p.sigma, wp)
    assert dim.params == p and dim.wall_params == wp and dim.device is None and dim.wall is None
    assert Loop.dimensionless(2.0, 0.1, 0.3).wall_params == dfa.WallParams()  # the spring


def test_loop_at_forms_the_groups_at_each_stiffness():
    base = Loop(DELTA, dfa.Wall.of(1.0, damping=5.0))
    at = base.at(2000.0)
    assert at.params == DELTA.params(2000.0)
    assert at.wall_params == dfa.Wall.of(2000.0, damping=5.0).params(DELTA.period, DELTA.resolution)
    spring = Loop(DELTA)
    assert spring.params is None and spring.stiffness is None and spring.at(2000.0).wall == dfa.Wall(2000.0)


def test_loop_stiffness_alone_is_the_spring():
    assert Loop(DELTA, 14500.0).wall == dfa.Wall(14500.0)


def test_loop_to_dict_is_strict_json():
    d = Loop(DELTA, DAMPED).to_dict()
    assert d["params"] == dimensionless_params(DELTA, 14500.0).to_dict()
    assert d["device"]["name"] == "Delta" and d["wall"]["damping"] == 5.0
    json.dumps(d, allow_nan=False)
    assert Loop.dimensionless(2.0, 0.1, 0.3).to_dict()["device"] is None


def test_eq6_check_and_criterion_same_from_loop_and_former_arguments():
    old = dfa.passivity_check(DELTA, DAMPED, 0.1)
    new = dfa.passivity_check(Loop(DELTA, DAMPED), 0.1)
    assert new.to_dict() == old.to_dict()
    assert dfa.device_criterion(Loop(DELTA, 14500.0), 0.1) == dfa.device_criterion(DELTA, 14500.0, 0.1)


def test_eq4_simulate_same_from_loop_and_former_arguments():
    p, wp = Loop(DELTA, DAMPED).groups("test")
    old = simulate(p.mu, p.beta, p.sigma, 2.0, 20000, wall=wp)
    new = simulate(Loop(DELTA, DAMPED), 2.0, 20000)
    assert new.to_dict() == old.to_dict()
    np.testing.assert_array_equal(new.xi, old.xi)
    kw = simulate(mu=100.0, beta=0.3, sigma=1.5, xi_dot0=2.0, samples=5000)  # the former keywords
    assert kw.to_dict() == simulate(Loop.dimensionless(100.0, 0.3, 1.5), 2.0, 5000).to_dict()


def test_eq11_kmax_same_from_loop_and_former_arguments_delta_with_damper():
    wall = dfa.Wall.of(1000.0, damping=1.0)
    kw = dict(speeds=2, grid=8, max_samples=20000)
    old = design_answer(DELTA, 0.05, wall=wall, **kw)
    new = design_answer(Loop(DELTA, wall), 0.05, **kw)
    assert new.to_dict() == old.to_dict()
    assert design_answer(Loop(DELTA), 0.0).to_dict() == design_answer(DELTA, 0.0).to_dict()


@pytest.mark.parametrize(
    ("build", "error", "start"),
    [
        (lambda: Loop("Delta", 1000.0), dfa.DFATypeError, "device = 'Delta' has type str: it must be a dfa.Device"),
        (lambda: Loop(DELTA, "hard"), dfa.DFATypeError, "wall = 'hard' has type str"),
        (lambda: Loop(DELTA, -5.0), dfa.DFAValueError, "stiffness = -5.0 is invalid: it must be a finite number > 0"),
        (lambda: Loop(None), dfa.DFAValueError, "device = None is invalid without the groups"),
        (lambda: Loop(None, dfa.Wall(1.0)), dfa.DFAValueError, "wall = Wall(stiffness=1.0"),
        (lambda: Loop.dimensionless(-1.0, 0.1, 0.3), dfa.DFAValueError, "mu = -1.0 is invalid"),
        (lambda: Loop.dimensionless(1.0, 0.1, 0.3, 5), dfa.DFATypeError, "wall_params = 5 has type int"),
        (
            lambda: Loop(DELTA, params=dfa.Params(1, 0, 0)),
            dfa.DFAValueError,
            "params = Params(mu=1.0, beta=0.0, sigma=0.0) is invalid with a device",
        ),
        (lambda: Loop.dimensionless(1.0, 0.1, 0.3).at(100.0), dfa.DFAValueError, "stiffness = 100.0 cannot be set"),
        (lambda: as_loop(Loop(DELTA), dfa.Wall(1.0)), dfa.DFAValueError, "wall = Wall(stiffness=1.0"),
        (lambda: dfa.passivity_check(Loop(DELTA), 0.1), dfa.DFAValueError, "loop = Loop('Delta') has no stiffness"),
        (lambda: simulate(Loop(DELTA), 1.0), dfa.DFAValueError, "loop = Loop('Delta') has no stiffness"),
        (
            lambda: design_answer(Loop.dimensionless(1.0, 0.1, 0.3), 0.1),
            dfa.DFAValueError,
            "loop = a dimensionless loop is invalid for design_answer",
        ),
    ],
)
def test_loop_bad_input_names_parameter_value_rule_and_fix(build, error, start):
    with pytest.raises(error) as info:
        build()
    msg = str(info.value)
    assert msg.startswith(start), msg
    assert ";" in msg  # the fix follows the rule


def test_loop_is_frozen():
    loop = Loop(DELTA, DAMPED)
    with pytest.raises(AttributeError):
        loop.device = None  # type: ignore[misc]
