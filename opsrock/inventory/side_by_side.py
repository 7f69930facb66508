"""Both models side by side for the user's inventory on the user's floor motions
(``opsrock contents --inventory F --motions M --model both``; :data:`SIDE_BY_SIDE`): each item planar per axis (the
planar route's campaigns, fits, tables, report and pelicun folder, as :data:`opsrock.inventory.study.PLANAR` writes
them) and a box in three dimensions under both components at once, turned to the study's azimuths, by the
registry's solver in plan (the campaigns of :data:`opsrock.inventory.three_d.THREE_D`: ``fits3d.csv`` and
``components3d.csv``), on the same motions and in the same stores.

``side_by_side.csv`` (:data:`SIDE_COLUMNS`) puts, per item, floor and limit state, the 3-D median and the planar one
in the same demand, the larger directional PFV (``pfv_max``, m/s; the planar median is the two planes' curves
combined, :func:`opsrock.inventory.components.planar_components`), and what the study measured that moves them, all
from the 3-D cases:

* **orientation**: the median fitted at each azimuth alone (no resamples), its lowest and highest and their azimuths
  (``median_az_low``, ``az_low``, ``median_az_high``, ``az_high``, m/s and deg);
* **corner overturning**: the share of the 3-D overturnings that went over a corner rather than an edge
  (``corner_share``);
* **sliding**: the share of each model's finished cases whose base slid at least the item's slide distance
  (``slid_share_3d``, ``slid_share_planar``; n/a where the planar solver models no slip: an item without friction).

The report gets its own section (:func:`side_by_side_lines`), rendered from that table; it computes nothing.
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.errors import InputError
from opsrock.inventory.stages import Route
from opsrock.inventory.study import PLANAR
from opsrock.inventory.three_d import OUTPUTS_3D, THREE_D
from opsrock.solvers.registry import plan_solver

#: The planar groups' direction is ``"1"`` or ``"2"``; the 3-D groups' (both at once) this one.
BOTH_DIRECTIONS: str = "12"

#: Columns of ``side_by_side.csv``, in order (medians in m/s of ``pfv_max``; azimuths in deg; shares in [0, 1]).
SIDE_COLUMNS: tuple[str, ...] = (
    "item", "floor", "limit_state", "median_3d", "median_planar", "ratio_3d_planar", "status_3d", "status_planar",
    "median_az_low", "az_low", "median_az_high", "az_high", "corner_share", "slid_share_3d", "slid_share_planar",
    "n_cases_3d", "n_cases_planar",
)  # fmt: skip

#: Files the route writes (globs relative to its folder): the 3-D route's and the side-by-side tables.
OUTPUTS_BOTH: tuple[str, ...] = (*OUTPUTS_3D, "components3d.csv", "side_by_side.csv")


def three_d_design(design: Any) -> Any:
    """``design`` (an :class:`~opsrock.inventory.study.InventoryDesign`) with every item a box in three dimensions:
    the registry's solver in plan (:func:`~opsrock.solvers.registry.plan_solver`)."""
    return dataclasses.replace(design, solver=plan_solver(), side_by_side=False)


def _scenes(design: Any) -> list:
    """The planar route's campaigns and the 3-D route's, on one list (one pool runs them all)."""
    if not design.side_by_side:
        raise InputError("the side-by-side route runs a design with side_by_side=True", argument="side_by_side")
    return [*PLANAR.scenes(design), *THREE_D.scenes(three_d_design(design))]


def split_cases(cases: pd.DataFrame) -> tuple[pd.DataFrame, pd.DataFrame]:
    """``cases`` as (planar, 3-D): the 3-D groups run both directions at once (:data:`BOTH_DIRECTIONS`)."""
    in_3d = cases["direction"].astype(str) == BOTH_DIRECTIONS
    return cases[~in_3d].reset_index(drop=True), cases[in_3d].reset_index(drop=True)


def _slid_share(cases: pd.DataFrame, distance: float) -> float:
    """The share of finished ``cases`` whose base slid at least ``distance`` (m); NaN where no slip was modelled."""
    slide = cases["slide_max"].astype(float)
    if slide.isna().all() or not len(cases):
        return math.nan
    return float((slide.fillna(0.0) >= distance).mean())


