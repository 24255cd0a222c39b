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
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from ._io import check_output_file, check_output_folder, written_paths
from .catalogue import DEFAULT_DEVICE, catalogue, get_device
from .criterion import device_criterion, passivity_criterion
from .device import Device, Params, dimensionless_params
from .errors import (
    DFAError,
    DFAValueError,
    check_beta,
    check_mu,
    check_nonnegative,
    check_positive,
    check_real,
    check_sigma,
)
from .stiffness import stiffness_limits

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
    "mass": ("--mass", "kg (rotary: kg·m²)"),
    "damping": ("--damping", "N·s/m (rotary: N·m·s/rad)"),
    "coulomb": ("--coulomb", "N (rotary: N·m)"),
    "resolution": ("--resolution", "m (rotary: rad)"),
    "period": ("--period", "s"),
}
_DIMLESS_FLAGS = {"mu": "--mu", "beta": "--beta", "sigma": "--sigma"}


def _add_device_args(p: argparse.ArgumentParser, dimensionless: bool, speed: bool) -> None:
    g = p.add_argument_group("device (a catalogue name, or physical values in SI units)")
    g.add_argument("--device", metavar="NAME", help="catalogue device (case-insensitive prefix, e.g. 'phantom')")
    for key, (flag, unit) in _PHYS_FLAGS.items():
        g.add_argument(
            flag,
            dest=key,
            type=_number(flag, unit),
            metavar="X",
            help=f"{key} in {unit}; overrides the catalogue value",
        )
    g.add_argument(
        "--stiffness",
        type=_number("--stiffness", "N/m"),
        metavar="K",
        help="virtual wall stiffness K in N/m (rotary: N·m/rad); defaults to the catalogue K",
    )
    g.add_argument("--rotary", action="store_true", help="physical values are rotary (rad, N·m, kg·m²)")
    if dimensionless:
        d = p.add_argument_group("dimensionless parameters (instead of a device)")
        d.add_argument("--mu", type=_number("--mu", "dimensionless units"), help="μ = m/(K T²)")
        d.add_argument("--beta", type=_number("--beta", "dimensionless units"), help="β = b/(K T)")
        d.add_argument("--sigma", type=_number("--sigma", "dimensionless units"), help="σ = c/(K Δ)")
    if speed:
        s = p.add_argument_group("speed (one of)")
        s.add_argument(
            "--velocity",
            type=_number("--velocity", "m/s (rotary: rad/s)"),
            metavar="V",
            help="impact speed in m/s (rotary: rad/s)",
        )
        s.add_argument(
            "--xi-dot",
            dest="xi_dot",
            type=_number("--xi-dot", "encoder ticks per sample"),
            metavar="V",
            help="impact speed ξ'0 in encoder ticks per sample",
        )
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout")


def _delay(text: str) -> int:
    try:
        out = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"{text!r} is not a whole number: --delay takes the computational delay in samples (integer >= 0)"
        ) from None
    if out < 0:
        raise argparse.ArgumentTypeError(f"{text!r} is invalid: --delay must be a whole number of samples >= 0")
    return out


def _add_delay_arg(p: argparse.ArgumentParser) -> None:
    p.add_argument(
        "--delay",
        type=_delay,
        default=0,
        metavar="N",
        help="computational delay in samples (default 0): the force of sample h uses the reading of sample h − N",
    )


@dataclass(frozen=True)
class _Inputs:
    params: Params | None  # full (μ, β, σ) when known
    beta: float
    sigma: float
    device: Device | None
    stiffness: float | None
    label: str


