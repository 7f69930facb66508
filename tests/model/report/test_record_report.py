"""``opsrock fragility``'s report for a loss assessor (:func:`opsrock.analysis.record_report.write_record_report`)
on a synthetic record campaign built here: two blocks on two floors, outcomes drawn from a lognormal
fragility in PFA whose median differs by floor, the scene's measure ``pfa_ratio`` (PFA / (g tan alpha)), one
failed case. The per-block, per-floor table comes first, the IMs are defined before their ranking, the pelicun
IDs carry the floor, no figure pools blocks or floors, and every axis names its quantity and unit."""

from __future__ import annotations

import io
import math
import re

import numpy as np
import pandas as pd
import pytest
from _support import drawn_figure
from scipy import stats

from opsrock._files import read_table, read_units
from opsrock.analysis import record_report as rr
from opsrock.analysis.record_columns import read_record_table, units_of
from opsrock.constants import G
from opsrock.fragility.pelicun_export import read_pelicun_csv
from opsrock.plots import record_fragility as rplots

#: block -> (alpha rad, {floor: median PFA of overturning in units of g tan alpha}).
BLOCKS = {"rack": (0.25, {"ground": 2.0, "b3.f3": 3.0}), "shelf": (0.2, {"ground": 2.5, "b3.f3": 2.5})}
LEVELS = (1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0)


def synthetic_campaign(n_records: int = 10, seed: int = 5) -> pd.DataFrame:
    """Cases of an IDA on ``pfa_ratio``: level value = PFA / (g tan alpha) exactly, PFV = PFA x 0.1 s."""
    rng = np.random.default_rng(seed)
    rows = []
    for block, (alpha, floors) in BLOCKS.items():
        for floor, median in floors.items():
            for r in range(n_records):
                for k, lv in enumerate(LEVELS, start=1):
                    over = bool(rng.random() < stats.norm.cdf(math.log(lv / median) / 0.4))
                    pfa = lv * G * math.tan(alpha)
                    rows.append({"case_id": f"{block}/r{r}/{floor}/l{k}", "block": block, "alpha": alpha,
                                 "record": f"r{r:02d}", "floor": floor, "level": k, "level_value": lv, "status": "ok",
                                 "reason": "", "overturned": over, "rocked": True,
                                 "theta_max_over_alpha": 8.0 if over else 0.5, "pfa": pfa, "pfv": 0.1 * pfa,
                                 "pfa_ratio": pfa / (G * math.tan(alpha)), "magnitude": 6.0 + 0.02 * r,
                                 "distance_km": 10.0 + r, "building_period": np.nan,
                                 **{f"IM{i}": lv * (1 + 0.1 * i) * (1 + 0.05 * r) for i in range(1, 10)}})
    cases = pd.DataFrame(rows)
    cases.loc[0, ["status", "reason"]] = ["failed", "max_steps reached before the end of the run (max_steps = 10000000, t = 12.5 s)"]
    return cases


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("record_report")
    res = rr.write_record_report(synthetic_campaign(), out, n_boot=8, seed=1, source="synthetic",
                                 demand_levels={"pfv": (0.1, 0.3), "pfa": (0.5,)})
    return out, res, (out / "report.md").read_text()


def test_the_scenes_measure_and_method_are_recognised():
    cases = synthetic_campaign(n_records=2)
    assert rr.scene_measure(cases) == "pfa_ratio" and rr.scene_method(cases) == "ida"
    as_g = cases.assign(level_value=cases["pfa"] / G)
    assert rr.scene_measure(as_g) == "pfa_g"
    assert rr.scene_measure(cases.assign(level_value=np.nan)) == "" and rr.scene_method(cases.assign(level_value=np.nan)) == "cloud"
    assert rr.scene_measure(cases.assign(level_value=cases["level_value"] * 1.01)) == "unknown"


def test_the_per_block_per_floor_table_comes_first(report):
    _, res, text = report
    sections = re.findall(r"^## (.+)$", text, re.M)
    assert sections[0] == "Per block and floor, for loss assessment"
    assert sections.index("The paper's nine intensity measures (IMs)") < sections.index(
        "Conclusion: which IM describes overturning best")
    table = text[text.index("## Per block and floor"):text.index("## Method")]
    rows = re.findall(r"^\| (rack|shelf) \| (\S+) \|", table, re.M)
    assert rows == [("rack", "ground"), ("rack", "b3.f3"), ("shelf", "ground"), ("shelf", "b3.f3")]
    assert "| P at PFV 0.1 m/s | P at PFV 0.3 m/s | P at PFA 0.5 g |" in table


