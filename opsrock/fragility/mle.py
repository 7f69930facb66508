"""Maximum-likelihood lognormal fit on 0/1 outcomes (Bernoulli likelihood, probit on ln IM), with
seeded percentile-bootstrap intervals. On IDA/MSA levels it is the binomial MLE of Baker (2015)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize, special

from opsrock.errors import InputError
from opsrock.fragility.lognormal import BETA_BOUNDS, LognormalFit
from opsrock.limits import int_at_least


@dataclass(frozen=True)
class MLEFit(LognormalFit):
    """Maximum-likelihood lognormal fit on 0/1 outcomes, with bootstrap intervals.

    Parameters
    ----------
    mu_lo, mu_hi, beta_lo, beta_hi : float
        Percentile-bootstrap confidence bounds of ``mu`` (IM units) and ``beta``.
    confidence : float
        Confidence level of the bounds (e.g. 0.95).
    n_boot : int
        Bootstrap resamples drawn.
    n_boot_used : int
        Resamples that gave a finite MLE (resamples with perfectly separated outcomes have
        none and are left out; if many are, the bounds are optimistic).
    seed : int
        Seed of ``numpy.random.default_rng`` for the resampling.
    loglik_per_case : float
        Maximum log-likelihood divided by the number of cases: invariant under any
        monotone power-law change of the IM, so comparable between IMs.
    """

    mu_lo: float = math.nan
    mu_hi: float = math.nan
    beta_lo: float = math.nan
    beta_hi: float = math.nan
    confidence: float = 0.95
    n_boot: int = 0
    n_boot_used: int = 0
    seed: int = 0
    loglik_per_case: float = math.nan


def _separated(u: np.ndarray, y: np.ndarray) -> bool:
    """True if every overturned case has a larger (oriented) IM than every safe one."""
    return bool(y.any() and (~y).any() and u[~y].max() <= u[y].min())


def _mle_core(u: np.ndarray, y: np.ndarray, q0: np.ndarray | None = None
              ) -> tuple[np.ndarray, float, bool, str]:
    """Probit MLE in ``u = s ln x``: returns ((m, ln beta), nll, success, message).

    Fitted as ``P = Phi(a + b v)`` on the standardised ``v = (u - mean) / sd``, whose
    log-likelihood is concave in ``(a, b)`` (probit regression), so the optimiser cannot
    wander off; then ``beta = sd / b`` and ``m = mean - a sd / b``. ``q0`` (a previous
    ``(m, ln beta)``) only seeds the start.
    """
    centre, sd = float(np.mean(u)), float(np.std(u)) or 1.0
    v = (u - centre) / sd
    if q0 is not None:
        b0 = sd / math.exp(q0[1])
        start = np.array([-(q0[0] - centre) / sd * b0, b0])
    else:
        start = np.array([0.0, 1.0])

    def nll(ab: np.ndarray) -> tuple[float, np.ndarray]:
        z = ab[0] + ab[1] * v
        lp, lq = special.log_ndtr(z), special.log_ndtr(-z)
        value = -float(np.sum(np.where(y, lp, lq)))
        log_phi = -0.5 * z**2 - 0.5 * math.log(2 * math.pi)
        # d(-loglik)/dz: -phi/Phi(z) for y = 1, +phi/Phi(-z) for y = 0
        dz = np.where(y, -np.exp(log_phi - lp), np.exp(log_phi - lq))
        return value, np.array([np.sum(dz), np.sum(dz * v)])

    res = optimize.minimize(nll, start, jac=True, method="BFGS", options={"gtol": 1e-8})
    a, b = res.x
    ok = bool(res.success) or res.status == 2  # status 2: precision loss at the optimum
    msg = str(res.message)
    if not b > 0:
        return np.array([math.nan, math.nan]), float(res.fun), False, (
            "overturning does not grow with the (oriented) IM: slope b = %.3g <= 0" % b)
    beta = sd / b
    m = centre - a * sd / b
    if not BETA_BOUNDS[0] < beta < BETA_BOUNDS[1]:
        ok, msg = False, f"beta = {beta:.3g} outside {BETA_BOUNDS}"
    return np.array([m, math.log(beta)]), float(res.fun), ok, msg


def _group_members(groups: np.ndarray | None, shape: tuple) -> list[np.ndarray] | None:
    """Indices of each group's cases, groups in order of first appearance (None: cases are independent)."""
    if groups is None:
        return None
    g = np.asarray(groups)
    if g.shape != shape:
        raise InputError(f"groups must have one label per case, got {g.shape} for {shape}")
    return [np.flatnonzero(g == label) for label in dict.fromkeys(g.tolist())]


