"""The friction solver on frictionless and near-frictionless floors, its ending rule, and free flight,
against closed forms (docs/guide/friction.md: the ending rule, frictionless floors, the flight rule)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputError
from opsrock.excitations import OneSinePulse, RectangularPulse, Record
from opsrock.excitations.vertical import MAX_FREE_FALL, check_free_fall, longest_free_fall
from opsrock.published import newmark_1965
from opsrock.solvers import friction
from opsrock.solvers.friction.modes import FLIGHT, REST


def _one_sine_floor(t: np.ndarray, a: float, omega: float) -> np.ndarray:
    """Displacement (m) of a floor under the one-sine pulse ``a sin(omega t)`` from rest, and after it."""
    t_end = 2.0 * math.pi / omega
    tc = np.minimum(t, t_end)
    return a / omega * tc - a / omega**2 * np.sin(omega * tc)


def _record_floor(rec: Record) -> tuple[float, float]:
    """Velocity (m/s) and displacement (m) of a floor at the end of ``rec`` (piecewise linear), exactly."""
    a, dt = rec.values, rec.dt
    v = np.concatenate(([0.0], np.cumsum(0.5 * dt * (a[:-1] + a[1:]))))
    x = np.sum(v[:-1] * dt + dt**2 * (2.0 * a[:-1] + a[1:]) / 6.0)
    return float(v[-1]), float(x)


STEP = Record(dt=0.01, values=np.r_[np.full(100, 0.1 * G), np.zeros(100)], name="step", units="m/s2")


@pytest.mark.parametrize("mu", [0.0, 1e-320])
@pytest.mark.parametrize("a_v", [0.0, 0.5 * G, -0.4 * G])
def test_frictionless_slide_is_minus_the_floor_displacement(mu, a_v):
    """No horizontal force: u(t) = -x_g(t) at every recorded time; the one-sine floor ends at rest, so does
    the block (at -x_g(T)), whatever the vertical acceleration."""
    a, omega = 1.0 * G, 2.0 * math.pi
    r = friction.solve(Block(0.4, 2.2, friction=mu), OneSinePulse(a, omega, vertical=a_v))
    assert r.ok and r.response == "slid" and r.contact.first_mode == "slide"
    assert r.theta_max == 0.0 and not r.rocked
    assert np.max(np.abs(r.slide + _one_sine_floor(r.time, a, omega))) < 1e-8
    assert r.contact.slide_residual == pytest.approx(-a / omega * 2.0 * math.pi / omega, rel=1e-9)
    assert r.contact.slip_velocity_end == 0.0 and not r.contact.still_sliding
    assert r.n_steps < 1000 and r.time[-1] == pytest.approx(1.0)
    assert abs(r.contact.energy["residual"]) < 1e-8 * G * 1.118  # J/kg, against m g R


@pytest.mark.parametrize("mu", [0.0, 1e-320, 1e-6])
def test_a_slide_friction_cannot_stop_ends_with_its_velocity(mu):
    """A floor that ends moving: the frictionless block slides on for ever at -v_g(end); the case ends at
    the end of the record with status ok, the slide so far, and that slip velocity."""
    v_end, x_end = _record_floor(STEP)
    t = STEP.duration  # the block slips backwards from t = 0 on: friction mu g acts forwards throughout
    r = friction.solve(Block(0.4, 2.2, friction=mu), STEP)
    assert r.ok and r.response == "slid"
    assert r.contact.still_sliding
    assert r.contact.slip_velocity_end == pytest.approx(-v_end + mu * G * t, rel=1e-12)
    assert r.contact.slide_residual == pytest.approx(-x_end + mu * G * t**2 / 2.0, rel=1e-12)
    assert r.time[-1] == pytest.approx(STEP.duration)
    e = r.contact.energy
    assert e["kinetic"] == pytest.approx(0.5 * r.contact.slip_velocity_end**2, rel=1e-12)  # J/kg: the slide's
    assert abs(e["residual"]) < 1e-8 * e["input_work"]


@pytest.mark.parametrize("a_g, t1, mu", [(0.5, 0.3, 0.02), (0.1, 1.0, 0.01)])
def test_the_ending_rule_follows_the_closed_form_stop(a_g, t1, mu):
    """Newmark's rectangular pulse with a small friction: the slide stops after t1 + v1 / (mu g). With a
    follow-up longer than that the slide is Newmark's to round-off; shorter, the case ends after the pulse
    with the slide (a - mu g) t1² / 2 and the slip velocity v1 = (a - mu g) t1, still status ok."""
    block, pulse = Block(1.0, 2.0, friction=mu), RectangularPulse(a_g * G, math.pi / t1)
    a_rel = a_g * G - mu * G
    v1, stop = a_rel * t1, a_rel * t1 / (mu * G)
    long = friction.solve(block, pulse, max_free_time=stop * 1.01)
    assert long.ok and not long.contact.still_sliding
    assert long.contact.slide_residual == pytest.approx(-newmark_1965.rectangular_slide(a_g * G, t1, mu), rel=1e-12)
    short = friction.solve(block, pulse, max_free_time=stop * 0.99)
    assert short.ok and short.contact.still_sliding
    assert short.contact.slip_velocity_end == pytest.approx(-v1, rel=1e-12)
    assert short.contact.slide_residual == pytest.approx(-a_rel * t1**2 / 2.0, rel=1e-12)
    assert short.time[-1] == pytest.approx(t1, rel=1e-12)


def test_a_frictionless_free_rocking_block_keeps_its_centre_of_mass_on_its_vertical():
    """Set rocking on a frictionless floor the pivot cannot hold: the block slide-rocks; with f = 1 (no
    loss beyond the rigid impact law) no horizontal force acts and x_cm stays put; it comes to rest."""
    block = Block(0.4, 2.2, friction=0.0, restitution_factor=1.0)
    r = friction.solve(block, None, theta0=0.5 * block.alpha, end_time=1.0)
    assert r.ok and r.contact.first_mode == "slide_rock" and r.n_impacts > 10
    s = np.sign(r.theta)
    x_cm = s * block.b + r.slide - block.R * np.sin(s * block.alpha - r.theta)
    assert np.ptp(x_cm) < 1e-8
    assert abs(r.contact.energy["residual"]) < 1e-6 * r.contact.energy["initial"]


def _drop(a_over_g: float, n_drop: int, dt: float = 0.01, n: int = 400) -> Record:
    """A still floor horizontally whose vertical acceleration is -a for ``n_drop`` samples, then 0."""
    v = np.zeros(n)
    v[:n_drop] = -a_over_g * G
    return Record(dt=dt, values=np.zeros(n), vertical=v, name="drop")


@pytest.mark.parametrize("a_over_g, n_drop", [(3.0, 10), (1.5, 30), (2.0, 1)])
def test_free_flight_of_a_block_thrown_by_a_falling_floor(a_over_g, n_drop):
    """Closed form: the gap grows at (a - g) while the floor falls at a (then along the linear ramp to 0 over
    one sample), and closes under g; the block lands flat, and the landing takes all the kinetic energy."""
    rec = _drop(a_over_g, n_drop)
    dt, a = rec.dt, a_over_g * G
    t_drop = (n_drop - 1) * dt
    v, h = (a - G) * t_drop, (a - G) * t_drop**2 / 2.0
    a0, a1 = a - G, -G  # the relative acceleration over the ramp, linear from a0 to a1
    v, h = v + dt * (a0 + a1) / 2.0, h + v * dt + dt**2 * (2.0 * a0 + a1) / 6.0
    land = math.sqrt(v * v + 2.0 * G * h)
    flight = t_drop + dt + (v + land) / G
    r = friction.solve(Block(0.4, 2.2, friction=0.5), rec)
    assert r.ok and r.contact.first_mode == "flight" and r.n_impacts == 1
    assert r.contact.time_flight == pytest.approx(flight, rel=1e-8)
    assert r.contact.energy["impact_loss"] == pytest.approx(0.5 * land**2, rel=1e-8)
    assert r.contact.energy["input_work"] == pytest.approx(0.5 * land**2, rel=1e-8)
    assert r.theta_max == 0.0 and r.contact.slide_max == 0.0 and r.response == "at_rest"


def test_flight_is_a_kernel_of_its_own_that_only_a_case_leaving_the_floor_enters():
    """Free flight is compiled only when a block first leaves the floor (issue 43): ``solve_case`` solves a case that
    stays on the floor alone, and hands a take-off over to ``fly_case``, which hands the landing back, through the
    state vector; the solver's result is what that sequence computes."""
    from opsrock.solvers.friction import kernel as K
    from opsrock.solvers.friction.settings import FrictionSettings
    from opsrock.solvers.friction.solver import case_parameters

    block = Block(0.4, 2.2, friction=0.5)

    def calls(excitation):
        params, kvals, gvals = case_parameters(block, excitation, FrictionSettings())
        args = (params, kvals, gvals, np.zeros(K.OUT_SIZE), K.history(10_000), K.state())
        seq = [int(K.solve_case(*args))]
        while seq[-1] == K.AIRBORNE:
            seq.append(int(K.fly_case(*args)))
            if seq[-1] == K.LANDED:
                seq.append(int(K.solve_case(*args)))
        return seq, args[3], args[4]

    seq, out, _ = calls(OneSinePulse.from_ratios(block, 4.0, 6.0))
    assert seq == [K.STATUS_OK] and out[K.OUT_IMPACTS] > 0 and out[K.OUT_TIME_FLIGHT] == 0.0
    rec = _drop(3.0, 10)
    seq, out, hist = calls(rec)
    assert seq == [K.AIRBORNE, K.LANDED, K.STATUS_OK]
    r = friction.solve(block, rec)
    n = int(out[K.OUT_N_HIST])
    assert np.array_equal(r.theta, hist[:n, K.H_THETA]) and np.array_equal(r.slide, hist[:n, K.H_U] * block.R)
    assert r.contact.time_flight == out[K.OUT_TIME_FLIGHT] / block.p > 0.0


