"""What every command shares on the way out: JSON, tables, figures, progress bars and the work limits."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
from collections.abc import Callable, Sequence
from typing import Any

from ..formatting import WIDTH, fill, number, text_table
from ..jsonable import dumps
from .inputs import Inputs
from .parsing import UsageError

__all__ = [
    "report_script",
    "MAP_TIME_LIMIT_HOURS",
    "RATE_NAMES",
    "SIMULATE_NS_PER_SAMPLE",
    "SIMULATE_TIME_LIMIT",
    "SIMULATION_BOUND",
    "WIDTH",
    "add_progress_args",
    "working",
    "check_samples",
    "close_progress_bars",
    "cores",
    "drop_warnings",
    "emit",
    "flush_warnings",
    "hold_warning",
    "check_work_time",
    "fmt",
    "mark_operating_point",
    "progress",
    "save_png",
    "say",
    "table",
]

#: Planned cost of one simulated sample in the worst case measured (an oscillating run, loaded machine).
SIMULATE_NS_PER_SAMPLE = 100
#: ``dfa simulate`` refuses runs estimated longer than this (seconds) unless --force (work is refused up
#: front; a run without delay is integrated in chunks and stops at Ctrl-C, one with a delay or one run of a
#: map cannot be interrupted before the compiled kernel returns).
SIMULATE_TIME_LIMIT = 30.0
#: ``dfa map`` refuses maps estimated longer than this (hours, at the worst-case cost per sample) unless --force.
MAP_TIME_LIMIT_HOURS = 24.0
#: ``dfa contours``, ``dfa zwidth`` and ``dfa report --zwidth`` refuse work estimated longer than this (seconds)
#: unless --force: a larger grid than meant (``--grid 2000``) is caught before minutes of silence.
WORK_TIME_LIMIT = 120.0
#: How the messages of :func:`dfa.checks.check_damping_rate` name (β, μ), by whether the input is dimensionless
#: (the flags) or a device (the groups, at the device's K).
RATE_NAMES = {True: ("--beta", "--mu"), False: ("β = b/(K T)", "μ = m/(K T²)")}
#: |ξ| (ticks) beyond which a run counts as unstable (the default ``bound`` of :func:`dfa.simulate`).
SIMULATION_BOUND = 1.0e6


#: The warning lines of this run not printed yet (:func:`hold_warning`).
_HELD: list[str] = []


def hold_warning(line: str) -> None:
    """Keep a warning line until the run's inputs are accepted: a refused run (exit 2) prints only its error.

    The lines are printed on stderr by :func:`flush_warnings`, which the first output of the run (:func:`say`,
    :func:`emit`, :func:`progress`) and the end of :func:`dfa.cli.main` call; :func:`drop_warnings` forgets them.
    """
    _HELD.append(line)


def flush_warnings() -> None:
    """Print the held warning lines on stderr (:func:`hold_warning`)."""
    lines, _HELD[:] = list(_HELD), []
    for line in lines:
        sys.stderr.write(line)
    if lines:
        sys.stderr.flush()


def drop_warnings() -> None:
    """Forget the held warning lines (the run was refused: its one error line says what to fix)."""
    _HELD.clear()


def emit(obj: object, ensure_ascii: bool = True) -> None:
    """Print one strict-JSON object (NaN/inf become null with the reason, :mod:`dfa.jsonable`)."""
    flush_warnings()
    print(dumps(obj, ensure_ascii=ensure_ascii))


def table(rows: Sequence[Sequence[object]], header: Sequence[str] | None = None) -> str:
    """A plain-text table (:func:`dfa.formatting.text_table`), its last column wrapped to fit :data:`WIDTH`."""
    return text_table(rows, header, width=WIDTH)


def say(text: object = "") -> None:
    """Print ``text``, each line wrapped at :data:`WIDTH` characters (continuation lines indented)."""
    flush_warnings()
    print(fill(str(text), WIDTH))


def fmt(x: float | None, digits: int = 4) -> str:
    """A number for a table: ``digits`` significant digits, ``-`` for None, ``inf``."""
    return number(x, digits, none="-", inf="inf")


def save_png(flag: str, path: str, ax: Any) -> str:
    """Write the figure of ``ax`` to ``path`` (checked for ``flag``), atomically, as PNG, PDF or SVG by the path's
    suffix (:func:`dfa.render.figures.save_figure`); close it."""
    import matplotlib.pyplot as plt

    from .._io import FIGURE_SUFFIXES, check_output_file
    from ..render.figures import save_figure

    save_figure(ax, check_output_file(flag, path, FIGURE_SUFFIXES))
    plt.close(ax.figure)
    return path


def mark_operating_point(
    axes: Any, inp: Inputs | None, notes: Sequence[str] | None = None, *, marker: bool = True
) -> None:
    """Mark the device's (β, σ) at its K on each panel of a map or contour figure, with the panel's note (the
    simulated outcome there, for a map) after the label; ``marker=False``: the label only (the figure drew the
    point)."""
    if inp is None or inp.params is None:
        return
    from ..render.figures import POINT_STYLE

    b, s = inp.params.beta, inp.params.sigma
    unit = f" {inp.device.units['stiffness']}" if inp.device is not None else ""
    for k, ax in enumerate(axes):
        note = f": {notes[k]}" if notes is not None else ""
        if marker:
            ax.plot([b], [s], **POINT_STYLE)
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        right, top = b > (x0 + x1) / 2, s > (y0 + y1) / 2  # the label toward the panel's middle, readable on any
        ax.annotate(  # outcome's colour
            f"{inp.device.name if inp.device else ''}, K = {inp.stiffness:g}{unit}{note}",
            (b, s),
            textcoords="offset points",
            xytext=(-8 if right else 8, -8 if top else 8),
            ha="right" if right else "left",
            va="top" if top else "bottom",
            fontsize=8,
            clip_on=True,
            bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "0.5", "alpha": 0.85},
        )


def add_progress_args(p: argparse.ArgumentParser, quiet: bool = True) -> None:
    """--progress (and --quiet): the progress bar policy of :func:`progress`."""
    p.add_argument(
        "--progress",
        action="store_true",
        help="progress bar with an estimate on stderr even when it is not a terminal (default: only on a terminal)",
    )
    if quiet:
        p.add_argument("--quiet", action="store_true", help="no progress bar (default: a bar on a terminal)")


def progress(args: argparse.Namespace) -> bool:
    """Show progress bars: never with --quiet; always with --progress; else only on a terminal and without --json.

    Asked when the work starts: the held warnings (:func:`hold_warning`) are printed first.
    """
    flush_warnings()
    if getattr(args, "quiet", False):
        return False
    if getattr(args, "progress", False):
        return True
    if getattr(args, "json", False):
        return False
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


def working(args: argparse.Namespace) -> contextlib.AbstractContextManager[None]:
    """The progress line of a command's work (:func:`dfa.progress.progress_line`): on a terminal's stderr after 2 s,
    never with ``--json`` or ``--quiet`` nor in a pipe; with ``--progress``, always. Wrap the computation only, not
    the printing of the answer (the line is cleared when the block ends)."""
    from ..progress import progress_line

    if getattr(args, "json", False) or getattr(args, "quiet", False):
        return contextlib.nullcontext()
    return progress_line(sys.stderr, force=bool(getattr(args, "progress", False)))


def close_progress_bars() -> None:
    """Close every progress bar still open (an interrupted run's), so that the next line starts on a fresh line.

    dfa's bars are made with ``leave=False``: closing one clears its line and returns to the line's start, where
    the interruption's line is then printed (it was printed after the bar's text, and the bar cleared later,
    when it was collected). Costs nothing when tqdm was never imported.
    """
    std = sys.modules.get("tqdm.std")
    if std is None:
        return
    for bar in sorted(getattr(std.tqdm, "_instances", ()), key=lambda b: -abs(getattr(b, "pos", 0))):
        try:  # the innermost (lowest) bar first, as they close when unwinding
            bar.close()
        except Exception:  # a bar that cannot be closed must not hide the interruption's line
            pass
    try:
        sys.stderr.flush()
    except (OSError, ValueError, AttributeError):
        pass


def check_samples(samples: int, force: bool) -> None:
    """Refuse a run estimated over :data:`SIMULATE_TIME_LIMIT` seconds unless ``force`` (up front, with the fix)."""
    if samples < 1:
        raise UsageError(f"--samples {samples} is invalid: simulate at least one sample")
    seconds = samples * SIMULATE_NS_PER_SAMPLE * 1e-9
    if seconds > SIMULATE_TIME_LIMIT and not force:
        raise UsageError(
            f"--samples {samples} could take up to {seconds:.3g} s (estimated {SIMULATE_NS_PER_SAMPLE} ns per sample; "
            f"limit {SIMULATE_TIME_LIMIT:g} s): lower --samples "
            f"(at most {int(SIMULATE_TIME_LIMIT / (SIMULATE_NS_PER_SAMPLE * 1e-9))}) or add --force"
        )


def check_work_time(what: str, seconds: float, fix: str, force: bool) -> None:
    """Refuse work estimated over :data:`WORK_TIME_LIMIT` unless ``force`` (one line: the estimate and the fix).

    Parameters
    ----------
    what : str
        The flags that set the work, as given (``"--grid 2000"``).
    seconds : float
        The analysis's own estimate (an upper one).
    fix : str
        How to make it smaller.
    force : bool
        --force was given: run anyway.
    """
    if seconds > WORK_TIME_LIMIT and not force:
        took = f"{seconds / 60.0:.3g} min" if seconds >= 120.0 else f"{seconds:.3g} s"
        raise UsageError(
            f"{what} could take up to {took} (estimated; limit {WORK_TIME_LIMIT:g} s): {fix}, or add --force"
        )


def cores(jobs: int) -> int:
    """The number of workers of ``--jobs`` (-1: every core)."""
    return (os.cpu_count() or 1) if jobs == -1 else jobs


def report_script(prog: str, work: Callable[[], object]) -> int:
    """Run a report script's ``work`` (parse, compute, write) and return its exit code, the one way.

    The ``python -m dfa.cli.…_report`` scripts write committed reports: bad input is one line on stderr and
    exit 2 (before any work, or from the analysis), a file that cannot be written exit 1, an interruption 130
    with nothing written (their files are written together at the end, atomically), ``--help`` its code.

    Parameters
    ----------
    prog : str
        The script's name for the messages (``"python -m dfa.cli.contact_report"``).
    work : callable
        Everything the script does; raises on failure.

    Returns
    -------
    int
        0 ok, 2 bad input, 1 a file error, 130 interrupted.
    """
    from ..errors import DFAError

    try:
        work()
    except DFAError as err:
        msg = " ".join(str(err).split())
        print(msg if msg.startswith(prog) else f"{prog}: error: {msg}", file=sys.stderr)
        return 2
    except SystemExit as err:  # --help
        return int(err.code or 0)
    except KeyboardInterrupt:
        close_progress_bars()
        print(f"{prog}: interrupted; nothing written", file=sys.stderr)
        return 130
    except OSError as err:
        where = f"{err.filename!r}: " if err.filename else ""
        print(f"{prog}: error: {where}{err.strerror or err}; check the path, its permissions and free space",
              file=sys.stderr)  # fmt: skip
        return 1
    return 0
