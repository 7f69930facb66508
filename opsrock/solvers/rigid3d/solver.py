"""One case: :func:`solve` (a floor motion in plan, a pulse or a record along the width, or free motion from a
tilted state)."""

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
from opsrock.solvers.rigid3d import kernel as kn
from opsrock.solvers.rigid3d.model import make_floor, make_model
from opsrock.solvers.rigid3d.settings import Rigid3DSettings
from opsrock.solvers.rigid3d.workspace import flat_slides
from opsrock.solvers.status import REASONS, failure_of

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "rigid3d"
#: The kernel's specialisation for finite friction (and for the rare infinite-friction case that slides flat in the
#: friction's limit, solved again), compiled when a case first needs it (the one for infinite friction, without the
#: flat slide and the coarse slide, is the kernel's first; :func:`_call_kernel`): its name in the compile notice
#: (:data:`opsrock.solvers._compile.COMPILE_PART_CPU_S`).
FINITE_FRICTION = "finite-friction"


@dataclass(frozen=True)
class BoxProperties:
    """A block's three-dimensional mass properties, per unit mass, as the kernel takes them.

    Parameters
    ----------
    inertia : tuple of float
        ``(I_x, I_y, I_z) / m`` about the centre of mass, body axes (m²).
    weak_y : bool
        True if the depth is the weaker axis (``alpha_depth < alpha``).
    alpha : float
        Slenderness of the weaker axis, ``atan(min(b, d) / h)`` (rad).
    R : float
        Pivot-to-centre-of-mass distance in the weaker axis's plane (m).
    p : float
        Frequency parameter of rocking in the weaker axis's plane, ``sqrt(g R / (r² + R²))`` (rad/s).
    """

    inertia: tuple[float, float, float]
    weak_y: bool
    alpha: float
    R: float  # noqa: N815  (the paper's symbol)
    p: float


def box_properties(block: Block) -> BoxProperties:
    """The block's inertia and weaker axis (docs/guide/three-dimensions.md, the model).

    A homogeneous box about its centre of mass: ``I_x = m (depth² + height²) / 12``, ``I_y = m (width² + height²)
    / 12``, ``I_z = m (width² + depth²) / 12``; with ``cm_height`` only, the same formulas about that centre of
    mass. With ``radius_of_gyration`` ``r`` (the radius for rocking along the width): ``I_y = m r²``, ``I_x = m (r²
    + (depth² - width²) / 12)`` (the same vertical part, the horizontal part a homogeneous box's), ``I_z = m
    (width² + depth²) / 12``.

    Raises
    ------
    InputError
        A block without ``depth``, or a ``radius_of_gyration`` that leaves ``I_x <= 0``.
    """
    if block.depth is None:
        raise InputError("solver 'rigid3d' needs the block's depth (Block.depth, m), got depth = None",
                         argument="depth")
    w, dep, hh = block.width, block.depth, block.height
    if block.radius_of_gyration is None:
        ix, iy = (dep**2 + hh**2) / 12.0, (w**2 + hh**2) / 12.0
    else:
        r2 = block.radius_of_gyration**2
        ix, iy = r2 + (dep**2 - w**2) / 12.0, r2
        if ix <= 0.0:
            raise InputError(f"radius_of_gyration = {block.radius_of_gyration!r} m leaves no inertia across the depth "
                             f"(r² + (depth² - width²)/12 <= 0)", argument="radius_of_gyration")
    iz = (w**2 + dep**2) / 12.0
    weak_y = block.d < block.b
    half, r2w = (block.d, ix) if weak_y else (block.b, iy)
    R = math.hypot(half, block.h_cm)
    return BoxProperties((ix, iy, iz), weak_y, math.atan2(half, block.h_cm), R, math.sqrt(G * R / (r2w + R * R)))


@dataclass(frozen=True)
class _Forcing:
    """The floor motion in the block frame as the kernel takes it (see :func:`kernel.run`)."""

    form: int
    ax: np.ndarray
    ay: np.ndarray
    av: np.ndarray
    sub: int
    n_exc: int
    tail_av: float
    dt: float
    peak: float  # max |a_h| + max |a_v| (m/s²), for the contact gap


