"""Run a campaign whose rigid-body solves are slowed down, so that a test can kill it mid-way.

Usage: python campaign_runner.py SCENE OUT_DIR WORKERS
Prints the campaign summary as one JSON line. Used by tests/model/campaign/test_campaign.py.
"""

import json
import sys
import time

from opsrock.campaign import CampaignOptions, run_campaign
from opsrock.solvers import simulate

#: Extra time per case (s): long enough that the killing test catches the run between cases.
DELAY_S = 0.25


def slow_housner(block, excitation, solver, **settings):
    """The real rigid-body solver, after a pause (its results are untouched)."""
    time.sleep(DELAY_S)
    return simulate(block, excitation, solver="housner", **settings)


if __name__ == "__main__":
    scene, out, workers = sys.argv[1], sys.argv[2], int(sys.argv[3])
    summary = run_campaign(scene, out, workers=workers,
                           options=CampaignOptions(solve_fn=slow_housner, batch=1), progress=False)
    print(json.dumps({"n_computed": summary.n_computed, "n_reused": summary.n_reused, "n_cases": summary.n_cases}))
