"""The directionality study (:mod:`opsrock.inventory.directionality.study`): the summary's tables on small synthetic
tables whose answers follow by hand, the plan frames of the weaker axis against :class:`PlanMotion`, and the
quick study end to end with a planar solver standing in for ``rigid3d`` (the plumbing: every file, and the
3-D over planar ratio exactly 1 when both models run the same planar cases)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from opsrock.inventory.directionality.study import DirectionalityDesign, StudyItem, quick
from opsrock.inventory.run import StudyOptions, run_design
from opsrock.inventory.directionality.cases import weak_cosines
from opsrock.inventory.directionality.columns import read_directionality_table, units_of
from opsrock.inventory.directionality.summary import (ALL, PELICUN_FACTOR, cost_table, directionality_table,
                                                     mechanisms, verdict)
from opsrock._files import read_units
from opsrock.errors import InputError
from opsrock.excitations import PlanMotion, Record


def _fit(model: str, demand: str, median: float, n: int = 5, azimuth: str = ALL) -> dict:
    return {"model": model, "item": "box", "floor": "8", "azimuth": azimuth, "demand": demand, "median": median,
            "median_lo": median * 0.9, "median_hi": median * 1.1, "beta": 0.4, "beta_lo": 0.3, "beta_hi": 0.5,
            "n_cases": 20, "n_overturned": n, "n_failed": 0, "n_records": 4, "ok": True, "message": ""}


def _case(over: str, overturned: bool, azimuth: float = 0.0, model: str = "3d", status: str = "ok") -> dict:
    return {"model": model, "item": "box", "floor": "8", "azimuth": azimuth, "record": "R", "status": status,
            "overturned": overturned, "overturned_over": over}


class _Design:
    azimuths = (0.0,)
    tolerance = 0.10


ITEM = StudyItem("box", "test", "a box", None, type("B", (), {"tan_alpha": 0.25})(), "x", None)


def test_directionality_table_ratios_follow_from_the_medians():
    # 3-D medians 0.5 (pfv_max) and 0.45 (pfv_weak), planar 0.6 (pfv_weak): by hand, ratio_weak = 0.45 / 0.6
    # = 0.75, factor_implied = 0.6 / 0.5 = 1.2, pelicun_over_3d = 1.2 / 1.2 = 1 (pelicun's factor exact)
    fits = pd.DataFrame([_fit("3d", d, m) for d, m in (("pfv_1", 0.52), ("pfv_2", 0.55), ("pfv_max", 0.5),
                                                       ("pfv_nd", 0.58), ("pfv_weak", 0.45))]
                        + [_fit("planar", "pfv_weak", 0.6), _fit("planar", "pfv_max", 0.62)])
    cases = pd.DataFrame([_case("edge", True), _case("corner", True), _case("corner", True), _case("", False)])
    row = directionality_table(fits, cases, _Design(), (ITEM,)).iloc[0]
    assert row["ratio_weak"] == pytest.approx(0.75, rel=1e-15)
    assert row["factor_implied"] == pytest.approx(1.2, rel=1e-15)
    assert row["pelicun_over_3d"] == pytest.approx(1.2 / PELICUN_FACTOR, rel=1e-15)
    assert row["share_corner"] == pytest.approx(2 / 3, rel=1e-15)
    assert row["verdict"] == "differs"  # 25 % off, beyond 10 %
    assert row["b_over_h"] == 0.25


@pytest.mark.parametrize(("ratio", "n3", "np_", "expected"), [
    (1.09, 3, 3, "suffices"), (0.91, 3, 3, "suffices"), (1.11, 3, 3, "differs"), (0.89, 3, 3, "differs"),
    (math.nan, 0, 0, "never overturns"), (math.nan, 3, 0, "no fit"), (math.nan, 2, 2, "no fit"),
])
def test_verdict_bounds(ratio, n3, np_, expected):
    # the tolerance 0.10 is a fraction of the planar median: 1.09 and 0.91 lie inside, 1.11 and 0.89 outside
    assert verdict(ratio, n3, np_, 0.10) == expected


def test_mechanisms_count_edges_and_corners_of_finished_3d_cases_only():
    cases = pd.DataFrame([_case("edge", True, 0.0), _case("corner", True, 45.0), _case("corner", True, 45.0),
                          _case("", False, 45.0), _case("edge", True, 45.0, model="planar"),
                          _case("corner", True, 45.0, status="failed")])
    table = mechanisms(cases).set_index("azimuth")
    assert table.loc["0", "share_corner"] == 0.0 and table.loc["45", "share_corner"] == 1.0
    assert table.loc[ALL, ["n_overturned", "n_edge", "n_corner"]].tolist() == [3, 1, 2]


def test_cost_ratio_is_of_the_medians():
    # the first case of a worker compiles the kernel: the mean would count it, the median does not
    cases = pd.DataFrame({"model": ["3d"] * 3 + ["planar"] * 3, "solver_name": ["rigid3d"] * 3 + ["housner_fast"] * 3,
                          "wall_time_s": [60.0, 0.5, 0.4, 1.0, 0.002, 0.001], "status": ["ok"] * 6})
    table = cost_table(cases).set_index("solver")
    assert table.loc["rigid3d", "ratio_to_planar"] == pytest.approx(0.5 / 0.002, rel=1e-12)
    assert table.loc["housner_fast", "ratio_to_planar"] == 1.0
    # n_cases counts the finished cases, as in every table; the wall times are of all of them
    failed = cost_table(cases.assign(status=["ok", "failed", "ok", "ok", "ok", "ok"])).set_index("solver")
    assert failed.loc["rigid3d", ["n_cases", "n_failed"]].tolist() == [2, 1]
    assert failed.loc["rigid3d", "median_s"] == 0.5
    # a store written before the CPU time was measured: its columns are empty, the wall times' as before
    assert table["cpu_median_s"].isna().all() and table["cpu_ratio_to_planar"].isna().all()


def test_cost_ratio_on_cpu_time_is_of_its_own_medians():
    # wall and CPU times are ranked apart: the CPU ratio is of the CPU medians, whatever the wall times say
    cases = pd.DataFrame({"model": ["3d"] * 3 + ["planar"] * 3, "solver_name": ["rigid3d"] * 3 + ["housner_fast"] * 3,
                          "wall_time_s": [60.0, 0.5, 0.4, 1.0, 0.002, 0.001],
                          "cpu_time_s": [55.0, 0.3, 0.2, 0.9, 0.001, 0.0015], "status": ["ok"] * 6})
    table = cost_table(cases).set_index("solver")
    assert table.loc["rigid3d", "cpu_ratio_to_planar"] == pytest.approx(0.3 / 0.0015, rel=1e-12)
    assert table.loc["rigid3d", "ratio_to_planar"] == pytest.approx(0.5 / 0.002, rel=1e-12)
    assert table.loc["rigid3d", "cpu_total_s"] == pytest.approx(55.5, rel=1e-12)


@pytest.mark.parametrize("weak", ["x", "y"])
@pytest.mark.parametrize("azimuth", [0.0, 22.5, 45.0, 67.5, 90.0])
def test_weak_axis_component_is_plan_motions(weak, azimuth):
    # PlanMotion.components is the frame's definition; the study's projection must give the same a_x (a_y)
    t = np.arange(0.0, 1.0, 0.01)
    r1 = Record(dt=0.01, values=np.sin(7.0 * t), name="one", units="m/s2")
    r2 = Record(dt=0.01, values=np.cos(3.0 * t) * t, name="two", units="m/s2")
    ax, ay = PlanMotion(r1, r2, azimuth).components(t)
    c1, c2 = weak_cosines(weak, azimuth)
    np.testing.assert_allclose(c1 * r1.values + c2 * r2.values, ax if weak == "x" else ay, rtol=0, atol=1e-15)


@pytest.mark.parametrize(("field", "value"), [("azimuths", (0.0, 91.0)), ("azimuths", (0.0, 0.0)),
                                              ("levels", (0.0,)), ("solver3d", "friction"), ("tolerance", 1.5)])
def test_design_refuses_naming_the_field(field, value):
    with pytest.raises(InputError) as err:
        DirectionalityDesign(**{field: value})
    assert err.value.argument == field


def test_quick_study_end_to_end_with_a_planar_stand_in(tmp_path):
    design = DirectionalityDesign(solver3d="housner_fast")
    res = run_design(quick(design), tmp_path / "out", StudyOptions(workers=1, progress=False))
    q = quick(design)
    n = len(q.items) * len(q.floors) * len(q.pairs) * len(q.azimuths) * len(q.levels)
    assert res.summary["n_cases"] == 2 * n and res.summary["n_failed"] == 0
    names = {p.name for p in (tmp_path / "out").iterdir()}
    assert {"report.md", "directionality.csv", "fits.csv", "map.csv", "mechanisms.csv", "cost.csv", "demands.csv",
            "figures"} <= names
    assert sorted(p.name for p in (tmp_path / "out" / "figures").iterdir()) == ["factor.png", "map.png",
                                                                                  "mechanisms.png"]
    for path in res.tables.values():  # each table's units row, each column's unit from its one definition
        header, units = read_units(path)
        assert units == units_of(header)
    fits = read_directionality_table(res.tables["fits"])  # the same planar cases twice: the same fits, bit for bit
    weak = {m: fits[(fits["model"] == m) & (fits["demand"] == "pfv_weak")].reset_index(drop=True) for m in ("3d", "planar")}
    assert weak["3d"]["n_overturned"].sum() > 0
    assert weak["3d"][["item", "azimuth", "n_overturned"]].equals(weak["planar"][["item", "azimuth", "n_overturned"]])
    assert np.array_equal(weak["3d"]["median"], weak["planar"]["median"], equal_nan=True)
    demands = read_directionality_table(res.tables["demands"])  # the vector's peak: between the larger and sqrt 2 of it
    assert ((demands["nd_over_max"] >= 1.0) & (demands["nd_over_max"] <= math.sqrt(2.0) + 1e-12)).all()


@pytest.mark.slow
def test_quick_study_through_the_console_script_with_rigid3d(tmp_path):
    # the real solver (a cold numba cache compiles its kernel first: about a minute per worker)
    from _support import run_opsrock

    proc = run_opsrock(("directionality", "--quick", "--out", "out", "--workers", "2", "--no-progress"), tmp_path,
                       timeout=900)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("opsrock directionality: 48 cases (0 failed)"), proc.stdout
    cost = read_directionality_table(tmp_path / "out" / "cost.csv").set_index("solver")
    assert cost.loc["rigid3d", "n_cases"] == 24 and cost.loc["rigid3d", "ratio_to_planar"] > 1.0
