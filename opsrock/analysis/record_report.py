"""``opsrock fragility``: the record fragility workflow of a record campaign.

    opsrock fragility RUN_DIR|cases.csv --out DIR [--n-boot N] [--seed S] [--outcome as_simulated|first_exceedance]
                      [--robustness-sets N] [--workers N]

Reads the ``cases.csv`` of a record scene's run (:func:`read_cases`), fits every IM
(:mod:`opsrock.fragility.record_study`), and writes into ``DIR``: ``ims.csv``, ``measure_fits.csv``,
``resurrections.csv``, ``sufficiency.csv``, ``frequencies.csv``, ``blocks.csv``, ``fragility_pelicun.csv``
(FEMA P-58 / pelicun damage model), ``figures/`` (:mod:`opsrock.plots.record_fragility`) and ``report.md``
(:func:`opsrock.report.records.write_markdown`, given what was computed here); with ``--robustness-sets N``
also the pulse study over N seeded block sets (``robustness.csv``). A campaign solved with friction (its
table has the contact columns) also gets the fragility of sliding beyond :data:`SLIDE_DISTANCES`
(:mod:`opsrock.fragility.sliding`): ``sliding.csv``, ``figures/sliding.png``, a section of the report and
the ``SLIDE`` components in ``fragility_pelicun.csv``; any other campaign's outputs are as they were. Every table
but pelicun's file has a units row after its header (:mod:`opsrock.analysis.record_columns`).
"""

from __future__ import annotations

import json
import math
import time
from pathlib import Path

import numpy as np
import pandas as pd

from opsrock._files import read_table
from opsrock.analysis.record_columns import write_record_table
from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.fragility.sliding import DEFAULT_DISTANCES
from opsrock.report.records import RecordReport, write_markdown

#: Distances (m) of the sliding section: 5 cm (a cabinet against a wall), 20 cm and 50 cm.
SLIDE_DISTANCES: tuple[float, ...] = DEFAULT_DISTANCES

#: Tables of the study (:class:`opsrock.fragility.record_study.RecordStudy` fields), each ``<name>.csv``.
STUDY_TABLES: tuple[str, ...] = ("ims", "measure_fits", "resurrections", "sufficiency", "frequencies", "blocks")
#: Every table the report may write: the study's, ``robustness`` and ``sliding`` (only when computed) and
#: the pelicun file.
TABLES: tuple[str, ...] = (*STUDY_TABLES, "robustness", "sliding", "fragility_pelicun")

#: Every output the report owns in its folder (globs relative to it): ``opsrock fragility`` replaces them
#: all and removes those a new report does not write (:func:`opsrock._files.staged_folder`: the sliding
#: table and figure of an earlier report on a campaign solved with friction, its ``robustness.csv``); any
#: other file in the folder (a campaign's store, the user's files) is kept.
OUTPUTS: tuple[str, ...] = ("report.md", *(f"{t}.csv" for t in TABLES), "figures/*.png")


def read_cases(source: str | Path) -> pd.DataFrame:
    """The ``cases.csv`` of a record campaign, checked: ``source`` is the campaign's folder or the file.

    Refused, with the file and the reason (:class:`~opsrock.errors.InputError`): a file that is not a
    table, a table of a pulse campaign, missing columns, text in a number column, no rows, a finished case
    without a finite demand, peak rotation or slide (NaN, inf) or with a negative peak or peak slide (the
    file, the column and the row with its case id), and a table shorter than the campaign it came from
    (its ``manifest.json`` beside it says how many cases).
    """
    from opsrock.campaign.cases import units_row

    p = Path(source)
    csv_path = p / "cases.csv" if p.is_dir() else p
    if not csv_path.is_file():
        raise InputError(f"cases: no cases.csv at {source!s} (give the --out folder of `opsrock run` or a cases.csv)")
    try:
        skip = units_row(csv_path)  # the units row of a cases.csv, checked; none in one of an older opsrock
        cases = read_table(csv_path, skiprows=skip)
    except InputError:
        raise
    except (ValueError, UnicodeDecodeError, pd.errors.ParserError) as exc:
        raise InputError(f"cases: {csv_path} cannot be read as a table: {str(exc).splitlines()[0]}") from None
    if "record" not in cases.columns:
        raise InputError(f"cases: {csv_path} is not from a record scene (no 'record' column); "
                         "pulse campaigns go through `opsrock reproduce`")
    _check_table(csv_path, cases, 2 if skip is None else 3)
    _check_complete(csv_path, len(cases))
    return cases


