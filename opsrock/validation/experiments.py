"""Validation case ``experiments``: measured free rocking of limestone blocks against Housner's
restitution and against the free-rocking decay each solver predicts.

Data: Colombo, C. et al., *Experimental dataset on the free-rocking response of masonry blocks*,
University of Minho, DOI 10.60756/uminho-jh25, CC BY 4.0; shipped in ``opsrock/data/experiments/``
(its ``SOURCE.md`` says how the tables were derived). 12 geometries (B = 0.05 m, H = 0.20-0.75 m),
134 distinct trials, 7,519 impacts, each with its measured angular-velocity ratio after/before.

Two parts (``validation/experiments/README.md`` derives the relations and tolerances):

1. **Restitution.** The measured ratio against Housner's ``e_R = 1 - 1.5 sin²(alpha)`` and against the
   paper's ``0.95 e_R``, per geometry and per impact number (bias, RMSE, medians); the factor
   ``f = measured / e_R`` fitted on the data (median over all impacts) with variants that drop or
   weight impacts differently, and tests of whether ``f`` drifts with the impact number or with
   the slenderness. Every interval is a bootstrap that resamples whole trials within each geometry
   (impacts of one trial are correlated), seeded.
2. **Decay of free rocking.** The running product of the measured ratios of each trial (the
   velocity after ``n`` impacts over that before the first), median and spread per geometry, against
   the rigid body with ``e_R``, with the fitted ``f e_R`` and with ``0.95 e_R`` (``housner``) and the
   paper's SDOF model at default settings (``sdof``, ``opensees``) released from rest at stated
   fractions of alpha (the experiments' release angles are not in the data).

``run(out_dir, quick)`` writes the tables and figures and returns the summary with ``"passed"``:
the data's own consistency, the intervals containing their estimates, the rigid body reproducing
``e^n`` and both SDOF implementations reproducing the model's closed-form decay.
"""

from __future__ import annotations

import math
import time
from pathlib import Path
from typing import Callable, Iterator

import numpy as np
import pandas as pd

from opsrock.block import Block
from opsrock.stats import cluster_resamples, percentile_interval
from opsrock.constants import DEFAULT_RESTITUTION_FACTOR
from opsrock.published.colombo_limestone import (
    DATA_FILES,
    DUPLICATE,
    N_EVENT_ROWS,
    N_GROUPS,
    N_TRIALS,
    N_UNIQUE_TRIALS,
    EventArrays,
    analysis_arrays,
    data_file,
    load_events,
    load_trials,
    sha256,
)

#: The paper's restitution factor ``e / e_R``.
PAPER_FACTOR: float = DEFAULT_RESTITUTION_FACTOR
#: The references the measured ratio is compared with: name -> factor on ``e_R``.
REFERENCES: dict[str, float] = {"e_R": 1.0, "paper": PAPER_FACTOR}

#: Bootstrap resamples (full, quick), seed, and two-sided interval level.
N_BOOT, N_BOOT_QUICK, SEED, LEVEL = 2000, 200, 20250617, 0.95
#: Impact-number windows of the drift regression (impacts 1..n, every trial present to >= 81).
DRIFT_WINDOWS: tuple[int, ...] = (20, 40)
#: Rows of the per-impact table: single impact numbers 1..40, then bins.
IMPACT_ROWS: tuple[tuple[int, int], ...] = tuple((n, n) for n in range(1, 41)) + (
    (1, 10), (11, 20), (21, 40), (41, 80), (81, 10_000))
#: Impact subsets of the per-geometry table: label -> (first, last) impact number.
GROUP_SUBSETS: dict[str, tuple[int, int]] = {"1": (1, 1), "1-10": (1, 10), "all": (1, 10_000)}

#: Release angles of the predicted free rocking, ``theta0 / alpha`` (the first is the primary one).
RELEASE_RATIOS: tuple[float, ...] = (0.5, 0.25)
#: Impacts compared in the decay (plotted, and the RMSE windows of log running product).
DECAY_IMPACTS, DECAY_WINDOWS = 30, (10, 20)
#: A measured median running product needs at least this many trials still rocking.
MIN_TRIALS: int = 3
#: Geometries of the quick form: the stockiest and the most slender.
QUICK_GROUPS: tuple[int, ...] = (1, 12)
#: Predicted models: name -> (solver, factor on e_R or None for "the fitted factor").
MODELS: dict[str, tuple[str, float | None]] = {
    "rigid e_R": ("housner", 1.0), "rigid fitted": ("housner", None), "rigid 0.95 e_R": ("housner", PAPER_FACTOR),
    "sdof": ("sdof", PAPER_FACTOR), "opensees": ("opensees", PAPER_FACTOR), "sdof e_R": ("sdof", 1.0),
}

