"""The tables of an inventory study's report, computed from the study's own tables (``fits.csv``,
``demands.csv``, the cases); :mod:`opsrock.inventory.report` and :mod:`opsrock.inventory.plots` only write
and draw them.

* :func:`item_floor_table`: one row per item, floor and direction: the median in PFV (m/s) and PFA (g), its
  dispersion beta, their record-bootstrap intervals, a flag where the point estimate lies outside its own
  interval, FEMA's median and the ratio where the item maps to a FEMA ID, and P(overturning) at the
  demand levels the user names;
* :func:`curve_table`: the points of the figures' fragility curves and their bootstrap bands;
* :func:`demand_table`: each floor's PFA (g) and PFV (m/s) per record;
* :func:`floor_findings`: what the report may say about the floors of one item, each sentence made from
  the numbers it states;
* :func:`failure_table`: failed cases counted by reason.

Units: PFV in m/s, PFA in g (``G`` = 9.81 m/s², :data:`opsrock.constants.G`), as the ``fits`` table gives
them; ``demands`` gives PFA in m/s² and is converted here.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np
import pandas as pd

from opsrock.constants import G
from opsrock.fragility.lognormal import fragility_probability

#: Demands of the report, in its order: column -> (abbreviation, unit, definition).
DEMANDS: dict[str, tuple[str, str, str]] = {
    "pfv": ("PFV", "m/s", "peak floor velocity: the largest absolute velocity of the floor (or of the support "
                          "the item stands on) during the motion, in m/s"),
    "pfa": ("PFA", "g", "peak floor acceleration: the largest absolute acceleration of the floor (or of the "
                        "support the item stands on) during the motion, in g (1 g = 9.81 m/s²)"),
}

#: Default demand levels of the probability columns: PFV (m/s) and PFA (g).
DEFAULT_LEVELS: dict[str, tuple[float, ...]] = {"pfv": (0.25, 0.5, 1.0), "pfa": (0.25, 0.5, 1.0)}

#: Keys of one item's row on one floor.
KEYS: tuple[str, ...] = ("item", "floor", "direction")

#: Relative difference (dimensionless) below which two medians are "the same" in a sentence: far below any
#: bootstrap interval's width, above the round-off of a fit.
SAME_RTOL: float = 1e-6


def level_column(demand: str, level: float) -> str:
    """The probability column of ``demand`` at ``level``: ``P_pfv_0.5`` (PFV 0.5 m/s), ``P_pfa_0.25`` (g)."""
    return f"P_{demand}_{level:g}"


_NUMBERED = re.compile(r"^(.*?)(\d+)$")


def _building(prefix: str) -> str:
    """The building part of a floor label's prefix: ``"b3.f"`` and ``"b3."`` -> ``"b3"``, ``"L"`` -> ``""``."""
    return re.sub(r"[.\s_-]*[a-z]*[.\s_-]*$", "", prefix)


def _floor_keys(labels: list[str]) -> dict[str, float] | None:
    """Height rank of each label when the labels name the floors of one building: a number (``"3"``), one
    prefix and a number (``"L3"``, ``"b3.f2"``), ``"ground"`` (0) or ``"roof"`` (above every number); None
    when any label is none of these or the prefixes differ (two buildings)."""
    keys, prefixes = {}, set()
    for label in labels:
        low = label.lower()
        if low in ("ground", "g"):
            keys[label] = 0.0
        elif low == "roof" or low.endswith(".roof"):
            keys[label], _ = math.inf, prefixes.add(_building(low[:-4]))
        else:
            m = _NUMBERED.match(label)
            if m is None:
                return None
            keys[label], _ = float(m.group(2)), prefixes.add(_building(m.group(1).lower()))
    return keys if len(prefixes - {""}) <= 1 else None


def floor_order(floors) -> list[str]:
    """Floors in building order where the labels give it (:func:`floors_are_numbered`: ``"1"``, ``"2"``,
    ``"10"``; ``"ground"``, ``"b3.f1"``, ``"b3.roof"``), else in first-seen order."""
    labels = [str(f) for f in dict.fromkeys(floors)]
    keys = _floor_keys(labels)
    return labels if keys is None else sorted(labels, key=keys.__getitem__)


