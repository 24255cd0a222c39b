"""Rendering: figures, documents, terminal text and files drawn from analysis results only (no numerics).

- :mod:`dfa.render.text`: the tables and sentences the ``dfa`` commands print;
- :mod:`dfa.render.files`: a trajectory as CSV (written atomically);
- :mod:`dfa.render.figures`: the figures (matplotlib), one module per thing drawn, reached by a result's ``.plot()``
  by name (:func:`dfa.results.base.figure_function`);
- ``templates/``: the Jinja2 templates (the design report's, filled by :mod:`dfa.studies.design_document`).

A study's own document (the design report, the validation and soundness reports, the catalogue comparisons) is
rendered by the study (:mod:`dfa.studies`), from these pieces.

Numbers are formatted by :mod:`dfa.formatting`. Rendering and the analyses are independent siblings: this package
imports no analysis, and no analysis imports it (import contracts in ``pyproject.toml``).
"""

__all__: list[str] = []
