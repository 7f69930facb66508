"""One case: :func:`solve` (a pulse, a record, or free motion from a rotated state)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE, G
from opsrock.errors import InputTypeError, ModelNotSupported
from opsrock.excitations import Pulse, Record
from opsrock.result import MODES, ContactSummary, RockingResult, failed_result
from opsrock.solvers._compile import announce_compile
from opsrock.solvers.common import SolverRun, check_inputs, inertia_ratio, make_settings, settings_record
from opsrock.solvers.moreau_jean import kernel as kn
from opsrock.solvers.moreau_jean.settings import DEFAULT_TAIL_DTAU, MoreauJeanSettings
from opsrock.solvers.status import REASONS, failure_of

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "moreau_jean"


@dataclass(frozen=True)
class _Forcing:
    """The floor motion as the kernel takes it (see :func:`kernel.run`)."""

    form: int
    ah: np.ndarray
    av: np.ndarray
    sub: int
    n_exc: int
    tail_av: float
    dt: float
    peak: float  # max |a_h| + max |a_v| (m/s²), for the contact gap


def _refuse_excitation(excitation: object) -> None:
    """Refuse what the kernel cannot take: anything but an analytic :class:`Pulse` or a :class:`Record`."""
    if not isinstance(excitation, (Pulse, Record)):
        raise InputTypeError(f"solver 'moreau_jean' solves analytic pulses (Pulse) and records (Record), got "
                             f"{type(excitation).__name__}")


def _pulse_forcing(pulse: Pulse, dt_nom: float, theta_mj: float) -> _Forcing:
    """The pulse sampled exactly at every step's evaluation time; a whole number of steps in the pulse."""
    n = max(1, math.ceil(pulse.duration / dt_nom))
    dt = pulse.duration / n
    t = (np.arange(n) + theta_mj) * dt
    ah = np.ascontiguousarray(pulse.acceleration(t), dtype=float)
    av = np.full(n, float(pulse.vertical))
    return _Forcing(kn.FORCING_STEPWISE, ah, av, 1, n, float(pulse.vertical), dt,
                    float(np.max(np.abs(ah))) + abs(float(pulse.vertical)))


def _record_forcing(record: Record, dt_nom: float) -> _Forcing:
    """The record's samples, ``sub`` steps per sample interval (no step straddles a sample)."""
    sub = max(1, math.ceil(record.dt / dt_nom))
    # writable copies: the record's arrays are read-only, which numba would compile a second kernel for
    ah = np.array(record.values, dtype=float)
    av = np.zeros_like(ah) if record.vertical is None else np.array(record.vertical, dtype=float)
    n = (ah.size - 1) * sub
    return _Forcing(kn.FORCING_LINEAR, ah, av, sub, n, 0.0, record.dt / sub,
                    float(np.max(np.abs(ah))) + float(np.max(np.abs(av))))


def _free_forcing(duration: float, dt_nom: float) -> _Forcing:
    """No floor motion for ``duration`` (s)."""
    n = max(1, math.ceil(duration / dt_nom))
    z = np.zeros(n)
    return _Forcing(kn.FORCING_STEPWISE, z, z.copy(), 1, n, 0.0, duration / n, 0.0)


def _run(run: SolverRun, forcing: _Forcing, state: np.ndarray, tail: bool) -> RockingResult:
    """Run the kernel on one case and build the result."""
    block, settings = run.block, run.settings
    p, R, dt = block.p, block.R, forcing.dt
    mu_inf = block.friction is None
    fric = kn.friction(0.0 if mu_inf else block.friction, 0.0 if mu_inf else block.friction_kinetic, mu_inf)
    num = kn.numerics(dt, settings.theta_mj, settings.local_tol, settings.rocked_theta)
    tail_dtau = DEFAULT_TAIL_DTAU if settings.max_free_time is None else settings.max_free_time * p
    max_tail = math.ceil(tail_dtau / (p * dt)) if tail else -1
    limits = kn.limits(settings.step_limit, max_tail, settings.rest_velocity * p * R,
                       max(1, math.ceil(settings.rest_duration / (p * dt))), settings.velocity_tol * p * R,
                       settings.contact_gap * (G + forcing.peak) * dt * dt)
    every = max(1, round(settings.history_dtau / (p * dt)))
    cap = min(forcing.n_exc + max(max_tail, 0), settings.step_limit) // every + 3 if settings.record else 0
    hist = kn.history(every, cap)
    out = np.zeros(kn.OUT_SIZE)
    record = {"solver": SOLVER_NAME, **settings_record(settings), "dt": dt}
    floor = kn.floor_motion(forcing.form, forcing.ah, forcing.av, forcing.sub, forcing.n_exc, forcing.tail_av)
    announce_compile(kn.run, SOLVER_NAME)
    try:
        run.compiled_call(kn.run, kn.body(block.b, block.h_cm, R, G, inertia_ratio(block)), fric, num, floor,
                          state.copy(), limits, hist, out)
    except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
        return failed_result(SOLVER_NAME, record, block.alpha, f"{type(exc).__name__}: {exc}",
                             wall_time_s=run.elapsed())
    return _result(block, out, hist, record, run.elapsed(), state)


