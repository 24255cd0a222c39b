"""Kernels compiled on first call: ``njit`` without importing numba until a kernel runs.

Importing numba costs about 0.2 s, three times what ``dfa check`` needs for its whole answer, and most
commands never run a kernel. Every kernel of :mod:`dfa.core` is therefore defined with :func:`njit` from
this module: it returns a :class:`Deferred`, which holds the Python function and numba's options and
imports numba, makes the dispatcher (``numba.njit(**options)(py_func)``) and compiles (or loads from the
cache) only when the kernel is first called.

A compiled kernel may call a deferred one: numba sees through a :class:`Deferred` because

- it carries the ``py_func`` and ``targetoptions`` that numba's inlining pass reads, so ``inline="always"``
  still inlines it, and
- :func:`_numba` registers its type with numba (``typeof`` of its dispatcher) before anything compiles, since
  every compilation starts from a :class:`Deferred`'s first call.

One implementation runs: a Python caller calls the compiled dispatcher, never the Python function, except
inside :func:`interpreted`, where a one-shot answer that needs only a few thousand scalar kernel calls (``dfa
stiffness --quick``) runs the same Python source instead of loading numba (about 0.6 s, most of that answer's
time). The source is numba's input unchanged, so both give the same numbers (``tests/test_jit.py`` compares
them bit for bit); where Python raises and the compiled code would not (a float division by zero, an
overflowing ``math.exp``: numba returns inf or NaN), the call is made again compiled.

Examples
--------
>>> import sys
>>> @njit(cache=False)
... def twice(x):
...     return 2.0 * x
>>> twice
Deferred(dfa.core.jit.twice)
>>> twice(1.5)
3.0
>>> "numba" in sys.modules   # imported by the first call
True
"""

from __future__ import annotations

import contextlib
import functools
import threading
from collections.abc import Callable, Iterator
from typing import Any, Generic, ParamSpec, TypeVar, cast, overload

import numpy as np

__all__ = ["njit", "Deferred", "when_numba_loads", "interpreted", "interpreting"]

_REGISTERED: list[bool] = []
_WAITING: list[Callable[[Any], None]] = []
#: One kernel made at a time: kernels are first called from worker threads (one dispatcher each, not one per
#: thread), and the callbacks waiting for numba run once.
_LOCK = threading.RLock()


def _numba() -> Any:
    """numba, imported once, with :class:`Deferred` registered as a type numba can call from compiled code."""
    import numba
    from numba.extending import typeof_impl

    with _LOCK:
        if not _REGISTERED:
            _register(typeof_impl)
            _REGISTERED.append(True)
            while _WAITING:
                _WAITING.pop(0)(numba)
    return numba


def _register(typeof_impl: Any) -> None:
    """Let numba type a :class:`Deferred` as its dispatcher (a compiled kernel calling a deferred one)."""

    def _typeof_deferred(val: Deferred[..., Any], c: Any) -> Any:
        return typeof_impl(val.dispatcher, c)

    typeof_impl.register(Deferred)(_typeof_deferred)


def when_numba_loads(callback: Callable[[Any], None]) -> Callable[[], None]:
    """Call ``callback(numba)`` when the first kernel imports numba (now, if one has).

    The command line's compile note (:func:`dfa.cli.compile_note.compile_note`) listens to numba's compile
    events this way without importing numba for a command that runs no kernel.

    Returns
    -------
    callable
        Withdraws the callback if it has not run yet (else does nothing).
    """
    with _LOCK:
        waiting = not _REGISTERED
        if waiting:
            _WAITING.append(callback)
    if not waiting:
        callback(_numba())

    def withdraw() -> None:
        with _LOCK:
            if callback in _WAITING:
                _WAITING.remove(callback)

    return withdraw


#: Kernel calls :func:`interpreted` still allows: the calls left (0 outside it). Past them, numba loads and the
#: rest of the block runs compiled: interpreting pays only while the work is small.
_INTERPRET_CALLS: list[int] = [0]
#: The calls one :func:`interpreted` block may interpret (``dfa stiffness --quick`` on the catalogue: 3·10⁴-10⁵,
#: 0.1-0.3 s; numba's load is about 0.6 s).
INTERPRET_BUDGET = 400_000


@contextlib.contextmanager
def interpreted(budget: int = INTERPRET_BUDGET) -> Iterator[None]:
    """Run kernels not yet compiled as their Python source inside the block, for at most ``budget`` calls.

    A command answering once with little kernel work (``dfa stiffness --quick``: no simulation) then does not
    load numba; a kernel already compiled in this process stays compiled, and past ``budget`` calls numba loads
    and the rest runs compiled. The numbers are the same either way (module docstring).

    Parameters
    ----------
    budget : int, optional
        Kernel calls interpreted at most (default :data:`INTERPRET_BUDGET`).

    Yields
    ------
    None

    See Also
    --------
    njit : the deferred kernels this applies to.

    Examples
    --------
    >>> @njit(cache=False)
    ... def half(x):
    ...     return 0.5 * x
    >>> with interpreted():
    ...     half(3.0)
    1.5
    >>> half._dispatcher is None     # never compiled
    True
    """
    with _LOCK:
        before = _INTERPRET_CALLS[0]
        _INTERPRET_CALLS[0] = max(before, int(budget))
    try:
        yield
    finally:
        with _LOCK:
            _INTERPRET_CALLS[0] = before


