"""Worker-process pools of the post-processing (bootstrap resamples, block sets, figures) and Ctrl-C.

:class:`TaskPool` runs a list of tasks on one state, here or in a pool, the results in task order.

A terminal's Ctrl-C sends SIGINT to the whole process group. The workers ignore it (:func:`ignore_interrupts`,
their initialiser): the parent gets it, stops waiting and shuts its pool down, so the user sees one line,
not a traceback per worker. While a pool forks its workers the parent only records a Ctrl-C
(:func:`deferred_interrupts`): raised inside ``fork()``'s own handlers, the ``KeyboardInterrupt`` would be
swallowed there ("Exception ignored in ... _releaseLock") and the run would go on; recorded, it is raised
as soon as the workers exist.

No worker outlives its parent, whatever stops the parent (SIGTERM, ``kill -9``, a crash): every worker of
opsrock's pools (these, and the campaign's :class:`~opsrock.campaign.executors.LocalPool`) runs
:func:`die_with_parent` first, so multiprocessing's ``resource_tracker`` (which ends once every process
that holds its pipe has ended) goes too.
"""

from __future__ import annotations

import contextlib
import ctypes
import multiprocessing
import os
import signal
import sys
import threading
import time
import warnings

from opsrock.errors import UnguardedScriptError

#: ``prctl`` option of Linux: the signal the kernel sends a process when the thread that made it ends.
PR_SET_PDEATHSIG: int = 1

#: Seconds between two looks at the parent's pid where ``prctl`` is not available (macOS, Windows).
PARENT_POLL_S: float = 1.0


#: Exit status of a worker process that found itself re-running the main script's campaign
#: (:func:`pool_allowed`): the parent reads it from the dead worker and raises :func:`unguarded_error`.
UNGUARDED_EXIT: int = 87


def reimported_script() -> str | None:
    """The main script that ``multiprocessing`` is importing again in this process (a worker being started by
    ``spawn`` or ``forkserver``, which runs the script's top-level code as ``__mp_main__``), if the caller is
    running inside that import; else None."""
    frame = sys._getframe(1)
    while frame is not None:
        if frame.f_code.co_name == "<module>" and frame.f_globals.get("__name__") == "__mp_main__":
            return str(frame.f_globals.get("__file__") or frame.f_code.co_filename)
        frame = frame.f_back
    return None


def main_script() -> str:
    """How to name this process's main script in a message: its file, its module, or ``"the main module"``."""
    main = sys.modules.get("__main__")
    spec = getattr(main, "__spec__", None)
    return str(getattr(main, "__file__", None) or getattr(spec, "name", None) or "the main module")


def unimportable_main() -> str | None:
    """The main script's name if worker processes started by ``spawn`` could not import it again: it names a
    file that does not exist (``"<stdin>"`` for ``python3 - <<EOF``, a script deleted since); else None (a file,
    a module run with ``-m``, ``python -c`` or an interactive session, which the workers do not import)."""
    main = sys.modules.get("__main__")
    if getattr(getattr(main, "__spec__", None), "name", None) is not None:
        return None
    path = getattr(main, "__file__", None)
    if path is None:
        return None
    origin = multiprocessing.process.ORIGINAL_DIR or os.getcwd()
    return None if os.path.isfile(os.path.join(origin, path)) else str(path)


def leave_if_reimported() -> None:
    """End this process at once, quietly, with status :data:`UNGUARDED_EXIT`, if it is a worker re-running the
    main script's top-level code (:func:`reimported_script`); the parent's pool tells the user."""
    if reimported_script() is not None:
        os._exit(UNGUARDED_EXIT)


def pool_allowed(workers: int | None) -> bool:
    """May this process start a pool of worker processes? Call it before a campaign writes anything.

    * In a worker process that is re-running the main script (the script has no
      ``if __name__ == "__main__":`` guard) the worker ends at once (:func:`leave_if_reimported`); the parent's
      pool tells the user (:func:`unguarded_error`).
    * Inside a worker process of any pool (``multiprocessing.parent_process()`` is set): False for
      ``workers`` 1 (run the items in this process), :class:`~opsrock.errors.UnguardedScriptError` for more.
    * Else True.

    Parameters
    ----------
    workers : int or None
        Worker processes asked for (None: all cores).
    """
    leave_if_reimported()
    parent = multiprocessing.parent_process()
    if parent is None:
        script = unimportable_main()
        if script is None:
            return True
        if workers == 1:
            return False
        raise UnguardedScriptError(
            f"the main script {script} has no file that worker processes can import (multiprocessing starts every "
            "worker by importing the main script again; a script read from standard input cannot be): save the "
            "script to a file and run that, or pass workers=1 to run the cases in this process")
    if workers == 1:
        return False
    raise UnguardedScriptError(
        f"a campaign cannot start worker processes inside a worker process (this process, pid {os.getpid()}, was "
        f"started by multiprocessing from pid {parent.pid}): start the campaign from the main process, or pass "
        "workers=1 to run its cases in this process")


