"""scipy's bounded least squares without its call overhead, for the many small strip fits.

``scipy.optimize.least_squares(fun, x0, jac=jac, bounds=(lb, ub), method="trf", x_scale=..., xtol=...,
ftol=..., gtol=..., max_nfev=...)`` on a two-parameter fit spends most of its time in wrappers (the
vector-function memoisation and copies, the checks of ``scipy.linalg.svd``). :func:`least_squares_trf`
runs the same algorithm, the loop of ``scipy.optimize._lsq.trf.trf_bounds`` (``tr_solver="exact"``,
linear loss) with scipy's own helpers and the same LAPACK SVD, on the same operations in the same
order, so its result is the same to the last bit; only the wrappers are gone.

As :mod:`opsrock.fragility._bfgs`: used only with a scipy release it was checked against
(:data:`~opsrock.fragility._bfgs.CHECKED_SCIPY`; ``tests/fragility/test_speed_postprocessing.py`` compares it bit
for bit with ``scipy.optimize.least_squares``); with any other, ``scipy.optimize.least_squares`` runs.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy
from scipy import optimize

from opsrock.fragility._bfgs import CHECKED_SCIPY

try:  # scipy's own helpers (private modules): the lean loop calls exactly what scipy calls
    from scipy.linalg import get_lapack_funcs
    from scipy.linalg.lapack import _compute_lwork
    from scipy.optimize._lsq.common import (
        check_termination,
        compute_grad,
        evaluate_quadratic,
        in_bounds,
        make_strictly_feasible,
        solve_lsq_trust_region,
        update_tr_radius,
    )
    from scipy.optimize._lsq.least_squares import TERMINATION_MESSAGES
    from scipy.optimize._lsq.trf import select_step
except ImportError:  # pragma: no cover - another scipy layout: fall back to scipy.optimize.least_squares
    LEAN = False
else:
    LEAN = scipy.__version__ in CHECKED_SCIPY


@dataclass
class LSQResult:
    """The fields of scipy's ``OptimizeResult`` that the fits read."""

    x: np.ndarray
    cost: float
    status: int
    success: bool
    message: str
    nfev: int


#: Calls of :func:`least_squares_trf` and of ``scipy.optimize.least_squares`` from it (counted for the tests).
CALLS = {"lean": 0, "scipy": 0}


def least_squares_trf(fun: Callable[[np.ndarray], np.ndarray], jac: Callable[[np.ndarray], np.ndarray],
                      x0, lb, ub, x_scale, xtol: float, ftol: float, gtol: float, max_nfev: int) -> LSQResult:
    """``scipy.optimize.least_squares(fun, x0, jac=jac, bounds=(lb, ub), method="trf", x_scale=x_scale,
    xtol=xtol, ftol=ftol, gtol=gtol, max_nfev=max_nfev)`` (finite bounds, linear loss, dense ``jac``).

    ``fun`` and ``jac`` must be deterministic and must not modify their argument.
    """
    if not LEAN:
        CALLS["scipy"] += 1
        res = optimize.least_squares(fun, x0, jac=jac, bounds=(lb, ub), method="trf", x_scale=x_scale,
                                     xtol=xtol, ftol=ftol, gtol=gtol, max_nfev=max_nfev)
        return LSQResult(res.x, float(res.cost), int(res.status), bool(res.success), str(res.message),
                         int(res.nfev))
    CALLS["lean"] += 1
    return _least_squares(fun, jac, x0, lb, ub, x_scale, xtol, ftol, gtol, max_nfev)


_LWORK: dict[tuple, int] = {}
_GESDD: dict[tuple, tuple] = {}


