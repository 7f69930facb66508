"""The FEMA P-58 nine's tables (``opsrock contents`` without an inventory): one unit and one meaning per column name,
shared with the inventory study's where a name is both's, a ``Units`` row written by the one writer, the values
round-tripping, and a table written before the row still read."""

from __future__ import annotations

import re

import pandas as pd

from opsrock._files import UNITS_ROW
from opsrock.inventory.columns import COLUMNS as STUDY_COLUMNS
from opsrock.inventory.fema.columns import COLUMNS, read_fema_table, units_of, write_fema_table
from _support import ROOT

DOCS = ROOT / "docs" / "guide" / "contents.md"


def test_shared_names_keep_the_inventory_study_s_unit():
    assert not set(COLUMNS) & set(STUDY_COLUMNS)  # one definition per name
    assert units_of(["item", "median", "ratio_fema", "n_cases"]) == ["", "see unit", "-", "-"]


def test_the_values_round_trip_and_a_table_without_the_row_reads_the_same(tmp_path):
    x = [0.1 + 0.2, 1 / 3, 7.05579345]
    df = pd.DataFrame({"item": ["a", "b", "c"], "T1": x, "median_pfv": x, "ratio_rule": x, "median_pfa_g": x})
    path = write_fema_table(df, tmp_path / "sweep.csv")
    assert path.read_text().splitlines()[:2] == ["item,T1,median_pfv,ratio_rule,median_pfa_g", f"{UNITS_ROW},s,m/s,-,g"]
    new = read_fema_table(path)
    assert new["median_pfv"].tolist() == x
    old = tmp_path / "old.csv"
    df.to_csv(old, index=False)  # as the study wrote its tables before the row
    pd.testing.assert_frame_equal(read_fema_table(old), new)


def test_the_docs_table_of_columns_is_the_list_itself():
    """The contents guide's table repeats :data:`COLUMNS` row for row (unit and meaning), nothing more or less."""
    section = DOCS.read_text().split("## The tables' columns")[1].split("\n#")[0]
    rows = re.findall(r"^\| `([^`]+)` \| ([^|]*) \| (.*) \|$", section, flags=re.M)
    assert {name: (unit.strip(), meaning) for name, unit, meaning in rows} == {
        k: (c.unit, c.meaning) for k, c in COLUMNS.items()}
