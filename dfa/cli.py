"""Command-line tool ``dfa``.

Every subcommand is reachable through :func:`main` (``main(argv) -> exit code``)
so that it can be tested without a subprocess. Bad input prints one line on
stderr and returns exit code 2; no traceback is ever shown for it.

Examples
--------
>>> main(["params", "--device", "impulse", "--json"])
{"mu": 100.00000000000001, "beta": 0.125, "sigma": 0.9554140127388535}
0
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import signal
import sys
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from ._io import check_output_file, check_output_folder, written_paths
from .analysis.criterion import device_criterion, passivity_criterion
from .checks import MAX_DELAY, check_beta, check_mu, check_real, check_sigma, check_speed
from .errors import DFAError, DFAValueError
from .formatting import number, text_table
from .model.catalogue import DEFAULT_DEVICE, CatalogueEntry, catalogue, resolve_device
from .model.device import Device, Params, dimensionless_params
from .model.wall import MIN_CUTOFF, Wall, WallParams
from .results.jsonable import dumps, explain_nulls

__all__ = ["main"]


class UsageError(DFAValueError):
    """Wrong or contradictory command-line inputs."""


class _Parser(argparse.ArgumentParser):
    """ArgumentParser whose errors are one line on stderr and exit code 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UsageError(f"{self.prog}: error: {message}")


# Decimal ASCII only: no '1_000', no Arabic-Indic or full-width digits, no 'nan'/'inf' (float() takes them all).
_DECIMAL = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_WHOLE = re.compile(r"[+-]?[0-9]+")


def _number(flag: str, unit: str) -> Callable[[str], float]:
    def parse(text: str) -> float:
        if not _DECIMAL.fullmatch(text):
            what = (
                "not a finite number"
                if text.strip().lower().lstrip("+-") in ("nan", "inf", "infinity")
                else "not a number"
            )
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is {what}: {flag} takes a finite decimal number in {unit}, written with ASCII digits "
                "(e.g. 0.25, -3, 1e-3; no '_', no other scripts)"
            )
        value = float(text)
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is too large: {flag} takes a number below 1.8e308 in {unit}"
            )
        if value == 0.0 and any(c in "123456789" for c in text.lower().split("e")[0]):
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is too small: it rounds to 0; {flag} takes a number above 1e-308 in {unit} (or 0)"
            )
        return value + 0.0  # -0 is zero

    parse.__name__ = flag
    return parse


def _integer(flag: str) -> Callable[[str], int]:
    def parse(text: str) -> int:
        if not _WHOLE.fullmatch(text):
            raise argparse.ArgumentTypeError(
                f"{text[:40]!r} is not a whole number: {flag} takes an integer written with ASCII digits (e.g. 2000; no '_', '.', 'e')"
            )
        if len(text.lstrip("+-").lstrip("0")) > 18:
            raise argparse.ArgumentTypeError(f"{text[:40]!r} is too large: {flag} takes an integer below 10^18")
        return int(text)

    parse.__name__ = flag
    return parse


_PHYS_FLAGS = {
    "mass": ("--mass", "kg (rotary: inertia in kg·m²)"),
    "damping": ("--damping", "N·s/m (rotary: N·m·s/rad)"),
    "coulomb": ("--coulomb", "N (rotary: N·m)"),
    "resolution": ("--resolution", "m (rotary: rad)"),
    "period": ("--period", "s"),
}
_PHYS_WHAT = {
    "mass": "moving mass m",
    "damping": "viscous friction b",
    "coulomb": "Coulomb friction c",
    "resolution": "encoder resolution Δ",
    "period": "sample period T",
}
_DIMLESS_FLAGS = {"mu": "--mu", "beta": "--beta", "sigma": "--sigma"}
_FLAG_NAMES = {k: f for k, (f, _u) in _PHYS_FLAGS.items()} | {
    "stiffness": "--stiffness",
    "counts": "--counts",
    "name": "--name",
}


def _name(text: str) -> str:
    if not text.strip() or any(not c.isprintable() for c in text) or len(text) > 100:
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is invalid: --name takes a printable device name of 1 to 100 characters (e.g. 'my pen')"
        )
    return text.strip()


def _add_counts_name_args(g: Any) -> None:
    """--counts and --name, for every command that takes a device."""
    g.add_argument(
        "--counts",
        type=_integer("--counts"),
        metavar="N",
        help="encoder counts per metre (with --rotary: per revolution) instead of --resolution: Δ = 1/N m "
        "(2π/N rad); default: none",
    )
    g.add_argument(
        "--name",
        type=_name,
        metavar="TEXT",
        help="device name in outputs and report file names; default: the catalogue name, else 'custom device'",
    )


def _add_device_group(p: argparse.ArgumentParser, title: str) -> argparse._ArgumentGroup:
    """--device, the physical flags, --counts, --name, --stiffness and --rotary (:func:`dfa.model.catalogue.resolve_device`)."""
    g = p.add_argument_group(title)
    g.add_argument(
        "--device",
        metavar="NAME",
        help="catalogue device, case-insensitive prefix (e.g. 'phantom'; list: `dfa devices`); default: none",
    )
    for key, (flag, unit) in _PHYS_FLAGS.items():
        g.add_argument(
            flag,
            dest=key,
            type=_number(flag, unit),
            metavar="X",
            help=f"{_PHYS_WHAT[key]} in {unit}; default: the catalogue value",
        )
    _add_counts_name_args(g)
    g.add_argument(
        "--stiffness",
        type=_number("--stiffness", "N/m"),
        metavar="K",
        help="virtual wall stiffness K in N/m (rotary: N·m/rad); default: the catalogue K",
    )
    g.add_argument(
        "--rotary",
        action="store_true",
        help="physical values are rotary (rad, N·m, inertia in kg·m²); default: linear (m, N, kg)",
    )
    return g


def _add_device_args(
    p: argparse.ArgumentParser,
    dimensionless: bool,
    speed: bool,
    json_help: str = "print one JSON object on stdout (default: a text table)",
) -> None:
    _add_device_group(p, "device (a catalogue name, or physical values in SI units)")
    if dimensionless:
        d = p.add_argument_group("dimensionless parameters (instead of a device)")
        d.add_argument(
            "--mu", type=_number("--mu", "dimensionless units"), help="μ = m/(K T²), dimensionless; default: none"
        )
        d.add_argument(
            "--beta", type=_number("--beta", "dimensionless units"), help="β = b/(K T), dimensionless; default: none"
        )
        d.add_argument(
            "--sigma", type=_number("--sigma", "dimensionless units"), help="σ = c/(K Δ), dimensionless; default: none"
        )
    if speed:
        s = p.add_argument_group("speed (one of)")
        s.add_argument(
            "--velocity",
            type=_number("--velocity", "m/s (rotary: rad/s)"),
            metavar="V",
            help="impact speed in m/s (rotary: rad/s); default: none",
        )
        s.add_argument(
            "--xi-dot",
            dest="xi_dot",
            type=_number("--xi-dot", "encoder ticks per sample"),
            metavar="V",
            help="impact speed ξ'0 in encoder ticks per sample; default: none",
        )
    p.add_argument("--json", action="store_true", help=json_help)


def _delay(text: str) -> int:
    """--delay: ASCII digits only (int() would take '1_0' or other scripts' digits), 0 to MAX_DELAY samples."""
    if not _WHOLE.fullmatch(text):
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is not a whole number: --delay takes the computational delay in samples (integer >= 0, "
            "ASCII digits, e.g. 1)"
        )
    digits = text.lstrip("+-").lstrip("0")
    out = int(text) if len(digits) <= 18 else (-1 if text.startswith("-") else MAX_DELAY + 1)
    if out < 0:
        raise argparse.ArgumentTypeError(f"{text!r} is invalid: --delay must be a whole number of samples >= 0")
    if out > MAX_DELAY:
        raise argparse.ArgumentTypeError(
            f"{text[:40]!r} is too large: --delay takes at most {MAX_DELAY} samples; give the computational delay "
            "in samples of the servo period (e.g. 1)"
        )
    return out


def _add_delay_arg(p: argparse.ArgumentParser, parse: Callable[[str], int] = _delay) -> None:
    p.add_argument(
        "--delay",
        type=parse,
        default=0,
        metavar="N",
        help="computational delay in samples (default: 0): the force of sample h uses the reading of sample h − N",
    )


