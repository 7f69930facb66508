"""Stability map (validation case 6): failures are reported as failures, the explicit critical step
matches its closed form, and the solver's default settings are accurate on every project block."""

from __future__ import annotations

import math

import numpy as np
import pytest

from opsrock.excitations import OneSinePulse
from opsrock.result import RockingResult, failed_result
from opsrock.solvers import opensees as osr
from opsrock.validation import stability_map as sm

pytestmark = pytest.mark.opensees

BLOCKS = {b.name: b for b in sm.map_blocks()}


def _below_uplift(block):
    # Eq. 4: no uplift below PFA = g tan(alpha); at half of it the exact answer is "no_uplift"
    return OneSinePulse.from_ratios(block, *sm.CRITICAL_STEP_PULSE)


@pytest.mark.parametrize("factor", [1.01, 1.5, 3.0])
def test_explicit_above_critical_step_refused_as_failed(factor):
    # Reference: the central-difference limit omega_e dt < 2 (closed form, critical_time_step).
    # With the default explicit_step_check=True a step above it must come back failed, with an
    # "unstable" reason, on a no-uplift pulse and on an overturning one: never a verdict.
    b = BLOCKS["bookcase"]
    dt = factor * osr.critical_time_step(b)
    for pulse in (_below_uplift(b), OneSinePulse.from_ratios(b, 2.0, 2.0)):
        r = osr.solve(b, pulse, integrator="central_difference", step=dt)
        assert r.status == "failed" and r.verdict == "failed"
        assert r.reason.startswith("unstable"), r.reason
        assert not r.overturned


@pytest.mark.parametrize("factor", [1.01, 1.1])
def test_explicit_just_above_critical_step_blows_up_and_is_failed(factor):
    # Without the up-front check the scheme must be caught while it blows up. Just above dt_cr
    # the stiff branch's mode grows by |lambda| = 1 + 4 eps + sqrt(8 eps) a step (eps = factor - 1,
    # central-difference amplification), so the run must fail as "unstable", not return.
    for b in BLOCKS.values():
        dt = factor * osr.critical_time_step(b)
        r = osr.solve(b, _below_uplift(b), integrator="central_difference", step=dt, explicit_step_check=False,
                          uplift_check=False)
        assert r.status == "failed" and r.reason.startswith("unstable"), (b.name, r.verdict, r.reason)


def test_explicit_far_above_critical_step_is_never_a_plausible_answer():
    # Reference: Eq. 4 (no uplift below g tan(alpha)): an ok run on this pulse must say no_uplift;
    # above dt_cr the scheme is unstable, so the only honest outcome is status "failed". With the
    # up-front check off (explicit_step_check=False), the solver must still see it during the run:
    # it once saturated off the stiff branch and came back "ok" with spurious rocking.
    for b in BLOCKS.values():
        for factor in (1.3, 2.0, 5.0):
            dt = factor * osr.critical_time_step(b)
            r = osr.solve(b, _below_uplift(b), integrator="central_difference", step=dt, explicit_step_check=False,
                          uplift_check=False)
            assert r.status == "failed", (b.name, factor, r.verdict, r.theta_max_over_alpha)
            assert r.reason.startswith("unstable"), r.reason


@pytest.mark.parametrize("name", ["bookcase", "medicine_cabinet"])
def test_measured_critical_step_matches_formula(name):
    # Reference: dt_cr = 2 sqrt(I_O theta_e / (m g R sin alpha)) (central difference on the linear
    # stiff branch, omega_e dt = 2). The table's stiff slope differs from the formula's by a
    # relative theta_e cot(alpha) ~ 5e-6, so the onset of blow-up must match to the bisection
    # resolution (1e-3 here; 1 % allowed). The usable step (ok and no_uplift) may sit below it:
    # near omega_e dt = 2 the stable scheme oscillates at almost the Nyquist frequency and the
    # solver's sawtooth test (8 sign changes in a row) trips once the discrete phase per step is
    # within pi/8 of pi, i.e. above cos(pi/16) = 0.981 dt_cr; so 0.97 <= usable <= 1.
    b = BLOCKS[name]
    m = sm.measured_critical_step(b, rtol=1e-3)
    assert abs(m["onset_ratio"] - 1.0) <= 0.01, m
    assert 0.97 <= m["usable_ratio"] <= 1.0 + 1e-3, m
    assert m["dt_usable"] <= m["dt_onset"] + 1e-3 * m["dt_formula"]


