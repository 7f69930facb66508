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

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers import status as ST
from opsrock.solvers.rigid3d import pivot as PV
from opsrock.solvers.rigid3d.workspace import (EVEC_P6, EVEC_Q, EVEC_U, EVEC_Y, VEC_OM, VEC_PN, VEC_V, VEC_VF, VEC_Y6,
                                              make_workspace)

# --- status codes: the shared ones (:mod:`opsrock.solvers.status`) ------------------------------------
STATUS_OK = ST.OK
STATUS_NONFINITE = ST.NONFINITE
STATUS_MAX_STEPS = ST.MAX_STEPS
STATUS_TAIL = ST.MAX_FREE_TIME
#: The contact solver (NSGS) did not converge in ``nsgs_fail_steps`` consecutive steps.
STATUS_CONTACT = ST.NO_CONTACT_SOLUTION

# --- contact modes, indices into opsrock.result.MODES ----------------------------------------------
MODE_REST = 0
MODE_SLIDE = 1
MODE_ROCK = 2
MODE_SLIDE_ROCK = 3
MODE_FLIGHT = 4

# --- forcing forms ---------------------------------------------------------------------------------
FORCING_STEPWISE = 0
FORCING_LINEAR = PV.FORCING_LINEAR

# --- history columns --------------------------------------------------------------------------------
H_T, H_THETA, H_THETA_DOT = 0, 1, 2
H_ROT = 3  # rotation vector, 3 columns
H_POS = 6  # CM displacement from rest, 3 columns
H_TWIST = 9
H_SLIDE = 10  # base centre's horizontal displacement, 2 columns
H_DOWN = 12
H_SIZE = 13

# --- layout of the kernel's output vector: the shared slots, then this kernel's own -----------------
OUT_STATUS, OUT_THETA_MAX, OUT_OVERTURNED, OUT_ROCKED = ST.OUT_STATUS, ST.OUT_THETA_MAX, ST.OUT_OVERTURNED, ST.OUT_ROCKED
OUT_IMPACTS, OUT_STEPS, OUT_N_HIST, OUT_EVENT_TIME = ST.OUT_IMPACTS, ST.OUT_STEPS, ST.OUT_N_HIST, ST.OUT_EVENT_TIME
OUT_FIRST_MODE = ST.OUT_COMMON
OUT_TIME_SLIDING = ST.OUT_COMMON + 1
OUT_TIME_ROCKING = ST.OUT_COMMON + 2
OUT_TIME_EDGE = ST.OUT_COMMON + 3
OUT_TIME_CORNER = ST.OUT_COMMON + 4
OUT_TIME_FLIGHT = ST.OUT_COMMON + 5
OUT_SLIDE_MAX = ST.OUT_COMMON + 6
OUT_TWIST_MAX = ST.OUT_COMMON + 7
OUT_INPUT_WORK = ST.OUT_COMMON + 8
OUT_FRICTION_WORK = ST.OUT_COMMON + 9
OUT_IMPACT_LOSS = ST.OUT_COMMON + 10
OUT_NSGS_FAILED = ST.OUT_COMMON + 11  # steps whose NSGS did not converge
OUT_NSGS_SWEEPS = ST.OUT_COMMON + 12  # sweeps over all contact solves
OUT_NSGS_MAX = ST.OUT_COMMON + 13  # most sweeps in one step
OUT_MAX_PENETRATION = ST.OUT_COMMON + 14
OUT_TIME = ST.OUT_COMMON + 15
OUT_REST_STEPS = ST.OUT_COMMON + 16  # steps taken by the rest skip
OUT_OVER_KIND = ST.OUT_COMMON + 17  # 1: over an edge, 2: over a corner
OUT_OVER_DIR = ST.OUT_COMMON + 18  # direction of overturning (rad, floor frame)
OUT_LIMIT_STEPS = ST.OUT_COMMON + 19  # local solves that met the infinite-friction limit (P_N < 0 to stick)
OUT_CONTACT_STEPS = ST.OUT_COMMON + 20  # steps that solved a contact problem
OUT_STATE = ST.OUT_COMMON + 21  # final state, 13 slots
OUT_STICK_STEPS = ST.OUT_COMMON + 34  # steps solved by the closed-form stick (_stick_all)
OUT_SLIDE_STEPS = ST.OUT_COMMON + 35  # steps solved by the closed-form flat slide (_slide_flat)
OUT_SMOOTH_STEPS = ST.OUT_COMMON + 36  # Runge-Kutta steps about stuck corners kept (:mod:`.pivot`)
OUT_SMOOTH_SPAN = ST.OUT_COMMON + 37  # Moreau-Jean steps those spanned
OUT_SMOOTH_TRIED = ST.OUT_COMMON + 38  # Runge-Kutta steps tried (kept or halved)
OUT_PEAK_STOP = ST.OUT_COMMON + 39  # 1.0: the run ended by the tail rule "peak"
OUT_NSGS_LOOSE = ST.OUT_COMMON + 40  # steps whose NSGS met only the looser tolerance (:func:`_solve_contacts`)
OUT_NSGS_EXTRA = ST.OUT_COMMON + 41  # the sweeps those took beyond nsgs_max_sweeps
OUT_COARSE_STEPS = ST.OUT_COMMON + 42  # coarse Moreau-Jean steps of a block sliding flat (_coarse_slide)
OUT_COARSE_SPAN = ST.OUT_COMMON + 43  # Moreau-Jean steps those spanned
OUT_EDGE_SLIP = ST.OUT_COMMON + 44  # steps solved by the closed-form slip on two corners (_edge_slip)
OUT_SLIP_STEPS = ST.OUT_COMMON + 45  # Runge-Kutta steps on slipping corners kept (_smooth_slip)
OUT_SLIP_SPAN = ST.OUT_COMMON + 46  # Moreau-Jean steps those spanned
OUT_SLIP_TRIED = ST.OUT_COMMON + 47  # Runge-Kutta steps on slipping corners tried (kept or halved)
OUT_SETTLED = ST.OUT_COMMON + 48  # times a block at rest on three corners was set down on four (_settle)
OUT_SETTLE_GAP = ST.OUT_COMMON + 49  # the largest gap (m) of a fourth corner so set down
OUT_SIZE = ST.OUT_COMMON + 50

#: Speed of the base (m/s) below which the tail rule "peak" may end a run: a block on its base sliding at
#: 1 mm/s under friction ``mu`` stops within ``(1e-3)² / (2 mu g)``, 5e-8/mu m.
PEAK_BASE_SPEED = 1e-3

#: Friction coefficient standing for infinity in the limit solve of :func:`_local` (its relative error 1/LIMIT_MU).
LIMIT_MU = 1e6

#: Normal impulses of the closed-form flat slide down to ``-FLAT_ROUNDOFF`` times their sum count as zero (round-off
#: of its least-squares solve): a block with ``mu_k = b/h`` slides with its trailing corners exactly unloaded.
FLAT_ROUNDOFF = 1e-10

#: The status pairs :func:`_edge_slip` tries, in order (0 stick, 1 slip, 2 open).
EDGE_STATUSES = np.array([[0, 1], [1, 0], [1, 1], [2, 1], [1, 2]], dtype=np.int64)

#: A smooth step on slipping corners (:func:`_smooth_slip`) takes Runge-Kutta sub-steps no longer than
#: ``1/SLIP_TURN`` of each slipping corner's speed over its tangential acceleration: its slip direction turns by at
#: most about ``1/SLIP_TURN`` rad a sub-step, and it cannot stop or reverse inside one.
SLIP_TURN = 20.0

#: The shortest Runge-Kutta sub-step on slipping corners, in Moreau-Jean steps (shorter: the Moreau-Jean steps
#: go on).
SLIP_MIN_SUB = 2.0

#: A block at rest on three stuck corners whose fourth hangs above the floor by at most ``SETTLE_GAP`` times the
#: contact gap (the Moreau-Jean steps' drift; ``Limits.lift_gap``) is set down level on all four (:func:`_settle`).
SETTLE_GAP = 10.0

# --- tolerances of the iterations and tests (dimensionless unless stated) ------------------------------------
#: Relative change of the multiplier at which the secular equation's Newton iteration stops (:func:`_slip_direction`).
SECULAR_TOL = 1e-15
#: Residual angle (rad) and angle step (rad) at which Newton on one corner's slip angle stops (:func:`_slip_newton`).
SLIP_ANGLE_TOL, SLIP_STEP_TOL = 1e-13, 1e-14
#: Change of a slip direction's components at which the fixed point of :func:`_local` stops.
DIRECTION_TOL = 1e-11
#: A closed form's friction impulse lies in the static cone up to this relative round-off.
CONE_SLACK = 1e-12
#: Gaussian elimination refuses a pivot below this fraction of the matrix's largest entry (:func:`_solve_n`).
PIVOT_TOL = 1e-13
#: Newton's and the fixed points' stopping tolerance in :func:`_flat_newton` (relative to the velocities' scale)
#: and :func:`_edge_try` (the directions' components and angles, rad).
NEWTON_TOL = 1e-12
#: Forward-difference step of the Jacobians of :func:`_flat_newton` (relative) and :func:`_edge_try` (rad).
FD_STEP = 1e-7
#: A flat-sliding corner's velocity must lie along its slip direction to within this (``1 - cos``).
ALIGN_TOL = 1e-9
#: Extra margin (m) by which a smooth step on slipping corners sets its contact corners onto the floor.
SETDOWN_MARGIN = 1e-13

#: Corner signs ``(sx, sy)``: corners 0..3 at (+b, +d), (-b, +d), (-b, -d), (+b, -d) (counter-clockwise).
CORNER_SX = np.array([1.0, -1.0, -1.0, 1.0])
CORNER_SY = np.array([1.0, 1.0, -1.0, -1.0])

#: Non-literal constants for counters and flags passed to compiled functions: numba types a counter that starts
#: at ``0`` (or an argument written ``True``) as a literal while it infers a caller's types, and compiles the
#: callee, with everything it calls, once more for that literal (a fifth of the cold compile, measured).
ZERO, ONE, TWO, FOUR, SIX = np.int64(0), np.int64(1), np.int64(2), np.int64(4), np.int64(6)
REST_MODE = np.int64(MODE_REST)
NO, YES = np.bool_(False), np.bool_(True)


@numba.njit(cache=True)
def _floor(floor, k, theta_mj):
    """Floor accelerations ``(a_x, a_y, a_v)`` (m/s²) of ``floor`` (:class:`.model.Floor`) at the evaluation time
    ``(k + theta_mj) dt`` of step ``k``."""
    ax, ay, av, sub = floor.ax, floor.ay, floor.av, floor.sub
    if k >= floor.n_exc:
        return 0.0, 0.0, floor.tail_av
    if floor.form == FORCING_STEPWISE:
        return ax[k], ay[k], av[k]
    j = k // sub
    f = (k - j * sub + theta_mj) / sub
    return (ax[j] + f * (ax[j + 1] - ax[j]), ay[j] + f * (ay[j + 1] - ay[j]), av[j] + f * (av[j + 1] - av[j]))


@numba.njit(cache=True)
def _rotmat(s, Q):
    """Rotation matrix ``Q`` (body to floor) of the unit quaternion ``s[3:7]``."""
    PV.quat_matrix(s, 3, Q)


@numba.njit(cache=True)
def _inv_inertia(Q, ib, Iinv, Iw):
    """Inverse inertia ``Q I_b^-1 Q^T`` and inertia ``Q I_b Q^T`` in the floor frame (per unit mass; both
    symmetric)."""
    v0, v1, v2 = 1.0 / ib[0], 1.0 / ib[1], 1.0 / ib[2]
    for i in range(3):
        for j in range(i, 3):
            q0, q1, q2 = Q[i, 0] * Q[j, 0], Q[i, 1] * Q[j, 1], Q[i, 2] * Q[j, 2]
            Iinv[i, j] = Iinv[j, i] = q0 * v0 + q1 * v1 + q2 * v2
            Iw[i, j] = Iw[j, i] = q0 * ib[0] + q1 * ib[1] + q2 * ib[2]


@numba.njit(cache=True)
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


@numba.njit(cache=True)
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


