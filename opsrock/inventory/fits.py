"""Each item's fragility per floor and direction, in the floor's PFV (m/s) and PFA (g): overturning, and
sliding beyond a distance where friction is modelled; lognormal maximum likelihood on every finished case
(:func:`opsrock.fragility.mle.plan_mle`, as the contents study fits), 95 % intervals from resampling whole
records, the resamples shared among worker processes (:func:`opsrock.fragility.mle.fit_plans`).

The demand of a case is the *floor* motion's, scaled: ``scale x PFV`` and ``scale x PFA / g`` of the motion
as recorded at that floor and direction (:func:`opsrock.inventory.campaigns.floor_demands`), also for an item
on a support (whose campaign scaled the floor motion before its oscillator), so that the fragility is in the
demand pelicun assesses.

Outcomes perfectly separated by the demand (every case below a gap survived, every case above it did not) have
no finite maximum-likelihood fit: the row's ``ok`` is False, its ``status`` ``no fit``, and it keeps the gap's
middle as ``median`` with ``beta`` 0 (a step), which :mod:`opsrock.inventory.components` uses as such.

A fit whose median lies beyond the largest demand of its cases (a few exceedances at the top levels) is kept,
with the status ``extrapolated`` (column ``status``, :data:`FIT_STATUSES`) and a message that says so.

Sliding "beyond ``slide_distance``" is ``slide_max >= slide_distance``: the peak displacement of the base
relative to the floor (m), whether the item then overturned or not (the item's own ``slide_distance`` where the
inventory gives one, else the study's). ``displaced`` is sliding beyond it *or* overturning: the first damage
state of the item's pelicun component, which overturning (the second) follows
(:mod:`opsrock.inventory.components`). These fits are per direction (``direction`` 1 or 2: the item rocking
and sliding in that plane alone); the item's damage under both components at once is
:mod:`opsrock.inventory.components`'.

``ratio_fema`` is opsrock's PFV median over FEMA P-58's (:data:`opsrock.published.fema_p58.ITEMS`) for the
overturning rows of an item that names one of FEMA's nine unanchored items; FEMA's fragilities are in PFV
only, so a PFA row has none.
"""

from __future__ import annotations

import math
from typing import Any

import pandas as pd

from opsrock.constants import G

#: Demands fitted: name -> (unit, column of the floor demands, divisor).
DEMANDS: dict[str, tuple[str, str, float]] = {"pfv": ("m/s", "pfv", 1.0), "pfa": ("g", "pfa", G)}

#: Columns of ``fits.csv``, in order (the report reads them).
FIT_COLUMNS: tuple[str, ...] = (
    "item", "description", "floor", "direction", "outcome", "demand", "unit", "method", "median", "median_lo",
    "median_hi", "beta", "beta_lo", "beta_hi", "n_cases", "n_exceeded", "n_failed", "n_records", "ok", "status", "message",
    "fema_id", "fema_median", "ratio_fema", "pelicun_id",
)  # fmt: skip


#: A fit's ``status``: ``fitted``; ``extrapolated`` (fitted, the median beyond the largest demand of its cases);
#: ``never`` (no case exceeded); ``always`` (every case did); ``no fit`` (the fit failed).
FIT_STATUSES: tuple[str, ...] = ("fitted", "extrapolated", "never", "always", "no fit")


def fit_status(ok: bool, median: float, x_max: float, n_exceeded: int, n_cases: int) -> str:
    """The :data:`FIT_STATUSES` entry of one fit: ``ok`` and its ``median`` (any unit), the largest demand of its
    cases ``x_max`` (that unit), the cases that exceeded and the finished cases."""
    if ok and math.isfinite(median):
        return "extrapolated" if median > x_max else "fitted"
    if n_exceeded == 0:
        return "never"
    return "always" if n_exceeded >= n_cases > 0 else "no fit"


def outcomes(cases: pd.DataFrame, slide_distance: float) -> dict[str, pd.Series]:
    """The outcomes a group of cases is fitted for: ``overturning`` always; when friction is modelled (a
    ``slide_max`` was computed) also ``sliding`` (``slide_max >= slide_distance``, m) and ``displaced`` (sliding
    that far or overturning)."""
    out = {"overturning": cases["overturned"].astype(bool)}
    slide = cases["slide_max"].astype(float) if "slide_max" in cases else pd.Series(math.nan, index=cases.index)
    if slide.notna().any():
        out["sliding"] = slide.fillna(0.0) >= slide_distance
        out["displaced"] = out["sliding"] | out["overturning"]
    return out


def slide_distance_of(item: Any, study: Any) -> float:
    """The distance (m) beyond which ``item`` counts as displaced: its own, else the study's."""
    return item.slide_distance if getattr(item, "slide_distance", None) is not None else study.slide_distance


