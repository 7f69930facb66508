"""Tests of the fast rigid-body solver :mod:`opsrock.solvers.housner_fast`.

Every reference value is computed independently of the code under test: closed forms
(Eq. 4, the energy integral, Housner's linearised free rocking), or
:func:`opsrock.bench.reference.reference_solve`, a plain event-driven scipy ``solve_ivp`` (DOP853,
rtol 1e-10) of the same rigid-body equation that integrates the free rocking after the pulse
instead of using the energy shortcut of the fast solver; the benchmark measures accuracy against
the same reference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from opsrock.bench.reference import reference_solve
from opsrock.block import Block
from opsrock.excitations import OneSinePulse
from opsrock.solvers import housner_fast as hf
from opsrock.solvers import simulate

#: The four blocks of the dense-spectrum benchmark (docs/guide/modelling.md section 5), (width, height) in m.
BLOCKS = [Block(0.40, 2.20), Block(0.60, 2.00), Block(0.50, 1.15), Block(1.00, 2.40)]


def _energy(alpha: float, p: float, theta: np.ndarray, theta_dot: np.ndarray) -> np.ndarray:
    """Rocking energy per m g R with a = 0 (docs/guide/modelling.md section 2):
    ``(theta'/p)²/2 + cos(alpha - |theta|) - cos(alpha)``, written here independently."""
    return 0.5 * (theta_dot / p) ** 2 + np.cos(alpha - np.abs(theta)) - math.cos(alpha)


def _impact_rows(res) -> np.ndarray:
    """Indices i of the history rows holding (just before, just after) an impact at i, i+1."""
    th, t = res.theta, res.time
    return np.flatnonzero((th[:-1] == 0.0) & (th[1:] == 0.0) & (t[:-1] == t[1:]))


# =============================================================================================
# Closed forms
# =============================================================================================


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: f"alpha={b.alpha:.3f}")
def test_uplift_threshold_eq4(block):
    """Eq. 4: the block leaves rest only when PFA exceeds g tan(alpha), i.e. pfa_ratio > 1.

    Each side of the threshold is checked 1e-6 away: the decision is a strict comparison, so
    any margin well above round-off (1e-16) must give the exact answer."""
    r = hf.solve_grid(block.alpha, block.e, [1.0 - 1e-6, 1.0, 1.0 + 1e-6], 2.0)
    assert r.ok.all()
    assert list(r.rocked) == [False, False, True]
    assert r.theta_max[0] == 0.0 and r.theta_max[1] == 0.0
    assert r.theta_max[2] > 0.0
    # the one-case entry point, with PFA built from the ratio (round-off in g tan alpha)
    at = hf.solve(block, OneSinePulse.from_ratios(block, 1.0, 2.0))
    assert at.verdict == "no_uplift"


def test_uplift_time_and_direction():
    """Uplift happens when PFA sin(omega_p t) first reaches g tan(alpha) (Eq. 4):
    t_up = asin(1/pfa_ratio)/omega_p, closed form; a positive a tips to negative theta.
    The kernel seats/uplifts by the same closed form, so the tolerance is round-off."""
    block = BLOCKS[1]
    pulse = OneSinePulse.from_ratios(block, 2.5, 3.0)
    res = hf.solve(block, pulse)
    moved = np.flatnonzero(res.theta != 0.0)
    t_up = res.time[moved[0] - 1]
    assert t_up == pytest.approx(math.asin(1.0 / 2.5) / pulse.omega_p, rel=1e-12)
    assert res.theta[moved[0]] < 0.0


def _first_impact_time_quadrature(alpha: float, p: float, theta0: float) -> float:
    """Exact time (s) to fall from rest at theta0 to theta = 0: energy integral
    t = (1/p) ∫_0^theta0 dθ / sqrt(2 (V(theta0) - V(θ))), V(θ) = cos(alpha - θ); the
    substitution θ = theta0 - u² removes the inverse-square-root singularity at theta0."""
    def V(th):  # noqa: N802
        return math.cos(alpha - th)

    val, _ = quad(lambda u: 2.0 * u / math.sqrt(2.0 * (V(theta0) - V(theta0 - u * u))),
                  0.0, math.sqrt(theta0), epsabs=1e-15, epsrel=1e-13)
    return val / p


