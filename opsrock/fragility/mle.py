"""Maximum-likelihood lognormal fit on 0/1 outcomes (Bernoulli likelihood, probit on ln IM), with
seeded percentile-bootstrap intervals. On IDA/MSA levels it is the binomial MLE of Baker (2015).

How the bootstrap is computed (a record campaign fits thousands of resamples), with the same numbers as
the textbook evaluation (``tests/unit/fragility/test_speed_postprocessing.py``):

* the resamples are drawn up front from the seed (:func:`resample_indices`, the same generator calls in
  the same order), so any range of them can be fitted anywhere (:class:`MLEPlan`, :class:`opsrock._pool.TaskPool`);
* each fit is damped Newton on the analytic gradient and Hessian (:func:`opsrock.fragility.optimise.newton`),
  converged to rounding: a few evaluations, no general-purpose optimiser and its wrappers;
* the likelihood is evaluated once per *distinct* case of a resample (a resample repeats whole records;
  a scene's measure takes a few values) with one ``log_ndtr`` per case instead of two, then gathered back
  so that every sum runs over the same values in the same order (:class:`_ProbitNLL`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from opsrock._pool import TaskPool
from opsrock.errors import InputError
from opsrock.fragility.lognormal import BETA_BOUNDS, LognormalFit
from opsrock.fragility.optimise import newton
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


#: ``0.5 ln(2 pi)``: ``ln phi(z) = -z²/2 - _HALF_LN_2PI``.
_HALF_LN_2PI = 0.5 * math.log(2 * math.pi)


class _ProbitNLL:
    """``-log-likelihood`` of ``P = Phi(a + b v)`` on 0/1 outcomes, its gradient and Hessian in ``(a, b)``.

    Every per-case quantity is computed once per *distinct* case (``v``, ``y`` of the table) and
    gathered back to all cases (``inverse``, one table row per case, in case order) before each sum:
    a bootstrap resample repeats whole records, and a scene's own measure takes a few values. The
    sums run over the same values in the same order as over the cases themselves, and one
    ``log_ndtr`` of ``+-z`` gives ``log Phi(z)`` for an overturned case and ``log Phi(-z)`` for a safe
    one, exactly the two terms of the likelihood: the value and the gradient are those of the
    textbook per-case evaluation to the last bit. The second derivative in ``z`` is
    ``lambda (lambda + sign z)`` with ``lambda`` the inverse Mills ratio ``phi(z) / Phi(sign z)``.
    """

    __slots__ = ("inverse", "neg_sign", "sign", "v", "v_cases")

    def __init__(self, v: np.ndarray, y: np.ndarray, inverse: np.ndarray | None = None) -> None:
        self.v = v
        self.sign = np.where(y, 1.0, -1.0)
        self.neg_sign = -self.sign
        self.inverse = inverse
        self.v_cases = v if inverse is None else np.take(v, inverse)

    def __call__(self, ab: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
        """The value, the gradient and the Hessian in ``(a, b)`` at ``ab``."""
        from scipy import special  # scipy.special here, not at the top: it imports numpy.f2py and numpy.testing (0.2 s of every command's start)

        z = ab[0] + ab[1] * self.v
        lp = special.log_ndtr(self.sign * z)  # log Phi(z) if overturned, log Phi(-z) if safe
        log_phi = -0.5 * z**2 - _HALF_LN_2PI
        ratio = np.exp(log_phi - lp)  # the inverse Mills ratio phi(z) / Phi(sign z)
        dz = self.neg_sign * ratio  # d(-loglik)/dz: -phi/Phi(z) for y = 1, +phi/Phi(-z) for y = 0
        d2z = ratio * (ratio + self.sign * z)  # d²(-loglik)/dz² > 0
        if self.inverse is not None:
            lp, dz, d2z = np.take(lp, self.inverse), np.take(dz, self.inverse), np.take(d2z, self.inverse)
        total = np.add.reduce  # np.sum of a 1-D array, without its wrapper
        v = self.v_cases
        d2z_v = d2z * v
        h01 = total(d2z_v)
        hess = np.array([[total(d2z), h01], [h01, total(d2z_v * v)]])
        return -float(total(lp)), np.array([total(dz), total(dz * v)]), hess


class Table(NamedTuple):
    """The distinct cases of a fit (:meth:`DistinctCases.table`): their ``u`` and outcome ``y``, the row of
    each case of the fit among them (``inverse``) and their positions among the base cases (``base``)."""

    u: np.ndarray
    y: np.ndarray
    inverse: np.ndarray
    base: np.ndarray


def _mle_core(u: np.ndarray, y: np.ndarray | None, q0: np.ndarray | None = None,
              table: Table | None = None) -> tuple[np.ndarray, float, bool, str]:
    """Probit MLE in ``u = s ln x``: returns ((m, ln beta), nll, success, message).

    Fitted as ``P = Phi(a + b v)`` on the standardised ``v = (u - mean) / sd``, whose
    log-likelihood is concave in ``(a, b)`` (probit regression), so the optimiser cannot
    wander off; then ``beta = sd / b`` and ``m = mean - a sd / b``. ``q0`` (a previous
    ``(m, ln beta)``) only seeds the start. With ``table`` (the distinct cases of ``u``) the likelihood
    runs over the distinct cases and ``y`` is not read; the mean and spread are those of ``u``.
    """
    centre, sd = float(np.mean(u)), float(np.std(u)) or 1.0
    if q0 is not None:
        b0 = sd / math.exp(q0[1])
        start = np.array([-(q0[0] - centre) / sd * b0, b0])
    else:
        start = np.array([0.0, 1.0])
    if table is None:
        nll = _ProbitNLL((u - centre) / sd, y)
    else:
        nll = _ProbitNLL((table.u - centre) / sd, table.y, table.inverse)
    res = newton(nll, start)
    a, b = res.x
    ok = res.success or res.status == 2  # status 2: flat to rounding before the step tolerance
    msg = str(res.message)
    if not b > 0:
        return np.array([math.nan, math.nan]), float(res.fun), False, (
            "overturning does not grow with the (oriented) IM: slope b = %.3g <= 0" % b)
    beta = sd / b
    m = centre - a * sd / b
    if not BETA_BOUNDS[0] < beta < BETA_BOUNDS[1]:
        ok, msg = False, f"beta = {beta:.3g} outside {BETA_BOUNDS}"
    return np.array([m, math.log(beta)]), float(res.fun), ok, msg


class DistinctCases:
    """Which cases of a fit are the same case: equal IM value ``x`` and equal outcome (hence equal ``u``),
    and equal ``flag`` if given (a caller that reads another per-case flag of the distinct cases, such as
    whether a case rocked, keeps the cases that differ in it apart).

    ``first[k]`` is the first case of distinct case ``k``, ``ids[i]`` the distinct case of case ``i``.
    :meth:`table` turns a resample (positions of cases, repeats allowed) into the :class:`Table` of
    :func:`_mle_core`: the distinct cases it holds and the row of each of its cases.
    """

    def __init__(self, x: np.ndarray, y: np.ndarray, u: np.ndarray, flag: np.ndarray | None = None) -> None:
        _, value_ids = np.unique(x, return_inverse=True)
        key = value_ids.ravel() * 2 + y
        if flag is not None:
            key = key * 2 + np.asarray(flag, dtype=bool)
        _, self.first, self.ids = np.unique(key, return_index=True, return_inverse=True)
        self.ids = self.ids.ravel()
        self.n = int(self.first.size)
        self.u, self.y = u, y

    def table(self, idx: np.ndarray | None = None) -> Table:
        """The :class:`Table` of the resample ``idx`` (positions of cases; all cases if None)."""
        ids = self.ids if idx is None else self.ids[idx]
        present = np.zeros(self.n, dtype=bool)
        present[ids] = True
        row_of = np.cumsum(present) - 1
        base = self.first[present]
        return Table(self.u[base], self.y[base], row_of[ids], base)


def group_members(groups: np.ndarray | None, shape: tuple) -> list[np.ndarray] | None:
    """Indices of each group's cases, groups in order of first appearance (None: cases are independent)."""
    if groups is None:
        return None
    g = np.asarray(groups)
    if g.shape != shape:
        raise InputError(f"groups must have one label per case, got {g.shape} for {shape}")
    if g.size == 0:
        return []
    try:
        if g.dtype.kind in "fc" and np.isnan(g).any():
            raise TypeError("NaN labels")  # NaN == NaN is False: the loop below keeps that meaning
        _, first, inverse = np.unique(g, return_index=True, return_inverse=True)
    except TypeError:  # labels that do not sort, or NaN: one comparison per group
        return [np.flatnonzero(g == label) for label in dict.fromkeys(g.tolist())]
    code = np.argsort(np.argsort(first, kind="stable"), kind="stable")[inverse.ravel()]  # by first appearance
    order = np.argsort(code, kind="stable")  # each group's cases in increasing position
    return np.split(order, np.cumsum(np.bincount(code, minlength=first.size))[:-1])


