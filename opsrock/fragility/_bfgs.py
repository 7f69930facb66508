"""scipy's BFGS without its call overhead, for the many small MLE fits of the bootstraps.

``scipy.optimize.minimize(fun, x0, jac=True, method="BFGS", options={"gtol": gtol})`` spends most of
a two-parameter fit in its wrappers (scalar-function memoisation, array copies, checks), not in the
function. :func:`minimize_bfgs` runs the same algorithm, the loop of ``scipy.optimize._optimize.
_minimize_bfgs`` with scipy's own Wolfe line searches, on the same numpy operations in the same
order, so its result is the same to the last bit; only the wrappers are gone.

It is used only with a scipy release it was checked against (:data:`CHECKED_SCIPY`, the version of
the lock file; ``tests/fragility/test_speed_postprocessing.py`` compares it bit for bit with
``scipy.optimize.minimize``). With any other scipy, :func:`minimize_bfgs` calls
``scipy.optimize.minimize`` itself: the same numbers as before, at the old speed.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import scipy
from scipy import optimize

#: scipy releases whose BFGS :func:`minimize_bfgs` reproduces bit for bit (checked by the tests).
CHECKED_SCIPY: tuple[str, ...] = ("1.17.1",)

try:  # scipy's own line-search pieces (private modules): the lean loop calls exactly what scipy calls
    from scipy.optimize._dcsrch import dcstep
    from scipy.optimize._linesearch import LineSearchWarning, line_search_wolfe2
except ImportError:  # pragma: no cover - another scipy layout: fall back to scipy.optimize.minimize
    LEAN = False
else:
    LEAN = scipy.__version__ in CHECKED_SCIPY

# scipy's messages (scipy.optimize._optimize._status_message)
_SUCCESS = "Optimization terminated successfully."
_MAXITER = "Maximum number of iterations has been exceeded."
_PR_LOSS = "Desired error not necessarily achieved due to precision loss."
_NAN = "NaN result encountered."


@dataclass
class BFGSResult:
    """The fields of scipy's ``OptimizeResult`` that the fits read."""

    x: np.ndarray
    fun: float
    status: int
    success: bool
    message: str
    nfev: int


#: Calls of :func:`minimize_bfgs` and of ``scipy.optimize.minimize`` from it (counted for the tests).
CALLS = {"lean": 0, "scipy": 0}


def minimize_bfgs(fun_and_grad: Callable[[np.ndarray], tuple[float, np.ndarray]], x0: np.ndarray,
                  gtol: float) -> BFGSResult:
    """``scipy.optimize.minimize(fun_and_grad, x0, jac=True, method="BFGS", options={"gtol": gtol})``.

    Parameters
    ----------
    fun_and_grad : callable
        ``x -> (f, grad)``: a Python float and a 1-D float array; it must not modify ``x``.
    x0 : array_like
        Start (1-D floats).
    gtol : float
        Gradient tolerance (infinity norm).
    """
    if not LEAN:
        CALLS["scipy"] += 1
        res = optimize.minimize(fun_and_grad, x0, jac=True, method="BFGS", options={"gtol": gtol})
        return BFGSResult(res.x, float(res.fun), int(res.status), bool(res.success), str(res.message),
                          int(res.nfev))
    CALLS["lean"] += 1
    return _bfgs(fun_and_grad, x0, gtol)


