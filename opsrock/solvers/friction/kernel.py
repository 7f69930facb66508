"""The compiled event-driven integrator of :mod:`opsrock.solvers.friction` (numba).

One case is integrated in the units of :mod:`.modes` by :func:`solve_case`: classical fourth-order
Runge-Kutta with a fixed step inside each forcing segment (:mod:`opsrock.solvers.forcing`), every
step ending on a segment end; the events of the current mode (impact ``theta = 0``, stick-slip,
loss of contact, and peaks of ``theta``) located on the Runge-Kutta map itself, so an event's time
is consistent with the integrator to round-off; a block at rest jumps in closed form to the next
time the floor overcomes it; a block leaving the floor flies ballistically (:func:`_fly`) until a
corner lands. After the excitation the block is followed (``a_h = 0``, the vertical acceleration of
the pulse kept) until it is at rest or has overturned, or, in a pure slide its friction cannot stop
within ``max_tail`` (:func:`_unstoppable`), until that is known: the case then ends with its slip
velocity in ``OUT_SLIP_END`` (docs/guide/friction.md, the ending rule).
"""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers import status as ST
from opsrock.solvers.forcing import Excitation, forcing, next_exceedance, next_exceedance_scaled, segment
from opsrock.solvers.friction.impacts import impact, landing
from opsrock.solvers.friction.modes import (
    FLIGHT,
    REST,
    ROCK,
    SLIDE,
    SLIDE_ROCK,
    Motion,
    accelerations,
    body,
    kinetic_energy,
    potential_energy,
    rock_forces,
    slide_rock_normal,
    start_mode,
)

# --- status codes: the shared ones (:mod:`opsrock.solvers.status`) --------------------------------
STATUS_OK = ST.OK
STATUS_MAX_IMPACTS = ST.MAX_IMPACTS
STATUS_NONFINITE = ST.NONFINITE
STATUS_MAX_STEPS = ST.MAX_STEPS
STATUS_EVENT_FAILED = ST.EVENT_FAILED
STATUS_IMPACT_LAW = ST.IMPACT_LAW
STATUS_TAIL = ST.MAX_FREE_TIME

# --- slots of the output array of :func:`solve_case`: the shared ones, then this kernel's own -------
OUT_THETA_MAX, OUT_OVERTURNED, OUT_ROCKED, OUT_STATUS = ST.OUT_THETA_MAX, ST.OUT_OVERTURNED, ST.OUT_ROCKED, ST.OUT_STATUS
OUT_IMPACTS, OUT_STEPS, OUT_N_HIST, OUT_EVENT_TIME = ST.OUT_IMPACTS, ST.OUT_STEPS, ST.OUT_N_HIST, ST.OUT_EVENT_TIME
OUT_FIRST_MODE, OUT_TIME_SLIDING, OUT_TIME_ROCKING, OUT_SLIDE_MAX, OUT_SLIDE_END = range(ST.OUT_COMMON, ST.OUT_COMMON + 5)
OUT_INPUT_WORK, OUT_KINETIC, OUT_POTENTIAL, OUT_FRICTION_WORK, OUT_IMPACT_LOSS, OUT_ENERGY_START = range(
    ST.OUT_COMMON + 5, ST.OUT_COMMON + 11)
OUT_TIME_FLIGHT = ST.OUT_COMMON + 11
#: The base's slip velocity (units of ``R p``) of a block still sliding when it is followed no further: a pure
#: slide on the still floor after the excitation whose friction cannot stop it within ``max_tail`` (0 otherwise).
OUT_SLIP_END = ST.OUT_COMMON + 12
OUT_SIZE = ST.OUT_COMMON + 13

# --- slots of the parameter vector of :func:`solve_case` (written by the solver, read once here) ----
#: The block: ``alpha`` (rad), ``e / e_H``, static and kinetic friction (``inf``: no slip).
P_ALPHA, P_F_REST, P_MU_S, P_MU_K = 0, 1, 2, 3
#: The horizontal forcing ``(form, k, nu, phase)`` of :func:`opsrock.solvers.forcing.forcing` up to ``tau_end``.
P_FORM, P_K, P_NU, P_PHASE, P_TAU_END = 4, 5, 6, 7, 8
#: The vertical ``1 + a_v/g`` without samples and after the excitation; the sample interval (units of 1/p).
P_G_CONST, P_G_TAIL, P_DTAU = 9, 10, 11
#: Steps (units of 1/p) during and after the excitation, rest velocity (units of p), limits.
P_H_NOM, P_H_TAIL, P_REST_VELOCITY, P_MAX_IMPACTS, P_MAX_STEPS, P_MAX_TAIL = 12, 13, 14, 15, 16, 17
#: The start state: ``theta0`` (rad) and ``omega0`` (units of p), rocking on a stuck pivot.
P_THETA0, P_OMEGA0 = 18, 19
#: The block's mass distribution ``kap = R² / r²`` (dimensionless, 3 for a homogeneous block; :mod:`.modes`).
P_KAPPA = 20
P_SIZE = 21

# --- slots of the forcing context: a_h/g of the segment, 1 + a_v/g = g0 + g1 (tau - gt0), tail flag, and the
# block's kap (it travels with the context to every function that evaluates the equations)
_FC_FORM, _FC_C0, _FC_C1, _FC_C2, _FC_G0, _FC_G1, _FC_GT0, _FC_TAIL, _FC_KAPPA = 0, 1, 2, 3, 4, 5, 6, 7, 8

