"""The contact flags: ``--one-sided``, ``--surface TICKS`` and ``--push N`` (issue 28 §1), on ``dfa check``,
``dfa simulate`` and ``dfa map``.

A one-sided wall (:class:`~dfa.model.elements.OneSided`) pushes only while the reading is beyond its surface, and
the operator may push toward it with a constant force (:class:`~dfa.model.elements.Push`). The run then starts
in free space, D samples before the device reaches the wall at the impact speed, with the controller's memory
of the approach (:func:`dfa.analysis.approach.approach_start`). ``dfa stiffness``, ``dfa zwidth`` and ``dfa report`` start
every impact with that approach too. ``dfa limit-cycles`` takes the flags only to refuse them with the reason:
no describing function covers a one-sided wall.
"""

from __future__ import annotations

import argparse

from ..model.device import Device
from ..model.elements import Element, OneSided, Push
from .flag_table import add_rows, needing
from .parsing import UsageError

__all__ = ["add_contact_args", "contact_elements", "refuse_one_sided_flag", "CONTACT_COMMANDS"]

#: The commands that take a one-sided wall (the others refuse --one-sided with the reason).
CONTACT_COMMANDS = "dfa check, simulate, map, stiffness, zwidth or report"


def add_contact_args(p: argparse.ArgumentParser) -> None:
    """--one-sided, --surface and --push, in their own group."""
    g = p.add_argument_group("contact (default: the paper's bilateral spring)")
    add_rows(g, OneSided)
    add_rows(g, Push)


def contact_elements(args: argparse.Namespace, device: Device | None) -> tuple[Element, ...]:
    """The contact's wall elements of the flags (none without --one-sided), or a one-line refusal (exit 2)."""
    surface, push = getattr(args, "surface", None), getattr(args, "push", None)
    if not getattr(args, "one_sided", False):
        given = needing(args, "--one-sided")
        if given:
            raise UsageError(f"{', '.join(given)} needs --one-sided: they describe a one-sided wall; add --one-sided")
        return ()
    if device is None:
        raise UsageError(
            "--one-sided needs a physical device and stiffness (the push and the approach are in physical "
            "units): give --device NAME (or --mass --damping --coulomb --resolution --period) and --stiffness K"
        )
    if surface is not None and not abs(surface) < 1e9:
        raise UsageError(f"--surface {surface:g} is invalid: give the surface's position in ticks, e.g. 0 or 0.25")
    if push is not None and not push >= 0.0:
        raise UsageError(f"--push {push:g} is invalid: the operator's force toward the wall must be >= 0 N")
    if push:
        from ..plausibility import warn_implausible

        warn_implausible("force", push, rotary=device.rotary, subject="--push")
    out: list[Element] = [OneSided(0.0 if surface is None else surface)]
    if push:
        out.append(Push(push))
    return tuple(out)


def refuse_one_sided_flag(args: argparse.Namespace, why: str) -> None:
    """Refuse --one-sided on a command that does not cover a one-sided wall (UsageError, exit 2), saying why."""
    if getattr(args, "one_sided", False):
        raise UsageError(f"--one-sided is not covered here: {why}; use {CONTACT_COMMANDS} with --one-sided")
