"""Smooth phase of :mod:`opsrock.solvers.cylinder3d`'s kernel: the cylinder rolling without slip on the lowest point
of its rim (rocking on it, or wobbling: the contact point running round the rim), integrated with the classical
Runge-Kutta method in sub-steps much longer than the Moreau-Jean step (numba).

While one rim point touches the floor and sticks, the velocity of the body's point at the contact, ``u = V + omega x
a`` (``a`` the arm from the centre of mass to the lowest rim point, body angle ``phi``), stays zero. The contact
point runs round the rim at the rate that keeps it the lowest point (the rim's tangent ``t = da/dphi`` horizontal):
``phi' = -(omega x t)_z / (r sin tilt)``. So ``du/dt = V' + omega' x a + omega x (omega x a + phi' t) = 0`` with
``V' = F + P`` and ``omega' = alpha_f + I^-1 (a x P)`` (``F = (-a_x, -a_y, -(g + a_v))`` the body force,
``alpha_f = -I^-1 (omega x I omega)``, ``P`` the contact force per unit mass): ``W P = -(F + alpha_f x a + omega x
(omega x a) + phi' omega x t)``, ``W`` the contact point's Delassus matrix (:func:`.contact.delassus`). The quaternion
follows ``q' = [0, omega] q / 2``. Rolling without slip does no work: the phase keeps the energy to the method's
fourth-order error, where a Moreau-Jean step keeps it to first order (the gravity torque of the step's start).

A sub-step is kept only where it is the same phase throughout: at each of its four stages the contact presses
(``P_z > 0``) within the static cone (``|P_T| <= mu_s P_z``; always with infinite friction), the contact point turns
by at most ``ROLL_PHI`` and the base stays tilted (``2 r sin tilt`` above ``ROLL_FLAT`` contact gaps; the point would
otherwise whip round the rim as the base passes through flat, or jump across it at a landing), and at its end the
tilt is below pi/2. It never crosses a sample of the floor motion (linear in between), the end of the excitation or
of the tail. Otherwise the Moreau-Jean steps go on: lift-off, the onset of slip, landings, flight and overturning
are theirs. After each kept sub-step the lowest rim point is set on the floor and its velocity to zero (the drift
of the constraint, of the method's order). Units as in :mod:`opsrock.solvers.cylinder3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import math


from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers.cylinder3d.constants import FORCING_LINEAR, ROLL_FLAT, ROLL_PHI

#: Rows of :class:`.model.RollWork`'s ``m``: rotation, inertia and its inverse (floor frame), Delassus block.
RM_Q, RM_IW, RM_IINV, RM_W = 0, 1, 2, 3
#: Rows of its ``v``: arm, rim tangent, free acceleration, alpha_f, contact force, body force (3 columns); end
#: state, derivative, weighted sum, stage state (13).
RV_ARM, RV_TAN, RV_B, RV_AL, RV_P, RV_F, RV_Y, RV_DY, RV_SUM, RV_TMP = 0, 1, 2, 3, 4, 5, 6, 7, 8, 9
from opsrock.solvers.cylinder3d.contact import delassus, stick
from opsrock.solvers.cylinder3d.geometry import inertia, lowest_angle, rim_arm, rotation, tilt
from opsrock.solvers.jitable import jitable


@jitable
def floor_force(floor, kf, k0, theta_mj, acc):
    """The floor's accelerations ``(a_x, a_y, a_v)`` (m/s²) into ``acc`` at the time ``kf`` (in Moreau-Jean steps) of
    a smooth step that starts at step ``k0``: a record linear within the sample interval of ``k0``; a pulse (its
    values sampled at ``(i + theta_mj) dt``) linear between its samples; after the excitation ``(0, 0, tail_av)``."""
    if k0 >= floor.n_exc:
        acc[0], acc[1], acc[2] = 0.0, 0.0, floor.tail_av
        return
    if floor.form == FORCING_LINEAR:
        i = k0 // floor.sub
        f = (kf - i * floor.sub) / floor.sub
        i1 = i + 1
    else:
        x = kf - theta_mj
        i = min(max(int(math.floor(x)), 0), floor.n_exc - 1)
        f = min(max(x - i, 0.0), 1.0)
        i1 = min(i + 1, floor.n_exc - 1)
    acc[0] = floor.ax[i] + f * (floor.ax[i1] - floor.ax[i])
    acc[1] = floor.ay[i] + f * (floor.ay[i1] - floor.ay[i])
    acc[2] = floor.av[i] + f * (floor.av[i1] - floor.av[i])


@jitable
def span_end(model, floor, k):
    """Where a smooth sub-step from step ``k`` may end: ``roll_steps`` steps on, never past a record's next sample, the
    end of the excitation, the end of the tail's span or ``max_steps``."""
    end = k + model.numerics.roll_steps
    if k < floor.n_exc:
        end = min(end, floor.n_exc)
        if floor.form == FORCING_LINEAR:
            end = min(end, (k // floor.sub + 1) * floor.sub)
    elif model.limits.max_tail >= 0:
        end = min(end, floor.n_exc + model.limits.max_tail)
    return min(end, model.limits.max_steps)


@jitable
def _contact_force(model, y, rw):
    """The contact force (row ``RV_P``, m/s², per unit mass) that keeps the lowest rim point of ``y`` rolling without
    slip under the body force (row ``RV_F``), with the arm, ``alpha_f`` (rows ``RV_ARM``, ``RV_AL``) and the rotation
    and inertia of ``y``. Returns the contact point's turning rate ``phi'`` (rad/s) and its body angle ``phi`` (rad)."""
    d, Q, Iw, Iinv, v = model.design, rw.m[RM_Q], rw.m[RM_IW], rw.m[RM_IINV], rw.v
    a, t, b, al, F = v[RV_ARM], v[RV_TAN], v[RV_B], v[RV_AL], v[RV_F]
    rotation(y, Q)
    inertia(Q, d, Iw, Iinv)
    phi = lowest_angle(Q, 0.0, 0.0)
    rim_arm(Q, d, phi, a)
    c, s = math.cos(phi), math.sin(phi)
    for i in range(3):
        t[i] = d.r * (c * Q[i, 1] - s * Q[i, 0])
    w0, w1, w2 = y[10], y[11], y[12]
    rate = -(w0 * t[1] - w1 * t[0]) / (d.r * math.hypot(Q[2, 0], Q[2, 1]))
    L0 = Iw[0, 0] * w0 + Iw[0, 1] * w1 + Iw[0, 2] * w2
    L1 = Iw[1, 0] * w0 + Iw[1, 1] * w1 + Iw[1, 2] * w2
    L2 = Iw[2, 0] * w0 + Iw[2, 1] * w1 + Iw[2, 2] * w2
    g0, g1, g2 = -(w1 * L2 - w2 * L1), -(w2 * L0 - w0 * L2), -(w0 * L1 - w1 * L0)
    for i in range(3):
        al[i] = Iinv[i, 0] * g0 + Iinv[i, 1] * g1 + Iinv[i, 2] * g2
    v0, v1, v2 = w1 * a[2] - w2 * a[1], w2 * a[0] - w0 * a[2], w0 * a[1] - w1 * a[0]  # omega x a
    b[0] = F[0] + al[1] * a[2] - al[2] * a[1] + w1 * v2 - w2 * v1 + rate * (w1 * t[2] - w2 * t[1])
    b[1] = F[1] + al[2] * a[0] - al[0] * a[2] + w2 * v0 - w0 * v2 + rate * (w2 * t[0] - w0 * t[2])
    b[2] = F[2] + al[0] * a[1] - al[1] * a[0] + w0 * v1 - w1 * v0 + rate * (w0 * t[1] - w1 * t[0])
    delassus(a, Iinv, rw.m[RM_W])
    stick(rw.m[RM_W], b, v[RV_P])
    return rate, phi


@jitable
def _rhs(model, y, rw, dy):
    """The time derivative ``dy`` of the state ``y`` (13) rolling on its lowest rim point (:func:`_contact_force`).
    Returns ``(holds, phi', phi)``: ``holds`` False unless the contact presses within the static cone and the base
    is tilted by more than ``ROLL_FLAT`` contact gaps over the diameter."""
    d, P, a, al, F = model.design, rw.v[RV_P], rw.v[RV_ARM], rw.v[RV_AL], rw.v[RV_F]
    if 2.0 * d.r * math.hypot(y[4] * y[6] + y[3] * y[5], y[5] * y[6] - y[3] * y[4]) * 2.0 <= \
            ROLL_FLAT * model.limits.lift_gap:
        return False, 0.0, 0.0
    rate, phi = _contact_force(model, y, rw)
    f = model.friction
    holds = P[2] > 0.0 and (f.infinite or math.hypot(P[0], P[1]) <= f.mu_s * P[2])
    c0, c1, c2 = a[1] * P[2] - a[2] * P[1], a[2] * P[0] - a[0] * P[2], a[0] * P[1] - a[1] * P[0]
    Iinv = rw.m[RM_IINV]
    for i in range(3):
        dy[i] = y[7 + i]
        dy[7 + i] = F[i] + P[i]
        dy[10 + i] = al[i] + Iinv[i, 0] * c0 + Iinv[i, 1] * c1 + Iinv[i, 2] * c2
    w0, w1, w2 = y[10], y[11], y[12]
    qw, qx, qy, qz = y[3], y[4], y[5], y[6]
    dy[3] = -0.5 * (w0 * qx + w1 * qy + w2 * qz)
    dy[4] = 0.5 * (qw * w0 + w1 * qz - w2 * qy)
    dy[5] = 0.5 * (qw * w1 + w2 * qx - w0 * qz)
    dy[6] = 0.5 * (qw * w2 + w0 * qy - w1 * qx)
    return holds, rate, phi


@jitable
def _set_on_floor(model, y, rw):
    """The constraint's drift removed from the end state ``y``: the lowest rim point set on the floor (the centre of
    mass shifted vertically) and its velocity zero (``V = -omega x a``)."""
    Q, a = rw.m[RM_Q], rw.v[RV_ARM]
    rotation(y, Q)
    rim_arm(Q, model.design, lowest_angle(Q, 0.0, 0.0), a)
    y[2] = -a[2]
    y[7] = -(y[11] * a[2] - y[12] * a[1])
    y[8] = -(y[12] * a[0] - y[10] * a[2])
    y[9] = -(y[10] * a[1] - y[11] * a[0])


@jitable
def roll(model, floor, s, k, n, rw):
    """One Runge-Kutta sub-step of ``n`` Moreau-Jean steps from the state ``s`` at step ``k`` rolling on its lowest rim
    point, into row ``RV_Y`` of ``rw.v``. Returns ``(kept, the floor's work (J/kg), the contact point's body angle at the end (rad),
    its turn over the sub-step (rad))``; not kept if any stage leaves the phase (see the module docstring). ``rw``
    is the scratch (:class:`.model.RollWork`)."""
    v = rw.v
    y, dy, acc, tmp, F = v[RV_Y], v[RV_DY], v[RV_SUM], v[RV_TMP], v[RV_F]
    h, th, g = n * model.numerics.dt, model.numerics.theta_mj, model.design.g
    work, phi0, turn = 0.0, 0.0, 0.0
    for stage in range(4):
        c = 0.0 if stage == 0 else (0.5 if stage < 3 else 1.0)
        w = 1.0 / 6.0 if (stage == 0 or stage == 3) else 1.0 / 3.0
        for i in range(13):
            tmp[i] = s[i] if stage == 0 else s[i] + c * h * dy[i]
        floor_force(floor, k + c * n, k, th, F)
        work -= w * h * (F[0] * tmp[7] + F[1] * tmp[8] + F[2] * tmp[9])
        F[0], F[1], F[2] = -F[0], -F[1], -(g + F[2])
        holds, rate, phi = _rhs(model, tmp, rw, dy)
        if stage == 0:
            phi0 = phi
        turn = (phi - phi0 + math.pi) % (2.0 * math.pi) - math.pi
        if not holds or abs(turn) > ROLL_PHI or abs(rate) * h > ROLL_PHI:
            return False, 0.0, 0.0, 0.0
        for i in range(13):
            acc[i] = w * dy[i] if stage == 0 else acc[i] + w * dy[i]
    for i in range(13):
        y[i] = s[i] + h * acc[i]
    nq = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5] + y[6] * y[6])
    for i in range(3, 7):
        y[i] /= nq
    if tilt(y)[0] >= OVERTURNING_ANGLE:
        return False, 0.0, 0.0, 0.0
    _set_on_floor(model, y, rw)
    phi1 = lowest_angle(rw.m[RM_Q], 0.0, 0.0)
    turn = (phi1 - phi0 + math.pi) % (2.0 * math.pi) - math.pi
    if abs(turn) > ROLL_PHI:
        return False, 0.0, 0.0, 0.0
    return True, work, phi1, turn


__all__ = ["RV_Y", "floor_force", "roll", "span_end"]
