"""``dfa map``: the stability map over the (β, σ) plane by exact simulation (paper Fig. 4), spring or wall."""

from __future__ import annotations

import argparse
from typing import TYPE_CHECKING, Any

from .._io import FIGURE_SUFFIXES, check_output_file
from ..checks import check_damping_rate
from ..jsonable import explain_nulls
from .configurations import MARGIN, limiting
from .contact import add_contact_args
from .inputs import Inputs, add_plane_args, device_json, outside_note, plane_device
from .output import (
    MAP_TIME_LIMIT_HOURS,
    SIMULATE_NS_PER_SAMPLE,
    SIMULATE_TIME_LIMIT,
    SIMULATION_BOUND,
    add_progress_args,
    check_samples,
    cores,
    emit,
    mark_operating_point,
    progress,
    save_png,
    say,
    table,
)
from .parsing import UsageError, integer, number
from .passivity import add_passivity_args
from .walls import add_wall_args, print_wall, wall_from_args, wall_json, wall_params

if TYPE_CHECKING:
    from ..analysis.maps import StabilityMap
    from ..analysis.simulation import SimulationResult
    from ..model.wall import Wall

COMMAND = "map"
HELP = "stability map over the (β, σ) plane by simulation (paper Fig. 4)"
EXAMPLE = "dfa map --mu 100 --xi-dot 1 5 --grid 50 --out fig4.npz"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """μ (or a device), the speeds, the plane, the run length, the wall, --out and the work limits."""
    add_plane_args(p, speeds=True)
    p.add_argument(
        "--xi-dot",
        dest="xi_dot",
        type=number("--xi-dot", "ticks per sample"),
        nargs="+",
        metavar="V",
        help="initial speeds ξ'0 in ticks per sample (required unless --velocity is given with a device)",
    )
    p.add_argument("--grid", type=integer("--grid"), default=100, metavar="N", help="points per axis (default: 100)")
    p.add_argument(
        "--samples", type=integer("--samples"), default=50_000, metavar="N", help="samples per run (default: 50000)"
    )
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)
    p.add_argument("--preload", action="store_true", help="spring preload instead of an initial speed (default: off)")
    p.add_argument(
        "--no-quantization", action="store_true", help="linear spring, no encoder (default: with the encoder)"
    )
    p.add_argument(
        "--jobs", type=integer("--jobs"), default=-1, metavar="J", help="parallel jobs (default: -1, all cores)"
    )
    p.add_argument("--out", required=True, metavar="FILE.npz", help="where to write the map (required)")
    add_progress_args(p)
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when one run is estimated over {SIMULATE_TIME_LIMIT:g} s or the map over "
        f"{MAP_TIME_LIMIT_HOURS:g} h (default: refuse)",
    )
    p.add_argument("--json", action="store_true", help="print counts per outcome per speed as JSON (default: text)")


def _speeds(args: argparse.Namespace, inp: Inputs | None) -> list[float]:
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


def _check_work(args: argparse.Namespace, speeds: list[float]) -> None:
    """Refuse a map that would run too long or not fit in memory, before any work (fix: smaller grid, --force)."""
    from .._io import check_memory
    from ..analysis.maps import map_memory_bytes
    from ..checks import check_jobs

    check_jobs("--jobs", args.jobs)
    check_samples(args.samples, args.force)  # one run is uninterruptible: the same limit as `dfa simulate`
    if args.grid < 2:
        return
    n = cores(args.jobs)
    hours = args.grid**2 * len(speeds) * args.samples * SIMULATE_NS_PER_SAMPLE * 1e-9 / 3600 / n
    if hours > MAP_TIME_LIMIT_HOURS and not args.force:
        raise UsageError(
            f"--grid {args.grid} with --samples {args.samples} could take up to {hours:.3g} h on {n} cores "
            f"(estimated {SIMULATE_NS_PER_SAMPLE} ns per sample; limit {MAP_TIME_LIMIT_HOURS:g} h): "
            "lower --grid or --samples, or add --force"
        )
    fix = "lower --grid or give fewer --xi-dot speeds"
    check_memory("--grid", args.grid, map_memory_bytes(args.grid, len(speeds)), fix)


