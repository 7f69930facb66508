"""The fast part of validation cases 2-4, 7 and 8 (case 1 runs in tests/validation/test_closed_forms.py).

Each case's ``run(out_dir, quick=True)`` regenerates its outputs into a temporary folder (once per module)
and reports ``passed`` against the relation and tolerance its README derives. Cases 2, 4, 7 and 8 are
also asserted row by row: one test a row, its id naming the case and the row, its message the value, the
reference and the tolerance.
"""

from __future__ import annotations

import math

import pandas as pd
import pytest

from opsrock.validation import CASES, run_case
from opsrock.validation.lumped_mass import BLOCKS as LUMPED_BLOCKS
from opsrock.validation.lumped_mass import PULSES as LUMPED_PULSES
from opsrock.validation.lumped_mass import TOLERANCE_ALPHA as LUMPED_TOLERANCE
from opsrock.validation.published_thresholds import REFERENCE_TOLERANCE
from opsrock.validation.published_thresholds import rows as published_rows
from opsrock.validation.records import BLOCKS as RECORD_BLOCKS
from opsrock.validation.records import LEVELS as RECORD_LEVELS
from opsrock.validation.sdof_agreement import THETA_TOLERANCE, paper_cases

#: Row ids of the quick forms known before they run: case 7's compared boundaries, case 2's pulses (6 per block).
PUBLISHED_ROWS: list[str] = [r.key for r in published_rows()]
QUICK_PULSES: list[str] = [c.case_id for c in paper_cases(quick=True)]

pytestmark = pytest.mark.opensees


def test_registry_lists_the_cases_in_order():
    assert CASES == ("closed_forms", "sdof_agreement", "model_form", "lumped_mass", "speed_accuracy",
                     "stability_map", "published_thresholds", "records", "sdof_records", "experiments",
                     "friction")


# --- case 7: the published overturning thresholds, one test a row --------------------------------------
@pytest.fixture(scope="module")
def published_thresholds(tmp_path_factory):
    out = tmp_path_factory.mktemp("published_thresholds")
    m = run_case("published_thresholds", out, quick=True)
    return out, m, pd.read_csv(out / "table.csv").set_index("key")


def test_published_thresholds_quick(published_thresholds):
    # every published value with a number (Housner 1963, Makris and Roussos 2000, Zhang and Makris
    # 2001 incl. the locomotive example) within the tolerance its row justifies (printing precision),
    # and housner_fast within 1e-5 of each independent reference (closed forms, closed-form event
    # solution); the table and the chart are written. Each row is asserted by test_published_threshold_row.
    out, m, table = published_thresholds
    assert m["passed"] and m["n_published_compared"] == 6, m
    assert m["max_rel_diff_reference"] <= 1e-5, m
    assert list(table.index) == PUBLISHED_ROWS
    assert table.loc["zhang_makris2001_locomotive_linearised", "role"] == "reading"
    assert abs(table.loc["zhang_makris2001_locomotive_linearised", "rel_diff_published"]) > 0.1  # not reproduced
    assert (out / "thresholds.png").stat().st_size > 20_000


@pytest.mark.parametrize("key", PUBLISHED_ROWS, ids=[f"published_thresholds/{k}" for k in PUBLISHED_ROWS])
def test_published_threshold_row(published_thresholds, key):
    _, _, table = published_thresholds
    row = table.loc[key]
    ours, published, reference = row["housner_fast"], row["published"], row["reference"]
    if row["role"] != "test":  # a reading of a chart, reported beside ours and never tested
        assert row["passed"], f"{key}: a '{row['role']}' row must not fail the case"
        return
    assert math.isfinite(ours), f"{key}: housner_fast found no boundary on the '{row['branch']}' branch"
    if not (math.isfinite(published) or math.isfinite(reference)):
        # an exact-equation row without a closed form: its reference is the event-driven housner run of the
        # full form only; the quick form finds the boundary and says the reference was not run
        assert row["reference_kind"] == "not run", f"{key}: no published value and no reference, yet '{row['reference_kind']}'"
    if math.isfinite(published):
        d = ours / published - 1.0
        assert abs(d) <= row["tolerance"], (
            f"{key}: housner_fast {ours:.8g} against published {published:.8g} ({row['unit']}): relative difference "
            f"{d:.3g} beyond the tolerance {row['tolerance']:.3g} ({row['tolerance_reason']})")
    if math.isfinite(reference):
        d = ours / reference - 1.0
        assert abs(d) <= REFERENCE_TOLERANCE, (
            f"{key}: housner_fast {ours:.10g} against the {row['reference_kind']} {reference:.10g} ({row['unit']}): "
            f"relative difference {d:.3g} beyond the tolerance {REFERENCE_TOLERANCE:.3g}")
    assert row["passed"], f"{key}: the case marks the row failed"