def interpreting(kernel: Deferred[..., Any]) -> bool:
    """Whether a call of ``kernel`` now would run its Python source: inside :func:`interpreted`, within its budget,
    the kernel not compiled yet. A caller with an array form of the same arithmetic runs that instead of a
    kernel's element loop interpreted (:func:`dfa.core.bracket.bracketed_roots`).

    Examples
    --------
    >>> @njit(cache=False)
    ... def half(x):
    ...     return 0.5 * x
    >>> with interpreted():
    ...     interpreting(half)
    True
    >>> interpreting(half)
    False
    """
    return kernel._dispatcher is None and _INTERPRET_CALLS[0] > 0


def _interpret(func: Callable[..., Any], args: tuple[Any, ...], kwargs: dict[str, Any]) -> tuple[bool, Any]:
    """(True, func(*args)) within :func:`interpreted`'s budget, with numpy's floating errors silent as numba's
    are; (False, None) past it or where Python raises and the compiled code would not."""
    if _INTERPRET_CALLS[0] <= 0:
        return False, None
    _INTERPRET_CALLS[0] -= 1
    try:
        with np.errstate(all="ignore"):
            return True, func(*args, **kwargs)
    except (ArithmeticError, ValueError):
        return False, None


#: A kernel's parameters and its return type: a :class:`Deferred` is called as its Python function is.
P = ParamSpec("P")
R = TypeVar("R")


class Deferred(Generic[P, R]):
    """A numba kernel made and compiled on its first call (see the module docstring).

    Parameters
    ----------
    py_func : callable
        The kernel's Python source, compiled unchanged.
    targetoptions : dict
        ``numba.njit``'s options (``cache``, ``inline``, …).
    """

    def __init__(self, py_func: Callable[P, R], targetoptions: dict[str, Any]) -> None:
        self.py_func = py_func
        self.targetoptions = dict(targetoptions)
        self._dispatcher: Any = None
        functools.update_wrapper(self, py_func)

    @property
    def dispatcher(self) -> Any:
        """numba's dispatcher of the kernel (imports numba the first time)."""
        if self._dispatcher is None:
            numba = _numba()
            with _LOCK:
                if self._dispatcher is None:
                    self._dispatcher = numba.njit(**self.targetoptions)(self.py_func)
        return self._dispatcher

    def __call__(self, *args: P.args, **kwargs: P.kwargs) -> R:
        if self._dispatcher is None and _INTERPRET_CALLS[0] > 0:
            done, value = _interpret(self.py_func, args, kwargs)
            if done:
                return cast(R, value)
        return cast(R, self.dispatcher(*args, **kwargs))

    def __getattr__(self, name: str) -> Any:
        # numba's own attributes (signatures, stats, inspect_types, …); only reached for names not set above
        if name.startswith("__") or name == "_dispatcher":
            raise AttributeError(name)
        return getattr(self.dispatcher, name)

    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        # by name when the module holds this kernel under its function's name (workers then share it), else a
        # new Deferred of the same function (``_spring = njit(...)(spring_energy_core)`` in dfa.core.kernel)
        try:
            same = _resolve(self.py_func.__module__, self.py_func.__qualname__) is self
        except (ImportError, AttributeError):
            same = False
        if same:
            return _resolve, (self.py_func.__module__, self.py_func.__qualname__)
        return Deferred, (self.py_func, self.targetoptions)

    def __repr__(self) -> str:
        return f"Deferred({self.py_func.__module__}.{self.py_func.__qualname__})"


def _resolve(module: str, qualname: str) -> Deferred[..., Any]:
    """The kernel ``module.qualname`` (unpickling a :class:`Deferred` finds the module's own)."""
    import importlib

    obj: Any = importlib.import_module(module)
    for part in qualname.split("."):
        obj = getattr(obj, part)
    return cast("Deferred[..., Any]", obj)


@overload
def njit(func: Callable[P, R], **options: Any) -> Deferred[P, R]: ...
@overload
def njit(func: None = None, **options: Any) -> Callable[[Callable[P, R]], Deferred[P, R]]: ...
def njit(
    func: Callable[P, R] | None = None, **options: Any
) -> Deferred[P, R] | Callable[[Callable[P, R]], Deferred[P, R]]:
    """``numba.njit`` deferred to the first call: ``@njit``, ``@njit(cache=True)`` or ``njit(**o)(f)``.

    Parameters
    ----------
    func : callable, optional
        The function, when used as ``@njit`` without options.
    **options
        numba's ``njit`` options, passed on unchanged.

    Returns
    -------
    Deferred or callable
        The deferred kernel, or a decorator making one.
    """
    if func is not None:
        return Deferred(func, options)

    def decorate(f: Callable[P, R]) -> Deferred[P, R]:
        return Deferred(f, options)

    return decorate