def _azimuth_medians(ok: pd.DataFrame, x: np.ndarray, y: np.ndarray, seed: int) -> dict[float, float]:
    """The lognormal median (m/s) fitted to each azimuth's cases alone (point fit, no resamples); NaN where it
    cannot be fitted (never or always exceeded)."""
    from opsrock.inventory.fits import FitBatch

    batch = FitBatch(0, seed)
    azimuths = ok["azimuth"].to_numpy(float)
    for z in sorted(set(azimuths)):
        at = azimuths == z
        mixed = bool(y[at].any() and not y[at].all())  # one outcome only: no finite median
        batch.add({"azimuth": z}, x[at], y[at] & mixed, None)
    batch.run(1)
    return {row["azimuth"]: row["median"] for row in batch.rows}


def _measured(cases3d: pd.DataFrame, planar: pd.DataFrame, demands: pd.DataFrame, item: Any, floor: str,
              design: Any) -> dict[tuple[str, str], dict[str, Any]]:
    """Per limit state of one item and floor, what moves the 3-D median (the module docstring)."""
    from opsrock.inventory.components import STATES, record_pfv
    from opsrock.inventory.fits import outcomes, slide_distance_of

    distance = slide_distance_of(item, design)
    ok = cases3d[(cases3d["item"] == item.id) & (cases3d["floor"].astype(str) == floor) & (cases3d["status"] == "ok")]
    ok_planar = planar[(planar["item"] == item.id) & (planar["floor"].astype(str) == floor) & (planar["status"] == "ok")]
    x = ok["scale"].to_numpy(float) * record_pfv(demands, floor)["pfv_max"].reindex(ok["record"]).to_numpy(float)
    found = outcomes(ok, distance)
    over = ok["overturned"].astype(bool)
    out = {}
    for ls, (outcome, _) in STATES.items():
        if outcome not in found:
            continue
        by_z = {z: m for z, m in _azimuth_medians(ok, x, found[outcome].to_numpy(bool), design.seed).items()
                if math.isfinite(m)}
        low = min(by_z, key=by_z.get) if by_z else math.nan
        high = max(by_z, key=by_z.get) if by_z else math.nan
        out[(item.id, ls)] = {
            "median_az_low": by_z.get(low, math.nan), "az_low": low, "median_az_high": by_z.get(high, math.nan),
            "az_high": high, "corner_share": float((ok.loc[over, "overturned_over"] == "corner").mean())
            if over.any() and ls == "overturned" else math.nan,
            "slid_share_3d": _slid_share(ok, distance), "slid_share_planar": _slid_share(ok_planar, distance),
            "n_cases_3d": len(ok), "n_cases_planar": len(ok_planar)}
    return out


def side_by_side_table(components: pd.DataFrame, components3d: pd.DataFrame, planar: pd.DataFrame,
                       cases3d: pd.DataFrame, demands: pd.DataFrame, design: Any) -> pd.DataFrame:
    """:data:`SIDE_COLUMNS`: per item, floor and limit state of the 3-D components, its median beside the planar
    one (both ``pfv_max``, m/s) and the measured quantities of the module docstring."""
    items = {it.id: it for it in design.inventory.items}
    flat = components.set_index(["item", "floor", "limit_state"])
    rows = []
    for (item_id, floor), g in components3d.groupby(["item", "floor"], sort=False):
        measured = _measured(cases3d, planar, demands, items[item_id], str(floor), design)
        for r in g.itertuples():
            key = (item_id, r.floor, r.limit_state)
            p = flat.loc[key] if key in flat.index else None
            median_planar = float(p["median"]) if p is not None else math.nan
            rows.append({"item": item_id, "floor": r.floor, "limit_state": r.limit_state, "median_3d": r.median,
                         "median_planar": median_planar, "ratio_3d_planar": r.median / median_planar,
                         "status_3d": r.status or "never",
                         "status_planar": (p["status"] or "never") if p is not None else "not modelled",
                         **measured.get((item_id, r.limit_state), {})})
    return pd.DataFrame(rows, columns=list(SIDE_COLUMNS))


