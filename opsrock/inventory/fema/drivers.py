"""The report's section on what drives the differences between opsrock and FEMA P-58: each paragraph
states a measurement of the study (its table is in the study's folder) and what it shows."""

from __future__ import annotations

import pandas as pd

from opsrock.inventory.fema.design import ContentsDesign, floor_name
from opsrock.inventory.report import Section
from opsrock.report.markdown import markdown_table
from opsrock.solvers.registry import planar_solver


def _rng(s: pd.Series, fmt: str = ".2f") -> str:
    s = pd.Series(s).dropna()
    return "n/a" if s.empty else f"{format(s.min(), fmt)}-{format(s.max(), fmt)}"


def _named(df: pd.DataFrame, design: ContentsDesign) -> pd.DataFrame:
    """``df`` with its ``floor`` labels (``ground``, ``f<n>``) in words."""
    out = df.copy()
    out["floor"] = [f if f == "ground" else floor_name(int(str(f)[1:]), design.storeys) for f in out["floor"]]
    return out


def _pct(x: float) -> str:
    return f"{100 * (x - 1):+.0f} %"


def _floors(result: dict, design: ContentsDesign) -> list[str]:
    r = result["ratios"]
    d = r[r["variant"] == "default"]
    rows = []
    for number, g in d.groupby("floor_number"):
        rows.append({"floor": floor_name(int(number), design.storeys), "opsrock / database": _rng(g["ratio_fema"]),
                     "opsrock / rule at T1": _rng(g["ratio_rule"]), "opsrock beta": _rng(g["beta_pfv"]),
                     "median PFV (m/s)": _rng(g["median_pfv"], ".3g")})
    out = ["", "### Floor and building period", "",
           ("The database gives one median per item for every floor and building; opsrock's default-variant medians "
           "per floor (ranges over the items):"), "", markdown_table(pd.DataFrame(rows))]
    ground = d[d["floor_number"] == 0].set_index("item")["median_pfv"]
    roof = d[d["floor_number"] == design.storeys].set_index("item")["median_pfv"]
    if len(ground) and len(roof):
        out += ["", f"Roof over ground median: {_rng(roof / ground)} over the items."]
    sweep = result["sweep"]
    if not sweep.empty:
        by_t = sweep.groupby("T1").agg(ratio_rule=("ratio_rule", "median"), ratio_fema=("ratio_fema", "median"),
                                       lo=("ratio_fema", "min"), hi=("ratio_fema", "max")).reset_index()
        by_t.columns = ["T1 (s)", "opsrock / rule at T1 (median over items)", "opsrock / database (median)",
                        "opsrock / database (min)", "opsrock / database (max)"]
        out += ["", "On the roofs of the sweep's buildings (`sweep.csv`, default variant):", "",
                markdown_table(by_t)]
    return out


def _uplift_and_velocity(result: dict, design: ContentsDesign) -> list[str]:
    dec, vel = result["decomposition"], result["velocity"]
    if dec.empty:
        return []
    rows = []
    for floor, g in dec.groupby("floor", sort=False):
        rows.append({"floor": floor, "PFA_50 / (g b/h)": _rng(g["overturn_over_uplift"]),
                     "(PFV_50 / PFA_50) / (T1 / 2 pi)": _rng(g["velocity_factor"]),
                     "opsrock / rule at T1": _rng(g["ratio_rule"])})
    return ["", "### Overturning is not uplift, and a floor motion is not harmonic", "",
            ("On the building's floors opsrock's median over the rule at T1 is the product of two measured factors "
            "(`decomposition.csv`): how far above the uplift acceleration g b/h the items overturn (in PFA), and how "
            "the PFV of the floor motions that overturn them compares with the harmonic PFA T1 / 2 pi the rule "
            "assumes:"), "", markdown_table(_named(pd.DataFrame(rows), design)), "",
            ("The floor motions themselves (unscaled, all records; `velocity_definition.csv`): median PFV / "
            "(PFA T / 2 pi) with T = T1 on the building's floors and the rule's 1.04 s on the ground, with the "
            "16th-84th percentiles over the records:"), "",
            markdown_table(_named(vel[["floor", "period", "harmonic_median", "harmonic_p16", "harmonic_p84"]], design))]


