"""pelicun 3.10 on an inventory study's ``pelicun/`` folder as it is (``opsrock contents --inventory ...``):
the damage assessment (and the loss assessment where the folder has a repair-cost model) that its
``config.json`` describes, through pelicun's ``DLCalculationAssessment`` (the engine of pelicun's
``DL_calculation``), and per item and floor (each unit once) pelicun's mean units damaged, overturned and repair
cost beside the study's exact expectations over the records (``expected.csv``), written to
``FOLDER/results/comparison.csv``. Runs in a venv that has pelicun 3.10 (``.pelicun-venv``: pelicun pins
scipy < 1.16 and pandas < 3; ``make test-pelicun`` makes it); it does not import opsrock.

    python tools/pelicun_inventory.py STUDY/pelicun [--repeat N] [--dl-calculation] [--out FILE.json]

``config.json`` paths are relative to the folder (``CustomDLDataFolder/`` is pelicun's custom model folder:
this one). The demands are the records as recorded, in order and repeated (``CoupledDemands``), so pelicun's
mean over the realisations samples only the capacities: each unit is damaged or not on its own draw. Exit
status 1 when pelicun's mean units damaged or overturned (all components) differs from the exact expectation by
more than four standard errors of that sampling (each unit one Bernoulli draw per realisation, variance at most
1/4). ``--dl-calculation`` also runs pelicun's own ``DL_calculation.run_pelicun`` on the configuration (schema
check included) and keeps its outputs (``DL_summary.csv``, ``DV_repair_*``, ``DMG_*``, its log) in
``FOLDER/results/``. On a folder without a repair-cost model (no ``DL/Losses`` in ``config.json``: no item of the
inventory has a ``repair_cost``, as the FEMA P-58 nine of ``opsrock contents``) it runs the damage assessment only:
DL_calculation's default outputs include the loss's, which it refuses without ``DL/Losses`` ("No loss data
specified"), so the configuration it gets names its outputs (``DL/Outputs``, pelicun's input schema: demand, asset
and damage, CSV) without the loss; one line says that no loss was computed and why.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

CUSTOM = "CustomDLDataFolder"


def resolved(config: dict, folder: Path) -> dict:
    """``config`` with its file paths made absolute (relative to ``folder``; ``CustomDLDataFolder`` kept)."""
    out = json.loads(json.dumps(config))
    dl = out["DL"]
    dl["Demands"]["DemandFilePath"] = str(folder / dl["Demands"]["DemandFilePath"])
    dl["Asset"]["ComponentAssignmentFile"] = str(folder / dl["Asset"]["ComponentAssignmentFile"])
    return out


def damage_and_loss(config: dict, folder: Path, repeat: int | None):
    """Run the assessment; returns (mean units per ``(cmp, loc, dir, ds)``, realisations, mean repair cost per
    ``cmp`` or None, mean total repair cost or None)."""
    from pelicun.assessment import DLCalculationAssessment

    dl = config["DL"]
    size = int(dl["Options"]["Sampling"]["SampleSize"])
    if repeat is not None:
        n_records = len(pd.read_csv(dl["Demands"]["DemandFilePath"], index_col=0)) - 1
        size = n_records * repeat
        dl["Options"]["Sampling"]["SampleSize"] = size
    asmnt = DLCalculationAssessment(config_options={**dl["Options"], "PrintLog": False, "Verbose": False})
    asmnt.calculate_demand(demand_path=Path(dl["Demands"]["DemandFilePath"]), collapse_limits=None,
                           length_unit=config["GeneralInformation"]["units"]["length"], demand_calibration=None,
                           sample_size=size, demand_cloning=None, residual_drift_inference=None,
                           coupled_demands=bool(dl["Demands"].get("CoupledDemands", False)))
    asmnt.calculate_asset(num_stories=int(dl["Asset"]["NumberOfStories"]),
                          component_assignment_file=dl["Asset"]["ComponentAssignmentFile"],
                          collapse_fragility_demand_type=None, component_sample_file=None,
                          add_irreparable_damage_columns=False)
    asmnt.calculate_damage(length_unit="m", component_database=dl["Asset"]["ComponentDatabase"],
                           component_database_path=dl["Asset"]["ComponentDatabasePath"],
                           damage_process_approach=dl["Damage"]["DamageProcess"], custom_model_dir=str(folder))
    ds = asmnt.damage.ds_model.sample
    counts = ds.T.groupby(level=["cmp", "loc", "dir", "ds"]).sum().T.mean(axis=0)
    cost, total = None, None
    repair = dl.get("Losses", {}).get("Repair")
    if repair:
        agg, _ = asmnt.calculate_loss(loss_map_approach=repair["MapApproach"], occupancy_type=None,
                                      consequence_database=repair["ConsequenceDatabase"],
                                      consequence_database_path=repair["ConsequenceDatabasePath"],
                                      custom_model_dir=str(folder), damage_process_approach="None",
                                      loss_map_path=repair["MapFilePath"], decision_variables=("Cost",))
        total = float(agg["repair_cost"].mean()) if "repair_cost" in agg else float(agg.iloc[:, 0].mean())
        sample = asmnt.loss.ds_model.sample
        cost = sample.T.groupby(level="dmg").sum().T.mean(axis=0)
    return counts, size, cost, total


def study_table(path: Path) -> pd.DataFrame:
    """A table of the study (``expected.csv``, ``mapping.csv``): its ``Units`` row (the second line, pelicun's
    tabular form) skipped; a folder written before the row has none, and these two tables' units did not change."""
    with open(path, encoding="utf-8") as fh:
        fh.readline()
        units = fh.readline().startswith("Units,")
    return pd.read_csv(path, dtype={"floor": str}, skiprows=[1] if units else None)


