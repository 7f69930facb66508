"""The solver runs of validation case ``experiments``: free rocking of each model of
:data:`~opsrock.validation.experiments.constants.MODELS` from rest at a release angle."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np

from opsrock.block import Block
from opsrock.solvers import simulate
from opsrock.validation.experiments.constants import DECAY_IMPACTS, MODELS


@dataclass(frozen=True)
class DecayRun:
    """The free rocking of one model from rest (:func:`predict_decay`).

    Parameters
    ----------
    ratio : numpy.ndarray
        Angular-velocity ratio after/before of each logged impact, the first ``n_impacts`` (dimensionless);
        empty when the run failed.
    time : numpy.ndarray
        Times of every logged impact of the run (s); empty when it failed.
    e : float
        The model's restitution ``e`` (dimensionless).
    end_time : float
        End of the run (s).
    ok : bool
        The run finished with its impacts logged.
    reason : str
        The solver's reason for its end.
    wall_s : float
        Wall time of the run (s).
    """

    ratio: np.ndarray
    time: np.ndarray
    e: float
    end_time: float
    ok: bool
    reason: str
    wall_s: float


def free_rocking(block: Block, solver: str, theta0: float, end_time: float):
    """Free rocking of ``block`` from rest at ``theta0``; the :class:`~opsrock.result.RockingResult`.

    The one place of the case that runs a solver without excitation: the solver contract's start
    state (``theta0``) on a still floor (excitation None); every free-rocking run of the case goes
    through here.

    Parameters
    ----------
    block : Block
        The block (its ``e`` is used).
    solver : str
        ``"housner"``, ``"sdof"`` or ``"opensees"``.
    theta0 : float
        Release angle (rad).
    end_time : float
        End of the run (s); OpenSees runs to it (``stop_at_rest=False``), as its rest test would stop a
        free-rocking run at once.
    """
    extra = {"stop_at_rest": False} if solver == "opensees" else {}
    return simulate(block, None, solver=solver, theta0=theta0, end_time=end_time, **extra)


def _rigid_run(block: Block, theta0: float, n_impacts: int):
    """The rigid body (``housner``) until it has made ``n_impacts`` impacts (the end time doubles from 4 s).

    Parameters
    ----------
    block : Block
        The block (its ``e``).
    theta0 : float
        Release angle (rad).
    n_impacts : int
        Impacts wanted (no unit).
    """
    end = 4.0
    while True:
        r = free_rocking(block, "housner", theta0, end)
        if not r.ok or len(r.impacts) >= n_impacts or end >= 256.0:
            return r
        end *= 2.0


def model_blocks(width: float, height: float, factor: float) -> dict[str, Block]:
    """The block of each model of :data:`MODELS`.

    Parameters
    ----------
    width, height : float
        Block width B and height H (m).
    factor : float
        The fitted restitution factor ``e / e_R`` (dimensionless).
    """
    e_R = Block(width, height, restitution_factor=1.0).e_R
    return {name: Block(width, height, restitution=(factor if f is None else f) * e_R)
            for name, (_, f) in MODELS.items()}


def predict_decay(width: float, height: float, factor: float, release_ratio: float,
                  n_impacts: int = DECAY_IMPACTS, models: tuple[str, ...] = tuple(MODELS)) -> dict[str, DecayRun]:
    """Free rocking of each model from rest at ``release_ratio`` alpha: the logged impacts' ratios.

    The SDOF runs end after about ``n_impacts`` impacts: ``sdof`` at 1.1 times the rigid body's time of
    that impact (same ``e``; the SDOF model loses a little more per impact, so it gets there sooner)
    plus 0.5 s, ``opensees`` half an interval after the ``sdof`` run's impact ``n_impacts + 1`` (or its
    last, if it came to rest first), since OpenSees reports a block at rest inside the damper band as
    a numerical sawtooth (failed).

    Parameters
    ----------
    width, height : float
        Block width B and height H (m).
    factor : float
        The fitted restitution factor (dimensionless).
    release_ratio : float
        Release angle over alpha (dimensionless).
    n_impacts : int
        Impacts wanted (no unit).
    models : tuple of str
        Names of :data:`MODELS`.

    Returns
    -------
    dict of str to DecayRun
        The run of each model, by name.
    """
    blocks = model_blocks(width, height, factor)
    theta0 = release_ratio * blocks["sdof"].alpha
    out: dict[str, DecayRun] = {}
    for name in models:
        solver, block = MODELS[name][0], blocks[name]
        t0 = time.perf_counter()
        if solver == "housner":
            r = _rigid_run(block, theta0, n_impacts)
            end = float(r.time[-1]) if r.ok else math.nan
        else:
            twin = next(k for k, (s, f) in MODELS.items() if s == "housner" and f == MODELS[name][1])
            t_rigid = out[twin].time if twin in out else _rigid_run(block, theta0, n_impacts).impacts.time
            if solver == "sdof" or "sdof" not in out or not out["sdof"].ok:
                end = 1.1 * float(t_rigid[min(n_impacts, t_rigid.size) - 1]) + 0.5
            else:
                t = out["sdof"].time
                k = min(t.size, n_impacts + 1)
                end = float(t[k - 1] + 0.5 * (t[k - 1] - t[k - 2]))
            r = free_rocking(block, solver, theta0, end)
        ok = bool(r.ok and r.impacts is not None)
        out[name] = DecayRun(ratio=r.impacts.velocity_ratio[:n_impacts] if ok else np.array([]),
                             time=r.impacts.time if ok else np.array([]), e=block.e, end_time=end, ok=ok,
                             reason=r.reason, wall_s=time.perf_counter() - t0)
    return out
