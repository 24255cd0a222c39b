"""The device, the dimensionless loop and the speed of a command, from its flags.

A device is a catalogue name (``--device``) or a file of your own (``--device-file``, the catalogue's format),
and/or physical values in SI units, which replace the named device's; the dimensionless (μ, β, σ) replace it
where a command takes them. :func:`resolve` turns the flags into :class:`Inputs` and refuses contradictions with
one line naming the flags; a physical value no haptic device has gets one warning line naming the flag (or the
file's key) and the likely slip (:mod:`dfa.plausibility`).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ..checks import check_beta, check_mu, check_real, check_sigma, check_speed
from ..errors import DFAError
from ..model.catalogue import CatalogueEntry, ResolvedDevice, get_device, load_device_file, resolve_device
from ..model.configurations import Configuration, unit_normal
from ..model.device import DEVICE_FIELDS, STIFFNESS, Device, Params, dimensionless_params
from ..model.hand import HAND_PRESETS, Hand, get_hand
from ..plausibility import warn_implausible
from ..render.hand import hand_label
from ..results.configurations import WorstConfiguration
from .parsing import UsageError, integer, name, number

__all__ = [
    "HAND_FLAGS",
    "PHYS_FLAGS",
    "Inputs",
    "add_device_group",
    "add_device_args",
    "add_plane_args",
    "check_plane",
    "device_given",
    "device_json",
    "impact_speed",
    "outside_note",
    "plane_device",
    "range_arg",
    "resolve",
    "resolve_hand",
    "speed",
]

#: The hand's flags: dest -> (flag, unit).
HAND_FLAGS = {
    "hand_mass": ("--hand-mass", "kg (rotary: kg·m²)"),
    "hand_damping": ("--hand-damping", "N·s/m (rotary: N·m·s/rad)"),
    "hand_stiffness": ("--hand-stiffness", "N/m (rotary: N·m/rad)"),
}
#: The physical flags of a device, one per field of :data:`dfa.model.device.DEVICE_FIELDS`: dest -> (flag, unit).
PHYS_FLAGS = {f.name: (f.flag, f.units) for f in DEVICE_FIELDS}
#: The flags a device of physical values needs (``--mass --damping --coulomb --resolution --period``).
_DEVICE_FLAGS = " ".join(f.flag for f in DEVICE_FIELDS if f.required)
_DIMLESS_FLAGS = {"mu": "--mu", "beta": "--beta", "sigma": "--sigma"}
_FLAG_NAMES = {k: f for k, (f, _u) in PHYS_FLAGS.items()} | {
    "stiffness": "--stiffness",
    "counts": "--counts",
    "name": "--name",
}


#: The commands that answer for the worst of a device file's configurations, with a table of every one.
CONFIGURATION_COMMANDS = ("stiffness", "check", "report")
#: The commands whose limiting configuration has the smallest recommended K (dfa stiffness's rule): the rest
#: of the --configuration help.
_STIFFNESS_RULE = {
    "stiffness": "",
    "report": "",
    "tune": ", the held wall's elements",
    "zwidth": " with the Z-width's wall, whose K_max(B) rows are then that configuration's (not a minimum over "
    "every configuration, row by row)",
}
#: The commands that answer every configuration, the limiting one marked.
_ALL_ROWS = {
    "params": "a row per configuration, the limiting one (the smallest margin σ − σ₀ at speed 0, eq. 6) marked"
}
#: The commands whose limiting configuration has the smallest criterion margin: (the speed, the rest of the help).
_MARGIN_RULE = {
    "simulate": ("|--velocity|", ""),
    "limit-cycles": ("speed 0 (σ − σ₀)", ""),
    "contours": ("speed 0 (σ − σ₀)", "; the plane is its μ"),
    "map": ("the largest --velocity, else 0", "; the plane is its μ"),
    "export": ("speed 0 (σ − σ₀)", " with --stiffness; with --velocity the smallest recommended K (as dfa stiffness)"),
}


def configuration_rule(command: str) -> str:
    """How ``command`` chooses the limiting configuration (its --configuration help; docs/cli.md)."""
    if command in _STIFFNESS_RULE:
        return "the smallest recommended K at the speed (as dfa stiffness)" + _STIFFNESS_RULE[command]
    if command in _ALL_ROWS:
        return _ALL_ROWS[command]
    speed, rest = _MARGIN_RULE.get(command, ("the speed", ""))
    return f"the smallest criterion margin (eq. 6) at K and {speed} (as dfa check){rest}"


def _normal_arg(text: str) -> tuple[float, float, float]:
    """--normal NX,NY,NZ: three finite numbers, not all zero (made a unit vector where it is used)."""
    items = [t.strip() for t in text.split(",")]
    try:
        values = [float(t) for t in items]
    except ValueError:
        values = []
    if len(values) != 3 or not all(math.isfinite(x) for x in values):
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is not three numbers: --normal takes three finite numbers separated by commas, e.g. "
            "--normal 0,0,1"
        )
    if not any(values):
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is invalid: a normal must have a length > 0; give e.g. --normal 0,0,1"
        )
    return (values[0], values[1], values[2])


def _add_counts_name_args(g: Any, command: str) -> None:
    """--counts, --name, --configuration and --normal, for every command that takes a device."""
    g.add_argument(
        "--configuration",
        metavar="NAME",
        help="one of the device file's [[devices.configurations]] (its values along the wall's normal; one "
        "without a normal along its worst direction); default: the limiting one, named in the output: "
        + configuration_rule(command),
    )
    g.add_argument(
        "--normal",
        type=_normal_arg,
        metavar="NX,NY,NZ",
        help="the wall's normal for the configurations with an inertia matrix, three numbers (made a unit vector, "
        "stated; a leading minus needs '=': --normal=-1,0,0), replacing the file's normal and the search of the worst "
        "direction; default: the file's normal, "
        "else the worst direction",
    )
    g.add_argument(
        "--counts",
        type=integer("--counts"),
        metavar="N",
        help="encoder counts per metre (with --rotary: per revolution) instead of --resolution: Δ = 1/N m "
        "(2π/N rad); default: none",
    )
    g.add_argument(
        "--name",
        type=name,
        metavar="TEXT",
        help="device name in outputs and report file names; default: the catalogue name, else 'custom device'",
    )


def add_device_group(p: argparse.ArgumentParser, title: str) -> Any:
    """--device, --device-file, the physical flags, --counts, --name, --stiffness and --rotary
    (:func:`dfa.model.catalogue.resolve_device`)."""
    g = p.add_argument_group(title)
    g.add_argument(
        "--device",
        metavar="NAME",
        help="catalogue device, case-insensitive prefix (e.g. 'phantom'; list: `dfa devices`); default: none",
    )
    g.add_argument(
        "--device-file",
        dest="device_file",
        metavar="FILE.toml",
        help="a device of your own, in the catalogue's TOML format (`dfa devices --template` writes one); "
        "instead of --device; the physical flags, --counts, --stiffness, --name and --rotary replace its "
        "values; default: none",
    )
    for f in DEVICE_FIELDS:
        default = "the catalogue value" + ("" if f.required else f", else {f.absent or 'none'}")
        g.add_argument(
            f.flag,
            dest=f.name,
            type=number(f.flag, f.units),
            metavar="X",
            help=f"{f.described} in {f.units}; default: {default}",
        )
    _add_counts_name_args(g, p.prog.split()[-1])
    g.add_argument(
        "--stiffness",
        type=number("--stiffness", "N/m"),
        metavar="K",
        help="virtual wall stiffness K in N/m (rotary: N·m/rad); default: the catalogue K",
    )
    g.add_argument(
        "--rotary",
        action="store_true",
        help="physical values are rotary (rad, N·m, inertia in kg·m²); default: linear (m, N, kg)",
    )
    _add_hand_args(p)
    return g


def _add_hand_args(p: argparse.ArgumentParser) -> None:
    """--hand and --hand-mass/-damping/-stiffness: a hand holding the device (dfa.model.hand)."""
    h = p.add_argument_group("a hand holding the device (default: none, the paper's worst case)")
    h.add_argument(
        "--hand",
        metavar="PRESET",
        help=f"hand preset: {', '.join(HAND_PRESETS)} (paper: Table 2's human operator, 0.150 kg and 4.8 N·s/m "
        "added to the device's); the flags below replace its values; default: none",
    )
    for key, (flag, unit) in HAND_FLAGS.items():
        h.add_argument(
            flag,
            dest=key,
            type=number(flag, unit),
            metavar="X",
            help=f"hand {key.removeprefix('hand_')} in {unit}"
            + (" to a fixed reference at the wall's origin" if key == "hand_stiffness" else ", added to the device's")
            + "; default: the preset's, else 0",
        )


def resolve_hand(args: argparse.Namespace, rotary: bool) -> Hand | None:
    """The hand of --hand and --hand-mass/-damping/-stiffness, or None when none is given."""
    preset = getattr(args, "hand", None)
    values = {k.removeprefix("hand_"): getattr(args, k, None) for k in HAND_FLAGS}
    if preset is None and all(v is None for v in values.values()):
        return None
    base = Hand(0.0, name="hand")
    if preset is not None:
        try:
            base = get_hand(preset)
        except DFAError:
            raise UsageError(
                f"--hand {preset!r} is not a hand preset: choose one of {', '.join(HAND_PRESETS)}, "
                "or give --hand-mass and --hand-damping"
            ) from None
        if rotary and not base.is_empty:
            raise UsageError(
                f"--hand {preset} holds a linear device's values (kg, N·s/m): for a rotary device give "
                "--hand-mass (kg·m²) and --hand-damping (N·m·s/rad) instead"
            )
    given = {k: v for k, v in values.items() if v is not None}
    for key, v in given.items():
        flag = HAND_FLAGS["hand_" + key][0]
        if not (math.isfinite(v) and v >= 0.0):
            raise UsageError(f"{flag} {v:g} is invalid: it must be a finite number >= 0; give 0 for none")
        if key == "mass" and v > 0.0:  # a hand of 150 kg is most likely grams (dfa.plausibility)
            warn_implausible("mass", v, rotary=rotary, subject=flag)
    if base.is_empty and not given:
        return None  # --hand none: nobody holds the device, exactly as without the flag
    if base.is_empty:
        base = Hand(0.0, name="hand")
    name = base.name if not given else ("hand" if preset is None else f"{base.name}, changed")
    return Hand(**{**{k: getattr(base, k) for k in values}, **given}, name=name, source=base.source)


def add_device_args(
    p: argparse.ArgumentParser,
    dimensionless: bool,
    speed: bool,
    json_help: str = "print one JSON object on stdout (default: a text table)",
) -> None:
    """The device group, the dimensionless group (``dimensionless``), one impact speed (``speed``) and --json."""
    add_device_group(p, "device (a catalogue name, or physical values in SI units)")
    if dimensionless:
        d = p.add_argument_group("dimensionless parameters (instead of a device)")
        for flag, what in (("--mu", "μ = m/(K T²)"), ("--beta", "β = b/(K T)"), ("--sigma", "σ = c/(K Δ)")):
            d.add_argument(flag, type=number(flag, "dimensionless units"), help=f"{what}, dimensionless; default: none")
    if speed:
        s = p.add_argument_group("speed (one of)")
        s.add_argument(
            "--velocity",
            type=number("--velocity", "m/s (rotary: rad/s)"),
            metavar="V",
            help="impact speed in m/s (rotary: rad/s); default: none",
        )
        s.add_argument(
            "--xi-dot",
            dest="xi_dot",
            type=number("--xi-dot", "encoder ticks per sample"),
            metavar="V",
            help="impact speed ξ'0 in encoder ticks per sample; default: none",
        )
    p.add_argument("--json", action="store_true", help=json_help)


@dataclass(frozen=True)
class Inputs:
    """What the device flags resolved to: the loop's (μ, β, σ) when known, the device and K, a label."""

    params: Params | None  # full (μ, β, σ) when known
    beta: float
    sigma: float
    device: Device | None
    stiffness: float | None
    label: str
    entry: CatalogueEntry | None = None  # the catalogue row, when the device is that row unchanged
    configurations: tuple[Configuration, ...] = ()  # the device file's, for the worst (`device` is the device's own)
    worst: WorstConfiguration | None = None  # every configuration's row, when `device` is the limiting one's
    rule: str | None = None  # how the limiting one was chosen (dfa.cli.configurations.MARGIN or STIFFNESS)


