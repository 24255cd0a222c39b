"""Wall stability maps (issue 15, Fig. 4 with a wall controller) and the Z-width run like the spring's map.

One runner (:func:`dfa._parallel.run_in_order`) for every grid of simulations: the map's chunks take the
controller, run in order (the same numbers for any number of jobs or backend, equal point by point to
:func:`dfa.simulate` with the controller), advance a progress bar chunk by chunk, and an interruption
(SIGTERM on the CLI) stops a controller map that is still running, with nothing written. The Z-width
(issue 15, "Parallel, with progress, deterministic for any number of jobs") uses the same runner for its
grid points and for its boundary columns.
"""

import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import dfa.analysis.limits.zwidth as zmod
import dfa.analysis.maps as maps
from dfa._parallel import run_in_order, started_in_order
from dfa.analysis.maps import stability_map
from dfa.analysis.simulation import OUTCOMES, divergence_bound, simulate
from dfa.cli import main
from dfa.model.catalogue import get_device
from dfa.model.wall import WallParams

CTL = WallParams.of(damping=0.3, delay=1, cutoff=0.1, lag=0.5)  # damper, filter, delay and amplifier lag
DFA = [sys.executable, "-c", "import sys; from dfa.cli import main; sys.exit(main())"]


class _Bar:
    """Stands in for tqdm: records the total and every update of each bar created."""

    made: list["_Bar"] = []

    def __init__(self, *args, total=None, **kwargs):
        self.total, self.updates = total, []
        _Bar.made.append(self)

    def update(self, n=1):
        self.updates.append(n)

    def close(self):
        pass


@pytest.fixture
def bars(monkeypatch):
    import tqdm.auto

    _Bar.made = []
    monkeypatch.setattr(tqdm.auto, "tqdm", _Bar)
    return _Bar.made


def _arrays(m):
    return m.outcome, m.amplitude, m.frequency


def test_fig4_controller_map_runs_in_chunks_with_progress(monkeypatch, bars):
    seen = []
    real = maps._run_chunk

    def spy(*task):
        seen.append((task[1].size, task[6]))  # (μ, β, σ, ξ0, ξ′0, samples, wall, …)
        return real(*task)

    monkeypatch.setattr(maps, "_run_chunk", spy)
    m = stability_map(100.0, [1.0, 2.0], grid=4, samples=3000, n_jobs=1, progress=True, wall=CTL)
    assert m.wall == CTL
    assert all(ctl == CTL for _, ctl in seen)  # every chunk (and the warm-up) runs the controller's kernel
    chunks = [size for size, _ in seen[1:]]  # seen[0]: the one-point warm-up that compiles the kernel
    assert len(chunks) > 1 and sum(chunks) == 2 * 4 * 4
    (bar,) = bars
    assert bar.total == 32 and bar.updates == chunks  # one update per chunk as it finishes


def test_fig4_controller_map_same_for_any_jobs_and_backend_and_equal_to_simulate():
    """n_jobs 1, 2 threads and 2 processes give the same arrays, each point equal to simulate(controller=)."""
    kw = dict(grid=3, samples=3000, progress=False, wall=CTL)
    one = stability_map(100.0, [1.0, 2.0], n_jobs=1, **kw)
    for other in (
        stability_map(100.0, [1.0, 2.0], n_jobs=2, **kw),
        stability_map(100.0, [1.0, 2.0], n_jobs=2, backend="processes", **kw),
    ):
        for a, b in zip(_arrays(one), _arrays(other), strict=True):
            assert np.array_equal(a, b, equal_nan=True)
    bound = divergence_bound(0.0, 2.0, 100.0)  # the map's: beyond the fastest start's travel
    for n, v in enumerate(one.xi_dots):
        for i, s in enumerate(one.sigma):
            for j, b in enumerate(one.beta):
                r = simulate(100.0, b, s, v, 3000, bound=bound, record=False, wall=CTL)
                assert r.outcome == OUTCOMES[one.outcome[n, i, j]]
                assert np.array_equal(r.amplitude, one.amplitude[n, i, j], equal_nan=True)
                freq = np.nan if r.frequency is None else r.frequency
                assert np.array_equal(freq, one.frequency[n, i, j], equal_nan=True)


def test_fig4_map_chunks_sized_by_planned_work_same_result(monkeypatch):
    """Chunks hold at most CHUNK_SAMPLES planned samples (a lag costs more): more chunks, the same numbers."""
    chunks = maps._chunks(10, 2, maps._chunk_cost(100, CTL) * 1e6)
    assert [c.tolist() for c in chunks] == [[i] for i in range(10)]  # every point once
    dealt = maps._chunks(10, 1)  # fewer points than 64 chunks: one each
    assert sorted(np.concatenate(maps._chunks(1000, 2)).tolist()) == list(range(1000)) and len(dealt) == 10
    assert maps._chunks(100, 2)[3].tolist() == [3, 35, 67, 99]  # dealt out in turn over 32 chunks
    assert maps._chunk_cost(100, CTL) == 100 * maps.WALL_COST["lag"] and maps._chunk_cost(100, WallParams()) == 100
    assert len(maps._chunks(10_000, 2)) == 32 and len(maps._chunks(10_000, 2, 1.0e5)) == 50  # 10^9 samples / 2e7
    kw = dict(grid=3, samples=2000, n_jobs=2, progress=False, wall=CTL)
    one = stability_map(100.0, [1.0, 2.0], **kw)
    monkeypatch.setattr(maps, "CHUNK_SAMPLES", 1.0)  # one point per chunk
    for a, b in zip(_arrays(one), _arrays(stability_map(100.0, [1.0, 2.0], **kw)), strict=True):
        assert np.array_equal(a, b, equal_nan=True)