def fit_table(cases: pd.DataFrame, demands: pd.DataFrame, study: Any, workers: int | None) -> pd.DataFrame:
    """Every fit of the study (:data:`FIT_COLUMNS`), one row per item, floor, direction, outcome and demand.

    Parameters
    ----------
    cases : DataFrame
        :func:`opsrock.inventory.campaigns.run_groups`.
    demands : DataFrame
        :func:`opsrock.inventory.campaigns.floor_demands` (pfa m/s², pfv m/s).
    study : InventoryDesign
        Its ``inventory``, ``method``, ``slide_distance`` (m), ``n_boot`` and ``seed``.
    workers : int or None
        Processes for the resamples (None or 1: this one).
    """
    from opsrock.fragility.mle import fit_plans, plan_mle

    items = {it.id: it for it in study.inventory.items}
    scaled = _scaled_demands(cases, demands)
    rows, plans, where = [], [], []
    for (item, floor, direction), g in scaled.groupby(["item", "floor", "direction"], sort=False):
        ok = g[g["status"] == "ok"]
        for outcome, y in outcomes(ok, slide_distance_of(items[item], study)).items():
            for demand, (unit, _, _) in DEMANDS.items():
                row = _row_keys(items[item], floor, direction, outcome, demand, unit, study.method)
                row.update(n_cases=len(ok), n_exceeded=int(y.sum()), n_failed=len(g) - len(ok),
                           n_records=int(ok["record"].nunique()))
                row["status"] = fit_status(False, math.nan, math.nan, row["n_exceeded"], row["n_cases"])
                if not y.any():
                    row.update(_no_fit(f"never {_verb(outcome)} {_within(study.method)}"))
                else:
                    x = ok[f"x_{demand}"].to_numpy(float)
                    plans.append(plan_mle(x, y.to_numpy(bool), n_boot=study.n_boot, seed=study.seed,
                                          groups=ok["record"].to_numpy()))
                    where.append((len(rows), float(x.max())))
                rows.append(row)
    for (i, x_max), f in zip(where, fit_plans(plans, workers or 1)):
        ok = bool(f.success and math.isfinite(f.mu))
        step = not ok and f.beta == 0.0 and math.isfinite(f.mu)  # separated outcomes: kept as a step at the gap
        rows[i].update(median=f.mu if ok or step else math.nan, median_lo=f.mu_lo, median_hi=f.mu_hi,
                       beta=f.beta if ok or step else math.nan, beta_lo=f.beta_lo, beta_hi=f.beta_hi, ok=ok,
                       status=fit_status(ok, f.mu, x_max, rows[i]["n_exceeded"], rows[i]["n_cases"]))
        rows[i]["message"] = _extrapolated(f.mu, x_max, rows[i]) if rows[i]["status"] == "extrapolated" else f.message
    table = pd.DataFrame(rows, columns=list(FIT_COLUMNS))
    table["ratio_fema"] = table["median"] / table["fema_median"]
    return table


def _extrapolated(median: float, x_max: float, row: dict) -> str:
    """The message of a fit whose median lies beyond every demand of its cases."""
    return (f"extrapolated: the median {median:.3g} {row['unit']} lies beyond the largest demand of the cases "
            f"({x_max:.3g} {row['unit']}), from {row['n_exceeded']} of {row['n_cases']} cases")


def _scaled_demands(cases: pd.DataFrame, demands: pd.DataFrame) -> pd.DataFrame:
    """``cases`` with ``x_pfv`` (m/s) and ``x_pfa`` (g): the scale factor times the floor motion's demand."""
    d = demands.set_index(["record", "floor", "direction"])
    keys = list(zip(cases["record"], cases["floor"], cases["direction"]))
    out = cases.copy()
    for demand, (_, column, div) in DEMANDS.items():
        out[f"x_{demand}"] = cases["scale"].to_numpy(float) * d[column].reindex(keys).to_numpy(float) / div
    return out


def _row_keys(item, floor: str, direction: str, outcome: str, demand: str, unit: str, method: str) -> dict:
    fema = fema_median(item.fema_id) if outcome == "overturning" and demand == "pfv" else math.nan
    return {"item": item.id, "description": item.description, "floor": floor, "direction": direction,
            "outcome": outcome, "demand": demand, "unit": unit, "method": method, "fema_id": item.fema_id,
            "fema_median": fema, "pelicun_id": ""}


def fema_median(fema_id: str) -> float:
    """FEMA P-58's median PFV at overturning (m/s) of one of its nine unanchored items; NaN for any other ID."""
    from opsrock.published.fema_p58 import ITEMS

    return next((it.median_mps for it in ITEMS if it.fema_id == fema_id), math.nan)


def _verb(outcome: str) -> str:
    return {"overturning": "overturned", "sliding": "slid that far"}.get(outcome, "slid that far or overturned")


def _within(method: str) -> str:
    return "within the levels" if method == "ida" else "under the motions as recorded"


def _no_fit(message: str) -> dict[str, Any]:
    nan = math.nan
    return {"median": nan, "median_lo": nan, "median_hi": nan, "beta": nan, "beta_lo": nan, "beta_hi": nan,
            "ok": False, "message": message}


__all__ = ["DEMANDS", "FIT_COLUMNS", "FIT_STATUSES", "fit_status", "slide_distance_of", "fema_median", "fit_table", "outcomes"]