# --- case 8: the solvers on FEMA P695 records, one test a case --------------------------------------------
#: The quick form's motions: the first far-field record at the ground and on the roof of the case's 3-storey building.
RECORD_FLOORS: tuple[str, ...] = ("ground", "b3.f3")
#: housner_fast against housner on a safe case (alpha): both solve the rigid-body equation to 5e-3 alpha or
#: better; measured 1.1e-5 alpha at most.
RECORDS_THETA_TOLERANCE: float = 1e-3
RECORD_ROWS: list[tuple[str, str, float]] = [
    (name, floor, level) for name, _, _ in RECORD_BLOCKS for floor in RECORD_FLOORS for level in RECORD_LEVELS]


@pytest.fixture(scope="module")
def records_case(record_library, tmp_path_factory):
    out = tmp_path_factory.mktemp("records")
    m = run_case("records", out, quick=True)
    return out, m, pd.read_csv(out / "cases.csv", keep_default_na=False, na_values=[""])


@pytest.mark.slow  # CI's make test-wheel runs this quick form through opsrock validate --quick
def test_records_quick(records_case):
    # 18 record cases (1 FEMA P695 component, ground and roof of a 3-storey building, 3 blocks,
    # 3 amplitudes); housner_fast must give housner's verdict on every case and its theta_max to
    # 1e-3 alpha on safe ones (each case asserted by test_records_row).
    out, m, cases = records_case
    assert m["passed"] and m["n_cases"] == 18, m
    assert set(cases["floor"]) == set(RECORD_FLOORS)
    summary = pd.read_csv(out / "summary.csv").set_index("pair")
    assert summary.loc["housner_fast vs housner", "verdict_agreement"] == 1.0
    assert summary.loc["housner_fast vs housner", "max_dtheta_over_alpha"] <= RECORDS_THETA_TOLERANCE
    assert summary["n_failed"].eq(0).all(), summary


@pytest.mark.slow
@pytest.mark.parametrize("block, floor, level", RECORD_ROWS,
                         ids=[f"records/{b}/{f}/{lv:g}" for b, f, lv in RECORD_ROWS])
def test_records_row(records_case, block, floor, level):
    _, _, cases = records_case
    sel = cases[(cases["block"] == block) & (cases["floor"] == floor) & (cases["pfa_ratio"] == level)]
    assert len(sel) == 1, f"records/{block}/{floor}/{level:g}: {len(sel)} rows"
    r = sel.iloc[0]
    case = f"records/{block}/{r['record']}@{floor}/PFA {level:g} g tan(alpha)"
    for s in ("housner", "housner_fast", "opensees"):
        assert r[f"{s}_verdict"] != "failed", f"{case}: {s} failed ({r[f'{s}_reason']})"
    assert r["housner_fast_verdict"] == r["housner_verdict"], (
        f"{case}: housner_fast says {r['housner_fast_verdict']}, the reference housner {r['housner_verdict']}")
    if r["housner_verdict"] == "safe":
        a, b = r["housner_fast_theta_max_over_alpha"], r["housner_theta_max_over_alpha"]
        assert abs(a - b) <= RECORDS_THETA_TOLERANCE, (
            f"{case}: housner_fast theta_max/alpha {a:.8g} against housner {b:.8g}: |difference| {abs(a - b):.3g} "
            f"beyond the tolerance {RECORDS_THETA_TOLERANCE:g}")


# --- case 2: OpenSees against the scipy SDOF solver, one test a pulse ---------------------------------------
@pytest.fixture(scope="module")
def sdof_agreement_case(tmp_path_factory):
    out = tmp_path_factory.mktemp("sdof_agreement")
    m = run_case("sdof_agreement", out, quick=True)
    return out, m, pd.read_csv(out / "agreement_quick.csv", keep_default_na=False, na_values=[""]).set_index("case_id")


@pytest.mark.slow  # CI's make test-wheel runs this quick form through opsrock validate --quick
def test_sdof_agreement_quick(sdof_agreement_case):
    # 24 paper pulses (6 per block): targets 99 % within 1 % of alpha, 99 % same verdict; on 24 pulses that
    # is every one of them (each asserted by test_sdof_agreement_row).
    out, m, df = sdof_agreement_case
    assert m["passed"] and m["n_failed"] == 0, m
    assert m["theta_within_rate"] >= 0.99 and m["verdict_rate"] >= 0.99, m
    assert (out / "histories_quick.png").stat().st_size > 10_000
    assert list(df.index) == QUICK_PULSES