def _svd(a: np.ndarray):
    # scipy.linalg.svd(a, full_matrices=False) for a float64 matrix: the same LAPACK driver and work size
    if not np.isfinite(a).all():
        raise ValueError("array must not contain infs or NaNs")
    kind = (a.dtype.char, a.flags.f_contiguous)
    if kind not in _GESDD:
        _GESDD[kind] = get_lapack_funcs(("gesdd", "gesdd_lwork"), (a,), ilp64="preferred")
    gesdd, gesdd_lwork = _GESDD[kind]
    key = (a.shape, kind)
    if key not in _LWORK:
        _LWORK[key] = _compute_lwork(gesdd_lwork, a.shape[0], a.shape[1], compute_uv=True, full_matrices=False)
    u, s, v, info = gesdd(a, compute_uv=True, lwork=_LWORK[key], full_matrices=False, overwrite_a=False)
    if info > 0:
        raise np.linalg.LinAlgError("SVD did not converge")
    if info < 0:
        raise ValueError("A has a NaN entry" if info == -4 else f"illegal value in {-info}th argument of gesdd")
    return u, s, v


def _norm(x: np.ndarray):
    # numpy.linalg.norm(x) of a 1-D float array: sqrt of its dot product with itself
    return np.sqrt(x.dot(x))


def _norm_inf(x: np.ndarray):
    # numpy.linalg.norm(x, ord=np.inf) of a 1-D float array
    return abs(x).max()


