"""The inventory study end to end (:func:`opsrock.inventory.run.run_design`): a tiny inventory (a
bookcase on every floor, a printer on a desk on one) on synthetic floor motions, run twice (the second run
computes nothing), its tables and its pelicun folder checked against each other; the campaigns' blocks and
groups; and ``opsrock contents --inventory/--motions`` through the console script (its refusals, and a
tiny run once the inventory and manifest readers exist)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _hostile import Case, sweep
from _support import run_opsrock
from scipy.stats import norm

from opsrock.errors import InputError
from opsrock.excitations.records import Record
from opsrock.inventory.campaigns import DEMANDS_FILE, group_scenes, groups_of, item_block_spec
from opsrock.inventory.fits import FIT_COLUMNS
from opsrock.inventory.items import FrictionLaw, Inventory, Item, Support
from opsrock.inventory.motions import FloorMotion, MotionSet
from opsrock.inventory.run import StudyOptions, run_design
from opsrock.inventory.study import InventoryDesign
from opsrock.inventory.columns import read_table

FLOORS = ("1", "2")
RECORDS = ("rec0", "rec1", "rec2", "rec3")


def synthetic_motions(floors=FLOORS, directions=("1",), records=RECORDS, seed: int = 0) -> MotionSet:
    """Band-limited noise under a sine-squared envelope, 6 s at dt = 0.01 s (m/s²), stronger up the
    building; a fixed seed, so every run sees the same motions."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, 6.0, 0.01)
    out = []
    for r in records:
        for k, f in enumerate(floors):
            for d in directions:
                a = np.convolve(rng.normal(size=t.size), np.ones(10) / 10, mode="same")
                out.append(FloorMotion(r, f, d, Record(0.01, (6.0 + 3.0 * k) * a * np.sin(np.pi * t / 6.0) ** 2, name=r)))
    return MotionSet(tuple(out), "synthetic")


BOOKCASE = Item("bookcase", "a five-shelf bookcase", 0.9, 0.32, 1.8, quantity=3.0, fema_id="E.20.22.105a",
                repair_cost=400.0)
PRINTER = Item("printer", "a printer on a desk", 0.45, 0.40, 0.55, floors=("1",), support=Support(0.25, 0.05))
INVENTORY = Inventory((BOOKCASE, PRINTER), "test")
LEVELS = (1.2, 2.0, 3.5, 6.0, 9.0)


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    """The study run twice into one folder: ``(first, second)``."""
    out = tmp_path_factory.mktemp("inventory") / "out"
    design = InventoryDesign(INVENTORY, synthetic_motions(), levels=LEVELS, n_boot=10)
    first = run_design(design, out, StudyOptions(workers=1, progress=False))
    second = run_design(design, out, StudyOptions(workers=1, progress=False))
    return first, second


def test_fits_csv_has_the_columns_the_report_reads(study):
    fits, units = read_table(study[0].tables["fits"], dtype={"floor": str, "direction": str})
    assert tuple(fits.columns) == FIT_COLUMNS
    assert units["median"] == "see unit" and units["fema_median"] == "m/s" and units["n_cases"] == "-"
    # bookcase: 2 floors; printer: floor 1 only; one direction; no friction: overturning only; two demands
    assert len(fits) == (2 + 1) * 2
    assert set(fits["outcome"]) == {"overturning"} and set(fits["method"]) == {"ida"}
    assert set(zip(fits["demand"], fits["unit"])) == {("pfv", "m/s"), ("pfa", "g")}
    book = fits[(fits["item"] == "bookcase") & (fits["demand"] == "pfv")]
    # FEMA P-58's E.20.22.105a median is 0.290 m/s (opsrock/published/fema_p58.py); the ratio is the division
    assert np.allclose(book["fema_median"], 0.290)
    assert np.allclose(book["ratio_fema"], book["median"] / 0.290, equal_nan=True)
    assert fits.loc[fits["demand"] == "pfa", "fema_median"].isna().all()
    assert (fits["n_cases"] == len(RECORDS) * len(LEVELS)).all() and (fits["n_records"] == len(RECORDS)).all()
    assert set(fits["pelicun_id"]) == {"opsrock.bookcase.1", "opsrock.bookcase.2", "opsrock.printer.1"}


