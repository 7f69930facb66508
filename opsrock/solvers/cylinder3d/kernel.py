"""Compiled kernel of :mod:`opsrock.solvers.cylinder3d` (numba): Moreau-Jean time stepping of a rigid cylinder on a
rigid floor, its contact the lowest rim point while tilted (the point runs round the rim as the cylinder rolls) or
points round the rim while its base is flat, Newton's impact law with ``e_n = 0`` and isotropic Coulomb friction.

Everything is per unit mass: positions in m, velocities in m/s and rad/s, impulses in m/s, energies in J/kg,
inertias in m². The floor frame ``(x, y, z)`` is the cylinder's frame at rest (``x`` the first component's
direction at azimuth 0, ``z`` up, origin at the base centre at rest); the floor's accelerations enter as the body
force ``(-a_x, -a_y, -(g + a_v))``. State (13 floats): centre of mass ``X``, unit quaternion ``(w, x, y, z)`` (body
to floor), velocity ``V`` and angular velocity ``omega`` (floor frame).

Only :func:`run` is a numba dispatcher (``cache=True``); every function it calls, here and in the modules it imports, is
a :data:`opsrock.solvers.jitable.jitable` helper compiled into it, without the CPython and C wrappers a dispatcher gets
(issue 43: a third of the first compile). Called from Python, a helper runs as plain Python.
"""

from __future__ import annotations

import math

import numba

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers.cylinder3d.constants import (H_DOWN, H_POS, H_ROT, H_SLIDE, H_T, H_THETA, H_THETA_DOT, H_TWIST,
                                                  LANDING_JUMP, MAX_SUBSTEPS, OUT_CONTACT_STEPS, OUT_CONTACT_TURN,
                                                  OUT_EVENT_TIME, OUT_FIRST_MODE, OUT_FRICTION_WORK, OUT_IMPACT_LOSS,
                                                  OUT_IMPACTS, OUT_INPUT_WORK,
                                                  OUT_NSGS_FAILED, OUT_NSGS_SWEEPS, OUT_N_HIST, OUT_OVERTURNED,
                                                  OUT_OVER_DIR, OUT_OVER_KIND, OUT_REST_STEPS, OUT_ROCKED,
                                                  OUT_SLIDE_MAX, OUT_STATE, OUT_STATUS, OUT_STEPS, OUT_TAIL_CUT,
                                                  OUT_TAIL_ENERGY, OUT_TAIL_SETTLED, OUT_THETA_MAX, OUT_TIME,
                                                  OUT_TIME_BASE, OUT_TIME_FLIGHT, OUT_TIME_ROCKING, OUT_TIME_ROLLING,
                                                  OUT_TIME_SLIDING, OUT_TWIST_MAX, PEAK_BASE_SPEED, PHI_STEP, ROLL_RATE,
                                                  ROLL_TURN, STATUS_CONTACT, STATUS_MAX_STEPS, STATUS_NONFINITE,
                                                  STATUS_OK, STATUS_TAIL, TAIL_CUT_MARGIN, TILT_SLACK, T_CONTACT_RATE,
                                                  ENERGY_ROUNDOFF, OUT_TAIL_BOUND, OUT_TILT_BOUND, OUT_ROLL_FAILED,
                                                  OUT_ROLL_SPAN, OUT_ROLL_STEPS, ROLL_CALM, ROLL_MIN_STEPS, T_CALM,
                                                  OUT_TAIL_WOBBLE, T_W_LAST, T_W_MAXES, T_W_RATE, T_W_RISING, T_W_TOP,
                                                  T_LAST_N, T_PHI, T_RESTING, T_SEATED, T_SLIDE_MAX, T_TILT_MAX, T_TURN,
                                                  T_TWIST_MAX, T_UNCONVERGED)
from opsrock.solvers.cylinder3d.geometry import base_centre, tilt, twist
from opsrock.solvers.cylinder3d.model import Model, Numerics
from opsrock.solvers.cylinder3d.rolling import RV_Y, roll, span_end
from opsrock.solvers.cylinder3d.step import floor_at, step
from opsrock.solvers.jitable import jitable