def floors_are_numbered(floors) -> bool:
    """True when the floor labels give their order (numbers, one building's numbered floors, ``ground``,
    ``roof``), so that "higher floor" has a meaning."""
    return _floor_keys([str(f) for f in dict.fromkeys(floors)]) is not None


def outside_interval(estimate: float, lo: float, hi: float) -> bool:
    """True when a finite point estimate lies outside its own finite interval ``[lo, hi]``."""
    values = (estimate, lo, hi)
    return all(isinstance(v, (int, float)) and math.isfinite(v) for v in values) and not lo <= estimate <= hi


def probability(x: np.ndarray | float, median: float, beta: float) -> np.ndarray:
    """Lognormal fragility ``Phi(ln(x / median) / beta)`` (dimensionless); NaN where there is no fit."""
    x = np.asarray(x, dtype=float)
    if not (math.isfinite(median) and math.isfinite(beta) and median > 0 and beta > 0):
        return np.full(x.shape, math.nan)
    return fragility_probability(x, median, beta)


def _status(r: pd.Series) -> str:
    """``fitted`` (extrapolated or not), ``never`` (no case exceeded), ``always`` (every case did) or ``no fit``:
    the fit's own ``status`` (:data:`opsrock.inventory.fits.FIT_STATUSES`)."""
    return "fitted" if r["status"] == "extrapolated" else str(r["status"])


def _demand_part(r: pd.Series, levels: tuple[float, ...]) -> dict:
    d = r["demand"]
    part = {f"{k}_{d}": float(r[k]) for k in ("median", "median_lo", "median_hi", "beta", "beta_lo", "beta_hi")}
    part[f"status_{d}"] = _status(r)
    part[f"message_{d}"] = str(r["message"]) if isinstance(r["message"], str) else ""
    part[f"median_outside_{d}"] = outside_interval(r["median"], r["median_lo"], r["median_hi"])
    part[f"beta_outside_{d}"] = outside_interval(r["beta"], r["beta_lo"], r["beta_hi"])
    part[f"median_extrapolated_{d}"] = r["status"] == "extrapolated"
    for level in levels:
        part[level_column(d, level)] = float(probability(level, r["median"], r["beta"]))
    return part


def item_floor_table(fits: pd.DataFrame, demand_levels: dict[str, tuple[float, ...]] | None = None,
                     outcome: str = "overturning") -> pd.DataFrame:
    """One row per item, floor and direction of ``outcome``: medians, betas, intervals, FEMA's median and
    the probabilities at the demand levels.

    Parameters
    ----------
    fits : pandas.DataFrame
        The study's fits (``fits.csv``: one row per item, floor, direction, outcome, demand; PFV in m/s, PFA
        in g).
    demand_levels : dict of str to tuple of float, optional
        ``{"pfv": (m/s, ...), "pfa": (g, ...)}``: where P(outcome) is given (default
        :data:`DEFAULT_LEVELS`).
    outcome : str
        ``"overturning"`` or ``"sliding"``.

    Returns
    -------
    pandas.DataFrame
        Columns ``item, description, floor, direction, method, n_records, n_cases, n_exceeded, n_failed``,
        per demand ``d`` in :data:`DEMANDS` ``median_d, median_lo_d, median_hi_d, beta_d, beta_lo_d,
        beta_hi_d, status_d, message_d, median_outside_d, beta_outside_d`` and ``P_d_<level>`` (see
        :func:`level_column`), then ``fema_id, fema_median`` (PFV, m/s; NaN if none) and ``ratio_fema``.
        Items in ``fits`` order, floors in building order (:func:`floor_order`).
    """
    levels = {**DEFAULT_LEVELS, **(demand_levels or {})}
    sel = fits[fits["outcome"] == outcome]
    order = {f: k for k, f in enumerate(floor_order(sel["floor"]))}
    items = {i: k for k, i in enumerate(dict.fromkeys(sel["item"]))}
    rows = []
    for key, g in sel.groupby(list(KEYS), sort=False):
        first = g.iloc[0]
        row = {"item": key[0], "description": first["description"], "floor": str(key[1]), "direction": str(key[2]),
               "method": first["method"], "n_records": int(g["n_records"].max()), "n_cases": int(g["n_cases"].max()),
               "n_exceeded": int(g["n_exceeded"].max()), "n_failed": int(g["n_failed"].max())}
        for d in DEMANDS:
            r = g[g["demand"] == d]
            row.update(_demand_part(r.iloc[0], levels.get(d, ())) if len(r) else _missing_demand(d, levels.get(d, ())))
        pfv = g[g["demand"] == "pfv"]
        fema = pfv.iloc[0] if len(pfv) else first
        row.update({"fema_id": str(fema["fema_id"]) if isinstance(fema["fema_id"], str) else "",
                    "fema_median": float(fema["fema_median"]) if len(pfv) else math.nan,
                    "ratio_fema": float(fema["ratio_fema"]) if len(pfv) else math.nan})
        rows.append(row)
    table = pd.DataFrame(rows)
    if table.empty:
        return table
    table["_i"], table["_f"] = table["item"].map(items), table["floor"].map(order)
    return table.sort_values(["_i", "_f", "direction"], kind="stable").drop(columns=["_i", "_f"]).reset_index(drop=True)