@pytest.mark.parametrize("block", [BLOCKS[0], BLOCKS[2]], ids=["slender", "stocky"])
def test_free_rocking_first_impact_time(block):
    """Free rocking from rest at theta0 = 0.5 alpha: first impact at the time given by the
    energy integral. Tolerance 1e-7 relative: RK4 at the default step is accurate to about
    1e-9 here (the impact is located on the RK map itself), the quadrature to 1e-13."""
    theta0 = 0.5 * block.alpha
    res = hf.solve(block, None, theta0=theta0, end_time=3.0)
    assert res.ok and not res.overturned
    t_impact = res.time[_impact_rows(res)[0]]
    assert t_impact == pytest.approx(_first_impact_time_quadrature(block.alpha, block.p, theta0), rel=1e-7)


def test_free_rocking_first_impact_linearised_slender():
    """Housner's linearised free rocking (slender block): t = arccosh(1/(1 - theta0/alpha))/p.
    The linearisation replaces sin(alpha - θ) by alpha - θ, a relative error of order
    alpha²/6 = 0.5 % for alpha = 0.18 rad, so the tolerance is 1 % (the exact solution is
    checked to 1e-7 above)."""
    block = BLOCKS[0]
    theta0 = 0.5 * block.alpha
    res = hf.solve(block, None, theta0=theta0, end_time=3.0)
    t_impact = res.time[_impact_rows(res)[0]]
    assert t_impact == pytest.approx(math.acosh(1.0 / (1.0 - theta0 / block.alpha)) / block.p, rel=1e-2)


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: f"alpha={b.alpha:.3f}")
def test_energy_ratio_e_squared_per_impact(block):
    """Kinetic (= total, at theta = 0) energy falls by e² at every impact (Housner). The
    before/after velocities are stored exactly; tolerance 1e-12 is round-off."""
    res = hf.solve(block, None, theta0=0.6 * block.alpha, end_time=4.0)
    rows = _impact_rows(res)
    assert rows.size >= 3
    for i in rows[:5]:
        before = _energy(block.alpha, block.p, res.theta[i], res.theta_dot[i])
        after = _energy(block.alpha, block.p, res.theta[i + 1], res.theta_dot[i + 1])
        assert after / before == pytest.approx(block.e**2, rel=1e-12)


@pytest.mark.parametrize("block", BLOCKS, ids=lambda b: f"alpha={b.alpha:.3f}")
def test_energy_conserved_between_impacts(block):
    """With a = 0 the energy is constant between impacts (docs/guide/modelling.md section 2). Between the
    start and the first impact, and between the first two impacts, it must stay within
    1e-9 of its value (relative to the barrier 1 - cos alpha): RK4's energy drift at the
    default step is about 1e-11 here, so a wrong sign or lever would fail by orders."""
    res = hf.solve(block, None, theta0=0.5 * block.alpha, end_time=4.0)
    rows = _impact_rows(res)
    E = _energy(block.alpha, block.p, res.theta, res.theta_dot)
    barrier = 1.0 - math.cos(block.alpha)
    seg0 = E[: rows[0] + 1]
    seg1 = E[rows[0] + 1: rows[1] + 1]
    assert np.ptp(seg0) / barrier < 1e-9
    assert np.ptp(seg1) / barrier < 1e-9
    # and the level: V(theta0), the potential at release
    assert seg0[0] == pytest.approx(math.cos(0.5 * block.alpha) - math.cos(block.alpha), rel=1e-14)


# =============================================================================================
# Against the independent solve_ivp reference
# =============================================================================================


def _random_cases(n: int, seed: int, pfa_high: float) -> tuple[np.ndarray, ...]:
    rng = np.random.default_rng(seed)
    idx = rng.integers(0, len(BLOCKS), n)
    alpha = np.array([BLOCKS[i].alpha for i in idx])
    p = np.array([BLOCKS[i].p for i in idx])
    e = np.array([BLOCKS[i].e for i in idx])
    return alpha, p, e, rng.uniform(1.0, pfa_high, n), rng.uniform(0.5, 10.0, n)


#: Largest |d theta_max| / alpha allowed against the reference. The issue asks for 5e-3;
#: measured differences are below 2e-8 (300 random pulses: 5e-11; chattering-rich set:
#: 7e-10), so 1e-6 still leaves a factor 50 for platform differences while catching any
#: error in the equation, the impact rule or the post-pulse energy verdict.
THETA_TOL = 1e-6


