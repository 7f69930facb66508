"""The post-processing is fast and gives the same numbers as before it was made fast.

Two kinds of check, both machine-independent (no wall-clock timing):

* **Same numbers.** The two-parameter solvers (:mod:`opsrock.fragility.optimise`) at the optimum that
  ``scipy.optimize.minimize`` / ``least_squares`` reach, to their tolerances, never at a worse objective;
  the MLE with its record bootstrap against the textbook evaluation (scipy's BFGS, two ``log_ndtr`` per
  case, one resample after the other: the implementation before the speed-up, kept here as the
  reference), to 1e-8 relative; the ranking frequencies
  against the resampled tables; the robustness study's batched solve against the set-by-set tables;
  results independent of the number of worker processes.
* **Work done, counted.** Optimiser runs, logistic fits, solver calls and likelihood elements: a change
  that brings back the per-resample logistic fits, the per-set solves, a general-purpose optimiser or the
  per-case likelihood makes one of these fail.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from scipy import optimize, special, stats

from opsrock.analysis import robustness as rb
from opsrock.fragility import least_squares as ls
from opsrock.fragility import logistic, mle, optimise
from opsrock.fragility import record_study as rs
from opsrock.fragility.lognormal import BETA_BOUNDS


def _campaign(n_records=12, levels=(1.25, 1.5, 2, 2.5, 3, 4, 5, 6), blocks=("a", "b"), seed=4) -> pd.DataFrame:
    """A small record campaign: two blocks, two floors, outcomes from a lognormal fragility with record
    effects; IMs that vary case by case (a cloud), and the scene's measure on a few levels."""
    rng = np.random.default_rng(seed)
    rows = []
    for bi, block in enumerate(blocks):
        for r in range(n_records):
            capacity = 3.0 * math.exp(0.3 * rng.normal())
            for floor in ("f1", "roof"):
                amp = 1.0 if floor == "f1" else 1.4
                for k, lv in enumerate(levels, start=1):
                    ims = {f"IM{i}": lv * amp * math.exp(0.25 * rng.normal()) * (1 + 0.1 * i) for i in range(1, 10)}
                    ims["IM1"] = 1.0 / ims["IM1"]  # IM1 decreases as the motion gets stronger
                    over = bool(rng.random() < stats.norm.cdf(math.log(lv * amp / capacity) / 0.35))
                    rows.append({"block": block, "record": f"r{r:02d}", "floor": floor, "level": k, "level_value": lv,
                                 "status": "ok", "overturned": over, "rocked": over or rng.random() < 0.8,
                                 "theta_max_over_alpha": 8.0 if over else rng.uniform(0.05, 0.9),
                                 "pfa": lv * amp * (2.0 + bi), "pfv": lv * amp * 0.2 * math.exp(0.2 * rng.normal()),
                                 "magnitude": 6.0 + 0.05 * r, "distance_km": 10.0 + 3 * r, "building_period": 0.5,
                                 **ims})
    return pd.DataFrame(rows)


# --- the reference: the MLE and its bootstrap as they were before the speed-up ---------------------

def _reference_core(u, y, q0=None):
    centre, sd = float(np.mean(u)), float(np.std(u)) or 1.0
    v = (u - centre) / sd
    if q0 is not None:
        b0 = sd / math.exp(q0[1])
        start = np.array([-(q0[0] - centre) / sd * b0, b0])
    else:
        start = np.array([0.0, 1.0])

    def nll(ab):
        z = ab[0] + ab[1] * v
        lp, lq = special.log_ndtr(z), special.log_ndtr(-z)
        value = -float(np.sum(np.where(y, lp, lq)))
        log_phi = -0.5 * z**2 - 0.5 * math.log(2 * math.pi)
        dz = np.where(y, -np.exp(log_phi - lp), np.exp(log_phi - lq))
        return value, np.array([np.sum(dz), np.sum(dz * v)])

    res = optimize.minimize(nll, start, jac=True, method="BFGS", options={"gtol": 1e-8})
    a, b = res.x
    ok = bool(res.success) or res.status == 2
    if not b > 0:
        return None, float(res.fun), False
    beta = sd / b
    ok = ok and BETA_BOUNDS[0] < beta < BETA_BOUNDS[1]
    return np.array([centre - a * sd / b, math.log(beta)]), float(res.fun), ok


