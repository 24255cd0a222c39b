"""``dfa devices``: the device catalogue (paper Table 2), or a device file to start from (``--template``)."""

from __future__ import annotations

import argparse

from ..errors import DFAError
from ..model.catalogue import CatalogueEntry, catalogue, device_template, get_device, load_device_file
from ..model.device import DEVICE_FIELDS, STIFFNESS, DeviceField
from .output import emit, fmt, say, table
from .parsing import UsageError

COMMAND = "devices"
HELP = "list the device catalogue (paper Table 2)"
EXAMPLE = "dfa devices --json"

#: The physical columns of the listing: the device's fields, then the stiffness K.
_COLUMNS = (*DEVICE_FIELDS, STIFFNESS)


def _symbol(f: DeviceField) -> str:
    """A column's heading: the field's symbol (``"m or J"`` where a rotary device's differs)."""
    rotary = f.rotary_symbol or f.symbol
    return f.symbol if rotary == f.symbol else f"{f.symbol} or {rotary}"


def add_arguments(p: argparse.ArgumentParser) -> None:
    """--json, --template."""
    p.add_argument("--json", action="store_true", help="print one JSON list on stdout (default: a text table)")
    p.add_argument(
        "--template",
        action="store_true",
        help="print a commented device file (TOML, the catalogue's format) to fill in and use with --device-file: "
        "`dfa devices --template > my_device.toml` (default: the catalogue)",
    )
    p.add_argument(
        "--device-file",
        dest="device_file",
        metavar="FILE.toml",
        help="with --template: write this device file's row in full instead (every value, and its "
        "[[devices.configurations]] tables), a file that reads back unchanged (default: the template to edit)",
    )
    p.add_argument(
        "--device",
        metavar="NAME",
        help="with --template: write this catalogue device's row in full instead, to start a file from it "
        "(default: the template to edit)",
    )


def _row(args: argparse.Namespace) -> CatalogueEntry | None:
    """The row --template writes in full: --device-file's (its configurations too) or --device's; None: the
    template to edit."""
    if args.device_file is not None and args.device is not None:
        raise UsageError("--device-file and --device cannot both be given to --template: give the one row to write")
    try:
        if args.device_file is not None:
            return load_device_file(args.device_file)
        if args.device is not None:
            return get_device(args.device)
    except DFAError as exc:
        raise UsageError(str(exc)) from None
    return None


def run(args: argparse.Namespace) -> int:
    """List the catalogue: physical values, recomputed (μ, β, σ), printed values and disagreements."""
    if args.template:
        if args.json:
            raise UsageError("--template and --json cannot both be given: the template is TOML; give one of them")
        print(device_template(_row(args)), end="")
        return 0
    for flag, value in (("--device-file", args.device_file), ("--device", args.device)):
        if value is not None:
            raise UsageError(f"{flag} {value!r} needs --template: it chooses the row the template writes; add "
                             "--template, or drop the flag for the catalogue")  # fmt: skip
    rows = catalogue()
    if args.json:
        emit([r.to_dict() for r in rows])
        return 0
    phys, dims = [], []
    for r in rows:
        p = r.params
        pr = r.printed_params
        flags = ["incomplete"] if r.incomplete else []
        flags += [f"{d.parameter} {100 * d.relative:+.0f}%" for d in r.discrepancies]
        printed = ", ".join(pr.get(k) and f"{pr[k]:g}" or "-" for k in ("mu", "beta", "sigma")) if pr else "-"
        phys.append([r.name, *(fmt(getattr(r, f.name)) for f in _COLUMNS)])
        dims.append([r.name, fmt(p.mu if p else None), fmt(p.beta if p else None, 3), fmt(p.sigma if p else None),
                     printed, "; ".join(flags) or "ok"])  # fmt: skip
    say(table(phys, ["device", *(_symbol(f) for f in _COLUMNS)]))
    say()
    say(table(dims, ["device", "μ", "β", "σ", "printed μ, β, σ", "flags"]))
    say()
    linear, rotary = (", ".join(f.unit_of(rot) for f in _COLUMNS) for rot in (False, True))
    say(f"SI units (linear: mass m in {linear}; rotary: inertia J in {rotary}).")
    say(
        "μ, β, σ recomputed from the physical columns (paper Table 1); flags: printed value disagrees (> 5 % and beyond its last digit)."
    )
    return 0
