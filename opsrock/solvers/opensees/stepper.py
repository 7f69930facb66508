"""The OpenSees transient loop, one step at a time, each concern a method of :class:`Stepper`:

* **step policy** (:meth:`Stepper.choose_step`): in adaptive mode the step lands just inside the damper
  band on entry and just outside it on exit (so the damper acts over the band and only the band,
  Eq. 7), crosses the band in at least ``band_steps`` steps, crosses the stiff branch at zero in one
  symmetric step, resolves the excitation, and under a record lands on the instant the floor can lift
  a seated block; fixed mode takes ``step`` throughout;
* **advance** (:meth:`Stepper.advance`): ``analyze``, and a step that fails is retried with halved
  steps, then the fallback algorithms (:func:`recover`); tolerances are never relaxed;
* **guards** (:meth:`Stepper.check_state`): non-finite states, a sign sawtooth, energy beyond what the
  floor gave, an explicit step from inside the stiff branch: each a failure, never a verdict;
* **the seat** (:meth:`Stepper.seat`): a block seated in the stiff branch drops its free oscillation, as
  the scipy solver does (implicit integrators only); with adaptive Newmark under a record it is then
  carried along the quasi-static deflection without steps up to the last step before the floor can lift
  it (every step there would end seated: the same states, bit for bit, without the steps);
* **damper switching** (:meth:`Stepper.switch_damper`): ``c_D`` armed at the start of every passage
  through the band, zero outside it and while seated, followed by a tiny reset step;
* **stopping** (:meth:`Stepper.stop`): overturning, rest after the excitation, or the end time.
"""

from __future__ import annotations

import math
import time as _time
from itertools import repeat
from math import cos, isfinite

import numpy as np

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE, G
from opsrock.errors import OpsrockError
from opsrock.excitations import Excitation, Record
from opsrock.model import Seat
from opsrock.opensees_session import CONSOLE, ops
from opsrock.result import ImpactLog
from opsrock.solvers.common import potential_energy
from opsrock.solvers.opensees.build import DAMPER_ELE, DAMPER_PARAM, SPRING_ELE, set_algorithm
from opsrock.solvers.opensees.settings import OpenSeesSettings, critical_time_step
from opsrock.solvers.status import MAX_STEPS, REASONS, TIMEOUT

#: Energy-growth test for numerical instability: a run is "unstable" when its mechanical energy
#: exceeds ``UNSTABLE_ENERGY_FACTOR * (E_0 + W_in) + UNSTABLE_ENERGY_FLOOR * m g R (1 - cos alpha)``,
#: with ``W_in`` an upper bound on the work the floor did (``Lambda * PFA * sum |d theta|``). The
#: physical system can never gain more energy than the floor gives, so only a numerical blow-up
#: trips it; factor 2 leaves room for integration error of a converged-but-coarse run.
UNSTABLE_ENERGY_FACTOR: float = 2.0
UNSTABLE_ENERGY_FLOOR: float = 1e-3

#: Default hard cap on the free-rocking tail after the excitation ends (s). Runs normally stop
#: much earlier, at the first moment the peak can no longer grow (usually the first impact).
DEFAULT_TAIL: float = 30.0

#: Sawtooth test for numerical instability: theta changing sign at this many consecutive steps.
#: A physical block needs at least a band crossing plus a flight between two impacts; a step-
#: to-step sign alternation is the signature of an explicit integrator above its critical step
#: on the stiff branch (measured: central difference at 1.01 dt_cr turns a no-uplift pulse into
#: spurious "rocking" of 2e-4 alpha, validation/stability_map).
SAWTOOTH_STEPS: int = 8

#: Adaptive mode: a block approaching zero inside the band lands this fraction of a band step
#: short of zero and then crosses the stiff branch in one symmetric step (see :meth:`Stepper.choose_step`).
CROSSING_FRACTION: float = 0.6