def as_plan(excitation: object) -> PlanMotion:
    """``excitation`` as a :class:`PlanMotion` (a bare pulse or record: along the block's width); refuses what the
    kernel cannot take (anything but analytic pulses and records, a pulse with a record, two records of
    different sample steps)."""
    plan = excitation if isinstance(excitation, PlanMotion) else None
    if plan is None:
        if not isinstance(excitation, (Pulse, Record)):
            raise InputTypeError(f"solver 'rigid3d' solves analytic pulses (Pulse), records (Record) and PlanMotion "
                                 f"of them, got {type(excitation).__name__}")
        return PlanMotion(excitation)
    parts = [plan.first] + ([] if plan.second is None else [plan.second])
    if not (all(isinstance(p, Pulse) for p in parts) or all(isinstance(p, Record) for p in parts)):
        raise InputTypeError("solver 'rigid3d' takes a PlanMotion of two pulses or of two records, got "
                             f"{' and '.join(type(p).__name__ for p in parts)}")
    if len(parts) == 2 and isinstance(plan.first, Record) and not math.isclose(plan.first.dt, plan.second.dt,
                                                                                 rel_tol=1e-12):
        raise InputError(f"second must share the first record's sample step dt = {plan.first.dt!r} s, got "
                         f"{plan.second.dt!r} s", argument="second")
    return plan


def _pulse_forcing(plan: PlanMotion, dt_nom: float, theta_mj: float) -> _Forcing:
    """Pulses sampled exactly at every step's evaluation time; a whole number of steps in the longer pulse."""
    n = max(1, math.ceil(plan.duration / dt_nom))
    dt = plan.duration / n
    t = (np.arange(n) + theta_mj) * dt
    ax, ay = (np.ascontiguousarray(a, dtype=float) for a in plan.components(t))
    vertical = float(plan.first.vertical)
    av = np.full(n, vertical)
    return _Forcing(kn.FORCING_STEPWISE, ax, ay, av, 1, n, vertical, dt,
                    float(np.max(np.hypot(ax, ay))) + abs(vertical))


def _padded(values: np.ndarray | None, n: int, *, copy: bool = True) -> np.ndarray:
    """``values`` (None: none) followed by zeros up to ``n`` samples, a new array; with ``copy=False``, the array
    itself when it has ``n`` already (read-only, as a record's are: only for what the kernel does not take; a record
    pair's components have one length, and the copies cost about 10 µs a component, issue 43)."""
    if not copy and values is not None and values.size == n:
        return values
    out = np.zeros(n)
    if values is not None:
        out[:values.size] = values
    return out


def _record_forcing(plan: PlanMotion, dt_nom: float) -> _Forcing:
    """The records' samples rotated into the block frame, ``sub`` steps per sample interval."""
    rec = plan.first
    sub = max(1, math.ceil(rec.dt / dt_nom))
    n_samples = max(rec.values.size, 0 if plan.second is None else plan.second.values.size)
    a1 = _padded(rec.values, n_samples, copy=False)
    a2 = _padded(None if plan.second is None else plan.second.values, n_samples, copy=False)
    av = _padded(rec.vertical, n_samples)
    c, s = math.cos(math.radians(plan.azimuth)), math.sin(math.radians(plan.azimuth))
    ax, ay = c * a1 + s * a2, -s * a1 + c * a2
    n = (n_samples - 1) * sub
    return _Forcing(kn.FORCING_LINEAR, ax, ay, av, sub, n, 0.0, rec.dt / sub,
                    float(np.max(np.hypot(ax, ay))) + float(np.max(np.abs(av))))


def _free_forcing(duration: float, dt_nom: float) -> _Forcing:
    """No floor motion for ``duration`` (s)."""
    n = max(1, math.ceil(duration / dt_nom))
    z = np.zeros(n)
    return _Forcing(kn.FORCING_STEPWISE, z, z.copy(), z.copy(), 1, n, 0.0, duration / n, 0.0)