#: The controller flags beside --delay (dest: flag); physical units, converted at the edge (dfa.model.wall).
_CTL_FLAGS = {
    "virtual_damping": "--virtual-damping",
    "velocity_filter": "--velocity-filter",
    "amplifier_bandwidth": "--amplifier-bandwidth",
}


def _add_controller_args(p: argparse.ArgumentParser, parse: Callable[[str], int] = _delay) -> None:
    """--delay and the wall controller's flags (issue 15): virtual damper, velocity filter, amplifier bandwidth."""
    _add_delay_arg(p, parse)
    g = p.add_argument_group("wall controller (default: the paper's spring; needs a physical device and K)")
    g.add_argument(
        "--virtual-damping",
        dest="virtual_damping",
        type=_number("--virtual-damping", "N·s/m (rotary: N·m·s/rad)"),
        metavar="B",
        help="virtual damper B >= 0 in N·s/m (rotary: N·m·s/rad) on the backward-difference velocity (default: none)",
    )
    _add_filter_amplifier_args(g)


def _add_filter_amplifier_args(g: Any) -> None:
    """--velocity-filter and --amplifier-bandwidth (shared by the controller flags and ``zwidth``)."""
    g.add_argument(
        "--velocity-filter",
        dest="velocity_filter",
        type=_number("--velocity-filter", "Hz"),
        metavar="HZ",
        help="cutoff in Hz of a first-order low-pass on the velocity, below the Nyquist frequency 1/(2T) "
        "(default: no filter)",
    )
    g.add_argument(
        "--amplifier-bandwidth",
        dest="amplifier_bandwidth",
        type=_number("--amplifier-bandwidth", "Hz"),
        metavar="HZ",
        help="bandwidth in Hz of the current amplifier, a first-order lag τ_a = 1/(2π f_bw) (default: ideal)",
    )


def _controller(args: argparse.Namespace, device: Device | None, stiffness: float | None) -> Wall | None:
    """The wall controller of the flags; None for the paper's spring (no flag, or B = 0 without filter and lag).

    Refuses (UsageError, exit 2) a negative B, a cutoff <= 0 or not below the Nyquist frequency, a
    bandwidth <= 0, and controller flags without a physical device and stiffness.
    """
    given = [f for k, f in _CTL_FLAGS.items() if getattr(args, k, None) is not None]
    if not given:
        return None
    if device is None or stiffness is None:
        raise UsageError(
            f"{', '.join(given)} needs a physical device and stiffness (K and T turn B, f_c, f_bw into β_B, ν_c, α): "
            "give --device NAME (or --mass --damping --coulomb --resolution --period) and --stiffness K"
        )
    b, fc, bw = args.virtual_damping, args.velocity_filter, args.amplifier_bandwidth
    bu = device.units["damping"]
    if b is not None and b < 0:
        raise UsageError(f"--virtual-damping {b:g} is invalid: B must be >= 0; give the damper in {bu} (0 for none)")
    _check_filter_amplifier(args, device)
    ctl = Wall.of(stiffness, b or 0.0, args.delay, fc, bw)
    return None if ctl.params(device.period).is_spring else ctl


def _check_filter_amplifier(args: argparse.Namespace, device: Device) -> None:
    """Refuse (UsageError, exit 2) a filter cutoff <= 0 or not below the Nyquist frequency, a bandwidth <= 0."""
    fc, bw = args.velocity_filter, args.amplifier_bandwidth
    nyquist = 0.5 / device.period
    floor = MIN_CUTOFF * 2.0 * nyquist  # as Wall checks it, with the same rounding allowance
    if fc is not None and not floor * (1 - 1e-12) <= fc < nyquist:
        raise UsageError(
            f"--velocity-filter {fc:g} is invalid: the cutoff must be at least {floor:.6g} Hz ({MIN_CUTOFF:g} cycles "
            f"per sample: below, the filter pole cannot be told from the mass's pole in double precision) and below "
            f"the Nyquist frequency {nyquist:.6g} Hz (1/(2T), T = {device.period:g} s); give a cutoff in Hz in "
            f"[{floor:.6g}, {nyquist:.6g}), or drop the flag"
        )
    if bw is not None and not bw > 0:
        raise UsageError(
            f"--amplifier-bandwidth {bw:g} is invalid: it must be > 0 Hz; give f_bw in Hz, or drop the flag"
        )


def _wall_params(args: argparse.Namespace, ctl: Wall | None, inp: _Inputs | None) -> WallParams:
    """The dimensionless wall of a run: the controller's groups, else the spring with the --delay."""
    if ctl is None or inp is None or inp.device is None:
        return WallParams.of(delay=args.delay)
    return ctl.params(inp.device.period)


def _ctl_json(d: dict[str, Any], ctl: Wall | None, inp: _Inputs) -> dict[str, Any]:
    """Add the "controller" object (physical values and dimensionless groups) to a JSON record."""
    if ctl is not None and inp.device is not None:
        from .render.controller import controller_dict

        d["controller"] = controller_dict(ctl, inp.device.period, inp.device.units)
    return d


def _print_ctl(ctl: Wall | None, inp: _Inputs) -> None:
    """State the controller on its own line (nothing for the spring: its output is unchanged)."""
    if ctl is not None and inp.device is not None:
        from .render.controller import controller_line

        print(controller_line(ctl, inp.device.period, inp.device.units))


@dataclass(frozen=True)
class _Inputs:
    params: Params | None  # full (μ, β, σ) when known
    beta: float
    sigma: float
    device: Device | None
    stiffness: float | None
    label: str
    entry: CatalogueEntry | None = None  # the catalogue row, when the device is that row unchanged


def _resolve(
    args: argparse.Namespace, *, dimensionless: bool, need_mu: bool = True, need_stiffness: bool = True
) -> _Inputs:
    """Turn device/physical/dimensionless flags into parameters, rejecting contradictions.

    With ``need_stiffness=False`` a device without any stiffness (no --stiffness, no catalogue K) gives
    ``params=None`` and ``stiffness=None``.
    """
    phys_given = [k for k in _PHYS_FLAGS if getattr(args, k, None) is not None]
    dim_given = [k for k in _DIMLESS_FLAGS if getattr(args, k, None) is not None] if dimensionless else []
    if dim_given:
        others = (["--device"] if args.device else []) + [_PHYS_FLAGS[k][0] for k in phys_given]
        others += [f"--{k}" for k in ("counts", "name") if getattr(args, k, None) is not None]
        others += ["--stiffness"] if args.stiffness is not None else []
        others += ["--velocity"] if getattr(args, "velocity", None) is not None else []
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
        return _Inputs(p, b, s, None, None, "dimensionless input")
    custom = phys_given + [k for k in ("counts", "name") if getattr(args, k, None) is not None]
    if not args.device and not custom:
        raise UsageError(
            "no device given: use --device NAME (see `dfa devices`), or --mass --damping --coulomb "
            "--resolution --period" + (", or --mu --beta --sigma" if dimensionless else "")
        )
    r = resolve_device(
        args.device,
        overrides={k: getattr(args, k, None) for k in _PHYS_FLAGS},
        counts=getattr(args, "counts", None),
        rotary=bool(getattr(args, "rotary", False)),
        stiffness=args.stiffness,
        label=getattr(args, "name", None),
        flags=_FLAG_NAMES,
    )
    dev = r.device
    if r.stiffness is None and not need_stiffness:
        return _Inputs(None, math.nan, math.nan, dev, None, r.label, r.entry)
    if r.stiffness is None:
        raise UsageError(
            f"missing --stiffness: no catalogue stiffness for {dev.name!r}; give K in {dev.units['stiffness']}"
        )
    p = dimensionless_params(dev, r.stiffness)  # resolve_device has refused groups that overflow or vanish
    return _Inputs(p, p.beta, p.sigma, dev, r.stiffness, r.label, r.entry)


def _impact_speed(flag: str, value: float, inputs: _Inputs | None, zero: bool = True) -> float:
    """An impact speed from ``flag``: its magnitude, >= 0 (> 0 if not ``zero``); a negative is refused, not flipped."""
    if flag == "--xi-dot":
        unit = "ticks per sample"
    else:
        unit = inputs.device.units["velocity"] if inputs is not None and inputs.device is not None else "m/s (rad/s)"
    return check_speed(flag, value, unit, zero=zero)


