"""Fragility from record campaigns: MLE by level with intervals by record, logistic regression,
resurrection counting, sufficiency, the pulse robustness study, and the FEMA P-58 / pelicun export.

References: synthetic outcomes drawn (seeded) from a known lognormal or logistic fragility (the
truth the fits must recover, with tolerances of several standard errors), hand-built IDA curves,
Wilson's interval formula (Wilson 1927) and pelicun's own loader (optional extra).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import special, stats

from opsrock.analysis.robustness import draw_block_sets, ranking_robustness
from opsrock.errors import AllCasesFailedError
from opsrock.fragility import fit_lognormal_mle
from opsrock.fragility.ida import outcomes, resurrection_summary, resurrections
from opsrock.fragility.logistic import fit_logistic
from opsrock.fragility.pelicun_export import ComponentFragility, read_pelicun_csv, write_pelicun_csv
from opsrock.fragility.record_study import RecordStudySettings, record_fragility
from opsrock.fragility.sufficiency import sufficiency
from opsrock.stats import wilson_interval
from _support import run_opsrock



def synthetic_ida(n_records=40, levels=(1.25, 1.5, 2, 2.5, 3, 3.5, 4, 5, 6, 8), mu=3.0, beta=0.4, seed=1):
    """A record-campaign table whose outcomes follow P = Phi(ln(level/mu)/beta), one curve per record."""
    rng = np.random.default_rng(seed)
    rows = []
    for r in range(n_records):
        for k, lv in enumerate(levels, start=1):
            over = bool(rng.random() < stats.norm.cdf(math.log(lv / mu) / beta))
            rows.append({"block": "b", "record": f"r{r:02d}", "floor": "ground", "level": k, "level_value": lv,
                         "status": "ok", "overturned": over, "rocked": True, "theta_max_over_alpha": 8.0 if over else 0.5,
                         "pfa": lv * 2.0, "pfv": lv * 0.2, "magnitude": 6.0 + 0.02 * r, "distance_km": 10.0 + r,
                         "building_period": np.nan, **{f"IM{i}": lv * (1 + 0.1 * i) for i in range(1, 10)}})
    return pd.DataFrame(rows)


def test_binomial_mle_recovers_the_generating_fragility():
    cases = synthetic_ida(n_records=100)  # 1,000 cases
    y = cases["overturned"].to_numpy(bool)
    fit = fit_lognormal_mle(cases["level_value"].to_numpy(float), y, n_boot=100, groups=cases["record"].to_numpy())
    # standard errors at this size (Fisher information): about 3 % on mu and 0.04 on beta; 3-4 of them
    assert fit.mu == pytest.approx(3.0, rel=0.1)
    assert fit.beta == pytest.approx(0.4, abs=0.15)
    assert fit.mu_lo < fit.mu < fit.mu_hi and fit.beta_lo < fit.beta < fit.beta_hi


def test_bootstrap_by_record_is_wider_when_a_records_cases_move_together():
    # every record has a latent capacity: its cases are strongly dependent, so resampling records
    # (the right unit) must give a wider interval than resampling single cases
    rng = np.random.default_rng(3)
    levels = np.geomspace(1, 9, 10)
    cap = np.exp(rng.normal(math.log(3.0), 0.5, 30))
    x = np.tile(levels, 30)
    g = np.repeat(np.arange(30), 10)
    y = x >= np.repeat(cap, 10)
    by_case = fit_lognormal_mle(x, y, n_boot=200, seed=0)
    by_record = fit_lognormal_mle(x, y, n_boot=200, seed=0, groups=g)
    assert by_record.mu == by_case.mu  # the point estimate does not depend on the resampling
    assert (by_record.mu_hi - by_record.mu_lo) > 1.3 * (by_case.mu_hi - by_case.mu_lo)


def test_logistic_regression_recovers_its_generating_curve():
    rng = np.random.default_rng(5)
    x = np.exp(rng.uniform(math.log(0.5), math.log(20), 4000))
    y = rng.random(x.size) < special.expit(np.log(x / 4.0) / 0.3)
    fit = fit_logistic(x, y)
    assert fit.success and fit.mu == pytest.approx(4.0, rel=0.05) and fit.scale == pytest.approx(0.3, rel=0.1)
    assert fit.beta_equivalent == pytest.approx(math.pi * fit.scale / math.sqrt(3), rel=1e-12)
    assert not fit_logistic(np.array([1.0, 2.0, 3.0, 4.0]), np.array([False, False, True, True])).success


def test_resurrections_are_counted_per_curve():
    rows = []
    for rec, verdicts in (("A", [0, 1, 0, 1]), ("B", [0, 0, 0, 0]), ("C", [1, 1, 1, 1]), ("D", [0, 1, 0, 0])):
        for k, v in enumerate(verdicts, start=1):
            rows.append({"block": "b", "record": rec, "floor": "ground", "level": k, "level_value": float(k),
                         "status": "ok", "overturned": bool(v), "rocked": True})
    rows.append({"block": "b", "record": "E", "floor": "ground", "level": 1, "level_value": 1.0,
                 "status": "failed", "overturned": False, "rocked": False})
    cases = pd.DataFrame(rows)
    table = resurrections(cases).set_index("record")
    assert table.loc["A", "first_overturned_level"] == 2 and table.loc["A", "n_resurrected"] == 1
    assert table.loc["B", "first_overturned_level"] == 0 and not table.loc["B", "resurrected"]
    assert table.loc["C", "n_resurrected"] == 0 and table.loc["D", "n_resurrected"] == 2
    s = resurrection_summary(table.reset_index())
    assert (s["n_curves"], s["n_curves_overturning"], s["n_curves_resurrected"], s["n_resurrected_cases"]) == (4, 3, 2, 3)
    mono = outcomes(cases, "first_exceedance")
    assert list(mono[cases["record"] == "A"]) == [False, True, True, True]  # failed case E is left out
    assert len(mono) == 16
    with pytest.raises(ValueError, match="convention"):
        outcomes(cases, "monotone")


def test_sufficiency_detects_a_covariate_and_not_a_random_one():
    rng = np.random.default_rng(0)
    n = 2000
    x = np.exp(rng.normal(0, 0.5, n))
    c = rng.normal(size=n)
    g = np.repeat(np.arange(200), 10)
    y_none = rng.random(n) < stats.norm.cdf(np.log(x) / 0.4)
    y_dep = rng.random(n) < stats.norm.cdf(np.log(x) / 0.4 + 0.5 * c)
    assert sufficiency(x, y_none, c, "c", groups=g).p_value > 0.05
    dep = sufficiency(x, y_dep, c, "c", groups=g)
    assert dep.p_value < 1e-10 and dep.coefficient == pytest.approx(0.5, abs=0.15)
    assert math.isnan(sufficiency(x[:5], y_dep[:5], c[:5], "c").p_value)


def test_record_study_on_a_synthetic_campaign():
    study = record_fragility(synthetic_ida(), RecordStudySettings(n_boot=20), n_rank_boot=10)
    ims = study.ims.set_index("im")
    # IMk = (1 + 0.1 k) level: the same fragility, scaled: beta equal, median scaled (IM1 decreases
    # with the intensity by definition, so this synthetic IM1 has no finite fit)
    assert ims.loc["IM4", "beta"] == pytest.approx(ims.loc["IM3", "beta"], rel=1e-6)
    assert ims.loc["IM4", "mu"] == pytest.approx(ims.loc["IM3", "mu"] * 1.4 / 1.3, rel=1e-6)
    assert set(study.measure_fits["outcome"]) == {"as_simulated", "first_exceedance"}
    assert study.frequencies["n_resamples"].iloc[0] == 10
    assert set(study.blocks["demand"]) == {"pfa", "pfv"}
    assert set(study.sufficiency["covariate"]) == {"magnitude", "distance_km"}  # the period does not vary


def test_a_block_whose_every_case_failed_is_skipped_with_its_reason_and_all_failed_is_refused():
    good = synthetic_ida(n_records=10)
    failed = good.assign(block="needle", status="failed", overturned=False, rocked=False,
                         reason="scale factor 0.003 to reach pfa_ratio = 1.5 is outside [0.01, 100]")
    study = record_fragility(pd.concat([good, failed], ignore_index=True), RecordStudySettings(n_boot=5),
                             n_rank_boot=5)
    needle = study.blocks[study.blocks["block"] == "needle"]
    assert list(needle["demand"]) == ["pfa", "pfv"] and not needle["success"].any()
    assert needle["message"].iloc[0] == ("every case failed (100 cases; first reason: scale factor 0.003 to reach "
                                         "pfa_ratio = 1.5 is outside [0.01, 100]): no fit")
    assert study.blocks[study.blocks["block"] == "b"]["success"].all() and study.n_failed == 100
    with pytest.raises(AllCasesFailedError, match=r"^every case of the cases failed \(100 cases; first reason: scale"):
        record_fragility(failed, RecordStudySettings(n_boot=5))


def test_wilson_interval():
    # Wilson (1927): k = 0 of 10 -> (0, 0.2775); 5 of 10 -> (0.2366, 0.7634) at 95 %
    lo, hi = wilson_interval(0, 10)
    assert lo == 0.0 and hi == pytest.approx(0.27754, abs=1e-4)
    assert wilson_interval(10, 10)[1] == 1.0
    lo, hi = wilson_interval(5, 10)
    assert lo == pytest.approx(0.23659, abs=1e-4) and hi == pytest.approx(0.76341, abs=1e-4)


def test_robustness_study_is_seeded_and_independent_of_workers():
    sets = draw_block_sets(3, seed=7)
    assert all(0.15 <= b.alpha <= 0.45 and 0.5 <= b.R <= 1.5 for s in sets for b in s)
    a = ranking_robustness(3, seed=7, workers=1)
    b = ranking_robustness(3, seed=7, workers=2)
    assert a.winners.equals(b.winners)
    assert a.shares[["wins_HR", "wins_cv_percent", "wins_beta"]].sum().tolist() == [3, 3, 3]


def test_pelicun_csv_round_trip(tmp_path):
    comps = [ComponentFragility("opsrock.b.PFA", "pfa", 6.055398004958769, 0.6505432263063391),
             ComponentFragility("opsrock.b.PFV", "pfv", 0.6115985322309946, 0.36682703654629484)]
    path = write_pelicun_csv(comps, tmp_path / "f.csv")
    assert read_pelicun_csv(path) == comps  # full precision
    header = path.read_text().splitlines()[0]
    assert header == "ID,Incomplete,Demand-Type,Demand-Unit,Demand-Offset,Demand-Directional,LS1-Family,LS1-Theta_0,LS1-Theta_1"
    with pytest.raises(ValueError, match="median"):
        ComponentFragility("x", "pfa", -1.0, 0.5)
    with pytest.raises(ValueError, match="demand"):
        ComponentFragility("x", "pgd", 1.0, 0.5)


def test_pelicun_loads_the_export(tmp_path):
    pytest.importorskip("pelicun", reason="pelicun 3.10 pins scipy < 1.16 and pandas < 3, so it is not in opsrock's "
                        "venv; `make test-pelicun` checks the export in a venv of its own")
    from pelicun.assessment import Assessment

    comps = [ComponentFragility("opsrock.b.PFA", "pfa", 6.0554, 0.65), ComponentFragility("opsrock.b.PFV", "pfv", 0.61, 0.37)]
    path = write_pelicun_csv(comps, tmp_path / "f.csv")
    asmnt = Assessment({"PrintLog": False, "Verbose": False})
    asmnt.damage.load_model_parameters([str(path)], {c.component_id for c in comps})
    params = asmnt.damage.ds_model.damage_params
    for c in comps:
        assert params.loc[c.component_id, ("LS1", "Theta_0")] == pytest.approx(c.median, rel=1e-12)
        assert params.loc[c.component_id, ("LS1", "Theta_1")] == pytest.approx(c.beta, rel=1e-12)


def _cli(*args, cwd=None):
    return run_opsrock(args, cwd, timeout=600)


def test_cli_fragility_report(tmp_path):
    synthetic_ida().to_csv(tmp_path / "cases.csv", index=False)
    p = _cli("fragility", str(tmp_path), "--out", str(tmp_path / "rep"), "--n-boot", "10")
    assert p.returncode == 0, p.stderr
    for name in ("report.md", "ims.csv", "resurrections.csv", "fragility_pelicun.csv", "figures/ida_curves.png",
                 "figures/fragility_b.png", "figures/im_ranking.png"):
        assert (tmp_path / "rep" / name).stat().st_size > 100, name
    assert not (tmp_path / "rep" / "figures" / "fragility.png").exists()  # no curve pooling blocks and floors
    report = (tmp_path / "rep" / "report.md").read_text()
    assert "## Conclusion" in report and "Resurrection" in report
    assert report.index("## Per block and floor") < report.index("## Conclusion")
    # one pelicun component per block, floor and demand, the floor in its ID
    assert [c.component_id for c in read_pelicun_csv(tmp_path / "rep" / "fragility_pelicun.csv")] == [
        "opsrock.b.ground.PFA", "opsrock.b.ground.PFV"]


@pytest.mark.parametrize("make,needle", [
    (lambda d: None, "no cases.csv"),
    (lambda d: pd.DataFrame({"case_id": ["a"], "status": ["ok"]}).to_csv(d / "cases.csv", index=False), "not from a record scene"),
])
def test_cli_fragility_bad_input_exits_2(tmp_path, make, needle):
    make(tmp_path)
    p = _cli("fragility", str(tmp_path), "--out", str(tmp_path / "rep"))
    assert p.returncode == 2 and len(p.stderr.splitlines()) == 1 and "Traceback" not in p.stderr
    assert needle in p.stderr
    assert not (tmp_path / "rep").exists()
