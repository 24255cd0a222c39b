"""The wall's flags: one row per wall element, from the element's own :class:`~dfa.model.elements.Parameter`.

Adding an element to :data:`dfa.model.elements.ELEMENTS` adds its flag to every command that takes a wall
(``--delay``, ``--virtual-damping``, ``--velocity-filter``, ``--amplifier-bandwidth`` today); the physical
values become a :class:`~dfa.model.wall.Wall` with :meth:`~dfa.model.wall.Wall.of` and its groups with
:meth:`~dfa.model.wall.Wall.params`.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

from ..model.device import Device
from ..model.elements import ELEMENTS, Coverage, Damper, Delay, Element, OneSided
from ..model.loop import device_elements, device_groups
from ..model.wall import MIN_CUTOFF, Wall, WallParams
from .flag_table import FLAG_ROWS, add_rows, given_rows, is_given
from .inputs import Inputs
from .output import say
from .parsing import UsageError

__all__ = [
    "WALL_FLAGS",
    "FLAG_ROWS",
    "add_rows",
    "hand_stiffness_of",
    "add_wall_args",
    "check_filter_amplifier",
    "given_flags",
    "print_wall",
    "wall_from_args",
    "wall_json",
    "wall_groups",
    "wall_params",
]


#: The wall's elements by their one row of the flag table (:data:`FLAG_ROWS`): element class -> (flag, argparse
#: destination). The delay is a plain flag (default 0); the others form the wall group (default: no such element).
WALL_FLAGS: dict[type[Element], tuple[str, str]] = {
    k: (row.flag, row.dest) for k in ELEMENTS if k.wall_flag for row in k.flag_rows()
}

#: Why ``dfa zwidth`` refuses the damper's flag (its help there).
_ZWIDTH_REFUSED = {
    Damper.parameter.flag: "not accepted here: B is the Z-width's axis, its grid spans B from 0 (default: the grid)"
}


def add_wall_args(p: argparse.ArgumentParser, *, zwidth: bool = False) -> None:
    """--delay and the other elements' flags. With ``zwidth`` the damper's flag is refused (B is the Z-width's axis)."""
    add_rows(p, Delay)
    title = (
        "wall (B is the Z-width's axis)"
        if zwidth
        else "wall (default: the paper's spring; needs a physical device and K)"
    )
    g = p.add_argument_group(title)
    for kind in WALL_FLAGS:
        if kind is not Delay:
            add_rows(g, kind, _ZWIDTH_REFUSED if zwidth else None)


def given_flags(args: argparse.Namespace) -> list[str]:
    """The wall flags given on the command line, besides --delay."""
    return [flag for kind in WALL_FLAGS if kind is not Delay for flag in given_rows(args, kind)]


def check_filter_amplifier(args: argparse.Namespace, device: Device) -> None:
    """Refuse (UsageError, exit 2) a filter cutoff <= 0 or not below the Nyquist frequency, a bandwidth <= 0."""
    fc, bw = args.velocity_filter, args.amplifier_bandwidth
    nyquist = 0.5 / device.period
    floor = MIN_CUTOFF * 2.0 * nyquist  # as Wall checks it, with the same rounding allowance
    if fc is not None and not floor * (1 - 1e-12) <= fc < nyquist:
        raise UsageError(
            f"--velocity-filter {fc:g} is invalid: the cutoff must be at least {floor:.6g} Hz ({MIN_CUTOFF:g} cycles "
            f"per sample: below, the linear analysis of a pole that close to the mass's has not been validated) and below "
            f"the Nyquist frequency {nyquist:.6g} Hz (1/(2T), T = {device.period:g} s); give a cutoff in Hz in "
            f"[{floor:.6g}, {nyquist:.6g}), or drop the flag"
        )
    if bw is not None and not bw > 0:
        raise UsageError(
            f"--amplifier-bandwidth {bw:g} is invalid: it must be > 0 Hz; give f_bw in Hz, or drop the flag"
        )


def _check_damper_rate(b: float, device: Device) -> None:
    """Refuse a damper whose B·T/m exceeds :data:`dfa.checks.MAX_RATE` (the analyses' rule, there worded with
    internal names), naming --virtual-damping, the value typed and the largest B that works."""
    from ..checks import MAX_RATE, format_value

    m, t = device.mass, device.period
    if b * t / m <= MAX_RATE:
        return
    u = device.units
    raise UsageError(
        f"--virtual-damping {format_value(b)} {u['damping']} is too large: B·T/m = {b * t / m:.3g} with m = {m:g} "
        f"{u['mass']}, T = {t:g} s must be at most {MAX_RATE:g} (the damper's time constant m/B under "
        f"{1 / MAX_RATE:g} samples: the loop's polynomials overflow); give B in {u['damping']} below "
        f"{MAX_RATE * m / t:.3g} (check the units)"
    )


def hand_stiffness_of(args: argparse.Namespace, device: Device | None) -> float:
    """The stiffness k_h of the hand holding ``device`` (0 for none), refused at or above the Nyquist resonance
    and with ``--amplifier-bandwidth``.

    The simulator's step needs the held device's resonance √(k_h/m)/(2π) below the Nyquist frequency 1/(2T)
    (:func:`dfa.analysis.simulation.check_hand_resonance`): k_h < π² m/T², m the moving mass with the hand's.
    """
    hand = device.hand.stiffness if device is not None and device.hand is not None else 0.0
    if hand and getattr(args, "amplifier_bandwidth", None) is not None:
        raise UsageError(
            "--amplifier-bandwidth cannot be combined with a hand stiffness (--hand-stiffness or --hand PRESET): the "
            "simulator's step with both is not derived yet; drop one of them (--hand-stiffness 0 keeps the hand's "
            "mass and damping)"
        )
    if hand and device is not None:
        top = math.pi**2 * device.mass / device.period**2
        if not hand < top:
            unit = device.units["stiffness"]
            raise UsageError(
                f"--hand-stiffness {hand:g} is invalid: the held device's resonance √(k_h/m)/(2π) must lie below the "
                f"Nyquist frequency 1/(2T); give k_h below π² m/T² = {top:.4g} {unit}"
            )
    return hand


def wall_from_args(args: argparse.Namespace, device: Device | None, stiffness: float | None) -> Wall | None:
    """The wall of the flags beyond a spring; None for the paper's spring (no flag, or B = 0 without filter and lag).

    Refuses (UsageError, exit 2) a negative B, a cutoff <= 0 or not below the Nyquist frequency, a
    bandwidth <= 0, and wall flags without a physical device and stiffness.
    """
    from .contact import contact_elements
    from .passivity import passivity_elements

    given = given_flags(args)
    hand = hand_stiffness_of(args, device)
    # the device's elements of the physical wall (the force limit, --max-force); without K the Loop adds them
    limit = () if stiffness is None else device_elements(device, in_wall=True)
    contact = contact_elements(args, device) + passivity_elements(args, device) + limit
    if not given and not hand and not contact:
        return None
    if device is None or stiffness is None:
        given += [row.flag for row in FLAG_ROWS.values() if row.metavar is None and is_given(args, row)]  # switches
        raise UsageError(
            f"{', '.join(given)} needs a physical device and stiffness (K and T turn B, f_c, f_bw into β_B, ν_c, α): "
            "give --device NAME (or --mass --damping --coulomb --resolution --period) and --stiffness K"
        )
    b = args.virtual_damping
    if b is not None and b < 0:
        bu = device.units["damping"]
        raise UsageError(f"--virtual-damping {b:g} is invalid: B must be >= 0; give the damper in {bu} (0 for none)")
    if b is not None:
        _check_damper_rate(b, device)
    check_filter_amplifier(args, device)
    values: dict[str, Any] = {kind.parameter.name: getattr(args, dest) for kind, (_f, dest) in WALL_FLAGS.items()}
    values["damping"] = values["damping"] or 0.0
    wall = Wall.of(stiffness, hand_stiffness=hand, **values)
    wall = Wall(stiffness, (*wall.elements, *contact)) if contact else wall
    return None if wall_groups(wall, device).covers(Coverage.CLOSED_FORM) else wall


#: How a message of the wall's groups calls each element's value: its flag (``--virtual-damping``, ``--push``).
WALL_NAMES = {k.parameter.name: k.parameter.flag for k in ELEMENTS}


def wall_groups(wall: Wall, device: Device) -> WallParams:
    """The wall's dimensionless groups on ``device``; a value whose group a float cannot hold (``--push 1e308``
    over K Δ) is refused naming its flag, the value in its unit, what overflowed and the value that works."""
    return wall.params(device.period, device.resolution, names=WALL_NAMES, rotary=device.rotary)


def wall_params(args: argparse.Namespace, wall: Wall | None, inp: Inputs | None) -> WallParams:
    """The dimensionless wall of a run: the wall's groups, else the spring with the --delay; with the device's
    groups-only elements, e.g. its travel (--travel, or the catalogue's), where the run ends at an end stop
    (:func:`dfa.model.loop.device_groups`)."""
    device = None if inp is None else inp.device
    if wall is None or device is None:
        return device_groups(WallParams.of(delay=args.delay), device)
    return device_groups(wall_groups(wall, device), device)


def wall_json(d: dict[str, Any], wall: Wall | None, inp: Inputs | None) -> dict[str, Any]:
    """Set the record's ``"wall"`` to the wall's physical values, units and dimensionless groups (nothing for the
    spring: its record is unchanged); with a device's travel, ``"travel"`` (m, rotary rad; its unit in
    ``"travel_unit"``), ``"travel_ticks"`` (ξ_travel = travel/Δ), where a run ends (``end_stop``), and
    ``"travel_assumption"`` (what the verdicts assume: the motion stays inside)."""
    if inp is not None and inp.worst is not None:
        from .configurations import configuration_json

        d.update(configuration_json(inp))
    if wall is not None and inp is not None and inp.device is not None:
        from ..render.controller import wall_dict

        d["wall"] = wall_dict(wall, inp.device.period, inp.device.units, inp.device.resolution)
    travel = None if inp is None or inp.device is None else inp.device.travel
    if inp is not None and inp.device is not None and travel is not None:
        dev = inp.device
        from ..render.controller import TRAVEL_ASSUMES

        d.update(travel=travel, travel_unit=dev.units["position"], travel_ticks=travel / dev.resolution)
        d["travel_assumption"] = TRAVEL_ASSUMES
    return d


def _print_travel(device: Device, wrap: bool) -> None:
    """State the device's travel and what the analyses assume of it (nothing without a travel)."""
    from ..render.controller import travel_text

    line = travel_text(device.travel, device.resolution, device.units["position"])
    if line is not None and wrap:
        say(line)
    elif line is not None:
        print(line)


def print_wall(wall: Wall | None, inp: Inputs | None, *, wrap: bool = True, contact: bool = True) -> None:
    """State the wall (nothing for the spring: its output is unchanged): its physical values, then its
    dimensionless groups on a second line; one line, unwrapped, when ``wrap`` is False (``--explain``); a
    one-sided wall's contact on a line of its own (unless ``contact`` is False: a command that states it itself)."""
    if inp is not None and inp.worst is not None:  # the device file's configuration answered for, named
        from .configurations import configuration_line

        (say if wrap else print)(configuration_line(inp))
    if inp is not None and inp.device is not None:
        _print_travel(inp.device, wrap)
    if wall is not None and inp is not None and inp.device is not None:
        from ..render.contact import contact_text
        from ..render.controller import controller_parts

        values, groups = controller_parts(wall, inp.device.period, inp.device.units, inp.device.resolution)
        line = (
            f"contact: {contact_text(wall, inp.device.units)}" if contact and wall.element(OneSided) is not None else ""
        )
        if wrap:
            say(f"{values};\n  {groups}")
            if line:
                say(line)
        else:
            print(f"{values}; {groups}")
            if line:
                print(line)
