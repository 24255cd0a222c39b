"""The device's travel (element Travel, device field ``travel``, flag ``--travel``, outcome ``end_stop``).

A real device stops at ±travel from the centre (ξ = 0, where the wall's spring is zero). The simulation ends a run
whose position leaves [−ξ_travel, ξ_travel] (ξ_travel = travel/Δ ticks) there, with the outcome ``end_stop``: the
controller kernel's exit test beside the divergence bound (its block, code 10, in the wall's kernel table), the
spring's kernel with the travel as its bound (:func:`dfa.analysis.simulation.mark_end_stops`). Checked:

1. a run that stays inside is bit for bit the same with and without the travel (both kernels);
2. the one-sided Phantom 1.0 at 800 N/m pushed with 1 N (which ran 200 s "undecided" while the device flew metres
   out) ends ``end_stop`` at the first sample instant past the travel, in the API, the CLI text and the JSON;
3. a diverging spring ends at the travel, not at the divergence bound, and past the bound it stays ``unstable``;
4. the element's group, block, JSON round trip and coverage; the device field, its rule and the Loop's default.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from dfa.analysis.approach import approach_start
from dfa.analysis.simulation import divergence_bound, simulate, simulate_batch
from dfa.cli import main
from dfa.core import kernel, table
from dfa.errors import DFAValueError
from dfa.model.catalogue import get_device
from dfa.model.device import DEVICE_FIELDS, Device
from dfa.model.elements import Coverage, Element, OneSided, Push, Travel
from dfa.model.loop import Loop, with_travel
from dfa.model.wall import Wall, WallParams
from dfa.results.status import ContactOutcome, SimulationOutcome

PHANTOM = get_device("phantom").device
TRAVEL = 0.0625  # m: a Phantom-sized travel (half of a 125 mm span), for the tests only


def _same(a, b) -> bool:
    """Two results identical: outcome, measurements and the record, bit for bit."""
    keys = ("outcome", "amplitude", "frequency", "centre", "rest_sample", "samples_run", "final_xi", "final_xi_dot")
    return all(getattr(a, k) == getattr(b, k) or getattr(a, k) != getattr(a, k) for k in keys) and (
        a.xi.tobytes() == b.xi.tobytes() and a.xi_dot.tobytes() == b.xi_dot.tobytes()
    )


@pytest.mark.parametrize(
    "wall",
    [WallParams(), WallParams.of(delay=1), WallParams.of(damping=0.3), WallParams(((OneSided, 0.0), (Push, 0.5)))],
    ids=["spring", "delay", "damper", "one_sided_push"],
)
def test_run_inside_the_travel_is_bit_identical(wall):
    """Eq. 4-5 with the travel far beyond the motion: nothing changes, bit for bit (either kernel)."""
    mu, beta, sigma, v0 = 50.0, 0.2, 0.3, 2.0
    x0, v0 = approach_start(v0, wall=wall)[:2] if wall.one_sided else (0.0, v0)
    plain = simulate(Loop.dimensionless(mu, beta, sigma, wall), v0, 20_000, xi0=x0)
    peak = float(np.nanmax(np.abs(plain.xi)))
    stopped = WallParams((*wall.groups, (Travel, 2.0 * peak + 10.0)))
    assert stopped.is_spring == wall.is_spring  # the travel keeps the closed forms and the spring's kernel
    with_stop = simulate(Loop.dimensionless(mu, beta, sigma, stopped), v0, 20_000, xi0=x0)
    assert plain.outcome is not SimulationOutcome.END_STOP and _same(plain, with_stop)


def _phantom_push():
    """The one-sided Phantom 1.0 at 800 N/m pushed with 1 N, approached at 0.05 m/s, with the travel."""
    dev = Device(PHANTOM.mass, PHANTOM.damping, PHANTOM.coulomb, PHANTOM.resolution, PHANTOM.period, travel=TRAVEL)
    loop = Loop(dev, Wall(800.0, (OneSided(), Push(1.0))))
    x0, v0, _ = approach_start(dev.xi_dot(0.05), wall=loop.wall_params)
    return dev, loop, x0, v0


def test_phantom_push_ends_at_the_end_stop_early():
    dev, loop, x0, v0 = _phantom_push()
    assert loop.wall_params.group(Travel) == pytest.approx(TRAVEL / dev.resolution, rel=1e-15)  # the Loop adds it
    r = simulate(loop, v0, xi0=x0)
    xt = TRAVEL / dev.resolution
    assert r.outcome is SimulationOutcome.END_STOP and r.contact is ContactOutcome.END_STOP
    assert r.samples_run < r.samples // 4  # early: the run (50 000 samples) stops at the stop
    # it ends at the first sample instant past the travel: the one before is inside, the last outside
    assert abs(r.final_xi) > xt and abs(r.xi[r.samples_run - 1]) <= xt
    assert r.final_xi == r.xi[r.samples_run] and np.isnan(r.xi[r.samples_run + 1 :]).all()
    # without the travel the same run does not end there (it runs on: the stop is the only change)
    free = simulate(Loop(PHANTOM, loop.wall), v0, xi0=x0, samples=r.samples_run + 200)
    assert free.outcome is not SimulationOutcome.END_STOP
    assert free.xi[: r.samples_run + 1].tobytes() == r.xi[: r.samples_run + 1].tobytes()


def test_phantom_push_cli_text_and_json_show_the_end_stop(capsys):
    argv = ["simulate", "--device", "phantom", "--stiffness", "800", "--one-sided", "--push", "1", "--velocity", "0.05"]
    assert main([*argv, "--travel", str(TRAVEL)]) == 0
    out = capsys.readouterr().out
    assert "end_stop: reached the device's end stop" in " ".join(out.split())
    assert main([*argv, "--travel", str(TRAVEL), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    dev, loop, x0, v0 = _phantom_push()
    r = simulate(loop, v0, xi0=x0)
    assert d["outcome"] == "end_stop" and d["contact"] == "end_stop"
    assert d["samples_run"] == r.samples_run and d["final_xi"] == pytest.approx(r.final_xi, rel=1e-9)  # JSON digits
    assert d["travel"] == TRAVEL and d["travel_unit"] == "m"
    assert d["travel_ticks"] == pytest.approx(loop.wall_params.group(Travel), rel=1e-9)


def test_diverging_spring_ends_at_the_travel_not_the_bound():
    """μ = 2, β = σ = 0 diverges (eq. 11 fails): with ξ_travel = 50 it stops past ±50 ticks, end_stop; the batch
    (one compiled call) gives the same; a travel beyond the bound leaves it unstable."""
    w = WallParams(((Travel, 50.0),))
    r = simulate(Loop.dimensionless(2.0, 0.0, 0.0, w), 3.0, samples=2000)
    assert r.outcome is SimulationOutcome.END_STOP and 50.0 < abs(r.final_xi) <= divergence_bound(0.0, 3.0, 2.0)
    assert np.abs(r.xi[: r.samples_run]).max() <= 50.0
    b = simulate_batch(2.0, [0.0, 0.0], 0.0, 3.0, samples=2000, wall=w)
    assert b.outcomes() == ["end_stop", "end_stop"] and int(b.samples_run[0]) == r.samples_run
    far = WallParams(((Travel, 1e12),))
    assert simulate(Loop.dimensionless(2.0, 0.0, 0.0, far), 3.0, samples=2000).outcome is SimulationOutcome.UNSTABLE


def test_controller_kernel_block_ends_the_run_at_the_travel():
    """The wall kernel's exit test (a damper keeps the spring's kernel out): flag 3, the outcome end_stop."""
    w = WallParams.of(damping=0.01)
    plain = simulate(Loop.dimensionless(2.0, 0.0, 0.0, w), 3.0, samples=2000)
    assert plain.outcome is SimulationOutcome.UNSTABLE
    stop = simulate(Loop.dimensionless(2.0, 0.0, 0.0, WallParams((*w.groups, (Travel, 40.0)))), 3.0, samples=2000)
    assert stop.outcome is SimulationOutcome.END_STOP and 40.0 < abs(stop.final_xi)
    k = stop.samples_run + 1
    assert stop.xi[:k].tobytes() == plain.xi[:k].tobytes()  # the same run up to the stop


def test_element_group_block_json_and_coverage():
    t = Travel(0.05)
    assert t.group(1e-3, 1000.0, resolution=2e-5) == 2500.0
    assert Travel.kernel_block(2500.0) == (table.TRAVEL, (2500.0,), 0) and table.TRAVEL == 10
    assert Element.from_dict(t.to_dict()) == t
    p = Wall(1000.0, (t,)).params(1e-3, 2e-5)
    assert WallParams.from_dict(p.to_dict()) == p and p.to_dict()["travel"] == 2500.0
    cov = Travel.coverage(2500.0)
    assert cov.covers(Coverage.ALL) and "inside the travel" in Travel.assumption
    with pytest.raises(DFAValueError, match="travel = -1.0 is invalid"):
        Travel(-1.0)
    with pytest.raises(DFAValueError, match="needs the encoder resolution"):
        t.group(1e-3, 1000.0)
    assert list(SimulationOutcome)[kernel.END_STOP] is SimulationOutcome.END_STOP


def test_device_field_is_optional_and_applies_by_default():
    row = next(f for f in DEVICE_FIELDS if f.name == "travel")
    assert not row.required and row.absent == "unlimited" and row.flag == "--travel"
    assert PHANTOM.travel is None and "travel" not in PHANTOM.to_dict()  # no cited catalogue value: unlimited
    dev = Device(0.072, 0.005, 0.038, 2e-5, 1e-3, travel=0.05)
    assert dev.to_dict()["travel"] == 0.05
    assert Loop(dev, 800.0).wall_params.group(Travel) == 2500.0 and Loop(dev, 800.0).wall_params.is_spring
    own = Wall(800.0, (Travel(0.01),))
    assert Loop(dev, own).wall_params.group(Travel) == 0.01 / 2e-5  # a wall's own travel is kept
    assert with_travel(WallParams(), PHANTOM) == WallParams()
    with pytest.raises(DFAValueError, match="travel = 0.0 is invalid"):
        Device(0.072, 0.005, 0.038, 2e-5, 1e-3, travel=0.0)


def test_end_stop_measures_no_amplitude_text_and_json_give_the_same_reason(capsys):
    # a run ended at the stop measured no cycle: no "amplitude 0 ticks" (a run at rest's), but null with the reason
    dev, loop, x0, v0 = _phantom_push()
    r = simulate(loop, v0, xi0=x0)
    assert np.isnan(r.amplitude) and np.isnan(r.force_peak_to_peak)
    argv = ["simulate", "--device", "phantom", "--stiffness", "800", "--one-sided", "--push", "1", "--velocity", "0.05",
            "--travel", str(TRAVEL)]  # fmt: skip
    assert main(argv) == 0
    out = " ".join(capsys.readouterr().out.split())
    why = r.null_reasons()["amplitude"]
    assert "not measured: the run's outcome is end_stop" in why and f"amplitude {why}" in out
    assert "amplitude 0 ticks" not in out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["amplitude"] is None and d["amplitude_m"] is None and d["force_peak_to_peak"] is None
    assert d["null_reasons"]["/amplitude"] == why and d["null_reasons"]["/force_peak_to_peak"] == why


@pytest.mark.parametrize("command", [["check", "--stiffness", "1000"], ["simulate", "--stiffness", "1000"]])
def test_verdict_with_a_travel_says_it_assumes_the_motion_inside(capsys, command):
    # the criterion (and the other analyses) cover a travel only as statements about the motion inside it: a verdict
    # given with a travel says so, in the text and in the JSON
    argv = [command[0], "--device", "phantom", *command[1:], "--velocity", "0.05", "--travel", "0.05"]
    assert main(argv) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "travel: ±0.05 m from the centre (ξ_travel = travel/Δ = 2488 ticks)" in out
    assert "assume the motion stays inside" in out
    assert main([*argv, "--json"]) == 0
    assert "assume the motion stays inside" in json.loads(capsys.readouterr().out)["travel_assumption"]
    assert main([argv[0], "--device", "phantom", *command[1:], "--velocity", "0.05"]) == 0
    assert "travel" not in capsys.readouterr().out  # no travel, no line


def test_design_search_runs_end_at_the_device_travel():
    """The stiffness searches simulate the device as it is, end stops included: with a travel of 5 ticks an impact
    at 5 ticks a sample leaves it at once (end_stop, which fails both simulated limits), while the criterion, a
    statement about the motion inside the travel, is unchanged."""
    import dataclasses

    from dfa.analysis.limits.kmax import design_answer
    from dfa.model.wall import Wall

    dev = get_device("phantom").device
    short = dataclasses.replace(dev, travel=5.0 * dev.resolution)
    free = design_answer(Loop(dev, Wall.of(1015.0)), 0.1, assess=True, grid=6, speeds=2)
    ends = design_answer(Loop(short, Wall.of(1015.0)), 0.1, assess=True, grid=6, speeds=2)
    assert ends.k_criterion == free.k_criterion
    assert set(ends.assessment.outcomes.values()) == {"end_stop"}
    assert "end_stop" not in free.assessment.outcomes.values()
    assert free.k_sim.value is not None and ends.k_sim.value is None
    # independent check: the same impact by simulate() with the device's travel ends at the end stop
    p = short.params(1015.0)
    w = with_travel(Wall.of(1015.0).params(short.period, short.resolution), short)
    assert simulate(p.mu, p.beta, p.sigma, short.xi_dot(0.1), wall=w, record=False).outcome == "end_stop"
