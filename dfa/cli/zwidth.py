"""``dfa zwidth``: the Z-width, the renderable (K, B) region by the linear bound, passivity, the describing
function and simulation, with the wall's delay, filter and amplifier held fixed."""

from __future__ import annotations

import argparse
import dataclasses
import math
from typing import Any

from .._io import FIGURE_SUFFIXES, check_output_file
from ..model.device import Device
from ..model.elements import OneSided, PassivityController
from ..model.loop import Loop
from ..model.wall import Wall
from ..render.hand import device_title
from .contact import add_contact_args, contact_elements
from .inputs import Inputs, add_device_group, impact_speed, resolve
from .output import (
    WORK_TIME_LIMIT,
    add_progress_args,
    check_work_time,
    emit,
    fmt,
    progress,
    save_png,
    say,
    table,
    working,
)
from .parsing import UsageError, integer, number
from .passivity import add_passivity_args, passivity_elements
from .walls import add_wall_args, check_filter_amplifier, hand_stiffness_of, wall_groups

COMMAND = "zwidth"
HELP = (
    "Z-width: the renderable region of the (K, B) plane by the exact linear bound, passivity, "
    "the describing function and exact simulation"
)
EXAMPLE = "dfa zwidth --device impulse --velocity 0.1 --grid 20"

#: The Z-width of a device file with configurations: its rule and its text (docs/cli.md).
MINIMUM = "minimum_per_damping"
ZWIDTH_NOTE = "the minimum over them B by B (a point is inside only if inside for every configuration)"
#: Column titles of the table, by method (dfa.analysis.limits.zwidth.ZWIDTH_METHODS).
COLUMNS = {"linear": "linear", "passivity": "C-S passivity", "criterion": "criterion", "df": "describing fn",
           "sim": "sim (no div.)", "rest": "sim (rest)"}  # fmt: skip


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device, one speed, the wall (its damper refused: B is the axis), the grid and --plot."""
    add_device_group(p, "device (a catalogue name, or physical values in SI units)")
    p.add_argument(
        "--velocity",
        required=True,
        type=number("--velocity", "m/s (rotary: rad/s)"),
        metavar="V",
        help="impact speed in m/s (rotary: rad/s); required",
    )
    add_wall_args(p, zwidth=True)
    add_contact_args(p)
    add_passivity_args(p)
    p.add_argument("--grid", type=integer("--grid"), default=40, metavar="N", help="points per axis (default: 40)")
    p.add_argument(
        "--damping-max",
        dest="damping_max",
        type=number("--damping-max", "N·s/m (rotary: N·m·s/rad)"),
        metavar="B",
        help="top of the virtual damping axis in N·s/m (rotary: N·m·s/rad), from 0 (default: twice the B where "
        "the criterion's and Colgate–Schenkel's boundaries end, at most m/T)",
    )
    p.add_argument(
        "--speeds",
        type=integer("--speeds"),
        default=2,
        metavar="N",
        help="impact speeds simulated, V/N ... V (default: 2)",
    )
    p.add_argument("--jobs", type=integer("--jobs"), default=-1, metavar="N", help="threads (default: -1, all cores)")
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when the Z-width is estimated over {WORK_TIME_LIMIT:g} s (default: refuse)",
    )
    p.add_argument(
        "--plot",
        metavar="FILE",
        help="write the Z-width figure to FILE: .png, .pdf or .svg by its suffix (default: none)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout (default: a text table)")
    add_progress_args(p)


def _refuse(args: argparse.Namespace) -> None:
    """--stiffness and --virtual-damping are the grid's axes; the grid and speeds are whole numbers >= 2, >= 1."""
    from ..checks import check_jobs

    if args.stiffness is not None:
        raise UsageError("--stiffness cannot be given to zwidth: the Z-width spans a grid of K (see --grid)")
    if args.virtual_damping is not None:
        raise UsageError(
            "--virtual-damping cannot be given to zwidth: the Z-width spans a grid of B from 0 (see --grid); "
            "drop the flag, or use `dfa stiffness`/`dfa report` with it for one damper"
        )
    for flag, value, least in (("--grid", args.grid, 2), ("--speeds", args.speeds, 1)):
        if value < least:
            raise UsageError(f"{flag} {value} is invalid: it must be a whole number >= {least}; give e.g. {flag} 4")
    check_jobs("--jobs", args.jobs)
    top = args.damping_max
    if top is not None and not (math.isfinite(top) and top > 0.0):
        raise UsageError(
            f"--damping-max {top:g} is invalid: it must be a finite number > 0 (the axis runs from B = 0); give the "
            "largest virtual damping in N·s/m (rotary: N·m·s/rad), or drop the flag for the device's default"
        )


