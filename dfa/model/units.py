"""Dimensionless results in physical units (issue 14 §3): the one place the conversions live.

With a device (Δ, T) and a stiffness K (paper Table 1):

* position: ξ ticks → ξ·Δ (m; rotary rad),
* speed: ξ' ticks per sample → ξ'·Δ/T (m/s; rad/s),
* frequency: ω rad per sample → ω/(2πT) (Hz),
* period: n samples → n·T (s),
* force: n steps of KΔ → n·K·Δ (N; rotary N·m); one tick of motion is one force step KΔ.

Keys carry the unit: ``amplitude_m`` / ``amplitude_rad``, ``velocity_m_s`` / ``velocity_rad_s``,
``force_*_n`` / ``force_*_nm``, ``frequency_hz``, ``period_s``. Non-finite values become None.

Examples
--------
>>> from dfa.model.device import Device
>>> dev = Device(mass=0.032, damping=0.02, coulomb=0.024, resolution=314e-6, period=2e-3)
>>> q = physical_quantities(dev, 80.0, amplitude=2.0, frequency=math.pi / 10)
>>> q["amplitude_m"], round(q["frequency_hz"], 6), round(q["force_amplitude_n"], 6)
(0.000628, 25.0, 0.05024)
"""

from __future__ import annotations

import math

from ..checks import check_positive, check_type
from .device import Device

__all__ = ["physical_quantities", "unit_context", "suffixes"]


def suffixes(device: Device) -> dict[str, str]:
    """Key suffixes of the device's units: position, velocity, force."""
    if device.rotary:
        return {"position": "rad", "velocity": "rad_s", "force": "nm"}
    return {"position": "m", "velocity": "m_s", "force": "n"}


def _fin(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def physical_quantities(
    device: Device,
    stiffness: float,
    *,
    amplitude: float | None = None,
    frequency: float | None = None,
    period: float | None = None,
    xi_dot: float | None = None,
    force_steps: float | None = None,
) -> dict[str, float | None]:
    """Physical values of the dimensionless ones given (module docstring); keys only for those given.

    Parameters
    ----------
    device : Device
    stiffness : float
        K in N/m (rotary N·m/rad), > 0.
    amplitude : float, optional
        Position amplitude in ticks → ``amplitude_<pos>`` and ``force_amplitude_<force>`` (amplitude × KΔ).
    frequency : float, optional
        Angular frequency in rad per sample → ``frequency_hz``.
    period : float, optional
        Period in samples → ``period_s``.
    xi_dot : float, optional
        Speed in ticks per sample → ``velocity_<vel>``.
    force_steps : float, optional
        A force in units of KΔ (e.g. a peak-to-peak) → ``force_peak_to_peak_<force>``.
    """
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
    sx = suffixes(dev)
    step = k * dev.resolution
    out: dict[str, float | None] = {}
    if amplitude is not None:
        out[f"amplitude_{sx['position']}"] = _fin(amplitude * dev.resolution)
        out[f"force_amplitude_{sx['force']}"] = _fin(amplitude * step)
    if frequency is not None:
        out["frequency_hz"] = _fin(frequency / (2.0 * math.pi * dev.period))
    if period is not None:
        out["period_s"] = _fin(period * dev.period)
    if xi_dot is not None:
        out[f"velocity_{sx['velocity']}"] = _fin(xi_dot * dev.resolution / dev.period)
    if force_steps is not None:
        out[f"force_peak_to_peak_{sx['force']}"] = _fin(force_steps * step)
    return out


def unit_context(device: Device, stiffness: float, velocity: float | None = None) -> dict[str, object]:
    """What produced a physical result: the device, K, the force step KΔ, the speed, and the unit strings."""
    dev = check_type("device", device, Device, "build one with dfa.Device(...) or dfa.get_device(name).device")
    k = check_positive("stiffness", stiffness, "give the virtual wall stiffness K in N/m")
    u = dev.units
    return {
        "device": dev.name,
        "rotary": dev.rotary,
        "stiffness": k,
        "stiffness_unit": u["stiffness"],
        f"force_step_{suffixes(dev)['force']}": k * dev.resolution,
        "force_unit": u["force"],
        "position_unit": u["position"],
        "velocity": velocity,
        "velocity_unit": u["velocity"],
        "sample_period_s": dev.period,
    }