def _bfgs(fun_and_grad, x0, gtol: float) -> BFGSResult:
    # The body of scipy.optimize._optimize._minimize_bfgs (scipy 1.17) with its defaults
    # (norm=inf, c1=1e-4, c2=0.9, xrtol=0, maxiter=200 len(x0), no callback, no hess_inv0); the
    # scalar-function wrapper becomes the memo below (the function is deterministic, so when it is
    # evaluated does not change any value), and the Wolfe line search is _line_search_wolfe1.
    x0 = np.asarray(x0).flatten()
    if x0.dtype.kind in np.typecodes["AllInteger"]:
        x0 = np.asarray(x0, dtype=float)
    memo = _Memo(fun_and_grad)
    f, myfprime = memo.f, memo.g
    c1, c2, xrtol = 1e-4, 0.9, 0
    maxiter = len(x0) * 200
    old_fval = f(x0)
    gfk = myfprime(x0)
    k = 0
    N = len(x0)
    I = np.eye(N, dtype=int)  # noqa: E741 (scipy's names throughout)
    Hk = I
    old_old_fval = old_fval + np.linalg.norm(gfk) / 2
    xk = x0
    warnflag = 0
    gnorm = np.amax(np.abs(gfk))
    with np.errstate(invalid="ignore", over="ignore"):  # as dcsrch's steps (only warnings are silenced)
        while (gnorm > gtol) and (k < maxiter):
            pk = -np.dot(Hk, gfk)
            ret = _line_search_wolfe1(memo, xk, pk, gfk, old_fval, old_old_fval, c1, c2, 1e-100, 1e100)
            if ret[0] is None:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore", LineSearchWarning)
                    ret = line_search_wolfe2(f, myfprime, xk, pk, gfk, old_fval, old_old_fval, extra_condition=None,
                                             c1=c1, c2=c2, amax=1e100)
            if ret[0] is None:
                warnflag = 2
                break
            alpha_k, _fc, _gc, old_fval, old_old_fval, gfkp1 = ret
            sk = alpha_k * pk
            xkp1 = xk + sk
            xk = xkp1
            if gfkp1 is None:
                gfkp1 = myfprime(xkp1)
            yk = gfkp1 - gfk
            gfk = gfkp1
            k += 1
            gnorm = np.amax(np.abs(gfk))
            if gnorm <= gtol:
                break
            if alpha_k * _norm2(pk) <= xrtol * (xrtol + _norm2(xk)):
                break
            if not np.isfinite(old_fval):
                warnflag = 2
                break
            rhok_inv = np.dot(yk, sk)
            if rhok_inv == 0.:
                rhok = 1000.0
            else:
                rhok = 1. / rhok_inv
            A1 = I - sk[:, np.newaxis] * yk[np.newaxis, :] * rhok
            A2 = I - yk[:, np.newaxis] * sk[np.newaxis, :] * rhok
            Hk = np.dot(A1, np.dot(Hk, A2)) + (rhok * sk[:, np.newaxis] * sk[np.newaxis, :])
    fval = old_fval
    if warnflag == 2:
        msg = _PR_LOSS
    elif k >= maxiter:
        warnflag = 1
        msg = _MAXITER
    elif np.isnan(gnorm) or np.isnan(fval) or np.isnan(xk).any():
        warnflag = 3
        msg = _NAN
    else:
        msg = _SUCCESS
    return BFGSResult(xk, float(fval), warnflag, warnflag == 0, msg, memo.n)


class _Memo:
    """The function and its gradient at the last point asked (scipy's scalar-function memoisation)."""

    __slots__ = ("fun", "g_", "n", "x", "x_", "f_")

    def __init__(self, fun_and_grad) -> None:
        self.fun, self.x, self.x_, self.f_, self.g_, self.n = fun_and_grad, None, None, None, None, 0

    def _at(self, x: np.ndarray) -> None:
        xs = x.tolist()  # equal lists <=> np.array_equal (NaN differs from itself; 0.0 equals -0.0)
        if self.x_ is None or xs != self.x_:
            f, g = self.fun(x)
            if not np.isscalar(f):
                f = np.asarray(f).item()
            self.x, self.x_, self.f_, self.g_ = np.array(x, dtype=float), xs, f, np.atleast_1d(g)
            self.n += 1

    def f(self, x: np.ndarray):
        self._at(x)
        return self.f_

    def g(self, x: np.ndarray) -> np.ndarray:
        self._at(x)
        return self.g_


def _first_step(phi0: float, old_old_fval, derphi0: float) -> float:
    """``scalar_search_wolfe1``'s first trial step (no unit): from the last two objective values, at most 1."""
    if old_old_fval is not None and derphi0 != 0:
        alpha1 = min(1.0, 1.01 * 2 * (phi0 - old_old_fval) / derphi0)
        return 1.0 if alpha1 < 0 else alpha1
    return 1.0


