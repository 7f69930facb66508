"""Validation case 5: speed against accuracy, one chart from one run on this machine.

For each configuration (solver + numerical settings) the same fixed set of paper pulses is
solved; the error of ``theta_max / alpha`` is measured against *that model's own* converged
solution (the SDOF model for ``opensees`` and ``sdof``: the scipy SDOF solver at rtol 1e-12;
the rigid-body model for ``housner`` and ``housner_fast``: the scipy rigid-body solver at
rtol 1e-12), so the chart shows numerical cost and numerical error, not model-form error.
Wall time per case is the mean of the solver-reported times. The Pareto front is the set of
configurations no other one beats in both time and error.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from opsrock._files import read_table
from opsrock.campaign.cases import PulseCase
from opsrock.solvers import simulate
from opsrock.validation.sdof_agreement import paper_cases

#: Error below which a configuration is called accurate (docs/guide/modelling.md section 5: within 0.5 % of alpha).
ACCURACY_TARGET = 0.005

#: Converged references (solver, settings) per model.
REFERENCES: dict[str, tuple[str, dict[str, Any]]] = {
    "sdof_model": ("sdof", {"rtol": 1e-12, "atol": 1e-14}),
    "rigid_body": ("housner", {"rtol": 1e-12, "atol": 1e-14}),
}


def configurations(quick: bool = False) -> list[tuple[str, str, str, dict[str, Any]]]:
    """(label, model, solver, settings) of every configuration charted."""
    cfg: list[tuple[str, str, str, dict[str, Any]]] = []
    dts = (2e-3, 1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2e-5, 1e-5) if not quick else (1e-3, 1e-4)
    integrators = ("newmark", "hht", "generalized_alpha") if not quick else ("newmark",)
    for integ in integrators:
        for dt in dts:
            cfg.append((f"opensees {integ} dt={dt:g}", "sdof_model", "opensees",
                        {"integrator": integ, "step": dt, "adaptive": False}))
    for dt in ((5e-4, 2e-4, 1e-4, 5e-5) if not quick else (1e-4,)):
        cfg.append((f"opensees central_difference dt={dt:g}", "sdof_model", "opensees",
                    {"integrator": "central_difference", "step": dt, "adaptive": False}))
    for dt in ((8e-3, 4e-3, 2e-3, 1e-3) if not quick else (2e-3,)):
        cfg.append((f"opensees newmark adaptive dtmax={dt:g}", "sdof_model", "opensees",
                    {"integrator": "newmark", "step": dt, "adaptive": True}))
    rtols = (1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10) if not quick else (1e-4, 1e-8)
    for rtol in rtols:
        cfg.append((f"sdof rtol={rtol:g}", "sdof_model", "sdof", {"rtol": rtol, "atol": rtol * 1e-3}))
    for rtol in rtols:
        cfg.append((f"housner rtol={rtol:g}", "rigid_body", "housner", {"rtol": rtol, "atol": rtol * 1e-3}))
    for ms in ((0.2, 0.1, 0.05, 0.02, 0.01, 0.005) if not quick else (0.05, 0.01)):
        cfg.append((f"housner_fast max_step={ms:g}/p", "rigid_body", "housner_fast",
                    {"max_dtau": ms, "steps_per_pulse": max(8, int(round(4.0 / ms)))}))
    return cfg


def chart_cases(quick: bool = False) -> list[PulseCase]:
    """The fixed pulse set: 24 paper pulses (6 per block: 3 overturn, 3 safe), or 8 when ``quick``
    (per block one that overturns, f02/a04, and one that rocks safely, f08/a05)."""
    cases = paper_cases(quick=True)
    return [c for i, c in enumerate(cases) if i % 6 in (0, 4)] if quick else cases


def pareto_front(time: np.ndarray, error: np.ndarray) -> np.ndarray:
    """Boolean mask of the points no other point beats in both ``time`` and ``error``."""
    time = np.asarray(time, float)
    error = np.asarray(error, float)
    front = np.ones(time.size, bool)
    for i in range(time.size):
        dominated = (time <= time[i]) & (error <= error[i]) & ((time < time[i]) | (error < error[i]))
        front[i] = not dominated.any()
    return front


def measure(cases: list[PulseCase], quick: bool = False) -> pd.DataFrame:
    """Run every configuration on ``cases``; one row a configuration."""
    refs: dict[str, list] = {}
    for model, (solver, settings) in REFERENCES.items():
        refs[model] = [simulate(c.block, c.pulse, solver=solver, **settings) for c in cases]
    rows = []
    for label, model, solver, settings in configurations(quick):
        if solver == "housner_fast":  # exclude the one-off JIT compilation from the timing
            simulate(cases[0].block, cases[0].pulse, solver=solver, **settings)
        errs, verdict_wrong, failed, times = [], 0, 0, []
        for case, ref in zip(cases, refs[model]):
            r = simulate(case.block, case.pulse, solver=solver, **settings)
            times.append(r.wall_time_s)
            if not r.ok:
                failed += 1
                continue
            if r.verdict != ref.verdict:
                verdict_wrong += 1
            elif r.verdict == "safe":
                errs.append(abs(r.theta_max_over_alpha - ref.theta_max_over_alpha))
        n = len(cases)
        rows.append({
            "label": label,
            "model": model,
            "solver": solver,
            "settings": repr(settings),
            "time_per_case_s": float(np.mean(times)),
            "max_error_over_alpha": float(max(errs)) if errs else math.nan,
            "median_error_over_alpha": float(np.median(errs)) if errs else math.nan,
            "verdict_error_rate": verdict_wrong / n,
            "failed_rate": failed / n,
            "n_cases": n,
        })
    df = pd.DataFrame(rows)
    usable = (df["failed_rate"] == 0) & df["max_error_over_alpha"].notna()
    err_for_front = df["max_error_over_alpha"].where(usable, np.inf) + df["verdict_error_rate"] * 10
    # one front per model: the SDOF model's and the rigid body's errors are each against their own
    # converged answer, so they are not on one scale
    df["pareto"] = False
    for _, idx in df.groupby("model").groups.items():
        front = pareto_front(df.loc[idx, "time_per_case_s"].to_numpy(), err_for_front.loc[idx].to_numpy())
        df.loc[idx, "pareto"] = front & usable.loc[idx].to_numpy()
    df["accurate"] = usable & (df["max_error_over_alpha"] <= ACCURACY_TARGET) & (df["verdict_error_rate"] == 0)
    return df


def plot(df: pd.DataFrame, path: Path) -> Path:
    """Log-log chart of time per case against error, Pareto front marked."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 6))
    floor = 1e-9
    families = df["label"].str.replace(r" (dt|dtmax|rtol|max_step)=.*$", "", regex=True)
    markers = dict(zip(sorted(families.unique()), "osD^v<>ph*X"))
    for fam, sub in df.groupby(families):
        err = sub["max_error_over_alpha"].fillna(np.inf).clip(lower=floor)
        ok = np.isfinite(err) & (sub["failed_rate"] == 0)
        ax.loglog(sub["time_per_case_s"][ok], err[ok], marker=markers[fam], ls="-", lw=0.8, ms=6, label=fam)
        bad = ~ok
        if bad.any():
            ax.scatter(sub["time_per_case_s"][bad], np.full(bad.sum(), 3.0), marker="x", color="red", zorder=5)
    for model, ls in (("sdof_model", "-"), ("rigid_body", "--")):
        front = df[df["pareto"] & (df["model"] == model)].sort_values("time_per_case_s")
        ax.plot(front["time_per_case_s"], front["max_error_over_alpha"].clip(lower=floor), color="k", lw=2.5,
                alpha=0.3, ls=ls, label=f"Pareto front ({model.replace('_', ' ')})", zorder=0)
    ax.axhline(ACCURACY_TARGET, color="tab:green", ls="--", lw=1, label="0.5 % of alpha")
    ax.set_xlabel("wall time per case (s)")
    ax.set_ylabel(r"max $|\Delta\theta_{max}|/\alpha$ vs own converged model (safe cases)")
    ax.set_title("Speed against accuracy, one run on this machine (red x at top: failed or wrong verdict)")
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def replot(csv: Path) -> Path:
    """Redraw the chart from a saved ``speed_accuracy.csv`` (no solving)."""
    df = read_table(csv)
    return plot(df, Path(csv).with_suffix(".png"))