def _fit(a: Any) -> dict[str, pd.DataFrame]:
    """The planar route's tables from the planar cases; ``fits3d`` and ``components3d`` from the 3-D cases; and
    :func:`side_by_side_table`."""
    from opsrock.inventory.components import three_d_components
    from opsrock.inventory.outputs import study_tables, workers_of
    from opsrock.inventory.three_d import fit3d_table, round_boxes

    planar, cases3d = split_cases(a.cases)
    design3d, workers = three_d_design(a.design), workers_of(a.options.workers)
    tables = study_tables(a, planar)
    components3d = three_d_components(cases3d, a.demands, design3d, workers)
    side = side_by_side_table(tables["components"], components3d, planar, cases3d, a.demands, a.design)
    boxes = round_boxes(cases3d, a.demands, design3d, workers)
    return {**tables, "fits3d": fit3d_table(cases3d, a.demands, design3d, workers), "components3d": components3d,
            "side_by_side": side, **({} if boxes is None else {"boxes": boxes})}


def side_by_side_lines(table: pd.DataFrame, design3d: Any) -> list[str]:
    """The report's section on the two models, rendered from ``side_by_side.csv`` (:func:`side_by_side_table`)."""
    from opsrock.report.markdown import markdown_table

    lines = ["", "## 3-D and planar side by side", "",
             f"Every item also ran as a box in three dimensions (solver {design3d.solver}) under both components at "
             f"once, turned to {', '.join(f'{z:g}' for z in design3d.azimuths)} deg (pooled in its median). Both medians "
             "are of the larger directional PFV (`pfv_max`, m/s); the planar one is the two planes' curves combined "
             "(the pelicun folder's). What moves them, measured on the 3-D cases: the median fitted at each azimuth "
             "alone (lowest and highest, orientation), the share of overturnings over a corner, and the share of "
             "each model's cases whose base slid at least the slide distance (n/a: the planar solver models no slip "
             "for that item). `side_by_side.csv` holds the table at full precision.", ""]
    if table.empty:
        return [*lines, "No item overturned or was displaced in three dimensions.", ""]
    shown = table.rename(columns={"limit_state": "state", "median_3d": "3-D", "median_planar": "planar",
                                  "ratio_3d_planar": "3-D / planar", "median_az_low": "lowest (az)",
                                  "median_az_high": "highest (az)", "corner_share": "over a corner",
                                  "slid_share_3d": "slid, 3-D", "slid_share_planar": "slid, planar"})
    shown["lowest (az)"] = [_at(m, z) for m, z in zip(table["median_az_low"], table["az_low"])]
    shown["highest (az)"] = [_at(m, z) for m, z in zip(table["median_az_high"], table["az_high"])]
    columns = ["item", "floor", "state", "3-D", "planar", "3-D / planar", "lowest (az)", "highest (az)",
               "over a corner", "slid, 3-D", "slid, planar"]
    return [*lines, markdown_table(shown[columns]), ""]


def _at(median: float, azimuth: float) -> str:
    return "n/a" if not math.isfinite(median) else f"{median:.3g} ({azimuth:g} deg)"


def _write(a: Any, stage: Path) -> Any:
    """The planar route's outputs from the planar tables (the pelicun folder is the planar one), the 3-D and
    side-by-side tables, and the report's section on the two models (:func:`side_by_side_lines`); the report's
    cases are both models' (every failed case of an item listed by reason)."""
    from opsrock._files import atomic_write
    from opsrock.inventory.outputs import write_outputs

    planar, cases3d = split_cases(a.cases)
    design3d = three_d_design(a.design)
    items = [it.id for it in a.design.inventory.items]

    def failed(c: pd.DataFrame) -> int:
        return int((c["status"] != "ok").sum())

    mine = cases3d[cases3d["item"].isin(items)]
    notes = (f"Both models: of the items' cases, {len(planar)} planar ({failed(planar)} failed) and {len(mine)} in "
             f"three dimensions ({failed(mine)} failed): the section 3-D and planar side by side.",)
    written = write_outputs(a, stage, notes)
    text = Path(written.report).read_text() + "\n".join(side_by_side_lines(a.tables["side_by_side"], design3d))
    atomic_write(Path(written.report), lambda fh: fh.write(text), durable=False)
    return written


#: Both models side by side for the user's inventory (:class:`opsrock.inventory.stages.Route`).
SIDE_BY_SIDE: Route = Route("both", _scenes, _fit, _write, OUTPUTS_BOTH)

__all__ = ["BOTH_DIRECTIONS", "OUTPUTS_BOTH", "SIDE_BY_SIDE", "SIDE_COLUMNS", "side_by_side_lines",
           "side_by_side_table", "split_cases", "three_d_design"]
