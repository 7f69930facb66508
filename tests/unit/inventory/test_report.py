"""The inventory study's report (:mod:`opsrock.inventory.summary`, :mod:`opsrock.inventory.report`,
:mod:`opsrock.inventory.plots`) on synthetic ``fits`` and ``demands`` tables built here (no simulation):
an item whose PFV median falls floor by floor (FEMA-mapped), an unmapped item whose floors 1 and 2 have
identical curves and whose floor 3 estimate lies outside its own interval, and an item that never overturned
(NaN median). Every expected number below is either written into the synthetic table or follows from the
lognormal CDF in closed form (scipy's ``norm.cdf``, to round-off).
"""

from __future__ import annotations

import math
import re

import matplotlib
import numpy as np
import pandas as pd
import pytest
from _support import drawn_figure
from scipy.stats import norm

from opsrock.inventory import plots, summary
from opsrock.inventory.report import OUTSIDE_MARK, ReportInputs, write_report
from opsrock.solvers.status import MAX_STEPS, REASONS

#: The reason a solver stores with max_steps (it appends where it stopped).
MAX_STEPS_REASON = REASONS[MAX_STEPS]

#: item -> (description, fema_id, fema median PFV m/s, {floor: (median PFV m/s, lo, hi, beta, beta_lo, beta_hi)}).
ITEMS = {
    "rack": ("server rack", "E.20.22.102a", 0.4,
             {"1": (0.6, 0.5, 0.7, 0.4, 0.3, 0.5), "2": (0.5, 0.42, 0.6, 0.4, 0.3, 0.5),
              "3": (0.4, 0.33, 0.5, 0.35, 0.25, 0.45)}),
    "cabinet": ("medical cabinet", "", math.nan,
                {"1": (0.8, 0.7, 0.9, 0.3, 0.2, 0.4), "2": (0.8, 0.7, 0.9, 0.3, 0.2, 0.4),
                 "3": (0.9, 0.95, 1.3, 0.3, 0.2, 0.4)}),  # floor 3: the MLE below its own interval
    "printer": ("printer on a desk", "", math.nan, {f: (math.nan,) * 6 for f in ("1", "2", "3")}),
}
#: PFA medians (g): the PFV median times this (any positive factor serves the report's tests).
PFA_PER_PFV = 0.9


def _fit_row(item, floor, demand, values):
    desc, fema_id, fema_median, _ = ITEMS[item]
    med, lo, hi, beta, blo, bhi = values
    ok = math.isfinite(med)
    scale = PFA_PER_PFV if demand == "pfa" else 1.0
    return {"item": item, "description": desc, "floor": floor, "direction": "1", "outcome": "overturning",
            "demand": demand, "unit": "g" if demand == "pfa" else "m/s", "method": "ida",
            "median": med * scale, "median_lo": lo * scale, "median_hi": hi * scale, "beta": beta, "beta_lo": blo,
            "beta_hi": bhi, "n_cases": 80, "n_exceeded": 30 if ok else 0, "n_failed": 2 if item == "rack" else 0,
            "n_records": 5, "ok": ok, "status": "fitted" if ok else "never", "message": "" if ok else "no case overturned",
            "fema_id": fema_id if demand == "pfv" else fema_id, "fema_median": fema_median if demand == "pfv" else math.nan,
            "ratio_fema": med / fema_median if demand == "pfv" and fema_id else math.nan,
            "pelicun_id": f"opsrock.{item}.{floor}.{demand.upper()}"}


def synthetic_fits() -> pd.DataFrame:
    return pd.DataFrame([_fit_row(item, floor, d, v) for item, (_, _, _, floors) in ITEMS.items()
                         for floor, v in floors.items() for d in ("pfv", "pfa")])


def synthetic_demands() -> pd.DataFrame:
    rows = [{"record": f"r{k}", "floor": f, "direction": "1", "pfa": 9.81 * 0.2 * (1 + j) * (1 + 0.1 * k),
             "pfv": 0.2 * (1 + j) * (1 + 0.1 * k)} for j, f in enumerate(("1", "2", "3")) for k in range(5)]
    return pd.DataFrame(rows)


