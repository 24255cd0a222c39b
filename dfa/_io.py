"""Atomic file writes, output-path rules and resource limits.

Every file :mod:`dfa` writes goes through :func:`atomic_write_bytes`,
:func:`atomic_write_text` or :func:`atomic_open`: the data are written to a
temporary name in the destination folder and moved into place with
:func:`os.replace`, so a reader (or an interrupted run) sees either the old file
or the complete new one, never a half-written file. On any exception,
``KeyboardInterrupt`` included, the temporary file is removed.

The paths written by this process are recorded (:func:`written_paths`) so that
the command line can say what was kept when it is interrupted.

Examples
--------
>>> import os, tempfile
>>> d = tempfile.mkdtemp()
>>> p = atomic_write_text(os.path.join(d, "a.txt"), "hello")
>>> open(p).read(), sorted(os.listdir(d))
('hello', ['a.txt'])
>>> try:
...     with atomic_open(os.path.join(d, "b.txt"), "w") as fh:
...         _ = fh.write("half")
...         raise RuntimeError("boom")
... except RuntimeError:
...     pass
>>> sorted(os.listdir(d))          # no b.txt, no temporary file left
['a.txt']
"""

from __future__ import annotations

import contextlib
import os
import shutil
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

from .errors import DFAValueError

__all__ = [
    "atomic_write_bytes",
    "atomic_write_text",
    "atomic_open",
    "written_paths",
    "staged_folder",
    "remove_stale",
    "check_output_file",
    "check_output_folder",
    "make_output_folder",
    "FIGURE_SUFFIXES",
    "available_memory",
    "check_memory",
    "MEMORY_FRACTION",
]

#: Paths written (moved into place) by this process, oldest first.
_WRITTEN: list[str] = []

#: Largest share of the available memory one computation may plan to use.
MEMORY_FRACTION = 0.5

#: Memory assumed available when the machine does not say (bytes).
FALLBACK_MEMORY = 2 * 1024**3

_TMP_PREFIX = ".dfa-tmp-"
#: Temporary names tried before giving up when another run's clean-up keeps removing them (:func:`_new_temp`).
_TEMP_TRIES = 10
#: :func:`_hold`'s answer for a name removed before it could be locked.
_GONE = -1

#: The file types a figure is written as, by the suffix of its path (:func:`dfa.render.figures.save_figure`).
FIGURE_SUFFIXES = (".png", ".pdf", ".svg")


