"""Every registered solver against the written contract (opsrock.solvers.common's docstring).

Parametrised over the registry (ids = solver names), so a new solver is checked as soon as it is
registered: the shared settings, the result fields, the error class for what it does not model (read
from its declarations), the shared statuses for a non-finite floor motion, the step limit and the
wall-clock limit, and free rocking from a start state against the closed form of the rigid block.
"""

from __future__ import annotations

import dataclasses
import math
import subprocess
import sys
import types

import numpy as np
import pytest

from opsrock import Block, OneSinePulse, Record
from opsrock.errors import InputError, InputTypeError, ModelNotSupported
from opsrock.result import RockingResult
from opsrock.solvers import METHODS, SOLVERS, capabilities, check_model, get_solver, settings_class, solver_names
from opsrock.solvers.common import SHARED_SETTINGS, SolverSettings, make_settings
from opsrock.solvers.status import FAILURE_KINDS, FAILURES, REASONS

#: A block every solver models: b/h = 0.25, alpha = 0.245 rad, p = 3.45 rad/s, Housner's e = e_H = 0.912
#: (Moreau-Jean reproduces no other).
BLOCK = Block(0.3, 1.2, restitution_factor=1.0)
#: The same block with a depth, for the solvers that model motion in plan (``rigid3d`` needs the depth). Twice the
#: width: the width stays the weaker axis, so alpha, p and the free rocking along it are BLOCK's.
BLOCK_3D = Block(0.3, 1.2, restitution_factor=1.0, depth=0.6)
#: A cylinder of diameter 0.3 m and height 1.2 m whose inertia about a horizontal axis is BLOCK's
#: (``radius_of_gyration``), for ``cylinder3d``: rocking in a vertical plane through its axis, its alpha, p and e_H are
#: BLOCK's (the rigid-body equation of the plane has only R, alpha and I_O).
CYLINDER = Block(0.3, 1.2, restitution_factor=1.0, cm_height=0.6, radius_of_gyration=BLOCK.r_gyration)
#: Free rocking: released at half its slenderness, followed for 1.6 s (two impacts: the first at ~0.33 s).
THETA0 = 0.5 * BLOCK.alpha
SPAN = 1.6

#: The result fields every solver fills, with their types.
RESULT_FIELDS = {"solver": str, "settings": dict, "alpha": float, "time": np.ndarray, "theta": np.ndarray,
                 "theta_dot": np.ndarray, "theta_max": float, "overturned": bool, "rocked": bool, "status": str,
                 "reason": str, "n_steps": int, "n_impacts": int, "wall_time_s": float}


def _solve(name: str, excitation, **settings) -> RockingResult:
    """The solver's own entry, ``solve(block, excitation, settings)``, with its settings object."""
    solver = get_solver(name)
    block = CYLINDER if name == "cylinder3d" else (BLOCK_3D if METHODS[name].plan else BLOCK)
    return solver.solve(block, excitation, make_settings(settings_class(name), None, settings))


def _free(name: str, **settings) -> RockingResult:
    """Free rocking from ``THETA0`` for ``SPAN``; run to the end where the solver lets the run go on past
    rest (OpenSees would stop at once: its peak is already known at the start)."""
    extra = {"theta0": THETA0, "end_time": SPAN, **settings}
    try:
        make_settings(settings_class(name), None, {"stop_at_rest": False})
        extra.setdefault("stop_at_rest", False)
    except ModelNotSupported:
        pass
    return _solve(name, None, **extra)


def _pulse() -> OneSinePulse:
    """A pulse that rocks the block to about half its slenderness (PFA = 1.35 g tan(alpha), omega_p = 3 p)."""
    return OneSinePulse.from_ratios(BLOCK, 1.35, 3.0)


class _NaNAfter(Record):
    """A record whose samples turn NaN after ``t = 0.1`` s: a floor motion that goes bad mid-run."""

    @classmethod
    def make(cls) -> _NaNAfter:
        dt = 0.002
        values = np.full(501, 0.5 * BLOCK.uplift_acceleration)
        record = cls(dt=dt, values=values, name="nan-after-0.1s")
        bad = values.copy()
        bad[int(0.1 / dt):] = np.nan
        object.__setattr__(record, "values", bad)  # past the Record's own checks, on purpose
        return record