def tilted_state(block: Block, theta: float, theta_dot: float = 0.0) -> np.ndarray:
    """The kernel's 13-float state of the block tilted by ``theta`` (rad) in the ``x-z`` plane (rocking along its
    width, positive: the centre of mass towards ``+x``) on its stuck edge ``x = sgn(theta) b`` with angular
    velocity ``theta_dot`` (rad/s): ``(X, q, V, omega)``, the rotation about ``+y``."""
    c = 1.0 if theta >= 0.0 else -1.0
    b, h = block.b, block.h_cm
    x = c * b * (1.0 - math.cos(theta)) + h * math.sin(theta)
    z = c * b * math.sin(theta) + h * math.cos(theta)
    rx, rz = x - c * b, z  # from the pivot edge to the centre of mass
    return np.array([x, 0.0, z, math.cos(0.5 * theta), 0.0, math.sin(0.5 * theta), 0.0,
                     theta_dot * rz, 0.0, -theta_dot * rx, 0.0, theta_dot, 0.0])


def _run(run: _Rigid3DRun, forcing: _Forcing, state: np.ndarray, tail: bool) -> RockingResult:
    """Run the kernel on one case and build the result."""
    block, settings, box = run.block, run.settings, run.box
    model = make_model(block, box, settings, forcing.dt, forcing.peak, tail)
    floor = make_floor(forcing.form, forcing.ax, forcing.ay, forcing.av, forcing.sub, forcing.n_exc, forcing.tail_av)
    every, max_tail = model.numerics.hist_every, model.limits.max_tail
    cap = min(forcing.n_exc + max(max_tail, 0), settings.step_limit) // every + 3 if settings.record else 0
    # a row per quantity (each then copied out whole; a column per quantity, copied out strided, cost about 0.3 ms
    # a case, issue 43); the kernel writes the samples it returns (zeroing them cost about 2 ms a case)
    hist = np.empty((kn.H_SIZE, cap))
    out = np.zeros(kn.OUT_SIZE)
    record = {"solver": SOLVER_NAME, **settings_record(settings), "dt": forcing.dt}
    try:
        flat = flat_slides(model.friction)
        _call_kernel(run, (model, floor, state.copy(), hist, out, flat))
        if flat is None and out[kn.OUT_NEEDS_FLAT]:  # slid flat (friction's limit): the case again, with the paths
            _call_kernel(run, (model, floor, state.copy(), hist, out, True))
    except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
        return failed_result(SOLVER_NAME, record, box.alpha, f"{type(exc).__name__}: {exc}",
                             wall_time_s=run.elapsed())
    return _result(run, box, out, hist[:, :int(out[kn.OUT_N_HIST])], record, state)


def _call_kernel(run: _Rigid3DRun, args: tuple) -> None:
    """``kernel.run(*args)`` in the specialisation ``args`` call for (their last, ``flat``). numba compiles the kernel
    once for ``flat`` None (infinite friction: neither the closed-form flat slide nor the coarse slide of a block
    sliding flat) and once for ``flat`` True (finite friction, and the rare infinite-friction case the first marks
    as sliding flat, ``OUT_NEEDS_FLAT``, solved again from its start), each when a case first needs it (issue 43)."""
    part = None if args[-1] is None else FINITE_FRICTION
    announce_compile(kn.run, SOLVER_NAME, part, args)
    run.compiled_call(kn.run, *args, variant="infinite friction" if part is None else FINITE_FRICTION)


def _samples(hist: np.ndarray, first: int, count: int) -> np.ndarray:
    """Rows ``first`` to ``first + count - 1`` of the kernel's history (a row per quantity) as an array of a row per
    sample, ``count`` columns (C order; copied column by column, each a contiguous read: the transposed copy took
    several times longer)."""
    out = np.empty((hist.shape[1], count))
    for c in range(count):
        out[:, c] = hist[first + c]
    return out


def _mechanical(block: Block, box: BoxProperties, state: np.ndarray) -> tuple[float, float]:
    """Kinetic and potential energy (J) of a kernel state; ``PE = m g (z - h)``."""
    w, x, y, z = (float(v) for v in state[3:7])
    Q = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    om = Q.T @ state[10:13]  # body frame
    m = block.mass
    kinetic = 0.5 * m * (float(state[7:10] @ state[7:10]) + float(np.dot(box.inertia, om * om)))
    return kinetic, m * G * (float(state[2]) - block.h_cm)


