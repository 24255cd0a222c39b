"""The docs' API index (issue 27 §1): no summary cut at the paper's abbreviations, constants documented.

Autosummary ends a summary at the first ". ", which cut 23 of 78 summaries at "eq." ("The critical line of eq.");
docs/conf.py teaches it the paper's abbreviations, and gives each public constant its ``#:`` comment.
"""

from __future__ import annotations

import importlib.util
import inspect
import sys
from pathlib import Path

import pytest

import dfa

sphinx_autosummary = pytest.importorskip("sphinx.ext.autosummary")
CONF = Path(__file__).resolve().parent.parent / "docs" / "conf.py"


@pytest.fixture(scope="module")
def conf():
    spec = importlib.util.spec_from_file_location("dfa_docs_conf", CONF)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)  # patches autosummary's abbreviations (and keeps docs/api.md current)
    return mod


def _settings():
    from docutils.frontend import get_default_settings
    from docutils.parsers.rst import Parser

    return get_default_settings(Parser)


def test_docs_no_api_summary_is_cut_at_an_abbreviation(conf):
    cut = []
    for name in dfa.__all__:
        obj = getattr(dfa, name)
        doc = inspect.getdoc(obj) if (inspect.isclass(obj) or callable(obj)) else None
        if not doc:
            continue
        lines = doc.split("\n\n", 1)[0].splitlines()
        summary = sphinx_autosummary.extract_summary(lines, _settings())
        if summary.endswith(("eq.", "eqs.", "Fig.", "cf.")):
            cut.append(f"{name}: {summary}")
    assert cut == []


def test_docs_constants_show_their_own_comment(conf):
    for name in ("DEFAULT_DEVICE", "LOOP_MODELS", "REGION_DESCRIPTIONS"):
        lines: list[str] = []
        conf._constant_doc(None, "data", f"dfa.{name}", getattr(dfa, name), None, lines)
        text = " ".join(lines)
        assert text and "Built-in" not in text and "str(object" not in text, (name, text)
    assert sys.modules["dfa"].LOOP_MODELS == ("half-delay", "pade", "zoh")
