"""Optional xarray support: the import with a clear error, the labelled grid axes and the attributes.

The dimensionless axes (β, σ, ξ'0) have fixed attributes; a physical axis or variable takes its unit from the
result's device (:func:`physical_attrs`), a variable of integer codes names them (:func:`flag_attrs`), and
the scalar inputs of a result become attributes a netCDF file can store (:func:`netcdf_attrs`).

xarray is an optional extra (``pip install 'dfa-haptics[xarray]'``); ``import dfa`` never loads it.

Examples
--------
>>> flag_attrs("outcome", ("rest", "diverges"))
{'long_name': 'outcome', 'flag_values': [0, 1], 'flag_meanings': 'rest diverges'}
>>> netcdf_attrs({"stiffness": None, "quantize": True, "wall": {"delay": 1, "filter_cutoff": None}})
{'quantize': 1, 'wall_delay': 1}
"""

from __future__ import annotations

import enum
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from ..errors import DFAError
from ..jsonable import NULL_REASONS_KEY

__all__ = [
    "import_xarray",
    "BETA_ATTRS",
    "SIGMA_ATTRS",
    "XI_DOT_ATTRS",
    "physical_attrs",
    "flag_attrs",
    "netcdf_attrs",
]

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


def physical_attrs(long_name: str, units: str, **more: str) -> dict[str, str]:
    """Attributes of a physical coordinate or variable: its long name, its units (the device's) and more text.

    Parameters
    ----------
    long_name : str
        What the values are, e.g. ``"virtual stiffness K"``.
    units : str
        Their unit, from the result's device (``device.units``).
    **more : str
        Further attributes (``description``, ``comment``).

    Returns
    -------
    dict of str to str
        ``{"long_name": ..., "units": ..., **more}``.
    """
    return {"long_name": long_name, "units": units, **more}


def flag_attrs(long_name: str, names: Sequence[str]) -> dict[str, Any]:
    """Attributes of a variable of integer codes (CF flags): the code of each name is its index in ``names``.

    Parameters
    ----------
    long_name : str
        What the codes are.
    names : sequence of str
        The name of each code, in the order of the codes (one word each).

    Returns
    -------
    dict
        ``long_name``, ``flag_values`` (0, 1, ...) and ``flag_meanings`` (the names, space-separated).
    """
    return {"long_name": long_name, "flag_values": list(range(len(names))), "flag_meanings": " ".join(names)}


def netcdf_attrs(values: Mapping[str, Any]) -> dict[str, Any]:
    """Scalar inputs of a result as attributes a netCDF file can store.

    None is left out (an absent attribute), True/False become 1/0, an enum member its value, a tuple a
    list, a nested mapping its keys prefixed by the outer key (``wall_delay``; its ``null_reasons`` left
    out). Numbers are kept as they are: NaN and infinities stay.

    Parameters
    ----------
    values : mapping of str to object
        The attributes, by name.

    Returns
    -------
    dict
        The attributes, in the order given.
    """
    out: dict[str, Any] = {}
    for key, value in values.items():
        if isinstance(value, Mapping):
            out.update(netcdf_attrs({f"{key}_{k}": v for k, v in value.items() if k != NULL_REASONS_KEY}))
        elif value is None:
            continue
        elif isinstance(value, (bool, np.bool_)):
            out[key] = int(value)
        elif isinstance(value, enum.Enum):
            out[key] = value.value
        elif isinstance(value, tuple):
            out[key] = list(value)
        else:
            out[key] = value
    return out
