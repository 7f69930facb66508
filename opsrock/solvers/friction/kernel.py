"""The compiled event-driven integrator of :mod:`opsrock.solvers.friction` (numba).

One case is integrated in the units of :mod:`.modes` by :func:`solve_case`: classical fourth-order
Runge-Kutta with a fixed step inside each forcing segment (:mod:`opsrock.solvers.forcing`), every
step ending on a segment end; the events of the current mode (impact ``theta = 0``, stick-slip,
loss of contact, and peaks of ``theta``) located on the Runge-Kutta map itself, so an event's time
is consistent with the integrator to round-off; a block at rest jumps in closed form to the next
time the floor overcomes it; a block leaving the floor flies ballistically (:func:`_fly`, in :func:`fly_case`) until
a corner lands. After the excitation the block is followed (``a_h = 0``, the vertical acceleration of
the pulse kept) until it is at rest or has overturned, or, in a pure slide its friction cannot stop
within ``max_tail`` (:func:`_unstoppable`), until that is known: the case then ends with its slip
velocity in ``OUT_SLIP_END`` (docs/guide/friction.md, the ending rule).

Compilation (issue 43: a first solve's compile time): the helpers are :data:`opsrock.solvers.jitable.jitable` functions,
each compiled once into its callers. Only a step's path (:func:`_rk_step`, :func:`_trial_step`, :func:`_fly_step`,
:func:`_record`) is inlined into the loop by numba (``inline='always'``): a call that is not inlined takes and drops a
reference to each array it is passed, a dozen atomic counts on every step (measured: the kernel 10-15 % slower per case
without it). Everything inlined, as before, made the compile about a third longer. The loop's turn is written in
:func:`_solve` itself, not in an inlined helper: numba copies an inlined function's IR block by block, each block with
the function's whole variable scope, so the cost grows as blocks times variables; inlining the turn (105 blocks, 1,181
variables with the step path in it) cost a first solve about 1 s of CPU (issue 43). Free flight (:func:`_fly_step` and
what it calls, about a sixth of the compile) is an entry point of its own, :func:`fly_case`, compiled only when a block
first leaves the floor: most cases never do (it takes the floor falling faster than ``g``, or a contact force turning
negative). :func:`solve_case` hands the case over when the block takes off and takes it back when it lands, through a
state vector (:func:`state`): the case state and the forcing context, copied whole, so the two kernels compute exactly
what one loop would. A first solve from an empty cache took 7.9-8.6 s of CPU with it against 9.6-10.1 s with flight in
the one loop (alternated; issue 43), at the same cost per case; a first solve that flies compiles both kernels, in about
the time the one kernel took (11.2 and 10.9 s against 11.2 and 10.8 s, alternated), and so does
:func:`opsrock.solvers.warm_up` (11.9 s both). An earlier attempt (branch ``planar-lazy-flight``) cost 5-6 % per case on
cases that never fly: not the hand-over, but two ``inline='always'`` helpers it put on the step path (the excitation's
end and the step size; written back in the loop, its kernel was as fast as before): the loop here keeps its body as it
was. """

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
from opsrock.solvers.jitable import jitable

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
_FC_SIZE = 9

# --- the named tuples the kernel passes (QuantEcon's layout; Body and Motion are :mod:`.modes`') -------------
#: A block in free flight at ``tau``: rotation ``th`` (rad) and rate ``om`` (units of p), the centre of mass's
#: horizontal position and velocity ``x``, ``vx`` and height and vertical velocity ``y``, ``vy`` (units of R, R p).
Flight = namedtuple("Flight", ["th", "om", "x", "vx", "y", "vy", "tau"])
#: Columns of the history rows (:func:`history`): ``tau`` (units of 1/p), ``theta`` (rad), ``omega`` (units of p),
#: ``u`` (units of R) and the mode. One 2-D array rather than a tuple of five: numba counts a reference to each
#: array a compiled function is passed, and the history goes through the loop's every step.
H_TAU, H_THETA, H_OMEGA, H_U, H_MODE = 0, 1, 2, 3, 4
H_SIZE = 5

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


@jitable
def _floor(tau, fc):
    """``(a_h/g, 1 + a_v/g)`` at ``tau`` on the current segment (``a_h = 0`` after the excitation)."""
    gv = fc[_FC_G0] + fc[_FC_G1] * (tau - fc[_FC_GT0])
    if fc[_FC_TAIL] > 0.0:
        return 0.0, gv
    return forcing(tau, int(fc[_FC_FORM]), fc[_FC_C0], fc[_FC_C1], fc[_FC_C2]), gv


def history(cap):
    """The history's ``cap`` rows (0: none), columns ``H_*``."""
    return np.zeros((cap, H_SIZE))


@jitable
def _deriv(m, fc, bd):
    """:func:`opsrock.solvers.friction.modes.accelerations` at the :class:`Motion` ``m``."""
    ah, gv = _floor(m.tau, fc)
    return accelerations(m, ah, gv, bd)


@jitable
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


@jitable
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


@jitable
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


@jitable
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
        th1, om1, u1, w1, _, _ = _rk4(m, d, fc, bd)  # the event's value on the RK4 map after d
        f = _event(ev, Motion(m.mode, sgn if ev == 3 else m.s, m.sig, th1, om1, u1, w1, m.tau + d), fc, bd)
        if abs(f) <= flat:  # zero to round-off: the event is at d
            return d, True
        lo, hi, f_lo, f_hi, side = _illinois(d, f, lo, hi, f_lo, f_hi, side)
    return hi, hi - lo <= _EVENT_SLACK * tol


