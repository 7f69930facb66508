"""Geometry and inertia of the box in a state (numba): the rotation, the floor-frame inertia, the corners' arms, the
Delassus blocks, the quaternion's step, tilt and twist. Units and frames as in :mod:`opsrock.solvers.rigid3d.kernel`
(SI, per unit mass).
"""

from __future__ import annotations

import math


from opsrock.solvers.jitable import jitable
from opsrock.solvers.rigid3d import pivot as PV
from opsrock.solvers.rigid3d.constants import (CORNER_SX, CORNER_SY)


@jitable
def _rotmat(s, Q):
    """Rotation matrix ``Q`` (body to floor) of the unit quaternion ``s[3:7]``."""
    PV.quat_matrix(s, 3, Q)


@jitable
def _inv_inertia(Q, ib, Iinv, Iw):
    """Inverse inertia ``Q I_b^-1 Q^T`` and inertia ``Q I_b Q^T`` in the floor frame (per unit mass; both
    symmetric)."""
    v0, v1, v2 = 1.0 / ib[0], 1.0 / ib[1], 1.0 / ib[2]
    for i in range(3):
        for j in range(i, 3):
            q0, q1, q2 = Q[i, 0] * Q[j, 0], Q[i, 1] * Q[j, 1], Q[i, 2] * Q[j, 2]
            Iinv[i, j] = Iinv[j, i] = q0 * v0 + q1 * v1 + q2 * v2
            Iw[i, j] = Iw[j, i] = q0 * ib[0] + q1 * ib[1] + q2 * ib[2]


@jitable
def _delassus(r, Iinv, W):
    """``W = 1 - S I^-1 S`` of one corner at ``r`` from the centre of mass (its own 3 x 3 block): ``-S I^-1 S
    e_j = r x (I^-1 (r x e_j))``."""
    r0, r1, r2 = r[0], r[1], r[2]
    for j in range(3):
        # c = r x e_j
        c0 = 0.0 if j == 0 else (r2 if j == 1 else -r1)
        c1 = -r2 if j == 0 else (0.0 if j == 1 else r0)
        c2 = r1 if j == 0 else (-r0 if j == 1 else 0.0)
        t0 = Iinv[0, 0] * c0 + Iinv[0, 1] * c1 + Iinv[0, 2] * c2
        t1 = Iinv[1, 0] * c0 + Iinv[1, 1] * c1 + Iinv[1, 2] * c2
        t2 = Iinv[2, 0] * c0 + Iinv[2, 1] * c1 + Iinv[2, 2] * c2
        # W e_j = e_j - (t x r) = e_j + r x t
        W[0, j] = (1.0 if j == 0 else 0.0) + r1 * t2 - r2 * t1
        W[1, j] = (1.0 if j == 1 else 0.0) + r2 * t0 - r0 * t2
        W[2, j] = (1.0 if j == 2 else 0.0) + r0 * t1 - r1 * t0


@jitable
def _delassus_pair(rk, rl, Iinv, W):
    """``W`` (3 x 3): the change of corner ``k``'s velocity (arm ``rk``) per unit impulse at corner ``l`` (arm
    ``rl``), ``W e = e + (I^-1 (rl x e)) x rk`` (:func:`_delassus` is ``rk = rl``, its sums in another order, kept
    so that results stay bitwise those of the validation runs)."""
    for j in range(3):
        c0 = 0.0 if j == 0 else (-rl[2] if j == 1 else rl[1])
        c1 = rl[2] if j == 0 else (0.0 if j == 1 else -rl[0])
        c2 = -rl[1] if j == 0 else (rl[0] if j == 1 else 0.0)
        t0 = Iinv[0, 0] * c0 + Iinv[0, 1] * c1 + Iinv[0, 2] * c2
        t1 = Iinv[1, 0] * c0 + Iinv[1, 1] * c1 + Iinv[1, 2] * c2
        t2 = Iinv[2, 0] * c0 + Iinv[2, 1] * c1 + Iinv[2, 2] * c2
        W[0, j] = (1.0 if j == 0 else 0.0) + t1 * rk[2] - t2 * rk[1]
        W[1, j] = (1.0 if j == 1 else 0.0) + t2 * rk[0] - t0 * rk[2]
        W[2, j] = (1.0 if j == 2 else 0.0) + t0 * rk[1] - t1 * rk[0]


@jitable
def _inv3(A, B):
    """``B = A^-1`` of a 3 x 3 matrix (the leading 3 x 3 blocks of ``A`` and ``B``); False if singular."""
    c00 = A[1, 1] * A[2, 2] - A[1, 2] * A[2, 1]
    c01 = A[1, 2] * A[2, 0] - A[1, 0] * A[2, 2]
    c02 = A[1, 0] * A[2, 1] - A[1, 1] * A[2, 0]
    det = A[0, 0] * c00 + A[0, 1] * c01 + A[0, 2] * c02
    if det == 0.0:
        return False
    B[0, 0] = c00 / det
    B[1, 0] = c01 / det
    B[2, 0] = c02 / det
    B[0, 1] = (A[0, 2] * A[2, 1] - A[0, 1] * A[2, 2]) / det
    B[1, 1] = (A[0, 0] * A[2, 2] - A[0, 2] * A[2, 0]) / det
    B[2, 1] = (A[0, 1] * A[2, 0] - A[0, 0] * A[2, 1]) / det
    B[0, 2] = (A[0, 1] * A[1, 2] - A[0, 2] * A[1, 1]) / det
    B[1, 2] = (A[0, 2] * A[1, 0] - A[0, 0] * A[1, 2]) / det
    B[2, 2] = (A[0, 0] * A[1, 1] - A[0, 1] * A[1, 0]) / det
    return True