def test_parallel_run_in_order_any_workers_and_interruption():
    tasks = [(i,) for i in range(20)]
    want = [i * i for i in range(20)]
    for workers in (1, 2, 3):

        class B:
            n = 0

            def update(self, k):
                self.n += k

        bar = B()
        assert run_in_order(lambda i: i * i, tasks, [2] * 20, workers, "threads", bar) == want and bar.n == 40
    started = []

    def stop_at_third(i):
        started.append(i)
        if i == 2:
            raise KeyboardInterrupt
        time.sleep(0.05)
        return i

    with pytest.raises(KeyboardInterrupt):
        run_in_order(stop_at_third, tasks, [1] * 20, 2, "threads", _Bar())
    assert len(started) < 20  # the tasks not started were cancelled


def test_parallel_started_in_order_collects_run_in_order_results_and_cancels_on_error():
    """Work started ahead (worker processes dispatched on entry) gives run_in_order's results in order; an error
    before collecting leaves the block and cancels the rest."""
    tasks = [(i, 3) for i in range(12)]
    want = run_in_order(pow, tasks, [1] * 12, 1, "threads", _Bar())
    for workers, backend in ((1, "processes"), (2, "threads"), (2, "processes")):
        bar = _Bar()
        with started_in_order(pow, tasks, [2] * 12, workers, backend) as collect:
            assert collect(bar) == want == [i**3 for i in range(12)]
        assert bar.updates == [2] * 12
    with pytest.raises(RuntimeError, match="before collecting"), started_in_order(pow, tasks, [1] * 12, 2, "processes"):
        raise RuntimeError("before collecting")


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
def test_cli_sigterm_stops_a_running_controller_map(tmp_path):
    """A controller map of ~50 CPU-seconds (every point sub-tick chatter, run to the end) stopped after ~1 s."""
    out = tmp_path / "m.npz"
    device = ["--mass", "0.1", "--damping", "0.09", "--coulomb", "0.004", "--resolution", "1e-5", "--period", "1e-3"]
    argv = ["map", *device, "--stiffness", "1000", "--velocity", "0.01", "--virtual-damping", "0.3"]  # μ 100, β_B 0.3
    argv += ["--beta-range", "0.85", "1", "--sigma-range", "0.38", "0.46", "--grid", "20", "--samples", "2000000"]
    argv += ["--jobs", "2", "--progress", "--out", str(out)]
    env = dict(os.environ, PYTHONUNBUFFERED="1")
    proc = subprocess.Popen(DFA + argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    first = os.read(proc.stderr.fileno(), 1)  # the progress bar: the chunks are running (unbuffered: see below)
    assert first, "no progress bar"
    time.sleep(1.0)
    assert proc.poll() is None, "the map ended before the signal: make it longer"
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=120)
    text = (first + err).decode()
    assert proc.returncode == 143, text
    assert text.replace("\r", "\n").strip().splitlines()[-1] == "dfa: interrupted (SIGTERM); nothing written"
    assert "Traceback" not in text, text
    assert "%|" in text, text  # a tqdm bar was shown
    assert os.listdir(tmp_path) == []


# ------------------------------------------------------------------ the Z-width through the same runner
ZDEV = get_device("Impulse Engine").device


def test_zwidth_progress_counts_points_and_boundary_columns(bars):
    z = zmod.z_width(ZDEV, 0.1, grid=3, speeds=1, n_jobs=2, progress=True)
    points, columns = bars
    assert points.total == 9 and sum(points.updates) == 9  # grid points (simulations)
    assert columns.total == 3 and sum(columns.updates) == 3  # one boundary column per B
    assert z.to_dict() == zmod.z_width(ZDEV, 0.1, grid=3, speeds=1, n_jobs=1).to_dict()


main_thread_only = pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signal handlers need the main thread"
)


@main_thread_only
@pytest.mark.parametrize("where, total", [("_run_chunk", 16), ("_column", 4)])
def test_zwidth_ctrl_c_cancels_what_has_not_started(monkeypatch, where, total):
    """Ctrl-C (SIGINT in the main thread) during the grid points or the boundary columns: the rest never starts."""
    real, calls = getattr(zmod, where), []
    monkeypatch.setattr(zmod, "POINTS_PER_CALL", 1)  # one chunk per point: 16 tasks

    def ctrl_c_at_second(*args):
        calls.append(1)
        if len(calls) == 2:
            os.kill(os.getpid(), signal.SIGINT)
        time.sleep(0.3)  # every task takes a while: the main thread cancels the pending ones meanwhile
        return real(*args)

    monkeypatch.setattr(zmod, where, ctrl_c_at_second)
    old = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            zmod.z_width(ZDEV, 0.1, grid=4, speeds=1, n_jobs=2)
    finally:
        signal.signal(signal.SIGINT, old)
    assert len(calls) < total  # the tasks not started when the signal came never ran


@main_thread_only
def test_cli_zwidth_signal_nothing_written(capsys, tmp_path, monkeypatch):
    def interrupted(*a, **k):
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(5)  # the handler raises before this ends
        raise AssertionError("signal not delivered")

    monkeypatch.setattr(zmod, "_column", interrupted)
    png = tmp_path / "z.png"
    argv = ["zwidth", "--device", "impulse", "--velocity", "0.1", "--grid", "3", "--speeds", "1", "--jobs", "1"]
    rc = main([*argv, "--plot", str(png)])
    assert rc == 143 and capsys.readouterr().err == "dfa: interrupted (SIGTERM); nothing written\n"
    assert os.listdir(tmp_path) == []
