"""numpy's fast reading of a record file gives what the careful line-by-line reading gives.

Reference: :func:`opsrock.excitations.readers._data_rows` with Python's ``float`` (the careful reading, which names
the line of every fault); the fast reading must return the same doubles, bit for bit (both round the decimal text
correctly), and hand every file it does not read cleanly back to the careful one.
"""

from __future__ import annotations

import numpy as np
import pytest

from opsrock.errors import RecordFileError
from opsrock.excitations.readers import read_record

FORMATS = ("%.17g", "%.6e", "%.4f", "%g")


def _careful(path, monkeypatch, **kw):
    """The record as the careful reading gives it (the fast one switched off)."""
    import opsrock.excitations.readers as readers

    monkeypatch.setattr(readers, "_fast_table", lambda path, lines: None)
    return read_record(path, **kw)


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("layout", ["one column", "time column csv", "header and blank lines"])
def test_fast_and_careful_readings_agree_bit_for_bit(tmp_path, monkeypatch, fmt, layout):
    rng = np.random.default_rng(46)  # derandomised: the same values every run
    acc = rng.normal(0.0, 0.3, 500)
    if layout == "one column":
        path = tmp_path / "a.txt"
        path.write_text("dt = 0.01\n" + "\n".join(fmt % v for v in acc) + "\n")
    elif layout == "time column csv":
        path = tmp_path / "a.csv"
        path.write_text("\n".join(f"{0.01 * k:.2f},{fmt % v}" for k, v in enumerate(acc)) + "\n")
    else:
        path = tmp_path / "a.txt"
        rows = [f"{0.01 * k:.2f} {fmt % v}" + ("\n" if k % 7 == 0 else "") for k, v in enumerate(acc)]
        path.write_text("# a comment before the header\ntime acc\n" + "\n".join(rows) + "\n")
    fast = read_record(path, units="g")
    careful = _careful(path, monkeypatch, units="g")
    assert fast.dt == careful.dt
    assert np.array_equal(fast.values, careful.values) and fast.values.size == 500


@pytest.mark.parametrize("text, line, reason", [
    ("dt = 0.01\n0.1\n0.2\nnan\n0.3\n", 4, "not a finite number"),
    ("dt = 0.01\n0.1\n0.2 # a note\n0.3\n", 3, "is not a number"),
    ("0.00,0.1\n0.01,0.2\n\n0.02,0.3,9\n", 4, "column(s) where the first data row has 2"),
    ("0.00,0.1\n0.01,0.2\n\n0.05,0.3\n", 4, "non-uniform time step"),
])
def test_a_fault_is_named_at_its_line_by_either_reading(tmp_path, text, line, reason):
    path = tmp_path / "a.csv"
    path.write_text(text)
    with pytest.raises(RecordFileError) as err:
        read_record(path, units="g")
    assert f"a.csv:{line}:" in str(err.value) and reason in str(err.value), str(err.value)


def test_at2_fast_reading_agrees_and_names_a_bad_line(tmp_path, monkeypatch):
    rng = np.random.default_rng(7)
    acc = rng.normal(0.0, 0.1, 40)
    body = "\n".join(" ".join("%.7E" % v for v in acc[k:k + 5]) for k in range(0, 40, 5))
    head = "PEER\nEvent, Station, 000\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   40, DT=   .0050 SEC\n"
    (tmp_path / "r.AT2").write_text(head + body + "\n")
    fast = read_record(tmp_path / "r.AT2")
    assert np.array_equal(fast.values, _careful(tmp_path / "r.AT2", monkeypatch).values)
    (tmp_path / "bad.AT2").write_text(head + body.replace("E", "Q", 1) + "\n")
    with pytest.raises(RecordFileError, match=r"bad.AT2:5: .* is not a number"):
        read_record(tmp_path / "bad.AT2")
