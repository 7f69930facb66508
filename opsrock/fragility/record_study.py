"""Fragility from a record campaign: every IM fitted, ranked as the paper ranks them, with
intervals by record, resurrections counted, sufficiency tested and per-block curves for loss
assessment.

Input: the ``cases.csv`` of a record scene (:data:`opsrock.campaign.records.RECORD_CASES_COLUMNS`).

Choices:

* **Population.** The fits use every finished case: a case below uplift is a case that did not
  overturn (``P(overturning | IM)`` is what a loss assessment needs). The paper's hybrid ratio HR
  (Eq. 12) is computed, as in the paper, on the rocking cases only. Failed cases are excluded and
  counted.
* **Methods.** For IDA/MSA the binomial MLE of Baker (2015): the Bernoulli likelihood of every case
  with a probit on ``ln IM`` (:func:`opsrock.fragility.mle.fit_lognormal_mle`); for the scene's own
  measure its value is the level, so this is the per-level binomial likelihood exactly; for the
  other IMs each case carries its own value (a cloud of points). Beside it, a logistic regression
  on ``ln IM`` (:mod:`opsrock.fragility.logistic`).
* **Per block and floor** for loss assessment: the fits in PFA and PFV never pool floors (one
  block's fragility differs from floor to floor with the floor motions' frequency content).
* **Intervals** by resampling **records** with replacement (all cases of a record together),
  never single cases: the cases of one record at ten levels are not ten independent draws.
* **Resurrection** (:mod:`opsrock.fragility.ida`): counted per IDA curve; the fits use the outcome
  convention ``settings.outcome`` (default ``"as_simulated"``), and the scene's own measure is fitted
  under both conventions so their difference is visible.
* **Ranking.** Per IM: MLE median and ``beta`` with their intervals, HR, CV = ``100 beta / mu``
  (the paper's, not scale-free), and the log-likelihood per case. Winners by ``beta``, HR and CV,
  and how often each IM wins in the record bootstrap (:func:`ranking_frequencies`).
* **Computation.** Every resample of every fit is drawn from the seed up front and fitted on arrays;
  with ``workers`` > 1 the resamples are shared among processes and put back in order
  (:class:`~opsrock._pool.TaskPool`): the numbers do not depend on ``workers``. The ranking
  resamples fit only what the winners need (the MLE point fit and HR), not the logistic regression.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from opsrock._pool import TaskPool
from opsrock.errors import InputError
from opsrock.fragility.cases import check_some_finished, failed_groups
from opsrock.fragility.hybrid_strip import hybrid_strip
from opsrock.fragility.ida import OUTCOMES, outcomes, resurrection_summary, resurrections
from opsrock.fragility.logistic import LogisticFit, fit_logistic
from opsrock.fragility.mle import (
    CHUNK,
    DistinctCases,
    MLEFit,
    MLEPlan,
    PlanTasks,
    group_members,
    plan_mle,
    point_fit,
    resample_indices,
)
from opsrock.fragility.sufficiency import sufficiency
from opsrock.intensity import IM_NAMES, get_im
from opsrock.limits import check_count, one_of

#: Covariates of the sufficiency test (columns of a record ``cases.csv``).
COVARIATES: tuple[str, ...] = ("magnitude", "distance_km", "building_period")
#: Demands exported per block for loss assessment: column, pelicun demand name.
EXPORT_DEMANDS: tuple[str, ...] = ("pfa", "pfv")


@dataclass(frozen=True)
class RecordStudySettings:
    """Settings of :func:`record_fragility`.

    Parameters
    ----------
    ims : tuple of str
        IMs to fit (default the nine of Table 1).
    n_boot : int
        Bootstrap resamples of the records (0: no intervals). Default 200.
    confidence : float
        Confidence level of the intervals. Default 0.95.
    seed : int
        Seed of the resampling. Default 0.
    outcome : str
        Outcome convention of the fits, one of :data:`opsrock.fragility.ida.OUTCOMES`.
    """

    ims: tuple[str, ...] = IM_NAMES
    n_boot: int = 200
    confidence: float = 0.95
    seed: int = 0
    outcome: str = "as_simulated"

    def __post_init__(self) -> None:
        for im in self.ims:
            one_of("ims", im, IM_NAMES)
        check_count("n_boot", self.n_boot)
        check_count("seed", self.seed)
        if not 0.0 < self.confidence < 1.0:
            raise InputError(f"confidence must lie in (0, 1), got {self.confidence!r}")
        one_of("outcome", self.outcome, OUTCOMES)


@dataclass(frozen=True)
class RecordStudy:
    """Result of :func:`record_fragility`.

    Parameters
    ----------
    cases : pandas.DataFrame
        The finished cases with the outcome column ``y`` used by the fits.
    ims : pandas.DataFrame
        One row per IM: MLE ``mu``, ``beta`` and intervals, logistic ``mu`` and ``beta_equivalent``,
        HR, CV, log-likelihood, counts, and ``rank_*`` columns.
    measure_fits : pandas.DataFrame
        The scene's own measure (``level_value``) fitted under both outcome conventions.
    resurrections : pandas.DataFrame
        One row per IDA curve (:func:`opsrock.fragility.ida.resurrections`).
    resurrection_summary : dict
        Counts over the curves.
    sufficiency : pandas.DataFrame
        One row per (IM, covariate): coefficient, standard error, z, p-value.
    blocks : pandas.DataFrame
        Per block, floor and exported demand (PFA in m/s², PFV in m/s): MLE median, beta, intervals, the
        counts of cases, overturned cases and records.
    frequencies : pandas.DataFrame
        How often each IM wins by beta, HR and CV over the record bootstrap.
    settings : RecordStudySettings
    n_failed : int
        Cases excluded because their solver failed.
    """

    cases: pd.DataFrame = field(repr=False)
    ims: pd.DataFrame
    measure_fits: pd.DataFrame
    resurrections: pd.DataFrame = field(repr=False)
    resurrection_summary: dict
    sufficiency: pd.DataFrame
    blocks: pd.DataFrame
    frequencies: pd.DataFrame
    settings: RecordStudySettings
    n_failed: int = 0


def _plan(x: np.ndarray, y: np.ndarray, groups: np.ndarray, decreasing: bool, s: RecordStudySettings) -> MLEPlan:
    return plan_mle(x, y, decreasing, s.n_boot, s.confidence, s.seed, groups=groups)


def _im_row(cases: pd.DataFrame, im: str, s: RecordStudySettings) -> dict:
    part = _im_part(cases, im, s)
    return part.row(part.plan.finish(part.plan.draws()))


@dataclass(frozen=True)
class _IMPart:
    """One IM of :func:`record_fragility`: its MLE (bootstrap still to draw) and everything else of its row."""

    im: str
    plan: MLEPlan
    n_cases: int
    n_overturned: int
    logistic: LogisticFit
    HR: float  # noqa: N815

    def row(self, m: MLEFit) -> dict:
        lg = self.logistic
        return {"im": self.im, "n_cases": self.n_cases, "n_overturned": self.n_overturned, "mu": m.mu, "beta": m.beta,
                "mu_lo": m.mu_lo, "mu_hi": m.mu_hi, "beta_lo": m.beta_lo, "beta_hi": m.beta_hi,
                "cv_percent": m.cv_percent, "HR": self.HR, "loglik_per_case": m.loglik_per_case,
                "mle_success": m.success, "mle_message": m.message, "n_boot_used": m.n_boot_used,
                "logistic_mu": lg.mu, "logistic_beta_equivalent": lg.beta_equivalent}


def _im_part(cases: pd.DataFrame, im: str, s: RecordStudySettings) -> _IMPart:
    dec = get_im(im).decreasing
    sub = cases[np.isfinite(cases[im]) & (cases[im] > 0)]
    x, y, g = sub[im].to_numpy(float), sub["y"].to_numpy(bool), sub["record"].to_numpy()
    plan = _plan(x, y, g, dec, s)
    lg = fit_logistic(x, y, dec)
    rock = sub["rocked_bool"].to_numpy(bool)
    hs = hybrid_strip(x[rock], y[rock], im, dec)
    return _IMPart(im, plan, int(x.size), int(y.sum()), lg, hs.HR)


def _rank(df: pd.DataFrame) -> pd.DataFrame:
    for col, asc in (("beta", True), ("HR", True), ("cv_percent", True), ("loglik_per_case", False)):
        df[f"rank_{col}"] = df[col].rank(ascending=asc, method="min")
    return df


def _prepare(cases: pd.DataFrame, outcome: str) -> tuple[pd.DataFrame, int]:
    missing = {"record", "block", "floor", "level", "status", "overturned", "rocked"} - set(cases.columns)
    if missing:
        raise InputError(f"cases must be the cases.csv of a record scene; missing columns {sorted(missing)}")
    n_failed = int((cases["status"] != "ok").sum())
    ok = cases[cases["status"] == "ok"].copy()
    ok["y"] = outcomes(cases, outcome).reindex(ok.index).astype(bool)
    ok["rocked_bool"] = ok["rocked"].astype(str).str.lower().isin(("true", "1"))
    return ok, n_failed


class _RankIM:
    """One IM's finished cases, ready for many resamples: the IM, the outcome and the rocking flag of
    the cases with a positive finite IM (as :func:`_im_row` keeps them), and where each case is."""

    def __init__(self, cases: pd.DataFrame, im: str) -> None:
        self.im, self.decreasing = im, get_im(im).decreasing
        self.s = -1.0 if self.decreasing else 1.0
        x = cases[im].to_numpy(float)
        keep = np.isfinite(x) & (x > 0)
        self.keep = keep
        self.position = np.cumsum(keep) - 1  # position among the kept cases (where kept)
        self.x = x[keep]
        self.u = self.s * np.log(self.x)
        self.y = cases["y"].to_numpy(bool)[keep]
        self.rock = cases["rocked_bool"].to_numpy(bool)[keep]
        self.all_kept = bool(keep.all())
        # the rocking flag is part of a distinct case: the hybrid strip reads it from the first case of each
        self.distinct = DistinctCases(self.x, self.y, self.u, self.rock) if self.x.size else None

    def criteria(self, idx: np.ndarray) -> tuple[float, float, float]:
        """MLE ``beta``, HR and CV of the resample ``idx`` (positions of finished cases), as :func:`_im_row`
        gives them for the resampled table."""
        at = idx if self.all_kept else self.position[idx[self.keep[idx]]]
        if not at.size:
            empty = np.empty(0)
            return (point_fit(empty, empty.astype(bool), self.s).beta,
                    hybrid_strip(empty, empty.astype(bool), self.im, self.decreasing).HR, math.nan)
        table = self.distinct.table(at)  # the resample's distinct cases: the same sets of values
        fit = point_fit(self.u[at], None, self.s, table)
        rock = self.rock[table.base]
        hr = hybrid_strip(self.x[table.base][rock], table.y[rock], self.im, self.decreasing).HR  # min/max only
        return fit.beta, hr, fit.cv_percent


class _Frequencies:
    """:func:`ranking_frequencies` in steps (as :class:`~opsrock.fragility.mle.MLEPlan`): :meth:`criteria` of
    any range of the seeded record resamples, :meth:`table` of all of them in order."""

    CRITERIA: tuple[str, ...] = ("beta", "HR", "cv_percent")

    def __init__(self, cases: pd.DataFrame, ims: tuple[str, ...], n_boot: int, seed: int) -> None:
        self.ims, self.n_boot, self.seed = tuple(ims), n_boot, seed
        self.n_cases = len(cases)
        records = cases["record"].to_numpy()
        self.members = group_members(records, records.shape)  # records in order of first appearance
        self.by_im = [_RankIM(cases, im) for im in self.ims]
        self._resamples: list[np.ndarray] | None = None

    def __getstate__(self) -> dict:
        return {**self.__dict__, "_resamples": None}

    def criteria(self, lo: int = 0, hi: int | None = None) -> np.ndarray:
        """``(resample, IM, criterion)``: MLE beta, HR and CV of each IM in resamples ``lo`` to ``hi - 1``."""
        hi = self.n_boot if hi is None else min(hi, self.n_boot)
        if self._resamples is None:
            self._resamples = resample_indices(self.n_cases, self.members, self.n_boot, self.seed)
        out = np.empty((max(hi - lo, 0), len(self.ims), len(self.CRITERIA)))
        for k, idx in enumerate(self._resamples[lo:hi]):
            out[k] = [r.criteria(idx) for r in self.by_im]
        return out

    def table(self, values: np.ndarray) -> pd.DataFrame:
        """Wins and shares of each IM over the resamples (``values`` of all of them, in order)."""
        from opsrock.stats import wilson_interval

        wins = {c: {im: 0 for im in self.ims} for c in self.CRITERIA}
        n_done = 0
        for v in values:
            if not np.isnan(v[:, 0]).all():
                n_done += 1
                for j, c in enumerate(self.CRITERIA):
                    if not np.isnan(v[:, j]).all():  # the first IM of the smallest value, as idxmin
                        wins[c][self.ims[int(np.nanargmin(v[:, j]))]] += 1
        out = []
        for im in self.ims:
            row = {"im": im, "n_resamples": n_done}
            for c in self.CRITERIA:
                k = wins[c][im]
                lo, hi = wilson_interval(k, n_done)
                row.update({f"wins_{c}": k, f"share_{c}": k / n_done if n_done else math.nan,
                            f"share_{c}_lo": lo, f"share_{c}_hi": hi})
            out.append(row)
        return pd.DataFrame(out)


def ranking_frequencies(cases: pd.DataFrame, ims: tuple[str, ...], n_boot: int, seed: int) -> pd.DataFrame:
    """How often each IM has the smallest ``beta`` (MLE), HR and CV when the records are resampled
    with replacement ``n_boot`` times (seeded); with 95 % Wilson intervals of each share.

    Each resample's criteria are those :func:`_im_row` gives on the resampled table (its MLE point fit
    and hybrid strip; nothing else of the row is needed), computed on arrays.
    """
    freq = _Frequencies(cases, ims, n_boot, seed)
    return freq.table(freq.criteria())


def _block_plans(cases: pd.DataFrame, s: RecordStudySettings) -> list[tuple[dict, MLEPlan]]:
    """One plan per block, floor and exported demand: a block's fragility differs from floor to floor (the
    floors' motions differ in frequency content), so no fit pools floors."""
    out = []
    for (block, floor), sub in cases.groupby(["block", "floor"], sort=False):
        for demand in EXPORT_DEMANDS:
            x = sub[demand].to_numpy(float)
            keep = np.isfinite(x) & (x > 0)
            y = sub["y"].to_numpy(bool)[keep]
            records = sub["record"].to_numpy()[keep]
            plan = _plan(x[keep], y, records, False, s)
            out.append(({"block": block, "floor": floor, "demand": demand,
                         "unit": "m/s2" if demand == "pfa" else "m/s", "n_cases": int(keep.sum()),
                         "n_overturned": int(y.sum()), "n_records": int(pd.unique(records).size)}, plan))
    return out


