"""Fast rigid-body rocking solver for dense overturning spectra (numba-compiled).

Solves the same exact rigid-body equation as :mod:`opsrock.solvers.housner` (paper Eq. 1-3,
docs/modelling.md section 2), written in the dimensionless time ``tau = p t``::

    d²theta/dtau² = -[ sin(alpha s - theta) + (a(t)/g) cos(alpha s - theta) ],   s = sgn(theta)

with uplift from rest only when ``|a| > g tan(alpha)`` (Eq. 4), towards ``s = -sgn(a)``;
instantaneous impacts at ``theta = 0`` that multiply the angular velocity by ``e``
(Housner's coefficient times the restitution factor); overturning at ``|theta| >= pi/2``
(Eq. 11).

Method
------
* While the pulse lasts: classical fourth-order Runge-Kutta with a fixed step
  ``h = min(max_step, 2 pi / (omega_p/p) / steps_per_pulse)`` (in units of ``1/p``), landing
  exactly on the end of the pulse (where ``a(t)`` has a kink). Impacts and peaks inside a
  step are located by a safeguarded Newton iteration *on the Runge-Kutta map itself* (the
  step length is the unknown), so the event time is consistent with the integrator to
  round-off. After an impact the first step is shortened to the predicted half-excursion
  ``|omega| / |theta''|`` (halved again if it still overshoots), so chattering sequences are
  resolved impact by impact with geometrically shrinking steps.
* Coming to rest (impacts accumulating): once an impact leaves less than ``rest_velocity``
  (dimensionless, ``theta' / p``) and the rotational acceleration on the new side points back
  to ``theta = 0``, the block is seated. The excursions that are dropped are smaller than
  ``rest_velocity² / (2 |theta''|)``. A seated block lifts off again, in closed form for the
  sine pulse, when ``|a|`` next exceeds ``g tan(alpha)``.
* After the pulse (``a = 0``) nothing is integrated: the energy
  ``E = omega²/2 + cos(alpha - |theta|) - cos(alpha)`` (per ``m g R``) is conserved between
  impacts and multiplied by ``e²`` at each one, so the block overturns if and only if it
  heads over the barrier ``1 - cos(alpha)`` with more energy than that, and otherwise its
  next peak is ``alpha - arccos(E + cos alpha)``, after which every impact lowers the energy
  and ``theta_max`` can no longer grow. A block beyond the hump (``|theta| > alpha``) at the
  end of the pulse overturns if it heads out, or heads in without the energy to recross the
  hump; with that energy it falls back to ``theta = 0``, impacts, and the same rules apply.
  This is exact, not an approximation.

Records
-------
A :class:`~opsrock.excitations.Record` is integrated segment by segment: its acceleration is
linear between samples, every step ends on a sample (no step straddles a kink), steps are also
bounded by ``max_step``, and a seated block's uplift is found in closed form on the segment where
``|a|`` first exceeds ``g tan(alpha)``. Impacts and peaks are located exactly as for the pulse,
and after the last sample the same exact energy verdict applies. On FEMA P695 floor motions it
matches the event-driven ``housner`` solver to 1.1e-5 alpha (validation case 8) at about a
millisecond per record (``bench/bench_records.py``).

Why numba: a per-case ``solve_ivp`` loop costs milliseconds per case (Python overhead per
step and per restart at every impact), too slow for 40,000-case spectra; a numpy-vectorised
fixed-step integrator over all cases wastes work on cases that have already settled or
overturned and handles per-case events clumsily. A compiled per-case integrator with a
thread pool over chunks of cases has neither problem. Measured by
``python bench/bench_housner_fast.py`` on the 2-core project machine while it was shared
(load average 8-11): 40,000 cases in 2.4-3.7 s, 25-90 µs per case against 23-77 ms per
case for a per-case ``solve_ivp`` loop (x250-x2000), with ``|d theta_max| / alpha`` below
1e-8 of the converged answer. The kernel is compiled once and cached (``cache=True``, in
``__pycache__``): about 16-20 s for a cold compile on that machine, 2-4 s to load the
cache in a new process.
"""

from __future__ import annotations

import math
import os
import time as _time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass, replace
from typing import Any, Sequence

import numpy as np