def _resolve(args: argparse.Namespace, *, dimensionless: bool, need_mu: bool = True) -> _Inputs:
    """Turn device/physical/dimensionless flags into parameters, rejecting contradictions."""
    phys_given = [k for k in _PHYS_FLAGS if getattr(args, k, None) is not None]
    dim_given = [k for k in _DIMLESS_FLAGS if getattr(args, k, None) is not None] if dimensionless else []
    if dim_given:
        others = (["--device"] if args.device else []) + [_PHYS_FLAGS[k][0] for k in phys_given]
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
    values: dict[str, object] = {}
    stiffness = args.stiffness
    name = "custom device"
    rotary = bool(getattr(args, "rotary", False))
    if args.device:
        entry = get_device(args.device)
        values = {k: getattr(entry, k) for k in _PHYS_FLAGS}
        name, rotary = entry.name, entry.rotary or rotary
        if stiffness is None:
            stiffness = entry.stiffness
    for k in phys_given:
        flag, unit = _PHYS_FLAGS[k]
        check = check_positive if k in ("mass", "resolution", "period") else check_nonnegative
        values[k] = check(flag, getattr(args, k), f"give {k} in {unit}")
    missing = [_PHYS_FLAGS[k][0] for k in _PHYS_FLAGS if values.get(k) is None]
    if missing:
        if args.device:
            raise UsageError(f"device {name!r} is incomplete in the catalogue: give {' '.join(missing)} explicitly")
        if not phys_given:
            raise UsageError(
                "no device given: use --device NAME (see `dfa devices`), or --mass --damping --coulomb "
                "--resolution --period" + (", or --mu --beta --sigma" if dimensionless else "")
            )
        raise UsageError(
            f"missing {' '.join(missing)}: a physical device needs all of --mass --damping --coulomb --resolution --period"
        )
    dev = Device(name=name, rotary=rotary, **values)  # type: ignore[arg-type]
    if stiffness is None:
        raise UsageError(
            f"missing --stiffness: no catalogue stiffness for {name!r}; give K in {dev.units['stiffness']}"
        )
    k = check_positive("--stiffness", stiffness, f"give the virtual wall stiffness K in {dev.units['stiffness']}")
    names = {key: _PHYS_FLAGS[key][0] for key in phys_given}
    if args.stiffness is not None:
        names["stiffness"] = "--stiffness"
    p = dimensionless_params(dev, k, names)  # refuses μ, β, σ that overflow or vanish, naming these flags
    return _Inputs(p, p.beta, p.sigma, dev, float(stiffness), f"{name}, K = {stiffness:g} {dev.units['stiffness']}")


def _speed(args: argparse.Namespace, inputs: _Inputs, required: bool = True) -> tuple[float | None, float | None]:
    """Return (xi_dot, velocity) from --xi-dot / --velocity."""
    v, xd = args.velocity, args.xi_dot
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
        "--progress", action="store_true", help="progress bar with an estimate on stderr even when it is not a terminal"
    )
    if quiet:
        p.add_argument("--quiet", action="store_true", help="no progress bar")


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
    print(json.dumps(obj, allow_nan=False))


def _table(rows: Sequence[Sequence[object]], header: Sequence[str] | None = None) -> str:
    cells = [[str(c) for c in r] for r in ([header] if header else []) + list(rows)]
    widths = [max(len(r[i]) for r in cells) for i in range(len(cells[0]))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths, strict=False)).rstrip() for r in cells]
    if header:
        lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join(lines)


def _g(x: float | None, digits: int = 4) -> str:
    if x is None:
        return "-"
    if isinstance(x, float) and math.isinf(x):
        return "inf"
    return f"{x:.{digits}g}"


_OUTCOME_TEXT = {
    "rest": "came to rest",
    "chatter": "never comes to rest; the force keeps toggling below one tick of motion (a buzz)",
    "oscillating": "persistent oscillation of one tick or more",
    "unstable": "diverged (past the bound, or a growing envelope)",
    "undecided": "the motion is still changing at the end of the run",
}


# ----------------------------------------------------------------- commands
def _cmd_devices(args: argparse.Namespace) -> int:
    rows = catalogue()
    if args.json:
        _emit([r.as_dict() for r in rows])
        return 0
    header = ["device", "m", "b", "c", "Δ", "T", "K", "μ", "β", "σ", "printed μ, β, σ", "flags"]
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
    print("\nSI units (linear: kg, N·s/m, N, m, s, N/m; rotary: kg·m², N·m·s/rad, N·m, rad, s, N·m/rad).")
    print(
        "μ, β, σ recomputed from the physical columns (paper Table 1); flags: printed value disagrees (> 5 % and beyond its last digit)."
    )
    return 0


