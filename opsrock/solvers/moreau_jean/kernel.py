"""Compiled kernel of :mod:`opsrock.solvers.moreau_jean` (numba): Moreau-Jean time stepping of a rigid
rectangular block on a rigid floor with two corner contacts, Newton's impact law with ``e_n = 0`` and
Coulomb friction (docs/guide/friction.md: notation, the impact at ``theta = 0``, the reference ``moreau_jean``).

Everything here is per unit mass (the motion does not depend on the mass): positions in m, velocities
in m/s and rad/s, impulses in m/s (N s per kg), energies in J/kg. The state is the centre of mass
``(x, y)`` in the floor frame and the clockwise rotation ``theta``; the floor's accelerations enter as
the body force ``(-a_h, -(g + a_v), 0)``. ``M^-1 = diag(1, 1, kappa / R²)``, ``kappa = R² / r²`` with ``r`` the
radius of gyration about the centre of mass (3 for a homogeneous block); ``h`` is the height of the centre of
mass above the base (half the height for a homogeneous block).

Corner ``c = +1`` (right) / ``-1`` (left), with ``s = sin(theta)``, ``co = cos(theta)``:

* gap ``g_c = y - c b s - h co``, horizontal position ``x_c = x + c b co - h s``;
* Jacobian rows ``G_N,c = (0, 1, gn_c)``, ``gn_c = h s - c b co``, and ``G_T,c = (1, 0, gt_c)``,
  ``gt_c = -(c b s + h co)``.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers import status as ST
from opsrock.solvers.jitable import jitable

# --- status codes: the shared ones (:mod:`opsrock.solvers.status`) ------------------------------------
#: Finished: the block came to rest after the excitation, overturned, or (free rocking) the span ended.
STATUS_OK = ST.OK
#: A non-finite state appeared.
STATUS_NONFINITE = ST.NONFINITE
#: ``max_steps`` steps taken before the end of the run.
STATUS_MAX_STEPS = ST.MAX_STEPS
#: The block was still moving when the tail after the excitation reached ``max_free_time``.
STATUS_TAIL = ST.MAX_FREE_TIME
#: The contact problem of a step had no solution among the statuses tried (never met in testing; a
#: Painlevé case needs ``mu_k`` above 4/3, which blocks refuse).
STATUS_LOCAL = ST.NO_CONTACT_SOLUTION

# --- contact modes, indices into opsrock.result.MODES ----------------------------------------------
MODE_REST = 0
MODE_SLIDE = 1
MODE_ROCK = 2
MODE_SLIDE_ROCK = 3
MODE_FLIGHT = 4

# --- forcing forms ---------------------------------------------------------------------------------
#: One value per step, the floor accelerations at the step's evaluation time (analytic pulses).
FORCING_STEPWISE = 0
#: Samples, linear between them, ``sub`` steps per sample interval (records).
FORCING_LINEAR = 1

# --- layout of the kernel's output vector: the shared slots, then this kernel's own -----------------
OUT_STATUS, OUT_THETA_MAX, OUT_OVERTURNED, OUT_ROCKED = ST.OUT_STATUS, ST.OUT_THETA_MAX, ST.OUT_OVERTURNED, ST.OUT_ROCKED
OUT_IMPACTS, OUT_STEPS, OUT_N_HIST, OUT_EVENT_TIME = ST.OUT_IMPACTS, ST.OUT_STEPS, ST.OUT_N_HIST, ST.OUT_EVENT_TIME
OUT_FIRST_MODE = ST.OUT_COMMON
OUT_TIME_SLIDING = ST.OUT_COMMON + 1
OUT_TIME_ROCKING = ST.OUT_COMMON + 2
OUT_SLIDE_MAX = ST.OUT_COMMON + 3
OUT_INPUT_WORK = ST.OUT_COMMON + 4
OUT_FRICTION_WORK = ST.OUT_COMMON + 5
OUT_IMPACT_LOSS = ST.OUT_COMMON + 6
OUT_X = ST.OUT_COMMON + 7  # final state: x, y, theta, x', y', theta' (6 slots)
OUT_LIMIT_STEPS = ST.OUT_COMMON + 13
OUT_MAX_PENETRATION = ST.OUT_COMMON + 14
OUT_MAX_FLICKER_GAP = ST.OUT_COMMON + 15
OUT_TIME = ST.OUT_COMMON + 16  # end of the run (s)
OUT_FLICKER_STEPS = ST.OUT_COMMON + 17
#: Slip velocity (m/s) of a block whose run ended while it slid flat on a still floor with too little friction to
#: stop it within the tail (0: it did not): the friction solver's ending of a slide that cannot stop.
OUT_SLIP_END = ST.OUT_COMMON + 18
OUT_TIME_FLIGHT = ST.OUT_COMMON + 19  # time with no corner down (s)
OUT_SIZE = ST.OUT_COMMON + 20

# --- the named tuples the kernel passes (QuantEcon's layout: one builder each) ------------------------------
#: The block, per unit mass: half-width ``b``, height of the centre of mass above the base ``h``, ``R = hypot(b,
#: h)`` (m), gravity ``g`` (m/s²), ``kappa = R² / r²`` (dimensionless; ``r`` the radius of gyration about the
#: centre of mass, 3 for a homogeneous block). Built by :func:`body`.
Body = namedtuple("Body", ["b", "h", "R", "g", "kappa"])
#: The floor's friction: static and kinetic coefficients, and ``stick_only`` (``mu`` infinite: then ``mu_s = inf``
#: and ``mu_k = 0``). Built by :func:`friction`.
Friction = namedtuple("Friction", ["mu_s", "mu_k", "stick_only"])
#: The numerics: step ``dt`` (s), theta-method parameter, relative slack ``tol`` of the contact laws, rotation
#: (rad) above which the block rocked. Built by :func:`numerics`.
Numerics = namedtuple("Numerics", ["dt", "theta_mj", "tol", "rocked_theta"])
#: When the run ends and what counts as contact: steps allowed, steps after the excitation (< 0: no tail), rest
#: velocity (m/s) and the steps at rest that end a tail, the velocity (m/s) and gap (m) of a corner's lift-off.
#: Built by :func:`limits`.
Limits = namedtuple("Limits", ["max_steps", "max_tail", "rest_velocity", "rest_steps", "velocity_tol", "lift_gap"])
#: Floor motion: :data:`FORCING_STEPWISE` (``ah[k]``, ``av[k]`` at step ``k``'s evaluation time) or
#: :data:`FORCING_LINEAR` (samples, ``sub`` steps per interval), for ``n_exc`` steps; after them ``a_h = 0`` and
#: ``a_v = tail_av`` (m/s²). Built by :func:`floor_motion`.
FloorMotion = namedtuple("FloorMotion", ["form", "ah", "av", "sub", "n_exc", "tail_av"])
#: The history: a row every ``every`` steps (and the last state): time (s), ``theta`` (rad), ``theta'`` (rad/s),
#: the base's slide (m); arrays of length 0: none. Built by :func:`history`.
History = namedtuple("History", ["every", "t", "theta", "theta_dot", "slide"])
#: One step's contact problem: the free velocity ``vf`` (``x'``, ``y'``, ``theta'``), the rotation entries ``gn``,
#: ``gt`` of each corner's Jacobian rows, and ``k3 = kappa / R²`` (the rotation's inverse mass, 1/m²).
Problem = namedtuple("Problem", ["vf", "gn", "gt", "k3"])
#: Its answer: normal and tangential impulses of each corner (m/s) and the velocity at the step's end.
Solution = namedtuple("Solution", ["pn", "pt", "v"])
#: Scratch of the two-contact enumeration: ``ws`` (float, 4 x 3 x 3), ``wi`` (int, 2 x 3), ``wb`` (float, 2 x 4),
#: and ``last[0]``, the previous step's status pair. Built by :func:`scratch`.
Scratch = namedtuple("Scratch", ["ws", "wi", "wb", "last"])
#: The arrays a step works in: its contact :class:`Problem` and :class:`Solution` (whose ``v`` is a view of
#: ``new``), whether each corner is active this step (``act``), touches and slips (``touch``, ``slip``, kept between
#: steps), the new state ``new`` and the :class:`Scratch`. Built by :func:`workspace`.
Workspace = namedtuple("Workspace", ["prob", "sol", "act", "touch", "slip", "new", "scratch"])


def body(b, h, R, g, kappa):
    """The :class:`Body` (m, m, m, m/s², dimensionless), typed as the kernel is compiled for (plain floats)."""
    return Body(float(b), float(h), float(R), float(g), float(kappa))


def friction(mu_s, mu_k, infinite):
    """The :class:`Friction` of coefficients ``mu_s``, ``mu_k``, or of infinite friction."""
    if infinite:
        return Friction(math.inf, 0.0, True)
    return Friction(float(mu_s), float(mu_k), False)


def numerics(dt, theta_mj, tol, rocked_theta):
    """The :class:`Numerics` (s, dimensionless, dimensionless, rad)."""
    return Numerics(float(dt), float(theta_mj), float(tol), float(rocked_theta))


def limits(max_steps, max_tail, rest_velocity, rest_steps, velocity_tol, lift_gap):
    """The :class:`Limits` (counts, m/s, count, m/s, m)."""
    return Limits(int(max_steps), int(max_tail), float(rest_velocity), int(rest_steps), float(velocity_tol),
                  float(lift_gap))


def floor_motion(form, ah, av, sub, n_exc, tail_av):
    """The :class:`FloorMotion` (``ah``, ``av`` m/s², writable float arrays; ``tail_av`` m/s²)."""
    return FloorMotion(int(form), ah, av, int(sub), int(n_exc), float(tail_av))


def history(every, cap):
    """A :class:`History` of ``cap`` rows, one every ``every`` steps (``cap`` 0: none)."""
    return History(int(every), np.zeros(cap), np.zeros(cap), np.zeros(cap), np.zeros(cap))


@jitable
def scratch(previous_pair):
    """A :class:`Scratch`, ``previous_pair`` the status pair taken last (-1: none)."""
    return Scratch(np.zeros((4, 3, 3)), np.zeros((2, 3), dtype=np.int64), np.zeros((2, 4)),
                   np.full(1, previous_pair, dtype=np.int64))


@jitable
def workspace(bd):
    """A fresh :class:`Workspace` for the :class:`Body` ``bd``."""
    new = np.zeros(6)
    return Workspace(Problem(np.zeros(3), np.zeros(2), np.zeros(2), bd.kappa / (bd.R * bd.R)),
                     Solution(np.zeros(2), np.zeros(2), new[3:]), np.zeros(2, dtype=np.bool_),
                     np.zeros(2, dtype=np.bool_), np.zeros(2, dtype=np.bool_), new, scratch(-1))


@numba.njit(cache=True, inline="always")
def _floor(k, theta_mj, fm):
    """Floor accelerations ``(a_h, a_v)`` (m/s²) of :class:`FloorMotion` ``fm`` at the evaluation time ``(k +
    theta_mj) dt`` of step ``k``."""
    if k >= fm.n_exc:
        return 0.0, fm.tail_av
    ah, av, sub = fm.ah, fm.av, fm.sub
    if fm.form == FORCING_STEPWISE:
        return ah[k], av[k]
    j = k // sub
    f = (k - j * sub + theta_mj) / sub
    return ah[j] + f * (ah[j + 1] - ah[j]), av[j] + f * (av[j + 1] - av[j])


@jitable
def _rows(c, b, h, th):
    """``(gn_c, gt_c)``: the rotation entries of the normal and tangential Jacobian rows of corner ``c``."""
    s = math.sin(th)
    co = math.cos(th)
    return h * s - c * b * co, -(c * b * s + h * co)


@jitable
def _gap(c, b, h, y, th):
    """Height of corner ``c`` above the floor (m)."""
    return y - c * b * math.sin(th) - h * math.cos(th)


@jitable
def _local(wnn, wnt, wtt, un, ut, mu_s, mu_k, stick_only):
    """One contact, exactly (docs/guide/friction.md, the impact at ``theta = 0``, with ``e_n = 0``): the impulse
    ``(P_N, P_T)`` making ``U+ = U + W P`` satisfy ``0 <= U_N+ _|_ P_N >= 0`` and Coulomb's law, and a
    code: 0 solved, 1 solved by the infinite-friction limit below, 2 no solution.

    Open if the corner does not approach; else stick (``U+ = 0``) if that impulse lies in the cone of
    the static coefficient ``mu_s`` (any ``P_T`` when ``stick_only``: ``mu`` infinite); else slip with the
    kinetic coefficient ``mu_k`` in the direction ``sigma`` that keeps ``sigma U_T+ >= 0``. Testing stick
    first is what makes ``mu_s > mu_k`` well defined: where both a stick and a slip solution exist, the
    contact sticks.

    With ``mu`` infinite, stick fails only if it needs a pulling normal impulse (``P_N < 0``). The slip
    solution for ``mu -> infinity`` then tends to ``P_N = 0``, ``P_T = -U_N / W_NT`` (``U_N+ = 0``), and
    its slip direction is always consistent; that limit is returned (with code 1). It arises at a corner
    that barely touches (``U_N`` ~ 1e-20, round-off) and near overturning, where the pivot's normal force
    vanishes (counted in ``diagnostics["limit_steps"]``).
    """
    if un >= 0.0:
        return 0.0, 0.0, 0
    det = wnn * wtt - wnt * wnt
    pn = -(wtt * un - wnt * ut) / det
    pt = -(wnn * ut - wnt * un) / det
    if pn >= 0.0 and (stick_only or abs(pt) <= mu_s * pn * (1.0 + 1e-12)):
        return pn, pt, 0
    if stick_only:  # here wnt ut < wtt un < 0, so wnt != 0
        return 0.0, -un / wnt, 1
    slack = 1e-12 * (abs(un) + abs(ut))
    for sg in (1.0, -1.0):
        d = wnn - sg * mu_k * wnt
        if d <= 0.0:
            continue
        pn = -un / d
        pt = -sg * mu_k * pn
        if sg * (wnt * pn + wtt * pt + ut) >= -slack:
            return pn, pt, 0
    return 0.0, 0.0, 2


# --- contact statuses of the two-contact enumeration --------------------------------------------------
_OPEN, _STICK, _SLIP_POS, _SLIP_NEG, _LIMIT = 0, 1, 2, 3, 4
#: Status pairs (right, left) tried in turn with finite friction: fewer contacts first, stick before slip
#: (the static law: where a stick and a slip solution both exist, the contact sticks).
#:
#: Fewer contacts first matters most for the both-stick pair ``[1, 1]``, whose friction is split between
#: the corners by a free parameter (:func:`_stick_both`). At ``theta_k != 0`` (a block that settled after
#: a landing a step away from ``theta = 0``, e.g. 1.4e-8 rad) the self-equilibrated split ``P_T,R = -s``,
#: ``P_T,L = s`` moves normal impulse from one corner to the other by ``s tan(theta_k)``: a friction
#: "squeeze" of ``|s| ~ P_N / tan(theta_k)`` wedges the block and makes ``[1, 1]`` a solution at any
#: horizontal load, with an impulse ratio ``|P_T| / P_N ~ 1 / theta_k`` that grows as the step shrinks
#: (a settled ``theta_k`` is a step's rotation at the last landing). With a finite ``mu`` the cones
#: allow a squeeze only while it feeds its own friction, ``mu tan(theta_k) >= 1`` (``theta_k >= 0.01`` rad
#: at the largest ``mu``, 100); below that the loads so held lie within a relative ``tan(theta_k)`` of
#: the uplift level. Infinite friction bounds nothing. The one-contact pairs (uplift about one corner)
#: are therefore tried before ``[1, 1]``, and ``[1, 1]`` with a squeeze is never taken ahead of them
#: (:func:`_impulses`).
_ORDER_FINITE = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [2, 0], [3, 0], [0, 2], [0, 3], [1, 2], [1, 3],
                          [2, 1], [3, 1], [2, 2], [2, 3], [3, 2], [3, 3]])
#: The same with infinite friction: stick or open, then the limit status of :func:`_local` (``P_N = 0``).
_ORDER_INFINITE = np.array([[0, 0], [1, 0], [0, 1], [1, 1], [4, 0], [0, 4], [1, 4], [4, 1], [4, 4]])


@jitable
def _solve_small(a, r, n):
    """Solve ``a[:n, :n] z = r[:n]`` in place by Gaussian elimination with partial pivoting; returns False
    if a pivot is below 1e-12 of the matrix's largest entry (singular status pair: skip it)."""
    big = 0.0
    for i in range(n):
        for j in range(n):
            big = max(big, abs(a[i, j]))
    for col in range(n):
        piv = col
        for i in range(col + 1, n):
            if abs(a[i, col]) > abs(a[piv, col]):
                piv = i
        if abs(a[piv, col]) <= 1e-12 * big:
            return False
        for j in range(n):
            a[col, j], a[piv, j] = a[piv, j], a[col, j]
        r[col], r[piv] = r[piv], r[col]
        for i in range(col + 1, n):
            f = a[i, col] / a[col, col]
            for j in range(col, n):
                a[i, j] -= f * a[col, j]
            r[i] -= f * r[col]
    for i in range(n - 1, -1, -1):
        acc = r[i]
        for j in range(i + 1, n):
            acc -= a[i, j] * r[j]
        r[i] = acc / a[i, i]
    return True


