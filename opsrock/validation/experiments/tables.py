"""The tables of validation case ``experiments``: restitution with intervals, factor variants and drift
tests (part 1), measured and predicted decay, the runs and the errors (part 2)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from opsrock.block import Block
from opsrock.published.colombo_limestone import N_GROUPS, EventArrays
from opsrock.validation.experiments.closed_forms import sdof_closed_form
from opsrock.validation.experiments.constants import GROUP_SUBSETS, IMPACT_ROWS, MODELS, QUICK_GROUPS, RELEASE_RATIOS
from opsrock.validation.experiments.runs import predict_decay
from opsrock.validation.experiments.statistics import FACTOR_VARIANTS, _label, decay_errors, measured_decay

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
            block = Block(b, h, restitution=p.e)
            n = p.ratio.size
            if MODELS[name][0] == "housner":
                cf = p.e ** np.arange(1, n + 1)
            else:
                cf = sdof_closed_form(block, rel * block.alpha, n)
            prod = np.cumprod(p.ratio)
            rows += [{"group": g, "H_m": h, "model": name, "release_ratio": rel, "e": p.e, "impact": k + 1,
                      "ratio": p.ratio[k], "product": prod[k], "closed_form": cf[k]} for k in range(n)]
            runs.append({"group": g, "H_m": h, "model": name, "release_ratio": rel, "e": p.e, "ok": p.ok,
                         "reason": p.reason, "end_time_s": p.end_time, "n_impacts": n,
                         "n_impacts_run": int(p.time.size), "wall_s": p.wall_s})
    return pd.DataFrame(rows), pd.DataFrame(runs)


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


def decay_outputs(a: EventArrays, events: pd.DataFrame, factor: float,
                  quick: bool) -> tuple[dict[str, pd.DataFrame], dict[int, tuple[float, float]]]:
    """The tables of part 2: measured and predicted decay, the runs, the errors; and the geometry
    ``{group: (B, H)}`` (m).

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
    return ({"decay_measured": measured, "decay_predicted": predicted, "decay_runs": runs,
             "decay_errors": decay_errors(measured, predicted)}, geometry)