def _dimensionless(args: argparse.Namespace, phys_given: list[str], dim_given: list[str], need_mu: bool) -> Inputs:
    others = (["--device"] if args.device else []) + (["--device-file"] if _device_file(args) else [])
    others += [PHYS_FLAGS[k][0] for k in phys_given]
    others += [f"--{k}" for k in ("counts", "name", "configuration", "normal") if getattr(args, k, None) is not None]
    others += ["--stiffness"] if args.stiffness is not None else []
    others += ["--velocity"] if getattr(args, "velocity", None) is not None else []
    others += ["--hand"] if getattr(args, "hand", None) is not None else []
    others += [f for k, (f, _u) in HAND_FLAGS.items() if getattr(args, k, None) is not None]
    if others:
        raise UsageError(
            f"{', '.join(_DIMLESS_FLAGS[k] for k in dim_given)} cannot be combined with {', '.join(others)}: "
            "give either dimensionless (--mu --beta --sigma, --xi-dot) or physical inputs"
        )
    required = ["beta", "sigma"] + (["mu"] if need_mu else [])
    missing = [_DIMLESS_FLAGS[k] for k in required if getattr(args, k) is None]
    if missing:
        raise UsageError(
            f"missing {', '.join(missing)}: dimensionless input needs {' '.join(_DIMLESS_FLAGS[k] for k in required)}"
        )
    b = check_beta(args.beta, "--beta")
    s = check_sigma(args.sigma, "--sigma")
    p = Params(check_mu(args.mu, "--mu"), b, s) if args.mu is not None else None
    return Inputs(p, b, s, None, None, "dimensionless input")


