"""The contents study of one building, end to end: :func:`run_contents_study`."""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from opsrock.contents.design import ContentsDesign
from opsrock.contents.design import quick as quick_design
from opsrock.contents.report import StudySummary, write_report

#: Files the study writes into its folder (besides ``campaigns/``, ``figures/`` and ``pelicun/``).
TABLES: dict[str, str] = {
    "fits": "fragility.csv", "ratios": "ratios.csv", "rule": "rule_reproduction.csv",
    "size": "size_regression.csv", "velocity": "velocity_definition.csv", "decomposition": "decomposition.csv",
    "sliding": "sliding.csv", "sweep": "sweep.csv", "paired": "paired_variants.csv",
}


#: Every output the study owns in its folder (globs relative to it): a new study replaces them all, and
#: removes those it does not write again (:func:`opsrock._files.staged_folder`); anything else in the folder
#: (the campaigns' stores, files of the user's) is kept.
OUTPUTS: tuple[str, ...] = ("report.md", *TABLES.values(), "figures/*.png", "pelicun/*.csv")


def _say(progress: bool, text: str) -> None:
    if progress:
        print(f"contents: {text}", file=sys.stderr, flush=True)


def _write_csv(df: pd.DataFrame, path: Path) -> Path:
    """``df`` as CSV at full precision (a float is written as its shortest round-trip repr: data files
    keep every digit; tables for reading round in the report)."""
    from opsrock._files import atomic_write

    atomic_write(path, lambda fh: df.to_csv(fh, index=False), durable=False)
    return path


def _tables(fits: pd.DataFrame, cases: pd.DataFrame, velocities: pd.DataFrame, design: ContentsDesign) -> dict:
    from opsrock.contents import tables
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
    from opsrock.contents.plots import plot_item, plot_rule

    folder = out / "figures"
    folder.mkdir(parents=True, exist_ok=True)
    paths = [plot_item(item, fits, cases, design, folder / f"{item}.png") for item in sorted(fits["item"].unique())]
    if "default" in design.variants:
        paths.append(plot_rule(result["ratios"], result["sweep"], design, folder / "fema_rule.png"))
    return paths


@dataclass(frozen=True)
class ContentsStudy:
    """What :func:`run_contents_study` computed and wrote.

    Parameters
    ----------
    design : ContentsDesign
        The study as run (after :func:`opsrock.contents.design.quick` when asked).
    summary : StudySummary
        Counts, timings and headline ratios.
    out_dir : str
        The output folder.
    report : str
        ``report.md``.
    tables : dict of str to str
        Table key of :data:`TABLES` -> CSV path.
    figures : list of str
        PNG paths.
    pelicun : dict of str to str
        pelicun file key -> path.
    """

    design: ContentsDesign
    summary: StudySummary
    out_dir: str
    report: str
    tables: dict[str, str]
    figures: list[str]
    pelicun: dict[str, str]


def run_contents_study(design: ContentsDesign, out_dir: str | Path, *, workers: int | None = None,
                       progress: bool = True, quick: bool = False, force: bool = False,
                       store_dir: str | Path | None = None) -> ContentsStudy:
    """Each FEMA P-58 unanchored item's overturning fragility on the floors of one building, beside
    FEMA P-58's, written into ``out_dir`` (resumable: a second call reuses every stored case).

    Parameters
    ----------
    design : ContentsDesign
        The building (period s, storeys, damping), floors, record set and records, IDA levels, items,
        variants, friction, record-bootstrap resamples and seed, and the sweep's buildings
        (:data:`opsrock.contents.design.SWEEP_BUILDINGS` for the chart of the medians against the period).
    out_dir : str or Path
        Output folder: ``report.md``, the tables (:data:`TABLES`), ``figures/``, ``pelicun/`` (and the
        campaigns, unless ``store_dir`` is given).
    workers, progress : int or None, bool
        Processes (default: all cores); progress on stderr.
    quick : bool
        A small study (:func:`opsrock.contents.design.quick`: six records, eight levels, ground and roof).
    force : bool
        Delete stored results of other settings in the campaigns' folders instead of refusing them.
    store_dir : str or Path, optional
        Where the campaigns keep their stores and case tables (large: about 35 MB per 25,000 cases);
        default ``out_dir/campaigns``. A report folder kept under version control names another one.

    Returns
    -------
    ContentsStudy
        The design run, the summary (counts, timings in s, headline ratios) and the paths written.
    """
    t_start = time.perf_counter()
    if quick:
        design = quick_design(design)
    from opsrock.contents.design import campaign_scenes

    scenes = campaign_scenes(design)  # every input checked (records, items) before anything is written
    out = Path(out_dir)
    store = Path(store_dir) if store_dir is not None else out / "campaigns"
    return _run(design, scenes, out, store, workers=workers, progress=progress, force=force, t_start=t_start)


