"""Where a campaign's cases run: one executor interface, two implementations.

* :class:`LocalPool` (the default): a ``concurrent.futures.ProcessPoolExecutor`` over the local
  cores; every item runs in a worker process, ``workers=1`` included.
* :class:`DaskExecutor`: a ``dask.distributed`` cluster, an existing one
  (``scheduler="tcp://HOST:PORT"``) or a ``LocalCluster`` of worker *processes* on loopback
  (``local_workers=N``). Dask is an optional extra: ``pip install "opsrock[dask]"``.

Both run a picklable function over *batches* of items and yield each batch's results as soon as
the batch finishes, in completion order, tagged with the batch's index. Batching keeps the
scheduling overhead (inter-process messages, and for Dask the scheduler's bookkeeping) small
against the solve time: see :func:`batch_size`.

Each worker process owns its interpreter, hence its own OpenSees state (OpenSeesPy keeps one
global model per process, so two solves must never share a process at the same time: the local
pool's workers and the ``LocalCluster`` workers run one thread each).

A worker that dies (a segmentation fault in native code, ``os._exit``, the OOM killer) does not
stop the campaign. The batches it may have been running are re-run one item at a time, each
alone, so that the item that kills its worker is identified; that item's result is then built
by the caller's ``lost(item, reason)`` function, with a reason that starts with
:data:`LOST_PREFIX` (lost to the infrastructure: a resume computes it again), and
every other item is computed normally. An item that overruns its budget alone is the solver's failure: its
reason starts ``"timeout"``.

Workers that end before they start, because the main script has no ``if __name__ == "__main__":`` guard
(:func:`opsrock._pool.pool_allowed`), stop the campaign at once with
:class:`~opsrock.errors.UnguardedScriptError`; with ``workers=1`` the items then run in this process.
"""

from __future__ import annotations

import contextlib
import math
import multiprocessing
import os
import signal
import threading
import time
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures import TimeoutError as FutureTimeout
from concurrent.futures.process import BrokenProcessPool
from typing import Callable, Iterator, Protocol, Sequence, TypeVar, runtime_checkable

from opsrock._pool import (UNGUARDED_EXIT, deferred_interrupts, leave_if_reimported, pool_allowed, unguarded_error,
                           warn_unguarded_here, worker_start)
from opsrock.errors import ExecutorUnavailableError, InputError
from opsrock.limits import check_count

T = TypeVar("T")
R = TypeVar("R")

#: Batches per worker that :func:`batch_size` aims for: enough for load balancing (a slow
#: batch at the end idles the other workers for at most about a quarter of a worker's share).
BATCHES_PER_WORKER: int = 4

#: Largest automatic batch: bounds the work lost when a run is interrupted (results are
#: stored per finished batch) and the granularity of the progress bar.
MAX_BATCH: int = 16

#: Seconds a batch may run past its items' budgets before :class:`LocalPool` kills its worker:
#: room for the in-process budget to fire first and for a spawned worker's imports.
KILL_GRACE: float = 30.0

#: How often (s) the pool looks whether a worker has started, while none has: a batch's budget is counted from
#: then, never from its submission, so a worker's start-up (a fresh interpreter's imports, seconds on a loaded
#: machine) is never charged to a case.
READY_POLL: float = 0.1

#: The optional extra that provides Dask.
DASK_EXTRA_HINT: str = 'the Dask executor needs the optional extra: pip install "opsrock[dask]"'


@runtime_checkable
class Executor(Protocol):
    """Runs ``fn`` over batches of items, yielding ``(batch_index, results)`` as batches finish.

    ``fn(batch)`` must return one result per item, in the batch's order, and must not raise
    for a bad item (the caller turns per-item errors into results). ``lost(item, reason)``
    builds the result of an item whose worker process died while running it, alone.
    """

    workers: int

    def map_batches(
        self,
        fn: Callable[[list[T]], list[R]],
        batches: Sequence[list[T]],
        lost: Callable[[T, str], R],
    ) -> Iterator[tuple[int, list[R]]]:
        """Yield ``(index into batches, fn(batch))`` for every batch, in completion order."""

    def close(self) -> None:
        """Release workers and connections."""


