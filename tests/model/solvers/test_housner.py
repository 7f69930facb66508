"""The exact rigid-body solver against closed forms (paper Eq. 1-4, 9; docs/guide/modelling.md section 2)."""

import math

import numpy as np
import pytest

from opsrock import Block, OneSinePulse, Record
from opsrock.solvers import housner
from opsrock.solvers.common import rocking_energy
from opsrock.validation.closed_forms import (
    exact_time_to_impact,
    first_zero_crossing,
    linearised_time_to_impact,
    peak_after_impact,
    peak_sequence,
    potential,
)

BLOCK = Block(0.40, 2.20)  # slender cabinet, alpha = 0.18 rad
STOCKY = Block(1.00, 2.40)  # alpha = 0.39 rad
FREE = Record(dt=1.0, values=[0.0, 0.0])  # no floor motion


@pytest.mark.parametrize("block", [BLOCK, STOCKY])
def test_uplift_threshold(block):
    # Eq. 4: uplift only when |a| > g tan(alpha); 1 % either side is far beyond the
    # Brent-refined threshold search (1e-14 s) and the peak refinement of the scan.
    below = OneSinePulse.from_ratios(block, 0.99, 2.0)
    above = OneSinePulse.from_ratios(block, 1.01, 2.0)
    assert housner.solve(block, below).verdict == "no_uplift"
    r = housner.solve(block, above, end_time=0.5 * above.T_p)
    assert r.rocked and not r.overturned


def test_uplift_direction_follows_the_floor():
    # Eq. 1 sign convention: a positive first half-cycle tips the block to negative theta.
    pulse = OneSinePulse.from_ratios(BLOCK, 3.0, 4.0)
    r = housner.solve(BLOCK, pulse, end_time=0.3 * pulse.T_p)
    moved = r.theta[np.abs(r.theta) > 0]
    assert moved.size and moved[0] < 0


@pytest.mark.parametrize("block", [BLOCK, STOCKY])
def test_free_rocking_time_to_impact(block):
    theta0 = 0.5 * block.alpha
    r = housner.solve(block, FREE, theta0=theta0, end_time=1.5)
    t1 = first_zero_crossing(r)
    # exact: quadrature of the energy integral (rel. 1e-11); solver at rtol 1e-10 -> 1e-8
    assert t1 == pytest.approx(exact_time_to_impact(block, theta0), rel=1e-8)
    # linearised arccosh form: O(alpha^2) off; measured 0.1 % (slender), 0.4 % (stocky)
    assert t1 == pytest.approx(linearised_time_to_impact(block, theta0), rel=1e-2)


def test_energy_ratio_e_squared_per_impact():
    theta0 = 0.6 * BLOCK.alpha
    r = housner.solve(BLOCK, FREE, theta0=theta0, end_time=4.0)
    peaks = peak_sequence(r)[:4]
    assert peaks.size == 4
    # energy conserved in flight, times e^2 at each impact: U(peak k+1)/U(peak k) = e^2;
    # peaks are stored exactly (turning-point events), tolerance from rtol 1e-10
    ratios = potential(BLOCK, peaks[1:]) / potential(BLOCK, peaks[:-1])
    np.testing.assert_allclose(ratios, BLOCK.e**2, rtol=1e-7)
    assert peaks[1] == pytest.approx(peak_after_impact(BLOCK, theta0), rel=1e-7)
    assert r.n_impacts >= 3


def test_energy_conserved_between_impacts():
    r = housner.solve(BLOCK, FREE, theta0=0.8 * BLOCK.alpha, theta_dot0=-0.1, end_time=2.0)
    assert r.n_impacts >= 1
    t_imp = first_zero_crossing(r)
    keep = r.time < t_imp
    energy = rocking_energy(BLOCK, r.theta[keep], r.theta_dot[keep])
    # a = 0: E is a first integral; drift bounded by rtol 1e-10 over a few hundred steps
    assert np.max(np.abs(energy / energy[0] - 1.0)) < 1e-8


