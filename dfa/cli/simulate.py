"""``dfa simulate``: one exact simulation of the sampled, quantized, frictional loop (eq. 4-5), spring or wall."""

from __future__ import annotations

import argparse
from typing import Any

from .._io import check_output_file
from ..checks import check_damping_rate
from ..jsonable import explain_nulls
from ..model.loop import Loop
from .configurations import MARGIN, limiting
from .contact import add_contact_args
from .inputs import Inputs, add_device_args, resolve, speed
from .output import (
    RATE_NAMES,
    SIMULATE_TIME_LIMIT,
    SIMULATION_BOUND,
    add_progress_args,
    check_samples,
    emit,
    progress,
    say,
    table,
)
from .parsing import UsageError, integer, number
from .passivity import add_observer_arg, add_passivity_args
from .walls import add_wall_args, print_wall, wall_from_args, wall_json, wall_params

COMMAND = "simulate"
#: Why a physical value is null in the JSON of a run without a device.
NO_DEVICE = "dimensionless input: no device, so no physical units (positions in ticks, time in samples)"
#: Why the force amplitude is null in the JSON of a saturated run.
SATURATED_AMPLITUDE = (
    "the actuator's force limit clipped the force in the run's tail: the amplitude times KΔ is not a force the "
    "actuator applied (the spring alone with a limit: force_peak_to_peak is the applied force's, at most 2 F_max)"
)
HELP = "exact simulation of the sampled, quantized, frictional loop (eq. 4-5)"
EXAMPLE = "dfa simulate --device delta --velocity 0.5"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device or (μ, β, σ), the initial state, the run length, the wall, --trace and the work limit."""
    add_device_args(p, dimensionless=True, speed=True)
    p.add_argument("--xi0", type=number("--xi0", "ticks"), metavar="X", help="initial position in ticks (default: 0)")
    p.add_argument(
        "--samples",
        type=integer("--samples"),
        default=None,
        metavar="N",
        help="samples to simulate (default: from the loop's time scales, 50000 to 10^7)",
    )
    add_wall_args(p)
    add_contact_args(p)
    add_passivity_args(p)
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
    p.add_argument(
        "--trace",
        metavar="FILE.csv",
        help="write sample, xi, xi_dot, phi (ticks, KΔ) and with a device t_s, x_m, v_m_per_s, force_n to a CSV "
        "file, one row per sample up to where the outcome was decided (rest, divergence, leaving the wall; "
        "otherwise the whole run) (default: none)",
    )
    add_observer_arg(p)
    add_progress_args(p)
    p.add_argument(
        "--force",
        action="store_true",
        help=f"run even when --samples is estimated to take over {SIMULATE_TIME_LIMIT:g} s (default: refuse)",
    )


def _plan(args: argparse.Namespace, loop: Loop, xd: float, quantize: bool) -> Any:
    """The run's :class:`~dfa.analysis.approach.SimulationPlan`; its typed errors as the flags' one-line messages."""
    from ..analysis import approach as ap

    per = 16 + (24 if args.observer else 0)  # ξ, ξ' and, replayed for the observer, φ_A, E_obs and f
    record = args.trace is not None or args.observer
    flags = {"preload": "--preload", "xi0": "--xi0"}
    try:
        return ap.plan_simulation(
            loop, xd, samples=args.samples, xi0=args.xi0, preload=args.preload, quantize=quantize,
            bound=SIMULATION_BOUND, record_bytes=per if record else 0,
        )  # fmt: skip
    except ap.StartConflict as err:
        if not err.one_sided:
            raise UsageError("--preload and --xi0 cannot both be given: the preload sets ξ0 from the speed") from None
        raise UsageError(
            f"{', '.join(flags[g] for g in err.given)} cannot be combined with --one-sided: the run starts in free "
            "space before contact"
        ) from None
    except ap.ApproachSpeedError as err:
        raise UsageError(
            f"the speed {err.speed:g} is invalid with --one-sided: the device must approach the wall (> 0)"
        ) from None
    except ap.StartBeyondBound as err:
        src = "the --preload position of this speed" if err.preload else "--xi0"
        raise UsageError(
            f"ξ0 = {err.xi0:.4g} ticks from {src} is beyond the simulation bound of {SIMULATION_BOUND:g} ticks "
            "(the run would stop at once as unstable): give a smaller start"
        ) from None
    except ap.RecordBudgetError as err:
        what = "--observer" if args.observer else "--trace"
        raise UsageError(
            f"{what} with --samples {err.samples} would need {err.nbytes / 1024**3:.1f} GiB of trajectory "
            f"(limit {ap.MAX_RECORD_BYTES / 1024**3:.0f} GiB): drop {what} or lower --samples"
        ) from None


def _write_trace(path: str, r: object, inp: Inputs, observer: bool) -> None:
    from ..render.files import write_trace_csv

    try:
        write_trace_csv(r, path, inp.device, inp.stiffness, observer=observer)
    except OSError as exc:
        raise UsageError(f"--trace {path!r} cannot be written: {exc.strerror}; choose a writable file") from None


def _trace_record(path: str, r: Any) -> dict[str, object]:
    """The JSON's ``trace`` record: the file, its last sample and rows, and why it ends there."""
    from ..render.files import trace_extent

    last, why = trace_extent(r)
    return {"file": path, "last_sample": last, "rows": last + 1, "ends": why}