@jitable
def _signed(s):
    """The tilt signed by the lean along ``x`` (rad) and the angular velocity about ``y`` (rad/s): the planar
    solvers' ``theta`` and ``theta'`` in motion along ``x``."""
    t, lx, ly = tilt(s)
    return (t if (lx > 0.0 or (lx == 0.0 and ly >= 0.0)) else -t), s[11]


@jitable
def _record(j, t, s, down, h, hist):
    """Store one history row at time ``t`` (s) if there is room; returns the next free row."""
    if j >= hist.shape[0]:
        return j
    w, x, y, z = s[3], s[4], s[5], s[6]
    nv = math.sqrt(x * x + y * y + z * z)
    f = 2.0 * math.atan2(nv, w) / nv if nv > 0.0 else 2.0
    hist[j, H_T] = t
    hist[j, H_THETA], hist[j, H_THETA_DOT] = _signed(s)
    hist[j, H_ROT], hist[j, H_ROT + 1], hist[j, H_ROT + 2] = f * x, f * y, f * z
    hist[j, H_POS], hist[j, H_POS + 1], hist[j, H_POS + 2] = s[0], s[1], s[2] - h
    hist[j, H_TWIST] = twist(s)
    hist[j, H_SLIDE], hist[j, H_SLIDE + 1] = base_centre(s, h)
    hist[j, H_DOWN] = down
    return j + 1


@jitable
def _rest_holds(model, acc):
    """A seated cylinder stays at rest this step: the floor's load pushes down (``g + a_v > 0``), its centre of
    pressure ``|a_h| h / (g + a_v)`` lies inside the base's circle of radius ``r`` and friction carries ``|a_h|``.
    The uplift threshold ``|a_h| = g r / h`` (a still vertical) is exact in every direction."""
    d, f = model.design, model.friction
    gz = d.g + acc[2]
    ah = math.hypot(acc[0], acc[1])
    return gz > 0.0 and ah * d.h <= d.r * gz and (f.infinite or ah <= f.mu_s * gz)


@jitable
def _seat(s, h):
    """Set a cylinder at rest on its stuck base down level: its base centre and twist kept, its velocities zero."""
    bx, by = base_centre(s, h)
    tw = twist(s)
    s[0], s[1], s[2] = bx, by, h
    s[3], s[4], s[5], s[6] = math.cos(0.5 * tw), 0.0, 0.0, math.sin(0.5 * tw)
    s[7:] = 0.0


@jitable
def _book(model, state, n, slipping, phi0, flat):
    """The step's bookkeeping: the contact mode and the time in it, a landing (an impact: a rim point touching down
    after a flight, the contact jumping across the base, or the base landing flat), the contact point's run round
    the rim. Returns True on a landing."""
    dt, out, tr = model.numerics.dt, state.out, state.track
    single = n > 0 and not flat
    landing = n > 0 and (tr[T_LAST_N] == 0.0 or (flat and tr[T_LAST_N] == 1.0))
    rate = 0.0
    if single and math.isfinite(tr[T_PHI]):
        dphi = (phi0 - tr[T_PHI] + math.pi) % (2.0 * math.pi) - math.pi
        if abs(dphi) > LANDING_JUMP:
            landing, tr[T_TURN] = True, 0.0
        else:
            tr[T_TURN] += abs(dphi)
            out[OUT_CONTACT_TURN] += dphi
            rate = abs(dphi) / dt
    elif not single:
        tr[T_TURN] = 0.0
    tr[T_PHI] = phi0 if single else math.nan
    tr[T_CONTACT_RATE] = rate
    tr[T_LAST_N] = n if single else (float(n) if n == 0 else 2.0)
    mode = 4 if n == 0 else ((1 if slipping > 0 else 0) if flat else (3 if slipping > 0 else 2))
    if mode != 0 and out[OUT_FIRST_MODE] < 0.0:
        out[OUT_FIRST_MODE] = mode
    out[OUT_TIME_FLIGHT] += dt if n == 0 else 0.0
    out[OUT_TIME_BASE] += dt if (n > 0 and flat) else 0.0
    out[OUT_TIME_ROCKING] += dt if single else 0.0
    out[OUT_TIME_ROLLING] += dt if (single and rate > ROLL_RATE * model.design.p) else 0.0
    out[OUT_TIME_SLIDING] += dt if slipping > 0 else 0.0
    if landing:
        out[OUT_IMPACTS] += 1.0
    return landing


