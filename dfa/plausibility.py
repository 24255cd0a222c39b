"""Plausibility of physical inputs: a value no haptic device has warns once, naming the value and the likely slip.

Such a value is not refused (dfa computes what it is given, and a bench rig may be odd), but it is most likely a
unit slip: ``--resolution 10`` meant 10 µm, ``--period 1`` meant 1 ms. One rule, :data:`RANGES`, and one message,
:func:`implausible`, serve the API and the command line:

- the model warns (:class:`~dfa.errors.ImplausibleInputWarning`) for values that come from outside the package
  (a script, a notebook, a test), directly or through one public function (``dfa.k_max_criterion(dev, 100.0)``):
  :class:`~dfa.model.device.Device` (mass, resolution, period), :meth:`Device.params
  <dfa.model.device.Device.params>` and :class:`~dfa.model.wall.Wall` (the stiffness), :meth:`Device.xi_dot
  <dfa.model.device.Device.xi_dot>` (the impact speed), and the device files; the values dfa derives itself
  (searches over K, grids of speeds) never warn (:func:`warn_if_from_outside`);
- the command line warns itself, naming the flag or the device file's key the value came from.

==========  =================  ================  ===========================
quantity    linear             rotary            the likely slip (examples)
==========  =================  ================  ===========================
resolution  1 nm to 1 mm       1 nrad to 0.1 rad µm or mm for m; mrad for rad
period      up to 0.1 s        up to 0.1 s       ms or µs for s
velocity    up to 10 m/s       up to 100 rad/s   mm/s or cm/s; °/s
stiffness   up to 1e7 N/m      up to 1e5 N·m/rad a factor 1000 too many
mass        up to 100 kg       up to 1 kg·m²     g for kg; g·cm² for kg·m²
force       up to 1000 N       up to 100 N·m     mN for N; N·mm for N·m (a push)
==========  =================  ================  ===========================

Examples
--------
>>> implausible("resolution", 10.0, subject="--resolution")
'--resolution 10 is above 0.001 m, which no haptic device has: did you mean 10 µm = 1e-5 m?'
>>> implausible("period", 1.0)
'period = 1 s is above 0.1 s, which no haptic device has: did you mean 1 ms = 0.001 s?'
>>> implausible("resolution", 30e-6) is None
True
"""

from __future__ import annotations

import math
import sys
import warnings
from dataclasses import dataclass
from types import FrameType

from .errors import ImplausibleInputWarning

__all__ = ["RANGES", "Range", "implausible", "warn_implausible", "warn_if_from_outside"]


@dataclass(frozen=True)
class Range:
    """Where a quantity of a haptic device lies, and the slips that put it outside.

    Attributes
    ----------
    low, high : float or None
        The plausible range (None: no bound on that side).
    unit : str
        The SI unit the value is in.
    slips : tuple of (str, float)
        For a value above ``high``: (the unit it was probably written in, its factor to ``unit``), likeliest
        first (the first that lands in the range is named); an empty unit means "a factor too many".
    low_slips : tuple of (str, float)
        The same for a value below ``low``.
    """

    low: float | None
    high: float | None
    unit: str
    slips: tuple[tuple[str, float], ...] = ()
    low_slips: tuple[tuple[str, float], ...] = ()


_PERIOD = Range(None, 0.1, "s", (("ms", 1e-3), ("µs", 1e-6)))

#: The plausible ranges: (quantity, rotary) -> :class:`Range` (module docstring).
RANGES: dict[tuple[str, bool], Range] = {
    ("resolution", False): Range(1e-9, 1e-3, "m", (("mm", 1e-3), ("µm", 1e-6), ("nm", 1e-9)), (("", 1e6), ("", 1e3))),
    ("resolution", True): Range(1e-9, 0.1, "rad", (("mrad", 1e-3), ("µrad", 1e-6)), (("", 1e6), ("", 1e3))),
    ("period", False): _PERIOD,
    ("period", True): _PERIOD,
    ("velocity", False): Range(None, 10.0, "m/s", (("mm/s", 1e-3), ("cm/s", 1e-2))),
    ("velocity", True): Range(None, 100.0, "rad/s", (("°/s", math.pi / 180.0), ("mrad/s", 1e-3))),
    ("stiffness", False): Range(None, 1e7, "N/m", (("", 1e-3),)),
    ("stiffness", True): Range(None, 1e5, "N·m/rad", (("", 1e-3),)),
    ("mass", False): Range(None, 100.0, "kg", (("g", 1e-3),)),
    ("mass", True): Range(None, 1.0, "kg·m²", (("g·cm²", 1e-7), ("kg·cm²", 1e-4))),
    ("force", False): Range(None, 1000.0, "N", (("mN", 1e-3),)),
    ("force", True): Range(None, 100.0, "N·m", (("N·mm", 1e-3),)),
}  # fmt: skip


def _num(x: float) -> str:
    """A number as people write it: 4 significant digits, ``1e-5`` rather than ``1e-05``."""
    text = f"{x:.4g}"
    if "e" in text:
        mant, exp = text.split("e")
        text = f"{mant}e{int(exp)}"
    return text


