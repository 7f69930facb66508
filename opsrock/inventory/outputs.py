"""What an inventory study hands back and how it writes its tables: the layer below the study's routes (the
planar one, :mod:`opsrock.inventory.study`, and the one in three dimensions, :mod:`opsrock.inventory.three_d`),
which both import it and neither each other."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pandas as pd

#: Files the study writes into its folder (besides ``campaigns/``).
TABLES: dict[str, str] = {"fits": "fits.csv", "components": "components.csv", "demands": "demands.csv",
                          "expected": "expected.csv"}

#: Every output the study owns in its folder (globs relative to it; :func:`opsrock._files.staged_folder`).
OUTPUTS: tuple[str, ...] = ("report.md", *TABLES.values(), "figures/*.png", "pelicun/*.csv", "pelicun/*.json",
                              "pelicun/per_direction/*.csv")


@dataclass(frozen=True)
class InventoryStudy:
    """What :func:`opsrock.inventory.run.run_design` computed and wrote.

    Parameters
    ----------
    design : opsrock.inventory.study.InventoryDesign
        The study as run.
    out_dir : str
        The output folder.
    tables : dict of str to str
        Key of :data:`TABLES` -> CSV path.
    pelicun : dict of str to str
        pelicun file key -> path (:func:`opsrock.inventory.pelicun.write_pelicun_folder`).
    report : str
        ``report.md``.
    n_cases, n_computed, n_failed : int
        Cases of the campaigns, those computed by this call (0 on a resume with nothing missing), those failed.
    timings : dict of str to float
        Wall times (s): ``demands_s``, ``campaigns_s``, ``fits_s``, ``outputs_s``, ``total_s``.
    figures : list of str
        PNG paths the route lists (the FEMA P-58 and the side-by-side routes).
    summary : object
        The route's headline numbers (:class:`opsrock.inventory.fema.report.StudySummary`, the side-by-side
        route's dict), or None.
    """

    design: Any
    out_dir: str
    tables: dict[str, str]
    pelicun: dict[str, str]
    report: str
    n_cases: int
    n_computed: int
    n_failed: int
    timings: dict[str, float]
    figures: list[str] = field(default_factory=list)
    summary: Any = None


@dataclass(frozen=True)
class Written:
    """What a route's output stage wrote into the staging folder.

    Parameters
    ----------
    tables : dict of str to Path
        Table key -> CSV path.
    report : Path
        ``report.md``.
    pelicun : dict of str to Path
        pelicun file key -> path (empty: no pelicun folder).
    figures : tuple of Path
        PNG paths.
    summary : object
        The route's headline numbers (what its command prints), or None.
    """

    tables: dict[str, Path]
    report: Path
    pelicun: dict[str, Path] = field(default_factory=dict)
    figures: tuple[Path, ...] = ()
    summary: Any = None


def workers_of(workers: int | None) -> int:
    """``workers``, or every core this process may use."""
    import os

    if workers is not None:
        return workers
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def study_tables(a: Any, cases: pd.DataFrame, components: pd.DataFrame | None = None) -> dict[str, pd.DataFrame]:
    """The tables (:data:`TABLES`) of the assessment ``a`` (:class:`opsrock.inventory.stages.Assessment`) from
    ``cases``: ``fits`` one row per item, floor, direction, outcome and demand (each with the ``pelicun_id`` of the
    component it feeds); ``components`` one row per item, floor and limit state (given, from the route in three
    dimensions, or the planar fits' two directions combined:
    :func:`opsrock.inventory.components.planar_components`); ``demands``; ``expected`` one row per item and floor
    (:func:`opsrock.inventory.components.expected_table`)."""
    from opsrock.inventory.components import component_id, expected_table, planar_components
    from opsrock.inventory.fits import fit_table

    fits = fit_table(cases, a.demands, a.design, workers_of(a.options.workers))
    fits["pelicun_id"] = [component_id(i, str(f)) for i, f in zip(fits["item"], fits["floor"])]
    planar = components is None
    if planar:
        components = planar_components(fits, a.demands, a.design)
    expected = expected_table(components, a.demands, a.design, fits if planar else None, cases)
    return {"fits": fits, "components": components, "demands": a.demands, "expected": expected}


def write_outputs(a: Any, stage: Path, notes: tuple[str, ...] = ()) -> Any:
    """The tables of the assessment ``a`` (:data:`TABLES`, and any other ``<key>.csv``; each with its units row,
    :func:`opsrock.inventory.columns.write_table`), its pelicun folder, then its report (which shows the wall
    times), into the staging folder ``stage``; ``notes``: lines the route adds to the report."""
    from opsrock.inventory.pelicun import write_pelicun_folder

    t0 = time.perf_counter()
    from opsrock.inventory.columns import write_table

    paths = {k: write_table(df, stage / TABLES.get(k, f"{k}.csv")) for k, df in a.tables.items()}
    say_ground(a.design)
    pel = write_pelicun_folder(a.tables["components"], a.tables["fits"], a.demands, a.design, stage / "pelicun")
    a.timings["outputs_s"] = time.perf_counter() - t0
    a.timings["total_s"] = time.perf_counter() - a.t_start
    report = _write_report(stage, {**a.tables, "design": a.design, "cases": a.cases, "timings": a.timings,
                                   "pelicun": pel, "n_computed": a.n_computed,
                                   "n_retried": a.n_retried}, notes)
    return Written(paths, report, pel)


def _write_report(stage: Path, study_tables: dict[str, Any], route_notes: tuple[str, ...] = ()) -> Path:
    """``report.md`` and its figures (:mod:`opsrock.inventory.report`, :mod:`opsrock.inventory.plots`) from the
    study's tables; every number the report shows is computed in :mod:`opsrock.inventory.summary`."""
    from opsrock.inventory.items import item_cells
    from opsrock.inventory.plots import item_figures, plot_floor_demands
    from opsrock.inventory.report import ReportInputs, write_report
    from opsrock.inventory.summary import demand_table, fema_ratio_reasons, report_tables

    design, fits, every = study_tables["design"], study_tables["fits"], study_tables["cases"]
    items = {it.id: it for it in design.inventory.items}
    cases, beside = every[every["item"].isin(list(items))], every[~every["item"].isin(list(items))]
    levels = {"pfv": design.demand_levels_pfv, "pfa": design.demand_levels_pfa}
    computed = report_tables(fits, levels, cases)  # the items' failures; the boxes' are in their own section
    computed["reasons"] = fema_ratio_reasons(computed["table"], items, study_tables["demands"])
    computed["never"] = tuple(i for i in items if i not in set(computed["curves"].query(
        "outcome == 'overturning' and demand == 'pfv'")["item"]))
    computed["slides"] = tuple(sorted(set(fits.loc[(fits["outcome"] == "sliding") & (fits["n_exceeded"] > 0), "item"])))
    figures = {item: f"figures/{p.name}" for item, p in item_figures(computed["curves"], stage / "figures").items()}
    figures["demands"] = f"figures/{plot_floor_demands(demand_table(study_tables['demands']), stage / 'figures' / 'demands.png').name}"
    t = study_tables["timings"]
    notes = (f"{case_count(cases, beside)}; {study_tables['n_computed']} of all these computed in this run"
             + (f" ({study_tables['n_retried']} of them stored as timed out before, computed again)."
                if study_tables.get("n_retried") else "."),
             f"Wall time (s): demands {t.get('demands_s', 0.0):.1f}, campaigns {t.get('campaigns_s', 0.0):.1f}, "
             f"fits {t.get('fits_s', 0.0):.1f}.", *route_notes)
    pelicun = {key: Path(path).relative_to(stage).as_posix() for key, path in study_tables["pelicun"].items()}
    inputs = ReportInputs(title=f"Contents fragility: {design.inventory.source} on {design.motions.source}",
                          method=design.method, fits=fits, demands=study_tables["demands"],
                          expected=study_tables["expected"],
                          inventory=pd.DataFrame([item_cells(i) for i in design.inventory.items]),
                          figures=figures, notes=notes, pelicun=pelicun, pelicun_notes=_pelicun_notes(design),
                          boxes=study_tables.get("boxes"),
                          **computed)
    return write_report(stage / "report.md", inputs)