@jitable
def _peaks(model, state):
    """The peaks of tilt, slide and twist after a step into the tracker; returns the tilt (rad) and the axis's
    horizontal components."""
    s, tr = state.s, state.track
    t, lx, ly = tilt(s)
    bx, by = base_centre(s, model.design.h)
    tr[T_TILT_MAX] = max(tr[T_TILT_MAX], t)
    tr[T_SLIDE_MAX] = max(tr[T_SLIDE_MAX], math.hypot(bx, by))
    tr[T_TWIST_MAX] = max(tr[T_TWIST_MAX], abs(twist(s)))
    return t, lx, ly


@jitable
def _roll_step(model, floor, state, rw, k):
    """A Runge-Kutta sub-step rolling on the rim point (:func:`.rolling.roll`) from step ``k`` to the next sample
    (at most ``roll_steps`` steps) and its bookkeeping: the time on the rim (rolling, if the contact point turned
    faster than ``ROLL_RATE p``), the contact point's run round the rim, the floor's work, the peaks; a sub-step that
    leaves the phase is halved, down to ``ROLL_MIN_STEPS`` steps. Returns the steps it spanned; 0 if none was kept
    (the Moreau-Jean steps go on, ``ROLL_MIN_STEPS`` of them at least before another is tried: the event lies
    within them)."""
    s, out, tr, num = state.s, state.out, state.track, model.numerics
    n = span_end(model, floor, k) - k
    while True:
        if n < ROLL_MIN_STEPS:
            tr[T_CALM] = -ROLL_MIN_STEPS
            return 0
        kept, work, phi, turn = roll(model, floor, s, k, n, rw)
        if kept:
            break
        out[OUT_ROLL_FAILED] += 1.0
        n //= 2
    s[:] = rw.v[RV_Y]
    span = n * num.dt
    rate = abs(turn) / span
    out[OUT_INPUT_WORK] += work
    out[OUT_CONTACT_TURN] += turn
    tr[T_TURN] += abs(turn)
    tr[T_PHI], tr[T_CONTACT_RATE], tr[T_LAST_N], tr[T_RESTING] = phi, rate, 1.0, 0.0
    out[OUT_TIME_ROCKING] += span
    out[OUT_TIME_ROLLING] += span if rate > ROLL_RATE * model.design.p else 0.0
    out[OUT_ROLL_STEPS] += 1.0
    out[OUT_ROLL_SPAN] += n
    t = _peaks(model, state)[0]
    if k >= floor.n_exc:
        _wobble(tr, t, math.hypot(s[10], s[11]))
    else:
        _wobble_broken(tr)
    return n


@jitable
def _wobble_broken(tr):
    """The unbroken rolling after the excitation ends (a Moreau-Jean step, or the excitation still on)."""
    tr[T_W_LAST], tr[T_W_RISING], tr[T_W_MAXES] = math.nan, 0.0, 0.0


@jitable
def _wobble(tr, t, rate):
    """The tilt ``t`` (rad) and ``|omega_h|`` ``rate`` (rad/s) at the end of a sub-step of unbroken rolling after the
    excitation: counts the tilt's local maxima and keeps, from the first, its largest value and the largest rate."""
    last = tr[T_W_LAST]
    if math.isfinite(last):
        rising = t > last
        if tr[T_W_RISING] > 0.5 and not rising:
            tr[T_W_MAXES] += 1.0
            if tr[T_W_MAXES] == 1.0:
                tr[T_W_TOP], tr[T_W_RATE] = last, rate
        tr[T_W_RISING] = 1.0 if rising else 0.0
    if tr[T_W_MAXES] >= 1.0:
        tr[T_W_TOP], tr[T_W_RATE] = max(tr[T_W_TOP], t), max(tr[T_W_RATE], rate)
    tr[T_W_LAST] = t


