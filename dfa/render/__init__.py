"""Rendering: figures, documents, terminal text and files drawn from analysis results only (no numerics).

- :mod:`dfa.render.report_figures`: the design report's figures (PNG bytes, nothing written);
- :mod:`dfa.render.document`: the Jinja2 template ``templates/design_report.md.j2`` filled from a
  :class:`~dfa.analysis.design.DesignAnalysis`, and Markdown → self-contained HTML with markdown-it-py;
- :mod:`dfa.render.text`: the tables and sentences the ``dfa`` commands print;
- :mod:`dfa.render.validation`: ``validation.md`` from a :class:`~dfa.analysis.validation.ValidationResult`;
- :mod:`dfa.render.soundness`: the soundness reports from :class:`~dfa.analysis.soundness.CriterionSoundness` records;
- :mod:`dfa.render.files`: a trajectory as CSV, the validation and soundness reports (written atomically).

Numbers are formatted by :mod:`dfa.formatting`. Analyses never import this package (import contracts in
``pyproject.toml``).
"""

__all__: list[str] = []