def batch_size(n_items: int, workers: int, *, per_worker: int = BATCHES_PER_WORKER, cap: int = MAX_BATCH) -> int:
    """Items per batch: about ``per_worker`` batches per worker, at most ``cap``, at least 1.

    Parameters
    ----------
    n_items : int
        Items to run (>= 0).
    workers : int
        Worker processes (>= 1).
    per_worker : int, optional
        Batches per worker to aim for (load balancing).
    cap : int, optional
        Largest batch (bounds the work lost on interruption).
    """
    if n_items <= 0:
        return 1
    return max(1, min(cap, math.ceil(n_items / (max(1, workers) * per_worker))))


def make_batches(items: Sequence[T], size: int) -> list[list[T]]:
    """Split ``items`` into consecutive lists of ``size`` (the last may be shorter)."""
    if size < 1:
        raise InputError(f"size must be >= 1, got {size!r}")
    return [list(items[k : k + size]) for k in range(0, len(items), size)]


#: Reason prefix of a case lost to the infrastructure: its worker process died or its pool broke while it ran
#: alone (``BrokenProcessPool``), or its Dask worker was lost (``KilledWorker``). Such a case is stored failed
#: (never a verdict), and is not a result: a resume computes it again. A case the solver failed (it did not
#: converge, ran past its budget, raised) is a result: stored failed with its reason, and reused.
LOST_PREFIX: str = "lost to the infrastructure: "

#: Texts that mark a lost case in a reason: :data:`LOST_PREFIX` (also inside a record case's ``"floor motion
#: failed: ..."``), and the reason stores written before it gave such a case.
LOST_MARKERS: tuple[str, ...] = (LOST_PREFIX, "worker process died")


def is_lost(reason: str | None) -> bool:
    """Is ``reason`` (a stored failure reason) that of a case lost to the infrastructure (:data:`LOST_PREFIX`)?"""
    return bool(reason) and any(m in reason for m in LOST_MARKERS)


def _lost_reason(kind: str, detail: str) -> str:
    return f"{LOST_PREFIX}worker process died while solving this case alone ({kind}: {detail})"


class _Closing:
    """Context-manager protocol shared by the executors: ``with`` closes them."""

    def close(self) -> None:  # pragma: no cover - overridden
        raise NotImplementedError

    def __enter__(self):
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