def test_events_are_zeros_of_their_functions():
    # scipy _ivp style: at a recorded impact the event function theta is ~0, and the
    # velocity jumps by exactly e (the duplicated time stamp holds both sides).
    r = housner.solve(BLOCK, FREE, theta0=0.5 * BLOCK.alpha, end_time=2.0)
    dup = np.flatnonzero(np.diff(r.time) == 0.0)
    assert dup.size >= 2
    i = int(dup[0])
    assert abs(r.theta[i]) < 1e-9 * BLOCK.alpha
    assert r.theta_dot[i + 1] == pytest.approx(BLOCK.e * r.theta_dot[i], rel=1e-12)
    # overturning: the run stops on |theta| = pi/2
    pulse = OneSinePulse.from_ratios(BLOCK, 10.0, 0.5)
    ro = housner.solve(BLOCK, pulse)
    assert ro.overturned and abs(abs(ro.theta[-1]) - math.pi / 2) < 1e-9


def test_overturning_long_strong_not_short_weak():
    # a long strong pulse (omega_p/p = 0.5, 10 g tan alpha) overturns any block; a short weak
    # one (omega_p/p = 8, 1.5 g tan alpha) only nudges it (its impulse PFA T_p/2 is small)
    strong = housner.solve(BLOCK, OneSinePulse.from_ratios(BLOCK, 10.0, 0.5))
    weak = housner.solve(BLOCK, OneSinePulse.from_ratios(BLOCK, 1.5, 8.0))
    assert strong.verdict == "overturned"
    assert weak.verdict == "safe" and weak.theta_max < 0.5 * BLOCK.alpha


def test_comes_to_rest_and_mirror_symmetry():
    pulse = OneSinePulse.from_ratios(BLOCK, 3.0, 8.0)
    r = housner.solve(BLOCK, pulse)
    assert r.verdict == "safe" and r.theta[-1] == 0.0 and r.theta_dot[-1] == 0.0

    class Mirrored:
        duration = pulse.duration
        pfa = pulse.pfa

        def acceleration(self, t):
            return -pulse.acceleration(t)

        def breakpoints(self):
            return pulse.breakpoints()

    m = housner.solve(BLOCK, Mirrored())
    # the equation is odd in (theta, a): the mirrored pulse gives the mirrored response
    assert m.theta_max == pytest.approx(r.theta_max, rel=1e-9)
    assert np.min(m.theta) == pytest.approx(-np.max(r.theta), rel=1e-9)


def test_peak_tail_gives_the_same_verdict_and_peak():
    # after the pulse the energy only falls, so stopping at the first turning point is exact
    pulse = OneSinePulse.from_ratios(BLOCK, 4.0, 8.0)
    full = housner.solve(BLOCK, pulse)
    short = housner.solve(BLOCK, pulse, tail="peak")
    assert short.verdict == full.verdict == "safe"
    assert short.theta_max == pytest.approx(full.theta_max, rel=1e-12)
    assert short.time[-1] < full.time[-1]


@pytest.mark.parametrize(
    "kwargs, name",
    [({"rtol": -1.0}, "rtol"), ({"method": "Euler"}, "method"), ({"theta0": 2.0}, "theta0"),
     ({"max_impacts": 0}, "max_impacts"), ({"tail": "forever"}, "tail"), ({"bogus": 1}, "bogus"),
     ({"atol": float("nan")}, "atol")],
)
def test_bad_settings_name_the_argument(kwargs, name):
    with pytest.raises((ValueError, TypeError), match=name):
        housner.solve(BLOCK, FREE, **kwargs)


def test_failures_are_reported_not_hidden():
    r = housner.solve(BLOCK, FREE, theta0=0.5 * BLOCK.alpha, end_time=5.0, max_impacts=2)
    assert r.status == "failed" and "max_impacts" in r.reason and r.verdict == "failed"

    class Broken:
        duration = 1.0
        pfa = 1.0

        def acceleration(self, t):
            return np.where(np.asarray(t) > 0.1, np.nan, 0.0)

        def breakpoints(self):
            return np.array([0.0, 1.0])

    b = housner.solve(BLOCK, Broken(), theta0=0.5 * BLOCK.alpha, end_time=1.0)
    assert b.status == "failed" and b.reason and not b.overturned