#: Columns of a record campaign's table the study reads, and those of them that must hold numbers.
_STUDY_COLUMNS = ("block", "record", "floor", "level", "level_value", "status", "overturned", "rocked",
                  "theta_max_over_alpha", "pfa", "pfv", "magnitude", "distance_km", "building_period",
                  *(f"IM{k}" for k in range(1, 10)))
_NUMBER_COLUMNS = ("level", "level_value", "theta_max_over_alpha", "pfa", "pfv", "magnitude", "distance_km",
                   "building_period", *(f"IM{k}" for k in range(1, 10)))
#: Number columns of a campaign solved with friction that the sliding section reads (when present).
_SLIDE_NUMBER_COLUMNS = ("slide_max", "slide_residual")
#: Columns every finished case (status ok) must give as a finite number, and those of them that are peaks
#: or distances, never negative (the fits take their logarithms or compare them with distances).
_FINISHED_FINITE = ("level_value", "pfa", "pfv", "theta_max_over_alpha", "slide_max", "slide_residual")
_NOT_NEGATIVE = ("pfa", "pfv", "theta_max_over_alpha", "slide_max")


def _check_table(csv_path: Path, cases: pd.DataFrame, first: int) -> None:
    """Refuse a table the study cannot read; ``first``: the file's line of the first case (2, or 3 after a units
    row), for the line a message names."""
    missing = [c for c in _STUDY_COLUMNS if c not in cases.columns]
    if missing:
        raise InputError(f"cases: {csv_path} lacks the column(s) {', '.join(missing)} of a record campaign's table")
    if cases.empty:
        raise InputError(f"cases: {csv_path} holds no cases (a header only)")
    for col in (*_NUMBER_COLUMNS, *(c for c in _SLIDE_NUMBER_COLUMNS if c in cases.columns)):
        if not pd.api.types.is_numeric_dtype(cases[col]):
            bad = pd.to_numeric(cases[col], errors="coerce").isna() & cases[col].notna()
            row = int(bad.to_numpy().nonzero()[0][0]) if bad.any() else 0
            raise InputError(f"cases: {csv_path}, column {col!r}, row {row + first}: "
                             f"{str(cases[col].iloc[row])!r} is not a number")
    if not cases["status"].isin(("ok", "failed")).all():
        bad = cases.loc[~cases["status"].isin(("ok", "failed")), "status"].iloc[0]
        raise InputError(f"cases: {csv_path}, column 'status': {bad!r} is neither 'ok' nor 'failed'")
    _check_finished(csv_path, cases, first)


def _check_finished(csv_path: Path, cases: pd.DataFrame, first: int) -> None:
    """Every finished case gives its demands, peak rotation and slides as finite numbers, the peaks and the
    peak slide never negative: else the file, the column and the row (line of the file, and case id)."""
    finished = cases["status"].eq("ok").to_numpy()
    for col in (c for c in _FINISHED_FINITE if c in cases.columns):
        values = cases[col].to_numpy(float)
        bad = finished & ~np.isfinite(values)
        what = "is not a finite number (a finished case needs one)"
        if not bad.any() and col in _NOT_NEGATIVE:
            bad, what = finished & (values < 0), "is negative (a peak or a distance cannot be)"
        if bad.any():
            row = int(np.flatnonzero(bad)[0])
            case = f" (case {cases['case_id'].iloc[row]})" if "case_id" in cases.columns else ""
            raise InputError(f"cases: {csv_path}, column {col!r}, row {row + first}{case}: {float(values[row])!r} "
                             f"{what}")


