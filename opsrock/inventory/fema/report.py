"""The study's report (``report.md``): the ratio table, FEMA's rule, and what drives the differences,
each claim with the measurement behind it (numbers taken from the study's own tables)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import pandas as pd

from opsrock.inventory.fema.design import ContentsDesign, floor_name
from opsrock.inventory.report import Section, write_sections
from opsrock.published import fema_p58
from opsrock.report.markdown import markdown_table


@dataclass(frozen=True)
class StudySummary:
    """The counts and headline ratios of a contents study (what its report states first).

    Parameters
    ----------
    n_cases, n_failed, n_overturned : int
        Cases run, failed (excluded, never a verdict) and overturned (counts).
    timings : dict
        Wall time per phase (s, keys ending ``_s``, and ``total_s``) and the campaigns' case counts.
    ratio_range : tuple of float or None
        Min and max of opsrock's default PFV median over FEMA's database median on the study's floors
        (dimensionless); None without a default variant fit.
    sweep_ratio_range : tuple of float or None
        The same on the sweep's roofs (dimensionless); None without a sweep.
    """

    n_cases: int
    n_failed: int
    n_overturned: int
    timings: dict[str, Any]
    ratio_range: tuple[float, float] | None
    sweep_ratio_range: tuple[float, float] | None


def _rng(s: pd.Series, fmt: str = ".2f") -> str:
    s = s.dropna()
    return "n/a" if s.empty else f"{format(s.min(), fmt)}-{format(s.max(), fmt)}"


def _cell(r: pd.Series) -> str:
    if not math.isfinite(r["ratio_fema"]):
        return "never" if r["n_overturned"] == 0 else "no fit"
    return f"{r['ratio_fema']:.2f} [{r['ratio_fema_lo']:.2f}, {r['ratio_fema_hi']:.2f}]"


def ratio_matrix(ratios: pd.DataFrame, variant: str, design: ContentsDesign) -> pd.DataFrame:
    """Item by floor: opsrock's PFV median over FEMA's database median, with its 95 % record interval."""
    sel = ratios[ratios["variant"] == variant]
    rows = []
    for item, g in sel.groupby("item", sort=True):
        it = fema_p58.item(item)
        row = {"item": item, "b/h": f"{it.aspect_ratio:.3f}", "FEMA (m/s)": f"{it.median_mps:.3f}"}
        for _, r in g.sort_values("floor_number").iterrows():
            row[floor_name(int(r["floor_number"]), design.storeys)] = _cell(r)
        row["beta"] = _rng(g["beta_pfv"])
        rows.append(row)
    return pd.DataFrame(rows)


def pfa_matrix(ratios: pd.DataFrame, variant: str, design: ContentsDesign) -> pd.DataFrame:
    """Item by floor: opsrock's PFA median (g) with its interval, and its multiple of the uplift g b/h
    (the rule's PFA)."""
    sel = ratios[ratios["variant"] == variant]
    rows = []
    for item, g in sel.groupby("item", sort=True):
        it = fema_p58.item(item)
        row = {"item": item, "g b/h (g)": f"{it.aspect_ratio:.3f}"}
        for _, r in g.sort_values("floor_number").iterrows():
            cell = ("never" if r["n_overturned"] == 0 else "no fit") if not math.isfinite(r["median_pfa_g"]) else (
                f"{r['median_pfa_g']:.3g} [{r['median_pfa_lo_g']:.3g}, {r['median_pfa_hi_g']:.3g}] "
                f"(x{r['ratio_pfa_rule']:.2f})")
            row[floor_name(int(r["floor_number"]), design.storeys)] = cell
        row["beta"] = _rng(g["beta_pfa"])
        rows.append(row)
    return pd.DataFrame(rows)


def _article(n: int) -> str:
    """``an`` before a storey count read with a vowel sound (8, 11, 18, 80-89, 800...), else ``a``."""
    return "an" if str(n).startswith("8") or n in (11, 18) else "a"


def _title(design: ContentsDesign) -> str:
    return (f"Unanchored contents beside FEMA P-58: {_article(design.storeys)} {design.storeys}-storey building, "
            f"T1 = {design.period:g} s")


def _head(design: ContentsDesign, summary: StudySummary) -> Section:
    t = summary.timings
    floors = ", ".join(floor_name(n, design.storeys) for n in design.floor_numbers)
    return Section("", (
        f"The nine unanchored items of FEMA P-58 (`fema-p58-contents`) as rigid blocks (width = depth, height = "
        f"height) on the {floors} of a linear shear building (T1 = {design.period:g} s, {design.storeys} storeys, "
        f"{design.damping:.0%} modal damping), under the {len(design.names) or 44} components of "
        f"`{design.record_set}`{' (' + ', '.join(design.names) + ')' if design.names else ''}, scaled to "
        f"{len(design.levels)} levels of PFA / (g tan alpha) from {min(design.levels):.3g} to "
        f"{max(design.levels):.3g} (IDA). Variants: "
        + "; ".join(f"`{v}` ({design.variant(v).label})" for v in design.variants) + ".",
        "",
        f"{summary.n_cases} cases ({summary.n_failed} failed, {summary.n_overturned} overturned). "
        "Fragilities: lognormal maximum likelihood on every finished case, "
        + (f"95 % intervals from {design.n_boot} resamples of whole records (seed {design.seed})" if design.n_boot
           else "no intervals (no record resamples: n_boot = 0)")
        + ". PFV is the peak absolute floor "
        "velocity (m/s), PFA the peak absolute floor acceleration (g). Wall time "
        f"{t['total_s']:.1f} s (campaigns " + ", ".join(f"{k[:-2]} {v:.1f} s" for k, v in t.items()
                                                        if k.endswith("_s") and k != "total_s") + ").",
        "",
        headline(design, summary),
    ))


def headline(design: ContentsDesign, summary: StudySummary) -> str:
    """The report's headline: the range of opsrock's no-slip median over FEMA P-58's database median, or
    why there is none (a study without the ``default`` variant, or no finite default median)."""
    if summary.ratio_range is None:
        why = ("the study has no `default` variant" if "default" not in design.variants
               else "no default-variant fit has a finite median (too few records or overturned cases)")
        return f"**No headline ratio of opsrock's no-slip median over FEMA P-58's**: {why}."
    lo, hi = summary.ratio_range
    return (f"**opsrock's no-slip median over FEMA P-58's database median: {lo:.2f} to {hi:.2f}** "
            "(default restitution, every item and floor)"
            + (f"; {summary.sweep_ratio_range[0]:.2f} to {summary.sweep_ratio_range[1]:.2f} on the roofs of the "
               f"buildings of T1 = {min(t for t, _ in design.sweep):g}-{max(t for t, _ in design.sweep):g} s."
               if summary.sweep_ratio_range else "."))


def _ratio_section(result: dict, design: ContentsDesign) -> Section:
    out = [("PFV medians of opsrock over the database's (95 % interval from the records), and opsrock's beta "
           "range over the floors (FEMA: 0.5). All numbers in `ratios.csv`; the curves per item in "
           "`figures/<item>.png`.")]
    for v in design.variants:
        out += ["", f"### {design.variant(v).label}", "", markdown_table(ratio_matrix(result["ratios"], v, design))]
    if "default" in design.variants:
        out += ["", "### In PFA (default variant)", "",
                ("opsrock's PFA median (g) with its 95 % interval and, in brackets, its multiple of the uplift "
                "acceleration g b/h, which is FEMA's rule in PFA (`PFV_50 = g (b/h) T / 2 pi` is `PFA_50 = g b/h` "
                "for a harmonic floor motion); FEMA P-58 itself has no PFA fragility for these items:"), "",
                markdown_table(pfa_matrix(result["ratios"], "default", design))]
    return Section("opsrock over FEMA P-58, per item and floor", tuple(out))


def _rule_section(result: dict, with_figure: bool) -> Section:
    """FEMA's rule and how well it reproduces the database; the figure (``figures/fema_rule.png``, drawn
    only with the default variant, whose medians it shows) when ``with_figure``."""
    rule = result["rule"].copy()
    rule = rule[["fema_id", "aspect_ratio", "database", "rule", "ratio", "rounding", "implied_period", "implied_lo",
                 "implied_hi"]]
    books = rule[rule["fema_id"].isin([i.fema_id for i in fema_p58.ITEMS if i.kind == "bookcase"])]
    cabinets = rule[~rule.index.isin(books.index)]
    return Section("FEMA P-58's rule", (
            ("The database says that each median is worked out from the item's aspect ratio and the building period "
            "T, but not how; the formula was not found in any source we could reach (the FEMA P-58 volumes and "
            "background reports could not be read). The best candidate we found is `PFV_50 = g (b/h) T / 2 pi`: the "
            "uplift acceleration g b/h turned into a velocity by a harmonic floor motion of period T "
            "(`opsrock.published.fema_p58`, which says how it was found and what is not known). It is our reading, "
            f"not FEMA's text. At T = {fema_p58.REFERENCE_PERIOD:.3f} s (the bookcases' best period) "
            f"it gives the five bookcases within {100 * (books['ratio'].min() - 1):+.1f} % / "
            f"{100 * (books['ratio'].max() - 1):+.1f} % (the printed values are rounded to 0.1 in/s, at most "
            f"0.5 %); the filing cabinets are {100 * (cabinets['ratio'].min() - 1):.0f}-"
            f"{100 * (cabinets['ratio'].max() - 1):.0f} % above it (they need T = "
            f"{cabinets['implied_period'].min():.2f}-{cabinets['implied_period'].max():.2f} s): with one period for "
            "all nine the rule does not reproduce the database, and we could not find the further input (another "
            "period, other dimensions, a lower centre of mass) that would."), "",
            markdown_table(rule, ".4g"),
            *(["", "![FEMA's rule against T and b/h beside opsrock](figures/fema_rule.png)"] if with_figure else [])))


def write_report(path: Path, design: ContentsDesign, result: dict, summary: StudySummary) -> Path:
    """Write ``report.md``."""
    from opsrock.inventory.fema.drivers import drivers_section

    return write_sections(path, _title(design), [
        _head(design, summary), _ratio_section(result, design), _rule_section(result, "default" in design.variants),
        drivers_section(result, design), _pelicun_section(design)])


def _pelicun_section(design: ContentsDesign) -> Section:
    if "default" not in design.variants:
        return Section("Into pelicun", ("No pelicun folder: it holds the items as the shipped inventory has them "
                                        "(no slip, e = 0.95 e_R), the `default` variant, which this study leaves out.",))
    return Section("Into pelicun", (
            ("`pelicun/` is written by the contents study's one pelicun writer, as for any inventory, from the "
             "`default` variant (the shipped inventory `fema-p58-nine`: no slip, e = 0.95 e_R, one unit of each item "
             "on each floor): each item on each floor is one non-directional component, `opsrock.<FEMA ID>.<floor>` "
             "(`fragility.csv`, PFV in m/s, `DS1` overturned), each physical unit counted once; `inventory.csv` "
             "places them, `mapping.csv` gives each component's FEMA ID, floor, pelicun location (the ground floor "
             "is location 1, floor slab n location n + 1) and quantity, `demands.csv` the unscaled records' PFA and "
             "PFV on each floor of interest (one realisation per record, direction 1: each recorded component "
             "along the items' weaker axis), and `config.json` the assessment (`NonDirectionalMultipliers` 1.0, so "
             "that pelicun's demand is the PFV the fragilities were fitted in). `components.csv` and `expected.csv` "
             "beside this report hold the components and the expected number overturned per item and floor, exact "
             "over the records. `tools/pelicun_inventory.py` (in pelicun's venv) runs that assessment; "
             "`tools/pelicun_assess.py` runs pelicun's damage assessment of the same units with the database's "
             "E.20.22 fragilities and with opsrock's, and reports the expected number of overturned items each way."),))


__all__ = ["StudySummary", "headline", "ratio_matrix", "write_report"]
