"""One Moreau-Jean step of the cylinder (numba): the floor's accelerations, the free velocity, the rim points in
contact, their impulses (:mod:`.contact`) and the end state.

Scheme (theta-method)::

    v_free = v_k + dt (body force, -omega x I omega)       body force (-a_x, -a_y, -(g + a_v)) at t_k + theta dt
    contact: the lowest rim point (tilted), or rim_points points round the rim (base flat), if its height
             predicted at mid-step, gap + dt/2 u_N, is at most the contact gap; on a flat base the lift about the
             load's rim point, else the closed forms of the base on the floor or lifting (:mod:`.flat`), else NSGS
    v_{k+1} = v_free + sum_i H_i^T P_i                     (arms and Delassus blocks at q_k)
    X_{k+1} = X_k + dt [(1 - theta) V_k + theta V_{k+1}]; the quaternion turned by dt times the same blend of omega
"""

from __future__ import annotations

import math


from opsrock.solvers.cylinder3d.constants import (FLAT_GAP, FORCING_STEPWISE, OPEN, OUT_FLAT_STEPS, OUT_LIFT_STEPS,
                                                  OUT_MAX_PENETRATION, SET_DOWN_GAPS, SLIP)
from opsrock.solvers.cylinder3d.contact import apply_impulse, delassus, local, nsgs
from opsrock.solvers.cylinder3d.flat import OUTSIDE, flat_base, lift_about, lowest_moving
from opsrock.solvers.cylinder3d.geometry import inertia, lean, lowest_angle, rim_arm, rotation
from opsrock.solvers.jitable import jitable


@jitable
def floor_at(floor, k, theta_mj, acc):
    """The floor's accelerations ``(a_x, a_y, a_v)`` (m/s²) at the evaluation time ``(k + theta_mj) dt`` of step
    ``k``, into ``acc``; after the excitation no horizontal motion and ``a_v = tail_av``."""
    if k >= floor.n_exc:
        acc[0], acc[1], acc[2] = 0.0, 0.0, floor.tail_av
    elif floor.form == FORCING_STEPWISE:
        acc[0], acc[1], acc[2] = floor.ax[k], floor.ay[k], floor.av[k]
    else:
        j = k // floor.sub
        f = (k - j * floor.sub + theta_mj) / floor.sub
        acc[0] = floor.ax[j] + f * (floor.ax[j + 1] - floor.ax[j])
        acc[1] = floor.ay[j] + f * (floor.ay[j + 1] - floor.ay[j])
        acc[2] = floor.av[j] + f * (floor.av[j + 1] - floor.av[j])


@jitable
def free_velocity(model, s, ws):
    """The rotation and inertias at ``q_k`` (``ws.Q``, ``ws.Iw``, ``ws.Iinv``) and the free velocity under the
    step's forces into ``ws.free`` and ``ws.vel``."""
    d, dt, acc = model.design, model.numerics.dt, ws.acc
    rotation(s, ws.Q)
    inertia(ws.Q, d, ws.Iw, ws.Iinv)
    w0, w1, w2 = s[10], s[11], s[12]
    L0 = ws.Iw[0, 0] * w0 + ws.Iw[0, 1] * w1 + ws.Iw[0, 2] * w2
    L1 = ws.Iw[1, 0] * w0 + ws.Iw[1, 1] * w1 + ws.Iw[1, 2] * w2
    L2 = ws.Iw[2, 0] * w0 + ws.Iw[2, 1] * w1 + ws.Iw[2, 2] * w2
    g0, g1, g2 = -(w1 * L2 - w2 * L1), -(w2 * L0 - w0 * L2), -(w0 * L1 - w1 * L0)  # -omega x I omega
    f = ws.free
    f[0], f[1], f[2] = s[7] - dt * acc[0], s[8] - dt * acc[1], s[9] - dt * (d.g + acc[2])
    for i in range(3):
        f[3 + i] = s[10 + i] + dt * (ws.Iinv[i, 0] * g0 + ws.Iinv[i, 1] * g1 + ws.Iinv[i, 2] * g2)
    ws.vel[:] = f


