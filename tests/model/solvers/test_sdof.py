"""The scipy SDOF solver (paper Eq. 5-8) against closed forms and the rigid-body solver."""

import numpy as np
import pytest

from opsrock import Block, OneSinePulse, Record
from opsrock.model import SDOFModel
from opsrock.solvers import housner, sdof
from opsrock.validation.closed_forms import exact_time_to_impact, first_zero_crossing, peak_after_impact, peak_sequence

BLOCK = Block(0.40, 2.20)  # slender cabinet, alpha = 0.18 rad
FREE = Record(dt=1.0, values=[0.0, 0.0])  # no floor motion


@pytest.mark.parametrize("lever, threshold", [("housner", 1.0), ("printed", 0.75)])
def test_uplift_threshold(lever, threshold):
    # Eq. 4 with the lever: the stiff branch is left when Lambda |a| > M_s(theta_e), i.e.
    # |a| > g tan(alpha) for Lambda = m R cos(alpha), 0.75 g tan(alpha) for the printed
    # 4/3 m R cos(alpha) (docs/guide/modelling.md section 2); 1 % either side is far outside theta_e = 1e-6 alpha.
    below = OneSinePulse.from_ratios(BLOCK, 0.99 * threshold, 2.0)
    above = OneSinePulse.from_ratios(BLOCK, 1.01 * threshold, 2.0)
    assert not sdof.solve(BLOCK, below, lever=lever, end_time=0.5 * below.T_p).rocked
    assert sdof.solve(BLOCK, above, lever=lever, end_time=0.5 * above.T_p).rocked


def test_free_fall_time_matches_exact_quadrature():
    theta0 = 0.5 * BLOCK.alpha
    r = sdof.solve(BLOCK, FREE, theta0=theta0, end_time=0.6)
    # the 30-point table misstates sin(alpha - theta) by up to ~0.2 % of m g R sin(alpha)
    # (docs/guide/modelling.md section 4); measured 3e-4 on the fall time, so 2e-3 is a real bound
    assert first_zero_crossing(r) == pytest.approx(exact_time_to_impact(BLOCK, theta0), rel=2e-3)


def test_velocity_ratio_across_band_is_e():
    # Eq. 7-8: with c_D = I_O (1 - e)|v1| / (2 delta alpha) the velocity falls linearly with
    # angle by (1 - e) v1 over the full band; gravity inside the band is symmetric about 0, so
    # the exit speed is e v1 up to O(p^2 delta alpha^2 / v1^2): measured 4e-4 relative here.
    delta = 0.005
    band = delta * BLOCK.alpha
    r = sdof.solve(BLOCK, FREE, theta0=0.5 * BLOCK.alpha, end_time=0.7, delta=delta)
    # read at the located band-edge events (terminal solve_ivp events), not at stored samples
    assert r.n_impacts >= 1
    assert r.impacts.velocity_ratio[0] == pytest.approx(BLOCK.e, rel=2e-3)
    assert r.impacts.theta_dot_before[0] < 0  # falling from +theta0 towards zero
    i_in = int(np.searchsorted(r.time, r.impacts.time[0]))  # the entry event is a stored state
    assert abs(abs(r.theta[i_in]) - band) < 1e-12 * BLOCK.alpha  # the event is really on the edge


def test_energy_conserved_outside_band():
    # outside the band f_d = 0 and a = 0: 1/2 I_O theta'^2 + U_table(theta) is a first integral
    model = SDOFModel()
    U = sdof.table_potential(*model.spring_table(BLOCK))
    r = sdof.solve(BLOCK, FREE, theta0=0.7 * BLOCK.alpha, end_time=1.2)
    keep = (r.time < first_zero_crossing(r)) & (np.abs(r.theta) > model.band(BLOCK))
    energy = 0.5 * BLOCK.I_O * r.theta_dot[keep] ** 2 + U(r.theta[keep])
    assert np.max(np.abs(energy / energy[0] - 1.0)) < 1e-8  # rtol 1e-10 over ~100 steps


def test_damper_only_inside_band_and_spring_is_the_table():
    model = SDOFModel()
    r = sdof.solve(BLOCK, FREE, theta0=0.5 * BLOCK.alpha, end_time=1.2)
    outside = np.abs(r.theta) > model.band(BLOCK)
    assert np.all(r.damper_force[outside] == 0.0)  # Eq. 7: f_d = 0 beyond delta alpha
    assert np.any(r.damper_force[~outside] != 0.0)
    th, m = model.spring_table(BLOCK)
    np.testing.assert_allclose(r.spring_moment, np.interp(r.theta, th, m))


def test_approaches_rigid_body_as_delta_shrinks():
    # physics limit: with a = 0 (no lever difference) the only model-form error left after the
    # first impact is the band; the peak error must fall with delta (measured ~0.57 delta)
    theta0 = 0.5 * BLOCK.alpha
    ref = peak_after_impact(BLOCK, theta0)  # exact rigid-body peak, e^2 energy loss
    errs = []
    for delta in (0.05, 0.01, 0.002):
        r = sdof.solve(BLOCK, FREE, theta0=theta0, end_time=1.6, delta=delta)
        errs.append(abs(peak_sequence(r)[1] / ref - 1.0))
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 2e-3 and errs[0] < 0.05


