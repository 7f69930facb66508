"""The OpenSees solver's entry points: :func:`solve` (the rotational SDOF model) and
:func:`solve_lumped_mass` (the lumped-mass form of Figure 2b, for the validation of the lever)."""

from __future__ import annotations

import dataclasses
import time as _time
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.errors import InputTypeError
from opsrock.excitations import Excitation, Record
from opsrock.limits import one_of
from opsrock.model import can_uplift
from opsrock.opensees_session import CONSOLE, console_to_log, count_messages, fresh_model, log_size
from opsrock.result import RockingResult, failed_result, seated_result
from opsrock.solvers.common import SolverRun, check_inputs, make_settings
from opsrock.solvers.opensees.build import build_lumped, build_sdof, define_analysis, set_initial_state
from opsrock.solvers.opensees.settings import ROCKED_THETA_E_MULTIPLE, SOLVER_NAME, OpenSeesSettings, critical_time_step
from opsrock.solvers.opensees.stepper import StepFailure, Stepper

#: The still floor of free rocking: a zero record (the model needs a time series; only its length, 0.01 s,
#: enters the run, as the end of the excitation after which the rest test applies).
STILL_FLOOR = Record(dt=0.01, values=np.zeros(2), name="no motion")


def solve(
    block: Block, excitation: Excitation | None, settings: OpenSeesSettings | None = None, **overrides: Any
) -> RockingResult:
    """Rocking response of ``block`` to ``excitation`` with the paper's OpenSees SDOF model.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation or None
        Floor acceleration (m/s^2): a one-sine pulse, a record, or any :class:`Excitation`. None: a still
        floor (:data:`STILL_FLOOR`, a zero record), free rocking from ``theta0``, ``theta_dot0``.
    settings : OpenSeesSettings, optional
        Model and numerics; defaults to ``OpenSeesSettings()``.
    **overrides
        Any :class:`OpenSeesSettings` field, or ``delta``, ``theta_e_ratio``, ``table_points``,
        ``lever``, ``damper`` of the :class:`~opsrock.model.SDOFModel`
        (:func:`opsrock.solvers.common.make_settings`).

    Returns
    -------
    RockingResult
        ``solver="opensees"``. ``status="failed"`` with a reason if a step could not be recovered,
        the run blew up numerically ("unstable: ..."), or the end time came before rest.
    """
    settings = make_settings(OpenSeesSettings, settings, overrides)
    block = check_inputs(SOLVER_NAME, block, excitation, settings)
    return _OpenSeesRun(block, STILL_FLOOR if excitation is None else excitation, settings).run()


def solve_lumped_mass(
    block: Block,
    excitation: Excitation,
    *,
    geometry: str = "linear",
    settings: OpenSeesSettings | None = None,
    **overrides: Any,
) -> RockingResult:
    """Lumped-mass form of the paper's Figure 2b, built in 2-D OpenSees.

    A pivot node with the same rotational spring and damper as :func:`solve`, a rigid link of
    length ``R`` to a mass node carrying ``m`` on its translations and ``I_CM = m r^2`` (``m R^2 / 3`` homogeneous) on its
    rotation, and the horizontal force ``m a(t) cos(alpha)`` on the mass (the model is the
    mirror image of the block, so that ``theta`` keeps the sign convention of :func:`solve`).
    The excitation lever is therefore *not* an input: it follows from the geometry. Gravity is
    in the spring (Eq. 5), so no P-Delta.

    Parameters
    ----------
    block, excitation, settings, overrides
        As :func:`solve`; ``lever`` is ignored (the model has no lever input).
    geometry : str
        ``"linear"`` only: a ``rigidLink beam`` (small-rotation kinematics, so the lever is
        exactly ``m R cos(alpha)``). A corotational stiff-beam variant was tried and did not
        converge reliably with a link stiff enough to leave the stiff branch intact; it is
        not offered.
    """
    one_of("geometry", geometry, ("linear",))
    settings = make_settings(OpenSeesSettings, settings, overrides)
    run = _OpenSeesRun(check_inputs(SOLVER_NAME, block, excitation, settings), excitation, settings)
    run.geometry = geometry
    return run.run()


