"""``dfa params``: the dimensionless (μ, β, σ) of a device and stiffness (paper Table 1)."""

from __future__ import annotations

import argparse
from typing import Any

from ..model.device import dimensionless_params
from ..render.configurations import MARK
from ..render.hand import moving_symbols
from .configurations import MARGIN, configuration_json, configuration_line, limiting
from .inputs import Inputs, add_device_args, resolve
from .output import emit, say, table

COMMAND = "params"
HELP = "dimensionless (μ, β, σ) of a device and stiffness (paper Table 1)"
EXAMPLE = "dfa params --device impulse"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device (or the dimensionless groups) and --json."""
    add_device_args(p, dimensionless=True, speed=False)


def _rows(base: Inputs, inp: Inputs) -> list[dict[str, Any]]:
    """Every configuration's (μ, β, σ) at K along its normal (the worst one found where the file gives none:
    :func:`dfa.analysis.configurations.worst_check`'s), the limiting one marked."""
    w, dev, k = inp.worst, base.device, base.stiffness
    assert w is not None and dev is not None and k is not None
    out: list[dict[str, Any]] = []
    for c, r in zip(base.configurations, w.rows, strict=True):
        p = dimensionless_params(c.device_at(dev, r.normal), k)
        normal = None if r.normal is None else list(r.normal)
        out.append({"name": r.name, "normal": normal} | p.to_dict() | {"limiting": r.name == w.limiting})
    return out


def run(args: argparse.Namespace) -> int:
    """Print μ = m/(K T²), β = b/(K T), σ = c/(K Δ) (a row per configuration of a device file)."""
    inp = resolve(args, dimensionless=True, configurations=True)
    rows = None
    if inp.configurations:  # a row each; the limiting one: the smallest margin at speed 0, σ − σ₀ (eq. 6)
        base = inp
        inp = limiting(args, inp, MARGIN)
        rows = _rows(base, inp)
    assert inp.params is not None
    dev = inp.device
    if args.json:
        extra = {} if rows is None else configuration_json(inp) | {"configurations": rows}
        emit(inp.params.to_dict() | ({} if dev is None else dev.hand_json()) | extra)
        return 0
    say(f"{inp.label}")
    if rows is not None:
        say(configuration_line(inp))
        say(table([[r["name"], f"{r['mu']:.6g}", f"{r['beta']:.6g}", f"{r['sigma']:.6g}", MARK if r["limiting"] else ""]
                   for r in rows], ["configuration", "μ", "β", "σ", ""]))  # fmt: skip
        return 0
    p = inp.params
    m, b = moving_symbols(dev)
    say(
        table(
            [[f"μ = {m}/(K T²)", f"{p.mu:.6g}"], [f"β = {b}/(K T)", f"{p.beta:.6g}"], ["σ = c/(K Δ)", f"{p.sigma:.6g}"]]
        )
    )
    return 0