#: Tolerances of the checks (README, "Checks"): data identities (written to 16 digits); the rigid
#: body's impact is one multiplication (rounding only); the SDOF implementations against the model's
#: closed-form decay over the first 10 impacts: ``sdof`` 10 passages x 1e-4 (ten times case 1's
#: measured energy error per passage), ``opensees`` the 1 % agreement target of case 2.
TOL_DATA, TOL_RIGID = 1e-9, 1e-9
TOL_CLOSED_FORM: dict[str, float] = {"sdof": 1e-3, "opensees": 1e-2}
CLOSED_FORM_IMPACTS: int = 10


# --- data ---------------------------------------------------------------------------------------------
def data_checks(events: pd.DataFrame, trials: pd.DataFrame) -> list[dict]:
    """The data's own consistency: digests, counts, the duplicate, Housner's formula, the trial table.

    Parameters
    ----------
    events, trials : pandas.DataFrame
        The two shipped tables as loaded (every row).
    """
    rows: list[dict] = []

    def add(check: str, value, reference, ok: bool, note: str = "") -> None:
        rows.append({"check": check, "value": value, "reference": reference, "passed": bool(ok), "note": note})

    for kind, (name, digest) in DATA_FILES.items():
        got = sha256(data_file(kind))
        add(f"sha256 {name}", got, digest, got == digest)
    uniq = events[events["duplicate_of"].isna()]
    for check, got, want in (("event rows", len(events), N_EVENT_ROWS), ("trials", len(trials), N_TRIALS),
                             ("distinct trials", uniq["source_id"].nunique(), N_UNIQUE_TRIALS),
                             ("geometries", events["group"].nunique(), N_GROUPS)):
        add(check, int(got), want, got == want)
    dup, orig = (events.loc[events["source_id"] == s, "measured_source_angular_ratio"].to_numpy() for s in DUPLICATE)
    marked = set(events.loc[events["duplicate_of"].notna(), "source_id"]) == {DUPLICATE[0]}
    add("duplicate trial repeats its original", int(dup.size), int(orig.size),
        marked and dup.size == orig.size and bool(np.array_equal(dup, orig)),
        f"{DUPLICATE[0]} = {DUPLICATE[1]}, excluded")
    b, h = events["B_m"].to_numpy(float), events["H_m"].to_numpy(float)
    ideal = events["predicted_ideal_angular_ratio"].to_numpy(float)
    meas = events["measured_source_angular_ratio"].to_numpy(float)
    d = float(np.max(np.abs(ideal - (1.0 - 1.5 * b**2 / (b**2 + h**2)))))
    add("ideal ratio = 1 - 1.5 B^2/(B^2+H^2)", d, TOL_DATA, d <= TOL_DATA)
    d = max(abs(Block(bb, hh, restitution_factor=1.0).e_R - i) for bb, hh, i in set(zip(b, h, ideal)))
    add("ideal ratio = Block(B, H).e_R", d, TOL_DATA, d <= TOL_DATA, "the project's own formula")
    d = float(np.max(np.abs(events["signed_ratio_error"].to_numpy(float) - (ideal - meas))))
    add("signed error = ideal - measured", d, TOL_DATA, d <= TOL_DATA)
    add("every measured ratio finite", int(np.isfinite(meas).sum()), len(events), bool(np.isfinite(meas).all()))
    per = events.groupby("source_id").agg(n=("event", "size"), first=("measured_source_angular_ratio", "first"))
    t = trials.set_index("source_id").loc[per.index]
    bad = int((per["n"] != t["finite_events"]).sum() + (per["first"] != t["first_measured_ratio"]).sum())
    add("trial table: impact counts and first ratios", bad, 0, bad == 0)
    return rows


# --- statistics --------------------------------------------------------------------------------------
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


def headline(n_boot: int = N_BOOT_QUICK, seed: int = SEED) -> dict:
    """:func:`headline_stats` of the shipped data with trial-bootstrap intervals, in about a second.

    Parameters
    ----------
    n_boot : int
        Resamples of whole trials (no unit); the validation case's full form uses :data:`N_BOOT`.
    seed : int
        Seed of the resamples (no unit).

    Returns
    -------
    dict
        ``{name: (estimate, low, high)}`` and ``n_trials``, ``n_impacts``, ``n_boot``.
    """
    a = analysis_arrays(load_events())
    out: dict = bootstrap(a, headline_stats, n_boot, seed)
    out.update(n_trials=int(np.unique(a.trial).size), n_impacts=int(a.trial.size), n_boot=n_boot)
    return out


# --- decay of free rocking -----------------------------------------------------------------------------
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


FREE_MOTION_DT: float = 1e-3  # s; an all-zero floor motion: only its length 2 dt matters


