"""Compiled kernels of :mod:`opsrock.solvers.housner_fast` (numba): one integrator for the one-sine
pulse and for piecewise-linear records.

The method is described in :mod:`opsrock.solvers.housner_fast`. A record enters as segments, one
per sample interval, each with a linear acceleration; every step ends on a segment end, so the
integrator never steps across a kink of the floor motion, and the uplift of a seated block is
found in closed form on each segment.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from opsrock.constants import OVERTURNING_ANGLE
from opsrock.solvers import status as ST
from opsrock.solvers.forcing import forcing, next_exceedance, pulse_forcing, segment

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

# --- slots of the parameter vector of :func:`solve_case` ---------------------------------------------
#: The block (``alpha`` rad, ``e``); the forcing ``(form, k, nu, phase)`` up to ``tau_end``, the sample
#: interval and the nominal step (units of 1/p); 1.0 for the linearised equation; the rest velocity
#: (units of p) and the limits; the start state (``theta0`` rad, ``omega0`` units of p).
P_ALPHA, P_E, P_FORM, P_K, P_NU, P_PHASE, P_TAU_END, P_DTAU, P_H_NOM = 0, 1, 2, 3, 4, 5, 6, 7, 8
P_LINEQ, P_REST_VELOCITY, P_MAX_IMPACTS, P_MAX_STEPS, P_THETA0, P_OMEGA0 = 9, 10, 11, 12, 13, 14
P_SIZE = 15
#: Length of the output vector: the shared slots only (:mod:`opsrock.solvers.status`).
OUT_SIZE = ST.OUT_COMMON

#: Iterations allowed to the safeguarded Newton event location (it converges in 2-4; 60
#: bisection halvings alone would shrink any bracket below double precision).
_EVENT_MAX_ITER = 60

#: Shortest post-impact trial step (in units of 1/p) before an excursion is treated as
#: negligible: far below any time scale of the problem (a 1e-14 fraction of 1/p).
_MIN_STEP = 1e-14




@numba.njit(cache=True)
def _accel(theta, tau, side, alpha, form, c0, c1, c2, lineq):
    """d²theta/dtau² on pivot ``side`` (+1/-1) under the forcing ``(form, c0, c1, c2)``; the exact
    equation, or its small-angle form when ``lineq``."""
    ag = forcing(tau, form, c0, c1, c2)
    phi = side * alpha - theta
    if lineq:
        return -(phi + ag)
    return -(math.sin(phi) + ag * math.cos(phi))


@numba.njit(cache=True)
def _rk4(theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq):
    """One classical RK4 step of size ``h`` (the right side does not depend on omega)."""
    a1 = _accel(theta, tau, side, alpha, form, c0, c1, c2, lineq)
    th2 = theta + 0.5 * h * omega
    w2 = omega + 0.5 * h * a1
    a2 = _accel(th2, tau + 0.5 * h, side, alpha, form, c0, c1, c2, lineq)
    th3 = theta + 0.5 * h * w2
    w3 = omega + 0.5 * h * a2
    a3 = _accel(th3, tau + 0.5 * h, side, alpha, form, c0, c1, c2, lineq)
    th4 = theta + h * w3
    w4 = omega + h * a3
    a4 = _accel(th4, tau + h, side, alpha, form, c0, c1, c2, lineq)
    theta_new = theta + h / 6.0 * (omega + 2.0 * w2 + 2.0 * w3 + w4)
    omega_new = omega + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
    return theta_new, omega_new


@numba.njit(cache=True)
def _locate(which, theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq):
    """Step length ``d`` in (0, h] at which the RK4 map's ``theta`` (which=0) or ``omega``
    (which=1) vanishes, given a sign change over ``[0, h]``. Safeguarded Newton (bisection
    fallback) on the RK4 map, derivative from the right side. Returns (d, ok)."""
    lo = 0.0
    hi = h
    f_lo = theta if which == 0 else omega
    th_h, w_h = _rk4(theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq)
    f_hi = th_h if which == 0 else w_h
    if f_hi == 0.0:
        return h, True
    # linear first guess from the end values
    d = lo + (hi - lo) * f_lo / (f_lo - f_hi)
    for _ in range(_EVENT_MAX_ITER):
        if not (lo < d < hi):
            d = 0.5 * (lo + hi)
        th_d, w_d = _rk4(theta, omega, tau, d, side, alpha, form, c0, c1, c2, lineq)
        f = th_d if which == 0 else w_d
        if f == 0.0:
            return d, True
        if (f > 0.0) == (f_lo > 0.0):
            lo = d
        else:
            hi = d
        df = w_d if which == 0 else _accel(th_d, tau + d, side, alpha, form, c0, c1, c2, lineq)
        step = f / df if df != 0.0 else 0.0
        d_new = d - step
        if abs(step) <= 4e-16 * max(1.0, tau + d) or hi - lo <= 4e-16 * max(1.0, tau + d):
            if lo < d_new < hi:
                return d_new, True
            return d, True
        d = d_new
    return d, False


@numba.njit(cache=True)
def _free_verdict(alpha, e, side, theta, omega, lineq):
    """Exact verdict after the excitation (a = 0) from the rocking energy (per m g R in the exact
    form, per m g R alpha-scaled in the linearised one): returns (overturned, peak |theta| of the
    next excursion, impacts on the way, ok)."""
    st = side * theta  # |theta| on the current pivot (>= 0)
    if lineq:
        energy = 0.5 * omega * omega + 0.5 * (alpha * alpha - (alpha - st) ** 2)
        barrier = 0.5 * alpha * alpha
    else:
        energy = 0.5 * omega * omega + math.cos(alpha - st) - math.cos(alpha)
        barrier = 1.0 - math.cos(alpha)
    outward = side * omega > 0.0
    n_imp = 0
    for _ in range(3):
        if st > alpha:
            if outward or energy <= barrier:
                return True, OVERTURNING_ANGLE, n_imp, True
            # crosses the hump inwards, falls to theta = 0, impact
            energy *= e * e
            n_imp += 1
            st = 0.0
            outward = True
        elif not outward:
            energy *= e * e
            n_imp += 1
            st = 0.0
            outward = True
        else:
            if energy > barrier:
                return True, OVERTURNING_ANGLE, n_imp, True
            if lineq:
                peak = alpha - math.sqrt(max(0.0, alpha * alpha - 2.0 * energy))
            else:
                peak = alpha - math.acos(min(1.0, energy + math.cos(alpha)))
            return False, peak, n_imp, True
    return False, 0.0, n_imp, False


@numba.njit(cache=True)
def _solve_case(alpha, e, form, k, nu, phase, tau_end, kvals, dtau, h_nom, lineq, rest_velocity,
                max_impacts, max_steps, theta0, omega0, hist_tau, hist_theta, hist_omega):
    """Solve one case in dimensionless time ``tau = p t``, from rotation ``theta0`` (rad) and
    angular velocity ``omega0`` (units of p), zero for a block at rest.

    Excitation: the forcing ``(form, k, nu, phase)`` of :func:`_forcing` up to ``tau_end`` for an
    analytic pulse (:func:`pulse_forcing`); for ``form == FORM_LINEAR`` the samples ``kvals``
    (a/g at ``tau = i dtau``, linear between, ending at ``tau_end``). ``h_nom`` is the nominal step
    (units of 1/p); steps also end on every segment end. ``lineq``: the small-angle equation.

    Returns (theta_max, overturned, rocked, status, n_impacts, n_steps, n_hist).
    History arrays of length 0 disable recording; otherwise states are recorded at every
    accepted step, uplift and impact until the arrays are full.
    """
    level = alpha if lineq else math.tan(alpha)
    seg = 0
    n_cap = hist_tau.shape[0]
    n_hist = 0
    if n_cap > 0:
        hist_tau[0] = 0.0
        hist_theta[0] = theta0
        hist_omega[0] = omega0
        n_hist = 1

    tau = 0.0
    theta = theta0
    omega = omega0
    side = 0.0  # 0: seated; +1/-1: rocking on that pivot
    theta_max = abs(theta0)
    rocked = False
    n_imp = 0
    n_steps = 0
    fresh = False  # True right after an impact or uplift (theta == 0 exactly)
    if theta0 != 0.0:
        side = 1.0 if theta0 > 0.0 else -1.0
        rocked = True
    elif omega0 != 0.0:
        side = 1.0 if omega0 > 0.0 else -1.0
        rocked = True
        fresh = True

    while True:
        if side == 0.0:
            t_up, sgn_a = next_exceedance(tau, level, form, k, nu, phase, tau_end, kvals, dtau)
            if t_up < 0.0:
                return theta_max, False, rocked, STATUS_OK, n_imp, n_steps, n_hist
            tau = t_up
            side = -sgn_a
            theta = 0.0
            omega = 0.0
            rocked = True
            fresh = True
            if n_hist < n_cap:
                hist_tau[n_hist] = tau
                hist_theta[n_hist] = 0.0
                hist_omega[n_hist] = 0.0
                n_hist += 1
        if tau >= tau_end:
            break
        if n_steps >= max_steps:
            return theta_max, False, rocked, STATUS_MAX_STEPS, n_imp, n_steps, n_hist

        seg, c0, c1, c2, seg_end = segment(form, tau, seg, k, nu, phase, tau_end, kvals, dtau)
        h = min(h_nom, seg_end - tau)
        last = h == seg_end - tau
        if fresh:
            acc0 = _accel(0.0, tau, side, alpha, form, c0, c1, c2, lineq)
            if side * acc0 < 0.0 and omega != 0.0:
                # restoring: the excursion peaks after about |omega| / |acc0|
                h_peak = abs(omega) / abs(acc0)
                if h_peak < h:
                    h = h_peak
                    last = False
        th1, w1 = _rk4(theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq)
        n_steps += 1
        if fresh:
            # the whole step must stay on the new side; halve until it does
            while side * th1 <= 0.0:
                h *= 0.5
                last = False
                if h < _MIN_STEP:
                    break
                th1, w1 = _rk4(theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq)
                n_steps += 1
            if side * th1 <= 0.0:
                # an excursion shorter than 1e-14/p: negligible, seat the block
                side = 0.0
                theta = 0.0
                omega = 0.0
                fresh = False
                continue
        if not (math.isfinite(th1) and math.isfinite(w1)):
            return theta_max, False, rocked, STATUS_NONFINITE, n_imp, n_steps, n_hist

        if side * th1 < 0.0:
            # impact inside the step
            d, ok = _locate(0, theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq)
            if not ok:
                return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist
            th_d, w_d = _rk4(theta, omega, tau, d, side, alpha, form, c0, c1, c2, lineq)
            n_steps += 1
            # a peak may lie between the start of the step and the impact
            if omega * w_d < 0.0:
                dp, ok = _locate(1, theta, omega, tau, d, side, alpha, form, c0, c1, c2, lineq)
                if not ok:
                    return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist
                th_p, _ = _rk4(theta, omega, tau, dp, side, alpha, form, c0, c1, c2, lineq)
                theta_max = max(theta_max, abs(th_p))
            tau = tau + d if d < h else (seg_end if last else tau + h)
            n_imp += 1
            if n_imp > max_impacts:
                return theta_max, False, rocked, STATUS_MAX_IMPACTS, n_imp, n_steps, n_hist
            omega = e * w_d
            theta = 0.0
            side = -side
            fresh = True
            if n_hist + 1 < n_cap:  # the state just before and just after the impact
                hist_tau[n_hist] = tau
                hist_theta[n_hist] = 0.0
                hist_omega[n_hist] = w_d
                hist_tau[n_hist + 1] = tau
                hist_theta[n_hist + 1] = 0.0
                hist_omega[n_hist + 1] = omega
                n_hist += 2
            # come to rest? tiny velocity into a side whose acceleration points back to 0
            if abs(omega) < rest_velocity:
                acc_new = _accel(0.0, tau, side, alpha, form, c0, c1, c2, lineq)
                if side * acc_new <= 0.0:
                    side = 0.0
                    omega = 0.0
                    fresh = False
            continue

        # ordinary step: a peak inside it?
        if omega * w1 < 0.0:
            dp, ok = _locate(1, theta, omega, tau, h, side, alpha, form, c0, c1, c2, lineq)
            if not ok:
                return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist
            th_p, _ = _rk4(theta, omega, tau, dp, side, alpha, form, c0, c1, c2, lineq)
            theta_max = max(theta_max, abs(th_p))
        tau = seg_end if last else tau + h
        theta = th1
        omega = w1
        fresh = False
        theta_max = max(theta_max, abs(theta))
        if n_hist < n_cap:
            hist_tau[n_hist] = tau
            hist_theta[n_hist] = theta
            hist_omega[n_hist] = omega
            n_hist += 1
        if abs(theta) >= OVERTURNING_ANGLE:
            return theta_max, True, rocked, STATUS_OK, n_imp, n_steps, n_hist

    # ---- pulse over, block rocking: exact free-rocking verdict from the energy -------------
    if side == 0.0:
        return theta_max, False, rocked, STATUS_OK, n_imp, n_steps, n_hist
    ov, peak, extra, ok = _free_verdict(alpha, e, side, theta, omega, lineq)
    if not ok:
        return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp + extra, n_steps, n_hist
    return max(theta_max, peak), ov, rocked, STATUS_OK, n_imp + extra, n_steps, n_hist


@numba.njit(cache=True)
def solve_case(params, kvals, out, hist_tau, hist_theta, hist_omega):
    """One case with its history: the scalars in ``params`` (slots ``P_*``), the samples ``kvals`` (record:
    ``a/g`` every ``dtau``), the answer in ``out`` (the shared slots of :mod:`opsrock.solvers.status`),
    the history in the arrays given (length 0: none). See :func:`_solve_case`."""
    tm, ov, rk, st, ni, ns, nh = _solve_case(
        params[P_ALPHA], params[P_E], int(params[P_FORM]), params[P_K], params[P_NU], params[P_PHASE],
        params[P_TAU_END], kvals, params[P_DTAU], params[P_H_NOM], params[P_LINEQ] > 0.0,
        params[P_REST_VELOCITY], int(params[P_MAX_IMPACTS]), int(params[P_MAX_STEPS]), params[P_THETA0],
        params[P_OMEGA0], hist_tau, hist_theta, hist_omega)
    out[:] = 0.0
    out[ST.OUT_STATUS], out[ST.OUT_THETA_MAX], out[ST.OUT_OVERTURNED], out[ST.OUT_ROCKED] = st, tm, ov, rk
    out[ST.OUT_IMPACTS], out[ST.OUT_STEPS], out[ST.OUT_N_HIST] = ni, ns, nh


@numba.njit(cache=True, nogil=True)
def _solve_chunk(alpha, e, k, nu, pulse, lineq, max_step, steps_per_pulse, rest_velocity, max_impacts,
                 max_steps, start, stop, theta_max, overturned, rocked, status, n_impacts, n_steps):
    """Solve cases ``start:stop`` of analytic pulse ``pulse`` (a :data:`PULSE_IDS` value) one after
    the other (releases the GIL, so Python threads can run chunks in parallel; each case is
    independent, so results do not depend on the chunking or the number of threads)."""
    empty = np.zeros(0)
    for i in range(start, stop):
        h_nom = min(max_step, 2.0 * math.pi / nu[i] / steps_per_pulse)
        form, c0, c1, c2, tau_end, kvals, dtau = pulse_forcing(pulse, k[i], nu[i])
        tm, ov, rk, st, ni, ns, _ = _solve_case(
            alpha[i], e[i], form, c0, c1, c2, tau_end, kvals, dtau, h_nom, lineq, rest_velocity,
            max_impacts, max_steps, 0.0, 0.0, empty, empty, empty)
        theta_max[i] = tm
        overturned[i] = ov
        rocked[i] = rk
        status[i] = st
        n_impacts[i] = ni
        n_steps[i] = ns
