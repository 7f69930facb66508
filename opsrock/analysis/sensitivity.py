"""How much does the answer move when the floor motion moves a little? A test for hypersensitive
(chaotic) responses.

On broadband floor motions the rocking response can be hypersensitive: a block that makes dozens of
small impacts can end a record far from where a copy scaled by ``1 + 1e-6`` ends (validation of the
SDOF model on records; `tools/sensitivity_probe.py`). Two solvers, or two step sizes of one solver,
differ by far more than 1e-6 in what they compute, so on such a case their theta_max cannot be
expected to agree case by case: only distributions (and fragility curves) can. This module gives the
test that separates the two kinds of case: the spread of theta_max (in alpha) and of the verdict over
copies of the excitation scaled by ``1 + eps`` for a few tiny ``eps``; and a convergence test, the
same spread between a solver's default numerics and tightened ones (:func:`step_convergence`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from opsrock.block import Block
from opsrock.errors import InputError
from opsrock.limits import positive_finite

#: Relative amplitude perturbations of the test: far below any physical uncertainty of a floor
#: motion and far above a solver's round-off.
DEFAULT_EPS: tuple[float, ...] = (-1e-6, 1e-6, -1e-5, 1e-5)
#: A case is sensitive if theta_max moves by more than this (in alpha) or its verdict changes.
DEFAULT_THRESHOLD: float = 0.01


@dataclass(frozen=True)
class Sensitivity:
    """Result of :func:`amplitude_sensitivity`.

    Parameters
    ----------
    eps : tuple of float
        Perturbations used (0 first: the unperturbed run).
    theta_max_over_alpha : tuple of float
        theta_max / alpha of each run (nan where it failed).
    verdicts : tuple of str
        Verdict of each run.
    spread : float
        Largest minus smallest theta_max / alpha over the finished runs that did not overturn
        (inf if some overturned and some did not).
    sensitive : bool
        ``spread > threshold`` or the verdicts differ.
    threshold : float
        The threshold used (alpha).
    """

    eps: tuple[float, ...]
    theta_max_over_alpha: tuple[float, ...]
    verdicts: tuple[str, ...]
    spread: float
    sensitive: bool
    threshold: float


def _scaled(excitation: Any, factor: float) -> Any:
    if hasattr(excitation, "scaled"):
        return excitation.scaled(factor)
    return dataclasses.replace(excitation, pfa=excitation.pfa * factor)


def amplitude_sensitivity(block: Block, excitation: Any, solver: str = "housner_fast", *,
                          eps: tuple[float, ...] = DEFAULT_EPS, threshold: float = DEFAULT_THRESHOLD,
                          **settings: Any) -> Sensitivity:
    """Run ``solver`` on ``excitation`` and on copies scaled by ``1 + eps``; report the spread.

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation
        A pulse (its ``pfa`` is scaled) or a record (``Record.scaled``).
    solver : str, optional
        One of :data:`opsrock.solvers.SOLVERS`. Default ``"housner_fast"``.
    eps : tuple of float, optional
        Relative perturbations, each with ``|eps| < 0.01`` (dimensionless).
    threshold : float, optional
        Spread of theta_max / alpha above which the case is sensitive. Default 0.01.
    **settings
        Solver settings.
    """
    from opsrock.solvers import simulate

    positive_finite("threshold", threshold)
    eps = (0.0, *tuple(float(e) for e in eps))
    if any(not (abs(e) < 0.01) for e in eps):
        raise InputError(f"eps must lie in (-0.01, 0.01), got {eps[1:]!r}")
    runs = [simulate(block, _scaled(excitation, 1.0 + e), solver, **settings) for e in eps]
    th, verdicts, spread, sensitive = _spread(runs, threshold)
    return Sensitivity(eps, th, verdicts, spread, sensitive, threshold)


def _spread(runs, threshold: float) -> tuple[tuple[float, ...], tuple[str, ...], float, bool]:
    """theta_max / alpha and verdict of each run, their spread (see :class:`Sensitivity`), and
    whether it exceeds ``threshold`` or the verdicts differ."""
    th = tuple(r.theta_max_over_alpha if r.ok else float("nan") for r in runs)
    verdicts = tuple(r.verdict for r in runs)
    done = [v for v in verdicts if v != "failed"]
    if len(set(done)) > 1 and "overturned" in done:
        spread = float("inf")
    else:
        vals = np.array([t for t, v in zip(th, verdicts) if v not in ("failed", "overturned")])
        spread = float(vals.max() - vals.min()) if vals.size else 0.0
    return th, verdicts, spread, bool(spread > threshold or len(set(done)) > 1)


#: Numerics tightened for the convergence test, per solver: the scipy solvers' tolerances by 100x;
#: the OpenSees step by 4x (2e-3 -> 5e-4 s) and its band steps by 4x (20 -> 80).
TIGHTENED: dict[str, dict[str, Any]] = {
    "sdof": {"rtol": 1e-12, "atol": 1e-15},
    "housner": {"rtol": 1e-12, "atol": 1e-15},
    "opensees": {"step": 5e-4, "band_steps": 80},
}


@dataclass(frozen=True)
class Convergence:
    """Result of :func:`step_convergence`.

    Parameters
    ----------
    theta_max_over_alpha : tuple of float
        theta_max / alpha with the given settings, then with :data:`TIGHTENED` numerics.
    verdicts : tuple of str
        Verdict of each run.
    spread : float
        As :attr:`Sensitivity.spread`.
    converged : bool
        ``spread <= threshold`` and the same verdict.
    threshold : float
        The threshold used (alpha).
    """

    theta_max_over_alpha: tuple[float, ...]
    verdicts: tuple[str, ...]
    spread: float
    converged: bool
    threshold: float


def step_convergence(block: Block, excitation: Any, solver: str, *, threshold: float = DEFAULT_THRESHOLD,
                     **settings: Any) -> Convergence:
    """Run ``solver`` with ``settings`` and again with its numerics tightened (:data:`TIGHTENED`).

    Parameters
    ----------
    block : Block
        The block.
    excitation : Excitation
        The floor motion.
    solver : str
        One of the keys of :data:`TIGHTENED`.
    threshold : float, optional
        Largest change of theta_max / alpha of a converged case. Default 0.01.
    **settings
        Solver settings of the first run (the tightened run overrides the :data:`TIGHTENED` ones).
    """
    from opsrock.solvers import simulate

    positive_finite("threshold", threshold)
    if solver not in TIGHTENED:
        raise InputError(f"solver must be one of {sorted(TIGHTENED)}, got {solver!r}")
    runs = [simulate(block, excitation, solver, **settings),
            simulate(block, excitation, solver, **{**settings, **TIGHTENED[solver]})]
    th, verdicts, spread, moved = _spread(runs, threshold)
    return Convergence(th, verdicts, spread, not moved, threshold)


__all__ = [
    "DEFAULT_EPS", "DEFAULT_THRESHOLD", "TIGHTENED", "Convergence", "Sensitivity", "amplitude_sensitivity",
    "step_convergence",
]
