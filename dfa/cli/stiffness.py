"""``dfa stiffness``: the largest stiffness for an impact speed, four ways, for the spring and any wall.

One path: the wall of the flags (the spring with its delay when none is given) is held fixed while K varies
(:func:`dfa.analysis.limits.kmax.design_answer`); K itself, when given or in the catalogue, is assessed.
"""

from __future__ import annotations

import argparse
import contextlib
import time
from typing import TYPE_CHECKING, Any

from .._io import FIGURE_SUFFIXES, check_output_file
from ..core.jit import interpreted
from ..formatting import fill, text_table
from ..jsonable import explain_nulls
from ..model.elements import PassivityController
from ..model.loop import Loop
from ..model.wall import Wall
from ..progress import runs_counted
from ..results.status import LimitStatus
from .configurations import add_configurations_plot_arg, check_configurations_plot, write_configurations_plot
from .contact import add_contact_args
from .inputs import Inputs, add_device_args, resolve, speed
from .output import emit, save_png, working
from .parsing import UsageError, add_margin_arg
from .passivity import add_passivity_args
from .walls import add_wall_args, print_wall, wall_from_args, wall_json

if TYPE_CHECKING:
    from ..results.limits import KMaxResult
    from ..results.require import Recommendation

COMMAND = "stiffness"
HELP = (
    "largest stiffness for an impact speed, four ways: criterion (eq. 11), exact linear bound, "
    "describing function, simulation; bounds of eq. 8, 9"
)
EXAMPLE = "dfa stiffness --device impulse --velocity 0.05 --stiffness 80"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device, one speed, the wall, --explain and --plot."""
    add_device_args(p, dimensionless=False, speed=True)
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)
    p.add_argument(
        "--explain",
        action="store_true",
        help="the full evidence: each limit's caveats in words, what its confirmation simulated, the runs "
        "(default: one screen, lines under 100 characters)",
    )
    p.add_argument(
        "--quick",
        action="store_true",
        help="a quick answer for sweeps: the criterion, the static and exact linear bounds and the describing "
        "function, without the simulated limits (no simulation; under a second; default: the full answer)",
    )
    add_margin_arg(p)
    add_configurations_plot_arg(p)
    p.add_argument(
        "--plot",
        metavar="FILE",
        help="write the stiffness-speed chart (largest safe impact speed against K, four ways) to FILE: .png, "
        ".pdf or .svg by its suffix (default: none)",
    )


def _source(args: argparse.Namespace, inp: Inputs) -> str | None:
    """Where the assessed K came from: --stiffness, the device file, the catalogue, or nowhere (None)."""
    if args.stiffness is not None:
        return "--stiffness"
    if inp.stiffness is None:
        return None
    return "device file" if getattr(args, "device_file", None) is not None else "catalogue"


def _plain(ans: KMaxResult, dev: Any, v: float, simulate: bool = True) -> KMaxResult | None:
    """The same answer for the wall without its passivity controller (None without one): the controller's gain,
    and the wall recommended when the controller does not help (:func:`recommend_stiffness`'s ``plain``)."""
    from ..analysis.limits.kmax import design_answer

    if ans.wall.element(PassivityController) is None:
        return None
    return design_answer(Loop(dev, ans.wall.without_controller()), v, simulate=simulate)


def run(args: argparse.Namespace) -> int:
    """K_max four ways for the spring or any wall (the wall's K is what is searched)."""
    from ..analysis.limits.kmax import design_answer
    from ..analysis.limits.passivity_gain import gain_of
    from ..analysis.limits.recommend import check_margin, recommend_stiffness
    from ..analysis.limits.require import damper_guidance_for

    inp = resolve(args, dimensionless=False, need_stiffness=False, configurations=True)
    dev = inp.device
    assert dev is not None
    _xd, v = speed(args, inp)
    assert v is not None
    k = inp.stiffness
    ctl = wall_from_args(args, dev, 1.0 if k is None else k)  # K is what is searched: any K states the elements
    wall = ctl if ctl is not None else Wall.of(1.0 if k is None else k, delay=args.delay)
    if args.plot is not None:
        check_output_file("--plot", args.plot, FIGURE_SUFFIXES)
        if args.quick:
            raise UsageError(
                "--plot draws the simulated limits, which --quick does not compute: drop --quick or --plot"
            )
    check_configurations_plot(args, inp)
    src = _source(args, inp)
    check_margin(args.margin)  # refused before the search, not after it
    where = src if src in ("catalogue", "device file") else "given"
    path = str(args.device_file) if where == "device file" else None
    loop = Loop(dev, wall)
    simulate = not args.quick
    if inp.configurations:  # a device file's configurations: the worst of them
        return _worst(args, inp, wall, ctl, v, dict(assess=k is not None, source=where, source_file=path))
    start, runs = time.perf_counter(), runs_counted()
    kernels = interpreted() if args.quick else contextlib.nullcontext()  # a quick answer need not load numba
    with working(args), kernels:
        ans = design_answer(loop, v, assess=k is not None, source=where, source_file=path, simulate=simulate)
        plain = _plain(ans, dev, v, simulate)
        gain = None if plain is None else gain_of(ans, plain)
        rec = recommend_stiffness(ans, args.margin, plain=plain)
        guide = damper_guidance_for(dev, wall, v)
        if args.plot is not None:
            from ..analysis.limits.speed_chart import stiffness_speed_chart

            chart = stiffness_speed_chart(loop, stiffness=k, velocity=v if v > 0 else None)
    if args.plot is not None:
        save_png("--plot", args.plot, chart.plot())
    work = (time.perf_counter() - start, runs_counted() - runs)
    if args.json:
        out = ans.to_dict()
        out["stiffness_source"] = src
        out["recommendation"] = rec.to_dict()
        out["damper_guidance"] = None if guide is None else guide.to_dict()
        explain_nulls(
            out,
            {
                "stiffness_source": "no --stiffness given, and no K in the catalogue or the device file",
                "damper_guidance": "no virtual damper",
            },
        )
        if args.plot is not None:
            out["plot"] = args.plot
        if gain is not None:
            out["passivity_gain"] = gain.to_dict()
        emit(wall_json(out, ctl, inp))
        return 0
    if args.explain:
        _print_explained(ans, rec, ctl, inp)
    else:
        from ..render.answer import stiffness_screen

        print("\n".join(stiffness_screen(ans, rec, guide)))
    if gain is not None:
        from ..render.passivity import gain_lines

        print("\n".join(gain_lines(gain)))
    if args.plot is not None:
        print(f"stiffness-speed chart written to {args.plot}")
    if args.explain:  # the last line: how long the answer took
        from ..render.answer import work_line

        print(work_line(*work))
    return 0


def _print_explained(ans: KMaxResult, rec: Recommendation, ctl: Wall | None, inp: Inputs) -> None:
    """The full answer (``--explain``): every limit in words with what its confirmation simulated."""
    from ..render.answer import recommendation_line
    from ..render.hand import device_title
    from ..render.limits import PROOF_NOTE, QUICK_PROOF_NOTE, evidence_text, kmax_rows, verdict_text
    from ..render.start_state import start_state_note

    dev, v, wall = ans.device, ans.velocity, ans.wall
    vu, d = dev.units["velocity"], wall.delay
    print(
        f"{device_title(dev)}, impact speed {v:.4g} {vu} ({ans.xi_dot:.4g} ticks/sample), delay {d} sample{'s' if d != 1 else ''}"
        + ("" if ctl is None else "; B, f_c, f_bw held fixed while K varies")
    )
    print_wall(ctl, inp, wrap=False)
    print(recommendation_line(rec))
    rows = kmax_rows(ans, explain=True)
    rows.append(["verdict at this speed", verdict_text(ans)])
    print(text_table(rows))  # the full evidence: a row a line, however long
    if v > 0:
        print(f"evidence: {evidence_text(ans)}.")
        quick = ans.k_sim.status is LimitStatus.NOT_SIMULATED
        note = (QUICK_PROOF_NOTE if quick else PROOF_NOTE).replace("a proof", f"a proof{start_state_note(ans.wall)}")
        print(fill(f"{note} (the describing function's: the first harmonic)."))
    else:
        print("impact speed 0: the describing-function and simulated limits need a speed > 0.")


def _worst(args: argparse.Namespace, inp: Inputs, wall: Wall, ctl: Wall | None, v: float, kw: dict[str, Any]) -> int:
    """The recommended stiffness of every configuration of the device file, the limiting one named and its full
    answer (:func:`dfa.analysis.configurations.worst_stiffness`)."""
    from ..analysis.configurations import worst_stiffness
    from ..analysis.limits.require import damper_guidance_for
    from ..render.answer import stiffness_screen
    from ..render.configurations import configuration_header, configuration_rows, limiting_line

    assert inp.device is not None
    with working(args):
        w = worst_stiffness(inp.device, inp.configurations, v, wall=wall, margin=args.margin, simulate=not args.quick,
                            **kw)  # fmt: skip
        ans, rec = w.details
        guide = damper_guidance_for(ans.device, wall, v)
        if args.plot is not None:
            from ..analysis.limits.speed_chart import stiffness_speed_chart

            chart = stiffness_speed_chart(
                Loop(ans.device, wall), stiffness=inp.stiffness, velocity=v if v > 0 else None
            )
    if args.plot is not None:
        save_png("--plot", args.plot, chart.plot())
    figure = write_configurations_plot(args, w)
    if args.json:
        out = w.to_dict()
        out["answer"] = ans.to_dict()
        out["recommendation"] = rec.to_dict()
        out["damper_guidance"] = None if guide is None else guide.to_dict()
        explain_nulls(out, {"damper_guidance": "no virtual damper"})
        if args.plot is not None:
            out["plot"] = args.plot
        if figure is not None:
            out["configurations_plot"] = figure
        emit(wall_json(out, ctl, inp))
        return 0
    print(text_table(configuration_rows(w), configuration_header(w)))
    print(limiting_line(w))
    print()
    print("\n".join(stiffness_screen(ans, rec, guide)))
    if args.plot is not None:
        print(f"stiffness-speed chart of {w.limiting} written to {args.plot}")
    if figure is not None:
        print(f"configurations figure written to {figure}")
    return 0
