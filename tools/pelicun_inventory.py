"""pelicun 3.10 on an inventory study's ``pelicun/`` folder as it is (``opsrock contents --inventory ...``):
the damage assessment (and the loss assessment where the folder has a repair-cost model) that its
``config.json`` describes, through pelicun's ``DLCalculationAssessment`` (the engine of pelicun's
``DL_calculation``), and each item's expected number overturned per floor and direction beside the exact
expectation over the records (the study's ``expected.csv``). Runs in a venv that has pelicun 3.10
(``.pelicun-venv``: pelicun pins scipy < 1.16 and pandas < 3); it does not import opsrock.

    python tools/pelicun_inventory.py STUDY/pelicun [--repeat N] [--dl-calculation] [--out FILE.json]

``config.json`` paths are relative to the folder (``CustomDLDataFolder/`` is pelicun's custom model folder:
this one). The demands are the records as recorded, in order and repeated (``CoupledDemands``), so pelicun's
mean over the realisations samples only the capacities: each unit overturns or not on its own draw. Exit
status 1 when pelicun's mean differs from the exact expectation by more than four standard errors of that
sampling (each unit one Bernoulli draw per realisation, variance at most 1/4). ``--dl-calculation`` also
runs pelicun's own ``DL_calculation.run_pelicun`` on the configuration (schema check included) into a
temporary folder.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import tempfile
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
    """Run the assessment; returns (mean overturned per ``(cmp, loc, dir)``, realisations, mean repair cost
    per realisation or None)."""
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
    ds1 = ds.loc[:, ds.columns.get_level_values("ds") == "1"]
    counts = ds1.T.groupby(level=["cmp", "loc", "dir"]).sum().T.mean(axis=0)
    cost = None
    repair = dl.get("Losses", {}).get("Repair")
    if repair:
        agg, _ = asmnt.calculate_loss(loss_map_approach=repair["MapApproach"], occupancy_type=None,
                                      consequence_database=repair["ConsequenceDatabase"],
                                      consequence_database_path=repair["ConsequenceDatabasePath"],
                                      custom_model_dir=str(folder), damage_process_approach="None",
                                      loss_map_path=repair["MapFilePath"], decision_variables=("Cost",))
        cost = float(agg["repair_cost"].mean()) if "repair_cost" in agg else float(agg.iloc[:, 0].mean())
    return counts, size, cost


def compare(folder: Path, counts: pd.Series) -> pd.DataFrame:
    """One row per item, floor and direction: pelicun's mean overturned count beside ``expected.csv``."""
    mapping = pd.read_csv(folder / "mapping.csv", dtype={"floor": str, "direction": str})
    expected = pd.read_csv(folder.parent / "expected.csv", dtype={"floor": str, "direction": str})
    table = expected.merge(mapping[["item", "floor", "direction", "pelicun_id", "location", "status_pfv"]],
                           on=["item", "floor", "direction"], how="left")
    table["pelicun"] = [float(counts.get((cid, str(int(loc)), str(d)), 0.0)) if s == "ok" else math.nan
                        for cid, loc, d, s in zip(table["pelicun_id"], table["location"], table["direction"],
                                                  table["status_pfv"])]
    return table


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("folder", type=Path, help="the study's pelicun/ folder")
    ap.add_argument("--repeat", type=int, help="realisations per record (default: the configuration's)")
    ap.add_argument("--dl-calculation", action="store_true", help="also run pelicun's DL_calculation on the config")
    ap.add_argument("--out", type=Path, help="also write the results (JSON)")
    args = ap.parse_args(argv)
    folder = args.folder.resolve()
    config = resolved(json.loads((folder / "config.json").read_text()), folder)
    counts, size, cost = damage_and_loss(config, folder, args.repeat)
    table = compare(folder, counts)
    print(f"pelicun damage assessment of {folder} ({size} realisations, the records as recorded, repeated): "
          "expected number overturned per item, floor and direction (pelicun / exact over the records)")
    shown = table[["item", "floor", "direction", "quantity", "pelicun", "expected_overturned", "status_pfv"]]
    with pd.option_context("display.width", 160, "display.max_rows", 500, "display.float_format", "{:.3f}".format):
        print(shown.rename(columns={"expected_overturned": "exact", "status_pfv": "component"}).to_string(index=False))
    have = table["status_pfv"].eq("ok")
    tot_p, tot_e = float(table.loc[have, "pelicun"].sum()), float(table.loc[have, "expected_overturned"].sum())
    n_units = float(table.loc[have, "quantity"].sum())
    tol = 4.0 * math.sqrt(max(n_units, 1.0) / 4.0 / size)
    print(f"total over the components: pelicun {tot_p:.3f}, exact {tot_e:.3f} ({n_units:g} units; tolerance {tol:.3f})")
    skipped = table.loc[~have, ["item", "floor", "direction", "status_pfv"]]
    if len(skipped):
        print(f"{len(skipped)} item-floor-directions without a PFV damage model (counted 0 by pelicun; mapping.csv says why)")
    result = {"realisations": size, "pelicun_total": tot_p, "exact_total": tot_e, "tolerance": tol,
              "rows": table.replace({np.nan: None}).to_dict("records")}
    if cost is not None:
        costs = pd.read_csv(folder / "loss_repair.csv", index_col=0)["DS1-Theta_0"]
        exact_cost = sum(costs.get(f"{cid}-Cost", 0.0) * e for cid, e, s in
                         zip(table["pelicun_id"], table["expected_overturned"], table["status_pfv"]) if s == "ok")
        print(f"loss assessment: mean repair cost {cost:.2f} per realisation (exact over the records {exact_cost:.2f})")
        result.update(repair_cost=cost, exact_repair_cost=exact_cost)
    if args.dl_calculation:
        from pelicun.tools.DL_calculation import run_pelicun

        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "config.json"
            config["DL"]["Options"]["LogFile"] = str(Path(tmp) / "pelicun_log.txt")  # not into the working folder
            path.write_text(json.dumps(config))
            run_pelicun(str(path), config["DL"]["Demands"]["DemandFilePath"], str(Path(tmp) / "out"), size, None,
                        str(folder), ["csv"], detailed_results=False, coupled_edp=True)
            made = sorted(p.name for p in (Path(tmp) / "out").iterdir())
        print(f"pelicun DL_calculation ran the configuration: {', '.join(made)}")
    if args.out:
        args.out.write_text(json.dumps(result, indent=1))
    if abs(tot_p - tot_e) > tol:
        print(f"pelicun's mean differs from the exact expectation by more than {tol:.3f}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