@jitable
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


@jitable
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
@jitable
def _flight_rhs(vx, vy, tau, fc):
    """Accelerations of the centre of mass in flight (units of ``R p²``: ``g / (R p²) = (kap + 1) / kap``, 4/3
    homogeneous) and the input power."""
    ah, gv = _floor(tau, fc)
    c = (fc[_FC_KAPPA] + 1.0) / fc[_FC_KAPPA]
    return -c * ah, -c * gv, -(ah * vx + (gv - 1.0) * vy)


@jitable
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


@jitable
def _gap(c, th, y, sa, ca):
    """Height of corner ``c`` above the floor (units of ``R``), plus :data:`_GAP_TOL`."""
    return y - c * sa * math.sin(th) - ca * math.cos(th) + _GAP_TOL


@jitable
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


@jitable
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


@jitable
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


@jitable
def _record(hist, out, m):
    """Append the :class:`Motion` ``m`` to the history rows ``hist`` (columns ``H_*``) if it has room
    (``out[OUT_N_HIST]``: the rows stored, counted on)."""
    n_hist = int(out[OUT_N_HIST])
    if n_hist < hist.shape[0]:
        hist[n_hist, H_TAU] = m.tau
        hist[n_hist, H_THETA] = m.th
        hist[n_hist, H_OMEGA] = m.om
        hist[n_hist, H_U] = m.u
        hist[n_hist, H_MODE] = m.mode
        out[OUT_N_HIST] = n_hist + 1


#: :func:`_record` inlined by numba (``inline='always'``) where it runs on every step (:func:`_rk_step`,
#: :func:`_fly_step`); called elsewhere (an impact, a take-off), it is one function compiled once: inlined at each of
#: those seven calls, its IR was copied and compiled seven more times (issue 43: cold compile time).
_record_step = numba.njit(inline='always')(_record)


@jitable
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


@jitable
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


@jitable
def _energy(mode, s, th, om, w, fy, fvy, bd):
    """Kinetic plus potential energy of any mode's state (units of ``m g R``)."""
    alpha, ca, kap = bd.alpha, bd.ca, bd.kap
    if mode == FLIGHT:
        return 0.5 * (kap / (kap + 1.0)) * (w * w + fvy * fvy + om * om / kap) + fy - ca
    return kinetic_energy(mode, s, th, om, w, alpha, kap) + potential_energy(s if mode != SLIDE else 0.0, th, alpha)


@jitable
def _unstoppable(w, mu_k, g_tail, time_left, kap):
    """Whether a pure slide at slip velocity ``w`` on the still floor after the excitation (closed form:
    uniform deceleration ``(kap + 1) / kap mu_k g_tail``, 4/3 homogeneous, units of ``R p²``) cannot stop within
    ``time_left`` (units of ``1/p``): always with ``mu_k = 0`` and ``w != 0``."""
    return (kap + 1.0) / kap * mu_k * g_tail * time_left < abs(w)


@jitable
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


# --- the case's state between steps: a float vector, slots _CS_* (the first eight a Motion's fields, in order) ----
_CS_MODE, _CS_S, _CS_SIG, _CS_TH, _CS_OM, _CS_U, _CS_W, _CS_TAU = 0, 1, 2, 3, 4, 5, 6, 7
#: In flight: the centre of mass's height and vertical velocity (units of R, R p; ``u``, ``w`` its horizontal ones).
_CS_FY, _CS_FVY = 8, 9
#: 1.0 while the rotation (``th``) or the slip (``w``) of a mode just entered has still to develop, or a flight has
#: just begun; 1.0 when the contact force would turn negative (the block leaves the floor next).
_CS_FRESH_TH, _CS_FRESH_W, _CS_FRESH_FLY, _CS_TAKEOFF = 10, 11, 12, 13
#: 1.0 after the excitation; the forcing segment the time is in and its end (units of 1/p).
_CS_TAIL, _CS_SEG, _CS_SEG_END = 14, 15, 16
_CS_SIZE = 17

#: What a phase of :func:`solve_case` or :func:`fly_case` returns to go on (any other value: the status the case ends
#: with, or a hand-over, :data:`AIRBORNE` and :data:`LANDED`).
_GO = np.int64(-1)

#: The case's fixed inputs, read from the parameter vector once (:func:`_setup`): the :class:`Excitation`, the
#: vertical samples ``gvals`` (``1 + a_v/g``; length 0: ``g_const``), ``g_tail`` after the excitation at
#: ``tau_end``, the steps ``h_nom`` and ``h_tail``, the rest velocity, the limits, and the level
#: ``min(mu_s, b/h)`` a block at rest is overcome by.
Setup = namedtuple("Setup", ["exc", "gvals", "g_const", "g_tail", "tau_end", "h_nom", "h_tail", "rest_velocity",
                             "max_impacts", "max_steps", "max_tail", "level"])


@jitable
def _setup(params, kvals, gvals):
    """The case's :class:`Setup` and :class:`~.modes.Body` from the parameter vector (slots ``P_*``)."""
    exc = Excitation(int(params[P_FORM]), params[P_K], params[P_NU], params[P_PHASE], params[P_TAU_END], kvals,
                     params[P_DTAU])
    bd = body(params[P_ALPHA], params[P_MU_S], params[P_MU_K], params[P_F_REST], params[P_KAPPA])
    cfg = Setup(exc, gvals, params[P_G_CONST], params[P_G_TAIL], params[P_TAU_END], params[P_H_NOM],
                params[P_H_TAIL], params[P_REST_VELOCITY], int(params[P_MAX_IMPACTS]), int(params[P_MAX_STEPS]),
                params[P_MAX_TAIL], min(params[P_MU_S], bd.beta))
    return cfg, bd


