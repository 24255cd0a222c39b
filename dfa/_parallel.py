"""Run independent tasks in parallel, results in submission order, with progress and a clean interruption.

One implementation for every grid of simulations (:func:`dfa.stability_map`, spring or controller, and
:func:`dfa.analysis.limits.zwidth.z_width`): ``fn(*task)`` for every task, the results in the order of the tasks whatever
the number of workers or the backend (so a result never depends on them), a progress bar advanced by each
task's size as its result arrives, and on an interruption (Ctrl-C, or SIGTERM routed to KeyboardInterrupt
by the CLI) the tasks not yet started are cancelled and the exception propagates: nothing is returned,
so nothing half-computed can be written.

Backends
--------
``"threads"``: a thread pool in this process (the compiled kernels release the GIL); running tasks finish
before the interruption propagates (a thread cannot be killed), pending ones never start. The pool is started,
waited for and joined with signals deferred (:mod:`dfa._signals`): a signal raises between two waits, never
inside the threading module, whose locks it would leave in a wrong state.
``"processes"``: joblib's process pool (loky); ``"joblib"``: whatever ``joblib.parallel_config`` selects
(e.g. dask). On an interruption the generator is closed, which cancels the pending tasks and stops the
workers.

Examples
--------
>>> class Bar:
...     n = 0
...     def update(self, k):
...         self.n += k
>>> bar = Bar()
>>> run_in_order(pow, [(2, 3), (3, 2)], [1, 1], 2, "threads", bar), bar.n
([8, 9], 2)
"""

from __future__ import annotations

import contextlib
import warnings
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Protocol

import numpy as np

from ._signals import check, deferred

__all__ = [
    "run_in_order",
    "started_in_order",
    "deal",
    "gather",
    "new_bar",
    "progress_bar",
    "NO_BAR",
    "PARALLEL_BACKENDS",
    "POLL_SECONDS",
]

#: Backends of :func:`run_in_order` (module docstring).
PARALLEL_BACKENDS = ("threads", "processes", "joblib")

#: Longest wait for a thread's result before a deferred interruption is raised (s): how soon Ctrl-C is obeyed
#: once the running tasks are done.
POLL_SECONDS = 0.05


def deal(total: int, parts: int) -> list[np.ndarray]:
    """Indices 0 … total − 1 dealt out in turn to ``parts`` chunks (chunk i: i, i + parts, i + 2 parts, …).

    Neighbouring points of a grid cost alike (a region that chatters for the whole run, one that comes to
    rest at once), so dealt-out chunks carry like work and parallel workers finish together. Empty chunks
    are left out (``parts`` > ``total``).

    >>> [c.tolist() for c in deal(5, 2)]
    [[0, 2, 4], [1, 3]]
    """
    return [np.arange(i, total, parts) for i in range(min(parts, total))]


def gather(chunks: Sequence[np.ndarray], parts: Sequence[np.ndarray]) -> np.ndarray:
    """The values of each chunk put back at their indices (the inverse of :func:`deal`).

    >>> gather(deal(5, 2), [np.array([0, 20, 40]), np.array([10, 30])]).tolist()
    [0, 10, 20, 30, 40]
    """
    out = np.empty(sum(c.size for c in chunks), dtype=np.result_type(*parts))
    for c, part in zip(chunks, parts, strict=True):
        out[c] = part
    return out


def new_bar(**kwargs: Any) -> Any:
    """A tqdm progress bar (``tqdm.auto.tqdm(**kwargs)``) created with signals deferred (tqdm starts its monitor
    thread with the first bar: :mod:`dfa._signals`). The caller closes it; :func:`progress_bar` does.

    Parameters
    ----------
    **kwargs
        tqdm's arguments (``iterable``, ``total``, ``desc``, ``unit``, ``disable``, ``leave``, ...).
    """
    from tqdm.auto import tqdm

    with deferred():
        return tqdm(**kwargs)


