"""The inventory study's ``report.md``, for a loss assessor: the per-item, per-floor table first, then what
the method means, what the floors show, the figures, the expected numbers overturned, the failed cases and
the pelicun files.

It computes nothing: every number comes from :class:`ReportInputs`, whose tables
:mod:`opsrock.inventory.summary` computed (:func:`~opsrock.inventory.summary.item_floor_table`,
:func:`~opsrock.inventory.summary.curve_table`, :func:`~opsrock.inventory.summary.floor_findings`, ...),
and every sentence is made from those numbers. PFV and PFA are defined before the table uses them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from opsrock._files import atomic_text
from opsrock.report.markdown import markdown_table

#: The headers of the failed cases' table (:func:`opsrock.inventory.summary.failure_table`) in a report.
FAILURE_HEADERS: dict[str, str] = {"code": "kind", "n_failed": "failed cases", "first_reason": "the first reason in full"}

#: Mark of a point estimate outside its own bootstrap interval.
OUTSIDE_MARK: str = "†"
#: Mark of a median beyond the largest demand of the cases (a fit's extrapolation from a few exceedances).
EXTRAPOLATED_MARK: str = "‡"
#: What each demand is, where the report first names it.
DEFINITIONS: dict[str, str] = {
    "pfv": "**PFV** (peak floor velocity, m/s): the largest absolute velocity of the floor the item stands on "
           "(or of its support: a desk, a table, a shelf) during the motion",
    "pfa": "**PFA** (peak floor acceleration, g; 1 g = 9.81 m/s²): the largest absolute acceleration of that "
           "floor (or support)",
}
#: What each method means, for the report's method paragraph.
METHODS: dict[str, str] = {
    "ida": "**IDA** (incremental dynamic analysis) on the given motions: each floor motion is scaled to a "
           "series of increasing levels and every item is run at each; the fit uses every finished case, so the "
           "curve describes the records' own shape at amplitudes they did not have as recorded",
    "cloud": "**cloud** (the motions as recorded, unscaled): each floor motion gives each item one case at its "
             "own PFA and PFV; the curve is only informed between the smallest and the largest demand of the "
             "records",
    "msa": "**multiple stripes**: each level has its own set of records, each at that level",
}


@dataclass(frozen=True)
class ReportInputs:
    """Everything ``report.md`` states, computed beforehand.

    Parameters
    ----------
    title : str
        The report's first line.
    method : str
        ``"ida"``, ``"cloud"`` or ``"msa"`` (:data:`METHODS`); another text is printed as it is.
    fits : pandas.DataFrame
        ``fits.csv`` (PFV in m/s, PFA in g).
    demands : pandas.DataFrame
        The floor demands (the study's table: PFA in m/s², PFV in m/s; ``demands.csv`` writes PFA in g).
    expected : pandas.DataFrame
        ``expected.csv`` (:func:`opsrock.inventory.components.expected_table`): per item and floor the units
        (counts) expected damaged, displaced only, overturned, and the expected repair cost.
    inventory : pandas.DataFrame
        One row per item: ``id, description, width, depth, height`` (m) and the optional columns.
    table : pandas.DataFrame
        :func:`opsrock.inventory.summary.item_floor_table` of overturning.
    curves : pandas.DataFrame
        :func:`opsrock.inventory.summary.curve_table` (the figures' points).
    figures : dict of str to str
        Figure name (an item id, or ``"demands"``) -> its path relative to the report.
    notes : tuple of str
        Measured lines (case counts, timings), printed as they are.
    pelicun : dict of str to str
        What each pelicun file is (``"fragility"``, ``"inventory"``, ``"demands"``, ``"config"``,
        ``"mapping"``) -> its file name relative to the report.
    findings : tuple of Finding or None
        :func:`opsrock.inventory.summary.floor_findings`; None: no statement about the floors.
    failures : pandas.DataFrame or None
        :func:`opsrock.inventory.summary.failure_table` (``code, n_failed, first_reason``); None: not counted.
    sliding : pandas.DataFrame or None
        :func:`opsrock.inventory.summary.item_floor_table` of sliding; None: no friction modelled.
    confidence : float
        Level of the intervals (dimensionless), for the headers.
    pelicun_notes : tuple of str
        What the pelicun folder assumes (floor locations, demand, damage states), printed as it is.
    reasons : pandas.DataFrame or None
        :func:`opsrock.inventory.summary.fema_ratio_reasons`: what drives each ratio to FEMA's median.
    never : tuple of str
        The items that never overturned in any case (one line, no figure).
    slides : tuple of str
        The items that slid beyond their distance in some case.
    boxes : pandas.DataFrame or None
        :func:`opsrock.inventory.three_d.box_table` (``boxes.csv``): each round item beside the box of its size;
        None: no round item.
    """

    title: str
    method: str
    fits: pd.DataFrame = field(repr=False)
    demands: pd.DataFrame = field(repr=False)
    expected: pd.DataFrame = field(repr=False)
    inventory: pd.DataFrame = field(repr=False)
    table: pd.DataFrame = field(repr=False)
    curves: pd.DataFrame = field(repr=False)
    figures: dict[str, str]
    notes: tuple[str, ...]
    pelicun: dict[str, str]
    findings: tuple | None = None
    failures: pd.DataFrame | None = field(default=None, repr=False)
    sliding: pd.DataFrame | None = field(default=None, repr=False)
    confidence: float = 0.95
    pelicun_notes: tuple[str, ...] = ()
    reasons: pd.DataFrame | None = field(default=None, repr=False)
    never: tuple[str, ...] = ()
    slides: tuple[str, ...] = ()
    boxes: pd.DataFrame | None = field(default=None, repr=False)


def _num(v: float) -> str:
    return f"{v:.3g}" if isinstance(v, (int, float)) and math.isfinite(v) else "n/a"


def _probability(p: float) -> str:
    """A probability to three decimals, bounded at 0.001 and 0.999 (a fitted tail, not a certainty); ``-``
    without a fit."""
    if not math.isfinite(p):
        return "-"
    return "< 0.001" if p < 0.001 else "> 0.999" if p > 0.999 else f"{p:.3f}"


def _no_fit(r: pd.Series, d: str, verb: str) -> str:
    status = r[f"status_{d}"]
    if status == "never":
        return f"none {verb} ({int(r['n_cases'])} cases)"
    if status == "always":
        return f"all {verb} ({int(r['n_cases'])} cases)"
    return "no fit (see below)"


def _median_cell(r: pd.Series, d: str, verb: str) -> str:
    if r[f"status_{d}"] != "fitted":
        return _no_fit(r, d, verb)
    mark = (OUTSIDE_MARK if r[f"median_outside_{d}"] else "") + (
        EXTRAPOLATED_MARK if r.get(f"median_extrapolated_{d}", False) else "")
    interval = (f" [{_num(r[f'median_lo_{d}'])}, {_num(r[f'median_hi_{d}'])}]"
                if math.isfinite(r[f"median_lo_{d}"]) else " (no interval)")
    return f"{_num(r[f'median_{d}'])}{mark}{interval}"


def _beta_cell(r: pd.Series, d: str) -> str:
    if r[f"status_{d}"] != "fitted":
        return "n/a"
    mark = OUTSIDE_MARK if r[f"beta_outside_{d}"] else ""
    interval = f" [{_num(r[f'beta_lo_{d}'])}, {_num(r[f'beta_hi_{d}'])}]" if math.isfinite(r[f"beta_lo_{d}"]) else ""
    return f"{_num(r[f'beta_{d}'])}{mark}{interval}"


def _levels(table: pd.DataFrame, d: str) -> list[tuple[str, str]]:
    """``(column, level text)`` of the probability columns of demand ``d``."""
    prefix = f"P_{d}_"
    return [(c, c[len(prefix):]) for c in table.columns if c.startswith(prefix)]


def formatted_table(table: pd.DataFrame, verb: str = "overturned", confidence: float = 0.95,
                    what: str = "item") -> pd.DataFrame:
    """The report's text cells of an :func:`~opsrock.inventory.summary.item_floor_table` (formatting only;
    ``what`` names the first column: ``item``, or ``block`` in the record-scene report)."""
    pct = f"{100 * confidence:.0f} %"
    several = table["direction"].nunique() > 1
    rows = []
    for _, r in table.iterrows():
        row = {what: r["item"], "floor": r["floor"]}
        if several:
            row["direction"] = r["direction"]
        row[f"median PFV (m/s) [{pct}]"] = _median_cell(r, "pfv", verb)
        row["beta (PFV)"] = _beta_cell(r, "pfv")
        row[f"median PFA (g) [{pct}]"] = _median_cell(r, "pfa", verb)
        row["beta (PFA)"] = _beta_cell(r, "pfa")
        row["FEMA P-58 median PFV (m/s)"] = (f"{_num(r['fema_median'])} ({r['fema_id']})" if r["fema_id"] else "not mapped")
        row["ours / FEMA"] = _num(r["ratio_fema"]) if r["fema_id"] else "-"
        for d, abbr, unit in (("pfv", "PFV", "m/s"), ("pfa", "PFA", "g")):
            for column, level in _levels(table, d):
                value = r[column]
                row[f"P at {abbr} {level} {unit}"] = _probability(value)
        row["records / cases"] = f"{int(r['n_records'])} / {int(r['n_cases'])}"
        rows.append(row)
    return pd.DataFrame(rows)


def method_lines(method: str, confidence: float = 0.95) -> list[str]:
    """The method paragraph: what ``method`` (:data:`METHODS` key, or a text) means and how the curves and
    intervals are fitted (``confidence`` dimensionless)."""
    method = METHODS.get(method, method)
    return ["## Method", "",
            f"Method: {method}. Each curve is a lognormal fragility P(overturning | demand) = "
            "Phi(ln(demand / median) / beta) fitted by maximum likelihood to every finished case of one item on one "
            f"floor; the {100 * confidence:.0f} % intervals come from resampling whole records (all the cases "
            "of a record together). beta is the lognormal dispersion (dimensionless). P at a level is that curve's "
            "probability at the demand named in the column.", ""]


def _where(r, several: bool) -> str:
    """``item on floor F`` of a table row, with ``, direction D`` when the table has several directions."""
    return f"{r.item} on floor {r.floor}" + (f", direction {r.direction}" if several else "")


def footnotes(table: pd.DataFrame, verb: str) -> list[str]:
    """The notes under a :func:`formatted_table`: why an estimate is marked, what \"none\" means, each missing fit."""
    lines = []
    several = "direction" in table.columns and table["direction"].nunique() > 1
    outside = table[table[[c for c in table.columns if "_outside_" in c]].any(axis=1)]
    if len(outside):
        which = ", ".join(_where(r, several) for r in outside.itertuples())
        records = sorted({int(n) for n in outside["n_records"]})
        lines.append(f"{OUTSIDE_MARK} The maximum-likelihood estimate lies outside its own bootstrap interval ({which}). "
                     f"With few records ({', '.join(map(str, records))} here) many resamples miss the records that "
                     "decide the fit, so the resampled estimates are skewed to one side and their percentile interval "
                     "need not contain the estimate from all the records. Read the estimate as the fit to these "
                     "records and the interval as how much it moves with them; more records narrow both.")
    extrapolated = [c for c in table.columns if c.startswith("median_extrapolated_")]
    beyond = table[table[extrapolated].any(axis=1)] if extrapolated else table.iloc[:0]
    if len(beyond):
        lines.append(f"{EXTRAPOLATED_MARK} The median lies beyond the largest demand any case of "
                     + ", ".join(_where(r, several) for r in beyond.itertuples())
                     + " reached: the curve is fitted to the few cases that exceeded and extrapolated past every "
                     "tested demand; read it as \"rarely, within these demands\", not as a measured median.")
    never = table[(table["status_pfv"] == "never")]
    if len(never):
        where = {item: sorted(set(g["floor"])) for item, g in never.groupby("item", sort=False)}
        lines.append(f"\"none {verb}\": no case {verb} " + "; ".join(f"{item} (floor{'s' if len(f) > 1 else ''} "
                     f"{', '.join(f)})" for item, f in where.items()) + ", so no curve is fitted and no probability "
                     "given (\"-\"): not zero, but beyond what these motions, at the levels run, made it do.")
    for r in table.itertuples():
        for d, abbr in (("pfv", "PFV"), ("pfa", "PFA")):
            if getattr(r, f"status_{d}") == "no fit":
                lines.append(f"no fit, {_where(r, several)}, {abbr}: {getattr(r, f'message_{d}').rstrip('.')}.")
    return [*(f"{line}\n" for line in lines)]


#: The expected-loss table's columns: ``expected.csv`` column -> (header, unit).
EXPECTED_SHOWN: dict[str, tuple[str, str]] = {
    "item": ("item", ""), "floor": ("floor", "label"), "quantity": ("units on the floor", "count"),
    "expected_damaged": ("expected damaged", "count"), "expected_displaced_only": ("displaced, not overturned", "count"),
    "expected_overturned": ("overturned", "count"), "expected_damaged_combined": ("damaged, before the lognormal", "count"),
    "expected_cost": ("expected repair cost", "currency"),
}


def _expected_lines(expected: pd.DataFrame, pelicun: dict[str, str]) -> list[str]:
    if expected is None or expected.empty:
        return []
    cols = [c for c in EXPECTED_SHOWN if c in expected.columns and not (c == "expected_damaged_combined"
                                                                          and expected[c].isna().all())]
    shown = expected[cols].astype(object)
    if "expected_cost" in cols:  # currency to the unit, not in exponent form
        shown["expected_cost"] = [f"{v:,.0f}" if isinstance(v, float) and math.isfinite(v) else "-"
                                  for v in expected["expected_cost"]]
    shown = shown.rename(columns={c: EXPECTED_SHOWN[c][0] for c in cols})
    units = pd.DataFrame([{EXPECTED_SHOWN[c][0]: f"({EXPECTED_SHOWN[c][1]})" if EXPECTED_SHOWN[c][1] else "(unit)"
                           for c in cols}])
    cost = expected["expected_cost"].sum(min_count=1) if "expected_cost" in expected else math.nan
    return ["## Expected units damaged and repair cost", "",
            "Per item and floor, each unit counted once whatever the direction: the expected number of units damaged "
            "(displaced, i.e. slid beyond the item's distance or overturned), of those only displaced, and overturned, "
            "and the expected repair cost (overturned units at `repair_cost`, units only displaced at `slide_cost`); "
            "the exact expectation over the records as recorded (each weighted equally) with the fragilities pelicun is "
            "given"
            + (f" (`{pelicun['fragility']}`)" if "fragility" in pelicun else "")
            + ", which pelicun's assessment of that folder reproduces within its sampling error. \"damaged, before the "
            "lognormal\" is the same count from the two directions' combined curve before a lognormal is fitted to it "
            "(the lognormal's own error).", "",
            markdown_table(pd.concat([units, shown.astype(object)], ignore_index=True), ".3g"), "",
            f"Total expected repair cost: {cost:,.0f} (the inventory's currency)." if math.isfinite(cost) else
            "No item gives a `repair_cost`: no repair cost is computed.", "", *_unpriced_slide_lines(expected)]


def _unpriced_slide_lines(expected: pd.DataFrame) -> list[str]:
    """One line per item expected to slide (units displaced and not overturned on a floor) without a ``slide_cost``:
    its sliding adds nothing to the repair cost."""
    if not {"expected_displaced_only", "slide_cost"} <= set(expected.columns):
        return []
    slid = expected[(expected["expected_displaced_only"] > 0) & expected["slide_cost"].isna()]
    lines = [f"- **{item}** slides (units displaced and not overturned expected on floor{'s' if len(g) > 1 else ''} "
             f"{', '.join(g['floor'].astype(str))}) but has no `slide_cost`: its sliding adds nothing to the repair "
             "cost." for item, g in slid.groupby("item", sort=False)]
    return [*lines, ""] if lines else []


def _failure_lines(inputs: ReportInputs) -> list[str]:
    n_failed = int(inputs.fits["n_failed"].max()) if len(inputs.fits) else 0
    lines = ["## Cases", ""]
    if inputs.failures is not None and len(inputs.failures):
        total = int(inputs.failures["n_failed"].sum())
        lines += [f"{total} case{'s' if total != 1 else ''} failed (excluded from the fits, never counted as a "
                  f"verdict); {'their reasons' if total != 1 else 'its reason'}:", "",
                  markdown_table(inputs.failures.rename(columns=FAILURE_HEADERS), ".3g"), ""]
    elif inputs.failures is not None or n_failed == 0:
        lines += ["No case failed.", ""]
    else:
        lines += [f"Failed cases per item and floor (excluded from the fits): up to {n_failed}; reasons not given.", ""]
    return lines + [*(f"- {note}" for note in inputs.notes), ""]


def _pelicun_lines(pelicun: dict[str, str], notes: tuple[str, ...] = ()) -> list[str]:
    if not pelicun:
        return []
    return ["## Into pelicun", "", *(f"{note}\n" for note in notes), "The folder pelicun runs as it is:", "",
            *(f"- {what}: `{name}`" for what, name in pelicun.items()), "",
            "pelicun's own DL_calculation on it, its outputs kept in `pelicun/results/` (in pelicun's venv, "
            "docs/getting-started-loss.md): `python tools/pelicun_inventory.py pelicun --dl-calculation`.", ""]


def _reason_lines(reasons: pd.DataFrame | None) -> list[str]:
    """What drives each ratio to FEMA P-58 (:func:`opsrock.inventory.summary.fema_ratio_reasons`), per item."""
    if reasons is None or reasons.empty:
        return []
    lines = ["## Ratios to FEMA P-58: what drives them", "",
             "FEMA P-58's medians follow (our reading, `opsrock/published/fema_p58.py`) PFV = g (b/h) T / (2 pi), the "
             "velocity at which a floor moving at period T uplifts the block. Each ratio is that rule at this item's "
             "b/h (b over twice the centre of mass height where given) and at the floor's own T = 2 pi PFV / PFA, "
             "over the rule for FEMA's item, times what the rule leaves out:", ""]
    for item, g in reasons.groupby("item", sort=False):
        lines += [f"- **{item}** (direction {g['direction'].iloc[0]}, its narrower side, as FEMA's):",
                  *(f"  - floor {r.floor}: {r.reason}." for r in g.itertuples())]
    return [*lines, ""]


def _share(v: float) -> str:
    return f"{100 * v:.0f} %" if isinstance(v, float) and math.isfinite(v) else "-"


def _box_lines(boxes: pd.DataFrame | None) -> list[str]:
    """Each round item beside the box of its size (``boxes.csv``, computed in the study): the median overturning
    PFV, the share of the overturnings by mechanism, the failed cases with their reasons."""
    if boxes is None or boxes.empty:
        return []
    rows = []
    for r in boxes.itertuples():
        rows.append({"item": r.item, "floor": r.floor, "model": f"{r.model} ({r.shape})",
                     "median pfv_max (m/s) [95 %]": "-" if not math.isfinite(r.median) else
                     f"{r.median:.3g} [{r.median_lo:.3g}, {r.median_hi:.3g}]",
                     "overturned / cases": f"{r.n_exceeded} / {r.n_cases}",
                     "rim / rolling": f"{_share(r.share_rim)} / {_share(r.share_rolling)}" if r.shape == "cylinder"
                     else "-",
                     "edge / corner": f"{_share(r.share_edge)} / {_share(r.share_corner)}" if r.shape == "box" else "-",
                     "box off by": (f"{100 * r.box_off:+.0f} %" if math.isfinite(r.box_off) else "-")
                     if r.shape == "box" else "",
                     "failed (reasons)": f"{r.n_failed}" + (f" ({r.failed_reasons})" if r.n_failed else "")})
    return ["## Round items against the box of their size", "",
            "Each round item (`shape = cylinder`, solved as a cylinder at one azimuth: it is round) beside the box "
            "of its size (side = its diameter, solved as every box, at every azimuth), on the same records and "
            "levels: the median of the overturning fragility in `pfv_max`, the overturnings by mechanism (a cylinder "
            "rocks over one rim point or rolls on its rim; a box tips over an edge or a corner), and how far the box's "
            "median is off the cylinder's. A failed case is excluded from its fit and counted here with its reason "
            "(`boxes.csv`). The box is in no other table, expected number or pelicun component.", "",
            markdown_table(pd.DataFrame(rows)), ""]


def _figure_lines(figures: dict[str, str], never: tuple[str, ...] = (), slides: tuple[str, ...] = ()) -> list[str]:
    lines = ["## Figures", "",
             "Each item's overturning fragility in PFV on each floor (one line style per floor and direction, the "
             "shaded band spanned by the curves at the corners of the intervals; curves, not data); the floors' "
             "demands, one point per record.", ""]
    for item in never:
        lines += [f"{item} never overturned in any case of the study, so it has no figure"
                  + (" (it slides instead: see the sliding table and its displaced damage state)." if item in slides
                     else "."), ""]
    for name, rel in figures.items():
        lines += [f"![{name}]({rel})", ""]
    return lines


@dataclass(frozen=True)
class Section:
    """One section of a contents study's report: every configuration's report (the inventory's,
    :func:`write_report`; FEMA P-58's nine, :func:`opsrock.inventory.fema.report.write_report`; the directionality
    study's, :func:`opsrock.inventory.directionality.report.write_report`) is a title and its sections, written by
    :func:`write_sections`.

    Parameters
    ----------
    heading : str
        The section's ``##`` heading; empty: lines under the title, before any heading.
    lines : tuple of str
        Its Markdown lines (tables already rendered; nothing computed here).
    """

    heading: str
    lines: tuple[str, ...]


def render_sections(title: str, sections: list[Section]) -> str:
    """``# title``, then each section (its ``## heading`` if any, then its lines), one blank line between them."""
    lines = [f"# {title}"]
    for s in sections:
        lines += ["", *((f"## {s.heading}", "") if s.heading else ()), *s.lines]
    return "\n".join(lines) + "\n"


def write_sections(path: str | Path, title: str, sections: list[Section]) -> Path:
    """Write ``report.md`` (atomically) from its title and sections (:func:`render_sections`); its path."""
    path = Path(path)
    atomic_text(path, render_sections(title, sections))
    return path


def write_report(path: str | Path, inputs: ReportInputs) -> Path:
    """Write ``report.md`` (atomically) from ``inputs`` and return its path.

    Parameters
    ----------
    path : str or pathlib.Path
        The file written (figure paths in ``inputs.figures`` are relative to its folder).
    inputs : ReportInputs
        The computed tables.
    """
    t = inputs.table
    lead = ("Each item's fragility on each floor of the building, in two demands: " + "; ".join(DEFINITIONS.values())
            + ". Overturning first; table rows are one item on one floor.")
    lines = [markdown_table(formatted_table(t, "overturned", inputs.confidence)) if len(t) else "(no item was fitted)", "",
             *(footnotes(t, "overturned") if len(t) else []),
             *_reason_lines(inputs.reasons),
             *method_lines(inputs.method, inputs.confidence)]
    if inputs.findings:
        lines += ["## What the floors show", "", *(f"- {f.text}" for f in inputs.findings), ""]
    if inputs.sliding is not None and len(inputs.sliding):
        lines += ["## Per item and floor: sliding", "",
                  markdown_table(formatted_table(inputs.sliding, "slid", inputs.confidence)), "",
                  *footnotes(inputs.sliding, "slid")]
    lines += [*_figure_lines(inputs.figures, inputs.never, inputs.slides), *_expected_lines(inputs.expected, inputs.pelicun),
              *_box_lines(inputs.boxes), *_failure_lines(inputs), *_pelicun_lines(inputs.pelicun, inputs.pelicun_notes)]
    return write_sections(path, inputs.title, [Section("", (lead,)),
                                               Section("Per item and floor: overturning", tuple(lines))])


__all__ = ["DEFINITIONS", "FAILURE_HEADERS", "METHODS", "OUTSIDE_MARK", "ReportInputs", "Section", "footnotes",
           "formatted_table", "method_lines", "render_sections", "write_report", "write_sections"]