def free_rocking(block: Block, solver: str, theta0: float, end_time: float):
    """Free rocking of ``block`` from rest at ``theta0``; the :class:`~opsrock.result.RockingResult`.

    Parameters
    ----------
    block : Block
        The block (its ``e`` is used).
    solver : str
        ``"housner"``, ``"sdof"`` or ``"opensees"``.
    theta0 : float
        Release angle (rad).
    end_time : float
        End of the run (s); OpenSees runs to it (``stop_at_rest=False``), as its rest test would stop a
        free-rocking run at once.
    """
    from opsrock.excitations import Record
    from opsrock.solvers import simulate

    extra = {"stop_at_rest": False} if solver == "opensees" else {}
    return simulate(block, Record(FREE_MOTION_DT, np.zeros(2)), solver=solver, theta0=theta0,
                    end_time=end_time, **extra)


def _rigid_run(block: Block, theta0: float, n_impacts: int):
    """The rigid body (``housner``) until it has made ``n_impacts`` impacts (the end time doubles from 4 s).

    Parameters
    ----------
    block : Block
        The block (its ``e``).
    theta0 : float
        Release angle (rad).
    n_impacts : int
        Impacts wanted (no unit).
    """
    end = 4.0
    while True:
        r = free_rocking(block, "housner", theta0, end)
        if not r.ok or len(r.impacts) >= n_impacts or end >= 256.0:
            return r
        end *= 2.0


def model_blocks(width: float, height: float, factor: float) -> dict[str, Block]:
    """The block of each model of :data:`MODELS`.

    Parameters
    ----------
    width, height : float
        Block width B and height H (m).
    factor : float
        The fitted restitution factor ``e / e_R`` (dimensionless).
    """
    e_R = Block(width, height, restitution_factor=1.0).e_R
    return {name: Block(width, height, restitution=(factor if f is None else f) * e_R)
            for name, (_, f) in MODELS.items()}


def predict_decay(width: float, height: float, factor: float, release_ratio: float,
                  n_impacts: int = DECAY_IMPACTS, models: tuple[str, ...] = tuple(MODELS)) -> dict[str, dict]:
    """Free rocking of each model from rest at ``release_ratio`` alpha: the logged impacts' ratios.

    The SDOF runs end after about ``n_impacts`` impacts: ``sdof`` at 1.1 times the rigid body's time of
    that impact (same ``e``; the SDOF model loses a little more per impact, so it gets there sooner)
    plus 0.5 s, ``opensees`` half an interval after the ``sdof`` run's impact ``n_impacts + 1`` (or its
    last, if it came to rest first), since OpenSees reports a block at rest inside the damper band as
    a numerical sawtooth (failed).

    Parameters
    ----------
    width, height : float
        Block width B and height H (m).
    factor : float
        The fitted restitution factor (dimensionless).
    release_ratio : float
        Release angle over alpha (dimensionless).
    n_impacts : int
        Impacts wanted (no unit).
    models : tuple of str
        Names of :data:`MODELS`.

    Returns
    -------
    dict
        ``{model: {"ratio": ndarray, "e": float, "end_time": s, "ok": bool, "reason": str, "wall_s": s}}``.
    """
    blocks = model_blocks(width, height, factor)
    theta0 = release_ratio * blocks["sdof"].alpha
    out: dict[str, dict] = {}
    for name in models:
        solver, block = MODELS[name][0], blocks[name]
        t0 = time.perf_counter()
        if solver == "housner":
            r = _rigid_run(block, theta0, n_impacts)
            end = float(r.time[-1]) if r.ok else math.nan
        else:
            twin = next(k for k, (s, f) in MODELS.items() if s == "housner" and f == MODELS[name][1])
            t_rigid = out[twin]["time"] if twin in out else _rigid_run(block, theta0, n_impacts).impacts.time
            if solver == "sdof" or "sdof" not in out or not out["sdof"]["ok"]:
                end = 1.1 * float(t_rigid[min(n_impacts, t_rigid.size) - 1]) + 0.5
            else:
                t = out["sdof"]["time"]
                k = min(t.size, n_impacts + 1)
                end = float(t[k - 1] + 0.5 * (t[k - 1] - t[k - 2]))
            r = free_rocking(block, solver, theta0, end)
        ok = bool(r.ok and r.impacts is not None)
        out[name] = {"ratio": r.impacts.velocity_ratio[:n_impacts] if ok else np.array([]),
                     "time": r.impacts.time if ok else np.array([]), "e": block.e, "end_time": end,
                     "ok": ok, "reason": r.reason, "wall_s": time.perf_counter() - t0}
    return out