def written_paths() -> list[str]:
    """Paths this process has written so far (a copy), oldest first."""
    return list(_WRITTEN)


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike[str], mode: str = "wb", encoding: str | None = None) -> Iterator[IO[Any]]:
    """Context manager yielding a file object whose content replaces ``path`` atomically on success.

    Parameters
    ----------
    path : path-like
        Final destination. Its folder must exist.
    mode : {"wb", "w"}
        Binary or text.
    encoding : str, optional
        Text encoding (default UTF-8 in text mode).
    """
    if mode not in ("wb", "w"):
        raise DFAValueError(f"mode = {mode!r} is invalid: it must be 'wb' or 'w'")
    dest = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(dest))
    tmp, fd, lock = _new_temp(folder, suffix=".part")
    assert fd is not None
    try:
        fh_cm: IO[Any] = (
            os.fdopen(fd, "wb") if mode == "wb" else os.fdopen(fd, "w", encoding=encoding or "utf-8", newline="")
        )
        with fh_cm as fh:
            yield fh
            fh.flush()
            os.fsync(fh.fileno())
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, dest)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    finally:
        _release(lock)
    _WRITTEN.append(dest)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def atomic_write_bytes(path: str | os.PathLike[str], data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically; return the path."""
    with atomic_open(path, "wb") as fh:
        fh.write(data)
    return Path(path)


def atomic_write_text(path: str | os.PathLike[str], text: str, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically; return the path."""
    return atomic_write_bytes(path, text.encode(encoding))


@contextlib.contextmanager
def staged_folder(folder: str | os.PathLike[str]) -> Iterator[Path]:
    """Context manager yielding an empty temporary folder inside ``folder``; its files replace those in ``folder``.

    Write a set of files (a report and its figures) into the yielded folder,
    keeping the layout they should have in ``folder``. On success every file
    is moved into place with :func:`os.replace` (no copying, one rename per
    file, after all the work is done); on any exception the temporary folder
    is removed and ``folder`` is untouched, so it never holds a mix of an old
    and a half-written new set. Files of ``folder`` not in the new set are
    left alone, except the temporary ones a killed run left there
    (:func:`remove_stale`, first).
    """
    dest = Path(folder)
    remove_stale(dest)
    path, _, lock = _new_temp(os.fspath(dest), directory=True)
    stage = Path(path)
    try:
        yield stage
        files = sorted(p for p in stage.rglob("*") if p.is_file())
        # files deeper in the tree (figures) first: the documents that link them come last
        files.sort(key=lambda p: -len(p.relative_to(stage).parts))
        for f in files:
            target = dest / f.relative_to(stage)
            target.parent.mkdir(parents=True, exist_ok=True)
            os.chmod(f, 0o666 & ~_umask())
            os.replace(f, target)
            _WRITTEN.append(os.fspath(target))
    finally:
        shutil.rmtree(stage, ignore_errors=True)
        _release(lock)


# ------------------------------------------------------------ temporary names, and those a killed run left
def _new_temp(folder: str, directory: bool = False, suffix: str = "") -> tuple[str, int | None, int | None]:
    """A new temporary file or folder ``.dfa-tmp-*`` in ``folder``, locked while in use (:func:`remove_stale`).

    Returns
    -------
    path : str
        The new file or folder.
    fd : int or None
        The file's descriptor, open for writing (None for a folder).
    lock : int or None
        The descriptor holding the lock (:func:`_release` when done; None where locks are not available).
    """
    for _ in range(_TEMP_TRIES):
        if directory:
            path, fd = tempfile.mkdtemp(prefix=_TMP_PREFIX, suffix=suffix, dir=folder), None
        else:
            fd, path = tempfile.mkstemp(prefix=_TMP_PREFIX, suffix=suffix, dir=folder)
        lock = _hold(path)
        if lock != _GONE:
            return path, fd, lock
        if fd is not None:  # another run's clean-up removed it before it was locked: make another
            os.close(fd)
    raise OSError(f"no temporary name could be kept in {folder!r} ({_TEMP_TRIES} were removed by another process)")


def _hold(path: str) -> int | None:
    """Lock ``path`` for as long as the returned descriptor stays open (the lock ends with the process, however
    it ends); None where locks are not available, :data:`_GONE` when ``path`` was removed before it was locked."""
    try:
        import fcntl
    except ImportError:  # no flock (Windows): nothing is locked, and remove_stale removes nothing
        return None
    try:
        fd = os.open(path, os.O_RDONLY)
    except FileNotFoundError:
        return _GONE
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # waits while a clean-up that locked it first removes it
        same = os.path.samestat(os.fstat(fd), os.stat(path))
    except FileNotFoundError:
        same = False
    except OSError:  # a file system without locks: remove_stale cannot lock there either, so it removes nothing
        os.close(fd)
        return None
    if not same:
        os.close(fd)
        return _GONE
    return fd


def _release(lock: int | None) -> None:
    """Give up a lock of :func:`_hold` (close its descriptor)."""
    if lock is not None:
        with contextlib.suppress(OSError):
            os.close(lock)


def remove_stale(folder: str | os.PathLike[str]) -> list[str]:
    """Remove the temporary files and folders (``.dfa-tmp-*``) that a killed run (SIGKILL, a power cut) left in
    ``folder``; return their paths.

    Rule: an entry of this user, a regular file or a folder, whose lock no process holds. Every run holds a lock
    on its temporary names from their creation to their removal (:func:`_new_temp`: ``flock``, which the system
    drops when the process ends, however it ends), so the stage or file of a run still going on, in this folder,
    by this process or another, is never touched. Where locks are not available (Windows, some network file
    systems) nothing is removed.
    """
    try:
        import fcntl
    except ImportError:
        return []
    try:
        names = sorted(n for n in os.listdir(folder) if n.startswith(_TMP_PREFIX))
    except OSError:
        return []
    removed = []
    for name in names:
        path = os.path.join(os.fspath(folder), name)
        try:
            st = os.lstat(path)
            if st.st_uid != os.getuid() or not (stat.S_ISDIR(st.st_mode) or stat.S_ISREG(st.st_mode)):
                continue
            fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
        except OSError:
            continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)  # refused: a run holds it
            if not os.path.samestat(os.fstat(fd), os.lstat(path)):
                continue
            if stat.S_ISDIR(st.st_mode):
                shutil.rmtree(path)
            else:
                os.unlink(path)
        except OSError:
            continue
        finally:
            os.close(fd)
        removed.append(path)
    return removed


