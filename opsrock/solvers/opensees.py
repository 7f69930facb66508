"""The paper's equivalent SDOF model (Eq. 5-8) built literally in OpenSeesPy.

OpenSees state is owned by :mod:`opsrock.opensees_session`: every model here is built inside its
``fresh_model()`` context, which wipes OpenSees before and after (also on errors), so no state
leaks from one run into the next.

Model (docs/modelling.md sections 2 and 4)
----------------------------------
One rotational degree of freedom (a 1-D model, ``ndm=1, ndf=1``: the node's single dof *is*
the block rotation ``theta``), rotational mass ``I_O``, and two ``zeroLength`` elements between
a fixed node and the free one:

* the spring, ``uniaxialMaterial ElasticMultiLinear`` with the table of
  :meth:`opsrock.model.SDOFModel.spring_table` (path-independent; its negative slopes are the
  rocking instability); ``MultiLinear``/``Hysteretic`` would be hysteretic and wrong here;
* the damper, ``uniaxialMaterial Viscous C 1.0`` whose ``C`` is changed through
  ``parameter``/``updateParameter``: ``c_D`` set by the model's damper law at the start of every
  passage through the band ``|theta| <= delta alpha`` (on entering it, at the first step after a
  turning point inside it; :meth:`opsrock.model.SDOFModel.arm_damper`), zero outside (Eq. 7) and
  while the block is seated. The change takes effect from the next step.

With an implicit integrator a block seated in the stiff branch is treated as the scipy solver treats
it (:class:`opsrock.model.Seat`): its free oscillation at ``omega_e`` is dropped once it fits in the branch, and in
adaptive mode under a record a step lands on the instant the floor can lift it.

The floor acceleration enters as the nodal moment ``-Lambda a(t)`` (``Lambda`` =
:meth:`~opsrock.model.SDOFModel.lever_arm`): a ``Trig`` time series for a one-sine pulse (exact
at every step, whatever the step), a ``Path`` series for a sampled :class:`~opsrock.excitations.Record`.

The transient loop stops when ``|theta| >= pi/2`` (overturned: OpenSees never fails by itself,
theta just grows), when the block can no longer exceed its peak after the excitation ended
(``V(theta_max + rest_tolerance alpha)``, see :func:`_reachable_rotation`), or at a hard end time (a *failed* run: the answer is unknown).

:func:`solve_lumped_mass` builds the lumped-mass form of the paper's Figure 2b (a pivot, a rigid
link of length ``R`` and the mass ``m`` with ``I_CM = m R^2 / 3``) for the validation of the
excitation lever.
"""

from __future__ import annotations

import dataclasses
import math
import time as _time
from dataclasses import asdict, dataclass, field, fields, replace
from typing import Any

import numpy as np

from opsrock._checks import bool_fields, int_at_least, one_of, positive_finite
from opsrock.block import Block
from opsrock.constants import G, OVERTURNING_ANGLE
from opsrock.limits import check
from opsrock.excitations import Excitation, HarmonicPulse, Record, RectangularPulse
from opsrock.model import SDOFModel, Seat, can_uplift
from opsrock.opensees_session import CONSOLE as _CONSOLE
from opsrock.opensees_session import count_messages as _count_messages
from opsrock.opensees_session import console_to_log, fresh_model, opensees_log_path, ops
from opsrock.opensees_session import log_size as _log_size
from opsrock.result import ImpactLog, RockingResult, failed_result, seated_result

SOLVER_NAME = "opensees"

#: Time integrators offered. ``"newmark"``: average acceleration (gamma 1/2, beta 1/4), implicit,
#: unconditionally stable, no numerical damping; ``"hht"`` and ``"generalized_alpha"``: implicit
#: with high-frequency dissipation set by ``rho_inf``; ``"central_difference"``: explicit, stable
#: only below ``dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha))`` (:func:`critical_time_step`).
INTEGRATORS: tuple[str, ...] = ("newmark", "hht", "generalized_alpha", "central_difference")

#: Equation-solving algorithms. docs/modelling.md section 4: KrylovNewton converged on 60/60 random
#: pulses, plain Newton failed on 3/60 (cycling at the stiff-branch corner near rest).
ALGORITHMS: tuple[str, ...] = ("KrylovNewton", "NewtonLineSearch", "Newton", "ModifiedNewton", "BFGS")

#: A run counts as *rocking* when ``theta_max`` exceeds this multiple of the stiff-branch
#: half-width ``theta_e``. Below uplift the block sits on the stiff branch at
#: ``|theta| = theta_e |Lambda a| / (m g R sin alpha) < theta_e`` (Eq. 4 with the housner lever);
#: an uplifted block leaves it by orders of magnitude, so the factor 10 separates the two with a
#: wide margin on either side (also for the small dynamic overshoot of the stiff branch).
ROCKED_THETA_E_MULTIPLE: float = 10.0

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

_SPRING_MAT, _DAMPER_MAT = 1, 2
_SPRING_ELE, _DAMPER_ELE = 1, 2
_DAMPER_PARAM = 1

#: Adaptive mode: a block approaching zero inside the band lands this fraction of a band step
#: short of zero and then crosses the stiff branch in one symmetric step (see ``_integrate``).
CROSSING_FRACTION: float = 0.6

#: Steps in a row with ``|theta| <= theta_e`` after the excitation that count as seated for good.
SEATED_STEPS: int = 20