@numba.njit(cache=True)
def _inv3(A, B):
    """``B = A^-1`` of a 3 x 3 matrix; False if singular."""
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


@numba.njit(cache=True)
def _slip_direction(a, c, e, r0, r1):
    """Unit ``s`` and ``lam >= 0`` with ``(lam 1 + A) s = r``, ``A = [[a, c], [c, e]]`` symmetric positive
    definite: the slip direction of a contact whose tangential velocity is ``r - A s`` (the trust-region
    "secular" equation ``|s(lam)| = 1``, by Newton on ``1 - 1 / |s(lam)|``, which is concave and increasing, so
    the iteration from ``lam = 0`` rises monotonically to the root). Returns ``(s0, s1)``."""
    # eigen-decomposition of A
    tr = 0.5 * (a + e)
    df = 0.5 * (a - e)
    rad = math.sqrt(df * df + c * c)
    l1, l2 = tr + rad, tr - rad
    if rad > 0.0:
        if df >= 0.0:
            cth, sth = df + rad, c
        else:
            cth, sth = c, rad - df
        nn = math.hypot(cth, sth)
        cth, sth = cth / nn, sth / nn
    else:
        cth, sth = 1.0, 0.0
    # coordinates of r in the eigenbasis (first eigenvector (cth, sth) for l1)
    p1 = cth * r0 + sth * r1
    p2 = -sth * r0 + cth * r1
    lam = 0.0
    for _ in range(60):
        s1 = p1 / (lam + l1)
        s2 = p2 / (lam + l2)
        ns = math.sqrt(s1 * s1 + s2 * s2)
        if ns == 0.0:
            break
        if lam == 0.0 and ns <= 1.0:
            break
        dns = -(s1 * s1 / (lam + l1) + s2 * s2 / (lam + l2)) / ns
        step = (1.0 - 1.0 / ns) / (dns / (ns * ns))
        lam_new = lam - step
        if lam_new < 0.0:
            lam_new = 0.0
        if abs(lam_new - lam) <= SECULAR_TOL * (lam + l1):
            lam = lam_new
            break
        lam = lam_new
    s1 = p1 / (lam + l1)
    s2 = p2 / (lam + l2)
    ns = math.sqrt(s1 * s1 + s2 * s2)
    if ns == 0.0:
        return 1.0, 0.0
    s1, s2 = s1 / ns, s2 / ns
    return cth * s1 - sth * s2, sth * s1 + cth * s2


@numba.njit(cache=True)
def _slip_newton(W, q, mu_k, s0, s1):
    """The slip direction ``s`` of one corner slipping with ``mu_k`` (:func:`_local`) by Newton's method on its angle
    ``phi`` from the warm start ``s``: for a given ``s`` the normal impulse ``N = -q_z / (W_zz - mu_k W_zt . s)``
    makes ``u_z = 0``, the friction impulse is ``-mu_k N s``, and the residual is the angle from ``s`` to the
    corner's tangential velocity ``u_t`` (zero where the friction opposes the slip; the antiparallel root is
    excluded), differentiated exactly. Returns ``(converged, s_x, s_y)``; not converged (the fixed point of
    :func:`_local` then takes over) if ``W_zz - mu_k W_zt . s`` leaves the positive or 30 steps do not do."""
    phi = math.atan2(s1, s0)
    for _ in range(30):
        c0, c1 = math.cos(phi), math.sin(phi)
        den = W[2, 2] - mu_k * (W[2, 0] * c0 + W[2, 1] * c1)
        if den <= 0.0:
            return False, s0, s1
        pn = -q[2] / den
        p0, p1 = -mu_k * pn * c0, -mu_k * pn * c1
        u0 = q[0] + W[0, 0] * p0 + W[0, 1] * p1 + W[0, 2] * pn
        u1 = q[1] + W[1, 0] * p0 + W[1, 1] * p1 + W[1, 2] * pn
        cr = c0 * u1 - c1 * u0
        dot = c0 * u0 + c1 * u1
        res = math.atan2(cr, dot)
        if abs(res) <= SLIP_ANGLE_TOL:
            return True, c0, c1
        dden = -mu_k * (-W[2, 0] * c1 + W[2, 1] * c0)
        dpn = -pn * dden / den
        dp0 = -mu_k * (dpn * c0 - pn * c1)
        dp1 = -mu_k * (dpn * c1 + pn * c0)
        du0 = W[0, 0] * dp0 + W[0, 1] * dp1 + W[0, 2] * dpn
        du1 = W[1, 0] * dp0 + W[1, 1] * dp1 + W[1, 2] * dpn
        dcr = -dot + c0 * du1 - c1 * du0
        ddot = cr + c0 * du0 + c1 * du1
        nrm = cr * cr + dot * dot
        if nrm == 0.0:
            return False, s0, s1
        dres = (dot * dcr - cr * ddot) / nrm
        if dres == 0.0:
            return False, s0, s1
        step = -res / dres
        step = max(-0.5, min(0.5, step))
        phi += step
        if abs(step) <= SLIP_STEP_TOL:
            return True, math.cos(phi), math.sin(phi)
    return False, s0, s1


@numba.njit(cache=True)
def _local(W, Winv, q, mu_s, mu_k, stick_only, Pw, P):
    """One corner's impulse ``P`` (tangential x, y, normal z) making ``u = q + W P`` obey ``0 <= u_z _|_ P_z >= 0``
    (Newton, ``e_n = 0``) and Coulomb's law: open if the corner does not approach; else stick (``u = 0``) if that
    impulse lies in the static cone ``|P_t| <= mu_s P_z``; else slip with ``|P_t| = mu_k P_z`` against the slip
    velocity (maximal dissipation), the slip direction iterated from that of ``Pw`` (the corner's current
    impulse). Returns 0 solved, 1 solved by the infinite-friction limit (sticking would need a pulling impulse:
    the slip solution with ``mu_k = LIMIT_MU``, whose normal impulse tends to 0 with a finite friction impulse
    and ``u_z = 0``, as moreau_jean's limit status), 2 no slip solution (``W_zz - mu_k W_zt . s <= 0``; the
    corner is then left open)."""
    if q[2] >= 0.0:
        P[0], P[1], P[2] = 0.0, 0.0, 0.0
        return 0
    for i in range(3):
        P[i] = -(Winv[i, 0] * q[0] + Winv[i, 1] * q[1] + Winv[i, 2] * q[2])
    if P[2] >= 0.0 and (stick_only or math.hypot(P[0], P[1]) <= mu_s * P[2] * (1.0 + CONE_SLACK)):
        return 0
    limit = stick_only
    if limit:  # the infinite-friction limit of slip: mu_k -> infinity, P_N -> 0 with a finite friction impulse
        mu_k = LIMIT_MU
    # slip: alternate the normal impulse (u_z = 0 for the slip direction s) and the slip direction (secular),
    # from the direction of the previous friction impulse (warm start) or of the velocity with u_z = 0
    nu = math.hypot(Pw[0], Pw[1])
    if nu > 0.0:
        s0, s1 = -Pw[0] / nu, -Pw[1] / nu
    else:
        ut0 = q[0] - W[0, 2] * q[2] / W[2, 2]
        ut1 = q[1] - W[1, 2] * q[2] / W[2, 2]
        nu = math.hypot(ut0, ut1)
        if nu > 0.0:
            s0, s1 = ut0 / nu, ut1 / nu
        else:
            nu = math.hypot(P[0], P[1])
            s0, s1 = (-P[0] / nu, -P[1] / nu) if nu > 0.0 else (1.0, 0.0)
    ok, n0, n1 = _slip_newton(W, q, mu_k, s0, s1)
    if ok:
        s0, s1 = n0, n1
    pn = 0.0
    for _ in range(0 if ok else 30):
        den = W[2, 2] - mu_k * (W[2, 0] * s0 + W[2, 1] * s1)
        if den <= 0.0:
            P[0], P[1], P[2] = 0.0, 0.0, 0.0
            return 2
        pn = -q[2] / den
        r0 = q[0] + pn * W[0, 2]
        r1 = q[1] + pn * W[1, 2]
        c = mu_k * pn
        if c <= 0.0:
            break
        n0, n1 = _slip_direction(c * W[0, 0], c * W[0, 1], c * W[1, 1], r0, r1)
        moved = abs(n0 - s0) + abs(n1 - s1)
        s0, s1 = n0, n1
        if moved < DIRECTION_TOL:
            break
    den = W[2, 2] - mu_k * (W[2, 0] * s0 + W[2, 1] * s1)
    pn = -q[2] / den
    if den <= 0.0:
        P[0], P[1], P[2] = 0.0, 0.0, 0.0
        return 2
    P[0], P[1], P[2] = -mu_k * pn * s0, -mu_k * pn * s1, pn
    return 1 if limit else 0


@numba.njit(cache=True)
def _cross_add(a, b, Iinv, w, scale):
    """``w += scale I^-1 (a x b)``."""
    c0 = a[1] * b[2] - a[2] * b[1]
    c1 = a[2] * b[0] - a[0] * b[2]
    c2 = a[0] * b[1] - a[1] * b[0]
    for i in range(3):
        w[i] += scale * (Iinv[i, 0] * c0 + Iinv[i, 1] * c1 + Iinv[i, 2] * c2)


@numba.njit(cache=True)
def _nsgs(act, r, Wd, Wi, Iinv, V, Om, P, mu_s, mu_k, stick_only, tol, max_iter, q, Pn, out, single):
    """Nonsmooth Gauss-Seidel (Jean & Moreau) over the active corners: each corner's local problem solved
    exactly (:func:`_local`) with the others' impulses fixed, the body's velocity ``(V, Om)`` updated after each,
    sweeps until no impulse changes by more than ``tol`` (m/s). Warm-started from ``P`` (the previous step's
    impulses). Returns the number of sweeps (``max_iter + 1``: not converged); with a ``single`` active corner
    one sweep is exact."""
    for it in range(max_iter):
        change = 0.0
        for i in range(4):
            if not act[i]:
                continue
            ri = r[i]
            Pi = P[i]
            u0 = V[0] + Om[1] * ri[2] - Om[2] * ri[1]
            u1 = V[1] + Om[2] * ri[0] - Om[0] * ri[2]
            u2 = V[2] + Om[0] * ri[1] - Om[1] * ri[0]
            W = Wd[i]
            for a in range(3):
                ua = u0 if a == 0 else (u1 if a == 1 else u2)
                q[a] = ua - (W[a, 0] * Pi[0] + W[a, 1] * Pi[1] + W[a, 2] * Pi[2])
            code = _local(W, Wi[i], q, mu_s, mu_k, stick_only, Pi, Pn)
            if code == 1:
                out[OUT_LIMIT_STEPS] += 1.0
            d0, d1, d2 = Pn[0] - Pi[0], Pn[1] - Pi[1], Pn[2] - Pi[2]
            change = max(change, abs(d0), abs(d1), abs(d2))
            V[0] += d0
            V[1] += d1
            V[2] += d2
            Pn[0], Pn[1], Pn[2] = d0, d1, d2
            _cross_add(ri, Pn, Iinv, Om, 1.0)
            Pi[0] += d0
            Pi[1] += d1
            Pi[2] += d2
        if change <= tol or single:
            return it + 1
    return max_iter + 1


@numba.njit(cache=True)
def _solve_contacts(act, r, Wd, Wi, Iinv, V, Om, P, mu_s, mu_k, stick_only, tol, nsgs, q, Pn, out, single):
    """NSGS (:func:`_nsgs`) to ``tol`` in ``nsgs.max_sweeps`` sweeps; failing that, on for up to ``nsgs.extra_sweeps``
    sweeps more (at least one) to the looser ``tol * nsgs.loose_tol / nsgs.tol`` (a block at the stick-slip limit on three or four corners, whose
    impulses are statically indeterminate, makes Gauss-Seidel converge slowly, not fail), counted in
    ``OUT_NSGS_LOOSE``. Returns the sweeps (``nsgs.max_sweeps + 1``: not converged)."""
    max_iter = nsgs.max_sweeps
    sweeps = _nsgs(act, r, Wd, Wi, Iinv, V, Om, P, mu_s, mu_k, stick_only, tol, max_iter, q, Pn, out, single)
    if sweeps <= max_iter:
        return sweeps
    extra = max(1, nsgs.extra_sweeps)
    more = _nsgs(act, r, Wd, Wi, Iinv, V, Om, P, mu_s, mu_k, stick_only, tol * nsgs.loose_tol / nsgs.tol, extra,
                 q, Pn, out, single)
    if more > extra:
        return max_iter + 1
    out[OUT_NSGS_LOOSE] += 1.0
    out[OUT_NSGS_EXTRA] += more
    return max_iter