@pytest.fixture(params=SOLVERS, ids=SOLVERS)
def name(request) -> str:
    return request.param


def test_registry_declares_each_solver_and_names_one_thing():
    assert set(SOLVERS) == set(METHODS) and len(SOLVERS) == 8
    assert solver_names(friction=True) == ("friction", "moreau_jean", "rigid3d", "cylinder3d")
    assert solver_names(plan=True) == ("rigid3d", "cylinder3d")
    assert solver_names(model="rigid") == ("housner", "housner_fast")
    assert solver_names(needs_opensees=True) == ("opensees",)
    with pytest.raises(InputError, match="capability 'slips'"):
        solver_names(slips=True)
    for n in SOLVERS:
        assert capabilities(n)["model"] == METHODS[n].model


def test_shared_settings_are_accepted_with_one_name_each(name):
    cls = settings_class(name)
    assert issubclass(cls, SolverSettings)
    fields = {f.name for f in dataclasses.fields(cls)}
    assert set(SHARED_SETTINGS) <= fields
    defaults = cls()
    # each shared field at its own default merges back unchanged (same names, same units in every solver)
    same = make_settings(cls, None, {k: getattr(defaults, k) for k in SHARED_SETTINGS})
    assert same == defaults
    with pytest.raises(InputError, match="max_wall_time"):
        make_settings(cls, None, {"max_wall_time": -1.0})
    with pytest.raises(InputError, match="theta0"):
        make_settings(cls, None, {"theta0": 2.0})


def test_result_fields_are_the_same(name):
    r = _solve(name, _pulse())
    assert r.ok and r.failure is None and r.reason == "" and r.solver == name, (r.reason, r.failure)
    for field, kind in RESULT_FIELDS.items():
        value = getattr(r, field)
        assert isinstance(value, kind) or (kind is float and isinstance(value, (int, float))), (field, type(value))
    assert r.rocked and 0.0 < r.theta_max < math.pi / 2 and r.n_impacts >= 1
    assert r.time.size == r.theta.size == r.theta_dot.size > 2
    blind = _solve(name, _pulse(), record=False)
    assert blind.time.size == 0 and blind.theta_max == pytest.approx(r.theta_max, rel=1e-12, abs=0.0)


def test_what_a_solver_does_not_model_is_refused_with_one_class(name):
    info = METHODS[name]
    cases = []
    if not info.friction:
        cases.append((Block(0.3, 1.2, friction=0.5, restitution_factor=1.0), _pulse(), "friction"))
    if not info.vertical:
        vertical = dataclasses.replace(_pulse(), vertical=0.1 * 9.81)
        cases.append((BLOCK, vertical, "vertical"))
    if not info.restitution:
        cases.append((Block(0.3, 1.2, restitution_factor=0.9), _pulse(), "restitution"))
    if info.excitations != "any":
        assert isinstance(get_solver(name).solve.__doc__, str)
    assert cases or name in solver_names(friction=True, vertical=True, restitution=True)
    for block, excitation, what in cases:
        with pytest.raises(ModelNotSupported, match=what):
            get_solver(name).solve(block, excitation)
        with pytest.raises(ModelNotSupported, match=what):
            check_model(name, block, excitation)
    with pytest.raises(InputTypeError, match="block"):
        get_solver(name).solve("not a block", _pulse())
    with pytest.raises(InputError, match="start state"):
        get_solver(name).solve(BLOCK, None)  # a still floor and a block at rest: nothing to solve


@pytest.mark.parametrize("start", ["rocking", "seated"])
def test_a_non_finite_floor_motion_fails_with_the_shared_status(name, start):
    # seated: the NaN reaches a block at rest on the floor (a state that stays finite unless the solver
    # checks the floor's motion itself)
    r = _solve(name, _NaNAfter.make(), **({"theta0": THETA0} if start == "rocking" else {}))
    assert not r.ok and r.verdict == "failed"
    assert r.failure == "nonfinite", (r.failure, r.reason)
    assert r.failure in FAILURE_KINDS and REASONS[next(c for c, k in FAILURES.items() if k == r.failure)]


