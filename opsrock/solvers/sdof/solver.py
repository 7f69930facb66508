"""The scipy SDOF solver: the rotation axis cut into regions where the equation is linear, one
segment per region and breakpoint (see the package docstring)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE
from opsrock.excitations.records import Record
from opsrock.model import Seat, can_uplift
from opsrock.result import RockingResult, seated_result
from opsrock.solvers.common import EventDrivenSolver, StopRun, check_inputs, first_exceedance, make_settings
from opsrock.solvers.sdof.closed_form import ClosedFormSegment, closed_form_solve
from opsrock.solvers.sdof.settings import SDOFSettings

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "sdof"


def table_potential(theta_tab: np.ndarray, moment_tab: np.ndarray):
    """Potential ``U(theta) = integral_0^theta M_s`` (J) of a piecewise-linear spring table.

    Returns a vectorised function; exact for the linear interpolation of the table.
    """
    th = np.asarray(theta_tab, dtype=float)
    m = np.asarray(moment_tab, dtype=float)
    i0 = int(np.searchsorted(th, 0.0))
    m0 = float(np.interp(0.0, th, m))
    nodes = np.concatenate([th[:i0], [0.0], th[i0:]])
    vals = np.concatenate([m[:i0], [m0], m[i0:]])
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (vals[1:] + vals[:-1]) * np.diff(nodes))])
    cum -= cum[i0]

    def U(theta: np.ndarray | float) -> np.ndarray:  # noqa: N802
        x = np.clip(np.asarray(theta, dtype=float), nodes[0], nodes[-1])
        j = np.clip(np.searchsorted(nodes, x, side="right") - 1, 0, nodes.size - 2)
        x0, m_0 = nodes[j], vals[j]
        slope = (vals[j + 1] - vals[j]) / (nodes[j + 1] - nodes[j])
        dx = x - x0
        return cum[j] + m_0 * dx + 0.5 * slope * dx**2

    return U



def solve(block: Block, excitation: Any, settings: SDOFSettings | None = None, **overrides: Any) -> RockingResult:
    """Rocking response of the paper's equivalent SDOF model, integrated by scipy.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation or None
        Floor acceleration (m/s²) as a function of time (s); None: a still floor (free rocking from
        ``theta0``, ``theta_dot0``).
    settings : SDOFSettings, optional
        Model and numerical settings; keyword ``overrides`` replace single fields (the model's too:
        ``delta=0.01``).

    Returns
    -------
    RockingResult
        ``solver="sdof"``, with ``spring_moment`` and ``damper_force`` histories when
        ``record``; ``n_impacts`` counts impacts (crossings of the damper band from one side to
        the other, logged in ``impacts`` with the velocities at the band's edges); ``rocked`` is True once
        ``|theta|`` leaves the stiff branch. Integrator failures and exceeded caps give
        ``status="failed"`` with the reason.
    """
    settings = make_settings(SDOFSettings, settings, overrides)
    return _SDOF(check_inputs(SOLVER_NAME, block, excitation, settings), excitation, settings).run()


class _SDOF(EventDrivenSolver):
    """The SDOF model region by region: seated in the stiff branch, or in flight across the table's regions."""

    name = SOLVER_NAME
    with_damping = True

    def _run_impl(self) -> RockingResult:
        """A seated block that the floor's peak cannot lift stays seated (``uplift_check``); else the run."""
        s = self.settings
        if s.uplift_check and self.seated and not can_uplift(self.block, s.model, self.excitation.pfa):
            return seated_result(SOLVER_NAME, self.settings_dict, self.block.alpha, self.excitation.duration,
                                 self.elapsed())
        return super()._run_impl()

    def _start(self) -> None:
        s, block = self.settings, self.block
        model = self.model = s.model
        self.inertia = block.I_O
        self.lam = model.lever_arm(block)
        self.theta_e = model.theta_e(block)
        self.band = model.band(block)
        self.th_tab, self.m_tab = model.spring_table(block)
        self.U = table_potential(self.th_tab, self.m_tab)
        self.u_band = float(self.U(self.band))
        self.seat = Seat(model, block, self.acc)
        self.m_e, self.k_e = model.edge_moment(block), self.seat.k_e  # moment and stiffness of the stiff branch
        self._regions()
        # the stiff branch in closed form where the floor acceleration is linear between breakpoints
        self.closed_form = s.stiff_closed_form and isinstance(self.excitation, Record)
        self.entry: tuple[float, float, float] | None = None  # (time, velocity, side) of the last band entry
        self.n_segments = 0
        self.c_d = 0.0
        self.rocked = abs(s.theta0) > self.theta_e
        self.region = -1
        self.at_turn = False  # the current state is a turning point just handled (its event must not fire again)
        y = self.y
        if not self.seated:
            self.region = _region_of(self.kinks, y[0], y[1])
            if model.tracks_passages() and self.theta_e < abs(y[0]) <= self.band and y[0] * y[1] <= 0.0:
                # starting inside the band, at rest or heading back towards zero: a passage begins
                self.c_d = model.arm_damper(block, y[0], y[1])
        self.history.add(self.t, y[0], y[1], 0.0)

    def _regions(self) -> None:
        """The rotation axis cut at every table kink and the band edges: each region's line ``k theta + m``."""
        band, theta_e = self.band, self.theta_e
        kinks = self.kinks = np.unique(np.concatenate([self.th_tab, [-band, band]]))
        self.slopes = np.diff(np.interp(kinks, self.th_tab, self.m_tab)) / np.diff(kinks)
        self.intercepts = np.interp(kinks[:-1], self.th_tab, self.m_tab) - self.slopes * kinks[:-1]
        self.in_band = (kinks[:-1] >= -band - 1e-15) & (kinks[1:] <= band + 1e-15)
        self.stiff = (kinks[:-1] >= -theta_e - 1e-15) & (kinks[1:] <= theta_e + 1e-15)

    def each_iteration(self) -> None:
        self.n_segments += 1
        if self.n_segments > self.settings.max_segments:
            raise StopRun(f"more than max_segments = {self.settings.max_segments} segments by t = {self.t:.6g} s",
                          "max_steps")

    def _seated_step(self) -> None:
        """Follow the quasi-static deflection of the stiff branch until the floor lifts the block."""
        t, lam, k_e, theta_e = self.t, self.lam, self.k_e, self.theta_e
        t_up = first_exceedance(self.excitation, self.m_e / lam, t, min(self.t_final, self.duration), self.scan)
        t_stop = t_up if t_up is not None else (min(self.t_final, self.duration) if self.open_end else self.t_final)
        if t_stop > t:
            bps = self.breakpoints
            grid = np.union1d(np.linspace(t, t_stop, 201), bps[(bps > t) & (bps < t_stop)])
            qs = np.clip(-lam * np.asarray(self.acc(grid), dtype=float) / k_e, -theta_e, theta_e)
            self.history.add(grid, qs, np.gradient(qs, grid), self.c_d)
            self.theta_max = max(self.theta_max, float(np.max(np.abs(qs))))
        self.t = t_stop
        if t_up is None:
            return
        # leave the stiff branch at its edge, on the side the floor pushes towards
        sign = -math.copysign(1.0, float(self.acc(t_up)))
        # one-sided (forward) slope: a pulse may jump at t_up (a one-cosine or rectangular pulse
        # at t = 0), and a central difference across the jump is a spurious huge velocity
        h = 1e-7 * max(self.duration, 1e-9)
        qs_dot = -lam * (float(self.acc(t_up + h)) - float(self.acc(t_up))) / h / k_e
        self.y = np.array([sign * theta_e, qs_dot if qs_dot * sign > 0 else 0.0])
        self.region = _region_of(self.kinks, self.y[0], sign)
        self.seated = False

    def _after_excitation_at_rest(self) -> bool:
        """With ``tail="rest"``, after the excitation: True once the block is trapped in the damper band."""
        s, y = self.settings, self.y
        if not (self.open_end and s.tail == "rest" and self.t >= self.duration and abs(y[0]) <= self.band):
            return False
        # trapped only *inside* the band: beyond alpha the table's potential falls below
        # U(delta alpha) too, and a block out there is falling over, not at rest
        energy = 0.5 * self.inertia * y[1] ** 2 + float(self.U(y[0]))
        return energy < self.u_band

    def _flight_step(self) -> None:
        if self._after_excitation_at_rest():
            raise StopRun()  # trapped in the damper band: it can never rock out again
        region = self.region
        self.at_turn, was_at_turn = False, self.at_turn
        seg = _Segment(self, region, was_at_turn)
        sol = self._integrate(seg)
        self.count_steps(sol)
        self.history.add_segment(sol, 3, seg.c_i, dense_step=self.settings.dense_step)
        self.track_peak(sol, 3)
        if not seg.is_stiff:
            self.rocked = True
        self.t = float(sol.t[-1])
        self.y = sol.y[:, -1].copy()
        if sol.status == 0:
            return
        self._event(seg, sol)

    def _integrate(self, seg: "_Segment"):
        s, t = self.settings, self.t
        t_seg = self.next_breakpoint()
        self.segment_method = s.stiff_method if seg.is_stiff else s.method
        if seg.is_stiff and self.closed_form and t_seg > t:
            # a record's acceleration is linear between samples: the stiff branch in closed form
            a0, a1 = float(self.acc(t)), (float(self.acc(t_seg)) - float(self.acc(t))) / (t_seg - t)
            if t_seg > self.duration:  # after the last sample the floor is still (a = 0)
                a0, a1 = (0.0, 0.0) if t >= self.duration else (a0, a1)
            cf = ClosedFormSegment(self.inertia, seg.c_i, seg.k_i, seg.m_i, self.lam, a0, a1, t, self.y)
            return closed_form_solve(cf, t, t_seg, seg.events)
        return solve_ivp(seg.rhs, (t, t_seg), self.y, method=self.segment_method, rtol=s.rtol, atol=self.atol,
                         max_step=s.max_step, events=seg.events, dense_output=s.dense_step is not None)

    def _event(self, seg: "_Segment", sol) -> None:
        """What the segment's terminal event means: overturning, a turning point, seated, at rest, or a
        crossing into the next region."""
        if sol.t_events[2].size:
            self.overturned = True
            self.theta_max = max(self.theta_max, OVERTURNING_ANGLE)
            raise StopRun()
        turning = seg.events[3]
        if sol.t_events[3].size and turning.terminal:
            if seg.stop_at_peak and abs(sol.y_events[3][-1][0]) < self.alpha:
                raise StopRun()
            self.y = sol.y_events[3][-1].copy()
            if seg.rearm:
                self.c_d = self.model.arm_damper(self.block, self.y[0], 0.0)
            self.at_turn = True
            return
        fired = {ev.__name__ for ev, te in zip(seg.events, sol.t_events) if te.size and ev.terminal}
        if "capture" in fired:
            self.seated = True
            if self.model.tracks_passages():
                self.c_d = 0.0  # no passage under way: the floor lifts the block again undamped
            return
        if "trapped" in fired:
            raise StopRun()
        self._cross(seg, sol)

    def _cross(self, seg: "_Segment", sol) -> None:
        """Into the neighbouring region: the damper armed on entering the band, an impact logged on
        leaving it on the other side."""
        region = self.region
        if sol.t_events[1].size:
            y = sol.y_events[1][-1].copy()
            y[0] = seg.hi
            new = region + 1
        else:
            y = sol.y_events[0][-1].copy()
            y[0] = seg.lo
            new = region - 1
        self.y = y
        if new < 0 or new >= self.slopes.size:
            raise StopRun(f"rotation {y[0]:.6g} rad left the spring table at t = {self.t:.6g} s")
        in_band = self.in_band
        if in_band[new] and not in_band[region]:
            self.c_d = self.model.arm_damper(self.block, y[0], y[1])
            self.entry = (self.t, float(y[1]), math.copysign(1.0, y[0]))
        elif in_band[region] and not in_band[new] and self.entry is not None:
            if math.copysign(1.0, y[0]) != self.entry[2]:  # left on the other side: an impact
                self.log_impact(self.entry[0], self.entry[1], y[1])
            self.entry = None
        self.region = new

    def _finish(self) -> RockingResult:
        spring = damper = None
        if self.settings.record:
            _, theta, theta_dot = self.history.arrays()
            spring = np.interp(theta, self.th_tab, self.m_tab)
            damper = self.history.damping() * theta_dot * (np.abs(theta) <= self.band)
        return self.result(spring_moment=spring, damper_force=damper)


class _Segment:
    """One region's linear equation and the events that end its segment."""

    def __init__(self, run: _SDOF, region: int, was_at_turn: bool) -> None:
        s, t = run.settings, run.t
        self.lo, self.hi = lo, hi = run.kinks[region], run.kinks[region + 1]
        self.k_i, self.m_i = k_i, m_i = run.slopes[region], run.intercepts[region]
        self.c_i = c_i = run.c_d if run.in_band[region] else 0.0
        self.is_stiff = bool(run.stiff[region])
        lam, inertia, acc = run.lam, run.inertia, run.acc

        def rhs(tt, yy):
            return [yy[1], (-lam * float(acc(tt)) - c_i * yy[1] - (k_i * yy[0] + m_i)) / inertia]

        self.rhs = rhs
        self.stop_at_peak = bool(run.open_end and s.tail == "peak" and t >= run.duration)
        # a turning point inside the band starts a new passage: the damper is re-armed there
        self.rearm = run.model.tracks_passages() and bool(run.in_band[region]) and not self.is_stiff
        self.events = self._edges(lo, hi) + [self._turning(t if was_at_turn else -math.inf)]
        if self.is_stiff:
            self.events.append(_capture(run.seat))
        if run.open_end and s.tail == "rest" and t >= run.duration and run.in_band[region]:
            self.events.append(_trapped(run))

    @staticmethod
    def _edges(lo: float, hi: float) -> list:
        def lower(tt, yy):
            return yy[0] - lo

        lower.terminal, lower.direction = True, -1

        def upper(tt, yy):
            return yy[0] - hi

        upper.terminal, upper.direction = True, 1

        def overturn(tt, yy):
            return abs(yy[0]) - OVERTURNING_ANGLE

        overturn.terminal, overturn.direction = True, 1
        return [lower, upper, overturn]

    def _turning(self, t_start: float):
        # peaks of |theta| only (theta' leaving the outward sign): a turning point beyond alpha,
        # from which the block falls outwards, does not fire again at the next segment's start
        mid = 0.5 * (self.lo + self.hi)
        direction = 0 if self.is_stiff else (-1 if mid > 0 else 1)

        def turning(tt, yy):
            # a segment that starts at the turning point just handled reports there the sign that
            # follows a peak, so the same peak does not fire again
            return float(direction) if (tt <= t_start and direction) else yy[1]

        turning.terminal = self.stop_at_peak or self.rearm
        turning.direction = direction
        return turning


def _capture(seat: Seat):
    def capture(tt, yy):
        return seat.margin(tt, yy[0], yy[1])

    capture.terminal, capture.direction = True, 1
    return capture


def _trapped(run: _SDOF):
    inertia, U, u_band = run.inertia, run.U, run.u_band

    def trapped(tt, yy):
        return 0.5 * inertia * yy[1] ** 2 + float(U(yy[0])) - u_band

    trapped.terminal, trapped.direction = True, -1
    return trapped


def _region_of(kinks: np.ndarray, theta: float, direction: float) -> int:
    """Index ``i`` of the region ``[kinks[i], kinks[i+1]]`` holding ``theta``; on a kink, the
    region on the side ``direction`` points to."""
    i = int(np.searchsorted(kinks, theta, side="right") - 1)
    if theta == kinks[min(max(i, 0), kinks.size - 1)] and direction < 0:
        i -= 1
    return int(np.clip(i, 0, kinks.size - 2))


__all__ = ["SOLVER_NAME", "solve", "table_potential"]
