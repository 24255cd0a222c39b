"""One numba cache whatever starts dfa (issue 27 §1): :mod:`dfa.core.cache` and the ``dfa`` console script."""

from __future__ import annotations

import io
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

from dfa.core import cache

ROOT = Path(__file__).resolve().parents[1]
CORE = ROOT / "dfa" / "core"
# a command whose kernels compile in seconds (the describing function's sums, dfa.core.dfcore)
COMMAND = ["limit-cycles", "--mu", "5", "--beta", "0.1", "--sigma", "0.3"]


@pytest.fixture
def env(monkeypatch, tmp_path):
    """No NUMBA_CACHE_DIR of the user or of dfa, dfa's cache under tmp_path; numba's parsed setting restored."""
    import numba.core.config as cfg

    monkeypatch.setattr(cfg, "CACHE_DIR", cfg.CACHE_DIR)
    for name in (cache.NUMBA_ENV, cache._CHOSEN_ENV):
        monkeypatch.setenv(name, "")  # so that what configure() sets is undone too
        monkeypatch.delenv(name)
    monkeypatch.setenv(cache.BASE_ENV, str(tmp_path / "base"))
    return tmp_path


def test_default_folder_is_keyed_under_the_user_cache(env, monkeypatch):
    path, users = cache.resolve_cache_dir()
    assert not users and path == str(env / "base" / "numba" / cache.kernel_key()) and os.path.isdir(path)
    monkeypatch.delenv(cache.BASE_ENV)
    monkeypatch.setenv("XDG_CACHE_HOME", str(env / "xdg"))
    if sys.platform not in ("win32", "darwin"):
        assert cache.user_cache_base() == str(env / "xdg" / "dfa")


def test_users_numba_cache_dir_is_the_override(env, monkeypatch):
    mine = env / "mine"
    monkeypatch.setenv(cache.NUMBA_ENV, str(mine))
    assert cache.resolve_cache_dir() == (str(mine), True)
    assert cache.configure() == str(mine) and os.environ[cache.NUMBA_ENV] == str(mine)
    assert cache._CHOSEN_ENV not in os.environ  # still the user's


def test_unwritable_folders_fall_back(env, monkeypatch):
    blocker = env / "a-file"
    blocker.write_text("x")  # nothing can be made under a regular file, even by root
    monkeypatch.setenv(cache.NUMBA_ENV, str(blocker / "numba"))
    path, users = cache.resolve_cache_dir()
    assert not users and path == cache.default_cache_dir()  # an unwritable NUMBA_CACHE_DIR: dfa's default
    monkeypatch.setenv(cache.BASE_ENV, str(blocker / "base"))  # and a read-only home: the temporary folder
    path, users = cache.resolve_cache_dir()
    assert not users and os.path.isdir(path) and os.access(path, os.W_OK)
    assert Path(path).is_relative_to(tempfile.gettempdir()) and "dfa-numba-cache" in path


def test_folder_chosen_by_dfa_is_not_taken_for_the_users(env, monkeypatch):
    chosen = cache.configure()  # sets NUMBA_CACHE_DIR and marks it dfa's
    assert os.environ[cache.NUMBA_ENV] == chosen == os.environ[cache._CHOSEN_ENV]
    monkeypatch.setenv(cache.BASE_ENV, str(env / "child"))  # a child process with its own DFA_CACHE_DIR
    assert cache.resolve_cache_dir() == (str(env / "child" / "numba" / cache.kernel_key()), False)