# --- local process pool ------------------------------------------------------------------------
class LocalPool(_Closing):
    """Local worker processes (``concurrent.futures.ProcessPoolExecutor``).

    Every item runs in a worker process, never in the caller's: a case that kills its process
    (a native crash, the OOM killer) or hangs in native code costs that case only, whatever the
    worker count, and a resumed campaign does not die on it again.

    Parameters
    ----------
    workers : int, optional
        Worker processes, >= 1. Default: the number of CPUs available to this process.
    mp_context : str, optional
        ``multiprocessing`` start method. Default ``"spawn"``: every worker starts from a fresh
        interpreter (no OpenSees model, thread or lock inherited from the parent), the same on
        Linux, macOS and Windows; it costs about a second of imports per worker, once.
    item_timeout : float, optional
        Hard wall-clock budget per item (s). A batch still running after ``len(batch) *
        item_timeout + KILL_GRACE`` seconds has its worker processes killed; its items are then
        re-run one at a time, and an item that overruns alone gets ``lost(item, reason)`` with a
        reason starting ``"timeout"``. This backs up the in-process budget
        (:func:`opsrock.campaign.timeout.time_limit`), which cannot interrupt native code. None: no limit.
        The budget counts from a worker's start (once it has started and warmed ``warm``), never from the
        submission.
    warm : sequence of str, optional
        Solvers whose compiled kernels each worker loads before it takes work (:func:`opsrock.solvers.warm_up`),
        so that no item's budget pays for them. Default: none.

    Raises
    ------
    UnguardedScriptError
        ``workers`` > 1 inside a worker process (:func:`opsrock._pool.pool_allowed`), or, from
        :meth:`map_batches`, workers that ended re-running a main script without an
        ``if __name__ == "__main__":`` guard. With ``workers=1`` the items run in this process instead (no
        protection against a case that kills its process; a warning says so when the script is unguarded).
    """

    def __init__(self, workers: int | None = None, *, mp_context: str = "spawn",
                 item_timeout: float | None = None, warm: Sequence[str] = ()) -> None:
        if workers is None:
            workers = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
        check_count("workers", workers)
        if mp_context not in multiprocessing.get_all_start_methods():
            raise InputError(
                f"mp_context must be one of {multiprocessing.get_all_start_methods()}, got {mp_context!r}"
            )
        if item_timeout is not None and not (isinstance(item_timeout, (int, float)) and item_timeout > 0):
            raise InputError(f"item_timeout must be a positive number of seconds, got {item_timeout!r}")
        self.workers = workers
        self.mp_context = mp_context
        self.item_timeout = None if item_timeout is None or math.isinf(item_timeout) else float(item_timeout)
        self.warm = tuple(warm)
        self._pool: ProcessPoolExecutor | None = None
        self._ready = None  # the pool's count of started workers (a shared multiprocessing.Value)
        self._processes: dict = {}  # the pool's worker processes, kept to read their exit status once it broke
        #: Run the items in this process: no worker may start here (``workers=1`` only).
        self.here = not pool_allowed(workers)

    def __repr__(self) -> str:
        return f"LocalPool(workers={self.workers})"

    def _new_pool(self, workers: int) -> ProcessPoolExecutor:
        self._shutdown_pool()
        context = multiprocessing.get_context(self.mp_context)
        self._ready = context.Value("i", 0)  # workers that have started (worker_start counts itself in)
        self._pool = ProcessPoolExecutor(max_workers=workers, mp_context=context,
                                         initializer=worker_start, initargs=(os.getpid(), self._ready, self.warm))
        self._processes = self._pool._processes  # the same dict, filled as workers start; kept after shutdown
        return self._pool

    def _unguarded(self) -> bool:
        """After a break: did a worker end re-running the main script (status :data:`UNGUARDED_EXIT`)? Then
        ``workers=1`` goes on in this process (with a warning) and more workers raise :func:`unguarded_error`."""
        deadline = time.monotonic() + UNGUARDED_WAIT
        procs = list(self._processes.values())
        for proc in procs:
            proc.join(timeout=max(0.0, deadline - time.monotonic()))
        if UNGUARDED_EXIT not in exit_codes(procs, deadline):
            return False
        self._kill_pool()
        if self.workers > 1:
            raise unguarded_error()
        warn_unguarded_here()
        self.here = True
        return True

    def _kill_pool(self) -> None:
        """Kill the worker processes (a hung native call cannot be stopped otherwise)."""
        if self._pool is not None:
            for proc in list(getattr(self._pool, "_processes", {}).values()):
                proc.kill()
        self._shutdown_pool()

    def _shutdown_pool(self) -> None:
        """Shut the pool down and wait for its manager thread: it is only called with the workers idle (the
        batches done), dead (a broken pool) or killed (:meth:`_kill_pool`), so the wait is short. Left running,
        the manager thread closed its wake-up pipe while the interpreter's exit handler of
        ``concurrent.futures`` wrote to it, and a run that stopped (SIGTERM, an unwritable standard output)
        printed "Exception ignored ... OSError: [Errno 9] Bad file descriptor" after its one line (CPython 3.11;
        twice in fresh clones' ``make test``)."""
        if self._pool is not None:
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None

    def close(self) -> None:
        """Stop the worker processes (queued batches are cancelled)."""
        self._shutdown_pool()

    def _started(self) -> int:
        """How many workers of the current pool have started (and so take batches)."""
        return self._ready.value if self._ready is not None else 0

    def _deadlines(self, running: dict) -> float:
        """Give the batches now being worked on their deadlines, and return the earliest (inf: none). A batch's
        clock starts once a worker can have taken it: with ``r`` workers started, the ``r`` oldest batches in
        flight (the pool's call queue is first in, first out). The others wait, their clock not running."""
        if self.item_timeout is None:
            return math.inf
        started = self._started()
        now = time.monotonic()
        for rank, (fut, (k, deadline, n)) in enumerate(list(running.items())):
            if deadline is None and rank < started:
                running[fut] = (k, now + n * self.item_timeout + KILL_GRACE, n)
        pending = [d for _, d, _ in running.values() if d is None]
        first = min((d for _, d, _ in running.values() if d is not None), default=math.inf)
        return min(first, now + READY_POLL) if pending else first

    def map_batches(
        self,
        fn: Callable[[list[T]], list[R]],
        batches: Sequence[list[T]],
        lost: Callable[[T, str], R],
    ) -> Iterator[tuple[int, list[R]]]:
        """Yield ``(batch_index, fn(batch))`` in completion order (see :class:`Executor`)."""
        # At most `workers` batches in flight: when the pool breaks, exactly those batches
        # may have been running, and only they need the one-at-a-time re-run.
        todo = list(range(len(batches)))[::-1]  # a stack, popped from the end = in order
        suspects: list[int] = []
        try:
            if not self.here:
                yield from self._run_batches(fn, batches, todo, suspects)
            while todo:  # no worker may start here (workers=1): this process runs what is left
                k = todo.pop()
                yield k, fn(batches[k])
            # Suspects: every item alone in a one-worker pool, so a death names its item.
            for k in sorted(suspects):
                yield k, [self._run_alone(fn, item, lost) for item in batches[k]]
        except BaseException:  # Ctrl-C, or the caller stopped: the workers' batches are not waited for
            self._kill_pool()
            raise
        finally:
            self._shutdown_pool()

    def _run_batches(self, fn, batches, todo: list[int], suspects: list[int]) -> Iterator[tuple[int, list]]:
        pool = self._new_pool(self.workers)
        running: dict[Future, tuple[int, float | None, int]] = {}  # batch, deadline (None: not started), items
        while todo or running:
            while todo and len(running) < self.workers:
                k = todo.pop()
                try:
                    with _interrupts_held():  # a worker spawned now starts deaf to Ctrl-C
                        fut = pool.submit(fn, batches[k])
                except BrokenProcessPool:
                    # a worker died after the last wait returned: batch k never ran; the batches
                    # in flight are the suspects, exactly as when wait() reports the break
                    todo.append(k)
                    if self._unguarded():
                        _give_back(todo, running)
                        return
                    suspects.extend(j for j, _, _ in running.values())
                    running.clear()
                    pool = self._new_pool(self.workers)
                    continue
                running[fut] = (k, None, len(batches[k]))
            first = self._deadlines(running)
            wait_for = None if math.isinf(first) else max(0.0, first - time.monotonic())
            done, _ = wait(running, timeout=wait_for, return_when=FIRST_COMPLETED)
            broken = False
            for fut in done:
                k, _, _ = running.pop(fut)
                try:
                    result = fut.result()
                except BrokenProcessPool:
                    suspects.append(k)
                    broken = True
                    continue
                yield k, result
            if not done and not any(d is not None and d <= time.monotonic() for _, d, _ in running.values()):
                continue  # no worker had started yet: look again
            if not done:  # a batch overran its budget: kill the workers, re-run its items alone
                self._kill_pool()
                broken = True
            if broken and self._unguarded():
                _give_back(todo, running, suspects)
                return
            if broken:
                suspects.extend(k for k, _, _ in running.values())
                running.clear()
                pool = self._new_pool(self.workers)

    def _run_alone(self, fn, item, lost):
        if self.here:
            return fn([item])[0]
        if self._pool is None or getattr(self._pool, "_max_workers", 1) != 1:
            self._new_pool(1)
        with _interrupts_held():
            fut = self._pool.submit(fn, [item])
        budget = None if self.item_timeout is None else self.item_timeout + KILL_GRACE
        try:
            while budget is not None and not self._started() and not fut.done():
                wait([fut], timeout=READY_POLL)  # the worker's start-up is not the item's budget
            return fut.result(timeout=budget)[0]
        except BrokenProcessPool as exc:
            if self._unguarded():
                return fn([item])[0]
            self._new_pool(1)
            return lost(item, _lost_reason("BrokenProcessPool", str(exc) or "no detail"))
        except FutureTimeout:
            self._kill_pool()
            return lost(item, f"timeout: no answer within {budget:g} s (the case budget plus {KILL_GRACE:g} s "
                              "of grace); its worker process was killed")


