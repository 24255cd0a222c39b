"""Hardening (issue 17): no tracebacks, nothing half-written, clean interruption.

Each example of the fuzzing report has its own regression test here; the
random CLI fuzzing is in ``test_cli_fuzz.py``.
"""

import decimal
import fractions
import json
import math
import os
import signal
import subprocess
import sys
import time
import warnings

import numpy as np
import pytest
from fixed_keywords import small_design_searches
from hypothesis import example, given
from hypothesis import strategies as st

import dfa
from dfa import _io
from dfa.analysis.simulation import preload_position, stored_energy
from dfa.checks import check_beta, check_int, check_mu, check_nonnegative, check_positive, check_real, check_sigma
from dfa.cli import main
from dfa.errors import DFAError, DFATypeError, DFAValueError
from dfa.model.wall import Wall, WallParams
from dfa.render.text import growth_meaning, search_text

#: Deliberately outside what haptic devices have (extreme values test the numerics): the plausibility warning
#: (dfa.plausibility) is expected here, and tested in tests/test_plausibility.py.
pytestmark = pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DFA = [sys.executable, "-c", "import sys; from dfa.cli import main; sys.exit(main())"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def refused(capsys, *argv):
    """Run, expect exit 2 and a one-line message; return it."""
    code, out, err = run(capsys, *argv)
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and err.startswith("dfa"), err
    assert "Traceback" not in err
    return err


DIMLESS = ["--mu", "1", "--beta", "0.1", "--sigma", "0.2"]
IMPULSE = ["--device", "impulse"]


# ------------------------------------------------------------------ 1. numbers parse as numbers
@pytest.mark.parametrize(
    "text", ["1_000", "١٢", "１２", "nan", "NaN", "inf", "-inf", "Infinity", "0x10", "1e", "", " ", "1,5", "²"]
)
def test_cli_numbers_decimal_ascii_only(capsys, text):
    err = refused(capsys, "params", f"--mu={text}", "--beta", "0", "--sigma", "0")
    assert "--mu" in err and "ASCII digits" in err


@pytest.mark.parametrize("text, word", [("1e400", "too large"), ("-1e400", "too large"), ("1e-400", "too small")])
def test_cli_numbers_overflow_and_underflow_refused(capsys, text, word):
    err = refused(capsys, "check", "--beta", "0.1", "--sigma", "0.1", f"--xi-dot={text}")
    assert "--xi-dot" in err and word in err


@pytest.mark.parametrize("text", ["1_000", "1e6", "2.0", "٣", "nan", "99999999999999999999999"])
def test_cli_integers_decimal_ascii_only(capsys, text):
    err = refused(capsys, "simulate", *DIMLESS, "--xi-dot", "1", "--samples", text)
    assert "--samples" in err


def test_cli_minus_zero_is_zero(capsys):
    code, out, _ = run(capsys, "params", "--mu", "1", "--beta", "-0", "--sigma", "-0.0")
    assert code == 0 and "-0" not in out
    assert [line.split()[-1] for line in out.splitlines()[1:]] == ["1", "0", "0"]
    code, out, _ = run(capsys, "params", "--mu", "1", "--beta", "-0", "--sigma", "-0", "--json")
    assert json.loads(out) == {"mu": 1.0, "beta": 0.0, "sigma": 0.0} and "-0" not in out


def test_cli_mass_1e308_names_the_flag_and_the_overflow(capsys):
    # was: "mu = inf is invalid: ... μ = m/(K T²) must be positive"
    err = refused(capsys, "params", *IMPULSE, "--mass", "1e308")
    assert "--mass" in err and "overflows" in err and "mu = inf" not in err


def test_cli_mass_1e_320_refused_not_nan(capsys):
    # was: exit 0 printing "ξ = nan"
    err = refused(capsys, "simulate", *IMPULSE, "--mass", "1e-320", "--velocity", "0.05", "--samples", "100")
    assert "--mass" in err and "vanishes" in err


def test_cli_physical_flag_errors_name_the_flag(capsys):
    err = refused(capsys, "params", *IMPULSE, "--mass", "-1")
    assert err.startswith("dfa params: error: --mass")
    err = refused(capsys, "params", *IMPULSE, "--stiffness", "1e-310")
    assert "--stiffness = 1e-310" in err and "μ = m/(K T²) overflows" in err


def test_cli_map_negative_xi_dot_refused_with_fix(capsys, tmp_path):
    # was: map --xi-dot=-3 silently ran +3
    out = tmp_path / "m.npz"
    err = refused(
        capsys, "map", "--mu", "100", "--xi-dot=-3", "--grid", "2", "--samples", "10", "--jobs", "1", "--out", str(out)
    )
    assert "--xi-dot 3" in err and not out.exists()


# ------------------------------------------------------------------ 2. validators
CHECKS = [check_real, check_positive, check_nonnegative, check_int]
HOSTILE = st.one_of(
    st.text(max_size=5),
    st.none(),
    st.booleans(),
    st.complex_numbers(),
    st.integers(),
    st.floats(),
    st.fractions(),
    st.decimals(allow_nan=True),
    st.just(10**400),
    st.just(-(10**400)),
    st.just(fractions.Fraction(10**400, 3)),
    st.just(np.array([1.0, 2.0])),
    st.just(np.array([[1]])),
    st.just(np.float32(2.5)),
    st.just(np.int64(3)),
    st.just(np.array(2.0)),
    st.just(np.bool_(True)),
    st.just(np.complex128(1j)),
    st.just(object()),
    st.just([1.0]),
    st.just(np.float64("nan")),
    st.just(decimal.Decimal("1e999999")),
)


@given(HOSTILE)
@example(10**400)
@example("1.0")
@example(np.array([1.0]))
@example(None)
def test_validators_raise_only_package_errors(value):
    for check in CHECKS + [lambda n, v: check_mu(v, n), lambda n, v: check_beta(v, n), lambda n, v: check_sigma(v, n)]:
        try:
            out = check("x", value)
        except DFAError as err:
            msg = str(err)
            assert msg.startswith("x = ") and len(msg) < 300, msg  # names the parameter, value abbreviated
        else:
            assert type(out) in (float, int)


def test_validators_400_digit_integer(capsys):
    with pytest.raises(DFAValueError, match=r"x = <integer of 40\d digits>.*finite number"):
        check_real("x", 10**400)
    with pytest.raises(DFAValueError, match="at most"):
        check_int("n", 10**400)
    with pytest.raises(DFAValueError, match="mass"):
        dfa.Device(mass=10**400, damping=0, coulomb=0, resolution=1e-5, period=1e-3)


@pytest.mark.parametrize(
    "value, kind",
    [
        ("1.0", DFATypeError),
        (1j, DFATypeError),
        (None, DFATypeError),
        (True, DFATypeError),
        (np.array([1.0, 2.0]), DFATypeError),
        (float("nan"), DFAValueError),
    ],
)
def test_validators_types(value, kind):
    with pytest.raises(kind, match="^x = "):
        check_real("x", value)


def test_validators_accept_numpy_scalars():
    assert check_real("x", np.float32(2.5)) == 2.5 and type(check_real("x", np.float32(2.5))) is float
    assert check_int("n", np.int64(3)) == 3 and type(check_int("n", np.int64(3))) is int
    assert check_real("x", np.array(2.0)) == 2.0
    assert check_int("n", np.uint8(7), minimum=1) == 7
    p = dfa.Params(np.float32(5.0), np.float64(0.1), np.int32(0))
    assert p.to_dict() == {"mu": 5.0, "beta": pytest.approx(0.1), "sigma": 0.0}


def test_table1_device_groups_refused_when_they_vanish_or_overflow():
    dev = dfa.Device(mass=1e-320, damping=0.02, coulomb=0.024, resolution=314e-6, period=2e-3)
    with pytest.raises(DFAValueError, match="mass = .*vanishes"):
        dev.params(80.0)
    dev = dfa.Device(mass=0.032, damping=1e308, coulomb=0.024, resolution=314e-6, period=2e-3)
    with pytest.raises(DFAValueError, match="damping = 1e\\+308.*β = b/\\(K T\\) overflows"):
        dev.params(80.0)
    # zero damping or friction stays allowed (β = 0, σ = 0 are valid)
    assert dfa.Device(mass=0.032, damping=0.0, coulomb=0.0, resolution=314e-6, period=2e-3).params(80.0).beta == 0.0
    with pytest.raises(DFAValueError, match="mu"):
        check_mu(5e-324)


def test_table1_speed_conversion_overflow_refused():
    dev = dfa.Device(mass=0.032, damping=0.02, coulomb=0.024, resolution=1e-300, period=2e-3)
    with pytest.raises(DFAValueError, match="velocity = .*overflows"):
        dev.xi_dot(1e300)


# ------------------------------------------------------------------ 3. atomic writes and output paths
def test_io_atomic_write_keeps_old_file_on_failure(tmp_path):
    p = tmp_path / "a.txt"
    _io.atomic_write_text(p, "old")
    with pytest.raises(RuntimeError):
        with _io.atomic_open(p, "w") as fh:
            fh.write("new, half")
            raise RuntimeError("disk full")
    assert p.read_text() == "old" and os.listdir(tmp_path) == ["a.txt"]
    with pytest.raises(KeyboardInterrupt):
        with _io.atomic_open(p, "wb") as fh:
            fh.write(b"x")
            raise KeyboardInterrupt
    assert p.read_text() == "old" and os.listdir(tmp_path) == ["a.txt"]
    _io.atomic_write_bytes(p, b"new")
    assert p.read_bytes() == b"new" and str(p) in _io.written_paths()


def test_io_staged_folder_all_or_nothing(tmp_path):
    (tmp_path / "r.md").write_text("old")
    with pytest.raises(RuntimeError):
        with _io.staged_folder(tmp_path) as stage:
            (stage / "figures").mkdir()
            (stage / "figures" / "f.png").write_bytes(b"png")
            raise RuntimeError
    assert sorted(os.listdir(tmp_path)) == ["r.md"] and (tmp_path / "r.md").read_text() == "old"
    with _io.staged_folder(tmp_path) as stage:
        (stage / "figures").mkdir()
        (stage / "figures" / "f.png").write_bytes(b"png")
        (stage / "r.md").write_text("new")
    assert sorted(os.listdir(tmp_path)) == ["figures", "r.md"] and (tmp_path / "r.md").read_text() == "new"


# A run that stages a report and writes a file atomically in the folder argv[1], says "staged" and waits for stdin.
_STAGING = """
import sys
from dfa._io import atomic_open, staged_folder

with staged_folder(sys.argv[1]) as stage, atomic_open(sys.argv[1] + "/" + sys.argv[2] + ".txt", "w") as fh:
    (stage / (sys.argv[2] + ".md")).write_text("report")
    fh.write("file")
    print("staged", flush=True)
    sys.stdin.read()
"""


def _staging(folder, name):
    proc = subprocess.Popen([sys.executable, "-c", _STAGING, str(folder), name], stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)  # fmt: skip
    assert proc.stdout.readline() == b"staged\n", proc.stderr.read()
    return proc


def _temporary(folder):
    return sorted(n for n in os.listdir(folder) if n.startswith(".dfa-tmp-"))


@pytest.mark.skipif(sys.platform == "win32", reason="flock")
def test_io_staged_folder_removes_what_a_killed_run_left_not_a_running_one(tmp_path):
    killed = _staging(tmp_path, "killed")
    killed.kill()  # SIGKILL: no clean-up runs
    killed.communicate(timeout=120)
    left = _temporary(tmp_path)
    assert len(left) == 2  # its stage and its .part file
    running = _staging(tmp_path, "running")  # another run, still going on in the same folder
    ours = set(_temporary(tmp_path)) - set(left)
    assert len(ours) == 2
    (tmp_path / "keep.txt").write_text("mine")
    with _io.staged_folder(tmp_path) as stage:
        (stage / "r.md").write_text("new")
    assert set(_temporary(tmp_path)) == ours  # the killed run's are gone, the running one's untouched
    assert sorted(_io.remove_stale(tmp_path)) == []
    out, err = running.communicate(timeout=120)  # closes stdin: it finishes
    assert running.returncode == 0, err
    assert _temporary(tmp_path) == []
    assert sorted(os.listdir(tmp_path)) == ["keep.txt", "r.md", "running.md", "running.txt"]


def test_fig4_map_save_is_atomic(tmp_path, monkeypatch):
    m = dfa.stability_map(100.0, [2.0], grid=2, samples=50, n_jobs=1, progress=False)
    p = m.save(tmp_path / "m.npz")
    before = p.read_bytes()

    def boom(fh, **kw):
        fh.write(b"PK half a zip")
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(np, "savez_compressed", boom)
    with pytest.raises(OSError):
        m.save(p)
    assert p.read_bytes() == before and os.listdir(tmp_path) == ["m.npz"]
    monkeypatch.undo()
    assert m.save(tmp_path / "other") == tmp_path / "other.npz"  # API keeps numpy's suffix rule


@pytest.mark.parametrize("cmd", ["map", "contours", "simulate"])
def test_cli_output_file_rules(capsys, tmp_path, cmd):
    (tmp_path / "d").mkdir()
    base = {
        "map": [
            "map",
            "--mu",
            "100",
            "--xi-dot",
            "1",
            "--grid",
            "2",
            "--samples",
            "10",
            "--jobs",
            "1",
            "--quiet",
            "--out",
        ],
        "contours": ["contours", "--mu", "5", "--grid", "2", "--max-amplitude", "2", "--out"],
        "simulate": ["simulate", *DIMLESS, "--xi-dot", "1", "--samples", "10", "--trace"],
    }[cmd]
    flag = base[-1]
    bad = [str(tmp_path / "d") + os.sep, str(tmp_path / "d"), os.devnull, "", str(tmp_path / "missing" / "x.npz")]
    if cmd != "simulate":
        bad.append(str(tmp_path / "x.txt"))  # maps are .npz files, written exactly where asked
    for path in bad:
        err = refused(capsys, *base, path)
        assert flag in err
    assert sorted(os.listdir(tmp_path)) == ["d"] and os.listdir(tmp_path / "d") == []
    assert not os.path.exists(os.devnull + ".npz") and not os.path.exists("..npz")
    good = tmp_path / ("ok.npz" if cmd != "simulate" else "ok.csv")
    code, _, err = run(capsys, *base, str(good))
    assert code == 0, err
    assert sorted(os.listdir(tmp_path)) == ["d", good.name]


def test_cli_output_folder_rules(capsys, tmp_path):
    f = tmp_path / "file"
    f.write_text("x")
    assert "not a folder" in refused(capsys, "report", *IMPULSE, "--out", str(f))
    assert "not a folder" in refused(capsys, "validate", "--quick", "--out", str(f))
    assert "does not exist" in refused(capsys, "report", *IMPULSE, "--out", str(tmp_path / "no" / "new"))
    assert "--out" in refused(capsys, "validate", "--quick", "--out", "")
    assert sorted(os.listdir(tmp_path)) == ["file"]


def test_report_interrupted_leaves_folder_untouched(tmp_path, monkeypatch):
    import dfa.studies.design
    import dfa.studies.design_document

    (tmp_path / "keep.txt").write_text("mine")

    def fail(*a, **k):
        raise KeyboardInterrupt

    # after the PNGs and the Markdown were written into the staging folder
    monkeypatch.setattr(dfa.studies.design_document, "design_html", fail)
    monkeypatch.setattr(dfa.studies.design, "first_unstable_speed", lambda *a, **k: 3.0)
    small_design_searches(monkeypatch)  # the report's numbers are not read: small searches and map
    with pytest.raises(KeyboardInterrupt):
        dfa.design_report(
            dfa.get_device("impulse"), velocity=0.05, out_dir=tmp_path, fmt="both", progress=False, samples=500,
            map_grid=3,
        )  # fmt: skip
    assert sorted(os.listdir(tmp_path)) == ["keep.txt"]


# ------------------------------------------------------------------ 4. --jobs
def test_cli_jobs_above_cores_refused(capsys, tmp_path):
    too_many = str((os.cpu_count() or 1) + 1)
    err = refused(
        capsys,
        "map",
        "--mu",
        "100",
        "--xi-dot",
        "1",
        "--grid",
        "4",
        "--jobs",
        too_many,
        "--out",
        str(tmp_path / "m.npz"),
    )
    assert "--jobs" in err and "cores" in err
    assert "--jobs" in refused(capsys, "validate", "--quick", "--jobs", too_many, "--out", str(tmp_path / "v"))
    assert "--jobs" in refused(
        capsys, "map", "--mu", "100", "--xi-dot", "1", "--jobs", "0", "--out", str(tmp_path / "m.npz")
    )
    assert os.listdir(tmp_path) == []
    with pytest.raises(DFAValueError, match="cores"):
        dfa.stability_map(100.0, [1.0], grid=2, samples=10, n_jobs=int(too_many), progress=False)


# ------------------------------------------------------------------ 5. interruption and closed pipes
import threading  # noqa: E402

main_thread_only = pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signal handlers need the main thread"
)


