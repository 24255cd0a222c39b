"""The wall's kernel table: one float64 array that carries a wall's elements to the compiled simulator.

:mod:`dfa.core.wall_kernel` takes a wall as this table (built by :meth:`dfa.model.wall.WallParams.kernel_table`
from each element's :class:`dfa.model.elements.KernelBlock`; the elements declare their codes from here)::

    table = [B,  code₁, m₁, s₁, p₁₁ … p₁ₘ₁,  code₂, m₂, s₂, p₂₁ …,  …]

B blocks, one per element in the wall's order. A block is the element's code (:data:`CODES`), its number of
parameters m (:data:`BLOCK_PARAMS`), its state size s and its m parameters. The state size counts the floats the
element adds to the loop's state between samples (:mod:`dfa.core.wall_kernel`, "Period skipping"): the delay's d
pending commands, the filter's y_{h−1} and v_{h−1}, the amplifier's φ_A, the passivity observer's own state
(5 + W: beside its bookings, one per slot of the delay ring); it documents the block and is not read by the kernel. The
parameters, dimensionless (ticks, samples, KΔ):

========================  ======  ==========================================================================
element                   code    parameters
========================  ======  ==========================================================================
Delay                     1       d, samples (the blocks' delays add up)
Damper                    2       β_B
VelocityFilter            3       its pole a = e^{−2πν_c} (computed once, in Python)
AmplifierLag              4       α, samples
HandSpring                5       κ_h
OneSided                  6       the surface s, ticks
Push                      7       p, KΔ
PassivityController       8       the window W, samples (0: unbounded), and the force limit, KΔ (inf: none)
ForceLimit                9       φ_max = F_max/(KΔ), the actuator's limit on the command
Travel                    10      ξ_travel, ticks: the device's end stops at ±ξ_travel (the run ends past them)
========================  ======  ==========================================================================

``[0.0]`` (no block) is the paper's spring. Anything after the B-th block is ignored, so tables of different
lengths stack into the rows of one array (:func:`stack_tables`). A table is read once per run
(:func:`dfa.core.wall_kernel.decode_table`); :func:`check_table` refuses an unknown code before a call.

Examples
--------
>>> t = np.array([2.0, DAMPER, 1, 0, 0.5, DELAY, 1, 1, 1.0])   # a damper β_B = 0.5 and a delay of one sample
>>> check_table(t) is t
True
>>> stack_tables([t, np.array([0.0])]).shape
(2, 9)
"""

from __future__ import annotations

from typing import Any, TypeAlias

import numpy as np
import numpy.typing as npt

from ..errors import DFAValueError

__all__ = [
    "BLOCK_PARAMS", "BLOCKS", "CODES", "DAMPER", "DELAY", "FILTER", "FORCE_LIMIT", "HAND", "HEAD", "LAG", "ONE_SIDED", "PASSIVITY", "PUSH",
    "TRAVEL", "check_table", "stack_tables",
]  # fmt: skip

FloatArray: TypeAlias = npt.NDArray[np.float64]

#: The element codes (one per element class of :mod:`dfa.model.elements`, which declares its own from these).
DELAY, DAMPER, FILTER, LAG, HAND, ONE_SIDED, PUSH, PASSIVITY, FORCE_LIMIT, TRAVEL = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10
#: A block's head: its code, parameter count and state size.
HEAD = 3
#: Each element code's block: the name of the class of :mod:`dfa.model.elements` that declares it (its
#: ``kernel_code``, checked by ``tests/test_kernel_table.py``) and the number of parameters its block carries. One
#: row per element; :data:`CODES` and :data:`BLOCK_PARAMS` are read from it.
BLOCKS: dict[int, tuple[str, int]] = {
    DELAY: ("Delay", 1), DAMPER: ("Damper", 1), FILTER: ("VelocityFilter", 1), LAG: ("AmplifierLag", 1),
    HAND: ("HandSpring", 1), ONE_SIDED: ("OneSided", 1), PUSH: ("Push", 1), PASSIVITY: ("PassivityController", 2),
    FORCE_LIMIT: ("ForceLimit", 1), TRAVEL: ("Travel", 1),
}  # fmt: skip
#: Each element code's name (the class of :mod:`dfa.model.elements` that declares it).
CODES = {code: name for code, (name, _m) in BLOCKS.items()}
#: The number of parameters each code's block carries.
BLOCK_PARAMS = {code: m for code, (_name, m) in BLOCKS.items()}


def check_table(table: Any) -> FloatArray:
    """Check a wall's kernel table (module docstring) before a kernel call.

    Parameters
    ----------
    table : numpy.ndarray
        One-dimensional float64: the block count B, then B blocks (code, m, state size, m parameters).

    Returns
    -------
    numpy.ndarray
        The table, if valid.

    Raises
    ------
    DFAValueError
        If it is not a 1-D float64 array, a block's code is unknown, its parameter count is not the code's,
        or the blocks run past the table's end.

    Examples
    --------
    >>> check_table(np.array([1.0, 99.0, 1.0, 0.0, 0.5]))
    Traceback (most recent call last):
    ...
    dfa.errors.DFAValueError: table block 0 code = 99 is invalid: the kernel knows the codes 1 Delay, 2 Damper, 3 VelocityFilter, 4 AmplifierLag, 5 HandSpring, 6 OneSided, 7 Push, 8 PassivityController, 9 ForceLimit, 10 Travel; build the table with WallParams.kernel_table()
    """
    fix = "build the table with WallParams.kernel_table()"
    if not (isinstance(table, np.ndarray) and table.ndim == 1 and table.dtype == np.float64 and table.size >= 1):
        raise DFAValueError(f"table = {table!r} is invalid: it must be a non-empty 1-D float64 array; {fix}")
    count, j = table[0], 1
    if not (count >= 0 and count == int(count)):
        raise DFAValueError(f"table block count = {count!r} is invalid: it must be a whole number >= 0; {fix}")
    for b in range(int(count)):
        if j + HEAD > table.size:
            raise DFAValueError(f"table = {table!r} is invalid: block {b} runs past its end; {fix}")
        code, m = table[j], table[j + 1]
        if code not in CODES:
            known = ", ".join(f"{c} {name}" for c, name in sorted(CODES.items()))
            raise DFAValueError(
                f"table block {b} code = {code:g} is invalid: the kernel knows the codes {known}; {fix}"
            )
        if m != BLOCK_PARAMS[int(code)] or j + HEAD + int(m) > table.size:
            raise DFAValueError(
                f"table block {b} ({CODES[int(code)]}) parameter count = {m:g} is invalid: it carries "
                f"{BLOCK_PARAMS[int(code)]} within the table; {fix}"
            )
        j += HEAD + int(m)
    return table


def stack_tables(tables: Any) -> FloatArray:
    """Stack kernel tables of different lengths into the rows of one array (:func:`dfa.core.batch.batch_wall_kernel`).

    Parameters
    ----------
    tables : sequence of numpy.ndarray
        Checked tables (:func:`check_table`).

    Returns
    -------
    numpy.ndarray
        (len(tables), longest) float64, row i table i padded with zeros after its last block (ignored).
    """
    out = np.zeros((len(tables), max((t.size for t in tables), default=1)))
    for i, t in enumerate(tables):
        out[i, : t.size] = t
    return out