def _energy(block: Block, box: BoxProperties, out: np.ndarray, state0: np.ndarray) -> dict[str, float]:
    """The run's energy balance in J (for the block's mass), from the kernel's per-unit-mass sums."""
    kinetic, potential = _mechanical(block, box, out[kn.OUT_STATE:kn.OUT_STATE + 13])
    initial = sum(_mechanical(block, box, state0))
    work, fric, imp = (block.mass * out[i] for i in (kn.OUT_INPUT_WORK, kn.OUT_FRICTION_WORK, kn.OUT_IMPACT_LOSS))
    return {"input_work": float(work), "kinetic": kinetic, "potential": potential, "friction_work": float(fric),
            "impact_loss": float(imp), "initial": initial,
            "residual": float(work + initial - kinetic - potential - fric - imp)}


def _diagnostics(out: np.ndarray) -> dict[str, Any]:
    """The kernel's bookkeeping, JSON-serialisable."""
    steps = max(1.0, out[kn.OUT_CONTACT_STEPS])
    return {"end_time": float(out[kn.OUT_TIME]), "max_penetration": float(out[kn.OUT_MAX_PENETRATION]),
            "contact_steps": int(out[kn.OUT_CONTACT_STEPS]), "rest_skip_steps": int(out[kn.OUT_REST_STEPS]),
            "stick_steps": int(out[kn.OUT_STICK_STEPS]), "flat_slide_steps": int(out[kn.OUT_SLIDE_STEPS]),
            "nsgs_unconverged_steps": int(out[kn.OUT_NSGS_FAILED]),
            "nsgs_mean_sweeps": float(out[kn.OUT_NSGS_SWEEPS] / steps), "nsgs_max_sweeps": int(out[kn.OUT_NSGS_MAX]),
            "limit_solves": int(out[kn.OUT_LIMIT_STEPS]), "smooth_steps": int(out[kn.OUT_SMOOTH_STEPS]),
            "smooth_span_steps": int(out[kn.OUT_SMOOTH_SPAN]), "smooth_tried": int(out[kn.OUT_SMOOTH_TRIED]),
            "peak_stop": bool(out[kn.OUT_PEAK_STOP] > 0.5), "nsgs_loose_steps": int(out[kn.OUT_NSGS_LOOSE]),
            "nsgs_extra_sweeps": int(out[kn.OUT_NSGS_EXTRA]), "coarse_slide_steps": int(out[kn.OUT_COARSE_STEPS]),
            "coarse_slide_span_steps": int(out[kn.OUT_COARSE_SPAN]), "edge_slip_steps": int(out[kn.OUT_EDGE_SLIP]),
            "slip_smooth_steps": int(out[kn.OUT_SLIP_STEPS]), "slip_smooth_span_steps": int(out[kn.OUT_SLIP_SPAN]),
            "slip_smooth_tried": int(out[kn.OUT_SLIP_TRIED]), "settled": int(out[kn.OUT_SETTLED]),
            "settle_gap_max": float(out[kn.OUT_SETTLE_GAP])}