@numba.njit(cache=True)
def _solve6(A, y):
    """Solve ``A y_new = y`` in place (6 x 6, :func:`_solve_n`)."""
    return _solve_n(A, y, SIX)


@numba.njit(cache=True)
def _solve_n(A, y, n):
    """Solve ``A[:n, :n] y_new = y[:n]`` in place (Gaussian elimination with partial pivoting; ``A`` is
    overwritten); False if a pivot is below 1e-13 of the largest entry."""
    big = 0.0
    for i in range(n):
        for j in range(n):
            big = max(big, abs(A[i, j]))
    for col in range(n):
        piv = col
        for i in range(col + 1, n):
            if abs(A[i, col]) > abs(A[piv, col]):
                piv = i
        if abs(A[piv, col]) <= PIVOT_TOL * big:
            return False
        if piv != col:
            for j in range(n):
                A[col, j], A[piv, j] = A[piv, j], A[col, j]
            y[col], y[piv] = y[piv], y[col]
        for i in range(col + 1, n):
            f = A[i, col] / A[col, col]
            for j in range(col, n):
                A[i, j] -= f * A[col, j]
            y[i] -= f * y[col]
    for i in range(n - 1, -1, -1):
        acc = y[i]
        for j in range(i + 1, n):
            acc -= A[i, j] * y[j]
        y[i] = acc / A[i, i]
    return True


@numba.njit(cache=True)
def _shift_range(x, z, n):
    """The ``t`` nearest to 0 with ``x[:n] + t z[:n] >= 0`` (a statically indeterminate normal distribution made
    compressive along its free direction ``z``), and whether one exists."""
    lo, hi = -np.inf, np.inf
    for i in range(n):
        if z[i] > 0.0:
            lo = max(lo, -x[i] / z[i])
        elif z[i] < 0.0:
            hi = min(hi, -x[i] / z[i])
        elif x[i] < 0.0:
            return 0.0, False
    if lo > hi:
        return 0.0, False
    return min(max(0.0, lo), hi), True


@numba.njit(cache=True)
def _stick_flat(act, r, Iw, vf, P, B):
    """Impulses that stop a block standing on three or four corners of its level base: the total impulse
    ``-vf`` (per unit mass) and torque ``-I omega_f`` are fixed; with the corners in one plane (``r_z`` the
    same, ``rz``) the tangential impulses enter the horizontal torques through their total only, so the normal
    impulses are the least-norm solution of ``sum N = F_z``, ``sum N r_y = T_x + rz F_y``, ``sum N r_x = rz F_x
    - T_y``; the tangential impulses are then proportional to the normal ones, ``P_t,i = N_i (c + kappa z x
    (rho_i - rho_bar))`` (a translation and a twist about the centre of pressure ``rho_bar``), ``c`` and
    ``kappa`` from the total and the vertical torque. False if the normal impulses do not add up to a
    compressive total. On four corners a distribution with a pulling corner is moved along the free (alternating)
    direction to the nearest compressive one where there is one (the least-norm one is compressive only for a
    centre of pressure inside the base's inscribed diamond). ``B`` (6 x 6) is workspace."""
    F0, F1, F2 = -vf[0], -vf[1], -vf[2]
    T0 = -(Iw[0, 0] * vf[3] + Iw[0, 1] * vf[4] + Iw[0, 2] * vf[5])
    T1 = -(Iw[1, 0] * vf[3] + Iw[1, 1] * vf[4] + Iw[1, 2] * vf[5])
    T2 = -(Iw[2, 0] * vf[3] + Iw[2, 1] * vf[4] + Iw[2, 2] * vf[5])
    if F2 <= 0.0:
        return False
    rz = 0.0
    n = 0
    for i in range(4):
        if act[i]:
            rz += r[i, 2]
            n += 1
    rz /= n
    # B B^T (3 x 3, rows (1, r_y, r_x)) into B[0:3, 0:3], its inverse into B[3:6, 0:3]
    for a in range(3):
        for c in range(3):
            B[a, c] = 0.0
    for i in range(4):
        if act[i]:
            row = (1.0, r[i, 1], r[i, 0])
            for a in range(3):
                for c in range(3):
                    B[a, c] += row[a] * row[c]
    if not _inv3(B[0:3, 0:3], B[3:6, 0:3]):
        return False
    g0, g1, g2 = F2, T0 + rz * F1, rz * F0 - T1
    y0 = B[3, 0] * g0 + B[3, 1] * g1 + B[3, 2] * g2
    y1 = B[4, 0] * g0 + B[4, 1] * g1 + B[4, 2] * g2
    y2 = B[5, 0] * g0 + B[5, 1] * g1 + B[5, 2] * g2
    total = 0.0
    cx = 0.0
    cy = 0.0
    for i in range(4):
        if act[i]:
            P[i, 2] = y0 + y1 * r[i, 1] + y2 * r[i, 0]
            total += P[i, 2]
            cx += P[i, 2] * r[i, 0]
            cy += P[i, 2] * r[i, 1]
        else:
            P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
    if n == 4:  # the free direction of four corners of a rectangle: alternating (+, -, +, -)
        neg = False
        for i in range(4):
            neg = neg or P[i, 2] < 0.0
        if neg:
            for i in range(4):
                B[0, i] = P[i, 2]
                B[1, i] = 1.0 if i % 2 == 0 else -1.0
            t, ok = _shift_range(B[0], B[1], 4)
            if ok:
                total = 0.0
                cx = 0.0
                cy = 0.0
                for i in range(4):
                    P[i, 2] += t * B[1, i]
                    total += P[i, 2]
                    cx += P[i, 2] * r[i, 0]
                    cy += P[i, 2] * r[i, 1]
    if total <= 0.0:
        return False
    cx /= total
    cy /= total
    c0, c1 = F0 / total, F1 / total
    spread = 0.0
    for i in range(4):
        if act[i]:
            spread += P[i, 2] * ((r[i, 0] - cx) ** 2 + (r[i, 1] - cy) ** 2)
    kappa = (T2 - (cx * c1 - cy * c0) * total) / spread if spread > 0.0 else 0.0
    for i in range(4):
        if act[i]:
            P[i, 0] = P[i, 2] * (c0 - kappa * (r[i, 1] - cy))
            P[i, 1] = P[i, 2] * (c1 + kappa * (r[i, 0] - cx))
    return True


@numba.njit(cache=True)
def _first_two(act):
    """The first two active corners' indices (-1 where fewer)."""
    i1 = -1
    i2 = -1
    for i in range(4):
        if act[i]:
            if i1 < 0:
                i1 = i
            elif i2 < 0:
                i2 = i
    return i1, i2


@numba.njit(cache=True)
def _cone_interval(P, e0, e1, e2, x0, mu):
    """The values ``x`` of the component along the unit ``e`` for which the impulse ``P + (x - x0) e`` (``x0`` its
    present component along ``e``) lies in the static cone ``hypot(P_x, P_y) <= mu P_z``: ``(lo, hi)``, empty
    (``lo > hi``) if none."""
    b0, b1, b2 = P[0] - x0 * e0, P[1] - x0 * e1, P[2] - x0 * e2
    a = e0 * e0 + e1 * e1 - mu * mu * e2 * e2
    bc = b0 * e0 + b1 * e1 - mu * mu * b2 * e2
    cc = b0 * b0 + b1 * b1 - mu * mu * b2 * b2
    disc = bc * bc - a * cc
    if a <= 0.0 or disc < 0.0:
        return 1.0, -1.0
    w = math.sqrt(disc)
    return (-bc - w) / a, (-bc + w) / a


@numba.njit(cache=True)
def _edge_split(Pa, Pb, e0, e1, e2, ca, cb, xa, mu):
    """Corner ``a``'s share of the impulse along an edge ``e`` shared by two stuck corners (which may carry any split
    of it): the share nearest ``xa`` that keeps both impulses in the static cone, ``xa`` if none does. ``Pa``,
    ``Pb`` are the impulses, ``ca``, ``cb`` their components along ``e``."""
    la, ha = _cone_interval(Pa, e0, e1, e2, ca, mu)
    lb, hb = _cone_interval(Pb, e0, e1, e2, cb, mu)
    total = ca + cb
    lo, hi = max(la, total - hb), min(ha, total - lb)
    if lo > hi:
        return xa
    return min(max(xa, lo), hi)


@numba.njit(cache=True)
def _stick_all(act, n_act, r, Iw, vf, V, Om, P, mu_s, stick_only, A6, y6):
    """Try every active corner stuck, in closed form: with two corners the block may only turn about the line
    through them (the velocity closest to the free one in the kinetic metric, one freedom), with three or four
    it stops; the impulses are the least-norm ones that make that velocity change (no self-equilibrated
    friction "squeeze": the statically indeterminate part is left at zero), with the friction along an edge,
    and on three or four corners all of it, split in proportion to the normal impulses (:func:`_stick_flat`). Accepted, into ``V``, ``Om`` and
    ``P``, if every normal impulse is compressive and every tangential one lies in the static cone; else False
    (NSGS then solves the step). ``A6`` (6 x 6) and ``y6`` (6) are workspace."""
    i1, i2 = _first_two(act)
    if n_act == 2:
        ra, rb = r[i1], r[i2]
        L0, L1, L2 = ra[0] - rb[0], ra[1] - rb[1], ra[2] - rb[2]
        nl = math.sqrt(L0 * L0 + L1 * L1 + L2 * L2)
        e0, e1, e2 = L0 / nl, L1 / nl, L2 / nl
        z0, z1, z2 = ra[1] * e2 - ra[2] * e1, ra[2] * e0 - ra[0] * e2, ra[0] * e1 - ra[1] * e0  # r_a x e
        Ie0 = Iw[0, 0] * e0 + Iw[0, 1] * e1 + Iw[0, 2] * e2
        Ie1 = Iw[1, 0] * e0 + Iw[1, 1] * e1 + Iw[1, 2] * e2
        Ie2 = Iw[2, 0] * e0 + Iw[2, 1] * e1 + Iw[2, 2] * e2
        num = z0 * vf[0] + z1 * vf[1] + z2 * vf[2] + Ie0 * vf[3] + Ie1 * vf[4] + Ie2 * vf[5]
        sc = num / (z0 * z0 + z1 * z1 + z2 * z2 + Ie0 * e0 + Ie1 * e1 + Ie2 * e2)
        V[0], V[1], V[2] = sc * z0, sc * z1, sc * z2
        Om[0], Om[1], Om[2] = sc * e0, sc * e1, sc * e2
        F0, F1, F2 = V[0] - vf[0], V[1] - vf[1], V[2] - vf[2]
        d0, d1, d2 = Om[0] - vf[3], Om[1] - vf[4], Om[2] - vf[5]
        T0 = Iw[0, 0] * d0 + Iw[0, 1] * d1 + Iw[0, 2] * d2
        T1 = Iw[1, 0] * d0 + Iw[1, 1] * d1 + Iw[1, 2] * d2
        T2 = Iw[2, 0] * d0 + Iw[2, 1] * d1 + Iw[2, 2] * d2
        m0, m1, m2 = 0.5 * (ra[0] + rb[0]), 0.5 * (ra[1] + rb[1]), 0.5 * (ra[2] + rb[2])
        T0 -= m1 * F2 - m2 * F1
        T1 -= m2 * F0 - m0 * F2
        T2 -= m0 * F1 - m1 * F0
        q = 1.0 / (nl * nl)
        D0, D1, D2 = (T1 * L2 - T2 * L1) * q, (T2 * L0 - T0 * L2) * q, (T0 * L1 - T1 * L0) * q
        for i in range(4):
            P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
        P[i1, 0], P[i1, 1], P[i1, 2] = 0.5 * F0 + D0, 0.5 * F1 + D1, 0.5 * F2 + D2
        P[i2, 0], P[i2, 1], P[i2, 2] = 0.5 * F0 - D0, 0.5 * F1 - D1, 0.5 * F2 - D2
        # the part along the edge is statically indeterminate (equal and opposite impulses along the line
        # through the two corners change neither the force nor the moment): split it in proportion to the
        # normal impulses, as on a level base, so that a lightly loaded corner is not asked for half of it
        n1, n2 = P[i1, 2], P[i2, 2]
        if n1 > 0.0 and n2 > 0.0:
            c1 = P[i1, 0] * e0 + P[i1, 1] * e1 + P[i1, 2] * e2
            c2 = P[i2, 0] * e0 + P[i2, 1] * e1 + P[i2, 2] * e2
            dl = (c1 + c2) * n1 / (n1 + n2) - c1
            if not stick_only:  # a split that keeps both in their static cones, if that one does not
                dl = _edge_split(P[i1], P[i2], e0, e1, e2, c1, c2, c1 + dl, mu_s) - c1
            P[i1, 0], P[i1, 1], P[i1, 2] = P[i1, 0] + dl * e0, P[i1, 1] + dl * e1, P[i1, 2] + dl * e2
            P[i2, 0], P[i2, 1], P[i2, 2] = P[i2, 0] - dl * e0, P[i2, 1] - dl * e1, P[i2, 2] - dl * e2
    else:  # three or four corners (a level base): the block stops
        if not _stick_flat(act, r, Iw, vf, P, A6):
            return False
        for a in range(3):
            V[a] = 0.0
            Om[a] = 0.0
    for i in range(4):
        if act[i]:
            if P[i, 2] < 0.0:
                return False
            if not stick_only and math.hypot(P[i, 0], P[i, 1]) > mu_s * P[i, 2] * (1.0 + CONE_SLACK):
                return False
    return True