def compare(folder: Path, counts: pd.Series, cost: pd.Series | None) -> pd.DataFrame:
    """One row per item and floor: pelicun's mean units damaged (any damage state), overturned (the
    overturned state, ``mapping.csv``) and repair cost beside the study's exact expectations (``expected.csv``)."""
    mapping = study_table(folder / "mapping.csv")
    expected = study_table(folder.parent / "expected.csv")
    table = expected.merge(mapping[["pelicun_id", "location", "exported", *[c for c in mapping if c.startswith("ds")
                                                                            and c[2:].isdigit()]]],
                           on="pelicun_id", how="left")
    by_cmp = counts.groupby(level=["cmp", "ds"]).sum()
    damaged, overturned, costs = [], [], []
    for r in table.itertuples():
        if not r.exported:
            damaged.append(math.nan), overturned.append(math.nan), costs.append(math.nan)
            continue
        states = [getattr(r, c) for c in table.columns if c.startswith("ds") and c[2:].isdigit()]
        mine = {k: float(by_cmp.get((r.pelicun_id, str(k)), 0.0)) for k in range(1, len(states) + 1)}
        damaged.append(sum(mine.values()))
        overturned.append(sum(v for k, v in mine.items() if states[k - 1] == "overturned"))
        costs.append(float(cost.get(r.pelicun_id, math.nan)) if cost is not None else math.nan)
    return table.assign(pelicun_damaged=damaged, pelicun_overturned=overturned, pelicun_cost=costs)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folder", type=Path, help="the study's pelicun/ folder")
    ap.add_argument("--repeat", type=int, help="realisations per record (default: the configuration's)")
    ap.add_argument("--dl-calculation", action="store_true",
                    help="also run pelicun's DL_calculation on the config, its outputs into FOLDER/results/")
    ap.add_argument("--out", type=Path, help="also write the results (JSON)")
    args = ap.parse_args(argv)
    folder = args.folder.resolve()
    config = resolved(json.loads((folder / "config.json").read_text()), folder)
    counts, size, cost, total = damage_and_loss(config, folder, args.repeat)
    table = compare(folder, counts, cost)
    print(f"pelicun damage assessment of {folder} ({size} realisations, the records as recorded, repeated): per item "
          "and floor, each unit once, the expected units damaged, overturned and repair cost (pelicun / exact over "
          "the records)")
    shown = table[["item", "floor", "location", "quantity", "pelicun_damaged", "expected_damaged", "pelicun_overturned",
                   "expected_overturned", "pelicun_cost", "expected_cost"]]
    with pd.option_context("display.width", 200, "display.max_rows", 500, "display.float_format", "{:.3f}".format):
        print(shown.to_string(index=False))
    have = table["exported"].fillna(False).astype(bool)
    n_units = float(table.loc[have, "quantity"].sum())
    # each unit one Bernoulli draw per realisation (variance at most 1/4), the units independent
    tol = 4.0 * math.sqrt(max(n_units, 1.0) / 4.0 / size)
    result = {"realisations": size, "tolerance": tol, "rows": table.replace({np.nan: None}).to_dict("records")}
    bad = []
    for what in ("damaged", "overturned"):
        p, e = float(table.loc[have, f"pelicun_{what}"].sum()), float(table.loc[have, f"expected_{what}"].sum())
        print(f"units {what}, all components: pelicun {p:.3f}, exact {e:.3f} ({n_units:g} units; tolerance {tol:.3f})")
        result[f"pelicun_{what}"], result[f"exact_{what}"] = p, e
        if abs(p - e) > tol:
            bad.append(what)
    skipped = table.loc[~have, ["item", "floor", "status"]]
    if len(skipped):
        print(f"{len(skipped)} item-floors without a damage model (counted 0 by pelicun; mapping.csv says why)")
    if total is not None:
        exact_cost = float(table.loc[have, "expected_cost"].sum())
        print(f"loss assessment: mean repair cost {total:.2f} per realisation (exact over the records {exact_cost:.2f})")
        result.update(repair_cost=total, exact_repair_cost=exact_cost)
    (folder / "results").mkdir(exist_ok=True)
    table.to_csv(folder / "results" / "comparison.csv", index=False)
    if args.dl_calculation:
        made = dl_calculation(config, folder, size)
        print(f"pelicun DL_calculation ran the configuration; its outputs in {folder / 'results'}: {', '.join(made)}")
    why = no_loss_reason(config)
    if why is not None:
        print(f"no loss computed: {why}" + ("; DL_calculation ran the damage assessment only" if args.dl_calculation
                                             else ""))
    if args.out:
        args.out.write_text(json.dumps(result, indent=1))
    if bad:
        print(f"pelicun's mean differs from the exact expectation by more than {tol:.3f} ({', '.join(bad)})",
              file=sys.stderr)
        return 1
    return 0


