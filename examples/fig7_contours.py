"""Paper Fig. 7: contour maps of the predicted amplitude and frequency of the small stable and large unstable
cycle families, μ = 5 (200 × 200 grid; --quick: 40 × 40).

Run: python examples/fig7_contours.py [--out DIR] [--quick]
"""

import os

import matplotlib

matplotlib.use("Agg")

import numpy as np

from dfa.analysis.contours import contour_maps
from dfa.render.figures import contour_plot


def main(out: str, quick: bool = False) -> dict:
    c = contour_maps(5.0, grid=40 if quick else 200)
    axes = contour_plot(c)
    path = os.path.join(out, "fig7_contours.png")
    axes[0].figure.savefig(path, dpi=130)
    both = np.isfinite(c.large_amplitude) & np.isfinite(c.large_amplitude_closed)
    rel = np.abs(c.large_amplitude[both] / c.large_amplitude_closed[both] - 1)
    res = dict(
        path=path,
        omega_closed=float(np.nanmax(c.large_frequency_closed)),
        omega_exact=(float(np.nanmin(c.large_frequency)), float(np.nanmax(c.large_frequency))),
        large_rel_median=float(np.median(rel)),
        large_rel_max=float(np.max(rel)),
        large_rel_median_big=float(np.median(rel[c.large_amplitude_closed[both] > 10]))
        if np.any(c.large_amplitude_closed[both] > 10)
        else float("nan"),
        far_count=int(np.sum(rel > 0.2)),
        far_exact_range=(
            float(np.min(c.large_amplitude[both][rel > 0.2])),
            float(np.max(c.large_amplitude[both][rel > 0.2])),
        )
        if np.any(rel > 0.2)
        else (float("nan"), float("nan")),
        small_max_sigma=float(np.max(np.meshgrid(c.beta, c.sigma)[1][np.isfinite(c.small_amplitude)])),
    )
    print(res)
    return res


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
