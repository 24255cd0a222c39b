"""Golden outputs of the ``dfa`` command line: the numbers users read, recorded from the code before a refactor.

``python tests/golden/make_golden.py`` runs every command of :data:`COMMANDS` in-process through
:func:`dfa.cli.main` with stdout captured and writes ``tests/golden/cli.json`` (stdout of every command, JSON
parsed when the command prints JSON) and ``tests/golden/report.json`` (the Markdown text of ``dfa report --format
md``). ``tests/test_golden_numbers.py`` re-runs the same commands and compares them with :func:`compare_json` and
:func:`compare_text`: every key and every number of the golden file must still be there, unchanged; new keys,
new lines and new numbers within a line are allowed.

Only regenerate the golden files on purpose (a number changed for a reason that is written in the commit).
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import re
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))  # tests/, for cli_text (also when run as a script)

from cli_text import unwrap  # noqa: E402

TMP = "<TMP>"

_CUSTOM = ["--mass", "0.05", "--damping", "0.01", "--coulomb", "0.02", "--resolution", "2e-5", "--period", "0.001"]
_ROTARY = ["--device", "re35", "--stiffness", "0.5", "--rotary"]

#: name -> argv ("{tmp}" is a scratch folder). Every subcommand and its main options.
COMMANDS: dict[str, list[str]] = {
    "devices": ["devices"],
    "devices_json": ["devices", "--json"],
    "params_device": ["params", "--device", "impulse"],
    "params_custom_json": ["params", *_CUSTOM, "--stiffness", "1000", "--json"],
    "params_dimless": ["params", "--mu", "50", "--beta", "0.1", "--sigma", "0.4"],
    "check_device": ["check", "--device", "phantom", "--velocity", "0.1"],
    "check_device_json": ["check", "--device", "phantom", "--velocity", "0.1", "--json"],
    "check_device_delay": ["check", "--device", "phantom", "--velocity", "0.05", "--delay", "1"],
    "check_position_json": ["check", "--device", "impulse", "--velocity", "0.1", "--position", "0.002", "--json"],
    "check_dimless": ["check", "--beta", "0.8", "--sigma", "0.7", "--xi-dot", "2"],
    "check_dimless_xi0": ["check", "--mu", "50", "--beta", "0.8", "--sigma", "0.7", "--xi-dot", "2", "--xi0", "3"],
    "check_noquant_json": ["check", "--beta", "0.3", "--sigma", "0.2", "--xi-dot", "1", "--no-quantization", "--json"],
    "check_rotary": ["check", *_ROTARY, "--velocity", "2"],
    "stiffness_device": ["stiffness", "--device", "phantom", "--velocity", "0.1", "--explain"],
    "stiffness_device_json": ["stiffness", "--device", "phantom", "--velocity", "0.1", "--json"],
    "stiffness_k": ["stiffness", "--device", "phantom", "--velocity", "0.1", "--stiffness", "800", "--explain"],
    "stiffness_k_json": ["stiffness", "--device", "impulse", "--velocity", "0.2", "--stiffness", "60", "--json"],
    "stiffness_delay": [
        "stiffness",
        "--device",
        "phantom",
        "--velocity",
        "0.1",
        "--stiffness",
        "800",
        "--delay",
        "1",
        "--explain",
    ],
    "stiffness_delay_json": ["stiffness", "--device", "delta", "--velocity", "0.1", "--delay", "2", "--json"],
    "stiffness_custom": ["stiffness", *_CUSTOM, "--stiffness", "1000", "--velocity", "0.1", "--explain"],
    "stiffness_rotary_json": ["stiffness", *_ROTARY, "--velocity", "2", "--json"],
    "cycles_half_delay": ["limit-cycles", "--device", "phantom", "--model", "half-delay"],
    "cycles_zoh": ["limit-cycles", "--device", "phantom", "--model", "zoh"],
    "cycles_pade": ["limit-cycles", "--device", "phantom", "--model", "pade"],
    "cycles_zoh_json": ["limit-cycles", "--device", "impulse", "--model", "zoh", "--json"],
    "cycles_dimless": ["limit-cycles", "--mu", "50", "--beta", "0.1", "--sigma", "0.4"],
    "cycles_dimless_json": [
        "limit-cycles",
        "--mu",
        "50",
        "--beta",
        "0.1",
        "--sigma",
        "0.4",
        "--model",
        "zoh",
        "--json",
    ],
    "cycles_delay": ["limit-cycles", "--device", "impulse", "--model", "zoh", "--delay", "1"],
    "simulate_rest": ["simulate", "--mu", "100", "--beta", "0.5", "--sigma", "1", "--xi-dot", "2"],
    "simulate_chatter": ["simulate", "--mu", "50", "--beta", "0.2", "--sigma", "0.4", "--xi-dot", "1"],
    "simulate_chatter_json": ["simulate", "--mu", "50", "--beta", "0.8", "--sigma", "0.2", "--xi-dot", "1", "--json"],
    "simulate_unstable": ["simulate", "--mu", "100", "--beta", "0.1", "--sigma", "0.6", "--xi-dot", "2"],
    "simulate_unstable_json": ["simulate", "--mu", "50", "--beta", "0", "--sigma", "0.2", "--xi-dot", "1", "--json"],
    "simulate_device": ["simulate", "--device", "impulse", "--velocity", "0.3"],
    "simulate_device_json": ["simulate", "--device", "phantom", "--velocity", "0.05", "--json"],
    "simulate_preload": ["simulate", "--mu", "50", "--beta", "0.4", "--sigma", "0.8", "--xi-dot", "3", "--preload"],
    "simulate_delay_json": [
        "simulate",
        "--mu",
        "50",
        "--beta",
        "0.8",
        "--sigma",
        "1",
        "--xi-dot",
        "1",
        "--delay",
        "1",
        "--json",
    ],
    "simulate_noquant": [
        "simulate",
        "--mu",
        "50",
        "--beta",
        "0.4",
        "--sigma",
        "0.8",
        "--xi-dot",
        "3",
        "--no-quantization",
    ],
    "simulate_samples": [
        "simulate",
        "--mu",
        "50",
        "--beta",
        "0.2",
        "--sigma",
        "0.4",
        "--xi-dot",
        "1",
        "--samples",
        "3000",
    ],
    "map_json": [
        "map",
        "--mu",
        "50",
        "--xi-dot",
        "1",
        "3",
        "--grid",
        "6",
        "--samples",
        "5000",
        "--jobs",
        "1",
        "--quiet",
        "--out",
        "{tmp}/m.npz",
        "--json",
    ],
    "map_text": [
        "map",
        "--mu",
        "50",
        "--xi-dot",
        "2",
        "--grid",
        "5",
        "--samples",
        "4000",
        "--jobs",
        "1",
        "--quiet",
        "--preload",
        "--out",
        "{tmp}/p.npz",
    ],
    "contours_json": ["contours", "--mu", "50", "--grid", "12", "--max-amplitude", "20", "--json"],
    "contours_text": ["contours", "--mu", "80", "--grid", "10", "--max-amplitude", "15", "--beta-range", "0", "0.5"],
}

#: The design report: Markdown text of each file written (figures are not compared).
REPORT = ["report", "--device", "phantom", "--velocity", "0.1", "--format", "md", "--quiet", "--out", "{tmp}"]


def run(argv: list[str], tmp: str) -> tuple[int, str]:
    """Run ``dfa`` in-process; return (exit code, stdout) with the scratch folder replaced by ``<TMP>``."""
    from dfa.cli import main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        code = main([a.replace("{tmp}", tmp) for a in argv])
    return code, out.getvalue().replace(tmp, TMP)


def record(name: str, argv: list[str], tmp: str) -> dict:
    """One command's golden entry: exit code and stdout (parsed when the command prints JSON)."""
    code, text = run(argv, tmp)
    entry: dict = {"argv": argv, "exit": code}
    if "--json" in argv:
        entry["json"] = json.loads(text)
    else:
        entry["text"] = text
    return entry


