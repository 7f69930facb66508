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


def no_fit(message: str) -> dict[str, Any]:
    """The fit fields of a row without a fit (NaN medians and betas, not ``ok``), saying why in ``message``."""
    nan = math.nan
    return {"median": nan, "median_lo": nan, "median_hi": nan, "beta": nan, "beta_lo": nan, "beta_hi": nan,
            "ok": False, "message": message}


def fitted(f: Any) -> dict[str, Any]:
    """The fit fields of a row fitted by ``f`` (:class:`~opsrock.fragility.mle.MLEFit`, medians in the demand's
    unit): its median and beta where it succeeded with a finite median (``ok``), NaN otherwise; its intervals and
    message as they are."""
    ok = bool(f.success and math.isfinite(f.mu))
    return {"median": f.mu if ok else math.nan, "median_lo": f.mu_lo, "median_hi": f.mu_hi,
            "beta": f.beta if ok else math.nan, "beta_lo": f.beta_lo, "beta_hi": f.beta_hi, "ok": ok,
            "message": f.message}


class FitBatch:
    """The rows of a fit table whose lognormal fits (maximum likelihood, record-bootstrap intervals:
    :func:`opsrock.fragility.mle.plan_mle`) run together, their resamples shared among worker processes
    (:func:`opsrock.fragility.mle.fit_plans`): every study's fit tables (the inventory's, in three dimensions,
    FEMA P-58's nine, both models side by side) are made by it.

    Parameters
    ----------
    n_boot : int
        Record-bootstrap resamples of each fit (0: none).
    seed : int
        Seed of the resamples.
    """

    def __init__(self, n_boot: int, seed: int) -> None:
        self.n_boot, self.seed = n_boot, seed
        self.rows: list[dict[str, Any]] = []
        self._plans: list[Any] = []
        self._where: list[int] = []

    def add(self, row: dict[str, Any], x: Any, y: Any, groups: Any, *, never: str = "",
            n_boot: int | None = None, seed: int | None = None) -> dict[str, Any]:
        """Add ``row``: fitted later to demands ``x`` (any unit) and outcomes ``y`` (bool) grouped by record
        (``groups``) if any case exceeded, else given :func:`no_fit` fields saying ``never`` now; ``n_boot`` and
        ``seed`` for this row only (default the batch's). Returns it."""
        if not y.any():
            row.update(no_fit(never))
        else:
            from opsrock.fragility.mle import plan_mle

            self._plans.append(plan_mle(x, y, n_boot=self.n_boot if n_boot is None else n_boot,
                                        seed=self.seed if seed is None else seed, groups=groups))
            self._where.append(len(self.rows))
        self.rows.append(row)
        return row

    def run(self, workers: int | None) -> list[tuple[dict[str, Any], Any]]:
        """Fit every row added with cases and fill it with :func:`fitted`; the ``(row, fit)`` pairs, for the fields a
        table adds of its own."""
        from opsrock.fragility.mle import fit_plans

        done = []
        for i, f in zip(self._where, fit_plans(self._plans, workers or 1)):
            self.rows[i].update(fitted(f))
            done.append((self.rows[i], f))
        return done


def fit_table(cases: pd.DataFrame, demands: pd.DataFrame, study: Any, workers: int | None) -> pd.DataFrame:
    """Every fit of the study (:data:`FIT_COLUMNS`), one row per item, floor, direction, outcome and demand.

    Parameters
    ----------
    cases : DataFrame
        :func:`opsrock.inventory.campaigns.run_campaigns`.
    demands : DataFrame
        :func:`opsrock.inventory.campaigns.floor_demands` (pfa m/s², pfv m/s).
    study : InventoryDesign
        Its ``inventory``, ``method``, ``slide_distance`` (m), ``n_boot`` and ``seed``.
    workers : int or None
        Processes for the resamples (None or 1: this one).
    """
    items = {it.id: it for it in study.inventory.items}
    scaled = _scaled_demands(cases, demands)
    batch = FitBatch(study.n_boot, study.seed)
    for (item, floor, direction), g in scaled.groupby(["item", "floor", "direction"], sort=False):
        ok = g[g["status"] == "ok"]
        for outcome, y in outcomes(ok, slide_distance_of(items[item], study)).items():
            for demand, (unit, _, _) in DEMANDS.items():
                row = _row_keys(items[item], floor, direction, outcome, demand, unit, study.method)
                x = ok[f"x_{demand}"].to_numpy(float)
                row.update(n_cases=len(ok), n_exceeded=int(y.sum()), n_failed=len(g) - len(ok),
                           n_records=int(ok["record"].nunique()), x_max=float(x.max()) if len(x) else math.nan)
                row["status"] = fit_status(False, math.nan, math.nan, row["n_exceeded"], row["n_cases"])
                batch.add(row, x, y.to_numpy(bool), ok["record"].to_numpy(),
                          never=f"never {_verb(outcome)} {_within(study.method)}")
    for row, f in batch.run(workers):
        if not row["ok"] and f.beta == 0.0 and math.isfinite(f.mu):  # separated outcomes: kept as a step at the gap
            row.update(median=f.mu, beta=f.beta)
        row["status"] = fit_status(row["ok"], f.mu, row["x_max"], row["n_exceeded"], row["n_cases"])
        if row["status"] == "extrapolated":
            row["message"] = _extrapolated(f.mu, row["x_max"], row)
    table = pd.DataFrame(batch.rows, columns=list(FIT_COLUMNS))
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


__all__ = ["DEMANDS", "FIT_COLUMNS", "FIT_STATUSES", "FitBatch", "fema_median", "fit_status", "fit_table", "fitted",
           "no_fit", "outcomes", "slide_distance_of"]
