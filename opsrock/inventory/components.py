"""Each item on each floor as **one** pelicun component: the physical units counted once, damaged by whatever
the two horizontal floor components do to them together, in the demand pelicun will give the component.

The demand (:data:`DEMAND`): ``pfv_max``, the larger of the two directions' peak floor velocities (m/s). pelicun
gives a non-directional component (``Demand-Directional`` 0) the largest of the directional demands at its
location times ``NonDirectionalMultipliers`` (NHERI-SimCenter/pelicun 3.10, ``pelicun/model/demand_model.py``,
``_assemble_required_demand_data``: "the maximum of all available directions ... scaling it using the
non-directional multiplier"; FEMA P-58's default 1.2); the pelicun folder sets the multiplier to
:data:`NONDIRECTIONAL_MULTIPLIER` = 1.0, so that pelicun's demand is exactly ``pfv_max``, the demand these
fragilities are fitted in.

The damage states (:data:`STATES`), **sequential**: ``DS1`` *displaced* (slid beyond ``slide_distance``, or
rolled that far on casters, or overturned: the limit state ``displaced``) and ``DS2`` *overturned* (the limit
state ``overturning``). Every overturned unit is also displaced, so the limit states are nested and a unit is in
the highest one it passed: pelicun's sequential damage states, whose limit-state capacities it draws perfectly
correlated within a unit (``pelicun/model/damage_model.py``, ``_create_dmg_RVs``: "we assume perfectly correlated
limit state random variables", the anchor of the first), so that ``P(DS >= 1) = max(P_displaced, P_overturning)``
and ``P(DS2) = P_overturning`` at every demand. Not mutually exclusive: that form splits one limit state's
exceedance between the states by fixed weights, while the split changes with the demand and the item (a wide
cabinet slides and never overturns, a slender bookcase overturns before it slides far). Without friction
modelled (no slip) an item has one damage state, DS1 *overturned*.

Where the items were modelled in three dimensions (:mod:`opsrock.inventory.three_d`) each case already felt both
components: the fragility is fitted to its cases against ``pfv_max`` (the azimuths pooled, a record bootstrap
for the intervals); where the demand separated the outcomes perfectly (no finite maximum-likelihood fit) the limit
state is a step at the middle of the gap in ``pfv_max``, as a planar direction's below, given to pelicun as a
deterministic capacity (a blank ``Family``: pelicun 3.10, ``damage_model.py``, "Normalize missing / empty family
specifications to `deterministic`"). Where they were modelled in each plane (the planar route), each direction's fragility
``P_d`` (:mod:`opsrock.inventory.fits`, in that direction's PFV) is combined into one: under record ``r`` with
directional PFVs ``v_1r, v_2r`` the unit reaches the state if it does in either plane, the planes taken as
independent given their demands, ``1 - prod_d (1 - P_d(v_dr))``; at ``pfv_max = x`` each record's directions
keep their proportions, ``v_dr = x v_dr / max_d v_dr``, and the curve is the mean over the records. The
lognormal given to pelicun is the one through that curve's quantiles at probabilities ``Phi(z)``, ``z`` in
:data:`Z_GRID` (least squares in ``ln x``); ``max_error`` is its largest distance (in probability) from the
combined curve. A direction in which the item never reached the state contributes nothing; one whose outcomes
were perfectly separated by the demand (no finite maximum-likelihood fit) contributes a step at the middle of the
gap (it reaches the state above it, certainly; where every record's combined curve is that one step, the
component's limit state is the step, a deterministic capacity, as in three dimensions); one whose fit failed otherwise (or in which every case reached it)
leaves the item without a component, with the reason.

``components.csv`` (:data:`COMPONENT_COLUMNS`): one row per item, floor and limit state.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pandas as pd
from scipy.optimize import brentq
from scipy.stats import norm

from opsrock.fragility.lognormal import fragility_probability

#: The demand of the components (m/s): the larger directional PFV, pelicun's non-directional demand with the
#: multiplier :data:`NONDIRECTIONAL_MULTIPLIER`.
DEMAND: str = "pfv_max"

#: pelicun's ``NonDirectionalMultipliers`` in the folder: 1.0, so that its demand is :data:`DEMAND` itself.
NONDIRECTIONAL_MULTIPLIER: float = 1.0

#: Limit states in pelicun's order -> (the fits' outcome, the damage state it leads to).
STATES: dict[str, tuple[str, str]] = {"displaced": ("displaced", "displaced (slid beyond the distance, or overturned)"),
                                      "overturned": ("overturning", "overturned")}

#: What ``source`` adds for a limit state whose outcomes the demand separated perfectly (no finite
#: maximum-likelihood lognormal): a step at the middle of the gap, which pelicun takes as a deterministic capacity.
STEP_SOURCE: str = " (a step at the gap of separated outcomes)"

#: Standard normal quantiles at which the combined curve is matched (P from 0.006 to 0.994).
Z_GRID: np.ndarray = np.linspace(-2.5, 2.5, 21)

#: Columns of ``components.csv``.
COMPONENT_COLUMNS: tuple[str, ...] = (
    "item", "floor", "pelicun_id", "limit_state", "ls", "demand", "unit", "median", "median_lo", "median_hi",
    "beta", "beta_lo", "beta_hi", "status", "source", "max_error", "n_records", "message",
)  # fmt: skip


def component_id(item: str, floor: str) -> str:
    """``opsrock.<item>.<floor>`` (``floor`` made safe for an ID): one component per item and floor."""
    from opsrock.excitations.records import safe_name

    return f"opsrock.{item}.{safe_name(floor)}"


def record_pfv(demands: pd.DataFrame, floor: str) -> pd.DataFrame:
    """The recorded PFV (m/s) of ``floor``: one row per record, one column per direction, and ``pfv_max``."""
    d = demands[demands["floor"].astype(str) == str(floor)]
    wide = d.pivot_table(index="record", columns="direction", values="pfv", aggfunc="first", sort=False).dropna()
    wide.columns = [str(c) for c in wide.columns]
    return wide.assign(pfv_max=wide.max(axis=1))


def _direction_curves(rows: pd.DataFrame) -> tuple[dict[str, tuple[float, float]], str | None]:
    """Per direction ``(median, beta)`` of a fitted row (m/s), None where it never reached the state; or the
    reason there is no combination."""
    curves = {}
    for r in rows.itertuples():
        if (bool(r.ok) or r.beta == 0.0) and math.isfinite(r.median):  # a fit, or separated outcomes' step
            curves[str(r.direction)] = (float(r.median), float(r.beta))
        elif r.status != "never":
            return {}, f"direction {r.direction}: {r.message}"
    return curves, None


def _probability(x: np.ndarray, median: float, beta: float) -> np.ndarray:
    """A direction's P at demands ``x`` (m/s): lognormal, or a step at ``median`` where ``beta`` is 0 (separated
    outcomes: the gap's middle)."""
    return (x >= median).astype(float) if beta == 0.0 else fragility_probability(x, median, beta)