LEVELS = {"pfv": (0.25, 0.5, 1.0), "pfa": (0.3,)}


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """The report written once from the synthetic tables, its figures and text."""
    out = tmp_path_factory.mktemp("inventory_report")
    fits = synthetic_fits()
    table = summary.item_floor_table(fits, LEVELS)
    curves = summary.curve_table(fits)
    figs = {item: f"figures/{item}.png" for item in ITEMS}
    drawn = plots.item_figures(curves, out / "figures")
    drawn["demands"] = plots.plot_floor_demands(summary.demand_table(synthetic_demands()), out / "figures" / "demands.png")
    figs["demands"] = "figures/demands.png"
    cases = pd.DataFrame({"status": ["ok"] * 5 + ["failed"] * 3,
                          "reason": [""] * 5 + [f"{MAX_STEPS_REASON} (max_steps = 10000000, t = 12.5 s)",
                                                f"{MAX_STEPS_REASON} (max_steps = 20000000, t = 31 s)",
                                                "lost to the infrastructure: worker process died while solving this "
                                                "case alone (signal: 9)"]})
    expected = pd.DataFrame({"item": ["rack"], "floor": ["1"], "direction": ["1"], "quantity": [4.0],
                             "expected_overturned": [0.5]})
    tables = summary.report_tables(fits, LEVELS, cases)
    pd.testing.assert_frame_equal(tables["table"], table)
    assert tables["sliding"] is None  # no sliding fits
    inputs = ReportInputs(title="Contents of building X", method="ida", fits=fits, demands=synthetic_demands(),
                          expected=expected, inventory=pd.DataFrame({"id": list(ITEMS)}), figures=figs,
                          notes=("240 cases in 3.2 s",), pelicun={"fragility": "pelicun/fragility.csv"}, **tables)
    path = write_report(out / "report.md", inputs)
    return {"text": path.read_text(), "table": table, "curves": curves, "drawn": drawn, "fits": fits}


def test_table_rows_and_probabilities(built):
    t = built["table"]
    assert list(t["item"]) == ["rack"] * 3 + ["cabinet"] * 3 + ["printer"] * 3 and list(t["floor"][:3]) == ["1", "2", "3"]
    rack1 = t.iloc[0]
    # P = Phi(ln(x / median) / beta), the lognormal CDF in closed form
    assert rack1["P_pfv_0.5"] == pytest.approx(norm.cdf(math.log(0.5 / 0.6) / 0.4), rel=1e-12)
    assert rack1["P_pfa_0.3"] == pytest.approx(norm.cdf(math.log(0.3 / (0.6 * PFA_PER_PFV)) / 0.4), rel=1e-12)
    assert rack1["ratio_fema"] == pytest.approx(0.6 / 0.4) and rack1["fema_id"] == "E.20.22.102a"
    printer = t[t["item"] == "printer"]
    assert (printer["status_pfv"] == "never").all() and printer["P_pfv_0.5"].isna().all()
    cab3 = t[(t["item"] == "cabinet") & (t["floor"] == "3")].iloc[0]
    assert cab3["median_outside_pfv"] and not cab3["beta_outside_pfv"]
    assert not t[t["item"] == "rack"]["median_outside_pfv"].any()


def test_the_table_comes_first_and_the_ims_are_defined_before_use(built):
    text = built["text"]
    first_table = text.index("\n| item |")
    assert first_table < text.index("## Method") < text.index("## Figures") < text.index("## Cases")
    assert text.index("## Per item and floor") < text.index("## ", text.index("## Per item and floor") + 3)
    for abbr, definition in (("PFV", "**PFV** (peak floor velocity, m/s)"), ("PFA", "**PFA** (peak floor acceleration, g")):
        first_use = re.search(rf"\b{abbr}\b", text).start()
        assert text.index(definition) <= first_use - 2, abbr  # the definition is the first mention
    assert "IDA" in text[:text.index("## Figures")] and "incremental dynamic analysis" in text