def _scaling_vector(x: np.ndarray, g: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    # scipy.optimize._lsq.common.CL_scaling_vector, element by element (finite bounds)
    v, dv = [], []
    for xi, gi, li, ui in zip(x.tolist(), g.tolist(), lb.tolist(), ub.tolist()):
        if gi > 0 and math.isfinite(li):
            v.append(xi - li)
            dv.append(1.0)
        elif gi < 0 and math.isfinite(ui):
            v.append(ui - xi)
            dv.append(-1.0)
        else:
            v.append(1.0)
            dv.append(0.0)
    return np.array(v), np.array(dv)


def _inside(x: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> bool:
    # scipy.optimize._lsq.common.in_bounds
    return all(li <= xi <= ui for xi, li, ui in zip(x.tolist(), lb.tolist(), ub.tolist()))


def _strictly_feasible(x: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> np.ndarray:
    # scipy.optimize._lsq.common.make_strictly_feasible(x, lb, ub, rstep=0), element by element
    out = []
    for xi, li, ui in zip(x.tolist(), lb.tolist(), ub.tolist()):
        if xi >= ui:
            xi = math.nextafter(ui, li)
        elif xi <= li:
            xi = math.nextafter(li, ui)
        if xi < li or xi > ui:
            xi = 0.5 * (li + ui)
        out.append(xi)
    return np.array(out)


def _prepared(fun, jac, x0, lb, ub, x_scale) -> tuple:
    # scipy.optimize.least_squares' preparation for method="trf": the checks, the strictly feasible start
    # and the first evaluation; returns (x0, lb, ub, x_scale, f0, J0)
    x0 = np.atleast_1d(x0).astype(float)
    lb, ub = (np.asarray(b, dtype=float) for b in (lb, ub))
    if lb.ndim == 0:
        lb = np.resize(lb, x0.shape[0])
    if ub.ndim == 0:
        ub = np.resize(ub, x0.shape[0])
    if lb.shape != x0.shape or ub.shape != x0.shape or np.any(lb >= ub) or not in_bounds(x0, lb, ub):
        raise ValueError("least_squares: inconsistent bounds or start")  # scipy raises here too
    x_scale = np.asarray(x_scale, dtype=float)
    if not (np.all(np.isfinite(x_scale)) and np.all(x_scale > 0)):
        raise ValueError("`x_scale` must be 'jac' or array_like with positive numbers.")
    if x_scale.ndim == 0:
        x_scale = np.resize(x_scale, x0.shape)
    if x_scale.shape != x0.shape:
        raise ValueError("Inconsistent shapes between `x_scale` and `x0`.")
    x0 = make_strictly_feasible(x0, lb, ub)
    f0 = np.atleast_1d(fun(x0.copy()))
    J0 = np.atleast_2d(jac(x0.copy()))
    if f0.ndim != 1:
        raise ValueError(f"`fun` must return at most 1-d array_like. f0.shape: {f0.shape}")
    if not np.all(np.isfinite(f0)):
        raise ValueError("Residuals are not finite in the initial point.")
    if J0.shape != (f0.size, x0.size):
        raise ValueError(f"The return value of `jac` has wrong shape: expected {(f0.size, x0.size)}, "
                         f"actual {J0.shape}.")
    if np.all(lb == -np.inf) and np.all(ub == np.inf):  # pragma: no cover - the fits always have bounds
        raise ValueError("least_squares_trf: bounds are required")
    return x0, lb, ub, x_scale, f0, J0


def _least_squares(fun, jac, x0, lb, ub, x_scale, xtol, ftol, gtol, max_nfev) -> LSQResult:
    # scipy.optimize.least_squares (_prepared) then scipy.optimize._lsq.trf.trf_bounds with tr_solver="exact",
    # no loss, no callback
    x0, lb, ub, x_scale, f0, J0 = _prepared(fun, jac, x0, lb, ub, x_scale)  # noqa: N806 (scipy's names)
    x = x0.copy()
    f = f0
    nfev = 1
    J = J0
    m, n = J.shape
    cost = 0.5 * np.dot(f, f)
    g = compute_grad(J, f)
    scale, scale_inv = x_scale, 1 / x_scale
    v, dv = _scaling_vector(x, g, lb, ub)
    v[dv != 0] *= scale_inv[dv != 0]
    Delta = _norm(x0 * scale_inv / v**0.5)  # noqa: N806 (scipy's names throughout)
    if Delta == 0:
        Delta = 1.0  # noqa: N806
    g_norm = _norm_inf(g * v)
    f_augmented = np.zeros(m + n)
    J_augmented = np.empty((m + n, n))  # noqa: N806
    alpha = 0.0
    termination_status = None
    while True:
        v, dv = _scaling_vector(x, g, lb, ub)
        g_norm = _norm_inf(g * v)
        if g_norm < gtol:
            termination_status = 1
        if termination_status is not None or nfev == max_nfev:
            break
        v[dv != 0] *= scale_inv[dv != 0]
        d = v**0.5 * scale
        diag_h = g * dv * scale
        g_h = d * g
        f_augmented[:m] = f
        J_augmented[:m] = J * d
        J_h = J_augmented[:m]  # noqa: N806
        J_augmented[m:] = np.diag(diag_h**0.5)
        U, s, V = _svd(J_augmented)  # noqa: N806
        V = V.T  # noqa: N806
        uf = U.T.dot(f_augmented)
        theta = max(0.995, 1 - g_norm)
        actual_reduction = -1
        while actual_reduction <= 0 and nfev < max_nfev:
            p_h, alpha, _ = solve_lsq_trust_region(n, m, uf, s, V, Delta, initial_alpha=alpha)
            p = d * p_h
            if _inside(x + p, lb, ub):  # select_step's first case, without its call
                step, step_h, predicted_reduction = p, p_h, -evaluate_quadratic(J_h, g_h, p_h, diag=diag_h)
            else:
                step, step_h, predicted_reduction = select_step(x, J_h, diag_h, g_h, p, p_h, d, Delta, lb, ub, theta)
            x_new = _strictly_feasible(x + step, lb, ub)
            f_new = np.atleast_1d(fun(x_new.copy()))
            nfev += 1
            step_h_norm = _norm(step_h)
            if not np.isfinite(f_new).all():
                Delta = 0.25 * step_h_norm  # noqa: N806
                continue
            cost_new = 0.5 * np.dot(f_new, f_new)
            actual_reduction = cost - cost_new
            Delta_new, ratio = update_tr_radius(Delta, actual_reduction, predicted_reduction,  # noqa: N806
                                                step_h_norm, step_h_norm > 0.95 * Delta)
            step_norm = _norm(step)
            termination_status = check_termination(actual_reduction, cost, step_norm, _norm(x), ratio, ftol, xtol)
            if termination_status is not None:
                break
            alpha *= Delta / Delta_new
            Delta = Delta_new  # noqa: N806
        if actual_reduction > 0:
            x = x_new
            f = f_new
            cost = cost_new
            J = np.atleast_2d(jac(x.copy()))  # noqa: N806
            g = compute_grad(J, f)
    if termination_status is None:
        termination_status = 0
    return LSQResult(x, float(cost), termination_status, termination_status > 0,
                     TERMINATION_MESSAGES[termination_status], nfev)
