"""The exported C header (issue 44, ``dfa export --format c``) gives the simulator's wall forces, sample by sample.

Each header is compiled with the system C compiler (``-std=c99 -Wall -Wextra -pedantic -Werror -ffp-contract=off``:
warning-free, and no fused multiply-add, so that the arithmetic is numpy/numba's) into a driver that reads counts on
stdin and prints ``dfa_wall_force``'s forces with 17 digits. The reference is the compiled simulator's controller
replayed on the same readings, :func:`dfa.core.wall_kernel.applied_forces` (the command applied from each instant,
in K·Δ) times K·Δ, with the firmware's kernel table. Tolerance: rtol 1e-12 and atol 1e-12·K·Δ·max|counts| (the same
operations in the same order agree to the last bit; the tolerance only allows a compiler that reorders).
Skipped, saying so, where no C compiler is found.
"""

from __future__ import annotations

import hashlib
import re
import shutil
import subprocess

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dfa.core.wall_kernel import applied_forces
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
    VelocityFilter,
)
from dfa.model.loop import Loop
from dfa.model.wall import Wall
from dfa.render.export import c_header
from dfa.results.deploy import DeployableWall

CC = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
FLAGS = ["-std=c99", "-Wall", "-Wextra", "-pedantic", "-Werror", "-ffp-contract=off", "-O2"]
DRIVER = r"""#include <stdio.h>
#include "wall.h"
int main(void)
{
    dfa_wall_t w;
    long counts;
    dfa_wall_init(&w);
    while (scanf("%ld", &counts) == 1) {
        printf("%.17g\n", dfa_wall_force(&w, counts));
    }
    return 0;
}
"""
# the Impulse Engine's values (dfa devices), with a force limit of its own
DEV = Device(0.032, 0.02, 0.024, 314e-6, 2e-3, name="Impulse Engine")
RTOL = 1e-12


def _compiler() -> str:
    if CC is None:
        pytest.skip("no C compiler (cc, gcc or clang) on PATH: the exported header is not compiled here")
    return CC


def compiled(header: str, folder) -> str:
    """The driver compiled with ``header`` as wall.h (once per header text, in ``folder``); its path."""
    cc = _compiler()
    key = hashlib.sha256(header.encode()).hexdigest()[:16]
    where = folder / key
    exe = where / "driver"
    if not exe.exists():
        where.mkdir(parents=True, exist_ok=True)
        (where / "wall.h").write_text(header, encoding="ascii")
        (where / "driver.c").write_text(DRIVER, encoding="ascii")
        done = subprocess.run([cc, *FLAGS, "-o", str(exe), str(where / "driver.c")], capture_output=True, text=True)
        assert done.returncode == 0 and not done.stderr, f"{cc} refused or warned:\n{done.stderr}"
    return str(exe)