#: Adaptive mode: steps approaching or leaving the band stop this fraction of a band step past
#: its edge, so the damper acts over the band and only the band (Eq. 7).
EDGE_FRACTION: float = 0.05

#: Adaptive mode: length of the reset step after the damper coefficient changes, as a fraction
#: of a band step.
RESET_FRACTION: float = 1e-3

#: Adaptive mode: smallest rotation per step (in ``theta_e``) of a passage that starts inside the
#: band. Passages shrink geometrically as a block settles; without a floor their steps would too
#: (measured: 1.9 million steps on a 20-s record at band_steps 160).
MIN_PASSAGE_STEP_RATIO: float = 10.0
_SERIES, _PATTERN = 1, 1


@dataclass(frozen=True)
class OpenSeesSettings:
    """Settings of the OpenSees solver: the SDOF model and every numerical choice.

    Parameters
    ----------
    model : SDOFModel
        The equivalent SDOF model (damper band ``delta``, stiff branch ``theta_e_ratio``, table
        points, excitation lever).
    dt : float
        Time step (s). Fixed-step runs use it throughout; adaptive runs use it as the *largest*
        step, in free rocking away from the damper band. Default 2e-3 s, adaptive.
    adaptive : bool
        Default True. The step lands just inside the damper band on entry and just outside it on
        exit (so the damper acts over the band and only the band), crosses the band in at least
        ``band_steps`` steps, crosses the stiff branch at zero in one symmetric step, takes a
        tiny reset step whenever the damper coefficient changes (Newmark would otherwise average
        the old damper force into the next step), resolves the excitation with at least
        ``excitation_steps`` steps, and is ``dt`` elsewhere. Measured on 100 paper pulses
        against the scipy SDOF solver: max |d theta_max| = 0.04 % of alpha, no verdict
        changed, ~20x faster than fixed steps of 1e-4 s, whose error reached 4 % of alpha
        (bench/bench_opensees.py, validation/sdof_agreement). False: fixed steps of ``dt``, the
        literal step-by-step loop.
    band_steps : int
        Adaptive mode: smallest number of steps across the band width ``2 delta alpha`` (-), and
        across a passage that starts inside the band. Default 40: the band's dissipation carries a
        first-order error in ``1 / band_steps`` (measured: -0.31 / -0.17 / -0.09 % of alpha on
        theta_max for 20 / 40 / 80 steps on a paper pulse, against the scipy SDOF solver).
    excitation_steps : int
        Adaptive mode: smallest number of steps over the excitation's duration (and no step
        longer than a record's sampling interval) while the floor moves (-).
    dt_min : float
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
        Hard end time (s). None: excitation duration + :data:`DEFAULT_TAIL`. A run that reaches
        it before the block overturned or came to rest is *failed* (its peak is not known).
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
        (tests/test_opensees_adaptive.py checks it) at a third less Python time per step.
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
    theta0 : float
        Initial rotation (rad), ``|theta0| < pi/2``.
    theta_dot0 : float
        Initial angular velocity (rad/s).
    """

    model: SDOFModel = field(default_factory=SDOFModel)
    dt: float = 2e-3
    adaptive: bool = True
    band_steps: int = 40
    excitation_steps: int = 1000
    dt_min: float = 1e-7
    integrator: str = "newmark"
    rho_inf: float = 0.9
    algorithm: str = "KrylovNewton"
    fallback_algorithms: tuple[str, ...] = ("NewtonLineSearch", "ModifiedNewton")
    tol: float = 1e-10
    max_iter: int = 50
    max_halvings: int = 8
    end_time: float | None = None
    rest_tolerance: float = 1e-4
    stop_at_rest: bool = True
    record_every: int = 1
    element_forces: bool = False
    explicit_step_check: bool = True
    stiff_branch_check: bool = True
    uplift_check: bool = True
    theta0: float = 0.0
    theta_dot0: float = 0.0

    def __post_init__(self) -> None:
        bool_fields(self)
        if not isinstance(self.model, SDOFModel):
            raise TypeError(f"model must be an SDOFModel, got {self.model!r}")
        check("dt", self.dt)
        if not isinstance(self.adaptive, bool):
            raise TypeError(f"adaptive must be a bool, got {self.adaptive!r}")
        int_at_least("band_steps", self.band_steps, 2)
        int_at_least("excitation_steps", self.excitation_steps, 10)
        positive_finite("dt_min", self.dt_min)
        if self.dt_min > self.dt:
            raise ValueError(f"dt_min must not exceed dt = {self.dt!r}, got {self.dt_min!r}")
        one_of("integrator", self.integrator, INTEGRATORS)
        low = 0.5 if self.integrator == "hht" else 0.0
        if isinstance(self.rho_inf, bool) or not isinstance(self.rho_inf, (int, float)) or not (
            low <= self.rho_inf <= 1.0
        ):
            raise ValueError(f"rho_inf must lie in [{low:g}, 1] for integrator {self.integrator!r}, got {self.rho_inf!r}")
        one_of("algorithm", self.algorithm, ALGORITHMS)
        fb = tuple(self.fallback_algorithms)
        for name in fb:
            one_of("fallback_algorithms", name, ALGORITHMS)
        object.__setattr__(self, "fallback_algorithms", fb)
        positive_finite("tol", self.tol)
        int_at_least("max_iter", self.max_iter, 1)
        int_at_least("max_halvings", self.max_halvings, 0)
        if self.end_time is not None:
            positive_finite("end_time", self.end_time)
        positive_finite("rest_tolerance", self.rest_tolerance)
        if not isinstance(self.element_forces, bool):
            raise TypeError(f"element_forces must be a bool, got {self.element_forces!r}")
        if not isinstance(self.uplift_check, bool):
            raise TypeError(f"uplift_check must be a bool, got {self.uplift_check!r}")
        if not isinstance(self.stop_at_rest, bool):
            raise TypeError(f"stop_at_rest must be a bool, got {self.stop_at_rest!r}")
        int_at_least("record_every", self.record_every, 1)
        th0 = float(self.theta0)
        if not (math.isfinite(th0) and abs(th0) < OVERTURNING_ANGLE):
            raise ValueError(f"theta0 must be finite with |theta0| < pi/2, got {self.theta0!r}")
        if not math.isfinite(float(self.theta_dot0)):
            raise ValueError(f"theta_dot0 must be finite, got {self.theta_dot0!r}")

    def as_dict(self) -> dict[str, Any]:
        """All settings, the model's included, as a JSON-friendly dict."""
        d = asdict(self)
        d["fallback_algorithms"] = list(self.fallback_algorithms)
        return d


