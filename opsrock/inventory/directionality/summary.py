"""The directionality study's numbers: every fit and every table the report shows (the report and the figures,
:mod:`opsrock.inventory.directionality.report`, compute nothing).

Fits (:func:`fit_table`): lognormal maximum likelihood on every finished case with 95 % intervals from
resampling whole record pairs (:func:`opsrock.fragility.mle.plan_mle`, :func:`~opsrock.fragility.mle.fit_plans`),
per model, item, floor and orientation (each azimuth, and all of them pooled: ``"all"``), in each demand
convention (:data:`CONVENTIONS`): the peak floor velocity of direction 1 (``pfv_1``), of direction 2 (``pfv_2``),
the larger of the two (``pfv_max``), the non-directional value (``pfv_nd``: the peak of the horizontal velocity
vector's length), and the velocity along the item's weaker axis (``pfv_weak``, the planar analysis's own).

pelicun assesses a non-directional component with ``1.2 x max(PFV_1, PFV_2)`` (its ``NonDirectionalMultipliers``,
default ``{"ALL": 1.2}``, docs/guide/directionality.md). A planar fragility of median ``theta_p`` used that way
stands for a three-dimensional one of median ``theta_p / 1.2`` in ``pfv_max``; the factor the three-dimensional
results ask for is ``factor_implied = theta_p / theta_3d(pfv_max)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock.fragility.cases import count_failed
from opsrock.inventory.fits import FitBatch

#: Demand conventions fitted for each model.
CONVENTIONS: dict[str, tuple[str, ...]] = {"3d": ("pfv_1", "pfv_2", "pfv_max", "pfv_nd", "pfv_weak"),
                                           "planar": ("pfv_weak", "pfv_max")}

#: pelicun's default multiplier of the larger directional demand for a non-directional component.
PELICUN_FACTOR: float = 1.2

#: Label of the fits that pool every orientation.
ALL: str = "all"

#: Columns of the fit table.
FIT_COLUMNS: tuple[str, ...] = ("model", "item", "floor", "azimuth", "demand", "median", "median_lo", "median_hi",
                                "beta", "beta_lo", "beta_hi", "n_cases", "n_overturned", "n_failed", "n_records",
                                "ok", "message")

#: Verdicts of a cell of the map of where planar analysis suffices.
VERDICTS: tuple[str, ...] = ("suffices", "differs", "never overturns", "no fit")


def _azimuth_label(azimuth: float) -> str:
    return f"{azimuth:g}"


def _groups(cases: pd.DataFrame):
    """``(model, item, floor, azimuth label), cases`` for each orientation and for all of them pooled."""
    for (model, item, floor), g in cases.groupby(["model", "item", "floor"], sort=False):
        for azimuth, h in g.groupby("azimuth", sort=True):
            yield (model, item, floor, _azimuth_label(float(azimuth))), h
        yield (model, item, floor, ALL), g


def fit_table(cases: pd.DataFrame, design: Any, workers: int = 1) -> pd.DataFrame:
    """Every fit of the study (:data:`FIT_COLUMNS`; medians in m/s).

    Parameters
    ----------
    cases : DataFrame
        The campaigns' cases (:func:`opsrock.inventory.campaigns.run_campaigns` of the study's campaigns).
    design : DirectionalityDesign
        Its ``n_boot`` and ``seed``.
    workers : int
        Processes for the resamples.
    """
    batch = FitBatch(design.n_boot, design.seed)
    for (model, item, floor, azimuth), g in _groups(cases):
        ok = g[g["status"] == "ok"]
        y = ok["overturned"].to_numpy(bool)
        for demand in CONVENTIONS[model]:
            row = {"model": model, "item": item, "floor": floor, "azimuth": azimuth, "demand": demand,
                   "n_cases": len(ok), "n_overturned": int(y.sum()), "n_failed": len(g) - len(ok),
                   "n_records": int(ok["record"].nunique())}
            batch.add(row, ok[demand].to_numpy(float), y, ok["record"].to_numpy(),
                      never="never overturned within the levels")
    batch.run(workers)
    return pd.DataFrame(batch.rows, columns=list(FIT_COLUMNS))


def _wide(fits: pd.DataFrame) -> pd.DataFrame:
    """One row per item, floor and orientation: ``median_<model>_<demand>`` and ``beta_<model>_<demand>``."""
    f = fits.assign(key=fits["model"] + "_" + fits["demand"])
    keys = ["item", "floor", "azimuth"]
    med = f.pivot_table(index=keys, columns="key", values="median", aggfunc="first", dropna=False)
    beta = f.pivot_table(index=keys, columns="key", values="beta", aggfunc="first", dropna=False)
    n = f[f["demand"] == "pfv_max"].pivot_table(index=keys, columns="model", values="n_overturned", aggfunc="first")
    out = pd.concat([med.add_prefix("median_"), beta.add_prefix("beta_"), n.add_prefix("n_overturned_")], axis=1)
    return out.reset_index()


def verdict(ratio: float, n_3d: float, n_planar: float, tolerance: float) -> str:
    """A map cell's verdict (:data:`VERDICTS`): ``suffices`` if the three-dimensional median lies within
    ``tolerance`` (a fraction) of the planar one (``ratio`` = 3-D / planar, same demand), ``differs`` if not,
    ``never overturns`` if neither model overturned, ``no fit`` if a median is missing."""
    if n_3d == 0 and n_planar == 0:
        return "never overturns"
    if not math.isfinite(ratio):
        return "no fit"
    return "suffices" if abs(ratio - 1.0) <= tolerance else "differs"


def directionality_table(fits: pd.DataFrame, cases: pd.DataFrame, design: Any, items: tuple) -> pd.DataFrame:
    """The main table: per item, floor and orientation (``all``: pooled) the 3-D medians in every convention
    (m/s), the planar one along the weaker axis, their ratio in the same demand (``ratio_weak``), the factor on
    ``max(PFV_1, PFV_2)`` the 3-D results imply for the planar fragility (``factor_implied``, beside pelicun's
    1.2), the share of 3-D overturnings over a corner, and the map's verdict."""
    wide = _wide(fits)
    slender = {it.id: it.b_over_h for it in items}
    wide.insert(1, "b_over_h", wide["item"].map(slender))
    wide["ratio_weak"] = wide["median_3d_pfv_weak"] / wide["median_planar_pfv_weak"]
    wide["factor_implied"] = wide["median_planar_pfv_weak"] / wide["median_3d_pfv_max"]
    wide["pelicun_over_3d"] = wide["factor_implied"] / PELICUN_FACTOR
    mech = mechanisms(cases).set_index(["item", "floor", "azimuth"])["share_corner"]
    wide["share_corner"] = [mech.get(k, math.nan) for k in zip(wide["item"], wide["floor"], wide["azimuth"])]
    wide["verdict"] = [verdict(r, a, b, design.tolerance) for r, a, b in
                       zip(wide["ratio_weak"], wide["n_overturned_3d"], wide["n_overturned_planar"])]
    order = {a: k for k, a in enumerate([*(_azimuth_label(x) for x in design.azimuths), ALL])}
    items_order = {it.id: k for k, it in enumerate(items)}
    wide = wide.assign(_i=wide["item"].map(items_order), _a=wide["azimuth"].map(order))
    return wide.sort_values(["_i", "floor", "_a"], kind="stable").drop(columns=["_i", "_a"]).reset_index(drop=True)


