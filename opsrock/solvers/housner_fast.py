"""Fast rigid-body rocking solver for dense overturning spectra (numba-compiled).

Solves the same exact rigid-body equation as :mod:`opsrock.solvers.housner` (paper Eq. 1-3,
docs/modelling.md section 2), written in the dimensionless time ``tau = p t``::

    d²theta/dtau² = -[ sin(alpha s - theta) + (a(t)/g) cos(alpha s - theta) ],   s = sgn(theta)

with uplift from rest only when ``|a| > g tan(alpha)`` (Eq. 4), towards ``s = -sgn(a)``;
instantaneous impacts at ``theta = 0`` that multiply the angular velocity by ``e``
(Housner's coefficient times the restitution factor); overturning at ``|theta| >= pi/2``
(Eq. 11).

Method
------
* While the pulse lasts: classical fourth-order Runge-Kutta with a fixed step
  ``h = min(max_step, 2 pi / (omega_p/p) / steps_per_pulse)`` (in units of ``1/p``), landing
  exactly on the end of the pulse (where ``a(t)`` has a kink). Impacts and peaks inside a
  step are located by a safeguarded Newton iteration *on the Runge-Kutta map itself* (the
  step length is the unknown), so the event time is consistent with the integrator to
  round-off. After an impact the first step is shortened to the predicted half-excursion
  ``|omega| / |theta''|`` (halved again if it still overshoots), so chattering sequences are
  resolved impact by impact with geometrically shrinking steps.
* Coming to rest (impacts accumulating): once an impact leaves less than ``rest_velocity``
  (dimensionless, ``theta' / p``) and the rotational acceleration on the new side points back
  to ``theta = 0``, the block is seated. The excursions that are dropped are smaller than
  ``rest_velocity² / (2 |theta''|)``. A seated block lifts off again, in closed form for the
  sine pulse, when ``|a|`` next exceeds ``g tan(alpha)``.
* After the pulse (``a = 0``) nothing is integrated: the energy
  ``E = omega²/2 + cos(alpha - |theta|) - cos(alpha)`` (per ``m g R``) is conserved between
  impacts and multiplied by ``e²`` at each one, so the block overturns if and only if it
  heads over the barrier ``1 - cos(alpha)`` with more energy than that, and otherwise its
  next peak is ``alpha - arccos(E + cos alpha)``, after which every impact lowers the energy
  and ``theta_max`` can no longer grow. A block beyond the hump (``|theta| > alpha``) at the
  end of the pulse overturns if it heads out, or heads in without the energy to recross the
  hump; with that energy it falls back to ``theta = 0``, impacts, and the same rules apply.
  This is exact, not an approximation.

Why numba: a per-case ``solve_ivp`` loop costs milliseconds per case (Python overhead per
step and per restart at every impact), too slow for 40,000-case spectra; a numpy-vectorised
fixed-step integrator over all cases wastes work on cases that have already settled or
overturned and handles per-case events clumsily. A compiled per-case integrator with a
thread pool over chunks of cases has neither problem. Measured by
``python bench/bench_housner_fast.py`` on the 2-core project machine while it was shared
(load average 8-11): 40,000 cases in 2.4-3.7 s, 25-90 µs per case against 23-77 ms per
case for a per-case ``solve_ivp`` loop (x250-x2000), with ``|d theta_max| / alpha`` below
1e-8 of the converged answer. The kernel is compiled once and cached (``cache=True``, in
``__pycache__``): about 16-20 s for a cold compile on that machine, 2-4 s to load the
cache in a new process.
"""

from __future__ import annotations

import math
import os
import time as _time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, replace
from typing import Any, Sequence

import numba
import numpy as np

from opsrock._checks import bool_fields, int_at_least, positive_finite
from opsrock.block import Block
from opsrock.constants import G, OVERTURNING_ANGLE
from opsrock.excitation import OneSinePulse
from opsrock.result import RockingResult, failed_result

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "housner_fast"

# --- status codes of the compiled kernel (one per case in :class:`GridResult`) ---------------
#: Finished: verdict (no uplift, safe or overturned) is valid.
STATUS_OK = 0
#: More impacts than ``max_impacts`` without coming to rest: no verdict.
STATUS_MAX_IMPACTS = 1
#: A non-finite state appeared: no verdict.
STATUS_NONFINITE = 2
#: More integrator steps than ``max_steps``: no verdict.
STATUS_MAX_STEPS = 3
#: Event location (impact or peak) did not converge: no verdict.
STATUS_EVENT_FAILED = 4

