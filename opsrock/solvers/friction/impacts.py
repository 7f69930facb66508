"""The impact law at ``theta = 0``, compiled (numba), in the units of :mod:`.modes`.

A block rocking (or slide-rocking) about corner ``s`` returns to ``theta = 0`` and its other corner
``c = -s`` strikes the floor. The impulse acts at ``c`` alone, with no bounce (Newton's law with
zero normal restitution: the corner's normal velocity after the impact is zero) and Coulomb's law at
impulse level (Moreau's impact law with friction for one contact):

* **stick**: the impulse that stops the corner, ``P = -W^-1 U``, with ``W`` the contact's inverse
  effective mass (Delassus) matrix and ``U = (U_N, U_T)`` the corner's velocity before; accepted if
  ``|P_T| <= mu P_N``. For a block that rocked without slip this is Housner's (1963) law: it
  conserves the angular momentum about ``c`` and gives ``theta'+ = e_H theta'-``,
  ``e_H = 1 - 2 m b² / I_O`` (``1 - 3/2 sin²(alpha)`` for a homogeneous block); the mass distribution enters
  as ``kap = R² / r²`` (:mod:`.modes`), the rotation's entry of the inverse mass matrix;
* **slip**: ``P_T = -sig mu_k P_N`` with ``P_N = -U_N / (W_NN - sig mu_k W_NT)``, for the slip
  direction ``sig`` whose impulse is compressive and whose slip after is along ``sig``. It conserves
  nothing but dissipates (docs/guide/friction.md).

If the old pivot would then be driven into the floor, both corners land (``theta'+ = 0``): a flat
landing, with the friction of the summed normal impulse deciding whether the base sticks or slides
on. The restitution factor ``f = e / e_H`` of the block then multiplies the angular velocity after
the impact (the slip velocity is the friction law's): for ``f = 1`` the law is the rigid-body one,
for the paper's ``f = 0.95`` it loses the extra energy the paper's ``e`` does.
"""

from __future__ import annotations

import math


from opsrock.solvers.friction.modes import REST, ROCK, SLIDE, SLIDE_ROCK
from opsrock.solvers.jitable import jitable

#: Relative round-off margin on the impact law's inequalities.
_TOL = 1e-12



@jitable
def single_contact(gn, gt, u_n, u_t, mu_s, mu_k, kap):
    """Impulse ``(P_N, P_T, ok)`` at one corner whose velocity is ``(u_n < 0, u_t)`` (units of ``m R p``),
    stick if friction allows it, else slip. ``gn`` and ``gt`` are the rotation's entries of the corner's
    normal and tangential Jacobian rows (``h sin(theta) - c b cos(theta)`` and ``-(c b sin(theta) + h
    cos(theta))``, over ``R``); with the mass matrix ``diag(1, 1, 1/kap)`` the Delassus matrix is
    ``W = [[1 + kap gn², kap gn gt], [kap gn gt, 1 + kap gt²]]`` (``kap = 3`` homogeneous)."""
    wnn = 1.0 + kap * gn * gn
    wtt = 1.0 + kap * gt * gt
    wnt = kap * gn * gt
    det = wnn * wtt - wnt * wnt  # = 1 + kap (gn² + gt²) > 0; exactly kap + 1 at theta = 0
    p_n = -(wtt * u_n - wnt * u_t) / det
    p_t = -(-wnt * u_n + wnn * u_t) / det
    if p_n > 0.0 and abs(p_t) <= mu_s * p_n * (1.0 + _TOL):
        return p_n, p_t, True
    if mu_k == math.inf:
        # no slip, and the impulse that would stop the corner pulls: the rigid, infinitely rough impact
        # has no solution (Painlevé's paradox at impulse level); reported, never forced
        return 0.0, 0.0, False
    first = 1.0 if u_t > 0.0 else -1.0
    for sig in (first, -first):
        den = wnn - sig * mu_k * wnt
        if den <= 0.0:
            continue
        p_n = -u_n / den
        p_t = -sig * mu_k * p_n
        u_t_after = u_t + wnt * p_n + wtt * p_t
        if p_n >= 0.0 and sig * u_t_after >= -_TOL * abs(u_n):
            return p_n, p_t, True
    return 0.0, 0.0, False


@jitable
def _flat_landing(vx, vy, om, sa, ca, mu_s, mu_k, kap):
    """Both corners land (``theta'+ = 0``, ``y'+ = 0``): ``(mode, sig, w+, ok)`` with the base at rest
    or sliding on at ``w+``; ``ok`` is False if no compressive pair of corner impulses does it."""
    p_n = -vy
    if abs(vx) <= mu_s * p_n:
        p_t = -vx
    else:
        p_t = -(1.0 if vx > 0.0 else -1.0) * mu_k * p_n
    # angular impulse about the centre of mass: -om / kap = -sa (P_+ - P_-) - ca P_T
    diff = (om / kap - ca * p_t) / sa
    p_plus = 0.5 * (p_n + diff)
    p_minus = 0.5 * (p_n - diff)
    tol = -_TOL * abs(p_n)
    if p_n < 0.0 or p_plus < tol or p_minus < tol:
        return REST, 0.0, 0.0, False
    w = vx + p_t
    if w == 0.0:
        return REST, 0.0, 0.0, True
    return SLIDE, (1.0 if w > 0.0 else -1.0), w, True