def _refused(block: Block, excitation: Excitation, s: OpenSeesSettings, settings_dict: dict, geometry: str | None,
             t_wall: float) -> RockingResult | None:
    """The answer given without building a model: an explicit step above its critical step (failed), or
    an excitation that cannot uplift the block (Eq. 4, seated); None if the model must run."""
    if s.integrator == "central_difference" and s.explicit_step_check:
        dt_cr = critical_time_step(block, s.model)
        if s.step >= dt_cr:
            return failed_result(
                SOLVER_NAME, settings_dict, block.alpha,
                f"unstable: explicit central difference with step = {s.step:.4g} s >= its critical step "
                f"dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha)) = {dt_cr:.4g} s", failure="unstable",
            )
    # Eq. 4 after the settings checks: bad settings are refused whatever the pulse
    if (s.uplift_check and geometry is None and s.theta0 == 0.0 and s.theta_dot0 == 0.0
            and not can_uplift(block, s.model, excitation.pfa)):
        return seated_result(SOLVER_NAME, settings_dict, block.alpha, excitation.duration,
                             _time.perf_counter() - t_wall)
    return None


class _OpenSeesRun(SolverRun):
    """One run of the OpenSees model (the rotational SDOF, or the lumped-mass form with ``geometry``)."""

    name = SOLVER_NAME
    geometry: str | None = None

    def _run_impl(self) -> RockingResult:
        result = _run(self.block, self.excitation, self.settings, self.geometry)
        if self.settings.record:
            return result
        empty = np.zeros(0)
        return dataclasses.replace(result, time=empty, theta=empty, theta_dot=empty,
                                   spring_moment=None if result.spring_moment is None else empty,
                                   damper_force=None if result.damper_force is None else empty)


def _run(block: Block, excitation: Excitation, s: OpenSeesSettings, geometry: str | None) -> RockingResult:
    if not isinstance(excitation, Excitation):
        raise InputTypeError(f"excitation must be an Excitation, got {excitation!r}")
    settings_dict = s.as_dict()
    if geometry is not None:
        settings_dict["form"] = f"lumped_mass/{geometry}"
    t_wall = _time.perf_counter()
    refused = _refused(block, excitation, s, settings_dict, geometry, t_wall)
    if refused is not None:
        return refused
    log = console_to_log()
    start = log_size(log)
    CONSOLE["retries"] = 0
    CONSOLE["recovered_by"] = {}
    result = _build_and_integrate(block, excitation, s, settings_dict, geometry, t_wall)
    diagnostics = {
        "opensees_messages": count_messages(log, start),
        "retried_steps": int(CONSOLE["retries"]),
        # how each retried step was recovered: "halving:<algorithm>" -> count; the default
        # algorithm and tolerance, with the step halved, or a fallback algorithm (same tol)
        "recovered_by": dict(CONSOLE["recovered_by"]),
        "needed_fallback_algorithm": any(not k.endswith(":" + s.algorithm) for k in CONSOLE["recovered_by"]),
        "opensees_log": log,
    }
    return dataclasses.replace(result, diagnostics=diagnostics)


def _build_and_integrate(block: Block, excitation: Excitation, s: OpenSeesSettings,
                         settings_dict: dict[str, Any], geometry: str | None, t_wall: float) -> RockingResult:
    with fresh_model():
        if geometry is None:
            build_sdof(block, excitation, s)
            node, dof = 2, 1
        else:
            build_lumped(block, excitation, s, geometry)
            node, dof = 2, 3
        # the lumped form's rigidLink is a multi-point constraint: Transformation handler
        define_analysis(s, s.algorithm, "Plain" if geometry is None else "Transformation")
        set_initial_state(block, excitation, s, node, dof)
        stepper = Stepper(block, excitation, s, node, dof)
        try:
            why = stepper.run()
        except StepFailure as exc:
            time, theta, theta_dot = stepper.history()
            return failed_result(SOLVER_NAME, settings_dict, block.alpha, str(exc), time=time, theta=theta,
                                 theta_dot=theta_dot, n_steps=stepper.n_steps,
                                 wall_time_s=_time.perf_counter() - t_wall, failure=exc.failure)
    time, theta, theta_dot = stepper.history()
    spring, damper = stepper.moments()
    return RockingResult(
        solver=SOLVER_NAME, settings=settings_dict, alpha=block.alpha, time=time, theta=theta, theta_dot=theta_dot,
        theta_max=float(stepper.theta_max), overturned=why == "overturned",
        rocked=bool(stepper.theta_max > ROCKED_THETA_E_MULTIPLE * s.model.theta_e(block)),
        n_steps=stepper.n_steps, wall_time_s=_time.perf_counter() - t_wall, spring_moment=spring,
        damper_force=damper, n_impacts=len(stepper.impacts), impacts=stepper.impacts.freeze())


__all__ = ["SOLVER_NAME", "STILL_FLOOR", "solve", "solve_lumped_mass"]