def resolve(
    args: argparse.Namespace,
    *,
    dimensionless: bool,
    need_mu: bool = True,
    need_stiffness: bool = True,
    configurations: bool = False,
) -> Inputs:
    """Turn device/physical/dimensionless flags into parameters, rejecting contradictions.

    With ``need_stiffness=False`` a device without any stiffness (no --stiffness, no catalogue K) gives
    ``params=None`` and ``stiffness=None``. A device file's configurations: ``--configuration NAME`` makes the
    device that configuration's; without it a command that answers for the worst (``configurations=True``) gets
    them in ``Inputs.configurations`` (``device`` the device's own), any other is refused with one line.
    """
    phys_given = [k for k in PHYS_FLAGS if getattr(args, k, None) is not None]
    dim_given = [k for k in _DIMLESS_FLAGS if getattr(args, k, None) is not None] if dimensionless else []
    if dim_given:
        return _dimensionless(args, phys_given, dim_given, need_mu)
    custom = phys_given + [k for k in ("counts", "name") if getattr(args, k, None) is not None]
    path = _device_file(args)
    if args.device and path is not None:
        raise UsageError(
            f"--device {args.device!r} and --device-file {path!r} cannot both be given: give one device (a catalogue "
            "name or your file; flags such as --mass replace either's values)"
        )
    if args.device and os.path.isfile(args.device) and args.device.lower().endswith(".toml"):
        raise UsageError(
            f"--device {args.device!r} is a file, and --device takes a catalogue name: give --device-file "
            f"{args.device} for a device file"
        )
    if not args.device and path is None and not custom:
        raise UsageError(
            "no device given: use --device NAME (see `dfa devices`), --device-file FILE.toml (`dfa devices "
            f"--template` writes one), or {_DEVICE_FLAGS}" + (", or --mu --beta --sigma" if dimensionless else "")
        )
    entry = None if path is None else load_device_file(path)
    _warn_implausible(args, entry, path)  # held until the inputs are accepted (dfa.cli.output.hold_warning)
    r = resolve_device(
        args.device or None,
        entry=entry,
        overrides={k: getattr(args, k, None) for k in PHYS_FLAGS},
        counts=getattr(args, "counts", None),
        rotary=bool(getattr(args, "rotary", False)),
        stiffness=args.stiffness,
        label=getattr(args, "name", None),
        flags=_FLAG_NAMES,
    )
    confs = _configurations(args, entry, path, configurations)
    one = getattr(args, "configuration", None) is not None and getattr(args, "normal", None) is None
    if len(confs) == 1 and one and not confs[0].directional:
        r, confs = ResolvedDevice(confs[0].device_at(r.device), r.stiffness), ()  # one configuration: its device
    dev, label, entry = r.device, r.label, r.entry
    hand = resolve_hand(args, dev.rotary)
    if hand is not None:
        dev = dev.held_by(hand)  # its stiffness joins the wall (dfa.cli.walls.wall_from_args: dfa.HandSpring)
        label, entry = f"{label}, held by {hand_label(hand, dev.units)}", None  # no longer the catalogue row
    if r.stiffness is None and not need_stiffness:
        return Inputs(None, math.nan, math.nan, dev, None, label, entry, confs)
    if r.stiffness is None:
        where = f"device file {path!r} gives no stiffness" if path is not None else "no catalogue stiffness"
        raise UsageError(f"missing --stiffness: {where} for {dev.name!r}; give K in {dev.units['stiffness']}")
    p = dimensionless_params(dev, r.stiffness)  # resolve_device has refused groups that overflow or vanish
    return Inputs(p, p.beta, p.sigma, dev, r.stiffness, label, entry, confs)


