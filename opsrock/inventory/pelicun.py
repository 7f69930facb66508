"""The inventory study's folder for pelicun (``<out>/pelicun/``): a damage (and loss) assessment that pelicun 3.10
runs as it is (``tools/pelicun_inventory.py`` runs it, in pelicun's own venv).

Files:

* ``fragility.csv``: one damage model per item, floor (and direction, when the motions have two): the fitted
  overturning fragility in PFV (m/s; FEMA P-58's demand for furniture), one limit state, lognormal
  (:func:`opsrock.fragility.pelicun_export.write_pelicun_csv`). A pelicun component has one fragility wherever
  it stands and opsrock's differ by floor, so the IDs carry it: ``opsrock.<item>.<floor>[.d<direction>]``
  (:func:`component_id`). ``fragility_pfa.csv``: the same components in PFA (m/s²), for an assessment in PFA.
* ``mapping.csv``: each component's item, FEMA ID, floor, direction, pelicun location, quantity, and per
  demand (``pfv`` m/s, ``pfa`` m/s²) its median, beta and status (``ok``, or why it has no damage model in
  that demand: an item that never overturned within the study has none and counts as never overturning;
  a fit without a finite optimum, e.g. outcomes perfectly separated by the demand, has none either).
* ``inventory.csv``: the component inventory (of the components with a PFV damage model) in pelicun's own format (``ID, Units, Location, Direction,
  Theta_0, Blocks, Comment``): each item's ``quantity`` at its floor's location in each direction, as
  ``Blocks`` separate units (each overturns on its own capacity). In each direction the item is counted
  once: the planar model rocks it about one axis per direction, so the two directions' counts are two views
  of the same units, not two sets of them.
* ``demands.csv``: the demand sample, as recorded: one realisation per record (``PFA-<n>-<dir>`` in m/s²,
  ``PFV-<n>-<dir>`` in m/s, a ``Units`` row first), ``n`` the floor slab (0 the ground). Records that lack
  a floor or direction are left out (pelicun needs every demand of a realisation).
* ``loss_repair.csv`` and ``loss_map.csv`` (only when the inventory gives ``repair_cost``): pelicun's
  consequence model, the repair cost of one overturned unit (deterministic, ``DS1-Theta_0``; the inventory's
  currency, labelled ``USD`` for pelicun, which converts nothing), and the map from each component to it.
* ``config.json``: the assessment in the form of pelicun's ``DL_calculation`` configuration; file paths are
  relative to this folder (``CustomDLDataFolder/`` where pelicun substitutes its custom model folder).

Locations (pelicun's convention, as :mod:`opsrock.contents.pelicun`): floor slab ``n`` is location
``n + 1`` (the ground floor 1); pelicun's default ``DemandOffset`` of -1 for PFA and PFV gives a component at
location ``n + 1`` the demand ``PFV-n``: the floor it stands on. A floor labelled with a whole number ``n``
is slab ``n``, ``ground`` is 0, ``roof`` one above the highest numbered floor; when any other label appears,
the floors are numbered 1, 2, ... in the motions' order (:func:`floor_numbers`). Each component is
directional (``Demand-Directional`` 1): it takes the demand of its own direction, no non-directional
multiplier.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import pandas as pd

from opsrock.constants import G

#: Realisations per record of the configured assessment (pelicun samples the capacities; the demands
#: are the records in order, repeated: ``CoupledDemands``).
REPEAT: int = 100

#: pelicun's currency label of the repair costs (no conversion is made).
CURRENCY: str = "USD"


def floor_numbers(floors: tuple[str, ...]) -> dict[str, int]:
    """The floor slab number (0 the ground) of each floor label; see the module docstring."""
    def number(label: str) -> int | None:
        return 0 if label == "ground" else int(label) if label.isascii() and label.isdigit() else None

    known = {f: number(f) for f in floors if f != "roof"}
    if all(n is not None for n in known.values()):
        out = dict(known)
        if "roof" in floors:
            out["roof"] = max(known.values(), default=0) + 1
        return {f: out[f] for f in floors}
    return {f: k + 1 for k, f in enumerate(floors)}


def component_id(item: str, floor: str, direction: str, by_direction: bool) -> str:
    """``opsrock.<item>.<floor>[.d<direction>]`` (``floor`` made safe for an ID)."""
    from opsrock.excitations.records import safe_name

    return f"opsrock.{item}.{safe_name(floor)}" + (f".d{direction}" if by_direction else "")


def with_pelicun_ids(fits: pd.DataFrame, directions: tuple[str, ...]) -> pd.DataFrame:
    """``fits`` with ``pelicun_id`` set on the overturning rows (the component of the item, floor, direction)."""
    out = fits.copy()
    over = out["outcome"] == "overturning"
    out.loc[over, "pelicun_id"] = [component_id(i, f, d, len(directions) > 1)
                                   for i, f, d in zip(out.loc[over, "item"], out.loc[over, "floor"],
                                                      out.loc[over, "direction"])]
    return out


def write_pelicun_folder(fits: pd.DataFrame, demands: pd.DataFrame, study: Any, folder: Path) -> dict[str, Path]:
    """Write the files of the module docstring into ``folder``; returns their paths by name.

    Parameters
    ----------
    fits : DataFrame
        :func:`opsrock.inventory.fits.fit_table` with ``pelicun_id`` (:func:`with_pelicun_ids`).
    demands : DataFrame
        :func:`opsrock.inventory.campaigns.floor_demands` (pfa m/s², pfv m/s).
    study : InventoryDesign
        Its inventory (quantities, repair costs), motions (floors) and seed.
    folder : Path
        The ``pelicun/`` folder (created).
    """
    folder.mkdir(parents=True, exist_ok=True)
    numbers = floor_numbers(study.motions.floors)
    mapping = _mapping(fits, study, numbers)
    paths = _fragilities(mapping, folder)
    paths["mapping"] = _csv(mapping, folder / "mapping.csv")
    paths["inventory"] = _csv(_inventory(mapping), folder / "inventory.csv", index=True)
    sample, n_records = _demand_sample(demands, numbers)
    paths["demands"] = _csv(sample, folder / "demands.csv", index=True)
    costs = {it.id: it.repair_cost for it in study.inventory.items if it.repair_cost is not None}
    ids = mapping[mapping["status_pfv"] == "ok"]
    if costs and not ids.empty:
        paths.update(_loss_files(ids, costs, folder))
    config = _config(numbers, n_records, study.seed, loss="loss_repair" in paths)
    paths["config"] = folder / "config.json"
    _write_text(paths["config"], json.dumps(config, indent=2) + "\n")
    return paths


def _mapping(fits: pd.DataFrame, study: Any, numbers: dict[str, int]) -> pd.DataFrame:
    items = {it.id: it for it in study.inventory.items}
    rows = []
    over = fits[fits["outcome"] == "overturning"]
    for cid, g in over.groupby("pelicun_id", sort=False):
        pfv, pfa = (g[g["demand"] == d].iloc[0] for d in ("pfv", "pfa"))
        item = items[pfv["item"]]
        row = {"pelicun_id": cid, "item": item.id, "fema_id": item.fema_id, "floor": pfv["floor"],
               "direction": pfv["direction"], "floor_number": numbers[pfv["floor"]],
               "location": numbers[pfv["floor"]] + 1, "quantity": item.quantity}
        for demand, r, factor in (("pfv", pfv, 1.0), ("pfa", pfa, G)):  # PFA fitted in g, exported in m/s2
            ok = bool(r["ok"])
            row.update({f"median_{demand}": r["median"] * factor if ok else math.nan,
                        f"beta_{demand}": r["beta"] if ok else math.nan,
                        f"status_{demand}": "ok" if ok else r["message"]})
        rows.append(row)
    return pd.DataFrame(rows)


def _fragilities(mapping: pd.DataFrame, folder: Path) -> dict[str, Path]:
    from opsrock.fragility.pelicun_export import ComponentFragility, write_pelicun_csv

    out = {}
    for key, demand in (("fragility", "pfv"), ("fragility_pfa", "pfa")):
        ok = mapping[mapping[f"status_{demand}"] == "ok"]
        comps = [ComponentFragility(r["pelicun_id"], demand, float(r[f"median_{demand}"]), float(r[f"beta_{demand}"]))
                 for _, r in ok.iterrows()]
        out[key] = write_pelicun_csv(comps, folder / f"{key}.csv")
    return out


def _inventory(mapping: pd.DataFrame) -> pd.DataFrame:
    ok = mapping[mapping["status_pfv"] == "ok"]
    return pd.DataFrame({"Units": "ea", "Location": ok["location"].astype(int).to_numpy(),
                         "Direction": ok["direction"].to_numpy(), "Theta_0": ok["quantity"].astype(float).to_numpy(),
                         "Blocks": [max(1, int(round(q))) for q in ok["quantity"]],
                         "Comment": [f"{i} on floor {f}" for i, f in zip(ok["item"], ok["floor"])]},
                        index=pd.Index(ok["pelicun_id"].to_numpy(), name="ID"))


def _demand_sample(demands: pd.DataFrame, numbers: dict[str, int]) -> tuple[pd.DataFrame, int]:
    """The records as realisations, PFA (m/s²) and PFV (m/s) per floor slab and direction, a Units row first."""
    d = demands.assign(n=demands["floor"].map(numbers))
    cols = {}
    for kind, column, unit in (("PFA", "pfa", "mps2"), ("PFV", "pfv", "mps")):
        wide = d.pivot_table(index="record", columns=["n", "direction"], values=column, aggfunc="first", sort=False)
        for (n, direction) in sorted(wide.columns):
            cols[f"{kind}-{n}-{direction}"] = (unit, wide[(n, direction)])
    table = pd.DataFrame({k: v for k, (_, v) in cols.items()})
    table = table.loc[[r for r in dict.fromkeys(demands["record"]) if r in table.index]].dropna()
    units = pd.DataFrame([[u for u, _ in cols.values()]], columns=list(cols), index=["Units"])
    out = pd.concat([units, table.astype(object)])
    out.index.name = "record"
    return out, len(table)


def _loss_files(ids: pd.DataFrame, costs: dict[str, float], folder: Path) -> dict[str, Path]:
    have = ids[ids["item"].isin(costs)]
    conseq = pd.DataFrame({"Incomplete": 0, "Quantity-Unit": "1 EA", "DV-Unit": CURRENCY, "DS1-Family": "",
                           "DS1-Theta_0": [float(costs[i]) for i in have["item"]], "DS1-Theta_1": "",
                           "DS1-LongLeadTime": ""}, index=pd.Index([f"{c}-Cost" for c in have["pelicun_id"]], name="ID"))
    lmap = pd.DataFrame({"Repair": have["pelicun_id"].to_numpy()}, index=pd.Index(have["pelicun_id"].to_numpy(), name="ID"))
    return {"loss_repair": _csv(conseq, folder / "loss_repair.csv", index=True),
            "loss_map": _csv(lmap, folder / "loss_map.csv", index=True)}


def _config(numbers: dict[str, int], n_records: int, seed: int, loss: bool) -> dict[str, Any]:
    storeys = max(1, max(numbers.values()))
    size = max(1, n_records) * REPEAT
    dl: dict[str, Any] = {
        "Demands": {"DemandFilePath": "demands.csv", "SampleSize": str(size), "CoupledDemands": True},
        "Asset": {"ComponentAssignmentFile": "inventory.csv", "ComponentDatabase": "None",
                  "ComponentDatabasePath": "CustomDLDataFolder/fragility.csv", "NumberOfStories": str(storeys)},
        "Damage": {"DamageProcess": "None"},
        "Options": {"Seed": seed, "NonDirectionalMultipliers": {"ALL": 1.0},
                    "Sampling": {"SampleSize": size, "PreserveRawOrder": True}},
    }
    if loss:
        dl["Losses"] = {"Repair": {"ConsequenceDatabase": "None",
                                   "ConsequenceDatabasePath": "CustomDLDataFolder/loss_repair.csv",
                                   "MapApproach": "User Defined", "MapFilePath": "CustomDLDataFolder/loss_map.csv",
                                   "DecisionVariables": {"Cost": True, "Time": False, "Carbon": False,
                                                         "Energy": False}}}
    return {"GeneralInformation": {"NumberOfStories": storeys, "units": {"length": "m"}}, "DL": dl}


def _csv(df: pd.DataFrame, path: Path, index: bool = False) -> Path:
    from opsrock._files import atomic_write

    atomic_write(path, lambda fh: df.to_csv(fh, index=index), durable=False)
    return path


def _write_text(path: Path, text: str) -> None:
    from opsrock._files import atomic_write

    atomic_write(path, lambda fh: fh.write(text), durable=False)


__all__ = ["CURRENCY", "REPEAT", "component_id", "floor_numbers", "with_pelicun_ids", "write_pelicun_folder"]