def c_forces(exe: str, counts: np.ndarray) -> np.ndarray:
    """The header's forces for the readings ``counts`` (N)."""
    done = subprocess.run([exe], input="\n".join(str(int(c)) for c in counts), capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return np.array([float(t) for t in done.stdout.split()])


def simulator_forces(dep: DeployableWall, counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """K·Δ times the simulator's controller replayed on the readings (applied_forces), and its controller's forces."""
    table = dep.firmware_params.kernel_table()
    n = counts.size
    out, energy, control = np.empty(n), np.empty(n), np.empty(n)
    applied_forces(counts.astype(np.float64), table, True, out, energy, control)
    return dep.force_step * out, control


def check_equal(dep: DeployableWall, counts: np.ndarray, folder) -> np.ndarray:
    """Compare the header's forces with the simulator's; return the controller's forces (for coverage checks)."""
    got = c_forces(compiled(c_header(dep), folder), counts)
    want, control = simulator_forces(dep, counts)
    atol = 1e-12 * dep.force_step * max(1.0, float(np.max(np.abs(counts))))
    assert got.shape == want.shape
    bad = np.flatnonzero(~np.isclose(got, want, rtol=RTOL, atol=atol))
    assert bad.size == 0, f"first difference at sample {bad[0]}: C {got[bad[0]]!r}, simulator {want[bad[0]]!r}"
    return control


def readings(seed: int, n: int = 300) -> np.ndarray:
    """A random walk of counts with impacts: small steps, now and then a jump of hundreds of counts."""
    rng = np.random.default_rng(seed)
    steps = np.rint(rng.normal(0.0, 3.0, n)).astype(np.int64)
    jumps = rng.random(n) < 0.03
    steps[jumps] += rng.integers(-400, 401, int(jumps.sum()))
    return int(rng.integers(-30, 31)) + np.cumsum(steps)


def crossings(seed: int, n: int = 300) -> np.ndarray:
    """Oscillations across the origin (a one-sided wall's surface lies within ±3 counts of it): in and out fast
    enough that a damper pulls on the way out, where a one-sided wall cuts the command at 0."""
    rng = np.random.default_rng(seed)
    amp, period = rng.uniform(3.0, 40.0), rng.uniform(4.0, 40.0)
    t = np.arange(n)
    return np.rint(amp * np.sin(2 * np.pi * t / period) + rng.normal(0.0, 1.0, n)).astype(np.int64)


@st.composite
def walls(draw: st.DrawFn) -> Wall:
    """A wall of the firmware's elements, each present or not (delay 0-3, damper, filter, one-sided, passivity
    controller with and without window and limit, force limit), at K from 20 to 3000 N/m."""
    k = draw(st.floats(20.0, 3000.0))
    els: list = []
    d = draw(st.integers(0, 3))
    if d:
        els.append(Delay(d))
    if draw(st.booleans()):
        els.append(Damper(draw(st.floats(0.01, 3.0))))
    if draw(st.booleans()):
        els.append(VelocityFilter(draw(st.floats(5.0, 240.0))))
    if draw(st.booleans()):
        els.append(OneSided(draw(st.floats(-3.0, 3.0))))
    if draw(st.booleans()):
        window = draw(st.one_of(st.none(), st.floats(2e-3, 0.04)))
        limit = draw(st.one_of(st.none(), st.floats(0.005, 3.0)))
        els.append(PassivityController(window, limit))
    if draw(st.booleans()):
        els.append(ForceLimit(draw(st.floats(0.05, 5.0))))
    return Wall(k, tuple(els))


@settings(max_examples=20)
@given(wall=walls(), seed=st.integers(0, 2**32 - 1))
def test_export_c_header_forces_equal_the_simulators(wall, seed, tmp_path_factory):
    dep = DeployableWall.given(Loop(DEV, wall))
    folder = tmp_path_factory.getbasetemp() / "export_c"
    check_equal(dep, readings(seed), folder)
    check_equal(dep, crossings(seed), folder)


def _every_element() -> Wall:
    return Wall(800.0, (Delay(2), Damper(1.0), VelocityFilter(60.0), OneSided(0.5),
                        PassivityController(0.01, 0.05), ForceLimit(0.6)))  # fmt: skip


@pytest.mark.parametrize(
    "wall",
    [
        Wall(500.0),
        Wall(500.0, (Delay(1),)),
        Wall(500.0, (Damper(2.0),)),
        Wall(500.0, (VelocityFilter(30.0), Damper(1.0))),
        Wall(500.0, (OneSided(-0.75),)),
        Wall(2000.0, (Delay(3), PassivityController())),
        Wall(2000.0, (Delay(1), PassivityController(0.006))),
        Wall(2000.0, (Delay(2), PassivityController(None, 0.02))),
        Wall(500.0, (ForceLimit(0.3),)),
        _every_element(),
    ],
    ids=["spring", "delay", "damper", "filter", "one_sided", "pc", "pc_window", "pc_limit", "force_limit", "all"],
)
def test_export_c_each_element_alone_and_all_together(wall, tmp_path):
    dep = DeployableWall.given(Loop(DEV, wall))
    for seed in range(3):
        check_equal(dep, readings(seed, 500), tmp_path)
        check_equal(dep, crossings(seed, 500), tmp_path)


def test_export_c_readings_saturate_the_limit_and_trigger_the_controller(tmp_path):
    """The sequences above reach the force limit and make the passivity controller act (else the test of those
    branches would pass vacuously)."""
    dep = DeployableWall.given(Loop(DEV, _every_element()))
    counts = readings(0, 500)
    control = check_equal(dep, counts, tmp_path)
    force, _ = simulator_forces(dep, counts)
    assert np.count_nonzero(control) > 5
    assert np.sum(np.isclose(np.abs(force), 0.6, rtol=1e-12)) > 5  # at F_max = 0.6 N


def test_export_c_device_force_limit_joins_the_firmware(tmp_path):
    dev = Device(0.032, 0.02, 0.024, 314e-6, 2e-3, name="limited", max_force=0.4)
    dep = DeployableWall.given(Loop(dev, Wall(500.0, (Damper(1.0),))))
    header = c_header(dep)
    assert "DFA_WALL_FORCE_LIMIT" in header
    got = c_forces(compiled(header, tmp_path), readings(1))
    assert np.max(np.abs(got)) == pytest.approx(0.4, rel=1e-12)
    check_equal(dep, readings(1), tmp_path)


def test_export_c_leaves_lag_hand_push_and_travel_out_and_says_so(tmp_path):
    dev = Device(0.032, 0.02, 0.024, 314e-6, 2e-3, name="Impulse Engine", travel=0.05)
    lag = DeployableWall.given(Loop(dev, Wall(500.0, (Delay(1), Damper(1.0), AmplifierLag(300.0)))))
    hand = DeployableWall.given(Loop(dev, Wall(500.0, (OneSided(0.0), Push(0.2), HandSpring(50.0)))))
    for dep, names in ((lag, ["AmplifierLag", "Travel"]), (hand, ["HandSpring", "Push", "Travel"])):
        header = c_header(dep)
        comment = header.split("*/")[0]
        code = header.split("#ifndef DFA_WALL_H")[1]
        assert "Not exported" in comment and all(n in comment for n in names)
        names_in_code = set(re.findall(r"\bDFA_WALL_[A-Z_]+", code)) | set(re.findall(r"\bdfa_wall_[a-z_]+", code))
        assert not {n for n in names_in_code if re.search("lag|amplifier|hand|push|travel", n, re.IGNORECASE)}
        check_equal(dep, readings(2), tmp_path)
    # the hand and the push do not enter the command: the simulator's full table gives the same forces
    counts = readings(3)
    n = counts.size
    out, e, c = np.empty(n), np.empty(n), np.empty(n)
    applied_forces(counts.astype(np.float64), hand.loop.wall_params.kernel_table(), True, out, e, c)
    got = c_forces(compiled(c_header(hand), tmp_path), counts)
    np.testing.assert_allclose(got, hand.force_step * out, rtol=RTOL, atol=1e-12)