def _configurations(
    args: argparse.Namespace, entry: CatalogueEntry | None, path: str | None, worst: bool
) -> tuple[Configuration, ...]:
    """The configurations a command analyses: --configuration's one, every one (``worst``), or none; refused with
    one line for a name the file lacks, and for a command that does not answer for the worst."""
    name = getattr(args, "configuration", None)
    confs = () if entry is None else entry.configurations
    command = f"dfa {getattr(args, 'command', None) or 'this command'}"
    answering = f"dfa {' and dfa '.join(CONFIGURATION_COMMANDS)}"
    if name is not None:
        if not confs:
            where = f"device file {path!r} has" if path is not None else "a catalogue device or flags have"
            raise UsageError(f"--configuration {name!r} needs configurations: {where} none; give a device file with "
                             "[[devices.configurations]] tables, or drop --configuration")  # fmt: skip
        chosen = [c for c in confs if c.name == name]
        if not chosen:
            raise UsageError(f"--configuration {name!r} is not in device file {path!r}: choose one of "
                             f"{', '.join(repr(c.name) for c in confs)}")  # fmt: skip
        confs = _with_normal(args, (chosen[0],), path)
        if confs[0].directional and not worst:
            raise UsageError(f"--configuration {name!r} has an inertia matrix but no normal: {command} needs "
                             f"one direction; give normal = [nx, ny, nz] in the file or --normal, or use "
                             f"{answering}, which search the worst direction")  # fmt: skip
        return confs
    confs = _with_normal(args, confs, path)
    if confs and not worst:
        raise UsageError(
            f"device file {path!r} has {len(confs)} configurations ({', '.join(repr(c.name) for c in confs[:5])}"
            f"{', ...' if len(confs) > 5 else ''}): {command} analyses one; give --configuration NAME "
            f"({answering} answer for the worst of them)"
        )
    return confs