def _check_complete(csv_path: Path, n_rows: int) -> None:
    """A ``cases.csv`` beside its campaign's manifest must hold every case of the campaign."""
    manifest = csv_path.parent / "manifest.json"
    if not manifest.is_file():
        return
    try:
        n_cases = int(json.loads(manifest.read_text())["n_cases"])
    except (OSError, ValueError, KeyError, TypeError):
        return
    if n_rows != n_cases:
        raise InputError(f"cases: {csv_path} holds {n_rows} of the {n_cases} cases of its campaign "
                         f"({manifest}); re-run `opsrock run` on the campaign to rebuild it")


#: The scene's measure (``[records.intensity] measure``) -> its axis label, quantity and unit.
MEASURE_LABELS: dict[str, str] = {
    "pfa_g": "PFA, peak floor acceleration (g)",
    "pfa_ratio": "PFA / (g tan alpha) (dimensionless)",
    "": "no levels (the motions as recorded)",
    "unknown": "the scene's level value (its measure not recognised from the cases; see the scene file)",
}
#: Relative tolerance (dimensionless) of recognising the measure: a level is set by scaling the motion to it
#: exactly, so its value and the scaled motion's measure agree to round-off.
MEASURE_RTOL: float = 1e-6


def scene_measure(cases: pd.DataFrame) -> str:
    """The scene's measure recognised from its cases: ``"pfa_g"`` when every finished case's ``level_value``
    is its PFA in g, ``"pfa_ratio"`` when it is its ``pfa_ratio``, ``""`` for a cloud (no level values),
    ``"unknown"`` otherwise."""
    ok = cases[cases["status"] == "ok"]
    level = ok["level_value"].to_numpy(float)
    finite = np.isfinite(level)
    if not finite.any():
        return ""
    candidates = [("pfa_g", ok["pfa"].to_numpy(float) / G)]
    if "pfa_ratio" in ok.columns:
        candidates.append(("pfa_ratio", ok["pfa_ratio"].to_numpy(float)))
    elif "alpha" in ok.columns:
        candidates.append(("pfa_ratio", ok["pfa"].to_numpy(float) / (G * np.tan(ok["alpha"].to_numpy(float)))))
    for name, value in candidates:
        if np.allclose(level[finite], value[finite], rtol=MEASURE_RTOL, atol=0.0):
            return name
    return "unknown"


def scene_method(cases: pd.DataFrame) -> str:
    """``"cloud"`` (no level values), ``"ida"`` (a motion at several levels) or ``"msa"`` (each motion at one
    level of several)."""
    if not np.isfinite(cases["level_value"].to_numpy(float)).any():
        return "cloud"
    per_motion = cases.groupby(["block", "record", "floor"], sort=False)["level"].nunique()
    return "ida" if (per_motion > 1).any() else "msa"


def record_fits(blocks: pd.DataFrame, cases: pd.DataFrame, method: str) -> pd.DataFrame:
    """The study's per-block, per-floor fits (:attr:`RecordStudy.blocks`) in the inventory study's ``fits``
    form (:func:`opsrock.inventory.summary.item_floor_table` reads it): PFA in g, PFV in m/s, the failed
    cases of each block and floor counted from ``cases``, the pelicun ID of each row."""
    from opsrock.fragility.pelicun_export import component_id
    from opsrock.inventory.fits import fit_status

    failed = cases[cases["status"] != "ok"].groupby(["block", "floor"]).size()
    rows = []
    for _, r in blocks.iterrows():
        ok = bool(r["success"]) and math.isfinite(r["mu"])
        to_unit = 1.0 / G if r["demand"] == "pfa" else 1.0
        rows.append({"item": r["block"], "description": r["block"], "floor": str(r["floor"]), "direction": "1",
                     "outcome": "overturning", "demand": r["demand"], "unit": "g" if r["demand"] == "pfa" else "m/s",
                     "method": method, **{k: float(r[m]) * to_unit for k, m in
                                          (("median", "mu"), ("median_lo", "mu_lo"), ("median_hi", "mu_hi"))},
                     "beta": float(r["beta"]), "beta_lo": float(r["beta_lo"]), "beta_hi": float(r["beta_hi"]),
                     "n_cases": int(r["n_cases"]), "n_exceeded": int(r["n_overturned"]),
                     "n_failed": int(failed.get((r["block"], r["floor"]), 0)), "n_records": int(r["n_records"]),
                     "ok": ok, "message": str(r["message"]),
                     "status": fit_status(ok, r["mu"], math.inf, int(r["n_overturned"]), int(r["n_cases"])),
                     "fema_id": "", "fema_median": math.nan, "ratio_fema": math.nan,
                     "pelicun_id": component_id(r["block"], str(r["floor"]), r["demand"])})
    return pd.DataFrame(rows)