def _missing_demand(d: str, levels: tuple[float, ...]) -> dict:
    part = {f"{k}_{d}": math.nan for k in ("median", "median_lo", "median_hi", "beta", "beta_lo", "beta_hi")}
    part.update({f"status_{d}": "no fit", f"message_{d}": "not fitted", f"median_outside_{d}": False,
                 f"beta_outside_{d}": False})
    part.update({level_column(d, level): math.nan for level in levels})
    return part


def default_grid(fits: pd.DataFrame, n: int = 120) -> dict[str, np.ndarray]:
    """Per demand, ``n`` log-spaced values spanning ``median · exp(±2.5 beta)`` of every fitted row of ``fits``
    (where such a curve runs from P = 0.006 to 0.994): PFV in m/s, PFA in g. Medians extrapolated beyond the
    demands tested (status ``extrapolated``) are left out when any other row has a fit, so that one poorly
    determined curve does not stretch the axis of the others over decades."""
    grid = {}
    for d in DEMANDS:
        sel = fits[(fits["demand"] == d) & np.isfinite(fits["median"].astype(float))
                   & np.isfinite(fits["beta"].astype(float)) & (fits["median"].astype(float) > 0)]
        measured = sel[sel["status"] != "extrapolated"]
        sel = measured if len(measured) else sel
        med, beta = sel["median"].to_numpy(float), sel["beta"].to_numpy(float)
        lo, hi = ((med * np.exp(-2.5 * beta)).min(), (med * np.exp(2.5 * beta)).max()) if med.size else (0.01, 10.0)
        grid[d] = np.geomspace(lo, hi, n)
    return grid


def curve_table(fits: pd.DataFrame, grid: dict[str, np.ndarray] | None = None) -> pd.DataFrame:
    """The points of every fitted curve, one row per (item, floor, direction, outcome, demand, x).

    Parameters
    ----------
    fits : pandas.DataFrame
        The study's fits (PFV in m/s, PFA in g).
    grid : dict of str to numpy.ndarray, optional
        Demand values per demand (m/s for ``pfv``, g for ``pfa``); default :func:`default_grid` of each item's
        own rows (each item's figure spans its own curves).

    Returns
    -------
    pandas.DataFrame
        Columns ``item, floor, direction, outcome, demand, unit, x, p, p_lo, p_hi`` (``p`` the MLE curve;
        ``p_lo, p_hi`` the band spanned by the curves at the corners of the median and beta intervals, NaN
        without intervals). Rows without a finite fit are left out.
    """
    grids = ({item: default_grid(rows) for item, rows in fits.groupby("item", sort=False)} if grid is None
             else dict.fromkeys(fits["item"], grid))
    parts = []
    for _, r in fits.iterrows():
        x = np.asarray(grids[r["item"]].get(r["demand"], ()), dtype=float)
        p = probability(x, r["median"], r["beta"])
        if not x.size or np.isnan(p).all():
            continue
        corners = [probability(x, m, b) for m in (r["median_lo"], r["median_hi"]) for b in (r["beta_lo"], r["beta_hi"])]
        band = np.array(corners)
        lo = np.full(x.shape, math.nan) if np.isnan(band).all() else np.nanmin(band, axis=0)
        hi = np.full(x.shape, math.nan) if np.isnan(band).all() else np.nanmax(band, axis=0)
        parts.append(pd.DataFrame({"item": r["item"], "floor": str(r["floor"]), "direction": str(r["direction"]),
                                   "outcome": r["outcome"], "demand": r["demand"], "unit": DEMANDS[r["demand"]][1],
                                   "x": x, "p": p, "p_lo": lo, "p_hi": hi}))
    columns = ["item", "floor", "direction", "outcome", "demand", "unit", "x", "p", "p_lo", "p_hi"]
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=columns)


