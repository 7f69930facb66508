"""The inventory study in three dimensions (``opsrock contents --inventory F --motions M --solver rigid3d``):
each item a box (``width`` along direction 1, ``depth`` along direction 2 at azimuth 0) under both horizontal
floor motions of each record and floor at once (:func:`opsrock.inventory.motions.paired_motions`), turned in
plan to each of the study's azimuths, by the solver in plan ``rigid3d``.

Campaigns: one record scene per group of items on the same floors and support (:mod:`opsrock.inventory.campaigns`'
groups, the direction ``"12"``): its ground records are the direction-1 motions (``<record>.<floor>``), its
second components the direction-2 ones (``<record>.<floor>.d2``), its azimuths the study's (case ids
``<item>-3d/<record>.<floor>/<ground|support.f1>/l<k>/z<m>``); the IDA levels scale both components by one
factor, ``PFA / (g min(tan alpha, mu))`` of the direction-1 motion and the item's width. Stored and resumed as
every campaign, in ``store/d12-rigid3d[...]``.

The fragility of each item per floor pools its cases over the azimuths (an item's orientation in a room is
not known in advance; the azimuths sample it), fitted as the planar study fits
(:func:`opsrock.fragility.mle.plan_mle`, record bootstrap) in the demand conventions pelicun uses for floor
velocity (:data:`PFV_CONVENTIONS`): the PFV of direction 1, of direction 2, the larger of the two, and the
non-directional demand. Pelicun's non-directional demand is the larger directional one times
``NonDirectionalMultipliers`` (default ``{"ALL": 1.2}``, "based on FEMA P-58"): NHERI-SimCenter/pelicun,
``pelicun/base.py`` (``Options``) and ``pelicun/model/damage_model.py`` (a demand of direction 0 is "the
maximum of all available directions" scaled by ``nondir_multi``); neither the geometric mean nor the SRSS. So
``pfv_max_x1.2 = 1.2 max(pfv_1, pfv_2)`` (not ``pfv_nd``, which in the directionality study is the peak of the
horizontal velocity vector), and its fitted median is 1.2 times ``pfv_max``'s with the same ``beta``
(the lognormal fit is scale-equivariant), given for reading against FEMA P-58's non-directional medians.

Outputs (in ``out_dir``, through a staging folder): the planar route's (:data:`opsrock.inventory.outputs.OUTPUTS`:
``fits.csv``, ``demands.csv``, ``expected.csv``, ``report.md`` with its figures, the pelicun folder), each case
read once per direction against that direction's demand (:func:`per_direction`), and ``fits3d.csv``
(:data:`FIT3D_COLUMNS`, the PFV conventions).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.errors import InputError
from opsrock.inventory.motions import paired_motions
from opsrock.inventory.outputs import OUTPUTS
from opsrock.inventory.stages import Route
from opsrock.solvers.registry import round_solver

#: The id of the box that stands beside a round item (:func:`box_of`): the item's id and this.
BOX_SUFFIX: str = ".as-box"

#: Overturning mechanisms counted per fit: ``overturned_over`` of a box (``edge``, ``corner``) and of a cylinder
#: (``rim``: rocking on one rim point, ``rolling``: while its contact point ran round the rim).
MECHANISMS: tuple[str, ...] = ("edge", "corner", "rim", "rolling")

#: Default azimuths of the items in plan (deg, from direction 1 to an item's width).
DEFAULT_AZIMUTHS: tuple[float, ...] = (0.0, 45.0, 90.0)

#: Pelicun's default non-directional multiplier (``NonDirectionalMultipliers = {"ALL": 1.2}``, from FEMA P-58).
NONDIRECTIONAL_FACTOR: float = 1.2

#: The PFV demand conventions fitted (all m/s).
PFV_CONVENTIONS: dict[str, str] = {
    "pfv_1": "PFV of direction 1",
    "pfv_2": "PFV of direction 2",
    "pfv_max": "the larger PFV of the two directions",
    "pfv_max_x1.2": f"pelicun's default non-directional demand: {NONDIRECTIONAL_FACTOR:g} x the larger "
                    "(NonDirectionalMultipliers; the pelicun folder sets it to 1.0 and uses pfv_max)",
}

#: Columns of ``fits3d.csv``, in order: per item, floor and demand convention (``demand``, m/s) the lognormal
#: median (m/s) and ``beta`` with their 95 % intervals, the cases, the overturnings and how many of them were
#: over an edge or a corner of a box, or on the rim of a cylinder, rocking or rolling (:data:`MECHANISMS`:
#: ``n_edge``, ``n_corner``, ``n_rim``, ``n_rolling``), the azimuths pooled, and FEMA P-58's median for its item (m/s) where named.
FIT3D_COLUMNS: tuple[str, ...] = (
    "item", "description", "floor", "demand", "unit", "method", "median", "median_lo", "median_hi", "beta",
    "beta_lo", "beta_hi", "n_cases", "n_exceeded", "n_edge", "n_corner", "n_rim", "n_rolling", "n_failed",
    "n_records", "n_azimuths", "ok",
    "message", "fema_id", "fema_median", "ratio_fema",
)  # fmt: skip

#: Files this route writes into its folder (globs relative to it; :func:`opsrock._files.staged_folder`): the
#: planar route's, ``fits3d.csv`` and, with a round item, ``boxes.csv`` (:data:`BOX_COLUMNS`).
OUTPUTS_3D: tuple[str, ...] = (*OUTPUTS, "fits3d.csv", "boxes.csv")

#: Columns of ``boxes.csv``: per round item and floor, the item (``model`` ``as given``) and the box of its size
#: (``box of its size``) side by side: the lognormal fit in ``pfv_max`` (m/s), the overturnings by mechanism and
#: their shares, the failed cases by reason, and how far the box's median is off the cylinder's (``box_off``).
BOX_COLUMNS: tuple[str, ...] = (
    "item", "floor", "model", "shape", "demand", "unit", "median", "median_lo", "median_hi", "beta", "n_cases",
    "n_exceeded", "n_failed", "n_edge", "n_corner", "n_rim", "n_rolling", "share_edge", "share_corner", "share_rim",
    "share_rolling", "failed_reasons", "box_off",
)  # fmt: skip


def check_azimuths(azimuths: tuple) -> tuple[float, ...]:
    """``azimuths`` as floats: a non-empty tuple of distinct finite angles in [-360, 360] deg; else
    :class:`InputError` naming ``azimuths``."""
    values = tuple(azimuths)
    if not values or any(isinstance(z, bool) or not isinstance(z, (int, float)) or not math.isfinite(z) or abs(z) > 360
                         for z in values) or len(set(values)) != len(values):
        raise InputError(f"azimuths must be distinct angles in degrees within [-360, 360], got {azimuths!r}",
                         argument="azimuths")
    return tuple(float(z) for z in values)


def box_of(item: Any) -> Any:
    """The box a round item would have been without ``shape``: ``width = depth =`` its diameter (m), its height,
    mass and any mass distribution or friction it gives (a blank one the box's own: homogeneous), its id
    ``<id>`` :data:`BOX_SUFFIX`. The study runs it beside the item and reports how far it is off
    (:func:`box_table`); it is in no table of items, no expected number, no pelicun component."""
    import dataclasses

    return dataclasses.replace(item, id=f"{item.id}{BOX_SUFFIX}", shape="box",
                               description=f"the box of {item.id}'s size ({item.width:g} x {item.width:g} m base)")


def study_items(design: Any) -> tuple:
    """The items the route runs: the inventory's, then the box of each round item's size (:func:`box_of`);
    ``InputError`` when an inventory id is already a box's."""
    items = tuple(design.inventory.items)
    boxes = tuple(box_of(it) for it in items if it.shape == "cylinder")
    taken = {it.id for it in items} & {b.id for b in boxes}
    if taken:
        raise InputError(f"item id {sorted(taken)[0]!r} ends with {BOX_SUFFIX!r}, the id of the box the study runs "
                         "beside a round item: rename it", argument="inventory")
    return items + boxes


def three_d_scenes(design: Any) -> list:
    """One record scene in plan per group of items on the same floors and support (the module docstring).

    Parameters
    ----------
    design : InventoryDesign
        Its ``inventory``, ``motions`` (both directions of every record and floor), ``intensity``, ``seed``
        and ``azimuths`` (deg).
    """
    from opsrock.campaign.records import Floor, RecordSet
    from opsrock.campaign.scene import Scene
    from opsrock.excitations.building import ShearBuilding
    from opsrock.excitations.records import safe_name
    from opsrock.inventory.campaigns import SUPPORT_NAME, Group, GroupScene, item_block_spec

    pairs = paired_motions(design.motions)
    floors = design.motions.floors
    groups: dict[Any, list] = {}
    for item in study_items(design):
        own = tuple(f for f in floors if f in item.floors) if item.floors else floors
        solver = round_solver() if item.shape == "cylinder" else design.solver  # a round base: the cylinder's solver
        groups.setdefault(Group(own, own == floors, "12", item.support, solver), []).append(item)
    out = []
    for g, items in groups.items():
        chosen = [p for p in pairs if p.floor in g.floors]
        names = {p: f"{safe_name(p.record)}.{safe_name(p.floor)}" for p in chosen}
        floor = Floor(None, 0) if g.support is None else Floor(
            ShearBuilding(SUPPORT_NAME, g.support.period, 1, g.support.damping), 1)
        # a cylinder is round: one azimuth (its rotation invariance is a check of cylinder3d, to round-off)
        azimuths = design.azimuths[:1] if g.solver == round_solver() else design.azimuths
        records = RecordSet(grounds=tuple(p.first.motion.with_name(names[p]) for p in chosen), floors=(floor,),
                            source=design.motions.source, intensity=design.intensity,
                            seconds=tuple(p.second.motion.with_name(names[p] + ".d2") for p in chosen),
                            second="manifest", azimuth=azimuths)
        blocks = tuple(item_block_spec(it, "1", f"{it.id}-3d", design.seed, g.solver) for it in items)
        scene = Scene(name=f"inventory-{g.name}", path="", blocks=blocks, grid=None, solver=g.solver,
                      records=records)
        out.append(GroupScene(g, scene, {b.name: it.id for b, it in zip(blocks, items)},
                              {names[p]: (p.record, p.floor) for p in chosen}))
    return out


def pfv_demands(cases: pd.DataFrame, demands: pd.DataFrame) -> pd.DataFrame:
    """``cases`` with the demand of each convention (:data:`PFV_CONVENTIONS`, m/s): the scale factor times the
    floor motion's PFV in direction 1 and 2 (:func:`opsrock.inventory.campaigns.floor_demands`), their larger,
    and :data:`NONDIRECTIONAL_FACTOR` times it."""
    d = demands.set_index(["record", "floor", "direction"])["pfv"]
    out = cases.copy()
    scale = cases["scale"].to_numpy(float)
    for direction in ("1", "2"):
        keys = list(zip(cases["record"], cases["floor"], [direction] * len(cases)))
        out[f"pfv_{direction}"] = scale * d.reindex(keys).to_numpy(float)
    out["pfv_max"] = np.maximum(out["pfv_1"], out["pfv_2"])
    out["pfv_max_x1.2"] = NONDIRECTIONAL_FACTOR * out["pfv_max"]
    return out


def fit3d_table(cases: pd.DataFrame, demands: pd.DataFrame, design: Any, workers: int | None,
                items: dict | None = None) -> pd.DataFrame:
    """Every fit of the route (:data:`FIT3D_COLUMNS`): one row per item, floor and PFV convention, the azimuths
    pooled; lognormal maximum likelihood with a record bootstrap (:func:`opsrock.fragility.mle.plan_mle`).
    ``items``: id -> item of the items fitted (default the design's inventory; the cases of others, the boxes
    beside round items, :func:`box_of`, are left out)."""
    from opsrock.inventory.fits import FitBatch, fema_median

    items = items if items is not None else {it.id: it for it in design.inventory.items}
    scaled = pfv_demands(cases[cases["item"].isin(list(items))], demands)  # a round item's box: not an item
    batch = FitBatch(design.n_boot, design.seed)
    for (item_id, floor), g in scaled.groupby(["item", "floor"], sort=False):
        ok, item = g[g["status"] == "ok"], items[item_id]
        y = ok["overturned"].to_numpy(bool)
        for demand in PFV_CONVENTIONS:
            fema = fema_median(item.fema_id)
            row = {"item": item_id, "description": item.description, "floor": floor, "demand": demand, "unit": "m/s",
                   "method": design.method, "n_cases": len(ok), "n_exceeded": int(y.sum()),
                   **{f"n_{m}": int((ok["overturned_over"] == m).sum()) for m in MECHANISMS},
                   "n_failed": len(g) - len(ok),
                   "n_records": int(ok["record"].nunique()), "n_azimuths": int(ok["azimuth"].nunique()),
                   "fema_id": item.fema_id, "fema_median": fema if demand == "pfv_max_x1.2" else math.nan}
            batch.add(row, ok[demand].to_numpy(float), y, ok["record"].to_numpy(),
                      never="never overturned " + ("within the levels" if design.method == "ida"
                                                   else "under the motions as recorded"))
    batch.run(workers)
    table = pd.DataFrame(batch.rows, columns=list(FIT3D_COLUMNS))
    table["ratio_fema"] = table["median"] / table["fema_median"]
    return table


def box_table(fits: pd.DataFrame, cases: pd.DataFrame) -> pd.DataFrame:
    """``boxes.csv`` (:data:`BOX_COLUMNS`): per round item and floor, its ``pfv_max`` fit (:func:`fit3d_table`
    rows of the item and of the box of its size, :func:`box_of`), each with its overturnings' shares by mechanism
    and its failed cases by reason (:func:`opsrock.inventory.summary.failure_table`); ``box_off`` on the box's
    row: its median over the item's, less 1 (NaN where either has no median)."""
    from opsrock.inventory.summary import failure_table

    rows = []
    pfv = fits[fits["demand"] == "pfv_max"].set_index(["item", "floor"])
    for item, floor in [k for k in pfv.index if not k[0].endswith(BOX_SUFFIX) and (k[0] + BOX_SUFFIX, k[1]) in pfv.index]:
        pair = []
        for model, key in (("as given", item), ("box of its size", item + BOX_SUFFIX)):
            f = pfv.loc[(key, floor)]
            n = int(f["n_exceeded"])
            mine = cases[(cases["item"] == key) & (cases["floor"].astype(str) == str(floor))]
            reasons = failure_table(mine)
            row = {"item": item, "floor": floor, "model": model, "shape": "box" if key != item else "cylinder",
                   **{c: f[c] for c in ("demand", "unit", "median", "median_lo", "median_hi", "beta", "n_cases",
                                        "n_exceeded", "n_failed")},
                   **{f"n_{m}": int(f[f"n_{m}"]) for m in MECHANISMS},
                   **{f"share_{m}": int(f[f"n_{m}"]) / n if n else math.nan for m in MECHANISMS},
                   "failed_reasons": "; ".join(f"{r.n_failed} x {r.code} ({r.first_reason})" for r in reasons.itertuples()),
                   "box_off": math.nan}
            pair.append(row)
        pair[1]["box_off"] = pair[1]["median"] / pair[0]["median"] - 1.0
        rows += pair
    return pd.DataFrame(rows, columns=list(BOX_COLUMNS))


def per_direction(cases: pd.DataFrame) -> pd.DataFrame:
    """Each case of a box in plan once per horizontal direction (``direction`` ``"1"`` and ``"2"``): its outcome
    read against the demand of that direction, so that the planar route's tables, report and pelicun folder
    (:func:`opsrock.inventory.outputs.study_tables`) take it as they are."""
    return pd.concat([cases.assign(direction=d) for d in ("1", "2")], ignore_index=True)


def _fit(a: Any) -> dict[str, pd.DataFrame]:
    """The planar route's tables from :func:`per_direction` cases of the inventory's items, ``fits3d``
    (:func:`fit3d_table`), and with a round item ``boxes`` (:func:`box_table`: the item beside the box of its
    size, whose cases are in no other table)."""
    from opsrock.inventory.components import three_d_components
    from opsrock.inventory.outputs import study_tables, workers_of

    workers = workers_of(a.options.workers)
    ids = {it.id for it in a.design.inventory.items}
    mine = a.cases[a.cases["item"].isin(ids)]
    components = three_d_components(mine, a.demands, a.design, workers)
    tables = {**study_tables(a, per_direction(mine), components),
              "fits3d": fit3d_table(mine, a.demands, a.design, workers)}
    boxes = round_boxes(a.cases, a.demands, a.design, workers)
    return tables if boxes is None else {**tables, "boxes": boxes}


def round_boxes(cases: pd.DataFrame, demands: pd.DataFrame, design: Any, workers: int) -> pd.DataFrame | None:
    """``boxes.csv`` (:func:`box_table`) from the 3-D ``cases`` of the round items and of the boxes of their size
    run beside them (:func:`study_items`); None when the inventory has no round item."""
    everything = {it.id: it for it in study_items(design)}
    round_ids = {i for i, it in everything.items() if it.shape == "cylinder"}
    if not round_ids:
        return None
    pairs = cases[cases["item"].map(lambda i: i in round_ids or i.removesuffix(BOX_SUFFIX) in round_ids)]
    return box_table(fit3d_table(pairs, demands, design, workers, everything), pairs)


def _write(a: Any, stage: Path) -> Any:
    """The planar route's outputs (:func:`opsrock.inventory.outputs.write_outputs`), ``fits3d.csv``, and the
    report's lines on the model in three dimensions."""
    from opsrock.inventory.outputs import write_outputs

    round_items = [it.id for it in a.design.inventory.items if it.shape == "cylinder"]
    notes = (f"Model: every item a box in three dimensions (solver {a.design.solver}) under both horizontal "
             f"components at once, turned in plan to {', '.join(f'{z:g}' for z in a.design.azimuths)} deg, the "
             "azimuths pooled"
             + (f"; the round items ({', '.join(round_items)}) cylinders (solver {round_solver()}) at "
                f"{a.design.azimuths[0]:g} deg only, being round" if round_items else "")
             + "; the rows of direction 1 (2) read each case against the PFV and PFA of direction 1 (2).",
             "fits3d.csv: the PFV medians in each convention, "
             + "; ".join(f"`{k}` {v}" for k, v in PFV_CONVENTIONS.items()) + " (pelicun's non-directional demand: "
             "NHERI-SimCenter/pelicun, pelicun/base.py NonDirectionalMultipliers).")
    return write_outputs(a, stage, notes)


#: The route in three dimensions (:class:`opsrock.inventory.stages.Route`).
THREE_D: Route = Route("3d", three_d_scenes, _fit, _write, OUTPUTS_3D)

__all__ = ["BOX_COLUMNS", "BOX_SUFFIX", "DEFAULT_AZIMUTHS", "FIT3D_COLUMNS", "MECHANISMS", "box_of", "box_table",
           "study_items", "NONDIRECTIONAL_FACTOR", "OUTPUTS_3D",
           "PFV_CONVENTIONS", "check_azimuths", "fit3d_table", "per_direction", "pfv_demands",
           "THREE_D", "round_boxes", "three_d_scenes"]