@numba.njit(cache=True)
def _flat_system(idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs):
    """The linear momentum equations of :func:`_slide_flat` for the slip directions ``sdir``: ``xs`` gets the
    normal impulses of the ``n`` corners ``idx`` and ``(V_x, V_y, omega_z)``; False if singular."""
    m = n + 3
    # rows: force x, y, z; torque x, y, z. Columns: N of each active corner, then V_x, V_y, omega_z
    for a in range(6):
        for c in range(7):
            Am[a, c] = 0.0
    for k in range(n):
        i = idx[k]
        p0, p1 = -mu_k * sdir[i, 0], -mu_k * sdir[i, 1]
        x0, x1, x2 = r[i, 0], r[i, 1], r[i, 2]
        # V - vf = sum P  ->  V_x - sum N p0 = vf_x; V_y - sum N p1 = vf_y; - sum N = vf_z (V_z = 0)
        Am[0, k] = -p0
        Am[1, k] = -p1
        Am[2, k] = -1.0
        # Iw (Om - Omf) = sum r x P  ->  Iw[:, 2] omega_z - sum N (r x p) = Iw Omf
        Am[3, k] = -(x1 * 1.0 - x2 * p1)
        Am[4, k] = -(x2 * p0 - x0 * 1.0)
        Am[5, k] = -(x0 * p1 - x1 * p0)
    Am[0, n] = 1.0
    Am[1, n + 1] = 1.0
    for a in range(3):
        Am[3 + a, n + 2] = Iw[a, 2]
    y6[0], y6[1], y6[2] = vf[0], vf[1], vf[2]
    for a in range(3):
        y6[3 + a] = Iw[a, 0] * vf[3] + Iw[a, 1] * vf[4] + Iw[a, 2] * vf[5]
    for a in range(6):
        for c in range(6):
            acc = 0.0
            for k in range(m):
                acc += Am[a, k] * Am[c, k]
            A6[a, c] = acc
    if not _solve6(A6, y6):
        return False
    for c in range(m):
        x = 0.0
        for a in range(6):
            x += Am[a, c] * y6[a]
        xs[c] = x
    if n == 4 and min(xs[0], xs[1], xs[2], xs[3]) < 0.0:
        # the free direction (null vector of Am, first entry 1) and the nearest compressive distribution
        for a in range(6):
            y6[a] = -Am[a, 0]
            for c in range(6):
                A6[a, c] = Am[a, c + 1]
        if _solve6(A6, y6):
            zs[0] = 1.0
            for c in range(6):
                zs[c + 1] = y6[c]
            t, ok = _shift_range(xs, zs, 4)
            if ok:
                for c in range(m):
                    xs[c] += t * zs[c]
    return True


@numba.njit(cache=True)
def _flat_directions(v0, v1, wz, idx, n, r, sdir):
    """Each of the ``n`` corners ``idx``'s slip direction ``sdir`` for the level block's velocities ``(V_x, V_y,
    omega_z) = (v0, v1, wz)``; returns the largest change of a direction's component, or -1 if a corner does not
    slip."""
    moved = 0.0
    for k in range(n):
        i = idx[k]
        u0 = v0 - wz * r[i, 1]
        u1 = v1 + wz * r[i, 0]
        nu = math.hypot(u0, u1)
        if nu == 0.0:
            return -1.0
        moved = max(moved, abs(u0 / nu - sdir[i, 0]), abs(u1 / nu - sdir[i, 1]))
        sdir[i, 0], sdir[i, 1] = u0 / nu, u1 / nu
    return moved


@numba.njit(cache=True)
def _flat_eval(x, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs, g):
    """``g = G(x) - x`` for the velocities ``x = (V_x, V_y, omega_z)``: the slip directions of ``x``, then the
    velocities :func:`_flat_system` gives for them. False if a corner does not slip or the system is singular."""
    if _flat_directions(x[0], x[1], x[2], idx, n, r, sdir) < 0.0:
        return False
    if not _flat_system(idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs):
        return False
    for a in range(3):
        g[a] = xs[n + a] - x[a]
    return True


@numba.njit(cache=True)
def _flat_newton(x, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs):
    """Newton on ``G(x) = x`` (:func:`_flat_eval`) from ``x``, with a forward-difference Jacobian and step
    halving, to ``1e-12`` of the velocities' scale. Returns True with ``xs`` and ``sdir`` of the solution."""
    g = np.zeros(3)
    g1 = np.zeros(3)
    x1 = np.zeros(3)
    J = np.zeros((3, 3))
    Ji = np.zeros((3, 3))
    scale = max(abs(x[0]), abs(x[1]), abs(vf[0]), abs(vf[1]), abs(vf[2]))
    arm = math.sqrt(r[idx[0], 0] ** 2 + r[idx[0], 1] ** 2)
    if not _flat_eval(x, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs, g):
        return False
    for it in range(20):
        res = max(abs(g[0]), abs(g[1]), arm * abs(g[2]))
        if res <= NEWTON_TOL * scale:
            return _flat_eval(x, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs, g)
        for j in range(3):
            hj = FD_STEP * (scale / arm if j == 2 else scale)
            for a in range(3):
                x1[a] = x[a] + (hj if a == j else 0.0)
            if not _flat_eval(x1, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs, g1):
                return False
            for a in range(3):
                J[a, j] = (g1[a] - g[a]) / hj
        if not _inv3(J, Ji):
            return False
        lam = 1.0
        for half in range(8):
            for a in range(3):
                x1[a] = x[a] - lam * (Ji[a, 0] * g[0] + Ji[a, 1] * g[1] + Ji[a, 2] * g[2])
            ok = _flat_eval(x1, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs, g1)
            if ok and max(abs(g1[0]), abs(g1[1]), arm * abs(g1[2])) < res:
                break
            lam *= 0.5
        if not ok:
            return False
        for a in range(3):
            x[a] = x1[a]
            g[a] = g1[a]
    return False


@numba.njit(cache=True)
def _slide_flat(act, r, Iw, vf, V, Om, P, mu_k, sdir, A6, y6, Am):
    """Three or four active corners all slipping, in closed form for given slip directions: the block keeps its corners
    on the floor (``V_z = 0``, no rotation about a horizontal axis: with the floor's normal ``z`` the corners'
    normal velocities ``V_z + omega_x r_y - omega_y r_x`` vanish at three corners not in a line iff these do,
    whatever the tilt) and moves with ``(V_x, V_y, omega_z)``; each corner's impulse is ``N_i (-mu_k s_i, 1)``. For
    the slip directions ``s_i`` the six momentum equations are linear in ``(N_i, V_x, V_y, omega_z)``; their least-
    norm solution (the indeterminate part of the normal impulses, alternating between the corners, left at zero) is
    iterated with ``s_i`` the direction of each corner's slip velocity (from the free velocity's first) until the
    directions settle (where that fixed point stalls, as a twisting block comes to a stop, by Newton on the
    velocities ``(V_x, V_y, omega_z)`` that give the directions, :func:`_flat_newton`); on four corners a
    distribution with a pulling corner is moved along the system's free direction to the nearest compressive one.
    Accepted, into ``V``, ``Om`` and ``P``, if the directions settle (each corner then slips along the ``s_i`` its
    friction opposes) and every ``N_i >= 0`` (to ``FLAT_ROUNDOFF``); else False (NSGS then solves the step).
    ``sdir`` (4 x 2), ``A6`` (6 x 6), ``y6`` (6) and ``Am`` (6 x 7) are workspace."""
    idx = np.empty(4, dtype=np.int64)
    xs = np.empty(7)
    zs = np.empty(7)
    n = ZERO
    for i in range(4):
        if act[i]:
            idx[n] = i
            n += 1
    if _flat_directions(vf[0], vf[1], vf[5], idx, n, r, sdir) < 0.0:
        return False
    settled = False
    for it in range(30):
        if not _flat_system(idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs):
            return False
        moved = _flat_directions(xs[n], xs[n + 1], xs[n + 2], idx, n, r, sdir)
        if moved < 0.0:
            return False
        if moved < NEWTON_TOL:
            settled = True
            break
    if not settled:
        x = np.array([xs[n], xs[n + 1], xs[n + 2]])
        if not _flat_newton(x, idx, n, r, Iw, vf, mu_k, sdir, A6, y6, Am, xs, zs):
            return False
    for k in range(n):
        P[idx[k], 2] = xs[k]
    V[0], V[1], wz = xs[n], xs[n + 1], xs[n + 2]
    V[2] = 0.0
    Om[0], Om[1], Om[2] = 0.0, 0.0, wz
    total = 0.0
    for k in range(n):
        total += abs(xs[k])
    for i in range(4):
        if not act[i]:
            P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
            continue
        N = P[i, 2]
        if N < -FLAT_ROUNDOFF * total:
            return False
        N = max(N, 0.0)
        P[i, 2] = N
        u0 = V[0] - wz * r[i, 1]
        u1 = V[1] + wz * r[i, 0]
        nu = math.hypot(u0, u1)
        if nu == 0.0:
            return False
        if u0 * sdir[i, 0] + u1 * sdir[i, 1] < (1.0 - ALIGN_TOL) * nu:
            return False
        P[i, 0], P[i, 1] = -mu_k * N * sdir[i, 0], -mu_k * N * sdir[i, 1]
    return True


@numba.njit(cache=True)
def _edge_system(st, sdir, mu_k, D, q, A, y, cols):
    """The linear system of :func:`_edge_slip` for the statuses ``st`` (0 stick, 1 slip, 2 open) and the slip
    directions ``sdir``: the unknowns are a stuck corner's impulse (3) and a slipping corner's normal impulse ``N``
    (its impulse ``N (-mu_k s, 1)``; an open corner has none); the equations a stuck corner's velocity ``u = 0`` (3)
    and a slipping corner's normal velocity ``u_z = 0``, with ``u = q + D P``, into the leading ``m x m`` of ``A``
    and ``m`` of ``y``; ``cols`` (6 x 6) holds ``P`` per unknown. Returns the number of unknowns ``m``."""
    m = 0
    for c in range(6):
        for a in range(6):
            cols[c, a] = 0.0
    for k in range(2):
        if st[k] == 0:
            for i in range(3):
                cols[m, 3 * k + i] = 1.0
                m += 1
        elif st[k] == 1:
            cols[m, 3 * k], cols[m, 3 * k + 1], cols[m, 3 * k + 2] = -mu_k * sdir[k, 0], -mu_k * sdir[k, 1], 1.0
            m += 1
    row = 0
    for k in range(2):
        for i in range(3):
            if st[k] == 2 or (st[k] == 1 and i < 2):
                continue
            e = 3 * k + i
            for c in range(m):
                acc = 0.0
                for a in range(6):
                    acc += D[e, a] * cols[c, a]
                A[row, c] = acc
            y[row] = -q[e]
            row += 1
    return m