# DL_calculation's outputs without the loss's (pelicun 3.10's input schema, DL/Outputs): what it writes of a
# configuration without DL/Losses, whose default outputs (the loss's included) it refuses
DAMAGE_OUTPUTS = {"Demand": {"Sample": True, "Statistics": True}, "Asset": {"Sample": True, "Statistics": True},
                  "Damage": {"Sample": True, "Statistics": True, "GroupedSample": True, "GroupedStatistics": True},
                  "Format": {"CSV": True, "JSON": False}}


def no_loss_reason(config: dict) -> str | None:
    """Why the folder's assessment computes no loss (None when it has a repair-cost model, ``DL/Losses/Repair``):
    the writer adds one only when an item of the inventory has a ``repair_cost``."""
    if config["DL"].get("Losses", {}).get("Repair"):
        return None
    return "config.json has no repair-cost model (DL/Losses), as no item of the inventory has a repair_cost"


def dl_configuration(config: dict, out: Path) -> dict:
    """The configuration DL_calculation runs, its log into ``out``; without a repair-cost model
    (:func:`no_loss_reason`) its outputs named, the damage assessment's only (:data:`DAMAGE_OUTPUTS`)."""
    run = json.loads(json.dumps(config))
    run["DL"]["Options"]["LogFile"] = str(out / "pelicun_log.txt")
    if no_loss_reason(run) is not None:
        run["DL"]["Outputs"] = json.loads(json.dumps(DAMAGE_OUTPUTS))
    return run


def dl_calculation(config: dict, folder: Path, size: int) -> list[str]:
    """pelicun's own ``DL_calculation.run_pelicun`` on the configuration (schema check included), its outputs
    (``DL_summary.csv``, ``DV_repair_*`` where the folder prices damage, ``DMG_*``, its log) kept in
    ``folder/results/``; the file names."""
    from pelicun.tools.DL_calculation import run_pelicun

    out = folder / "results"
    out.mkdir(exist_ok=True)
    path = out / "config.json"
    run = dl_configuration(config, out)
    path.write_text(json.dumps(run, indent=2))
    run_pelicun(str(path), run["DL"]["Demands"]["DemandFilePath"], str(out), size, None, str(folder), ["csv"],
                detailed_results=True, coupled_edp=True)
    return sorted(p.name for p in out.iterdir())

if __name__ == "__main__":
    sys.exit(main())