@pytest.mark.parametrize(
    "seed, pfa_high",
    [(11, 10.5), (12, 1.6)],
    ids=["spectrum-range", "low-pfa-chattering"],
)
def test_matches_solve_ivp_reference(seed, pfa_high):
    """25 random pulses per set (the spectrum's range; and a low-PFA set where impacts
    accumulate, the block comes to rest and lifts off again): theta_max and the verdict
    agree with the rtol 1e-10 event-driven reference."""
    alpha, p, e, r, f = _random_cases(25, seed, pfa_high)
    fast = hf.solve_grid(alpha, e, r, f)
    assert fast.ok.all()
    for i in range(alpha.size):
        ref = reference_solve(alpha[i], e[i], r[i], f[i])
        assert bool(fast.overturned[i]) == ref["overturned"], (i, r[i], f[i])
        assert bool(fast.rocked[i]) == ref["rocked"]
        if not ref["overturned"]:
            assert abs(fast.theta_max[i] - ref["theta_max"]) / alpha[i] < THETA_TOL, (i, r[i], f[i])
    if pfa_high < 2.0:
        assert fast.n_impacts.max() > 50  # the set really exercises chattering


def _end_of_pulse_branch(block, res, freq_ratio) -> str:
    """Which exact post-pulse rule decides the case: where the block is at the end of the
    pulse (inside the well |theta| <= alpha or beyond the hump) and whether it heads out."""
    t_end = 2.0 * math.pi / (freq_ratio * block.p)
    if res.time[-1] < t_end * (1.0 - 1e-12) or res.theta[-1] == 0.0:
        return "pulse"  # overturned or seated during the pulse, or at an impact at the end
    th, w = res.theta[-1], res.theta_dot[-1]
    where = "beyond" if abs(th) > block.alpha else "inside"
    return f"{where}-{'out' if th * w > 0.0 else 'in'}-{res.verdict}"


def test_every_post_pulse_branch_matches_reference():
    """After the pulse the fast solver decides by the energy barrier, in closed form; the
    reference integrates the free rocking instead. Two cases of every branch met on a
    12 x 12 scan (inside/beyond the hump x heading in/out x safe/overturned) must agree to
    THETA_TOL and in verdict: this checks the closed-form tail branch by branch."""
    picked: dict[str, list] = {}
    for block in BLOCKS:
        for r in np.linspace(1.05, 10.5, 12):
            for f in np.linspace(0.5, 10.0, 12):
                res = hf.solve(block, OneSinePulse.from_ratios(block, r, f))
                if res.rocked:
                    key = _end_of_pulse_branch(block, res, f)
                    if len(picked.setdefault(key, [])) < 2:
                        picked[key].append((block, r, f, res))
    expected = {"inside-out-safe", "inside-in-safe", "beyond-in-safe", "inside-out-overturned",
                "inside-in-overturned", "beyond-in-overturned", "beyond-out-overturned"}
    assert expected <= set(picked), sorted(picked)
    for key, cases in picked.items():
        for block, r, f, res in cases:
            ref = reference_solve(block.alpha, block.e, r, f)
            assert res.overturned == ref["overturned"], (key, r, f)
            if not ref["overturned"]:
                assert abs(res.theta_max - ref["theta_max"]) / block.alpha < THETA_TOL, (key, r, f)


def test_solve_matches_solve_grid():
    """The one-case entry point and the batch entry point run the same kernel: the same verdicts, and
    theta_max equal to rounding. Not bit for bit on every numpy: the pulse's ratios reach the kernel
    through ``OneSinePulse.from_ratios`` (physical units and back, numpy's trigonometry) in one path and
    directly in the other, and numpy 1.24's vectorised tan/sin differ from 2.x's by an ulp (measured:
    1.4e-15 relative in theta_max); 1e-13 is a hundred times that and far below any physical meaning."""
    block = BLOCKS[3]
    for r, f in [(1.3, 0.7), (4.0, 2.0), (9.0, 8.0)]:
        one = hf.solve(block, OneSinePulse.from_ratios(block, r, f))
        many = hf.solve_grid(block.alpha, block.e, r, f)
        assert one.solver == "housner_fast" and one.ok
        assert one.theta_max == pytest.approx(float(many.theta_max), rel=1e-13, abs=0.0)
        assert one.overturned == bool(many.overturned)
        assert one.verdict == many.verdict.item()


