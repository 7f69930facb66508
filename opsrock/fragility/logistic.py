"""Logistic regression on ``ln IM``: the cloud-analysis alternative to the probit (lognormal) MLE.

``P(overturning | IM = x) = 1 / (1 + exp(-(ln(x / mu)) / s))`` (mirrored for a decreasing IM): the
median ``mu`` is where P = 1/2, ``s`` the logistic scale in ``ln IM``. The lognormal dispersion with
the same standard deviation of ``ln IM`` at failure is ``beta_equivalent = pi s / sqrt(3)``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from opsrock.errors import InputError
from opsrock.fragility.optimise import newton


@dataclass(frozen=True)
class LogisticFit:
    """A logistic fragility fit.

    Parameters
    ----------
    mu : float
        Median (IM units).
    scale : float
        Logistic scale ``s`` in ``ln IM`` (dimensionless).
    beta_equivalent : float
        ``pi s / sqrt(3)`` (dimensionless): comparable with a lognormal ``beta``.
    n_points : int
        Cases fitted.
    decreasing : bool
        Orientation of the IM.
    success : bool
        False when no finite optimum exists (one kind of outcome, perfect separation).
    message : str
        Diagnostic.
    loglik_per_case : float
        Maximum log-likelihood per case.
    """

    mu: float
    scale: float
    beta_equivalent: float
    n_points: int
    decreasing: bool
    success: bool
    message: str = ""
    loglik_per_case: float = math.nan

    def probability(self, x: np.ndarray | float) -> np.ndarray:
        """Fitted ``P(overturning | IM = x)``."""
        from scipy import special  # scipy.special here, not at the top: it imports numpy.f2py and numpy.testing (0.2 s of every command's start)

        s = -1.0 if self.decreasing else 1.0
        return special.expit(s * np.log(np.asarray(x, dtype=float) / self.mu) / self.scale)


def fit_logistic(values: np.ndarray, overturned: np.ndarray, decreasing: bool = False) -> LogisticFit:
    """Maximum-likelihood logistic regression of the outcomes on ``ln IM``.

    Parameters
    ----------
    values : array_like
        IM value of each case (IM units, > 0).
    overturned : array_like of bool
        Outcome of each case.
    decreasing : bool, optional
        IM orientation (True for IM1).
    """
    x = np.asarray(values, dtype=float)
    y = np.asarray(overturned, dtype=bool)
    if x.shape != y.shape or x.ndim != 1:
        raise InputError(f"values and overturned must be 1-D of equal length, got {x.shape} and {y.shape}")
    if np.any(~np.isfinite(x) | (x <= 0)):
        raise InputError("values must be positive and finite")
    n = int(x.size)
    s = -1.0 if decreasing else 1.0
    u = s * np.log(x) if n else x
    if n == 0 or y.all() or (~y).all() or (u[~y].max() <= u[y].min()):
        return LogisticFit(math.nan, math.nan, math.nan, n, decreasing, False,
                           "one kind of outcome, or perfectly separated: no finite optimum")
    mean, sd = float(u.mean()), float(u.std()) or 1.0
    v = (u - mean) / sd
    yf = y.astype(float)

    from scipy import special  # scipy.special here, not at the top: it imports numpy.f2py and numpy.testing (0.2 s of every command's start)

    def nll(q):  # concave log-likelihood in (a, b): the optimiser cannot wander off
        z = q[0] + q[1] * v
        val = np.sum(np.logaddexp(0.0, z) - yf * z)
        p = special.expit(z)
        w = p * (1.0 - p)
        wv = w * v
        h01 = np.sum(wv)
        return val, np.array([np.sum(p - yf), np.sum((p - yf) * v)]), np.array([[np.sum(w), h01], [h01, np.sum(wv * v)]])

    res = newton(nll, np.array([0.0, 1.0]))
    a, b = res.x
    if not (res.success or res.status == 2) or b <= 0:
        return LogisticFit(math.nan, math.nan, math.nan, n, decreasing, False, f"optimiser: {res.message}")
    scale = sd / b
    mu = math.exp(s * (mean - a * sd / b))
    return LogisticFit(mu, scale, math.pi * scale / math.sqrt(3.0), n, decreasing, True, "",
                       -float(res.fun) / n)