def test_cells_flags_and_explanations(built):
    text = built["text"]
    first = text[text.index("## Per item and floor"):text.index("## Method")]
    rows = {(m.group(1), m.group(2)): m.group(0) for m in re.finditer(r"^\| (\w+) \| (\d) \|.*$", first, re.M)}
    assert f"0.9{OUTSIDE_MARK} [0.95, 1.3]" in rows[("cabinet", "3")]
    assert OUTSIDE_MARK not in rows[("cabinet", "1")] and OUTSIDE_MARK not in rows[("rack", "1")]
    assert f"{OUTSIDE_MARK} The maximum-likelihood estimate lies outside its own bootstrap interval (cabinet on floor 3)" in text
    assert "none overturned (80 cases)" in rows[("printer", "1")]
    # P at PFV 1 m/s of rack, floor 3: Phi(ln(1/0.4)/0.35) = 0.99558 in closed form, three decimals; cabinet,
    # floor 1 at 0.25 m/s: Phi(ln(0.25/0.8)/0.3) = 5.3e-5, below the table's resolution
    assert "| 0.996 |" in rows[("rack", "3")] and "| < 0.001 |" in rows[("cabinet", "1")]
    assert "0.4 (E.20.22.102a)" in rows[("rack", "1")] and "not mapped" in rows[("cabinet", "1")]
    # failures counted by the kind of their reason (their numbers differ), the first reason of each kind in full
    assert "3 cases failed" in text and "| lost | 1 | lost to the infrastructure: worker process died" in text
    assert f"| max_steps | 2 | {MAX_STEPS_REASON} (max_steps = 10000000, t = 12.5 s) |" in text


def test_sentences_agree_with_the_numbers(built):
    found = {f.item: f for f in summary.floor_findings(built["table"])}
    assert found["rack"].kind == "lower_higher" and found["rack"].medians == (0.6, 0.5, 0.4)
    assert "rack overturns at a lower PFV on higher floors" in built["text"]
    assert found["cabinet"].kind == "mixed" and "cabinet overturns at" not in built["text"]
    assert found["printer"].kind == "none"
    # each sentence's claim checked against the table it came from, and every kind reached
    for f in found.values():
        med = built["table"].set_index(["item", "floor"])["median_pfv"]
        values = [med[(f.item, fl)] for fl in f.floors]
        assert list(f.medians) == values
        if f.kind == "lower_higher":
            assert all(a > b for a, b in zip(values, values[1:]))
    # reversing the floors' medians reverses the sentence; equal medians say "the same"
    t2 = built["table"].copy()
    t2.loc[t2["item"] == "rack", "median_pfv"] = [0.4, 0.5, 0.6]
    assert {f.item: f.kind for f in summary.floor_findings(t2)}["rack"] == "higher_higher"
    t2.loc[t2["item"] == "rack", "median_pfv"] = 0.5
    assert "the same PFV median on every fitted floor" in {f.item: f for f in summary.floor_findings(t2)}["rack"].text
    # a fit that failed (perfect separation: a finite "median" in the middle of the gap, ok False) is not a
    # median a sentence may quote: the table says "no fit" there
    t4 = built["table"].copy()
    t4.loc[(t4["item"] == "rack") & (t4["floor"] == "2"), ["status_pfv", "median_pfv"]] = ["no fit", 0.9]
    rack = {f.item: f for f in summary.floor_findings(t4)}["rack"]
    assert rack.floors == ("1", "3") and "0.9 m/s" not in rack.text and rack.kind == "lower_higher"
    # floor labels without an order: no claim about "higher" floors, the lowest and highest named
    t3 = built["table"].replace({"floor": {"1": "lobby", "2": "mezzanine", "3": "attic"}})
    rack = {f.item: f for f in summary.floor_findings(t3)}["rack"]
    assert rack.kind == "unordered" and "lowest on floor attic and highest on floor lobby" in rack.text
    # one building's labels give the order: ground, b3.f1, ..., roof
    assert summary.floor_order(["b3.roof", "b3.f10", "ground", "b3.f2"]) == ["ground", "b3.f2", "b3.f10", "b3.roof"]
    assert not summary.floors_are_numbered(["b3.f1", "b4.f1"])  # two buildings: no order


def test_curves_carry_bands_and_leave_out_unfitted_items(built):
    c = built["curves"]
    assert "printer" not in set(c["item"])
    rack = c[(c["item"] == "rack") & (c["floor"] == "1") & (c["demand"] == "pfv")]
    assert (rack["p_lo"] <= rack["p"] + 1e-12).all() and (rack["p"] <= rack["p_hi"] + 1e-12).all()
    assert set(c.groupby(["item", "floor", "demand"]).size()) == {120}


