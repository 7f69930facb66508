"""The flat base in closed form (numba): a Moreau-Jean step of a cylinder whose whole base stays on the floor, stuck
or sliding and twisting on it, and the lift about the rim point its centre of pressure would leave the base at.
Units and frames as in :mod:`opsrock.solvers.cylinder3d.kernel` (SI, per unit mass).

The base on the floor. After the step ``V_z = 0`` and ``omega_x = omega_y = 0``, which keep every rim point's normal
velocity at zero whatever the base's small tilt, so the normal impulse is ``N = -V_free,z`` (it must press) and the
unknowns are the base's motion in plan ``(V_x, V_y, omega_z)``. The rim's normal impulses are statically
indeterminate (16 points, three equations): their resultant's line, the centre of pressure ``c``, follows from the
moment balance about the centre of mass once the friction impulse is known, and the base stays down only if ``c``
lies inside the base (``|c| <= r``; with part of the rim off the floor, inside the polygon of the rim points in
contact). Friction: the friction impulse ``F`` and its moment about the axis ``T`` lie in the *ellipsoidal limit
surface* ``|F|² + (T / r)² <= (mu N)²`` (Goyal, Ruina & Papadopoulos, Wear 143, 1991; Howe & Cutkosky, IJRR 15,
1996) with its normal flow rule: the base sticks (``V = 0``, ``omega_z = 0``) while the impulse that stops it lies
inside with ``mu_s``; else it slides and twists with ``(V, r omega_z)`` against ``(F, T / r)`` on the surface with
``mu_k``. For a rim with any distribution of pressure the limits of pure sliding (``|F| = mu N``) and pure twisting
(``|T| = mu N r``) are exact; in between the ellipsoid is the outer bound of a uniformly pressed rim (up to 11 % more
friction where the base turns about a rim point). The implicit step is then one scalar equation (:func:`_slip_scale`).

The lift. With ``|c| > r`` the base cannot stay down: the cylinder starts to rock about one rim point. It is sought
from the rim point towards ``c`` (or, where the base would not press at all, from the rim point moving down fastest):
the rim point whose lone impulse (:func:`.contact.local`, stuck or slipping) leaves it the rim point moving down
fastest, so that the rest of the rim rises (:func:`lift_about`: at any exact body angle, not only the rim points');
it is accepted if every rim point in contact then separates.
"""

from __future__ import annotations

import math


from opsrock.solvers.cylinder3d.constants import CONE_SLACK, OPEN, SLIP, STICK
from opsrock.solvers.cylinder3d.contact import apply_impulse, delassus, local
from opsrock.solvers.cylinder3d.geometry import rim_arm
from opsrock.solvers.jitable import jitable

#: Relative tolerance of the flow rule's scalar equation (:func:`_slip_scale`) and most of its Newton iterations.
SCALE_TOL = 1e-14
SCALE_ITERATIONS = 100
#: The lift's rim point is found to ``LIFT_TOL`` rad round the rim (:func:`_settle_lift`).
LIFT_TOL = 1e-10
LIFT_ITERATIONS = 30
#: A bisected sign change of the turn is a root, not its wrap at +-pi, if the turn there is at most ``ROOT_TURN`` rad.
ROOT_TURN = 1e-6
#: :func:`flat_base`'s and :func:`lift_about`'s refusals (their successes are the local statuses ``STICK``, ``SLIP``).
NO_PRESS, OUTSIDE = -1, -2


@jitable
def _slip_scale(a, b, d3, target):
    """The ``lam > 0`` with ``lam² (a / (1 + lam)² + b / (d3 + lam)²) = target²`` (``a = |V_free|²``, ``b = (d3 r
    omega_free)²``, ``target = mu_k N < sqrt(a + b)``): the sliding base's velocities are ``V_free / (1 + lam)`` and
    ``omega_free d3 / (d3 + lam)``. The left side grows with ``lam`` from 0 to ``a + b``; Newton inside the bracket
    ``[min(1, d3), max(1, d3)] target / (sqrt(a + b) - target)``, bisection where it leaves it."""
    s = math.sqrt(a + b)
    lo, hi = min(1.0, d3) * target / (s - target), max(1.0, d3) * target / (s - target)
    lam, goal = hi, target * target
    for _ in range(SCALE_ITERATIONS):
        u, w = 1.0 + lam, d3 + lam
        f = lam * lam * (a / (u * u) + b / (w * w)) - goal
        if f > 0.0:
            hi = lam
        else:
            lo = lam
        df = 2.0 * lam * (a / (u * u * u) + d3 * b / (w * w * w))
        nxt = lam - f / df if df > 0.0 else 0.5 * (lo + hi)
        if not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - lam) <= SCALE_TOL * lam:
            return nxt
        lam = nxt
    return lam