def _block_row(head: dict, m: MLEFit) -> dict:
    return {"block": head["block"], "floor": head["floor"], "demand": head["demand"], "unit": head["unit"],
            "mu": m.mu, "beta": m.beta, "mu_lo": m.mu_lo, "mu_hi": m.mu_hi, "beta_lo": m.beta_lo,
            "beta_hi": m.beta_hi, "n_cases": head["n_cases"], "n_overturned": head["n_overturned"],
            "n_records": head["n_records"], "success": m.success, "message": m.message}


def _failed_block_rows(cases: pd.DataFrame) -> list[dict]:
    """Rows of ``blocks`` for the blocks of which no case finished: no fit, and why (:func:`failed_groups`)."""
    nan = math.nan
    return [{"block": block, "demand": demand, "unit": "m/s2" if demand == "pfa" else "m/s", "mu": nan, "beta": nan,
             "mu_lo": nan, "mu_hi": nan, "beta_lo": nan, "beta_hi": nan, "n_cases": 0, "success": False,
             "message": f"{why}: no fit"}
            for block, why in failed_groups(cases, "block").items() for demand in EXPORT_DEMANDS]


def _block_fits(cases: pd.DataFrame, s: RecordStudySettings) -> pd.DataFrame:
    return pd.DataFrame([_block_row(head, plan.finish(plan.draws())) for head, plan in _block_plans(cases, s)])


