"""Choose the virtual wall stiffness K of a device for a given impact speed, and check it by simulation.

Device: the Phantom 1.0 of paper Table 2 with Δ = 29 µm (the value its printed σ implies); impact speed 0.1 m/s.
Run: python examples/design_stiffness.py [--out DIR]
"""

import os

import matplotlib

matplotlib.use("Agg")

import dfa
from dfa.analysis.limits.closed_form import stiffness_response
from dfa.analysis.simulation import simulate
from dfa.render.figures import stiffness_plot


def main(out: str, quick: bool = False) -> dict:
    e = dfa.get_device("Phantom")
    dev = dfa.Device(e.mass, e.damping, e.coulomb, 29e-6, e.period, name="Phantom 1.0 (Δ = 29 µm)")
    v = 0.1
    lim = dfa.stiffness_limits(dev, v)
    k = 0.8 * lim.k_max  # keep a 20 % margin below the criterion's limit
    check = dfa.device_criterion(dev, k, v)
    p = dev.params(k)
    sim = simulate(p.mu, p.beta, p.sigma, dev.xi_dot(v), 50_000, record=False)
    ax = stiffness_plot(stiffness_response(dev, stiffness=k))
    path = os.path.join(out, "design_stiffness.png")
    ax.figure.savefig(path, dpi=130)
    print(
        f"K_max({v} m/s) = {lim.k_max:.4g} N/m; chosen K = {k:.4g} N/m: region {check.region}, passive up to "
        f"{check.critical_velocity:.3g} m/s; simulated impact at {v} m/s: {sim.outcome}"
    )
    return dict(
        path=path,
        k_max=lim.k_max,
        k=k,
        region=check.region,
        critical_velocity=check.critical_velocity,
        outcome=sim.outcome,
    )


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