#: Why the map's JSON has no operating point without a device.
NO_POINT = "dimensionless input (--mu): no device, so no operating point and no physical units"


def _point_runs(m: StabilityMap, inp: Inputs | None, bound: float) -> tuple[SimulationResult, ...]:
    """The device's operating point simulated at each speed with the map's settings (none without a device)."""
    if inp is None or inp.params is None or inp.device is None:
        return ()
    from ..analysis.maps import simulate_point

    return simulate_point(m, inp.params.beta, inp.params.sigma, bound=bound)


def _point_note(r: SimulationResult, phys: dict[str, Any]) -> str:
    """The outcome of one run at the operating point, with its time to rest or amplitude in physical units."""
    if r.outcome == "rest":
        return f"rest at {phys['rest_time_s']:.4g} s"
    amp = phys["amplitude_si"]
    if r.outcome == "left":
        return "left the one-sided wall for good"
    return str(r.outcome.value) + ("" if amp is None else f", amplitude {amp:.3g} {phys['position_unit']}")


def _point_json(m: StabilityMap, runs: tuple[SimulationResult, ...], inp: Inputs) -> list[dict[str, Any]]:
    """Each speed's run at the operating point: outcome and measurements in ticks and in physical units."""
    keep = ("outcome", "status_message", "amplitude", "frequency", "period", "rest_sample", "samples_run",
            "force_peak_to_peak", "suggested_samples")  # fmt: skip
    from ..model.units import speed, suffixes

    out = []
    for v, r in zip(m.xi_dots, runs, strict=True):
        phys = r.physical(inp.device, inp.stiffness)
        d = r.to_dict()
        rec: dict[str, Any] = {"xi_dot": v, f"velocity_{suffixes(inp.device)['velocity']}": speed(inp.device, v)}
        rec.update({k: d[k] for k in keep})
        rec.update({k: phys[k] for k in phys if k not in _CONTEXT and not k.startswith(("x0_", "v0_", "final_"))})
        explain_nulls(rec, r.null_reasons())
        out.append(rec)
    return out


#: Keys of :meth:`SimulationResult.physical` the map's JSON states once (device_json), not per run.
_CONTEXT = ("device", "rotary", "stiffness", "stiffness_unit", "force_unit", "position_unit", "velocity",
            "velocity_unit", "sample_period_s", "force_step_n", "force_step_nm", "tick_m", "tick_rad",
            "duration_s")  # fmt: skip


def _print(
    args: argparse.Namespace,
    m: StabilityMap,
    path: object,
    inp: Inputs | None,
    ctl: Wall | None,
    runs: tuple[SimulationResult, ...] = (),
) -> None:
    """The map's counts per outcome and speed, with the device's operating point."""
    if inp is not None and inp.params is not None and inp.device is not None:
        vu = inp.device.units["velocity"]
        speeds = ", ".join(f"{x:g} ticks/sample = {inp.device.velocity(x):.4g} {vu}" for x in m.xi_dots)
        beta, sigma = inp.params.beta, inp.params.sigma
        say(f"{inp.label}: operating point β = {beta:.5g}, σ = {sigma:.5g}{outside_note(args, inp)}; speeds {speeds}")
        print_wall(ctl, inp)
    b, s = m.beta, m.sigma
    say(
        f"stability map μ = {m.mu:g}, β in [{b[0]:g}, {b[-1]:g}], σ in [{s[0]:g}, {s[-1]:g}], "
        f"{b.size}×{s.size} points, {m.samples} samples" + (", spring preload" if m.preload else "")
    )
    counts = m.counts()
    names: tuple[str, ...] = ("rest", "chatter", "oscillating", "unstable", "undecided")
    names += ("left",) if any("left" in c for c in counts) else ()  # a one-sided wall's runs only
    rows = [[f"{v:g}", *(c.get(k, 0) for k in names)] for v, c in zip(m.xi_dots, counts, strict=False)]
    say(table(rows, ["ξ'0", *names]))
    contact = m.contact_counts()
    if contact is not None:  # a one-sided wall: how each run ended as contact (dfa simulate's contact row)
        kinds = [k for k in contact[0] if any(c[k] for c in contact)]
        say("as contact:")
        say(
            table(
                [[f"{v:g}", *(c[k] for k in kinds)] for v, c in zip(m.xi_dots, contact, strict=True)], ["ξ'0", *kinds]
            )
        )
    if runs and inp is not None and inp.device is not None and inp.params is not None:
        vu = inp.device.units["velocity"]
        how = f"--samples {m.samples}" + (" --preload" if m.preload else "")
        say(f"at the operating point β = {inp.params.beta:.5g}, σ = {inp.params.sigma:.5g} (as `dfa simulate {how}`):")
        rows = [
            [f"{v:g}", f"{inp.device.velocity(v):.4g}", _point_note(r, r.physical(inp.device, inp.stiffness))]
            for v, r in zip(m.xi_dots, runs, strict=True)
        ]
        say(table(rows, ["ξ'0", f"speed ({vu})", "outcome"]))
    say(f"written to {path}")


