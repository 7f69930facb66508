"""One case with its history: :func:`solve` (a pulse, a record, or free motion on a still floor)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputTypeError, ModelNotSupported
from opsrock.excitations import Pulse, Record
from opsrock.excitations.records import check_sampling
from opsrock.excitations.vertical import check_free_fall
from opsrock.result import MODES, ContactSummary, RockingResult, failed_result
from opsrock.solvers._compile import announce_compile
from opsrock.solvers.common import SolverRun, check_inputs, inertia_ratio, make_settings, settings_record
from opsrock.solvers.forcing import FORM_LINEAR, PULSE_IDS, pulse_forcing
from opsrock.solvers.friction import kernel as K
from opsrock.solvers.friction.settings import DEFAULT_TAIL_DTAU, FrictionSettings
from opsrock.solvers.status import REASONS, failure_of

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "friction"
#: The part of the kernel compiled only when a block first leaves the floor
#: (:data:`opsrock.solvers._compile.COMPILE_PART_CPU_S`).
FLIGHT_PART = "flight"

#: History slots reserved beyond the nominal steps of the excitation (impacts, events and the
#: motion after the excitation); a history that fills up stops being recorded, the solution itself
#: is unaffected.
_HISTORY_EXTRA = 50_000


def block_parameters(block: Block) -> tuple[float, float, float, float]:
    """``(alpha, e / e_H, mu, mu_k)`` of ``block`` as the kernel takes them (``inf``: no slip). A block that lands
    flat (``e_H <= 0``, :attr:`Block.lands_flat`) gets the factor 1: the kernel's impact law itself then lands it
    flat (its rigid stick impulse would drive the old pivot into the floor), ``e = 0``; such a block with a
    ``restitution`` of its own is refused before (:func:`opsrock.solvers.registry.check_model`)."""
    mu = math.inf if block.friction is None else block.friction
    mu_k = math.inf if block.friction_kinetic is None else block.friction_kinetic
    return block.alpha, 1.0 if block.lands_flat else block.e / block.e_R, mu, mu_k


def excitation_parameters(block: Block, excitation: Pulse | Record | None, settings: FrictionSettings,
                          params: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Write the forcing slots of ``params`` (``P_FORM`` ... ``P_H_NOM``) for ``excitation`` in the time
    scale of ``block``; return the samples ``(kvals, gvals)`` (``a_h/g``, ``1 + a_v/g``; empty for a pulse).
    ``excitation=None``: a still floor for ``end_time`` (None: one sample interval of ``0.1/p``)."""
    p = block.p
    if excitation is None:
        duration = settings.end_time if settings.end_time is not None else 0.1 / p
        n = max(2, math.ceil(duration * p / 0.1) + 1)
        excitation = Record(dt=duration / (n - 1), values=np.zeros(n), name="no motion")
    if isinstance(excitation, Record):
        check_sampling(excitation, block)
        check_free_fall(excitation)
        kvals, dtau = excitation.values / G, excitation.dt * p
        gvals = np.zeros(0) if excitation.vertical is None else 1.0 + excitation.vertical / G
        forcing = (FORM_LINEAR, 0.0, 0.0, 0.0, excitation.duration * p, 1.0, 1.0, dtau, min(settings.max_dtau, dtau))
    elif isinstance(excitation, Pulse) and excitation.shape in PULSE_IDS:
        nu = excitation.omega_p / p
        # the plain Python of the compiled function (numba's documented ``py_func``), the same IEEE operations: called
        # once a case, compiling it cost a first solve about 0.4 s of CPU (issue 43)
        form, k, nu_, phase, tau_end, kvals, dtau = pulse_forcing.py_func(PULSE_IDS[excitation.shape],
                                                                           excitation.pfa / G, nu)
        g = 1.0 + excitation.vertical / G
        gvals = np.zeros(0)
        forcing = (form, k, nu_, phase, tau_end, g, g, dtau, min(settings.max_dtau, 2.0 * math.pi / nu / settings.steps_per_pulse))
    else:
        raise InputTypeError(f"friction solves the pulses of PULSE_SHAPES and records (Pulse, Record), got "
                             f"{type(excitation).__name__}")
    slots = (K.P_FORM, K.P_K, K.P_NU, K.P_PHASE, K.P_TAU_END, K.P_G_CONST, K.P_G_TAIL, K.P_DTAU, K.P_H_NOM)
    for slot, value in zip(slots, forcing):
        params[slot] = value
    return kvals, gvals