def _speed(
    args: argparse.Namespace, inputs: _Inputs, required: bool = True, signed: bool = False
) -> tuple[float | None, float | None]:
    """Return (xi_dot, velocity) from --xi-dot / --velocity; unless ``signed``, an impact speed (>= 0)."""
    v, xd = args.velocity, args.xi_dot
    if not signed:
        v = None if v is None else _impact_speed("--velocity", v, inputs)
        xd = None if xd is None else _impact_speed("--xi-dot", xd, inputs)
    if v is not None and xd is not None:
        raise UsageError("--velocity and --xi-dot cannot both be given: choose one speed")
    if v is None and xd is None:
        if required:
            raise UsageError("missing speed: give --velocity V (m/s, rad/s) or --xi-dot V (encoder ticks per sample)")
        return None, None
    if v is not None:
        if inputs.device is None:
            raise UsageError("--velocity needs a physical device: with --mu/--beta/--sigma give --xi-dot instead")
        return inputs.device.xi_dot(v), v
    xd = check_real("--xi-dot", xd, "give the speed in encoder ticks per sample")
    return xd, (inputs.device.velocity(xd) if inputs.device is not None else None)


def _add_progress_args(p: argparse.ArgumentParser, quiet: bool = True) -> None:
    """--progress (and --quiet): the progress bar policy of :func:`_progress`."""
    p.add_argument(
        "--progress",
        action="store_true",
        help="progress bar with an estimate on stderr even when it is not a terminal (default: only on a terminal)",
    )
    if quiet:
        p.add_argument("--quiet", action="store_true", help="no progress bar (default: a bar on a terminal)")


def _progress(args: argparse.Namespace) -> bool:
    """Show progress bars: never with --quiet; always with --progress; else only on a terminal and without --json."""
    if getattr(args, "quiet", False):
        return False
    if getattr(args, "progress", False):
        return True
    if getattr(args, "json", False):
        return False
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


def _emit(obj: object) -> None:
    print(dumps(obj))  # strict JSON: NaN/inf become null with the reason (dfa.results.jsonable)


def _table(rows: Sequence[Sequence[object]], header: Sequence[str] | None = None) -> str:
    return text_table(rows, header)


def _g(x: float | None, digits: int = 4) -> str:
    return number(x, digits, none="-", inf="inf")


# ----------------------------------------------------------------- commands
def _cmd_devices(args: argparse.Namespace) -> int:
    rows = catalogue()
    if args.json:
        _emit([r.to_dict() for r in rows])
        return 0
    header = ["device", "m or J", "b", "c", "Δ", "T", "K", "μ", "β", "σ", "printed μ, β, σ", "flags"]
    body = []
    for r in rows:
        p = r.params
        pr = r.printed_params
        flags = []
        if r.incomplete:
            flags.append("incomplete")
        flags += [f"{d.parameter} {100 * d.relative:+.0f}%" for d in r.discrepancies]
        body.append(
            [
                r.name,
                _g(r.mass),
                _g(r.damping),
                _g(r.coulomb),
                _g(r.resolution),
                _g(r.period),
                _g(r.stiffness),
                _g(p.mu if p else None),
                _g(p.beta if p else None, 3),
                _g(p.sigma if p else None),
                ", ".join(pr.get(k) and f"{pr[k]:g}" or "-" for k in ("mu", "beta", "sigma")) if pr else "-",
                "; ".join(flags) or "ok",
            ]
        )
    print(_table(body, header))
    print(
        "\nSI units (linear: mass m in kg, N·s/m, N, m, s, N/m; rotary: inertia J in kg·m², N·m·s/rad, N·m, rad, s, N·m/rad)."
    )
    print(
        "μ, β, σ recomputed from the physical columns (paper Table 1); flags: printed value disagrees (> 5 % and beyond its last digit)."
    )
    return 0


def _cmd_params(args: argparse.Namespace) -> int:
    inp = _resolve(args, dimensionless=True)
    assert inp.params is not None
    if args.json:
        _emit(inp.params.to_dict())
        return 0
    print(f"{inp.label}")
    print(
        _table(
            [
                ["μ = m/(K T²)", f"{inp.params.mu:.6g}"],
                ["β = b/(K T)", f"{inp.params.beta:.6g}"],
                ["σ = c/(K Δ)", f"{inp.params.sigma:.6g}"],
            ]
        )
    )
    return 0


