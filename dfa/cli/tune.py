"""``dfa tune``: the wall with the largest recommended stiffness among the elements allowed, and the trade-off.

Parses the device, the speed, the held wall elements and the lists of what may vary, calls :func:`dfa.tune`,
renders the table (:func:`dfa.render.tune.tune_screen`) and says how to export the best wall.
"""

from __future__ import annotations

import argparse
import os
import shlex
import sys
from collections.abc import Callable, Sequence
from typing import Any

from .._io import FIGURE_SUFFIXES, check_output_file
from ..model.loop import Loop
from ..model.wall import Wall
from .configurations import STIFFNESS, configuration_line, limiting, pinned
from .contact import add_contact_args
from .inputs import add_device_args, resolve, speed
from .output import add_progress_args, emit, save_png, working
from .parsing import UsageError, add_margin_arg, integer, number
from .walls import add_wall_args, wall_from_args, wall_json

COMMAND = "tune"
HELP = (
    "the wall with the largest recommended stiffness among the dampers, filters, delays, sample periods and "
    "passivity-controller limits allowed, and the trade-off with fidelity"
)
EXAMPLE = "dfa tune --device impulse --velocity 0.05"

#: The tuned elements' own flags, refused here: the lists say what is tried.
_TUNED = {
    "virtual_damping": ("--virtual-damping", "--dampings"),
    "velocity_filter": ("--velocity-filter", "--cutoffs"),
    "passivity_controller": ("--passivity-controller", "--pc-limits"),
}
#: This command's own options with a value, left out of the export command it prints.
_OWN = ("--dampings", "--cutoffs", "--delays", "--periods", "--pc-limits", "--evaluate", "--max-force-error",
        "--plot", "--delay", "--period", "--export")  # fmt: skip
#: --export's formats by the file's suffix.
_FORMATS = {".h": "c", ".yaml": "yaml", ".yml": "yaml", ".json": "json"}
_OWN_SWITCHES = ("--json", "--all", "--quiet", "--progress", "--allow-buzz")


