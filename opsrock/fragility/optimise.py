"""The two-parameter optimisers of the fits, on analytic derivatives and numpy alone.

Every fit of the fragility layer has two parameters and analytic first and second derivatives, and a
record study runs thousands of them (bootstrap resamples, ranking resamples, block sets), so the fits do
not go through a general-purpose optimiser and its wrappers:

* :func:`newton`: damped Newton on a convex objective (the probit and logistic negative log-likelihoods,
  concave in ``(a, b)`` of ``P = F(a + b v)``), for :mod:`~opsrock.fragility.mle` and
  :mod:`~opsrock.fragility.logistic`;
* :func:`least_squares_box`: Newton / Levenberg-Marquardt on ``0.5 sum r²`` inside a box, for the paper's
  least-squares fit (:mod:`~opsrock.fragility.least_squares`).

Rules both keep:

* **Converged means at the optimum to rounding.** Newton converges quadratically: a run stops when its
  step is below ``xtol`` relative to the point (then the point is the optimum to about ``xtol²``); when
  no step can lower the objective any further and the last step was already below :data:`FLAT_STEP`
  relative (the objective is flat to rounding there); or, for the least squares, when an accepted step
  lowers the cost by at most :data:`FTOL` of it (at the optimum, or on the floor of a flat valley, where
  strip fractions of 0 and 1 leave the curve free between two strips). Each is ``status`` 0.
* **A run that cannot get there says so**: ``status`` 1 when the evaluations run out (``max_nfev``),
  ``status`` 2 when the line search cannot lower the objective from a point that is not yet converged.
* **Work is counted in the result** (:attr:`Optimum.nfev`), never in a module-level counter.
* Only numpy: the same numbers with every scipy release the package allows.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

#: ``Optimum.message`` by ``Optimum.status``.
MESSAGES: dict[int, str] = {
    0: "Optimization terminated successfully.",
    1: "Maximum number of function evaluations has been exceeded.",
    2: "Desired error not necessarily achieved due to precision loss.",
}

#: A last step below this (relative to the point) that cannot lower the objective ends a run converged.
FLAT_STEP: float = 1e-8

#: Sufficient decrease of the backtracking line search (Armijo constant, dimensionless).
ARMIJO: float = 1e-4

#: Rounding allowance of the objective's value (relative) when the gradient still falls.
ROUNDING: float = 8.0 * np.finfo(float).eps


@dataclass(frozen=True)
class Optimum:
    """The end of a run of :func:`newton` or :func:`least_squares_box`.

    Parameters
    ----------
    x : ndarray
        The point (the objective's parameter units).
    fun : float
        The objective at ``x`` (:func:`least_squares_box`: the cost ``0.5 sum r²``).
    status : int
        0 converged, 1 evaluations exhausted, 2 no decrease from a point not yet converged.
    message : str
        :data:`MESSAGES` of ``status``.
    nfev : int
        Evaluations of the model (value and derivatives together).
    """

    x: np.ndarray
    fun: float
    status: int
    message: str
    nfev: int

    @property
    def success(self) -> bool:
        """True when the run converged (``status`` 0)."""
        return self.status == 0


def _solve2(h: np.ndarray, g: np.ndarray) -> np.ndarray | None:
    """``-h⁻¹ g`` of a symmetric 2x2 ``h`` by its explicit inverse; None unless ``h`` is positive definite."""
    a, b, d = float(h[0, 0]), float(h[0, 1]), float(h[1, 1])
    det = a * d - b * b
    if not (a > 0.0 and det > 0.0):
        return None
    g0, g1 = float(g[0]), float(g[1])
    return np.array([-(d * g0 - b * g1) / det, -(a * g1 - b * g0) / det])


def _small(step: np.ndarray, x: np.ndarray, tol: float) -> bool:
    """Whether ``step`` is below ``tol`` relative to ``x`` (absolute below 1)."""
    s0, s1 = step.tolist()
    x0, x1 = x.tolist()
    return max(abs(s0), abs(s1)) <= tol * max(1.0, abs(x0), abs(x1))


def _accept(f_new: float, g_new: np.ndarray, f: float, g: np.ndarray, decrease: float) -> bool:
    """Sufficient decrease, or a value equal to rounding with a smaller gradient (at the optimum the
    objective's value no longer separates the points; its gradient still does)."""
    if not math.isfinite(f_new):
        return False
    if f_new <= f + decrease:
        return True
    if f_new > f + ROUNDING * abs(f):
        return False
    (a0, a1), (b0, b1) = g_new.tolist(), g.tolist()
    return max(abs(a0), abs(a1)) < max(abs(b0), abs(b1))


def newton(model: Callable[[np.ndarray], tuple[float, np.ndarray, np.ndarray]], x0: np.ndarray,
           xtol: float = 1e-12, max_nfev: int = 200) -> Optimum:
    """Minimise a smooth convex function of two parameters by damped Newton.

    Parameters
    ----------
    model : callable
        ``x -> (f, g, h)``: the objective (float), its gradient (2 floats) and its Hessian (2x2), at ``x``.
    x0 : ndarray
        Start (2 floats, the parameters' units).
    xtol : float, optional
        Converged when the Newton step is at most ``xtol`` relative to the point (dimensionless).
    max_nfev : int, optional
        Evaluations of ``model`` allowed.

    Returns
    -------
    Optimum

    Notes
    -----
    Where ``h`` is not positive definite the step is the steepest descent ``-g``; the step is halved
    until the value falls by the Armijo share of the predicted decrease (or, equal to rounding, the
    gradient falls).
    """
    x = np.array(x0, dtype=float)
    f, g, h = model(x)
    nfev = 1
    while nfev < max_nfev:
        p = _solve2(h, g)
        if p is None:
            p = -g
        if _small(p, x, xtol):
            return Optimum(x, float(f), 0, MESSAGES[0], nfev)
        slope, alpha = float(g @ p), 1.0
        while True:
            trial = x + alpha * p
            f_new, g_new, h_new = model(trial)
            nfev += 1
            if _accept(f_new, g_new, f, g, ARMIJO * alpha * slope):
                break
            alpha *= 0.5
            if nfev >= max_nfev or _small(alpha * p, x, xtol):
                status = 0 if _small(p, x, FLAT_STEP) else (1 if nfev >= max_nfev else 2)
                return Optimum(x, float(f), status, MESSAGES[status], nfev)
        x, f, g, h = trial, f_new, g_new, h_new
    return Optimum(x, float(f), 1, MESSAGES[1], nfev)


#: A step stops at this fraction of the way to a bound it would cross (the points stay inside the box).
TO_BOUND: float = 0.995

#: An accepted step that lowers the cost by at most this share of it ends the run (converged).
FTOL: float = 1e-15

#: Gauss-Newton steps shorter than this (relative to the point) switch to Newton on the full Hessian.
POLISH: float = 1e-4


def _damped(jtj: np.ndarray, damping: float) -> np.ndarray:
    """``jtj`` with ``damping`` times its diagonal added to the diagonal (Marquardt's scaling)."""
    out = jtj.copy()
    out[0, 0] *= 1.0 + damping
    out[1, 1] *= 1.0 + damping
    return out


def _box_step(g: np.ndarray, h: np.ndarray, jtj: np.ndarray, damping: float) -> np.ndarray:
    """The step of :func:`least_squares_box` before the box: Levenberg-Marquardt on ``jtj`` (``damping``
    relative to its diagonal; Gauss-Newton at 0), or Newton on the full Hessian ``h`` once the
    Gauss-Newton step is short and ``h`` positive definite (quadratic convergence at a non-zero residual)."""
    p = _solve2(_damped(jtj, damping), g) if damping > 0.0 else _solve2(jtj, g)
    if p is None:
        p = _solve2(_damped(jtj, max(damping, 1e-8)), g)
    if p is None:
        return -g
    if damping == 0.0:
        newton_step = _solve2(h, g)
        if newton_step is not None and max(abs(p[0]), abs(p[1])) <= POLISH:
            return newton_step
    return p


def _inside(x: np.ndarray, step: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> np.ndarray:
    """``step`` with each component shortened to :data:`TO_BOUND` of the way to the bound it would cross."""
    out = []
    for si, xi, li, ui in zip(step.tolist(), x.tolist(), lb.tolist(), ub.tolist()):
        room = xi - li if si < 0.0 else ui - xi
        out.append(si * TO_BOUND * room / abs(si) if abs(si) > room else si)
    return np.array(out)


def _held(x: np.ndarray, g: np.ndarray, lb: np.ndarray, ub: np.ndarray) -> np.ndarray:
    """Parameters within ``1e-9`` (relative) of a bound with the gradient pushing them out of the box."""
    held = []
    for xi, gi, li, ui in zip(x.tolist(), g.tolist(), lb.tolist(), ub.tolist()):
        near = 1e-9 * max(1.0, abs(xi))
        held.append((xi - li <= near and gi > 0.0) or (ui - xi <= near and gi < 0.0))
    return np.array(held)


def _held_step(g: np.ndarray, jtj: np.ndarray, held: np.ndarray, damping: float) -> np.ndarray:
    """The Levenberg-Marquardt step of the parameter not held on its bound (none if both are)."""
    step = np.zeros(2)
    if held.all():
        return step
    i = int(np.flatnonzero(~held)[0])
    curvature = jtj[i, i] * (1.0 + damping)
    step[i] = -g[i] / curvature if curvature > 0.0 else -g[i]
    return step


def least_squares_box(model: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]], x0, lb, ub,
                      max_nfev: int, xtol: float = 1e-12) -> Optimum:
    """Minimise ``0.5 sum r(x)²`` over two parameters inside the box ``lb < x < ub``.

    Levenberg-Marquardt steps on ``JᵀJ`` (damping from ``1e-3`` of its diagonal, raised fourfold after a
    step that does not lower the cost, lowered fourfold after one that does, down to Gauss-Newton), and
    Newton steps on the full Hessian ``JᵀJ + sum r_i ∇²r_i`` near the optimum. A step component that would
    cross a bound stops :data:`TO_BOUND` of the way to it, so every point stays strictly inside the box and an
    optimum on a bound is approached geometrically.

    Parameters
    ----------
    model : callable
        ``x -> (r, J, S)``: the residuals (m floats), their Jacobian (m x 2) and ``sum r_i ∇²r_i`` (2x2).
    x0 : array_like
        Start, strictly inside the box (2 floats, the parameters' units).
    lb, ub : array_like
        The box (2 floats each, the parameters' units), ``lb < ub``.
    max_nfev : int
        Evaluations of ``model`` allowed.
    xtol : float, optional
        Converged when a step is at most ``xtol`` relative to the point (dimensionless).

    Returns
    -------
    Optimum
        ``fun`` is the cost ``0.5 sum r²``.
    """
    lb, ub = np.asarray(lb, dtype=float), np.asarray(ub, dtype=float)
    x = np.array(x0, dtype=float)
    r, jac, s = model(x)
    nfev, cost, damping = 1, 0.5 * float(r @ r), 1e-3
    while nfev < max_nfev:
        g, jtj = jac.T @ r, jac.T @ jac
        held = _held(x, g, lb, ub)
        step = _held_step(g, jtj, held, damping) if held.any() else _box_step(g, jtj + s, jtj, damping)
        step = _inside(x, step, lb, ub)
        if _small(step, x, xtol):
            return Optimum(x, cost, 0, MESSAGES[0], nfev)
        r_new, jac_new, s_new = model(x + step)
        nfev += 1
        cost_new = 0.5 * float(r_new @ r_new)
        if _accept(cost_new, jac_new.T @ r_new, cost, g, 0.0):
            flat = cost - cost_new <= FTOL * cost
            x, r, jac, s, cost = x + step, r_new, jac_new, s_new, cost_new
            if flat:  # the cost no longer falls: at the optimum to rounding, or on a flat valley floor
                return Optimum(x, cost, 0, MESSAGES[0], nfev)
            damping = 0.0 if damping < 1e-9 else damping / 4.0
        elif damping > 1e12:
            status = 0 if _small(step, x, FLAT_STEP) else 2
            return Optimum(x, cost, status, MESSAGES[status], nfev)
        else:
            damping = max(4.0 * damping, 1e-4)
    return Optimum(x, cost, 1, MESSAGES[1], nfev)