@jitable
def _cross_add(a, b, Iinv, w, scale):
    """``w += scale I^-1 (a x b)``."""
    c0 = a[1] * b[2] - a[2] * b[1]
    c1 = a[2] * b[0] - a[0] * b[2]
    c2 = a[0] * b[1] - a[1] * b[0]
    for i in range(3):
        w[i] += scale * (Iinv[i, 0] * c0 + Iinv[i, 1] * c1 + Iinv[i, 2] * c2)


@jitable
def _quat_step(s, w0, w1, w2, dt, new):
    """``new[3:7] = exp(dt omega / 2) * s[3:7]``, renormalised (``omega`` in the floor frame)."""
    ang = math.sqrt(w0 * w0 + w1 * w1 + w2 * w2) * dt
    if ang > 0.0:
        sh = math.sin(0.5 * ang) / (ang / dt)
        a, bx, by, bz = math.cos(0.5 * ang), w0 * sh, w1 * sh, w2 * sh
    else:
        a, bx, by, bz = 1.0, 0.0, 0.0, 0.0
    w, x, y, z = s[3], s[4], s[5], s[6]
    nw = a * w - bx * x - by * y - bz * z
    nx = a * x + bx * w + by * z - bz * y
    ny = a * y - bx * z + by * w + bz * x
    nz = a * z + bx * y - by * x + bz * w
    n = math.sqrt(nw * nw + nx * nx + ny * ny + nz * nz)
    new[3], new[4], new[5], new[6] = nw / n, nx / n, ny / n, nz / n


@jitable
def _kinetic(s, Iw):
    """Kinetic energy per unit mass (J/kg) of state ``s`` with floor-frame inertia ``Iw``."""
    e = 0.5 * (s[7] * s[7] + s[8] * s[8] + s[9] * s[9])
    for i in range(3):
        for j in range(3):
            e += 0.5 * s[10 + i] * Iw[i, j] * s[10 + j]
    return e


@jitable
def _cm_outside(X, r):
    """True if the centre of mass's plan projection lies outside the convex hull of the four corners'
    projections (the plan projection of the base)."""
    inside_pos = True
    inside_neg = True
    for i in range(4):
        j = (i + 1) % 4
        ax, ay = X[0] + r[i, 0], X[1] + r[i, 1]
        bx, by = X[0] + r[j, 0], X[1] + r[j, 1]
        cr = (bx - ax) * (X[1] - ay) - (by - ay) * (X[0] - ax)
        if cr < 0.0:
            inside_pos = False
        if cr > 0.0:
            inside_neg = False
    return not (inside_pos or inside_neg)


@jitable
def _twist(s):
    """Rotation about the vertical (rad) of the swing-twist decomposition of the quaternion, in (-pi, pi]."""
    tw = 2.0 * math.atan2(s[6], s[3])
    if tw > math.pi:
        tw -= 2.0 * math.pi
    elif tw <= -math.pi:
        tw += 2.0 * math.pi
    return tw


@jitable
def _tilt(s, weak_y):
    """``(tilt, signed tilt, lean x, lean y)``: the tilt (rad) from the quaternion, ``2 asin(sqrt(q_x² + q_y²))``,
    signed by the lean of the body's vertical axis along the weaker axis (``x``, or ``y`` if ``weak_y``), and the
    plan components of that axis."""
    w, x, y, z = s[3], s[4], s[5], s[6]
    tilt = 2.0 * math.asin(min(1.0, math.sqrt(x * x + y * y)))
    lx, ly = 2.0 * (x * z + w * y), 2.0 * (y * z - w * x)
    lean = ly if weak_y else lx
    return tilt, (tilt if lean >= 0.0 else -tilt), lx, ly


@jitable
def _geometry(s, body, Q, Iinv, Iw, r):
    """Rotation, floor-frame inertia and the corners' arms ``r`` (4 x 3) of state ``s`` (``body``:
    :class:`.model.Body`)."""
    _arms(s, body, Q, r)
    _inv_inertia(Q, body.inertia, Iinv, Iw)


@jitable
def _arms(s, body, Q, r):
    """The corners' arms ``r`` (4 x 3, from the centre of mass, floor frame) of state ``s``; ``Q`` is workspace."""
    b, d, h = body.b, body.d, body.h
    _rotmat(s, Q)
    for i in range(4):
        cx, cy = CORNER_SX[i] * b, CORNER_SY[i] * d
        for a in range(3):
            r[i, a] = Q[a, 0] * cx + Q[a, 1] * cy - Q[a, 2] * h
