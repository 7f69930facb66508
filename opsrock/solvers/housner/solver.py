"""The event-driven rigid-body run (:func:`solve`); the equations are in the package docstring."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE, G
from opsrock.result import RockingResult
from opsrock.solvers.common import EventDrivenSolver, StopRun, check_inputs, first_exceedance, make_settings
from opsrock.solvers.housner.settings import HousnerSettings

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "housner"


def solve(block: Block, excitation: Any, settings: HousnerSettings | None = None, **overrides: Any) -> RockingResult:
    """Rocking response of the rigid block by the exact equation with instantaneous impacts.

    Parameters
    ----------
    block : Block
        The block (geometry, restitution ``e``).
    excitation : Excitation or None
        Floor acceleration (m/s²) as a function of time (s); None: a still floor (free rocking from
        ``theta0``, ``theta_dot0``).
    settings : HousnerSettings, optional
        Numerical settings; keyword ``overrides`` replace single fields.

    Returns
    -------
    RockingResult
        ``solver="housner"``; ``n_impacts`` counts impacts; ``n_steps`` accepted steps.
        An integrator failure or more than ``max_impacts`` impacts give ``status="failed"``.
    """
    settings = make_settings(HousnerSettings, settings, overrides)
    return _Housner(check_inputs(SOLVER_NAME, block, excitation, settings), excitation, settings).run()


class _Housner(EventDrivenSolver):
    """The rigid block, event by event: uplift, flight about one corner, impact, rest, overturning."""

    name = SOLVER_NAME

    def _start(self) -> None:
        s = self.settings
        self.e = self.block.e
        self.p2 = self.p * self.p
        self.linearised = s.equations == "linearised"
        self.level = G * self.alpha if self.linearised else self.block.uplift_acceleration
        self.v_rest = s.rest_velocity_ratio * self.p * self.alpha
        self.segment_method = s.method
        self.history.add(np.array(self.t), self.y[0], self.y[1])
        y = self.y
        self.side = 0.0 if self.seated else (math.copysign(1.0, y[0]) if y[0] != 0.0 else math.copysign(1.0, y[1]))

    def _seated_step(self) -> None:
        t = self.t
        t_up = first_exceedance(self.excitation, self.level, t, min(self.t_final, self.duration), self.scan)
        if t_up is None:
            t_stop = min(self.t_final, self.duration) if self.open_end else self.t_final
            self.history.add(np.array(t_stop), 0.0, 0.0)
            self.t = t_stop
            return
        if t_up > t:
            self.history.add(np.array(t_up), 0.0, 0.0)
        self.t = t_up
        self.side = -math.copysign(1.0, float(self.acc(t_up + 1e-12 * max(1.0, t_up))) or float(self.acc(t_up)))
        self.y = np.array([0.0, 0.0])
        self.seated = False
        self.rocked = True

    def _events(self, sd: float):
        alpha, p2, acc, linearised = self.alpha, self.p2, self.acc, self.linearised

        def rhs(tt: float, yy: np.ndarray) -> list[float]:
            ang = alpha * sd - yy[0]
            if linearised:
                return [yy[1], -p2 * (ang + float(acc(tt)) / G)]
            return [yy[1], -p2 * (math.sin(ang) + float(acc(tt)) / G * math.cos(ang))]

        def impact(tt: float, yy: np.ndarray) -> float:
            return sd * yy[0]

        impact.terminal, impact.direction = True, -1

        def overturn(tt: float, yy: np.ndarray) -> float:
            return sd * yy[0] - OVERTURNING_ANGLE

        overturn.terminal, overturn.direction = True, 1

        def turning(tt: float, yy: np.ndarray) -> float:
            return sd * yy[1]

        s = self.settings
        turning.terminal = bool(self.t >= self.duration and self.open_end and s.tail == "peak")
        turning.direction = -1
        return rhs, (impact, overturn, turning)

    def _flight_step(self) -> None:
        s = self.settings
        rhs, events = self._events(self.side)
        sol = solve_ivp(rhs, (self.t, self.next_breakpoint()), self.y, method=s.method, rtol=s.rtol, atol=self.atol,
                        max_step=s.max_step, events=events, dense_output=s.dense_step is not None)
        self.count_steps(sol)
        self.history.add_segment(sol, 2, dense_step=s.dense_step)
        self.track_peak(sol, 2)
        if sol.status == 0:
            self.t, self.y = float(sol.t[-1]), sol.y[:, -1].copy()
            return
        self.t = float(sol.t[-1])
        if sol.t_events[1].size:
            self.overturned = True
            self.theta_max = max(self.theta_max, OVERTURNING_ANGLE)
            raise StopRun()
        if sol.t_events[2].size and events[2].terminal:
            y_turn = sol.y_events[2][-1]
            if abs(y_turn[0]) < self.alpha:
                raise StopRun()  # energy only falls from here: theta_max and the verdict are final
            self.y = y_turn.copy()
            return
        self._impact(float(sol.y_events[0][-1][1]))

    def _impact(self, v_before: float) -> None:
        """``theta = 0``: ``theta' -> e theta'``, the pivot switches corner; a slow block comes to rest."""
        t = self.t
        v = self.e * v_before
        self.log_impact(t, v_before, v)
        self.history.add(np.array(t), 0.0, v)
        if abs(v) < self.v_rest:
            self.seated = True
            self.y = np.array([0.0, 0.0])
            self.history.add(np.array(t), 0.0, 0.0)
            return
        self.side = math.copysign(1.0, v)
        self.y = np.array([0.0, v])


__all__ = ["SOLVER_NAME", "solve"]