def case_count(cases: pd.DataFrame, beside: pd.DataFrame) -> str:
    """What the report says it counts: the inventory's items' ``cases`` and their failed ones, then (where there
    are any) the cases of the boxes run ``beside`` the round items, counted apart."""
    def failed(c: pd.DataFrame) -> int:
        return int((c["status"] != "ok").sum())

    text = f"{len(cases)} cases of the inventory's items, {failed(cases)} failed"
    if len(beside):
        text += (f"; {len(beside)} more of the boxes run beside the round items, {failed(beside)} failed (their own "
                 "section)")
    return text


def say_ground(design: Any) -> None:
    """Which floor label the pelicun folder takes as the ground, on stderr (always: it is an assumption about the
    user's building, not progress), unless the manifest's ``location`` column gave every floor's location."""
    import sys

    from opsrock.inventory.pelicun import floor_locations

    floors = floor_locations(design.motions)
    if not floors.given:
        where = ", ".join(f"{f} -> {n}" for f, n in floors.locations.items())
        print(f"contents: pelicun locations: {floors.ground} ({where}; NumberOfStories {floors.storeys}); give the "
              "manifest a 'location' column to set them", file=sys.stderr, flush=True)


def _pelicun_notes(design: Any) -> tuple[str, ...]:
    """What the report says of the pelicun folder: the floors' locations, the storeys, the demand and states."""
    from opsrock.inventory.components import NONDIRECTIONAL_MULTIPLIER
    from opsrock.inventory.pelicun import floor_locations

    floors = floor_locations(design.motions)
    how = "as the manifest's `location` column gives them" if floors.given else \
        f"no `location` column in the manifest: {floors.ground}"
    return (f"Floors -> pelicun locations ({how}): " + ", ".join(floors.lines()) + ".",
            "Each item on each floor is one non-directional component (`Demand-Directional` 0): its units counted "
            "once, `quantity` units as that many blocks. Its demand is pelicun's non-directional PFV, the larger "
            f"direction times `NonDirectionalMultipliers`, set to {NONDIRECTIONAL_MULTIPLIER:g} so that it is "
            "`pfv_max`, the demand its fragility is fitted in (`components.csv`).",
            "Damage states, sequential: DS1 displaced (slid or rolled beyond the item's `slide_distance`, or "
            "overturned), DS2 overturned, where friction is modelled; DS1 overturned otherwise. Every overturned "
            "unit is also displaced, and pelicun draws a unit's limit-state capacities perfectly correlated, so "
            "P(DS >= 1) and P(DS2) are the two fitted curves; mutually exclusive states would split one exceedance "
            "by fixed weights, while the split between sliding and overturning changes with the demand and the item.",
            "The per-direction fragilities (`per_direction/`) are for those who build their own model: assigning "
            "both directions to the same units counts each unit twice.")


__all__ = ["OUTPUTS", "TABLES", "InventoryStudy", "Written", "case_count", "study_tables", "workers_of", "write_outputs"]