# --- the named tuples the kernel passes (QuantEcon's layout; Body and Motion are :mod:`.modes`') -------------
#: A block in free flight at ``tau``: rotation ``th`` (rad) and rate ``om`` (units of p), the centre of mass's
#: horizontal position and velocity ``x``, ``vx`` and height and vertical velocity ``y``, ``vy`` (units of R, R p).
Flight = namedtuple("Flight", ["th", "om", "x", "vx", "y", "vy", "tau"])
#: Where the history goes: ``tau`` (units of 1/p), ``theta`` (rad), ``omega`` (units of p), ``u`` (units of R) and
#: the mode; arrays of length 0: none. Built by :func:`history`.
History = namedtuple("History", ["tau", "theta", "omega", "u", "mode"])

#: Non-literal ``0`` (a start index) and the peak event's id: numba compiles a callee, and all it calls, once more
#: for a literal argument met while it infers a caller (issue 43: cold compile time).
_ZERO = np.int64(0)
_EV_PEAK = np.int64(3)

#: Width of an event's bracket, relative to ``max(1, tau)``, at which it is located: a few ulps of the time.
_EVENT_TOL = 4e-16
#: An event location out of iterations still counts as found if its bracket is within this many widths.
_EVENT_SLACK = 1e3

#: Iterations allowed to an event location (Illinois with a bisection every fourth step).
_EVENT_MAX_ITER = 100
#: Shortest step (units of 1/p) before a mode that does not develop is dropped.
_MIN_STEP = 1e-14


@numba.njit(cache=True)
def _floor(tau, fc):
    """``(a_h/g, 1 + a_v/g)`` at ``tau`` on the current segment (``a_h = 0`` after the excitation)."""
    gv = fc[_FC_G0] + fc[_FC_G1] * (tau - fc[_FC_GT0])
    if fc[_FC_TAIL] > 0.0:
        return 0.0, gv
    return forcing(tau, int(fc[_FC_FORM]), fc[_FC_C0], fc[_FC_C1], fc[_FC_C2]), gv


@numba.njit(cache=True)
def _body(params):
    """The :class:`~.modes.Body` of the parameter vector (slots ``P_*``)."""
    return body(params[P_ALPHA], params[P_MU_S], params[P_MU_K], params[P_F_REST], params[P_KAPPA])


def history(cap):
    """A :class:`History` of ``cap`` rows (0: none)."""
    return History(np.zeros(cap), np.zeros(cap), np.zeros(cap), np.zeros(cap), np.zeros(cap, dtype=np.int64))


@numba.njit(cache=True)
def _deriv(m, fc, bd):
    """:func:`opsrock.solvers.friction.modes.accelerations` at the :class:`Motion` ``m``."""
    ah, gv = _floor(m.tau, fc)
    return accelerations(m, ah, gv, bd)


@numba.njit(cache=True)
def _rk4(m, h, fc, bd):
    """One RK4 step of the :class:`Motion` ``m``: ``(th, om, u, w, input work, friction work)`` after ``h``."""
    mode, s, sig, th, om, u, w, tau = m.mode, m.s, m.sig, m.th, m.om, m.u, m.w, m.tau
    a1, b1, p1, q1 = _deriv(m, fc, bd)
    th2, om2, w2 = th + 0.5 * h * om, om + 0.5 * h * a1, w + 0.5 * h * b1
    a2, b2, p2, q2 = _deriv(Motion(mode, s, sig, th2, om2, u, w2, tau + 0.5 * h), fc, bd)
    th3, om3, w3 = th + 0.5 * h * om2, om + 0.5 * h * a2, w + 0.5 * h * b2
    a3, b3, p3, q3 = _deriv(Motion(mode, s, sig, th3, om3, u, w3, tau + 0.5 * h), fc, bd)
    th4, om4, w4 = th + h * om3, om + h * a3, w + h * b3
    a4, b4, p4, q4 = _deriv(Motion(mode, s, sig, th4, om4, u, w4, tau + h), fc, bd)
    k = h / 6.0
    return (th + k * (om + 2.0 * om2 + 2.0 * om3 + om4), om + k * (a1 + 2.0 * a2 + 2.0 * a3 + a4),
            u + k * (w + 2.0 * w2 + 2.0 * w3 + w4), w + k * (b1 + 2.0 * b2 + 2.0 * b3 + b4),
            k * (p1 + 2.0 * p2 + 2.0 * p3 + p4), k * (q1 + 2.0 * q2 + 2.0 * q3 + q4))


@numba.njit(cache=True)
def _event(ev, m, fc, bd):
    """Value of event ``ev`` (it happens when the value falls to zero from above): 0 impact (``s theta``),
    1 stick-slip (rock: ``mu_s N - |F|``; slide, slide-rock: ``sig w``), 2 contact (``N``; slide:
    ``1 + a_v/g``), 3 peak (``s omega``, with ``s`` the sign of omega at the step's start); at the
    :class:`Motion` ``m``."""
    mode, s, sig, th, om, w, tau = m.mode, m.s, m.sig, m.th, m.om, m.w, m.tau
    alpha, mu_s, mu_k = bd.alpha, bd.mu_s, bd.mu_k
    if ev == 0:
        return s * th
    if ev == 3:
        return s * om
    ah, gv = _floor(tau, fc)
    if mode == SLIDE:
        return sig * w if ev == 1 else gv
    if mode == SLIDE_ROCK:
        return sig * w if ev == 1 else slide_rock_normal(s, sig, th, om, gv, alpha, mu_k, fc[_FC_KAPPA])
    f, n = rock_forces(s, th, om, ah, gv, alpha, fc[_FC_KAPPA])
    if ev == 2:
        return n
    return 1.0 if mu_s == math.inf else mu_s * n - abs(f)