#: Steps in a row with ``|theta| <= theta_e`` after the excitation that count as seated for good.
SEATED_STEPS: int = 20

#: Adaptive mode: steps approaching or leaving the band stop this fraction of a band step past
#: its edge, so the damper acts over the band and only the band (Eq. 7).
EDGE_FRACTION: float = 0.05

#: Adaptive mode: length of the reset step after the damper coefficient changes, as a fraction
#: of a band step.
RESET_FRACTION: float = 1e-3

#: Under a record, a seated block is carried along ``theta_qs`` without steps (:meth:`Stepper.seat`)
#: only over at least this many steps of the seated step.
CARRY_MIN_STEPS: int = 4

#: Adaptive mode: smallest rotation per step (in ``theta_e``) of a passage that starts inside the
#: band. Passages shrink geometrically as a block settles; without a floor their steps would too
#: (measured: 1.9 million steps on a 20-s record at band_steps 160).
MIN_PASSAGE_STEP_RATIO: float = 10.0


class StepFailure(OpsrockError):
    """A step that could not be recovered, or a numerical blow-up: the run is failed with this reason;
    ``failure`` is its kind (:data:`opsrock.solvers.status.FAILURE_KINDS`)."""

    def __init__(self, reason: str, failure: str = "integrator") -> None:
        super().__init__(reason)
        self.failure = failure


def passage_step(h_band: float, distance: float, band_steps: int, theta_e: float) -> float:
    """Rotation per step (rad) of a passage starting ``distance`` (rad) from zero inside the band:
    ``band_steps`` steps over its length ``2 distance``, no more than a band step ``h_band`` and no
    less than :data:`MIN_PASSAGE_STEP_RATIO` ``theta_e``."""
    return max(min(h_band, 2.0 * distance / band_steps), MIN_PASSAGE_STEP_RATIO * theta_e)


