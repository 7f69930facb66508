"""Compiled kernel of :mod:`opsrock.solvers.rigid3d` (numba): Moreau-Jean time stepping of a rigid box on a
rigid floor with its four base corners as contacts, Newton's impact law with ``e_n = 0`` and isotropic Coulomb
friction, the contact problem of each step solved by nonsmooth Gauss-Seidel (docs/guide/three-dimensions.md).

Everything here is per unit mass: positions in m, velocities in m/s and rad/s, impulses in m/s (N s per kg),
energies in J/kg, inertias in m² (``I / m``). Frames: the floor frame ``(x, y, z)`` is the block frame at rest
(``x`` along the width, ``y`` along the depth, ``z`` up, origin at the base centre at rest); the floor's
accelerations enter as the body force ``(-a_x, -a_y, -(g + a_v))``.

State (13 floats): centre of mass ``X`` (3, floor frame), orientation as a unit quaternion ``q = (w, x, y, z)``
(body to floor), CM velocity ``V`` (3) and angular velocity ``omega`` (3, floor frame). The inertia is diagonal
in the body frame, ``I_b = diag(I_x, I_y, I_z)``; in the floor frame ``I = Q I_b Q^T`` (``Q`` the rotation
matrix of ``q``).

Corner ``i`` sits at ``c_i = (sx_i b, sy_i d, -h)`` in the body frame (``h`` the height of the centre of mass
above the base), at ``r_i = Q c_i`` from the centre of mass; its velocity is ``u_i = V + omega x r_i``, its gap
the height ``X_z + r_i,z``. The contact frame is the floor's: tangents ``x``, ``y``, normal ``z``. An impulse
``P_j`` at corner ``j`` changes ``u_i`` by ``W_ij P_j``, ``W_ij = 1 - S_i I^-1 S_j`` (``S`` the cross-product
matrix of ``r``).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from opsrock.solvers.rigid3d.constants import (ALIGN_TOL, CONE_SLACK, CORNER_SX, CORNER_SY, DIRECTION_TOL,
                                               EDGE_STATUSES, FD_STEP, FLAT_ROUNDOFF, FORCING_LINEAR,
                                               FORCING_STEPWISE, FOUR, H_DOWN, H_POS, H_ROT, H_SIZE, H_SLIDE, H_T,
                                               H_THETA, H_THETA_DOT, H_TWIST, LIMIT_MU, MODE_FLIGHT, MODE_REST,
                                               MODE_ROCK, MODE_SLIDE, MODE_SLIDE_ROCK, NEWTON_TOL, NO, ONE,
                                               OUT_COARSE_SPAN, OUT_COARSE_STEPS, OUT_CONTACT_STEPS, OUT_EDGE_SLIP,
                                               OUT_EVENT_TIME, OUT_FIRST_MODE, OUT_FRICTION_WORK, OUT_IMPACTS,
                                               OUT_IMPACT_LOSS, OUT_INPUT_WORK, OUT_LIMIT_STEPS, OUT_MAX_PENETRATION,
                                               OUT_NSGS_EXTRA, OUT_NSGS_FAILED, OUT_NSGS_LOOSE, OUT_NSGS_MAX,
                                               OUT_NSGS_SWEEPS, OUT_N_HIST, OUT_OVERTURNED, OUT_OVER_DIR,
                                               OUT_OVER_KIND, OUT_PEAK_STOP, OUT_REST_STEPS, OUT_ROCKED, OUT_SETTLED,
                                               OUT_SETTLE_GAP, OUT_SIZE, OUT_SLIDE_MAX, OUT_SLIDE_STEPS,
                                               OUT_SLIP_SPAN, OUT_SLIP_STEPS, OUT_SLIP_TRIED, OUT_SMOOTH_SPAN,
                                               OUT_SMOOTH_STEPS, OUT_SMOOTH_TRIED, OUT_STATE, OUT_STATUS, OUT_STEPS,
                                               OUT_STICK_STEPS, OUT_THETA_MAX, OUT_TIME, OUT_TIME_CORNER,
                                               OUT_TIME_EDGE, OUT_TIME_FLIGHT, OUT_TIME_ROCKING, OUT_TIME_SLIDING,
                                               OUT_TWIST_MAX, PEAK_BASE_SPEED, PIVOT_TOL, REST_MODE, SECULAR_TOL,
                                               SETDOWN_MARGIN, SETTLE_GAP, SIX, SLIP_ANGLE_TOL, SLIP_MIN_SUB,
                                               SLIP_STEP_TOL, SLIP_TURN, STATUS_CONTACT, STATUS_MAX_STEPS,
                                               STATUS_NONFINITE, STATUS_OK, STATUS_TAIL, TWO, YES,
                                               ZERO)  # noqa: F401  (the layout, re-exported)
from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers.rigid3d import pivot as PV
from opsrock.solvers.rigid3d.geometry import (_arms, _cm_outside, _geometry, _tilt, _twist)
from opsrock.solvers.rigid3d.step import (_book, _count_sweeps, _floor, _rest_holds, _rest_span, _step)
from opsrock.solvers.rigid3d.smooth import (_coarse_slide, _flat_slip, _slip_pivot, _smooth, _smooth_slip, _stuck_pivot)
from opsrock.solvers.rigid3d.workspace import (VEC_VF, make_workspace)


@numba.njit(cache=True)
def _record(j, cap, t, s, theta, theta_dot, down, h, hist):
    """Store one history row if there is room; returns the next free row."""
    if j >= cap:
        return j
    w, x, y, z = s[3], s[4], s[5], s[6]
    nv = math.sqrt(x * x + y * y + z * z)
    ang = 2.0 * math.atan2(nv, w)
    f = ang / nv if nv > 0.0 else 2.0
    hist[j, H_T] = t
    hist[j, H_THETA] = theta
    hist[j, H_THETA_DOT] = theta_dot
    hist[j, H_ROT], hist[j, H_ROT + 1], hist[j, H_ROT + 2] = f * x, f * y, f * z
    hist[j, H_POS], hist[j, H_POS + 1], hist[j, H_POS + 2] = s[0], s[1], s[2] - h
    hist[j, H_TWIST] = _twist(s)
    q02, q12 = 2.0 * (x * z + w * y), 2.0 * (y * z - w * x)
    hist[j, H_SLIDE], hist[j, H_SLIDE + 1] = s[0] - h * q02, s[1] - h * q12
    hist[j, H_DOWN] = down
    return j + 1


@numba.njit(cache=True)
def _mode(touch, slip):
    """Contact mode (a ``MODE_*`` index) and corners down from the corners' contact and slip flags."""
    n = 0
    sl = False
    for i in range(4):
        if touch[i]:
            n += 1
            sl = sl or slip[i]
    if n >= 3:
        return (MODE_SLIDE if sl else MODE_REST), n
    if n >= 1:
        return (MODE_SLIDE_ROCK if sl else MODE_ROCK), n
    return MODE_FLIGHT, n