@jitable
def _motion(cs):
    """The :class:`Motion` of the case state ``cs``."""
    return Motion(int(cs[_CS_MODE]), cs[_CS_S], cs[_CS_SIG], cs[_CS_TH], cs[_CS_OM], cs[_CS_U], cs[_CS_W],
                  cs[_CS_TAU])


@jitable
def _set_mode(cs, mode, s, sig, om, w):
    """A new mode ``(mode, s, sig)`` with rate ``om`` and slip velocity ``w`` into the case state ``cs``."""
    cs[_CS_MODE], cs[_CS_S], cs[_CS_SIG], cs[_CS_OM], cs[_CS_W] = mode, s, sig, om, w


@jitable
def _first_mode(out, mode):
    """Count ``mode`` as the first the block left rest into, if it is."""
    if out[OUT_FIRST_MODE] < 0.0:
        out[OUT_FIRST_MODE] = mode


@jitable
def _start(params, cfg, bd, fc, cs, out, hist):
    """The case's start: from rest, or rocking on a stuck pivot from ``theta0``, ``omega0`` (slide-rocking if the
    pivot cannot hold, :func:`_start_slip`); ``out`` cleared but for the start's energy, the first history row."""
    theta0, omega0 = params[P_THETA0], params[P_OMEGA0]
    out[:] = 0.0
    out[OUT_FIRST_MODE] = -1.0
    cs[:] = 0.0
    cs[_CS_TH], cs[_CS_OM], cs[_CS_MODE] = theta0, omega0, REST
    if theta0 != 0.0 or omega0 != 0.0:
        cs[_CS_MODE], out[OUT_FIRST_MODE] = ROCK, ROCK
        cs[_CS_S] = (1.0 if theta0 > 0.0 else -1.0) if theta0 != 0.0 else (1.0 if omega0 > 0.0 else -1.0)
        cs[_CS_FRESH_TH] = theta0 == 0.0
        out[OUT_ROCKED] = 1.0
    m = _motion(cs)
    out[OUT_ENERGY_START] = _energy(m.mode, m.s, m.th, m.om, m.w, 0.0, 0.0, bd)
    out[OUT_THETA_MAX] = abs(theta0)
    cs[_CS_SEG], cs[_CS_SEG_END] = _set_segment(fc, 0.0, _ZERO, cfg.exc, cfg.gvals, cfg.g_const)
    sig = _start_slip(m.mode, m.s, m.th, m.om, m.tau, fc, bd.alpha, bd.mu_s)
    cs[_CS_SIG] = sig
    if sig != 0.0:  # the pivot cannot hold (e.g. a frictionless floor): the block starts slide-rocking
        cs[_CS_MODE], out[OUT_FIRST_MODE], cs[_CS_FRESH_W] = SLIDE_ROCK, SLIDE_ROCK, True
    _record(hist, out, _motion(cs))


@jitable
def _take_off(bd, cs, out, hist):
    """The block leaves the floor (its contact force would turn negative): the flight's start from its mode."""
    fx, fvx, fy, fvy = _takeoff(_motion(cs), bd)
    cs[_CS_U], cs[_CS_W], cs[_CS_FY], cs[_CS_FVY] = fx, fvx, fy, fvy
    _set_mode(cs, FLIGHT, 0.0, 0.0, cs[_CS_OM], fvx)
    cs[_CS_TAKEOFF], cs[_CS_FRESH_FLY], cs[_CS_FRESH_TH], cs[_CS_FRESH_W] = False, True, False, False
    _first_mode(out, FLIGHT)
    _record(hist, out, _motion(cs))


@jitable
def _leave_rest(cfg, bd, fc, cs, out, hist):
    """A block at rest jumps to the next time the floor overcomes it and takes the mode it starts in
    (:func:`~.modes.start_mode`; flight: a take-off next). Returns :data:`_GO`, or ``STATUS_OK`` if it stays at
    rest to the excitation's end. Where round-off still gives rest there, the level exceeded decides: ``1 + a_v/g``'s
    (it reaches 0 within the event tolerance of the time: the floor falls faster than ``g``, no ``a_h`` overcame the
    block) is a take-off; else it slides or rocks by ``a_h``'s. Before, such a block rocked with no contact force
    under it (a seated block on a floor dropping at -3 g with no horizontal motion overturned)."""
    exc, gvals = cfg.exc, cfg.gvals  # the first time the floor overcomes it: |a_h| > level (g + a_v)
    if gvals.shape[0] > 0:
        t_up, _ = next_exceedance_scaled(cs[_CS_TAU], cfg.level, exc.kvals, gvals, exc.dtau)
    else:
        t_up, _ = next_exceedance(cs[_CS_TAU], cfg.level * cfg.g_const, exc)
    out[OUT_STEPS] += 1
    if t_up < 0.0:
        return STATUS_OK
    tau = t_up
    cs[_CS_TAU] = tau
    cs[_CS_SEG], cs[_CS_SEG_END] = _set_segment(fc, tau, int(cs[_CS_SEG]), cfg.exc, cfg.gvals, cfg.g_const)
    ah, gv = _floor(tau, fc)
    mode, s, sig = start_mode(ah, gv, bd.beta, bd.mu_s, bd.mu_k, bd.kap)
    if mode == REST:  # at the threshold to round-off: leave by the level that was exceeded
        if gv + fc[_FC_G1] * _EVENT_TOL * max(1.0, tau) <= 0.0:  # g_v's: it vanishes within the time's round-off
            mode = FLIGHT
        else:
            d = -1.0 if ah > 0.0 else 1.0
            mode, s, sig = (SLIDE, 0.0, d) if bd.mu_s < bd.beta else (ROCK, d, 0.0)
    if mode != FLIGHT:
        _first_mode(out, mode)
    cs[_CS_TH] = 0.0
    _set_mode(cs, mode, s, sig, 0.0, 0.0)
    if mode == FLIGHT:
        cs[_CS_MODE], cs[_CS_TAKEOFF] = REST, True
        return _GO
    fresh_th = mode == ROCK or mode == SLIDE_ROCK
    cs[_CS_FRESH_TH], cs[_CS_FRESH_W] = fresh_th, mode == SLIDE or mode == SLIDE_ROCK
    if fresh_th:
        out[OUT_ROCKED] = 1.0
    _record(hist, out, _motion(cs))
    return _GO