@jitable
def contact_at_zero(vx, vy, om, bd):
    """The impact of a block (:class:`~.modes.Body` ``bd``) at ``theta = 0`` whose centre of mass moves at ``(vx,
    vy)`` and turns at ``om`` (units of ``R p``, ``p``): ``(mode, s, sig, om, w, ok)``.

    Both corners are at the floor. The impulse acts at one corner (each approaching corner is tried, the
    faster first: accepted if the other corner is not then driven into the floor) or at both (a flat
    landing, :func:`_flat_landing`); with no approaching corner there is no impulse and the block rocks or
    slide-rocks on the corner its rotation lowers. ``ok`` is False if none of these obeys the laws."""
    sa, ca, mu_s, mu_k, f, kap = bd.sa, bd.ca, bd.mu_s, bd.mu_k, bd.f_rest, bd.kap
    u_plus, u_minus = vy - sa * om, vy + sa * om  # normal velocities of the corners c = +1 and c = -1
    first = 1.0 if u_plus <= u_minus else -1.0
    for c in (first, -first):
        u_n = vy - c * sa * om
        if u_n >= 0.0:
            continue
        p_n, p_t, ok = single_contact(-c * sa, -ca, u_n, vx - ca * om, mu_s, mu_k, kap)
        if not ok:
            continue
        om_after = om + kap * (-c * sa * p_n - ca * p_t)
        if vy + p_n + c * sa * om_after < -_TOL * abs(u_n):  # the other corner, -c, would go into the floor
            continue
        w_after = vx + p_t - ca * om_after
        if abs(w_after) <= _TOL * abs(u_n):
            return ROCK, c, 0.0, f * om_after, 0.0, True
        return SLIDE_ROCK, c, (1.0 if w_after > 0.0 else -1.0), f * om_after, w_after, True
    if min(u_plus, u_minus) >= 0.0:  # nothing approaches: no impulse
        c = 1.0 if om > 0.0 else -1.0
        w = vx - ca * om
        return SLIDE_ROCK if w != 0.0 else ROCK, c, (1.0 if w > 0.0 else -1.0) if w != 0.0 else 0.0, om, w, True
    mode, sig, w_after, ok = _flat_landing(vx, vy, om, sa, ca, mu_s, mu_k, kap)
    return mode, 0.0, sig, 0.0, w_after, ok


@jitable
def impact(s, om, w, bd):
    """The state after corner ``-s`` strikes: ``(mode, s, sig, om, w, ok)`` (:func:`contact_at_zero`).

    ``om`` (< 0 along ``s``) and ``w`` are the rotation rate and the pivot's slip velocity just before.
    The new mode is ``ROCK`` or ``SLIDE_ROCK`` about ``-s`` (``sig`` the new pivot's slip direction),
    or, after a flat landing, ``REST`` or ``SLIDE``. ``ok`` is False if the law has no solution; ``bd`` the
    :class:`~.modes.Body`."""
    return contact_at_zero(w + bd.ca * om, s * bd.sa * om, om, bd)


@jitable
def landing(th, om, vx, vy, bd):
    """A block in free flight lands: ``(mode, s, sig, om, w, ok)`` after the impact of its lower corner
    ``c = sgn(theta)`` (``theta``, ``om``: rotation and rate; ``vx``, ``vy``: the centre of mass's
    velocity relative to the floor, units of ``R p``), by the same law as :func:`impact` in the general
    position; at ``theta = 0`` by :func:`contact_at_zero`. The new mode
    rocks, or slide-rocks, about ``c`` (``w`` the corner's slip velocity); ``bd`` the :class:`~.modes.Body`."""
    if th == 0.0:
        return contact_at_zero(vx, vy, om, bd)
    sa, ca, mu_s, mu_k, f, kap = bd.sa, bd.ca, bd.mu_s, bd.mu_k, bd.f_rest, bd.kap
    c = 1.0 if th > 0.0 else -1.0
    sn, cs = math.sin(th), math.cos(th)
    gn = ca * sn - c * sa * cs
    gt = -(c * sa * sn + ca * cs)
    u_n = vy + gn * om
    u_t = vx + gt * om
    if u_n >= 0.0:  # grazing: no impulse
        p_n, p_t = 0.0, 0.0
    else:
        p_n, p_t, ok = single_contact(gn, gt, u_n, u_t, mu_s, mu_k, kap)
        if not ok:
            return REST, 0.0, 0.0, 0.0, 0.0, False
    om_after = om + kap * (gn * p_n + gt * p_t)
    w_after = u_t + (1.0 + kap * gt * gt) * p_t + kap * gn * gt * p_n
    if abs(w_after) <= _TOL * max(abs(u_n), abs(u_t)):
        return ROCK, c, 0.0, f * om_after, 0.0, True
    return SLIDE_ROCK, c, (1.0 if w_after > 0.0 else -1.0), f * om_after, w_after, True


__all__ = ["contact_at_zero", "impact", "landing", "single_contact"]