def _measure_plans(raw: pd.DataFrame, s: RecordStudySettings) -> list[tuple[dict, MLEPlan]]:
    out = []
    if "level_value" not in raw.columns or not np.isfinite(raw["level_value"]).any():
        return out
    for conv in OUTCOMES:
        ok, _ = _prepare(raw, conv)
        sub = ok[np.isfinite(ok["level_value"]) & (ok["level_value"] > 0)]
        plan = _plan(sub["level_value"].to_numpy(float), sub["y"].to_numpy(bool), sub["record"].to_numpy(), False, s)
        out.append(({"outcome": conv, "n_overturned": int(sub["y"].sum()), "n_cases": len(sub)}, plan))
    return out


def _measure_row(head: dict, m: MLEFit) -> dict:
    return {"outcome": head["outcome"], "mu": m.mu, "beta": m.beta, "mu_lo": m.mu_lo, "mu_hi": m.mu_hi,
            "beta_lo": m.beta_lo, "beta_hi": m.beta_hi, "n_overturned": head["n_overturned"],
            "n_cases": head["n_cases"]}


def _measure_fits(raw: pd.DataFrame, s: RecordStudySettings) -> pd.DataFrame:
    return pd.DataFrame([_measure_row(head, plan.finish(plan.draws())) for head, plan in _measure_plans(raw, s)])