def _over_configurations(
    args: argparse.Namespace, inp: Inputs, wall: Wall, v: float, b_range: tuple[float, float] | None
) -> tuple[Any, Inputs, list[tuple[str, Device]]]:
    """The Z-width of every configuration on one grid, the minimum B by B (:func:`worst_z_width`); the inputs
    with their rows (a directional configuration along its worst normal under dfa stiffness's rule); each
    configuration's name and one-axis device."""
    from ..analysis.configurations import worst_stiffness, worst_z_width, z_width_common_ranges
    from ..analysis.limits.zwidth import z_width_seconds

    dev = inp.device
    assert dev is not None
    with working(args):
        w = worst_stiffness(dev, inp.configurations, v, wall=wall, simulate=False)
    devices = [(c.name, c.device_at(dev, r.normal)) for c, r in zip(inp.configurations, w.rows, strict=True)]
    for _n, d in devices:
        wall_groups(wall, d)
    _k, b_all = z_width_common_ranges([d for _n, d in devices], wall, v, b_range)
    seconds = sum(z_width_seconds(Loop(d, wall), v, grid=args.grid, speeds=args.speeds, n_jobs=args.jobs,
                                  b_range=b_all) for _n, d in devices)  # fmt: skip
    what = f"--grid {args.grid} with --speeds {args.speeds} over {len(devices)} configurations"
    check_work_time(what, seconds, "lower --grid or --speeds, or choose one with --configuration", args.force)
    zw = worst_z_width(dev, devices, v, wall, grid=args.grid, b_range=b_range, speeds=args.speeds,
                       n_jobs=args.jobs, progress=progress(args))  # fmt: skip
    return zw, dataclasses.replace(inp, configurations=(), worst=w, rule=MINIMUM), devices


def _cell(value: float | None) -> str:
    """A K_max cell: ``-`` where the limit is undefined (None or not finite)."""
    return fmt(value if value is not None and math.isfinite(value) else None)


def _compute(
    args: argparse.Namespace, inp: Inputs, wall: Wall, v: float, b_range: tuple[float, float] | None
) -> tuple[Any, Inputs, list[tuple[str, Device]]]:
    """The Z-width (the minimum over a file's configurations, B by B), refused up front when it would take longer
    than the work limit; the inputs (the limiting configuration's, with configurations); the devices it
    covers, named (one, unnamed, without configurations)."""
    from ..analysis.limits.zwidth import z_width, z_width_seconds

    if inp.configurations:  # the minimum over the configurations, B by B
        return _over_configurations(args, inp, wall, v, b_range)
    assert inp.device is not None
    loop = Loop(inp.device, wall)
    seconds = z_width_seconds(loop, v, grid=args.grid, speeds=args.speeds, n_jobs=args.jobs, b_range=b_range)
    check_work_time(f"--grid {args.grid} with --speeds {args.speeds}", seconds, "lower --grid or --speeds",
                    args.force)  # fmt: skip
    zw = z_width(
        loop, v, grid=args.grid, b_range=b_range, speeds=args.speeds, n_jobs=args.jobs, progress=progress(args)
    )
    return zw, inp, [("", inp.device)]


def _elements(zw: Any, u: dict[str, str]) -> str:
    """The wall's elements besides the damper the Z-width varies: delay, filter, amplifier, contact, controller."""
    fc, bw = zw.wall.filter_cutoff, zw.wall.amplifier_bandwidth
    elements = f"delay {zw.delay}" + (f", velocity filter {fmt(fc)} Hz" if fc is not None else "")
    elements += f", amplifier {fmt(bw)} Hz" if bw is not None else ""
    if zw.wall.element(OneSided) is not None:
        from ..render.contact import contact_text

        elements += f"; {contact_text(zw.wall, u)}"
    pc = zw.wall.element(PassivityController)
    if pc is not None:
        from ..render.passivity import passivity_text

        elements += f"; {passivity_text(pc, u)}"
    return elements


