"""numpydoc on the public API: every name in ``dfa.__all__`` (and the public methods and properties its
classes define in dfa) has the sections a user of ``help()`` and of the API site needs.

One test lists every missing item at once, so a failure says exactly what to write.
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import re
import subprocess
import sys
from pathlib import Path

import pytest
from numpydoc.docscrape import FunctionDoc
from numpydoc.validate import validate

import dfa

ROOT = Path(__file__).resolve().parents[1]

# numpydoc codes every documented object must pass (summary, whitespace, section names and order).
COMMON = {"GL03", "GL05", "GL06", "GL07", "GL08", "GL09", "GL10", "SS01", "SS02", "SS03", "SS04", "SS06"}
# Functions and methods: summary in the infinitive, parameters matching the signature with a type and a
# description, a Returns section with a description when something is returned.
CALLABLE = {"SS05", "PR01", "PR02", "PR03", "PR04", "PR05", "PR06", "PR07", "PR08", "PR09", "PR10"}
CALLABLE |= {"RT01", "RT02", "RT03", "RT04", "RT05"}
# Public functions also point to their neighbours.
FUNCTION = {"SA01", "SA02", "SA03", "SA04"}

# Parameters that carry a physical quantity name its unit in their description.
UNITS = {
    "stiffness": ("N/m", "N·m/rad"),
    "velocity": ("m/s",),
    "mass": ("kg",),
    "damping": ("N·s/m", "N s/m"),
    "coulomb": ("N",),
    "period": (" s",),
    "resolution": (" m",),
    "delay": ("samples",),
    "xi_dot": ("ticks per sample", "ticks/sample"),
    "xi_dot0": ("ticks per sample", "ticks/sample"),
    "xi0": ("ticks",),
    "xi_dots": ("ticks per sample", "ticks/sample"),
}


def _public_objects() -> dict[str, object]:
    """Dotted name -> object for the public functions, classes, and the methods and properties classes define."""
    found: dict[str, object] = {}
    seen: set[int] = set()

    def add(name: str, obj: object) -> None:
        if id(obj) not in seen:
            seen.add(id(obj))
            found[name] = obj

    for name in dfa.__all__:
        obj = getattr(dfa, name)
        if inspect.isclass(obj):
            add(f"dfa.{name}", obj)
            for attr in sorted(dir(obj)):
                if attr.startswith("_"):
                    continue
                owner = next((k for k in obj.__mro__ if attr in vars(k)), None)
                if owner is None or not owner.__module__.startswith("dfa"):
                    continue  # inherited from Exception, Enum, tuple...
                member = vars(owner)[attr]
                kinds = (property, functools.cached_property, staticmethod, classmethod)
                if isinstance(member, kinds) or inspect.isfunction(member):
                    add(f"dfa.{name}.{attr}", member)
        elif callable(obj):
            add(f"dfa.{name}", obj)
    return found


def _attribute_names(cls: type) -> set[str]:
    """Names documented in a class docstring's Attributes (or Parameters) section, ``a, b : type`` split."""
    doc = inspect.getdoc(cls) or ""
    names: set[str] = set()
    for section in re.split(r"\n(?=\S[^\n]*\n-{3,}\n)", doc):
        head = section.split("\n", 1)[0].strip()
        if head not in ("Attributes", "Parameters"):
            continue
        for line in section.splitlines()[2:]:
            if line and not line[0].isspace():
                names.update(n.strip().strip("*") for n in line.split(" : ")[0].split(","))
    return names


def _problems() -> list[str]:
    problems: list[str] = []
    for name, obj in _public_objects().items():
        result = validate(name)
        kind = result["type"]
        is_callable = kind in ("function", "method")
        is_function = is_callable and name.count(".") == 1
        wanted = COMMON | (CALLABLE if is_callable else set()) | (FUNCTION if is_function else set())
        problems += [f"{name}: {code} {message}" for code, message in result["errors"] if code in wanted]
        if inspect.isclass(obj) and dataclasses.is_dataclass(obj):
            documented = _attribute_names(obj)
            missing = [f.name for f in dataclasses.fields(obj) if f.name not in documented]
            if missing:
                problems.append(f"{name}: fields not in its Attributes section: {', '.join(missing)}")
        if is_function and inspect.signature(obj).parameters:  # every public function checks its inputs
            doc = FunctionDoc(obj)
            raises = " ".join(" ".join([p.type, *p.desc]) for p in doc["Raises"])
            if not re.search(r"DFA(Value|Type)Error", raises):
                problems.append(f"{name}: no Raises section naming DFAValueError/DFATypeError")
        if is_callable:
            func = obj.__func__ if isinstance(obj, (staticmethod, classmethod)) else obj
            for p in FunctionDoc(func)["Parameters"]:
                for pname in p.name.split(","):
                    units = UNITS.get(pname.strip())
                    text = " ".join([p.type, *p.desc])
                    if units and not any(u in text for u in units):
                        problems.append(f"{name}: parameter {pname.strip()!r} states no unit ({' or '.join(units)})")
    return problems


