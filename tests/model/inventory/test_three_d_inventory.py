"""The inventory study in three dimensions (opsrock.inventory.three_d): the demand conventions (PFV of each
direction, the larger, pelicun's non-directional 1.2 x the larger), the campaigns in plan built from the
paired motions (every item a box with its depth, Housner's impact, at every azimuth), the refusals naming the
argument, and one tiny study end to end, stored and resumed."""

from __future__ import annotations

import math
import sqlite3
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from opsrock.errors import InputError
from opsrock.inventory.items import read_inventory
from opsrock.inventory.motions import MotionSet, read_motions
from opsrock.inventory.run import StudyOptions, run_design
from opsrock.inventory.study import InventoryDesign
from opsrock.inventory.columns import read_table
from opsrock.inventory.three_d import NONDIRECTIONAL_FACTOR, PFV_CONVENTIONS, pfv_demands, three_d_scenes


@pytest.fixture
def inputs(tmp_path: Path) -> tuple[Path, Path]:
    """A one-record, one-floor manifest in both directions (2 s of sines, then 1 s at rest, in g at 0.01 s) and a
    one-item inventory (a 0.4 x 0.6 x 1.2 m cabinet)."""
    for d, (amp, f) in {"1": (0.25, 1.5), "2": (0.2, 2.0)}.items():
        vals = [amp * math.sin(2 * math.pi * f * k * 0.01) * (k < 200) for k in range(300)]
        (tmp_path / f"r-d{d}.txt").write_text("\n".join(f"{v:.6f}" for v in vals) + "\n")
    (tmp_path / "motions.csv").write_text("record,floor,direction,file,units,dt\nr,1,1,r-d1.txt,g,0.01\n"
                                          "r,1,2,r-d2.txt,g,0.01\n")
    (tmp_path / "inv.csv").write_text("id,description,width,depth,height\ncab,a cabinet,0.4,0.6,1.2\n")
    return tmp_path / "inv.csv", tmp_path / "motions.csv"


def _design(inputs, **over) -> InventoryDesign:
    inv, motions = inputs
    settings = {"solver": "rigid3d", "azimuths": (0.0, 45.0), "levels": (4.0,), "n_boot": 0, **over}
    return InventoryDesign(read_inventory(inv), read_motions(motions), **settings)


def test_the_demand_conventions_are_pelicuns():
    cases = pd.DataFrame({"record": ["r", "r"], "floor": ["1", "1"], "scale": [2.0, 0.5]})
    demands = pd.DataFrame({"record": ["r", "r"], "floor": ["1", "1"], "direction": ["1", "2"], "pfv": [0.3, 0.4]})
    out = pfv_demands(cases, demands)
    np.testing.assert_allclose(out["pfv_1"], [0.6, 0.15], rtol=1e-15)  # the scale factor times the floor's PFV
    np.testing.assert_allclose(out["pfv_2"], [0.8, 0.2], rtol=1e-15)
    np.testing.assert_allclose(out["pfv_max"], [0.8, 0.2], rtol=1e-15)
    # pelicun: a non-directional demand is the largest directional one times NonDirectionalMultipliers (1.2)
    assert NONDIRECTIONAL_FACTOR == 1.2
    np.testing.assert_allclose(out["pfv_max_x1.2"], [0.96, 0.24], rtol=1e-15)
    assert list(PFV_CONVENTIONS) == ["pfv_1", "pfv_2", "pfv_max", "pfv_max_x1.2"]


def test_the_campaigns_are_in_plan_with_both_directions(inputs):
    (gs,) = three_d_scenes(_design(inputs))
    scene = gs.scene
    assert scene.solver == "rigid3d" and scene.in_plan and gs.group.name == "d12-rigid3d"
    assert [r.name for r in scene.records.grounds] == ["r.1"] and [r.name for r in scene.records.seconds] == ["r.1.d2"]
    block = scene.blocks[0].block
    assert (block.width, block.depth, block.height, block.restitution_factor) == (0.4, 0.6, 1.2, 1.0)
    assert [c.case_id for c in scene.cases()] == ["cab-3d/r.1/ground/l01/z01", "cab-3d/r.1/ground/l01/z02"]
    assert gs.records == {"r.1": ("r", "1")}


