"""The inverse question (issue 26): what each parameter must be for a target K, checked by substituting back.

At each returned value the target K is exactly the method's limit (eq. 11 extended for the criterion, the exact
linear bound for the linear loop), the spring's criterion values equal eq. 11 solved by hand for the parameter,
and the damper guidance sits exactly where the criterion starts (or stops) proving some K.
"""

from __future__ import annotations

import dataclasses
import json
import math
import types

import numpy as np
import pytest

from dfa.analysis.limits.kmax import criterion_passes, linear_limit, wall_k_criterion
from dfa.analysis.limits.require import PARAMETERS, _changed, damper_guidance, requirements
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.model.catalogue import get_device
from dfa.model.device import Device
from dfa.model.wall import Wall
from dfa.results.status import RequireStatus

CUSTOM = Device(0.1, 0.005, 0.02, 1e-5, 1e-3)
CASES = [
    ("delta spring", get_device("delta").device, 20000.0, 0.1, None),
    ("delta wall", get_device("delta").device, 3000.0, 0.1, Wall.of(1.0, damping=1.0, filter_cutoff=100.0, delay=1)),
    ("custom spring d=1", CUSTOM, 100.0, 0.1, Wall.of(1.0, delay=1)),
    ("custom wall", CUSTOM, 500.0, 0.1, Wall.of(1.0, damping=0.5, delay=1)),
    ("impulse wall", get_device("impulse").device, 200.0, 0.05, Wall.of(1.0, damping=0.2)),
]


def _limit(method, dev, wall, v):
    return wall_k_criterion(dev, wall, v) if method == "criterion" else linear_limit(dev, wall)


@pytest.mark.parametrize("name, dev, k, v, wall", CASES, ids=[c[0] for c in CASES])
def test_eq11_require_substituted_back_the_target_is_the_limit(name, dev, k, v, wall):
    req = requirements(dev, k, v, wall=wall)
    assert len(req.requirements) == 2 * len(PARAMETERS)
    answered = 0
    for r in req.requirements:
        if r.required is None:
            continue
        answered += 1
        d2, w2 = _changed(dev, req.wall, r.parameter, r.required)
        if r.parameter == "delay":  # whole samples: K holds at the value, fails one sample the harmful way
            step = 1 if r.bound == "at_most" else -1
            d3, w3 = _changed(dev, req.wall, "delay", r.required + step)
            holds = (lambda d_, w_: criterion_passes(d_, w_, k, v)) if r.method == "criterion" else (
                lambda d_, w_: k < linear_limit(d_, w_))  # fmt: skip
            assert holds(d2, w2) and not holds(d3, w3), r
            continue
        assert _limit(r.method, d2, w2, v) == pytest.approx(k, rel=1e-6), r
        # today's value is on the side the status says
        now_holds = k <= _limit(r.method, dev, req.wall, v) * (1 + 1e-9)
        assert now_holds == (r.status is RequireStatus.MET), r
    assert answered >= 4


def test_eq11_require_spring_matches_eq11_solved_for_each_parameter():
    """Eq. 11 (delay d): K <= 2c/Δ and (b − K T(½ + d))|ẋ0| + c − KΔ/2 >= 0, solved for c, Δ and b by hand."""
    dev, k, v, d = get_device("delta").device, 5000.0, 0.1, 1
    req = requirements(dev, k, v, wall=Wall.of(1.0, delay=d))
    b, c, res, t = dev.damping, dev.coulomb, dev.resolution, dev.period
    dyn = k * t * (0.5 + d) * v
    c_min = max(k * res / 2, dyn + k * res / 2 - b * v)
    res_max = min(2 * c / k, 2 * (b * v + c - dyn) / k)
    assert req.find("criterion", "coulomb").required == pytest.approx(c_min, rel=1e-7)
    assert req.find("criterion", "resolution").required == pytest.approx(res_max, rel=1e-7)
    # the largest T: (b − K T(½ + d))v + c − KΔ/2 = 0
    assert req.find("criterion", "period").required == pytest.approx(
        (b * v + c - k * res / 2) / (k * (0.5 + d) * v), rel=1e-7
    )
    # the linear loop never sees Δ or c
    assert req.find("linear", "coulomb").status is RequireStatus.NO_EFFECT
    assert req.find("linear", "resolution").status is RequireStatus.NO_EFFECT


