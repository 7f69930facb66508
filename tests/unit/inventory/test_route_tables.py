"""The tables of the contents study's own routes (FEMA P-58's nine, the directionality preset), each written by its
route's writer: the committed studies' every table carries the one ``Units`` row its definitions give, and a column
without a definition is never written. The routes' own definitions are checked in ``test_fema_columns.py`` and
``test_directionality_columns.py``."""

from __future__ import annotations

import pandas as pd
import pytest

from opsrock._files import read_units
from opsrock.inventory.directionality import columns as directionality_columns
from opsrock.inventory.directionality.study import TABLES as DIRECTIONALITY_TABLES
from opsrock.inventory.fema import columns as fema_columns
from opsrock.inventory.fema.study import TABLES as FEMA_TABLES
from _support import ROOT

#: route -> (its committed study, its tables, its columns module, its writer)
ROUTES = {
    "fema": (ROOT / "studies" / "contents", FEMA_TABLES, fema_columns, fema_columns.write_fema_table),
    "directionality": (ROOT / "studies" / "directionality", DIRECTIONALITY_TABLES, directionality_columns,
                       directionality_columns.write_directionality_table),
}
TABLES = [(route, name) for route, (_, tables, _, _) in ROUTES.items() for name in sorted(tables.values())]


@pytest.mark.parametrize("route, name", TABLES, ids=[f"{r}/{n}" for r, n in TABLES])
def test_the_committed_study_tables_carry_their_one_units_row(route, name):
    """The committed study (regenerated with the row) holds every table; its units row is the definitions'."""
    study, _, module, _ = ROUTES[route]
    header, units = read_units(study / name)
    assert units is not None and units == module.units_of(header)


@pytest.mark.parametrize("route", sorted(ROUTES))
def test_a_column_without_a_definition_is_not_written(tmp_path, route):
    write = ROUTES[route][3]
    with pytest.raises(KeyError, match="no_such_column"):
        write(pd.DataFrame({"item": ["a"], "no_such_column": [1.0]}), tmp_path / "t.csv")
    assert not (tmp_path / "t.csv").exists()
