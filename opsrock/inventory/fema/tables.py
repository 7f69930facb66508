"""The study's tables: opsrock's medians against FEMA P-58's per item, floor and variant (the ratio
table), and the measurements behind what drives the differences."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from opsrock.inventory.fema.design import ContentsDesign, floor_label
from opsrock.published import fema_p58


def _fits(fits: pd.DataFrame, demand: str, campaign: str | None = None) -> pd.DataFrame:
    sel = fits[fits["demand"] == demand]
    return sel if campaign is None else sel[sel["campaign"] == campaign]


def ratio_table(fits: pd.DataFrame, design: ContentsDesign) -> pd.DataFrame:
    """One row per item, floor and variant of the study's building: opsrock's PFV and PFA medians with
    their intervals beside FEMA P-58's database median and the rule at ``T_1``
    (:func:`opsrock.published.fema_p58.median_pfv`; not defined at the ground, where the database
    says only that the ground motion decides), and the ratios opsrock / FEMA."""
    pfv = _fits(fits, "pfv").set_index(["campaign", "variant", "item", "floor"])
    pfa = _fits(fits, "pfa").set_index(["campaign", "variant", "item", "floor"])
    rows = []
    for key, r in pfv.iterrows():
        campaign, variant, item, _ = key
        if campaign == "sweep":
            continue
        it, a = fema_p58.item(item), pfa.loc[key]
        number = int(r["floor_number"])
        rule = fema_p58.median_pfv(it.aspect_ratio, design.period) if number > 0 else math.nan
        uplift_g = it.aspect_ratio  # g b/h in g
        rows.append({
            "item": item, "kind": it.kind, "b_over_h": it.aspect_ratio, "R": 0.5 * math.hypot(it.depth, it.height),
            "floor": floor_label(number, design.storeys), "floor_number": number, "variant": variant,
            "median_pfv": r["median"], "median_pfv_lo": r["median_lo"], "median_pfv_hi": r["median_hi"],
            "beta_pfv": r["beta"], "beta_pfv_lo": r["beta_lo"], "beta_pfv_hi": r["beta_hi"],
            "fema_median_pfv": it.median_mps, "ratio_fema": r["median"] / it.median_mps,
            "ratio_fema_lo": r["median_lo"] / it.median_mps, "ratio_fema_hi": r["median_hi"] / it.median_mps,
            "rule_pfv": rule, "ratio_rule": r["median"] / rule,
            "median_pfa_g": a["median"], "median_pfa_lo_g": a["median_lo"], "median_pfa_hi_g": a["median_hi"],
            "beta_pfa": a["beta"], "rule_pfa_g": uplift_g, "ratio_pfa_rule": a["median"] / uplift_g,
            "n_cases": int(r["n_cases"]), "n_overturned": int(r["n_overturned"]), "n_failed": int(r["n_failed"]),
            "message": "" if r["ok"] else r["message"],
        })
    table = pd.DataFrame(rows)
    order = {v: k for k, v in enumerate(design.variants)}
    table["_v"] = table["variant"].map(order)
    return table.sort_values(["_v", "item", "floor_number"]).drop(columns="_v").reset_index(drop=True)


def size_regression(ratios: pd.DataFrame, variant: str = "default") -> pd.DataFrame:
    """Per floor, the least-squares fit ``ln PFV_50 = c + a ln(b/h) + r ln R`` over the items (``R`` in
    m): FEMA's rule has ``a = 1`` and ``r = 0``; ``r > 0`` means larger items need more velocity."""
    rows = []
    for number, g in ratios[(ratios["variant"] == variant) & ratios["median_pfv"].notna()].groupby("floor_number"):
        if len(g) < 4:
            continue
        x = np.c_[np.ones(len(g)), np.log(g["b_over_h"]), np.log(g["R"])]
        y = np.log(g["median_pfv"].to_numpy(float))
        coef, *_ = np.linalg.lstsq(x, y, rcond=None)
        resid = y - x @ coef
        r2 = 1.0 - float(resid @ resid) / float(((y - y.mean()) ** 2).sum())
        rows.append({"floor": g["floor"].iloc[0], "floor_number": int(number), "a_slenderness": coef[1],
                     "r_size": coef[2], "r2": r2, "max_residual": float(np.exp(np.abs(resid).max()) - 1.0),
                     "n_items": len(g)})
    return pd.DataFrame(rows)


def paired_ratio(ratios: pd.DataFrame, variant: str, reference: str = "default") -> pd.DataFrame:
    """Per item and floor, the PFV median of ``variant`` over that of ``reference`` (same motions, same
    levels), and the betas."""
    a = ratios[ratios["variant"] == variant].set_index(["item", "floor"])
    b = ratios[ratios["variant"] == reference].set_index(["item", "floor"])
    common = a.index.intersection(b.index)
    out = pd.DataFrame({"ratio": a.loc[common, "median_pfv"] / b.loc[common, "median_pfv"],
                        "beta": a.loc[common, "beta_pfv"], "beta_ref": b.loc[common, "beta_pfv"],
                        "n_overturned": a.loc[common, "n_overturned"], "n_cases": a.loc[common, "n_cases"]})
    return out.reset_index()


