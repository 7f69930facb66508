"""FEMA P-58's nine in the contents study's pelicun folder, written by the study's one writer
(:func:`opsrock.inventory.pelicun.write_pelicun_folder`), as for any inventory: **each physical unit once**.

The nine are the shipped inventory ``fema-p58-nine`` (:data:`opsrock.inventory.fema.design.INVENTORY`: no slip,
the project's default restitution, one unit per floor), which is the study's ``default`` variant; so the folder
holds that variant (no folder when the study leaves it out). What this module gives the writer:

* the floors as the shipped building labels them (:mod:`opsrock.inventory.sources`: ``ground``, the floor numbers
  ``"1"`` .. ``"<storeys>"``, the roof the top number), so that pelicun's locations follow (1 the ground floor,
  ``n + 1`` the slab ``n``) and ``NumberOfStories`` is the building's storeys;
* the demands: each record's unscaled floor motion (PFA m/s², PFV m/s; :func:`opsrock.inventory.fema.campaigns.
  floor_velocities`), direction ``"1"``: the study runs each recorded component as a motion along the items'
  weaker axis (their ``width``), so each component is one realisation with one direction;
* the fits in the inventory study's form (:data:`opsrock.inventory.fits.FIT_COLUMNS` keys: ``direction`` 1,
  ``outcome`` overturning, ``status`` :func:`opsrock.inventory.fits.fit_status`), from which the writer's components
  (:func:`opsrock.inventory.components.planar_components`: one non-directional PFV component per item and floor, its
  demand ``pfv_max``, with one direction the direction's own lognormal) and the expected numbers
  (:func:`opsrock.inventory.components.expected_table`) follow.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any

import pandas as pd

from opsrock.inventory.fema.design import INVENTORY, ContentsDesign

#: The variant the pelicun folder holds: the shipped inventory's items as they are (no slip, default restitution).
PELICUN_VARIANT: str = "default"

#: The one direction of the study's motions (each recorded component along the items' weaker axis).
DIRECTION: str = "1"


@dataclass(frozen=True)
class BuildingFloors:
    """The floors of the study as the writer reads a motion set's (:func:`opsrock.inventory.pelicun.floor_locations`):
    their labels (``ground``, floor numbers), no ``location`` column (pelicun's follow from the numbers)."""

    floors: tuple[str, ...]
    locations: dict[str, int] = field(default_factory=dict)


@dataclass(frozen=True)
class PelicunStudy:
    """What the writer reads of a study: the items (quantities, costs), the floors and the seed, and the method
    (IDA) for the expected numbers.

    Parameters
    ----------
    inventory : Inventory
        The study's items of the shipped inventory (:class:`opsrock.inventory.items.Inventory`).
    motions : BuildingFloors
        The floors.
    seed : int
        pelicun's seed in ``config.json``.
    method : str
        ``"ida"``.
    """

    inventory: Any
    motions: BuildingFloors
    seed: int
    method: str = "ida"


def floor_of(number: int) -> str:
    """The shipped building's label of floor ``number``: ``ground`` (0) or the number (the roof the top one)."""
    return "ground" if number == 0 else str(number)


def _number(label: str) -> int:
    """Floor number of a campaign floor label (``ground``: 0, ``<building>.f<n>``: n)."""
    return 0 if label == "ground" else int(label.rsplit(".f", 1)[1])


def pelicun_study(design: ContentsDesign) -> PelicunStudy:
    """The study as the writer reads it: the design's items of :data:`INVENTORY` on its floors."""
    from opsrock.inventory.items import shipped_inventory

    inventory = shipped_inventory(INVENTORY)
    chosen = [it for it in inventory.items if not design.items or it.id in design.items]
    floors = tuple(floor_of(n) for n in sorted(design.floor_numbers))
    return PelicunStudy(dataclasses.replace(inventory, items=tuple(chosen)), BuildingFloors(floors), design.seed)


def writer_demands(velocities: pd.DataFrame) -> pd.DataFrame:
    """Each record's unscaled floor motion on the study's floors, as the writer reads the motions' measures
    (:func:`opsrock.inventory.campaigns.floor_demands`'s ``record``, ``floor``, ``direction``, ``pfa`` m/s²,
    ``pfv`` m/s)."""
    floors = velocities["floor"].map(lambda f: floor_of(_number(f)))
    return pd.DataFrame({"record": velocities["record"].to_numpy(), "floor": floors.to_numpy(),
                         "direction": DIRECTION, "pfa": velocities["pfa"].to_numpy(float),
                         "pfv": velocities["pfv"].to_numpy(float)})


def writer_fits(fits: pd.DataFrame) -> pd.DataFrame:
    """The :data:`PELICUN_VARIANT`'s fits on the study's floors (the sweep's roofs left out), PFV (m/s) and PFA (g),
    in the inventory study's form (module docstring)."""
    from opsrock.inventory.fits import fit_status

    own = fits[(fits["campaign"] != "sweep") & (fits["variant"] == PELICUN_VARIANT)
               & fits["demand"].isin(("pfv", "pfa"))]
    rows = []
    for r in own.sort_values(["item", "floor_number"], kind="stable").itertuples():
        ok = bool(r.ok) and math.isfinite(r.median) and math.isfinite(r.beta) and r.beta > 0
        finished = int(r.n_cases) - int(r.n_failed)
        rows.append({"item": r.item, "floor": floor_of(int(r.floor_number)), "direction": DIRECTION,
                     "outcome": "overturning", "demand": r.demand, "unit": r.unit, "median": r.median,
                     "beta": r.beta, "ok": ok, "status": fit_status(ok, r.median, math.inf, int(r.n_overturned),
                                                                    finished),
                     "message": "" if ok else r.message})
    return pd.DataFrame(rows, columns=["item", "floor", "direction", "outcome", "demand", "unit", "median", "beta",
                                       "ok", "status", "message"])


def pelicun_tables(fits: pd.DataFrame, velocities: pd.DataFrame, design: ContentsDesign) -> dict[str, Any]:
    """What the writer and the study's tables need: ``components`` and ``expected`` (tables of the study),
    ``fits``, ``demands`` and ``study`` (the writer's inputs); empty without the :data:`PELICUN_VARIANT`."""
    from opsrock.inventory.components import expected_table, planar_components

    if PELICUN_VARIANT not in design.variants:
        return {}
    study, demands, own = pelicun_study(design), writer_demands(velocities), writer_fits(fits)
    components = planar_components(own, demands, study)
    return {"components": components, "expected": expected_table(components, demands, study, own),
            "fits": own, "demands": demands, "study": study}


__all__ = ["DIRECTION", "PELICUN_VARIANT", "BuildingFloors", "PelicunStudy", "floor_of", "pelicun_study",
           "pelicun_tables", "writer_demands", "writer_fits"]
