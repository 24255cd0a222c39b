"""Dimensionless results in physical units (issue 14 §3, issue 26 §3): the one place the conversions live.

With a device (Δ, T) and a stiffness K (paper Table 1):

* position: ξ ticks → ξ·Δ (m; rotary rad) (:func:`position`),
* speed: ξ' ticks per sample → ξ'·Δ/T (m/s; rad/s) (:func:`speed`),
* time: n samples → n·T (s) (:func:`seconds`; also a period),
* frequency: ω rad per sample → ω/(2πT) (Hz) (:func:`hertz`),
* force: φ steps of KΔ → φ·K·Δ (N; rotary N·m) (:func:`force`); one tick of motion is one force step KΔ.

Each takes a number or a numpy array; with no device (``None``: dimensionless input) each returns None, so a
record keeps the same keys, null, whether a device is known or not.

Keys carry the unit: ``amplitude_m`` / ``amplitude_rad``, ``velocity_m_s`` / ``velocity_rad_s``,
``force_*_n`` / ``force_*_nm``, ``frequency_hz``, ``period_s``. Non-finite values become None.
Columns of a trace file (:func:`trace_columns`) spell the speed's unit out: ``v_m_per_s``.

Examples
--------
>>> from dfa.model.device import Device
>>> dev = Device(mass=0.032, damping=0.02, coulomb=0.024, resolution=314e-6, period=2e-3)
>>> q = physical_quantities(dev, 80.0, amplitude=2.0, frequency=math.pi / 10)
>>> q["amplitude_m"], round(q["frequency_hz"], 6), round(q["force_amplitude_n"], 6)
(0.000628, 25.0, 0.05024)
>>> seconds(dev, 500), seconds(None, 500)
(1.0, None)
"""

from __future__ import annotations

import math
from typing import Any

from ..checks import check_positive, check_type
from .device import Device

__all__ = [
    "force",
    "hertz",
    "physical_quantities",
    "energy",
    "position",
    "seconds",
    "speed",
    "suffixes",
    "trace_columns",
    "unit_context",
]

_FIX_DEVICE = "build one with dfa.Device(...) or dfa.get_device(name).device"
_FIX_K = "give the virtual wall stiffness K in N/m"


def position(device: Device | None, ticks: Any) -> Any:
    """ξ ticks → ξ·Δ (m; rotary rad); None without a device."""
    return None if device is None or ticks is None else ticks * device.resolution


def speed(device: Device | None, xi_dot: Any) -> Any:
    """ξ' ticks per sample → ξ'·Δ/T (m/s; rotary rad/s); None without a device."""
    return None if device is None or xi_dot is None else xi_dot * device.resolution / device.period


def seconds(device: Device | None, samples: Any) -> Any:
    """n samples → n·T (s); None without a device."""
    return None if device is None or samples is None else samples * device.period


def hertz(device: Device | None, omega: Any) -> Any:
    """ω rad per sample → ω/(2πT) (Hz); None without a device."""
    return None if device is None or omega is None else omega / (2.0 * math.pi * device.period)


def force(device: Device | None, stiffness: float | None, steps: Any) -> Any:
    """φ in units of KΔ → φ·K·Δ (N; rotary N·m); None without a device."""
    if device is None or stiffness is None or steps is None:
        return None
    return steps * (stiffness * device.resolution)


def energy(device: Device | None, stiffness: float | None, value: Any) -> Any:
    """E in units of KΔ² → E·K·Δ² (J; rotary J too); None without a device."""
    if device is None or stiffness is None or value is None:
        return None
    return value * (stiffness * device.resolution**2)


def suffixes(device: Device | None) -> dict[str, str]:
    """Key suffixes of the device's units: position, velocity, force (a linear device's without one)."""
    if device is not None and device.rotary:
        return {"position": "rad", "velocity": "rad_s", "force": "nm"}
    return {"position": "m", "velocity": "m_s", "force": "n"}


def trace_columns(device: Device | None) -> dict[str, str]:
    """Column names of a trace file's physical columns (time, position, velocity, force): ``t_s``, ``x_m``,
    ``v_m_per_s``, ``force_n`` (rotary ``x_rad``, ``v_rad_per_s``, ``force_nm``)."""
    sx = suffixes(device)
    return {
        "time": "t_s",
        "position": f"x_{sx['position']}",
        "velocity": f"v_{sx['velocity'].replace('_s', '_per_s')}",
        "force": f"force_{sx['force']}",
    }


def _fin(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def _checked(device: Device | None, stiffness: float | None) -> tuple[Device | None, float | None]:
    """The device and K, checked; (None, None) without a device (dimensionless input)."""
    if device is None:
        return None, None
    dev = check_type("device", device, Device, _FIX_DEVICE)
    return dev, check_positive("stiffness", stiffness, _FIX_K)


def physical_quantities(
    device: Device | None,
    stiffness: float | None,
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
    device : Device or None
        None (dimensionless input): the same keys (a linear device's), every value None.
    stiffness : float
        K in N/m (rotary N·m/rad), > 0 (ignored without a device).
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
    dev, k = _checked(device, stiffness)
    sx = suffixes(dev)
    out: dict[str, float | None] = {}
    if amplitude is not None:
        out[f"amplitude_{sx['position']}"] = _fin(position(dev, amplitude))
        out[f"force_amplitude_{sx['force']}"] = _fin(force(dev, k, amplitude))
    if frequency is not None:
        out["frequency_hz"] = _fin(hertz(dev, frequency))
    if period is not None:
        out["period_s"] = _fin(seconds(dev, period))
    if xi_dot is not None:
        out[f"velocity_{sx['velocity']}"] = _fin(speed(dev, xi_dot))
    if force_steps is not None:
        out[f"force_peak_to_peak_{sx['force']}"] = _fin(force(dev, k, force_steps))
    return out


def unit_context(device: Device | None, stiffness: float | None, velocity: float | None = None) -> dict[str, object]:
    """What produced a physical result: the device, K, the force step KΔ, the speed, and the unit strings
    (every value None without a device)."""
    dev, k = _checked(device, stiffness)
    u = dev.units if dev is not None else None
    return ({} if dev is None else dev.hand_json()) | {
        "device": None if dev is None else dev.name,
        "rotary": None if dev is None else dev.rotary,
        "stiffness": k,
        "stiffness_unit": None if u is None else u["stiffness"],
        f"force_step_{suffixes(dev)['force']}": _fin(force(dev, k, 1.0)),
        "force_unit": None if u is None else u["force"],
        "position_unit": None if u is None else u["position"],
        "velocity": velocity,
        "velocity_unit": None if u is None else u["velocity"],
        "sample_period_s": None if dev is None else dev.period,
    }
