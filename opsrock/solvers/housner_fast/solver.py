"""One case with its history: :func:`solve` (a pulse, a record, or free rocking on a still floor)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.constants import G
from opsrock.errors import InputTypeError, ModelNotSupported
from opsrock.excitations import Pulse, Record
from opsrock.excitations.records import check_sampling
from opsrock.result import RockingResult, failed_result
from opsrock.solvers._compile import announce_compile
from opsrock.solvers.common import SolverRun, check_inputs, make_settings, settings_record
from opsrock.solvers.forcing import PULSE_IDS, PULSE_ONE_SINE, Excitation, pulse_forcing, record_forcing
from opsrock.solvers.housner_fast import kernel as K
from opsrock.solvers.housner_fast.settings import HousnerFastSettings
from opsrock.solvers.status import NONFINITE, OK, REASONS, failure_of

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "housner_fast"

#: History slots reserved beyond the nominal steps of a case in :func:`solve` and
#: free rocking (two per impact, one per uplift and extra event step); a history
#: that fills up stops being recorded, the solution itself is unaffected.
_HISTORY_EXTRA = 20_000


def case_parameters(block: Block, excitation: Pulse | Record | None,
                    settings: HousnerFastSettings) -> tuple[K.Params, Excitation]:
    """The kernel's inputs for one case: its :class:`~.kernel.Params` and the floor motion.

    ``excitation=None`` is a still floor integrated for ``end_time`` (s), after which the exact energy
    verdict of a pulse's end applies (an analytic pulse of zero amplitude whose period is ``end_time``).
    """
    p = block.p
    if isinstance(excitation, Record):
        check_sampling(excitation, block)
        dtau = excitation.dt * p
        exc = record_forcing(excitation.values / G, dtau, excitation.duration * p)
        h_nom = min(settings.max_dtau, dtau)
    else:
        if excitation is None:
            k, nu, pulse = 0.0, 2.0 * math.pi / (settings.end_time * p), PULSE_ONE_SINE
        elif isinstance(excitation, Pulse) and excitation.shape in PULSE_IDS:
            k, nu, pulse = excitation.pfa / G, excitation.omega_p / p, PULSE_IDS[excitation.shape]
        else:
            raise InputTypeError(
                f"housner_fast solves the pulses of PULSE_SHAPES and records (Pulse, Record), got "
                f"{type(excitation).__name__}; use solver='housner' for other excitations")
        exc = pulse_forcing(pulse, k, nu)
        h_nom = min(settings.max_dtau, 2.0 * math.pi / nu / settings.steps_per_pulse)
    par = K.case_params(block.alpha, block.e, settings.equations == "linearised", h_nom, settings.rest_velocity,
                        settings.max_impacts, settings.step_limit)
    return par, exc


class _HousnerFastRun(SolverRun):
    """One case through the compiled kernel, with its history."""

    name = SOLVER_NAME

    def _run_impl(self) -> RockingResult:
        block, settings = self.block, self.settings
        settings_dict = {"solver": SOLVER_NAME, **settings_record(settings)}
        alpha, p = block.alpha, block.p
        par, exc = case_parameters(block, self.excitation, settings)
        cap = int(math.ceil(exc.tau_end / par.h_nom)) + _HISTORY_EXTRA if settings.record else 0
        hist = K.History(np.zeros(cap), np.zeros(cap), np.zeros(cap))
        announce_compile(K.solve_case, SOLVER_NAME)
        try:
            out = self.compiled_call(K.solve_case, par, exc, float(settings.theta0), float(settings.theta_dot0 / p),
                                     hist)
        except Exception as exc:  # noqa: BLE001  a solver failure must become a failed result
            return failed_result(SOLVER_NAME, settings_dict, alpha, f"{type(exc).__name__}: {exc}",
                                 wall_time_s=self.elapsed())
        wall = self.elapsed()
        nh, st, tm = int(out.n_hist), int(out.status), float(out.theta_max)
        time_s, theta, theta_dot = hist.tau[:nh] / p, hist.theta[:nh], hist.omega[:nh] * p
        if st != OK or not math.isfinite(tm):
            reason = REASONS[st] if st != OK else f"non-finite theta_max {tm!r}"
            return failed_result(SOLVER_NAME, settings_dict, alpha, reason, time=time_s, theta=theta,
                                 theta_dot=theta_dot, n_steps=int(out.n_steps), wall_time_s=wall,
                                 failure=failure_of(st if st != OK else NONFINITE))
        return RockingResult(
            solver=SOLVER_NAME, settings=settings_dict, alpha=alpha, time=time_s, theta=theta, theta_dot=theta_dot,
            theta_max=tm, overturned=bool(out.overturned), rocked=bool(out.rocked),
            n_steps=int(out.n_steps), wall_time_s=wall, n_impacts=int(out.n_impacts))


def solve(block: Block, excitation: Pulse | Record | None, settings: HousnerFastSettings | None = None,
          **overrides: Any) -> RockingResult:
    """Rocking response of one block to an analytic pulse or a record, or its free rocking from a start
    state (rigid-body model, exact or linearised equations).

    Parameters
    ----------
    block : Block
        The block.
    excitation : Pulse or Record or None
        The floor motion: any pulse of :data:`opsrock.excitations.PULSE_SHAPES`, or a record. A record is
        integrated segment by segment (linear acceleration between samples, every step ending on a
        sample), with the step also bounded by ``max_dtau``; it must be sampled finely enough for the
        block (:func:`opsrock.excitations.records.check_sampling`). None: a still floor, integrated for
        ``end_time`` (required) from ``theta0``, ``theta_dot0`` (used to check the integrator against
        closed forms: first impact time, energy, ``e²`` per impact); the step is then
        ``min(max_dtau, p end_time / steps_per_pulse)`` in units of ``1/p``.
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
    block = check_inputs(SOLVER_NAME, block, excitation, settings)
    if (excitation is None) != (settings.end_time is not None):
        raise ModelNotSupported(f"solver {SOLVER_NAME!r} takes end_time (the span of free rocking) with "
                                f"excitation None and only then, got end_time = {settings.end_time!r}")
    return _HousnerFastRun(block, excitation, settings).run()


__all__ = ["SOLVER_NAME", "case_parameters", "solve"]