def combined_probability(x: np.ndarray, curves: dict[str, tuple[float, float]], pfv: pd.DataFrame) -> np.ndarray:
    """P(the state) at ``pfv_max = x`` (m/s): the mean over the records of ``1 - prod_d (1 - P_d)`` (module
    docstring); ``pfv`` from :func:`record_pfv`."""
    x = np.atleast_1d(np.asarray(x, dtype=float))
    survive = np.ones((len(pfv), x.size))
    for d, (median, beta) in curves.items():
        share = (pfv[d] / pfv["pfv_max"]).to_numpy(float)[:, None]
        survive *= 1.0 - _probability(share * x[None, :], median, beta)
    return (1.0 - survive).mean(axis=0)


def lognormal_through(curves: dict[str, tuple[float, float]], pfv: pd.DataFrame) -> tuple[float, float, float]:
    """``(median, beta, max_error)`` of the lognormal through the combined curve's quantiles (module docstring)."""
    lo = 0.5 * min(m * math.exp(-6.0 * b) for m, b in curves.values())
    hi = max(m * math.exp(6.0 * b) for m, b in curves.values()) / max(float((pfv.drop(columns="pfv_max").min(axis=1)
                                                                              / pfv["pfv_max"]).min()), 1e-6)
    xs = []
    for z in Z_GRID:
        p = float(norm.cdf(z))
        xs.append(math.exp(brentq(lambda u: combined_probability(math.exp(u), curves, pfv)[0] - p,
                                  math.log(lo), math.log(hi), xtol=1e-12)))
    slope, intercept = np.polyfit(Z_GRID, np.log(xs), 1)
    median, beta = math.exp(intercept), float(slope)
    if not beta > 1e-9:  # every quantile the same demand (to the fit's round-off): a step there
        median, beta = float(np.median(xs)), 0.0
    grid = np.geomspace(xs[0], xs[-1], 200)
    err = float(np.max(np.abs(fragility_probability(grid, median, beta) - combined_probability(grid, curves, pfv))))
    return median, beta, err


