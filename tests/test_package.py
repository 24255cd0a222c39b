"""Package hygiene: import graph, public API, packaging."""

import subprocess
import sys
from pathlib import Path

import dfa


def test_import_dfa_does_not_load_matplotlib():
    # python-control imports matplotlib itself, so it must not be imported eagerly either
    # nor numba: kernels import it on their first call (dfa.core.jit)
    code = "import sys, dfa, dfa.cli; print(sorted(m for m in ('matplotlib', 'control', 'numba') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "[]"


#: What `dfa check` must not load (issue 27 §1, issue 41 §2: it started in 3.5 times `import numpy`): python-control,
#: numba, scipy, the cycle solver, and the analyses and readers of the other commands, which `import dfa` loads on
#: first use (dfa._DEFERRED), the fit of `dfa identify`, the installed version's metadata (importlib.metadata).
NOT_FOR_CHECK = (
    "control", "matplotlib", "numba", "scipy", "dfa.analysis.cycles", "dfa.analysis.identify", "dfa.analysis.check",
    "dfa.analysis.colgate_schenkel", "dfa.analysis.limits.closed_form", "dfa.analysis.linear_wall", "dfa.model.log",
    "importlib.metadata",
)  # fmt: skip


def _loaded_by(commands: list[list[str]], modules: tuple[str, ...], then: str) -> list[str]:
    """In a fresh interpreter: run each dfa command (its output discarded, exit 0 asserted), print which of
    ``modules`` are loaded (a sorted list), then ``import dfa`` and run the line ``then``; return the lines."""
    runs = "".join(f"    assert main({argv!r}) == 0\n" for argv in commands)
    code = (
        "import io, sys, contextlib\nfrom dfa.cli import main\nwith contextlib.redirect_stdout(io.StringIO()):\n"
        f"{runs}print(sorted(m for m in {modules!r} if m in sys.modules))\nimport dfa\n{then}"
    )
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split("\n")


def test_dfa_check_loads_neither_python_control_nor_numba_nor_the_other_commands_analyses():
    """`dfa check` starts fast: its text needs none of :data:`NOT_FOR_CHECK`; they still load when used."""
    then = "print(dfa.stiffness_limits.__module__, dfa.read_log.__module__, dfa.__version__ == dfa._version())"
    out = _loaded_by([["check", "--device", "delta", "--velocity", "0.1"]], NOT_FOR_CHECK, then)
    assert out[0] == "[]"
    assert out[1] == "dfa.analysis.limits.closed_form dfa.model.log True"


#: What the everyday design commands must not load (issue 43: python-control took 1.6 s of `dfa stiffness`'s
#: 2.4 s): python-control (and matplotlib through it), sympy (the describing function's derivation, cached as
#: numbers in dfa.core.dfcore) and scipy.signal, scipy.integrate and scipy.stats.
NOT_FOR_DESIGN = ("control", "matplotlib", "sympy", "scipy.signal", "scipy.integrate", "scipy.stats")


def test_everyday_commands_do_not_load_python_control_sympy_or_scipy_signal():
    """`dfa stiffness` and `dfa simulate` answer without :data:`NOT_FOR_DESIGN`; `QuantizerNonlinearity` loads it."""
    commands = [
        ["stiffness", "--device", "impulse", "--velocity", "0.1"],
        ["simulate", "--device", "impulse", "--velocity", "0.1", "--stiffness", "500"],
    ]
    out = _loaded_by(commands, NOT_FOR_DESIGN, "print(dfa.QuantizerNonlinearity.__module__, 'control' in sys.modules)")
    assert out[0] == "[]"
    assert out[1] == "dfa.analysis.nonlinearities True"


def test_public_api_is_listed_and_importable():
    for name in dfa.__all__:
        assert hasattr(dfa, name), name
    assert issubclass(dfa.DFAValueError, ValueError) and issubclass(dfa.DFATypeError, TypeError)


def test_catalogue_is_package_data():
    from importlib import resources

    assert resources.files("dfa.model").joinpath("data/devices.toml").is_file()
    assert resources.files("dfa").joinpath("py.typed").is_file()
    assert resources.files("dfa.render").joinpath("templates/design_report.md.j2").is_file()


