"""Sliding and slipping in closed form (numba): a level block sliding on three or four corners, and two corners of
which one or both slip, for consistent slip directions. Units and frames as in :mod:`opsrock.solvers.rigid3d.kernel`
(SI, per unit mass).
"""

from __future__ import annotations

import math

import numpy as np
from numba import types
from numba.extending import overload

from opsrock.solvers.jitable import HELPER_OPTIONS, jitable
from opsrock.solvers.rigid3d.constants import (ALIGN_TOL, CONE_SLACK, EDGE_STATUSES, FD_STEP, FLAT_ROUNDOFF, LIMIT_MU,
                                               NEWTON_TOL, OUT_LIMIT_STEPS, PIVOT_TOL, SIX, ZERO)
from opsrock.solvers.rigid3d.geometry import (_cross_add, _delassus_pair, _inv3)
from opsrock.solvers.rigid3d.sticking import _shift_range
from opsrock.solvers.rigid3d.workspace import (EVEC_P6, EVEC_Q, EVEC_U, EVEC_Y, VEC_OM, VEC_V, VEC_VF, VEC_Y6,
                                               FlatWork)


@jitable
def _solve6(A, y):
    """Solve ``A y_new = y`` in place (6 x 6, :func:`_solve_n`)."""
    return _solve_n(A, y, SIX)


@jitable
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


@jitable
def _flat_system(cw, fw, n, mu_k):
    """The linear momentum equations of :func:`_slide_flat` for the slip directions ``fw.sdir``: ``fw.xs`` gets the
    normal impulses of the ``n`` corners ``fw.idx`` and ``(V_x, V_y, omega_z)``; False if singular. ``cw`` is the
    step's :class:`.workspace.Contact` (arms ``r``, inertia ``Iw``, free velocity row ``VEC_VF``, scratch ``A6`` and
    row ``VEC_Y6``), ``fw`` the slide's :class:`.workspace.FlatWork`."""
    r, Iw, A6, sdir, Am = cw.r, cw.Iw, cw.A6, fw.sdir, fw.Am
    vf, y6 = cw.vec[VEC_VF], cw.vec[VEC_Y6]
    idx, xs, zs = fw.idx, fw.xs, fw.zs
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


@jitable
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


@jitable
def _flat_eval(cw, fw, n, mu_k, x, g):
    """``g = G(x) - x`` for the velocities ``x = (V_x, V_y, omega_z)``: the slip directions of ``x``, then the
    velocities :func:`_flat_system` gives for them. False if a corner does not slip or the system is singular."""
    if _flat_directions(x[0], x[1], x[2], fw.idx, n, cw.r, fw.sdir) < 0.0:
        return False
    if not _flat_system(cw, fw, n, mu_k):
        return False
    xs = fw.xs
    for a in range(3):
        g[a] = xs[n + a] - x[a]
    return True


@jitable
def _flat_newton(cw, fw, n, mu_k, x):
    """Newton on ``G(x) = x`` (:func:`_flat_eval`) from ``x``, with a forward-difference Jacobian and step
    halving, to ``1e-12`` of the velocities' scale. Returns True with ``fw.xs`` and ``fw.sdir`` of the solution."""
    r, vf, idx = cw.r, cw.vec[VEC_VF], fw.idx
    g = np.zeros(3)
    g1 = np.zeros(3)
    x1 = np.zeros(3)
    J = np.zeros((3, 3))
    Ji = np.zeros((3, 3))
    scale = max(abs(x[0]), abs(x[1]), abs(vf[0]), abs(vf[1]), abs(vf[2]))
    arm = math.sqrt(r[idx[0], 0] ** 2 + r[idx[0], 1] ** 2)
    if not _flat_eval(cw, fw, n, mu_k, x, g):
        return False
    for it in range(20):
        res = max(abs(g[0]), abs(g[1]), arm * abs(g[2]))
        if res <= NEWTON_TOL * scale:
            return _flat_eval(cw, fw, n, mu_k, x, g)
        for j in range(3):
            hj = FD_STEP * (scale / arm if j == 2 else scale)
            for a in range(3):
                x1[a] = x[a] + (hj if a == j else 0.0)
            if not _flat_eval(cw, fw, n, mu_k, x1, g1):
                return False
            for a in range(3):
                J[a, j] = (g1[a] - g[a]) / hj
        if not _inv3(J, Ji):
            return False
        lam = 1.0
        for half in range(8):
            for a in range(3):
                x1[a] = x[a] - lam * (Ji[a, 0] * g[0] + Ji[a, 1] * g[1] + Ji[a, 2] * g[2])
            ok = _flat_eval(cw, fw, n, mu_k, x1, g1)
            if ok and max(abs(g1[0]), abs(g1[1]), arm * abs(g1[2])) < res:
                break
            lam *= 0.5
        if not ok:
            return False
        for a in range(3):
            x[a] = x1[a]
            g[a] = g1[a]
    return False