def _row(item: str, floor: str, ls: str, n_records: int) -> dict[str, Any]:
    nan = math.nan
    return {"item": item, "floor": floor, "pelicun_id": component_id(item, floor), "limit_state": ls, "ls": "",
            "demand": DEMAND, "unit": "m/s", "median": nan, "median_lo": nan, "median_hi": nan, "beta": nan,
            "beta_lo": nan, "beta_hi": nan, "status": "never", "source": "", "max_error": nan,
            "n_records": n_records, "message": ""}


def planar_components(fits: pd.DataFrame, demands: pd.DataFrame, design: Any) -> pd.DataFrame:
    """:data:`COMPONENT_COLUMNS` from the planar route's per-direction PFV fits (m/s) and the recorded floor
    demands (m/s): each item and floor's limit states, the two planes combined (module docstring)."""
    rows = []
    pfv_fits = fits[fits["demand"] == "pfv"]
    for (item, floor), g in pfv_fits.groupby(["item", "floor"], sort=False):
        pfv = record_pfv(demands, floor)
        slides = bool((g["outcome"] == "displaced").any())
        for ls, (outcome, _) in STATES.items():
            if ls == "displaced" and not slides:
                continue
            row = _row(item, str(floor), ls, len(pfv))
            directions = sorted(g["direction"].astype(str).unique())
            row["source"] = (f"planar: direction {directions[0]} alone" if len(directions) == 1 else
                             "planar: directions " + " and ".join(directions) + " combined")
            curves, why = _direction_curves(g[g["outcome"] == outcome])
            if why is not None:
                row.update(status="no fit", message=why)
            elif not curves:
                row["message"] = f"never {'overturned' if ls == 'overturned' else 'displaced'} in any direction"
            else:
                median, beta, err = lognormal_through(curves, pfv)
                steps = [d for d, (_, b) in curves.items() if b == 0.0]
                if steps:
                    row["source"] += f" (direction {' and '.join(steps)}: a step at the gap of separated outcomes)"
                if beta == 0.0:  # every record's combined curve a step at one demand: that step, as the 3-D route's
                    row["message"] = "every direction a step at the same demand: a deterministic capacity"
                row.update(median=median, beta=beta, max_error=err, status="fitted")
            rows.append(row)
    return _numbered(pd.DataFrame(rows, columns=list(COMPONENT_COLUMNS)))


