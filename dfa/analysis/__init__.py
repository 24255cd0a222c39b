"""The analyses: each a function of the device and the wall (or their dimensionless groups) returning a frozen result.

Passivity (:mod:`~dfa.analysis.criterion`, :mod:`~dfa.analysis.colgate_schenkel`), exact linear stability
(:mod:`~dfa.analysis.linear`), describing functions and limit cycles (:mod:`~dfa.analysis.describing`,
:mod:`~dfa.analysis.loop`, :mod:`~dfa.analysis.cycles`), exact simulation and maps
(:mod:`~dfa.analysis.simulation`, :mod:`~dfa.analysis.maps`, :mod:`~dfa.analysis.contours`), stiffness limits
(:mod:`~dfa.analysis.limits`), soundness and validation, and the design analysis of a report
(:mod:`~dfa.studies.design`). Analyses import no rendering and no matplotlib beyond a result's ``.plot()``.
"""
