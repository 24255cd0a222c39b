"""Test-suite set-up: headless plotting and the hypothesis profiles.

Profiles (select with ``HYPOTHESIS_PROFILE`` or ``pytest --hypothesis-profile``):

``ci`` (default)
    Derandomised: the same examples on every run and every machine, so a
    failure in CI fails the same way locally. Used by ``make test`` and ``.ci/run``.
``explore``
    Random, many more examples, for hunting counterexamples on demand
    (``make explore``).
"""

import os

os.environ.setdefault("MPLBACKEND", "Agg")

from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    max_examples=60,
    deadline=None,
    derandomize=True,
    database=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "explore",
    max_examples=1000,
    deadline=None,
    derandomize=False,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
