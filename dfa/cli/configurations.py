"""Which configuration of a device file a command answers for (issue 46), by one rule per kind of command.

A device file's ``[[devices.configurations]]`` (:mod:`dfa.model.configurations`) make one device many one-axis
devices; a command answers for the limiting one and names it:

- a command *given* a stiffness (``simulate``, ``limit-cycles``, ``require``, ``export --stiffness``, ``map``,
  ``contours``, ``params``): the configuration with the smallest margin of the criterion (β − β₀)V + (σ − σ₀)
  (eq. 6) at its K and impact speed, :func:`dfa.analysis.configurations.worst_check` (``dfa check``'s rule); a
  command without a speed (``limit-cycles``, ``contours``, ``params``, ``export --stiffness``) takes V = 0, the
  margin σ − σ₀;
- a command that *searches* a stiffness (``tune``, ``export --velocity``): the configuration with the
  smallest recommended K at its speed, :func:`dfa.analysis.configurations.worst_stiffness` (``dfa stiffness``'s
  rule); ``zwidth`` takes the minimum over every configuration B by B instead
  (:func:`dfa.analysis.configurations.worst_z_width`).

:func:`limiting` turns :class:`~dfa.cli.inputs.Inputs` with configurations into the inputs of the limiting
configuration's one-axis device (``Inputs.worst`` keeps every row); :func:`configuration_json` is its record in
a command's JSON, :func:`configuration_line` its one line of text.
"""

from __future__ import annotations

import argparse
import dataclasses
from typing import Any

from ..model.device import dimensionless_params
from ..model.wall import Wall
from .inputs import Inputs
from .output import working
from .parsing import UsageError

__all__ = [
    "MARGIN",
    "STIFFNESS",
    "RULES",
    "limiting",
    "configuration_json",
    "configuration_line",
    "pinned",
    "add_configurations_plot_arg",
    "check_configurations_plot",
    "write_configurations_plot",
]

#: The rule of a command given a stiffness (``dfa check``'s).
MARGIN = "smallest_margin"
#: The rule of a command that searches a stiffness (``dfa stiffness``'s).
STIFFNESS = "smallest_recommended_stiffness"
#: Each rule in words (the commands' help and docs/cli.md).
RULES = {
    MARGIN: "the configuration with the smallest criterion margin (eq. 6) at K and the speed, as dfa check",
    STIFFNESS: "the configuration with the smallest recommended K at the speed, as dfa stiffness",
}


def limiting(
    args: argparse.Namespace,
    inp: Inputs,
    rule: str,
    *,
    velocity: float | None = None,
    wall: Wall | None = None,
    margin: float = 2.0,
) -> Inputs:
    """The inputs of the limiting configuration (``inp`` unchanged without configurations).

    Parameters
    ----------
    args : argparse.Namespace
        The command's flags (``--xi-dot`` is refused beside configurations: ticks of which encoder?).
    inp : Inputs
        :func:`~dfa.cli.inputs.resolve`'s, with ``configurations``.
    rule : {MARGIN, STIFFNESS}
        :data:`MARGIN`: the smallest criterion margin at the wall's K; :data:`STIFFNESS`: the smallest
        recommended K (the wall's elements held, K searched).
    velocity : float, optional
        Impact speed, m/s (rotary rad/s); its magnitude is taken; None: 0.
    wall : Wall, optional
        The wall (default the spring at the device's K with ``--delay``; for :data:`STIFFNESS` at K = 1).
    margin : float, optional
        The gain margin of the recommendation (:data:`STIFFNESS`), default 2.

    Returns
    -------
    Inputs
        The limiting configuration's one-axis device, its (μ, β, σ) at K, its label; ``worst`` every row.
    """
    from ..analysis.configurations import worst_check, worst_stiffness

    if not inp.configurations:
        return inp
    dev = inp.device
    assert dev is not None
    if getattr(args, "xi_dot", None) is not None:
        raise UsageError(
            "--xi-dot is in ticks of one encoder, and the device file's configurations have their own: give the "
            "impact speed as --velocity V (m/s, rad/s), or choose one with --configuration NAME"
        )
    v = 0.0 if velocity is None else abs(float(velocity))
    delay = getattr(args, "delay", 0) or 0
    with working(args):
        if rule == STIFFNESS:
            wall = Wall.of(1.0, delay=delay) if wall is None else wall
            w = worst_stiffness(dev, inp.configurations, v, wall=wall, margin=margin)
        else:
            if inp.stiffness is None:
                raise UsageError(f"missing --stiffness: the device file gives none for {dev.name!r}; give K in "
                                 f"{dev.units['stiffness']} (the configurations are compared at K)")  # fmt: skip
            wall = Wall.of(inp.stiffness, delay=delay) if wall is None else wall
            w = worst_check(dev, inp.configurations, v, wall)
    row = w.row
    conf = next(c for c in inp.configurations if c.name == w.limiting)
    one = conf.device_at(dev, row.normal)
    p = None if inp.stiffness is None else dimensionless_params(one, inp.stiffness)
    label = one.name + inp.label[len(dev.name) :] if inp.label.startswith(dev.name) else f"{inp.label} [{conf.name}]"
    return dataclasses.replace(
        inp, params=p, beta=p.beta if p else inp.beta, sigma=p.sigma if p else inp.sigma, device=one, label=label,
        entry=None, configurations=(), worst=w, rule=rule,
    )  # fmt: skip


