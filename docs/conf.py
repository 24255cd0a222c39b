"""Sphinx configuration of the dfa documentation (``make docs`` builds it into docs/_build/html)."""

from __future__ import annotations

import importlib.metadata
import os
import sys

sys.path.insert(0, os.path.abspath(".."))
sys.path.insert(0, os.path.abspath("_ext"))

project = "dfa"
author = "dfa developers"
copyright = "2026, dfa developers"
try:
    release = importlib.metadata.version("dfa-haptics")
except importlib.metadata.PackageNotFoundError:  # the distribution is still named "dfa" in an old install
    release = importlib.metadata.version("dfa")
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "dfa_docs",  # docs/_ext: plain console commands, console blocks that wrap (docs/_static/dfa.css)
]
autosummary_generate = True


def _keep_paper_abbreviations() -> None:
    """Autosummary ends a summary at the first ". ": teach it the paper's abbreviations ("the critical line of
    eq. 6" was cut at "eq."), as it knows "e.g." and "et al."."""
    import sphinx.ext.autosummary as autosummary

    ours = ("eq.", "eqs.", "Eq.", "Fig.", "fig.", "cf.", "Sec.", "sec.", "approx.")
    autosummary.WELL_KNOWN_ABBREVIATIONS = (*autosummary.WELL_KNOWN_ABBREVIATIONS, *ours)  # type: ignore[attr-defined]


_keep_paper_abbreviations()
autodoc_typehints = "none"  # numpydoc's Parameters sections carry the types and units
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build"]
suppress_warnings = ["myst.header", "myst.xref_missing"]
html_theme = "pydata_sphinx_theme"
html_static_path = ["_static"]
html_title = f"dfa {release}"


def _write_api_page() -> None:
    """Write api.md from ``dfa.__all__`` so the reference never lists a stale name."""
    import dfa

    names = "\n".join(f"   {n}" for n in sorted(dfa.__all__))
    text = (
        "# API reference\n\nEverything listed here is in `dfa.__all__`; the rest of the package is internal.\n\n"
        "```{eval-rst}\n.. currentmodule:: dfa\n\n.. autosummary::\n   :toctree: generated\n   :nosignatures:\n\n"
        f"{names}\n```\n"
    )
    here = os.path.dirname(__file__)
    generated = os.path.join(here, "generated")
    if os.path.isdir(generated):  # stubs of names no longer public (autosummary would build them and fail)
        keep = {f"dfa.{n}" for n in dfa.__all__}
        for f in os.listdir(generated):
            if f.endswith(".rst") and ".".join(f.split(".")[:2]) not in keep:
                os.remove(os.path.join(generated, f))
    path = os.path.join(here, "api.md")
    old = open(path, encoding="utf-8").read() if os.path.exists(path) else None
    if old != text:
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)


_write_api_page()


def _constant_doc(app: object, what: str, name: str, obj: object, options: object, lines: list[str]) -> None:
    """A public constant's docstring is its ``#:`` comment where it is defined, not its type's (``str``, ``tuple``):
    autosummary showed "Built-in immutable sequence." for ``dfa.LOOP_MODELS``."""
    if what not in ("data", "attribute") or not name.startswith("dfa."):
        return
    from sphinx.pycode import ModuleAnalyzer

    short = name.rsplit(".", 1)[-1]
    for modname, module in sorted(sys.modules.items()):
        if not modname.startswith("dfa.") or getattr(module, short, None) is not obj:
            continue
        try:
            docs = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:
            continue
        if ("", short) in docs:
            lines[:] = [line for line in docs[("", short)] if line is not None]
            return


def setup(app: object) -> None:
    """Connect the constants' docstrings (:func:`_constant_doc`)."""
    app.connect("autodoc-process-docstring", _constant_doc)  # type: ignore[attr-defined]