def _criterion_for_args(args: argparse.Namespace, inp: _Inputs, xd: float, v: float | None):
    """The criterion for `dfa check`: device mode takes --position (m, rad), dimensionless mode --xi0 (ticks)."""
    quantized = not args.no_quantization
    if inp.device is not None:
        assert inp.stiffness is not None  # a device always comes with its K (_resolve)
        if args.xi0 is not None:
            raise UsageError(
                "--xi0 is for dimensionless input: with a device give the initial position as --position (m, rad)"
            )
        return device_criterion(
            inp.device,
            Wall.of(inp.stiffness, delay=args.delay),
            inp.device.velocity(xd) if v is None else v,
            quantized=quantized,
            position=args.position or 0.0,
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
    wall = WallParams.of(delay=args.delay)
    return passivity_criterion(inp.beta, inp.sigma, xd, wall=wall, quantized=quantized, xi0=x0, mu=args.mu)


def _cmd_check(args: argparse.Namespace) -> int:
    from .render.text import check_rows

    inp = _resolve(args, dimensionless=True, need_mu=False)
    xd, v = _speed(args, inp)
    assert xd is not None
    ctl = _controller(args, inp.device, inp.stiffness)
    if ctl is not None:
        return _check_controller(args, inp, ctl, xd, v)
    r = _criterion_for_args(args, inp, xd, v)
    if args.json:
        _emit(r.to_dict())
        return 0
    vu = inp.device.units["velocity"] if inp.device else ""
    print(inp.label)
    print(_table(check_rows(r, not args.no_quantization, vu)))
    return 0


def _check_controller(args: argparse.Namespace, inp: _Inputs, ctl: Wall, xd: float, v: float | None) -> int:
    """`dfa check` with a controller: the extended criterion and Colgate–Schenkel; with a lag, not covered."""
    from .analysis.check import passivity_check
    from .render.controller import check_table_rows

    dev = inp.device
    assert dev is not None  # _controller refuses a controller without a device
    if args.xi0 is not None:
        raise UsageError(
            "--xi0 is for dimensionless input: with a device give the initial position as --position (m, rad)"
        )
    vel = dev.velocity(xd) if v is None else v
    chk = passivity_check(dev, ctl, vel, position=args.position or 0.0, quantized=not args.no_quantization)
    if args.json:
        _emit(_ctl_json(chk.to_dict(), ctl, inp))
        return 0
    print(inp.label)
    _print_ctl(ctl, inp)
    print(_table(check_table_rows(chk)))
    return 0


def _save_png(flag: str, path: str, ax) -> str:
    """Write the figure of ``ax`` to ``path`` as PNG, atomically; close it."""
    import matplotlib.pyplot as plt

    from ._io import atomic_open

    with atomic_open(path, "wb") as fh:
        ax.figure.savefig(fh, format="png", dpi=120, bbox_inches="tight")
    plt.close(ax.figure)
    return path


def _stiffness_source(args: argparse.Namespace, inp: _Inputs) -> str | None:
    """Where the assessed K came from: --stiffness, the catalogue, or nowhere (None)."""
    if args.stiffness is not None:
        return "--stiffness"
    return "catalogue" if inp.stiffness is not None else None


def _cmd_stiffness(args: argparse.Namespace) -> int:
    """`dfa stiffness`: K_max four ways for the spring or any wall (one path; the wall's K is searched)."""
    from .analysis.limits.kmax import design_answer
    from .render.limits import PROOF_NOTE, evidence_text, kmax_rows, verdict_text

    inp = _resolve(args, dimensionless=False, need_stiffness=False)
    dev = inp.device
    assert dev is not None
    _xd, v = _speed(args, inp)
    assert v is not None
    k = inp.stiffness
    ctl = _controller(args, dev, 1.0 if k is None else k)  # K is what is searched: any K states the elements
    wall = ctl if ctl is not None else Wall.of(1.0 if k is None else k, delay=args.delay)
    if args.plot is not None:
        check_output_file("--plot", args.plot, ".png")
    src = _stiffness_source(args, inp)
    ans = design_answer(dev, v, wall=wall, assess=k is not None, source="catalogue" if src == "catalogue" else "given")
    if args.plot is not None:
        from .analysis.limits.speed_chart import stiffness_speed_chart

        chart = stiffness_speed_chart(dev, wall=wall, stiffness=k, velocity=v if v > 0 else None)
        _save_png("--plot", args.plot, chart.plot())
    if args.json:
        rec = ans.to_dict()
        rec["stiffness_source"] = src
        explain_nulls(rec, {"stiffness_source": "no --stiffness given and no catalogue K"})
        if args.plot is not None:
            rec["plot"] = args.plot
        _emit(_ctl_json(rec, ctl, inp))
        return 0
    vu = dev.units["velocity"]
    d = wall.delay
    print(
        f"{dev.name}, impact speed {v:.4g} {vu} ({ans.xi_dot:.4g} ticks/sample), delay {d} sample{'s' if d != 1 else ''}"
        + ("" if ctl is None else "; B, f_c, f_bw held fixed while K varies")
    )
    _print_ctl(ctl, inp)
    rows = kmax_rows(ans, explain=args.explain)
    rows.append(["verdict at this speed", verdict_text(ans)])
    print(_table(rows))
    if v > 0:
        print(f"evidence: {evidence_text(ans)}.")
        print(f"{PROOF_NOTE} (or the first harmonic).")
    else:
        print("impact speed 0: the describing-function and simulated limits need a speed > 0.")
    if args.plot is not None:
        print(f"stiffness-speed chart written to {args.plot}")
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    from .analysis.simulation import MAX_RECORD_BYTES, default_samples, divergence_bound, preload_position, simulate
    from .render.text import simulation_rows

    inp = _resolve(args, dimensionless=True)
    p = inp.params
    assert p is not None
    xd, _v = _speed(args, inp, signed=True)  # an initial condition: the sign of ξ'0 is the direction of motion
    assert xd is not None
    ctl = _controller(args, inp.device, inp.stiffness)
    if args.preload and args.xi0 is not None:
        raise UsageError("--preload and --xi0 cannot both be given: the preload sets ξ0 from the speed")
    if args.trace is not None:
        check_output_file("--trace", args.trace)
    if args.preload:
        x0, v0 = preload_position(p.mu, xd), 0.0
    else:
        x0, v0 = (0.0 if args.xi0 is None else args.xi0), xd
    if not abs(x0) < SIMULATION_BOUND:
        src = "--xi0" if args.xi0 is not None else "the --preload position of this speed"
        raise UsageError(
            f"ξ0 = {x0:.4g} ticks from {src} is beyond the simulation bound of {SIMULATION_BOUND:g} ticks "
            "(the run would stop at once as unstable): give a smaller start"
        )
    n = (
        args.samples
        if args.samples is not None
        else default_samples(p.mu, p.beta, p.sigma, v0, x0, not args.no_quantization, wall=_wall_params(args, ctl, inp))
    )
    if args.trace is not None and 16 * (n + 1) > MAX_RECORD_BYTES:
        raise UsageError(
            f"--trace with --samples {n} would need {16 * (n + 1) / 1024**3:.1f} GiB of trajectory "
            f"(limit {MAX_RECORD_BYTES / 1024**3:.0f} GiB): drop --trace or lower --samples"
        )
    if args.samples is not None:  # the automatic length is capped (dfa.analysis.simulation.default_samples)
        _check_samples(args.samples, args.force)
    r = simulate(
        p.mu,
        p.beta,
        p.sigma,
        v0,
        args.samples,
        xi0=x0,
        quantize=not args.no_quantization,
        record=args.trace is not None,
        progress=_progress(args),
        bound=divergence_bound(x0, v0, p.mu, SIMULATION_BOUND),
        wall=_wall_params(args, ctl, inp),
    )
    if args.trace is not None:
        _write_trace(args.trace, r)
    phys = r.physical(inp.device, inp.stiffness) if inp.device is not None and inp.stiffness is not None else None
    if args.json:
        d = r.to_dict()
        if phys is not None:
            d.update(phys)
            d["velocity"] = _v
            explain_nulls(d, r.null_reasons())
        _emit(_ctl_json(d, ctl, inp))
        return 0
    print(f"{inp.label}: μ = {p.mu:.5g}, β = {p.beta:.5g}, σ = {p.sigma:.5g}")
    _print_ctl(ctl, inp)
    print(_table(simulation_rows(r, x0, v0, args.preload, phys)))
    if args.trace is not None:
        print(f"trace written to {args.trace}")
    return 0


#: Planned cost of one simulated sample in the worst case measured (an oscillating run, loaded machine).
SIMULATE_NS_PER_SAMPLE = 100
#: ``dfa simulate`` refuses runs estimated longer than this (seconds) unless --force (work is refused up
#: front; a run without delay is integrated in chunks and stops at Ctrl-C, one with a delay or one run of a
#: map cannot be interrupted before the compiled kernel returns).
SIMULATE_TIME_LIMIT = 30.0
#: ``dfa map`` refuses maps estimated longer than this (hours, at the worst-case cost per sample) unless --force.
MAP_TIME_LIMIT_HOURS = 24.0
#: |ξ| (ticks) beyond which a run counts as unstable (the default ``bound`` of :func:`dfa.simulate`).
SIMULATION_BOUND = 1.0e6


def _check_samples(samples: int, force: bool) -> None:
    if samples < 1:
        raise UsageError(f"--samples {samples} is invalid: simulate at least one sample")
    seconds = samples * SIMULATE_NS_PER_SAMPLE * 1e-9
    if seconds > SIMULATE_TIME_LIMIT and not force:
        raise UsageError(
            f"--samples {samples} could take up to {seconds:.3g} s (estimated {SIMULATE_NS_PER_SAMPLE} ns per sample; "
            f"limit {SIMULATE_TIME_LIMIT:g} s): lower --samples "
            f"(at most {int(SIMULATE_TIME_LIMIT / (SIMULATE_NS_PER_SAMPLE * 1e-9))}) or add --force"
        )


def _write_trace(path: str, r) -> None:
    from .render.files import write_trace_csv

    try:
        write_trace_csv(r, path)
    except OSError as exc:
        raise UsageError(f"--trace {path!r} cannot be written: {exc.strerror}; choose a writable file") from None


def _add_map_device_args(p: argparse.ArgumentParser, speeds: bool) -> None:
    """A device instead of --mu for `map` and `contours` (μ from the device at K; its (β, σ) is marked), and --plot."""
    g = _add_device_group(p, "device (instead of --mu: a catalogue name, or physical values in SI units)")
    if speeds:
        g.add_argument(
            "--velocity",
            type=_number("--velocity", "m/s (rotary: rad/s)"),
            nargs="+",
            metavar="V",
            help="initial speeds in m/s (rotary: rad/s; needs a device), instead of --xi-dot; default: none",
        )
    p.add_argument("--plot", metavar="FILE.png", help="write the figure to a PNG file (default: none)")


def _check_plane(args: argparse.Namespace) -> None:
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


def _map_device(args: argparse.Namespace) -> tuple[float, _Inputs | None]:
    """μ of `map`/`contours`: --mu, or a device at its stiffness (never both)."""
    _check_plane(args)
    given = bool(args.device) or any(getattr(args, k, None) is not None for k in _PHYS_FLAGS)
    given = given or any(getattr(args, k, None) is not None for k in ("stiffness", "counts", "name"))
    if args.mu is not None and given:
        raise UsageError("--mu cannot be combined with a device: give --mu, or --device/physical values (μ follows)")
    if args.mu is None and not given:
        raise UsageError(
            "missing --mu: give --mu, or a device (--device NAME, or --mass --damping --coulomb --resolution --period)"
        )
    if args.mu is not None:
        return check_mu(args.mu, "--mu"), None
    inp = _resolve(args, dimensionless=False)
    assert inp.params is not None
    return inp.params.mu, inp


def _map_speeds(args: argparse.Namespace, inp: _Inputs | None) -> list[float]:
    """ξ'0 values of `map` from --xi-dot or --velocity (m/s, with a device)."""
    if args.xi_dot is not None and args.velocity is not None:
        raise UsageError("--xi-dot and --velocity cannot both be given: choose one unit for the speeds")
    if args.velocity is None and args.xi_dot is None:
        raise UsageError("missing speeds: give --xi-dot V [V ...] (ticks per sample) or, with a device, --velocity")
    flag, given = ("--velocity", args.velocity) if args.velocity is not None else ("--xi-dot", args.xi_dot)
    negative = [v for v in given if v < 0]
    if negative:  # the flag and the value as given (not a --velocity converted to ticks)
        raise UsageError(
            f"{flag} {negative[0]:g} is invalid: initial speeds must be >= 0 (the map is symmetric in the "
            f"sign of ξ'0); give {flag} {abs(negative[0]):g}"
        )
    if args.velocity is not None:
        if inp is None or inp.device is None:
            raise UsageError("--velocity needs a device: with --mu give --xi-dot (ticks per sample)")
        return [inp.device.xi_dot(v) for v in args.velocity]
    return list(args.xi_dot)


def _device_json(inp: _Inputs | None, xi_dots: Sequence[float] = ()) -> dict[str, object]:
    """Device, K, force step, operating point and physical speeds for the JSON of `map`/`contours`."""
    if inp is None or inp.device is None or inp.stiffness is None or inp.params is None:
        return {}
    from .model.units import unit_context

    d = unit_context(inp.device, inp.stiffness)
    d.pop("velocity")
    d["operating_point"] = {"mu": inp.params.mu, "beta": inp.params.beta, "sigma": inp.params.sigma}
    d["tick_" + ("rad" if inp.device.rotary else "m")] = inp.device.resolution
    if xi_dots:
        d["velocities"] = [inp.device.velocity(x) for x in xi_dots]
    return d


def _outside_note(args: argparse.Namespace, inp: _Inputs) -> str:
    """A warning when the device's (β, σ) lies outside the plotted ranges (empty otherwise)."""
    assert inp.params is not None
    b0, b1 = sorted(args.beta_range)
    s0, s1 = sorted(args.sigma_range)
    if b0 <= inp.params.beta <= b1 and s0 <= inp.params.sigma <= s1:
        return ""
    return " (outside the (β, σ) range of the map: widen --beta-range/--sigma-range to see it)"


def _mark_operating_point(axes, inp: _Inputs | None) -> None:
    if inp is None or inp.params is None:
        return
    for ax in axes:
        from .figures import POINT_STYLE

        ax.plot([inp.params.beta], [inp.params.sigma], **POINT_STYLE)
        ax.annotate(
            f"{inp.device.name if inp.device else ''}, K = {inp.stiffness:g}",
            (inp.params.beta, inp.params.sigma),
            textcoords="offset points",
            xytext=(6, 6),
            fontsize=7,
            clip_on=True,
        )


def _check_map_work(args: argparse.Namespace) -> None:
    """Refuse a map that would run too long or not fit in memory, before any work (fix: smaller grid, --force)."""
    from ._io import check_memory
    from .analysis.maps import map_memory_bytes
    from .checks import check_jobs

    check_jobs("--jobs", args.jobs)
    _check_samples(args.samples, args.force)  # one run is uninterruptible: the same limit as `dfa simulate`
    if args.grid >= 2:
        runs = args.grid**2 * len(args.xi_dot)
        cores = (os.cpu_count() or 1) if args.jobs == -1 else args.jobs
        hours = runs * args.samples * SIMULATE_NS_PER_SAMPLE * 1e-9 / 3600 / cores
        if hours > MAP_TIME_LIMIT_HOURS and not args.force:
            raise UsageError(
                f"--grid {args.grid} with --samples {args.samples} could take up to {hours:.3g} h on {cores} cores "
                f"(estimated {SIMULATE_NS_PER_SAMPLE} ns per sample; limit {MAP_TIME_LIMIT_HOURS:g} h): "
                "lower --grid or --samples, or add --force"
            )
        check_memory(
            "--grid",
            args.grid,
            map_memory_bytes(args.grid, len(args.xi_dot)),
            "lower --grid or give fewer --xi-dot speeds",
        )


def _cmd_map(args: argparse.Namespace) -> int:
    from .analysis.maps import stability_map
    from .analysis.simulation import divergence_bound

    check_output_file("--out", args.out, ".npz")
    if args.plot is not None:
        check_output_file("--plot", args.plot, ".png")
    mu, inp = _map_device(args)
    args.xi_dot = _map_speeds(args, inp)
    _check_map_work(args)
    ctl = _controller(args, *((inp.device, inp.stiffness) if inp is not None else (None, None)))
    m = stability_map(
        mu,
        args.xi_dot,
        beta_range=tuple(args.beta_range),
        sigma_range=tuple(args.sigma_range),
        grid=args.grid,
        samples=args.samples,
        preload=args.preload,
        quantize=not args.no_quantization,
        n_jobs=args.jobs,
        progress=_progress(args),
        bound=divergence_bound(0.0, max(args.xi_dot), mu, SIMULATION_BOUND),  # beyond every start's travel
        wall=_wall_params(args, ctl, inp),
    )
    path = m.save(args.out)
    if args.plot is not None:
        from .figures import stability_map_plot

        dev, k = (inp.device, inp.stiffness) if inp is not None else (None, None)
        axes = stability_map_plot(m, device=dev, stiffness=k)
        _mark_operating_point(axes, inp)
        _save_png("--plot", args.plot, axes[0])
    if args.json:
        d = m.to_dict()
        d["out"] = str(path)
        d.update(_device_json(inp, m.xi_dots))
        if args.plot is not None:
            d["plot"] = args.plot
        _emit(d if ctl is None or inp is None else _ctl_json(d, ctl, inp))
        return 0
    if inp is not None and inp.params is not None and inp.device is not None:
        vu = inp.device.units["velocity"]
        print(
            f"{inp.label}: operating point β = {inp.params.beta:.5g}, σ = {inp.params.sigma:.5g}{_outside_note(args, inp)}; speeds "
            + ", ".join(f"{x:g} ticks/sample = {inp.device.velocity(x):.4g} {vu}" for x in m.xi_dots)
        )
        _print_ctl(ctl, inp)
    print(
        f"stability map μ = {m.mu:g}, β in [{m.beta[0]:g}, {m.beta[-1]:g}], σ in [{m.sigma[0]:g}, {m.sigma[-1]:g}], "
        f"{m.beta.size}×{m.sigma.size} points, {m.samples} samples" + (", spring preload" if m.preload else "")
    )
    names = ("rest", "chatter", "oscillating", "unstable", "undecided")
    print(
        _table(
            [[f"{v:g}", *(c[k] for k in names)] for v, c in zip(m.xi_dots, m.counts(), strict=False)], ["ξ'0", *names]
        )
    )
    print(f"written to {path}")
    if args.plot is not None:
        print(f"figure written to {args.plot}")
    return 0


def _cmd_limit_cycles(args: argparse.Namespace) -> int:
    from .analysis.cycles import growth_threshold
    from .render.text import limit_cycle_lines, limit_cycles_dict

    for flag, value in (("--max-amplitude", args.max_amplitude), ("--time-budget", args.time_budget)):
        if value is not None and not value > 0:
            raise UsageError(f"{flag} {value:g} is invalid: it must be > 0; give e.g. {flag} 10")
    inp = _resolve(args, dimensionless=True)
    p = inp.params
    assert p is not None
    ctl = _controller(args, inp.device, inp.stiffness)
    g = growth_threshold(
        p,
        inp.device,
        model=args.model,
        wall=_wall_params(args, ctl, inp),
        max_amplitude=args.max_amplitude,
        **({} if args.time_budget is None else {"time_budget": args.time_budget}),
    )
    res = g.result
    phys = None if inp.device is None or inp.stiffness is None else res.physical(inp.device, inp.stiffness)
    if args.json:
        d = limit_cycles_dict(g, phys)
        _emit(_ctl_json(d, ctl, inp))
        return 0
    print(
        f"{inp.label}: μ = {p.mu:.5g}, β = {p.beta:.5g}, σ = {p.sigma:.5g}; model {res.model}"
        + (f", delay {res.delay}" if res.delay else "")
    )
    _print_ctl(ctl, inp)
    for line in limit_cycle_lines(g, inp.device, phys):
        print(line)
    return 0


def _cmd_contours(args: argparse.Namespace) -> int:
    from .analysis.contours import check_contour_memory, contour_maps

    if args.out is not None:
        check_output_file("--out", args.out, ".npz")
    if args.plot is not None:
        check_output_file("--plot", args.plot, ".png")
    mu, inp = _map_device(args)
    if not args.max_amplitude >= 1.0:
        raise UsageError(
            f"--max-amplitude {args.max_amplitude:g} is invalid: it must be >= 1 tick (the large cycle family has "
            "M >= 1); give e.g. --max-amplitude 10"
        )
    if args.grid >= 2 and args.max_amplitude >= 1.0:
        check_contour_memory(args.grid, args.max_amplitude, ("--grid", "--max-amplitude"))
    c = contour_maps(
        mu,
        beta_range=tuple(args.beta_range),
        sigma_range=tuple(args.sigma_range),
        grid=args.grid,
        max_amplitude=args.max_amplitude,
        progress=_progress(args),
    )
    d = c.to_dict()
    if args.out is not None:
        d["out"] = str(c.save(args.out))
    if args.plot is not None:
        from .figures import contour_plot

        dev, k = (inp.device, inp.stiffness) if inp is not None else (None, None)
        axes = contour_plot(c, device=dev, stiffness=k)  # physical axes b, c like `dfa map --plot`
        _mark_operating_point(axes, inp)
        d["plot"] = _save_png("--plot", args.plot, axes[0])
    d.update(_device_json(inp))
    if inp is not None and inp.device is not None and inp.stiffness is not None:
        d["frequency_hz_per_rad_per_sample"] = 1.0 / (2.0 * math.pi * inp.device.period)
    if args.json:
        _emit(d)
        return 0
    print(
        f"contour maps μ = {c.mu:g}, β in [{c.beta[0]:g}, {c.beta[-1]:g}], σ in [{c.sigma[0]:g}, {c.sigma[-1]:g}], {c.beta.size}×{c.sigma.size}"
    )
    print(
        _table(
            [
                ["small stable (M < 1, eq. 42-43)", d["small_points"]],
                ["large unstable, exact D (eq. 41)", d["large_points"]],
                ["large unstable, closed form (eq. 44-45)", d["large_closed_points"]],
            ],
            ["family", "grid points"],
        )
    )
    if inp is not None and inp.params is not None and inp.device is not None:
        u = inp.device.units
        print(
            f"{inp.label}: operating point β = {inp.params.beta:.5g}, σ = {inp.params.sigma:.5g}{_outside_note(args, inp)}; "
            f"1 tick = {inp.device.resolution:.4g} {u['position']}, ω = 1 rad/sample = {d['frequency_hz_per_rad_per_sample']:.4g} Hz, "
            f"force step KΔ = {inp.stiffness * inp.device.resolution:.4g} {u['force']}"  # type: ignore[operator]
        )
    if args.out is not None:
        print(f"written to {d['out']}")
    if args.plot is not None:
        print(f"figure written to {args.plot}")
    return 0


def _read_validation(path: str) -> dict:
    """A validation summary the user names (``dfa validate`` writes it as validation.json)."""
    try:
        with open(path, encoding="utf-8") as fh:
            data = json.load(fh)
    except (OSError, ValueError) as exc:
        why = exc.strerror if isinstance(exc, OSError) else "not JSON"
        raise UsageError(
            f"--validation {path!r} cannot be read ({why}): give the validation.json that `dfa validate --out DIR` wrote"
        ) from None
    if not isinstance(data, dict) or "soundness_violations" not in data:
        raise UsageError(
            f"--validation {path!r} is not a validation summary: give the validation.json that `dfa validate` wrote"
        )
    return data


def _cmd_report(args: argparse.Namespace) -> int:
    from .report import design_report
    from .results.jsonable import dumps

    if args.device is None and not any(getattr(args, k, None) is not None for k in (*_PHYS_FLAGS, "counts")):
        args.device = DEFAULT_DEVICE
    check_output_folder("--out", args.out, create=True)  # the parent must exist; the folder is created
    inp = _resolve(args, dimensionless=False)
    assert inp.device is not None
    ctl = _controller(args, inp.device, inp.stiffness)  # None: the spring (no flag, or B = 0 without filter/lag)
    if args.zwidth is not None and args.zwidth < 0:
        raise UsageError(f"--zwidth {args.zwidth} is invalid: give the points per axis (0: no Z-width section)")
    _xd, v = _speed(args, inp, required=False)
    summary = _read_validation(args.validation) if args.validation is not None else None
    os.makedirs(args.out, exist_ok=True)
    res = design_report(
        inp.entry or inp.device,
        inp.stiffness,
        v,
        out_dir=args.out,
        fmt=args.format,
        progress=_progress(args),
        delay=args.delay,
        validation=summary,
        force=args.force,
        zwidth_grid=args.zwidth,
        controller=ctl,
    )
    if args.json:
        print(dumps(res.to_dict(), ensure_ascii=False))
        return 0
    for pth in res.paths:
        print(f"written {pth}")
    return 0


def _cmd_validate(args: argparse.Namespace) -> int:
    from .analysis.validation import validate
    from .checks import check_jobs
    from .render.files import write_validation

    check_jobs("--jobs", args.jobs)
    out = args.out
    check_output_folder("--out", out, create=True)  # the parent must exist; the folder itself is created
    v = validate(quick=args.quick, n_jobs=args.jobs, progress=_progress(args))
    summary = write_validation(v, out)  # all four files appear together, or none (dfa._io)
    if args.json:
        from .results.jsonable import dumps

        print(dumps(summary, ensure_ascii=False))
        return 0
    print(f"validation written to {os.path.join(out, 'validation.md')}")
    print(
        _table(
            [
                ["soundness violations", summary["soundness_violations"]],
                ["criterion rejects (share of points that come to rest)", f"{100 * summary['conservatism']:.1f} %"],
                [
                    "DF growth threshold vs simulated speed, median error",
                    f"{100 * summary['speed_df_median_error']:.2g} %",
                ],
                ["criterion speed ≤ simulated in every case", "yes" if summary["speeds_ordered"] else "no"],
            ]
        )
    )
    return 0


def _range_arg(p: argparse.ArgumentParser, flag: str, default: list[float], what: str) -> None:
    p.add_argument(
        flag,
        type=_number(flag, "dimensionless units"),
        nargs=2,
        default=default,
        metavar=("A", "B"),
        help=f"{what} range, dimensionless (default: {default[0]:g} {default[1]:g})",
    )


def _sub(sub: Any, name: str, help: str, example: str, func: Callable[[argparse.Namespace], int]) -> Any:
    """A subcommand with a one-line description and an example in its --help."""
    p = sub.add_parser(
        name,
        help=help,
        description=help[0].upper() + help[1:] + ".",
        epilog=f"example:\n  {example}",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.set_defaults(func=func)
    return p


def _add_devices(sub: Any) -> None:
    p = _sub(sub, "devices", "list the device catalogue (paper Table 2)", "dfa devices --json", _cmd_devices)
    p.add_argument("--json", action="store_true", help="print one JSON list on stdout (default: a text table)")


def _add_params(sub: Any) -> None:
    help = "dimensionless (μ, β, σ) of a device and stiffness (paper Table 1)"
    p = _sub(sub, "params", help, "dfa params --device impulse", _cmd_params)
    _add_device_args(p, dimensionless=True, speed=False)


def _add_check(sub: Any) -> None:
    help = "passivity criterion and region at an impact speed (eq. 6-12)"
    p = _sub(sub, "check", help, "dfa check --device delta --velocity 0.1", _cmd_check)
    _add_device_args(p, dimensionless=True, speed=True)
    p.add_argument("--no-quantization", action="store_true", help="use eq. 7 (Δ → 0) instead of eq. 6 (default: eq. 6)")
    _add_controller_args(p)
    p.add_argument(
        "--xi0",
        type=_number("--xi0", "ticks"),
        metavar="X",
        help="initial position ξ0 in ticks (dimensionless input; needs --mu); default: 0",
    )
    p.add_argument(
        "--position",
        type=_number("--position", "m (rotary: rad)"),
        metavar="X",
        help="initial position in m (rotary: rad; device input); default: 0",
    )


def _add_stiffness(sub: Any) -> None:
    help = (
        "largest stiffness for an impact speed, four ways: criterion (eq. 11), exact linear bound, "
        "describing function, simulation; bounds of eq. 8, 9"
    )
    p = _sub(sub, "stiffness", help, "dfa stiffness --device impulse --velocity 0.05 --stiffness 80", _cmd_stiffness)
    _add_device_args(p, dimensionless=False, speed=True)
    _add_controller_args(p)
    p.add_argument(
        "--explain",
        action="store_true",
        help="state what each simulated limit's confirmation simulated (default: the limits and their caveats)",
    )
    p.add_argument(
        "--plot",
        metavar="FILE.png",
        help="write the stiffness-speed chart (largest safe impact speed against K, four ways) to a PNG file "
        "(default: none)",
    )


def _add_simulate(sub: Any) -> None:
    help = "exact simulation of the sampled, quantized, frictional loop (eq. 4-5)"
    p = _sub(sub, "simulate", help, "dfa simulate --device delta --velocity 0.5", _cmd_simulate)
    _add_device_args(p, dimensionless=True, speed=True)
    p.add_argument("--xi0", type=_number("--xi0", "ticks"), metavar="X", help="initial position in ticks (default: 0)")
    p.add_argument(
        "--samples",
        type=_integer("--samples"),
        default=None,
        metavar="N",
        help="samples to simulate (default: from the loop's time scales, 50000 to 10^7)",
    )
    _add_controller_args(p)
    p.add_argument(
        "--preload",
        action="store_true",
        help="start at rest with the spring preloaded to the speed's kinetic energy (section 5; default: off)",
    )
    p.add_argument(
        "--no-quantization",
        action="store_true",
        help="linear spring φ = −ξ instead of the encoder staircase (default: with the encoder)",
    )
    p.add_argument("--trace", metavar="FILE.csv", help="write sample, xi, xi_dot (ticks) to a CSV file (default: none)")
    _add_progress_args(p)
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when --samples is estimated to take over {SIMULATE_TIME_LIMIT:g} s (default: refuse)",
    )


def _add_map(sub: Any) -> None:
    help = "stability map over the (β, σ) plane by simulation (paper Fig. 4)"
    p = _sub(sub, "map", help, "dfa map --mu 100 --xi-dot 1 5 --grid 50 --out fig4.npz", _cmd_map)
    p.add_argument(
        "--mu",
        type=_number("--mu", "dimensionless units"),
        help="μ = m/(K T²), dimensionless (required unless a device is given)",
    )
    p.add_argument(
        "--xi-dot",
        dest="xi_dot",
        type=_number("--xi-dot", "ticks per sample"),
        nargs="+",
        metavar="V",
        help="initial speeds ξ'0 in ticks per sample (required unless --velocity is given with a device)",
    )
    _range_arg(p, "--beta-range", [0.0, 1.0], "β")
    _range_arg(p, "--sigma-range", [0.0, 2.0], "σ")
    p.add_argument("--grid", type=_integer("--grid"), default=100, metavar="N", help="points per axis (default: 100)")
    p.add_argument(
        "--samples", type=_integer("--samples"), default=50_000, metavar="N", help="samples per run (default: 50000)"
    )
    _add_controller_args(p)
    p.add_argument("--preload", action="store_true", help="spring preload instead of an initial speed (default: off)")
    p.add_argument(
        "--no-quantization", action="store_true", help="linear spring, no encoder (default: with the encoder)"
    )
    _add_map_device_args(p, speeds=True)
    p.add_argument(
        "--jobs", type=_integer("--jobs"), default=-1, metavar="J", help="parallel jobs (default: -1, all cores)"
    )
    p.add_argument("--out", required=True, metavar="FILE.npz", help="where to write the map (required)")
    _add_progress_args(p)
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when one run is estimated over {SIMULATE_TIME_LIMIT:g} s or the map over {MAP_TIME_LIMIT_HOURS:g} h (default: refuse)",
    )
    p.add_argument("--json", action="store_true", help="print counts per outcome per speed as JSON (default: text)")