@contextlib.contextmanager
def progress_bar(**kwargs: Any) -> Iterator[Any]:
    """A tqdm progress bar (``tqdm.auto.tqdm(**kwargs)``), closed however the block ends.

    Created and closed with signals deferred (:mod:`dfa._signals`: tqdm starts and stops a monitor thread), and
    closed when the block ends, an interruption included: a bar made with ``leave=False`` clears its line, so
    what is printed next (the interruption's line) starts on a fresh line, never in the middle of the bar.

    Parameters
    ----------
    **kwargs
        tqdm's arguments (``total``, ``desc``, ``unit``, ``disable``, ``leave``, ...).
    """
    bar = new_bar(**kwargs)
    try:
        yield bar
    finally:
        with deferred():
            bar.close()


class _Progress(Protocol):
    def update(self, n: int) -> Any: ...


class _NoBar:
    """A progress bar that shows nothing (:data:`NO_BAR`)."""

    def update(self, n: int) -> None:
        """Nothing to advance."""


#: The ``bar`` of :func:`run_in_order` for work that shows no progress.
NO_BAR = _NoBar()


def run_in_order(
    fn: Callable[..., Any], tasks: Sequence[tuple], sizes: Sequence[int], workers: int, backend: str, bar: _Progress
) -> list:
    """``[fn(*task) for task in tasks]`` on ``workers`` (1: this thread), advancing ``bar`` by each task's size.

    Parameters
    ----------
    fn : callable
        The work of one task; with ``"processes"`` or ``"joblib"`` it must be picklable (a module-level function).
    tasks : sequence of tuple
        Positional arguments of each call.
    sizes : sequence of int
        Progress units of each task (e.g. simulated points), same length as ``tasks``.
    workers : int
        Parallel workers (>= 1; never more are started than there are tasks).
    backend : {"threads", "processes", "joblib"}
        Where the workers run (module docstring); ignored with one worker.
    bar : object with ``update(n)``
        Progress bar (tqdm, :func:`progress_bar`), or :data:`NO_BAR`.

    Returns
    -------
    list
        The results, in the order of ``tasks`` (independent of ``workers`` and ``backend``).
    """
    if len(sizes) != len(tasks):
        raise ValueError(f"sizes has {len(sizes)} entries for {len(tasks)} tasks: give one size per task")
    if workers == 1 or len(tasks) <= 1:
        results = []
        for task, size in zip(tasks, sizes, strict=True):
            results.append(fn(*task))  # interrupted as any Python code: a signal raises where it lands
            with deferred():
                bar.update(size)
        return results
    if backend == "threads":
        return _threads(fn, tasks, sizes, min(workers, len(tasks)), bar)
    return _joblib(fn, tasks, sizes, min(workers, len(tasks)), backend, bar)


def _threads(fn: Callable[..., Any], tasks: Sequence[tuple], sizes: Sequence[int], workers: int, bar) -> list:
    """The thread pool of :func:`run_in_order`: started, waited for and joined with signals deferred
    (:mod:`dfa._signals`: an interruption is raised between two waits, never inside the threading module)."""
    from concurrent.futures import ThreadPoolExecutor

    results: list = []
    futures: list = []
    with deferred():
        pool = ThreadPoolExecutor(max_workers=workers)
        try:
            for task in tasks:
                futures.append(pool.submit(fn, *task))
                check()
            for size, fut in zip(sizes, futures, strict=True):  # in submission order
                results.append(_result(fut))
                bar.update(size)
        finally:
            for fut in futures:  # on an interruption: drop the tasks not started
                fut.cancel()
            pool.shutdown(wait=True)  # the running ones finish: a thread cannot be stopped
    return results


def _result(fut: Any) -> Any:
    """The result of ``fut``, waited for in steps of :data:`POLL_SECONDS` with an interruption raised between them."""
    from concurrent.futures import wait

    while not wait([fut], timeout=POLL_SECONDS).done:
        check()
    check()
    return fut.result()


