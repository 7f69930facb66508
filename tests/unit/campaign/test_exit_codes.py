"""Reading a broken pool's worker exit statuses (:func:`opsrock.campaign.executors.exit_codes`).

The pool's manager thread reaps its dead workers while the campaign's thread reads them; the reader that loses the
race gets None from ``Popen.poll`` for an instant. Once, in CI, that hid a worker's "unguarded script" status: the
pool was started again and the script ran five times. Fake processes replay that race here without timing.
"""

from __future__ import annotations

import time

from opsrock._pool import UNGUARDED_EXIT
from opsrock.campaign.executors import exit_codes


class RacedProcess:
    """A process that ended with ``code``, whose status reads None the first ``misses`` times (the lost race)."""

    def __init__(self, code: int | None, misses: int = 0) -> None:
        self.code, self.misses, self.reads = code, misses, 0

    @property
    def exitcode(self) -> int | None:
        self.reads += 1
        return None if self.reads <= self.misses else self.code


def test_a_status_lost_to_the_reaper_is_read_again():
    late = RacedProcess(UNGUARDED_EXIT, misses=3)
    codes = exit_codes([RacedProcess(-15), late], time.monotonic() + 60.0)
    assert UNGUARDED_EXIT in codes and late.reads == 4  # read until it showed, not a fixed number of times


def test_every_status_read_ends_the_wait_at_once():
    procs = [RacedProcess(1), RacedProcess(-15, misses=1)]
    assert exit_codes(procs, time.monotonic() + 60.0) == [1, -15] and procs[0].reads == 2


def test_a_worker_still_running_at_the_deadline_reads_none():
    assert exit_codes([RacedProcess(None), RacedProcess(-9)], time.monotonic()) == [None, -9]