@jitable
def _seat_slide(cfg, bd, cs, out):
    """The ending rule (docs/guide/friction.md): a pure slide on the still floor after the excitation that friction
    stops only after ``max_tail``, or never, ends the case; its slip velocity into ``OUT_SLIP_END``, one slower than
    the rest velocity seated."""
    w = cs[_CS_W]
    if abs(w) < cfg.rest_velocity:
        out[OUT_IMPACT_LOSS] += 0.5 * (bd.kap / (bd.kap + 1.0)) * w * w
        cs[_CS_MODE], cs[_CS_W], cs[_CS_SIG] = REST, 0.0, 0.0
        w = 0.0
    out[OUT_SLIP_END] = w


@numba.njit(cache=True, inline='always')
def _fly_step(cfg, bd, fc, cs, h, last, out, hist):
    """A step of free flight of at most ``h`` (``last``: to the segment's end) and its landing, if a corner lands
    (:func:`~.impacts.landing`, then :func:`_settle`; a take-off again if it cannot). Returns :data:`_GO` or the
    case's status."""
    th, om, fy, fvy, tau, seg_end = cs[_CS_TH], cs[_CS_OM], cs[_CS_FY], cs[_CS_FVY], cs[_CS_TAU], cs[_CS_SEG_END]
    fl = Flight(th, om, cs[_CS_U], cs[_CS_W], fy, fvy, tau)
    th, om, u, w, fy, fvy, d, dwin, landed, ok = _fly(fl, h, fc, cs[_CS_FRESH_FLY] > 0.0, bd)
    out[OUT_STEPS] += 1
    if not ok:
        return STATUS_EVENT_FAILED
    cs[_CS_FRESH_FLY] = False
    out[OUT_INPUT_WORK] += dwin
    out[OUT_TIME_FLIGHT] += d
    if cs[_CS_TAIL] == 0.0 and (last and not landed or seg_end - (tau + d) <= 4e-16 * seg_end):
        tau = seg_end
    else:
        tau = tau + d
    cs[_CS_TH], cs[_CS_OM], cs[_CS_U], cs[_CS_W], cs[_CS_FY], cs[_CS_FVY], cs[_CS_TAU] = th, om, u, w, fy, fvy, tau
    out[OUT_THETA_MAX] = max(out[OUT_THETA_MAX], abs(th))
    out[OUT_SLIDE_MAX] = max(out[OUT_SLIDE_MAX], abs(u))
    _record_step(hist, out, _motion(cs))
    if abs(th) >= OVERTURNING_ANGLE:
        out[OUT_OVERTURNED] = 1.0
        return STATUS_OK
    if not landed:
        return _GO
    out[OUT_IMPACTS] += 1
    if out[OUT_IMPACTS] > cfg.max_impacts:
        return STATUS_MAX_IMPACTS
    return _land(cfg, bd, fc, cs, out, hist)


@jitable
def _land(cfg, bd, fc, cs, out, hist):
    """A corner lands from flight (:func:`_fly_step`): the impact law, then the mode the block settles in."""
    th, om, fy, fvy, tau = cs[_CS_TH], cs[_CS_OM], cs[_CS_FY], cs[_CS_FVY], cs[_CS_TAU]
    e_before = _energy(FLIGHT, 0.0, th, om, cs[_CS_W], fy, fvy, bd)
    x_cm, vx = cs[_CS_U], cs[_CS_W]
    mode, s, sig, om, w, ok = landing(th, om, vx, fvy, bd)
    if not ok:
        _set_mode(cs, mode, s, sig, om, w)
        return STATUS_IMPACT_LAW
    # the base displacement: of the landing corner (its rest position is s b), or the centre's if flat
    u = x_cm if th == 0.0 else x_cm + s * bd.sa * math.cos(th) - bd.ca * math.sin(th) - s * bd.sa
    ah, gv = _floor(tau, fc)
    mode, s, sig, om, w, ok = _settle(Motion(mode, s, sig, th, om, u, w, tau), ah, gv, bd, cfg.rest_velocity)
    cs[_CS_U] = u
    _set_mode(cs, mode, s, sig, om, w)
    out[OUT_IMPACT_LOSS] += e_before - _energy(mode, s, th, om, w, 0.0, 0.0, bd)
    if not ok:
        cs[_CS_TAKEOFF] = True
        return _GO
    cs[_CS_FRESH_TH] = th == 0.0 and (mode == ROCK or mode == SLIDE_ROCK)
    cs[_CS_FRESH_W] = (mode == SLIDE_ROCK or mode == SLIDE) and w == 0.0
    if mode == ROCK or mode == SLIDE_ROCK:
        out[OUT_ROCKED] = 1.0
    _record(hist, out, _motion(cs))
    return _GO