from opsrock._checks import bool_fields, int_at_least, one_of, positive_finite
from opsrock.block import Block
from opsrock.constants import EQUATIONS, G, OVERTURNING_ANGLE
from opsrock.excitations import PULSE_SHAPES, Pulse, Record
from opsrock.excitations.records import check_sampling
from opsrock.result import RockingResult, failed_result
from opsrock.solvers._housner_fast_kernel import (  # noqa: F401  (status codes are public)
    STATUS_EVENT_FAILED, STATUS_MAX_IMPACTS, STATUS_MAX_STEPS, STATUS_NONFINITE, STATUS_OK,
    STATUS_REASONS, FORM_LINEAR, PULSE_IDS, PULSE_ONE_SINE, _pulse_forcing, _solve_case, _solve_chunk)

#: Name this solver writes into :attr:`RockingResult.solver`.
SOLVER_NAME = "housner_fast"

@dataclass(frozen=True)
class HousnerFastSettings:
    """Numerical settings of the fast rigid-body solver (all dimensionless).

    Parameters
    ----------
    max_step : float
        Largest Runge-Kutta step in units of ``1/p`` (dimensionless time ``tau = p t``).
        Default 0.02. Measured on the 40,000-case benchmark grid against a run with steps
        eight times shorter: (max_step, steps_per_pulse) = (0.02, 200) differs by at most
        1.5e-8 alpha in theta_max (0.04, 100: 2.3e-7; 0.08, 50: 2.5e-5), with the same
        verdict everywhere; the target is 5e-3 alpha, so the default keeps a wide
        margin for verdicts of cases close to the overturning boundary at little cost.
    steps_per_pulse : int
        Minimum number of steps per pulse period ``T_p`` (dimensionless count), so short
        pulses (``omega_p/p`` up to 10 and beyond) are resolved as finely as long ones.
        Default 200 (see ``max_step``).
    rest_velocity : float
        Angular velocity, in units of ``p`` rad/s, below which a block leaving an impact
        towards a restoring acceleration is taken as seated. Default 1e-7: the excursions
        dropped are then below ~1e-14 rad / |theta''| and the chattering tail they would
        take lasts less than ~1e-6 / p seconds.
    max_impacts : int
        Impacts allowed per case before it is reported as failed. Default 100000. One
        chattering sequence from ``theta' ~ p`` down to ``rest_velocity`` takes
        ``ln(1e-7)/ln(e)`` impacts: about 170 for ``e = 0.91`` (slender block) and 55 for
        ``e = 0.74`` (alpha = 0.42 rad).
    max_steps : int
        Integrator steps allowed per case before it is reported as failed. Default 10**7.
    equations : str
        Form of the equation of motion, one of :data:`opsrock.constants.EQUATIONS`. Default
        ``"exact"``; ``"linearised"``: ``d²theta/dtau² = -[(alpha s - theta) + a/g]`` with uplift when
        ``|a| > g alpha`` and the free-rocking verdict from the linearised energy.
    """

    max_step: float = 0.02
    steps_per_pulse: int = 200
    rest_velocity: float = 1e-7
    max_impacts: int = 100_000
    max_steps: int = 10_000_000
    equations: str = "exact"

    def __post_init__(self) -> None:
        bool_fields(self)
        one_of("equations", self.equations, EQUATIONS)
        positive_finite("max_step", self.max_step)
        if self.max_step > 0.5:
            raise ValueError(f"max_step must be <= 0.5 (units of 1/p), got {self.max_step!r}")
        int_at_least("steps_per_pulse", self.steps_per_pulse, 8)
        positive_finite("rest_velocity", self.rest_velocity)
        if self.rest_velocity > 1e-3:
            raise ValueError(f"rest_velocity must be <= 1e-3 (units of p), got {self.rest_velocity!r}")
        int_at_least("max_impacts", self.max_impacts, 1)
        int_at_least("max_steps", self.max_steps, 1)


# =============================================================================================
# Public API
# =============================================================================================


@dataclass(frozen=True)
class GridResult:
    """Batch results, one element per case, in the broadcast shape of the inputs.

    Parameters
    ----------
    theta_max : ndarray of float
        Peak ``|theta|`` (rad); ``>= pi/2`` when overturned; meaningless where ``status != 0``.
    overturned : ndarray of bool
        ``|theta|`` reached ``pi/2`` (Eq. 11). False where ``status != 0``.
    rocked : ndarray of bool
        The block uplifted at all (Eq. 4).
    status : ndarray of int8
        :data:`STATUS_OK` or a failure code, see :data:`STATUS_REASONS`.
    n_impacts : ndarray of int64
        Impacts resolved (the free-rocking tail after the first post-pulse peak is not counted).
    n_steps : ndarray of int64
        Runge-Kutta steps taken, event location included.
    wall_time_s : float
        Wall-clock time of the batch (s).
    """

    theta_max: np.ndarray
    overturned: np.ndarray
    rocked: np.ndarray
    status: np.ndarray
    n_impacts: np.ndarray
    n_steps: np.ndarray
    wall_time_s: float = 0.0

    @property
    def ok(self) -> np.ndarray:
        """True where the case finished (its verdict is valid)."""
        return self.status == STATUS_OK

    @property
    def verdict(self) -> np.ndarray:
        """Per-case verdict string: ``no_uplift``, ``safe``, ``overturned`` or ``failed``."""
        out = np.where(self.rocked, "safe", "no_uplift").astype(object)
        out[self.overturned] = "overturned"
        out[~self.ok] = "failed"
        return out