@jitable
def _steady_wobble(model, state):
    """At the end of the tail's span, still rolling: True if the cylinder can never overturn because it has rolled
    without slip, unbroken, through a full period of its tilt (two of its maxima) after the excitation. A body of
    revolution rolling without slip on a still plane is integrable (Chaplygin 1897: the energy and two integrals
    linear in the angular velocity), so its tilt is periodic between fixed turning points, the contact's forces
    with it: the largest tilt of one period, sampled at the sub-steps' ends and raised by ``|omega_h|`` (which
    bounds the tilt's rate) times a sub-step, is its tilt for ever. Writes that bound (``OUT_TILT_BOUND``) and
    ``OUT_TAIL_WOBBLE`` if it is below ``alpha``."""
    tr, out, d = state.track, state.out, model.design
    bound = tr[T_W_TOP] + tr[T_W_RATE] * model.numerics.roll_steps * model.numerics.dt
    if tr[T_W_MAXES] < 2.0 or not math.isfinite(tr[T_W_LAST]) or bound >= d.alpha:
        return False
    out[OUT_TAIL_WOBBLE], out[OUT_TILT_BOUND] = 1.0, bound
    return True


@jitable
def _track(model, state, ws):
    """The peaks after a step (tilt, slide, twist) and the input work; returns True if the cylinder overturned
    (tilt ``>= pi/2``), its mechanism and direction then written."""
    s, new, out, tr, acc = state.s, ws.new, state.out, state.track, ws.acc
    out[OUT_INPUT_WORK] -= acc[0] * (new[0] - s[0]) + acc[1] * (new[1] - s[1]) + acc[2] * (new[2] - s[2])
    s[:] = new
    t, lx, ly = _peaks(model, state)
    if t < OVERTURNING_ANGLE:
        return False
    out[OUT_OVERTURNED] = 1.0
    out[OUT_OVER_KIND] = 2.0 if tr[T_TURN] > ROLL_TURN else 1.0
    out[OUT_OVER_DIR] = math.atan2(ly, lx)
    return True


@jitable
def _tail_energy(model, s, tail_av):
    """Energy per unit mass above rest on the still floor after the excitation (J/kg): ``|V|²/2``, the rotation's
    ``(i_h |omega|² + (i_z - i_h) (omega . a)²) / 2`` (``a`` the axis) and ``(g + tail_av) (z - h)``. Nothing feeds
    it any more: rolling without slip keeps it, impacts and slip take from it."""
    d = model.design
    w, x, y, z = s[3], s[4], s[5], s[6]
    along = s[10] * 2.0 * (x * z + w * y) + s[11] * 2.0 * (y * z - w * x) + s[12] * (1.0 - 2.0 * (x * x + y * y))
    rot = d.i_h * (s[10] ** 2 + s[11] ** 2 + s[12] ** 2) + (d.i_z - d.i_h) * along * along
    return 0.5 * (s[7] * s[7] + s[8] * s[8] + s[9] * s[9] + rot) + (d.g + tail_av) * (s[2] - d.h)


@jitable
def _lift(model, tilt_, tail_av):
    """The energy per unit mass (J/kg) that raises the centre of mass to the tilt ``tilt_`` (rad) on a rim point:
    ``(g + tail_av) (h cos tilt + r sin tilt - h)``."""
    d = model.design
    return (d.g + tail_av) * (d.h * math.cos(tilt_) + d.r * math.sin(tilt_) - d.h)