@jitable
def contact_points(model, s, ws, out):
    """The rim points in contact this step into ``ws.arms``, ``ws.phi``, ``ws.W``: the lowest rim point while the
    cylinder is tilted, or ``n_rim`` points evenly round the rim from the one the floor's load pushes towards while
    its base is flat (the rim's height varying by less than ``FLAT_GAP`` contact gaps); each if its height predicted
    at mid-step is at most the contact gap. Returns their number, the first point's body angle (rad) and whether
    the base was flat."""
    d, lim, dt, Q = model.design, model.limits, model.numerics.dt, ws.Q
    flat = 2.0 * d.r * lean(Q) <= FLAT_GAP * lim.lift_gap
    if flat:
        fx, fy = -ws.acc[0], -ws.acc[1]
        bx, by = Q[0, 0] * fx + Q[1, 0] * fy, Q[0, 1] * fx + Q[1, 1] * fy
        phi0 = math.atan2(by, bx) if (bx != 0.0 or by != 0.0) else 0.0
    else:
        phi0 = lowest_angle(Q, 0.0, 0.0)
    m = d.n_rim if flat else 1
    n = 0
    for k in range(m):
        phi = phi0 + 2.0 * math.pi * k / m
        arm = ws.arms[n]
        rim_arm(Q, d, phi, arm)
        gap = s[2] + arm[2]
        vz = s[9] + s[10] * arm[1] - s[11] * arm[0]
        if gap + 0.5 * dt * vz <= lim.lift_gap:
            out[OUT_MAX_PENETRATION] = max(out[OUT_MAX_PENETRATION], -gap)
            ws.phi[n] = phi
            delassus(arm, ws.Iinv, ws.W[n])
            n += 1
    return n, phi0, flat


@jitable
def _pivot_alone(model, ws, n, phi0, out):
    """The flat base's first rim point (towards the floor's load) alone: its exact local solve, accepted if every
    other point then separates (``u_N >= 0``): the uplift about the rim point the load pushes towards. Returns its
    local status if accepted (``ws.vel`` and ``ws.P`` hold it), else -1 (``ws.vel`` the free velocity again and
    ``ws.P`` zero)."""
    ws.P[:n] = 0.0
    if ws.phi[0] != phi0:
        return -1
    a = ws.arms[0]
    vel = ws.vel
    for c in range(3):
        ws.q[c] = vel[c] + (vel[4] * a[2] - vel[5] * a[1] if c == 0 else
                            (vel[5] * a[0] - vel[3] * a[2] if c == 1 else vel[3] * a[1] - vel[4] * a[0]))
    st = local(ws.W[0], ws.q, model.friction, ws.P[0], out, False)
    if st == OPEN:
        return -1
    apply_impulse(vel, ws.Iinv, a, ws.P[0, 0], ws.P[0, 1], ws.P[0, 2])
    for i in range(1, n):
        b = ws.arms[i]
        if vel[2] + vel[3] * b[1] - vel[4] * b[0] < 0.0:
            vel[:] = ws.free
            ws.P[0] = 0.0
            return -1
    return st