def resample_indices(n: int, members: list[np.ndarray] | None, n_boot: int, seed: int) -> list[np.ndarray]:
    """The ``n_boot`` seeded resamples of the bootstrap, drawn up front: positions of cases, ``n`` cases
    with replacement, or (``members``) the cases of as many groups drawn with replacement."""
    rng = np.random.default_rng(seed)
    if members is None:
        return [rng.integers(0, n, n) for _ in range(n_boot)]
    k = len(members)
    return [np.concatenate([members[i] for i in rng.integers(0, k, k)]) for _ in range(n_boot)]


@dataclass(frozen=True)
class PointFit:
    """The MLE of :func:`fit_lognormal_mle` without its intervals (:func:`point_fit`).

    ``q`` is ``(m, ln beta)`` of a finite optimum (None when there is none: one kind of outcome, perfect
    separation, a median run off to 0 or infinity); ``ok`` and ``message`` as ``MLEFit.success`` and
    ``MLEFit.message``.
    """

    mu: float
    beta: float
    cv_percent: float
    ok: bool
    message: str
    objective: float = math.nan
    loglik_per_case: float = math.nan
    q: np.ndarray | None = None


def point_fit(u: np.ndarray, y: np.ndarray | None, s: float, table: Table | None = None) -> PointFit:
    """The maximum-likelihood fit of :func:`fit_lognormal_mle` on ``u = s ln x`` (no intervals).

    ``table`` (:meth:`DistinctCases.table` of these cases) lets the likelihood be evaluated once per
    distinct case when many cases repeat (a resample of records, a scene's own measure that takes a few
    values); the checks read it too (the same sets of values), and ``y`` is then not needed.
    """
    n = int(u.size)
    cu, cy = (u, y) if table is None else (table.u, table.y)
    if n == 0 or cy.all() or (~cy).all():
        return PointFit(math.nan, math.nan, math.nan, False, "outcomes are all one kind: no fragility to fit")
    if _separated(cu, cy):
        gap_mid = 0.5 * (cu[~cy].max() + cu[cy].min())
        return PointFit(math.exp(s * gap_mid), 0.0, 0.0, False,
                        "outcomes perfectly separated by the IM: no finite MLE (beta -> 0); mu is the middle "
                        "of the gap", objective=0.0, loglik_per_case=0.0)
    q, value, ok, msg = _mle_core(u, y, table=table)
    with np.errstate(over="ignore"):
        mu, beta = float(np.exp(s * q[0])), float(np.exp(q[1]))
    if not (math.isfinite(mu) and mu > 0.0 and math.isfinite(beta)):
        # the optimiser ran off to a median of 0 or infinity: too few or too one-sided outcomes
        return PointFit(math.nan, math.nan, math.nan, False,
                        f"no finite MLE: the median ran off to {mu!r} (too few transitional outcomes)",
                        objective=value)
    return PointFit(mu, beta, 100.0 * beta / mu, ok, msg, value, -value / n, q)