@main_thread_only
@pytest.mark.parametrize("sig, code", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_cli_signal_during_map_nothing_written(capsys, tmp_path, monkeypatch, sig, code):
    import dfa.analysis.maps as maps

    def interrupted(*a, **k):
        os.kill(os.getpid(), sig)
        time.sleep(5)  # the handler raises before this ends
        raise AssertionError("signal not delivered")

    monkeypatch.setattr(maps, "_run_chunk", interrupted)
    out = tmp_path / "m.npz"
    rc, _, err = run(
        capsys,
        "map",
        "--mu",
        "100",
        "--xi-dot",
        "1",
        "--grid",
        "2",
        "--samples",
        "10",
        "--jobs",
        "1",
        "--quiet",
        "--out",
        str(out),
    )
    assert rc == code
    assert err == f"dfa: interrupted ({signal.Signals(sig).name}); nothing written\n"
    assert os.listdir(tmp_path) == []
    assert signal.getsignal(signal.SIGTERM) is not dfa.cli.app.on_signal  # handlers restored


@main_thread_only
def test_cli_signal_while_writing_trace(capsys, tmp_path, monkeypatch):
    def interrupted(*a, **k):
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5)

    monkeypatch.setattr(np, "savetxt", interrupted)
    rc, _, err = run(
        capsys, "simulate", *DIMLESS, "--xi-dot", "1", "--samples", "50", "--trace", str(tmp_path / "t.csv")
    )
    assert rc == 143 and err == "dfa: interrupted (SIGTERM); nothing written\n"
    assert os.listdir(tmp_path) == []


