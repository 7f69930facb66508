"""Scenes in three dimensions (issue 33): blocks with ``depth``, ``[pulse] azimuth`` and ``[records] azimuth``
(a swept axis), ``[records] second = "other"``, ``solver = "auto"`` picking ``rigid3d`` exactly when the design
turns a block or gives a second component, the refusals, and one tiny campaign run end to end: stored,
resumed, with the three-dimensional columns in ``cases.csv``."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from opsrock.campaign.cases import CONTACT_COLUMNS, PLAN_COLUMNS, PULSE_COLUMNS
from opsrock.campaign.scene import load_scene
from opsrock.campaign.workflow import run_campaign
from opsrock.errors import SceneError
from opsrock.excitations.plan import PlanMotion
from _support import case_rows

BLOCKS = """[[block]]
name = "box"
width = 0.4
height = 1.2
depth = 0.6
restitution = "housner"
reason = "a cabinet, 0.4 x 0.6 x 1.2 m"
"""

PULSE_SCENE = """blocks = "blocks.toml"
[solver]
name = "{solver}"
[pulse]
{pulse}
[grid.freq_ratio]
values = [3.0]
[grid.pfa_ratio]
values = [{pfa}]
"""


def _scene(tmp_path: Path, solver: str = "auto", pulse: str = "azimuth = [0, 45]", pfa: str = "1.5, 4.0",
           blocks: str = BLOCKS) -> Path:
    (tmp_path / "blocks.toml").write_text(blocks)
    path = tmp_path / "scene.toml"
    path.write_text(PULSE_SCENE.format(solver=solver, pulse=pulse, pfa=pfa))
    return path


def test_azimuths_are_an_axis_and_auto_picks_rigid3d(tmp_path):
    scene = load_scene(_scene(tmp_path))
    assert scene.solver == "rigid3d" and scene.in_plan and "three dimensions" in scene.choice.reason
    assert scene.n_cases == 4 and scene.blocks[0].block.depth == 0.6
    cases = scene.cases()
    assert [c.case_id for c in cases] == ["box/f01/a01/z01", "box/f01/a01/z02", "box/f01/a02/z01", "box/f01/a02/z02"]
    assert [c.azimuth for c in cases] == [0.0, 45.0, 0.0, 45.0]
    assert isinstance(cases[1].excitation, PlanMotion) and cases[1].excitation.azimuth == 45.0
    assert scene.columns == (*PULSE_COLUMNS, *CONTACT_COLUMNS, *PLAN_COLUMNS)
    assert cases[1].row()["depth"] == 0.6 and cases[1].row()["azimuth"] == 45.0


def test_a_planar_design_keeps_the_planar_choice_and_its_digest(tmp_path):
    # azimuths that do not turn the block (multiples of 360 deg) and a depth need no third dimension: auto keeps
    # the planar solvers' choice, and a planar solver ignores the depth
    scene = load_scene(_scene(tmp_path, pulse="azimuth = 360"))
    assert not scene.in_plan and scene.solver != "rigid3d"
    plain = load_scene(_scene(tmp_path, solver="housner_fast", pulse="", blocks=BLOCKS.replace("depth = 0.6\n", "")))
    assert [c.case_id for c in plain.cases()] == ["box/f01/a01", "box/f01/a02"]  # no azimuth, no /z part
    assert "azimuth" not in plain.design.fingerprint() and "depth" not in str(plain.fingerprint()["blocks"])


@pytest.mark.parametrize("pulse, field, needle", [
    ("azimuth = 400", "pulse.azimuth", "within [-360, 360]"),
    ("azimuth = nan", "pulse.azimuth", "within [-360, 360]"),
    ("azimuth = [30, 30]", "pulse.azimuth", "twice"),
    ("azimuth = []", "pulse.azimuth", "non-empty"),
    ('azimuth = "north"', "pulse.azimuth", "angle"),
])
def test_bad_azimuths_are_refused_naming_the_key(tmp_path, pulse, field, needle):
    with pytest.raises(SceneError, match=re.escape(needle)) as info:
        load_scene(_scene(tmp_path, pulse=pulse))
    assert info.value.field == field


def test_a_planar_solver_or_a_box_without_depth_is_refused_in_plan(tmp_path):
    with pytest.raises(SceneError, match="planar.*three dimensions|is planar") as info:
        load_scene(_scene(tmp_path, solver="friction", pulse="azimuth = 30"))
    assert info.value.field == "solver.name"
    with pytest.raises(SceneError, match="block 'box' has no depth"):
        load_scene(_scene(tmp_path, pulse="azimuth = 30", blocks=BLOCKS.replace("depth = 0.6\n", "")))
    with pytest.raises(SceneError, match="block\\[0\\].depth"):
        load_scene(_scene(tmp_path, blocks=BLOCKS.replace("depth = 0.6", "depth = -1")))


def test_second_components_need_a_library_set(tmp_path):
    (tmp_path / "blocks.toml").write_text(BLOCKS)
    (tmp_path / "r.txt").write_text("0.1\n" * 50)
    path = tmp_path / "rec.toml"
    path.write_text('blocks = "blocks.toml"\n[records]\nfiles = ["r.txt"]\nunits = "g"\ndt = 0.01\nsecond = "other"\n')
    with pytest.raises(SceneError, match="needs a library set") as info:
        load_scene(path)
    assert info.value.field == "records.second"


def test_a_tiny_campaign_in_three_dimensions_is_stored_and_resumed(tmp_path):
    """Two cases (one pulse, azimuths 0 and 45 deg) of a 0.4 x 0.6 x 1.2 m box, about a second each."""
    path = _scene(tmp_path, pfa="4.0")
    first = run_campaign(path, tmp_path / "out", workers=1, progress=False)
    again = run_campaign(path, tmp_path / "out", workers=1, progress=False)
    assert (first.n_computed, again.n_computed, again.n_reused) == (2, 0, 2)
    rows = case_rows(tmp_path / "out" / "cases.csv")
    assert [r["case_id"] for r in rows] == ["box/f01/a01/z01", "box/f01/a01/z02"]
    for r in rows:
        assert r["status"] == "ok" and r["solver"] == "rigid3d" and r["depth"] == "0.6"
        # rigid3d's theta_max is the peak tilt (opsrock.result: RockingResult.theta_max for rigid3d)
        assert float(r["tilt_max"]) == float(r["theta_max"]) and math.isfinite(float(r["twist_max"]))
        assert (r["overturned_over"] in ("edge", "corner")) == (r["verdict"] == "overturned")
        assert (r["time_rim"], r["time_rolling"]) == ("0.0", "0.0")  # a cylinder's (PlanSummary): 0 for a box
    assert [r["azimuth"] for r in rows] == ["0.0", "45.0"]
