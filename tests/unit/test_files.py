"""opsrock._files: tables written for the next tool (a spreadsheet, pandas) to read back to the last bit."""

from __future__ import annotations

import numpy as np
import pandas as pd

from opsrock._files import atomic_metrics, read_table


def test_a_metrics_table_holds_plain_numbers_at_full_precision(tmp_path):
    """numpy 2's repr of a scalar is ``np.float64(0.1)``: a validation summary held 15 such cells."""
    metrics = {"a": np.float64(0.1) + np.float64(0.2), "n": np.int64(7), "ok": np.bool_(True), "x": 1 / 3,
               "name": "rigid e_R"}
    atomic_metrics(tmp_path / "summary.csv", metrics)
    text = (tmp_path / "summary.csv").read_text()
    assert "np." not in text
    back = read_table(tmp_path / "summary.csv", index_col="metric")["value"]
    assert float(back["a"]) == 0.30000000000000004 and float(back["x"]) == 1 / 3  # every bit kept
    assert back["n"] == "7" and back["ok"] == "True" and back["name"] == "'rigid e_R'"
    assert isinstance(back, pd.Series)
