"""The one line a terminal shows when a command compiles kernels: "compiling kernels once (about N s)".

numba compiles a kernel the first time it is called and keeps it in the cache folder (:mod:`dfa.core.cache`);
later runs load it in a fraction of a second. The first run of a command on a fresh cache would otherwise wait
in silence for up to a minute. :func:`compile_note` listens to numba's ``numba:compile`` event, which numba
fires only when it really compiles (a kernel loaded from the cache fires none), and prints the line once, on
stderr, when stderr is a terminal and the first kernel of :mod:`dfa.core` starts compiling: nothing when
everything is cached, nothing in a pipe, a file or a test.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from collections.abc import Iterator
from typing import Any, TextIO

__all__ = ["FIRST_RUN_SECONDS", "compile_note", "note_text"]

#: Seconds each command's first run spends compiling on a fresh cache (its example of ``dfa COMMAND --help``:
#: first run less a second one, measured on 2 cores on 2026-11-27, rounded); a command not listed says "up to a few minutes". Commands that compile
#: nothing (devices, params, check, contours) never print the note.
FIRST_RUN_SECONDS = {
    "stiffness": 25,
    "simulate": 6,
    "map": 12,
    "limit-cycles": 3,
    "require": 1,
    "report": 15,
    "zwidth": 30,
    "validate": 40,
    "identify": 5,  # 3 before its fit's Jacobian and normal equations were compiled (2026-12-07: +1.6 s CPU)
}


def note_text(command: str | None, cache_dir: str) -> str:
    """The line printed when ``command`` starts compiling kernels into ``cache_dir``.

    Examples
    --------
    >>> note_text("stiffness", os.path.expanduser("~/.cache/dfa/numba/0123456789abcdef"))
    'dfa: compiling kernels once (about 25 s), cached in ~/.cache/dfa/numba/0123456789abcdef'
    """
    seconds = FIRST_RUN_SECONDS.get(command or "")
    about = f"about {seconds} s" if seconds else "up to a few minutes"
    home = os.path.expanduser("~")
    where = (
        "~" + cache_dir[len(home) :]
        if home not in ("", "~", os.sep) and cache_dir.startswith(home + os.sep)
        else cache_dir
    )
    line = f"dfa: compiling kernels once ({about}), cached in {where}"
    return line if len(line) <= 100 else f"dfa: compiling kernels once ({about}); later runs load them"


def _is_terminal(stream: TextIO) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):  # no stream, or a closed one
        return False


@contextlib.contextmanager
def compile_note(command: str | None, stream: TextIO | None = None) -> Iterator[None]:
    """While the block runs, print :func:`note_text` once on ``stream`` (stderr) when a kernel of
    :mod:`dfa.core` starts compiling and ``stream`` is a terminal; otherwise do nothing.

    Parameters
    ----------
    command : str or None
        The subcommand (its first-run estimate, :data:`FIRST_RUN_SECONDS`).
    stream : text stream, optional
        Where the line goes (default: ``sys.stderr`` at the time of the call).

    Yields
    ------
    None
        The block runs with the listener installed (numba's event API, :mod:`numba.core.event`).
    """
    out = sys.stderr if stream is None else stream
    if not _is_terminal(out):
        yield
        return
    from ..core import CACHE_DIR
    from ..core.jit import when_numba_loads

    lock = threading.Lock()
    said = False
    installed: list[tuple[Any, Any]] = []

    def on_start(ev: Any) -> None:
        nonlocal said
        py_func = getattr(ev.data.get("dispatcher") if ev.data else None, "py_func", None)
        if said or not getattr(py_func, "__module__", "").startswith("dfa.core."):
            return
        with lock:  # kernels may start compiling in worker threads
            if said:
                return
            said = True
        print(note_text(command, CACHE_DIR), file=out, flush=True)

    def install(numba: Any) -> None:  # numba's event API, once a kernel has imported numba
        from numba.core import event

        class _Note(event.Listener):
            def on_start(self, ev: Any) -> None:
                on_start(ev)

            def on_end(self, ev: Any) -> None:
                pass

        listener = _Note()
        event.register("numba:compile", listener)
        installed.append((event, listener))

    withdraw = when_numba_loads(install)
    try:
        yield
    finally:
        withdraw()
        for event, listener in installed:
            event.unregister("numba:compile", listener)