def listed(
    flag: str, unit: str, *, none: bool = False, whole: bool = False, zero: bool = True
) -> Callable[[str], list[Any]]:
    """The parser of a comma-separated list of numbers >= 0 in ``unit`` (> 0 unless ``zero``; ``none`` allowed as a
    value where ``none``)."""
    one = integer(flag) if whole else number(flag, unit)

    def parse(text: str) -> list[Any]:
        items = [t.strip() for t in text.split(",")]
        if not all(items):
            raise argparse.ArgumentTypeError(f"{text[:40]!r} is invalid: {flag} takes values separated by commas")
        values = [None if (none and t.lower() == "none") else one(t) for t in items]
        for t, x in zip(items, values, strict=True):
            if x is not None and not (x > 0 or (zero and x == 0)):
                rule = ">= 0" if zero else "> 0"
                raise argparse.ArgumentTypeError(f"{t[:40]!r} is invalid: {flag} takes values {rule} in {unit}")
        return values

    parse.__name__ = flag
    return parse


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device, one speed, the held wall, what may vary, --plot and --all."""
    add_device_args(p, dimensionless=False, speed=True)
    add_wall_args(p)
    add_contact_args(p)
    g = p.add_argument_group("what may vary (each a comma-separated list; every combination is screened)")
    g.add_argument(
        "--dampings",
        type=listed("--dampings", "N·s/m (rotary N·m·s/rad)"),
        metavar="B,...",
        help="virtual dampers to try, N·s/m (rotary N·m·s/rad), 0 for none (default: 0 and the 1-2-5 "
        "values from the largest damper the criterion still proves some K with up to m/T)",
    )
    g.add_argument(
        "--cutoffs",
        type=listed("--cutoffs", "Hz", none=True, zero=False),
        metavar="HZ,...",
        help="velocity-filter cutoffs to try, Hz, 'none' for no filter (default: none and the 1-2-5 "
        "value below a tenth of the sample rate)",
    )
    g.add_argument(
        "--delays",
        type=listed("--delays", "samples", whole=True),
        metavar="D,...",
        help="computational delays to try, whole samples (default: --delay)",
    )
    g.add_argument(
        "--periods",
        type=listed("--periods", "s", zero=False),
        metavar="T,...",
        help="sample periods the hardware offers, s (default: the device's)",
    )
    g.add_argument(
        "--pc-limits",
        type=listed("--pc-limits", "N (rotary N·m)", zero=False),
        metavar="N,...",
        default=[],
        help="force limits of a passivity controller to try on the best wall, N (rotary N·m) (default: "
        "none tried; each takes tens of seconds)",
    )
    g.add_argument(
        "--evaluate",
        type=integer("--evaluate"),
        default=3,
        metavar="N",
        help="how many best-screened walls besides the plain one are simulated in full (default 3)",
    )
    g.add_argument("--max-force-error", type=_percent_or_none, default=50.0,
                   metavar="PCT", help="the best wall's largest force error, %% of the ideal spring's peak force, "
                   "or 'none' (default 50)")  # fmt: skip
    add_margin_arg(p)
    p.add_argument(
        "--allow-buzz",
        action="store_true",
        help="the best wall may be one that buzzes at its K (above "
        "its simulated rest limit) (default: the stiffest wall that comes to rest, where one does)",
    )
    add_progress_args(p)
    p.add_argument("--all", action="store_true", help="list the walls only screened too (default: the simulated)")
    p.add_argument("--plot", metavar="FILE", help="write the chart of K against force error to FILE: .png, .pdf or "
                   ".svg by its suffix (default: none)")  # fmt: skip
    p.add_argument("--export", metavar="FILE", help="write the best wall for the firmware to FILE, by its suffix: "
                   ".h (C99 header), .yaml or .json, as dfa export does (default: none)")  # fmt: skip
    p.set_defaults(tune_parser=p)  # the export command it prints leaves out this command's own options


def _refuse_tuned(args: argparse.Namespace) -> None:
    """The tuned elements' own flags are refused: the lists say what is tried."""
    for dest, (flag, instead) in _TUNED.items():
        if getattr(args, dest, None) not in (None, False):
            raise UsageError(f"{flag} is not taken here: the tuning varies it; give {instead}")
    if args.stiffness is not None:
        raise UsageError(
            "--stiffness is not taken here: the tuning searches K for each wall; drop it (dfa stiffness "
            "--stiffness K assesses one K)"
        )


def _percent_or_none(text: str) -> float | None:
    """--max-force-error: a number of per cent in (0, 100], or 'none'."""
    if text.strip().lower() == "none":
        return None
    value = number("--max-force-error", "per cent")(text)
    if not 0 < value <= 100:
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is invalid: --max-force-error takes a per cent in (0, 100] (e.g. 50) or 'none'"
        )
    return value


def export_command(
    argv: Sequence[str], parser: argparse.ArgumentParser, best: Any, device: Any, pin: Sequence[str] = ()
) -> str:
    """``dfa export`` with the device and speed flags given here and the best wall's flags: the same answer.

    The flags of this command alone (the lists, --plot, --json, ...) are left out; the best wall's delay, period,
    damper, filter and controller are appended. ``dfa export --velocity`` searches the same wall at the same speed
    with the same rule, so it recommends the same K. ``pin``: the flags of the device file's configuration tuned
    (``--configuration NAME`` and its ``--normal``, :func:`dfa.cli.configurations.pinned`), in place of any given.
    """
    takes = {s: a.nargs != 0 for a in parser._actions for s in a.option_strings}
    kept: list[str] = []
    i = 0
    while i < len(argv):
        tok = argv[i]
        flag = tok.split("=", 1)[0]
        own = flag in _OWN or flag in _OWN_SWITCHES or (bool(pin) and flag in ("--configuration", "--normal"))
        step = 2 if takes.get(flag, False) and "=" not in tok else 1
        if not own:
            kept += argv[i : i + step]
        i += step
    from ..render.tune import wall_flags

    kept += list(pin)
    return " ".join(["dfa", "export", *map(shlex.quote, kept), *wall_flags(best, device), "--format", "c",
                     "--out", "wall.h"])  # fmt: skip


