"""Construction helpers of the frozen result dataclasses: read-only array copies and checks.

Examples
--------
>>> import numpy as np
>>> a = frozen_array("beta", [0.0, 0.5])
>>> a.flags.writeable
False
>>> frozen_array("beta", [0.0, np.nan])
Traceback (most recent call last):
...
dfa.errors.DFAValueError: beta = [0.0, nan] is invalid: it must hold finite numbers (NaN or inf given); pass the array the analysis computed
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..checks import format_value
from ..errors import DFAValueError

__all__ = ["frozen_array", "freeze_fields", "check_shape"]

_FIX = "pass the array the analysis computed"


def frozen_array(
    name: str, value: Any, *, dtype: Any = float, ndim: int | None = None, finite: bool = True
) -> np.ndarray:
    """A read-only copy of ``value`` as an array of ``dtype``.

    Parameters
    ----------
    name : str
        Field name, for the error message.
    value : array_like
    dtype : numpy dtype, optional
    ndim : int, optional
        Required number of dimensions.
    finite : bool, optional
        When True (default), NaN and infinities are refused; a result whose
        arrays may hold them documents what they mean in its status.

    Raises
    ------
    DFAValueError
        Wrong number of dimensions, or non-finite entries where ``finite``.
    """
    try:
        a = np.array(value, dtype=dtype, copy=True)
    except (TypeError, ValueError, OverflowError) as err:
        raise DFAValueError(
            f"{name} = {format_value(value)} is invalid: it must be an array of {np.dtype(dtype)} ({err}); {_FIX}"
        ) from None
    if ndim is not None and a.ndim != ndim:
        raise DFAValueError(
            f"{name} = {format_value(value)} is invalid: it must have {ndim} dimension(s), not {a.ndim}; {_FIX}"
        )
    if finite and a.dtype.kind in "fc" and not np.all(np.isfinite(a)):
        raise DFAValueError(
            f"{name} = {format_value(value)} is invalid: it must hold finite numbers (NaN or inf given); {_FIX}"
        )
    a.setflags(write=False)
    return a


def freeze_fields(obj: Any, names: dict[str, dict[str, Any]]) -> None:
    """Replace each field of the frozen dataclass ``obj`` named in ``names`` by :func:`frozen_array` of it.

    ``names`` maps a field name to the keyword arguments of :func:`frozen_array`;
    fields holding None are left alone.
    """
    for name, kw in names.items():
        value = getattr(obj, name)
        if value is not None:
            object.__setattr__(obj, name, frozen_array(name, value, **kw))


def check_shape(name: str, array: np.ndarray, shape: tuple[int, ...]) -> None:
    """Refuse ``array`` unless its shape is ``shape``.

    Raises
    ------
    DFAValueError
        Shape mismatch (the fields of a result disagree).
    """
    if array.shape != tuple(shape):
        raise DFAValueError(
            f"{name} has shape {array.shape} but {tuple(shape)} is required by the other fields: "
            f"they must come from the same grid; {_FIX}"
        )
