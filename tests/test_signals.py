"""Interruption of threaded runs (issue 41): a signal at any moment ends with 130 / 143 and one line.

Python runs a signal handler in the main thread wherever that thread is; raising there inside the threading
module's own code (``Condition.wait`` after it released its lock) left a lock in a wrong state:
``RuntimeError: release unlocked lock`` from ``ThreadPoolExecutor.submit``, a traceback and exit 1. Under load
the signal landed there by chance; these tests put it there on purpose (:data:`_AT_SPOT`), in a subprocess
whose threading module is instrumented, so the result never depends on timing. No test sleeps and then asserts:
each waits for a marker the run prints.
"""

import os
import signal
import subprocess
import sys
import threading

import pytest

from dfa import _signals
from dfa.cli import main

POSIX = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
TWO_CORES = pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="--jobs 2 needs 2 cores")
MAIN_THREAD = pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signal handlers need the main thread"
)

#: Runs ``dfa`` (argv after the script's own two arguments) with every ``Condition`` of the threading module
#: instrumented: at ``spot`` the process signals itself right after a condition released its lock and before
#: it waits (the window the race hit), once per "spot:SIGNAL" event of argv[1], in that order.
#: Spots: "bar" (the first wait of the main thread: tqdm starting its monitor thread), "submit" (inside the
#: pool's submit), "wait" (waiting for a result), "shutdown" (joining the workers) and "joblib" (joblib's
#: generator starting its thread, the process backend).
_AT_SPOT = r"""
import os, signal, sys, threading
from concurrent.futures import ThreadPoolExecutor, _base
import concurrent.futures

events = [e.split(":") for e in sys.argv[1].split(",")]
where = {"spot": "bar"}

def fire(spot):
    if events and events[0][0] == spot and threading.current_thread() is threading.main_thread():
        sig = getattr(signal, events.pop(0)[1])
        os.kill(os.getpid(), sig)
        fired.set()

released = threading.Event()  # made before the instrumentation: the main thread passed the "bar" spot
fired = threading.Event()  # a signal was sent (the threads held for "submit", "joblib" and "wait" go on)
init = threading.Condition.__init__
def instrumented(self, lock=None):
    init(self, lock)
    release = self._release_save
    def release_save():
        saved = release()
        at_bar = where["spot"] == "bar" and threading.current_thread() is threading.main_thread()
        fire(where["spot"])  # the lock is released, the wait not entered yet
        if at_bar:
            released.set()
        return saved
    self._release_save = release_save
threading.Condition.__init__ = instrumented
bootstrap = threading.Thread._bootstrap_inner
def started_late(self):
    # a "bar" event pending: a new thread says it started only once the main thread waits for it, so that the
    # main thread enters the wait (under load it could find the thread started and never wait: no signal sent)
    if events and events[0][0] == "bar":
        released.wait(60)
    elif events and events[0][0] in ("submit", "joblib") and where["spot"] == events[0][0]:
        fired.wait(60)  # a thread started at the spot: likewise, the main thread then waits for its start
    bootstrap(self)
threading.Thread._bootstrap_inner = started_late

def spot(name, fn):
    def at(*args, **kwargs):
        where["spot"] = name
        try:
            return fn(*args, **kwargs)
        finally:
            where["spot"] = None
    return at

ThreadPoolExecutor.submit = spot("submit", ThreadPoolExecutor.submit)
_base.Future.result = spot("wait", _base.Future.result)
concurrent.futures.wait = spot("wait", concurrent.futures.wait)
shutdown = ThreadPoolExecutor.shutdown
def at_shutdown(self, *args, **kwargs):
    fire("shutdown")
    return shutdown(self, *args, **kwargs)
ThreadPoolExecutor.shutdown = at_shutdown
import joblib
joblib.Parallel.__call__ = spot("joblib", joblib.Parallel.__call__)

import dfa.analysis.maps as maps
run_chunk = maps._run_chunk
def chunk_after_the_wait(*args):
    # a "wait" event pending: a map's chunk ends only once the main thread waits for it (a small chunk could end
    # before the main thread asks for its result, which then never waits: no signal sent)
    if events and events[0][0] == "wait" and threading.current_thread() is not threading.main_thread():
        fired.wait(60)
    return run_chunk(*args)
maps._run_chunk = chunk_after_the_wait

if sys.argv[2].startswith("api"):  # dfa's API under Python's own SIGINT handler; api-processes: on loky
    import dfa
    how = sys.argv[2][4:] or "threads"
    try:
        dfa.stability_map(100.0, [1.0], grid=8, samples=2000, n_jobs=2, progress=False, backend=how)
    except KeyboardInterrupt:
        restored = signal.getsignal(signal.SIGINT) is signal.default_int_handler
        print("KeyboardInterrupt" + (", handler restored" if restored else ""), flush=True)
        sys.exit(130)
    sys.exit(0)
from dfa.cli import main
sys.argv = ["dfa"] + sys.argv[2:]
sys.exit(main())
"""

