"""The one-line notice while a numba kernel compiles (:mod:`opsrock.solvers._compile`), and the cold start of a
first planar and a first 3-D solve (issue 43).

The fast tests use a one-line kernel of their own in a temporary module, compiled in fresh processes with an
empty ``NUMBA_CACHE_DIR`` of the test's own (a second process loads it from that cache); the slow test runs the
real solvers' kernels from an empty cache through the console script.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import textwrap

import pytest
from _support import COMPILE_NOTICE as NOTICE
from _support import run_opsrock

KERNEL_MODULE = textwrap.dedent("""
    import numba

    @numba.njit(cache=True)
    def twice(x):
        return 2.0 * x
""")

#: Announces, calls, announces again (warm in-process now: no second line), prints the answer on stdout.
CALLER = textwrap.dedent("""
    import tiny_kernel
    from opsrock.solvers._compile import announce_compile
    announce_compile(tiny_kernel.twice, "tiny")
    value = tiny_kernel.twice(21.0)
    announce_compile(tiny_kernel.twice, "tiny")
    print(value + tiny_kernel.twice(0.0))
""")


def _run(tmp_path, cache):
    env = {**os.environ, "NUMBA_CACHE_DIR": str(cache), "PYTHONPATH": str(tmp_path)}
    return subprocess.run([sys.executable, "-c", CALLER], capture_output=True, text=True, env=env, timeout=300,
                          stdin=subprocess.DEVNULL, cwd=tmp_path)


def test_notice_on_a_cold_cache_only_once_and_never_on_stdout(tmp_path):
    (tmp_path / "tiny_kernel.py").write_text(KERNEL_MODULE)
    cache = tmp_path / "cache"
    cold = _run(tmp_path, cache)
    assert cold.returncode == 0, cold.stderr
    assert cold.stdout == "42.0\n"
    lines = [x for x in cold.stderr.splitlines() if x.startswith(NOTICE)]
    assert lines == ["opsrock: compiling the tiny kernel (numba, once: later runs load it from the cache); a while"]
    # a second process finds the kernel in the cache: silent
    warm = _run(tmp_path, cache)
    assert warm.returncode == 0, warm.stderr
    assert warm.stdout == "42.0\n" and NOTICE not in warm.stderr


def test_every_compiled_solver_declares_its_compile_time():
    from opsrock.solvers import SOLVERS
    from opsrock.solvers._compile import COMPILE_CPU_S, COMPILE_PART_CPU_S

    compiled = {"friction", "housner_fast", "moreau_jean", "rigid3d", "cylinder3d"}
    assert compiled <= set(SOLVERS)
    assert set(COMPILE_CPU_S) == compiled and all(v > 0.0 for v in COMPILE_CPU_S.values())
    assert {solver for solver, _ in COMPILE_PART_CPU_S} <= compiled
    assert all(v > 0.0 for v in COMPILE_PART_CPU_S.values())


def test_notice_names_a_part_compiled_when_a_case_first_needs_it(capfd):
    import numba

    from opsrock.solvers._compile import COMPILE_PART_CPU_S, announce_compile

    @numba.njit
    def flight(x):
        return x + 1.0

    announce_compile(flight, "friction", part="flight")
    assert flight(1.0) == 2.0
    announce_compile(flight, "friction", part="flight")  # compiled now: silent
    flight(2.0)
    seconds = COMPILE_PART_CPU_S[("friction", "flight")]
    assert capfd.readouterr().err == (f"opsrock: compiling the friction kernel's flight path (numba, once: later runs "
                                      f"load it from the cache); about {seconds:.0f} s of CPU\n")


def test_notice_names_each_specialisation_of_a_kernel_compiled_per_kind_of_argument(capfd):
    """A kernel numba compiles once per kind of argument (rigid3d's, for infinite and for finite friction): given
    the call's ``args``, each specialisation is announced when it first compiles, the first as the kernel, the other
    as its part, and neither again."""
    import numba

    from opsrock.solvers._compile import COMPILE_CPU_S, COMPILE_PART_CPU_S, announce_compile

    @numba.njit
    def kernel(x):
        return x + 1

    announce_compile(kernel, "rigid3d", args=(1.0,))
    assert kernel(1.0) == 2.0
    announce_compile(kernel, "rigid3d", args=(1.0,))  # compiled now: silent
    announce_compile(kernel, "rigid3d", part="finite-friction", args=(1,))  # another kind of argument
    assert kernel(1) == 2
    announce_compile(kernel, "rigid3d", part="finite-friction", args=(1,))
    whole, part = COMPILE_CPU_S["rigid3d"], COMPILE_PART_CPU_S[("rigid3d", "finite-friction")]
    tail = "(numba, once: later runs load it from the cache); about"
    assert capfd.readouterr().err == (f"opsrock: compiling the rigid3d kernel {tail} {whole:.0f} s of CPU\n"
                                      f"opsrock: compiling the rigid3d kernel's finite-friction path {tail} {part:.0f} "
                                      f"s of CPU\n")


def test_fewer_collections_restores_the_collector_however_the_block_ends():
    import gc

    from opsrock.solvers._compile import COMPILE_GC_THRESHOLDS, fewer_collections

    before = gc.get_threshold()
    with fewer_collections():
        inside = gc.get_threshold()
    assert inside == tuple(max(o, n) for o, n in zip(before, COMPILE_GC_THRESHOLDS)) and inside != before
    with pytest.raises(KeyError), fewer_collections():
        raise KeyError("a failed compile")
    assert gc.get_threshold() == before
    gc.set_threshold(0, *before[1:])  # the program turned collection off: it stays off
    try:
        with fewer_collections():
            assert gc.get_threshold()[0] == 0
    finally:
        gc.set_threshold(*before)


# --- cold start of a first solve -----------------------------------------------------------------------------------
#: Issue 43: the first solve in a fresh process with an empty numba cache spends at most this much CPU (s), compile
#: included: 10 s for a planar solver, 30 s for ``rigid3d``.
COLD_CPU_S = {"housner_fast": 10.0, "friction": 10.0, "moreau_jean": 10.0, "rigid3d": 30.0}
#: The block and pulse of issue 43's measurement; ``moreau_jean`` takes Housner's impact only, ``rigid3d`` a depth.
CASE = ["simulate", "--json", "--width", "0.4", "--height", "2.2", "--pfa-ratio", "4", "--freq-ratio", "6"]
EXTRA = {"housner_fast": [], "friction": [], "moreau_jean": ["--restitution-law", "housner"],
         "rigid3d": ["--depth", "0.6"]}
#: Solvers whose cold start is not within the limit (issue 43 open), marked as expected to fail, not strictly:
#: measured (``/usr/bin/time``, user + system, same command as the test, once only the kernels' entry points were
#: numba dispatchers) friction 18.2 s (11.5-12.6 s once its helpers were compiled once each), moreau_jean 8.1-8.6 s
#: (within 10 s, but by less than the fifth the load moves the CPU time: not yet robustly), rigid3d 52.6 s of CPU;
#: housner_fast 5.0 s. Later in issue 43 (friction's loop turn no longer an inlined helper, the garbage collector run
#: less during a compile; alternated with the code before, load average 2-3): friction 9.9/10.4/10.5 s against
#: 11.8/11.9/12.3 s, still not within 10 s with the fifth's margin; moreau_jean 6.3/6.4/6.5 s against 6.7/7.1/7.2 s,
#: within 10 s by more than a fifth, so no longer expected to fail. rigid3d, once its run loop had one exit and its
#: smooth steps took the workspace apart once: 42.7-44.5 s against 44.7-48.0 s before (alternated, load average
#: 2-7), then with the collector change 37.8-39.9 s: still over 30 s, expected to fail. friction, once its free flight
#: was a kernel of its own compiled only when a block first leaves the floor (this case never does): 7.9/7.9/8.6 s and,
#: at load average 3, 9.2/8.8/9.3 s, against 9.6/9.6/10.1 and 10.5/10.4/10.3 s before (alternated): within 10 s, so no
#: longer expected to fail. rigid3d, once its kernel was compiled per friction (this case, infinite friction, compiles
#: the specialisation without the flat slide): 36.5/36.6 s against 40.5/38.5 s before (alternated, load average 2-3),
#: and 35.2/34.7 s against 39.0/39.4 s (load average 2): still over 30 s, expected to fail. rigid3d, once its
#: infinite-friction specialisation left out the coarse slide and every helper its C-callable wrapper: 29.2/28.2 s
#: against 33.1/33.6 s (alternated, load average 0.8-1.0), about 2.5 s of it the system's (CPython's frame-stack
#: chunks mapped and unmapped at the console script's call depth): within 30 s by 3-6 %, less than the fifth the load
#: moves the CPU time, so still marked, not strictly (an unexpected pass is reported, not a failure).
OVER_LIMIT = {"rigid3d"}


def _child_cpu(run):
    """``run()``'s result and the CPU time (user + system, s) of the children it waited for.

    CPU time, not wall time: on a shared machine the wall time of the same compile varies by a factor of two
    to five with the load of the other cores (measured 13.5 s and 27 s of wall time for ``housner_fast``'s 6-7 s
    of CPU), while the CPU time is the compiler's own work, which the other processes do not add to (it still
    varies by up to a fifth with the load, through shared caches: the limit is checked where the margin exceeds
    that)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    result = run()
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return result, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


