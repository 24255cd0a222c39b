"""Coverage of `dfa identify`'s 95 % intervals under noise on the force column (issue 45 a).

Synthetic logs of a known device (the exact simulator, `synthetic_log`), a square-plus-sine force that reverses,
Gaussian noise on the logged force of a standard deviation relative to the force's; each seed a fresh noise draw.
For each: the estimates' errors, whether each 95 % interval holds the truth, the estimated noise level against the
one drawn, the status. Run: ``python benchmarks/identify_noise_coverage.py [--seeds 50] [--bootstrap 10]``; the
result committed is ``reports/identify_noise_coverage.md``.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import dfa
from dfa.analysis.identify import identify, synthetic_log


def excited(samples: int):
    """The device of tests/test_identify_log.py's `_excited(0.2, 1e-5, 1e-3, 5.0, 80.0)` and its force."""
    c, delta, period, ticks, tau = 0.2, 1e-5, 1e-3, 5.0, 80.0
    b = c / (ticks * delta / period)
    dev = dfa.Device(tau * b * period, b, c, delta, period)
    f1 = 1.0 / (6.0 * tau * period)
    t = np.arange(samples) * period
    return dev, 3.0 * c * np.sign(np.sin(2 * np.pi * f1 * t)) + 1.5 * c * np.sin(2 * np.pi * 3.3 * f1 * t)


def study(samples: int, relative: float, seeds: int, bootstrap: int) -> dict:
    dev, force = excited(samples)
    keys = ("mass", "damping", "coulomb")
    covered = {k: 0 for k in keys}
    worst = {k: 0.0 for k in keys}
    noise, status, t0 = [], [], time.time()
    for seed in range(seeds):
        r = identify(synthetic_log(dev, force, force_noise=relative * np.std(force), seed=seed), bootstrap=bootstrap)
        status.append(r.status.value)
        noise.append(r.force_noise_relative)
        for k in keys:
            e, true = getattr(r, k), getattr(dev, k)
            worst[k] = max(worst[k], abs(e.value / true - 1.0))
            covered[k] += e.low is not None and e.low <= true <= e.high
    return {"samples": samples, "noise": relative, "seeds": seeds, "bootstrap": bootstrap, "covered": covered,
            "worst": worst, "noise_est": (float(np.mean(noise)), float(np.std(noise))),
            "status": {s: status.count(s) for s in sorted(set(status))}, "seconds": time.time() - t0}  # fmt: skip


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--seeds", type=int, default=50)
    p.add_argument("--bootstrap", type=int, default=10)
    p.add_argument("--out", default=None)
    a = p.parse_args()
    rows = []
    for samples, rel in ((4000, 0.02), (12000, 0.05), (12000, 0.01), (4000, 0.0)):
        d = study(samples, rel, a.seeds if rel > 0 else 1, a.bootstrap)
        cov = ", ".join(f"{k} {v}/{d['seeds']}" for k, v in d["covered"].items())
        err = ", ".join(f"{k} {100 * v:.2f} %" for k, v in d["worst"].items())
        m, s = d["noise_est"]
        rows.append(f"| {samples} | {100 * rel:g} % | {100 * m:.2f} ± {100 * s:.2f} % | {cov} | {err} | "
                    f"{d['status']} | {d['seconds']:.0f} s |")  # fmt: skip
        print(rows[-1], flush=True)
    text = (
        "# Coverage of dfa identify's 95 % intervals under force noise (issue 45 a)\n\n"
        f"`python benchmarks/identify_noise_coverage.py --seeds {a.seeds} --bootstrap {a.bootstrap}`: the device "
        "m = 0.32 kg, b = 4 N·s/m, c = 0.2 N, Δ = 10 µm, T = 1 ms driven by a square-plus-sine force that "
        "reverses; Gaussian noise on the logged force (standard deviation relative to the force's), one draw per "
        "seed. Covered: how many of the 95 % intervals hold the true value; worst error: the largest |estimate/true "
        "− 1| over the seeds; noise estimated: mean ± standard deviation of `force_noise_relative`.\n\n"
        "| samples | force noise | noise estimated | covered | worst error | status | time |\n"
        "|---|---|---|---|---|---|---|\n" + "\n".join(rows) + "\n"
    )
    if a.out:
        with open(a.out, "w", encoding="utf-8") as fh:
            fh.write(text)


if __name__ == "__main__":
    main()