def mechanisms(cases: pd.DataFrame) -> pd.DataFrame:
    """Per item, floor and orientation (and pooled), the 3-D overturnings over an edge and over a corner
    (:attr:`opsrock.result.PlanSummary.overturned_over`) and the corner's share of them."""
    three = cases[(cases["model"] == "3d") & (cases["status"] == "ok")]
    rows = []
    for (_, item, floor, azimuth), g in _groups(three):
        over = g.loc[g["overturned"], "overturned_over"].astype(str)
        n, edge, corner = len(over), int((over == "edge").sum()), int((over == "corner").sum())
        rows.append({"item": item, "floor": floor, "azimuth": azimuth, "n_overturned": n, "n_edge": edge,
                     "n_corner": corner, "n_unstated": n - edge - corner,
                     "share_corner": corner / (edge + corner) if edge + corner else math.nan})
    return pd.DataFrame(rows, columns=["item", "floor", "azimuth", "n_overturned", "n_edge", "n_corner",
                                       "n_unstated", "share_corner"])


def cost_table(cases: pd.DataFrame) -> pd.DataFrame:
    """Time per case (s) of each campaign's solver (its finished and failed cases), measured in this run: wall time
    (``*_s``) and the solving thread's CPU time (``cpu_*_s``: what a loaded machine does not stretch; NaN for cases
    read from a store written before opsrock measured it), and the ratio of each median to the fastest planar
    solver's (the median: the first case a worker solves also compiles the solver's kernel, when the compiled
    cache is cold, which the mean would count)."""
    rows = []
    for (model, solver), g in cases.groupby(["model", "solver_name"], sort=True):
        failed = count_failed(g)  # n_cases: the finished ones, as in every table (opsrock.inventory.columns)
        row = {"model": model, "solver": solver, "n_cases": len(g) - failed, "n_failed": failed}
        for prefix, column in (("", "wall_time_s"), ("cpu_", "cpu_time_s")):
            t = (g[column].astype(float) if column in g else pd.Series(math.nan, index=g.index)).dropna()
            row.update({f"{prefix}mean_s": float(t.mean()) if len(t) else math.nan,  # (an empty median warns)
                        f"{prefix}median_s": float(t.median()) if len(t) else math.nan,
                        f"{prefix}total_s": float(t.sum()) if len(t) else math.nan})
        rows.append(row)
    table = pd.DataFrame(rows)
    for prefix in ("", "cpu_"):
        planar = table.loc[table["model"] == "planar", f"{prefix}median_s"]
        table[f"{prefix}ratio_to_planar"] = table[f"{prefix}median_s"] / (float(planar.min()) if len(planar)
                                                                          else math.nan)
    return table[["model", "solver", "n_cases", "n_failed", "mean_s", "median_s", "total_s", "ratio_to_planar",
                  "cpu_mean_s", "cpu_median_s", "cpu_total_s", "cpu_ratio_to_planar"]]


