"""Validation case 2: the OpenSees model against the independent scipy SDOF solver.

Both solve the *same* equations (Eq. 6-8: tabulated spring, discrete damper, same lever), so
any difference is an implementation or discretisation error of the OpenSees model. Targets
(docs/guide/modelling.md section 5): ``|d theta_max| / alpha <= 1 %`` for at least 99 % of the cases that do not
overturn, the same verdict for at least 99 % of all cases, every disagreement listed with its
distance to the overturning boundary.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np
import pandas as pd

from opsrock._pool import process_pool
from opsrock.campaign.cases import PulseCase
from opsrock.campaign.scene import load_scene
from opsrock.data import scene_file
from opsrock.excitations import OneSinePulse
from opsrock.solvers import simulate

#: Repository scene of the paper's 400 pulses (docs/guide/modelling.md section 3).
PAPER_SCENE = scene_file("paper")

#: Agreement targets (docs/guide/modelling.md section 5).
THETA_TOLERANCE = 0.01  # |d theta_max| / alpha
THETA_TARGET_RATE = 0.99  # share of cases safe in both within THETA_TOLERANCE
VERDICT_TARGET_RATE = 0.99  # share of all cases with the same verdict

#: Relative PFA changes tried, in order, to measure a disagreeing case's distance to the boundary.
BOUNDARY_STEPS: tuple[float, ...] = (0.0025, 0.005, 0.01, 0.02, 0.05, 0.1)


@dataclass(frozen=True)
class Agreement:
    """Summary of a two-solver comparison.

    Parameters
    ----------
    n_cases : int
        Cases compared.
    n_failed : int
        Cases where either solver failed (never counted as agreeing).
    n_safe_both : int
        Cases that rocked and did not overturn in both solvers.
    theta_within_rate : float
        Share of ``n_safe_both`` with ``|d theta_max| / alpha <= THETA_TOLERANCE``.
    verdict_rate : float
        Share of all cases with the same verdict (failures count as disagreements).
    max_dtheta : float
        Largest ``|d theta_max| / alpha`` among ``n_safe_both`` cases.
    p99_dtheta : float
        99th percentile of the same.
    passed : bool
        Both targets met and no failure.
    """

    n_cases: int
    n_failed: int
    n_safe_both: int
    theta_within_rate: float
    verdict_rate: float
    max_dtheta: float
    p99_dtheta: float
    passed: bool


def _one(job: tuple[PulseCase, str, dict, str, dict]) -> dict[str, Any]:
    case, solver_a, settings_a, solver_b, settings_b = job
    ra = simulate(case.block, case.pulse, solver=solver_a, **settings_a)
    rb = simulate(case.block, case.pulse, solver=solver_b, **settings_b)
    return {
        "case_id": case.case_id,
        "block": case.block.name,
        "alpha": case.block.alpha,
        "freq_ratio": case.freq_ratio,
        "pfa_ratio": case.pfa_ratio,
        "theta_max_over_alpha_a": ra.theta_max_over_alpha,
        "theta_max_over_alpha_b": rb.theta_max_over_alpha,
        "verdict_a": ra.verdict,
        "verdict_b": rb.verdict,
        "reason_a": ra.reason,
        "reason_b": rb.reason,
        "wall_time_a": ra.wall_time_s,
        "wall_time_b": rb.wall_time_s,
        "steps_a": ra.n_steps,
        "steps_b": rb.n_steps,
    }


def compare(
    cases: Sequence[PulseCase],
    solver_a: str = "opensees",
    solver_b: str = "sdof",
    *,
    settings_a: dict | None = None,
    settings_b: dict | None = None,
    workers: int | None = None,
) -> pd.DataFrame:
    """Run every case through two solvers; one row a case.

    Parameters
    ----------
    cases : sequence of PulseCase
        Cases (block + pulse) to compare.
    solver_a, solver_b : str
        Solver names; ``solver_b`` is the reference.
    settings_a, settings_b : dict, optional
        Keyword settings of each solver.
    workers : int, optional
        Worker processes (default: the machine's cores).
    """
    jobs = [(c, solver_a, settings_a or {}, solver_b, settings_b or {}) for c in cases]
    workers = workers or os.cpu_count() or 1
    if workers == 1:
        rows = [_one(j) for j in jobs]
    else:
        with process_pool(workers) as pool:
            rows = list(pool.map(_one, jobs, chunksize=max(1, len(jobs) // (8 * workers))))
    df = pd.DataFrame(rows)
    df["dtheta_over_alpha"] = (df["theta_max_over_alpha_a"] - df["theta_max_over_alpha_b"]).abs()
    df["same_verdict"] = (df["verdict_a"] == df["verdict_b"]) & (df["verdict_a"] != "failed")
    return df


def summarize(df: pd.DataFrame) -> Agreement:
    """Agreement figures of a :func:`compare` table against the targets of docs/guide/modelling.md section 5."""
    failed = (df["verdict_a"] == "failed") | (df["verdict_b"] == "failed")
    safe = (df["verdict_a"] == "safe") & (df["verdict_b"] == "safe")
    d = df.loc[safe, "dtheta_over_alpha"].to_numpy()
    within = float(np.mean(d <= THETA_TOLERANCE)) if d.size else 1.0
    verdict = float(df["same_verdict"].mean()) if len(df) else 1.0
    return Agreement(
        n_cases=int(len(df)),
        n_failed=int(failed.sum()),
        n_safe_both=int(safe.sum()),
        theta_within_rate=within,
        verdict_rate=verdict,
        max_dtheta=float(d.max()) if d.size else 0.0,
        p99_dtheta=float(np.quantile(d, 0.99)) if d.size else 0.0,
        passed=bool(within >= THETA_TARGET_RATE and verdict >= VERDICT_TARGET_RATE and not failed.any()),
    )


def boundary_distance(case: PulseCase, target_verdict: str, solver: str = "sdof", settings: dict | None = None) -> float:
    """Smallest relative change of PFA for which ``solver`` gives ``target_verdict``.

    A disagreement between two solvers right at the overturning boundary (a fraction of a
    percent of PFA away) is a different matter from one far from it. Returns ``inf`` if no
    change up to 10 % flips the verdict.
    """
    for step in BOUNDARY_STEPS:
        for sign in (-1.0, 1.0):
            pulse = OneSinePulse(pfa=case.pulse.pfa * (1.0 + sign * step), omega_p=case.pulse.omega_p)
            if simulate(case.block, pulse, solver=solver, **(settings or {})).verdict == target_verdict:
                return sign * step
    return math.inf


def disagreements(df: pd.DataFrame, cases: Sequence[PulseCase], solver_b: str = "sdof") -> pd.DataFrame:
    """Every case with a different verdict, or outside the theta tolerance, with its boundary distance."""
    by_id = {c.case_id: c for c in cases}
    bad = df[(~df["same_verdict"]) | ((df["verdict_a"] == "safe") & (df["dtheta_over_alpha"] > THETA_TOLERANCE))].copy()
    dist = []
    for _, row in bad.iterrows():
        if row["verdict_a"] in ("safe", "overturned") and row["verdict_a"] != row["verdict_b"]:
            dist.append(boundary_distance(by_id[row["case_id"]], row["verdict_a"], solver_b))
        else:
            dist.append(math.nan)
    bad["pfa_change_to_flip_reference"] = dist
    return bad


def paper_cases(quick: bool = False) -> list[PulseCase]:
    """The paper's 400 cases, or (``quick``) a fixed spread of 24 of them: 6 per block."""
    cases = load_scene(PAPER_SCENE).cases()
    if not quick:
        return cases
    pick = []
    for k in range(4):
        block_cases = cases[100 * k : 100 * (k + 1)]
        pick += [block_cases[i] for i in (13, 27, 45, 58, 74, 96)]
    return pick


def run(out_dir: Path, quick: bool = False) -> dict[str, Any]:
    """Run the case: table, disagreements, summary and the Figure-4 style overlay into ``out_dir``."""
    from opsrock.plots.response import plot_histories

    out_dir = Path(out_dir)
    cases = paper_cases(quick)
    df = compare(cases)
    summary = summarize(df)
    bad = disagreements(df, cases)
    suffix = "_quick" if quick else ""
    df.to_csv(out_dir / f"agreement{suffix}.csv", index=False, float_format="%.6g")
    bad.to_csv(out_dir / f"disagreements{suffix}.csv", index=False, float_format="%.6g")
    # Figure 4 layout: three safe, three overturning cases, OpenSees over the scipy SDOF reference
    by_id = {c.case_id: c for c in cases}
    safe = df[df["verdict_b"] == "safe"].sort_values("theta_max_over_alpha_b")
    over = df[df["verdict_b"] == "overturned"].sort_values("pfa_ratio")
    chosen = list(safe["case_id"].iloc[np.linspace(0, len(safe) - 1, 3).astype(int)]) if len(safe) >= 3 else list(safe["case_id"])
    chosen += list(over["case_id"].iloc[np.linspace(0, len(over) - 1, 3).astype(int)]) if len(over) >= 3 else list(over["case_id"])
    res_a, res_b, titles = [], [], []
    for cid in chosen:
        c = by_id[cid]
        res_a.append(simulate(c.block, c.pulse, solver="opensees"))
        res_b.append(simulate(c.block, c.pulse, solver="sdof"))
        titles.append(f"{cid}: " + r"$\omega_p/p$" + f"={c.freq_ratio:.3g}, PFA/g tan" + r"$\alpha$" + f"={c.pfa_ratio:.3g}")
    plot_histories(res_a, titles, out_dir / f"histories{suffix}.png", references=res_b, reference_label="scipy SDOF")
    metrics = dict(summary.__dict__)
    metrics["n_disagreements"] = int(len(bad))
    metrics["opensees_s_per_case"] = float(df["wall_time_a"].mean())
    metrics["sdof_s_per_case"] = float(df["wall_time_b"].mean())
    pd.Series(metrics).to_csv(out_dir / f"summary{suffix}.csv", header=["value"])
    return metrics