# ------------------------------------------------------------ output-path rules
def _check_path_text(flag: str, path: str) -> None:
    """Refuse a path the operating system cannot take: NUL bytes, non-encodable text, too long a name."""
    shown = repr(path[:60]) + ("…" if len(path) > 60 else "")
    try:
        os.fsencode(path)
    except UnicodeError:
        raise DFAValueError(
            f"{flag} {shown} is invalid: it cannot be encoded as a file name; use plain characters"
        ) from None
    if "\0" in path:
        raise DFAValueError(f"{flag} {shown} is invalid: it contains a NUL byte; give a plain path")
    try:
        name_max = os.pathconf(os.path.dirname(os.path.abspath(path)) or ".", "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        name_max = 255
    longest = max((len(os.fsencode(part)) for part in path.split(os.sep)), default=0)
    if longest > name_max or len(os.fsencode(path)) > 4000:
        raise DFAValueError(
            f"{flag} {shown} is invalid: a name in it is longer than {name_max} bytes; give a shorter path"
        )


def check_output_file(flag: str, path: str, suffix: str | tuple[str, ...] | None = None) -> str:
    """Refuse an output *file* path that cannot be written as given; return it.

    Rule: a non-empty path that does not end in a path separator, is not an
    existing folder or special file (``/dev/null``), whose folder exists, and
    (when ``suffix`` is given) ends in ``suffix`` (one of them for a tuple, e.g.
    :data:`FIGURE_SUFFIXES` for a figure): the file is written exactly there,
    never at a derived name.
    """
    suffixes = (suffix,) if isinstance(suffix, str) else tuple(suffix or ())
    example = suffixes[0] if suffixes else ".csv"
    if not isinstance(path, str) or not path.strip():
        raise DFAValueError(f"{flag} {path!r} is invalid: it must name a file; give e.g. {flag} out{example}")
    _check_path_text(flag, path)
    if path.endswith(("/", os.sep)) or os.path.isdir(path):
        raise DFAValueError(
            f"{flag} {path!r} is a folder: it must name a file; give e.g. {flag} {os.path.join(path, 'out' + example)}"
        )
    if os.path.exists(path) and not os.path.isfile(path):
        raise DFAValueError(f"{flag} {path!r} is not a regular file: it cannot be replaced; choose a file path")
    if suffixes and not path.endswith(suffixes):
        raise DFAValueError(f"{flag} {path!r} is invalid: {_suffix_rule(path, suffixes)}; give {flag} "
                            f"{os.path.splitext(path)[0] if len(suffixes) > 1 else path}{example}")  # fmt: skip
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise DFAValueError(f"{flag} {path!r} is invalid: folder {folder!r} does not exist; create it first")
    if not os.access(folder, os.W_OK):
        raise DFAValueError(f"{flag} {path!r} is invalid: folder {folder!r} is not writable; choose another folder")
    return path


def _suffix_rule(path: str, suffixes: tuple[str, ...]) -> str:
    """Why ``path`` is refused for its suffix, in words: which suffixes are accepted (and the one it has).

    Examples
    --------
    >>> _suffix_rule("fig.jpg", FIGURE_SUFFIXES)
    'the file name must end in .png, .pdf or .svg, not .jpg'
    >>> _suffix_rule("map", (".npz",))
    'the file name must end in .npz'
    """
    if len(suffixes) == 1:
        return f"the file name must end in {suffixes[0]}"
    has = os.path.splitext(path)[1]
    listed = ", ".join(suffixes[:-1]) + f" or {suffixes[-1]}"
    return f"the file name must end in {listed}" + (f", not {has}" if has else "")


def _probe(folder: str) -> str | None:
    """Why no file can be made in the existing ``folder`` (a temporary folder is made and removed), or None.

    :func:`os.access` says yes to root for a read-only file system or ``/proc``; only trying tells.
    """
    try:
        path, _, lock = _new_temp(folder, directory=True)
    except OSError as exc:
        return exc.strerror or type(exc).__name__
    try:
        os.rmdir(path)
    except OSError as exc:
        return exc.strerror or type(exc).__name__
    finally:
        _release(lock)
    return None


def check_output_folder(flag: str, path: str, create: bool) -> str:
    """Refuse an output *folder* that cannot be used; return it.

    Rule: a non-empty path that is an existing folder or (with ``create``) a not-yet-existing folder whose
    parent is an existing folder (one level is created, :func:`make_output_folder`); never an existing file, nor
    a path through one; and something must be writable there (tried, not asked: :func:`os.access` says yes to root
    for ``/proc``).
    """
    if not isinstance(path, str) or not path.strip():
        raise DFAValueError(f"{flag} {path!r} is invalid: it must name a folder; give e.g. {flag} reports")
    _check_path_text(flag, path)
    if os.path.exists(path) and not os.path.isdir(path):
        raise DFAValueError(f"{flag} {path!r} is not a folder: it is an existing file; choose a folder")
    folder = os.path.abspath(path)
    if not os.path.isdir(path):
        if not create:
            raise DFAValueError(f"{flag} {path!r} is invalid: folder {folder!r} does not exist; create it first")
        folder = os.path.dirname(folder)
        if not os.path.isdir(folder):
            up = folder
            while not os.path.lexists(up) and os.path.dirname(up) != up:
                up = os.path.dirname(up)
            if os.path.lexists(up) and not os.path.isdir(up):
                raise DFAValueError(f"{flag} {path!r} is invalid: {up!r} is a file, not a folder; choose a folder path")
            raise DFAValueError(
                f"{flag} {path!r} is invalid: folder {folder!r} does not exist; create it first (only the last "
                "folder of the path is created)"
            )
    why = _probe(folder)
    if why is not None:
        where = "the folder" if folder == os.path.abspath(path) else f"folder {folder!r}"
        raise DFAValueError(
            f"{flag} {path!r} is invalid: nothing can be written in {where} ({why}); choose another folder"
        )
    return path


def make_output_folder(flag: str, path: str) -> str:
    """Create the output folder ``path`` if missing (checked first by :func:`check_output_folder`).

    A folder that still cannot be made is bad input (:class:`DFAValueError`, exit 2), not a failed write.
    """
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as exc:
        raise DFAValueError(
            f"{flag} {path!r} is invalid: the folder cannot be created ({exc.strerror or exc}); choose another folder"
        ) from None
    return path


# ------------------------------------------------------------ resource limits
def available_memory() -> int:
    """Memory available to a new computation in bytes.

    ``MemAvailable`` of ``/proc/meminfo`` (Linux), else physical pages ×
    page size from :func:`os.sysconf`, else :data:`FALLBACK_MEMORY`.
    """
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return int(os.sysconf("SC_PHYS_PAGES")) * int(os.sysconf("SC_PAGE_SIZE"))
    except (AttributeError, OSError, ValueError):
        return FALLBACK_MEMORY


def _gib(nbytes: float) -> str:
    return f"{nbytes / 1024**3:.3g} GiB"


def check_memory(name: str, value: object, nbytes: float, fix: str) -> None:
    """Refuse a computation planned to need more than :data:`MEMORY_FRACTION` of the available memory.

    Parameters
    ----------
    name : str
        The parameter (or command-line flag) that sets the size.
    value : object
        Its value, for the message.
    nbytes : float
        Estimated peak memory in bytes.
    fix : str
        How to make it smaller.
    """
    avail = available_memory()
    if nbytes > MEMORY_FRACTION * avail:
        raise DFAValueError(
            f"{name} = {value} is too large: it needs about {_gib(nbytes)} of memory, more than "
            f"{MEMORY_FRACTION:.0%} of the {_gib(avail)} available; {fix}"
        )
