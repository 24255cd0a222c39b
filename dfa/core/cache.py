"""Where numba keeps the compiled kernels: one folder whatever starts dfa, named after what was compiled.

numba compiles a ``cache=True`` kernel once and keeps it on disk: in ``NUMBA_CACHE_DIR`` when that is set,
otherwise next to its source (``dfa/core/__pycache__``). It keys a cached kernel on its own file only, so a
kernel that inlines an edited function of another file (:mod:`dfa.core.exprel` into :mod:`dfa.core.kernel`)
would keep stale code. :func:`configure` runs when :mod:`dfa.core` is first imported, before any kernel is
defined, and points numba at one folder, in this order:

1. ``NUMBA_CACHE_DIR`` when the user set it and it is writable: theirs, used as it is (the override);
2. otherwise ``<base>/numba/<key>``, where ``<base>`` is ``DFA_CACHE_DIR`` when set, else the user's cache
   directory (``$XDG_CACHE_HOME/dfa`` or ``~/.cache/dfa``; ``~/Library/Caches/dfa`` on macOS,
   ``%LOCALAPPDATA%\\dfa\\Cache`` on Windows), and ``<key>`` (:func:`kernel_key`) is a hash of every source
   file of :mod:`dfa.core` and of the Python, numba, llvmlite and numpy versions: an edited kernel, or
   another numba, gets a new folder and stale kernels are never loaded;
3. when that folder cannot be written (a read-only home): ``<tempdir>/dfa-numba-cache-<uid>/<key>``, and
   failing that a new temporary folder.

So ``make``, ``.venv/bin/dfa``, ``python -m dfa`` and ``import dfa`` share one cache, and a read-only
installation still runs. The folder chosen is also put in ``NUMBA_CACHE_DIR`` (for worker processes, and so
that numba keeps it when it reloads its configuration), marked as dfa's own in ``_DFA_NUMBA_CACHE_DIR``: a
child process started from there (``dfa`` in a subprocess) tells it from a folder the user chose and
computes its own.

This module imports no numba (it must run before numba reads its configuration) and nothing of dfa.
"""

from __future__ import annotations

import hashlib
import os
import sys
import tempfile
from importlib.util import find_spec

__all__ = ["BASE_ENV", "configure", "default_cache_dir", "kernel_key", "resolve_cache_dir", "user_cache_base"]

#: The environment variable that moves dfa's cache folder (its kernels go to ``$DFA_CACHE_DIR/numba/<key>``).
BASE_ENV = "DFA_CACHE_DIR"
#: Set by :func:`configure` to the ``NUMBA_CACHE_DIR`` it chose, so that a child process can tell it from the user's.
_CHOSEN_ENV = "_DFA_NUMBA_CACHE_DIR"
#: numba's own variable.
NUMBA_ENV = "NUMBA_CACHE_DIR"

_CORE = os.path.dirname(os.path.abspath(__file__))


def user_cache_base() -> str:
    """dfa's cache folder: ``DFA_CACHE_DIR`` when set, else the platform's user cache directory + ``dfa``.

    Returns
    -------
    str
        An absolute path (not created here).
    """
    env = os.environ.get(BASE_ENV)
    if env:
        return os.path.abspath(os.path.expanduser(env))
    home = os.path.expanduser("~")
    if sys.platform == "win32":
        return os.path.join(os.environ.get("LOCALAPPDATA") or os.path.join(home, "AppData", "Local"), "dfa", "Cache")
    if sys.platform == "darwin":
        return os.path.join(home, "Library", "Caches", "dfa")
    xdg = os.environ.get("XDG_CACHE_HOME")
    return os.path.join(xdg if xdg and os.path.isabs(xdg) else os.path.join(home, ".cache"), "dfa")


def _version_file(package: str, name: str) -> bytes:
    """The bytes of ``package/name`` found without importing the package (b"" when absent)."""
    try:
        spec = find_spec(package)
    except (ImportError, ValueError):
        return b""
    if spec is None or not spec.submodule_search_locations:
        return b""
    for folder in spec.submodule_search_locations:
        try:
            with open(os.path.join(folder, name), "rb") as fh:
                return fh.read()
        except OSError:
            continue
    return b""


def kernel_key() -> str:
    """The name of the cache folder of these kernels: a hash of what numba compiles and what compiles it.

    Hashed: the name and bytes of every ``dfa/core/*.py`` (numba keys a cached kernel on its own file only,
    while kernels inline functions of other files), the Python implementation, version and machine, and the
    version files of numba, llvmlite and numpy (read, not imported). The Makefile used to compute the same
    from the sources alone (``cksum``).

    Returns
    -------
    str
        16 hexadecimal digits.
    """
    h = hashlib.sha256()
    h.update(f"{sys.implementation.cache_tag} {sys.version} {sys.platform} {os.sep}".encode())
    for package, name in (("numba", "_version.py"), ("llvmlite", "_version.py"), ("numpy", "version.py")):
        h.update(package.encode() + b"\0" + _version_file(package, name) + b"\0")
    for name in sorted(n for n in os.listdir(_CORE) if n.endswith(".py")):
        with open(os.path.join(_CORE, name), "rb") as fh:
            h.update(name.encode() + b"\0" + fh.read() + b"\0")
    return h.hexdigest()[:16]


def default_cache_dir() -> str:
    """``<user_cache_base()>/numba/<kernel_key()>``: where the kernels go unless ``NUMBA_CACHE_DIR`` is set.

    Returns
    -------
    str
        An absolute path (not created here).
    """
    return os.path.join(user_cache_base(), "numba", kernel_key())


def _writable_dir(path: str) -> bool:
    """Create ``path`` if missing and check that a file can be made in it."""
    try:
        os.makedirs(path, exist_ok=True)
        fd, probe = tempfile.mkstemp(prefix=".dfa-probe-", dir=path)
    except OSError:
        return False
    os.close(fd)
    try:
        os.unlink(probe)
    except OSError:
        pass
    return True


def resolve_cache_dir() -> tuple[str, bool]:
    """The folder numba should cache the kernels in (module docstring), created.

    Returns
    -------
    path : str
        The folder.
    users : bool
        True when it is the user's own ``NUMBA_CACHE_DIR`` (left as it is), False when dfa chose it.
    """
    current = os.environ.get(NUMBA_ENV)
    if current and current != os.environ.get(_CHOSEN_ENV) and _writable_dir(current):
        return current, True
    path = default_cache_dir()
    if _writable_dir(path):
        return path, False
    uid = os.getuid() if hasattr(os, "getuid") else "user"
    path = os.path.join(tempfile.gettempdir(), f"dfa-numba-cache-{uid}", os.path.basename(path))
    if _writable_dir(path):
        return path, False
    return tempfile.mkdtemp(prefix="dfa-numba-cache-"), False


def configure() -> str:
    """Point numba's cache at :func:`resolve_cache_dir`'s folder; run before any kernel is defined.

    Sets ``NUMBA_CACHE_DIR`` (and numba's parsed setting when numba is already imported) unless the user's
    own is used.

    Returns
    -------
    str
        The folder the kernels are cached in.
    """
    path, users = resolve_cache_dir()
    if not users:
        os.environ[NUMBA_ENV] = path
        os.environ[_CHOSEN_ENV] = path
    cfg = sys.modules.get("numba.core.config")
    if cfg is not None:  # numba was imported before dfa.core: update its parsed setting too
        cfg.CACHE_DIR = path  # type: ignore[attr-defined]
    return path