def _cmd_params(args: argparse.Namespace) -> int:
    inp = _resolve(args, dimensionless=True)
    assert inp.params is not None
    if args.json:
        _emit(inp.params.as_dict())
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
        if args.xi0 is not None:
            raise UsageError(
                "--xi0 is for dimensionless input: with a device give the initial position as --position (m, rad)"
            )
        return device_criterion(
            inp.device,
            inp.stiffness,
            inp.device.velocity(xd) if v is None else v,  # type: ignore[arg-type]
            quantized=quantized,
            delay=args.delay,
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
    return passivity_criterion(inp.beta, inp.sigma, xd, quantized=quantized, delay=args.delay, xi0=x0, mu=args.mu)


def _check_rows(r, quantized: bool, vu: str) -> list[list[str]]:
    """Rows of the `dfa check` table; every verdict says what is proven and what is not."""
    d = r.delay
    crit = "none" if r.critical_xi_dot is None else f"{r.critical_xi_dot:.4g} ticks/sample"
    if r.critical_velocity is not None:
        crit += f" ({r.critical_velocity:.4g} {vu})"
    if r.critical_xi_dot is not None and r.xi0 != 0.0:
        crit += ", a bound on the equivalent speed V, not on ξ'0"
    speed = f"{r.xi_dot:.4g} ticks/sample" + (f" ({r.velocity:.4g} {vu})" if r.velocity is not None else "")
    s0 = "½" if quantized else "0"
    rule = f"(β − ½ − d)V + (σ − {s0}) ≥ 0" + (" and σ ≥ ½" if quantized else "")
    if r.passive:
        upto = "at every speed" if r.region == "a" else f"for speeds up to V = {r.critical_xi_dot:.4g} ticks/sample"
        verdict = f"yes: the energy cannot grow {upto} (proven)"
    else:
        verdict = "no: no passivity guarantee (not a proof of instability)"
    rows = [["β, σ", f"{r.beta:.4g}, {r.sigma:.4g}"], ["speed |ξ'0|", speed]]
    if r.xi0 != 0.0:
        pos = f" ({r.position:.4g} {r.device.units['position']})" if r.device is not None else ""
        rows.append(["initial position ξ0", f"{r.xi0:.4g} ticks{pos}"])
    rows += [
        ["equivalent speed V", f"{r.equivalent_speed:.4g} ticks/sample (½μV² = stored energy, eq. 19)"],
        ["delay d", f"{d} sample{'s' if d != 1 else ''}"],
        ["criterion", ("eq. 6 (with encoder)" if quantized else "eq. 7 (no quantization)") + f": {rule}"],
        ["region", f"{r.region}: {r.status}"],
        ["passive", verdict],
        ["margin", f"{r.margin:.4g}"],
        [f"critical speed (eq. 12, d = {d})", crit],
    ]
    return rows


def _cmd_check(args: argparse.Namespace) -> int:
    inp = _resolve(args, dimensionless=True, need_mu=False)
    xd, v = _speed(args, inp)
    assert xd is not None
    r = _criterion_for_args(args, inp, xd, v)
    if args.json:
        _emit(r.as_dict())
        return 0
    vu = inp.device.units["velocity"] if inp.device else ""
    print(inp.label)
    print(_table(_check_rows(r, not args.no_quantization, vu)))
    return 0


def _cmd_stiffness(args: argparse.Namespace) -> int:
    inp = _resolve(args, dimensionless=False)
    dev = inp.device
    assert dev is not None
    xd, v = _speed(args, inp)
    assert v is not None
    k_given = args.stiffness  # only an explicit --stiffness is assessed
    lim = stiffness_limits(dev, v, k_given, delay=args.delay)
    if args.json:
        _emit(lim.as_dict())
        return 0
    ku, vu = dev.units["stiffness"], dev.units["velocity"]
    d = lim.delay
    cs = "2b/T" if d == 0 else "b/(T(½ + d))"
    rows = [
        [f"criterion K_max at this speed (eq. 11, d = {d})", f"{lim.k_max:.5g} {ku}"],
        ["static limit 2c/Δ (eq. 9)", f"{lim.k_static:.5g} {ku}"],
        [f"Colgate-Schenkel {cs} (eq. 8)", f"{lim.k_colgate:.5g} {ku}"],
        [f"Abbott-Okamura min({cs}, 2c/Δ)", f"{lim.k_abbott_okamura:.5g} {ku}"],
        ["exact linear bound (all Jury conditions" + (f", delay {d})" if d else ")"), f"{lim.k_gil:.5g} {ku}"],
    ]
    if lim.stiffness is not None:
        rows.append([f"largest passive speed at K = {lim.stiffness:g}", lim.max_passive_velocity_text()])
        rows.append(["verdict at this speed", lim.verdict_text()])
    print(
        f"{dev.name}, impact speed {lim.velocity:.4g} {vu} ({lim.xi_dot:.4g} ticks/sample), delay {d} sample{'s' if d != 1 else ''}"
    )
    print(_table(rows))
    return 0


def _cmd_simulate(args: argparse.Namespace) -> int:
    from .simulation import MAX_RECORD_BYTES, default_samples, preload_position, simulate

    inp = _resolve(args, dimensionless=True)
    p = inp.params
    assert p is not None
    xd, _v = _speed(args, inp)
    assert xd is not None
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
        else default_samples(p.mu, p.beta, p.sigma, v0, x0, args.delay, not args.no_quantization)
    )
    if args.trace is not None and 16 * (n + 1) > MAX_RECORD_BYTES:
        raise UsageError(
            f"--trace with --samples {n} would need {16 * (n + 1) / 1024**3:.1f} GiB of trajectory "
            f"(limit {MAX_RECORD_BYTES / 1024**3:.0f} GiB): drop --trace or lower --samples"
        )
    if args.samples is not None:  # the automatic length is capped (dfa.simulation.default_samples)
        _check_samples(args.samples, args.force)
    r = simulate(
        p.mu,
        p.beta,
        p.sigma,
        v0,
        args.samples,
        xi0=x0,
        delay=args.delay,
        quantize=not args.no_quantization,
        record=args.trace is not None,
        progress=_progress(args),
    )
    if args.trace is not None:
        _write_trace(args.trace, r)
    phys = r.physical(inp.device, inp.stiffness) if inp.device is not None and inp.stiffness is not None else None
    if args.json:
        d = r.as_dict()
        if phys is not None:
            d.update(device=inp.device.name, stiffness=inp.stiffness, **phys)  # type: ignore[union-attr]
        _emit(d)
        return 0
    print(f"{inp.label}: μ = {p.mu:.5g}, β = {p.beta:.5g}, σ = {p.sigma:.5g}")
    freq = "-" if r.frequency is None else f"{r.frequency:.4g} rad/sample (period {r.period:.4g} samples)"
    if phys is not None and phys["frequency_hz"] is not None:
        freq += f", {phys['frequency_hz']:.4g} Hz"
    rows = [
        [
            "initial state",
            f"ξ0 = {x0:.5g} ticks, ξ'0 = {v0:.5g} ticks/sample" + (" (spring preload)" if args.preload else ""),
        ],
        [
            "samples",
            f"{r.samples_run} of {r.samples} integrated"
            + (" (length from the loop's time scales)" if r.samples_auto else "")
            + (f", delay {r.delay}" if r.delay else ""),
        ],
        ["outcome", f"{r.outcome}: {_OUTCOME_TEXT[r.outcome]}"],
    ]
    if r.suggested_samples is not None:
        rows.append(["to decide", f"run longer: --samples {r.suggested_samples}"])
    rows += [
        ["rest at sample", "-" if r.rest_sample is None else str(r.rest_sample)],
        ["amplitude", f"{_g(r.amplitude)} ticks"],
        ["frequency", freq],
    ]
    if r.outcome in ("chatter", "oscillating", "undecided"):
        force = f"{_g(r.force_peak_to_peak)} KΔ" + ("" if r.quantize else " (linear spring)")
        if phys is not None and phys["force_peak_to_peak_si"] is not None:
            force += f" = {phys['force_peak_to_peak_si']:.4g} {phys['force_unit']}"
        rows.append(["force peak-to-peak", force + " (tail)"])
    rows.append(["final state", f"ξ = {_g(r.final_xi)}, ξ' = {_g(r.final_xi_dot)}"])
    print(_table(rows))
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
    import numpy as np

    from ._io import atomic_open

    try:
        with atomic_open(path, "w") as fh:
            fh.write("sample,xi,xi_dot\n")
            np.savetxt(
                fh, np.column_stack([np.arange(r.xi.size), r.xi, r.xi_dot]), delimiter=",", fmt=["%d", "%.17g", "%.17g"]
            )
    except OSError as exc:
        raise UsageError(f"--trace {path!r} cannot be written: {exc.strerror}; choose a writable file") from None


