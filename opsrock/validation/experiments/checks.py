"""The checks of validation case ``experiments``: the data's own consistency, the bootstrap intervals
containing their estimates, and the free-rocking runs against their closed forms."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from opsrock.block import Block
from opsrock.published.colombo_limestone import (
    DATA_FILES,
    DUPLICATE,
    N_EVENT_ROWS,
    N_GROUPS,
    N_TRIALS,
    N_UNIQUE_TRIALS,
    data_file,
    sha256,
)
from opsrock.validation.experiments.constants import (
    CLOSED_FORM_IMPACTS,
    DECAY_IMPACTS,
    GROUP_SUBSETS,
    MODELS,
    TOL_CLOSED_FORM,
    TOL_DATA,
    TOL_RIGID,
)


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
