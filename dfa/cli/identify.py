"""``dfa identify``: a device's mass, damping, Coulomb friction, resolution and period from a logged run."""

from __future__ import annotations

import argparse
import math
import sys
from typing import Any

from .._io import FIGURE_SUFFIXES, check_output_file, check_output_folder, make_output_folder
from ..errors import DFAError
from ..plausibility import warn_implausible
from .output import add_progress_args, emit, progress, save_png, say
from .parsing import UsageError, delay, integer, name, number

COMMAND = "identify"
HELP = "identify a device (m, b, c, Δ, T) from a logged run (CSV with t, x, f)"
EXAMPLE = "dfa identify examples/logs/delta_chirp.csv --stiffness 14500"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The log, the grid when known, a wall to close the loop with, and the outputs."""
    from ..analysis.identify import BOOTSTRAP  # here: the other commands' start-up does not load the fit

    p.add_argument("log", metavar="LOG.csv", help="the log: a CSV file with a header naming t (s), x (m), f (N)")
    p.add_argument("--resolution", type=number("--resolution", "m (rotary: rad)"), metavar="X",
                   help="encoder resolution Δ in m (rotary rad); default: from the readings")  # fmt: skip
    p.add_argument("--period", type=number("--period", "s"), metavar="X",
                   help="sample period T in s; default: from the times")  # fmt: skip
    p.add_argument("--rotary", action="store_true", help="the log is in rad and N·m (default: m and N)")
    p.add_argument("--columns", type=_columns, metavar="t=NAME,x=NAME,f=NAME",
                   help="the header's names of the time, position and force columns (default: t, x, f)")  # fmt: skip
    for c, what, example in (("t", "times", "ms"), ("x", "positions", "mm, or counts with --resolution"),
                             ("f", "forces", "mN")):  # fmt: skip
        p.add_argument(f"--{c}-unit", metavar="UNIT", help=f"unit of the {what} when the header gives none "
                       f"(e.g. {example}); default: the header's, else SI")  # fmt: skip
    p.add_argument("--write-device", metavar="FILE.toml", help="write the identified device as a device file (the "
                   "catalogue's format, the intervals in its notes) that every command takes with --device-file; "
                   "default: none")  # fmt: skip
    p.add_argument("--name", type=name, metavar="TEXT", help="name of the identified device (default: from the file)")
    p.add_argument("--stiffness", type=number("--stiffness", "N/m"), metavar="K",
                   help="close the loop: K_max four ways of the identified device with b and c at the lower ends of "
                   "their 95 %% intervals (as `dfa stiffness`), a wall "
                   "of stiffness K in N/m (rotary N·m/rad) assessed, and a sustained oscillation in a log of that "
                   "wall set next to the predicted limit cycles; default: none")  # fmt: skip
    g = p.add_argument_group("the wall the log was taken with (default: a free-motion log)")
    g.add_argument("--wall-on", action="store_true", help="the log was taken with the wall of --stiffness on "
                   "(and --virtual-damping, --delay, --one-sided; x in the wall's frame, the wall at x = 0 occupying "
                   "x >= 0; f the force it applied): check f against that wall's law and set the logged contact "
                   "beside the exact simulation of the identified device with that wall; default: off")  # fmt: skip
    g.add_argument("--virtual-damping", type=number("--virtual-damping", "N·s/m"), metavar="B",
                   help="with --wall-on: the wall's virtual damper in N·s/m (rotary N·m·s/rad) on the "
                   "backward-difference velocity (default: none)")  # fmt: skip
    g.add_argument("--delay", type=delay, default=0, metavar="D", help="with --wall-on: the wall's computational "
                   "delay in whole samples: the force of sample h uses the reading of sample h − D (default 0)")  # fmt: skip
    g.add_argument("--one-sided", action="store_true", help="with --wall-on: the wall pushes only while the reading "
                   "is inside (x >= 0) and never pulls (default: the paper's bilateral spring)")  # fmt: skip
    p.add_argument("--velocity", type=number("--velocity", "m/s"), metavar="V",
                   help="impact speed for --stiffness in m/s (rad/s); default: the log's peak speed")  # fmt: skip
    p.add_argument("--bootstrap", type=integer("--bootstrap"), default=BOOTSTRAP, metavar="N",
                   help=f"replicate fits that set the 95 %% intervals (default {BOOTSTRAP}; each costs one fit; 0: "
                   "the fit's Jacobian alone, too narrow)")  # fmt: skip
    p.add_argument("--report", metavar="DIR", help="with --stiffness: write the design report of the identified "
                   "device and that wall to DIR (HTML, as `dfa report`); default: none")  # fmt: skip
    p.add_argument("--force", action="store_true", help="with --report: replace a report of the same name made for "
                   "another device (default: refuse)")  # fmt: skip
    p.add_argument("--plot", metavar="FILE", help="write the log against the identified model to FILE (.png, .pdf, "
                   ".svg); default: none")  # fmt: skip
    p.add_argument("--explain", action="store_true", help="the full evidence: the fit and each warning in words, "
                   "the noise, K_max four ways with its notes, the contact in full (default: one screen, lines under "
                   "100 characters)")  # fmt: skip
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout (default: text)")
    add_progress_args(p)


def _columns(text: str) -> dict[str, str]:
    """``t=time,x=pos,f=force``: the header's name of each column."""
    out: dict[str, str] = {}
    for part in text.split(","):
        key, sep, value = part.partition("=")
        key, value = key.strip().lower(), value.strip()
        if not sep or key not in ("t", "x", "f") or not value or key in out:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not t=NAME,x=NAME,f=NAME: give each of t, x, f at most once, with its name as the "
                "header writes it"
            )
        out[key] = value
    return out