def _exports(fits: pd.DataFrame):
    """The pelicun components of the fitted rows of :func:`record_fits` (medians back in m/s² and m/s), and
    the rows not exported with why."""
    from opsrock.fragility.pelicun_export import ComponentFragility

    out, skipped = [], []
    for _, r in fits.iterrows():
        median = r["median"] * (G if r["demand"] == "pfa" else 1.0)
        if r["ok"] and math.isfinite(median) and r["beta"] > 0:
            out.append(ComponentFragility(r["pelicun_id"], r["demand"], float(median), float(r["beta"])))
        else:
            skipped.append(f"{r['pelicun_id']}: {r['message']}")
    return out, skipped


def _slide_exports(sliding: pd.DataFrame):
    """The pelicun components of the per-floor sliding fits (``opsrock.<block>.<floor>.SLIDE<mm>MM.<PFA|PFV>``),
    and the rows not exported with why."""
    from opsrock.fragility.pelicun_export import ComponentFragility, component_id

    out, skipped = [], []
    for _, r in sliding.iterrows():
        cid = component_id(r["block"], str(r["floor"]), r["demand"], f"SLIDE{round(r['distance'] * 1000)}MM")
        if r["success"] and math.isfinite(r["median"]) and r["beta"] > 0:
            out.append(ComponentFragility(cid, r["demand"], float(r["median"]), float(r["beta"])))
        else:
            skipped.append(f"{cid}: {r['message']}")
    return out, skipped


def write_record_report(cases: pd.DataFrame, out: Path, *, n_boot: int = 200, seed: int = 0,
                        outcome: str = "as_simulated", robustness_sets: int = 0, workers: int = 1,
                        source: str = "", demand_levels: dict[str, tuple[float, ...]] | None = None) -> RecordReport:
    """Run the study on ``cases`` and write every output into ``out``.

    Parameters
    ----------
    cases : pandas.DataFrame
        :func:`read_cases`.
    out : pathlib.Path
        Output folder (created).
    n_boot, seed : int
        Record resamples of every interval, and their seed (no unit).
    outcome : str
        Outcome convention of the fits (:data:`opsrock.fragility.ida.OUTCOMES`).
    robustness_sets : int
        Block sets of the pulse study (0: not run).
    workers : int
        Processes.
    source : str
        Where the cases came from (named in the report).
    demand_levels : dict of str to tuple of float, optional
        Where the per-block table gives P(overturning): ``{"pfv": (m/s, ...), "pfa": (g, ...)}`` (default
        :data:`opsrock.inventory.summary.DEFAULT_LEVELS`).
    """
    from opsrock.fragility.pelicun_export import write_pelicun_csv
    from opsrock.fragility.record_study import RecordStudySettings, record_fragility
    from opsrock.inventory import summary

    t0 = time.perf_counter()
    out.mkdir(parents=True, exist_ok=True)
    study = record_fragility(cases, RecordStudySettings(n_boot=n_boot, seed=seed, outcome=outcome), workers=workers)
    t_fit = time.perf_counter() - t0
    robust = None
    if robustness_sets:
        from opsrock.analysis.robustness import ranking_robustness

        robust = ranking_robustness(robustness_sets, seed=seed, workers=workers).shares
        write_record_table(robust, out / "robustness.csv")
    measure = scene_measure(cases)
    for name in STUDY_TABLES:
        write_record_table(getattr(study, name), out / f"{name}.csv", measure)
    fits = record_fits(study.blocks, cases, scene_method(cases))
    comps, skipped = _exports(fits)
    sliding = _sliding(cases, out, n_boot, seed, workers)
    if sliding is not None:
        slide_comps, slide_skipped = _slide_exports(sliding)
        comps, skipped = comps + slide_comps, skipped + slide_skipped
    pel = write_pelicun_csv(comps, out / "fragility_pelicun.csv")
    table = summary.item_floor_table(fits, demand_levels)
    figs = _figures(cases, study, summary.curve_table(fits), robust, sliding, out / "figures", workers,
                    MEASURE_LABELS[measure])
    report = RecordReport(study=study, robustness=robust, robustness_sets=robustness_sets, sliding=sliding,
                          slide_distances=SLIDE_DISTANCES, pelicun=pel, skipped=skipped, figures=figs,
                          timings={"fits_s": t_fit, "total_s": time.perf_counter() - t0}, source=source,
                          table=table, findings=summary.floor_findings(table), failures=summary.failure_table(cases),
                          measure=measure, method=fits["method"].iloc[0] if len(fits) else scene_method(cases))
    write_markdown(out, report)
    return report


