"""FEMA P-58's nine unanchored items in the shipped building, beside FEMA's fragilities: the contents study's
route :data:`FEMA_NINE` (``opsrock contents``), run end to end by :func:`opsrock.inventory.run.run_design`."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pandas as pd

from opsrock.fragility.cases import count_failed
from opsrock.inventory.fema.design import ContentsDesign, campaign_scenes
from opsrock.inventory.fema.report import StudySummary
from opsrock.inventory.stages import Route

#: Files the study writes into its folder (besides ``campaigns/``, ``figures/`` and ``pelicun/``), each with a
#: ``Units`` row after its header (:mod:`opsrock.inventory.fema.columns`).
TABLES: dict[str, str] = {
    "fits": "fragility.csv", "ratios": "ratios.csv", "rule": "rule_reproduction.csv",
    "size": "size_regression.csv", "velocity": "velocity_definition.csv", "decomposition": "decomposition.csv",
    "sliding": "sliding.csv", "sweep": "sweep.csv", "paired": "paired_variants.csv",
}


#: The tables of the study's pelicun folder (:func:`opsrock.inventory.fema.pelicun.pelicun_tables`), written as the
#: inventory study writes them (a ``Units`` row after the header): each item and floor's component, and the expected
#: numbers damaged over the records.
PELICUN_TABLES: dict[str, str] = {"components": "components.csv", "expected": "expected.csv"}


#: Every output the study owns in its folder (globs relative to it): a new study replaces them all, and
#: removes those it does not write again (:func:`opsrock._files.staged_folder`); anything else in the folder
#: (the campaigns' stores, files of the user's) is kept.
OUTPUTS: tuple[str, ...] = ("report.md", *TABLES.values(), *PELICUN_TABLES.values(), "figures/*.png", "pelicun/*.csv",
                             "pelicun/*.json", "pelicun/per_direction/*.csv")


def _tables(fits: pd.DataFrame, cases: pd.DataFrame, velocities: pd.DataFrame, design: ContentsDesign) -> dict:
    from opsrock.inventory.fema import tables
    from opsrock.published import fema_p58

    ratios = tables.ratio_table(fits, design)
    paired = [tables.paired_ratio(ratios, v).assign(variant=v) for v in design.variants if v != "default"]
    return {
        "fits": fits, "ratios": ratios, "rule": pd.DataFrame(fema_p58.reproduction()),
        "size": tables.size_regression(ratios), "velocity": tables.velocity_definition(fits, velocities, design),
        "decomposition": tables.decomposition(ratios), "sliding": tables.sliding_share(cases),
        "sweep": tables.sweep_table(fits, design),
        "paired": pd.concat(paired, ignore_index=True) if paired and "default" in design.variants else pd.DataFrame(),
    }


def _figures(out: Path, fits: pd.DataFrame, cases: pd.DataFrame, result: dict, design: ContentsDesign) -> list[Path]:
    from opsrock.inventory.fema.plots import plot_item, plot_rule

    folder = out / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    paths = [plot_item(item, fits, cases, design, folder / f"{item}.png") for item in sorted(fits["item"].unique())]
    if "default" in design.variants:
        paths.append(plot_rule(result["ratios"], result["sweep"], design, folder / "fema_rule.png"))
    return paths


def _jobs(a: Any) -> list:
    """The study's campaigns (no slip, friction, the sweep's roofs), in that order
    (:func:`opsrock.inventory.fema.campaigns.campaign_jobs`)."""
    from opsrock.inventory.fema.campaigns import campaign_jobs

    return campaign_jobs(a.scenes)


def _campaign_timings(runs: tuple) -> dict[str, Any]:
    """Each campaign's wall time (s), cases and cases computed now, and whether the friction campaign's floor
    motions were seeded, as the report and the summary name them."""
    out: dict[str, Any] = {}
    for r in runs:
        if r.name == "friction" and any(q.name == "rocking" for q in runs):
            out["friction_motions_seeded"] = r.seeded
        out.update({f"{r.name}_s": r.seconds, f"{r.name}_cases": r.n_cases, f"{r.name}_computed": r.n_computed})
    return out


def _fit(a: Any) -> dict[str, pd.DataFrame]:
    """The fits (:func:`opsrock.inventory.fema.fits.fit_table`), the floor velocities, the tables computed
    from them (:data:`TABLES`) and what the study's pelicun writer takes (:data:`PELICUN_TABLES`)."""
    from opsrock.inventory.fema.campaigns import floor_velocities
    from opsrock.inventory.fema.fits import fit_table, fit_tasks
    from opsrock.inventory.fema.pelicun import pelicun_tables

    base = "rocking" if "rocking" in a.scenes else "friction"
    velocities = floor_velocities(a.scenes[base], a.store / base)
    tasks = fit_tasks(a.cases, a.design.n_boot, a.design.seed, velocities if base == "rocking" else None)
    fits = fit_table(tasks, a.options.workers)
    own = velocities[velocities["floor"].isin(set(a.cases["floor"]))]
    return {**_tables(fits, a.cases, velocities, a.design), "velocities": velocities,
            "pelicun": pelicun_tables(fits, own, a.design)}