def test_a_floor_falling_faster_than_g_for_long_is_refused():
    """-3 g for 9.99 s (the floor would fall 1.5 km) is no floor motion: refused naming vertical, before any
    work; a stretch just under MAX_FREE_FALL is followed when the block lands inside the record (-3 g for 0.98 s
    leaves the floor 9.4 m below the block, moving down at 19 m/s: it lands 5.3 s later, inside a 10-s record,
    not inside a 4-s one, whose end it would outlast in flight: refused, issue 46)."""
    long = _drop(3.0, 1000, n=1000)
    assert longest_free_fall(long) == pytest.approx((9.99, 0.0))
    with pytest.raises(InputError, match=r"vertical: .*for 9\.99 s on end from t = 0 s") as err:
        friction.solve(Block(0.4, 2.2, friction=0.5), long)
    assert err.value.argument == "vertical"
    n_ok = int(MAX_FREE_FALL / 0.01) - 1
    check_free_fall(_drop(3.0, n_ok, n=1000))
    with pytest.raises(InputError, match=r"vertical: .* m below it when the record ends"):
        check_free_fall(_drop(3.0, n_ok, n=400))
    assert friction.solve(Block(0.4, 2.2, friction=0.5), _drop(1.2, n_ok, n=400)).ok
    with pytest.raises(InputError, match="vertical"):
        check_free_fall(_drop(3.0, n_ok + 2, n=400))


