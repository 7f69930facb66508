"""Both models side by side for the user's inventory (opsrock.inventory.side_by_side, ``--model both`` with
``--inventory``/``--motions``): its planar outputs are the planar route's and its 3-D tables the 3-D route's, byte
for byte (same cases, same stores' digests, same fits), and the side-by-side table is read from those tables and
the 3-D cases. A tiny study: two items (one with friction), one record in both directions, four levels; the three
runs (both, planar alone, 3-D alone) take about a minute, so they are behind ``slow``."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pandas as pd
import pytest

from opsrock.errors import InputError
from opsrock.inventory.items import read_inventory
from opsrock.inventory.motions import read_motions
from opsrock.inventory.run import StudyOptions, route_of, run_design
from opsrock.inventory.side_by_side import SIDE_BY_SIDE, SIDE_COLUMNS
from opsrock.inventory.study import InventoryDesign


def _inputs(folder: Path) -> InventoryDesign:
    """One record, one floor, both directions (2 s of sines in g at 0.01 s, then 1 s at rest); a cabinet with
    friction and a box without."""
    for d, (amp, f) in {"1": (0.25, 1.5), "2": (0.2, 2.0)}.items():
        vals = [amp * math.sin(2 * math.pi * f * k * 0.01) * (k < 200) for k in range(300)]
        (folder / f"r-d{d}.txt").write_text("\n".join(f"{v:.6f}" for v in vals) + "\n")
    (folder / "motions.csv").write_text("record,floor,direction,file,units,dt\nr,1,1,r-d1.txt,g,0.01\n"
                                        "r,1,2,r-d2.txt,g,0.01\n")
    (folder / "inv.csv").write_text("id,description,width,depth,height,friction\ncab,a cabinet,0.4,0.6,1.2,0.5\n"
                                    "box,a box,0.3,0.3,1.0,\n")
    return InventoryDesign(read_inventory(folder / "inv.csv"), read_motions(folder / "motions.csv"),
                           levels=(0.5, 1.2, 2.5, 6.0), n_boot=0, azimuths=(0.0, 45.0), side_by_side=True)


@pytest.fixture(scope="module")
def studies(tmp_path_factory):
    folder = tmp_path_factory.mktemp("side")
    both = _inputs(folder)
    planar = dataclasses.replace(both, side_by_side=False)
    three_d = dataclasses.replace(planar, solver="rigid3d")
    return {name: Path(run_design(d, folder / name, StudyOptions(workers=1, progress=False)).out_dir)
            for name, d in (("both", both), ("planar", planar), ("3d", three_d))}


@pytest.mark.slow
def test_planar_outputs_are_the_planar_route_s(studies):
    for name in ("fits.csv", "components.csv", "expected.csv", "demands.csv", "pelicun/fragility.csv"):
        assert (studies["both"] / name).read_bytes() == (studies["planar"] / name).read_bytes(), name


@pytest.mark.slow
def test_3d_tables_are_the_3d_route_s(studies):
    assert (studies["both"] / "fits3d.csv").read_bytes() == (studies["3d"] / "fits3d.csv").read_bytes()
    assert (studies["both"] / "components3d.csv").read_bytes() == (studies["3d"] / "components.csv").read_bytes()


@pytest.mark.slow
def test_the_side_by_side_table_reads_both_models(studies):
    side = pd.read_csv(studies["both"] / "side_by_side.csv", skiprows=[1], dtype={"floor": str})
    assert list(side.columns) == list(SIDE_COLUMNS)
    c3 = pd.read_csv(studies["3d"] / "components.csv", skiprows=[1], dtype={"floor": str})  # [1]: the Units row
    cp = pd.read_csv(studies["planar"] / "components.csv", skiprows=[1], dtype={"floor": str})
    c3, cp = (c.set_index(["item", "limit_state"]) for c in (c3, cp))
    fits3d = pd.read_csv(studies["3d"] / "fits3d.csv", skiprows=[1]).query("demand == 'pfv_max'").set_index("item")
    assert set(zip(side["item"], side["limit_state"])) == set(c3.index)
    for r in side.itertuples():
        assert r.median_3d == c3.loc[(r.item, r.limit_state), "median"] or math.isnan(r.median_3d)
        planar = cp.loc[(r.item, r.limit_state), "median"] if (r.item, r.limit_state) in cp.index else math.nan
        assert r.median_planar == planar or (math.isnan(r.median_planar) and math.isnan(planar))
        if r.limit_state == "overturned" and fits3d.loc[r.item, "n_exceeded"] > 0:  # counted by fit3d_table too
            assert r.corner_share == fits3d.loc[r.item, "n_corner"] / fits3d.loc[r.item, "n_exceeded"]
        assert r.n_cases_3d == 8 and r.n_cases_planar == 8  # 4 levels x 2 azimuths; 4 levels x 2 directions
    box = side[side["item"] == "box"]
    assert box["slid_share_planar"].isna().all()  # the planar solver of an item without friction models no slip
    report = (studies["both"] / "report.md").read_text()
    assert "## 3-D and planar side by side" in report and "| box | 1 | overturned |" in report


def test_a_solver_in_plan_is_refused_as_the_planar_model(tmp_path):
    design = _inputs(tmp_path)
    assert route_of(design) is SIDE_BY_SIDE
    with pytest.raises(InputError, match="give a planar solver") as err:
        dataclasses.replace(design, solver="rigid3d")
    assert err.value.argument == "solver"
