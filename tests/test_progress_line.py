"""Long work shows itself (issue 43): one updating line on a terminal's stderr, never in a pipe or with --json;
`dfa stiffness --explain` ends with how long it took and how many simulations it ran."""

import io
import os
import re
import subprocess
import sys

import pytest

from dfa import progress
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.runs import RunCache
from dfa.cli import main
from dfa.model.catalogue import get_device
from dfa.model.loop import Loop
from dfa.model.wall import Wall

STIFFNESS = ["stiffness", "--device", "impulse", "--velocity", "0.2"]


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_progress_line_shows_the_stage_how_far_and_the_runs_after_the_delay():
    out = _Terminal()
    with progress.progress_line(out, delay=0.0):
        with progress.stage("searching", total=4, unit="judgement"):
            progress.advance(runs=3, unit="judgement")
            progress.advance(unit="parameter")  # another unit's step: not this stage's
    text = out.getvalue().replace("\r", "\n")
    assert "searching: 1/~4, ~0:00 left, 0:00 elapsed, 3 runs" in text
    assert "2/~4" not in text


def test_progress_line_silent_before_its_delay_and_off_a_terminal():
    quick, pipe = _Terminal(), io.StringIO()
    with progress.progress_line(quick, delay=60.0), progress.stage("quick work", total=2):
        progress.advance()
    with progress.progress_line(pipe, delay=0.0), progress.stage("piped work", total=2):
        progress.advance()
    assert quick.getvalue() == "" and pipe.getvalue() == ""


def test_progress_runs_counted_is_the_cache_s_simulations():
    """The runs the progress line counts are the runs simulated (the cache's misses), nothing else."""
    before = progress.runs_counted()
    cache = RunCache()
    design_answer(Loop(get_device("impulse").device, Wall.of(80.0)), 0.2, grid=6, speeds=2, cache=cache)
    assert progress.runs_counted() - before == cache.simulated > 0


def _run_on_a_terminal(argv):
    """Run dfa with stderr on a pseudo-terminal (stdout a pipe); return (stdout, what the terminal received)."""
    pty = pytest.importorskip("pty")
    import fcntl
    import struct
    import termios

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 200, 0, 0))  # a terminal's size: 40 x 200
    env = dict(os.environ, DFA_PROGRESS_DELAY="0", COLUMNS="200")
    code = "import sys; from dfa.cli.app import main; sys.exit(main(sys.argv[1:]))"
    proc = subprocess.Popen([sys.executable, "-c", code, *argv], stdout=subprocess.PIPE, stderr=slave, env=env)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 65536)
        except OSError:  # the terminal's other end closed: the process is done
            break
        if not data:
            break
        chunks.append(data)
    out, _ = proc.communicate()
    os.close(master)
    assert proc.returncode == 0
    return out.decode(), b"".join(chunks).decode(errors="replace")


@pytest.mark.skipif(sys.platform == "win32", reason="pseudo-terminals are POSIX")
def test_cli_stiffness_progress_line_on_a_terminal_never_in_json_or_a_pipe(capsys):
    out, tty = _run_on_a_terminal(STIFFNESS)
    assert "K_sim (no divergence): " in tty and re.search(r": \d+/~\d+, ~\d:\d\d left, \d:\d\d elapsed", tty)
    assert "K_sim" not in out  # the answer on stdout holds no line of progress
    _out, tty_json = _run_on_a_terminal([*STIFFNESS, "--json"])
    assert "K_sim" not in tty_json and "elapsed" not in tty_json
    piped = subprocess.run(
        [sys.executable, "-c", "import sys; from dfa.cli.app import main; sys.exit(main(sys.argv[1:]))", *STIFFNESS],
        capture_output=True, text=True, env=dict(os.environ, DFA_PROGRESS_DELAY="0"), check=True,
    )  # fmt: skip
    assert piped.stderr == "" and piped.stdout == out


def test_cli_stiffness_explain_ends_with_its_time_and_the_simulations_it_ran(capsys):
    assert main([*STIFFNESS, "--explain"]) == 0
    last = capsys.readouterr().out.rstrip("\n").splitlines()[-1]
    m = re.fullmatch(r"answered in ([0-9.]+) s \(wall clock, this machine\); (\d+) runs simulated \(repeats taken "
                     r"from the cache\)", last)  # fmt: skip
    assert m is not None, last
    cache = RunCache()
    design_answer(Loop(get_device("impulse").device, Wall.of(80.0)), 0.2, assess=True, cache=cache)
    assert int(m.group(2)) == cache.simulated and float(m.group(1)) > 0.0
    assert main([*STIFFNESS, "--explain", "--quick"]) == 0
    assert capsys.readouterr().out.rstrip("\n").splitlines()[-1].endswith("no simulation run")
