"""Settings of the OpenSees solver: the SDOF model and every numerical choice, each named and justified."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

from opsrock.block import Block
from opsrock.errors import InputError, InputTypeError
from opsrock.limits import check, int_at_least, one_of, positive_finite
from opsrock.model import SDOFModel
from opsrock.solvers.common import SolverSettings, refuse_value, settings_record

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "opensees"

#: Time integrators offered. ``"newmark"``: average acceleration (gamma 1/2, beta 1/4), implicit,
#: unconditionally stable, no numerical damping; ``"hht"`` and ``"generalized_alpha"``: implicit
#: with high-frequency dissipation set by ``rho_inf``; ``"central_difference"``: explicit, stable
#: only below ``dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha))`` (:func:`critical_time_step`).
INTEGRATORS: tuple[str, ...] = ("newmark", "hht", "generalized_alpha", "central_difference")


#: Equation-solving algorithms. docs/guide/modelling.md section 4: KrylovNewton converged on 60/60 random
#: pulses, plain Newton failed on 3/60 (cycling at the stiff-branch corner near rest).
ALGORITHMS: tuple[str, ...] = ("KrylovNewton", "NewtonLineSearch", "Newton", "ModifiedNewton", "BFGS")


#: A run counts as *rocking* when ``theta_max`` exceeds this multiple of the stiff-branch
#: half-width ``theta_e``. Below uplift the block sits on the stiff branch at
#: ``|theta| = theta_e |Lambda a| / (m g R sin alpha) < theta_e`` (Eq. 4 with the housner lever);
#: an uplifted block leaves it by orders of magnitude, so the factor 10 separates the two with a
#: wide margin on either side (also for the small dynamic overshoot of the stiff branch).
ROCKED_THETA_E_MULTIPLE: float = 10.0



@dataclass(frozen=True)
class OpenSeesSettings(SolverSettings):
    """Settings of the OpenSees solver: the SDOF model and every numerical choice; those of
    :class:`~opsrock.solvers.common.SolverSettings` (``tail="rest"`` only: the run stops at rest or at the
    end time; ``max_free_time`` None: :data:`~opsrock.solvers.opensees.stepper.DEFAULT_TAIL`; ``max_steps``
    counts OpenSees steps, the retried halves included; ``record=False`` returns empty histories) and

    Parameters
    ----------
    model : SDOFModel
        The equivalent SDOF model (damper band ``delta``, stiff branch ``theta_e_ratio``, table
        points, excitation lever).
    step : float
        Time step (s). Fixed-step runs use it throughout; adaptive runs use it as the *largest*
        step, in free rocking away from the damper band. Default 2e-3 s, adaptive.
    adaptive : bool
        Default True. The step lands just inside the damper band on entry and just outside it on
        exit (so the damper acts over the band and only the band), crosses the band in at least
        ``band_steps`` steps, crosses the stiff branch at zero in one symmetric step, takes a
        tiny reset step whenever the damper coefficient changes (Newmark would otherwise average
        the old damper force into the next step), resolves the excitation with at least
        ``excitation_steps`` steps, and is ``step`` elsewhere. With Newmark, under a record, a block
        seated in the stiff branch is carried along its quasi-static deflection without steps up to
        the last step before the floor can lift it (every step there ended seated: the same answer,
        bit for bit, in 21,600 steps instead of 70,300 on the records of ``opsrock bench --only
        records``). Measured on 100 paper pulses
        against the scipy SDOF solver: max ``|d theta_max|`` = 0.04 % of alpha, no verdict
        changed, ~20x faster than fixed steps of 1e-4 s, whose error reached 4 % of alpha
        (``opsrock bench --only opensees``, validation/sdof_agreement). False: fixed steps of ``step``, the
        literal step-by-step loop.
    band_steps : int
        Adaptive mode: smallest number of steps across the band width ``2 delta alpha`` (-), and
        across a passage that starts inside the band. Default 40: the band's dissipation carries a
        first-order error in ``1 / band_steps`` (measured: -0.31 / -0.17 / -0.09 % of alpha on
        theta_max for 20 / 40 / 80 steps on a paper pulse, against the scipy SDOF solver).
    excitation_steps : int
        Adaptive mode: smallest number of steps over the excitation's duration (and no step
        longer than a record's sampling interval) while the floor moves (-).
    min_step : float
        Smallest step the adaptive mode or the step-halving recovery may take (s).
    integrator : str
        One of :data:`INTEGRATORS`.
    rho_inf : float
        Spectral radius at infinite frequency for ``"hht"`` (in [0.5, 1]) and
        ``"generalized_alpha"`` (in [0, 1]) (-): 1 is no numerical damping.
    algorithm : str
        Equation-solving algorithm, one of :data:`ALGORITHMS`.
    fallback_algorithms : tuple of str
        Algorithms tried, in order, when a step still fails after ``max_halvings`` halvings.
    tol : float
        ``NormDispIncr`` convergence tolerance (rad).
    max_iter : int
        Largest number of iterations per step (-).
    max_halvings : int
        How many times a failed step is halved before trying the fallback algorithms (-).
    end_time : float or None
        Hard end time (s). None: excitation duration + ``max_free_time`` (default
        :data:`~opsrock.solvers.opensees.stepper.DEFAULT_TAIL`). A run that reaches it before the block
        overturned or came to rest is *failed* (its peak is not known).
    rest_tolerance : float
        Rest test after the excitation ended, as a fraction of ``alpha`` (-): the run stops once
        the largest rotation the remaining energy can reach is below ``theta_max +
        rest_tolerance * alpha``, i.e. the peak can grow by less than that.
    stop_at_rest : bool
        If True (default), stop at rest as above; if False, run to ``end_time`` and end normally
        there (free-rocking studies that need the whole history).
    element_forces : bool
        If True, read the spring moment and damper force of every recorded step from the
        elements (``eleResponse``, two calls a step); if False (default), compute them after the
        run from the same table (``ElasticMultiLinear`` interpolates it linearly) and the damper
        coefficient at each recorded state (``Viscous``: ``F = C theta'``): the same numbers
        (tests/model/solvers/test_opensees_adaptive.py checks it) at a third less Python time per step.
    record_every : int
        Keep every n-th step in the returned history (the last step is always kept) (-).
    explicit_step_check : bool
        If True (default), an explicit run whose largest step exceeds
        :func:`critical_time_step` is refused up front as *failed* ("unstable: ..."): above it the
        stiff branch blows up within a step or two and the run can end in a plausible but wrong
        verdict (measured: validation/stability_map). False lets the stability map measure that.
    stiff_branch_check : bool
        If True (default), an explicit run reports *failed* ("unstable: ...") as soon as it takes a
        step at or above :func:`critical_time_step` from inside the stiff branch, the only place
        where the explicit scheme is unstable; this catches what ``explicit_step_check=False``
        lets through (such runs used to come back "ok" with spurious rocking: the state
        saturates off the branch, and neither the sawtooth nor the energy test sees it). False
        only to measure the raw scheme (validation/stability_map does).
    uplift_check : bool
        If True (default), a block starting from rest under an excitation that cannot uplift it
        (Eq. 4: ``|Lambda| PFA <= m g R sin(alpha)``, :func:`opsrock.model.can_uplift`) is
        returned seated without integration. At exactly the threshold the finite stiff branch is
        at neutral equilibrium and tips numerically (up to 0.03 alpha on the paper grid's
        ``PFA = g tan(alpha)`` row); False runs the model anyway.
    """

    model: SDOFModel = field(default_factory=SDOFModel)
    step: float = 2e-3
    adaptive: bool = True
    band_steps: int = 40
    excitation_steps: int = 1000
    min_step: float = 1e-7
    integrator: str = "newmark"
    rho_inf: float = 0.9
    algorithm: str = "KrylovNewton"
    fallback_algorithms: tuple[str, ...] = ("NewtonLineSearch", "ModifiedNewton")
    tol: float = 1e-10
    max_iter: int = 50
    max_halvings: int = 8
    rest_tolerance: float = 1e-4
    record_every: int = 1
    element_forces: bool = False
    explicit_step_check: bool = True
    stiff_branch_check: bool = True
    uplift_check: bool = True

    def __post_init__(self) -> None:
        super().__post_init__()
        refuse_value(SOLVER_NAME, self, "tail", ("rest",))
        if not isinstance(self.model, SDOFModel):
            raise InputTypeError(f"model must be an SDOFModel, got {self.model!r}")
        check("step", self.step)
        if not isinstance(self.adaptive, bool):
            raise InputTypeError(f"adaptive must be a bool, got {self.adaptive!r}")
        int_at_least("band_steps", self.band_steps, 2)
        int_at_least("excitation_steps", self.excitation_steps, 10)
        positive_finite("min_step", self.min_step)
        if self.min_step > self.step:
            raise InputError(f"min_step must not exceed step = {self.step!r}, got {self.min_step!r}")
        one_of("integrator", self.integrator, INTEGRATORS)
        low = 0.5 if self.integrator == "hht" else 0.0
        if isinstance(self.rho_inf, bool) or not isinstance(self.rho_inf, (int, float)) or not (
            low <= self.rho_inf <= 1.0
        ):
            raise InputError(f"rho_inf must lie in [{low:g}, 1] for integrator {self.integrator!r}, got {self.rho_inf!r}")
        one_of("algorithm", self.algorithm, ALGORITHMS)
        fb = tuple(self.fallback_algorithms)
        for name in fb:
            one_of("fallback_algorithms", name, ALGORITHMS)
        object.__setattr__(self, "fallback_algorithms", fb)
        positive_finite("tol", self.tol)
        int_at_least("max_iter", self.max_iter, 1)
        int_at_least("max_halvings", self.max_halvings, 0)
        positive_finite("rest_tolerance", self.rest_tolerance)
        if not isinstance(self.element_forces, bool):
            raise InputTypeError(f"element_forces must be a bool, got {self.element_forces!r}")
        if not isinstance(self.uplift_check, bool):
            raise InputTypeError(f"uplift_check must be a bool, got {self.uplift_check!r}")
        int_at_least("record_every", self.record_every, 1)

    def as_dict(self) -> dict[str, Any]:
        """All settings, the model's included, as a JSON-friendly dict."""
        return settings_record(self)


def critical_time_step(block: Block, model: SDOFModel | None = None) -> float:
    """Explicit (central-difference) stability limit ``dt_cr = 2 / omega_e`` (s).

    ``omega_e = sqrt(k_e / I_O)`` with the stiff-branch stiffness ``k_e = m g R sin(alpha) /
    theta_e``, i.e. ``dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha))`` = the stiff branch's
    period / pi.
    """
    model = SDOFModel() if model is None else model
    k_e = block.overturning_rotation_moment / model.theta_e(block)
    return 2.0 * math.sqrt(block.I_O / k_e)


__all__ = ["ALGORITHMS", "INTEGRATORS", "OpenSeesSettings", "ROCKED_THETA_E_MULTIPLE", "SOLVER_NAME", "critical_time_step"]
