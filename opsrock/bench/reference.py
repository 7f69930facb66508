"""An independent reference for the fast rigid-body solver: plain event-driven ``solve_ivp``.

It shares no numerics with :mod:`opsrock.solvers.housner_fast`: scipy's DOP853 (rtol 1e-10),
restarted at every event, in the dimensionless time ``tau = p t``, integrating the free rocking
after the pulse instead of using the fast solver's energy shortcut. The tests
(``tests/test_housner_fast.py``) and the benchmark (:mod:`opsrock.bench.housner_fast`) measure the
fast solver's accuracy against it.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

#: Reference tolerances: rtol 1e-10 (the reference solver's setting); atol far below the smallest excursion the
#: reference still resolves (REF_REST_VELOCITY² / 2 ~ 5e-13 rad).
REF_RTOL = 1e-10
REF_ATOL = 1e-15
#: Post-impact velocity (units of p) below which the reference seats the block.
REF_REST_VELOCITY = 1e-6
#: Impacts the reference allows before giving up.
REF_MAX_IMPACTS = 20_000


def reference_solve(alpha: float, e: float, pfa_ratio: float, freq_ratio: float) -> dict:
    """Rigid-body rocking by plain solve_ivp, restarted at every event.

    Returns ``theta_max`` (rad), ``overturned``, ``rocked`` and ``n_impacts``. The free
    rocking after the pulse is integrated (a = 0) up to the first peak inside ``|theta| <
    alpha``; from there every impact lowers the energy, so theta_max cannot grow.
    """
    k = pfa_ratio * math.tan(alpha)  # PFA / g
    nu = freq_ratio
    tau_end = 2.0 * math.pi / nu
    half_pi = 0.5 * math.pi

    def ag(tau: float) -> float:
        return k * math.sin(nu * tau) if tau <= tau_end else 0.0

    def rhs_factory(side: float):
        def rhs(tau, y):
            phi = side * alpha - y[0]
            return [y[1], -(math.sin(phi) + ag(tau) * math.cos(phi))]

        return rhs

    tau = 0.0
    theta_max = 0.0
    rocked = False
    n_imp = 0
    seated = True
    side = 0.0
    y = np.zeros(2)
    peak_enabled = True
    while True:
        if seated:
            if tau >= tau_end:
                break
            # uplift: first time |a|/g exceeds tan(alpha), found by solve_ivp events on a
            # dummy ODE (no closed form used)
            ev_pos = lambda t, _y: ag(t) - math.tan(alpha)  # noqa: E731
            ev_neg = lambda t, _y: -ag(t) - math.tan(alpha)  # noqa: E731
            for ev in (ev_pos, ev_neg):
                ev.terminal, ev.direction = True, 1.0
            if ag(tau) > math.tan(alpha):
                t_up, sgn = tau, 1.0
            elif -ag(tau) > math.tan(alpha):
                t_up, sgn = tau, -1.0
            else:
                sol = solve_ivp(lambda t, _y: [0.0], (tau, tau_end), [0.0], events=(ev_pos, ev_neg),
                                max_step=0.01 / nu, rtol=1e-12, atol=1e-12)
                if sol.status != 1:
                    break
                if sol.t_events[0].size:
                    t_up, sgn = float(sol.t_events[0][0]), 1.0
                else:
                    t_up, sgn = float(sol.t_events[1][0]), -1.0
            tau, side, seated, rocked = t_up, -sgn, False, True
            y = np.zeros(2)
        rhs = rhs_factory(side)

        def impact(t, yy, s=side):
            return s * yy[0]

        impact.terminal, impact.direction = True, -1.0

        def overturn(t, yy):
            return abs(yy[0]) - half_pi

        overturn.terminal, overturn.direction = True, 1.0

        def peak(t, yy):
            return yy[1]

        peak.terminal = tau >= tau_end  # after the pulse: stop at a peak, then decide
        events = (impact, overturn, peak) if peak_enabled else (impact, overturn)
        t_stop = tau_end if tau < tau_end else tau + 1e4
        first = None
        if y[0] == 0.0 and y[1] != 0.0:
            acc = rhs(tau, y)[1]
            if side * acc < 0.0:
                first = 0.1 * abs(y[1]) / abs(acc)  # see the excursion: scipy grows steps <= 10x
                first = min(first, 0.5 * (t_stop - tau))
        sol = solve_ivp(rhs, (tau, t_stop), y, method="DOP853", rtol=REF_RTOL, atol=REF_ATOL,
                        events=events, first_step=first, max_step=0.05)
        if sol.status < 0:
            raise RuntimeError(f"reference failed: {sol.message}")
        theta_max = max(theta_max, float(np.max(np.abs(sol.y[0]))))
        if peak_enabled and sol.y_events[2].size:
            theta_max = max(theta_max, float(np.max(np.abs(sol.y_events[2][:, 0]))))
        if sol.t_events[1].size:
            return dict(theta_max=max(theta_max, half_pi), overturned=True, rocked=rocked, n_impacts=n_imp)
        if sol.t_events[0].size:
            tau = float(sol.t_events[0][0])
            w = e * float(sol.y_events[0][0, 1])
            n_imp += 1
            if n_imp > REF_MAX_IMPACTS:
                raise RuntimeError("reference: too many impacts")
            side = -side
            y = np.array([0.0, w])
            if abs(w) < REF_REST_VELOCITY:
                phi = side * alpha
                acc = -(math.sin(phi) + ag(tau) * math.cos(phi))
                if side * acc <= 0.0:
                    seated, y = True, np.zeros(2)
            continue
        if peak_enabled and sol.t_events[2].size and tau >= tau_end:
            th_pk = abs(float(sol.y_events[2][0, 0]))
            tau = float(sol.t_events[2][0])
            y = sol.y_events[2][0].copy()
            if th_pk < alpha:
                break  # peak inside the well after the pulse: energy only falls from here
            peak_enabled = False  # peak beyond the hump: it falls outwards, integrate on
            continue
        # reached the end of the pulse without event
        tau = float(sol.t[-1])
        y = sol.y[:, -1].copy()
        tau = max(tau, tau_end)
    return dict(theta_max=theta_max, overturned=False, rocked=rocked, n_impacts=n_imp)


__all__ = ["reference_solve"]