@jitable
def _advance(model, s, ws):
    """The end state into ``ws.new``: position by the theta-blend of the velocities, the quaternion turned by
    ``dt`` times the same blend of the angular velocities (floor frame: ``q <- exp(dt omega / 2) q``)."""
    th, dt, v, new = model.numerics.theta_mj, model.numerics.dt, ws.vel, ws.new
    for i in range(3):
        new[i] = s[i] + dt * ((1.0 - th) * s[7 + i] + th * v[i])
        new[7 + i], new[10 + i] = v[i], v[3 + i]
    m0 = (1.0 - th) * s[10] + th * v[3]
    m1 = (1.0 - th) * s[11] + th * v[4]
    m2 = (1.0 - th) * s[12] + th * v[5]
    wn = math.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
    half = 0.5 * dt * wn
    c, f = math.cos(half), (math.sin(half) / wn if wn > 0.0 else 0.5 * dt)
    a0, a1, a2 = f * m0, f * m1, f * m2
    w, x, y, z = s[3], s[4], s[5], s[6]
    nw = c * w - a0 * x - a1 * y - a2 * z
    nx = c * x + w * a0 + a1 * z - a2 * y
    ny = c * y + w * a1 + a2 * x - a0 * z
    nz = c * z + w * a2 + a0 * y - a1 * x
    norm = math.sqrt(nw * nw + nx * nx + ny * ny + nz * nz)
    new[3], new[4], new[5], new[6] = nw / norm, nx / norm, ny / norm, nz / norm


@jitable
def _set_down(model, ws):
    """Set the lowest rim point of the end state ``ws.new`` back onto the floor (shift the centre of mass
    vertically): velocity-level contact lets a loaded point drift off the floor by ``O(dt²)`` a step (the arm turns
    while its velocity is held at zero), enough over a long roll to lift it into spurious flights and landings."""
    Q, arm = ws.Q, ws.tmp
    rotation(ws.new, Q)
    rim_arm(Q, model.design, lowest_angle(Q, 0.0, 0.0), arm)
    gap = ws.new[2] + arm[2]
    if abs(gap) <= SET_DOWN_GAPS * model.limits.lift_gap:
        ws.new[2] -= gap


@jitable
def _flat_closed(model, ws, n, out):
    """The flat base's closed forms (:mod:`.flat`) where the lift about the load's rim point did not hold: the base
    stays down (stuck, or sliding and twisting), or the cylinder lifts about one rim point, sought from the
    centre of pressure that would have been outside the base, or from the rim point moving down fastest where the
    base would not press. Returns the local status, or -1 (NSGS solves the step)."""
    st = flat_base(model, ws, n, out)
    if st >= 0:
        out[OUT_FLAT_STEPS] += 1.0
        return st
    Q = ws.Q
    if st == OUTSIDE:  # towards the centre of pressure
        phi = math.atan2(Q[0, 1] * ws.q[0] + Q[1, 1] * ws.q[1], Q[0, 0] * ws.q[0] + Q[1, 0] * ws.q[1])
    else:  # the base would not press: the rim point moving down fastest
        phi = lowest_moving(Q, model.design.r, ws.free, 0.0)
    st = lift_about(model, ws, n, phi, out)
    if st >= 0:
        out[OUT_LIFT_STEPS] += 1.0
        return st
    return -1


@jitable
def step(model, s, ws, out):
    """One Moreau-Jean step from ``s`` into ``ws.new`` (the floor's accelerations in ``ws.acc``). Returns the rim
    points in contact, the sweeps NSGS took (0: no contact), the points slipping, the first point's body angle
    (rad) and whether the base was flat."""
    free_velocity(model, s, ws)
    n, phi0, flat = contact_points(model, s, ws, out)
    sweeps, slipping = 0, 0
    alone = _pivot_alone(model, ws, n, phi0, out) if n > 1 else -1
    if alone < 0 and n > 1 and flat:
        alone = _flat_closed(model, ws, n, out)
    if alone >= 0:
        sweeps, slipping = 1, (1 if alone == SLIP else 0)
    elif n > 0:
        sweeps, slipping = nsgs(ws, n, model.friction, model.nsgs, model.design.g * model.numerics.dt, out)
    _advance(model, s, ws)
    if n == 1 and ws.P[0, 2] > 0.0:
        _set_down(model, ws)
    return n, sweeps, slipping, phi0, flat


__all__ = ["contact_points", "floor_at", "free_velocity", "step"]