def _reference_fit(x, y, decreasing, n_boot, seed, groups):
    s = -1.0 if decreasing else 1.0
    u = s * np.log(x)
    q, value, ok = _reference_core(u, y)
    mu, beta = math.exp(s * q[0]), math.exp(q[1])
    members = [np.flatnonzero(groups == g) for g in dict.fromkeys(groups.tolist())]
    rng = np.random.default_rng(seed)
    draws = []
    for _ in range(n_boot):
        idx = np.concatenate([members[i] for i in rng.integers(0, len(members), len(members))])
        ub, yb = u[idx], y[idx]
        if yb.all() or (~yb).all() or ub[~yb].max() <= ub[yb].min():
            continue
        qb, _, okb = _reference_core(ub, yb, q if ok else None)
        if okb:
            draws.append((math.exp(s * qb[0]), math.exp(qb[1])))
    arr = np.array(draws)
    tail = 50.0 * (1.0 - 0.95)
    return (mu, beta, -value / x.size, *np.percentile(arr, tail, axis=0), *np.percentile(arr, 100.0 - tail, axis=0),
            len(draws))


@pytest.mark.parametrize("column", ["IM3", "IM1", "level_value", "pfa"])
def test_mle_with_record_bootstrap_equals_the_textbook_evaluation(column):
    cases = _campaign()
    x, y, g = cases[column].to_numpy(float), cases["overturned"].to_numpy(bool), cases["record"].to_numpy()
    fit = mle.fit_lognormal_mle(x, y, column == "IM1", 40, 0.95, 3, groups=g)
    ref = _reference_fit(x, y, column == "IM1", 40, 3, g)
    got = (fit.mu, fit.beta, fit.loglik_per_case, fit.mu_lo, fit.beta_lo, fit.mu_hi, fit.beta_hi, fit.n_boot_used)
    assert got[-1] == ref[-1]  # the same resamples fitted
    # the same draws and sums; the optimum to rounding where scipy's BFGS stops at its gradient tolerance
    assert got[:-1] == pytest.approx(ref[:-1], rel=1e-8, abs=0.0)


def test_mle_plan_in_chunks_equals_the_whole():
    cases = _campaign()
    x, y, g = cases["IM5"].to_numpy(float), cases["overturned"].to_numpy(bool), cases["record"].to_numpy()
    plan = mle.plan_mle(x, y, False, 30, 0.95, 0, groups=g)
    chunks = [d for lo in range(0, 30, 7) for d in mle.plan_mle(x, y, False, 30, 0.95, 0, groups=g).draws(lo, lo + 7)]
    assert repr(plan.finish(chunks)) == repr(mle.fit_lognormal_mle(x, y, False, 30, 0.95, 0, groups=g))


def test_group_members_equal_the_label_by_label_search():
    rng = np.random.default_rng(0)
    for labels in (rng.integers(0, 7, 200), np.array([f"r{k}" for k in rng.integers(0, 30, 500)], dtype=object),
                   np.array([2.5, 1.0, 2.5, 3.0])):
        fast = mle.group_members(labels, labels.shape)
        slow = [np.flatnonzero(labels == v) for v in dict.fromkeys(labels.tolist())]
        assert len(fast) == len(slow) and all(np.array_equal(a, b) for a, b in zip(fast, slow))


# --- the lean optimisers against scipy, bit for bit --------------------------------------------------

def _probit_problems(n_problems=60, seed=5):
    rng = np.random.default_rng(seed)
    for _ in range(n_problems):
        n = int(rng.integers(8, 400))
        v = rng.normal(size=n)
        slope = rng.choice([0.3, 2.0, 8.0, 40.0])  # up to nearly separated outcomes (precision loss)
        y = rng.random(n) < special.ndtr(rng.normal() + slope * v)
        if y.all() or (~y).all():
            continue
        yield v, y, np.array([rng.normal(), rng.uniform(0.2, 3)]) if rng.random() < 0.5 else np.array([0.0, 1.0])