def three_d_components(cases: pd.DataFrame, demands: pd.DataFrame, design: Any, workers: int | None) -> pd.DataFrame:
    """:data:`COMPONENT_COLUMNS` from the cases of boxes in plan (:mod:`opsrock.inventory.three_d`): each item and
    floor's limit states fitted to every finished case against ``scale x pfv_max`` (m/s), the azimuths pooled,
    record-bootstrap intervals (:func:`opsrock.fragility.mle.plan_mle`); the cases of anything not in the design's
    inventory (the box beside a round item, :func:`opsrock.inventory.three_d.box_of`) are left out."""
    from opsrock.inventory.fits import FitBatch, fit_status, outcomes, slide_distance_of

    items = {it.id: it for it in design.inventory.items}
    batch = FitBatch(design.n_boot, design.seed)
    mine = cases[cases["item"].isin(list(items))]  # the boxes run beside round items are no components
    for (item_id, floor), g in mine.groupby(["item", "floor"], sort=False):
        ok = g[g["status"] == "ok"]
        pfv = record_pfv(demands, floor)["pfv_max"]
        x = ok["scale"].to_numpy(float) * pfv.reindex(ok["record"]).to_numpy(float)
        found = outcomes(ok, slide_distance_of(items[item_id], design))
        for ls, (outcome, _) in STATES.items():
            if outcome not in found:
                continue
            y = found[outcome].to_numpy(bool)
            row = _row(item_id, str(floor), ls, int(ok["record"].nunique()))
            row["source"] = f"3-D ({ok['azimuth'].nunique() if 'azimuth' in ok else 1} azimuths pooled)"
            row.update(n=len(y), k=int(y.sum()), x_max=float(x.max()) if len(x) else math.nan)
            batch.add(row, x, y, ok["record"].to_numpy(),
                      never=f"never {'overturned' if ls == 'overturned' else 'displaced'} in {len(y)} cases")
    for row, f in batch.run(workers):
        good, n, k = row["ok"], row["n"], row["k"]
        row.update(status="fitted" if good else fit_status(False, math.nan, math.nan, k, n),
                   message="" if good else f.message)
        if not good and f.beta == 0.0 and math.isfinite(f.mu):  # separated outcomes: a step, as the planar route's
            row.update(status="fitted", median=f.mu, beta=0.0, median_lo=math.nan, median_hi=math.nan,
                       beta_lo=math.nan, beta_hi=math.nan, source=row["source"] + STEP_SOURCE,
                       message=f"{f.message}: pelicun is given that demand as a deterministic capacity")
        if good and f.mu > row["x_max"]:  # kept (as the planar fits keep theirs), and said
            row["message"] = (f"extrapolated: the median {f.mu:.3g} m/s lies beyond the largest demand of the "
                              f"cases ({row['x_max']:.3g} m/s), from {k} of {n} cases")
    return _numbered(pd.DataFrame(batch.rows, columns=list(COMPONENT_COLUMNS)))


def _numbered(table: pd.DataFrame) -> pd.DataFrame:
    """``ls``: each fitted limit state's number in its component (``LS1``, ``LS2``), in :data:`STATES` order."""
    fitted = table["status"] == "fitted"
    table.loc[fitted, "ls"] = ("LS" + (table[fitted].groupby(["item", "floor"], sort=False).cumcount() + 1)
                               .astype(str))
    return table


def damage_states(components: pd.DataFrame, item: str, floor: str) -> list[str]:
    """The limit states of one component, in pelicun's order (its ``DS1``, ``DS2``): the fitted ones."""
    c = components[(components["item"] == item) & (components["floor"].astype(str) == str(floor))
                   & (components["status"] == "fitted")]
    return list(c["limit_state"])


#: Columns of ``expected.csv``.
EXPECTED_COLUMNS: tuple[str, ...] = (
    "item", "floor", "pelicun_id", "quantity", "n_records", "expected_damaged", "expected_displaced_only",
    "expected_overturned", "expected_damaged_combined", "empirical_overturned", "slide_cost", "repair_cost",
    "expected_cost", "status",
)  # fmt: skip


