"""The passivity controller's flags: ``--passivity-controller``, ``--pc-window S`` and ``--pc-force-limit N``
(issue 30), on ``dfa check``, ``simulate``, ``map``, ``stiffness``, ``zwidth`` and ``report``.

The controller (:class:`~dfa.model.elements.PassivityController`) joins the wall: the simulator runs it exactly;
the criterion, the exact linear bound, Colgate–Schenkel and the describing function say they do not cover it.
``dfa limit-cycles`` takes the flags only to refuse them with the reason. ``dfa simulate --observer`` reports
the passivity observer on any wall (:func:`add_observer_arg`).
"""

from __future__ import annotations

import argparse

from ..model.device import Device
from ..model.elements import Element, PassivityController
from .flag_table import add_rows, given_rows, needing
from .parsing import UsageError

__all__ = ["add_passivity_args", "add_observer_arg", "passivity_elements", "refuse_passivity_flag"]


def add_passivity_args(p: argparse.ArgumentParser) -> None:
    """--passivity-controller, --pc-window and --pc-force-limit, in their own group."""
    g = p.add_argument_group("passivity controller (default: none)")
    add_rows(g, PassivityController)


def add_observer_arg(p: argparse.ArgumentParser) -> None:
    """--observer (dfa simulate): report the passivity observer over the run."""
    p.add_argument(
        "--observer",
        action="store_true",
        help="report the passivity observer over the run: the energy the wall produced (positive: active), and "
        "with --trace a produced_energy column (default: off)",
    )


def passivity_elements(args: argparse.Namespace, device: Device | None) -> tuple[Element, ...]:
    """The controller's wall element of the flags (none without --passivity-controller), or a one-line refusal."""
    window, limit = getattr(args, "pc_window", None), getattr(args, "pc_force_limit", None)
    if not getattr(args, "passivity_controller", False):
        given = needing(args, "--passivity-controller")
        if given:
            raise UsageError(
                f"{', '.join(given)} needs --passivity-controller (they set its window and force limit); add "
                "--passivity-controller"
            )
        return ()
    if device is None:
        raise UsageError(
            "--passivity-controller needs a physical device and stiffness (its window and force limit are in s and "
            "N): give --device NAME (or --mass --damping --coulomb --resolution --period) and --stiffness K"
        )
    t = device.period
    if window is not None and not (t * (1 - 1e-9) <= window <= 1e6):
        raise UsageError(
            f"--pc-window {window:g} is invalid: the window must span at least one sample (T = {t:g} s) and at most "
            f"1e6 s; give a window in s in [{t:g}, 1e6] (it is rounded to whole samples), or drop the flag for the "
            "whole run"
        )
    if limit is not None and not 0.0 < limit <= 1e12:
        unit = device.units["force"]
        raise UsageError(
            f"--pc-force-limit {limit:g} is invalid: it must be > 0 and at most 1e12 {unit}; give the most force the "
            f"controller adds in {unit}, or drop the flag for no limit"
        )
    return (PassivityController(window=window, force_limit=limit),)


def refuse_passivity_flag(args: argparse.Namespace, why: str) -> None:
    """Refuse the controller's flags on a command that does not cover it (UsageError, exit 2), saying why."""
    flags = given_rows(args, PassivityController)
    if flags:
        raise UsageError(
            f"{', '.join(flags)} is not covered here: {why}; use dfa simulate, map, stiffness, zwidth, check or "
            "report with --passivity-controller"
        )