@numba.njit(cache=True)
def _tally(mode, n_down, dt, out):
    """First mode left rest into, and the times in each state."""
    if mode != MODE_REST and out[OUT_FIRST_MODE] < 0.0:
        out[OUT_FIRST_MODE] = mode
    if mode == MODE_SLIDE or mode == MODE_SLIDE_ROCK:
        out[OUT_TIME_SLIDING] += dt
    if mode == MODE_ROCK or mode == MODE_SLIDE_ROCK:
        out[OUT_TIME_ROCKING] += dt
    if n_down == 2:
        out[OUT_TIME_EDGE] += dt
    elif n_down == 1:
        out[OUT_TIME_CORNER] += dt
    elif n_down == 0:
        out[OUT_TIME_FLIGHT] += dt


@numba.njit(cache=True)
def _settle(state, touch, body, Q, r, gap_max, out):
    """A block at rest on three corners (``touch``) whose fourth hangs above the floor by at most ``gap_max`` (m):
    the gap is the Moreau-Jean steps' drift (a corner that rose above the contact gap while the block came to rest
    stays up, and the block would never be seated), so the block is set down level on all four, its base centre
    and twist kept (its centre of mass moves by at most ``gap_max``, its tilt by ``gap_max / min(2b, 2d)``). Returns
    True if it was (then seated by the caller). ``Q`` and ``r`` are workspace."""
    _arms(state, body, Q, r)
    up = -1
    for i in range(4):
        if not touch[i]:
            up = i
    if up < 0:
        return True
    gap = state[2] + r[up, 2]
    if not gap <= gap_max:
        return False
    h = body.h
    w, x, y, z = state[3], state[4], state[5], state[6]
    bx, by = state[0] - h * 2.0 * (x * z + w * y), state[1] - h * 2.0 * (y * z - w * x)
    tw = _twist(state)
    state[0], state[1], state[2] = bx, by, h
    state[3], state[4], state[5], state[6] = math.cos(0.5 * tw), 0.0, 0.0, math.sin(0.5 * tw)
    touch[up] = True
    out[OUT_SETTLED] += 1.0
    out[OUT_SETTLE_GAP] = max(out[OUT_SETTLE_GAP], gap)
    return True


