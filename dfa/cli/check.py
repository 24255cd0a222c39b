"""``dfa check``: the passivity criterion and its region at an impact speed (eq. 6-12), spring or wall."""

from __future__ import annotations

import argparse
from typing import Any

from ..analysis.criterion import criterion_from_groups, device_criterion
from ..model.loop import Loop
from ..model.wall import Wall, WallParams
from .configurations import add_configurations_plot_arg, check_configurations_plot, write_configurations_plot
from .contact import add_contact_args
from .inputs import Inputs, add_device_args, resolve, speed
from .output import emit, say, table
from .parsing import UsageError, number
from .passivity import add_passivity_args
from .walls import add_wall_args, print_wall, wall_from_args, wall_json

COMMAND = "check"
#: The flags of the dimensionless inputs, as the criterion's messages name them.
_FLAGS = {"beta": "--beta", "sigma": "--sigma", "xi_dot": "--xi-dot"}
HELP = "passivity criterion and region at an impact speed (eq. 6-12)"
EXAMPLE = "dfa check --device delta --velocity 0.1"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device or (β, σ), one speed, the wall, the start position and --no-quantization."""
    add_device_args(p, dimensionless=True, speed=True)
    p.add_argument("--no-quantization", action="store_true", help="use eq. 7 (Δ → 0) instead of eq. 6 (default: eq. 6)")
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)
    add_configurations_plot_arg(p)
    p.add_argument(
        "--xi0",
        type=number("--xi0", "ticks"),
        metavar="X",
        help="initial position ξ0 in ticks (dimensionless input; needs --mu); default: 0",
    )
    p.add_argument(
        "--position",
        type=number("--position", "m (rotary: rad)"),
        metavar="X",
        help="initial position in m (rotary: rad; device input); default: 0",
    )
    p.add_argument(
        "--history",
        choices=("fresh", "moving"),
        default="fresh",
        help="the loop's memory at t = 0: fresh (default: as if at rest there) or moving (the device moved at the "
        "speed for the d samples before; the spring with a delay, needs --mu without a device)",
    )


def _criterion(args: argparse.Namespace, inp: Inputs, xd: float, v: float | None) -> Any:
    """The criterion: device mode takes --position (m, rad), dimensionless mode --xi0 (ticks)."""
    quantized = not args.no_quantization
    if inp.device is not None:
        assert inp.stiffness is not None  # a device always comes with its K (resolve)
        if args.xi0 is not None:
            raise UsageError(
                "--xi0 is for dimensionless input: with a device give the initial position as --position (m, rad)"
            )
        vel = inp.device.velocity(xd) if v is None else v
        if args.position is not None:
            inp.device.xi(args.position, "--position")  # x/Δ overflowing: refused naming the flag
        spring = Wall.of(inp.stiffness, delay=args.delay)
        return device_criterion(
            Loop(inp.device, spring), vel, quantized=quantized, position=args.position or 0.0, history=args.history
        )
    if args.position is not None:
        raise UsageError(
            "--position needs a physical device: with --beta --sigma give the initial position as --xi0 (ticks)"
        )
    x0 = 0.0 if args.xi0 is None else args.xi0
    if x0 != 0.0 and args.mu is None:
        raise UsageError(
            f"--xi0 {x0:g} needs --mu: the spring energy enters the speed as 2H_c(ξ0)/μ; give --mu m/(K T²)"
        )
    groups = WallParams.of(delay=args.delay)
    if args.history == "moving" and args.delay and args.mu is None:
        raise UsageError("--history moving needs --mu: the pending commands' work enters through μ; give --mu")
    return criterion_from_groups(  # --mu is optional: the groups, not a loop
        inp.beta, inp.sigma, xd, wall=groups, quantized=quantized, xi0=x0, mu=args.mu, names=_FLAGS,
        history=args.history,
    )  # fmt: skip


def _check_wall(args: argparse.Namespace, inp: Inputs, wall: Wall, xd: float, v: float | None) -> int:
    """With a wall beyond a spring: the criterion with it and Colgate–Schenkel; with a lag, not covered."""
    from ..analysis.check import passivity_check
    from ..render.controller import check_table_rows

    dev = inp.device
    assert dev is not None  # wall_from_args refuses a wall without a device
    if args.xi0 is not None:
        raise UsageError(
            "--xi0 is for dimensionless input: with a device give the initial position as --position (m, rad)"
        )
    if args.history != "fresh":
        raise UsageError(
            f"--history {args.history} is derived for the spring with a delay only (a damper's or filter's memory, "
            "a one-sided wall's approach and a hand stiffness are other cases); drop it, or the wall, contact and "
            "hand-stiffness flags"
        )
    vel = dev.velocity(xd) if v is None else v
    if args.position is not None:
        dev.xi(args.position, "--position")  # x/Δ overflowing: refused naming the flag
    chk = passivity_check(Loop(dev, wall), vel, position=args.position or 0.0, quantized=not args.no_quantization)
    if args.json:
        emit(wall_json(chk.to_dict(), wall, inp))
        return 0
    say(inp.label)
    print_wall(wall, inp)
    say(table(check_table_rows(chk)))
    return 0


def run(args: argparse.Namespace) -> int:
    """Print the criterion's region, verdict, margin and critical speed (and Colgate–Schenkel with a wall)."""
    from ..render.text import check_rows

    inp = resolve(args, dimensionless=True, need_mu=False, configurations=True)
    check_configurations_plot(args, inp)
    xd, v = speed(args, inp)
    assert xd is not None
    wall = wall_from_args(args, inp.device, inp.stiffness)
    if inp.configurations:  # a device file's configurations: the smallest margin of them
        return _worst(args, inp, wall, xd, v)
    if wall is not None:
        return _check_wall(args, inp, wall, xd, v)
    r = _criterion(args, inp, xd, v)
    if args.json:
        emit(wall_json(r.to_dict(), None, inp))  # the spring's record; with a device's travel, the travel
        return 0
    vu = inp.device.units["velocity"] if inp.device else ""
    say(inp.label)
    print_wall(None, inp)  # the spring: nothing, but a device's travel and what the verdict assumes
    say(table(check_rows(r, not args.no_quantization, vu)))
    return 0