def _write(a: Any, stage: Path) -> Any:
    """The tables, figures, pelicun files and report into the staging folder ``stage``."""
    from opsrock.inventory.columns import write_table
    from opsrock.inventory.fema.columns import write_fema_table
    from opsrock.inventory.fema.report import write_report
    from opsrock.inventory.outputs import Written
    from opsrock.inventory.pelicun import write_pelicun_folder

    t0 = time.perf_counter()
    result = {k: v for k, v in a.tables.items() if k in TABLES}
    fits, pel = result["fits"], a.tables["pelicun"]
    a.say(f"tables, figures, pelicun files and report into {a.out}")
    paths = {k: write_fema_table(df, stage / TABLES[k]) for k, df in result.items() if not df.empty}
    paths.update({k: write_table(pel[k], stage / name) for k, name in PELICUN_TABLES.items() if k in pel})
    figures = _figures(stage, fits, a.cases, result, a.design)
    pelicun = write_pelicun_folder(pel["components"], pel["fits"], pel["demands"], pel["study"],
                                   stage / "pelicun") if pel else {}
    a.timings["outputs_s"] = time.perf_counter() - t0
    a.timings["total_s"] = time.perf_counter() - a.t_start
    timings = {**_campaign_timings(a.runs),
               **{k: v for k, v in a.timings.items() if k not in ("demands_s", "campaigns_s")}}
    summary = _summary(a.cases, result, timings)
    report = write_report(stage / "report.md", a.design, result, summary)
    return Written(paths, report, pelicun, tuple(figures), summary)


def _summary(cases: pd.DataFrame, result: dict, timings: dict) -> StudySummary:
    ratios = result["ratios"]
    default = ratios[ratios["variant"] == "default"]["ratio_fema"].dropna()
    sweep = result["sweep"]["ratio_fema"].dropna() if not result["sweep"].empty else pd.Series(dtype=float)
    return StudySummary(n_cases=len(cases), n_failed=count_failed(cases),
                        n_overturned=int(cases["overturned"].sum()), timings=timings,
                        ratio_range=(float(default.min()), float(default.max())) if len(default) else None,
                        sweep_ratio_range=(float(sweep.min()), float(sweep.max())) if len(sweep) else None)


#: FEMA P-58's nine in the shipped building, beside FEMA's fragilities (:class:`opsrock.inventory.stages.Route`):
#: the campaigns of :func:`opsrock.inventory.fema.design.campaign_scenes` (no floor-motion demand stage: the
#: campaigns filter the records through the building themselves), their fits, the tables and the pelicun files.
FEMA_NINE: Route = Route("fema-p58", campaign_scenes, _fit, _write, OUTPUTS, demands=lambda a: None, jobs=_jobs)


__all__ = ["FEMA_NINE", "OUTPUTS", "TABLES", "StudySummary"]