@pytest.mark.slow
@pytest.mark.parametrize("case_id", QUICK_PULSES, ids=[f"sdof_agreement/{c}" for c in QUICK_PULSES])
def test_sdof_agreement_row(sdof_agreement_case, case_id):
    _, _, df = sdof_agreement_case
    r = df.loc[case_id]
    case = f"sdof_agreement/{case_id} (omega_p/p {r['freq_ratio']:.4g}, PFA/(g tan alpha) {r['pfa_ratio']:.4g})"
    assert r["verdict_a"] != "failed" and r["verdict_b"] != "failed", (
        f"{case}: failed run: opensees {r['reason_a']!r}, sdof {r['reason_b']!r}")
    assert r["verdict_a"] == r["verdict_b"], f"{case}: opensees says {r['verdict_a']}, the reference sdof {r['verdict_b']}"
    if r["verdict_a"] == "safe":
        a, b = r["theta_max_over_alpha_a"], r["theta_max_over_alpha_b"]
        assert abs(a - b) <= THETA_TOLERANCE, (
            f"{case}: opensees theta_max/alpha {a:.6g} against sdof {b:.6g}: |difference| {abs(a - b):.3g} beyond "
            f"the tolerance {THETA_TOLERANCE:g}")


# Behind slow to keep make test under 10 minutes: CI's `make test-wheel` runs every case's quick form through
# `opsrock validate --quick`, which fails unless each case passes its targets.
@pytest.mark.slow
def test_model_form_quick(tmp_path):
    # 36 pulses; the SDOF model approaches the rigid body as delta shrinks (README of the case).
    m = run_case("model_form", tmp_path, quick=True)
    assert m["passed"], m


# --- case 4: the lumped-mass form against the rotational form, one test a pulse ------------------------------
LUMPED_ROWS: list[tuple[str, float, float]] = [(LUMPED_BLOCKS[0].name, pr, fr) for pr, fr in LUMPED_PULSES[:2]]
LEVER_ROWS: list[tuple[str, float]] = [(LUMPED_BLOCKS[0].name, pr) for pr in (0.7, 0.8, 0.9)]


@pytest.fixture(scope="module")
def lumped_mass_case(tmp_path_factory):
    out = tmp_path_factory.mktemp("lumped_mass")
    m = run_case("lumped_mass", out, quick=True)
    return (m, pd.read_csv(out / "lumped_vs_rotational.csv", keep_default_na=False),
            pd.read_csv(out / "printed_lever_uplift.csv", keep_default_na=False))


def test_lumped_mass_quick(lumped_mass_case):
    # Figure 2b's lumped-mass form equals the rotational form with lever m R cos(alpha) (each pulse and each
    # lever row asserted below).
    m, rows, lever = lumped_mass_case
    assert m["passed"], m
    assert len(rows) == len(LUMPED_ROWS) and len(lever) == len(LEVER_ROWS)


@pytest.mark.parametrize("block, pfa_ratio, freq_ratio", LUMPED_ROWS,
                         ids=[f"lumped_mass/{b}/pfa{p:g}/freq{f:g}" for b, p, f in LUMPED_ROWS])
def test_lumped_mass_row(lumped_mass_case, block, pfa_ratio, freq_ratio):
    _, rows, _ = lumped_mass_case
    r = rows[(rows["block"] == block) & (rows["pfa_ratio"] == pfa_ratio) & (rows["freq_ratio"] == freq_ratio)].iloc[0]
    case = f"lumped_mass/{block}/PFA {pfa_ratio:g} g tan(alpha)/omega_p/p {freq_ratio:g}"
    assert r["verdict_lumped"] == r["verdict_1dof"], (
        f"{case}: lumped-mass form says {r['verdict_lumped']}, the rotational form {r['verdict_1dof']}")
    assert r["max_diff_alpha"] <= LUMPED_TOLERANCE, (
        f"{case}: max |theta_lumped - theta_1dof|/alpha = {r['max_diff_alpha']:.3g} beyond the tolerance "
        f"{LUMPED_TOLERANCE:g} (theta_max/alpha {r['theta_max_lumped_alpha']:.8g} against {r['theta_max_1dof_alpha']:.8g})")