@numba.njit(cache=True)
def _peak_reached(s, body, tilt_max, tail_av):
    """The tail rule "peak": after the excitation (a still floor, ``g' = g + tail_av``), the block's energy per
    unit mass above rest, bounded above by ``|V|²/2 + I_max |omega|²/2 + g' (z - h)``, can only fall; at a tilt
    ``theta`` its centre of mass stands at least ``h cos theta + min(b, d) sin theta`` above the floor. Once the
    bound is below half of ``g' (h cos theta_max + min(b, d) sin theta_max - h)`` (half: a margin for the
    scheme's energy error) and the base moves slower than :data:`PEAK_BASE_SPEED`, neither the verdict nor
    ``theta_max`` can change."""
    b, d, h, ib = body.b, body.d, body.h, body.inertia
    gp = body.g + tail_av
    i_max = max(ib[0], max(ib[1], ib[2]))
    w0, w1, w2 = s[10], s[11], s[12]
    e = 0.5 * (s[7] * s[7] + s[8] * s[8] + s[9] * s[9]) + 0.5 * i_max * (w0 * w0 + w1 * w1 + w2 * w2)
    e += gp * (s[2] - h)
    m = min(b, d)
    if e >= 0.5 * gp * (h * math.cos(tilt_max) + m * math.sin(tilt_max) - h):
        return False
    w, x, y, z = s[3], s[4], s[5], s[6]
    c0, c1, c2 = -h * 2.0 * (x * z + w * y), -h * 2.0 * (y * z - w * x), -h * (1.0 - 2.0 * (x * x + y * y))
    return math.hypot(s[7] + w1 * c2 - w2 * c1, s[8] + w2 * c0 - w0 * c2) < PEAK_BASE_SPEED