def _bootstrap(u: np.ndarray, y: np.ndarray, s: float, start: np.ndarray | None, n_boot: int, seed: int,
               members: list[np.ndarray] | None, confidence: float) -> tuple[tuple, tuple, int]:
    """Percentile bounds ``(mu_lo, beta_lo), (mu_hi, beta_hi)`` of the MLE over ``n_boot`` resamples of the
    cases (or of whole groups of them), and the number of resamples that gave a fit."""
    lo = hi = (math.nan, math.nan)
    if not n_boot:
        return lo, hi, 0
    n = u.size
    rng = np.random.default_rng(seed)
    draws = []
    for _ in range(n_boot):
        if members is None:
            idx = rng.integers(0, n, n)
        else:
            idx = np.concatenate([members[i] for i in rng.integers(0, len(members), len(members))])
        ub, yb = u[idx], y[idx]
        if yb.all() or (~yb).all() or _separated(ub, yb):
            continue
        qb, _, okb, _ = _mle_core(ub, yb, start)
        if okb:
            draws.append((math.exp(s * qb[0]), math.exp(qb[1])))
    if len(draws) >= 2:
        arr = np.array(draws)
        tail = 50.0 * (1.0 - confidence)
        lo = tuple(np.percentile(arr, tail, axis=0))
        hi = tuple(np.percentile(arr, 100.0 - tail, axis=0))
    return lo, hi, len(draws)


def fit_lognormal_mle(
    values: np.ndarray,
    overturned: np.ndarray,
    decreasing: bool = False,
    n_boot: int = 200,
    confidence: float = 0.95,
    seed: int = 0,
    groups: np.ndarray | None = None,
) -> MLEFit:
    """Maximum-likelihood lognormal fragility on the raw outcomes of rocking cases.

    Maximises ``sum y ln P + (1 - y) ln(1 - P)`` with ``P = Phi(s ln(x / mu) / beta)``
    (a probit regression on ``ln x``), then resamples the cases with replacement ``n_boot``
    times for percentile confidence bounds.

    Parameters
    ----------
    values : array_like
        IM value of each rocking case (IM units, > 0).
    overturned : array_like of bool
        Outcome of each case.
    decreasing : bool, optional
        IM orientation (True for IM1).
    n_boot : int, optional
        Bootstrap resamples (0: no intervals).
    confidence : float, optional
        Confidence level of the bounds, in (0, 1).
    seed : int, optional
        Seed of the resampling.
    groups : array_like, optional
        A label per case (e.g. the record name). When given, the bootstrap resamples whole groups
        with replacement, keeping each group's cases together: the cases of one record are not
        independent draws (the same record scaled to many levels), the records are.

    Returns
    -------
    MLEFit
    """
    x = np.asarray(values, dtype=float)
    y = np.asarray(overturned, dtype=bool)
    if x.shape != y.shape or x.ndim != 1:
        raise InputError(f"values and overturned must be 1-D of equal length, got {x.shape} and {y.shape}")
    if np.any(~np.isfinite(x) | (x <= 0)):
        raise InputError(f"values must be positive and finite, got {x[~np.isfinite(x) | (x <= 0)][0]!r}")
    n_boot = int_at_least("n_boot", n_boot, 0)
    if not 0.0 < confidence < 1.0:
        raise InputError(f"confidence must lie in (0, 1), got {confidence!r}")
    s = -1.0 if decreasing else 1.0
    u = s * np.log(x)
    n = int(x.size)
    common = dict(method="mle", n_points=n, decreasing=decreasing, confidence=confidence,
                  n_boot=n_boot, seed=seed)
    if n == 0 or y.all() or (~y).all():
        return MLEFit(math.nan, math.nan, math.nan, success=False,
                      message="outcomes are all one kind: no fragility to fit", **common)
    if _separated(u, y):
        gap_mid = 0.5 * (u[~y].max() + u[y].min())
        mu = math.exp(s * gap_mid)
        return MLEFit(mu, 0.0, 0.0, success=False, objective=0.0, loglik_per_case=0.0,
                      message="outcomes perfectly separated by the IM: no finite MLE "
                              "(beta -> 0); mu is the middle of the gap", **common)
    q, value, ok, msg = _mle_core(u, y)
    with np.errstate(over="ignore"):
        mu, beta = float(np.exp(s * q[0])), float(np.exp(q[1]))
    if not (math.isfinite(mu) and mu > 0.0 and math.isfinite(beta)):
        # the optimiser ran off to a median of 0 or infinity: too few or too one-sided outcomes
        return MLEFit(math.nan, math.nan, math.nan, success=False, objective=value,
                      message=f"no finite MLE: the median ran off to {mu!r} (too few transitional "
                              "outcomes)", **common)
    members = _group_members(groups, x.shape)
    lo, hi, used = _bootstrap(u, y, s, q if ok else None, n_boot, seed, members, confidence)
    return MLEFit(mu, beta, 100.0 * beta / mu, success=ok, message=msg, objective=value,
                  mu_lo=float(lo[0]), mu_hi=float(hi[0]), beta_lo=float(lo[1]),
                  beta_hi=float(hi[1]), n_boot_used=used, loglik_per_case=-value / n, **common)