#: Human-readable reason for every failure code.
STATUS_REASONS: dict[int, str] = {
    STATUS_OK: "",
    STATUS_MAX_IMPACTS: "max_impacts reached without the block coming to rest",
    STATUS_NONFINITE: "non-finite rotation or angular velocity",
    STATUS_MAX_STEPS: "max_steps reached before the end of the pulse",
    STATUS_EVENT_FAILED: "impact/peak location did not converge",
}

#: Iterations allowed to the safeguarded Newton event location (it converges in 2-4; 60
#: bisection halvings alone would shrink any bracket below double precision).
_EVENT_MAX_ITER = 60

#: Relative margin on Eq. 4: a PFA within 1e-12 of ``g tan(alpha)`` counts as *at* the
#: threshold, which does not uplift (Eq. 4 needs strict exceedance). Without it, round-off
#: in ``PFA = ratio * g * tan(alpha)`` (``b/h`` against ``tan(atan2(b, h))``, 1 ulp) could
#: turn the spectrum's ``pfa_ratio = 1`` row into a rocking of 1e-24 rad.
_UPLIFT_RTOL = 1e-12

#: Shortest post-impact trial step (in units of 1/p) before an excursion is treated as
#: negligible: far below any time scale of the problem (a 1e-14 fraction of 1/p).
_MIN_STEP = 1e-14


@dataclass(frozen=True)
class HousnerFastSettings:
    """Numerical settings of the fast rigid-body solver (all dimensionless).

    Parameters
    ----------
    max_step : float
        Largest Runge-Kutta step in units of ``1/p`` (dimensionless time ``tau = p t``).
        Default 0.02. Measured on the 40,000-case benchmark grid against a run with steps
        eight times shorter: (max_step, steps_per_pulse) = (0.02, 200) differs by at most
        1.5e-8 alpha in theta_max (0.04, 100: 2.3e-7; 0.08, 50: 2.5e-5), with the same
        verdict everywhere; the target is 5e-3 alpha, so the default keeps a wide
        margin for verdicts of cases close to the overturning boundary at little cost.
    steps_per_pulse : int
        Minimum number of steps per pulse period ``T_p`` (dimensionless count), so short
        pulses (``omega_p/p`` up to 10 and beyond) are resolved as finely as long ones.
        Default 200 (see ``max_step``).
    rest_velocity : float
        Angular velocity, in units of ``p`` rad/s, below which a block leaving an impact
        towards a restoring acceleration is taken as seated. Default 1e-7: the excursions
        dropped are then below ~1e-14 rad / |theta''| and the chattering tail they would
        take lasts less than ~1e-6 / p seconds.
    max_impacts : int
        Impacts allowed per case before it is reported as failed. Default 100000. One
        chattering sequence from ``theta' ~ p`` down to ``rest_velocity`` takes
        ``ln(1e-7)/ln(e)`` impacts: about 170 for ``e = 0.91`` (slender block) and 55 for
        ``e = 0.74`` (alpha = 0.42 rad).
    max_steps : int
        Integrator steps allowed per case before it is reported as failed. Default 10**7.
    """

    max_step: float = 0.02
    steps_per_pulse: int = 200
    rest_velocity: float = 1e-7
    max_impacts: int = 100_000
    max_steps: int = 10_000_000

    def __post_init__(self) -> None:
        bool_fields(self)
        positive_finite("max_step", self.max_step)
        if self.max_step > 0.5:
            raise ValueError(f"max_step must be <= 0.5 (units of 1/p), got {self.max_step!r}")
        int_at_least("steps_per_pulse", self.steps_per_pulse, 8)
        positive_finite("rest_velocity", self.rest_velocity)
        if self.rest_velocity > 1e-3:
            raise ValueError(f"rest_velocity must be <= 1e-3 (units of p), got {self.rest_velocity!r}")
        int_at_least("max_impacts", self.max_impacts, 1)
        int_at_least("max_steps", self.max_steps, 1)


# =============================================================================================
# Compiled kernel
# =============================================================================================