def _relative_flight(t_off: float, rec: Record) -> float:
    """Closed form of a flight on a still floor horizontally: the block leaves at ``t_off`` (where ``g + a_v`` is 0,
    at rest relative to the floor) and falls at ``-(g + a_v)`` relative to it, ``a_v`` linear between samples; the
    gap's velocity and height are integrated exactly sample interval by sample interval (a linear acceleration: a
    quadratic velocity, a cubic height) until the record's ``a_v`` is 0 again, then it closes under ``g``."""
    dt, gv = rec.dt, G + rec.vertical
    v = h = 0.0
    t, i = t_off, int(t_off / dt)
    while gv[i] != G or gv[i + 1] != G:
        a0 = gv[i] + (gv[i + 1] - gv[i]) * (t - i * dt) / dt  # the relative acceleration is -(g + a_v)
        a1, span = gv[i + 1], (i + 1) * dt - t
        v, h = v - span * (a0 + a1) / 2.0, h + v * span - span**2 * (2.0 * a0 + a1) / 6.0
        t, i = (i + 1) * dt, i + 1
    return t - t_off + (v + math.sqrt(v * v + 2.0 * G * h)) / G


def test_a_seated_block_takes_off_whenever_its_floor_falls_faster_than_g():
    """A block seated after a first flight leaves the floor again when ``g + a_v`` crosses 0 partway through the
    record (-3 g on samples 0-9 and 200-209, no horizontal motion), in flight, not rocking: with no horizontal
    force and the support gone nothing can tilt it, and the symmetric floor brings it back down flat. Before the fix
    the block left rest at 1.99 s by the rest threshold's rule for round-off (rock, as if ``a_h`` had overcome it;
    ``g + a_v`` was 5e-14 there, 1 ulp of the time before its 0), slide-rocked with a negative contact force and
    overturned at 2.56 s.

    References: the second take-off is at the 0 of ``g + a_v`` on its linear ramp from 1 g (sample 199) to -2 g
    (sample 200), t = 1.99 + 0.01/3 s; the kernel jumps there in closed form (``next_exceedance_scaled``), so only
    the round-off of ``tau = p t`` (about 1e-15 s) separates them: 1e-12 s. Each flight's length is
    :func:`_relative_flight`'s closed form; the kernel's RK4 is exact for an acceleration linear in time and
    locates the landing to a few ulps (and the gap's 1e-12 R), so the two agree to round-off: rel 1e-8 as in
    :func:`test_free_flight_of_a_block_thrown_by_a_falling_floor`. No rotation: ``theta`` is 0 exactly (no torque
    acts, the landings are flat), asserted exact."""
    v = np.zeros(400)
    v[:10] = v[200:210] = -3.0 * G
    rec = Record(dt=0.01, values=np.zeros(400), vertical=v, name="two drops")
    block = Block(0.4, 2.2, friction=0.5)
    r = friction.solve(block, rec)
    assert r.ok and not r.overturned and not r.rocked and r.contact.first_mode == "flight"
    assert r.n_impacts == 2 and r.response == "at_rest"
    assert r.theta_max == 0.0 and np.all(r.theta == 0.0) and r.contact.slide_max == 0.0
    assert r.contact.time_rocking == 0.0 and r.contact.time_sliding == 0.0
    t_cross = 1.99 + 0.01 / 3.0
    assert r.contact.time_flight == pytest.approx(_relative_flight(0.0, rec) + _relative_flight(t_cross, rec), rel=1e-8)
    take_offs, modes = _take_offs(block, rec)
    assert set(modes) == {REST, FLIGHT}
    assert take_offs.shape == (2,) and take_offs[0] == 0.0
    assert take_offs[1] == pytest.approx(t_cross, abs=1e-12)


