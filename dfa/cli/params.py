"""``dfa params``: the dimensionless (μ, β, σ) of a device and stiffness (paper Table 1)."""

from __future__ import annotations

import argparse

from ..render.hand import moving_symbols
from .inputs import add_device_args, resolve
from .output import emit, say, table

COMMAND = "params"
HELP = "dimensionless (μ, β, σ) of a device and stiffness (paper Table 1)"
EXAMPLE = "dfa params --device impulse"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The device (or the dimensionless groups) and --json."""
    add_device_args(p, dimensionless=True, speed=False)


def run(args: argparse.Namespace) -> int:
    """Print μ = m/(K T²), β = b/(K T), σ = c/(K Δ)."""
    inp = resolve(args, dimensionless=True)
    assert inp.params is not None
    dev = inp.device
    if args.json:
        emit(inp.params.to_dict() | ({} if dev is None else dev.hand_json()))
        return 0
    say(f"{inp.label}")
    p = inp.params
    m, b = moving_symbols(dev)
    say(
        table(
            [[f"μ = {m}/(K T²)", f"{p.mu:.6g}"], [f"β = {b}/(K T)", f"{p.beta:.6g}"], ["σ = c/(K Δ)", f"{p.sigma:.6g}"]]
        )
    )
    return 0
