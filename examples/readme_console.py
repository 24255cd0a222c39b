"""Keep the README's command-line examples true: run every ``$ dfa ...`` line of its console blocks.

Each ```` ```console ```` block of README.md and of the docs pages in :data:`FILES` holds commands (lines starting with ``$ dfa``) each followed by
its output. This script runs every command in-process (``dfa.cli.main``, in a temporary folder so files they
write go nowhere) and either checks that the README shows exactly what the code prints now, or rewrites the
README with the new output.

Run: python examples/readme_console.py [--write] [--readme FILE]  (default: every file of FILES)
(``make readme`` rewrites; ``tests/test_readme_console.py`` checks.)
"""

from __future__ import annotations

import argparse
import contextlib
import difflib
import io
import os
import re
import shlex
import sys
import tempfile
from pathlib import Path

BLOCK = re.compile(r"(```console\n)(.*?)(```)", re.S)
ROOT = Path(__file__).resolve().parent.parent
#: The documents whose console blocks are run: the README's quick start and the command-line page.
FILES = ("README.md", "docs/cli.md")


def sessions(block: str) -> list[tuple[str, str]]:
    """Split a console block into (command, output) pairs."""
    out: list[tuple[str, str]] = []
    for line in block.splitlines(keepends=True):
        if line.startswith("$ "):
            out.append((line[2:].strip(), ""))
        elif out:
            out[-1] = (out[-1][0], out[-1][1] + line)
    return out


def run(command: str) -> str:
    """Stdout of one ``dfa ...`` command, run in-process in a scratch folder."""
    from dfa.cli import main

    argv = shlex.split(command)
    if argv[:1] != ["dfa"]:
        raise ValueError(f"README console command {command!r} does not start with 'dfa'")
    argv = [str(ROOT / a) if a.startswith("examples/") and (ROOT / a).is_file() else a for a in argv]  # shipped files
    buf = io.StringIO()
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        try:
            with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(io.StringIO()):
                rc = main(argv[1:])
        finally:
            os.chdir(here)
    if rc != 0:
        raise RuntimeError(f"README command {command!r} exited with {rc}")
    return buf.getvalue()


def render(text: str) -> str:
    """README text with every console block's outputs replaced by what the code prints now."""

    def block(m: re.Match) -> str:
        parts = [f"$ {cmd}\n{run(cmd)}" for cmd, _old in sessions(m.group(2))]
        return m.group(1) + "\n".join(parts) + m.group(3)

    return BLOCK.sub(block, text)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--write", action="store_true", help="rewrite the files instead of checking them")
    ap.add_argument("--readme", default=None, help="one file to check or rewrite (default: every file of FILES)")
    args = ap.parse_args(argv)
    paths = [Path(args.readme)] if args.readme else [ROOT / f for f in FILES]
    status = 0
    for path in paths:
        status |= _one(path, args.write)
    return status


def _one(path: Path, write: bool) -> int:
    old = path.read_text(encoding="utf-8")
    new = render(old)
    if write:
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(new, encoding="utf-8")
        os.replace(tmp, path)
        print(f"{path}: {'updated' if new != old else 'unchanged'}")
        return 0
    if new != old:
        sys.stdout.writelines(
            difflib.unified_diff(
                old.splitlines(True), new.splitlines(True), f"{path.name} (committed)", f"{path.name} (code now)"
            )
        )
        return 1
    print(f"{path}: every console example matches the code")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