def sdof_closed_form(block: Block, theta0: float, n_impacts: int) -> np.ndarray:
    """The SDOF model's running product of impact ratios in closed form (dimensionless, NaN at rest).

    The damper keeps ``e²`` of the energy ``E = 1/2 I_O theta'² + U(theta)`` per passage (``U`` the
    table spring's potential), flight conserves it, and an impact's velocities are logged at the band
    edges ``|theta| = delta alpha``; so after ``n`` passages ``E_n = e^(2n) U(theta0)`` and the product
    telescopes to ``sqrt((E_n - U(delta alpha)) / (E_0 - U(delta alpha)))``.

    Parameters
    ----------
    block : Block
        The block (its ``e``).
    theta0 : float
        Release angle (rad).
    n_impacts : int
        Impacts (no unit).
    """
    from opsrock.model import SDOFModel
    from opsrock.solvers.sdof import table_potential

    model = SDOFModel()
    u = table_potential(*model.spring_table(block))
    e0, ub = float(u(theta0)), float(u(model.band(block)))
    en = block.e ** (2.0 * np.arange(1, n_impacts + 1)) * e0
    with np.errstate(invalid="ignore"):
        return np.where(en > ub, np.sqrt(np.maximum(en - ub, 0.0) / (e0 - ub)), np.nan)


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


# --- tables ----------------------------------------------------------------------------------------------
#: Statistics of the restitution tables (each with its interval ``_lo``, ``_hi``).
RESTITUTION_COLUMNS: tuple[str, ...] = ("factor", "share_above_1", "share_above_e_R", "share_above_paper",
                                        "bias_e_R", "rmse_e_R",
                                        "median_error_e_R", "bias_paper", "rmse_paper", "median_error_paper")


def restitution_table(a: EventArrays, est: dict, rows: list[tuple]) -> pd.DataFrame:
    """Rows ``(group, label, first, last)`` of the restitution statistics with their intervals.

    Parameters
    ----------
    a : EventArrays
        The impacts (for the counts and the geometry).
    est : dict
        :func:`bootstrap` of :func:`statistics`.
    rows : list of tuple
        ``(group or "all", impacts label, first impact, last impact)`` (no units).
    """
    out = []
    for g, label, lo, hi in rows:
        mask = ((a.group == g) if g != "all" else np.ones(a.group.size, bool)) & (a.event >= lo) & (a.event <= hi)
        row = {"group": g, "impacts": label, "n_trials": int(np.unique(a.trial[mask]).size),
               "n_impacts": int(mask.sum())}
        if g != "all":
            row.update({"alpha_rad": float(a.alpha[mask][0]), "e_R": float(a.e_R[mask][0])})
        for c in RESTITUTION_COLUMNS:
            v, low, high = est[("restitution", g, label, c)]
            row.update({c: v, f"{c}_lo": low, f"{c}_hi": high})
        out.append(row)
    return pd.DataFrame(out)


def interval_table(est: dict, kind: str, notes: dict[str, str] | None = None) -> pd.DataFrame:
    """The estimates of one kind (``"factor"`` or ``"drift"``) with their intervals.

    Parameters
    ----------
    est : dict
        :func:`bootstrap` of :func:`statistics`.
    kind : str
        First element of the keys (no unit).
    notes : dict, optional
        Description per name.
    """
    rows = [{"name": k[1], "estimate": v[0], "lo": v[1], "hi": v[2],
             "interval_excludes_0": bool(v[1] > 0 or v[2] < 0), "note": (notes or {}).get(k[1], "")}
            for k, v in est.items() if k[0] == kind]
    return pd.DataFrame(rows)


def predicted_table(preds: dict, geometry: dict[int, tuple[float, float]]) -> tuple[pd.DataFrame, pd.DataFrame]:
    """Per-impact predictions (with the rigid body's ``e^n`` and the SDOF closed form) and per-run rows.

    Parameters
    ----------
    preds : dict
        ``{(group, release_ratio): predict_decay(...)}``.
    geometry : dict
        ``{group: (B, H)}`` (m).
    """
    rows, runs = [], []
    for (g, rel), models in preds.items():
        b, h = geometry[g]
        for name, p in models.items():
            block = Block(b, h, restitution=p["e"])
            n = p["ratio"].size
            if MODELS[name][0] == "housner":
                cf = p["e"] ** np.arange(1, n + 1)
            else:
                cf = sdof_closed_form(block, rel * block.alpha, n)
            prod = np.cumprod(p["ratio"])
            rows += [{"group": g, "H_m": h, "model": name, "release_ratio": rel, "e": p["e"], "impact": k + 1,
                      "ratio": p["ratio"][k], "product": prod[k], "closed_form": cf[k]} for k in range(n)]
            runs.append({"group": g, "H_m": h, "model": name, "release_ratio": rel, "e": p["e"], "ok": p["ok"],
                         "reason": p["reason"], "end_time_s": p["end_time"], "n_impacts": n,
                         "n_impacts_run": int(p["time"].size), "wall_s": p["wall_s"]})
    return pd.DataFrame(rows), pd.DataFrame(runs)