@jitable
def _below_overturning(model, state, tail_av):
    """At the end of the tail's span: True if the cylinder can never overturn, its energy (:func:`_tail_energy`, its
    centre of mass raised to put its lowest rim point on the floor if it lies below it) with ``ENERGY_ROUNDOFF`` of
    its terms' magnitudes added being below ``(g + a_v)(R - h)``, what raising the centre of mass over a rim point
    takes, and its tilt below ``alpha``. After the excitation the floor is still (or moves at a constant velocity,
    or accelerates vertically at a constant ``a_v > -g``): nothing works on the cylinder, rolling without slip
    keeps its energy and slip and impacts take from it; overturning needs the tilt to pass ``alpha``, where the
    centre of mass stands at least ``R`` high (``h cos t + r sin t`` peaks there). Writes the energy over that
    threshold (``OUT_TAIL_ENERGY``) and, if True, the largest tilt the energy can reach, ``alpha - acos((e / (g +
    a_v) + h) / R)`` (``OUT_TILT_BOUND``, rad)."""
    s, d, out = state.s, model.design, state.out
    gz = d.g + tail_av
    w, x, y, z = s[3], s[4], s[5], s[6]
    along = s[10] * 2.0 * (x * z + w * y) + s[11] * 2.0 * (y * z - w * x) + s[12] * (1.0 - 2.0 * (x * x + y * y))
    size = 0.5 * (s[7] ** 2 + s[8] ** 2 + s[9] ** 2 + d.i_h * (s[10] ** 2 + s[11] ** 2 + s[12] ** 2)
                  + abs(d.i_z - d.i_h) * along * along) + abs(gz) * (abs(s[2]) + d.h)
    t = tilt(s)[0]
    seated = d.h * math.cos(t) + d.r * math.sin(t)  # the centre of mass's height, the lowest rim point down
    e = _tail_energy(model, s, tail_av) + gz * max(0.0, seated - s[2])
    need = gz * (d.R - d.h)
    out[OUT_TAIL_ENERGY] = e / need if gz > 0.0 else math.inf
    if gz <= 0.0 or t >= d.alpha or e + ENERGY_ROUNDOFF * size >= need:
        return False
    out[OUT_TILT_BOUND] = d.alpha - math.acos(min(1.0, ((e + ENERGY_ROUNDOFF * size) / gz + d.h) / d.R))
    return True


@jitable
def _tail_settled(model, state, tail_av):
    """The tail may end before rest (1: settled; 2: bounded): its energy (:func:`_tail_energy`), which nothing feeds
    any more, cannot raise the centre of mass to the overturning tilt (below ``TAIL_CUT_MARGIN`` of the lift to it),
    nor the tilt more than ``TILT_SLACK alpha`` above its peak so far (on a rim point the lift ``g (h cos t + r sin t -
    h)`` grows with the tilt up to ``alpha``): the verdict is final, the peak tilt to within that slack (2; the base
    may still roll on, so the slide is the one so far). 1 when the energy is also below half of what the peak tilt
    took and the base moves slower than ``PEAK_BASE_SPEED`` (rigid3d's rule "peak": the peak is final, the slide to
    within that speed's stopping distance). A cylinder rolling on its rim keeps its energy (nothing in the rigid model
    resists rolling) and may never come to rest, so a wobble ends by the bound. 0: go on."""
    s, d = state.s, model.design
    e = _tail_energy(model, s, tail_av)
    peak = state.track[T_TILT_MAX]
    if peak >= d.alpha or e >= TAIL_CUT_MARGIN * _lift(model, d.alpha, tail_av):
        return 0  # (past alpha the centre of mass is beyond the rim point and falls: the bound does not hold)
    if e > _lift(model, min(peak + TILT_SLACK * d.alpha, d.alpha), tail_av):
        return 0
    if e >= 0.5 * _lift(model, peak, tail_av):
        return 2
    w, x, y, z = s[3], s[4], s[5], s[6]
    c0, c1, c2 = -d.h * 2.0 * (x * z + w * y), -d.h * 2.0 * (y * z - w * x), -d.h * (1.0 - 2.0 * (x * x + y * y))
    return 1 if math.hypot(s[7] + s[11] * c2 - s[12] * c1, s[8] + s[12] * c0 - s[10] * c2) < PEAK_BASE_SPEED else 0