def run(out_dir: Path, quick: bool = False) -> dict[str, Any]:
    """Measure, write ``speed_accuracy.csv`` and ``speed_accuracy.png``, return headline figures."""
    out_dir = Path(out_dir)
    cases = chart_cases(quick)
    df = measure(cases, quick)
    suffix = "_quick" if quick else ""
    df.to_csv(out_dir / f"speed_accuracy{suffix}.csv", index=False, float_format="%.4g")
    plot(df, out_dir / f"speed_accuracy{suffix}.png")
    fastest = {}
    for solver, sub in df[df["accurate"]].groupby("solver"):
        best = sub.sort_values("time_per_case_s").iloc[0]
        fastest[f"fastest_accurate_{solver}"] = f"{best['label']} ({best['time_per_case_s']:.3g} s/case)"
    defaults_ok = {}
    for solver in ("opensees", "sdof", "housner", "housner_fast"):
        model = "rigid_body" if solver.startswith("housner") else "sdof_model"
        ref_solver, ref_settings = REFERENCES[model]
        errs, wrong = [], 0
        for c in cases:
            r = simulate(c.block, c.pulse, solver=solver)
            ref = simulate(c.block, c.pulse, solver=ref_solver, **ref_settings)
            if r.verdict != ref.verdict:
                wrong += 1
            elif r.verdict == "safe":
                errs.append(abs(r.theta_max_over_alpha - ref.theta_max_over_alpha))
        defaults_ok[f"default_{solver}_max_error"] = max(errs) if errs else 0.0
        defaults_ok[f"default_{solver}_verdict_errors"] = wrong
    metrics: dict[str, Any] = {"n_configurations": int(len(df)), "n_cases": len(cases),
                               "n_pareto": int(df["pareto"].sum()), **fastest, **defaults_ok}
    metrics["passed"] = bool(df["pareto"].any()) and all(
        defaults_ok[f"default_{s}_verdict_errors"] == 0 and defaults_ok[f"default_{s}_max_error"] <= ACCURACY_TARGET
        for s in ("opensees", "sdof", "housner", "housner_fast"))
    return metrics
