"""The study's tables: one unit and one meaning per column name, a ``Units`` row in pelicun's tabular form, the
values at full precision, PFA written in g, and a table without the row refused by the reader."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from opsrock.constants import G
from opsrock.inventory.columns import COLUMNS, UNITS_ROW, OldTableError, read_table, units_of, write_table
from opsrock.inventory.components import COMPONENT_COLUMNS, EXPECTED_COLUMNS
from opsrock.inventory.fits import FIT_COLUMNS
from opsrock.inventory.side_by_side import SIDE_COLUMNS
from opsrock.inventory.three_d import BOX_COLUMNS, FIT3D_COLUMNS

DOCS = Path(__file__).resolve().parents[3] / "docs" / "guide" / "inventory.md"
DEMAND_COLUMNS = ("record", "floor", "direction", "pfa", "pfv", "pfd", "mean_period", "predominant_period")


@pytest.mark.parametrize("columns", [FIT_COLUMNS, COMPONENT_COLUMNS, EXPECTED_COLUMNS, FIT3D_COLUMNS, DEMAND_COLUMNS,
                                     BOX_COLUMNS, SIDE_COLUMNS])
def test_every_column_of_every_table_has_one_definition(columns):
    assert len(units_of(columns)) == len(columns)


def test_a_column_without_a_definition_is_not_written(tmp_path):
    with pytest.raises(KeyError, match="no_such_column"):
        write_table(pd.DataFrame({"item": ["a"], "no_such_column": [1.0]}), tmp_path / "t.csv")


def test_the_units_row_follows_the_header_and_the_values_round_trip(tmp_path):
    """pfa kept in m/s² inside, written in g (divided by G = 9.81, the study's g); every other float exactly as
    given (repr round trip), read back by pandas with the row skipped and by read_table with the units."""
    x = [0.1 + 0.2, 1 / 3, 7.05579345]
    df = pd.DataFrame({"record": ["a", "b", "c"], "floor": ["1", "2", "3"], "direction": ["1", "1", "2"],
                       "pfa": x, "pfv": x, "pfd": x, "mean_period": x, "predominant_period": x})
    path = write_table(df, tmp_path / "demands.csv")
    lines = path.read_text().splitlines()
    assert lines[0] == ",".join(DEMAND_COLUMNS) and lines[1] == f"{UNITS_ROW},,,g,m/s,m,s,s"
    table, units = read_table(path, dtype={"floor": str, "direction": str})
    assert units["pfa"] == "g" and units["pfv"] == "m/s"
    assert table["pfv"].tolist() == x and table["pfa"].tolist() == [v / G for v in x]
    # the documented pandas way; pandas 2's default parser is not correctly rounded (0.1 + 0.2 read back as
    # 0.30000000000000004), so there it takes float_precision="round_trip", which pandas 3 makes the default
    exact = {} if int(pd.__version__.split(".")[0]) >= 3 else {"float_precision": "round_trip"}
    plain = pd.read_csv(path, skiprows=[1], **exact)
    assert np.array_equal(plain["pfd"].to_numpy(), np.array(x))


def test_a_table_written_before_the_units_row_is_refused_with_what_to_do(tmp_path):
    old = tmp_path / "demands.csv"
    old.write_text("record,floor,direction,pfa,pfv\nnorthridge,1,1,7.05,0.64\n")
    with pytest.raises(OldTableError, match=r"demands\.csv: no 'Units' row.*run the study again"):
        read_table(old)


def test_the_docs_table_of_columns_is_the_list_itself():
    """One definition per column name across outputs and docs: the inventory guide's table repeats
    :data:`COLUMNS` row for row (unit and meaning), nothing more, nothing less."""
    section = DOCS.read_text().split("## The study's tables: one unit and one meaning per column")[1].split("\n#")[0]
    rows = re.findall(r"^\| `([^`]+)` \| ([^|]*) \| (.*) \|$", section, flags=re.M)
    assert {name: (unit.strip(), meaning) for name, unit, meaning in rows} == {
        k: (c.unit, c.meaning) for k, c in COLUMNS.items()}