def _line_search_wolfe1(memo: _Memo, xk, pk, gfk, old_fval, old_old_fval, c1: float, c2: float, amin: float,
                        amax: float):
    """``scipy.optimize._linesearch.line_search_wolfe1`` (``scalar_search_wolfe1`` and ``DCSRCH`` with
    ``xtol=1e-14``, ``maxiter=100``), the same steps in the same arithmetic, without the objects: returns
    ``(stp, fc, gc, phi1, phi0, gval)`` with ``stp`` None when no step is found."""
    gval = gfk
    n_f = n_g = 0
    derphi0 = np.dot(gfk, pk)
    phi0 = old_fval
    alpha1 = _first_step(phi0, old_old_fval, derphi0)
    ftol, gtol, xtol, stpmin, stpmax = c1, c2, 1e-14, amin, amax
    p5, p66, xtrapl, xtrapu = 0.5, 0.66, 1.1, 4.0
    stp, f, g = alpha1, phi0, derphi0
    # DCSRCH's first call (task START): the checks, then the first trial step
    if stp < stpmin or stp > stpmax or g >= 0 or ftol < 0 or gtol < 0 or xtol < 0 or stpmin < 0 or stpmax < stpmin:
        return None, n_f, n_g, f, phi0, gval
    brackt, stage = False, 1
    finit, ginit = f, g
    gtest = ftol * ginit
    width = stpmax - stpmin
    width1 = width / p5
    stx, fx, gx = 0.0, finit, ginit
    sty, fy, gy = 0.0, finit, ginit
    stmin, stmax = 0, stp + xtrapu * stp
    for i in range(100):  # DCSRCH.__call__: the first pass was the START above; 100 evaluations at most
        if i:  # DCSRCH._iterate on the last evaluation
            ftest = finit + stp * gtest
            if stage == 1 and f <= ftest and g >= 0:
                stage = 2
            warn = ((brackt and (stp <= stmin or stp >= stmax))  # rounding errors prevent progress
                    or (brackt and stmax - stmin <= xtol * stmax)  # xtol test satisfied
                    or (stp == stpmax and f <= ftest and g <= gtest)  # stp = stpmax
                    or (stp == stpmin and (f > ftest or g >= gtest)))  # stp = stpmin
            if f <= ftest and abs(g) <= gtol * -ginit:  # convergence, over any warning
                return stp, n_f, n_g, f, phi0, gval
            if warn:
                return None, n_f, n_g, f, phi0, gval
            if stage == 1 and f <= fx and f > ftest:
                fm = f - stp * gtest
                fxm = fx - stx * gtest
                fym = fy - sty * gtest
                gm = g - gtest
                gxm = gx - gtest
                gym = gy - gtest
                stx, fxm, gxm, sty, fym, gym, stp, brackt = dcstep(stx, fxm, gxm, sty, fym, gym, stp, fm, gm, brackt,
                                                                   stmin, stmax)
                fx = fxm + stx * gtest
                fy = fym + sty * gtest
                gx = gxm + gtest
                gy = gym + gtest
            else:
                stx, fx, gx, sty, fy, gy, stp, brackt = dcstep(stx, fx, gx, sty, fy, gy, stp, f, g, brackt, stmin,
                                                               stmax)
            if brackt:
                if abs(sty - stx) >= p66 * width1:
                    stp = stx + p5 * (sty - stx)
                width1 = width
                width = abs(sty - stx)
            if brackt:
                stmin = min(stx, sty)
                stmax = max(stx, sty)
            else:
                stmin = stp + xtrapl * (stp - stx)
                stmax = stp + xtrapu * (stp - stx)
            stp = np.clip(stp, stpmin, stpmax)
            if brackt and (stp <= stmin or stp >= stmax) or (brackt and stmax - stmin <= xtol * stmax):
                stp = stx
        if not np.isfinite(stp):
            return None, n_f, n_g, f, phi0, gval
        x = xk + stp * pk  # phi(stp) and derphi(stp): one point, one evaluation
        f = memo.f(x)
        gval = memo.g(x)
        n_f += 1
        n_g += 1
        g = np.dot(gval, pk)
    return None, n_f, n_g, f, phi0, gval  # maxiter reached


def _norm2(x: np.ndarray):
    # scipy.optimize._optimize.vecnorm(x, ord=2)
    return np.sum(np.abs(x)**2, axis=0)**(1.0 / 2)
