"""The rigid cylinder in three dimensions (``cylinder3d``, issue 45): each check with its reference.

1. the uplift threshold ``g r / h`` in every direction (moment balance about the rim point), and the rim point it
   lifts about; 2. the planar limit against ``housner_fast`` with ``width = 2r`` and the cylinder's ``cm_height`` and
   ``radius_of_gyration``; 3. rotation invariance (a record pair at any azimuth); 4. energy kept while the cylinder
   rolls on its rim without slip or impact; 5. Srinivasan & Ruina's angle of turn; 6. sliding before rocking;
   7. what it refuses. The slow tier (test_cylinder3d_slow.py) runs the planar limit on a grid.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputError, InputTypeError
from opsrock.excitations import OneSinePulse, Record
from opsrock.excitations.pulses import RectangularPulse
from opsrock.excitations.plan import PlanMotion
from opsrock.solvers import housner_fast, simulate
from opsrock.solvers.cylinder3d import (cylinder_block, cylinder_properties, free_motion, mechanical_energy, solve,
                                        tilted_state)

#: A homogeneous cylinder 0.3 m across and 1.2 m tall: r/h = 0.25, alpha = 0.245 rad, e_H = 0.911.
CYL = cylinder_block(0.3, 1.2)


# =============================================================================================
# 1. Uplift threshold in every direction
# =============================================================================================


@pytest.mark.parametrize("phi", [0.0, 37.0, 90.0, 143.0, 250.0])
def test_uplift_threshold_g_r_over_h_in_every_direction(phi):
    """A rectangular pulse along ``phi`` at 0.99 and 1.01 of ``g r / h``: the floor's inertia force at the centre of
    mass tips the cylinder about the rim point its centre of pressure reaches, ``|a| h = g r`` whatever the direction
    (the base is a circle of radius ``r``). The rest skip decides a seated cylinder by exactly this criterion, so the
    1 % margin is far from anything numerical. Lifted, it leans away from the floor's acceleration (towards the
    inertia force): the lean's direction is ``phi + 180`` deg to round-off (1e-9 rad: the first step's contact is
    the rim point towards the load, and nothing breaks the symmetry of the plane)."""
    a = G * cylinder_properties(CYL).r / CYL.h_cm
    for factor, lifts in ((0.99, False), (1.01, True)):
        r = solve(CYL, PlanMotion.along(RectangularPulse.from_duration(factor * a, 0.15), phi))
        assert r.ok and r.rocked == lifts, (phi, factor, r.theta_max)
        assert (r.theta_max > 1e-5) == lifts
        if lifts:
            axis = Rotation.from_rotvec(r.plan_history.rotation).apply([0.0, 0.0, 1.0])
            k = int(np.argmax(np.hypot(axis[:, 0], axis[:, 1])))
            lean = math.degrees(math.atan2(axis[k, 1], axis[k, 0]))
            assert abs((lean - phi - 180.0 + 180.0) % 360.0 - 180.0) < 1e-7, (lean, phi)


# =============================================================================================
# 2. Planar limit
# =============================================================================================

#: Pulses ``(PFA / (g tan alpha), omega_p / p)``: safe with the peak before and after the first impact, and
#: overturning.
PULSES = [(1.2, 2.0), (1.6, 4.0), (6.0, 8.0), (2.5, 4.0)]


@pytest.mark.parametrize("ratios", PULSES)
def test_planar_limit_against_housner_fast(ratios):
    """One component along ``x``, a base that never slips: the cylinder rocks in the vertical plane through its axis
    as the planar rigid block of width ``2r``, its ``cm_height`` and ``radius_of_gyration`` (:func:`cylinder_block`'s
    block is that block), Housner's impact at the landing rim point included. Reference ``housner_fast``
    (event-driven, exact impacts). Tolerance 1e-3 alpha on the peak: the accuracy of Moreau-Jean at the default step
    dtau = 1e-4 (rigid3d's accuracy table, the same scheme: about 1e-4 alpha on pulses, 1e-3 on records, whose many
    impacts add up; a rim point rolling without slip is crossed by Runge-Kutta, fourth order); measured at most
    3.6e-4 over 30 pulses (the slow tier)."""
    pulse = OneSinePulse.from_ratios(CYL, *ratios)
    ref = housner_fast.solve(CYL, pulse)
    r = solve(CYL, pulse, record=False)
    assert r.ok and ref.ok and r.verdict == ref.verdict
    assert abs(r.theta_max - ref.theta_max) / CYL.alpha < 1e-3
    assert r.plan.twist_max < 1e-12 and abs(r.plan.slide_residual[1]) < 1e-12  # it stays in the plane


# =============================================================================================
# 3. Rotation invariance
# =============================================================================================


def _two_components(seed: int, n: int = 600, dt: float = 0.01) -> tuple[Record, Record]:
    """Two synthetic floor-motion components (filtered noise, 6 s, PGA 0.3 g), derandomised by ``seed``."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(2):
        x = np.convolve(rng.standard_normal(n), np.hanning(15), mode="same")
        x *= np.sin(np.pi * np.arange(n) / (n - 1)) ** 2
        out.append(Record(dt=dt, values=0.3 * G * x / np.max(np.abs(x))))
    return out[0], out[1]


