"""The ``dfa`` program: its parser (one subcommand per module of :mod:`dfa.cli`), signals, exit codes.

Exit codes: 0 ok; 2 bad input (one line on stderr, before any work is done), or no command at all (bare ``dfa``
prints the help on stdout); 1 a file could not be written or memory ran out; 130 / 143 interrupted by SIGINT /
SIGTERM (one line on stderr naming what was kept: files are written atomically, so nothing is half-written);
141 stdout was a closed pipe (``dfa devices | head -1``), ended quietly.

Signals: the first SIGINT or SIGTERM unwinds the run (:class:`Interrupted`); later ones are ignored while it cleans
up. Where threads are started, waited for or joined (and progress bars made) the signal is raised as soon as that
is safe, never inside the threading module (:mod:`dfa._signals`); any bar still drawn is cleared before the line.
As the program (``main()`` without ``argv``: the ``dfa`` script, ``python -m dfa.cli``) the handlers stay
installed to the end: a second signal while the interpreter exits (worker threads or the process pool still
finishing) changes nothing, and a first one arriving after the run ends exits at once with its one line and
128 + the signal's number (:func:`_exit_on_signal`), never by the signal itself nor with a traceback from
``threading._shutdown``; once the worker threads are joined, the last moments of the interpreter ignore both
(:func:`_ignore_signals`). Called with ``argv`` (in-process, as the tests do), ``main`` restores the caller's handlers.

An input no haptic device has (``--resolution 10``, :mod:`dfa.plausibility`) is computed as given with one
``dfa: warning:`` line naming the likely slip, printed once the inputs are accepted: a refused run prints only its
error line. numpy's ``RuntimeWarning`` lines ("overflow encountered in multiply") are never printed as they come:
a run that succeeds ends with one warning line counting them, a refused or interrupted one prints none.
"""

from __future__ import annotations

import argparse
import atexit
import gc
import os
import signal
import sys
import warnings
from collections.abc import Sequence
from types import ModuleType
from typing import Any

from .._io import written_paths
from .._signals import interrupt
from ..errors import DFAError, ImplausibleInputWarning
from . import (
    check,
    contours,
    devices,
    export,
    identify,
    limit_cycles,
    maps,
    params,
    report,
    require,
    simulate,
    stiffness,
    tune,
    validate,
    zwidth,
)
from .compile_note import compile_note
from .output import close_progress_bars, drop_warnings, flush_warnings, hold_warning
from .parsing import Parser, UsageError

__all__ = ["COMMANDS", "build_parser", "main", "on_signal", "package_version"]

#: The subcommands, in the order of ``dfa --help``: each module has COMMAND, HELP, EXAMPLE, add_arguments, run.
COMMANDS: tuple[ModuleType, ...] = (
    devices, params, check, stiffness, require, tune, export, simulate, maps, limit_cycles, contours, report,
    validate, zwidth, identify,
)  # fmt: skip


class _Version(argparse.Action):
    """``--version``: the installed distribution's version (importlib.metadata), looked up only when asked."""

    def __init__(self, option_strings: Sequence[str], dest: str = argparse.SUPPRESS, **kwargs: Any) -> None:
        super().__init__(option_strings, dest, nargs=0, default=argparse.SUPPRESS, **kwargs)

    def __call__(self, parser: argparse.ArgumentParser, *args: Any, **kwargs: Any) -> None:
        print(f"dfa {package_version()}")
        parser.exit(0)


