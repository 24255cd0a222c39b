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


@pytest.mark.slow
def test_docs_site_builds_without_warnings(tmp_path):
    pytest.importorskip("sphinx")
    pytest.importorskip("myst_parser")
    pytest.importorskip("pydata_sphinx_theme")
    cmd = [sys.executable, "-m", "sphinx", "-b", "html", "-q", "-W", "--keep-going"]
    cmd += ["-d", str(tmp_path / "doctrees"), str(ROOT / "docs"), str(tmp_path / "html")]
    run = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-5000:]
    assert (tmp_path / "html" / "api.html").exists()
