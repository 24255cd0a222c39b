"""The actuator's force limit (dfa.model.elements.ForceLimit): the command clipped to ±F_max after every other
element (dfa.core.wall_kernel._clip), the outcome ``saturated``, its coverage (eq. 6 for the spring alone) and
the device field ``max_force`` (--max-force)."""

from __future__ import annotations

import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dfa.analysis.approach import approach_start
from dfa.analysis.simulation import simulate
from dfa.cli.app import main
from dfa.core import kernel
from dfa.core.wall_kernel import applied_forces, run_wall_kernel
from dfa.model.catalogue import get_device
from dfa.model.device import Device
from dfa.model.elements import Coverage, Damper, Delay, Element, ForceLimit, OneSided, Push
from dfa.model.loop import Loop
from dfa.model.wall import Wall, WallParams
from dfa.results.status import SimulationOutcome


def _run(table: np.ndarray, mu: float, beta: float, sigma: float, v0: float, n: int, x0: float = 0.0):
    rx, rv, st_ = np.empty(n + 1), np.empty(n + 1), np.empty(kernel.NSTATS)
    done, rest, _ = run_wall_kernel((mu, beta, sigma), (x0, v0), (n, n // 4, 1e9, True), table, rx, rv, st_, False)
    return done, rest, rx, rv, st_


def _limited(phi_max: float, *others: tuple[type[Element[object]], object]) -> WallParams:
    return WallParams(((ForceLimit, phi_max), *others))


def test_limit_never_reached_is_bit_identical_to_the_plain_wall() -> None:
    # μ = 50, β = 2.5, σ = 1.5 (passive with the corner (½ + d + β_B, ½ + β_B) = (1.8, 0.8), eq. 6 extended),
    # ξ'0 = 3, the spring alone and with a damper and a delay: the command stays far below 1e6
    for others in ((), ((Damper, 0.3), (Delay, 1))):
        plain, lim = WallParams(others).kernel_table(), _limited(1e6, *others).kernel_table()
        if not others:
            plain = np.array([1.0, Delay.kernel_code, 1.0, 0.0, 0.0])  # the wall kernel's spring (d = 0)
        a, b = _run(plain, 50.0, 2.5, 1.5, 3.0, 20_000), _run(lim, 50.0, 2.5, 1.5, 3.0, 20_000)
        assert a[:2] == b[:2]
        for x, y in zip(a[2:], b[2:], strict=True):
            assert np.array_equal(x, y, equal_nan=True)  # records and stats, bit for bit (the flag is 0: never)


def test_saturation_flag_zero_without_limit_and_set_when_the_command_reaches_it() -> None:
    *_, st0 = _run(WallParams(((Damper, 0.1),)).kernel_table(), 20.0, 0.0, 0.0, 40.0, 4000)
    assert st0[kernel.SATURATION] == 0.0
    *_, st1 = _run(_limited(5.0).kernel_table(), 20.0, 0.0, 0.0, 40.0, 4000)
    assert st1[kernel.SATURATION] == 2.0  # reached in the tail: the undamped loop keeps hitting it


PHANTOM = get_device("phantom").device


def test_diverging_phantom_is_held_by_the_limit_saturated_peak_force_at_the_limit() -> None:
    # Phantom 1.0 at K = 5000 N/m (far above its K_max: β = 0.001 < ½), ξ'0 = 0.5 m/s: unlimited it diverges;
    # with F_max = 3 N the motion stays bounded and the outcome is saturated
    k, n = 5000.0, 200_000
    free = simulate(Loop(PHANTOM, Wall(k)), PHANTOM.xi_dot(0.5), n, record=False)
    assert free.outcome is SimulationOutcome.UNSTABLE
    loop = Loop(PHANTOM, Wall(k, (ForceLimit(3.0),)))
    r = simulate(loop, PHANTOM.xi_dot(0.5), n)
    assert r.outcome is SimulationOutcome.SATURATED
    phi_max = 3.0 / (k * PHANTOM.resolution)
    xs = np.asarray(r.trajectory.xi if hasattr(r, "trajectory") else r.xi, dtype=float)
    force, energy, control = np.empty_like(xs), np.empty_like(xs), np.empty_like(xs)
    applied_forces(xs, loop.wall_params.kernel_table(), True, force, energy, control)
    assert np.max(np.abs(force)) == phi_max  # the peak force is the limit, exactly (the clip returns ±φ_max)
    assert np.all(np.isfinite(xs)) and np.max(np.abs(xs)) < 1e5  # bounded: about 4000 ticks (8 cm)


def test_limit_touched_then_resting_is_rest() -> None:
    # μ = 50, β = 0.6, σ = 0.6 (passive); a limit of 2 ticks' force is reached on impact at ξ'0 = 3, then it rests
    done, rest, *_, st_ = _run(_limited(2.0).kernel_table(), 50.0, 0.6, 0.6, 3.0, 20_000)
    assert rest >= 0 and st_[kernel.SATURATION] == 1.0  # reached, before the tail
    code = kernel.classify(20_000, done, rest, st_, 1.0, 1.2, 0.05, True, 50.0)[0]
    assert code == kernel.REST


def test_coverage_criterion_for_the_spring_alone_not_beside_other_elements() -> None:
    alone = _limited(30.0)
    assert alone.covers(Coverage.CRITERION | Coverage.SIMULATION) and alone.corner() == (0.5, 0.5)
    assert not alone.covers(Coverage.LINEAR) and not alone.covers(Coverage.DESCRIBING_FUNCTION)
    assert not alone.covers(Coverage.CLOSED_FORM)  # the spring's kernel does not clip: the wall kernel runs it
    for other in ((Damper, 0.3), (Delay, 1)):
        w = _limited(30.0, other)
        assert not w.covers(Coverage.CRITERION) and "force limit" in (w.not_covered() or "")


@settings(max_examples=25, deadline=None)
@given(
    mu=st.floats(1.0, 200.0),
    beta=st.floats(0.5, 2.0),
    sigma=st.floats(0.5, 2.0),
    v0=st.floats(0.0, 40.0),
    phi_max=st.floats(0.5, 50.0),
)
def test_eq6_passive_spring_with_any_limit_stores_no_energy(
    mu: float, beta: float, sigma: float, v0: float, phi_max: float
) -> None:
    # eq. 6 holds at every speed for β >= ½, σ >= ½ (region a): with the limit the storage H_F = ½μξ'² + ∫₀^ξ sat(g)
    # (the class docstring's proof) never exceeds its start, at every sample instant, to rounding
    n = 3000
    _, _, rx, rv, _ = _run(_limited(phi_max).kernel_table(), mu, beta, sigma, v0, n)
    ok = np.isfinite(rx)
    x, v = rx[ok], rv[ok]
    top = int(np.max(np.abs(x))) + 2  # bounded (a weak limit lets the device in deep, where friction may hold it)
    grid = np.arange(-top, top + 1.0)  # ∫ of the clipped staircase over whole ticks, then the part tick
    steps = np.clip(grid[:-1] + 0.5, -phi_max, phi_max)
    cum = np.concatenate(([0.0], np.cumsum(steps)))  # ∫ from −top to r, r = −top … top
    r = np.floor(x)
    part = x - r
    h = cum[(r + top).astype(int)] - cum[top] + part * np.clip(r + 0.5, -phi_max, phi_max)
    stored = 0.5 * mu * v * v + h
    assert np.all(stored <= stored[0] + 1e-9 * (1.0 + stored[0]))


def test_element_json_and_wall_record_round_trip() -> None:
    e = ForceLimit(2.5)
    assert Element.from_dict(e.to_dict()) == e
    w = Wall(1000.0, (Damper(1.0), ForceLimit(2.5)))
    assert Wall.from_dict(w.to_dict()) == w and w.to_dict()["max_force"] == 2.5
    p = w.params(1e-3, 1e-5)
    assert WallParams.from_dict(p.to_dict()) == p and p.group(ForceLimit) == pytest.approx(250.0, rel=1e-15)


def test_device_max_force_applies_in_a_loop_and_the_wall_limit_wins() -> None:
    dev = Device(0.072, 0.005, 0.038, 20.1e-6, 1e-3, name="limited", max_force=4.0)
    assert Loop(dev, Wall(1000.0)).wall.element(ForceLimit) == ForceLimit(4.0)
    assert Loop(dev, Wall(1000.0, (ForceLimit(2.0),))).wall.element(ForceLimit) == ForceLimit(2.0)
    assert Loop(dev).at(1000.0).wall_params.group(ForceLimit) == pytest.approx(4.0 / (1000.0 * 20.1e-6))
    assert Device(1.0, 0.0, 0.0, 1e-5, 1e-3).to_dict().get("max_force") is None  # absent: unlimited, not written


def test_cli_simulate_with_max_force_text_and_json(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["simulate", "--device", "phantom", "--stiffness", "5000", "--max-force", "3", "--velocity", "0.5",
            "--samples", "200000"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    out = " ".join(out.split())  # the table's columns widen with the force row the saturated run adds
    assert "actuator force limit F_max = 3 N" in out and "outcome saturated" in out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == "saturated" and d["wall"]["max_force"] == 3.0
    assert d["wall"]["dimensionless"]["force_limit"] == pytest.approx(
        3.0 / (5000.0 * 20.1e-6), rel=1e-10
    )  # JSON: 12 digits


def _one_sided_push_limited(push: float, phi_max: float) -> WallParams:
    """A one-sided wall at the origin with a push toward it and the actuator's force limit."""
    return WallParams(((OneSided, 0.0), (Push, push), (ForceLimit, phi_max)))


@pytest.mark.parametrize(
    "mu, beta, sigma, v0, push, phi_max",
    [
        (50.0, 0.6, 0.6, 3.0, 1.0, 3.0),  # the limit reached at impact, then rests pushed onto the wall (p > σ)
        (20.0, 0.3, 0.7, 1.5, 1.0, 2.0),  # a push of half the limit: rests inside, held by the clipped spring
    ],
)
def test_eq4_one_sided_push_with_limit_rests_and_matches_solve_ivp(mu, beta, sigma, v0, push, phi_max) -> None:
    # eq. 4-5 with the one-sided wall, the operator's push and the command clipped to ±φ_max: the kernel agrees with
    # the solve_ivp reference (which clips the command, the push outside it) to 1e-8 at the sample instants, the
    # limit is reached, and the run's rest (proven with the clipped commands) is rest, on the wall
    from reference_ctl import simulate_ivp_ctl

    wall = _one_sided_push_limited(push, phi_max)
    x0, xd0, _ = approach_start(v0, wall=wall)
    n = 4000
    r = simulate(Loop.dimensionless(mu, beta, sigma, wall), xd0, n, xi0=x0)
    assert r.outcome is SimulationOutcome.REST and r.contact is not None and r.contact.value == "rests"
    ix, iv = simulate_ivp_ctl(mu, beta, sigma, x0, xd0, n, wall)
    scale = max(1.0, float(np.max(np.abs(ix))))
    assert np.max(np.abs(r.xi - ix)) <= 1e-8 * scale and np.max(np.abs(r.xi_dot - iv)) <= 1e-8 * scale
    reach = np.floor(ix[: r.rest_sample + 1]) + 0.5  # the readings' levels: the spring's command −(⌊ξ⌋ + ½) inside
    assert np.max(reach) > phi_max  # the limit was reached: the clip mattered for this run


def test_simulate_saturated_force_peak_to_peak_is_the_applied_force() -> None:
    # the saturated Phantom (K = 5000 N/m, F_max = 3 N): the applied force swings between ±F_max, so its
    # peak-to-peak is 2 φ_max KΔ = 6 N, not the readings' 7967 KΔ (800 N); the force amplitude is no applied force
    k = 5000.0
    r = simulate(Loop(PHANTOM, Wall(k, (ForceLimit(3.0),))), PHANTOM.xi_dot(0.5), 200_000)
    assert r.outcome is SimulationOutcome.SATURATED
    phi_max = 3.0 / (k * PHANTOM.resolution)
    assert r.force_peak_to_peak == pytest.approx(2.0 * phi_max, rel=1e-12)
    assert r.physical(PHANTOM, k)["force_peak_to_peak_n"] == pytest.approx(6.0, rel=1e-12)


def test_cli_simulate_saturated_reports_the_applied_force(capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["simulate", "--device", "phantom", "--stiffness", "5000", "--max-force", "3", "--velocity", "0.5",
            "--samples", "200000"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "force peak-to-peak  59.7 KΔ = 6 N (tail; the applied force, clipped" in out
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["force_peak_to_peak_n"] == pytest.approx(6.0, rel=1e-11) and d["force_amplitude_n"] is None
    assert "force limit" in d["null_reasons"]["/force_amplitude_n"]


def test_stiffness_footnote_names_the_force_limit_not_a_one_sided_wall(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["stiffness", "--device", "phantom", "--max-force", "3", "--velocity", "0.05"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "none: not covered: an actuator's force limit is not linear" in out
    assert "one-sided" not in out and "passivity controller" not in out
    assert "wall held fixed while K varies: delay 0 samples, actuator force limit F_max = 3 N" in out


def test_force_limit_beside_a_travel_keeps_the_criterion() -> None:
    # the travel adds no force: the spring with a limit inside a travel is covered as the spring with a limit
    w = WallParams.of(force_limit=30.0, travel=3000.0)
    assert w.covers(Coverage.CRITERION) and w.corner() == (0.5, 0.5)


def test_public_api_exports_force_limit_and_wall_keywords() -> None:
    import dfa

    assert dfa.ForceLimit is ForceLimit and "ForceLimit" in dfa.__all__
    wall = Wall.of(1000.0, max_force=3.0, travel=0.05)
    assert wall.elements == (ForceLimit(3.0), dfa.Travel(0.05))
    assert Wall.of(1000.0).elements == ()
    groups = wall.params(1e-3, 1e-5)
    assert groups.group(ForceLimit) == pytest.approx(300.0, rel=1e-12)
    assert WallParams.of(force_limit=300.0, travel=5000.0) == groups


def test_cli_contours_refuses_a_force_limit_with_the_describing_functions_reason(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """The contour maps are the describing function of the paper's loop (eq. 42-45): a device's force limit is
    not covered there, and the command says so in one line (exit 2) instead of ignoring the field."""
    assert main(["contours", "--device", "phantom", "--max-force", "3", "--grid", "10"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--max-force 3 is not covered here" in err[0]
    assert "no describing function of the clip" in err[0] and "dfa map or dfa simulate" in err[0]