def test_refusals_name_the_argument(inputs, tmp_path):
    design = _design(inputs)
    one = MotionSet(tuple(m for m in design.motions.motions if m.direction == "1"), "one direction")
    with pytest.raises(InputError, match="has direction 1 only") as info:
        three_d_scenes(InventoryDesign(design.inventory, one, solver="rigid3d"))
    assert info.value.argument == "motions"
    for bad in ((), (0.0, 0.0), (400.0,), (math.nan,)):
        with pytest.raises(InputError, match="azimuths must be") as info:
            _design(inputs, azimuths=bad)
        assert info.value.argument == "azimuths"
    (tmp_path / "e.csv").write_text("id,description,width,depth,height,restitution\ncab,a cabinet,0.4,0.6,1.2,0.8\n")
    with pytest.raises(InputError, match="item 'cab' gives restitution = 0.8") as info:
        three_d_scenes(InventoryDesign(read_inventory(tmp_path / "e.csv"), design.motions, solver="rigid3d"))
    assert info.value.argument == "inventory"


def test_a_tiny_study_in_three_dimensions_is_written_and_resumed(inputs, tmp_path):
    """Two cases (one level, azimuths 0 and 45 deg), about a second each with the floor measures."""
    design = _design(inputs)
    first = run_design(design, tmp_path / "out", StudyOptions(workers=1, progress=False))
    again = run_design(design, tmp_path / "out", StudyOptions(workers=1, progress=False))
    assert (first.n_cases, first.n_computed, again.n_computed) == (2, 2, 0)
    rows = read_table(first.tables["fits3d"], dtype=str, keep_default_na=False)[0].to_dict("records")
    assert [r["demand"] for r in rows] == list(PFV_CONVENTIONS)
    assert all(r["item"] == "cab" and r["floor"] == "1" and int(r["n_azimuths"]) == 2 for r in rows)
    assert all(int(r["n_cases"]) + int(r["n_failed"]) == 2 for r in rows)
    assert "1.2" in Path(first.report).read_text()
    # the planar route's outputs too (the same stages): fits per direction, expected numbers, a pelicun folder
    assert set(first.tables) == {"fits", "components", "demands", "expected", "fits3d"} and first.pelicun
    comps, _ = read_table(first.tables["components"], dtype={"floor": str})
    assert set(comps["source"]) == {"3-D (2 azimuths pooled)"} and set(comps["demand"]) == {"pfv_max"}
    fits, _ = read_table(first.tables["fits"], dtype={"direction": str, "floor": str})
    assert set(fits["direction"]) == {"1", "2"} and set(fits["item"]) == {"cab"}
    assert (fits["n_cases"] + fits["n_failed"] == 2).all()  # each case once per direction, not twice


@pytest.mark.slow
def test_a_case_stored_as_timed_out_is_computed_again_by_a_plain_rerun(inputs, tmp_path):
    """A case stored as failed on its case budget (a loaded machine, a cold compile) is computed again by a plain
    re-run, no --force, and the report says so; every other stored failure stays a result (issue 44). About 15 s
    (a study, then its re-run): slow."""
    design = _design(inputs)
    run_design(design, tmp_path / "out", StudyOptions(workers=1, progress=False))
    store = next((tmp_path / "out" / "campaigns").glob("*/results.sqlite"))
    db = sqlite3.connect(store)
    db.execute("UPDATE results SET status = 'failed', verdict = 'failed', "
               "reason = 'timeout: no answer within the case budget of 300 s' WHERE case_id = "
               "(SELECT MIN(case_id) FROM results)")
    db.commit()
    db.close()
    retried = run_design(design, tmp_path / "out", StudyOptions(workers=1, progress=False))
    assert (retried.n_computed, retried.n_failed) == (1, 0)
    assert "1 of all these computed in this run (1 of them stored as timed out before, computed again)" in \
        Path(retried.report).read_text()