_MODEL_FIELDS = tuple(f.name for f in fields(SDOFModel))
_SETTINGS_FIELDS = tuple(f.name for f in fields(OpenSeesSettings))


def make_settings(settings: OpenSeesSettings | None = None, **overrides: Any) -> OpenSeesSettings:
    """Return ``settings`` (or the defaults) with ``overrides`` applied.

    ``overrides`` may name any :class:`OpenSeesSettings` field and, for convenience, any
    :class:`~opsrock.model.SDOFModel` field (``delta``, ``theta_e_ratio``, ``table_points``,
    ``lever``), which then replaces that field of ``settings.model``.
    """
    base = OpenSeesSettings() if settings is None else settings
    if not isinstance(base, OpenSeesSettings):
        raise TypeError(f"settings must be an OpenSeesSettings, got {settings!r}")
    model_over = {k: overrides.pop(k) for k in list(overrides) if k in _MODEL_FIELDS}
    unknown = [k for k in overrides if k not in _SETTINGS_FIELDS]
    if unknown:
        raise TypeError(
            f"unknown OpenSees setting(s) {', '.join(map(repr, unknown))}; "
            f"valid: {', '.join(_SETTINGS_FIELDS + _MODEL_FIELDS)}"
        )
    if model_over:
        overrides["model"] = replace(overrides.get("model", base.model), **model_over)
    return replace(base, **overrides) if overrides else base


def critical_time_step(block: Block, model: SDOFModel | None = None) -> float:
    """Explicit (central-difference) stability limit ``dt_cr = 2 / omega_e`` (s).

    ``omega_e = sqrt(k_e / I_O)`` with the stiff-branch stiffness ``k_e = m g R sin(alpha) /
    theta_e``, i.e. ``dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha))`` = the stiff branch's
    period / pi.
    """
    model = SDOFModel() if model is None else model
    k_e = block.overturning_rotation_moment / model.theta_e(block)
    return 2.0 * math.sqrt(block.I_O / k_e)


def _potential(block: Block, theta: float) -> float:
    """Potential energy ``m g R [cos(alpha - |theta|) - cos(alpha)]`` (J) of the rigid block."""
    return block.mass * G * block.R * (math.cos(block.alpha - abs(theta)) - math.cos(block.alpha))


def _reachable_rotation(block: Block, energy: float) -> float:
    """Largest ``|theta|`` (rad) a freely rocking block of mechanical ``energy`` (J) can reach.

    With no excitation the spring is conservative and the damper only dissipates, so
    ``V(theta) <= E``: ``theta <= alpha - arccos(cos alpha + E / (m g R))``; ``inf`` when ``E``
    reaches the barrier ``m g R (1 - cos alpha)``.
    """
    c = math.cos(block.alpha) + energy / (block.mass * G * block.R)
    if c >= 1.0:
        return math.inf
    return block.alpha - math.acos(c)


def _define_time_series(excitation: Excitation, dt: float) -> None:
    """Define time series ``_SERIES`` giving the floor acceleration ``a(t)`` (m/s^2)."""
    if isinstance(excitation, HarmonicPulse):
        # Trig: factor * sin(2 pi (t - tStart) / period + shift) on [tStart, tEnd], zero outside:
        # exact for the half-sine, one-sine and one-cosine pulses.
        ops.timeSeries("Trig", _SERIES, 0.0, excitation.duration, excitation.T_p, "-factor", excitation.pfa,
                       "-shift", excitation.PHASE)
    elif isinstance(excitation, RectangularPulse):
        # Rectangular: factor on [tStart, tEnd], zero outside: exact.
        ops.timeSeries("Rectangular", _SERIES, 0.0, excitation.duration, "-factor", excitation.pfa)
    elif isinstance(excitation, Record):
        # Path with constant dt interpolates linearly and is zero after the last sample.
        ops.timeSeries("Path", _SERIES, "-dt", excitation.dt, "-values", *map(float, excitation.values))
    else:
        t = np.union1d(np.arange(0.0, excitation.duration + dt, dt), excitation.breakpoints())
        t = t[t <= excitation.duration]
        a = excitation.acceleration(t)
        t = np.append(t, excitation.duration + dt)
        a = np.append(a, 0.0)
        ops.timeSeries("Path", _SERIES, "-time", *map(float, t), "-values", *map(float, a))


