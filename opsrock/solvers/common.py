"""What the solvers share: the contract, the settings base, the one settings merge, the run skeleton,
the block's energy, the uplift search and the recorded history.

The contract (every solver registered in :data:`opsrock.solvers.SOLVERS` keeps it; tests/model/solvers/
test_contract.py checks it)
-----------------------------------------------------------------------------------------------------
Every solver is a package ``opsrock.solvers.<name>`` with ``settings.py`` (its frozen settings dataclass,
derived from :class:`SolverSettings`), ``solver.py`` (its :func:`solve` and the run) and, where compiled,
``kernel.py``. Its one entry is::

    solve(block, excitation, settings=None, **overrides) -> RockingResult

* ``block`` is a :class:`~opsrock.block.Block`; ``excitation`` an
  :class:`~opsrock.excitations.Excitation` the solver takes, or None: a still floor (free rocking from
  the start state ``theta0``, ``theta_dot0`` of the settings, for ``end_time`` or until rest by the
  solver's tail rule). ``settings`` is the solver's settings object (None: its defaults); keyword
  ``overrides`` replace single fields (:func:`make_settings`, the one merge).
* Every settings class derives from :class:`SolverSettings` and so accepts its fields with the same
  names and units: start state (``theta0`` rad, ``theta_dot0`` rad/s), end (``end_time`` s, ``tail``,
  ``max_free_time`` s, ``stop_at_rest``), ``record`` (keep the histories), the step limit ``max_steps``
  (a count of steps; None: the solver's own default) and the wall-clock limit ``max_wall_time`` (s). A
  solver that does not model a value of a shared field refuses it when the settings are made
  (:class:`~opsrock.errors.InputError` naming the field), never ignores it.
* It returns a :class:`~opsrock.result.RockingResult` with the fields every solver fills (``solver``,
  ``settings``, ``alpha``, ``time``, ``theta``, ``theta_dot``, ``theta_max``, ``overturned``, ``rocked``,
  ``status``, ``reason``, ``failure``, ``n_steps``, ``n_impacts``, ``wall_time_s``). A run that cannot
  give a verdict is *returned*, not raised: ``status="failed"``, ``failure`` one of
  :data:`opsrock.solvers.status.FAILURE_KINDS` (``"nonfinite"``, ``"max_steps"``, ``"timeout"``, ...)
  and a ``reason`` in words; ``failure`` is None when ``status="ok"``.
* It raises only for bad input, before any work: :class:`~opsrock.errors.InputTypeError` (a block,
  excitation or settings of the wrong type), :class:`~opsrock.errors.InputError` (a value out of range)
  and its subclass :class:`~opsrock.errors.ModelNotSupported` for what the solver does not model
  (friction on a no-slip solver, vertical floor motion, free rocking, a restitution law), as the
  registry declares it (:class:`opsrock.solvers.SolverInfo`).
* Statuses are shared (:mod:`opsrock.solvers.status`): the compiled kernels return its integer codes
  and write the one output layout (``OUT_*``) defined there.
* Limits: ``max_steps`` counts the solver's steps (integrator steps, time steps, departures from rest);
  ``max_wall_time`` is checked by the Python solvers between steps (scipy segments, OpenSees steps); a
  compiled kernel cannot be interrupted and is bounded by ``max_steps``, so its run is reported
  ``"timeout"`` when it returns past ``max_wall_time``, as the campaign reports a case past its process
  timeout: the same failure kind either way.

The run skeleton is written once (:class:`SolverRun`, as scipy's ``OdeSolver.step`` around
``_step_impl``): the prelude (types, start state, wall clock), the solver's own stepping
(:meth:`SolverRun._run_impl`), then the result with the shared timeout rule; :class:`EventDrivenSolver`
is its event-driven specialisation for the scipy solvers.

Nothing here knows a particular solver; each solver module imports from here and from nowhere
else among the solvers (as scipy's ``_ivp`` solvers share ``common.py``).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time as _time
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any, ClassVar, Mapping

import numpy as np

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE, G
from opsrock.errors import InputError, InputTypeError, ModelNotSupported, UnknownSettingError
from opsrock.excitations.plan import PlanMotion
from opsrock.limits import bool_fields, initial_state, int_at_least, one_of, positive_finite, real_number
from opsrock.result import ImpactLog, RockingResult, failed_result
from opsrock.solvers.registry import check_model
from opsrock.solvers.status import INTEGRATOR, MAX_IMPACTS, MAX_STEPS, NONFINITE, REASONS, TIMEOUT, failure_of

#: :func:`scipy.integrate.solve_ivp` methods the scipy solvers accept (``method``, ``stiff_method``). Between events both equations are
#: smooth and non-stiff (rates ``p`` and ``c_D / I_O``), so explicit high-order methods are the efficient
#: choice; the implicit ones are there for cross-checks and for the SDOF model's stiff branch.
#: Wall-clock seconds of one segment of the event-driven scipy solvers (:class:`EventDrivenSolver`; a record
#: has one segment per sample interval): measured 0.5 ms (housner, a 32 000-sample record, one core).
SECONDS_PER_SEGMENT: float = 5e-4

#: A single solve expected to run longer than this (s) is announced before it starts (``opsrock simulate``).
LONG_SOLVE_S: float = 30.0


def event_driven_estimate(excitation: Any) -> float:
    """Expected wall-clock time (s) of an event-driven solver on ``excitation``: one segment per breakpoint
    (a record's samples) at :data:`SECONDS_PER_SEGMENT` each; more when the block rocks hard (impacts add
    segments)."""
    if excitation is None:
        return 0.0
    return len(excitation.breakpoints()) * SECONDS_PER_SEGMENT


IVP_METHODS: tuple[str, ...] = ("DOP853", "RK45", "RK23", "Radau", "LSODA", "BDF")

#: What happens after the excitation ends when ``end_time`` is None: ``"rest"`` integrates the free
#: rocking until the block is at rest again (or the cap ``max_free_time`` is reached); ``"peak"`` stops at
#: the first turning point after the excitation ends with ``|theta| < alpha``: from there on the energy
#: only falls (impacts dissipate, nothing feeds it), so no later peak can exceed it and the verdict and
#: ``theta_max`` are already final.
TAILS: tuple[str, ...] = ("rest", "peak")


# --- settings ---------------------------------------------------------------------------------------
def setting_names(cls: type) -> dict[str, str | None]:
    """Every setting name ``cls`` accepts, with the nested field that holds it (None: ``cls`` itself).

    A field whose default is itself a dataclass (the SDOF solvers' ``model``) lends its fields:
    ``delta`` reaches ``settings.model.delta``.
    """
    names: dict[str, str | None] = {}
    defaults = cls()
    for f in dataclasses.fields(cls):
        names[f.name] = None
        value = getattr(defaults, f.name)
        if dataclasses.is_dataclass(value):
            for g in dataclasses.fields(value):
                names.setdefault(g.name, f.name)
    return names


@functools.cache
def _names_of(cls: type) -> Mapping[str, str | None]:
    """:func:`setting_names` worked out once per class, read-only: it builds the class's defaults, 0.07 ms of every
    3-D case of the directionality study, whose settings name ``tail`` (issue 43)."""
    return MappingProxyType(setting_names(cls))


def make_settings(cls: type, settings: Any = None, overrides: dict[str, Any] | None = None) -> Any:
    """``settings`` (an instance of ``cls``, or its defaults) with ``overrides`` applied: the one
    place where solver settings are merged.

    Parameters
    ----------
    cls : type
        The solver's frozen settings dataclass.
    settings : cls or None
        The starting settings; None: ``cls()``.
    overrides : dict, optional
        Field values to replace. A field of a nested dataclass (``delta`` of the SDOF model) may be
        named directly; a table (dict) given for a dataclass field becomes that dataclass, an array
        (list) given for a tuple field a tuple, so settings read from TOML merge as given in code.

    Raises
    ------
    InputTypeError
        ``settings`` of another type; :class:`~opsrock.errors.UnknownSettingError` (one) for an unknown
        name (its ``key``; the message lists the known ones).
    InputError
        A value the settings class refuses (its message names the field).
    """
    base = cls() if settings is None else settings
    if not isinstance(base, cls):
        raise InputTypeError(f"settings must be a {cls.__name__}, got {settings!r}")
    if not overrides:
        return base
    names = _names_of(cls)
    unknown = sorted(set(overrides) - set(names))
    if unknown:
        raise UnknownSettingError(unknown[0], f"unknown setting(s) {', '.join(map(repr, unknown))} of "
                                              f"{cls.__name__}; known: {', '.join(sorted(names))}")
    direct: dict[str, Any] = {}
    nested: dict[str, dict[str, Any]] = {}
    for key, value in overrides.items():
        owner = names[key]
        if owner is not None:
            nested.setdefault(owner, {})[key] = value
            continue
        current = getattr(base, key)
        if isinstance(value, dict) and dataclasses.is_dataclass(current):
            value = dataclasses.replace(current, **value)
        elif isinstance(value, list) and isinstance(current, tuple):
            value = tuple(value)
        direct[key] = value
    for owner, values in nested.items():
        direct[owner] = dataclasses.replace(direct.get(owner, getattr(base, owner)), **values)
    return dataclasses.replace(base, **direct)


def settings_record(settings: Any) -> dict[str, Any]:
    """A settings dataclass as plain JSON data, for :attr:`RockingResult.settings` (tuples as lists,
    ``inf`` as the string ``"inf"``)."""

    def plain(v: Any) -> Any:
        if isinstance(v, dict):
            return {k: plain(x) for k, x in v.items()}
        if isinstance(v, (list, tuple)):
            return [plain(x) for x in v]
        if isinstance(v, float) and math.isinf(v):
            return "inf"
        return v

    return plain(dataclasses.asdict(settings))


@dataclass(frozen=True)
class SolverSettings:
    """The settings every solver shares: the base of every solver's settings dataclass.

    A solver states its own defaults for these fields by redeclaring them (``HousnerFastSettings``:
    ``tail = "peak"``) and refuses, in its ``__post_init__``, a value it does not model
    (:func:`refuse_value`).

    Parameters
    ----------
    theta0 : float
        Initial rotation (rad), ``|theta0| < pi/2``. Default 0 (seated). With ``excitation=None`` this is
        free rocking from a start state.
    theta_dot0 : float
        Initial angular velocity (rad/s). Default 0.
    end_time : float or None
        Hard end of the run (s). None: the excitation's duration and then the free-rocking tail
        (``tail``, ``max_free_time``). With ``excitation=None`` (a still floor) the span of free rocking.
    tail : str
        What follows the excitation when ``end_time`` is None, one of :data:`TAILS`: ``"rest"`` (until
        the block is at rest, at most ``max_free_time``) or ``"peak"`` (until the first turning point
        below ``alpha``: ``theta_max`` and the verdict are then final).
    max_free_time : float or None
        Longest tail after the excitation (s). None: the solver's default (its settings class says it).
    stop_at_rest : bool
        Stop once the block is at rest after the excitation (True, default); False: run to the end time.
    record : bool
        Keep the time histories (default True); False keeps the peaks and counts only.
    max_steps : int or None
        Largest number of steps of the run (a count: integrator steps, time steps, departures from rest;
        the one unit of every solver's step limit), past which it fails with ``failure="max_steps"``.
        None: the solver's default (unlimited for the scipy and OpenSees solvers).
    max_wall_time : float
        Largest wall-clock time of the run (s), past which it fails with ``failure="timeout"``. Default
        ``inf``. See the contract (:mod:`opsrock.solvers.common`) for how compiled kernels honour it.
    """

    theta0: float = 0.0
    theta_dot0: float = 0.0
    end_time: float | None = None
    tail: str = "rest"
    max_free_time: float | None = None
    stop_at_rest: bool = True
    record: bool = True
    max_steps: int | None = None
    max_wall_time: float = math.inf

    def __post_init__(self) -> None:
        bool_fields(self)
        initial_state(self.theta0, self.theta_dot0)
        if self.end_time is not None:
            positive_finite("end_time", self.end_time)
        one_of("tail", self.tail, TAILS)
        if self.max_free_time is not None:
            positive_finite("max_free_time", self.max_free_time)
        for name in ("stop_at_rest", "record"):
            if not isinstance(getattr(self, name), bool):
                raise InputTypeError(f"{name} must be a bool, got {getattr(self, name)!r}")
        if self.max_steps is not None:
            int_at_least("max_steps", self.max_steps, 1)
        if not real_number("max_wall_time", self.max_wall_time) > 0.0:
            raise InputError(f"max_wall_time must be positive, got {self.max_wall_time!r}")

    @property
    def seated_start(self) -> bool:
        """True if the run starts from rest (``theta0 = theta_dot0 = 0``)."""
        return self.theta0 == 0.0 and self.theta_dot0 == 0.0


#: The shared fields (:class:`SolverSettings`), by name.
SHARED_SETTINGS: tuple[str, ...] = tuple(f.name for f in dataclasses.fields(SolverSettings))


def refuse_value(solver: str, settings: SolverSettings, name: str, allowed: tuple) -> None:
    """Refuse a shared setting ``name`` whose value the solver does not model (only ``allowed`` ones).

    Raises
    ------
    ModelNotSupported
        Naming the solver, the setting and its value.
    """
    value = getattr(settings, name)
    if value not in allowed:
        raise ModelNotSupported(f"solver {solver!r} does not model {name} = {value!r}; it takes "
                                f"{' or '.join(map(repr, allowed))}")


@dataclass(frozen=True)
class ScipySettings(SolverSettings):
    """Numerical settings shared by the two scipy solvers (``housner``, ``sdof``): those of
    :class:`SolverSettings` and

    Parameters
    ----------
    method : str
        :func:`scipy.integrate.solve_ivp` method, one of :data:`IVP_METHODS`. Default ``"DOP853"``.
    rtol : float
        Relative tolerance of the integrator (dimensionless), in (0, 1). Default 1e-10: the closed-form
        tests compare to 1e-7, and these solvers are the references of the others.
    atol : float
        Absolute tolerance on ``theta`` (rad); ``atol · p`` is used on ``theta'`` (rad/s).
    max_free_time : float
        Cap on the free-rocking tail after the excitation ends (s). Default 60 s: a slender block of
        R = 1 m rocks down from alpha to rest in a few seconds; a block still rocking after the cap has
        its ``theta_max`` final anyway (energy only falls after the excitation).
    max_step : float
        Largest integrator step (s). Default ``inf`` (the error control decides; excitation breakpoints
        are always stepped on exactly).
    max_impacts : int
        Largest number of impacts before the run is reported as failed. Default 10 000 (free rocking
        from alpha to rest takes 100-300).
    scan_step : float or None
        Grid spacing (s) on which a seated block's uplift is searched (:func:`first_exceedance`). None:
        ``duration / 2000``.
    dense_step : float or None
        If set (s), the history also holds the integrator's dense output (its own interpolant, of the
        method's order) every ``dense_step`` inside each step, for figures that must not show the long
        straight chords of large steps. None (default): accepted steps and events only.
    """

    max_free_time: float | None = 60.0
    method: str = "DOP853"
    rtol: float = 1e-10
    atol: float = 1e-12
    max_step: float = math.inf
    max_impacts: int = 10_000
    scan_step: float | None = None
    dense_step: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        one_of("method", self.method, IVP_METHODS)
        if not 0.0 < real_number("rtol", self.rtol) < 1.0:
            raise InputError(f"rtol must lie in (0, 1), got {self.rtol!r}")
        positive_finite("atol", self.atol)
        if not (real_number("max_step", self.max_step) > 0.0):
            raise InputError(f"max_step must be positive, got {self.max_step!r}")
        int_at_least("max_impacts", self.max_impacts, 1)
        if self.scan_step is not None:
            positive_finite("scan_step", self.scan_step)
        if self.dense_step is not None:
            positive_finite("dense_step", self.dense_step)

    @property
    def free_time(self) -> float:
        """The tail's cap (s): ``max_free_time``, 60 s when None."""
        return 60.0 if self.max_free_time is None else float(self.max_free_time)


# --- the run skeleton ----------------------------------------------------------------------------------
def check_inputs(solver: str, block: object, excitation: object, settings: SolverSettings) -> Block:
    """The prelude's checks, before any work: ``block`` a :class:`Block` (else :class:`InputTypeError`),
    nothing the solver does not model (:func:`opsrock.solvers.registry.check_model`, from its registry
    entry), and with ``excitation=None`` (a still floor) a start state that moves. Returns ``block``.

    Raises
    ------
    InputTypeError, ModelNotSupported, InputError
    """
    if not isinstance(block, Block):
        raise InputTypeError(f"block must be a Block, got {block!r}")
    check_model(solver, block, excitation)
    if excitation is None and settings.seated_start:
        raise InputError("excitation None (a still floor) needs a start state: theta0 or theta_dot0 != 0")
    return block


def timed_out(result: RockingResult, settings: SolverSettings) -> RockingResult:
    """``result``, failed with ``failure="timeout"`` if its run took longer than ``max_wall_time``."""
    limit = settings.max_wall_time
    if result.status != "ok" or not result.wall_time_s > limit:
        return result
    return dataclasses.replace(
        result, status="failed", failure="timeout", overturned=False, rocked=False,
        reason=f"{REASONS[TIMEOUT]} ({result.wall_time_s:.3g} s > {limit:g} s)")


def at_most_overturned(result: RockingResult) -> RockingResult:
    """``result`` with ``theta_max`` (rad) at most :data:`~opsrock.constants.OVERTURNING_ANGLE`, and equal to it
    when the block overturned, in every solver alike: past pi/2 the block lies on its side, and a solver that
    steps on after the crossing (``friction`` reported 1.585 rad for a block that overturned during the
    excitation) measures its fall, not its rocking; a box's ``plan.tilt_max``, the same peak, alike. The time
    history is left as computed."""
    if not result.overturned and not result.theta_max > OVERTURNING_ANGLE:
        return result
    plan = getattr(result, "plan", None)
    if plan is not None and plan.tilt_max > OVERTURNING_ANGLE:
        plan = dataclasses.replace(plan, tilt_max=OVERTURNING_ANGLE)
    return dataclasses.replace(result, theta_max=OVERTURNING_ANGLE, plan=plan)


def first_nonfinite_sample(excitation: Any) -> float | None:
    """Time (s) of the first non-finite sample of a sampled floor motion (its ``values`` and, where given,
    ``vertical``, m/s², every ``dt`` s), or None: finite, not sampled (a pulse's closed form), or absent. A
    :class:`~opsrock.excitations.plan.PlanMotion` is checked component by component: the first component's
    first non-finite sample, else the second's."""
    if isinstance(excitation, PlanMotion):
        for part in (excitation.first, excitation.second):
            bad = first_nonfinite_sample(part)
            if bad is not None:
                return bad
        return None
    values, dt = getattr(excitation, "values", None), getattr(excitation, "dt", None)
    if values is None or dt is None:
        return None
    first = None
    for samples in (values, getattr(excitation, "vertical", None)):
        if samples is None:
            continue
        bad = np.flatnonzero(~np.isfinite(np.asarray(samples, dtype=float)))
        if bad.size:
            first = bad[0] if first is None else min(first, bad[0])
    return None if first is None else float(first) * float(dt)


#: The ``(kernel, variant)`` specialisations :meth:`SolverRun.compiled_call` has found compiled or compiled in this
#: process (a set look-up a call, once each is known).
_SPECIALISED: set[tuple[Any, str]] = set()


class SolverRun:
    """The run skeleton of every solver, written once (as scipy's ``OdeSolver.step`` around ``_step_impl``).

    :meth:`run`: the prelude (done in ``__init__``: the settings are already merged and checked by
    :func:`make_settings`; the wall clock starts), the solver's own :meth:`_run_impl`, then the shared
    timeout rule (:func:`timed_out`). A subclass gives :attr:`name` and :meth:`_run_impl`.

    Parameters
    ----------
    block : Block
    excitation : Excitation or None
        Floor acceleration (m/s²) as a function of time (s); None: a still floor.
    settings : SolverSettings
        The solver's settings (merged).
    """

    #: Name written into :attr:`RockingResult.solver`.
    name: ClassVar[str] = ""
    #: Whether a compiled kernel has run in this solve yet (:meth:`compiled_call`'s clock rule).
    kernel_called: bool = False

    def __init__(self, block: Block, excitation: Any, settings: SolverSettings) -> None:
        self.settings = settings
        self.block, self.excitation = block, excitation
        self.t_wall = _time.perf_counter()

    def elapsed(self) -> float:
        """Wall-clock time since the solve started (s)."""
        return _time.perf_counter() - self.t_wall

    def compiled_call(self, kernel: Any, *args: Any, variant: str | None = None) -> Any:
        """``kernel(*args)`` for a compiled (numba) kernel, compiled first, outside the wall clock, when this
        process has not compiled it yet: ``wall_time_s`` is the solve's, never the compilation's (a first 3-D solve
        reported 345.5 s, of which 0.1 s was the solve) nor the loading of numba's cache.

        Before the solve's first kernel call the clock restarts after the compile: the solver's set-up before it
        may itself have compiled small helpers on their first call (housner_fast's case parameters and forcing:
        1.4 s of a first solve). A kernel compiled later, mid-solve (friction's flight), moves the clock on by its
        compile's duration, so the solve's time so far is kept.

        ``variant`` names the specialisation ``args`` need of a kernel numba compiles for more than one kind of
        argument (rigid3d's: finite and infinite friction); each is compiled the first time it is needed, as above.
        Without it, a kernel with any compiled signature is taken as ready."""
        if variant is None:
            fresh = not getattr(kernel, "signatures", True)
        elif (kernel, variant) in _SPECIALISED:
            fresh = False
        else:
            import numba

            fresh = tuple(numba.typeof(a) for a in args) not in kernel.signatures
        if fresh:
            import numba

            from opsrock.solvers._compile import fewer_collections

            start = _time.perf_counter()
            with fewer_collections():  # about a tenth of a compile's CPU was Python's garbage collector (issue 43)
                kernel.compile(tuple(numba.typeof(a) for a in args))
            now = _time.perf_counter()
            self.t_wall = self.t_wall + (now - start) if self.kernel_called else now
        if variant is not None:
            _SPECIALISED.add((kernel, variant))
        self.kernel_called = True
        return kernel(*args)

    def run(self) -> RockingResult:
        """Solve and return the result (failed, with its ``failure`` kind, where the run could not finish).

        A floor motion with a non-finite sample fails at once with ``failure="nonfinite"``, in every
        solver alike: a seated block compares the floor's acceleration with its uplift level, and a NaN
        compares false, so without this check it would sit out the NaN and report a verdict."""
        bad = first_nonfinite_sample(self.excitation)
        if bad is not None:
            return failed_result(self.name, {"solver": self.name, **settings_record(self.settings)}, self.block.alpha,
                                 f"{REASONS[NONFINITE]}: the floor motion is not finite at t = {bad:.6g} s",
                                 wall_time_s=self.elapsed(), failure=failure_of(NONFINITE))
        return at_most_overturned(timed_out(self._run_impl(), self.settings))

    def _run_impl(self) -> RockingResult:
        """The solver's own run."""
        raise NotImplementedError


class StopRun(Exception):
    """Raised by a step of :class:`EventDrivenSolver` to end the run: with a reason, the run failed
    (``failure``: its kind, :data:`opsrock.solvers.status.FAILURE_KINDS`)."""

    def __init__(self, reason: str = "", failure: str = "error") -> None:
        super().__init__(reason)
        self.reason = reason
        self.failure = failure


def _still(t: Any) -> Any:
    """The acceleration of a still floor (m/s²) at ``t`` (s): zero, scalar or array as ``t``."""
    return 0.0 * np.asarray(t, dtype=float) if np.ndim(t) else 0.0


class EventDrivenSolver(SolverRun):
    """The event-driven specialisation of :class:`SolverRun`: the skeleton of the scipy solvers.

    The prelude (settings, times, breakpoints, history, impact log), then a loop that alternates two
    phases until the end time: :meth:`_seated_step` (a block at rest: find when the floor lifts it) and
    :meth:`_flight_step` (a rocking block: one segment between events), and the result. A subclass gives
    :attr:`name`, the two phases, :meth:`_start` and :meth:`_finish`; a phase ends the run by raising
    :class:`StopRun` (with a reason: a failed result that keeps the history computed so far). The shared
    limits (``max_steps``, ``max_wall_time``, ``max_impacts``) are checked here.

    Parameters
    ----------
    block : Block
    excitation : Excitation or None
        Floor acceleration (m/s²) as a function of time (s); None: a still floor.
    settings : ScipySettings
        The solver's settings (already merged, :func:`make_settings`).
    """

    #: Whether the history keeps the damper coefficient of each state (the SDOF model).
    with_damping: ClassVar[bool] = False

    def __init__(self, block: Block, excitation: Any, settings: ScipySettings) -> None:
        super().__init__(block, excitation, settings)
        s = settings
        self.settings_dict = settings_record(s)
        self.alpha, self.p = block.alpha, block.p
        self.duration = 0.0 if excitation is None else float(excitation.duration)
        #: The run may end before ``t_final`` (rest, a final peak): no hard end time, ``stop_at_rest``.
        self.open_end = s.end_time is None and s.stop_at_rest
        self.t_final = s.end_time if s.end_time is not None else self.duration + s.free_time
        self.scan = s.scan_step if s.scan_step is not None else max(self.duration, 1e-9) / 2000.0
        self.atol = np.array([s.atol, s.atol * self.p])
        self.acc = _still if excitation is None else excitation.acceleration
        bps = np.zeros(0) if excitation is None else np.asarray(excitation.breakpoints(), dtype=float)
        end = self.duration if self.duration < self.t_final else self.t_final
        self.breakpoints = np.unique(np.append(bps[(bps > 0.0) & (bps < self.t_final)], end))
        self.history = History(s.record, self.with_damping)
        self.impacts = ImpactLog()
        self.n_steps = 0
        self.overturned = False
        self.t = 0.0
        self.y = np.array([float(s.theta0), float(s.theta_dot0)])
        self.theta_max = abs(s.theta0)
        self.seated = s.seated_start
        self.rocked = not self.seated

    def _run_impl(self) -> RockingResult:
        """Solve and return the result (``status="failed"`` with the reason where a phase stopped it)."""
        self._start()
        try:
            while self.t < self.t_final:
                self._check_limits()
                self.each_iteration()
                if self.seated:
                    if self.open_end and self.t >= self.duration:
                        break  # a = 0 from here on: the block stays seated
                    self._seated_step()
                else:
                    self._flight_step()
        except StopRun as stop:
            if stop.reason:
                return self._failed(stop.reason, stop.failure)
        return self._finish()

    def _check_limits(self) -> None:
        """The shared limits, between segments: ``max_steps`` and ``max_wall_time``."""
        s = self.settings
        if s.max_steps is not None and self.n_steps >= s.max_steps:
            raise StopRun(f"{REASONS[MAX_STEPS]} (max_steps = {s.max_steps}, t = {self.t:.6g} s)", "max_steps")
        if self.elapsed() > s.max_wall_time:
            raise StopRun(f"{REASONS[TIMEOUT]} (max_wall_time = {s.max_wall_time:g} s, t = {self.t:.6g} s)",
                          "timeout")

    def next_breakpoint(self) -> float:
        """End of the current segment (s): the next excitation breakpoint after ``t``, else the end time.

        A binary search in the sorted breakpoints (a record has one per sample): a scan of them all at every
        segment made a record of 1.2 million samples take days (quadratic in its length)."""
        k = int(np.searchsorted(self.breakpoints, self.t + 1e-15 * max(1.0, self.t), side="right"))
        return float(self.breakpoints[k]) if k < self.breakpoints.size else self.t_final

    def count_steps(self, sol: Any) -> None:
        """Add a segment's accepted steps; a failed integration stops the run with scipy's message."""
        self.n_steps += max(len(sol.t) - 1, 0)
        t_end = float(sol.t[-1])
        if not np.all(np.isfinite(sol.y[:, -1])):
            raise StopRun(f"{REASONS[NONFINITE]} at t = {t_end:.6g} s", failure_of(NONFINITE))
        if sol.status == -1:
            # a floor acceleration that turns non-finite makes the step control fail just before it
            probe = np.asarray(self.acc(t_end + np.linspace(0.0, 1e-6 * max(1.0, t_end), 5)), dtype=float)
            if not np.all(np.isfinite(probe)):
                raise StopRun(f"{REASONS[NONFINITE]}: the floor acceleration at t = {t_end:.6g} s",
                              failure_of(NONFINITE))
            raise StopRun(f"solve_ivp ({self.segment_method}) failed at t = {self.t:.6g} s: {sol.message}",
                          failure_of(INTEGRATOR))

    def track_peak(self, sol: Any, turning_event: int) -> None:
        """Raise ``theta_max`` to the segment's largest ``|theta|``, its turning points included."""
        self.theta_max = max(self.theta_max, float(np.max(np.abs(sol.y[0]))))
        if sol.t_events[turning_event].size:
            self.theta_max = max(self.theta_max, float(np.max(np.abs(sol.y_events[turning_event][:, 0]))))

    def log_impact(self, time: float, before: float, after: float) -> None:
        """Log an impact; past ``max_impacts`` the run stops failed."""
        if len(self.impacts) + 1 > self.settings.max_impacts:
            raise StopRun(f"more than max_impacts = {self.settings.max_impacts} impacts by t = {self.t:.6g} s",
                          failure_of(MAX_IMPACTS))
        self.impacts.add(time, before, after)

    def _failed(self, reason: str, failure: str = "error") -> RockingResult:
        t, th, td = self.history.arrays()
        return failed_result(self.name, self.settings_dict, self.alpha, reason,
                             time=t if t.size else None, theta=th if th.size else None,
                             theta_dot=td if td.size else None, n_steps=self.n_steps, wall_time_s=self.elapsed(),
                             failure=failure)

    def result(self, **extra: Any) -> RockingResult:
        """The finished run's :class:`RockingResult` (``extra``: the SDOF model's moment histories)."""
        t, th, td = self.history.arrays()
        return RockingResult(
            solver=self.name, settings=self.settings_dict, alpha=self.alpha, time=t, theta=th, theta_dot=td,
            theta_max=self.theta_max, overturned=self.overturned, rocked=self.rocked, n_steps=self.n_steps,
            n_impacts=len(self.impacts), impacts=self.impacts.freeze(), wall_time_s=self.elapsed(), **extra)

    # --- the solver's own parts ----------------------------------------------------------------------
    #: Method of the segment under way, for the failure message.
    segment_method: str = ""

    def _start(self) -> None:
        """Before the loop (the initial state is recorded here)."""
        raise NotImplementedError

    def each_iteration(self) -> None:
        """At the top of every pass of the loop (a cap on the number of segments)."""

    def _seated_step(self) -> None:
        """A seated block: advance to its uplift (or to the end of the excitation)."""
        raise NotImplementedError

    def _flight_step(self) -> None:
        """A rocking block: one segment, up to the next event or breakpoint."""
        raise NotImplementedError

    def _finish(self) -> RockingResult:
        """The result of a run that ended normally."""
        return self.result()


# --- the block's energy -------------------------------------------------------------------------------
def inertia_ratio(block: Block) -> float:
    """``kappa = R² / r²`` of ``block`` (dimensionless): the distance from a base corner to the centre of mass over
    the radius of gyration about the centre of mass, squared; exactly 3 for a homogeneous block (``I_cm = m R² /
    3``), so that the kernels written with it reproduce a homogeneous block's numbers bit for bit."""
    return 3.0 if block.homogeneous else block.R**2 / block.r_gyration**2


def potential_energy(block: Block, theta: np.ndarray | float) -> np.ndarray | float:
    """Potential energy of the rocking block ``m g R [cos(alpha - |theta|) - cos(alpha)]`` (J), zero when
    seated; ``theta`` in rad."""
    if isinstance(theta, (float, int)):
        return block.mass * G * block.R * (math.cos(block.alpha - abs(float(theta))) - math.cos(block.alpha))
    theta = np.asarray(theta, dtype=float)
    return block.mass * G * block.R * (np.cos(block.alpha - np.abs(theta)) - math.cos(block.alpha))


def rocking_energy(block: Block, theta: np.ndarray | float, theta_dot: np.ndarray | float) -> np.ndarray:
    """Mechanical energy of the rocking block (J): ``1/2 I_O theta'² + m g R [cos(alpha - |theta|) -
    cos(alpha)]`` (paper Section 2.1), conserved between impacts when the floor is still.

    Parameters
    ----------
    block : Block
    theta : float or ndarray
        Rotation (rad).
    theta_dot : float or ndarray
        Angular velocity (rad/s).
    """
    theta = np.asarray(theta, dtype=float)
    theta_dot = np.asarray(theta_dot, dtype=float)
    return 0.5 * block.I_O * theta_dot**2 + potential_energy(block, theta)


# --- uplift -----------------------------------------------------------------------------------------
def first_exceedance(excitation: Any, level: float, t_start: float, t_stop: float, step: float) -> float | None:
    """First time in ``[t_start, t_stop]`` at which ``|a(t)| > level``, or None.

    Scans ``|a|`` on a grid of spacing ``<= step`` that includes the excitation's
    breakpoints, refines every grid-local maximum lying within 0.1 % below ``level`` (so a
    peak that barely exceeds ``level`` between grid points is found), and locates the
    crossing with Brent's method to ~1e-14 s. The returned time is on the exceeding side.

    Parameters
    ----------
    excitation : Excitation
        Floor motion with ``acceleration(t)`` (m/s²) and ``breakpoints()`` (s).
    level : float
        Acceleration level (m/s²), > 0.
    t_start, t_stop : float
        Search interval (s).
    step : float
        Largest grid spacing (s).
    """
    if t_stop <= t_start:
        return None

    def f(t: float) -> float:
        return float(abs(excitation.acceleration(t))) - level

    if f(t_start) > 0.0:
        return t_start
    n = max(2, int(math.ceil((t_stop - t_start) / step)) + 1)
    bps = np.asarray(excitation.breakpoints(), dtype=float)
    grid = np.union1d(np.linspace(t_start, t_stop, n), bps[(bps > t_start) & (bps < t_stop)])
    vals = np.abs(np.asarray(excitation.acceleration(grid), dtype=float)) - level
    candidates = _crossing_brackets(f, grid, vals, level)
    if not candidates:
        return None
    lo, hi = min(candidates)
    from scipy.optimize import brentq  # here: scipy.optimize costs a third of a second to import, and a refused
                                       # command line or a compiled solver's run never needs it

    tol = 1e-14 * max(1.0, abs(hi))
    root = brentq(f, lo, hi, xtol=tol, rtol=4 * np.finfo(float).eps)
    # step onto the exceeding side so the uplift starts with the right sign of theta''
    for _ in range(60):
        if f(root) > 0.0:
            return root
        root = min(hi, root + tol)
        tol *= 2.0
    return hi


def _crossing_brackets(f, grid: np.ndarray, vals: np.ndarray, level: float) -> list[tuple[float, float]]:
    """Brackets ``(t_lo, t_hi)`` with ``f(t_lo) <= 0 < f(t_hi)``: the first grid exceedance, and the first
    grid-local maximum just below the level that exceeds it between grid points."""
    from scipy.optimize import minimize_scalar  # imported here as brentq above

    candidates: list[tuple[float, float]] = []
    above = np.flatnonzero(vals > 0.0)
    if above.size:
        j = int(above[0])
        candidates.append((grid[j - 1], grid[j]))
    last = int(above[0]) if above.size else grid.size - 1
    inner = np.arange(1, last)
    if inner.size:
        peak = (vals[inner] >= vals[inner - 1]) & (vals[inner] >= vals[inner + 1]) & (vals[inner] > -1e-3 * level)
        for i in inner[peak]:
            lo, hi = grid[i - 1], grid[i + 1]
            res = minimize_scalar(lambda t: -f(t), bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-14 * max(1.0, hi)})
            if -res.fun > 0.0:
                candidates.append((lo, float(res.x)))
                break
    return candidates


# --- the recorded history -------------------------------------------------------------------------------
class History:
    """The time history a solver records: ``(t, theta, theta_dot)`` and, for the SDOF models, the damper
    coefficient in force at each state; kept only when ``record`` is True.

    Parameters
    ----------
    record : bool
        Keep the history (False: every ``add`` is dropped, for campaigns that keep peaks only).
    with_damping : bool
        Also keep a damper coefficient per state (N m s/rad).
    """

    def __init__(self, record: bool = True, with_damping: bool = False) -> None:
        self.record = record
        self.with_damping = with_damping
        self._t: list[np.ndarray] = []
        self._th: list[np.ndarray] = []
        self._td: list[np.ndarray] = []
        self._c: list[np.ndarray] = []

    def add(self, t, theta, theta_dot, damping: float = 0.0) -> None:
        """Append states: times (s), rotations (rad), angular velocities (rad/s), scalars or arrays."""
        if not self.record:
            return
        t = np.atleast_1d(np.asarray(t, dtype=float))
        self._t.append(t)
        self._th.append(np.broadcast_to(np.asarray(theta, dtype=float), t.shape).copy())
        self._td.append(np.broadcast_to(np.asarray(theta_dot, dtype=float), t.shape).copy())
        if self.with_damping:
            self._c.append(np.full(t.shape, damping))

    def add_segment(self, sol: Any, turning_event: int, damping: float = 0.0, dense_step: float | None = None) -> None:
        """A :func:`scipy.integrate.solve_ivp` segment's accepted steps merged with its turning points
        (event ``turning_event``), so the history holds every peak exactly, not only the nearest step;
        with ``dense_step`` (s) also the dense output (``sol.sol``) every ``dense_step``."""
        t, th, td = sol.t[1:], sol.y[0, 1:], sol.y[1, 1:]
        if dense_step is not None and sol.sol is not None and sol.t[-1] > sol.t[0]:
            grid = np.arange(sol.t[0] + dense_step, sol.t[-1], dense_step)
            if grid.size:
                yd = sol.sol(grid)
                t, th, td = _merged((t, th, td), (grid, yd[0], yd[1]))
        if sol.t_events[turning_event].size:
            te, ye = sol.t_events[turning_event], sol.y_events[turning_event]
            inside = (te > sol.t[0]) & (te < sol.t[-1])
            t, th, td = _merged((t, th, td), (te[inside], ye[inside, 0], ye[inside, 1]))
        self.add(t, th, td, damping)

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(time, theta, theta_dot)`` as arrays (empty when nothing was recorded)."""
        cat = (lambda parts: np.concatenate(parts) if parts else np.zeros(0))
        return cat(self._t), cat(self._th), cat(self._td)

    def damping(self) -> np.ndarray:
        """The damper coefficient in force at each recorded state (N m s/rad)."""
        return np.concatenate(self._c) if self._c else np.zeros(0)


def _merged(a: tuple[np.ndarray, ...], b: tuple[np.ndarray, ...]) -> tuple[np.ndarray, ...]:
    """Two sets of ``(t, theta, theta_dot)`` merged in time order (stable: ``a`` first at equal times)."""
    t = np.concatenate([a[0], b[0]])
    order = np.argsort(t, kind="stable")
    return tuple(np.concatenate([x, y])[order] for x, y in zip(a, b))


__all__ = ["EventDrivenSolver", "History", "IVP_METHODS", "LONG_SOLVE_S", "SECONDS_PER_SEGMENT", "SHARED_SETTINGS", "ScipySettings", "SolverRun",
           "SolverSettings", "StopRun", "TAILS", "check_inputs", "event_driven_estimate", "first_exceedance",
           "first_nonfinite_sample", "inertia_ratio", "refuse_value", "timed_out",
           "make_settings", "potential_energy", "rocking_energy", "setting_names", "settings_record"]