#: Seconds a broken pool's workers are given to end, and their exit statuses to be read (:meth:`LocalPool._unguarded`).
UNGUARDED_WAIT: float = 2.0


def exit_codes(procs: Sequence, deadline: float) -> list[int | None]:
    """The exit statuses of the ``multiprocessing`` processes ``procs`` (None: still running), read again until one
    is :data:`~opsrock._pool.UNGUARDED_EXIT`, every process has one, or ``deadline`` (``time.monotonic()``) passes.

    A broken ``ProcessPoolExecutor``'s manager thread reaps its dead workers while this thread reads them, and the
    reader that loses that race gets no status for an instant (``Popen.poll`` returns None on ``ECHILD`` until the
    winner records it). Read once, a worker that ended re-running an unguarded script could pass unseen: the pool
    was then started again, and the script ran five times where three is the rule (once in CI, loaded)."""
    while True:
        codes = [proc.exitcode for proc in procs]
        if UNGUARDED_EXIT in codes or None not in codes or time.monotonic() >= deadline:
            return codes
        time.sleep(EXIT_POLL)


#: Seconds between two readings of the workers' exit statuses (:func:`exit_codes`).
EXIT_POLL: float = 0.005


def _give_back(todo: list[int], running: dict, suspects: list[int] | None = None) -> None:
    """Put the batches that were in flight (and the suspects: none of them ran) back on the ``todo`` stack,
    in order, for this process to run (a pool whose workers could not start)."""
    todo.extend(k for k, _, _ in running.values())
    if suspects is not None:
        todo.extend(suspects)
        suspects.clear()
    running.clear()
    todo.sort(reverse=True)


