"""Smooth phases of :mod:`opsrock.solvers.rigid3d`'s kernel: the block turning about stuck corners, integrated
with the classical Runge-Kutta method in steps much longer than the Moreau-Jean step (numba).

While one corner (a corner pivot: three rotational freedoms) or two (an edge: one freedom, the turn about the
line through them) stay down and stuck, and no other corner comes down, the motion is the smooth motion of a
rigid body about a fixed point ``O`` (the pivot corner):

    d(I_O omega)/dt = r x F,   I_O = I + |r|² 1 - r r^T,   r = X - O,

per unit mass, in the floor frame (``I`` the floor-frame inertia about the centre of mass, ``F = (-a_x, -a_y,
-(g + a_v))`` the body force of gravity and the floor's inertia force), so ``I_O omega' = r x F - omega x I_O
omega``; on an edge of unit direction ``e``, ``omega = omega_e e`` and ``omega_e' = e.(r x F) / (e^T I_O e)``.
The quaternion follows ``q' = [0, omega] q / 2``. Moreau-Jean integrates the same phase with a first-order
error (its contact impulse carries the gravity torque of the step's start); this is fourth-order, so a phase
is crossed in steps of :data:`RK_DTAU` instead of ``dtau``.

A smooth step is only taken, and only kept, where it is the same phase throughout
(:func:`opsrock.solvers.rigid3d.smooth._smooth`): the step ends on a sample of the floor motion or the end of
the excitation (the floor's acceleration is linear between samples, a pulse smooth), at the end of every
Runge-Kutta sub-step the pivots' reaction presses on the floor within the static cone (:func:`_loads_hold`;
without this check a smooth step held a pivot through 0.19 s of flight), every other corner stays above the
floor (no impact inside), the tilt stays below pi/2, and a Moreau-Jean probe step from the end state solves the
contact problem with the same corners, stuck and loaded. Otherwise the step is halved, down to :data:`MIN_STEPS`
Moreau-Jean steps, and then the Moreau-Jean steps take over (impacts, lift-off, the onset of slip, flight and
overturning are always theirs; a block rocking on slipping corners has smooth steps of its own,
:func:`opsrock.solvers.rigid3d.smooth._smooth_slip`).

Units as in :mod:`opsrock.solvers.rigid3d.kernel` (per unit mass, SI).
"""

from __future__ import annotations

import math

import numba

from opsrock.solvers.jitable import jitable

#: Longest Runge-Kutta sub-step, in units of ``1/p`` of the weaker axis: the peak tilt is read at the sub-steps'
#: ends, so it is missed by at most ``p² sin(alpha) (RK_DTAU / p)² / 8``, about 3e-6 rad at 5e-3; the method's
#: own error per unit time is of order ``RK_DTAU^4``.
RK_DTAU = 5e-3

#: Longest smooth step, in units of ``1/p`` (a longer one is cut at a sample of the floor motion anyway).
MAX_DTAU = 0.05

#: Shortest smooth step tried, in Moreau-Jean steps: below it the Moreau-Jean steps locate the event.
MIN_STEPS = 16

#: Moreau-Jean steps in the same stuck contact, without an impact, before a smooth step is tried.
CALM_STEPS = 4

#: Longest coarse Moreau-Jean step of a block sliding flat on its four corners, in units of ``1/p``: sliding has
#: no time scale of rocking, and the closed-form flat slide integrates a constant load exactly; a stick-slip
#: transition inside a coarse step moves the slide by about ``mu g (SLIDE_DTAU / p)² / 8``, 1e-7 m.
SLIDE_DTAU = 2e-3

#: The floor motion's form of a record (samples, linear between them): ``kernel.FORCING_LINEAR``.
FORCING_LINEAR = 1


