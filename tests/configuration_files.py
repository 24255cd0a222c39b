"""A device file with configurations for the configuration tests (issue 46): its head, an inertia matrix, and
the command line run in process."""

from __future__ import annotations

from dfa.cli import main

#: The device's own row (a Phantom-like arm in SI units); configurations are appended to it.
HEAD = """[[devices]]
name = "Arm"
mass = 0.032
damping = 0.02
coulomb = 0.024
resolution = 314e-6
period = 0.002
stiffness = 80.0
"""
#: A symmetric positive-definite inertia matrix (kg), not diagonal.
INERTIA = [[0.05, 0.01, 0.0], [0.01, 0.04, 0.005], [0.0, 0.005, 0.03]]


def run_cli(capsys, *argv: str) -> tuple[int, str, str]:
    """``dfa ARGV`` in process: (exit code, stdout, stderr)."""
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def device_file(tmp_path, *tables: str) -> str:
    """The path of ``arm.toml`` in ``tmp_path``: the head and one ``[[devices.configurations]]`` per table."""
    path = tmp_path / "arm.toml"
    path.write_text(HEAD + "".join("\n[[devices.configurations]]\n" + t + "\n" for t in tables), encoding="utf-8")
    return str(path)
