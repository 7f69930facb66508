"""Multi-fidelity campaigns (opsrock.campaign.multifidelity): the rule, the seeded audit, the table, resume.

The campaigns here are small record scenes (2 blocks x 4 synthetic records x 3 levels) with ``housner`` as the
"expensive" solver (the scene's own, stopping at the first peak after the record) and ``housner_fast`` as the
screen, run in this process, so the suite stays fast; the paper's pairing (``opensees``) is the study in
``studies/multifidelity``.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import math
import shutil
import sqlite3
from pathlib import Path

import numpy as np
import pytest

from opsrock.campaign import CampaignOptions, run_campaign
from opsrock.campaign.cases import IDENTITY_EXCLUDED
from opsrock.campaign.multifidelity import (
    EVIDENCE,
    EscalationRule,
    derive_rule,
    MultiFidelity,
    escalation_reason,
    select_cases,
)
from opsrock.campaign.scene import load_scene
from opsrock.errors import CampaignConflictError, InputError
from _support import ROOT, BLOCKS, case_rows


SCENE = """
name = "mf"
blocks = "{blocks}"
select = ["bookcase", "medicine_cabinet"]
[solver]
name = "housner"
[solver.settings]
tail = "peak"
[records]
glob = "recs/*.csv"
units = "g"
ground = true
[records.intensity]
method = "ida"
measure = "pfa_ratio"
levels = [1.5, 3.0, 6.0]
"""

#: The rule of the integration tests: wide enough to escalate some safe cases and keep others; the
#: overturned cases are escalated too (the evidence for housner would trust the screen's: 29/29 agree).
MARGIN = 0.5
AUDIT = 0.2
POLICY = MultiFidelity(solver="housner", margin=MARGIN, escalate_overturned=True, audit_fraction=AUDIT, seed=3)


def run_multifidelity(scene, out, *, policy=POLICY, progress=False, force=False, **how):
    """The multi-fidelity policy over ``run_campaign`` (the one engine), quietly; ``how``: the other
    :class:`~opsrock.campaign.workflow.CampaignOptions` (executor, batch)."""
    return run_campaign(scene, out, progress=progress, force=force, options=CampaignOptions(policy=policy, **how))


class InProcess:
    """An executor that runs every batch in this process, in order (no worker start-up)."""

    workers = 1

    def map_batches(self, fn, batches, lost):
        for k, batch in enumerate(batches):
            yield k, fn(batch)

    def close(self):
        pass


class StopAfter(InProcess):
    """Runs ``n`` batches of the expensive solver (``housner``), then stops as a Ctrl-C would."""

    def __init__(self, n: int) -> None:
        self.n = n

    def map_batches(self, fn, batches, lost):
        for k, batch in enumerate(batches):
            if k == self.n and getattr(fn, "keywords", {}).get("solver") == "housner":
                raise KeyboardInterrupt
            yield k, fn(batch)


def write_records(folder: Path, n: int = 4) -> None:
    """Short, smooth records (4 s at 50 Hz): a windowed sine of 1-2.8 Hz with a little seeded noise."""
    folder.mkdir(parents=True, exist_ok=True)
    for k in range(n):
        rng = np.random.default_rng(200 + k)
        t = np.arange(200) * 0.02
        a = np.sin(2 * np.pi * (1.0 + 0.6 * k) * t) * np.exp(-((t - 1.5) / 0.8) ** 2) + 0.2 * rng.standard_normal(t.size)
        a = np.convolve(a, np.ones(3) / 3, mode="same") * 0.2
        np.savetxt(folder / f"rec{k}.csv", np.c_[t, a], delimiter=",", header="time,acc", comments="")


@pytest.fixture(scope="module")
def scene_path(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("mfscene")
    write_records(folder / "recs")
    path = folder / "scene.toml"
    path.write_text(SCENE.format(blocks=BLOCKS))
    return path


@pytest.fixture(scope="module")
def full(scene_path, tmp_path_factory) -> dict[str, dict[str, str]]:
    """A full campaign of the scene with the expensive solver: what every escalated row must equal."""
    out = tmp_path_factory.mktemp("full")
    run_campaign(scene_path, out, solver="housner", options=CampaignOptions(executor=InProcess()), progress=False)
    return {r["case_id"]: r for r in read_csv(out / "cases.csv")}


@pytest.fixture(scope="module")
def mf(scene_path, tmp_path_factory):
    out = tmp_path_factory.mktemp("mf") / "run"
    summary = run_multifidelity(scene_path, out, executor=InProcess())
    return summary, out


def read_csv(path: Path) -> list[dict[str, str]]:
    return case_rows(path)


def without_time(rows: list[dict[str, str]]) -> list[dict[str, str]]:
    return [{k: v for k, v in r.items() if k not in IDENTITY_EXCLUDED} for r in rows]


# --- the rule ------------------------------------------------------------------------------------
def row(verdict: str, q: float, pfa_ratio: float = 2.0, status: str = "ok", case_id: str = "c") -> dict:
    return {"case_id": case_id, "status": status, "verdict": verdict, "theta_max_over_alpha": q,
            "pfa_ratio": pfa_ratio}


@pytest.mark.parametrize(("rec", "reason"), [
    (row("failed", math.nan, status="failed"), "screen_failed"),
    (row("overturned", 8.7), "overturned"),
    (row("safe", 0.80), "near_overturning"),        # exactly at 1 - margin: escalated
    (row("safe", 1.15), "near_overturning"),        # past alpha and back: still near the boundary
    (row("safe", 0.7999), ""),                      # just outside the margin: kept
    (row("safe", 0.3), ""),
    (row("safe", 5e-5, pfa_ratio=1.005), "near_uplift"),   # lifted by less than the SDOF model calls rocking
    (row("safe", 2e-4, pfa_ratio=1.05), ""),
    (row("no_uplift", 0.0, pfa_ratio=1.0), "near_uplift"),  # at the threshold itself
    (row("no_uplift", 0.0, pfa_ratio=0.999), ""),           # below it neither model lifts the block
])
def test_escalation_reason_picks_the_cases_near_either_boundary(rec, reason):
    rule = EscalationRule(margin=0.2, escalate_overturned=True, uplift_q=1e-4, margin_source="test")
    assert escalation_reason(rule, rec) == reason


def test_a_rule_that_trusts_the_screen_keeps_overturned_and_uplift_cases():
    rule = EscalationRule(margin=0.2, escalate_overturned=False, uplift_q=0.0, margin_source="test")
    assert escalation_reason(rule, row("overturned", 8.7)) == ""
    assert escalation_reason(rule, row("no_uplift", 0.0, pfa_ratio=1.0)) == ""
    assert escalation_reason(rule, row("safe", 1e-6, pfa_ratio=1.001)) == ""
    assert escalation_reason(rule, row("safe", 0.85)) == "near_overturning"
    with pytest.raises(InputError, match="margin"):
        EscalationRule(margin=1.5, escalate_overturned=True, uplift_q=0.0, margin_source="test")


def test_the_derived_rule_is_the_measured_evidence():
    rule = derive_rule("opensees", "housner_fast")
    assert rule.margin == EVIDENCE["opensees"].abs_error[95]
    assert rule.escalate_overturned  # 11 of 52 rigid-overturned cases are safe for the SDOF model: > 5 %
    assert rule.uplift_q == pytest.approx(1e-4)  # 10 x the SDOF model's rocking threshold 10 theta_e
    assert "opensees_vs_rigid_p95_all" in rule.margin_source
    assert derive_rule("opensees", "housner", percentile=90).margin == EVIDENCE["opensees"].abs_error[90]
    same = derive_rule("housner", "housner_fast")  # the rigid pair: 108/108 verdicts, 1e-6 alpha
    assert not same.escalate_overturned and same.uplift_q == 0.0 and same.margin < 1e-5
    with pytest.raises(InputError, match="default SDOF model"):  # other physics: no evidence, no default
        derive_rule("opensees", "housner_fast", {"delta": 0.02})
    assert derive_rule("opensees", "housner_fast", {"delta": 0.02}, margin=0.3).margin == 0.3
    with pytest.raises(InputError, match="rigid body"):
        derive_rule("opensees", "sdof")
    with pytest.raises(InputError, match="percentile"):
        derive_rule("opensees", "housner_fast", percentile=99)
    with pytest.raises(InputError, match="no measured"):
        derive_rule("housner_fast", "housner")


def test_evidence_is_the_validation_files_numbers():
    """The shipped table the rule reads is what tools/evidence.py derives from the validation outputs."""
    import subprocess
    import sys

    assert (ROOT / "validation" / "sdof_records" / "cases.csv").is_file()  # committed: the evidence's source
    proc = subprocess.run([sys.executable, str(ROOT / "tools" / "evidence.py"), "--check"], capture_output=True)
    assert proc.returncode == 0, "opsrock/data/evidence/*.csv is stale: run tools/evidence.py"
    assert EVIDENCE["opensees"].abs_error[95] > EVIDENCE["opensees"].abs_error[50] > 0.0
    assert EVIDENCE["housner"].n_overturned_to_safe == 0


def test_evidence_agrees_with_the_shipped_solver_evidence():
    """The p95 the margin uses is also the one the package ships for ``solver = "auto"``."""
    shipped = ROOT / "opsrock" / "data" / "evidence" / "solvers.csv"
    assert shipped.is_file()  # package data (pyproject.toml): the evidence solver = "auto" reads
    with open(shipped, newline="") as fh:
        rows = {r["solver"]: r for r in csv.DictReader(fh)}
    for solver in ("opensees", "sdof"):  # both SDOF implementations are shipped with their model-form p95
        assert float(rows[solver]["model_form_p95_alpha"]) == EVIDENCE[solver].abs_error[95]


# --- the audit -----------------------------------------------------------------------------------
def test_the_audit_is_seeded_reproducible_and_drawn_from_the_kept_cases_only():
    rng = np.random.default_rng(0)
    table = [row("safe", float(q), case_id=f"c{k:04d}") for k, q in enumerate(rng.uniform(0.0, 1.0, 1000))]
    rule = EscalationRule(margin=0.1, escalate_overturned=True, uplift_q=0.0, margin_source="test")
    a = select_cases(table, rule, audit_fraction=0.03, seed=7)
    assert a == select_cases(table, rule, audit_fraction=0.03, seed=7)
    b = select_cases(table, rule, audit_fraction=0.03, seed=8)
    assert a.escalated == b.escalated and a.audited != b.audited
    n_kept = 1000 - len(a.escalated)
    assert len(a.audited) == math.ceil(0.03 * n_kept) == len(set(a.audited))
    assert not set(a.audited) & set(a.escalated)
    assert set(a.escalated) == {r["case_id"] for r in table if r["theta_max_over_alpha"] >= 0.9}
    assert list(a.audited) == sorted(a.audited)  # in the table's order
    assert select_cases(table, rule, audit_fraction=0.0).audited == ()
    with pytest.raises(InputError, match="audit_fraction"):
        select_cases(table, rule, audit_fraction=1.5)


# --- a campaign ----------------------------------------------------------------------------------
def test_every_case_has_one_row_from_the_right_solver(mf, full, scene_path):
    summary, out = mf
    rows = read_csv(out / "cases.csv")
    screen = {r["case_id"]: r for r in read_csv(out / "screen" / "cases.csv")}
    scene = load_scene(scene_path).with_solver("housner")
    assert [r["case_id"] for r in rows] == list(screen) == list(full)  # one row per case, the scene's order
    assert list(rows[0]) == [*scene.columns, "source"]
    audit = select_cases(list(screen.values()), summary.rule, audit_fraction=AUDIT, seed=3).audited
    assert summary.audited == audit
    for r in rows:
        reason = escalation_reason(summary.rule, screen[r["case_id"]])
        assert r["source"] == ("escalated" if reason else "audit" if r["case_id"] in audit else "screen")
        ref = full[r["case_id"]] if r["source"] != "screen" else screen[r["case_id"]]
        assert {k: v for k, v in r.items() if k not in (*IDENTITY_EXCLUDED, "source")} == \
               {k: v for k, v in ref.items() if k not in IDENTITY_EXCLUDED}
        assert r["solver"] == ("housner_fast" if r["source"] == "screen" else "housner")
    by_source = {s: sum(r["source"] == s for r in rows) for s in ("screen", "escalated", "audit")}
    assert by_source == {"screen": summary.n_screened, "escalated": summary.n_escalated, "audit": summary.n_audited}
    # the scene is not degenerate: the rule has picked near-boundary cases and kept others
    assert summary.escalated_by_reason["near_overturning"] > 0 and summary.escalated_by_reason["overturned"] > 0
    assert summary.n_audited == math.ceil(AUDIT * (24 - summary.n_escalated)) > 0
    assert summary.n_solves_saved == 24 - summary.n_escalated - summary.n_audited > 0
    assert summary.n_computed == summary.n_escalated + summary.n_audited


def test_escalation_picks_the_cases_within_the_margin(mf):
    _, out = mf
    rows = read_csv(out / "cases.csv")
    screen = {r["case_id"]: r for r in read_csv(out / "screen" / "cases.csv")}
    taken = {"escalated": 0, "kept": 0}
    for r in rows:
        s = screen[r["case_id"]]
        near = s["verdict"] == "safe" and float(s["theta_max_over_alpha"]) >= 1 - MARGIN
        if near or s["verdict"] == "overturned":
            assert r["source"] == "escalated"
            taken["escalated"] += 1
        else:
            assert r["source"] in ("screen", "audit")
            taken["kept"] += 1
    assert taken["escalated"] > 0 and taken["kept"] > 0  # the scene exercises both sides of the rule


def test_the_audit_agreement_and_manifest_are_reported(mf):
    summary, out = mf
    manifest = json.loads((out / "manifest.json").read_text())
    assert manifest["n_cases"] == 24 and manifest["kind"] == "multifidelity"
    assert manifest["rule"]["margin"] == MARGIN and manifest["rule"]["margin_source"] == "given"
    assert manifest["audit"]["seed"] == 3 and manifest["audit"]["n"] == summary.n_audited
    assert manifest["counts"]["by_reason"] == dict(summary.escalated_by_reason)
    # housner_fast and housner solve the same equation: the audit agrees, and its interval says how well
    assert summary.n_audit_agree == summary.n_audit_compared == summary.n_audited
    lo, hi = summary.audit_interval
    assert hi == 1.0 and 0.0 < lo < 1.0
    text = "\n".join(summary.lines())
    assert f"{summary.n_audited}/{summary.n_audited} same verdict" in text and "fewer" in text


def test_same_seed_same_table_other_seed_other_audit(mf, scene_path, tmp_path):
    summary, out = mf
    run = tmp_path / "run"
    shutil.copytree(out, run)
    again = run_multifidelity(scene_path, run, executor=InProcess())
    assert (again.n_computed, again.n_reused, again.audited) == (0, summary.n_computed, summary.audited)
    assert without_time(read_csv(run / "cases.csv")) == without_time(read_csv(out / "cases.csv"))
    other = run_multifidelity(scene_path, run, executor=InProcess(), policy=dataclasses.replace(POLICY, seed=4))
    assert other.audited != summary.audited and len(other.audited) == len(summary.audited)
    assert other.n_escalated == summary.n_escalated
    # the escalated store keeps every expensive row: only the newly audited cases are solved
    assert other.n_computed == len(set(other.audited) - set(summary.audited))
    assert {r["case_id"] for r in read_csv(run / "cases.csv") if r["source"] == "audit"} == set(other.audited)


def test_an_interrupted_run_resumes_and_ends_with_the_same_table(mf, scene_path, tmp_path):
    summary, out = mf
    run = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt):  # the screen completes, the expensive solver stops after 1 batch
        run_multifidelity(scene_path, run, executor=StopAfter(1), batch=2)
    with sqlite3.connect(run / "escalated" / "results.sqlite") as db:
        (kept,) = db.execute("SELECT COUNT(*) FROM results").fetchone()
    assert kept == 2  # the one committed batch, nothing else
    assert not (run / "cases.csv").exists()
    resumed = run_multifidelity(scene_path, run, executor=InProcess())
    assert (resumed.n_reused, resumed.n_computed) == (2, summary.n_escalated + summary.n_audited - 2)
    assert without_time(read_csv(run / "cases.csv")) == without_time(read_csv(out / "cases.csv"))
    # a case lost in flight (its row never committed) is computed again, and only it
    with sqlite3.connect(run / "escalated" / "results.sqlite") as db:
        lost = db.execute("SELECT case_id FROM results ORDER BY case_id LIMIT 1").fetchone()[0]
        db.execute("DELETE FROM results WHERE case_id = ?", (lost,))
    again = run_multifidelity(scene_path, run, executor=InProcess())
    assert again.n_computed == 1 and again.n_reused == summary.n_escalated + summary.n_audited - 1
    assert without_time(read_csv(run / "cases.csv")) == without_time(read_csv(out / "cases.csv"))


def test_a_folder_of_other_settings_is_refused_unless_forced(mf, scene_path, tmp_path):
    summary, out = mf
    run = tmp_path / "run"
    shutil.copytree(out, run)
    other = load_scene(scene_path).with_solver("housner", {"tail": "rest"})
    with pytest.raises(CampaignConflictError, match="refusing to mix"):
        run_multifidelity(other, run, executor=InProcess())
    assert without_time(read_csv(run / "cases.csv")) == without_time(read_csv(out / "cases.csv"))
    cheap = dataclasses.replace(POLICY, margin=0.0, escalate_overturned=False, audit_fraction=0.0)
    forced = run_multifidelity(other, run, executor=InProcess(), force=True, policy=cheap)
    assert forced.n_reused == 0 and forced.n_computed == forced.n_escalated + forced.n_audited
    with sqlite3.connect(run / "escalated" / "results.sqlite") as db:
        (n_rows,) = db.execute("SELECT COUNT(*) FROM results").fetchone()
    assert n_rows == forced.n_computed < summary.n_computed  # the old results are gone


def test_bad_arguments_write_nothing(scene_path, tmp_path):
    for kwargs, match in (({"solver": "housner_fast"}, "other than the screen"),
                          ({"solver": "housner", "screen_solver": "opensees"}, "rigid body"),
                          ({"solver": "opensees", "percentile": 99}, "percentile"),
                          ({"solver": "housner", "margin": -0.1}, "margin")):
        with pytest.raises(InputError, match=match):
            run_multifidelity(scene_path, tmp_path / "bad", executor=InProcess(), policy=MultiFidelity(**kwargs))
    assert not (tmp_path / "bad").exists()