def test_p_only_scales_time():
    """In tau = p t the rigid-body equation depends on alpha, e and the two ratios only, so two
    geometrically similar blocks (same alpha and e, sizes 1 : 7.3², so p differs 7.3 times) under
    pulses of the same ratios must give the same theta_max and verdict, with times in the ratio
    of their p (dimensional analysis). Checked where it could fail: the dimensional solvers
    ``housner`` (solve_ivp in seconds, rtol 1e-10) and ``housner_fast.solve`` (seconds in, seconds
    out). Tolerance 1e-7 of alpha: the solvers' own accuracy (1e-9 to 1e-10) with room to spare;
    a wrong p anywhere (lever, gravity term, pulse sampling) moves theta_max by percents."""
    small = Block(0.04, 0.22)
    large = Block(0.04 * 7.3**2, 0.22 * 7.3**2)
    assert large.alpha == pytest.approx(small.alpha, rel=1e-14) and large.p == pytest.approx(small.p / 7.3)
    for pfa_ratio, freq_ratio in [(3.0, 4.0), (2.2, 1.7), (5.0, 8.0)]:
        for solver in ("housner", "housner_fast"):
            a = simulate(small, OneSinePulse.from_ratios(small, pfa_ratio, freq_ratio), solver=solver)
            b = simulate(large, OneSinePulse.from_ratios(large, pfa_ratio, freq_ratio), solver=solver)
            assert a.verdict == b.verdict and a.rocked
            assert abs(a.theta_max_over_alpha - b.theta_max_over_alpha) < 1e-7, (solver, pfa_ratio, freq_ratio)
            if solver == "housner" and a.n_impacts:
                np.testing.assert_allclose(a.impacts.time * small.p, b.impacts.time * large.p, rtol=1e-7)


def test_deterministic_regardless_of_threads_and_order():
    """Same inputs give bit-identical outputs whatever the thread count or case order:
    cases are independent and each is solved serially."""
    alpha, p, e, r, f = _random_cases(600, 5, 10.5)
    one = hf.solve_grid(alpha, e, r, f, threads=1)
    two = hf.solve_grid(alpha, e, r, f, threads=2)
    perm = np.random.default_rng(0).permutation(alpha.size)
    shuffled = hf.solve_grid(alpha[perm], e[perm], r[perm], f[perm], threads=2)
    for name in ("theta_max", "overturned", "rocked", "status", "n_impacts", "n_steps"):
        np.testing.assert_array_equal(getattr(one, name), getattr(two, name))
        np.testing.assert_array_equal(getattr(one, name)[perm], getattr(shuffled, name))


def test_overturning_monotone_in_pfa_at_fixed_frequency():
    """Physical fact: for a sine pulse, once the block overturns at some PFA it still
    overturns at a slightly larger PFA in the low-frequency regime (omega_p/p = 1), where
    there is no safe 'island' above the first overturning amplitude (Zhang & Makris 2001,
    Fig. 4). Checked on a fine 200-point PFA sweep of each block."""
    pfa = np.linspace(1.0, 10.5, 200)
    for block in BLOCKS:
        res = hf.solve_grid(block.alpha, block.e, pfa, 1.0)
        first = int(np.argmax(res.overturned))
        assert res.overturned.any()
        assert res.overturned[first:].all()


# =============================================================================================
# Results, failures and inputs
# =============================================================================================


def test_failure_is_reported_not_hidden():
    """A chattering case with max_impacts = 1 cannot finish: status failed with a reason, no
    verdict (never safe or overturned)."""
    block = BLOCKS[0]
    pulse = OneSinePulse.from_ratios(block, 1.1, 3.0)
    assert hf.solve(block, pulse).n_impacts > 1  # the case does impact more than once
    res = hf.solve(block, pulse, max_impacts=1)
    assert res.status == "failed" and res.verdict == "failed"
    assert "max_impacts" in res.reason
    grid = hf.solve_grid(block.alpha, block.e, 1.1, 3.0,
                         settings=hf.HousnerFastSettings(max_impacts=1))
    assert grid.status.item() == hf.STATUS_MAX_IMPACTS and grid.verdict.item() == "failed"


@pytest.mark.parametrize(
    "kwargs, name",
    [({"max_dtau": 0.0}, "max_dtau"), ({"max_dtau": 1.0}, "max_dtau"),
     ({"steps_per_pulse": 4}, "steps_per_pulse"), ({"rest_velocity": -1.0}, "rest_velocity"),
     ({"max_impacts": 0}, "max_impacts"), ({"max_steps": 2.5}, "max_steps")],
)
def test_settings_errors_name_the_argument(kwargs, name):
    with pytest.raises((ValueError, TypeError), match=name):
        hf.HousnerFastSettings(**kwargs)