def test_eq11_damper_guidance_is_where_the_criterion_starts_proving():
    dev, v = CUSTOM, 0.1
    g = damper_guidance(dev, Wall.of(1.0, damping=0.5), v)
    assert not g.proves_some_k and g.max_resolution is None  # (B − b)v = 0.0495 N > c = 0.02 N
    for b_, proves in ((g.max_virtual_damping * 0.999, True), (g.max_virtual_damping * 1.001, False)):
        assert (wall_k_criterion(dev, Wall.of(1.0, damping=b_), v) > 0) == proves
    for c_, proves in ((g.min_coulomb * 1.001, True), (g.min_coulomb * 0.999, False)):
        d2 = dataclasses.replace(dev, coulomb=c_)
        assert (wall_k_criterion(d2, Wall.of(1.0, damping=0.5), v) > 0) == proves
    # a small damper: the resolution bound exists and is where the proof stops
    g2 = damper_guidance(dev, Wall.of(1.0, damping=0.1), v)
    assert g2.proves_some_k and g2.max_resolution is not None
    for r_, proves in ((g2.max_resolution * 0.999, True), (g2.max_resolution * 1.001, False)):
        d2 = dataclasses.replace(dev, resolution=r_)
        assert (wall_k_criterion(d2, Wall.of(1.0, damping=0.1), v) > 0) == proves


def test_eq11_strictest_damper_guidance_is_the_configuration_proving_the_smallest_damper():
    """Over configurations (a Z-width's minimum), the guidance is the one whose criterion stops at the smallest B
    (eq. 11 per device), named; the criterion proves a K with B just below it in every configuration."""
    from dfa.analysis.limits.require import strictest_damper_guidance
    from dfa.render.zwidth import criterion_damper_note

    v, wall = 0.1, Wall.of(1.0, damping=0.5)
    devices = [("light", CUSTOM), ("rough", dataclasses.replace(CUSTOM, coulomb=3 * CUSTOM.coulomb))]
    name, g = strictest_damper_guidance(devices, wall, v)
    each = {n: damper_guidance(d, wall, v).max_virtual_damping for n, d in devices}
    assert name == min(each, key=each.__getitem__) == "light" and g.max_virtual_damping == each["light"]
    for _n, d in devices:
        assert wall_k_criterion(d, Wall.of(1.0, damping=0.999 * g.max_virtual_damping), v) > 0
    assert strictest_damper_guidance(devices, Wall.of(1.0), v) is None  # no damper: nothing to guide

    class _ZW:  # the two fields the note reads besides the criterion's column
        damping = np.array([0.0, 0.5])
        limits = {"criterion": [types.SimpleNamespace(value=1.0), types.SimpleNamespace(value=None)]}
        device, velocity = CUSTOM, v

    note = criterion_damper_note(g, _ZW(), name)
    assert note.endswith("(configuration light, the strictest)") and "criterion '-' for B > 0" in note


def test_eq11_require_refuses_bad_input():
    dev = get_device("delta").device
    for bad in (0.0, -1.0, math.nan, math.inf):
        with pytest.raises(DFAValueError, match="stiffness"):
            requirements(dev, bad, 0.1)
    with pytest.raises(DFAValueError, match="velocity"):
        requirements(dev, 1000.0, -0.1)
    with pytest.raises(DFAValueError, match="methods"):
        requirements(dev, 1000.0, 0.1, methods=("simulation",))


def _printed_bound(text: str, sign: str, unit: str, tag: str, required: float) -> float:
    """The value printed after ``sign`` for one cell, checked to lie on the side where K holds (rounded toward it:
    ≥ up, ≤ down) within the 4 significant digits printed."""
    import re

    values = [float(m) for m in re.findall(rf"{sign} ([0-9.e+-]+) {unit} \({tag}\)", text)]
    near = [v for v in values if abs(v - required) <= 1e-3 * abs(required)]
    assert near, (values, required)
    v = near[0]
    assert (v >= required) if sign == "≥" else (v <= required), (v, required)
    return v


def test_eq11_require_cli_text_and_json_agree(capsys):
    argv = ["require", "--device", "delta", "--stiffness", "20000", "--velocity", "0.1"]
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert all(len(line) < 100 for line in text.splitlines())
    rows = {(r["method"], r["parameter"]): r for r in d["requirements"]}
    c = rows[("criterion", "coulomb")]
    assert c["status"] == "met" and _printed_bound(text, "≥", "N", "holds now", c["required"])
    p = rows[("linear", "period")]
    assert p["status"] == "change" and _printed_bound(text, "≤", "s", "change", p["required"])
    assert d["stiffness"] == 20000.0 and rows[("linear", "coulomb")]["required"] is None


def test_eq11_require_cli_needs_the_target_stiffness(capsys):
    code = main(["require", "--mass", "0.1", "--damping", "0.005", "--coulomb", "0.02", "--resolution", "1e-5",
                 "--period", "1e-3", "--velocity", "0.1"])  # fmt: skip
    err = capsys.readouterr().err
    assert code == 2 and "--stiffness" in err and len(err.strip().splitlines()) == 1


