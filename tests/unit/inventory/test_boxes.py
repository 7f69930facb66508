"""Issue 45: a round item beside the box of its size, computed in the study (:func:`box_table`) and rendered by
the report without computing: the medians, how far the box is off, the shares by mechanism, the failures with
their reasons."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from opsrock.inventory.items import Item
from opsrock.inventory.three_d import BOX_COLUMNS, BOX_SUFFIX, box_of, box_table

#: A tail failure's reason as cylinder3d stores it (opsrock.solvers.status.REASONS, with where it stopped).
TAIL = "the block was still moving max_free_time after the end of the excitation (still rolling on its rim, t = {t:g} s)"


def _fit(item: str, median: float, n: dict[str, int], n_cases: int, n_failed: int) -> dict:
    return {"item": item, "floor": "2", "demand": "pfv_max", "unit": "m/s", "median": median, "median_lo": median * 0.8,
            "median_hi": median * 1.2, "beta": 0.4, "n_cases": n_cases, "n_exceeded": sum(n.values()),
            "n_failed": n_failed, **{f"n_{m}": n.get(m, 0) for m in ("edge", "corner", "rim", "rolling")}}


def _cases(item: str, failed: list[str], ok: int) -> list[dict]:
    return ([{"item": item, "floor": "2", "status": "failed", "reason": r} for r in failed]
            + [{"item": item, "floor": "2", "status": "ok", "reason": ""}] * ok)


def test_the_box_of_a_round_item_s_size_is_a_box_with_its_diameter_as_width_and_depth():
    o2 = Item("o2", "an oxygen cylinder", 0.23, 0.23, 1.5, mass=65.0, shape="cylinder", quantity=2, repair_cost=1200)
    box = box_of(o2)
    assert (box.id, box.shape, box.width, box.depth, box.height, box.mass) == ("o2" + BOX_SUFFIX, "box", 0.23, 0.23,
                                                                                1.5, 65.0)
    assert box.cm_height is None and box.radius_of_gyration is None  # a homogeneous box, as a user would enter it


def test_the_box_is_off_by_its_median_over_the_cylinder_s_and_shares_are_of_the_overturnings():
    """Cylinder median 0.5 m/s, box 0.4 m/s: off by 0.4 / 0.5 - 1 = -0.2; the cylinder's 10 overturnings 7 rolling
    and 3 on one rim point; the box's 8 over 2 edges and 6 corners; failures grouped by the kind of their reason,
    whatever time each reason holds (the text before a colon, the old grouping, gave one group per time)."""
    fits = pd.DataFrame([_fit("o2", 0.5, {"rim": 3, "rolling": 7}, 38, 2),
                         _fit("o2" + BOX_SUFFIX, 0.4, {"edge": 2, "corner": 6}, 120, 0),
                         _fit("cab", 0.9, {"edge": 1}, 40, 0)])
    cases = pd.DataFrame(_cases("o2", [TAIL.format(t=41.25), TAIL.format(t=38.5)], 38) + _cases("o2" + BOX_SUFFIX, [], 120))
    table = box_table(fits, cases)
    assert tuple(table.columns) == BOX_COLUMNS and list(table["model"]) == ["as given", "box of its size"]
    cyl, box = table.iloc[0], table.iloc[1]
    assert (cyl["share_rim"], cyl["share_rolling"], cyl["share_corner"]) == (0.3, 0.7, 0.0)
    assert (box["share_edge"], box["share_corner"]) == (0.25, 0.75)
    assert box["box_off"] == pytest.approx(-0.2, rel=1e-12) and math.isnan(cyl["box_off"])
    assert cyl["failed_reasons"] == f"2 x max_free_time ({TAIL.format(t=41.25)})" and box["failed_reasons"] == ""


def test_a_round_item_that_never_overturned_has_no_shares_and_no_offset():
    fits = pd.DataFrame([_fit("o2", math.nan, {}, 40, 0), _fit("o2" + BOX_SUFFIX, 0.4, {"corner": 4}, 120, 0)])
    table = box_table(fits, pd.DataFrame(_cases("o2", [], 40) + _cases("o2" + BOX_SUFFIX, [], 120)))
    assert math.isnan(table.iloc[0]["share_rim"]) and math.isnan(table.iloc[1]["box_off"])


def test_the_report_renders_the_table_it_is_given():
    from opsrock.inventory.report import _box_lines

    fits = pd.DataFrame([_fit("o2", 0.5, {"rim": 3, "rolling": 7}, 38, 2),
                         _fit("o2" + BOX_SUFFIX, 0.4, {"edge": 2, "corner": 6}, 120, 0)])
    cases = pd.DataFrame(_cases("o2", [TAIL.format(t=41.25), TAIL.format(t=38.5)], 38) + _cases("o2" + BOX_SUFFIX, [], 120))
    text = "\n".join(_box_lines(box_table(fits, cases)))
    assert "## Round items against the box of their size" in text
    assert "| o2 | 2 | as given (cylinder) | 0.5 [0.4, 0.6] | 10 / 38 | 30 % / 70 % | - |  | 2 (2 x max_free_time (" + TAIL.format(t=41.25) + ")) |" in text
    assert "| o2 | 2 | box of its size (box) | 0.4 [0.32, 0.48] | 8 / 120 | - | 25 % / 75 % | -20 % | 0 |" in text
    assert _box_lines(None) == [] and _box_lines(pd.DataFrame(columns=list(BOX_COLUMNS))) == []