@jitable
def _impulse_energy(ws):
    """The energy per unit mass (J/kg) the step's contact impulses took: ``-dv . M v_end`` (their work at the step's
    end velocities, ``dv = v_end - v_free``, ``M = diag(1, Iw)``: friction's alone where the normal impulses do none,
    ``P_N u_N = 0`` at a solved contact) and ``-dv . M v_end + dv . M dv / 2`` (all the kinetic energy they took,
    an impact's loss)."""
    vel, free, Iw = ws.vel, ws.free, ws.Iw
    work, quad = 0.0, 0.0
    for i in range(3):
        dv = vel[i] - free[i]
        work -= dv * vel[i]
        quad += 0.5 * dv * dv
        dw = vel[3 + i] - free[3 + i]
        for j in range(3):
            work -= dw * Iw[i, j] * vel[3 + j]
            quad += 0.5 * dw * Iw[i, j] * (vel[3 + j] - free[3 + j])
    return work, work + quad


@jitable
def _sub_step(model, state, ws, k):
    """One Moreau-Jean step of ``model``'s step and its bookkeeping; returns False if the run must stop failed
    (non-finite state, NSGS unconverged too long: ``out[OUT_STATUS]`` set)."""
    s, out, tr = state.s, state.out, state.track
    n, sweeps, slipping, phi0, flat = step(model, s, ws, out)
    if n > 0:
        out[OUT_CONTACT_STEPS] += 1.0
        out[OUT_NSGS_SWEEPS] += sweeps
    if sweeps > model.nsgs.max_sweeps:
        out[OUT_NSGS_FAILED] += 1.0
        tr[T_UNCONVERGED] += 1.0
        if tr[T_UNCONVERGED] > model.nsgs.fail_steps:
            out[OUT_STATUS] = STATUS_CONTACT
            return False
    else:
        tr[T_UNCONVERGED] = 0.0
    landing = _book(model, state, n, slipping, phi0, flat)
    if landing:
        out[OUT_IMPACT_LOSS] += _impulse_energy(ws)[1]
    elif n > 0:
        out[OUT_FRICTION_WORK] += _impulse_energy(ws)[0]
    calm = n == 1 and not flat and slipping == 0 and ws.P[0, 2] > 0.0 and not landing
    tr[T_CALM] = tr[T_CALM] + 1.0 if calm else min(0.0, tr[T_CALM] + 1.0)
    _wobble_broken(tr)
    fin = 0.0
    for a in range(13):
        fin += ws.new[a]
    if not math.isfinite(fin):
        out[OUT_STATUS] = STATUS_NONFINITE
        return False
    speed = max(math.sqrt(ws.new[7] ** 2 + ws.new[8] ** 2 + ws.new[9] ** 2),
                model.design.R * math.sqrt(ws.new[10] ** 2 + ws.new[11] ** 2 + ws.new[12] ** 2))
    still = flat and n == model.design.n_rim and slipping == 0
    tr[T_RESTING] = tr[T_RESTING] + 1.0 if (k >= 0 and still and speed < model.limits.rest_velocity) else 0.0
    if still and speed < model.limits.velocity_tol:
        tr[T_SEATED] = 1.0
    return True


@jitable
def _contact_step(model, state, ws, k):
    """One step ``dt`` of Moreau-Jean, cut into sub-steps while the contact point runs fast round the rim (at most
    ``PHI_STEP`` rad a sub-step at its last rate, at most ``MAX_SUBSTEPS`` of them): a cylinder rolling through a
    nearly flat state turns its contact point by about pi in a short time (Srinivasan & Ruina), which whole steps
    would cross as a train of small impacts. Returns 0 (go on), 1 (stop, failed) or 2 (overturned)."""
    num = model.numerics
    m = min(MAX_SUBSTEPS, max(1, int(math.ceil(state.track[T_CONTACT_RATE] * num.dt / PHI_STEP))))
    sub = model
    if m > 1:
        sub = Model(model.design, model.friction, Numerics(num.dt / m, num.theta_mj, num.hist_every, num.smooth,
                                                           num.roll_steps), model.nsgs, model.limits)
    for _ in range(m):
        if not _sub_step(sub, state, ws, k):
            return 1
        if _track(sub, state, ws):
            return 2
    return 0