@numba.njit(cache=True)
def _event_after(ev, sgn, m, d, fc, bd):
    """Value of event ``ev`` on the RK4 map after a step of length ``d`` from the :class:`Motion` ``m``."""
    th1, om1, u1, w1, _, _ = _rk4(m, d, fc, bd)
    return _event(ev, Motion(m.mode, sgn if ev == 3 else m.s, m.sig, th1, om1, u1, w1, m.tau + d), fc, bd)


@numba.njit(cache=True)
def _illinois(d, f, lo, hi, f_lo, f_hi, side):
    """The bracket after a trial at ``d`` with value ``f``: ``(lo, hi, f_lo, f_hi, side)``, the end kept twice
    in a row has its value halved (Illinois regula falsi)."""
    if f <= 0.0:
        if side == -1:
            f_lo *= 0.5
        return lo, d, f_lo, f, -1
    if side == 1:
        f_hi *= 0.5
    return d, hi, f, f_hi, 1


@numba.njit(cache=True)
def _locate(ev, sgn, f_lo, f_hi, m, h, fc, bd):
    """Smallest step ``d`` in (0, h] after which event ``ev`` has happened (its value <= 0), to
    round-off, given ``f_lo > 0`` at 0 and ``f_hi <= 0`` at ``h``: Illinois regula falsi with a
    bisection every fourth iteration, from the :class:`Motion` ``m``. Returns ``(d, ok)``."""
    lo, hi = 0.0, h
    side = _ZERO
    tol = _EVENT_TOL * max(1.0, m.tau + h)
    flat = 1e-14 * max(abs(f_lo), abs(f_hi))  # a value this small is the event to round-off
    for it in range(_EVENT_MAX_ITER):
        if hi - lo <= tol:
            return hi, True
        d = hi - f_hi * (hi - lo) / (f_hi - f_lo) if f_hi != f_lo else 0.5 * (lo + hi)
        if it % 4 == 3 or not (lo < d < hi):
            d = 0.5 * (lo + hi)
        f = _event_after(ev, sgn, m, d, fc, bd)
        if abs(f) <= flat:  # zero to round-off: the event is at d
            return d, True
        lo, hi, f_lo, f_hi, side = _illinois(d, f, lo, hi, f_lo, f_hi, side)
    return hi, hi - lo <= _EVENT_SLACK * tol


@numba.njit(cache=True)
def _set_segment(fc, tau, seg, exc, gvals, g_const):
    """Load the forcing segment holding ``tau`` into ``fc``; returns ``(segment index, segment end)``."""
    seg, c0, c1, c2, seg_end = segment(exc, tau, seg)
    dtau = exc.dtau
    fc[_FC_FORM] = exc.form
    fc[_FC_C0], fc[_FC_C1], fc[_FC_C2] = c0, c1, c2
    if gvals.shape[0] > 0:
        fc[_FC_G0] = gvals[seg]
        fc[_FC_G1] = (gvals[seg + 1] - gvals[seg]) / dtau
        fc[_FC_GT0] = seg * dtau
    else:
        fc[_FC_G0], fc[_FC_G1], fc[_FC_GT0] = g_const, 0.0, 0.0
    return seg, seg_end


@numba.njit(cache=True)
def _next_departure(tau, level, exc, gvals, g_const):
    """First time >= tau at which a block at rest is overcome (``|a_h| > level (g + a_v)``)."""
    if gvals.shape[0] > 0:
        return next_exceedance_scaled(tau, level, exc.kvals, gvals, exc.dtau)
    return next_exceedance(tau, level * g_const, exc)


@numba.njit(cache=True)
def _settle(m, ah, gv, bd, rest_velocity):
    """The mode a block takes after an impact or a landing: seated if, at ``theta = 0``, the rotation
    left is below ``rest_velocity`` and pulled back; slide-rock if a stuck pivot cannot hold; a
    slide that tips (``mu_k > b/h``) turns into slide-rock. Returns ``(mode, s, sig, om, w, ok)``
    (``ok`` False: the contact force would be negative, the block takes off); ``m`` the :class:`Motion` at the
    impact or landing."""
    mode, s, sig, th, om, w = m.mode, m.s, m.sig, m.th, m.om, m.w
    alpha, beta, mu_s, mu_k, kap = bd.alpha, bd.beta, bd.mu_s, bd.mu_k, bd.kap
    if th == 0.0 and (mode == ROCK or mode == SLIDE_ROCK) and abs(om) < rest_velocity:
        thdd = accelerations(Motion(mode, s, sig, 0.0, om, m.u, w, m.tau), ah, gv, bd)[0]
        if s * thdd <= 0.0:
            if abs(w) < rest_velocity:
                return REST, 0.0, 0.0, 0.0, 0.0, True
            mode, s, sig, om = SLIDE, 0.0, (1.0 if w > 0.0 else -1.0), 0.0
    if mode == ROCK:
        f, n = rock_forces(s, th, om, ah, gv, alpha, kap)
        if n <= 0.0:
            return mode, s, sig, om, w, False
        if abs(f) > mu_s * n:
            return SLIDE_ROCK, s, (-1.0 if f > 0.0 else 1.0), om, 0.0, True
    if mode == SLIDE_ROCK and slide_rock_normal(s, sig, th, om, gv, alpha, mu_k, kap) <= 0.0:
        return mode, s, sig, om, w, False
    if (mode == SLIDE or mode == REST) and gv <= 0.0:
        return mode, s, sig, om, w, False
    if mode == SLIDE and mu_k > beta:
        return SLIDE_ROCK, sig, sig, 0.0, w, True
    return mode, s, sig, om, w, True