def _add_limit_cycles(sub: Any) -> None:
    help = "limit cycles by harmonic balance with the exact describing function (eq. 36-45)"
    p = _sub(sub, "limit-cycles", help, "dfa limit-cycles --device delta --model zoh", _cmd_limit_cycles)
    _add_device_args(p, dimensionless=True, speed=False)
    p.add_argument(
        "--model",
        choices=["half-delay", "zoh", "pade"],
        default="half-delay",
        help="hold model (default: half-delay; zoh is exact)",
    )
    _add_controller_args(p)
    p.add_argument(
        "--max-amplitude",
        type=_number("--max-amplitude", "ticks"),
        default=None,
        metavar="M",
        help="largest amplitude searched in ticks (default: up to where the envelope of eq. 41 excludes roots)",
    )
    p.add_argument(
        "--time-budget",
        type=_number("--time-budget", "seconds"),
        default=None,
        metavar="S",
        help="longest search time in seconds (default: 10, dfa.analysis.cycles.DEFAULT_TIME_BUDGET); "
        "when it is hit the search is reported incomplete",
    )


def _add_contours(sub: Any) -> None:
    help = "amplitude/frequency maps of both cycle families (paper Fig. 7)"
    p = _sub(sub, "contours", help, "dfa contours --mu 100 --grid 200 --out fig7.npz", _cmd_contours)
    p.add_argument(
        "--mu",
        type=_number("--mu", "dimensionless units"),
        help="μ = m/(K T²), dimensionless (required unless a device is given)",
    )
    _add_map_device_args(p, speeds=False)
    _range_arg(p, "--beta-range", [0.0, 1.0], "β")
    _range_arg(p, "--sigma-range", [0.0, 2.0], "σ")
    p.add_argument("--grid", type=_integer("--grid"), default=200, metavar="N", help="points per axis (default: 200)")
    p.add_argument(
        "--max-amplitude",
        type=_number("--max-amplitude", "ticks"),
        default=200.0,
        metavar="M",
        help="largest amplitude in ticks (default: 200)",
    )
    p.add_argument("--out", metavar="FILE.npz", help="write the maps (default: not written)")
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout (default: text)")
    _add_progress_args(p)


