"""``dfa limit-cycles``: limit cycles by harmonic balance with the exact describing function (eq. 36-45)."""

from __future__ import annotations

import argparse

from ..checks import check_damping_rate
from .configurations import MARGIN, limiting
from .contact import add_contact_args, refuse_one_sided_flag
from .inputs import add_device_args, resolve
from .output import RATE_NAMES, emit, say
from .parsing import UsageError, number
from .passivity import add_passivity_args, refuse_passivity_flag
from .walls import add_wall_args, print_wall, wall_from_args, wall_json, wall_params

COMMAND = "limit-cycles"
HELP = "limit cycles by harmonic balance with the exact describing function (eq. 36-45)"
EXAMPLE = "dfa limit-cycles --device delta --model zoh"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device or (μ, β, σ), the hold model, the wall and the search's reach and time."""
    add_device_args(p, dimensionless=True, speed=False)
    p.add_argument(
        "--model",
        choices=["half-delay", "zoh", "pade"],
        default="half-delay",
        help="hold model (default: half-delay; zoh is exact)",
    )
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)
    p.add_argument(
        "--max-amplitude",
        type=number("--max-amplitude", "ticks"),
        default=None,
        metavar="M",
        help="largest amplitude searched in ticks (default: up to where the envelope of eq. 41 excludes roots)",
    )
    p.add_argument(
        "--time-budget",
        type=number("--time-budget", "seconds"),
        default=None,
        metavar="S",
        help="longest search time in seconds (default: 10, dfa.analysis.cycles.DEFAULT_TIME_BUDGET); "
        "when it is hit the search is reported incomplete",
    )


def run(args: argparse.Namespace) -> int:
    """Print the cycles, the search's completeness, the linear loop and the growth band."""
    from ..analysis.cycles import growth_threshold
    from ..render.text import limit_cycle_lines, limit_cycles_dict

    for flag, value in (("--max-amplitude", args.max_amplitude), ("--time-budget", args.time_budget)):
        if value is not None and not value > 0:
            raise UsageError(f"{flag} {value:g} is invalid: it must be > 0; give e.g. {flag} 10")
    inp = resolve(args, dimensionless=True, configurations=True)
    if inp.configurations:  # the smallest margin at speed 0, σ − σ₀ (dfa check's rule without a speed)
        inp = limiting(args, inp, MARGIN, wall=wall_from_args(args, inp.device, inp.stiffness))
    p = inp.params
    assert p is not None
    check_damping_rate(p.beta, p.mu, RATE_NAMES[inp.device is None])
    refuse_one_sided_flag(
        args,
        "a one-sided wall is not a linear loop (a cycle that leaves the wall is not first-harmonic, and one in contact about a push's offset needs a biased describing function, not derived)",
    )
    refuse_passivity_flag(args, "its damper switches with the observed energy, which no describing function covers")
    ctl = wall_from_args(args, inp.device, inp.stiffness)
    budget = {} if args.time_budget is None else {"time_budget": args.time_budget}
    g = growth_threshold(
        p, inp.device, model=args.model, wall=wall_params(args, ctl, inp), max_amplitude=args.max_amplitude, **budget
    )
    res = g.result
    phys = None if inp.device is None or inp.stiffness is None else res.physical(inp.device, inp.stiffness)
    if args.json:
        emit(wall_json(limit_cycles_dict(g, phys), ctl, inp))
        return 0
    say(
        f"{inp.label}: μ = {p.mu:.5g}, β = {p.beta:.5g}, σ = {p.sigma:.5g}; model {res.model}"
        + (f", delay {res.delay}" if res.delay else "")
    )
    print_wall(ctl, inp)
    for line in limit_cycle_lines(g, inp.device, phys):
        say(line)
    return 0