def test_rotation_invariance_of_a_record_pair():
    """The same record pair at azimuths 0, 40, 135 and 260 deg: the cylinder is round, so the tilt, twist and slide
    and the verdict are the same. The records are turned into the floor frame by the azimuth (round-off), and nothing
    in the model has a preferred direction (the contact is the lowest rim point, or the flat base's points from the
    load's direction); the peak tilt agrees to 1e-9 alpha (measured 4e-14 on a pulse: round-off, which the impacts
    may amplify; no stick-slip decision here, the base never slips)."""
    first, second = _two_components(5)
    runs = [solve(CYL, PlanMotion(first, second, azimuth=az), record=False) for az in (0.0, 40.0, 135.0, 260.0)]
    assert all(r.ok for r in runs)
    assert runs[0].rocked and runs[0].n_impacts > 0  # the pair rocks it, with impacts
    for r in runs[1:]:
        assert r.verdict == runs[0].verdict
        assert abs(r.plan.tilt_max - runs[0].plan.tilt_max) < 1e-9 * CYL.alpha


# =============================================================================================
# 4. Energy while rolling
# =============================================================================================


def test_energy_is_kept_while_it_rolls_without_slip_or_impact():
    """Released tilted by 0.15 rad and turning about the vertical at 3 rad/s on a still floor, the cylinder wobbles:
    its contact point runs round the rim (rolling) and its tilt stays above 0.04 rad (no landing). Rolling without
    slip does no work, so its energy is kept up to the scheme's error. Moreau-Jean steps throughout (``smooth=False``)
    are first order in the step: the relative change is below 1e-3 over 2 s at the default step (measured 3.5e-4)
    and halves with the step (ratio in [1.7, 2.3]; measured 2.0). The smooth phase (the default: fourth-order
    Runge-Kutta sub-steps of ``1e-2/p``, the constraint's drift removed after each) keeps it below 1e-5, a hundredth
    of that (measured 4.5e-7; 1.3e-8 with sub-steps half as long), and the contact point runs round the rim by the angle the Moreau-Jean steps converge to at first order
    (11.410, 11.451, 11.472 rad at dtau 1e-4, 5e-5, 2.5e-5; the smooth phase 11.494 at 1e-4 and 5e-5): within 1 % of
    the Moreau-Jean run at 5e-5 (measured 0.37 %)."""
    block = cylinder_block(0.4, 1.2)
    s0 = tilted_state(block, 0.15, 0.0, 3.0)
    e0 = sum(mechanical_energy(block, s0))
    changes, turns = [], []
    for dtau, smooth in ((1e-4, False), (5e-5, False), (1e-4, True)):
        r = free_motion(block, s0, end_time=2.0, dtau=dtau, smooth=smooth)
        assert r.ok and r.n_impacts == 0 and r.plan.time_sliding == 0.0
        assert np.min(np.abs(r.theta)) > 0.04 or np.min(np.linalg.norm(r.plan_history.rotation[:, :2], axis=1)) > 0.04
        assert r.plan.time_rolling > 0.5 * 2.0 and abs(r.diagnostics["contact_turn"]) > 2 * math.pi
        assert (r.diagnostics["roll_steps"] > 0) == smooth
        changes.append((r.plan.energy["kinetic"] + r.plan.energy["potential"] - e0) / e0)
        turns.append(r.diagnostics["contact_turn"])
    assert abs(changes[0]) < 1e-3
    assert 1.7 < changes[0] / changes[1] < 2.3
    assert abs(changes[2]) < 1e-5
    assert turns[2] == pytest.approx(turns[1], rel=1e-2)


