"""Paper Fig. 3: regions a-e of the (β, σ) plane and the critical lines of eq. 10.

Run: python examples/fig3_regions.py [--out DIR]
"""

import os

import matplotlib

matplotlib.use("Agg")

import dfa
from dfa.render.figures import regions_plot


def main(out: str, quick: bool = False) -> dict:
    r = dfa.passivity_criterion(beta=0.25, sigma=1.2, xi_dot=2.0)
    ax = regions_plot(r, xi_dots=[0.5, 1.0, 5.0])
    path = os.path.join(out, "fig3_regions.png")
    ax.figure.savefig(path, dpi=130)
    print(
        f"operating point β = 0.25, σ = 1.2 at ξ'0 = 2: region {r.region}, critical speed {r.critical_xi_dot:.3g}; wrote {path}"
    )
    return dict(path=path, region=r.region, critical=r.critical_xi_dot)


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
