"""Test-suite configuration shared by every test module.

Hypothesis profiles
-------------------
``ci`` (the default, used by ``make test`` and CI): derandomised, so every run on every machine
draws the same examples, and no example database is read or written (a fresh clone and a
developer's tree behave alike). ``fuzz`` (``make test-fuzz``): fresh random seeds and ten times
the examples, to explore; a failure it finds is pinned with ``@example`` in the test so that the
``ci`` profile keeps checking it.
"""

from __future__ import annotations

import os

from hypothesis import HealthCheck, settings

settings.register_profile("ci", derandomize=True, database=None, deadline=None, print_blob=True)
settings.register_profile(
    "fuzz", derandomize=False, database=None, deadline=None, print_blob=True, max_examples=1000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