@numba.njit(cache=True)
def _accel(theta, tau, side, alpha, k, nu, tau_end):
    """d²theta/dtau² on pivot ``side`` (+1/-1); ``k = PFA/g``; pulse ``k sin(nu tau)`` to ``tau_end``."""
    ag = k * math.sin(nu * tau) if tau <= tau_end else 0.0
    phi = side * alpha - theta
    return -(math.sin(phi) + ag * math.cos(phi))


@numba.njit(cache=True)
def _rk4(theta, omega, tau, h, side, alpha, k, nu, tau_end):
    """One classical RK4 step of size ``h`` (the right side does not depend on omega)."""
    a1 = _accel(theta, tau, side, alpha, k, nu, tau_end)
    th2 = theta + 0.5 * h * omega
    w2 = omega + 0.5 * h * a1
    a2 = _accel(th2, tau + 0.5 * h, side, alpha, k, nu, tau_end)
    th3 = theta + 0.5 * h * w2
    w3 = omega + 0.5 * h * a2
    a3 = _accel(th3, tau + 0.5 * h, side, alpha, k, nu, tau_end)
    th4 = theta + h * w3
    w4 = omega + h * a3
    a4 = _accel(th4, tau + h, side, alpha, k, nu, tau_end)
    theta_new = theta + h / 6.0 * (omega + 2.0 * w2 + 2.0 * w3 + w4)
    omega_new = omega + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
    return theta_new, omega_new


@numba.njit(cache=True)
def _locate(which, theta, omega, tau, h, side, alpha, k, nu, tau_end):
    """Step length ``d`` in (0, h] at which the RK4 map's ``theta`` (which=0) or ``omega``
    (which=1) vanishes, given a sign change over ``[0, h]``. Safeguarded Newton (bisection
    fallback) on the RK4 map, derivative from the right side. Returns (d, ok)."""
    lo = 0.0
    hi = h
    f_lo = theta if which == 0 else omega
    th_h, w_h = _rk4(theta, omega, tau, h, side, alpha, k, nu, tau_end)
    f_hi = th_h if which == 0 else w_h
    if f_hi == 0.0:
        return h, True
    # linear first guess from the end values
    d = lo + (hi - lo) * f_lo / (f_lo - f_hi)
    for _ in range(_EVENT_MAX_ITER):
        if not (lo < d < hi):
            d = 0.5 * (lo + hi)
        th_d, w_d = _rk4(theta, omega, tau, d, side, alpha, k, nu, tau_end)
        f = th_d if which == 0 else w_d
        if f == 0.0:
            return d, True
        if (f > 0.0) == (f_lo > 0.0):
            lo = d
        else:
            hi = d
        df = w_d if which == 0 else _accel(th_d, tau + d, side, alpha, k, nu, tau_end)
        step = f / df if df != 0.0 else 0.0
        d_new = d - step
        if abs(step) <= 4e-16 * max(1.0, tau + d) or hi - lo <= 4e-16 * max(1.0, tau + d):
            if lo < d_new < hi:
                return d_new, True
            return d, True
        d = d_new
    return d, False


@numba.njit(cache=True)
def _next_uplift(tau, tan_alpha, k, nu, tau_end):
    """First time >= tau at which |a|/g > tan(alpha) for the sine pulse, and the sign of a
    there; (-1.0, 0.0) if none before the end of the pulse."""
    if k <= tan_alpha * (1.0 + _UPLIFT_RTOL):
        return -1.0, 0.0
    beta = math.asin(tan_alpha / k)
    phi = nu * tau
    # exceedance windows in phase: (beta, pi - beta) with a > 0, (pi + beta, 2 pi - beta) a < 0
    if beta < phi < math.pi - beta:
        return tau, 1.0
    if math.pi + beta < phi < 2.0 * math.pi - beta:
        return tau, -1.0
    if phi <= beta:
        return beta / nu, 1.0
    if phi <= math.pi + beta:
        return (math.pi + beta) / nu, -1.0
    return -1.0, 0.0


