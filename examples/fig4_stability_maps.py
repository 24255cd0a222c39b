"""Paper Fig. 4: simulated stability over the (β, σ) plane for μ = 100 and ξ'0 = 1, 2, 5, 10.

White: came to rest; light: persisting oscillation (lightest: chatter below one tick; darker: oscillating);
dark: unstable; orange: undecided (50 000 samples too short to tell). The conservatism is measured against the
points that come to rest.

5·10⁴ samples per run (50 s at 1 kHz), 100 × 100 grid (the paper's resolution); --quick: 20 × 20, 5000 samples.
Run: python examples/fig4_stability_maps.py [--out DIR] [--quick]
"""

import os

import matplotlib

matplotlib.use("Agg")

import numpy as np

import dfa
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import OUTCOMES
from dfa.render.figures import stability_map_plot

SPEEDS = (1.0, 2.0, 5.0, 10.0)


def main(out: str, quick: bool = False) -> dict:
    grid, samples = (20, 5000) if quick else (100, 50_000)
    m = stability_map(100.0, SPEEDS, grid=grid, samples=samples, progress=not quick)
    axes = stability_map_plot(m)
    path = os.path.join(out, "fig4_stability_maps.png")
    axes[0].figure.savefig(path, dpi=130)
    m.save(os.path.join(out, "fig4_stability_maps.npz"))
    # criterion vs simulation on this map
    viol = 0
    rejected = 0
    rest = 0
    for k, v in enumerate(m.xi_dots):
        reg = dfa.classify_region(m.beta[None, :], m.sigma[:, None], v)
        passive = (reg == "a") | (reg == "e")
        viol += int(np.sum(passive & (m.outcome[k] == OUTCOMES.index("unstable"))))
        at_rest = m.outcome[k] == OUTCOMES.index("rest")
        rest += int(at_rest.sum())
        rejected += int(np.sum(at_rest & ~passive))
    print(f"wrote {path}; counts {m.counts()}; criterion-passive points found unstable: {viol}")
    return dict(
        path=path, counts=m.counts(), violations=viol, conservatism=rejected / max(1, rest), grid=grid, samples=samples
    )


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