def test_input_errors_name_the_argument():
    with pytest.raises(ValueError, match="pfa_ratio"):
        hf.solve_grid(0.2, 0.9, [2.0, -1.0], 1.0)
    with pytest.raises(ValueError, match="alpha"):
        hf.solve_grid(2.0, 0.9, 2.0, 1.0)
    with pytest.raises(TypeError, match="unknown"):
        hf.solve(BLOCKS[0], OneSinePulse(3.0, 10.0), max_stepp=0.1)
    with pytest.raises(TypeError, match="Pulse, Record"):
        hf.solve(BLOCKS[0], "a pulse")
    from opsrock.excitations import Record
    # a record sampled too coarsely for the block (dt p = 0.5 x 2.57 > 0.2) is refused, named
    with pytest.raises(ValueError, match="dt = 0.5 s is too coarse"):
        hf.solve(BLOCKS[0], Record(0.5, [0.0, 1.0, 0.0]))


def test_grid_shape_and_verdicts():
    """solve_pulses returns (blocks, pfa, freq) arrays; the pfa_ratio = 1.0 row never uplifts
    (Eq. 4), every other case rocks."""
    res = hf.solve_pulses(BLOCKS, [1.0, 3.0, 9.0], [0.5, 2.0, 9.0, 10.0])
    assert res.theta_max.shape == (4, 3, 4)
    assert not res.rocked[:, 0, :].any() and res.rocked[:, 1:, :].all()
    assert set(res.verdict.ravel()) <= {"no_uplift", "safe", "overturned"}
    assert np.array_equal(res.overturned, res.theta_max >= 0.5 * math.pi)


# =============================================================================================
# Against the project's per-case event-driven solver, when present
# =============================================================================================


def test_matches_housner_solver():
    """opsrock.solvers.housner (scipy, rtol 1e-10, written independently) on 8 random
    pulses: same verdicts, theta_max within THETA_TOL alpha (both converge to the same exact
    rigid-body answer)."""
    housner = pytest.importorskip("opsrock.solvers.housner")
    rng = np.random.default_rng(21)
    for _ in range(8):
        block = BLOCKS[int(rng.integers(0, 4))]
        pulse = OneSinePulse.from_ratios(block, float(rng.uniform(1.0, 10.5)), float(rng.uniform(0.5, 10.0)))
        ref = housner.solve(block, pulse)
        fast = hf.solve(block, pulse)
        assert ref.ok and fast.ok
        assert fast.verdict == ref.verdict
        if not ref.overturned:
            assert abs(fast.theta_max - ref.theta_max) / block.alpha < THETA_TOL


# =============================================================================================
# Dense-spectrum timing (docs/guide/modelling.md section 5)
# =============================================================================================


@pytest.mark.slow
def test_dense_spectrum_of_40000_cases_finishes_every_case():
    """4 blocks x 100 x 100 pulses, the dense spectrum docs/reference.md times: every case finishes
    without failure. Its speed (2-5 s measured, loaded machine) is a measurement for ``opsrock bench``, never a
    test's verdict (issue 46)."""
    res = hf.solve_pulses(BLOCKS, np.linspace(1.0, 10.5, 100), np.linspace(0.5, 10.0, 100))
    assert res.theta_max.size == 40_000
    assert res.ok.all()


def test_a_grids_wall_time_starts_once_the_kernel_is_loaded(monkeypatch):
    """Issue 46: a first grid from an empty numba cache counted seconds of compilation in ``wall_time_s``. The
    kernel is now called on no case (loaded, or compiled) before the clock starts: checked by the order of the
    calls, which does not depend on how warm the cache or how fast the machine is."""
    from opsrock.solvers.housner_fast import grid

    events = []
    kernel, clock = grid._solve_chunk, grid._time.perf_counter
    monkeypatch.setattr(grid, "announce_compile", lambda *a: None)  # it inspects the real dispatcher
    monkeypatch.setattr(grid, "_solve_chunk", lambda *a: (events.append(("kernel", a[2], a[3])), kernel(*a))[1])
    monkeypatch.setattr(grid._time, "perf_counter", lambda: (events.append(("clock",)), clock())[1])
    res = grid.solve_grid(0.25, 0.8, [2.0, 3.0], 3.0, threads=1)
    assert events[0] == ("kernel", 0, 0)  # no case: the load
    assert events[1] == ("clock",) and ("kernel", 0, 2) in events[2:]
    assert res.wall_time_s > 0.0 and res.overturned.shape == (2,)