@numba.njit(cache=True, inline='always')
def _trial_step(bd, fc, cs, h, last, out):
    """An RK4 step of at most ``h`` from the case state (``last``: to the segment's end); a rotation or slip just
    begun shortens it so that it develops (a rotation its own way, halved until it does). Returns ``(end state,
    h, last, developed)``; ``developed`` False if the new mode does not develop within 1e-14/p."""
    m = _motion(cs)
    fresh_th, fresh_w, s, om = cs[_CS_FRESH_TH] > 0.0, cs[_CS_FRESH_W] > 0.0, m.s, m.om
    if fresh_th and om != 0.0:
        thdd0 = _deriv(Motion(m.mode, s, m.sig, 0.0, om, m.u, m.w, m.tau), fc, bd)[0]
        if s * thdd0 < 0.0 and abs(om) / abs(thdd0) < h:
            h, last = abs(om) / abs(thdd0), False
    y1 = _rk4(m, h, fc, bd)
    out[OUT_STEPS] += 1
    if fresh_w and bd.mu_k == 0.0 and y1[3] != 0.0:
        cs[_CS_SIG] = 1.0 if y1[3] > 0.0 else -1.0  # no friction force: the slip takes the direction it develops in
        m = _motion(cs)
    while (fresh_th and s * y1[0] <= 0.0) or (fresh_w and m.sig * y1[3] <= 0.0):
        h, last = 0.5 * h, False
        if h < _MIN_STEP:
            return y1, h, last, False
        y1 = _rk4(m, h, fc, bd)
        out[OUT_STEPS] += 1
    return y1, h, last, True


@jitable
def _drop_undeveloped(bd, cs, y1, out):
    """A new mode that does not develop within 1e-14/p (:func:`_trial_step`, ending in ``y1``): the part that does
    not (the rotation or the slip), or both, is dropped; the energy that takes away counted as lost."""
    m = _motion(cs)
    mode, s, sig, th, om, w = m.mode, m.s, m.sig, m.th, m.om, m.w
    fresh_th, fresh_w = cs[_CS_FRESH_TH] > 0.0, cs[_CS_FRESH_W] > 0.0
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
    out[OUT_IMPACT_LOSS] += e_before - _energy(mode, s, th, om, w, 0.0, 0.0, bd)
    cs[_CS_TH] = th
    _set_mode(cs, mode, s, sig, om, w)
    cs[_CS_FRESH_TH], cs[_CS_FRESH_W] = False, False


@numba.njit(cache=True, inline='always')
def _rk_step(cfg, bd, fc, cs, trial, out, hist):
    """A step of a mode on the floor (rock, slide, slide-rock), ``trial`` its RK4 step (:func:`_trial_step`'s
    ``(end state, h, last, developed)``), cut at its first event (:func:`_first_event`), its peak of ``|theta|``
    (:func:`_peak`) and tallies, then the event's mode change (:func:`_at_event`). Returns :data:`_GO` or the case's
    status. The loop calls :func:`_trial_step` itself: numba copies an inlined function's IR block by block with its
    whole variable scope, so one inlined into another costs more than both inlined into the loop (issue 43)."""
    y1, h, last, developed = trial
    if not developed:
        _drop_undeveloped(bd, cs, y1, out)
        return _GO
    if not (math.isfinite(y1[0]) and math.isfinite(y1[1]) and math.isfinite(y1[2]) and math.isfinite(y1[3])):
        return STATUS_NONFINITE
    m = _motion(cs)
    ev, d, ok = _first_event(m, h, y1, fc, bd)
    if not ok:
        return STATUS_EVENT_FAILED
    if ev >= 0:
        y1 = _rk4(m, d, fc, bd)
        out[OUT_STEPS] += 1
    th_p, ok = _peak(m, d, y1[1], fc, bd)
    if not ok:
        return STATUS_EVENT_FAILED
    out[OUT_THETA_MAX] = max(out[OUT_THETA_MAX], th_p)
    if m.mode == SLIDE or m.mode == SLIDE_ROCK:
        out[OUT_TIME_SLIDING] += d
    if m.mode != SLIDE:
        out[OUT_TIME_ROCKING] += d
    tau, seg_end = m.tau, cs[_CS_SEG_END]
    tail = cs[_CS_TAIL] > 0.0
    tau = seg_end if ((last and ev < 0) or (not tail and seg_end - (tau + d) <= 4e-16 * seg_end)) else tau + d
    cs[_CS_TAU], cs[_CS_TH], cs[_CS_OM], cs[_CS_U], cs[_CS_W] = tau, y1[0], y1[1], y1[2], y1[3]
    out[OUT_INPUT_WORK] += y1[4]
    out[OUT_FRICTION_WORK] += y1[5]
    cs[_CS_FRESH_TH], cs[_CS_FRESH_W] = False, False
    out[OUT_THETA_MAX] = max(out[OUT_THETA_MAX], abs(y1[0]))
    out[OUT_SLIDE_MAX] = max(out[OUT_SLIDE_MAX], abs(y1[2]))
    over = abs(y1[0]) >= OVERTURNING_ANGLE
    if over or ev < 0:  # the common step, no event (or the last): its history row, inlined once
        if over:
            out[OUT_OVERTURNED] = 1.0
        _record_step(hist, out, _motion(cs))
        return STATUS_OK if over else _GO
    return _at_event(cfg, bd, fc, cs, ev, out, hist)


