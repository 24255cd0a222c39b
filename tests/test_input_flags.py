"""Input checks found by the red team (issue 15): flags must be True or False (never ``bool(x)``: the text "False"
would count as True), a virtual damping B must be a number (not True/False) and its errors name the parameter the
caller typed; the ZWidth status is an enum with a message, validated on construction."""

import dataclasses
import json

import pytest

from dfa import checks
from dfa.analysis import contours, criterion, maps, simulation
from dfa.analysis.limits import zwidth
from dfa.analysis.linear_wall import stable_region
from dfa.errors import DFATypeError, DFAValueError
from dfa.model.catalogue import get_device
from dfa.results.status import ZWidthStatus

DEV = get_device("Impulse Engine").device

FLAG_CALLS = {
    "stability_map quantize": ("quantize", lambda v: maps.stability_map(5.0, [1.0], grid=2, samples=10, quantize=v, n_jobs=1, progress=False)),
    "stability_map preload": ("preload", lambda v: maps.stability_map(5.0, [1.0], grid=2, samples=10, preload=v, n_jobs=1, progress=False)),
    "stability_map progress": ("progress", lambda v: maps.stability_map(5.0, [1.0], grid=2, samples=10, n_jobs=1, progress=v)),
    "simulate record": ("record", lambda v: simulation.simulate(5.0, 0.1, 0.6, 1.0, 10, record=v)),
    "simulate energy": ("energy", lambda v: simulation.simulate(5.0, 0.1, 0.6, 1.0, 10, energy=v)),
    "simulate progress": ("progress", lambda v: simulation.simulate(5.0, 0.1, 0.6, 1.0, 10, progress=v)),
    "default_samples quantize": ("quantize", lambda v: simulation.default_samples(5.0, 0.1, 0.6, 1.0, quantize=v)),
    "default_samples cap": ("cap", lambda v: simulation.default_samples(5.0, 0.1, 0.6, 1.0, cap=v)),
    "stored_energy quantize": ("quantize", lambda v: simulation.stored_energy(0.3, 0.1, 5.0, quantize=v)),
    "spring_energy quantize": ("quantize", lambda v: criterion.spring_energy(0.3, quantize=v)),
    "equivalent_speed quantized": ("quantized", lambda v: criterion.equivalent_speed(1.0, quantized=v)),
    "CriticalLine.of quantized": ("quantized", lambda v: criterion.CriticalLine.of(1.0, quantized=v)),
    "contour_maps progress": ("progress", lambda v: contours.contour_maps(5.0, grid=2, progress=v)),
    "z_width progress": ("progress", lambda v: zwidth.z_width(DEV, 0.1, grid=2, speeds=1, n_jobs=1, progress=v)),
}  # fmt: skip


@pytest.mark.parametrize("case", list(FLAG_CALLS))
@pytest.mark.parametrize("bad", ["False", 0, None, [True]])
def test_flags_refuse_non_bool_naming_the_parameter(case, bad):
    name, call = FLAG_CALLS[case]
    with pytest.raises(DFATypeError, match=rf"^{name} = .* it must be True or False"):
        call(bad)


@pytest.mark.parametrize("case", ["stability_map quantize", "stability_map preload", "spring_energy quantize"])
def test_flags_accept_numpy_bools(case):
    import numpy as np

    _name, call = FLAG_CALLS[case]
    call(np.bool_(False))


def test_check_bool_is_the_one_rule():
    assert checks.check_bool("x", True) is True and checks.check_bool("x", False) is False
    with pytest.raises(DFATypeError, match=r"^x = 'no' has type str: it must be True or False; fix it$"):
        checks.check_bool("x", "no", "fix it")


@pytest.mark.parametrize("bad", [True, [0.0, True], (1.0, False)])
def test_stable_region_refuses_bool_virtual_damping(bad):
    with pytest.raises(DFATypeError, match=r"^virtual_damping = "):
        stable_region(1.0, 2.0, 1e-3, bad)


def test_stable_region_negative_B_names_virtual_damping():
    with pytest.raises(DFAValueError, match=r"^virtual_damping = -1.0 is invalid: it must be a finite number >= 0"):
        stable_region(1.0, 2.0, 1e-3, [0.0, -1.0])


def test_check_real_array_refuses_bools_in_a_list_but_not_numbers():
    with pytest.raises(DFATypeError, match=r"^beta = \[0.5, True\] has type list"):
        checks.check_real_array("beta", [0.5, True])
    assert checks.check_real_array("beta", [0.5, 1]).tolist() == [0.5, 1.0]


# ------------------------------------------------------------------ ZWidth status
@pytest.fixture(scope="module")
def zw():
    return zwidth.z_width(DEV, 0.1, grid=2, speeds=1, n_jobs=1)


def test_zwidth_status_is_an_enum_with_a_message(zw):
    assert isinstance(zw.status, ZWidthStatus) and zw.status in (ZWidthStatus.OK, ZWidthStatus.CAVEATS)
    d = json.loads(json.dumps(zw.to_dict()))
    assert d["status"] == zw.status.value and d["status_message"] == zw.status.message
    assert {m.value for m in ZWidthStatus} == {"ok", "caveats", "counterexample"}  # JSON values unchanged


def test_zwidth_status_validated_on_construction(zw):
    assert dataclasses.replace(zw, status="caveats").status is ZWidthStatus.CAVEATS
    with pytest.raises(DFAValueError, match=r"^status = 'fine' is invalid: it must be a ZWidthStatus"):
        dataclasses.replace(zw, status="fine")
    with pytest.raises(DFAValueError, match=r"status = 'counterexample' is invalid with 0 counterexample"):
        dataclasses.replace(zw, status=ZWidthStatus.COUNTEREXAMPLE)
    ce = ({"stiffness": 1.0, "damping": 0.0, "outcome": "diverges", "unit": "N/m"},)
    with pytest.raises(DFAValueError, match=r"status = 'ok' is invalid with 1 counterexample"):
        dataclasses.replace(zw, counterexamples=ce, status="ok")
