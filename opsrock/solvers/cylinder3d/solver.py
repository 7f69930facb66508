"""One case: :func:`solve` (a floor motion in plan, a pulse or a record along ``x``, or free motion from a tilted
state) and :func:`free_motion` (from any state on a still floor)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE, G
from opsrock.errors import InputError, InputTypeError, ModelNotSupported
from opsrock.excitations import Pulse, Record
from opsrock.excitations.plan import PlanMotion
from opsrock.result import MODES, ContactSummary, PlanHistory, PlanSummary, RockingResult, failed_result
from opsrock.solvers._compile import announce_compile
from opsrock.solvers.common import SolverRun, check_inputs, make_settings, settings_record
from opsrock.solvers.registry import check_model
from opsrock.solvers.cylinder3d import constants as C
from opsrock.solvers.cylinder3d import kernel as kn
from opsrock.solvers.cylinder3d.model import (CylinderProperties, cylinder_mass, cylinder_properties, make_floor,
                                              make_model, make_roll_work, make_state, make_workspace)
from opsrock.solvers.cylinder3d.settings import Cylinder3DSettings
from opsrock.solvers.status import REASONS, failure_of

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "cylinder3d"


@dataclass(frozen=True)
class _Forcing:
    """The floor motion in the cylinder's frame as the kernel takes it (:class:`.model.Floor`), with its step
    ``dt`` (s) and ``peak`` ``max |a_h| + max |a_v|`` (m/s²)."""

    form: int
    ax: np.ndarray
    ay: np.ndarray
    av: np.ndarray
    sub: int
    n_exc: int
    tail_av: float
    dt: float
    peak: float


def _plan(excitation: object) -> PlanMotion:
    """``excitation`` as a :class:`PlanMotion` (a bare pulse or record acts along ``x``); refuses what the kernel
    cannot take: anything but analytic pulses and records, a pulse with a record, records of different steps."""
    if not isinstance(excitation, PlanMotion):
        if not isinstance(excitation, (Pulse, Record)):
            raise InputTypeError(f"solver {SOLVER_NAME!r} solves analytic pulses (Pulse), records (Record) and "
                                 f"PlanMotion of them, got {type(excitation).__name__}")
        return PlanMotion(excitation)
    parts = [excitation.first] + ([] if excitation.second is None else [excitation.second])
    if not (all(isinstance(p, Pulse) for p in parts) or all(isinstance(p, Record) for p in parts)):
        raise InputTypeError(f"solver {SOLVER_NAME!r} takes a PlanMotion of two pulses or of two records, got "
                             f"{' and '.join(type(p).__name__ for p in parts)}")
    if len(parts) == 2 and isinstance(parts[0], Record) and not math.isclose(parts[0].dt, parts[1].dt, rel_tol=1e-12):
        raise InputError(f"second must share the first record's sample step dt = {parts[0].dt!r} s, got "
                         f"{parts[1].dt!r} s", argument="second")
    return excitation


def _pulse_forcing(plan: PlanMotion, dt_nom: float, theta_mj: float) -> _Forcing:
    """Pulses sampled at every step's evaluation time; a whole number of steps in the longer pulse."""
    n = max(1, math.ceil(plan.duration / dt_nom))
    dt = plan.duration / n
    ax, ay = (np.ascontiguousarray(a, dtype=float) for a in plan.components((np.arange(n) + theta_mj) * dt))
    vertical = float(plan.first.vertical)
    return _Forcing(C.FORCING_STEPWISE, ax, ay, np.full(n, vertical), 1, n, vertical, dt,
                    float(np.max(np.hypot(ax, ay))) + abs(vertical))


def _record_forcing(plan: PlanMotion, dt_nom: float) -> _Forcing:
    """The records' samples turned into the cylinder's frame (by the azimuth), ``sub`` steps per sample interval."""
    rec, second = plan.first, plan.second
    sub = max(1, math.ceil(rec.dt / dt_nom))
    n = max(rec.values.size, 0 if second is None else second.values.size)
    a1, a2, av = np.zeros(n), np.zeros(n), np.zeros(n)
    a1[:rec.values.size] = rec.values
    if second is not None:
        a2[:second.values.size] = second.values
    if rec.vertical is not None:
        av[:rec.values.size] = rec.vertical
    c, s = math.cos(math.radians(plan.azimuth)), math.sin(math.radians(plan.azimuth))
    ax, ay = c * a1 + s * a2, -s * a1 + c * a2
    return _Forcing(C.FORCING_LINEAR, ax, ay, av, sub, (n - 1) * sub, 0.0, rec.dt / sub,
                    float(np.max(np.hypot(ax, ay))) + float(np.max(np.abs(av))))