def unguarded_error() -> UnguardedScriptError:
    """The error of a pool whose workers ended with :data:`UNGUARDED_EXIT`: they re-ran the main script."""
    return UnguardedScriptError(
        f"the worker processes re-ran the script {main_script()}: multiprocessing starts every worker by "
        "importing the main script again, and this one starts its campaign when imported; put the script's "
        'work under `if __name__ == "__main__":`, or pass workers=1 to run the cases in this process')


def warn_unguarded_here() -> None:
    """Warn (``RuntimeWarning``, at the user's line) that an unguarded script's ``workers=1`` campaign runs its
    cases in this process (:func:`unguarded_error` for more workers)."""
    level, frame = 2, sys._getframe(1)  # stacklevel 2: the caller of this function
    while frame is not None and str(frame.f_globals.get("__name__", "")).startswith("opsrock"):
        level, frame = level + 1, frame.f_back
    warnings.warn(f"the worker process re-ran the script {main_script()} (no `if __name__ == \"__main__\":` guard): "
                  "with workers=1 its cases run in this process instead, without a worker's protection against a "
                  "case that crashes its process; put the script's work under the guard to run them in workers",
                  RuntimeWarning, stacklevel=level)


def ignore_interrupts() -> None:
    """Worker initialiser: ignore SIGINT (the parent handles Ctrl-C and stops the pool)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def die_with_parent(parent: int) -> None:
    """Worker initialiser: end this process when its parent ``parent`` (a pid) ends, however it ends.

    On Linux the kernel kills the worker (``prctl(PR_SET_PDEATHSIG, SIGKILL)``); elsewhere a daemon thread
    looks at the parent's pid every :data:`PARENT_POLL_S` seconds. A parent already gone when this runs
    (stopped while the worker started) ends the worker at once.
    """
    armed = False
    if sys.platform.startswith("linux"):
        try:
            armed = ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGKILL), 0, 0, 0) == 0
        except (OSError, AttributeError):
            armed = False
    if os.getppid() != parent:
        os._exit(1)
    if not armed:
        threading.Thread(target=_watch_parent, args=(parent,), daemon=True, name="opsrock-parent-watch").start()


def _watch_parent(parent: int) -> None:
    while os.getppid() == parent:
        time.sleep(PARENT_POLL_S)
    os._exit(1)


def worker_start(parent: int, ready=None, warm: tuple[str, ...] = ()) -> None:
    """What every worker of opsrock's pools runs first: die with ``parent``, leave Ctrl-C to it, and take the
    default action of SIGTERM and SIGHUP (a worker spawned while the parent held them back inherits them
    blocked). Then it makes the kernels of the solvers ``warm`` ready (:func:`opsrock.solvers.warm_up`: loaded
    from numba's cache, which the parent has filled), and last it counts itself in ``ready`` (a shared
    ``multiprocessing.Value``, when given): from then on the worker takes work, and the parent's clock of a case
    budget may run."""
    die_with_parent(parent)
    ignore_interrupts()
    stops = {s for s in (getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None)) if s is not None}
    for s in stops:
        signal.signal(s, signal.SIG_DFL)
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_UNBLOCK, stops)
    for solver in warm:
        _warm_up(solver)
    if ready is not None:
        with ready.get_lock():
            ready.value += 1


def _warm_up(solver: str) -> None:
    """:func:`opsrock.solvers.warm_up`, whose failure is left to the cases: each one that meets it is stored as
    failed with its reason, where a failed initializer would break the pool and lose every case."""
    from opsrock.solvers import warm_up

    try:
        warm_up(solver)
    except Exception:  # noqa: BLE001  the cases report it, each with its reason
        pass


@contextlib.contextmanager
def deferred_interrupts():
    """Inside the block (where a pool forks its workers) a Ctrl-C is recorded, not raised; it is raised
    as ``KeyboardInterrupt`` when the block ends. So are SIGTERM and SIGHUP where a Python handler takes
    them (the command line's, which stops like Ctrl-C): recorded, then given to that handler. Outside the
    main thread (where Python delivers no signal) the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    stops = [s for s in (getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None))
             if s is not None and callable(signal.getsignal(s))]
    previous = {s: signal.signal(s, lambda signum, frame: caught.append(signum)) for s in (signal.SIGINT, *stops)}
    try:
        yield
    finally:
        for s, handler in previous.items():
            signal.signal(s, handler)
    if caught:
        first = caught[0]
        if callable(previous[first]):
            previous[first](first, None)  # the usual handler: KeyboardInterrupt (or the command line's stop)
        elif previous[first] != signal.SIG_IGN:
            raise KeyboardInterrupt


