"""The contact problem of a step by nonsmooth Gauss-Seidel (numba): one corner's exact local solution (stick in the
static cone, else slip with the kinetic coefficient, its direction by Newton or the secular equation) and the sweeps
over the active corners. Units and frames as in :mod:`opsrock.solvers.rigid3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import math


from opsrock.solvers.jitable import jitable
from opsrock.solvers.rigid3d.constants import (CONE_SLACK, DIRECTION_TOL, LIMIT_MU, OUT_LIMIT_STEPS, OUT_NSGS_EXTRA,
                                               OUT_NSGS_LOOSE, SECULAR_TOL, SLIP_ANGLE_TOL, SLIP_STEP_TOL)
from opsrock.solvers.rigid3d.geometry import _cross_add
from opsrock.solvers.rigid3d.workspace import (VEC_OM, VEC_PN, VEC_V, VEC_Y6)


@jitable
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


@jitable
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


@jitable
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


@jitable
def _nsgs(cw, act, P, fric, tol, max_iter, out, single):
    """Nonsmooth Gauss-Seidel (Jean & Moreau) over the active corners ``act``: each corner's local problem solved
    exactly (:func:`_local`, friction ``fric``: :class:`.model.Friction`) with the others' impulses fixed, the body's
    velocity (``cw.vec`` rows ``VEC_V``, ``VEC_OM``) updated after each, sweeps until no impulse changes by more than
    ``tol`` (m/s). Warm-started from ``P`` (the previous step's impulses). Returns the number of sweeps
    (``max_iter + 1``: not converged); with a ``single`` active corner one sweep is exact. ``cw`` is the step's
    :class:`.workspace.Contact` (arms ``r``, Delassus blocks ``Wd`` and inverses ``Wi``, ``Iinv``)."""
    r, Wd, Wi, Iinv, vec = cw.r, cw.Wd, cw.Wi, cw.Iinv, cw.vec
    V, Om, q, Pn = vec[VEC_V], vec[VEC_OM], vec[VEC_Y6], vec[VEC_PN]
    mu_s, mu_k, stick_only = fric.mu_s, fric.mu_k, fric.infinite
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


@jitable
def _solve_contacts(cw, act, P, fric, tol, nsgs, out, single):
    """NSGS (:func:`_nsgs`) to ``tol`` in ``nsgs.max_sweeps`` sweeps; failing that, on for up to ``nsgs.extra_sweeps``
    sweeps more (at least one) to the looser ``tol * nsgs.loose_tol / nsgs.tol`` (a block at the stick-slip limit on
    three or four corners, whose impulses are statically indeterminate, makes Gauss-Seidel converge slowly, not
    fail), counted in ``OUT_NSGS_LOOSE``. Returns the sweeps (``nsgs.max_sweeps + 1``: not converged)."""
    max_iter = nsgs.max_sweeps
    sweeps = _nsgs(cw, act, P, fric, tol, max_iter, out, single)
    if sweeps <= max_iter:
        return sweeps
    extra = max(1, nsgs.extra_sweeps)
    more = _nsgs(cw, act, P, fric, tol * nsgs.loose_tol / nsgs.tol, extra, out, single)
    if more > extra:
        return max_iter + 1
    out[OUT_NSGS_LOOSE] += 1.0
    out[OUT_NSGS_EXTRA] += more
    return max_iter
