"""Exception types of the whole package (input checks: :mod:`dfa.checks`).

Every message names the parameter, the offending value, the rule it breaks and
how to fix it, so that the command-line tool can print it as a single line.
:class:`ImplausibleInputWarning` is the one warning about inputs: a value no
haptic device has, most likely a unit slip (:mod:`dfa.plausibility`).

Examples
--------
>>> issubclass(DFAValueError, ValueError) and issubclass(DFATypeError, TypeError)
True
>>> issubclass(DeviceFileError, DFAValueError) and issubclass(ImplausibleInputWarning, UserWarning)
True
"""

from __future__ import annotations

__all__ = ["DFAError", "DFAValueError", "DFATypeError", "DeviceFileError", "ImplausibleInputWarning"]


class DFAError(Exception):
    """Base class of every error raised on purpose by :mod:`dfa`."""


class DFAValueError(DFAError, ValueError):
    """A parameter has the right type but a value outside its rule."""


class DFATypeError(DFAError, TypeError):
    """A parameter has the wrong type (for example text where a number is needed)."""


class DeviceFileError(DFAValueError):
    """A device file (``--device-file``, :func:`dfa.load_device_file`) that cannot be used.

    Missing, not TOML, a key missing or unknown, or a value outside its rule; the message names the file and the
    key.
    """


class ImplausibleInputWarning(UserWarning):
    """A physical input no haptic device has (a resolution of 10 m, a sample period of 1 s).

    It is computed as given, but it is most likely a unit slip, which the message names
    (``resolution = 10 m ...: did you mean 10 µm = 1e-5 m?``; :mod:`dfa.plausibility`).
    """
