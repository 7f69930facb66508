"""A campaign with nothing to fit, through the real console script (issue 32, "a Python API that is safe to
script").

The table: ``opsrock fragility`` on a record campaign whose every case failed (a real campaign: its records are
all zeros, so no floor motion can be measured), given as its folder or its ``cases.csv``, and on one whose
every case was lost to the infrastructure (reasons as opsrock wrote them before the lost marker: "worker process
died ..."). Each is refused with exit 2 and one line that names the campaign, the count and the first reason,
and writes nothing (the promise of ``_hostile``); before, a traceback (``ValueError: need at least one array to
concatenate``). ``opsrock contents`` makes the same check through the same function
(:func:`opsrock.fragility.cases.check_some_finished`) on each of its campaigns: its test drives the study's
campaign step on the same campaign.
"""

from __future__ import annotations

import math
from collections import Counter
from pathlib import Path

import pandas as pd
import pytest
from _hostile import Case, sweep
from _support import BLOCKS, RECORD_SCENE

from opsrock.campaign import run_campaign
from opsrock.campaign.executors import LOST_PREFIX
from opsrock.campaign.scene import load_scene
from opsrock.errors import AllCasesFailedError

#: Two blocks (bookcase, wardrobe) under two records at three levels: 12 cases, every one failed.
N_CASES = 12

#: The reason a case whose worker died was stored with before the lost marker (opsrock up to issue 32).
OLD_LOST = "worker process died while solving this case alone (BrokenProcessPool: A process in the pool was terminated)"


@pytest.fixture(scope="module")
def campaigns(tmp_path_factory) -> Path:
    """``failed/``: a record campaign (folder ``failed/rocking``) whose every case failed; ``lost/``: its table with
    every reason replaced by :data:`OLD_LOST`."""
    base = tmp_path_factory.mktemp("api_campaigns")
    failed = base / "failed"
    failed.mkdir()
    for k in range(2):
        (failed / f"r{k}.txt").write_text("0\n" * 300)  # a still floor: its motion has no measures, no case runs
    scene = failed / "scene.toml"
    scene.write_text(RECORD_SCENE.format(name="nothing", blocks=BLOCKS, files='["r0.txt", "r1.txt"]',
                                         levels="[1.5, 2.0, 3.0]"))
    summary = run_campaign(scene, failed / "rocking", workers=1, progress=False)
    assert (summary.n_cases, summary.n_failed) == (N_CASES, N_CASES)
    still = base / "still"  # the user's route: floor motions so weak (2e-4 m/s²) that no IDA level is in reach
    still.mkdir()
    (still / "inventory.csv").write_text("id,description,width,depth,height\nrack,server rack,0.6,1.0,2.0\n")
    (still / "motions.csv").write_text("record,floor,direction,file,units,dt\n"
                                       + "".join(f"r{k},1,1,r{k}.txt,m/s2,0.01\n" for k in range(2)))
    for k in range(2):
        (still / f"r{k}.txt").write_text("".join(f"{2e-4 * math.sin(0.1 * (i + k)):.6e}\n" for i in range(300)))
    lost = base / "lost"
    lost.mkdir()
    table = pd.read_csv(failed / "rocking" / "cases.csv", skiprows=[1])  # its units row; written back without it
    table.assign(reason=OLD_LOST).to_csv(lost / "cases.csv", index=False)
    return base


def api_cases(b: Path) -> list[Case]:
    """``opsrock fragility`` on campaigns with nothing to fit."""
    out = ("--out", "rep", "--n-boot", "10")
    return [
        Case("fragility on a campaign whose every case failed", ("fragility", f"{b}/failed/rocking", *out),
             ("every case of", f"{b}/failed/rocking", f"failed ({N_CASES} cases", "first reason: floor motion failed",
              "nothing to fit")),
        Case("fragility on the cases.csv of that campaign", ("fragility", f"{b}/failed/rocking/cases.csv", *out),
             ("every case of", "cases.csv", f"({N_CASES} cases", "nothing to fit")),
        Case("fragility on a campaign whose every case was lost (old store)", ("fragility", f"{b}/lost", *out),
             (f"({N_CASES} cases", "worker process died", f"{N_CASES} of them were lost to the infrastructure",
              "run the campaign again")),
        Case("contents on the user's motions too weak to scale", ("contents", "--inventory", f"{b}/still/inventory.csv",
             "--motions", f"{b}/still/motions.csv", "--out", "rep", "--store", "store", "--quick", "--no-progress"),
             ("every case of", "failed (", "first reason:", "scale factor", "nothing to fit"),
             expect_files=("store",)),  # the failed cases are results (each with its reason), kept for a resume
    ]


def test_api_refusals_keep_the_promise(campaigns, tmp_path):
    assert sweep(api_cases(campaigns), tmp_path, workers=3) == []


def test_api_case_counts(campaigns):
    assert Counter(c.args[0] for c in api_cases(campaigns)) == {"fragility": 3, "contents": 1}


def test_contents_campaigns_with_nothing_to_fit_are_refused_in_one_line(campaigns):
    # the study's campaign step (opsrock contents) resumes the failed campaign (all 12 cases reused, none computed)
    # and stops before any fit, naming it: the same check as opsrock fragility
    from opsrock.inventory.campaigns import StudyOptions, run_campaigns
    from opsrock.inventory.fema.campaigns import campaign_jobs

    scene = load_scene(campaigns / "failed" / "scene.toml")
    with pytest.raises(AllCasesFailedError) as err:
        run_campaigns(campaign_jobs({"rocking": scene}), campaigns / "failed", StudyOptions(workers=1, progress=False))
    message = str(err.value)
    assert message.startswith(f"every case of {campaigns / 'failed' / 'rocking'} failed ({N_CASES} cases; first "
                              "reason: floor motion failed")
    assert message.endswith("nothing to fit") and "\n" not in message and LOST_PREFIX not in message