def _cmd_map(args: argparse.Namespace) -> int:
    from ._io import check_memory
    from .maps import check_jobs, map_memory_bytes, stability_map

    check_output_file("--out", args.out, ".npz")
    negative = [v for v in args.xi_dot if v < 0]
    if negative:
        raise UsageError(
            f"--xi-dot {negative[0]:g} is invalid: initial speeds must be >= 0 (the map is symmetric in the "
            f"sign of ξ'0); give --xi-dot {abs(negative[0]):g}"
        )
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
    m = stability_map(
        args.mu,
        args.xi_dot,
        beta_range=tuple(args.beta_range),
        sigma_range=tuple(args.sigma_range),
        grid=args.grid,
        samples=args.samples,
        delay=args.delay,
        preload=args.preload,
        quantize=not args.no_quantization,
        n_jobs=args.jobs,
        progress=_progress(args),
    )
    path = m.save(args.out)
    if args.json:
        d = m.as_dict()
        d["out"] = str(path)
        _emit(d)
        return 0
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
    return 0


def _cmd_limit_cycles(args: argparse.Namespace) -> int:
    from .cycles import growth_threshold

    for flag, value in (("--max-amplitude", args.max_amplitude), ("--time-budget", args.time_budget)):
        if value is not None and not value > 0:
            raise UsageError(f"{flag} {value:g} is invalid: it must be > 0; give e.g. {flag} 10")
    inp = _resolve(args, dimensionless=True)
    p = inp.params
    assert p is not None
    g = growth_threshold(
        p,
        inp.device,
        model=args.model,
        delay=args.delay,
        max_amplitude=args.max_amplitude,
        **({} if args.time_budget is None else {"time_budget": args.time_budget}),
    )
    res = g.result
    if args.json:
        d = res.as_dict()
        d["growth_threshold"] = g.as_dict()
        _emit(d)
        return 0
    print(
        f"{inp.label}: μ = {p.mu:.5g}, β = {p.beta:.5g}, σ = {p.sigma:.5g}; model {res.model}"
        + (f", delay {res.delay}" if res.delay else "")
    )
    for line in _cycle_lines(g, inp.device):
        print(line)
    return 0