#: A fit evaluates its likelihood on the distinct cases when they are at most this share of the cases.
_TABLE_SHARE: float = 0.75


class MLEPlan:
    """:func:`fit_lognormal_mle` in three steps, so that its resamples can be shared out:
    :func:`plan_mle` makes the checks and the point fit, :meth:`draws` fits a range of the seeded
    resamples (any range, in any process: the resamples are drawn up front from the seed, the same
    draws whatever the range), :meth:`finish` takes the percentiles of all of them, in order.
    ``finish(draws(0, n_boot))`` is ``fit_lognormal_mle``.
    """

    def __init__(self, x: np.ndarray, y: np.ndarray, s: float, point: PointFit, members: list[np.ndarray] | None,
                 common: dict, distinct: DistinctCases | None) -> None:
        self.x, self.u, self.y, self.s = x, s * np.log(x), y, s
        self.point, self.members, self.common = point, members, common
        self.n_boot = common["n_boot"] if point.q is not None else 0
        self._distinct = distinct
        self._resamples: list[np.ndarray] | None = None

    def __getstate__(self) -> dict:  # sent to a worker without its caches (rebuilt there if needed)
        return {**self.__dict__, "_distinct": None, "_resamples": None}

    def draws(self, lo: int = 0, hi: int | None = None) -> list[tuple[float, float] | None]:
        """``(mu, beta)`` of resamples ``lo`` to ``hi - 1``; None for a resample with no fit (one kind of
        outcome, perfect separation, an optimiser failure)."""
        hi = self.n_boot if hi is None else min(hi, self.n_boot)
        if lo >= hi:
            return []
        if self._resamples is None:
            self._resamples = resample_indices(self.u.size, self.members, self.n_boot, self.common["seed"])
        if self._distinct is None:
            self._distinct = DistinctCases(self.x, self.y, self.u)
        start = self.point.q if self.point.ok else None
        out: list[tuple[float, float] | None] = []
        for idx in self._resamples[lo:hi]:
            table = self._distinct.table(idx)  # the checks on it read the resample's own sets of values
            if table.y.all() or (~table.y).all() or _separated(table.u, table.y):
                out.append(None)
                continue
            qb, _, okb, _ = _mle_core(self.u[idx], None, start, table)
            out.append((math.exp(self.s * qb[0]), math.exp(qb[1])) if okb else None)
        return out

    def finish(self, draws: list[tuple[float, float] | None]) -> MLEFit:
        """The :class:`MLEFit`, with percentile bounds over the resamples that gave a fit."""
        p, common = self.point, self.common
        if p.q is None:
            return MLEFit(p.mu, p.beta, p.cv_percent, success=False, objective=p.objective,
                          loglik_per_case=p.loglik_per_case, message=p.message, **common)
        fitted = [d for d in draws if d is not None]
        lo = hi = (math.nan, math.nan)
        if len(fitted) >= 2:
            arr = np.array(fitted)
            tail = 50.0 * (1.0 - common["confidence"])
            lo = tuple(np.percentile(arr, tail, axis=0))
            hi = tuple(np.percentile(arr, 100.0 - tail, axis=0))
        return MLEFit(p.mu, p.beta, p.cv_percent, success=p.ok, message=p.message, objective=p.objective,
                      mu_lo=float(lo[0]), mu_hi=float(hi[0]), beta_lo=float(lo[1]), beta_hi=float(hi[1]),
                      n_boot_used=len(fitted), loglik_per_case=p.loglik_per_case, **common)