# =============================================================================================
# 5. Srinivasan & Ruina's angle of turn
# =============================================================================================


@pytest.mark.parametrize("omega_z", [0.01, 0.03])
def test_angle_of_turn_of_a_tall_cylinder_released_nearly_flat(omega_z):
    """Srinivasan & Ruina, "Rocking and rolling: a can that appears to rock might actually roll", Phys. Rev. E 78,
    066609 (2008): a tall body (height much bigger than radius) released tilted with a small turning velocity falls
    nearly flat without slapping: its contact point runs round the rim by an angle of turn *just over pi*, nearly
    independent of the initial conditions, and it rises leaning on the nearly opposite rim point. A cylinder 0.2 m
    across and 1.2 m tall (H/D = 6) released at 0.05 rad turning at ``omega_z`` about the vertical, followed to its
    next rise (0.6 s): the turn lies in (pi, 1.1 pi) (measured 1.014 pi and 1.019 pi), without a landing."""
    block = cylinder_block(0.2, 1.2)
    r = free_motion(block, tilted_state(block, 0.05, 0.0, omega_z), end_time=0.6)
    assert r.ok and r.n_impacts == 0
    turn = abs(r.diagnostics["contact_turn"])
    assert math.pi < turn < 1.1 * math.pi, turn / math.pi


# =============================================================================================
# 6. Sliding
# =============================================================================================


def test_it_slides_before_it_rocks_when_mu_is_below_r_over_h():
    """mu = 0.15 < r/h = 0.25: a rectangular pulse at 0.2 g (above mu g, below g r/h) slides the base without
    lifting it (Coulomb: the floor can pass at most mu g to the base), opposite the pulse's direction (1e-4 deg, the
    bound kept from the Gauss-Seidel solve this slide once took; the flat base's closed form slides it straight); the
    tilt stays zero to round-off."""
    block = cylinder_block(0.3, 1.2, friction=0.15)
    r = solve(block, PlanMotion.along(RectangularPulse.from_duration(0.2 * G, 0.3), 60.0))
    assert r.ok and r.contact.first_mode == "slide" and r.plan.time_sliding > 0.0
    assert r.plan.tilt_max < 1e-9
    sx, sy = r.plan.slide_residual
    assert math.degrees(math.atan2(sy, sx)) == pytest.approx(60.0 - 180.0, abs=1e-4)