def _free_forcing(duration: float, dt_nom: float) -> _Forcing:
    """No floor motion for ``duration`` (s)."""
    n = max(1, math.ceil(duration / dt_nom))
    z = np.zeros(n)
    return _Forcing(C.FORCING_STEPWISE, z, z.copy(), z.copy(), 1, n, 0.0, duration / n, 0.0)


def tilted_state(block: Block, theta: float, theta_dot: float = 0.0, omega_z: float = 0.0) -> np.ndarray:
    """The kernel's 13-float state of the cylinder ``block`` tilted by ``theta`` (rad) in the ``x-z`` plane on its
    rim point at ``x = sgn(theta) r``, turning about that point with angular velocity ``(0, theta_dot, omega_z)``
    (rad/s, floor frame): ``omega_z`` about the vertical sets the contact point running round the rim (wobbling)."""
    r, h = cylinder_properties(block).r, block.h_cm
    c = 1.0 if theta >= 0.0 else -1.0
    x = c * r * (1.0 - math.cos(theta)) + h * math.sin(theta)
    z = c * r * math.sin(theta) + h * math.cos(theta)
    om = np.array([0.0, theta_dot, omega_z])
    v = np.cross(om, np.array([x - c * r, 0.0, z]))
    return np.array([x, 0.0, z, math.cos(0.5 * theta), 0.0, math.sin(0.5 * theta), 0.0, *v, *om])


def _run(run: SolverRun, forcing: _Forcing, state0: np.ndarray, tail: bool) -> RockingResult:
    """Run the kernel on one case and build the result."""
    block, settings = run.block, run.settings
    cyl = cylinder_properties(block)
    model = make_model(block, cyl, settings, forcing.dt, forcing.peak, tail)
    floor = make_floor(forcing.form, forcing.ax, forcing.ay, forcing.av, forcing.sub, forcing.n_exc, forcing.tail_av)
    every, max_tail = model.numerics.hist_every, model.limits.max_tail
    cap = min(forcing.n_exc + max(max_tail, 0), settings.step_limit) // every + 3 if settings.record else 0
    hist = np.empty((cap, C.H_SIZE))
    state = make_state(state0)
    state.track[C.T_SEATED] = 1.0 if not np.any(state0[3:] - np.array([1.0] + [0.0] * 9)) else 0.0
    record = {"solver": SOLVER_NAME, **settings_record(settings), "dt": forcing.dt}
    announce_compile(kn.run, SOLVER_NAME)
    try:
        run.compiled_call(kn.run, model, floor, state, make_workspace(model.design.n_rim), make_roll_work(), hist)
    except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
        return failed_result(SOLVER_NAME, record, cyl.alpha, f"{type(exc).__name__}: {exc}",
                             wall_time_s=run.elapsed())
    return _result(run, cyl, state.out, hist[:int(state.out[C.OUT_N_HIST])], record, state0)


def mechanical_energy(block: Block, state: np.ndarray) -> tuple[float, float]:
    """Kinetic and potential energy (J) of a kernel state of the cylinder ``block``; ``PE = m g (z - h_cm)``."""
    cyl = cylinder_properties(block)
    w, x, y, z = (float(v) for v in state[3:7])
    axis = np.array([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)])
    om = np.asarray(state[10:13], dtype=float)
    along = float(om @ axis)
    rot = cyl.i_h * float(om @ om - along * along) + cyl.i_z * along * along
    kinetic = 0.5 * block.mass * (float(state[7:10] @ state[7:10]) + rot)
    return kinetic, block.mass * G * (float(state[2]) - block.h_cm)


def _energy(block: Block, out: np.ndarray, state0: np.ndarray) -> dict[str, float]:
    """The run's energy balance in J (for the block's mass), with rigid3d's keys: the floor's work, the initial and
    final kinetic and potential energy, ``friction_work`` (the contact impulses' work at each contact step's end
    velocities, landings apart: slip, and the rim point's drift while it rolls), ``impact_loss`` (the kinetic energy
    the impulses took at each landing) and ``residual`` (the balance: the scheme's own error, ``O(dt)``)."""
    kinetic, potential = mechanical_energy(block, out[C.OUT_STATE:C.OUT_STATE + 13])
    initial = sum(mechanical_energy(block, state0))
    work, fric, imp = (block.mass * float(out[i]) for i in (C.OUT_INPUT_WORK, C.OUT_FRICTION_WORK, C.OUT_IMPACT_LOSS))
    return {"input_work": work, "kinetic": kinetic, "potential": potential, "friction_work": fric,
            "impact_loss": imp, "initial": initial, "residual": work + initial - kinetic - potential - fric - imp}


