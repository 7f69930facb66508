"""The case file of the Siconos reference (opsrock.validation.siconos3d): what the Siconos model reads must be
opsrock's own floor motion in the block frame and the kernel's inertia rule (no Siconos needed here)."""

import csv
import json
import math

import numpy as np

from opsrock.solvers.rigid3d.solver import box_properties
from opsrock.validation.siconos3d import PULSE_DT, smoke_cases, write_cases


def test_case_file_holds_the_block_frame_motion_and_inertia(tmp_path):
    cases = smoke_cases()
    data = np.load(write_cases(tmp_path / "cases.npz", cases))
    meta = json.loads(str(data["meta"]))
    assert len(meta) == len(cases)
    for m, case in zip(meta, cases):
        s = slice(m["start"], m["start"] + m["n"])
        t = np.arange(m["n"]) * m["dt"]
        ax, ay = case.motion.components(t)
        # the arrays are PlanMotion.components sampled as is: equal to round-off
        np.testing.assert_allclose(data["ax"][s], ax, rtol=0, atol=1e-12)
        np.testing.assert_allclose(data["ay"][s], ay, rtol=0, atol=1e-12)
        assert m["dt"] == PULSE_DT
        assert m["inertia"] == list(box_properties(case.block).inertia)
        assert (m["b"], m["d"], m["h"]) == (case.block.b, case.block.d, case.block.h_cm)
    # the 30-deg case: a_y / a_x = tan(30 deg) wherever the pulse is not zero (PlanMotion.along's frame)
    m = meta[1]
    s = slice(m["start"], m["start"] + m["n"])
    ax, ay = data["ax"][s], data["ay"][s]
    big = np.abs(ax) > 1.0
    np.testing.assert_allclose(ay[big] / ax[big], math.tan(math.radians(30.0)), rtol=1e-12)


# --- the comparison logic on a small synthetic table (opsrock.validation.siconos3d_compare; no Siconos, no solver)

import pytest  # noqa: E402

from opsrock.validation import siconos3d_compare as sc  # noqa: E402
from opsrock.validation import siconos3d as sc3  # noqa: E402
from opsrock.validation.siconos3d import pulse_cases, uplift_threshold  # noqa: E402

ALPHA = 0.25


def _rigid(overturned=False, tilt=0.1, flips=False, flight=0.0, t_end=5.0, slide=0.0, status="ok"):
    return sc.Rigid3DRun(overturned, tilt, slide, ALPHA, t_end, flight, status, flips, 0.01)


def _sic(overturned=False, tilt=0.1, steps=8000, slide=0.0, status="ok"):
    return {"overturned": overturned, "tilt_max": tilt, "slide_max": slide, "twist_max": 0.0, "wall_s": 1.0,
            "steps": steps, "status": status, "step": sc.STEP}


def test_classify_tries_the_classes_in_order():
    # agreement: no class
    assert sc.classify(_rigid(), _sic(), 1.0) == ""
    # the amplitude test flips: ill-conditioned, whatever else holds
    assert sc.classify(_rigid(True, math.pi / 2, flips=True), _sic(tilt=0.95 * ALPHA), 1.0) == "ill-conditioned"
    # the solver that stayed up came within NEAR alpha of... (0.95 alpha >= 0.9 alpha)
    assert sc.classify(_rigid(True, math.pi / 2), _sic(tilt=0.95 * ALPHA), 1.0) == "near the threshold"
    assert sc.classify(_rigid(tilt=0.92 * ALPHA), _sic(True, math.pi / 2), 1.0) == "near the threshold"
    # 0.5 alpha is not near; flight in rigid3d
    assert sc.classify(_rigid(True, math.pi / 2, flight=0.01), _sic(tilt=0.5 * ALPHA), 1.0) == \
        "flight/late overturning"
    # rigid3d overturned at 6 s, after Siconos's run ended (8000 steps x 5e-4 s = 4 s) and the 1-s motion
    assert sc.classify(_rigid(True, math.pi / 2, t_end=6.0), _sic(tilt=0.5 * ALPHA), 1.0) == \
        "flight/late overturning"
    # Siconos at half the step agrees with rigid3d: step size; otherwise unexplained
    assert sc.classify(_rigid(True, math.pi / 2, t_end=2.0), _sic(tilt=0.5 * ALPHA), 1.0, True) == "step size"
    assert sc.classify(_rigid(True, math.pi / 2, t_end=2.0), _sic(tilt=0.5 * ALPHA), 1.0, False) == "unexplained"
    assert sc.classify(_rigid(True, math.pi / 2, t_end=2.0), _sic(tilt=0.5 * ALPHA), 1.0) == "unexplained"
    # a failed run has no verdict to differ
    assert sc.classify(_rigid(True, math.pi / 2, t_end=2.0, status="failed"), _sic(tilt=0.5 * ALPHA), 1.0) == ""