def test_energy_balance_has_rigid3ds_terms_and_closes():
    """The energy balance carries rigid3d's keys. A base sliding without lifting (mu = 0.2 < r/h, a pulse at 2 g tan
    alpha): friction takes the floor's work, the residual (the scheme's) below 1e-5 of it (measured 1.1e-6, halving
    with the step). A rocking block that overturns after one landing (no slip): no friction work, an impact loss,
    the residual below 2e-3 of the input (measured 5.6e-4 at the default step, 1.2e-3 at twice it: first order).
    The friction work is the impulses' whole work at the end velocities, the normal part zero at a solved contact."""
    slide = cylinder_block(0.3, 1.2, friction=0.2)
    e = solve(slide, PlanMotion.along(OneSinePulse.from_ratios(slide, 2.0, 3.0), 25.0)).plan.energy
    assert set(e) >= {"input_work", "kinetic", "potential", "friction_work", "impact_loss", "residual"}
    assert e["impact_loss"] == 0.0 and e["friction_work"] > 0.9 * e["input_work"] > 0.0
    assert abs(e["residual"]) < 1e-5 * e["input_work"]
    rock = cylinder_block(0.3, 1.2)
    r = solve(rock, PlanMotion.along(OneSinePulse.from_ratios(rock, 2.0, 3.0), 25.0))
    e = r.plan.energy
    assert r.overturned and r.n_impacts == 1 and e["impact_loss"] > 0.0
    assert abs(e["friction_work"]) < 1e-12 * e["input_work"]  # the normal impulses' P_N u_N: round-off (8e-15 J)
    assert abs(e["residual"]) < 2e-3 * e["input_work"]


def _flat_state(block, vx, vy, wz):
    """The kernel state of ``block`` standing on its base at rest position, moving in plan with ``(vx, vy)`` (m/s)
    and twisting at ``wz`` (rad/s)."""
    return np.array([0.0, 0.0, block.h_cm, 1.0, 0.0, 0.0, 0.0, vx, vy, 0.0, 0.0, 0.0, wz])


def test_a_base_sliding_on_the_floor_stops_where_coulomb_says():
    """A 0.5 x 1.0 m cylinder (mu = 0.3 < r/h = 0.5: it cannot tip) launched along 30 deg at 0.5 m/s on its base on
    a still floor slides ``v² / (2 mu g)`` = 42.5 mm and stops, straight, without tilt or twist: the flat base's
    closed form (pure sliding: the limit surface's exact end, ``|F| = mu N``). Tolerance 1e-3 relative: Moreau-Jean's
    theta-method is second order in the step on a constant deceleration, the stop within a step of ``dt v / 2``, 2e-4
    of the slide here; no step of it is left to NSGS."""
    block = cylinder_block(0.5, 1.0, friction=0.3)
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    r = free_motion(block, _flat_state(block, 0.5 * c, 0.5 * s, 0.0), end_time=0.5)
    assert r.ok and r.diagnostics["nsgs_unconverged_steps"] == 0 and r.diagnostics["flat_closed_steps"] > 0
    sx, sy = r.plan.slide_residual
    assert math.hypot(sx, sy) == pytest.approx(0.25 / (2 * 0.3 * G), rel=1e-3)
    assert math.degrees(math.atan2(sy, sx)) == pytest.approx(30.0, abs=1e-9)
    assert r.plan.tilt_max < 1e-12 and r.plan.twist_max < 1e-12


def test_a_base_twisting_on_the_floor_stops_where_coulomb_says():
    """The same cylinder twisting on its base at 5 rad/s: every rim point slips at ``r omega``, so the friction
    moment is ``mu N r`` (the limit surface's other exact end) and ``i_z = r²/2`` stops it after ``omega² r / (4 mu
    g)`` = 0.531 rad of twist, the base centre still (its centre slides by round-off only). Tolerance 1e-3 relative
    (as the slide's)."""
    block = cylinder_block(0.5, 1.0, friction=0.3)
    r = free_motion(block, _flat_state(block, 0.0, 0.0, 5.0), end_time=0.5)
    assert r.ok and r.diagnostics["nsgs_unconverged_steps"] == 0
    assert r.plan.twist_max == pytest.approx(25.0 * 0.25 / (4 * 0.3 * G), rel=1e-3)
    assert r.plan.slide_max < 1e-12 and r.plan.tilt_max < 1e-12


