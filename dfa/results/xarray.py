"""Optional xarray support: the import with a clear error, and the labelled grid axes (β, σ, ξ'0).

xarray is an optional extra (``pip install 'dfa-haptics[xarray]'``); ``import dfa`` never loads it.
"""

from __future__ import annotations

from typing import Any

from ..errors import DFAError

__all__ = ["import_xarray", "BETA_ATTRS", "SIGMA_ATTRS", "XI_DOT_ATTRS"]

#: attributes of the grid coordinates (dimensionless, paper Table 1)
BETA_ATTRS = {"long_name": "β = b/(KT)", "units": "1", "description": "dimensionless viscous damping (paper Table 1)"}
SIGMA_ATTRS = {"long_name": "σ = c/(KΔ)", "units": "1", "description": "dimensionless Coulomb friction (paper Table 1)"}
XI_DOT_ATTRS = {"long_name": "ξ'0", "units": "ticks/sample", "description": "initial speed in encoder ticks per sample"}


def import_xarray() -> Any:
    """The :mod:`xarray` module.

    Raises
    ------
    DFAError
        When xarray is not installed, naming the fix.
    """
    try:
        import xarray
    except ImportError:
        raise DFAError(
            "to_xarray() needs the optional package xarray, which is not installed: "
            "pip install 'dfa-haptics[xarray]' (or pip install xarray)"
        ) from None
    return xarray