@jitable
def mean_floor(floor, k0, n, theta_mj, a):
    """Mean floor accelerations ``a`` (m/s²) of the floor motion ``floor`` (:class:`.model.Floor`) over steps ``k0
    .. k0 + n - 1`` (within one sample interval of a record, where they are linear: the value at ``k0 + theta_mj
    n``; a pulse's samples averaged)."""
    ax, ay, av, sub, n_exc = floor.ax, floor.ay, floor.av, floor.sub, floor.n_exc
    if k0 >= n_exc:
        a[0], a[1], a[2] = 0.0, 0.0, floor.tail_av
        return
    if floor.form == FORCING_LINEAR:
        j = k0 // sub
        f = (k0 + theta_mj * n - j * sub) / sub
        a[0] = ax[j] + f * (ax[j + 1] - ax[j])
        a[1] = ay[j] + f * (ay[j + 1] - ay[j])
        a[2] = av[j] + f * (av[j + 1] - av[j])
        return
    a[0], a[1], a[2] = 0.0, 0.0, 0.0
    for i in range(k0, k0 + n):
        a[0] += ax[i]
        a[1] += ay[i]
        a[2] += av[i]
    a[0], a[1], a[2] = a[0] / n, a[1] / n, a[2] / n


@jitable
def floor_at(floor, kf, k0, theta_mj, F, g):
    """Body force ``F = (-a_x, -a_y, -(g + a_v))`` (m/s²) of the floor motion ``floor`` at time ``kf`` (units of
    the Moreau-Jean step) of a smooth step that starts at step ``k0``: records linear within the sample interval
    of ``k0``, pulses (sampled at ``(i + theta_mj) dt``) interpolated linearly between their samples."""
    ax, ay, av, sub, n_exc = floor.ax, floor.ay, floor.av, floor.sub, floor.n_exc
    if k0 >= n_exc:
        F[0], F[1], F[2] = 0.0, 0.0, -(g + floor.tail_av)
        return
    if floor.form == FORCING_LINEAR:
        j = k0 // sub
        f = (kf - j * sub) / sub
        F[0] = -(ax[j] + f * (ax[j + 1] - ax[j]))
        F[1] = -(ay[j] + f * (ay[j + 1] - ay[j]))
        F[2] = -(g + av[j] + f * (av[j + 1] - av[j]))
        return
    x = kf - theta_mj
    i = int(math.floor(x))
    if i < 0:
        i, f = 0, 0.0
    elif i >= n_exc - 1:
        i, f = n_exc - 1, 0.0
    else:
        f = x - i
    i1 = min(i + 1, n_exc - 1)
    F[0] = -(ax[i] + f * (ax[i1] - ax[i]))
    F[1] = -(ay[i] + f * (ay[i1] - ay[i]))
    F[2] = -(g + av[i] + f * (av[i1] - av[i]))


@jitable
def quat_matrix(v, o, Q):
    """Rotation matrix ``Q`` of the unit quaternion ``v[o:o + 4] = (w, x, y, z)``."""
    w, x, y, z = v[o], v[o + 1], v[o + 2], v[o + 3]
    Q[0, 0] = 1.0 - 2.0 * (y * y + z * z)
    Q[0, 1] = 2.0 * (x * y - w * z)
    Q[0, 2] = 2.0 * (x * z + w * y)
    Q[1, 0] = 2.0 * (x * y + w * z)
    Q[1, 1] = 1.0 - 2.0 * (x * x + z * z)
    Q[1, 2] = 2.0 * (y * z - w * x)
    Q[2, 0] = 2.0 * (x * z - w * y)
    Q[2, 1] = 2.0 * (y * z + w * x)
    Q[2, 2] = 1.0 - 2.0 * (x * x + y * y)


@jitable
def _arm(y, cb, Q, r):
    """``r = X - O = -Q c_b``: from the pivot corner (body coordinates ``cb`` from the centre of mass) to the
    centre of mass, floor frame."""
    quat_matrix(y, 0, Q)
    for a in range(3):
        r[a] = -(Q[a, 0] * cb[0] + Q[a, 1] * cb[1] + Q[a, 2] * cb[2])


