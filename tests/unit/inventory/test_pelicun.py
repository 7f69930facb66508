"""The inventory study's pelicun folder (:mod:`opsrock.inventory.pelicun`) from a fits table made by hand: pelicun's
location convention, the component IDs, the damage models' numbers, the demand sample, the loss files and
the configuration. No campaign runs (milliseconds)."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd

from opsrock.constants import G
from opsrock.excitations.records import Record
from opsrock.inventory.fits import FIT_COLUMNS
from opsrock.inventory.items import Inventory, Item
from opsrock.inventory.motions import FloorMotion, MotionSet
from opsrock.inventory.pelicun import component_id, floor_numbers, with_pelicun_ids, write_pelicun_folder
from opsrock.inventory.study import InventoryDesign


def test_floor_numbers_follow_pelicuns_convention():
    assert floor_numbers(("ground", "1", "2", "roof")) == {"ground": 0, "1": 1, "2": 2, "roof": 3}
    assert floor_numbers(("3", "1")) == {"3": 3, "1": 1}
    # labels without a number: numbered in the motions' order
    assert floor_numbers(("L1", "mezzanine", "roof")) == {"L1": 1, "mezzanine": 2, "roof": 3}


def test_component_ids_carry_floor_and_direction():
    assert component_id("server_rack", "3", "2", True) == "opsrock.server_rack.3.d2"
    assert component_id("server_rack", "level 3", "1", False) == "opsrock.server_rack.level_3"


def _fit(item, floor, direction, demand, median, beta, ok=True, message="ok"):
    row = dict.fromkeys(FIT_COLUMNS, math.nan)
    row.update(item=item, description=item, floor=floor, direction=direction, outcome="overturning", demand=demand,
               unit="m/s" if demand == "pfv" else "g", method="ida", median=median, beta=beta, ok=ok, message=message,
               fema_id="", pelicun_id="")
    return row


def test_the_folder_from_a_fits_table(tmp_path):
    t = np.arange(0.0, 2.0, 0.01)
    motions = MotionSet(tuple(FloorMotion(r, f, d, Record(0.01, (1.0 + k) * np.sin(2 * np.pi * t), name=r))
                              for k, r in enumerate(("a", "b")) for f in ("ground", "2") for d in ("1", "2")), "test")
    inv = Inventory((Item("cab", "cabinet", 0.5, 0.4, 1.5, quantity=2.0, repair_cost=250.0),
                     Item("rack", "rack", 0.6, 1.0, 2.0, floors=("2",))), "test")
    design = InventoryDesign(inv, motions, levels=(1.0, 2.0))
    rows = []
    for f in ("ground", "2"):
        for d in ("1", "2"):
            rows += [_fit("cab", f, d, "pfv", 0.8, 0.4), _fit("cab", f, d, "pfa", 0.5, 0.45)]
    rows += [_fit("rack", "2", d, demand, math.nan, math.nan, False, "never overturned within the levels")
             for d in ("1", "2") for demand in ("pfv", "pfa")]
    fits = with_pelicun_ids(pd.DataFrame(rows, columns=list(FIT_COLUMNS)), motions.directions)
    demands = pd.DataFrame([{"record": m.record, "floor": m.floor, "direction": m.direction,
                             "pfa": m.motion.pfa, "pfv": 0.1 * m.motion.pfa} for m in motions.motions])
    paths = write_pelicun_folder(fits, demands, design, tmp_path)
    frag = pd.read_csv(paths["fragility"], index_col=0)
    pfa = pd.read_csv(paths["fragility_pfa"], index_col=0)
    assert sorted(frag.index) == ["opsrock.cab.2.d1", "opsrock.cab.2.d2", "opsrock.cab.ground.d1",
                                  "opsrock.cab.ground.d2"]
    assert np.allclose(frag["LS1-Theta_0"], 0.8) and np.allclose(pfa["LS1-Theta_0"], 0.5 * G)  # PFA in m/s2
    inventory = pd.read_csv(paths["inventory"], index_col=0)
    # pelicun's locations: the ground floor 1, slab 2 at 3; each unit a block of its own
    assert inventory.loc["opsrock.cab.ground.d1", "Location"] == 1 and inventory.loc["opsrock.cab.2.d2", "Location"] == 3
    assert (inventory["Theta_0"] == 2.0).all() and (inventory["Blocks"] == 2).all()
    assert set(inventory["Direction"].astype(str)) == {"1", "2"}
    mapping = pd.read_csv(paths["mapping"])
    assert set(mapping.loc[mapping["item"] == "rack", "status_pfv"]) == {"never overturned within the levels"}
    sample = pd.read_csv(paths["demands"], index_col=0)
    assert list(sample.index) == ["Units", "a", "b"]
    assert sorted(sample.columns) == sorted(f"{k}-{n}-{d}" for k in ("PFA", "PFV") for n in (0, 2) for d in (1, 2))
    assert float(sample.loc["b", "PFA-2-1"]) == demands.query("record == 'b' and floor == '2' and direction == '1'")["pfa"].item()
    loss = pd.read_csv(paths["loss_repair"], index_col=0)
    assert sorted(loss.index) == sorted(f"{c}-Cost" for c in frag.index) and (loss["DS1-Theta_0"] == 250.0).all()
    lmap = pd.read_csv(paths["loss_map"], index_col=0)
    assert (lmap.index == lmap["Repair"]).all()
    config = json.loads(paths["config"].read_text())
    # 2 records, each repeated pelicun.REPEAT = 100 times; storeys: the highest slab (2)
    assert config["DL"]["Options"]["Sampling"]["SampleSize"] == 200 and config["GeneralInformation"]["NumberOfStories"] == 2
    assert config["DL"]["Losses"]["Repair"]["MapApproach"] == "User Defined"
