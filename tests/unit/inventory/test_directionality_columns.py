"""The directionality study's tables (``opsrock contents --model both``): one unit and one meaning per column name,
shared with the inventory study's where a name is both's (and never one of the FEMA P-58 nine's), a ``Units`` row
written by the one writer, PFA written in g, the values round-tripping, and a table written before the row (PFA in
m/s² then) still read, to the same frame."""

from __future__ import annotations

import re

import pandas as pd

from opsrock._files import UNITS_ROW
from opsrock.constants import G
from opsrock.inventory.columns import COLUMNS as STUDY_COLUMNS
from opsrock.inventory.directionality.columns import (COLUMNS, read_directionality_table, units_of,
                                                      write_directionality_table)
from opsrock.inventory.fema.columns import COLUMNS as FEMA_COLUMNS
from _support import ROOT

DOCS = ROOT / "docs" / "guide" / "directionality.md"


def test_one_definition_per_name_across_the_three_lists():
    assert not set(COLUMNS) & set(STUDY_COLUMNS) and not set(COLUMNS) & set(FEMA_COLUMNS)
    assert not set(FEMA_COLUMNS) & set(STUDY_COLUMNS)
    # a fit's median (the inventory study's "see unit") is a PFV here in every row
    assert units_of(["item", "median", "pfv_nd", "pfa_1", "n_overturned"]) == ["", "m/s", "m/s", "g", "-"]


def test_pfa_is_written_in_g_the_values_round_trip_and_an_older_table_reads_the_same(tmp_path):
    pfa = [4.0788312300000005, 13.904260314472252, 0.1 + 0.2]  # m/s2, as the study holds them
    pfv = [0.5894769296229171, 1 / 3, 2.0610242639462637]
    df = pd.DataFrame({"record": ["a", "b", "c"], "floor": ["ground", "8", "roof"], "pfa_1": pfa, "pfv_1": pfv})
    path = write_directionality_table(df, tmp_path / "demands.csv")
    assert path.read_text().splitlines()[:2] == ["record,floor,pfa_1,pfv_1", f"{UNITS_ROW},,g,m/s"]
    new = read_directionality_table(path, dtype={"floor": str})
    assert new["pfa_1"].tolist() == [x / G for x in pfa] and new["pfv_1"].tolist() == pfv
    old = tmp_path / "old.csv"
    df.to_csv(old, index=False)  # as the study wrote its tables before the row: PFA in m/s2
    pd.testing.assert_frame_equal(read_directionality_table(old, dtype={"floor": str}), new)


def test_the_docs_table_of_columns_is_the_list_itself():
    """The directionality guide's table repeats :data:`COLUMNS` row for row (unit and meaning), nothing more or less."""
    section = DOCS.read_text().split("## The tables' columns")[1].split("\n#")[0]
    rows = re.findall(r"^\| `([^`]+)` \| ([^|]*) \| (.*) \|$", section, flags=re.M)
    assert {name: (unit.strip(), meaning) for name, unit, meaning in rows} == {
        k: (c.unit, c.meaning) for k, c in COLUMNS.items()}
