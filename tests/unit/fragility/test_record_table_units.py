"""The units rows of ``opsrock fragility``'s tables (:mod:`opsrock.analysis.record_columns`): one unit per column,
the scene's measure resolved, a column without a unit refused, full precision kept, and a table written before the
row read to the same frame. The expected units are written here from the tables' docstrings (the paper's nine IMs
dimensionless; ``blocks.csv``'s and ``sliding.csv``'s medians in their row's ``unit``)."""

from __future__ import annotations

import pandas as pd
import pytest

from opsrock._files import read_units
from opsrock.analysis.record_columns import read_record_table, units_of, write_record_table


def test_the_scene_s_measure_gives_the_unit_of_its_level_values():
    header = ["outcome", "mu", "beta", "mu_lo", "mu_hi", "beta_lo", "beta_hi", "n_overturned", "n_cases"]
    assert units_of("measure_fits", header, "pfa_g") == ["", "g", "-", "g", "g", "-", "-", "-", "-"]
    assert units_of("measure_fits", header, "pfa_ratio")[1] == "-"
    assert units_of("measure_fits", header, "unknown")[1] == "see measure"
    assert units_of("resurrections", ["block", "first_overturned_value"], "pfa_g") == ["", "g"]


def test_per_criterion_counts_and_shares_are_dimensionless_and_an_unknown_column_is_refused():
    assert units_of("frequencies", ["im", "n_resamples", "wins_HR", "share_HR_lo"]) == ["", "-", "-", "-"]
    assert units_of("robustness", ["im", "wins_beta", "share_beta"]) == ["", "-", "-"]
    with pytest.raises(KeyError, match=r"ims.csv: columns without a unit .*'share_HR'"):
        units_of("ims", ["im", "share_HR"])
    with pytest.raises(KeyError, match="'pfa_new'"):
        units_of("blocks", ["block", "pfa_new"])


def test_a_table_is_written_with_its_units_row_and_read_back_exactly_as_an_older_one_is(tmp_path):
    df = pd.DataFrame({"block": ["box", "crate"], "floor": ["ground", "roof"], "demand": ["pfa", "pfv"],
                       "unit": ["m/s2", "m/s"], "mu": [0.1 + 0.2, 2 / 3], "beta": [0.4, 1e-17], "mu_lo": [0.2, 0.5],
                       "mu_hi": [0.4, 0.9], "beta_lo": [0.3, 0.2], "beta_hi": [0.5, 0.6], "n_cases": [80, 80],
                       "n_overturned": [10, 0], "n_records": [8, 8], "success": [True, False], "message": ["", "never"]})
    path = write_record_table(df, tmp_path / "blocks.csv")
    header, units = read_units(path)
    assert header == list(df.columns)
    assert units == ["", "", "", "", "see unit", "-", "see unit", "see unit", "-", "-", "-", "-", "-", "", ""]
    assert path.read_text().splitlines()[1] == "Units,,,,see unit,-,see unit,see unit,-,-,-,-,-,,"
    back = read_record_table(path, keep_default_na=False)
    pd.testing.assert_frame_equal(back, df)  # every float to the last bit (0.1 + 0.2, 2/3)
    lines = path.read_text().splitlines(keepends=True)
    (tmp_path / "old").mkdir()
    old = tmp_path / "old" / "blocks.csv"
    old.write_text(lines[0] + "".join(lines[2:]))
    pd.testing.assert_frame_equal(read_record_table(old, keep_default_na=False), df)