def case_parameters(block: Block, excitation: Pulse | Record | None,
                    settings: FrictionSettings) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The kernel's inputs ``(params, kvals, gvals)`` (slots ``P_*`` of :mod:`.kernel`)."""
    params = np.zeros(K.P_SIZE)
    params[K.P_ALPHA], params[K.P_F_REST], params[K.P_MU_S], params[K.P_MU_K] = block_parameters(block)
    kvals, gvals = excitation_parameters(block, excitation, settings, params)
    tail = DEFAULT_TAIL_DTAU if settings.max_free_time is None else settings.max_free_time * block.p
    params[K.P_H_TAIL], params[K.P_REST_VELOCITY] = settings.max_dtau, settings.rest_velocity
    params[K.P_MAX_IMPACTS], params[K.P_MAX_STEPS], params[K.P_MAX_TAIL] = settings.max_impacts, settings.step_limit, tail
    params[K.P_THETA0], params[K.P_OMEGA0] = settings.theta0, settings.theta_dot0 / block.p
    params[K.P_KAPPA] = inertia_ratio(block)
    return params, kvals, gvals


def _contact(out: np.ndarray, block: Block, tau: np.ndarray) -> ContactSummary:
    """The kernel's summary in SI units."""
    p, R, scale = block.p, block.R, block.mass * G * block.R
    energy = {name: float(out[slot]) * scale for name, slot in (
        ("input_work", K.OUT_INPUT_WORK), ("kinetic", K.OUT_KINETIC), ("potential", K.OUT_POTENTIAL),
        ("friction_work", K.OUT_FRICTION_WORK), ("impact_loss", K.OUT_IMPACT_LOSS), ("initial", K.OUT_ENERGY_START))}
    energy["residual"] = (energy["input_work"] - (energy["kinetic"] + energy["potential"] - energy["initial"])
                          - energy["friction_work"] - energy["impact_loss"])
    return ContactSummary(first_mode=MODES[int(out[K.OUT_FIRST_MODE])], time_sliding=float(out[K.OUT_TIME_SLIDING]) / p,
                          time_rocking=float(out[K.OUT_TIME_ROCKING]) / p, slide_max=float(out[K.OUT_SLIDE_MAX]) * R,
                          slide_residual=float(out[K.OUT_SLIDE_END]) * R,
                          time_flight=float(out[K.OUT_TIME_FLIGHT]) / p, energy=energy,
                          slip_velocity_end=float(out[K.OUT_SLIP_END]) * R * p)


