"""An independent reference for the fast rigid-body solver: plain event-driven ``solve_ivp``.

It shares no numerics with :mod:`opsrock.solvers.housner_fast`: scipy's DOP853 (rtol 1e-10),
restarted at every event, in the dimensionless time ``tau = p t``, integrating the free rocking
after the pulse instead of using the fast solver's energy shortcut. The tests
(``tests/model/solvers/test_housner_fast.py``) and the benchmark (:mod:`opsrock.bench.housner_fast`) measure the
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
    """Rigid-body rocking under a one-sine pulse by plain solve_ivp, restarted at every event.

    Parameters
    ----------
    alpha : float
        Slenderness (rad).
    e : float
        Restitution coefficient (-).
    pfa_ratio : float
        ``PFA / (g tan alpha)`` (-).
    freq_ratio : float
        ``omega_p / p`` (-).

    Returns
    -------
    dict
        ``theta_max`` (rad), ``overturned``, ``rocked`` and ``n_impacts``. The free rocking after the
        pulse is integrated (a = 0) up to the first peak inside ``|theta| < alpha``; from there every
        impact lowers the energy, so theta_max cannot grow.
    """
    return _Reference(alpha, e, pfa_ratio * math.tan(alpha), freq_ratio).run()


class _Reference:
    """The state of one reference run in the dimensionless time ``tau = p t``."""

    def __init__(self, alpha: float, e: float, k: float, nu: float) -> None:
        self.alpha, self.e, self.k, self.nu = alpha, e, k, nu  # k = PFA / g
        self.tau_end = 2.0 * math.pi / nu
        self.tau, self.theta_max, self.rocked, self.n_imp = 0.0, 0.0, False, 0
        self.seated, self.side, self.y = True, 0.0, np.zeros(2)
        self.peak_enabled = True
        self.final = False  # theta_max and the verdict can no longer change

    def ag(self, tau: float) -> float:
        """Floor acceleration over g."""
        return self.k * math.sin(self.nu * tau) if tau <= self.tau_end else 0.0

    def rhs(self, tau, y, side=None):
        side = self.side if side is None else side
        phi = side * self.alpha - y[0]
        return [y[1], -(math.sin(phi) + self.ag(tau) * math.cos(phi))]

    def run(self) -> dict:
        while not self.final:
            if self.seated and (self.tau >= self.tau_end or not self._uplift()):
                break
            outcome = self._flight()
            if outcome is not None:
                return outcome
        return dict(theta_max=self.theta_max, overturned=False, rocked=self.rocked, n_impacts=self.n_imp)

    def _uplift(self) -> bool:
        """First time ``|a|/g`` exceeds ``tan(alpha)``, found by solve_ivp events on a dummy ODE (no
        closed form used); False if the pulse never lifts the block again."""
        tan_a, tau = math.tan(self.alpha), self.tau
        ev_pos = lambda t, _y: self.ag(t) - tan_a  # noqa: E731
        ev_neg = lambda t, _y: -self.ag(t) - tan_a  # noqa: E731
        for ev in (ev_pos, ev_neg):
            ev.terminal, ev.direction = True, 1.0
        if self.ag(tau) > tan_a:
            t_up, sgn = tau, 1.0
        elif -self.ag(tau) > tan_a:
            t_up, sgn = tau, -1.0
        else:
            sol = solve_ivp(lambda t, _y: [0.0], (tau, self.tau_end), [0.0], events=(ev_pos, ev_neg),
                            max_step=0.01 / self.nu, rtol=1e-12, atol=1e-12)
            if sol.status != 1:
                return False
            t_up, sgn = (float(sol.t_events[0][0]), 1.0) if sol.t_events[0].size else (float(sol.t_events[1][0]), -1.0)
        self.tau, self.side, self.seated, self.rocked = t_up, -sgn, False, True
        self.y = np.zeros(2)
        return True

    def _events(self):
        side = self.side

        def impact(t, yy):
            return side * yy[0]

        impact.terminal, impact.direction = True, -1.0

        def overturn(t, yy):
            return abs(yy[0]) - 0.5 * math.pi

        overturn.terminal, overturn.direction = True, 1.0

        def peak(t, yy):
            return yy[1]

        peak.terminal = self.tau >= self.tau_end  # after the pulse: stop at a peak, then decide
        return (impact, overturn, peak) if self.peak_enabled else (impact, overturn)

    def _flight(self) -> dict | None:
        """One segment up to the next event; the result dict once the block overturns."""
        tau, y, side = self.tau, self.y, self.side
        t_stop = self.tau_end if tau < self.tau_end else tau + 1e4
        first = None
        if y[0] == 0.0 and y[1] != 0.0:
            acc = self.rhs(tau, y)[1]
            if side * acc < 0.0:
                first = 0.1 * abs(y[1]) / abs(acc)  # see the excursion: scipy grows steps <= 10x
                first = min(first, 0.5 * (t_stop - tau))
        sol = solve_ivp(lambda t, yy: self.rhs(t, yy, side), (tau, t_stop), y, method="DOP853", rtol=REF_RTOL,
                        atol=REF_ATOL, events=self._events(), first_step=first, max_step=0.05)
        if sol.status < 0:
            raise RuntimeError(f"reference failed: {sol.message}")
        self.theta_max = max(self.theta_max, float(np.max(np.abs(sol.y[0]))))
        if self.peak_enabled and sol.y_events[2].size:
            self.theta_max = max(self.theta_max, float(np.max(np.abs(sol.y_events[2][:, 0]))))
        if sol.t_events[1].size:
            return dict(theta_max=max(self.theta_max, 0.5 * math.pi), overturned=True, rocked=self.rocked,
                        n_impacts=self.n_imp)
        if sol.t_events[0].size:
            self._impact(sol)
        elif self.peak_enabled and sol.t_events[2].size and tau >= self.tau_end:
            th_pk = abs(float(sol.y_events[2][0, 0]))
            self.tau = float(sol.t_events[2][0])
            self.y = sol.y_events[2][0].copy()
            if th_pk < self.alpha:
                self.final = True  # peak inside the well after the pulse: energy only falls from here
            self.peak_enabled = False  # peak beyond the hump: it falls outwards, integrate on
        else:  # reached the end of the pulse without event
            self.tau = max(float(sol.t[-1]), self.tau_end)
            self.y = sol.y[:, -1].copy()
        return None

    def _impact(self, sol) -> None:
        self.tau = float(sol.t_events[0][0])
        w = self.e * float(sol.y_events[0][0, 1])
        self.n_imp += 1
        if self.n_imp > REF_MAX_IMPACTS:
            raise RuntimeError("reference: too many impacts")
        self.side = -self.side
        self.y = np.array([0.0, w])
        if abs(w) < REF_REST_VELOCITY:
            phi = self.side * self.alpha
            acc = -(math.sin(phi) + self.ag(self.tau) * math.cos(phi))
            if self.side * acc <= 0.0:
                self.seated, self.y = True, np.zeros(2)


__all__ = ["reference_solve"]