@numba.njit(cache=True)
def run(model, floor, state, hist, out):
    """Integrate one case; fills ``out`` (layout ``OUT_*``) and the history rows ``hist`` (columns ``H_*``);
    returns the status.

    Parameters
    ----------
    model : Model
        The block, its friction and the numerical settings and limits (:class:`.model.Model`, built by
        :func:`.model.make_model`).
    floor : Floor
        The floor motion in the block frame (:class:`.model.Floor`): :data:`FORCING_STEPWISE` or
        :data:`FORCING_LINEAR` (samples, ``sub`` steps per interval), for ``n_exc`` steps; after them no
        horizontal motion and ``a_v = tail_av`` (m/s²).
    state : float64[13]
        Initial state; holds the final one on return.
    hist : float64[n, H_SIZE]
        History rows, one every ``model.numerics.hist_every`` steps (and the last state).
    out : float64[OUT_SIZE]
        The run's results and bookkeeping.
    """
    body, num, lim = model.body, model.numerics, model.limits
    h, Rw, weak_y = body.h, body.R, body.weak_y
    dt, theta_mj, hist_every = num.dt, num.theta_mj, num.hist_every
    max_steps, max_tail, rest_vel = lim.max_steps, lim.max_tail, lim.rest_velocity
    rest_steps, vel_tol, lift_gap = lim.rest_steps, lim.velocity_tol, lim.lift_gap
    peak_rule, smooth_on = lim.peak_rule, num.smooth
    fail_steps = model.nsgs.fail_steps
    n_exc, tail_av = floor.n_exc, floor.tail_av
    n_max = max(PV.MIN_STEPS, int(PV.MAX_DTAU / (body.p * dt)))
    out[:] = 0.0
    out[OUT_FIRST_MODE] = -1.0
    ws, wk, probe, sw = make_workspace(OUT_SIZE)
    Q, Iinv, Iw, r = ws.Q, ws.Iinv, ws.Iw, ws.r
    act = np.zeros(4, dtype=np.bool_)
    touch = np.zeros(4, dtype=np.bool_)
    slip = np.zeros(4, dtype=np.bool_)
    P = np.zeros((4, 3))
    new = np.zeros(13)
    r1 = ws.r1
    cap = hist.shape[0]
    _geometry(state, body, Q, Iinv, Iw, r)
    for i in range(4):
        touch[i] = state[2] + r[i, 2] <= lift_gap
    tilt, theta, _, _ = _tilt(state, weak_y)
    mode, n_down = _mode(touch, slip)
    j = _record(ZERO, cap, 0.0, state, theta, state[10 + (0 if weak_y else 1)] * (-1.0 if weak_y else 1.0),
                n_down, h, hist)
    theta_max = tilt
    slide_max = 0.0
    twist_max = abs(_twist(state))
    status = STATUS_OK
    resting = 0
    unconverged = 0
    seated = False
    outside = False
    over_kind = 0.0
    last_down = n_down
    calm = 0
    slipc = 0
    sliding = 0
    n_slide = max(2, int(PV.SLIDE_DTAU / (body.p * dt)))
    k = ZERO
    while True:
        if k >= n_exc and (max_tail < 0 or resting >= rest_steps):
            break
        if k >= n_exc + max(max_tail, 0) or k >= max_steps:
            status = STATUS_TAIL if k < max_steps else STATUS_MAX_STEPS
            break
        a_x, a_y, a_v = _floor(floor, k, theta_mj)
        if not math.isfinite(a_x + a_y + a_v):
            status = STATUS_NONFINITE
            break
        if seated and _rest_holds(a_x, a_y, a_v, body, model.friction):
            # the rest skip: a seated, stuck block whose load the base carries stays at rest this step, and
            # a whole sample interval of a record if it does at both its samples (the accelerations are
            # linear in between and the set of loads the base carries is convex), and the whole rest of
            # a still tail
            n = _rest_span(model, floor, k, rest_steps - resting)
            out[OUT_REST_STEPS] += n
            _tally(REST_MODE, FOUR, n * dt, out)
            for kk in range(k + 1, k + n + 1):
                if kk % hist_every == 0:
                    j = _record(j, cap, kk * dt, state, theta, 0.0, FOUR, h, hist)
            k += n
            resting = resting + min(n, k - n_exc + 1) if k >= n_exc else 0
            continue
        if seated:  # leaving rest: warm start from the static impulses of the step's load
            seated = False
            gz = body.g + a_v
            for i in range(4):
                P[i, 0], P[i, 1], P[i, 2] = 0.25 * a_x * dt, 0.25 * a_y * dt, 0.25 * gz * dt
        n, tilt_sub, smoothed = 0, 0.0, False
        if smooth_on and calm >= PV.CALM_STEPS:
            n, tilt_sub = _smooth(model, floor, state, touch, k, n_max, ws, wk, probe, P, new, out)
            smoothed = n > 0
            if n == 0:
                calm = -4 * PV.MIN_STEPS  # none kept: the Moreau-Jean steps locate the event first
        elif smooth_on and slipc >= PV.CALM_STEPS:
            n, tilt_sub = _smooth_slip(model, floor, state, touch, slip, k, n_max, ws, sw, probe, P, new, out)
            smoothed = n > 0
            if n == 0:
                slipc = -4 * PV.MIN_STEPS
        elif smooth_on and sliding >= PV.CALM_STEPS:
            n = _coarse_slide(model, floor, state, k, n_slide, ws, probe, P, new, out, touch, slip)
            if n == 0:
                sliding = -n_slide
        if smoothed:  # a smooth step's input work (the floor's force at its middle)
            F = wk.F
            PV.floor_at(floor, k + 0.5 * n, k, theta_mj, F, body.g)
            out[OUT_INPUT_WORK] += F[0] * (new[0] - state[0]) + F[1] * (new[1] - state[1]) + \
                (F[2] + body.g) * (new[2] - state[2])
        if n <= 0:
            n = 1
            converged = _count_sweeps(_step(model, state, a_x, a_y, a_v, dt, ws, act, P, new, out, touch),
                                      model.nsgs, out)
            a_step = ws.a  # (an array, as _coarse_slide passes it: one specialisation of _book)
            a_step[0], a_step[1], a_step[2] = a_x, a_y, a_v
            impact = _book(state, a_step, ws.Q1, ws.r1, ws.r, ws.Iw, ws.vec[VEC_VF], act, P, new, out, touch,
                           slip, vel_tol, lift_gap, body)
            if not converged:
                unconverged += 1
                if unconverged > fail_steps:
                    status = STATUS_CONTACT
                    break
            else:
                unconverged = 0
            if calm < 0:
                calm += 1
            elif not impact and _stuck_pivot(act, touch, slip, P):
                calm += 1
            else:
                calm = 0
            if slipc < 0:
                slipc += 1
            elif not impact and _slip_pivot(act, touch, slip, P):
                slipc += 1
            else:
                slipc = 0
            if sliding < 0:
                sliding += 1
            elif not impact and _flat_slip(act, touch, slip):
                sliding += 1
            else:
                sliding = 0
        state[:] = new
        k += n
        fin = 0.0
        for a in range(13):
            fin += state[a]
        if not math.isfinite(fin):
            status = STATUS_NONFINITE
            break
        mode, n_down = _mode(touch, slip)
        _tally(mode, n_down, n * dt, out)
        if n_down > 0:
            last_down = n_down
        tilt, theta, lx, ly = _tilt(state, weak_y)
        sx, sy = state[0] - h * lx, state[1] - h * ly
        slide_max = max(slide_max, math.hypot(sx, sy))
        twist_max = max(twist_max, abs(_twist(state)))
        theta_max = max(theta_max, tilt, tilt_sub)
        now_out = _cm_outside(state, r1)
        if now_out and not outside:
            over_kind = 1.0 if last_down >= 2 else 2.0
        outside = now_out
        theta_dot = -state[10] if weak_y else state[11]
        if k // hist_every != (k - n) // hist_every:
            j = _record(j, cap, k * dt, state, theta, theta_dot, n_down, h, hist)
        if theta_max >= OVERTURNING_ANGLE:
            out[OUT_OVERTURNED] = 1.0
            out[OUT_OVER_KIND] = over_kind
            out[OUT_OVER_DIR] = math.atan2(ly, lx)
            break
        speed = max(abs(state[7]), abs(state[8]), abs(state[9]),
                    Rw * (abs(state[10]) + abs(state[11]) + abs(state[12])))
        still = speed < rest_vel
        resting = resting + min(n, k - n_exc + 1) if (k >= n_exc and mode == MODE_REST and still) else 0
        if peak_rule and k >= n_exc and _peak_reached(state, body, theta_max, tail_av):
            out[OUT_PEAK_STOP] = 1.0
            break
        if mode == MODE_REST and speed < vel_tol and (n_down == 4 or _settle(state, touch, body, ws.Q1, ws.r1,
                                                                               SETTLE_GAP * lift_gap, out)):
            seated = True
            for a in range(7, 13):
                state[a] = 0.0
    if k % hist_every != 0:
        tilt, theta, _, _ = _tilt(state, weak_y)
        j = _record(j, cap, k * dt, state, theta, -state[10] if weak_y else state[11], _mode(touch, slip)[1], h, hist)
    out[OUT_STATUS] = status
    out[OUT_STEPS] = k
    out[OUT_THETA_MAX] = theta_max
    out[OUT_ROCKED] = 1.0 if theta_max > lim.rocked_theta else 0.0
    out[OUT_SLIDE_MAX] = slide_max
    out[OUT_TWIST_MAX] = twist_max
    out[OUT_STATE:OUT_STATE + 13] = state
    out[OUT_N_HIST] = j
    out[OUT_TIME] = k * dt
    out[OUT_EVENT_TIME] = k * dt * body.p
    return status
