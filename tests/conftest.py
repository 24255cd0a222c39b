"""Test-suite set-up: headless plotting and the hypothesis profiles.

Profiles (select with ``HYPOTHESIS_PROFILE`` or ``pytest --hypothesis-profile``):

``ci`` (default)
    Derandomised: the same examples on every run and every machine, so a
    failure in CI fails the same way locally. Used by ``make test`` and ``.ci/run``.
``explore``
    Random, many more examples, for hunting counterexamples on demand
    (``make explore``).

``DFA_TESTS_AFTER`` (set by ``make test``): a file whose appearance the tests wait for once collected. ``make test``
starts the kernel warm-up (``tests/compile_kernels.py``) and the suite together and the warm-up writes that
file when it ends: the workers collect the tests (about 12 s of each one's start) while it compiles, then run them
on its kernels.
"""

import os
import time

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


#: Seconds the tests wait at most for ``DFA_TESTS_AFTER`` (a warm-up that hangs: the suite then compiles itself).
WAIT_AT_MOST = 600.0


def pytest_collection_finish(session):
    """Wait, once the tests are collected, for the file ``DFA_TESTS_AFTER`` names (module docstring)."""
    marker = os.environ.get("DFA_TESTS_AFTER")
    deadline = time.monotonic() + WAIT_AT_MOST
    while marker and not os.path.exists(marker) and time.monotonic() < deadline:
        time.sleep(0.1)