def _sufficiency(cases: pd.DataFrame, ims: tuple[str, ...]) -> pd.DataFrame:
    rows = []
    for im in ims:
        for cov in COVARIATES:
            if cov not in cases.columns or cases[cov].nunique(dropna=True) < 2:
                continue
            t = sufficiency(cases[im].to_numpy(float), cases["y"].to_numpy(bool), cases[cov].to_numpy(float),
                            cov, get_im(im).decreasing, groups=cases["record"].to_numpy())
            rows.append({"im": im, "covariate": cov, "coefficient": t.coefficient, "std_error": t.std_error,
                         "z": t.z, "p_value": t.p_value, "n_cases": t.n_points, "message": t.message})
    return pd.DataFrame(rows)


def record_fragility(cases: pd.DataFrame, settings: RecordStudySettings | None = None,
                     n_rank_boot: int | None = None, workers: int = 1) -> RecordStudy:
    """Fit, rank and test every IM on a record campaign's cases.

    Parameters
    ----------
    cases : pandas.DataFrame
        ``cases.csv`` of a record scene.
    settings : RecordStudySettings, optional
        Defaults to ``RecordStudySettings()``.
    n_rank_boot : int, optional
        Record resamples for :func:`ranking_frequencies` (default ``settings.n_boot``).
    workers : int, optional
        Processes that share the bootstrap resamples (default 1: all in this process). The resamples are
        drawn from the seed whatever the split and put back in order, so the result does not depend on
        ``workers``.

    Returns
    -------
    RecordStudy
        A block whose every case failed has rows in ``blocks`` with ``success`` False and the reason.

    Raises
    ------
    AllCasesFailedError
        No case finished (:func:`opsrock.fragility.cases.check_some_finished`): nothing to fit.
    """
    s = settings or RecordStudySettings()
    workers = check_count("workers", workers)
    if "status" in cases.columns:  # (a table without it is refused by _prepare, naming the column)
        check_some_finished(cases, "the cases")
    ok, n_failed = _prepare(cases, s.outcome)
    freq = _Frequencies(ok, s.ims, s.n_boot if n_rank_boot is None else n_rank_boot, s.seed)
    parts = [_im_part(ok, im, s) for im in s.ims]
    blocks = _block_plans(ok, s)
    measures = _measure_plans(cases, s)
    plans = [p.plan for p in parts] + [plan for _, plan in blocks] + [plan for _, plan in measures]
    state = _StudyTasks(plans, freq)
    tasks = state.tasks()
    with TaskPool(state, tasks, workers) as pool:
        res = resurrections(cases)  # the light work, while the workers fit the resamples
        suff = _sufficiency(ok, s.ims)
        fits, criteria = state.finish(tasks, pool.results())
    ims = _rank(pd.DataFrame([p.row(m) for p, m in zip(parts, fits)]))
    k = len(parts)
    return RecordStudy(
        cases=ok, ims=ims,
        measure_fits=pd.DataFrame([_measure_row(h, m) for (h, _), m in zip(measures, fits[k + len(blocks):])]),
        resurrections=res, resurrection_summary=resurrection_summary(res), sufficiency=suff,
        blocks=pd.DataFrame([_block_row(h, m) for (h, _), m in zip(blocks, fits[k:k + len(blocks)])]
                            + _failed_block_rows(cases)),
        frequencies=freq.table(criteria), settings=s, n_failed=n_failed)


class _StudyTasks(PlanTasks):
    """Task state of :func:`record_fragility` (:class:`~opsrock._pool.TaskPool`): the resamples of the
    MLE plans (task ``(i, lo)``) and of the ranking frequencies (task ``(-1, lo)``), the latter first (they
    cost the most: every IM of a resample is fitted from a cold start)."""

    def __init__(self, plans: list[MLEPlan], freq: _Frequencies) -> None:
        super().__init__(plans)
        self.freq = freq

    def tasks(self) -> list[tuple[int, int]]:
        return [(-1, lo) for lo in range(0, self.freq.n_boot, CHUNK)] + super().tasks()

    def run(self, i: int, lo: int):
        return self.freq.criteria(lo, lo + CHUNK) if i < 0 else super().run(i, lo)

    def finish(self, tasks: list[tuple[int, int]], results: list) -> tuple[list[MLEFit], np.ndarray]:
        n = sum(1 for i, _ in tasks if i < 0)
        parts = results[:n]
        criteria = np.concatenate(parts) if parts else np.empty((0, len(self.freq.ims), len(self.freq.CRITERIA)))
        return super().finish(tasks[n:], results[n:]), criteria