def test_item_figure_is_readable(built, tmp_path):
    fig = drawn_figure(plots, plots.plot_item_fragility, built["curves"], "cabinet", tmp_path / "c.png")
    ax = fig.axes[0]
    legend = ax.get_legend()
    assert all(t.get_fontsize() >= 8 for t in legend.get_texts())
    # one curve per floor, the direction always named (issue 44: a legend that dropped it read as both)
    assert [t.get_text() for t in legend.get_texts()] == ["floor 1, direction 1", "floor 2, direction 1",
                                                          "floor 3, direction 1"]
    assert "(m/s)" in ax.get_xlabel() and "PFV" in ax.get_xlabel() and "(-)" in ax.get_ylabel()
    lines = [ln for ln in ax.get_lines() if ln.get_label().startswith("floor")]
    # floors 1 and 2 coincide: both drawn, told apart by line style; fitted curves carry no markers (issue 44:
    # markers on a curve read as data points)
    assert np.allclose(lines[0].get_ydata(), lines[1].get_ydata())
    assert lines[0].get_linestyle() != lines[1].get_linestyle()
    assert all(ln.get_marker() in ("None", None, "") for ln in lines)
    assert all(t.get_fontsize() >= 8 for t in ax.get_xticklabels() + ax.get_yticklabels())


def test_demand_figure_is_readable(tmp_path):
    fig = drawn_figure(plots, plots.plot_floor_demands, summary.demand_table(synthetic_demands()), tmp_path / "d.png")
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels == ["PFA, peak floor acceleration (g)", "PFV, peak floor velocity (m/s)"]
    for ax in fig.axes:
        assert all(t.get_fontsize() >= 8 for t in ax.get_legend().get_texts())
    pfa = fig.axes[0].get_lines()[0].get_ydata()
    assert pfa.max() == pytest.approx(0.2 * 3 * 1.4)  # m/s² converted to g: 9.81 * 0.84 / 9.81


def test_figures_written_as_png(built):
    for path in built["drawn"].values():
        assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert matplotlib.get_backend().lower() == "agg"


def test_sliding_gets_its_own_table_after_overturning(tmp_path):
    fits = synthetic_fits()
    slide = fits[fits["item"] == "rack"].assign(outcome="sliding", median=lambda d: d["median"] / 2,
                                                median_lo=lambda d: d["median_lo"] / 2,
                                                median_hi=lambda d: d["median_hi"] / 2)
    both = pd.concat([fits, slide], ignore_index=True)
    tables = summary.report_tables(both, LEVELS)
    assert list(tables["sliding"]["item"]) == ["rack"] * 3 and tables["sliding"]["median_pfv"].tolist() == [0.3, 0.25, 0.2]
    inputs = ReportInputs(title="t", method="cloud", fits=both, demands=synthetic_demands(), expected=pd.DataFrame(),
                          inventory=pd.DataFrame(), figures={}, notes=(), pelicun={}, **tables)
    text = write_report(tmp_path / "report.md", inputs).read_text()
    assert text.index("## Per item and floor: overturning") < text.index("## Per item and floor: sliding")
    assert "| rack | 1 | 0.3 [0.25, 0.35] |" in text and "**cloud**" in text


def test_an_extrapolated_median_is_marked_and_explained():
    """A median beyond every demand tested (fits.py's status ``extrapolated``) gets its own
    mark in the table and a note saying it is extrapolated; the other rows stay unmarked."""
    from opsrock.inventory.report import EXTRAPOLATED_MARK, footnotes, formatted_table

    fits = synthetic_fits()
    rack3 = (fits["item"] == "rack") & (fits["floor"] == "3") & (fits["demand"] == "pfv")
    fits.loc[rack3, "status"] = "extrapolated"
    table = summary.item_floor_table(fits)
    cells = formatted_table(table).set_index(["item", "floor"])
    assert EXTRAPOLATED_MARK in cells.loc[("rack", "3"), "median PFV (m/s) [95 %]"]
    assert EXTRAPOLATED_MARK not in cells.loc[("rack", "3"), "median PFA (g) [95 %]"]
    assert EXTRAPOLATED_MARK not in cells.loc[("rack", "1"), "median PFV (m/s) [95 %]"]
    notes = "".join(footnotes(table, "overturned"))
    assert f"{EXTRAPOLATED_MARK} The median lies beyond the largest demand any case of rack on floor 3 reached" in notes


