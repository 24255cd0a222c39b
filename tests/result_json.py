"""Shared check of results on dfa.results.base.Result: ``to_dict()`` is derived from the fields."""

import dataclasses
import json


def json_keys(result) -> set[str]:
    """The keys :meth:`dfa.results.base.Result.to_dict` writes: fields (but ``json: None``, and an ``omit_none`` field
    that is None), json_properties, message."""
    keys = {
        f.name
        for f in dataclasses.fields(result)
        if f.metadata.get("json", True) is not None
        and not (f.metadata.get("omit_none") and getattr(result, f.name) is None)
    }
    keys |= set(type(result).json_properties)
    if getattr(result, "status", None) is not None:
        keys.add("status_message")
    if result.units():
        keys.add("units")
    return keys


def assert_json_from_fields(result, extra=frozenset()) -> dict:
    """``to_dict()`` has exactly :func:`json_keys` (plus ``extra``; ``null_reasons`` where a value is null) and is
    strict JSON; returns it."""
    d = result.to_dict()
    assert set(d) - {"null_reasons"} == json_keys(result) | set(extra)
    json.dumps(d, allow_nan=False)
    return d


def written(value):
    """``value`` as the JSON output writes it (``dfa.jsonable.dumps``: floats to 12 significant digits).

    Tests that compare a number of ``--json`` (or a JSON file) with the API's compare it with this: the same
    serialiser, so equal means equal to the 12 digits JSON carries (issue 41), not to the last bit of a float.
    """
    from dfa.jsonable import dumps

    return json.loads(dumps(value))
