"""The contact problem of a Moreau-Jean step (numba): Newton's impact law with ``e_n = 0`` and isotropic Coulomb
friction at each rim point in contact (``0 <= u_N _|_ P_N >= 0``; stick inside the static cone ``|P_T| <= mu_s
P_N``, else slip with ``mu_k`` against the slip velocity), solved exactly at one point and by nonsmooth Gauss-Seidel
(Jean & Moreau) over several. Impulses and velocities per unit mass (m/s), floor frame: tangents ``x``, ``y``,
normal ``z``.

A single rim point (the cylinder tilted) is solved exactly: open if its free normal velocity separates; else stuck,
``P = -W^-1 q``, if that presses and lies in the static cone; else slipping, ``P = P_N (-mu_k t, 1)`` with the slip
direction ``t`` the fixed point of ``t = u_T / |u_T|`` (``u = W P + q``, ``u_N = 0``)."""

from __future__ import annotations

import math


from opsrock.solvers.cylinder3d.constants import (CONE_SLACK, DIRECTION_TOL, LIMIT_MU, OPEN, OUT_SLIP_UNCONVERGED,
                                                  SLIP, SLIP_ITERATIONS, STICK)
from opsrock.solvers.jitable import jitable


@jitable
def delassus(arm, Iinv, W):
    """``W = E + [r]^T Iinv [r]``: how an impulse at the point with arm ``arm`` changes that point's velocity
    (``Delta u = P + (Iinv (r x P)) x r``), into ``W`` (3 x 3)."""
    rx, ry, rz = arm[0], arm[1], arm[2]
    for j in range(3):
        cx, cy, cz = (0.0, rz, -ry) if j == 0 else ((-rz, 0.0, rx) if j == 1 else (ry, -rx, 0.0))  # r x e_j
        dx = Iinv[0, 0] * cx + Iinv[0, 1] * cy + Iinv[0, 2] * cz
        dy = Iinv[1, 0] * cx + Iinv[1, 1] * cy + Iinv[1, 2] * cz
        dz = Iinv[2, 0] * cx + Iinv[2, 1] * cy + Iinv[2, 2] * cz
        W[0, j] = (1.0 if j == 0 else 0.0) + dy * rz - dz * ry
        W[1, j] = (1.0 if j == 1 else 0.0) + dz * rx - dx * rz
        W[2, j] = (1.0 if j == 2 else 0.0) + dx * ry - dy * rx


@jitable
def stick(W, q, P):
    """``P = -W^-1 q`` by Cramer's rule (``W`` symmetric positive definite)."""
    a, b, c = W[0, 0], W[0, 1], W[0, 2]
    d, e, f = W[1, 0], W[1, 1], W[1, 2]
    g, h, k = W[2, 0], W[2, 1], W[2, 2]
    A, B, C = e * k - f * h, f * g - d * k, d * h - e * g
    det = a * A + b * B + c * C
    P[0] = -(A * q[0] + (c * h - b * k) * q[1] + (b * f - c * e) * q[2]) / det
    P[1] = -(B * q[0] + (a * k - c * g) * q[1] + (c * d - a * f) * q[2]) / det
    P[2] = -(C * q[0] + (b * g - a * h) * q[1] + (a * e - b * d) * q[2]) / det


@jitable
def _slip(W, q, mu, P):
    """Slip with ``mu`` in the direction of the fixed point ``t = u_T / |u_T|``, started from the stuck impulse's
    friction (in ``P``, reversed) or the free slip velocity. Returns True if the direction settled."""
    tx, ty = -P[0], -P[1]
    n = math.hypot(tx, ty)
    if n == 0.0:
        tx, ty, n = q[0], q[1], math.hypot(q[0], q[1])
    tx, ty = (tx / n, ty / n) if n > 0.0 else (1.0, 0.0)
    pn = 0.0
    for _ in range(SLIP_ITERATIONS):
        den = W[2, 2] - mu * (W[2, 0] * tx + W[2, 1] * ty)
        pn = max(-q[2] / den, 0.0) if den > 0.0 else 0.0
        ux = q[0] + pn * (W[0, 2] - mu * (W[0, 0] * tx + W[0, 1] * ty))
        uy = q[1] + pn * (W[1, 2] - mu * (W[1, 0] * tx + W[1, 1] * ty))
        un = math.hypot(ux, uy)
        if un == 0.0:
            break
        nx, ny = ux / un, uy / un
        done = abs(nx - tx) + abs(ny - ty) < DIRECTION_TOL
        tx, ty = nx, ny
        if done:
            P[0], P[1], P[2] = -mu * pn * tx, -mu * pn * ty, pn
            return True
    P[0], P[1], P[2] = -mu * pn * tx, -mu * pn * ty, pn
    return False