@jitable
def _impact(cfg, bd, fc, cs, out, hist):
    """An impact at ``theta = 0`` (:func:`~.impacts.impact`), then the mode the block settles in (:func:`_settle`;
    a take-off next if it cannot). Returns :data:`_GO` or the case's status."""
    m = _motion(cs)
    _record(hist, out, Motion(m.mode, m.s, m.sig, 0.0, m.om, m.u, m.w, m.tau))
    out[OUT_IMPACTS] += 1
    if out[OUT_IMPACTS] > cfg.max_impacts:
        return STATUS_MAX_IMPACTS
    e_before = _energy(m.mode, m.s, 0.0, m.om, m.w, 0.0, 0.0, bd)
    mode, s, sig, om, w, ok = impact(m.s, m.om, m.w, bd)
    if not ok:
        _set_mode(cs, mode, s, sig, om, w)
        return STATUS_IMPACT_LAW
    cs[_CS_TH] = 0.0
    ah, gv = _floor(m.tau, fc)
    mode, s, sig, om, w, ok = _settle(Motion(mode, s, sig, 0.0, om, m.u, w, m.tau), ah, gv, bd, cfg.rest_velocity)
    _set_mode(cs, mode, s, sig, om, w)
    out[OUT_IMPACT_LOSS] += e_before - _energy(mode, s, 0.0, om, w, 0.0, 0.0, bd)
    if not ok:
        cs[_CS_TAKEOFF] = True
        return _GO
    cs[_CS_FRESH_TH] = mode == ROCK or mode == SLIDE_ROCK
    cs[_CS_FRESH_W] = mode == SLIDE_ROCK and w == 0.0
    _record(hist, out, _motion(cs))
    return _GO


@jitable
def _stick_slip(bd, fc, cs, out, hist):
    """The stick-slip event: a rocking block's pivot starts slipping (a take-off next if its contact force is gone
    with the friction's hold: slide-rocking from there, the contact event, which needs the force positive at a step's
    start, would not see it), a slide-rocking one's slip stops (it sticks, or slips back), a sliding one stops and
    takes the mode it starts in (a take-off next if flight). Returns :data:`_GO`."""
    m = _motion(cs)
    mode, s, sig, th, om = m.mode, m.s, m.sig, m.th, m.om
    ah, gv = _floor(m.tau, fc)
    if mode == ROCK:
        f, n = rock_forces(s, th, om, ah, gv, bd.alpha, bd.kap)
        if n <= 0.0:  # the contact force is gone with the friction's hold (both at once): it leaves the floor
            cs[_CS_TAKEOFF] = True
            return _GO
        _set_mode(cs, SLIDE_ROCK, s, -1.0 if f > 0.0 else 1.0, om, 0.0)
        cs[_CS_FRESH_W] = True
    elif mode == SLIDE_ROCK:
        f, n = rock_forces(s, th, om, ah, gv, bd.alpha, bd.kap)
        cs[_CS_W] = 0.0
        if abs(f) <= bd.mu_s * n:
            cs[_CS_MODE], cs[_CS_SIG] = ROCK, 0.0
        else:
            cs[_CS_SIG], cs[_CS_FRESH_W] = (-1.0 if f > 0.0 else 1.0), True
    else:
        mode, s, sig = start_mode(ah, gv, bd.beta, bd.mu_s, bd.mu_k, bd.kap)
        if mode == FLIGHT:
            _set_mode(cs, SLIDE, s, sig, om, 0.0)
            cs[_CS_TAKEOFF] = True
            return _GO
        cs[_CS_TH] = 0.0
        _set_mode(cs, mode, s, sig, 0.0, 0.0)
        fresh_th = mode == ROCK or mode == SLIDE_ROCK
        cs[_CS_FRESH_TH], cs[_CS_FRESH_W] = fresh_th, mode == SLIDE or mode == SLIDE_ROCK
        if fresh_th:
            out[OUT_ROCKED] = 1.0
    _record(hist, out, _motion(cs))
    return _GO


@jitable
def _at_event(cfg, bd, fc, cs, ev, out, hist):
    """The mode change at the end of a step cut by event ``ev`` (0 impact, 1 stick-slip, 2 contact lost: a take-off
    next, or overturning if the block leaves the floor beyond its hump turning outwards). Returns :data:`_GO` or the
    case's status."""
    if ev == 0:
        return _impact(cfg, bd, fc, cs, out, hist)
    if ev == 1:
        return _stick_slip(bd, fc, cs, out, hist)
    if cs[_CS_MODE] != SLIDE and cs[_CS_S] * cs[_CS_TH] > bd.alpha and cs[_CS_S] * cs[_CS_OM] > 0.0:
        # it leaves the floor beyond its hump, turning outwards: nothing brings it back
        out[OUT_OVERTURNED] = 1.0
        out[OUT_THETA_MAX] = OVERTURNING_ANGLE
        return STATUS_OK
    cs[_CS_TAKEOFF] = True
    return _GO


