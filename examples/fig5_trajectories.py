"""Paper Fig. 5: three operating points of the RE35 testbed, each as its (β, σ) point with the critical
line (left) and the simulated displacement in ticks with ±1 tick marked (right).

Chosen points (the paper's values are illegible in the available copy):
 1. globally stable (region a): K = 0.1 N·m/rad, encoder coarsened to Δ = 0.133 rad (σ = 1.5), impact 5 ticks/sample;
 2. limit-cycle region b with a very coarse encoder: K = 0.1 N·m/rad, Δ = 0.667 rad (σ = 0.3);
 3. locally stable region e at reduced initial energy: K = 1 N·m/rad, encoder coarsened ×8, spring
    preload equivalent to 4 ticks/sample (below the critical speed).
Run: python examples/fig5_trajectories.py [--out DIR]
"""

import os
import warnings

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt
from matplotlib.lines import Line2D
from matplotlib.patches import Patch

import dfa
from dfa.analysis.criterion import REGION_DESCRIPTIONS
from dfa.analysis.simulation import preload_position, simulate
from dfa.render.figures import POINT_STYLE, REGION_COLORS, regions_plot, trajectory_plot


def cases():
    # deliberately coarse encoders (0.13 and 0.67 rad) that place the paper's cases in each region: the
    # plausibility warning (no haptic device has them) is expected here
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", dfa.ImplausibleInputWarning)
        return _cases()


def _cases():
    re35 = dfa.get_device("RE35").device
    fine = re35.resolution
    return [
        (
            "globally stable (a)",
            dfa.Device(re35.mass, re35.damping, re35.coulomb, 0.02 / (0.1 * 1.5), re35.period, "RE35 coarse", True),
            0.1,
            5.0,
            False,
        ),
        (
            "limit cycle, coarse encoder (b)",
            dfa.Device(re35.mass, re35.damping, re35.coulomb, 0.02 / (0.1 * 0.3), re35.period, "RE35 coarse", True),
            0.1,
            1.0,
            False,
        ),
        (
            "locally stable, reduced energy (e)",
            dfa.Device(re35.mass, re35.damping, re35.coulomb, 8 * fine, re35.period, "RE35 ×8", True),
            1.0,
            4.0,
            True,
        ),
    ]


def main(out: str, quick: bool = False) -> dict:
    n = 2000 if quick else 6000
    fig, axs = plt.subplots(3, 2, figsize=(11, 10), constrained_layout=True, gridspec_kw={"width_ratios": [1, 1.6]})
    results = []
    for row, (label, dev, k, xd, preload) in enumerate(cases()):
        p = dev.params(k)
        crit = dfa.passivity_criterion(p.beta, p.sigma, xd)
        regions_plot(
            crit,
            ax=axs[row, 0],
            beta_max=max(1.0, 1.2 * p.beta),
            sigma_max=min(max(2.0, 1.2 * p.sigma), 10.0),
            legend=False,
        )
        axs[row, 0].set_title(f"{label}: β = {p.beta:.3g}, σ = {p.sigma:.3g}, μ = {p.mu:.3g}", fontsize=8)
        if preload:
            r = simulate(p.mu, p.beta, p.sigma, 0.0, n, xi0=preload_position(p.mu, xd))
        else:
            r = simulate(p.mu, p.beta, p.sigma, xd, n)
        persistent = r.rest_sample is None and 0 < r.amplitude < 0.5  # a sub-tick cycle: its start, and an inset
        # a run that comes to rest is shown up to about four times its settling time, so that its motion fills the axis
        trajectory_plot(r, ax=axs[row, 1], device=dev, max_samples=n // 6 if persistent else None)
        start = f"preload ≡ {xd:g} ticks/sample" if preload else f"ξ'0 = {xd:g} ticks/sample"
        axs[row, 1].set_title(
            f"{label}, K = {k:g} N·m/rad, {start}: {r.outcome}, amplitude {r.amplitude:.2g} ticks", fontsize=8
        )
        if persistent:  # zoom on the tail of the whole run
            ins = axs[row, 1].inset_axes([0.55, 0.56, 0.42, 0.36])
            tail = slice(n - 60, n + 1)
            ins.plot(range(n - 60, n + 1), r.xi[tail], ".-", lw=0.8, ms=3, color="#2166ac")
            ins.set_title(f"last 60 samples of the {n * dev.period:g} s run", fontsize=7)
            ins.set_xlabel("time (samples)", fontsize=6)
            ins.set_ylabel("ξ (ticks)", fontsize=6)
            ins.tick_params(labelsize=6)
        results.append(
            dict(
                label=label,
                region=crit.region,
                passive=crit.passive,
                outcome=r.outcome,
                amplitude=r.amplitude,
                frequency=r.frequency,
                beta=p.beta,
                sigma=p.sigma,
                mu=p.mu,
            )
        )
    handles = [
        Patch(facecolor=REGION_COLORS[k], edgecolor="0.5", label=f"{k}: {REGION_DESCRIPTIONS[k].split(':')[0]}")
        for k in "abcde"
    ]
    handles += [
        Line2D([], [], color="k", ls="--", label="critical line at the impact speed"),
        Line2D([], [], label="operating point", **POINT_STYLE),
        Line2D([], [], color="0.4", ls="--", lw=0.8, label="±1 tick"),
    ]
    fig.legend(handles=handles, loc="outside lower center", ncol=4, fontsize=9)
    path = os.path.join(out, "fig5_trajectories.png")
    fig.savefig(path, dpi=120)
    for r in results:
        print(r)
    return dict(path=path, cases=results)


if __name__ == "__main__":
    from _common import parse

    a = parse(__doc__)
    main(a.out, a.quick)