MAP = ["map", "--mu", "100", "--xi-dot", "1", "--grid", "8", "--samples", "2000", "--jobs", "2", "--out", "m.npz"]
#: The stiffness limits' simulations run on their own threads (dfa.analysis.limits.runs), one per core.
STIFFNESS = ["stiffness", "--device", "impulse", "--velocity", "0.05"]


@POSIX
@TWO_CORES
@pytest.mark.parametrize(
    "argv, events, code",
    [
        (MAP, "submit:SIGINT", 130),
        (MAP, "submit:SIGTERM,shutdown:SIGINT", 143),  # a second signal, while the workers are joined, changes nothing
        (MAP, "wait:SIGINT", 130),
        (MAP, "wait:SIGTERM", 143),
        (MAP, "shutdown:SIGINT", 130),
        (MAP + ["--progress"], "bar:SIGTERM", 143),
        (STIFFNESS, "submit:SIGINT", 130),
        (STIFFNESS, "wait:SIGTERM", 143),
        (["contours", "--mu", "5", "--grid", "10", "--progress"], "bar:SIGINT", 130),  # a bar, no thread pool
    ],
    ids=lambda x: x[0] if isinstance(x, list) else None,
)
def test_signal_inside_the_threading_module_exits_with_its_code_and_one_line(tmp_path, argv, events, code):
    cmd = [sys.executable, "-c", _AT_SPOT, events, *argv]
    proc = subprocess.run(cmd, capture_output=True, cwd=tmp_path, timeout=600, check=False)
    err = proc.stderr.decode()
    name = events.split(",")[0].split(":")[1]
    assert "Traceback" not in err and "Exception ignored" not in err, err
    assert proc.returncode == code, err
    assert err.replace("\r", "\n").strip().splitlines()[-1] == f"dfa: interrupted ({name}); nothing written", err
    assert os.listdir(tmp_path) == []
    assert os.listdir(tmp_path) == []


@POSIX
@TWO_CORES
@pytest.mark.parametrize(
    "events, mode", [("submit:SIGINT", "api"), ("wait:SIGINT", "api"), ("joblib:SIGINT", "api-processes")]
)
def test_api_ctrl_c_inside_the_threading_module_raises_keyboard_interrupt(tmp_path, events, mode):
    """The API keeps Python's own SIGINT handler: Ctrl-C at the racy spot is a KeyboardInterrupt, raised by dfa,
    with nothing on stderr (no traceback from a thread, no warning from joblib about the cancelled tasks)."""
    proc = subprocess.run(
        [sys.executable, "-c", _AT_SPOT, events, mode], capture_output=True, cwd=tmp_path, timeout=600, check=False
    )
    assert proc.returncode == 130 and proc.stdout == b"KeyboardInterrupt, handler restored\n", proc.stderr.decode()
    assert proc.stderr == b"", proc.stderr.decode()


def test_deferred_interruption_raised_when_the_block_ends_not_inside():
    seen = []
    with pytest.raises(KeyboardInterrupt, match="stop"), _signals.deferred():
        _signals.interrupt(KeyboardInterrupt("stop"))
        seen.append("went on")
    assert seen == ["went on"]
    with pytest.raises(KeyboardInterrupt, match="first"):  # one interruption: the failure it met is its context
        with _signals.deferred():
            _signals.interrupt(KeyboardInterrupt("first"))
            raise ValueError("a worker failed meanwhile")
    assert _signals._STATE == {"depth": 0, "pending": None}


# ------------------------------------------------------------------ the interruption's line after progress bars
def _interrupt_report(capsys, monkeypatch, tmp_path, target, name):
    """``dfa report --progress`` with ``target.name`` signalling SIGINT (once, then doing its work)."""
    original = getattr(target, name)
    sent = []

    def signalling(*args, **kwargs):
        if not sent:
            sent.append(True)
            os.kill(os.getpid(), signal.SIGINT)
        return original(*args, **kwargs)

    monkeypatch.setattr(target, name, signalling)
    code = main(["report", "--device", "impulse", "--velocity", "0.05", "--progress", "--out", str(tmp_path)])
    return code, capsys.readouterr().err