@numba.njit(cache=True)
def run(model, floor, state, ws, rw, hist):
    """Integrate one case: ``state`` (:class:`.model.State`) from its start to the end of the excitation and the
    tail (rest), writing ``state.out`` (``OUT_*``) and the history rows ``hist`` (``H_*``, one every
    ``hist_every`` steps and the last state); ``ws`` the scratch (:class:`.model.Workspace`), ``rw`` the smooth
    phase's (:class:`.model.RollWork`). Returns the status."""
    num, lim, d = model.numerics, model.limits, model.design
    s, out, tr = state.s, state.out, state.track
    j = _record(0, 0.0, s, 0.0, d.h, hist)
    tr[T_TILT_MAX] = tilt(s)[0]
    out[OUT_FIRST_MODE] = -1.0
    out[OUT_STATUS] = STATUS_OK
    k = 0
    while True:
        if k >= floor.n_exc and (lim.max_tail < 0 or tr[T_RESTING] >= lim.rest_steps):
            break
        if k >= floor.n_exc + max(lim.max_tail, 0) or k >= lim.max_steps:
            if k < lim.max_steps and _below_overturning(model, state, floor.tail_av):
                out[OUT_TAIL_BOUND] = 1.0  # still rolling, unable ever to overturn: the verdict holds
            elif not (k < lim.max_steps and _steady_wobble(model, state)):
                out[OUT_STATUS] = STATUS_TAIL if k < lim.max_steps else STATUS_MAX_STEPS
            break
        settled = _tail_settled(model, state, floor.tail_av) if (k > floor.n_exc and lim.max_tail >= 0) else 0
        if settled > 0:
            out[OUT_TAIL_SETTLED if settled == 1 else OUT_TAIL_CUT] = 1.0
            _below_overturning(model, state, floor.tail_av)  # the tilt bound
            break
        floor_at(floor, k, num.theta_mj, ws.acc)
        if not math.isfinite(ws.acc[0] + ws.acc[1] + ws.acc[2]):
            out[OUT_STATUS] = STATUS_NONFINITE
            break
        if tr[T_SEATED] > 0.5 and _rest_holds(model, ws.acc):
            out[OUT_REST_STEPS] += 1.0
            out[OUT_TIME_BASE] += num.dt
            k, n = k + 1, 1
            if k >= floor.n_exc:
                tr[T_RESTING] = lim.rest_steps  # seated on a still floor: it stays so
        else:
            if tr[T_SEATED] > 0.5:
                tr[T_SEATED] = 0.0
            n = _roll_step(model, floor, state, rw, k) if (num.smooth and tr[T_CALM] >= ROLL_CALM) else 0
            if n > 0:
                k += n
            else:
                done = _contact_step(model, state, ws, k - floor.n_exc)
                if done == 1:
                    break
                k, n = k + 1, 1
                if done == 2:
                    break
                if tr[T_SEATED] > 0.5:
                    _seat(s, d.h)
        if k // num.hist_every != (k - n) // num.hist_every:
            j = _record(j, k * num.dt, s, tr[T_LAST_N], d.h, hist)
    return _finish(model, state, hist, j, k)


@jitable
def _finish(model, state, hist, j, k):
    """The last history row and the output vector's totals; returns the status."""
    s, out, tr, dt = state.s, state.out, state.track, model.numerics.dt
    if k % model.numerics.hist_every != 0:
        j = _record(j, k * dt, s, tr[T_LAST_N], model.design.h, hist)
    out[OUT_STEPS] = k
    out[OUT_THETA_MAX] = tr[T_TILT_MAX]
    out[OUT_ROCKED] = 1.0 if tr[T_TILT_MAX] > model.limits.rocked_theta else 0.0
    out[OUT_SLIDE_MAX] = tr[T_SLIDE_MAX]
    out[OUT_TWIST_MAX] = tr[T_TWIST_MAX]
    out[OUT_N_HIST] = j
    out[OUT_TIME] = k * dt
    out[OUT_EVENT_TIME] = k * dt * model.design.p
    out[OUT_STATE:OUT_STATE + 13] = s
    return int(out[OUT_STATUS])


__all__ = ["run"]
