"""``dfa export``: the chosen or given wall as the firmware takes it (issue 44): a C99 header, YAML or JSON.

The wall is the flags' (as ``dfa stiffness`` reads them) at ``--stiffness K`` (rule ``given``), or at the K
recommended for ``--velocity V`` (``design_answer`` and ``recommend_stiffness``, as ``dfa stiffness`` runs them), or a
wall to deploy read back from JSON (``--from FILE.json``: ``dfa export --format json``'s). The text goes to stdout, or
to ``--out FILE`` (written atomically).
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import sys
from dataclasses import replace
from typing import TYPE_CHECKING

from .._io import atomic_write_text, check_output_file
from ..errors import DFAError
from ..model.loop import Loop
from ..model.wall import Wall
from .configurations import MARGIN, STIFFNESS, configuration_line, limiting
from .contact import add_contact_args
from .inputs import Inputs, add_device_group, device_given, resolve, speed
from .output import working
from .parsing import UsageError, add_margin_arg, number
from .passivity import add_passivity_args
from .walls import add_wall_args, given_flags, wall_from_args

if TYPE_CHECKING:
    from ..results.deploy import DeployableWall
    from ..results.require import Recommendation

COMMAND = "export"
HELP = (
    "the chosen or given wall for the firmware: a C99 header with a reference implementation, a YAML parameter "
    "file or JSON, with its provenance"
)
EXAMPLE = "dfa export --device impulse --stiffness 100 --virtual-damping 0.5 --format c --out wall.h"
#: Each format's file suffix (``--out``).
SUFFIXES = {"c": (".h",), "yaml": (".yaml", ".yml"), "json": (".json",)}


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device, the wall, the speed or K, --from, --format, --out and --margin."""
    add_device_group(p, "device (a catalogue name, or physical values in SI units)")
    s = p.add_argument_group("the stiffness (one of: --stiffness K above, --velocity, --from)")
    s.add_argument(
        "--velocity",
        type=number("--velocity", "m/s (rotary: rad/s)"),
        metavar="V",
        help="impact speed in m/s (rotary: rad/s): export the K recommended for it (as dfa stiffness recommends; "
        "refused when no rule gives one); default: none",
    )
    s.add_argument(
        "--from",
        dest="source",
        metavar="FILE.json",
        help="a wall to deploy read back from JSON (dfa export --format json writes one), instead of the device, "
        "wall and stiffness flags; default: none",
    )
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)
    add_margin_arg(p, "with --velocity: ")
    p.add_argument(
        "--format",
        choices=("c", "yaml", "json"),
        default=None,
        help="c: a self-contained C99 header (constants and the wall's reference implementation); yaml: a parameter "
        "file for ros2_control-style configurations; json: the record --from reads (default: by the suffix of "
        "--out, .h, .yaml/.yml or .json; c on stdout)",
    )
    p.add_argument(
        "--out",
        metavar="FILE",
        help="write to FILE (.h, .yaml or .json by --format; replaced atomically) (default: stdout)",
    )


def command_line(args: argparse.Namespace, command: str = COMMAND) -> str:
    """The command line that runs now, as ``dfa <command> ...`` (quoted for a shell; the argv the parser read)."""
    argv = list(getattr(args, "argv", sys.argv[1:]))
    if command in argv:
        argv = argv[argv.index(command) + 1 :]
    return shlex.join(["dfa", command, *argv])


def _from_file(args: argparse.Namespace) -> DeployableWall:
    """The wall to deploy of --from FILE.json; refused (exit 2) beside device or wall flags, or unreadable."""
    from ..results.deploy import DeployableWall

    others = (["device flags"] if device_given(args) else []) + given_flags(args)
    others += ["--velocity"] if args.velocity is not None else []
    if others:
        raise UsageError(
            f"--from {args.source!r} cannot be combined with {', '.join(others)}: the file holds the device, the "
            "wall and its stiffness; drop them, or drop --from"
        )
    path = args.source
    if not os.path.isfile(path):
        raise UsageError(
            f"--from {path!r} is invalid: no such file; give a JSON file written by dfa export --format json"
        )
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
        return DeployableWall.from_dict(data)
    except (ValueError, KeyError, TypeError, DFAError) as err:
        raise UsageError(
            f"--from {path!r} is invalid: {err}; give a JSON file written by dfa export --format json"
        ) from None


