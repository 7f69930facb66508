"""Issue 44: failed cases are counted by the kind of their reason (:func:`opsrock.campaign.cases.reason_code`), so
that reasons holding numbers (a time, a budget) are not split into one group each."""

from __future__ import annotations

import pandas as pd

from opsrock.campaign.cases import OTHER_REASON, reason_code
from opsrock.campaign.executors import LOST_PREFIX
from opsrock.inventory.summary import failure_table
from opsrock.solvers.status import FAILURES, MAX_FREE_TIME, REASONS


def test_each_solver_reason_with_what_a_solver_appends_is_its_failure_kind():
    for code, kind in FAILURES.items():
        if kind is not None:
            assert reason_code(f"{REASONS[code]} (at t = 12.5 s)") == kind
    assert reason_code("timeout: no answer within the case budget of 300 s") == "timeout"
    assert reason_code(f"{LOST_PREFIX}worker process died while solving this case alone (signal: 9)") == "lost"
    assert reason_code("ValueError: singular matrix") == OTHER_REASON and reason_code(None) == OTHER_REASON


def test_the_failure_table_groups_reasons_that_differ_only_in_their_numbers():
    tail = REASONS[MAX_FREE_TIME] + " (still rolling on its rim, t = {t:g} s)"
    cases = pd.DataFrame({"status": ["failed", "ok", "failed", "failed", "failed"],
                          "reason": [tail.format(t=41.25), "", "timeout: no answer within the case budget of 60 s",
                                     tail.format(t=38.5), "timeout: no answer within the case budget of 300 s"]})
    table = failure_table(cases)
    assert table.to_dict("list") == {"code": ["max_free_time", "timeout"], "n_failed": [2, 2],
                                     "first_reason": [tail.format(t=41.25),
                                                      "timeout: no answer within the case budget of 60 s"]}
    assert list(failure_table(cases.iloc[[1]]).columns) == ["code", "n_failed", "first_reason"]
