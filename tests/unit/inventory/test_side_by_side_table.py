"""The side-by-side table of the two models (opsrock.inventory.side_by_side.side_by_side_table) on hand-made
tables: the medians taken from each model's components, the azimuth medians fitted to each azimuth's cases, the
corner share of the overturnings and the slid shares counted on the cases. Exact counts; the azimuth medians
checked for their order (the azimuth that overturns at lower demands has the lower median)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pandas as pd

from opsrock.inventory.side_by_side import side_by_side_table, split_cases


def _cases() -> pd.DataFrame:
    """Eight 3-D cases of item ``a`` on floor 1 (record r, PFV max 1 m/s) at scales 1 to 4: azimuth 0 overturns at
    scales 2 and 4, azimuth 45 at 3 only (outcomes overlap at both, so both fit); over a corner from scale 3."""
    rows = []
    for z, over in ((0.0, (False, True, False, True)), (45.0, (False, False, True, False))):
        for scale, o in zip((1.0, 2.0, 3.0, 4.0), over):
            rows.append({"item": "a", "floor": "1", "direction": "12", "record": "r", "status": "ok", "scale": scale,
                         "azimuth": z, "overturned": o, "overturned_over": "corner" if o and scale >= 3 else
                         ("edge" if o else ""), "slide_max": 0.1 * scale})
    rows.append({**rows[0], "direction": "1", "azimuth": math.nan, "slide_max": math.nan})  # a planar case
    return pd.DataFrame(rows)


def test_split_and_measure():
    planar, cases3d = split_cases(_cases())
    assert len(planar) == 1 and len(cases3d) == 8
    demands = pd.DataFrame({"record": ["r", "r"], "floor": ["1", "1"], "direction": ["1", "2"], "pfv": [0.5, 1.0]})
    components = pd.DataFrame({"item": ["a"], "floor": ["1"], "limit_state": ["overturned"], "median": [2.0],
                               "status": ["fitted"]})
    components3d = pd.DataFrame({"item": ["a", "a"], "floor": ["1", "1"], "limit_state": ["displaced", "overturned"],
                                 "median": [1.5, 2.5], "status": ["fitted", "fitted"]})
    design = SimpleNamespace(inventory=SimpleNamespace(items=(SimpleNamespace(id="a", slide_distance=0.25),)),
                             slide_distance=0.05, seed=0)
    side = side_by_side_table(components, components3d, planar, cases3d, demands, design).set_index("limit_state")
    over = side.loc["overturned"]
    assert (over["median_3d"], over["median_planar"], over["ratio_3d_planar"]) == (2.5, 2.0, 1.25)
    assert over["corner_share"] == 2 / 3  # three overturnings (scales 2, 4 at azimuth 0; 3 at 45), two from scale 3
    assert over["slid_share_3d"] == 4 / 8  # slide 0.1 x scale >= 0.25 m at scales 3 and 4 (of 4), both azimuths
    assert math.isnan(over["slid_share_planar"])  # no slip modelled in the planar case
    assert over["az_low"] == 0.0 and over["az_high"] == 45.0  # azimuth 0 overturns at lower demands
    assert 1.0 < over["median_az_low"] < over["median_az_high"]
    disp = side.loc["displaced"]
    assert disp["median_planar"] != disp["median_planar"] and disp["status_planar"] == "not modelled"
    assert math.isnan(disp["corner_share"])
