"""The case budget (:func:`opsrock.campaign.timeout.time_limit`): one watchdog thread per process serves every
budget (issue 43: a thread started per case cost each case a thread start and that thread's turns at the
interpreter lock), and it still fires, never early, only for a budget still armed, after a fork too."""

from __future__ import annotations

import multiprocessing
import threading
import time

import pytest

from opsrock.campaign.timeout import time_limit
from opsrock.errors import CaseTimeout, InputError

#: How long a loop waits for a budget to fire before the test gives up (s): far beyond any budget below, so
#: only a budget that never fires reaches it, however loaded the machine.
GIVE_UP_S = 60.0


def _spin_past(seconds: float) -> float:
    """Run Python code (where an asynchronous exception can land) until ``seconds`` have passed; returns the time
    spent (s)."""
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        pass
    return time.monotonic() - start


def _budget_fires(budget: float) -> tuple[str, float]:
    start = time.monotonic()
    with pytest.raises(CaseTimeout) as caught:
        with time_limit(budget):
            _spin_past(GIVE_UP_S)
    return str(caught.value), time.monotonic() - start


def test_a_block_past_its_budget_is_stopped_never_before_the_budget():
    message, spent = _budget_fires(0.2)
    assert message == "timeout: no answer within the case budget of 0.2 s"
    assert 0.2 <= spent < GIVE_UP_S


def test_a_budget_shorter_than_the_one_the_watchdog_sleeps_on_still_fires():
    with time_limit(3600.0):  # the watchdog now sleeps until an hour from now
        pass
    assert _budget_fires(0.2)[1] < GIVE_UP_S


def test_a_finished_block_leaves_nothing_behind_after_its_deadline():
    for _ in range(3):
        with time_limit(0.3):
            pass
    assert _spin_past(0.9) >= 0.9  # past every deadline above: no exception arrived


def test_one_watchdog_thread_serves_every_budget():
    for _ in range(200):
        with time_limit(300.0):
            pass
    names = [t.name for t in threading.enumerate()]
    assert names.count("opsrock-case-budget") == 1


def test_no_budget_and_a_bad_budget():
    with time_limit(None):
        pass
    with time_limit(float("inf")):
        pass
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(InputError, match="seconds must be positive"):
            with time_limit(bad):
                pass


def _child_fires(queue) -> None:
    try:
        with time_limit(0.2):
            _spin_past(GIVE_UP_S)
        queue.put("not stopped")
    except CaseTimeout as exc:
        queue.put(str(exc))


def test_a_forked_child_gets_its_own_watchdog():
    with time_limit(300.0):  # the parent's watchdog runs (a child forked now does not inherit the thread)
        queue = multiprocessing.get_context("fork").Queue()
        child = multiprocessing.get_context("fork").Process(target=_child_fires, args=(queue,))
        child.start()
        answer = queue.get(timeout=GIVE_UP_S)
        child.join(GIVE_UP_S)
    assert answer == "timeout: no answer within the case budget of 0.2 s"
