"""Sticking in closed form (numba): one or two corners stuck while the others separate, every active corner stuck (an
edge turning about itself, a level base stopping), the friction along an edge split in the static cones. Units and
frames as in :mod:`opsrock.solvers.rigid3d.kernel` (SI, per unit mass).
"""

from __future__ import annotations

import math

import numpy as np

from opsrock.solvers.jitable import jitable
from opsrock.solvers.rigid3d.constants import (CONE_SLACK, ONE, TWO, ZERO)
from opsrock.solvers.rigid3d.geometry import (_cross_add, _delassus, _inv3)
from opsrock.solvers.rigid3d.workspace import (VEC_OM, VEC_V, VEC_VF)


@jitable
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


@jitable
def _flat_normals(act, r, F, T, P, B):
    """The normal impulses ``P[:, 2]`` of :func:`_stick_flat`: the least-norm solution of ``sum N = F_z``, ``sum N
    r_y = T_x + rz F_y``, ``sum N r_x = rz F_x - T_y`` (``F`` the total impulse, ``T`` the torque's horizontal part,
    both tuples; ``rz`` the corners' mean ``r_z``), on four corners moved along the free (alternating) direction to
    the nearest compressive distribution where there is one; an inactive corner's impulse zeroed. Returns ``(total,
    cx, cy)``: their sum and the sums ``sum N r_x``, ``sum N r_y`` (``total`` 0 and ``P`` untouched if ``B B^T`` is
    singular). ``B`` (6 x 6) is workspace."""
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
    if not _inv3(B[0:3], B[3:6]):  # (whole rows: C-contiguous views, the layout of _inv3's other calls, one compile)
        return 0.0, 0.0, 0.0
    g0, g1, g2 = F[2], T[0] + rz * F[1], rz * F[0] - T[1]
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
    return total, cx, cy


@jitable
def _stick_flat(act, r, Iw, vf, P, B):
    """Impulses that stop a block standing on three or four corners of its level base: the total impulse
    ``-vf`` (per unit mass) and torque ``-I omega_f`` are fixed; with the corners in one plane (``r_z`` the
    same, ``rz``) the tangential impulses enter the horizontal torques through their total only, so the normal
    impulses are the least-norm solution of ``sum N = F_z``, ``sum N r_y = T_x + rz F_y``, ``sum N r_x = rz F_x
    - T_y`` (:func:`_flat_normals`); the tangential impulses are then proportional to the normal ones, ``P_t,i =
    N_i (c + kappa z x (rho_i - rho_bar))`` (a translation and a twist about the centre of pressure ``rho_bar``),
    ``c`` and ``kappa`` from the total and the vertical torque. False if the normal impulses do not add up to a
    compressive total. On four corners a distribution with a pulling corner is moved along the free (alternating)
    direction to the nearest compressive one where there is one (the least-norm one is compressive only for a
    centre of pressure inside the base's inscribed diamond). ``B`` (6 x 6) is workspace."""
    F0, F1, F2 = -vf[0], -vf[1], -vf[2]
    T0 = -(Iw[0, 0] * vf[3] + Iw[0, 1] * vf[4] + Iw[0, 2] * vf[5])
    T1 = -(Iw[1, 0] * vf[3] + Iw[1, 1] * vf[4] + Iw[1, 2] * vf[5])
    T2 = -(Iw[2, 0] * vf[3] + Iw[2, 1] * vf[4] + Iw[2, 2] * vf[5])
    if F2 <= 0.0:
        return False
    total, cx, cy = _flat_normals(act, r, (F0, F1, F2), (T0, T1), P, B)
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


@jitable
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


@jitable
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


@jitable
def _edge_split(Pa, Pb, e, ca, cb, xa, mu):
    """Corner ``a``'s share of the impulse along an edge of unit direction ``e`` (a 3-tuple) shared by two stuck
    corners (which may carry any split of it): the share nearest ``xa`` that keeps both impulses in the static cone,
    ``xa`` if none does. ``Pa``, ``Pb`` are the impulses, ``ca``, ``cb`` their components along ``e``."""
    la, ha = _cone_interval(Pa, e[0], e[1], e[2], ca, mu)
    lb, hb = _cone_interval(Pb, e[0], e[1], e[2], cb, mu)
    total = ca + cb
    lo, hi = max(la, total - hb), min(ha, total - lb)
    if lo > hi:
        return xa
    return min(max(xa, lo), hi)