def demand_table(demands: pd.DataFrame) -> pd.DataFrame:
    """Each motion's PFA (g) and PFV (m/s): columns ``record, floor, direction, pfa_g, pfv``, floors in
    building order.

    Parameters
    ----------
    demands : pandas.DataFrame
        ``demands.csv``: ``record, floor, direction, pfa`` (m/s²), ``pfv`` (m/s).
    """
    out = pd.DataFrame({"record": demands["record"].astype(str), "floor": demands["floor"].astype(str),
                        "direction": demands["direction"].astype(str), "pfa_g": demands["pfa"].to_numpy(float) / G,
                        "pfv": demands["pfv"].to_numpy(float)})
    order = {f: k for k, f in enumerate(floor_order(out["floor"]))}
    return out.assign(_f=out["floor"].map(order)).sort_values(["_f", "direction"], kind="stable") \
        .drop(columns="_f").reset_index(drop=True)


def failure_table(cases: pd.DataFrame) -> pd.DataFrame:
    """Failed cases (``status`` not ``"ok"``) counted by the kind of their reason
    (:func:`opsrock.campaign.cases.reason_code`: the same for every case that failed the same way, whatever
    times or settings its reason holds): columns ``code, n_failed, first_reason`` (one of those reasons in full,
    the first in the table's order), most frequent first."""
    from opsrock.campaign.cases import reason_code

    columns = ["code", "n_failed", "first_reason"]
    if cases.empty or "status" not in cases.columns:
        return pd.DataFrame(columns=columns)
    failed = cases[cases["status"] != "ok"]
    reasons = failed["reason"].fillna("").astype(str) if "reason" in failed else pd.Series("", index=failed.index)
    reasons = reasons.where(reasons.str.strip() != "", "no reason recorded")
    codes = reasons.map(reason_code)
    counts = codes.value_counts().reindex(codes.unique()).sort_values(ascending=False, kind="stable")  # ties: first seen
    first = reasons.groupby(codes, sort=False).first()
    return pd.DataFrame({"code": counts.index.astype(str), "n_failed": counts.to_numpy(int),
                         "first_reason": first.reindex(counts.index).to_numpy(str)}, columns=columns)


@dataclass(frozen=True)
class Finding:
    """One statement of the report about one item's floors, with the numbers it rests on.

    Parameters
    ----------
    item, demand : str
        The item and the demand (``pfv``/``pfa``).
    kind : str
        ``"lower_higher"`` (the median falls floor by floor going up), ``"higher_higher"`` (it rises),
        ``"same"`` (equal on every floor), ``"mixed"`` (ordered floors, neither), ``"unordered"`` (floor labels
        without an order: the lowest and highest named), ``"single"`` (one fitted floor), ``"none"`` (no fit).
    floors : tuple of str
        The fitted floors (status ``fitted``: a successful fit with a finite median), in building order.
    medians : tuple of float
        Their medians (m/s or g).
    overlap : bool
        True when every fitted floor's interval overlaps every other's (the records do not resolve a
        difference); False when any two are disjoint or there are no intervals.
    text : str
        The sentence.
    """

    item: str
    demand: str
    kind: str
    floors: tuple[str, ...]
    medians: tuple[float, ...]
    overlap: bool
    text: str


def _kind(medians: list[float], numbered: bool) -> str:
    if not medians:
        return "none"
    if len(medians) == 1:
        return "single"
    if max(medians) - min(medians) <= SAME_RTOL * max(medians):
        return "same"
    steps = np.diff(medians)
    if numbered and (steps < 0).all():
        return "lower_higher"
    if numbered and (steps > 0).all():
        return "higher_higher"
    return "mixed" if numbered else "unordered"