def _cycle_lines(g, device) -> list[str]:
    """Text of `dfa limit-cycles`: the table, the search's completeness, the linear loop and the growth band."""
    res = g.result
    lines = []
    lin = (
        "the linear loop without encoder and Coulomb friction (exact ZOH model"
        + (f", delay {res.delay}" if res.delay else "")
        + ")"
    )
    why = res.status.removeprefix("incomplete: ")
    if not res.cycles:
        if not res.complete:
            lines.append(f"no limit cycle found up to M = {res.max_amplitude:g} ticks (search incomplete: {why})")
        elif res.linear_stable is False:
            lines.append(f"no limit cycle predicted, but {lin} is unstable: amplitudes grow without bound")
        elif res.search_bound:
            lines.append(
                f"no limit cycle predicted (search complete: eq. 36 has no root beyond M = {res.search_bound:.4g} ticks)"
            )
        else:
            lines.append(
                "no limit cycle predicted (search complete: the loop never meets the phase condition of eq. 36)"
            )
    else:
        rows = [
            [
                f"{c.amplitude:.6g}",
                f"{c.frequency:.6g}",
                f"{c.period:.4g}",
                "stable" if c.stable else "unstable",
                c.family + (" (period < 8 samples)" if c.few_samples else ""),
            ]
            for c in res.cycles
        ]
        lines.append(_table(rows, ["M (ticks)", "ω (rad/sample)", "period (samples)", "stability", "family"]))
        if not res.complete:
            lines.append(f"search incomplete beyond M = {res.max_amplitude:g} ticks ({why}): more cycles may exist")
    if g.amplitude is not None:
        u = device.units if device is not None else None

        def speed(xd, vel, pos, m):
            txt = f"M·ω = {xd:.4g} ticks/sample"
            if u is not None and vel is not None:
                txt += f" = {vel:.4g} {u['velocity']}; M = {pos:.4g} {u['position']}"
            return txt

        if g.is_band:
            lines.append(
                f"growth band: {g.unstable_count} unstable cycles from M = {g.amplitude:.4g} to {g.amplitude_high:.4g} ticks "
                f"(speeds {speed(g.xi_dot, g.velocity, g.position, g.amplitude)} to {speed(g.xi_dot_high, g.velocity_high, g.position_high, g.amplitude_high)})"
            )
        else:
            lines.append(
                f"growth threshold: M_u = {g.amplitude:.4g} ticks ({speed(g.xi_dot, g.velocity, g.position, g.amplitude)})"
            )
        lines.append(g.meaning())
    elif res.cycles and res.linear_stable is False:
        lines.append(
            f"no unstable cycle predicted{'' if res.complete else ' in the range searched'}, but {lin} is unstable: "
            "large oscillations are predicted to grow without bound"
        )
    if res.model != "zoh" and (res.linear_stable is False or g.amplitude is not None):
        lines.append(f"(the linear verdict uses the exact ZOH loop; the limit cycles, the {res.model} model)")
    return lines