# --- free flight ------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _flight_rhs(vx, vy, tau, fc):
    """Accelerations of the centre of mass in flight (units of ``R p²``: ``g / (R p²) = (kap + 1) / kap``, 4/3
    homogeneous) and the input power."""
    ah, gv = _floor(tau, fc)
    c = (fc[_FC_KAPPA] + 1.0) / fc[_FC_KAPPA]
    return -c * ah, -c * gv, -(ah * vx + (gv - 1.0) * vy)


@numba.njit(cache=True)
def _rk4_flight(x, vx, y, vy, tau, h, fc):
    """One RK4 step of the flight of the centre of mass: ``(x, vx, y, vy, input work)`` after ``h``
    (the rotation rate is constant in flight)."""
    ax1, ay1, p1 = _flight_rhs(vx, vy, tau, fc)
    vx2, vy2 = vx + 0.5 * h * ax1, vy + 0.5 * h * ay1
    ax2, ay2, p2 = _flight_rhs(vx2, vy2, tau + 0.5 * h, fc)
    vx3, vy3 = vx + 0.5 * h * ax2, vy + 0.5 * h * ay2
    ax3, ay3, p3 = _flight_rhs(vx3, vy3, tau + 0.5 * h, fc)
    vx4, vy4 = vx + h * ax3, vy + h * ay3
    ax4, ay4, p4 = _flight_rhs(vx4, vy4, tau + h, fc)
    k = h / 6.0
    return (x + k * (vx + 2.0 * vx2 + 2.0 * vx3 + vx4), vx + k * (ax1 + 2.0 * ax2 + 2.0 * ax3 + ax4),
            y + k * (vy + 2.0 * vy2 + 2.0 * vy3 + vy4), vy + k * (ay1 + 2.0 * ay2 + 2.0 * ay3 + ay4),
            k * (p1 + 2.0 * p2 + 2.0 * p3 + p4))


#: Gap (units of R) below which a corner in flight counts as touching the floor: round-off of the centre's
#: height, so that a lift-off whose gap opens more slowly than the last digit is not mistaken for a landing.
_GAP_TOL = 1e-12


@numba.njit(cache=True)
def _gap(c, th, y, sa, ca):
    """Height of corner ``c`` above the floor (units of ``R``), plus :data:`_GAP_TOL`."""
    return y - c * sa * math.sin(th) - ca * math.cos(th) + _GAP_TOL


@numba.njit(cache=True)
def _takeoff(m, bd):
    """The centre of mass's ``(x, vx, y, vy)`` (units of ``R``, ``R p``) of a block leaving the floor in
    the :class:`Motion` ``m``; ``x`` is measured from the centre's position at rest, as the base displacement
    ``u``."""
    mode, s, th, om, u, w = m.mode, m.s, m.th, m.om, m.u, m.w
    sa, ca, alpha = bd.sa, bd.ca, bd.alpha
    if mode == ROCK or mode == SLIDE_ROCK:
        phi = s * alpha - th
        return s * sa + u - math.sin(phi), w + math.cos(phi) * om, math.cos(phi), math.sin(phi) * om
    return u, w, ca, 0.0


@numba.njit(cache=True)
def _locate_landing(c, f_lo, f_hi, fl, h, fc, bd):
    """Smallest flight time ``d`` in (0, h] after which corner ``c`` touches the floor: Illinois regula
    falsi with a bisection every fourth iteration, on the RK4 flight map from the :class:`Flight` ``fl``.
    Returns ``(d, ok)``."""
    th, om, x, vx, y, vy, tau = fl.th, fl.om, fl.x, fl.vx, fl.y, fl.vy, fl.tau
    sa, ca = bd.sa, bd.ca
    lo, hi = 0.0, h
    side = _ZERO
    tol = _EVENT_TOL * max(1.0, tau + h)
    for it in range(_EVENT_MAX_ITER):
        if hi - lo <= tol:
            return hi, True
        d = hi - f_hi * (hi - lo) / (f_hi - f_lo) if f_hi != f_lo else 0.5 * (lo + hi)
        if it % 4 == 3 or not (lo < d < hi):
            d = 0.5 * (lo + hi)
        f = _gap(c, th + d * om, _rk4_flight(x, vx, y, vy, tau, d, fc)[2], sa, ca)
        lo, hi, f_lo, f_hi, side = _illinois(d, f, lo, hi, f_lo, f_hi, side)
    return hi, hi - lo <= _EVENT_SLACK * tol