@numba.njit(cache=True)
def _solve_case(alpha, e, k, nu, max_step, steps_per_pulse, rest_velocity, max_impacts,
                max_steps, theta0, omega0, hist_tau, hist_theta, hist_omega):
    """Solve one case in dimensionless time. ``k = PFA/g``, ``nu = omega_p/p``; initial
    rotation ``theta0`` (rad) and angular velocity ``omega0`` (units of p), zero for a block
    at rest.

    Returns (theta_max, overturned, rocked, status, n_impacts, n_steps, n_hist).
    History arrays of length 0 disable recording; otherwise states are recorded at every
    accepted step, uplift and impact until the arrays are full.
    """
    tan_alpha = math.tan(alpha)
    tau_end = 2.0 * math.pi / nu
    h_nom = min(max_step, tau_end / steps_per_pulse)
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
            t_up, sgn_a = _next_uplift(tau, tan_alpha, k, nu, tau_end)
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

        h = min(h_nom, tau_end - tau)
        last = h == tau_end - tau
        if fresh:
            acc0 = _accel(0.0, tau, side, alpha, k, nu, tau_end)
            if side * acc0 < 0.0 and omega != 0.0:
                # restoring: the excursion peaks after about |omega| / |acc0|
                h_peak = abs(omega) / abs(acc0)
                if h_peak < h:
                    h = h_peak
                    last = False
        th1, w1 = _rk4(theta, omega, tau, h, side, alpha, k, nu, tau_end)
        n_steps += 1
        if fresh:
            # the whole step must stay on the new side; halve until it does
            while side * th1 <= 0.0:
                h *= 0.5
                last = False
                if h < _MIN_STEP:
                    break
                th1, w1 = _rk4(theta, omega, tau, h, side, alpha, k, nu, tau_end)
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
            d, ok = _locate(0, theta, omega, tau, h, side, alpha, k, nu, tau_end)
            if not ok:
                return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist
            th_d, w_d = _rk4(theta, omega, tau, d, side, alpha, k, nu, tau_end)
            n_steps += 1
            # a peak may lie between the start of the step and the impact
            if omega * w_d < 0.0:
                dp, ok = _locate(1, theta, omega, tau, d, side, alpha, k, nu, tau_end)
                if not ok:
                    return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist
                th_p, _ = _rk4(theta, omega, tau, dp, side, alpha, k, nu, tau_end)
                theta_max = max(theta_max, abs(th_p))
            tau = tau + d if d < h else (tau_end if last else tau + h)
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
                acc_new = _accel(0.0, tau, side, alpha, k, nu, tau_end)
                if side * acc_new <= 0.0:
                    side = 0.0
                    omega = 0.0
                    fresh = False
            continue

        # ordinary step: a peak inside it?
        if omega * w1 < 0.0:
            dp, ok = _locate(1, theta, omega, tau, h, side, alpha, k, nu, tau_end)
            if not ok:
                return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist
            th_p, _ = _rk4(theta, omega, tau, dp, side, alpha, k, nu, tau_end)
            theta_max = max(theta_max, abs(th_p))
        tau = tau_end if last else tau + h
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
    st = side * theta  # |theta| on the current pivot (>= 0)
    energy = 0.5 * omega * omega + math.cos(alpha - st) - math.cos(alpha)
    barrier = 1.0 - math.cos(alpha)
    outward = side * omega > 0.0
    for _ in range(3):
        if st > alpha:
            if outward or energy <= barrier:
                return max(theta_max, OVERTURNING_ANGLE), True, rocked, STATUS_OK, n_imp, n_steps, n_hist
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
                return max(theta_max, OVERTURNING_ANGLE), True, rocked, STATUS_OK, n_imp, n_steps, n_hist
            peak = alpha - math.acos(min(1.0, energy + math.cos(alpha)))
            return max(theta_max, peak), False, rocked, STATUS_OK, n_imp, n_steps, n_hist
    return theta_max, False, rocked, STATUS_EVENT_FAILED, n_imp, n_steps, n_hist


@numba.njit(cache=True, nogil=True)
def _solve_chunk(alpha, e, k, nu, max_step, steps_per_pulse, rest_velocity, max_impacts, max_steps,
                 start, stop, theta_max, overturned, rocked, status, n_impacts, n_steps):
    """Solve cases ``start:stop`` one after the other (releases the GIL, so Python threads
    can run chunks in parallel; each case is independent, so results do not depend on the
    chunking or the number of threads)."""
    empty = np.zeros(0)
    for i in range(start, stop):
        tm, ov, rk, st, ni, ns, _ = _solve_case(
            alpha[i], e[i], k[i], nu[i], max_step, steps_per_pulse, rest_velocity,
            max_impacts, max_steps, 0.0, 0.0, empty, empty, empty)
        theta_max[i] = tm
        overturned[i] = ov
        rocked[i] = rk
        status[i] = st
        n_impacts[i] = ni
        n_steps[i] = ns


