"""Multi-fidelity campaign of ``fema-far-field-ida-b3`` against the full OpenSees campaign (issue 26).

    .venv/bin/python studies/multifidelity/run_study.py [--work DIR] [--reuse]

In one run, one after the other on the same machine: the full campaign (``opsrock run fema-far-field-ida-b3
--solver opensees``), the multi-fidelity campaign (:func:`opsrock.campaign.run_campaign` with the ``MultiFidelity`` policy,
defaults: screen ``housner_fast``, margin the p95 of the measured model-form error, overturned cases
escalated, 2 % audit, seed 0), then ``opsrock fragility`` (200 record resamples, seed 0) on the full
campaign, the multi-fidelity one and the screen alone. Each stage runs in a child process; its wall time
and CPU time (its own and its workers', ``RUSAGE_CHILDREN``) are measured, with the load average
before it. ``--reuse`` skips the campaigns whose folders are complete (for re-running the comparison).

Writes into this folder: ``timings.csv``, ``fragility_comparison.csv``, ``escalation.csv`` (the rule's
picks against the full campaign's verdicts), ``variants.csv`` (other rules, replayed from the two
complete campaigns: every OpenSees row of a multi-fidelity run is the full campaign's row of that case,
checked here), ``summary.json`` (the run's :class:`MultiFidelitySummary`) and ``fragility_comparison.png``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import time
from dataclasses import asdict
from pathlib import Path

import numpy as np
import pandas as pd

from opsrock.analysis.record_columns import read_record_table
from opsrock.campaign.cases import read_cases

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
BIN = Path(sys.executable).parent
SCENE = "fema-far-field-ida-b3"
IMS = tuple(f"IM{k}" for k in range(1, 10))


def timed(name: str, argv: list[str], rows: list[dict]) -> None:
    """Run ``argv`` in a child process; append its wall and CPU time and the load before it."""
    load = os.getloadavg()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(argv, check=True, cwd=ROOT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    rows.append({"stage": name, "wall_s": wall, "cpu_s": cpu, "load_1min_before": load[0],
                 "load_5min_before": load[1]})
    print(f"{name}: {wall:.1f} s wall, {cpu:.1f} s CPU (load {load[0]:.2f} {load[1]:.2f})", flush=True)


def complete(folder: Path) -> bool:
    return (folder / "cases.csv").is_file()


def run_mf(out: str) -> None:
    """The multi-fidelity campaign, in this (child) process; its summary as JSON beside it."""
    from opsrock.campaign import run_campaign
    from opsrock.campaign.multifidelity import MultiFidelity

    s = run_campaign(SCENE, out, policy=MultiFidelity(), force=True, progress=False)
    print("\n".join(s.lines()), flush=True)
    d = asdict(s)
    Path(out, "summary.json").write_text(json.dumps(d, indent=2, default=str))


def campaigns(work: Path, reuse: bool) -> list[dict]:
    rows: list[dict] = []
    full, mf = work / "full_opensees", work / "mf"
    if not (reuse and complete(full)):
        timed("full opensees campaign (opsrock run --solver opensees)",
              [str(BIN / "opsrock"), "run", SCENE, "--solver", "opensees", "--out", str(full), "--force",
               "--no-progress"], rows)
    if not (reuse and complete(mf)):
        timed("multi-fidelity campaign (run_campaign, MultiFidelity defaults)",
              [sys.executable, __file__, "--mf-only", str(mf)], rows)
    for name, src in (("full", full), ("mf", mf), ("screen", mf / "screen")):
        dest = work / f"fragility_{name}"
        if not (reuse and (dest / "ims.csv").is_file()):
            timed(f"opsrock fragility ({name})", [str(BIN / "opsrock"), "fragility", str(src), "--out", str(dest)],
                  rows)
    return rows


# --- comparison ----------------------------------------------------------------------------------
def fragility_table(work: Path) -> pd.DataFrame:
    """Medians and betas of the multi-fidelity run and the screen against the full run's intervals."""
    cols = ["im", "n_overturned", "mu", "mu_lo", "mu_hi", "beta", "beta_lo", "beta_hi"]
    full = read_record_table(work / "fragility_full" / "ims.csv")[cols]
    out = full.rename(columns={c: f"{c}_full" for c in cols if c != "im"})
    for name in ("mf", "screen"):
        x = read_record_table(work / f"fragility_{name}" / "ims.csv")[["im", "n_overturned", "mu", "beta"]]
        x = x.rename(columns={c: f"{c}_{name}" for c in ("n_overturned", "mu", "beta")})
        out = out.merge(x, on="im")
        out[f"mu_{name}_in_ci"] = out[f"mu_{name}"].between(out["mu_lo_full"], out["mu_hi_full"])
        out[f"beta_{name}_in_ci"] = out[f"beta_{name}"].between(out["beta_lo_full"], out["beta_hi_full"])
        for q in ("mu", "beta"):
            out[f"{q}_{name}_ratio"] = out[f"{q}_{name}"] / out[f"{q}_full"]
            # share of the interval's half-width (on the side it falls) the deviation uses: 1 = at the bound
            dev = out[f"{q}_{name}"] - out[f"{q}_full"]
            half = np.where(dev >= 0, out[f"{q}_hi_full"] - out[f"{q}_full"], out[f"{q}_full"] - out[f"{q}_lo_full"])
            out[f"{q}_{name}_ci_use"] = dev / half
    return out


