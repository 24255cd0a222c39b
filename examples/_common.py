"""Shared command-line handling of the example scripts (not part of the package)."""

import argparse
import os


def parse(description: str):
    ap = argparse.ArgumentParser(description=description)
    ap.add_argument(
        "--out",
        default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "reports", "figures"),
        help="folder for the figure (default reports/figures)",
    )
    ap.add_argument("--quick", action="store_true", help="small grids and short runs (seconds)")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    return args