def velocity_definition(fits: pd.DataFrame, velocities: pd.DataFrame, design: ContentsDesign) -> pd.DataFrame:
    """What the PFV definition does, per floor:

    * ``rel_over_abs``: the median in the peak velocity relative to the ground over the median in the
      absolute one (range over the items; default variant, NaN without it);
    * ``harmonic``: the median over the records of ``PFV / (PFA T / 2 pi)`` of the unscaled floor
      motions, with ``T = T_1`` (building floors) or the rule's reference period (ground): 1 for a
      harmonic motion at ``T``, the rule's assumption.
    """
    numbers = fits[fits["campaign"] != "sweep"].drop_duplicates("floor").set_index("floor")["floor_number"]
    rocking = fits[(fits["campaign"] == "rocking") & (fits["variant"] == "default")]
    absolute = rocking[rocking["demand"] == "pfv"].set_index(["item", "floor"])["median"]
    relative = rocking[rocking["demand"] == "pfv_rel"].set_index(["item", "floor"])["median"]
    rows = []
    for flabel, v in velocities.groupby("floor"):
        number = int(numbers[flabel])  # from any variant's fits: the study may have no default variant
        period = design.period if number > 0 else fema_p58.REFERENCE_PERIOD
        harmonic = v["pfv"] / (v["pfa"] * period / (2.0 * math.pi))
        ratio = (relative.xs(flabel, level="floor") / absolute.xs(flabel, level="floor")).dropna() \
            if number > 0 and flabel in set(relative.index.get_level_values("floor")) else pd.Series(dtype=float)
        rows.append({"floor": floor_label(number, design.storeys), "floor_number": number, "period": period,
                     "harmonic_median": float(harmonic.median()), "harmonic_p16": float(harmonic.quantile(0.16)),
                     "harmonic_p84": float(harmonic.quantile(0.84)),
                     "rel_over_abs_min": float(ratio.min()) if len(ratio) else math.nan,
                     "rel_over_abs_max": float(ratio.max()) if len(ratio) else math.nan})
    return pd.DataFrame(rows).sort_values("floor_number").reset_index(drop=True)


def decomposition(ratios: pd.DataFrame) -> pd.DataFrame:
    """The ratio to the rule split in two measured factors (default variant, building floors):
    ``overturn_over_uplift`` = PFA_50 / (g b/h), and ``velocity_factor`` = (PFV_50 / PFA_50) / (T_1 / 2 pi),
    whose product is ``ratio_rule``."""
    d = ratios[(ratios["variant"] == "default") & (ratios["floor_number"] > 0)].copy()
    d["overturn_over_uplift"] = d["ratio_pfa_rule"]
    d["velocity_factor"] = d["ratio_rule"] / d["ratio_pfa_rule"]
    return d[["item", "floor", "b_over_h", "ratio_rule", "overturn_over_uplift", "velocity_factor"]]


def sliding_share(cases: pd.DataFrame) -> pd.DataFrame:
    """Per item and floor of the friction campaign: the share of cases that ended ``slid`` (moved on the
    floor without overturning) and of those that overturned."""
    f = cases[cases["campaign"] == "friction"]
    if f.empty:
        return pd.DataFrame()
    g = f.groupby(["item", "floor_number"])
    return pd.DataFrame({"slid": g["response"].apply(lambda s: float((s == "slid").mean())),
                         "overturned": g["overturned"].mean()}).reset_index()


def sweep_table(fits: pd.DataFrame, design: ContentsDesign) -> pd.DataFrame:
    """The roofs of the period sweep (default variant): PFV median per item and ``T_1``, beside the rule
    at that period and the database median. The study's own roof stands for its building when it is one
    of the sweep's (:func:`opsrock.inventory.fema.design.sweep_buildings`)."""
    if not design.sweep:
        return pd.DataFrame()
    s = _fits(fits, "pfv", "sweep")
    own = _fits(fits, "pfv", "rocking")
    own = own[(own["variant"] == "default") & (own["floor_number"] == design.storeys)]
    if (design.period, design.storeys) in [tuple(b) for b in design.sweep]:
        s = pd.concat([s, own])
    rows = []
    for _, r in s.iterrows():
        it = fema_p58.item(r["item"])
        rule = fema_p58.median_pfv(it.aspect_ratio, r["building_period"])
        rows.append({"item": r["item"], "T1": r["building_period"], "median_pfv": r["median"],
                     "median_pfv_lo": r["median_lo"], "median_pfv_hi": r["median_hi"], "beta_pfv": r["beta"],
                     "rule_pfv": rule, "ratio_rule": r["median"] / rule, "fema_median_pfv": it.median_mps,
                     "ratio_fema": r["median"] / it.median_mps})
    return pd.DataFrame(rows).sort_values(["item", "T1"]).reset_index(drop=True) if rows else pd.DataFrame()


__all__ = ["decomposition", "paired_ratio", "ratio_table", "size_regression", "sliding_share", "sweep_table",
           "velocity_definition"]