def _run(design: ContentsDesign, scenes: dict, out: Path, store: Path, *, workers: int | None, progress: bool,
         force: bool, t_start: float) -> ContentsStudy:
    from opsrock.contents.campaigns import floor_velocities, run_campaigns
    from opsrock.contents.fits import fit_table, fit_tasks

    timings: dict[str, Any] = {}
    _say(progress, f"{sum(len(s.blocks) * s.records.n_per_block for s in scenes.values())} cases in "
                   f"{len(scenes)} campaigns ({', '.join(scenes)}) into {store}")
    cases, t_camp = run_campaigns(scenes, store, workers=workers, progress=progress, force=force)
    timings.update(t_camp)
    t0 = time.perf_counter()
    base = "rocking" if "rocking" in scenes else "friction"
    velocities = floor_velocities(scenes[base], store / base)
    tasks = fit_tasks(cases, design.n_boot, design.seed, velocities if base == "rocking" else None)
    _say(progress, f"{len(tasks)} fits ({design.n_boot} record resamples each)")
    fits = fit_table(tasks, workers)
    timings["fits_s"] = time.perf_counter() - t0
    _say(progress, f"tables, figures, pelicun files and report into {out}")
    written = _outputs(design, out, fits, cases, velocities, timings, t_start)
    _say(progress, f"done in {timings['total_s']:.1f} s: {written.report}")
    return written


def _outputs(design: ContentsDesign, out: Path, fits: pd.DataFrame, cases: pd.DataFrame, velocities: pd.DataFrame,
             timings: dict, t_start: float) -> ContentsStudy:
    """Write every output file through a staging folder: all of them replace their namesakes in ``out``
    together, and the outputs of an earlier study that this one does not write (:data:`OUTPUTS`) are
    removed, or (on any failure or Ctrl-C) nothing changes."""
    from opsrock._files import staged_folder
    from opsrock.contents.pelicun import write_pelicun_files

    t0 = time.perf_counter()
    with staged_folder(out, OUTPUTS) as stage:
        result = _tables(fits, cases, velocities, design)
        paths = {k: _write_csv(df, stage / TABLES[k]) for k, df in result.items() if not df.empty}
        figures = _figures(stage, fits, cases, result, design)
        pelicun = write_pelicun_files(fits, velocities[velocities["floor"].isin(set(cases["floor"]))], design,
                                      stage / "pelicun")
        timings["outputs_s"] = time.perf_counter() - t0
        timings["total_s"] = time.perf_counter() - t_start
        summary = _summary(cases, result, timings)
        report = write_report(stage / "report.md", design, result, summary)
        final = {p: out / Path(p).relative_to(stage) for p in [report, *paths.values(), *figures, *pelicun.values()]}
    return ContentsStudy(design=design, summary=summary, out_dir=str(out), report=str(final[report]),
                         tables={k: str(final[p]) for k, p in paths.items()}, figures=[str(final[p]) for p in figures],
                         pelicun={k: str(final[p]) for k, p in pelicun.items()})


def _summary(cases: pd.DataFrame, result: dict, timings: dict) -> StudySummary:
    ratios = result["ratios"]
    default = ratios[ratios["variant"] == "default"]["ratio_fema"].dropna()
    sweep = result["sweep"]["ratio_fema"].dropna() if not result["sweep"].empty else pd.Series(dtype=float)
    return StudySummary(n_cases=len(cases), n_failed=int((cases["status"] != "ok").sum()),
                        n_overturned=int(cases["overturned"].sum()), timings=timings,
                        ratio_range=(float(default.min()), float(default.max())) if len(default) else None,
                        sweep_ratio_range=(float(sweep.min()), float(sweep.max())) if len(sweep) else None)


__all__ = ["OUTPUTS", "TABLES", "ContentsStudy", "StudySummary", "run_contents_study"]
