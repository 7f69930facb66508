"""``cases.csv``'s units row (:data:`opsrock.campaign.cases.UNITS`): written after the header with each column's unit,
checked and skipped by :func:`~opsrock.campaign.cases.read_cases`, which reads a ``cases.csv`` written before the row
(an older opsrock) to the same frame. Every expected unit is written here, from the columns' docstrings in
opsrock/campaign/cases.py (SI: m/s² spelled ``m/s2``)."""

from __future__ import annotations

import pandas as pd
import pytest

from opsrock._files import read_units
from opsrock.campaign.cases import (
    CONTACT_COLUMNS, PLAN_COLUMNS, PULSE_COLUMNS, RECORD_COLUMNS, SOURCE_COLUMN, UNITS, read_cases, units_of,
    write_cases_csv,
)  # fmt: skip
from opsrock.errors import InputError

#: A record scene's columns with friction and in plan, and a multi-fidelity campaign's ``source``: every column.
COLUMNS = (*RECORD_COLUMNS, *CONTACT_COLUMNS, *PLAN_COLUMNS, SOURCE_COLUMN)


def _row(k: int) -> dict:
    """A case whose floats need all 17 digits (0.1 + 0.2), with text, flags and empty cells."""
    text = {"case_id": f"box/r{k}/F1/l01", "block": "box", "record": "r", "event": "", "component": "", "floor": "F1",
            "status": "ok", "reason": "", "verdict": "safe", "solver": "friction", "response": "rocked",
            "first_mode": "uplift", "record2": None, "overturned_over": None, SOURCE_COLUMN: "screen",
            "overturned": k == 1, "rocked": True, "level": 1}
    return {c: text[c] if c in text else (0.1 + 0.2) * (k + 1) for c in COLUMNS}


def test_every_column_a_campaign_writes_has_one_unit():
    assert set(UNITS) == {*PULSE_COLUMNS, *COLUMNS}


def test_a_written_cases_csv_has_the_units_row_and_is_read_as_an_old_one_is(tmp_path):
    new, old = tmp_path / "cases.csv", tmp_path / "old.csv"
    write_cases_csv(new, [_row(0), _row(1)], COLUMNS, units_of(COLUMNS, "pfa_g"))
    lines = new.read_text().splitlines(keepends=True)
    header, units = read_units(new)
    assert header == list(COLUMNS) and lines[1].startswith("Units,")
    unit = dict(zip(header, units))
    assert {c: unit[c] for c in ("pfa", "pfa_vertical", "pfv", "pfd", "width", "alpha", "p", "T_m", "wall_time_s",
                                 "cpu_time_s", "slide_max", "tilt_max", "azimuth", "distance_km", "level_value", "IM3", "e_R",
                                 "floor", "status", "overturned")} == {
        "pfa": "m/s2", "pfa_vertical": "m/s2", "pfv": "m/s", "pfd": "m", "width": "m", "alpha": "rad", "p": "rad/s",
        "T_m": "s", "wall_time_s": "s", "cpu_time_s": "s", "slide_max": "m", "tilt_max": "rad", "azimuth": "deg", "distance_km": "km",
        "level_value": "g", "IM3": "-", "e_R": "-", "floor": "", "status": "", "overturned": ""}
    write_cases_csv(tmp_path / "ratio.csv", [_row(0)], COLUMNS, units_of(COLUMNS, "pfa_ratio"))
    assert dict(zip(*read_units(tmp_path / "ratio.csv")))["level_value"] == "-"
    old.write_text(lines[0] + "".join(lines[2:]))  # as an opsrock before the row wrote it: values untouched
    assert read_units(old)[1] is None
    frame = read_cases(new)
    pd.testing.assert_frame_equal(frame, read_cases(old))
    assert frame["pfa"].tolist() == [0.1 + 0.2, (0.1 + 0.2) * 2] and frame["overturned"].tolist() == [False, True]
    assert lines[2].split(",")[COLUMNS.index("pfa")] == repr(0.1 + 0.2)  # full precision, as before


def test_a_units_row_in_other_units_is_refused_naming_the_file(tmp_path):
    path = tmp_path / "cases.csv"
    write_cases_csv(path, [_row(0)], COLUMNS)
    lines = path.read_text().splitlines(keepends=True)
    cells = lines[1].split(",")
    cells[COLUMNS.index("pfa")] = "g"
    path.write_text(lines[0] + ",".join(cells) + "".join(lines[2:]))
    with pytest.raises(InputError) as err:
        read_cases(path)
    assert str(err.value) == (f"{path}: column 'pfa' in 'g' in its units row, expected 'm/s2': not a cases.csv as "
                              "opsrock writes it")