def test_every_measure_is_defined_before_its_first_use(report):
    _, _, text = report
    for name, definition in (("PFV", "**PFV** (peak floor velocity, m/s)"), ("PFA", "**PFA** (peak floor acceleration, g"),
                             ("IM1", "| IM1 | `omega_p/p` |"), ("IM9", "| IM9 | `PFA T_p^2/(R tan alpha)` |")):
        first = re.search(rf"\b{name}\b", text).start()
        assert text.index(definition) <= first <= text.index(definition) + len(definition), name
    assert "**PFA / (g tan alpha)** (dimensionless)" in text[:text.index("## Per block")]


def test_pelicun_ids_carry_the_floor(report):
    out, res, _ = report
    ids = {c.component_id for c in read_pelicun_csv(out / "fragility_pelicun.csv")}
    fitted = res.study.blocks[res.study.blocks["success"]]
    assert ids == {f"opsrock.{r.block}.{r.floor}.{r.demand.upper()}" for r in fitted.itertuples()}
    assert len(res.study.blocks) == 2 * 2 * 2  # blocks x floors x (PFA, PFV): no fit pools floors
    blocks = read_record_table(out / "blocks.csv")
    assert list(blocks.columns[:3]) == ["block", "floor", "demand"]


def test_every_table_has_a_units_row_and_reads_back_to_the_study(report, tmp_path):
    """Each CSV table ``opsrock fragility`` writes (but pelicun's own file) has its ``Units`` row after the header, one
    unit per column (``TABLE_UNITS``; the scene's measure ``pfa_ratio`` dimensionless, the blocks' medians in their
    row's unit), and reads back to the study's frame to the last bit; the same table without the row (an older
    opsrock's) reads to the same frame."""
    out, res, _ = report
    written = sorted(p.name for p in out.glob("*.csv"))
    assert written == sorted([*(f"{t}.csv" for t in rr.STUDY_TABLES), "fragility_pelicun.csv"])
    for name in rr.STUDY_TABLES:
        header, units = read_units(out / f"{name}.csv")
        assert units == units_of(name, header), name
        assert units[0] == "" and all(isinstance(u, str) for u in units)
        table = read_record_table(out / f"{name}.csv")
        pd.testing.assert_frame_equal(table, read_table(io.StringIO(getattr(res.study, name).to_csv(index=False))),
                                      check_dtype=False)
        lines = (out / f"{name}.csv").read_text().splitlines(keepends=True)
        old = tmp_path / f"{name}.csv"
        old.write_text(lines[0] + "".join(lines[2:]))
        pd.testing.assert_frame_equal(read_record_table(old), table)
    header, units = read_units(out / "measure_fits.csv")
    assert dict(zip(header, units))["mu"] == "-"  # the scene's measure, PFA / (g tan alpha)
    blocks = dict(zip(*read_units(out / "blocks.csv")))
    assert blocks["mu"] == "see unit" and blocks["unit"] == "" and blocks["beta"] == "-"
    assert dict(zip(*read_units(out / "ims.csv")))["cv_percent"] == "%"


def test_sentences_and_failures_agree_with_the_numbers(report):
    _, res, text = report
    for f in res.findings:
        assert f"- {f.text}" in text
        t = res.table.set_index(["item", "floor"])
        assert [t.loc[(f.item, fl), "median_pfv"] for fl in f.floors] == list(f.medians)
        if f.kind == "same":
            assert max(f.medians) - min(f.medians) <= 1e-6 * max(f.medians)
    assert "1 case failed" in text and "| max_steps | 1 | max_steps reached before the end of the run (max_steps = 10000000, t = 12.5 s) |" in text


def test_no_figure_pools_blocks_or_floors(report):
    out, res, _ = report
    names = sorted(p.name for p in (out / "figures").glob("*.png"))
    assert names == ["fragility_rack.png", "fragility_shelf.png", "ida_curves.png", "im_ranking.png"]
    assert "fragility" not in res.figures and "![Fragility]" not in (out / "report.md").read_text()


def test_axes_name_quantity_and_unit_and_legends_read(report, tmp_path):
    _, res, _ = report
    fig = drawn_figure(rplots, rplots.plot_ida_curves, res.study.cases, tmp_path / "i.png", rr.MEASURE_LABELS["pfa_ratio"])
    for ax in fig.axes:
        if ax.get_visible():
            assert ax.get_xlabel().startswith("PFA / (g tan alpha)") and ax.get_xlabel().endswith("(dimensionless)")
            assert "(-)" in ax.get_ylabel()
            assert all(t.get_fontsize() >= 8 for t in ax.get_legend().get_texts())
    fig = drawn_figure(rplots, rplots.plot_im_ranking, res.study.ims, res.study.frequencies, tmp_path / "r.png")
    assert all(ax.get_ylabel().endswith("(-)") for ax in fig.axes)
    assert all(t.get_fontsize() >= 8 for t in fig.axes[2].get_legend().get_texts())