def _size(result: dict, design: ContentsDesign) -> list[str]:
    size = result["size"]
    if size.empty:
        return []
    return ["", "### Size and slenderness", "",
            ("Least squares over the items, per floor, of `ln PFV_50 = c + a ln(b/h) + r ln R` (R the half-diagonal, "
            "m; `size_regression.csv`). FEMA's rule has a = 1 and r = 0 (no size effect):"), "",
            markdown_table(_named(size[["floor", "a_slenderness", "r_size", "r2", "max_residual", "n_items"]], design))]


def _paired(result: dict, variant: str, title: str, intro: str, design: ContentsDesign) -> list[str]:
    p = result["paired"]
    p = p[p["variant"] == variant] if not p.empty else p
    if p.empty:
        return []
    never = p[p["ratio"].isna() & (p["n_overturned"] == 0)]
    rows = [{"floor": f, "median ratio (range)": _rng(g["ratio"], ".3f"), "beta": _rng(g["beta"]),
             "beta, default": _rng(g["beta_ref"])} for f, g in p.groupby("floor", sort=False)]
    out = ["", f"### {title}", "", intro + f" Ratio {_rng(p['ratio'], '.3f')} over the items and floors "
           f"(median {_pct(p['ratio'].median()) if p['ratio'].notna().any() else 'n/a'}):", "",
           markdown_table(_named(pd.DataFrame(rows), design))]
    if len(never):
        out += ["", f"Never overturned within the levels: {', '.join(sorted(set(never['item'])))}."]
    return out


def _sliding(result: dict) -> list[str]:
    s = result["sliding"]
    if s.empty:
        return []
    by_item = s.groupby("item").agg(slid=("slid", "mean"), overturned=("overturned", "mean")).reset_index()
    return ["", ("Share of the friction cases that ended sliding (moved on the floor, standing) or overturned, "
            "averaged over the floors (`sliding.csv`):"), "", markdown_table(by_item)]


def _definition(result: dict, design: ContentsDesign) -> list[str]:
    vel = result["velocity"]
    v = vel[vel["floor_number"] > 0]
    if v.empty or not v["rel_over_abs_min"].notna().any():
        return []
    return ["", "### The PFV definition", "",
            ("FEMA's PFV is the peak total floor velocity (at the ground floor the database uses the ground motion "
            "itself, which a velocity relative to the ground would make zero); opsrock's `pfv` is the same: the "
            "peak of the integrated absolute floor acceleration, baseline-corrected. Had the medians been read in "
            "the peak velocity relative to the ground, they would be, per floor, this fraction of the absolute "
            "ones (point fits on the same cases):"), "",
            markdown_table(_named(v[["floor", "rel_over_abs_min", "rel_over_abs_max"]], design))]


def _mu(design: ContentsDesign) -> str:
    mu_s, mu_k = design.friction_pair
    return f"mu = {mu_s:g}" if mu_s == mu_k else f"mu_s = {mu_s:g}, mu_k = {mu_k:g}"


def _span(s: pd.Series) -> tuple[float, float]:
    s = pd.Series(s).dropna()
    return (float(s.min()), float(s.max())) if len(s) else (float("nan"), float("nan"))


def _claims(result: dict, design: ContentsDesign) -> list[str]:
    """One line per driver, each with its number (the tables below hold the detail)."""
    r, out = result["ratios"], []
    d = r[r["variant"] == "default"]
    if d.empty:
        return out
    by_floor = d.groupby("floor_number")["median_pfv"]
    ground = d[d["floor_number"] == 0].set_index("item")["median_pfv"]
    above = [(n, g.set_index("item")["median_pfv"]) for n, g in d[d["floor_number"] > 0].groupby("floor_number")]
    if len(ground) and above:
        spans = [(floor_name(int(n), design.storeys), *_span(m / ground)) for n, m in above]
        out.append("- **Floor**: the same item's median differs between floors ("
                   + ", ".join(f"{name} over ground {lo:.2f}-{hi:.2f}" for name, lo, hi in spans)
                   + " over the items); the database has one value for all floors.")
    elif by_floor.ngroups > 1:
        out.append("- **Floor**: medians per floor below; the database has one value for all floors.")
    out += _period_claim(result)
    dec = result["decomposition"]
    if not dec.empty:
        a_lo, a_hi = _span(dec["overturn_over_uplift"])
        v_lo, v_hi = _span(dec["velocity_factor"])
        out.append(f"- **Overturning is not uplift**: on the building's floors the items overturn at PFA "
                   f"{a_lo:.2f}-{a_hi:.2f} times the uplift acceleration g b/h that the rule equates with "
                   "overturning; this factor alone puts opsrock above the rule.")
        out.append(f"- **A floor motion is not harmonic at T1**: the PFV of the motions that overturn the items is "
                   f"{v_lo:.2f}-{v_hi:.2f} times the rule's PFA T1 / 2 pi, which pulls opsrock back towards it.")
    size = result["size"]
    if not size.empty:
        out.append(f"- **Size and slenderness**: over the items, opsrock's median grows like (b/h)^a R^r with a = "
                   f"{_rng(size['a_slenderness'])} and r = {_rng(size['r_size'])} over the floors (the rule: a = 1, "
                   "r = 0): at equal size a slenderer item is weaker than the rule says (a > 1), and at equal b/h a larger item "
                   "needs more velocity (r > 0), which the rule ignores.")
    out += _variant_claims(result, design)
    return out


