"""What every result shares: status enums, strict JSON, frozen arrays (no analysis, no prose beyond a status message).

- :mod:`~dfa.results.status`: the status enums (snake_case codes, each with its message);
- :mod:`~dfa.results.jsonable`: strict-JSON data of results, nulls with their reasons;
- :mod:`~dfa.results.frozen`: read-only array fields checked on construction;
- :mod:`~dfa.results.xarray`: the optional xarray export of gridded results.
"""