# =============================================================================================
# Public API
# =============================================================================================


@dataclass(frozen=True)
class GridResult:
    """Batch results, one element per case, in the broadcast shape of the inputs.

    Parameters
    ----------
    theta_max : ndarray of float
        Peak ``|theta|`` (rad); ``>= pi/2`` when overturned; meaningless where ``status != 0``.
    overturned : ndarray of bool
        ``|theta|`` reached ``pi/2`` (Eq. 11). False where ``status != 0``.
    rocked : ndarray of bool
        The block uplifted at all (Eq. 4).
    status : ndarray of int8
        :data:`STATUS_OK` or a failure code, see :data:`STATUS_REASONS`.
    n_impacts : ndarray of int64
        Impacts resolved (the free-rocking tail after the first post-pulse peak is not counted).
    n_steps : ndarray of int64
        Runge-Kutta steps taken, event location included.
    wall_time_s : float
        Wall-clock time of the batch (s).
    """

    theta_max: np.ndarray
    overturned: np.ndarray
    rocked: np.ndarray
    status: np.ndarray
    n_impacts: np.ndarray
    n_steps: np.ndarray
    wall_time_s: float = 0.0

    @property
    def ok(self) -> np.ndarray:
        """True where the case finished (its verdict is valid)."""
        return self.status == STATUS_OK

    @property
    def verdict(self) -> np.ndarray:
        """Per-case verdict string: ``no_uplift``, ``safe``, ``overturned`` or ``failed``."""
        out = np.where(self.rocked, "safe", "no_uplift").astype(object)
        out[self.overturned] = "overturned"
        out[~self.ok] = "failed"
        return out


def _as_settings(settings: HousnerFastSettings | None, overrides: dict[str, Any]) -> HousnerFastSettings:
    if settings is None:
        settings = HousnerFastSettings()
    elif not isinstance(settings, HousnerFastSettings):
        raise TypeError(f"settings must be a HousnerFastSettings, got {settings!r}")
    if overrides:
        unknown = set(overrides) - set(HousnerFastSettings.__dataclass_fields__)
        if unknown:
            raise TypeError(f"unknown housner_fast settings: {sorted(unknown)}")
        settings = replace(settings, **overrides)
    return settings


#: Cases per work item of :func:`solve_grid`: small enough to balance cheap (no uplift) and
#: costly (chattering) cases across threads, large enough that dispatch costs nothing.
_CHUNK = 256


def _default_threads() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _check_array(name: str, arr: np.ndarray, low: float, high: float) -> None:
    bad = ~(np.isfinite(arr) & (arr > low) & (arr < high))
    if np.any(bad):
        i = int(np.flatnonzero(bad.ravel())[0])
        raise ValueError(f"{name} must lie in ({low:g}, {high:g}); element {i} is {arr.ravel()[i]!r}")