def _as_settings(settings: HousnerFastSettings | None, overrides: dict[str, Any]) -> HousnerFastSettings:
    if settings is None:
        settings = HousnerFastSettings()
    elif not isinstance(settings, HousnerFastSettings):
        raise TypeError(f"settings must be a HousnerFastSettings, got {settings!r}")
    if overrides:
        unknown = set(overrides) - set(HousnerFastSettings.__dataclass_fields__)
        if unknown:
            raise TypeError(f"unknown housner_fast settings: {sorted(unknown)}")
        settings = replace(settings, **overrides)
    return settings


#: Cases per work item of :func:`solve_grid`: small enough to balance cheap (no uplift) and
#: costly (chattering) cases across threads, large enough that dispatch costs nothing.
_CHUNK = 256


def _default_threads() -> int:
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _check_array(name: str, arr: np.ndarray, low: float, high: float) -> None:
    bad = ~(np.isfinite(arr) & (arr > low) & (arr < high))
    if np.any(bad):
        i = int(np.flatnonzero(bad.ravel())[0])
        raise ValueError(f"{name} must lie in ({low:g}, {high:g}); element {i} is {arr.ravel()[i]!r}")


def solve_grid(
    alpha: Any,
    e: Any,
    pfa_ratio: Any,
    freq_ratio: Any,
    *,
    settings: HousnerFastSettings | None = None,
    threads: int | None = None,
    pulse: str = "one-sine",
) -> GridResult:
    """Solve many analytic-pulse cases at once: the batch entry point for dense spectra.

    All inputs broadcast together; each element of the broadcast is one independent case.
    The kernel integrates in the dimensionless time ``tau = p t``, in which the peak rotation and
    the verdict depend on ``alpha``, ``e`` and the two ratios alone, so the block's size (``p``)
    is not an input here (tests/test_housner_fast.py checks that claim against the dimensional
    solver ``housner``).

    Parameters
    ----------
    alpha : array_like of float
        Block slenderness ``atan(b/h)`` (rad), in (0, pi/2).
    e : array_like of float
        Coefficient of restitution (dimensionless), in (0, 1].
    pfa_ratio : array_like of float
        ``PFA / (g tan alpha)`` (dimensionless, IM2), > 0.
    freq_ratio : array_like of float
        ``omega_p / p`` (dimensionless, IM1), > 0.
    settings : HousnerFastSettings, optional
        Numerical settings (defaults if omitted).
    threads : int, optional
        Worker threads (the compiled kernel releases the GIL). Default: the CPUs this
        process may use. Results are identical for any value: cases are independent.
    pulse : str, optional
        Pulse shape, a key of :data:`opsrock.excitations.PULSE_SHAPES`. Default ``"one-sine"``.

    Returns
    -------
    GridResult
        Arrays of the broadcast shape.
    """
    settings = _as_settings(settings, {})
    one_of("pulse", pulse, tuple(PULSE_SHAPES))
    threads = _default_threads() if threads is None else int_at_least("threads", threads, 1)
    arrays = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (alpha, e, pfa_ratio, freq_ratio)))
    shape = arrays[0].shape
    a_, e_, r_, f_ = (np.ascontiguousarray(x).ravel() for x in arrays)
    _check_array("alpha", a_, 0.0, 0.5 * math.pi)
    _check_array("e", e_, 0.0, 1.0 + 1e-12)
    _check_array("pfa_ratio", r_, 0.0, math.inf)
    _check_array("freq_ratio", f_, 0.0, math.inf)
    n = a_.size
    k = r_ * np.tan(a_)  # PFA / g
    theta_max = np.empty(n)
    overturned = np.empty(n, dtype=np.bool_)
    rocked = np.empty(n, dtype=np.bool_)
    status = np.empty(n, dtype=np.int8)
    n_impacts = np.empty(n, dtype=np.int64)
    n_steps = np.empty(n, dtype=np.int64)
    args = (a_, e_, k, f_, PULSE_IDS[pulse], settings.equations == "linearised",
            float(settings.max_step), int(settings.steps_per_pulse),
            float(settings.rest_velocity), int(settings.max_impacts), int(settings.max_steps))
    outs = (theta_max, overturned, rocked, status, n_impacts, n_steps)
    bounds = [(i, min(i + _CHUNK, n)) for i in range(0, n, _CHUNK)]
    t0 = _time.perf_counter()
    if threads == 1 or len(bounds) <= 1:
        for lo, hi in bounds:
            _solve_chunk(*args, lo, hi, *outs)
    else:
        with ThreadPoolExecutor(max_workers=threads) as pool:
            for fut in [pool.submit(_solve_chunk, *args, lo, hi, *outs) for lo, hi in bounds]:
                fut.result()
    wall = _time.perf_counter() - t0
    return GridResult(
        theta_max=theta_max.reshape(shape),
        overturned=overturned.reshape(shape),
        rocked=rocked.reshape(shape),
        status=status.reshape(shape),
        n_impacts=n_impacts.reshape(shape),
        n_steps=n_steps.reshape(shape),
        wall_time_s=wall,
    )