def report_texts(tmp: str) -> dict:
    """Exit code, stdout and the Markdown files of :data:`REPORT`, keyed by path relative to the folder."""
    code, text = run(REPORT, tmp)
    files = {str(p.relative_to(tmp)): p.read_text(encoding="utf-8") for p in sorted(Path(tmp).rglob("*.md"))}
    return {"argv": REPORT, "exit": code, "text": text, "files": files}


# ------------------------------------------------------------------ comparison
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|∞|\binf\b|\bnan\b")


def numbers(line: str) -> list[str]:
    """The numbers a line prints, as written."""
    return _NUMBER.findall(line)


def _is_subsequence(small: list[str], big: list[str]) -> bool:
    it = iter(big)
    return all(any(x == y for y in it) for x in small)


def compare_text(golden: str, new: str, where: str = "") -> list[str]:
    """Problems: golden lines whose numbers (in order) appear on no logical line of ``new`` (wrapped lines joined
    back, ``tests/cli_text.unwrap``: wrapping moves no number); empty when all are there."""
    new_numbers = [numbers(line) for line in unwrap(new).splitlines()]
    problems = []
    for line in golden.splitlines():
        want = numbers(line)
        if want and not any(_is_subsequence(want, have) for have in new_numbers):
            problems.append(f"{where}: numbers {want} of golden line {line.strip()!r} appear on no line")
    return problems


