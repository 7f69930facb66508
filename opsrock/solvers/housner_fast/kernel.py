"""Compiled kernels of :mod:`opsrock.solvers.housner_fast` (numba): one integrator for the one-sine
pulse and for piecewise-linear records.

The method is described in :mod:`opsrock.solvers.housner_fast`. A record enters as segments, one
per sample interval, each with a linear acceleration; every step ends on a segment end, so the
integrator never steps across a kink of the floor motion, and the uplift of a seated block is
found in closed form on each segment.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers import status as ST
from opsrock.solvers.forcing import forcing, next_exceedance, pulse_forcing, segment
from opsrock.solvers.jitable import jitable

# --- status codes: the shared ones (:mod:`opsrock.solvers.status`), one per case in :class:`GridResult` --
#: Finished: verdict (no uplift, safe or overturned) is valid.
STATUS_OK = ST.OK
#: More impacts than ``max_impacts`` without coming to rest: no verdict.
STATUS_MAX_IMPACTS = ST.MAX_IMPACTS
#: A non-finite state appeared: no verdict.
STATUS_NONFINITE = ST.NONFINITE
#: More integrator steps than ``max_steps``: no verdict.
STATUS_MAX_STEPS = ST.MAX_STEPS
#: Event location (impact or peak) did not converge: no verdict.
STATUS_EVENT_FAILED = ST.EVENT_FAILED

#: Human-readable reason for every failure code (the shared ones).
STATUS_REASONS: dict[int, str] = ST.REASONS

# --- the named tuples the kernel passes (QuantEcon's layout: one builder each) -----------------------------
#: The block and the numerics of one case: ``alpha`` (rad) and ``e``; ``lineq``, the linearised equation; ``level``
#: the ``|a|/g`` that uplifts a seated block (``alpha`` linearised, else ``tan(alpha)``); the nominal step
#: ``h_nom`` (units of 1/p), the rest velocity (units of p) and the limits (counts). Built by :func:`case_params`.
Params = namedtuple("Params", ["alpha", "e", "lineq", "level", "h_nom", "rest_velocity", "max_impacts", "max_steps"])
#: Where the history goes (``tau`` units of 1/p, ``theta`` rad, ``omega`` units of p); arrays of length 0: none.
History = namedtuple("History", ["tau", "theta", "omega"])
#: The motion between steps: time (units of 1/p), rotation (rad) and its rate (units of p), the pivot ``side``
#: (+1/-1, 0 seated), ``fresh`` (right after an impact or uplift, ``theta == 0`` exactly) and the forcing segment.
State = namedtuple("State", ["tau", "theta", "omega", "side", "fresh", "seg"])
#: What a case has counted so far: peak ``|theta|`` (rad), whether it rocked, impacts, steps, history rows.
Tally = namedtuple("Tally", ["theta_max", "rocked", "n_imp", "n_steps", "n_hist"])
#: The floor's acceleration on the current segment: ``form`` and coefficients of :func:`forcing`.
Piece = namedtuple("Piece", ["form", "c0", "c1", "c2"])
#: One trial step of length ``h`` (units of 1/p) to ``(th1, w1)``; ``last``: it ends on the segment's end ``end``.
Trial = namedtuple("Trial", ["h", "last", "end", "th1", "w1"])
#: A case's answer: peak ``|theta|`` (rad), overturned, rocked, status (:mod:`opsrock.solvers.status`), impacts,
#: steps and history rows written.
Outcome = namedtuple("Outcome", ["theta_max", "overturned", "rocked", "status", "n_impacts", "n_steps", "n_hist"])
#: The cases of a batch (:func:`_solve_chunk`), arrays over the cases: ``alpha`` (rad), ``e``, ``k = PFA/g`` and
#: ``nu = omega_p / p``.
Cases = namedtuple("Cases", ["alpha", "e", "k", "nu"])
#: The settings of a batch: the pulse id, ``lineq``, the largest step (units of 1/p), the steps per pulse period,
#: the rest velocity (units of p) and the limits.
BatchSettings = namedtuple("BatchSettings", ["pulse", "lineq", "max_step", "steps_per_pulse", "rest_velocity",
                                             "max_impacts", "max_steps"])
#: The arrays a batch writes, one entry per case: the fields of :class:`Outcome` but the history.
Answers = namedtuple("Answers", ["theta_max", "overturned", "rocked", "status", "n_impacts", "n_steps"])
#: Length of the output vector: the shared slots only (:mod:`opsrock.solvers.status`).
OUT_SIZE = ST.OUT_COMMON

#: Iterations allowed to the safeguarded Newton event location (it converges in 2-4; 60
#: bisection halvings alone would shrink any bracket below double precision).
_EVENT_MAX_ITER = 60

#: Shortest post-impact trial step (in units of 1/p) before an excursion is treated as
#: negligible: far below any time scale of the problem (a 1e-14 fraction of 1/p).
_MIN_STEP = 1e-14


#: Relative width (of ``max(1, tau)``) to which an event is located: a few ulps of the time.
_EVENT_TOL = 4e-16

#: Non-literal constants for arguments of compiled functions: numba compiles a callee (and all it calls) once more
#: for each literal argument it meets while it infers a caller (issue 43: cold compile time). The events
#: :func:`_locate` finds (``theta = 0``, ``omega = 0``), a zero count, a flag and the statuses a case ends with.
_THETA_ZERO, _OMEGA_ZERO, _ZERO, _NO = np.int64(0), np.int64(1), np.int64(0), np.bool_(False)
_OK, _MAX_STEPS, _EVENT_FAILED = np.int64(STATUS_OK), np.int64(STATUS_MAX_STEPS), np.int64(STATUS_EVENT_FAILED)


@numba.njit(cache=True)
def case_params(alpha, e, lineq, h_nom, rest_velocity, max_impacts, max_steps):
    """The :class:`Params` of one case (``alpha`` rad, ``e``, ``lineq`` bool, ``h_nom`` units of 1/p,
    ``rest_velocity`` units of p, the limits counts), typed alike wherever it is built."""
    level = alpha if lineq else math.tan(alpha)
    return Params(float(alpha), float(e), bool(lineq), level, float(h_nom), float(rest_velocity),
                  int(max_impacts), int(max_steps))


@jitable
def _accel(theta, tau, side, par, pc):
    """d²theta/dtau² on pivot ``side`` (+1/-1) under the forcing :class:`Piece` ``pc``; the exact
    equation, or its small-angle form when ``par.lineq``."""
    ag = forcing(tau, pc.form, pc.c0, pc.c1, pc.c2)
    phi = side * par.alpha - theta
    if par.lineq:
        return -(phi + ag)
    return -(math.sin(phi) + ag * math.cos(phi))


@jitable
def _rk4(theta, omega, tau, h, side, par, pc):
    """One classical RK4 step of size ``h`` (the right side does not depend on omega)."""
    a1 = _accel(theta, tau, side, par, pc)
    th2 = theta + 0.5 * h * omega
    w2 = omega + 0.5 * h * a1
    a2 = _accel(th2, tau + 0.5 * h, side, par, pc)
    th3 = theta + 0.5 * h * w2
    w3 = omega + 0.5 * h * a2
    a3 = _accel(th3, tau + 0.5 * h, side, par, pc)
    th4 = theta + h * w3
    w4 = omega + h * a3
    a4 = _accel(th4, tau + h, side, par, pc)
    theta_new = theta + h / 6.0 * (omega + 2.0 * w2 + 2.0 * w3 + w4)
    omega_new = omega + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
    return theta_new, omega_new


@jitable
def _locate(which, st, h, par, pc):
    """Step length ``d`` in (0, h] from the state ``st`` at which the RK4 map's ``theta`` (which=0) or
    ``omega`` (which=1) vanishes, given a sign change over ``[0, h]``. Safeguarded Newton (bisection
    fallback) on the RK4 map, derivative from the right side. Returns (d, ok)."""
    theta, omega, tau, side = st.theta, st.omega, st.tau, st.side
    lo = 0.0
    hi = h
    f_lo = theta if which == 0 else omega
    th_h, w_h = _rk4(theta, omega, tau, h, side, par, pc)
    f_hi = th_h if which == 0 else w_h
    if f_hi == 0.0:
        return h, True
    # linear first guess from the end values
    d = lo + (hi - lo) * f_lo / (f_lo - f_hi)
    for _ in range(_EVENT_MAX_ITER):
        if not (lo < d < hi):
            d = 0.5 * (lo + hi)
        th_d, w_d = _rk4(theta, omega, tau, d, side, par, pc)
        f = th_d if which == 0 else w_d
        if f == 0.0:
            return d, True
        if (f > 0.0) == (f_lo > 0.0):
            lo = d
        else:
            hi = d
        df = w_d if which == 0 else _accel(th_d, tau + d, side, par, pc)
        step = f / df if df != 0.0 else 0.0
        d_new = d - step
        if abs(step) <= _EVENT_TOL * max(1.0, tau + d) or hi - lo <= _EVENT_TOL * max(1.0, tau + d):
            if lo < d_new < hi:
                return d_new, True
            return d, True
        d = d_new
    return d, False


@jitable
def _free_verdict(par, st):
    """Exact verdict after the excitation (a = 0) from the rocking energy of the state ``st`` (per m g R in the
    exact form, per m g R alpha-scaled in the linearised one): returns (overturned, peak |theta| of the next
    excursion, impacts on the way, ok)."""
    alpha, e = par.alpha, par.e
    st_ = st.side * st.theta  # |theta| on the current pivot (>= 0)
    if par.lineq:
        energy = 0.5 * st.omega * st.omega + 0.5 * (alpha * alpha - (alpha - st_) ** 2)
        barrier = 0.5 * alpha * alpha
    else:
        energy = 0.5 * st.omega * st.omega + math.cos(alpha - st_) - math.cos(alpha)
        barrier = 1.0 - math.cos(alpha)
    outward = st.side * st.omega > 0.0
    n_imp = 0
    for _ in range(3):
        if st_ > alpha:
            if outward or energy <= barrier:
                return True, OVERTURNING_ANGLE, n_imp, True
            # crosses the hump inwards, falls to theta = 0, impact
            energy *= e * e
            n_imp += 1
            st_ = 0.0
            outward = True
        elif not outward:
            energy *= e * e
            n_imp += 1
            st_ = 0.0
            outward = True
        else:
            if energy > barrier:
                return True, OVERTURNING_ANGLE, n_imp, True
            if par.lineq:
                peak = alpha - math.sqrt(max(0.0, alpha * alpha - 2.0 * energy))
            else:
                peak = alpha - math.acos(min(1.0, energy + math.cos(alpha)))
            return False, peak, n_imp, True
    return False, 0.0, n_imp, False


@jitable
def _record(hist, n, tau, theta, omega):
    """Append one row to the history if it has room; returns the rows written."""
    if n < hist.tau.shape[0]:
        hist.tau[n] = tau
        hist.theta[n] = theta
        hist.omega[n] = omega
        return n + 1
    return n


@jitable
def _outcome(tl, overturned, status):
    """The :class:`Outcome` of a case ended with ``status``."""
    return Outcome(tl.theta_max, overturned, tl.rocked, status, tl.n_imp, tl.n_steps, tl.n_hist)


@jitable
def _start(theta0, omega0, hist):
    """The :class:`State` and :class:`Tally` of a case starting from ``theta0`` (rad), ``omega0`` (units of p)."""
    n_hist = _record(hist, _ZERO, 0.0, theta0, omega0)
    side = 0.0  # 0: seated; +1/-1: rocking on that pivot
    rocked = False
    fresh = False
    if theta0 != 0.0:
        side = 1.0 if theta0 > 0.0 else -1.0
        rocked = True
    elif omega0 != 0.0:
        side = 1.0 if omega0 > 0.0 else -1.0
        rocked = True
        fresh = True
    return State(0.0, theta0, omega0, side, fresh, 0), Tally(abs(theta0), rocked, 0, 0, n_hist)


@jitable
def _trial(par, exc, st, tl):
    """The step from the rocking state ``st`` on its forcing segment: ``(piece, trial, steps so far, seated,
    segment)``;
    right after an impact or uplift it is shortened to about the excursion's peak and halved until it stays on
    the new side; ``seated``: an excursion shorter than 1e-14/p, negligible."""
    seg, c0, c1, c2, seg_end = segment(exc, st.tau, st.seg)
    pc = Piece(exc.form, c0, c1, c2)
    tau, theta, omega, side = st.tau, st.theta, st.omega, st.side
    h = min(par.h_nom, seg_end - tau)
    last = h == seg_end - tau
    if st.fresh:
        acc0 = _accel(0.0, tau, side, par, pc)
        if side * acc0 < 0.0 and omega != 0.0:
            # restoring: the excursion peaks after about |omega| / |acc0|
            h_peak = abs(omega) / abs(acc0)
            if h_peak < h:
                h = h_peak
                last = False
    th1, w1 = _rk4(theta, omega, tau, h, side, par, pc)
    n_steps = tl.n_steps + 1
    seated = False
    if st.fresh:
        # the whole step must stay on the new side; halve until it does
        while side * th1 <= 0.0:
            h *= 0.5
            last = False
            if h < _MIN_STEP:
                break
            th1, w1 = _rk4(theta, omega, tau, h, side, par, pc)
            n_steps += 1
        seated = side * th1 <= 0.0
    return pc, Trial(h, last, seg_end, th1, w1), n_steps, seated, seg


@jitable
def _impact(par, pc, st, tl, tr, hist):
    """The step ``tr`` crosses ``theta = 0``: to the impact (and a peak before it), Housner's impact, and the
    block seated if it leaves too slowly towards a restoring acceleration. ``(state, tally, end)``: ``end`` -1
    goes on, else the status the case ends with."""
    theta_max, n_imp, n_steps = tl.theta_max, tl.n_imp, tl.n_steps
    d, ok = _locate(_THETA_ZERO, st, tr.h, par, pc)
    if not ok:
        return st, Tally(theta_max, tl.rocked, n_imp, n_steps, tl.n_hist), STATUS_EVENT_FAILED
    th_d, w_d = _rk4(st.theta, st.omega, st.tau, d, st.side, par, pc)
    n_steps += 1
    # a peak may lie between the start of the step and the impact
    if st.omega * w_d < 0.0:
        dp, ok = _locate(_OMEGA_ZERO, st, d, par, pc)
        if not ok:
            return st, Tally(theta_max, tl.rocked, n_imp, n_steps, tl.n_hist), STATUS_EVENT_FAILED
        th_p, _ = _rk4(st.theta, st.omega, st.tau, dp, st.side, par, pc)
        theta_max = max(theta_max, abs(th_p))
    tau = st.tau + d if d < tr.h else (tr.end if tr.last else st.tau + tr.h)
    n_imp += 1
    if n_imp > par.max_impacts:
        return st, Tally(theta_max, tl.rocked, n_imp, n_steps, tl.n_hist), STATUS_MAX_IMPACTS
    omega = par.e * w_d
    side = -st.side
    fresh = True
    n_hist = tl.n_hist
    if n_hist + 1 < hist.tau.shape[0]:  # the state just before and just after the impact
        n_hist = _record(hist, _record(hist, n_hist, tau, 0.0, w_d), tau, 0.0, omega)
    # come to rest? tiny velocity into a side whose acceleration points back to 0
    if abs(omega) < par.rest_velocity:
        acc_new = _accel(0.0, tau, side, par, pc)
        if side * acc_new <= 0.0:
            side = 0.0
            omega = 0.0
            fresh = False
    return State(tau, 0.0, omega, side, fresh, st.seg), Tally(theta_max, tl.rocked, n_imp, n_steps, n_hist), -1


@jitable
def _ordinary(par, pc, st, tl, tr, hist):
    """The step ``tr`` stays on its side: a peak inside it, then the new state, overturned or not. ``(state,
    tally, end)`` as :func:`_impact`."""
    theta_max = tl.theta_max
    if st.omega * tr.w1 < 0.0:
        dp, ok = _locate(_OMEGA_ZERO, st, tr.h, par, pc)
        if not ok:
            return st, tl, STATUS_EVENT_FAILED
        th_p, _ = _rk4(st.theta, st.omega, st.tau, dp, st.side, par, pc)
        theta_max = max(theta_max, abs(th_p))
    tau = tr.end if tr.last else st.tau + tr.h
    theta = tr.th1
    theta_max = max(theta_max, abs(theta))
    n_hist = _record(hist, tl.n_hist, tau, theta, tr.w1)
    new = State(tau, theta, tr.w1, st.side, False, st.seg)
    tally = Tally(theta_max, tl.rocked, tl.n_imp, tl.n_steps, n_hist)
    return new, tally, (STATUS_OK if abs(theta) >= OVERTURNING_ANGLE else -1)


@jitable
def _step(par, exc, st, tl, hist):
    """One step of a rocking block: ``(state, tally, end)`` as :func:`_impact` (``end`` :data:`STATUS_OK`: it
    overturned)."""
    pc, tr, n_steps, seated, seg = _trial(par, exc, st, tl)
    st = State(st.tau, st.theta, st.omega, st.side, st.fresh, seg)
    tl = Tally(tl.theta_max, tl.rocked, tl.n_imp, n_steps, tl.n_hist)
    if seated:
        return State(st.tau, 0.0, 0.0, 0.0, False, seg), tl, -1
    if not (math.isfinite(tr.th1) and math.isfinite(tr.w1)):
        return st, tl, STATUS_NONFINITE
    if st.side * tr.th1 < 0.0:
        return _impact(par, pc, st, tl, tr, hist)
    return _ordinary(par, pc, st, tl, tr, hist)


@numba.njit(cache=True)
def solve_case(par, exc, theta0, omega0, hist):
    """Solve one case in dimensionless time ``tau = p t``, from rotation ``theta0`` (rad) and
    angular velocity ``omega0`` (units of p), zero for a block at rest: the block and numerics
    :class:`Params`, the floor motion :class:`opsrock.solvers.forcing.Excitation` (steps end on every
    segment end). Returns the :class:`Outcome`; the :class:`History` is written at every accepted step,
    uplift and impact until its arrays are full (length 0: none).
    """
    st, tl = _start(theta0, omega0, hist)
    while True:
        if st.side == 0.0:
            t_up, sgn_a = next_exceedance(st.tau, par.level, exc)
            if t_up < 0.0:
                return _outcome(tl, _NO, _OK)
            n_hist = _record(hist, tl.n_hist, t_up, 0.0, 0.0)
            st = State(t_up, 0.0, 0.0, -sgn_a, True, st.seg)
            tl = Tally(tl.theta_max, True, tl.n_imp, tl.n_steps, n_hist)
        if st.tau >= exc.tau_end:
            break
        if tl.n_steps >= par.max_steps:
            return _outcome(tl, _NO, _MAX_STEPS)
        st, tl, end = _step(par, exc, st, tl, hist)
        if end >= 0:
            return _outcome(tl, end == STATUS_OK, end)
    # ---- pulse over, block rocking: exact free-rocking verdict from the energy -------------
    if st.side == 0.0:
        return _outcome(tl, _NO, _OK)
    ov, peak, extra, ok = _free_verdict(par, st)
    tl = Tally(tl.theta_max, tl.rocked, tl.n_imp + extra, tl.n_steps, tl.n_hist)
    if not ok:
        return _outcome(tl, _NO, _EVENT_FAILED)
    return _outcome(Tally(max(tl.theta_max, peak), tl.rocked, tl.n_imp, tl.n_steps, tl.n_hist), ov, _OK)


@numba.njit(cache=True, nogil=True)
def _solve_chunk(cases, opts, start, stop, answers):
    """Solve cases ``start:stop`` of :class:`Cases` under the analytic pulse and :class:`BatchSettings` ``opts``
    one after the other, into :class:`Answers` (releases the GIL, so Python threads can run chunks in parallel;
    each case is independent, so results do not depend on the chunking or the number of threads)."""
    empty = np.zeros(0)
    hist = History(empty, empty, empty)
    for i in range(start, stop):
        h_nom = min(opts.max_step, 2.0 * math.pi / cases.nu[i] / opts.steps_per_pulse)
        exc = pulse_forcing(opts.pulse, cases.k[i], cases.nu[i])
        par = case_params(cases.alpha[i], cases.e[i], opts.lineq, h_nom, opts.rest_velocity, opts.max_impacts,
                          opts.max_steps)
        res = solve_case(par, exc, 0.0, 0.0, hist)
        answers.theta_max[i] = res.theta_max
        answers.overturned[i] = res.overturned
        answers.rocked[i] = res.rocked
        answers.status[i] = res.status
        answers.n_impacts[i] = res.n_impacts
        answers.n_steps[i] = res.n_steps
