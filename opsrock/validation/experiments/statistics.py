"""The statistics of validation case ``experiments``: restitution, the fitted factor and its drift, the
trial bootstrap, the headline numbers, and the measured decay and its errors against predictions."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Iterator

import numpy as np
import pandas as pd

from opsrock.published.colombo_limestone import N_GROUPS, EventArrays, analysis_arrays, load_events
from opsrock.stats import cluster_resamples, percentile_interval
from opsrock.validation.experiments.constants import (
    DECAY_IMPACTS,
    DECAY_WINDOWS,
    DRIFT_WINDOWS,
    GROUP_SUBSETS,
    IMPACT_ROWS,
    LEVEL,
    MIN_TRIALS,
    N_BOOT_QUICK,
    PAPER_FACTOR,
    REFERENCES,
    SEED,
)


def _median(x: np.ndarray) -> float:
    """Median of ``x`` (its unit), NaN if empty."""
    return float(np.median(x)) if x.size else math.nan


def _subset_stats(a: EventArrays, mask: np.ndarray, key: tuple, out: dict) -> None:
    """Factor, shares and errors against each reference of some impacts, added to ``out``.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    mask : ndarray of bool
        The impacts to use (no unit).
    key : tuple
        Key prefix of the statistics (no unit).
    out : dict
        Receives ``key + (statistic,)``: the factor and shares (dimensionless), biases, RMSEs and
        median errors of the ratio (dimensionless).
    """
    x, r = a.ratio[mask], a.e_R[mask]
    out[key + ("factor",)] = _median(x / r) if x.size else math.nan
    out[key + ("share_above_1",)] = float(np.mean(x > 1.0)) if x.size else math.nan
    out[key + ("share_above_e_R",)] = float(np.mean(x > r)) if x.size else math.nan
    out[key + ("share_above_paper",)] = float(np.mean(x > PAPER_FACTOR * r)) if x.size else math.nan
    for name, c in REFERENCES.items():
        d = x - c * r
        out[key + (f"bias_{name}",)] = float(d.mean()) if d.size else math.nan
        out[key + (f"rmse_{name}",)] = float(np.sqrt(np.mean(d * d))) if d.size else math.nan
        out[key + (f"median_error_{name}",)] = _median(d)


def restitution_stats(a: EventArrays) -> dict:
    """Per geometry (and pooled) x impact subset, and per impact number: see :func:`_subset_stats`.

    Parameters
    ----------
    a : EventArrays
        The impacts (the data or a resample).
    """
    out: dict = {}
    groups = [("all", np.ones(a.group.size, bool))] + [(g, a.group == g) for g in range(1, N_GROUPS + 1)]
    for g, gmask in groups:
        for label, (lo, hi) in GROUP_SUBSETS.items():
            _subset_stats(a, gmask & (a.event >= lo) & (a.event <= hi), ("restitution", g, label), out)
    for lo, hi in IMPACT_ROWS[1:]:  # impact 1 pooled is ("all", "1") above
        if (lo, hi) == GROUP_SUBSETS["1-10"]:
            continue  # so is ("all", "1-10")
        _subset_stats(a, (a.event >= lo) & (a.event <= hi), ("restitution", "all", _label(lo, hi)), out)
    return out


def _label(lo: int, hi: int) -> str:
    """Label of the impacts ``lo..hi`` (impact numbers, no unit): ``"3"``, ``"1-10"``, ``"81+"``."""
    return str(lo) if lo == hi else (f"{lo}+" if hi >= 10_000 else f"{lo}-{hi}")


#: Variants of the fitted factor: name -> description (the first is the primary estimate).
FACTOR_VARIANTS: dict[str, str] = {
    "median all impacts": "median of measured/e_R over all impacts (primary)",
    "median impact 1": "impact 1 only",
    "median impacts 1-5": "first 5 impacts of each trial",
    "median impacts 1-10": "first 10 impacts",
    "median impacts 1-20": "first 20 impacts",
    "median impacts 21+": "late impacts only",
    "median ratios <= 1": "measured ratios <= 1 only (biased low by construction)",
    "median 0 < ratio <= 1.5": "wild values dropped (58 negative, 209 above 1.5)",
    "trimmed mean 5-95 %": "mean of measured/e_R between its pooled 5th and 95th percentiles",
    "median of trial medians": "each trial counts once",
    "least squares impact 1": "sum(m e_R)/sum(e_R^2) over impact 1",
    "least squares impacts 1-10": "sum(m e_R)/sum(e_R^2) over the first 10 impacts",
    "geometric impacts 1-10": "median over trials of (P_10/e_R^10)^(1/10), P the running product",
    "geometric impacts 1-20": "median over trials of (P_20/e_R^20)^(1/20)",
}


def factor_stats(a: EventArrays) -> dict:
    """The fitted restitution factor ``f = measured / e_R`` by every variant of :data:`FACTOR_VARIANTS`.

    Parameters
    ----------
    a : EventArrays
        The impacts (the data or a resample).
    """
    q, ev, x = a.q, a.event, a.ratio
    lo, hi = np.percentile(q, [5.0, 95.0])
    cuts = np.flatnonzero(np.diff(a.trial)) + 1
    first, first10 = ev == 1, ev <= 10
    v = {
        "median all impacts": _median(q), "median impact 1": _median(q[first]),
        "median impacts 1-5": _median(q[ev <= 5]), "median impacts 1-10": _median(q[first10]),
        "median impacts 1-20": _median(q[ev <= 20]), "median impacts 21+": _median(q[ev > 20]),
        "median ratios <= 1": _median(q[x <= 1.0]), "median 0 < ratio <= 1.5": _median(q[(x > 0) & (x <= 1.5)]),
        "trimmed mean 5-95 %": float(np.mean(q[(q >= lo) & (q <= hi)])),
        "median of trial medians": _median(np.array([np.median(s) for s in np.split(q, cuts)])),
        "least squares impact 1": float(x[first] @ a.e_R[first] / (a.e_R[first] @ a.e_R[first])),
        "least squares impacts 1-10": float(x[first10] @ a.e_R[first10] / (a.e_R[first10] @ a.e_R[first10])),
    }
    for n in (10, 20):
        at = ev == n
        g = np.clip(a.product[at], 0.0, None) ** (1.0 / n) / a.e_R[at]  # a non-positive product counts as 0
        v[f"geometric impacts 1-{n}"] = _median(g)
    return {("factor", k): val for k, val in v.items()}


def drift_stats(a: EventArrays) -> dict:
    """Tests of drift of ``f``: with the impact number (slope of the per-impact-number medians over
    impacts 1..n, with an odd/even term) and with the slenderness (slope of the per-geometry medians
    against alpha), and the odd-minus-even difference of the medians.

    Parameters
    ----------
    a : EventArrays
        The impacts (the data or a resample).
    """
    q, ev = a.q, a.event
    out: dict = {}
    for n_max in DRIFT_WINDOWS:
        n = np.arange(1, n_max + 1)
        med = np.array([_median(q[ev == k]) for k in n])
        design = np.column_stack([np.ones(n.size), n, n % 2])
        coef = np.linalg.lstsq(design, med, rcond=None)[0]
        out[("drift", f"impact number, impacts 1-{n_max}: slope per 10 impacts")] = float(10.0 * coef[1])
        out[("drift", f"impact number, impacts 1-{n_max}: odd minus even")] = float(coef[2])
    for label, (lo, hi) in (("all impacts", (1, 10_000)), ("impacts 1-10", (1, 10))):
        sel = (ev >= lo) & (ev <= hi)
        g = np.arange(1, N_GROUPS + 1)
        med = np.array([_median(q[sel & (a.group == k)]) for k in g])
        al = np.array([a.alpha[a.group == k][0] for k in g])
        slope = np.polyfit(al, med, 1)[0]
        out[("drift", f"slenderness, {label}: slope per 0.1 rad of alpha")] = float(0.1 * slope)
    early, odd = ev <= 20, ev % 2 == 1
    out[("drift", "odd minus even impacts 1-20 (medians)")] = _median(q[early & odd]) - _median(q[early & ~odd])
    return out


def statistics(a: EventArrays) -> dict:
    """Every statistic of the case on the impacts ``a`` (the data or a resample), keyed by tuples.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    """
    return {**restitution_stats(a), **factor_stats(a), **drift_stats(a)}


def trial_resamples(a: EventArrays, n_boot: int, seed: int) -> Iterator[EventArrays]:
    """Bootstrap resamples of whole trials, stratified by geometry (each keeps its number of trials).

    Parameters
    ----------
    a : EventArrays
        The impacts.
    n_boot : int
        Number of resamples (no unit).
    seed : int
        Seed of :func:`numpy.random.default_rng` (no unit).
    """
    starts = np.concatenate([[0], np.flatnonzero(np.diff(a.trial)) + 1])
    lengths = np.diff(np.concatenate([starts, [a.trial.size]]))
    by_group = [np.flatnonzero(a.group[starts] == g) for g in range(1, N_GROUPS + 1)]
    for chosen in cluster_resamples(by_group, n_boot, seed):
        n = lengths[chosen]
        offsets = np.repeat(starts[chosen] - (np.cumsum(n) - n), n)
        yield a.take(offsets + np.arange(n.sum()), np.repeat(np.arange(chosen.size), n))


def bootstrap(a: EventArrays, stat: Callable[[EventArrays], dict], n_boot: int, seed: int = SEED) -> dict:
    """Point estimates and percentile intervals of ``stat`` under :func:`trial_resamples`.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    stat : callable
        ``EventArrays -> {key: float}``.
    n_boot : int
        Number of resamples (no unit).
    seed : int
        Seed (no unit).

    Returns
    -------
    dict
        ``{key: (estimate, low, high)}``, the interval at :data:`LEVEL` (NaN resamples ignored).
    """
    point = stat(a)
    draws = np.array([[s[k] for k in point] for s in map(stat, trial_resamples(a, n_boot, seed))], dtype=float)
    lo, hi = percentile_interval(draws, LEVEL, len(point))
    return {k: (float(point[k]), float(l), float(h)) for k, l, h in zip(point, lo, hi)}


def headline_stats(a: EventArrays) -> dict:
    """The few numbers of :func:`headline`: the fitted factor (median of ``measured / e_R`` over all
    impacts) and the first impacts' RMSE against Housner's ``e_R`` and against the paper's factor.

    Parameters
    ----------
    a : EventArrays
        The impacts (the data or a resample).
    """
    first = a.event == 1
    x, e = a.ratio[first], a.e_R[first]
    return {"factor": _median(a.q), "rmse_first_e_R": float(np.sqrt(np.mean((x - e) ** 2))),
            "rmse_first_paper": float(np.sqrt(np.mean((x - PAPER_FACTOR * e) ** 2)))}


@dataclass(frozen=True)
class Headline:
    """The restitution of the shipped free-rocking data in a few numbers (:func:`headline`).

    Each estimate is ``(estimate, low, high)``, the interval at :data:`LEVEL` of a bootstrap of whole trials.

    Parameters
    ----------
    factor : tuple of float
        The fitted factor ``f`` (median of ``measured / e_R`` over all impacts; dimensionless).
    rmse_first_e_R : tuple of float
        RMSE of Housner's ``e_R`` on the first impacts (angular-velocity ratio, dimensionless).
    rmse_first_paper : tuple of float
        RMSE of the paper's ``0.95 e_R`` on the first impacts (dimensionless).
    n_trials, n_impacts : int
        Trials and impacts analysed (counts).
    n_boot : int
        Bootstrap resamples (count).
    """

    factor: tuple[float, float, float]
    rmse_first_e_R: tuple[float, float, float]
    rmse_first_paper: tuple[float, float, float]
    n_trials: int
    n_impacts: int
    n_boot: int


def headline(n_boot: int = N_BOOT_QUICK, seed: int = SEED) -> Headline:
    """:func:`headline_stats` of the shipped data with trial-bootstrap intervals, in about a second.

    Parameters
    ----------
    n_boot : int
        Resamples of whole trials (no unit); the validation case's full form uses :data:`N_BOOT`.
    seed : int
        Seed of the resamples (no unit).
    """
    a = analysis_arrays(load_events())
    est = bootstrap(a, headline_stats, n_boot, seed)
    return Headline(factor=est["factor"], rmse_first_e_R=est["rmse_first_e_R"],
                    rmse_first_paper=est["rmse_first_paper"], n_trials=int(np.unique(a.trial).size),
                    n_impacts=int(a.trial.size), n_boot=n_boot)


def measured_decay(a: EventArrays, n_max: int = DECAY_IMPACTS) -> pd.DataFrame:
    """Running product of the measured ratios per geometry and impact: median and spread over trials.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    n_max : int
        Last impact number (no unit).

    Returns
    -------
    pandas.DataFrame
        ``group, H_m, impact, n_trials, median, p10, p25, p75, p90`` (products dimensionless); an
        impact number is listed while at least :data:`MIN_TRIALS` trials of the geometry reach it.
    """
    rows = []
    for g in range(1, N_GROUPS + 1):
        for n in range(1, n_max + 1):
            p = a.product[(a.group == g) & (a.event == n)]
            if p.size < MIN_TRIALS:
                break
            pct = np.percentile(p, [10, 25, 50, 75, 90])
            rows.append({"group": g, "impact": n, "n_trials": int(p.size), "median": pct[2], "p10": pct[0],
                         "p25": pct[1], "p75": pct[3], "p90": pct[4]})
    return pd.DataFrame(rows)


def decay_errors(measured: pd.DataFrame, predicted: pd.DataFrame) -> pd.DataFrame:
    """RMSE and mean of ``log(P_model) - log(P_measured median)`` per geometry, model, release angle and
    window (impacts 1..N of :data:`DECAY_WINDOWS`), over the impacts both have; pooled rows
    (``group = "all"``) over every geometry's impacts.

    Parameters
    ----------
    measured : pandas.DataFrame
        :func:`measured_decay`.
    predicted : pandas.DataFrame
        ``group, model, release_ratio, impact, product`` rows.
    """
    m = predicted.merge(measured[["group", "impact", "median"]], on=["group", "impact"], how="inner")
    m = m[(m["product"] > 0) & (m["median"] > 0)]
    m = m.assign(d=np.log(m["product"]) - np.log(m["median"]))
    n_model = predicted.groupby(["group", "model", "release_ratio"])["impact"].max()
    rows = []
    for window in DECAY_WINDOWS:
        w = m[m["impact"] <= window]
        for keys, s in list(w.groupby(["group", "model", "release_ratio"])) + [
                (("all",) + k, s) for k, s in w.groupby(["model", "release_ratio"])]:
            g, model, rel = keys
            rows.append({"group": g, "model": model, "release_ratio": rel, "window": window,
                         "n_compared": len(s), "rmse_log": float(np.sqrt(np.mean(s["d"] ** 2))),
                         "mean_log": float(np.mean(s["d"])),
                         "model_impacts": int(n_model.get((g, model, rel), -1)) if g != "all" else -1})
    return pd.DataFrame(rows)