def test_key_follows_every_kernel_source(monkeypatch, tmp_path):
    copy = tmp_path / "core"
    shutil.copytree(CORE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    monkeypatch.setattr(cache, "_CORE", str(copy))
    key = cache.kernel_key()
    assert key == cache.kernel_key() and len(key) == 16
    with open(copy / "exprel.py", "a") as fh:  # inlined into the kernels of other files
        fh.write("\n# edited\n")
    assert cache.kernel_key() != key


def _snapshot(folder: Path) -> dict[str, int]:
    """numba's cache files under ``folder`` (index .nbi, data .nbc) and their modification times."""
    if not folder.is_dir():
        return {}
    return {str(p): p.stat().st_mtime_ns for p in folder.rglob("*") if p.suffix in (".nbi", ".nbc")}


def _run_on_a_terminal(argv: list[str], env: dict[str, str], cwd: Path) -> tuple[int, str, str]:
    """Run ``argv`` with stderr on a pseudo-terminal (as in a shell); return (exit code, stdout, stderr)."""
    import pty

    master, slave = pty.openpty()
    try:
        proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=slave, text=True, env=env, cwd=cwd)
        os.close(slave)
        out, _ = proc.communicate(timeout=300)
        err = b""
        while True:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # EIO: the terminal's other end is closed and drained
                break
            if not chunk:
                break
            err += chunk
    finally:
        os.close(master)
    return proc.returncode, out, err.decode(errors="replace")


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals are POSIX")
def test_console_script_caches_in_one_folder_and_compiles_once(tmp_path):
    """``dfa`` started as the README says, on a fresh cache: kernels go to the cache folder only, a terminal
    is told once that they compile, and a second start compiles nothing (numba's debug log: loads only)."""
    script = Path(sys.executable).parent / "dfa"
    if not script.exists():
        pytest.skip("the dfa console script is not installed (pip install -e .)")
    env = {k: v for k, v in os.environ.items() if k not in (cache.NUMBA_ENV, cache._CHOSEN_ENV)}
    env.update({cache.BASE_ENV: str(tmp_path / "cache"), "NUMBA_DEBUG_CACHE": "1"})
    in_tree = _snapshot(CORE / "__pycache__")

    code, first, err = _run_on_a_terminal([str(script), *COMMAND], env, tmp_path)
    assert code == 0, err
    files = _snapshot(tmp_path / "cache")
    assert "[cache] data saved to" in first and files
    assert all(Path(f).is_relative_to(tmp_path / "cache" / "numba" / cache.kernel_key()) for f in files)
    assert err.count("dfa: compiling kernels once (") == 1, err
    code, second, err = _run_on_a_terminal([str(script), *COMMAND], env, tmp_path)
    assert code == 0, err
    assert "[cache] data loaded from" in second and "saved to" not in second  # nothing compiled
    assert "compiling" not in err  # and nothing said
    assert _snapshot(tmp_path / "cache") == files
    assert _snapshot(CORE / "__pycache__") == in_tree  # nothing next to the sources
    env[cache.BASE_ENV] = str(tmp_path / "piped")  # compiles again, stderr not a terminal: nothing said
    piped = subprocess.run([str(script), *COMMAND], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert piped.returncode == 0 and "[cache] data saved to" in piped.stdout and "compiling" not in piped.stderr


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_compile_note_once_on_a_terminal_when_a_kernel_compiles():
    from numba.core import event

    from dfa.cli.compile_note import compile_note, note_text
    from dfa.core import CACHE_DIR, dfcore

    def compile_event(dispatcher: object) -> None:  # what numba fires around a real compile (never on a cache load)
        with event.trigger_event("numba:compile", data={"dispatcher": dispatcher, "args": (), "return_type": None}):
            pass

    other = type("Dispatcher", (), {"py_func": test_key_follows_every_kernel_source})()
    for stream, expected in ((_Terminal(), note_text("stiffness", CACHE_DIR) + "\n"), (io.StringIO(), "")):
        with compile_note("stiffness", stream):
            compile_event(other)  # not a kernel of dfa.core: no note
            compile_event(dfcore.df_value.dispatcher)
            compile_event(dfcore.df_array.dispatcher)  # once only
        compile_event(dfcore.df_value.dispatcher)  # after the command: no listener left
        assert stream.getvalue() == expected
    assert note_text("stiffness", CACHE_DIR).startswith("dfa: compiling kernels once (about ")
    assert len(note_text(None, "/x" * 200)) <= 100


def test_compile_note_listens_from_the_first_kernel_when_the_command_starts_without_numba():
    """The note's listener waits for numba (dfa.core.jit): a command that runs no kernel never imports it."""
    code = (
        "import io, sys\n"
        "from dfa.cli.compile_note import compile_note, note_text\n"
        "from dfa.core import CACHE_DIR, dfcore\n"
        "class T(io.StringIO):\n"
        "    def isatty(self): return True\n"
        "quiet, s = T(), T()\n"
        "with compile_note('check', quiet):\n"
        "    pass\n"
        "with compile_note('stiffness', s):\n"
        "    before = 'numba' in sys.modules\n"
        "    d = dfcore.df_value.dispatcher\n"
        "    from numba.core import event\n"
        "    with event.trigger_event('numba:compile', data={'dispatcher': d, 'args': (), 'return_type': None}):\n"
        "        pass\n"
        "print(before, quiet.getvalue() == '', s.getvalue() == note_text('stiffness', CACHE_DIR) + '\\n')\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    assert out == ["False", "True", "True"]