@numba.njit(cache=True)
def _fly(fl, h, fc, fresh, bd):
    """One step of free flight of at most ``h`` from the :class:`Flight` ``fl``: ``(th, om, x, vx, y, vy, d, input
    work, landed, ok)``; ``landed``: a corner reached the floor after ``d`` (``d = 0``: a lift-off that does not
    develop within 1e-14/p lands back at once)."""
    th, om, x, vx, y, vy, tau = fl.th, fl.om, fl.x, fl.vx, fl.y, fl.vy, fl.tau
    sa, ca = bd.sa, bd.ca
    f1 = _rk4_flight(x, vx, y, vy, tau, h, fc)
    while fresh and min(_gap(1.0, th + h * om, f1[2], sa, ca), _gap(-1.0, th + h * om, f1[2], sa, ca)) <= 0.0:
        h *= 0.5
        if h < _MIN_STEP:
            return th, om, x, vx, y, vy, 0.0, 0.0, True, True
        f1 = _rk4_flight(x, vx, y, vy, tau, h, fc)
    best, d = 0.0, h
    for c in (1.0, -1.0):
        g0 = _gap(c, th, y, sa, ca)
        g1 = _gap(c, th + h * om, f1[2], sa, ca)
        if g0 > 0.0 and g1 <= 0.0:
            dc, ok = _locate_landing(c, g0, g1, fl, h, fc, bd)
            if not ok:
                return th, om, x, vx, y, vy, 0.0, 0.0, False, False
            if dc < d:
                best, d = c, dc
    if best != 0.0:
        f1 = _rk4_flight(x, vx, y, vy, tau, d, fc)
    return th + d * om, om, f1[0], f1[1], f1[2], f1[3], d, f1[4], best != 0.0, True


@numba.njit(cache=True)
def _record(hist, n_hist, tau, th, om, u, mode):
    """Append one state to the :class:`History` if it has room; returns the new length."""
    if n_hist < hist.tau.shape[0]:
        hist.tau[n_hist] = tau
        hist.theta[n_hist] = th
        hist.omega[n_hist] = om
        hist.u[n_hist] = u
        hist.mode[n_hist] = mode
        return n_hist + 1
    return n_hist


@numba.njit(cache=True)
def _first_event(m, h, y1, fc, bd):
    """The earliest event inside a step of length ``h`` from the :class:`Motion` ``m`` ending in the state
    ``y1``: ``(event, d, ok)``, ``event = -1`` if none (then ``d = h``)."""
    best, d_best = -1, h
    end = Motion(m.mode, m.s, m.sig, y1[0], y1[1], y1[2], y1[3], m.tau + h)
    for ev in range(3):
        if m.mode == SLIDE and ev == 0:
            continue
        f0 = _event(ev, m, fc, bd)
        f1 = _event(ev, end, fc, bd)
        if f0 > 0.0 and f1 <= 0.0:
            d, ok = _locate(ev, 0.0, f0, f1, m, h, fc, bd)
            if not ok:
                return ev, d, False
            if d < d_best:
                best, d_best = ev, d
    return best, d_best, True


@numba.njit(cache=True)
def _peak(m, d, om_end, fc, bd):
    """``|theta|`` at a turning point inside a step of length ``d`` from the :class:`Motion` ``m`` (0 if
    ``omega`` keeps its sign)."""
    om = m.om
    if m.mode == SLIDE or om * om_end >= 0.0 or om == 0.0:
        return 0.0, True
    sgn = 1.0 if om > 0.0 else -1.0
    d_p, ok = _locate(_EV_PEAK, sgn, abs(om), -abs(om_end), m, d, fc, bd)
    th_p = _rk4(m, d_p, fc, bd)[0]
    return abs(th_p), ok


@numba.njit(cache=True)
def _energy(mode, s, th, om, w, fy, fvy, bd):
    """Kinetic plus potential energy of any mode's state (units of ``m g R``)."""
    alpha, ca, kap = bd.alpha, bd.ca, bd.kap
    if mode == FLIGHT:
        return 0.5 * (kap / (kap + 1.0)) * (w * w + fvy * fvy + om * om / kap) + fy - ca
    return kinetic_energy(mode, s, th, om, w, alpha, kap) + potential_energy(s if mode != SLIDE else 0.0, th, alpha)


@numba.njit(cache=True)
def _unstoppable(w, mu_k, g_tail, time_left, kap):
    """Whether a pure slide at slip velocity ``w`` on the still floor after the excitation (closed form:
    uniform deceleration ``(kap + 1) / kap mu_k g_tail``, 4/3 homogeneous, units of ``R p²``) cannot stop within
    ``time_left`` (units of ``1/p``): always with ``mu_k = 0`` and ``w != 0``."""
    return (kap + 1.0) / kap * mu_k * g_tail * time_left < abs(w)


@numba.njit(cache=True)
def _start_slip(mode, s, th, om, tau, fc, alpha, mu_s):
    """The slip direction ``sig`` of a block started rocking on a stuck pivot (``theta0``, ``omega0``): 0 if
    the pivot holds (``|F| <= mu_s N``), else ``-sgn(F)`` (it starts slide-rocking)."""
    if mode != ROCK or mu_s == math.inf:
        return 0.0
    ah, gv = _floor(tau, fc)
    f, n = rock_forces(s, th, om, ah, gv, alpha, fc[_FC_KAPPA])
    if abs(f) <= mu_s * n:
        return 0.0
    return -1.0 if f > 0.0 else 1.0