def _joblib(fn: Callable[..., Any], tasks: Sequence[tuple], sizes: Sequence[int], workers: int, backend, bar) -> list:
    with _dispatched(fn, tasks, workers, backend) as gen:
        return _collected(gen, sizes, bar)


@contextlib.contextmanager
def _dispatched(fn: Callable[..., Any], tasks: Sequence[tuple], workers: int, backend: str) -> Iterator[Any]:
    """joblib's generator of ``fn(*task)`` in submission order, dispatched to the workers on entry; closed on exit
    (which cancels the tasks not started and stops the workers, quietly on an interruption)."""
    from joblib import Parallel, delayed

    kw = {"backend": "loky"} if backend == "processes" else {}
    gen = None
    try:
        with deferred():  # joblib starts a thread here
            gen = Parallel(n_jobs=workers, return_as="generator", **kw)(delayed(fn)(*task) for task in tasks)
        yield gen
    except BaseException:
        _quiet_cancelled_pool()
        raise
    finally:
        if gen is not None:
            with deferred(), warnings.catch_warnings():  # joblib's count of the cancelled tasks: not news here
                warnings.simplefilter("ignore", UserWarning)
                gen.close()  # on an interruption: cancel the pending tasks, stop the workers


def _collected(gen: Any, sizes: Sequence[int], bar: _Progress) -> list:
    """The results of a :func:`_dispatched` generator, advancing ``bar`` by each task's size as it arrives."""
    results: list = []
    for size, res in zip(sizes, gen, strict=False):  # the generator yields in submission order
        results.append(res)
        with deferred():
            bar.update(size)
    return results


@contextlib.contextmanager
def started_in_order(
    fn: Callable[..., Any], tasks: Sequence[tuple], sizes: Sequence[int], workers: int, backend: str
) -> Iterator[Callable[[_Progress], list]]:
    """:func:`run_in_order` started on entry and collected later: the block gets ``collect(bar)``, which returns
    the results in the order of ``tasks`` (the same as :func:`run_in_order`'s).

    With ``"processes"`` and more than one worker and task, ``workers − 1`` worker processes start on entry and
    take the tasks from the front, one at a time, while this process does something else (a Z-width's planning
    and simulations on threads); ``collect`` then takes tasks from the back in this process until the two meet,
    and waits for the workers' (:class:`_Claims`: each task runs once, in one place). This process is one of the
    workers: one worker process fewer to start (a second or two of imports each). With ``"joblib"`` the tasks
    are dispatched on entry (:func:`_dispatched`); otherwise they run when collected. Leaving the block before
    collecting (an error, an interruption) cancels the tasks not started.

    Parameters
    ----------
    fn, tasks, sizes, workers, backend
        As :func:`run_in_order`.

    Examples
    --------
    >>> with started_in_order(pow, [(2, 3), (3, 2)], [1, 1], 1, "processes") as collect:
    ...     collect(NO_BAR)
    [8, 9]
    """
    if len(sizes) != len(tasks):
        raise ValueError(f"sizes has {len(sizes)} entries for {len(tasks)} tasks: give one size per task")
    if workers == 1 or len(tasks) <= 1 or backend == "threads":
        yield lambda bar: run_in_order(fn, tasks, sizes, workers, backend, bar)
    elif backend == "joblib":
        with _dispatched(fn, tasks, min(workers, len(tasks)), backend) as gen:
            yield lambda bar: _collected(gen, sizes, bar)
    else:
        claims = _Claims(fn, tasks, min(workers, len(tasks)) - 1)
        try:
            yield lambda bar: claims.collect(sizes, bar)
        finally:
            claims.cancel()


#: Seconds an idle worker process of :func:`started_in_order` lives (joblib's reusable loky executor, the one its
#: ``Parallel`` uses; other settings restart its workers): one setting, so that the processes :func:`warm_processes`
#: starts are those the tasks then use.
IDLE_SECONDS = 300