def test_newton_reaches_scipys_bfgs_optimum():
    statuses = set()
    for v, y, start in _probit_problems():
        if mle._separated(v, y):
            continue  # no finite optimum: the fits never get here
        f = mle._ProbitNLL(v, y)
        ref = optimize.minimize(lambda ab: f(ab)[:2], start, jac=True, method="BFGS", options={"gtol": 1e-8})
        got = optimise.newton(f, start)
        assert got.fun <= ref.fun + 1e-12 * abs(ref.fun)  # never a worse optimum
        assert got.x == pytest.approx(ref.x, rel=1e-5, abs=1e-7)  # scipy stops within its gradient tolerance
        assert np.abs(f(got.x)[1]).max() <= 1e-8 * max(1.0, got.fun)  # at the optimum to rounding
        assert got.nfev < 40
        statuses.add(got.status)
    assert statuses == {0}


def test_probit_hessian_is_the_derivative_of_the_gradient():
    rng = np.random.default_rng(7)
    v, y = rng.normal(size=50), rng.random(50) < 0.4
    f = mle._ProbitNLL(v, y)
    ab, h = np.array([0.3, 1.7]), 1e-6
    numeric = np.array([(f(ab + h * e)[1] - f(ab - h * e)[1]) / (2 * h) for e in np.eye(2)])
    assert f(ab)[2] == pytest.approx(numeric, rel=1e-6)


def test_likelihood_on_distinct_cases_equals_the_per_case_sum():
    rng = np.random.default_rng(2)
    x = np.repeat(np.exp(rng.normal(size=30)), rng.integers(1, 6, 30))
    u = np.log(x)
    y = rng.random(u.size) < 0.5
    idx = rng.integers(0, u.size, u.size)
    ub, yb = u[idx], y[idx]
    t = mle.DistinctCases(x, y, u).table(idx)
    assert t.u.size < ub.size and np.array_equal(t.u[t.inverse], ub) and np.array_equal(t.y[t.inverse], yb)
    assert np.array_equal(x[t.base][t.inverse], x[idx])
    full, table = mle._ProbitNLL(ub, yb), mle._ProbitNLL(t.u, t.y, t.inverse)
    for ab in (np.array([0.2, 1.3]), np.array([-1.0, 7.0])):
        (f1, g1, h1), (f2, g2, h2) = full(ab), table(ab)
        assert f1 == f2 and g1.tobytes() == g2.tobytes() and h1.tobytes() == h2.tobytes()


def _strip_problems(n_problems=60, seed=3):
    rng = np.random.default_rng(seed)
    for _ in range(n_problems):
        m, s = int(rng.integers(3, 30)), rng.choice([-1.0, 1.0])
        lx = np.sort(rng.normal(scale=rng.uniform(0.1, 2.0), size=m))
        f = np.clip(special.ndtr(s * (lx - rng.normal(scale=0.5)) / rng.uniform(0.01, 1.5))
                    + rng.normal(scale=rng.choice([0.0, 0.05, 0.2]), size=m), 0.0, 1.0)
        yield lx, f, s


def test_least_squares_fit_is_at_least_as_good_as_scipys_trf():
    # scipy's trf with the settings the fit used before (four starts, the best kept): the same verdicts,
    # never a higher cost; where both converge, the same optimum to trf's tolerances
    n_same = 0
    for lx, f, s in _strip_problems():
        got = ls.fit_lognormal_least_squares(np.exp(lx), f, s < 0)

        def residual(q, lx=lx, f=f, s=s):
            return f - special.ndtr(s * (lx - q[0]) / q[1])

        spread = float(np.ptp(lx)) or 1.0
        lo, hi = [lx.min() - 3 * spread, BETA_BOUNDS[0]], [lx.max() + 3 * spread, BETA_BOUNDS[1]]
        m0 = float(lx[np.argmin(np.abs(f - 0.5))])
        if np.all(f == f[0]) or np.all((f == 0) | (f == 1)):
            continue
        ref = min((optimize.least_squares(residual, [m0, float(np.clip(b0 * max(spread, 0.1), *BETA_BOUNDS))],
                                          bounds=(lo, hi), method="trf", x_scale=[1.0, 0.1], xtol=1e-10, ftol=1e-12,
                                          gtol=1e-12, max_nfev=300) for b0 in (0.05, 0.2, 0.5, 1.5)),
                  key=lambda r: r.cost)
        assert got.objective <= 2 * ref.cost * (1 + 1e-9) + 1e-15
        if got.success and ref.success and got.objective >= 2 * ref.cost * (1 - 1e-9):
            assert (math.log(got.mu), got.beta) == pytest.approx(tuple(ref.x), rel=1e-4)
            n_same += 1
    assert n_same > 30