def _slide_flat(cw, act, P, mu_k, sdir, Am):
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
    ``cw`` is the step's :class:`.workspace.Contact` (arms ``r``, free velocity row ``VEC_VF``; the velocities into
    rows ``VEC_V``, ``VEC_OM``); ``sdir`` (4 x 2: the slip directions) and ``Am`` (6 x 7) are workspace."""
    r, vec = cw.r, cw.vec
    vf, V, Om = vec[VEC_VF], vec[VEC_V], vec[VEC_OM]
    fw = FlatWork(np.empty(4, dtype=np.int64), np.empty(7), np.empty(7), sdir, Am)
    idx, xs = fw.idx, fw.xs
    n = ZERO
    for i in range(4):
        if act[i]:
            idx[n] = i
            n += 1
    if _flat_directions(vf[0], vf[1], vf[5], idx, n, r, sdir) < 0.0:
        return False
    settled = False
    for it in range(30):
        if not _flat_system(cw, fw, n, mu_k):
            return False
        moved = _flat_directions(xs[n], xs[n + 1], xs[n + 2], idx, n, r, sdir)
        if moved < 0.0:
            return False
        if moved < NEWTON_TOL:
            settled = True
            break
    if not settled:
        x = np.array([xs[n], xs[n + 1], xs[n + 2]])
        if not _flat_newton(cw, fw, n, mu_k, x):
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


def _never_slide_flat(cw, act, P, mu_k, sdir, Am):
    """:func:`_slide_flat` without its scratch (``sdir`` and ``Am`` None: the kernel's specialisation for infinite
    friction, which never slides flat): not tried."""
    return False


@overload(_slide_flat, jit_options=HELPER_OPTIONS)
def _slide_flat_typed(cw, act, P, mu_k, sdir, Am):
    """The implementation of :func:`_slide_flat` numba compiles for these argument types: none of the flat slide's
    if its scratch is None (infinite friction; issue 43: about a tenth of the kernel's compile)."""
    return _never_slide_flat if isinstance(sdir, types.NoneType) else _slide_flat


@jitable
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


@jitable
def _edge_eval(ew, st, mu_k, f):
    """The impulses ``P6`` and corner velocities ``u`` (``ew.vec`` rows ``EVEC_P6``, ``EVEC_U``) of
    :func:`_edge_system` for the slip directions ``ew.sdir``, and per slipping corner ``k`` the angle from its
    direction ``s`` to its tangential velocity, ``f[k]`` in (-pi, pi] (zero where the friction opposes the slip).
    False if the system is singular. ``ew`` is the :class:`.workspace.EdgeWork` of :func:`_edge_slip`."""
    sdir, D, A, cols = ew.sdir, ew.D, ew.A, ew.cols
    q, y, P6, u = ew.vec[EVEC_Q], ew.vec[EVEC_Y], ew.vec[EVEC_P6], ew.vec[EVEC_U]
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


@jitable
def _edge_try(ew, st, mu_s, mu_k):
    """One status pair of :func:`_edge_slip`: the slip directions brought to consistency (each along that corner's
    tangential velocity; a few fixed-point steps ``s <- u_t / |u_t|``, then Newton on the directions' angles with a
    finite-difference Jacobian and step halving, the fixed point alone stalling or flipping where the two corners'
    slips are strongly coupled), then the statuses checked (a stuck corner pressing inside the static cone, a
    slipping one pressing and slipping along its ``s``, an open one not approaching). Returns True with the impulses
    ``P6`` and velocities ``u`` of the two corners (``ew.vec`` rows ``EVEC_P6``, ``EVEC_U``); ``ew`` is the
    :class:`.workspace.EdgeWork` of :func:`_edge_slip`."""
    sdir, fw = ew.sdir, ew.fw
    P6, u = ew.vec[EVEC_P6], ew.vec[EVEC_U]
    f, f1, ang, J = fw[0], fw[1], fw[2], fw[3:5]
    done = False
    for it in range(5):
        if not _edge_eval(ew, st, mu_k, f):
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
        if not _edge_eval(ew, st, mu_k, f):
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
                if not _edge_eval(ew, st, mu_k, f1):
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
                if not _edge_eval(ew, st, mu_k, f1):
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


@jitable
def _edge_slip(cw, ew, act, P, fric, out):
    """Two active corners, one stuck and one slipping, both slipping, or one slipping and the other leaving the
    floor, in closed form for consistent slip directions (a block rocking on an edge while the edge slips or twists
    about one of its corners; Gauss-Seidel converges slowly there, the two corners being strongly coupled through
    the body). The status pairs are tried in turn (stick-slip, slip-stick, slip-slip, open-slip, slip-open; the
    pairs stick-stick and stick-open have closed forms of their own), the slip directions from those of the corners'
    friction impulses ``P`` (warm start) or free velocities; the first whose statuses hold is the step's solution of
    the contact problem (into ``V``, ``Om``, ``P``), else False (NSGS then solves it). With infinite friction
    (``stick_only``) a slipping corner is :func:`_local`'s infinite-friction limit (``mu_k = LIMIT_MU``, counted in
    ``OUT_LIMIT_STEPS``) and a stuck one needs only to press. ``cw`` is the step's :class:`.workspace.Contact`
    (arms ``r``, ``Iinv``, free velocity row ``VEC_VF``; the velocities into rows ``VEC_V``, ``VEC_OM``), ``ew``
    this one's scratch (:class:`.workspace.EdgeWork`), ``ew.last[0]`` the pair that held last (tried first)."""
    r, Iinv = cw.r, cw.Iinv
    vf, V, Om = cw.vec[VEC_VF], cw.vec[VEC_V], cw.vec[VEC_OM]
    mu_s, mu_k, stick_only = fric.mu_s, fric.mu_k, fric.infinite
    if stick_only:
        mu_s, mu_k = np.inf, LIMIT_MU
    D, q, P6, sdir = ew.D, ew.vec[EVEC_Q], ew.vec[EVEC_P6], ew.sdir
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
        if ok and _edge_try(ew, st, mu_s, mu_k):
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