@jitable
def _stick_all(cw, act, n_act, P, fric):
    """Try every active corner stuck, in closed form: with two corners the block may only turn about the line
    through them (the velocity closest to the free one in the kinetic metric, one freedom), with three or four
    it stops; the impulses are the least-norm ones that make that velocity change (no self-equilibrated
    friction "squeeze": the statically indeterminate part is left at zero), with the friction along an edge,
    and on three or four corners all of it, split in proportion to the normal impulses (:func:`_stick_flat`).
    Accepted, into ``V``, ``Om`` (``cw.vec`` rows ``VEC_V``, ``VEC_OM``) and ``P``, if every normal impulse is
    compressive and every tangential one lies in the static cone (``fric``: :class:`.model.Friction`); else False
    (NSGS then solves the step). ``cw`` is the step's :class:`.workspace.Contact`: the arms ``r``, the inertia
    ``Iw``, the free velocity (row ``VEC_VF``), ``A6`` workspace."""
    r, Iw, vec = cw.r, cw.Iw, cw.vec
    vf, V, Om = vec[VEC_VF], vec[VEC_V], vec[VEC_OM]
    mu_s, stick_only = fric.mu_s, fric.infinite
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
                dl = _edge_split(P[i1], P[i2], (e0, e1, e2), c1, c2, c1 + dl, mu_s) - c1
            P[i1, 0], P[i1, 1], P[i1, 2] = P[i1, 0] + dl * e0, P[i1, 1] + dl * e1, P[i1, 2] + dl * e2
            P[i2, 0], P[i2, 1], P[i2, 2] = P[i2, 0] - dl * e0, P[i2, 1] - dl * e1, P[i2, 2] - dl * e2
    else:  # three or four corners (a level base): the block stops
        if not _stick_flat(act, r, Iw, vf, P, cw.A6):
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


@jitable
def _stick_subset(cw, act, guess, landing, n_act, P, fric, tol):
    """The active corners that were down (``act`` and ``guess``; with ``landing`` those that were not: a rocking
    impact, where the landing edge takes the load and the pivot lifts), one or two of them and fewer than
    ``n_act``, stuck and loaded, the other active corners without impulse: accepted, into ``V``, ``Om``, ``P``
    and ``act`` (the others dropped), if those others separate, ``u_n >= -tol`` (m/s), which with the stuck
    corners' loads in their cones solves the step's contact problem. One corner: ``P = -W^-1 u_free``; two:
    :func:`_stick_all`. ``cw`` is the step's :class:`.workspace.Contact`."""
    sub = cw.mask
    n_sub = ZERO
    for i in range(4):
        sub[i] = act[i] and (guess[i] != landing)
        n_sub += sub[i]
    if n_sub == 0 or n_sub > 2 or n_sub == n_act:
        return False
    return _stick_mask(cw, act, sub, n_sub, P, fric, tol)


@jitable
def _stick_mask(cw, act, sub, n_sub, P, fric, tol):
    """The corners of ``sub`` (one or two of the active ones) stuck and loaded, the other active corners
    separating (:func:`_stick_subset`)."""
    r, Iinv, vec = cw.r, cw.Iinv, cw.vec
    vf, V, Om = vec[VEC_VF], vec[VEC_V], vec[VEC_OM]
    mu_s, stick_only = fric.mu_s, fric.infinite
    if n_sub == 2:
        if not _stick_all(cw, sub, TWO, P, fric):
            return False
    else:
        i = 0
        while not sub[i]:
            i += 1
        W, Wi = cw.Wd[i], cw.Wi[i]
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


@jitable
def _stick_single(cw, act, P, fric, tol):
    """Two active corners whose edge cannot carry the step stuck (a corner pulls): each alone stuck, the other
    separating (:func:`_stick_mask`), the lower one first (a block turning about a corner with the edge's other
    corner grazing the floor)."""
    r = cw.r
    i1, i2 = _first_two(act)
    if r[i2, 2] < r[i1, 2]:
        i1, i2 = i2, i1
    sub = cw.mask
    for first in (i1, i2):
        for i in range(4):
            sub[i] = i == first
        if _stick_mask(cw, act, sub, ONE, P, fric, tol):
            return True
    return False