@numba.njit(cache=True)
def solve_case(params, kvals, gvals, out, hist):
    """Solve one case from rest (or from ``theta0``, ``omega0`` rocking without slip); ``params`` holds
    the scalars (slots ``P_*``), results go in ``out`` (slots ``OUT_*``), the history in the :class:`History`
    ``hist``.

    Excitation: ``(form, k, nu, phase)`` of :func:`opsrock.solvers.forcing.forcing` up to ``tau_end``
    for an analytic pulse; for ``form == FORM_LINEAR`` the samples ``kvals`` (``a_h/g`` at
    ``tau = i dtau``). Vertical: the samples ``gvals`` (``1 + a_v/g``, same grid; length 0: the
    constant ``g_const``); after the excitation ``g_tail``. ``f_rest = e / e_H``; ``mu_s``, ``mu_k``
    may be ``inf`` (no slip). Steps: ``h_nom`` during the excitation, ``h_tail`` after it (units of
    ``1/p``), followed for at most ``max_tail``. In flight ``u`` and ``w`` hold the centre of mass's
    horizontal position and velocity, ``fy`` and ``fvy`` its height and vertical velocity.
    """
    alpha, f_rest, mu_s, mu_k = params[P_ALPHA], params[P_F_REST], params[P_MU_S], params[P_MU_K]
    form, k, nu, phase, tau_end = int(params[P_FORM]), params[P_K], params[P_NU], params[P_PHASE], params[P_TAU_END]
    g_const, g_tail, dtau = params[P_G_CONST], params[P_G_TAIL], params[P_DTAU]
    h_nom, h_tail, rest_velocity = params[P_H_NOM], params[P_H_TAIL], params[P_REST_VELOCITY]
    max_impacts, max_steps, max_tail = int(params[P_MAX_IMPACTS]), int(params[P_MAX_STEPS]), params[P_MAX_TAIL]
    theta0, omega0, kap = params[P_THETA0], params[P_OMEGA0], params[P_KAPPA]
    exc = Excitation(form, k, nu, phase, tau_end, kvals, dtau)
    bd = _body(params)
    sa, ca, beta = bd.sa, bd.ca, bd.beta
    level = min(mu_s, beta)
    fc = np.zeros(9)
    fc[_FC_KAPPA] = kap
    out[:] = 0.0
    tau, th, om, u, w, fy, fvy = 0.0, theta0, omega0, 0.0, 0.0, 0.0, 0.0
    mode, s, sig = REST, 0.0, 0.0
    fresh_th, fresh_w, fresh_fly = False, False, False
    first_mode = -1
    if theta0 != 0.0 or omega0 != 0.0:
        mode, first_mode = ROCK, ROCK
        s = (1.0 if theta0 > 0.0 else -1.0) if theta0 != 0.0 else (1.0 if omega0 > 0.0 else -1.0)
        fresh_th = theta0 == 0.0
        out[OUT_ROCKED] = 1.0
    out[OUT_ENERGY_START] = _energy(mode, s, th, om, w, fy, fvy, bd)
    theta_max, u_max = abs(theta0), 0.0
    win = wfr = eimp = t_slide = t_rock = t_fly = 0.0
    n_imp = n_steps = 0
    seg, seg_end = _set_segment(fc, 0.0, _ZERO, exc, gvals, g_const)
    sig = _start_slip(mode, s, th, om, tau, fc, alpha, mu_s)
    if sig != 0.0:  # the pivot cannot hold (e.g. a frictionless floor): the block starts slide-rocking
        mode, first_mode, fresh_w = SLIDE_ROCK, SLIDE_ROCK, True
    n_hist = _record(hist, _ZERO, tau, th, om, u, mode)
    status = STATUS_OK
    tail = False
    takeoff = False
    while True:
        if takeoff:  # the contact force would turn negative: the block leaves the floor
            u, w, fy, fvy = _takeoff(Motion(mode, s, sig, th, om, u, w, tau), bd)
            mode, s, sig, takeoff, fresh_fly, fresh_th, fresh_w = FLIGHT, 0.0, 0.0, False, True, False, False
            if first_mode < 0:
                first_mode = FLIGHT
            n_hist = _record(hist, n_hist, tau, th, om, u, mode)
        if n_steps >= max_steps:
            status = STATUS_MAX_STEPS
            break
        if not tail and tau >= tau_end:
            tail = True
            fc[_FC_TAIL], fc[_FC_G0], fc[_FC_G1], fc[_FC_GT0] = 1.0, g_tail, 0.0, 0.0
            seg_end = math.inf
        if mode == REST:
            if tail:
                break
            t_up, _ = _next_departure(tau, level, exc, gvals, g_const)
            n_steps += 1
            if t_up < 0.0:
                break
            tau = t_up
            seg, seg_end = _set_segment(fc, tau, seg, exc, gvals, g_const)
            ah, gv = _floor(tau, fc)
            mode, s, sig = start_mode(ah, gv, beta, mu_s, mu_k, kap)
            if mode == REST:  # at the threshold to round-off: leave by the level that was exceeded
                d = -1.0 if ah > 0.0 else 1.0
                mode, s, sig = (SLIDE, 0.0, d) if mu_s < beta else (ROCK, d, 0.0)
            if first_mode < 0 and mode != FLIGHT:
                first_mode = mode
            th, om, w = 0.0, 0.0, 0.0
            if mode == FLIGHT:
                mode, takeoff = REST, True
                continue
            fresh_th = mode == ROCK or mode == SLIDE_ROCK
            fresh_w = mode == SLIDE or mode == SLIDE_ROCK
            if fresh_th:
                out[OUT_ROCKED] = 1.0
            n_hist = _record(hist, n_hist, tau, th, om, u, mode)
            continue
        if tail and mode == SLIDE and _unstoppable(w, mu_k, g_tail, max_tail - (tau - tau_end), kap):
            # a pure slide on the still floor stops only after max_tail, or never: the case ends here
            # (docs/guide/friction.md, the ending rule); a slip slower than rest_velocity is seated
            if abs(w) < rest_velocity:
                eimp += 0.5 * (kap / (kap + 1.0)) * w * w
                mode, w, sig = REST, 0.0, 0.0
            out[OUT_SLIP_END] = w
            break
        if tail and tau - tau_end > max_tail:
            status = STATUS_TAIL
            break
        if not tail and tau >= seg_end:
            seg, seg_end = _set_segment(fc, tau, seg, exc, gvals, g_const)
        h = min(h_tail if tail else h_nom, seg_end - tau)
        last = h == seg_end - tau
        if mode == FLIGHT:
            th, om, u, w, fy, fvy, d, dwin, landed, ok = _fly(Flight(th, om, u, w, fy, fvy, tau), h, fc, fresh_fly, bd)
            n_steps += 1
            if not ok:
                status = STATUS_EVENT_FAILED
                break
            fresh_fly = False
            win += dwin
            t_fly += d
            if not tail and (last and not landed or seg_end - (tau + d) <= 4e-16 * seg_end):
                tau = seg_end
            else:
                tau = tau + d
            theta_max = max(theta_max, abs(th))
            u_max = max(u_max, abs(u))
            n_hist = _record(hist, n_hist, tau, th, om, u, mode)
            if abs(th) >= OVERTURNING_ANGLE:
                out[OUT_OVERTURNED] = 1.0
                break
            if not landed:
                continue
            n_imp += 1
            if n_imp > max_impacts:
                status = STATUS_MAX_IMPACTS
                break
            e_before = _energy(FLIGHT, 0.0, th, om, w, fy, fvy, bd)
            x_cm, vx = u, w
            mode, s, sig, om, w, ok = landing(th, om, vx, fvy, bd)
            if not ok:
                status = STATUS_IMPACT_LAW
                break
            # the base displacement: of the landing corner (its rest position is s b), or the centre's if flat
            u = x_cm if th == 0.0 else x_cm + s * sa * math.cos(th) - ca * math.sin(th) - s * sa
            ah, gv = _floor(tau, fc)
            mode, s, sig, om, w, ok = _settle(Motion(mode, s, sig, th, om, u, w, tau), ah, gv, bd, rest_velocity)
            eimp += e_before - _energy(mode, s, th, om, w, 0.0, 0.0, bd)
            if not ok:
                takeoff = True
                continue
            fresh_th = th == 0.0 and (mode == ROCK or mode == SLIDE_ROCK)
            fresh_w = (mode == SLIDE_ROCK or mode == SLIDE) and w == 0.0
            if mode == ROCK or mode == SLIDE_ROCK:
                out[OUT_ROCKED] = 1.0
            n_hist = _record(hist, n_hist, tau, th, om, u, mode)
            continue
        if fresh_th and om != 0.0:
            thdd0 = _deriv(Motion(mode, s, sig, 0.0, om, u, w, tau), fc, bd)[0]
            if s * thdd0 < 0.0 and abs(om) / abs(thdd0) < h:
                h, last = abs(om) / abs(thdd0), False
        y1 = _rk4(Motion(mode, s, sig, th, om, u, w, tau), h, fc, bd)
        n_steps += 1
        if fresh_w and mu_k == 0.0 and y1[3] != 0.0:
            sig = 1.0 if y1[3] > 0.0 else -1.0  # no friction force: the slip takes the direction it develops in
        undeveloped = False
        while (fresh_th and s * y1[0] <= 0.0) or (fresh_w and sig * y1[3] <= 0.0):
            h, last = 0.5 * h, False
            if h < _MIN_STEP:
                undeveloped = True
                break
            y1 = _rk4(Motion(mode, s, sig, th, om, u, w, tau), h, fc, bd)
            n_steps += 1
        if undeveloped:
            # the new mode does not develop within 1e-14/p: drop the part that does not (the rotation
            # or the slip), or both
            e_before = _energy(mode, s, th, om, w, 0.0, 0.0, bd)
            rotates = fresh_th and s * y1[0] > 0.0
            slips = (fresh_w and sig * y1[3] > 0.0) or (not fresh_w and w != 0.0)
            if fresh_th and not rotates:
                th, om = 0.0, 0.0
                mode, s = (SLIDE, 0.0) if (mode == SLIDE_ROCK and slips) else (REST, 0.0)
                if mode == REST:
                    w, sig = 0.0, 0.0
            elif mode == SLIDE:
                mode, w, sig = REST, 0.0, 0.0
            else:
                mode, w, sig = ROCK, 0.0, 0.0
            eimp += e_before - _energy(mode, s, th, om, w, 0.0, 0.0, bd)
            fresh_th, fresh_w = False, False
            continue
        if not (math.isfinite(y1[0]) and math.isfinite(y1[1]) and math.isfinite(y1[2]) and math.isfinite(y1[3])):
            status = STATUS_NONFINITE
            break
        ev, d, ok = _first_event(Motion(mode, s, sig, th, om, u, w, tau), h, y1, fc, bd)
        if not ok:
            status = STATUS_EVENT_FAILED
            break
        if ev >= 0:
            y1 = _rk4(Motion(mode, s, sig, th, om, u, w, tau), d, fc, bd)
            n_steps += 1
        th_p, ok = _peak(Motion(mode, s, sig, th, om, u, w, tau), d, y1[1], fc, bd)
        if not ok:
            status = STATUS_EVENT_FAILED
            break
        theta_max = max(theta_max, th_p)
        if mode == SLIDE or mode == SLIDE_ROCK:
            t_slide += d
        if mode != SLIDE:
            t_rock += d
        tau = seg_end if ((last and ev < 0) or (not tail and seg_end - (tau + d) <= 4e-16 * seg_end)) else tau + d
        th, om, u, w = y1[0], y1[1], y1[2], y1[3]
        win += y1[4]
        wfr += y1[5]
        fresh_th, fresh_w = False, False
        theta_max = max(theta_max, abs(th))
        u_max = max(u_max, abs(u))
        if abs(th) >= OVERTURNING_ANGLE:
            out[OUT_OVERTURNED] = 1.0
            n_hist = _record(hist, n_hist, tau, th, om, u, mode)
            break
        ah, gv = _floor(tau, fc)
        if ev == 0:  # impact at theta = 0
            n_hist = _record(hist, n_hist, tau, 0.0, om, u, mode)
            n_imp += 1
            if n_imp > max_impacts:
                status = STATUS_MAX_IMPACTS
                break
            e_before = _energy(mode, s, 0.0, om, w, 0.0, 0.0, bd)
            mode, s, sig, om, w, ok = impact(s, om, w, bd)
            if not ok:
                status = STATUS_IMPACT_LAW
                break
            th = 0.0
            mode, s, sig, om, w, ok = _settle(Motion(mode, s, sig, 0.0, om, u, w, tau), ah, gv, bd, rest_velocity)
            eimp += e_before - _energy(mode, s, 0.0, om, w, 0.0, 0.0, bd)
            if not ok:
                takeoff = True
                continue
            fresh_th = mode == ROCK or mode == SLIDE_ROCK
            fresh_w = mode == SLIDE_ROCK and w == 0.0
        elif ev == 1:  # stick-slip
            if mode == ROCK:
                f, _ = rock_forces(s, th, om, ah, gv, alpha, kap)
                mode, sig, w, fresh_w = SLIDE_ROCK, (-1.0 if f > 0.0 else 1.0), 0.0, True
            elif mode == SLIDE_ROCK:
                f, n = rock_forces(s, th, om, ah, gv, alpha, kap)
                w = 0.0
                if abs(f) <= mu_s * n:
                    mode, sig = ROCK, 0.0
                else:
                    sig, fresh_w = (-1.0 if f > 0.0 else 1.0), True
            else:
                w = 0.0
                mode, s, sig = start_mode(ah, gv, beta, mu_s, mu_k, kap)
                if mode == FLIGHT:
                    mode, takeoff = SLIDE, True
                    continue
                th, om = 0.0, 0.0
                fresh_th = mode == ROCK or mode == SLIDE_ROCK
                fresh_w = mode == SLIDE or mode == SLIDE_ROCK
                if fresh_th:
                    out[OUT_ROCKED] = 1.0
        elif ev == 2:  # contact lost
            if mode != SLIDE and s * th > alpha and s * om > 0.0:
                # it leaves the floor beyond its hump, turning outwards: nothing brings it back
                out[OUT_OVERTURNED] = 1.0
                theta_max = OVERTURNING_ANGLE
                break
            takeoff = True
            continue
        n_hist = _record(hist, n_hist, tau, th, om, u, mode)
    out[OUT_EVENT_TIME] = tau
    if out[OUT_OVERTURNED] > 0.0:
        theta_max = max(theta_max, OVERTURNING_ANGLE)
    out[OUT_THETA_MAX], out[OUT_STATUS], out[OUT_IMPACTS], out[OUT_STEPS] = theta_max, status, n_imp, n_steps
    out[OUT_N_HIST], out[OUT_FIRST_MODE] = n_hist, max(first_mode, REST)
    out[OUT_TIME_SLIDING], out[OUT_TIME_ROCKING], out[OUT_SLIDE_MAX], out[OUT_SLIDE_END] = t_slide, t_rock, u_max, u
    out[OUT_TIME_FLIGHT] = t_fly
    out[OUT_INPUT_WORK], out[OUT_FRICTION_WORK], out[OUT_IMPACT_LOSS] = win, wfr, eimp
    total = _energy(mode, s, th, om, w, fy, fvy, bd)
    out[OUT_POTENTIAL] = fy - ca if mode == FLIGHT else potential_energy(s if mode != SLIDE else 0.0, th, alpha)
    out[OUT_KINETIC] = total - out[OUT_POTENTIAL]


__all__ = ["OUT_SIZE", "P_SIZE", "STATUS_OK", "History", "history", "solve_case"]