def _with_normal(
    args: argparse.Namespace, confs: tuple[Configuration, ...], path: str | None
) -> tuple[Configuration, ...]:
    """The configurations with --normal (a unit vector) in place of the file's normal, for those with an inertia
    matrix; refused with one line when none has one."""
    given = getattr(args, "normal", None)
    if given is None:
        return confs
    text = ",".join(f"{x:g}" for x in given)
    if not any(c.inertia is not None for c in confs):
        where = f"device file {path!r}" if path is not None else "a catalogue device or flags"
        if not confs:
            has = f"{where} has no configurations"
        elif len(confs) == 1:
            has = f"configuration {confs[0].name!r} has none"
        else:
            has = f"no configuration of {where} has one"
        raise UsageError(f"--normal {text} needs an inertia matrix: {has}; give [[devices.configurations]] with "
                         "inertia = [[...], [...], [...]] in a device file, or drop --normal")  # fmt: skip
    n = unit_normal(given, "--normal")
    return tuple(dataclasses.replace(c, normal=n) if c.inertia is not None else c for c in confs)


def _device_file(args: argparse.Namespace) -> str | None:
    """--device-file, or None (also for a command without it)."""
    path = getattr(args, "device_file", None)
    return None if path is None else str(path)


def _warn_implausible(args: argparse.Namespace, entry: CatalogueEntry | None, path: str | None) -> None:
    """One warning line per value no haptic device has, naming where it came from: the flag, --counts, or the
    device file's key (the catalogue's own values are not checked)."""
    if entry is None and args.device:
        try:
            entry = get_device(args.device)  # for its units (a rotary device); its values are not checked
        except DFAError:
            return  # resolve_device refuses the name, with its message
    rotary = bool(getattr(args, "rotary", False)) or (entry is not None and entry.rotary)
    counts = getattr(args, "counts", None)
    for key, quantity in ((f.name, f.plausibility) for f in (*DEVICE_FIELDS, STIFFNESS) if f.plausibility):
        value, subject, hint = getattr(args, key, None), _FLAG_NAMES[key], None
        if value is None and key == "resolution" and isinstance(counts, int) and counts >= 1:
            value = (2.0 * math.pi if rotary else 1.0) / counts
            subject, hint = f"--counts {counts}: resolution", "--counts is per metre (with --rotary: per revolution)"
        elif value is None and path is not None and entry is not None:
            value, subject = getattr(entry, key), f"{path}: {key}"
        if value is not None:
            warn_implausible(quantity, value, rotary=rotary, subject=subject, hint=hint)


