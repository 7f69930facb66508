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
* **Intervals** by resampling **records** with replacement (all cases of a record together),
  never single cases: the cases of one record at ten levels are not ten independent draws.
* **Resurrection** (:mod:`opsrock.fragility.ida`): counted per IDA curve; the fits use the outcome
  convention ``settings.outcome`` (default ``"as_simulated"``), and the scene's own measure is fitted
  under both conventions so their difference is visible.
* **Ranking.** Per IM: MLE median and ``beta`` with their intervals, HR, CV = ``100 beta / mu``
  (the paper's, not scale-free), and the log-likelihood per case. Winners by ``beta``, HR and CV,
  and how often each IM wins in the record bootstrap (:func:`ranking_frequencies`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from opsrock.errors import InputError
from opsrock.fragility.hybrid_strip import hybrid_strip
from opsrock.fragility.ida import OUTCOMES, outcomes, resurrection_summary, resurrections
from opsrock.fragility.logistic import fit_logistic
from opsrock.fragility.mle import MLEFit, fit_lognormal_mle
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
        Per block and exported demand (PFA in m/s², PFV in m/s): MLE median, beta, intervals.
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


def _fit(x: np.ndarray, y: np.ndarray, groups: np.ndarray, decreasing: bool, s: RecordStudySettings,
         n_boot: int | None = None) -> MLEFit:
    return fit_lognormal_mle(x, y, decreasing, s.n_boot if n_boot is None else n_boot, s.confidence, s.seed,
                             groups=groups)


def _im_row(cases: pd.DataFrame, im: str, s: RecordStudySettings) -> dict:
    dec = get_im(im).decreasing
    sub = cases[np.isfinite(cases[im]) & (cases[im] > 0)]
    x, y, g = sub[im].to_numpy(float), sub["y"].to_numpy(bool), sub["record"].to_numpy()
    m = _fit(x, y, g, dec, s)
    lg = fit_logistic(x, y, dec)
    rock = sub["rocked_bool"].to_numpy(bool)
    hs = hybrid_strip(x[rock], y[rock], im, dec)
    return {"im": im, "n_cases": int(x.size), "n_overturned": int(y.sum()), "mu": m.mu, "beta": m.beta,
            "mu_lo": m.mu_lo, "mu_hi": m.mu_hi, "beta_lo": m.beta_lo, "beta_hi": m.beta_hi,
            "cv_percent": m.cv_percent, "HR": hs.HR, "loglik_per_case": m.loglik_per_case,
            "mle_success": m.success, "mle_message": m.message, "n_boot_used": m.n_boot_used,
            "logistic_mu": lg.mu, "logistic_beta_equivalent": lg.beta_equivalent}


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


def ranking_frequencies(cases: pd.DataFrame, ims: tuple[str, ...], n_boot: int, seed: int) -> pd.DataFrame:
    """How often each IM has the smallest ``beta`` (MLE), HR and CV when the records are resampled
    with replacement ``n_boot`` times (seeded); with 95 % Wilson intervals of each share."""
    from opsrock.analysis.robustness import wilson_interval

    records = np.array(list(dict.fromkeys(cases["record"].tolist())))
    by_rec = {r: np.flatnonzero(cases["record"].to_numpy() == r) for r in records}
    rng = np.random.default_rng(seed)
    wins = {c: {im: 0 for im in ims} for c in ("beta", "HR", "cv_percent")}
    n_done = 0
    quick = RecordStudySettings(ims=ims, n_boot=0)
    for _ in range(n_boot):
        pick = rng.integers(0, records.size, records.size)
        sample = cases.iloc[np.concatenate([by_rec[records[i]] for i in pick])].reset_index(drop=True)
        rows = pd.DataFrame([_im_row(sample, im, quick) for im in ims]).set_index("im")
        if rows["beta"].notna().any():
            n_done += 1
            for c in wins:
                if rows[c].notna().any():
                    wins[c][rows[c].idxmin()] += 1
    out = []
    for im in ims:
        row = {"im": im, "n_resamples": n_done}
        for c in wins:
            k = wins[c][im]
            lo, hi = wilson_interval(k, n_done)
            row.update({f"wins_{c}": k, f"share_{c}": k / n_done if n_done else math.nan,
                        f"share_{c}_lo": lo, f"share_{c}_hi": hi})
        out.append(row)
    return pd.DataFrame(out)


def _block_fits(cases: pd.DataFrame, s: RecordStudySettings) -> pd.DataFrame:
    rows = []
    for block, sub in cases.groupby("block", sort=False):
        for demand in EXPORT_DEMANDS:
            x = sub[demand].to_numpy(float)
            keep = np.isfinite(x) & (x > 0)
            m = _fit(x[keep], sub["y"].to_numpy(bool)[keep], sub["record"].to_numpy()[keep], False, s)
            rows.append({"block": block, "demand": demand, "unit": "m/s2" if demand == "pfa" else "m/s",
                         "mu": m.mu, "beta": m.beta, "mu_lo": m.mu_lo, "mu_hi": m.mu_hi, "beta_lo": m.beta_lo,
                         "beta_hi": m.beta_hi, "n_cases": int(keep.sum()), "success": m.success, "message": m.message})
    return pd.DataFrame(rows)


def _measure_fits(raw: pd.DataFrame, s: RecordStudySettings) -> pd.DataFrame:
    rows = []
    if "level_value" not in raw.columns or not np.isfinite(raw["level_value"]).any():
        return pd.DataFrame(rows)
    for conv in OUTCOMES:
        ok, _ = _prepare(raw, conv)
        sub = ok[np.isfinite(ok["level_value"]) & (ok["level_value"] > 0)]
        m = _fit(sub["level_value"].to_numpy(float), sub["y"].to_numpy(bool), sub["record"].to_numpy(), False, s)
        rows.append({"outcome": conv, "mu": m.mu, "beta": m.beta, "mu_lo": m.mu_lo, "mu_hi": m.mu_hi,
                     "beta_lo": m.beta_lo, "beta_hi": m.beta_hi, "n_overturned": int(sub["y"].sum()),
                     "n_cases": len(sub)})
    return pd.DataFrame(rows)


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
                     n_rank_boot: int | None = None) -> RecordStudy:
    """Fit, rank and test every IM on a record campaign's cases.

    Parameters
    ----------
    cases : pandas.DataFrame
        ``cases.csv`` of a record scene.
    settings : RecordStudySettings, optional
        Defaults to ``RecordStudySettings()``.
    n_rank_boot : int, optional
        Record resamples for :func:`ranking_frequencies` (default ``settings.n_boot``).

    Returns
    -------
    RecordStudy
    """
    s = settings or RecordStudySettings()
    ok, n_failed = _prepare(cases, s.outcome)
    ims = _rank(pd.DataFrame([_im_row(ok, im, s) for im in s.ims]))
    res = resurrections(cases)
    return RecordStudy(
        cases=ok, ims=ims, measure_fits=_measure_fits(cases, s), resurrections=res,
        resurrection_summary=resurrection_summary(res), sufficiency=_sufficiency(ok, s.ims),
        blocks=_block_fits(ok, s),
        frequencies=ranking_frequencies(ok, s.ims, s.n_boot if n_rank_boot is None else n_rank_boot, s.seed),
        settings=s, n_failed=n_failed)