@jitable
def _inside(ws, n, n_rim, r, c0, c1):
    """The centre of pressure ``(c0, c1)`` (m, floor frame, from the base centre) lies in the base: in its circle with
    the whole rim in contact, else in the polygon of the ``n`` rim points in contact (``ws.arms``, in order round the
    rim; fewer than three carry no area)."""
    if n == n_rim:
        return math.hypot(c0, c1) <= r
    if n < 3:
        return False
    b0, b1 = ws.tmp[0], ws.tmp[1]  # the base centre's arm
    for i in range(n):
        j = (i + 1) % n
        x0, y0 = ws.arms[i, 0] - b0, ws.arms[i, 1] - b1
        x1, y1 = ws.arms[j, 0] - b0, ws.arms[j, 1] - b1
        if (x1 - x0) * (c1 - y0) - (y1 - y0) * (c0 - x0) < 0.0:
            return False
    return True


@jitable
def _plan_motion(model, ws, normal):
    """The base's motion in plan after the step, ``(V_x, V_y, omega_z)`` and the status (``STICK``, ``SLIP``), for
    the normal impulse ``normal`` (m/s) and the free velocity ``ws.vel``: stuck if the impulse that stops it lies in the
    static limit surface, else sliding and twisting on the kinetic one (:mod:`.flat`)."""
    d, f, vel, Iw = model.design, model.friction, ws.vel, ws.Iw
    k = Iw[2, 2]
    wz = (Iw[2, 0] * vel[3] + Iw[2, 1] * vel[4] + k * vel[5]) / k  # the free twist rate
    d3 = k / (d.r * d.r)
    a, b = vel[0] * vel[0] + vel[1] * vel[1], (d3 * d.r * wz) ** 2
    s = math.sqrt(a + b)
    if f.infinite or s <= f.mu_s * normal * (1.0 + CONE_SLACK) or s <= f.mu_k * normal:
        return 0.0, 0.0, 0.0, STICK
    lam = _slip_scale(a, b, d3, f.mu_k * normal)
    return vel[0] / (1.0 + lam), vel[1] / (1.0 + lam), wz * d3 / (d3 + lam), SLIP


@jitable
def flat_base(model, ws, n, out):
    """The whole base on the floor this step (the ``n`` rim points in contact in ``ws.arms``, the free velocity in
    ``ws.vel``): returns ``STICK`` or ``SLIP`` with ``ws.vel`` the velocity after the step, else ``NO_PRESS`` (the
    normal impulse would pull) or ``OUTSIDE`` (the centre of pressure lies outside the base: ``ws.q[:2]`` holds it, m
    from the base centre, floor frame); ``ws.vel`` is then unchanged."""
    d, vel, Iw, Q = model.design, ws.vel, ws.Iw, ws.Q
    normal = -vel[2]
    if normal <= 0.0:
        return NO_PRESS
    v0, v1, wz, status = _plan_motion(model, ws, normal)
    p0, p1 = v0 - vel[0], v1 - vel[1]
    b = ws.tmp
    b[0], b[1], b[2] = -d.h * Q[0, 2], -d.h * Q[1, 2], -d.h * Q[2, 2]
    # the impulses' moment about the base centre: Iw (omega - omega_free) - b x P
    m0 = Iw[0, 2] * wz - (Iw[0, 0] * vel[3] + Iw[0, 1] * vel[4] + Iw[0, 2] * vel[5]) - (b[1] * normal - b[2] * p1)
    m1 = Iw[1, 2] * wz - (Iw[1, 0] * vel[3] + Iw[1, 1] * vel[4] + Iw[1, 2] * vel[5]) - (b[2] * p0 - b[0] * normal)
    ws.q[0], ws.q[1] = -m1 / normal, m0 / normal
    if not _inside(ws, n, d.n_rim, d.r, ws.q[0], ws.q[1]):
        return OUTSIDE
    vel[0], vel[1], vel[2], vel[3], vel[4], vel[5] = v0, v1, 0.0, 0.0, 0.0, wz
    return status


@jitable
def lowest_moving(Q, r, vel, phi):
    """Body angle (rad) of the rim point moving down fastest (smallest normal velocity) at the velocity ``vel`` of the
    cylinder with a level base: ``u_N(psi) = V_z + r (alpha cos psi + beta sin psi)`` (``alpha``, ``beta`` the
    vertical velocities the rotation gives the body's ``x`` and ``y`` axes) is least at ``atan2(-beta, -alpha)``;
    ``phi`` where the rotation moves no rim point."""
    a0 = vel[3] * Q[1, 0] - vel[4] * Q[0, 0]
    a1 = vel[3] * Q[1, 1] - vel[4] * Q[0, 1]
    if a0 == 0.0 and a1 == 0.0:
        return phi
    return math.atan2(-a1, -a0)


