"""The study's fragilities: one lognormal maximum-likelihood fit per campaign, item, variant, floor and
demand, on every finished case (all outcomes, as the project fits record campaigns), with 95 %
intervals from resampling whole records (:func:`opsrock.fragility.mle.fit_lognormal_mle`).

Demands: ``pfv`` (m/s, the peak absolute floor velocity of the scaled floor motion), ``pfa`` (g) and,
for the no-slip default on the building's floors, ``pfv_rel`` (m/s, the peak velocity relative to the
ground; point fit only), which measures what the PFV definition does to a median.
"""

from __future__ import annotations

import math
from typing import Any

import pandas as pd

from opsrock.constants import G

#: Demands fitted for every group: column of the case table -> (unit, divisor of the column).
DEMANDS: dict[str, tuple[str, float]] = {"pfv": ("m/s", 1.0), "pfa": ("g", G)}

#: Columns of the fit table, after the group's keys.
FIT_COLUMNS: tuple[str, ...] = ("median", "median_lo", "median_hi", "beta", "beta_lo", "beta_hi", "n_cases",
                                "n_overturned", "n_failed", "n_boot_used", "ok", "message")


def _nan_fit(message: str) -> dict[str, Any]:
    nan = math.nan
    return {"median": nan, "median_lo": nan, "median_hi": nan, "beta": nan, "beta_lo": nan, "beta_hi": nan,
            "n_boot_used": 0, "ok": False, "message": message}


def fit_tasks(cases: pd.DataFrame, n_boot: int, seed: int, relative: pd.DataFrame | None = None) -> list[tuple]:
    """The fits of a case table (:func:`opsrock.inventory.fema.campaigns.run_campaigns`), as picklable tasks.

    ``relative`` (:func:`opsrock.inventory.fema.campaigns.floor_velocities` of the no-slip campaign) adds the
    ``pfv_rel`` fits of the default variant on the building's floors."""
    tasks = []
    rel = None if relative is None else relative.set_index(["record", "floor"])["pfv_rel"]
    for (campaign, variant, item, floor), g in cases.groupby(["campaign", "variant", "item", "floor"], sort=True):
        ok = g[g["status"] == "ok"]
        keys = {"campaign": campaign, "variant": variant, "item": item, "floor": floor,
                "floor_number": int(g["floor_number"].iloc[0]), "building_period": float(g["building_period"].iloc[0])}
        y, groups, n_failed = ok["overturned"].to_numpy(bool), ok["record"].to_numpy(), int(len(g) - len(ok))
        for demand, (unit, div) in DEMANDS.items():
            x = ok[demand].to_numpy(float) / div
            tasks.append(({**keys, "demand": demand, "unit": unit}, x, y, groups, n_boot, seed, n_failed))
        if rel is not None and campaign == "rocking" and variant == "default" and keys["floor_number"] > 0:
            x = ok["scale"].to_numpy(float) * rel.loc[list(zip(ok["record"], ok["floor"]))].to_numpy(float)
            tasks.append(({**keys, "demand": "pfv_rel", "unit": "m/s"}, x, y, groups, 0, seed, n_failed))
    return tasks


def fit_table(tasks: list[tuple], workers: int | None = None) -> pd.DataFrame:
    """Run the fits (their record resamples shared among ``workers`` processes,
    :func:`opsrock.fragility.mle.fit_plans`: the same fits whatever ``workers``) and return one row per fit."""
    from opsrock.fragility.mle import fit_plans, plan_mle

    rows, plans, where = [], [], []
    for key, x, y, groups, n_boot, seed, n_failed in tasks:
        rows.append(dict(key, n_cases=len(x), n_overturned=int(y.sum()), n_failed=n_failed))
        if not y.any():
            rows[-1].update(_nan_fit("never overturned within the levels"))
        else:
            plans.append(plan_mle(x, y, n_boot=n_boot, seed=seed, groups=groups))
            where.append(len(rows) - 1)
    for i, f in zip(where, fit_plans(plans, workers or 1)):
        ok = bool(f.success and math.isfinite(f.mu))
        rows[i].update(median=f.mu if ok else math.nan, median_lo=f.mu_lo, median_hi=f.mu_hi,
                       beta=f.beta if ok else math.nan, beta_lo=f.beta_lo, beta_hi=f.beta_hi,
                       n_boot_used=f.n_boot_used, ok=ok, message=f.message)
    table = pd.DataFrame(rows)
    order = ["campaign", "variant", "item", "floor", "demand"]
    return table.sort_values(order, kind="stable").reset_index(drop=True)[
        [*order, "floor_number", "building_period", "unit", *FIT_COLUMNS]]


__all__ = ["DEMANDS", "FIT_COLUMNS", "fit_table", "fit_tasks"]