def pool_context():
    """The start method of opsrock's post-processing pools (:class:`TaskPool`, :func:`process_pool`): ``fork`` on
    Linux, the platform's default elsewhere (``spawn`` on macOS and Windows).

    Chosen here, not left to Python: Python 3.14 makes ``forkserver`` Linux's default, which starts each worker by
    importing the main script again, so a script read from standard input (``python3 - <<EOF``) could not start one,
    and each worker would load numpy, scipy and the state anew where a forked one has them already. (The campaign's
    :class:`~opsrock.campaign.executors.LocalPool` spawns its workers on purpose, and says why.)"""
    if sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods():
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context()


def tasks_stay_here() -> bool:
    """True where :class:`TaskPool` runs its tasks in this process whatever ``workers`` says: its workers would
    import the main script again (not ``fork``) and the main script has no file they could import
    (:func:`unimportable_main`)."""
    return pool_context().get_start_method() != "fork" and unimportable_main() is not None


class TaskPool:
    """``[state.run(*task) for task in tasks]``, in this process (``workers`` 1) or in a pool of ``workers``
    processes, each given ``state`` once; the results in the order of ``tasks`` whatever the split.

    With a pool the tasks start at once and :meth:`results` waits for them, so the caller can do other
    work in between. A context manager: leaving it shuts the pool down (Ctrl-C included; the workers
    ignore it and the parent stops them).
    """

    def __init__(self, state, tasks: list[tuple], workers: int = 1) -> None:
        self.state, self.tasks = state, list(tasks)
        self.pool = self.futures = self._done = None
        if workers > 1 and len(self.tasks) > 1 and not tasks_stay_here():
            self.pool = process_pool(min(workers, len(self.tasks)), _pool_init, (state,))
            try:
                with deferred_interrupts():  # the workers are forked at the first submit
                    self.futures = [self.pool.submit(_pool_run, *t) for t in self.tasks]
            except BaseException:  # a Ctrl-C deferred while forking: no caller's `with` will shut the pool down
                self.pool.shutdown(cancel_futures=True)
                raise

    def __enter__(self) -> TaskPool:
        return self

    def __exit__(self, *exc) -> None:
        if self.pool is not None:
            self.pool.shutdown(cancel_futures=True)

    def results(self) -> list:
        if self._done is None:
            if self.futures is None:
                self._done = [self.state.run(*t) for t in self.tasks]
            else:
                self._done = [f.result() for f in self.futures]
        return self._done


_POOL_STATE: list = []


def _pool_init(state) -> None:
    _POOL_STATE[:] = [state]


def _pool_run(*task):
    return _POOL_STATE[0].run(*task)


def process_pool(workers: int, initializer=None, initargs: tuple = ()):
    """A ``ProcessPoolExecutor`` of ``workers`` processes started by :func:`pool_context`, whose workers die with
    this process and ignore SIGINT (:func:`worker_start`), then run ``initializer``.

    Submit the first task inside :func:`deferred_interrupts`: that is where the workers are forked.
    """
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(max_workers=workers, mp_context=pool_context(), initializer=_init,
                               initargs=(os.getpid(), initializer, initargs))


def _init(parent: int, initializer, initargs: tuple) -> None:
    worker_start(parent)
    if initializer is not None:
        initializer(*initargs)
