"""The paper's whole fragility analysis of a cases table, Tables 2 and 3 and the IM ranking."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import pandas as pd

from opsrock.excitations import PFV_CONVENTIONS
from opsrock.fragility.cases import CaseSplit, split_cases
from opsrock.fragility.hybrid_strip import HybridStrip, hybrid_strip
from opsrock.fragility.least_squares import fit_lognormal_least_squares
from opsrock.fragility.lognormal import LognormalFit, failed_fit
from opsrock.fragility.mle import MLEFit, fit_plans, plan_mle
from opsrock.fragility.strips import STRIP_EXTENTS, StripFractions, strip_fractions
from opsrock.intensity import IM_NAMES, add_intensity_measures, get_im
from opsrock.limits import check_count, int_at_least, one_of, positive_finite
from opsrock.published.liu_huang_liu_2023 import STRIP_FACTORS


@dataclass(frozen=True)
class FragilitySettings:
    """Settings of :func:`analyse_fragility`.

    Parameters
    ----------
    ims : tuple of str, optional
        IMs to analyse (default all nine).
    strip_factors : tuple of float, optional
        ``W_AS / W_SAS`` values (default Table 3's 0.5, 1, 2).
    extent : {"hybrid", "range"}, optional
        Where the analysis strips go (module notes).
    n_boot : int, optional
        Bootstrap resamples of the MLE (0: no intervals).
    confidence : float, optional
        Confidence level of the MLE bounds.
    seed : int, optional
        Bootstrap seed.
    pfv_convention : {"amplitude", "peak"} or None, optional
        If given, IM1..IM9 are recomputed from the block and pulse columns with this PFV;
        if None, the table's IM columns are used (computed with "amplitude" if absent).
    """

    ims: tuple[str, ...] = IM_NAMES
    strip_factors: tuple[float, ...] = STRIP_FACTORS
    extent: str = "range"
    n_boot: int = 200
    confidence: float = 0.95
    seed: int = 0
    pfv_convention: str | None = None

    def __post_init__(self) -> None:
        for im in self.ims:
            one_of("ims", im, IM_NAMES)
        for f in self.strip_factors:
            positive_finite("strip_factors", f)
        one_of("extent", self.extent, STRIP_EXTENTS)
        int_at_least("n_boot", self.n_boot, 0)
        if self.pfv_convention is not None:
            one_of("pfv_convention", self.pfv_convention, PFV_CONVENTIONS)


@dataclass(frozen=True)
class IMFragility:
    """Everything the fragility layer computes for one IM.

    Parameters
    ----------
    im : str
        IM name.
    hybrid : HybridStrip
        Hybrid strip and ratio.
    strips : Mapping[float, StripFractions]
        Strip fractions per strip factor.
    ls_fits : Mapping[float, LognormalFit]
        Least-squares fit per strip factor (Eq. 15-16).
    mle : MLEFit
        Maximum-likelihood fit on the rocking cases.
    """

    im: str
    hybrid: HybridStrip
    strips: Mapping[float, StripFractions] = field(repr=False)
    ls_fits: Mapping[float, LognormalFit]
    mle: MLEFit


@dataclass(frozen=True)
class FragilityAnalysis:
    """Result of :func:`analyse_fragility`: the case split and one :class:`IMFragility` per IM."""

    split: CaseSplit
    results: Mapping[str, IMFragility]
    settings: FragilitySettings

    def __getitem__(self, im: str) -> IMFragility:
        return self.results[im]


def _with_ims(cases: pd.DataFrame, pfv_convention: str | None) -> pd.DataFrame:
    if pfv_convention is not None or any(im not in cases.columns for im in IM_NAMES):
        return add_intensity_measures(cases, pfv_convention or "amplitude")
    return cases


def analyse_fragility(
    cases: pd.DataFrame, settings: FragilitySettings | None = None, workers: int = 1
) -> FragilityAnalysis:
    """Hybrid strips, strip fractions, least-squares and MLE fits for every IM.

    Parameters
    ----------
    cases : pandas.DataFrame
        Cases table (columns of ``cases.csv``).
    settings : FragilitySettings, optional
        Defaults to ``FragilitySettings()``.
    workers : int, optional
        Processes that share the MLE bootstrap resamples (default 1: all in this process); the
        result does not depend on it.

    Returns
    -------
    FragilityAnalysis
    """
    settings = settings or FragilitySettings()
    workers = check_count("workers", workers)
    split = split_cases(_with_ims(cases, settings.pfv_convention))
    y = split.rocking["overturned"].to_numpy(bool)
    parts = {}
    for im in settings.ims:
        dec = get_im(im).decreasing
        x = split.rocking[im].to_numpy(float)
        hs = hybrid_strip(x, y, im, dec)
        strips, fits = {}, {}
        for fac in settings.strip_factors:
            if hs.n_safe == 0 or hs.n_overturned == 0:
                fits[fac] = failed_fit("least_squares", 0, dec, hs.note)
                continue
            st = strip_fractions(x, y, hs, fac, settings.extent)
            strips[fac] = st
            fit = fit_lognormal_least_squares(st.centre, st.fraction, dec)
            if st.fallback:
                fit = LognormalFit(fit.mu, fit.beta, fit.cv_percent, fit.method, fit.n_points,
                                   dec, False, "fallback strips (no hybrid strip); " + fit.message,
                                   fit.objective)
            fits[fac] = fit
        plan = plan_mle(x, y, dec, settings.n_boot, settings.confidence, settings.seed) if x.size else None
        parts[im] = (hs, strips, fits, plan, dec)
    # the MLE bootstraps last, all together: their resamples can be shared among processes
    plans = [p[3] for p in parts.values() if p[3] is not None]
    mles = iter(fit_plans(plans, workers))
    results = {}
    for im, (hs, strips, fits, plan, dec) in parts.items():
        mle = next(mles) if plan is not None else MLEFit(math.nan, math.nan, math.nan, "mle", 0, dec, False,
                                                         "no rocking cases")
        results[im] = IMFragility(im, hs, strips, fits, mle)
    return FragilityAnalysis(split, results, settings)


def _analysis(cases_or_analysis, settings: FragilitySettings | None) -> FragilityAnalysis:
    if isinstance(cases_or_analysis, FragilityAnalysis):
        return cases_or_analysis
    return analyse_fragility(cases_or_analysis, settings)


#: Columns of :func:`table2`, exactly those of the paper's Table 2.
TABLE2_COLUMNS: tuple[str, ...] = ("im", "W_HS", "R_S", "R_O", "W_HS_over_R_S", "W_HS_over_R_O",
                                   "HR", "W_SAS")


def table2(cases_or_analysis, settings: FragilitySettings | None = None) -> pd.DataFrame:
    """The paper's Table 2 (hybrid strip parameters per IM) from a cases table.

    Parameters
    ----------
    cases_or_analysis : pandas.DataFrame or FragilityAnalysis
        Cases table, or an analysis already computed.
    settings : FragilitySettings, optional
        Used when a cases table is given.

    Returns
    -------
    pandas.DataFrame
        Columns ``im, W_HS, R_S, R_O, W_HS_over_R_S, W_HS_over_R_O, HR, W_SAS`` (IM units
        and dimensionless ratios), one row per IM.
    """
    if not isinstance(cases_or_analysis, FragilityAnalysis):
        settings = FragilitySettings(**{**vars(settings or FragilitySettings()), "n_boot": 0})
    an = _analysis(cases_or_analysis, settings)
    rows = []
    for im, r in an.results.items():
        h = r.hybrid
        rows.append({"im": im, "W_HS": h.W_HS, "R_S": h.R_S, "R_O": h.R_O,
                     "W_HS_over_R_S": h.ratio_S, "W_HS_over_R_O": h.ratio_O, "HR": h.HR,
                     "W_SAS": h.W_SAS})
    return pd.DataFrame(rows, columns=list(TABLE2_COLUMNS))


def table3(cases_or_analysis, settings: FragilitySettings | None = None) -> pd.DataFrame:
    """The paper's Table 3 (least-squares fits per strip width) plus the MLE beside it.

    Parameters
    ----------
    cases_or_analysis : pandas.DataFrame or FragilityAnalysis
        Cases table, or an analysis already computed.
    settings : FragilitySettings, optional
        Used when a cases table is given.

    Returns
    -------
    pandas.DataFrame
        One row per (IM, strip factor): ``im, strip_factor, W_AS, n_strips, mu, beta,
        cv_percent, ls_success, ls_message, fallback, mle_mu, mle_beta, mle_cv_percent,
        mle_mu_lo, mle_mu_hi, mle_beta_lo, mle_beta_hi, mle_success, mle_loglik_per_case,
        n_rocking, n_safe, n_overturned, n_no_uplift, n_failed``. ``mu`` in IM units,
        ``beta`` dimensionless, ``cv_percent`` = 100 beta / mu.
    """
    an = _analysis(cases_or_analysis, settings)
    counts = an.split.counts()
    rows = []
    for im, r in an.results.items():
        m = r.mle
        for fac, fit in r.ls_fits.items():
            st = r.strips.get(fac)
            rows.append({
                "im": im, "strip_factor": fac,
                "W_AS": st.width if st is not None else math.nan,
                "n_strips": st.n_strips if st is not None else 0,
                "mu": fit.mu, "beta": fit.beta, "cv_percent": fit.cv_percent,
                "ls_success": fit.success, "ls_message": fit.message,
                "fallback": bool(st.fallback) if st is not None else True,
                "mle_mu": m.mu, "mle_beta": m.beta, "mle_cv_percent": m.cv_percent,
                "mle_mu_lo": m.mu_lo, "mle_mu_hi": m.mu_hi,
                "mle_beta_lo": m.beta_lo, "mle_beta_hi": m.beta_hi,
                "mle_success": m.success, "mle_loglik_per_case": m.loglik_per_case,
                "n_rocking": counts["n_rocking"], "n_safe": counts["n_safe"],
                "n_overturned": counts["n_overturned"], "n_no_uplift": counts["n_no_uplift"],
                "n_failed": counts["n_failed"],
            })
    return pd.DataFrame(rows)


def rank_ims(analysis: FragilityAnalysis, strip_factor: float = 1.0) -> pd.DataFrame:
    """Rank the IMs by the paper's criteria (HR, CV) and by scale-free ones.

    Parameters
    ----------
    analysis : FragilityAnalysis
        A computed analysis.
    strip_factor : float, optional
        Which least-squares fit supplies ``cv_percent`` and ``beta``.

    Returns
    -------
    pandas.DataFrame
        Indexed by IM: ``HR``, ``cv_percent``, ``beta`` (NaN, so unranked, when the
        least-squares fit is flagged unreliable, e.g. a perfectly separating IM: HR and
        ``fraction_in_hybrid`` rank those), ``mle_beta``,
        ``mle_loglik_per_case`` (higher is better; invariant under power laws of the IM),
        ``fraction_in_hybrid`` (rocking cases in the hybrid strip; invariant under any
        monotone change of the IM), and a ``rank_<criterion>`` column for each (1 = best).
    """
    n = max(analysis.split.n_rocking, 1)
    rows = {}
    for im, r in analysis.results.items():
        fit = r.ls_fits.get(strip_factor)
        usable = fit is not None and fit.success
        rows[im] = {
            "HR": r.hybrid.HR,
            "cv_percent": fit.cv_percent if usable else math.nan,
            "beta": fit.beta if usable else math.nan,
            "mle_beta": r.mle.beta if r.mle.success else math.nan,
            "mle_loglik_per_case": r.mle.loglik_per_case,
            "fraction_in_hybrid": r.hybrid.n_in_strip / n,
        }
    df = pd.DataFrame.from_dict(rows, orient="index")
    df.index.name = "im"
    for col in list(df.columns):
        df[f"rank_{col}"] = df[col].rank(ascending=col != "mle_loglik_per_case", method="min")
    return df


def best_ims(ranking: pd.DataFrame) -> dict[str, str]:
    """The best IM under each criterion of a :func:`rank_ims` table (NaNs skipped)."""
    out = {}
    for col in ranking.columns:
        if col.startswith("rank_") or ranking[col].isna().all():
            continue
        out[col] = str(ranking[col].idxmax() if col == "mle_loglik_per_case" else ranking[col].idxmin())
    return out