def escalation_table(work: Path) -> pd.DataFrame:
    """Per reason: cases, and among them those where the screen's verdict differs from the full run's."""
    from opsrock.campaign.multifidelity import derive_rule, escalation_reason

    rule = derive_rule("opensees", "housner_fast")
    screen = read_cases(work / "mf" / "screen" / "cases.csv")
    full = read_cases(work / "full_opensees" / "cases.csv").set_index("case_id")
    mf = read_cases(work / "mf" / "cases.csv").set_index("case_id")
    screen["reason"] = [escalation_reason(rule, r) or "kept" for r in screen.to_dict("records")]
    screen["source"] = mf.loc[screen["case_id"], "source"].to_numpy()
    screen["full_verdict"] = full.loc[screen["case_id"], "verdict"].to_numpy()
    screen["differs"] = screen["verdict"] != screen["full_verdict"]
    screen["group"] = np.where(screen["source"] == "audit", "kept (audited)", screen["reason"])
    g = screen.groupby("group")
    return pd.DataFrame({"cases": g.size(), "screen_verdict_differs_from_full": g["differs"].sum()}).reset_index()


def check_rows(work: Path) -> int:
    """Every OpenSees row of the multi-fidelity table is the full campaign's row of that case."""
    full = read_cases(work / "full_opensees" / "cases.csv").set_index("case_id")
    mf = read_cases(work / "mf" / "cases.csv").set_index("case_id")
    x = mf[mf["source"] != "screen"]
    cols = ["verdict", "status", "theta_max_over_alpha", "solver"]
    same = (x[cols].fillna(-1) == full.loc[x.index, cols].fillna(-1)).all(axis=1)
    if not same.all():
        raise SystemExit(f"rows differ from the full campaign: {list(x.index[~same])}")
    return int(same.sum())


def _fit(cases: pd.DataFrame) -> pd.DataFrame:
    from opsrock.fragility.record_study import RecordStudySettings, record_fragility

    return record_fragility(cases, RecordStudySettings(n_boot=0), n_rank_boot=0).ims.set_index("im")


def _variant(name: str, rule, screen: pd.DataFrame, full: pd.DataFrame, ref: pd.DataFrame) -> dict:
    from opsrock.campaign.multifidelity import select_cases

    if rule is None:
        ids, table = set(), screen
    else:
        sel = select_cases(screen.to_dict("records"), rule, audit_fraction=0.02, seed=0)
        ids = sel.ids
        table = pd.concat([screen[~screen["case_id"].isin(ids)], full[full["case_id"].isin(ids)]])
        table = table.set_index("case_id").loc[screen["case_id"]].reset_index()
    fit = _fit(table)
    agree = (table["verdict"].to_numpy() == full["verdict"].to_numpy()).mean()
    mu_in = ((fit["mu"] >= ref["mu_lo"]) & (fit["mu"] <= ref["mu_hi"])).sum()
    beta_in = ((fit["beta"] >= ref["beta_lo"]) & (fit["beta"] <= ref["beta_hi"])).sum()
    return {"rule": name, "margin": math.nan if rule is None else rule.margin,
            "escalate_overturned": None if rule is None else rule.escalate_overturned,
            "opensees_solves": len(ids), "fewer_x": len(screen) / len(ids) if ids else math.inf,
            "verdicts_as_full": agree, "n_overturned": int((table["verdict"] == "overturned").sum()),
            "mu_in_ci": int(mu_in), "beta_in_ci": int(beta_in),
            "max_abs_mu_dev": float((fit["mu"] / ref["mu"] - 1).abs().max()),
            "max_abs_beta_dev": float((fit["beta"] / ref["beta"] - 1).abs().max())}