def test_least_squares_model_derivatives():
    # the Jacobian and the second-order term sum r ∇²r of the strip fit's model, against differences
    lx, f = np.log([0.5, 0.8, 1.0, 1.3, 2.0]), np.array([0.0, 0.2, 0.5, 0.7, 1.0])
    seen = {}

    def spy(model, q0, lo, hi, max_nfev):
        seen["model"] = model
        return optimise.least_squares_box(model, q0, lo, hi, max_nfev)

    import unittest.mock

    with unittest.mock.patch.object(ls, "least_squares_box", spy):
        ls.fit_lognormal_least_squares(np.exp(lx), f, True)
    model, q, h = seen["model"], np.array([0.1, 0.4]), 1e-6
    r, jac, second = model(q)
    cols = [(model(q + h * e)[0] - model(q - h * e)[0]) / (2 * h) for e in np.eye(2)]
    assert jac == pytest.approx(np.stack(cols, axis=1), rel=1e-6, abs=1e-9)
    hess = np.array([(model(q + h * e)[1].T @ model(q + h * e)[0] - model(q - h * e)[1].T @ model(q - h * e)[0])
                     / (2 * h) for e in np.eye(2)])
    assert jac.T @ jac + second == pytest.approx(hess, rel=1e-5, abs=1e-8)


def test_the_fits_import_no_private_scipy_name():
    import pathlib
    import re

    import opsrock

    private = re.compile(r"scipy\.[a-z_.]*\._|from scipy.* import _")
    hits = [str(p) for p in pathlib.Path(opsrock.__file__).parent.rglob("*.py") if private.search(p.read_text())]
    assert hits == []


# --- the record study: same numbers, counted work ------------------------------------------------------

def _reference_frequencies(cases, ims, n_boot, seed):
    """Winners of each record resample from the resampled table, as the study computed them before."""
    records = np.array(list(dict.fromkeys(cases["record"].tolist())))
    by_rec = {r: np.flatnonzero(cases["record"].to_numpy() == r) for r in records}
    rng = np.random.default_rng(seed)
    quick = rs.RecordStudySettings(ims=ims, n_boot=0)
    wins = {c: dict.fromkeys(ims, 0) for c in ("beta", "HR", "cv_percent")}
    for _ in range(n_boot):
        pick = rng.integers(0, records.size, records.size)
        sample = cases.iloc[np.concatenate([by_rec[records[i]] for i in pick])].reset_index(drop=True)
        rows = pd.DataFrame([rs._im_row(sample, im, quick) for im in ims]).set_index("im")
        if rows["beta"].notna().any():
            for c in wins:
                if rows[c].notna().any():
                    wins[c][rows[c].idxmin()] += 1
    return wins


def test_ranking_frequencies_equal_the_resampled_tables():
    ok, _ = rs._prepare(_campaign(), "as_simulated")
    ims = ("IM1", "IM2", "IM3", "IM6", "IM9")
    freq = rs.ranking_frequencies(ok, ims, 12, 5).set_index("im")
    ref = _reference_frequencies(ok, ims, 12, 5)
    for c, w in ref.items():
        assert freq[f"wins_{c}"].to_dict() == w


def test_ranking_criteria_equal_the_rows_of_the_resampled_tables():
    # an IM on a few values (the scene's measure) and safe cases that rock or not at the same value: the
    # criteria of a resample read the rocking flag of every distinct case, as the table's row reads its cases'
    cases = _campaign()
    cases["IM2"] = cases["level_value"] * 0.7
    safe = ~cases["overturned"]
    cases["rocked"] = True
    cases.loc[safe & ~cases[safe].duplicated("IM2").reindex(cases.index, fill_value=True), "rocked"] = False
    ok, _ = rs._prepare(cases, "as_simulated")
    assert ok.groupby(["IM2", "y"])["rocked_bool"].nunique().max() == 2  # the flag differs at one value
    freq = rs._Frequencies(ok, ("IM2", "IM5"), 15, 1)
    resamples = mle.resample_indices(len(ok), freq.members, 15, 1)
    for k, idx in enumerate(resamples):
        sample = ok.iloc[idx].reset_index(drop=True)
        for j, im in enumerate(freq.ims):
            row = rs._im_row(sample, im, rs.RecordStudySettings(ims=freq.ims, n_boot=0))
            got = freq.criteria(k, k + 1)[0, j]
            assert got.tolist() == [row["beta"], row["HR"], row["cv_percent"]]


