"""The results: every frozen result class of the analyses, below both the analyses and the rendering.

A result may import the model (it carries the device and the wall), never an analysis nor the rendering (its
``.plot()`` reaches the figures by name: :func:`dfa.results.base.figure_function`). What every result shares:

- :mod:`~dfa.results.status`: the status enums (snake_case codes, each with its message);
- :mod:`~dfa.results.frozen`: read-only array fields checked on construction;
- :mod:`~dfa.results.xarray`: the optional xarray export of gridded results;

and one module per topic: :mod:`~dfa.results.limits`, :mod:`~dfa.results.require`, :mod:`~dfa.results.grip`,
:mod:`~dfa.results.zwidth`, :mod:`~dfa.results.cycles` (with :mod:`~dfa.results.caveats`),
:mod:`~dfa.results.criterion`, :mod:`~dfa.results.identify`, :mod:`~dfa.results.simulation`,
:mod:`~dfa.results.maps`, :mod:`~dfa.results.contours`, :mod:`~dfa.results.linear`, :mod:`~dfa.results.observer`. Strict JSON (:mod:`dfa.jsonable`) sits below every layer.
"""