def model_checks(predicted: pd.DataFrame, runs: pd.DataFrame) -> list[dict]:
    """Every run ok; the rigid body's product equals ``e^n``; the SDOF implementations follow the
    closed form over the first :data:`CLOSED_FORM_IMPACTS` impacts.

    Parameters
    ----------
    predicted, runs : pandas.DataFrame
        :func:`predicted_table`.
    """
    rows = [{"check": "every free-rocking run ok", "value": int((~runs["ok"]).sum()), "reference": 0,
             "passed": bool(runs["ok"].all()), "note": "; ".join(sorted(set(runs.loc[~runs["ok"], "reason"])))}]
    rel = (predicted["product"] / predicted["closed_form"] - 1.0).abs()
    rigid = predicted["model"].map(lambda m: MODELS[m][0] == "housner")
    d = float(rel[rigid].max())
    rows.append({"check": "rigid body: running product = e^n", "value": d, "reference": TOL_RIGID,
                 "passed": bool(d <= TOL_RIGID),
                 "note": f"impacts 1-{DECAY_IMPACTS}, every geometry and release angle"})
    for solver, tol in TOL_CLOSED_FORM.items():
        sel = predicted["model"].map(lambda m: MODELS[m][0] == solver) & (predicted["impact"] <= CLOSED_FORM_IMPACTS)
        d = float(rel[sel].max()) if sel.any() else math.nan
        rows.append({"check": f"{solver}: running product = SDOF closed form", "value": d, "reference": tol,
                     "passed": bool(d <= tol), "note": f"impacts 1-{CLOSED_FORM_IMPACTS}, relative"})
    return rows


# --- figures -----------------------------------------------------------------------------------------------
def plot_restitution(a: EventArrays, by_group: pd.DataFrame, by_impact: pd.DataFrame, factor: tuple,
                     path: Path) -> None:
    """Three panels: first-impact ratios against alpha with ``e_R`` and ``0.95 e_R``; the factor per
    geometry; the median factor per impact number.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    by_group, by_impact : pandas.DataFrame
        :func:`restitution_table` rows per geometry and per impact number.
    factor : tuple
        The fitted factor ``(estimate, low, high)`` (dimensionless).
    path : pathlib.Path
        The PNG.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from opsrock.plots import save_figure

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.6), constrained_layout=True)
    first = a.event == 1
    al = np.linspace(0.05, 0.26, 200)
    e_r = 1.0 - 1.5 * np.sin(al) ** 2
    ax[0].scatter(a.alpha[first], a.ratio[first], s=10, color="0.3", label="measured, impact 1 (134 trials)")
    ax[0].plot(al, e_r, color="C0", label="Housner e_R")
    ax[0].plot(al, PAPER_FACTOR * e_r, color="C3", ls="--", label="paper 0.95 e_R")
    ax[0].plot(al, factor[0] * e_r, color="C2", ls=":", label=f"fitted {factor[0]:.4f} e_R")
    ax[0].set(xlabel="alpha = atan(B/H) (rad)", ylabel="angular-velocity ratio after/before",
              title="first impact", ylim=(0.75, 1.1))
    for k, (label, mk) in enumerate((("all", "o"), ("1-10", "s"), ("1", "^"))):
        t = by_group[by_group["impacts"] == label]
        x = t["alpha_rad"] + (k - 1) * 0.003
        ax[1].errorbar(x, t["factor"], yerr=[t["factor"] - t["factor_lo"], t["factor_hi"] - t["factor"]],
                       fmt=mk, ms=4, capsize=2, label=f"impacts {label}")
    ax[2].fill_between(by_impact["n"], by_impact["factor_lo"], by_impact["factor_hi"], color="C0", alpha=0.25,
                       label="95 % interval (trial bootstrap)")
    ax[2].plot(by_impact["n"], by_impact["factor"], "o-", ms=3, color="C0", label="median")
    for axis in ax[1:]:
        axis.axhline(1.0, color="C0", lw=0.8)
        axis.axhline(PAPER_FACTOR, color="C3", ls="--", lw=0.8, label="paper 0.95")
        axis.axhspan(factor[1], factor[2], color="C2", alpha=0.25, label=f"fitted {factor[0]:.4f} (all impacts)")
        axis.set(ylabel="measured / e_R", ylim=(0.9, 1.06))
        axis.legend(fontsize=7, loc="lower left")
    ax[1].set(xlabel="alpha (rad)", title="factor per geometry (median, 95 % interval)")
    ax[2].set(xlabel="impact number", title="factor per impact number, all geometries")
    ax[0].legend(fontsize=7, loc="lower left")
    save_figure(fig, path)


#: Line style per model in the decay figure.
_STYLE = {"rigid e_R": ("C0", "-"), "rigid fitted": ("C2", "-"), "rigid 0.95 e_R": ("C3", "--"),
          "sdof": ("C1", "-"), "opensees": ("C4", ":"), "sdof e_R": ("C5", "-.")}


def plot_decay(measured: pd.DataFrame, predicted: pd.DataFrame, geometry: dict, path: Path) -> None:
    """One panel per geometry: the measured running product (median, 25-75 % and 10-90 % of trials)
    and each model's, at every release angle (the first solid, the others thin).

    Parameters
    ----------
    measured : pandas.DataFrame
        :func:`measured_decay`.
    predicted : pandas.DataFrame
        :func:`predicted_table`.
    geometry : dict
        ``{group: (B, H)}`` (m).
    path : pathlib.Path
        The PNG.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from opsrock.plots import save_figure

    groups = sorted(predicted["group"].unique())
    ncol = min(4, len(groups))
    nrow = -(-len(groups) // ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.6 * ncol, 3.0 * nrow), sharex=True, squeeze=False,
                             constrained_layout=True)
    for axis, g in zip(axes.flat, groups):
        m = measured[measured["group"] == g]
        axis.fill_between(m["impact"], m["p10"], m["p90"], color="0.85", label="measured 10-90 %")
        axis.fill_between(m["impact"], m["p25"], m["p75"], color="0.65", label="measured 25-75 %")
        axis.plot(m["impact"], m["median"], "k.-", ms=3, lw=1.2, label="measured median")
        for (model, rel), s in predicted[predicted["group"] == g].groupby(["model", "release_ratio"], sort=False):
            color, ls = _STYLE[model]
            primary = rel == RELEASE_RATIOS[0]
            if MODELS[model][0] == "housner" and not primary:
                continue  # the rigid body's ratios do not depend on the release angle
            axis.plot(s["impact"], s["product"], color=color, ls=ls, lw=1.3 if primary else 0.7,
                      alpha=1 if primary else 0.7,
                      label=model + ("" if MODELS[model][0] == "housner" else f" {rel:g} alpha"))
        b, h = geometry[g]
        axis.set_yscale("log")
        axis.set_ylim(0.05, 1.3)
        axis.set_title(f"group {g}: {b:g} x {h:g} m", fontsize=9)
    for axis in axes[-1]:
        axis.set_xlabel("impact number n")
    for axis in axes[:, 0]:
        axis.set_ylabel("velocity after n impacts / before 1st")
    for axis in list(axes.flat)[len(groups):]:
        axis.set_visible(False)
    axes.flat[0].legend(fontsize=6, loc="lower left")
    save_figure(fig, path)