def test_a_block_whose_support_vanishes_as_its_pivot_would_slip_takes_off():
    """The same floor with a constant horizontal 1e-14 g: at the 0 of ``g + a_v`` that ``a_h`` overcomes the block
    (``g + a_v`` is 5e-14 there), it starts rocking, and its pivot's friction hold and contact force vanish in the
    same step; the stick-slip event came first and the block slide-rocked with a negative contact force (the
    slide-rock contact event needs it positive at a step's start) and overturned at 2.56 s. Now a rocking block whose
    contact force is gone at its stick-slip event takes off. References as in the test above: the take-off at the
    crossing to 1e-12 s (``a_h`` moves it by about 1 ulp of the time), the flights' total to rel 1e-8 (1e-14 g
    horizontal changes no vertical motion). What follows the second landing is not asserted: the block comes down
    tilted by about 1e-28 rad, a corner landing whose rotation does not vanish with the tilt."""
    v = np.zeros(400)
    v[:10] = v[200:210] = -3.0 * G
    rec = Record(dt=0.01, values=np.full(400, 1e-14 * G), vertical=v, name="two drops", units="m/s2")
    block = Block(0.4, 2.2, friction=0.5)
    r = friction.solve(block, rec)
    t_cross = 1.99 + 0.01 / 3.0
    assert r.ok and not r.overturned and r.contact.first_mode == "flight"
    assert r.contact.time_flight == pytest.approx(_relative_flight(0.0, rec) + _relative_flight(t_cross, rec), rel=1e-8)
    take_offs, _ = _take_offs(block, rec)
    assert take_offs.shape == (2,) and take_offs[0] == 0.0
    assert take_offs[1] == pytest.approx(t_cross, abs=1e-12)


def _take_offs(block: Block, rec: Record) -> tuple[np.ndarray, np.ndarray]:
    """The times (s) at which ``block`` leaves the floor under ``rec``, and the modes of its history rows, from the
    kernel's history (the result keeps no mode)."""
    from opsrock.solvers.friction import kernel as K
    from opsrock.solvers.friction.settings import FrictionSettings
    from opsrock.solvers.friction.solver import case_parameters

    params, kvals, gvals = case_parameters(block, rec, FrictionSettings())
    out, hist, state = np.zeros(K.OUT_SIZE), K.history(10_000), K.state()
    status = K.solve_case(params, kvals, gvals, out, hist, state)
    while status == K.AIRBORNE and K.fly_case(params, kvals, gvals, out, hist, state) == K.LANDED:
        status = K.solve_case(params, kvals, gvals, out, hist, state)
    rows = hist[:int(out[K.OUT_N_HIST])]
    modes = rows[:, K.H_MODE]
    return rows[1:, K.H_TAU][(modes[1:] == FLIGHT) & (modes[:-1] != FLIGHT)] / block.p, modes