def warm_processes(workers: int, module: str) -> None:
    """Start now the worker processes of :func:`started_in_order` with ``workers`` and ``"processes"`` (``workers −
    1`` of them), each importing ``module`` and running its ``warm_worker()`` when it has one (e.g. loading numba
    and the compiled kernels the tasks call): their start (a second or two) overlaps what this process does until
    the tasks come. Nothing with one worker.

    Parameters
    ----------
    workers : int
        The workers the tasks will be started with (>= 1).
    module : str
        The module whose import the tasks need, e.g. ``"dfa.analysis.limits.zwidth"``.
    """
    if workers <= 1:
        return
    from joblib.executor import get_memmapping_executor

    with deferred():  # loky starts its threads and processes here
        executor = get_memmapping_executor(workers - 1, timeout=IDLE_SECONDS)
        for _ in range(workers - 1):
            executor.submit(_import, module)


def _import(module: str) -> None:
    """Import ``module`` and run its ``warm_worker()`` if it has one (in a worker process, :func:`warm_processes`); at
    the worker's exit, freeze the objects then alive out of the garbage collector (:func:`gc.freeze`), so that its
    interpreter ends without collecting numba's and scipy's objects: the command's own exit waits for its
    workers' (about 0.2 s less, issue 43)."""
    import atexit
    import gc
    import importlib

    warm = getattr(importlib.import_module(module), "warm_worker", None)
    if warm is not None:
        warm()
    atexit.register(gc.freeze)


class _Claims:
    """Tasks taken from the front by worker processes (loky's, one in flight per worker) and from the back by this
    process (:func:`started_in_order`), each task once: a claim is made under a lock."""

    def __init__(self, fn: Callable[..., Any], tasks: Sequence[tuple], processes: int):
        import threading

        from joblib.executor import get_memmapping_executor

        self.fn, self.tasks = fn, tasks
        self.front, self.back, self.stopped = 0, len(tasks), False
        self.futures: dict[int, Any] = {}
        self.lock = threading.RLock()
        with deferred():  # loky starts its threads and processes here
            self.executor = get_memmapping_executor(processes, timeout=IDLE_SECONDS)
            for _ in range(processes):
                self._feed()

    def _feed(self, _done: Any = None) -> None:
        """Submit the next task from the front (called again as each finishes, from loky's thread)."""
        with self.lock:
            if self.stopped or self.front >= self.back:
                return
            i, self.front = self.front, self.front + 1
            fut = self.executor.submit(self.fn, *self.tasks[i])
            self.futures[i] = fut
        fut.add_done_callback(self._feed)

    def _take_back(self) -> int | None:
        with self.lock:
            if self.stopped or self.back <= self.front:
                return None
            self.back -= 1
            return self.back

    def collect(self, sizes: Sequence[int], bar: _Progress) -> list:
        """Every result in the order of the tasks: this process's from the back, then the workers'."""
        results: list = [None] * len(self.tasks)
        while (i := self._take_back()) is not None:
            results[i] = self.fn(*self.tasks[i])  # interrupted as any Python code: a signal raises where it lands
            with deferred():
                bar.update(sizes[i])
        with self.lock:
            ahead = sorted(self.futures.items())
        for i, fut in ahead:
            results[i] = _result(fut)
            bar.update(sizes[i])
        return results

    def cancel(self) -> None:
        """No more tasks: those not started are cancelled (running ones finish in their worker)."""
        with self.lock:
            self.stopped = True
            for fut in self.futures.values():
                fut.cancel()


def _quiet_cancelled_pool() -> None:
    """Drop what loky's manager thread raises from here on: interrupted, its pending tasks are cancelled under it.

    Seen under load: ``KeyError`` in ``ExecutorManagerThread`` when the generator is closed while the thread queues
    a task that was just cancelled, a traceback from a thread beside the interruption's one line. The run is
    ending (the interruption propagates); any other thread's exceptions are reported as before.
    """
    import threading

    previous = threading.excepthook

    def hook(args: Any) -> None:
        if args.thread is not None and args.thread.name == "ExecutorManagerThread":
            return
        previous(args)

    threading.excepthook = hook
