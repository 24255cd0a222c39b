"""Command-line tool ``dfa``: one module per subcommand, each parse → call → render.

Every subcommand is reachable through :func:`main` (``main(argv) -> exit code``) so that it can be tested
without a subprocess. Bad input prints one line on stderr and returns exit code 2; no traceback is ever shown
for it. The modules: :mod:`~dfa.cli.app` (the parser, signals, exit codes), :mod:`~dfa.cli.parsing` (values),
:mod:`~dfa.cli.inputs` (device, loop, speed), :mod:`~dfa.cli.walls` (the wall's flags, one row per element),
:mod:`~dfa.cli.output` (JSON, tables, figures, progress, work limits), and one module per command.

Examples
--------
>>> main(["params", "--device", "impulse", "--json"])
{"mu": 100.0, "beta": 0.125, "sigma": 0.955414012739}
0
"""

from __future__ import annotations

from .app import main

__all__ = ["main"]