def _positive(flag: str, value: float | None) -> float | None:
    if value is not None and not value > 0.0:
        raise UsageError(f"{flag} {value:g} is invalid: it must be a number > 0")
    return value


def _report(args: argparse.Namespace, device: Any, velocity: float) -> dict[str, Any]:
    """The design report of the identified device and the wall of --stiffness (as `dfa report`), written to --report."""
    from ..model.loop import Loop
    from ..model.wall import Wall
    from ..studies.report import design_report

    make_output_folder("--report", args.report)
    res = design_report(Loop(device, Wall.of(args.stiffness)), velocity, out_dir=args.report, fmt="html",
                        progress=progress(args), force=args.force)  # fmt: skip
    return dict(res.to_dict())


def _check_flags(args: argparse.Namespace) -> None:
    """Refuse flag values and combinations that cannot run, before the log is read."""
    for flag in ("--resolution", "--period", "--stiffness"):
        _positive(flag, getattr(args, flag[2:]))
    for flag, needs in (("--velocity", "--stiffness"), ("--report", "--stiffness"), ("--force", "--report"),
                        ("--wall-on", "--stiffness"), ("--virtual-damping", "--wall-on"), ("--delay", "--wall-on"),
                        ("--one-sided", "--wall-on")):  # fmt: skip
        if getattr(args, _dest(flag), None) not in (None, False, 0) and getattr(args, _dest(needs), None) in (
            None,
            False,
        ):
            raise UsageError(f"{flag} needs {needs}: {NEEDS[flag]}")
    b = getattr(args, "virtual_damping", None)
    if b is not None and not b >= 0.0:
        raise UsageError(f"--virtual-damping {b:g} is invalid: B must be >= 0 (0 for none)")
    if args.velocity is not None and not args.velocity >= 0.0:
        raise UsageError(f"--velocity {args.velocity:g} is invalid: give the impact speed, >= 0")
    if args.bootstrap < 0:
        raise UsageError(f"--bootstrap {args.bootstrap} is invalid: give a whole number of replicate fits >= 0")
    if args.report is not None:
        check_output_folder("--report", args.report, create=True)
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
    if getattr(args, "write_device", None) is not None:
        check_output_file("--write-device", args.write_device, (".toml",))
    if (getattr(args, "x_unit", None) or "").strip().lower() == "counts" and args.resolution is None:
        raise UsageError("--x-unit counts needs --resolution: the encoder's resolution in m (rad) per count")
    for key, flag in (("resolution", "--resolution"), ("period", "--period"), ("stiffness", "--stiffness"),
                      ("velocity", "--velocity")):  # fmt: skip
        if getattr(args, key) is not None:
            warn_implausible(key, getattr(args, key), rotary=args.rotary, subject=flag)


def _dest(flag: str) -> str:
    return flag[2:].replace("-", "_")


