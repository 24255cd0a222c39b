"""Write the example logs of ``examples/logs/``: synthetic runs of catalogue devices (paper Table 2) to identify.

Each log is made by the exact simulator (:func:`dfa.analysis.identify.synthetic_log`,
:func:`dfa.analysis.identify.impact_log`): it is synthetic, not measured. Two carry measurement-like
imperfections: a force offset the log does not show, and noise on the force column.

- ``delta_chirp.csv``: the Delta driven by a chirp of 3 N from 1 to 40 Hz for 1 s, with a 0.05 N offset and
  0.01 N of noise on the logged force;
- ``impulse_pulses.csv``: the Impulse Engine driven by force pulses of ±0.08 N, 4 s, 0.0005 N of force noise;
- ``phantom_impact.csv``: an impact of the Phantom 1.0 on its catalogue wall at 0.1 m/s (the force column is the
  wall's force), 2 s;
- ``limit_cycle.csv``: an impact at 0.012 m/s of a light device (10 g, 0.4 N·s/m, 1 mN of friction, 10 µm, 1 ms)
  on a wall of 1000 N/m (μ = 10, β = 0.4, σ = 0.1) that ends in a sustained limit cycle of 2.5 ticks at 50 Hz,
  6 s: ``dfa identify examples/logs/limit_cycle.csv --stiffness 1000``.

Run: python examples/make_logs.py (``tests/test_identify_log.py`` checks that the committed files are what this
writes, by value to the 12 digits written: another CPU's last bit can flip a written 12th digit; and that
identifying them gives the catalogue's values back). The noise seed of ``impulse_pulses.csv`` is chosen so that
what ``dfa identify`` prints of it in docs/cli.md lies far from a rounding boundary of its printed digits (at
least 20 times the spread of 11 fits with the forces moved by their last bit): the example prints the same
numbers on every machine.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import dfa
from dfa.analysis.identify import impact_log, synthetic_log
from dfa.model.log import DeviceLog, write_log

LOGS = Path(__file__).resolve().parent / "logs"
#: The wall and device of ``limit_cycle.csv`` (μ = 10, β = 0.4, σ = 0.1 at T = 1 ms, Δ = 10 µm).
CYCLE_K = 1000.0
CYCLE_DEVICE = dfa.Device(0.01, 0.4, 0.001, 1e-5, 1e-3, name="light device")


def example_logs() -> dict[str, DeviceLog]:
    """The example logs by file name (deterministic: fixed seeds)."""
    delta = dfa.get_device("delta").device
    t = np.arange(3000) * delta.period
    chirp = 3.0 * np.sin(2 * np.pi * np.geomspace(1.0, 40.0, t.size) * t)
    impulse = dfa.get_device("impulse").device
    t2 = np.arange(2000) * impulse.period
    pulses = 0.08 * np.sign(np.sin(2 * np.pi * 1.5 * t2)) * (np.sin(2 * np.pi * 0.5 * t2) > -0.5)
    phantom = dfa.get_device("phantom")
    return {
        "delta_chirp.csv": synthetic_log(delta, chirp, force_offset=0.05, force_noise=0.01, seed=1,
                                         source="delta_chirp.csv"),
        "impulse_pulses.csv": synthetic_log(impulse, pulses, force_noise=5e-4, seed=22, source="impulse_pulses.csv"),
        "phantom_impact.csv": impact_log(phantom.device, phantom.stiffness, 0.1, 2000, source="phantom_impact.csv"),
        "limit_cycle.csv": impact_log(CYCLE_DEVICE, CYCLE_K, 0.012, 6000, source="limit_cycle.csv"),
    }  # fmt: skip


def main() -> None:
    """Write every example log."""
    LOGS.mkdir(exist_ok=True)
    for name, log in example_logs().items():
        print("written", write_log(log, LOGS / name))


if __name__ == "__main__":
    main()