def test_record_study_does_not_depend_on_workers():
    cases = _campaign(n_records=8)
    settings = rs.RecordStudySettings(n_boot=25)
    a = rs.record_fragility(cases, settings, n_rank_boot=25, workers=1)
    b = rs.record_fragility(cases, settings, n_rank_boot=25, workers=2)
    for name in ("ims", "measure_fits", "blocks", "frequencies", "sufficiency", "resurrections"):
        pd.testing.assert_frame_equal(getattr(a, name), getattr(b, name), check_exact=True)


def test_record_study_counts_its_fits(monkeypatch):
    cases = _campaign(n_records=8)
    n_boot, n_rank = 12, 10
    calls = {"logistic": 0, "minimize": 0, "elements": 0, "evaluations": 0, "newton": 0}
    fit_logistic = rs.fit_logistic
    minimize = optimize.minimize
    call = mle._ProbitNLL.__call__

    def count_logistic(*a, **k):
        calls["logistic"] += 1
        return fit_logistic(*a, **k)

    def count_minimize(*a, **k):
        calls["minimize"] += 1
        return minimize(*a, **k)

    def count_nll(self, ab):
        calls["evaluations"] += 1
        calls["elements"] += self.v.size
        return call(self, ab)

    monkeypatch.setattr(rs, "fit_logistic", count_logistic)
    monkeypatch.setattr(optimize, "minimize", count_minimize)
    newton = optimise.newton

    def count_newton(*a, **k):
        calls["newton"] += 1
        return newton(*a, **k)

    monkeypatch.setattr(mle._ProbitNLL, "__call__", count_nll)
    monkeypatch.setattr(mle, "newton", count_newton)
    monkeypatch.setattr(logistic, "newton", count_newton)
    study = rs.record_fragility(cases, rs.RecordStudySettings(n_boot=n_boot), n_rank_boot=n_rank)
    # IMs, blocks x floors x (PFA, PFV) (two each: _campaign), the measure under both conventions
    n_ims, n_plans = 9, 9 + 2 * 2 * 2 + 2
    assert len(study.blocks) == 2 * 2 * 2 and study.blocks.groupby(["block", "floor"]).size().eq(2).all()
    assert calls["logistic"] == n_ims  # one per IM: none in the ranking resamples
    # one Newton run per point fit, per bootstrap resample, per ranking resample and IM, per logistic fit; at most
    assert 0 < calls["newton"] <= n_plans * (1 + n_boot) + n_ims * n_rank + n_ims
    # scipy.optimize.minimize itself only for the sufficiency tests (numerical gradient): one per test
    assert calls["minimize"] == len(study.sufficiency)
    # the likelihood runs over distinct cases: on average well under the cases of a fit
    assert calls["elements"] / calls["evaluations"] < 0.8 * len(cases)


def test_the_scenes_measure_is_fitted_on_its_few_levels(monkeypatch):
    cases = _campaign(n_records=10)
    sizes = []
    call = mle._ProbitNLL.__call__

    def record(self, ab):
        sizes.append(self.v.size)
        return call(self, ab)

    monkeypatch.setattr(mle._ProbitNLL, "__call__", record)
    y = cases["overturned"].to_numpy(bool)
    mle.fit_lognormal_mle(cases["level_value"].to_numpy(float), y, False, 10, 0.95, 0,
                          groups=cases["record"].to_numpy())
    assert sizes and max(sizes) <= 2 * cases["level_value"].nunique()  # (level, outcome) pairs, not cases


# --- the robustness study ---------------------------------------------------------------------------