def _check_against_grid(args: argparse.Namespace, delta: float, t: float) -> None:
    """Refuse --stiffness and --velocity that no device on the log's grid (Δ, T) can take, before the fit: the
    products K T², K T and K Δ of the dimensionless groups and the speed V T/Δ in ticks must be floats."""
    from ..model.device import device_units

    u = device_units(args.rotary)
    grid = f"the log's T = {t:.4g} s and Δ = {delta:.4g} {u['resolution']}"
    if args.stiffness is not None:
        k = args.stiffness
        for what, value in (("K T²", k * t * t), ("K T", k * t), ("K Δ", k * delta)):
            if not sys.float_info.min <= value <= sys.float_info.max:
                way = "underflows" if value < 1.0 else "overflows"
                raise UsageError(
                    f"--stiffness {k:g} is invalid with {grid}: {what} {way} a float, so μ = m/(K T²), β = b/(K T) "
                    f"and σ = c/(K Δ) cannot be formed for any device; give K in {u['stiffness']}"
                )
    if args.velocity is not None and not args.velocity * t / delta <= sys.float_info.max:
        raise UsageError(
            f"--velocity {args.velocity:g} is invalid with {grid}: the speed in ticks per sample V T/Δ overflows a "
            f"float; give the impact speed in {u['velocity']}"
        )


#: How the messages of the dimensionless groups name the inputs of the closed loop (the identified device's values
#: are no flags the user gave).
LOOP_NAMES = {
    "mass": "identified mass",
    "damping": "identified damping (lower end)",
    "coulomb": "identified Coulomb friction (lower end)",
    "resolution": "the log's resolution",
    "period": "the log's period",
    "stiffness": "--stiffness",
}

#: Why a flag needs another.
NEEDS = {
    "--velocity": "it is the impact speed of the wall the device is checked with",
    "--report": "the report is of the identified device and a wall of K",
    "--force": "it lets --report replace a report made for another device",
    "--wall-on": "the wall the log was taken with is a spring of stiffness K",
    "--virtual-damping": "it describes the wall the log was taken with",
    "--delay": "it describes the wall the log was taken with",
    "--one-sided": "it describes the wall the log was taken with",
}


def _peak_speed(v: float) -> float:
    """The log's peak speed rounded up to the 4 digits printed (its 5th moves with the fit's last bits), so that
    the limits are computed at the speed the output states, the same on every machine."""
    from ..formatting import round_at

    return round_at(v, math.floor(math.log10(v)) - 3, "up") if v > 0.0 and math.isfinite(v) else v


def _close_loop(args: argparse.Namespace, r: Any, log: Any, out: dict[str, Any], lines: list[str],
                short: list[str]) -> None:  # fmt: skip
    """K_max four ways of the cautious identified device (b, c at their lower 95 % bounds), the given K assessed,
    the logged oscillation against the predicted cycles, and the report; nothing on a poor fit. ``lines`` gets the
    full text (--explain), ``short`` the default screen."""
    from ..analysis.identify import period_effect
    from ..analysis.limits.kmax import design_answer
    from ..analysis.limits.recommend import recommend_stiffness
    from ..analysis.logged_cycle import compare_logged_cycle
    from ..model.device import dimensionless_params
    from ..model.loop import Loop
    from ..render.answer import stiffness_screen
    from ..render.identify import cycle_lines, loop_head, period_effect_lines, poor_fit_loop
    from ..render.identify_screen import cycle_screen, loop_screen, period_effect_screen, poor_fit_screen

    if r.status.value == "poor_fit":
        out["loop"] = None
        out.setdefault("null_reasons", {})["/loop"] = "poor fit: no limits for a model that does not reproduce the log"
        lines += poor_fit_loop(r)
        short += poor_fit_screen(r)
        if getattr(args, "wall_on", False):
            out["closed_loop"] = None
            out["null_reasons"]["/closed_loop"] = "poor fit: no prediction from a model that does not reproduce the log"
        return
    dev = r.cautious()
    dimensionless_params(dev, args.stiffness, names=LOOP_NAMES)  # names the identified values, not as flags
    v = _peak_speed(r.velocity_peak) if args.velocity is None else args.velocity
    try:
        wall = _logged_wall(args) or args.stiffness
        loop = Loop(dev, wall)
    except DFAError as err:  # a damper too strong for the identified mass (B T/m), say
        raise UsageError(str(err)) from None
    ans = design_answer(loop, v, assess=True)
    rec = recommend_stiffness(ans)
    out["loop"] = ans.to_dict() | {"recommendation": rec.to_dict(), "device": dev.to_dict()}
    lines += loop_head(dev, v, args.velocity is None) + stiffness_screen(ans, rec)
    short += loop_screen(ans, rec, args.velocity is None)
    if r.timing.exceeds:  # the limits hold at T: how the proof moves at the longest period logged
        eff = period_effect(dev, r.timing, v, getattr(args, "delay", 0), answer=ans)
        out["loop"]["period_effect"] = eff.to_dict()
        lines += period_effect_lines(eff, dev.units["stiffness"])
        short += period_effect_screen(eff, dev.units["stiffness"])
    if isinstance(wall, float) or wall.elements == ():  # the paper's spring: its cycles replayed across the intervals
        cyc = compare_logged_cycle(r, log, args.stiffness)
        out["cycle"] = cyc.to_dict()
        lines += cycle_lines(cyc)
        short += cycle_screen(cyc)
    else:
        out["cycle"] = None
        out.setdefault("null_reasons", {})["/cycle"] = "the logged wall is not the paper's spring: see closed_loop"
    if getattr(args, "wall_on", False):
        _wall_on(args, r, log, out, lines, short)
    if args.report is not None:
        out["report"] = _report(args, dev, v)
        written = [f"written {p}" for p in out["report"]["paths"]]
        lines += written
        short += written


