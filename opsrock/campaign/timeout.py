"""A wall-clock budget for one case: :func:`time_limit`.

The budget is enforced inside the process that solves, from a watchdog thread that raises
:class:`CaseTimeout` in the solving thread (``PyThreadState_SetAsyncExc``). That works in the
main thread and in a Dask worker's task threads alike, for every solver whose loop runs Python
code between native calls (the OpenSees stepper, the scipy solvers). A compiled loop or a single
native call that never returns cannot be interrupted this way: the local executor kills such a
worker process after the budget and a grace period (:class:`opsrock.campaign.executors.LocalPool`), and
the compiled rigid-body solver bounds its own work by ``max_steps``.

One watchdog thread per process serves every budget (``_Watchdog``), started with the first and
sleeping until the earliest deadline; a budget is armed and disarmed without waking it. A thread started per
case (a :class:`threading.Timer`) cost every case a thread start and that thread's turns at the interpreter lock
(issue 43): on the directionality study's cases, in one process, a planar case's median wall time was 0.70 ms with
it and 0.38 ms without, a 3-D case's 10.7 and 10.3 ms, on a machine loaded by other work; more as the load grows.
"""

from __future__ import annotations

import ctypes
import itertools
import math
import os
import threading
import time
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


class _Watchdog:
    """The process's one watchdog thread: it sleeps until the earliest armed deadline (indefinitely when none is
    armed) and raises :class:`CaseTimeout` in the thread of a budget that ran out while still armed.

    A budget armed with a deadline later than the one the watchdog sleeps until (every case of a campaign: the same
    budget, one case after the other) does not wake it: it finds the new deadline when it wakes at the old one. An
    earlier deadline, or a watchdog asleep with none, is woken. Fork-safe: a child starts with no budgets and its
    own watchdog on its first budget.
    """

    def __init__(self) -> None:
        self._reset()

    def _reset(self) -> None:
        self._cond = threading.Condition(threading.Lock())
        self._armed: dict[int, tuple[int, float]] = {}  # budget serial -> (thread id, deadline on time.monotonic)
        self._fired: set[int] = set()
        self._serials = itertools.count()
        self._until = math.inf  # when the watchdog wakes next
        self._thread: threading.Thread | None = None

    def arm(self, seconds: float) -> int:
        """Arm a budget of ``seconds`` (s) for the calling thread; returns its serial."""
        deadline = time.monotonic() + seconds
        with self._cond:
            serial = next(self._serials)
            self._armed[serial] = (threading.get_ident(), deadline)
            if self._thread is None or not self._thread.is_alive():
                self._thread = threading.Thread(target=self._watch, daemon=True, name="opsrock-case-budget")
                self._thread.start()
            elif deadline < self._until:
                self._cond.notify()
        return serial

    def disarm(self, serial: int) -> bool:
        """Disarm a budget; returns whether it fired (its exception raised or still pending in its thread)."""
        with self._cond:
            self._armed.pop(serial, None)
            if serial not in self._fired:
                return False
            self._fired.discard(serial)
            _inject(threading.get_ident(), None)  # a pending exception that has not been raised yet is dropped
            return True

    def _watch(self) -> None:
        with self._cond:
            while True:
                now = time.monotonic()
                for serial, (thread, deadline) in list(self._armed.items()):
                    if deadline <= now:
                        del self._armed[serial]
                        self._fired.add(serial)
                        _inject(thread, CaseTimeout)
                self._until = min((d for _, d in self._armed.values()), default=math.inf)
                self._cond.wait(None if math.isinf(self._until) else self._until - now)


_WATCHDOG = _Watchdog()
if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_WATCHDOG._reset)


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
    message = f"timeout: no answer within the case budget of {seconds:g} s"
    serial = _WATCHDOG.arm(seconds)
    try:
        yield
    except CaseTimeout:
        raise CaseTimeout(message) from None
    finally:
        fired = _WATCHDOG.disarm(serial)
    if fired:
        raise CaseTimeout(message)


__all__ = ["CaseTimeout", "DEFAULT_CASE_TIMEOUT", "time_limit"]