@numba.njit(cache=True)
def _edge_eval(st, sdir, mu_k, D, q, A, y, cols, P6, u, f):
    """The impulses ``P6`` and corner velocities ``u`` of :func:`_edge_system` for the slip directions ``sdir``,
    and per slipping corner ``k`` the angle from its direction ``s`` to its tangential velocity, ``f[k]`` in
    (-pi, pi] (zero where the friction opposes the slip). False if the system is singular."""
    m = _edge_system(st, sdir, mu_k, D, q, A, y, cols)
    if not _solve_n(A, y, m):
        return False
    for a in range(6):
        acc = 0.0
        for c in range(m):
            acc += cols[c, a] * y[c]
        P6[a] = acc
    for e in range(6):
        acc = q[e]
        for a in range(6):
            acc += D[e, a] * P6[a]
        u[e] = acc
    for k in range(2):
        if st[k] == 1:
            f[k] = math.atan2(sdir[k, 0] * u[3 * k + 1] - sdir[k, 1] * u[3 * k],
                              sdir[k, 0] * u[3 * k] + sdir[k, 1] * u[3 * k + 1])
        else:
            f[k] = 0.0
    return True


@numba.njit(cache=True)
def _edge_try(st, sdir, mu_s, mu_k, D, q, A, y, cols, P6, u, fw):
    """One status pair of :func:`_edge_slip`: the slip directions brought to consistency (each along that corner's
    tangential velocity; a few fixed-point steps ``s <- u_t / |u_t|``, then Newton on the directions' angles with a
    finite-difference Jacobian and step halving, the fixed point alone stalling or flipping where the two corners'
    slips are strongly coupled), then the statuses checked (a stuck corner pressing inside the static cone, a
    slipping one pressing and slipping along its ``s``, an open one not approaching). Returns True with the impulses
    ``P6`` and velocities ``u`` of the two corners; ``fw`` (5 x 2) is workspace."""
    f, f1, ang, J = fw[0], fw[1], fw[2], fw[3:5]
    done = False
    for it in range(5):
        if not _edge_eval(st, sdir, mu_k, D, q, A, y, cols, P6, u, f):
            return False
        moved = 0.0
        for k in range(2):
            if st[k] == 1:
                nu = math.hypot(u[3 * k], u[3 * k + 1])
                if nu == 0.0:
                    return False
                moved = max(moved, abs(u[3 * k] / nu - sdir[k, 0]), abs(u[3 * k + 1] / nu - sdir[k, 1]))
                sdir[k, 0], sdir[k, 1] = u[3 * k] / nu, u[3 * k + 1] / nu
        if moved < NEWTON_TOL:
            done = True
            break
    if not done:
        for k in range(2):
            ang[k] = math.atan2(sdir[k, 1], sdir[k, 0])
        if not _edge_eval(st, sdir, mu_k, D, q, A, y, cols, P6, u, f):
            return False
        for it in range(20):
            res = max(abs(f[0]), abs(f[1]))
            if res <= NEWTON_TOL:
                done = True
                break
            for j in range(2):  # the Jacobian by forward differences
                if st[j] != 1:
                    J[0, j], J[1, j] = 0.0, 0.0
                    continue
                sdir[j, 0], sdir[j, 1] = math.cos(ang[j] + FD_STEP), math.sin(ang[j] + FD_STEP)
                if not _edge_eval(st, sdir, mu_k, D, q, A, y, cols, P6, u, f1):
                    return False
                J[0, j], J[1, j] = (f1[0] - f[0]) / FD_STEP, (f1[1] - f[1]) / FD_STEP
                sdir[j, 0], sdir[j, 1] = math.cos(ang[j]), math.sin(ang[j])
            for k in range(2):
                if st[k] != 1:
                    J[k, k] = 1.0
            det = J[0, 0] * J[1, 1] - J[0, 1] * J[1, 0]
            if det == 0.0:
                return False
            d0 = -(J[1, 1] * f[0] - J[0, 1] * f[1]) / det
            d1 = -(J[0, 0] * f[1] - J[1, 0] * f[0]) / det
            lam = 1.0
            for half in range(8):
                for k in range(2):
                    a = ang[k] + lam * (d0 if k == 0 else d1)
                    sdir[k, 0], sdir[k, 1] = math.cos(a), math.sin(a)
                if not _edge_eval(st, sdir, mu_k, D, q, A, y, cols, P6, u, f1):
                    return False
                if max(abs(f1[0]), abs(f1[1])) < res or half == 7:
                    break
                lam *= 0.5
            ang[0] += lam * d0
            ang[1] += lam * d1
            f[0], f[1] = f1[0], f1[1]
    if not done:
        return False
    for k in range(2):
        pz = P6[3 * k + 2]
        if pz < 0.0:
            return False
        if st[k] == 0 and math.hypot(P6[3 * k], P6[3 * k + 1]) > mu_s * pz * (1.0 + CONE_SLACK):
            return False
        if st[k] == 1 and u[3 * k] * sdir[k, 0] + u[3 * k + 1] * sdir[k, 1] <= 0.0:
            return False
        if st[k] == 2 and u[3 * k + 2] < 0.0:
            return False
    return True


@numba.njit(cache=True)
def _edge_slip(act, r, Iinv, vf, V, Om, P, mu_s, mu_k, stick_only, ew, out):
    """Two active corners, one stuck and one slipping, both slipping, or one slipping and the other leaving the
    floor, in closed form for consistent slip directions (a block rocking on an edge while the edge slips or twists
    about one of its corners; Gauss-Seidel converges slowly there, the two corners being strongly coupled through
    the body). The status pairs are tried in turn (stick-slip, slip-stick, slip-slip, open-slip, slip-open; the
    pairs stick-stick and stick-open have closed forms of their own), the slip directions from those of the corners'
    friction impulses ``P`` (warm start) or free velocities; the first whose statuses hold is the step's solution of
    the contact problem (into ``V``, ``Om``, ``P``), else False (NSGS then solves it). With infinite friction
    (``stick_only``) a slipping corner is :func:`_local`'s infinite-friction limit (``mu_k = LIMIT_MU``, counted in
    ``OUT_LIMIT_STEPS``) and a stuck one needs only to press. ``ew`` is its scratch (:class:`.workspace.EdgeWork`),
    ``last[0]`` the pair that held last (tried first)."""
    if stick_only:
        mu_s, mu_k = np.inf, LIMIT_MU
    D, A, cols, vecs = ew.D, ew.A, ew.cols, ew.vec
    q, y, P6, u = vecs[EVEC_Q], vecs[EVEC_Y], vecs[EVEC_P6], vecs[EVEC_U]
    sdir = ew.sdir
    st, idx = ew.stidx[0:2], ew.stidx[2:4]
    n = 0
    for i in range(4):
        if act[i]:
            idx[n] = i
            n += 1
    for a in range(2):
        ra = r[idx[a]]
        for b in range(2):
            _delassus_pair(ra, r[idx[b]], Iinv, D[3 * a:3 * a + 3, 3 * b:3 * b + 3])
        q[3 * a] = vf[0] + vf[4] * ra[2] - vf[5] * ra[1]
        q[3 * a + 1] = vf[1] + vf[5] * ra[0] - vf[3] * ra[2]
        q[3 * a + 2] = vf[2] + vf[3] * ra[1] - vf[4] * ra[0]
    last = ew.last
    for c in range(5):
        combo = last[0] if c == 0 else (c - 1 if c - 1 < last[0] else c)  # the last pair that held first
        st[0], st[1] = EDGE_STATUSES[combo, 0], EDGE_STATUSES[combo, 1]
        ok = True
        for k in range(2):
            if st[k] != 1:
                continue
            i = idx[k]
            nu = math.hypot(P[i, 0], P[i, 1])
            if nu > 0.0:
                sdir[k, 0], sdir[k, 1] = -P[i, 0] / nu, -P[i, 1] / nu
            else:
                nu = math.hypot(q[3 * k], q[3 * k + 1])
                if nu == 0.0:
                    ok = False
                    break
                sdir[k, 0], sdir[k, 1] = q[3 * k] / nu, q[3 * k + 1] / nu
        if ok and _edge_try(st, sdir, mu_s, mu_k, D, q, A, y, cols, P6, u, ew.fw):
            last[0] = combo
            V[0], V[1], V[2], Om[0], Om[1], Om[2] = vf[0], vf[1], vf[2], vf[3], vf[4], vf[5]
            for i in range(4):
                P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
            if stick_only:
                out[OUT_LIMIT_STEPS] += (st[0] == 1) + (st[1] == 1)
            for k in range(2):
                i = idx[k]
                P[i, 0], P[i, 1], P[i, 2] = P6[3 * k], P6[3 * k + 1], P6[3 * k + 2]
                V[0] += P[i, 0]
                V[1] += P[i, 1]
                V[2] += P[i, 2]
                _cross_add(r[i], P[i], Iinv, Om, 1.0)
            return True
    return False


@numba.njit(cache=True)
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


@numba.njit(cache=True)
def _kinetic(s, Iw):
    """Kinetic energy per unit mass (J/kg) of state ``s`` with floor-frame inertia ``Iw``."""
    e = 0.5 * (s[7] * s[7] + s[8] * s[8] + s[9] * s[9])
    for i in range(3):
        for j in range(3):
            e += 0.5 * s[10 + i] * Iw[i, j] * s[10 + j]
    return e


@numba.njit(cache=True)
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
def _twist(s):
    """Rotation about the vertical (rad) of the swing-twist decomposition of the quaternion, in (-pi, pi]."""
    tw = 2.0 * math.atan2(s[6], s[3])
    if tw > math.pi:
        tw -= 2.0 * math.pi
    elif tw <= -math.pi:
        tw += 2.0 * math.pi
    return tw


@numba.njit(cache=True)
def _tilt(s, weak_y):
    """``(tilt, signed tilt, lean x, lean y)``: the tilt (rad) from the quaternion, ``2 asin(sqrt(q_x² + q_y²))``,
    signed by the lean of the body's vertical axis along the weaker axis (``x``, or ``y`` if ``weak_y``), and the
    plan components of that axis."""
    w, x, y, z = s[3], s[4], s[5], s[6]
    tilt = 2.0 * math.asin(min(1.0, math.sqrt(x * x + y * y)))
    lx, ly = 2.0 * (x * z + w * y), 2.0 * (y * z - w * x)
    lean = ly if weak_y else lx
    return tilt, (tilt if lean >= 0.0 else -tilt), lx, ly


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
def _geometry(s, body, Q, Iinv, Iw, r):
    """Rotation, floor-frame inertia and the corners' arms ``r`` (4 x 3) of state ``s`` (``body``:
    :class:`.model.Body`)."""
    _arms(s, body, Q, r)
    _inv_inertia(Q, body.inertia, Iinv, Iw)


@numba.njit(cache=True)
def _arms(s, body, Q, r):
    """The corners' arms ``r`` (4 x 3, from the centre of mass, floor frame) of state ``s``; ``Q`` is workspace."""
    b, d, h = body.b, body.d, body.h
    _rotmat(s, Q)
    for i in range(4):
        cx, cy = CORNER_SX[i] * b, CORNER_SY[i] * d
        for a in range(3):
            r[i, a] = Q[a, 0] * cx + Q[a, 1] * cy - Q[a, 2] * h


@numba.njit(cache=True)
def _stick_subset(act, guess, landing, n_act, r, Iinv, Iw, vf, V, Om, P, mu_s, stick_only, tol, ws, y6):
    """The active corners that were down (``act`` and ``guess``; with ``landing`` those that were not: a rocking
    impact, where the landing edge takes the load and the pivot lifts), one or two of them and fewer than
    ``n_act``, stuck and loaded, the other active corners without impulse: accepted, into ``V``, ``Om``, ``P``
    and ``act`` (the others dropped), if those others separate, ``u_n >= -tol`` (m/s), which with the stuck
    corners' loads in their cones solves the step's contact problem. One corner: ``P = -W^-1 u_free``; two:
    :func:`_stick_all`."""
    sub = ws.mask
    n_sub = ZERO
    for i in range(4):
        sub[i] = act[i] and (guess[i] != landing)
        n_sub += sub[i]
    if n_sub == 0 or n_sub > 2 or n_sub == n_act:
        return False
    return _stick_mask(act, sub, n_sub, r, Iinv, Iw, vf, V, Om, P, mu_s, stick_only, tol, ws, y6)