def test_each_item_figure_spans_its_own_curves():
    """An extrapolated median of 1e6 m/s on one item leaves every other item's grid where its own curves are
    (median · exp(±2.5 beta), the closed form of P = 0.006 to 0.994), and the item's own measured rows
    keep it out of its grid too."""
    fits = synthetic_fits()
    rack3 = (fits["item"] == "rack") & (fits["floor"] == "3") & (fits["demand"] == "pfv")
    fits.loc[rack3, ["median", "status"]] = [1e6, "extrapolated"]
    curves = summary.curve_table(fits)
    pfv = curves[curves["demand"] == "pfv"]
    cabinet = pfv[pfv["item"] == "cabinet"]["x"]
    assert cabinet.max() == pytest.approx(0.9 * math.exp(2.5 * 0.3), rel=1e-12)
    assert cabinet.min() == pytest.approx(0.8 * math.exp(-2.5 * 0.3), rel=1e-12)
    assert pfv[pfv["item"] == "rack"]["x"].max() == pytest.approx(0.6 * math.exp(2.5 * 0.4), rel=1e-12)


def test_each_ratio_to_fema_splits_into_fema_s_own_rule_and_what_it_leaves_out():
    """Issue 44: ratio = rule_factor x beyond_factor, rule_factor = (b/h_cm)/(b/h)_FEMA x T_floor/T_FEMA with
    T_floor = 2 pi PFV/PFA of the floor's records (values made up; the rule is opsrock.published.fema_p58's)."""
    import math as _m

    from opsrock.inventory.items import FrictionLaw, Item
    from opsrock.inventory.summary import fema_ratio_reasons
    from opsrock.published.fema_p58 import ITEMS, REFERENCE_PERIOD

    ref = next(it for it in ITEMS if it.fema_id == "E.20.22.105a")
    item = Item("book", "a bookcase", 0.3, 0.9, 1.8, cm_height=0.8, friction=FrictionLaw("fixed", (0.1,)),
                fema_id="E.20.22.105a")
    table = pd.DataFrame([{"item": "book", "floor": "1", "direction": d, "fema_id": "E.20.22.105a",
                           "ratio_fema": 2.0} for d in ("1", "2")])
    demands = pd.DataFrame({"record": ["a", "b", "c"], "floor": "1", "direction": "1", "pfa": [4.0, 5.0, 6.0],
                            "pfv": [0.4, 0.4, 0.9]})
    out = fema_ratio_reasons(table, {"book": item}, demands)
    assert list(out["direction"]) == ["1"]  # the narrower side only, as FEMA's items rock about their depth
    r = out.iloc[0]
    period = 2 * _m.pi * 0.1  # 2 pi times the median of PFV/PFA over the three records (0.1, 0.08, 0.15)
    assert r["rule_factor"] == pytest.approx((0.3 / 1.6) / ref.aspect_ratio * period / REFERENCE_PERIOD, rel=1e-12)
    assert r["rule_factor"] * r["beyond_factor"] == pytest.approx(2.0, rel=1e-12)
    assert r["slides_first"] and "slides before it rocks" in r["reason"]  # friction 0.1 < b/h 0.19


def test_an_item_that_slides_without_a_slide_cost_is_named_once(tmp_path):
    """An item expected to slide (units displaced, not overturned) that has no ``slide_cost`` gets one line saying
    its sliding adds nothing to the repair cost, naming its floors; a priced slider and an item that never slides
    (its displaced units all overturned) get none."""
    expected = pd.DataFrame({
        "item": ["cabinet", "cabinet", "rack", "bookcase", "printer"], "floor": ["1", "2", "1", "1", "1"],
        "quantity": [4.0, 4.0, 6.0, 12.0, 3.0], "expected_damaged": [1.0, 2.5, 0.3, 4.0, 0.0],
        "expected_displaced_only": [1.0, 2.5, 0.1, 0.0, 0.0], "expected_overturned": [0.0, 0.0, 0.2, 4.0, 0.0],
        "slide_cost": [math.nan, math.nan, 3000.0, math.nan, math.nan],
        "repair_cost": [500.0, 500.0, 30000.0, 300.0, 800.0], "expected_cost": [0.0, 0.0, 6300.0, 1200.0, 0.0]})
    tables = summary.report_tables(synthetic_fits(), LEVELS)
    inputs = ReportInputs(title="t", method="ida", fits=synthetic_fits(), demands=synthetic_demands(),
                          expected=expected, inventory=pd.DataFrame(), figures={}, notes=(), pelicun={}, **tables)
    text = write_report(tmp_path / "report.md", inputs).read_text()
    lines = [line for line in text.splitlines() if "no `slide_cost`" in line]
    assert lines == ["- **cabinet** slides (units displaced and not overturned expected on floors 1, 2) but has no "
                     "`slide_cost`: its sliding adds nothing to the repair cost."]
    assert text.index("Total expected repair cost") < text.index(lines[0])
