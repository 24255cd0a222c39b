"""Nyquist view of the harmonic balance (paper Fig. 6): the loop against −1/D(M), limit cycles marked.

Run: python examples/nyquist.py [--out DIR]
"""

import os

import matplotlib

matplotlib.use("Agg")

import dfa
from dfa.analysis.cycles import limit_cycles
from dfa.analysis.loop import nyquist_locus_response
from dfa.render.figures import nyquist_plot


def main(out: str, quick: bool = False) -> dict:
    p = dfa.Params(mu=2.0, beta=0.4, sigma=0.1)
    res = limit_cycles(p)
    ny = nyquist_locus_response(p, amplitudes=[c.amplitude for c in res.cycles[:3]], cycles=res)
    ax = nyquist_plot(ny)
    path = os.path.join(out, "nyquist.png")
    ax.figure.savefig(path, dpi=130)
    for c in res.cycles:
        print(f"M = {c.amplitude:.4g} ticks, ω = {c.frequency:.4g} rad/sample, {'stable' if c.stable else 'unstable'}")
    return dict(path=path, cycles=[(c.amplitude, c.frequency, c.stable) for c in res.cycles])


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