@jitable
def _check(st, pn, pt, un, ut, mu_s, eps):
    """Does a contact with status ``st``, impulse ``(pn, pt)`` and end-of-step velocity ``(un, ut)`` obey
    its law (within ``eps``, m/s)?"""
    if st == _OPEN:
        return un >= -eps
    if pn < -eps or abs(un) > eps:
        return False
    if st == _STICK:  # mu_s is inf for infinite friction
        return (math.isinf(mu_s) or abs(pt) <= mu_s * pn + eps) and abs(ut) <= eps
    if st == _SLIP_POS:
        return ut >= -eps
    if st == _SLIP_NEG:
        return ut <= eps
    return pt * ut <= eps * (abs(pt) + eps)  # _LIMIT: friction opposes the slip


@jitable
def _try_pair(sr, sl, prob, fr, eps, sol, sc):
    """Impulses of both contacts for the status pair ``(sr, sl)`` (not both stick), by one small linear
    system: each status adds its unknowns (stick: ``P_N``, ``P_T``; slip ``sigma``: ``P_N`` with ``P_T = -sigma
    mu_k P_N``; limit: ``P_T`` with ``P_N = 0``) and its equations (``U_N = 0``, and ``U_T = 0`` for stick).
    Fills the :class:`Solution` ``sol`` and returns True if the pair obeys every contact's law; works in the
    :class:`Scratch` ``sc``."""
    vf, gn, gt, k3 = prob.vf, prob.gn, prob.gt, prob.k3
    mu_s, mu_k = fr.mu_s, fr.mu_k
    pn, pt, v = sol.pn, sol.pt, sol.v
    ws, wi = sc.ws, sc.wi
    cols, rows, a = ws[0], ws[1], ws[2]  # impulse direction of each unknown, velocity row of each equation
    r = ws[3, 0]
    who, kind = wi[0], wi[1]  # kind 0: a P_N unknown (with the slip's P_T), 1: a P_T unknown
    n = np.int64(0)  # not a literal 0: numba would compile _solve_small for Literal[int](0) as well
    sts = (sr, sl)
    for i in range(2):
        st = sts[i]
        if st == _OPEN:
            continue
        sg = 1.0 if st == _SLIP_POS else -1.0
        mu = mu_k if (st == _SLIP_POS or st == _SLIP_NEG) else 0.0
        if st != _LIMIT:  # a P_N column (for slip, with its friction), and the U_N = 0 row
            cols[n, 0], cols[n, 1], cols[n, 2] = -sg * mu, 1.0, gn[i] - sg * mu * gt[i]
            rows[n, 0], rows[n, 1], rows[n, 2] = 0.0, 1.0, gn[i]
            who[n], kind[n] = i, 0
            n += 1
        if st == _STICK or st == _LIMIT:  # a P_T column; stick's U_T = 0 row, or the limit's U_N = 0 row
            cols[n, 0], cols[n, 1], cols[n, 2] = 1.0, 0.0, gt[i]
            if st == _STICK:
                rows[n, 0], rows[n, 1], rows[n, 2] = 1.0, 0.0, gt[i]
            else:
                rows[n, 0], rows[n, 1], rows[n, 2] = 0.0, 1.0, gn[i]
            who[n], kind[n] = i, 1
            n += 1
    for e in range(n):
        r[e] = -(rows[e, 0] * vf[0] + rows[e, 1] * vf[1] + rows[e, 2] * vf[2])
        for u in range(n):
            a[e, u] = rows[e, 0] * cols[u, 0] + rows[e, 1] * cols[u, 1] + k3 * rows[e, 2] * cols[u, 2]
    if not _solve_small(a, r, n):
        return False
    v[0], v[1], v[2] = vf[0], vf[1], vf[2]
    pn[0], pt[0], pn[1], pt[1] = 0.0, 0.0, 0.0, 0.0
    for u in range(n):
        v[0] += cols[u, 0] * r[u]
        v[1] += cols[u, 1] * r[u]
        v[2] += k3 * cols[u, 2] * r[u]
        if kind[u] == 0:
            pn[who[u]] += r[u]
            pt[who[u]] += cols[u, 0] * r[u]
        else:
            pt[who[u]] += r[u]
    for i in range(2):
        if not _check(sts[i], pn[i], pt[i], v[1] + gn[i] * v[2], v[0] + gt[i] * v[2], mu_s, eps):
            return False
    return True