def test_the_second_run_computes_nothing_and_writes_the_same_fits(study):
    first, second = study
    assert first.n_cases == second.n_cases == 3 * len(RECORDS) * len(LEVELS)
    assert first.n_computed == first.n_cases and second.n_computed == 0
    assert (Path(first.out_dir) / "campaigns" / DEMANDS_FILE).exists()  # the demands are not measured again
    a, b = (read_table(s.tables["fits"])[0] for s in study)
    pd.testing.assert_frame_equal(a, b)


def test_expected_is_the_exact_expectation_over_the_records(study):
    """``quantity x mean_r Phi(ln(pfv_max_r / theta) / beta)`` with the component's fragility, recomputed from
    components.csv and demands.csv with scipy's normal CDF (an independent evaluation of the same closed form:
    agreement to rounding); one direction here, so ``pfv_max`` is its PFV."""
    comps, _ = read_table(study[0].tables["components"], dtype={"floor": str})
    demands, units = read_table(study[0].tables["demands"], dtype={"floor": str, "direction": str})
    expected, _ = read_table(study[0].tables["expected"], dtype={"floor": str})
    assert {"pfa", "pfv", "pfd", "mean_period", "predominant_period"} <= set(demands.columns)
    assert [units[c] for c in ("pfa", "pfv", "pfd", "mean_period")] == ["g", "m/s", "m", "s"]
    assert len(demands) == len(RECORDS) * len(FLOORS)
    assert len(expected) == 3  # the bookcase on two floors, the printer on one: each unit once
    for _, r in expected.iterrows():
        c = comps[(comps["item"] == r["item"]) & (comps["floor"] == r["floor"])].iloc[0]
        pfv = demands.loc[demands["floor"] == r["floor"], "pfv"].to_numpy()
        if c["status"] == "fitted":
            want = r["quantity"] * norm.cdf(np.log(pfv / c["median"]) / c["beta"]).mean()
            assert r["expected_overturned"] == pytest.approx(want, rel=1e-12, abs=1e-15)
        else:
            assert math.isnan(r["expected_overturned"]) or (c["status"] == "never" and r["expected_overturned"] == 0)
        assert r["expected_damaged"] <= r["quantity"]


def test_the_pelicun_folder_is_complete_and_consistent(study):
    folder = Path(study[0].out_dir) / "pelicun"
    mapping, _ = read_table(folder / "mapping.csv", dtype={"floor": str})
    frag = pd.read_csv(folder / "fragility.csv", index_col=0)
    inv = pd.read_csv(folder / "inventory.csv", index_col=0)
    ok = mapping[mapping["exported"]]
    assert set(frag.index) == set(ok["pelicun_id"]) == set(inv.index)
    assert (frag["Demand-Type"] == "Peak Floor Velocity").all() and (frag["Demand-Unit"] == "mps").all()
    assert (frag["Demand-Directional"] == 0).all()
    # pelicun's locations: floor slab n at n + 1 (labels "1", "2" are slabs 1 and 2)
    assert dict(zip(mapping["floor"], mapping["location"])) == {"1": 2, "2": 3}
    assert np.allclose(inv.loc[ok["pelicun_id"], "Theta_0"], ok["quantity"])
    assert np.allclose(frag.loc[ok["pelicun_id"], "LS1-Theta_0"], ok["median_ds1"])
    demands = pd.read_csv(folder / "demands.csv", index_col=0)
    assert list(demands.index) == ["Units", *RECORDS]
    assert set(demands.columns) == {"PFA-1-1", "PFA-2-1", "PFV-1-1", "PFV-2-1"}
    assert set(demands.loc["Units"]) == {"mps2", "mps"}
    config = json.loads((folder / "config.json").read_text())
    dl = config["DL"]
    assert (folder / dl["Demands"]["DemandFilePath"]).exists()
    assert (folder / dl["Asset"]["ComponentAssignmentFile"]).exists()
    for key in ("ComponentDatabasePath",):
        assert (folder / dl["Asset"][key].replace("CustomDLDataFolder/", "")).exists()
    repair = dl["Losses"]["Repair"]  # the bookcase has a repair cost
    loss = pd.read_csv(folder / repair["ConsequenceDatabasePath"].replace("CustomDLDataFolder/", ""), index_col=0)
    assert all(i.startswith("opsrock.bookcase.") for i in loss.index.str.removesuffix("-Cost"))
    assert (loss["DS1-Theta_0"] == 400.0).all()