def device_given(args: argparse.Namespace) -> bool:
    """True when any device flag (--device, --device-file, a physical value, --counts, --name, --stiffness) is given."""
    keys = (*PHYS_FLAGS, "stiffness", "counts", "name", "hand", *HAND_FLAGS)
    return bool(args.device) or _device_file(args) is not None or any(getattr(args, k, None) is not None for k in keys)


def impact_speed(flag: str, value: float, inputs: Inputs | None, zero: bool = True) -> float:
    """An impact speed from ``flag``: its magnitude, >= 0 (> 0 if not ``zero``); a negative is refused, not flipped."""
    if flag == "--xi-dot":
        unit = "ticks per sample"
    else:
        unit = inputs.device.units["velocity"] if inputs is not None and inputs.device is not None else "m/s (rad/s)"
    out = check_speed(flag, value, unit, zero=zero)
    if flag != "--xi-dot" and inputs is not None and inputs.device is not None:
        warn_implausible("velocity", out, rotary=inputs.device.rotary, subject=flag)
    return out


def speed(
    args: argparse.Namespace, inputs: Inputs, required: bool = True, signed: bool = False
) -> tuple[float | None, float | None]:
    """Return (xi_dot, velocity) from --xi-dot / --velocity; unless ``signed``, an impact speed (>= 0)."""
    v, xd = args.velocity, args.xi_dot
    if not signed:
        v = None if v is None else impact_speed("--velocity", v, inputs)
        xd = None if xd is None else impact_speed("--xi-dot", xd, inputs)
    if v is not None and xd is not None:
        raise UsageError("--velocity and --xi-dot cannot both be given: choose one speed")
    if v is None and xd is None:
        if required:
            raise UsageError("missing speed: give --velocity V (m/s, rad/s) or --xi-dot V (encoder ticks per sample)")
        return None, None
    if v is not None:
        if inputs.device is None:
            raise UsageError("--velocity needs a physical device: with --mu/--beta/--sigma give --xi-dot instead")
        if signed:  # an impact speed (not signed) was checked by impact_speed
            warn_implausible("velocity", v, rotary=inputs.device.rotary, subject="--velocity")
        return inputs.device.xi_dot(v), v
    xd = check_real("--xi-dot", xd, "give the speed in encoder ticks per sample")
    return xd, (inputs.device.velocity(xd) if inputs.device is not None else None)


# ----------------------------------------------------------------- the (β, σ) plane of `map` and `contours`
def range_arg(p: argparse.ArgumentParser, flag: str, default: list[float], what: str) -> None:
    """A LOW HIGH range of a dimensionless group."""
    p.add_argument(
        flag,
        type=number(flag, "dimensionless units"),
        nargs=2,
        default=default,
        metavar=("A", "B"),
        help=f"{what} range, dimensionless (default: {default[0]:g} {default[1]:g})",
    )


