"""``dfa require``: the inverse question, what each parameter must be for a target stiffness at a speed."""

from __future__ import annotations

import argparse

from ..model.wall import Wall
from ..results.codes import REQUIRE_PARAMETERS
from .configurations import MARGIN, limiting
from .inputs import add_device_args, resolve, speed
from .output import emit, working
from .parsing import UsageError
from .walls import add_wall_args, print_wall, wall_from_args, wall_json

COMMAND = "require"
HELP = (
    "the inverse question: what the sample period, encoder, friction, damping, virtual damper or delay must be "
    "for a target stiffness at an impact speed"
)
EXAMPLE = "dfa require --device delta --stiffness 20000 --velocity 0.1"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device, the target stiffness (--stiffness), one speed and the wall held fixed."""
    add_device_args(p, dimensionless=False, speed=True)
    add_wall_args(p)
    p.add_argument(
        "--describing-function",
        action="store_true",
        help="also answer by the describing function (a K search per value tried: tens of seconds; "
        "default: the criterion and the linear loop)",
    )
    p.add_argument(
        "--parameter",
        action="append",
        choices=list(REQUIRE_PARAMETERS),
        metavar="NAME",
        help=f"only this parameter (repeatable; one of {', '.join(REQUIRE_PARAMETERS)}; default: all)",
    )


def run(args: argparse.Namespace) -> int:
    """Each parameter by the criterion (a proof) and by the linear loop (necessary), the others held."""
    from ..analysis.limits.require import METHODS, requirements

    inp = resolve(args, dimensionless=False, need_stiffness=False, configurations=True)
    if args.stiffness is None:
        raise UsageError("the target stiffness is missing: give --stiffness K in N/m (rotary: N·m/rad)")
    k = float(args.stiffness)
    _xd, v = speed(args, inp)
    assert v is not None
    if inp.configurations:  # the target K is given: the smallest margin there (dfa check's rule)
        inp = limiting(args, inp, MARGIN, velocity=v, wall=wall_from_args(args, inp.device, k))
    dev = inp.device
    assert dev is not None
    ctl = wall_from_args(args, dev, k)
    wall = ctl if ctl is not None else Wall.of(k, delay=args.delay)
    methods = (*METHODS, "df") if args.describing_function else METHODS
    names = tuple(args.parameter) if args.parameter else REQUIRE_PARAMETERS
    with working(args):
        req = requirements(dev, k, v, wall=wall, methods=methods, parameters=names)
    if args.json:
        emit(wall_json(req.to_dict(), ctl, inp))
        return 0
    from ..render.require import require_screen

    lines = require_screen(req)
    print(lines[0])
    print_wall(ctl, inp)
    print("\n".join(lines[1:]))
    return 0