def test_top_level_functions_survive_submodule_imports():
    # a submodule named like a function would rebind dfa.<name> to the module on import
    import dfa.analysis.cycles
    import dfa.analysis.simulation

    assert dfa.simulate.__name__ == "simulate" and callable(dfa.simulate)
    assert dfa.limit_cycles.__name__ == "limit_cycles" and callable(dfa.limit_cycles)
    for name in ("stability_map", "contour_maps", "validate", "design_report", "growth_threshold"):
        assert callable(getattr(dfa, name)), name


def test_hypothesis_ci_profile_is_derandomised():
    """`make test` and CI run hypothesis derandomised: a failure repeats the same way everywhere."""
    import os

    from hypothesis import settings

    if os.environ.get("HYPOTHESIS_PROFILE", "ci") == "ci":
        assert settings.default.derandomize is True
        assert settings.default.database is None
    assert settings.get_profile("ci").derandomize is True
    assert settings.get_profile("explore").derandomize is False


def test_import_contracts_kept():
    # the layering rules (core -> results -> analyses | rendering -> studies -> CLI; matplotlib, jinja2, markdown-it
    # only in rendering)
    # are import-linter contracts in pyproject.toml; they replace tests that grepped the source for imports
    import os
    import shutil
    from pathlib import Path

    import pytest

    exe = Path(sys.executable).parent / "lint-imports"
    if not exe.exists():
        exe = Path(shutil.which("lint-imports") or "lint-imports")
    if not exe.exists():
        pytest.skip("import-linter is not installed (pip install -e '.[dev]')")
    root = Path(__file__).resolve().parent.parent
    proc = subprocess.run([str(exe)], cwd=root, capture_output=True, text=True, env=dict(os.environ))
    assert proc.returncode == 0, proc.stdout[-3000:]
    assert "broken" in proc.stdout and " 0 broken" in proc.stdout


def _cycles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Strongly connected components of more than one module (Tarjan), iteratively."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    out: list[list[str]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    work.append((w, iter(sorted(edges.get(w, ())))))
                elif w in stack:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def test_no_import_cycle_between_modules_counting_imports_inside_functions_and_packages():
    # grimp (import-linter's graph) records every import statement, those inside functions included, and a
    # package's __init__ as a module: "loop imports dfa.analysis.cycles, whose __init__ imports solve, which
    # imports loop" is a cycle here (it was one, until the loop models moved to dfa.analysis.loop_models)
    import pytest

    grimp = pytest.importorskip("grimp", reason="import-linter is not installed (pip install -e '.[dev]')")
    graph = grimp.build_graph("dfa")
    edges = {m: set(graph.find_modules_directly_imported_by(m)) for m in graph.modules}
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]  # the check can fail
    cycles = _cycles(edges)
    if cycles:
        pytest.fail(f"import cycles: {cycles}")


def test_every_function_in_dfa_is_under_80_lines_of_code():
    # issue 13: small functions. Counted without the docstring (numpydoc sections are documentation, not logic).
    import ast

    long = []
    for path in sorted((Path(dfa.__file__).parent).rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                lines = node.end_lineno - node.lineno + 1
                first = node.body[0]
                if (
                    isinstance(first, ast.Expr)
                    and isinstance(first.value, ast.Constant)
                    and isinstance(first.value.value, str)
                ):
                    lines -= first.end_lineno - first.lineno + 1
                if lines >= 80:
                    long.append(f"{path.name}:{node.lineno} {node.name} ({lines} lines)")
    assert not long, "functions of 80 lines or more: " + ", ".join(long)


def test_every_subpackage_is_in_the_distribution():
    """A non-editable install ships every package under dfa/ (dfa.analysis.cycles was once missing from a fixed list)."""
    from fnmatch import fnmatch

    try:
        import tomllib
    except ModuleNotFoundError:  # Python 3.10
        import tomli as tomllib  # type: ignore[no-redef]

    root = Path(__file__).resolve().parents[1]
    cfg = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    patterns = cfg["packages"]["find"]["include"]
    subpackages = [".".join(p.parent.relative_to(root).parts) for p in (root / "dfa").rglob("__init__.py")]
    assert "dfa.analysis.cycles" in subpackages and "dfa.render" in subpackages
    missing = [name for name in subpackages if not any(fnmatch(name, pat) for pat in patterns)]
    assert missing == [], f"packages left out of the distribution: {missing}"
