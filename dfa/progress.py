"""One progress line for long work: the analyses say what they do, a command shows it (issue 43).

The analyses never print. They name their stage of work (:func:`stage`: what, and how many steps when that is
known) and count the simulations they run (:func:`advance`); both cost a lock and an attribute read when
nothing listens. A command line that wants a line (a terminal, no ``--json``) opens one with
:func:`progress_line`: after :data:`DELAY` seconds of work it shows, on stderr, one updating line with the
stage, how far it is, the runs so far and the time left where a stage knows its size, and clears it when the
work ends. Work shorter than the delay shows nothing; tqdm is imported only when a line is due to appear.

Examples
--------
>>> import io
>>> out = io.StringIO()
>>> with progress_line(out, delay=0.0, force=True):
...     with stage("searching K", total=2):
...         advance(1)
...         advance(1)
>>> "searching K" in out.getvalue()
True
>>> with stage("nobody listens", total=3):   # no line open: nothing happens
...     advance(3)
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import threading
import time
from collections.abc import Iterator
from typing import Any, TextIO

from ._parallel import new_bar
from ._signals import deferred

__all__ = ["DELAY", "stage", "advance", "progress_line", "runs_counted", "samples_counted"]

#: Seconds of work before the line appears (the environment variable ``DFA_PROGRESS_DELAY`` overrides it).
DELAY = 2.0
#: Seconds between two refreshes of a shown line when the work reports nothing.
TICK = 0.5

_LOCK = threading.RLock()


@dataclasses.dataclass
class _Stage:
    """A stage of work: what it does, its size in steps of ``unit`` (None: unknown), whether its pace estimates
    the time left, when it began, the steps done."""

    what: str
    total: int | None
    unit: str
    eta: bool
    start: float
    done: int = 0


class _Line:
    """The open line: its stream, its start, the stage, the runs; the tqdm bar once shown."""

    def __init__(self, stream: TextIO, delay: float) -> None:
        self.stream, self.delay, self.start = stream, delay, time.monotonic()
        self.stage = _Stage("working", None, "step", True, self.start)
        self.runs = 0
        self.bar: Any = None

    def refresh(self) -> None:
        """Show or update the line once the delay has passed (the caller holds the lock)."""
        now = time.monotonic()
        if self.bar is None:
            if now - self.start < self.delay:
                return
            self.bar = new_bar(file=self.stream, leave=False, dynamic_ncols=True, mininterval=0.0,
                               bar_format="{desc}")  # fmt: skip
        self.bar.set_description_str(self.text(now), refresh=False)
        self.bar.refresh()

    def text(self, now: float) -> str:
        """What the line says, short (a terminal's width): the stage, how far (n/~N), the time left where the stage
        knows its size and its steps cost alike (from the stage's own pace), the time since the work began, the
        runs so far."""
        st = self.stage
        parts = [st.what]
        if st.total:
            parts[0] += f": {min(st.done, st.total)}/~{st.total}"
            if st.done > 0 and st.eta:
                left = (now - st.start) / st.done * max(st.total - st.done, 0)
                parts.append(f"~{_clock(left)} left")
        parts.append(f"{_clock(now - self.start)} elapsed")
        if self.runs:
            parts.append(f"{self.runs} run{'s' if self.runs != 1 else ''}")
        return ", ".join(parts)


def _clock(seconds: float) -> str:
    """Seconds as m:ss."""
    m, s = divmod(int(round(seconds)), 60)
    return f"{m}:{s:02d}"


_OPEN: list[_Line] = []
_COUNTED: list[int] = [0, 0]  # runs, samples


@contextlib.contextmanager
def stage(what: str, total: int | None = None, unit: str = "step", eta: bool = True) -> Iterator[None]:
    """The stage of work ``what`` (a few words), of ``total`` steps when known; the previous stage after it.

    Parameters
    ----------
    what : str
        What the work does, e.g. ``"K_sim: grid of 16 stiffnesses"``.
    total : int, optional
        How many steps (:func:`advance` calls' ``step``) the stage takes; None when unknown (no estimate).
    unit : str, optional
        What a step is: only :func:`advance` calls of the same ``unit`` count (a stiffness search's judgements
        inside a stage counting parameters do not).
    eta : bool, optional
        Estimate the time left from the stage's pace (default True); False where its steps differ widely in cost.
    """
    with _LOCK:
        line = _OPEN[-1] if _OPEN else None
        if line is not None:
            saved, line.stage = line.stage, _Stage(what, total, unit, eta, time.monotonic())
            line.refresh()
    try:
        yield
    finally:
        if line is not None:
            with _LOCK:
                line.stage = saved
                line.refresh()


def advance(runs: int = 0, step: int = 1, unit: str = "step", samples: int = 0) -> None:
    """``runs`` simulations of ``samples`` samples in all run, and ``step`` steps of ``unit`` done (thread-safe;
    steps count in a stage of that unit only)."""
    with _LOCK:
        _COUNTED[0] += runs
        _COUNTED[1] += samples
        if _OPEN:
            line = _OPEN[-1]
            line.runs += runs
            line.stage.done += step if unit == line.stage.unit else 0
            line.refresh()


def runs_counted() -> int:
    """Simulations counted by :func:`advance` in this process so far (a command's ``--explain`` takes the
    difference over its work)."""
    with _LOCK:
        return _COUNTED[0]


def samples_counted() -> int:
    """Samples of the simulations counted by :func:`advance` in this process so far (the benchmarks' count)."""
    with _LOCK:
        return _COUNTED[1]


@contextlib.contextmanager
def progress_line(stream: TextIO, delay: float | None = None, force: bool = False) -> Iterator[None]:
    """Open the progress line on ``stream`` for the work of the block: only on a terminal, unless ``force``.

    Parameters
    ----------
    stream : file
        Where the line goes (stderr).
    delay : float, optional
        Seconds before the line appears (default :data:`DELAY`, or ``DFA_PROGRESS_DELAY``).
    force : bool, optional
        Show the line even when ``stream`` is not a terminal (``--progress``).
    """
    try:
        tty = bool(stream.isatty())
    except (AttributeError, ValueError):
        tty = False
    if not (tty or force):
        yield
        return
    wait = float(os.environ.get("DFA_PROGRESS_DELAY", DELAY)) if delay is None else delay
    line = _Line(stream, wait)
    stop = threading.Event()
    ticker = threading.Thread(target=_tick, args=(line, stop), name="dfa-progress", daemon=True)
    with _LOCK:
        _OPEN.append(line)
    with deferred():  # a signal while a thread starts is raised after it (dfa._signals)
        ticker.start()
    try:
        yield
    finally:
        stop.set()
        with deferred():
            ticker.join()
            with _LOCK:
                _OPEN.remove(line)
                if line.bar is not None:
                    line.bar.close()


def _tick(line: _Line, stop: threading.Event) -> None:
    """Refresh the line every :data:`TICK` seconds (the time shown moves during a long kernel call)."""
    while not stop.wait(TICK):
        with _LOCK:
            line.refresh()
