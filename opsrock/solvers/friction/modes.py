"""The equations of motion of each contact mode, compiled (numba), in the units of the kernel.

Units: time ``tau = p t`` (``p = sqrt(m g R / I_O)``), lengths in ``R``, floor accelerations in ``g``
(``ah = a_h / g``; ``gv = 1 + a_v / g``, the effective gravity), forces in ``m g``, energies in
``m g R``. The block's mass distribution enters as ``kap = R² / r²`` (``r`` the radius of gyration about
the centre of mass; 3 for a homogeneous block), through ``k = R p² / g = kap / (kap + 1)`` (3/4
homogeneous) and ``1 / k``. With these, the rocking equation has no constants left: ``theta'' = -(gv
sin(phi) + ah cos(phi))``, ``phi = s alpha - theta``, and the kinetic energy is ``k/2 (x'² + y'² +
theta'²/kap)`` (``3/8 (x'² + y'² + theta'²/3)`` homogeneous).

Generalised state of a moving mode: rotation ``th`` and its rate ``om``; the base's horizontal
displacement relative to the floor ``u`` (the pivot corner's while one corner is up, the whole
base's while both are down) and its rate ``w`` (the slip velocity). The derivation of every line is
in docs/guide/friction.md.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from opsrock.solvers.jitable import jitable

#: Mode ids; their order is :data:`opsrock.result.MODES`. numpy integers, so that numba types them as ``int64``, not
#: as literals: a literal mode passed to a compiled function (``_energy(FLIGHT, ...)``) made numba compile it, and
#: all it calls, once more (issue 43: cold compile time).
REST = np.int64(0)
SLIDE = np.int64(1)
ROCK = np.int64(2)
SLIDE_ROCK = np.int64(3)
FLIGHT = np.int64(4)

#: The block as the equations take it: ``alpha`` (rad), its sine, cosine and tangent (``b/h``), static and kinetic
#: friction (``inf``: no slip), the restitution factor ``f_rest = e / e_H`` of the impact law (:mod:`.impacts`) and
#: ``kap = R² / r²``. Built by :func:`body`.
Body = namedtuple("Body", ["alpha", "sa", "ca", "beta", "mu_s", "mu_k", "f_rest", "kap"])
#: The state of a moving mode at time ``tau`` (units of 1/p): ``mode``, pivot ``s`` and slip direction ``sig``
#: (+-1 or 0), rotation ``th`` (rad) and its rate ``om`` (units of p), the base's displacement ``u`` (units of R)
#: and slip velocity ``w`` (units of R p).
Motion = namedtuple("Motion", ["mode", "s", "sig", "th", "om", "u", "w", "tau"])


@jitable
def body(alpha, mu_s, mu_k, f_rest, kap):
    """The :class:`Body` of a block of slenderness ``alpha`` (rad), friction ``mu_s``, ``mu_k``, restitution factor
    ``f_rest`` and ``kap`` (dimensionless)."""
    return Body(float(alpha), math.sin(alpha), math.cos(alpha), math.tan(alpha), float(mu_s), float(mu_k),
                float(f_rest), float(kap))


@jitable
def accelerations(m, ah, gv, bd):
    """``(theta'', u'', input power, friction power)`` of the :class:`Motion` ``m`` of a moving mode (``SLIDE``,
    ``ROCK``, ``SLIDE_ROCK``) of the :class:`Body` ``bd`` under ``ah``, ``gv``; pivot ``s`` and slip direction
    ``sig`` are +-1. The powers are the rates of the floor's inertial work and of the friction dissipation (units
    of ``m g R`` per tau)."""
    mode, s, sig, th, om, w = m.mode, m.s, m.sig, m.th, m.om, m.w
    alpha, mu_k, kap = bd.alpha, bd.mu_k, bd.kap
    c = (kap + 1.0) / kap  # 1 / k, 4/3 homogeneous
    if mode == SLIDE:
        return 0.0, c * (-ah - sig * mu_k * gv), -ah * w, mu_k * gv * abs(w)
    phi = s * alpha - th
    sp = math.sin(phi)
    cp = math.cos(phi)
    av = gv - 1.0
    if mode == ROCK:
        return -(gv * sp + ah * cp), 0.0, -(ah * cp + av * sp) * om, 0.0
    k = kap / (kap + 1.0)
    q = sp - mu_k * sig * cp
    thdd = -c * q * (gv - k * om * om * cp) / (1.0 / kap + sp * q)
    normal = gv + k * (sp * thdd - cp * om * om)
    udd = c * (-ah - mu_k * sig * normal) - cp * thdd - sp * om * om
    return thdd, udd, -ah * (w + cp * om) - av * sp * om, mu_k * normal * abs(w)


@jitable
def rock_forces(s, th, om, ah, gv, alpha, kap):
    """``(F, N)``: the horizontal and vertical force of the floor on a stuck pivot ``s`` while the
    block rocks (units of ``m g``; ``F`` positive along +x). Rocking needs ``N > 0`` and ``|F| <= mu N``."""
    phi = s * alpha - th
    sp = math.sin(phi)
    cp = math.cos(phi)
    thdd = -(gv * sp + ah * cp)
    k = kap / (kap + 1.0)
    return ah + k * (cp * thdd + sp * om * om), gv + k * (sp * thdd - cp * om * om)


@jitable
def slide_rock_normal(s, sig, th, om, gv, alpha, mu_k, kap):
    """``N``: the normal force on a slipping pivot ``s`` (slip direction ``sig``), units of ``m g``."""
    phi = s * alpha - th
    sp = math.sin(phi)
    cp = math.cos(phi)
    c, k = (kap + 1.0) / kap, kap / (kap + 1.0)
    q = sp - mu_k * sig * cp
    thdd = -c * q * (gv - k * om * om * cp) / (1.0 / kap + sp * q)
    return gv + k * (sp * thdd - cp * om * om)


@jitable
def critical_friction(lam, beta, kap):
    """The static friction a block at rest needs to start rocking without slip when
    ``|a_h| / (g + a_v) = lam`` (``> beta = b/h``): ``[lam (1 + (kap + 1) beta²) + kap beta] / [kap + 1 + beta² +
    kap lam beta]``, ``[lam (1 + 4 beta²) + 3 beta] / [4 + beta² + 3 lam beta]`` for a homogeneous block (``kap =
    3``; docs/guide/friction.md, mode initiation)."""
    return (lam * (1.0 + (kap + 1.0) * beta * beta) + kap * beta) / ((kap + 1.0) + beta * beta + kap * lam * beta)


@jitable
def start_mode(ah, gv, beta, mu_s, mu_k, kap):
    """The mode a block at rest (or whose base has just stopped slipping) takes under ``ah``, ``gv``:
    ``(mode, s, sig)`` with the pivot ``s`` and slip direction ``sig`` (0 where they do not apply).

    Rest while ``|ah| <= mu_s gv`` and ``|ah| <= beta gv``; else, towards ``-sgn(ah)``: slide if
    ``mu_s < beta``; rock if ``mu_s >= critical_friction``; slide-rock between (or slide if the
    kinetic friction ``mu_k <= beta`` cannot turn the block); flight if ``gv <= 0``."""
    if gv <= 0.0:
        return FLIGHT, 0.0, 0.0
    mag = abs(ah)
    if mag <= mu_s * gv and mag <= beta * gv:
        return REST, 0.0, 0.0
    d = -1.0 if ah > 0.0 else 1.0
    if mu_s < beta:
        return SLIDE, 0.0, d
    if mu_s >= critical_friction(mag / gv, beta, kap):
        return ROCK, d, 0.0
    if mu_k <= beta * (1.0 + 1e-12):  # b/h from atan2 and back may miss mu_k = b/h by an ulp
        return SLIDE, 0.0, d
    return SLIDE_ROCK, d, d


@jitable
def kinetic_energy(mode, s, th, om, w, alpha, kap):
    """Kinetic energy of a mode's state (units of ``m g R``)."""
    if mode == REST:
        return 0.0
    half_k = 0.5 * (kap / (kap + 1.0))  # 3/8 homogeneous
    if mode == SLIDE:
        return half_k * w * w
    phi = s * alpha - th
    vx = w + math.cos(phi) * om
    vy = math.sin(phi) * om
    return half_k * (vx * vx + vy * vy + om * om / kap)


@jitable
def potential_energy(s, th, alpha):
    """Height of the centre of mass above its seated height (units of ``R``; energy in ``m g R``,
    with ``g``, not ``g + a_v``: the vertical floor motion's share is input work)."""
    if s == 0.0:
        return 0.0
    return math.cos(s * alpha - th) - math.cos(alpha)


__all__ = ["FLIGHT", "REST", "Body", "Motion", "body", "ROCK", "SLIDE", "SLIDE_ROCK", "accelerations", "critical_friction",
           "kinetic_energy", "potential_energy", "rock_forces", "slide_rock_normal", "start_mode"]