def solve_pulses(
    blocks: Sequence[Block],
    pfa_ratios: Any,
    freq_ratios: Any,
    *,
    settings: HousnerFastSettings | None = None,
    threads: int | None = None,
    pulse: str = "one-sine",
) -> GridResult:
    """Solve every block against the full grid ``pfa_ratios x freq_ratios``.

    Parameters
    ----------
    blocks : sequence of Block
        The blocks (their ``alpha`` and ``e`` are used).
    pfa_ratios : array_like of float
        ``PFA / (g tan alpha)`` values (dimensionless), 1-D.
    freq_ratios : array_like of float
        ``omega_p / p`` values (dimensionless), 1-D.
    settings : HousnerFastSettings, optional
        Numerical settings.
    threads : int, optional
        Worker threads, see :func:`solve_grid`.
    pulse : str, optional
        Pulse shape, see :func:`solve_grid`.

    Returns
    -------
    GridResult
        Arrays of shape ``(len(blocks), len(pfa_ratios), len(freq_ratios))``.
    """
    blocks = list(blocks)
    if not blocks or not all(isinstance(b, Block) for b in blocks):
        raise TypeError(f"blocks must be a non-empty sequence of Block, got {blocks!r}")
    r = np.asarray(pfa_ratios, dtype=float).ravel()
    f = np.asarray(freq_ratios, dtype=float).ravel()
    al = np.array([b.alpha for b in blocks])[:, None, None]
    ee = np.array([b.e for b in blocks])[:, None, None]
    return solve_grid(al, ee, r[None, :, None], f[None, None, :], settings=settings,
                      threads=threads, pulse=pulse)


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
        form, c0, c1, c2, tau_end, kvals, dtau = _pulse_forcing(pulse, k, nu)
        h_nom = min(settings.max_step, 2.0 * math.pi / nu / settings.steps_per_pulse)
    else:
        form, c0, c1, c2 = FORM_LINEAR, 0.0, 0.0, 0.0
        kvals, dtau = record.values / G, record.dt * p
        tau_end = record.duration * p
        h_nom = min(settings.max_step, dtau)
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
        samples, every step ending on a sample), with the step also bounded by ``max_step``; it
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
    settings = _as_settings(settings, overrides)
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {block!r}")
    if isinstance(excitation, Record):
        check_sampling(excitation, block)
        return _run_one(block, 0.0, 1.0, 0.0, 0.0, settings, record=excitation)
    if not isinstance(excitation, Pulse) or excitation.shape not in PULSE_IDS:
        raise TypeError(
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
        ``min(max_step, p duration / steps_per_pulse)`` in units of ``1/p``.
    """
    settings = _as_settings(settings, overrides)
    if not isinstance(block, Block):
        raise TypeError(f"block must be a Block, got {block!r}")
    theta0 = float(theta0)
    if not (math.isfinite(theta0) and abs(theta0) < OVERTURNING_ANGLE):
        raise ValueError(f"theta0 must be finite with |theta0| < pi/2, got {theta0!r}")
    duration = positive_finite("duration", duration)
    theta_dot0 = float(theta_dot0)
    if not math.isfinite(theta_dot0):
        raise ValueError(f"theta_dot0 must be finite, got {theta_dot0!r}")
    nu = 2.0 * math.pi / (duration * block.p)  # so that the integrated span is `duration`
    return _run_one(block, 0.0, nu, theta0, theta_dot0 / block.p, settings)
