"""The cylinder's geometry (numba): the rotation and inertia in the floor frame, the rim's points, the lowest of
them, the tilt and twist. The body frame has its ``z`` along the cylinder's axis and its origin at the centre of
mass; the rim point at body angle ``phi`` sits at ``(r cos phi, r sin phi, -h)``."""

from __future__ import annotations

import math

from opsrock.solvers.jitable import jitable


@jitable
def rotation(s, Q):
    """The rotation matrix (body to floor) of the state's quaternion ``s[3:7]`` into ``Q`` (3 x 3)."""
    w, x, y, z = s[3], s[4], s[5], s[6]
    Q[0, 0], Q[0, 1], Q[0, 2] = 1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)
    Q[1, 0], Q[1, 1], Q[1, 2] = 2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)
    Q[2, 0], Q[2, 1], Q[2, 2] = 2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)


@jitable
def inertia(Q, design, Iw, Iinv):
    """The floor-frame inertia ``Iw = Q diag(i_h, i_h, i_z) Q^T`` and its inverse ``Iinv`` (m², per unit mass):
    axisymmetric, ``i_h E + (i_z - i_h) a a^T`` with ``a`` the axis."""
    ih, iz = design.i_h, design.i_z
    for i in range(3):
        for j in range(3):
            e = 1.0 if i == j else 0.0
            aa = Q[i, 2] * Q[j, 2]
            Iw[i, j] = ih * e + (iz - ih) * aa
            Iinv[i, j] = e / ih + (1.0 / iz - 1.0 / ih) * aa


@jitable
def rim_arm(Q, design, phi, arm):
    """The arm (floor frame, m) from the centre of mass to the rim point at body angle ``phi`` (rad), into the
    3-vector ``arm``."""
    cx, cy, cz = design.r * math.cos(phi), design.r * math.sin(phi), -design.h
    for i in range(3):
        arm[i] = Q[i, 0] * cx + Q[i, 1] * cy + Q[i, 2] * cz


@jitable
def lean(Q):
    """``sin`` of the tilt: the horizontal length of the axis (dimensionless)."""
    return math.hypot(Q[0, 2], Q[1, 2])


@jitable
def lowest_angle(Q, fx, fy):
    """Body angle (rad) of the lowest rim point; for a level base (the axis vertical to round-off) the rim point
    towards the floor-frame direction ``(fx, fy)`` (the way the floor's load pushes the centre of mass), or body
    angle 0 without one. The lowest point of ``Q (r cos phi, r sin phi, -h)`` has ``(cos phi, sin phi)`` along
    ``-(Q_20, Q_21)``."""
    q0, q1 = Q[2, 0], Q[2, 1]
    if math.hypot(q0, q1) > 1e-300:
        return math.atan2(-q1, -q0)
    bx, by = Q[0, 0] * fx + Q[1, 0] * fy, Q[0, 1] * fx + Q[1, 1] * fy
    return math.atan2(by, bx) if (bx != 0.0 or by != 0.0) else 0.0


@jitable
def tilt(s):
    """The tilt (rad, angle of the axis from the vertical) and the axis's horizontal components ``(l_x, l_y)``."""
    w, x, y, z = s[3], s[4], s[5], s[6]
    lx, ly = 2.0 * (x * z + w * y), 2.0 * (y * z - w * x)
    lz = 1.0 - 2.0 * (x * x + y * y)
    return math.atan2(math.hypot(lx, ly), lz), lx, ly


@jitable
def twist(s):
    """Rotation about the vertical (rad): the swing-twist decomposition's twist, ``2 atan2(q_z, q_w)`` in
    ``(-pi, pi]``."""
    t = 2.0 * math.atan2(s[6], s[3])
    if t > math.pi:
        t -= 2.0 * math.pi
    elif t <= -math.pi:
        t += 2.0 * math.pi
    return t


@jitable
def base_centre(s, h):
    """Horizontal position ``(x, y)`` of the base's centre (m, floor frame)."""
    w, x, y, z = s[3], s[4], s[5], s[6]
    return s[0] - h * 2.0 * (x * z + w * y), s[1] - h * 2.0 * (y * z - w * x)


__all__ = ["base_centre", "inertia", "lean", "lowest_angle", "rim_arm", "rotation", "tilt", "twist"]
