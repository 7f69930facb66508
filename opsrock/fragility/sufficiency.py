"""Sufficiency of an IM (Luco and Cornell 2007): given the IM, does the outcome still depend on
something else (magnitude, distance, the building's period)?

Fits the probit model ``P = Phi(a + b ln IM + c z)`` with ``z`` the standardised covariate and
tests ``c = 0`` with the Wald statistic from the observed information (numerical Hessian of the
log-likelihood). A small p-value says the IM is not sufficient with respect to that covariate: two
floor motions with the same IM but different ``z`` overturn the block with different probabilities.

With ``groups`` (the record of each case) the standard error is the cluster-robust (sandwich) one,
``H^-1 (sum_g s_g s_g^T) H^-1`` with ``s_g`` the score summed over a record's cases: the cases of one
record scaled to many levels are not independent, and the plain Wald error would be too small.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, special, stats


@dataclass(frozen=True)
class SufficiencyTest:
    """Result of :func:`sufficiency`.

    Parameters
    ----------
    covariate : str
        Name of the covariate.
    coefficient : float
        ``c``: change of the probit index per standard deviation of the covariate.
    std_error : float
        Its standard error.
    z : float
        Wald statistic ``c / std_error``.
    p_value : float
        Two-sided p-value of ``c = 0``.
    n_points : int
        Cases used (finite IM and covariate).
    message : str
        Why the test could not be made, if so.
    """

    covariate: str
    coefficient: float
    std_error: float
    z: float
    p_value: float
    n_points: int
    message: str = ""


def _nll(q: np.ndarray, X: np.ndarray, y: np.ndarray) -> float:
    z = X @ q
    # one log_ndtr of +-z: log Phi(z) where y, log Phi(-z) elsewhere (the same numbers as two calls)
    return -float(np.sum(special.log_ndtr(np.where(y, z, -z))))


def _scores(q: np.ndarray, X: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Per-case gradient of the log-likelihood (n x 3)."""
    z = X @ q
    # d/dz log Phi(z) = phi/Phi, d/dz log Phi(-z) = -phi/Phi(-z), in a stable form
    e = np.exp(_log_phi(z) - special.log_ndtr(np.where(y, z, -z)))
    w = np.where(y, e, -e)
    return X * w[:, None]


def _log_phi(z: np.ndarray) -> np.ndarray:
    return -0.5 * z * z - 0.5 * math.log(2.0 * math.pi)


def sufficiency(values: np.ndarray, overturned: np.ndarray, covariate: np.ndarray, name: str,
                decreasing: bool = False, groups: np.ndarray | None = None) -> SufficiencyTest:
    """Wald test of the covariate's coefficient in a probit on ``ln IM`` and the covariate.

    Parameters
    ----------
    values : array_like
        IM values (IM units, > 0).
    overturned : array_like of bool
        Outcomes.
    covariate : array_like
        Covariate per case (any unit; standardised here).
    name : str
        Its name, for the result.
    decreasing : bool, optional
        IM orientation.
    groups : array_like, optional
        Cluster label per case (the record): cluster-robust standard error.
    """
    x = np.asarray(values, dtype=float)
    y = np.asarray(overturned, dtype=bool)
    c = np.asarray(covariate, dtype=float)
    keep = np.isfinite(x) & (x > 0) & np.isfinite(c)
    x, y, c = x[keep], y[keep], c[keep]
    g = None if groups is None else np.asarray(groups)[keep]
    n = int(x.size)
    nan = math.nan
    if n < 10 or y.all() or (~y).all() or np.std(c) == 0:
        return SufficiencyTest(name, nan, nan, nan, nan, n, "too few cases, one outcome, or a constant covariate")
    u = (-1.0 if decreasing else 1.0) * np.log(x)
    X = np.column_stack([np.ones(n), (u - u.mean()) / (u.std() or 1.0), (c - c.mean()) / c.std()])
    res = optimize.minimize(_nll, np.zeros(3), args=(X, y), method="BFGS", options={"gtol": 1e-9})
    h = 1e-4
    H = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            ei, ej = np.eye(3)[i] * h, np.eye(3)[j] * h
            H[i, j] = (_nll(res.x + ei + ej, X, y) - _nll(res.x + ei - ej, X, y)
                       - _nll(res.x - ei + ej, X, y) + _nll(res.x - ei - ej, X, y)) / (4 * h * h)
    try:
        cov = np.linalg.inv(H)
    except np.linalg.LinAlgError:
        return SufficiencyTest(name, float(res.x[2]), nan, nan, nan, n, "singular information (separated data)")
    if g is not None:
        sc = _scores(res.x, X, y)
        labels, inv = np.unique(g, return_inverse=True)
        sums = np.zeros((labels.size, 3))
        np.add.at(sums, inv, sc)
        cov = cov @ (sums.T @ sums) @ cov
    se = math.sqrt(cov[2, 2]) if cov[2, 2] > 0 else nan
    zval = float(res.x[2]) / se if se == se else nan
    p = float(2.0 * stats.norm.sf(abs(zval))) if zval == zval else nan
    return SufficiencyTest(name, float(res.x[2]), se, zval, p, n)