def floor_findings(table: pd.DataFrame, demand: str = "pfv", verb: str = "overturns") -> tuple[Finding, ...]:
    """What can be said of each item's floors in ``demand`` (per direction when there are several), from
    :func:`item_floor_table`; every sentence states the medians it compares (``verb``: what the outcome
    does, ``"overturns"`` or ``"slides"``)."""
    abbr, unit, _ = DEMANDS[demand]
    out = []
    for (item, direction), g in table.groupby(["item", "direction"], sort=False):
        fit = g[g[f"status_{demand}"].eq("fitted").to_numpy() & np.isfinite(g[f"median_{demand}"].to_numpy(float))]
        floors, med = tuple(fit["floor"]), [float(v) for v in fit[f"median_{demand}"]]
        lo, hi = fit[f"median_lo_{demand}"].to_numpy(float), fit[f"median_hi_{demand}"].to_numpy(float)
        overlap = bool(len(fit) > 1 and np.isfinite(lo).all() and np.isfinite(hi).all() and lo.max() <= hi.min())
        kind = _kind(med, floors_are_numbered(g["floor"]))
        where = f"{item}" + (f" (direction {direction})" if table["direction"].nunique() > 1 else "")
        listed = ", ".join(f"{m:.3g} {unit} on floor {f}" for f, m in zip(floors, med))
        text = {
            "none": f"{where} has no fitted {abbr} median on any floor.",
            "single": f"{where} has a fitted {abbr} median on floor {floors[0] if floors else ''} only "
                      f"({med[0]:.3g} {unit})." if med else "",
            "same": f"{where} has the same {abbr} median on every fitted floor ({listed}).",
            "lower_higher": f"{where} {verb} at a lower {abbr} on higher floors ({listed}).",
            "higher_higher": f"{where} {verb} at a higher {abbr} on higher floors ({listed}).",
            "mixed": f"{where}: the {abbr} median does not change in one direction from floor to floor ({listed}).",
            "unordered": f"{where}: the {abbr} median is lowest on floor {floors[int(np.argmin(med))]} and highest on "
                         f"floor {floors[int(np.argmax(med))]} ({listed}); the floor labels do not give their order."
                         if med else "",
        }[kind]
        if overlap and kind in ("lower_higher", "higher_higher", "mixed", "unordered"):
            text += " The floors' intervals overlap: these records do not resolve the difference."
        out.append(Finding(item, demand, kind, floors, tuple(med), overlap, text))
    return tuple(out)


def report_tables(fits: pd.DataFrame, demand_levels: dict[str, tuple[float, ...]] | None = None,
                  cases: pd.DataFrame | None = None, grid: dict[str, np.ndarray] | None = None) -> dict:
    """Every computed field of :class:`opsrock.inventory.report.ReportInputs` from the study's tables:
    ``table`` and ``sliding`` (:func:`item_floor_table` of each outcome; ``sliding`` None without sliding
    fits), ``curves`` (:func:`curve_table`), ``findings`` (:func:`floor_findings` in PFV) and ``failures``
    (:func:`failure_table` of ``cases``; None without them), so that
    ``ReportInputs(title=..., ..., **report_tables(fits, levels, cases))``.

    Parameters
    ----------
    fits : pandas.DataFrame
        ``fits.csv`` (PFV in m/s, PFA in g).
    demand_levels : dict of str to tuple of float, optional
        ``{"pfv": (m/s, ...), "pfa": (g, ...)}`` (default :data:`DEFAULT_LEVELS`).
    cases : pandas.DataFrame, optional
        The study's cases (``status``, ``reason``), for the failures by reason.
    grid : dict of str to numpy.ndarray, optional
        The figures' demand values (m/s, g); default :func:`default_grid`.
    """
    table = item_floor_table(fits, demand_levels)
    has_sliding = bool((fits["outcome"] == "sliding").any())
    return {"table": table, "curves": curve_table(fits, grid), "findings": floor_findings(table),
            "failures": None if cases is None else failure_table(cases),
            "sliding": item_floor_table(fits, demand_levels, "sliding") if has_sliding else None}


#: Columns of :func:`fema_ratio_reasons`.
REASON_COLUMNS: tuple[str, ...] = ("item", "floor", "direction", "ratio_fema", "aspect_item", "aspect_fema",
                                   "period_floor", "period_fema", "rule_factor", "beyond_factor", "friction",
                                   "slides_first", "reason")