def solve_grid(
    alpha: Any,
    e: Any,
    pfa_ratio: Any,
    freq_ratio: Any,
    *,
    settings: HousnerFastSettings | None = None,
    threads: int | None = None,
) -> GridResult:
    """Solve many one-sine-pulse cases at once: the batch entry point for dense spectra.

    All inputs broadcast together; each element of the broadcast is one independent case.
    The kernel integrates in the dimensionless time ``tau = p t``, in which the peak rotation and
    the verdict depend on ``alpha``, ``e`` and the two ratios alone, so the block's size (``p``)
    is not an input here (tests/test_housner_fast.py checks that claim against the dimensional
    solver ``housner``).

    Parameters
    ----------
    alpha : array_like of float
        Block slenderness ``atan(b/h)`` (rad), in (0, pi/2).
    e : array_like of float
        Coefficient of restitution (dimensionless), in (0, 1].
    pfa_ratio : array_like of float
        ``PFA / (g tan alpha)`` (dimensionless, IM2), > 0.
    freq_ratio : array_like of float
        ``omega_p / p`` (dimensionless, IM1), > 0.
    settings : HousnerFastSettings, optional
        Numerical settings (defaults if omitted).
    threads : int, optional
        Worker threads (the compiled kernel releases the GIL). Default: the CPUs this
        process may use. Results are identical for any value: cases are independent.

    Returns
    -------
    GridResult
        Arrays of the broadcast shape.
    """
    settings = _as_settings(settings, {})
    threads = _default_threads() if threads is None else int_at_least("threads", threads, 1)
    arrays = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (alpha, e, pfa_ratio, freq_ratio)))
    shape = arrays[0].shape
    a_, e_, r_, f_ = (np.ascontiguousarray(x).ravel() for x in arrays)
    _check_array("alpha", a_, 0.0, 0.5 * math.pi)
    _check_array("e", e_, 0.0, 1.0 + 1e-12)
    _check_array("pfa_ratio", r_, 0.0, math.inf)
    _check_array("freq_ratio", f_, 0.0, math.inf)
    n = a_.size
    k = r_ * np.tan(a_)  # PFA / g
    theta_max = np.empty(n)
    overturned = np.empty(n, dtype=np.bool_)
    rocked = np.empty(n, dtype=np.bool_)
    status = np.empty(n, dtype=np.int8)
    n_impacts = np.empty(n, dtype=np.int64)
    n_steps = np.empty(n, dtype=np.int64)
    args = (a_, e_, k, f_, float(settings.max_step), int(settings.steps_per_pulse),
            float(settings.rest_velocity), int(settings.max_impacts), int(settings.max_steps))
    outs = (theta_max, overturned, rocked, status, n_impacts, n_steps)
    bounds = [(i, min(i + _CHUNK, n)) for i in range(0, n, _CHUNK)]
    t0 = _time.perf_counter()
    if threads == 1 or len(bounds) <= 1:
        for lo, hi in bounds:
            _solve_chunk(*args, lo, hi, *outs)
    else:
        with ThreadPoolExecutor(max_workers=threads) as pool:
            for fut in [pool.submit(_solve_chunk, *args, lo, hi, *outs) for lo, hi in bounds]:
                fut.result()
    wall = _time.perf_counter() - t0
    return GridResult(
        theta_max=theta_max.reshape(shape),
        overturned=overturned.reshape(shape),
        rocked=rocked.reshape(shape),
        status=status.reshape(shape),
        n_impacts=n_impacts.reshape(shape),
        n_steps=n_steps.reshape(shape),
        wall_time_s=wall,
    )


def solve_pulses(
    blocks: Sequence[Block],
    pfa_ratios: Any,
    freq_ratios: Any,
    *,
    settings: HousnerFastSettings | None = None,
    threads: int | None = None,
) -> GridResult:
    """Solve every block against the full grid ``pfa_ratios x freq_ratios``.

    Parameters
    ----------
    blocks : sequence of Block
        The blocks (their ``alpha`` and ``e`` are used).
    pfa_ratios : array_like of float
        ``PFA / (g tan alpha)`` values (dimensionless), 1-D.
    freq_ratios : array_like of float
        ``omega_p / p`` values (dimensionless), 1-D.
    settings : HousnerFastSettings, optional
        Numerical settings.
    threads : int, optional
        Worker threads, see :func:`solve_grid`.

    Returns
    -------
    GridResult
        Arrays of shape ``(len(blocks), len(pfa_ratios), len(freq_ratios))``.
    """
    blocks = list(blocks)
    if not blocks or not all(isinstance(b, Block) for b in blocks):
        raise TypeError(f"blocks must be a non-empty sequence of Block, got {blocks!r}")
    r = np.asarray(pfa_ratios, dtype=float).ravel()
    f = np.asarray(freq_ratios, dtype=float).ravel()
    al = np.array([b.alpha for b in blocks])[:, None, None]
    ee = np.array([b.e for b in blocks])[:, None, None]
    return solve_grid(al, ee, r[None, :, None], f[None, None, :], settings=settings,
                      threads=threads)


#: History slots reserved beyond the nominal steps of a case in :func:`solve` and
#: :func:`free_rocking` (two per impact, one per uplift and extra event step); a history
#: that fills up stops being recorded, the solution itself is unaffected.
_HISTORY_EXTRA = 20_000