def _result(run: SolverRun, box: BoxProperties, out: np.ndarray, hist: np.ndarray, record: dict[str, Any],
            state0: np.ndarray) -> RockingResult:
    """The :class:`RockingResult` of a finished kernel run."""
    block = run.block
    time_s, theta, theta_dot = (hist[c].copy() for c in (kn.H_T, kn.H_THETA, kn.H_THETA_DOT))
    axis = 1 if box.weak_y else 0
    slide = hist[kn.H_SLIDE + axis].copy()
    status, steps = int(out[kn.OUT_STATUS]), int(out[kn.OUT_STEPS])
    diagnostics = _diagnostics(out)
    if status != kn.STATUS_OK:
        reason = REASONS[status]
        if status == kn.STATUS_CONTACT:
            reason += (f": the NSGS contact solver did not converge in {run.settings.nsgs_fail_steps} consecutive "
                       f"steps (t = {out[kn.OUT_TIME]:.6g} s)")
        failed = failed_result(SOLVER_NAME, record, box.alpha, reason, time=time_s, theta=theta,
                               theta_dot=theta_dot, n_steps=steps, wall_time_s=run.elapsed(),
                               failure=failure_of(status))
        return replace(failed, slide=slide, diagnostics=diagnostics)
    fin = out[kn.OUT_STATE:kn.OUT_STATE + 13]
    w, x, y, z = fin[3:7]
    h = block.h_cm
    residual = (float(fin[0] - 2 * h * (x * z + w * y)), float(fin[1] - 2 * h * (y * z - w * x)))
    energy = _energy(block, box, out, state0)
    kind = int(out[kn.OUT_OVER_KIND])
    overturned = bool(out[kn.OUT_OVERTURNED])
    plan = PlanSummary(
        tilt_max=float(out[kn.OUT_THETA_MAX]), twist_max=float(out[kn.OUT_TWIST_MAX]),
        slide_max=float(out[kn.OUT_SLIDE_MAX]), slide_residual=residual,
        overturned_over=("edge" if kind == 1 else "corner") if overturned else "",
        overturn_direction=math.degrees(out[kn.OUT_OVER_DIR]) if overturned else math.nan,
        time_edge=float(out[kn.OUT_TIME_EDGE]), time_corner=float(out[kn.OUT_TIME_CORNER]),
        time_sliding=float(out[kn.OUT_TIME_SLIDING]), time_flight=float(out[kn.OUT_TIME_FLIGHT]), energy=energy)
    first = int(out[kn.OUT_FIRST_MODE])
    contact = ContactSummary(
        first_mode=MODES[first] if first >= 0 else "rest", time_sliding=plan.time_sliding,
        time_rocking=float(out[kn.OUT_TIME_ROCKING]), slide_max=plan.slide_max, slide_residual=residual[axis],
        time_flight=plan.time_flight, energy=energy)
    history = None
    if run.settings.record:
        history = PlanHistory(rotation=_samples(hist, kn.H_ROT, 3), position=_samples(hist, kn.H_POS, 3),
                              twist=hist[kn.H_TWIST].copy(), slide=_samples(hist, kn.H_SLIDE, 2),
                              corners_down=hist[kn.H_DOWN].astype(int))
    theta_max = float(out[kn.OUT_THETA_MAX])
    return RockingResult(
        solver=SOLVER_NAME, settings=record, alpha=box.alpha, time=time_s, theta=theta, theta_dot=theta_dot,
        theta_max=theta_max, overturned=theta_max >= OVERTURNING_ANGLE, rocked=bool(out[kn.OUT_ROCKED]),
        n_steps=steps, wall_time_s=run.elapsed(), n_impacts=int(out[kn.OUT_IMPACTS]), diagnostics=diagnostics,
        slide=slide, contact=contact, plan=plan, plan_history=history)


