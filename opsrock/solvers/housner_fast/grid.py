"""Many analytic-pulse cases at once: the batch entry point for dense spectra.

The kernel (:mod:`~opsrock.solvers.housner_fast.kernel`) solves chunks of independent cases on a
thread pool (it releases the GIL); results come back as arrays (:class:`GridResult`).
"""

from __future__ import annotations

import math
import os
import time as _time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any, Sequence

import numpy as np

from opsrock.block import Block
from opsrock.constants import OVERTURNING_ANGLE
from opsrock.errors import InputError, InputTypeError
from opsrock.excitations import PULSE_SHAPES
from opsrock.limits import int_at_least, one_of
from opsrock.solvers._compile import announce_compile
from opsrock.solvers.common import make_settings
from opsrock.solvers.forcing import PULSE_IDS
from opsrock.solvers.housner_fast.kernel import STATUS_OK, Answers, BatchSettings, Cases, _solve_chunk
from opsrock.solvers.housner_fast.settings import HousnerFastSettings


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


#: Cases per work item of :func:`solve_grid`: small enough to balance cheap (no uplift) and
#: costly (chattering) cases across threads, large enough that dispatch costs nothing.
_CHUNK = 256



def default_threads() -> int:
    """Threads :func:`solve_grid` uses by default: the CPUs this process may use."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # not on Linux
        return max(1, os.cpu_count() or 1)


def _check_array(name: str, arr: np.ndarray, low: float, high: float) -> None:
    bad = ~(np.isfinite(arr) & (arr > low) & (arr < high))
    if np.any(bad):
        i = int(np.flatnonzero(bad.ravel())[0])
        raise InputError(f"{name} must lie in ({low:g}, {high:g}); element {i} is {arr.ravel()[i]!r}")


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
    is not an input here (tests/model/solvers/test_housner_fast.py checks that claim against the dimensional
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
    settings = make_settings(HousnerFastSettings, settings)
    one_of("pulse", pulse, tuple(PULSE_SHAPES))
    threads = default_threads() if threads is None else int_at_least("threads", threads, 1)
    shape, (a_, e_, r_, f_) = _cases(alpha, e, pfa_ratio, freq_ratio)
    n = a_.size
    outs = Answers(np.empty(n), np.empty(n, dtype=np.bool_), np.empty(n, dtype=np.bool_), np.empty(n, dtype=np.int8),
                   np.empty(n, dtype=np.int64), np.empty(n, dtype=np.int64))
    cases = Cases(a_, e_, r_ * np.tan(a_), f_)  # k = PFA / g
    opts = BatchSettings(PULSE_IDS[pulse], settings.equations == "linearised", float(settings.max_dtau),
                         int(settings.steps_per_pulse), float(settings.rest_velocity), int(settings.max_impacts),
                         int(settings.step_limit))
    _load_kernel((cases, opts), outs)
    t0 = _time.perf_counter()
    _run_chunks((cases, opts), outs, n, threads)
    wall = _time.perf_counter() - t0
    theta_max, overturned, rocked, status, n_impacts, n_steps = (x.reshape(shape) for x in outs)
    theta_max = np.where(overturned, OVERTURNING_ANGLE, theta_max)  # pi/2 on overturning, as every solver's
    return GridResult(theta_max=theta_max, overturned=overturned, rocked=rocked, status=status,
                      n_impacts=n_impacts, n_steps=n_steps, wall_time_s=wall)


def _cases(alpha: Any, e: Any, pfa_ratio: Any, freq_ratio: Any) -> tuple[tuple, tuple[np.ndarray, ...]]:
    """The inputs broadcast together, checked, and flattened: their shape and the four flat arrays."""
    arrays = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (alpha, e, pfa_ratio, freq_ratio)))
    flat = tuple(np.ascontiguousarray(x).ravel() for x in arrays)
    for name, arr, low, high in zip(("alpha", "e", "pfa_ratio", "freq_ratio"), flat,
                                    (0.0, 0.0, 0.0, 0.0), (0.5 * math.pi, 1.0 + 1e-12, math.inf, math.inf)):
        _check_array(name, arr, low, high)
    return arrays[0].shape, flat


def _load_kernel(args: tuple, outs: tuple) -> None:
    """The kernel called on no case: numba loads it from its cache, or compiles it (announced on stderr), here,
    so that ``wall_time_s`` counts the solving alone (a first grid from an empty cache spent seconds compiling)."""
    announce_compile(_solve_chunk, "housner_fast")
    _solve_chunk(*args, 0, 0, outs)


def _run_chunks(args: tuple, outs: tuple, n: int, threads: int) -> None:
    """The kernel over chunks of :data:`_CHUNK` cases, on ``threads`` threads (it releases the GIL)."""
    bounds = [(i, min(i + _CHUNK, n)) for i in range(0, n, _CHUNK)]
    if threads == 1 or len(bounds) <= 1:
        for lo, hi in bounds:
            _solve_chunk(*args, lo, hi, outs)
        return
    with ThreadPoolExecutor(max_workers=threads) as pool:
        for fut in [pool.submit(_solve_chunk, *args, lo, hi, outs) for lo, hi in bounds]:
            fut.result()


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
        raise InputTypeError(f"blocks must be a non-empty sequence of Block, got {blocks!r}")
    r = np.asarray(pfa_ratios, dtype=float).ravel()
    f = np.asarray(freq_ratios, dtype=float).ravel()
    al = np.array([b.alpha for b in blocks])[:, None, None]
    ee = np.array([b.e for b in blocks])[:, None, None]
    return solve_grid(al, ee, r[None, :, None], f[None, None, :], settings=settings,
                      threads=threads, pulse=pulse)


__all__ = ["GridResult", "default_threads", "solve_grid", "solve_pulses"]