@jitable
def _lift_at(model, ws, phi, out):
    """The rim point at body angle ``phi`` alone from the free velocity ``ws.free``: its exact local solve into
    ``ws.vel``; returns its status (``OPEN``: it does not press)."""
    Q, vel, a, W, q, P = ws.Q, ws.vel, ws.parm, ws.pW, ws.q, ws.pP
    vel[:] = ws.free
    rim_arm(Q, model.design, phi, a)
    delassus(a, ws.Iinv, W)
    q[0] = vel[0] + vel[4] * a[2] - vel[5] * a[1]
    q[1] = vel[1] + vel[5] * a[0] - vel[3] * a[2]
    q[2] = vel[2] + vel[3] * a[1] - vel[4] * a[0]
    st = local(W, q, model.friction, P, out, False)
    if st != OPEN:
        apply_impulse(vel, ws.Iinv, a, P[0], P[1], P[2])
    return st


@jitable
def _turn(model, ws, phi, out):
    """How far round the rim (rad, in ``(-pi, pi]``) from the body angle ``phi`` lies the rim point moving down
    fastest after ``phi``'s lone impulse (:func:`_lift_at`); NaN if ``phi`` does not press."""
    if _lift_at(model, ws, phi, out) == OPEN:
        return math.nan
    return (lowest_moving(ws.Q, model.design.r, ws.vel, phi) - phi + math.pi) % (2.0 * math.pi) - math.pi


@jitable
def _settle_lift(model, ws, phi, out):
    """The body angle near ``phi`` where the lift's point is itself the rim point moving down fastest after its
    impulse (:func:`_turn` zero, falling through it as the angle grows): the fixed point of moving to that rim point
    if it settles within ``LIFT_ITERATIONS`` moves (to ``LIFT_TOL``), else of the ``n_rim`` angles round the rim
    from ``phi`` the sign change nearest to it, bisected to ``LIFT_TOL`` (a root if the turn there is within
    ``ROOT_TURN``, not the wrap at ``+-pi``); NaN if there is none."""
    start = phi
    for _ in range(LIFT_ITERATIONS):
        d = _turn(model, ws, phi, out)
        if not abs(d) > LIFT_TOL:  # settled, or NaN: it does not press
            return phi if d == d else math.nan
        phi += d
    phi = start
    d0 = _turn(model, ws, phi, out)
    m, best, lo, hi = model.design.n_rim, math.inf, 0.0, 0.0
    step = 2.0 * math.pi / m
    prev = d0
    for k in range(1, m + 1):
        cur = _turn(model, ws, phi + k * step, out)
        if prev > 0.0 and cur <= 0.0:  # a crossing (or the wrap at +-pi, refused below)
            away = min(k - 1, m + 1 - k)
            if away < best:
                best, lo, hi = away, phi + (k - 1) * step, phi + k * step
        prev = cur
    if best == math.inf:
        return math.nan
    while hi - lo > LIFT_TOL:
        mid = 0.5 * (lo + hi)
        d = _turn(model, ws, mid, out)
        if d > 0.0:
            lo = mid
        elif d <= 0.0:
            hi = mid
        else:
            return math.nan
    return hi if abs(_turn(model, ws, hi, out)) <= ROOT_TURN else math.nan


@jitable
def lift_about(model, ws, n, phi, out):
    """The cylinder rocking up about one rim point of its flat base, sought from the body angle ``phi`` (rad): the
    point whose lone impulse (:func:`_lift_at`, stuck or slipping) leaves it the rim point moving down fastest
    (:func:`_settle_lift`), so that every other rim point rises or stays. Accepted if it presses and every one of the
    ``n`` rim points in contact (``ws.arms``) then separates. Returns its status (``ws.vel`` the velocity after the
    step) or ``OUTSIDE`` (``ws.vel`` the free velocity ``ws.free``)."""
    phi = _settle_lift(model, ws, phi, out)
    st = OPEN if math.isnan(phi) else _lift_at(model, ws, phi, out)
    vel, P = ws.vel, ws.pP
    if st != OPEN:
        for i in range(n):
            e = ws.arms[i]
            if vel[2] + vel[3] * e[1] - vel[4] * e[0] < -SEPARATION_SLACK * abs(P[2]):
                st = OPEN
                break
    if st == OPEN:
        vel[:] = ws.free
        return OUTSIDE
    return st


#: A rim point next to the lift's point separates if its normal velocity is at least ``-SEPARATION_SLACK`` times the
#: lift's normal impulse (round-off: the lift's point may lie between two rim points or on one of them).
SEPARATION_SLACK = 1e-12


__all__ = ["flat_base", "lift_about", "lowest_moving"]