#: Signals held back while workers are spawned: Ctrl-C, and the stops the command line treats like it.
_HELD = {s for s in (getattr(signal, n, None) for n in ("SIGINT", "SIGTERM", "SIGHUP")) if s is not None}


@contextlib.contextmanager
def _interrupts_held():
    """Hold SIGINT (and SIGTERM, SIGHUP) back while worker processes are spawned (``submit`` spawns them on
    demand): a child inherits the blocked signal mask, so a Ctrl-C during its start-up, before
    :func:`opsrock._pool.worker_start` runs, cannot make it print a traceback, and a stop cannot cut a spawn
    in half; the parent gets the held signal as soon as the spawn is over.

    The mask holds the signal back from this thread only: another thread of the process (a progress bar's,
    a queue's feeder) can still take it, and Python then runs the handler here, between two steps of the
    spawn. So the handlers are also swapped for ones that record (:func:`opsrock._pool.deferred_interrupts`):
    a stop that came in mid-spawn once left a child reading its start-up data from a parent that had gone,
    and the child printed ``EOFError: Ran out of input`` after the command's one line (a SIGTERM test of a
    loaded ``make test``)."""
    if not hasattr(signal, "pthread_sigmask") or threading.current_thread() is not threading.main_thread():
        yield
        return
    with deferred_interrupts():
        old = signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)
        try:
            yield
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)  # a held signal arrives here: recorded, raised next


# --- Dask ------------------------------------------------------------------------------------
def _import_distributed():
    try:
        import distributed
    except ImportError:
        raise ExecutorUnavailableError(DASK_EXTRA_HINT) from None
    return distributed