@pytest.mark.parametrize("block, pfa_ratio", LEVER_ROWS,
                         ids=[f"lumped_mass/printed_lever/{b}/pfa{p:g}" for b, p in LEVER_ROWS])
def test_printed_lever_row(lumped_mass_case, block, pfa_ratio):
    # the printed lever I_O cos(alpha)/R uplifts above 0.75 g tan(alpha); Figure 2b's model never below 1
    _, _, lever = lumped_mass_case
    r = lever[(lever["block"] == block) & (lever["pfa_ratio"] == pfa_ratio)].iloc[0]
    case = f"lumped_mass/printed_lever/{block}/PFA {pfa_ratio:g} g tan(alpha)"
    assert bool(r["printed_rocked"]) == (pfa_ratio > 0.75), (
        f"{case}: printed lever rocked = {r['printed_rocked']}, expected {pfa_ratio > 0.75} (uplift at 0.75 g tan(alpha))")
    assert not bool(r["lumped_rocked"]), f"{case}: the lumped-mass form rocked below g tan(alpha)"


def test_unknown_case_is_refused():
    with pytest.raises(ValueError, match="case must be one of"):
        run_case("nonsense")


def test_cli_validate_one_quick_case(tmp_path, capsys):
    from opsrock.cli import main

    assert main(["validate", "--case", "lumped_mass", "--quick", "--out", str(tmp_path)]) == 0
    assert "lumped_mass: passed" in capsys.readouterr().out


# Behind slow to keep make test under 10 minutes: CI's `make test-wheel` runs every case's quick form through
# `opsrock validate --quick`, which fails unless each case passes its targets.
@pytest.mark.slow
def test_sdof_records_quick(tmp_path):
    # Validation case 9, quick form: 3 broadband records (seed 1, the three blocks at 1.3 g tan alpha).
    # On these the two SDOF implementations are well-conditioned (theta_max moves by < 1e-4 alpha under
    # amplitude changes of 1e-6 and 1e-5 and under tightened numerics) and agree: measured
    # |sdof - opensees| <= 2e-4 alpha, so the case's own 0.01 alpha criterion passes with a wide margin.
    from opsrock.validation import sdof_records

    m = run_case("sdof_records", tmp_path, quick=True)
    assert m["passed"] and m["n_cases"] == 3 and m["n_ill_conditioned"] == 0 and m["n_rigid_sensitive"] == 0
    assert m["verdict_agreement"] == 1.0 and m["within_1pct_alpha"] == 1.0
    df = pd.read_csv(tmp_path / "cases_quick.csv")
    assert len(df) == 3 and (df["sdof_theta"] - df["opensees_theta"]).abs().max() < 0.01
    # a re-run keeps the stored rows and computes nothing (workers=0 would fail if it made a pool)
    path = tmp_path / "cases_quick.csv"
    assert len(sdof_records.compute(path, sdof_records.cases(quick=True), workers=0)) == 3
    # a line cut short by an interruption is dropped (and would be recomputed)
    text = path.read_text()
    path.write_text(text + "1,0.5,1.15,1.3,0.0")
    assert len(sdof_records._load(path)) == 3
    path.write_text(text[: text.rstrip("\n").rfind("\n") + 1] + "1,0.5,1.15,1.3,0.0")
    assert len(sdof_records._load(path)) == 2


# Behind slow to keep make test under 10 minutes: CI's `make test-wheel` runs every case's quick form through
# `opsrock validate --quick`, which fails unless each case passes its targets.
@pytest.mark.slow
def test_friction_quick(tmp_path):
    # Validation case 11, quick form: every closed form and limit check, the mode-initiation diagram on a
    # coarse grid, and 35 cases of the two implementations (26 pulses, 8 noise-record cases). Measured: all
    # well-conditioned, responses equal, max |d theta_max| 1.5e-3 alpha and 2e-5 m of slide against the
    # targets 5e-3 alpha and 1 mm.
    m = run_case("friction", tmp_path, quick=True)
    assert m["passed"] and m["n_failed_checks"] == 0 and m["diagram_agreement"] == 1.0
    assert m["agreement_n_cases"] == 35 and m["agreement_response_agreement"] >= 0.99
    assert m["agreement_max_d_theta_over_alpha"] <= 0.005 and m["agreement_max_d_slide_m"] <= 0.001
    for name in ("checks.csv", "diagram.csv", "agreement.csv", "summary.csv", "diagram.png", "agreement.png"):
        assert (tmp_path / name).is_file()