def _diagnostics(out: np.ndarray) -> dict[str, Any]:
    """The kernel's bookkeeping, JSON-serialisable."""
    steps = max(1.0, out[C.OUT_CONTACT_STEPS])
    return {"end_time": float(out[C.OUT_TIME]), "max_penetration": float(out[C.OUT_MAX_PENETRATION]),
            "contact_steps": int(out[C.OUT_CONTACT_STEPS]), "rest_skip_steps": int(out[C.OUT_REST_STEPS]),
            "nsgs_unconverged_steps": int(out[C.OUT_NSGS_FAILED]),
            "nsgs_mean_sweeps": float(out[C.OUT_NSGS_SWEEPS] / steps),
            "flat_closed_steps": int(out[C.OUT_FLAT_STEPS]), "lift_steps": int(out[C.OUT_LIFT_STEPS]),
            "slip_unconverged": int(out[C.OUT_SLIP_UNCONVERGED]), "time_base": float(out[C.OUT_TIME_BASE]),
            "tail_settled": bool(out[C.OUT_TAIL_SETTLED] > 0.5), "tail_cut": bool(out[C.OUT_TAIL_CUT] > 0.5),
            "roll_steps": int(out[C.OUT_ROLL_STEPS]), "roll_span": int(out[C.OUT_ROLL_SPAN]),
            "roll_failed": int(out[C.OUT_ROLL_FAILED]), "tail_bound": bool(out[C.OUT_TAIL_BOUND] > 0.5),
            "tail_wobble": bool(out[C.OUT_TAIL_WOBBLE] > 0.5), "contact_turn": float(out[C.OUT_CONTACT_TURN]),
            "tail_energy_ratio": float(out[C.OUT_TAIL_ENERGY])}


def _ending(out: np.ndarray, cyl: CylinderProperties, tail: bool) -> str:
    """How a finished run ended, in words (``diagnostics["ending"]``)."""
    if out[C.OUT_OVERTURNED] > 0.5:
        return "overturned"
    bound = f"tilt bounded by {out[C.OUT_TILT_BOUND]:.6g} rad ({out[C.OUT_TILT_BOUND] / cyl.alpha:.4g} alpha)"
    if out[C.OUT_TAIL_BOUND] > 0.5:
        return (f"energy below overturning energy ({out[C.OUT_TAIL_ENERGY]:.6g} of m (g + a_v) (sqrt(r² + h_cm²) - "
                f"h_cm)) at "
                f"the end of max_free_time after the excitation, still moving: it can never overturn "
                f"(nothing works on it any more); {bound}")
    if out[C.OUT_TAIL_WOBBLE] > 0.5:
        return (f"steady wobble: energy {out[C.OUT_TAIL_ENERGY]:.6g} of what overturning takes, but rolling without "
                f"slip after the excitation through a full period of its tilt, which is periodic (Chaplygin's "
                f"integrable rolling body of revolution): it can never overturn; {bound}")
    if out[C.OUT_TAIL_SETTLED] > 0.5:
        return f"peak final: energy below half of what the peak took, the base at most {C.PEAK_BASE_SPEED} m/s; {bound}"
    if out[C.OUT_TAIL_CUT] > 0.5:
        return (f"peak final to {C.TILT_SLACK} alpha: energy cannot raise the tilt further, still moving; {bound}")
    return "at rest" if tail else "end_time"