def _logged_wall(args: argparse.Namespace) -> Any:
    """The wall of --stiffness, --virtual-damping, --delay, --one-sided with --wall-on; None without."""
    from ..analysis.closed_loop import logged_wall

    if not getattr(args, "wall_on", False):
        return None
    return logged_wall(args.stiffness, damping=args.virtual_damping or 0.0, delay=args.delay,
                       one_sided=args.one_sided)  # fmt: skip


def _wall_on(args: argparse.Namespace, r: Any, log: Any, out: dict[str, Any], lines: list[str],
             short: list[str]) -> None:  # fmt: skip
    """The log's force column against the wall, its contact beside the prediction (--wall-on)."""
    from ..analysis.closed_loop import closed_loop_evidence
    from ..render.identify import closed_loop_lines
    from ..render.identify_screen import closed_loop_screen

    try:
        ev = closed_loop_evidence(r, log, _logged_wall(args))
    except DFAError as err:
        raise UsageError(str(err)) from None
    out["closed_loop"] = ev.to_dict()
    lines += closed_loop_lines(ev)
    short += closed_loop_screen(ev)


def _write_device(args: argparse.Namespace, r: Any) -> str:
    """The identified device as a device file (--write-device); refused after a poor fit."""
    import datetime
    import os

    from .._io import atomic_write_text
    from ..render.identify import device_file, device_notes, device_source
    from ..results.identify import identified_entry

    if r.status.value == "poor_fit":
        raise UsageError(
            f"--write-device {args.write_device}: not written: the identified model does not reproduce the log "
            "(status poor_fit), so its values are no device"
        )
    stamp = datetime.datetime.fromtimestamp(os.stat(args.log).st_mtime, tz=datetime.timezone.utc)
    entry = identified_entry(r, source=device_source(r, stamp.date().isoformat()), notes=device_notes(r),
                             stiffness=args.stiffness)  # fmt: skip
    return str(atomic_write_text(args.write_device, device_file(entry, r)))


def run(args: argparse.Namespace) -> int:
    """Read the log, identify, optionally close the loop; print the result (text or JSON)."""
    from ..analysis.identify import identify, log_grid
    from ..model.log import read_log
    from ..render.identify import identify_lines
    from ..render.identify_screen import EXPLAIN_LINE, identify_screen

    _check_flags(args)
    try:
        units = {c: getattr(args, f"{c}_unit") for c in ("t", "x", "f") if getattr(args, f"{c}_unit")}
        log = read_log(args.log, rotary=args.rotary, columns=args.columns, units=units, count=args.resolution)
        _check_against_grid(args, *log_grid(log, resolution=args.resolution, period=args.period))
    except DFAError as err:
        raise UsageError(str(err)) from None
    r = identify(log, resolution=args.resolution, period=args.period, name=args.name, bootstrap=args.bootstrap,
                 progress=progress(args))  # fmt: skip
    for key, hint in (("mass", None), ("resolution", "positions in encoder counts? give x in m (rad)"),
                      ("period", "times in ms? give t in s")):  # fmt: skip
        warn_implausible(key, getattr(r.device, key), rotary=args.rotary, subject=f"identified {key}", hint=hint)
    out = r.to_dict()
    lines, short = identify_lines(r), identify_screen(r)
    if args.stiffness is not None:
        _close_loop(args, r, log, out, lines, short)
    written = []
    if args.plot is not None:
        out["plot"] = save_png("--plot", args.plot, r.plot()[0])
        written.append(f"written {out['plot']}")
    if args.write_device is not None:
        out["device_file"] = _write_device(args, r)
        written.append(f"written {out['device_file']} (use it with --device-file)")
    if args.json:
        emit(out, ensure_ascii=False)
        return 0
    for line in [*lines, *written] if args.explain else [*short, *written, EXPLAIN_LINE]:
        say(line)
    return 0