def _mechanical(block: Block, state: np.ndarray) -> tuple[float, float]:
    """Kinetic and potential energy (J) of ``state = (x, y, theta, x', y', theta')``; ``PE = m g (y - h)``."""
    _, y, _, vx, vy, vt = (float(v) for v in state)
    m = block.mass
    return 0.5 * m * (vx * vx + vy * vy + block.R ** 2 / inertia_ratio(block) * vt * vt), m * G * (y - block.h_cm)


def _energy(block: Block, out: np.ndarray, state0: np.ndarray) -> dict[str, float]:
    """The run's energy balance in J (for the block's mass), from the kernel's per-unit-mass sums;
    ``initial`` is the mechanical energy at the start (0 from rest)."""
    kinetic, potential = _mechanical(block, out[kn.OUT_X:kn.OUT_X + 6])
    initial = sum(_mechanical(block, state0))
    work, fric, imp = (block.mass * out[i] for i in (kn.OUT_INPUT_WORK, kn.OUT_FRICTION_WORK, kn.OUT_IMPACT_LOSS))
    return {"input_work": float(work), "kinetic": kinetic, "potential": potential, "friction_work": float(fric),
            "impact_loss": float(imp), "initial": initial,
            "residual": float(work + initial - kinetic - potential - fric - imp)}


def _result(block: Block, out: np.ndarray, hist: kn.History, record: dict[str, Any],
            wall: float, state0: np.ndarray) -> RockingResult:
    """The :class:`RockingResult` of a finished kernel run."""
    n = int(out[kn.OUT_N_HIST])
    time_s, theta, theta_dot, slide = (a[:n].copy() for a in (hist.t, hist.theta, hist.theta_dot, hist.slide))
    status = int(out[kn.OUT_STATUS])
    steps = int(out[kn.OUT_STEPS])
    diagnostics = {"end_time": float(out[kn.OUT_TIME]), "max_penetration": float(out[kn.OUT_MAX_PENETRATION]),
                   "flicker_steps": int(out[kn.OUT_FLICKER_STEPS]),
                   "max_flicker_gap": float(out[kn.OUT_MAX_FLICKER_GAP]), "limit_steps": int(out[kn.OUT_LIMIT_STEPS])}
    if status != kn.STATUS_OK:
        failed = failed_result(SOLVER_NAME, record, block.alpha, REASONS[status], time=time_s,
                               theta=theta, theta_dot=theta_dot, n_steps=steps, wall_time_s=wall,
                               failure=failure_of(status))
        return replace(failed, slide=slide, diagnostics=diagnostics)
    first = int(out[kn.OUT_FIRST_MODE])
    contact = ContactSummary(
        first_mode=MODES[first] if first >= 0 else "rest", time_sliding=float(out[kn.OUT_TIME_SLIDING]),
        time_rocking=float(out[kn.OUT_TIME_ROCKING]), slide_max=float(out[kn.OUT_SLIDE_MAX]),
        slide_residual=float(kn._slide_of(block.b, block.h_cm, out[kn.OUT_X], out[kn.OUT_X + 2])),
        time_flight=float(out[kn.OUT_TIME_FLIGHT]), energy=_energy(block, out, state0),
        slip_velocity_end=float(out[kn.OUT_SLIP_END]))
    theta_max = float(out[kn.OUT_THETA_MAX])
    return RockingResult(
        solver=SOLVER_NAME, settings=record, alpha=block.alpha, time=time_s, theta=theta, theta_dot=theta_dot,
        theta_max=theta_max, overturned=theta_max >= OVERTURNING_ANGLE, rocked=bool(out[kn.OUT_ROCKED]),
        n_steps=steps, wall_time_s=wall, n_impacts=int(out[kn.OUT_IMPACTS]), diagnostics=diagnostics,
        slide=slide, contact=contact)