def _cmd_contours(args: argparse.Namespace) -> int:
    from .contours import check_contour_memory, contour_maps

    if args.out is not None:
        check_output_file("--out", args.out, ".npz")
    if args.grid >= 2 and args.max_amplitude >= 1.0:
        check_contour_memory(args.grid, args.max_amplitude, ("--grid", "--max-amplitude"))
    c = contour_maps(
        args.mu,
        beta_range=tuple(args.beta_range),
        sigma_range=tuple(args.sigma_range),
        grid=args.grid,
        max_amplitude=args.max_amplitude,
        progress=_progress(args),
    )
    d = c.as_dict()
    if args.out is not None:
        d["out"] = str(c.save(args.out))
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
    if args.out is not None:
        print(f"written to {d['out']}")
    return 0


def _cmd_report(args: argparse.Namespace) -> int:
    from .report import design_report

    if args.device is None and not any(getattr(args, k, None) is not None for k in _PHYS_FLAGS):
        args.device = DEFAULT_DEVICE
    inp = _resolve(args, dimensionless=False)
    assert inp.device is not None
    entry = get_device(args.device) if args.device else None
    v = args.velocity
    if args.xi_dot is not None:
        if v is not None:
            raise UsageError("--velocity and --xi-dot cannot both be given: choose one speed")
        v = inp.device.velocity(args.xi_dot)
    if entry is not None and not any(getattr(args, k, None) is not None for k in _PHYS_FLAGS):
        target = entry
    else:
        target = inp.device
    check_output_folder("--out", args.out, create=False)
    res = design_report(
        target, inp.stiffness, v, out_dir=args.out, fmt=args.format, progress=_progress(args), delay=args.delay
    )
    for pth in res.paths:
        print(f"written {pth}")
    return 0


