"""``dfa identify``: a device's mass, damping, Coulomb friction, resolution and period from a logged run."""

from __future__ import annotations

import argparse

from .._io import FIGURE_SUFFIXES, check_output_file
from ..errors import DFAError
from ..plausibility import warn_implausible
from .output import emit, save_png, say
from .parsing import UsageError, name, number

COMMAND = "identify"
HELP = "identify a device (m, b, c, Δ, T) from a logged run (CSV with t, x, f)"
EXAMPLE = "dfa identify examples/logs/delta_chirp.csv --stiffness 14500"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The log, the grid when known, a wall to close the loop with, and the outputs."""
    p.add_argument("log", metavar="LOG.csv", help="the log: a CSV file with a header naming t (s), x (m), f (N)")
    p.add_argument("--resolution", type=number("--resolution", "m (rotary: rad)"), metavar="X",
                   help="encoder resolution Δ in m (rotary rad); default: from the readings")  # fmt: skip
    p.add_argument("--period", type=number("--period", "s"), metavar="X",
                   help="sample period T in s; default: from the times")  # fmt: skip
    p.add_argument("--rotary", action="store_true", help="the log is in rad and N·m (default: m and N)")
    p.add_argument("--name", type=name, metavar="TEXT", help="name of the identified device (default: from the file)")
    p.add_argument("--stiffness", type=number("--stiffness", "N/m"), metavar="K",
                   help="close the loop: K_max four ways of the identified device (as `dfa stiffness`), a wall "
                   "of stiffness K in N/m (rotary N·m/rad) assessed; default: none")  # fmt: skip
    p.add_argument("--velocity", type=number("--velocity", "m/s"), metavar="V",
                   help="impact speed for --stiffness in m/s (rad/s); default: the log's peak speed")  # fmt: skip
    p.add_argument("--plot", metavar="FILE", help="write the log against the identified model to FILE (.png, .pdf, "
                   ".svg); default: none")  # fmt: skip
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout (default: text)")


def _positive(flag: str, value: float | None) -> float | None:
    if value is not None and not value > 0.0:
        raise UsageError(f"{flag} {value:g} is invalid: it must be a number > 0")
    return value


def run(args: argparse.Namespace) -> int:
    """Read the log, identify, optionally close the loop; print the result (text or JSON)."""
    from ..analysis.identify import identify
    from ..analysis.limits.kmax import design_answer
    from ..analysis.limits.recommend import recommend_stiffness
    from ..model.log import read_log
    from ..render.answer import stiffness_screen
    from ..render.identify import identify_lines, loop_head

    for flag in ("--resolution", "--period", "--stiffness"):
        _positive(flag, getattr(args, flag[2:]))
    if args.velocity is not None and args.stiffness is None:
        raise UsageError("--velocity needs --stiffness: it is the impact speed of the wall the device is checked with")
    if args.velocity is not None and not args.velocity >= 0.0:
        raise UsageError(f"--velocity {args.velocity:g} is invalid: give the impact speed, >= 0")
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
    try:
        log = read_log(args.log, rotary=args.rotary)
    except DFAError as err:
        raise UsageError(str(err)) from None
    r = identify(log, resolution=args.resolution, period=args.period, name=args.name)
    for key, hint in (("mass", None), ("resolution", "positions in encoder counts? give x in m (rad)"),
                      ("period", "times in ms? give t in s")):  # fmt: skip
        warn_implausible(key, getattr(r.device, key), rotary=args.rotary, subject=f"identified {key}", hint=hint)
    out = r.to_dict()
    lines = identify_lines(r)
    if args.stiffness is not None:  # K_max four ways of the identified device, the given K assessed
        v = r.velocity_peak if args.velocity is None else args.velocity
        ans = design_answer(r.device, v, wall=args.stiffness, assess=True)
        rec = recommend_stiffness(ans)
        out["loop"] = ans.to_dict() | {"recommendation": rec.to_dict()}
        lines += loop_head(r, v, args.velocity is None) + stiffness_screen(ans, rec)
    if args.plot is not None:
        written = save_png("--plot", args.plot, r.plot()[0])
        lines.append(f"written {written}")
    if args.json:
        emit(out, ensure_ascii=False)
        return 0
    for line in lines:
        say(line)
    return 0