#: Residuals of the harmonic-balance solver (|1 + D·L|) below this are equally converged.
RESIDUAL_NOISE = 1e-12
#: Loeb's stability coefficient (dfa.analysis.cycles.stability._loeb) is a central difference: compare to this.
LOEB_REL = 1e-7


def compare_json(golden: object, new: object, where: str = "$", rel: float = 1e-9) -> list[str]:
    """Problems: every key of ``golden`` must be in ``new`` with the same value (floats to ``rel``)."""
    if isinstance(golden, dict):
        if not isinstance(new, dict):
            return [f"{where}: was an object, now {type(new).__name__}"]
        out = []
        for k, v in golden.items():
            if k not in new:
                out.append(f"{where}.{k}: missing")
            else:
                out += compare_json(v, new[k], f"{where}.{k}", rel)
        return out
    if isinstance(golden, list):
        if not isinstance(new, list) or len(new) != len(golden):
            return [f"{where}: was a list of {len(golden)}, now {new!r:.80}"]
        return [
            p
            for i, (a, b) in enumerate(zip(golden, new, strict=True))
            for p in compare_json(a, b, f"{where}[{i}]", rel)
        ]
    if isinstance(golden, float) and not isinstance(new, bool) and isinstance(new, (int, float)):
        # a solver residual is rounding noise: it must stay at rounding level, not keep its digits
        noise = RESIDUAL_NOISE if where.endswith(".residual") else 0.0
        # Loeb's coefficient is a central difference (step 1e-7 relative): its roundoff is ~1e-9 relative
        tol = max(rel, LOEB_REL) if where.endswith(".loeb") else rel
        if math.isclose(golden, new, rel_tol=tol, abs_tol=noise) or golden == new:
            return []
        return [f"{where}: was {golden!r}, now {new!r}"]
    if type(golden) is not type(new) or golden != new:
        return [f"{where}: was {golden!r}, now {new!r}"]
    return []


def main() -> int:
    cli = {}
    for name, argv in COMMANDS.items():
        with tempfile.TemporaryDirectory() as tmp:
            cli[name] = record(name, argv, tmp)
            print(f"{name}: exit {cli[name]['exit']}", file=sys.stderr)
    (HERE / "cli.json").write_text(json.dumps(cli, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    with tempfile.TemporaryDirectory() as tmp:
        rep = report_texts(tmp)
    (HERE / "report.json").write_text(json.dumps(rep, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