def package_version() -> str:
    """Version of the installed distribution (``dfa.__version__``, from ``importlib.metadata``)."""
    from .. import __version__

    return __version__


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The ``dfa`` parser: every subcommand of :data:`COMMANDS` with its help, example and arguments.

    Parameters
    ----------
    command : str, optional
        The subcommand about to run: only its arguments are added (the others keep their name and help, which is
        all ``dfa --help`` and a misspelt command need), so that a run does not pay for the other commands'
        arguments nor import what they need for them. Default: every subcommand's.
    """
    parser = Parser(
        prog="dfa",
        description="Passivity, limit cycles and stiffness limits of sampled, quantized haptic devices "
        "(Diolaiti, Niemeyer, Barbagli & Salisbury, ICRA 2005).",
        epilog="`dfa COMMAND --help` describes each command. Without a command, dfa prints this help and exits with 2.",
    )
    parser.add_argument("--version", action=_Version, help="print the installed version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=Parser)
    for cmd in COMMANDS:
        p = sub.add_parser(
            cmd.COMMAND,
            help=cmd.HELP,
            description=cmd.HELP[0].upper() + cmd.HELP[1:] + ".",
            epilog=f"example:\n  {cmd.EXAMPLE}",
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        if command in (None, cmd.COMMAND):
            cmd.add_arguments(p)
        p.set_defaults(func=cmd.run)
    return parser


class Interrupted(KeyboardInterrupt):
    """SIGINT or SIGTERM received: unwinds like Ctrl-C so that every ``finally`` cleans up."""

    def __init__(self, signum: int) -> None:
        super().__init__(signum)
        self.signum = signum


_SIGNALS = tuple(getattr(signal, n) for n in ("SIGINT", "SIGTERM") if hasattr(signal, n))


def on_signal(signum: int, frame: object) -> None:
    """The handler of SIGINT and SIGTERM: ignore further signals (the clean-up must finish), raise :class:`Interrupted`
    (where it lands, or, while threads are started, waited for or joined, once that is safe: :mod:`dfa._signals`)."""
    for sig in _SIGNALS:  # a second signal must not interrupt the clean-up of the first
        signal.signal(sig, signal.SIG_IGN)
    interrupt(Interrupted(signum))


def _install_signal_handlers() -> dict[Any, Any]:
    """Route SIGINT and SIGTERM to :class:`Interrupted` (main thread only); return the old handlers."""
    import threading

    if threading.current_thread() is not threading.main_thread():
        return {}
    old = {}
    for sig in _SIGNALS:
        old[sig] = signal.getsignal(sig)
        signal.signal(sig, on_signal)
    return old


def _one_line_warning(message: Warning | str, category: type[Warning], *_args: object, **_kw: object) -> str:
    """A warning on stderr as one line, like the errors (no source file or code line)."""
    text = " ".join(str(message).split())
    return f"dfa: warning: {text} ({category.__name__})\n"


def _show_implausible(previous: Any, numeric: list[str]) -> Any:
    """A ``warnings.showwarning`` that holds :class:`ImplausibleInputWarning` as one line for stderr
    (:func:`~dfa.cli.output.hold_warning`: printed once the inputs are accepted, also where a test framework records
    warnings), collects the text of every plain ``RuntimeWarning`` (numpy's "overflow encountered in multiply") in
    ``numeric`` (:func:`_numeric_note`) and passes every other warning on to ``previous``."""

    def show(message: Warning | str, category: type[Warning], *args: Any, **kwargs: Any) -> None:
        if issubclass(category, ImplausibleInputWarning):
            hold_warning(_one_line_warning(message, category))
        elif category is RuntimeWarning:  # numpy's floating-point warnings (not dfa's own subclasses)
            numeric.append(" ".join(str(message).split()))
        else:
            previous(message, category, *args, **kwargs)

    return show


def _numeric_note(numeric: list[str]) -> str:
    """The one warning line of a run that met floating-point overflow or invalid operations (numpy's
    ``RuntimeWarning``), or "" when it met none; a refused or interrupted run prints none (its one line says it all).
    """
    if not numeric:
        return ""
    kinds = list(dict.fromkeys(numeric))
    shown = "; ".join(kinds[:3]) + (f"; {len(kinds) - 3} more" if len(kinds) > 3 else "")
    return (
        f"dfa: warning: numpy reported {len(numeric)} floating-point exception(s) ({shown}): with inputs this far "
        "from a haptic device's values the numbers above may be inexact; check the inputs' units (RuntimeWarning)\n"
    )


def _quiet_stdout() -> None:
    """After a closed pipe: send what is left on stdout to /dev/null, so exiting does not raise again."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, AttributeError, ValueError):  # not a real file (captured in tests)
        pass


def _run(parser: argparse.ArgumentParser, argv: list[str]) -> int:
    if not argv:  # bare `dfa`: the help, and exit code 2 (no command ran)
        parser.print_help()
        return 2
    args, extra = parser.parse_known_args(argv)
    if extra:  # said by the command's name, as its other errors are (argparse's top parser would say `dfa:`)
        command = getattr(args, "command", None)
        raise UsageError(f"dfa{' ' + command if command else ''}: error: unrecognized arguments: {' '.join(extra)}")
    args.argv = list(argv)  # the command line as given (a command that prints a command to run next reads it)
    if getattr(args, "func", None) is None:
        raise UsageError("dfa: error: give a COMMAND (see `dfa --help`)")
    with compile_note(args.command):  # one line on a terminal while kernels compile (first run only)
        return int(args.func(args) or 0)


def _interrupted_line(signum: int, before: int) -> str:
    """The one line of an interruption: the signal, and the files this run kept (complete) or none."""
    kept = written_paths()[before:]
    what = "nothing written" if not kept else "kept " + ", ".join(kept) + " (complete)"
    return f"dfa: interrupted ({signal.Signals(signum).name}); {what}"


def _exit_on_signal(before: int) -> Any:
    """The handler of a signal that arrives after the run (the interpreter exiting): its one line, then exit.

    ``os._exit(128 + signum)``: nothing is left to clean up (every file was written atomically, stdout is
    flushed), and raising would end in ``threading._shutdown``'s traceback while worker threads finish.
    """

    def handler(signum: int, frame: object) -> None:
        for sig in _SIGNALS:
            signal.signal(sig, signal.SIG_IGN)
        try:
            sys.stderr.flush()
        except (OSError, ValueError, AttributeError):  # a closed or broken stderr: the line below is what matters
            pass
        try:
            os.write(2, (_interrupted_line(signum, before) + "\n").encode())
        except OSError:
            pass
        os._exit(128 + int(signum))

    return handler


def _after_run(old_handlers: dict[Any, Any], program: bool, before: int) -> None:
    """The signal handlers once ``main`` is done: the caller's again (in-process), or, as the program, ignored
    after an interruption (the clean-up finishes) and :func:`_exit_on_signal` otherwise.

    As the program, the objects alive now are frozen out of the garbage collector (:func:`gc.freeze`): the process
    is ending, and the interpreter's last collections then skip numba's and scipy's hundreds of thousands of
    objects (about 0.15 s of every command that ran a kernel, issue 43). Nothing is collected that would have been
    at exit: the output is flushed, files are closed, atexit handlers run as before."""
    if not program:
        for sig, handler in old_handlers.items():
            signal.signal(sig, handler if handler is not None else signal.SIG_DFL)
        return
    late = _exit_on_signal(before)
    for sig in old_handlers:
        if signal.getsignal(sig) is on_signal:  # not interrupted: a late signal exits with its line
            signal.signal(sig, late)
    atexit.register(_ignore_signals)  # runs once threading._shutdown has joined the workers
    gc.freeze()


def _ignore_signals() -> None:
    """Ignore SIGINT and SIGTERM for the last moments of the interpreter: Python resets a handler written in Python
    to the default action when it finalizes the signal module, and a signal then killed dfa (status -2, -15)."""
    for sig in _SIGNALS:
        signal.signal(sig, signal.SIG_IGN)


def _error(err: BaseException, before: int, prog: str = "dfa") -> int:
    """The exit code of an exception (module docstring), with its one line on stderr, which starts with ``prog``
    (``dfa COMMAND``, as argparse's own errors do, or ``dfa`` before a command is known)."""
    if isinstance(err, DFAError):
        msg = str(err)
        print((msg if msg.startswith("dfa") else f"{prog}: error: {msg}").replace("\n", " "), file=sys.stderr)
        return 2
    if isinstance(err, SystemExit):  # --help and --version
        return int(err.code or 0)
    if isinstance(err, KeyboardInterrupt):
        signum = getattr(err, "signum", int(signal.SIGINT))
        close_progress_bars()  # the line starts on a fresh line, not after a bar's text
        print(_interrupted_line(signum, before), file=sys.stderr)
        return 128 + int(signum)
    if isinstance(err, BrokenPipeError):
        _quiet_stdout()
        return 141
    if isinstance(err, MemoryError):
        print(f"{prog}: error: out of memory; lower --grid, --samples or the number of speeds", file=sys.stderr)
        return 1
    assert isinstance(err, OSError)
    where = f"{err.filename!r}: " if err.filename else ""
    print(
        f"{prog}: error: {where}{err.strerror or err}; check the path, its permissions and free space", file=sys.stderr
    )
    return 1


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``dfa`` command line; return the exit code (module docstring).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments after ``dfa`` (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        0 ok, 2 bad input, 1 a file or memory error, 128 + signal when interrupted, 141 a closed pipe.
    """
    program = argv is None  # the dfa program itself: signals are handled until the process ends
    args = list(sys.argv[1:] if argv is None else argv)
    command = args[0] if args and args[0] in {c.COMMAND for c in COMMANDS} else None
    parser = build_parser(command)
    prog = f"dfa {command}" if command else "dfa"  # every error line of a command starts alike
    before = len(written_paths())
    old_handlers = _install_signal_handlers()
    numeric: list[str] = []  # the RuntimeWarnings of this run (_numeric_note)
    old_format = warnings.formatwarning
    warnings.formatwarning = _one_line_warning
    try:
        try:
            with warnings.catch_warnings():  # a slip is said on every run, not once per process as by default
                warnings.simplefilter("always", ImplausibleInputWarning)
                warnings.showwarning = _show_implausible(warnings.showwarning, numeric)
                code = _run(parser, args)
        except (DFAError, SystemExit, KeyboardInterrupt, BrokenPipeError, MemoryError, OSError) as err:
            (drop_warnings if isinstance(err, DFAError) else flush_warnings)()  # refused: the error line alone
            code = _error(err, before, prog)
        else:
            note = _numeric_note(numeric)
            if note:
                hold_warning(note)
            flush_warnings()
        try:  # a buffered stdout meets a closed pipe here, not at exit ("Exception ignored ...", exit 120)
            sys.stdout.flush()
        except BrokenPipeError as err:
            code = _error(err, before, prog)
        except (OSError, ValueError, AttributeError):  # no stdout, or a closed one: nothing left to say
            pass
        return code
    except KeyboardInterrupt as err:  # the first signal while the outcome is being printed: its line too
        return _error(err, before, prog)
    finally:
        warnings.formatwarning = old_format
        _after_run(old_handlers, program, before)
