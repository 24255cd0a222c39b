"""Rendering: figures and documents drawn from analysis results only (no numerics, no file writes).

:mod:`dfa.render.figures` draws the design report's figures (PNG bytes); :mod:`dfa.render.document` fills the
Jinja2 template ``templates/design_report.md.j2`` and turns Markdown into self-contained HTML with markdown-it-py.
"""

__all__: list[str] = []