@pytest.mark.slow
@pytest.mark.parametrize("solver", [
    pytest.param(s, marks=pytest.mark.xfail(strict=False, reason="issue 43: cold start not reliably within the limit"))
    if s in OVER_LIMIT else s for s in sorted(EXTRA)])
def test_first_solve_from_an_empty_cache(solver, tmp_path):
    """A fresh process, an empty ``NUMBA_CACHE_DIR``: the answer within :data:`COLD_CPU_S` of CPU, the
    notice on stderr and the JSON alone on stdout; a second process, warm, prints no notice."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    args = [*CASE, "--solver", solver, *EXTRA[solver]]
    cold, cpu = _child_cpu(lambda: run_opsrock(args, tmp_path, env=env, timeout=900))
    assert cold.returncode == 0, cold.stderr
    assert json.loads(cold.stdout)["solver"] == solver
    assert f"{NOTICE}{solver} kernel" in cold.stderr
    warm = run_opsrock(args, tmp_path, env=env, timeout=900)
    assert warm.returncode == 0 and json.loads(warm.stdout)["theta_max"] == json.loads(cold.stdout)["theta_max"]
    assert NOTICE not in warm.stderr
    assert cpu <= COLD_CPU_S[solver], f"{solver}: {cpu:.1f} s of CPU from an empty cache"
