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

import openseespy.opensees as ops

# --- OpenSees' console output: to a log file, never to the user's terminal -------------------
#: Per process: the log file OpenSees writes to (``logFile -noEcho``) and the failed steps
#: retried by :func:`_recover` in the current run.
CONSOLE: dict[str, Any] = {"pid": None, "path": None, "retries": 0, "recovered_by": {}}


def opensees_log_path() -> str:
    """Path of this process's OpenSees log file (its warnings and progress lines go there)."""
    return os.path.join(tempfile.gettempdir(), f"opsrock-opensees-{os.getpid()}.log")


def console_to_log() -> str:
    """Send OpenSees' output to :func:`opensees_log_path` (once per process); return the path.

    OpenSees also prints a ``Process 0 Terminating`` line on stderr when the interpreter exits,
    whatever its log setting; an exit handler silences stderr just before that (nothing of
    Python's runs after it) and removes the log if it stayed empty.
    """
    pid = os.getpid()
    if CONSOLE["pid"] != pid:
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


__all__ = ["CONSOLE", "console_to_log", "count_messages", "fresh_model", "log_size", "opensees_log_path", "ops"]