def test_a_round_item_is_a_cylinder_in_its_own_campaign(inputs, tmp_path):
    """Issue 45: an inventory row with ``shape = cylinder`` and a ``diameter`` (an oxygen cylinder 0.23 x 1.5 m)
    beside a box: the box's campaign in plan runs rigid3d, the cylinder's cylinder3d, its block the diameter wide
    without a depth, a homogeneous solid cylinder's mass distribution (cm at mid-height, radius of gyration
    sqrt(d²/16 + H²/12)), Housner's impact; and a tiny study runs both."""
    inv, motions = inputs
    (tmp_path / "mixed.csv").write_text("id,description,width,depth,height,shape,diameter\n"
                                        "cab,a cabinet,0.4,0.6,1.2,,\n"
                                        "o2,an oxygen cylinder,,,1.5,cylinder,0.23\n")
    design = InventoryDesign(read_inventory(tmp_path / "mixed.csv"), read_motions(motions), solver="rigid3d",
                             azimuths=(0.0, 45.0), levels=(4.0,), n_boot=0)
    scenes = {gs.group.name: gs.scene for gs in three_d_scenes(design)}
    assert set(scenes) == {"d12-rigid3d", "d12-cylinder3d"}
    block = scenes["d12-cylinder3d"].blocks[0].block
    assert (block.width, block.depth, block.height, block.restitution_factor) == (0.23, None, 1.5, 1.0)
    assert block.h_cm == 0.75 and block.r_gyration == pytest.approx(math.sqrt(0.23**2 / 16 + 1.5**2 / 12))
    out = run_design(design, tmp_path / "out", StudyOptions(workers=1, progress=False))
    # the cylinder at one azimuth (it is round), the box of its size beside it at both, in no item's table
    assert out.n_cases == 5 and out.n_computed == 5
    assert set(read_table(out.tables["fits3d"])[0]["item"]) == {"cab", "o2"}
    assert set(read_table(out.tables["expected"])[0]["item"]) == {"cab", "o2"}
    boxes, units = read_table(out.tables["boxes"], dtype={"floor": str})
    assert list(boxes["model"]) == ["as given", "box of its size"] and list(boxes["shape"]) == ["cylinder", "box"]
    assert list(boxes["n_cases"] + boxes["n_failed"]) == [1, 2] and units["median"] == "see unit"
    assert set(boxes["demand"]) == {"pfv_max"} and units["share_rim"] == "-"
    # the report counts the items' cases, and the boxes' apart (they are in no item's table)
    n_box_failed = int(boxes.loc[boxes["model"] == "box of its size", "n_failed"].iloc[0])
    assert "3 cases of the inventory's items" in Path(out.report).read_text()
    assert f"2 more of the boxes run beside the round items, {n_box_failed} failed" in Path(out.report).read_text()


@pytest.mark.slow
def test_both_models_write_the_box_beside_a_round_item(inputs, tmp_path):
    """``--model both`` computes the box of a round item's size beside it in three dimensions, as the 3-D route
    does: it writes its table and the report's section (before, the box was computed and left unreported). About
    15 s (a cylinder case and the planar campaigns): slow."""
    inv, motions = inputs
    (tmp_path / "round.csv").write_text("id,description,width,depth,height,shape,diameter\n"
                                        "o2,an oxygen cylinder,,,1.5,cylinder,0.23\n")
    design = InventoryDesign(read_inventory(tmp_path / "round.csv"), read_motions(motions), side_by_side=True,
                             azimuths=(0.0, 45.0), levels=(4.0,), n_boot=0)
    both = run_design(design, tmp_path / "both", StudyOptions(workers=1, progress=False))
    boxes, _ = read_table(both.tables["boxes"], dtype={"floor": str})
    assert list(boxes["model"]) == ["as given", "box of its size"]
    assert list(boxes["n_cases"] + boxes["n_failed"]) == [1, 2]
    report = Path(both.report).read_text()
    assert "## Round items against the box of their size" in report
    # the items' cases of both models (2 planar, 1 in three dimensions), the boxes' apart
    assert "3 cases of the inventory's items" in report and "2 more of the boxes run beside the round items" in report
    assert "of the items' cases, 2 planar (" in report and "and 1 in three dimensions (" in report