def test_step_limit_fails_with_the_shared_status(name):
    r = _solve(name, _pulse(), max_steps=3)
    assert not r.ok and r.failure == "max_steps" and "max_steps" in r.reason, (r.failure, r.reason)
    assert r.n_steps <= 3 + 2**8  # OpenSees counts the halves of a retried step (at most 2^max_halvings)


def test_wall_clock_limit_fails_with_the_shared_status(name):
    r = _solve(name, _pulse(), max_wall_time=1e-9)
    assert not r.ok and r.failure == "timeout" and "max_wall_time" in r.reason, (r.failure, r.reason)


def _first_return_peak(r: RockingResult) -> float:
    """``|theta|`` at the first turning point after the first impact (the first sign change of theta)."""
    th = r.theta
    side = np.sign(th[0])
    crossed = np.flatnonzero(np.sign(th) == -side)
    assert crossed.size, "no impact in the span"
    after = th[crossed[0]:]
    back = np.flatnonzero(np.sign(after) == side)
    return float(np.max(np.abs(after[:back[0]] if back.size else after)))


def test_free_rocking_from_a_start_state_meets_the_closed_form(name):
    """Released from rest at theta0 on a still floor, the rigid block reaches theta = 0 with the energy
    ``m g R [cos(alpha - theta0) - cos(alpha)]``; the impact keeps ``e²`` of it, so the first return peak
    theta1 solves ``cos(alpha - theta1) - cos(alpha) = e² [cos(alpha - theta0) - cos(alpha)]``.

    Tolerances on |d theta1| / alpha, per method, about ten times the error measured on this block (in
    brackets): the event-driven housner solves the exact equation with the impact as an event (2e-11):
    1e-8; housner_fast and friction take the peak from steps recorded ``h = 0.02/p`` apart (1.3e-5,
    1.8e-5): 1e-4; Moreau-Jean's impact carries an O(dt) energy error (3e-3 at dtau = 1e-3, the
    moreau_jean docstring; 1.6e-5 at the default 1e-4) and its history is sampled every 0.01/p: 1e-3; the
    SDOF models replace the impact by the damper band tuned to keep e² of the energy over a free passage,
    with the tabulated spring (sdof 1.4e-5; OpenSees adds its adaptive Newmark steps, 1.4e-4): 1e-3.
    rigid3d is the same Moreau-Jean scheme on the box (BLOCK_3D, rocking along its width: both corners of an
    edge land in one step, e_n = 0 at each): the same error, 1e-3; so is cylinder3d on CYLINDER (the landing rim point
    takes the impulse, e_n = 0), 1e-3. Every solver but friction stops at
    ``end_time``, after 3 impacts; friction follows the block to rest.
    """
    tolerance = {"housner": 1e-8, "housner_fast": 1e-4, "friction": 1e-4, "moreau_jean": 1e-3,
                 "sdof": 1e-3, "opensees": 1e-3, "rigid3d": 1e-3, "cylinder3d": 1e-3}[name]
    r = _free(name)
    assert r.ok and r.failure is None, r.reason
    assert r.theta_max == pytest.approx(THETA0, rel=1e-12)  # released from rest: the first peak is theta0
    assert r.rocked and (r.n_impacts > 3 if name == "friction" else r.n_impacts == 3)
    a, e = BLOCK.alpha, BLOCK.e
    theta1 = a - math.acos(math.cos(a) + e * e * (math.cos(a - THETA0) - math.cos(a)))
    assert abs(_first_return_peak(r) - theta1) / a < tolerance, (_first_return_peak(r) / a, theta1 / a)
    assert abs(r.theta[-1]) < THETA0  # it decays