def add_plane_args(p: argparse.ArgumentParser, speeds: bool) -> None:
    """The (β, σ) plane of `map` and `contours`: --mu (or a device at its K, whose (β, σ) is marked), the β and σ
    ranges, and --plot."""
    p.add_argument(
        "--mu",
        type=number("--mu", "dimensionless units"),
        help="μ = m/(K T²), dimensionless (required unless a device is given)",
    )
    range_arg(p, "--beta-range", [0.0, 1.0], "β")
    range_arg(p, "--sigma-range", [0.0, 2.0], "σ")
    g = add_device_group(p, "device (instead of --mu: a catalogue name, or physical values in SI units)")
    if speeds:
        g.add_argument(
            "--velocity",
            type=number("--velocity", "m/s (rotary: rad/s)"),
            nargs="+",
            metavar="V",
            help="initial speeds in m/s (rotary: rad/s; needs a device), instead of --xi-dot; default: none",
        )
    p.add_argument(
        "--plot", metavar="FILE", help="write the figure to FILE: .png, .pdf or .svg by its suffix (default: none)"
    )


def check_plane(args: argparse.Namespace) -> None:
    """--grid, --beta-range and --sigma-range of `map` and `contours`, refused with the flag's name."""
    if args.grid < 2:
        raise UsageError(
            f"--grid {args.grid} is invalid: it must be a whole number >= 2 (points per axis); give e.g. --grid 50"
        )
    for flag, (lo, hi), sym in (("--beta-range", args.beta_range, "β"), ("--sigma-range", args.sigma_range, "σ")):
        if lo < 0.0 or not hi > lo:
            raise UsageError(
                f"{flag} {lo:g} {hi:g} is invalid: it must be LOW HIGH with 0 <= LOW < HIGH ({sym} >= 0); "
                f"give e.g. {flag} 0 {max(lo, hi, 1.0):g}"
            )


def plane_device(args: argparse.Namespace) -> tuple[float, Inputs | None]:
    """μ of `map`/`contours`: --mu, or a device at its stiffness (never both)."""
    check_plane(args)
    given = device_given(args)
    if args.mu is not None and given:
        raise UsageError(
            "--mu cannot be combined with a device or a hand: give --mu, or --device/physical values (μ follows; "
            "a hand needs a device)"
        )
    if args.mu is None and not given:
        raise UsageError(f"missing --mu: give --mu, or a device (--device NAME, or {_DEVICE_FLAGS})")
    if args.mu is not None:
        return check_mu(args.mu, "--mu"), None
    inp = resolve(args, dimensionless=False, configurations=True)  # the caller chooses the limiting one
    assert inp.params is not None and inp.device is not None
    speeds = getattr(args, "velocity", None) or []
    if speeds:  # the largest initial speed (a sign is refused later, with the flag's message)
        warn_implausible("velocity", max(abs(v) for v in speeds), rotary=inp.device.rotary, subject="--velocity")
    return inp.params.mu, inp


def device_json(inp: Inputs | None, xi_dots: Sequence[float] = ()) -> dict[str, object]:
    """Device, K, force step, operating point and physical speeds for the JSON of `map`/`contours`."""
    if inp is None or inp.device is None or inp.stiffness is None or inp.params is None:
        return {}
    from ..model.units import unit_context

    d = unit_context(inp.device, inp.stiffness)
    d.pop("velocity")
    d["operating_point"] = {"mu": inp.params.mu, "beta": inp.params.beta, "sigma": inp.params.sigma}
    d["tick_" + ("rad" if inp.device.rotary else "m")] = inp.device.resolution
    if xi_dots:
        d["velocities"] = [inp.device.velocity(x) for x in xi_dots]
    return d


def outside_note(args: argparse.Namespace, inp: Inputs) -> str:
    """A warning when the device's (β, σ) lies outside the plotted ranges (empty otherwise)."""
    assert inp.params is not None
    b0, b1 = sorted(args.beta_range)
    s0, s1 = sorted(args.sigma_range)
    if b0 <= inp.params.beta <= b1 and s0 <= inp.params.sigma <= s1:
        return ""
    return " (outside the (β, σ) range of the map: widen --beta-range/--sigma-range to see it)"