def test_eq11_stiffness_and_zwidth_say_what_restores_the_proof_with_a_damper(capsys):
    dev_flags = ["--mass", "0.1", "--damping", "0.005", "--coulomb", "0.02", "--resolution", "1e-5",
                 "--period", "1e-3", "--velocity", "0.1"]  # fmt: skip
    g = damper_guidance(CUSTOM, Wall.of(1.0, damping=0.5), 0.1)
    assert main(["stiffness", *dev_flags, "--virtual-damping", "0.5"]) == 0
    out = capsys.readouterr().out
    assert f"B < {g.max_virtual_damping:.4g} N·s/m or c > {g.min_coulomb:.4g} N" in out.replace("\n  ", " ")
    assert main(["stiffness", *dev_flags, "--virtual-damping", "0.5", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["damper_guidance"]["max_virtual_damping"] == pytest.approx(g.max_virtual_damping)
    assert main(["zwidth", *dev_flags, "--grid", "3", "--speeds", "1"]) == 0
    out = capsys.readouterr().out.replace("\n  ", " ")
    assert f"unless B < {g.max_virtual_damping:.4g} N·s/m" in out


def test_eq11_require_describing_function_substituted_back(capsys, monkeypatch):
    """`--describing-function`: at the least Coulomb friction returned, K_df (the design answer's) is the target K;
    a little less friction and it falls below (each value to DF_RTOL). Text and JSON agree."""
    import dfa.analysis.limits.require as require_mod
    from dfa.analysis.limits.kmax import describing_limit
    from dfa.analysis.limits.require import DF_RTOL

    runs: list[tuple[str, object]] = []
    original = require_mod.requirements

    def requirements_once(*args, **kwargs):  # the text run renders the JSON run's requirements: one search
        if not runs:
            runs.append((repr((args, kwargs)), original(*args, **kwargs)))
        assert repr((args, kwargs)) == runs[0][0], "the text run asks for the same requirements"
        return runs[0][1]

    monkeypatch.setattr(require_mod, "requirements", requirements_once)
    dev, k, v = get_device("delta").device, 20000.0, 0.1
    argv = ["require", "--device", "delta", "--stiffness", "20000", "--velocity", "0.1", "--describing-function",
            "--parameter", "coulomb"]  # fmt: skip
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    rows = {(r["method"], r["parameter"]): r for r in d["requirements"]}
    assert set(rows) == {("criterion", "coulomb"), ("linear", "coulomb"), ("df", "coulomb")}
    r = rows[("df", "coulomb")]
    assert r["status"] == "met" and r["bound"] == "at_least"
    c = r["required"]
    at = describing_limit(dataclasses.replace(dev, coulomb=c), Wall(k), v).value
    below = describing_limit(dataclasses.replace(dev, coulomb=c * (1 - 3 * DF_RTOL)), Wall(k), v).value
    assert at is not None and at >= k and (below is None or below < k)
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "describing function" in text and _printed_bound(text, "≥", "N", "holds now", c)
    assert all(len(line) < 100 for line in text.splitlines())


def test_eq11_require_period_with_a_damper_searches_both_ways():
    """Issue 41: with a virtual damper the criterion's friction term c − KΔ/2 − BΔ/T grows with T, so a longer
    period proves K where a shorter never does; `require` answered "no value helps" (it only tried shorter).

    Here c − KΔ/2 − BΔ/T = 0.06 − 0.015 − 0.054 < 0 today; eq. 11 with the damper, solved by hand for T:
    (b − B)ẋ − KẋT/2 + c − KΔ/2 − BΔ/T = 0, a quadratic in T whose smaller root is the least period that holds.
    """
    dev = Device(0.25, 0.01, 0.06, 3e-5, 3.333e-4)
    k, v, b = 1000.0, 0.001, 0.6
    wall = Wall.of(k, damping=b)
    assert not criterion_passes(dev, wall, k, v)
    r = requirements(dev, k, v, wall=wall, methods=("criterion",), parameters=("period",)).find("criterion", "period")
    assert r.status is RequireStatus.CHANGE and r.bound == "at_least" and r.required > dev.period
    # the root by hand: −(Kẋ/2) T² + ((b − B)ẋ + c − KΔ/2) T − BΔ = 0
    qa, qb, qc = -0.5 * k * v, (dev.damping - b) * v + dev.coulomb - 0.5 * k * dev.resolution, -b * dev.resolution
    roots = sorted((-qb + s * math.sqrt(qb * qb - 4 * qa * qc)) / (2 * qa) for s in (1.0, -1.0))
    assert r.required == pytest.approx(roots[0], rel=1e-6)
    for t, holds in ((r.required * (1 + 1e-6), True), (r.required * (1 - 1e-6), False)):
        assert criterion_passes(*_changed(dev, wall, "period", t), k, v) is holds
