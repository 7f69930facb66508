"""One case with its history: :func:`solve` (a pulse or a record) and :func:`free_rocking`."""

from __future__ import annotations

import math
import time as _time
from dataclasses import asdict
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputTypeError
from opsrock.excitations import Pulse, Record
from opsrock.excitations.records import check_sampling
from opsrock.limits import initial_state, positive_finite
from opsrock.result import RockingResult, failed_result
from opsrock.solvers.common import make_settings
from opsrock.solvers.forcing import FORM_LINEAR, PULSE_IDS, PULSE_ONE_SINE, pulse_forcing
from opsrock.solvers.housner_fast.kernel import STATUS_OK, STATUS_REASONS, _solve_case
from opsrock.solvers.housner_fast.settings import HousnerFastSettings

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "housner_fast"

#: History slots reserved beyond the nominal steps of a case in :func:`solve` and
#: :func:`free_rocking` (two per impact, one per uplift and extra event step); a history
#: that fills up stops being recorded, the solution itself is unaffected.
_HISTORY_EXTRA = 20_000


def _run_one(block: Block, k: float, nu: float, theta0: float, omega0: float,
             settings: HousnerFastSettings, record: Record | None = None,
             pulse: int = PULSE_ONE_SINE) -> RockingResult:
    """Solve one case with history; ``k = PFA/g``, ``nu = omega_p/p`` (dimensionless) for the
    analytic pulse ``pulse`` (a kernel id), or the samples of ``record`` when it is given."""
    settings_dict = {"solver": SOLVER_NAME, **asdict(settings)}
    alpha = block.alpha
    p = block.p
    if record is None:
        form, c0, c1, c2, tau_end, kvals, dtau = pulse_forcing(pulse, k, nu)
        h_nom = min(settings.max_dtau, 2.0 * math.pi / nu / settings.steps_per_pulse)
    else:
        form, c0, c1, c2 = FORM_LINEAR, 0.0, 0.0, 0.0
        kvals, dtau = record.values / G, record.dt * p
        tau_end = record.duration * p
        h_nom = min(settings.max_dtau, dtau)
    cap = int(math.ceil(tau_end / h_nom)) + _HISTORY_EXTRA
    hist = [np.zeros(cap) for _ in range(3)]
    t0 = _time.perf_counter()
    try:
        tm, ov, rk, st, ni, ns, nh = _solve_case(
            alpha, block.e, form, c0, c1, c2, tau_end, kvals, dtau, h_nom,
            settings.equations == "linearised", float(settings.rest_velocity), int(settings.max_impacts), int(settings.max_steps),
            float(theta0), float(omega0), *hist)
    except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
        return failed_result(SOLVER_NAME, settings_dict, alpha, f"{type(exc).__name__}: {exc}",
                             wall_time_s=_time.perf_counter() - t0)
    wall = _time.perf_counter() - t0
    time_s = hist[0][:nh] / p
    theta = hist[1][:nh]
    theta_dot = hist[2][:nh] * p
    if st != STATUS_OK or not math.isfinite(tm):
        reason = STATUS_REASONS.get(int(st), "") or f"non-finite theta_max {tm!r}"
        return failed_result(SOLVER_NAME, settings_dict, alpha, reason, time=time_s, theta=theta,
                             theta_dot=theta_dot, n_steps=int(ns), wall_time_s=wall)
    return RockingResult(
        solver=SOLVER_NAME,
        settings=settings_dict,
        alpha=alpha,
        time=time_s,
        theta=theta,
        theta_dot=theta_dot,
        theta_max=float(tm),
        overturned=bool(ov),
        rocked=bool(rk),
        n_steps=int(ns),
        wall_time_s=wall,
        n_impacts=int(ni),
    )


def solve(block: Block, excitation: Pulse | Record, *, settings: HousnerFastSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Rocking response of one block, initially at rest, to an analytic pulse or a record
    (rigid-body model, exact or linearised equations).

    Parameters
    ----------
    block : Block
        The block.
    excitation : Pulse or Record
        The floor motion: any pulse of :data:`opsrock.excitations.PULSE_SHAPES`, or a record. A record is integrated segment by segment (linear acceleration between
        samples, every step ending on a sample), with the step also bounded by ``max_dtau``; it
        must be sampled finely enough for the block (:func:`opsrock.excitations.records.check_sampling`).
    settings : HousnerFastSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields.

    Returns
    -------
    RockingResult
        ``time``/``theta``/``theta_dot`` hold the accepted steps, uplifts and impacts (the
        state just before and just after each, at the same time) while the pulse lasts
        (s, rad, rad/s); ``theta_max`` (rad) includes the exact first free-rocking peak after
        the pulse; an overturning decided after the pulse by the energy barrier reports
        ``theta_max = pi/2``. ``n_impacts`` counts impacts up to that first free-rocking peak (the
        decay to rest after it is not simulated): the count of ``housner`` with ``tail="peak"``.
    """
    settings = make_settings(HousnerFastSettings, settings, overrides)
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    if isinstance(excitation, Record):
        check_sampling(excitation, block)
        return _run_one(block, 0.0, 1.0, 0.0, 0.0, settings, record=excitation)
    if not isinstance(excitation, Pulse) or excitation.shape not in PULSE_IDS:
        raise InputTypeError(
            f"housner_fast solves the pulses of PULSE_SHAPES and records (Pulse, Record), got "
            f"{type(excitation).__name__}; use solver='housner' for other excitations")
    return _run_one(block, excitation.pfa / G, excitation.omega_p / block.p, 0.0, 0.0, settings,
                    pulse=PULSE_IDS[excitation.shape])


def free_rocking(block: Block, theta0: float, duration: float, *, theta_dot0: float = 0.0,
                 settings: HousnerFastSettings | None = None, **overrides: Any) -> RockingResult:
    """Free rocking (no floor motion) from an initial state, integrated step by step.

    Used to check the integrator against closed forms (first impact time, energy, ``e²`` per
    impact). The motion is integrated for ``duration``; the verdict after that uses the same
    exact energy argument as :func:`solve`.

    Parameters
    ----------
    block : Block
        The block.
    theta0 : float
        Initial rotation (rad), ``|theta0| < pi/2``.
    duration : float
        Integrated time (s), > 0.
    theta_dot0 : float, optional
        Initial angular velocity (rad/s). Default 0.
    settings : HousnerFastSettings, optional
        Numerical settings; keyword ``overrides`` replace individual fields. The step is
        ``min(max_dtau, p duration / steps_per_pulse)`` in units of ``1/p``.
    """
    settings = make_settings(HousnerFastSettings, settings, overrides)
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    theta0, theta_dot0 = initial_state(theta0, theta_dot0)
    duration = positive_finite("duration", duration)
    nu = 2.0 * math.pi / (duration * block.p)  # so that the integrated span is `duration`
    return _run_one(block, 0.0, nu, theta0, theta_dot0 / block.p, settings)


__all__ = ["SOLVER_NAME", "free_rocking", "solve"]