def _define_analysis(settings: OpenSeesSettings, algorithm: str, constraints: str = "Plain") -> None:
    ops.constraints(constraints)
    ops.numberer("Plain")
    # BandGeneral: a general (non-symmetric-positive) solver; the spring's tangent is negative
    # beyond the stiff branch, so SPD solvers are wrong here.
    ops.system("BandGeneral")
    ops.test("NormDispIncr", settings.tol, settings.max_iter)
    _set_integrator(settings)
    _set_algorithm(settings, algorithm)
    ops.analysis("Transient")


def _set_integrator(settings: OpenSeesSettings) -> None:
    rho = float(settings.rho_inf)
    if settings.integrator == "newmark":
        ops.integrator("Newmark", 0.5, 0.25)
    elif settings.integrator == "hht":
        # OpenSees HHT alpha in [2/3, 1] (1 = Newmark); rho_inf = alpha / (2 - alpha).
        ops.integrator("HHT", 2.0 * rho / (1.0 + rho))
    elif settings.integrator == "generalized_alpha":
        # Chung & Hulbert (1993): alpha_m = (2 - rho) / (1 + rho), alpha_f = 1 / (1 + rho) in
        # OpenSees' convention (alpha = 1 means no shift).
        ops.integrator("GeneralizedAlpha", (2.0 - rho) / (1.0 + rho), 1.0 / (1.0 + rho))
    else:
        ops.integrator("CentralDifference")


def _set_algorithm(settings: OpenSeesSettings, algorithm: str) -> None:
    if settings.integrator == "central_difference":
        ops.algorithm("Linear")  # explicit: one solve with the mass matrix per step
    elif algorithm == "NewtonLineSearch":
        ops.algorithm("NewtonLineSearch")
    else:
        ops.algorithm(algorithm)




class _Failure(Exception):
    """Internal: a step that could not be recovered, or a numerical blow-up."""


def _build_sdof(block: Block, excitation: Excitation, settings: OpenSeesSettings) -> None:
    model = settings.model
    theta_tab, moment_tab = model.spring_table(block)
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.node(2, 0.0)
    ops.fix(1, 1)
    ops.mass(2, block.I_O)
    ops.uniaxialMaterial(
        "ElasticMultiLinear", _SPRING_MAT, 0.0, "-strain", *map(float, theta_tab), "-stress", *map(float, moment_tab)
    )
    ops.uniaxialMaterial("Viscous", _DAMPER_MAT, 1.0, 1.0)
    ops.element("zeroLength", _SPRING_ELE, 1, 2, "-mat", _SPRING_MAT, "-dir", 1)
    ops.element("zeroLength", _DAMPER_ELE, 1, 2, "-mat", _DAMPER_MAT, "-dir", 1)
    ops.parameter(_DAMPER_PARAM, "element", _DAMPER_ELE, "C")
    ops.updateParameter(_DAMPER_PARAM, 0.0)
    _define_time_series(excitation, settings.dt)
    ops.pattern("Plain", _PATTERN, _SERIES)
    ops.load(2, -model.lever_arm(block))


def _set_initial_state(block: Block, excitation: Excitation, settings: OpenSeesSettings, node: int, dof: int) -> None:
    th0, v0 = float(settings.theta0), float(settings.theta_dot0)
    if th0 == 0.0 and v0 == 0.0:
        return
    ops.setNodeDisp(node, dof, th0, "-commit")
    ops.setNodeVel(node, dof, v0, "-commit")
    # Consistent initial acceleration: I_O theta'' = -M_s(theta0) - Lambda a(0).
    th_tab, m_tab = settings.model.spring_table(block)
    m_s = float(np.interp(th0, th_tab, m_tab))
    a0 = float(excitation.acceleration(0.0))
    ops.setNodeAccel(node, dof, (-m_s - settings.model.lever_arm(block) * a0) / block.I_O, "-commit")


def solve(
    block: Block, excitation: Excitation, *, settings: OpenSeesSettings | None = None, **overrides: Any
) -> RockingResult:
    """Rocking response of ``block`` to ``excitation`` with the paper's OpenSees SDOF model.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation
        Floor acceleration (m/s^2): a one-sine pulse, a record, or any :class:`Excitation`.
    settings : OpenSeesSettings, optional
        Model and numerics; defaults to ``OpenSeesSettings()``.
    **overrides
        Any :class:`OpenSeesSettings` field, or ``delta``, ``theta_e_ratio``, ``table_points``,
        ``lever`` of the :class:`~opsrock.model.SDOFModel` (see :func:`make_settings`).

    Returns
    -------
    RockingResult
        ``solver="opensees"``. ``status="failed"`` with a reason if a step could not be recovered,
        the run blew up numerically ("unstable: ..."), or the end time came before rest.
    """
    s = make_settings(settings, **overrides)
    return _run(block, excitation, s, geometry=None)


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
    length ``R`` to a mass node carrying ``m`` on its translations and ``I_CM = m R^2 / 3`` on its
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
    s = make_settings(settings, **overrides)
    return _run(block, excitation, s, geometry=geometry)