def run(args: argparse.Namespace) -> int:
    """Simulate every point of the plane at each speed; write the map (.npz) and print the counts."""
    from ..analysis.maps import stability_map
    from ..analysis.simulation import divergence_bound

    check_output_file("--out", args.out, ".npz")
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
    mu, inp = plane_device(args)
    if inp is not None and inp.configurations:  # the smallest margin at the largest speed; the plane is its μ
        top_v = max(abs(x) for x in args.velocity) if args.velocity else None
        inp = limiting(args, inp, MARGIN, velocity=top_v, wall=wall_from_args(args, inp.device, inp.stiffness))
        assert inp.params is not None
        mu = inp.params.mu
    speeds = _speeds(args, inp)
    _check_work(args, speeds)
    top = max(args.beta_range + ([inp.params.beta] if inp is not None and inp.params is not None else []))
    check_damping_rate(top, mu, ("--beta-range", "--mu") if inp is None else ("β", "μ = m/(K T²)"))
    ctl = wall_from_args(args, *((inp.device, inp.stiffness) if inp is not None else (None, None)))
    bound = divergence_bound(0.0, max(speeds), mu, SIMULATION_BOUND)
    m = stability_map(
        mu, speeds, beta_range=tuple(args.beta_range), sigma_range=tuple(args.sigma_range), grid=args.grid,
        samples=args.samples, preload=args.preload, quantize=not args.no_quantization, n_jobs=args.jobs,
        progress=progress(args), bound=bound, wall=wall_params(args, ctl, inp),
    )  # fmt: skip
    path = m.save(args.out)
    runs = _point_runs(m, inp, bound)
    if args.plot is not None:
        from ..render.figures import stability_map_plot

        dev, k = (inp.device, inp.stiffness) if inp is not None else (None, None)
        point = (inp.params.beta, inp.params.sigma) if inp is not None and inp.params is not None else None
        axes = stability_map_plot(m, device=dev, stiffness=k, point=point)  # the point drawn and in the legend
        notes = [_point_note(r, r.physical(dev, k)) for r in runs] if runs else None
        mark_operating_point(axes, inp, notes, marker=False)
        save_png("--plot", args.plot, axes[0])
    if args.json:
        d = m.to_dict()
        d["out"] = str(path)
        d.update(device_json(inp, m.xi_dots))
        if runs and inp is not None:
            d["operating_point_runs"] = _point_json(m, runs, inp)
        else:
            d["operating_point"] = d["operating_point_runs"] = None
            explain_nulls(d, dict.fromkeys(("operating_point", "operating_point_runs"), NO_POINT))
        if args.plot is not None:
            d["plot"] = args.plot
        emit(wall_json(d, ctl, inp))
        return 0
    _print(args, m, path, inp, ctl, runs)
    if args.plot is not None:
        say(f"figure written to {args.plot}")
    return 0