def test_forced_response_close_to_rigid_body():
    # a pulse that peaks after uplift without impact: the remaining difference is the
    # constant lever cos(alpha) of Eq. 6 against cos(alpha - |theta|) of Eq. 1 (measured
    # -0.8 %, table-independent); 2 % bounds it while catching any real error
    pulse = OneSinePulse.from_ratios(BLOCK, 4.0, 8.0)
    h = housner.solve(BLOCK, pulse, tail="peak")
    s = sdof.solve(BLOCK, pulse, tail="peak", delta=0.002)
    assert s.verdict == h.verdict == "safe"
    assert s.theta_max == pytest.approx(h.theta_max, rel=0.02)
    assert s.theta_max < h.theta_max  # the constant lever under-drives the tilted block


def test_overturning_long_strong_not_short_weak():
    strong = sdof.solve(BLOCK, OneSinePulse.from_ratios(BLOCK, 10.0, 0.5))
    weak = sdof.solve(BLOCK, OneSinePulse.from_ratios(BLOCK, 1.5, 8.0), tail="peak")
    assert strong.verdict == "overturned" and abs(abs(strong.theta[-1]) - np.pi / 2) < 1e-9
    assert weak.verdict == "safe" and weak.theta_max < 0.5 * BLOCK.alpha


@pytest.mark.parametrize(
    "kwargs, name",
    [({"delta": 2.0}, "delta"), ({"theta_e_ratio": 0.5}, "theta_e_ratio"), ({"lever": "long"}, "lever"),
     ({"stiff_method": "Euler"}, "stiff_method"), ({"rtol": 0.0}, "rtol"), ({"max_segments": 0}, "max_segments"),
     ({"end_time": -1.0}, "end_time"), ({"nonsense": 1}, "nonsense")],
)
def test_bad_settings_name_the_argument(kwargs, name):
    with pytest.raises((ValueError, TypeError), match=name):
        sdof.solve(BLOCK, FREE, **kwargs)


def test_failures_are_reported_not_hidden():
    r = sdof.solve(BLOCK, FREE, theta0=0.5 * BLOCK.alpha, end_time=3.0, max_impacts=1)
    assert r.status == "failed" and "max_impacts" in r.reason and r.verdict == "failed"
    r = sdof.solve(BLOCK, FREE, theta0=0.5 * BLOCK.alpha, end_time=3.0, max_segments=3)
    assert r.status == "failed" and "max_segments" in r.reason


def test_closed_form_segment_is_the_exact_solution():
    # I th'' + c th' + k th + m = -lam (a0 + a1 (t - t0)) on one stiff region: the closed form
    # against solve_ivp (DOP853, rtol 1e-12) of the same linear equation, at 200 times over a
    # window of about four periods; both are exact to ~1e-12 of the amplitude
    from scipy.integrate import solve_ivp

    from opsrock.solvers.sdof.closed_form import ClosedFormSegment

    inertia, c, k, m, lam, a0, a1, t0 = 2.0, 3.0, 5.0e4, 0.1, 1.5, 0.7, -40.0, 0.3
    y0 = np.array([1e-6, 2e-3])
    seg = ClosedFormSegment(inertia, c, k, m, lam, a0, a1, t0, y0)
    t_end = t0 + 4 * 2 * np.pi / np.sqrt(k / inertia)
    ref = solve_ivp(lambda t, y: [y[1], (-lam * (a0 + a1 * (t - t0)) - c * y[1] - k * y[0] - m) / inertia],
                    (t0, t_end), y0, method="DOP853", rtol=1e-12, atol=1e-16, dense_output=True)
    t = np.linspace(t0, t_end, 200)
    got, want = seg(t), ref.sol(t)
    scale = np.max(np.abs(want), axis=1, keepdims=True)
    assert np.max(np.abs(got - want) / scale) < 1e-8
    assert np.allclose(seg(t0), y0, rtol=1e-14, atol=1e-20)


def test_sdof_stiff_branch_in_closed_form_matches_the_implicit_integrator_on_a_record():
    # the closed form replaces Radau in the stiff branch under a record: same answer (measured
    # 1e-10 alpha on FEMA roof motions), far fewer steps; a record at 1.3 g tan alpha on which the
    # response is not hypersensitive (opsrock.analysis.sensitivity), so the two can be compared case by case
    from scipy import signal

    from opsrock.excitations import Record

    rng = np.random.default_rng(2)
    n, dt = 800, 0.01
    a = signal.sosfiltfilt(signal.butter(4, (0.5, 6.0), btype="bandpass", fs=1 / dt, output="sos"), rng.standard_normal(n))
    block = Block(0.5, 1.15)
    rec = Record(dt, a, units="m/s2").scaled(1.3 * block.uplift_acceleration / np.abs(a).max())
    fast = sdof.solve(block, rec)
    slow = sdof.solve(block, rec, stiff_closed_form=False)
    assert fast.verdict == slow.verdict and fast.rocked
    assert fast.theta_max_over_alpha == pytest.approx(slow.theta_max_over_alpha, abs=1e-6)
    assert fast.n_impacts == slow.n_impacts