# --- the case ------------------------------------------------------------------------------------------------
def interval_checks(est: dict) -> list[dict]:
    """Each headline interval (factor variants, drift tests, factor per geometry) contains its estimate.

    Parameters
    ----------
    est : dict
        :func:`bootstrap` of :func:`statistics`.
    """
    keys = [k for k in est if k[0] in ("factor", "drift")
            or (k[0] == "restitution" and k[2] in GROUP_SUBSETS and k[3] == "factor")]
    bad = [" / ".join(map(str, k)) for k in keys if not est[k][1] <= est[k][0] <= est[k][2]]
    return [{"check": "bootstrap intervals contain their estimates", "value": len(bad), "reference": 0,
             "passed": not bad, "note": f"{len(keys)} intervals; " + "; ".join(bad)}]


def restitution_outputs(a: EventArrays, est: dict) -> dict[str, pd.DataFrame]:
    """The tables of part 1: per geometry, per impact number, factor variants, drift tests.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    est : dict
        :func:`bootstrap` of :func:`statistics`.
    """
    gl = [(g, label, lo, hi) for g in ["all", *range(1, N_GROUPS + 1)] for label, (lo, hi) in GROUP_SUBSETS.items()]
    by_group = restitution_table(a, est, gl)
    il = [("all", _label(lo, hi), lo, hi) for lo, hi in IMPACT_ROWS]
    by_impact = restitution_table(a, est, il)
    by_impact.insert(1, "n", [lo if lo == hi else math.nan for lo, hi in IMPACT_ROWS])
    return {"restitution_by_group": by_group, "restitution_by_impact": by_impact,
            "factor": interval_table(est, "factor", FACTOR_VARIANTS), "drift": interval_table(est, "drift")}