class Stepper:
    """The transient loop of one OpenSees run, from the built model's initial state to its stop.

    Parameters
    ----------
    block : Block
    excitation : Excitation
        Floor acceleration (m/s²).
    s : OpenSeesSettings
    node, dof : int
        The node and degree of freedom that carry the block's rotation.
    """

    def __init__(self, block: Block, excitation: Excitation, s: OpenSeesSettings, node: int, dof: int) -> None:
        self.block, self.excitation, self.s, self.node, self.dof = block, excitation, s, node, dof
        # the settings the loop reads at every step, as plain attributes
        self.adaptive, self.step, self.min_step = s.adaptive, s.step, s.min_step
        self.stop_at_rest, self.element_forces = s.stop_at_rest, s.element_forces
        model = self.model = s.model
        self.alpha = block.alpha
        self.band = model.band(block)
        self.theta_e = model.theta_e(block)
        self.half_i = 0.5 * block.I_O
        self.mgR = block.mass * G * block.R
        self.cos_a = math.cos(self.alpha)
        self.barrier = self.mgR * (1.0 - self.cos_a)
        self.lam_pfa = abs(model.lever_arm(block)) * excitation.pfa
        self.duration = float(excitation.duration)
        tail = DEFAULT_TAIL if s.max_free_time is None else float(s.max_free_time)
        self.t_end = self.duration + tail if s.end_time is None else float(s.end_time)
        self.max_steps, self.max_wall_time, self.t_wall = s.max_steps, s.max_wall_time, _time.perf_counter()
        self.rest_margin = s.rest_tolerance * self.alpha
        self.h_band_num = 2.0 * self.band / s.band_steps
        # rotation per step inside the band: a passage that starts at a turning point inside the band
        # is shorter than the band and gets band_steps steps of its own length
        self.h_len = self.h_band_num
        self._excitation_steps(excitation)
        # explicit scheme: a step longer than the stiff branch's critical step, taken from inside
        # the branch, is unstable there (omega_e h > 2); its outcome is not an answer
        explicit = s.integrator == "central_difference" and s.stiff_branch_check
        self.dt_cr = critical_time_step(block, model) if explicit else math.inf
        self.rearm = model.tracks_passages()
        self.seat_on = s.integrator != "central_difference"
        # a seated block is carried over the record's samples that cannot lift it: adaptive mode (the fixed
        # mode stays the literal step-by-step loop) and Newmark, the one integrator whose whole state the
        # seat sets (with HHT and generalized alpha the carry moved theta_max by 1e-13 alpha, which chaotic
        # cases amplified to 0.02 alpha; with Newmark it is bit-identical)
        self.carry = s.integrator == "newmark" and s.adaptive and self.lift_times is not None
        self.seat_model = Seat(model, block, excitation.acceleration)
        self.th_tab, self.m_tab = model.spring_table(block)
        self._initial_state()

    def _excitation_steps(self, excitation: Excitation) -> None:
        """While the floor moves, the adaptive step also resolves the excitation; under a record it lands
        on the samples at which the floor can lift a seated block."""
        s, duration = self.s, self.duration
        self.dt_exc = min(s.step, duration / s.excitation_steps) if duration > 0 else s.step
        self.rec_dt = getattr(excitation, "dt", None)
        if self.rec_dt is not None:
            self.dt_exc = min(self.dt_exc, float(self.rec_dt))
        self.uplift_level = self.model.edge_moment(self.block) / abs(self.model.lever_arm(self.block))  # m/s²
        self.lift_times = None  # record samples at which the floor can lift a seated block (s)
        if isinstance(excitation, Record):
            self.lift_times = excitation.time[np.abs(excitation.values) > self.uplift_level]

    def _initial_state(self) -> None:
        th = self.th = float(ops.nodeDisp(self.node, self.dof))
        thd = self.thd = float(ops.nodeVel(self.node, self.dof))
        self.th_prev, self.thd_prev = th, thd
        self.e_0 = self.half_i * thd * thd + potential_energy(self.block, th)
        self.w_in = 0.0  # upper bound of the work done by the floor (J)
        self.in_band = abs(th) <= self.band
        self.c_now = 0.0
        self.t = 0.0
        self.n_steps = 0
        self.impacts = ImpactLog()
        self.entry: tuple[float, float, bool] | None = None  # (time, velocity, side) of the last band entry
        self.n_alt = 0
        self.theta_max = abs(th)
        self.n_seated = 0
        self.energy = self.e_0
        if self.rearm and self.in_band and abs(th) > self.theta_e and th * thd <= 0.0:
            # starting inside the band, at rest or heading back towards zero: a passage begins
            self.c_now = self.model.arm_damper(self.block, th, thd)
            ops.updateParameter(DAMPER_PARAM, self.c_now)
            self.h_len = passage_step(self.h_band_num, abs(th), self.s.band_steps, self.theta_e)
        # the recorded states: one list of floats a quantity (cheaper to append and to convert than rows)
        self.ts, self.ths, self.thds = [self.t], [th], [thd]
        self.cs = [0.0]  # damper coefficient at each recorded state (after its update: Eq. 7 at that state)
        # initial spring moment from the table: the element's force is only updated by a step
        self.ms, self.fds = [float(np.interp(th, self.th_tab, self.m_tab))], [0.0]
        self.seated_state = False  # the current state was set by the seat, not by a step

    # --- the loop ---------------------------------------------------------------------------------
    def run(self) -> str:
        """Step until a stop; return why (``"overturned"``, ``"rest"``, ``"end_time"``).

        Raises
        ------
        StepFailure
            With the reason the run is failed (an unrecoverable step, an instability, the end time
            reached before rest).
        """
        k_rec = 0
        record_every, adaptive = self.s.record_every, self.adaptive
        # the methods of the step, looked up once (the loop runs some 10^4 times a record)
        choose_step, advance, check_state, seat = self.choose_step, self.advance, self.check_state, self.seat
        switch_damper, stop, record = self.switch_damper, self.stop, self.record
        while True:
            h = choose_step()
            advance(h)
            check_state(h)
            seat()
            if switch_damper() and adaptive and self.thd != 0.0:
                self.reset_step()
            why = stop()
            if why:
                break
            k_rec += 1
            if k_rec >= record_every:
                k_rec = 0
                record()
        if self.ts[-1] != self.t:
            record()
        return why

    def choose_step(self) -> float:
        """The next step (s): ``step`` in fixed mode, the adaptive policy otherwise."""
        if not self.adaptive:
            return self.step
        t, th, thd, duration, min_step = self.t, self.th, self.thd, self.duration, self.min_step
        ath = abs(th)
        h = self._policy_step(ath, abs(thd), th * thd < 0.0)
        h_cap = self.dt_exc if t < duration else self.step
        if h > h_cap:
            h = h_cap
        elif h < min_step:
            h = min_step
        if t < duration < t + h:
            h = duration - t  # land on the end of the excitation (a kink in a(t))
            if h < min_step:
                h = min_step
        if ath <= self.theta_e and t < duration and self.lift_times is not None:
            h = self._land_on_uplift(h)
        return h

    def _policy_step(self, ath: float, avel: float, approaching: bool) -> float:
        """The adaptive step before its caps: by where the block is against the band and where it heads."""
        dt, band = self.step, self.band
        h_rot = self.h_len if ath <= band else self.h_band_num
        if avel * dt <= h_rot:
            return dt
        if ath <= band:
            h = h_rot / avel
            if approaching:
                if ath > self.theta_e:
                    # approaching zero: land about half a band step short of it, then cross the stiff
                    # branch in one step ending as far beyond zero as it started. The spring moment jumps
                    # from +M0 to -M0 there and the trapezoidal rule sees only the step ends: an
                    # asymmetric crossing gains or loses an impulse of up to M0 h, a symmetric one none.
                    if ath <= CROSSING_FRACTION * h_rot:
                        h = 2.0 * ath / avel
                    elif ath < (1.0 + CROSSING_FRACTION) * h_rot:
                        h = (ath - 0.5 * h_rot) / avel
            elif band - ath < 1.5 * h_rot:
                # leaving: step just past the band edge, so the damper acts over the band only (a step
                # overshooting the edge by a band step adds 1/band_steps of the band's dissipation)
                h = (band - ath + EDGE_FRACTION * h_rot) / avel
            return h
        if approaching:
            # approaching the band: halve the distance, then step just inside the edge, so the damper is
            # switched on where the band begins (Eq. 7)
            gap = ath - band
            if gap > 2.0 * self.h_band_num:
                return 0.5 * gap / avel
            return (gap + EDGE_FRACTION * self.h_band_num) / avel
        return dt

    def _land_on_uplift(self, h: float) -> float:
        """Seated under a record: land on the instant the floor can lift the block (``|Lambda a| =
        M_s(theta_e)``), as the scipy solver does; a step of ``omega_e h >> 1`` across it lifts it late.
        Between samples ``a(t)`` is linear, so a crossing in ``(t, t + h]`` ends at a sample above the
        level: only then is it searched for."""
        # imported here: scipy.optimize is not needed by a pulse (a campaign's first case pays module
        # imports inside its time budget)
        from opsrock.solvers.common import first_exceedance

        t, lift_times = self.t, self.lift_times
        j = int(lift_times.searchsorted(t, "right"))
        if j < lift_times.size and lift_times[j] - self.rec_dt < t + h:
            t_up = first_exceedance(self.excitation, self.uplift_level, t, min(t + h, lift_times[j]), h)
            if t_up is not None and t_up > t + self.s.min_step:
                h = t_up - t
        return h

    def advance(self, h: float) -> None:
        """One step of ``h`` (s), recovered by :func:`recover` if it fails; then the new state."""
        t = self.t
        if ops.analyze(1, h) == 0:
            self.n_steps += 1
        else:
            try:
                self.n_steps += recover(self.s, h)
            except StepFailure as exc:
                # a floor acceleration that turns non-finite makes the step fail to converge
                kind = exc.failure if isfinite(float(self.excitation.acceleration(t + h))) else "nonfinite"
                raise StepFailure(f"step at t = {t:.6g} s (dt = {h:.3g} s) did not converge: {exc}", kind) from None
        if h >= self.dt_cr and abs(self.th) <= self.theta_e:
            raise StepFailure(
                f"unstable: explicit central difference stepped {h:.4g} s from inside the stiff branch "
                f"(|theta| <= theta_e) at t = {t:.6g} s, above its critical step dt_cr = {self.dt_cr:.4g} s",
                "unstable")
        self.t = t + h
        self.th_prev, self.thd_prev = self.th, self.thd
        self.th = ops.nodeDisp(self.node, self.dof)
        self.thd = ops.nodeVel(self.node, self.dof)

    def check_state(self, h: float) -> None:
        """The guards: a finite state, no sign sawtooth, no energy the floor did not give."""
        t, th, thd, th_prev = self.t, self.th, self.thd, self.th_prev
        if not (isfinite(th) and isfinite(thd)):
            raise StepFailure(f"unstable: non-finite state at t = {t:.6g} s (theta = {th!r}, theta_dot = {thd!r})",
                              "nonfinite")
        ath = abs(th)
        if ath > self.theta_max:
            self.theta_max = ath
        if (th > 0.0) != (th_prev > 0.0):
            self.n_alt += 1
            if self.n_alt >= SAWTOOTH_STEPS:
                raise StepFailure(
                    f"unstable: theta changed sign at {self.n_alt} consecutive steps up to t = {t:.6g} s "
                    f"(dt = {h:.3g} s): a numerical sawtooth, not rocking", "unstable")
        else:
            self.n_alt = 0
        # physical plausibility: energy can only come from the floor
        if t <= self.duration + h:
            self.w_in += self.lam_pfa * abs(th - th_prev)
        energy = self.energy = self.half_i * thd * thd + self.mgR * (cos(self.alpha - ath) - self.cos_a)
        if energy > UNSTABLE_ENERGY_FACTOR * (self.e_0 + self.w_in) + UNSTABLE_ENERGY_FLOOR * self.barrier:
            raise StepFailure(
                f"unstable: mechanical energy {energy:.4g} J at t = {t:.6g} s exceeds the initial energy "
                f"plus the floor's work ({self.e_0 + self.w_in:.4g} J); numerical blow-up (theta = {th:.4g} rad)",
                "unstable")

    def seat(self) -> None:
        """Seated: drop the stiff branch's free oscillation, as the scipy solver does.

        Implicit schemes only: the explicit scheme's stiff-branch instability above its critical step must
        stay visible; without the seat, fixed-step Newmark at 1e-4 s was up to 0.45 alpha off on the paper
        pulses with the per-passage damper, 3.1 % with it. With adaptive Newmark under a record the seated
        block is then carried to the last step before the floor can lift it (:meth:`_carry_seated`).
        """
        t, th = self.t, self.th
        if abs(th) > self.theta_e or not self.seat_on:
            self.seated_state = False
            return
        self.seated_state = self.seat_model.captures(t, th, self.thd)
        if self.seated_state:
            if self.carry and t < self.duration:
                t = self._carry_seated(t)
            self.th, self.thd = self.seat_model.theta_qs(t), 0.0
            ops.setNodeDisp(self.node, self.dof, self.th, "-commit")
            ops.setNodeVel(self.node, self.dof, 0.0, "-commit")
            ops.setNodeAccel(self.node, self.dof, 0.0, "-commit")
            ops.domainChange()  # the integrator keeps its own state vectors: re-read the domain's

    def _carry_seated(self, t: float) -> float:
        """Seated under a record at ``t`` (s): carry the block along ``theta_qs`` without steps; return the
        time (s) it is carried to (``t`` itself if the carry is shorter than :data:`CARRY_MIN_STEPS` steps).

        A seated block follows ``theta_qs`` until the floor can lift it (:class:`opsrock.model.Seat`). Up to
        the carry's end (:meth:`_carry_target`) every step would be a seated step from ``(theta_qs, 0)``
        that the seat captures again: only the step grid and the domain's clock carry over to the next
        step, and both are set as the steps would have left them. The seated path (piecewise linear
        between the samples) enters ``theta_max``, the floor's work bound, the seated-step count of the
        rest test and the history. Measured: 48,700 of the 70,300 steps on the four records of ``opsrock
        bench --only records`` were such steps; with the carry, theta_max and the verdict are bit-identical
        there and on all 207 records of validation case 9 (steps 2.27 million -> 1.56 million).
        """
        t_to, t_ops, n = self._carry_target(t)
        if n < CARRY_MIN_STEPS:
            return t
        excitation, times = self.excitation, self.excitation.time
        i0, i1 = int(times.searchsorted(t, "right")), int(times.searchsorted(t_to, "left"))
        path_t = np.concatenate(([t], times[i0:i1], [t_to]))
        a = np.concatenate(([excitation.acceleration(t)], excitation.values[i0:i1], [excitation.acceleration(t_to)]))
        path = (-self.seat_model.lam / self.seat_model.k_e) * a  # theta_qs (rad)
        self.theta_max = max(self.theta_max, float(np.max(np.abs(path))))
        self.w_in += self.lam_pfa * float(np.sum(np.abs(np.diff(path))))
        self.n_seated += n
        keep = slice(0, -1, self.s.record_every)  # the states at t and at the samples before t_to
        kept = path[keep]
        self.ts.extend(path_t[keep].tolist())
        self.ths.extend(kept.tolist())
        self.thds.extend(repeat(0.0, kept.size))
        self.cs.extend(repeat(0.0, kept.size))
        if self.element_forces:
            self.ms.extend(np.interp(kept, self.th_tab, self.m_tab).tolist())
            self.fds.extend(repeat(0.0, kept.size))
        self.t = t_to
        ops.setTime(t_ops)
        return t_to

    def _carry_target(self, t: float) -> tuple[float, float, int]:
        """Where a block seated at ``t`` (s) is carried: ``(t_to, the domain's clock there, seated steps)``.

        ``a(t)`` is linear between samples, so the floor cannot lift the block before the start of the first
        sample interval that ends above the uplift level; the carry ends at the last point of the step grid
        ``t, t + h, ...`` (``h`` the seated step) from which a step cannot reach into that interval (the
        steps from there on land on the uplift instant as before), or at the end of the excitation.
        """
        h, lift = max(self.dt_exc, self.min_step), self.lift_times
        t_stop = min(self.duration, self.t_end)
        j = int(lift.searchsorted(t, "right"))
        t_last = lift[j] - self.rec_dt - h if j < lift.size else math.inf  # the last step start short of it
        if t_last >= t_stop:  # no uplift before the excitation ends (or the run does): carried to that end
            return t_stop, ops.getTime() + (t_stop - t), math.ceil((t_stop - t) / h)
        if t_last < t + CARRY_MIN_STEPS * h:
            return t, 0.0, 0
        # the grid as the steps add it up (t += h, rounding included, so the landing step is the same)
        steps = np.full(int((t_last - t) / h) + 2, h)
        grid = np.add.accumulate(np.concatenate(([t], steps)))
        n = int(grid.searchsorted(t_last, "right")) - 1
        # OpenSees adds the same steps to its own clock, which sub-stepped recoveries leave a few ulps off
        # this one (the floor's acceleration is read at its time)
        t_ops = float(np.add.accumulate(np.concatenate(([ops.getTime()], steps[:n])))[-1])
        return float(grid[n]), t_ops, n

    def switch_damper(self) -> bool:
        """The damper (Eq. 7-8): armed at the start of a passage through the band, zero outside it and
        while seated; an impact logged on leaving the band on the other side. True if ``c_D`` changed."""
        th, thd = self.th, self.thd
        ath = abs(th)
        if ath <= self.band:
            if not self.in_band:
                self.in_band = True
                self.entry = (self.t, thd, th > 0.0)
                self.h_len = self.h_band_num
                return self._set_damper(self.model.arm_damper(self.block, th, thd))
            if self.rearm and self.seated_state and self.c_now != 0.0:
                # seated (the seat just dropped the branch's oscillation): no passage under way
                return self._set_damper(0.0)
            if self.rearm and ath > self.theta_e and th * thd < 0.0 and self.th_prev * self.thd_prev > 0.0:
                # turned inside the band in this step: a new passage, the damper is re-armed with the
                # state at the step's end (heading back towards zero)
                self.h_len = passage_step(self.h_band_num, ath, self.s.band_steps, self.theta_e)
                return self._set_damper(self.model.arm_damper(self.block, th, thd))
            return False
        if self.in_band:
            self.in_band = False
            if self.entry is not None and (th > 0.0) != self.entry[2]:  # left on the other side: an impact
                self.impacts.add(self.entry[0], self.entry[1], thd)
            self.entry = None
            if self.c_now != 0.0:
                return self._set_damper(0.0)
        return False

    def _set_damper(self, c: float) -> bool:
        self.c_now = c
        ops.updateParameter(DAMPER_PARAM, c)
        return True

    def reset_step(self) -> None:
        """Newmark's next step averages the damper force at its start, computed with the old coefficient,
        with the one at its end: half a step of stale damping (measured: an exit step of 1 ms took 0.08
        rad/s off 1.35 rad/s). A tiny step re-establishes equilibrium with the new coefficient at
        negligible cost."""
        s = self.s
        h_reset = min(s.step, max(s.min_step, RESET_FRACTION * self.h_len / abs(self.thd)))
        if ops.analyze(1, h_reset) != 0:
            try:
                self.n_steps += recover(s, h_reset)
            except StepFailure as exc:
                raise StepFailure(f"reset step at t = {self.t:.6g} s did not converge: {exc}") from None
        else:
            self.n_steps += 1
        self.t += h_reset
        self.th = ops.nodeDisp(self.node, self.dof)
        self.thd = ops.nodeVel(self.node, self.dof)
        self.seated_state = False
        if abs(self.th) > self.theta_max:
            self.theta_max = abs(self.th)

    def stop(self) -> str:
        """Why the run stops after this step (``""``: it goes on).

        Rest: the excitation is over, the block inside the hump (``|theta| < alpha``; beyond it a block
        with less than the barrier energy falls over) and unable to pass its peak again. Inside the stiff
        branch the step-end velocity is not the physical one (the branch is crossed within a step), so
        the energy test waits for a step that ends outside it; a block seated for good stays inside for
        :data:`SEATED_STEPS` steps in a row.
        """
        ath, t = abs(self.th), self.t
        if ath >= OVERTURNING_ANGLE:
            return "overturned"
        self.n_seated = self.n_seated + 1 if ath <= self.theta_e else 0
        if self.stop_at_rest and t >= self.duration and ath < self.alpha:
            barrier = self.mgR * (math.cos(self.alpha - min(self.theta_max + self.rest_margin, self.alpha)) - self.cos_a)
            if (ath > self.theta_e and self.energy <= barrier) or self.n_seated >= SEATED_STEPS:
                return "rest"
        if t >= self.t_end:
            if not self.stop_at_rest:
                return "end_time"
            raise StepFailure(
                f"end_time = {self.t_end:.6g} s reached before the block overturned or came to rest "
                f"(theta = {self.th:.4g} rad, theta_dot = {self.thd:.4g} rad/s); raise end_time", "max_free_time")
        if self.max_steps is not None and self.n_steps >= self.max_steps:
            raise StepFailure(f"{REASONS[MAX_STEPS]} (max_steps = {self.max_steps}, t = {t:.6g} s)", "max_steps")
        if _time.perf_counter() - self.t_wall > self.max_wall_time:
            raise StepFailure(f"{REASONS[TIMEOUT]} (max_wall_time = {self.max_wall_time:g} s, t = {t:.6g} s)",
                              "timeout")
        return ""

    def record(self) -> None:
        """Keep the current state (and, with ``element_forces``, the elements' moments)."""
        self.ts.append(self.t)
        self.ths.append(self.th)
        self.thds.append(self.thd)
        self.cs.append(self.c_now)
        if not self.element_forces:
            return
        if self.seated_state:
            # a state set by the seat (no step since): the elements still hold the step's forces
            self.ms.append(float(np.interp(self.th, self.th_tab, self.m_tab)))
            self.fds.append(self.c_now * self.thd)
        else:
            self.ms.append(ops.eleResponse(SPRING_ELE, "force")[1])
            self.fds.append(ops.eleResponse(DAMPER_ELE, "force")[1])

    def history(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(time, theta, theta_dot)`` recorded; the current state appended if it is not the last kept."""
        if not self.ts or self.ts[-1] != self.t:
            self.ts.append(self.t)
            self.ths.append(self.th)
            self.thds.append(self.thd)
        return np.array(self.ts), np.array(self.ths), np.array(self.thds)

    def moments(self) -> tuple[np.ndarray, np.ndarray]:
        """Spring moment and damper force (N m) at the recorded states."""
        if self.element_forces:
            return np.array(self.ms), np.array(self.fds)
        theta, theta_dot = np.array(self.ths), np.array(self.thds)
        return np.interp(theta, self.th_tab, self.m_tab), np.array(self.cs) * theta_dot


def recover(s: OpenSeesSettings, h: float) -> int:
    """Advance by ``h`` after a failed step: halve the step, then try the fallback algorithms.

    Returns the number of sub-steps taken; raises :class:`StepFailure` with the reason otherwise.
    """
    CONSOLE["retries"] += 1
    tried = []
    for algorithm in (s.algorithm, *s.fallback_algorithms):
        if algorithm != s.algorithm:
            set_algorithm(s, algorithm)
        try:
            for k in range(1, s.max_halvings + 1):
                sub = h / 2**k
                if sub < s.min_step:
                    break
                if _advance_in_substeps(sub, 2**k):
                    key = f"halving:{algorithm}"
                    CONSOLE["recovered_by"][key] = CONSOLE["recovered_by"].get(key, 0) + 1
                    return 2**k
            tried.append(algorithm)
        finally:
            if algorithm != s.algorithm:
                set_algorithm(s, s.algorithm)
    raise StepFailure(
        f"no convergence with {', '.join(tried) or s.algorithm} after up to {s.max_halvings} step halvings "
        f"(tol = {s.tol:g}, max_iter = {s.max_iter})"
    )


def _advance_in_substeps(sub: float, n: int) -> bool:
    """Take ``n`` steps of ``sub``; on a failure part-way, give up (the domain keeps the
    committed sub-steps, so the caller must not retry from the start)."""
    for i in range(n):
        if ops.analyze(1, sub) != 0:
            if i > 0:
                raise StepFailure(f"sub-step {i + 1} of {n} (dt = {sub:.3g} s) failed after earlier ones committed")
            return False
    return True


__all__ = ["CARRY_MIN_STEPS", "DEFAULT_TAIL", "SAWTOOTH_STEPS", "Stepper", "StepFailure", "passage_step", "recover"]
