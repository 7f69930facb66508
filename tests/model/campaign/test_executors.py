"""Executors: real process pools and a real Dask LocalCluster (worker processes on loopback)."""

from __future__ import annotations

import os
import signal
import sys
import threading
import time

import pytest

from opsrock.campaign.executors import (
    DASK_EXTRA_HINT,
    DaskExecutor,
    ExecutorUnavailableError,
    LocalPool,
    batch_size,
    make_batches,
)


# Module-level, so that spawned workers can import them by reference.
def square_batch(batch: list[int]) -> list[tuple[int, int, int]]:
    """(item, item², pid of the process that computed it)."""
    return [(x, x * x, os.getpid()) for x in batch]


def dying_batch(batch: list[int]) -> list[tuple[int, int, int]]:
    """Like square_batch, but the worker process dies outright on item 13."""
    if 13 in batch:
        os._exit(1)  # no exception, no cleanup: what a segfault in native code looks like
    return square_batch(batch)


def lost(item: int, reason: str) -> tuple[int, str, int]:
    return (item, reason, -1)


def collect(executor, fn, batches):
    out = {}
    for k, results in executor.map_batches(fn, batches, lost):
        assert k not in out, "a batch was yielded twice"
        assert len(results) == len(batches[k])
        out[k] = results
    assert sorted(out) == list(range(len(batches)))
    return [r for k in sorted(out) for r in out[k]]


def test_batch_size_balances_and_caps():
    assert batch_size(400, 2) == 16  # 400 / (2 workers x 4) = 50, capped at MAX_BATCH = 16
    assert batch_size(40, 2) == 5  # ceil(40 / 8): four batches per worker
    assert batch_size(3, 8) == 1 and batch_size(0, 2) == 1
    items = list(range(10))
    batches = make_batches(items, 4)
    assert [len(b) for b in batches] == [4, 4, 2] and sum(batches, []) == items
    with pytest.raises(ValueError, match="size"):
        make_batches(items, 0)


@pytest.mark.parametrize("workers", [0, -1, 1.5, True])
def test_local_pool_refuses_bad_worker_counts(workers):
    with pytest.raises(ValueError, match="workers"):
        LocalPool(workers)


def test_local_pool_one_worker_still_isolates_items():
    # workers=1 (the default on a one-CPU machine) runs in a worker process too: an item that
    # kills its process must cost that item only, not the campaign and every resume after it.
    batches = make_batches(list(range(20)), 3)
    with LocalPool(1) as pool:
        results = collect(pool, dying_batch, batches)
    by_item = {r[0]: r for r in results}
    assert sorted(by_item) == list(range(20))
    assert by_item[13][2] == -1 and "worker process died" in by_item[13][1]
    assert all(by_item[x][1] == x * x and by_item[x][2] != os.getpid() for x in range(20) if x != 13)


def hanging_batch(batch: list[int]) -> list[tuple[int, int, int]]:
    """Like square_batch, but item 5 blocks in a native call (time.sleep) for an hour."""
    if 5 in batch:
        time.sleep(3600)  # a C call: no Python-level timeout can interrupt it
    return square_batch(batch)


def test_local_pool_kills_a_worker_hung_in_native_code(monkeypatch):
    # The hard backstop: a batch past len(batch) * item_timeout + KILL_GRACE has its worker
    # killed, its items re-run alone, and the one that hangs alone is lost with "timeout".
    import opsrock.campaign.executors as ex

    # The budget of 2 s (plus 1 s of grace) counts from the worker's start, not from the submission (a fresh
    # interpreter's start-up, seconds on a loaded machine, is not the case's): the items that return at once
    # need microseconds of it, the hung one can never meet it.
    monkeypatch.setattr(ex, "KILL_GRACE", 1.0)
    batches = make_batches(list(range(8)), 2)
    with LocalPool(1, item_timeout=2.0) as pool:
        results = collect(pool, hanging_batch, batches)
    by_item = {r[0]: r for r in results}
    assert sorted(by_item) == list(range(8))
    assert by_item[5][2] == -1 and by_item[5][1].startswith("timeout")
    assert all(by_item[x][1] == x * x for x in range(8) if x != 5)
    # (the hour of the hung call was not waited for: item 5's reason says the worker was killed at its budget)


def test_local_pool_two_workers_use_other_processes_and_lose_nothing():
    batches = make_batches(list(range(40)), 3)
    with LocalPool(2) as pool:
        results = collect(pool, square_batch, batches)
    assert [r[:2] for r in results] == [(x, x * x) for x in range(40)]
    pids = {r[2] for r in results}
    assert os.getpid() not in pids and 1 <= len(pids) <= 2