@jitable
def _finish(bd, cs, status, out):
    """The case's outputs at its end with ``status``: its time, peak tilt, first mode, base displacement and the
    energies of its last state."""
    m = _motion(cs)
    out[OUT_EVENT_TIME] = m.tau
    if out[OUT_OVERTURNED] > 0.0:
        out[OUT_THETA_MAX] = max(out[OUT_THETA_MAX], OVERTURNING_ANGLE)
    out[OUT_STATUS] = status
    out[OUT_FIRST_MODE] = max(out[OUT_FIRST_MODE], REST)
    out[OUT_SLIDE_END] = m.u
    fy, fvy = cs[_CS_FY], cs[_CS_FVY]
    total = _energy(m.mode, m.s, m.th, m.om, m.w, fy, fvy, bd)
    out[OUT_POTENTIAL] = fy - bd.ca if m.mode == FLIGHT else potential_energy(m.s if m.mode != SLIDE else 0.0, m.th,
                                                                              bd.alpha)
    out[OUT_KINETIC] = total - out[OUT_POTENTIAL]


#: The hand-over state between the two entry points (:func:`solve_case`, :func:`fly_case`): the case state ``cs``
#: (slots ``_CS_*``), the forcing context ``fc`` (slots ``_FC_*``), then 1.0 once a kernel has handed the case over.
ST_CS, ST_FC, ST_RESUME = 0, _CS_SIZE, _CS_SIZE + _FC_SIZE
ST_SIZE = ST_RESUME + 1
#: What :func:`solve_case` returns when the block leaves the floor (:func:`fly_case` goes on from ``state``), and
#: :func:`fly_case` when it is back on it (:func:`solve_case` goes on); any other value: the case's status.
AIRBORNE, LANDED = np.int64(-2), np.int64(-3)


def state():
    """A fresh hand-over state (:data:`ST_SIZE` slots): :func:`solve_case` starts the case from it."""
    return np.zeros(ST_SIZE)


@jitable
def _resume(state, cs, fc):
    """The case state and forcing context handed over in ``state`` copied into ``cs`` and ``fc``."""
    for i in range(_CS_SIZE):
        cs[i] = state[ST_CS + i]
    for i in range(_FC_SIZE):
        fc[i] = state[ST_FC + i]


@jitable
def _hand_over(bd, cs, fc, status, out, state):
    """The end of an entry point's call with ``status``: the state handed over to the other entry point
    (:data:`AIRBORNE`, :data:`LANDED`), or the case's outputs (:func:`_finish`). Returns ``status``."""
    if status != AIRBORNE and status != LANDED:
        _finish(bd, cs, status, out)
        return status
    for i in range(_CS_SIZE):
        state[ST_CS + i] = cs[i]
    for i in range(_FC_SIZE):
        state[ST_FC + i] = fc[i]
    state[ST_RESUME] = 1.0
    return status


@numba.njit(cache=True)
def solve_case(params, kvals, gvals, out, hist, state):
    """Solve one case from rest (or from ``theta0``, ``omega0`` rocking without slip) while the block stays on the
    floor; ``params`` holds the scalars (slots ``P_*``), results go in ``out`` (slots ``OUT_*``), the history in the
    rows ``hist`` (:func:`history`, columns ``H_*``). Returns the case's status, or :data:`AIRBORNE` when the block
    leaves the floor: :func:`fly_case` goes on from ``state`` (:func:`state`: fresh, the case starts; handed over,
    it goes on from there). Free flight is a kernel of its own, compiled only when a block first leaves the floor
    (about a sixth of the compile; most cases never fly: issue 43).

    Excitation: ``(form, k, nu, phase)`` of :func:`opsrock.solvers.forcing.forcing` up to ``tau_end``
    for an analytic pulse; for ``form == FORM_LINEAR`` the samples ``kvals`` (``a_h/g`` at
    ``tau = i dtau``). Vertical: the samples ``gvals`` (``1 + a_v/g``, same grid; length 0: the
    constant ``g_const``); after the excitation ``g_tail``. ``f_rest = e / e_H``; ``mu_s``, ``mu_k``
    may be ``inf`` (no slip). Steps: ``h_nom`` during the excitation, ``h_tail`` after it (units of
    ``1/p``), followed for at most ``max_tail``. The case's state between steps is the vector ``cs`` (slots
    ``_CS_*``: the :class:`Motion`, in flight the centre's height and vertical velocity, the flags of a mode just
    entered, the forcing segment); each turn of :func:`_solve`'s loop is one phase (a block leaving rest or a step
    on the floor); the counts and peaks accumulate in ``out`` as they go.
    """
    return _solve(params, kvals, gvals, out, hist, state)