def _check_cutoffs(args: argparse.Namespace, period: float) -> None:
    """--cutoffs below the Nyquist frequency of the longest period tried (refused before any work)."""
    longest = max(args.periods or [period])
    nyquist = 0.5 / longest
    for fc in args.cutoffs or []:
        if fc is not None and not fc < nyquist:
            raise UsageError(
                f"--cutoffs {fc:g} is invalid: a filter cutoff must lie below the Nyquist frequency {nyquist:.6g} Hz of "
                f"the longest period tried, {longest:g} s; give lower cutoffs, or none for no filter"
            )


def _write_export(args: argparse.Namespace, r: Any) -> str | None:
    """--export: the best wall written as dfa export writes it (format by the suffix); None when not asked.

    Without a best wall nothing is written (the command says so after the table, exit 1)."""
    best = r.best
    if args.export is None or best is None or best.recommendation is None:
        return None
    from .._io import atomic_write_text
    from ..render.export import export
    from ..results.deploy import DeployableWall
    from .export import command_line

    rec = best.recommendation
    dep = DeployableWall.from_recommendation(rec, command_line(args, COMMAND))
    fmt = _FORMATS[os.path.splitext(args.export)[1].lower()]
    atomic_write_text(args.export, export(dep, fmt))
    return str(args.export)


def run(args: argparse.Namespace) -> int:
    """Tune the wall, print the table (or JSON) and the export command."""
    from ..analysis.limits.recommend import check_margin
    from ..analysis.limits.tune import tune

    _refuse_tuned(args)
    inp = resolve(args, dimensionless=False, need_stiffness=False, configurations=True)
    dev = inp.device
    assert dev is not None
    _xd, v = speed(args, inp)
    if v is None or v <= 0:
        raise UsageError("the impact speed is missing: give --velocity V > 0 (m/s; rotary rad/s)")
    _check_cutoffs(args, dev.period)
    held = wall_from_args(args, dev, 1.0)
    wall = held if held is not None else Wall.of(1.0, delay=args.delay)
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
    if args.export is not None:
        check_output_file("--export", args.export, tuple(_FORMATS))
    check_margin(args.margin)
    if inp.configurations:  # the smallest recommended K with the held wall (dfa stiffness's rule), then tuned
        inp = limiting(args, inp, STIFFNESS, velocity=v, wall=wall, margin=args.margin)
        dev = inp.device
        assert dev is not None
    cap = None if args.max_force_error is None else args.max_force_error / 100.0
    with working(args):
        r = tune(Loop(dev, wall), v, dampings=args.dampings, cutoffs=args.cutoffs, delays=args.delays,
                 periods=args.periods, pc_limits=args.pc_limits, margin=args.margin, evaluate=args.evaluate,
                 max_force_error=cap, require_rest=not args.allow_buzz)  # fmt: skip
    if args.plot is not None:
        save_png("--plot", args.plot, r.plot())
    best = r.best
    argv = args.argv[args.argv.index(COMMAND) + 1 :]
    cmd = None if best is None else export_command(argv, args.tune_parser, best, dev, pinned(inp))
    written = _write_export(args, r)
    if args.json:
        out = r.to_dict()
        out["export_command"] = cmd
        out["export"] = written
        emit(wall_json(out, held, inp))
        return 0 if args.export is None or written is not None else 1
    from ..render.tune import tune_screen

    line = configuration_line(inp)
    if line is not None:
        print(line)
    print("\n".join(tune_screen(r, cmd, screened=args.all)))
    if args.plot is not None:
        print(f"chart of K against force error written to {args.plot}")
    if written is not None:
        print(f"the best wall written to {written}")
    if args.export is not None and written is None:
        print(f"dfa tune: --export {args.export}: nothing written: {r.status.message}", file=sys.stderr)
        return 1
    return 0