class DaskExecutor(_Closing):
    """Batches as tasks on a ``dask.distributed`` cluster.

    Parameters
    ----------
    scheduler : str, optional
        Address of a running scheduler, ``"tcp://HOST:PORT"``. Start its workers with one
        thread each (``dask worker tcp://HOST:PORT --nthreads 1 --nworkers N``): OpenSeesPy
        keeps one model per process. (A worker with more threads still runs one solve at a
        time: the campaign's batch function holds a per-process lock.)
    local_workers : int, optional
        Start a ``LocalCluster`` of this many worker processes, one thread each, listening on
        127.0.0.1 only, without dashboard; it is closed with the executor.

    Exactly one of ``scheduler`` and ``local_workers`` must be given.

    Raises
    ------
    ExecutorUnavailableError
        If ``dask.distributed`` is not installed (the message names the extra).
    """

    def __init__(self, scheduler: str | None = None, *, local_workers: int | None = None) -> None:
        if (scheduler is None) == (local_workers is None):
            raise InputError(
                f"give exactly one of scheduler (got {scheduler!r}) and local_workers (got {local_workers!r})"
            )
        if scheduler is not None and (not isinstance(scheduler, str) or "://" not in scheduler):
            raise InputError(f"scheduler must be an address like 'tcp://HOST:PORT', got {scheduler!r}")
        if local_workers is not None and (
            isinstance(local_workers, bool) or not isinstance(local_workers, int) or local_workers < 1
        ):
            raise InputError(f"local_workers must be an integer >= 1, got {local_workers!r}")
        leave_if_reimported()  # a worker re-running an unguarded script starts no cluster
        distributed = _import_distributed()
        self._cluster = None
        if local_workers is not None:
            self._cluster = distributed.LocalCluster(
                n_workers=local_workers,
                threads_per_worker=1,
                processes=True,
                host="127.0.0.1",
                dashboard_address=None,
                # no dashboard, and the scheduler's HTTP routes on a free loopback port: with no address given,
                # distributed binds them to port 8787 and warns "Port 8787 is already in use" whenever another
                # cluster (a second campaign, a user's own) holds it
                scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                silence_logs=40,  # logging.ERROR: keep worker chatter off the user's terminal
            )
            self.client = distributed.Client(self._cluster)
        else:
            self.client = distributed.Client(scheduler, timeout=30)
        self.scheduler = self.client.scheduler.address
        self.workers = max(1, sum(w.get("nthreads", 1) for w in self.client.scheduler_info()["workers"].values()))

    def __repr__(self) -> str:
        return f"DaskExecutor(scheduler={self.scheduler!r}, workers={self.workers})"

    def close(self) -> None:
        """Close the client, and the ``LocalCluster`` if this executor started one."""
        client, self.client = getattr(self, "client", None), None
        if client is not None:
            client.close()
        if self._cluster is not None:
            self._cluster.close()
            self._cluster = None

    def map_batches(
        self,
        fn: Callable[[list[T]], list[R]],
        batches: Sequence[list[T]],
        lost: Callable[[T, str], R],
    ) -> Iterator[tuple[int, list[R]]]:
        """Yield ``(batch_index, fn(batch))`` in completion order (see :class:`Executor`).

        Dask itself re-runs a task whose worker died, on another worker, up to the scheduler's
        ``allowed-failures`` (default 3) before it raises ``KilledWorker``. Batches that end in
        ``KilledWorker`` are re-run after all others, one item at a time with nothing else
        running; an item that ends in ``KilledWorker`` alone gets ``lost(item, reason)``.
        """
        distributed = _import_distributed()
        killed = distributed.KilledWorker
        futures = {self.client.submit(fn, batch, pure=False): k for k, batch in enumerate(batches)}
        suspects: list[int] = []
        try:
            for fut in distributed.as_completed(list(futures)):
                k = futures.pop(fut)
                try:
                    result = fut.result()
                except killed:
                    suspects.append(k)
                    continue
                finally:
                    fut.release()  # gathered: do not keep the result in worker memory
                yield k, result
            # Suspects: one item at a time, nothing else running, so a death names its item
            # (tasks merely sharing a dying worker would otherwise be counted as suspicious).
            for k in sorted(suspects):
                results = []
                for item in batches[k]:
                    fut = self.client.submit(fn, [item], pure=False)
                    try:
                        results.append(fut.result()[0])
                    except killed as exc:
                        results.append(lost(item, _lost_reason("KilledWorker", str(exc))))
                    finally:
                        fut.release()
                yield k, results
        finally:
            for fut in list(futures):
                fut.cancel()


__all__ = [
    "BATCHES_PER_WORKER",
    "DASK_EXTRA_HINT",
    "DaskExecutor",
    "Executor",
    "KILL_GRACE",
    "ExecutorUnavailableError",
    "LOST_MARKERS",
    "LOST_PREFIX",
    "LocalPool",
    "MAX_BATCH",
    "batch_size",
    "is_lost",
    "make_batches",
]
