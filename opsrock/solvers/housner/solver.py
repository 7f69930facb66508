"""The exact rigid-body rocking equation with instantaneous impacts (paper Eq. 1-4, 9-11).

Between impacts the block pivots about one base corner (``s = sgn(theta)``)::

    theta'' = -p² [ sin(alpha s - theta) + a(t)/g cos(alpha s - theta) ]

with a positive floor acceleration ``a`` tipping the block towards negative ``theta``. The
solver is event-driven:

* **seated** while ``|a(t)| <= g tan(alpha)`` (Eq. 4); the first time ``|a|`` exceeds that
  level the block uplifts about the corner set by the sign of ``a`` (``s = -sgn(a)``);
* **impact** when ``theta`` returns to zero: ``theta' -> e theta'`` (Housner's instantaneous
  impact, ``e = block.e``) and the block goes on about the other corner;
* **rest** when the velocity after an impact falls below ``rest_velocity_ratio · p · alpha``:
  the remaining bounces ("chattering") form a geometric series ``e, e², ...`` of vanishing
  duration (at most ``2 |theta'| / ((1 - e) p² alpha)`` in free rocking), so the block is
  set down as seated; it lifts off again if ``|a|`` still exceeds ``g tan(alpha)``;
* **overturning** when ``|theta|`` reaches ``pi/2`` (Eq. 11), a terminal event.

With ``equations="linearised"`` the small-angle form of the classical rocking papers is solved
instead, ``theta'' = -p² [(alpha s - theta) + a/g]`` with uplift when ``|a| > g alpha``
(:data:`opsrock.constants.EQUATIONS`); overturning is still ``|theta| = pi/2``.

The lever here is the exact ``cos(alpha s - theta)`` of Eq. 1; the SDOF model of Eq. 6 keeps
it constant at ``cos(alpha)`` (see :mod:`opsrock.solvers.sdof`): one of the model-form
differences measured by ``validation/model_form``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from opsrock.block import Block
from opsrock.constants import EQUATIONS, OVERTURNING_ANGLE, G
from opsrock.limits import one_of, positive_finite
from opsrock.result import RockingResult
from opsrock.solvers.common import (
    METHODS,
    TAILS,
    EventDrivenSolver,
    ScipySettings,
    StopRun,
    first_exceedance,
    make_settings,
    rocking_energy,
)


@dataclass(frozen=True)
class HousnerSettings(ScipySettings):
    """Numerical settings of the rigid-body solver (the model has no free parameter): those of
    :class:`~opsrock.solvers.common.ScipySettings` and

    Parameters
    ----------
    atol : float
        Absolute tolerance on ``theta`` (rad). Default 1e-12 rad, far below any rotation of interest
        (alpha is 0.1-0.5 rad).
    rest_velocity_ratio : float
        After an impact the block is set down as seated if ``|theta'| < rest_velocity_ratio · p · alpha``
        (dimensionless). Default 1e-6: the bounces left would rise to ``~(1e-6)² alpha / 2`` at most.
    equations : str
        Form of the equation of motion, one of :data:`opsrock.constants.EQUATIONS`. Default ``"exact"``
        (Eq. 1); ``"linearised"`` for the small-angle form of the classical papers.
    """

    atol: float = 1e-12
    rest_velocity_ratio: float = 1e-6
    equations: str = "exact"

    def __post_init__(self) -> None:
        super().__post_init__()
        one_of("equations", self.equations, EQUATIONS)
        positive_finite("rest_velocity_ratio", self.rest_velocity_ratio)


def solve(block: Block, excitation: Any, *, settings: HousnerSettings | None = None, **overrides: Any) -> RockingResult:
    """Rocking response of the rigid block by the exact equation with instantaneous impacts.

    Parameters
    ----------
    block : Block
        The block (geometry, restitution ``e``).
    excitation : Excitation
        Floor acceleration (m/s²) as a function of time (s).
    settings : HousnerSettings, optional
        Numerical settings; keyword ``overrides`` replace single fields.

    Returns
    -------
    RockingResult
        ``solver="housner"``; ``n_impacts`` counts impacts; ``n_steps`` accepted steps.
        An integrator failure or more than ``max_impacts`` impacts give ``status="failed"``.
    """
    return _Housner(block, excitation, make_settings(HousnerSettings, settings, overrides)).run()


class _Housner(EventDrivenSolver):
    """The rigid block, event by event: uplift, flight about one corner, impact, rest, overturning."""

    name = "housner"

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
        s, t = self.settings, self.t
        t_up = first_exceedance(self.excitation, self.level, t, min(self.t_final, self.duration), self.scan)
        if t_up is None:
            t_stop = self.t_final if s.end_time is not None else min(self.t_final, self.duration)
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
        turning.terminal = bool(self.t >= self.duration and s.end_time is None and s.tail == "peak")
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


__all__ = ["HousnerSettings", "METHODS", "TAILS", "rocking_energy", "solve"]
