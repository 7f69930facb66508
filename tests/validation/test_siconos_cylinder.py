"""The case file of the Siconos cylinder reference (opsrock.validation.siconos_cylinder, issue 45): what the Siconos
model reads must be opsrock's own floor motion in the cylinder's frame and the cylinder's radius, centre-of-mass height
and inertia as cylinder3d reads them (no Siconos needed here; ``make test-siconos`` runs both)."""

import json
import math

import numpy as np
import pytest

from opsrock.constants import G
from opsrock.solvers.cylinder3d import cylinder_properties
from opsrock.validation import siconos_cylinder as sc


def test_case_file_holds_the_motion_and_the_cylinders_properties(tmp_path):
    cases = sc.pulse_cases()[:4] + sc.pulse_cases()[-2:]
    data = np.load(sc.write_cases(tmp_path / "cases.npz", cases))
    meta = json.loads(str(data["meta"]))
    assert len(meta) == len(cases)
    for m, case in zip(meta, cases):
        s = slice(m["start"], m["start"] + m["n"])
        ax, ay = case.motion.components(np.arange(m["n"]) * m["dt"])
        # PlanMotion.components sampled as is: equal to round-off
        np.testing.assert_allclose(data["ax"][s], ax, rtol=0, atol=1e-12)
        np.testing.assert_allclose(data["ay"][s], ay, rtol=0, atol=1e-12)
        cyl = cylinder_properties(case.block)
        assert (m["r"], m["h"], m["inertia"]) == (cyl.r, cyl.h, [cyl.i_h, cyl.i_h, cyl.i_z])
        assert m["mu"] == case.block.friction


def test_case_set_and_the_pulses_amplitudes():
    """32 cases (24 pulses, 8 record cases counted from the constants: loading the library costs seconds), the
    quick form every fifth (7); each pulse peaks at its stated multiple of ``g r / h``, all above the Siconos
    16-gon's lowest uplift threshold (``cos(pi/16)`` of it), along its stated direction."""
    pulses = sc.pulse_cases()
    n_records = len(sc.RECORD_PAIRS) * len(sc.RECORD_AZIMUTHS)
    assert (len(pulses), n_records) == (24, 8)
    assert len(range(0, len(pulses) + n_records, sc.QUICK_EVERY)) == 7
    assert min(sc.AMPLITUDES) > 1.0 / math.cos(math.pi / 16)
    for c in pulses:
        k = float(c.label.split("a/a_up ")[1].split()[0])
        phi = float(c.label.split("phi ")[1].split()[0])
        cyl = cylinder_properties(c.block)
        assert c.motion.pfa == pytest.approx(k * G * cyl.r / cyl.h, rel=1e-12)
        ax, ay = c.motion.components(np.array([0.25 * c.motion.duration]))
        assert math.degrees(math.atan2(ay[0], ax[0])) == pytest.approx(phi, abs=1e-9)
