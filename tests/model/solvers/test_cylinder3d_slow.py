"""The slow tier of ``cylinder3d`` (issue 45): the planar limit on a grid of pulses against ``housner_fast``.

``pytest -m slow -s tests/model/solvers/test_cylinder3d_slow.py`` prints the table."""

from __future__ import annotations

import numpy as np
import pytest

from opsrock.excitations import OneSinePulse
from opsrock.solvers import housner_fast
from opsrock.solvers.cylinder3d import cylinder_block, solve

pytestmark = pytest.mark.slow


def test_planar_limit_on_a_grid_of_pulses():
    """Two homogeneous cylinders (0.3 x 1.2 m, 0.5 x 1.5 m), one-sine pulses ``omega_p / p`` in {2, 4, 8} and ``PFA /
    (g tan alpha)`` in {1.2, 1.6, 2.5, 4, 6}, one component along ``x``, no slip: the cylinder rocks as the planar
    block of width ``2r`` with its ``cm_height`` and ``radius_of_gyration`` (test_cylinder3d.py, the planar limit).
    Every verdict equal; ``|d theta_max| / alpha`` below 1e-3 (Moreau-Jean's accuracy at the default step, the
    fast test's reasoning); measured 30/30, median 3e-5, largest 3.9e-4."""
    diffs, rows = [], []
    for diameter, height in ((0.3, 1.2), (0.5, 1.5)):
        block = cylinder_block(diameter, height)
        for freq in (2.0, 4.0, 8.0):
            for pfa in (1.2, 1.6, 2.5, 4.0, 6.0):
                pulse = OneSinePulse.from_ratios(block, pfa, freq)
                ref, r = housner_fast.solve(block, pulse), solve(block, pulse, record=False)
                assert r.ok and ref.ok and r.verdict == ref.verdict, (diameter, freq, pfa)
                d = (r.theta_max - ref.theta_max) / block.alpha
                diffs.append(abs(d))
                rows.append(f"{diameter:4g} x {height:4g}  {freq:3g}  {pfa:4g}  {ref.verdict:10s}  "
                            f"{ref.theta_max_over_alpha:9.5f}  {d:+.2e}")
    print("\nD x H (m)    w/p   PFA/(g tan a)  verdict  theta_max/alpha  d/alpha\n" + "\n".join(rows))
    print(f"median {np.median(diffs):.2e}, largest {max(diffs):.2e}")
    assert max(diffs) < 1e-3