def _row(i, rigid, sic):
    diff = sc.classify(rigid, sic, 1.0)
    return sc.Row(i, f"case {i}", "pulse", 1.0, rigid, sic, rigid.flips, diff)


def test_summary_counts_only_well_conditioned_cases_and_both_up_tilts():
    rows = [_row(i, _rigid(tilt=0.1), _sic(tilt=0.1 + 2e-4 * i)) for i in range(18)]  # d/alpha = 8e-4 i
    rows.append(_row(18, _rigid(True, math.pi / 2, flips=True), _sic(tilt=0.2)))           # ill-conditioned
    rows.append(_row(19, _rigid(True, math.pi / 2, t_end=2.0), _sic(tilt=0.1)))                    # a real difference
    s = sc.summarize(rows)
    assert (s.n_cases, s.n_ill, s.n_well, s.n_agree) == (20, 1, 19, 18)
    assert s.agreement == pytest.approx(18 / 19, rel=1e-15)
    assert s.n_tilt == 18
    d = np.arange(18) * 2e-4 / ALPHA
    assert s.tilt_median == pytest.approx(np.median(d), rel=1e-12)
    assert s.tilt_p95 == pytest.approx(np.percentile(d, 95), rel=1e-12)
    assert s.classes["ill-conditioned"] == 1 and s.classes["unexplained"] == 1
    # 18/19 = 94.7 % < 95 %: below target
    assert not s.passed
    assert sc.summarize(rows[:19]).passed
    # a failed run is never counted as agreeing and fails the targets
    bad = rows[:19] + [_row(20, _rigid(status="failed"), _sic())]
    assert sc.summarize(bad).n_failed == 1 and not sc.summarize(bad).passed


def test_tables_round_trip_at_full_precision(tmp_path):
    rows = [_row(0, _rigid(tilt=0.1 + 1e-13), _sic(tilt=1 / 3)), _row(1, _rigid(True, math.pi / 2, t_end=2.0), _sic(tilt=0.1))]
    sc.write_tables(rows, sc.summarize(rows), tmp_path)
    data = list(csv.DictReader(open(tmp_path / "cases.csv")))
    assert float(data[0]["rigid3d_tilt_max"]) == 0.1 + 1e-13 and float(data[0]["siconos_tilt_max"]) == 1 / 3
    assert data[1]["difference"] == "unexplained"
    summary = dict(csv.reader(open(tmp_path / "summary.csv")))
    assert summary["n_cases"] == "2"


def test_case_set_size_and_thresholds():
    # the pulses are built here; the record pairs are counted from the set's constants (loading the FEMA P695
    # library costs seconds: make test-siconos builds them)
    pulses = pulse_cases()
    n_records = 2 * len(sc3.RECORD_PAIRS) * len(sc3.RECORD_AZIMUTHS)
    # the issue asks for at least 200 cases; the quick form (every tenth) about 20
    assert len(pulses) + n_records >= 200 and n_records >= 40
    assert 15 <= len(range(0, len(pulses) + n_records, 10)) <= 25
    assert all(c.block.restitution_factor == 1.0 for c in pulses)
    # the uplift threshold in plan: g/h min(b/|cos|, d/|sin|) (issue 33), here at 0 and 90 deg: g b/h and g d/h
    b = pulses[0].block
    assert uplift_threshold(b, 0.0) == pytest.approx(9.81 * b.b / b.h_cm, rel=1e-12)
    assert uplift_threshold(b, 90.0) == pytest.approx(9.81 * b.d / b.h_cm, rel=1e-12)
    # each pulse's peak is its stated multiple of the threshold along its direction
    k = [float(c.label.split("a/a_up ")[1].split()[0]) for c in pulses]
    phi = [float(c.label.split("phi ")[1].split()[0]) for c in pulses]
    for c, kk, ph in zip(pulses, k, phi):
        assert c.motion.pfa == pytest.approx(kk * uplift_threshold(c.block, ph), rel=1e-12)