def _add_report(sub: Any) -> None:
    help = "design report of a device: verdict, limits, cycles, figures (HTML or Markdown)"
    p = _sub(sub, "report", help, "dfa report --device phantom --velocity 0.1 --out reports --format both", _cmd_report)
    _add_device_args(
        p,
        False,
        True,
        "print the paths written and the numbers stated as one JSON object (default: one line per file)",
    )
    p.add_argument(
        "--out", default="reports", metavar="DIR", help="output folder, created if missing (default: reports)"
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
        help="replace a report of the same name made for another device, stiffness, speed or delay (default: refuse)",
    )
    p.add_argument(
        "--zwidth",
        type=_integer("--zwidth"),
        metavar="N",
        help="Z-width section on an N x N grid (K against virtual damping B; default: none for the spring, "
        "16 with a controller flag; 0: none)",
    )
    _add_progress_args(p)
    _add_controller_args(p)


def _cmd_zwidth(args: argparse.Namespace) -> int:
    from .analysis.limits.zwidth import ZWIDTH_METHODS, z_width
    from .checks import check_jobs

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
    inp = _resolve(args, dimensionless=False, need_stiffness=False)
    dev = inp.device
    assert dev is not None
    _check_filter_amplifier(args, dev)
    if args.plot is not None:
        check_output_file("--plot", args.plot, ".png")
    wall = Wall.of(1.0, delay=args.delay, filter_cutoff=args.velocity_filter,
                   amplifier_bandwidth=args.amplifier_bandwidth)  # fmt: skip
    zw = z_width(
        dev,
        _impact_speed("--velocity", args.velocity, inp, zero=False),
        wall=wall,
        grid=args.grid,
        speeds=args.speeds,
        n_jobs=args.jobs,
        progress=_progress(args),
    )
    if args.plot is not None:
        _save_png("--plot", args.plot, zw.plot())
    if args.json:
        rec = zw.to_dict()
        if args.plot is not None:
            rec["plot"] = args.plot
        _emit(rec)
        return 0
    u = dev.units
    names = {"linear": "linear", "passivity": "C-S passivity", "criterion": "criterion", "df": "describing fn",
             "sim": "sim (no div.)", "rest": "sim (rest)"}  # fmt: skip
    rows = [[_g(float(b))] + [_g(None if not math.isfinite(x) else float(x)) for x in col]
            for b, col in zip(zw.damping, zip(*(zw.boundary(m) for m in ZWIDTH_METHODS), strict=True), strict=True)]  # fmt: skip
    ctl = f"delay {zw.delay}"
    fc, bw = zw.wall.filter_cutoff, zw.wall.amplifier_bandwidth
    ctl += f", velocity filter {_g(fc)} Hz" if fc is not None else ""
    ctl += f", amplifier {_g(bw)} Hz" if bw is not None else ""
    print(f"Z-width of {dev.name}: impacts up to {zw.velocity:.4g} {u['velocity']}, {ctl}; status {zw.status}")
    print(f"K_max(B) in {u['stiffness']} ('-': undefined, see --json for the reason)")
    print(_table(rows, [f"B ({u['damping']})"] + [names[m] for m in ZWIDTH_METHODS]))
    print(
        f"{zw.simulations} exact simulations on a {zw.stiffness.size} x {zw.damping.size} grid "
        f"(K {zw.stiffness[0]:.4g} to {zw.stiffness[-1]:.4g} {u['stiffness']}); simulated limits are grid values"
    )
    if zw.counterexamples:
        print(f"COUNTEREXAMPLES to the extended criterion: {len(zw.counterexamples)} (see --json)")
    if args.plot is not None:
        print(f"Z-width figure written to {args.plot}")
    return 0


