"""The case file of the Siconos reference (opsrock.validation.siconos3d): what the Siconos model reads must be
opsrock's own floor motion in the block frame and the kernel's inertia rule (no Siconos needed here)."""

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
