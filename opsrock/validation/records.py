"""Validation case 8: the four solvers on real floor motions.

FEMA P695 far-field components (the record library), on the ground and at the roof of a 3-storey
shear building (T_1 = 0.45 s, 5 %), three blocks, amplitudes PFA / (g tan alpha) = 1.5, 2.5 and 4
(around the overturning threshold of these records). ``housner`` (event-driven scipy) is the
reference of the rigid-body model; ``housner_fast`` solves the same equation compiled; ``opensees``
and ``sdof`` are the paper's SDOF model (its damper band and spring), expected to depart from the
rigid body on records (the model-form question has its own case). A case a solver cannot answer
within :data:`CASE_BUDGET` is counted as failed, never as a verdict.

Outputs: ``cases.csv`` (every case, every solver), ``summary.csv`` (per solver pair: verdict
agreement, theta_max differences on cases safe for both), ``disagreements.csv``.
"""

from __future__ import annotations

import csv
import math
import time
from pathlib import Path

import numpy as np

from opsrock.block import Block
from opsrock.campaign.timeout import CaseTimeout, time_limit

#: Blocks (2b, 2h in m): slender bookcase, deep wardrobe, stocky cabinet.
BLOCKS: tuple[tuple[str, float, float], ...] = (("bookcase", 0.40, 2.20), ("wardrobe", 0.60, 2.00),
                                                ("medicine_cabinet", 0.50, 1.15))
#: PFA / (g tan alpha) of the scaled motions.
LEVELS: tuple[float, ...] = (1.5, 2.5, 4.0)
#: Wall-clock budget per solve (s): beyond it the case is failed ("timeout").
CASE_BUDGET: float = 30.0
#: ``sdof`` (scipy, 0.3-12 s per 30-40-s floor motion) runs on the motions of the first records only.
SDOF_RECORDS: int = 2
SOLVERS: tuple[str, ...] = ("housner", "housner_fast", "opensees", "sdof")


def _motions(n_records: int):
    from opsrock.excitations import library
    from opsrock.excitations.building import ShearBuilding, floor_motion

    building = ShearBuilding("b3", 0.45, 3, damping=0.05)
    out = []
    for e in library.entries("far-field")[:n_records]:
        ground = library.load(e.reference)
        out += [ground, floor_motion(ground, building)]
    return out


def _solve(block, rec, solver):
    from opsrock.solvers import simulate

    t0 = time.perf_counter()
    try:
        with time_limit(CASE_BUDGET):
            r = simulate(block, rec, solver)
        return {"verdict": r.verdict, "theta_max_over_alpha": r.theta_max_over_alpha,
                "n_impacts": r.n_impacts, "reason": r.reason, "time": time.perf_counter() - t0}
    except CaseTimeout:
        return {"verdict": "failed", "theta_max_over_alpha": math.nan, "n_impacts": -1,
                "reason": f"timeout after {CASE_BUDGET:g} s", "time": time.perf_counter() - t0}


def run(out_dir: Path, quick: bool = False) -> dict:
    """Run the case; quick: 1 record (ground and roof), housner/housner_fast/opensees only (``make test``)."""
    out_dir = Path(out_dir)
    motions = _motions(1 if quick else 6)
    solvers = SOLVERS[:3] if quick else SOLVERS
    sdof_names = {m.name for m in motions[: 2 * SDOF_RECORDS]}
    rows = []
    for name, w, h in BLOCKS:
        block = Block(w, h, name=name)
        for rec in motions:
            for level in LEVELS:
                scaled = rec.scaled_to_pfa(level * block.uplift_acceleration)
                row = {"block": name, "record": rec.name, "floor": rec.info.floor, "pfa_ratio": level,
                       "duration_s": rec.duration}
                for s in solvers:
                    if s == "sdof" and rec.name not in sdof_names:
                        res = {"verdict": "not_run", "theta_max_over_alpha": math.nan, "n_impacts": -1,
                               "reason": "sdof runs on the first records only", "time": math.nan}
                    else:
                        res = _solve(block, scaled, s)
                    row.update({f"{s}_{k}": v for k, v in res.items()})
                rows.append(row)
    summary = _summary(rows, solvers)
    _write(out_dir / "cases.csv", rows)
    _write(out_dir / "summary.csv", summary)
    _write(out_dir / "disagreements.csv",
           [r for r in rows if len({r[f"{s}_verdict"] for s in solvers} - {"not_run"}) > 1])
    fast = next(s for s in summary if s["pair"] == "housner_fast vs housner")
    return {"passed": fast["verdict_agreement"] == 1.0 and fast["max_dtheta_over_alpha"] <= 1e-3,
            "n_cases": len(rows), **{f"{s['pair']}: verdict agreement": s["verdict_agreement"] for s in summary}}


def _summary(rows, solvers) -> list[dict]:
    out = []
    for s in solvers:
        if s == "housner":
            continue
        ran = [r for r in rows if r[f"{s}_verdict"] != "not_run"]
        both = [r for r in ran if r[f"{s}_verdict"] != "failed" and r["housner_verdict"] != "failed"]
        agree = [r for r in both if r[f"{s}_verdict"] == r["housner_verdict"]]
        safe = [r for r in both if r[f"{s}_verdict"] == r["housner_verdict"] == "safe"]
        d = np.array([abs(r[f"{s}_theta_max_over_alpha"] - r["housner_theta_max_over_alpha"]) for r in safe])
        t = np.array([r[f"{s}_time"] for r in ran])
        sec = sum(r["duration_s"] for r in ran)
        out.append({
            "pair": f"{s} vs housner", "n_cases": len(ran), "n_failed": len(ran) - len(both),
            "verdict_agreement": len(agree) / len(both) if both else math.nan, "n_safe_both": len(safe),
            "median_dtheta_over_alpha": float(np.median(d)) if d.size else math.nan,
            "p95_dtheta_over_alpha": float(np.percentile(d, 95)) if d.size else math.nan,
            "max_dtheta_over_alpha": float(d.max()) if d.size else math.nan,
            "record_seconds_per_wall_second": sec / float(t.sum()) if t.sum() > 0 else math.nan,
        })
    return out


def _write(path: Path, rows: list[dict]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        if not rows:
            fh.write("")
            return
        w = csv.DictWriter(fh, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