def decay_outputs(a: EventArrays, events: pd.DataFrame, factor: float, quick: bool) -> dict[str, pd.DataFrame]:
    """The tables of part 2: measured and predicted decay, the runs, the errors.

    Parameters
    ----------
    a : EventArrays
        The impacts.
    events : pandas.DataFrame
        The per-impact table (for the geometry).
    factor : float
        The fitted restitution factor (dimensionless).
    quick : bool
        Geometries :data:`QUICK_GROUPS` at the first release angle only.
    """
    geometry = {int(g): (float(s["B_m"].iloc[0]), float(s["H_m"].iloc[0])) for g, s in events.groupby("group")}
    groups = QUICK_GROUPS if quick else tuple(range(1, N_GROUPS + 1))
    releases = RELEASE_RATIOS[:1] if quick else RELEASE_RATIOS
    preds = {(g, rel): predict_decay(*geometry[g], factor, rel) for g in groups for rel in releases}
    predicted, runs = predicted_table(preds, geometry)
    measured = measured_decay(a)
    return {"decay_measured": measured, "decay_predicted": predicted, "decay_runs": runs,
            "decay_errors": decay_errors(measured, predicted), "_geometry": geometry}


def summarise(a: EventArrays, events: pd.DataFrame, est: dict, tables: dict, checks: list[dict]) -> dict:
    """The case's headline numbers (see README) and ``"passed"``.

    Parameters
    ----------
    a : EventArrays
        The impacts analysed.
    events : pandas.DataFrame
        Every impact row (the duplicate included).
    est : dict
        :func:`bootstrap` of :func:`statistics`.
    tables : dict
        :func:`restitution_outputs` and :func:`decay_outputs`.
    checks : list of dict
        Every check row.
    """
    f = est[("factor", "median all impacts")]
    m: dict = {"passed": all(c["passed"] for c in checks), "n_checks": len(checks),
               "n_checks_failed": sum(not c["passed"] for c in checks),
               "n_event_rows": len(events), "n_trials_analysed": int(np.unique(a.trial).size),
               "n_impacts_analysed": a.trial.size,
               "share_above_1_all_rows": float(np.mean(events["measured_source_angular_ratio"] > 1.0)),
               "fitted_factor": f[0], "fitted_factor_lo": f[1], "fitted_factor_hi": f[2],
               "paper_factor_in_interval": bool(f[1] <= PAPER_FACTOR <= f[2])}
    for key, name in ((("all", "all", "share_above_1"), "share_above_1"), (("all", "1", "rmse_e_R"), "rmse_first_e_R"),
                      (("all", "1", "rmse_paper"), "rmse_first_paper"), (("all", "1", "bias_e_R"), "bias_first_e_R"),
                      (("all", "1", "bias_paper"), "bias_first_paper")):
        v = est[("restitution",) + key]
        m.update({name: v[0], f"{name}_lo": v[1], f"{name}_hi": v[2]})
    wild = np.abs(a.q - 1.0) > 0.5
    length = np.repeat(np.bincount(a.trial), np.bincount(a.trial))  # rows are contiguous per trial
    position = a.event / length
    m.update({"share_wild": float(wild.mean()), "share_wild_first_fifth": float(wild[position <= 0.2].mean()),
              "share_wild_last_tenth": float(wild[position > 0.9].mean())})
    fac = tables["factor"].set_index("name")
    robust = fac.drop(index=["median ratios <= 1"])
    m.update({"factor_variants_min": float(robust["estimate"].min()),
              "factor_variants_max": float(robust["estimate"].max()),
              "factor_all_with_duplicate": float(np.median(analysis_arrays(events, keep_duplicate=True).q))})
    single = tables["restitution_by_impact"].dropna(subset=["n"])
    m.update({"median_factor_per_impact_min": float(single["factor"].min()),
              "median_factor_per_impact_max": float(single["factor"].max())})
    bins = tables["restitution_by_impact"].set_index("impacts")
    for label in ("1-10", "11-20", "21-40", "41-80", "81+"):
        m[f"factor_impacts_{label}"] = float(bins.loc[label, "factor"])
    dr = tables["drift"].set_index("name")
    for name, key in (("drift_impact_per10_1_20", "impact number, impacts 1-20: slope per 10 impacts"),
                      ("drift_impact_per10_1_40", "impact number, impacts 1-40: slope per 10 impacts"),
                      ("drift_alpha_per_0.1rad", "slenderness, all impacts: slope per 0.1 rad of alpha"),
                      ("drift_alpha_per_0.1rad_first10", "slenderness, impacts 1-10: slope per 0.1 rad of alpha"),
                      ("odd_minus_even", "odd minus even impacts 1-20 (medians)")):
        m.update({name: dr.loc[key, "estimate"], f"{name}_lo": dr.loc[key, "lo"], f"{name}_hi": dr.loc[key, "hi"]})
    g = tables["restitution_by_group"]
    g = g[g["group"] != "all"]
    contains = (g["factor_lo"] <= PAPER_FACTOR) & (g["factor_hi"] >= PAPER_FACTOR)
    excludes = (g["factor_hi"] < f[0]) | (g["factor_lo"] > f[0])
    m["n_groups_interval_excludes_fitted"] = int(excludes[g["impacts"] == "all"].sum())
    m["n_groups_interval_contains_0.95"] = int(contains[g["impacts"] == "all"].sum())
    m["n_groups_interval_contains_0.95_impact_1"] = int(contains[g["impacts"] == "1"].sum())
    err = tables["decay_errors"]
    rigid = err["model"].map(lambda x: MODELS[x][0] == "housner")
    for _, r in err[(err["group"] == "all") & ~(rigid & (err["release_ratio"] != RELEASE_RATIOS[0]))].iterrows():
        m[f"decay_rmse_log_{r['model'].replace(' ', '_')}_{r['release_ratio']:g}alpha_1-{r['window']}"] = r["rmse_log"]
    return m