def configuration_json(inp: Inputs | None) -> dict[str, Any]:
    """The ``configuration`` record of a command's JSON: the limiting configuration's name and normal, the rule,
    and every row (:class:`~dfa.results.configurations.WorstConfiguration`); empty without configurations."""
    if inp is None or inp.worst is None:
        return {}
    w = inp.worst
    normal = w.row.normal
    return {
        "configuration": {
            "name": w.limiting,
            "normal": None if normal is None else list(normal),
            "rule": inp.rule,
            "rule_text": RULES.get(inp.rule or "", ""),
        }
        | w.to_dict()
    }


def configuration_line(inp: Inputs | None) -> str | None:
    """One line naming the limiting configuration and its number (None without configurations)."""
    if inp is None or inp.worst is None:
        return None
    from ..render.configurations import limiting_line

    return limiting_line(inp.worst)


def pinned(inp: Inputs) -> tuple[str, ...]:
    """The flags that choose the limiting configuration in another command: ``--configuration NAME`` and, for an
    inertia matrix, ``--normal`` of its normal (17 digits: the same double); empty without configurations."""
    if inp.worst is None:
        return ()
    row = inp.worst.row
    out: tuple[str, ...] = ("--configuration", row.name)
    if row.normal is not None:
        out += ("--normal", ",".join(repr(float(x)) for x in row.normal))
    return out


def add_configurations_plot_arg(p: argparse.ArgumentParser) -> None:
    """``--configurations-plot FILE``: the figure of every configuration's answer (``dfa stiffness``, ``dfa check``)."""
    p.add_argument(
        "--configurations-plot",
        dest="configurations_plot",
        metavar="FILE",
        help="write the figure of every configuration's answer to FILE, .png, .pdf or .svg by its suffix: over the "
        "pose grid when every configuration has a pose (the limiting one starred), else a bar each; needs a device "
        "file with configurations (default: none)",
    )


def check_configurations_plot(args: argparse.Namespace, inp: Inputs) -> None:
    """--configurations-plot: refused (exit 2) without configurations to draw, or for a file it cannot write."""
    from .._io import FIGURE_SUFFIXES, check_output_file

    path = getattr(args, "configurations_plot", None)
    if path is None:
        return
    if not inp.configurations:
        raise UsageError(
            f"--configurations-plot {path!r} needs a device file with [[devices.configurations]]: "
            + ("--configuration chose one device" if getattr(args, "configuration", None) else "the device has none")
            + "; drop the flag, or give such a file without --configuration"
        )
    check_output_file("--configurations-plot", path, FIGURE_SUFFIXES)


def write_configurations_plot(args: argparse.Namespace, w: Any) -> str | None:
    """Write ``w.plot()`` (:class:`~dfa.results.configurations.WorstConfiguration`) to --configurations-plot,
    atomically; None when not asked."""
    from .output import save_png

    path = getattr(args, "configurations_plot", None)
    if path is None:
        return None
    return save_png("--configurations-plot", path, w.plot())