def _recommended(args: argparse.Namespace, loop: Loop, v: float, command: str) -> DeployableWall:
    """The K recommended for the speed ``v`` (dfa stiffness's rule), as a wall to deploy; refused without one."""
    from ..analysis.limits.kmax import design_answer
    from ..analysis.limits.recommend import recommend_stiffness
    from ..model.elements import PassivityController

    with working(args):
        ans = design_answer(loop, v)
        plain = None
        if ans.wall.element(PassivityController) is not None:
            plain = design_answer(Loop(loop.device, ans.wall.without_controller()), v)
        rec = recommend_stiffness(ans, args.margin, plain=plain)
    return _deployable(v, rec, command)


def _deployable(v: float, rec: Recommendation, command: str) -> DeployableWall:
    """The recommended K as a wall to deploy; refused (exit 2) without one."""
    from ..results.deploy import DeployableWall

    if rec.k_recommended is None:
        raise UsageError(
            f"--velocity {v:g}: no K to export: {rec.status.message}; give the stiffness with --stiffness K "
            "(rule 'given')"
        )
    return DeployableWall.from_recommendation(rec, command)


def deployable(args: argparse.Namespace) -> DeployableWall:
    """The wall to deploy of the flags: --from, --stiffness (given) or --velocity (recommended)."""
    from ..analysis.limits.recommend import check_margin
    from ..results.deploy import DeployableWall

    if args.source is not None:
        dep = _from_file(args)
        made = "" if dep.command is None else f" (the wall of: {dep.command})"
        return replace(dep, command=command_line(args) + made)
    if args.velocity is not None and args.stiffness is not None:
        raise UsageError(
            "--velocity and --stiffness cannot both be given: give --stiffness K to export that K, or --velocity V "
            "to export the K recommended for V"
        )
    args.xi_dot = None  # dfa.cli.inputs.speed reads it; export takes speeds in physical units only
    inp = resolve(args, dimensionless=False, need_stiffness=args.velocity is None, configurations=True)
    dev = inp.device
    assert dev is not None
    command = command_line(args)
    k = inp.stiffness
    if args.velocity is None:
        assert k is not None
        if args.stiffness is None:  # the device file's or the catalogue's K: said, not silent
            print(f"dfa export: no --stiffness or --velocity: the device's own K = {k:g} {dev.units['stiffness']}, "
                  "rule 'given'", file=sys.stderr)  # fmt: skip
        ctl = wall_from_args(args, dev, k)
        if inp.configurations:  # K given: the smallest margin at speed 0, σ − σ₀ (dfa check's rule)
            inp = _limiting(args, limiting(args, inp, MARGIN, wall=ctl))
            dev = inp.device
            assert dev is not None
            ctl = wall_from_args(args, dev, k)
        wall = ctl if ctl is not None else Wall.of(k, delay=args.delay)
        return DeployableWall.given(Loop(dev, wall), command)
    _xd, v = speed(args, inp)
    assert v is not None
    if not v > 0:
        raise UsageError(f"--velocity {v:g} is invalid for an export: the recommended K needs an impact speed > 0")
    check_margin(args.margin)
    ctl = wall_from_args(args, dev, 1.0)  # K is what is searched: any K states the elements
    wall = ctl if ctl is not None else Wall.of(1.0, delay=args.delay)
    if inp.configurations:  # K searched: the smallest recommended K (dfa stiffness's rule), its answer exported
        inp = _limiting(args, limiting(args, inp, STIFFNESS, velocity=v, wall=wall, margin=args.margin))
        assert inp.worst is not None
        return _deployable(v, inp.worst.details[1], command)
    return _recommended(args, Loop(dev, wall), v, command)


def _limiting(args: argparse.Namespace, inp: Inputs) -> Inputs:
    """The limiting configuration named on stderr (stdout may be the export itself)."""
    line = configuration_line(inp)
    if line is not None:
        print(f"dfa export: {line}", file=sys.stderr)
    return inp


def run(args: argparse.Namespace) -> int:
    """Export the wall: the text on stdout, or in --out."""
    from ..render.export import export

    if args.format is None:  # by the file's suffix; c on stdout or an unknown suffix (refused just below)
        suffix = os.path.splitext(args.out or "")[1].lower()
        args.format = next((f for f, sfx in SUFFIXES.items() if suffix in sfx), "c")
    if args.out is not None:
        check_output_file("--out", args.out, SUFFIXES[args.format])
    dep = deployable(args)
    text = export(dep, args.format)
    if args.out is None:
        sys.stdout.write(text)
    else:
        atomic_write_text(args.out, text)
        print(f"{args.format} export of K = {dep.stiffness:.6g} {dep.device.units['stiffness']} ({dep.rule.value}) "
              f"written to {args.out}")  # fmt: skip
    return 0
