"""The paper's least-squares lognormal fit to strip fractions (Eq. 15-16)."""

from __future__ import annotations

import math

import numpy as np

from opsrock.errors import InputError
from opsrock.fragility.lognormal import BETA_BOUNDS, LognormalFit, failed_fit
from opsrock.fragility.optimise import least_squares_box

#: crawls towards the ``beta`` bound for hundreds of iterations).
LS_MAX_EVALUATIONS: int = 300


def fit_lognormal_least_squares(
    x: np.ndarray, fraction: np.ndarray, decreasing: bool = False
) -> LognormalFit:
    """Least-squares lognormal fit to strip fractions (paper Eq. 15-16).

    Minimises ``sum (P_i - Phi(s ln(x_i / mu) / beta))²`` over ``mu`` and ``beta``
    (``s = -1`` for a decreasing IM), from several starting ``beta`` values, keeping the best.

    Parameters
    ----------
    x : array_like
        Strip centres (IM units, > 0).
    fraction : array_like
        Overturning fraction in each strip (dimensionless, in [0, 1]).
    decreasing : bool, optional
        IM orientation.

    Returns
    -------
    LognormalFit
    """
    x = np.asarray(x, dtype=float)
    f = np.asarray(fraction, dtype=float)
    method = "least_squares"
    if x.shape != f.shape or x.ndim != 1:
        raise InputError(f"x and fraction must be 1-D of equal length, got {x.shape} and {f.shape}")
    if np.any(~np.isfinite(x) | (x <= 0)):
        raise InputError(f"x must be positive and finite, got {x[~np.isfinite(x) | (x <= 0)][0]!r}")
    if np.any((f < 0) | (f > 1) | ~np.isfinite(f)):
        raise InputError("fraction must lie in [0, 1]")
    if x.size < 2:
        return failed_fit(method, int(x.size), decreasing, f"{x.size} strip(s): need at least 2")
    if np.all(f == 0) or np.all(f == 1):
        return failed_fit(method, int(x.size), decreasing,
                           "every strip fraction is %d: no transition to fit" % f[0])
    if np.all((f == 0) | (f == 1)):
        return failed_fit(method, int(x.size), decreasing,
                           "every strip fraction is 0 or 1: the strip fractions are a step and "
                           "beta is not identified")
    from scipy import special  # scipy.special here, not at the top: it imports numpy.f2py and numpy.testing (0.2 s of every command's start)

    s = -1.0 if decreasing else 1.0
    lx = np.log(x)

    def model(q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        # the residuals r = f - Phi(z), z = s (ln x - m) / beta, their Jacobian in (m, beta), and sum r ∇²r
        z = s * (lx - q[0]) / q[1]
        phi = np.exp(-0.5 * z**2) / math.sqrt(2.0 * math.pi)
        r = f - special.ndtr(z)
        jac = np.empty((lx.size, 2))  # np.stack([...], axis=1), without its checks
        jac[:, 0] = phi * s / q[1]
        jac[:, 1] = phi * z / q[1]
        w = r * phi / q[1] ** 2  # ∇²Phi(z) = phi (∇²z - z ∇z ∇zᵀ), ∇z = -(s, z) / beta
        wz, wz2 = w * z, w * z**2
        total = np.add.reduce  # np.sum of a 1-D array, without its wrapper
        off = -s * (total(w) - total(wz2))
        return r, jac, np.array([[total(wz), off], [off, total(wz2 * z) - 2.0 * total(wz)]])

    # start the median where the fractions cross 1/2 (nearest strip), beta from the spread
    m0 = float(lx[np.argmin(np.abs(f - 0.5))])
    spread = float(np.ptp(lx)) if np.ptp(lx) > 0 else 1.0
    lo = [lx.min() - 3 * spread, BETA_BOUNDS[0]]
    hi = [lx.max() + 3 * spread, BETA_BOUNDS[1]]
    best = None
    for b0 in (0.05, 0.2, 0.5, 1.5):
        q0 = [m0, float(np.clip(b0 * max(spread, 0.1), *BETA_BOUNDS))]
        res = least_squares_box(model, q0, lo, hi, LS_MAX_EVALUATIONS)
        if best is None or res.fun < best.fun:
            best = res
    mu, beta = math.exp(best.x[0]), float(best.x[1])
    ok, msg = _judge(best, mu, beta, lo, hi, x)
    return LognormalFit(mu, beta, 100.0 * beta / mu, method, int(x.size), decreasing, ok, msg, 2.0 * best.fun)


def _judge(best, mu: float, beta: float, lo: list, hi: list, x: np.ndarray) -> tuple[bool, str]:
    """Whether the least-squares optimum is a fit, and why not: a parameter at its bound, or a transition
    narrower than one strip."""
    ok, msg = bool(best.success), str(best.message)
    if beta <= BETA_BOUNDS[0] * (1 + 1e-6):
        return False, "beta at its lower bound: the strip fractions are a step"
    if beta >= BETA_BOUNDS[1] * (1 - 1e-6):
        return False, "beta at its upper bound: no transition in the data"
    if not (lo[0] < best.x[0] < hi[0]) or abs(best.x[0] - lo[0]) < 1e-9 or abs(best.x[0] - hi[0]) < 1e-9:
        return False, "median at its bound: outside the data"
    if ok:
        # Resolution: the fitted curve rises from 16 % to 84 % over about 2 beta mu (IM units).
        # If that is narrower than one strip, the strip fractions cannot tell beta = 0.02 from
        # 0.002: the data are a step at strip resolution and beta is not identified.
        spacing = float(np.median(np.diff(np.sort(x))))
        if 2.0 * beta * mu < spacing:
            return False, (f"beta = {beta:.3g} below the strip resolution: the fitted transition "
                           f"2 beta mu = {2 * beta * mu:.3g} is narrower than one strip ({spacing:.3g})")
    return ok, msg