def test_a_flat_landing_with_slide_and_twist_is_solved_in_closed_form():
    """The oxygen cylinder (0.23 x 1.5 m) dropped level from 1 mm with a horizontal velocity and a twist (the state
    after which NSGS over the 16 rim points once failed to converge for 500 steps in a row, issue 45) lands
    plastically on its whole base (one impact) and slides and twists to rest on it in the flat base's closed form:
    the run ends ok, no contact step left unconverged, no tilt (mu = 0.1 < r/h = 0.153: friction cannot trip it;
    with mu = 0.5 it tips on landing, as it should)."""
    block = cylinder_block(0.23, 1.5, friction=0.1)
    s = _flat_state(block, 0.3, -0.2, 2.0)
    s[2] += 1e-3
    r = free_motion(block, s, end_time=1.0)
    assert r.ok and r.diagnostics["nsgs_unconverged_steps"] == 0 and r.n_impacts == 1
    assert r.plan.tilt_max < 1e-9 and r.diagnostics["flat_closed_steps"] > 0


@pytest.mark.parametrize("theta_dot0, ends_ok", [(0.0, True), (-0.2, False)])
def test_the_tail_ends_by_the_energy_only_below_what_overturning_takes(theta_dot0, ends_ok):
    """After the excitation nothing works on the cylinder (rolling without slip keeps its energy, slip and impacts
    take from it), and overturning needs its tilt to pass alpha, where its centre of mass stands ``R`` high: below
    ``m g (R - h)`` it can never overturn. Released at 0.9 alpha on its rim (0.990 of that energy) under a negligible
    pulse, and cut by ``max_free_time`` (0.05 s, mid-fall, no landing), the run ends ok, not overturned, its ending
    stated and the tilt its energy can reach (``alpha - acos((E / m g + h) / R)``: 0.9 alpha up to the pulse's and
    the scheme's work, below 1e-5 alpha) given; with 1.046 of that energy (falling back at 0.2 rad/s) it is failed
    with its reason, never cut. The old rule ended only below 0.9 of it: the first case failed."""
    cyl = cylinder_properties(CYL)
    pulse = PlanMotion.along(RectangularPulse.from_duration(1e-3 * G, 0.01), 0.0)
    r = solve(CYL, pulse, theta0=0.9 * CYL.alpha, theta_dot0=theta_dot0, max_free_time=0.05)
    assert r.ok == ends_ok and not r.overturned
    if not ends_ok:
        assert r.failure == "max_free_time" and "times what overturning takes" in r.reason
        return
    d = r.diagnostics
    assert d["ending"].startswith("energy below overturning energy") and d["tail_bound"] and r.n_impacts == 0
    start = sum(mechanical_energy(CYL, tilted_state(CYL, 0.9 * CYL.alpha))) / (CYL.mass * G * (cyl.R - cyl.h))
    assert d["tail_energy_ratio"] == pytest.approx(start, rel=1e-5)  # measured +5e-7: the pulse's and scheme's work
    bound = d["tilt_bound"]
    assert abs(r.theta[-1]) < bound < CYL.alpha and abs(bound - 0.9 * CYL.alpha) < 1e-5 * CYL.alpha
    e = (r.plan.energy["kinetic"] + r.plan.energy["potential"]) / (CYL.mass * G)
    assert bound == pytest.approx(cyl.alpha - math.acos((e + cyl.h) / cyl.R), abs=1e-9)


# =============================================================================================
# 7. Refusals
# =============================================================================================


def test_refuses_a_base_that_is_not_round_and_other_restitutions():
    with pytest.raises(InputError, match="depth"):
        solve(Block(0.3, 1.2, restitution_factor=1.0, depth=0.6), OneSinePulse.from_ratios(CYL, 2.0, 3.0))
    with pytest.raises(InputError, match="restitution"):
        solve(Block(0.3, 1.2, restitution_factor=0.9), OneSinePulse.from_ratios(CYL, 2.0, 3.0))
    with pytest.raises(InputTypeError, match="smooth"):
        solve(CYL, OneSinePulse.from_ratios(CYL, 2.0, 3.0), smooth="yes")
    r = simulate(CYL, OneSinePulse.from_ratios(CYL, 2.0, 3.0), solver="cylinder3d")
    assert r.solver == "cylinder3d" and r.plan is not None