def _worst(args: argparse.Namespace, inp: Inputs, wall: Wall | None, xd: float, v: float | None) -> int:
    """The criterion's margin of every configuration of the device file at K, the limiting one named and its
    check (:func:`dfa.analysis.configurations.worst_check`)."""
    from ..analysis.configurations import worst_check
    from ..formatting import text_table
    from ..render.configurations import configuration_header, configuration_rows, limiting_line
    from ..render.controller import check_table_rows
    from ..render.text import check_rows

    dev = inp.device
    assert dev is not None and inp.stiffness is not None
    if args.xi0 is not None:
        raise UsageError(
            "--xi0 is for dimensionless input: with a device give the initial position as --position (m, rad)"
        )
    vel = dev.velocity(xd) if v is None else v
    if args.position is not None:
        dev.xi(args.position, "--position")  # x/Δ overflowing: refused naming the flag
    if wall is not None and args.history != "fresh":
        raise UsageError(
            f"--history {args.history} is derived for the spring with a delay only; drop it or the wall flags"
        )
    loop_wall = wall if wall is not None else Wall.of(inp.stiffness, delay=args.delay)
    kw: dict[str, Any] = dict(position=args.position or 0.0, quantized=not args.no_quantization)
    if args.history != "fresh":
        kw["history"] = args.history
    w = worst_check(dev, inp.configurations, vel, loop_wall, **kw)
    (detail,) = w.details
    figure = write_configurations_plot(args, w)
    if args.json:
        out = w.to_dict()
        out["check"] = detail.to_dict()
        if figure is not None:
            out["configurations_plot"] = figure
        emit(wall_json(out, wall, inp))
        return 0
    say(inp.label)
    print_wall(wall, inp)
    say(text_table(configuration_rows(w), configuration_header(w)))  # a row a line, however wide
    say(limiting_line(w))
    say()
    vu = dev.units["velocity"]
    rows = check_rows(detail, not args.no_quantization, vu) if hasattr(detail, "region") else check_table_rows(detail)
    say(table(rows))
    if figure is not None:
        say(f"configurations figure written to {figure}")
    return 0