@numba.njit(cache=True)
def _stick_mask(act, sub, n_sub, r, Iinv, Iw, vf, V, Om, P, mu_s, stick_only, tol, ws, y6):
    """The corners of ``sub`` (one or two of the active ones) stuck and loaded, the other active corners
    separating (:func:`_stick_subset`)."""
    if n_sub == 2:
        if not _stick_all(sub, TWO, r, Iw, vf, V, Om, P, mu_s, stick_only, ws.A6, y6):
            return False
    else:
        i = 0
        while not sub[i]:
            i += 1
        W, Wi = ws.Wd[i], ws.Wi[i]
        _delassus(r[i], Iinv, W)
        if not _inv3(W, Wi):
            return False
        ri = r[i]
        u0 = vf[0] + vf[4] * ri[2] - vf[5] * ri[1]
        u1 = vf[1] + vf[5] * ri[0] - vf[3] * ri[2]
        u2 = vf[2] + vf[3] * ri[1] - vf[4] * ri[0]
        for c in range(4):
            P[c, 0], P[c, 1], P[c, 2] = 0.0, 0.0, 0.0
        for a in range(3):
            P[i, a] = -(Wi[a, 0] * u0 + Wi[a, 1] * u1 + Wi[a, 2] * u2)
        if P[i, 2] <= 0.0 or (not stick_only and math.hypot(P[i, 0], P[i, 1]) > mu_s * P[i, 2]):
            return False
        V[0], V[1], V[2], Om[0], Om[1], Om[2] = vf[0] + P[i, 0], vf[1] + P[i, 1], vf[2] + P[i, 2], vf[3], vf[4], vf[5]
        _cross_add(ri, P[i], Iinv, Om, 1.0)
    for j in range(4):
        if act[j] and not sub[j]:
            rj = r[j]
            if V[2] + Om[0] * rj[1] - Om[1] * rj[0] < -tol:
                return False
    for j in range(4):
        if act[j] and not sub[j]:
            act[j] = False
            P[j, 0], P[j, 1], P[j, 2] = 0.0, 0.0, 0.0
    return True


@numba.njit(cache=True)
def _stick_single(act, r, Iinv, Iw, vf, V, Om, P, mu_s, stick_only, tol, ws, y6):
    """Two active corners whose edge cannot carry the step stuck (a corner pulls): each alone stuck, the other
    separating (:func:`_stick_mask`), the lower one first (a block turning about a corner with the edge's other
    corner grazing the floor)."""
    i1, i2 = _first_two(act)
    if r[i2, 2] < r[i1, 2]:
        i1, i2 = i2, i1
    sub = ws.mask
    for first in (i1, i2):
        for i in range(4):
            sub[i] = i == first
        if _stick_mask(act, sub, ONE, r, Iinv, Iw, vf, V, Om, P, mu_s, stick_only, tol, ws, y6):
            return True
    return False


@numba.njit(cache=True)
def _step(model, s, a_x, a_y, a_v, dt, ws, act, P, new, out, guess):
    """One Moreau-Jean step from ``s`` into ``new`` (docs/guide/three-dimensions.md): the free velocity under the
    step's forces (gravity and the floor's inertia force on the centre of mass, the gyroscopic torque
    ``-omega x I omega`` at ``t_k``), the active corners from the mid-step prediction of their gaps, the
    corners' Delassus blocks at ``q_k``, the impulses by NSGS (:func:`_nsgs`) warm-started from ``P``, then
    ``X_{k+1} = X_k + dt [(1 - theta_mj) V_k + theta_mj V_{k+1}]`` and the quaternion turned by ``dt`` times the
    same blend of the angular velocities. Returns the sweeps NSGS took (0: no contact;
    ``model.nsgs.max_sweeps + 1``: it did not converge). ``ws`` holds the workspace (see :func:`run`).

    Before the closed forms and NSGS, the corners that were down (``guess``) are tried alone, stuck
    (:func:`_stick_subset`): a block rocking on an edge just after an impact has its other corners still
    predicted active, unloaded and separating."""
    Q, Iinv, Iw, r, Wd, Wi, vec = ws.Q, ws.Iinv, ws.Iw, ws.r, ws.Wd, ws.Wi, ws.vec
    body, fric, nsgs, theta_mj = model.body, model.friction, model.nsgs, model.numerics.theta_mj
    g = body.g
    _geometry(s, body, Q, Iinv, Iw, r)
    V = vec[VEC_V]
    Om = vec[VEC_OM]
    # free velocity
    V[0], V[1], V[2] = s[7] - dt * a_x, s[8] - dt * a_y, s[9] - dt * (g + a_v)
    w0, w1, w2 = s[10], s[11], s[12]
    L0 = Iw[0, 0] * w0 + Iw[0, 1] * w1 + Iw[0, 2] * w2
    L1 = Iw[1, 0] * w0 + Iw[1, 1] * w1 + Iw[1, 2] * w2
    L2 = Iw[2, 0] * w0 + Iw[2, 1] * w1 + Iw[2, 2] * w2
    g0, g1, g2 = -(w1 * L2 - w2 * L1), -(w2 * L0 - w0 * L2), -(w0 * L1 - w1 * L0)
    for a in range(3):
        Om[a] = s[10 + a] + dt * (Iinv[a, 0] * g0 + Iinv[a, 1] * g1 + Iinv[a, 2] * g2)
    vf = vec[VEC_VF]
    vf[0], vf[1], vf[2], vf[3], vf[4], vf[5] = V[0], V[1], V[2], Om[0], Om[1], Om[2]
    n_act = ZERO
    for i in range(4):
        ri = r[i]
        un = s[9] + s[10] * ri[1] - s[11] * ri[0]
        act[i] = s[2] + ri[2] + 0.5 * dt * un <= 0.0
        n_act += act[i]
    sweeps = 0
    stick_only, mu_s, mu_k = fric.infinite, fric.mu_s, fric.mu_k
    scale = max(g * dt, abs(vf[0]), abs(vf[1]), abs(vf[2]), body.R * (abs(vf[3]) + abs(vf[4]) + abs(vf[5])))
    tol = nsgs.tol * scale
    n_down = 0  # the active corners that were down: a subset to try alone (_stick_subset) if one or two, not all
    for i in range(4):
        n_down += act[i] and guess[i]
    try_down = 0 < n_down <= 2 and n_down < n_act
    try_landing = 0 < n_act - n_down <= 2 and n_down > 0
    if n_act >= 2 and ((try_down and _stick_subset(act, guess, NO, n_act, r, Iinv, Iw, vf, V, Om, P, mu_s,
                                                    stick_only, tol, ws, vec[VEC_Y6]))
                       or (try_landing and _stick_subset(act, guess, YES, n_act, r, Iinv, Iw, vf, V, Om, P, mu_s,
                                                         stick_only, tol, ws, vec[VEC_Y6]))):
        sweeps = 1
        out[OUT_STICK_STEPS] += 1.0
    elif n_act >= 2 and _stick_all(act, n_act, r, Iw, vf, V, Om, P, mu_s, stick_only, ws.A6, vec[VEC_Y6]):
        sweeps = 1
        out[OUT_STICK_STEPS] += 1.0
    elif n_act == 2 and _stick_single(act, r, Iinv, Iw, vf, V, Om, P, mu_s, stick_only, tol, ws,
                                      vec[VEC_Y6]):
        sweeps = 1
        out[OUT_STICK_STEPS] += 1.0
    elif n_act == 2 and _edge_slip(act, r, Iinv, vf, V, Om, P, mu_s, mu_k, stick_only, ws.edge, out):
        sweeps = 1
        out[OUT_EDGE_SLIP] += 1.0
    elif n_act >= 3 and not stick_only and _slide_flat(act, r, Iw, vf, V, Om, P, mu_k, ws.sdir, ws.A6,
                                                                   vec[VEC_Y6], ws.Am):
        sweeps = 1
        out[OUT_SLIDE_STEPS] += 1.0
    elif n_act > 0:
        V[0], V[1], V[2], Om[0], Om[1], Om[2] = vf[0], vf[1], vf[2], vf[3], vf[4], vf[5]
        for i in range(4):
            if act[i]:
                _delassus(r[i], Iinv, Wd[i])
                _inv3(Wd[i], Wi[i])
                V[0] += P[i, 0]
                V[1] += P[i, 1]
                V[2] += P[i, 2]
                _cross_add(r[i], P[i], Iinv, Om, 1.0)
            else:
                P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
        sweeps = _solve_contacts(act, r, Wd, Wi, Iinv, V, Om, P, mu_s, mu_k, stick_only, tol,
                                 nsgs, vec[VEC_Y6], vec[VEC_PN], out, n_act == 1)
    else:
        for i in range(4):
            P[i, 0], P[i, 1], P[i, 2] = 0.0, 0.0, 0.0
    for a in range(3):
        new[a] = s[a] + dt * ((1.0 - theta_mj) * s[7 + a] + theta_mj * V[a])
        new[7 + a] = V[a]
        new[10 + a] = Om[a]
    _quat_step(s, (1.0 - theta_mj) * s[10] + theta_mj * Om[0], (1.0 - theta_mj) * s[11] + theta_mj * Om[1],
               (1.0 - theta_mj) * s[12] + theta_mj * Om[2], dt, new)
    return sweeps


@numba.njit(cache=True)
def _contacts(new, r, r1, act, P, touch, slip, vel_tol, lift_gap, out):
    """After a step: friction work of the impulses, and each corner's contact and slip flags (the arms ``r``
    of the step's start: the velocity rows the solver enforced; ``r1`` those of its end, for the gaps); returns
    True if a corner landed (an impact).

    A corner with a normal impulse is down (an impact if it was up), slipping if its tangential speed exceeds
    ``vel_tol``. A corner without impulse is up once it moves away from the floor faster than ``vel_tol`` or
    rises above ``lift_gap``; otherwise it stays down (a pivot constrained at velocity level drifts up and
    takes an occasional free step; a level block may rest on three corners), slipping if it moves."""
    impact = False
    V0, V1, V2, w0, w1, w2 = new[7], new[8], new[9], new[10], new[11], new[12]
    for i in range(4):
        ri = r[i]
        u0 = V0 + w1 * ri[2] - w2 * ri[1]
        u1 = V1 + w2 * ri[0] - w0 * ri[2]
        u2 = V2 + w0 * ri[1] - w1 * ri[0]
        gap = new[2] + r1[i, 2]
        if act[i]:
            out[OUT_FRICTION_WORK] -= P[i, 0] * u0 + P[i, 1] * u1
        if P[i, 2] > 0.0:
            impact = impact or not touch[i]
            touch[i] = True
            slip[i] = math.hypot(u0, u1) > vel_tol
            out[OUT_MAX_PENETRATION] = max(out[OUT_MAX_PENETRATION], -gap)
        elif u2 > vel_tol or gap > lift_gap:
            touch[i] = False
            slip[i] = False
        elif touch[i]:  # down without load (a level block on three corners): slipping if it moves
            slip[i] = math.hypot(u0, u1) > vel_tol
    return impact


@numba.njit(cache=True)
def _rest_holds(a_x, a_y, a_v, body, fric):
    """Does a block at rest on its four corners, stuck, stay at rest under the floor accelerations? Iff
    ``g + a_v > 0``, the centre of pressure ``(a_x, a_y) h / (g + a_v)`` lies in the base ``[-b, b] x [-d, d]``
    and friction carries the load, ``hypot(a_x, a_y) <= mu (g + a_v)``."""
    gz = body.g + a_v
    if gz <= 0.0:
        return False
    h = body.h
    if abs(a_x) * h > body.b * gz or abs(a_y) * h > body.d * gz:
        return False
    return fric.infinite or math.hypot(a_x, a_y) <= fric.mu_s * gz