def solve(block: Block, excitation: PlanMotion | Pulse | Record | None, settings: Rigid3DSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Response of a box on a floor with Coulomb friction to a floor motion in plan (two horizontal components
    and a vertical one), by Moreau-Jean time stepping with NSGS (module docstring).

    Parameters
    ----------
    block : Block
        The block, with its ``depth`` (m); ``friction`` (static ``mu``; None: infinite, no corner slips) and
        ``friction_kinetic`` (``mu_k``, used while a corner slips); ``cm_height`` and ``radius_of_gyration``
        (:func:`box_properties`). Its impact law must be Housner's (``restitution_factor = 1``, no
        ``restitution``): ``e_n = 0`` at the corners gives ``e_H`` in planar rocking and nothing else.
    excitation : PlanMotion or Pulse or Record or None
        The floor motion in plan (two pulses or two records of one sample step; the vertical is the first
        component's); a bare pulse or record acts along the block's width. None: a still floor for ``end_time``
        (required; no tail) from the block tilted by ``theta0`` (rad) in its ``x-z`` plane with ``theta_dot0``
        (rad/s) on its stuck edge (:func:`tilted_state`).
    settings : Rigid3DSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields.

    Returns
    -------
    RockingResult
        ``theta`` the tilt (rad), signed by the lean along the weaker axis (positive: the centre of mass towards
        ``+x``, or ``+y`` if the depth is the weaker axis), ``theta_dot`` the angular velocity about that axis's
        horizontal normal (rad/s; the planar solvers' ``theta'`` in planar motion), ``alpha`` the weaker axis's
        slenderness, ``theta_max`` the peak tilt, ``overturned`` (tilt reached pi/2), ``rocked`` (tilt above
        ``rocked_theta``), ``n_impacts`` (steps in which a corner that was up landed), ``slide`` (base centre's
        displacement along the weaker axis, m), ``contact`` (:class:`~opsrock.result.ContactSummary`, slides along
        the weaker axis), ``plan`` (:class:`~opsrock.result.PlanSummary`) and ``plan_history``
        (:class:`~opsrock.result.PlanHistory`, with ``record``). A run that did not finish is failed with its
        reason (non-finite state or floor motion, ``max_steps``, still moving at the end of the tail, the contact
        solver unconverged for ``nsgs_fail_steps`` steps in a row). ``diagnostics``: ``end_time`` (s),
        ``max_penetration`` (m), ``contact_steps`` (of which ``stick_steps``, ``flat_slide_steps`` and ``edge_slip_steps``
        were solved in closed form, the rest by NSGS), ``rest_skip_steps``, ``nsgs_unconverged_steps``,
        ``nsgs_mean_sweeps``, ``nsgs_max_sweeps``, ``limit_solves`` (local solves where sticking with infinite
        friction needed a pulling impulse: solved by the infinite-friction limit of slip).

    Raises
    ------
    InputError
        A block without depth, a restitution other than Housner's, a settings value out of range, two records
        of different sample steps.
    InputTypeError
        A block that is not a :class:`Block`, or an excitation other than pulses and records.
    """
    settings = make_settings(Rigid3DSettings, settings, overrides)
    block = check_inputs(SOLVER_NAME, block, excitation, settings)
    box = box_properties(block)
    if (excitation is None) != (settings.end_time is not None):
        raise ModelNotSupported(f"solver {SOLVER_NAME!r} takes end_time (the span of free motion) with "
                                f"excitation None and only then, got end_time = {settings.end_time!r}")
    plan = None if excitation is None else as_plan(excitation)
    return _Rigid3DRun(block, plan, settings, box).run()


class _Rigid3DRun(SolverRun):
    """One case through the kernel: from rest under the floor motion, or free from a tilted state; ``box`` the
    block's :func:`box_properties`, worked out once."""

    name = SOLVER_NAME

    def __init__(self, block: Block, excitation: PlanMotion | None, settings: Rigid3DSettings,
                 box: BoxProperties) -> None:
        super().__init__(block, excitation, settings)
        self.box = box

    def _run_impl(self) -> RockingResult:
        s, plan = self.settings, self.excitation
        dt_nom = s.dtau / self.box.p
        if plan is None:
            return _run(self, _free_forcing(s.end_time, dt_nom), tilted_state(self.block, s.theta0, s.theta_dot0),
                        tail=False)
        forcing = _record_forcing(plan, dt_nom) if isinstance(plan.first, Record) else \
            _pulse_forcing(plan, dt_nom, s.theta_mj)
        return _run(self, forcing, tilted_state(self.block, s.theta0, s.theta_dot0), tail=True)


def warm_up_paths() -> None:
    """Make the kernel's specialisation for infinite friction ready too, by one short solve of a block with infinite
    friction (that of :func:`opsrock.solvers.warm_up`, a block on a slipping base, compiles the one for finite
    friction): :func:`opsrock.solvers.warm_up` calls it after its own solve, so that no case of a campaign pays for
    either."""
    from opsrock.excitations.pulses import OneSinePulse

    block = Block(0.3, 1.2, restitution_factor=1.0, depth=0.6)
    solve(block, PlanMotion.along(OneSinePulse.from_ratios(Block(0.3, 1.2, restitution_factor=1.0), 1.35, 3.0), 30.0))


__all__ = ["FINITE_FRICTION", "SOLVER_NAME", "BoxProperties", "as_plan", "box_properties", "solve", "tilted_state",
           "warm_up_paths"]