def _build_lumped(block: Block, excitation: Excitation, settings: OpenSeesSettings, geometry: str) -> None:
    model = settings.model
    theta_tab, moment_tab = model.spring_table(block)
    m, R = block.mass, block.R
    ops.model("basic", "-ndm", 2, "-ndf", 3)
    ops.node(1, 0.0, 0.0)
    ops.node(2, 0.0, 0.0)  # pivot: translations fixed, rotation free
    ops.node(3, 0.0, R)  # centre of mass
    ops.fix(1, 1, 1, 1)
    ops.fix(2, 1, 1, 0)
    ops.mass(3, m, m, m * R**2 / 3.0)
    ops.uniaxialMaterial(
        "ElasticMultiLinear", _SPRING_MAT, 0.0, "-strain", *map(float, theta_tab), "-stress", *map(float, moment_tab)
    )
    ops.uniaxialMaterial("Viscous", _DAMPER_MAT, 1.0, 1.0)
    ops.element("zeroLength", _SPRING_ELE, 1, 2, "-mat", _SPRING_MAT, "-dir", 6)
    ops.element("zeroLength", _DAMPER_ELE, 1, 2, "-mat", _DAMPER_MAT, "-dir", 6)
    ops.parameter(_DAMPER_PARAM, "element", _DAMPER_ELE, "C")
    ops.updateParameter(_DAMPER_PARAM, 0.0)
    ops.rigidLink("beam", 2, 3)
    _define_time_series(excitation, settings.dt)
    ops.pattern("Plain", _PATTERN, _SERIES)
    ops.load(3, m * math.cos(block.alpha), 0.0, 0.0)


def _run(block: Block, excitation: Excitation, s: OpenSeesSettings, geometry: str | None) -> RockingResult:
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {block!r}")
    if not isinstance(excitation, Excitation):
        raise TypeError(f"excitation must be an Excitation, got {excitation!r}")
    settings_dict = s.as_dict()
    if geometry is not None:
        settings_dict["form"] = f"lumped_mass/{geometry}"
    t_wall = _time.perf_counter()
    if s.integrator == "central_difference" and s.explicit_step_check:
        dt_cr = critical_time_step(block, s.model)
        if s.dt >= dt_cr:
            return failed_result(
                SOLVER_NAME, settings_dict, block.alpha,
                f"unstable: explicit central difference with dt = {s.dt:.4g} s >= its critical step "
                f"dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha)) = {dt_cr:.4g} s",
            )
    # Eq. 4 after the settings checks: bad settings are refused whatever the pulse
    if (s.uplift_check and geometry is None and s.theta0 == 0.0 and s.theta_dot0 == 0.0
            and not can_uplift(block, s.model, excitation.pfa)):
        return seated_result(SOLVER_NAME, settings_dict, block.alpha, excitation.duration,
                             _time.perf_counter() - t_wall)
    log = console_to_log()
    start = _log_size(log)
    _CONSOLE["retries"] = 0
    _CONSOLE["recovered_by"] = {}
    result = _build_and_integrate(block, excitation, s, settings_dict, geometry, t_wall)
    diagnostics = {
        "opensees_messages": _count_messages(log, start),
        "retried_steps": int(_CONSOLE["retries"]),
        # how each retried step was recovered: "halving:<algorithm>" -> count; the default
        # algorithm and tolerance, with the step halved, or a fallback algorithm (same tol)
        "recovered_by": dict(_CONSOLE["recovered_by"]),
        "needed_fallback_algorithm": any(not k.endswith(":" + s.algorithm) for k in _CONSOLE["recovered_by"]),
        "opensees_log": log,
    }
    return dataclasses.replace(result, diagnostics=diagnostics)


def _build_and_integrate(block: Block, excitation: Excitation, s: OpenSeesSettings,
                         settings_dict: dict[str, Any], geometry: str | None, t_wall: float) -> RockingResult:
    with fresh_model():
        if geometry is None:
            _build_sdof(block, excitation, s)
            node, dof = 2, 1
        else:
            _build_lumped(block, excitation, s, geometry)
            node, dof = 2, 3
        # the lumped form's rigidLink is a multi-point constraint: Transformation handler
        _define_analysis(s, s.algorithm, "Plain" if geometry is None else "Transformation")
        _set_initial_state(block, excitation, s, node, dof)
        return _integrate(block, excitation, s, settings_dict, node, dof, t_wall)