def plan_mle(values: np.ndarray, overturned: np.ndarray, decreasing: bool = False, n_boot: int = 200,
             confidence: float = 0.95, seed: int = 0, groups: np.ndarray | None = None) -> MLEPlan:
    """The checks and the point fit of :func:`fit_lognormal_mle` (same parameters); its resamples are
    fitted by :meth:`MLEPlan.draws`."""
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
    distinct = DistinctCases(x, y, u) if n else None
    point = point_fit(u, y, s, distinct.table() if n and distinct.n <= _TABLE_SHARE * n else None)
    members = group_members(groups, x.shape) if point.q is not None else None  # checks groups, as before
    return MLEPlan(x, y, s, point, members, common, distinct)


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
    plan = plan_mle(values, overturned, decreasing, n_boot, confidence, seed, groups)
    return plan.finish(plan.draws())


#: Resamples per task when the resamples of fits are shared among worker processes.
CHUNK: int = 20


class PlanTasks:
    """Task state of :func:`fit_plans`: task ``(i, lo)`` draws resamples ``lo`` to ``lo + CHUNK - 1`` of plan ``i``."""

    def __init__(self, plans: list[MLEPlan]) -> None:
        self.plans = plans

    def tasks(self) -> list[tuple[int, int]]:
        return [(i, lo) for i, p in enumerate(self.plans) for lo in range(0, p.n_boot, CHUNK)]

    def run(self, i: int, lo: int) -> list:
        return self.plans[i].draws(lo, lo + CHUNK)

    def finish(self, tasks: list[tuple[int, int]], results: list) -> list[MLEFit]:
        draws: list[list] = [[] for _ in self.plans]
        for (i, _), r in zip(tasks, results):
            draws[i] += r
        return [p.finish(d) for p, d in zip(self.plans, draws)]


def fit_plans(plans: list[MLEPlan], workers: int = 1) -> list[MLEFit]:
    """``[plan.finish(plan.draws()) for plan in plans]``, the resamples shared among ``workers`` processes
    (:class:`~opsrock._pool.TaskPool`): the same fits whatever ``workers``."""
    state = PlanTasks(plans)
    tasks = state.tasks()
    with TaskPool(state, tasks, workers) as pool:
        return state.finish(tasks, pool.results())