def _result(run: SolverRun, cyl: CylinderProperties, out: np.ndarray, hist: np.ndarray, record: dict[str, Any],
            state0: np.ndarray) -> RockingResult:
    """The :class:`RockingResult` of a finished kernel run."""
    block = run.block
    time_s, theta, theta_dot = (hist[:, c].copy() for c in (C.H_T, C.H_THETA, C.H_THETA_DOT))
    slide = hist[:, C.H_SLIDE].copy()
    status, steps = int(out[C.OUT_STATUS]), int(out[C.OUT_STEPS])
    diagnostics = _diagnostics(out)
    diagnostics["ending"] = "failed" if status != C.STATUS_OK else _ending(out, cyl, run.excitation is not None)
    if any(diagnostics[key] for key in ("tail_cut", "tail_settled", "tail_bound", "tail_wobble")):
        diagnostics["tilt_bound"] = float(out[C.OUT_TILT_BOUND])
    if status != C.STATUS_OK:
        reason = REASONS[status]
        if status == C.STATUS_TAIL:
            reason += (f" (still rolling on its rim, its energy {out[C.OUT_TAIL_ENERGY]:.6g} times what overturning "
                       f"takes, m (g + a_v) (sqrt(r² + h_cm²) - h_cm), or tilted past alpha: it may still overturn; the rigid "
                       f"model has no rolling resistance; a longer max_free_time may settle it)")
        if status == C.STATUS_CONTACT:
            reason += (f": the NSGS contact solver did not converge in {run.settings.nsgs_fail_steps} consecutive "
                       f"steps (t = {out[C.OUT_TIME]:.6g} s)")
        failed = failed_result(SOLVER_NAME, record, cyl.alpha, reason, time=time_s, theta=theta, theta_dot=theta_dot,
                               n_steps=steps, wall_time_s=run.elapsed(), failure=failure_of(status))
        return replace(failed, slide=slide, diagnostics=diagnostics)
    fin = out[C.OUT_STATE:C.OUT_STATE + 13]
    w, x, y, z = fin[3:7]
    residual = (float(fin[0] - 2 * cyl.h * (x * z + w * y)), float(fin[1] - 2 * cyl.h * (y * z - w * x)))
    energy = _energy(block, out, state0)
    overturned = bool(out[C.OUT_OVERTURNED])
    plan = PlanSummary(
        tilt_max=float(out[C.OUT_THETA_MAX]), twist_max=float(out[C.OUT_TWIST_MAX]),
        slide_max=float(out[C.OUT_SLIDE_MAX]), slide_residual=residual,
        overturned_over=("rim" if out[C.OUT_OVER_KIND] < 1.5 else "rolling") if overturned else "",
        overturn_direction=math.degrees(out[C.OUT_OVER_DIR]) if overturned else math.nan,
        time_sliding=float(out[C.OUT_TIME_SLIDING]), time_flight=float(out[C.OUT_TIME_FLIGHT]), energy=energy,
        time_rim=float(out[C.OUT_TIME_ROCKING]), time_rolling=float(out[C.OUT_TIME_ROLLING]))
    first = int(out[C.OUT_FIRST_MODE])
    contact = ContactSummary(
        first_mode=MODES[first] if first >= 0 else "rest", time_sliding=plan.time_sliding,
        time_rocking=plan.time_rim, slide_max=plan.slide_max, slide_residual=residual[0],
        time_flight=plan.time_flight, energy=energy)
    history = None
    if run.settings.record:
        history = PlanHistory(rotation=hist[:, C.H_ROT:C.H_ROT + 3].copy(),
                              position=hist[:, C.H_POS:C.H_POS + 3].copy(), twist=hist[:, C.H_TWIST].copy(),
                              slide=hist[:, C.H_SLIDE:C.H_SLIDE + 2].copy(),
                              corners_down=hist[:, C.H_DOWN].astype(int))
    theta_max = float(out[C.OUT_THETA_MAX])
    return RockingResult(
        solver=SOLVER_NAME, settings=record, alpha=cyl.alpha, time=time_s, theta=theta, theta_dot=theta_dot,
        theta_max=theta_max, overturned=theta_max >= OVERTURNING_ANGLE, rocked=bool(out[C.OUT_ROCKED]),
        n_steps=steps, wall_time_s=run.elapsed(), n_impacts=int(out[C.OUT_IMPACTS]), diagnostics=diagnostics,
        slide=slide, contact=contact, plan=plan, plan_history=history)


