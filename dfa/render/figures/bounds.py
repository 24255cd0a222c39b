"""The closed-form stiffness bounds (eq. 8, 9 and the exact linear bound) as labelled lines, in one style each."""

from __future__ import annotations

import numpy as np

from ...formatting import number

#: One style per closed-form stiffness bound (stiffness plot, stiffness-speed chart): coinciding lines stay
#: visible because they differ in width, dash and colour (the wide pale line under the thin ones).
BOUND_STYLES = {
    "abbott_okamura": dict(color="#c2a5cf", lw=6.0, alpha=0.8, ls="-"),
    "colgate": dict(color="#762a83", lw=1.6, ls="--"),
    "linear": dict(color="k", lw=1.1, ls=(0, (1, 1.5))),
    "static": dict(color="#4d9221", lw=1.3, ls="-."),
}


def closed_form_bounds(k_static: float, k_colgate: float, k_ao: float, k_linear: float, delay: int):
    """(key, value, name) of the closed-form bounds (eq. 8, 9 and the exact linear bound), widest line first."""
    cs = "2b/T" if delay == 0 else f"b/(T(½ + {delay}))"
    return [
        ("abbott_okamura", k_ao, f"Abbott–Okamura min({cs}, 2c/Δ)"),
        ("colgate", k_colgate, f"Colgate–Schenkel {cs}"),
        ("linear", k_linear, "exact linear bound (no encoder, no friction)"),
        ("static", k_static, "static limit 2c/Δ (eq. 9)"),
    ]


def draw_bounds(ax, bounds, unit: str, *, vertical: bool) -> None:
    """Draw each bound as a labelled line; a label names the bounds it coincides with (equal to 0.1 %)."""
    short = {"abbott_okamura": "A–O", "colgate": "C–S", "linear": "linear", "static": "2c/Δ"}
    for key, k, name in bounds:
        if k is None or not (k > 0 and np.isfinite(k)):  # None: a bound the wall does not have (the spring's)
            continue
        same = [short[o] for o, ko, _n in bounds if o != key and ko is not None and ko > 0 and abs(ko - k) <= 1e-3 * k]
        label = f"{name}: {number(k)} {unit}" + (f" (= {', '.join(same)})" if same else "")
        (ax.axvline if vertical else ax.axhline)(k, label=label, **BOUND_STYLES[key])
