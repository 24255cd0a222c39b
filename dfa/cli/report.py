"""``dfa report``: the design report of a device (HTML and/or Markdown with figures), spring or wall."""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import stat
from typing import Any

from .._io import check_output_folder, make_output_folder
from ..model.catalogue import DEFAULT_DEVICE
from ..model.loop import Loop
from ..model.wall import Wall
from .contact import add_contact_args
from .inputs import PHYS_FLAGS, add_device_args, resolve, speed
from .output import WORK_TIME_LIMIT, add_progress_args, check_work_time, emit, progress, say
from .parsing import UsageError, integer
from .passivity import add_passivity_args
from .walls import add_wall_args, wall_from_args

COMMAND = "report"
HELP = "design report of a device: verdict, limits, cycles, figures (HTML or Markdown)"
EXAMPLE = "dfa report --device phantom --velocity 0.1 --out reports --format both"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device (default: the built-in one), one speed, --out, --format, --validation, --zwidth and the wall."""
    json_help = "print the paths written and the numbers stated as one JSON object (default: one line per file)"
    add_device_args(p, False, True, json_help)
    p.add_argument(
        "--out",
        default="reports",
        metavar="DIR",
        help="output folder, created if missing (its parent must exist; default: reports)",
    )
    p.add_argument(
        "--format",
        choices=["html", "md", "both"],
        default="html",
        help="html (self-contained), md (with PNGs in DIR/figures) or both (default: html)",
    )
    p.add_argument(
        "--validation",
        metavar="FILE.json",
        help="validation summary for the 'how far to trust' paragraph, as written by `dfa validate` (default: none)",
    )
    p.add_argument(
        "--force",
        action="store_true",
        help="replace a report of the same name made for another device, stiffness, speed or delay, and run a "
        f"--zwidth grid estimated over {WORK_TIME_LIMIT:g} s (default: refuse both)",
    )
    p.add_argument(
        "--zwidth",
        type=integer("--zwidth"),
        metavar="N",
        help="Z-width section on an N x N grid (K against virtual damping B; default: none for the spring, "
        "16 with a wall flag; 0: none)",
    )
    p.add_argument(
        "--tune",
        action="store_true",
        help="add the deployable wall: dfa tune with its default lists at this speed, and the dfa export command that "
        "writes the best wall (about 40 s; default: none)",
    )
    add_progress_args(p)
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)


#: Largest validation summary ``--validation`` reads (bytes); ``dfa validate`` writes about 8 kB.
VALIDATION_MAX_BYTES = 1_000_000


def _read_validation(path: str) -> dict[str, Any]:
    """A validation summary the user names (``dfa validate`` writes it as validation.json).

    Only a regular file of at most :data:`VALIDATION_MAX_BYTES` is read: ``/dev/zero`` or a pipe is refused
    before it is opened, not read until memory runs out.
    """
    fix = "give the validation.json that `dfa validate --out DIR` wrote"
    try:
        st = os.stat(path)
    except (OSError, ValueError) as exc:
        why = exc.strerror if isinstance(exc, OSError) else "not a path"
        raise UsageError(f"--validation {path!r} cannot be read ({why}): {fix}") from None
    if not stat.S_ISREG(st.st_mode):
        raise UsageError(f"--validation {path!r} is not a regular file: {fix}")
    if st.st_size > VALIDATION_MAX_BYTES:
        raise UsageError(
            f"--validation {path!r} is too large ({st.st_size} bytes; a validation summary is about 8 kB, at most "
            f"{VALIDATION_MAX_BYTES} bytes are read): {fix}"
        )
    try:
        with open(path, "rb") as fh:
            data = json.loads(fh.read(VALIDATION_MAX_BYTES + 1).decode("utf-8"))
    except (OSError, ValueError) as exc:  # UnicodeDecodeError and JSONDecodeError are ValueErrors
        why = exc.strerror if isinstance(exc, OSError) else "not JSON"
        raise UsageError(f"--validation {path!r} cannot be read ({why}): {fix}") from None
    if not isinstance(data, dict) or "soundness_violations" not in data:
        raise UsageError(
            f"--validation {path!r} is not a validation summary: give the validation.json that `dfa validate` wrote"
        )
    return data


def _limiting(inp: Any, wall: Wall, v: float | None) -> tuple[Loop, Any]:
    """A device file's configurations answered (:func:`dfa.analysis.configurations.worst_stiffness`) and the loop of
    the limiting one (its device, the wall at the file's K), for its report."""
    from ..analysis.configurations import worst_stiffness

    if v is None or not v > 0:
        raise UsageError(
            "a device file with configurations needs --velocity V > 0 (the limiting configuration is the "
            "one with the smallest recommended K at V), or --configuration NAME"
        )
    worst = worst_stiffness(inp.device, inp.configurations, v, wall=wall.with_stiffness(1.0))
    ans, _rec = worst.details
    limiting = dataclasses.replace(ans.device, name=f"{inp.device.name} ({worst.limiting})")
    return Loop(limiting, wall), worst


def run(args: argparse.Namespace) -> int:
    """Write the report; print the paths written (or, with --json, the paths and the numbers stated)."""
    from ..studies.design import resolve_design_inputs
    from ..studies.report import design_report

    if (
        args.device is None
        and args.device_file is None
        and not any(getattr(args, k, None) is not None for k in (*PHYS_FLAGS, "counts"))
    ):
        args.device = DEFAULT_DEVICE
    check_output_folder("--out", args.out, create=True)  # created (one level) once the inputs pass
    inp = resolve(args, dimensionless=False, configurations=True)
    assert inp.device is not None
    ctl = wall_from_args(args, inp.device, inp.stiffness)  # None: the spring (no flag, or B = 0 without filter/lag)
    if args.zwidth is not None and args.zwidth < 0:
        raise UsageError(f"--zwidth {args.zwidth} is invalid: give the points per axis (0: no Z-width section)")
    _xd, v = speed(args, inp, required=False)
    summary = _read_validation(args.validation) if args.validation is not None else None
    assert inp.stiffness is not None  # resolve() refuses a device without K here
    wall = ctl if ctl is not None else Wall.of(inp.stiffness, delay=args.delay)
    _entry, loop, _v = resolve_design_inputs(inp.entry or inp.device, wall, v)  # refused before any output (issue 27)
    if args.zwidth and v is not None and v > 0:
        from ..analysis.limits.zwidth import check_zwidth_size, z_width_seconds

        check_zwidth_size(args.zwidth, names=("--zwidth", "--speeds"))  # before any section runs
        seconds = z_width_seconds(loop, v, grid=args.zwidth, speeds=1)
        check_work_time(f"--zwidth {args.zwidth}", seconds, "lower --zwidth", args.force)
    worst = None
    if inp.configurations:  # the limiting configuration's report, with a row per configuration
        loop, worst = _limiting(inp, wall, v)
    make_output_folder("--out", args.out)
    res = design_report(
        loop, v, entry=None if worst is not None else inp.entry, out_dir=args.out, fmt=args.format,
        progress=progress(args), validation=summary, force=args.force, zwidth_grid=args.zwidth, tune=args.tune,
        configurations=worst,
    )  # fmt: skip
    if args.json:
        emit(res.to_dict(), ensure_ascii=False)
        return 0
    for pth in res.paths:
        say(f"written {pth}")
    return 0