@numba.njit(cache=True)
def _count_sweeps(sweeps, nsgs, out):
    """A Moreau-Jean step's contact-solver counts (:func:`_step`'s ``sweeps``); returns True if it converged.
    (The step and its bookkeeping, :func:`_book`, are called from :func:`run` itself: a function between them
    that passed the kernel's workspace on cost about a third of a microsecond a step in numba's reference
    counting of its arrays.)"""
    if sweeps > 0:
        out[OUT_CONTACT_STEPS] += 1.0
        out[OUT_NSGS_SWEEPS] += min(sweeps, nsgs.max_sweeps)
        out[OUT_NSGS_MAX] = max(out[OUT_NSGS_MAX], min(sweeps, nsgs.max_sweeps))
    converged = sweeps <= nsgs.max_sweeps
    if not converged:
        out[OUT_NSGS_FAILED] += 1.0
    return converged


@numba.njit(cache=True)
def _book(state, a, Q1, r1, r, Iw, vf, act, P, new, out, touch, slip, vel_tol, lift_gap, body):
    """The bookkeeping of a Moreau-Jean step from ``state`` to ``new`` under the accelerations ``a`` with the
    impulses ``P``: input work, the corners' flags and friction work (:func:`_contacts`), an impact's loss.
    ``r`` and ``Iw`` are the step's arms and inertia, ``vf`` its free velocity; ``Q1`` and ``r1`` workspace (the
    arms of ``new`` on return). Returns True at an impact."""
    # energy bookkeeping (per unit mass): input work over the step's displacement, friction work in
    # _contacts, and at an impact the kinetic energy of the impulses' velocity change
    out[OUT_INPUT_WORK] -= a[0] * (new[0] - state[0]) + a[1] * (new[1] - state[1]) + a[2] * (new[2] - state[2])
    _arms(new, body, Q1, r1)
    impact = _contacts(new, r, r1, act, P, touch, slip, vel_tol, lift_gap, out)
    if impact:
        e = 0.0
        for c in range(3):
            dv = new[7 + c] - vf[c]
            e += 0.5 * dv * dv
            for c2 in range(3):
                e += 0.5 * (new[10 + c] - vf[3 + c]) * Iw[c, c2] * (new[10 + c2] - vf[3 + c2])
        out[OUT_IMPACT_LOSS] += e
        out[OUT_IMPACTS] += 1.0
    return impact


@numba.njit(cache=True)
def _flat_slip(act, touch, slip):
    """After a Moreau-Jean step: all four corners active and down, some slipping (a block sliding flat)."""
    sl = False
    for i in range(4):
        if not (act[i] and touch[i]):
            return False
        sl = sl or slip[i]
    return sl


@numba.njit(cache=True)
def _stuck_pivot(act, touch, slip, P):
    """After a Moreau-Jean step: one corner or two down, exactly those solved in contact, loaded, none slipping
    (the phase :mod:`.pivot` integrates)."""
    n = 0
    for i in range(4):
        if act[i] != touch[i] or (touch[i] and (slip[i] or P[i, 2] <= 0.0)):
            return False
        n += touch[i]
    return n == 1 or n == 2


@numba.njit(cache=True)
def _rest_span(model, floor, k, tail_left):
    """Steps a seated block whose load the base carries at step ``k`` stays at rest (>= 1): a record's whole
    sample interval from its start if the base carries the load at both samples, the tail's remaining rest
    steps ``tail_left`` under a still floor, else one."""
    ax, ay, av, sub, body, fric = floor.ax, floor.ay, floor.av, floor.sub, model.body, model.friction
    if k >= floor.n_exc:
        return max(1, min(tail_left, model.limits.max_steps - k))
    if floor.form == FORCING_LINEAR and k % sub == 0:
        jj = k // sub
        if _rest_holds(ax[jj], ay[jj], av[jj], body, fric) and _rest_holds(ax[jj + 1], ay[jj + 1], av[jj + 1],
                                                                            body, fric):
            return sub
    return 1


@numba.njit(cache=True, inline='always')
def _same_phase(model, new, piv, n_piv, a, ws, probe):
    """Is the end state ``new`` of a smooth step still in its phase? Every other corner above ``lift_gap``, and
    a Moreau-Jean probe step from it (``a``: the floor's accelerations of that step) solved with exactly the
    pivots active, each loaded and stuck. ``probe`` is ``(act, P, state, out)`` scratch (``P`` holds the warm
    start on entry and the probe's impulses on return)."""
    actp, Pp, sp, outp = probe.act, probe.P, probe.state, probe.out
    Q1, r1 = ws.Q1, ws.r1
    lift_gap, vel_tol = model.limits.lift_gap, model.limits.velocity_tol
    _arms(new, model.body, Q1, r1)
    for i in range(4):
        mine = i == piv[0] or (n_piv == 2 and i == piv[1])
        if not mine and new[2] + r1[i, 2] <= lift_gap:
            return False
    outp[:] = 0.0
    guess = ws.mask
    for i in range(4):
        guess[i] = i == piv[0] or (n_piv == 2 and i == piv[1])
    sweeps = _step(model, new, a[0], a[1], a[2], model.numerics.dt, ws, actp, Pp, sp, outp, guess)
    if sweeps == 0 or sweeps > model.nsgs.max_sweeps:
        return False
    for i in range(4):
        mine = i == piv[0] or (n_piv == 2 and i == piv[1])
        if actp[i] != mine or (mine and Pp[i, 2] <= 0.0):
            return False
    if n_piv == 2:
        return outp[OUT_STICK_STEPS] > 0.5
    ri = ws.r[piv[0]]  # the probe's arms
    u0 = sp[7] + sp[11] * ri[2] - sp[12] * ri[1]
    u1 = sp[8] + sp[12] * ri[0] - sp[10] * ri[2]
    return math.hypot(u0, u1) <= vel_tol