def _figures(cases: pd.DataFrame, study, curves: pd.DataFrame, robust: pd.DataFrame | None,
             sliding: pd.DataFrame | None, fig: Path, workers: int, measure_label: str) -> dict[str, Path]:
    """The report's figures from the computed study (independent: drawn at once with ``workers`` > 1):
    ``curves`` the per-block, per-floor curve table, ``robust`` and ``sliding`` None where not computed,
    ``measure_label`` the IDA axis (the scene's measure and its unit). Each block's fragility is drawn per
    floor, never pooled."""
    from opsrock.inventory.plots import plot_item_fragility
    from opsrock.plots import record_fragility as rplots

    jobs = {"ida": (rplots.plot_ida_curves, (study.cases, fig / "ida_curves.png", measure_label)),
            "ranking": (rplots.plot_im_ranking, (study.ims, study.frequencies, fig / "im_ranking.png", robust))}
    for block in dict.fromkeys(curves["item"]):
        jobs[f"fragility:{block}"] = (plot_item_fragility, (curves, block, fig / f"fragility_{block}.png"))
    if sliding is not None:
        jobs["sliding"] = (rplots.plot_sliding_fragility, (cases, sliding, fig / "sliding.png"))
    if workers > 1:
        from opsrock._pool import deferred_interrupts
        from opsrock.plots import figure_pool

        with figure_pool(min(workers, len(jobs))) as pool:
            with deferred_interrupts():
                futures = {k: pool.submit(fn, *args) for k, (fn, args) in jobs.items()}
            return {k: f.result() for k, f in futures.items()}
    return {k: fn(*args) for k, (fn, args) in jobs.items()}


def _sliding(cases: pd.DataFrame, out: Path, n_boot: int, seed: int, workers: int) -> pd.DataFrame | None:
    """The sliding fragilities of a campaign solved with friction, per block and floor (``sliding.csv``:
    :func:`opsrock.fragility.sliding.sliding_table` of each floor's cases, its ``floor`` column after ``block`` and
    the unit of the row's demand and medians after ``demand``: the cases' PFA in m/s2, PFV in m/s), None for another
    campaign."""
    from opsrock.campaign.cases import UNITS as CASE_UNITS
    from opsrock.fragility.sliding import has_slides, sliding_table

    if not has_slides(cases):
        return None
    parts = []
    for floor in dict.fromkeys(cases["floor"]):
        part = sliding_table(cases[cases["floor"] == floor], SLIDE_DISTANCES, n_boot=n_boot, seed=seed, workers=workers)
        part.insert(1, "floor", floor)
        parts.append(part)
    table = pd.concat(parts, ignore_index=True)
    table.insert(table.columns.get_loc("demand") + 1, "unit", table["demand"].map(CASE_UNITS))
    write_record_table(table, out / "sliding.csv")
    return table


__all__ = ["MEASURE_LABELS", "OUTPUTS", "SLIDE_DISTANCES", "STUDY_TABLES", "TABLES", "read_cases", "record_fits",
           "scene_measure", "scene_method", "write_record_report"]