@MAIN_THREAD
@POSIX
def test_report_progress_interrupted_in_the_analysis_line_starts_fresh(capsys, monkeypatch, tmp_path):
    import dfa.studies.design as design

    code, err = _interrupt_report(capsys, monkeypatch, tmp_path, design, "first_unstable_speed")
    assert code == 130
    assert "analysis Impulse Engine" in err  # the bar was drawn
    head, line, tail = err.rpartition("dfa: interrupted (SIGINT); nothing written")
    assert line and tail == "\n", repr(err[-300:])  # nothing after the line (no bar cleared below it)
    assert head.endswith("\r") and head.rsplit("\n", 1)[-1].rsplit("\r", 2)[-2].strip() == "", repr(head[-200:])
    assert os.listdir(tmp_path) == []


@MAIN_THREAD
@POSIX
def test_report_progress_interrupted_in_the_map_line_starts_fresh(capsys, monkeypatch, tmp_path):
    import dfa.analysis.maps as maps
    import dfa.studies.design as design

    monkeypatch.setattr(design, "first_unstable_speed", lambda *a, **k: 3.0)  # quicker to the map
    calls = []
    run_chunk = maps._run_chunk

    def second_call(*args):  # the first call compiles, before the map's bar: signal inside the map
        calls.append(1)
        if len(calls) == 2:
            os.kill(os.getpid(), signal.SIGINT)
        return run_chunk(*args)

    monkeypatch.setattr(maps, "_run_chunk", second_call)
    code = main(["report", "--device", "impulse", "--velocity", "0.05", "--progress", "--out", str(tmp_path)])
    err = capsys.readouterr().err
    assert code == 130 and "stability map" in err, err
    head, line, tail = err.rpartition("dfa: interrupted (SIGINT); nothing written")
    assert line and tail == "\n", repr(err[-300:])
    assert head.endswith("\r") and head.rsplit("\n", 1)[-1].rsplit("\r", 2)[-2].strip() == "", repr(head[-200:])


def test_interrupted_process_pool_drops_only_lokys_manager_thread_errors(monkeypatch):
    """Interrupted under load, loky's ExecutorManagerThread raised KeyError on a cancelled task, a traceback beside
    the interruption's one line (test_api_ctrl_c_...[joblib] failed so): after an interruption its errors are
    dropped, any other thread's still reach threading.excepthook."""
    import threading

    from dfa import _parallel

    seen = []
    monkeypatch.setattr(threading, "excepthook", lambda args: seen.append(args.thread.name))
    _parallel._quiet_cancelled_pool()

    def boom():
        raise KeyError(1)

    for name in ("ExecutorManagerThread", "other"):
        t = threading.Thread(target=boom, name=name)
        t.start()
        t.join()
    assert seen == ["other"]


_EXIT_SCRIPT = r"""
import gc, io, sys
from dfa.cli import main
frozen = gc.get_freeze_count()
code = main(["params", "--device", "delta", "--stiffness", "1000"])  # in-process: nothing frozen
assert gc.get_freeze_count() == frozen, "an in-process main froze the collector"
sys.argv = ["dfa", "params", "--device", "delta", "--stiffness", "1000", "--json"]
code = main()  # the program: frozen once done, its output already written
print("frozen" if gc.get_freeze_count() > frozen else "not frozen", file=sys.stderr)
sys.exit(code)
"""


def test_program_exit_freezes_the_collector_after_its_output_and_in_process_calls_do_not():
    """``dfa`` as the program freezes the objects alive once its command is done (gc.freeze: the interpreter's last
    collections skip them, issue 43); its output and exit code are those of before; ``main(argv)`` in a caller's
    process never freezes."""
    import json

    proc = subprocess.run([sys.executable, "-c", _EXIT_SCRIPT], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr.strip().splitlines()[-1] == "frozen"
    assert json.loads(proc.stdout.strip().splitlines()[-1])["mu"] == 2250.0


def test_worker_warm_up_runs_the_modules_warm_worker_and_freezes_the_collector_at_exit(monkeypatch):
    """A worker process's warm-up (dfa._parallel._import) imports the module, runs its ``warm_worker()`` when it has
    one (the Z-width's loads numba there, while the worker waits for its first column), and registers gc.freeze to
    run at the worker's exit (its interpreter then ends without collecting numba's objects; the command waits)."""
    import atexit
    import gc
    import types

    from dfa import _parallel
    from dfa.analysis.limits import zwidth

    registered, warmed = [], []
    monkeypatch.setattr(atexit, "register", lambda fn, *a, **k: registered.append(fn))
    _parallel._import("json")  # no warm_worker: imported only
    fake = types.ModuleType("dfa_fake_warm")
    fake.warm_worker = lambda: warmed.append(True)  # type: ignore[attr-defined]
    monkeypatch.setitem(sys.modules, "dfa_fake_warm", fake)
    _parallel._import("dfa_fake_warm")
    assert registered == [gc.freeze, gc.freeze] and warmed == [True]
    zwidth.warm_worker()
    from dfa.core import exprel

    assert exprel._phi_flat._dispatcher is not None  # numba loaded, the column's first kernel ready