class _FrictionRun(SolverRun):
    """One case through the compiled kernel, with its history."""

    name = SOLVER_NAME

    def _integrate(self, params: np.ndarray, kvals: np.ndarray, gvals: np.ndarray, out: np.ndarray,
                   hist: np.ndarray) -> None:
        """The case through the kernel's two entry points: on the floor (:func:`~.kernel.solve_case`) and, each time
        the block leaves it, in flight (:func:`~.kernel.fly_case`, compiled the first time a block flies)."""
        state = K.state()
        announce_compile(K.solve_case, SOLVER_NAME)
        status = self.compiled_call(K.solve_case, params, kvals, gvals, out, hist, state)
        while status == K.AIRBORNE:
            announce_compile(K.fly_case, SOLVER_NAME, part=FLIGHT_PART)
            if self.compiled_call(K.fly_case, params, kvals, gvals, out, hist, state) != K.LANDED:
                return
            status = K.solve_case(params, kvals, gvals, out, hist, state)

    def _run_impl(self) -> RockingResult:
        block, settings = self.block, self.settings
        settings_dict = {"solver": SOLVER_NAME, **settings_record(settings)}
        alpha = block.alpha
        params, kvals, gvals = case_parameters(block, self.excitation, settings)
        cap = math.ceil(params[K.P_TAU_END] / params[K.P_H_NOM]) + _HISTORY_EXTRA if settings.record else 0
        hist = K.history(cap)
        out = np.zeros(K.OUT_SIZE)
        try:
            self._integrate(params, kvals, gvals, out, hist)
        except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
            return failed_result(SOLVER_NAME, settings_dict, alpha, f"{type(exc).__name__}: {exc}",
                                 wall_time_s=self.elapsed())
        wall = self.elapsed()
        p, nh = block.p, int(out[K.OUT_N_HIST])
        time_s, theta, theta_dot = hist[:nh, K.H_TAU] / p, hist[:nh, K.H_THETA].copy(), hist[:nh, K.H_OMEGA] * p
        status = int(out[K.OUT_STATUS])
        if status != K.STATUS_OK:
            reason = f"{REASONS[status]} (at t = {out[K.OUT_EVENT_TIME] / p:.6g} s)"
            return failed_result(SOLVER_NAME, settings_dict, alpha, reason, time=time_s, theta=theta,
                                 theta_dot=theta_dot, n_steps=int(out[K.OUT_STEPS]), wall_time_s=wall,
                                 failure=failure_of(status))
        return RockingResult(
            solver=SOLVER_NAME, settings=settings_dict, alpha=alpha, time=time_s, theta=theta, theta_dot=theta_dot,
            theta_max=float(out[K.OUT_THETA_MAX]), overturned=bool(out[K.OUT_OVERTURNED]),
            rocked=bool(out[K.OUT_ROCKED]), n_steps=int(out[K.OUT_STEPS]), wall_time_s=wall,
            n_impacts=int(out[K.OUT_IMPACTS]), slide=hist[:nh, K.H_U] * block.R,
            contact=_contact(out, block, time_s))


def solve(block: Block, excitation: Pulse | Record | None, settings: FrictionSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Response of one block on a floor with Coulomb friction under an analytic pulse or a record,
    horizontal and vertical (docs/guide/friction.md), or free motion from a start state.

    Parameters
    ----------
    block : Block
        The block; ``friction`` (static) and ``friction_kinetic`` set the floor's friction (None:
        the base never slips).
    excitation : Pulse or Record or None
        The floor motion: any pulse of :data:`opsrock.excitations.PULSE_SHAPES` (with its constant
        ``vertical`` acceleration), or a record (with its ``vertical`` samples, if any). None: a still
        floor (``g`` only) for ``end_time``, from rocking at ``theta0`` (rad) with ``theta_dot0`` (rad/s)
        on a stuck pivot, followed until the block is at rest.
    settings : FrictionSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields.

    Returns
    -------
    RockingResult
        ``time``/``theta``/``theta_dot``/``slide`` hold the accepted steps and events, during the
        excitation and after it until the block is at rest (s, rad, rad/s, m); ``contact`` the modes,
        sliding and energy balance.
    """
    settings = make_settings(FrictionSettings, settings, overrides)
    block = check_inputs(SOLVER_NAME, block, excitation, settings)
    if excitation is not None and settings.end_time is not None:
        raise ModelNotSupported(f"solver {SOLVER_NAME!r} follows the block to rest after the excitation: "
                                f"end_time = {settings.end_time!r} only with excitation None")
    return _FrictionRun(block, excitation, settings).run()


def warm_up_paths() -> None:
    """Make the kernel's flight path ready too (:func:`~opsrock.solvers.friction.kernel.fly_case`, compiled only when
    a block first leaves the floor), by one short solve of a block the floor throws: it falls at 2 g for 0.1 s.
    :func:`opsrock.solvers.warm_up` calls it after its own solve, so that no case of a campaign pays for it."""
    vertical = np.zeros(50)
    vertical[:10] = -2.0 * G
    solve(Block(0.4, 2.2, friction=0.5), Record(dt=0.01, values=np.zeros(50), vertical=vertical, name="warm-up"))


__all__ = ["SOLVER_NAME", "block_parameters", "case_parameters", "excitation_parameters", "solve", "warm_up_paths"]