def _add_zwidth(sub: Any) -> None:
    help = (
        "Z-width: the renderable region of the (K, B) plane by the exact linear bound, passivity, "
        "the describing function and exact simulation"
    )
    p = _sub(sub, "zwidth", help, "dfa zwidth --device impulse --velocity 0.1 --grid 20", _cmd_zwidth)
    _add_device_group(p, "device (a catalogue name, or physical values in SI units)")
    p.add_argument(
        "--velocity",
        required=True,
        type=_number("--velocity", "m/s (rotary: rad/s)"),
        metavar="V",
        help="impact speed in m/s (rotary: rad/s); required",
    )
    _add_delay_arg(p)
    g = p.add_argument_group("wall controller (B is the Z-width's axis)")
    _add_filter_amplifier_args(g)
    g.add_argument(
        "--virtual-damping",
        type=_number("--virtual-damping", "N·s/m (rotary: N·m·s/rad)"),
        default=None,
        metavar="B",
        help="not accepted here: B is the Z-width's axis, its grid spans B from 0 (default: the grid)",
    )
    p.add_argument("--grid", type=_integer("--grid"), default=40, metavar="N", help="points per axis (default: 40)")
    p.add_argument(
        "--speeds",
        type=_integer("--speeds"),
        default=2,
        metavar="N",
        help="impact speeds simulated, V/N ... V (default: 2)",
    )
    p.add_argument("--jobs", type=_integer("--jobs"), default=-1, metavar="N", help="threads (default: -1, all cores)")
    p.add_argument("--plot", metavar="FILE.png", help="write the Z-width figure to a PNG file (default: none)")
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout (default: a text table)")
    _add_progress_args(p)