def solve(block: Block, excitation: Pulse | Record | None, settings: MoreauJeanSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Response of a block on a floor with Coulomb friction, initially at rest, to a floor motion with
    horizontal and vertical components, by Moreau-Jean time stepping.

    Parameters
    ----------
    block : Block
        The block; ``friction`` (static ``mu``, None: infinite, the base never slips) and
        ``friction_kinetic`` (``mu_k <= mu``, used while a corner slips). Its impact law must be
        Housner's: ``restitution_factor = 1`` and no ``restitution`` (Moreau-Jean with ``e_n = 0`` at the
        corners gives exactly ``e_H``, and no impulses at the corners can give less).
    excitation : Pulse or Record or None
        Any analytic pulse (its constant ``vertical`` acts during the pulse and after it) or a record
        (its ``vertical`` samples, if any; nothing after its last sample). None: a still floor for
        ``end_time`` (required; no tail), from rocking at ``theta0`` (rad) with ``theta_dot0`` (rad/s) on
        the stuck corner ``sgn(theta0)`` (:func:`rocking_state`): used to check the impact law against
        closed forms (Housner's ``e_H``, the slipping impact).
    settings : MoreauJeanSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields.

    Returns
    -------
    RockingResult
        Histories every ``history_dtau`` (time s, theta rad, theta_dot rad/s, slide m) over the
        excitation and the tail to rest; ``theta_max``, ``overturned``, ``rocked`` (``|theta|`` ever
        above ``rocked_theta``), ``n_impacts`` (closings of a corner on the floor after it had left
        it, counted once per step), and ``contact`` (:class:`~opsrock.result.ContactSummary`). A run that
        did not finish (non-finite state, ``max_steps``, still moving at ``max_tail``, a contact problem
        without solution) is failed, with its reason. ``diagnostics``: ``end_time`` (s), ``max_penetration``
        (m, deepest corner below the floor at the end of a step with a normal impulse; an impact sinks
        the corner by up to its approach velocity times ``dt``), ``flicker_steps`` and ``max_flicker_gap``
        (m) (free steps of a pivot that stays down, see ``contact_gap``), ``limit_steps`` (steps solved with
        the infinite-friction limit ``P_N = 0``, :func:`kernel._local`).

    Raises
    ------
    InputError
        A block whose restitution is not Housner's, or a settings value out of range.
    InputTypeError
        A block that is not a :class:`Block`, or an excitation that is neither a pulse nor a record.
    """
    settings = make_settings(MoreauJeanSettings, settings, overrides)
    block = check_inputs(SOLVER_NAME, block, excitation, settings)
    if (excitation is None) != (settings.end_time is not None):
        raise ModelNotSupported(f"solver {SOLVER_NAME!r} takes end_time (the span of free motion) with "
                                f"excitation None and only then, got end_time = {settings.end_time!r}")
    if excitation is not None:
        _refuse_excitation(excitation)
    return _MoreauJeanRun(block, excitation, settings).run()


class _MoreauJeanRun(SolverRun):
    """One case through the kernel: from rest under the floor motion, or free from a start state."""

    name = SOLVER_NAME

    def _run_impl(self) -> RockingResult:
        block, s, excitation = self.block, self.settings, self.excitation
        dt_nom = s.dtau / block.p
        if excitation is None:
            forcing = _free_forcing(s.end_time, dt_nom)
            return _run(self, forcing, rocking_state(block, s.theta0, s.theta_dot0), tail=False)
        if isinstance(excitation, Record):
            forcing = _record_forcing(excitation, dt_nom)
        else:
            forcing = _pulse_forcing(excitation, dt_nom, s.theta_mj)
        # from rest: theta = 0 gives (0, h, 0, 0, 0, 0) exactly
        return _run(self, forcing, rocking_state(block, s.theta0, s.theta_dot0), tail=True)


def rocking_state(block: Block, theta: float, theta_dot: float = 0.0) -> np.ndarray:
    """``(x, y, theta, x', y', theta')`` of the block rocking on corner ``sgn(theta)`` (stuck, on the floor)
    with rotation ``theta`` (rad) and angular velocity ``theta_dot`` (rad/s); the pivot is where it
    was at rest, so the slide is zero."""
    c = 1.0 if theta >= 0.0 else -1.0
    phi = c * block.alpha - theta
    x = c * block.b * (1.0 - math.cos(theta)) + block.h_cm * math.sin(theta)
    y = c * block.b * math.sin(theta) + block.h_cm * math.cos(theta)
    return np.array([x, y, theta, block.R * math.cos(phi) * theta_dot, block.R * math.sin(phi) * theta_dot,
                     theta_dot])


__all__ = ["SOLVER_NAME", "rocking_state", "solve"]