def _cmd_validate(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from . import plotting
    from ._io import staged_folder
    from .maps import check_jobs
    from .validation import validate

    check_jobs("--jobs", args.jobs)
    out = args.out
    check_output_folder("--out", out, create=True)  # the parent must exist; the folder itself is created
    v = validate(quick=args.quick, n_jobs=args.jobs, progress=_progress(args))
    os.makedirs(out, exist_ok=True)
    figs = {}
    summary = v.summary()
    with staged_folder(out) as stage:  # all four files appear together, or none (dfa._io)
        for key, fn in (("cycles", plotting.cycle_error_plot), ("speeds", plotting.critical_speed_plot)):
            ax = fn(v)
            name = f"validation_{key}.png"
            ax.figure.savefig(stage / name, dpi=120)
            plt.close(ax.figure)
            figs[key] = name
        (stage / "validation.md").write_text(v.to_markdown(figs), encoding="utf-8")
        (stage / "validation.json").write_text(json.dumps(summary, indent=1, allow_nan=True), encoding="utf-8")
    if args.json:
        _emit(json.loads(json.dumps(summary).replace("NaN", "null")))
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


def _build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="dfa",
        description="Passivity, limit cycles and stiffness limits of sampled, quantized haptic devices "
        "(Diolaiti, Niemeyer, Barbagli & Salisbury, ICRA 2005).",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True

    p = sub.add_parser("devices", help="list the device catalogue (paper Table 2)")
    p.add_argument("--json", action="store_true", help="print one JSON list on stdout")
    p.set_defaults(func=_cmd_devices)

    p = sub.add_parser("params", help="dimensionless (μ, β, σ) of a device and stiffness (paper Table 1)")
    _add_device_args(p, dimensionless=True, speed=False)
    p.set_defaults(func=_cmd_params)

    p = sub.add_parser("check", help="passivity criterion and region at an impact speed (eq. 6-12)")
    _add_device_args(p, dimensionless=True, speed=True)
    p.add_argument("--no-quantization", action="store_true", help="use eq. 7 (Δ → 0) instead of eq. 6")
    _add_delay_arg(p)
    p.add_argument(
        "--xi0",
        type=_number("--xi0", "ticks"),
        metavar="X",
        help="initial position ξ0 in ticks (dimensionless input; needs --mu)",
    )
    p.add_argument(
        "--position",
        type=_number("--position", "m (rotary: rad)"),
        metavar="X",
        help="initial position in m (rotary: rad; device input)",
    )
    p.set_defaults(func=_cmd_check)

    p = sub.add_parser("stiffness", help="stiffness limits for design at an impact speed (eq. 8, 9, 11)")
    _add_device_args(p, dimensionless=False, speed=True)
    _add_delay_arg(p)
    p.set_defaults(func=_cmd_stiffness)

    p = sub.add_parser("simulate", help="exact simulation of the sampled, quantized, frictional loop (eq. 4-5)")
    _add_device_args(p, dimensionless=True, speed=True)
    p.add_argument("--xi0", type=_number("--xi0", "ticks"), metavar="X", help="initial position in ticks (default 0)")
    p.add_argument(
        "--samples",
        type=_integer("--samples"),
        default=None,
        metavar="N",
        help="samples to simulate (default: from the loop's time scales, 50000 to 10^7)",
    )
    p.add_argument(
        "--delay", type=_integer("--delay"), default=0, metavar="D", help="computational delay in samples (default 0)"
    )
    p.add_argument(
        "--preload",
        action="store_true",
        help="start at rest with the spring preloaded to the speed's kinetic energy (section 5)",
    )
    p.add_argument(
        "--no-quantization", action="store_true", help="linear spring φ = −ξ instead of the encoder staircase"
    )
    p.add_argument("--trace", metavar="FILE.csv", help="write sample, xi, xi_dot to a CSV file")
    _add_progress_args(p)
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when --samples is estimated to take over {SIMULATE_TIME_LIMIT:g} s",
    )
    p.set_defaults(func=_cmd_simulate)

    p = sub.add_parser("map", help="stability map over the (β, σ) plane by simulation (paper Fig. 4)")
    p.add_argument("--mu", type=_number("--mu", "dimensionless units"), required=True, help="μ = m/(K T²)")
    p.add_argument(
        "--xi-dot",
        dest="xi_dot",
        type=_number("--xi-dot", "ticks per sample"),
        nargs="+",
        required=True,
        metavar="V",
        help="initial speeds ξ'0 (ticks per sample)",
    )
    p.add_argument(
        "--beta-range",
        type=_number("--beta-range", "dimensionless units"),
        nargs=2,
        default=[0.0, 1.0],
        metavar=("A", "B"),
    )
    p.add_argument(
        "--sigma-range",
        type=_number("--sigma-range", "dimensionless units"),
        nargs=2,
        default=[0.0, 2.0],
        metavar=("A", "B"),
    )
    p.add_argument("--grid", type=_integer("--grid"), default=100, metavar="N", help="points per axis (default 100)")
    p.add_argument(
        "--samples", type=_integer("--samples"), default=50_000, metavar="N", help="samples per run (default 50000)"
    )
    p.add_argument("--delay", type=_integer("--delay"), default=0, metavar="D")
    p.add_argument("--preload", action="store_true", help="spring preload instead of an initial speed")
    p.add_argument("--no-quantization", action="store_true")
    p.add_argument("--jobs", type=_integer("--jobs"), default=-1, metavar="J", help="parallel jobs (default all cores)")
    p.add_argument("--out", required=True, metavar="FILE.npz", help="where to write the map")
    _add_progress_args(p)
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when one run is estimated over {SIMULATE_TIME_LIMIT:g} s or the map over {MAP_TIME_LIMIT_HOURS:g} h",
    )
    p.add_argument("--json", action="store_true", help="print counts per outcome per speed as JSON")
    p.set_defaults(func=_cmd_map)

    p = sub.add_parser(
        "limit-cycles", help="limit cycles by harmonic balance with the exact describing function (eq. 36-45)"
    )
    _add_device_args(p, dimensionless=True, speed=False)
    p.add_argument(
        "--model",
        choices=["half-delay", "zoh", "pade"],
        default="half-delay",
        help="hold model (default half-delay; zoh is exact)",
    )
    p.add_argument("--delay", type=_integer("--delay"), default=0, metavar="D", help="computational delay in samples")
    p.add_argument(
        "--max-amplitude",
        type=_number("--max-amplitude", "ticks"),
        default=None,
        metavar="M",
        help="largest amplitude searched (ticks); default: up to where the envelope of eq. 41 excludes roots",
    )
    p.add_argument(
        "--time-budget",
        type=_number("--time-budget", "seconds"),
        default=None,
        metavar="S",
        help="longest search time in seconds (default 10, dfa.cycles.DEFAULT_TIME_BUDGET); "
        "when it is hit the search is reported incomplete",
    )
    p.set_defaults(func=_cmd_limit_cycles)

    p = sub.add_parser("contours", help="amplitude/frequency maps of both cycle families (paper Fig. 7)")
    p.add_argument("--mu", type=_number("--mu", "dimensionless units"), required=True, help="μ = m/(K T²)")
    p.add_argument(
        "--beta-range",
        type=_number("--beta-range", "dimensionless units"),
        nargs=2,
        default=[0.0, 1.0],
        metavar=("A", "B"),
    )
    p.add_argument(
        "--sigma-range",
        type=_number("--sigma-range", "dimensionless units"),
        nargs=2,
        default=[0.0, 2.0],
        metavar=("A", "B"),
    )
    p.add_argument("--grid", type=_integer("--grid"), default=200, metavar="N", help="points per axis (default 200)")
    p.add_argument("--max-amplitude", type=_number("--max-amplitude", "ticks"), default=200.0, metavar="M")
    p.add_argument("--out", metavar="FILE.npz", help="write the maps")
    p.add_argument("--json", action="store_true")
    _add_progress_args(p)
    p.set_defaults(func=_cmd_contours)

    p = sub.add_parser("report", help="design report of a device: verdict, limits, cycles, figures (HTML or Markdown)")
    _add_device_args(p, dimensionless=False, speed=True)
    p.add_argument("--out", default="reports", metavar="DIR", help="output folder (default reports)")
    p.add_argument(
        "--format", choices=["html", "md", "both"], default="html", help="html (self-contained), md (with PNGs) or both"
    )
    _add_progress_args(p)
    _add_delay_arg(p)
    p.set_defaults(func=_cmd_report)

    p = sub.add_parser("validate", help="validate the predictions against exact simulation; writes validation.md")
    p.add_argument("--quick", action="store_true", help="a reduced set (under a minute)")
    p.add_argument("--jobs", type=_integer("--jobs"), default=-1, metavar="J", help="parallel jobs (default all cores)")
    p.add_argument(
        "--out", default="reports/validation", metavar="DIR", help="output folder (default reports/validation)"
    )
    _add_progress_args(p)
    p.add_argument("--json", action="store_true", help="print the summary as JSON")
    p.set_defaults(func=_cmd_validate)
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
    done); 1 a file could not be written or memory ran out; 130 / 143
    interrupted by SIGINT / SIGTERM (one line on stderr naming what was kept:
    files are written atomically, so nothing is half-written); 141 stdout was
    a closed pipe (``dfa devices | head -1``), ended quietly.
    """
    parser = _build_parser()
    before = len(written_paths())
    old_handlers = _install_signal_handlers()
    try:
        args = parser.parse_args(list(sys.argv[1:] if argv is None else argv))
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
        for sig, handler in old_handlers.items():
            signal.signal(sig, handler if handler is not None else signal.SIG_DFL)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
