"""The study's files for a pelicun assessment (``tools/pelicun_assess.py`` runs it, in pelicun's own venv).

* ``fragility_<variant>.csv``: opsrock's fragilities in FEMA P-58 / pelicun's damage-model form
  (:func:`opsrock.fragility.pelicun_export.write_pelicun_csv`), one component per item, floor and
  demand. A pelicun component has one fragility wherever it stands, and opsrock's differ by floor, so
  each item gets new IDs, ``opsrock.<FEMA ID>.<floor>.<PFV|PFA>`` (``opsrock.E.20.22.104a.f8.PFV``),
  with ``<floor>`` ``ground`` or ``f<n>``; ``mapping.csv`` maps each to its FEMA ID and pelicun location.
* ``mapping.csv``: ``opsrock_id``, ``fema_id``, ``variant``, ``demand``, ``floor``, ``floor_number``,
  ``location`` (pelicun's: 1 the ground floor, ``n + 1`` the floor slab ``n``, the roof ``storeys + 1``),
  ``median``, ``beta``, ``status`` (``ok`` or why there is no component: an item that never overturned
  within the levels has none).
* ``demands.csv``: a demand sample in pelicun's format (one realisation per record, a ``Units`` row):
  ``PFV-<n>-1`` the peak absolute velocity of floor slab ``n`` (``0`` the ground, i.e. the PGV) of each
  record, unscaled (as recorded), through the study's building. pelicun's default ``DemandOffset`` of
  -1 for PFV makes a component at location ``L`` use ``PFV-(L-1)``: the floor it stands on.
* ``inventory.csv``: the small inventory the assessment places: ``count`` of each item on each floor.
"""

from __future__ import annotations

import math
from pathlib import Path

import pandas as pd

from opsrock.constants import G
from opsrock.inventory.fema.design import ContentsDesign, floor_label

#: Items of each kind on each floor of the assessment's inventory.
INVENTORY_COUNT: int = 3


def component_id(fema_id: str, floor: str, demand: str) -> str:
    """``opsrock.<FEMA ID>.<floor>.<PFV|PFA>``."""
    return f"opsrock.{fema_id}.{floor}.{demand.upper()}"


def write_pelicun_files(fits: pd.DataFrame, velocities: pd.DataFrame, design: ContentsDesign, folder: Path,
                        count: int = INVENTORY_COUNT) -> dict[str, Path]:
    """Write the files of the module docstring into ``folder``; returns their paths by name."""
    from opsrock._files import atomic_write
    from opsrock.fragility.pelicun_export import ComponentFragility, write_pelicun_csv

    folder.mkdir(parents=True, exist_ok=True)
    paths: dict[str, Path] = {}
    mapping = []
    study = fits[(fits["campaign"] != "sweep") & fits["demand"].isin(("pfv", "pfa"))]
    for variant, g in study.groupby("variant", sort=False):
        components = []
        for _, r in g.iterrows():
            floor = floor_label(int(r["floor_number"]), design.storeys)
            cid = component_id(r["item"], floor, r["demand"])
            median = r["median"] * (G if r["demand"] == "pfa" else 1.0)  # fitted in g; exported in m/s2
            ok = bool(r["ok"]) and math.isfinite(median) and math.isfinite(r["beta"]) and r["beta"] > 0
            if ok:
                components.append(ComponentFragility(cid, r["demand"], float(median), float(r["beta"])))
            mapping.append({"opsrock_id": cid, "fema_id": r["item"], "variant": variant, "demand": r["demand"],
                            "floor": floor, "floor_number": int(r["floor_number"]),
                            "location": int(r["floor_number"]) + 1, "median": median if ok else math.nan,
                            "beta": r["beta"] if ok else math.nan, "status": "ok" if ok else r["message"]})
        paths[f"fragility_{variant}"] = write_pelicun_csv(components, folder / f"fragility_{variant}.csv")
    table = pd.DataFrame(mapping)
    paths["mapping"] = folder / "mapping.csv"
    atomic_write(paths["mapping"], lambda fh: table.to_csv(fh, index=False), durable=False)
    paths["demands"] = _write_demands(velocities, design, folder / "demands.csv")
    items = sorted(study["item"].unique())
    inv = pd.DataFrame([{"fema_id": i, "floor": floor_label(n, design.storeys), "floor_number": n, "location": n + 1,
                         "count": count} for n in design.floor_numbers for i in items])
    paths["inventory"] = folder / "inventory.csv"
    atomic_write(paths["inventory"], lambda fh: inv.to_csv(fh, index=False), durable=False)
    return paths


def _write_demands(velocities: pd.DataFrame, design: ContentsDesign, path: Path) -> Path:
    from opsrock._files import atomic_write

    numbers = dict(zip(velocities["floor"], velocities["floor"].map(_floor_number)))
    wide = velocities.assign(n=velocities["floor"].map(numbers)).pivot(index="record", columns="n", values="pfv")
    wide = wide[sorted(wide.columns)]
    wide.columns = [f"PFV-{n}-1" for n in wide.columns]
    wide = wide.reset_index(drop=True)
    units = pd.DataFrame([["mps"] * wide.shape[1]], columns=wide.columns, index=["Units"])
    out = pd.concat([units, wide.astype(object)])
    atomic_write(path, lambda fh: out.to_csv(fh), durable=False)
    return path


def _floor_number(label: str) -> int:
    """Floor number of a campaign floor label (``ground``: 0, ``<building>.f<n>``: n)."""
    return 0 if label == "ground" else int(label.rsplit(".f", 1)[1])


__all__ = ["INVENTORY_COUNT", "component_id", "write_pelicun_files"]