@jitable
def _rhs(y, wk, ib, edge):
    """Time derivative ``wk.dy`` of ``y = (q, omega)`` about the fixed pivot ``wk.cb`` under the body force ``wk.F``
    (see the module docstring; ``ib`` the body-frame inertia, ``edge``: turning about the edge ``wk.e``); ``wk``
    (:class:`.workspace.PivotWork`) gets the arm ``r``, ``Q`` and ``IO`` of ``y``."""
    cb, F, e, dy, Q, IO, r = wk.cb, wk.F, wk.e, wk.dy, wk.Q, wk.IO, wk.r
    _arm(y, cb, Q, r)
    rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
    for i in range(3):
        for j in range(3):
            c = 0.0
            for k in range(3):
                c += Q[i, k] * Q[j, k] * ib[k]
            IO[i, j] = c + (rr if i == j else 0.0) - r[i] * r[j]
    t0 = r[1] * F[2] - r[2] * F[1]
    t1 = r[2] * F[0] - r[0] * F[2]
    t2 = r[0] * F[1] - r[1] * F[0]
    w0, w1, w2 = y[4], y[5], y[6]
    if edge:
        Ie = 0.0
        for i in range(3):
            Ie += e[i] * (IO[i, 0] * e[0] + IO[i, 1] * e[1] + IO[i, 2] * e[2])
        acc = (e[0] * t0 + e[1] * t1 + e[2] * t2) / Ie
        dy[4], dy[5], dy[6] = acc * e[0], acc * e[1], acc * e[2]
    else:
        L0 = IO[0, 0] * w0 + IO[0, 1] * w1 + IO[0, 2] * w2
        L1 = IO[1, 0] * w0 + IO[1, 1] * w1 + IO[1, 2] * w2
        L2 = IO[2, 0] * w0 + IO[2, 1] * w1 + IO[2, 2] * w2
        b0, b1, b2 = t0 - (w1 * L2 - w2 * L1), t1 - (w2 * L0 - w0 * L2), t2 - (w0 * L1 - w1 * L0)
        c00 = IO[1, 1] * IO[2, 2] - IO[1, 2] * IO[2, 1]
        c01 = IO[0, 2] * IO[2, 1] - IO[0, 1] * IO[2, 2]
        c02 = IO[0, 1] * IO[1, 2] - IO[0, 2] * IO[1, 1]
        c10 = IO[1, 2] * IO[2, 0] - IO[1, 0] * IO[2, 2]
        c11 = IO[0, 0] * IO[2, 2] - IO[0, 2] * IO[2, 0]
        c12 = IO[0, 2] * IO[1, 0] - IO[0, 0] * IO[1, 2]
        c20 = IO[1, 0] * IO[2, 1] - IO[1, 1] * IO[2, 0]
        c21 = IO[0, 1] * IO[2, 0] - IO[0, 0] * IO[2, 1]
        c22 = IO[0, 0] * IO[1, 1] - IO[0, 1] * IO[1, 0]
        det = IO[0, 0] * c00 + IO[0, 1] * c10 + IO[0, 2] * c20
        dy[4] = (c00 * b0 + c01 * b1 + c02 * b2) / det
        dy[5] = (c10 * b0 + c11 * b1 + c12 * b2) / det
        dy[6] = (c20 * b0 + c21 * b1 + c22 * b2) / det
    qw, qx, qy, qz = y[0], y[1], y[2], y[3]
    dy[0] = -0.5 * (w0 * qx + w1 * qy + w2 * qz)
    dy[1] = 0.5 * (qw * w0 + w1 * qz - w2 * qy)
    dy[2] = 0.5 * (qw * w1 + w2 * qx - w0 * qz)
    dy[3] = 0.5 * (qw * w2 + w0 * qy - w1 * qx)


@jitable
def _tilt_of(y):
    """Tilt (rad) of the quaternion ``y[0:4]``: ``2 asin(sqrt(q_x² + q_y²))``."""
    return 2.0 * math.asin(min(1.0, math.sqrt(y[1] * y[1] + y[2] * y[2])))


