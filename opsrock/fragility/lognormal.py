"""The lognormal fragility curve (paper Eq. 14) and the fit result every method returns."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: CDF is a step at the resolution of any IM table; above 20 it is flat over 10 decades.
BETA_BOUNDS: tuple[float, float] = (1e-3, 20.0)

#: Cap on residual evaluations per least-squares start (a step-like data set otherwise

def fragility_probability(
    x: np.ndarray | float, mu: float, beta: float, decreasing: bool = False
) -> np.ndarray:
    """Lognormal overturning fragility (Eq. 14), mirrored for a decreasing IM.

    Parameters
    ----------
    x : array_like
        IM values (IM units, > 0).
    mu : float
        Median (IM units): the IM of 50 % overturning probability.
    beta : float
        Logarithmic standard deviation (dimensionless); 0 gives a step at ``mu``.
    decreasing : bool, optional
        True for IM1: ``Phi(ln(mu / x) / beta)``; else ``Phi(ln(x / mu) / beta)``.

    Returns
    -------
    ndarray
        ``P(overturning | IM = x)``.
    """
    from scipy import special  # scipy.special here, not at the top: it imports numpy.f2py and numpy.testing (0.2 s of every command's start)

    x = np.asarray(x, dtype=float)
    s = -1.0 if decreasing else 1.0
    z = s * np.log(x / mu)
    if beta == 0.0:
        return np.where(z > 0, 1.0, np.where(z < 0, 0.0, 0.5))
    return special.ndtr(z / beta)


@dataclass(frozen=True)
class LognormalFit:
    """A lognormal fragility fit (Eq. 14): median ``mu``, dispersion ``beta``.

    Parameters
    ----------
    mu : float
        Median (IM units).
    beta : float
        Dispersion (dimensionless).
    cv_percent : float
        The paper's ``CV = 100 beta / mu`` (% per IM unit; not scale-free).
    method : str
        ``"least_squares"`` (Eq. 15-16 on strip fractions) or ``"mle"``.
    n_points : int
        Strips (least squares) or cases (MLE) fitted.
    decreasing : bool
        Orientation (see :func:`fragility_probability`).
    success : bool
        False when the fit is not to be trusted (too few points, ``beta`` at a bound,
        perfectly separated outcomes, optimiser failure); ``message`` says why.
    message : str
        Diagnostic.
    objective : float
        Sum of squared errors (Eq. 15) or negative log-likelihood at the optimum.
    """

    mu: float
    beta: float
    cv_percent: float
    method: str
    n_points: int
    decreasing: bool = False
    success: bool = True
    message: str = ""
    objective: float = math.nan

    def probability(self, x: np.ndarray | float) -> np.ndarray:
        """Fitted ``P(overturning | IM = x)``."""
        return fragility_probability(x, self.mu, self.beta, self.decreasing)


def failed_fit(method: str, n: int, decreasing: bool, message: str) -> LognormalFit:
    """A fit that could not be made: NaN parameters, ``success=False`` and the reason (``message``)."""
    return LognormalFit(math.nan, math.nan, math.nan, method, n, decreasing, False, message)