def _period_claim(result: dict) -> list[str]:
    """The building period: opsrock over the database and over the rule on the sweep's roofs."""
    sweep = result["sweep"]
    if sweep.empty or sweep["T1"].nunique() < 2:
        return []
    by_t = sweep.groupby("T1")
    fema = ", ".join(f"{_rng(g['ratio_fema'])} at {t:g} s" for t, g in by_t)
    rule = ", ".join(f"{g['ratio_rule'].median():.2f} at {t:g} s" for t, g in by_t)
    spread = sweep.groupby("item")["median_pfv"].agg(lambda m: m.max() / m.min())
    t_lo, t_hi = sweep["T1"].min(), sweep["T1"].max()
    return [(f"- **Building period**: on the roofs of buildings of T1 = {t_lo:g}-{t_hi:g} s opsrock over the database "
            f"is {fema} (range over the items), while the database has one value for every building. Over the rule "
            f"at T1 it is {rule} (median over the items): across these buildings an item's opsrock median changes "
            f"by a factor of {_rng(spread)} (largest over smallest), the rule's by {t_hi / t_lo:g} (it is "
            "proportional to T).")]


def _variant_claims(result: dict, design: ContentsDesign) -> list[str]:
    p, out = result["paired"], []
    if p.empty:
        return out
    h = p[p["variant"] == "housner"]
    if len(h):
        lo, hi = _span(h["ratio"])
        out.append(f"- **Restitution**: Housner's e = e_R instead of 0.95 e_R moves the PFV medians by "
                   f"{_pct(lo)} to {_pct(hi)} (more energy kept per impact, overturning earlier).")
    f = p[p["variant"] == "friction"]
    if len(f):
        never = sorted(set(f.loc[f["ratio"].isna() & (f["n_overturned"] == 0), "item"]))
        lo, hi = _span(f["ratio"])
        out.append(f"- **Sliding** ({_mu(design)}, an assumption): "
                   + (f"{', '.join(never)} (b/h above mu) slide and never overturn within the levels; " if never
                      else "") + f"the others' medians move by {_pct(lo)} to {_pct(hi)}.")
    vel = result["velocity"]
    v = vel[vel["floor_number"] > 0] if not vel.empty else vel
    if len(v) and v["rel_over_abs_min"].notna().any():
        out.append(f"- **PFV definition**: read in the velocity relative to the ground the medians would be "
                   f"{v['rel_over_abs_min'].min():.2f}-{v['rel_over_abs_max'].max():.2f} of the absolute ones "
                   "(both definitions fitted to the same cases).")
    return out


def drivers_section(result: dict, design: ContentsDesign) -> Section:
    """The report's section (:class:`opsrock.inventory.report.Section`)."""
    out = [*_claims(result, design)]
    out += _floors(result, design)
    out += _uplift_and_velocity(result, design)
    out += _size(result, design)
    out += _paired(result, "housner", "Restitution",
                   "Housner's own restitution e = e_R against the default e = 0.95 e_R (same motions and levels, "
                   "PFV medians of `housner` over `default`; `paired_variants.csv`).", design)
    out += _paired(result, "friction", "Sliding",
                   f"The block on a floor of friction {_mu(design)} (solver `{planar_solver(True)}`) against no-slip "
                   "rocking (PFV medians of `friction` over `default`). An item with b/h above mu slides before it can "
                   "rock, and a sliding base caps the force the floor passes to it.", design)
    out += _sliding(result)
    out += _definition(result, design)
    return Section("What drives the differences (measured)", tuple(out))


__all__ = ["drivers_section"]


