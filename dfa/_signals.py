"""Signals that arrive while threads are started, waited for or joined: raised where raising is safe.

Python runs a signal handler in the main thread between two bytecodes, wherever the thread is. A handler that
raises (Ctrl-C's ``KeyboardInterrupt``, the command line's ``Interrupted``) inside the threading module's own
code, e.g. in ``Condition.wait`` after it released its lock and before it waits, leaves that lock in a wrong
state: ``RuntimeError: release unlocked lock`` from ``ThreadPoolExecutor.submit``, a traceback instead of the
interruption (issue 41). Code that starts, waits for or joins threads, or creates a progress bar (tqdm starts
a monitor thread), runs inside :func:`deferred`: a signal there is recorded by :func:`interrupt` and raised by
:func:`check` (called between waits) or when the block ends, from dfa's own code.

Ctrl-C in a program that kept Python's default SIGINT handler is deferred too: inside the block SIGINT's
handler records a ``KeyboardInterrupt``, and the default handler is back when the block ends. Only the main
thread receives signals; in any other thread :func:`deferred` does nothing.

Examples
--------
>>> try:
...     with deferred():
...         interrupt(KeyboardInterrupt("late"))  # a signal handler's exception: recorded, not raised here
...         print("the block goes on")
... except KeyboardInterrupt as exc:
...     print("raised when the block ends:", exc)
the block goes on
raised when the block ends: late
"""

from __future__ import annotations

import signal
import threading
from typing import Any

__all__ = ["check", "deferred", "interrupt"]

#: How deep the main thread is in :func:`deferred` blocks, and the interruption recorded there (or None).
_STATE: dict[str, Any] = {"depth": 0, "pending": None}


def _main() -> bool:
    return threading.current_thread() is threading.main_thread()


def interrupt(exc: BaseException) -> None:
    """Raise ``exc`` (from a signal handler) now, or record it when the main thread is inside :func:`deferred`.

    Parameters
    ----------
    exc : BaseException
        The interruption (``KeyboardInterrupt`` or a subclass). Only the first one recorded is kept.
    """
    if _STATE["depth"] > 0 and _main():
        if _STATE["pending"] is None:
            _STATE["pending"] = exc
        return
    raise exc


def check() -> None:
    """Raise the interruption recorded inside :func:`deferred` (a point where raising is safe), if any."""
    exc = _STATE["pending"]
    if exc is not None and _main():
        _STATE["pending"] = None
        raise exc


def _record_sigint(signum: int, frame: object) -> None:
    """SIGINT's handler inside :func:`deferred` in place of Python's default one."""
    interrupt(KeyboardInterrupt())


class deferred:  # a context manager, named like contextlib's
    """Context manager: in the main thread, signals that would raise are recorded and raised at the block's end.

    Inside the block call :func:`check` wherever an interruption may be raised (between waits). Blocks nest; the
    outermost one raises what is still recorded when it ends. When the block ends with an exception, that
    exception propagates; a recorded interruption is raised from it unless it is itself a ``KeyboardInterrupt``
    (one interruption, one exception).
    """

    def __enter__(self) -> deferred:
        self._active = _main()
        if not self._active:
            return self
        self._own = _STATE["depth"] == 0 and signal.getsignal(signal.SIGINT) is signal.default_int_handler
        _STATE["depth"] += 1
        try:
            if self._own:
                signal.signal(signal.SIGINT, _record_sigint)
        except BaseException:
            _STATE["depth"] -= 1
            raise
        return self

    def __exit__(self, kind: object, err: BaseException | None, tb: object) -> None:
        if not self._active:
            return
        try:
            if self._own and signal.getsignal(signal.SIGINT) is _record_sigint:
                signal.signal(signal.SIGINT, signal.default_int_handler)
        finally:
            _STATE["depth"] -= 1
        if _STATE["depth"] > 0:
            return
        if isinstance(err, KeyboardInterrupt):
            _STATE["pending"] = None  # already interrupted: one interruption, one exception
            return
        check()  # raised from dfa's code; a failure propagating becomes its __context__