@jitable
def _solve(params, kvals, gvals, out, hist, state):
    """:func:`solve_case`'s work. The entry point calls this one helper only: numba compiles a helper once for each
    set of compile flags it is called under, and an entry point's differ from a helper's (it has a CPython wrapper),
    so a helper called both from the entry point and from another helper would be compiled twice (issue 43: cold
    compile time). Measured: this body written in the entry point itself saves the entry's second optimisation of
    the whole kernel but compiles four helpers twice, and took as long (alternated runs, 11.3 s against 10.8 s).
    ``cs`` and ``fc`` are allocated here, the handed-over state copied in: passed in, the kernel was 7 % slower per
    case (LLVM cannot tell that they overlap no other array)."""
    cfg, bd = _setup(params, kvals, gvals)
    fc = np.zeros(_FC_SIZE)
    cs = np.zeros(_CS_SIZE)
    if state[ST_RESUME] > 0.0:
        _resume(state, cs, fc)
    else:
        fc[_FC_KAPPA] = params[P_KAPPA]
        _start(params, cfg, bd, fc, cs, out, hist)
    status = _GO
    while status == _GO:  # a turn: the block leaving the floor, the excitation's end, then a phase by mode
        if cs[_CS_TAKEOFF] > 0.0:
            status = AIRBORNE
            break
        if out[OUT_STEPS] >= cfg.max_steps:
            status = STATUS_MAX_STEPS
            break
        tau = cs[_CS_TAU]
        if cs[_CS_TAIL] == 0.0 and tau >= cfg.tau_end:  # a still floor from here, the vertical acceleration g_tail
            cs[_CS_TAIL] = 1.0
            fc[_FC_TAIL], fc[_FC_G0], fc[_FC_G1], fc[_FC_GT0] = 1.0, cfg.g_tail, 0.0, 0.0
            cs[_CS_SEG_END] = math.inf
        tail = cs[_CS_TAIL] > 0.0
        mode = int(cs[_CS_MODE])
        if mode == REST:  # it leaves rest; after the excitation the case ends
            status = STATUS_OK if tail else _leave_rest(cfg, bd, fc, cs, out, hist)
            continue
        if tail and mode == SLIDE and _unstoppable(cs[_CS_W], bd.mu_k, cfg.g_tail,
                                                   cfg.max_tail - (tau - cfg.tau_end), bd.kap):
            _seat_slide(cfg, bd, cs, out)
            status = STATUS_OK
            break
        if tail and tau - cfg.tau_end > cfg.max_tail:
            status = STATUS_TAIL
            break
        if not tail and tau >= cs[_CS_SEG_END]:
            cs[_CS_SEG], cs[_CS_SEG_END] = _set_segment(fc, tau, int(cs[_CS_SEG]), cfg.exc, cfg.gvals, cfg.g_const)
        h = min(cfg.h_tail if tail else cfg.h_nom, cs[_CS_SEG_END] - tau)
        last = h == cs[_CS_SEG_END] - tau
        status = _rk_step(cfg, bd, fc, cs, _trial_step(bd, fc, cs, h, last, out), out, hist)
    return _hand_over(bd, cs, fc, status, out, state)


@numba.njit(cache=True)
def fly_case(params, kvals, gvals, out, hist, state):
    """:func:`solve_case`'s case on from the ``state`` it handed over when the block left the floor: a take-off, then
    free flight until the block is back on the floor (:data:`LANDED`: :func:`solve_case` goes on from ``state``) or
    the case ends (its status). The same arguments as :func:`solve_case`'s; compiled only when a block first leaves
    the floor."""
    return _fly_solve(params, kvals, gvals, out, hist, state)


@jitable
def _fly_solve(params, kvals, gvals, out, hist, state):
    """:func:`fly_case`'s work (its one helper, as :func:`_solve` is :func:`solve_case`'s): the turns of
    :func:`_solve`'s loop while the block is in flight, in the same order (a take-off if one is due, the step
    limit, the excitation's end, the tail's limit, then a flight step on the forcing segment)."""
    cfg, bd = _setup(params, kvals, gvals)
    fc = np.zeros(_FC_SIZE)
    cs = np.zeros(_CS_SIZE)
    _resume(state, cs, fc)
    status = _GO
    while status == _GO:
        if cs[_CS_TAKEOFF] > 0.0:
            _take_off(bd, cs, out, hist)
        status = _flight_turn(cfg, fc, cs, out)
        if status == _GO:
            span = cs[_CS_SEG_END] - cs[_CS_TAU]
            h = min(cfg.h_tail if cs[_CS_TAIL] > 0.0 else cfg.h_nom, span)
            status = _fly_step(cfg, bd, fc, cs, h, h == span, out, hist)
    return _hand_over(bd, cs, fc, status, out, state)


@jitable
def _flight_turn(cfg, fc, cs, out):
    """The start of a turn of :func:`_fly_solve`'s loop: :data:`LANDED` if the block is back on the floor, the
    status of a limit reached (steps; the time after the excitation), else :data:`_GO` with the excitation's end
    entered or the forcing segment of the time loaded."""
    if int(cs[_CS_MODE]) != FLIGHT:
        return LANDED
    if out[OUT_STEPS] >= cfg.max_steps:
        return STATUS_MAX_STEPS
    tau = cs[_CS_TAU]
    if cs[_CS_TAIL] == 0.0 and tau >= cfg.tau_end:  # as in _solve: a still floor from here, g_tail
        cs[_CS_TAIL] = 1.0
        fc[_FC_TAIL], fc[_FC_G0], fc[_FC_G1], fc[_FC_GT0] = 1.0, cfg.g_tail, 0.0, 0.0
        cs[_CS_SEG_END] = math.inf
    if cs[_CS_TAIL] > 0.0:
        return STATUS_TAIL if tau - cfg.tau_end > cfg.max_tail else _GO
    if tau >= cs[_CS_SEG_END]:
        cs[_CS_SEG], cs[_CS_SEG_END] = _set_segment(fc, tau, int(cs[_CS_SEG]), cfg.exc, cfg.gvals, cfg.g_const)
    return _GO


__all__ = ["AIRBORNE", "H_OMEGA", "H_SIZE", "H_TAU", "H_THETA", "H_U", "LANDED", "OUT_SIZE", "P_SIZE", "STATUS_OK",
           "fly_case", "history", "solve_case", "state"]
