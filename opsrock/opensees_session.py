"""The one owner of OpenSees state in opsrock.

OpenSeesPy keeps one global model per interpreter. Every model in the project (the SDOF rocking
model of :mod:`opsrock.solvers.opensees`, the shear building of
:mod:`opsrock.excitations.building`) is built inside :func:`fresh_model`, which wipes that state
before and after (also when the build or the analysis raises), so nothing leaks from one run to
the next. From import on, OpenSees' console output goes to a per-process log file
(:func:`opensees_log_path`), never to the user's terminal; callers count what it wrote there.
"""

from __future__ import annotations

import atexit
import contextlib
import os
import sys
import tempfile
from typing import Any, Iterator

from opsrock._blas import require_blas

# OpenSeesPy's Linux wheel needs libblas.so.3: say so plainly, before its bare RuntimeError
require_blas()

import openseespy.opensees as ops  # noqa: E402

# --- OpenSees' console output: to a log file, never to the user's terminal -------------------
#: Per process: the log file OpenSees writes to (``logFile -noEcho``) and the failed steps
#: retried by :func:`_recover` in the current run.
CONSOLE: dict[str, Any] = {"pid": None, "path": None, "retries": 0, "recovered_by": {}}


#: Logs of finished processes younger than this (s) are kept for a look after a run; older ones are
#: removed by the next process that uses OpenSees, so that they do not pile up.
LOG_KEEP_S: float = 600.0

#: At most this many logs of finished processes are kept, whatever their age.
LOG_KEEP_MAX: int = 50


def log_folder() -> str:
    """The folder of the per-process OpenSees logs (in the system's temporary folder)."""
    return os.path.join(tempfile.gettempdir(), "opsrock-opensees")


def opensees_log_path() -> str:
    """Path of this process's OpenSees log file (its warnings and progress lines go there)."""
    return os.path.join(log_folder(), f"opsrock-opensees-{os.getpid()}.log")


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def _ended_logs(folder: str) -> list[tuple[float, str]]:
    """``(mtime, path)`` of the logs in ``folder`` whose process has ended."""
    out = []
    for name in os.listdir(folder):
        stem = name.removeprefix("opsrock-opensees-").removesuffix(".log")
        if name.startswith("opsrock-opensees-") and stem.isdigit() and not _alive(int(stem)):
            path = os.path.join(folder, name)
            try:
                out.append((os.path.getmtime(path), path))
            except OSError:
                pass
    return out


def prune_logs(now: float | None = None) -> int:
    """Remove the logs of processes that have ended, except the :data:`LOG_KEEP_MAX` newest of those
    younger than :data:`LOG_KEEP_S`; return how many were removed."""
    import time

    now = time.time() if now is None else now
    ended = []
    # the folder, and the temporary folder itself, where earlier versions left their logs
    for folder in (log_folder(), tempfile.gettempdir()):
        ended += _ended_logs(folder)
    ended.sort(reverse=True)
    removed = 0
    for k, (mtime, path) in enumerate(ended):
        if k >= LOG_KEEP_MAX or now - mtime > LOG_KEEP_S:
            try:
                os.unlink(path)
                removed += 1
            except OSError:
                pass
    return removed


def console_to_log() -> str:
    """Send OpenSees' output to :func:`opensees_log_path` (once per process); return the path.

    OpenSees also prints a ``Process 0 Terminating`` line on stderr when the interpreter exits,
    whatever its log setting; an exit handler silences stderr just before that (nothing of
    Python's runs after it) and removes the log if it stayed empty.
    """
    pid = os.getpid()
    if CONSOLE["pid"] != pid:
        os.makedirs(log_folder(), exist_ok=True)
        prune_logs()
        path = opensees_log_path()
        ops.logFile(path, "-noEcho")
        CONSOLE.update(pid=pid, path=path)
        atexit.register(_stderr_to_log_at_exit, path, pid)
    return CONSOLE["path"]


def _stderr_to_log_at_exit(path: str, pid: int) -> None:
    """At exit: silence stderr for OpenSees' ``Process 0 Terminating`` line, and remove the log
    file if OpenSees never wrote to it (one per process would otherwise pile up)."""
    if os.getpid() != pid:  # a forked child inherited the handler: not its log
        return
    try:
        sys.stderr.flush()
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, 2)
        os.close(fd)
        if os.path.getsize(path) == 0:
            os.unlink(path)
    except OSError:
        pass


def log_size(path: str) -> int:
    try:
        return os.path.getsize(path)
    except OSError:
        return 0


def count_messages(path: str, start: int) -> int:
    """Non-empty lines OpenSees wrote to its log after byte ``start``."""
    try:
        with open(path, "rb") as fh:
            fh.seek(start)
            return sum(1 for line in fh.read().splitlines() if line.strip())
    except OSError:
        return 0


console_to_log()  # from import on: nothing OpenSees prints reaches the terminal


@contextlib.contextmanager
def fresh_model() -> Iterator[Any]:
    """Context in which one OpenSees model is built and analysed; yields the ``ops`` module.

    Wipes OpenSees on entry and on exit (normal or not).
    """
    console_to_log()
    ops.wipe()
    try:
        yield ops
    finally:
        ops.wipe()


__all__ = ["CONSOLE", "console_to_log", "count_messages", "fresh_model", "log_folder", "log_size", "opensees_log_path",
           "ops", "prune_logs"]
