"""The studies: what runs many analyses for one document, above both the analyses and the rendering.

- :mod:`~dfa.studies.design`: the design analysis of a device (:class:`~dfa.studies.design.DesignAnalysis`), and
  :mod:`~dfa.studies.report` its report's files; :mod:`~dfa.studies.design_document` and
  :mod:`~dfa.studies.design_figures` render it (a study renders its own document);
- :mod:`~dfa.studies.validation`: the validation runs (:mod:`~dfa.studies.validation_document` its report);
- :mod:`~dfa.studies.soundness` (with :mod:`~dfa.studies.soundness_counts`): the criterion's soundness runs
  (:mod:`~dfa.studies.soundness_document` their reports);
- :mod:`~dfa.studies.passivity_comparison`, :mod:`~dfa.studies.contact_comparison`: the catalogue comparisons.

A study imports the analyses, the rendering, the results and the model; nothing imports a study but the command line.
"""