def _integrate(
    block: Block,
    excitation: Excitation,
    s: OpenSeesSettings,
    settings_dict: dict[str, Any],
    node: int,
    dof: int,
    t_wall: float,
) -> RockingResult:
    model = s.model
    alpha = block.alpha
    band = model.band(block)
    band_len = 2.0 * band
    half_i = 0.5 * block.I_O
    mgR = block.mass * G * block.R
    cos_a = math.cos(alpha)
    barrier = mgR * (1.0 - cos_a)
    lam_pfa = abs(model.lever_arm(block)) * excitation.pfa
    duration = float(excitation.duration)
    t_end = duration + DEFAULT_TAIL if s.end_time is None else float(s.end_time)
    rest_margin = s.rest_tolerance * alpha
    dt, dt_min, adaptive = s.dt, s.dt_min, s.adaptive
    h_band_num = band_len / s.band_steps
    # rotation per step inside the band: a passage that starts at a turning point inside the band
    # is shorter than the band and gets band_steps steps of its own length
    h_len = h_band_num
    # adaptive: while the floor moves, the step also resolves the excitation itself
    dt_exc = min(dt, duration / s.excitation_steps) if duration > 0 else dt
    rec_dt = getattr(excitation, "dt", None)
    if rec_dt is not None:
        dt_exc = min(dt_exc, float(rec_dt))
    record_every = s.record_every
    stop_at_rest = s.stop_at_rest
    # explicit scheme: a step longer than the stiff branch's critical step, taken from inside
    # the branch, is unstable there (omega_e h > 2); its outcome is not an answer
    explicit = s.integrator == "central_difference" and s.stiff_branch_check
    dt_cr = critical_time_step(block, model) if explicit else math.inf

    analyze, node_disp, node_vel, update = ops.analyze, ops.nodeDisp, ops.nodeVel, ops.updateParameter
    ele_resp = ops.eleResponse

    th = float(node_disp(node, dof))
    thd = float(node_vel(node, dof))
    e_0 = half_i * thd * thd + _potential(block, th)
    w_in = 0.0  # upper bound of the work done by the floor (J)
    in_band = abs(th) <= band
    c_now = 0.0
    t = 0.0
    n_steps = 0
    impacts = ImpactLog()
    entry: tuple[float, float, bool] | None = None  # (time, velocity, side) of the last band entry
    n_alt = 0
    theta_max = abs(th)
    theta_e = model.theta_e(block)
    n_seated = 0
    rearm = model.tracks_passages()
    seat_on = s.integrator != "central_difference"
    uplift_level = model.edge_moment(block) / abs(model.lever_arm(block))  # m/s²
    lift_times = None  # record samples at which the floor can lift a seated block (s)
    if isinstance(excitation, Record):
        # imported here: the housner module pulls in scipy.integrate, which a pulse never needs (a
        # campaign's first case pays module imports inside its time budget)
        from opsrock.solvers.housner import first_exceedance
        lift_times = excitation.time[np.abs(excitation.values) > uplift_level]
    seat = Seat(model, block, excitation.acceleration)
    if rearm and in_band and abs(th) > theta_e and th * thd <= 0.0:
        # starting inside the band, at rest or heading back towards zero: a passage begins
        c_now = model.arm_damper(block, th, thd)
        ops.updateParameter(_DAMPER_PARAM, c_now)
        h_len = _passage_step(h_band_num, abs(th), s.band_steps, theta_e)
    # initial spring moment from the table: the element's force is only updated by a step
    th_tab, m_tab = model.spring_table(block)
    ts, ths, thds, ms, fds = [t], [th], [thd], [float(np.interp(th, th_tab, m_tab))], [0.0]
    cs = [0.0]  # damper coefficient at each recorded state (after its update: Eq. 7 at that state)
    element_forces = s.element_forces
    seated_state = False  # the current state was set by the seat, not by a step
    k_rec = 0

    def record() -> None:
        ts.append(t)
        ths.append(th)
        thds.append(thd)
        cs.append(c_now)
        if element_forces and seated_state:
            # a state set by the seat (no step since): the elements still hold the step's forces
            ms.append(float(np.interp(th, th_tab, m_tab)))
            fds.append(c_now * thd)
        elif element_forces:
            ms.append(ele_resp(_SPRING_ELE, "force")[1])
            fds.append(ele_resp(_DAMPER_ELE, "force")[1])

    def fail(reason: str) -> RockingResult:
        if not ts or ts[-1] != t:
            ts.append(t)
            ths.append(th)
            thds.append(thd)
        return failed_result(
            SOLVER_NAME,
            settings_dict,
            alpha,
            reason,
            time=np.array(ts),
            theta=np.array(ths),
            theta_dot=np.array(thds),
            n_steps=n_steps,
            wall_time_s=_time.perf_counter() - t_wall,
        )

    status_stop = ""
    while True:
        # --- choose the step --------------------------------------------------------------
        if adaptive:
            ath = abs(th)
            avel = abs(thd)
            h_rot = h_len if ath <= band else h_band_num
            if avel * dt <= h_rot:
                h = dt
            elif ath <= band:
                h = h_rot / avel
                if th * thd < 0.0:
                    if ath > theta_e:
                        # approaching zero: land about half a band step short of it, then cross
                        # the stiff branch in one step ending as far beyond zero as it started.
                        # The spring moment jumps from +M0 to -M0 there and the trapezoidal rule
                        # sees only the step ends: an asymmetric crossing gains or loses an
                        # impulse of up to M0 h, a symmetric one none.
                        if ath <= CROSSING_FRACTION * h_rot:
                            h = 2.0 * ath / avel
                        elif ath < (1.0 + CROSSING_FRACTION) * h_rot:
                            h = (ath - 0.5 * h_rot) / avel
                elif band - ath < 1.5 * h_rot:
                    # leaving: step just past the band edge, so the damper acts over the band
                    # only (a step overshooting the edge by a band step adds 1/band_steps of the
                    # band's dissipation)
                    h = (band - ath + EDGE_FRACTION * h_rot) / avel
            elif th * thd < 0.0:
                # approaching the band: halve the distance, then step just inside the edge, so
                # the damper is switched on where the band begins (Eq. 7)
                gap = ath - band
                if gap > 2.0 * h_band_num:
                    h = 0.5 * gap / avel
                else:
                    h = (gap + EDGE_FRACTION * h_band_num) / avel
            else:
                h = dt
            h_cap = dt_exc if t < duration else dt
            if h > h_cap:
                h = h_cap
            elif h < dt_min:
                h = dt_min
            if t < duration < t + h:
                h = duration - t  # land on the end of the excitation (a kink in a(t))
                if h < dt_min:
                    h = dt_min
            if ath <= theta_e and t < duration and lift_times is not None:
                # seated under a record: land on the instant the floor can lift the block
                # (|Lambda a| = M_s(theta_e)), as the scipy solver does; a step of omega_e h >> 1
                # across it lifts it late. Between samples a(t) is linear, so a crossing in
                # (t, t + h] ends at a sample above the level: only then is it searched for.
                j = int(np.searchsorted(lift_times, t, side="right"))
                if j < lift_times.size and lift_times[j] - rec_dt < t + h:
                    t_up = first_exceedance(excitation, uplift_level, t, min(t + h, lift_times[j]), h)
                    if t_up is not None and t_up > t + dt_min:
                        h = t_up - t
        else:
            h = dt
        # --- advance ------------------------------------------------------------------------
        if analyze(1, h) == 0:
            n_steps += 1
        else:
            try:
                n_steps += _recover(s, h)
            except _Failure as exc:
                return fail(f"step at t = {t:.6g} s (dt = {h:.3g} s) did not converge: {exc}")
        if h >= dt_cr and abs(th) <= theta_e:
            return fail(
                f"unstable: explicit central difference stepped {h:.4g} s from inside the stiff branch "
                f"(|theta| <= theta_e) at t = {t:.6g} s, above its critical step dt_cr = {dt_cr:.4g} s"
            )
        t += h
        th_prev, thd_prev = th, thd
        th = node_disp(node, dof)
        thd = node_vel(node, dof)
        if not (math.isfinite(th) and math.isfinite(thd)):
            return fail(f"unstable: non-finite state at t = {t:.6g} s (theta = {th!r}, theta_dot = {thd!r})")
        ath = abs(th)
        if ath > theta_max:
            theta_max = ath
        if (th > 0.0) != (th_prev > 0.0):
            n_alt += 1
            if n_alt >= SAWTOOTH_STEPS:
                return fail(
                    f"unstable: theta changed sign at {n_alt} consecutive steps up to t = {t:.6g} s "
                    f"(dt = {h:.3g} s): a numerical sawtooth, not rocking"
                )
        else:
            n_alt = 0
        # --- physical plausibility: energy can only come from the floor --------------------
        if t <= duration + h:
            w_in += lam_pfa * abs(th - th_prev)
        energy = half_i * thd * thd + mgR * (math.cos(alpha - ath) - cos_a)
        if energy > UNSTABLE_ENERGY_FACTOR * (e_0 + w_in) + UNSTABLE_ENERGY_FLOOR * barrier:
            return fail(
                f"unstable: mechanical energy {energy:.4g} J at t = {t:.6g} s exceeds the initial energy "
                f"plus the floor's work ({e_0 + w_in:.4g} J); numerical blow-up (theta = {th:.4g} rad)"
            )
        # --- seated: drop the stiff branch's free oscillation, as the scipy solver does ----------
        # (implicit schemes only: the explicit scheme's stiff-branch instability above its critical
        # step must stay visible; without the seat, fixed-step Newmark at 1e-4 s was up to 0.45 alpha
        # off on the paper pulses with the per-passage damper, 3.1 % with it)
        seated_state = seat_on and ath <= theta_e and seat.captures(t, th, thd)
        if seated_state:
            th, thd = seat.theta_qs(t), 0.0
            ops.setNodeDisp(node, dof, th, "-commit")
            ops.setNodeVel(node, dof, 0.0, "-commit")
            ops.setNodeAccel(node, dof, 0.0, "-commit")
            ops.domainChange()  # the integrator keeps its own state vectors: re-read the domain's
            ath = abs(th)
        # --- damper (Eq. 7-8): set on entering the band, zero outside ----------------------
        switched = False
        if ath <= band:
            if not in_band:
                in_band = True
                entry = (t, thd, th > 0.0)
                c_now = model.arm_damper(block, th, thd)
                update(_DAMPER_PARAM, c_now)
                switched = True
                h_len = h_band_num
            elif rearm and seated_state and c_now != 0.0:
                # seated (the seat just dropped the branch's oscillation): no passage under way
                c_now = 0.0
                update(_DAMPER_PARAM, 0.0)
                switched = True
            elif rearm and ath > theta_e and th * thd < 0.0 and th_prev * thd_prev > 0.0:
                # turned inside the band in this step: a new passage, the damper is re-armed
                # with the state at the step's end (heading back towards zero)
                c_now = model.arm_damper(block, th, thd)
                update(_DAMPER_PARAM, c_now)
                switched = True
                h_len = _passage_step(h_band_num, ath, s.band_steps, theta_e)
        elif in_band:
            in_band = False
            if entry is not None and (th > 0.0) != entry[2]:  # left on the other side: an impact
                impacts.add(entry[0], entry[1], thd)
            entry = None
            if c_now != 0.0:
                c_now = 0.0
                update(_DAMPER_PARAM, 0.0)
                switched = True
        if switched and adaptive and thd != 0.0:
            # Newmark's next step averages the damper force at its start, computed with the old
            # coefficient, with the one at its end: half a step of stale damping (measured: an
            # exit step of 1 ms took 0.08 rad/s off 1.35 rad/s). A tiny step re-establishes
            # equilibrium with the new coefficient at negligible cost.
            h_reset = min(dt, max(dt_min, RESET_FRACTION * h_len / abs(thd)))
            if analyze(1, h_reset) != 0:
                try:
                    n_steps += _recover(s, h_reset)
                except _Failure as exc:
                    return fail(f"reset step at t = {t:.6g} s did not converge: {exc}")
            else:
                n_steps += 1
            t += h_reset
            th = node_disp(node, dof)
            thd = node_vel(node, dof)
            seated_state = False
            ath = abs(th)
            if ath > theta_max:
                theta_max = ath
        # --- stopping ------------------------------------------------------------------------
        if ath >= OVERTURNING_ANGLE:
            status_stop = "overturned"
            break
        # rest: excitation over, block inside the hump (|theta| < alpha; beyond it a block with
        # less than the barrier energy falls over) and unable to pass its peak again
        # Inside the stiff branch the step-end velocity is not the physical one (the branch is
        # crossed within a step), so the energy test waits for a step that ends outside it; a
        # block seated for good stays inside for SEATED_STEPS steps in a row.
        if ath <= theta_e:
            n_seated += 1
        else:
            n_seated = 0
        if stop_at_rest and t >= duration and ath < alpha and (
            (ath > theta_e and energy <= mgR * (math.cos(alpha - min(theta_max + rest_margin, alpha)) - cos_a))
            or n_seated >= SEATED_STEPS
        ):
            status_stop = "rest"
            break
        if t >= t_end:
            if not stop_at_rest:
                status_stop = "end_time"
                break
            return fail(
                f"end_time = {t_end:.6g} s reached before the block overturned or came to rest "
                f"(theta = {th:.4g} rad, theta_dot = {thd:.4g} rad/s); raise end_time"
            )
        k_rec += 1
        if k_rec >= record_every:
            k_rec = 0
            record()
    if ts[-1] != t:
        record()
    theta_arr = np.array(ths)
    thd_arr = np.array(thds)
    if element_forces:
        spring, damper = np.array(ms), np.array(fds)
    else:
        spring = np.interp(theta_arr, th_tab, m_tab)
        damper = np.array(cs) * thd_arr
    overturned = status_stop == "overturned"
    return RockingResult(
        solver=SOLVER_NAME,
        settings=settings_dict,
        alpha=alpha,
        time=np.array(ts),
        theta=theta_arr,
        theta_dot=thd_arr,
        theta_max=float(theta_max),
        overturned=overturned,
        rocked=bool(theta_max > ROCKED_THETA_E_MULTIPLE * model.theta_e(block)),
        n_steps=n_steps,
        wall_time_s=_time.perf_counter() - t_wall,
        spring_moment=spring,
        damper_force=damper,
        n_impacts=len(impacts),
        impacts=impacts.freeze(),
    )