def test_a_block_spec_takes_width_or_depth_and_fixed_friction():
    a, b = (item_block_spec(BOOKCASE, d, f"bookcase-d{d}") for d in ("1", "2"))
    assert (a.width, b.width, a.height) == (0.9, 0.32, 1.8) and a.friction is None
    rack = Item("rack", "rack", 0.6, 1.0, 2.0, friction=FrictionLaw("fixed", (0.3,)), friction_kinetic=0.25)
    spec = item_block_spec(rack, "1", "rack-d1")
    assert (spec.friction, spec.friction_kinetic) == (0.3, 0.25)
    drawn = Item("crate", "crate", 0.6, 0.6, 0.5, friction=FrictionLaw("uniform", (0.3, 0.5)))
    spec = item_block_spec(drawn, "1", "crate-d1", seed=3)  # the friction drawn per case
    assert spec.friction_distribution is not None and spec.friction_distribution.law == drawn.friction


def test_groups_keep_items_on_their_floors_and_a_support_is_a_one_storey_building():
    motions = synthetic_motions(floors=("1", "2", "3"), directions=("1", "2"), records=("a", "b"))
    design = InventoryDesign(INVENTORY, motions, levels=LEVELS)
    groups = groups_of(INVENTORY.items, motions, "housner_fast", "friction")
    assert sorted(g.name for g in groups) == ["d1-housner_fast", "d1-housner_fast-T0p25z0p05-on-1",
                                              "d2-housner_fast", "d2-housner_fast-T0p25z0p05-on-1"]
    scenes = {s.group.name: s for s in group_scenes(groups, motions, design.intensity)}
    desk = scenes["d1-housner_fast-T0p25z0p05-on-1"].scene.records
    (floor,) = desk.floors
    assert (floor.building.storeys, floor.building.period, floor.building.damping, floor.label) == (1, 0.25, 0.05,
                                                                                                    "support.f1")
    assert [g.name for g in desk.grounds] == ["a.1", "b.1"]
    assert len(scenes["d2-housner_fast"].scene.records.grounds) == 2 * 3
    with pytest.raises(InputError, match="floors"):
        groups_of((Item("x", "x", 0.3, 0.3, 1.0, floors=("9",)),), motions, "housner_fast", "friction")


def test_design_refuses_what_does_not_apply():
    motions = synthetic_motions(records=("a",))
    for kwargs, argument in (({"method": "msa"}, "method"), ({"levels": (1.0, -2.0)}, "levels"),
                             ({"slide_distance": 0.0}, "slide_distance"), ({"solver": "friction"}, "solver"),
                             ({"friction_solver": "housner_fast"}, "friction_solver")):
        with pytest.raises(InputError) as err:
            InventoryDesign(INVENTORY, motions, **kwargs)
        assert err.value.argument == argument
    huge = Inventory((Item("tower", "a 40-m tower", 4.0, 4.0, 40.0),), "test")
    with pytest.raises(InputError, match="tower"):
        InventoryDesign(huge, motions)
    InventoryDesign(huge, motions, accept_implausible=True)


# --- the console script ------------------------------------------------------------------------------
CONTENTS = ("contents", "--out", "out", "--no-progress")
REFUSALS = [
    Case("--method without --inventory", (*CONTENTS, "--method", "cloud"), ("--method", "--inventory")),
    Case("--items with --motions", (*CONTENTS, "--motions", "m.csv", "--items", "E.20.22.102a"), ("--items",)),
    Case("--variants with --inventory", (*CONTENTS, "--inventory", "i.csv", "--variants", "default"), ("--variants",)),
    Case("--period with --motions", (*CONTENTS, "--motions", "m.csv", "--period", "2"), ("--period", "--motions")),
    Case("--levels not numbers", (*CONTENTS, "--inventory", "i.csv", "--levels", "1,x"), ("--levels", "1,x")),
    Case("--demand-levels-pfv empty entry", (*CONTENTS, "--inventory", "i.csv", "--demand-levels-pfv", "0.5,"),
         ("--demand-levels-pfv",)),
]