def test_local_pool_survives_a_dying_worker_and_names_the_item():
    # Item 13 kills its worker. Everything else must be computed; 13 alone gets `lost`.
    batches = make_batches(list(range(30)), 4)
    with LocalPool(2) as pool:
        results = collect(pool, dying_batch, batches)
    by_item = {r[0]: r for r in results}
    assert sorted(by_item) == list(range(30))
    assert by_item[13][2] == -1 and "worker process died" in by_item[13][1]
    assert all(by_item[x][1] == x * x for x in range(30) if x != 13)


def test_dask_missing_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed -> ImportError
    with pytest.raises(ExecutorUnavailableError) as info:
        DaskExecutor(local_workers=1)
    assert str(info.value) == DASK_EXTRA_HINT and "opsrock[dask]" in str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    "kwargs, match",
    [({}, "exactly one"), ({"scheduler": "localhost", "local_workers": None}, "tcp://"),
     ({"local_workers": 0}, "local_workers")],
)
def test_dask_refuses_bad_arguments(kwargs, match):
    with pytest.raises(ValueError, match=match):
        DaskExecutor(**kwargs)


@pytest.mark.slow  # ~10 s of cluster start-up; test_campaign's executor-identity test runs Dask in the fast suite
def test_dask_local_cluster_two_processes():
    pytest.importorskip("distributed")
    batches = make_batches(list(range(20)), 3)
    with DaskExecutor(local_workers=2) as ex:
        assert ex.workers == 2 and ex.scheduler.startswith("tcp://127.0.0.1:")
        results = collect(ex, square_batch, batches)
    assert [r[:2] for r in results] == [(x, x * x) for x in range(20)]
    assert os.getpid() not in {r[2] for r in results}  # worker processes, not threads


@pytest.mark.slow  # a cluster's start-up, as above
def test_a_local_cluster_starts_without_warning_when_port_8787_is_taken():
    """Two campaigns at once (or a user's own Dask cluster) hold 8787, distributed's default HTTP port: the local
    cluster needs no fixed port, so nothing is said about it (two make test runs side by side showed the warning)."""
    pytest.importorskip("distributed")
    import socket
    import warnings

    holder = socket.socket()
    try:
        holder.bind(("127.0.0.1", 8787))
        holder.listen()
    except OSError:
        pass  # already held by another process: the same situation
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            with DaskExecutor(local_workers=1) as ex:
                assert collect(ex, square_batch, make_batches([3], 1))[0][:2] == (3, 9)
    finally:
        holder.close()
    assert not [str(w.message) for w in caught if "8787" in str(w.message)]


def kernel_loaded_batch(batch: list[int]) -> list[tuple[int, bool, int]]:
    """(item, whether housner_fast's kernel was compiled or loaded in this worker before the item, pid)."""
    from opsrock.solvers.housner_fast import kernel

    return [(x, bool(kernel.solve_case.signatures), os.getpid()) for x in batch]


@pytest.mark.parametrize("warm", [("housner_fast",), ()])
def test_a_worker_makes_its_kernel_ready_before_it_takes_a_case(warm):
    # The case budget counts from a worker's start; a worker told which solver it serves loads that solver's
    # compiled kernel first (opsrock.solvers.warm_up), so no case pays for a compile or a cache load: the kernel
    # is there before the first item, whatever the machine's speed. Without `warm`, it is not.
    with LocalPool(1, warm=warm) as pool:
        results = collect(pool, kernel_loaded_batch, make_batches([0, 1], 2))
    assert [r[1] for r in results] == [bool(warm)] * 2


def test_a_stop_another_thread_takes_while_workers_spawn_waits_for_the_spawn():
    """The signal mask holds a stop back from the main thread only; a thread started earlier (a progress bar's)
    can take it, and Python then runs the handler in the main thread mid-spawn. Sent to such a thread
    (``pthread_kill``, so the kernel cannot pick another), a Ctrl-C must still wait for the held block's end.
    Python's own Ctrl-C handler is set for the test, whatever runs it (a pytest-xdist worker ignores SIGINT)."""
    from opsrock.campaign.executors import _interrupts_held

    go, sent = threading.Event(), threading.Event()

    def other_thread():
        go.wait(10)
        signal.pthread_kill(threading.get_ident(), signal.SIGINT)
        sent.set()

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        thread = threading.Thread(target=other_thread)
        thread.start()  # before the block: this thread's mask lets SIGINT in
        steps = 0
        with pytest.raises(KeyboardInterrupt):
            with _interrupts_held():
                go.set()
                assert sent.wait(10)
                thread.join(10)
                for _ in range(10_000):  # bytecode on which Python would run a pending handler
                    steps += 1
        assert steps == 10_000  # the whole block ran; the KeyboardInterrupt came after it
    finally:
        signal.signal(signal.SIGINT, previous)