def implausible(
    quantity: str, value: float, *, rotary: bool = False, subject: str | None = None, hint: str | None = None
) -> str | None:
    """The warning for ``value`` of ``quantity`` when no haptic device has it (:data:`RANGES`), else None.

    Parameters
    ----------
    quantity : str
        ``"resolution"``, ``"period"``, ``"velocity"`` (the impact speed's magnitude), ``"stiffness"``, ``"mass"``
        or ``"force"`` (an operator's push).
    value : float
        The value in SI units (rotary: rad, N·m, kg·m²); a speed's sign is ignored.
    rotary : bool, optional
        Rotary units and ranges.
    subject : str, optional
        How the message names the input: a flag (``"--resolution"``: ``--resolution 10``) or a name
        (``"my.toml: resolution"``: ``my.toml: resolution = 10 m``); default the quantity's name.
    hint : str, optional
        What to check, instead of the likely slip (for a value derived from another input: ``--counts``).

    Returns
    -------
    str or None
        One line: the input, the bound it passes, and the likely slip.
    """
    rng = RANGES[(quantity, bool(rotary))]
    try:
        v = abs(float(value))
    except (TypeError, ValueError):
        return None  # not a number: the value's own check refuses it
    if not math.isfinite(v) or v == 0.0:
        return None
    high = rng.high is not None and v > rng.high
    low = rng.low is not None and v < rng.low
    if not (high or low):
        return None
    name = subject or quantity
    subj = f"{name} {_num(v)}" if name.startswith("--") and " " not in name else f"{name} = {_num(v)} {rng.unit}"
    bound = rng.high if high else rng.low
    assert bound is not None
    text = f"{subj} is {'above' if high else 'below'} {_num(bound)} {rng.unit}, which no haptic device has"
    if hint is not None:
        return f"{text}: {hint}"
    fits = [
        (label, f)
        for label, f in (rng.slips if high else rng.low_slips)
        if (rng.low is None or v * f >= rng.low) and (rng.high is None or v * f <= rng.high)
    ]
    if not fits:
        return f"{text}: check its unit (dfa takes {rng.unit})"
    label, f = fits[0]
    meant = f"{_num(v)} {label} = {_num(v * f)} {rng.unit}" if label else f"{_num(v * f)} {rng.unit}"
    return f"{text}: did you mean {meant}?"


def warn_implausible(
    quantity: str,
    value: float,
    *,
    rotary: bool = False,
    subject: str | None = None,
    hint: str | None = None,
    stacklevel: int = 2,
) -> str | None:
    """Warn (:class:`~dfa.errors.ImplausibleInputWarning`) with :func:`implausible`'s message, if any; return it."""
    text = implausible(quantity, value, rotary=rotary, subject=subject, hint=hint)
    if text is not None:
        warnings.warn(text, ImplausibleInputWarning, stacklevel=stacklevel + 1)
    return text


#: Modules a value passes through between the caller and the model without being "inside" dfa.
_PASS_THROUGH = ("dataclasses", "copy", "functools")
#: The wrapper of :func:`dfa.model.loop.loop_first` (an analysis called with its former first arguments): it
#: passes the user's values through, like :data:`_PASS_THROUGH`.
_LOOP_WRAPPER = ("dfa.model.loop", "loop_first_wrapper")


def _in_dfa(frame: FrameType) -> bool:
    module = str(frame.f_globals.get("__name__", ""))
    return module == "dfa" or module.startswith("dfa.")


def _outside_level() -> int | None:
    """The stacklevel (for :func:`warnings.warn` in the caller's caller) of the code that gave the value, when
    that code is outside dfa; None when the value is dfa's own.

    Frames of :mod:`dfa.model` (a constructor, its ``__post_init__``, a factory such as ``Wall.of``) and of
    :data:`_PASS_THROUGH` are skipped. Then either the code outside dfa is reached (a script called the model),
    or one public function of dfa called directly from outside (``dfa.k_max_criterion(dev, 100.0)``: the speed is
    the user's); anything deeper (a search over K, a grid of speeds, the command line) is dfa's own.
    """
    frame: FrameType | None = sys._getframe(2)  # the caller of warn_if_from_outside
    level = 1
    entry = False
    while frame is not None:
        module = str(frame.f_globals.get("__name__", ""))
        if (
            module.startswith("dfa.model.")
            and not entry
            or module in _PASS_THROUGH
            or (module, frame.f_code.co_name) == _LOOP_WRAPPER
        ):
            pass
        elif not _in_dfa(frame):
            return level
        elif entry or frame.f_code.co_name.startswith("_"):
            return None  # a second frame of dfa, or a private function: the value is dfa's own
        else:
            entry = True  # a public function of dfa: the value is the user's if its caller is outside dfa
        frame = frame.f_back
        level += 1
    return None


def warn_if_from_outside(quantity: str, value: float, *, rotary: bool = False) -> str | None:
    """:func:`warn_implausible` for a value given to the model by code outside dfa; silent for dfa's own values.

    The warning points at the first line outside the model (the user's ``Device(...)`` or ``dev.params(K)``).
    """
    if implausible(quantity, value, rotary=rotary) is None:  # cheap: the frames are looked at only when needed
        return None
    level = _outside_level()
    if level is None:
        return None
    return warn_implausible(quantity, value, rotary=rotary, stacklevel=level + 1)