def demand_table(demands: pd.DataFrame) -> pd.DataFrame:
    """The pairs' floor demands with ``nd_over_max = pfv_nd / pfv_max``: the part of pelicun's 1.2 that is the
    motion's own (the velocity vector's peak over the larger directional peak, between 1 and sqrt 2)."""
    return demands.assign(nd_over_max=demands["pfv_nd"] / demands["pfv_max"])


def study_tables(fits: pd.DataFrame, cases: pd.DataFrame, demands: pd.DataFrame, design: Any,
                 items: tuple) -> dict[str, pd.DataFrame]:
    """Every table the study writes, by file stem."""
    main = directionality_table(fits, cases, design, items)
    return {"directionality": main, "fits": fits, "mechanisms": mechanisms(cases), "cost": cost_table(cases),
            "demands": demand_table(demands),
            "map": main[["item", "b_over_h", "floor", "azimuth", "median_3d_pfv_weak", "median_planar_pfv_weak",
                         "ratio_weak", "verdict"]]}


def headline(tables: dict[str, pd.DataFrame], cases: pd.DataFrame, timings: dict[str, float]) -> dict[str, Any]:
    """The numbers the command prints and the report leads with."""
    main, cost = tables["directionality"], tables["cost"]
    pooled = main[main["azimuth"] == ALL]
    each = main[main["azimuth"] != ALL]
    mech = tables["mechanisms"]
    mech_all = mech[mech["azimuth"] == ALL]
    three = cost[cost["model"] == "3d"]
    fits = tables["fits"]
    planar_all = fits[(fits["model"] == "planar") & (fits["azimuth"] == ALL) & (fits["demand"] == "pfv_weak")]
    half = (planar_all["median_hi"] - planar_all["median_lo"]) / (2.0 * planar_all["median"])
    counts = each["verdict"].value_counts()
    return {
        "n_cases": len(cases), "n_failed": count_failed(cases),
        "n_computed": int(timings.get("n_computed", 0)), "wall_time_s": float(timings.get("total_s", math.nan)),
        "timings": {k: float(v) for k, v in timings.items() if k.endswith("_s")},
        "cost_ratio_3d": float(three["ratio_to_planar"].max()) if len(three) else math.nan,
        "cost_ratio_3d_cpu": float(three["cpu_ratio_to_planar"].max()) if len(three) else math.nan,
        "factor_implied_median": _median(pooled["factor_implied"]),
        "factor_implied_range": _range(pooled["factor_implied"]),
        "ratio_weak_range": _range(pooled["ratio_weak"]),
        "nd_over_max_mean": float(tables["demands"]["nd_over_max"].mean()),
        "share_corner": float(mech_all["n_corner"].sum() / max(1, mech_all["n_edge"].sum() + mech_all["n_corner"].sum())),
        "cells": {v: int(counts.get(v, 0)) for v in VERDICTS},
        "planar_ci_halfwidth_median": _median(half),
    }


def _median(values: pd.Series) -> float:
    v = values.astype(float)
    v = v[np.isfinite(v)]
    return float(v.median()) if len(v) else math.nan


def _range(values: pd.Series) -> tuple[float, float] | None:
    v = values.astype(float)
    v = v[np.isfinite(v)]
    return (float(v.min()), float(v.max())) if len(v) else None


@dataclass(frozen=True)
class ReportInputs:
    """Everything the report shows, computed here.

    Parameters
    ----------
    design : DirectionalityDesign
        The study as run.
    tables : dict of str to DataFrame
        :func:`study_tables`.
    headline : dict
        :func:`headline`.
    figures : dict of str to str
        Figure key -> path relative to the report.
    left_out : tuple of str
        The shipped inventories' round items, which the study leaves out
        (:func:`opsrock.inventory.directionality.study.round_items`).
    """

    design: Any
    tables: dict
    headline: dict
    figures: dict
    left_out: tuple[str, ...] = ()


def report_inputs(design: Any, tables: dict, head: dict, figures: list,
                  left_out: tuple[str, ...] = ()) -> ReportInputs:
    """:class:`ReportInputs` of the study (figures relative to the report's folder; ``left_out`` the round items the
    study left out, :func:`opsrock.inventory.directionality.study.left_out`)."""
    return ReportInputs(design, tables, head, {Path(p).stem: f"figures/{Path(p).name}" for p in figures}, left_out)


__all__ = ["ALL", "CONVENTIONS", "FIT_COLUMNS", "PELICUN_FACTOR", "VERDICTS", "ReportInputs", "cost_table",
           "demand_table", "directionality_table", "fit_table", "headline", "mechanisms", "report_inputs",
           "study_tables", "verdict"]