def test_public_api_docstrings_complete():
    problems = _problems()
    assert not problems, f"{len(problems)} docstring items missing:\n" + "\n".join(problems)


@pytest.fixture(scope="module")
def docs_site(tmp_path_factory):
    """The site built once for this module's checks: (the build's return code and stderr, its html folder)."""
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    pytest.importorskip("pydata_sphinx_theme")
    tmp = tmp_path_factory.mktemp("docs")
    cmd = [sys.executable, "-m", "sphinx", "-b", "html", "-q", "-W", "--keep-going"]
    cmd += ["-d", str(tmp / "doctrees"), str(ROOT / "docs"), str(tmp / "html")]
    run = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=600)
    return run, tmp / "html"


@pytest.mark.slow
def test_docs_site_builds_without_warnings(docs_site):
    run, html = docs_site
    assert run.returncode == 0, run.stderr[-5000:]
    assert (html / "api.html").exists()


def _pages(html: Path) -> dict[str, str]:
    return {p.name: p.read_text(encoding="utf-8") for p in sorted(html.glob("*.html"))}


@pytest.mark.slow
def test_docs_every_page_has_one_title(docs_site):
    """The paper page showed two H1 titles (its own and the included report's); so did the README, benchmarks and
    validation pages."""
    _run, html = docs_site
    titles = {name: text.count("<h1") for name, text in _pages(html).items()}
    assert titles and all(n == 1 for n in titles.values()), {k: n for k, n in titles.items() if n != 1}


_CONSOLE = re.compile(r'<div class="highlight-console[^"]*"><div class="highlight"><pre>(.*?)</pre>', re.S)


@pytest.mark.slow
def test_docs_console_commands_are_plain_text(docs_site):
    """Pygments' console lexer coloured numbers in commands, and only in part (the 0 of ``--velocity 0.1``)."""
    _run, html = docs_site
    blocks = _CONSOLE.findall(_pages(html)["cli.html"])
    commands = [line for block in blocks for line in block.splitlines() if 'class="gp"' in line]
    assert len(commands) >= 10
    for line in commands:
        command = re.sub(r'<span class="gp">\$ </span>', "", line, count=1)
        assert "<span" not in command.replace("<span></span>", ""), line


@pytest.mark.slow
def test_docs_console_blocks_wrap_instead_of_being_cut(docs_site):
    """Console blocks on the command-line page were clipped at the column's right edge: their long lines wrap."""
    _run, html = docs_site
    assert "_static/dfa.css" in _pages(html)["cli.html"]
    css = re.sub(r"/\*.*?\*/", "", (html / "_static" / "dfa.css").read_text(encoding="utf-8"), flags=re.S)
    rules = dict(re.findall(r"([^{}]+)\{([^}]*)\}", css))
    wrap = [body for sel, body in rules.items() if "highlight-console pre" in sel]
    assert wrap and "white-space: pre-wrap" in wrap[0] and "overflow-wrap: anywhere" in wrap[0]


def test_docs_console_lexer_gives_a_prompt_a_plain_command_and_output():
    """docs/_ext/dfa_docs.py's lexer for ``console`` blocks: no token of a command is a number (Pygments' own lexer
    coloured the 0 of ``0.1``); a ``\\``-continued command stays plain; a block without a final newline ends."""
    pytest.importorskip("pygments")
    from pygments.token import Generic, Text

    sys.path.insert(0, str(ROOT / "docs" / "_ext"))
    try:
        from dfa_docs import ConsoleLexer
    finally:
        sys.path.remove(str(ROOT / "docs" / "_ext"))
    text = "$ dfa check --velocity 0.1 \\\n    --stiffness 80\nmargin  0.9766\n\n$ dfa map --grid 3"
    tokens = [(t, v) for t, v in ConsoleLexer().get_tokens(text) if v]
    assert tokens[0] == (Generic.Prompt, "$ ")
    assert [t for t, _v in tokens[1:3]] == [Text, Text] and tokens[2][1] == "    --stiffness 80\n"
    assert (Generic.Output, "margin  0.9766\n") in tokens
    assert tokens[-2:] == [(Generic.Prompt, "$ "), (Text, "dfa map --grid 3\n")]