def test_inventory_route_refusals(tmp_path):
    assert sweep(REFUSALS, tmp_path) == []


def test_inventory_route_case_counts():
    assert len(REFUSALS) == 6 and len({c.name for c in REFUSALS}) == len(REFUSALS)


def _write_inputs(folder: Path) -> tuple[Path, Path]:
    """A two-item inventory CSV (one campaign: both on every floor) and a manifest of two records on two
    floors (CSV motion files in m/s²)."""
    inv = folder / "inventory.csv"
    inv.write_text("id,description,width,depth,height,floor,quantity\n"
                   "bookcase,a bookcase,0.9,0.32,1.8,,2\ncabinet,a cabinet,0.45,0.6,1.3,,1\n")
    rows = ["record,floor,direction,file,units,dt"]
    for m in synthetic_motions(records=("r1", "r2")).motions:
        name = f"{m.record}_{m.floor}.csv"
        np.savetxt(folder / name, m.motion.values, delimiter=",")
        rows.append(f"{m.record},{m.floor},{m.direction},{name},m/s2,{m.motion.dt}")
    man = folder / "motions.csv"
    man.write_text("\n".join(rows) + "\n")
    return inv, man


def test_contents_inventory_motions_through_the_console_script(tmp_path):
    from opsrock.inventory.items import read_inventory

    inv, man = _write_inputs(tmp_path)
    read_inventory(inv)
    proc = run_opsrock(["contents", "--inventory", inv, "--motions", man, "--out", tmp_path / "out", "--quick",
                        "--n-boot", "2", "--workers", "1", "--no-progress"], tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert "opsrock contents: 2 items" in proc.stdout
    for name in ("fits.csv", "expected.csv", "demands.csv", "report.md", "pelicun/config.json", "pelicun/fragility.csv"):
        assert (tmp_path / "out" / name).exists(), name


def test_a_cloud_gives_the_empirical_count_beside_the_expectation():
    """A cloud (one case per motion, as recorded) made by hand: the fit on the records' own PFV, and
    ``empirical_overturned = quantity x`` the share of the records that overturned the item (2 of 4)."""
    from opsrock.inventory.components import expected_table, planar_components
    from opsrock.inventory.fits import fit_table

    motions = synthetic_motions(floors=("1",))
    design = InventoryDesign(Inventory((BOOKCASE,), "test"), motions, method="cloud", n_boot=0)
    pfv = np.array([0.2, 0.45, 0.3, 0.6])  # m/s, made up
    demands = pd.DataFrame({"record": RECORDS, "floor": "1", "direction": "1", "pfa": 9.81 * pfv, "pfv": pfv})
    over = np.array([False, False, True, True])  # at 0.3 and 0.6, not at 0.45: not separated, a finite MLE
    cases = pd.DataFrame({"item": "bookcase", "floor": "1", "direction": "1", "record": RECORDS, "scale": 1.0,
                          "status": "ok", "overturned": over, "slide_max": math.nan})
    fits = fit_table(cases, demands, design, 1)
    assert set(fits["method"]) == {"cloud"} and (fits["n_exceeded"] == 2).all()
    pfv_fit = fits[fits["demand"] == "pfv"].iloc[0]
    assert pfv_fit["ok"] and pfv_fit["n_records"] == 4
    components = planar_components(fits, demands, design)
    expected = expected_table(components, demands, design, fits, cases).iloc[0]
    assert expected["empirical_overturned"] == 3.0 * 2 / 4  # quantity 3, 2 of 4 records
    # one direction: the component's curve is that direction's, to the precision of the quantile fit
    want = 3.0 * norm.cdf(np.log(pfv / pfv_fit["median"]) / pfv_fit["beta"]).mean()
    assert expected["expected_overturned"] == pytest.approx(want, rel=1e-9)
    assert expected["expected_damaged_combined"] == pytest.approx(want, rel=1e-12)
