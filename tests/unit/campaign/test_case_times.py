"""The two times a campaign stores per case (``wall_time_s`` and ``cpu_time_s``, :mod:`opsrock.campaign.run`): the
wall-clock time of the case's solve and its thread's CPU time, which waiting (a loaded machine, I/O) does not add
to. Every bound below holds however loaded the machine is: a thread's CPU time cannot run ahead of the wall clock,
and a thread that waits is not charged for it."""

from __future__ import annotations

import time
from types import SimpleNamespace

import pytest

from opsrock.campaign.run import _solve_one
from opsrock.result import RockingResult

#: How long the waiting solve sleeps (s).
WAIT_S = 0.3
#: CPU time the computing solve spends (s).
BURN_S = 0.05


def _result(settings) -> RockingResult:
    return RockingResult(solver="fake", settings=settings, alpha=0.2, time=[], theta=[], theta_dot=[], theta_max=0.0,
                         overturned=False, rocked=False)


def waits(block, excitation, solver, **settings) -> RockingResult:
    """A solve that computes nothing and waits: its wall time, not its CPU time."""
    time.sleep(WAIT_S)
    return _result(settings)


def burns(block, excitation, solver, **settings) -> RockingResult:
    """A solve that computes for ``BURN_S`` of its thread's CPU time."""
    start = time.thread_time()
    while time.thread_time() - start < BURN_S:
        pass
    return _result(settings)


def fails(block, excitation, solver, **settings) -> RockingResult:
    """A solve that computes for ``BURN_S`` and raises."""
    burns(block, excitation, solver)
    raise RuntimeError("singular matrix at step 12")


CASE = SimpleNamespace(case_id="c", problem="", block=None, excitation=None)


def test_waiting_counts_in_the_wall_time_only():
    row = _solve_one(CASE, waits, "fake", {}, None)
    assert row["status"] == "ok" and row["wall_time_s"] >= WAIT_S
    assert 0.0 <= row["cpu_time_s"] < 0.5 * WAIT_S  # a sleeping thread is charged nothing; Python's own cost is µs


@pytest.mark.parametrize("solve", [burns, fails])
def test_computing_counts_in_both_and_the_cpu_time_never_exceeds_the_wall_time(solve):
    row = _solve_one(CASE, solve, "fake", {}, None)
    assert row["status"] == ("ok" if solve is burns else "failed")
    assert BURN_S <= row["cpu_time_s"] <= row["wall_time_s"]


def test_a_case_that_cannot_be_set_up_took_no_time():
    row = _solve_one(SimpleNamespace(case_id="c", problem="its record is missing"), burns, "fake", {}, None)
    assert (row["status"], row["reason"], row["wall_time_s"], row["cpu_time_s"]) == (
        "failed", "its record is missing", 0.0, 0.0)