@jitable
def local(W, q, friction, P, out, ring):
    """One rim point's exact Coulomb problem ``u = W P + q`` into ``P``; returns ``OPEN``, ``STICK`` or ``SLIP``.
    With infinite friction a point that would need a pulling impulse to stick slides in the limit ``LIMIT_MU`` when
    it is the only point (the limit's impulse is finite); one of the flat base's ``ring`` of points is left open
    instead (its limit impulse is unbounded where the slip runs across its arm, and Gauss-Seidel diverged on it):
    the others carry the load."""
    if q[2] >= 0.0:
        P[0], P[1], P[2] = 0.0, 0.0, 0.0
        return OPEN
    stick(W, q, P)
    if P[2] > 0.0 and (friction.infinite or math.hypot(P[0], P[1]) <= friction.mu_s * P[2] * (1.0 + CONE_SLACK)):
        return STICK
    if friction.infinite and ring:
        P[0], P[1], P[2] = 0.0, 0.0, 0.0
        return OPEN
    mu = LIMIT_MU if friction.infinite else friction.mu_k
    if not _slip(W, q, mu, P):
        out[OUT_SLIP_UNCONVERGED] += 1.0
    return SLIP


@jitable
def nsgs(ws, n, friction, solver, scale, out):
    """Nonsmooth Gauss-Seidel over the ``n`` rim points of ``ws.arms`` (their blocks ``ws.W``), from the impulses
    ``ws.P`` already applied to ``ws.vel``: each point's exact local problem in turn, the velocity updated after
    each. Returns the sweeps taken (``solver.max_sweeps + 1``: not converged to ``solver.tol * scale``) and the
    number of slipping points. One point is exact in one sweep."""
    vel, Iinv, tmp, q = ws.vel, ws.Iinv, ws.tmp, ws.q
    for sweep in range(solver.max_sweeps):
        change, slipping = 0.0, 0
        for i in range(n):
            a, Wi, Pi = ws.arms[i], ws.W[i], ws.P[i]
            u0 = vel[0] + vel[4] * a[2] - vel[5] * a[1]
            u1 = vel[1] + vel[5] * a[0] - vel[3] * a[2]
            u2 = vel[2] + vel[3] * a[1] - vel[4] * a[0]
            for c in range(3):
                q[c] = (u0 if c == 0 else (u1 if c == 1 else u2)) - (Wi[c, 0] * Pi[0] + Wi[c, 1] * Pi[1]
                                                                      + Wi[c, 2] * Pi[2])
            if local(Wi, q, friction, tmp, out, n > 1) == SLIP:
                slipping += 1
            d0, d1, d2 = tmp[0] - Pi[0], tmp[1] - Pi[1], tmp[2] - Pi[2]
            Pi[0], Pi[1], Pi[2] = tmp[0], tmp[1], tmp[2]
            apply_impulse(vel, Iinv, a, d0, d1, d2)
            change = max(change, abs(d0) + abs(d1) + abs(d2))
        if n == 1 or change <= solver.tol * scale:
            return sweep + 1, slipping
    return solver.max_sweeps + 1, slipping


@jitable
def apply_impulse(vel, Iinv, a, p0, p1, p2):
    """Add the impulse ``(p0, p1, p2)`` at the arm ``a`` to the velocity ``vel`` (``V``, ``omega``)."""
    c0, c1, c2 = a[1] * p2 - a[2] * p1, a[2] * p0 - a[0] * p2, a[0] * p1 - a[1] * p0
    vel[0] += p0
    vel[1] += p1
    vel[2] += p2
    for i in range(3):
        vel[3 + i] += Iinv[i, 0] * c0 + Iinv[i, 1] * c1 + Iinv[i, 2] * c2


__all__ = ["apply_impulse", "delassus", "local", "nsgs", "stick"]