@numba.njit(cache=True, inline='always')
def _loads_hold(wk, edge, length, friction):
    """Do the pivots carry the motion ``(wk.y, wk.dy)`` (the arm ``wk.r`` and ``wk.IO`` of ``y``, body force
    ``wk.F``)? The
    reaction per unit mass ``R = omega' x r + omega x (omega x r) - F`` presses on the floor (``R_z > 0``) within
    the static cone (``hypot(R_x, R_y) <= mu_s R_z``; always with infinite friction); on an edge of direction
    ``e`` and ``length`` from the pivot ``O`` to the other corner, each corner presses: the other's share
    ``R_Bz = (e_y m_x - e_x m_y) / length`` from the moment about ``O``, ``length e x R_B = m = I_O omega' +
    omega x I_O omega - r x F``. A block that would lift a pivot or slip leaves the smooth phase here, between
    two Moreau-Jean probes."""
    y, dy, r, IO, F, e = wk.y, wk.dy, wk.r, wk.IO, wk.F, wk.e
    w0, w1, w2 = y[4], y[5], y[6]
    a0, a1, a2 = dy[4], dy[5], dy[6]
    r0, r1, r2 = r[0], r[1], r[2]
    v0, v1, v2 = w1 * r2 - w2 * r1, w2 * r0 - w0 * r2, w0 * r1 - w1 * r0  # omega x r
    R0 = a1 * r2 - a2 * r1 + w1 * v2 - w2 * v1 - F[0]
    R1 = a2 * r0 - a0 * r2 + w2 * v0 - w0 * v2 - F[1]
    R2 = a0 * r1 - a1 * r0 + w0 * v1 - w1 * v0 - F[2]
    if R2 <= 0.0 or (not friction.infinite and math.hypot(R0, R1) > friction.mu_s * R2):
        return False
    if not edge:
        return True
    L0 = IO[0, 0] * w0 + IO[0, 1] * w1 + IO[0, 2] * w2
    L1 = IO[1, 0] * w0 + IO[1, 1] * w1 + IO[1, 2] * w2
    L2 = IO[2, 0] * w0 + IO[2, 1] * w1 + IO[2, 2] * w2
    m0 = IO[0, 0] * a0 + IO[0, 1] * a1 + IO[0, 2] * a2 + w1 * L2 - w2 * L1 - (r1 * F[2] - r2 * F[1])
    m1 = IO[1, 0] * a0 + IO[1, 1] * a1 + IO[1, 2] * a2 + w2 * L0 - w0 * L2 - (r2 * F[0] - r0 * F[2])
    rb = (e[1] * m0 - e[0] * m1) / length
    return rb > 0.0 and R2 - rb > 0.0


