"""A wall-clock budget for one case: :func:`time_limit`.

The budget is enforced inside the process that solves, from a timer thread that raises
:class:`CaseTimeout` in the solving thread (``PyThreadState_SetAsyncExc``). That works in the
main thread and in a Dask worker's task threads alike, for every solver whose loop runs Python
code between native calls (the OpenSees stepper, the scipy solvers). A compiled loop or a single
native call that never returns cannot be interrupted this way: the local executor kills such a
worker process after the budget and a grace period (:class:`opsrock.campaign.executors.LocalPool`), and
the compiled rigid-body solver bounds its own work by ``max_steps``.
"""

from __future__ import annotations

import ctypes
import math
import threading
from contextlib import contextmanager
from typing import Iterator

from opsrock.errors import CaseTimeout, InputError

#: Default wall-clock budget of one case (s). The slowest solver measured on a 20-s record took
#: 17 s and a paper pulse takes under 0.1 s: five minutes is far beyond any healthy case and short
#: enough that a stuck one does not hold a campaign for long.
DEFAULT_CASE_TIMEOUT: float = 300.0


def _inject(thread_id: int, exc: type[BaseException] | None) -> int:
    return ctypes.pythonapi.PyThreadState_SetAsyncExc(
        ctypes.c_ulong(thread_id), ctypes.py_object(exc) if exc is not None else ctypes.c_void_p(0)
    )


@contextmanager
def time_limit(seconds: float | None) -> Iterator[None]:
    """Raise :class:`CaseTimeout` in the calling thread if the block runs longer than ``seconds``.

    Parameters
    ----------
    seconds : float or None
        Budget (s), > 0. None or ``inf``: no limit.

    Raises
    ------
    CaseTimeout
        When the budget ran out, with the budget in the message.
    """
    if seconds is None or math.isinf(seconds):
        yield
        return
    if not (seconds > 0):
        raise InputError(f"seconds must be positive, got {seconds!r}")
    target = threading.get_ident()
    lock = threading.Lock()
    state = {"done": False, "fired": False}

    def fire() -> None:
        with lock:
            if not state["done"]:
                state["fired"] = True
                _inject(target, CaseTimeout)

    timer = threading.Timer(seconds, fire)
    timer.daemon = True
    timer.start()
    message = f"timeout: no answer within the case budget of {seconds:g} s"
    try:
        yield
    except CaseTimeout:
        raise CaseTimeout(message) from None
    finally:
        with lock:
            state["done"] = True
            fired = state["fired"]
        timer.cancel()
        if fired:
            _inject(target, None)  # a pending exception that has not been raised yet is dropped
    if fired:
        raise CaseTimeout(message)


__all__ = ["CaseTimeout", "DEFAULT_CASE_TIMEOUT", "time_limit"]
