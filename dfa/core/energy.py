"""The pseudo-elastic energy of the quantized spring (paper eq. 18): one formula for numpy and the kernels.

H_c(ξ) = ½ξ² + ½(p − p²), p = ξ − ⌊ξ⌋, is the exact integral of the restoring staircase
⌊s⌋ + ½ from 0 to ξ, so ½ξ² <= H_c(ξ) <= ½ξ² + 1/8; without quantization H_c = ½ξ².

Examples
--------
>>> import numpy as np
>>> float(spring_energy_core(np.float64(0.5), True)), float(spring_energy_core(np.float64(0.5), False))
(0.25, 0.125)
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["spring_energy_core"]


def spring_energy_core(x: Any, quantize: bool) -> Any:
    """H_c(ξ) for a float or a float array (eq. 18); ½ξ² without quantization.

    No validation: :func:`dfa.analysis.criterion.spring_energy` checks its inputs; ``numba.njit`` compiles this
    function unchanged for floats (:mod:`dfa.core.kernel`).
    """
    if quantize:
        p = x - np.floor(x)
        return 0.5 * x * x + 0.5 * (p - p * p)
    return 0.5 * x * x
