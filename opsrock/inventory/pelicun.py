"""The inventory study's folder for pelicun (``<out>/pelicun/``): a damage and loss assessment that pelicun 3.10
runs as it is (``tools/pelicun_inventory.py``, in pelicun's own venv), **each physical unit once**.

Files:

* ``fragility.csv``: one non-directional component per item and floor, ``opsrock.<item>.<floor>``
  (:func:`opsrock.inventory.components.component_id`), in PFV (m/s), ``Demand-Directional`` 0: its damage
  states in sequence, ``DS1`` displaced (slid beyond the item's ``slide_distance`` or overturned) and ``DS2``
  overturned where friction is modelled, else ``DS1`` overturned (:mod:`opsrock.inventory.components`, which
  says why sequential); each limit state lognormal, fitted in ``pfv_max``, or where the demand separated the
  outcomes perfectly a step at the middle of the gap: a deterministic capacity (a blank ``Family``).
* ``inventory.csv``: pelicun's component assignment (``ID, Units, Location, Direction, Theta_0, Blocks,
  Comment``): each item's ``quantity`` once at its floor's location, direction 0 (non-directional), as
  ``Blocks`` separate units (each damaged on its own capacity draw). The units pelicun instantiates are the
  inventory's.
* ``demands.csv``: the demand sample, as recorded: one realisation per record (``PFA-<loc-1>-<dir>`` in m/s²,
  ``PFV-<loc-1>-<dir>`` in m/s, a ``Units`` row first in pelicun's spellings, ``mps2`` and ``mps``; pelicun's ``Demand-Offset`` default -1 for floor demands
  gives a component at location ``L`` the demand ``PFV-(L-1)``: the floor it stands on). A non-directional
  component takes the larger direction times ``NonDirectionalMultipliers``, set to 1.0 in ``config.json``
  (:data:`opsrock.inventory.components.NONDIRECTIONAL_MULTIPLIER`): ``pfv_max``, the demand of the fits.
  Records that lack a floor or direction are left out (pelicun needs every demand of a realisation).
* ``loss_repair.csv`` and ``loss_map.csv`` (items with a ``repair_cost``): pelicun's consequence model per
  component: ``DS1`` of a two-state component the item's ``slide_cost`` (0 when not given), the overturned state
  its ``repair_cost`` (deterministic, the inventory's currency labelled ``USD`` for pelicun, which converts
  nothing).
* ``mapping.csv`` (a ``Units`` row after its header, :mod:`opsrock.inventory.columns`): per component its item, FEMA ID, floor label, pelicun location, quantity, and per limit state
  its damage state, median (m/s), beta, status and source (``planar: ... combined`` or ``3-D``); components
  without a damage model (never damaged within the study, or a failed fit) are listed with the reason and
  left out of ``inventory.csv``.
* ``per_direction/fragility_pfv.csv`` and ``per_direction/fragility_pfa.csv``: **per-direction** fragilities
  (``opsrock.<item>.<floor>.d<direction>.<state>``, directional, one limit state each: overturning, and sliding
  beyond the distance where friction is modelled), for those who assemble their own model; assigning both
  directions of an item to its units counts each unit twice, so ``inventory.csv`` never uses them.
* ``config.json``: the assessment in the form of pelicun's ``DL_calculation`` configuration; file paths are
  relative to this folder (``CustomDLDataFolder/`` where pelicun substitutes its custom model folder).

Units: every file of the folder states its own in pelicun's form (a ``Units`` row, ``Demand-Unit``,
``DV-Unit``, a ``Units`` column). PFA is the one quantity the folder gives in another unit than the study's tables
(g there): pelicun's files take it in SI (``mps2``) so that no convention of ``g`` enters (pelicun's is 9.80665
m/s², opsrock's :data:`opsrock.constants.G` 9.81 m/s²).

Locations (:func:`floor_locations`): the manifest's ``location`` column where given (pelicun's location number
of each floor label: 1 the ground floor); otherwise ``ground`` (or ``0``) is location 1 and a whole number ``n``
the slab ``n`` above the ground, location ``n + 1`` (``roof`` above the highest; without a roof label the highest
slab is the roof of an ``n``-storey building, unless the motions come from a building model that gives its storeys,
as the shipped shear building does: floors ``ground,4`` of an 8-storey building are locations 1 and 5 of 8 storeys),
or, for other labels, the
lowest floor in building order is taken as the ground (location 1) and the others follow; which label was taken
as the ground is said on stderr and in the report. ``NumberOfStories`` is the highest location, less one where
that floor is the roof (pelicun's roof is ``NumberOfStories + 1``).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from opsrock.constants import G
from opsrock.inventory.columns import write_table
from opsrock.inventory.components import NONDIRECTIONAL_MULTIPLIER, STATES

#: Realisations per record of the configured assessment (pelicun samples the capacities; the demands
#: are the records in order, repeated: ``CoupledDemands``).
REPEAT: int = 100

#: pelicun's currency label of the repair costs (no conversion is made).
CURRENCY: str = "USD"

#: pelicun's inventory direction of a non-directional component.
NONDIRECTIONAL: str = "0"


@dataclass(frozen=True)
class FloorLocations:
    """Each floor label's pelicun location and the storeys pelicun is told.

    Parameters
    ----------
    locations : dict of str to int
        Floor label -> pelicun location (1 the ground floor).
    storeys : int
        ``NumberOfStories``.
    given : bool
        True when the manifest's ``location`` column gave them.
    ground : str
        What was taken as the ground (location 1), in a sentence (empty when given).
    """

    locations: dict[str, int]
    storeys: int
    given: bool
    ground: str

    def lines(self) -> list[str]:
        """``label -> location`` lines and the storeys, for the report."""
        return [*(f"`{f}` -> location {n}" for f, n in self.locations.items()),
                f"NumberOfStories: {self.storeys}"]


def _is_roof(label: str) -> bool:
    low = label.lower()
    return low == "roof" or low.endswith(".roof")


def floor_locations(motions: Any) -> FloorLocations:
    """The pelicun location of each floor of ``motions`` (:class:`~opsrock.inventory.motions.MotionSet`: its
    ``locations`` where the manifest gave them) and ``NumberOfStories``; see the module docstring."""
    from opsrock.inventory.summary import floor_order

    floors = tuple(motions.floors)
    given = dict(getattr(motions, "locations", ()) or ())
    if given:
        top = max(given, key=given.__getitem__)
        storeys = max(1, given[top] - 1 if _is_roof(top) else given[top])
        return FloorLocations({f: given[f] for f in floors}, storeys, True, "")
    number = {f: 0 if f.lower() in ("ground", "0") else int(f) if f.isascii() and f.isdigit() else None
              for f in floors if not _is_roof(f)}
    if all(n is not None for n in number.values()):
        top = max(number.values(), default=0)
        slabs = {f: (top + 1 if _is_roof(f) else number[f]) for f in floors}
        ground = next((f for f, n in slabs.items() if n == 0), None)
        said = (f"floor {ground!r} is the ground (location 1)" if ground is not None else
                f"no floor label is the ground: a whole number n is the n-th slab above it (location n + 1), "
                f"so {min(slabs, key=slabs.__getitem__)!r} is location {min(slabs.values()) + 1}")
        storeys = getattr(motions, "storeys", None) or max(1, max(slabs.values()))
        return FloorLocations({f: n + 1 for f, n in slabs.items()}, storeys, False, said)
    ordered = floor_order(floors)
    locations = {f: k + 1 for k, f in enumerate(ordered)}
    storeys = max(1, len(ordered) - 1 if _is_roof(ordered[-1]) else len(ordered))
    how = "in building order" if ordered != list(floors) or _ordered(floors) else "in the manifest's order"
    return FloorLocations({f: locations[f] for f in floors}, storeys, False,
                          f"floor {ordered[0]!r} is taken as the ground (location 1), the others above it {how}")


def _ordered(floors: tuple[str, ...]) -> bool:
    from opsrock.inventory.summary import floors_are_numbered

    return floors_are_numbered(floors)


def write_pelicun_folder(components: pd.DataFrame, fits: pd.DataFrame, demands: pd.DataFrame, study: Any,
                         folder: Path) -> dict[str, Path]:
    """Write the files of the module docstring into ``folder``; returns their paths by name.

    Parameters
    ----------
    components : DataFrame
        :func:`opsrock.inventory.components.planar_components` or ``three_d_components`` (m/s).
    fits : DataFrame
        :func:`opsrock.inventory.fits.fit_table`: the per-direction fragilities (PFV m/s, PFA g).
    demands : DataFrame
        :func:`opsrock.inventory.campaigns.floor_demands` (pfa m/s², pfv m/s).
    study : InventoryDesign
        Its inventory (quantities, costs), motions (floors, locations) and seed.
    folder : Path
        The ``pelicun/`` folder (created).
    """
    folder.mkdir(parents=True, exist_ok=True)
    floors = floor_locations(study.motions)
    mapping = _mapping(components, study, floors.locations)
    paths = {"fragility": _fragility(components, folder / "fragility.csv")}
    paths["mapping"] = write_table(mapping, folder / "mapping.csv")
    paths["inventory"] = _csv(_inventory(mapping), folder / "inventory.csv", index=True)
    sample, n_records = _demand_sample(demands, floors.locations)
    paths["demands"] = _csv(sample, folder / "demands.csv", index=True)
    paths.update(_per_direction(fits, folder / "per_direction"))
    items = {it.id: it for it in study.inventory.items}
    priced = mapping[mapping["exported"] & mapping["item"].map(lambda i: items[i].repair_cost is not None)]
    if not priced.empty:
        paths.update(_loss_files(priced, items, folder))
    config = _config(floors.storeys, n_records, study.seed, loss="loss_repair" in paths)
    paths["config"] = folder / "config.json"
    _write_text(paths["config"], json.dumps(config, indent=2) + "\n")
    return paths


def _mapping(components: pd.DataFrame, study: Any, locations: dict[str, int]) -> pd.DataFrame:
    items = {it.id: it for it in study.inventory.items}
    rows = []
    for (item_id, floor), c in components.groupby(["item", "floor"], sort=False):
        item, fitted = items[item_id], c[c["status"] == "fitted"]
        row = {"pelicun_id": c["pelicun_id"].iloc[0], "item": item_id, "fema_id": item.fema_id, "floor": floor,
               "location": locations[str(floor)], "quantity": item.quantity, "exported": len(fitted) > 0,
               "source": c["source"].iloc[0],
               "status": "ok" if len(fitted) and not (c["status"] == "no fit").any() else "; ".join(
                   f"{r.limit_state}: {r.message}" for r in c.itertuples() if r.status != "fitted")}
        if (c["status"] == "no fit").any():
            row["exported"] = False
        for k, r in enumerate(fitted.itertuples(), start=1):
            row.update({f"ds{k}": STATES[r.limit_state][1], f"median_ds{k}": r.median, f"beta_ds{k}": r.beta})
        rows.append(row)
    return pd.DataFrame(rows)


def _fragility(components: pd.DataFrame, path: Path) -> Path:
    """pelicun's damage-model CSV: one non-directional PFV component per item and floor, its limit states in
    sequence."""
    ok = components[components["status"] == "fitted"]
    failed = set(components.loc[components["status"] == "no fit", "pelicun_id"])
    n_ls = max([int(ls[2:]) for ls in ok["ls"]], default=1)
    rows = []
    for cid, c in ok.groupby("pelicun_id", sort=False):
        if cid in failed:
            continue
        row = {"ID": cid, "Incomplete": 0, "Demand-Type": "Peak Floor Velocity", "Demand-Unit": "mps",
               "Demand-Offset": 0, "Demand-Directional": 0}
        for r in c.itertuples():  # a step (beta 0, separated outcomes): a deterministic capacity, pelicun's blank Family
            step = float(r.beta) == 0.0
            row.update({f"{r.ls}-Family": "" if step else "lognormal", f"{r.ls}-Theta_0": repr(float(r.median)),
                        f"{r.ls}-Theta_1": "" if step else repr(float(r.beta))})
        rows.append(row)
    columns = ["ID", "Incomplete", "Demand-Type", "Demand-Unit", "Demand-Offset", "Demand-Directional",
               *(f"LS{k}-{p}" for k in range(1, n_ls + 1) for p in ("Family", "Theta_0", "Theta_1"))]
    return _csv(pd.DataFrame(rows, columns=columns), path)


def _per_direction(fits: pd.DataFrame, folder: Path) -> dict[str, Path]:
    """The per-direction fragilities (directional, one limit state each), marked as such in their IDs."""
    from opsrock.fragility.pelicun_export import ComponentFragility, write_pelicun_csv

    out = {}
    for demand, factor in (("pfv", 1.0), ("pfa", G)):  # PFA fitted in g, exported in m/s2 (module docstring)
        ok = fits[(fits["demand"] == demand) & fits["ok"].astype(bool) & fits["outcome"].isin(["overturning", "sliding"])]
        comps = [ComponentFragility(f"{component_id(r.item, r.floor)}.d{r.direction}.{r.outcome}", demand,
                                    float(r.median) * factor, float(r.beta)) for r in ok.itertuples()]
        out[f"per_direction_{demand}"] = write_pelicun_csv(comps, folder / f"fragility_{demand}.csv")
    return out


def component_id(item: str, floor: str) -> str:
    """The component of ``item`` on ``floor`` (:func:`opsrock.inventory.components.component_id`)."""
    from opsrock.inventory.components import component_id as cid

    return cid(item, str(floor))


def _inventory(mapping: pd.DataFrame) -> pd.DataFrame:
    ok = mapping[mapping["exported"]]
    return pd.DataFrame({"Units": "ea", "Location": ok["location"].astype(int).to_numpy(),
                         "Direction": NONDIRECTIONAL, "Theta_0": ok["quantity"].astype(float).to_numpy(),
                         "Blocks": [max(1, int(round(q))) for q in ok["quantity"]],
                         "Comment": [f"{i} on floor {f}" for i, f in zip(ok["item"], ok["floor"])]},
                        index=pd.Index(ok["pelicun_id"].to_numpy(), name="ID"))


def _demand_sample(demands: pd.DataFrame, locations: dict[str, int]) -> tuple[pd.DataFrame, int]:
    """The records as realisations, PFA (m/s²) and PFV (m/s) per location - 1 and direction, a Units row first
    (pelicun's spellings)."""
    d = demands.assign(n=demands["floor"].astype(str).map(locations) - 1)
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


def _loss_files(priced: pd.DataFrame, items: dict, folder: Path) -> dict[str, Path]:
    n_ds = max(int(k[2:]) for k in priced.columns if k.startswith("ds") and k[2:].isdigit())
    rows = []
    for r in priced.itertuples():
        item = items[r.item]
        row = {"ID": f"{r.pelicun_id}-Cost", "Incomplete": 0, "Quantity-Unit": "1 EA", "DV-Unit": CURRENCY}
        for k in range(1, n_ds + 1):
            state = getattr(r, f"ds{k}", None)
            if not isinstance(state, str):
                continue
            cost = item.repair_cost if state == STATES["overturned"][1] else (item.slide_cost or 0.0)
            row.update({f"DS{k}-Family": "", f"DS{k}-Theta_0": float(cost), f"DS{k}-Theta_1": "",
                        f"DS{k}-LongLeadTime": ""})
        rows.append(row)
    columns = ["ID", "Incomplete", "Quantity-Unit", "DV-Unit",
               *(f"DS{k}-{p}" for k in range(1, n_ds + 1) for p in ("Family", "Theta_0", "Theta_1", "LongLeadTime"))]
    conseq = pd.DataFrame(rows, columns=columns).set_index("ID")
    lmap = pd.DataFrame({"Repair": priced["pelicun_id"].to_numpy()}, index=pd.Index(priced["pelicun_id"].to_numpy(), name="ID"))
    return {"loss_repair": _csv(conseq, folder / "loss_repair.csv", index=True),
            "loss_map": _csv(lmap, folder / "loss_map.csv", index=True)}


def _config(storeys: int, n_records: int, seed: int, loss: bool) -> dict[str, Any]:
    size = max(1, n_records) * REPEAT
    dl: dict[str, Any] = {
        "Demands": {"DemandFilePath": "demands.csv", "SampleSize": str(size), "CoupledDemands": True},
        "Asset": {"ComponentAssignmentFile": "inventory.csv", "ComponentDatabase": "None",
                  "ComponentDatabasePath": "CustomDLDataFolder/fragility.csv", "NumberOfStories": str(storeys)},
        "Damage": {"DamageProcess": "None"},
        "Options": {"Seed": seed, "NonDirectionalMultipliers": {"ALL": NONDIRECTIONAL_MULTIPLIER},
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

    path.parent.mkdir(parents=True, exist_ok=True)
    atomic_write(path, lambda fh: df.to_csv(fh, index=index), durable=False)
    return path


def _write_text(path: Path, text: str) -> None:
    from opsrock._files import atomic_write

    atomic_write(path, lambda fh: fh.write(text), durable=False)


__all__ = ["CURRENCY", "NONDIRECTIONAL", "REPEAT", "FloorLocations", "component_id", "floor_locations",
           "write_pelicun_folder"]
