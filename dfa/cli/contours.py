"""``dfa contours``: amplitude and frequency maps of both limit-cycle families (paper Fig. 7)."""

from __future__ import annotations

import argparse
import math
from typing import TYPE_CHECKING, Any

from .._io import FIGURE_SUFFIXES, check_output_file
from .configurations import MARGIN, configuration_json, configuration_line, limiting
from .inputs import Inputs, add_plane_args, device_json, outside_note, plane_device
from .output import (
    WORK_TIME_LIMIT,
    add_progress_args,
    check_work_time,
    emit,
    mark_operating_point,
    progress,
    save_png,
    say,
    table,
)
from .parsing import UsageError, integer, number

if TYPE_CHECKING:
    from ..analysis.contours import ContourMaps

COMMAND = "contours"
HELP = "amplitude/frequency maps of both cycle families (paper Fig. 7)"
EXAMPLE = "dfa contours --mu 100 --grid 200 --out fig7.npz"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """μ (or a device), the plane, the largest amplitude, --out and --json."""
    add_plane_args(p, speeds=False)
    p.add_argument("--grid", type=integer("--grid"), default=200, metavar="N", help="points per axis (default: 200)")
    p.add_argument(
        "--max-amplitude",
        type=number("--max-amplitude", "ticks"),
        default=200.0,
        metavar="M",
        help="largest amplitude in ticks (default: 200)",
    )
    p.add_argument("--out", metavar="FILE.npz", help="write the maps (default: not written)")
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when the maps are estimated over {WORK_TIME_LIMIT:g} s (default: refuse)",
    )
    p.add_argument("--json", action="store_true", help="print one JSON object on stdout (default: text)")
    add_progress_args(p)


def _print(args: argparse.Namespace, c: ContourMaps, d: dict[str, Any], inp: Inputs | None) -> None:
    """The grid points of each family, with the device's operating point and units."""
    b, s = c.beta, c.sigma
    say(f"contour maps μ = {c.mu:g}, β in [{b[0]:g}, {b[-1]:g}], σ in [{s[0]:g}, {s[-1]:g}], {b.size}×{s.size}")
    rows = [
        ["small stable (M < 1, eq. 42-43)", d["small_points"]],
        ["large unstable, exact D (eq. 41)", d["large_points"]],
        ["large unstable, closed form (eq. 44-45)", d["large_closed_points"]],
    ]
    say(table(rows, ["family", "grid points"]))
    if c.flagged:
        from ..render.text import flagged_text  # here: it loads the limit-cycle package

        say(f"flagged (NaN): {flagged_text(c)}")
    line = configuration_line(inp)
    if line is not None:
        say(line)
    if inp is not None and inp.params is not None and inp.device is not None and inp.stiffness is not None:
        u = inp.device.units
        say(
            f"{inp.label}: operating point β = {inp.params.beta:.5g}, σ = {inp.params.sigma:.5g}"
            f"{outside_note(args, inp)}; 1 tick = {inp.device.resolution:.4g} {u['position']}, ω = 1 rad/sample = "
            f"{d['frequency_hz_per_rad_per_sample']:.4g} Hz, force step KΔ = "
            f"{inp.stiffness * inp.device.resolution:.4g} {u['force']}"
        )


def _refuse_uncovered_device_elements(inp: Inputs | None) -> None:
    """Refuse a device field whose element the describing function does not cover (the force limit), saying why
    (UsageError, exit 2): the contour maps are of the paper's loop, and a field of the device must not be ignored
    in silence."""
    from ..model.elements import Coverage
    from ..model.loop import device_elements

    device = None if inp is None else inp.device
    for in_wall in (True, False):
        for e in device_elements(device, in_wall=in_wall):
            why = type(e).class_coverage().reason(Coverage.DESCRIBING_FUNCTION)
            if why is not None:
                flag = "--" + str(type(e).device_field).replace("_", "-")
                raise UsageError(
                    f"{flag} {e.value:g} is not covered here: {why}; drop {flag} (the maps are the paper's loop "
                    "without it), or use dfa map or dfa simulate with it"
                )


def run(args: argparse.Namespace) -> int:
    """Map the small stable and the large unstable cycles over the plane; print the counts."""
    from ..analysis.contours import check_contour_memory, contour_maps, contour_seconds

    if args.out is not None:
        check_output_file("--out", args.out, ".npz")
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
    mu, inp = plane_device(args)
    if inp is not None and inp.configurations:  # the smallest margin at speed 0 (σ − σ₀); the plane is its μ
        inp = limiting(args, inp, MARGIN)
        assert inp.params is not None
        mu = inp.params.mu
    if inp is not None and inp.device is not None and inp.device.hand is not None and inp.device.hand.stiffness:
        raise UsageError(
            f"--hand-stiffness {inp.device.hand.stiffness:g} is not covered here: the contour maps are the paper's "
            "closed forms for the spring (eq. 42-45); drop the hand's stiffness (its mass and damping are taken), or "
            "use dfa limit-cycles with it"
        )
    _refuse_uncovered_device_elements(inp)
    if not args.max_amplitude >= 1.0:
        raise UsageError(
            f"--max-amplitude {args.max_amplitude:g} is invalid: it must be >= 1 tick (the large cycle family has "
            "M >= 1); give e.g. --max-amplitude 10"
        )
    check_contour_memory(args.grid, args.max_amplitude, ("--grid", "--max-amplitude"))
    check_work_time(
        f"--grid {args.grid} with --max-amplitude {args.max_amplitude:g}",
        contour_seconds(args.grid, args.max_amplitude),
        "lower --grid or --max-amplitude",
        args.force,
    )
    c = contour_maps(
        mu, beta_range=tuple(args.beta_range), sigma_range=tuple(args.sigma_range), grid=args.grid,
        max_amplitude=args.max_amplitude, progress=progress(args),
    )  # fmt: skip
    d = c.to_dict()
    if args.out is not None:
        d["out"] = str(c.save(args.out))
    if args.plot is not None:
        from ..render.figures import contour_plot

        dev, k = (inp.device, inp.stiffness) if inp is not None else (None, None)
        axes = contour_plot(c, device=dev, stiffness=k)  # physical axes b, c like `dfa map --plot`
        mark_operating_point(axes, inp)
        d["plot"] = save_png("--plot", args.plot, axes[0])
    d.update(device_json(inp))
    d.update(configuration_json(inp))
    if inp is not None and inp.device is not None and inp.stiffness is not None:
        d["frequency_hz_per_rad_per_sample"] = 1.0 / (2.0 * math.pi * inp.device.period)
    if args.json:
        emit(d)
        return 0
    _print(args, c, d, inp)
    if args.out is not None:
        say(f"written to {d['out']}")
    if args.plot is not None:
        say(f"figure written to {args.plot}")
    return 0