@numba.njit(cache=True, inline='always')
def _smooth(model, floor, state, touch, k, n_max, ws, wk, probe, P, new, out):
    """A smooth step (:mod:`opsrock.solvers.rigid3d.pivot`) about the corners down: from ``k`` to the next
    sample (at most ``n_max`` steps), halved while it leaves its phase, down to ``pivot.MIN_STEPS``. Returns
    ``(steps, largest tilt)``; 0 steps if none was kept, -1 if none could be tried (fewer than two steps to
    the next sample, or not one corner or two down); the Moreau-Jean steps then go on."""
    piv = ws.piv
    n_piv = ZERO
    for i in range(4):
        if touch[i]:
            if n_piv == 2:
                return 0, 0.0
            piv[n_piv] = i
            n_piv += 1
    if n_piv == 0:
        return 0, 0.0
    n = PV.step_end(floor, k, n_max) - k
    if n < 2:
        return -1, 0.0
    a = ws.a
    Pp = probe.P
    while True:
        out[OUT_SMOOTH_TRIED] += 1.0
        tilt = PV.integrate(model, floor, state, piv, n_piv, k, n, new, wk)
        a[0], a[1], a[2] = _floor(floor, k + n, model.numerics.theta_mj)
        Pp[:, :] = P
        if 0.0 <= tilt < OVERTURNING_ANGLE and _same_phase(model, new, piv, n_piv, a, ws, probe):
            P[:, :] = Pp
            out[OUT_SMOOTH_STEPS] += 1.0
            out[OUT_SMOOTH_SPAN] += n
            return n, tilt
        if n <= PV.MIN_STEPS:
            return 0, 0.0
        n = max(PV.MIN_STEPS, n // 2)


# --- smooth steps on slipping corners: the contact forces at acceleration level --------------------------------


@numba.njit(cache=True)
def _slip_rhs(model, y, F, idx, st, sw, dy):
    """Time derivative ``dy`` of the state ``y`` (13) of a block on the corners ``idx[:2]`` with the statuses
    ``st`` (0 stuck, 1 slipping, 2 not in contact) under the body force ``F`` (m/s², per unit mass): the contact
    forces per unit mass solve :func:`_edge_system` at acceleration level (a stuck corner's acceleration zero, a
    slipping corner's normal acceleration zero and its force ``N (-mu_k s, 1)``, ``s`` its slip velocity's
    direction; with infinite friction :func:`_local`'s limit, ``mu_k = LIMIT_MU``), the corners' free
    accelerations ``F + alpha_f x r + omega x (omega x r)`` with ``alpha_f = -I^-1 (omega x I omega)``. Returns
    ``(holds, friction power, stop time)``: ``holds`` False unless every contact presses (``N > 0``) and a stuck
    corner's force lies in its static cone; the power (W/kg) the slipping corners' friction dissipates; the
    smallest of the slipping corners' speed over tangential acceleration (s)."""
    Q, Iinv, Iw, r, D, A, cols, vecs, sdir = sw.Q, sw.Iinv, sw.Iw, sw.r, sw.D, sw.A, sw.cols, sw.vec, sw.sdir
    q, yv, P6, u = vecs[EVEC_Q], vecs[EVEC_Y], vecs[EVEC_P6], vecs[EVEC_U]
    fric = model.friction
    mu_s, mu_k = (np.inf, LIMIT_MU) if fric.infinite else (fric.mu_s, fric.mu_k)
    _arms(y, model.body, Q, r)
    _inv_inertia(Q, model.body.inertia, Iinv, Iw)
    w0, w1, w2 = y[10], y[11], y[12]
    L0 = Iw[0, 0] * w0 + Iw[0, 1] * w1 + Iw[0, 2] * w2
    L1 = Iw[1, 0] * w0 + Iw[1, 1] * w1 + Iw[1, 2] * w2
    L2 = Iw[2, 0] * w0 + Iw[2, 1] * w1 + Iw[2, 2] * w2
    g0, g1, g2 = -(w1 * L2 - w2 * L1), -(w2 * L0 - w0 * L2), -(w0 * L1 - w1 * L0)
    al0 = Iinv[0, 0] * g0 + Iinv[0, 1] * g1 + Iinv[0, 2] * g2
    al1 = Iinv[1, 0] * g0 + Iinv[1, 1] * g1 + Iinv[1, 2] * g2
    al2 = Iinv[2, 0] * g0 + Iinv[2, 1] * g1 + Iinv[2, 2] * g2
    for k in range(2):
        ri = r[idx[k]]
        x0, x1, x2 = w1 * ri[2] - w2 * ri[1], w2 * ri[0] - w0 * ri[2], w0 * ri[1] - w1 * ri[0]
        u[3 * k], u[3 * k + 1], u[3 * k + 2] = y[7] + x0, y[8] + x1, y[9] + x2
        q[3 * k] = F[0] + al1 * ri[2] - al2 * ri[1] + w1 * x2 - w2 * x1
        q[3 * k + 1] = F[1] + al2 * ri[0] - al0 * ri[2] + w2 * x0 - w0 * x2
        q[3 * k + 2] = F[2] + al0 * ri[1] - al1 * ri[0] + w0 * x1 - w1 * x0
        for b in range(2):
            _delassus_pair(ri, r[idx[b]], Iinv, D[3 * k:3 * k + 3, 3 * b:3 * b + 3])
        if st[k] == 1:
            nu = math.hypot(u[3 * k], u[3 * k + 1])
            if nu == 0.0:
                return False, 0.0, 0.0
            sdir[k, 0], sdir[k, 1] = u[3 * k] / nu, u[3 * k + 1] / nu
    m = _edge_system(st, sdir, mu_k, D, q, A, yv, cols)
    if not _solve_n(A, yv, m):
        return False, 0.0, 0.0
    for a in range(6):
        acc = 0.0
        for c in range(m):
            acc += cols[c, a] * yv[c]
        P6[a] = acc
    holds = True
    power = 0.0
    t_stop = np.inf
    for k in range(2):
        if st[k] == 2:
            continue
        pz = P6[3 * k + 2]
        if pz <= 0.0 or (st[k] == 0 and math.hypot(P6[3 * k], P6[3 * k + 1]) > mu_s * pz):
            holds = False
        if st[k] == 1:
            at0, at1 = q[3 * k], q[3 * k + 1]
            for a in range(6):
                at0 += D[3 * k, a] * P6[a]
                at1 += D[3 * k + 1, a] * P6[a]
            a_t = math.hypot(at0, at1)
            if a_t > 0.0:
                t_stop = min(t_stop, math.hypot(u[3 * k], u[3 * k + 1]) / a_t)
            power -= P6[3 * k] * u[3 * k] + P6[3 * k + 1] * u[3 * k + 1]
    t0, t1, t2 = 0.0, 0.0, 0.0
    dy[7], dy[8], dy[9] = F[0], F[1], F[2]
    for k in range(2):
        if st[k] == 2:
            continue
        ri = r[idx[k]]
        p0, p1, p2 = P6[3 * k], P6[3 * k + 1], P6[3 * k + 2]
        dy[7] += p0
        dy[8] += p1
        dy[9] += p2
        t0 += ri[1] * p2 - ri[2] * p1
        t1 += ri[2] * p0 - ri[0] * p2
        t2 += ri[0] * p1 - ri[1] * p0
    dy[10] = al0 + Iinv[0, 0] * t0 + Iinv[0, 1] * t1 + Iinv[0, 2] * t2
    dy[11] = al1 + Iinv[1, 0] * t0 + Iinv[1, 1] * t1 + Iinv[1, 2] * t2
    dy[12] = al2 + Iinv[2, 0] * t0 + Iinv[2, 1] * t1 + Iinv[2, 2] * t2
    dy[0], dy[1], dy[2] = y[7], y[8], y[9]
    qw, qx, qy, qz = y[3], y[4], y[5], y[6]
    dy[3] = -0.5 * (w0 * qx + w1 * qy + w2 * qz)
    dy[4] = 0.5 * (qw * w0 + w1 * qz - w2 * qy)
    dy[5] = 0.5 * (qw * w1 + w2 * qx - w0 * qz)
    dy[6] = 0.5 * (qw * w2 + w0 * qy - w1 * qx)
    return holds, power, t_stop


@numba.njit(cache=True)
def _slip_integrate(model, floor, s, idx, st, k0, n_steps, new, sw):
    """Classical Runge-Kutta from state ``s`` at Moreau-Jean step ``k0`` over ``n_steps`` steps on the slipping
    (and stuck) corners ``idx`` / ``st`` (:func:`_slip_rhs`) into ``new``, in sub-steps of at most
    ``pivot.RK_DTAU``. Returns ``(largest tilt at the sub-steps' ends (rad), friction work (J/kg))``, the tilt -1
    as soon as a stage's forces stop holding (:func:`_slip_rhs`), a corner not in contact reaches the floor or
    the tilt reaches pi/2. ``sw`` is the workspace of :func:`_slip_rhs` and ``(dy, acc, ytmp, F)``."""
    dy, acc, ytmp, F = sw.dy, sw.acc, sw.ytmp, sw.F
    r = sw.r
    g, dt, theta_mj = model.body.g, model.numerics.dt, model.numerics.theta_mj
    new[:] = s
    PV.floor_at(floor, float(k0), k0, theta_mj, F, g)
    holds, _, t_stop = _slip_rhs(model, new, F, idx, st, sw, dy)
    span = n_steps * dt
    if not holds or t_stop <= 0.0 or span * SLIP_TURN > n_steps * t_stop:  # (the last: a sub-step under dt)
        return -1.0, 0.0
    n_sub = max(1, int(math.ceil(span * model.body.p / PV.RK_DTAU)), int(math.ceil(span * SLIP_TURN / t_stop)))
    hs = n_steps / n_sub
    hdt = hs * dt
    if hs < SLIP_MIN_SUB:
        return -1.0, 0.0
    work = 0.0
    tilt_max = _tilt(new, NO)[0]
    for m in range(n_sub):
        kf = k0 + m * hs
        for stage in range(4):
            c = 0.0 if stage == 0 else (0.5 if stage < 3 else 1.0)
            w = 1.0 / 6.0 if (stage == 0 or stage == 3) else 1.0 / 3.0
            for a in range(13):
                ytmp[a] = new[a] + (c * hdt * dy[a] if stage > 0 else 0.0)
            PV.floor_at(floor, kf + c * hs, k0, theta_mj, F, g)
            holds, power, t_stop = _slip_rhs(model, ytmp, F, idx, st, sw, dy)
            if not holds or 0.5 * SLIP_TURN * hdt > t_stop:
                return -1.0, 0.0
            work += w * hdt * power
            for a in range(13):
                acc[a] = (w * dy[a]) if stage == 0 else acc[a] + w * dy[a]
        for a in range(13):
            new[a] += hdt * acc[a]
        nq = math.sqrt(new[3] * new[3] + new[4] * new[4] + new[5] * new[5] + new[6] * new[6])
        for a in range(3, 7):
            new[a] /= nq
        tilt = _tilt(new, NO)[0]
        if tilt >= OVERTURNING_ANGLE:
            return -1.0, 0.0
        tilt_max = max(tilt_max, tilt)
        _arms(new, model.body, sw.Q, r)
        for i in range(4):
            mine = (i == idx[0] and st[0] != 2) or (i == idx[1] and st[1] != 2)
            if not mine and new[2] + r[i, 2] <= 0.0:
                return -1.0, 0.0
    # the contact corners back on the floor as the next Moreau-Jean step predicts them (their normal
    # acceleration is zero, so their gaps drift only by the initial normal velocity and round-off)
    shift = 0.0
    for k in range(2):
        if st[k] != 2:
            ri = r[idx[k]]
            un = new[9] + new[10] * ri[1] - new[11] * ri[0]
            shift = max(shift, new[2] + ri[2] + 0.5 * dt * un)
    if shift > 0.0:
        new[2] -= shift + SETDOWN_MARGIN
    return tilt_max, work


@numba.njit(cache=True)
def _slip_pivot(act, touch, slip, P):
    """After a Moreau-Jean step: one corner or two down, exactly those solved in contact, loaded, at least one
    slipping (the phase :func:`_smooth_slip` integrates)."""
    n = 0
    sl = False
    for i in range(4):
        if act[i] != touch[i] or (touch[i] and P[i, 2] <= 0.0):
            return False
        n += touch[i]
        sl = sl or (touch[i] and slip[i])
    return sl and (n == 1 or n == 2)


@numba.njit(cache=True, inline='always')
def _same_slip(model, new, idx, st, a, ws, probe, sw):
    """Is the end state ``new`` of a smooth step on slipping corners still in its phase? Every corner not in
    contact above ``lift_gap``, and a Moreau-Jean probe step from it (``a``: its floor accelerations) solved with
    exactly the contact corners active, each loaded, slipping where it slipped (along the direction it slipped,
    in the half-plane of the end state's slip velocity) and stuck where it stuck. ``probe`` as in
    :func:`_same_phase`."""
    actp, Pp, sp, outp = probe.act, probe.P, probe.state, probe.out
    guess = ws.mask
    for i in range(4):
        guess[i] = (i == idx[0] and st[0] != 2) or (i == idx[1] and st[1] != 2)
    _arms(new, model.body, ws.Q1, ws.r1)
    for i in range(4):
        if not guess[i] and new[2] + ws.r1[i, 2] <= model.limits.lift_gap:
            return False
    outp[:] = 0.0
    sweeps = _step(model, new, a[0], a[1], a[2], model.numerics.dt, ws, actp, Pp, sp, outp, guess)
    if sweeps == 0 or sweeps > model.nsgs.max_sweeps:
        return False
    u = sw.vec[EVEC_U]  # the end state's corner velocities, from its last _slip_rhs (the arms of ``new``)
    for k in range(2):
        i = idx[k]
        if st[k] == 2:
            continue
        if not actp[i] or Pp[i, 2] <= 0.0:
            return False
        ri = ws.r[i]  # the probe's arms
        u0 = sp[7] + sp[11] * ri[2] - sp[12] * ri[1]
        u1 = sp[8] + sp[12] * ri[0] - sp[10] * ri[2]
        sl = math.hypot(u0, u1) > model.limits.velocity_tol
        if sl != (st[k] == 1) or (sl and u0 * u[3 * k] + u1 * u[3 * k + 1] <= 0.0):
            return False
    for i in range(4):  # (``guess`` is the contact solver's workspace: the membership again)
        if actp[i] and not ((i == idx[0] and st[0] != 2) or (i == idx[1] and st[1] != 2)):
            return False
    return True


@numba.njit(cache=True, inline='always')
def _smooth_slip(model, floor, state, touch, slip, k, n_max, ws, sw, probe, P, new, out):
    """A smooth step on one or two corners of which at least one slips (:func:`_slip_integrate`): from ``k`` to
    the next sample (at most ``n_max`` steps), halved while it leaves its phase (:func:`_same_slip`), down to
    ``pivot.MIN_STEPS``. Returns ``(steps, largest tilt)`` as :func:`_smooth` does; the friction work into
    ``out``."""
    idx, st = sw.idx, sw.st
    n_c = ZERO
    for i in range(4):
        if touch[i]:
            if n_c == 2:
                return 0, 0.0
            idx[n_c] = i
            st[n_c] = 1 if slip[i] else 0
            n_c += 1
    if n_c == 0:
        return 0, 0.0
    if n_c == 1:
        idx[1], st[1] = (idx[0] + 1) % 4, 2
    n = PV.step_end(floor, k, n_max) - k
    if n < 2:
        return -1, 0.0
    a = ws.a
    Pp = probe.P
    while True:
        out[OUT_SLIP_TRIED] += 1.0
        tilt, work = _slip_integrate(model, floor, state, idx, st, k, n, new, sw)
        if tilt >= 0.0:
            a[0], a[1], a[2] = _floor(floor, k + n, model.numerics.theta_mj)
            Pp[:, :] = P
            if _same_slip(model, new, idx, st, a, ws, probe, sw):
                P[:, :] = Pp
                out[OUT_SLIP_STEPS] += 1.0
                out[OUT_SLIP_SPAN] += n
                out[OUT_FRICTION_WORK] += work
                return n, tilt
        if n <= PV.MIN_STEPS:
            return 0, 0.0
        n = max(PV.MIN_STEPS, n // 2)


@numba.njit(cache=True, inline='always')
def _coarse_slide(model, floor, state, k, n_max, ws, probe, P, new, out, touch, slip):
    """A block sliding flat on its four corners: one Moreau-Jean step of up to ``n_max`` steps (to the next
    sample), kept if its contact problem is the same, all four corners active, solved by the closed-form
    flat slide or stick (:mod:`.pivot`, ``SLIDE_DTAU``) and kept on the floor (no corner's normal velocity above
    ``vel_tol``; a corner may carry none of the load, the four corners' loads being indeterminate). Returns the steps taken (0: none kept, -1: none
    tried)."""
    vel_tol, lift_gap = model.limits.velocity_tol, model.limits.lift_gap
    n = PV.step_end(floor, k, n_max) - k
    if n < 2:
        return -1
    a = ws.a
    PV.mean_floor(floor, k, n, model.numerics.theta_mj, a)
    actp, Pp, outp = probe.act, probe.P, probe.out
    for i in range(4):
        for c in range(3):
            Pp[i, c] = P[i, c] * n
    outp[:] = 0.0
    sweeps = _step(model, state, a[0], a[1], a[2], n * model.numerics.dt, ws, actp, Pp, new, outp, touch)
    if sweeps != 1 or outp[OUT_SLIDE_STEPS] + outp[OUT_STICK_STEPS] < 0.5:
        return 0
    for i in range(4):  # every corner active and kept on the floor (a corner may carry no load: see _slide_flat)
        ri = ws.r[i]
        if not actp[i] or abs(new[9] + new[10] * ri[1] - new[11] * ri[0]) > vel_tol:
            return 0
    _book(state, a, ws.Q1, ws.r1, ws.r, ws.Iw, ws.vec[VEC_VF], actp, Pp, new, out, touch, slip, vel_tol, lift_gap,
          model.body)
    for i in range(4):
        for c in range(3):
            P[i, c] = Pp[i, c] / n
    out[OUT_SLIDE_STEPS] += outp[OUT_SLIDE_STEPS]
    out[OUT_STICK_STEPS] += outp[OUT_STICK_STEPS]
    out[OUT_COARSE_STEPS] += 1.0
    out[OUT_COARSE_SPAN] += n
    return n


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