def _run_one(block: Block, k: float, nu: float, theta0: float, omega0: float,
             settings: HousnerFastSettings) -> RockingResult:
    """Solve one case with history; ``k = PFA/g``, ``nu = omega_p/p`` (dimensionless)."""
    settings_dict = {"solver": SOLVER_NAME, **asdict(settings)}
    alpha = block.alpha
    p = block.p
    tau_end = 2.0 * math.pi / nu
    h_nom = min(settings.max_step, tau_end / settings.steps_per_pulse)
    cap = int(math.ceil(tau_end / h_nom)) + _HISTORY_EXTRA
    hist = [np.zeros(cap) for _ in range(3)]
    t0 = _time.perf_counter()
    try:
        tm, ov, rk, st, ni, ns, nh = _solve_case(
            alpha, block.e, k, nu, float(settings.max_step), int(settings.steps_per_pulse),
            float(settings.rest_velocity), int(settings.max_impacts), int(settings.max_steps),
            float(theta0), float(omega0), *hist)
    except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
        return failed_result(SOLVER_NAME, settings_dict, alpha, f"{type(exc).__name__}: {exc}",
                             wall_time_s=_time.perf_counter() - t0)
    wall = _time.perf_counter() - t0
    time_s = hist[0][:nh] / p
    theta = hist[1][:nh]
    theta_dot = hist[2][:nh] * p
    if st != STATUS_OK or not math.isfinite(tm):
        reason = STATUS_REASONS.get(int(st), "") or f"non-finite theta_max {tm!r}"
        return failed_result(SOLVER_NAME, settings_dict, alpha, reason, time=time_s, theta=theta,
                             theta_dot=theta_dot, n_steps=int(ns), wall_time_s=wall)
    return RockingResult(
        solver=SOLVER_NAME,
        settings=settings_dict,
        alpha=alpha,
        time=time_s,
        theta=theta,
        theta_dot=theta_dot,
        theta_max=float(tm),
        overturned=bool(ov),
        rocked=bool(rk),
        n_steps=int(ns),
        wall_time_s=wall,
        n_impacts=int(ni),
    )


def solve(block: Block, excitation: OneSinePulse, *, settings: HousnerFastSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Rocking response of one block, initially at rest, to one sine pulse (exact rigid-body model).

    Parameters
    ----------
    block : Block
        The block.
    excitation : OneSinePulse
        The one-sine floor pulse (other excitations are not supported by this solver; use
        ``solver="housner"`` for records).
    settings : HousnerFastSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields.

    Returns
    -------
    RockingResult
        ``time``/``theta``/``theta_dot`` hold the accepted steps, uplifts and impacts (the
        state just before and just after each, at the same time) while the pulse lasts
        (s, rad, rad/s); ``theta_max`` (rad) includes the exact first free-rocking peak after
        the pulse; an overturning decided after the pulse by the energy barrier reports
        ``theta_max = pi/2``.
    """
    settings = _as_settings(settings, overrides)
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {block!r}")
    if not isinstance(excitation, OneSinePulse):
        raise TypeError(
            f"housner_fast solves one-sine pulses only (OneSinePulse), got {type(excitation).__name__}; "
            "use solver='housner' for records")
    return _run_one(block, excitation.pfa / G, excitation.omega_p / block.p, 0.0, 0.0, settings)


def free_rocking(block: Block, theta0: float, duration: float, *, theta_dot0: float = 0.0,
                 settings: HousnerFastSettings | None = None, **overrides: Any) -> RockingResult:
    """Free rocking (no floor motion) from an initial state, integrated step by step.

    Used to check the integrator against closed forms (first impact time, energy, ``e²`` per
    impact). The motion is integrated for ``duration``; the verdict after that uses the same
    exact energy argument as :func:`solve`.

    Parameters
    ----------
    block : Block
        The block.
    theta0 : float
        Initial rotation (rad), ``|theta0| < pi/2``.
    duration : float
        Integrated time (s), > 0.
    theta_dot0 : float, optional
        Initial angular velocity (rad/s). Default 0.
    settings : HousnerFastSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields. The step is
        ``min(max_step, p duration / steps_per_pulse)`` in units of ``1/p``.
    """
    settings = _as_settings(settings, overrides)
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {block!r}")
    theta0 = float(theta0)
    if not (math.isfinite(theta0) and abs(theta0) < OVERTURNING_ANGLE):
        raise ValueError(f"theta0 must be finite with |theta0| < pi/2, got {theta0!r}")
    duration = positive_finite("duration", duration)
    theta_dot0 = float(theta_dot0)
    if not math.isfinite(theta_dot0):
        raise ValueError(f"theta_dot0 must be finite, got {theta_dot0!r}")
    nu = 2.0 * math.pi / (duration * block.p)  # so that the integrated span is `duration`
    return _run_one(block, 0.0, nu, theta0, theta_dot0 / block.p, settings)