def _observer_units(phys: dict[str, float] | None, inp: Inputs) -> dict[str, str]:
    """The unit of each number of the JSON's ``observer`` record."""
    out = {"produced": "KΔ²", "peak_produced": "KΔ²", "peak_controller_force": "KΔ", "peak_sample": "samples"}
    if phys is not None and inp.device is not None:
        out |= {"produced_j": "J", "peak_produced_j": "J", "peak_controller_force_n": inp.device.units["force"]}
    return out


def _observer(r: Any, inp: Inputs) -> tuple[Any, dict[str, float] | None]:
    """The passivity observer's summary of the run, and its energies and force in J and N with a device."""
    from ..analysis.observer import observe

    s = observe(r)
    if inp.device is None or inp.stiffness is None:
        return s, None
    return s, s.physical(inp.device, inp.stiffness)


def run(args: argparse.Namespace) -> int:
    """Simulate one impact; print its outcome, amplitude, frequency and final state."""
    from ..analysis.simulation import divergence_bound, simulate
    from ..render.contact import contact_line
    from ..render.files import trace_extent
    from ..render.text import simulation_rows

    inp = resolve(args, dimensionless=True, configurations=True)
    if inp.configurations:  # the smallest margin at |--velocity| (dfa check's rule), then that one's run
        _xd, v = speed(args, inp, signed=True)
        inp = limiting(args, inp, MARGIN, velocity=v, wall=wall_from_args(args, inp.device, inp.stiffness))
    p = inp.params
    assert p is not None
    check_damping_rate(p.beta, p.mu, RATE_NAMES[inp.device is None])
    xd, vel = speed(args, inp, signed=True)  # an initial condition: the sign of ξ'0 is the direction of motion
    assert xd is not None
    ctl = wall_from_args(args, inp.device, inp.stiffness)
    wp = wall_params(args, ctl, inp)
    if args.trace is not None:
        check_output_file("--trace", args.trace)
    quantize = not args.no_quantization
    loop = Loop.dimensionless(p.mu, p.beta, p.sigma, wp)
    plan = _plan(args, loop, xd, quantize)
    x0, v0 = plan.xi0, plan.xi_dot0
    if args.samples is not None:  # the automatic length is capped (dfa.analysis.simulation.default_samples)
        check_samples(args.samples, args.force)
    r = simulate(
        loop, v0, args.samples, xi0=x0, quantize=quantize, record=args.trace is not None or args.observer,
        progress=progress(args),
        bound=divergence_bound(x0, v0, p.mu, SIMULATION_BOUND),
    )  # fmt: skip
    if args.trace is not None:
        _write_trace(args.trace, r, inp, args.observer)
    known = inp.device is not None and inp.stiffness is not None
    phys = r.physical(inp.device, inp.stiffness) if known else r.physical(None, None)
    obs = _observer(r, inp) if args.observer else None
    if args.json:
        d = r.to_dict()
        d.update(phys)
        d["velocity"] = vel
        if not known:  # the same keys, null: no device, no physical units
            explain_nulls(d, dict.fromkeys(phys, NO_DEVICE) | {"velocity": NO_DEVICE})
        if r.outcome == "saturated":  # amplitude × KΔ is not a force the clipped actuator applies
            keys = ("force_amplitude_n", "force_amplitude_nm")
            d.update({k: None for k in keys if k in d})
            explain_nulls(d, dict.fromkeys(keys, SATURATED_AMPLITUDE))
        if r.outcome in ("left", "end_stop"):  # no cycle measured: the reason, not the serialiser's "NaN"
            unmeasured = r.null_reasons()
            d.setdefault("null_reasons", {}).update(
                {f"/{k}": unmeasured[k] for k in ("amplitude", "force_peak_to_peak")}
            )
        explain_nulls(d, r.null_reasons())
        if obs is not None:
            d["observer"] = obs[0].to_dict() | (obs[1] or {}) | {"units": _observer_units(obs[1], inp)}
        if args.trace is not None:
            d["trace"] = _trace_record(args.trace, r)
        emit(wall_json(d, ctl, inp))
        return 0
    say(f"{inp.label}: μ = {p.mu:.5g}, β = {p.beta:.5g}, σ = {p.sigma:.5g}")
    print_wall(ctl, inp, contact=False)  # the contact line below says more (the approach)
    if plan.approach is not None:
        say(contact_line(wp, plan.approach, xd))
    rows = simulation_rows(r, x0, v0, args.preload, phys if known else None)
    if obs is not None:
        from ..render.passivity import observer_rows

        rows += observer_rows(*obs, None if inp.device is None else inp.device.period)
    say(table(rows))
    if args.trace is not None:
        last, why = trace_extent(r)
        say(f"trace written to {args.trace}: samples 0 to {last} ({why})")
    return 0
