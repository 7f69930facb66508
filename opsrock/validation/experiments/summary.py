"""The summary of validation case ``experiments`` and the case itself, :func:`run`."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pandas as pd

from opsrock._files import atomic_csv, atomic_metrics
from opsrock.analysis.restitution_scatter import compare
from opsrock.published.colombo_limestone import EventArrays, analysis_arrays, load_events, load_trials
from opsrock.validation.experiments.checks import data_checks, interval_checks, model_checks
from opsrock.validation.experiments.constants import MODELS, N_BOOT, N_BOOT_QUICK, PAPER_FACTOR, RELEASE_RATIOS
from opsrock.validation.experiments.figures import plot_decay, plot_restitution
from opsrock.validation.experiments.statistics import bootstrap, statistics
from opsrock.validation.experiments.tables import decay_outputs, restitution_outputs


def summarise(a: EventArrays, events: pd.DataFrame, est: dict, tables: dict, checks: list[dict]) -> dict:
    """The case's headline numbers (see README) and ``"passed"``.

    Parameters
    ----------
    a : EventArrays
        The impacts analysed.
    events : pandas.DataFrame
        Every impact row (the duplicate included).
    est : dict
        :func:`bootstrap` of :func:`statistics`.
    tables : dict
        :func:`restitution_outputs` and :func:`decay_outputs`.
    checks : list of dict
        Every check row.
    """
    f = est[("factor", "median all impacts")]
    m: dict = {"passed": all(c["passed"] for c in checks), "n_checks": len(checks),
               "n_checks_failed": sum(not c["passed"] for c in checks),
               "n_event_rows": len(events), "n_trials_analysed": int(np.unique(a.trial).size),
               "n_impacts_analysed": a.trial.size,
               "share_above_1_all_rows": float(np.mean(events["measured_source_angular_ratio"] > 1.0)),
               "fitted_factor": f[0], "fitted_factor_lo": f[1], "fitted_factor_hi": f[2],
               "paper_factor_in_interval": bool(f[1] <= PAPER_FACTOR <= f[2])}
    for key, name in ((("all", "all", "share_above_1"), "share_above_1"), (("all", "1", "rmse_e_R"), "rmse_first_e_R"),
                      (("all", "1", "rmse_paper"), "rmse_first_paper"), (("all", "1", "bias_e_R"), "bias_first_e_R"),
                      (("all", "1", "bias_paper"), "bias_first_paper")):
        v = est[("restitution",) + key]
        m.update({name: v[0], f"{name}_lo": v[1], f"{name}_hi": v[2]})
    wild = np.abs(a.q - 1.0) > 0.5
    length = np.repeat(np.bincount(a.trial), np.bincount(a.trial))  # rows are contiguous per trial
    position = a.event / length
    m.update({"share_wild": float(wild.mean()), "share_wild_first_fifth": float(wild[position <= 0.2].mean()),
              "share_wild_last_tenth": float(wild[position > 0.9].mean())})
    fac = tables["factor"].set_index("name")
    robust = fac.drop(index=["median ratios <= 1"])
    m.update({"factor_variants_min": float(robust["estimate"].min()),
              "factor_variants_max": float(robust["estimate"].max()),
              "factor_all_with_duplicate": float(np.median(analysis_arrays(events, keep_duplicate=True).q))})
    single = tables["restitution_by_impact"].dropna(subset=["n"])
    m.update({"median_factor_per_impact_min": float(single["factor"].min()),
              "median_factor_per_impact_max": float(single["factor"].max())})
    bins = tables["restitution_by_impact"].set_index("impacts")
    for label in ("1-10", "11-20", "21-40", "41-80", "81+"):
        m[f"factor_impacts_{label}"] = float(bins.loc[label, "factor"])
    dr = tables["drift"].set_index("name")
    for name, key in (("drift_impact_per10_1_20", "impact number, impacts 1-20: slope per 10 impacts"),
                      ("drift_impact_per10_1_40", "impact number, impacts 1-40: slope per 10 impacts"),
                      ("drift_alpha_per_0.1rad", "slenderness, all impacts: slope per 0.1 rad of alpha"),
                      ("drift_alpha_per_0.1rad_first10", "slenderness, impacts 1-10: slope per 0.1 rad of alpha"),
                      ("odd_minus_even", "odd minus even impacts 1-20 (medians)")):
        m.update({name: dr.loc[key, "estimate"], f"{name}_lo": dr.loc[key, "lo"], f"{name}_hi": dr.loc[key, "hi"]})
    g = tables["restitution_by_group"]
    g = g[g["group"] != "all"]
    contains = (g["factor_lo"] <= PAPER_FACTOR) & (g["factor_hi"] >= PAPER_FACTOR)
    excludes = (g["factor_hi"] < f[0]) | (g["factor_lo"] > f[0])
    m["n_groups_interval_excludes_fitted"] = int(excludes[g["impacts"] == "all"].sum())
    m["n_groups_interval_contains_0.95"] = int(contains[g["impacts"] == "all"].sum())
    m["n_groups_interval_contains_0.95_impact_1"] = int(contains[g["impacts"] == "1"].sum())
    err = tables["decay_errors"]
    rigid = err["model"].map(lambda x: MODELS[x][0] == "housner")
    for _, r in err[(err["group"] == "all") & ~(rigid & (err["release_ratio"] != RELEASE_RATIOS[0]))].iterrows():
        m[f"decay_rmse_log_{r['model'].replace(' ', '_')}_{r['release_ratio']:g}alpha_1-{r['window']}"] = r["rmse_log"]
    return m


def scatter_outputs(out_dir: Path) -> dict:
    """The fixed against uncertain restitution comparison (:mod:`opsrock.analysis.restitution_scatter`) into
    ``out_dir/scatter/`` and ``scatter.csv``; its counts for the summary."""

    table = compare(out_dir / "scatter")
    atomic_csv(out_dir / "scatter.csv", table)
    unc, pap = table[table["variant"] == "uncertain"], table[table["variant"] == "paper"]
    return {"scatter_cells": int(len(unc)), "scatter_uncertain_inside": int((unc["verdict"] == "inside").sum()),
            "scatter_paper_inside": int((pap["verdict"] == "inside").sum()),
            "scatter_max_added_beta": float(unc["added_beta"].max())}


def run(out_dir: Path, quick: bool = False) -> dict:
    """Run the case into ``out_dir``: tables (CSV, full precision), ``restitution.png``, ``decay.png``,
    ``checks.csv``, ``summary.csv`` (``_quick`` suffixes for the quick form).

    Parameters
    ----------
    out_dir : pathlib.Path
        Folder of the outputs (created if missing).
    quick : bool
        :data:`N_BOOT_QUICK` resamples; the decay of :data:`QUICK_GROUPS` at the first release angle.

    Returns
    -------
    dict
        :func:`summarise`, with ``"wall_time_s"`` (s) and ``"quick"``.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t0, sfx = time.perf_counter(), "_quick" if quick else ""
    events, trials = load_events(), load_trials()
    checks = data_checks(events, trials)
    a = analysis_arrays(events)
    est = bootstrap(a, statistics, N_BOOT_QUICK if quick else N_BOOT)
    checks += interval_checks(est)
    tables = restitution_outputs(a, est)
    decay, geometry = decay_outputs(a, events, est[("factor", "median all impacts")][0], quick)
    tables.update(decay)
    checks += model_checks(tables["decay_predicted"], tables["decay_runs"])
    for name in ("decay_predicted", "decay_errors"):  # the rigid body's rows repeat at every release angle
        t = tables[name]
        keep = t["model"].map(lambda x: MODELS[x][0] != "housner") | (t["release_ratio"] == RELEASE_RATIOS[0])
        tables[name] = t[keep]
    for name, df in tables.items():
        atomic_csv(out_dir / f"{name}{sfx}.csv", df)
    atomic_csv(out_dir / f"checks{sfx}.csv", pd.DataFrame(checks))
    plot_restitution(a, tables["restitution_by_group"], tables["restitution_by_impact"].dropna(subset=["n"]),
                     est[("factor", "median all impacts")], out_dir / f"restitution{sfx}.png")
    plot_decay(tables["decay_measured"], tables["decay_predicted"], geometry, out_dir / f"decay{sfx}.png")
    m = summarise(a, events, est, tables, checks)
    if not quick:  # restitution as an uncertain input on the FEMA P695 IDA scene (three campaigns)
        m.update(scatter_outputs(out_dir))
    m.update({"quick": quick, "n_boot": N_BOOT_QUICK if quick else N_BOOT, "wall_time_s": time.perf_counter() - t0})
    atomic_metrics(out_dir / f"summary{sfx}.csv", m)
    return m


__all__ = ["run", "scatter_outputs", "summarise"]
