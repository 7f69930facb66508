"""The inventory study's pelicun folder (:mod:`opsrock.inventory.pelicun`) and its components
(:mod:`opsrock.inventory.components`) from a fits table made by hand: each unit once (one non-directional
component per item and floor), the two planes' fragilities combined, sliding as the first damage state, the
locations, the loss files and the configuration. No campaign runs (milliseconds)."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
from scipy.stats import norm

from opsrock.constants import G
from opsrock.excitations.records import Record
from opsrock.inventory.components import (combined_probability, expected_table, lognormal_through, planar_components,
                                          record_pfv)
from opsrock.inventory.fits import FIT_COLUMNS
from opsrock.inventory.items import FrictionLaw, Inventory, Item
from opsrock.inventory.motions import FloorMotion, MotionSet
from opsrock.inventory.pelicun import floor_locations, write_pelicun_folder
from opsrock.inventory.columns import read_table
from opsrock.inventory.study import InventoryDesign


def _motions(floors=("ground", "2"), locations=(), storeys=None):
    t = np.arange(0.0, 2.0, 0.01)
    return MotionSet(tuple(FloorMotion(r, f, d, Record(0.01, (1.0 + k) * np.sin(2 * np.pi * t), name=r))
                           for k, r in enumerate(("a", "b")) for f in floors for d in ("1", "2")), "test",
                     locations=locations, storeys=storeys)


def test_floor_locations_say_which_label_is_the_ground():
    fl = floor_locations(_motions(("ground", "1", "2", "roof")))
    assert fl.locations == {"ground": 1, "1": 2, "2": 3, "roof": 4} and fl.storeys == 3 and "'ground'" in fl.ground
    # whole numbers: slab n above the ground at location n + 1, the highest the roof (the shipped example)
    fl = floor_locations(_motions(("1", "2", "3")))
    assert fl.locations == {"1": 2, "2": 3, "3": 4} and fl.storeys == 3 and "no floor label is the ground" in fl.ground
    # the shipped building's floors ground and 4 of 8 storeys (labels 'ground', '4'; its roof would be '8'): the
    # building's height, not the highest floor studied (NumberOfStories was 4 here before)
    fl = floor_locations(_motions(("ground", "4"), storeys=8))
    assert fl.locations == {"ground": 1, "4": 5} and fl.storeys == 8
    # the building: L1 (the ground floor) to L4, a 4-storey building
    fl = floor_locations(_motions(("L1", "L2", "L3", "L4")))
    assert fl.locations == {"L1": 1, "L2": 2, "L3": 3, "L4": 4} and fl.storeys == 4 and "'L1'" in fl.ground
    # the manifest's own locations win
    fl = floor_locations(_motions(("L1", "L2"), locations=(("L1", 2), ("L2", 5))))
    assert fl.locations == {"L1": 2, "L2": 5} and fl.storeys == 5 and fl.given


def _fit(item, floor, direction, demand, median, beta, outcome="overturning", ok=True, status="fitted", message="ok"):
    row = dict.fromkeys(FIT_COLUMNS, math.nan)
    row.update(item=item, description=item, floor=floor, direction=direction, outcome=outcome, demand=demand,
               unit="m/s" if demand == "pfv" else "g", method="ida", median=median, beta=beta, ok=ok, status=status,
               message=message, fema_id="", pelicun_id="")
    return row


def _demands(motions, pfv):
    """``pfv[(record, direction)]`` (m/s) on every floor."""
    return pd.DataFrame([{"record": m.record, "floor": m.floor, "direction": m.direction, "pfa": m.motion.pfa,
                          "pfv": pfv[(m.record, m.direction)]} for m in motions.motions])


PFV = {("a", "1"): 0.4, ("a", "2"): 0.2, ("b", "1"): 0.3, ("b", "2"): 0.6}  # m/s, made up


def test_two_planes_combine_into_one_curve_in_the_larger_pfv():
    """At ``pfv_max = x`` each record keeps its directions' proportions; the unit reaches the state when it does
    in either plane (independent given the demands): checked against the formula written out by hand."""
    motions = _motions(("2",))
    pfv = record_pfv(_demands(motions, PFV), "2")
    assert list(pfv["pfv_max"]) == [0.4, 0.6]
    curves = {"1": (0.5, 0.4), "2": (0.8, 0.3)}
    x = 0.7
    p = lambda v, m, b: norm.cdf(np.log(v / m) / b)  # noqa: E731
    want = np.mean([1 - (1 - p(x * 0.4 / 0.4, 0.5, 0.4)) * (1 - p(x * 0.2 / 0.4, 0.8, 0.3)),
                    1 - (1 - p(x * 0.3 / 0.6, 0.5, 0.4)) * (1 - p(x * 0.6 / 0.6, 0.8, 0.3))])
    assert combined_probability(x, curves, pfv)[0] == pytest.approx(want, rel=1e-12)
    # one direction alone, the other never: the combination is that direction's curve in its share of pfv_max;
    # with both records at the same share it is exactly lognormal, and the fit through its quantiles finds it
    same = pd.DataFrame({"1": [0.2, 0.4], "2": [0.1, 0.2]}, index=["a", "b"]).assign(pfv_max=[0.2, 0.4])
    median, beta, err = lognormal_through({"1": (0.5, 0.4)}, same)
    assert median == pytest.approx(0.5, rel=1e-9) and beta == pytest.approx(0.4, rel=1e-9) and err < 1e-9


def test_each_unit_once_with_sliding_as_the_first_damage_state(tmp_path):
    motions = _motions()
    inv = Inventory((Item("cab", "cabinet", 0.5, 0.4, 1.5, quantity=2.0, repair_cost=250.0, slide_cost=40.0,
                          friction=FrictionLaw("fixed", (0.3,))),
                     Item("rack", "rack", 0.6, 1.0, 2.0, floors=("2",))), "test")
    design = InventoryDesign(inv, motions, levels=(1.0, 2.0))
    rows = []
    for f in ("ground", "2"):
        for d in ("1", "2"):
            rows += [_fit("cab", f, d, "pfv", 0.8, 0.4), _fit("cab", f, d, "pfa", 0.5, 0.45),
                     _fit("cab", f, d, "pfv", 0.3, 0.3, "sliding"), _fit("cab", f, d, "pfv", 0.3, 0.3, "displaced")]
    rows += [_fit("rack", "2", d, demand, math.nan, math.nan, ok=False, status="never", message="never overturned")
             for d in ("1", "2") for demand in ("pfv", "pfa")]
    fits = pd.DataFrame(rows, columns=list(FIT_COLUMNS))
    demands = _demands(motions, PFV)
    components = planar_components(fits, demands, design)
    cab = components[components["item"] == "cab"]
    assert list(cab["limit_state"]) == ["displaced", "overturned"] * 2 and list(cab["ls"]) == ["LS1", "LS2"] * 2
    assert set(components.loc[components["item"] == "rack", "status"]) == {"never"}
    paths = write_pelicun_folder(components, fits, demands, design, tmp_path)
    frag = pd.read_csv(paths["fragility"], index_col=0)
    assert sorted(frag.index) == ["opsrock.cab.2", "opsrock.cab.ground"]  # one component per item and floor
    assert (frag["Demand-Directional"] == 0).all() and (frag["Demand-Type"] == "Peak Floor Velocity").all()
    assert (frag["LS1-Theta_0"] < frag["LS2-Theta_0"]).all()  # displaced before overturned
    inventory = pd.read_csv(paths["inventory"], index_col=0)
    # each unit once: the quantity, as that many blocks, non-directional, at pelicun's location (ground 1)
    assert (inventory["Theta_0"] == 2.0).all() and (inventory["Blocks"] == 2).all()
    assert set(inventory["Direction"].astype(str)) == {"0"}
    assert inventory.loc["opsrock.cab.ground", "Location"] == 1 and inventory.loc["opsrock.cab.2", "Location"] == 3
    per_dir = pd.read_csv(paths["per_direction_pfa"], index_col=0)  # marked per direction, PFA in m/s2
    assert "opsrock.cab.ground.d1.overturning" in per_dir.index and np.allclose(per_dir["LS1-Theta_0"], 0.5 * G)
    mapping, _ = read_table(paths["mapping"])
    assert mapping.loc[mapping["item"] == "rack", "status"].str.contains("never").all()
    loss = pd.read_csv(paths["loss_repair"], index_col=0)
    assert (loss["DS1-Theta_0"] == 40.0).all() and (loss["DS2-Theta_0"] == 250.0).all()
    sample = pd.read_csv(paths["demands"], index_col=0)
    assert list(sample.index) == ["Units", "a", "b"]
    assert float(sample.loc["b", "PFV-2-2"]) == 0.6  # location 3's demand: PFV-2 (pelicun's offset -1)
    config = json.loads(paths["config"].read_text())
    assert config["DL"]["Options"]["NonDirectionalMultipliers"] == {"ALL": 1.0}
    assert config["DL"]["Options"]["Sampling"]["SampleSize"] == 200 and config["GeneralInformation"]["NumberOfStories"] == 2
    # the exact expectation: per record pfv_max, P(damaged) = max of the two limit states, never above the quantity
    expected = expected_table(components, demands, design, fits)
    for r in expected.itertuples():
        c = components[(components["item"] == r.item) & (components["floor"] == r.floor)
                       & (components["status"] == "fitted")].set_index("limit_state")
        x = np.array([0.4, 0.6])
        if not len(c):
            assert r.expected_damaged == 0.0
            continue
        p = {k: norm.cdf(np.log(x / c.loc[k, "median"]) / c.loc[k, "beta"]) for k in c.index}
        assert r.expected_overturned == pytest.approx(2.0 * p["overturned"].mean(), rel=1e-12)
        assert r.expected_damaged == pytest.approx(2.0 * np.maximum(p["displaced"], p["overturned"]).mean(), rel=1e-12)
        assert r.expected_damaged <= r.quantity
        assert r.expected_cost == pytest.approx(40.0 * r.expected_displaced_only + 250.0 * r.expected_overturned)


def test_separated_outcomes_are_a_step_in_both_routes_and_pelicun_gets_a_deterministic_capacity(tmp_path):
    """Outcomes the demand separates perfectly have no finite maximum-likelihood lognormal; the planar route has
    always kept such a direction as a step at the middle of the gap (in ln x: the geometric mean of its ends).
    The 3-D route now does the same in ``pfv_max`` instead of leaving the item without a component, and a
    combined planar curve that is one step is that step: pelicun gets a blank ``Family`` (deterministic)."""
    from opsrock.inventory.components import STEP_SOURCE, three_d_components

    motions = _motions(("2",))
    pfv = {("a", "1"): 0.4, ("a", "2"): 0.2, ("b", "1"): 0.6, ("b", "2"): 0.3}  # m/s: direction 1 the larger
    demands = _demands(motions, pfv)
    inv = Inventory((Item("rack", "rack", 0.6, 1.0, 2.0, quantity=2.0, repair_cost=100.0),), "test")
    design = InventoryDesign(inv, motions, levels=(1.0, 2.0), n_boot=4)
    # 3-D: x = scale x pfv_max is 0.2, 0.4, 0.6, 0.8 (record a) and 0.3, 0.6, 0.9, 1.2 (b); overturned above 0.5
    cases = pd.DataFrame([{"item": "rack", "floor": "2", "record": r, "scale": s, "azimuth": z, "status": "ok",
                           "overturned": s * {"a": 0.4, "b": 0.6}[r] > 0.5, "slide_max": math.nan,
                           "overturned_over": ""} for r in ("a", "b") for s in (0.5, 1.0, 1.5, 2.0) for z in (0.0, 30.0)])
    components3d = three_d_components(cases, demands, design, 1)
    three_d = components3d.iloc[0]
    assert three_d["status"] == "fitted" and three_d["beta"] == 0.0 and three_d["source"].endswith(STEP_SOURCE)
    assert three_d["median"] == pytest.approx(math.sqrt(0.4 * 0.6), rel=1e-12)  # the gap 0.4 .. 0.6
    # planar: direction 1 a step at 0.49 m/s, direction 2 never; direction 1 is pfv_max under both records
    fits = pd.DataFrame([_fit("rack", "2", "1", "pfv", math.sqrt(0.4 * 0.6), 0.0, ok=False, status="no fit",
                              message="separated"),
                         _fit("rack", "2", "2", "pfv", math.nan, math.nan, ok=False, status="never", message="never")],
                        columns=list(FIT_COLUMNS))
    components = planar_components(fits, demands, design)
    planar = components.iloc[0]
    assert planar["status"] == "fitted" and planar["beta"] == 0.0
    assert planar["median"] == pytest.approx(three_d["median"], rel=1e-9)
    for name, components in (("3d", components3d), ("planar", components)):
        frag = pd.read_csv(write_pelicun_folder(components, fits, demands, design, tmp_path / name)["fragility"],
                           index_col=0, keep_default_na=False)
        assert (frag.loc["opsrock.rack.2", "LS1-Family"], frag.loc["opsrock.rack.2", "LS1-Theta_1"]) == ("", "")
        # the exact expectation with the step: record a (pfv_max 0.4) below it, b (0.6) above: 2 units x 1/2
        assert expected_table(components, demands, design).iloc[0]["expected_overturned"] == 1.0