@jitable
def _stick_both(prob, fr, strict, eps, sol, wb):
    """Both corners stick: then ``v = 0`` (their four velocity rows span the three freedoms) and the
    impulses solve ``G^T P = -M v_free``, a one-parameter family ``P(s)``, ``s = P_T`` of the left corner
    (the split of friction between the corners, free at ``theta = 0``). Keeps the ``s`` nearest to the
    split proportional to the normal impulses that satisfies ``P_N >= 0`` and the cones; False if none.
    With ``strict``, only the proportional split itself is accepted: no self-equilibrated friction
    "squeeze" away from it, which at ``theta_k != 0`` can hold the block against any load (see
    ``_ORDER_FINITE``). ``wb`` (2 x 4) is workspace."""
    vf, gn, gt, k3 = prob.vf, prob.gn, prob.gt, prob.k3
    mu_s, stick_only = fr.mu_s, fr.stick_only
    pn, pt, v = sol.pn, sol.pt, sol.v
    dgn = gn[1] - gn[0]  # 2 b cos(theta) > 0
    dgt = gt[1] - gt[0]  # 2 b sin(theta)
    rhs = -vf[2] / k3 + gn[0] * vf[1] + gt[0] * vf[0]
    # P = a0 + s d over (P_N,R, P_T,R, P_N,L, P_T,L)
    a0, d = wb[0], wb[1]
    a0[0], a0[1], a0[2], a0[3] = -vf[1] - rhs / dgn, -vf[0], rhs / dgn, 0.0
    d[0], d[1], d[2], d[3] = dgt / dgn, -1.0, -dgt / dgn, 1.0
    lo, hi = -np.inf, np.inf
    n_con = 2 if stick_only else 6
    for c in range(n_con):  # constraints alpha + beta s >= 0: P_N,R, P_N,L, then mu P_N -+ P_T per corner
        if c < 2:
            al, be = a0[2 * c], d[2 * c]
        else:
            j = 2 * ((c - 2) // 2)
            sg = 1.0 if c % 2 == 0 else -1.0
            al, be = mu_s * a0[j] - sg * a0[j + 1], mu_s * d[j] - sg * d[j + 1]
        if be > 0.0:
            lo = max(lo, (-eps - al) / be)
        elif be < 0.0:
            hi = min(hi, (-eps - al) / be)
        elif al < -eps:
            return False
    if lo > hi:
        return False
    s = 0.0
    if vf[1] < 0.0:
        rho = vf[0] / vf[1]  # total P_T / total P_N
        den = dgn + rho * dgt
        if den != 0.0:
            s = rho * rhs / den
    if strict and not lo <= s <= hi:
        return False
    s = min(max(s, lo), hi)
    pn[0], pt[0], pn[1], pt[1] = a0[0] + s * d[0], a0[1] + s * d[1], a0[2] + s * d[2], a0[3] + s * d[3]
    v[0], v[1], v[2] = 0.0, 0.0, 0.0
    return True


@jitable
def _try(k, order, prob, fr, strict, eps, sol, sc):
    """Try status pair ``order[k]`` (:func:`_stick_both`, with ``strict``, or :func:`_try_pair`)."""
    sr, sl = order[k, 0], order[k, 1]
    if sr == _STICK and sl == _STICK:
        return _stick_both(prob, fr, strict, eps, sol, sc.wb)
    return _try_pair(sr, sl, prob, fr, eps, sol, sc)


@numba.njit(cache=True, inline="always")
def _impulses(prob, act, R, fr, tol, scale, sol, sc):
    """Contact impulses of one step and the end-of-step velocity ``v`` (:class:`Solution` ``sol``) from the
    free velocity ``vf`` of the :class:`Problem` ``prob``, the corners ``act`` active.

    One active contact: the closed form :func:`_local`. Two: enumeration of the status pairs (open,
    stick, slip +/-, and with infinite friction the limit status), in the order of ``_ORDER_*``; the
    first pair that satisfies every law (within ``tol`` times the step's velocity scale) is the
    answer. Returns a status: STATUS_OK, -1 (solved using the infinite-friction limit) or STATUS_LOCAL.

    ``last[0]`` holds the index of the previous step's pair, tried first when ``mu_s == mu_k`` or ``mu`` is
    infinite: it is usually the answer again (a sliding block slips at both corners step after step, a
    resting block sticks at both), and should a problem have two solutions, the one that continues the
    previous step's statuses is taken. With ``mu_s > mu_k`` the fixed order is kept, so that stick wins.
    Two exceptions keep the fixed order's "uplift before both-stick" (see ``_ORDER_FINITE``): a previous
    both-stick pair is accepted ahead of the order only with its proportional friction split
    (``strict``, no squeeze), and with infinite friction no other previous pair is tried first (its
    limit pairs squeeze too; the one-contact pairs come first anyway). Accepting the previous both-stick
    pair with a squeeze once wedged a resting block for good: on a record, a block that settled at
    ``theta_k = 1.4e-8`` after a brief uplift was held at 1.16 times the uplift acceleration by friction
    impulses of 2e3 m/s a step and never rocked again. ``sc`` is the :class:`Scratch` (``last`` in it).
    """
    vf, gn, gt, k3 = prob.vf, prob.gn, prob.gt, prob.k3
    mu_s, mu_k, stick_only = fr.mu_s, fr.mu_k, fr.stick_only
    pn, pt, v = sol.pn, sol.pt, sol.v
    last = sc.last
    pn[0], pt[0], pn[1], pt[1] = 0.0, 0.0, 0.0, 0.0
    v[0], v[1], v[2] = vf[0], vf[1], vf[2]
    if act[0] != act[1]:
        i = 0 if act[0] else 1
        un, ut = vf[1] + gn[i] * vf[2], vf[0] + gt[i] * vf[2]
        wnn, wnt, wtt = 1.0 + k3 * gn[i] * gn[i], k3 * gn[i] * gt[i], 1.0 + k3 * gt[i] * gt[i]
        pn[i], pt[i], code = _local(wnn, wnt, wtt, un, ut, mu_s, mu_k, stick_only)
        v[0] += pt[i]
        v[1] += pn[i]
        v[2] += k3 * (gn[i] * pn[i] + gt[i] * pt[i])
        return STATUS_LOCAL if code == 2 else (-1 if code == 1 else STATUS_OK)
    if not act[0]:
        return STATUS_OK
    eps = tol * max(scale, abs(vf[0]), abs(vf[1]), R * abs(vf[2]))
    order = _ORDER_INFINITE if stick_only else _ORDER_FINITE
    prev, skip = last[0], -1
    if prev >= 0 and (stick_only or mu_s == mu_k):
        both = order[prev, 0] == _STICK and order[prev, 1] == _STICK
        if both or not stick_only:
            if _try(prev, order, prob, fr, both, eps, sol, sc):
                return STATUS_OK  # never a limit pair: those are not tried first
            skip = -1 if both else prev  # a failed strict both-stick is tried again in the order
    for k in range(order.shape[0]):
        if k == skip:
            continue
        # not strict: ``k < 0`` is False, computed, so that numba compiles one _try (a literal False would be a
        # second specialisation of _try and _stick_both, about 1 s of a cold compile)
        if _try(k, order, prob, fr, k < 0, eps, sol, sc):
            last[0] = k
            return -1 if (order[k, 0] == _LIMIT or order[k, 1] == _LIMIT) else STATUS_OK
    return STATUS_LOCAL


@numba.njit(cache=True)
def _slide_of(b, h, x, th):
    """Horizontal displacement of the lower base corner from where it was at rest, ``x_c(q) - c b`` (m):
    the base's displacement as a rigid body; the CM displacement at ``theta = 0``."""
    c = 1.0 if th >= 0.0 else -1.0
    return x + c * b * (math.cos(th) - 1.0) - h * math.sin(th)


@jitable
def _mode(touch, slip):
    """Contact mode (a ``MODE_*`` index) from the two corners' contact and slip flags."""
    n = int(touch[0]) + int(touch[1])
    sl = (touch[0] and slip[0]) or (touch[1] and slip[1])
    if n == 2:
        return MODE_SLIDE if sl else MODE_REST
    if n == 1:
        return MODE_SLIDE_ROCK if sl else MODE_ROCK
    return MODE_FLIGHT


@numba.njit(cache=True, inline="always")
def _copy(src, dst, at):
    """``dst[at:at + len(src)] = src``, element by element: a slice assignment would compile numba's shape-mismatch
    error message (string formatting: about 1.5 s of CPU of a cold compile) for a mismatch that cannot happen."""
    for i in range(src.shape[0]):
        dst[at + i] = src[i]


@numba.njit(cache=True, inline="always")
def _record(hist, j, t, th, vt, sl):
    """Store one row of the :class:`History` if there is room; returns the next free row."""
    if j < hist.t.size:
        hist.t[j] = t
        hist.theta[j] = th
        hist.theta_dot[j] = vt
        hist.slide[j] = sl
        return j + 1
    return j


@numba.njit(cache=True, inline="always")
def _step(state, a_h, a_v, bd, fr, num, wk):
    """One Moreau-Jean step (docs/guide/friction.md, the reference ``moreau_jean``) from ``state = (x, y, theta, x',
    y', theta')`` into ``wk.new``: free velocity under the step's forces, active corners from the mid-step
    prediction of their gaps, Jacobians at ``q_k``, the contact impulses (:func:`_impulses`), then ``q_{k+1} = q_k
    + dt [(1 - theta_mj) v_k + theta_mj v_{k+1}]``. Returns the status of the contact problem; works in the
    :class:`Workspace` ``wk``."""
    b, h, R, g = bd.b, bd.h, bd.R, bd.g
    dt, theta_mj = num.dt, num.theta_mj
    prob, sol, act, new = wk.prob, wk.sol, wk.act, wk.new
    vf, gn, gt, v = prob.vf, prob.gn, prob.gt, sol.v
    y, th, vx, vy, vt = state[1], state[2], state[3], state[4], state[5]
    vf[0], vf[1], vf[2] = vx - dt * a_h, vy - dt * (g + a_v), vt
    ym, tm = y + 0.5 * dt * vy, th + 0.5 * dt * vt
    for i in range(2):
        c = 1.0 - 2.0 * i
        act[i] = _gap(c, b, h, ym, tm) <= 0.0
        gn[i], gt[i] = _rows(c, b, h, th)
    st = _impulses(prob, act, R, fr, num.tol, dt * g, sol, wk.scratch)
    for i in range(3):
        new[i] = state[i] + dt * ((1.0 - theta_mj) * state[3 + i] + theta_mj * v[i])
    return st


@numba.njit(cache=True, inline="always")
def _contacts(bd, lim, wk, out):
    """After a step: friction work of the impulses, and each corner's contact and slip flags; returns
    True if a corner landed (an impact).

    A corner with a normal impulse is down (an impact if it was up), slipping if its tangential velocity
    (the row the solver enforced) exceeds ``velocity_tol``. A corner without impulse is up once it moves away
    from the floor faster than ``velocity_tol`` or rises above ``lift_gap``; otherwise it keeps its flags (a
    rotating pivot, constrained at velocity level, drifts up and takes an occasional free step; the
    flags ignore that "flicker", counted in ``out``)."""
    b, h = bd.b, bd.h
    new, gt, act, pn, pt, touch, slip = wk.new, wk.prob.gt, wk.act, wk.sol.pn, wk.sol.pt, wk.touch, wk.slip
    y1, th1, nx, ny, nt = new[1], new[2], new[3], new[4], new[5]
    impact = False
    for i in range(2):
        c = 1.0 - 2.0 * i
        if act[i]:
            out[OUT_FRICTION_WORK] -= pt[i] * (nx + gt[i] * nt)
        gap1 = _gap(c, b, h, y1, th1)
        gn1, _ = _rows(c, b, h, th1)
        if pn[i] > 0.0:
            impact = impact or not touch[i]
            touch[i] = True
            slip[i] = abs(nx + gt[i] * nt) > lim.velocity_tol
            out[OUT_MAX_PENETRATION] = max(out[OUT_MAX_PENETRATION], -gap1)
        elif ny + gn1 * nt > lim.velocity_tol or gap1 > lim.lift_gap:
            touch[i] = False
            slip[i] = False
        elif touch[i]:
            out[OUT_FLICKER_STEPS] += 1.0
            out[OUT_MAX_FLICKER_GAP] = max(out[OUT_MAX_FLICKER_GAP], gap1)
    return impact


@numba.njit(cache=True, inline="always")
def _book(state, a_h, a_v, bd, lim, wk, out):
    """Energy bookkeeping of the step from ``state`` to ``wk.new`` (docs/guide/friction.md, per unit mass): input
    work over the step's displacement, friction work in :func:`_contacts`, and at an impact the kinetic energy of
    the impulse's velocity change."""
    new, vf = wk.new, wk.prob.vf
    out[OUT_INPUT_WORK] -= a_h * (new[0] - state[0]) + a_v * (new[1] - state[1])
    if _contacts(bd, lim, wk, out):
        dvx, dvy, dvt = new[3] - vf[0], new[4] - vf[1], new[5] - vf[2]
        out[OUT_IMPACT_LOSS] += 0.5 * (dvx * dvx + dvy * dvy + bd.R * bd.R * dvt * dvt / bd.kappa)
        out[OUT_IMPACTS] += 1.0


@jitable
def _tally(mode, dt, out):
    """First mode left rest into, time sliding, time rocking and time in flight."""
    if mode != MODE_REST and out[OUT_FIRST_MODE] < 0.0:
        out[OUT_FIRST_MODE] = mode
    if mode == MODE_SLIDE or mode == MODE_SLIDE_ROCK:
        out[OUT_TIME_SLIDING] += dt
    if mode == MODE_ROCK or mode == MODE_SLIDE_ROCK:
        out[OUT_TIME_ROCKING] += dt
    if mode == MODE_FLIGHT:
        out[OUT_TIME_FLIGHT] += dt


@numba.njit(cache=True, inline="always")
def _slides_on(k, state, mode, bd, fr, fm, num, lim):
    """After step ``k`` of the tail: sliding flat on a still floor, decelerated by ``mu_k (g + a_v)`` without tipping
    (``mu_k <= b / h``), the block would still slide when the tail ends (a frictionless block, always)."""
    return (k >= fm.n_exc and lim.max_tail >= 0 and not fr.stick_only and mode == MODE_SLIDE
            and fr.mu_k * bd.h <= bd.b
            and fr.mu_k * (bd.g + fm.tail_av) * (fm.n_exc + lim.max_tail - k) * num.dt < abs(state[3]))


@numba.njit(cache=True)
def run(bd, fr, num, fm, state, lim, hist, out):
    """Integrate one case of the :class:`Body` ``bd`` with :class:`Friction` ``fr``, :class:`Numerics` ``num``
    under the :class:`FloorMotion` ``fm`` from ``state`` (``(x, y, theta, x', y', theta')``, m and m/s, rad and
    rad/s; it holds the final state on return), within the :class:`Limits` ``lim``; fills ``out`` (layout
    ``OUT_*``) and the :class:`History`; returns the status."""
    wk = workspace(bd)
    b, h, R, dt = bd.b, bd.h, bd.R, num.dt
    out[:] = 0.0
    out[OUT_FIRST_MODE] = -1.0
    for i in range(2):
        wk.touch[i] = _gap(1.0 - 2.0 * i, b, h, state[1], state[2]) <= lim.lift_gap
    j = _record(hist, 0, 0.0, state[2], state[5], _slide_of(b, h, state[0], state[2]))
    theta_max = abs(state[2])
    slide_max = abs(_slide_of(b, h, state[0], state[2]))
    status = STATUS_OK
    resting = 0
    k = 0
    n_exc, max_tail = fm.n_exc, lim.max_tail
    while True:
        if k >= n_exc and (max_tail < 0 or resting >= lim.rest_steps):
            break
        if k >= n_exc + max(max_tail, 0) or k >= lim.max_steps:
            status = STATUS_TAIL if k < lim.max_steps else STATUS_MAX_STEPS
            break
        a_h, a_v = _floor(k, num.theta_mj, fm)
        st = _step(state, a_h, a_v, bd, fr, num, wk)
        if st == -1:
            out[OUT_LIMIT_STEPS] += 1.0
        elif st != STATUS_OK:
            status = st
            break
        _book(state, a_h, a_v, bd, lim, wk, out)
        _copy(wk.new, state, 0)
        k += 1
        if not math.isfinite(state[0] + state[1] + state[2] + state[3] + state[4] + state[5]):
            status = STATUS_NONFINITE
            break
        mode = _mode(wk.touch, wk.slip)
        _tally(mode, dt, out)
        sl = _slide_of(b, h, state[0], state[2])
        slide_max = max(slide_max, abs(sl))
        theta_max = max(theta_max, abs(state[2]))
        if k % hist.every == 0:
            j = _record(hist, j, k * dt, state[2], state[5], sl)
        if theta_max >= OVERTURNING_ANGLE:
            out[OUT_OVERTURNED] = 1.0
            break
        still = max(abs(state[3]), abs(state[4]), R * abs(state[5])) < lim.rest_velocity
        resting = resting + 1 if (k >= n_exc and mode == MODE_REST and still) else 0
        if _slides_on(k, state, mode, bd, fr, fm, num, lim):
            out[OUT_SLIP_END] = state[3]  # the run ends with the motion
            break
    if k % hist.every != 0:
        j = _record(hist, j, k * dt, state[2], state[5], _slide_of(b, h, state[0], state[2]))
    out[OUT_STATUS] = status
    out[OUT_STEPS] = k
    out[OUT_THETA_MAX] = theta_max
    out[OUT_ROCKED] = 1.0 if theta_max > num.rocked_theta else 0.0
    out[OUT_SLIDE_MAX] = slide_max
    _copy(state, out, OUT_X)
    out[OUT_N_HIST] = j
    out[OUT_TIME] = k * dt
    # in units of 1/p, p = sqrt(g R / (r² + R²)) = sqrt(kappa / (kappa + 1) g / R) (sqrt(3 g / 4 R) homogeneous)
    out[OUT_EVENT_TIME] = k * dt * math.sqrt(bd.kappa / (bd.kappa + 1.0) * bd.g / R)
    return status