def test_opensees_is_loaded_only_when_first_used():
    """``import opsrock.solvers``, the registry, every settings class and every solver but OpenSees run
    without importing OpenSeesPy (whose wheel needs the system BLAS)."""
    code = ("import sys\n"
            "from opsrock import Block, OneSinePulse\n"
            "from opsrock.solvers import SOLVERS, settings_class, simulate, solver_names\n"
            "b = Block(0.3, 1.2, restitution_factor=1.0, depth=0.6)  # rigid3d needs the depth; the rest ignore it\n"
            "c = Block(0.3, 1.2, restitution_factor=1.0)  # cylinder3d: a round base (depth None)\n"
            "[settings_class(n)() for n in SOLVERS]\n"
            "for n in solver_names(needs_opensees=False):\n"
            "    k = c if n == 'cylinder3d' else b\n"
            "    assert simulate(k, OneSinePulse.from_ratios(k, 1.35, 3.0), solver=n).ok, n\n"
            "assert not any(m.startswith('openseespy') or m == 'opsrock.opensees_session' for m in sys.modules)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]


class _FakeKernel:
    """A compiled kernel on an injected clock (``clock["t"]``, s): its compile takes ``compile_s``, a call 1 s; as a
    numba dispatcher, a call compiles the arguments' types first if they are not among its ``signatures``."""

    def __init__(self, clock: dict, compile_s: float) -> None:
        self.signatures, self.clock, self.compile_s = [], clock, compile_s

    def compile(self, sig):
        self.clock["t"] += self.compile_s
        self.signatures = [*self.signatures, sig]

    def __call__(self, *args):
        import numba

        sig = tuple(numba.typeof(a) for a in args)
        if sig not in self.signatures:
            self.compile(sig)
        self.clock["t"] += 1.0
        return sum(args)


def _clocked_run(monkeypatch) -> tuple:
    """A bare :class:`SolverRun` whose wall clock is the injected ``clock`` (starting at 0 s)."""
    import opsrock.solvers.common as common

    clock = {"t": 0.0}
    monkeypatch.setattr(common, "_time", types.SimpleNamespace(perf_counter=lambda: clock["t"]))
    run = common.SolverRun.__new__(common.SolverRun)
    run.t_wall = 0.0
    return run, clock


def test_wall_time_counts_the_solve_not_the_compilation(monkeypatch):
    """``SolverRun.compiled_call`` compiles a kernel this process has not compiled yet outside the wall clock
    (issue 46: a first 3-D solve reported 345.5 s for 0.1 s of solving). An injected clock: the compilation
    takes 100 s of it, the call 1 s."""
    run, clock = _clocked_run(monkeypatch)
    kernel = _FakeKernel(clock, 100.0)
    assert run.compiled_call(kernel, 1.0, 2.0) == 3.0 and run.elapsed() == 1.0
    assert run.compiled_call(kernel, 1.0, 2.0) == 3.0 and run.elapsed() == 2.0  # compiled once


def test_wall_time_leaves_out_a_first_solves_set_up_and_a_kernel_compiled_mid_solve(monkeypatch):
    """Before the solve's first kernel call the clock restarts after the compile, so helpers compiled during the
    set-up (housner_fast's case parameters and forcing, 1.4 s of a first solve, were counted after 2e72f45) are
    left out; a second kernel compiled mid-solve (friction's flight) moves the clock on by its compile alone, so
    the solve's time before it is kept. An injected clock: set-up 7 s, compiles 100 s and 50 s, calls 1 s each."""
    run, clock = _clocked_run(monkeypatch)
    clock["t"] += 7.0  # the set-up, compiling its helpers on their first call
    assert run.compiled_call(_FakeKernel(clock, 100.0), 1.0) == 1.0 and run.elapsed() == 1.0
    assert run.compiled_call(_FakeKernel(clock, 50.0), 2.0) == 2.0 and run.elapsed() == 2.0


def test_wall_time_leaves_out_a_second_specialisation_compiled_mid_solve(monkeypatch):
    """A kernel numba compiles once per kind of argument (rigid3d's, for infinite and for finite friction): the
    specialisation a call names (``variant``) is compiled outside the clock the first time it is needed, even with
    another already compiled, and then only called. An injected clock: compiles 100 s each, calls 1 s."""
    run, clock = _clocked_run(monkeypatch)
    kernel = _FakeKernel(clock, 100.0)
    assert run.compiled_call(kernel, 1.0, variant="float") == 1.0 and run.elapsed() == 1.0
    assert run.compiled_call(kernel, 2, variant="int") == 2 and run.elapsed() == 2.0
    assert run.compiled_call(kernel, 3, variant="int") == 3 and run.elapsed() == 3.0
    assert len(kernel.signatures) == 2
