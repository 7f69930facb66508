"""One case with its history: :func:`solve` (a pulse or a record) and :func:`free_rocking`."""

from __future__ import annotations

import math
import time as _time
from dataclasses import asdict
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputError, InputTypeError
from opsrock.excitations import Pulse, Record
from opsrock.excitations.records import check_sampling
from opsrock.limits import initial_state, positive_finite
from opsrock.result import MODES, ContactSummary, RockingResult, failed_result
from opsrock.solvers.common import make_settings
from opsrock.solvers.forcing import FORM_LINEAR, PULSE_IDS, pulse_forcing
from opsrock.solvers.friction import kernel as K
from opsrock.solvers.friction.settings import FrictionSettings

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "friction"

#: History slots reserved beyond the nominal steps of the excitation (impacts, events and the
#: motion after the excitation); a history that fills up stops being recorded, the solution itself
#: is unaffected.
_HISTORY_EXTRA = 50_000


def block_parameters(block: Block) -> tuple[float, float, float, float]:
    """``(alpha, e / e_H, mu, mu_k)`` of ``block`` as the kernel takes them (``inf``: no slip).

    Raises
    ------
    InputError
        If Housner's ``e_H`` of the block is not positive (the impact law needs it).
    """
    if block.e_R <= 0.0:
        raise InputError(f"block {block.name or '<unnamed>'}: e_R = 1 - 1.5 sin²(alpha) = {block.e_R:.4f} <= 0; "
                         "the impact law needs a block with width/height < 1.414")
    mu = math.inf if block.friction is None else block.friction
    mu_k = math.inf if block.friction_kinetic is None else block.friction_kinetic
    return block.alpha, block.e / block.e_R, mu, mu_k


def excitation_arrays(block: Block, excitation: Pulse | Record, settings: FrictionSettings) -> tuple:
    """The kernel's forcing arguments ``(form, k, nu, phase, tau_end, kvals, gvals, g_const, g_tail, dtau,
    h_nom)`` for ``excitation`` in the time scale of ``block``."""
    p = block.p
    if isinstance(excitation, Record):
        check_sampling(excitation, block)
        kvals, dtau = excitation.values / G, excitation.dt * p
        gvals = np.zeros(0) if excitation.vertical is None else 1.0 + excitation.vertical / G
        return (FORM_LINEAR, 0.0, 0.0, 0.0, excitation.duration * p, kvals, gvals, 1.0, 1.0, dtau,
                min(settings.max_dtau, dtau))
    if not isinstance(excitation, Pulse) or excitation.shape not in PULSE_IDS:
        raise InputTypeError(f"friction solves the pulses of PULSE_SHAPES and records (Pulse, Record), got "
                             f"{type(excitation).__name__}")
    nu = excitation.omega_p / p
    form, k, nu_, phase, tau_end, kvals, dtau = pulse_forcing(PULSE_IDS[excitation.shape], excitation.pfa / G, nu)
    g = 1.0 + excitation.vertical / G
    h_nom = min(settings.max_dtau, 2.0 * math.pi / nu / settings.steps_per_pulse)
    return form, k, nu_, phase, tau_end, kvals, np.zeros(0), g, g, dtau, h_nom


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
                          time_flight=float(out[K.OUT_TIME_FLIGHT]) / p, energy=energy)


def run_case(block: Block, excitation: Pulse | Record, settings: FrictionSettings, theta0: float = 0.0,
             omega0: float = 0.0) -> RockingResult:
    """Solve one case with its history (``theta0`` rad, ``omega0`` in units of ``p``)."""
    settings_dict = {"solver": SOLVER_NAME, **asdict(settings)}
    alpha, f_rest, mu, mu_k = block_parameters(block)
    form, k, nu, phase, tau_end, kvals, gvals, g_const, g_tail, dtau, h_nom = excitation_arrays(
        block, excitation, settings)
    cap = math.ceil(tau_end / h_nom) + _HISTORY_EXTRA
    hist = [np.zeros(cap) for _ in range(4)] + [np.zeros(cap, dtype=np.int64)]
    out = np.zeros(K.OUT_SIZE)
    t0 = _time.perf_counter()
    try:
        K.solve_case(alpha, f_rest, mu, mu_k, form, k, nu, phase, tau_end, kvals, gvals, g_const, g_tail, dtau,
                     h_nom, settings.max_dtau, settings.rest_velocity, settings.max_impacts, settings.max_steps,
                     settings.max_tail, float(theta0), float(omega0), out, *hist)
    except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
        return failed_result(SOLVER_NAME, settings_dict, alpha, f"{type(exc).__name__}: {exc}",
                             wall_time_s=_time.perf_counter() - t0)
    wall = _time.perf_counter() - t0
    p, nh = block.p, int(out[K.OUT_HIST])
    time_s, theta, theta_dot = hist[0][:nh] / p, hist[1][:nh], hist[2][:nh] * p
    status = int(out[K.OUT_STATUS])
    if status != K.STATUS_OK:
        reason = f"{K.STATUS_REASONS[status]} (at t = {out[K.OUT_EVENT_TAU] / p:.6g} s)"
        return failed_result(SOLVER_NAME, settings_dict, alpha, reason, time=time_s, theta=theta,
                             theta_dot=theta_dot, n_steps=int(out[K.OUT_STEPS]), wall_time_s=wall)
    return RockingResult(
        solver=SOLVER_NAME, settings=settings_dict, alpha=alpha, time=time_s, theta=theta, theta_dot=theta_dot,
        theta_max=float(out[K.OUT_THETA_MAX]), overturned=bool(out[K.OUT_OVERTURNED]),
        rocked=bool(out[K.OUT_ROCKED]), n_steps=int(out[K.OUT_STEPS]), wall_time_s=wall,
        n_impacts=int(out[K.OUT_IMPACTS]), slide=hist[3][:nh] * block.R,
        contact=_contact(out, block, time_s))


def solve(block: Block, excitation: Pulse | Record, *, settings: FrictionSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Response of one block, initially at rest, on a floor with Coulomb friction under an analytic
    pulse or a record, horizontal and vertical (docs/friction.md).

    Parameters
    ----------
    block : Block
        The block; ``friction`` (static) and ``friction_kinetic`` set the floor's friction (None:
        the base never slips).
    excitation : Pulse or Record
        The floor motion: any pulse of :data:`opsrock.excitations.PULSE_SHAPES` (with its constant
        ``vertical`` acceleration), or a record (with its ``vertical`` samples, if any).
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
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    return run_case(block, excitation, settings)


def free_rocking(block: Block, theta0: float, duration: float, *, theta_dot0: float = 0.0,
                 settings: FrictionSettings | None = None, **overrides: Any) -> RockingResult:
    """Free motion (no floor motion, ``g`` only) from rocking at ``theta0`` (rad, ``|theta0| < pi/2``)
    with ``theta_dot0`` (rad/s) on a stuck pivot, followed until the block is at rest. ``duration``
    (s) is the span of the (zero) excitation; the motion after it is followed as always."""
    settings = make_settings(FrictionSettings, settings, overrides)
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    theta0, theta_dot0 = initial_state(theta0, theta_dot0)
    duration = positive_finite("duration", duration)
    n = max(2, math.ceil(duration * block.p / 0.1) + 1)
    still = Record(dt=duration / (n - 1), values=np.zeros(n), name="no motion")
    return run_case(block, still, settings, theta0, theta_dot0 / block.p)


__all__ = ["SOLVER_NAME", "block_parameters", "excitation_arrays", "free_rocking", "run_case", "solve"]