def test_batched_robustness_equals_the_set_by_set_analysis():
    from opsrock.fragility.analysis import FragilitySettings, analyse_fragility, rank_ims

    sets = rb.draw_block_sets(3, seed=11)
    batched = rb._sets_winners(sets)
    for blocks, won in zip(sets, batched):
        rank = rank_ims(analyse_fragility(rb.pulse_cases(blocks), FragilitySettings(strip_factors=(1.0,), n_boot=0)))
        assert won == {c: (str(rank[c].idxmin()) if rank[c].notna().any() else "") for c in rb.CRITERIA}


def test_robustness_counts_its_solves_and_fits(monkeypatch):
    from opsrock.solvers import housner_fast

    solves = []
    solve_pulses = housner_fast.solve_pulses

    def count_solve(blocks, *a, **k):
        solves.append(len(blocks))
        return solve_pulses(blocks, *a, **k)

    monkeypatch.setattr(housner_fast, "solve_pulses", count_solve)
    monkeypatch.setattr(rb, "SETS_PER_TASK", 4)
    runs = {"newton": 0, "box": 0}
    newton, box = optimise.newton, optimise.least_squares_box

    def count(name, fn):
        def counted(*a, **k):
            runs[name] += 1
            return fn(*a, **k)
        return counted

    monkeypatch.setattr(mle, "newton", count("newton", newton))
    monkeypatch.setattr(ls, "least_squares_box", count("box", box))
    n_sets = 6
    rb.ranking_robustness(n_sets, seed=2, workers=1)
    assert solves == [16, 8]  # one solve per task of four sets (four blocks each), not one per set
    assert runs["newton"] == 0  # no MLE: no criterion reads it
    assert 0 < runs["box"] <= 4 * 9 * n_sets  # four starts per IM at most


def test_paper_analysis_does_not_depend_on_workers():
    from opsrock.fragility import FragilitySettings, analyse_fragility, table2, table3

    cases = rb.pulse_cases(rb.draw_block_sets(1, seed=3)[0])
    settings = FragilitySettings(n_boot=30)
    a, b = analyse_fragility(cases, settings, workers=1), analyse_fragility(cases, settings, workers=2)
    pd.testing.assert_frame_equal(table3(a), table3(b), check_exact=True)
    pd.testing.assert_frame_equal(table2(a), table2(b), check_exact=True)


@pytest.fixture
def sigint_as_in_a_terminal():
    """Python's own Ctrl-C handler for the test, whatever this process inherited (a shell starts background
    jobs with SIGINT ignored, and then Python installs no handler)."""
    import signal

    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


def test_ctrl_c_while_a_pool_forks_is_delivered_after_it(sigint_as_in_a_terminal):
    import os
    import signal
    import time

    from opsrock._pool import deferred_interrupts

    reached = False
    with pytest.raises(KeyboardInterrupt):
        with deferred_interrupts():
            os.kill(os.getpid(), signal.SIGINT)  # recorded here (a fork's handlers would swallow it) ...
            time.sleep(0.05)
            reached = True
        pytest.fail("the recorded Ctrl-C was lost")  # ... and raised as the block ends
    assert reached
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_ctrl_c_while_a_task_pool_starts_shuts_its_workers_down(sigint_as_in_a_terminal, monkeypatch):
    # a Ctrl-C recorded while TaskPool submits (forks) is raised in its constructor, before any caller's `with`
    # could shut the pool down: the constructor must do it, else the interpreter's exit waits for every queued
    # task (`opsrock fragility --n-boot 10000` stayed a minute after Ctrl-C)
    import os
    import signal
    import time

    from opsrock import _pool

    class Recorder:
        shutdowns: list = []

        def submit(self, fn, *args):
            os.kill(os.getpid(), signal.SIGINT)  # recorded by deferred_interrupts, raised as its block ends
            time.sleep(0.01)

        def shutdown(self, cancel_futures=False):
            self.shutdowns.append(cancel_futures)

    monkeypatch.setattr(_pool, "process_pool", lambda *a, **k: Recorder())
    with pytest.raises(KeyboardInterrupt):
        _pool.TaskPool(None, [(0,), (1,)], workers=2)
    assert Recorder.shutdowns == [True]


def test_an_ignored_ctrl_c_stays_ignored_through_a_pool_start():
    # nohup and a shell's background jobs ignore SIGINT: the block must not turn it into an interrupt
    import os
    import signal
    import time

    from opsrock._pool import deferred_interrupts

    before = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        with deferred_interrupts():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, before)