def solve(block: Block, excitation: PlanMotion | Pulse | Record | None,
          settings: Cylinder3DSettings | None = None, **overrides: Any) -> RockingResult:
    """Response of a rigid cylinder on a floor with Coulomb friction to a floor motion in plan (two horizontal
    components and a vertical one), by Moreau-Jean time stepping (:mod:`opsrock.solvers.cylinder3d`).

    Parameters
    ----------
    block : Block
        The cylinder: ``width`` its diameter (m; ``depth`` None or the same), ``height`` (m), ``cm_height`` and
        ``radius_of_gyration`` (m; about a horizontal axis through the centre of mass; without it a homogeneous
        solid cylinder's), ``friction`` and ``friction_kinetic`` (None: a base that never slips). Its impact law
        must be Housner's (``restitution_factor = 1``, no ``restitution``). :func:`cylinder_block` builds one.
    excitation : PlanMotion or Pulse or Record or None
        The floor motion in plan; a bare pulse or record acts along ``x``. None: a still floor for ``end_time``
        from the cylinder tilted by ``theta0`` (rad) in its ``x-z`` plane with ``theta_dot0`` (rad/s).
    settings : Cylinder3DSettings, optional
        Numerical settings; keyword ``overrides`` replace single fields.

    Returns
    -------
    RockingResult
        As rigid3d's: ``theta`` the tilt (rad) signed by the lean along ``x``, ``theta_dot`` the angular velocity
        about ``y`` (rad/s), ``alpha = atan(r / h_cm)``, ``plan`` (:class:`~opsrock.result.PlanSummary`, its
        ``overturned_over`` ``"rim"`` or ``"rolling"``, ``time_rim`` and ``time_rolling``), ``contact``,
        ``plan_history``, ``slide`` (the base centre along ``x``, m). A run that did not finish is failed with its
        reason.

    Raises
    ------
    InputError
        A depth other than the width, a restitution other than Housner's, a settings value out of range, two
        records of different sample steps.
    InputTypeError
        A block that is not a :class:`Block`, or an excitation other than pulses and records.
    """
    settings = make_settings(Cylinder3DSettings, settings, overrides)
    block = check_inputs(SOLVER_NAME, block, excitation, settings)
    cylinder_properties(block)
    if (excitation is None) != (settings.end_time is not None):
        raise ModelNotSupported(f"solver {SOLVER_NAME!r} takes end_time (the span of free motion) with "
                                f"excitation None and only then, got end_time = {settings.end_time!r}")
    plan = None if excitation is None else _plan(excitation)
    return _CylinderRun(block, plan, settings).run()


def free_motion(block: Block, state: np.ndarray, settings: Cylinder3DSettings | None = None,
                **overrides: Any) -> RockingResult:
    """The cylinder ``block`` moving freely on a still floor from the 13-float kernel ``state`` (as
    :func:`tilted_state` makes) for ``end_time`` (s, required)."""
    settings = make_settings(Cylinder3DSettings, settings, overrides)
    if settings.end_time is None:
        raise InputError("free_motion needs end_time (s), got None", argument="end_time")
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    check_model(SOLVER_NAME, block, None)
    cylinder_properties(block)
    return _CylinderRun(block, None, settings, np.asarray(state, dtype=float)).run()


def cylinder_block(diameter: float, height: float, **fields: Any) -> Block:
    """A :class:`Block` standing for a cylinder of ``diameter`` and ``height`` (m): width the diameter, and unless
    given, ``cm_height = height / 2`` and a homogeneous solid cylinder's ``radius_of_gyration = sqrt(d²/16 +
    H²/12)`` (m), so that its planar properties (``alpha``, ``R``, ``p``, ``I_O``, ``e_R``) are those of the cylinder
    rocking in a vertical plane through its axis; ``restitution_factor`` 1 (Housner's). Other ``fields`` go to
    :class:`Block`."""
    fields = {**cylinder_mass(diameter, height), "restitution_factor": 1.0, **fields}
    return Block(diameter, height, **fields)


class _CylinderRun(SolverRun):
    """One case through the kernel: from rest under the floor motion, or free from a tilted state."""

    name = SOLVER_NAME

    def __init__(self, block: Block, excitation: PlanMotion | None, settings: Cylinder3DSettings,
                 state0: np.ndarray | None = None) -> None:
        super().__init__(block, excitation, settings)
        self.state0 = state0

    def _run_impl(self) -> RockingResult:
        s, plan = self.settings, self.excitation
        dt_nom = s.dtau / cylinder_properties(self.block).p
        if plan is None:
            state = self.state0 if self.state0 is not None else tilted_state(self.block, s.theta0, s.theta_dot0)
            return _run(self, _free_forcing(s.end_time, dt_nom), state, tail=False)
        forcing = _record_forcing(plan, dt_nom) if isinstance(plan.first, Record) else \
            _pulse_forcing(plan, dt_nom, s.theta_mj)
        return _run(self, forcing, tilted_state(self.block, s.theta0, s.theta_dot0), tail=True)


__all__ = ["SOLVER_NAME", "cylinder_block", "free_motion", "mechanical_energy", "solve", "tilted_state"]