def variants(work: Path) -> pd.DataFrame:
    """Other rules replayed on the two complete campaigns (point fits; the intervals are the full run's)."""
    from dataclasses import replace

    from opsrock.campaign.multifidelity import EVIDENCE, derive_rule

    screen = read_cases(work / "mf" / "screen" / "cases.csv")
    full = read_cases(work / "full_opensees" / "cases.csv")
    ref = read_record_table(work / "fragility_full" / "ims.csv").set_index("im")
    base = derive_rule("opensees", "housner_fast")
    ev = EVIDENCE["opensees"]
    rules = [("screen only", None), ("default: p95 case 9, overturned escalated", base),
             ("p90 case 9", derive_rule("opensees", "housner_fast", percentile=90)),
             ("p95 case 8 (0.2250)", replace(base, margin=0.22498004316022227)),
             (f"smallest flip in case 9 (1 - {ev.min_q_safe_to_overturned:.3f})",
              replace(base, margin=1 - ev.min_q_safe_to_overturned)),
             ("p95 case 9, overturned kept", replace(base, escalate_overturned=False)),
             ("overturned only (margin 0)", replace(base, margin=0.0))]
    return pd.DataFrame([_variant(n, r, screen, full, ref) for n, r in rules])


def figure(frag: pd.DataFrame, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), sharey=False)
    x = np.arange(len(frag))
    for ax, p in zip(axes, ("mu", "beta")):
        ref = frag[f"{p}_full"]
        lo, hi = frag[f"{p}_lo_full"] / ref, frag[f"{p}_hi_full"] / ref
        ax.vlines(x, lo, hi, color="0.6", lw=6, label="full OpenSees: 95 % record-bootstrap interval")
        ax.plot(x, np.ones(len(x)), "k_", ms=14, label="full OpenSees")
        ax.plot(x - 0.15, frag[f"{p}_mf"] / ref, "o", color="C0", label="multi-fidelity")
        ax.plot(x + 0.15, frag[f"{p}_screen"] / ref, "s", mfc="none", color="C3", label="rigid screen alone")
        ax.set_xticks(x, frag["im"])
        ax.set_ylabel(f"{'median' if p == 'mu' else 'beta'} / full campaign's")
        ax.grid(axis="y", alpha=0.3)
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("fema-far-field-ida-b3: fragility of the multi-fidelity campaign against the full OpenSees one",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main(argv: list[str]) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--work", default="/tmp/opsrock-mf-study", help="folder of the campaigns (not kept)")
    p.add_argument("--reuse", action="store_true", help="keep complete campaigns and fragility reports")
    p.add_argument("--mf-only", metavar="OUT", help=argparse.SUPPRESS)
    a = p.parse_args(argv)
    if a.mf_only:
        run_mf(a.mf_only)
        return 0
    work = Path(a.work)
    rows = campaigns(work, a.reuse)
    if rows:
        pd.DataFrame(rows).to_csv(HERE / "timings.csv", index=False)
    print(f"{check_rows(work)} OpenSees rows of the multi-fidelity table equal the full campaign's")
    frag = fragility_table(work)
    frag.to_csv(HERE / "fragility_comparison.csv", index=False)
    escalation_table(work).to_csv(HERE / "escalation.csv", index=False)
    variants(work).to_csv(HERE / "variants.csv", index=False)
    (HERE / "summary.json").write_text((work / "mf" / "summary.json").read_text())
    figure(frag, HERE / "fragility_comparison.png")
    with pd.option_context("display.width", 200, "display.max_columns", 40):
        print(frag.round(4).to_string(index=False))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
