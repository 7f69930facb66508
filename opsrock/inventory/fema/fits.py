"""The study's fragilities: one lognormal maximum-likelihood fit per campaign, item, variant, floor and
demand, on every finished case (all outcomes, as the project fits record campaigns), with 95 %
intervals from resampling whole records (:func:`opsrock.fragility.mle.fit_lognormal_mle`).

Demands: ``pfv`` (m/s, the peak absolute floor velocity of the scaled floor motion), ``pfa`` (g) and,
for the no-slip default on the building's floors, ``pfv_rel`` (m/s, the peak velocity relative to the
ground; point fit only), which measures what the PFV definition does to a median.
"""

from __future__ import annotations

import pandas as pd

from opsrock.constants import G

#: Demands fitted for every group: column of the case table -> (unit, divisor of the column).
DEMANDS: dict[str, tuple[str, float]] = {"pfv": ("m/s", 1.0), "pfa": ("g", G)}

#: Columns of the fit table, after the group's keys.
FIT_COLUMNS: tuple[str, ...] = ("median", "median_lo", "median_hi", "beta", "beta_lo", "beta_hi", "n_cases",
                                "n_overturned", "n_failed", "n_boot_used", "ok", "message")


def fit_tasks(cases: pd.DataFrame, n_boot: int, seed: int, relative: pd.DataFrame | None = None) -> list[tuple]:
    """The fits of a case table (:func:`opsrock.inventory.campaigns.run_campaigns` of
    :func:`opsrock.inventory.fema.campaigns.campaign_jobs`), as picklable tasks.

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
    from opsrock.inventory.fits import FitBatch

    batch = FitBatch(0, 0)  # each task names its resamples and seed
    for key, x, y, groups, n_boot, seed, n_failed in tasks:
        row = dict(key, n_cases=len(x), n_overturned=int(y.sum()), n_failed=n_failed, n_boot_used=0)
        batch.add(row, x, y, groups, never="never overturned within the levels", n_boot=n_boot, seed=seed)
    for row, f in batch.run(workers):
        row["n_boot_used"] = f.n_boot_used
    table = pd.DataFrame(batch.rows)
    order = ["campaign", "variant", "item", "floor", "demand"]
    return table.sort_values(order, kind="stable").reset_index(drop=True)[
        [*order, "floor_number", "building_period", "unit", *FIT_COLUMNS]]


__all__ = ["DEMANDS", "FIT_COLUMNS", "fit_table", "fit_tasks"]