def scatter_outputs(out_dir: Path) -> dict:
    """The fixed against uncertain restitution comparison (:mod:`opsrock.analysis.restitution_scatter`) into
    ``out_dir/scatter/`` and ``scatter.csv``; its counts for the summary."""
    from opsrock._files import atomic_csv
    from opsrock.analysis.restitution_scatter import compare

    table = compare(out_dir / "scatter")
    atomic_csv(out_dir / "scatter.csv", table)
    unc, pap = table[table["variant"] == "uncertain"], table[table["variant"] == "paper"]
    return {"scatter_cells": int(len(unc)), "scatter_uncertain_inside": int((unc["verdict"] == "inside").sum()),
            "scatter_paper_inside": int((pap["verdict"] == "inside").sum()),
            "scatter_max_added_beta": float(unc["added_beta"].max())}


def run(out_dir: Path, quick: bool = False) -> dict:
    """Run the case into ``out_dir``: tables (CSV, full precision), ``restitution.png``, ``decay.png``,
    ``checks.csv``, ``summary.csv`` (``_quick`` suffixes for the quick form).

    Parameters
    ----------
    out_dir : pathlib.Path
        Folder of the outputs (created if missing).
    quick : bool
        :data:`N_BOOT_QUICK` resamples; the decay of :data:`QUICK_GROUPS` at the first release angle.

    Returns
    -------
    dict
        :func:`summarise`, with ``"wall_time_s"`` (s) and ``"quick"``.
    """
    from opsrock._files import atomic_csv, atomic_text

    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    t0, sfx = time.perf_counter(), "_quick" if quick else ""
    events, trials = load_events(), load_trials()
    checks = data_checks(events, trials)
    a = analysis_arrays(events)
    est = bootstrap(a, statistics, N_BOOT_QUICK if quick else N_BOOT)
    checks += interval_checks(est)
    tables = restitution_outputs(a, est)
    tables.update(decay_outputs(a, events, est[("factor", "median all impacts")][0], quick))
    geometry = tables.pop("_geometry")
    checks += model_checks(tables["decay_predicted"], tables["decay_runs"])
    for name in ("decay_predicted", "decay_errors"):  # the rigid body's rows repeat at every release angle
        t = tables[name]
        keep = t["model"].map(lambda x: MODELS[x][0] != "housner") | (t["release_ratio"] == RELEASE_RATIOS[0])
        tables[name] = t[keep]
    for name, df in tables.items():
        atomic_csv(out_dir / f"{name}{sfx}.csv", df)
    atomic_csv(out_dir / f"checks{sfx}.csv", pd.DataFrame(checks))
    plot_restitution(a, tables["restitution_by_group"], tables["restitution_by_impact"].dropna(subset=["n"]),
                     est[("factor", "median all impacts")], out_dir / f"restitution{sfx}.png")
    plot_decay(tables["decay_measured"], tables["decay_predicted"], geometry, out_dir / f"decay{sfx}.png")
    m = summarise(a, events, est, tables, checks)
    if not quick:  # restitution as an uncertain input on the FEMA P695 IDA scene (three campaigns)
        m.update(scatter_outputs(out_dir))
    m.update({"quick": quick, "n_boot": N_BOOT_QUICK if quick else N_BOOT, "wall_time_s": time.perf_counter() - t0})
    atomic_text(out_dir / f"summary{sfx}.csv", "metric,value\n" + "".join(f"{k},{v!r}\n" for k, v in m.items()))
    return m


__all__ = ["DATA_FILES", "FACTOR_VARIANTS", "MODELS", "EventArrays", "analysis_arrays", "bootstrap", "data_checks",
           "data_file", "decay_errors", "headline", "headline_stats", "load_events", "load_trials", "measured_decay", "predict_decay", "run",
           "sdof_closed_form", "statistics", "trial_resamples"]