def _passage_step(h_band: float, distance: float, band_steps: int, theta_e: float) -> float:
    """Rotation per step (rad) of a passage starting ``distance`` (rad) from zero inside the band:
    ``band_steps`` steps over its length ``2 distance``, no more than a band step ``h_band`` and no
    less than :data:`MIN_PASSAGE_STEP_RATIO` ``theta_e``."""
    return max(min(h_band, 2.0 * distance / band_steps), MIN_PASSAGE_STEP_RATIO * theta_e)


def _recover(s: OpenSeesSettings, h: float) -> int:
    """Advance by ``h`` after a failed step: halve the step, then try the fallback algorithms.

    Returns the number of sub-steps taken; raises :class:`_Failure` with the reason otherwise.
    """
    _CONSOLE["retries"] += 1
    tried = []
    for algorithm in (s.algorithm, *s.fallback_algorithms):
        if algorithm != s.algorithm:
            _set_algorithm(s, algorithm)
        try:
            for k in range(1, s.max_halvings + 1):
                sub = h / 2**k
                if sub < s.dt_min:
                    break
                if _advance_in_substeps(sub, 2**k):
                    key = f"halving:{algorithm}"
                    _CONSOLE["recovered_by"][key] = _CONSOLE["recovered_by"].get(key, 0) + 1
                    return 2**k
            tried.append(algorithm)
        finally:
            if algorithm != s.algorithm:
                _set_algorithm(s, s.algorithm)
    raise _Failure(
        f"no convergence with {', '.join(tried) or s.algorithm} after up to {s.max_halvings} step halvings "
        f"(tol = {s.tol:g}, max_iter = {s.max_iter})"
    )


def _advance_in_substeps(sub: float, n: int) -> bool:
    """Take ``n`` steps of ``sub``; on a failure part-way, give up (the domain keeps the
    committed sub-steps, so the caller must not retry from the start)."""
    for i in range(n):
        if ops.analyze(1, sub) != 0:
            if i > 0:
                raise _Failure(f"sub-step {i + 1} of {n} (dt = {sub:.3g} s) failed after earlier ones committed")
            return False
    return True


__all__ = [
    "ALGORITHMS",
    "INTEGRATORS",
    "OpenSeesSettings",
    "ROCKED_THETA_E_MULTIPLE",
    "critical_time_step",
    "make_settings",
    "opensees_log_path",
    "solve",
    "solve_lumped_mass",
]