@main_thread_only
def test_cli_signal_after_a_file_was_kept(capsys, tmp_path, monkeypatch):
    import dfa.cli.maps as cli

    def interrupted(obj):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(5)

    monkeypatch.setattr(cli, "emit", interrupted)
    out = tmp_path / "m.npz"
    rc, _, err = run(
        capsys,
        "map",
        "--mu",
        "100",
        "--xi-dot",
        "1",
        "--grid",
        "2",
        "--samples",
        "10",
        "--jobs",
        "1",
        "--quiet",
        "--json",
        "--out",
        str(out),
    )
    assert rc == 130 and err == f"dfa: interrupted (SIGINT); kept {out} (complete)\n"
    assert dfa.load_map(out).outcome.shape == (1, 2, 2)


def _children_gone(pgid: int, timeout: float = 120.0) -> bool:
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        try:
            os.killpg(pgid, 0)
        except ProcessLookupError:
            return True
        time.sleep(0.1)
    return False


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs 2 cores")
def test_cli_sigterm_stops_joblib_workers(tmp_path):
    out = tmp_path / "m.npz"
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(
        DFA
        + [
            "map",
            "--mu",
            "100",
            "--xi-dot",
            "1",
            "2",
            "--grid",
            "200",  # about 10 s on 2 cores: long enough to still run at the signal
            "--samples",
            "5000000",
            "--delay",
            "1",  # d > 0: no exact period skipping, so the map lasts well past the signal
            "--force",
            "--jobs",
            "2",
            "--progress",
            "--out",
            str(out),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
        start_new_session=True,
    )
    # wait for the progress bar: the workers are running
    first = proc.stderr.read(1)
    assert first, "no progress bar"
    proc.send_signal(signal.SIGTERM)  # wherever it lands (dfa._signals): the run lasts ~10 s, longer under load
    _, err = proc.communicate(timeout=300)
    text = (first + err).decode()
    assert proc.returncode == 143, text
    assert text.replace("\r", "\n").strip().splitlines()[-1] == "dfa: interrupted (SIGTERM); nothing written"
    assert "Traceback" not in text
    assert os.listdir(tmp_path) == []
    assert _children_gone(proc.pid), "joblib workers still running"


# Issue 27 §2: a signal while the interpreter exits (worker threads or the process pool still finishing) killed dfa
# by the signal (status -15), or printed "Exception ignored in threading._shutdown ... KeyboardInterrupt" and
# exited 0, because main() restored the default handlers before the process ended.
# The worker thread runs until the test closes the process's stdin: the signal is sure to arrive while the
# interpreter waits for it, however slow the machine (no sleep stands for "still running").
_LATE = """
import os, signal, sys, threading, time
import dfa.cli.devices as devices
from dfa.cli import main


def run(args):
    threading.Thread(target=sys.stdin.buffer.read).start()  # a worker still running when main returns
    if {interrupt}:
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(60)  # the handler raises before this ends
    print("done")
    return 0

devices.run = run
sys.argv = ["dfa", "devices"]
code = main()
print("returned", flush=True)
sys.exit(code)
"""


def _late(interrupt: bool) -> subprocess.Popen:
    code = _LATE.format(interrupt=interrupt)
    return subprocess.Popen(
        [sys.executable, "-c", code], stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_cli_second_signal_while_exiting_keeps_the_first_code():
    proc = _late(interrupt=True)
    assert proc.stdout.readline() == b"returned\n"  # main() has returned; the thread runs until stdin closes
    proc.send_signal(signal.SIGTERM)
    out, err = proc.communicate(timeout=120)  # closes stdin: the thread ends, then the interpreter
    assert proc.returncode == 130 and out == b"", (proc.returncode, out, err)
    assert err == b"dfa: interrupted (SIGINT); nothing written\n", err


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_cli_signal_after_the_run_exits_with_one_line():
    proc = _late(interrupt=False)
    assert proc.stdout.readline() == b"done\n"
    assert proc.stdout.readline() == b"returned\n"  # main() has returned; the thread runs until stdin closes
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, (proc.returncode, err)
    assert err == b"dfa: interrupted (SIGINT); nothing written\n", err


# dfa with its thread pool's tasks held at a gate that opens when the test closes stdin, and markers on stdout:
# "working" when the first task starts, "joining" when a pool waits for its workers. The test sends SIGINT once
# the run works and SIGTERM while the interrupted pool is joined: each lands where it is meant to, however
# loaded the machine (no sleep stands for "still running").
_GATED = """
import sys, threading
from concurrent.futures import ThreadPoolExecutor

gate, said = threading.Event(), set()

def say(word):
    if word not in said:
        said.add(word)
        print(word, flush=True)

def opener():
    sys.stdin.buffer.read()
    gate.set()

threading.Thread(target=opener, daemon=True).start()
submit, shutdown = ThreadPoolExecutor.submit, ThreadPoolExecutor.shutdown

def gated(fn):
    def task(*args, **kwargs):
        say("working")
        gate.wait()
        return fn(*args, **kwargs)
    return task

def joining(self, *args, **kwargs):
    say("joining")
    return shutdown(self, *args, **kwargs)

ThreadPoolExecutor.submit = lambda self, fn, *a, **k: submit(self, gated(fn), *a, **k)
ThreadPoolExecutor.shutdown = joining
from dfa.cli import main
sys.argv = ["dfa"] + sys.argv[1:]
sys.exit(main())
"""


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs 2 cores")
@pytest.mark.parametrize(
    "argv",
    [
        ["map", "--mu", "100", "--xi-dot", "1", "2", "--grid", "8", "--samples", "2000", "--jobs", "2"]
        + ["--out", "m.npz"],
        ["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "6", "--jobs", "2", "--plot", "z.png"],
    ],
    ids=["map", "zwidth"],
)
def test_cli_sigint_then_sigterm_exits_130(tmp_path, argv):
    cmd = [sys.executable, "-c", _GATED, *argv, "--progress"]
    proc = subprocess.Popen(cmd, stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, cwd=tmp_path)
    assert proc.stdout.readline() == b"working\n"  # the thread pool runs (its tasks wait at the gate)
    proc.send_signal(signal.SIGINT)
    assert proc.stdout.readline() == b"joining\n"  # interrupted: the pool waits for its running tasks
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=300)  # closes stdin: the gate opens, the running tasks end
    text = err.decode()
    assert proc.returncode == 130, text
    assert text.replace("\r", "\n").strip().splitlines()[-1] == "dfa: interrupted (SIGINT); nothing written", text
    assert "Traceback" not in text and "Exception ignored" not in text
    assert os.listdir(tmp_path) == []


def test_cli_closed_pipe_ends_quietly():
    proc = subprocess.Popen(DFA + ["devices"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # like `dfa devices | head -0`: the reader is gone before dfa writes
    err = proc.stderr.read()
    proc.wait(timeout=60)
    assert proc.returncode in (0, 141) and b"Traceback" not in err and b"BrokenPipe" not in err, err


# ------------------------------------------------------------------ 6. resources
@pytest.mark.parametrize(
    "argv, word",
    [
        (["map", "--mu", "100", "--xi-dot", "1", "--grid", "100000", "--out", "{tmp}/m.npz"], "--grid"),
        (["contours", "--mu", "5", "--grid", "100000"], "--grid"),
        (["contours", "--mu", "5", "--grid", "10", "--max-amplitude", "1e13"], "--max-amplitude"),
        (["simulate", *DIMLESS, "--xi-dot", "1", "--samples", "10000000000"], "--force"),
    ],
)
def test_cli_resources_refused_up_front(capsys, tmp_path, argv, word):
    err = refused(capsys, *[a.replace("{tmp}", str(tmp_path)) for a in argv])
    assert word in err and ("memory" in err or "s (estimated" in err)
    assert os.listdir(tmp_path) == []


def test_memory_estimates_and_limit(monkeypatch):
    from dfa.analysis.contours import contour_memory_bytes
    from dfa.analysis.maps import map_memory_bytes

    assert map_memory_bytes(100000, 1) > 1e12 and map_memory_bytes(10, 2) < 1e5
    assert contour_memory_bytes(100000, 200) > 1e12
    monkeypatch.setattr(_io, "available_memory", lambda: 1000)
    with pytest.raises(DFAValueError, match=r"grid = 10 is too large.*50%"):
        dfa.stability_map(100.0, [1.0], grid=10, samples=10, n_jobs=1, progress=False)
    monkeypatch.undo()
    assert _io.available_memory() > 0


def test_cli_simulate_force_runs_beyond_the_estimate(capsys, monkeypatch):
    import dfa.cli.output as cli

    monkeypatch.setattr(cli, "SIMULATE_TIME_LIMIT", 1e-6)
    assert "--force" in refused(capsys, "simulate", *DIMLESS, "--xi-dot", "1", "--samples", "100")
    code, out, _ = run(capsys, "simulate", *DIMLESS, "--xi-dot", "1", "--samples", "100", "--force", "--json")
    assert code == 0 and json.loads(out)["samples"] == 100


# ------------------------------------------------------------------ 7. preload_position (section 5)
def test_preload_position_huge_energy_returns(capsys):
    # was: never returned (the cell search stepped by 1 below the float spacing)
    x = preload_position(7e16, 7e16)
    e = 0.5 * 7e16 * 7e16**2
    assert stored_energy(x, 0.0, 1.0) == pytest.approx(e, rel=1e-15)
    assert x == pytest.approx(math.sqrt(2 * e), rel=1e-15)
    err = refused(
        capsys, "simulate", "--mu", "7e16", "--beta", "0.1", "--sigma", "0.1", "--xi-dot", "7e16", "--preload"
    )
    assert "--preload" in err and "bound" in err
    with pytest.raises(DFAValueError, match="overflows"):
        preload_position(1e300, 1e10)


@given(st.floats(1e-6, 1e6), st.floats(-1e8, 1e8))
@example(1.0, 1.0)
@example(1e6, 1e8)
@example(1e-6, 1e-200)
@example(2.0, 1.0)  # E = 1 inside the cell [1, 2)
def test_preload_position_closed_form_matches_stored_energy(mu, v):
    x = preload_position(mu, v)
    e = 0.5 * mu * v * v
    assert x >= 0.0
    assert stored_energy(x, 0.0, 1.0) == pytest.approx(e, rel=4e-16 * max(1.0, x), abs=1e-300)
    k = math.floor(x)
    assert 0.5 * k * k <= e * (1 + 1e-15)  # ξ0 lies in the cell that holds E (H_c(k) = k²/2)


def test_preload_position_tiny_energies():
    assert preload_position(1.0, 1e-170) == 0.0  # 2E underflows: the exact answer rounds to 0
    assert preload_position(1.0, 1e-100) == 1e-200  # first cell: ξ0 = E/(1/2) = ξ'0²
    assert preload_position(100.0, 0.05) == pytest.approx(0.25, rel=1e-15)


# ------------------------------------------------------------------ 8. numba cache
def test_numba_cache_dir_not_writable_falls_back(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("x")
    env = dict(
        os.environ, NUMBA_CACHE_DIR=str(blocker / "cache")
    )  # under a regular file: never writable, even for root
    proc = subprocess.run(
        DFA
        + ["simulate", "--mu", "100", "--beta", "0.1", "--sigma", "0.3", "--xi-dot", "2", "--samples", "200", "--json"],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
        cwd=str(tmp_path),
    )
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["samples"] == 200


# ------------------------------------------------------------------ found while hardening (another branch fixes it)
def test_eq11_max_passive_velocity_delta_k60_counterexample():
    # K = 60 N/m is just above 2b/T = 59.99999999999999 for the Delta: KT/2 − b rounded to 1.7e-18 and
    # max_passive_velocity claimed 5.08e17 m/s where eq. 6 already failed at 3.97e17 m/s; it is now the
    # criterion's own critical speed.
    dev = dfa.get_device("Delta").device
    v = dfa.max_passive_velocity(dev, 60.0)
    assert dfa.device_criterion(dev, 60.0, v * (1 - 1e-9)).passive


def test_cli_map_huge_samples_refused(capsys, tmp_path):
    # found by the fuzz test: `dfa map --samples 999999999999999999` ran for hours, uninterruptibly per point
    err = refused(
        capsys,
        "map",
        "--mu",
        "100",
        "--xi-dot",
        "1",
        "--grid",
        "2",
        "--samples",
        "999999999999999999",
        "--jobs",
        "1",
        "--out",
        str(tmp_path / "m.npz"),
    )
    assert "--samples" in err and "--force" in err
    err = refused(
        capsys,
        "map",
        "--mu",
        "100",
        "--xi-dot",
        "1",
        "--grid",
        "20000",
        "--jobs",
        "1",
        "--out",
        str(tmp_path / "m.npz"),
    )
    assert "--grid 20000" in err and " h " in err
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("argv", [["--period", "1e200"], ["--resolution", "1e-310", "--stiffness", "1e-20"]])
def test_cli_table1_groups_without_float_exceptions(capsys, argv):
    # found by the fuzz test: T² overflowed (OverflowError) and K·Δ underflowed to 0 (ZeroDivisionError)
    err = refused(capsys, "params", *IMPULSE, *argv)
    assert "is invalid" in err and argv[0] in err


@pytest.mark.parametrize(
    "cmd",
    [
        ["stiffness", "--device", "phantom", "--xi-dot", "1"],
        ["check", "--device", "phantom", "--xi-dot", "1"],
        ["simulate", "--mu", "100", "--beta", "1", "--sigma", "1", "--xi-dot", "1"],
    ],
)
def test_cli_huge_delay_refused_with_the_limit(capsys, cmd):
    # found by the fuzz test: --delay 999999999999999999 reached numpy's "array is too big" in dfa.analysis.linear
    err = refused(capsys, *cmd, "--delay", "999999999999999999")
    assert "delay" in err and str(dfa.checks.MAX_DELAY) in err
    with pytest.raises(dfa.errors.DFAValueError, match="at most"):
        dfa.analysis.linear.critical_stiffness(0.1, 1.0, 1e-3, wall=Wall.of(1.0, delay=dfa.checks.MAX_DELAY + 1))


# ------------------------------------------------------------------ 9. limit-cycle time budget (eq. 36 search)
def _no_cycle_missed_below(part, full):
    """Every cycle of the full search below the partial result's max_amplitude is in the partial result."""
    got = {(round(c.amplitude, 9), round(c.frequency, 9)) for c in part.cycles}
    below = [c for c in full.cycles if c.amplitude < part.max_amplitude]
    return all((round(c.amplitude, 9), round(c.frequency, 9)) in got for c in below)


def test_eq36_time_budget_hit_is_incomplete_and_says_so():
    from dfa.analysis.cycles import DEFAULT_TIME_BUDGET, SearchStatus

    p = dfa.Params(5.0, 0.1, 0.3)
    full = dfa.limit_cycles(p)
    assert full.complete and DEFAULT_TIME_BUDGET == 10.0 and len(full.cycles) == 2
    part = dfa.limit_cycles(p, time_budget=1e-9)
    assert not part.complete and part.status is SearchStatus.TIME_BUDGET
    ev = part.search
    assert (ev.time_budget, ev.pieces_searched, ev.pieces_total, ev.reached) == (1e-9, 0, 1, part.max_amplitude)
    assert search_text(part).startswith("incomplete: time budget of 1e-09 s hit after searching 0 of 1 pieces")
    assert part.to_dict()["search"]["pieces_total"] == 1
    assert part.search_bound is None and part.cycles == ()
    assert 0.0 < part.max_amplitude < full.cycles[0].amplitude and _no_cycle_missed_below(part, full)
    assert part.to_dict()["status"] == "time_budget" and part.to_dict()["complete"] is False
    g = dfa.growth_threshold(p, time_budget=1e-9)
    assert g.amplitude is None and "time budget of 1e-09 s" in growth_meaning(g)
    for bad in (0, -1.0, math.nan, math.inf, "10", None):
        with pytest.raises(DFAError, match="time_budget"):
            dfa.limit_cycles(p, time_budget=bad)


def test_eq36_time_budget_stops_between_pieces(monkeypatch):
    # two pieces of the phase curve (delay 2): a clock that passes the deadline after the first piece
    import dfa.analysis.cycles.solve as cycles

    p = dfa.Params(100.0, 0.2, 0.3)
    full = dfa.limit_cycles(p, wall=WallParams.of(delay=2))
    ticks = iter(range(10**6))
    monkeypatch.setattr(cycles.time, "monotonic", lambda: float(next(ticks)))
    part = dfa.limit_cycles(
        p, time_budget=1.5, wall=WallParams.of(delay=2)
    )  # deadline 1.5: the check at 1 passes, at 2 stops
    assert not part.complete and (part.search.pieces_searched, part.search.pieces_total) == (1, 2)
    assert "after searching 1 of 2 pieces" in search_text(part)
    assert 0 < len(part.cycles) < len(full.cycles) and _no_cycle_missed_below(part, full)
    assert all(c in full.cycles for c in part.cycles)


def test_cli_limit_cycles_time_budget(capsys):
    code, out, _ = run(capsys, "limit-cycles", *DIMLESS, "--time-budget", "1e-9")
    assert code == 0 and "search incomplete: time budget of 1e-09 s hit" in out
    assert "no limit cycle predicted" not in out
    code, out, _ = run(capsys, "limit-cycles", *DIMLESS, "--time-budget", "1e-9", "--json")
    d = json.loads(out)
    assert code == 0 and d["complete"] is False and d["status"] == "time_budget"
    for v in ("0", "-1"):
        assert "--time-budget" in refused(capsys, "limit-cycles", *DIMLESS, f"--time-budget={v}")
    assert "--max-amplitude" in refused(capsys, "limit-cycles", *DIMLESS, "--max-amplitude=0")
    code, out, _ = run(capsys, "limit-cycles", *DIMLESS, "--time-budget", "30")
    assert code == 0 and "incomplete" not in out


# ------------------------------------------------------------------ 10. found by the API fuzz (tests/test_api_fuzz.py)
@pytest.mark.parametrize("device", ["delta", 0.0, None, dfa.get_device("delta")])
def test_eq11_device_criterion_needs_a_device(device):
    # issue 17: "'str' object has no attribute 'params'" (AttributeError) from device_criterion
    with pytest.raises(DFATypeError, match="^device = .*dfa.Device"):
        dfa.device_criterion(device, 1000.0, 0.1)


@pytest.mark.parametrize(
    "kw, kind",
    [
        ({"sigma": ""}, DFATypeError),
        ({"sigma": {}}, DFATypeError),
        ({"xi_dot": 10**400}, DFAValueError),
        ({"xi_dot": [1.0, 10**400]}, DFAValueError),
        ({"beta": [0.1, math.nan]}, DFAValueError),
        ({"beta": 1j}, DFATypeError),
        ({"quantized": "yes"}, DFATypeError),
        ({"delay": math.inf}, DFAValueError),
        ({"delay": 10**400}, DFAValueError),
    ],
)
def test_eq6_classify_region_refuses_non_numbers(kw, kind):
    # issue 17: "could not convert string to float", OverflowError and ambiguous truth values from classify_region
    args = {"beta": [0.1, 0.6], "sigma": [0.7, 0.7], "xi_dot": 1.0, **kw}
    with pytest.raises(kind, match=f"^{next(iter(kw))}"):
        dfa.classify_region(**args)
    assert dfa.classify_region(**{"beta": [0.1, 0.6], "sigma": [0.7, 0.7], "xi_dot": 1.0}).tolist() == ["d", "a"]


@pytest.mark.parametrize("velocity", ["", 10**400, [0.1, math.inf], None, "0.1"])
def test_eq11_k_max_criterion_refuses_non_numbers(velocity):
    with pytest.raises(DFAError, match="^velocity"):
        dfa.k_max_criterion(dfa.get_device("delta").device, velocity)


@pytest.mark.parametrize("m", [1e-173, 1e-151, 1e-300])
def test_eq41_quantizer_df_tiny_amplitude_is_2_over_pi_m(m):
    # found by the API fuzz: M² underflowed and D(1e-173) returned inf (it is 2/(πM) = 6.4e172)
    assert dfa.quantizer_df(m) == pytest.approx(2.0 / (math.pi * m), rel=1e-15)
    assert dfa.quantizer_df(np.array([m, 0.5]))[0] == pytest.approx(2.0 / (math.pi * m), rel=1e-15)


@pytest.mark.parametrize(
    "call",
    [
        lambda: dfa.quantizer_df(5e-324),
        lambda: dfa.quantizer_df(["a"]),
        lambda: dfa.quantizer_df(np.array(["a"])),
        lambda: dfa.quantizer_df(10**400),
        lambda: dfa.coulomb_df(1e-320, 1.0),
        lambda: dfa.coulomb_df("x", 1.0),
        lambda: dfa.coulomb_df(10**400, 0.0),
        lambda: dfa.coulomb_equivalent_damping(1.0, 1e-200, 1e-200),
    ],
)
def test_eq41_describing_functions_refuse_what_they_cannot_compute(call):
    # issue 17: "could not convert string to float" and OverflowError from the describing functions
    with pytest.raises(DFAError, match="^(amplitude|omega)"):
        call()


@pytest.mark.parametrize("mu", [1e12, 1e14, 1e16, 1e-200, 1e-20])
def test_gil_beta_critical_outside_its_reliable_range_refused(mu):
    # found by the API fuzz: μ = 1e12 gave 0.4991 (the true value is 0.5 − 4e-14), μ >= 1e14 raised
    # "please report this as a bug", μ = 1e-200 a ZeroDivisionError
    with pytest.raises(DFAValueError, match="^mu = .*exact linear bound"):
        dfa.gil_beta_critical(mu)
    assert 0.5 - dfa.gil_beta_critical(1e10) == pytest.approx(1 / 24 / 1e10, rel=1e-3)  # the asymptote ½ − 1/(24μ)


@pytest.mark.parametrize(
    "kw, kind, name",
    [
        ({"overrides": np.array([1.0, 2.0])}, DFATypeError, "overrides"),  # was: ambiguous truth value
        ({"overrides": 5e-324}, DFATypeError, "overrides"),  # was: AttributeError 'items'
        ({"flags": 1.0}, DFATypeError, "flags"),  # was: TypeError dict | float
        ({"name": 1.0}, DFATypeError, "name"),
        ({"name": "delta", "label": 1.0}, DFATypeError, "label"),
        ({"name": "delta", "rotary": "yes"}, DFATypeError, "rotary"),
        ({"name": "delta", "counts": 10**400}, DFAValueError, "counts"),  # was: OverflowError in 1/counts
    ],
)
def test_resolve_device_refuses_hostile_arguments(kw, kind, name):
    # found by the API fuzz: resolve_device raised ValueError, AttributeError, TypeError and OverflowError
    with pytest.raises(kind, match=f"^{name}"):
        dfa.resolve_device(**kw)
    assert dfa.resolve_device("delta", counts=40_000).device.resolution == pytest.approx(2.5e-5)


@pytest.mark.parametrize("kw", [{"rotary": np.float64("nan")}, {"rotary": "yes"}, {"name": 3}, {"name": None}])
def test_device_refuses_a_name_or_rotary_flag_of_the_wrong_type(kw):
    # found by the API fuzz: Device(..., rotary=nan) was built (a NaN in a record with no status)
    with pytest.raises(DFATypeError, match=f"^{next(iter(kw))} = "):
        dfa.Device(1.0, 0.0, 0.0, 1e-5, 1e-3, **kw)
    assert dfa.Device(1.0, 0.0, 0.0, 1e-5, 1e-3, rotary=np.bool_(True)).rotary is True


def test_stiffness_response_takes_a_scalar_speed_and_refuses_text():
    # found by the API fuzz: velocity=1.0 raised IndexError (a 0-d array indexed), "x" a bare ValueError
    dev = dfa.get_device("delta").device
    r = dfa.stiffness_response(dev, velocity=1.0)
    assert r.velocity.tolist() == [1.0] and r.k_max.shape == (1,)
    for bad, kind in (("x", DFATypeError), (10**400, DFAValueError), ([0.1, 0.0], DFAValueError), ([], DFAValueError)):
        with pytest.raises(kind, match="^velocity"):
            dfa.stiffness_response(dev, velocity=bad)


@pytest.mark.parametrize(
    "kw, kind, name",
    [
        ({"v_top": ""}, DFATypeError, "v_top"),  # was: TypeError float > str
        ({"v_top": np.array([1.0, 2.0])}, DFATypeError, "v_top"),  # was: ambiguous truth value
        ({"v_top": 5e-324}, DFAValueError, "v_top"),  # was: "Geometric sequence cannot include zero"
        ({"speeds": 7632098863}, DFAValueError, "speeds"),  # was: numpy MemoryError (57 GiB)
        ({"grid": 10**6}, DFAValueError, "grid"),
        ({"max_samples": "i?"}, DFATypeError, "max_samples"),
    ],
)
def test_stiffness_speed_chart_refuses_hostile_arguments(kw, kind, name):
    # found by the API fuzz: stiffness_speed_chart raised TypeError, ValueError and MemoryError
    with pytest.raises(kind, match=f"^{name}"):
        dfa.stiffness_speed_chart(dfa.get_device("delta").device, **kw)


def _record_kwargs(cls):
    import dataclasses

    return {
        f.name: 0.0
        for f in dataclasses.fields(cls)
        if f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
    }


@pytest.mark.parametrize("cls", [dfa.KMaxResult, dfa.DesignAnalysis, dfa.StiffnessSpeedChart])
def test_result_records_refuse_fields_of_the_wrong_kind(cls):
    # found by the API fuzz: KMaxResult(device=0.0, ...) and StiffnessSpeedChart(device=[1.0], ...) were built
    # and failed later in as_dict (AttributeError); DesignAnalysis(params=0.0, ...) raised "'float' is not iterable"
    dev = dfa.get_device("delta").device
    kw = _record_kwargs(cls)
    with pytest.raises(DFATypeError, match="^device"):
        cls(**kw)
    extra = {"wall": dfa.Wall(10.0)} if "wall" in kw else {"delay": 0}
    kw.update({"device": dev, **extra} | ({"stiffness": 10.0} if "stiffness" in kw else {}))
    with pytest.raises(DFAError, match=r"^\w+ = "):
        cls(**kw)


def test_klimit_refuses_a_limit_that_is_not_a_number():
    # found by the API fuzz (KMaxResult fields): KSearch("x") raised TypeError from math.isfinite; KLimit replaces
    # KSearch (its status, not a reason sentence, says why a limit is None)
    from dfa.analysis.limits.search import KLimit
    from dfa.results.status import LimitStatus

    with pytest.raises(DFATypeError, match="^value"):
        KLimit("x")
    with pytest.raises(DFAValueError, match="^value"):
        KLimit(math.inf)
    assert KLimit(None, status=LimitStatus.NO_STABLE_K).value is None


def test_stiffness_speed_chart_record_validates_its_arrays():
    # found by the API fuzz: StiffnessSpeedChart(speeds=0.0, ...) was built and as_dict raised "'float' is not iterable"
    dev = dfa.get_device("delta").device
    ok = dict(device=dev, wall=dfa.Wall(1.0), v_top=0.5, stiffness=[1.0, 2.0], v_df=[0.1, math.nan], v_sim=[0.1, 0.2],
              v_rest=[0.1, 0.2], criterion_stiffness=[1.0], v_criterion=[0.3], speeds=[0.1],
              k_linear=1.0, k_colgate=math.inf, k_abbott_okamura=1.0, k_static=2.0)  # fmt: skip
    assert dfa.StiffnessSpeedChart(**ok).to_dict()["v_df"] == [0.1, None]
    # the status follows v_df: a stiffness where the describing function cannot tell makes it df_unknown
    assert dfa.StiffnessSpeedChart(**ok).to_dict()["status"] == "df_unknown"
    assert dfa.StiffnessSpeedChart(**(ok | {"v_df": [0.1, 0.2]})).status == "ok"
    for bad in ({"speeds": 0.0}, {"v_sim": [0.1]}, {"v_rest": [0.1, math.nan]}, {"k_static": "x"}):
        with pytest.raises(DFAError, match=f"^({next(iter(bad))}|v_sim|v_rest|k_static)"):
            dfa.StiffnessSpeedChart(**(ok | bad))


# ------------------------------------------------------------------ 11. progress bars: stderr, a terminal or --progress
MAP_SMALL = ["map", "--mu", "100", "--xi-dot", "1", "--grid", "3", "--samples", "200", "--jobs", "1", "--out"]


@pytest.mark.parametrize(
    "extra, shown",
    [([], False), (["--progress"], True), (["--progress", "--quiet"], False), (["--json"], False)],
)
def test_cli_progress_bar_policy(capsys, tmp_path, extra, shown):
    code, out, err = run(capsys, *MAP_SMALL, str(tmp_path / "m.npz"), *extra)
    assert code == 0 and ("stability map" in err) == shown, err
    assert "%|" not in out and "run/s" not in out
    if "--json" in extra:
        json.loads(out)


def test_cli_progress_bar_on_a_terminal(capsys, tmp_path, monkeypatch):
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    code, _, err = run(capsys, *MAP_SMALL, str(tmp_path / "m.npz"))
    assert code == 0 and "stability map" in err
    code, out, err = run(capsys, *MAP_SMALL, str(tmp_path / "m.npz"), "--json")
    assert code == 0 and "stability map" not in err and json.loads(out)


def test_cli_contours_and_simulate_progress(capsys, monkeypatch):
    import dfa.analysis.simulation as simulation

    code, out, err = run(capsys, "contours", "--mu", "5", "--grid", "4", "--max-amplitude", "5", "--progress", "--json")
    assert code == 0 and "contours" in err and json.loads(out)["grid"] == [4, 4]
    monkeypatch.setattr(simulation, "CHUNK", 1000)
    argv = ["simulate", *DIMLESS, "--xi-dot", "1", "--samples", "20000", "--json"]
    code, out, err = run(capsys, *argv, "--progress")
    assert code == 0 and "simulate" in err
    code, out2, err = run(capsys, *argv)
    assert code == 0 and err == "" and out2 == out  # the same numbers with and without the bar


def test_fig4_load_map_refuses_missing_and_broken_files(tmp_path):
    # issue 17: a half-written 127-byte .npz did not load (numpy's own errors); now the package's, with the fix
    with pytest.raises(DFAValueError, match="no such file"):
        dfa.load_map(tmp_path / "missing.npz")
    bad = tmp_path / "half.npz"
    bad.write_bytes(b"PK\x03\x04" + b"\0" * 123)
    with pytest.raises(DFAValueError, match="not a complete dfa map file"):
        dfa.load_map(bad)
    with pytest.raises(DFATypeError, match="^path"):
        dfa.load_map(None)
    m = dfa.stability_map(100.0, [2.0], grid=2, samples=50, n_jobs=1, progress=False)
    assert dfa.load_map(m.save(tmp_path / "ok.npz")).to_dict() == m.to_dict()


@pytest.mark.parametrize(
    "kw, word",
    [({"quick": ""}, "quick"), ({"quick": 1}, "quick"), ({"n_jobs": 0}, "n_jobs"), ({"progress": None}, "progress")],
)
def test_validate_refuses_bad_arguments_before_any_work(kw, word, monkeypatch):
    # found by the API fuzz: quick="" ran the full validation (minutes); n_jobs was checked after minutes of work
    import dfa.studies.validation as validation

    monkeypatch.setattr(validation, "cycle_checks", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(DFAError, match=f"^{word}"):
        dfa.validate(**{"quick": True, **kw})


@pytest.mark.parametrize(
    "kw, word", [({"map_grid": 1}, "map_grid"), ({"samples": "1"}, "samples"), ({"out_dir": 3}, "out_dir")]
)
def test_design_report_refuses_bad_arguments_before_any_work(kw, word, tmp_path, monkeypatch):
    import dfa.studies.report as report

    monkeypatch.setattr(report, "design_analysis", lambda *a, **k: pytest.fail("work started"))
    with pytest.raises(DFAError, match=f"^{word}"):
        dfa.design_report(dfa.get_device("delta"), **{"out_dir": tmp_path, "progress": False, **kw})


@pytest.mark.parametrize("amax", ["1e5", "1e308"])
def test_cli_eq36_zoh_at_the_linear_bound_huge_max_amplitude_ends(capsys, amax):
    # issue 17: `limit-cycles --model zoh` at the linear bound ran over 5 minutes with --max-amplitude 1e5 and
    # ended in a traceback with 1e308; now it ends (time budget, 10 s at most per search) with exit 0
    beta = repr(dfa.gil_beta_critical(5.0))
    argv = ["limit-cycles", "--mu", "5", "--beta", beta, "--sigma", "0.3", "--model", "zoh", "--max-amplitude", amax]
    with warnings.catch_warnings():
        warnings.simplefilter(
            "ignore", dfa.analysis.cycles.LimitCycleSearchWarning
        )  # a numerical failure is reported in out
        code, out, err = run(capsys, *argv)
    assert code == 0 and "Traceback" not in err
    assert "incomplete" in out and "no limit cycle predicted" not in out  # never a claim the search cannot back


@pytest.mark.slow
def test_report_too_stiff_writes_the_report(tmp_path, monkeypatch):
    # issue 17: any K above the static limit 2c/Δ crashed `dfa report` (TypeError) after writing its figures
    # (the CLI only parses and calls this; a small map and small searches keep the test short)
    small_design_searches(monkeypatch)
    res = dfa.design_report(
        dfa.get_device("delta"), 60000.0, 0.1, out_dir=tmp_path, fmt="md", progress=False, map_grid=3, samples=500
    )
    md = [p for p in res.paths if str(p).endswith(".md")]
    assert len(md) == 1 and "no passivity guarantee even at rest" in md[0].read_text(encoding="utf-8")


def test_found_by_explore_fuzz():
    # HYPOTHESIS_PROFILE=explore run of tests/test_api_fuzz.py: scipy's "f(a) and f(b) must have different signs",
    # numpy broadcast errors and an ambiguous truth value, each now the package's error or the right answer
    assert dfa.large_cycle_closed_form(2.654260412659872e-53, 0.0, 0.0) == (0.0, math.pi)  # ω = π − 2π²μ: π
    assert dfa.analysis.cycles.large_cycle_frequency(1e-18) == math.pi
    with pytest.raises(DFAValueError, match="^beta = .*rounding of π"):
        dfa.small_cycle_closed_form(0.01, 513061015760152.0, 0.0)
    with pytest.raises(DFAValueError, match="broadcast"):
        dfa.coulomb_equivalent_damping(0.0, np.array([0.5, 1.5, 20.0]), np.array([1.0, 2.0]))
    dev = dfa.get_device("delta").device
    with pytest.raises(DFATypeError, match="^quantized"):
        dfa.device_criterion(dev, 10.0, 1.0, quantized=np.array([1.0, 2.0]))
    with pytest.raises(DFATypeError, match="^quantized"):
        dfa.passivity_criterion(0.6, 0.6, 1.0, quantized="no")