def _add_validate(sub: Any) -> None:
    help = "validate the predictions against exact simulation; writes validation.md"
    p = _sub(sub, "validate", help, "dfa validate --quick --out reports/validation", _cmd_validate)
    p.add_argument("--quick", action="store_true", help="a reduced set, under a minute (default: the full set)")
    p.add_argument(
        "--jobs", type=_integer("--jobs"), default=-1, metavar="J", help="parallel jobs (default: -1, all cores)"
    )
    p.add_argument(
        "--out", default="reports/validation", metavar="DIR", help="output folder (default: reports/validation)"
    )
    _add_progress_args(p)
    p.add_argument("--json", action="store_true", help="print the summary as JSON (default: text)")


class _Version(argparse.Action):
    """``--version``: the installed distribution's version (importlib.metadata), looked up only when asked."""

    def __init__(self, option_strings: Sequence[str], dest: str = argparse.SUPPRESS, **kwargs: Any) -> None:
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser: argparse.ArgumentParser, *args: Any, **kwargs: Any) -> None:
        print(f"dfa {package_version()}")
        parser.exit(0)


def package_version() -> str:
    """Version of the installed distribution (``dfa.__version__``, from ``importlib.metadata``)."""
    from . import __version__

    return __version__


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="dfa",
        description="Passivity, limit cycles and stiffness limits of sampled, quantized haptic devices "
        "(Diolaiti, Niemeyer, Barbagli & Salisbury, ICRA 2005).",
        epilog="`dfa COMMAND --help` describes each command. Without a command, dfa prints this help and exits with 2.",
    )
    parser.add_argument("--version", action=_Version, help="print the installed version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for add in (_add_devices, _add_params, _add_check, _add_stiffness, _add_simulate, _add_map, _add_limit_cycles,
                _add_contours, _add_report, _add_validate, _add_zwidth):  # fmt: skip
        add(sub)
    return parser


class _Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM received: unwinds like Ctrl-C so that every ``finally`` cleans up."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_SIGNALS = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM") if hasattr(signal, n))


def _on_signal(signum: int, frame: object) -> None:
    for sig in _SIGNALS:  # a second signal must not interrupt the clean-up of the first
        signal.signal(sig, signal.SIG_IGN)
    raise _Interrupted(signum)


def _install_signal_handlers() -> dict:
    """Route SIGINT and SIGTERM to :class:`_Interrupted` (main thread only); return the old handlers."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        return {}
    old = {}
    for sig in _SIGNALS:
        old[sig] = signal.getsignal(sig)
        signal.signal(sig, _on_signal)
    return old


def _one_line_warning(message: Warning | str, category: type[Warning], *_args: object, **_kw: object) -> str:
    """A warning on stderr as one line, like the errors (no source file or code line)."""
    text = " ".join(str(message).split())
    return f"dfa: warning: {text} ({category.__name__})\n"


def _quiet_stdout() -> None:
    """After a closed pipe: send what is left on stdout to /dev/null, so exiting does not raise again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, AttributeError, ValueError):  # not a real file (captured in tests)
        pass


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``dfa`` command line; return the exit code.

    Exit codes: 0 ok; 2 bad input (one line on stderr, before any work is
    done), or no command at all (bare ``dfa`` prints the help on stdout); 1 a file could not be written or memory ran out; 130 / 143
    interrupted by SIGINT / SIGTERM (one line on stderr naming what was kept:
    files are written atomically, so nothing is half-written); 141 stdout was
    a closed pipe (``dfa devices | head -1``), ended quietly.
    """
    parser = _build_parser()
    before = len(written_paths())
    old_handlers = _install_signal_handlers()
    old_format = warnings.formatwarning
    warnings.formatwarning = _one_line_warning
    try:
        argv = list(sys.argv[1:] if argv is None else argv)
        if not argv:  # bare `dfa`: the help, and exit code 2 (no command ran)
            parser.print_help()
            return 2
        args = parser.parse_args(argv)
        if getattr(args, "func", None) is None:
            raise UsageError("dfa: error: give a COMMAND (see `dfa --help`)")
        return int(args.func(args) or 0)
    except DFAError as err:
        msg = str(err)
        if not msg.startswith("dfa"):
            msg = f"dfa: error: {msg}"
        print(msg.replace("\n", " "), file=sys.stderr)
        return 2
    except SystemExit as exc:  # --help and --version
        return int(exc.code or 0)
    except KeyboardInterrupt as exc:
        signum = getattr(exc, "signum", int(signal.SIGINT))
        kept = written_paths()[before:]
        what = "nothing written" if not kept else "kept " + ", ".join(kept) + " (complete)"
        print(f"dfa: interrupted ({signal.Signals(signum).name}); {what}", file=sys.stderr)
        return 128 + int(signum)
    except BrokenPipeError:
        _quiet_stdout()
        return 141
    except MemoryError:
        print("dfa: error: out of memory; lower --grid, --samples or the number of speeds", file=sys.stderr)
        return 1
    except OSError as err:
        where = f"{err.filename!r}: " if err.filename else ""
        print(
            f"dfa: error: {where}{err.strerror or err}; check the path, its permissions and free space", file=sys.stderr
        )
        return 1
    finally:
        warnings.formatwarning = old_format
        for sig, handler in old_handlers.items():
            signal.signal(sig, handler if handler is not None else signal.SIG_DFL)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