def expected_table(components: pd.DataFrame, demands: pd.DataFrame, design: Any,
                   fits: pd.DataFrame | None = None, cases: pd.DataFrame | None = None) -> pd.DataFrame:
    """Per item and floor the expected number of units damaged (``DS >= 1``), displaced only (``DS1`` of a
    component with two states) and overturned, and the expected repair cost: the exact expectation over the
    records as recorded (each weighted equally) with the fragilities pelicun is given, in pelicun's demand
    (``pfv_max``, m/s): ``quantity x mean_r max(P_displaced, P_overturning)(pfv_max_r)`` (module docstring), which
    pelicun's damage assessment of the folder reproduces within its sampling error.
    ``expected_damaged_combined`` is the same before the lognormal: with the per-direction PFV ``fits`` (m/s) of the
    planar route, ``quantity x mean_r (1 - prod_d (1 - P_d(v_dr)))`` of the first limit state (NaN without them). ``expected_cost = expected_displaced_only x slide_cost + expected_overturned x repair_cost``
    (a missing ``slide_cost`` counts 0; a missing ``repair_cost`` leaves the cost NaN). For a cloud (the motions as
    recorded) with its ``cases``, ``empirical_overturned``: ``quantity`` times the share of the records under which
    the item overturned (in either direction, or in any azimuth); NaN otherwise.
    """
    items = {it.id: it for it in design.inventory.items}
    rows = []
    for (item_id, floor), c in components.groupby(["item", "floor"], sort=False):
        item, pfv = items[item_id], record_pfv(demands, floor)
        x = pfv["pfv_max"].to_numpy(float)
        fitted = c[c["status"] == "fitted"]
        p = {r.limit_state: fragility_probability(x, r.median, r.beta) for r in fitted.itertuples()}
        failed = (c["status"] == "no fit").any()
        over = p.get("overturned", np.zeros(x.size))
        damaged = np.maximum(p.get("displaced", over), over)
        q = item.quantity
        row = {"item": item_id, "floor": str(floor), "pelicun_id": component_id(item_id, floor), "quantity": q,
               "n_records": len(x), "expected_damaged": q * float(damaged.mean()),
               "expected_overturned": q * float(over.mean()), "expected_damaged_combined": math.nan,
               "slide_cost": item.slide_cost, "repair_cost": item.repair_cost,
               "status": "no fit: " + "; ".join(c.loc[c["status"] == "no fit", "message"]) if failed else
               ("ok" if len(fitted) else "never damaged")}
        if failed:
            row.update(expected_damaged=math.nan, expected_overturned=math.nan)
        row["empirical_overturned"] = _empirical(cases, item_id, floor, q) if design.method == "cloud" else math.nan
        if fits is not None and not failed and len(fitted):
            row["expected_damaged_combined"] = q * _combined_at_records(fits, item_id, floor, fitted.iloc[0], pfv)
        row["expected_displaced_only"] = row["expected_damaged"] - row["expected_overturned"]
        row["expected_cost"] = (row["expected_displaced_only"] * (item.slide_cost or 0.0)
                                + row["expected_overturned"] * item.repair_cost) if item.repair_cost is not None else math.nan
        rows.append(row)
    return pd.DataFrame(rows, columns=list(EXPECTED_COLUMNS))


def _empirical(cases: pd.DataFrame | None, item: str, floor: str, quantity: float) -> float:
    """``quantity`` times the share of the records under which the item overturned (any direction or azimuth)."""
    if cases is None:
        return math.nan
    c = cases[(cases["item"] == item) & (cases["floor"].astype(str) == str(floor)) & (cases["status"] == "ok")]
    return quantity * float(c.groupby("record")["overturned"].any().mean()) if len(c) else math.nan


def _combined_at_records(fits: pd.DataFrame, item: str, floor: str, first: Any, pfv: pd.DataFrame) -> float:
    """``mean_r (1 - prod_d (1 - P_d(v_dr)))`` of the component's first limit state, from the per-direction fits."""
    outcome = STATES[first["limit_state"]][0]
    rows = fits[(fits["item"] == item) & (fits["floor"].astype(str) == str(floor)) & (fits["demand"] == "pfv")
                & (fits["outcome"] == outcome)]
    curves, _ = _direction_curves(rows)
    survive = np.ones(len(pfv))
    for d, (median, beta) in curves.items():
        survive *= 1.0 - _probability(pfv[d].to_numpy(float), median, beta)
    return float((1.0 - survive).mean())


__all__ = ["COMPONENT_COLUMNS", "DEMAND", "EXPECTED_COLUMNS", "NONDIRECTIONAL_MULTIPLIER", "STATES", "STEP_SOURCE", "Z_GRID",
           "combined_probability", "component_id", "damage_states", "expected_table", "lognormal_through",
           "planar_components", "record_pfv", "three_d_components"]