def run(args: argparse.Namespace) -> int:
    """Compute the Z-width; print K_max(B) per method."""
    from ..analysis.limits.require import strictest_damper_guidance
    from ..analysis.limits.zwidth import ZWIDTH_METHODS, check_zwidth_size, start_workers
    from ..render.zwidth import criterion_damper_note, damping_axis_note, non_monotone_mark, non_monotone_notes

    _refuse(args)
    inp = resolve(args, dimensionless=False, need_stiffness=False, configurations=True)
    dev = inp.device
    assert dev is not None
    check_filter_amplifier(args, dev)
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
    hand = hand_stiffness_of(args, dev)  # the hand's stiffness joins the wall (dfa.HandSpring)
    wall = Wall.of(1.0, delay=args.delay, filter_cutoff=args.velocity_filter,
                   amplifier_bandwidth=args.amplifier_bandwidth, hand_stiffness=hand)  # fmt: skip
    wall = Wall(1.0, (*wall.elements, *contact_elements(args, dev), *passivity_elements(args, dev)))
    wall_groups(wall, dev)  # a value whose group overflows: refused naming its flag
    v = impact_speed("--velocity", args.velocity, inp, zero=False)
    b_range = None if args.damping_max is None else (0.0, float(args.damping_max))
    check_zwidth_size(args.grid, args.speeds, ("--grid", "--speeds"))  # before the estimate: --force cannot lift it
    start_workers(args.grid, args.jobs)  # the columns' worker processes start while the estimate and plan run
    zw, inp, devices = _compute(args, inp, wall, v, b_range)
    dev = inp.device
    assert dev is not None
    if args.plot is not None:
        save_png("--plot", args.plot, zw.plot())
    if args.json:
        rec = zw.to_dict()
        if args.plot is not None:
            rec["plot"] = args.plot
        if inp.worst is not None:  # the rows: each configuration's one-axis device (and dfa stiffness's normal)
            rec["configuration"] = {
                "rule": MINIMUM, "rule_text": ZWIDTH_NOTE, "rows": [r.to_dict() for r in inp.worst.rows],
            }  # fmt: skip
        emit(rec)
        return 0
    u = dev.units
    rows = [
        [fmt(float(b))]
        + [_cell(lim.value) + non_monotone_mark(lim.non_monotone) for lim in (zw.limits[m][i] for m in ZWIDTH_METHODS)]
        + ([zw.limiting["sim"][i]] if zw.limiting else [])
        for i, b in enumerate(zw.damping)
    ]
    say(
        f"Z-width of {device_title(dev)}: impacts up to {zw.velocity:.4g} {u['velocity']}, {_elements(zw, u)}; "
        f"status {zw.status}"
    )
    if zw.limiting:
        n = len(inp.worst.rows) if inp.worst else 0
        say(f"{n} configurations, {ZWIDTH_NOTE}; 'sim by' names the configuration of the simulated limit per B "
            "(--json: every method's)")  # fmt: skip
    say(f"K_max(B) in {u['stiffness']} ('-': undefined, see --json for the reason)")
    say(
        table(
            rows, [f"B ({u['damping']})"] + [COLUMNS[m] for m in ZWIDTH_METHODS] + (["sim by"] if zw.limiting else [])
        )
    )
    say(
        f"{zw.simulations} exact simulations on a {zw.stiffness.size} x {zw.damping.size} grid "
        f"(K {zw.stiffness[0]:.4g} to {zw.stiffness[-1]:.4g} {u['stiffness']}, B {zw.damping[0]:.4g} to "
        f"{zw.damping[-1]:.4g} {u['damping']}{'' if args.damping_max else damping_axis_note()}); "
        "simulated limits are grid values"
    )
    for line in non_monotone_notes(zw, {m: COLUMNS[m] for m in ZWIDTH_METHODS}):
        say(line)
    first = next((float(b) for b in zw.damping if b > 0), None)
    guide = None if first is None else strictest_damper_guidance(devices, zw.wall.with_damping(first), zw.velocity)
    if guide is not None:
        note = criterion_damper_note(guide[1], zw, guide[0])
        if note:
            say(note)
    if zw.counterexamples:
        say(f"COUNTEREXAMPLES to the extended criterion: {len(zw.counterexamples)} (see --json)")
    if args.plot is not None:
        say(f"Z-width figure written to {args.plot}")
    return 0