@pytest.mark.parametrize("name", list(BLOCKS))
def test_default_settings_accurate_on_map_pulses(name):
    # Reference: the scipy SDOF solver (same model, independent numerics) at rtol 1e-10; the
    # map's accuracy class: same verdicts on all three pulses and |d theta_max| <= 5 % of alpha.
    # The solver's own target for its default is 0.5 % of alpha (docs/guide/modelling.md section 5), checked too.
    b = BLOCKS[name]
    refs = sm.references(b)
    defaults = osr.OpenSeesSettings()
    cell = sm.run_cell(b, "default", defaults.step, refs, overrides={})
    assert cell.cls == "accurate", cell
    assert cell.n_failed == 0 and cell.n_wrong_verdicts == 0
    assert cell.max_error <= 0.005, cell


def _ok(theta_max, alpha=0.2, overturned=False):
    t = np.array([0.0, 1.0])
    th = np.array([0.0, theta_max])
    return RockingResult(solver="x", settings={}, alpha=alpha, time=t, theta=th, theta_dot=0 * t,
                         theta_max=theta_max, overturned=overturned, rocked=True)


def test_classify_orders_unstable_over_failed_over_wrong():
    # Definitions of the classes (module docstring): one unstable run makes the whole cell
    # unstable; a wrong verdict is wrong even with a small peak error; overturned pairs count
    # by verdict only (their theta_max is the stopping point, not a peak).
    b = BLOCKS["bookcase"]
    a = b.alpha
    refs = [_ok(0.3 * a, a), _ok(math.pi / 2, a, True), _ok(0.8 * a, a)]
    good = [_ok(0.31 * a, a), _ok(math.pi / 2 + 0.01, a, True), _ok(0.82 * a, a)]
    assert sm.classify(b, "m", 1e-3, good, refs).cls == "accurate"
    off = [_ok(0.3 * a, a), _ok(math.pi / 2, a, True), _ok(0.9 * a, a)]  # 10 % of alpha
    c = sm.classify(b, "m", 1e-3, off, refs)
    assert c.cls == "converged_but_wrong" and math.isclose(c.max_error, 0.1)
    wrong = [_ok(0.3 * a, a), _ok(1.2 * a, a), _ok(0.8 * a, a)]  # misses the overturning
    assert sm.classify(b, "m", 1e-3, wrong, refs).n_wrong_verdicts == 1
    assert sm.classify(b, "m", 1e-3, wrong, refs).cls == "converged_but_wrong"
    failed = failed_result("x", {}, a, "step did not converge")
    unstable = failed_result("x", {}, a, "unstable: sawtooth")
    assert sm.classify(b, "m", 1e-3, [good[0], failed, good[2]], refs).cls == "failed"
    assert sm.classify(b, "m", 1e-3, [unstable, failed, good[2]], refs).cls == "unstable"


@pytest.mark.slow
def test_quick_map_writes_outputs(tmp_path):
    # The quick map (bookcase, dt 1e-2/1e-3/1e-4): every implicit method is accurate at 1e-4 s
    # (reference: the sdof solver; docs/guide/modelling.md section 4 says dt = 1e-4 gives 0.01-1 % of alpha), and the
    # explicit scheme at 1e-2 s (13 dt_cr) is not accurate (closed-form stability limit).
    metrics = sm.run(tmp_path, quick=True)
    assert (tmp_path / "stability_map.png").stat().st_size > 0
    rows = (tmp_path / "stability_map.csv").read_text().splitlines()
    cells = {(r.split(",")[1], float(r.split(",")[2])): r.split(",")[3] for r in rows[1:]}
    for m in ("newmark", "hht", "generalized_alpha", "adaptive"):
        assert cells[(m, 1e-4)] == "accurate"
    assert cells[("central_difference", 1e-2)] != "accurate"
    assert metrics["defaults_accurate_all_blocks"]