@jitable
def integrate(model, floor, s, pivots, k0, n_steps, new, wk):
    """Runge-Kutta from state ``s`` at Moreau-Jean step ``k0`` over ``n_steps`` steps about the stuck corners
    ``pivots`` (one or two indices) into ``new``; returns the largest tilt (rad) at the sub-steps' ends, or -1 as
    soon as the pivots' loads stop holding the block there (:func:`_loads_hold`). ``model`` and ``floor`` are the
    kernel's (:mod:`.model`); ``wk`` its scratch (:class:`.workspace.PivotWork`)."""
    y, dy, acc, ytmp, F, cb, e, r, Q = wk.y, wk.dy, wk.acc, wk.ytmp, wk.F, wk.cb, wk.e, wk.r, wk.Q
    body, dt, theta_mj = model.body, model.numerics.dt, model.numerics.theta_mj
    b, d, h, g, ib = body.b, body.d, body.h, body.g, body.inertia
    i0 = pivots[0]
    sx = 1.0 if i0 == 0 or i0 == 3 else -1.0
    sy = 1.0 if i0 == 0 or i0 == 1 else -1.0
    cb[0], cb[1], cb[2] = sx * b, sy * d, -h
    y[0], y[1], y[2], y[3] = s[3], s[4], s[5], s[6]
    y[4], y[5], y[6] = s[10], s[11], s[12]
    _arm(y, cb, Q, r)
    o0, o1, o2 = s[0] - r[0], s[1] - r[1], s[2] - r[2]  # the pivot, fixed in the floor frame
    edge = pivots.shape[0] == 2
    n = 1.0
    if edge:
        i1 = pivots[1]
        tx = (1.0 if i1 == 0 or i1 == 3 else -1.0) * b - cb[0]
        ty = (1.0 if i1 == 0 or i1 == 1 else -1.0) * d - cb[1]
        e0 = Q[0, 0] * tx + Q[0, 1] * ty
        e1 = Q[1, 0] * tx + Q[1, 1] * ty
        e2 = Q[2, 0] * tx + Q[2, 1] * ty
        n = math.sqrt(e0 * e0 + e1 * e1 + e2 * e2)
        e[0], e[1], e[2] = e0 / n, e1 / n, e2 / n
        we = y[4] * e[0] + y[5] * e[1] + y[6] * e[2]
        y[4], y[5], y[6] = we * e[0], we * e[1], we * e[2]
    n_sub = max(1, int(math.ceil(n_steps * dt * body.p / RK_DTAU)))
    hs = n_steps / n_sub  # sub-step in Moreau-Jean steps
    hdt = hs * dt
    tilt_max = _tilt_of(y)
    floor_at(floor, float(k0), k0, theta_mj, F, g)
    _rhs(y, wk, ib, edge)
    for m in range(n_sub):
        kf = k0 + m * hs
        for a in range(7):
            acc[a] = dy[a] / 6.0  # the first stage: the derivative at the sub-step's start
        for stage in range(1, 4):
            c = 0.5 if stage < 3 else 1.0
            w = 1.0 / 3.0 if stage < 3 else 1.0 / 6.0
            for a in range(7):
                ytmp[a] = y[a] + c * hdt * dy[a]
            floor_at(floor, kf + c * hs, k0, theta_mj, F, g)
            _rhs(ytmp, wk, ib, edge)
            for a in range(7):
                acc[a] += w * dy[a]
        for a in range(7):
            y[a] += hdt * acc[a]
        nq = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
        for a in range(4):
            y[a] /= nq
        tilt_max = max(tilt_max, _tilt_of(y))
        floor_at(floor, kf + hs, k0, theta_mj, F, g)
        _rhs(y, wk, ib, edge)  # also the next sub-step's first stage
        if not _loads_hold(wk, edge, n if edge else 1.0, model.friction):
            return -1.0
    _arm(y, cb, Q, r)
    new[0], new[1], new[2] = o0 + r[0], o1 + r[1], o2 + r[2]
    new[3], new[4], new[5], new[6] = y[0], y[1], y[2], y[3]
    w0, w1, w2 = y[4], y[5], y[6]
    new[7], new[8], new[9] = w1 * r[2] - w2 * r[1], w2 * r[0] - w0 * r[2], w0 * r[1] - w1 * r[0]
    new[10], new[11], new[12] = w0, w1, w2
    return tilt_max


@jitable
def step_end(floor, k, n_steps_max):
    """Where a smooth step from step ``k`` may end: at most ``n_steps_max`` steps on, never past the end of the
    excitation or (records) the next sample."""
    end = k + n_steps_max
    if k < floor.n_exc:
        end = min(end, floor.n_exc)
        if floor.form == FORCING_LINEAR:
            end = min(end, (k // floor.sub + 1) * floor.sub)
    return end


__all__ = ["CALM_STEPS", "MAX_DTAU", "MIN_STEPS", "RK_DTAU", "SLIDE_DTAU", "floor_at", "integrate", "mean_floor",
           "quat_matrix", "step_end"]