def fema_ratio_reasons(table: pd.DataFrame, items: dict, demands: pd.DataFrame) -> pd.DataFrame:
    """What drives each ratio to FEMA P-58's median, per item, floor and direction, by FEMA's own rule (our
    reading, :mod:`opsrock.published.fema_p58`): ``PFV_50 = g (b/h) T / (2 pi)``, the PFV at which a floor moving
    harmonically at the period ``T`` uplifts the block. The ratio splits into ``rule_factor``, the rule at this
    item's ``b/h`` (``b / (2 h_cm)`` where the inventory gives a centre of mass: a low one steadies it) and at the
    floor motions' own ``T = 2 pi PFV / PFA`` (the median over the records of that floor and direction) over the
    rule at FEMA's item's ``b/h`` and period (:data:`~opsrock.published.fema_p58.REFERENCE_PERIOD`), and
    ``beyond_factor``, what the rule leaves out: overturning needs more than uplift, more so for a larger
    block (Housner's size effect), and an item whose friction is below its ``b/h`` slides before it rocks.
    Only the direction of the item's narrower side is compared (FEMA's items rock about their depth).

    Parameters
    ----------
    table : pandas.DataFrame
        :func:`item_floor_table` of overturning (``ratio_fema``, ``fema_id``; PFV m/s).
    items : dict of str to Item
        The inventory's items by id (m).
    demands : pandas.DataFrame
        ``demands.csv`` (``pfa`` m/s², ``pfv`` m/s).
    """
    from opsrock.published.fema_p58 import ITEMS, REFERENCE_PERIOD

    fema = {it.fema_id: it for it in ITEMS}
    rows = []
    for r in table[(table["fema_id"] != "") & np.isfinite(table["ratio_fema"].astype(float))].itertuples():
        item, ref = items[r.item], fema[r.fema_id]
        b = item.width if str(r.direction) == "1" else item.depth
        if b > min(item.width, item.depth):
            continue  # FEMA's item rocks about its depth, the narrower side: the other direction is not comparable
        h = 2.0 * item.cm_height if item.cm_height is not None else item.height
        d = demands[(demands["floor"].astype(str) == r.floor) & (demands["direction"].astype(str) == r.direction)]
        period = float(np.median(2.0 * np.pi * d["pfv"].to_numpy(float) / d["pfa"].to_numpy(float)))
        rule = (b / h) * period / (ref.aspect_ratio * REFERENCE_PERIOD)
        mu = item.friction.median if item.friction is not None else math.nan
        slides = bool(math.isfinite(mu) and mu < b / h)
        beyond = float(r.ratio_fema) / rule
        parts = {"geometry and floor period (FEMA's own rule)": rule, "beyond uplift (size, dynamics)": beyond}
        main = max(parts, key=lambda k: abs(math.log(parts[k])))
        why = (f"{float(r.ratio_fema):.2f} = {rule:.2f} by FEMA's own rule (b/h {b / h:.3g} vs {ref.aspect_ratio:.3g}"
               f"{', a low centre of mass' if item.cm_height is not None and item.cm_height < 0.5 * item.height else ''}"
               f"; the floor's T = 2 pi PFV/PFA {period:.2f} s vs {REFERENCE_PERIOD:.2f} s) x {beyond:.2f} beyond uplift "
               f"(overturning needs more than uplift; R = {0.5 * math.hypot(b, item.height):.2f} m)"
               + (f"; friction {mu:.2g} below b/h: it slides before it rocks" if slides else "")
               + f". Mostly: {main}" + (", and sliding" if slides else ""))
        rows.append({"item": r.item, "floor": r.floor, "direction": r.direction, "ratio_fema": float(r.ratio_fema),
                     "aspect_item": b / h, "aspect_fema": ref.aspect_ratio, "period_floor": period,
                     "period_fema": REFERENCE_PERIOD, "rule_factor": rule, "beyond_factor": beyond, "friction": mu,
                     "slides_first": slides, "reason": why})
    return pd.DataFrame(rows, columns=list(REASON_COLUMNS))


__all__ = ["DEFAULT_LEVELS", "DEMANDS", "Finding", "REASON_COLUMNS", "fema_ratio_reasons", "curve_table", "default_grid", "demand_table", "failure_table",
           "floor_findings", "floor_order", "floors_are_numbered", "item_floor_table", "level_column", "outside_interval",
           "probability", "report_tables"]
