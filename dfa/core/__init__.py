"""The compiled numerical core of dfa: dimensionless, no units, nothing of dfa above it.

Every numba kernel of the package lives here, and only here: importing this package first points numba's
on-disk cache at one folder named after these sources (:mod:`~dfa.core.cache`), whatever starts dfa. The
modules import numpy, numba, one another and dfa's errors only:

- :mod:`~dfa.core.exprel`: the relative exponentials φ₁, φ₂, ψ, χ and λ of the exact solution;
- :mod:`~dfa.core.energy`: the pseudo-elastic energy H_c of the quantized spring (paper eq. 18);
- :mod:`~dfa.core.kernel`: the exact simulator of the paper's loop, a spring wall (eq. 4-5);
- :mod:`~dfa.core.wall_kernel`: the same with a damper, velocity filter, delay and amplifier lag;
- :mod:`~dfa.core.table`: the wall's kernel table, the one array that carries a wall's elements to that kernel;
- :mod:`~dfa.core.open_loop`: the device driven by logged forces, and the identification fit's compiled sums;
- :mod:`~dfa.core.pair` and :mod:`~dfa.core.batch`: many runs in one compiled call;
- :mod:`~dfa.core.storage`: runs that record the storage function, for the soundness checks;
- :mod:`~dfa.core.dfcore`: the quantizer's describing function (eq. 41) in compiled sums;
- :mod:`~dfa.core.divdiff` and :mod:`~dfa.core.zohlag`: the ZOH pulse transfer with an amplifier lag;
- :mod:`~dfa.core.bracket`: many bracketed roots at once, each element on its own (ω(M) of the limit-cycle search);
- :mod:`~dfa.core.cache`: the cache folder of the compiled kernels (no kernel; imports no numba).

Analyses (:mod:`dfa.analysis.simulation`, :mod:`dfa.analysis.describing`, …) call these with validated dimensionless
inputs; nothing here checks its arguments but the kernel table (:func:`~dfa.core.table.check_table`).
"""

from .cache import configure as _configure

#: The folder numba caches these kernels in (:mod:`~dfa.core.cache`), set before any kernel is defined.
CACHE_DIR = _configure()
