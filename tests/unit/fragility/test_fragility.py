"""Fragility layer (paper Section 4, Eq. 12-16) on hand-built and synthetic case tables."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from _synthetic_cases import case_row, grid_cases
from scipy import special

from opsrock import Block, OneSinePulse
from opsrock.fragility import (
    FALLBACK_STRIPS,
    TABLE2_COLUMNS,
    FragilitySettings,
    analyse_fragility,
    best_ims,
    fit_lognormal_least_squares,
    fit_lognormal_mle,
    fragility_probability,
    hybrid_strip,
    rank_ims,
    split_cases,
    strip_fractions,
    table2,
    table2_markdown,
    table3,
    table3_markdown,
)
from opsrock.published.liu_huang_liu_2023 import TABLE2

# --- case selection ------------------------------------------------------------------------
def test_no_uplift_and_failed_cases_are_counted_not_used():
    base = grid_cases()
    block = Block(0.4, 1.6, name="B1")
    # 7 pulses below the uplift threshold and 3 failed runs, all at IM values far outside
    # the grid: if they entered the statistics they would change R_S / R_O.
    extra = [case_row(block, OneSinePulse.from_ratios(block, 0.5, 0.05), "no_uplift")] * 7
    extra += [case_row(block, OneSinePulse.from_ratios(block, 50.0, 40.0), "failed")] * 3
    cases = pd.concat([base, pd.DataFrame(extra)], ignore_index=True)
    split = split_cases(cases)
    # counts from the construction: 100 rocking (32 overturned: 8+6+4+3+1 in IM1 = 2..6 plus
    # all 10 at IM1 = 0.5), 7 no-uplift, 3 failed
    assert split.counts() == {"n_total": 110, "n_rocking": 100, "n_safe": 68,
                              "n_overturned": 32, "n_no_uplift": 7, "n_failed": 3}
    pd.testing.assert_frame_equal(table2(cases), table2(base))
    t3 = table3(cases, FragilitySettings(ims=("IM1",), n_boot=0))
    assert set(t3["n_failed"]) == {3} and set(t3["n_no_uplift"]) == {7}


def test_inconsistent_verdicts_are_refused():
    cases = grid_cases()
    bad = cases.copy()
    bad.loc[5, "verdict"] = "safe" if bad.loc[5, "verdict"] == "overturned" else "overturned"
    with pytest.raises(ValueError, match="row 5"):
        split_cases(bad)
    bad = cases.drop(columns="verdict")
    bad.loc[0, "rocked"] = False  # row 0 (IM1 = 0.5, IM2 = 1.5) is overturned
    with pytest.raises(ValueError, match="overturned but not rocked"):
        split_cases(bad)
    with pytest.raises(KeyError, match="status"):
        split_cases(cases.drop(columns="status"))


def test_booleans_read_back_from_csv_text(tmp_path):
    cases = grid_cases()
    path = tmp_path / "cases.csv"
    cases.astype({"rocked": str, "overturned": str}).to_csv(path, index=False)
    split = split_cases(pd.read_csv(path, dtype={"rocked": str, "overturned": str}))
    assert (split.n_rocking, split.n_overturned) == (100, 32)


# --- hybrid strip --------------------------------------------------------------------------
def test_hybrid_strip_by_hand_increasing():
    # safe at 1, 2, 3, 4; overturned at 3, 5, 9: overlap [3, 4], W_HS = 1, R_S = 3, R_O = 6,
    # HR = sqrt((1/3)² + (1/6)²) = 0.372678 (Eq. 12 by hand), W_SAS = 1/5.
    x = np.array([1, 2, 3, 4, 3, 5, 9.0])
    y = np.array([0, 0, 0, 0, 1, 1, 1], dtype=bool)
    h = hybrid_strip(x, y, "IMx")
    assert (h.W_HS, h.R_S, h.R_O) == (1.0, 3.0, 6.0)
    assert (h.overlap_low, h.overlap_high) == (3.0, 4.0)
    assert h.HR == pytest.approx(math.sqrt(1 / 9 + 1 / 36), rel=1e-14)
    assert h.W_SAS == pytest.approx(0.2)
    assert h.n_in_strip == 3  # 3 (safe), 4 (safe), 3 (overturned)


def test_hybrid_strip_by_hand_decreasing_like_im1():
    # IM1-like: overturned at LOW values (0.5 .. 6), safe at 2 .. 10. The intersection is
    # [2, 6]: W_HS 4.00, R_S 8.00, R_O 5.50, the paper's Table 2 IM1 row.
    x = np.array([0.5, 1.0, 6.0, 2.0, 7.0, 10.0])
    y = np.array([1, 1, 1, 0, 0, 0], dtype=bool)
    h = hybrid_strip(x, y, "IM1", decreasing=True)
    assert (h.W_HS, h.R_S, h.R_O) == (4.0, 8.0, 5.5)
    assert (h.overlap_low, h.overlap_high) == (2.0, 6.0)


def test_hybrid_strip_without_overlap():
    # safe at 1, 2; overturned at 3, 4: perfectly separated, W_HS = 0 so both ratios, HR and
    # W_SAS are 0 and the edges are undefined.
    x = np.array([1.0, 2.0, 3.0, 4.0])
    y = np.array([0, 0, 1, 1], dtype=bool)
    h = hybrid_strip(x, y, "IMx")
    assert (h.W_HS, h.ratio_S, h.ratio_O, h.HR, h.W_SAS) == (0.0, 0.0, 0.0, 0.0, 0.0)
    assert math.isnan(h.overlap_low) and "no overlap" in h.note
    # strips fall back to FALLBACK_STRIPS over the range [1, 4], flagged
    st = strip_fractions(x, y, h)
    assert st.fallback and st.width == pytest.approx(3.0 / FALLBACK_STRIPS)
    assert st.n_cases.sum() == 4
    # the MLE has no finite optimum; it says so and puts mu mid-gap: sqrt(2 * 3)
    m = fit_lognormal_mle(x, y, n_boot=0)
    assert not m.success and "separated" in m.message
    assert m.mu == pytest.approx(math.sqrt(6.0)) and m.beta == 0.0


def test_hybrid_strip_with_one_state_missing():
    h = hybrid_strip(np.array([1.0, 2.0]), np.array([False, False]), "IMx")
    assert math.isnan(h.HR) and "no overturned" in h.note


# --- Table 2 on the synthetic grid -----------------------------------------------------------
@pytest.mark.parametrize("im", ["IM1", "IM2"])
def test_table2_rows_of_the_paper_from_a_synthetic_grid(im):
    # Reference: paper Table 2, rows IM1 and IM2 (2-decimal print, hence abs=0.005).
    t2 = table2(grid_cases()).set_index("im")
    assert list(t2.reset_index().columns) == list(TABLE2_COLUMNS)
    paper = TABLE2[im]
    for col in TABLE2_COLUMNS[1:]:
        assert t2.loc[im, col] == pytest.approx(getattr(paper, col), abs=0.005), col


# --- strips -----------------------------------------------------------------------------------
def test_strip_fractions_on_the_grid():
    cases = grid_cases()
    split = split_cases(cases)
    an = analyse_fragility(cases, FragilitySettings(ims=("IM1",), n_boot=0, extent="hybrid"))
    st = an["IM1"].strips[1.0]
    # W_SAS = 0.8 over [2, 6]: 5 strips, one IM1 column of 10 cases each. Overturned count
    # per column from the boundary IM2 > 1.7 IM1 on IM2 = 1.5 + k 9.5/9: IM1 = 2 -> 8,
    # 3 -> 6, 4 -> 4 (6.78 < 6.8), 5 -> 3, 6 -> 1.
    np.testing.assert_allclose(st.low, [2.0, 2.8, 3.6, 4.4, 5.2], atol=1e-12)
    np.testing.assert_array_equal(st.n_cases, [10] * 5)
    np.testing.assert_array_equal(st.n_overturned, [8, 6, 4, 3, 1])
    assert st.n_cases.sum() == an["IM1"].hybrid.n_in_strip == 50
    assert split.n_rocking == 100
    # 2 W_SAS: 4.0 / 1.6 = 2.5 strips -> 3, the last one full width past the strip top
    st2 = an["IM1"].strips[2.0]
    assert st2.n_strips == 3 and st2.high[-1] == pytest.approx(6.8)
    np.testing.assert_array_equal(st2.n_cases, [20, 20, 10])
    # "range" extent adds the certain cases: IM1 = 0.5 (all overturned) and 7..10 (all safe)
    ar = analyse_fragility(cases, FragilitySettings(ims=("IM1",), n_boot=0, extent="range"))
    sr = ar["IM1"].strips[1.0]
    assert sr.n_cases.sum() == 100
    assert sr.fraction[sr.centre < 2.0].tolist() == [1.0]
    assert set(sr.fraction[sr.centre > 6.0]) == {0.0}


def test_case_on_an_inner_edge_goes_to_the_upper_strip():
    # hybrid strip [0, 5] from safe {0, 5} and overturned {0, 5}; W_SAS = 1. A case at 2.0
    # (an edge, reached as 0 + 2 * 1.0) belongs to [2, 3), the top case 5.0 to the last strip.
    x = np.array([0.0, 5.0, 0.0, 5.0, 2.0]) + 1.0
    y = np.array([0, 0, 1, 1, 1], dtype=bool)
    h = hybrid_strip(x, y)
    st = strip_fractions(x, y, h, extent="hybrid")
    np.testing.assert_allclose(st.low, [1.0, 3.0, 5.0])
    np.testing.assert_array_equal(st.n_cases, [2, 1, 2])


# --- fits ---------------------------------------------------------------------------------------
def test_fragility_orientation():
    x = np.array([1.0, 2.0, 4.0])
    inc = fragility_probability(x, 2.0, 0.3)
    dec = fragility_probability(x, 2.0, 0.3, decreasing=True)
    assert inc[1] == dec[1] == 0.5
    assert inc[0] < 0.5 < inc[2] and dec[0] > 0.5 > dec[2]
    np.testing.assert_allclose(inc + dec, 1.0, rtol=1e-15)  # mirror images


@pytest.mark.parametrize("decreasing", [False, True])
def test_least_squares_recovers_exact_lognormal_fractions(decreasing):
    # Noise-free fractions Phi(+-ln(x/mu)/beta) at 8 strip centres: Eq. 16 has the exact
    # minimum error 0 there, so the fit must return the generating values to optimiser
    # tolerance (1e-6 relative).
    mu, beta = 4.77, 0.32  # the paper's IM1 values (Table 3)
    x = mu * np.exp(np.linspace(-2, 2, 8) * beta)
    f = fragility_probability(x, mu, beta, decreasing)
    fit = fit_lognormal_least_squares(x, f, decreasing)
    assert fit.success
    assert fit.mu == pytest.approx(mu, rel=1e-6) and fit.beta == pytest.approx(beta, rel=1e-6)
    assert fit.cv_percent == pytest.approx(100 * beta / mu, rel=1e-6)


def _synthetic_outcomes(n, mu, beta, seed, decreasing=False):
    rng = np.random.default_rng(seed)
    x = mu * np.exp(rng.uniform(-3 * beta, 3 * beta, n))
    y = rng.random(n) < fragility_probability(x, mu, beta, decreasing)
    return x, y


def _probit_standard_errors(x, mu, beta, decreasing=False):
    """Asymptotic standard errors of (mu, beta) of the MLE, from the Fisher information of
    the Bernoulli likelihood at the true values: I = sum phi(z)² / (P (1-P)) g g^T with
    g = dz/d(ln mu, beta) = (-s/beta, -z/beta); delta method to mu."""
    s = -1.0 if decreasing else 1.0
    z = s * np.log(x / mu) / beta
    p = special.ndtr(z)
    w = np.exp(-z**2) / (2 * math.pi) / (p * (1 - p))
    g = np.stack([-s / beta * np.ones_like(z), -z / beta])
    cov = np.linalg.inv((g * w) @ g.T)
    return mu * math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1])


@pytest.mark.parametrize("decreasing", [False, True])
def test_mle_recovers_a_known_fragility_within_four_standard_errors(decreasing):
    # 1000 outcomes drawn (seeded) from P = Phi(+-ln(x/mu)/beta): the MLE is asymptotically
    # normal with the Fisher-information standard errors computed above; 4 SE leaves a
    # 6e-5 chance of a false failure per parameter. The percentile-bootstrap 95 % interval
    # must contain the truth and have a half-width within a factor 2 of 1.96 SE.
    mu, beta = 13.15, 0.15  # the paper's IM9 values (Table 3)
    x, y = _synthetic_outcomes(1000, mu, beta, seed=11, decreasing=decreasing)
    se_mu, se_beta = _probit_standard_errors(x, mu, beta, decreasing)
    m = fit_lognormal_mle(x, y, decreasing, n_boot=100, seed=3)
    assert m.success
    assert abs(m.mu - mu) < 4 * se_mu and abs(m.beta - beta) < 4 * se_beta
    assert m.mu_lo < mu < m.mu_hi and m.beta_lo < beta < m.beta_hi
    assert 0.5 < (m.mu_hi - m.mu_lo) / 2 / (1.96 * se_mu) < 2.0
    assert 0.5 < (m.beta_hi - m.beta_lo) / 2 / (1.96 * se_beta) < 2.0
    assert m.n_boot_used == 100
    # seeded: the same seed gives the same interval
    again = fit_lognormal_mle(x, y, decreasing, n_boot=100, seed=3)
    assert (again.mu_lo, again.beta_hi) == (m.mu_lo, m.beta_hi)


def test_least_squares_on_strip_fractions_recovers_a_known_fragility():
    # 3000 seeded outcomes from mu = 1.27, beta = 0.14 (the paper's IM4 values), strips of
    # width 0.1 beta mu over the whole range. Error budget: (a) binning: the fit to the exact
    # expected strip fractions (mean of P over each strip's cases) differs from the truth by
    # a deterministic amount, computed here; (b) sampling: the sandwich covariance of
    # nonlinear least squares with binomial strip noise, var_i = P_i (1 - P_i) / n_i, at the
    # truth. Tolerance = |binning bias| + 4 sampling SE.
    mu, beta = 1.27, 0.14
    x, y = _synthetic_outcomes(3000, mu, beta, seed=5)
    width = 0.1 * beta * mu
    edges = np.arange(x.min(), x.max() + width, width)
    k = np.digitize(x, edges) - 1
    idx = np.unique(k)
    centre = edges[idx] + width / 2
    n = np.array([np.sum(k == i) for i in idx])
    frac = np.array([y[k == i].mean() for i in idx])
    expected = np.array([fragility_probability(x[k == i], mu, beta).mean() for i in idx])
    fit = fit_lognormal_least_squares(centre, frac)
    exact = fit_lognormal_least_squares(centre, expected)
    z = np.log(centre / mu) / beta
    phi = np.exp(-0.5 * z**2) / math.sqrt(2 * math.pi)
    jac = np.stack([-phi / beta, -phi * z / beta], axis=1)  # d P / d(ln mu, beta)
    p = special.ndtr(z)
    bread = np.linalg.inv(jac.T @ jac)
    cov = bread @ (jac.T * (p * (1 - p) / n)) @ jac @ bread
    se_mu, se_beta = mu * math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1])
    assert fit.success
    assert abs(fit.mu - mu) < abs(exact.mu - mu) + 4 * se_mu
    assert abs(fit.beta - beta) < abs(exact.beta - beta) + 4 * se_beta


def test_least_squares_refuses_degenerate_data():
    assert not fit_lognormal_least_squares([1.0], [0.5]).success
    assert not fit_lognormal_least_squares([1.0, 2.0], [0.0, 0.0]).success
    step = fit_lognormal_least_squares([1.0, 2.0, 3.0, 4.0], [0.0, 0.0, 1.0, 1.0])
    assert not step.success and "step" in step.message
    with pytest.raises(ValueError, match="fraction"):
        fit_lognormal_least_squares([1.0, 2.0], [0.5, 1.5])


# --- whole analysis, tables and ranking ----------------------------------------------------------
def test_tables_rank_and_markdown_on_the_grid():
    cases = grid_cases()
    an = analyse_fragility(cases, FragilitySettings(n_boot=20))
    t3 = table3(an)
    for col in ("im", "strip_factor", "mu", "beta", "cv_percent", "mle_mu", "mle_beta",
                "mle_mu_lo", "mle_mu_hi", "mle_beta_lo", "mle_beta_hi", "n_rocking", "n_failed"):
        assert col in t3.columns
    assert len(t3) == 27 and set(t3["strip_factor"]) == {0.5, 1.0, 2.0}
    # CV is the paper's beta / mu in percent
    np.testing.assert_allclose(t3["cv_percent"], 100 * t3["beta"] / t3["mu"], rtol=1e-12)
    # The boundary IM2 = 1.7 IM1 is a level set of IM3 = IM2/IM1 = 1.7 and of
    # IM8 = e_R^4 IM3 (one block): those two IMs separate the states perfectly (HR = 0).
    # Their fits are flagged, never reported as ordinary fits.
    t2 = table2(an).set_index("im")
    assert t2.loc["IM3", "HR"] == 0.0 and t2.loc["IM8", "HR"] == 0.0
    assert t2.loc["IM2", "HR"] == pytest.approx(math.sqrt(2.0))
    flagged = t3[t3["im"].isin(["IM3", "IM8"])]
    assert flagged["fallback"].all() and not flagged["ls_success"].any()
    assert not flagged["mle_success"].any()
    # the perfect IMs rank first by HR and by the share of cases in the hybrid strip
    ranking = rank_ims(an)
    perfect = set(t2.index[t2["HR"] == 0.0])  # IM6 ~ (IM2/IM1)^0.5 separates on this grid too
    assert {"IM3", "IM8"} <= perfect
    assert set(ranking.index[ranking["rank_HR"] == 1]) == perfect
    assert best_ims(ranking)["HR"] in perfect
    assert ranking.loc["IM3", "fraction_in_hybrid"] == 0.0
    # IM2's hybrid strip holds every rocking case: the worst possible share
    assert ranking.loc["IM2", "fraction_in_hybrid"] == 1.0
    # Markdown: ours beside the paper's value, per cell
    md2 = table2_markdown(table2(an))
    assert "| IM1 | 4.00 (4.00) | 8.00 (8.00) | 5.50 (5.50)" in md2
    md3 = table3_markdown(t3)
    assert "(4.77)" in md3 and "(13.15)" in md3 and "MLE mu [CI]" in md3


def test_settings_are_checked():
    with pytest.raises(ValueError, match="IM0"):
        FragilitySettings(ims=("IM0",))
    with pytest.raises(ValueError, match="extent"):
        FragilitySettings(extent="everywhere")
    with pytest.raises(ValueError, match="pfv_convention"):
        FragilitySettings(pfv_convention="rms")


def test_least_squares_beta_below_strip_resolution_is_flagged():
    # A single intermediate strip between all-safe and all-overturned strips: any beta with
    # 2 beta mu below one strip width fits it equally well, so beta is not identified (the
    # 400-case OpenSees run gave IM4 beta = 0.02 this way, ranking it 'best' by CV and beta).
    from opsrock.fragility import fit_lognormal_least_squares

    x = np.array([1.0, 1.2, 1.4, 1.6, 1.8, 2.0])
    f = np.array([0.0, 0.0, 0.5, 1.0, 1.0, 1.0])
    fit = fit_lognormal_least_squares(x, f)
    assert not fit.success and "resolution" in fit.message
    # a transition spread over several strips is resolved and trusted
    xs = np.linspace(0.5, 2.0, 16)
    fs = np.round(special.ndtr(np.log(xs / 1.2) / 0.3), 2)
    good = fit_lognormal_least_squares(xs, fs)
    assert good.success and good.beta == pytest.approx(0.3, rel=0.05)
